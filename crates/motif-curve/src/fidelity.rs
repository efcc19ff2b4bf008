//! How much a result looks like its exemplar, measured by the engine itself (not in the paper; the
//! paper judges results by eye).
//!
//! The output is read back along the ribbon with a *rigid* local frame: at regular steps along the
//! curve and across the ribbon, a `P × P` patch is sampled from the canvas in the frame of the
//! curve's tangent and normal at that point, at exemplar resolution (the scale `s` undone). A piece
//! copied without distortion gives back exemplar patches exactly; a seam that breaks the pattern,
//! a motif cut in half or a bent copy (the repeat baseline stretches the outer side of every bend)
//! gives patches found nowhere in the exemplar. Each output patch that shows some of the pattern
//! is matched with its nearest exemplar patch (sum of absolute differences of premultiplied RGBA,
//! exact search), and the figure is the mean of those distances as a fraction of full scale: 0 is
//! a perfect copy, 1 the largest possible difference.
//!
//! A second figure tells the variety: the fraction of the exemplar's pattern pixels that lie in
//! the nearest exemplar patch of some output patch. A result that repeats one window of the
//! exemplar scores low however well that window is copied.

use motif_core::vector;
use motif_core::{Point, RgbaImage};
use rayon::prelude::*;
use serde::Serialize;

/// Side of the compared patches, in cells of `CELL × CELL` exemplar pixels (averaged, so that
/// the resampling of rotated pieces does not drown the structure in noise).
pub(crate) const PATCH_SIZE: usize = 8;
/// Side of a cell, exemplar pixels.
pub(crate) const CELL: usize = 2;
/// Side of a patch, exemplar pixels.
const SPAN: usize = PATCH_SIZE * CELL;
/// Distance beyond which an output patch counts as broken (found nowhere in the exemplar). The
/// resampling of the rendering alone keeps 99 % of the patches of an undistorted copy below 0.03.
pub(crate) const BROKEN: f64 = 0.05;
/// Step between output patches along and across the ribbon, exemplar pixels.
const STEP: usize = 4;
/// Largest number of output patches compared (evenly spaced along the curve beyond that), so that
/// the measure stays cheap on long curves.
const MAX_PATCHES: usize = 6000;

/// The patch figures of one result.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PatchFidelity {
    /// Mean over output patches of the distance to the nearest exemplar patch, in `[0, 1]`
    /// (0: every patch is found in the exemplar).
    pub mean_distance: f64,
    /// The 90th percentile of the same distances.
    pub p90_distance: f64,
    /// Fraction of output patches farther than 0.05 (`BROKEN`) from every exemplar patch: seams that
    /// break the pattern, motifs cut in half, wrap-around seams of a tiled copy.
    pub broken_fraction: f64,
    /// Output patches showing some pattern (the ones measured).
    pub patches: usize,
    /// Fraction of the exemplar's pattern pixels (alpha > 0) covered by the nearest exemplar
    /// patch of at least one output patch, in `[0, 1]`.
    pub exemplar_coverage: f64,
}

/// Premultiplied RGBA bytes of `image`, row-major.
fn premultiplied(image: &RgbaImage) -> Vec<[u8; 4]> {
    (0..image.height())
        .flat_map(|y| (0..image.width()).map(move |x| (x, y)))
        .map(|(x, y)| {
            let [r, g, b, a] = image.get(x, y);
            let scale = |c: u8| ((u32::from(c) * u32::from(a) + 127) / 255) as u8;
            [scale(r), scale(g), scale(b), a]
        })
        .collect()
}

/// Bilinear sample of premultiplied pixels at continuous position `(x, y)` (pixel centres at
/// half-integers); transparent outside.
fn sample(pixels: &[[u8; 4]], width: usize, height: usize, x: f64, y: f64) -> [u8; 4] {
    let (fx, fy) = (x - 0.5, y - 0.5);
    let (x0, y0) = (fx.floor(), fy.floor());
    let (tx, ty) = (fx - x0, fy - y0);
    let fetch = |ix: f64, iy: f64| -> [f64; 4] {
        if ix < 0.0 || iy < 0.0 || ix >= width as f64 || iy >= height as f64 {
            return [0.0; 4];
        }
        pixels[iy as usize * width + ix as usize].map(f64::from)
    };
    let (a, b, c, d) = (fetch(x0, y0), fetch(x0 + 1.0, y0), fetch(x0, y0 + 1.0), fetch(x0 + 1.0, y0 + 1.0));
    let mut out = [0_u8; 4];
    for k in 0..4 {
        let value = (a[k] * (1.0 - tx) + b[k] * tx) * (1.0 - ty) + (c[k] * (1.0 - tx) + d[k] * tx) * ty;
        out[k] = value.round().clamp(0.0, 255.0) as u8;
    }
    out
}

/// A set of flattened `P × P × 4` patches sorted by their byte sum, for exact nearest-patch search:
/// the sum of absolute differences is at least the difference of the sums, so the search walks
/// outwards from the query's sum and stops once that gap exceeds the best distance found.
struct PatchIndex {
    /// Patches in sum order, `P·P·4` bytes each.
    bytes: Vec<u8>,
    sums: Vec<u32>,
    /// Top-left corner of each patch in the exemplar.
    corners: Vec<[i64; 2]>,
}

const PATCH_BYTES: usize = PATCH_SIZE * PATCH_SIZE * 4;

/// The cell averages of a `SPAN × SPAN` block given pixel by pixel (`pixel(col, row)`).
fn cell_patch(pixel: impl Fn(usize, usize) -> [u8; 4]) -> [u8; PATCH_BYTES] {
    let mut sums = [0_u32; PATCH_BYTES];
    for row in 0..SPAN {
        for col in 0..SPAN {
            let at = ((row / CELL) * PATCH_SIZE + col / CELL) * 4;
            for (k, value) in pixel(col, row).into_iter().enumerate() {
                sums[at + k] += u32::from(value);
            }
        }
    }
    let area = (CELL * CELL) as u32;
    sums.map(|sum| ((sum + area / 2) / area) as u8)
}

impl PatchIndex {
    fn new(patches: &[([i64; 2], [u8; PATCH_BYTES])]) -> Self {
        let mut order: Vec<(u32, usize)> = patches.iter().enumerate().map(|(i, (_, p))| (byte_sum(p), i)).collect();
        order.sort_unstable();
        let sums = order.iter().map(|&(s, _)| s).collect();
        let bytes = order.iter().flat_map(|&(_, i)| patches[i].1.iter().copied()).collect();
        let corners = order.iter().map(|&(_, i)| patches[i].0).collect();
        Self { bytes, sums, corners }
    }

    fn len(&self) -> usize {
        self.sums.len()
    }

    /// The smallest sum of absolute differences from `query` to a patch of the index, and that
    /// patch's corner (the first in sum order among equals).
    fn nearest(&self, query: &[u8; PATCH_BYTES]) -> (u32, [i64; 2]) {
        let key = byte_sum(query);
        let start = self.sums.partition_point(|&s| s < key);
        let (mut best, mut best_index) = (u32::MAX, 0);
        let (mut below, mut above) = (start, start);
        loop {
            let gap_below = if below > 0 { Some(key - self.sums[below - 1]) } else { None };
            let gap_above = if above < self.len() { Some(self.sums[above] - key) } else { None };
            let take_below = match (gap_below, gap_above) {
                (None, None) => break,
                (Some(low), Some(high)) => low <= high,
                (Some(_), None) => true,
                (None, Some(_)) => false,
            };
            let (index, gap) = if take_below {
                below -= 1;
                (below, gap_below.expect("checked"))
            } else {
                above += 1;
                (above - 1, gap_above.expect("checked"))
            };
            if gap >= best {
                break;
            }
            let distance = bounded_distance(query, &self.bytes[index * PATCH_BYTES..(index + 1) * PATCH_BYTES], best);
            if distance < best || (distance == best && index < best_index) {
                (best, best_index) = (distance, index);
            }
        }
        (best, self.corners[best_index])
    }
}

fn byte_sum(patch: &[u8]) -> u32 {
    patch.iter().map(|&b| u32::from(b)).sum()
}

/// Sum of absolute differences, abandoned (returning at least `bound`) once it reaches `bound`.
fn bounded_distance(a: &[u8], b: &[u8], bound: u32) -> u32 {
    let mut total = 0_u32;
    for (row_a, row_b) in a.chunks_exact(PATCH_SIZE * 4).zip(b.chunks_exact(PATCH_SIZE * 4)) {
        total += row_a.iter().zip(row_b).map(|(&x, &y)| u32::from(x.abs_diff(y))).sum::<u32>();
        if total >= bound {
            return total;
        }
    }
    total
}

/// Every patch of the exemplar whose top-left corner lies in `[0, W − S] × [1 − S, H − 1]` (`S`
/// the patch side in pixels)
/// (patches may reach into the transparent space above and below the strip, never past its left
/// and right borders, where the exemplar is cut).
fn exemplar_patches(exemplar: &RgbaImage) -> Vec<([i64; 2], [u8; PATCH_BYTES])> {
    let (w, h) = (exemplar.width(), exemplar.height());
    let pixels = premultiplied(exemplar);
    let span = SPAN as i64;
    let mut patches = Vec::new();
    for y in (1 - span)..h as i64 {
        for x in 0..=(w as i64 - span) {
            let patch = cell_patch(|col, row| {
                let at_row = y + row as i64;
                if at_row < 0 || at_row >= h as i64 { [0; 4] } else { pixels[at_row as usize * w + x as usize + col] }
            });
            patches.push(([x, y], patch));
        }
    }
    patches
}

/// Patches of the output read along the ribbon (borders `top` and `bottom`, canvas coordinates,
/// about one canvas pixel apart) in the rigid frame of the curve, at scale `scale` (exemplar
/// pixels per canvas pixel). Only patches showing some pattern are returned.
fn output_patches(image: &RgbaImage, top: &[Point], bottom: &[Point], scale: f64) -> Vec<[u8; PATCH_BYTES]> {
    let (w, h) = (image.width(), image.height());
    let pixels = premultiplied(image);
    let count = top.len().min(bottom.len());
    if count < 2 {
        return Vec::new();
    }
    let length: f64 = top
        .windows(2)
        .zip(bottom.windows(2))
        .map(|(t, b)| vector::distance(t[0].midpoint(b[0]), t[1].midpoint(b[1])))
        .sum();
    let spacing = length / (count - 1) as f64;
    let half = SPAN as f64 / 2.0;
    // Keep whole patches on the curve: skip half a patch at each end.
    let margin = (half / scale / spacing).ceil() as usize;
    let step = ((STEP as f64 / scale / spacing).round() as usize).max(1);
    let along: Vec<usize> = (margin..count.saturating_sub(margin)).step_by(step).collect();
    let ribbon_width = vector::distance(top[0], bottom[0]) * scale;
    let across: Vec<f64> =
        (0..).map(|i| (i * STEP) as f64).take_while(|&y0| y0 + SPAN as f64 <= ribbon_width.ceil() + half).collect();
    let stride = (along.len() * across.len()).div_ceil(MAX_PATCHES).max(1);
    let along: Vec<usize> = along.into_iter().step_by(stride).collect();
    along
        .par_iter()
        .flat_map_iter(|&k| {
            let (t, b) = (top[k], bottom[k]);
            let normal = vector::normalized(b - t);
            let tangent = motif_core::Vec2::new(normal.y, -normal.x);
            let pixels = &pixels;
            across.iter().filter_map(move |&y0| {
                let patch = cell_patch(|col, row| {
                    let along_offset = (col as f64 + 0.5 - half) / scale;
                    let across_offset = (y0 + row as f64 + 0.5) / scale;
                    let p = t + tangent * along_offset + normal * across_offset;
                    sample(pixels, w, h, p.x, p.y)
                });
                (patch.iter().skip(3).step_by(4).any(|&a| a > 0)).then_some(patch)
            })
        })
        .collect()
}

/// The patch figures of `image`, a result along the ribbon with borders `top` and `bottom`, against
/// `exemplar`, at scale `scale`.
pub fn patch_fidelity(
    exemplar: &RgbaImage,
    image: &RgbaImage,
    top: &[Point],
    bottom: &[Point],
    scale: f64,
) -> PatchFidelity {
    let full_scale = (PATCH_BYTES * 255) as f64;
    let queries = output_patches(image, top, bottom, scale);
    let exemplar_set = exemplar_patches(exemplar);
    if queries.is_empty() || exemplar_set.is_empty() {
        return PatchFidelity {
            mean_distance: 1.0,
            p90_distance: 1.0,
            broken_fraction: 1.0,
            patches: 0,
            exemplar_coverage: 0.0,
        };
    }
    let index = PatchIndex::new(&exemplar_set);
    let matches: Vec<(u32, [i64; 2])> = queries.par_iter().map(|q| index.nearest(q)).collect();
    let mut distances: Vec<f64> = matches.iter().map(|&(d, _)| f64::from(d) / full_scale).collect();
    let mean_distance = distances.iter().sum::<f64>() / distances.len() as f64;
    distances.sort_by(f64::total_cmp);
    let p90_distance = distances[(distances.len() * 9 / 10).min(distances.len() - 1)];
    let (w, h) = (exemplar.width(), exemplar.height());
    let mut covered = vec![false; w * h];
    for &(_, [x, y]) in &matches {
        for row in y.max(0)..(y + SPAN as i64).min(h as i64) {
            for col in x..x + SPAN as i64 {
                covered[row as usize * w + col as usize] = true;
            }
        }
    }
    let pattern = (0..w * h).filter(|&i| exemplar.get(i % w, i / w)[3] > 0);
    let (hit, total) = pattern.fold((0_usize, 0_usize), |(hit, total), i| (hit + usize::from(covered[i]), total + 1));
    let broken = distances.iter().filter(|&&d| d > BROKEN).count();
    PatchFidelity {
        mean_distance,
        p90_distance,
        broken_fraction: broken as f64 / distances.len() as f64,
        patches: distances.len(),
        exemplar_coverage: hit as f64 / total.max(1) as f64,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn exemplar() -> RgbaImage {
        // An irregular pattern: rings of varying radius along a strip, transparent around them.
        RgbaImage::from_fn(96, 32, |x, y| {
            let cx = (x / 24) as f64 * 24.0 + 12.0;
            let r = ((x as f64 - cx).powi(2) + (y as f64 - 16.0).powi(2)).sqrt();
            let ring = 6.0 + (x / 24) as f64 * 1.5;
            if (r - ring).abs() < 2.0 { [200, (x * 2) as u8, 40, 255] } else { [0; 4] }
        })
    }

    fn straight_ribbon(length: usize, y_top: f64, width: f64) -> (Vec<Point>, Vec<Point>) {
        let top = (0..=length).map(|x| Point::new(x as f64, y_top)).collect();
        let bottom = (0..=length).map(|x| Point::new(x as f64, y_top + width)).collect();
        (top, bottom)
    }

    #[test]
    fn a_copy_of_the_exemplar_is_found_exactly_and_noise_is_not() {
        let exemplar = exemplar();
        let (top, bottom) = straight_ribbon(96, 0.0, 32.0);
        let copy = patch_fidelity(&exemplar, &exemplar, &top, &bottom, 1.0);
        assert!(copy.patches > 50, "{copy:?}");
        assert!(copy.mean_distance < 1e-9, "{copy:?}");
        assert!(copy.exemplar_coverage > 0.9, "{copy:?}");
        let noise = RgbaImage::from_fn(96, 32, |x, y| {
            let v = ((x * 7919 + y * 104_729) % 251) as u8;
            [v, v / 3, 255 - v, if v.is_multiple_of(2) { 255 } else { 0 }]
        });
        let garbage = patch_fidelity(&exemplar, &noise, &top, &bottom, 1.0);
        assert!(garbage.mean_distance > 0.1, "{garbage:?}");
        assert!(garbage.broken_fraction > 0.9, "{garbage:?}");
        assert_eq!(copy.broken_fraction, 0.0);
    }

    #[test]
    fn the_sorted_search_equals_brute_force() {
        let exemplar = exemplar();
        let set = exemplar_patches(&exemplar);
        let index = PatchIndex::new(&set);
        let shifted = RgbaImage::from_fn(96, 32, |x, y| exemplar.get((x + 5) % 96, (y + 3) % 32));
        let (top, bottom) = straight_ribbon(96, 0.0, 32.0);
        for query in output_patches(&shifted, &top, &bottom, 1.0).iter().take(200) {
            let brute = set.iter().map(|(_, p)| bounded_distance(query, p, u32::MAX)).min().unwrap();
            assert_eq!(index.nearest(query).0, brute);
        }
    }

    #[test]
    fn a_rotated_and_scaled_copy_is_read_back_in_the_curve_frame() {
        // The exemplar drawn at twice its size (scale 0.5) along a vertical line going down: the
        // ribbon's top border is on the right (x = 80), its bottom on the left (x = 16).
        let exemplar = exemplar();
        let image = RgbaImage::from_fn(96, 200, |x, y| {
            let (ex, ey) = (y / 2, (80_i64 - 1 - x as i64).div_euclid(2));
            if ex >= 96 || !(0..32).contains(&ey) { [0; 4] } else { exemplar.get(ex, ey as usize) }
        });
        let top: Vec<Point> = (0..=192).map(|y| Point::new(80.0, y as f64)).collect();
        let bottom: Vec<Point> = (0..=192).map(|y| Point::new(16.0, y as f64)).collect();
        let figures = patch_fidelity(&exemplar, &image, &top, &bottom, 0.5);
        assert!(figures.patches > 50, "{figures:?}");
        assert!(figures.mean_distance < 1e-9, "{figures:?}");
        assert!(figures.exemplar_coverage > 0.9, "{figures:?}");
        // The same drawing read as if it were mirrored (top and bottom swapped) is not found.
        let mirrored = patch_fidelity(&exemplar, &image, &bottom, &top, 0.5);
        assert!(mirrored.mean_distance > 0.002, "{mirrored:?}");
    }

    #[test]
    fn one_repeated_window_covers_little_of_the_exemplar() {
        let exemplar = exemplar();
        let repeated = RgbaImage::from_fn(96, 32, |x, y| exemplar.get(x % 24, y));
        let (top, bottom) = straight_ribbon(96, 0.0, 32.0);
        let figures = patch_fidelity(&exemplar, &repeated, &top, &bottom, 1.0);
        assert!(figures.exemplar_coverage < 0.4, "{figures:?}");
    }
}
