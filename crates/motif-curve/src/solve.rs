//! The optimisation as a whole: the dynamic program over all rows (open curves, or the closed
//! solvers of §1.5), and the rounds of repetition control around it (`variety`).

use serde::Serialize;

use crate::closed;
use crate::coarse::{self, CoarseReport};
use rayon::prelude::*;

use crate::cost::{COST_SCALE, CostModel, edge_distance, left_edges, right_edges};
use crate::dp::{self, DpCounters, RowSpec, Solver, path_cost};
use crate::exemplar::Exemplar;
use crate::incremental::{Cache, chain_signatures};
use crate::piece::Position;
use crate::variety::Rule;

/// One solved DP: the position index of every row on the optimal path and its cost.
pub(crate) struct Solution {
    pub path: Vec<usize>,
    /// `Ω` plus the repetition charges of the path.
    pub cost: u64,
    pub row_ms: Vec<f64>,
    pub counters: DpCounters,
    pub closed_certified: Option<bool>,
    pub closed_lower_bound: Option<u64>,
    pub closed_starts_tried: usize,
    pub closed_directly: bool,
    /// The coarse-to-fine solver's figures (with [`Solver::CoarseToFine`]).
    pub coarse: Option<CoarseReport>,
}

/// How the closed solvers run.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Setup {
    pub solver: Solver,
    pub closed: bool,
    pub exact_closed: bool,
    pub closed_max_starts: usize,
    /// The repetition rule (weight 0: none).
    pub rule: Rule,
    /// With the coarse-to-fine solver, also run the exact one for the cost gap.
    pub check_gap: bool,
}

/// Solves `rows` once (closed curves: `rows` ends with the terminal row). The coarse-to-fine
/// solver runs without the cache (its rows are not those of the exact table).
pub(crate) fn solve_once(
    exemplar: &Exemplar,
    model: &CostModel,
    rows: &[RowSpec<'_>],
    setup: Setup,
    cache: Option<&mut Cache>,
    on_row: &mut dyn FnMut(usize),
) -> Solution {
    if setup.solver == Solver::CoarseToFine {
        let factor = coarse::factor_for(rows);
        let (mut solution, figures) = coarse::solve(exemplar, model, rows, setup, factor, on_row);
        solution.coarse = Some(figures);
        return solution;
    }
    if setup.closed {
        let cycle = closed::solve_closed(
            exemplar,
            model,
            rows,
            setup.solver,
            setup.exact_closed,
            setup.closed_max_starts,
            on_row,
        );
        Solution {
            path: cycle.path,
            cost: cycle.cost,
            row_ms: cycle.row_ms,
            counters: cycle.counters,
            closed_certified: cycle.certified,
            closed_lower_bound: cycle.lower_bound,
            closed_starts_tried: cycle.starts_tried,
            closed_directly: cycle.closed_directly,
            coarse: None,
        }
    } else {
        let table = match cache {
            // Open curves reuse the rows of the last run that the edit left as they were.
            Some(cache) => {
                let frames: Vec<_> = rows.iter().map(|row| row.frame).collect();
                let positions: Vec<_> = rows.iter().map(|row| row.positions).collect();
                let chain = chain_signatures(&frames, &positions);
                cache.solve_rows(chain, rows[0].positions.len(), |start, initial| {
                    dp::solve_from(exemplar, model, rows, setup.solver, (start, initial), true, on_row)
                })
            }
            None => dp::solve(exemplar, model, rows, setup.solver, on_row),
        };
        let last = (0..table.last_costs.len()).min_by_key(|&i| (table.last_costs[i], i)).expect("non-empty row");
        Solution {
            path: table.backtrack(last),
            cost: table.last_costs[last],
            row_ms: table.row_ms,
            counters: table.counters,
            closed_certified: None,
            closed_lower_bound: None,
            closed_starts_tried: 0,
            closed_directly: false,
            coarse: None,
        }
    }
}

/// Figures of the repetition control.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct VarietyReport {
    /// `W`, paper units per repeated pair.
    pub weight: f64,
    /// `R`, pieces.
    pub radius: usize,
    /// `E = Ω + W · repeated pairs` of the result (paper units).
    pub energy: f64,
    /// `Ω*`, the unpenalised optimum: no result can have a lower `E` (paper units).
    /// With the coarse-to-fine solver, `Ω*` is the exact solver's optimum when it ran too
    /// (`check_gap`), else the coarse-to-fine `Ω`, which is then no bound.
    pub lower_bound: f64,
    /// `(E − Ω*) / E`: how far above the lower bound the result is at most, as a fraction of `E`
    /// (0: proven optimal).
    pub gap: f64,
    /// Pieces moved by the descent.
    pub descent_moves: usize,
    /// Repeated pairs in the unpenalised optimum.
    pub repeated_pairs_unpenalised: usize,
    /// `E` of the unpenalised optimum (paper units).
    pub energy_unpenalised: f64,
}

/// The result of [`optimise`]: the solution, its repeated pairs and the variety figures.
pub(crate) struct Optimised {
    pub solution: Solution,
    /// `Ω` of the dynamic program's path (before the descent of the repetition control).
    pub dp_cost: u64,
    /// The exact optimum of `Ω`, when the exact solver ran beside the coarse-to-fine one.
    pub exact_optimum: Option<u64>,
    pub repeated_pairs: usize,
    pub distinct_windows: usize,
    pub variety: Option<VarietyReport>,
}

/// Solves `rows` (the exact optimum of `Ω`); with a repetition rule of positive weight, then
/// lowers `E` from there by single-piece descent (see `variety`). `empty[i]` marks pieces left
/// empty (their single position copies nothing).
pub(crate) fn optimise(
    exemplar: &Exemplar,
    model: &CostModel,
    rows: &[RowSpec<'_>],
    setup: Setup,
    empty: &[bool],
    cache: Option<&mut Cache>,
    on_row: &mut dyn FnMut(usize),
) -> Optimised {
    let rule = setup.rule;
    let pieces = empty.len();
    let windows = |path: &[usize]| -> Vec<Option<Position>> {
        (0..pieces).map(|i| (!empty[i]).then(|| rows[i].positions[path[i]])).collect()
    };
    let mut solution = solve_once(exemplar, model, rows, setup, cache, on_row);
    let dp_cost = solution.cost;
    let exact_optimum = (setup.solver == Solver::CoarseToFine && setup.check_gap)
        .then(|| solve_once(exemplar, model, rows, Setup { solver: Solver::Exact, ..setup }, None, &mut |_| {}).cost);
    let first_pairs = rule.repeated_pairs(&windows(&solution.path));
    if rule.weight == 0 {
        return Optimised {
            dp_cost,
            exact_optimum,
            repeated_pairs: first_pairs,
            distinct_windows: rule.distinct_windows(&windows(&solution.path)),
            solution,
            variety: None,
        };
    }
    let lower_bound = exact_optimum.unwrap_or(solution.cost);
    let energy_of = |cost: u64, pairs: usize| cost + rule.weight * pairs as u64;
    let first_energy = energy_of(solution.cost, first_pairs);
    let descent_moves = descend(exemplar, model, rows, rule, empty, &mut solution.path);
    solution.cost = path_cost(exemplar, model, rows, &solution.path);
    let repeated_pairs = rule.repeated_pairs(&windows(&solution.path));
    let energy = energy_of(solution.cost, repeated_pairs);
    let to_paper = |cost: u64| cost as f64 / COST_SCALE;
    let variety = VarietyReport {
        weight: to_paper(rule.weight),
        radius: rule.radius,
        energy: to_paper(energy),
        lower_bound: to_paper(lower_bound),
        gap: if energy == 0 { 0.0 } else { energy.saturating_sub(lower_bound) as f64 / energy as f64 },
        descent_moves,
        repeated_pairs_unpenalised: first_pairs,
        energy_unpenalised: to_paper(first_energy),
    };
    Optimised {
        dp_cost,
        exact_optimum,
        distinct_windows: rule.distinct_windows(&windows(&solution.path)),
        repeated_pairs,
        solution,
        variety: Some(variety),
    }
}

/// Sweeps of the single-piece descent at most.
const DESCENT_SWEEPS: usize = 12;

/// Exact coordinate descent on `E`: piece by piece, the position minimising its two seams plus
/// `W` times the windows it repeats within `R`, all other pieces fixed; a piece moves only when
/// that lowers `E`, so `E` decreases strictly and the descent ends. Returns the number of moves.
fn descend(
    exemplar: &Exemplar,
    model: &CostModel,
    rows: &[RowSpec<'_>],
    rule: Rule,
    empty: &[bool],
    path: &mut [usize],
) -> usize {
    let pieces = empty.len();
    let closed = rule.closed;
    let mut moves = 0;
    let mut current: Vec<Option<Position>> =
        (0..pieces).map(|j| (!empty[j]).then(|| rows[j].positions[path[j]])).collect();
    for _ in 0..DESCENT_SWEEPS {
        let mut moved = false;
        for i in 0..pieces {
            if empty[i] || (i == 0 && rows[0].positions.len() == 1) {
                continue;
            }
            let candidates = rows[i].positions;
            let previous = if i > 0 { Some(i - 1) } else { closed.then(|| pieces - 1) };
            let next = if i + 1 < pieces { Some(i + 1) } else { closed.then_some(0) };
            let left_cost: Vec<u64> = match previous {
                Some(p) => {
                    let rights = right_edges(exemplar, model, rows[p].frame, &[rows[p].positions[path[p]]]);
                    let lefts = left_edges(exemplar, model, candidates, rows[i].frame.samples);
                    (0..candidates.len())
                        .into_par_iter()
                        .map(|u| u64::from(edge_distance(model, &rights, 0, &lefts, u)))
                        .collect()
                }
                None => vec![0; candidates.len()],
            };
            let right_cost: Vec<u64> = match next {
                Some(n) => {
                    let lefts = left_edges(exemplar, model, &[rows[n].positions[path[n]]], rows[n].frame.samples);
                    let rights = right_edges(exemplar, model, rows[i].frame, candidates);
                    (0..candidates.len())
                        .into_par_iter()
                        .map(|u| u64::from(edge_distance(model, &rights, u, &lefts, 0)))
                        .collect()
                }
                None => vec![0; candidates.len()],
            };
            let penalty = rule.penalty(i, &current);
            let total = |u: usize| left_cost[u] + right_cost[u] + penalty.as_ref().map_or(0, |p| p.cost(candidates[u]));
            let best = (0..candidates.len()).min_by_key(|&u| (total(u), u)).expect("a valid position");
            if total(best) < total(path[i]) {
                path[i] = best;
                current[i] = Some(candidates[best]);
                moves += 1;
                moved = true;
            }
        }
        if closed {
            // The terminal row repeats the first piece.
            if path.len() > pieces {
                path[pieces] = path[0];
            }
        }
        if !moved {
            break;
        }
    }
    moves
}
