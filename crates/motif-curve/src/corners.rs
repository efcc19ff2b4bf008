//! Corners for corner tiles (a pattern brush's corner piece; not in the paper): where the curve
//! turns by more than the corner angle within one tile's length, a tile is drawn whole.
//!
//! Corners are read on the curve as drawn, before tight bends are rounded: the turning at arc
//! length `x` is the angle between the curve's directions half a tile before and half a tile
//! after `x`, and every stretch where it passes the angle is one corner, centred in the stretch.
//! Rounding replaces a corner by an arc around it, so the tile is centred on the ribbon's point
//! nearest to the corner. A closed curve is restarted where its first tile begins, so that no tile
//! straddles its start.

use motif_core::{Point, Polyline, math};

use crate::ribbon::Ribbon;

/// Steps of the scan along the curve, canvas pixels.
const SCAN_STEP: f64 = 0.5;

/// The corners of `curve`: where its direction `half` before and `half` after turns by more than
/// `angle_degrees`, one point per such stretch.
pub(crate) fn corner_points(curve: &Polyline, half: f64, angle_degrees: f64) -> Vec<Point> {
    let length = curve.length();
    let limit = math::cos(angle_degrees.to_radians());
    let sharp = |x: f64| {
        let (before, after) = (curve.tangent_at(x - half), curve.tangent_at(x + half));
        before.x * after.x + before.y * after.y < limit
    };
    let steps = (length / SCAN_STEP).floor() as usize;
    let (first, last) = if curve.is_closed() {
        // A full turn from a point in no corner, so that no stretch wraps.
        match (0..steps).map(|k| k as f64 * SCAN_STEP).find(|&x| !sharp(x)) {
            Some(x) => (x, x + length),
            None => return Vec::new(),
        }
    } else {
        (half, length - half)
    };
    let mut centres = Vec::new();
    let mut run: Option<f64> = None;
    let mut x = first;
    while x <= last {
        match (sharp(x), run) {
            (true, None) => run = Some(x),
            (false, Some(start)) => {
                centres.push(0.5 * (start + x - SCAN_STEP));
                run = None;
            }
            _ => {}
        }
        x += SCAN_STEP;
    }
    if let Some(start) = run {
        centres.push(0.5 * (start + x - SCAN_STEP));
    }
    centres.into_iter().map(|s| curve.point_at(s)).collect()
}

/// The stretches `[start, end)` of `ribbon`'s arc length that corner tiles `tile` long take, one
/// centred on the ribbon's point nearest to each of `corners`, ascending, within `[from, to]`,
/// each at least `min_gap` after the one before; a corner too close to another or to the ends is
/// left to the pieces. On a closed curve a tile that begins within a pixel of the start begins
/// there.
pub(crate) fn corner_stretches(
    ribbon: &Ribbon,
    corners: &[Point],
    tile: f64,
    closed: bool,
    [from, to]: [f64; 2],
    min_gap: f64,
) -> Vec<(f64, f64)> {
    let half = 0.5 * tile;
    let length = ribbon.length();
    let mut starts: Vec<f64> = corners
        .iter()
        .map(|&corner| {
            let start = ribbon.nearest(corner) - half;
            if closed && (start < 1.0 && start > -1.0 || start > length - 1.0) { 0.0 } else { start }
        })
        .collect();
    starts.sort_by(f64::total_cmp);
    let mut stretches: Vec<(f64, f64)> = Vec::new();
    let mut cursor = from;
    for start in starts {
        let end = start + tile;
        let after_previous =
            if stretches.is_empty() { start == from || start >= from + min_gap } else { start >= cursor + min_gap };
        if after_previous && end + min_gap <= to {
            stretches.push((start, end));
            cursor = end;
        }
    }
    stretches
}

/// A closed curve restarted at arc length `start`: the same points, beginning there.
pub(crate) fn restarted(curve: &Polyline, start: f64) -> Polyline {
    let (segment, _) = curve.locate(start);
    let points = curve.points();
    let count = points.len();
    let mut restarted: Vec<Point> = Vec::with_capacity(count + 1);
    restarted.push(curve.point_at(start));
    restarted.extend((1..=count).map(|k| points[(segment + k) % count]));
    Polyline::new(restarted, true).unwrap_or_else(|_| curve.clone())
}

#[cfg(test)]
mod tests {
    use motif_core::Point;

    use super::*;

    fn polyline(points: &[(f64, f64)], closed: bool) -> Polyline {
        Polyline::new(points.iter().map(|&(x, y)| Point::new(x, y)).collect(), closed).unwrap()
    }

    #[test]
    fn a_square_has_four_corners_and_a_circle_none() {
        let square = polyline(&[(0.0, 0.0), (200.0, 0.0), (200.0, 200.0), (0.0, 200.0)], true);
        let mut corners = corner_points(&square, 10.0, 60.0);
        corners.sort_by(|a, b| (a.x, a.y).partial_cmp(&(b.x, b.y)).unwrap());
        let expected = [(0.0, 0.0), (0.0, 200.0), (200.0, 0.0), (200.0, 200.0)];
        assert_eq!(corners.len(), 4, "{corners:?}");
        for (corner, (x, y)) in corners.iter().zip(expected) {
            assert!((corner.x - x).abs() < 1.0 && (corner.y - y).abs() < 1.0, "{corners:?}");
        }
        let circle: Vec<(f64, f64)> = (0..120)
            .map(|i| f64::from(i) / 120.0 * std::f64::consts::TAU)
            .map(|a| (100.0 * math::cos(a), 100.0 * math::sin(a)))
            .collect();
        assert!(corner_points(&polyline(&circle, true), 10.0, 60.0).is_empty());
    }

    #[test]
    fn a_turn_below_the_angle_is_no_corner() {
        // An open path turning by 45° at (100, 0), then by 120° at arc length 200.
        let d = 100.0 * std::f64::consts::FRAC_1_SQRT_2;
        let turn = 165.0_f64.to_radians();
        let a = (100.0 + d, d);
        let b = (a.0 + 100.0 * math::cos(turn), a.1 + 100.0 * math::sin(turn));
        let path = polyline(&[(0.0, 0.0), (100.0, 0.0), a, b], false);
        let corners = corner_points(&path, 10.0, 60.0);
        assert_eq!(corners.len(), 1, "{corners:?}");
        assert!((corners[0].x - a.0).abs() < 1.0 && (corners[0].y - a.1).abs() < 1.0, "{corners:?}");
        let both = corner_points(&path, 10.0, 30.0);
        assert_eq!(both.len(), 2);
        // The stretches are centred on the corners, and keep clear of the ends and of each other.
        let ribbon = Ribbon::new(&path, 20.0).unwrap();
        let stretches = corner_stretches(&ribbon, &both, 20.0, false, [0.0, ribbon.length()], 10.0);
        assert_eq!(stretches.len(), 2, "{stretches:?}");
        assert!((stretches[0].0 - 90.0).abs() < 0.5 && (stretches[1].0 - 190.0).abs() < 0.5, "{stretches:?}");
        assert!(stretches.iter().all(|(s, e)| (e - s - 20.0).abs() < 1e-9));
        assert_eq!(corner_stretches(&ribbon, &both, 20.0, false, [0.0, ribbon.length()], 90.0).len(), 1);
        assert!(corner_stretches(&ribbon, &both, 20.0, false, [95.0, ribbon.length()], 10.0).len() == 1);
    }

    #[test]
    fn a_restarted_curve_is_the_same_loop_from_another_point() {
        let square = polyline(&[(0.0, 0.0), (200.0, 0.0), (200.0, 200.0), (0.0, 200.0)], true);
        let restarted = restarted(&square, 190.0);
        assert!((restarted.length() - square.length()).abs() < 1e-9);
        assert_eq!(restarted.points()[0], Point::new(190.0, 0.0));
        assert_eq!(restarted.points()[1], Point::new(200.0, 0.0));
        assert_eq!(restarted.points().len(), 5);
    }
}
