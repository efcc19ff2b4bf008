//! Neighbourhood matching (§3.1): relevant pairs by mutual nearest centres, the five perceptual
//! measures averaged over the pairs, and the test `col and (shape or (par and ov and sup))`.
//!
//! Every synthesized element is (until the variation post-process) a copy of a reference element,
//! so a pair's measures depend only on the two reference elements involved. [`MeasureTable`]
//! computes them once for all reference pairs, already divided by their thresholds; comparing two
//! neighbourhoods is then a mutual-nearest search plus table look-ups. [`compare_plain`] computes
//! every measure from the boxes instead, as the reference implementation.

use kurbo::Vec2;
use motif_core::math;

use crate::attributes::Appearance;
use crate::element::OrientedBox;
use crate::params::Thresholds;

/// Boxes this elongated (thickness at most a third of the length) have a full orientation.
const FULL_ANISOTROPY: f64 = 0.5;

/// How much a box's principal axis means, in [0, 1]: its anisotropy `(length − thickness) /
/// (length + thickness)` over [`FULL_ANISOTROPY`], capped at 1. A square or round element (a
/// dot, a three-armed star, an equilateral triangle) has a principal axis set by noise in its
/// drawing; comparing that axis across elements made the paper's parallelism test fail at random
/// on such patterns (134 of 229 elements fell back to the best match on the demo's figures).
fn orientation_weight(frame: &OrientedBox) -> f64 {
    let total = frame.length + frame.thickness;
    if total <= 0.0 {
        return 0.0;
    }
    ((frame.length - frame.thickness) / total / FULL_ANISOTROPY).min(1.0)
}

/// The measures of one element pair or, averaged, of two neighbourhoods: the paper's five (§3.1)
/// and the attribute measure.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Measures {
    /// Symmetric Hausdorff distance between the boxes with their centres aligned.
    pub shape: f64,
    /// Angle between the principal axes, in `[0, π/2]`, scaled down for nearly square boxes
    /// whose axis means little (see `orientation_weight`).
    pub parallelism: f64,
    /// Ratio of principal-axis lengths, larger over smaller (≥ 1).
    pub overlap: f64,
    /// Difference of secondary-axis lengths (thicknesses).
    pub superimposition: f64,
    /// Distance between the mean colours in the RGB unit cube.
    pub colour: f64,
    /// The largest difference of stroke width, opacity, fill or dash ([`crate::Attributes::difference`]).
    pub attributes: f64,
}

impl Measures {
    /// The measures of a reference element and a target element, both in the pattern frame.
    pub(crate) fn of_pair(
        reference: &OrientedBox,
        target: &OrientedBox,
        reference_appearance: &Appearance,
        target_appearance: &Appearance,
    ) -> Measures {
        let (reference_colour, target_colour) = (reference_appearance.colour, target_appearance.colour);
        let aligned = target.moved_to(reference.centre);
        let shape = reference.directed_hausdorff(&aligned).max(aligned.directed_hausdorff(reference));
        let cosine = reference.axis.dot(target.axis).abs().min(1.0);
        let parallelism = math::acos(cosine) * orientation_weight(reference).min(orientation_weight(target));
        let (long, short) = if reference.length >= target.length {
            (reference.length, target.length)
        } else {
            (target.length, reference.length)
        };
        let overlap = if short > 0.0 {
            long / short
        } else if long > 0.0 {
            f64::INFINITY
        } else {
            1.0
        };
        let superimposition = (reference.thickness - target.thickness).abs();
        let colour = reference_colour.iter().zip(&target_colour).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt();
        let attributes = reference_appearance.attributes.difference(&target_appearance.attributes);
        Measures { shape, parallelism, overlap, superimposition, colour, attributes }
    }

    /// The measures divided by their thresholds, overlap as `(ov - 1) / (σ_ov - 1)`: each is below
    /// 1 exactly when its measure is below its threshold, and each is linear in its measure, so
    /// averaging normalized values equals normalizing averages.
    pub(crate) fn normalized(&self, limits: &Limits) -> Normalized {
        [
            self.shape / limits.shape,
            self.parallelism / limits.parallelism,
            (self.overlap - 1.0) / (limits.overlap - 1.0),
            self.superimposition / limits.superimposition,
            self.colour / limits.colour,
            self.attributes / limits.attributes,
        ]
    }
}

/// The thresholds in drawing units (shape and superimposition multiplied by L).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Limits {
    /// σ_shape in drawing units.
    pub shape: f64,
    /// σ_par in radians.
    pub parallelism: f64,
    /// σ_ov, a ratio > 1.
    pub overlap: f64,
    /// σ_sup in drawing units.
    pub superimposition: f64,
    /// σ_col in the RGB unit cube.
    pub colour: f64,
    /// σ_attr, on the unit scales of [`crate::Attributes::difference`].
    pub attributes: f64,
}

impl Limits {
    /// Thresholds for a reference whose elements have mean principal-axis length `mean_length`.
    pub(crate) fn new(thresholds: &Thresholds, mean_length: f64) -> Limits {
        let length = mean_length.max(1e-9);
        Limits {
            shape: thresholds.shape * length,
            parallelism: thresholds.parallelism,
            overlap: thresholds.overlap,
            superimposition: thresholds.superimposition * length,
            colour: thresholds.colour,
            attributes: thresholds.attributes,
        }
    }
}

/// The six measures divided by their thresholds, in the order shape, parallelism, overlap,
/// superimposition, colour, attributes.
pub(crate) type Normalized = [f64; 6];

/// How far averaged normalized measures are from passing the paper's test, with the attribute
/// measure beside colour: `col and attr and (shape or (par and ov and sup))`, that is
/// `max(col, attr, min(shape, max(par, ov, sup)))`. The test passes exactly when this is below 1;
/// the fallback takes the smallest.
pub(crate) fn violation(normalized: &Normalized) -> f64 {
    let [shape, parallelism, overlap, superimposition, colour, attributes] = *normalized;
    colour.max(attributes).max(shape.min(parallelism.max(overlap).max(superimposition)))
}

/// A neighbour in a neighbourhood: which reference element it is (or is a copy of) and its offset
/// from the neighbourhood's centre in the pattern frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Member {
    /// Reference element index.
    pub element: u32,
    /// Offset from the centre element's position.
    pub offset: Vec2,
}

/// References with more elements than this do not get a full pair table (it grows with the
/// square of the count: 2 048 elements take 160 MiB); their measures are computed on demand.
pub(crate) const MAX_TABLE_ELEMENTS: usize = 2048;

/// Normalized measures for every ordered pair of reference elements: a precomputed table, or for
/// very large references, the boxes to compute them from on demand.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MeasureTable {
    count: usize,
    values: Vec<Normalized>,
    frames: Vec<OrientedBox>,
    appearances: Vec<Appearance>,
    limits: Limits,
}

impl MeasureTable {
    /// The table for reference elements with boxes `frames` (pattern frame) and `appearances`.
    pub(crate) fn new(frames: &[OrientedBox], appearances: &[Appearance], limits: &Limits) -> MeasureTable {
        let count = frames.len();
        let mut values = Vec::new();
        if count <= MAX_TABLE_ELEMENTS {
            values.reserve(count * count);
            for i in 0..count {
                for j in 0..count {
                    values.push(
                        Measures::of_pair(&frames[i], &frames[j], &appearances[i], &appearances[j]).normalized(limits),
                    );
                }
            }
        }
        MeasureTable { count, values, frames: frames.to_vec(), appearances: appearances.to_vec(), limits: *limits }
    }

    /// Normalized measures of reference element `reference` against (a copy of) `target`.
    pub(crate) fn get(&self, reference: u32, target: u32) -> Normalized {
        let (i, j) = (reference as usize, target as usize);
        if self.values.is_empty() {
            Measures::of_pair(&self.frames[i], &self.frames[j], &self.appearances[i], &self.appearances[j])
                .normalized(&self.limits)
        } else {
            self.values[i * self.count + j]
        }
    }
}

/// Reusable buffers for [`compare`].
#[derive(Debug, Clone, Default)]
pub(crate) struct CompareScratch {
    /// For each target member: index of its nearest reference member.
    nearest_reference: Vec<u32>,
}

/// Index of the member of `members` nearest to `offset` (the first one on ties).
fn nearest(members: &[Member], offset: Vec2) -> usize {
    let mut best = (f64::INFINITY, 0);
    for (index, member) in members.iter().enumerate() {
        let d = (member.offset - offset).hypot2();
        if d < best.0 {
            best = (d, index);
        }
    }
    best.1
}

/// Calls `visit(a, b)` for every relevant pair: `reference[a]` and `target[b]` mutually nearest by
/// centre offsets (ties to the lower index), in target order.
///
/// A pair needs `a` to be the nearest reference member of `b`, so only those candidates are
/// checked the other way: `|target| × (|reference| + |target|)` distances instead of the whole
/// matrix twice.
fn mutual_nearest(
    reference: &[Member],
    target: &[Member],
    scratch: &mut CompareScratch,
    mut visit: impl FnMut(usize, usize),
) {
    if target.is_empty() || reference.is_empty() {
        return;
    }
    let candidates = &mut scratch.nearest_reference;
    candidates.clear();
    candidates.extend(target.iter().map(|t| nearest(reference, t.offset) as u32));
    for (b, &a) in candidates.iter().enumerate() {
        if nearest(target, reference[a as usize].offset) == b {
            visit(a as usize, b);
        }
    }
}

/// Averaged normalized measures between a reference neighbourhood and a (partial) target
/// neighbourhood: relevant pairs by mutual nearest centres, measures from the table, averaged over
/// the pairs, which normalizes by the number of known target neighbours that found a partner
/// (§3.2). `None` when no pair exists.
pub(crate) fn compare(
    reference: &[Member],
    target: &[Member],
    table: &MeasureTable,
    scratch: &mut CompareScratch,
) -> Option<Normalized> {
    let mut sum = [0.0; 6];
    let mut pairs = 0usize;
    mutual_nearest(reference, target, scratch, |a, b| {
        let values = table.get(reference[a].element, target[b].element);
        for (s, v) in sum.iter_mut().zip(values) {
            *s += v;
        }
        pairs += 1;
    });
    (pairs > 0).then(|| sum.map(|s| s / pairs as f64))
}

/// [`compare`] computing every measure from the boxes: the plain reference implementation, which
/// the tests hold the table look-ups to.
#[cfg(test)]
pub(crate) fn compare_plain(
    reference: &[Member],
    target: &[Member],
    frames: &[OrientedBox],
    appearances: &[Appearance],
    limits: &Limits,
) -> Option<Normalized> {
    let mut sum = [0.0; 6];
    let mut pairs = 0usize;
    for (a, r) in reference.iter().enumerate() {
        let nearest_target = (0..target.len())
            .min_by(|&x, &y| (r.offset - target[x].offset).hypot2().total_cmp(&(r.offset - target[y].offset).hypot2()));
        let Some(b) = nearest_target else { continue };
        let nearest_reference = (0..reference.len()).min_by(|&x, &y| {
            (reference[x].offset - target[b].offset)
                .hypot2()
                .total_cmp(&(reference[y].offset - target[b].offset).hypot2())
        });
        if nearest_reference != Some(a) {
            continue;
        }
        let (i, j) = (r.element as usize, target[b].element as usize);
        let values = Measures::of_pair(&frames[i], &frames[j], &appearances[i], &appearances[j]).normalized(limits);
        for (s, v) in sum.iter_mut().zip(values) {
            *s += v;
        }
        pairs += 1;
    }
    (pairs > 0).then(|| sum.map(|s| s / pairs as f64))
}

#[cfg(test)]
mod tests {
    use super::*;
    use motif_core::random::Rng;
    use motif_core::{Point, SeedStreams};

    fn frame(angle: f64, length: f64, thickness: f64) -> OrientedBox {
        OrientedBox { centre: Point::ORIGIN, axis: Vec2::new(math::cos(angle), math::sin(angle)), length, thickness }
    }

    #[test]
    fn pair_measures_follow_their_definitions() {
        let a = frame(0.0, 10.0, 2.0);
        let b = frame(std::f64::consts::FRAC_PI_2 + 0.1, 5.0, 1.0).moved_to(Point::new(50.0, 50.0));
        let m = Measures::of_pair(&a, &b, &Appearance::coloured([1.0, 0.0, 0.0]), &Appearance::coloured([0.0; 3]));
        assert!((m.parallelism - (std::f64::consts::FRAC_PI_2 - 0.1)).abs() < 1e-12);
        assert_eq!(m.overlap, 2.0);
        assert_eq!(m.superimposition, 1.0);
        assert_eq!(m.colour, 1.0);
        // Centres are aligned first: the far-away position of b does not matter.
        assert!(m.shape < 10.0);
        let grey = Appearance::coloured([0.5; 3]);
        let same = Measures::of_pair(&a, &a.moved_to(Point::new(9.0, 9.0)), &grey, &grey);
        assert_eq!(
            same,
            Measures { shape: 0.0, parallelism: 0.0, overlap: 1.0, superimposition: 0.0, colour: 0.0, attributes: 0.0 }
        );
    }

    #[test]
    fn violation_is_below_one_exactly_when_the_paper_test_passes() {
        let streams = SeedStreams::new(11);
        let mut random = streams.stream("violation", 0);
        for _ in 0..2000 {
            let v: Normalized = std::array::from_fn(|_| random.random_range(0.0..2.0));
            let pass = |x: f64| x < 1.0;
            let [shape, par, ov, sup, col, attr] = v;
            let paper = pass(col) && pass(attr) && (pass(shape) || (pass(par) && pass(ov) && pass(sup)));
            assert_eq!(violation(&v) < 1.0, paper, "{v:?}");
        }
    }

    #[test]
    fn large_references_compute_measures_on_demand() {
        let frames: Vec<OrientedBox> =
            (0..=MAX_TABLE_ELEMENTS).map(|i| frame(i as f64 * 0.001, 5.0 + (i % 7) as f64, (i % 3) as f64)).collect();
        let appearances: Vec<Appearance> =
            (0..frames.len()).map(|i| Appearance::coloured([(i % 5) as f64 / 5.0, 0.2, 0.4])).collect();
        let limits = Limits::new(&Thresholds::default(), 8.0);
        let table = MeasureTable::new(&frames, &appearances, &limits);
        assert!(table.values.is_empty());
        for (i, j) in [(0, 1), (17, 2048), (2048, 5)] {
            let direct =
                Measures::of_pair(&frames[i], &frames[j], &appearances[i], &appearances[j]).normalized(&limits);
            assert_eq!(table.get(i as u32, j as u32), direct);
        }
    }

    #[test]
    fn table_comparison_equals_the_plain_computation() {
        let streams = SeedStreams::new(5);
        let mut random = streams.stream("table", 0);
        let frames: Vec<OrientedBox> = (0..12)
            .map(|_| {
                frame(random.random_range(0.0..3.0), random.random_range(2.0..20.0), random.random_range(0.0..4.0))
            })
            .collect();
        let appearances: Vec<Appearance> = (0..12)
            .map(|i| {
                let mut appearance = Appearance::coloured(std::array::from_fn(|_| random.random_range(0.0..1.0)));
                appearance.attributes.width = 1.0 + (i % 3) as f64 * 0.1;
                appearance
            })
            .collect();
        let limits = Limits::new(&Thresholds::default(), 10.0);
        let table = MeasureTable::new(&frames, &appearances, &limits);
        let mut scratch = CompareScratch::default();
        for _ in 0..200 {
            let members = |count: usize, random: &mut motif_core::random::Stream| -> Vec<Member> {
                (0..count)
                    .map(|_| Member {
                        element: random.random_range(0..12),
                        offset: Vec2::new(random.random_range(-30.0..30.0), random.random_range(-30.0..30.0)),
                    })
                    .collect()
            };
            let (m, n) = (random.random_range(0..8), random.random_range(0..8));
            let reference = members(m, &mut random);
            let target = members(n, &mut random);
            let fast = compare(&reference, &target, &table, &mut scratch);
            let plain = compare_plain(&reference, &target, &frames, &appearances, &limits);
            match (fast, plain) {
                (Some(f), Some(p)) => assert!(f.iter().zip(&p).all(|(a, b)| (a - b).abs() < 1e-12)),
                (None, None) => assert!(m == 0 || n == 0),
                other => panic!("{other:?}"),
            }
        }
    }
}
