//! 2D curves and regions on `kurbo` points.
//!
//! [`Polyline`] is the curve type every engine walks along: it stores its vertices and their
//! cumulative arc length, so that points, tangents and normals can be looked up by arc length `s`.
//! Closed polylines wrap: `s` is taken modulo the length and the closing segment is part of the
//! curve. [`Polygon`] is a region (area, containment, simplicity).
//!
//! Normals are tangents turned by +90° in the `(x, y)` frame: `n = (-t.y, t.x)`. For a circle run
//! with increasing angle (`(cos θ, sin θ)`) they point to the centre; with y down on screen, that
//! is the clockwise-looking direction of travel.

use kurbo::{Affine, BezPath, ParamCurveNearest, PathEl, Point, Rect, Vec2};
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{RTree, RTreeObject};

use crate::{math, vector};

use crate::error::InvalidParameter;

/// A polyline with arc-length parameterization; open or closed.
#[derive(Debug, Clone, PartialEq)]
pub struct Polyline {
    points: Vec<Point>,
    closed: bool,
    /// `cumulative[i]` is the arc length at vertex `i`; for a closed curve a final entry holds the
    /// full length (back at vertex 0).
    cumulative: Vec<f64>,
}

impl Polyline {
    /// Builds a polyline. Consecutive duplicate points are dropped (and, for a closed curve, a
    /// last point equal to the first). Fails on non-finite coordinates, fewer than two distinct
    /// points, or zero length.
    pub fn new(points: Vec<Point>, closed: bool) -> Result<Self, InvalidParameter> {
        if let Some(bad) = points.iter().find(|p| !p.x.is_finite() || !p.y.is_finite()) {
            return Err(InvalidParameter::new(
                "curve",
                format!("point ({}, {})", bad.x, bad.y),
                "coordinates must be finite numbers",
            ));
        }
        let mut kept: Vec<Point> = Vec::with_capacity(points.len());
        for point in points {
            if kept.last().is_none_or(|last| vector::distance(*last, point) > 1e-9) {
                kept.push(point);
            }
        }
        if closed && kept.len() > 1 && vector::distance(kept[0], *kept.last().expect("non-empty")) <= 1e-9 {
            kept.pop();
        }
        if kept.len() < 2 {
            return Err(InvalidParameter::new(
                "curve",
                format!("{} distinct point(s)", kept.len()),
                "a curve needs at least two distinct points and a length > 0",
            ));
        }
        let mut cumulative = Vec::with_capacity(kept.len() + 1);
        let mut total = 0.0;
        cumulative.push(0.0);
        for pair in kept.windows(2) {
            total += vector::distance(pair[0], pair[1]);
            cumulative.push(total);
        }
        if closed {
            total += vector::distance(kept[kept.len() - 1], kept[0]);
            cumulative.push(total);
        }
        Ok(Self { points: kept, closed, cumulative })
    }

    /// Flattens every subpath of a Bézier path into a polyline, within `tolerance` (the maximum
    /// distance between the curve and its polyline, in the path's units). A subpath ending in
    /// `ClosePath` gives a closed polyline. Subpaths that collapse to a point are skipped.
    pub fn from_bez_path(path: &BezPath, tolerance: f64) -> Result<Vec<Polyline>, InvalidParameter> {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(InvalidParameter::new("tolerance", tolerance, "must be a finite number > 0"));
        }
        let mut polylines = Vec::new();
        let mut current: Vec<Point> = Vec::new();
        let mut first_error = None;
        let mut finish = |points: &mut Vec<Point>, closed: bool, out: &mut Vec<Polyline>| {
            if points.len() >= 2 {
                match Polyline::new(std::mem::take(points), closed) {
                    Ok(polyline) => out.push(polyline),
                    Err(error) if error.value.starts_with("point") => first_error = first_error.take().or(Some(error)),
                    Err(_) => {}
                }
            }
            points.clear();
        };
        kurbo::flatten(path, tolerance, |element| match element {
            PathEl::MoveTo(p) => {
                finish(&mut current, false, &mut polylines);
                current.push(p);
            }
            PathEl::LineTo(p) => current.push(p),
            PathEl::ClosePath => finish(&mut current, true, &mut polylines),
            PathEl::QuadTo(..) | PathEl::CurveTo(..) => unreachable!("flatten emits only lines"),
        });
        finish(&mut current, false, &mut polylines);
        match first_error {
            Some(error) => Err(error),
            None => Ok(polylines),
        }
    }

    /// The polyline as a Bézier path of lines (closed with `ClosePath` when closed).
    pub fn to_bez_path(&self) -> BezPath {
        let mut path = BezPath::new();
        path.move_to(self.points[0]);
        for &point in &self.points[1..] {
            path.line_to(point);
        }
        if self.closed {
            path.close_path();
        }
        path
    }

    /// The vertices (for a closed curve the first is not repeated at the end).
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// True for a closed curve.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Number of segments (one more than open for a closed curve).
    pub fn segment_count(&self) -> usize {
        self.cumulative.len() - 1
    }

    /// Total arc length.
    pub fn length(&self) -> f64 {
        *self.cumulative.last().expect("at least two entries")
    }

    /// Arc length at each vertex, plus the full length at the end for a closed curve.
    pub fn cumulative_lengths(&self) -> &[f64] {
        &self.cumulative
    }

    fn vertex(&self, index: usize) -> Point {
        self.points[index % self.points.len()]
    }

    /// Maps arc length `s` to `(segment, t)` with `t` in `[0, 1]`: wrapped for closed curves,
    /// clamped for open ones.
    pub fn locate(&self, s: f64) -> (usize, f64) {
        let length = self.length();
        let s = if self.closed { s.rem_euclid(length) } else { s.clamp(0.0, length) };
        let segment = match self.cumulative.partition_point(|&c| c <= s) {
            0 => 0,
            n => (n - 1).min(self.segment_count() - 1),
        };
        let (start, end) = (self.cumulative[segment], self.cumulative[segment + 1]);
        let t = if end > start { ((s - start) / (end - start)).clamp(0.0, 1.0) } else { 0.0 };
        (segment, t)
    }

    /// The point at arc length `s`.
    pub fn point_at(&self, s: f64) -> Point {
        let (segment, t) = self.locate(s);
        self.vertex(segment).lerp(self.vertex(segment + 1), t)
    }

    /// Unit direction of segment `segment`.
    pub fn segment_direction(&self, segment: usize) -> Vec2 {
        vector::normalized(self.vertex(segment + 1) - self.vertex(segment))
    }

    /// Unit tangent at arc length `s` (the direction of the segment holding `s`).
    pub fn tangent_at(&self, s: f64) -> Vec2 {
        self.segment_direction(self.locate(s).0)
    }

    /// Unit normal at arc length `s`: the tangent turned by +90° (see the module comment).
    pub fn normal_at(&self, s: f64) -> Vec2 {
        perpendicular(self.tangent_at(s))
    }

    /// Unit tangent at each vertex: the normalized sum of the adjacent segment directions (the
    /// ends of an open curve use their one segment).
    pub fn vertex_tangents(&self) -> Vec<Vec2> {
        let n = self.points.len();
        (0..n)
            .map(|i| {
                let incoming = if i > 0 || self.closed { Some(self.segment_direction((i + n - 1) % n)) } else { None };
                let outgoing = if i + 1 < n || self.closed { Some(self.segment_direction(i)) } else { None };
                let sum = incoming.unwrap_or(Vec2::ZERO) + outgoing.unwrap_or(Vec2::ZERO);
                if vector::length(sum) > 1e-12 {
                    vector::normalized(sum)
                } else {
                    outgoing.or(incoming).expect("two points")
                }
            })
            .collect()
    }

    /// Unit normal at each vertex (vertex tangents turned by +90°).
    pub fn vertex_normals(&self) -> Vec<Vec2> {
        self.vertex_tangents().into_iter().map(perpendicular).collect()
    }

    /// Signed discrete curvature at each vertex: turning angle divided by the mean length of the
    /// two adjacent segments (zero at the ends of an open curve). Positive turns towards the normal.
    pub fn curvature(&self) -> Vec<f64> {
        let n = self.points.len();
        (0..n)
            .map(|i| {
                if !self.closed && (i == 0 || i + 1 == n) {
                    return 0.0;
                }
                let previous = self.vertex((i + n - 1) % n);
                let here = self.points[i];
                let next = self.vertex(i + 1);
                let (a, b) = (here - previous, next - here);
                let angle = math::atan2(a.cross(b), a.dot(b));
                angle / (0.5 * (vector::length(a) + vector::length(b)))
            })
            .collect()
    }

    /// Resamples at equal arc-length steps as close as possible to `step`: `n = round(L / step)`
    /// steps of exactly `L / n` (at least one step, two for a closed curve). An open result keeps
    /// both ends; a closed one does not repeat its first point.
    pub fn resample(&self, step: f64) -> Result<Polyline, InvalidParameter> {
        if !(step.is_finite() && step > 0.0) {
            return Err(InvalidParameter::new("step", step, "must be a finite number > 0"));
        }
        let length = self.length();
        let minimum = if self.closed { 3 } else { 1 };
        let steps = ((length / step).round() as usize).max(minimum);
        let spacing = length / steps as f64;
        let count = if self.closed { steps } else { steps + 1 };
        let points = (0..count).map(|i| self.point_at(i as f64 * spacing)).collect();
        Polyline::new(points, self.closed)
    }

    /// The curve moved by `distance` along its vertex normals, with mitred joins (the miter is
    /// limited to 4 × `distance` at sharp turns). Negative distances offset to the other side.
    pub fn offset(&self, distance: f64) -> Result<Polyline, InvalidParameter> {
        let n = self.points.len();
        let normals = self.vertex_normals();
        let points = (0..n)
            .map(|i| {
                let segment_normal = if i + 1 < n || self.closed {
                    perpendicular(self.segment_direction(i))
                } else {
                    perpendicular(self.segment_direction(i - 1))
                };
                let cosine = normals[i].dot(segment_normal).max(0.25);
                self.points[i] + normals[i] * (distance / cosine)
            })
            .collect();
        Polyline::new(points, self.closed)
    }

    /// The same curve run backwards.
    pub fn reversed(&self) -> Polyline {
        let mut points = self.points.clone();
        points.reverse();
        Polyline::new(points, self.closed).expect("reversing keeps a valid curve")
    }

    /// The curve under an affine map (which must not collapse it).
    pub fn transformed(&self, transform: Affine) -> Result<Polyline, InvalidParameter> {
        Polyline::new(self.points.iter().map(|&p| transform * p).collect(), self.closed)
    }

    /// Axis-aligned bounds of the vertices.
    pub fn bounds(&self) -> Rect {
        bounds_of(&self.points)
    }
}

/// `v` turned by +90°: `(-v.y, v.x)`.
pub fn perpendicular(v: Vec2) -> Vec2 {
    Vec2::new(-v.y, v.x)
}

/// Axis-aligned bounds of points (an empty rect at the origin for no points).
pub fn bounds_of(points: &[Point]) -> Rect {
    let Some(first) = points.first() else { return Rect::ZERO };
    points.iter().fold(Rect::from_points(*first, *first), |rect, &p| rect.union_pt(p))
}

/// A simple polygon region given by its boundary vertices (not repeated at the end).
#[derive(Debug, Clone, PartialEq)]
pub struct Polygon {
    vertices: Vec<Point>,
}

impl Polygon {
    /// Builds a polygon; fails on non-finite coordinates, fewer than three vertices or zero area.
    pub fn new(vertices: Vec<Point>) -> Result<Self, InvalidParameter> {
        let outline = Polyline::new(vertices, true)?;
        let polygon = Polygon { vertices: outline.points };
        if polygon.vertices.len() < 3 || polygon.area() <= 1e-12 {
            return Err(InvalidParameter::new(
                "region",
                format!("area {}", polygon.area()),
                "a region needs at least three vertices and an area > 0",
            ));
        }
        Ok(polygon)
    }

    /// The boundary vertices.
    pub fn vertices(&self) -> &[Point] {
        &self.vertices
    }

    /// Signed area (shoelace formula): positive when the vertices run counterclockwise in the
    /// `(x, y)` frame.
    pub fn signed_area(&self) -> f64 {
        let n = self.vertices.len();
        0.5 * (0..n).map(|i| self.vertices[i].to_vec2().cross(self.vertices[(i + 1) % n].to_vec2())).sum::<f64>()
    }

    /// Area.
    pub fn area(&self) -> f64 {
        self.signed_area().abs()
    }

    /// Centroid of the enclosed area.
    pub fn centroid(&self) -> Point {
        let n = self.vertices.len();
        let mut sum = Vec2::ZERO;
        let mut twice_area = 0.0;
        for i in 0..n {
            let (a, b) = (self.vertices[i].to_vec2(), self.vertices[(i + 1) % n].to_vec2());
            let cross = a.cross(b);
            twice_area += cross;
            sum += (a + b) * cross;
        }
        (sum / (3.0 * twice_area)).to_point()
    }

    /// True when `point` is inside (even-odd rule; points on the boundary may go either way).
    pub fn contains(&self, point: Point) -> bool {
        let n = self.vertices.len();
        let mut inside = false;
        let mut j = n - 1;
        for i in 0..n {
            let (a, b) = (self.vertices[i], self.vertices[j]);
            if (a.y > point.y) != (b.y > point.y) && point.x < (b.x - a.x) * (point.y - a.y) / (b.y - a.y) + a.x {
                inside = !inside;
            }
            j = i;
        }
        inside
    }

    /// Distance from `point` to the nearest boundary edge.
    pub fn distance_to_boundary(&self, point: Point) -> f64 {
        let n = self.vertices.len();
        (0..n)
            .map(|i| {
                kurbo::Line::new(self.vertices[i], self.vertices[(i + 1) % n]).nearest(point, 1e-9).distance_sq.sqrt()
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// True when no two non-adjacent edges intersect (see [`outline_crosses_itself`]).
    pub fn is_simple(&self) -> bool {
        !outline_crosses_itself(&self.vertices)
    }

    /// Axis-aligned bounds.
    pub fn bounds(&self) -> Rect {
        bounds_of(&self.vertices)
    }

    /// The boundary as a closed polyline.
    pub fn outline(&self) -> Polyline {
        Polyline::new(self.vertices.clone(), true).expect("a polygon's outline is a valid curve")
    }
}

/// True when closed segments `ab` and `cd` share a point.
pub fn segments_intersect(a: Point, b: Point, c: Point, d: Point) -> bool {
    let orient = |p: Point, q: Point, r: Point| (q - p).cross(r - p);
    let on_segment = |p: Point, q: Point, r: Point| {
        r.x >= p.x.min(q.x) && r.x <= p.x.max(q.x) && r.y >= p.y.min(q.y) && r.y <= p.y.max(q.y)
    };
    let (d1, d2, d3, d4) = (orient(c, d, a), orient(c, d, b), orient(a, b, c), orient(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0)) {
        return true;
    }
    (d1 == 0.0 && on_segment(c, d, a))
        || (d2 == 0.0 && on_segment(c, d, b))
        || (d3 == 0.0 && on_segment(a, b, c))
        || (d4 == 0.0 && on_segment(a, b, d))
}

/// True when two non-adjacent edges of the closed outline through `vertices` intersect (touching
/// counts). Compares only the edge pairs whose bounding boxes meet, found in an R-tree of the
/// edges' boxes: about `n log n` for drawn outlines, where a sweep along x was quadratic for edges
/// spanning the same x range (a comb of long teeth). An outline with a non-finite vertex has no
/// defined crossing: false.
pub fn outline_crosses_itself(vertices: &[Point]) -> bool {
    if vertices.iter().any(|p| !(p.x.is_finite() && p.y.is_finite())) {
        return false;
    }
    let n = vertices.len();
    let edge = |i: usize| (vertices[i], vertices[(i + 1) % n]);
    let boxes: Vec<GeomWithData<Rectangle<[f64; 2]>, usize>> = (0..n)
        .map(|i| {
            let (a, b) = edge(i);
            GeomWithData::new(Rectangle::from_corners([a.x, a.y], [b.x, b.y]), i)
        })
        .collect();
    let tree = RTree::bulk_load(boxes.clone());
    boxes.iter().any(|entry| {
        let (i, (a, b)) = (entry.data, edge(entry.data));
        tree.locate_in_envelope_intersecting(&entry.envelope()).any(|other| {
            let j = other.data;
            let adjacent = (i + 1) % n == j || (j + 1) % n == i;
            j > i && !adjacent && segments_intersect(a, b, vertices[j], vertices[(j + 1) % n])
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::Shape;
    use std::f64::consts::{PI, TAU};

    fn circle(radius: f64, count: usize) -> Polyline {
        let points = (0..count).map(|i| {
            let angle = TAU * i as f64 / count as f64;
            Point::new(radius * math::cos(angle), radius * math::sin(angle))
        });
        Polyline::new(points.collect(), true).unwrap()
    }

    #[test]
    fn circle_resampling_gives_equal_steps_and_the_right_length() {
        let curve = circle(10.0, 1000);
        assert!((curve.length() - TAU * 10.0).abs() < 1e-3);
        let resampled = curve.resample(1.0).unwrap();
        assert_eq!(resampled.points().len(), 63);
        let steps: Vec<f64> = resampled.cumulative_lengths().windows(2).map(|w| w[1] - w[0]).collect();
        let mean = steps.iter().sum::<f64>() / steps.len() as f64;
        assert!(steps.iter().all(|s| (s - mean).abs() < 1e-3), "{steps:?}");
        assert!((resampled.length() - TAU * 10.0).abs() < 0.05);
    }

    #[test]
    fn circle_normals_point_to_the_centre() {
        let curve = circle(5.0, 360);
        for s in [0.0, 3.0, 17.5, 30.0] {
            let p = curve.point_at(s);
            let n = curve.normal_at(s);
            let to_centre = vector::normalized(Point::ORIGIN - p);
            assert!(n.dot(to_centre) > 0.99, "at s={s}: {n:?} vs {to_centre:?}");
        }
        for (p, n) in curve.points().iter().zip(curve.vertex_normals()) {
            assert!(n.dot(vector::normalized(Point::ORIGIN - *p)) > 0.999);
        }
        let inner = curve.offset(1.0).unwrap();
        assert!((inner.length() - TAU * 4.0).abs() < 0.01);
        let kappa = curve.curvature();
        assert!(kappa.iter().all(|k| (k - 0.2).abs() < 1e-3), "{:?}", &kappa[..3]);
    }

    #[test]
    fn closed_polylines_wrap_and_open_ones_clamp() {
        let square = Polyline::new(
            vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(1.0, 1.0), Point::new(0.0, 1.0)],
            true,
        )
        .unwrap();
        assert_eq!(square.length(), 4.0);
        assert_eq!(square.segment_count(), 4);
        assert!(vector::distance(square.point_at(3.5), Point::new(0.0, 0.5)) < 1e-12);
        assert!(vector::distance(square.point_at(4.25), Point::new(0.25, 0.0)) < 1e-12);
        assert!(vector::distance(square.point_at(-0.5), Point::new(0.0, 0.5)) < 1e-12);
        assert_eq!(square.tangent_at(3.5), Vec2::new(0.0, -1.0));
        let open = Polyline::new(square.points().to_vec(), false).unwrap();
        assert_eq!(open.length(), 3.0);
        assert_eq!(open.point_at(10.0), Point::new(0.0, 1.0));
        assert_eq!(open.resample(1.0).unwrap().points().len(), 4);
    }

    #[test]
    fn bad_curves_are_rejected() {
        assert!(Polyline::new(vec![Point::new(1.0, 1.0), Point::new(1.0, 1.0)], false).is_err());
        assert!(Polyline::new(vec![Point::new(f64::NAN, 1.0), Point::new(1.0, 1.0)], false).is_err());
        assert!(Polygon::new(vec![Point::new(0.0, 0.0), Point::new(1.0, 1.0), Point::new(2.0, 2.0)]).is_err());
    }

    #[test]
    fn bezier_paths_flatten_within_tolerance() {
        let circle_path = kurbo::Circle::new((0.0, 0.0), 20.0).to_path(1e-6);
        let polylines = Polyline::from_bez_path(&circle_path, 0.01).unwrap();
        assert_eq!(polylines.len(), 1);
        assert!(polylines[0].is_closed());
        assert!((polylines[0].length() - TAU * 20.0).abs() < 0.1);
        for p in polylines[0].points() {
            assert!((vector::distance(*p, Point::ORIGIN) - 20.0).abs() < 0.011);
        }
        let mut two = BezPath::new();
        two.move_to((0.0, 0.0));
        two.line_to((5.0, 0.0));
        two.move_to((0.0, 3.0));
        two.quad_to((2.0, 6.0), (4.0, 3.0));
        assert_eq!(Polyline::from_bez_path(&two, 0.1).unwrap().len(), 2);
        assert!(Polyline::from_bez_path(&two, 0.0).is_err());
    }

    #[test]
    fn polygon_area_containment_and_simplicity() {
        let square =
            Polygon::new(vec![Point::new(0.0, 0.0), Point::new(2.0, 0.0), Point::new(2.0, 2.0), Point::new(0.0, 2.0)])
                .unwrap();
        assert_eq!(square.area(), 4.0);
        assert!(square.signed_area() > 0.0);
        assert!(square.contains(Point::new(1.0, 1.5)));
        assert!(!square.contains(Point::new(3.0, 1.0)));
        assert!(vector::distance(square.centroid(), Point::new(1.0, 1.0)) < 1e-12);
        assert!((square.distance_to_boundary(Point::new(1.0, 0.5)) - 0.5).abs() < 1e-12);
        assert!(square.is_simple());
        let bowtie =
            Polygon::new(vec![Point::new(0.0, 0.0), Point::new(3.0, 3.0), Point::new(3.0, 0.0), Point::new(0.0, 2.0)]);
        assert!(!bowtie.unwrap().is_simple());
        let _ = PI;
    }

    /// The pairwise test the R-tree one must agree with.
    fn simple_by_every_pair(vertices: &[Point]) -> bool {
        let n = vertices.len();
        (0..n).all(|i| {
            (i + 1..n).all(|j| {
                (i + 1) % n == j
                    || (j + 1) % n == i
                    || !segments_intersect(vertices[i], vertices[(i + 1) % n], vertices[j], vertices[(j + 1) % n])
            })
        })
    }

    /// A comb of `teeth` long horizontal teeth: every edge spans the same x range.
    fn comb(teeth: usize) -> Vec<Point> {
        let mut vertices = Vec::new();
        for i in 0..teeth {
            let y = 2.0 * i as f64;
            vertices.extend([Point::new(0.0, y), Point::new(100.0, y), Point::new(100.0, y + 1.0)]);
            vertices.push(Point::new(0.5, y + 1.0));
        }
        vertices.extend([Point::new(0.0, 2.0 * teeth as f64), Point::new(-5.0, 2.0 * teeth as f64)]);
        vertices.push(Point::new(-5.0, 0.0));
        vertices
    }

    #[test]
    fn simplicity_agrees_with_every_pair_on_combs_and_random_polygons() {
        let teeth = comb(40);
        assert!(simple_by_every_pair(&teeth) && Polygon::new(teeth.clone()).unwrap().is_simple());
        let mut crossed = teeth;
        crossed[41].y = 7.5; // a tooth's tip pulled across the next tooth
        assert!(!simple_by_every_pair(&crossed) && !Polygon::new(crossed).unwrap().is_simple());
        use crate::random::Rng;
        let mut stream = crate::SeedStreams::new(4).stream("polygons", 0);
        for _ in 0..200 {
            let n = 4 + (stream.random::<f64>() * 6.0) as usize;
            let vertices: Vec<Point> =
                (0..n).map(|_| Point::new(stream.random::<f64>().round(), stream.random::<f64>() * 3.0)).collect();
            if let Ok(polygon) = Polygon::new(vertices.clone()) {
                assert_eq!(polygon.is_simple(), simple_by_every_pair(polygon.vertices()), "{vertices:?}");
            }
        }
        // A large comb answers at once (the sweep along x compared every pair of teeth).
        assert!(Polygon::new(comb(50_000)).unwrap().is_simple());
    }
}
