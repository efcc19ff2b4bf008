//! Image quilting (Efros and Freeman 2001) as the start of texture optimization: square blocks
//! of the exemplar laid in raster order, each chosen among those whose overlap with the blocks
//! already laid differs least, and joined along the minimum-error boundary cut.
//!
//! Blocks hold whole structure elements (a stone and the mortar round it, a tile, a weave
//! cell), and a block is chosen to continue its neighbours' gaps across the overlap, so the
//! start already has whole elements in continuous courses. The optimization then runs at the
//! finest level only, from the field the quilt defines, and mends the seams (Kwatra et al. 2005
//! start texture optimization the same way).

use motif_core::random::Rng;
use motif_core::{ChannelImage, FloatImage, InvalidParameter, Progress, SeedStreams};
use rayon::prelude::*;

use crate::{Error, Params};

/// The optimization's starting field for texture synthesis from a quilt of
/// [`Params::quilt_block`]-pixel blocks: per target pixel, the exemplar pixel the quilt put
/// there, as the centre of its patch (moved inside the exemplar's valid centres at its border).
pub(crate) fn starting_field(
    style: &impl ChannelImage,
    target_size: (usize, usize),
    params: &Params,
    progress: &mut dyn Progress,
) -> Result<Vec<u32>, Error> {
    let (width, height) = (style.width(), style.height());
    let block = params.quilt_block;
    if block > width.min(height) {
        let allowed = format!("must be at most the exemplar's smaller side ({} pixels)", width.min(height));
        return Err(InvalidParameter::new("quilt-block", block, allowed).into());
    }
    let seed = SeedStreams::new(params.seed).child("quilting", 0).seed();
    let origin =
        quilt(&style.to_float_image(), target_size, block, seed, &mut |done| progress.report("quilting", done));
    let radius = params.patch_size / 2;
    Ok(origin
        .iter()
        .map(|&s| {
            let (x, y) = (s as usize % width, s as usize / width);
            let (x, y) = (x.clamp(radius, width - 1 - radius), y.clamp(radius, height - 1 - radius));
            (y * width + x) as u32
        })
        .collect())
}

/// The quilt block `motif texture` uses when none is given: half the exemplar's smaller side
/// (the block that brought every real texture of the corpus, regular or not, closest to its
/// exemplar when grown to twice its size: `docs/stylize.md`), when the output grows the exemplar
/// (more pixels, and its smaller side at least the exemplar's smaller side, so that at least two
/// blocks a side are laid) and the block is at least 8 pixels; else 0, no quilt (an output no
/// larger than its exemplar, whose pyramid search draws from the whole exemplar, and the large
/// exemplars of native-size synthesis). At most 4 096. Front ends turn it off themselves where a
/// quilt cannot apply (guides, masks, structure guidance, tileable output).
pub fn inferred_quilt_block(exemplar: (usize, usize), output: (usize, usize)) -> usize {
    let side = exemplar.0.min(exemplar.1);
    let block = (side / 2).min(4096);
    let grows = output.0 * output.1 > exemplar.0 * exemplar.1 && output.0.min(output.1) >= side;
    if grows && block >= 8 { block } else { 0 }
}

/// The coarse patch side ([`crate::Params::coarse_patch_size`]) for a texture synthesized through
/// the pyramid (no quilt) from an `exemplar`-sized exemplar with `patch`-sided patches: 11, or 15
/// when the exemplar's smaller side is at least 1 024 pixels (its elements are many pixels wide
/// and its coarse levels many), never below `patch`; 0 (off) with a quilt, which optimizes the
/// finest level only. Measured (docs/stylize.md): 11 lowers the nearest-patch distance of all
/// eight small real textures at the default's cost (15 blurs the maple leaves); from 4 096²
/// exemplars 15 keeps straight structures that 5 and 11 bend (GNOME's wood slats, 24 → 8.6; a
/// stone wall, 477 → 280).
pub fn inferred_coarse_patch_size(exemplar: (usize, usize), patch: usize, quilt_block: usize) -> usize {
    if quilt_block > 0 {
        return 0;
    }
    let coarse = if exemplar.0.min(exemplar.1) >= 1024 { 15 } else { 11 };
    coarse.max(patch)
}

/// Candidates within this factor of the best overlap error are drawn from at random (Efros and
/// Freeman's tolerance), so the quilt does not repeat one block.
const TOLERANCE: f64 = 1.1;

/// Most exemplar positions compared for one block: beyond it, positions on a coarser grid
/// (a large exemplar's blocks differ little from their neighbours one pixel away), which bounds
/// the quilt's cost at about `MAX_CANDIDATES × overlap` per block.
const MAX_CANDIDATES: usize = 4096;

/// The exemplar pixel each target pixel comes from (`y · width + x` of the exemplar), for a
/// `target_size` quilt of `block`-pixel blocks overlapping by `block / 6` (at least 1).
/// `block` is at most the exemplar's smaller side and at least 2.
/// `done` hears the fraction of block rows laid.
pub(crate) fn quilt(
    style: &FloatImage,
    target_size: (usize, usize),
    block: usize,
    seed: u64,
    done: &mut dyn FnMut(f64),
) -> Vec<u32> {
    let (source_width, source_height) = (style.width(), style.height());
    let (width, height) = target_size;
    let overlap = (block / 4).max(1);
    let step = block - overlap;
    let channels = style.channels();
    let mut origin = vec![u32::MAX; width * height];
    let mut image = vec![0.0_f32; width * height * channels];
    let streams = SeedStreams::new(seed);
    let (positions_x, positions_y) = (source_width - block + 1, source_height - block + 1);
    let stride = ((positions_x * positions_y) as f64 / MAX_CANDIDATES as f64).sqrt().ceil().max(1.0) as usize;
    let candidates: Vec<(usize, usize)> =
        (0..positions_y).step_by(stride).flat_map(|y| (0..positions_x).step_by(stride).map(move |x| (x, y))).collect();
    let blocks_x = width.saturating_sub(overlap).div_ceil(step).max(1);
    let blocks_y = height.saturating_sub(overlap).div_ceil(step).max(1);
    for by in 0..blocks_y {
        done(by as f64 / blocks_y as f64);
        for bx in 0..blocks_x {
            let (x0, y0) = (bx * step, by * step);
            let (w, h) = (block.min(width - x0), block.min(height - y0));
            let overlaps = Overlaps {
                left: if bx > 0 { overlap.min(w) } else { 0 },
                top: if by > 0 { overlap.min(h) } else { 0 },
            };
            let placed = Placed { image: &image, width, channels, x0, y0, w, h };
            let errors: Vec<f64> =
                candidates.par_iter().map(|&(sx, sy)| overlap_error(style, &placed, overlaps, (sx, sy))).collect();
            let best = errors.iter().copied().fold(f64::INFINITY, f64::min);
            let good: Vec<usize> = (0..candidates.len()).filter(|&i| errors[i] <= best * TOLERANCE + 1e-9).collect();
            let mut stream = streams.stream("block", (by * blocks_x + bx) as u64);
            let (sx, sy) = candidates[good[stream.random_range(0..good.len())]];
            let keep_old = cut(style, &placed, overlaps, (sx, sy));
            for y in 0..h {
                for x in 0..w {
                    if keep_old[y * w + x] {
                        continue;
                    }
                    let t = (y0 + y) * width + x0 + x;
                    let s = (sy + y) * source_width + sx + x;
                    origin[t] = s as u32;
                    image[t * channels..(t + 1) * channels].copy_from_slice(style.pixel(sx + x, sy + y));
                }
            }
        }
    }
    done(1.0);
    origin
}

/// The output laid so far, and the block being placed at `(x0, y0)`, `w × h` (clipped by the
/// target's border).
struct Placed<'a> {
    image: &'a [f32],
    width: usize,
    channels: usize,
    x0: usize,
    y0: usize,
    w: usize,
    h: usize,
}

impl Placed<'_> {
    /// Squared difference between the laid output at block pixel `(x, y)` and exemplar pixel
    /// `(sx + x, sy + y)`.
    #[inline]
    fn difference(&self, style: &FloatImage, (sx, sy): (usize, usize), x: usize, y: usize) -> f64 {
        let t = ((self.y0 + y) * self.width + self.x0 + x) * self.channels;
        let old = &self.image[t..t + self.channels];
        old.iter().zip(style.pixel(sx + x, sy + y)).map(|(a, b)| f64::from(a - b).powi(2)).sum()
    }
}

/// Widths of the left and top overlaps of a block (0 on the first column or row).
#[derive(Clone, Copy)]
struct Overlaps {
    left: usize,
    top: usize,
}

/// Sum of squared differences over the block's overlaps with what is laid.
fn overlap_error(style: &FloatImage, placed: &Placed<'_>, overlaps: Overlaps, source: (usize, usize)) -> f64 {
    let mut total = 0.0;
    for y in 0..placed.h {
        let columns = if y < overlaps.top { placed.w } else { overlaps.left };
        for x in 0..columns {
            total += placed.difference(style, source, x, y);
        }
    }
    total
}

/// Which pixels of the block keep the laid output: those on the old side of the minimum-error
/// vertical cut through the left overlap and the horizontal cut through the top one.
fn cut(style: &FloatImage, placed: &Placed<'_>, overlaps: Overlaps, source: (usize, usize)) -> Vec<bool> {
    let (w, h) = (placed.w, placed.h);
    let mut keep = vec![false; w * h];
    if overlaps.left > 0 {
        // One column per row: pixels left of it keep the old output.
        let columns = minimum_path(h, overlaps.left, |row, column| placed.difference(style, source, column, row));
        for (y, &column) in columns.iter().enumerate() {
            keep[y * w..y * w + column].fill(true);
        }
    }
    if overlaps.top > 0 {
        let rows = minimum_path(w, overlaps.top, |column, row| placed.difference(style, source, column, row));
        for (x, &row) in rows.iter().enumerate() {
            for y in 0..row {
                keep[y * w + x] = true;
            }
        }
    }
    keep
}

/// The minimum-cost path of dynamic programming across `length` steps, one of `span` positions
/// per step, moving at most one position between steps; `cost(step, position)`.
fn minimum_path(length: usize, span: usize, cost: impl Fn(usize, usize) -> f64) -> Vec<usize> {
    let mut total = vec![0.0_f64; length * span];
    for step in 0..length {
        for position in 0..span {
            let here = cost(step, position);
            total[step * span + position] = if step == 0 {
                here
            } else {
                let previous = &total[(step - 1) * span..step * span];
                let low = position.saturating_sub(1);
                let high = (position + 1).min(span - 1);
                here + previous[low..=high].iter().copied().fold(f64::INFINITY, f64::min)
            };
        }
    }
    let mut path = vec![0; length];
    let last = &total[(length - 1) * span..];
    path[length - 1] = (0..span).min_by(|&a, &b| last[a].total_cmp(&last[b])).unwrap_or(0);
    for step in (0..length - 1).rev() {
        let next = path[step + 1];
        let (low, high) = (next.saturating_sub(1), (next + 1).min(span - 1));
        let row = &total[step * span..(step + 1) * span];
        path[step] = (low..=high).min_by(|&a, &b| row[a].total_cmp(&row[b])).unwrap_or(next);
    }
    path
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dynamic program's path equals the cheapest of all connected paths (brute force).
    #[test]
    fn minimum_path_is_optimal() {
        let cost = |step: usize, position: usize| ((step * 7 + position * 13) % 11) as f64 + 0.5 * position as f64;
        let (length, span) = (6, 4);
        let path = minimum_path(length, span, cost);
        let sum = |p: &[usize]| p.iter().enumerate().map(|(s, &q)| cost(s, q)).sum::<f64>();
        let mut best = f64::INFINITY;
        for code in 0..span.pow(length as u32) {
            let p: Vec<usize> = (0..length).map(|s| code / span.pow(s as u32) % span).collect();
            if p.windows(2).all(|w| w[0].abs_diff(w[1]) <= 1) {
                best = best.min(sum(&p));
            }
        }
        assert!(path.windows(2).all(|w| w[0].abs_diff(w[1]) <= 1));
        assert_eq!(sum(&path), best);
    }

    /// Every target pixel comes from the exemplar; a periodic exemplar quilts into its own
    /// period (the overlaps match exactly only in phase), and the same seed gives the same quilt.
    #[test]
    fn quilting_a_periodic_exemplar_continues_its_period() {
        let period = 6;
        let mut style = FloatImage::new(30, 30, 1);
        for y in 0..30 {
            for x in 0..30 {
                style.pixel_mut(x, y)[0] = ((x % period) as f32 * 0.1 + (y % period) as f32 * 0.05).min(1.0);
            }
        }
        let origin = quilt(&style, (70, 55), 18, 4, &mut |_| ());
        assert!(origin.iter().all(|&s| (s as usize) < 30 * 30));
        let phase = |x: usize, y: usize| {
            let s = origin[y * 70 + x] as usize;
            ((s % 30 + period - x % period) % period, (s / 30 + period - y % period) % period)
        };
        // The first block is drawn at random; every later one continues its phase.
        let first = phase(0, 0);
        for y in 0..55 {
            for x in 0..70 {
                assert_eq!(phase(x, y), first, "({x}, {y})");
            }
        }
        assert_eq!(quilt(&style, (70, 55), 18, 4, &mut |_| ()), origin);
    }

    /// The inferred coarse patch: off with a quilt, 11 for small exemplars, 15 from 1024 pixels a
    /// side, and never below the patch.
    #[test]
    fn the_inferred_coarse_patch_grows_with_the_exemplar() {
        assert_eq!(inferred_coarse_patch_size((96, 96), 5, 48), 0, "a quilt optimizes the finest level only");
        assert_eq!(inferred_coarse_patch_size((96, 96), 5, 0), 11);
        assert_eq!(inferred_coarse_patch_size((4096, 1023), 5, 0), 11);
        assert_eq!(inferred_coarse_patch_size((1024, 4096), 5, 0), 15);
        assert_eq!(inferred_coarse_patch_size((96, 96), 13, 0), 13);
        assert_eq!(inferred_coarse_patch_size((8192, 8192), 21, 0), 21);
    }

    /// The inferred block is half the exemplar's smaller side when the output grows the exemplar,
    /// at least 8, and off otherwise; the same sizes give the same block.
    #[test]
    fn the_inferred_block_is_half_the_exemplar_when_it_grows() {
        assert_eq!(inferred_quilt_block((96, 96), (192, 192)), 48);
        assert_eq!(inferred_quilt_block((156, 120), (400, 300)), 60);
        assert_eq!(inferred_quilt_block((96, 96), (150, 100)), 48);
        assert_eq!(inferred_quilt_block((96, 96), (300, 90)), 0, "a side below the exemplar's");
        assert_eq!(inferred_quilt_block((1024, 1024), (1024, 1024)), 0, "no larger");
        assert_eq!(inferred_quilt_block((8192, 8192), (1024, 1024)), 0, "native size");
        assert_eq!(inferred_quilt_block((14, 14), (64, 64)), 0, "below 8 pixels");
        assert_eq!(inferred_quilt_block((10000, 9000), (20000, 20000)), 4096);
        for (w, h) in [(16, 16), (50, 70), (96, 96), (333, 200)] {
            let block = inferred_quilt_block((w, h), (3 * w, 3 * h));
            assert!((8..=w.min(h) / 2).contains(&block), "{w}×{h}: {block}");
            assert_eq!(block, inferred_quilt_block((w, h), (3 * w, 3 * h)));
        }
    }

    /// A quilted texture optimizes one level from the quilt's field; the same seed gives the same
    /// bytes; what quilting cannot do is refused by name.
    #[test]
    fn quilted_textures_run_at_the_finest_level_and_refuse_what_they_cannot_do() {
        use crate::{Guide, Input, Params, synthesize};
        use motif_core::NoProgress;
        let exemplar = crate::tests::texture(40, 36, 3, 9);
        let params = Params::default().with_quilt_block(16).with_seed(7);
        let input = Input::texture(exemplar.clone(), 70, 50);
        let first = synthesize(&input, &params, &mut NoProgress).unwrap();
        assert_eq!((first.image.width(), first.image.height()), (70, 50));
        assert_eq!(first.report.levels.len(), 1);
        assert_eq!(synthesize(&input, &params, &mut NoProgress).unwrap().image, first.image);
        let refused =
            |input: &Input, params: &Params| synthesize(input, params, &mut NoProgress).unwrap_err().to_string();
        assert!(refused(&input, &params.clone().with_quilt_block(37)).contains("smaller side (36 pixels)"));
        assert!(refused(&input, &params.clone().with_tileable(true)).contains("tileable"));
        let guide = Guide { source: exemplar.clone(), target: exemplar.clone(), weight: None };
        assert!(refused(&Input::guided(exemplar, vec![guide]), &params).contains("quilt-block"));
        assert!(Params::default().with_quilt_block(5).validate().is_err());
    }
}
