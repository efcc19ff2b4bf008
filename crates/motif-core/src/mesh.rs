//! Triangle meshes: the surfaces that bound volume domains and carry surface ones, and element
//! meshes placed at synthesized points.

use serde::{Deserialize, Serialize};

/// A triangle mesh: vertex positions and triangles as vertex indices (counter-clockwise seen from
/// outside for a closed surface, though volume tests do not rely on it).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct TriangleMesh {
    /// Vertex positions.
    pub vertices: Vec<[f64; 3]>,
    /// Triangles, three indices into `vertices` each.
    pub triangles: Vec<[u32; 3]>,
}

impl TriangleMesh {
    /// The corners of triangle `t`.
    pub fn corners(&self, t: usize) -> [[f64; 3]; 3] {
        self.triangles[t].map(|v| self.vertices[v as usize])
    }

    /// How many triangles use each edge, as sorted `(edge, count)` runs: an edge is `(low, high)`
    /// vertex indices.
    pub fn edge_uses(&self) -> Vec<((u32, u32), usize)> {
        let mut edges: Vec<(u32, u32)> = self
            .triangles
            .iter()
            .flat_map(|t| (0..3).map(move |i| (t[i].min(t[(i + 1) % 3]), t[i].max(t[(i + 1) % 3]))))
            .collect();
        edges.sort_unstable();
        edges.chunk_by(|a, b| a == b).map(|run| (run[0], run.len())).collect()
    }

    /// One copy of this mesh per placement `(position, frame)`: vertex `v` goes to
    /// `position + frame · v` (`frame[i][j]`: row `i`, column `j`; its columns are where the
    /// mesh's axes go). `None` when the result would exceed `max_triangles` or `u32` indices.
    pub fn placed_copies(
        &self,
        placements: &[([f64; 3], [[f64; 3]; 3])],
        max_triangles: usize,
    ) -> Option<TriangleMesh> {
        let triangles = self.triangles.len().checked_mul(placements.len())?;
        let vertices = self.vertices.len().checked_mul(placements.len())?;
        if triangles > max_triangles || vertices > u32::MAX as usize {
            return None;
        }
        let mut mesh =
            TriangleMesh { vertices: Vec::with_capacity(vertices), triangles: Vec::with_capacity(triangles) };
        for (position, frame) in placements {
            let offset = mesh.vertices.len() as u32;
            mesh.vertices.extend(self.vertices.iter().map(|v| {
                std::array::from_fn(|i| position[i] + frame[i][0] * v[0] + frame[i][1] * v[1] + frame[i][2] * v[2])
            }));
            mesh.triangles.extend(self.triangles.iter().map(|t| t.map(|v| v + offset)));
        }
        Some(mesh)
    }

    /// The bounding box of the vertices used by triangles: `(min, max)`, `None` without triangles.
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        let mut corners = self.triangles.iter().flatten().map(|&v| self.vertices[v as usize]);
        let first = corners.next()?;
        Some(corners.fold((first, first), |(low, high), p| {
            (std::array::from_fn(|a| low[a].min(p[a])), std::array::from_fn(|a| high[a].max(p[a])))
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn copies_are_placed_by_their_frames() {
        let triangle =
            TriangleMesh { vertices: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], triangles: vec![[0, 1, 2]] };
        // The second copy turns x onto y and doubles the size.
        let turn = [[0.0, -2.0, 0.0], [2.0, 0.0, 0.0], [0.0, 0.0, 2.0]];
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let copies = triangle.placed_copies(&[([5.0, 0.0, 0.0], identity), ([0.0, 0.0, 3.0], turn)], 10).unwrap();
        assert_eq!(copies.triangles, vec![[0, 1, 2], [3, 4, 5]]);
        assert_eq!(copies.vertices[1], [6.0, 0.0, 0.0]);
        assert_eq!(copies.vertices[4], [0.0, 2.0, 3.0]);
        assert_eq!(copies.vertices[5], [-2.0, 0.0, 3.0]);
        assert!(triangle.placed_copies(&[([0.0; 3], identity); 11], 10).is_none());
    }
}
