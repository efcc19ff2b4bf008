//! Small fixed-size vector and matrix helpers for points in `D` = 2 or 3 dimensions.
//!
//! The solver is generic over the dimension through const generics, so every hot loop works on
//! stack arrays the compiler can unroll; nothing here allocates.
use motif_core::math;

/// A point or vector in `D` dimensions.
pub(crate) type Vector<const D: usize> = [f64; D];
/// A `D`×`D` matrix, row-major (`m[row][column]`).
pub(crate) type Matrix<const D: usize> = [[f64; D]; D];

#[inline(always)]
pub(crate) fn sub<const D: usize>(a: &Vector<D>, b: &Vector<D>) -> Vector<D> {
    std::array::from_fn(|i| a[i] - b[i])
}

#[inline(always)]
pub(crate) fn add<const D: usize>(a: &Vector<D>, b: &Vector<D>) -> Vector<D> {
    std::array::from_fn(|i| a[i] + b[i])
}

#[inline(always)]
pub(crate) fn scale<const D: usize>(a: &Vector<D>, s: f64) -> Vector<D> {
    std::array::from_fn(|i| a[i] * s)
}

#[inline(always)]
pub(crate) fn dot<const D: usize>(a: &Vector<D>, b: &Vector<D>) -> f64 {
    let mut sum = 0.0;
    for i in 0..D {
        sum += a[i] * b[i];
    }
    sum
}

#[inline(always)]
pub(crate) fn norm2<const D: usize>(a: &Vector<D>) -> f64 {
    dot(a, a)
}

/// `a += s * b`.
#[inline(always)]
pub(crate) fn axpy<const D: usize>(a: &mut Vector<D>, s: f64, b: &Vector<D>) {
    for i in 0..D {
        a[i] += s * b[i];
    }
}

#[inline(always)]
pub(crate) fn mat_vec<const D: usize>(m: &Matrix<D>, v: &Vector<D>) -> Vector<D> {
    std::array::from_fn(|r| dot(&m[r], v))
}

/// `mᵀ v`.
#[inline(always)]
pub(crate) fn mat_t_vec<const D: usize>(m: &Matrix<D>, v: &Vector<D>) -> Vector<D> {
    std::array::from_fn(|c| {
        let mut sum = 0.0;
        for r in 0..D {
            sum += m[r][c] * v[r];
        }
        sum
    })
}

pub(crate) fn mat_mul<const D: usize>(a: &Matrix<D>, b: &Matrix<D>) -> Matrix<D> {
    std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            let mut sum = 0.0;
            for k in 0..D {
                sum += a[r][k] * b[k][c];
            }
            sum
        })
    })
}

#[cfg(test)]
pub(crate) fn transpose<const D: usize>(m: &Matrix<D>) -> Matrix<D> {
    std::array::from_fn(|r| std::array::from_fn(|c| m[c][r]))
}

pub(crate) fn identity<const D: usize>() -> Matrix<D> {
    std::array::from_fn(|r| std::array::from_fn(|c| if r == c { 1.0 } else { 0.0 }))
}

/// Rotation by `angle` radians in the xy-plane (about z in 3D), counter-clockwise for y up.
pub(crate) fn rotation_xy<const D: usize>(angle: f64) -> Matrix<D> {
    let mut m = identity::<D>();
    let (sin, cos) = math::sin_cos(angle);
    m[0][0] = cos;
    m[0][1] = -sin;
    m[1][0] = sin;
    m[1][1] = cos;
    m
}

/// Rotation about the unit `axis` by `angle` radians (Rodrigues); `D` must be 3. In 2D the axis is
/// ignored and the rotation is in the plane.
pub(crate) fn rotation_axis_angle<const D: usize>(axis: [f64; 3], angle: f64) -> Matrix<D> {
    if D == 2 {
        return rotation_xy::<D>(angle);
    }
    let (s, c) = math::sin_cos(angle);
    let t = 1.0 - c;
    let [x, y, z] = axis;
    let full = [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ];
    std::array::from_fn(|r| std::array::from_fn(|col| full[r][col]))
}

/// The smallest rotation taking the x axis onto the unit vector `direction`.
pub(crate) fn rotation_from_x<const D: usize>(direction: &Vector<D>) -> Matrix<D> {
    if D == 2 {
        return rotation_xy::<D>(math::atan2(direction[1], direction[0]));
    }
    // Axis = x × d, angle = acos(x·d).
    let (dx, dy, dz) = (direction[0], direction[1], direction[2]);
    let axis = [0.0, -dz, dy];
    let sin = (dy * dy + dz * dz).sqrt();
    if sin < 1e-12 {
        if dx >= 0.0 {
            return identity::<D>();
        }
        return rotation_axis_angle::<D>([0.0, 0.0, 1.0], std::f64::consts::PI);
    }
    let angle = math::atan2(sin, dx);
    rotation_axis_angle::<D>([axis[0] / sin, axis[1] / sin, axis[2] / sin], angle)
}

/// Re-orthonormalizes a rotation matrix (Gram–Schmidt on the columns) so that many small updates do
/// not let it drift away from a rigid motion.
pub(crate) fn orthonormalize<const D: usize>(m: &mut Matrix<D>) {
    let mut columns: [Vector<D>; D] = std::array::from_fn(|c| std::array::from_fn(|r| m[r][c]));
    for c in 0..D {
        for p in 0..c {
            let projection = dot(&columns[c], &columns[p]);
            let previous = columns[p];
            axpy(&mut columns[c], -projection, &previous);
        }
        let length = norm2(&columns[c]).sqrt();
        columns[c] = scale(&columns[c], 1.0 / length);
    }
    if D == 3 {
        // Keep a proper rotation: the third column is the cross product of the first two.
        let (a, b) = (columns[0], columns[1]);
        columns[2] = std::array::from_fn(|i| match i {
            0 => a[1] * b[2] - a[2] * b[1],
            1 => a[2] * b[0] - a[0] * b[2],
            _ => a[0] * b[1] - a[1] * b[0],
        });
    }
    for r in 0..D {
        for c in 0..D {
            m[r][c] = columns[c][r];
        }
    }
}

/// The "torque" of a force `force` applied at lever `lever`: a scalar (z component) in 2D, the
/// cross product in 3D (returned as three components; the unused ones are zero in 2D).
pub(crate) fn torque<const D: usize>(lever: &Vector<D>, force: &Vector<D>) -> [f64; 3] {
    if D == 2 {
        [0.0, 0.0, lever[0] * force[1] - lever[1] * force[0]]
    } else {
        [
            lever[1] * force[2] - lever[2] * force[1],
            lever[2] * force[0] - lever[0] * force[2],
            lever[0] * force[1] - lever[1] * force[0],
        ]
    }
}

/// The rotation by the small axis-angle vector `omega` (|omega| = angle), for rigid updates.
pub(crate) fn rotation_from_vector<const D: usize>(omega: [f64; 3]) -> Matrix<D> {
    if D == 2 {
        return rotation_xy::<D>(omega[2]);
    }
    let angle = (omega[0] * omega[0] + omega[1] * omega[1] + omega[2] * omega[2]).sqrt();
    if angle < 1e-300 {
        return identity::<D>();
    }
    rotation_axis_angle::<D>([omega[0] / angle, omega[1] / angle, omega[2] / angle], angle)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_from_x_maps_x_onto_direction() {
        let d = [0.3, -0.4, 0.866];
        let len = norm2(&d).sqrt();
        let d = scale(&d, 1.0 / len);
        let r = rotation_from_x::<3>(&d);
        let image = mat_vec(&r, &[1.0, 0.0, 0.0]);
        for i in 0..3 {
            assert!((image[i] - d[i]).abs() < 1e-12);
        }
        let rt = mat_mul(&transpose(&r), &r);
        for i in 0..3 {
            for j in 0..3 {
                assert!((rt[i][j] - if i == j { 1.0 } else { 0.0 }).abs() < 1e-12);
            }
        }
        let r2 = rotation_from_x::<2>(&[0.0, 1.0]);
        let image = mat_vec(&r2, &[1.0, 0.0]);
        assert!((image[0]).abs() < 1e-12 && (image[1] - 1.0).abs() < 1e-12);
    }

    #[test]
    fn orthonormalize_repairs_drift() {
        let mut r = rotation_axis_angle::<3>([0.0, 0.6, 0.8], 0.7);
        r[0][0] += 1e-3;
        orthonormalize(&mut r);
        let rt = mat_mul(&transpose(&r), &r);
        for i in 0..3 {
            for j in 0..3 {
                assert!((rt[i][j] - if i == j { 1.0 } else { 0.0 }).abs() < 1e-12);
            }
        }
    }
}
