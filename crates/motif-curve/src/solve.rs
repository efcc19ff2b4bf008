//! The optimisation as a whole: the dynamic program over all rows (open curves, or the closed
//! solvers of §1.5), and the rounds of repetition control around it (`variety`).

use serde::Serialize;

use crate::closed;
use crate::cost::{COST_SCALE, CostModel};
use crate::dp::{self, DpCounters, RowSpec, Solver};
use crate::exemplar::Exemplar;
use crate::piece::Position;
use crate::variety::{self, Penalty, Rule};

/// One solved DP: the position index of every row on the optimal path and its cost.
pub(crate) struct Solution {
    pub path: Vec<usize>,
    /// `Ω` plus the repetition charges of the path.
    pub cost: u64,
    pub row_ms: Vec<f64>,
    pub counters: DpCounters,
    pub closed_certified: Option<bool>,
    pub closed_starts_tried: usize,
    pub closed_directly: bool,
}

/// How the closed solvers run.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Setup {
    pub solver: Solver,
    pub closed: bool,
    pub exact_closed: bool,
    pub closed_max_starts: usize,
}

/// Solves `rows` once (closed curves: `rows` ends with the terminal row).
pub(crate) fn solve_once(
    exemplar: &Exemplar,
    model: &CostModel,
    rows: &[RowSpec<'_>],
    setup: Setup,
    on_row: &mut dyn FnMut(usize),
) -> Solution {
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
            closed_starts_tried: cycle.starts_tried,
            closed_directly: cycle.closed_directly,
        }
    } else {
        let table = dp::solve(exemplar, model, rows, setup.solver, on_row);
        let last = (0..table.last_costs.len()).min_by_key(|&i| (table.last_costs[i], i)).expect("non-empty row");
        Solution {
            path: table.backtrack(last),
            cost: table.last_costs[last],
            row_ms: table.row_ms,
            counters: table.counters,
            closed_certified: None,
            closed_starts_tried: 0,
            closed_directly: false,
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
    /// DP solves run (the unpenalised one included).
    pub solves: usize,
    /// `E = Ω + W · repeated pairs` of the result (paper units).
    pub energy: f64,
    /// `Ω*`, the unpenalised optimum: no result can have a lower `E` (paper units).
    pub lower_bound: f64,
    /// `(E − Ω*) / E`: how far above the lower bound the result is at most, as a fraction of `E`
    /// (0: proven optimal).
    pub gap: f64,
    /// Repeated pairs in the unpenalised optimum.
    pub repeated_pairs_unpenalised: usize,
    /// `E` of the unpenalised optimum (paper units).
    pub energy_unpenalised: f64,
}

/// The result of [`optimise`]: the solution, its repeated pairs and the variety figures.
pub(crate) struct Optimised {
    pub solution: Solution,
    pub repeated_pairs: usize,
    pub distinct_windows: usize,
    pub variety: Option<VarietyReport>,
}

/// Solves `rows`; with a repetition `rule`, re-solves in rounds with the charges of the current
/// path and keeps the path of lowest penalised energy. `empty[i]` marks pieces left empty (their
/// single position copies nothing).
pub(crate) fn optimise(
    exemplar: &Exemplar,
    model: &CostModel,
    rows: &[RowSpec<'_>],
    setup: Setup,
    rule: Rule,
    empty: &[bool],
    on_row: &mut dyn FnMut(usize),
) -> Optimised {
    let pieces = empty.len();
    let windows = |path: &[usize]| -> Vec<Option<Position>> {
        (0..pieces).map(|i| (!empty[i]).then(|| rows[i].positions[path[i]])).collect()
    };
    let first = solve_once(exemplar, model, rows, setup, on_row);
    let first_windows = windows(&first.path);
    let first_pairs = rule.repeated_pairs(&first_windows);
    if rule.weight == 0 {
        return Optimised {
            repeated_pairs: first_pairs,
            distinct_windows: rule.distinct_windows(&first_windows),
            solution: first,
            variety: None,
        };
    }
    let lower_bound = first.cost;
    let energy_of = |cost: u64, pairs: usize| cost + rule.weight * pairs as u64;
    let first_energy = energy_of(first.cost, first_pairs);
    let (mut best, mut best_energy, mut best_pairs) = (first, first_energy, first_pairs);
    let mut current = windows(&best.path);
    let mut row_ms = best.row_ms.clone();
    let mut counters = best.counters;
    let mut solves = 1;
    for fraction in variety::ROUND_WEIGHTS {
        let penalties: Vec<Option<Penalty>> = rule.penalties(&current, fraction);
        let charged: Vec<RowSpec<'_>> = rows
            .iter()
            .enumerate()
            .map(|(i, row)| RowSpec { penalty: penalties.get(i).and_then(Option::as_ref), ..*row })
            .collect();
        let solution = solve_once(exemplar, model, &charged, setup, &mut |_| {});
        solves += 1;
        row_ms.extend_from_slice(&solution.row_ms);
        counters = counters.plus(solution.counters);
        let charges: u64 = (0..pieces).map(|i| charged[i].charge(solution.path[i])).sum();
        let seams = solution.cost - charges;
        let next = windows(&solution.path);
        let pairs = rule.repeated_pairs(&next);
        let energy = energy_of(seams, pairs);
        let settled = next == current && fraction == 1.0;
        if energy < best_energy {
            best_energy = energy;
            best_pairs = pairs;
            best = Solution { cost: seams, ..solution };
        }
        if settled {
            break;
        }
        current = next;
    }
    let distinct_windows = rule.distinct_windows(&windows(&best.path));
    let to_paper = |cost: u64| cost as f64 / COST_SCALE;
    let variety = VarietyReport {
        weight: to_paper(rule.weight),
        radius: rule.radius,
        solves,
        energy: to_paper(best_energy),
        lower_bound: to_paper(lower_bound),
        gap: if best_energy == 0 { 0.0 } else { (best_energy - lower_bound) as f64 / best_energy as f64 },
        repeated_pairs_unpenalised: first_pairs,
        energy_unpenalised: to_paper(first_energy),
    };
    best.row_ms = row_ms;
    best.counters = counters;
    Optimised { solution: best, repeated_pairs: best_pairs, distinct_windows, variety: Some(variety) }
}
