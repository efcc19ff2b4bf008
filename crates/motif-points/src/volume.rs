//! Volume domains: the inside of a closed triangle mesh (§6.2, the chair of Figure 1).
//!
//! Membership casts a ray along +x and counts the surface crossings (even-odd), which needs no
//! consistent orientation and holds for closed non-manifold surfaces (every edge shared by an even
//! number of triangles). A ray through an edge or a vertex is counted once: the crossing test
//! projects each triangle on the yz-plane and decides with exact orientation signs
//! (`robust::orient2d`) and a top-left rule, so the triangles around an edge or a vertex never
//! both, nor neither, claim it. Distances to the surface come from an `rstar` tree of triangles.

use motif_core::TriangleMesh;
use robust::{Coord, orient2d};
use rstar::{AABB, PointDistance, RTree};

use crate::error::DomainProblem;
use crate::triangles::{Triangle, Vec3, cross, dot, sub};

/// True when the edge `from → to` of a counter-clockwise 2D triangle owns the points on it: a
/// top edge (horizontal, pointing left) or a left edge (pointing down).
fn owns_edge(from: Coord<f64>, to: Coord<f64>) -> bool {
    (from.y == to.y && to.x < from.x) || to.y < from.y
}

/// Where the ray from `p` along +x meets triangle `corners`, as its x coordinate, when it does
/// (each point of the yz-plane belongs to exactly one of the triangles sharing an edge or vertex).
fn ray_crossing(p: Vec3, corners: [Vec3; 3]) -> Option<f64> {
    let project = |v: Vec3| Coord { x: v[1], y: v[2] };
    let mut t = corners.map(project);
    let q = Coord { x: p[1], y: p[2] };
    let area = orient2d(t[0], t[1], t[2]);
    if area == 0.0 {
        // Edge-on to the ray: no transversal crossing.
        return None;
    }
    if area < 0.0 {
        t.swap(1, 2);
    }
    let mut sides = [0.0; 3];
    for i in 0..3 {
        let (from, to) = (t[i], t[(i + 1) % 3]);
        let side = orient2d(from, to, q);
        if side < 0.0 || (side == 0.0 && !owns_edge(from, to)) {
            return None;
        }
        sides[i] = side;
    }
    // Barycentric weights from the edge tests: the side of edge i weighs the corner opposite it.
    // All are ≥ 0 with a positive sum, so x stays within the triangle's x range even for a
    // triangle nearly edge-on to the ray, where dividing by the normal's x would not.
    let xs = if area < 0.0 { [corners[0][0], corners[2][0], corners[1][0]] } else { corners.map(|c| c[0]) };
    let total = sides[0] + sides[1] + sides[2];
    Some((sides[0] * xs[2] + sides[1] * xs[0] + sides[2] * xs[1]) / total)
}

/// The inside of a closed triangle mesh, ready for membership and distance queries.
#[derive(Debug, Clone)]
pub(crate) struct MeshVolume {
    tree: RTree<Triangle>,
    low: Vec3,
    high: Vec3,
    volume: Option<f64>,
}

impl MeshVolume {
    /// Checks the mesh (triangles, finite vertices, no degenerate triangle, closed) and indexes it.
    pub(crate) fn new(mesh: &TriangleMesh) -> Result<MeshVolume, DomainProblem> {
        let (low, high) = crate::triangles::check_mesh(mesh)?;
        let open = mesh.edge_uses().iter().filter(|(_, uses)| uses % 2 == 1).count();
        if open > 0 {
            return Err(DomainProblem::OpenMesh(open));
        }
        let triangles: Vec<Triangle> =
            (0..mesh.triangles.len()).map(|t| Triangle { corners: mesh.corners(t), index: t as u32 }).collect();
        // Signed tetrahedra from a corner of the bounds (not the origin, against cancellation far
        // from it): the enclosed volume, when the faces are consistently oriented (each edge
        // used as often in one direction as in the other); otherwise the grid measures it.
        let mut directed: Vec<(u32, u32)> =
            mesh.triangles.iter().flat_map(|t| (0..3).map(move |i| (t[i], t[(i + 1) % 3]))).collect();
        directed.sort_unstable();
        let count =
            |edge: (u32, u32)| directed.partition_point(|&e| e <= edge) - directed.partition_point(|&e| e < edge);
        let consistent = directed.iter().all(|&(a, b)| count((a, b)) == count((b, a)));
        let volume = consistent.then(|| {
            let signed: f64 = triangles
                .iter()
                .map(|t| dot(sub(t.corners[0], low), cross(sub(t.corners[1], low), sub(t.corners[2], low))))
                .sum();
            signed.abs() / 6.0
        });
        Ok(MeshVolume { tree: RTree::bulk_load(triangles), low, high, volume })
    }

    /// The bounding box.
    pub(crate) fn bounds(&self) -> (Vec3, Vec3) {
        (self.low, self.high)
    }

    /// The enclosed volume from signed tetrahedra, `None` when the faces are not consistently
    /// oriented (then the quadrature grid measures it).
    pub(crate) fn volume(&self) -> Option<f64> {
        self.volume
    }

    /// Whether `p` lies inside the surface: the number of crossings of the ray from `p` along +x
    /// is odd (points on the surface may fall either way).
    pub(crate) fn contains(&self, p: &Vec3) -> bool {
        if (0..3).any(|a| p[a] < self.low[a] || p[a] > self.high[a]) {
            return false;
        }
        let ray = AABB::from_corners(*p, [self.high[0], p[1], p[2]]);
        let mut crossings = 0usize;
        for triangle in self.tree.locate_in_envelope_intersecting(&ray) {
            match ray_crossing(*p, triangle.corners) {
                Some(x) if x == p[0] => return true,
                Some(x) if x > p[0] => crossings += 1,
                _ => {}
            }
        }
        crossings % 2 == 1
    }

    /// Distance from `p` to the surface.
    pub(crate) fn distance_to_surface(&self, p: &Vec3) -> f64 {
        self.tree.nearest_neighbor(p).map_or(f64::INFINITY, |t| t.distance_2(p).sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An axis-aligned cube `[low, low + side]³` as 12 triangles (outward, counter-clockwise).
    pub(super) fn cube(low: Vec3, side: f64) -> TriangleMesh {
        let vertices = (0..8).map(|i| std::array::from_fn(|a| low[a] + side * f64::from((i >> a) & 1))).collect();
        let quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
        let triangles = quads.iter().flat_map(|q: &[u32; 4]| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect();
        TriangleMesh { vertices, triangles }
    }

    #[test]
    fn a_cube_contains_its_inside_whatever_edges_the_ray_grazes() {
        let volume = MeshVolume::new(&cube([0.0; 3], 2.0)).unwrap();
        assert!((volume.volume().unwrap() - 8.0).abs() < 1e-12);
        // Rays through the middle of faces and along face diagonals (the shared edges of the two
        // triangles of a face); points on the surface may fall either way.
        for p in [[1.0, 1.0, 1.0], [0.5, 0.5, 0.5], [1.0, 1.5, 1.5], [0.3, 0.7, 0.7], [1.9, 0.1, 0.1]] {
            assert!(volume.contains(&p), "{p:?}");
        }
        // Outside, with rays grazing the cube's edges and through its vertices.
        for p in
            [[-0.5, 1.0, 1.0], [3.0, 1.0, 1.0], [1.0, 2.5, 1.0], [-1.0, 1.0, 1.0], [-1.0, 2.0, 2.0], [-1.0, 0.0, 2.0]]
        {
            assert!(!volume.contains(&p), "{p:?}");
        }
        assert!((volume.distance_to_surface(&[1.0, 1.0, 0.5]) - 0.5).abs() < 1e-12);
        assert!((volume.distance_to_surface(&[3.0, 3.0, 1.0]) - 2f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn two_cubes_sharing_an_edge_are_closed_and_non_manifold() {
        let mut mesh = cube([0.0; 3], 1.0);
        let other = cube([1.0, 1.0, 0.0], 1.0);
        let offset = mesh.vertices.len() as u32;
        mesh.vertices.extend(other.vertices);
        mesh.triangles.extend(other.triangles.iter().map(|t| t.map(|v| v + offset)));
        // Weld the shared edge (x = 1, y = 1, z in [0, 1]) so that four faces meet on it.
        let volume = MeshVolume::new(&mesh).unwrap();
        assert!((volume.volume().unwrap() - 2.0).abs() < 1e-12);
        for p in [[0.5, 0.5, 0.5], [1.5, 1.5, 0.5], [0.5, 0.5, 0.999]] {
            assert!(volume.contains(&p), "{p:?}");
        }
        // Outside, the first two rays along the edge that four faces share.
        for p in [[-1.0, 1.0, 0.5], [-1.0, 1.0, 0.25], [1.5, 0.5, 0.5], [0.5, 1.5, 0.5], [-1.0, 0.5, 0.5]] {
            assert!(!volume.contains(&p), "{p:?}");
        }
    }

    /// The octahedron |x − c| + |y − c| + |z − c| ≤ r.
    fn octahedron(c: f64, r: f64) -> TriangleMesh {
        let vertices = vec![[c + r, c, c], [c - r, c, c], [c, c + r, c], [c, c - r, c], [c, c, c + r], [c, c, c - r]];
        let mut triangles = Vec::new();
        for (x, y, z) in [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)] {
            triangles.push([x, y, z]);
        }
        TriangleMesh { vertices, triangles }
    }

    #[test]
    fn a_synthesis_fills_a_mesh_volume_and_stays_inside() {
        use crate::{Domain, Input, Params, synthesize};
        let mesh = octahedron(4.0, 4.0);
        let region = MeshVolume::new(&mesh).unwrap();
        let enclosed = region.volume().unwrap();
        assert!((enclosed - 4.0 / 3.0 * 64.0).abs() < 1e-9);
        let params = Params { neighbourhood: Some(1.2), shrink: Some(0.7), merge_iterations: 10, ..Params::default() };
        let input = Input { exemplar: crate::tests::jittered_cloud(3), domain: Domain::Volume(mesh), existing: None };
        let output = synthesize(&input, &params, &mut motif_core::NoProgress).unwrap();
        let n = output.points.len();
        assert!((n as f64 - enclosed).abs() < 0.15 * enclosed, "{n} points in {enclosed}");
        // One face turned the wrong way: the tetrahedra no longer give the volume, the grid does.
        let mut flipped = octahedron(4.0, 4.0);
        flipped.triangles[0].swap(1, 2);
        assert_eq!(MeshVolume::new(&flipped).unwrap().volume(), None);
        for i in 0..n {
            let p = output.points.position(i);
            assert!(region.contains(&[p[0], p[1], p[2]]), "{p:?} outside");
        }
    }

    #[test]
    fn bad_meshes_are_refused() {
        assert_eq!(MeshVolume::new(&TriangleMesh::default()).unwrap_err(), DomainProblem::EmptyMesh);
        let mut open = cube([0.0; 3], 1.0);
        open.triangles.pop();
        assert_eq!(MeshVolume::new(&open).unwrap_err(), DomainProblem::OpenMesh(3));
        let mut nan = cube([0.0; 3], 1.0);
        nan.vertices[3][1] = f64::NAN;
        assert_eq!(MeshVolume::new(&nan).unwrap_err(), DomainProblem::NonFiniteMeshVertex(3));
        let mut flat = cube([0.0; 3], 1.0);
        flat.triangles[4] = [0, 1, 1];
        assert_eq!(MeshVolume::new(&flat).unwrap_err(), DomainProblem::DegenerateTriangle(4));
        let mut index = cube([0.0; 3], 1.0);
        index.triangles[2][0] = 99;
        assert_eq!(MeshVolume::new(&index).unwrap_err(), DomainProblem::MeshIndex { triangle: 2, vertices: 8 });
    }
}
