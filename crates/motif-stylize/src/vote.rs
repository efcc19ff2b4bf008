//! Voting (the E-step of Kwatra's EM, §3.3): every output pixel becomes the weighted average of
//! the source pixels that the overlapping target patches put on it.
//!
//! Written as a gather (each output pixel reads the patches that cover it), so rows are
//! independent, run in parallel, and sum in a fixed order: the result never depends on threads.
//! A patch's vote weighs `1 / (1 + D / patch²)`: well-matched patches dominate, which keeps
//! edges sharper than a plain mean (Kwatra's robust weighting in spirit). The weight is rounded to
//! 16 bits ([`weight_code`]), so that a saved field carries the exact weights of the final vote and
//! re-applying it reproduces the output (`crate::apply_field`).

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
    // Only searched patches vote: the others' weights are never read.
    let code = |t: usize, cost: f32| match (weighted, level.is_active(t)) {
        (true, true) => weight_code(cost, area),
        (false, true) => 1,
        (_, false) => 0,
    };
    let mut changed = vec![false; level.target_len()];
    let gathered = Gathered { output, changed: &mut changed, threshold };
    match level.style {
        Samples::Float(style) => {
            // Unweighted, every patch weighs 1 (not the code 1's 1 / 65535).
            let weight = |(t, &cost)| if weighted { weight_of_code(code(t, cost)) } else { f32::from(code(t, cost)) };
            let weights: Vec<f32> = field.costs.par_iter().enumerate().map(weight).collect();
            gather::<FloatVotes>(level, field, &weights, gathered, style);
        }
        Samples::Byte(style) => {
            let codes: Vec<u16> = field.costs.par_iter().enumerate().map(|(t, &cost)| code(t, cost)).collect();
            gather::<ByteVotes>(level, field, &codes, gathered, style);
        }
    }
    changed
}

/// Where a gather writes: the image and the per-pixel change flags.
struct Gathered<'a> {
    output: &'a mut FloatImage,
    changed: &'a mut [bool],
    threshold: f32,
}

/// The votes one output pixel has gathered: per channel the weighted sum of its source samples,
/// and the sum of the weights. Up to 4 style channels, plus structure guidance's distance channel.
pub(crate) trait Votes: Default {
    /// A style sample.
    type Sample: Copy + Sync;
    /// A patch's vote weight.
    type Weight: Copy + Sync;
    /// Adds one patch's samples of the pixel (one per channel) with the patch's weight.
    fn add(&mut self, samples: &[Self::Sample], weight: Self::Weight);
    /// The weighted mean of every channel into `out`, or `false` (and `out` untouched) when no
    /// weight was gathered.
    fn mean(&self, out: &mut [f32]) -> bool;
}

/// Votes of a float style, weighed by [`weight_of_code`]: summed in the gather's order.
#[derive(Default)]
pub(crate) struct FloatVotes {
    sums: [f32; 5],
    total: f32,
}

impl Votes for FloatVotes {
    type Sample = f32;
    type Weight = f32;

    #[inline(always)]
    fn add(&mut self, samples: &[f32], weight: f32) {
        for (sum, &sample) in self.sums.iter_mut().zip(samples) {
            *sum += weight * sample;
        }
        self.total += weight;
    }

    #[inline(always)]
    fn mean(&self, out: &mut [f32]) -> bool {
        if self.total <= 0.0 {
            return false;
        }
        for (out, sum) in out.iter_mut().zip(&self.sums) {
            *out = sum / self.total;
        }
        true
    }
}

/// Votes of an 8-bit style, weighed by their [`weight_code`]s: exact integer sums (no lookup of
/// the byte's value, no float rounding per vote, no dependence on the order), and the mean
/// `Σ code · byte / (255 · Σ code)` divided once.
#[derive(Default)]
pub(crate) struct ByteVotes {
    sums: [u64; 5],
    total: u64,
}

impl Votes for ByteVotes {
    type Sample = u8;
    type Weight = u16;

    #[inline(always)]
    fn add(&mut self, samples: &[u8], code: u16) {
        for (sum, &sample) in self.sums.iter_mut().zip(samples) {
            *sum += u64::from(code) * u64::from(sample);
        }
        self.total += u64::from(code);
    }

    #[inline(always)]
    fn mean(&self, out: &mut [f32]) -> bool {
        if self.total == 0 {
            return false;
        }
        let scale = 255.0 * self.total as f64;
        for (out, &sum) in out.iter_mut().zip(&self.sums) {
            *out = (sum as f64 / scale) as f32;
        }
        true
    }
}

/// The vote's gather with the accumulator `V` (monomorphized per sample type: no branch per
/// sample). Each output pixel sums its patches row by row, left to right, in that fixed order
/// whatever the layout.
fn gather<V: Votes>(
    level: &Level,
    field: &Field,
    weights: &[V::Weight],
    Gathered { output, changed, threshold }: Gathered<'_>,
    style: &[V::Sample],
) {
    let (width, channels) = (level.target_width, level.style_channels);
    let all_active;
    let active = match &level.active {
        Some(active) => &active[..],
        None => {
            all_active = vec![true; level.target_len()];
            &all_active[..]
        }
    };
    let patches = Patches { level, matches: &field.matches, weights, active };
    let rows = output.data_mut().par_chunks_mut(width * channels).zip(changed.par_chunks_mut(width));
    rows.enumerate().for_each(|(y, (row, changed_row))| {
        let mut mean = [0.0_f32; 5];
        for x in 0..width {
            if !level.in_domain(y * width + x) {
                continue;
            }
            let mut votes = V::default();
            patches.for_each((x, y), |start, weight| votes.add(&style[start..start + channels], weight));
            if votes.mean(&mut mean[..channels]) {
                let out = &mut row[x * channels..(x + 1) * channels];
                let mut largest = 0.0_f32;
                for (value, &new) in out.iter_mut().zip(&mean[..channels]) {
                    largest = largest.max((new - *value).abs());
                    *value = new;
                }
                changed_row[x] = largest * 255.0 >= threshold;
            }
        }
    });
}

/// The searched patches of a level, as the vote reads them.
struct Patches<'a, W> {
    level: &'a Level<'a>,
    matches: &'a [u32],
    weights: &'a [W],
    active: &'a [bool],
}

impl<W: Copy> Patches<'_, W> {
    /// Calls `vote(start, weight)` for each searched patch over target pixel `(x, y)`, row by
    /// row from the top, left to right: `start` is the first style sample of the source pixel
    /// that patch puts there. The source pixel lies at the same offset from the matched centre
    /// (a valid centre, so the whole patch is inside): `s − oy · width − ox`, no division needed.
    #[inline(always)]
    fn for_each(&self, (x, y): (usize, usize), mut vote: impl FnMut(usize, W)) {
        let level = self.level;
        let (width, height, radius) = (level.target_width, level.target_height, level.radius);
        let (source_width, channels) = (level.source_width as isize, level.style_channels);
        if level.tileable {
            let r = radius as isize;
            for oy in -r..=r {
                let py = (y as isize + oy).rem_euclid(height as isize) as usize;
                for ox in -r..=r {
                    let t = py * width + (x as isize + ox).rem_euclid(width as isize) as usize;
                    if self.active[t] {
                        let start = (self.matches[t] as isize - oy * source_width - ox) as usize * channels;
                        vote(start, self.weights[t]);
                    }
                }
            }
            return;
        }
        // Clipped at the borders: the rows and columns of patches that exist, as slices.
        let (left, right) = (x.saturating_sub(radius), (x + radius).min(width - 1));
        for py in y.saturating_sub(radius)..=(y + radius).min(height - 1) {
            let oy = py as isize - y as isize;
            let row = py * width + left..=py * width + right;
            let patches = self.matches[row.clone()].iter().zip(&self.weights[row.clone()]).zip(&self.active[row]);
            // The source pixel of the patch at column `px`: `s − oy · width − (px − x)`.
            let shift = x as isize - oy * source_width - left as isize;
            for (i, ((&s, &weight), &active)) in patches.enumerate() {
                if active {
                    vote((s as isize + shift - i as isize) as usize * channels, weight);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use motif_core::random::Rng;
    use motif_core::{ByteImage, ChannelImage, FloatImage, SeedStreams};

    use super::{vote, weight_code, weight_of_code};
    use crate::level::{Level, LevelSpec};
    use crate::search::Field;
    use crate::tests::texture;

    /// The vote written out: every patch over a pixel, by its offset, the source pixel found by
    /// coordinates, summed in the gather's order (rows from the top, left to right). A float
    /// style sums `weight · value` in f32; an 8-bit one (`bytes`) sums `code · byte` exactly (in
    /// f64, exact below 2⁵³) and divides once.
    fn reference(level: &Level, field: &Field, style: &FloatImage, bytes: Option<&ByteImage>, output: &mut FloatImage) {
        let (width, height, r) = (level.target_width as isize, level.target_height as isize, level.radius as isize);
        let channels = style.channels();
        let area = (level.patch * level.patch) as f32;
        for y in 0..height {
            for x in 0..width {
                if !level.in_domain((y * width + x) as usize) {
                    continue;
                }
                let (mut sum, mut total) = (vec![0.0_f32; channels], 0.0_f32);
                let (mut exact, mut exact_total) = (vec![0.0_f64; channels], 0.0_f64);
                for oy in -r..=r {
                    for ox in -r..=r {
                        let (mut px, mut py) = (x + ox, y + oy);
                        if level.tileable {
                            (px, py) = (px.rem_euclid(width), py.rem_euclid(height));
                        } else if px < 0 || py < 0 || px >= width || py >= height {
                            continue;
                        }
                        let t = (py * width + px) as usize;
                        if !level.is_active(t) {
                            continue;
                        }
                        let s = field.matches[t] as usize;
                        let (sx, sy) = ((s % level.source_width) as isize - ox, (s / level.source_width) as isize - oy);
                        let code = weight_code(field.costs[t], area);
                        let weight = weight_of_code(code);
                        for (c, acc) in sum.iter_mut().enumerate() {
                            *acc += weight * style.pixel(sx as usize, sy as usize)[c];
                        }
                        total += weight;
                        if let Some(bytes) = bytes {
                            let pixel = &bytes.data()[(sy as usize * bytes.width() + sx as usize) * channels..];
                            for (c, acc) in exact.iter_mut().enumerate() {
                                *acc += f64::from(code) * f64::from(pixel[c]);
                            }
                            exact_total += f64::from(code);
                        }
                    }
                }
                let out = output.pixel_mut(x as usize, y as usize);
                match bytes {
                    Some(_) if exact_total > 0.0 => {
                        for (value, acc) in out.iter_mut().zip(&exact) {
                            *value = (acc / (255.0 * exact_total)) as f32;
                        }
                    }
                    None if total > 0.0 => {
                        for (value, acc) in out.iter_mut().zip(&sum) {
                            *value = acc / total;
                        }
                    }
                    _ => {}
                }
            }
        }
    }

    /// The gather against [`reference`], bit for bit: clipped and tileable, with searched and
    /// voted masks, float and 8-bit styles, patches of 3 and 5.
    #[test]
    fn the_vote_is_the_written_out_weighted_mean() {
        let float_style = texture(19, 15, 3, 41);
        let byte_style = ByteImage::from_float(&float_style);
        let byte_values = byte_style.to_float_image().into_owned();
        for (patch, tileable) in [(3, false), (5, false), (5, true), (3, true)] {
            check(&float_style, &float_style, None, patch, tileable);
            check(&byte_style, &byte_values, Some(&byte_style), patch, tileable);
        }
    }

    /// One case of [`the_vote_is_the_written_out_weighted_mean`]: `style` read as `values`, and
    /// as `bytes` when it is an 8-bit one.
    fn check<I: ChannelImage>(style: &I, values: &FloatImage, bytes: Option<&ByteImage>, patch: usize, tileable: bool) {
        let mut stream = SeedStreams::new(42).stream("masks", patch as u64);
        let mut level = Level::new(LevelSpec {
            patch,
            style,
            style_weights: &[1.0; 3],
            source_guides: Vec::new(),
            target_guides: Vec::new(),
            guide_weights: &[],
            target_size: (13, 11),
            tileable,
            source_labels: None,
            target_labels: None,
            label_count: 0,
            prepared: None,
        });
        level.active = Some((0..13 * 11).map(|_| stream.random::<f32>() < 0.8).collect());
        level.domain = Some((0..13 * 11).map(|_| stream.random::<f32>() < 0.9).collect());
        let mut field = Field::random(&level, &SeedStreams::new(patch as u64));
        field.costs = (0..13 * 11).map(|_| stream.random::<f32>() * 4000.0).collect();
        let start = texture(13, 11, 3, 43);
        let (mut gathered, mut expected) = (start.clone(), start);
        vote(&level, &field, &mut gathered, true, 0.0);
        reference(&level, &field, values, bytes, &mut expected);
        assert_eq!(gathered, expected, "patch {patch}, tileable {tileable}");
        // The exact 8-bit mean and the float one of the same values differ in the last bits only.
        let mut rounded = expected.clone();
        reference(&level, &field, values, None, &mut rounded);
        let largest = expected.data().iter().zip(rounded.data()).map(|(a, b)| (a - b).abs()).fold(0.0, f32::max);
        assert!(largest < 1e-6, "patch {patch}, tileable {tileable}: {largest}");
    }
}
