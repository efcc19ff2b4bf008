//! Element fitting (§2.1): an oriented bounding box fitted to a set of points, and the box
//! distances the clustering and matching measures are built on.
//!
//! The principal axes are the eigenvectors of the points' covariance. The points are treated as
//! the curves they sample (every polyline segment weighted by its length), so that the fit does
//! not depend on how finely a curve was flattened.

use kurbo::{Rect, Vec2};
use motif_core::geometry::perpendicular;
use motif_core::{Point, Polyline};
use motif_core::{math, vector};

use crate::params::FitPoints;
use crate::stroke::Stroke;

/// An element's oriented bounding box: centre, principal axis A and secondary axis B.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrientedBox {
    /// Centre c of the box.
    pub centre: Point,
    /// Unit direction of the principal axis A (the direction of largest variance).
    pub axis: Vec2,
    /// |A|: the box's extent along A.
    pub length: f64,
    /// |B|: the box's extent along B (A turned by +90°), the element's thickness.
    pub thickness: f64,
}

impl OrientedBox {
    /// Unit direction of the secondary axis B.
    pub fn secondary_axis(&self) -> Vec2 {
        perpendicular(self.axis)
    }

    /// Orientation of the principal axis in `[0, π)` (axes are undirected).
    pub fn angle(&self) -> f64 {
        math::atan2(self.axis.y, self.axis.x).rem_euclid(std::f64::consts::PI)
    }

    /// The four corners.
    pub fn corners(&self) -> [Point; 4] {
        let a = self.axis * (0.5 * self.length);
        let b = self.secondary_axis() * (0.5 * self.thickness);
        [self.centre - a - b, self.centre + a - b, self.centre + a + b, self.centre - a + b]
    }

    /// Distance from `point` to the box as a solid rectangle (0 inside).
    pub fn distance_to(&self, point: Point) -> f64 {
        let d = point - self.centre;
        let u = (d.dot(self.axis).abs() - 0.5 * self.length).max(0.0);
        let v = (d.dot(self.secondary_axis()).abs() - 0.5 * self.thickness).max(0.0);
        math::hypot(u, v)
    }

    /// Directed Hausdorff distance d_H(self, other) between the solid boxes. The distance to a
    /// convex set is a convex function, so its maximum over `self` is reached at a corner: four
    /// point-box distances give the exact value.
    pub fn directed_hausdorff(&self, other: &OrientedBox) -> f64 {
        self.corners().iter().map(|&corner| other.distance_to(corner)).fold(0.0, f64::max)
    }

    /// The same box moved to `centre`.
    pub fn moved_to(&self, centre: Point) -> OrientedBox {
        OrientedBox { centre, ..*self }
    }

    /// The box rotated by `angle` radians about its centre.
    pub fn rotated(&self, angle: f64) -> OrientedBox {
        let (sin, cos) = math::sin_cos(angle);
        let axis = Vec2::new(cos * self.axis.x - sin * self.axis.y, sin * self.axis.x + cos * self.axis.y);
        OrientedBox { axis, ..*self }
    }

    /// Axis-aligned bounds of the box.
    pub fn bounds(&self) -> Rect {
        motif_core::geometry::bounds_of(&self.corners())
    }
}

/// Length-weighted first and second moments of a set of segments: what a box fit needs, and
/// additive, so that merged clusters are refitted without revisiting their strokes' segments.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Moments {
    weight: f64,
    sum: Vec2,
    xx: f64,
    xy: f64,
    yy: f64,
}

impl Moments {
    /// Adds segment `p0 → p1` as a uniform density along it.
    pub(crate) fn add_segment(&mut self, p0: Point, p1: Point) {
        let length = vector::distance(p0, p1);
        if length <= 0.0 {
            return;
        }
        let (a, d) = (p0.to_vec2(), p1 - p0);
        // E[(a + t d)(a + t d)ᵀ] for t uniform in [0, 1].
        self.weight += length;
        self.sum += (a + d * 0.5) * length;
        self.xx += length * (a.x * a.x + a.x * d.x + d.x * d.x / 3.0);
        self.yy += length * (a.y * a.y + a.y * d.y + d.y * d.y / 3.0);
        self.xy += length * (a.x * a.y + 0.5 * (a.x * d.y + d.x * a.y) + d.x * d.y / 3.0);
    }

    /// Adds every segment of a polyline (with its closing segment when closed).
    pub(crate) fn add_polyline(&mut self, polyline: &Polyline) {
        let points = polyline.points();
        for pair in points.windows(2) {
            self.add_segment(pair[0], pair[1]);
        }
        if polyline.is_closed() {
            self.add_segment(points[points.len() - 1], points[0]);
        }
    }

    /// The sum of two moment sets.
    pub(crate) fn merged(&self, other: &Moments) -> Moments {
        Moments {
            weight: self.weight + other.weight,
            sum: self.sum + other.sum,
            xx: self.xx + other.xx,
            xy: self.xy + other.xy,
            yy: self.yy + other.yy,
        }
    }

    /// Mean point (origin for an empty set).
    pub(crate) fn mean(&self) -> Point {
        if self.weight > 0.0 { (self.sum / self.weight).to_point() } else { Point::ORIGIN }
    }

    /// Unit principal direction: the eigenvector of the covariance with the larger eigenvalue.
    /// An isotropic set gives the x axis.
    pub(crate) fn principal_axis(&self) -> Vec2 {
        if self.weight <= 0.0 {
            return Vec2::new(1.0, 0.0);
        }
        let mean = self.sum / self.weight;
        let cxx = self.xx / self.weight - mean.x * mean.x;
        let cyy = self.yy / self.weight - mean.y * mean.y;
        let cxy = self.xy / self.weight - mean.x * mean.y;
        let scale = (cxx.abs() + cyy.abs()).max(1e-300);
        if ((cxx - cyy).abs() + 2.0 * cxy.abs()) <= 1e-12 * scale {
            return Vec2::new(1.0, 0.0);
        }
        let angle = 0.5 * math::atan2(2.0 * cxy, cxx - cyy);
        canonical_axis(Vec2::new(math::cos(angle), math::sin(angle)))
    }
}

/// The undirected axis `axis` written with a deterministic sign: angle in `[0, π)`.
pub(crate) fn canonical_axis(axis: Vec2) -> Vec2 {
    if axis.y < 0.0 || (axis.y == 0.0 && axis.x < 0.0) { -axis } else { axis }
}

/// The points one stroke contributes to a fit, with their moments.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct FitSet {
    /// The points whose projections give the box extents.
    pub points: Vec<Point>,
    /// Length-weighted moments of the curves through `points`.
    pub moments: Moments,
}

impl FitSet {
    /// The skeleton or contour points of `stroke` (§2.1).
    pub(crate) fn of_stroke(stroke: &Stroke, fit: FitPoints) -> FitSet {
        let skeleton = &stroke.polyline;
        let half_width = 0.5 * stroke.width;
        if fit == FitPoints::Skeleton || half_width <= 0.0 {
            let mut moments = Moments::default();
            moments.add_polyline(skeleton);
            return FitSet { points: skeleton.points().to_vec(), moments };
        }
        // The stroked outline: both offsets of the skeleton, joined by round caps at the ends of
        // an open stroke (closed strokes have an inner and an outer ring instead).
        let (Ok(left), Ok(right)) = (skeleton.offset(half_width), skeleton.offset(-half_width)) else {
            return FitSet::of_stroke(stroke, FitPoints::Skeleton);
        };
        let mut moments = Moments::default();
        if skeleton.is_closed() {
            moments.add_polyline(&left);
            moments.add_polyline(&right);
            let mut points = left.points().to_vec();
            points.extend_from_slice(right.points());
            return FitSet { points, moments };
        }
        let points_of = skeleton.points();
        let tangents = skeleton.vertex_tangents();
        let cap = |centre: Point, direction: Vec2| -> Vec<Point> {
            // Half circle from the left offset round the tip to the right offset.
            let normal = perpendicular(direction);
            (0..=8)
                .map(|i| {
                    let angle = std::f64::consts::PI * i as f64 / 8.0;
                    centre + (normal * math::cos(angle) + direction * math::sin(angle)) * half_width
                })
                .collect()
        };
        let last = points_of.len() - 1;
        let mut outline: Vec<Point> = left.points().to_vec();
        outline.extend(cap(points_of[last], tangents[last]).into_iter().skip(1));
        outline.extend(right.points().iter().rev().skip(1).copied());
        outline.extend(cap(points_of[0], -tangents[0]).into_iter().skip(1));
        for pair in outline.windows(2) {
            moments.add_segment(pair[0], pair[1]);
        }
        FitSet { points: outline, moments }
    }
}

/// Fits the oriented box of a union of fit sets: axes from the summed moments, extents and centre
/// from the projections of every point.
pub(crate) fn fit_box<'a>(moments: &Moments, sets: impl Iterator<Item = &'a FitSet>) -> OrientedBox {
    let axis = moments.principal_axis();
    let secondary = perpendicular(axis);
    let mean = moments.mean();
    let (mut a_min, mut a_max, mut b_min, mut b_max) =
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for set in sets {
        for &point in &set.points {
            let d = point - mean;
            let (a, b) = (d.dot(axis), d.dot(secondary));
            a_min = a_min.min(a);
            a_max = a_max.max(a);
            b_min = b_min.min(b);
            b_max = b_max.max(b);
        }
    }
    if !a_min.is_finite() {
        return OrientedBox { centre: mean, axis, length: 0.0, thickness: 0.0 };
    }
    let centre = mean + axis * (0.5 * (a_min + a_max)) + secondary * (0.5 * (b_min + b_max));
    OrientedBox { centre, axis, length: a_max - a_min, thickness: b_max - b_min }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(a: (f64, f64), b: (f64, f64), width: f64) -> Stroke {
        Stroke {
            polyline: Polyline::new(vec![Point::new(a.0, a.1), Point::new(b.0, b.1)], false).unwrap(),
            width,
            colour: [0, 0, 0, 255],
            fill: None,
            dash: None,
        }
    }

    #[test]
    fn a_diagonal_segment_gives_a_thin_box_along_it() {
        let set = FitSet::of_stroke(&line((0.0, 0.0), (30.0, 40.0), 2.0), FitPoints::Skeleton);
        let fitted = fit_box(&set.moments, std::iter::once(&set));
        assert!((fitted.length - 50.0).abs() < 1e-9);
        assert!(fitted.thickness.abs() < 1e-9);
        assert!(vector::distance(fitted.centre, Point::new(15.0, 20.0)) < 1e-9);
        assert!((fitted.axis.dot(Vec2::new(0.6, 0.8)).abs() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn contour_fit_takes_the_width_into_account() {
        let stroke = line((0.0, 0.0), (20.0, 0.0), 4.0);
        let set = FitSet::of_stroke(&stroke, FitPoints::Contour);
        let fitted = fit_box(&set.moments, std::iter::once(&set));
        assert!((fitted.length - 24.0).abs() < 1e-9, "{fitted:?}");
        assert!((fitted.thickness - 4.0).abs() < 1e-9, "{fitted:?}");
        assert!(vector::distance(fitted.centre, Point::new(10.0, 0.0)) < 1e-9);
    }

    #[test]
    fn hausdorff_between_boxes_matches_dense_sampling() {
        let a = OrientedBox { centre: Point::new(0.0, 0.0), axis: Vec2::new(1.0, 0.0), length: 10.0, thickness: 2.0 };
        let b = OrientedBox { centre: Point::new(3.0, 7.0), axis: Vec2::new(0.6, 0.8), length: 6.0, thickness: 1.0 };
        for (p, q) in [(a, b), (b, a)] {
            let mut brute: f64 = 0.0;
            for i in 0..=60 {
                for j in 0..=60 {
                    let point = p.centre
                        + p.axis * p.length * (i as f64 / 60.0 - 0.5)
                        + p.secondary_axis() * p.thickness * (j as f64 / 60.0 - 0.5);
                    brute = brute.max(q.distance_to(point));
                }
            }
            assert!((p.directed_hausdorff(&q) - brute).abs() < 1e-9);
        }
        assert_eq!(a.directed_hausdorff(&a), 0.0);
    }
}
