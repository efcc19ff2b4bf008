//! Stitching (§3.2): aligning the right edge of piece `i` with the left edge of piece `i+1`
//! (Eq. 2–3), and the deformation that propagates the alignment inside the piece at render time.
//!
//! The table `M[s, t]` is the best cost of an alignment in which right-edge sample `t` faces
//! left-edge sample `s`:
//! `M[s,t] = min(M[s−1,t−1], M[s−1,t] + β, M[s,t−1] + β) + ξ(L[s], R[t])`, with `β = P` when
//! either sample is (partly) opaque, so that opaque segments are not stretched. We use ξ, the
//! alpha-aware cost of §1, for the per-sample term so that the alignment sees where the pattern
//! is (with equal alphas it is the paper's `‖L[s] − R[t]‖`). Backtracking gives, for every `s`, the
//! right sample `T[s]` read in front of it. Diagonal steps win ties, so edges that already match
//! keep `T = identity`, and the result is kept only if it lowers the seam cost: since the
//! identity path costs `D` and every `s` keeps one of its matched samples, stitching never
//! increases the seam cost.

use motif_core::Vec2;
use motif_core::vector;

use crate::cost::{CostModel, EdgeSet};
use crate::piece::PieceFrame;

/// The stitch of one seam: the remapping `T` and the seam cost before and after.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Stitch {
    /// `T[s]`: the right-edge sample shown in front of left-edge sample `s`.
    pub remap: Vec<usize>,
    /// Seam cost `D` without stitching (internal eighths).
    pub before: u64,
    /// Seam cost `Σ_s ξ(L[s], R[T[s]])` with stitching (internal eighths).
    pub after: u64,
}

impl Stitch {
    /// True when `T[s] = s` everywhere.
    pub(crate) fn is_identity(&self) -> bool {
        self.remap.iter().enumerate().all(|(s, &t)| s == t)
    }

    /// The identity stitch of a seam of `samples` samples and cost `cost`.
    pub(crate) fn identity(samples: usize, cost: u64) -> Self {
        Self { remap: (0..samples).collect(), before: cost, after: cost }
    }
}

/// Aligns right edge `r` of `rights` with left edge `l` of `lefts` (Eq. 2–3) with penalty `penalty`
/// (paper units; the paper uses P = 32).
pub(crate) fn align(model: &CostModel, rights: &EdgeSet, r: usize, lefts: &EdgeSet, l: usize, penalty: f64) -> Stitch {
    let c = rights.samples;
    let beta = (penalty * crate::cost::COST_SCALE).round() as u64;
    let right: Vec<[u8; 4]> = (0..c).map(|k| rights.sample(r, k)).collect();
    let left: Vec<[u8; 4]> = (0..c).map(|k| lefts.sample(l, k)).collect();
    let xi = |s: usize, t: usize| u64::from(model.xi(left[s], right[t]));
    let before: u64 = (0..c).map(|k| xi(k, k)).sum();
    let step = |s: usize, t: usize| if left[s][3] > 0 || right[t][3] > 0 { beta } else { 0 };
    let mut table = vec![0_u64; c * c];
    for s in 0..c {
        for t in 0..c {
            let here = xi(s, t);
            let best = match (s, t) {
                (0, 0) => 0,
                (0, _) => table[t - 1] + step(s, t),
                (_, 0) => table[(s - 1) * c] + step(s, t),
                _ => table[(s - 1) * c + t - 1]
                    .min(table[(s - 1) * c + t] + step(s, t))
                    .min(table[s * c + t - 1] + step(s, t)),
            };
            table[s * c + t] = best + here;
        }
    }
    // Backtrack from (C−1, C−1), diagonal first on ties; keep for each s its cheapest matched t.
    let mut remap: Vec<Option<usize>> = vec![None; c];
    let (mut s, mut t) = (c - 1, c - 1);
    loop {
        let keep = match remap[s] {
            Some(previous) => (xi(s, t), t.abs_diff(s)) < (xi(s, previous), previous.abs_diff(s)),
            None => true,
        };
        if keep {
            remap[s] = Some(t);
        }
        if s == 0 && t == 0 {
            break;
        }
        let value = table[s * c + t] - xi(s, t);
        if s > 0 && t > 0 && table[(s - 1) * c + t - 1] == value {
            (s, t) = (s - 1, t - 1);
        } else if s > 0 && table[(s - 1) * c + t] + step(s, t) == value {
            s -= 1;
        } else {
            t -= 1;
        }
    }
    let remap: Vec<usize> = remap.into_iter().map(|t| t.expect("every s is on the path")).collect();
    let after: u64 = remap.iter().enumerate().map(|(s, &t)| xi(s, t)).sum();
    if after < before { Stitch { remap, before, after } } else { Stitch::identity(c, before) }
}

/// The deformed local lookup of point `p` (local exemplar coordinates of piece `frame`) under the
/// stitch remapping `remap` (§3.2, "Propagation"): the direction `d` is interpolated between the
/// top and bottom edge directions by the height of `p`, `p` is projected along `d` onto the right
/// edge at distance `λ`, and the lookup moves by `x/(x + r) · (T(λ) − λ) · w`, where `x` and `r`
/// are the distances to the left and right edges along `d`.
pub(crate) fn deform(frame: &PieceFrame, remap: &[usize], p: Vec2) -> Vec2 {
    let top = frame.top_right;
    let bottom = frame.bottom_right - Vec2::new(0.0, frame.height);
    if vector::length(top) < 1e-9 || vector::length(bottom) < 1e-9 {
        return p;
    }
    let height_fraction = (p.y / frame.height).clamp(0.0, 1.0);
    let d = vector::normalized(top).lerp(vector::normalized(bottom), height_fraction);
    if d.x.abs() < 1e-9 {
        return p;
    }
    let w = frame.right_direction;
    // p + r·d = top_right + λ·w
    let det = -d.x * w.y + w.x * d.y;
    if det.abs() < 1e-12 {
        return p;
    }
    let q = frame.top_right - p;
    let r = (-q.x * w.y + w.x * q.y) / det;
    let lambda = (d.x * q.y - d.y * q.x) / det;
    let x = p.x / d.x;
    if x < 0.0 || r < 0.0 || x + r <= 1e-9 {
        return p;
    }
    // T is defined at samples λ_k = k + 0.5: shift Δ(λ) = T(λ) − λ, interpolated linearly.
    let position = (lambda - 0.5).clamp(0.0, (remap.len() - 1) as f64);
    let k = position.floor() as usize;
    let fraction = position - k as f64;
    let delta_at = |k: usize| remap[k] as f64 - k as f64;
    let delta =
        if k + 1 < remap.len() { delta_at(k) * (1.0 - fraction) + delta_at(k + 1) * fraction } else { delta_at(k) };
    p + w * (x / (x + r) * delta)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cost::AlphaMode;

    fn edges(columns: &[Vec<[u8; 4]>]) -> EdgeSet {
        let mut set = EdgeSet::default();
        set.samples = columns[0].len();
        set.stride = set.samples.div_ceil(16) * 16;
        set.words = set.samples.div_ceil(64);
        for column in columns {
            let start = set.planes.len();
            set.planes.resize(start + 4 * set.stride, 0);
            set.masks.resize(set.masks.len() + 2 * set.words, 0);
            for (k, pixel) in column.iter().enumerate() {
                for (c, &value) in pixel.iter().enumerate() {
                    set.planes[start + c * set.stride + k] = value;
                }
            }
        }
        set
    }

    fn bar(from: usize, to: usize, len: usize) -> Vec<[u8; 4]> {
        (0..len).map(|k| if (from..to).contains(&k) { [200, 50, 50, 255] } else { [0; 4] }).collect()
    }

    #[test]
    fn matching_edges_keep_the_identity() {
        let model = CostModel::new(AlphaMode::Binary, 1024.0);
        let set = edges(&[bar(5, 12, 20)]);
        let stitch = align(&model, &set, 0, &set, 0, 32.0);
        assert!(stitch.is_identity());
        assert_eq!(stitch.before, 0);
        assert_eq!(stitch.after, 0);
    }

    #[test]
    fn shifted_bars_are_aligned_and_cost_drops() {
        let model = CostModel::new(AlphaMode::Binary, 1024.0);
        let rights = edges(&[bar(7, 14, 24)]);
        let lefts = edges(&[bar(5, 12, 24)]);
        let stitch = align(&model, &rights, 0, &lefts, 0, 32.0);
        assert!(stitch.after < stitch.before, "{stitch:?}");
        assert_eq!(stitch.remap[6], 8, "{:?}", stitch.remap);
        assert!(stitch.remap.windows(2).all(|w| w[0] <= w[1]), "monotone");
    }
}
