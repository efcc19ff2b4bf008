//! Algorithm 1, the multi-scale local–global solver (§5.1): validation, the loop over window sizes,
//! the report; and single evaluations of T for benchmarks.

use motif_core::error::number;
use motif_core::timing::Clock;
use motif_core::{InvalidParameter, Progress, SeedStreams, StageTimer};
use serde::Serialize;

use crate::InputError;
use crate::energy::{Evaluation, Problem};
use crate::error::{DomainProblem, Error};
use crate::fidelity::Fidelity;
use crate::linear::Vector;
use crate::local_global::{Course, Solver, window_sizes};
use crate::matching::{self, MatchSettings, SearchFields};
use crate::merging::MergeSettings;
use crate::model::State;
use crate::pair_statistics::StatisticsRefinement;
use crate::params::{Domain, Evaluator, Input, Params};
use crate::setup::{Setup, count_bounds, measure_fidelity, prepare, to_point_set};
use crate::{PointSet, reference};

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
    /// The run's estimated peak memory, bytes (checked against `max-memory` before allocating).
    pub estimated_memory_bytes: u64,
    /// σ used (output units).
    pub sigma: f64,
    /// The starting window size δ.
    pub neighbourhood: f64,
    /// Whether δ was inferred from the exemplar (no neighbourhood given).
    pub neighbourhood_inferred: bool,
    /// The exemplar's mean nearest-neighbour spacing (exemplar units), which σ and an inferred δ
    /// are multiples of.
    pub exemplar_spacing: f64,
    /// The window shrink factor α used.
    pub shrink: f64,
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
    /// Points copied into patch interiors and kept as copied ([`Refinement::Seams`](crate::Refinement::Seams)).
    pub patch_interior_points: usize,
    /// How unevenly the patches copied the exemplar: the coefficient of variation of how many
    /// output points copy each exemplar point (0: all equally often, as in a tiled copy; `None`
    /// without patch initialization).
    pub patch_usage_variation: Option<f64>,
    /// The pair-statistics refinement after the optimization (`None` where it does not apply:
    /// surfaces, scale fields, `statistics_iterations` 0).
    pub pair_statistics: Option<StatisticsRefinement>,
    /// Structure fidelity on the interior.
    pub fidelity: Fidelity,
    /// Milliseconds per stage.
    pub stages_ms: Vec<(String, f64)>,
    /// On a surface domain: its area and how far the window trusts distances measured in 3D.
    pub surface: Option<SurfaceFigures>,
}

/// The synthesized points and the report.
#[derive(Debug, Clone)]
pub struct Output {
    /// Output points with the exemplar's (selected) attributes and, when it has elements, element ids.
    pub points: PointSet,
    /// Per output point, where the exemplar's axes point there, scaled: the columns of `s R` (a
    /// 2D synthesis's frames turn in the xy-plane, z stays z). An element's points share its
    /// pose. For placing an element mesh on each output element.
    pub frames: Vec<[[f64; 3]; 3]>,
    /// Figures.
    pub report: Report,
}

/// Figures of a surface domain.
#[derive(Debug, Clone, Serialize)]
pub struct SurfaceFigures {
    /// Area of the mesh (output units²).
    pub area: f64,
    /// The radius of curvature that 95 % of the vertices exceed in every direction (infinite
    /// for a plane): the smallest but for sharp tips and creases.
    pub curvature_radius: f64,
    /// The starting window δ over that radius. Neighbourhoods are measured in 3D, the distance
    /// along the surface to within `r³ / (24 R²)` for a radius `r` on a radius of curvature `R`:
    /// below about 0.5 the two agree to a few per cent over the window.
    pub window_over_radius: f64,
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
        return Err(Error::Input(InputError::TooFewPoints { count: exemplar.len() }));
    }
    let surface = matches!(input.domain, Domain::Surface { .. });
    if surface && exemplar.dimension != 2 {
        return Err(Error::Input(InputError::EmptyDomain(DomainProblem::SurfaceExemplar(exemplar.dimension))));
    }
    if let Some(existing) = &input.existing {
        existing.validate("existing points")?;
        // On a surface the output, and so the existing points, are 3D.
        let output_dimension = if surface { 3 } else { exemplar.dimension };
        if existing.dimension != output_dimension {
            return Err(Error::Input(InputError::DimensionMismatch {
                existing: existing.dimension,
                exemplar: output_dimension,
            }));
        }
    }
    params.validate()?;
    if let Some((low, high)) = &params.exemplar_window {
        check_exemplar_window(exemplar, low, high)?;
    }
    Ok(())
}

/// The window must have one lower and one upper value per axis, be finite and hold every point.
fn check_exemplar_window(exemplar: &PointSet, low: &[f64], high: &[f64]) -> Result<(), Error> {
    let d = exemplar.dimension;
    let shown = || {
        let corner = |c: &[f64]| c.iter().map(|&v| number(v)).collect::<Vec<_>>().join(",");
        format!("{} to {}", corner(low), corner(high))
    };
    let invalid = |allowed: String| Error::Parameter(InvalidParameter::new("exemplar-window", shown(), allowed));
    if low.len() != d || high.len() != d {
        return Err(invalid(format!("the exemplar is {d}D: it needs {d} lower and {d} upper values")));
    }
    if let Some(a) = (0..d).find(|&a| !(low[a].is_finite() && high[a].is_finite() && low[a] < high[a])) {
        return Err(invalid(format!("axis {a} needs finite values, the lower below the upper")));
    }
    for i in 0..exemplar.len() {
        let p = exemplar.position(i);
        if let Some(a) = (0..d).find(|&a| p[a] < low[a] || p[a] > high[a]) {
            return Err(invalid(format!(
                "it must hold every exemplar point; point {} is at {} on axis {a}",
                i + 1,
                number(p[a])
            )));
        }
    }
    Ok(())
}

/// Synthesizes a structure like `input.exemplar` over `params.domain` (§5, Algorithm 1).
pub fn synthesize(input: &Input, params: &Params, progress: &mut dyn Progress) -> Result<Output, Error> {
    validate(input, params)?;
    match (input.exemplar.dimension, &input.domain) {
        (_, Domain::Surface { .. }) => run::<3>(input, params, progress),
        (2, _) => run::<2>(input, params, progress),
        _ => run::<3>(input, params, progress),
    }
}

/// Times one evaluation of T and its position gradient with the fast and the reference
/// implementation on the initialized output (after one matching step).
pub fn compare_evaluators(input: &Input, params: &Params) -> Result<EvaluatorComparison, Error> {
    compare(input, params)
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
    let matches = setup.initialize(params, &streams.child("initialize", 0));
    setup.state.settle(|p| setup.region.keep_on(p));
    let initial_points = setup.state.positions.len();
    let thinned = crate::pair_statistics::thins(&setup, params.statistics_iterations);
    let bounds = count_bounds(&setup, params.count_tolerance, thinned);
    let state = std::mem::take(&mut setup.state);
    let solver = Solver {
        setup: &setup,
        params,
        streams: &streams,
        deltas: window_sizes(setup.delta, params),
        match_settings: MatchSettings {
            starts: params.matching_starts,
            iterations: params.matching_iterations,
            polish: params.matching_polish,
        },
        merge_settings: MergeSettings {
            iterations: params.merge_iterations,
            attribute_iterations: params.attribute_iterations,
            step: params.step,
            tolerance: params.tolerance,
            stagnation: params.stagnation,
            sigma: setup.sigma,
        },
        bounds,
    };
    let mut course = Course {
        state,
        matches,
        timer,
        energies: Vec::new(),
        added: 0,
        removed: 0,
        rejected: 0,
        held_by_bound: 0,
        final_energy: f64::NAN,
        done: 0,
    };
    solver.optimize(&mut course, progress);
    progress.report("synthesis", 1.0);
    finish(&setup, params, course, initial_points)
}

/// The last stages (the pair-statistics refinement, the fidelity figures) and the output with its
/// report.
fn finish<const D: usize>(
    setup: &Setup<D>,
    params: &Params,
    course: Course<D>,
    initial_points: usize,
) -> Result<Output, Error> {
    let Course { mut state, mut timer, energies, added, removed, rejected, held_by_bound, final_energy, .. } = course;
    timer.start("pair statistics");
    let mut stream = SeedStreams::new(params.seed).stream("relocation", 0);
    let pair_statistics = crate::pair_statistics::refine_state(
        setup,
        &mut state,
        params.statistics_iterations,
        params.count_tolerance,
        &mut stream,
    );
    timer.start("fidelity");
    let fidelity = measure_fidelity(setup, &state.positions, params.seed);
    let points = to_point_set(setup, &state);
    let frames = output_frames(setup, &state, params)?;
    let frozen: usize = state.units.iter().filter(|u| u.frozen).map(|u| u.points.len()).sum();
    let fixed_points = frozen - setup.patch_interiors;
    let stages_ms = timer.finish();
    Ok(Output {
        points,
        frames,
        report: Report {
            estimated_memory_bytes: setup.estimated_memory_bytes,
            sigma: setup.sigma,
            neighbourhood: setup.delta,
            neighbourhood_inferred: params.neighbourhood.is_none(),
            exemplar_spacing: setup.exemplar.spacing,
            shrink: params.effective_shrink(),
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
            patch_interior_points: setup.patch_interiors,
            patch_usage_variation: setup.patch_usage_variation,
            pair_statistics,
            fidelity,
            stages_ms,
            surface: surface_figures(setup),
        },
    })
}

/// On a surface domain: its area, its typical radius of curvature and the window over it.
fn surface_figures<const D: usize>(setup: &Setup<D>) -> Option<SurfaceFigures> {
    match &setup.region {
        crate::domain::Region::Surface { surface, .. } => {
            let radius = 1.0 / surface.typical_largest_curvature();
            Some(SurfaceFigures {
                area: surface.area(),
                curvature_radius: radius,
                window_over_radius: setup.delta / radius,
            })
        }
        _ => None,
    }
}

/// The frame `s R` at every output point (see [`Output::frames`]), promoted to 3 × 3.
fn output_frames<const D: usize>(
    setup: &crate::setup::Setup<D>,
    state: &crate::model::State<D>,
    params: &Params,
) -> Result<Vec<[[f64; 3]; 3]>, Error> {
    let promote = |m: &crate::linear::Matrix<D>, s: f64| -> [[f64; 3]; 3] {
        std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                if i < D && j < D {
                    s * m[i][j]
                } else if i == j {
                    s
                } else {
                    0.0
                }
            })
        })
    };
    let mut frames = vec![[[0.0; 3]; 3]; state.positions.len()];
    for unit in &state.units {
        let (position, rigid_rotation) = match &unit.rigid {
            Some(rigid) => (rigid.centre, Some(rigid.rotation)),
            None => (state.positions[unit.points[0] as usize], None),
        };
        let (rotation, scale) = setup.region.guided_frame(&position, &params.rotation, &params.scale)?;
        // A rigid element carries its own pose (its frame when placed, then its rotations).
        let frame = promote(&rigid_rotation.unwrap_or(rotation), scale);
        for &p in &unit.points {
            frames[p as usize] = frame;
        }
    }
    Ok(frames)
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

impl std::fmt::Debug for EnergyCase {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // The prepared case holds the whole solver state; its dimension says which it is.
        let dimension = match self.prepared {
            PreparedAny::Two(_) => 2,
            PreparedAny::Three(_) => 3,
        };
        f.debug_struct("EnergyCase").field("dimension", &dimension).finish_non_exhaustive()
    }
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
