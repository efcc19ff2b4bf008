//! Closed curves (§1.5).
//!
//! A closed curve is cut at its start and a *terminal* row is added after the last piece: it holds
//! the positions of the first piece again, and its left edges are those of the first piece, so a
//! path through the table pays for the seam back to the start. Only paths whose terminal position
//! equals their first position are cycles.
//!
//! - Approximate (the paper's choice, after Lasram and Lefebvre 2012): one unconstrained DP, then backtrack from
//!   every terminal position and keep the cheapest path that closes. If none closes, the start of
//!   the cheapest terminal is pinned and the DP rerun, which always yields a cycle.
//! - Exact: branch and bound over start positions. In the unconstrained DP, `P[N, s]` is the
//!   cheapest path from *any* start to terminal `s`, and in the backward table `Q[0, s]` is the
//!   cheapest path from `s` to *any* terminal; both bound the best cycle through `s` from below.
//!   Starts are tried in increasing bound with a DP pinned at both ends (start = terminal = `s`);
//!   once the next bound is not below the best cycle found, no untried start can do better and
//!   the optimum is certified. Inside a pinned DP, a position whose cost so far plus its backward
//!   cost `Q` reaches the best cycle found cannot lead to a better one and is dropped, which keeps
//!   the pinned DPs small. A budget of starts bounds the work; when it runs out the result is the
//!   best cycle found and is reported as not certified, with the bound of the first start left
//!   untried: no cycle costs less, so the gap to the optimum is at most the difference.

use motif_core::timing::{Clock, elapsed_ms};

use crate::cost::CostModel;
use crate::dp::{DpCounters, DpTable, RowSpec, Solver, solve, solve_backward, step};
use crate::exemplar::Exemplar;
use crate::piece::Position;

/// The chosen cycle.
#[derive(Debug, Clone)]
pub(crate) struct Cycle {
    /// Position of each row's piece in the full candidate lists (terminal row included).
    pub path: Vec<usize>,
    /// `Ω` of the cycle.
    pub cost: u64,
    /// For exact mode: whether the optimum was proven.
    pub certified: Option<bool>,
    /// For exact mode: a lower bound of every cycle's `Ω` (the cost itself when certified; else
    /// the smallest bound of the starts left untried), so that the gap to the optimum is known.
    pub lower_bound: Option<u64>,
    /// Start positions evaluated with a pinned DP.
    pub starts_tried: usize,
    /// True when the single-DP approximation found a closing path directly.
    pub closed_directly: bool,
    /// Row timings and counters of every DP run.
    pub row_ms: Vec<f64>,
    /// Work counters of every DP run.
    pub counters: DpCounters,
}

/// The cheapest cycle in an unconstrained table, if any path closes.
fn cheapest_closing(table: &DpTable) -> Option<(u64, usize)> {
    (0..table.last_costs.len()).filter(|&t| table.start_of(t) == t).map(|t| (table.last_costs[t], t)).min()
}

/// What every DP of a closed curve shares.
#[derive(Clone, Copy)]
struct ClosedSolver<'a> {
    exemplar: &'a Exemplar,
    model: &'a CostModel,
    solver: Solver,
}

/// Row timings and work counters accumulated over several DPs.
struct Work {
    row_ms: Vec<f64>,
    counters: DpCounters,
}

/// The cheapest cycle through `start` (index into row 0's positions) that costs less than
/// `upper`, by a DP pinned at both ends to `start`. Positions whose cost so far plus `remaining`
/// (a lower bound of the cost still to come: the backward table, or zeros) reaches `upper` can
/// not lead to a better cycle and are dropped from the table, so that a pinned DP around a good
/// incumbent touches only a narrow band of positions. Returns the cost and the path in full-list
/// indices, or `None` when no cycle through `start` beats `upper`.
fn pinned_cycle(
    solver: &ClosedSolver<'_>,
    rows: &[RowSpec<'_>],
    start: usize,
    remaining: Option<&[Vec<u64>]>,
    upper: u64,
    work: &mut Work,
) -> Option<(u64, Vec<usize>)> {
    let ClosedSolver { exemplar, model, solver } = *solver;
    let last = rows.len() - 1;
    let mut alive: Vec<Vec<usize>> = vec![vec![start]];
    let mut alive_positions: Vec<Vec<Position>> = vec![vec![rows[0].positions[start]]];
    let mut predecessors: Vec<Vec<u32>> = vec![Vec::new()];
    let mut costs = vec![0_u64];
    for r in 1..rows.len() {
        let clock = Clock::now();
        let candidates: Vec<usize> = if r == last { vec![start] } else { (0..rows[r].positions.len()).collect() };
        let candidate_positions: Vec<Position> = candidates.iter().map(|&i| rows[r].positions[i]).collect();
        let before = RowSpec { frame: rows[r - 1].frame, positions: &alive_positions[r - 1] };
        let current = RowSpec { frame: rows[r].frame, positions: &candidate_positions };
        let (next, row_predecessors, row_counters) = step(exemplar, model, &before, &costs, &current, solver);
        work.counters = work.counters.plus(row_counters);
        let keep: Vec<usize> = (0..candidates.len())
            .filter(|&j| {
                let rest = remaining.map_or(0, |table| table[r][candidates[j]]);
                next[j].saturating_add(rest) < upper
            })
            .collect();
        work.row_ms.push(elapsed_ms(clock));
        if keep.is_empty() {
            return None;
        }
        alive.push(keep.iter().map(|&j| candidates[j]).collect());
        alive_positions.push(keep.iter().map(|&j| candidate_positions[j]).collect());
        predecessors.push(keep.iter().map(|&j| row_predecessors[j]).collect());
        costs = keep.iter().map(|&j| next[j]).collect();
    }
    let mut path = vec![0_usize; rows.len()];
    let mut index = 0_usize;
    for r in (0..rows.len()).rev() {
        path[r] = alive[r][index];
        if r > 0 {
            index = predecessors[r][index] as usize;
        }
    }
    Some((costs[0], path))
}

/// Solves a closed curve. `rows` ends with the terminal row (same positions as row 0).
///
/// A cycle may be cut at any piece, and the exact search pins one start per position of the row
/// it is cut at: the exact mode cuts it at the row with the fewest positions (a piece left empty
/// has one, and one pinned DP then certifies the optimum), solves the rotated rows and turns the
/// path back. The approximate mode keeps the paper's cut at the first piece.
pub(crate) fn solve_closed(
    exemplar: &Exemplar,
    model: &CostModel,
    rows: &[RowSpec<'_>],
    solver: Solver,
    exact: bool,
    max_starts: usize,
    on_row: &mut dyn FnMut(usize),
) -> Cycle {
    let context = ClosedSolver { exemplar, model, solver };
    let pieces = rows.len() - 1;
    let cut = if exact { (0..pieces).min_by_key(|&r| (rows[r].positions.len(), r)).unwrap_or(0) } else { 0 };
    if cut == 0 {
        return solve_cut(&context, rows, exact, max_starts, on_row);
    }
    let rotated: Vec<RowSpec<'_>> = (0..=pieces).map(|r| rows[(r + cut) % pieces]).collect();
    let mut cycle = solve_cut(&context, &rotated, exact, max_starts, on_row);
    let mut path: Vec<usize> = (0..pieces).map(|r| cycle.path[(r + pieces - cut) % pieces]).collect();
    path.push(path[0]);
    cycle.path = path;
    cycle
}

/// [`solve_closed`] with the cycle cut at row 0.
fn solve_cut(
    context: &ClosedSolver<'_>,
    rows: &[RowSpec<'_>],
    exact: bool,
    max_starts: usize,
    on_row: &mut dyn FnMut(usize),
) -> Cycle {
    let &ClosedSolver { exemplar, model, solver } = context;
    let table = solve(exemplar, model, rows, solver, on_row);
    let mut work = Work { row_ms: table.row_ms.clone(), counters: table.counters };
    let mut starts_tried = 0;
    let closing = cheapest_closing(&table);
    let (mut best_cost, mut best_path) = match closing {
        Some((cost, terminal)) => (cost, table.backtrack(terminal)),
        None => {
            let terminal =
                (0..table.last_costs.len()).min_by_key(|&t| (table.last_costs[t], t)).expect("non-empty row");
            starts_tried += 1;
            pinned_cycle(context, rows, table.start_of(terminal), None, u64::MAX, &mut work)
                .expect("an unbounded pinned DP always closes")
        }
    };
    let mut certified = None;
    let mut lower_bound = None;
    if exact {
        // Q[0][s]: the cheapest path leaving s, also a lower bound of any cycle through s; and
        // the backward table prunes the pinned DPs. The reference solver keeps plain DPs.
        let backward = (solver == Solver::Exact).then(|| solve_backward(exemplar, model, rows));
        let bound = |s: usize| {
            let leaving = backward.as_ref().map_or(0, |q| q[0][s]);
            table.last_costs[s].max(leaving)
        };
        let mut candidates: Vec<usize> = (0..table.last_costs.len()).collect();
        candidates.sort_unstable_by_key(|&s| (bound(s), s));
        let mut proven = true;
        let mut untried_bound = best_cost;
        for &start in &candidates {
            if bound(start) >= best_cost {
                break;
            }
            if starts_tried >= max_starts {
                // Starts are sorted by bound: no untried one has a cycle cheaper than this one's.
                proven = false;
                untried_bound = bound(start);
                break;
            }
            starts_tried += 1;
            if let Some((cost, path)) = pinned_cycle(context, rows, start, backward.as_deref(), best_cost, &mut work)
                && cost < best_cost
            {
                best_cost = cost;
                best_path = path;
            }
        }
        certified = Some(proven);
        lower_bound = Some(untried_bound.min(best_cost));
    }
    Cycle {
        path: best_path,
        cost: best_cost,
        certified,
        lower_bound,
        starts_tried,
        closed_directly: closing.is_some(),
        row_ms: work.row_ms,
        counters: work.counters,
    }
}
