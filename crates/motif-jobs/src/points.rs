//! `points` jobs: repetitive structures from point samples (`motif_points`).
//!
//! Field names are the flags of `motif points` (kebab-case). An option left out takes the engine's
//! default ([`motif_points::Params::default`]); only the neighbourhood and the domain are required.

use std::collections::BTreeMap;

use motif_core::error::number;
use motif_core::{InvalidParameter, Progress, ToneMap};
use motif_points::{
    Domain, Evaluator, Field, Initialization, Input, Output, Params, PointSet, Refinement, SurfaceDirections, Window,
};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value, json};

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

/// Every option of `motif points` that is not a file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct PointsJob {
    /// Neighbourhood size δ in exemplar units (> 0).
    pub neighbourhood: f64,
    /// Where the output grows.
    pub domain: DomainSpec,
    /// Seed of every random choice (default 1, as on the command line).
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Initialization: `patches` (default) or `random`.
    #[serde(default)]
    pub init: Option<Initialization>,
    /// Side of the copied patches in δ.
    #[serde(default)]
    pub patch_size: Option<f64>,
    /// Candidate sources judged per patch.
    #[serde(default)]
    pub patch_candidates: Option<usize>,
    /// Balancing of patch sources: tolerance above the best candidate's score (default 0.5).
    pub patch_balance: Option<f64>,
    /// Which points move after a patch initialization: `seams`, `everywhere` or `none`.
    #[serde(default)]
    pub refine: Option<Refinement>,
    /// Gradient steps of the pair-statistics refinement (default 40; 0 turns it off).
    #[serde(default)]
    pub statistics_iterations: Option<usize>,
    /// The exemplar's observation window: sizes from the origin (one per axis) or both corners.
    #[serde(default)]
    pub exemplar_window: Option<Vec<f64>>,
    /// Attributes to synthesize (default: all).
    #[serde(default)]
    pub attributes: Option<Vec<String>>,
    /// Attributes snapped to the exemplar's values.
    #[serde(default)]
    pub discrete: Vec<String>,
    /// Attributes never detected as discrete.
    #[serde(default)]
    pub continuous: Vec<String>,
    /// Per-attribute weights against point density.
    #[serde(default)]
    pub attribute_weight: BTreeMap<String, f64>,
    /// Window shape: `gaussian` or `box`.
    #[serde(default)]
    pub window: Option<Window>,
    /// Gaussian width σ (default half the exemplar's mean spacing).
    #[serde(default)]
    pub sigma: Option<f64>,
    /// Uniform rotation field, degrees (default 0).
    #[serde(default)]
    pub rotation: Option<f64>,
    /// Uniform scale field (default 1).
    #[serde(default)]
    pub scale: Option<f64>,
    /// Quadrature grid spacing in σ.
    #[serde(default)]
    pub quadrature_spacing: Option<f64>,
    /// Sampling-control rounds per window size.
    #[serde(default)]
    pub sampling_rounds: Option<usize>,
    /// Merging iterations per step.
    #[serde(default)]
    pub merge_iterations: Option<usize>,
    /// Truncation radius of the Gaussian window, in δ (default 3).
    #[serde(default)]
    pub window_cutoff: Option<f64>,
    /// Random starts of each quadrature point's matching search (default 5).
    #[serde(default)]
    pub matching_starts: Option<usize>,
    /// Descent iterations per matching start (default 8).
    #[serde(default)]
    pub matching_iterations: Option<usize>,
    /// Window shrink factor per scale.
    #[serde(default)]
    pub shrink: Option<f64>,
    /// Turn sampling control off.
    #[serde(default)]
    pub no_sampling_control: bool,
    /// Use the plain reference energy.
    #[serde(default)]
    pub reference: bool,
    /// Progressive synthesis: existing points farther than this from the new domain stay fixed.
    #[serde(default)]
    pub keep_margin: Option<f64>,
    /// Refuse domains that ask for more points than this.
    #[serde(default)]
    pub max_points: Option<usize>,
    /// Refuse runs whose estimated peak memory passes this: bytes, or a size such as `"8G"`
    /// (default: the engine's, 4 GiB; the CLI passes half of the machine's memory).
    #[serde(default, deserialize_with = "crate::memory_size::optional")]
    pub max_memory: Option<u64>,
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
    /// A job with every option at its default.
    pub fn new(neighbourhood: f64, domain: DomainSpec) -> Self {
        Self {
            neighbourhood,
            domain,
            seed: default_seed(),
            init: None,
            patch_size: None,
            patch_candidates: None,
            patch_balance: None,
            refine: None,
            statistics_iterations: None,
            exemplar_window: None,
            attributes: None,
            discrete: Vec::new(),
            continuous: Vec::new(),
            attribute_weight: BTreeMap::new(),
            window: None,
            sigma: None,
            rotation: None,
            scale: None,
            quadrature_spacing: None,
            sampling_rounds: None,
            merge_iterations: None,
            window_cutoff: None,
            matching_starts: None,
            matching_iterations: None,
            shrink: None,
            no_sampling_control: false,
            reference: false,
            keep_margin: None,
            max_points: None,
            max_memory: None,
        }
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
                Domain::Stroke(motif_points::Stroke {
                    points: stroke.points.clone(),
                    width: stroke.width,
                    scale_start,
                    scale_end,
                })
            }
            DomainSpec::Volume(mesh) => Domain::Volume(mesh.clone()),
            DomainSpec::Surface(surface) => Domain::Surface {
                mesh: surface.mesh.clone(),
                directions: match &surface.directions {
                    DirectionsSpec::Curvature => SurfaceDirections::Curvature,
                    DirectionsSpec::Constant(v) => SurfaceDirections::Constant(*v),
                    DirectionsSpec::PerVertex(vectors) => SurfaceDirections::PerVertex(vectors.clone()),
                },
            },
        })
    }

    /// The engine's parameters for an exemplar of `dimension` whose `integer_columns` (labels read
    /// as integers) are discrete unless listed as continuous or left out of `attributes`.
    pub fn params(&self, dimension: usize, integer_columns: &[String]) -> Result<Params, JobError> {
        let defaults = Params::default();
        let mut discrete = self.discrete.clone();
        for name in integer_columns {
            let used = self.attributes.as_ref().is_none_or(|list| list.contains(name));
            if used && !discrete.contains(name) && !self.continuous.contains(name) {
                discrete.push(name.clone());
            }
        }
        let exemplar_window = match &self.exemplar_window {
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
        let params = defaults
            .clone()
            .with_neighbourhood(Some(self.neighbourhood))
            .with_window(self.window.unwrap_or(defaults.window))
            .with_sigma(self.sigma)
            .with_rotation(self.rotation.filter(|&r| r != 0.0).map_or(Field::None, Field::Uniform))
            .with_scale(self.scale.filter(|&s| s != 1.0).map_or(Field::None, Field::Uniform))
            .with_quadrature_spacing(self.quadrature_spacing.or(defaults.quadrature_spacing))
            .with_sampling_rounds(self.sampling_rounds.unwrap_or(defaults.sampling_rounds))
            .with_merge_iterations(self.merge_iterations.unwrap_or(defaults.merge_iterations))
            .with_window_cutoff(self.window_cutoff.unwrap_or(defaults.window_cutoff))
            .with_matching_starts(self.matching_starts.unwrap_or(defaults.matching_starts))
            .with_matching_iterations(self.matching_iterations.unwrap_or(defaults.matching_iterations))
            .with_shrink(self.shrink)
            .with_sampling_control(!self.no_sampling_control)
            .with_evaluator(if self.reference { Evaluator::Reference } else { Evaluator::Fast })
            .with_initialization(self.init.unwrap_or(defaults.initialization))
            .with_attributes(self.attributes.clone())
            .with_discrete_attributes(discrete)
            .with_patch_size(self.patch_size.unwrap_or(defaults.patch_size))
            .with_patch_candidates(self.patch_candidates.unwrap_or(defaults.patch_candidates))
            .with_patch_balance(self.patch_balance.unwrap_or(defaults.patch_balance))
            .with_refinement(self.refine.unwrap_or(defaults.refinement))
            .with_statistics_iterations(self.statistics_iterations.unwrap_or(defaults.statistics_iterations))
            .with_exemplar_window(exemplar_window)
            .with_continuous_attributes(self.continuous.clone())
            .with_attribute_weights(self.attribute_weight.iter().map(|(name, w)| (name.clone(), *w)).collect())
            .with_keep_margin(self.keep_margin)
            .with_max_points(self.max_points.unwrap_or(defaults.max_points))
            .with_max_memory(self.max_memory.unwrap_or(defaults.max_memory))
            .with_seed(self.seed);
        params.validate()?;
        Ok(params)
    }

    /// Runs the job on decoded inputs: the exemplar, a previous result to extend, and the names
    /// of the exemplar's integer columns (see [`PointsJob::params`]).
    pub fn run(
        &self,
        exemplar: PointSet,
        existing: Option<PointSet>,
        integer_columns: &[String],
        progress: &mut dyn Progress,
    ) -> Result<PointsRun, JobError> {
        self.run_with_maps(exemplar, existing, integer_columns, &FieldMaps::default(), progress)
    }

    /// [`PointsJob::run`] with rotation and scale maps painted as images (2D), see [`FieldMaps`].
    pub fn run_with_maps(
        &self,
        exemplar: PointSet,
        existing: Option<PointSet>,
        integer_columns: &[String],
        maps: &FieldMaps,
        progress: &mut dyn Progress,
    ) -> Result<PointsRun, JobError> {
        let mut params = self.params(exemplar.dimension, integer_columns)?;
        let domain = self.engine_domain()?;
        maps.apply(&domain, exemplar.dimension, &mut params)?;
        let input = Input { exemplar, domain, existing };
        let output = motif_points::synthesize(&input, &params, progress)?;
        let figures = figures(&output.report);
        Ok(PointsRun { output, figures })
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
        "quadrature_points": report.quadrature_points,
        "fidelity": report.fidelity,
    });
    let mut figures = crate::object(value);
    if let Some(surface) = &report.surface {
        figures.insert("surface".into(), serde_json::json!(surface));
    }
    figures
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn painted_maps_become_rotation_and_scale_fields() {
        // Left half black, right half white (rotation), left black right mid-grey (scale).
        let rotation = ToneMap::from_grey(4, 2, vec![0.0, 0.0, 0.25, 0.25, 0.0, 0.0, 0.25, 0.25]).unwrap();
        let scale = ToneMap::from_grey(4, 2, vec![0.0, 0.0, 0.5, 0.5, 0.0, 0.0, 0.5, 0.5]).unwrap();
        let job = PointsJob { rotation: Some(10.0), ..PointsJob::new(2.0, DomainSpec::Box(vec![40.0, 20.0])) };
        let mut params = job.params(2, &[]).unwrap();
        let maps = FieldMaps { rotation: Some(rotation), scale: Some(scale) };
        maps.apply(&job.engine_domain().unwrap(), 2, &mut params).unwrap();
        assert!((params.rotation.value(&[2.0, 5.0], 0.0) - 10.0).abs() < 1e-9);
        assert!((params.rotation.value(&[38.0, 5.0], 0.0) - 100.0).abs() < 1e-9);
        assert!((params.scale.value(&[2.0, 5.0], 1.0) - 0.5).abs() < 1e-9);
        assert!((params.scale.value(&[38.0, 5.0], 1.0) - 1.0).abs() < 1e-9);
        // Maps need a 2D domain of their aspect ratio.
        let square = FieldMaps { scale: Some(ToneMap::from_grey(3, 3, vec![0.5; 9]).unwrap()), rotation: None };
        let error = square.apply(&job.engine_domain().unwrap(), 2, &mut params).unwrap_err().to_string();
        assert!(error.contains("scale-map") && error.contains("aspect"), "{error}");
        let job3 = PointsJob::new(2.0, DomainSpec::Box(vec![4.0, 4.0, 4.0]));
        let error = maps.apply(&job3.engine_domain().unwrap(), 3, &mut params).unwrap_err().to_string();
        assert!(error.contains("2D"), "{error}");
    }

    #[test]
    fn descriptions_use_the_flag_names_and_the_engine_defaults() {
        let job: PointsJob = serde_json::from_value(json!({
            "neighbourhood": 14,
            "domain": { "box": [400, 400] },
            "exemplar-window": [200, 200],
            "attribute-weight": { "dbh": 0.5 },
            "refine": "everywhere",
            "init": "random",
        }))
        .unwrap();
        let params = job.params(2, &["label".to_string()]).unwrap();
        assert_eq!(params.exemplar_window, Some((vec![0.0, 0.0], vec![200.0, 200.0])));
        assert_eq!(params.attribute_weights, vec![("dbh".to_string(), 0.5)]);
        assert_eq!(params.refinement, Refinement::Everywhere);
        assert_eq!(params.initialization, Initialization::Random);
        assert_eq!(params.discrete_attributes, vec!["label".to_string()]);
        assert_eq!(params.seed, 1);
        let defaults = Params::default();
        assert_eq!(params.patch_size, defaults.patch_size);
        assert_eq!(params.merge_iterations, defaults.merge_iterations);
        // Corners instead of sizes, and a round trip through JSON.
        let corners = PointsJob { exemplar_window: Some(vec![1.0, 2.0, 5.0, 6.0]), ..job.clone() };
        let params = corners.params(2, &[]).unwrap();
        assert_eq!(params.exemplar_window, Some((vec![1.0, 2.0], vec![5.0, 6.0])));
        let text = serde_json::to_string(&corners).unwrap();
        assert_eq!(serde_json::from_str::<PointsJob>(&text).unwrap(), corners);
        // max-memory as bytes or as a size people write; a round trip keeps it.
        let sized = |value: Value| {
            let mut description = json!({ "neighbourhood": 14, "domain": { "box": [400, 400] } });
            description["max-memory"] = value;
            serde_json::from_value::<PointsJob>(description)
        };
        assert_eq!(sized(json!("1.5G")).unwrap().params(2, &[]).unwrap().max_memory, 3 << 29);
        let bytes = sized(json!(1 << 24)).unwrap();
        assert_eq!(bytes.max_memory, Some(1 << 24));
        let text = serde_json::to_string(&bytes).unwrap();
        assert_eq!(serde_json::from_str::<PointsJob>(&text).unwrap(), bytes);
        assert!(sized(json!("8 parsecs")).unwrap_err().to_string().contains("not a size"));
        let tiny = sized(json!(1000)).unwrap().params(2, &[]).unwrap_err().to_string();
        assert!(tiny.contains("max-memory"), "{tiny}");
    }

    #[test]
    fn bad_descriptions_name_the_option() {
        let bad = |value: Value| serde_json::from_value::<PointsJob>(value).unwrap_err().to_string();
        assert!(bad(json!({ "neighbourhood": 1, "domain": { "box": [4, 4] }, "patchsize": 3 })).contains("patchsize"));
        assert!(bad(json!({ "domain": { "box": [4, 4] } })).contains("neighbourhood"));
        assert!(bad(json!({ "neighbourhood": 1, "domain": { "box": [4, 4] }, "refine": "most" })).contains("most"));
        let job = PointsJob::new(1.0, DomainSpec::Box(vec![4.0]));
        assert!(job.engine_domain().unwrap_err().to_string().contains("domain"));
        let job = PointsJob {
            exemplar_window: Some(vec![1.0, 2.0, 3.0]),
            ..PointsJob::new(1.0, DomainSpec::Box(vec![4.0, 4.0]))
        };
        assert!(job.params(2, &[]).unwrap_err().to_string().contains("exemplar-window"));
        let job = PointsJob { patch_size: Some(0.0), ..PointsJob::new(1.0, DomainSpec::Box(vec![4.0, 4.0])) };
        assert!(job.params(2, &[]).unwrap_err().to_string().contains("patch-size"));
    }
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
