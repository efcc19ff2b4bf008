//! Uniform grids for fixed-radius neighbour queries (no O(n²) loops anywhere).
//!
//! Every query in the solver has a radius known in advance (the Gaussian cut-off or the truncated
//! window), so a uniform grid with cells of about that radius answers each query by scanning 3^D
//! cells. Points outside the grid's bounds are clamped into the border cells; since clamping is
//! monotone, a query still finds them.

use rayon::prelude::*;

use crate::linear::Vector;

/// Maps positions to cells.
#[derive(Debug, Clone)]
pub(crate) struct CellIndex<const D: usize> {
    origin: Vector<D>,
    inverse_cell: f64,
    dims: [usize; D],
}

/// Grids never have more cells than this (a huge, sparse domain gets coarser cells instead).
const MAX_CELLS: usize = 1 << 22;

impl<const D: usize> CellIndex<D> {
    /// Cells of side about `cell` covering `[low, high]`.
    pub(crate) fn new(low: Vector<D>, high: Vector<D>, cell: f64) -> Self {
        let mut cell = cell.max(1e-12);
        loop {
            let dims: [usize; D] = std::array::from_fn(|i| (((high[i] - low[i]) / cell).floor() as usize + 1).max(1));
            let total = dims.iter().try_fold(1usize, |acc, &d| acc.checked_mul(d));
            match total {
                Some(total) if total <= MAX_CELLS => return Self { origin: low, inverse_cell: 1.0 / cell, dims },
                _ => cell *= 2.0,
            }
        }
    }

    #[inline(always)]
    fn coordinate(&self, value: f64, axis: usize) -> usize {
        // `t as usize` truncates, which for t > 0 is `floor` without a libm call (same result).
        let t = (value - self.origin[axis]) * self.inverse_cell;
        if t <= 0.0 { 0 } else { (t as usize).min(self.dims[axis] - 1) }
    }

    /// The linear index of the cell holding `p` (clamped into the grid).
    #[inline(always)]
    pub(crate) fn cell_of(&self, p: &Vector<D>) -> usize {
        let mut index = 0;
        for axis in (0..D).rev() {
            index = index * self.dims[axis] + self.coordinate(p[axis], axis);
        }
        index
    }

    /// Total number of cells.
    pub(crate) fn len(&self) -> usize {
        self.dims.iter().product()
    }

    /// Calls `visit(cell)` for every cell overlapping the cube of half-side `radius` around `center`.
    #[inline(always)]
    pub(crate) fn for_each_cell(&self, center: &Vector<D>, radius: f64, mut visit: impl FnMut(usize)) {
        let low: [usize; D] = std::array::from_fn(|a| self.coordinate(center[a] - radius, a));
        let high: [usize; D] = std::array::from_fn(|a| self.coordinate(center[a] + radius, a));
        if D == 2 {
            for y in low[1]..=high[1] {
                let row = y * self.dims[0];
                for x in low[0]..=high[0] {
                    visit(row + x);
                }
            }
        } else {
            for z in low[D - 1]..=high[D - 1] {
                for y in low[1]..=high[1] {
                    let row = (z * self.dims[1] + y) * self.dims[0];
                    for x in low[0]..=high[0] {
                        visit(row + x);
                    }
                }
            }
        }
    }
}

impl<const D: usize> CellIndex<D> {
    /// The squared distance from `value` to cell `c` along `axis` (0 inside it).
    #[inline(always)]
    fn gap2(&self, value: f64, c: usize, axis: usize) -> f64 {
        let cell = 1.0 / self.inverse_cell;
        let low = self.origin[axis] + c as f64 * cell;
        // Border cells hold clamped points, so they extend without limit outwards.
        let below = if c == 0 { f64::NEG_INFINITY } else { low };
        let above = if c + 1 == self.dims[axis] { f64::INFINITY } else { low + cell };
        let gap = if value < below {
            below - value
        } else if value > above {
            value - above
        } else {
            0.0
        };
        gap * gap
    }

    /// Calls `visit(first, last)` with the first and last linear cell index of every row (along
    /// axis 0) of the cells overlapping the cube of half-side `radius` around `center`, in
    /// [`CellIndex::for_each_cell`] order, leaving out rows that lie entirely beyond `radius` and
    /// clipping each row to the chord of the ball through it (with cells finer than the radius, this
    /// scans about half the volume of the full cube of cells).
    #[inline(always)]
    pub(crate) fn for_each_row(&self, center: &Vector<D>, radius: f64, mut visit: impl FnMut(usize, usize)) {
        let low: [usize; D] = std::array::from_fn(|a| self.coordinate(center[a] - radius, a));
        let high: [usize; D] = std::array::from_fn(|a| self.coordinate(center[a] + radius, a));
        let r2 = radius * radius;
        // The cells along axis 0 that the ball's chord at squared cross-section distance `g` covers.
        let chord = |g: f64| {
            let half = (r2 - g).sqrt();
            (self.coordinate(center[0] - half, 0), self.coordinate(center[0] + half, 0))
        };
        match D {
            1 => visit(low[0], high[0]),
            2 => {
                for y in low[1]..=high[1] {
                    let g = self.gap2(center[1], y, 1);
                    if g >= r2 {
                        continue;
                    }
                    let row = y * self.dims[0];
                    let (first, last) = chord(g);
                    visit(row + first, row + last);
                }
            }
            _ => {
                for z in low[D - 1]..=high[D - 1] {
                    let gz = self.gap2(center[D - 1], z, D - 1);
                    if gz >= r2 {
                        continue;
                    }
                    for y in low[1]..=high[1] {
                        let g = gz + self.gap2(center[1], y, 1);
                        if g >= r2 {
                            continue;
                        }
                        let row = (z * self.dims[1] + y) * self.dims[0];
                        let (first, last) = chord(g);
                        visit(row + first, row + last);
                    }
                }
            }
        }
    }
}

/// An immutable grid over a point set, with the positions stored in cell order so that a query
/// scans contiguous memory.
#[derive(Debug, Clone)]
pub(crate) struct StaticGrid<const D: usize> {
    index: CellIndex<D>,
    starts: Vec<u32>,
    positions: Vec<Vector<D>>,
    ids: Vec<u32>,
}

impl<const D: usize> StaticGrid<D> {
    /// Builds the grid over `points` with cells of side about `cell`.
    pub(crate) fn new(points: &[Vector<D>], cell: f64) -> Self {
        let (low, high) = bounds(points);
        let index = CellIndex::new(low, high, cell);
        let mut counts = vec![0u32; index.len() + 1];
        let cells: Vec<usize> = points.iter().map(|p| index.cell_of(p)).collect();
        for &c in &cells {
            counts[c + 1] += 1;
        }
        for i in 1..counts.len() {
            counts[i] += counts[i - 1];
        }
        let mut fill = counts.clone();
        let mut positions = vec![[0.0; D]; points.len()];
        let mut ids = vec![0u32; points.len()];
        for (id, &c) in cells.iter().enumerate() {
            let slot = fill[c] as usize;
            fill[c] += 1;
            positions[slot] = points[id];
            ids[slot] = id as u32;
        }
        Self { index, starts: counts, positions, ids }
    }

    /// The point ids in cell order (neighbouring points close together in the sequence).
    pub(crate) fn cell_order(&self) -> &[u32] {
        &self.ids
    }

    /// Calls `visit(id, position, squared distance)` for every point within `radius` of `center`.
    ///
    /// Points are stored in cell order and a row of cells along the first axis is contiguous, so
    /// each row of the query's cell range is one slice scan (same visiting order as cell by cell);
    /// rows whose cross-section lies farther than `radius` from `center` are skipped.
    #[inline(always)]
    pub(crate) fn for_each_within(
        &self,
        center: &Vector<D>,
        radius: f64,
        mut visit: impl FnMut(usize, &Vector<D>, f64),
    ) {
        let r2 = radius * radius;
        self.index.for_each_row(center, radius, |first, last| {
            let (start, end) = (self.starts[first] as usize, self.starts[last + 1] as usize);
            for (p, &id) in self.positions[start..end].iter().zip(&self.ids[start..end]) {
                let mut d2 = 0.0;
                for a in 0..D {
                    let d = p[a] - center[a];
                    d2 += d * d;
                }
                if d2 < r2 {
                    visit(id as usize, p, d2);
                }
            }
        });
    }
}

/// Fixed-radius queries on a small static point set answered by one slice scan: every cell of a
/// fine grid keeps the ids of all points within `radius` of any place in it (its centre's ball
/// grown by half the cell diagonal).
///
/// The energy's inner loop asks the exemplar for the points within the pair cut-off of a place
/// hundreds of times per output point; with [`StaticGrid`] each query walks 9 rows of 3 cells and
/// scans about 5.8 times the ball's volume, here it reads one list of about 2.9 times the ball's
/// volume (cells of half the radius) with no row bookkeeping. Lists of large sets would take too much
/// memory, so cells grow until the lists fit [`CellLists::MAX_ENTRIES`].
#[derive(Debug, Clone)]
pub(crate) struct CellLists<const D: usize> {
    index: CellIndex<D>,
    starts: Vec<u32>,
    ids: Vec<u32>,
    positions: Vec<Vector<D>>,
    radius: f64,
    /// The longest list.
    longest: usize,
}

impl<const D: usize> CellLists<D> {
    /// The most list entries kept (4 bytes each).
    pub(crate) const MAX_ENTRIES: usize = 1 << 23;

    /// Lists for queries of radius up to `radius` over `points`.
    pub(crate) fn new(points: &[Vector<D>], radius: f64) -> Self {
        let grid = StaticGrid::new(points, radius);
        let (low, high) = bounds(points);
        let mut cell = 0.5 * radius;
        loop {
            let index = CellIndex::new(low, high, cell);
            let side = 1.0 / index.inverse_cell;
            let reach = radius + 0.5 * side * (D as f64).sqrt();
            let mut starts = Vec::with_capacity(index.len() + 1);
            let mut ids = Vec::new();
            starts.push(0);
            let mut fits = true;
            let mut position = [0usize; D];
            for _ in 0..index.len() {
                let centre: Vector<D> = std::array::from_fn(|a| index.origin[a] + (position[a] as f64 + 0.5) * side);
                let first = ids.len();
                grid.for_each_within(&centre, reach, |id, _, _| ids.push(id as u32));
                ids[first..].sort_unstable();
                starts.push(ids.len() as u32);
                if ids.len() > Self::MAX_ENTRIES {
                    fits = false;
                    break;
                }
                // Next cell in linear order (axis 0 fastest, as `cell_of`).
                for a in 0..D {
                    position[a] += 1;
                    if position[a] < index.dims[a] {
                        break;
                    }
                    position[a] = 0;
                }
            }
            if fits {
                let longest = starts.windows(2).map(|w| (w[1] - w[0]) as usize).max().unwrap_or(0);
                return Self { index, starts, ids, positions: points.to_vec(), radius, longest };
            }
            cell *= 2.0;
        }
    }
}

impl<const D: usize> CellLists<D> {
    /// The position of point `id`.
    #[inline(always)]
    pub(crate) fn position(&self, id: usize) -> &Vector<D> {
        &self.positions[id]
    }

    /// Writes `(id, squared distance)` of every point within `radius` (at most the radius the lists
    /// were built for) of `center` into `found`, in increasing id order. The distance test is done
    /// without a branch, which the inner loops' unpredictable hit rate (about one in three)
    /// otherwise pays for in mispredictions.
    ///
    /// `found` is grown to the longest list once and then only overwritten: the result is
    /// `found[..count]` with the returned `count`.
    #[inline(always)]
    pub(crate) fn collect_within(&self, center: &Vector<D>, radius: f64, found: &mut Vec<(u32, f64)>) -> usize {
        debug_assert!(radius <= self.radius * (1.0 + 1e-12));
        // A center outside the grid is clamped into a border cell: its projection onto the grid's box
        // lies in that cell and is no farther from any point of the set, so the list still holds
        // every point within `radius`.
        let cell = self.index.cell_of(center);
        let list = &self.ids[self.starts[cell] as usize..self.starts[cell + 1] as usize];
        if found.len() < list.len() {
            found.resize(self.longest, (0, 0.0));
        }
        let r2 = radius * radius;
        let center = *center;
        let positions = &self.positions[..];
        // A plain slice keeps the buffer's address in a register (writes through the `Vec` would make
        // the compiler reload it on every candidate).
        let out = &mut found[..list.len()];
        let mut count = 0;
        for &id in list {
            let p = &positions[id as usize];
            let mut d2 = 0.0;
            for a in 0..D {
                let d = p[a] - center[a];
                d2 += d * d;
            }
            // Every candidate is written at `count`; a hit keeps it by moving `count` on.
            out[count] = (id, d2);
            count += usize::from(d2 < r2);
        }
        count
    }
}

/// A grid whose points can be inserted and removed (the output during sampling control).
#[derive(Debug, Clone)]
pub(crate) struct DynamicGrid<const D: usize> {
    index: CellIndex<D>,
    cells: Vec<Vec<u32>>,
}

impl<const D: usize> DynamicGrid<D> {
    /// An empty grid covering `[low, high]` with cells of side about `cell`.
    pub(crate) fn new(low: Vector<D>, high: Vector<D>, cell: f64) -> Self {
        let index = CellIndex::new(low, high, cell);
        let cells = vec![Vec::new(); index.len()];
        Self { index, cells }
    }

    /// Adds point `id` at `p`.
    pub(crate) fn insert(&mut self, id: usize, p: &Vector<D>) {
        let cell = self.index.cell_of(p);
        self.cells[cell].push(id as u32);
    }

    /// Removes point `id`, which was inserted at `p`.
    pub(crate) fn remove(&mut self, id: usize, p: &Vector<D>) {
        let cell = self.index.cell_of(p);
        if let Some(slot) = self.cells[cell].iter().position(|&other| other as usize == id) {
            self.cells[cell].swap_remove(slot);
        }
    }

    /// Calls `visit(id)` for every point in the cells near `center` (a superset of the points within
    /// `radius`; the caller checks the distance against its own positions).
    #[inline(always)]
    pub(crate) fn for_each_candidate(&self, center: &Vector<D>, radius: f64, mut visit: impl FnMut(usize)) {
        self.index.for_each_cell(center, radius, |cell| {
            for &id in &self.cells[cell] {
                visit(id as usize);
            }
        });
    }
}

/// The bounding box of `points` (a unit box at the origin when empty).
pub(crate) fn bounds<const D: usize>(points: &[Vector<D>]) -> (Vector<D>, Vector<D>) {
    if points.is_empty() {
        return ([0.0; D], [1.0; D]);
    }
    let mut low = points[0];
    let mut high = points[0];
    for p in points {
        for a in 0..D {
            low[a] = low[a].min(p[a]);
            high[a] = high[a].max(p[a]);
        }
    }
    (low, high)
}

/// Compressed neighbour lists (each point's neighbours within a radius, itself excluded).
#[derive(Debug, Clone, Default)]
pub(crate) struct Neighbours {
    starts: Vec<u32>,
    items: Vec<u32>,
    /// The points in the grid's cell order.
    order: Vec<u32>,
}

impl Neighbours {
    /// Neighbours within `radius` of every point, through a uniform grid.
    pub(crate) fn build<const D: usize>(positions: &[Vector<D>], radius: f64) -> Self {
        let grid = StaticGrid::new(positions, radius);
        let lists: Vec<Vec<u32>> = positions
            .par_iter()
            .enumerate()
            .map(|(i, p)| {
                let mut list = Vec::new();
                grid.for_each_within(p, radius, |j, _, _| {
                    if j != i {
                        list.push(j as u32);
                    }
                });
                // Grid order depends only on the positions, but sort anyway so sums are reproducible.
                list.sort_unstable();
                list
            })
            .collect();
        let mut starts = Vec::with_capacity(positions.len() + 1);
        let mut items = Vec::with_capacity(lists.iter().map(Vec::len).sum());
        starts.push(0);
        for list in lists {
            items.extend_from_slice(&list);
            starts.push(items.len() as u32);
        }
        Self { starts, items, order: grid.cell_order().to_vec() }
    }

    /// The points in the grid's cell order (neighbours close together in the sequence).
    pub(crate) fn order(&self) -> &[u32] {
        &self.order
    }

    /// The neighbours of point `i`.
    #[inline(always)]
    pub(crate) fn of(&self, i: usize) -> &[u32] {
        &self.items[self.starts[i] as usize..self.starts[i + 1] as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use motif_core::random::{Rng, SeedStreams};

    #[test]
    fn rows_cover_the_cells_in_order() {
        // Rows are the cells of `for_each_cell` in the same order, minus cells beyond the radius.
        let index = CellIndex::<3>::new([0.0; 3], [5.0, 4.0, 3.0], 0.5);
        for (center, radius) in [([2.0, 2.0, 1.5], 0.9), ([0.1, 3.9, 0.2], 1.7), ([-1.0, 2.0, 9.0], 0.4)] {
            let mut cells = Vec::new();
            index.for_each_cell(&center, radius, |c| cells.push(c));
            let mut rows = Vec::new();
            index.for_each_row(&center, radius, |first, last| rows.extend(first..=last));
            assert!(rows.len() <= cells.len());
            let mut position = 0;
            for c in &rows {
                position += cells[position..].iter().position(|x| x == c).expect("row cell outside the cell range") + 1;
            }
        }
        let flat = CellIndex::<2>::new([0.0; 2], [5.0, 4.0], 0.5);
        let mut cells = Vec::new();
        flat.for_each_cell(&[2.0, 2.0], 1.2, |c| cells.push(c));
        let mut rows = Vec::new();
        flat.for_each_row(&[2.0, 2.0], 1.2, |first, last| rows.extend(first..=last));
        // The centre row is whole; the outer rows are clipped to the disc's chords.
        assert!(rows.len() < cells.len());
        // 11 cells per row; the centre cell is (4, 4) and its row reaches x ∈ (0.8, 3.2): cells 1..=6.
        assert!((45..=50).all(|c| rows.contains(&c)), "{rows:?}");
    }

    #[test]
    fn cell_lists_answer_queries_from_outside_the_set() {
        let mut stream = SeedStreams::new(5).stream("lists", 0);
        let points: Vec<[f64; 2]> =
            (0..300).map(|_| [stream.random::<f64>() * 6.0, stream.random::<f64>() * 3.0]).collect();
        let lists = CellLists::new(&points, 0.8);
        for center in [[-0.5, 1.0], [6.3, -0.4], [3.0, 3.7], [-0.79, -0.1], [2.0, 1.5]] {
            let mut collected = Vec::new();
            let count = lists.collect_within(&center, 0.8, &mut collected);
            let found: Vec<usize> = collected[..count].iter().map(|c| c.0 as usize).collect();
            let expected: Vec<usize> = (0..points.len())
                .filter(|&i| crate::linear::norm2(&crate::linear::sub(&points[i], &center)) < 0.64)
                .collect();
            assert_eq!(found, expected, "{center:?}");
        }
    }

    #[test]
    fn grid_queries_match_brute_force() {
        let mut stream = SeedStreams::new(3).stream("grid", 0);
        let points: Vec<[f64; 3]> = (0..500)
            .map(|_| [stream.random::<f64>() * 10.0, stream.random::<f64>() * 5.0, stream.random::<f64>()])
            .collect();
        let grid = StaticGrid::new(&points, 0.7);
        let lists = CellLists::new(&points, 1.0);
        let mut dynamic = DynamicGrid::new([0.0; 3], [10.0, 5.0, 1.0], 0.7);
        for (i, p) in points.iter().enumerate() {
            dynamic.insert(i, p);
        }
        dynamic.remove(7, &points[7]);
        for q in 0..50 {
            let center = points[q * 7 % 500];
            let radius = 0.3 + (q as f64) * 0.05;
            let mut found: Vec<usize> = Vec::new();
            grid.for_each_within(&center, radius, |id, _, _| found.push(id));
            found.sort();
            let expected: Vec<usize> = (0..points.len())
                .filter(|&i| crate::linear::norm2(&crate::linear::sub(&points[i], &center)) < radius * radius)
                .collect();
            assert_eq!(found, expected);
            let mut collected = Vec::new();
            let count = lists.collect_within(&center, radius.min(1.0), &mut collected);
            let listed: Vec<usize> = collected[..count].iter().map(|c| c.0 as usize).collect();
            let expected_listed: Vec<usize> = (0..points.len())
                .filter(|&i| crate::linear::norm2(&crate::linear::sub(&points[i], &center)) < radius.min(1.0).powi(2))
                .collect();
            assert_eq!(listed, expected_listed);
            let mut candidates: Vec<usize> = Vec::new();
            dynamic.for_each_candidate(&center, radius, |id| candidates.push(id));
            for &e in &expected {
                assert_eq!(candidates.contains(&e), e != 7);
            }
        }
    }
}
