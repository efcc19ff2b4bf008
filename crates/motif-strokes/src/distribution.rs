//! Element distribution (§2.3 and the seed graph of §3.2): neighbour graphs (a chain along a path,
//! unskewed Delaunay edges in a region), k-ring neighbourhoods, shift vectors and neighbourhood
//! areas.

use kurbo::Vec2;
use motif_core::Point;
use motif_core::{math, vector};
use spade::{DelaunayTriangulation, HasPosition, Point2, Triangulation};

/// The largest angle a triangle may have and still count as unskewed: 2π/3 (§2.3).
pub(crate) const MAX_UNSKEWED_ANGLE: f64 = 2.0 * std::f64::consts::FRAC_PI_3;

/// An undirected neighbour graph in compressed rows: `neighbours(i)` is sorted.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Graph {
    offsets: Vec<usize>,
    targets: Vec<u32>,
}

impl Graph {
    /// The graph on `count` nodes with the given undirected edges (duplicates and loops dropped).
    pub fn from_edges(count: usize, edges: &[(usize, usize)]) -> Graph {
        let mut directed: Vec<(u32, u32)> = Vec::with_capacity(2 * edges.len());
        for &(a, b) in edges {
            if a != b {
                directed.push((a as u32, b as u32));
                directed.push((b as u32, a as u32));
            }
        }
        directed.sort_unstable();
        directed.dedup();
        let mut offsets = vec![0; count + 1];
        for &(a, _) in &directed {
            offsets[a as usize + 1] += 1;
        }
        for i in 0..count {
            offsets[i + 1] += offsets[i];
        }
        Graph { offsets, targets: directed.into_iter().map(|(_, b)| b).collect() }
    }

    /// The chain `0 - 1 - … - (count-1)`, closed into a ring when `closed` (and `count > 2`).
    pub fn chain(count: usize, closed: bool) -> Graph {
        let mut edges: Vec<(usize, usize)> = (1..count).map(|i| (i - 1, i)).collect();
        if closed && count > 2 {
            edges.push((count - 1, 0));
        }
        Graph::from_edges(count, &edges)
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// True for a graph without nodes.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The neighbours of node `i`, sorted.
    pub fn neighbours(&self, i: usize) -> &[u32] {
        &self.targets[self.offsets[i]..self.offsets[i + 1]]
    }

    /// Every edge once, as `(a, b)` with `a < b`.
    pub fn edges(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.len())
            .flat_map(move |a| self.neighbours(a).iter().map(move |&b| (a, b as usize)).filter(|(a, b)| a < b))
    }

    /// The k-ring of node `start`: every node within `k` edges of it, itself excluded, in
    /// breadth-first order (nearer rings first, each ring in neighbour order).
    pub fn ring(&self, start: usize, k: usize, scratch: &mut RingScratch, out: &mut Vec<u32>) {
        out.clear();
        scratch.prepare(self.len());
        let stamp = scratch.stamp;
        scratch.mark[start] = stamp;
        let mut begin = 0;
        out.push(start as u32);
        for _ in 0..k {
            let end = out.len();
            for index in begin..end {
                let node = out[index] as usize;
                for &next in self.neighbours(node) {
                    if scratch.mark[next as usize] != stamp {
                        scratch.mark[next as usize] = stamp;
                        out.push(next);
                    }
                }
            }
            if out.len() == end {
                break;
            }
            begin = end;
        }
        out.remove(0);
    }
}

/// Reusable marks for [`Graph::ring`], so that ring queries do not allocate.
#[derive(Debug, Clone, Default)]
pub struct RingScratch {
    mark: Vec<u32>,
    stamp: u32,
}

impl RingScratch {
    fn prepare(&mut self, count: usize) {
        if self.mark.len() < count {
            self.mark.resize(count, 0);
        }
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.mark.iter_mut().for_each(|m| *m = 0);
            self.stamp = 1;
        }
    }
}

/// A point with its index, so that triangulation vertices map back to elements.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Site {
    pub position: Point2<f64>,
    pub index: usize,
}

impl HasPosition for Site {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.position
    }
}

/// The largest interior angle of triangle `abc` (π for a degenerate one).
pub(crate) fn max_angle(a: Point, b: Point, c: Point) -> f64 {
    let angle = |p: Point, q: Point, r: Point| {
        let (u, v) = (q - p, r - p);
        let norms = vector::length(u) * vector::length(v);
        if norms <= 0.0 { std::f64::consts::PI } else { math::acos((u.dot(v) / norms).clamp(-1.0, 1.0)) }
    };
    angle(a, b, c).max(angle(b, c, a)).max(angle(c, a, b))
}

/// A Delaunay triangulation reduced to the edges of its unskewed triangles.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct UnskewedDelaunay {
    /// Edges that belong to at least one triangle without an angle above 2π/3.
    pub graph: Graph,
    /// Number of unskewed triangles.
    pub unskewed_triangles: usize,
    /// Number of triangles removed for an angle above 2π/3.
    pub skewed_triangles: usize,
    /// Mean area of the unskewed triangles (0 when there are none).
    pub mean_triangle_area: f64,
}

/// Triangulates `points` (with `spade`) and keeps only the edges of unskewed triangles (§2.3).
/// Points closer than spade's duplicate tolerance share one vertex; the later ones get no edges.
pub(crate) fn unskewed_delaunay(points: &[Point]) -> UnskewedDelaunay {
    let sites: Vec<Site> =
        points.iter().enumerate().map(|(index, p)| Site { position: Point2::new(p.x, p.y), index }).collect();
    let mut edges = Vec::new();
    let (mut unskewed, mut skewed, mut area) = (0, 0, 0.0);
    if let Ok(triangulation) = DelaunayTriangulation::<Site>::bulk_load(sites) {
        for face in triangulation.inner_faces() {
            let [a, b, c] = face.vertices().map(|v| v.data().index);
            if max_angle(points[a], points[b], points[c]) > MAX_UNSKEWED_ANGLE {
                skewed += 1;
                continue;
            }
            unskewed += 1;
            area += 0.5 * (points[b] - points[a]).cross(points[c] - points[a]).abs();
            edges.extend_from_slice(&[(a, b), (b, c), (c, a)]);
        }
    }
    UnskewedDelaunay {
        graph: Graph::from_edges(points.len(), &edges),
        unskewed_triangles: unskewed,
        skewed_triangles: skewed,
        mean_triangle_area: if unskewed > 0 { area / unskewed as f64 } else { 0.0 },
    }
}

/// The shift vector S of an element (§2.3): its position minus the barycentre of its neighbours,
/// from the neighbours' offsets relative to it (zero without neighbours).
pub(crate) fn shift_from_offsets(offsets: &[Vec2]) -> Vec2 {
    if offsets.is_empty() {
        return Vec2::ZERO;
    }
    -offsets.iter().fold(Vec2::ZERO, |sum, &o| sum + o) / offsets.len() as f64
}

/// The size A_E of a neighbourhood (§3.3) from the neighbours' offsets: along a path, the length
/// it spans along the pattern direction (x); in a region, the area of the polygon through the
/// neighbours taken in angular order (0 with fewer than three).
pub(crate) fn neighbourhood_size(offsets: &[Vec2], along_path: bool) -> f64 {
    if along_path {
        let (low, high) =
            offsets.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), o| (low.min(o.x), high.max(o.x)));
        return if high > low { high - low } else { 0.0 };
    }
    if offsets.len() < 3 {
        return 0.0;
    }
    let mut sorted: Vec<Vec2> = offsets.to_vec();
    sorted.sort_by(|a, b| math::atan2(a.y, a.x).total_cmp(&math::atan2(b.y, b.x)));
    let n = sorted.len();
    0.5 * (0..n).map(|i| sorted[i].cross(sorted[(i + 1) % n])).sum::<f64>().abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unskewed_filter_drops_triangles_with_an_angle_above_two_thirds_pi() {
        // A tall triangle on a base with a fourth point just below the base, outside the tall
        // triangle's circumcircle: Delaunay keeps the flat triangle under the base (an angle near
        // π), whose two new edges must go.
        let points = [Point::new(0.0, 0.0), Point::new(10.0, 0.0), Point::new(5.0, 30.0), Point::new(5.0, -1.0)];
        assert!(max_angle(points[0], points[1], points[3]) > MAX_UNSKEWED_ANGLE);
        let result = unskewed_delaunay(&points);
        assert_eq!(result.unskewed_triangles, 1);
        assert_eq!(result.skewed_triangles, 1);
        assert_eq!(result.graph.edges().collect::<Vec<_>>(), vec![(0, 1), (0, 2), (1, 2)]);
        assert!(result.graph.neighbours(3).is_empty());
        assert!((result.mean_triangle_area - 150.0).abs() < 1e-9);
        // The same quadrilateral with the fourth point farther down keeps every edge.
        let kite = [points[0], points[1], Point::new(5.0, 8.66), Point::new(5.0, -6.0)];
        let kept = unskewed_delaunay(&kite);
        assert_eq!((kept.unskewed_triangles, kept.skewed_triangles), (2, 0));
        assert_eq!(kept.graph.edges().count(), 5);
    }

    #[test]
    fn rings_grow_by_graph_distance() {
        let chain = Graph::chain(12, false);
        let mut scratch = RingScratch::default();
        let mut out = Vec::new();
        chain.ring(5, 2, &mut scratch, &mut out);
        assert_eq!(out, vec![4, 6, 3, 7]);
        chain.ring(0, 3, &mut scratch, &mut out);
        assert_eq!(out, vec![1, 2, 3]);
        let ring = Graph::chain(6, true);
        ring.ring(0, 5, &mut scratch, &mut out);
        assert_eq!(out.len(), 5);
        assert_eq!(ring.neighbours(0), &[1, 5]);
    }

    #[test]
    fn shifts_and_sizes() {
        let offsets = [Vec2::new(-4.0, 1.0), Vec2::new(6.0, 1.0)];
        assert_eq!(shift_from_offsets(&offsets), Vec2::new(-1.0, -1.0));
        assert_eq!(neighbourhood_size(&offsets, true), 10.0);
        let square = [Vec2::new(1.0, 1.0), Vec2::new(-1.0, 1.0), Vec2::new(1.0, -1.0), Vec2::new(-1.0, -1.0)];
        assert_eq!(neighbourhood_size(&square, false), 4.0);
        assert_eq!(shift_from_offsets(&square), Vec2::ZERO);
    }
}
