//! Lower bounds of the seam cost `D` between two edges (§2 of the curve paper leaves the search to
//! the GPU; the exact solver prunes with these): from the block-sum profiles (alpha alone, or
//! colour and alpha) and from the solid/clear masks. Distances between profiles are L1 sums on
//! 16-bit lanes.

use crate::cost::CostModel;

/// Lower bound of `D` from the block-sum profiles. Per sample, ξ ≥ 8γ·|a − b|/255 and, when
/// γ ≥ 442 (the largest RGB distance), ξ ≥ 8‖p − q‖ + 8(γ − 442)·|a − b|/255 with
/// ‖p − q‖ ≥ (|Δr| + |Δg| + |Δb|)/√3. Summing over a
/// block, the sum of absolute differences is at least the absolute difference of the sums
/// (triangle inequality), so block sums bound both totals; one unit per sample covers rounding.
/// The search computes it in two steps ([`alpha_bound_of_distance`], then [`bound_of_distances`]).
#[cfg(test)]
pub(crate) fn profile_bound(model: &CostModel, right: &[u16], left: &[u16], samples: usize) -> u64 {
    let alpha = alpha_profile_distance(right, left);
    if !model.colour_bounds() {
        return alpha_bound_of_distance(model, alpha, samples);
    }
    bound_of_distances(model, colour_profile_distance(right, left), alpha, samples)
}

/// The L1 distance of two profiles' alpha block sums.
#[cfg(test)]
pub(crate) fn alpha_profile_distance(right: &[u16], left: &[u16]) -> u32 {
    let len = right.len() / 4;
    l1_u16(&right[3 * len..], &left[3 * len..])
}

/// The L1 distance of two profiles' colour block sums.
#[inline]
pub(crate) fn colour_profile_distance(right: &[u16], left: &[u16]) -> u32 {
    let len = right.len() / 4;
    l1_u16(&right[..3 * len], &left[..3 * len])
}

/// The alpha part of [`profile_bound`] alone, from the alpha distance (cheaper; a first filter).
#[inline]
pub(crate) fn alpha_bound_of_distance(model: &CostModel, alpha: u32, samples: usize) -> u64 {
    (u64::from(alpha) * model.gamma_floor() / 255).saturating_sub(samples as u64)
}

/// [`profile_bound`] from the colour and alpha distances of the block sums (the colour term
/// counts only when [`CostModel::colour_bounds`]).
#[inline]
pub(crate) fn bound_of_distances(model: &CostModel, colour: u32, alpha: u32, samples: usize) -> u64 {
    let alpha_only = alpha_bound_of_distance(model, alpha, samples);
    if !model.colour_bounds() {
        return alpha_only;
    }
    // With γ ≥ 442 ≥ ‖p − q‖: ξ ≥ 8‖p − q‖ + 8·(|a − b|/255)·(γ − 442), so colour and alpha add up.
    let colour_bound = u64::from(colour) * 4618 / 1000;
    let both = colour_bound + u64::from(alpha) * model.gamma_floor().saturating_sub(8 * 442) / 255;
    alpha_only.max(both.saturating_sub(samples as u64))
}

/// L1 distance of two `u16` slices whose length is a multiple of 8, written for SSE2
/// (saturating differences, 8 lanes).
#[inline(always)]
pub(crate) fn l1_u16(a: &[u16], b: &[u16]) -> u32 {
    // Block sums are at most 4 × 255, so 64 chunks of differences fit a u16 lane: the lanes stay
    // 16 bits wide (one SSE2 register) and widen once per 64 chunks.
    let mut total = 0_u32;
    for (a, b) in a.chunks(64 * 8).zip(b.chunks(64 * 8)) {
        let mut lanes = [0_u16; 8];
        for (x, y) in a.chunks_exact(8).zip(b.chunks_exact(8)) {
            let x: &[u16; 8] = x.try_into().expect("8 lanes");
            let y: &[u16; 8] = y.try_into().expect("8 lanes");
            for i in 0..8 {
                lanes[i] = lanes[i].wrapping_add(x[i].saturating_sub(y[i]) | y[i].saturating_sub(x[i]));
            }
        }
        total += lanes.iter().map(|&lane| u32::from(lane)).sum::<u32>();
    }
    total
}

/// Lower bound of `D` from the masks: `mask_weight × #(solid vs clear samples)`.
#[inline]
pub(crate) fn mask_bound(weight: u32, right: (&[u64], &[u64]), left: (&[u64], &[u64])) -> u64 {
    let mut count = 0_u32;
    for w in 0..right.0.len() {
        count += ((right.0[w] & left.1[w]) | (right.1[w] & left.0[w])).count_ones();
    }
    u64::from(weight) * u64::from(count)
}

/// The L1 distances (colour, alpha) of two whole profiles, as [`crate::cost::edge_distance_bounded`] takes them.
#[cfg(test)]
pub(crate) fn profile_distances(right: &[u16], left: &[u16]) -> (u32, u32) {
    (colour_profile_distance(right, left), alpha_profile_distance(right, left))
}
