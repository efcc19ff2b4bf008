//! ε inferred from the reference (the paper lets the user choose it, §2): the merge heights of
//! single-linkage clustering of the strokes' boxes under the pair test of §2.2, and ε in the
//! widest gap between them.

use motif_core::math;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};
use serde::Serialize;

use crate::analysis::fit_sets;
use crate::cluster::merge_height;
use crate::element::{OrientedBox, fit_box};
use crate::params::Params;
use crate::stroke::Stroke;

/// Candidate neighbours per stroke for the spanning tree (nearest by bounding-box distance).
pub const NEIGHBOURS: usize = 16;

/// How [`infer_scale`] chose ε.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ScaleMethod {
    /// In the widest gap between consecutive merge heights.
    Gap,
    /// No gap (fewer than two strokes, all touching, or no gap that leaves [`MIN_ELEMENTS`]):
    /// [`TOUCHING_FRACTION`] of the strokes' median size.
    StrokeSize,
}

/// The ε [`infer_scale`] found, and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InferredScale {
    /// ε, in drawing units (> 0).
    pub value: f64,
    /// How it was chosen.
    pub method: ScaleMethod,
    /// The merge height just below ε (heights under the touching floor count as the floor): the
    /// widest gap within an element. ε is the geometric mean of `below` and `above`.
    pub below: f64,
    /// The merge height just above ε (infinity when none, `null` in JSON): the closest two
    /// elements.
    pub above: f64,
    /// Strokes whose boxes were compared.
    pub strokes: usize,
    /// Stroke pairs whose merge height was measured.
    pub pairs: usize,
}

type Entry = GeomWithData<Rectangle<[f64; 2]>, usize>;

fn entry(frame: &OrientedBox, id: usize) -> Entry {
    let b = frame.bounds();
    GeomWithData::new(Rectangle::from_corners([b.x0, b.y0], [b.x1, b.y1]), id)
}

/// The strokes' fitted boxes (one per stroke, as clustering starts from).
fn stroke_boxes(strokes: &[Stroke], params: &Params) -> Vec<OrientedBox> {
    fit_sets(strokes, params).iter().map(|set| fit_box(&set.moments, std::iter::once(set))).collect()
}

/// Distance between two axis-aligned rectangles (0 when they meet).
fn rect_distance(a: &kurbo::Rect, b: &kurbo::Rect) -> f64 {
    let dx = (a.x0 - b.x1).max(b.x0 - a.x1).max(0.0);
    let dy = (a.y0 - b.y1).max(b.y0 - a.y1).max(0.0);
    math::hypot(dx, dy)
}

/// Each box's [`NEIGHBOURS`] nearest others by bounding-box distance, found in an R-tree by
/// widening a search window: the candidate edges of the spanning tree, each pair once.
fn candidate_pairs(boxes: &[OrientedBox]) -> Vec<(usize, usize)> {
    let tree = RTree::bulk_load(boxes.iter().enumerate().map(|(i, b)| entry(b, i)).collect());
    let extent = boxes.iter().map(|b| b.bounds()).reduce(|a, b| a.union(b)).unwrap_or_default();
    let start = 1e-3 * extent.width().max(extent.height()).max(1e-9);
    let wanted = NEIGHBOURS.min(boxes.len() - 1);
    let mut pairs = Vec::with_capacity(boxes.len() * wanted);
    for (i, frame) in boxes.iter().enumerate() {
        let bounds = frame.bounds();
        let mut reach = start;
        let found = loop {
            let window = bounds.inflate(reach, reach);
            let envelope = AABB::from_corners([window.x0, window.y0], [window.x1, window.y1]);
            let found: Vec<usize> =
                tree.locate_in_envelope_intersecting(&envelope).map(|e| e.data).filter(|&j| j != i).collect();
            if found.len() >= wanted {
                break found;
            }
            reach *= 2.0;
        };
        let mut near: Vec<(f64, usize)> =
            found.into_iter().map(|j| (rect_distance(&bounds, &boxes[j].bounds()), j)).collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        pairs.extend(near.into_iter().take(wanted).map(|(_, j)| (i.min(j), i.max(j))));
    }
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}

fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// The merge heights of single-linkage clustering of the strokes' boxes under the pair test of
/// §2.2 (the `cluster` module's proximity and continuation, as the ε at which each passes): the
/// edge lengths of a minimum spanning tree (Kruskal) over each stroke's [`NEIGHBOURS`] nearest
/// boxes, ascending, with the number of pairs measured. A spanning forest when the candidate graph
/// is not connected.
pub fn merge_heights(strokes: &[Stroke], params: &Params) -> (Vec<f64>, usize) {
    spanning_heights(&stroke_boxes(strokes, params))
}

/// [`merge_heights`] of the boxes.
fn spanning_heights(boxes: &[OrientedBox]) -> (Vec<f64>, usize) {
    if boxes.len() < 2 {
        return (Vec::new(), 0);
    }
    let mut edges: Vec<(f64, usize, usize)> =
        candidate_pairs(boxes).into_iter().map(|(a, b)| (merge_height(&boxes[a], &boxes[b]), a, b)).collect();
    let pairs = edges.len();
    edges.sort_by(|a, b| a.0.total_cmp(&b.0).then((a.1, a.2).cmp(&(b.1, b.2))));
    let mut parent: Vec<usize> = (0..boxes.len()).collect();
    let mut heights = Vec::with_capacity(boxes.len() - 1);
    for (height, a, b) in edges {
        let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
        if ra != rb {
            parent[ra.max(rb)] = ra.min(rb);
            heights.push(height);
        }
    }
    (heights, pairs)
}

/// Merge heights below this fraction of the median stroke size (the diagonal of a stroke's
/// fitted box) count as touching: a gap that small is not seen as a separation.
pub const TOUCHING_FRACTION: f64 = 0.1;

/// The fewest elements an inferred ε leaves (or every stroke, with fewer strokes): a gap among
/// the last few merges, the widest between a handful of clumps, does not make a pattern.
pub const MIN_ELEMENTS: usize = 4;

/// The median of the strokes' sizes: the diagonals of their fitted boxes.
fn median_size(boxes: &[OrientedBox]) -> f64 {
    let mut sizes: Vec<f64> = boxes.iter().map(|b| math::hypot(b.length, b.thickness)).collect();
    sizes.sort_by(f64::total_cmp);
    sizes.get(sizes.len() / 2).copied().unwrap_or(0.0)
}

/// The widest gap in log scale between consecutive `heights` (ascending, each at least `floor`,
/// `floor` itself first) that leaves at least `min_elements` elements: the index of the height
/// below it, when a gap is wider than a ratio of 1.
fn widest_gap(heights: &[f64], min_elements: usize) -> Option<usize> {
    let mut best: Option<(f64, usize)> = None;
    for i in 0..heights.len().saturating_sub(1) {
        // Merging every height up to i leaves one element per height above it, plus one.
        if heights.len() - i < min_elements {
            break;
        }
        let ratio = heights[i + 1] / heights[i];
        if ratio > 1.0 && best.is_none_or(|(widest, _)| ratio > widest) {
            best = Some((ratio, i));
        }
    }
    best.map(|(_, i)| i)
}

/// Infers ε from the reference strokes (`params.fit` decides the boxes; ε itself is ignored).
///
/// Method: the [`merge_heights`] of single-linkage clustering of the strokes' boxes under the
/// pair test of §2.2 (a minimum spanning tree over each stroke's [`NEIGHBOURS`] nearest boxes,
/// so the work stays O(n log n)), heights below [`TOUCHING_FRACTION`] of the median stroke size
/// raised to that floor, then ε at the geometric mean of the two heights around the widest gap in
/// log scale, among the gaps that leave at least [`MIN_ELEMENTS`] elements; the floor itself is
/// the first height, so that a pattern whose strokes are all apart gets an ε under its closest
/// pair. Without such a gap (fewer than two strokes, or every stroke touching a neighbour), ε is
/// the floor ([`ScaleMethod::StrokeSize`]). Deterministic. On the real corpus
/// (`data/real/strokes/`, `docs/strokes.md`) it finds within 25 % of the elements a person counts
/// in 7 of the 9 drawings.
pub fn infer_scale(strokes: &[Stroke], params: &Params) -> InferredScale {
    let boxes = stroke_boxes(strokes, params);
    let (heights, pairs) = spanning_heights(&boxes);
    let size = median_size(&boxes);
    let floor = if size > 0.0 { TOUCHING_FRACTION * size } else { 1.0 };
    let mut raised = Vec::with_capacity(heights.len() + 1);
    raised.push(floor);
    raised.extend(heights.iter().map(|&h| h.max(floor)));
    let min_elements = MIN_ELEMENTS.min(strokes.len());
    let found =
        |value, method, below, above| InferredScale { value, method, below, above, strokes: strokes.len(), pairs };
    match widest_gap(&raised, min_elements) {
        Some(i) => found((raised[i] * raised[i + 1]).sqrt(), ScaleMethod::Gap, raised[i], raised[i + 1]),
        None => {
            let below = heights.iter().copied().filter(|&h| h <= floor).fold(0.0, f64::max);
            let above = heights.iter().copied().find(|&h| h > floor).unwrap_or(f64::INFINITY);
            found(floor, ScaleMethod::StrokeSize, below, above)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cluster::cluster;
    use motif_core::{Point, Polyline};

    fn segment(x: f64, y: f64) -> Stroke {
        Stroke {
            polyline: Polyline::new(vec![Point::new(x, y), Point::new(x, y + 10.0)], false).unwrap(),
            width: 1.0,
            colour: [0, 0, 0, 255],
            fill: None,
            dash: None,
        }
    }

    /// A 6 × 4 grid of hatches, each of three strokes 10 long and `inner` apart, with gaps of
    /// `outer` between hatches.
    fn hatches(inner: f64, outer: f64) -> Vec<Stroke> {
        hatches_grid(inner, outer, 6, 4)
    }

    fn hatches_grid(inner: f64, outer: f64, columns: usize, rows: usize) -> Vec<Stroke> {
        let (width, height) = (2.0 * inner + outer, 10.0 + outer);
        let mut strokes = Vec::new();
        for row in 0..rows {
            for column in 0..columns {
                for k in 0..3 {
                    strokes.push(segment(column as f64 * width + k as f64 * inner, row as f64 * height));
                }
            }
        }
        strokes
    }

    #[test]
    fn epsilon_falls_between_the_gaps_within_and_between_elements() {
        let strokes = hatches(1.5, 12.0);
        let params = Params::default();
        let inferred = infer_scale(&strokes, &params);
        assert_eq!(inferred.method, ScaleMethod::Gap);
        assert!(inferred.value > 1.5 && inferred.value < 12.0, "{inferred:?}");
        assert!((inferred.below - 1.5).abs() < 1e-9 && (inferred.above - 12.0).abs() < 1e-9, "{inferred:?}");
        let sets = crate::analysis::fit_sets(&strokes, &params);
        assert_eq!(cluster(&strokes, &sets, inferred.value).len(), 24);
        assert_eq!(infer_scale(&strokes, &params), inferred, "deterministic");
    }

    #[test]
    fn strokes_all_apart_get_an_epsilon_under_their_closest_pair() {
        // Every stroke 4 apart, far above the touching floor (a tenth of their length, 1).
        let strokes: Vec<Stroke> = (0..12).map(|i| segment(4.0 * i as f64, 0.0)).collect();
        let inferred = infer_scale(&strokes, &Params::default());
        assert_eq!(inferred.method, ScaleMethod::Gap);
        assert!(inferred.value < 4.0 && inferred.value >= 1.0, "{inferred:?}");
    }

    #[test]
    fn without_a_gap_epsilon_is_the_touching_floor() {
        let one = infer_scale(&[segment(0.0, 0.0)], &Params::default());
        assert_eq!((one.method, one.value, one.pairs), (ScaleMethod::StrokeSize, 1.0, 0));
        // Strokes that all cross one another: every merge height is 0.
        let mut crossing = vec![segment(5.0, -5.0)];
        crossing.push(Stroke {
            polyline: Polyline::new(vec![Point::new(0.0, 0.0), Point::new(10.0, 0.0)], false).unwrap(),
            ..segment(0.0, 0.0)
        });
        let inferred = infer_scale(&crossing, &Params::default());
        assert_eq!(inferred.method, ScaleMethod::StrokeSize);
        assert!(inferred.value > 0.0);
    }

    #[test]
    fn many_strokes_measure_a_bounded_number_of_pairs() {
        let strokes = hatches_grid(1.5, 12.0, 30, 24);
        let params = Params::default();
        let (heights, pairs) = merge_heights(&strokes, &params);
        assert!(pairs <= NEIGHBOURS * strokes.len(), "{pairs}");
        assert!(heights.len() < strokes.len());
        let inferred = infer_scale(&strokes, &params);
        assert!(inferred.value > 1.5 && inferred.value < 12.0, "{inferred:?}");
    }

    #[test]
    fn empty_and_degenerate_references_give_a_positive_epsilon() {
        let empty = infer_scale(&[], &Params::default());
        assert_eq!((empty.method, empty.value, empty.strokes, empty.pairs), (ScaleMethod::StrokeSize, 1.0, 0, 0));
        // The same stroke drawn ten times: every merge height is 0, no gap.
        let copies = vec![segment(3.0, 4.0); 10];
        let inferred = infer_scale(&copies, &Params::default());
        assert_eq!((inferred.method, inferred.value), (ScaleMethod::StrokeSize, 1.0), "{inferred:?}");
        assert_eq!(inferred.above, f64::INFINITY);
        // Tiny strokes far apart, and strokes far from the origin.
        let tiny: Vec<Stroke> = (0..5)
            .map(|i| Stroke {
                polyline: Polyline::new(vec![Point::new(i as f64, 0.0), Point::new(i as f64, 1e-6)], false).unwrap(),
                ..segment(0.0, 0.0)
            })
            .collect();
        let far: Vec<Stroke> = (0..5).map(|i| segment(1e9 + 30.0 * i as f64, -1e9)).collect();
        for strokes in [tiny, far] {
            let inferred = infer_scale(&strokes, &Params::default());
            assert!(inferred.value.is_finite() && inferred.value > 0.0, "{inferred:?}");
            assert!(inferred.below <= inferred.value && inferred.value <= inferred.above, "{inferred:?}");
        }
    }

    #[test]
    fn the_order_of_the_strokes_does_not_change_epsilon() {
        let strokes = hatches(2.0, 9.0);
        let params = Params::default();
        let mut reversed = strokes.clone();
        reversed.reverse();
        let (forward, backward) = (infer_scale(&strokes, &params), infer_scale(&reversed, &params));
        assert_eq!(forward.value.to_bits(), backward.value.to_bits(), "{forward:?} {backward:?}");
        assert!(forward.value > 2.0 && forward.value < 9.0, "{forward:?}");
    }
}
