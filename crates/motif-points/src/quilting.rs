//! The choice of each initial patch's source: image quilting (Efros and Freeman 2001) carried over
//! to point sets.
//!
//! Tiles are filled in scan order. For a new tile, every candidate source in the exemplar is
//! judged on the band just outside the tile, where earlier tiles already placed points: the points
//! there, carried into the candidate's exemplar coordinates, should land on exemplar points, and
//! the candidate's own exemplar points in that band should land on placed points. The candidate
//! whose band agrees best is copied. Random sources leave seams where two copies cross at random
//! offsets (pairs closer than the exemplar ever has them, or gaps); on the real corpus those seams
//! were most of what the synthesis then had to repair, and the repair left its own traces.

use crate::grid::StaticGrid;
use crate::linear::{self, Matrix, Vector};

/// The placed points near one tile, and how to read them in the exemplar's coordinates.
pub(crate) struct Band<const D: usize> {
    /// Placed points in the band, in output coordinates.
    placed: Vec<Vector<D>>,
    /// `placed` indexed for fixed-radius queries (None when the band is empty).
    grid: Option<StaticGrid<D>>,
}

/// Where a tile sits in the output and which of its surroundings are already filled.
pub(crate) struct Tile<'a, const D: usize> {
    /// The tile's centre (output coordinates).
    pub centre: Vector<D>,
    /// Half the tile's side along each axis (output units).
    pub half: Vector<D>,
    /// Width of the judged band around the tile (output units).
    pub band: f64,
    /// Output → exemplar frame at the tile (without the translation).
    pub inverse: &'a Matrix<D>,
    /// Exemplar → output frame at the tile.
    pub frame: &'a Matrix<D>,
    /// The output scale at the tile (output units per exemplar unit).
    pub scale: f64,
}

impl<const D: usize> Tile<'_, D> {
    fn in_band(&self, offset: &Vector<D>) -> bool {
        let inside_tile = (0..D).all(|a| offset[a].abs() <= self.half[a]);
        let inside_band = (0..D).all(|a| offset[a].abs() <= self.half[a] + self.band);
        inside_band && !inside_tile
    }
}

impl<const D: usize> Band<D> {
    /// The points of `positions` in the band around `tile`.
    pub(crate) fn gather(positions: &[Vector<D>], tile: &Tile<'_, D>, cell: f64) -> Self {
        let placed: Vec<Vector<D>> =
            positions.iter().filter(|x| tile.in_band(&linear::sub(x, &tile.centre))).copied().collect();
        let grid = (!placed.is_empty()).then(|| StaticGrid::new(&placed, cell));
        Self { placed, grid }
    }

    /// True when nothing is placed around the tile yet (any source is as good as another).
    pub(crate) fn is_empty(&self) -> bool {
        self.placed.is_empty()
    }

    /// The disagreement of copying the exemplar around `origin` into `tile`: the mean squared
    /// distance, capped at `reach` (exemplar units), from each placed band point to the nearest
    /// exemplar point and from each exemplar band point to the nearest placed point. Only places
    /// both sides can see count: placed points that fall outside the exemplar, and exemplar points
    /// whose copy would land where nothing is placed yet (`filled` is false) or outside the domain.
    #[allow(clippy::too_many_arguments, reason = "the seam measure reads both sides of a tile boundary and its bounds")]
    pub(crate) fn disagreement(
        &self,
        tile: &Tile<'_, D>,
        origin: &Vector<D>,
        exemplar: &[Vector<D>],
        exemplar_grid: &StaticGrid<D>,
        low: &Vector<D>,
        high: &Vector<D>,
        reach: f64,
        filled: &dyn Fn(&Vector<D>) -> bool,
    ) -> f64 {
        let Some(grid) = &self.grid else { return 0.0 };
        let cap = reach * reach;
        let (mut sum, mut count) = (0.0, 0usize);
        for x in &self.placed {
            let e = linear::add(origin, &linear::mat_vec(tile.inverse, &linear::sub(x, &tile.centre)));
            if (0..D).any(|a| e[a] < low[a] || e[a] > high[a]) {
                continue;
            }
            let mut nearest = cap;
            exemplar_grid.for_each_within(&e, reach, |_, _, d2| nearest = nearest.min(d2));
            sum += nearest;
            count += 1;
        }
        // Exemplar points of the band, carried into the output.
        let half: Vector<D> = std::array::from_fn(|a| (tile.half[a] + tile.band) / tile.scale);
        let scaled_reach = reach * tile.scale;
        for c in exemplar {
            let local = linear::sub(c, origin);
            if (0..D).any(|a| local[a].abs() > half[a]) {
                continue;
            }
            let offset = linear::mat_vec(tile.frame, &local);
            if !tile.in_band(&offset) {
                continue;
            }
            let x = linear::add(&tile.centre, &offset);
            if !filled(&x) {
                continue;
            }
            let mut nearest = scaled_reach * scaled_reach;
            grid.for_each_within(&x, scaled_reach, |_, _, d2| nearest = nearest.min(d2));
            sum += nearest / (tile.scale * tile.scale);
            count += 1;
        }
        if count == 0 { 0.0 } else { sum / count as f64 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use motif_core::math;

    #[test]
    fn the_source_a_band_was_copied_from_agrees_exactly() {
        // An irregular exemplar; the band around a tile is filled from the exemplar at a known
        // origin, so that origin must score zero and a shifted one must not.
        let exemplar: Vec<Vector<2>> = (0..400)
            .map(|i| {
                let t = i as f64;
                [(t * 7.31).rem_euclid(20.0), (t * 3.17 + math::sin(t * 0.7)).rem_euclid(20.0)]
            })
            .collect();
        let grid = StaticGrid::new(&exemplar, 1.0);
        let identity = [[1.0, 0.0], [0.0, 1.0]];
        let tile = Tile {
            centre: [50.0, 50.0],
            half: [3.0, 3.0],
            band: 2.0,
            inverse: &identity,
            frame: &identity,
            scale: 1.0,
        };
        let origin = [10.0, 10.0];
        let placed: Vec<Vector<2>> = exemplar
            .iter()
            .map(|e| linear::add(&tile.centre, &linear::sub(e, &origin)))
            .filter(|x| x[0] < 50.0 - 3.0)
            .collect();
        let band = Band::gather(&placed, &tile, 1.0);
        assert!(!band.is_empty());
        let filled = |x: &Vector<2>| x[0] < 50.0 - 3.0;
        let (low, high) = ([0.0, 0.0], [20.0, 20.0]);
        let exact = band.disagreement(&tile, &origin, &exemplar, &grid, &low, &high, 1.0, &filled);
        let shifted = band.disagreement(&tile, &[10.4, 9.7], &exemplar, &grid, &low, &high, 1.0, &filled);
        assert!(exact < 1e-12, "{exact}");
        assert!(shifted > 0.01, "{shifted}");
    }
}
