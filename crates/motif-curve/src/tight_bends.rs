//! Bends tighter than the ribbon (not in the paper). Where the curve turns with a radius below
//! half the ribbon's width, the inner offset curve folds over itself (§1.3, Figure 3); the paper
//! forbids the pattern there (§3.1), and on real curves (a heart's cusp and tip, the corners of a
//! letter, the kinks of a surveyed river) that leaves whole pieces empty and cuts the links on
//! either side. Instead, the curve's tight bends are rounded before the ribbon is built: the curve
//! is resampled and, near every vertex whose curvature exceeds `1 / r_min`, smoothed by small
//! Laplacian steps until no vertex does. Elsewhere the curve is left as given (a curve without a
//! tight bend is not even resampled), and the report tells how many bends were rounded and how far
//! the curve moved.

use motif_core::{InvalidParameter, Point, Polyline};
use motif_core::{math, vector};

/// Largest number of smoothing steps; a bend still too tight after them is left to the fold-over
/// avoidance.
const MAX_STEPS: usize = 20_000;

/// Most vertex visits of all smoothing steps together (a bend still tight then is left to the
/// fold-over avoidance and reported).
const MAX_WORK: usize = 50_000_000;

/// The curve with its tight bends rounded.
#[derive(Debug, Clone)]
pub(crate) struct Rounded {
    pub curve: Polyline,
    /// Bends (runs of vertices tighter than the radius) that were rounded.
    pub bends: usize,
    /// Largest distance a point of the curve moved, in curve units.
    pub max_shift: f64,
    /// True when a bend stayed tighter than the radius after [`MAX_STEPS`] steps.
    pub unresolved: bool,
}

/// Curvature magnitude at each vertex, measured over `span` vertices on either side (the turning
/// angle between the chords to the vertices `span` before and after, over the mean chord
/// length), so that the kinks of a flattened curve do not read as tight bends; 0 where the span
/// leaves an open curve.
fn curvatures(points: &[Point], closed: bool, span: usize) -> Vec<f64> {
    (0..points.len()).map(|i| curvature_at(points, closed, span, i)).collect()
}

/// One vertex's entry of [`curvatures`].
fn curvature_at(points: &[Point], closed: bool, span: usize, i: usize) -> f64 {
    let n = points.len();
    if !closed && (i < span || i + span >= n) {
        return 0.0;
    }
    let (previous, here, next) = (points[(i + n - span) % n], points[i], points[(i + span) % n]);
    let (a, b) = (here - previous, next - here);
    let angle = math::atan2(a.cross(b), a.dot(b)).abs();
    angle / (0.5 * (vector::length(a) + vector::length(b))).max(1e-12)
}

/// The indices within `reach` vertices of `i` (cyclic when `closed`, clipped otherwise).
fn around(i: usize, reach: usize, n: usize, closed: bool) -> impl Iterator<Item = usize> {
    (0..=2 * reach).filter_map(move |offset| {
        let j = i as isize + offset as isize - reach as isize;
        if closed {
            Some(j.rem_euclid(n as isize) as usize)
        } else if j < 0 || j >= n as isize {
            None
        } else {
            Some(j as usize)
        }
    })
}

/// Number of runs of `true` in `flags` (cyclic when `closed`).
fn runs(flags: &[bool], closed: bool) -> usize {
    let n = flags.len();
    let starts = (0..n).filter(|&i| flags[i] && !(if i == 0 { closed && flags[n - 1] } else { flags[i - 1] }));
    let count = starts.count();
    if count == 0 && flags.iter().all(|&f| f) && n > 0 { 1 } else { count }
}

/// The resampling step and the curvature span (in vertices, about a quarter of the radius) for
/// `min_radius`.
fn scales(min_radius: f64) -> (f64, usize) {
    let step = (min_radius / 8.0).clamp(0.25, 2.0);
    (step, ((min_radius / 4.0 / step).round() as usize).max(1))
}

/// Rounds the bends of `curve` tighter than `min_radius` (curve units; 0 leaves the curve as it is).
/// No point moves farther than `max_shift` from where it was: a bend that would need more (the
/// corners of a letter outline narrower than the ribbon) stays tight and is reported unresolved.
pub(crate) fn round_bends(curve: &Polyline, min_radius: f64, max_shift: f64) -> Result<Rounded, InvalidParameter> {
    if min_radius <= 0.0 {
        return Ok(Rounded { curve: curve.clone(), bends: 0, max_shift: 0.0, unresolved: false });
    }
    let limit = 1.0 / min_radius;
    let closed = curve.is_closed();
    let (step, span) = scales(min_radius);
    let resampled = curve.resample(step)?;
    let original: Vec<Point> = resampled.points().to_vec();
    let mut points = original.clone();
    let n = points.len();
    let reach = (min_radius / step).ceil() as usize;
    let tight: Vec<bool> = curvatures(&points, closed, span).iter().map(|&k| k > limit).collect();
    let bends = runs(&tight, closed);
    if bends == 0 {
        return Ok(Rounded { curve: curve.clone(), bends: 0, max_shift: 0.0, unresolved: false });
    }
    let mut unresolved = true;
    let mut next = points.clone();
    // Curvatures are kept up to date where vertices moved (a vertex's curvature reads the vertices
    // `span` away), not recomputed over the whole curve every step: the steps are local, and the
    // full pass was most of an interactive edit's curve preparation (5 ms of 7 on the bench's
    // flourish).
    let mut curvature = curvatures(&points, closed, span);
    let mut marked = vec![false; n];
    let mut dirty = vec![false; n];
    // Each step reads the whole curve: bound the work on very long curves.
    let steps = MAX_STEPS.min(MAX_WORK / n.max(1)).max(1);
    for _ in 0..steps {
        let tight: Vec<usize> = (0..n).filter(|&i| curvature[i] > limit).collect();
        if tight.is_empty() {
            unresolved = false;
            break;
        }
        // Smooth a window around every tight vertex (windows wide enough for an arc of the
        // target radius to form).
        marked.fill(false);
        for &i in &tight {
            for j in around(i, reach, n, closed) {
                marked[j] = true;
            }
        }
        next.copy_from_slice(&points);
        let mut moved = Vec::new();
        for i in (0..n).filter(|&i| marked[i]) {
            if !closed && (i == 0 || i + 1 == n) {
                continue;
            }
            let (previous, following) = (points[(i + n - 1) % n], points[(i + 1) % n]);
            let candidate = points[i].lerp(previous.midpoint(following), 0.5);
            if vector::distance(candidate, original[i]) <= max_shift {
                next[i] = candidate;
                moved.push(i);
            }
        }
        std::mem::swap(&mut points, &mut next);
        if moved.is_empty() {
            break;
        }
        dirty.fill(false);
        for &i in &moved {
            for j in around(i, span, n, closed) {
                dirty[j] = true;
            }
        }
        for i in (0..n).filter(|&i| dirty[i]) {
            curvature[i] = curvature_at(&points, closed, span, i);
        }
    }
    let max_shift = points.iter().zip(&original).map(|(a, b)| vector::distance(*a, *b)).fold(0.0, f64::max);
    Ok(Rounded { curve: Polyline::new(points, closed)?, bends, max_shift, unresolved })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn corner(angle_degrees: f64) -> Polyline {
        // Two 200-unit legs meeting at the origin with the given turning angle.
        let turn = angle_degrees.to_radians();
        let start = Point::new(-200.0, 0.0);
        let end = Point::new(200.0 * math::cos(turn), 200.0 * math::sin(turn));
        let points: Vec<Point> = (0..=100)
            .map(|i| start.lerp(Point::ORIGIN, i as f64 / 100.0))
            .chain((1..=100).map(|i| Point::ORIGIN.lerp(end, i as f64 / 100.0)))
            .collect();
        Polyline::new(points, false).unwrap()
    }

    #[test]
    fn a_sharp_corner_is_rounded_to_the_radius_and_the_rest_stays() {
        let curve = corner(120.0);
        let rounded = round_bends(&curve, 30.0, 100.0).unwrap();
        assert_eq!(rounded.bends, 1);
        assert!(!rounded.unresolved);
        let (_, span) = scales(30.0);
        assert!(curvatures(rounded.curve.points(), false, span).iter().all(|&k| k <= 1.0 / 30.0 + 1e-9));
        // With a small allowance the corner cannot be rounded that far and says so.
        let limited = round_bends(&curve, 30.0, 3.0).unwrap();
        assert!(limited.unresolved);
        assert!(limited.max_shift <= 3.0 + 1e-9);
        assert!(rounded.max_shift > 1.0 && rounded.max_shift < 60.0, "{}", rounded.max_shift);
        // The ends stay where they were.
        let (a, b) = (rounded.curve.points(), curve.points());
        assert!(vector::distance(a[0], b[0]) < 1e-9);
        assert!(vector::distance(a[a.len() - 1], b[b.len() - 1]) < 1e-9);
        // Far from the corner the curve has not moved.
        assert!(a[2].y.abs() < 1e-9 && a[2].x < -190.0, "{:?}", a[2]);
    }

    #[test]
    fn a_gentle_curve_is_returned_unchanged() {
        let points: Vec<Point> = (0..=60)
            .map(|i| {
                let t = i as f64 / 60.0 * std::f64::consts::PI;
                Point::new(300.0 * math::cos(t), 300.0 * math::sin(t))
            })
            .collect();
        let curve = Polyline::new(points, false).unwrap();
        let rounded = round_bends(&curve, 100.0, 50.0).unwrap();
        assert_eq!(rounded.bends, 0);
        assert_eq!(rounded.curve.points(), curve.points());
        let off = round_bends(&corner(150.0), 0.0, 50.0).unwrap();
        assert_eq!(off.bends, 0);
    }

    #[test]
    fn run_counting_is_cyclic_for_closed_curves() {
        assert_eq!(runs(&[true, false, false, true], true), 1);
        assert_eq!(runs(&[true, false, false, true], false), 2);
        assert_eq!(runs(&[true, true], true), 1);
        assert_eq!(runs(&[false, false], true), 0);
    }
}
