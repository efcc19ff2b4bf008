//! Fidelity figures of a synthesized pattern against its reference, for benchmarks and tests.
//!
//! A pattern is measured element by element (each a group of strokes): its oriented box (§2.1),
//! centre and footprint. Against the reference's usable elements, a candidate pattern (the output,
//! a tiled copy of the reference, or reference elements at random places) gets:
//! - size: the Wasserstein-1 distance between the distributions of principal-axis lengths, in
//!   units of the reference's mean length L;
//! - spacing: the same between nearest-neighbour distances of element centres, in units of the
//!   reference's mean nearest-neighbour distance s, counting only elements at least s inside the
//!   frame (the reference's own bounding box, the candidate's target) so that the frame's cut does
//!   not count;
//! - orientation: the total variation distance (half the L1 distance, in [0, 1]) between
//!   histograms of axis angles in 18 bins of 10°;
//! - overlap: the share of elements whose ink meets another's.

use std::ops::Range;

use kurbo::Rect;
use motif_core::{Point, math, vector};
use serde::Serialize;

use motif_core::random::Rng;

use crate::analysis::Analysis;
use crate::element::{FitSet, Moments, OrientedBox, fit_box};
use crate::overlap::{Footprint, overlap_rate};
use crate::params::FitPoints;
use crate::stroke::Stroke;

/// The elements of a pattern as measured.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredPattern {
    /// Each element's box.
    pub boxes: Vec<OrientedBox>,
    /// The share of elements whose ink meets another element's.
    pub overlap_rate: f64,
    /// The frame the pattern fills.
    pub frame: Rect,
}

impl MeasuredPattern {
    /// Measures the elements `groups` (ranges of `strokes`) of a pattern that fills `frame`.
    pub fn new(strokes: &[Stroke], groups: &[Range<usize>], frame: Rect) -> MeasuredPattern {
        let boxes = groups
            .iter()
            .map(|group| {
                let sets: Vec<FitSet> =
                    strokes[group.clone()].iter().map(|s| FitSet::of_stroke(s, FitPoints::Skeleton)).collect();
                let moments = sets.iter().fold(Moments::default(), |sum, set| sum.merged(&set.moments));
                fit_box(&moments, sets.iter())
            })
            .collect();
        let footprints: Vec<Footprint> =
            groups.iter().map(|group| Footprint::of_strokes(&strokes[group.clone()])).collect();
        MeasuredPattern { boxes, overlap_rate: overlap_rate(&footprints), frame }
    }

    /// Nearest-neighbour distances of the element centres at least `margin` inside the frame.
    fn nearest_distances(&self, margin: f64) -> Vec<f64> {
        let centres: Vec<Point> = self.boxes.iter().map(|b| b.centre).collect();
        let tree =
            rstar::RTree::bulk_load(centres.iter().enumerate().map(|(i, p)| IndexedPoint([p.x, p.y], i)).collect());
        centres
            .iter()
            .enumerate()
            .filter(|(_, p)| {
                p.x - self.frame.x0 >= margin
                    && self.frame.x1 - p.x >= margin
                    && p.y - self.frame.y0 >= margin
                    && self.frame.y1 - p.y >= margin
            })
            .filter_map(|(i, p)| {
                tree.nearest_neighbor_iter(&[p.x, p.y]).find(|q| q.1 != i).map(|q| vector::distance(*p, centres[q.1]))
            })
            .collect()
    }

    fn mean_length(&self) -> f64 {
        self.boxes.iter().map(|b| b.length).sum::<f64>() / self.boxes.len().max(1) as f64
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct IndexedPoint([f64; 2], usize);

impl rstar::RTreeObject for IndexedPoint {
    type Envelope = rstar::AABB<[f64; 2]>;
    fn envelope(&self) -> Self::Envelope {
        rstar::AABB::from_point(self.0)
    }
}

impl rstar::PointDistance for IndexedPoint {
    fn distance_2(&self, point: &[f64; 2]) -> f64 {
        let (dx, dy) = (self.0[0] - point[0], self.0[1] - point[1]);
        dx * dx + dy * dy
    }
}

/// A candidate pattern's figures against the reference (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Fidelity {
    /// Elements in the candidate.
    pub elements: usize,
    /// Size distance, in units of the reference's mean element length.
    pub size: f64,
    /// Spacing distance, in units of the reference's mean nearest-neighbour distance.
    pub spacing: f64,
    /// Orientation distance (total variation of 10° histograms), in [0, 1].
    pub orientation: f64,
    /// Share of the candidate's elements overlapping another.
    pub overlap_rate: f64,
}

/// The Wasserstein-1 distance between two samples' empirical distributions (0 if either is empty).
pub fn wasserstein(a: &[f64], b: &[f64]) -> f64 {
    if a.is_empty() || b.is_empty() {
        return 0.0;
    }
    let (mut a, mut b) = (a.to_vec(), b.to_vec());
    a.sort_by(f64::total_cmp);
    b.sort_by(f64::total_cmp);
    // Integrate |F_a⁻¹(t) − F_b⁻¹(t)| over the merged quantile breakpoints.
    let (n, m) = (a.len() as f64, b.len() as f64);
    let (mut i, mut j, mut t, mut total) = (0usize, 0usize, 0.0f64, 0.0);
    while i < a.len() && j < b.len() {
        let next = ((i + 1) as f64 / n).min((j + 1) as f64 / m);
        total += (next - t) * (a[i] - b[j]).abs();
        t = next;
        if (i + 1) as f64 / n <= next {
            i += 1;
        }
        if (j + 1) as f64 / m <= next {
            j += 1;
        }
    }
    total
}

fn angle_histogram(boxes: &[OrientedBox]) -> [f64; 18] {
    let mut bins = [0.0; 18];
    for b in boxes {
        let angle = math::atan2(b.axis.y, b.axis.x).rem_euclid(std::f64::consts::PI);
        let bin = ((angle / std::f64::consts::PI * 18.0) as usize).min(17);
        bins[bin] += 1.0 / boxes.len() as f64;
    }
    bins
}

/// The figures of `candidate` against `reference`.
pub fn fidelity(reference: &MeasuredPattern, candidate: &MeasuredPattern) -> Fidelity {
    let length = reference.mean_length().max(1e-12);
    let reference_nearest = reference.nearest_distances(0.0);
    let spacing_unit = (reference_nearest.iter().sum::<f64>() / reference_nearest.len().max(1) as f64).max(1e-12);
    let lengths = |p: &MeasuredPattern| p.boxes.iter().map(|b| b.length).collect::<Vec<f64>>();
    let size = wasserstein(&lengths(reference), &lengths(candidate)) / length;
    let spacing = wasserstein(&reference.nearest_distances(spacing_unit), &candidate.nearest_distances(spacing_unit))
        / spacing_unit;
    let (a, b) = (angle_histogram(&reference.boxes), angle_histogram(&candidate.boxes));
    let orientation = 0.5 * a.iter().zip(&b).map(|(x, y)| (x - y).abs()).sum::<f64>();
    Fidelity { elements: candidate.boxes.len(), size, spacing, orientation, overlap_rate: candidate.overlap_rate }
}

/// The bounding box of every stroke's points.
pub fn strokes_bounds(strokes: &[Stroke]) -> Rect {
    let points: Vec<Point> = strokes.iter().flat_map(|s| s.polyline.points().iter().copied()).collect();
    motif_core::geometry::bounds_of(&points)
}

/// The reference's usable elements (not the border elements left out of copying), measured in
/// the reference's bounding box; their overlap rate counts overlaps with any element, as the
/// synthesis does.
pub fn reference_pattern(analysis: &Analysis, strokes: &[Stroke]) -> MeasuredPattern {
    let (kept, groups) = element_groups(analysis, strokes, |i| analysis.is_usable(i));
    let mut pattern = MeasuredPattern::new(&kept, &groups, strokes_bounds(strokes));
    pattern.overlap_rate = crate::placement::reference_overlap_rate(analysis, strokes);
    pattern
}

/// The strokes of the elements `keep` selects, with each element's range.
fn element_groups(
    analysis: &Analysis,
    strokes: &[Stroke],
    keep: impl Fn(usize) -> bool,
) -> (Vec<Stroke>, Vec<Range<usize>>) {
    let mut kept = Vec::new();
    let mut groups = Vec::new();
    for (i, element) in analysis.elements.iter().enumerate() {
        if keep(i) {
            let start = kept.len();
            kept.extend(element.strokes.iter().map(|&s| strokes[s].clone()));
            groups.push(start..kept.len());
        }
    }
    (kept, groups)
}

/// Baseline: the whole reference repeated side by side (its bounding box as the period) over
/// `frame`, keeping the copies of elements whose centre falls inside the frame.
pub fn tiled_copy(analysis: &Analysis, strokes: &[Stroke], frame: Rect) -> MeasuredPattern {
    let bounds = strokes_bounds(strokes);
    let (width, height) = (bounds.width().max(1e-9), bounds.height().max(1e-9));
    let mut tiled = Vec::new();
    let mut groups = Vec::new();
    let columns = ((frame.width() / width).ceil() as i64).clamp(1, 10_000);
    let rows = ((frame.height() / height).ceil() as i64).clamp(1, 10_000);
    for row in 0..rows {
        for column in 0..columns {
            let offset = kurbo::Vec2::new(
                frame.x0 - bounds.x0 + column as f64 * width,
                frame.y0 - bounds.y0 + row as f64 * height,
            );
            for element in &analysis.elements {
                let centre = element.frame.centre + offset;
                if !frame.contains(centre) {
                    continue;
                }
                let start = tiled.len();
                tiled.extend(element.strokes.iter().map(|&s| strokes[s].transformed(kurbo::Affine::translate(offset))));
                groups.push(start..tiled.len());
            }
        }
    }
    MeasuredPattern::new(&tiled, &groups, frame)
}

/// Baseline: `count` usable reference elements picked at random, unrotated, at uniformly random
/// places in `frame`.
pub fn random_placement(
    analysis: &Analysis,
    strokes: &[Stroke],
    count: usize,
    frame: Rect,
    seed: u64,
) -> MeasuredPattern {
    let usable: Vec<usize> = (0..analysis.elements.len()).filter(|&i| analysis.is_usable(i)).collect();
    let mut random = motif_core::SeedStreams::new(seed).stream("random baseline", 0);
    let mut placed = Vec::new();
    let mut groups = Vec::new();
    for _ in 0..count {
        if usable.is_empty() {
            break;
        }
        let element = &analysis.elements[usable[random.random_range(0..usable.len())]];
        let centre = Point::new(
            frame.x0 + random.random::<f64>() * frame.width(),
            frame.y0 + random.random::<f64>() * frame.height(),
        );
        let shift = kurbo::Affine::translate(centre - element.frame.centre);
        let start = placed.len();
        placed.extend(element.strokes.iter().map(|&s| strokes[s].transformed(shift)));
        groups.push(start..placed.len());
    }
    MeasuredPattern::new(&placed, &groups, frame)
}

/// The synthesized elements of `output` as a measured pattern filling `frame`.
pub fn output_pattern(output: &crate::Output, frame: Rect) -> MeasuredPattern {
    let groups: Vec<Range<usize>> = output.elements.iter().map(|e| e.strokes.clone()).collect();
    MeasuredPattern::new(&output.strokes, &groups, frame)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wasserstein_of_a_shift_is_the_shift() {
        let a = [1.0, 2.0, 3.0, 4.0];
        let b = [1.5, 2.5, 3.5, 4.5];
        assert!((wasserstein(&a, &b) - 0.5).abs() < 1e-12);
        assert!((wasserstein(&a, &[2.5]) - 1.0).abs() < 1e-12);
        assert_eq!(wasserstein(&a, &a), 0.0);
    }
}
