//! Overlaps between elements: where the ink of two elements meets.
//!
//! Clustering (§2.2) merges any two reference strokes closer than ε into one element, so the
//! reference's elements never touch unless their ink does so through its width; a synthesized
//! pattern should not either. An element's footprint is its strokes as `geo` shapes: closed strokes
//! as polygons (an outline drawn inside another overlaps it, even without crossing), open ones as
//! lines with their half widths. Two footprints overlap when their shapes intersect or their inked
//! lines come closer than the sum of their half widths.

use geo::{Coord, Intersects, LineString, Polygon as GeoPolygon};
use motif_core::Point;
use rstar::{AABB, RTree, RTreeObject};

use crate::stroke::Stroke;

/// One element's ink in document coordinates.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Footprint {
    lines: Vec<(LineString<f64>, f64)>,
    areas: Vec<GeoPolygon<f64>>,
    /// Bounds of the ink, half widths included: `[min x, min y, max x, max y]`.
    bounds: [f64; 4],
}

impl Footprint {
    /// The footprint of `strokes` (an element's strokes, already placed).
    pub(crate) fn of_strokes<'a>(strokes: impl IntoIterator<Item = &'a Stroke>) -> Footprint {
        let mut footprint = Footprint {
            lines: Vec::new(),
            areas: Vec::new(),
            bounds: [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY],
        };
        for stroke in strokes {
            let points = stroke.polyline.points();
            let half = 0.5 * stroke.width;
            for p in points {
                footprint.bounds[0] = footprint.bounds[0].min(p.x - half);
                footprint.bounds[1] = footprint.bounds[1].min(p.y - half);
                footprint.bounds[2] = footprint.bounds[2].max(p.x + half);
                footprint.bounds[3] = footprint.bounds[3].max(p.y + half);
            }
            let mut coords: Vec<Coord<f64>> = points.iter().map(|p| Coord { x: p.x, y: p.y }).collect();
            if stroke.polyline.is_closed() && points.len() >= 3 {
                coords.push(coords[0]);
                footprint.areas.push(GeoPolygon::new(LineString::new(coords.clone()), Vec::new()));
            }
            footprint.lines.push((LineString::new(coords), half));
        }
        footprint
    }

    /// True when the footprint holds no ink.
    pub(crate) fn is_empty(&self) -> bool {
        self.lines.is_empty()
    }

    fn envelope(&self) -> AABB<[f64; 2]> {
        AABB::from_corners([self.bounds[0], self.bounds[1]], [self.bounds[2], self.bounds[3]])
    }

    /// True when the two footprints' ink meets.
    pub(crate) fn overlaps(&self, other: &Footprint) -> bool {
        if self.is_empty()
            || other.is_empty()
            || self.bounds[0] > other.bounds[2]
            || other.bounds[0] > self.bounds[2]
            || self.bounds[1] > other.bounds[3]
            || other.bounds[1] > self.bounds[3]
        {
            return false;
        }
        let area_meets = |areas: &[GeoPolygon<f64>], lines: &[(LineString<f64>, f64)]| {
            areas.iter().any(|area| lines.iter().any(|(line, _)| area.intersects(line)))
        };
        if area_meets(&self.areas, &other.lines) || area_meets(&other.areas, &self.lines) {
            return true;
        }
        self.lines.iter().any(|(a, half_a)| {
            other
                .lines
                .iter()
                .any(|(b, half_b)| a.intersects(b) || (half_a + half_b > 0.0 && lines_within(a, b, half_a + half_b)))
        })
    }
}

/// Squared distance from `p` to the segment `a`–`b`.
fn point_segment_squared(p: Coord<f64>, a: Coord<f64>, b: Coord<f64>) -> f64 {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let length_squared = dx * dx + dy * dy;
    let t = if length_squared > 0.0 {
        (((p.x - a.x) * dx + (p.y - a.y) * dy) / length_squared).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (ex, ey) = (a.x + t * dx - p.x, a.y + t * dy - p.y);
    ex * ex + ey * ey
}

/// True when two lines that do not cross come closer than `reach`. Squared distances with plain
/// arithmetic (no square roots or `hypot`), so the decision has the same bits natively and in
/// WebAssembly; `geo`'s distances go through the platform's `hypot`.
fn lines_within(a: &LineString<f64>, b: &LineString<f64>, reach: f64) -> bool {
    let reach_squared = reach * reach;
    // A single point is a segment of length 0.
    fn segments(line: &LineString<f64>) -> impl Iterator<Item = (Coord<f64>, Coord<f64>)> + '_ {
        let single = (line.0.len() == 1).then(|| (line.0[0], line.0[0]));
        single.into_iter().chain(line.0.windows(2).map(|w| (w[0], w[1])))
    }
    segments(a).any(|(p, q)| {
        segments(b).any(|(r, s)| {
            // Bounds apart by more than the reach cannot come within it.
            if p.x.min(q.x) - r.x.max(s.x) > reach
                || r.x.min(s.x) - p.x.max(q.x) > reach
                || p.y.min(q.y) - r.y.max(s.y) > reach
                || r.y.min(s.y) - p.y.max(q.y) > reach
            {
                return false;
            }
            point_segment_squared(p, r, s) < reach_squared
                || point_segment_squared(q, r, s) < reach_squared
                || point_segment_squared(r, p, q) < reach_squared
                || point_segment_squared(s, p, q) < reach_squared
        })
    })
}

/// A footprint's bounds in an R-tree, with its index.
struct Indexed {
    envelope: AABB<[f64; 2]>,
    index: usize,
}

impl RTreeObject for Indexed {
    type Envelope = AABB<[f64; 2]>;
    fn envelope(&self) -> Self::Envelope {
        self.envelope
    }
}

/// Footprints by bounds, for finding the ones an element may overlap.
pub(crate) struct FootprintIndex {
    tree: RTree<Indexed>,
}

impl FootprintIndex {
    /// An index over `footprints`.
    pub(crate) fn new(footprints: &[Footprint]) -> FootprintIndex {
        let items = footprints
            .iter()
            .enumerate()
            .filter(|(_, f)| !f.is_empty())
            .map(|(index, f)| Indexed { envelope: f.envelope(), index })
            .collect();
        FootprintIndex { tree: RTree::bulk_load(items) }
    }

    /// An empty index.
    pub(crate) fn empty() -> FootprintIndex {
        FootprintIndex { tree: RTree::new() }
    }

    /// Adds footprint `index`.
    pub(crate) fn insert(&mut self, index: usize, footprint: &Footprint) {
        if !footprint.is_empty() {
            self.tree.insert(Indexed { envelope: footprint.envelope(), index });
        }
    }

    /// Indices of the indexed footprints whose bounds meet `footprint`'s, in increasing order.
    pub(crate) fn near(&self, footprint: &Footprint) -> Vec<usize> {
        if footprint.is_empty() {
            return Vec::new();
        }
        let mut found: Vec<usize> =
            self.tree.locate_in_envelope_intersecting(&footprint.envelope()).map(|item| item.index).collect();
        found.sort_unstable();
        found
    }
}

/// Number of footprints that overlap at least one other.
pub(crate) fn overlapping_count(footprints: &[Footprint]) -> usize {
    let index = FootprintIndex::new(footprints);
    footprints
        .iter()
        .enumerate()
        .filter(|(i, footprint)| {
            index.near(footprint).into_iter().any(|j| j != *i && footprint.overlaps(&footprints[j]))
        })
        .count()
}

/// The share of elements overlapping another (0 without elements).
pub(crate) fn overlap_rate(footprints: &[Footprint]) -> f64 {
    if footprints.is_empty() { 0.0 } else { overlapping_count(footprints) as f64 / footprints.len() as f64 }
}

/// The centre of a footprint's bounds.
pub(crate) fn bounds_centre(footprint: &Footprint) -> Point {
    Point::new(0.5 * (footprint.bounds[0] + footprint.bounds[2]), 0.5 * (footprint.bounds[1] + footprint.bounds[3]))
}

#[cfg(test)]
mod tests {
    use motif_core::Polyline;

    use super::*;

    fn stroke(points: &[(f64, f64)], closed: bool, width: f64) -> Stroke {
        let points = points.iter().map(|&(x, y)| Point::new(x, y)).collect();
        Stroke::new(Polyline::new(points, closed).unwrap(), width, [0, 0, 0, 255], None)
    }

    #[test]
    fn crossing_touching_nested_and_apart() {
        let horizontal = Footprint::of_strokes([&stroke(&[(0.0, 0.0), (10.0, 0.0)], false, 1.0)]);
        let crossing = Footprint::of_strokes([&stroke(&[(5.0, -5.0), (5.0, 5.0)], false, 1.0)]);
        let near = Footprint::of_strokes([&stroke(&[(0.0, 0.8), (10.0, 0.8)], false, 1.0)]);
        let apart = Footprint::of_strokes([&stroke(&[(0.0, 1.2), (10.0, 1.2)], false, 1.0)]);
        let square = [(-20.0, -20.0), (20.0, -20.0), (20.0, 20.0), (-20.0, 20.0)];
        let outline = Footprint::of_strokes([&stroke(&square, true, 1.0)]);
        assert!(horizontal.overlaps(&crossing) && crossing.overlaps(&horizontal));
        // Ink 1 wide whose skeletons are 0.8 apart touches; 1.2 apart does not.
        assert!(horizontal.overlaps(&near));
        assert!(!horizontal.overlaps(&apart));
        // A stroke inside a closed outline overlaps it without crossing it.
        assert!(outline.overlaps(&horizontal) && horizontal.overlaps(&outline));
        assert_eq!(overlapping_count(&[horizontal.clone(), apart.clone()]), 0);
        let from_below = Footprint::of_strokes([&stroke(&[(5.0, -5.0), (5.0, 0.0)], false, 1.0)]);
        assert_eq!(overlapping_count(&[horizontal, apart, from_below]), 2);
    }
}
