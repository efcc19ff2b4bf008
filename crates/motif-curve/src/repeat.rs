//! The classic baseline (`--method repeat`): arc-length texture mapping of the repeated exemplar
//! inside the ribbon, as pattern brushes do it.
//!
//! A ribbon point at arc length `x` and signed offset `y` from the curve (positive towards the
//! top) reads the exemplar at `(s·x mod W, (H − s·b)/2 + s·(b/2 − y))`: the exemplar is tiled
//! along the curve and centred across it, at the same scale as the synthesis. The ribbon is cut
//! into thin quads (one per resampled curve segment, split into two triangles) whose
//! `(x, y)` coordinates are interpolated linearly, which is what a texture-mapped strip does.
//! This bends the pattern with the curve (stretching it outside bends and squeezing it inside)
//! and shows a seam wherever the tile wraps; both are measured for comparison.

use motif_core::vector;
use motif_core::{Point, Vec2};

use crate::exemplar::Exemplar;
use crate::render::Shape;
use crate::ribbon::Ribbon;

/// A ribbon triangle with `(arc length, offset)` at its corners.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Triangle {
    pub corners: [Point; 3],
    pub coordinates: [Vec2; 3],
    /// `1 / ((b − a) × (c − a))`, 0 for a degenerate triangle (computed once: every render
    /// sample that the triangle's box holds needs it).
    inverse_area: f64,
}

impl Triangle {
    fn new(corners: [Point; 3], coordinates: [Vec2; 3]) -> Self {
        let [a, b, c] = corners;
        let det = (b - a).cross(c - a);
        let inverse_area = if det.abs() < 1e-12 { 0.0 } else { 1.0 / det };
        Self { corners, coordinates, inverse_area }
    }
}

/// The ribbon cut into triangles, plus the stretch of the top and bottom borders of every slice
/// (length along the offset curve / length along the centre curve).
pub(crate) fn triangulate(ribbon: &Ribbon) -> (Vec<Triangle>, Vec<f64>) {
    let length = ribbon.length();
    let steps = slice_count(ribbon);
    let half = 0.5 * ribbon.width();
    // Each slice is also cut across into bands of about BAND pixels, so that every triangle's box
    // is small and a render sample tests a few triangles, not every slice the ribbon's width
    // crosses.
    let bands = ((ribbon.width() / BAND).ceil() as usize).max(1);
    let xs: Vec<f64> = (0..=steps).map(|i| length * i as f64 / steps as f64).collect();
    let mut triangles = Vec::with_capacity(2 * steps * bands);
    let mut stretch = Vec::with_capacity(2 * steps);
    for pair in xs.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let (ta, ba, tb, bb) = (ribbon.top(a), ribbon.bottom(a), ribbon.top(b), ribbon.bottom(b));
        let centre = vector::distance(ribbon.point(a), ribbon.point(b)).max(1e-12);
        stretch.push(vector::distance(ta, tb) / centre);
        stretch.push(vector::distance(ba, bb) / centre);
        // The offset coordinate is in units of the base width (a width profile is divided out:
        // `top` and `bottom` carry it), so that the pattern's height always spans the ribbon.
        for band in 0..bands {
            let (u0, u1) = (band as f64 / bands as f64, (band + 1) as f64 / bands as f64);
            let (y0, y1) = (half - u0 * 2.0 * half, half - u1 * 2.0 * half);
            let (pa0, pa1, pb0, pb1) = (ta.lerp(ba, u0), ta.lerp(ba, u1), tb.lerp(bb, u0), tb.lerp(bb, u1));
            let (ca0, ca1, cb0, cb1) = (Vec2::new(a, y0), Vec2::new(a, y1), Vec2::new(b, y0), Vec2::new(b, y1));
            triangles.push(Triangle::new([pa0, pa1, pb1], [ca0, ca1, cb1]));
            triangles.push(Triangle::new([pa0, pb1, pb0], [ca0, cb1, cb0]));
        }
    }
    (triangles, stretch)
}

/// Number of slices [`triangulate`] cuts the ribbon into along its length (each one
/// `length / slices` long and made of the same number of triangles).
pub(crate) fn slice_count(ribbon: &Ribbon) -> usize {
    ((ribbon.length() / SLICE).ceil() as usize).max(2)
}

/// Length of a slice along the curve, canvas pixels: the linear interpolation inside a slice
/// strays from the ribbon's true coordinates by less than 0.05 px on the tightest bend that the
/// rounding of bends leaves (a radius of half the ribbon's width at its inner border).
const SLICE: f64 = 3.0;

/// Width of the bands the ribbon's slices are cut into across, canvas pixels.
const BAND: f64 = 4.0;

/// Barycentric interpolation of the triangle's coordinates at `p`, or `None` outside.
pub(crate) fn interpolate(triangle: &Triangle, p: Point) -> Option<Vec2> {
    if triangle.inverse_area == 0.0 {
        return None;
    }
    let [a, b, c] = triangle.corners;
    let (v0, v1, v2) = (b - a, c - a, p - a);
    let beta = v2.cross(v1) * triangle.inverse_area;
    let gamma = v0.cross(v2) * triangle.inverse_area;
    let alpha = 1.0 - beta - gamma;
    let eps = -1e-9;
    if alpha < eps || beta < eps || gamma < eps {
        return None;
    }
    let [ca, cb, cc] = triangle.coordinates;
    Some(ca * alpha + cb * beta + cc * gamma)
}

/// Premultiplied bilinear lookup with the exemplar repeated horizontally.
fn sample_wrapped(exemplar: &Exemplar, x: f64, y: f64) -> [f32; 4] {
    let w = f64::from(exemplar.width);
    let fx = x - 0.5;
    let fy = y - 0.5;
    let (x0, y0) = (fx.floor(), fy.floor());
    let (tx, ty) = ((fx - x0) as f32, (fy - y0) as f32);
    let mut out = [0.0_f32; 4];
    for (dx, dy, weight) in [
        (0.0, 0.0, (1.0 - tx) * (1.0 - ty)),
        (1.0, 0.0, tx * (1.0 - ty)),
        (0.0, 1.0, (1.0 - tx) * ty),
        (1.0, 1.0, tx * ty),
    ] {
        let px = (x0 + dx).rem_euclid(w) as i32;
        let py = y0 + dy;
        if weight == 0.0 || py < 0.0 || py >= f64::from(exemplar.height) {
            continue;
        }
        let pixel = exemplar.premultiplied_at(px, py as i32);
        for c in 0..4 {
            out[c] += weight * pixel[c];
        }
    }
    out
}

/// The canvas pixel box of a triangle, clipped to the canvas.
pub(crate) fn triangle_bounds(triangle: &Triangle, canvas: (usize, usize)) -> (usize, usize, usize, usize) {
    let xs = triangle.corners.map(|c| c.x);
    let ys = triangle.corners.map(|c| c.y);
    let clip = |v: f64, limit: usize| v.clamp(0.0, limit as f64) as usize;
    (
        clip(xs.iter().copied().fold(f64::INFINITY, f64::min).floor(), canvas.0),
        clip(ys.iter().copied().fold(f64::INFINITY, f64::min).floor(), canvas.1),
        clip(xs.iter().copied().fold(f64::NEG_INFINITY, f64::max).ceil() + 1.0, canvas.0),
        clip(ys.iter().copied().fold(f64::NEG_INFINITY, f64::max).ceil() + 1.0, canvas.1),
    )
}

/// Shapes drawing the repeated exemplar along the ribbon at scale `scale`.
pub(crate) fn shapes<'a>(
    triangles: &'a [Triangle],
    exemplar: &'a Exemplar,
    ribbon_width: f64,
    scale: f64,
    canvas: (usize, usize),
) -> Vec<Shape<'a>> {
    let centre_offset = (f64::from(exemplar.height) - scale * ribbon_width) / 2.0;
    let half = 0.5 * ribbon_width;
    triangles
        .iter()
        .map(|triangle| Shape {
            bounds: triangle_bounds(triangle, canvas),
            sampler: Box::new(move |p: Point| {
                let coordinates = interpolate(triangle, p)?;
                let x = scale * coordinates.x;
                let y = centre_offset + scale * (half - coordinates.y);
                Some(sample_wrapped(exemplar, x, y))
            }),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use motif_core::Polyline;
    use motif_core::math;

    #[test]
    fn straight_ribbons_are_not_stretched_and_bends_are() {
        let line = Polyline::new(vec![Point::new(0.0, 10.0), Point::new(50.0, 10.0)], false).unwrap();
        let (triangles, stretch) = triangulate(&Ribbon::new(&line, 8.0).unwrap());
        assert!(stretch.iter().all(|s| (s - 1.0).abs() < 1e-9));
        let inside = interpolate(&triangles[0], Point::new(0.2, 10.0)).unwrap();
        assert!((inside.y).abs() < 0.5, "{inside:?}");
        let points = (0..100).map(|i| {
            let a = i as f64 / 100.0 * std::f64::consts::TAU;
            Point::new(30.0 * math::cos(a), 30.0 * math::sin(a))
        });
        let circle = Polyline::new(points.collect(), true).unwrap();
        let (_, stretch) = triangulate(&Ribbon::new(&circle, 10.0).unwrap());
        let worst = stretch.iter().map(|s| (s - 1.0).abs()).fold(0.0, f64::max);
        assert!((worst - 5.0 / 30.0).abs() < 0.02, "{worst}");
    }
}
