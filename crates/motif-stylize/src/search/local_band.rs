//! The band's local search (§3.7 with [`crate::Params::band_local_search`]): a Jacobi iteration
//! whose random draws are keyed by each pixel's place in the textures' plane, so that two
//! overlapping windows of one map (a slippy map's tiles) find the same matches.

use motif_core::SeedStreams;
use rayon::prelude::*;

use super::{Best, Candidates, Field};
use crate::level::{Level, WHOLE_PATCH_SIDE};
use crate::occurrence::{Occurrence, OmegaDelta};

/// The key of target pixel `(x, y)` of a target whose top-left lies at `origin` in the textures'
/// plane: its position in that plane, so that overlapping windows of one plane draw the same
/// numbers for the same pixel.
pub(crate) fn plane_key((x, y): (usize, usize), origin: (i64, i64)) -> u64 {
    let gx = (x as i64).wrapping_add(origin.0) as u32;
    let gy = (y as i64).wrapping_add(origin.1) as u32;
    (u64::from(gy) << 32) | u64::from(gx)
}

/// One iteration of the band's local search ([`crate::Params::band_local_search`]): every band
/// pixel (but those marked in `converged`, which keep their match) reads the field only as it
/// was when the iteration started (propagation from its four neighbours' matches, shifted:
/// Jacobi, not PatchMatch's scan order) and draws its random candidates within the level's
/// search radius from a stream keyed by its position in the textures' plane ([`plane_key`]). A
/// pixel's new match thus depends only on what lies within a patch of it, so two overlapping
/// windows of one map (a slippy map's tiles) find the same matches wherever both see that far
/// around a pixel.
pub(crate) fn local_band_iteration(
    level: &Level,
    field: &mut Field,
    previous: &mut Vec<u32>,
    occurrence: &Occurrence,
    streams: &SeedStreams,
    (origin, converged): ((i64, i64), Option<&[bool]>),
) {
    previous.clear();
    previous.extend_from_slice(&field.matches);
    specialize!(level, local_band_rows)(level, field, previous, occurrence, streams, (origin, converged));
}

/// [`local_band_iteration`] with the patch row length `ROW` (bytes) fixed at compile time, or 0.
fn local_band_rows<const ROW: usize>(
    level: &Level,
    field: &mut Field,
    previous: &[u32],
    occurrence: &Occurrence,
    streams: &SeedStreams,
    (origin, converged): ((i64, i64), Option<&[bool]>),
) {
    let pixel_streams = streams.stage("pixel");
    let rows = field.matches.par_chunks_mut(level.target_width).zip(field.costs.par_chunks_mut(level.target_width));
    rows.enumerate().for_each_init(
        || (OmegaDelta::new(level, None), Candidates::new()),
        |(delta, scratch), (y, (matches, costs))| {
            for x in 0..level.target_width {
                let t = y * level.target_width + x;
                // The band's own pixels: the patches around it that reach into it keep their
                // textures' matches (their centres lie in one segment, where those are right).
                if !level.in_domain(t) || converged.is_some_and(|c| c[t]) {
                    continue;
                }
                let start = previous[t];
                let mut best =
                    Best { centre: start, distance: costs[x], total: costs[x] + occurrence.cost(start, delta) };
                let here = (t, x, y);
                let propagated = propagated(level, previous, (x, y)).into_iter().flatten();
                if level.patch <= WHOLE_PATCH_SIDE {
                    scratch.propagate::<ROW>(level, (occurrence, delta), propagated, &mut best, here);
                } else {
                    for candidate in propagated {
                        best.consider::<ROW>(level, occurrence, delta, candidate, here);
                    }
                }
                let mut stream = pixel_streams.stream(plane_key((x, y), origin));
                scratch.random_search::<ROW>(level, occurrence, delta, &mut stream, &mut best, here);
                matches[x] = best.centre;
                costs[x] = best.distance;
            }
        },
    );
}

/// The band's propagation candidates of target pixel `(x, y)`: the matches of its four
/// neighbours in `previous` (left, right, above, below), each shifted back by the neighbour's
/// offset, where the neighbour is searched and the shifted centre valid.
#[inline(always)]
fn propagated(level: &Level, previous: &[u32], (x, y): (usize, usize)) -> [Option<u32>; 4] {
    let (width, height) = (level.target_width as i64, level.target_height as i64);
    let (x0, x1) = level.valid_x();
    let (y0, y1) = level.valid_y();
    [(-1_i64, 0_i64), (1, 0), (0, -1), (0, 1)].map(|(dx, dy)| {
        let (nx, ny) = (x as i64 + dx, y as i64 + dy);
        if nx < 0 || ny < 0 || nx >= width || ny >= height {
            return None;
        }
        let n = (ny * width + nx) as usize;
        if !level.is_active(n) {
            return None;
        }
        let (sx, sy) = level.source_xy(previous[n]);
        let (sx, sy) = (sx as i64 - dx, sy as i64 - dy);
        let valid = (x0 as i64..x1 as i64).contains(&sx) && (y0 as i64..y1 as i64).contains(&sy);
        valid.then(|| (sy as usize * level.source_width + sx as usize) as u32)
    })
}

impl Candidates {
    /// The band's propagated candidates of one pixel, for patches of at most
    /// [`WHOLE_PATCH_SIDE`]: the allowed ones other than the current match, by
    /// [`keep_best`](Self::keep_best) (the choice [`Best::consider`] makes one by one).
    #[inline(always)]
    fn propagate<const ROW: usize>(
        &mut self,
        level: &Level,
        (occurrence, delta): (&Occurrence, &OmegaDelta),
        propagated: impl Iterator<Item = u32>,
        best: &mut Best,
        (t, x, y): (usize, usize, usize),
    ) {
        let mut kept = 0;
        for candidate in propagated {
            if candidate != best.centre && level.allowed(t, candidate) {
                self.centres[kept] = candidate;
                self.penalties[kept] = occurrence.cost(candidate, delta);
                kept += 1;
            }
        }
        self.keep_best::<ROW>(level, kept, best, (x, y));
    }
}
