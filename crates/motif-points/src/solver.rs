//! Algorithm 1, the multi-scale local–global solver (§5.1), with validation and set-up.

use motif_core::error::{check_count, check_positive, check_range};
use motif_core::timing::Clock;
use motif_core::{Progress, SeedStreams, StageTimer};
use serde::Serialize;

use crate::domain::{Quadrature, Region};
use crate::energy::{Evaluation, Neighbours, Problem};
use crate::exemplar_pairs::ExemplarPairs;
use crate::fidelity::{self, Fidelity};
use crate::grid::{CellLists, StaticGrid};
use crate::linear::{self, Vector};
use crate::matching::{self, MatchSettings, SearchFields};
use crate::merging::{self, MergeSettings};
use crate::model::{Exemplar, ExemplarElement, Kernel, Rigid, State};
use crate::params::{Error, Evaluator, Initialization, Input, Params};
use crate::{PointSet, init, reference, sampling};

/// T at one outer iteration of Algorithm 1.
#[derive(Debug, Clone, Serialize)]
pub struct IterationEnergy {
    /// Index of the window size (0 = the user's δ).
    pub scale: usize,
    /// The window size δ at this iteration.
    pub neighbourhood: f64,
    /// Sampling-control round within the scale.
    pub round: usize,
    /// T after matching (before merging).
    pub after_matching: f64,
    /// T after merging.
    pub after_merging: f64,
    /// Accepted gradient steps of the position merging.
    pub merge_steps: usize,
    /// Output points at this iteration.
    pub points: usize,
    /// Points added by the sampling control that followed (0 when none ran).
    pub added: usize,
    /// Points removed by the sampling control that followed.
    pub removed: usize,
}

/// What the synthesis did.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// σ used (output units).
    pub sigma: f64,
    /// The starting window size δ.
    pub neighbourhood: f64,
    /// Number of quadrature points.
    pub quadrature_points: usize,
    /// Points after initialization (existing ones included).
    pub initial_points: usize,
    /// Points in the result.
    pub final_points: usize,
    /// Points added by sampling control.
    pub added: usize,
    /// Points removed by sampling control.
    pub removed: usize,
    /// Proposals of sampling control that did not lower T.
    pub rejected: usize,
    /// Proposals that lowered T but would have taken the count outside its bounds.
    pub held_by_bound: usize,
    /// Points the exemplar's density asks for over the domain.
    pub expected_points: f64,
    /// Attributes snapped to the exemplar's values (given or detected).
    pub discrete_attributes: Vec<String>,
    /// T per outer iteration.
    pub energy: Vec<IterationEnergy>,
    /// The last T.
    pub final_energy: f64,
    /// Points that were kept fixed (progressive synthesis).
    pub fixed_points: usize,
    /// Structure fidelity on the interior.
    pub fidelity: Fidelity,
    /// Milliseconds per stage.
    pub stages_ms: Vec<(String, f64)>,
}

/// The synthesized points and the report.
#[derive(Debug, Clone)]
pub struct Output {
    /// Output points with the exemplar's (selected) attributes and, when it has elements, element ids.
    pub points: PointSet,
    /// Figures.
    pub report: Report,
}

/// Timings of one evaluation of T and its gradient by both implementations (the speed-up figure).
#[derive(Debug, Clone, Serialize)]
pub struct EvaluatorComparison {
    /// Output points evaluated.
    pub points: usize,
    /// Quadrature points.
    pub quadrature_points: usize,
    /// Milliseconds of the fast evaluation.
    pub fast_ms: f64,
    /// Milliseconds of the reference evaluation.
    pub reference_ms: f64,
    /// T from the fast evaluation.
    pub fast_energy: f64,
    /// T from the reference evaluation.
    pub reference_energy: f64,
}

fn validate(input: &Input, params: &Params) -> Result<(), Error> {
    let exemplar = &input.exemplar;
    exemplar.validate("exemplar")?;
    if exemplar.len() < 3 {
        return Err(Error::Input(format!("the exemplar has {} points; it needs at least 3", exemplar.len())));
    }
    if let Some(existing) = &input.existing {
        existing.validate("existing points")?;
        if existing.dimension != exemplar.dimension {
            return Err(Error::Input(format!(
                "the existing points are {}D but the exemplar is {}D",
                existing.dimension, exemplar.dimension
            )));
        }
    }
    if let Some(delta) = params.neighbourhood {
        check_positive("neighbourhood", delta)?;
    }
    if let Some(sigma) = params.sigma {
        check_positive("sigma", sigma)?;
    }
    check_range("spacing-fraction", params.spacing_fraction, 0.1, 2.0)?;
    check_range("quadrature-spacing", params.quadrature_spacing, 0.25, 4.0)?;
    check_range("kernel-cutoff", params.kernel_cutoff, 2.0, 6.0)?;
    check_range("shrink", params.shrink, 0.5, 0.99)?;
    check_range("final-fraction", params.final_fraction, 0.05, 1.0)?;
    check_count("sampling-rounds", params.sampling_rounds, 1, 20)?;
    check_count("local-global-iterations", params.local_global_iterations, 1, 20)?;
    check_count("merge-iterations", params.merge_iterations, 1, 1000)?;
    check_count("attribute-iterations", params.attribute_iterations, 0, 1000)?;
    check_range("step", params.step, 1e-4, 1.0)?;
    check_range("tolerance", params.tolerance, 0.0, 1.0)?;
    check_range("stagnation", params.stagnation, 0.0, 1.0)?;
    check_count("matching-starts", params.matching_starts, 1, 64)?;
    check_count("matching-iterations", params.matching_iterations, 1, 200)?;
    check_count("matching-polish", params.matching_polish, 0, 50)?;
    check_range("sampling-threshold", params.sampling_threshold, 0.05, 10.0)?;
    check_range("count-tolerance", params.count_tolerance, 0.01, 1.0)?;
    check_range("patch-size", params.patch_size, 1.0, 20.0)?;
    check_range("attribute-weight", params.attribute_weight, 1e-6, 100.0)?;
    if let Some(margin) = params.keep_margin {
        check_range("keep-margin", margin, 0.0, f64::MAX)?;
    }
    if params.domain.is_none() {
        return Err(Error::EmptyDomain("no domain given (a box, a polygon region or a brush stroke)".into()));
    }
    Ok(())
}

/// Synthesizes a structure like `input.exemplar` over `params.domain` (§5, Algorithm 1).
pub fn synthesize(input: &Input, params: &Params, progress: &mut dyn Progress) -> Result<Output, Error> {
    validate(input, params)?;
    match input.exemplar.dimension {
        2 => run::<2>(input, params, progress),
        _ => run::<3>(input, params, progress),
    }
}

/// Times one evaluation of T and its position gradient with the fast and the reference
/// implementation on the initialized output (after one matching step).
pub fn compare_evaluators(input: &Input, params: &Params) -> Result<EvaluatorComparison, Error> {
    compare(input, params)
}

/// Attribute bookkeeping: which exemplar columns are used and how they are made unit-free.
#[derive(Debug, Clone)]
pub(crate) struct AttributeMap {
    pub names: Vec<String>,
    pub columns: Vec<usize>,
    pub mean: Vec<f64>,
    /// Feature = (value − mean) · factor.
    pub factor: Vec<f64>,
    /// Allowed normalized values per channel (index = channel; channel 0 is the density).
    pub discrete: Vec<Vec<f64>>,
    /// The exemplar values behind `discrete` (same order), written back exactly.
    pub discrete_values: Vec<Vec<f64>>,
}

/// Everything fixed for a synthesis.
pub(crate) struct Setup<const D: usize> {
    pub exemplar: Exemplar<D>,
    pub attributes: AttributeMap,
    pub sigma: f64,
    pub delta: f64,
    pub region: Region<D>,
    pub quadrature: Quadrature<D>,
    pub exemplar_grid: StaticGrid<D>,
    pub exemplar_cells: CellLists<D>,
    pub exemplar_pairs: ExemplarPairs<D>,
    pub exemplar_neighbours: Neighbours,
    pub state: State<D>,
    pub fill: Vec<usize>,
    pub margin: Option<f64>,
    pub has_elements: bool,
    /// Points the exemplar's density asks for over the quadrature domain.
    pub expected_points: f64,
}

fn vector<const D: usize>(values: &[f64]) -> Vector<D> {
    std::array::from_fn(|a| values[a])
}

pub(crate) fn prepare<const D: usize>(input: &Input, params: &Params) -> Result<Setup<D>, Error> {
    let source = &input.exemplar;
    let n = source.len();
    let positions: Vec<Vector<D>> = (0..n).map(|i| vector(source.position(i))).collect();
    // Attributes.
    let names: Vec<String> = match &params.attributes {
        Some(names) => names.clone(),
        None => source.attribute_names.clone(),
    };
    let mut columns = Vec::new();
    for name in &names {
        match source.attribute_names.iter().position(|c| c == name) {
            Some(c) => columns.push(c),
            None => {
                return Err(Error::Input(format!(
                    "the exemplar has no attribute {name:?} (it has: {})",
                    source.attribute_names.join(", ")
                )));
            }
        }
    }
    for name in params.discrete_attributes.iter().chain(&params.continuous_attributes) {
        if !names.contains(name) {
            return Err(Error::Input(format!(
                "attribute {name:?} (named as discrete or continuous) is not among the synthesized attributes ({})",
                names.join(", ")
            )));
        }
    }
    for (name, weight) in &params.attribute_weights {
        if !names.contains(name) {
            return Err(Error::Input(format!(
                "attribute weight for {name:?}: no such synthesized attribute ({})",
                names.join(", ")
            )));
        }
        check_range(&format!("attribute weight of {name}"), *weight, 1e-6, 100.0)?;
    }
    let channels = 1 + columns.len();
    let mut mean = Vec::new();
    let mut factor = Vec::new();
    let mut discrete = vec![Vec::new(); channels];
    let mut discrete_values = vec![Vec::new(); channels];
    for (c, &column) in columns.iter().enumerate() {
        let values: Vec<f64> = (0..n).map(|i| source.attributes_of(i)[column]).collect();
        let mu = values.iter().sum::<f64>() / n as f64;
        let variance = values.iter().map(|v| (v - mu).powi(2)).sum::<f64>() / n as f64;
        let std = variance.sqrt();
        if std <= 1e-12 * mu.abs().max(1.0) {
            return Err(Error::Input(format!(
                "attribute {:?} has the same value ({mu}) at every exemplar point; it carries no structure: leave it \
                 out (choose the others with the attribute list)",
                names[c]
            )));
        }
        let weight =
            params.attribute_weights.iter().find(|(n, _)| n == &names[c]).map_or(params.attribute_weight, |w| w.1);
        let f = weight / std;
        mean.push(mu);
        factor.push(f);
        let mut distinct = values.clone();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup();
        // Labels: whole numbers with at most 32 values, or at most 4 values of any kind among 20
        // or more points (the demo lattice's radius 0.5/1).
        let labels = (values.iter().all(|v| v.fract() == 0.0) && distinct.len() <= 32)
            || (distinct.len() <= 4 && values.len() >= 20);
        let detected = params.detect_discrete && labels && !params.continuous_attributes.contains(&names[c]);
        if params.discrete_attributes.contains(&names[c]) || detected {
            let mut raw = values.clone();
            raw.sort_by(f64::total_cmp);
            raw.dedup_by(|a, b| (*a - *b).abs() < 1e-12 * a.abs().max(1.0));
            discrete[c + 1] = raw.iter().map(|v| (v - mu) * f).collect();
            discrete_values[c + 1] = raw;
        }
    }
    let attributes = AttributeMap { names, columns, mean, factor, discrete, discrete_values };
    let features_of = |set: &PointSet, i: usize, map: &[usize]| -> Vec<f64> {
        let mut f = vec![1.0];
        for (c, &column) in map.iter().enumerate() {
            f.push((set.attributes_of(i)[column] - attributes.mean[c]) * attributes.factor[c]);
        }
        f
    };
    let mut features = Vec::with_capacity(n * channels);
    for i in 0..n {
        features.extend(features_of(source, i, &attributes.columns));
    }
    // Elements.
    let mut element_of = vec![None; n];
    let mut elements: Vec<ExemplarElement<D>> = Vec::new();
    if let Some(ids) = &source.elements {
        let mut index: std::collections::BTreeMap<i64, u32> = std::collections::BTreeMap::new();
        for (i, &id) in ids.iter().enumerate() {
            if id < 0 {
                continue;
            }
            let e = *index.entry(id).or_insert_with(|| {
                elements.push(ExemplarElement { centre: [0.0; D], members: Vec::new() });
                (elements.len() - 1) as u32
            });
            element_of[i] = Some(e);
            elements[e as usize].members.push(i);
        }
        for element in &mut elements {
            let mut centre = [0.0; D];
            for &p in &element.members {
                linear::axpy(&mut centre, 1.0, &positions[p]);
            }
            element.centre = linear::scale(&centre, 1.0 / element.members.len() as f64);
        }
    }
    let spacing = fidelity::mean_spacing(&positions);
    if spacing <= 0.0 || !spacing.is_finite() {
        return Err(Error::Input("the exemplar's points all coincide; they need a positive spacing".into()));
    }
    let sigma = params.sigma.unwrap_or(params.spacing_fraction * spacing);
    let delta = params.neighbourhood.unwrap_or(2.0 * sigma);
    let (low, high) = crate::grid::bounds(&positions);
    let exemplar = Exemplar { positions, features, channels, element_of, elements, low, high, spacing };
    // Domain and quadrature.
    let domain = params.domain.as_ref().ok_or_else(|| Error::EmptyDomain("no domain given".into()))?;
    let region = Region::<D>::new(domain).map_err(Error::EmptyDomain)?;
    let existing: Vec<Vector<D>> = match &input.existing {
        Some(set) => (0..set.len()).map(|i| vector(set.position(i))).collect(),
        None => Vec::new(),
    };
    let margin = input.existing.as_ref().map(|_| params.keep_margin.unwrap_or(3.0 * delta));
    let existing_grid = StaticGrid::new(&existing, 2.0 * sigma);
    let near_existing = |q: &Vector<D>| {
        let mut found = false;
        existing_grid.for_each_within(q, 2.0 * sigma, |_, _, _| found = true);
        found
    };
    let (mut low, mut high) = region.bounds();
    if let Some(margin) = margin {
        for a in 0..D {
            low[a] -= margin;
            high[a] += margin;
        }
    }
    let h = params.quadrature_spacing * sigma;
    let keep = |q: &Vector<D>| {
        region.contains(q) || margin.is_some_and(|margin| region.distance(q) < margin && near_existing(q))
    };
    let quadrature = Quadrature::new(low, high, h, keep, &region, &params.rotation, &params.scale)?;
    // The grid measures Ω with a boundary layer of half a cell on every side; where the region's
    // volume is known exactly (a fresh box or polygon) the expected count follows it instead (a
    // 9 × 9 box of a unit-density exemplar holds 81 points, not the grid's 91).
    let mut expected: f64 = quadrature.scale.iter().map(|s| (h / s).powi(D as i32) * exemplar.density()).sum();
    let grid_volume = quadrature.len() as f64 * h.powi(D as i32);
    if let (Some(volume), None) = (region.volume(), margin) {
        expected *= volume / grid_volume.max(1e-300);
    }
    if quadrature.len() == 0 || (expected < 1.0 && input.existing.is_none()) {
        return Err(Error::EmptyDomain(format!(
            "the domain holds {expected:.2} points at the exemplar's density; make it larger"
        )));
    }
    let s_min = quadrature.scale.iter().copied().fold(f64::INFINITY, f64::min);
    let cutoff = params.kernel_cutoff * sigma;
    // Cells of the pair cut-off: a query of that radius scans 3 rows (2D) or 9 rows (3D) of 3 cells.
    // Half-size cells scan less volume but, measured in 3D, cost more in per-row overhead.
    let exemplar_grid = StaticGrid::new(&exemplar.positions, cutoff / s_min);
    let exemplar_cells = CellLists::new(&exemplar.positions, cutoff / s_min);
    let exemplar_neighbours = Neighbours::build(&exemplar.positions, cutoff / s_min);
    let exemplar_pairs = ExemplarPairs::new(&exemplar, &exemplar_neighbours, cutoff / s_min, 3.0 * delta / s_min);
    // Existing points (progressive synthesis): fixed unless near the new region.
    let mut state = State::new(channels);
    if let Some(set) = &input.existing {
        let mut map = Vec::new();
        for name in &attributes.names {
            match set.attribute_names.iter().position(|c| c == name) {
                Some(c) => map.push(c),
                None => return Err(Error::Input(format!("the existing points have no attribute {name:?}"))),
            }
        }
        let margin = margin.unwrap_or(0.0);
        let mut groups: std::collections::BTreeMap<i64, Vec<usize>> = std::collections::BTreeMap::new();
        for i in 0..set.len() {
            let id = set.elements.as_ref().map_or(-1, |e| e[i]);
            let x = existing[i];
            if id < 0 {
                let frozen = region.distance(&x) > margin;
                state.add_free(x, &features_of(set, i, &map), frozen);
            } else {
                groups.entry(id).or_default().push(i);
            }
        }
        for (_, members) in groups {
            let mut centre = [0.0; D];
            for &p in &members {
                linear::axpy(&mut centre, 1.0, &existing[p]);
            }
            let centre = linear::scale(&centre, 1.0 / members.len() as f64);
            let body = members.iter().map(|&p| linear::sub(&existing[p], &centre)).collect();
            let mut features = Vec::new();
            for &p in &members {
                features.extend(features_of(set, p, &map));
            }
            let frozen = region.distance(&centre) > margin;
            let rigid = Rigid { centre, rotation: linear::identity(), body };
            state.add_rigid(rigid, &features, 0, frozen);
        }
    }
    let fill: Vec<usize> = (0..quadrature.len())
        .filter(|&k| region.contains(&quadrature.points[k]) && !near_existing(&quadrature.points[k]))
        .collect();
    let has_elements = !exemplar.elements.is_empty()
        || input.existing.as_ref().is_some_and(|e| e.elements.as_ref().is_some_and(|ids| ids.iter().any(|&i| i >= 0)));
    Ok(Setup {
        exemplar,
        attributes,
        sigma,
        delta,
        region,
        quadrature,
        exemplar_grid,
        exemplar_cells,
        exemplar_pairs,
        exemplar_neighbours,
        state,
        fill,
        margin,
        has_elements,
        expected_points: expected,
    })
}

impl<const D: usize> Setup<D> {
    pub fn allowed(&self, p: &Vector<D>) -> bool {
        // Existing points near the new region may move within the band of Ω around it.
        self.region.contains(p) || self.margin.is_some_and(|m| self.region.distance(p) < m && self.quadrature.inside(p))
    }

    /// Creates the initial output; returns the matches the initialization knows (the source of
    /// each copied patch; empty for random points).
    pub fn initialize(&mut self, params: &Params, streams: &SeedStreams) -> Vec<Vector<D>> {
        let mut state = std::mem::take(&mut self.state);
        let allowed = |p: &Vector<D>| self.allowed(p);
        let matches = match params.initialization {
            Initialization::Random => {
                init::random(&self.exemplar, &self.quadrature, &self.fill, &mut state, streams, &allowed);
                Vec::new()
            }
            Initialization::Patches => {
                // Patches of 6δ (capped at 0.7 of the exemplar's smallest side): a window reaches
                // about 2δ, so with the 2δ patches of the first version every window straddled
                // several copies, no match could explain it, and the first merging step tore the
                // copies apart (longleaf pines: g(r) distance 0.35 against 0.15 now).
                let extent = (0..D).map(|a| self.exemplar.high[a] - self.exemplar.low[a]).fold(f64::INFINITY, f64::min);
                let s_min = self.quadrature.scale.iter().copied().fold(f64::INFINITY, f64::min);
                let patch = (params.patch_size * self.delta).min(0.7 * extent * s_min).max(3.0 * self.sigma);
                let sources =
                    init::patches(&self.exemplar, &self.quadrature, &self.fill, patch, &mut state, streams, &allowed);
                // Points outside every copied tile start from the exemplar's centre; the searched
                // match replaces it at the first matching.
                let centre = std::array::from_fn(|a| 0.5 * (self.exemplar.low[a] + self.exemplar.high[a]));
                sources.into_iter().map(|m| m.unwrap_or(centre)).collect()
            }
        };
        state.compact();
        self.state = state;
        matches
    }

    pub fn problem(&self, delta: f64, params: &Params) -> Problem<'_, D> {
        let kernel = Kernel::new(params.window, self.sigma, delta, params.kernel_cutoff);
        // A window is interior when everything it reaches (and the grid node each place rounds to)
        // is inside Ω; then the exemplar needs no masking there.
        let h = self.quadrature.spacing();
        let interior = self.quadrature.depth.iter().map(|&d| d as f64 * h > kernel.gather + h).collect();
        Problem {
            kernel,
            interior,
            exemplar: &self.exemplar,
            exemplar_grid: &self.exemplar_grid,
            exemplar_cells: &self.exemplar_cells,
            exemplar_pairs: &self.exemplar_pairs,
            exemplar_neighbours: &self.exemplar_neighbours,
            quadrature: &self.quadrature,
        }
    }
}

pub(crate) fn evaluate_with<const D: usize>(
    problem: &Problem<'_, D>,
    evaluator: Evaluator,
    state: &State<D>,
    matches: &[Vector<D>],
    exemplar_self: f64,
    features: bool,
) -> Evaluation<D> {
    match evaluator {
        Evaluator::Fast => problem.evaluate(state, matches, exemplar_self, features),
        Evaluator::Reference => reference::evaluate(problem, state, matches, features),
    }
}

fn run<const D: usize>(input: &Input, params: &Params, progress: &mut dyn Progress) -> Result<Output, Error> {
    let mut timer = StageTimer::new();
    timer.start("prepare");
    let streams = SeedStreams::new(params.seed);
    let mut setup = prepare::<D>(input, params)?;
    timer.start("initialize");
    let mut matches = setup.initialize(params, &streams.child("initialize", 0));
    let initial_points = setup.state.positions.len();
    // Window sizes: δ, αδ, α²δ, ... while ≥ final_fraction·δ.
    let mut deltas = vec![setup.delta];
    while deltas.len() < 200 {
        let next = deltas[deltas.len() - 1] * params.shrink;
        if next < params.final_fraction * setup.delta - 1e-12 {
            break;
        }
        deltas.push(next);
    }
    let total_iterations = deltas.len() * params.sampling_rounds * params.local_global_iterations;
    let match_settings = MatchSettings {
        starts: params.matching_starts,
        iterations: params.matching_iterations,
        polish: params.matching_polish,
    };
    let merge_settings = MergeSettings {
        iterations: params.merge_iterations,
        attribute_iterations: params.attribute_iterations,
        step: params.step,
        tolerance: params.tolerance,
        stagnation: params.stagnation,
        sigma: setup.sigma,
    };
    let mut energies = Vec::new();
    let (mut added, mut removed, mut rejected, mut held_by_bound) = (0, 0, 0, 0);

    let mut final_energy = f64::NAN;
    let mut done = 0;
    let mut state = std::mem::take(&mut setup.state);
    let bounds = count_bounds(&setup, params.count_tolerance);
    let mut fields: Option<SearchFields<D>> = None;
    for (scale, &delta) in deltas.iter().enumerate() {
        let problem = setup.problem(delta, params);
        timer.start("matching");
        let fields = match &mut fields {
            Some(fields) => {
                fields.set_window(&problem);
                fields
            }
            None => fields.insert(SearchFields::new(&problem)),
        };
        for round in 0..params.sampling_rounds {
            for _ in 0..params.local_global_iterations {
                progress.report("synthesis", done as f64 / total_iterations as f64);
                timer.start("matching");
                let iteration_streams = streams.child("iteration", done as u64);
                let found = matching::match_all(&problem, fields, &state, &matches, match_settings, &iteration_streams);
                matches = found.iter().map(|m| m.location).collect();
                let exemplar_self: f64 = found.iter().map(|m| m.exemplar_self).sum();
                timer.start("merging");
                let evaluate =
                    |s: &State<D>, f: bool| evaluate_with(&problem, params.evaluator, s, &matches, exemplar_self, f);
                let allowed = |p: &Vector<D>| setup.allowed(p);
                let attributes = state.channels > 1 && merge_settings.attribute_iterations > 0;
                let (steps, last) =
                    merging::merge_positions(&mut state, merge_settings, attributes, &evaluate, &allowed);
                let discrete = &setup.attributes.discrete;
                let after = merging::merge_attributes(&mut state, merge_settings, discrete, Some(last), &evaluate)
                    .unwrap_or_else(|| steps.last().copied().unwrap_or(f64::NAN));
                energies.push(IterationEnergy {
                    scale,
                    neighbourhood: delta,
                    round,
                    after_matching: steps[0],
                    after_merging: after,
                    merge_steps: steps.len() - 1,
                    points: state.positions.len(),
                    added: 0,
                    removed: 0,
                });
                final_energy = after;
                done += 1;
            }
            if params.sampling_control {
                timer.start("sampling control");
                let allowed = |p: &Vector<D>| setup.allowed(p);
                let outcome = sampling::control(
                    &problem,
                    &setup.exemplar,
                    &mut state,
                    &matches,
                    params.sampling_threshold,
                    bounds,
                    &allowed,
                );
                if let Some(last) = energies.last_mut() {
                    last.added = outcome.added;
                    last.removed = outcome.removed;
                }
                added += outcome.added;
                removed += outcome.removed;
                rejected += outcome.rejected;
                held_by_bound += outcome.held_by_bound;
            }
        }
    }
    progress.report("synthesis", 1.0);
    timer.start("fidelity");
    let fidelity = measure_fidelity(&setup, &state.positions, params.seed);
    let points = to_point_set(&setup, &state);
    let fixed_points = state.units.iter().filter(|u| u.frozen).map(|u| u.points.len()).sum();
    let stages_ms = timer.finish();
    Ok(Output {
        points,
        report: Report {
            sigma: setup.sigma,
            neighbourhood: setup.delta,
            quadrature_points: setup.quadrature.len(),
            initial_points,
            final_points: state.positions.len(),
            added,
            removed,
            rejected,
            held_by_bound,
            expected_points: setup.expected_points,
            discrete_attributes: setup
                .attributes
                .names
                .iter()
                .enumerate()
                .filter(|(c, _)| !setup.attributes.discrete[c + 1].is_empty())
                .map(|(_, n)| n.clone())
                .collect(),
            energy: energies,
            final_energy,
            fixed_points,
            fidelity,
            stages_ms,
        },
    })
}

/// The count bounds of sampling control, on the points it may add or remove (those not frozen):
/// the count the exemplar's density asks for over the quadrature domain (which, in a progressive
/// synthesis, is the new region and the band of existing points that may move) ± `tolerance`.
fn count_bounds<const D: usize>(setup: &Setup<D>, tolerance: f64) -> sampling::CountBounds {
    sampling::CountBounds {
        least: ((1.0 - tolerance) * setup.expected_points).ceil() as usize,
        most: ((1.0 + tolerance) * setup.expected_points).floor() as usize,
    }
}

/// The output's fidelity figures, in output units: the exemplar is scaled by the domain's mean scale.
fn measure_fidelity<const D: usize>(setup: &Setup<D>, output: &[Vector<D>], seed: u64) -> Fidelity {
    let quadrature = &setup.quadrature;
    let scale = quadrature.scale.iter().sum::<f64>() / quadrature.len().max(1) as f64;
    let exemplar: Vec<Vector<D>> = setup.exemplar.positions.iter().map(|p| linear::scale(p, scale)).collect();
    let region = &setup.region;
    let (low, high) = region.bounds();
    let volume = region.volume().unwrap_or(quadrature.len() as f64 * quadrature.spacing().powi(D as i32));
    let domain = fidelity::Domain {
        contains: &|p: &Vector<D>| region.contains(p),
        depth: &|p: &Vector<D>| region.depth(p),
        low,
        high,
        volume,
    };
    fidelity::compare(&exemplar, output, &domain, setup.exemplar.spacing * scale, seed)
}

fn to_point_set<const D: usize>(setup: &Setup<D>, state: &State<D>) -> PointSet {
    let map = &setup.attributes;
    let mut positions = Vec::with_capacity(state.positions.len() * D);
    let mut attributes = Vec::with_capacity(state.positions.len() * map.names.len());
    for (i, p) in state.positions.iter().enumerate() {
        positions.extend_from_slice(p);
        let f = state.feature(i);
        for c in 0..map.names.len() {
            let allowed = &map.discrete[c + 1];
            let value = match allowed.iter().position(|&a| a == f[c + 1]) {
                // A snapped label: the exemplar's own value, without the round trip's rounding.
                Some(index) => map.discrete_values[c + 1][index],
                None => f[c + 1] / map.factor[c] + map.mean[c],
            };
            attributes.push(value);
        }
    }
    PointSet {
        dimension: D,
        positions,
        attribute_names: map.names.clone(),
        attributes,
        elements: setup.has_elements.then(|| state.element_id.clone()),
    }
}

/// One prepared evaluation problem of a given dimension (see [`EnergyCase`]).
struct PreparedCase<const D: usize> {
    setup: Setup<D>,
    matches: Vec<Vector<D>>,
    exemplar_self: f64,
    delta: f64,
    params: Params,
}

impl<const D: usize> PreparedCase<D> {
    fn new(input: &Input, params: &Params) -> Result<Self, Error> {
        let streams = SeedStreams::new(params.seed);
        let mut setup = prepare::<D>(input, params)?;
        setup.initialize(params, &streams.child("initialize", 0));
        let delta = setup.delta;
        let problem = setup.problem(delta, params);
        let fields = SearchFields::new(&problem);
        let settings =
            MatchSettings { starts: params.matching_starts, iterations: params.matching_iterations, polish: 0 };
        let found = matching::match_all(&problem, &fields, &setup.state, &[], settings, &streams);
        let matches = found.iter().map(|m| m.location).collect();
        let exemplar_self = found.iter().map(|m| m.exemplar_self).sum();
        Ok(Self { setup, matches, exemplar_self, delta, params: params.clone() })
    }

    fn evaluate(&self, evaluator: Evaluator, attributes: bool) -> f64 {
        let problem = self.setup.problem(self.delta, &self.params);
        evaluate_with(&problem, evaluator, &self.setup.state, &self.matches, self.exemplar_self, attributes).energy
    }
}

enum PreparedAny {
    Two(PreparedCase<2>),
    Three(PreparedCase<3>),
}

/// The initialized output of a synthesis after its first matching step, ready for timing single
/// evaluations of T (the merging step's unit of work) with either implementation: for benchmarks
/// and the speed-up figure.
pub struct EnergyCase {
    prepared: PreparedAny,
}

impl EnergyCase {
    /// Validates, prepares and initializes as [`synthesize`] does, then matches once.
    pub fn new(input: &Input, params: &Params) -> Result<Self, Error> {
        validate(input, params)?;
        let prepared = match input.exemplar.dimension {
            2 => PreparedAny::Two(PreparedCase::new(input, params)?),
            _ => PreparedAny::Three(PreparedCase::new(input, params)?),
        };
        Ok(Self { prepared })
    }

    /// T with its position gradient (and, with `attributes`, the attribute form) by `evaluator`.
    pub fn evaluate(&self, evaluator: Evaluator, attributes: bool) -> f64 {
        match &self.prepared {
            PreparedAny::Two(case) => case.evaluate(evaluator, attributes),
            PreparedAny::Three(case) => case.evaluate(evaluator, attributes),
        }
    }

    /// Output points of the initialized state.
    pub fn points(&self) -> usize {
        match &self.prepared {
            PreparedAny::Two(case) => case.setup.state.positions.len(),
            PreparedAny::Three(case) => case.setup.state.positions.len(),
        }
    }

    /// Quadrature points.
    pub fn quadrature_points(&self) -> usize {
        match &self.prepared {
            PreparedAny::Two(case) => case.setup.quadrature.len(),
            PreparedAny::Three(case) => case.setup.quadrature.len(),
        }
    }
}

fn compare(input: &Input, params: &Params) -> Result<EvaluatorComparison, Error> {
    let case = EnergyCase::new(input, params)?;
    // The fastest of three runs each (the first may pay for cold caches or thread start-up).
    let mut fast_ms = f64::INFINITY;
    let mut reference_ms = f64::INFINITY;
    let mut energies = (0.0, 0.0);
    for _ in 0..3 {
        let start = Clock::now();
        energies.0 = case.evaluate(Evaluator::Fast, false);
        fast_ms = fast_ms.min(start.elapsed().as_secs_f64() * 1000.0);
        let start = Clock::now();
        energies.1 = case.evaluate(Evaluator::Reference, false);
        reference_ms = reference_ms.min(start.elapsed().as_secs_f64() * 1000.0);
    }
    Ok(EvaluatorComparison {
        points: case.points(),
        quadrature_points: case.quadrature_points(),
        fast_ms,
        reference_ms,
        fast_energy: energies.0,
        reference_energy: energies.1,
    })
}
