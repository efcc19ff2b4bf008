//! Variation post-processes (§3.3): parameter exchange between similar reference elements, and
//! position variation from the reference shift vectors.

use kurbo::Vec2;
use motif_core::random::Rng;
use motif_core::{Point, SeedStreams};

use crate::analysis::Analysis;
use crate::distribution::neighbourhood_size;
use crate::matching::Limits;
use crate::synthesis::Layout;

/// Parameter changes applied to one copied element, in its own frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exchange {
    /// Extra rotation about the element centre, radians.
    pub rotation: f64,
    /// Scale along the element's principal axis (new length over old).
    pub length_scale: f64,
    /// Scale along the secondary axis (new thickness over old).
    pub thickness_scale: f64,
    /// Added to every stroke colour (RGB unit cube).
    pub colour_shift: [f64; 3],
}

impl Default for Exchange {
    fn default() -> Self {
        Exchange { rotation: 0.0, length_scale: 1.0, thickness_scale: 1.0, colour_shift: [0.0; 3] }
    }
}

impl Exchange {
    /// True when it changes nothing.
    pub fn is_identity(&self) -> bool {
        *self == Exchange::default()
    }
}

/// Signed difference of two undirected axis angles, in `(-π/2, π/2]`.
fn axis_difference(to: f64, from: f64) -> f64 {
    let pi = std::f64::consts::PI;
    let d = (to - from).rem_euclid(pi);
    if d > 0.5 * pi { d - pi } else { d }
}

/// Parameter exchange (§3.3): for each copied element and each of its parameters independently
/// (orientation, length, thickness, colour), the reference values within `amount ×` that
/// parameter's matching threshold of the element's own value form a set; one is picked at random
/// and replaces it. `amount = 0` leaves every element unchanged; at 1 the exchanged values stay
/// within the perceptual thresholds, so elements never become too different from the reference.
pub(crate) fn exchange(
    assigned: &[u32],
    analysis: &Analysis,
    limits: &Limits,
    amount: f64,
    streams: &SeedStreams,
) -> Vec<Exchange> {
    if amount <= 0.0 {
        return vec![Exchange::default(); assigned.len()];
    }
    let frames: Vec<_> = (0..analysis.elements.len()).map(|i| analysis.pattern_frame(i)).collect();
    let colours: Vec<[f64; 3]> = analysis.elements.iter().map(|e| e.colour).collect();
    let tiny = 1e-6 * analysis.mean_length.max(1e-9);
    let mut pool: Vec<usize> = Vec::with_capacity(frames.len());
    assigned
        .iter()
        .enumerate()
        .map(|(index, &reference)| {
            let own = &frames[reference as usize];
            let mut stream = streams.stream("exchange", index as u64);
            let mut pick = |pool: &mut Vec<usize>, similar: &dyn Fn(usize) -> bool| -> usize {
                pool.clear();
                pool.extend((0..frames.len()).filter(|&j| analysis.is_usable(j) && similar(j)));
                if pool.is_empty() { reference as usize } else { pool[stream.random_range(0..pool.len())] }
            };
            let angle = own.angle();
            let j =
                pick(&mut pool, &|j| axis_difference(frames[j].angle(), angle).abs() <= amount * limits.parallelism);
            let rotation = axis_difference(frames[j].angle(), angle);
            let ratio_limit = 1.0 + amount * (limits.overlap - 1.0);
            let j = pick(&mut pool, &|j| {
                let (a, b) = (frames[j].length, own.length);
                a.max(b) <= ratio_limit * a.min(b)
            });
            let length_scale = if own.length > tiny { frames[j].length / own.length } else { 1.0 };
            let j =
                pick(&mut pool, &|j| (frames[j].thickness - own.thickness).abs() <= amount * limits.superimposition);
            let thickness_scale = if own.thickness > tiny && frames[j].thickness > tiny {
                frames[j].thickness / own.thickness
            } else {
                1.0
            };
            let own_colour = colours[reference as usize];
            let distance = |c: &[f64; 3]| c.iter().zip(&own_colour).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt();
            let j = pick(&mut pool, &|j| distance(&colours[j]) <= amount * limits.colour);
            let colour_shift = std::array::from_fn(|c| colours[j][c] - own_colour[c]);
            Exchange { rotation, length_scale, thickness_scale, colour_shift }
        })
        .collect()
}

/// Position variation (§3.3): every seed with n ≥ k neighbours (k = 2 along a path, 4 in a
/// region) moves, all at once, to the barycentre of its neighbours plus the shift vector of the
/// reference element copied there, scaled by the ratio of the neighbourhood sizes. The paper
/// prints the scale as `A_tar / (n A_ref)`; we use the linear size ratio (`A_tar / A_ref` along a
/// path, `√(A_tar / A_ref)` in a region), so that a target neighbourhood shaped like the
/// reference one reproduces the reference displacement, and the result is a length in 2D too.
/// Returns the new positions in pattern-frame coordinates (see [`Layout::coords`]).
pub(crate) fn shifted_coords(layout: &Layout, assigned: &[u32], analysis: &Analysis) -> Vec<Option<Point>> {
    let minimum = Analysis::shift_neighbours(analysis.along_path);
    let mut offsets: Vec<Vec2> = Vec::new();
    (0..layout.len())
        .map(|i| {
            let neighbours = layout.graph.neighbours(i);
            if neighbours.len() < minimum {
                return None;
            }
            offsets.clear();
            offsets.extend(neighbours.iter().map(|&j| layout.offset(i, j as usize)));
            let barycentre = offsets.iter().fold(Vec2::ZERO, |s, &o| s + o) / offsets.len() as f64;
            let reference = assigned[i] as usize;
            let shift = match analysis.shifts[reference] {
                Some(shift) if analysis.neighbourhood_sizes[reference] > 0.0 => {
                    let ratio =
                        neighbourhood_size(&offsets, analysis.along_path) / analysis.neighbourhood_sizes[reference];
                    shift * if analysis.along_path { ratio } else { ratio.sqrt() }
                }
                _ => Vec2::ZERO,
            };
            Some(layout.coords[i] + barycentre + shift)
        })
        .collect()
}
