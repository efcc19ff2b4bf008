//! The matching cost ξ and the edge distance `D` (§1, §1.3).
//!
//! ξ compares two RGBA pixels. With binary alpha it is the paper's function: `‖p − q‖` (RGB,
//! 0..255) when both are opaque or both transparent, `γ` otherwise. The continuous variant (the
//! paper's "continuous cost in case of semi-transparent pixels") blends the two cases by the
//! alpha difference: with `a, b ∈ [0, 1]`, `ξ = (1 − |a − b|)·‖p − q‖ + |a − b|·γ`. It equals the
//! paper's ξ for alphas 0 and 1, and identical pixels cost 0 whatever their alpha (so a periodic
//! anti-aliased exemplar can still join seamlessly). Binary mode thresholds alpha at 128 first,
//! so both modes share one formula.
//!
//! Costs are fixed-point integers in eighths of the paper's unit. Summing integers is exact in
//! any order, so the reference solver, the fast solver's chunked early-exit sums and the
//! brute-force enumerator all see bit-identical `D` values, and "the fast optimum equals the
//! reference optimum" is an exact statement.
//!
//! `D` sums ξ over the `C` samples of a right edge (bilinear along the tilted edge of piece `i`)
//! and a left edge (a column of piece `i+1`). Edges are stored as planes of bytes, with two
//! bit masks per edge ("solid": alpha ≥ 224, "clear": alpha ≤ 31) that give a cheap exact lower
//! bound: every pixel where one edge is solid and the other clear costs at least
//! [`CostModel::mask_weight`].

use rayon::prelude::*;
use serde::Serialize;

use crate::bounds::bound_of_distances;
use crate::exemplar::Exemplar;
use crate::piece::{PieceFrame, Position};

/// Fixed-point scale of costs: one unit of the paper's ξ is 8 internal units.
pub(crate) const COST_SCALE: f64 = 8.0;

/// How alpha enters the matching cost ξ.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AlphaMode {
    /// The paper's ξ: alpha thresholded at 128 (opaque or transparent).
    Binary,
    /// ξ blended by alpha, for anti-aliased and semi-transparent exemplars.
    Continuous,
}

/// The parameters of ξ, in the internal fixed-point unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CostModel {
    /// Binary or continuous alpha.
    pub mode: AlphaMode,
    /// `γ` (paper unit).
    pub gamma: f64,
    gamma_scaled: f32,
    /// `⌊8γ⌋`, for integer lower bounds.
    gamma_floor: u64,
}

impl CostModel {
    /// ξ with mismatch penalty `gamma` (the paper uses 1024).
    pub(crate) fn new(mode: AlphaMode, gamma: f64) -> Self {
        Self {
            mode,
            gamma,
            gamma_scaled: (gamma * COST_SCALE) as f32,
            gamma_floor: (gamma * COST_SCALE).floor() as u64,
        }
    }

    /// The alpha used for matching: thresholded in binary mode.
    #[inline]
    pub(crate) fn matching_alpha(&self, alpha: u8) -> u8 {
        match self.mode {
            AlphaMode::Binary => {
                if alpha >= 128 {
                    255
                } else {
                    0
                }
            }
            AlphaMode::Continuous => alpha,
        }
    }

    /// ξ of two pixels whose alphas already went through [`matching_alpha`](Self::matching_alpha),
    /// in eighths.
    #[inline(always)]
    pub(crate) fn xi(&self, p: [u8; 4], q: [u8; 4]) -> u32 {
        self.xi_lane(p[0], p[1], p[2], p[3], q[0], q[1], q[2], q[3])
    }

    /// ξ on separate channels (the form the vectorized edge comparison uses).
    #[inline(always)]
    #[allow(
        clippy::too_many_arguments,
        reason = "one lane per channel, the form the vectorized comparison compiles to"
    )]
    fn xi_lane(&self, pr: u8, pg: u8, pb: u8, pa: u8, qr: u8, qg: u8, qb: u8, qa: u8) -> u32 {
        let dr = i32::from(pr) - i32::from(qr);
        let dg = i32::from(pg) - i32::from(qg);
        let db = i32::from(pb) - i32::from(qb);
        let distance = ((dr * dr + dg * dg + db * db) as f32).sqrt();
        let difference = (i32::from(pa) - i32::from(qa)).abs() as f32;
        let value =
            ((255.0 - difference) * (distance * COST_SCALE as f32) + difference * self.gamma_scaled) * (1.0 / 255.0);
        (value + 8_388_608.0).to_bits() & 0x7f_ffff
    }

    /// `⌊8γ⌋`, in internal units.
    pub(crate) fn gamma_floor(&self) -> u64 {
        self.gamma_floor
    }

    /// Whether colour differences add to the alpha bound (γ ≥ 442, the largest RGB distance).
    #[inline]
    pub(crate) fn colour_bounds(&self) -> bool {
        self.gamma >= 442.0
    }

    /// A lower bound of ξ for a pixel where one edge is solid (alpha ≥ 224) and the other clear
    /// (alpha ≤ 31): their alpha difference is at least 193 (255 in binary mode). One unit is kept
    /// for float rounding.
    pub(crate) fn mask_weight(&self) -> u32 {
        let least_difference = match self.mode {
            AlphaMode::Binary => 255.0,
            AlphaMode::Continuous => 193.0,
        };
        ((f64::from(self.gamma_scaled) * least_difference / 255.0).floor() as u32).saturating_sub(1)
    }
}

/// Edges (columns of `C` samples) at many positions, as byte planes plus solid/clear masks.
#[derive(Debug, Clone, Default)]
pub(crate) struct EdgeSet {
    /// Samples per edge, `C`.
    pub samples: usize,
    /// `C` rounded up to a multiple of 16 (the planes' stride; padding is zero in every plane).
    pub stride: usize,
    /// Per edge: red, green, blue and matching alpha planes, each `stride` bytes.
    pub planes: Vec<u8>,
    /// 64-bit words per mask.
    pub words: usize,
    /// Per edge: `words` words of the solid mask, then `words` of the clear mask.
    pub masks: Vec<u64>,
    /// Profile entries per channel: `⌈C / 4⌉` rounded up to a multiple of 8.
    pub profile_len: usize,
    /// Per edge: for red, green, blue and alpha, the sums of 4 consecutive samples
    /// (`profile_len` entries per channel, zero padded).
    pub profiles: Vec<u16>,
}

impl EdgeSet {
    pub(crate) fn with_capacity(samples: usize, count: usize) -> Self {
        let stride = samples.div_ceil(16) * 16;
        let words = samples.div_ceil(64);
        let profile_len = samples.div_ceil(4).div_ceil(8) * 8;
        Self {
            samples,
            stride,
            planes: Vec::with_capacity(count * 4 * stride),
            words,
            masks: Vec::with_capacity(count * 2 * words),
            profile_len,
            profiles: Vec::with_capacity(count * 4 * profile_len),
        }
    }

    /// Number of edges.
    pub(crate) fn len(&self) -> usize {
        if self.stride == 0 { 0 } else { self.planes.len() / (4 * self.stride) }
    }

    /// Appends one edge (tests build small sets this way).
    #[cfg(test)]
    pub(crate) fn push(&mut self, samples: impl Iterator<Item = [u8; 4]>) {
        let column: Vec<[u8; 4]> = samples.take(self.samples).collect();
        let (plane_start, mask_start, profile_start) = (self.planes.len(), self.masks.len(), self.profiles.len());
        self.planes.resize(plane_start + 4 * self.stride, 0);
        self.masks.resize(mask_start + 2 * self.words, 0);
        self.profiles.resize(profile_start + 4 * self.profile_len, 0);
        write_edge(
            &column,
            &mut self.planes[plane_start..],
            &mut self.masks[mask_start..],
            &mut self.profiles[profile_start..],
            [self.stride, self.words, self.profile_len],
        );
    }

    /// `count` edges of `samples` samples, where `fill(index, column)` writes the samples of edge
    /// `index`. Edges are independent, so they are extracted in parallel (a row has thousands of
    /// positions; extracting them one by one took as long as the whole search).
    fn from_fn(samples: usize, count: usize, fill: impl Fn(usize, &mut [[u8; 4]]) + Sync) -> Self {
        let mut set = Self::with_capacity(samples, 0);
        if samples == 0 || count == 0 {
            return set;
        }
        let layout = [set.stride, set.words, set.profile_len];
        set.planes = vec![0; count * 4 * set.stride];
        set.masks = vec![0; count * 2 * set.words];
        set.profiles = vec![0; count * 4 * set.profile_len];
        set.planes
            .par_chunks_mut(4 * set.stride)
            .zip(set.masks.par_chunks_mut(2 * set.words))
            .zip(set.profiles.par_chunks_mut(4 * set.profile_len))
            .enumerate()
            .for_each_init(
                || vec![[0_u8; 4]; samples],
                |column, (index, ((planes, masks), profiles))| {
                    fill(index, column);
                    write_edge(column, planes, masks, profiles, layout);
                },
            );
        set
    }

    /// The four planes of edge `index`.
    #[inline]
    pub(crate) fn planes_of(&self, index: usize) -> &[u8] {
        &self.planes[index * 4 * self.stride..(index + 1) * 4 * self.stride]
    }

    /// Solid and clear masks of edge `index`.
    #[inline]
    pub(crate) fn masks_of(&self, index: usize) -> (&[u64], &[u64]) {
        let start = index * 2 * self.words;
        (&self.masks[start..start + self.words], &self.masks[start + self.words..start + 2 * self.words])
    }

    /// The block-sum profile of edge `index` (red, green, blue, alpha).
    #[inline]
    pub(crate) fn profile_of(&self, index: usize) -> &[u16] {
        &self.profiles[index * 4 * self.profile_len..(index + 1) * 4 * self.profile_len]
    }

    /// Sample `k` of edge `index` as RGBA.
    pub(crate) fn sample(&self, index: usize, k: usize) -> [u8; 4] {
        let planes = self.planes_of(index);
        [planes[k], planes[self.stride + k], planes[2 * self.stride + k], planes[3 * self.stride + k]]
    }

    /// The edges with every run of `factor` consecutive samples averaged into one (`⌈C / factor⌉`
    /// samples; the last run may be shorter), alpha through `model`'s matching alpha again: the
    /// coarse solver's edges (see `coarse`). Averaging keeps what a run holds, so a one-pixel
    /// shift along the edge changes the coarse edge little.
    pub(crate) fn downsampled(&self, model: &CostModel, factor: usize) -> EdgeSet {
        let factor = factor.max(1);
        let samples = self.samples.div_ceil(factor);
        EdgeSet::from_fn(samples, self.len(), |index, column| {
            for (k, out) in column.iter_mut().enumerate() {
                let run = k * factor..((k + 1) * factor).min(self.samples);
                let count = run.len() as u32;
                let mut sum = [0_u32; 4];
                for s in run {
                    for (total, value) in sum.iter_mut().zip(self.sample(index, s)) {
                        *total += u32::from(value);
                    }
                }
                let [r, g, b, a] = sum.map(|total| ((total + count / 2) / count) as u8);
                *out = [r, g, b, model.matching_alpha(a)];
            }
        })
    }

    /// The edges reordered by `order` (used to stream predecessors in cost order).
    pub(crate) fn permuted(&self, order: &[u32]) -> EdgeSet {
        let mut out = EdgeSet::with_capacity(self.samples, order.len());
        for &index in order {
            out.planes.extend_from_slice(self.planes_of(index as usize));
            let start = index as usize * 2 * self.words;
            out.masks.extend_from_slice(&self.masks[start..start + 2 * self.words]);
            out.profiles.extend_from_slice(self.profile_of(index as usize));
        }
        out
    }
}

/// Writes one edge's planes, masks and profiles into zeroed storage laid out as
/// `[stride, words, profile_len]`. Padding samples stay transparent black in every plane and
/// "clear" in no mask, so they never count as a mismatch.
fn write_edge(column: &[[u8; 4]], planes: &mut [u8], masks: &mut [u64], profiles: &mut [u16], layout: [usize; 3]) {
    let [stride, words, profile_len] = layout;
    let samples = column.len();
    for (channel, plane) in planes.chunks_exact_mut(stride).enumerate() {
        for (out, pixel) in plane.iter_mut().zip(column) {
            *out = pixel[channel];
        }
        let profile = &mut profiles[channel * profile_len..(channel + 1) * profile_len];
        // Whole blocks of the zero-padded plane: the padding adds nothing.
        for (sum, block) in profile.iter_mut().zip(plane.chunks_exact(4)) {
            let block: &[u8; 4] = block.try_into().expect("4 samples");
            *sum = block.map(u16::from).iter().sum();
        }
    }
    let alpha = &planes[3 * stride..3 * stride + samples];
    let (solid, clear) = masks[..2 * words].split_at_mut(words);
    for (w, block) in alpha.chunks(64).enumerate() {
        // Fixed 64 lanes so the comparisons vectorize; 128 is neither solid nor clear.
        let mut lanes = [128_u8; 64];
        lanes[..block.len()].copy_from_slice(block);
        let (mut solid_bits, mut clear_bits) = (0_u64, 0_u64);
        for (bit, &a) in lanes.iter().enumerate() {
            solid_bits |= u64::from(a >= 224) << bit;
            clear_bits |= u64::from(a <= 31) << bit;
        }
        (solid[w], clear[w]) = (solid_bits, clear_bits);
    }
}

/// Left edges `L` (exemplar columns of `C` pixels starting at `u`) for every position.
pub(crate) fn left_edges(exemplar: &Exemplar, model: &CostModel, positions: &[Position], samples: usize) -> EdgeSet {
    EdgeSet::from_fn(samples, positions.len(), |index, column| {
        let [x, y] = positions[index];
        let pixels = exemplar.rgba[exemplar.index(x, y)..].iter().step_by(exemplar.stride);
        for (out, &pixel) in column.iter_mut().zip(pixels) {
            *out = [pixel[0], pixel[1], pixel[2], model.matching_alpha(pixel[3])];
        }
    })
}

/// Right edges `R` (bilinear samples along the tilted right edge of `frame`) for every position.
/// Colours are interpolated premultiplied, so transparent neighbours do not darken an edge.
pub(crate) fn right_edges(
    exemplar: &Exemplar,
    model: &CostModel,
    frame: &PieceFrame,
    positions: &[Position],
) -> EdgeSet {
    EdgeSet::from_fn(frame.samples, positions.len(), |index, column| {
        let [x, y] = positions[index];
        let base = exemplar.index(x, y);
        let row = exemplar.stride;
        for (tap, out) in frame.right_taps.iter().zip(column.iter_mut()) {
            // The four bilinear neighbours, read around one index (the padding keeps them inside).
            let at = base.wrapping_add_signed(tap.dy as isize * row as isize + tap.dx as isize);
            let neighbours =
                [exemplar.rgba[at], exemplar.rgba[at + 1], exemplar.rgba[at + row], exemplar.rgba[at + row + 1]];
            *out = if neighbours[1..].iter().all(|&pixel| pixel == neighbours[0]) {
                // A flat neighbourhood (empty or solid regions, most of a pattern) interpolates to
                // itself: the float sums below land within 10⁻³ of its integer channels, which
                // rounding to bytes removes, so skipping them gives the same bytes.
                let [r, g, b, a] = neighbours[0];
                if a == 0 { [0, 0, 0, 0] } else { [r, g, b, model.matching_alpha(a)] }
            } else {
                bilinear(model, neighbours, tap.weights)
            };
        }
    })
}

/// One right-edge sample from its four neighbours, interpolated premultiplied.
#[inline]
fn bilinear(model: &CostModel, neighbours: [[u8; 4]; 4], weights: [f32; 4]) -> [u8; 4] {
    let mut sum = [0.0_f32; 4];
    for (pixel, weight) in neighbours.into_iter().zip(weights) {
        let alpha = f32::from(pixel[3]) * weight;
        sum[0] += f32::from(pixel[0]) * alpha;
        sum[1] += f32::from(pixel[1]) * alpha;
        sum[2] += f32::from(pixel[2]) * alpha;
        sum[3] += alpha;
    }
    if sum[3] <= 0.0 {
        return [0, 0, 0, 0];
    }
    // The same divisions as one lane-wise operation (the lane results are identical).
    let [r, g, b, _] = [sum[0], sum[1], sum[2], 1.0].map(|v| v / sum[3]);
    let byte = |v: f32| (v.clamp(0.0, 255.0) + 0.5) as u8;
    [byte(r), byte(g), byte(b), model.matching_alpha(byte(sum[3]))]
}

/// `D`: the sum of ξ over the samples of right edge `r` of `rights` and left edge `l` of `lefts`.
#[inline]
pub(crate) fn edge_distance(model: &CostModel, rights: &EdgeSet, r: usize, lefts: &EdgeSet, l: usize) -> u32 {
    let (a, b) = (rights.planes_of(r), lefts.planes_of(l));
    let stride = rights.stride;
    let mut total = 0_u32;
    for chunk in 0..stride / 16 {
        total += chunk_cost(model, a, b, stride, chunk * 16);
    }
    total
}

/// `D`, stopping as soon as the partial sum plus a lower bound of the rest exceeds `limit`
/// (returns `None` then). `profile_distances` are the L1 distances (colour, alpha) of the two
/// edges' whole profiles; each chunk of 16 samples covers 4 block sums per channel, so the bound
/// of the chunks still to come is that of the distances less those of the chunks done (samples
/// are compared in the order of [`edge_distance`], so a completed sum is identical).
#[inline]
pub(crate) fn edge_distance_bounded(
    model: &CostModel,
    rights: &EdgeSet,
    r: usize,
    lefts: &EdgeSet,
    l: usize,
    limit: u64,
    profile_distances: (u32, u32),
) -> Option<u32> {
    let (a, b) = (rights.planes_of(r), lefts.planes_of(l));
    let (right_profile, left_profile) = (rights.profile_of(r), lefts.profile_of(l));
    let (len, stride, samples) = (rights.profile_len, rights.stride, rights.samples);
    let colour_bounds = model.colour_bounds();
    let (mut colour_rest, mut alpha_rest) = profile_distances;
    let mut total = 0_u32;
    for chunk in 0..stride / 16 {
        total += chunk_cost(model, a, b, stride, chunk * 16);
        let entries = |channel: usize| channel * len + 4 * chunk..channel * len + 4 * chunk + 4;
        alpha_rest -= l1_small(&right_profile[entries(3)], &left_profile[entries(3)]);
        if colour_bounds {
            for channel in 0..3 {
                colour_rest -= l1_small(&right_profile[entries(channel)], &left_profile[entries(channel)]);
            }
        }
        let samples_rest = samples.saturating_sub(16 * (chunk + 1));
        if u64::from(total) + bound_of_distances(model, colour_rest, alpha_rest, samples_rest) > limit {
            return None;
        }
    }
    Some(total)
}

/// L1 distance of two short `u16` slices.
#[inline(always)]
fn l1_small(a: &[u16], b: &[u16]) -> u32 {
    a.iter().zip(b).map(|(&x, &y)| u32::from(x.abs_diff(y))).sum()
}

/// ξ summed over 16 consecutive samples; written on fixed-size lanes without bounds checks or
/// saturating float casts so that the compiler vectorizes it. The rounding adds 2²³ and reads the
/// mantissa, which rounds to nearest for values below 2²³ (ξ is at most 8·(442 + γ) < 2²³).
/// Padding samples are transparent black in both edges and cost 0.
#[inline(always)]
fn chunk_cost(model: &CostModel, a: &[u8], b: &[u8], stride: usize, start: usize) -> u32 {
    let lanes = |planes: &[u8], channel: usize| -> [u8; 16] {
        let from = channel * stride + start;
        planes[from..from + 16].try_into().expect("16 lanes")
    };
    let (ar, ag, ab, aa) = (lanes(a, 0), lanes(a, 1), lanes(a, 2), lanes(a, 3));
    let (br, bg, bb, ba) = (lanes(b, 0), lanes(b, 1), lanes(b, 2), lanes(b, 3));
    let mut total = [0_u32; 16];
    for k in 0..16 {
        total[k] = model.xi_lane(ar[k], ag[k], ab[k], aa[k], br[k], bg[k], bb[k], ba[k]);
    }
    total.iter().sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bounds::{mask_bound, profile_bound, profile_distances};

    #[test]
    fn xi_matches_the_paper_for_binary_alpha() {
        let model = CostModel::new(AlphaMode::Binary, 1024.0);
        assert_eq!(model.xi([10, 20, 30, 255], [10, 20, 30, 255]), 0);
        assert_eq!(model.xi([0, 0, 0, 255], [3, 4, 0, 255]), 40, "‖(3,4,0)‖ = 5 → 40 eighths");
        assert_eq!(model.xi([0, 0, 0, 0], [3, 4, 0, 0]), 40, "both transparent compare colours");
        assert_eq!(model.xi([0, 0, 0, 255], [0, 0, 0, 0]), 8192, "γ = 1024");
        assert!(u64::from(model.mask_weight()) <= 8192);
    }

    #[test]
    fn continuous_xi_blends_and_respects_the_mask_bound() {
        let model = CostModel::new(AlphaMode::Continuous, 1024.0);
        let half = model.xi([0, 0, 0, 128], [0, 0, 0, 255]);
        assert!(half > 3000 && half < 5000, "{half}");
        assert_eq!(model.xi([200, 100, 50, 90], [200, 100, 50, 90]), 0, "identical pixels match");
        for a in 224..=255_u8 {
            for b in 0..=31_u8 {
                for colour in [[0, 0, 0], [255, 255, 255]] {
                    let p = [colour[0], colour[1], colour[2], a];
                    assert!(model.xi(p, [0, 0, 0, b]) >= model.mask_weight());
                    assert!(model.xi([0, 0, 0, b], p) >= model.mask_weight());
                }
            }
        }
    }

    #[test]
    fn bounded_distance_agrees_with_the_full_sum() {
        let model = CostModel::new(AlphaMode::Continuous, 1024.0);
        let mut a = EdgeSet::with_capacity(40, 2);
        let mut b = EdgeSet::with_capacity(40, 2);
        a.push((0..40).map(|k| [k as u8 * 3, 7, 9, if k < 20 { 255 } else { 0 }]));
        b.push((0..40).map(|k| [k as u8, 70, 9, if k < 25 { 255 } else { 10 }]));
        let full = edge_distance(&model, &a, 0, &b, 0);
        assert_eq!(
            edge_distance_bounded(
                &model,
                &a,
                0,
                &b,
                0,
                u64::from(full),
                profile_distances(a.profile_of(0), b.profile_of(0))
            ),
            Some(full)
        );
        assert_eq!(
            edge_distance_bounded(
                &model,
                &a,
                0,
                &b,
                0,
                u64::from(full) - 1,
                profile_distances(a.profile_of(0), b.profile_of(0))
            ),
            None
        );
        let bound = mask_bound(model.mask_weight(), a.masks_of(0), b.masks_of(0));
        assert!(bound <= u64::from(full) && bound > 0);
        let profile = profile_bound(&model, a.profile_of(0), b.profile_of(0), 40);
        assert!(profile <= u64::from(full) && profile > 0, "{profile} {full}");
    }

    #[test]
    fn downsampled_edges_average_runs_of_samples() {
        let model = CostModel::new(AlphaMode::Continuous, 1024.0);
        let mut set = EdgeSet::with_capacity(5, 1);
        set.push([[10, 0, 0, 255], [20, 0, 0, 255], [30, 0, 0, 0], [41, 0, 0, 0], [7, 8, 9, 100]].into_iter());
        let same = set.downsampled(&model, 1);
        assert_eq!(same.planes, set.planes);
        let half = set.downsampled(&model, 2);
        assert_eq!(half.samples, 3);
        assert_eq!(
            (0..3).map(|k| half.sample(0, k)).collect::<Vec<_>>(),
            [[15, 0, 0, 255], [36, 0, 0, 0], [7, 8, 9, 100]]
        );
        let binary = CostModel::new(AlphaMode::Binary, 1024.0);
        let mut mixed = EdgeSet::with_capacity(2, 1);
        mixed.push([[0, 0, 0, 255], [0, 0, 0, 0]].into_iter());
        assert_eq!(mixed.downsampled(&binary, 2).sample(0, 0)[3], 255, "binary alpha thresholds the average again");
    }

    proptest::proptest! {
        /// The flat-neighbourhood shortcut of `right_edges` gives the bytes of the full
        /// interpolation, for any pixel, weights and alpha mode.
        #[test]
        fn flat_neighbourhoods_interpolate_to_themselves(
            pixel in proptest::prelude::any::<[u8; 4]>(),
            tx in 0.0_f32..1.0,
            ty in 0.0_f32..1.0,
            binary in proptest::prelude::any::<bool>(),
        ) {
            let model = CostModel::new(if binary { AlphaMode::Binary } else { AlphaMode::Continuous }, 1024.0);
            let weights = [(1.0 - tx) * (1.0 - ty), tx * (1.0 - ty), (1.0 - tx) * ty, tx * ty];
            let shortcut = if pixel[3] == 0 { [0; 4] } else { [pixel[0], pixel[1], pixel[2], model.matching_alpha(pixel[3])] };
            proptest::prop_assert_eq!(bilinear(&model, [pixel; 4], weights), shortcut);
        }

        #[test]
        fn lower_bounds_never_exceed_the_distance(
            samples in 1_usize..90,
            a in proptest::collection::vec(proptest::prelude::any::<[u8; 4]>(), 90),
            b in proptest::collection::vec(proptest::prelude::any::<[u8; 4]>(), 90),
            binary in proptest::prelude::any::<bool>(),
            gamma in 1.0_f64..5000.0,
            limit_fraction in 0_u64..200,
        ) {
            let model = CostModel::new(if binary { AlphaMode::Binary } else { AlphaMode::Continuous }, gamma);
            let fix = |p: [u8; 4]| [p[0], p[1], p[2], model.matching_alpha(p[3])];
            let mut right = EdgeSet::with_capacity(samples, 1);
            let mut left = EdgeSet::with_capacity(samples, 1);
            right.push(a.iter().map(|&p| fix(p)));
            left.push(b.iter().map(|&p| fix(p)));
            let full = u64::from(edge_distance(&model, &right, 0, &left, 0));
            proptest::prop_assert!(mask_bound(model.mask_weight(), right.masks_of(0), left.masks_of(0)) <= full);
            proptest::prop_assert!(profile_bound(&model, right.profile_of(0), left.profile_of(0), samples) <= full);
            // The early exit (partial sums plus the bound of the chunks to come) never drops an
            // edge within the limit, and a completed sum is the full one.
            let distances = profile_distances(right.profile_of(0), left.profile_of(0));
            for limit in [full.saturating_sub(1), full, full + 1, full / 2, limit_fraction * full / 100] {
                let bounded = edge_distance_bounded(&model, &right, 0, &left, 0, limit, distances);
                proptest::prop_assert_eq!(bounded, (full <= limit).then_some(full as u32));
            }
        }
    }
}
