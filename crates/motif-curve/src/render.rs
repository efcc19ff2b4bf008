//! Rasterization of the result: anti-aliased, transparent background.
//!
//! Every canvas pixel is covered by `n × n` samples; a sample takes its colour from each shape
//! (a placed piece, or a triangle of the repeat baseline) that contains it, composited "over" in
//! shape order with premultiplied alpha, and the pixel is the mean of its samples. The canvas is
//! cut into tiles rendered in parallel; each tile only looks at the shapes whose box meets it.

use motif_core::{Point, RgbaImage};

use crate::exemplar::Exemplar;
use crate::piece::{PieceFrame, Position};
use crate::{avoidance, stitch};
use rayon::prelude::*;

const TILE: usize = 32;

/// A shape to draw: its canvas pixel box and a sampler returning a premultiplied colour for the
/// canvas points it covers (`None` outside).
pub(crate) struct Shape<'a> {
    pub bounds: (usize, usize, usize, usize),
    pub sampler: Box<dyn Fn(Point) -> Option<[f32; 4]> + Sync + 'a>,
}

/// Renders `shapes` onto a `width × height` transparent canvas with `n × n` samples per pixel.
pub(crate) fn render(width: usize, height: usize, samples_per_axis: usize, shapes: &[Shape<'_>]) -> RgbaImage {
    let n = samples_per_axis;
    let tiles_x = width.div_ceil(TILE);
    let tiles_y = height.div_ceil(TILE);
    // Each tile's shapes, in shape order: binned once by their boxes (testing every shape's box
    // against every tile cost more than drawing on the canvases of the bent pieces, which are
    // thousands of small triangles).
    let mut binned: Vec<Vec<&Shape<'_>>> = vec![Vec::new(); tiles_x * tiles_y];
    for shape in shapes {
        let (sx0, sy0, sx1, sy1) = shape.bounds;
        if sx0 >= sx1.min(width) || sy0 >= sy1.min(height) {
            continue;
        }
        for ty in sy0 / TILE..=(sy1.min(height) - 1) / TILE {
            for tx in sx0 / TILE..=(sx1.min(width) - 1) / TILE {
                binned[ty * tiles_x + tx].push(shape);
            }
        }
    }
    let tiles: Vec<Vec<[u8; 4]>> = binned
        .into_par_iter()
        .enumerate()
        .map(|(tile, relevant)| {
            let (tx, ty) = (tile % tiles_x, tile / tiles_x);
            let (x0, y0) = (tx * TILE, ty * TILE);
            let (x1, y1) = ((x0 + TILE).min(width), (y0 + TILE).min(height));
            let (tile_width, tile_height) = (x1 - x0, y1 - y0);
            if relevant.is_empty() {
                return vec![[0_u8; 4]; tile_width * tile_height];
            }
            // Shape by shape over the pixels of its box, each sample composited "over" what the
            // earlier shapes left there: per sample the same operations in the same order as
            // pixel by pixel over the shapes covering it, without testing every pixel against
            // the boxes of every shape near it (the bent pieces and the repeat baseline draw
            // thousands of small triangles).
            let per_pixel = n * n;
            let mut samples = vec![[0.0_f32; 4]; tile_width * tile_height * per_pixel];
            let mut covered = vec![false; tile_width * tile_height];
            for shape in &relevant {
                let (sx0, sy0, sx1, sy1) = shape.bounds;
                for y in sy0.max(y0)..sy1.min(y1) {
                    for x in sx0.max(x0)..sx1.min(x1) {
                        let pixel = (y - y0) * tile_width + x - x0;
                        covered[pixel] = true;
                        let slots = &mut samples[pixel * per_pixel..(pixel + 1) * per_pixel];
                        for (colour, p) in slots.iter_mut().zip(crate::avoidance::sample_points(x, y, n)) {
                            if let Some(src) = (shape.sampler)(p) {
                                let keep = 1.0 - src[3];
                                for c in 0..4 {
                                    colour[c] = src[c] + colour[c] * keep;
                                }
                            }
                        }
                    }
                }
            }
            let mut pixels = vec![[0_u8; 4]; tile_width * tile_height];
            for (pixel, out) in pixels.iter_mut().enumerate() {
                if !covered[pixel] {
                    continue;
                }
                let mut sum = [0.0_f32; 4];
                for colour in &samples[pixel * per_pixel..(pixel + 1) * per_pixel] {
                    for c in 0..4 {
                        sum[c] += colour[c];
                    }
                }
                *out = to_straight(sum, per_pixel as f32);
            }
            pixels
        })
        .collect();
    let mut image = RgbaImage::new(width, height);
    for (tile, pixels) in tiles.into_iter().enumerate() {
        let (tx, ty) = (tile % tiles_x, tile / tiles_x);
        let (x0, y0) = (tx * TILE, ty * TILE);
        let tile_width = (x0 + TILE).min(width) - x0;
        for (i, pixel) in pixels.into_iter().enumerate() {
            image.set(x0 + i % tile_width, y0 + i / tile_width, pixel);
        }
    }
    image
}

/// Mean premultiplied colour → straight 8-bit RGBA.
fn to_straight(sum: [f32; 4], count: f32) -> [u8; 4] {
    let alpha = sum[3] / count;
    if alpha <= 0.0 {
        return [0, 0, 0, 0];
    }
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    [byte(sum[0] / sum[3]), byte(sum[1] / sum[3]), byte(sum[2] / sum[3]), byte(alpha)]
}

/// The shape drawing a rigid piece at exemplar position `u` (§1.3), deformed by its stitch.
pub(crate) fn rigid_shape<'a>(
    frame: &'a PieceFrame,
    u: Position,
    remap: Option<Vec<usize>>,
    exemplar: &'a Exemplar,
    canvas: (usize, usize),
) -> Shape<'a> {
    Shape {
        bounds: avoidance::canvas_box(frame, canvas.0, canvas.1),
        sampler: Box::new(move |p: Point| {
            let local = frame.to_local(p);
            if !frame.contains_local(local) {
                return None;
            }
            let local = match &remap {
                Some(remap) => stitch::deform(frame, remap, local),
                None => local,
            };
            let (x, y) = PieceFrame::exemplar_point(u, local);
            Some(exemplar.sample_premultiplied(x, y))
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_covered_pixels_are_half_transparent() {
        let shapes = [Shape {
            bounds: (0, 0, 4, 4),
            sampler: Box::new(|p: Point| if p.x < 2.0 { Some([1.0, 0.0, 0.0, 1.0]) } else { None }),
        }];
        let image = render(4, 4, 4, &shapes);
        assert_eq!(image.get(0, 0), [255, 0, 0, 255]);
        assert_eq!(image.get(3, 3), [0, 0, 0, 0]);
        let shapes = [Shape {
            bounds: (0, 0, 4, 4),
            sampler: Box::new(|p: Point| if p.x < 1.5 { Some([0.0, 1.0, 0.0, 1.0]) } else { None }),
        }];
        let image = render(4, 4, 4, &shapes);
        assert_eq!(image.get(1, 2), [0, 255, 0, 128]);
    }
}
