//! Voting (the E-step of Kwatra's EM, §3.3): every output pixel becomes the weighted average of
//! the source pixels that the overlapping target patches put on it.
//!
//! Written as a gather (each output pixel reads the patches that cover it), so rows are
//! independent, run in parallel, and sum in a fixed order: the result never depends on threads.
//! A patch's vote weighs `1 / (1 + D / patch²)`: well-matched patches dominate, which keeps
//! edges sharper than a plain mean (Kwatra's robust weighting in spirit). The weight is rounded to
//! 16 bits ([`weight_code`]), so that a saved field carries the exact weights of the final vote and
//! re-applying it reproduces the output (`crate::apply_field`).

use motif_core::channel_image::BYTE_VALUES;
use motif_core::{FloatImage, Samples};
use rayon::prelude::*;

use crate::level::Level;
use crate::search::Field;

/// A patch's vote weight `1 / (1 + cost / area)` in 16 bits (at least 1: every patch votes).
pub(crate) fn weight_code(cost: f32, area: f32) -> u16 {
    motif_core::math::round_non_negative((1.0 / (1.0 + cost / area)) * 65535.0).clamp(1.0, 65535.0) as u16
}

/// The weight a [`weight_code`] stands for.
pub(crate) fn weight_of_code(code: u16) -> f32 {
    f32::from(code) / 65535.0
}

/// Votes the level's style through `field` into `output` (target size, style channels). Pixels
/// outside the level's domain keep their value. Returns, per target pixel, whether its largest
/// change over the style channels reached `threshold` (8-bit units): taken as each value is
/// overwritten, so no copy of the image before the vote is needed.
pub(crate) fn vote(level: &Level, field: &Field, output: &mut FloatImage, weighted: bool, threshold: f32) -> Vec<bool> {
    let area = (level.patch * level.patch) as f32;
    let weights: Vec<f32> = if weighted {
        // Only searched patches vote: the others' weights are never read.
        let weight = |(t, &cost)| if level.is_active(t) { weight_of_code(weight_code(cost, area)) } else { 0.0 };
        field.costs.par_iter().enumerate().map(weight).collect()
    } else {
        vec![1.0; field.costs.len()]
    };
    let mut changed = vec![false; level.target_len()];
    let gathered = Gathered { output, changed: &mut changed, threshold };
    match level.style {
        Samples::Float(style) => gather(level, field, &weights, gathered, style, |v| v),
        Samples::Byte(style) => gather(level, field, &weights, gathered, style, |v| BYTE_VALUES[usize::from(v)]),
    }
    changed
}

/// Where a gather writes: the image and the per-pixel change flags.
struct Gathered<'a> {
    output: &'a mut FloatImage,
    changed: &'a mut [bool],
    threshold: f32,
}

/// The vote's gather over style samples of type `T`, read as values by `value` (monomorphized
/// per sample type: no branch per sample).
fn gather<T: Copy + Sync>(
    level: &Level,
    field: &Field,
    weights: &[f32],
    Gathered { output, changed, threshold }: Gathered<'_>,
    style: &[T],
    value: impl Fn(T) -> f32 + Sync,
) {
    let (width, height, radius) = (level.target_width, level.target_height, level.radius as isize);
    let channels = level.style_channels;
    let source_width = level.source_width as isize;
    let rows = output.data_mut().par_chunks_mut(width * channels).zip(changed.par_chunks_mut(width));
    rows.enumerate().for_each(|(y, (row, changed_row))| {
        // Up to 4 style channels, plus structure guidance's distance channel.
        let mut sum = [0.0_f32; 5];
        for x in 0..width {
            if !level.in_domain(y * width + x) {
                continue;
            }
            sum[..channels].fill(0.0);
            let mut total_weight = 0.0;
            for oy in -radius..=radius {
                let py = y as isize + oy;
                let py = if level.tileable {
                    py.rem_euclid(height as isize)
                } else if py < 0 || py >= height as isize {
                    continue;
                } else {
                    py
                } as usize;
                for ox in -radius..=radius {
                    let px = x as isize + ox;
                    let px = if level.tileable {
                        px.rem_euclid(width as isize)
                    } else if px < 0 || px >= width as isize {
                        continue;
                    } else {
                        px
                    } as usize;
                    let t = py * width + px;
                    if !level.is_active(t) {
                        continue;
                    }
                    // The source pixel at the same offset from the matched centre (a valid centre,
                    // so the whole patch is inside): `s − oy · width − ox`, no division needed.
                    let s = field.matches[t] as isize;
                    let start = (s - oy * source_width - ox) as usize * channels;
                    let weight = weights[t];
                    for (acc, &sample) in sum[..channels].iter_mut().zip(&style[start..start + channels]) {
                        *acc += weight * value(sample);
                    }
                    total_weight += weight;
                }
            }
            if total_weight > 0.0 {
                let out = &mut row[x * channels..(x + 1) * channels];
                let mut largest = 0.0_f32;
                for (value, acc) in out.iter_mut().zip(&sum[..channels]) {
                    let new = acc / total_weight;
                    largest = largest.max((new - *value).abs());
                    *value = new;
                }
                changed_row[x] = largest * 255.0 >= threshold;
            }
        }
    });
}
