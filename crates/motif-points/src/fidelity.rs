//! Structure fidelity: how closely the output's local point statistics follow the exemplar's.
//!
//! Two figures, both computed on interior points only (points at least `margin` inside their
//! domain) so that the border's missing neighbours do not count as a difference:
//! the total-variation distance between the nearest-neighbour-distance histograms (0 = identical,
//! 1 = disjoint) and the mean absolute difference between the radial distribution functions g(r).

use serde::Serialize;

use crate::grid::StaticGrid;
use crate::linear::{self, Vector};

/// Histogram bins over `[0, 3σ)` for nearest-neighbour distances.
const NN_BINS: usize = 30;
/// RDF bins over `(0, 4σ]`.
const RDF_BINS: usize = 20;

/// Statistics of one point set.
#[derive(Debug, Clone, Serialize)]
pub struct Statistics {
    /// Interior points used.
    pub interior_points: usize,
    /// Mean nearest-neighbour distance of interior points (in units of σ).
    pub mean_nearest: f64,
    /// Normalized histogram of nearest-neighbour distances, bins of 0.1σ from 0.
    pub nearest_histogram: Vec<f64>,
    /// Radial distribution function g(r), bins of 0.2σ from 0.
    pub radial_distribution: Vec<f64>,
}

/// The fidelity figure of a synthesis.
#[derive(Debug, Clone, Serialize)]
pub struct Fidelity {
    /// Total-variation distance between the nearest-neighbour histograms, in [0, 1].
    pub nearest_histogram_distance: f64,
    /// Mean |g_exemplar(r) − g_output(r)| over the RDF bins.
    pub radial_distribution_distance: f64,
    /// Exemplar statistics.
    pub exemplar: Statistics,
    /// Output statistics.
    pub output: Statistics,
}

/// Statistics of `points`; `depth(p)` is the distance of `p` from the border of its domain (the
/// point is interior when it is ≥ `margin`), `volume` the domain's volume.
pub fn statistics<const D: usize>(
    points: &[Vector<D>],
    depth: &dyn Fn(&Vector<D>) -> f64,
    margin: f64,
    volume: f64,
    sigma: f64,
) -> Statistics {
    let r_max = 4.0 * sigma;
    let grid = StaticGrid::new(points, r_max);
    let mut nearest_histogram = vec![0.0; NN_BINS];
    let mut rdf = vec![0.0; RDF_BINS];
    let mut interior = 0usize;
    let mut nearest_sum = 0.0;
    for (i, p) in points.iter().enumerate() {
        if depth(p) < margin {
            continue;
        }
        interior += 1;
        let mut nearest = f64::INFINITY;
        grid.for_each_within(p, r_max, |j, _, d2| {
            if j != i {
                let d = d2.sqrt();
                nearest = nearest.min(d);
                let bin = (d / r_max * RDF_BINS as f64) as usize;
                if bin < RDF_BINS {
                    rdf[bin] += 1.0;
                }
            }
        });
        if nearest.is_finite() {
            nearest_sum += nearest / sigma;
            let bin = (nearest / (3.0 * sigma) * NN_BINS as f64) as usize;
            nearest_histogram[bin.min(NN_BINS - 1)] += 1.0;
        }
    }
    if interior > 0 {
        nearest_histogram.iter_mut().for_each(|h| *h /= interior as f64);
        let density = points.len() as f64 / volume.max(1e-300);
        let unit_ball = if D == 2 { std::f64::consts::PI } else { 4.0 / 3.0 * std::f64::consts::PI };
        for (b, value) in rdf.iter_mut().enumerate() {
            let r0 = b as f64 * r_max / RDF_BINS as f64;
            let r1 = (b + 1) as f64 * r_max / RDF_BINS as f64;
            let shell = unit_ball * (r1.powi(D as i32) - r0.powi(D as i32));
            *value /= interior as f64 * density * shell;
        }
    }
    Statistics {
        interior_points: interior,
        mean_nearest: if interior > 0 { nearest_sum / interior as f64 } else { 0.0 },
        nearest_histogram,
        radial_distribution: rdf,
    }
}

/// Compares two sets of statistics.
pub fn compare(exemplar: Statistics, output: Statistics) -> Fidelity {
    let nearest_histogram_distance =
        0.5 * exemplar.nearest_histogram.iter().zip(&output.nearest_histogram).map(|(a, b)| (a - b).abs()).sum::<f64>();
    let radial_distribution_distance =
        exemplar.radial_distribution.iter().zip(&output.radial_distribution).map(|(a, b)| (a - b).abs()).sum::<f64>()
            / RDF_BINS as f64;
    Fidelity { nearest_histogram_distance, radial_distribution_distance, exemplar, output }
}

/// Depth of `p` inside the box `[low, high]`.
pub fn box_depth<const D: usize>(p: &Vector<D>, low: &Vector<D>, high: &Vector<D>) -> f64 {
    let mut depth = f64::INFINITY;
    for a in 0..D {
        depth = depth.min(p[a] - low[a]).min(high[a] - p[a]);
    }
    depth
}

/// Mean nearest-neighbour distance of a point set (σ of §7.1); 0 for fewer than two points.
pub fn mean_spacing<const D: usize>(points: &[Vector<D>]) -> f64 {
    if points.len() < 2 {
        return 0.0;
    }
    let (low, high) = crate::grid::bounds(points);
    let volume: f64 = (0..D).map(|a| (high[a] - low[a]).max(1e-12)).product();
    // Start from the spacing a uniform set of this size would have, and widen until found.
    let radius = 2.0 * (volume / points.len() as f64).powf(1.0 / D as f64);
    let grid = StaticGrid::new(points, radius);
    let mut total = 0.0;
    for (i, p) in points.iter().enumerate() {
        let mut r = radius;
        loop {
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
            if r > 1e6 * radius {
                break;
            }
        }
    }
    total / points.len() as f64
}
