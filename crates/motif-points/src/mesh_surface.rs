//! Surface domains: a 2D exemplar laid on a triangle mesh (§6.2, "triangular surfaces").
//!
//! The exemplar's plane becomes the surface's tangent plane at every quadrature point: its x axis
//! follows the orientation field (the direction of least curvature by default, or a user's vector
//! field), its y axis the normal's cross product with it, and its (empty) third axis the normal.
//! Output points are kept on the mesh by projecting them onto its closest point. Neighbourhoods
//! are measured in 3D, which is the distance along the surface to within `κ² r³ / 24` for a window
//! of radius `r` on a surface of curvature `κ`; the report gives the window over the smallest
//! radius of curvature so that a user can see when that no longer holds.

use motif_core::TriangleMesh;
use rstar::primitives::Line;
use rstar::{PointDistance, RTree};

use crate::curvature::{self, Tensor, VertexGeometry};
use crate::error::DomainProblem;
use crate::params::SurfaceDirections;
use crate::triangles::{self, Triangle, Vec3, cross, dot, normalized, sub};

/// A triangle mesh prepared for projection, frames and sampling.
#[derive(Debug, Clone)]
pub(crate) struct MeshSurface {
    tree: RTree<Triangle>,
    triangles: Vec<[u32; 3]>,
    corners: Vec<[Vec3; 3]>,
    geometry: VertexGeometry,
    directions: SurfaceDirections,
    /// Edges used by one triangle only; `None` for a closed surface.
    boundary: Option<RTree<Line<Vec3>>>,
    /// Cumulative triangle areas, for uniform sampling.
    cumulative_area: Vec<f64>,
    low: Vec3,
    high: Vec3,
    /// Below this difference of principal curvature magnitudes the curvature frame fades into the
    /// fallback direction: a plane or a sphere has no preferred direction.
    flat_curvature: f64,
    /// Cells of side `occupancy_cell` that a triangle's box grown by the band touches: a position
    /// in no such cell is farther than the band from the surface, without a tree query (the
    /// grid of a 20 000-point synthesis on a bull has 3.4 million nodes, of which 2 % are kept).
    occupancy: std::collections::HashSet<[i64; 3]>,
    occupancy_cell: f64,
}

/// The closest point of the surface to a position.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Closest {
    pub point: Vec3,
    pub triangle: usize,
    pub weights: Vec3,
    pub distance: f64,
}

impl MeshSurface {
    /// Checks the mesh and the direction field, and prepares the surface.
    pub(crate) fn new(mesh: &TriangleMesh, directions: &SurfaceDirections) -> Result<MeshSurface, DomainProblem> {
        let (low, high) = triangles::check_mesh(mesh)?;
        match directions {
            SurfaceDirections::Constant(v) => {
                if !v.iter().all(|c| c.is_finite()) || normalized(*v).is_none() {
                    return Err(DomainProblem::SurfaceDirection);
                }
            }
            SurfaceDirections::PerVertex(vectors) => {
                if vectors.len() != mesh.vertices.len() {
                    return Err(DomainProblem::SurfaceDirectionCount {
                        given: vectors.len(),
                        vertices: mesh.vertices.len(),
                    });
                }
                if vectors.iter().flatten().any(|c| !c.is_finite()) {
                    return Err(DomainProblem::SurfaceDirection);
                }
            }
            SurfaceDirections::Curvature => {}
        }
        let triangles_in_tree: Vec<Triangle> =
            (0..mesh.triangles.len()).map(|t| Triangle { corners: mesh.corners(t), index: t as u32 }).collect();
        let mut cumulative_area = Vec::with_capacity(mesh.triangles.len());
        let mut total = 0.0;
        for t in &triangles_in_tree {
            let [a, b, c] = t.corners;
            let n = cross(sub(b, a), sub(c, a));
            total += 0.5 * dot(n, n).sqrt();
            cumulative_area.push(total);
        }
        let edges: Vec<Line<Vec3>> = mesh
            .edge_uses()
            .iter()
            .filter(|(_, uses)| *uses == 1)
            .map(|&((a, b), _)| Line::new(mesh.vertices[a as usize], mesh.vertices[b as usize]))
            .collect();
        let diagonal = dot(sub(high, low), sub(high, low)).sqrt();
        Ok(MeshSurface {
            tree: RTree::bulk_load(triangles_in_tree),
            triangles: mesh.triangles.clone(),
            corners: (0..mesh.triangles.len()).map(|t| mesh.corners(t)).collect(),
            geometry: curvature::vertex_geometry(mesh),
            directions: directions.clone(),
            boundary: (!edges.is_empty()).then(|| RTree::bulk_load(edges)),
            cumulative_area,
            low,
            high,
            flat_curvature: 1.0 / diagonal.max(1e-300),
            occupancy: std::collections::HashSet::new(),
            occupancy_cell: 0.0,
        })
    }

    /// Marks the cells within `band` of a triangle's box (cells of side 2·band, capped at a
    /// million cells per triangle's box; beyond that every position is tested exactly).
    pub(crate) fn mark_band(&mut self, band: f64) {
        self.occupancy.clear();
        self.occupancy_cell = 0.0;
        let cell = 2.0 * band;
        if !(cell > 0.0 && cell.is_finite()) {
            return;
        }
        let index = |v: f64| (v / cell).floor() as i64;
        for corners in &self.corners {
            let low: [i64; 3] =
                std::array::from_fn(|a| index(corners.iter().map(|c| c[a]).fold(f64::INFINITY, f64::min) - band));
            let high: [i64; 3] =
                std::array::from_fn(|a| index(corners.iter().map(|c| c[a]).fold(f64::NEG_INFINITY, f64::max) + band));
            let count: i64 = (0..3).map(|a| high[a] - low[a] + 1).product();
            if count > 1_000_000 {
                self.occupancy.clear();
                return;
            }
            for x in low[0]..=high[0] {
                for y in low[1]..=high[1] {
                    for z in low[2]..=high[2] {
                        self.occupancy.insert([x, y, z]);
                    }
                }
            }
        }
        self.occupancy_cell = cell;
    }

    /// Whether `p` lies within `band` (the one given to [`MeshSurface::mark_band`]) of the surface.
    pub(crate) fn within(&self, p: &Vec3, band: f64) -> bool {
        if self.occupancy_cell > 0.0 && !self.occupancy.contains(&p.map(|v| (v / self.occupancy_cell).floor() as i64)) {
            return false;
        }
        // Any triangle within the band will do: stopping at the first is several times cheaper
        // than finding the nearest.
        self.tree.locate_within_distance(*p, band * band).next().is_some()
    }

    pub(crate) fn bounds(&self) -> (Vec3, Vec3) {
        (self.low, self.high)
    }

    pub(crate) fn area(&self) -> f64 {
        self.cumulative_area.last().copied().unwrap_or(0.0)
    }

    /// The closest point of the surface to `p`.
    pub(crate) fn closest(&self, p: &Vec3) -> Closest {
        let triangle = self.tree.nearest_neighbor(p).expect("a checked mesh has triangles");
        let point = triangles::closest_point(*p, triangle.corners);
        Closest {
            point,
            triangle: triangle.index as usize,
            weights: triangles::barycentric(point, triangle.corners),
            distance: dot(sub(*p, point), sub(*p, point)).sqrt(),
        }
    }

    /// Distance from `p` to the surface's border along it (to within the surface's curvature);
    /// infinite for a closed surface.
    pub(crate) fn border_distance(&self, p: &Vec3) -> f64 {
        self.boundary
            .as_ref()
            .and_then(|tree| tree.nearest_neighbor(p).map(|edge| edge.distance_2(p).sqrt()))
            .unwrap_or(f64::INFINITY)
    }

    fn interpolate<T: Copy>(&self, closest: &Closest, values: &[T], combine: impl Fn(&[T; 3], Vec3) -> T) -> T {
        let corners = self.triangles[closest.triangle].map(|v| values[v as usize]);
        combine(&corners, closest.weights)
    }

    /// The unit normal at the closest point of `p`.
    pub(crate) fn normal(&self, closest: &Closest) -> Vec3 {
        let n = self.interpolate(closest, &self.geometry.normals, |c, w| {
            std::array::from_fn(|i| w[0] * c[0][i] + w[1] * c[1][i] + w[2] * c[2][i])
        });
        normalized(n).unwrap_or_else(|| {
            let [a, b, c] = self.corners[closest.triangle];
            normalized(cross(sub(b, a), sub(c, a))).unwrap_or([0.0, 0.0, 1.0])
        })
    }

    /// The frame at the closest point of `p`: columns x (the orientation field), y = n × x, n.
    pub(crate) fn frame(&self, p: &Vec3) -> [[f64; 3]; 3] {
        let closest = self.closest(p);
        let n = self.normal(&closest);
        // Fallback: the world axis least aligned with the normal, projected (x for a plane z = c).
        let fallback = {
            let axis = if n[0].abs() < 0.9 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
            normalized(sub(axis, scale(n, dot(axis, n)))).unwrap_or_else(|| curvature::perpendicular(n))
        };
        let y_of = |x: Vec3| cross(n, x);
        let field: Option<(Vec3, f64)> = match &self.directions {
            SurfaceDirections::Curvature => {
                let tensor: Tensor = self.interpolate(&closest, &self.geometry.tensors, |c, w| {
                    std::array::from_fn(|i| {
                        std::array::from_fn(|j| w[0] * c[0][i][j] + w[1] * c[1][i][j] + w[2] * c[2][i][j])
                    })
                });
                let v = y_of(fallback);
                let (least, most, direction) = curvature::principal(&tensor, fallback, v);
                let x: Vec3 = std::array::from_fn(|i| direction[0] * fallback[i] + direction[1] * v[i]);
                let anisotropy = (most.abs() - least.abs()) / self.flat_curvature;
                Some((x, anisotropy * anisotropy / (1.0 + anisotropy * anisotropy)))
            }
            SurfaceDirections::Constant(v) => Some((*v, 1.0)),
            SurfaceDirections::PerVertex(vectors) => Some((
                self.interpolate(&closest, vectors, |c, w| {
                    std::array::from_fn(|i| w[0] * c[0][i] + w[1] * c[1][i] + w[2] * c[2][i])
                }),
                1.0,
            )),
        };
        let x = field
            .and_then(|(direction, weight)| {
                let tangent = normalized(sub(direction, scale(n, dot(direction, n))))?;
                // Directions of curvature have no sign: take the one nearer the fallback.
                let tangent = if matches!(self.directions, SurfaceDirections::Curvature) && dot(tangent, fallback) < 0.0
                {
                    scale(tangent, -1.0)
                } else {
                    tangent
                };
                normalized(std::array::from_fn(|i| weight * tangent[i] + (1.0 - weight) * fallback[i]))
            })
            .unwrap_or(fallback);
        let y = y_of(x);
        std::array::from_fn(|i| [x[i], y[i], n[i]])
    }

    /// The larger principal curvature magnitude at the vertices, at the 95th percentile (0 for a
    /// plane): the largest but for sharp tips and creases, where a quadric fit means little.
    pub(crate) fn typical_largest_curvature(&self) -> f64 {
        let mut values: Vec<f64> = self
            .geometry
            .tensors
            .iter()
            .zip(&self.geometry.normals)
            .map(|(t, &n)| {
                let u = curvature::perpendicular(n);
                let (_, most, _) = curvature::principal(t, u, cross(n, u));
                most.abs()
            })
            .collect();
        values.sort_by(f64::total_cmp);
        values.get(values.len() * 95 / 100).copied().unwrap_or(0.0)
    }

    /// A uniform point of the surface from three uniform numbers in [0, 1).
    pub(crate) fn sample(&self, choice: f64, s: f64, t: f64) -> Vec3 {
        let target = choice * self.area();
        let index = self.cumulative_area.partition_point(|&c| c <= target).min(self.cumulative_area.len() - 1);
        let [a, b, c] = self.corners[index];
        let (s, t) = if s + t > 1.0 { (1.0 - s, 1.0 - t) } else { (s, t) };
        std::array::from_fn(|i| a[i] + s * (b[i] - a[i]) + t * (c[i] - a[i]))
    }
}

fn scale(a: Vec3, s: f64) -> Vec3 {
    a.map(|c| c * s)
}
