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

    /// The bounding box of the vertices used by triangles: `(min, max)`, `None` without triangles.
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        let mut corners = self.triangles.iter().flatten().map(|&v| self.vertices[v as usize]);
        let first = corners.next()?;
        Some(corners.fold((first, first), |(low, high), p| {
            (std::array::from_fn(|a| low[a].min(p[a])), std::array::from_fn(|a| high[a].max(p[a])))
        }))
    }
}
