//! Structure fidelity: how closely the output's point statistics follow the exemplar's, with the two
//! baselines that frame the figures (a uniform random set and a tiled copy of the exemplar over the
//! same domain).
//!
//! All distances are in units of the exemplar's mean nearest-neighbour spacing `s`, so figures from
//! different data sets compare. Border effects are removed by reduced-sample estimators rather than
//! by discarding a fixed margin (which would leave a small exemplar with no interior at all):
//! - **nearest-neighbour distances** count a point only when it lies deeper inside its domain than
//!   its nearest neighbour is far (then that neighbour is certainly its true one); the figure is the
//!   Wasserstein-1 distance between the two distributions, `∫ |F_a(r) − F_b(r)| dr`;
//! - **the radial distribution function** `g(r)` counts, for each ring `[r, r + Δr)`, only the
//!   centres at least `r + Δr` inside the domain; the figure is the mean `|g_a − g_b|` over
//!   `r ∈ [0.5 s, 4 s]` (below half a spacing both are mostly zero and only noise differs).

use motif_core::SeedStreams;
use motif_core::math;
use motif_core::random::Rng;
use serde::Serialize;

use crate::grid::StaticGrid;
use crate::linear::{self, Vector};

/// Width of a g(r) ring and of a nearest-neighbour histogram bin, in spacings.
const BIN: f64 = 0.1;
/// g(r) and the nearest-neighbour histogram cover `[0, 4 s)`.
const RANGE: f64 = 4.0;
/// Points closer than this many spacings belong to one cluster (`Statistics::mean_cluster_size`):
/// a uniform random set has 0.79 neighbours that close on average, far below percolation.
pub(crate) const CLUSTER_LINK: f64 = 1.0;
/// The g(r) distance is taken over `[0.5 s, 4 s)`.
const RDF_FROM: f64 = 0.5;

/// Point statistics of one set, distances in spacings.
#[derive(Debug, Clone, Serialize)]
pub struct Statistics {
    /// Points in the set.
    pub points: usize,
    /// Points whose nearest neighbour counted (deeper than it is far).
    pub nearest_counted: usize,
    /// Mean nearest-neighbour distance of the counted points.
    pub mean_nearest: f64,
    /// Nearest-neighbour distance histogram: bins of 0.1 spacing from 0 to 4, normalized to sum 1.
    pub nearest_histogram: Vec<f64>,
    /// g(r) at ring `b` covering `[0.1 b, 0.1 (b + 1))` spacings, `b < 40` (1 = uncorrelated).
    pub radial_distribution: Vec<f64>,
    /// Centres deep enough to count for each ring (0: the ring's g is unknown, reported as 0).
    pub ring_centres: Vec<usize>,
    /// Mean size of the cluster a point belongs to (`Σ size² / points`), clusters linking points
    /// closer than one spacing (`CLUSTER_LINK`): 1 for points all farther apart, larger for
    /// clustered sets.
    pub mean_cluster_size: f64,
    /// Mean local thickness of a 3D set: the root-mean-square distance of a point and its 12
    /// nearest neighbours from their plane, in spacings (a sheet or shell is thin; a uniform
    /// random set about 1.4); 0 for 2D sets and sets on a surface.
    pub thickness: f64,
    /// Counted nearest-neighbour distances, sorted (for the Wasserstein distance; not reported).
    #[serde(skip)]
    nearest: Vec<f64>,
}

/// Distances of one set's statistics to the exemplar's.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Distances {
    /// Wasserstein-1 distance between the nearest-neighbour distance distributions (spacings).
    pub nearest_neighbour: f64,
    /// Mean `|g_exemplar(r) − g(r)|` over the rings of `[0.5, 4)` spacings that both sets can
    /// estimate (a domain or exemplar too small for the outer rings compares the inner ones).
    pub radial_distribution: f64,
    /// Rings compared for `radial_distribution` (35 when both sets are large enough).
    pub rings_compared: usize,
    /// The set's mean cluster size over the exemplar's (1: clusters of the exemplar's size).
    pub cluster_size_ratio: f64,
    /// The set's mean local thickness over the exemplar's (3D sets; 0 otherwise).
    pub thickness_ratio: f64,
}

/// The fidelity figures of a synthesis.
#[derive(Debug, Clone, Serialize)]
pub struct Fidelity {
    /// The unit of every distance: the exemplar's mean nearest-neighbour spacing (output units).
    pub spacing: f64,
    /// Output points over the count the exemplar's density asks for in the domain.
    pub density_ratio: f64,
    /// The output against the exemplar.
    pub output: Distances,
    /// A uniform random set of the expected count over the same domain, against the exemplar.
    pub random: Distances,
    /// Copies of the exemplar's box tiled over the domain, against the exemplar.
    pub tiled: Distances,
    /// One half of the exemplar against the other (split across its longest side): how far two
    /// samples of the same structure, each half the exemplar's size, already differ. A synthesis
    /// is a new sample, so its distances cannot be expected far below these; the tiled copy's
    /// can, because it holds the exemplar's own pairs.
    pub halves: Distances,
    /// Exemplar statistics.
    pub exemplar_statistics: Statistics,
    /// Output statistics.
    pub output_statistics: Statistics,
}

/// A point set with what its estimators need: where the border is and how dense it is.
pub(crate) struct Sample<'a, const D: usize> {
    /// The points.
    pub points: &'a [Vector<D>],
    /// Distance from a point to the border of the set's domain (≤ 0 outside).
    pub depth: &'a dyn Fn(&Vector<D>) -> f64,
    /// Volume of the domain (its area, for a surface).
    pub volume: f64,
    /// The dimension the volume and rings are measured in: `D`, or 2 for points on a surface.
    pub dimension: usize,
}

/// Statistics of `sample`, distances in units of `spacing`.
pub(crate) fn statistics<const D: usize>(sample: &Sample<'_, D>, spacing: f64) -> Statistics {
    let points = sample.points;
    let bins = (RANGE / BIN).round() as usize;
    let reach = RANGE * spacing;
    let grid = StaticGrid::new(points, reach);
    let mut pair_counts = vec![0.0; bins];
    // centres_beyond[b]: centres deep enough for ring b (depth ≥ its outer radius).
    let mut centres_beyond = vec![0usize; bins + 1];
    let mut nearest = Vec::new();
    let mut histogram = vec![0.0; bins];
    let mut ring_counts = vec![0.0; bins];
    let mut clusters = Clusters::new(points.len());
    for (i, p) in points.iter().enumerate() {
        let depth = (sample.depth)(p) / spacing;
        if depth <= 0.0 {
            continue;
        }
        ring_counts.iter_mut().for_each(|c| *c = 0.0);
        let mut closest = f64::INFINITY;
        grid.for_each_within(p, reach, |j, _, d2| {
            if j != i {
                let r = d2.sqrt() / spacing;
                closest = closest.min(r);
                if r < CLUSTER_LINK {
                    clusters.join(i, j);
                }
                let bin = (r / BIN) as usize;
                if bin < bins {
                    ring_counts[bin] += 1.0;
                }
            }
        });
        // Ring b counts when the centre is at least its outer radius deep.
        let deep_rings = ((depth / BIN).floor() as usize).min(bins);
        centres_beyond[deep_rings] += 1;
        for b in 0..deep_rings {
            pair_counts[b] += ring_counts[b];
        }
        if closest <= depth {
            nearest.push(closest);
            let bin = (closest / BIN) as usize;
            histogram[bin.min(bins - 1)] += 1.0;
        }
    }
    // Centres usable for ring b: those with deep_rings > b.
    let mut usable = vec![0usize; bins];
    let mut running = centres_beyond[bins];
    for b in (0..bins).rev() {
        usable[b] = running;
        running += centres_beyond[b];
    }
    let dimension = sample.dimension as i32;
    let density = points.len() as f64 / sample.volume.max(1e-300) * spacing.powi(dimension);
    let unit_ball = if dimension == 2 { std::f64::consts::PI } else { 4.0 / 3.0 * std::f64::consts::PI };
    let radial_distribution = (0..bins)
        .map(|b| {
            let (r0, r1) = (b as f64 * BIN, (b + 1) as f64 * BIN);
            let shell = unit_ball * (r1.powi(dimension) - r0.powi(dimension));
            if usable[b] == 0 { 0.0 } else { pair_counts[b] / (usable[b] as f64 * density * shell) }
        })
        .collect();
    nearest.sort_by(f64::total_cmp);
    let counted = nearest.len();
    if counted > 0 {
        histogram.iter_mut().for_each(|h| *h /= counted as f64);
    }
    Statistics {
        points: points.len(),
        nearest_counted: counted,
        mean_nearest: if counted > 0 { nearest.iter().sum::<f64>() / counted as f64 } else { 0.0 },
        nearest_histogram: histogram,
        radial_distribution,
        ring_centres: usable,
        mean_cluster_size: clusters.mean_size(),
        thickness: if sample.dimension == 3 { crate::thickness::mean_thickness(points, spacing) } else { 0.0 },
        nearest,
    }
}

/// Union-find over point indices: the clusters of `Statistics::mean_cluster_size`.
struct Clusters {
    parent: Vec<usize>,
}

impl Clusters {
    fn new(n: usize) -> Self {
        Self { parent: (0..n).collect() }
    }

    fn root(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    fn join(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.root(a), self.root(b));
        if ra != rb {
            self.parent[ra.max(rb)] = ra.min(rb);
        }
    }

    /// `Σ size² / n` (1 for an empty set).
    fn mean_size(&mut self) -> f64 {
        let n = self.parent.len();
        let mut sizes = vec![0usize; n];
        (0..n).for_each(|i| sizes[self.root(i)] += 1);
        if n == 0 { 1.0 } else { sizes.iter().map(|&s| (s * s) as f64).sum::<f64>() / n as f64 }
    }
}

/// Distances of `other` to `reference`.
pub(crate) fn distances(reference: &Statistics, other: &Statistics) -> Distances {
    let from = (RDF_FROM / BIN).round() as usize;
    let rings: Vec<usize> = (from..reference.radial_distribution.len())
        .filter(|&b| reference.ring_centres[b] > 0 && other.ring_centres[b] > 0)
        .collect();
    let total: f64 =
        rings.iter().map(|&b| (reference.radial_distribution[b] - other.radial_distribution[b]).abs()).sum();
    Distances {
        nearest_neighbour: wasserstein(&reference.nearest, &other.nearest),
        radial_distribution: if rings.is_empty() { 0.0 } else { total / rings.len() as f64 },
        rings_compared: rings.len(),
        cluster_size_ratio: other.mean_cluster_size / reference.mean_cluster_size.max(1e-300),
        thickness_ratio: if reference.thickness > 0.0 { other.thickness / reference.thickness } else { 0.0 },
    }
}

/// `∫ |F_a − F_b|` of two sorted samples; the largest possible distance (the range) when one is
/// empty and the other is not.
fn wasserstein(a: &[f64], b: &[f64]) -> f64 {
    match (a.is_empty(), b.is_empty()) {
        (true, true) => return 0.0,
        (true, false) | (false, true) => return RANGE,
        _ => {}
    }
    let (mut i, mut j) = (0, 0);
    let mut last = a[0].min(b[0]);
    let mut total = 0.0;
    while i < a.len() || j < b.len() {
        let next = match (a.get(i), b.get(j)) {
            (Some(&x), Some(&y)) => x.min(y),
            (Some(&x), None) => x,
            (None, Some(&y)) => y,
            (None, None) => break,
        };
        let fa = i as f64 / a.len() as f64;
        let fb = j as f64 / b.len() as f64;
        total += (fa - fb).abs() * (next - last);
        last = next;
        while a.get(i).is_some_and(|&x| x <= next) {
            i += 1;
        }
        while b.get(j).is_some_and(|&y| y <= next) {
            j += 1;
        }
    }
    total
}

/// The domain of a comparison: membership, depth, bounds and volume.
pub(crate) struct Domain<'a, const D: usize> {
    /// Whether a point is inside.
    pub contains: &'a dyn Fn(&Vector<D>) -> bool,
    /// Distance to the border from inside.
    pub depth: &'a dyn Fn(&Vector<D>) -> f64,
    /// Bounding box.
    pub low: Vector<D>,
    /// Bounding box.
    pub high: Vector<D>,
    /// Volume (area, for a surface).
    pub volume: f64,
    /// The dimension the volume is measured in: `D`, or 2 for a surface (whose exemplar lies in
    /// the plane of the first two axes).
    pub dimension: usize,
    /// Uniform points of a surface from three uniform numbers (rejection from the bounding box
    /// cannot hit a surface).
    pub sample: Option<&'a dyn Fn(f64, f64, f64) -> Vector<D>>,
    /// Where the tiled baseline is laid when not over the domain itself: a curved surface cannot
    /// be tiled, so its baseline tiles a square of the same area.
    pub tiling: Option<&'a Domain<'a, D>>,
}

/// The exemplar's window: its bounding box padded by half a spacing on every side, so that each
/// point owns a spacing-sized cell (a 14 × 14 grid of spacing 1 has density 1, not 196/169).
pub(crate) fn exemplar_window<const D: usize>(points: &[Vector<D>], spacing: f64) -> (Vector<D>, Vector<D>) {
    let (low, high) = crate::grid::bounds(points);
    (std::array::from_fn(|a| low[a] - 0.5 * spacing), std::array::from_fn(|a| high[a] + 0.5 * spacing))
}

/// Compares `output` over `domain` with `exemplar` observed in `window` (lower and upper
/// corners, see [`exemplar_window`] for a default), and computes both baselines (seeded).
pub(crate) fn compare<const D: usize>(
    exemplar: &[Vector<D>],
    window: &(Vector<D>, Vector<D>),
    output: &[Vector<D>],
    domain: &Domain<'_, D>,
    spacing: f64,
    seed: u64,
) -> Fidelity {
    let (low, high) = *window;
    let dimension = domain.dimension;
    let window_volume: f64 = (0..dimension).map(|a| high[a] - low[a]).product();
    let window_depth = |p: &Vector<D>| box_depth(p, &low, &high, dimension);
    let exemplar_statistics =
        statistics(&Sample { points: exemplar, depth: &window_depth, volume: window_volume, dimension }, spacing);
    let on_domain = |points: &[Vector<D>]| {
        statistics(&Sample { points, depth: domain.depth, volume: domain.volume, dimension }, spacing)
    };
    let output_statistics = on_domain(output);
    let expected = exemplar.len() as f64 / window_volume * domain.volume;
    let random = random_set(domain, expected.round() as usize, seed);
    let tiled = match domain.tiling {
        Some(tiling) => {
            let tiled = tiled_copy(exemplar, &low, &high, tiling);
            statistics(&Sample { points: &tiled, depth: tiling.depth, volume: tiling.volume, dimension }, spacing)
        }
        None => on_domain(&tiled_copy(exemplar, &low, &high, domain)),
    };
    Fidelity {
        spacing,
        halves: halves(exemplar, &low, &high, spacing, dimension),
        density_ratio: output.len() as f64 / expected.max(1e-300),
        output: distances(&exemplar_statistics, &output_statistics),
        random: distances(&exemplar_statistics, &on_domain(&random)),
        tiled: distances(&exemplar_statistics, &tiled),
        exemplar_statistics,
        output_statistics,
    }
}

/// The distances between the two halves of the exemplar window, split across its longest side.
fn halves<const D: usize>(
    exemplar: &[Vector<D>],
    low: &Vector<D>,
    high: &Vector<D>,
    spacing: f64,
    dimension: usize,
) -> Distances {
    let axis = (0..dimension).max_by(|&a, &b| (high[a] - low[a]).total_cmp(&(high[b] - low[b]))).unwrap_or(0);
    let middle = 0.5 * (low[axis] + high[axis]);
    let half_statistics = |first: bool| {
        let (mut lo, mut hi) = (*low, *high);
        if first {
            hi[axis] = middle;
        } else {
            lo[axis] = middle;
        }
        let points: Vec<Vector<D>> = exemplar.iter().copied().filter(|p| (p[axis] < middle) == first).collect();
        let volume: f64 = (0..dimension).map(|a| hi[a] - lo[a]).product();
        let depth = |p: &Vector<D>| box_depth(p, &lo, &hi, dimension);
        statistics(&Sample { points: &points, depth: &depth, volume, dimension }, spacing)
    };
    distances(&half_statistics(true), &half_statistics(false))
}

/// `count` uniform points in the domain (rejection from its bounding box, bounded tries).
pub(crate) fn random_set<const D: usize>(domain: &Domain<'_, D>, count: usize, seed: u64) -> Vec<Vector<D>> {
    let mut stream = SeedStreams::new(seed).stream("fidelity random baseline", 0);
    let mut points = Vec::with_capacity(count);
    let mut tries = 0usize;
    if let Some(sample) = domain.sample {
        return (0..count).map(|_| sample(stream.random(), stream.random(), stream.random())).collect();
    }
    while points.len() < count && tries < 1000 * count.max(1) {
        tries += 1;
        let p: Vector<D> =
            std::array::from_fn(|a| domain.low[a] + stream.random::<f64>() * (domain.high[a] - domain.low[a]));
        if (domain.contains)(&p) {
            points.push(p);
        }
    }
    points
}

/// Copies of the exemplar window `[low, high]` laid edge to edge from the domain's lower corner,
/// kept where they fall inside the domain.
pub(crate) fn tiled_copy<const D: usize>(
    exemplar: &[Vector<D>],
    low: &Vector<D>,
    high: &Vector<D>,
    domain: &Domain<'_, D>,
) -> Vec<Vector<D>> {
    let size: Vector<D> = std::array::from_fn(|a| high[a] - low[a]);
    let counts: [usize; D] =
        std::array::from_fn(|a| ((domain.high[a] - domain.low[a]) / size[a]).ceil().clamp(1.0, 1e4) as usize);
    let tiles: usize = counts.iter().product();
    let mut points = Vec::new();
    for t in 0..tiles {
        let mut rest = t;
        let offset: Vector<D> = std::array::from_fn(|a| {
            let index = rest % counts[a];
            rest /= counts[a];
            domain.low[a] + index as f64 * size[a] - low[a]
        });
        for e in exemplar {
            let p = linear::add(e, &offset);
            if (domain.contains)(&p) {
                points.push(p);
            }
        }
    }
    points
}

/// Depth of `p` inside the box `[low, high]`, over its first `dimension` axes.
pub(crate) fn box_depth<const D: usize>(p: &Vector<D>, low: &Vector<D>, high: &Vector<D>, dimension: usize) -> f64 {
    let mut depth = f64::INFINITY;
    for a in 0..dimension {
        depth = depth.min(p[a] - low[a]).min(high[a] - p[a]);
    }
    depth
}

/// Mean nearest-neighbour distance of a point set (σ of §7.1); 0 for fewer than two points.
pub(crate) fn mean_spacing<const D: usize>(points: &[Vector<D>]) -> f64 {
    if points.len() < 2 {
        return 0.0;
    }
    let (low, high) = crate::grid::bounds(points);
    // Over the axes the set spans: a flat set in 3D (a 2D exemplar lifted onto a surface) has no
    // volume, and a start radius from it made a grid of millions of empty cells.
    let extents: Vec<f64> = (0..D).map(|a| high[a] - low[a]).filter(|extent| *extent > 0.0).collect();
    let volume: f64 = extents.iter().product::<f64>().max(1e-12);
    // Start from the spacing a uniform set of this size would have, and widen until found (the
    // start changes the work, never the nearest distances found).
    let radius = 2.0 * math::powf(volume / points.len() as f64, 1.0 / extents.len().max(1) as f64);
    let grid = StaticGrid::new(points, radius);
    let mut total = 0.0;
    for (i, p) in points.iter().enumerate() {
        // Twenty doublings reach a million times the start: a bounded count, so that a radius or
        // a distance that overflows to infinity cannot keep the search going.
        let mut r = radius;
        for _ in 0..20 {
            let mut nearest = f64::INFINITY;
            grid.for_each_within(p, r, |j, q, _| {
                if j != i {
                    nearest = nearest.min(linear::norm2(&linear::sub(p, q)));
                }
            });
            if nearest.is_finite() {
                total += nearest.sqrt();
                break;
            }
            r *= 2.0;
        }
    }
    total / points.len() as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wasserstein_of_shifted_samples_is_the_shift() {
        let a = [1.0, 2.0, 3.0];
        let b = [1.5, 2.5, 3.5];
        assert!((wasserstein(&a, &b) - 0.5).abs() < 1e-12);
        assert_eq!(wasserstein(&a, &a), 0.0);
        assert!((wasserstein(&[1.0], &[1.0, 3.0]) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn mean_spacing_ends_on_a_set_whose_extent_overflows() {
        // The area of this set overflows, so the search radius is infinite; it looped forever.
        let points = [[0.0, 0.0], [1.0, 0.0], [1e200, -1e200]];
        assert!(mean_spacing(&points).is_finite());
        let far = [[0.0, 0.0], [1e308, -1e308], [-1e308, 1e308]];
        mean_spacing(&far);
    }

    #[test]
    fn a_flat_set_in_3d_has_the_spacing_of_its_plane() {
        let plane = uniform(300, 20.0, 4);
        let lifted: Vec<Vector<3>> = plane.iter().map(|p| [p[0], p[1], 0.0]).collect();
        // The same distances (the memory its search took is `tests/memory.rs`'s surface case).
        assert_eq!(mean_spacing(&lifted), mean_spacing(&plane));
    }

    fn uniform(count: usize, side: f64, seed: u64) -> Vec<Vector<2>> {
        let mut stream = SeedStreams::new(seed).stream("test", 0);
        (0..count).map(|_| [stream.random::<f64>() * side, stream.random::<f64>() * side]).collect()
    }

    #[test]
    fn uniform_points_have_flat_g_and_lattices_do_not() {
        let side = 60.0;
        let low = [0.0, 0.0];
        let high = [side, side];
        let depth = |p: &Vector<2>| box_depth(p, &low, &high, 2);
        let random = uniform(3600, side, 3);
        let spacing = mean_spacing(&random);
        let s = statistics(&Sample { points: &random, depth: &depth, volume: side * side, dimension: 2 }, spacing);
        let tail: Vec<f64> = s.radial_distribution[10..].to_vec();
        let mean = tail.iter().sum::<f64>() / tail.len() as f64;
        assert!((mean - 1.0).abs() < 0.05, "g of a uniform set averages {mean}");
        // A square lattice has no pair closer than its period: g is 0 below it.
        let lattice: Vec<Vector<2>> = (0..3600).map(|i| [(i % 60) as f64 + 0.5, (i / 60) as f64 + 0.5]).collect();
        let l = statistics(&Sample { points: &lattice, depth: &depth, volume: side * side, dimension: 2 }, 1.0);
        assert!(l.radial_distribution[..9].iter().all(|&g| g == 0.0));
        assert!(l.radial_distribution[10] > 3.0);
        assert!((l.mean_nearest - 1.0).abs() < 1e-9);
        // The distance of a uniform set to the lattice is large, of the lattice to itself zero.
        assert_eq!(distances(&l, &l).radial_distribution, 0.0);
        let u = statistics(&Sample { points: &random, depth: &depth, volume: side * side, dimension: 2 }, 1.0);
        assert!(distances(&l, &u).radial_distribution > 0.3);
    }

    #[test]
    fn tiled_copy_of_a_lattice_matches_it_and_random_does_not() {
        let lattice: Vec<Vector<2>> = (0..400).map(|i| [(i % 20) as f64 + 0.5, (i / 20) as f64 + 0.5]).collect();
        let (low, high) = ([0.0, 0.0], [50.0, 50.0]);
        let contains = |p: &Vector<2>| (0..2).all(|a| p[a] >= low[a] && p[a] < high[a]);
        let depth = |p: &Vector<2>| box_depth(p, &low, &high, 2);
        let domain = Domain {
            contains: &contains,
            depth: &depth,
            low,
            high,
            volume: 2500.0,
            dimension: 2,
            sample: None,
            tiling: None,
        };
        let fidelity = compare(&lattice, &exemplar_window(&lattice, 1.0), &lattice, &domain, 1.0, 7);
        assert!(fidelity.tiled.radial_distribution < 0.05, "{:?}", fidelity.tiled);
        assert!(fidelity.tiled.nearest_neighbour < 1e-9);
        assert!(fidelity.random.radial_distribution > 0.3);
        assert!(fidelity.random.nearest_neighbour > 0.3);
        // 400 points in a 20 × 20 window ask for 2 500 in the domain.
        assert!((fidelity.density_ratio - 400.0 / 2500.0).abs() < 1e-9);
    }
}
