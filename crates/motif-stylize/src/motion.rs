//! Motion between consecutive video frames and the guides built from frames, for video
//! stylization (Jamriška et al. 2019, "Stylizing Video by Example", §3: the edge, positional and
//! temporal guides).
//!
//! Motion comes from the engine's own PatchMatch: the earlier frame is the source and the later
//! one the target, guided by their colours and, with a small weight, by pixel coordinates (a
//! prior for small motion, which decides flat regions where colour alone matches anywhere). The
//! integer matches are refined to a sub-pixel offset by a few Lucas–Kanade steps around each
//! match, then smoothed by a median filter per component, which removes isolated
//! wrong matches without blurring motion edges. No well-kept Rust crate computes dense optical
//! flow, and the field PatchMatch gives is what the paper's own guides are built on.

use motif_core::{FloatImage, NoProgress, SeedStreams};
use rayon::prelude::*;

use crate::{Error, Guide, Input, Params, synthesize};

/// Patch side of the motion search: larger than the stylization's default, so that a match is
/// unambiguous on natural images.
const MOTION_PATCH: usize = 7;
/// Weight of the coordinate guide in the motion search against 1 for the frames' colours.
const SMALL_MOTION_PRIOR: f32 = 0.05;
/// Half-side of the window of the sub-pixel refinement.
const REFINE_RADIUS: isize = 3;
/// Lucas–Kanade steps of the refinement.
const REFINE_STEPS: usize = 3;
/// Damping of the refinement's structure tensor (squared luma gradient, summed over the window).
const DAMPING: f64 = 1e-3;
/// Half-side of the median filter.
const MEDIAN_RADIUS: isize = 2;

/// A dense motion field between two frames of the same size: for each pixel `p` of the later
/// frame, the offset `d(p)` such that it shows what the earlier frame showed at `p + d(p)` (a
/// backward field, the form that warping needs).
#[derive(Debug, Clone, PartialEq)]
pub struct MotionField {
    /// Frame width.
    pub width: usize,
    /// Frame height.
    pub height: usize,
    /// Row-major offsets `[dx, dy]` in pixels.
    pub offsets: Vec<[f32; 2]>,
}

impl MotionField {
    /// No motion.
    pub fn zero(width: usize, height: usize) -> Self {
        Self { width, height, offsets: vec![[0.0, 0.0]; width * height] }
    }

    /// `image` (the earlier frame's size) carried along the motion: the result at `p` is `image`
    /// at `p + d(p)`, sampled bilinearly and clamped to the border.
    pub fn warp(&self, image: &FloatImage) -> FloatImage {
        let mut out = FloatImage::new(self.width, self.height, image.channels());
        for y in 0..self.height {
            for x in 0..self.width {
                let [dx, dy] = self.offsets[y * self.width + x];
                let (sx, sy) = (x as f64 + 0.5 + f64::from(dx), y as f64 + 0.5 + f64::from(dy));
                image.sample_bilinear(sx, sy, out.pixel_mut(x, y));
            }
        }
        out
    }

    /// Whether the pixel at `index` came from inside the earlier frame (it was visible there).
    pub fn came_from_inside(&self, index: usize) -> bool {
        let [dx, dy] = self.offsets[index];
        let (x, y) = ((index % self.width) as f32 + dx, (index / self.width) as f32 + dy);
        x >= 0.0 && y >= 0.0 && x <= (self.width - 1) as f32 && y <= (self.height - 1) as f32
    }
}

/// The motion from `earlier` to `later` (frames of the same size and channels), see the module
/// documentation. Deterministic for a given `seed`.
pub fn estimate_motion(earlier: &FloatImage, later: &FloatImage, seed: u64) -> Result<MotionField, Error> {
    let (width, height) = (later.width(), later.height());
    let colour_earlier = colour_channels(earlier);
    let colour_later = colour_channels(later);
    let coordinates = coordinate_guide(width, height);
    let guides = vec![
        Guide { source: colour_earlier.clone(), target: colour_later.clone(), weight: Some(1.0) },
        Guide { source: coordinates.clone(), target: coordinates, weight: Some(SMALL_MOTION_PRIOR) },
    ];
    let params = Params::default()
        .with_style_weight(0.0)
        .with_uniformity(0.0)
        .with_patch_size(MOTION_PATCH)
        .with_search_vote_iterations(1)
        .with_stop_threshold(0.0)
        .with_seed(SeedStreams::new(seed).child("motion", 0).seed());
    let early = luminance(&colour_earlier);
    let output = synthesize(&Input::guided(early.clone(), guides), &params, &mut NoProgress)?;
    let integer: Vec<[isize; 2]> = output
        .field
        .matches
        .iter()
        .enumerate()
        .map(|(index, found)| match found {
            // A pixel within half a patch of the border moves with the nearest whole patch.
            Some([sx, sy]) => [*sx as isize - inner(index % width, width), *sy as isize - inner(index / width, height)],
            None => [0, 0],
        })
        .collect();
    let late = luminance(&colour_later);
    // The patch search compares whole patches only, which leaves some pixels near the borders
    // (and a few elsewhere) at a poor match: each pixel keeps, of its own match, no motion and
    // its four neighbours' matches, the one its window fits best.
    let chosen: Vec<[isize; 2]> = (0..width * height)
        .into_par_iter()
        .map(|index| {
            let (x, y) = (index % width, index / width);
            let mut best = ([0, 0], window_cost(&early, &late, x, y, [0, 0]));
            let neighbours = [
                (x > 0).then(|| index - 1),
                (x + 1 < width).then(|| index + 1),
                (y > 0).then(|| index - width),
                (y + 1 < height).then(|| index + width),
            ];
            for candidate in std::iter::once(integer[index]).chain(neighbours.into_iter().flatten().map(|n| integer[n]))
            {
                let cost = window_cost(&early, &late, x, y, candidate);
                if cost < best.1 {
                    best = (candidate, cost);
                }
            }
            best.0
        })
        .collect();
    let planes = Planes::new(&early);
    let refined: Vec<[f32; 2]> = (0..width * height)
        .into_par_iter()
        .map(|index| refine(&planes, &late, index % width, index / width, chosen[index]))
        .collect();
    Ok(MotionField { width, height, offsets: median_filtered(&refined, width, height) })
}

/// The centre of the nearest whole motion patch along one axis.
fn inner(at: usize, side: usize) -> isize {
    let radius = MOTION_PATCH / 2;
    at.clamp(radius.min(side / 2), side.saturating_sub(radius + 1).max(side / 2)) as isize
}

/// The earlier frame's luma and its central-difference gradients, interleaved, so one bilinear
/// weight set reads all three.
struct Planes {
    width: usize,
    height: usize,
    values: Vec<[f32; 3]>,
}

impl Planes {
    fn new(luma: &FloatImage) -> Self {
        let (width, height) = (luma.width(), luma.height());
        let values = (0..width * height)
            .map(|index| {
                let (x, y) = ((index % width) as isize, (index / width) as isize);
                let gx = 0.5 * (clamped(luma, x + 1, y) - clamped(luma, x - 1, y));
                let gy = 0.5 * (clamped(luma, x, y + 1) - clamped(luma, x, y - 1));
                [luma.data()[index], gx, gy]
            })
            .collect();
        Self { width, height, values }
    }

    /// Luma and gradient at pixel coordinates `(x, y)` (pixel centres at integers), clamped.
    fn sample(&self, x: f64, y: f64) -> [f64; 3] {
        let fx = x.clamp(0.0, (self.width - 1) as f64);
        let fy = y.clamp(0.0, (self.height - 1) as f64);
        let (x0, y0) = (fx as usize, fy as usize);
        let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
        let (tx, ty) = (fx - x0 as f64, fy - y0 as f64);
        let at = |x: usize, y: usize| self.values[y * self.width + x];
        let (a, b, c, d) = (at(x0, y0), at(x1, y0), at(x0, y1), at(x1, y1));
        std::array::from_fn(|k| {
            let top = f64::from(a[k]) + (f64::from(b[k]) - f64::from(a[k])) * tx;
            let bottom = f64::from(c[k]) + (f64::from(d[k]) - f64::from(c[k])) * tx;
            top + (bottom - top) * ty
        })
    }
}

/// The sub-pixel offset at `(x, y)`: Lucas–Kanade steps from the integer match (a window of
/// brightness constancy, linearized around the current offset; the structure tensor is damped so
/// that where the window sees an edge only, the offset across it moves and the one along it
/// stays at the match).
fn refine(early: &Planes, late: &FloatImage, x: usize, y: usize, [dx, dy]: [isize; 2]) -> [f32; 2] {
    let start = [dx as f64, dy as f64];
    let mut offset = start;
    for _ in 0..REFINE_STEPS {
        let (mut a, mut b, mut c, mut bx, mut by) = (DAMPING, 0.0, DAMPING, 0.0, 0.0);
        let mut residual_total = 0.0;
        for wy in -REFINE_RADIUS..=REFINE_RADIUS {
            for wx in -REFINE_RADIUS..=REFINE_RADIUS {
                let (lx, ly) = (x as isize + wx, y as isize + wy);
                let [value, gx, gy] = early.sample(lx as f64 + offset[0], ly as f64 + offset[1]);
                let residual = f64::from(clamped(late, lx, ly)) - value;
                a += gx * gx;
                b += gx * gy;
                c += gy * gy;
                bx += gx * residual;
                by += gy * residual;
                residual_total += residual.abs();
            }
        }
        if residual_total == 0.0 {
            break;
        }
        let determinant = a * c - b * b;
        let step = [(c * bx - b * by) / determinant, (a * by - b * bx) / determinant];
        offset = [
            (offset[0] + step[0]).clamp(start[0] - 1.5, start[0] + 1.5),
            (offset[1] + step[1]).clamp(start[1] - 1.5, start[1] + 1.5),
        ];
    }
    [offset[0] as f32, offset[1] as f32]
}

/// Squared luma differences over the refinement window at an integer offset.
fn window_cost(early: &FloatImage, late: &FloatImage, x: usize, y: usize, [dx, dy]: [isize; 2]) -> f32 {
    let mut sum = 0.0;
    for wy in -REFINE_RADIUS..=REFINE_RADIUS {
        for wx in -REFINE_RADIUS..=REFINE_RADIUS {
            let (lx, ly) = (x as isize + wx, y as isize + wy);
            let difference = clamped(late, lx, ly) - clamped(early, lx + dx, ly + dy);
            sum += difference * difference;
        }
    }
    sum
}

fn clamped(image: &FloatImage, x: isize, y: isize) -> f32 {
    let x = x.clamp(0, image.width() as isize - 1) as usize;
    let y = y.clamp(0, image.height() as isize - 1) as usize;
    image.pixel(x, y)[0]
}

fn median_filtered(offsets: &[[f32; 2]], width: usize, height: usize) -> Vec<[f32; 2]> {
    let mut out = vec![[0.0; 2]; offsets.len()];
    let mut window: Vec<f32> = Vec::with_capacity(((2 * MEDIAN_RADIUS + 1) * (2 * MEDIAN_RADIUS + 1)) as usize);
    for y in 0..height as isize {
        for x in 0..width as isize {
            for axis in 0..2 {
                window.clear();
                for wy in (y - MEDIAN_RADIUS).max(0)..=(y + MEDIAN_RADIUS).min(height as isize - 1) {
                    for wx in (x - MEDIAN_RADIUS).max(0)..=(x + MEDIAN_RADIUS).min(width as isize - 1) {
                        window.push(offsets[wy as usize * width + wx as usize][axis]);
                    }
                }
                window.sort_by(f32::total_cmp);
                out[y as usize * width + x as usize][axis] = window[window.len() / 2];
            }
        }
    }
    out
}

/// The colour channels of a frame (alpha dropped).
pub(crate) fn colour_channels(frame: &FloatImage) -> FloatImage {
    if frame.channels() == 4 {
        let data = frame.data().chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
        FloatImage::from_data(frame.width(), frame.height(), 3, data).expect("sizes match")
    } else {
        frame.clone()
    }
}

/// Rec. 601 luma of a 1- or 3-channel image.
pub(crate) fn luminance(image: &FloatImage) -> FloatImage {
    let data = if image.channels() >= 3 {
        image.data().chunks_exact(image.channels()).map(|p| 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]).collect()
    } else {
        image.data().to_vec()
    };
    FloatImage::from_data(image.width(), image.height(), 1, data).expect("sizes match")
}

/// The positional guide of an unmoved frame: red grows with x, green with y (Jamriška et al.'s
/// G_pos, here with a constant blue so that it has the three channels a guide may have).
pub fn coordinate_guide(width: usize, height: usize) -> FloatImage {
    let (scale_x, scale_y) =
        (1.0 / width.saturating_sub(1).max(1) as f32, 1.0 / height.saturating_sub(1).max(1) as f32);
    let mut data = Vec::with_capacity(width * height * 3);
    for y in 0..height {
        for x in 0..width {
            data.extend_from_slice(&[x as f32 * scale_x, y as f32 * scale_y, 0.0]);
        }
    }
    FloatImage::from_data(width, height, 3, data).expect("sizes match")
}

/// The edge guide (G_edge): the gradient magnitude of the blurred luma, blurred again, so that
/// the style's strokes follow the frame's edges.
pub fn edge_guide(frame: &FloatImage) -> FloatImage {
    let luma = luminance(&colour_channels(frame)).blur();
    let (width, height) = (luma.width(), luma.height());
    let mut edges = FloatImage::new(width, height, 1);
    for y in 0..height {
        for x in 0..width {
            let at = |dx: isize, dy: isize| clamped(&luma, x as isize + dx, y as isize + dy);
            let gx = (at(1, -1) + 2.0 * at(1, 0) + at(1, 1)) - (at(-1, -1) + 2.0 * at(-1, 0) + at(-1, 1));
            let gy = (at(-1, 1) + 2.0 * at(0, 1) + at(1, 1)) - (at(-1, -1) + 2.0 * at(0, -1) + at(1, -1));
            // A Sobel response of 0.5 (a step of an eighth of the range) saturates.
            edges.pixel_mut(x, y)[0] = (2.0 * (gx * gx + gy * gy).sqrt()).min(1.0);
        }
    }
    edges.blur()
}

/// Temporal flicker: the mean absolute difference between consecutive `frames` after motion
/// compensation (`motion[i]` carries frame `i` to frame `i + 1`), over the pixels that were
/// visible in both and the colour channels. 0 for fewer than two frames.
pub fn flicker(frames: &[FloatImage], motion: &[MotionField]) -> f64 {
    let mut total = 0.0;
    let mut count = 0usize;
    for (pair, carried) in frames.windows(2).zip(motion) {
        let warped = carried.warp(&pair[0]);
        let channels = warped.channels().min(3);
        let stride = warped.channels();
        for index in 0..carried.width * carried.height {
            if !carried.came_from_inside(index) {
                continue;
            }
            let (a, b) = (&warped.data()[index * stride..], &pair[1].data()[index * stride..]);
            total += (0..channels).map(|c| f64::from((a[c] - b[c]).abs())).sum::<f64>() / channels as f64;
            count += 1;
        }
    }
    if count == 0 { 0.0 } else { total / count as f64 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tests::texture;

    /// `image` moved by `(shift_x, shift_y)`: the result at `p` is `image` at `p − shift`.
    fn shifted(image: &FloatImage, shift_x: f64, shift_y: f64) -> FloatImage {
        let mut out = FloatImage::new(image.width(), image.height(), image.channels());
        for y in 0..image.height() {
            for x in 0..image.width() {
                image.sample_bilinear(x as f64 + 0.5 - shift_x, y as f64 + 0.5 - shift_y, out.pixel_mut(x, y));
            }
        }
        out
    }

    #[test]
    fn the_motion_of_a_shifted_texture_is_found_to_a_fraction_of_a_pixel() {
        let frame = texture(72, 56, 3, 17).blur();
        for (shift_x, shift_y) in [(3.0, -2.0), (1.5, 0.5), (0.0, 0.0)] {
            let later = shifted(&frame, shift_x, shift_y);
            let motion = estimate_motion(&frame, &later, 1).unwrap();
            // Away from the borders (where content entered the frame) the offset is −shift.
            let mut error = 0.0;
            let mut count = 0;
            for y in 8..48 {
                for x in 8..64 {
                    let [dx, dy] = motion.offsets[y * 72 + x];
                    error += (f64::from(dx) + shift_x).abs() + (f64::from(dy) + shift_y).abs();
                    count += 1;
                }
            }
            let mean = error / f64::from(count);
            assert!(mean < 0.25, "shift ({shift_x}, {shift_y}): mean offset error {mean:.3} px");
            // Warping the earlier frame along the motion gives the later one.
            let warped = motion.warp(&frame);
            let difference: f32 = (8..48)
                .flat_map(|y| (8..64).map(move |x| (x, y)))
                .map(|(x, y)| (warped.pixel(x, y)[0] - later.pixel(x, y)[0]).abs())
                .sum::<f32>()
                / (40.0 * 56.0);
            assert!(difference < 0.02, "warped frame differs by {difference:.4}");
        }
    }

    #[test]
    fn identical_frames_have_no_motion() {
        let frame = texture(48, 40, 3, 5);
        let motion = estimate_motion(&frame, &frame, 2).unwrap();
        assert!(motion.offsets.iter().all(|&[dx, dy]| dx == 0.0 && dy == 0.0));
        assert_eq!(motion.warp(&frame), frame);
    }
}
