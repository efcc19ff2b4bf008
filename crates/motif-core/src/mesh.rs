//! Triangle meshes: the surfaces that bound volume domains (and, later, carry surface ones).

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

    /// The bounding box of the vertices used by triangles: `(min, max)`, `None` without triangles.
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        let mut corners = self.triangles.iter().flatten().map(|&v| self.vertices[v as usize]);
        let first = corners.next()?;
        Some(corners.fold((first, first), |(low, high), p| {
            (std::array::from_fn(|a| low[a].min(p[a])), std::array::from_fn(|a| high[a].max(p[a])))
        }))
    }
}
