//! The loop of Algorithm 1 (§5.1): per window size, rounds of local–global iterations (matching,
//! then merging positions and attributes), each round followed by sampling control.

use motif_core::{Progress, SeedStreams, StageTimer};

use crate::energy::Problem;
use crate::linear::Vector;
use crate::matching::{self, MatchSettings, SearchFields};
use crate::merging::{self, MergeSettings};
use crate::model::State;
use crate::params::{Evaluator, Params, Refinement};
use crate::sampling;
use crate::setup::Setup;
use crate::solver::{IterationEnergy, evaluate_with};

/// The window sizes of Algorithm 1: δ, αδ, α²δ, ... while ≥ final_fraction·δ (at most 200).
pub(crate) fn window_sizes(delta: f64, params: &Params) -> Vec<f64> {
    let mut deltas = vec![delta];
    while deltas.len() < 200 {
        let next = deltas[deltas.len() - 1] * params.effective_shrink();
        if next < params.final_fraction * delta - 1e-12 {
            break;
        }
        deltas.push(next);
    }
    deltas
}

/// What the optimization reads: the setup, the options and what follows from them.
pub(crate) struct Solver<'a, const D: usize> {
    pub(crate) setup: &'a Setup<D>,
    pub(crate) params: &'a Params,
    pub(crate) streams: &'a SeedStreams,
    /// The window sizes, from δ down.
    pub(crate) deltas: Vec<f64>,
    pub(crate) match_settings: MatchSettings,
    pub(crate) merge_settings: MergeSettings,
    /// The count bounds of sampling control.
    pub(crate) bounds: sampling::CountBounds,
}

/// What the optimization changes: the output, its matches, the stage timer and the tallies of the
/// report.
pub(crate) struct Course<const D: usize> {
    pub(crate) state: State<D>,
    pub(crate) matches: Vec<Vector<D>>,
    pub(crate) timer: StageTimer,
    pub(crate) energies: Vec<IterationEnergy>,
    pub(crate) added: usize,
    pub(crate) removed: usize,
    pub(crate) rejected: usize,
    pub(crate) held_by_bound: usize,
    pub(crate) final_energy: f64,
    /// Local–global iterations done.
    pub(crate) done: usize,
}

impl<const D: usize> Solver<'_, D> {
    /// Algorithm 1's loop: per window size, its search fields, then rounds of local–global
    /// iterations each followed by sampling control (none with copies only: the quilted patches
    /// are the result).
    pub(crate) fn optimize(&self, course: &mut Course<D>, progress: &mut dyn Progress) {
        let params = self.params;
        let total_iterations = self.deltas.len() * params.sampling_rounds * params.local_global_iterations;
        let mut fields: Option<SearchFields<D>> = None;
        // Copies only: the quilted patches are the result.
        let optimized = if params.refinement == Refinement::None { 0 } else { self.deltas.len() };
        for (scale, &delta) in self.deltas.iter().enumerate().take(optimized) {
            let problem = self.setup.problem(delta, params);
            // The exemplar's search rasters at this window size (part of matching's work; a stage
            // of its own because a brush stroke, a small synthesis, pays it in full every time).
            course.timer.start("search fields");
            let fields = match &mut fields {
                Some(fields) => {
                    fields.set_window(&problem);
                    fields
                }
                None => fields.insert(SearchFields::new(&problem)),
            };
            for round in 0..params.sampling_rounds {
                for _ in 0..params.local_global_iterations {
                    progress.report("synthesis", course.done as f64 / total_iterations as f64);
                    self.iterate(&problem, fields, course, (scale, delta, round));
                }
                if params.sampling_control {
                    self.control(&problem, course);
                }
            }
        }
    }

    /// One local–global iteration at window size `delta` (`at`: scale index, δ, round): matching
    /// every quadrature point, then merging the positions and the attributes; records its T.
    fn iterate(
        &self,
        problem: &Problem<'_, D>,
        fields: &SearchFields<D>,
        course: &mut Course<D>,
        (scale, delta, round): (usize, f64, usize),
    ) {
        let (setup, params, merge_settings) = (self.setup, self.params, self.merge_settings);
        course.timer.start("matching");
        let iteration_streams = self.streams.child("iteration", course.done as u64);
        let found = matching::match_all(
            problem,
            fields,
            &course.state,
            &course.matches,
            self.match_settings,
            &iteration_streams,
        );
        course.matches = found.iter().map(|m| m.location).collect();
        let exemplar_self: f64 = found.iter().map(|m| m.exemplar_self).sum();
        course.timer.start("merging");
        let matches = &course.matches;
        let state = &mut course.state;
        let evaluate = |s: &State<D>, f: bool| evaluate_with(problem, params.evaluator, s, matches, exemplar_self, f);
        let allowed = |p: &Vector<D>| setup.allowed(p);
        let attributes = state.channels > 1 && merge_settings.attribute_iterations > 0;
        let movable = state.movable();
        let restricted = params.evaluator == Evaluator::Fast && problem.restricts() && movable.iter().any(|m| !m);
        let (steps, last) = if restricted {
            // Frozen points (copied interiors, existing points) keep their rows' values while
            // the others move: the steps evaluate the movable rows alone, and T is their sum
            // plus a constant. One full pass after the steps gives that constant (and the
            // attribute form, when the attribute step follows), so the recorded energies
            // are T's; a pass before the steps as well cost 10 % of a brush stroke.
            let evaluate_movable = |s: &State<D>, _: bool| problem.evaluate_active(s, matches, &movable);
            let (mut steps, last) = merging::merge_positions(state, merge_settings, false, &evaluate_movable, &allowed);
            let full = problem.evaluate(state, matches, exemplar_self, attributes);
            let constant = full.energy - last.energy;
            steps.iter_mut().for_each(|energy| *energy += constant);
            (steps, Some(full))
        } else {
            let (steps, last) = merging::merge_positions(state, merge_settings, attributes, &evaluate, &allowed);
            (steps, Some(last))
        };
        state.settle(|p| setup.region.keep_on(p));
        let discrete = &setup.attributes.discrete;
        let ranges = params.attributes_within_range.then_some(setup.exemplar.ranges.as_slice());
        let after = merging::merge_attributes(state, merge_settings, discrete, ranges, last, &evaluate)
            .unwrap_or_else(|| steps.last().copied().unwrap_or(f64::NAN));
        let points = state.positions.len();
        course.energies.push(IterationEnergy {
            scale,
            neighbourhood: delta,
            round,
            after_matching: steps[0],
            after_merging: after,
            merge_steps: steps.len() - 1,
            points,
            added: 0,
            removed: 0,
        });
        course.final_energy = after;
        course.done += 1;
    }

    /// Sampling control after a round: points added and removed where that lowers T, within the
    /// count bounds; tallied on the round's last iteration and in the totals.
    fn control(&self, problem: &Problem<'_, D>, course: &mut Course<D>) {
        let setup = self.setup;
        course.timer.start("sampling control");
        let allowed = |p: &Vector<D>| setup.allowed(p);
        let outcome = sampling::control(
            problem,
            &setup.exemplar,
            &mut course.state,
            &course.matches,
            self.params.sampling_threshold,
            self.bounds,
            &allowed,
        );
        course.state.settle(|p| setup.region.keep_on(p));
        if let Some(last) = course.energies.last_mut() {
            last.added = outcome.added;
            last.removed = outcome.removed;
        }
        course.added += outcome.added;
        course.removed += outcome.removed;
        course.rejected += outcome.rejected;
        course.held_by_bound += outcome.held_by_bound;
    }
}
