//! Sampling control (§5.1, Eq. 7): add points where the output lacks density, remove them where it
//! has too much, each change kept only if T decreases — within count bounds around the exemplar's
//! density ([`CountBounds`]): outside them a change goes the bound's way even if T rises, and no
//! change leaves them.
//!
//! `P_k = ∫ (f(q_k + s) − e(m_k + s)) w(s) ds` with all attributes set to 1. For the Gaussian window
//! it is `Σ_i g(u_i, σ_P) − Σ_j g(v_j, σ_P)` with `σ_P² = σ² + δ²` (the constant factor dropped),
//! so one point at `q_k` adds 1; for the box window it counts points inside δ. Quadrature points are
//! visited from the largest deficit (excess) down; `P` is updated after every accepted change so a
//! region is not filled twice. A proposal copies the exemplar point (or element) of the matched
//! neighbourhood that is farthest from any output point, placed by the match's frame, then takes a
//! few gradient steps; the change in T is computed exactly from the terms that hold the unit.

use motif_core::math;
use rayon::prelude::*;

use crate::energy::Problem;
use crate::grid::{DynamicGrid, StaticGrid};
use crate::linear::{self, Vector};
use crate::model::{Exemplar, Rigid, State, feature_dot};

/// What one sampling-control pass did.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct SamplingOutcome {
    pub added: usize,
    pub removed: usize,
    pub rejected: usize,
    /// Changes T accepted but the count bounds refused.
    pub held_by_bound: usize,
}

/// The least and the most points sampling control may leave (T alone can prefer an emptier
/// output: an empty window matches an empty part of a clustered exemplar at no cost, and every
/// removal then makes the next matching choose emptier parts).
#[derive(Debug, Clone, Copy)]
pub(crate) struct CountBounds {
    pub least: usize,
    pub most: usize,
}

struct Pass<'a, 'p, const D: usize> {
    problem: &'a Problem<'p, D>,
    matches: &'a [Vector<D>],
    grid: DynamicGrid<D>,
    density: Vec<f64>,
    width: Option<f64>,
    allowed: &'a dyn Fn(&Vector<D>) -> bool,
    /// Points that sampling control may remove (alive and not frozen) now.
    alive: usize,
    bounds: CountBounds,
}

/// The sampling error density `P_k` of every quadrature point.
pub(crate) fn sampling_density<const D: usize>(
    problem: &Problem<'_, D>,
    state: &State<D>,
    matches: &[Vector<D>],
) -> Vec<f64> {
    let width = problem.kernel.density_width();
    let reach = width.map_or(problem.kernel.delta, |w| 3.0 * w);
    let grid = StaticGrid::new(&state.positions, reach);
    let quadrature = problem.quadrature;
    (0..quadrature.len())
        .into_par_iter()
        .map(|k| {
            let q = quadrature.points[k];
            let mut p = 0.0;
            let m = matches[k];
            grid.for_each_within(&q, reach, |i, x, d2| {
                if state.alive[i] && seen_by_exemplar(problem, k, &m, x) {
                    p += weight(width, d2);
                }
            });
            let s = quadrature.scale[k];
            let transform = &quadrature.transform[k];
            problem.exemplar_grid.for_each_within(&m, reach / s, |_, e, d2| {
                if quadrature.inside(&linear::add(&q, &linear::mat_vec(transform, &linear::sub(e, &m)))) {
                    p -= weight(width, d2 * s * s);
                }
            });
            p
        })
        .collect()
}

/// Whether output place `x` has its counterpart inside the exemplar's observation window under
/// quadrature point `k`'s match `m`: the exemplar shows nothing beyond its window, so `P` counts
/// only the output points whose counterparts it could have shown (as it counts only the exemplar
/// points whose images lie inside Ω). Counting them all made every window matched near the
/// exemplar's border look too full.
fn seen_by_exemplar<const D: usize>(problem: &Problem<'_, D>, k: usize, m: &Vector<D>, x: &Vector<D>) -> bool {
    let quadrature = problem.quadrature;
    let offset = linear::mat_vec(&quadrature.inverse[k], &linear::sub(x, &quadrature.points[k]));
    let exemplar = problem.exemplar;
    (0..D).all(|a| {
        let e = m[a] + offset[a];
        e >= exemplar.window_low[a] && e <= exemplar.window_high[a]
    })
}

#[inline]
fn weight(width: Option<f64>, d2: f64) -> f64 {
    match width {
        Some(w) => math::exp(-d2 / (w * w)),
        None => 1.0,
    }
}

/// The threshold on `|P_k|` at every quadrature point: `threshold` peak contributions, or
/// `threshold` times the standard deviation that `P` has on a uniform random set of the
/// exemplar's density, when that is larger. A window of δ = 4 spacings weighs ~50 points and its
/// `P` fluctuates by several points on any sample; with the plain threshold almost every
/// quadrature point proposed a change (a traced contour, δ = 35σ, spent 50 of 62 s on rejected
/// proposals).
fn thresholds<const D: usize>(problem: &Problem<'_, D>, exemplar: &Exemplar<D>, threshold: f64) -> Vec<f64> {
    let quadrature = problem.quadrature;
    let density = exemplar.density();
    let spread = match problem.kernel.density_width() {
        // Σ g(u)² over a Poisson set: ρ ∫ exp(−2|u|²/w²) du = ρ (π w²/2)^(D/2).
        Some(w) => math::powf(std::f64::consts::PI * w * w / 2.0, D as f64 / 2.0),
        // Points counted inside δ: ρ times the ball's volume.
        None => {
            let unit_ball = if D == 2 { std::f64::consts::PI } else { 4.0 / 3.0 * std::f64::consts::PI };
            unit_ball * problem.kernel.delta.powi(D as i32)
        }
    };
    (0..quadrature.len())
        .map(|k| {
            let output_density = density / quadrature.density_scale(k);
            threshold * (output_density * spread).sqrt().max(1.0)
        })
        .collect()
}

/// One sampling-control pass over all quadrature points. Compacts `state` at the end.
pub(crate) fn control<const D: usize>(
    problem: &Problem<'_, D>,
    exemplar: &Exemplar<D>,
    state: &mut State<D>,
    matches: &[Vector<D>],
    threshold: f64,
    bounds: CountBounds,
    allowed: &dyn Fn(&Vector<D>) -> bool,
) -> SamplingOutcome {
    let density = sampling_density(problem, state, matches);
    let (low, high) = crate::grid::bounds(&problem.quadrature.points);
    let mut grid = DynamicGrid::new(low, high, problem.kernel.cutoff);
    for (i, p) in state.positions.iter().enumerate() {
        if state.alive[i] {
            grid.insert(i, p);
        }
    }
    let width = problem.kernel.density_width();
    let alive = state.units.iter().filter(|u| u.alive && !u.frozen).map(|u| u.points.len()).sum();
    let mut pass = Pass { problem, matches, grid, density, width, allowed, alive, bounds };
    let mut outcome = SamplingOutcome::default();
    let limits = thresholds(problem, exemplar, threshold);
    let mut streak = Streak::new(pass.alive);
    let mut deficits: Vec<usize> = (0..pass.density.len()).filter(|&k| pass.density[k] < -limits[k]).collect();
    deficits.sort_by(|&a, &b| pass.density[a].total_cmp(&pass.density[b]).then(a.cmp(&b)));
    for k in deficits {
        if pass.density[k] >= -limits[k] {
            continue;
        }
        if streak.exhausted() {
            break;
        }
        outcome.tally(pass.propose_addition(exemplar, state, k), true, &mut streak);
    }
    // Still below the least count (a start with too few points, where no window shows a deficit
    // beyond the threshold): the quadrature points with the lowest P take one more point each.
    if pass.alive < pass.bounds.least {
        let mut order: Vec<usize> = (0..pass.density.len()).collect();
        order.sort_by(|&a, &b| pass.density[a].total_cmp(&pass.density[b]).then(a.cmp(&b)));
        let mut tries = 2 * (pass.bounds.least - pass.alive) + 8;
        for k in order {
            if pass.alive >= pass.bounds.least || tries == 0 {
                break;
            }
            // Places with nothing to propose (no gap) cost no try.
            match pass.propose_addition(exemplar, state, k) {
                Some(Proposal::Accepted) => outcome.added += 1,
                Some(_) => tries -= 1,
                None => {}
            }
        }
    }
    streak.reset();
    let mut excesses: Vec<usize> = (0..pass.density.len()).filter(|&k| pass.density[k] > limits[k]).collect();
    excesses.sort_by(|&a, &b| pass.density[b].total_cmp(&pass.density[a]).then(a.cmp(&b)));
    for k in excesses {
        if pass.density[k] <= limits[k] {
            continue;
        }
        if streak.exhausted() {
            break;
        }
        outcome.tally(pass.propose_removal(state, k), false, &mut streak);
    }
    // Still above the most: the quadrature points with the highest P give one point each.
    if pass.alive > pass.bounds.most {
        let mut order: Vec<usize> = (0..pass.density.len()).collect();
        order.sort_by(|&a, &b| pass.density[b].total_cmp(&pass.density[a]).then(a.cmp(&b)));
        let mut tries = 2 * (pass.alive - pass.bounds.most) + 8;
        for k in order {
            if pass.alive <= pass.bounds.most || tries == 0 {
                break;
            }
            // Places with no removable point near them (patch interiors) cost no try.
            match pass.propose_removal(state, k) {
                Some(Proposal::Accepted) => outcome.removed += 1,
                Some(_) => tries -= 1,
                None => {}
            }
        }
    }
    state.compact();
    outcome
}

/// Consecutive rejected proposals. Proposals are visited from the most significant |P| down; once
/// this many in a row have failed to lower T, the rest (smaller deviations still) are skipped:
/// each costs a local energy over a whole window, and on large windows nearly all were rejected.
struct Streak {
    misses: usize,
    limit: usize,
}

impl Streak {
    fn new(points: usize) -> Self {
        Self { misses: 0, limit: (points / 20).max(32) }
    }

    fn miss(&mut self) {
        self.misses += 1;
    }

    fn reset(&mut self) {
        self.misses = 0;
    }

    fn exhausted(&self) -> bool {
        self.misses >= self.limit
    }
}

impl SamplingOutcome {
    /// Counts one proposal (an addition when `adding`) and feeds the run of rejections.
    fn tally(&mut self, proposal: Option<Proposal>, adding: bool, streak: &mut Streak) {
        match proposal {
            Some(Proposal::Accepted) => {
                if adding {
                    self.added += 1;
                } else {
                    self.removed += 1;
                }
                streak.reset();
            }
            Some(Proposal::Rejected) => {
                self.rejected += 1;
                streak.miss();
            }
            Some(Proposal::HeldByBound) => self.held_by_bound += 1,
            None => {}
        }
    }
}

/// What became of one proposal.
enum Proposal {
    Accepted,
    Rejected,
    HeldByBound,
}

impl<const D: usize> Pass<'_, '_, D> {
    fn reach(&self) -> f64 {
        self.width.map_or(self.problem.kernel.delta, |w| 3.0 * w)
    }

    /// Adds (`sign = 1`) or removes (`-1`) the unit's points from `P`.
    fn update_density(&mut self, state: &State<D>, unit: usize, sign: f64) {
        let reach = self.reach();
        for &p in &state.units[unit].points {
            let x = state.positions[p as usize];
            let quadrature = self.problem.quadrature;
            let density = &mut self.density;
            let width = self.width;
            let (problem, matches) = (self.problem, self.matches);
            quadrature.for_each_within(&x, reach, |k| {
                if seen_by_exemplar(problem, k, &matches[k], &x) {
                    density[k] += sign * weight(width, linear::norm2(&linear::sub(&x, &quadrature.points[k])));
                }
            });
        }
    }

    fn nearest_distance(&self, state: &State<D>, x: &Vector<D>, radius: f64, skip_unit: Option<usize>) -> f64 {
        let mut best = radius * radius;
        self.grid.for_each_candidate(x, radius, |j| {
            if state.alive[j] && Some(state.unit_of[j] as usize) != skip_unit {
                best = best.min(linear::norm2(&linear::sub(&state.positions[j], x)));
            }
        });
        best.sqrt()
    }

    /// The change of T from the terms that hold `unit` (what removing it would subtract), and the
    /// gradient of T with respect to each of its points.
    fn unit_energy(&self, state: &State<D>, unit: usize, gradients: &mut Vec<Vector<D>>) -> f64 {
        let kernel = &self.problem.kernel;
        let members = &state.units[unit].points;
        gradients.clear();
        let mut total = 0.0;
        let mut neighbours: Vec<u32> = Vec::new();
        let mut scratch = crate::energy::RowScratch::default();
        let mut tables = Vec::new();
        let mut own_terms = Vec::with_capacity(members.len());
        let gaussian = kernel.window == crate::params::Window::Gaussian;
        for &p in members {
            let p = p as usize;
            let x = state.positions[p];
            neighbours.clear();
            self.grid.for_each_candidate(&x, kernel.cutoff, |j| {
                if j != p
                    && state.alive[j]
                    && linear::norm2(&linear::sub(&state.positions[j], &x)) < kernel.cutoff * kernel.cutoff
                {
                    neighbours.push(j as u32);
                }
            });
            neighbours.sort_unstable();
            let mut gradient = [0.0; D];
            // With the Gaussian window the row does the exemplar side only and the output pairs come
            // pair by pair (see `crate::output_pairs`); the box window's row keeps them.
            let (mut row_a, row_b) = self.problem.point_row(
                state,
                self.matches,
                p,
                &neighbours,
                &mut gradient,
                None,
                &mut scratch,
                !gaussian,
            );
            if gaussian {
                let (pairs, own) = self.problem.pair_row(state, p, &neighbours, &mut gradient, &mut tables);
                row_a = pairs;
                own_terms.push(own);
            }
            total += 2.0 * row_a + row_b;
            gradients.push(gradient);
        }
        // Pairs inside the unit were counted twice above (once per end, twice each): take one copy off.
        if gaussian {
            for (&p, &own) in members.iter().zip(&own_terms) {
                let a = state.feature(p as usize);
                for &r in members {
                    // A point's own term came with its row.
                    let value =
                        if r == p { own } else { self.problem.pair_of(state, p as usize, r as usize, &mut tables).0 };
                    total -= feature_dot(a, state.feature(r as usize)) * value;
                }
            }
            return total;
        }
        let quadrature = self.problem.quadrature;
        for &p in members {
            let x = state.positions[p as usize];
            let a = state.feature(p as usize);
            quadrature.for_each_within(&x, kernel.gather, |k| {
                let u = linear::sub(&x, &quadrature.points[k]);
                for &r in members {
                    let v = linear::sub(&state.positions[r as usize], &quadrature.points[k]);
                    if let Some((value, _, _)) = kernel.eval(&u, &v) {
                        total -= feature_dot(a, state.feature(r as usize)) * value;
                    }
                }
            });
        }
        total
    }

    fn insert_unit(&mut self, state: &State<D>, unit: usize) {
        for &p in &state.units[unit].points {
            self.grid.insert(p as usize, &state.positions[p as usize]);
        }
    }

    fn remove_unit(&mut self, state: &State<D>, unit: usize) {
        for &p in &state.units[unit].points {
            self.grid.remove(p as usize, &state.positions[p as usize]);
        }
    }

    /// Proposes a unit at quadrature point `k`; `None` when nothing fits there.
    fn propose_addition(&mut self, exemplar: &Exemplar<D>, state: &mut State<D>, k: usize) -> Option<Proposal> {
        let problem = self.problem;
        let kernel = &problem.kernel;
        let quadrature = problem.quadrature;
        let q = quadrature.points[k];
        let m = self.matches[k];
        let transform = quadrature.transform[k];
        let s = quadrature.scale[k];
        let sigma = kernel.sigma;
        // The exemplar points of the matched window farthest from every output point: the three
        // largest gaps are tried and the best is kept.
        let mut candidates: Vec<(usize, Vector<D>)> = Vec::new();
        problem.exemplar_grid.for_each_within(&m, kernel.delta.max(sigma) / s, |j, e, _| {
            candidates.push((j, linear::add(&q, &linear::mat_vec(&transform, &linear::sub(e, &m)))));
        });
        candidates.sort_unstable_by_key(|c| c.0);
        let mut gaps: Vec<(f64, usize, Vector<D>)> = Vec::new();
        for (j, x) in candidates {
            if !(self.allowed)(&x) {
                continue;
            }
            let gap = self.nearest_distance(state, &x, 2.0 * sigma, None);
            if gap > 0.5 * sigma * s.min(1.0) {
                gaps.push((gap, j, x));
            }
        }
        gaps.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        let mut best: Option<(f64, usize)> = None;
        for &(_, j, x) in gaps.iter().take(3) {
            let Some((energy, unit)) = self.try_unit(exemplar, state, k, j, x) else { continue };
            match best {
                Some((best_energy, _)) if best_energy <= energy => self.discard(state, unit),
                _ => {
                    if let Some((_, previous)) = best {
                        self.discard(state, previous);
                    }
                    best = Some((energy, unit));
                }
            }
        }
        let (energy, unit) = best?;
        let size = state.units[unit].points.len();
        // Below the least count the best candidate goes in even when T rises (a start with too
        // few points, e.g. patches copied from a sparse part of the exemplar).
        let needed = self.alive < self.bounds.least;
        if (energy < 0.0 || needed) && self.alive + size <= self.bounds.most {
            self.update_density(state, unit, 1.0);
            self.alive += size;
            Some(Proposal::Accepted)
        } else {
            self.discard(state, unit);
            Some(if energy < 0.0 { Proposal::HeldByBound } else { Proposal::Rejected })
        }
    }

    fn discard(&mut self, state: &mut State<D>, unit: usize) {
        self.remove_unit(state, unit);
        state.kill(unit);
    }

    /// Inserts a copy of exemplar point `j` (or its element) at `x`, lets it take a few gradient
    /// steps, and returns the change of T it causes with its unit.
    fn try_unit(
        &mut self,
        exemplar: &Exemplar<D>,
        state: &mut State<D>,
        k: usize,
        j: usize,
        x: Vector<D>,
    ) -> Option<(f64, usize)> {
        let problem = self.problem;
        let quadrature = problem.quadrature;
        let q = quadrature.points[k];
        let m = self.matches[k];
        let transform = quadrature.transform[k];
        let s = quadrature.scale[k];
        let sigma = problem.kernel.sigma;
        let unit = match exemplar.element_of[j] {
            None => state.add_free(x, exemplar.feature(j), false),
            Some(element) => {
                let source = &exemplar.elements[element as usize];
                let centre = linear::add(&q, &linear::mat_vec(&transform, &linear::sub(&source.centre, &m)));
                if !(self.allowed)(&centre) {
                    return None;
                }
                let rotation: crate::linear::Matrix<D> =
                    std::array::from_fn(|r| std::array::from_fn(|c| transform[r][c] / s));
                let body: Vec<Vector<D>> = source
                    .members
                    .iter()
                    .map(|&p| linear::scale(&linear::sub(&exemplar.positions[p], &source.centre), s))
                    .collect();
                let mut features = Vec::new();
                for &p in &source.members {
                    features.extend_from_slice(exemplar.feature(p));
                }
                state.add_rigid(Rigid { centre, rotation, body }, &features, 0, false)
            }
        };
        self.insert_unit(state, unit);
        // A few gradient steps on the new unit alone (translation), each kept only if it helps.
        let mut gradients = Vec::new();
        let mut energy = self.unit_energy(state, unit, &mut gradients);
        let mut step = 0.1 * sigma;
        for _ in 0..4 {
            let mut force = [0.0; D];
            for g in &gradients {
                linear::axpy(&mut force, 1.0, g);
            }
            let norm = linear::norm2(&force).sqrt();
            if norm == 0.0 {
                break;
            }
            let shift = linear::scale(&force, -step / norm);
            let moved = self.shift_unit(state, unit, &shift);
            let mut trial_gradients = Vec::new();
            let trial = self.unit_energy(state, unit, &mut trial_gradients);
            if moved && trial < energy {
                energy = trial;
                gradients = trial_gradients;
                step *= 1.5;
            } else {
                if moved {
                    self.shift_unit(state, unit, &linear::scale(&shift, -1.0));
                }
                step *= 0.4;
            }
        }
        Some((energy, unit))
    }

    /// Moves a unit by `shift` if its anchor stays allowed; returns whether it moved.
    fn shift_unit(&mut self, state: &mut State<D>, unit: usize, shift: &Vector<D>) -> bool {
        let anchor = match &state.units[unit].rigid {
            Some(rigid) => rigid.centre,
            None => state.positions[state.units[unit].points[0] as usize],
        };
        if !(self.allowed)(&linear::add(&anchor, shift)) {
            return false;
        }
        self.remove_unit(state, unit);
        if let Some(rigid) = &mut state.units[unit].rigid {
            rigid.centre = linear::add(&rigid.centre, shift);
            state.place_rigid(unit);
        } else {
            let p = state.units[unit].points[0] as usize;
            state.positions[p] = linear::add(&state.positions[p], shift);
        }
        self.insert_unit(state, unit);
        true
    }

    /// Proposes removing, among the units near quadrature point `k`, the one whose removal lowers T
    /// the most.
    fn propose_removal(&mut self, state: &mut State<D>, k: usize) -> Option<Proposal> {
        let kernel = &self.problem.kernel;
        let q = self.problem.quadrature.points[k];
        let radius = kernel.delta.max(kernel.sigma);
        let mut candidates: Vec<(f64, usize)> = Vec::new();
        self.grid.for_each_candidate(&q, radius, |i| {
            let d2 = linear::norm2(&linear::sub(&state.positions[i], &q));
            if state.alive[i] && !state.units[state.unit_of[i] as usize].frozen && d2 < radius * radius {
                candidates.push((d2, state.unit_of[i] as usize));
            }
        });
        candidates.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut units: Vec<usize> = Vec::new();
        for (_, unit) in candidates {
            if !units.contains(&unit) {
                units.push(unit);
            }
            if units.len() == 8 {
                break;
            }
        }
        let mut best: Option<(f64, usize)> = None;
        let mut gradients = Vec::new();
        for unit in units {
            let energy = self.unit_energy(state, unit, &mut gradients);
            if best.is_none_or(|b| energy > b.0) {
                best = Some((energy, unit));
            }
        }
        let (energy, unit) = best?;
        let size = state.units[unit].points.len();
        let surplus = self.alive > self.bounds.most;
        if energy <= 0.0 && !surplus {
            return Some(Proposal::Rejected);
        }
        if self.alive < self.bounds.least + size {
            return Some(Proposal::HeldByBound);
        }
        self.update_density(state, unit, -1.0);
        self.remove_unit(state, unit);
        state.kill(unit);
        self.alive -= size;
        Some(Proposal::Accepted)
    }
}
