//! Surfaces reconstructed from points with normals, for display (§6.1, Figure 5: continuous
//! structures shown as surfaces, after [OGG09]).
//!
//! The implicit function is the implicit moving least squares of Kolluri (2005) and Shen et al.
//! (2004): at `x`, the Gaussian-weighted mean of the signed distances `(x − pᵢ)·nᵢ` to the points'
//! tangent planes, with a width of 1.5 mean spacings. It is sampled on a grid of one mean spacing,
//! in the band of nodes within 2.5 widths of a point (the others count as outside), and
//! polygonized with surface nets (`fast-surface-nets`: one vertex per cell the surface crosses,
//! at the mean of the edge crossings, and quads between them), the dual variant of marching
//! cubes: no ambiguous cases and better shaped triangles. Triangles farther than two widths from
//! every point are dropped: the band's inner edge, where the MLS value is negative next to the
//! outside value of the nodes beyond, would otherwise draw a second sheet.

use fast_surface_nets::ndshape::{RuntimeShape, Shape};
use fast_surface_nets::{SurfaceNetsBuffer, surface_nets};
use motif_core::{InvalidParameter, TriangleMesh};
use rayon::prelude::*;
use rstar::RTree;

/// The most grid nodes sampled; a finer grid is coarsened to fit.
const MAX_NODES: f64 = 16_000_000.0;

fn distance2(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]) * (a[i] - b[i])).sum()
}

/// A surface through `positions` with outward `normals` (any length > 0), as triangles.
pub fn reconstruct_surface(positions: &[[f64; 3]], normals: &[[f64; 3]]) -> Result<TriangleMesh, InvalidParameter> {
    if positions.len() < 4 || positions.len() != normals.len() {
        return Err(InvalidParameter::new(
            "surface points",
            format!("{} points and {} normals", positions.len(), normals.len()),
            "at least 4 points, each with a normal",
        ));
    }
    let unit = unit_normals(positions, normals)?;
    let tree: RTree<[f64; 3]> = RTree::bulk_load(positions.to_vec());
    let index: RTree<IndexedPoint> =
        RTree::bulk_load(positions.iter().enumerate().map(|(i, p)| IndexedPoint(*p, i)).collect());
    let spacing = positions
        .iter()
        .map(|p| tree.nearest_neighbor_iter(p).nth(1).map_or(0.0, |q| distance2(p, q).sqrt()))
        .sum::<f64>()
        / positions.len() as f64;
    if spacing <= 0.0 {
        return Err(InvalidParameter::new("surface points", "all at one place", "points spread over a surface"));
    }
    let width = 1.5 * spacing;
    let grid = Grid::new(positions, spacing, width);
    let near = grid.band(positions, width);
    let field = grid.field(&near, &index, &unit, width);
    let mut buffer = SurfaceNetsBuffer::default();
    surface_nets(&field, &grid.shape, [0; 3], grid.dims.map(|d| d - 1), &mut buffer);
    Ok(grid.mesh(&buffer, &tree, width))
}

/// The normals scaled to unit length; fails on a zero or non-finite normal or position.
fn unit_normals(positions: &[[f64; 3]], normals: &[[f64; 3]]) -> Result<Vec<[f64; 3]>, InvalidParameter> {
    let mut unit = Vec::with_capacity(normals.len());
    for (i, n) in normals.iter().enumerate() {
        let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if !(length.is_finite() && length > 0.0) || positions[i].iter().any(|v| !v.is_finite()) {
            return Err(InvalidParameter::new(
                "surface points",
                format!("point {i}"),
                "finite positions and non-zero finite normals (nx, ny, nz)",
            ));
        }
        unit.push(n.map(|v| v / length));
    }
    Ok(unit)
}

/// The grid the implicit function is sampled on: nodes `low + i · step` over the points' bounds
/// padded by two widths.
struct Grid {
    low: [f64; 3],
    step: f64,
    dims: [u32; 3],
    shape: RuntimeShape<u32, 3>,
}

impl Grid {
    /// A grid of one mean spacing, coarsened to at most [`MAX_NODES`] nodes.
    fn new(positions: &[[f64; 3]], spacing: f64, width: f64) -> Self {
        let (mut low, mut high) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in positions {
            for a in 0..3 {
                low[a] = low[a].min(p[a] - 2.0 * width);
                high[a] = high[a].max(p[a] + 2.0 * width);
            }
        }
        let volume: f64 = (0..3).map(|a| high[a] - low[a]).product();
        let step = spacing.max(motif_core::math::cbrt(volume / MAX_NODES));
        let dims: [u32; 3] = std::array::from_fn(|a| ((high[a] - low[a]) / step).ceil() as u32 + 1);
        let shape = RuntimeShape::<u32, 3>::new(dims);
        Self { low, step, dims, shape }
    }

    /// The position of node `i`.
    fn node(&self, i: u32) -> [f64; 3] {
        let [x, y, z] = self.shape.delinearize(i);
        let (low, step) = (self.low, self.step);
        [low[0] + f64::from(x) * step, low[1] + f64::from(y) * step, low[2] + f64::from(z) * step]
    }

    /// Per node, whether it lies within 2.5 widths (in grid cells) of a point: those get the MLS
    /// value; the others only need to be outside (their sheets, at the band's edge, lie farther
    /// than the triangles kept).
    fn band(&self, positions: &[[f64; 3]], width: f64) -> Vec<bool> {
        let (low, step, dims) = (self.low, self.step, self.dims);
        let mut near = vec![false; self.shape.size() as usize];
        let cells = (2.5 * width / step).ceil() as i64;
        for p in positions {
            let centre: [i64; 3] = std::array::from_fn(|a| ((p[a] - low[a]) / step).round() as i64);
            for dz in -cells..=cells {
                for dy in -cells..=cells {
                    for dx in -cells..=cells {
                        let at = [centre[0] + dx, centre[1] + dy, centre[2] + dz];
                        if (0..3).all(|a| at[a] >= 0 && at[a] < i64::from(dims[a])) {
                            near[self.shape.linearize(at.map(|v| v as u32)) as usize] = true;
                        }
                    }
                }
            }
        }
        near
    }

    /// The implicit function at every node: the Gaussian-weighted mean of the signed distances to
    /// the points' tangent planes within the band (that of the nearest point where all weights
    /// vanish), 1 (outside) beyond it.
    fn field(&self, near: &[bool], index: &RTree<IndexedPoint>, unit: &[[f64; 3]], width: f64) -> Vec<f32> {
        // Past 2.5 widths a weight is below 0.2 % of the nearest's.
        let reach2 = (2.5 * width) * (2.5 * width);
        let inverse = 1.0 / (width * width);
        (0..self.shape.size())
            .into_par_iter()
            .with_min_len(4096)
            .map(|i| {
                if !near[i as usize] {
                    return 1.0;
                }
                let x = self.node(i);
                let (mut sum, mut weights) = (0.0, 0.0);
                for IndexedPoint(p, j) in index.locate_within_distance(x, reach2) {
                    let w = motif_core::math::exp(-distance2(&x, p) * inverse);
                    let d: f64 = (0..3).map(|a| (x[a] - p[a]) * unit[*j][a]).sum();
                    sum += w * d;
                    weights += w;
                }
                let value = if weights > 1e-12 {
                    sum / weights
                } else {
                    let IndexedPoint(p, j) = index.nearest_neighbor(&x).expect("at least 4 points");
                    (0..3).map(|a| (x[a] - p[a]) * unit[*j][a]).sum()
                };
                value as f32
            })
            .collect()
    }

    /// The surface nets' triangles as a mesh in the drawing's units, those whose centre is farther
    /// than two widths from every point dropped and the vertices re-indexed.
    fn mesh(&self, buffer: &SurfaceNetsBuffer, tree: &RTree<[f64; 3]>, width: f64) -> TriangleMesh {
        let world: Vec<[f64; 3]> = buffer
            .positions
            .iter()
            .map(|p| std::array::from_fn(|a| self.low[a] + f64::from(p[a]) * self.step))
            .collect();
        let near = |p: &[f64; 3]| tree.nearest_neighbor(p).is_some_and(|q| distance2(p, q) <= 4.0 * width * width);
        let mut mesh = TriangleMesh::default();
        let mut remap = vec![u32::MAX; world.len()];
        for triangle in buffer.indices.chunks_exact(3) {
            let corners = [triangle[0], triangle[1], triangle[2]].map(|v| world[v as usize]);
            let centre: [f64; 3] = std::array::from_fn(|a| (corners[0][a] + corners[1][a] + corners[2][a]) / 3.0);
            if !near(&centre) {
                continue;
            }
            let mut out = [0u32; 3];
            for (k, &v) in triangle.iter().enumerate() {
                if remap[v as usize] == u32::MAX {
                    remap[v as usize] = mesh.vertices.len() as u32;
                    mesh.vertices.push(world[v as usize]);
                }
                out[k] = remap[v as usize];
            }
            mesh.triangles.push(out);
        }
        mesh
    }
}

/// A point with its index, in an R-tree.
#[derive(Debug, Clone, Copy, PartialEq)]
struct IndexedPoint([f64; 3], usize);

impl rstar::RTreeObject for IndexedPoint {
    type Envelope = rstar::AABB<[f64; 3]>;
    fn envelope(&self) -> Self::Envelope {
        rstar::AABB::from_point(self.0)
    }
}

impl rstar::PointDistance for IndexedPoint {
    fn distance_2(&self, point: &[f64; 3]) -> f64 {
        distance2(&self.0, point)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `count` points spread evenly on a sphere (a Fibonacci lattice) with outward normals.
    fn sphere(count: usize, radius: f64, centre: [f64; 3]) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        let (mut positions, mut normals) = (Vec::new(), Vec::new());
        for i in 0..count {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / count as f64;
            let r = (1.0 - z * z).sqrt();
            let angle = golden * i as f64;
            let n = [r * motif_core::math::cos(angle), r * motif_core::math::sin(angle), z];
            positions.push(std::array::from_fn(|a| centre[a] + radius * n[a]));
            normals.push(n);
        }
        (positions, normals)
    }

    #[test]
    fn a_sphere_comes_back_with_its_radius() {
        let centre = [3.0, -2.0, 5.0];
        let (positions, normals) = sphere(4000, 10.0, centre);
        let mesh = reconstruct_surface(&positions, &normals).unwrap();
        assert!(mesh.triangles.len() > 1000, "{} triangles", mesh.triangles.len());
        let radii: Vec<f64> = mesh.vertices.iter().map(|v| distance2(v, &centre).sqrt()).collect();
        let mean = radii.iter().sum::<f64>() / radii.len() as f64;
        assert!((mean - 10.0).abs() < 0.1, "mean radius {mean}");
        assert!(
            radii.iter().all(|r| (r - 10.0).abs() < 0.1),
            "radii {:?}",
            radii.iter().fold((f64::MAX, 0f64), |(a, b), &r| (a.min(r), b.max(r)))
        );
        // Closed: every edge is shared by two triangles.
        assert!(mesh.edge_uses().iter().all(|&(_, uses)| uses == 2));
    }

    #[test]
    fn bad_points_are_refused() {
        assert!(reconstruct_surface(&[[0.0; 3]; 3], &[[0.0, 0.0, 1.0]; 3]).is_err());
        let (positions, mut normals) = sphere(20, 1.0, [0.0; 3]);
        normals[4] = [0.0; 3];
        assert!(reconstruct_surface(&positions, &normals).unwrap_err().to_string().contains("point 4"));
    }
}
