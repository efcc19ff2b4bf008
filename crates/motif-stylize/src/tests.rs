//! Properties of the search: exact search against a naive formula, the occurrence map's
//! incremental updates, monotone PatchMatch; and the images the synthesis tests
//! (`tests_synthesis`) share.

use motif_core::random::Rng;
use motif_core::{ChannelImage, FloatImage, SeedStreams};

use crate::level::{Level, LevelSpec};
use crate::occurrence::{Occurrence, OmegaDelta};
use crate::search::{Field, exact_search, patchmatch_iteration};

/// A smooth, textured image: sums of random sinusoids plus some per-pixel noise.
pub(crate) fn texture(width: usize, height: usize, channels: usize, seed: u64) -> FloatImage {
    let mut stream = SeedStreams::new(seed).stream("texture", 0);
    let waves: Vec<[f32; 4]> = (0..6 * channels)
        .map(|_| [stream.random::<f32>() * 0.6, stream.random::<f32>() * 0.6, stream.random::<f32>() * 6.3, 0.0])
        .collect();
    let mut data = Vec::with_capacity(width * height * channels);
    for y in 0..height {
        for x in 0..width {
            for c in 0..channels {
                let mut v = 0.5;
                for wave in &waves[c * 6..(c + 1) * 6] {
                    v += 0.07 * motif_core::math::sin_f32(wave[0] * x as f32 + wave[1] * y as f32 + wave[2]);
                }
                v += 0.08 * (stream.random::<f32>() - 0.5);
                // 8-bit values, as PNG inputs are (the engine stores 8 bits).
                data.push((v.clamp(0.0, 1.0) * 255.0).round() / 255.0);
            }
        }
    }
    FloatImage::from_data(width, height, channels, data).unwrap()
}

pub(crate) fn flat(width: usize, height: usize, colour: impl Fn(usize, usize) -> [f32; 3]) -> FloatImage {
    let data = (0..width * height).flat_map(|i| colour(i % width, i / width)).collect();
    FloatImage::from_data(width, height, 3, data).unwrap()
}

pub(crate) fn psnr(a: &FloatImage, b: &FloatImage) -> f64 {
    let mse: f64 =
        a.data().iter().zip(b.data()).map(|(x, y)| f64::from(x - y).powi(2)).sum::<f64>() / a.data().len() as f64;
    10.0 * motif_core::math::log10(1.0 / mse.max(1e-12))
}

/// A level with a 3-channel style, a 1-channel and a 3-channel guide of their own weights,
/// and target guides of a different size. The level borrows its style for the whole test run
/// (leaked: a few hundred bytes per call).
pub(crate) fn small_level(
    patch: usize,
) -> (Level<'static>, FloatImage, Vec<FloatImage>, Vec<FloatImage>, Vec<f32>, FloatImage) {
    let style = texture(14, 12, 3, 1);
    let sources = vec![texture(14, 12, 1, 2), texture(14, 12, 3, 3)];
    let targets = vec![texture(11, 9, 1, 4), texture(11, 9, 3, 5)];
    let weights = vec![0.7 / 3.0, 0.3, 0.2 / 3.0];
    let style_weights = vec![0.7_f32 / 3.0; 3];
    let mut guide_weights = vec![0.3_f32];
    guide_weights.extend([0.2_f32 / 3.0; 3]);
    let source_stack = FloatImage::stack(&[&sources[0], &sources[1]]).unwrap();
    let target_stack = FloatImage::stack(&[&targets[0], &targets[1]]).unwrap();
    let borrowed: &'static FloatImage = Box::leak(Box::new(style.clone()));
    let mut level = Level::new(LevelSpec {
        patch,
        style: borrowed,
        style_weights: &style_weights,
        source_guides: vec![&source_stack],
        target_guides: vec![&target_stack],
        guide_weights: &guide_weights,
        target_size: (11, 9),
        tileable: false,
        source_labels: None,
        target_labels: None,
        label_count: 0,
        prepared: None,
    });
    let current = texture(11, 9, 3, 6);
    level.set_target_style(&current, false);
    (level, style, sources, targets, weights, current)
}

/// Eq. 4 written out over the engine's 8-bit representation: channel `c` of weight `w_c` stored
/// as `round(v · 255 · sqrt(w_c / w_max))`, distance `w_max · Σ d²`, target border clamped.
fn naive_distance(
    (style, sources, targets, weights, current): (&FloatImage, &[FloatImage], &[FloatImage], &[f32], &FloatImage),
    (sx, sy): (usize, usize),
    (x, y): (usize, usize),
    radius: isize,
) -> f64 {
    // Channel weights in stacking order: style (3), guide 1 (1), guide 2 (3).
    let channel_weights = [weights[0], weights[0], weights[0], weights[1], weights[2], weights[2], weights[2]];
    let w_max = channel_weights.iter().copied().fold(0.0_f32, f32::max);
    let q = |v: f32, c: usize| (v.clamp(0.0, 1.0) * 255.0 * (channel_weights[c] / w_max).sqrt()).round() as f64;
    let mut total = 0.0;
    for dy in -radius..=radius {
        for dx in -radius..=radius {
            let (ax, ay) = ((sx as isize + dx) as usize, (sy as isize + dy) as usize);
            let bx = (x as isize + dx).clamp(0, current.width() as isize - 1) as usize;
            let by = (y as isize + dy).clamp(0, current.height() as isize - 1) as usize;
            let mut add = |a: f32, b: f32, c: usize| {
                let d = q(a, c) - q(b, c);
                total += f64::from(w_max) * d * d;
            };
            for c in 0..3 {
                add(style.pixel(ax, ay)[c], current.pixel(bx, by)[c], c);
            }
            add(sources[0].pixel(ax, ay)[0], targets[0].pixel(bx, by)[0], 3);
            for c in 0..3 {
                add(sources[1].pixel(ax, ay)[c], targets[1].pixel(bx, by)[c], 4 + c);
            }
        }
    }
    total
}

#[test]
fn exact_search_equals_naive_minimum_with_occurrence() {
    for patch in [3, 5] {
        let (level, style, sources, targets, weights, current) = small_level(patch);
        let r = (patch / 2) as isize;
        let streams = SeedStreams::new(9);
        let mut field = Field::random(&level, &streams);
        field.recompute_costs(&level);
        let lambda = 2000.0;
        let mut occurrence = Occurrence::new(&level, lambda);
        occurrence.refresh(&level, &field.matches);
        // Ω written out: per source pixel, how many matched patches cover it.
        let (sw, sh) = (level.source_width, level.source_height);
        let mut counts = vec![0.0_f64; sw * sh];
        for &s in &field.matches {
            let (cx, cy) = (s as usize % sw, s as usize / sw);
            for y in cy - r as usize..=cy + r as usize {
                for x in cx - r as usize..=cx + r as usize {
                    counts[y * sw + x] += 1.0;
                }
            }
        }
        let area = (patch * patch) as f64;
        let best_use = area * 99.0 / (sw * sh) as f64;
        let penalty = |sx: usize, sy: usize| -> f64 {
            let mut omega = 0.0;
            for y in sy - r as usize..=sy + r as usize {
                for x in sx - r as usize..=sx + r as usize {
                    omega += counts[y * sw + x];
                }
            }
            f64::from(lambda) * omega / area / best_use
        };
        let images = (&style, &sources[..], &targets[..], &weights[..], &current);
        let before = field.clone();
        exact_search(&level, &mut field, &occurrence);
        for y in 0..9 {
            for x in 0..11 {
                let cost = |s: u32| {
                    let (sx, sy) = (s as usize % sw, s as usize / sw);
                    naive_distance(images, (sx, sy), (x, y), r) + penalty(sx, sy)
                };
                let mut naive_best = cost(before.matches[y * 11 + x]);
                for sy in r as usize..sh - r as usize {
                    for sx in r as usize..sw - r as usize {
                        naive_best = naive_best.min(cost((sy * sw + sx) as u32));
                    }
                }
                let found = cost(field.matches[y * 11 + x]);
                assert!(
                    (found - naive_best).abs() <= 1e-3 * naive_best.max(1.0),
                    "patch {patch} at {x},{y}: {found} vs {naive_best}"
                );
                let stored = f64::from(field.costs[y * 11 + x]);
                let (sx, sy) = (field.matches[y * 11 + x] as usize % sw, field.matches[y * 11 + x] as usize / sw);
                assert!((stored - naive_distance(images, (sx, sy), (x, y), r)).abs() <= 1e-3 * stored.max(1.0));
            }
        }
    }
}

#[test]
fn omega_delta_tracks_a_full_refresh() {
    let (level, ..) = small_level(5);
    let streams = SeedStreams::new(3);
    let field = Field::random(&level, &streams);
    let mut occurrence = Occurrence::new(&level, 1.0);
    occurrence.refresh(&level, &field.matches);
    let mut delta = OmegaDelta::new(&level, Some(&occurrence));
    let mut moved = field.matches.clone();
    let other = Field::random(&level, &SeedStreams::new(4));
    for t in [0, 7, 30, 31, 50] {
        delta.moved(moved[t], other.matches[t]);
        moved[t] = other.matches[t];
    }
    let mut fresh = Occurrence::new(&level, 1.0);
    fresh.refresh(&level, &moved);
    let inert = OmegaDelta::new(&level, None);
    for s in 0..(level.source_width * level.source_height) as u32 {
        assert!((occurrence.cost(s, &delta) - fresh.cost(s, &inert)).abs() < 1e-4);
    }
    delta.clear();
    for s in 0..(level.source_width * level.source_height) as u32 {
        assert_eq!(occurrence.cost(s, &delta), occurrence.snapshot_cost(s));
    }
}

/// The precomputed window of a move (and its unrolled interior path) changes Ω by exactly the
/// products the direct formula forms, in the same order: the same bits, not just close.
#[test]
fn omega_delta_windows_add_exactly_the_direct_products() {
    for patch in [3, 5] {
        let (level, ..) = small_level(patch);
        let field = Field::random(&level, &SeedStreams::new(3));
        let mut occurrence = Occurrence::new(&level, 3500.0);
        occurrence.refresh(&level, &field.matches);
        let mut delta = OmegaDelta::new(&level, Some(&occurrence));
        let (w, h, p) = (level.source_width, level.source_height, patch);
        let len = (w * h) as u32;
        let mut expected: Vec<f32> = (0..len).map(|s| occurrence.snapshot_cost(s)).collect();
        // ω_best = patch² · 99 / (14 · 12); factor = λ / (patch² · ω_best).
        let area = (p * p) as f32;
        let factor = 3500.0 / (area * (area * 99.0 / (w * h) as f32));
        let overlap = |d: usize, c: usize| (p - d.abs_diff(c)) as f32;
        let mut apply = |centre: u32, sign: f32| {
            let (cx, cy) = (centre as usize % w, centre as usize / w);
            for y in (cy + 1).saturating_sub(p)..(cy + p).min(h) {
                let scale = factor * (overlap(y, cy) * sign);
                for x in (cx + 1).saturating_sub(p)..(cx + p).min(w) {
                    expected[y * w + x] += scale * overlap(x, cx);
                }
            }
        };
        let other = Field::random(&level, &SeedStreams::new(4));
        for t in 0..40 {
            delta.moved(field.matches[t], other.matches[t]);
            apply(field.matches[t], -1.0);
            apply(other.matches[t], 1.0);
        }
        for s in 0..len {
            assert_eq!(occurrence.cost(s, &delta).to_bits(), expected[s as usize].to_bits(), "patch {patch}, {s}");
        }
    }
}

/// The 3×3 distance without early exit takes the same decisions as the one with it, and equals
/// it whenever it is below the limit.
#[test]
fn distance_without_early_exit_decides_alike() {
    for patch in [3, 5] {
        let (level, ..) = small_level(patch);
        let (x0, x1) = level.valid_x();
        let (y0, y1) = level.valid_y();
        for (x, y) in [(0, 0), (5, 4), (10, 8)] {
            for sy in y0..y1 {
                for sx in x0..x1 {
                    let s = (sy * level.source_width + sx) as u32;
                    let full = level.distance::<0>(s, x, y, f32::INFINITY);
                    for limit in [0.0, 0.5 * full, full, 1.5 * full + 1.0] {
                        let exiting = level.distance::<0>(s, x, y, limit);
                        let small = level.distance_small::<0>(s, x, y, 0, 0.0, limit);
                        assert_eq!(small < limit, exiting < limit);
                        if small < limit {
                            assert_eq!(small, exiting);
                        }
                        let first = level.first_row::<0>(s, x, y);
                        let rest = level.distance_small::<0>(s, x, y, 1, first, limit);
                        assert_eq!(rest < limit, exiting < limit);
                    }
                }
            }
        }
    }
}

/// With λ = 0 every accepted candidate lowers its own pixel's distance, so the field's energy
/// can only fall (with the penalty, one pixel's cost depends on the others' choices and the sum
/// is not monotone by construction, in ebsynth either).
#[test]
fn patchmatch_energy_never_increases_and_nears_exact() {
    let style = texture(40, 36, 3, 11);
    let target_style = texture(33, 30, 3, 12);
    let weights = [1.0_f32 / 3.0; 3];
    let spec = |patch| LevelSpec {
        patch,
        style: &style,
        style_weights: &weights,
        source_guides: Vec::new(),
        target_guides: Vec::new(),
        guide_weights: &[],
        target_size: (33, 30),
        tileable: false,
        source_labels: None,
        target_labels: None,
        label_count: 0,
        prepared: None,
    };
    let mut level = Level::new(spec(5));
    level.set_target_style(&target_style, false);
    let occurrence = Occurrence::new(&level, 0.0);
    let streams = SeedStreams::new(5);
    let mut field = Field::random(&level, &streams);
    field.recompute_costs(&level);
    let mut energies = vec![field.mean_energy(&level, &occurrence)];
    let mut scratch = Vec::new();
    for k in 0..8 {
        let before = field.costs.clone();
        patchmatch_iteration(&level, &mut field, &mut scratch, &occurrence, &streams.child("pm", k as u64), k, None);
        assert!(field.costs.iter().zip(&before).all(|(after, before)| after <= before));
        energies.push(field.mean_energy(&level, &occurrence));
    }
    assert!(energies.windows(2).all(|w| w[1] <= w[0]), "{energies:?}");
    assert!(energies[8] < 0.5 * energies[0]);
    let mut exact = field.clone();
    exact_search(&level, &mut exact, &occurrence);
    let exact_energy = exact.mean_energy(&level, &occurrence);
    assert!(energies[8] <= 1.1 * exact_energy, "patchmatch {} vs exact {exact_energy}", energies[8]);
}

/// 8-bit images stack into a level through per-channel tables: the same bytes as their float
/// values quantized one by one, for unequal channel weights (scales below 255) and guides on both
/// sides.
#[test]
fn byte_images_stack_as_their_float_values() {
    let floats = [texture(21, 17, 3, 31), texture(21, 17, 2, 32), texture(12, 9, 2, 33)];
    let bytes = floats.clone().map(|image| motif_core::ByteImage::from_float(&image));
    let as_floats = bytes.clone().map(|image| image.to_float_image().into_owned());
    fn stack<I: ChannelImage>([style, source, target]: &[I; 3]) -> (Vec<u8>, Vec<u8>) {
        let (weights, guide_weights) = ([0.5_f32, 0.2, 0.05], [0.3_f32, 0.011]);
        let level = Level::new(LevelSpec {
            patch: 3,
            style,
            style_weights: &weights,
            source_guides: vec![source],
            target_guides: vec![target],
            guide_weights: &guide_weights,
            target_size: (12, 9),
            tileable: false,
            source_labels: None,
            target_labels: None,
            label_count: 0,
            prepared: None,
        });
        assert!(level.channel_scales.iter().any(|&scale| scale < 200.0));
        (level.source.into_owned(), level.target)
    }
    assert_eq!(stack(&bytes), stack(&as_floats));
}
