//! Element clustering (§2.2): the greedy queue in drawing order with the proximity and
//! continuation tests; merged clusters are refitted.
//!
//! [`cluster`] finds the queue elements a popped element E* could merge with through an R-tree of
//! their bounds (a test can only pass within 1.25 ε of E*'s bounds, see [`SEARCH_MARGIN`]) and
//! visits them in queue order, so it takes the same decisions as the paper's full scan of the
//! queue, which [`cluster_plain`] keeps as the reference implementation.

use crate::attributes::{Appearance, Attributes};
use std::collections::{BTreeSet, VecDeque};

use motif_core::StageTimer;
use motif_core::geometry::perpendicular;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{AABB, RTree};

use crate::element::{FitSet, Moments, OrientedBox, fit_box};
use crate::params::FitPoints;
use crate::stroke::Stroke;

/// An element of the reference pattern: a cluster of strokes and its fitted box.
#[derive(Debug, Clone, PartialEq)]
pub struct Element {
    /// Indices of its strokes in the input, in drawing order.
    pub strokes: Vec<usize>,
    /// The oriented box fitted to all its strokes' points (§2.1).
    pub frame: OrientedBox,
    /// Mean colour in the RGB unit cube, weighted by stroke length.
    pub colour: [f64; 3],
    /// Width, opacity, fill and dash, weighted by stroke length.
    pub attributes: Attributes,
}

impl Element {
    /// What the colour and attribute measures compare.
    pub fn appearance(&self) -> Appearance {
        Appearance { colour: self.colour, attributes: self.attributes }
    }
}

/// How far beyond E*'s bounds a merge partner can lie, in units of ε. Proximity needs a box
/// distance < ε; continuation needs a point of the other box within ε/2 of an axis line and a gap
/// < ε along it, so a distance below √(1 + 1/4) ε ≈ 1.118 ε.
pub(crate) const SEARCH_MARGIN: f64 = 1.25;

/// Proximity (§2.2.1): `min(d_H(E1, E2), d_H(E2, E1)) < ε`, boxes as solid rectangles.
pub(crate) fn proximity(first: &OrientedBox, second: &OrientedBox) -> f64 {
    first.directed_hausdorff(second).min(second.directed_hausdorff(first))
}

/// One axis configuration of the continuation test (§2.2.2): `other`'s largest corner offset from
/// the line through `base`'s centre along `axis`, and the gap between the two boxes' projections
/// on that axis (0 when they overlap).
fn axis_configuration(base: &OrientedBox, other: &OrientedBox, axis: kurbo::Vec2) -> (f64, f64) {
    let other_corners = other.corners();
    let normal = perpendicular(axis);
    let offset = other_corners.iter().map(|&q| (q - base.centre).dot(normal).abs()).fold(0.0, f64::max);
    let range = |corners: &[motif_core::Point; 4]| {
        corners.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), &q| {
            let t = (q - base.centre).dot(axis);
            (low.min(t), high.max(t))
        })
    };
    let ((a0, a1), (b0, b1)) = (range(&base.corners()), range(&other_corners));
    (offset, (a0.max(b0) - a1.min(b1)).max(0.0))
}

/// The four axis configurations (A and B of either element) of the continuation test.
fn axis_configurations(first: &OrientedBox, second: &OrientedBox) -> [(f64, f64); 4] {
    [
        axis_configuration(first, second, first.axis),
        axis_configuration(first, second, first.secondary_axis()),
        axis_configuration(second, first, second.axis),
        axis_configuration(second, first, second.secondary_axis()),
    ]
}

/// Continuation (§2.2.2): for each of the four axes (A and B of either element), the other
/// element is near-collinear when all its corners lie within ε/2 of the axis line through the
/// element's centre; the continuation error is then the gap between the two boxes' projections on
/// the axis. Returns the smallest error over the near-collinear configurations (infinity if none).
pub(crate) fn continuation(first: &OrientedBox, second: &OrientedBox, scale: f64) -> f64 {
    axis_configurations(first, second)
        .into_iter()
        .filter(|&(offset, _)| offset < 0.5 * scale)
        .fold(f64::INFINITY, |best, (_, gap)| best.min(gap))
}

/// The smallest ε at which the continuation test of [`continuation`] passes: over the four axis
/// configurations, the larger of twice the other element's offset from the axis line (it must be
/// within ε/2) and the gap between the projections (it must be below ε).
pub(crate) fn continuation_height(first: &OrientedBox, second: &OrientedBox) -> f64 {
    axis_configurations(first, second)
        .into_iter()
        .fold(f64::INFINITY, |best, (offset, gap)| best.min((2.0 * offset).max(gap)))
}

/// The smallest ε at which the pair test of §2.2 (`should_merge`) joins two elements (it joins
/// them at every ε above): the smaller of their proximity and their `continuation_height`.
pub fn merge_height(first: &OrientedBox, second: &OrientedBox) -> f64 {
    proximity(first, second).min(continuation_height(first, second))
}

/// The element pair test of §2.2: proximity or continuation below ε.
pub(crate) fn should_merge(first: &OrientedBox, second: &OrientedBox, scale: f64) -> bool {
    proximity(first, second) < scale || continuation(first, second, scale) < scale
}

struct Cluster {
    strokes: Vec<usize>,
    moments: Moments,
    frame: OrientedBox,
}

impl Cluster {
    fn merge(&mut self, other: Cluster, sets: &[FitSet]) {
        self.strokes.extend(other.strokes);
        self.strokes.sort_unstable();
        self.moments = self.moments.merged(&other.moments);
        self.frame = fit_box(&self.moments, self.strokes.iter().map(|&s| &sets[s]));
    }
}

fn initial_clusters(sets: &[FitSet]) -> Vec<Option<Cluster>> {
    sets.iter()
        .enumerate()
        .map(|(index, set)| {
            Some(Cluster {
                strokes: vec![index],
                moments: set.moments,
                frame: fit_box(&set.moments, std::iter::once(set)),
            })
        })
        .collect()
}

fn finish(clusters: &mut [Option<Cluster>], order: Vec<usize>, strokes: &[Stroke]) -> Vec<Element> {
    order
        .into_iter()
        .map(|id| {
            let cluster = clusters[id].take().expect("an output cluster is alive");
            let mut colour = [0.0; 3];
            let mut weight = 0.0;
            for &s in &cluster.strokes {
                let length = strokes[s].polyline.length();
                let rgba = strokes[s].representative_colour();
                for (c, &v) in colour.iter_mut().zip(&rgba[..3]) {
                    *c += length * f64::from(v) / 255.0;
                }
                weight += length;
            }
            if weight > 0.0 {
                colour.iter_mut().for_each(|c| *c /= weight);
            }
            let attributes = Attributes::of_strokes(strokes, &cluster.strokes);
            Element { strokes: cluster.strokes, frame: cluster.frame, colour, attributes }
        })
        .collect()
}

/// The R-tree clustering against the paper's full scan on the same strokes: both results must
/// agree, and the times give the speed-up figure of `motif bench --engine strokes`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ClusteringComparison {
    /// Strokes clustered.
    pub strokes: usize,
    /// Elements found (by the R-tree queue).
    pub elements: usize,
    /// Milliseconds of the R-tree queue.
    pub rtree_ms: f64,
    /// Milliseconds of the full scan.
    pub full_scan_ms: f64,
    /// Whether both found the same elements in the same order.
    pub agree: bool,
}

/// Clusters `strokes` at `scale` with the R-tree queue and with the full scan of §2.2 and times
/// both (see [`ClusteringComparison`]).
pub fn compare_clustering(strokes: &[Stroke], fit: FitPoints, scale: f64) -> ClusteringComparison {
    let sets: Vec<FitSet> = strokes.iter().map(|stroke| FitSet::of_stroke(stroke, fit)).collect();
    let mut timer = StageTimer::new();
    let fast = timer.time("rtree", || cluster(strokes, &sets, scale));
    let plain = timer.time("full scan", || cluster_plain(strokes, &sets, scale));
    let stages = timer.finish();
    ClusteringComparison {
        strokes: strokes.len(),
        elements: fast.len(),
        rtree_ms: stages[0].1,
        full_scan_ms: stages[1].1,
        agree: fast == plain,
    }
}

type Entry = GeomWithData<Rectangle<[f64; 2]>, usize>;

fn entry(frame: &OrientedBox, id: usize) -> Entry {
    let bounds = frame.bounds();
    GeomWithData::new(Rectangle::from_corners([bounds.x0, bounds.y0], [bounds.x1, bounds.y1]), id)
}

/// Clusters strokes into elements with the greedy queue of §2.2, using an R-tree to find the
/// queue elements within reach of E*. Elements come out in the order the queue releases them.
pub(crate) fn cluster(strokes: &[Stroke], sets: &[FitSet], scale: f64) -> Vec<Element> {
    let mut clusters = initial_clusters(sets);
    let count = clusters.len();
    let mut ticket: Vec<u64> = (0..count as u64).collect();
    let mut next_ticket = count as u64;
    let mut entries: Vec<Entry> =
        clusters.iter().enumerate().map(|(id, c)| entry(&c.as_ref().expect("fresh").frame, id)).collect();
    let mut tree = RTree::bulk_load(entries.clone());
    let mut queue: VecDeque<usize> = (0..count).collect();
    let mut output = Vec::new();
    let margin = SEARCH_MARGIN * scale;
    let query = |tree: &RTree<Entry>, frame: &OrientedBox| -> Vec<usize> {
        let bounds = frame.bounds().inflate(margin, margin);
        let envelope = AABB::from_corners([bounds.x0, bounds.y0], [bounds.x1, bounds.y1]);
        tree.locate_in_envelope_intersecting(&envelope).map(|e| e.data).collect()
    };
    while let Some(star) = queue.pop_front() {
        if clusters[star].is_none() {
            continue; // merged into an earlier E*; its queue slot is stale
        }
        tree.remove(&entries[star]);
        let mut star_cluster = clusters[star].take().expect("checked above");
        let mut pending: BTreeSet<(u64, usize)> =
            query(&tree, &star_cluster.frame).into_iter().map(|id| (ticket[id], id)).collect();
        let mut merged = false;
        while let Some((position, id)) = pending.pop_first() {
            let other = clusters[id].as_ref().expect("pending clusters are alive");
            if !should_merge(&star_cluster.frame, &other.frame, scale) {
                continue;
            }
            tree.remove(&entries[id]);
            star_cluster.merge(clusters[id].take().expect("alive"), sets);
            merged = true;
            // E* grew: elements later in the queue may now be within reach.
            for id in query(&tree, &star_cluster.frame) {
                if ticket[id] > position {
                    pending.insert((ticket[id], id));
                }
            }
        }
        if merged {
            ticket[star] = next_ticket;
            next_ticket += 1;
            entries[star] = entry(&star_cluster.frame, star);
            tree.insert(entries[star]);
            queue.push_back(star);
        } else {
            output.push(star);
        }
        clusters[star] = Some(star_cluster);
    }
    finish(&mut clusters, output, strokes)
}

/// The paper's algorithm as written: E* is tested against every element of the queue, in order.
/// Quadratic; kept as the reference [`cluster`] is checked against.
pub(crate) fn cluster_plain(strokes: &[Stroke], sets: &[FitSet], scale: f64) -> Vec<Element> {
    let mut clusters = initial_clusters(sets);
    let mut queue: VecDeque<usize> = (0..clusters.len()).collect();
    let mut output = Vec::new();
    while let Some(star) = queue.pop_front() {
        let mut star_cluster = clusters[star].take().expect("queued clusters are alive");
        let mut merged = false;
        queue.retain(|&id| {
            let other = clusters[id].as_ref().expect("queued clusters are alive");
            if should_merge(&star_cluster.frame, &other.frame, scale) {
                star_cluster.merge(clusters[id].take().expect("alive"), sets);
                merged = true;
                false
            } else {
                true
            }
        });
        clusters[star] = Some(star_cluster);
        if merged {
            queue.push_back(star);
        } else {
            output.push(star);
        }
    }
    finish(&mut clusters, output, strokes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::FitPoints;
    use motif_core::math;
    use motif_core::random::Rng;
    use motif_core::{Point, Polyline, SeedStreams};

    fn stroke(points: &[(f64, f64)], closed: bool) -> Stroke {
        Stroke {
            polyline: Polyline::new(points.iter().map(|&(x, y)| Point::new(x, y)).collect(), closed).unwrap(),
            width: 1.0,
            colour: [0, 0, 0, 255],
            fill: None,
            dash: None,
        }
    }

    fn run(strokes: &[Stroke], scale: f64) -> Vec<Element> {
        let sets: Vec<FitSet> = strokes.iter().map(|s| FitSet::of_stroke(s, FitPoints::Skeleton)).collect();
        let fast = cluster(strokes, &sets, scale);
        assert_eq!(fast, cluster_plain(strokes, &sets, scale), "the R-tree queue must agree with the full scan");
        fast
    }

    #[test]
    fn three_overlapping_near_collinear_strokes_form_one_hatch() {
        let strokes = [
            stroke(&[(0.0, 0.0), (20.0, 1.0)], false),
            stroke(&[(14.0, 1.2), (36.0, 1.6)], false),
            stroke(&[(30.0, 1.1), (52.0, 2.4)], false),
        ];
        // Proximity alone would not join them: the outer strokes are far apart.
        let sets: Vec<FitSet> = strokes.iter().map(|s| FitSet::of_stroke(s, FitPoints::Skeleton)).collect();
        let boxes: Vec<OrientedBox> = sets.iter().map(|s| fit_box(&s.moments, std::iter::once(s))).collect();
        assert!(proximity(&boxes[0], &boxes[1]) > 4.0);
        let elements = run(&strokes, 4.0);
        assert_eq!(elements.len(), 1);
        assert_eq!(elements[0].strokes, vec![0, 1, 2]);
        assert!(elements[0].frame.length > 50.0 && elements[0].frame.thickness < 3.0);
    }

    fn flower(centre: (f64, f64), petal: f64) -> Vec<Stroke> {
        (0..5)
            .map(|k| {
                let angle = std::f64::consts::TAU * k as f64 / 5.0;
                let (cx, cy) = (centre.0 + 1.6 * petal * math::cos(angle), centre.1 + 1.6 * petal * math::sin(angle));
                let ring: Vec<(f64, f64)> = (0..16)
                    .map(|i| {
                        let t = std::f64::consts::TAU * i as f64 / 16.0;
                        (cx + petal * math::cos(t), cy + petal * math::sin(t))
                    })
                    .collect();
                stroke(&ring, true)
            })
            .collect()
    }

    #[test]
    fn a_five_stroke_flower_within_scale_is_one_element() {
        let mut strokes = flower((0.0, 0.0), 3.0);
        strokes.extend(flower((40.0, 0.0), 3.0));
        let elements = run(&strokes, 6.0);
        assert_eq!(elements.len(), 2);
        assert_eq!(elements[0].strokes, vec![0, 1, 2, 3, 4]);
        assert_eq!(elements[1].strokes, vec![5, 6, 7, 8, 9]);
    }

    #[test]
    fn strokes_farther_than_scale_stay_apart() {
        // Parallel hatches 6 units apart: separate at ε = 5, one element at ε = 7.
        let strokes: Vec<Stroke> =
            (0..4).map(|i| stroke(&[(6.0 * i as f64, 0.0), (6.0 * i as f64, 20.0)], false)).collect();
        assert_eq!(run(&strokes, 5.0).len(), 4);
        assert_eq!(run(&strokes, 7.0).len(), 1);
        // Collinear strokes with a gap of 8: apart at ε = 6, joined by continuation at ε = 9.
        let dashes = [stroke(&[(0.0, 0.0), (20.0, 0.0)], false), stroke(&[(28.0, 0.0), (48.0, 0.0)], false)];
        assert_eq!(run(&dashes, 6.0).len(), 2);
        assert_eq!(run(&dashes, 9.0).len(), 1);
    }

    #[test]
    fn contour_fitting_lets_a_wide_stroke_reach_its_neighbour() {
        // A short tick 5 units beside a broad stroke 8 wide: its outline reaches to 4, so the
        // tick lies 1.5 from it as drawn, but 5 from its skeleton.
        let mut strokes = vec![stroke(&[(0.0, 0.0), (0.0, 20.0)], false), stroke(&[(5.0, 8.0), (5.0, 12.0)], false)];
        strokes[0].width = 8.0;
        let count = |fit: FitPoints| {
            let sets: Vec<FitSet> = strokes.iter().map(|s| FitSet::of_stroke(s, fit)).collect();
            let elements = cluster(&strokes, &sets, 3.0);
            assert_eq!(elements, cluster_plain(&strokes, &sets, 3.0));
            elements.len()
        };
        assert_eq!(count(FitPoints::Skeleton), 2);
        assert_eq!(count(FitPoints::Contour), 1);
    }

    #[test]
    fn r_tree_queue_equals_full_scan_on_random_scribbles() {
        let streams = SeedStreams::new(3);
        for trial in 0..20 {
            let mut random = streams.stream("scribbles", trial);
            let strokes: Vec<Stroke> = (0..60)
                .map(|_| {
                    let (x, y): (f64, f64) = (random.random_range(0.0..200.0), random.random_range(0.0..200.0));
                    let angle: f64 = random.random_range(0.0..std::f64::consts::PI);
                    let length: f64 = random.random_range(2.0..25.0);
                    stroke(&[(x, y), (x + length * math::cos(angle), y + length * math::sin(angle))], false)
                })
                .collect();
            let elements = run(&strokes, 6.0);
            let mut all: Vec<usize> = elements.iter().flat_map(|e| e.strokes.clone()).collect();
            all.sort_unstable();
            assert_eq!(all, (0..60).collect::<Vec<_>>());
        }
    }

    #[test]
    fn the_merge_height_is_where_the_pair_test_starts_to_pass() {
        let streams = SeedStreams::new(5);
        let mut random = streams.stream("boxes", 0);
        let mut boxes = Vec::new();
        for _ in 0..40 {
            let angle: f64 = random.random_range(0.0..std::f64::consts::PI);
            boxes.push(OrientedBox {
                centre: Point::new(random.random_range(0.0..60.0), random.random_range(0.0..60.0)),
                axis: kurbo::Vec2::new(math::cos(angle), math::sin(angle)),
                length: random.random_range(1.0..20.0),
                thickness: random.random_range(0.0..4.0),
            });
        }
        for (i, first) in boxes.iter().enumerate() {
            for second in &boxes[i + 1..] {
                let height = merge_height(first, second);
                assert!(height.is_finite() && height >= 0.0, "{first:?} {second:?}: {height}");
                assert!(should_merge(first, second, height * 1.001 + 1e-9), "{first:?} {second:?} above {height}");
                assert!(!should_merge(first, second, height * 0.999), "{first:?} {second:?} below {height}");
            }
        }
    }
}
