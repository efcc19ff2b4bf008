//! Per-vertex normals and curvature tensors of a triangle mesh, for the orientation field of a
//! surface domain (§6.2: "we used the principal curvature directions as an orientation field",
//! Figure 6 middle).
//!
//! - Normals are area-weighted face normals. Where they cancel (faces not consistently
//!   oriented), each face is turned to agree with the vertex's first face instead; turning them
//!   always would flip the faces around a sharp corner (an octahedron's, at 109°).
//! - Curvature comes from a quadric height field `z = a x² + b xy + c y² + d x + e y` fitted by least
//!   squares, in the vertex's tangent frame, to its two-ring (its one-ring when that is all there
//!   is). The second fundamental form `[[2a, b], [b, 2c]]` is kept as a symmetric 3 × 3 tensor:
//!   tensors interpolate across a triangle without the sign ambiguity of direction vectors.

use motif_core::TriangleMesh;

use crate::triangles::{Vec3, cross, dot, normalized, sub};

/// A symmetric 3 × 3 tensor.
pub(crate) type Tensor = [[f64; 3]; 3];

/// Normals and curvature tensors at the vertices of a mesh.
#[derive(Debug, Clone)]
pub(crate) struct VertexGeometry {
    pub normals: Vec<Vec3>,
    pub tensors: Vec<Tensor>,
}

/// A unit vector perpendicular to the unit vector `n`.
pub(crate) fn perpendicular(n: Vec3) -> Vec3 {
    let axis = if n[0].abs() <= n[1].abs() && n[0].abs() <= n[2].abs() {
        [1.0, 0.0, 0.0]
    } else if n[1].abs() <= n[2].abs() {
        [0.0, 1.0, 0.0]
    } else {
        [0.0, 0.0, 1.0]
    };
    normalized(cross(n, axis)).unwrap_or([1.0, 0.0, 0.0])
}

/// Normals and curvature tensors of every vertex of a checked mesh.
pub(crate) fn vertex_geometry(mesh: &TriangleMesh) -> VertexGeometry {
    let count = mesh.vertices.len();
    let mut normals: Vec<Option<Vec3>> = vec![None; count];
    let mut sums = vec![[0.0; 3]; count];
    let mut plain = vec![[0.0; 3]; count];
    let mut weights = vec![0.0; count];
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); count];
    for (t, triangle) in mesh.triangles.iter().enumerate() {
        let [a, b, c] = mesh.corners(t);
        let face = cross(sub(b, a), sub(c, a));
        for (i, &v) in triangle.iter().enumerate() {
            let v = v as usize;
            let reference = *normals[v].get_or_insert(face);
            let sign = if dot(reference, face) < 0.0 { -1.0 } else { 1.0 };
            for axis in 0..3 {
                sums[v][axis] += sign * face[axis];
                plain[v][axis] += face[axis];
            }
            weights[v] += dot(face, face).sqrt();
            neighbours[v].push(triangle[(i + 1) % 3]);
            neighbours[v].push(triangle[(i + 2) % 3]);
        }
    }
    for list in &mut neighbours {
        list.sort_unstable();
        list.dedup();
    }
    let normals: Vec<Vec3> = (0..count)
        .map(|v| {
            let sum = if dot(plain[v], plain[v]).sqrt() > 0.1 * weights[v] { plain[v] } else { sums[v] };
            normalized(sum).unwrap_or([0.0, 0.0, 1.0])
        })
        .collect();
    let tensors = (0..count)
        .map(|v| {
            let mut ring: Vec<u32> = neighbours[v].clone();
            for &n in &neighbours[v] {
                ring.extend_from_slice(&neighbours[n as usize]);
            }
            ring.sort_unstable();
            ring.dedup();
            ring.retain(|&r| r as usize != v);
            fit_tensor(mesh.vertices[v], normals[v], ring.iter().map(|&r| mesh.vertices[r as usize]))
        })
        .collect();
    VertexGeometry { normals, tensors }
}

/// The second fundamental form at `origin` with normal `normal`, fitted to `ring`.
fn fit_tensor(origin: Vec3, normal: Vec3, ring: impl Iterator<Item = Vec3>) -> Tensor {
    let u = perpendicular(normal);
    let v = cross(normal, u);
    let local: Vec<Vec3> = ring
        .map(|p| {
            let d = sub(p, origin);
            [dot(d, u), dot(d, v), dot(d, normal)]
        })
        .collect();
    // Coordinates in units of the ring's mean distance keep the normal equations well scaled.
    let unit = local.iter().map(|p| (p[0] * p[0] + p[1] * p[1]).sqrt()).sum::<f64>() / local.len().max(1) as f64;
    if local.len() < 3 || unit <= 0.0 {
        return [[0.0; 3]; 3];
    }
    let basis = |p: &Vec3, terms: usize| -> Vec<f64> {
        let (x, y) = (p[0] / unit, p[1] / unit);
        [x * x, x * y, y * y, x, y][..terms].to_vec()
    };
    let fit = |terms: usize| -> Option<Vec<f64>> {
        let mut normal_matrix = vec![vec![0.0; terms]; terms];
        let mut right = vec![0.0; terms];
        for p in &local {
            let row = basis(p, terms);
            for i in 0..terms {
                right[i] += row[i] * p[2] / unit;
                for j in 0..terms {
                    normal_matrix[i][j] += row[i] * row[j];
                }
            }
        }
        solve(normal_matrix, right)
    };
    let coefficients = if local.len() >= 5 { fit(5).or_else(|| fit(3)) } else { fit(3) };
    let Some(k) = coefficients else { return [[0.0; 3]; 3] };
    // z/unit = k0 (x/unit)² + …: the second derivatives in real units are 2 k0 / unit, etc.
    let (a, b, c) = (k[0] / unit, k[1] / unit, k[2] / unit);
    std::array::from_fn(|i| {
        std::array::from_fn(|j| 2.0 * a * u[i] * u[j] + b * (u[i] * v[j] + v[i] * u[j]) + 2.0 * c * v[i] * v[j])
    })
}

/// Solves the small system `m x = right` by Gaussian elimination with partial pivoting; `None`
/// when it is (nearly) singular.
fn solve(mut m: Vec<Vec<f64>>, mut right: Vec<f64>) -> Option<Vec<f64>> {
    let n = right.len();
    let scale = m.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
    for column in 0..n {
        let pivot = (column..n).max_by(|&a, &b| m[a][column].abs().total_cmp(&m[b][column].abs()))?;
        if m[pivot][column].abs() <= 1e-10 * scale {
            return None;
        }
        m.swap(column, pivot);
        right.swap(column, pivot);
        for row in column + 1..n {
            let factor = m[row][column] / m[column][column];
            for k in column..n {
                m[row][k] -= factor * m[column][k];
            }
            right[row] -= factor * right[column];
        }
    }
    let mut x = vec![0.0; n];
    for row in (0..n).rev() {
        let rest: f64 = (row + 1..n).map(|k| m[row][k] * x[k]).sum();
        x[row] = (right[row] - rest) / m[row][row];
    }
    Some(x)
}

/// The principal curvatures of `tensor` in the tangent plane spanned by the orthonormal `u`, `v`,
/// and the direction (in that basis, unit) of the one with the smaller magnitude.
pub(crate) fn principal(tensor: &Tensor, u: Vec3, v: Vec3) -> (f64, f64, [f64; 2]) {
    let apply =
        |a: Vec3, b: Vec3| -> f64 { (0..3).map(|i| (0..3).map(|j| a[i] * tensor[i][j] * b[j]).sum::<f64>()).sum() };
    let (p, q, r) = (apply(u, u), apply(u, v), apply(v, v));
    let mean = 0.5 * (p + r);
    let radius = (0.25 * (p - r) * (p - r) + q * q).sqrt();
    let (first, second) = (mean + radius, mean - radius);
    // Eigenvector of `second` is perpendicular to that of `first`: (q, first − p) or (first − r, q).
    let along_first =
        if (first - p).abs() + q.abs() > (first - r).abs() + q.abs() { [q, first - p] } else { [first - r, q] };
    let length = (along_first[0] * along_first[0] + along_first[1] * along_first[1]).sqrt();
    let along_first = if length > 0.0 { [along_first[0] / length, along_first[1] / length] } else { [1.0, 0.0] };
    let along_second = [-along_first[1], along_first[0]];
    if first.abs() <= second.abs() { (first, second, along_first) } else { (second, first, along_second) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cylinder_curves_around_and_not_along_its_axis() {
        let mesh = crate::tests_surface::cylinder(2.0, 6.0, 13, 48);
        let geometry = vertex_geometry(&mesh);
        for v in (48 * 3..48 * 10).step_by(7) {
            let n = geometry.normals[v];
            let p = mesh.vertices[v];
            // Outward or inward, the normal is radial.
            let radial = normalized([p[0], p[1], 0.0]).unwrap();
            assert!(dot(n, radial).abs() > 0.999, "normal {n:?} at {p:?}");
            let u = perpendicular(n);
            let w = cross(n, u);
            let (least, most, direction) = principal(&geometry.tensors[v], u, w);
            assert!(least.abs() < 0.01, "curvature along the axis {least}");
            assert!((most.abs() - 0.5).abs() < 0.01, "curvature around {most}");
            let along: Vec3 = std::array::from_fn(|i| direction[0] * u[i] + direction[1] * w[i]);
            assert!(along[2].abs() > 0.999, "least curvature direction {along:?} should be the axis");
        }
    }

    #[test]
    fn normals_at_sharp_corners_point_out_of_the_corner() {
        // An octahedron: four faces meet at each corner, at 109° to each other.
        let vertices = vec![
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ];
        let triangles = vec![[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]];
        let mesh = TriangleMesh { vertices: vertices.clone(), triangles };
        let geometry = vertex_geometry(&mesh);
        for (n, v) in geometry.normals.iter().zip(&vertices) {
            assert!(dot(*n, *v) > 0.999, "normal {n:?} at corner {v:?}");
        }
    }

    #[test]
    fn a_plane_has_no_curvature() {
        let vertices = (0..25).map(|i| [(i % 5) as f64, (i / 5) as f64, 0.0]).collect();
        let mut triangles = Vec::new();
        for y in 0..4u32 {
            for x in 0..4u32 {
                let a = y * 5 + x;
                triangles.push([a, a + 1, a + 6]);
                triangles.push([a, a + 6, a + 5]);
            }
        }
        let geometry = vertex_geometry(&TriangleMesh { vertices, triangles });
        for (n, t) in geometry.normals.iter().zip(&geometry.tensors) {
            assert!((n[2].abs() - 1.0).abs() < 1e-12);
            assert!(t.iter().flatten().all(|c| c.abs() < 1e-9));
        }
    }
}
