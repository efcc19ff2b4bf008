//! The exemplar's own term `C_k(m) = Σ_{j,j'} b_j·b_j' K(v_j, v_j')` (the third sum of Eq. 5), pair
//! by pair.
//!
//! The matching step evaluates `C_k` at several candidate locations `m` of every quadrature point.
//! The kernel of an exemplar pair depends on `m` only through the window at the pair's midpoint: `K = pair(s²|e_j − e_j'|²) · window(s²|mid − m|²)`. So the pairs
//! within the cut-off are listed once, with their midpoints, the product of their features and the
//! pair factor at scale 1, and `C_k(m)` is a sum over the midpoints within the window's reach — one
//! exponential per pair instead of a neighbour walk with two per ordered pair.

use crate::grid::CellLists;
use crate::linear::{self, Vector};
use crate::model::{Exemplar, Kernel, feature_dot};
use motif_core::math;

/// The exemplar's pairs within the pair cut-off (each unordered pair once, and each point with
/// itself), for the Gaussian-window `C_k`.
#[derive(Debug, Clone)]
pub(crate) struct ExemplarPairs<const D: usize> {
    /// Pair midpoints, queried by distance.
    mids: CellLists<D>,
    /// `|e_j − e_j'|²` per pair.
    distance2: Vec<f64>,
    /// `b_j·b_j'` times the pair's multiplicity in the sum (2 for two points, 1 for a point with itself).
    weight: Vec<f64>,
    /// The pair's two exemplar points (for masking).
    ends: Vec<(u32, u32)>,
    /// Exemplar points.
    points: usize,
}

impl<const D: usize> ExemplarPairs<D> {
    /// The pairs of `exemplar` closer than `cutoff` (in exemplar units), for window reaches up to `reach`.
    pub(crate) fn new(exemplar: &Exemplar<D>, neighbours: &crate::grid::Neighbours, cutoff: f64, reach: f64) -> Self {
        let mut mids = Vec::new();
        let mut distance2 = Vec::new();
        let mut weight = Vec::new();
        let mut ends = Vec::new();
        for (j, e) in exemplar.positions.iter().enumerate() {
            let b = exemplar.feature(j);
            mids.push(*e);
            distance2.push(0.0);
            weight.push(feature_dot(b, b));
            ends.push((j as u32, j as u32));
            for &o in neighbours.of(j) {
                let o = o as usize;
                let other = &exemplar.positions[o];
                let d2 = linear::norm2(&linear::sub(e, other));
                if o < j || d2 >= cutoff * cutoff {
                    continue;
                }
                mids.push(std::array::from_fn(|c| 0.5 * (e[c] + other[c])));
                distance2.push(d2);
                weight.push(2.0 * feature_dot(b, exemplar.feature(o)));
                ends.push((j as u32, o as u32));
            }
        }
        Self { mids: CellLists::new(&mids, reach), distance2, weight, ends, points: exemplar.positions.len() }
    }

    /// `C(m)` at scale `s`, adding `∂C/∂m` to `gradient` when given. With `keep`, only pairs whose
    /// two points it accepts take part (masking: exemplar points whose place in the output falls
    /// outside Ω); each point is asked once.
    pub(crate) fn exemplar_self(
        &self,
        kernel: &Kernel,
        s: f64,
        m: &Vector<D>,
        found: &mut Vec<(u32, f64)>,
        keep: Option<&dyn Fn(usize) -> bool>,
        gradient: Option<&mut Vector<D>>,
    ) -> f64 {
        // Per exemplar point: 0 not asked yet, 1 kept, 2 masked.
        let mut verdicts = if keep.is_some() { vec![0u8; self.points] } else { Vec::new() };
        let mut kept = |j: u32| match keep {
            None => true,
            Some(keep) => {
                let verdict = &mut verdicts[j as usize];
                if *verdict == 0 {
                    *verdict = if keep(j as usize) { 1 } else { 2 };
                }
                *verdict == 1
            }
        };
        let s2 = s * s;
        let reach = kernel.window_radius / s;
        let count = self.mids.collect_within(m, reach, found);
        let mut total = 0.0;
        let mut g = [0.0; D];
        for &(p, mid_distance2) in &found[..count] {
            let p = p as usize;
            let d2 = s2 * self.distance2[p];
            if d2 >= kernel.cutoff2 {
                continue;
            }
            let (j, o) = self.ends[p];
            if !(kept(j) && kept(o)) {
                continue;
            }
            let pair = math::exp(-d2 * kernel.half_inv_sigma2) - kernel.pair_floor;
            let window_exp = math::exp(-s2 * mid_distance2 * kernel.inv_delta_prime2);
            let weight = self.weight[p];
            total += weight * pair * (window_exp - kernel.window_floor);
            if gradient.is_some() {
                // ∂/∂m of the window at s²|mid − m|²: 2 s²/δ'² (mid − m) window.
                let factor = 2.0 * weight * pair * window_exp * s2 * kernel.inv_delta_prime2;
                let mid = self.mids.position(p);
                for c in 0..D {
                    g[c] += factor * (mid[c] - m[c]);
                }
            }
        }
        if let Some(gradient) = gradient {
            linear::axpy(gradient, 1.0, &g);
        }
        total
    }
}
