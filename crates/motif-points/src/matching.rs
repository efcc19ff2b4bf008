//! The local step of Algorithm 1 (§5.1): for every quadrature point `q_k`, the exemplar location
//! `m_k` whose neighbourhood best matches the output around `q_k`.
//!
//! `∂T/∂m_k = ∂S_k/∂m_k`, so quadrature points are matched independently, in parallel, each with
//! its own random stream keyed by (iteration, k). Following the paper, gradient descent runs from
//! five random starts. The descent of the starts uses a rasterized form of `S_k` (the exemplar
//! function `e` smoothed by the σ-Gaussian and the exemplar self-term, both sampled on grids, and
//! the window weight taken at the output point) which costs a few lookups per window point; the
//! winner is then compared with the previous match on the exact `S_k` and polished by exact
//! gradient descent (∂S/∂m of [`crate::energy`]). Keeping the previous match when it is better
//! makes the step never raise T.

use motif_core::SeedStreams;
use motif_core::math;
use motif_core::random::Rng;
use rayon::prelude::*;

use crate::energy::Problem;
use crate::grid::StaticGrid;
use crate::linear::{self, Vector};
use crate::model::{State, feature_dot};
use crate::params::Window;
use crate::raster::Raster;

/// Matching settings.
#[derive(Debug, Clone, Copy)]
pub(crate) struct MatchSettings {
    pub starts: usize,
    pub iterations: usize,
    pub polish: usize,
}

/// Rasters of the exemplar used by the candidate search at one window size.
pub(crate) struct SearchFields<const D: usize> {
    /// `ẽ(y) = Σ_j b_j exp(−|y − e_j|²/2σ²)`, `channels` components.
    smoothed: Raster<D>,
    /// `C(m)` for the identity frame.
    exemplar_self: Raster<D>,
    channels: usize,
}

impl<const D: usize> SearchFields<D> {
    pub(crate) fn new(problem: &Problem<'_, D>) -> Self {
        let exemplar = problem.exemplar;
        let sigma = problem.kernel.sigma;
        let channels = exemplar.channels;
        let margin = problem.kernel.cutoff;
        let low = std::array::from_fn(|a| exemplar.low[a] - margin);
        let high = std::array::from_fn(|a| exemplar.high[a] + margin);
        let fine = if D == 2 { 0.25 * sigma } else { 0.4 * sigma };
        let cutoff = problem.kernel.cutoff;
        let inv = 0.5 / (sigma * sigma);
        let smoothed = Raster::new(low, high, fine, channels, |y, out| {
            problem.exemplar_grid.for_each_within(y, cutoff, |j, _, d2| {
                let g = math::exp(-d2 * inv);
                for (o, b) in out.iter_mut().zip(exemplar.feature(j)) {
                    *o += b * g;
                }
            });
        });
        let exemplar_self = Self::exemplar_self_raster(problem);
        Self { smoothed, exemplar_self, channels }
    }

    /// Rebuilds the part that depends on the window size (the smoothed exemplar does not).
    pub(crate) fn set_window(&mut self, problem: &Problem<'_, D>) {
        self.exemplar_self = Self::exemplar_self_raster(problem);
    }

    /// `C(m)` varies on the window's scale, so a raster of spacing δ'/2 resolves it.
    fn exemplar_self_raster(problem: &Problem<'_, D>) -> Raster<D> {
        let exemplar = problem.exemplar;
        let kernel = &problem.kernel;
        let identity = linear::identity::<D>();
        let delta_prime = (kernel.delta * kernel.delta + 0.5 * kernel.sigma * kernel.sigma).sqrt();
        Raster::new(exemplar.low, exemplar.high, 0.5 * delta_prime, 1, |m, out| {
            out[0] = problem.exemplar_self_with(&identity, 1.0, m, None, None);
        })
    }
}

/// The box that matches are kept in: the exemplar shrunk by the window's width δ (where the
/// Gaussian window's weight is e⁻¹), and by at most a quarter of its extent on each side.
///
/// Shrinking by the whole reach of the window (2δ), or by up to 45 % of the extent, left a small
/// real exemplar (71 pines, δ = 4 spacings) a 10 × 10 box of admissible matches out of 96 × 100:
/// every output window matched nearly the same exemplar window and the output crystallized into
/// a repetition of it (nearest-neighbour distance 0.36 against a random set's 0.20; 0.16 now).
fn admissible<const D: usize>(problem: &Problem<'_, D>, k: usize) -> (Vector<D>, Vector<D>) {
    let exemplar = problem.exemplar;
    let reach = problem.kernel.delta / problem.quadrature.scale[k];
    let mut low = [0.0; D];
    let mut high = [0.0; D];
    for a in 0..D {
        let extent = exemplar.high[a] - exemplar.low[a];
        let margin = reach.min(0.25 * extent);
        low[a] = exemplar.low[a] + margin;
        high[a] = exemplar.high[a] - margin;
    }
    (low, high)
}

fn clamp<const D: usize>(m: &Vector<D>, low: &Vector<D>, high: &Vector<D>) -> Vector<D> {
    std::array::from_fn(|a| m[a].clamp(low[a], high[a]))
}

/// The result of matching: `m_k` and the exact `C_k(m_k)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Match<const D: usize> {
    pub location: Vector<D>,
    pub exemplar_self: f64,
}

/// Matches every quadrature point. `previous` holds the last matches (empty on the first call).
pub(crate) fn match_all<const D: usize>(
    problem: &Problem<'_, D>,
    fields: &SearchFields<D>,
    state: &State<D>,
    previous: &[Vector<D>],
    settings: MatchSettings,
    streams: &SeedStreams,
) -> Vec<Match<D>> {
    let matcher = Matcher {
        problem,
        fields,
        state,
        grid: StaticGrid::new(&state.positions, problem.kernel.gather),
        settings,
        streams,
    };
    let quadrature = problem.quadrature;
    (0..quadrature.len())
        .into_par_iter()
        .map(|k| {
            // Propagation (as in PatchMatch, but from the last matches so that the order of work
            // does not matter): a neighbour matched at m' suggests m' shifted by the offset between
            // the two quadrature points, which keeps whole patches of the output matched coherently.
            let mut guesses: Vec<Vector<D>> = Vec::new();
            if !previous.is_empty() {
                let q = quadrature.points[k];
                quadrature.for_each_within(&q, 1.01 * quadrature.spacing(), |n| {
                    if n != k {
                        let offset = linear::mat_vec(&quadrature.inverse[k], &linear::sub(&q, &quadrature.points[n]));
                        guesses.push(linear::add(&previous[n], &offset));
                    }
                });
            }
            matcher.match_one(k, previous.get(k), &guesses)
        })
        .collect()
}

/// How many window offsets ahead the search's loop asks for the raster's nodes.
const PREFETCH_AHEAD: usize = 4;

/// What matching every quadrature point reads (shared by the parallel workers).
struct Matcher<'a, 'p, const D: usize> {
    problem: &'a Problem<'p, D>,
    fields: &'a SearchFields<D>,
    state: &'a State<D>,
    /// The output points, gathered into each quadrature point's window.
    grid: StaticGrid<D>,
    settings: MatchSettings,
    streams: &'a SeedStreams,
}

/// One quadrature point's search: its index, its output window and the box of admissible matches.
struct Search<'w, const D: usize> {
    k: usize,
    window: &'w [(Vector<D>, u32)],
    low: Vector<D>,
    high: Vector<D>,
}

impl<const D: usize> Matcher<'_, '_, D> {
    /// Matches quadrature point `k`: a search on the rasterized `S_k` from random starts and the
    /// informed guesses, then the exact selection and polish.
    fn match_one(&self, k: usize, previous: Option<&Vector<D>>, guesses: &[Vector<D>]) -> Match<D> {
        let window = self.problem.output_window(k, &self.grid);
        let (low, high) = admissible(self.problem, k);
        let search = Search { k, window: &window, low, high };
        let candidate = self.search(&search, previous, guesses);
        self.select(&search, candidate, previous)
    }

    /// The window points that carry weight in the search objective: their exemplar offsets and
    /// their features times the window weight, `channels` per point.
    fn weighted_window(&self, search: &Search<'_, D>) -> (Vec<Vector<D>>, Vec<f64>) {
        let kernel = &self.problem.kernel;
        let inverse = &self.problem.quadrature.inverse[search.k];
        let delta_prime2 = kernel.delta * kernel.delta + 0.5 * kernel.sigma * kernel.sigma;
        let mut offsets: Vec<Vector<D>> = Vec::new();
        let mut weights: Vec<f64> = Vec::new();
        for (u, i) in search.window {
            let r2 = linear::norm2(u);
            let w = match kernel.window {
                Window::Gaussian if r2 < 9.0 * kernel.delta * kernel.delta => math::exp(-r2 / delta_prime2),
                Window::Box if r2 < kernel.delta * kernel.delta => 1.0,
                _ => 0.0,
            };
            if w > 0.1 {
                offsets.push(linear::mat_vec(inverse, u));
                weights.extend(self.state.feature(*i as usize).iter().map(|a| a * w));
            }
        }
        (offsets, weights)
    }

    /// Gradient descent on the rasterized `S_k` from `starts` random starts, plus one from the
    /// best of the previous match and the neighbours' propagated matches (keeps coherence between
    /// iterations); returns the best place found.
    fn search(&self, search: &Search<'_, D>, previous: Option<&Vector<D>>, guesses: &[Vector<D>]) -> Vector<D> {
        let (fields, settings) = (self.fields, self.settings);
        let (low, high) = (&search.low, &search.high);
        let channels = fields.channels;
        let (offsets, weights) = self.weighted_window(search);
        let mut sample = vec![0.0; channels];
        let mut sample_gradient = vec![[0.0; D]; channels];
        let mut objective = |m: &Vector<D>, gradient: &mut Vector<D>| -> f64 {
            let mut one = [0.0];
            let mut one_gradient = [[0.0; D]];
            fields.exemplar_self.sample(m, &mut one, &mut one_gradient);
            let mut value = one[0];
            *gradient = one_gradient[0];
            for (o, offset) in offsets.iter().enumerate() {
                if let Some(ahead) = offsets.get(o + PREFETCH_AHEAD) {
                    fields.smoothed.prefetch(&linear::add(m, ahead));
                }
                let y = linear::add(m, offset);
                fields.smoothed.sample(&y, &mut sample, &mut sample_gradient);
                let w = &weights[o * channels..(o + 1) * channels];
                value -= 2.0 * feature_dot(w, &sample);
                for c in 0..channels {
                    linear::axpy(gradient, -2.0 * w[c], &sample_gradient[c]);
                }
            }
            value
        };
        let sigma = self.problem.kernel.sigma;
        let mut stream = self.streams.stream("matching", search.k as u64);
        let mut best: Option<(f64, Vector<D>)> = None;
        let mut informed: Option<(f64, Vector<D>)> = None;
        let mut scratch = [0.0; D];
        for guess in previous.into_iter().chain(guesses) {
            let m = clamp(guess, low, high);
            let value = objective(&m, &mut scratch);
            if informed.is_none_or(|(v, _)| value < v) {
                informed = Some((value, m));
            }
        }
        let extra = usize::from(informed.is_some());
        for start in 0..settings.starts + extra {
            let mut m: Vector<D> = std::array::from_fn(|a| low[a] + stream.random::<f64>() * (high[a] - low[a]));
            if start == settings.starts
                && let Some((_, guess)) = informed
            {
                m = guess;
            }
            let mut gradient = [0.0; D];
            let mut value = objective(&m, &mut gradient);
            let mut step = 0.5 * sigma;
            for _ in 0..settings.iterations {
                let norm = linear::norm2(&gradient).sqrt();
                if norm == 0.0 || step < 1e-3 * sigma {
                    break;
                }
                let trial = clamp(&linear::add(&m, &linear::scale(&gradient, -step / norm)), low, high);
                let mut trial_gradient = [0.0; D];
                let trial_value = objective(&trial, &mut trial_gradient);
                if trial_value < value {
                    m = trial;
                    value = trial_value;
                    gradient = trial_gradient;
                    step *= 1.5;
                } else {
                    step *= 0.4;
                }
            }
            if best.is_none_or(|(v, _)| value < v) {
                best = Some((value, m));
            }
        }
        best.map(|b| b.1).unwrap_or_else(|| clamp(low, low, high))
    }

    /// Exact selection: the searched candidate against the previous match on the exact `S_k`,
    /// the better polished by exact gradient descent.
    fn select(&self, search: &Search<'_, D>, candidate: Vector<D>, previous: Option<&Vector<D>>) -> Match<D> {
        let (problem, state, k, window) = (self.problem, self.state, search.k, search.window);
        let (low, high) = (&search.low, &search.high);
        let sigma = problem.kernel.sigma;
        let mut gradient = [0.0; D];
        let mut m = candidate;
        let (mut c, cross) = problem.match_parts(k, &m, window, state, Some(&mut gradient));
        let mut value = c + cross;
        if let Some(p) = previous {
            let mut previous_gradient = [0.0; D];
            let (previous_c, previous_cross) = problem.match_parts(k, p, window, state, Some(&mut previous_gradient));
            if previous_c + previous_cross <= value {
                m = *p;
                value = previous_c + previous_cross;
                c = previous_c;
                gradient = previous_gradient;
            }
        }
        let mut step = 0.25 * sigma;
        for _ in 0..self.settings.polish {
            let norm = linear::norm2(&gradient).sqrt();
            if norm == 0.0 {
                break;
            }
            let trial = clamp(&linear::add(&m, &linear::scale(&gradient, -step / norm)), low, high);
            let mut trial_gradient = [0.0; D];
            let (trial_c, trial_cross) = problem.match_parts(k, &trial, window, state, Some(&mut trial_gradient));
            if trial_c + trial_cross < value {
                m = trial;
                value = trial_c + trial_cross;
                c = trial_c;
                gradient = trial_gradient;
                step *= 1.5;
            } else {
                step *= 0.4;
            }
        }
        Match { location: m, exemplar_self: c }
    }
}
