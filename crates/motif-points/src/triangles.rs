//! Triangles of a mesh in an `rstar` tree: closest points and barycentric coordinates, shared by
//! volume and surface domains.

use motif_core::TriangleMesh;
use rstar::{AABB, PointDistance, RTreeObject};

use crate::error::DomainProblem;

pub(crate) type Vec3 = [f64; 3];

pub(crate) fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// One triangle in the tree.
#[derive(Debug, Clone)]
pub(crate) struct Triangle {
    pub corners: [Vec3; 3],
    /// The triangle's index in its mesh.
    pub index: u32,
}

impl RTreeObject for Triangle {
    type Envelope = AABB<Vec3>;
    fn envelope(&self) -> Self::Envelope {
        let [a, b, c] = self.corners;
        AABB::from_corners(
            std::array::from_fn(|i| a[i].min(b[i]).min(c[i])),
            std::array::from_fn(|i| a[i].max(b[i]).max(c[i])),
        )
    }
}

impl PointDistance for Triangle {
    fn distance_2(&self, point: &Vec3) -> f64 {
        let closest = closest_point(*point, self.corners);
        let d = sub(*point, closest);
        dot(d, d)
    }
}

/// The point of triangle `[a, b, c]` closest to `p` (Ericson, Real-Time Collision Detection §5.1.5).
pub(crate) fn closest_point(p: Vec3, [a, b, c]: [Vec3; 3]) -> Vec3 {
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let along =
        |origin: Vec3, direction: Vec3, t: f64| -> Vec3 { std::array::from_fn(|i| origin[i] + t * direction[i]) };
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return along(a, ab, d1 / (d1 - d3));
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return along(a, ac, d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return along(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denominator = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denominator, vc * denominator);
    std::array::from_fn(|i| a[i] + ab[i] * v + ac[i] * w)
}

/// Barycentric weights of `p` (a point of the triangle's plane) in triangle `[a, b, c]`.
pub(crate) fn barycentric(p: Vec3, [a, b, c]: [Vec3; 3]) -> Vec3 {
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d00, d01, d11) = (dot(ab, ab), dot(ab, ac), dot(ac, ac));
    let (d20, d21) = (dot(ap, ab), dot(ap, ac));
    let denominator = d00 * d11 - d01 * d01;
    if denominator <= 0.0 {
        return [1.0, 0.0, 0.0];
    }
    let v = (d11 * d20 - d01 * d21) / denominator;
    let w = (d00 * d21 - d01 * d20) / denominator;
    [1.0 - v - w, v, w]
}

/// `a / |a|`, or `None` for a (nearly) zero vector.
pub(crate) fn normalized(a: Vec3) -> Option<Vec3> {
    let length = dot(a, a).sqrt();
    (length > 1e-300 && length.is_finite()).then(|| a.map(|c| c / length))
}

/// Checks a mesh (triangles, finite vertices, valid indices, no degenerate triangle) and returns
/// its bounding box.
pub(crate) fn check_mesh(mesh: &TriangleMesh) -> Result<(Vec3, Vec3), DomainProblem> {
    if mesh.triangles.is_empty() {
        return Err(DomainProblem::EmptyMesh);
    }
    if let Some(index) = mesh.vertices.iter().position(|v| v.iter().any(|c| !c.is_finite())) {
        return Err(DomainProblem::NonFiniteMeshVertex(index));
    }
    let count = mesh.vertices.len();
    if let Some(t) = mesh.triangles.iter().position(|t| t.iter().any(|&v| v as usize >= count)) {
        return Err(DomainProblem::MeshIndex { triangle: t, vertices: count });
    }
    let (low, high) = mesh.bounds().ok_or(DomainProblem::EmptyMesh)?;
    let size = (0..3).map(|a| high[a] - low[a]).fold(0.0, f64::max);
    if let Some(t) = (0..mesh.triangles.len()).position(|t| {
        let [a, b, c] = mesh.corners(t);
        let n = cross(sub(b, a), sub(c, a));
        // Twice the area, against the mesh's size: a sliver of relative area 1e-12 is a point.
        dot(n, n).sqrt() <= 1e-12 * size * size
    }) {
        return Err(DomainProblem::DegenerateTriangle(t));
    }
    Ok((low, high))
}
