//! Pieces that bend with the ribbon (not in the paper, whose pieces are rigid).
//!
//! A rigid piece keeps its left edge vertical in the exemplar, so on a curve its right edge is
//! tilted against the next piece's left edge (by the angle the curve turns over one piece). For a
//! pattern whose structures span the ribbon (the interlocked rings of a real chain), a tilted
//! column is found nowhere in the exemplar as a vertical one, and the cheapest seams become the
//! ones that cross the holes of the rings: the result is a row of C-shaped half links. A bent
//! piece reads the exemplar in ribbon coordinates instead, as the repeat baseline does: the canvas
//! point at arc length `x` and offset `y` from the curve shows exemplar pixel
//! `u_i + s · (x − x_i, b/2 − y)`. Every seam is then a vertical column on both sides, the piece
//! that continues the exemplar matches exactly, and the dynamic program (still the exact
//! optimum, §1.4) cuts only where it has to; the price is the repeat baseline's stretch outside
//! bends and squeeze inside them, which the rounding of tight bends keeps moderate.

use motif_core::{Point, Vec2};

use crate::avoidance::{ForbiddenMask, sample_points};
use crate::exemplar::Exemplar;
use crate::piece::{PieceFrame, Position};
use crate::render::Shape;
use crate::repeat::Triangle;
use crate::ribbon::PieceQuad;

/// The frame of a bent piece: the frame of the same piece laid straight (a `length × b`
/// rectangle), which is what it looks like in ribbon coordinates.
/// With a width profile the piece's width is `width × factor` and its scale `scale / factor`: the
/// pattern grows with the ribbon and still spans `C` samples.
pub(crate) fn straight_frame(quad: &PieceQuad, width: f64, scale: f64, samples: usize) -> PieceFrame {
    let length = quad.end - quad.start;
    let straight = PieceQuad {
        start: quad.start,
        end: quad.end,
        corners: [Point::new(0.0, 0.0), Point::new(0.0, width), Point::new(length, width), Point::new(length, 0.0)],
    };
    PieceFrame::new(&straight, scale, samples)
}

/// The local points (exemplar offsets from the piece's corner) of the render samples of a bent
/// piece that lie in forbidden canvas pixels. The samples are mapped to ribbon coordinates through
/// the same triangles the renderer uses (`slices` slices `spacing` long, each made of the same
/// number of consecutive triangles), so the test sees exactly the points that will be drawn.
pub(crate) fn forbidden_samples(
    triangles: &[Triangle],
    (spacing, slices): (f64, usize),
    quad: &PieceQuad,
    ribbon_width: f64,
    [along_scale, scale]: [f64; 2],
    mask: &ForbiddenMask,
    samples_per_axis: usize,
) -> Vec<Vec2> {
    let per_slice = triangles.len() / slices.max(1);
    let first = ((quad.start / spacing).floor() as usize).saturating_sub(1) * per_slice;
    let last = (((quad.end / spacing).ceil() as usize + 1) * per_slice).min(triangles.len());
    let mine = &triangles[first.min(last)..last];
    let half = 0.5 * ribbon_width;
    let mut points = Vec::new();
    for triangle in mine {
        let (x0, y0, x1, y1) = crate::repeat::triangle_bounds(triangle, (mask.width, mask.height));
        for y in y0..y1 {
            for x in x0..x1 {
                if !mask.is_forbidden(x, y) {
                    continue;
                }
                for p in sample_points(x, y, samples_per_axis) {
                    if let Some(c) = crate::repeat::interpolate(triangle, p)
                        && c.x >= quad.start
                        && c.x <= quad.end
                    {
                        points.push(Vec2::new(along_scale * (c.x - quad.start), scale * (half - c.y)));
                    }
                }
            }
        }
    }
    points
}

/// What the renderer needs of one placed bent piece.
pub(crate) struct BentPiece<'a> {
    /// Arc length where the piece starts (pieces are in order).
    pub start: f64,
    /// Arc length after which nothing is drawn until the next piece: its end when pieces are
    /// spaced out ([`Fit::Space`](crate::Fit::Space)), otherwise infinite (contiguous pieces, and
    /// the ribbon's far end drawn by the last one).
    pub visible_end: f64,
    /// `None` for a piece left empty.
    pub position: Option<Position>,
    pub frame: &'a PieceFrame,
    pub remap: Option<Vec<usize>>,
    /// Exemplar pixels per canvas pixel along the piece (the scale over the width factor).
    pub along_scale: f64,
}

/// Shapes drawing bent pieces: the ribbon's triangles, each sample read from the piece whose arc
/// range holds its arc length.
pub(crate) fn shapes<'a>(
    triangles: &'a [Triangle],
    pieces: &'a [BentPiece<'a>],
    exemplar: &'a Exemplar,
    ribbon_width: f64,
    scale: f64,
    canvas: (usize, usize),
) -> Vec<Shape<'a>> {
    let half = 0.5 * ribbon_width;
    triangles
        .iter()
        .map(|triangle| Shape {
            bounds: crate::repeat::triangle_bounds(triangle, canvas),
            sampler: Box::new(move |p: Point| {
                let coordinates = crate::repeat::interpolate(triangle, p)?;
                let index = pieces.partition_point(|piece| piece.start <= coordinates.x).max(1) - 1;
                let piece = &pieces[index];
                if coordinates.x > piece.visible_end {
                    return None;
                }
                let position = piece.position?;
                let mut local =
                    Vec2::new(piece.along_scale * (coordinates.x - piece.start), scale * (half - coordinates.y));
                if let Some(remap) = &piece.remap {
                    local = crate::stitch::deform(piece.frame, remap, local);
                }
                let (x, y) = PieceFrame::exemplar_point(position, local);
                Some(exemplar.sample_premultiplied(x, y))
            }),
        })
        .collect()
}
