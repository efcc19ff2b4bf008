//! `points` jobs: repetitive structures from point samples (`motif_points`).
//!
//! Field names are the flags of `motif points` (kebab-case). An option left out takes the engine's
//! default ([`motif_points::Params::default`]); only the domain is required (δ is inferred from the exemplar when not given).

use std::collections::BTreeMap;

use motif_core::error::number;
use motif_core::{InvalidParameter, Progress, ToneMap};
use motif_points::{Domain, Evaluator, Field, Initialization, Input, Params, Refinement, SurfaceDirections, Window};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value, json};

/// The engine's types that points inputs and runs are made of (and the surface reconstruction of
/// a synthesized set with normals), named here so that front ends need no engine crate.
pub use motif_points::{Fidelity, Output, PointSet, reconstruct_surface};

use crate::JobError;

/// Where the structure grows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum DomainSpec {
    /// A box from the origin: `[W, H]` (2D) or `[W, H, D]` (3D).
    Box(Vec<f64>),
    /// A polygon region (2D): its outline, `[[x, y], ...]`.
    Region(Vec<[f64; 2]>),
    /// A brush stroke: a polyline (2D or 3D) filled over `width`.
    Stroke(StrokeSpec),
    /// The inside of a closed triangle mesh (3D): `{"vertices": [[x, y, z], ...], "triangles":
    /// [[i, j, k], ...]}`.
    Volume(motif_core::TriangleMesh),
    /// The surface of a triangle mesh, for a 2D exemplar (the output is 3D): `{"mesh": {...},
    /// "directions": "curvature" | {"constant": [x, y, z]} | {"per-vertex": [[x, y, z], ...]}}`.
    Surface(SurfaceSpec),
}

/// A surface domain of [`DomainSpec::Surface`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct SurfaceSpec {
    /// The mesh, as for a volume.
    pub mesh: motif_core::TriangleMesh,
    /// Where the exemplar's x axis points on the surface (default: least curvature).
    #[serde(default)]
    pub directions: DirectionsSpec,
}

/// The orientation field of a surface domain.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum DirectionsSpec {
    /// The principal direction of least curvature.
    #[default]
    Curvature,
    /// One direction, projected on each tangent plane.
    Constant([f64; 3]),
    /// One vector per mesh vertex.
    PerVertex(Vec<[f64; 3]>),
}

impl DirectionsSpec {
    /// The engine's surface directions.
    pub fn engine(&self) -> SurfaceDirections {
        match self {
            DirectionsSpec::Curvature => SurfaceDirections::Curvature,
            DirectionsSpec::Constant(v) => SurfaceDirections::Constant(*v),
            DirectionsSpec::PerVertex(vectors) => SurfaceDirections::PerVertex(vectors.clone()),
        }
    }
}

impl DomainSpec {
    /// Checks a mesh domain before anything runs: a volume's mesh must enclose space, a
    /// surface's mesh must have faces its directions can be drawn on (one vector per vertex when
    /// given per vertex). Other domains pass: a job checks them when it runs.
    pub fn check_mesh(&self) -> Result<(), JobError> {
        match self {
            DomainSpec::Volume(mesh) => motif_points::check_volume_mesh(mesh)?,
            DomainSpec::Surface(surface) => {
                motif_points::check_surface_mesh(&surface.mesh, &surface.directions.engine())?
            }
            _ => {}
        }
        Ok(())
    }
}

/// A brush stroke of [`DomainSpec::Stroke`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct StrokeSpec {
    /// The stroke's points, `[[x, y(, z)], ...]`; the exemplar's x axis follows its tangent.
    pub points: Vec<Vec<f64>>,
    /// Brush width (output units, > 0).
    pub width: f64,
    /// Exemplar scale at the start and the end, varying linearly (default `[1, 1]`).
    #[serde(default)]
    pub scale_along: Option<[f64; 2]>,
}

fn default_seed() -> u64 {
    1
}

crate::choice_option!(Initialization: "random", "patches");
crate::choice_option!(Refinement: "seams", "everywhere", "none");
crate::choice_option!(Window: "gaussian", "box");

crate::declare_options! {
    /// Every option of `motif points` that is neither a file nor the domain, declared once.
    pub struct PointsOptions {
        /// Neighbourhood size δ in exemplar units (> 0): the width of the Gaussian window
        /// (truncated at --window-cutoff × δ) or the radius of the box window. Larger keeps larger
        /// structures; it shrinks to δ/2 during the synthesis. Default: 4 times the exemplar's mean
        /// nearest-neighbour spacing in 2D, 2 times in 3D (reported as `neighbourhood` and
        /// `exemplar_spacing`); continuous structures such as contours need about the size of
        /// their features.
        [value_name: "DELTA"]
        neighbourhood: Option<f64> = DEFAULTS.neighbourhood,
        /// Refuse domains that ask for more points than this at the exemplar's density (a guard
        /// against a unit mix-up; about 2 minutes of work per 150 000 points on two cores).
        [value_name: "N", range: (1.0, 1e8)]
        max_points: usize = DEFAULTS.max_points,
        /// Initialization: exemplar patches (default; each starts matched to where it came from) or
        /// random points (the paper's robustness claim does not hold on real, irregular exemplars).
        [value_name: "random|patches"]
        init: Initialization = DEFAULTS.initialization,
        /// Side of the copied patches, in units of the neighbourhood δ (capped at 0.7 of the
        /// exemplar's smallest side).
        [value_name: "F", range: (1.0, 20.0)]
        patch_size: f64 = DEFAULTS.patch_size,
        /// Candidate sources judged for each patch: the one whose surroundings agree best with the
        /// points already placed around the patch is copied. 1 copies a random source.
        [value_name: "N", range: (1.0, 256.0)]
        patch_candidates: usize = DEFAULTS.patch_candidates,
        /// Balancing of patch sources (0 takes the best-scored candidate): of the candidates scored
        /// within this fraction of the best, the one whose exemplar points were copied least so far
        /// is taken, so that every part of the exemplar is copied about equally often.
        [value_name: "F", range: (0.0, 10.0)]
        patch_balance: f64 = DEFAULTS.patch_balance,
        /// Which points the optimization moves after a patch initialization: the seams between
        /// patches (default; on real exemplars moving the copies' interiors lowered fidelity), every
        /// point, or none (the patches are the output).
        [value_name: "seams|everywhere|none"]
        refine: Refinement = DEFAULTS.refinement,
        /// Gradient steps of the pair-statistics refinement after the optimization (0 turns it off):
        /// the points the optimization moved move again so that the output's pair distances and
        /// nearest-neighbour distances follow the exemplar's. Flat domains at a uniform scale only.
        [value_name: "N", range: (0.0, 1000.0)]
        statistics_iterations: usize = DEFAULTS.statistics_iterations,
        /// The window the exemplar was observed in: `W,H[,D]` from the origin, or its corners
        /// `X0,Y0,X1,Y1` (`X0,Y0,Z0,X1,Y1,Z1` in 3D). It must hold every point. The exemplar's
        /// density is its count over this window; without it, the bounding box grown by one mean
        /// spacing per axis (right for lattices, too dense for sparse irregular patterns).
        [value_name: "W,H[,D]"]
        exemplar_window: Option<Vec<f64>> = None,
        /// Attributes to synthesize (default: every float column other than x, y, z, element, plus
        /// integer columns).
        [value_name: "a,b,..."]
        attributes: Option<Vec<String>> = None,
        /// Attributes with discrete values (snapped to the exemplar's values after each step).
        /// Integer columns are always discrete.
        [value_name: "a,b,..."]
        discrete: Vec<String> = Vec::new(),
        /// Attributes never treated as discrete. Without it, attributes whose exemplar values are
        /// all whole numbers (at most 32 distinct) are detected as discrete labels.
        [value_name: "a,b,..."]
        continuous: Vec<String> = Vec::new(),
        /// Weight of an attribute against point density, `NAME=W` (repeatable). Every attribute is
        /// divided by its exemplar standard deviation first, so units and ranges do not matter; the
        /// default weight is 1.
        [value_name: "NAME=W", range: (0.0, 100.0)]
        attribute_weight: BTreeMap<String, f64> = BTreeMap::new(),
        /// Window shape: Gaussian, truncated at --window-cutoff × δ, or the box |s| < δ.
        [value_name: "gaussian|box"]
        window: Window = DEFAULTS.window,
        /// Gaussian width σ (exemplar units, > 0). Default: half the exemplar's mean
        /// nearest-neighbour spacing.
        [value_name: "SIGMA"]
        sigma: Option<f64> = DEFAULTS.sigma,
        /// Uniform rotation field in degrees (counter-clockwise in the xy-plane), added to a
        /// stroke's tangent orientation.
        [value_name: "DEG"]
        rotation: f64 = 0.0,
        /// Uniform scale field (> 0), multiplied with --scale-along.
        [value_name: "S"]
        scale: f64 = 1.0,
        /// Quadrature grid spacing in units of σ (2 = the exemplar's point spacing). Default: 2, or
        /// an eighth of the neighbourhood when that is coarser (wide windows).
        [value_name: "H", range: (0.25, 4.0)]
        quadrature_spacing: Option<f64> = DEFAULTS.quadrature_spacing,
        /// Truncation radius of the Gaussian window, in units of the neighbourhood δ (its weight
        /// there is exp(-c²)). Smaller is faster.
        [value_name: "C", range: (1.5, 4.0)]
        window_cutoff: f64 = DEFAULTS.window_cutoff,
        /// Sampling-control rounds per window size.
        [value_name: "N", range: (1.0, 20.0)]
        sampling_rounds: usize = DEFAULTS.sampling_rounds,
        /// Gradient iterations of each position merging step (§7.1 uses 30).
        [value_name: "N", range: (1.0, 1000.0)]
        merge_iterations: usize = DEFAULTS.merge_iterations,
        /// Random starts of each quadrature point's matching search.
        [value_name: "N", range: (1.0, 64.0)]
        matching_starts: usize = DEFAULTS.matching_starts,
        /// Descent iterations per matching start.
        [value_name: "N", range: (1.0, 200.0)]
        matching_iterations: usize = DEFAULTS.matching_iterations,
        /// Window shrink factor per scale α. Default: 0.9 (§7.1), or 0.8 after patches with
        /// --refine seams (the same fidelity in less time on the real-data corpus).
        [value_name: "ALPHA", range: (0.5, 0.99)]
        shrink: Option<f64> = DEFAULTS.shrink,
        /// Turn sampling control (adding and removing points, Eq. 7) off.
        no_sampling_control: bool = !DEFAULTS.sampling_control,
        /// Let continuous attributes leave the exemplar's range. By default each stays between the
        /// exemplar's smallest and largest value of it (no negative diameters from a fit).
        attributes_beyond_range: bool = !DEFAULTS.attributes_within_range,
        /// Use the plain reference implementation of the energy (slow; for comparisons).
        reference: bool = false,
        /// Progressive synthesis: existing points farther than this from the new domain stay fixed
        /// (output units; default 3δ).
        [value_name: "M", range: (0.0, f64::MAX), requires: "existing"]
        keep_margin: Option<f64> = DEFAULTS.keep_margin,
    }
}

/// The engine's defaults, which the options take theirs from.
const DEFAULTS: Params = Params::DEFAULT;

/// A points job: the domain, the run's seed and memory bound, and
/// every other option ([`PointsOptions`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "crate::options::Described<PointsJobFields>")]
pub struct PointsJob {
    /// Where the output grows.
    pub domain: DomainSpec,
    /// Seed of every random choice (default 1, as on the command line).
    pub seed: u64,
    /// Refuse runs whose estimated peak memory passes this: bytes, or a size such as `"8G"`
    /// (default: the engine's, 4 GiB; the CLI passes half of the machine's memory).
    #[serde(rename = "max-memory")]
    pub max_memory: Option<u64>,
    /// Every other option.
    #[serde(flatten)]
    pub options: PointsOptions,
}

/// The fields of a [`PointsJob`] outside its options, as a description holds them.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub struct PointsJobFields {
    domain: DomainSpec,
    #[serde(default = "default_seed")]
    seed: u64,
    #[serde(default, deserialize_with = "crate::memory_size::optional")]
    max_memory: Option<u64>,
}

impl TryFrom<crate::options::Described<PointsJobFields>> for PointsJob {
    type Error = String;
    fn try_from(described: crate::options::Described<PointsJobFields>) -> Result<Self, String> {
        let (fields, options) = described.split()?;
        Ok(Self { domain: fields.domain, seed: fields.seed, max_memory: fields.max_memory, options })
    }
}

/// A finished points job.
#[derive(Debug, Clone)]
pub struct PointsRun {
    /// The engine's output (points and its `Report`).
    pub output: Output,
    /// The report's figures as one JSON object, the keys every front end writes.
    pub figures: Map<String, Value>,
}

impl PointsJob {
    /// A job with the neighbourhood δ and every option at its default.
    pub fn new(neighbourhood: f64, domain: DomainSpec) -> Self {
        let mut job = Self::with_domain(domain);
        job.options.neighbourhood = Some(neighbourhood);
        job
    }

    /// A job with δ inferred from the exemplar and every option at its default.
    pub fn with_domain(domain: DomainSpec) -> Self {
        Self { domain, seed: default_seed(), max_memory: None, options: PointsOptions::default() }
    }

    /// The engine's domain.
    pub fn engine_domain(&self) -> Result<Domain, JobError> {
        Ok(match &self.domain {
            DomainSpec::Box(sizes) => {
                if sizes.len() != 2 && sizes.len() != 3 {
                    let shown = sizes.iter().map(|&v| number(v)).collect::<Vec<_>>().join(",");
                    return Err(
                        InvalidParameter::new("domain", format!("box:{shown}"), "2 sizes (W,H) or 3 (W,H,D)").into()
                    );
                }
                Domain::Box { min: vec![0.0; sizes.len()], max: sizes.clone() }
            }
            DomainSpec::Region(outline) => {
                let points = outline.iter().map(|p| motif_core::Point::new(p[0], p[1])).collect();
                let polygon = motif_core::Polygon::new(points).map_err(|error| {
                    InvalidParameter::new("domain", format!("a region of {} points", outline.len()), error.to_string())
                })?;
                Domain::Polygon(polygon)
            }
            DomainSpec::Stroke(stroke) => {
                let [scale_start, scale_end] = stroke.scale_along.unwrap_or([1.0, 1.0]);
                Domain::Stroke(motif_points::BrushStroke {
                    points: stroke.points.clone(),
                    width: stroke.width,
                    scale_start,
                    scale_end,
                })
            }
            DomainSpec::Volume(mesh) => Domain::Volume(mesh.clone()),
            DomainSpec::Surface(surface) => {
                Domain::Surface { mesh: surface.mesh.clone(), directions: surface.directions.engine() }
            }
        })
    }

    /// The engine's parameters for an exemplar of `dimension` whose `integer_columns` (labels read
    /// as integers) are discrete unless listed as continuous or left out of `attributes`.
    pub fn params(&self, dimension: usize, integer_columns: &[String]) -> Result<Params, JobError> {
        use crate::options::Declared;
        let options = &self.options;
        options.check_ranges()?;
        let mut discrete = options.discrete.clone();
        for name in integer_columns {
            let used = options.attributes.as_ref().is_none_or(|list| list.contains(name));
            if used && !discrete.contains(name) && !options.continuous.contains(name) {
                discrete.push(name.clone());
            }
        }
        let exemplar_window = match &options.exemplar_window {
            None => None,
            Some(values) if values.len() == dimension => Some((vec![0.0; dimension], values.clone())),
            Some(values) if values.len() == 2 * dimension => {
                Some((values[..dimension].to_vec(), values[dimension..].to_vec()))
            }
            Some(values) => {
                let shown = values.iter().map(|&v| number(v)).collect::<Vec<_>>().join(",");
                let allowed =
                    format!("{dimension} sizes or {} corner values for a {dimension}D exemplar", 2 * dimension);
                return Err(InvalidParameter::new("exemplar-window", shown, allowed).into());
            }
        };
        let params = Params::DEFAULT
            .with_neighbourhood(options.neighbourhood)
            .with_window(options.window)
            .with_sigma(options.sigma)
            .with_rotation(Some(options.rotation).filter(|&r| r != 0.0).map_or(Field::Unset, Field::Uniform))
            .with_scale(Some(options.scale).filter(|&s| s != 1.0).map_or(Field::Unset, Field::Uniform))
            .with_quadrature_spacing(options.quadrature_spacing)
            .with_sampling_rounds(options.sampling_rounds)
            .with_merge_iterations(options.merge_iterations)
            .with_window_cutoff(options.window_cutoff)
            .with_matching_starts(options.matching_starts)
            .with_matching_iterations(options.matching_iterations)
            .with_shrink(options.shrink)
            .with_sampling_control(!options.no_sampling_control)
            .with_attributes_within_range(!options.attributes_beyond_range)
            .with_evaluator(if options.reference { Evaluator::Reference } else { Evaluator::Fast })
            .with_initialization(options.init)
            .with_attributes(options.attributes.clone())
            .with_discrete_attributes(discrete)
            .with_patch_size(options.patch_size)
            .with_patch_candidates(options.patch_candidates)
            .with_patch_balance(options.patch_balance)
            .with_refinement(options.refine)
            .with_statistics_iterations(options.statistics_iterations)
            .with_exemplar_window(exemplar_window)
            .with_continuous_attributes(options.continuous.clone())
            .with_attribute_weights(options.attribute_weight.iter().map(|(name, w)| (name.clone(), *w)).collect())
            .with_keep_margin(options.keep_margin)
            .with_max_points(options.max_points)
            .with_max_memory(self.max_memory.unwrap_or(DEFAULTS.max_memory))
            .with_seed(self.seed);
        params.validate()?;
        Ok(params)
    }
}

/// The decoded inputs of a points job.
#[derive(Debug, Clone)]
pub struct PointsInputs<'a> {
    /// The exemplar.
    pub exemplar: PointSet,
    /// A previous result to extend (`--existing`).
    pub existing: Option<PointSet>,
    /// The exemplar's integer columns (see [`PointsJob::params`]).
    pub integer_columns: &'a [String],
    /// Rotation and scale maps painted as images (2D).
    pub maps: FieldMaps,
}

impl PointsInputs<'_> {
    /// The exemplar alone: nothing to extend, no integer columns, no maps.
    pub fn new(exemplar: PointSet) -> Self {
        Self { exemplar, existing: None, integer_columns: &[], maps: FieldMaps::default() }
    }
}

impl crate::Job for PointsJob {
    const NAME: &'static str = "points";
    const FIELDS: &'static [&'static str] = &["domain", "seed", "max-memory"];
    const SUMMARY: &'static str = "Grow a repetitive structure of points with attributes, in 2D or 3D";
    const DETAILS: &'static str = "Discrete elements, continuous structures and mixtures, in boxes, regions, brush \
        strokes, mesh volumes or on mesh surfaces (Roveri et al. 2015).";
    type Options = PointsOptions;
    type Inputs<'a> = PointsInputs<'a>;
    type Run = PointsRun;

    fn run(&self, inputs: PointsInputs<'_>, progress: &mut dyn Progress) -> Result<PointsRun, JobError> {
        let PointsInputs { exemplar, existing, integer_columns, maps } = inputs;
        let mut params = self.params(exemplar.dimension, integer_columns)?;
        let domain = self.engine_domain()?;
        maps.apply(&domain, exemplar.dimension, &mut params)?;
        let input = Input { exemplar, domain, existing };
        let output = motif_points::synthesize(&input, &params, progress)?;
        let figures = figures(&output.report);
        Ok(PointsRun { output, figures })
    }
}

impl crate::Finished for PointsRun {
    fn figures(&self) -> &Map<String, Value> {
        &self.figures
    }
}

/// The figures of a points run under the keys of `motif points --report`.
pub fn figures(report: &motif_points::Report) -> Map<String, Value> {
    let value = json!({
        "command": "points",
        "estimated_memory_bytes": report.estimated_memory_bytes,
        "stages_ms": crate::stages(&report.stages_ms),
        "energy_per_iteration": report.energy,
        "final_energy": report.final_energy,
        "points_added": report.added,
        "points_removed": report.removed,
        "proposals_rejected": report.rejected,
        "proposals_held_by_count_bound": report.held_by_bound,
        "expected_points": report.expected_points,
        "discrete_attributes": report.discrete_attributes,
        "initial_points": report.initial_points,
        "output_points": report.final_points,
        "fixed_points": report.fixed_points,
        "patch_interior_points": report.patch_interior_points,
        "patch_usage_variation": report.patch_usage_variation,
        "pair_statistics": report.pair_statistics,
        "shrink": report.shrink,
        "sigma": report.sigma,
        "neighbourhood": report.neighbourhood,
        "neighbourhood_inferred": report.neighbourhood_inferred,
        "exemplar_spacing": report.exemplar_spacing,
        "quadrature_points": report.quadrature_points,
        "fidelity": report.fidelity,
    });
    let mut figures = crate::object(value);
    if let Some(surface) = &report.surface {
        figures.insert("surface".into(), serde_json::json!(surface));
    }
    figures
}

/// Rotation and scale fields painted as grey images (2D domains), stretched over the domain's
/// bounding box (same aspect ratio within 2 %). Encoding: rotation `360° × grey` (black and white
/// 0°, mid-grey 180°; counter-clockwise, added to the uniform `rotation`; pixels are blended as
/// directions, so black next to white stays 0°), scale `2^(2·grey − 1)`
/// (black 0.5, mid-grey 1, white 2; times the uniform `scale`).
#[derive(Debug, Clone, Default)]
pub struct FieldMaps {
    /// The rotation map (`--rotation-map`).
    pub rotation: Option<ToneMap>,
    /// The scale map (`--scale-map`).
    pub scale: Option<ToneMap>,
}

impl FieldMaps {
    /// Turns the maps into the parameters' rotation and scale fields over `domain`.
    pub fn apply(&self, domain: &Domain, dimension: usize, params: &mut Params) -> Result<(), JobError> {
        if self.rotation.is_none() && self.scale.is_none() {
            return Ok(());
        }
        let name = if self.rotation.is_some() { "rotation-map" } else { "scale-map" };
        if dimension != 2 || matches!(domain, Domain::Surface { .. }) {
            let given = if dimension != 2 { format!("with a {dimension}D exemplar") } else { "on a surface".into() };
            return Err(InvalidParameter::new(
                name,
                given,
                "a 2D exemplar and domain (on a surface, give the surface's directions instead)",
            )
            .into());
        }
        let bounds = domain_bounds(domain);
        let uniform = |field: &Field, default: f64| field.value(&[0.0, 0.0], default);
        if let Some(map) = &self.rotation {
            map.check_fits(&bounds, "rotation-map")?;
            let (map, base) = (map.clone(), uniform(&params.rotation, 0.0));
            params.rotation = Field::Custom(std::sync::Arc::new(move |p: &[f64]| {
                base + 360.0 * map.turn_at(&bounds, motif_core::Point::new(p[0], p[1]))
            }));
        }
        if let Some(map) = &self.scale {
            map.check_fits(&bounds, "scale-map")?;
            let (map, base) = (map.clone(), uniform(&params.scale, 1.0));
            params.scale = Field::Custom(std::sync::Arc::new(move |p: &[f64]| {
                let grey = map.grey_at(&bounds, motif_core::Point::new(p[0], p[1]));
                base * motif_core::math::powf(2.0, 2.0 * grey - 1.0)
            }));
        }
        Ok(())
    }
}

/// The bounding box of a 2D domain (a stroke's polyline widened by half its width).
fn domain_bounds(domain: &Domain) -> motif_core::kurbo::Rect {
    use motif_core::kurbo::Rect;
    match domain {
        Domain::Box { min, max } => Rect::new(min[0], min[1], max[0], max[1]),
        Domain::Polygon(polygon) => polygon.bounds(),
        Domain::Stroke(stroke) => {
            let half = 0.5 * stroke.width;
            let points: Vec<motif_core::Point> =
                stroke.points.iter().map(|p| motif_core::Point::new(p[0], p[1])).collect();
            motif_core::geometry::bounds_of(&points).inflate(half, half)
        }
        // 3D: refused before the bounds are asked for.
        Domain::Volume(_) | Domain::Surface { .. } => Rect::ZERO,
    }
}

mod syntax;

pub use syntax::{DOMAIN_SYNTAX, DomainArgument, parse_scale_along};

#[cfg(test)]
mod tests;
