//! Lengths, directions and rotations of `kurbo` vectors with the same bits on every platform.
//!
//! `kurbo`'s `Vec2::hypot`, `normalize`, `angle`, `from_angle`, `Point::distance` and
//! `Affine::rotate` call the platform's math library (glibc natively, a port of musl's in
//! WebAssembly), which rounds some results differently, so a synthesis in the browser drifted
//! from the same one on the command line. Lengths here are `sqrt(x² + y²)` (square roots are
//! correctly rounded everywhere; drawing coordinates never come near overflow) and angles come from
//! [`crate::math`].

use kurbo::{Affine, Point, Vec2};

use crate::math;

/// `|v|`.
#[inline]
pub fn length(v: Vec2) -> f64 {
    (v.x * v.x + v.y * v.y).sqrt()
}

/// `|a − b|`.
#[inline]
pub fn distance(a: Point, b: Point) -> f64 {
    length(a - b)
}

/// `v / |v|` (NaN for the zero vector, as `kurbo`'s).
#[inline]
pub fn normalized(v: Vec2) -> Vec2 {
    v / length(v)
}

/// The angle of `v` from the x axis, in (−π, π].
#[inline]
pub fn angle(v: Vec2) -> f64 {
    math::atan2(v.y, v.x)
}

/// The unit vector at `angle` from the x axis.
#[inline]
pub fn from_angle(angle: f64) -> Vec2 {
    let (sin, cos) = math::sin_cos(angle);
    Vec2::new(cos, sin)
}

/// The rotation by `angle` (counter-clockwise in a y-up frame), as `Affine::rotate`.
#[inline]
pub fn rotation(angle: f64) -> Affine {
    let (sin, cos) = math::sin_cos(angle);
    Affine::new([cos, sin, -sin, cos, 0.0, 0.0])
}

#[cfg(test)]
#[allow(clippy::disallowed_methods, reason = "compares with kurbo's platform-math versions")]
mod tests {
    use super::*;

    #[test]
    fn agree_with_kurbo_to_rounding() {
        for i in 0..200 {
            let t = i as f64 * 0.173 - 17.0;
            let v = Vec2::new(3.0 * t.cos() + 0.5, -2.0 * t.sin() + t);
            assert!((length(v) - v.hypot()).abs() <= 1e-15 * v.hypot());
            assert!((normalized(v) - v.normalize()).hypot() <= 1e-15);
            assert!((angle(v) - v.angle()).abs() <= 1e-15);
            assert!((from_angle(t) - Vec2::from_angle(t)).hypot() <= 1e-15);
            let (ours, theirs) = (rotation(t), Affine::rotate(t));
            for (a, b) in ours.as_coeffs().iter().zip(theirs.as_coeffs()) {
                assert!((a - b).abs() <= 1e-15);
            }
        }
        assert_eq!(distance(Point::new(1.0, 2.0), Point::new(4.0, 6.0)), 5.0);
    }
}
