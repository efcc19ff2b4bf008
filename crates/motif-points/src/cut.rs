//! Minimum error boundary cuts between two overlapping copies (the seam of image quilting, Efros
//! and Freeman 2001, §2.1, carried over to point sets in 2D).
//!
//! A new copy overlaps the points already placed in a band along its border. Cutting at the
//! border itself puts two unrelated arrangements side by side: pairs closer than the exemplar ever
//! has them, and gaps. Instead, the band is divided into cells, each cell scored by how much the
//! two arrangements disagree there (each point's squared distance to the nearest point of the
//! other arrangement, capped), and the cut is the path across the band's length with the least
//! total disagreement, moving at most one cell sideways per step (dynamic programming). Beyond the
//! cut the new copy replaces what was placed; where the two agree, the seam is invisible.

use crate::grid::StaticGrid;
use crate::linear::Vector;

/// A band between placed points (on the low side of `across`) and a new copy (on the high side).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Overlap {
    /// The axis the cut's position is measured on (0: a vertical band, 1: a horizontal one).
    pub across: usize,
    /// The band's extent along the cut.
    pub along_range: (f64, f64),
    /// The band's extent across it.
    pub across_range: (f64, f64),
    /// Side of the scoring cells.
    pub cell: f64,
    /// Distances are capped here (a point with nothing of the other side within it costs this).
    pub reach: f64,
}

/// The cut: a position across the band for each cell along it.
#[derive(Debug, Clone)]
pub(crate) struct Cut {
    overlap: Overlap,
    positions: Vec<f64>,
}

impl Cut {
    /// Whether `p` (inside the band) lies on the new copy's side.
    pub(crate) fn on_new_side(&self, p: &Vector<2>) -> bool {
        let along = 1 - self.overlap.across;
        let cell = self.overlap.cell;
        let index = ((p[along] - self.overlap.along_range.0) / cell).floor().max(0.0) as usize;
        p[self.overlap.across] > self.positions[index.min(self.positions.len() - 1)]
    }

    /// Whether `p` lies in the band.
    pub(crate) fn contains(&self, p: &Vector<2>) -> bool {
        self.overlap.contains(p)
    }
}

impl Overlap {
    /// Whether `p` lies in the band.
    pub(crate) fn contains(&self, p: &Vector<2>) -> bool {
        let along = 1 - self.across;
        p[along] >= self.along_range.0
            && p[along] < self.along_range.1
            && p[self.across] >= self.across_range.0
            && p[self.across] < self.across_range.1
    }

    /// The least-disagreement cut between `placed` and `copy` (both the points inside the band).
    /// `covered` tells where the copy has a source (inside the exemplar's window): the copy never
    /// replaces placed points where it has none, so the cut keeps to the right of such cells.
    pub(crate) fn minimum_cut(
        &self,
        placed: &[Vector<2>],
        copy: &[Vector<2>],
        covered: &dyn Fn(&Vector<2>) -> bool,
    ) -> Cut {
        let along = 1 - self.across;
        let rows = (((self.along_range.1 - self.along_range.0) / self.cell).ceil() as usize).max(1);
        let columns = (((self.across_range.1 - self.across_range.0) / self.cell).ceil() as usize).max(1);
        let mut error = vec![0.0; rows * columns];
        let cap = self.reach * self.reach;
        let mut score = |points: &[Vector<2>], others: &[Vector<2>]| {
            let grid = (!others.is_empty()).then(|| StaticGrid::new(others, self.reach));
            for p in points {
                let mut nearest = cap;
                if let Some(grid) = &grid {
                    grid.for_each_within(p, self.reach, |_, _, d2| nearest = nearest.min(d2));
                }
                let row = ((p[along] - self.along_range.0) / self.cell).floor().clamp(0.0, (rows - 1) as f64) as usize;
                let column = ((p[self.across] - self.across_range.0) / self.cell)
                    .floor()
                    .clamp(0.0, (columns - 1) as f64) as usize;
                error[row * columns + column] += nearest / cap;
            }
        };
        score(placed, copy);
        score(copy, placed);
        // A cut through an empty cell between two disagreeing ones still joins them: each cell
        // also carries half of its neighbours' error across the band.
        let blurred: Vec<f64> = (0..rows * columns)
            .map(|index| {
                let (row, column) = (index / columns, index % columns);
                let side = |c: usize| error[row * columns + c];
                let left = if column > 0 { side(column - 1) } else { 0.0 };
                let right = if column + 1 < columns { side(column + 1) } else { 0.0 };
                error[index] + 0.5 * (left + right)
            })
            .collect();
        // Per row, the first column the cut may take (cut at a column's far side: every cell after
        // it must be covered by the copy).
        let first_allowed: Vec<usize> = (0..rows)
            .map(|row| {
                let along_centre = self.along_range.0 + (row as f64 + 0.5) * self.cell;
                (0..columns)
                    .rev()
                    .find(|&column| {
                        let mut centre = [0.0; 2];
                        centre[along] = along_centre;
                        centre[self.across] = self.across_range.0 + (column as f64 + 0.5) * self.cell;
                        !covered(&centre)
                    })
                    .map_or(0, |column| column.min(columns - 1))
            })
            .collect();
        let blurred: Vec<f64> = blurred
            .into_iter()
            .enumerate()
            .map(|(index, e)| if index % columns < first_allowed[index / columns] { f64::INFINITY } else { e })
            .collect();
        // Cumulative cost from the first row, and the column each cell came from.
        let mut cost = blurred[..columns].to_vec();
        let mut from = vec![0usize; rows * columns];
        for row in 1..rows {
            let mut next = vec![0.0; columns];
            for column in 0..columns {
                let low = column.saturating_sub(1);
                let high = (column + 1).min(columns - 1);
                // Ties go to the column nearest the new copy's own tile: replace placed points only
                // where that is better (on point sets many cells cost nothing on either side).
                let mut best = high;
                for candidate in (low..=high).rev() {
                    if cost[candidate] < cost[best] {
                        best = candidate;
                    }
                }
                next[column] = cost[best] + blurred[row * columns + column];
                from[row * columns + column] = best;
            }
            cost = next;
        }
        let mut column = (0..columns).rev().fold(columns - 1, |best, c| if cost[c] < cost[best] { c } else { best });
        let mut positions = vec![0.0; rows];
        for row in (0..rows).rev() {
            // At the cell's far side: the last column keeps everything placed (the cut then runs
            // along the band's edge), so a cut that prefers to replace nothing can.
            positions[row] = self.across_range.0 + (column as f64 + 1.0) * self.cell;
            column = from[row * columns + column];
        }
        Cut { overlap: *self, positions }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cut_runs_where_the_two_copies_agree() {
        // Placed and new points agree exactly in the band's column 5 (of 8) and disagree
        // everywhere else (the new ones shifted along the band, so they stay in their column):
        // the cut must run through that column (at its far side, x = 3) over the band's length.
        let overlap = Overlap { across: 0, along_range: (0.0, 10.0), across_range: (0.0, 4.0), cell: 0.5, reach: 0.5 };
        let mut placed = Vec::new();
        let mut copy = Vec::new();
        for row in 0..20 {
            let y = 0.25 + 0.5 * row as f64;
            for column in 0..8 {
                let x = 0.25 + 0.5 * column as f64;
                placed.push([x, y]);
                copy.push(if column == 5 { [x, y] } else { [x, y + 0.2] });
            }
        }
        let cut = overlap.minimum_cut(&placed, &copy, &|_| true);
        for row in 0..20 {
            let y = 0.25 + 0.5 * row as f64;
            assert!(!cut.on_new_side(&[2.95, y]) && cut.on_new_side(&[3.05, y]), "row {row}: {:?}", cut.positions);
        }
        assert!(cut.contains(&[1.0, 1.0]) && !cut.contains(&[4.5, 1.0]));
    }
}
