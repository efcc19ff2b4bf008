//! The coarse-to-fine solver (not in the paper; issue 34): the dynamic program at a reduced
//! resolution, then the exact one in bands of positions around the coarse optimum.
//!
//! 1. **Coarse problem.** Each row's valid positions are grouped into cells of `f × f` exemplar
//!    pixels (grids shifted along the rows so that the exemplar's continuation maps cells onto
//!    cells), and one position stands for each cell: its corner where that is valid. Its edges
//!    are the representative's with every run of `f` samples averaged
//!    ([`EdgeSet::downsampled`]). With `V` positions and `C` samples a row has about `V²/f⁴`
//!    pairs of `C/f` samples. (Averaging the edges of a cell's columns as well lost 16 % of the
//!    optimum on the dense chain at `f = 2`, where single representatives lost nothing.)
//! 2. **Forward and backward tables** `P` and `Q` over the cells (the exact solver's row update,
//!    both ways, as `dp::solve_backward`): `P + Q` of a cell is the cost of the cheapest coarse
//!    path through it.
//! 3. **Bands.** In each row the cells of lowest `P + Q` are kept, with their neighbours within a
//!    radius ([`BAND_SHAPES`]); the band is every valid position in them (the whole row if that
//!    were empty). Row 0 and a closed curve's terminal row keep the union of their cells, so they
//!    keep the same positions, as the closed solvers need.
//! 4. **Refinement.** The exact solver (open or closed, `solve::solve_once`) over the bands at full
//!    resolution; its path is mapped back to the rows' own indices.
//!
//! The result is a valid path, so its cost is at least the exact optimum; it is the exact optimum
//! whenever the bands hold an optimal path. The factor is [`factor_for`]'s; at `f = 1` the exact
//! solver runs on the whole rows. Every figure is an integer sum and every choice is
//! ordered by index, so the result does not depend on the thread count.

use std::collections::{HashMap, HashSet};

use motif_core::timing::{Clock, elapsed_ms};
use serde::Serialize;

use crate::cost::{CostModel, EdgeSet, left_edges, right_edges};
use crate::dp::{DpCounters, RowSpec, Seeds, Solver, distinct_row, same_left_edges, same_right_edges};
use crate::exemplar::Exemplar;
use crate::piece::Position;
use crate::solve::{Setup, Solution, solve_once};

/// Cells per row the factor aims at (mean over rows).
pub(crate) const TARGET_CELLS: usize = 3000;
/// Largest cell side.
const MAX_FACTOR: usize = 4;
/// Fewest samples of a coarse edge (one comparison chunk).
const MIN_COARSE_SAMPLES: usize = 16;
/// Cells of lowest `P + Q` kept per row and the radius of neighbouring cells added around each
/// (Chebyshev distance), for cells of side 2 and of side 4. Measured on the hard speed cases: on
/// the dense chain (cells of 2), 16 or 48 cells with their neighbours left a gap of 7 %, 96 none,
/// and 96 or 192 cells without neighbours 7 %; on the 600 × 250 chain (cells of 4), 24 cells with
/// neighbours left 0.06 % at 106 ms per row, 48 cells without neighbours none at 21 ms.
const BAND_SHAPES: [(usize, i32); 2] = [(96, 1), (48, 0)];

/// Figures of a coarse-to-fine solve.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CoarseReport {
    /// `f`: the cell side in exemplar pixels and the samples averaged per coarse sample (1: the
    /// problem was small enough for the exact solver on whole rows).
    pub factor: usize,
    /// Mean valid positions per row.
    pub positions_per_row: f64,
    /// Mean coarse cells per row.
    pub cells_per_row: f64,
    /// Mean positions per row of the bands the exact solver refined.
    pub band_positions_per_row: f64,
    /// Milliseconds of the coarse forward and backward tables.
    pub coarse_ms: f64,
    /// Milliseconds of the refinement over the bands.
    pub fine_ms: f64,
}

/// One row of the coarse problem: its cells (cell coordinates) and their representatives.
#[derive(Debug, Clone, PartialEq)]
struct CoarseRow {
    cells: Vec<Position>,
    representatives: Vec<Position>,
    /// Where the cell grid starts (`0..factor` on both axes).
    phase: [i32; 2],
}

/// The cell of position `p` for cells of side `factor` whose grid starts at `phase`.
fn cell_of(p: Position, factor: i32, phase: [i32; 2]) -> Position {
    [(p[0] - phase[0]).div_euclid(factor), (p[1] - phase[1]).div_euclid(factor)]
}

impl CoarseRow {
    /// The cells of `positions` (grid starting at `phase`) in order of first appearance, each
    /// represented by its corner position where that is valid, else by its first.
    fn new(positions: &[Position], factor: i32, phase: [i32; 2]) -> Self {
        let mut index: HashMap<Position, usize> = HashMap::with_capacity(positions.len());
        let mut row = Self { cells: Vec::new(), representatives: Vec::new(), phase };
        let at_corner =
            |p: Position| cell_of(p, factor, phase).map(|c| c * factor) == [p[0] - phase[0], p[1] - phase[1]];
        for &p in positions {
            let cell = cell_of(p, factor, phase);
            match index.get(&cell) {
                Some(&k) => {
                    if at_corner(p) {
                        row.representatives[k] = p;
                    }
                }
                None => {
                    index.insert(cell, row.cells.len());
                    row.cells.push(cell);
                    row.representatives.push(p);
                }
            }
        }
        row
    }
}

/// The cell side for `rows`: the smallest of 1, 2 and 4 that leaves at most [`TARGET_CELLS`]
/// cells per row on average, and at least 16 samples per coarse edge (3 lost 16 % of the optimum
/// on the dense chain, where 2 and 4 lost nothing).
pub(crate) fn factor_for(rows: &[RowSpec<'_>]) -> usize {
    let mean = rows.iter().map(|row| row.positions.len()).sum::<usize>() / rows.len().max(1);
    let samples = rows.iter().map(|row| row.frame.samples).min().unwrap_or(0);
    let mut factor = 1;
    while factor < MAX_FACTOR && mean / (factor * factor) > TARGET_CELLS && samples / (2 * factor) >= MIN_COARSE_SAMPLES
    {
        factor *= 2;
    }
    factor
}

/// Cells kept per row and the radius of neighbours added, for cells of side `factor` (see
/// [`BAND_SHAPES`]).
pub(crate) fn band_shape(factor: usize) -> (usize, i32) {
    if factor <= 2 { BAND_SHAPES[0] } else { BAND_SHAPES[1] }
}

/// Solves `rows` coarse to fine with cells of side `factor` (at 1, the exact solver on whole
/// rows); `setup` says whether the curve is closed. Returns the solution, in the rows' own
/// indices, and the figures.
pub(crate) fn solve(
    exemplar: &Exemplar,
    model: &CostModel,
    rows: &[RowSpec<'_>],
    setup: Setup,
    factor: usize,
    on_row: &mut dyn FnMut(usize),
) -> (Solution, CoarseReport) {
    let exact = Setup { solver: Solver::Exact, ..setup };
    let positions_per_row = rows.iter().map(|row| row.positions.len()).sum::<usize>() as f64 / rows.len() as f64;
    let mut report = CoarseReport {
        factor,
        positions_per_row,
        cells_per_row: positions_per_row,
        band_positions_per_row: positions_per_row,
        coarse_ms: 0.0,
        fine_ms: 0.0,
    };
    if factor <= 1 || rows.len() < 2 {
        let clock = Clock::now();
        let solution = solve_once(exemplar, model, rows, exact, None, on_row);
        report.fine_ms = elapsed_ms(clock);
        return (solution, report);
    }
    let clock = Clock::now();
    let coarse = coarse_rows(rows, factor as i32);
    let problem = Problem { exemplar, model, rows, coarse: &coarse, factor };
    let (forward, forward_ms, forward_counters) = problem.forward();
    let (backward, backward_ms, backward_counters) = problem.backward();
    let bands = problem.bands(&forward, &backward, setup.closed);
    report.coarse_ms = elapsed_ms(clock);
    report.cells_per_row = coarse.iter().map(|row| row.cells.len()).sum::<usize>() as f64 / rows.len() as f64;
    report.band_positions_per_row = bands.iter().map(Vec::len).sum::<usize>() as f64 / rows.len() as f64;

    let clock = Clock::now();
    let band_positions: Vec<Vec<Position>> =
        bands.iter().zip(rows).map(|(band, row)| band.iter().map(|&i| row.positions[i]).collect()).collect();
    let fine_rows: Vec<RowSpec<'_>> =
        rows.iter().zip(&band_positions).map(|(row, positions)| RowSpec { frame: row.frame, positions }).collect();
    let mut solution = solve_once(exemplar, model, &fine_rows, exact, None, on_row);
    report.fine_ms = elapsed_ms(clock);
    solution.path = solution.path.iter().enumerate().map(|(r, &i)| bands[r][i]).collect();
    solution.counters = solution.counters.plus(forward_counters).plus(backward_counters);
    // A row's time is its coarse forward and backward updates and its refinement (rows line up
    // for open curves; a closed curve's passes are listed after the coarse rows).
    let coarse_row_ms: Vec<f64> = forward_ms.iter().zip(backward_ms.iter().rev()).map(|(a, b)| a + b).collect();
    solution.row_ms = if solution.row_ms.len() == coarse_row_ms.len() {
        solution.row_ms.iter().zip(&coarse_row_ms).map(|(fine, coarse)| fine + coarse).collect()
    } else {
        coarse_row_ms.into_iter().chain(solution.row_ms).collect()
    };
    (solution, report)
}

/// The coarse rows. Row `r`'s cell grid starts at `phase_r`, the sum of the exemplar shifts `t`
/// from one piece to the next (the rounded top-right corners) over the rows before it, modulo the
/// factor: the cell continuing a cell (its columns moved by `t`) is then a whole cell of the next
/// row, so the coarse problem sees the exemplar continue at no cost as the fine one does. Rows
/// with the same positions and phase share their cells.
fn coarse_rows(rows: &[RowSpec<'_>], factor: i32) -> Vec<CoarseRow> {
    let mut out: Vec<CoarseRow> = Vec::with_capacity(rows.len());
    let mut phases: Vec<[i32; 2]> = Vec::with_capacity(rows.len());
    let mut phase = [0, 0];
    for (r, row) in rows.iter().enumerate() {
        if r > 0 {
            let top_right = rows[r - 1].frame.top_right;
            let shift = [top_right.x.round() as i32, top_right.y.round() as i32];
            phase = [(phase[0] + shift[0]).rem_euclid(factor), (phase[1] + shift[1]).rem_euclid(factor)];
        }
        let earlier = (0..r).rev().take(4).find(|&k| phases[k] == phase && rows[k].positions == row.positions);
        let next = match earlier {
            Some(k) => out[k].clone(),
            None => CoarseRow::new(row.positions, factor, phase),
        };
        out.push(next);
        phases.push(phase);
    }
    out
}

/// What the coarse tables share.
struct Problem<'a> {
    exemplar: &'a Exemplar,
    model: &'a CostModel,
    rows: &'a [RowSpec<'a>],
    coarse: &'a [CoarseRow],
    factor: usize,
}

/// Edges kept between rows: `(row, edges)` of the last row extracted.
type Kept = Option<(usize, EdgeSet)>;

impl Problem<'_> {
    /// Whether rows `a` and `b` have the same cell grid (rows with the same positions may not).
    fn same_cells(&self, a: usize, b: usize) -> bool {
        self.coarse[a].phase == self.coarse[b].phase
    }

    /// The coarse right edges of row `r`, reusing `kept` when its row has the same ones.
    fn rights<'k>(&self, kept: &'k mut Kept, r: usize) -> &'k EdgeSet {
        let rows = self.rows;
        if !kept.as_ref().is_some_and(|(row, _)| self.same_cells(*row, r) && same_right_edges(&rows[*row], &rows[r])) {
            let full = right_edges(self.exemplar, self.model, rows[r].frame, &self.coarse[r].representatives);
            *kept = Some((r, full.downsampled(self.model, self.factor)));
        }
        &kept.as_ref().expect("set above").1
    }

    /// The coarse left edges of row `r`, reusing `kept` when its row has the same ones.
    fn lefts<'k>(&self, kept: &'k mut Kept, r: usize) -> &'k EdgeSet {
        let rows = self.rows;
        if !kept.as_ref().is_some_and(|(row, _)| self.same_cells(*row, r) && same_left_edges(&rows[*row], &rows[r])) {
            let full = left_edges(self.exemplar, self.model, &self.coarse[r].representatives, rows[r].frame.samples);
            *kept = Some((r, full.downsampled(self.model, self.factor)));
        }
        &kept.as_ref().expect("set above").1
    }

    /// The exemplar shift `t` from a piece of row `r` to the one continuing it, in cells: a
    /// representative of row `r + 1` continues the one of its cell less this (see [`coarse_rows`]).
    fn shift(&self, r: usize) -> [i32; 2] {
        let top_right = self.rows[r].frame.top_right;
        let t = [top_right.x.round() as i32, top_right.y.round() as i32];
        let (from, to) = (self.coarse[r].phase, self.coarse[r + 1].phase);
        let f = self.factor as i32;
        [(t[0] + from[0] - to[0]).div_euclid(f), (t[1] + from[1] - to[1]).div_euclid(f)]
    }

    /// `P` of every row (row 0 costs 0), with each row's milliseconds and the work counters.
    fn forward(&self) -> (Vec<Vec<u64>>, Vec<f64>, DpCounters) {
        let (coarse, rows) = (self.coarse, self.rows);
        let mut tables = vec![vec![0_u64; coarse[0].cells.len()]];
        let (mut rights, mut lefts): (Kept, Kept) = (None, None);
        let (mut row_ms, mut counters) = (Vec::with_capacity(rows.len()), DpCounters::default());
        for r in 1..rows.len() {
            let clock = Clock::now();
            let shift = self.shift(r - 1);
            let (before, current) = (&coarse[r - 1].cells, &coarse[r].cells);
            let (costs, _, row_counters) = distinct_row(
                self.model,
                &tables[r - 1],
                self.rights(&mut rights, r - 1),
                self.lefts(&mut lefts, r),
                |predecessors, successors| Seeds::new(before, current, shift, predecessors, successors),
            );
            tables.push(costs);
            counters = counters.plus(row_counters);
            row_ms.push(elapsed_ms(clock));
        }
        (tables, row_ms, counters)
    }

    /// `Q` of every row (the last costs 0): the next row's left edges play the predecessors and
    /// this row's right edges the positions (`D` is symmetric); the seeds look for the position
    /// that this one continues into. Milliseconds are listed from the last row back.
    fn backward(&self) -> (Vec<Vec<u64>>, Vec<f64>, DpCounters) {
        let (coarse, rows) = (self.coarse, self.rows);
        let last = rows.len() - 1;
        let mut tables = vec![Vec::new(); rows.len()];
        tables[last] = vec![0_u64; coarse[last].cells.len()];
        let (mut rights, mut lefts): (Kept, Kept) = (None, None);
        let (mut row_ms, mut counters) = (Vec::with_capacity(rows.len()), DpCounters::default());
        for r in (0..last).rev() {
            let clock = Clock::now();
            let [x, y] = self.shift(r);
            let (after, current) = (&coarse[r + 1].cells, &coarse[r].cells);
            let (costs, _, row_counters) = distinct_row(
                self.model,
                &tables[r + 1],
                self.lefts(&mut lefts, r + 1),
                self.rights(&mut rights, r),
                |predecessors, successors| Seeds::new(after, current, [-x, -y], predecessors, successors),
            );
            tables[r] = costs;
            counters = counters.plus(row_counters);
            row_ms.push(elapsed_ms(clock));
        }
        (tables, row_ms, counters)
    }

    /// The band of every row: indices into the row's positions, ascending (see the module
    /// comment).
    fn bands(&self, forward: &[Vec<u64>], backward: &[Vec<u64>], closed: bool) -> Vec<Vec<usize>> {
        let mut bands: Vec<Vec<usize>> = (0..self.rows.len())
            .map(|r| {
                let coarse = &self.coarse[r];
                let through = |c: usize| forward[r][c].saturating_add(backward[r][c]);
                let mut order: Vec<(u64, usize)> = (0..coarse.cells.len()).map(|c| (through(c), c)).collect();
                order.sort_unstable();
                let (keep, radius) = band_shape(self.factor);
                let kept: Vec<Position> = order.iter().take(keep).map(|&(_, c)| coarse.cells[c]).collect();
                band(self.rows[r].positions, &kept, [self.factor as i32, radius], coarse.phase)
            })
            .collect();
        if closed {
            // Row 0 and the terminal row have the same positions (in grids of different phases):
            // both take the union of their bands.
            let last = bands.len() - 1;
            let mut union: Vec<usize> = bands[0].iter().chain(&bands[last]).copied().collect();
            union.sort_unstable();
            union.dedup();
            bands[0].clone_from(&union);
            bands[last] = union;
        }
        bands
    }
}

/// The indices of `positions` whose cell (side `factor`, grid starting at `phase`) is within
/// `radius` cells of one of `cells`; every index when none is.
fn band(positions: &[Position], cells: &[Position], [factor, radius]: [i32; 2], phase: [i32; 2]) -> Vec<usize> {
    let mut near: HashSet<Position> = HashSet::new();
    for &[x, y] in cells {
        for dy in -radius..=radius {
            for dx in -radius..=radius {
                near.insert([x + dx, y + dy]);
            }
        }
    }
    let band: Vec<usize> =
        (0..positions.len()).filter(|&i| near.contains(&cell_of(positions[i], factor, phase))).collect();
    if band.is_empty() { (0..positions.len()).collect() } else { band }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_are_represented_by_their_corner_or_their_first_position() {
        let positions = [[0, 0], [1, 0], [2, 0], [3, 0], [0, 1], [3, 1], [-1, -1]];
        let row = CoarseRow::new(&positions, 2, [0, 0]);
        assert_eq!(row.cells, vec![[0, 0], [1, 0], [-1, -1]]);
        assert_eq!(row.representatives, vec![[0, 0], [2, 0], [-1, -1]]);
        // A grid starting at (1, 1): cell (0, 0) spans x 1..3, y 1..3, and its corner (1, 1) is not valid.
        let row = CoarseRow::new(&positions, 2, [1, 1]);
        assert_eq!(row.cells, vec![[-1, -1], [0, -1], [1, -1], [-1, 0], [1, 0]]);
        assert_eq!(row.representatives, vec![[-1, -1], [1, 0], [3, 0], [0, 1], [3, 1]]);
    }

    #[test]
    fn a_band_is_never_empty() {
        let positions = [[0, 0], [5, 5], [9, 9]];
        assert_eq!(band(&positions, &[[2, 2]], [2, 1], [0, 0]), vec![1]);
        assert_eq!(band(&positions, &[[2, 2]], [2, 0], [1, 1]), vec![1]);
        assert_eq!(band(&positions, &[[40, 40]], [2, 1], [0, 0]), vec![0, 1, 2], "no position near: the whole row");
        assert_eq!(band(&positions, &[], [2, 1], [1, 1]), vec![0, 1, 2]);
    }
}
