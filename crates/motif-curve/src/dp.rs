//! The dynamic program over valid positions (§1.4, §2), with two solvers and a brute-force check.
//!
//! `P[i, u] = min_v P[i−1, v] + D(v + R_{i−1}, u + L_i)` over valid `u` of row `i` and valid `v`
//! of row `i−1`; `P[0, u] = 0` (the first piece is unconstrained unless pinned). Both solvers
//! work on compacted valid positions (the paper's `compactValidPositions`).
//!
//! - [`Solver::Reference`]: the plain `O(V²C)` loop of Eq. 1, every pair compared in full.
//! - [`Solver::Exact`]: the same optimum, found faster, without ever skipping a predecessor that
//!   could win. Identical edges are merged first (periodic exemplars and empty regions repeat
//!   columns exactly: the generated 199×82 chain has 5 000 positions but about 1 100 distinct right
//!   edges and 550 distinct left edges); only the cheapest of identical predecessors can win, and
//!   identical successors share their answer. The distinct predecessors go into a k-d tree over
//!   their alpha block sums whose nodes know their lowest `P`; since `D ≥ 8γ·|Δalpha|/255` per
//!   sample and block sums only shrink the alpha L1 distance, a node's box distance to `u` bounds
//!   `D` for all its predecessors. For each `u`, a few likely predecessors are tried first (the one
//!   continuing the exemplar, the best one of the neighbouring positions, the cheapest overall) so
//!   that the best total is tight early; then the tree is searched branch-and-bound, nearer child
//!   first, dropping nodes whose lowest `P` plus bound cannot win. Each remaining pair passes
//!   through the block-sum profile bounds and the solid-vs-clear mask bound (see `cost`) before its
//!   pixels are read, and the column comparison runs in chunks of 16 samples and exits as soon as
//!   the partial sum is too large. Ties are broken by the smaller predecessor index in both
//!   solvers, so they return the same path.
//!
//! Each `u` is independent, so rows are computed in parallel with rayon; every figure is an
//! integer sum, so results do not depend on the thread count.

use motif_core::timing::{Clock, elapsed_ms};
use rayon::prelude::*;
use serde::Serialize;

use crate::cost::{CostModel, EdgeSet, edge_distance, left_edges, right_edges};
use crate::exemplar::Exemplar;
use crate::piece::{PieceFrame, Position};
use crate::profile_tree::exact_row;

/// Which dynamic-programming solver to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Solver {
    /// Merged identical edges, branch-and-bound over a profile tree, lower bounds and early
    /// exit; exact optimum.
    Exact,
    /// The plain `O(V²C)` dynamic program.
    Reference,
    /// Coarse to fine (not in the paper): the DP on every `f`-th position and sample, then the
    /// exact DP over bands of positions around the coarse optimum's best cells (see `coarse`).
    /// Not guaranteed optimal; its cost is at least the exact optimum, and equal when the bands
    /// hold an optimal path (the report gives the gap when the exact solver also runs).
    #[serde(rename = "coarse")]
    CoarseToFine,
    /// [`Solver::Exact`], or [`Solver::CoarseToFine`] for an open curve whose dynamic program has
    /// more than [`AUTO_COARSE_PAIRS`] position pairs (`Σ V_{i−1} V_i`): the 600 × 250 real chain
    /// along 100 pieces has 2.7–3.5 × 10¹⁰ and takes over 100 s exact, 2 s coarse with the same
    /// optimum. Closed curves stay exact (the coarse bands can miss the cycle). The report names
    /// the solver that ran.
    Auto,
}

/// Position pairs above which [`Solver::Auto`] runs the coarse-to-fine solver on an open curve.
pub const AUTO_COARSE_PAIRS: u64 = 10_000_000_000;

impl Solver {
    /// The solver that runs for rows of `positions` valid positions each: `self`, with
    /// [`Solver::Auto`] decided.
    pub(crate) fn resolve(self, positions: &[usize], closed: bool) -> Self {
        if self != Self::Auto {
            return self;
        }
        let pairs: u64 = positions.windows(2).map(|pair| pair[0] as u64 * pair[1] as u64).sum();
        if !closed && pairs > AUTO_COARSE_PAIRS { Self::CoarseToFine } else { Self::Exact }
    }
}

/// One row of the DP table: a piece and its candidate positions.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RowSpec<'a> {
    pub frame: &'a PieceFrame,
    pub positions: &'a [Position],
}

/// Work counters of the DP.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct DpCounters {
    /// Predecessor/position pairs of all rows (`Σ V_{i−1} V_i`).
    pub pairs: u64,
    /// Pairs of distinct edges reached by the tree search (their lower bounds were evaluated).
    pub visited: u64,
    /// Pairs whose pixels were compared (fully or until early exit).
    pub compared: u64,
    /// Pairs whose comparison ran to the end.
    pub completed: u64,
}

impl DpCounters {
    /// The sum of two sets of counters.
    pub fn plus(self, other: Self) -> Self {
        Self {
            pairs: self.pairs + other.pairs,
            visited: self.visited + other.visited,
            compared: self.compared + other.compared,
            completed: self.completed + other.completed,
        }
    }

    /// Fraction of pairs never compared pixel by pixel.
    pub fn skipped_fraction(&self) -> f64 {
        if self.pairs == 0 { 0.0 } else { 1.0 - self.compared as f64 / self.pairs as f64 }
    }
}

/// The filled DP table: last row costs and the argmin predecessors of every row.
#[derive(Debug, Clone)]
pub(crate) struct DpTable {
    /// `P` of the last row.
    pub last_costs: Vec<u64>,
    /// For rows `1..`, the index of the best predecessor of each position.
    pub predecessors: Vec<Vec<u32>>,
    /// Milliseconds per row (edge extraction, cost comparison and table update), rows `1..`.
    pub row_ms: Vec<f64>,
    /// Work counters.
    pub counters: DpCounters,
    /// `P` after each computed row (only when asked for, for incremental re-synthesis).
    pub row_costs: Vec<Vec<u64>>,
}

impl DpTable {
    /// Position indices of every row on the optimal path ending at `last` in the last row.
    pub(crate) fn backtrack(&self, last: usize) -> Vec<usize> {
        let mut path = vec![last];
        let mut index = last;
        for row in self.predecessors.iter().rev() {
            index = row[index] as usize;
            path.push(index);
        }
        path.reverse();
        path
    }

    /// Index of the first position in row 0 reached from `last` (the start of its path).
    pub(crate) fn start_of(&self, last: usize) -> usize {
        self.predecessors.iter().rev().fold(last, |index, row| row[index] as usize)
    }
}

/// Runs the DP over `rows` (row 0 costs 0 everywhere). `on_row` is called after each row.
pub(crate) fn solve(
    exemplar: &Exemplar,
    model: &CostModel,
    rows: &[RowSpec<'_>],
    solver: Solver,
    on_row: &mut dyn FnMut(usize),
) -> DpTable {
    let initial = vec![0_u64; rows[0].positions.len()];
    solve_from(exemplar, model, rows, solver, (1, initial), false, on_row)
}

/// Runs rows `start..` of the DP given `P` of row `start − 1` (`start ≥ 1`); the table's
/// predecessors cover those rows only. With `keep_costs`, the table also keeps `P` of every row it
/// computed.
pub(crate) fn solve_from(
    exemplar: &Exemplar,
    model: &CostModel,
    rows: &[RowSpec<'_>],
    solver: Solver,
    (start, initial): (usize, Vec<u64>),
    keep_costs: bool,
    on_row: &mut dyn FnMut(usize),
) -> DpTable {
    let mut costs = initial;
    let count = rows.len().saturating_sub(start);
    let mut predecessors = Vec::with_capacity(count);
    let mut row_ms = Vec::with_capacity(count);
    let mut row_costs = Vec::new();
    let mut counters = DpCounters::default();
    // Rows with the same frame and positions have the same edges (every bent piece of an open
    // curve shares one frame), so the last row's edges are kept and reused when they match: about
    // an eighth of a row's time went into extracting them again.
    let mut rights: Option<(usize, EdgeSet)> = None;
    let mut lefts: Option<(usize, EdgeSet)> = None;
    for r in start..rows.len() {
        let clock = Clock::now();
        if !rights.as_ref().is_some_and(|(row, _)| same_right_edges(&rows[*row], &rows[r - 1])) {
            rights = Some((r - 1, right_edges(exemplar, model, rows[r - 1].frame, rows[r - 1].positions)));
        }
        if !lefts.as_ref().is_some_and(|(row, _)| same_left_edges(&rows[*row], &rows[r])) {
            lefts = Some((r, left_edges(exemplar, model, rows[r].positions, rows[r].frame.samples)));
        }
        let edges = (&rights.as_ref().expect("set above").1, &lefts.as_ref().expect("set above").1);
        let (next, row_predecessors, row_counters) = step_on(model, &rows[r - 1], &costs, &rows[r], edges, solver);
        row_ms.push(elapsed_ms(clock));
        counters = counters.plus(row_counters);
        costs = next;
        if keep_costs {
            row_costs.push(costs.clone());
        }
        predecessors.push(row_predecessors);
        on_row(r);
    }
    DpTable { last_costs: costs, predecessors, row_ms, counters, row_costs }
}

/// One row update of Eq. 1: the best `P` of every position of `current` given the costs
/// `previous` of the positions of `before`, with the index of the best predecessor.
pub(crate) fn step(
    exemplar: &Exemplar,
    model: &CostModel,
    before: &RowSpec<'_>,
    previous: &[u64],
    current: &RowSpec<'_>,
    solver: Solver,
) -> RowResult {
    let rights = right_edges(exemplar, model, before.frame, before.positions);
    let lefts = left_edges(exemplar, model, current.positions, current.frame.samples);
    step_on(model, before, previous, current, (&rights, &lefts), solver)
}

/// Whether rows `a` and `b` have the same right edges (they depend on the frame's right-edge
/// taps and on the positions).
pub(crate) fn same_right_edges(a: &RowSpec<'_>, b: &RowSpec<'_>) -> bool {
    (std::ptr::eq(a.frame, b.frame) || (a.frame.samples == b.frame.samples && a.frame.right_taps == b.frame.right_taps))
        && a.positions == b.positions
}

/// Whether rows `a` and `b` have the same left edges (the positions' columns of `C` samples).
pub(crate) fn same_left_edges(a: &RowSpec<'_>, b: &RowSpec<'_>) -> bool {
    a.frame.samples == b.frame.samples && a.positions == b.positions
}

/// [`step`] given the right edges of `before` and the left edges of `current`.
fn step_on(
    model: &CostModel,
    before: &RowSpec<'_>,
    previous: &[u64],
    current: &RowSpec<'_>,
    (rights, lefts): (&EdgeSet, &EdgeSet),
    solver: Solver,
) -> RowResult {
    match solver {
        Solver::Reference => reference_row(model, previous, rights, lefts),
        // The coarse-to-fine solver refines its bands with the exact solver's rows.
        Solver::Exact | Solver::CoarseToFine | Solver::Auto => {
            let top_right = before.frame.top_right;
            let shift = [top_right.x.round() as i32, top_right.y.round() as i32];
            distinct_row(model, previous, rights, lefts, |predecessors, successors| {
                Seeds::new(before.positions, current.positions, shift, predecessors, successors)
            })
        }
    }
}

/// The backward table: `Q[r][u]`, the cheapest cost from position `u` of row `r` to the end of
/// the rows (any last position). `D` is symmetric in its two edges (ξ is), so a backward row is
/// the forward update with the roles of the edges swapped: the next row's left edges play the
/// predecessors and this row's right edges the positions.
pub(crate) fn solve_backward(exemplar: &Exemplar, model: &CostModel, rows: &[RowSpec<'_>]) -> Vec<Vec<u64>> {
    let mut tables = vec![Vec::new(); rows.len()];
    tables[rows.len() - 1] = vec![0_u64; rows[rows.len() - 1].positions.len()];
    for r in (0..rows.len() - 1).rev() {
        let next_lefts = left_edges(exemplar, model, rows[r + 1].positions, rows[r + 1].frame.samples);
        let rights = right_edges(exemplar, model, rows[r].frame, rows[r].positions);
        let (costs, _, _) =
            distinct_row(model, &tables[r + 1], &next_lefts, &rights, |_, successors| Seeds::none(successors.len()));
        tables[r] = costs;
    }
    tables
}

/// Costs, best predecessors and work counters of one row.
pub(crate) type RowResult = (Vec<u64>, Vec<u32>, DpCounters);

/// Eq. 1 as written: every predecessor, every sample.
fn reference_row(model: &CostModel, previous: &[u64], rights: &EdgeSet, lefts: &EdgeSet) -> RowResult {
    let results: Vec<(u64, u32)> = (0..lefts.len())
        .into_par_iter()
        .map(|u| {
            let mut best = (u64::MAX, u32::MAX);
            for (v, &cost) in previous.iter().enumerate() {
                let total = cost + u64::from(edge_distance(model, rights, v, lefts, u));
                if total < best.0 {
                    best = (total, v as u32);
                }
            }
            best
        })
        .collect();
    let pairs = (previous.len() * lefts.len()) as u64;
    let counters = DpCounters { pairs, visited: pairs, compared: pairs, completed: pairs };
    let (costs, predecessors) = results.into_iter().unzip();
    (costs, predecessors, counters)
}

/// Good first guesses of the best predecessor of each position, so that the cost-ordered scan
/// starts with a tight bound: the predecessor that continues the exemplar (`v = u − t`, with `t`
/// the rounded top-right corner of the previous piece), and the best predecessor of the position
/// just above `u` moved down by one pixel. Guesses only change how fast the optimum is found, never
/// which one: every predecessor is still considered.
pub(crate) struct Seeds {
    pub previous: Vec<Position>,
    origin: [i32; 2],
    size: [i32; 2],
    index: Vec<u32>,
    pub continuation: Vec<u32>,
    pub above: Vec<u32>,
}

impl Seeds {
    /// Guesses for the distinct edges: predecessor and position indices are those of
    /// `predecessors` and `successors` (every original position maps to its group).
    pub(crate) fn new(
        previous: &[Position],
        current: &[Position],
        shift: [i32; 2],
        predecessors: &DistinctEdges,
        successors: &DistinctEdges,
    ) -> Self {
        let (mut lo, mut hi) = ([i32::MAX; 2], [i32::MIN; 2]);
        for p in previous.iter().chain(current) {
            for axis in 0..2 {
                lo[axis] = lo[axis].min(p[axis]);
                hi[axis] = hi[axis].max(p[axis]);
            }
        }
        let size = [hi[0] - lo[0] + 1, hi[1] - lo[1] + 1];
        let mut seeds = Self {
            previous: predecessors.representatives.iter().map(|&v| previous[v as usize]).collect(),
            origin: lo,
            size,
            index: Vec::new(),
            continuation: Vec::new(),
            above: Vec::new(),
        };
        let cells = size[0] as usize * size[1] as usize;
        if cells > 1 << 24 {
            // Too sparse to index densely (only with far-apart empty positions): no guesses.
            seeds.continuation = vec![u32::MAX; successors.len()];
            seeds.above = vec![u32::MAX; successors.len()];
            return seeds;
        }
        seeds.index = vec![u32::MAX; cells];
        for (i, &p) in previous.iter().enumerate() {
            let cell = seeds.cell(p).expect("inside the box");
            seeds.index[cell] = predecessors.group_of[i];
        }
        let mut current_index = vec![u32::MAX; cells];
        for (i, &p) in current.iter().enumerate() {
            current_index[seeds.cell(p).expect("inside the box")] = successors.group_of[i];
        }
        let representatives = successors.representatives.iter().map(|&u| current[u as usize]);
        seeds.continuation = representatives
            .clone()
            .map(|[x, y]| seeds.cell([x - shift[0], y - shift[1]]).map_or(u32::MAX, |cell| seeds.index[cell]))
            .collect();
        seeds.above =
            representatives.map(|[x, y]| seeds.cell([x, y - 1]).map_or(u32::MAX, |cell| current_index[cell])).collect();
        seeds
    }

    /// No guesses at all (for the backward table, where positions and edges swap roles).
    pub(crate) fn none(count: usize) -> Self {
        Self {
            previous: Vec::new(),
            origin: [0, 0],
            size: [0, 0],
            index: Vec::new(),
            continuation: vec![u32::MAX; count],
            above: vec![u32::MAX; count],
        }
    }

    fn cell(&self, p: Position) -> Option<usize> {
        let (x, y) = (p[0] - self.origin[0], p[1] - self.origin[1]);
        if x < 0 || y < 0 || x >= self.size[0] || y >= self.size[1] {
            return None;
        }
        Some(y as usize * self.size[0] as usize + x as usize)
    }

    /// Group (distinct-predecessor index) of position `p` of the previous row, if it is there.
    pub(crate) fn previous_index(&self, p: Position) -> Option<u32> {
        self.cell(p).map(|cell| self.index[cell]).filter(|&i| i != u32::MAX)
    }
}

/// Edges grouped by identical content. Two edges with the same four planes have the same `D`
/// to any other edge, so only one of each group needs to enter the search: periodic exemplars,
/// flat or empty regions and repeated motifs give thousands of positions but a few hundred
/// distinct columns.
pub(crate) struct DistinctEdges {
    /// One original index per group, its lowest by priority then index; ascending, so comparing group
    /// indices compares original indices (the solvers' tie-break).
    representatives: Vec<u32>,
    /// Group (index into `representatives`) of each original edge.
    group_of: Vec<u32>,
}

impl DistinctEdges {
    /// Groups the edges of `set`; each group's representative is its member of lowest
    /// `(priority, index)`.
    fn new(set: &EdgeSet, priority: impl Fn(usize) -> u64 + Sync) -> Self {
        // Sorting by a 64-bit digest (then priority and index) brings identical edges together, lowest priority
        // first, without comparing planes; the planes are compared only within a run of equal
        // digests, so a collision cannot merge different edges.
        let mut order: Vec<(u64, u64, usize)> = (0..set.len())
            .into_par_iter()
            .map(|i| {
                // Four independent lanes, so the multiplications overlap.
                let mut lanes = [0x243f_6a88_85a3_08d3_u64, 0x1319_8a2e_0370_7344, 0xa409_3822_299f_31d0, 0x082e_fa98];
                for words in set.planes_of(i).chunks_exact(32) {
                    for (lane, word) in lanes.iter_mut().zip(words.chunks_exact(8)) {
                        let word = u64::from_le_bytes(word.try_into().expect("8 bytes"));
                        *lane = (*lane ^ word).wrapping_mul(0x9e37_79b9_7f4a_7c15).rotate_left(29);
                    }
                }
                let digest = lanes.iter().fold(0_u64, |d, &lane| (d ^ lane).wrapping_mul(0xff51_afd7_ed55_8ccd));
                (digest, priority(i), i)
            })
            .collect();
        order.par_sort_unstable();
        let mut representatives: Vec<u32> = Vec::new();
        let mut members = vec![0_u32; set.len()];
        let mut run_start = 0;
        for (k, &(digest, _, i)) in order.iter().enumerate() {
            if k > 0 && order[k - 1].0 != digest {
                run_start = representatives.len();
            }
            // Groups of this digest run; almost always one.
            let group = (run_start..representatives.len())
                .find(|&g| set.planes_of(representatives[g] as usize) == set.planes_of(i))
                .unwrap_or_else(|| {
                    representatives.push(i as u32);
                    representatives.len() - 1
                });
            members[i] = group as u32;
        }
        // Renumber the groups by ascending representative.
        let mut renumber: Vec<u32> = (0..representatives.len() as u32).collect();
        renumber.sort_unstable_by_key(|&g| representatives[g as usize]);
        let mut new_index = vec![0_u32; representatives.len()];
        for (new, &old) in renumber.iter().enumerate() {
            new_index[old as usize] = new as u32;
        }
        let group_of = members.iter().map(|&g| new_index[g as usize]).collect();
        let representatives = renumber.iter().map(|&g| representatives[g as usize]).collect();
        Self { representatives, group_of }
    }

    /// Number of groups.
    fn len(&self) -> usize {
        self.representatives.len()
    }

    /// The representatives' edges (borrowed when every edge is distinct).
    fn edges<'a>(&self, set: &'a EdgeSet) -> std::borrow::Cow<'a, EdgeSet> {
        if self.len() == set.len() {
            std::borrow::Cow::Borrowed(set)
        } else {
            std::borrow::Cow::Owned(set.permuted(&self.representatives))
        }
    }
}

/// [`exact_row`] on distinct edges only, expanded back to every position. Within a group of
/// identical right edges only the representative (lowest `P`, then lowest index) can be the
/// reference's argmin, since every member has the same `D`; identical left edges pose the same
/// minimisation, so they share its answer.
pub(crate) fn distinct_row(
    model: &CostModel,
    previous: &[u64],
    rights: &EdgeSet,
    lefts: &EdgeSet,
    seeds: impl FnOnce(&DistinctEdges, &DistinctEdges) -> Seeds,
) -> RowResult {
    let predecessors = DistinctEdges::new(rights, |v| previous[v]);
    let successors = DistinctEdges::new(lefts, |_| 0);
    let seeds = seeds(&predecessors, &successors);
    let distinct_previous: Vec<u64> = predecessors.representatives.iter().map(|&v| previous[v as usize]).collect();
    let (costs, best, mut counters) =
        exact_row(model, &distinct_previous, &predecessors.edges(rights), &successors.edges(lefts), &seeds);
    counters.pairs = (previous.len() * lefts.len()) as u64;
    let original = |g: u32| predecessors.representatives.get(g as usize).copied().unwrap_or(u32::MAX);
    let (costs, best) = successors.group_of.iter().map(|&g| (costs[g as usize], original(best[g as usize]))).unzip();
    (costs, best, counters)
}

/// The cost `Ω` of a given choice of positions (one index per row), summing `D` over all seams.
pub(crate) fn path_cost(exemplar: &Exemplar, model: &CostModel, rows: &[RowSpec<'_>], path: &[usize]) -> u64 {
    (1..rows.len())
        .map(|r| {
            let rights = right_edges(exemplar, model, rows[r - 1].frame, &[rows[r - 1].positions[path[r - 1]]]);
            let lefts = left_edges(exemplar, model, &[rows[r].positions[path[r]]], rows[r].frame.samples);
            u64::from(edge_distance(model, &rights, 0, &lefts, 0))
        })
        .sum()
}

/// Brute force for tests: the minimum of `Ω` over every combination of positions, optionally
/// only over cycles (last position equal to the first). `None` when no combination qualifies.
#[cfg(test)]
pub(crate) fn brute_force(
    exemplar: &Exemplar,
    model: &CostModel,
    rows: &[RowSpec<'_>],
    cycle: bool,
) -> Option<(u64, Vec<usize>)> {
    let rights: Vec<EdgeSet> = rows.iter().map(|row| right_edges(exemplar, model, row.frame, row.positions)).collect();
    let lefts: Vec<EdgeSet> =
        rows.iter().map(|row| left_edges(exemplar, model, row.positions, row.frame.samples)).collect();
    let mut best: Option<(u64, Vec<usize>)> = None;
    let mut path = vec![0_usize; rows.len()];
    fn visit(
        r: usize,
        cost: u64,
        path: &mut Vec<usize>,
        best: &mut Option<(u64, Vec<usize>)>,
        context: (&CostModel, &[RowSpec<'_>], &[EdgeSet], &[EdgeSet], bool),
    ) {
        let (model, rows, rights, lefts, cycle) = context;
        if r == rows.len() {
            if cycle && rows[r - 1].positions[path[r - 1]] != rows[0].positions[path[0]] {
                return;
            }
            if best.as_ref().is_none_or(|(b, _)| cost < *b) {
                *best = Some((cost, path.clone()));
            }
            return;
        }
        for i in 0..rows[r].positions.len() {
            let step =
                if r == 0 { 0 } else { u64::from(edge_distance(model, &rights[r - 1], path[r - 1], &lefts[r], i)) };
            path[r] = i;
            visit(r + 1, cost + step, path, best, context);
        }
    }
    visit(0, 0, &mut path, &mut best, (model, rows, &rights, &lefts, cycle));
    best
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Edges of `samples` samples whose alphas come from a small alphabet (so that distances
    /// are often small and bounds matter) and whose colours are free.
    pub(crate) fn edge_set(samples: usize, columns: &[Vec<(u8, u8)>]) -> EdgeSet {
        let mut set = EdgeSet::with_capacity(samples, columns.len());
        for column in columns {
            set.push(column.iter().map(|&(alpha, colour)| {
                let alpha = [0, 255, 128, colour][usize::from(alpha % 4)];
                [colour, colour.wrapping_mul(3), 40, alpha]
            }));
        }
        set
    }

    #[test]
    fn auto_is_coarse_only_on_large_open_problems() {
        // 100 rows of 18 660 positions (the 600 × 250 chain): 3.4 × 10¹⁰ pairs.
        let large = vec![18_660; 100];
        let small = vec![1_200; 60];
        assert_eq!(Solver::Auto.resolve(&large, false), Solver::CoarseToFine);
        assert_eq!(Solver::Auto.resolve(&large, true), Solver::Exact);
        assert_eq!(Solver::Auto.resolve(&small, false), Solver::Exact);
        assert_eq!(Solver::Exact.resolve(&large, false), Solver::Exact);
        assert_eq!(Solver::Reference.resolve(&large, false), Solver::Reference);
        // Just over and at the threshold.
        let edge = |n: usize| vec![100_000; n];
        assert_eq!(Solver::Auto.resolve(&edge(2), false), Solver::Exact);
        assert_eq!(Solver::Auto.resolve(&edge(3), false), Solver::CoarseToFine);
    }

    proptest! {
        /// Identical edges, and only they, share a group; representatives are the lowest
        /// (priority, index) of their group and ascend.
        #[test]
        fn distinct_edges_group_exactly_the_identical_ones(
            samples in 1_usize..40,
            kinds in proptest::collection::vec(0_usize..5, 1..60),
            patterns in proptest::collection::vec(proptest::collection::vec(any::<(u8, u8)>(), 40), 5),
            priorities in proptest::collection::vec(0_u64..4, 60),
        ) {
            let columns: Vec<Vec<(u8, u8)>> = kinds.iter().map(|&k| patterns[k].clone()).collect();
            let set = edge_set(samples, &columns);
            let distinct = DistinctEdges::new(&set, |i| priorities[i]);
            prop_assert!(distinct.representatives.is_sorted());
            for i in 0..set.len() {
                let group = distinct.group_of[i] as usize;
                let representative = distinct.representatives[group] as usize;
                prop_assert_eq!(set.planes_of(i), set.planes_of(representative));
                prop_assert!((priorities[representative], representative) <= (priorities[i], i));
                for j in 0..set.len() {
                    let same = set.planes_of(i) == set.planes_of(j);
                    prop_assert_eq!(same, distinct.group_of[j] as usize == group);
                }
            }
        }
    }
}
