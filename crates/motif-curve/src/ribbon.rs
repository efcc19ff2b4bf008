//! The ribbon around the curve and its slicing into pieces (§1.1, §1.3).
//!
//! The ribbon's top and bottom curves are `T(x) = C(x) + b/2 · up(x)` and
//! `B(x) = C(x) - b/2 · up(x)`, where `up(x)` is the curve's unit normal on the side that shows the
//! top of the exemplar. With y pointing down on screen, a curve drawn left to right has `up`
//! pointing to the top of the screen, so the pattern appears upright. Normals are interpolated
//! smoothly along a finely resampled copy of the curve, so `‖B(x) − T(x)‖ = b` exactly at every
//! slice and every left edge has the same length (hence one `C` for all pieces).

use motif_core::vector;
use motif_core::{InvalidParameter, Point, Polyline, Vec2};

/// The ribbon: a finely resampled centre curve with smooth normals, and a width, constant or
/// varying along the curve by a profile of factors.
#[derive(Debug, Clone)]
pub(crate) struct Ribbon {
    centre: Polyline,
    up: Vec<Vec2>,
    width: f64,
    /// `(t, factor)` pairs, `t` the fraction of the arc length, ascending; empty for a constant
    /// width. The width at `t` is `width ×` the linearly interpolated factor.
    profile: Vec<(f64, f64)>,
}

impl Ribbon {
    /// Builds the ribbon of `width` around `curve`.
    pub(crate) fn new(curve: &Polyline, width: f64) -> Result<Self, InvalidParameter> {
        let length = curve.length();
        let step = (length / 64.0).min(1.0);
        let centre = curve.resample(step)?;
        // up = −(core normal) = (t.y, −t.x): the top of a left-to-right curve is the top of the screen.
        let up = centre.vertex_tangents().into_iter().map(|t| Vec2::new(t.y, -t.x)).collect();
        Ok(Self { centre, up, width, profile: Vec::new() })
    }

    /// The same ribbon with the width varying by `profile` (see [`Ribbon::factor`]).
    pub(crate) fn with_profile(mut self, profile: &[(f64, f64)]) -> Self {
        self.profile = profile.to_vec();
        self
    }

    /// The width factor at arc length `x`: 1 without a profile; else the profile's factors
    /// interpolated linearly in the fraction of the arc length, held constant beyond its ends.
    pub(crate) fn factor(&self, x: f64) -> f64 {
        let Some(&(first_t, first)) = self.profile.first() else {
            return 1.0;
        };
        let t = x / self.length().max(1e-12);
        if t <= first_t {
            return first;
        }
        for pair in self.profile.windows(2) {
            let ((t0, f0), (t1, f1)) = (pair[0], pair[1]);
            if t <= t1 {
                return if t1 > t0 { f0 + (f1 - f0) * (t - t0) / (t1 - t0) } else { f1 };
            }
        }
        self.profile.last().map_or(1.0, |&(_, f)| f)
    }

    /// Arc length of the curve.
    pub(crate) fn length(&self) -> f64 {
        self.centre.length()
    }

    /// Ribbon width `b` (times [`Ribbon::factor`] along a profile).
    pub(crate) fn width(&self) -> f64 {
        self.width
    }

    /// The point `C(x)` on the curve.
    pub(crate) fn point(&self, x: f64) -> Point {
        self.centre.point_at(x)
    }

    /// The arc length of the centre's point nearest to `point`.
    pub(crate) fn nearest(&self, point: Point) -> f64 {
        let cumulative = self.centre.cumulative_lengths();
        let points = self.centre.points();
        let mut best = (f64::INFINITY, 0.0);
        for segment in 0..self.centre.segment_count() {
            let (a, b) = (points[segment], points[(segment + 1) % points.len()]);
            let along = b - a;
            let squared = along.x * along.x + along.y * along.y;
            let t = if squared > 0.0 {
                (((point - a).x * along.x + (point - a).y * along.y) / squared).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let distance = vector::distance(a + along * t, point);
            if distance < best.0 {
                best = (distance, cumulative[segment] + t * (cumulative[segment + 1] - cumulative[segment]));
            }
        }
        best.1
    }

    /// The unit normal towards the top of the pattern at `x`, interpolated between vertices.
    pub(crate) fn up(&self, x: f64) -> Vec2 {
        let (segment, t) = self.centre.locate(x);
        let n = self.up.len();
        let a = self.up[segment % n];
        let b = self.up[(segment + 1) % n];
        let mixed = a.lerp(b, t);
        if vector::length(mixed) > 1e-9 { vector::normalized(mixed) } else { a }
    }

    /// `T(x)`, the top offset curve.
    pub(crate) fn top(&self, x: f64) -> Point {
        self.point(x) + self.up(x) * (0.5 * self.width * self.factor(x))
    }

    /// `B(x)`, the bottom offset curve.
    pub(crate) fn bottom(&self, x: f64) -> Point {
        self.point(x) - self.up(x) * (0.5 * self.width * self.factor(x))
    }
}

/// One piece of the ribbon in the canvas: the quadrilateral `(T(x_i), B(x_i), B(x_{i+1}), T(x_{i+1}))`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PieceQuad {
    /// Arc length where the piece starts, `x_i`.
    pub start: f64,
    /// Arc length where the piece ends, `x_{i+1}`.
    pub end: f64,
    /// Corners in the order top-left, bottom-left, bottom-right, top-right.
    pub corners: [Point; 4],
}

/// Slice positions `x_i = iδ`, `i ∈ [0..N]`, with a final shorter piece for the fractional part
/// (§1.3). A remainder shorter than half a canvas unit is absorbed by the last full piece, which
/// would otherwise be a sliver with no room for the pattern. Requires `δ ≤ L` (checked by the caller).
pub(crate) fn slice_positions(length: f64, delta: f64) -> Vec<f64> {
    let full = (length / delta).floor() as usize;
    let mut positions: Vec<f64> = (0..=full).map(|i| i as f64 * delta).collect();
    let remainder = length - full as f64 * delta;
    if remainder >= 0.5 || full == 0 {
        positions.push(length);
    } else {
        *positions.last_mut().expect("at least one slice") = length;
    }
    positions.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    positions
}

/// Slices the ribbon into pieces of length `delta` (§1.3).
#[cfg(test)]
pub(crate) fn slice(ribbon: &Ribbon, delta: f64) -> Vec<PieceQuad> {
    let positions = slice_positions(ribbon.length(), delta);
    let bounds: Vec<(f64, f64)> = positions.windows(2).map(|pair| (pair[0], pair[1])).collect();
    quads(ribbon, &bounds)
}

/// The pieces of the ribbon between each pair of arc lengths.
pub(crate) fn quads(ribbon: &Ribbon, bounds: &[(f64, f64)]) -> Vec<PieceQuad> {
    bounds
        .iter()
        .map(|&(start, end)| PieceQuad {
            start,
            end,
            corners: [ribbon.top(start), ribbon.bottom(start), ribbon.bottom(end), ribbon.top(end)],
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use motif_core::math;

    #[test]
    fn slicing_adds_a_shorter_final_piece() {
        assert_eq!(slice_positions(10.0, 3.0), vec![0.0, 3.0, 6.0, 9.0, 10.0]);
        assert_eq!(slice_positions(9.0, 3.0), vec![0.0, 3.0, 6.0, 9.0]);
        assert_eq!(slice_positions(9.2, 3.0), vec![0.0, 3.0, 6.0, 9.2]);
    }

    #[test]
    fn straight_ribbon_has_upright_rectangular_pieces() {
        let curve = Polyline::new(vec![Point::new(0.0, 50.0), Point::new(100.0, 50.0)], false).unwrap();
        let ribbon = Ribbon::new(&curve, 20.0).unwrap();
        let pieces = slice(&ribbon, 25.0);
        assert_eq!(pieces.len(), 4);
        let first = pieces[0].corners;
        assert!(vector::distance(first[0], Point::new(0.0, 40.0)) < 1e-9, "{first:?}");
        assert!(vector::distance(first[1], Point::new(0.0, 60.0)) < 1e-9);
        assert!(vector::distance(first[2], Point::new(25.0, 60.0)) < 1e-9);
        assert!(vector::distance(first[3], Point::new(25.0, 40.0)) < 1e-9);
    }

    #[test]
    fn every_slice_edge_has_the_ribbon_width() {
        let points = (0..200).map(|i| {
            let a = i as f64 / 200.0 * std::f64::consts::TAU;
            Point::new(100.0 + 60.0 * math::cos(a), 100.0 + 40.0 * math::sin(a))
        });
        let curve = Polyline::new(points.collect(), true).unwrap();
        let ribbon = Ribbon::new(&curve, 16.0).unwrap();
        for piece in slice(&ribbon, 13.0) {
            assert!((vector::distance(piece.corners[0], piece.corners[1]) - 16.0).abs() < 1e-9);
            assert!((vector::distance(piece.corners[3], piece.corners[2]) - 16.0).abs() < 1e-9);
        }
    }
}
