//! `strokes` jobs: vector stroke patterns along a path or in a region (`motif_strokes`).
//!
//! Field names are the flags of `motif strokes`; only the target is required. The scale ε is
//! inferred from the reference strokes when a job leaves it out ([`motif_strokes::infer_scale`]).
//! Every option is declared once, in [`StrokesOptions`].
//! The reference strokes come decoded (the CLI reads them from SVG with its `--tolerance`).

use std::collections::BTreeMap;

use motif_core::error::number;
use motif_core::{InvalidParameter, Point, Polygon, Polyline, Progress};
use motif_strokes::{FitPoints, InferredScale, Input, Params, Thresholds};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value, json};

use crate::JobError;

mod records;
#[cfg(feature = "svg")]
mod svg;

/// The engine's types that strokes inputs and runs are made of, named here so that front ends
/// need no engine crate.
pub use motif_strokes::{Analysis, Output, Stroke, Target, ToneMap, region_from_outline};
pub use records::{StrokeRecord, strokes_from_json, strokes_to_json};
#[cfg(feature = "svg")]
pub use svg::{draw_stroke, reference_from_svg, strokes_svg};

/// Why reference strokes could not be read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ReferenceProblem {
    /// A path of the drawing cannot be read (its `id`, empty when it has none).
    #[error("path `{id}` of the reference cannot be read: {source}")]
    Path {
        /// The path's `id`.
        id: String,
        /// What is wrong with it.
        source: InvalidParameter,
    },
    /// A stroke record's width is not a finite number ≥ 0.
    #[error("reference stroke {index}: width {width} must be a finite number >= 0")]
    Width {
        /// 1-based position of the record.
        index: usize,
        /// The width given.
        width: f64,
    },
    /// The stroke records are not a JSON list of strokes.
    #[error("reference strokes: {0}")]
    Json(String),
    /// Nothing visible is left.
    #[error("the reference has no strokes: it needs at least one stroked or filled path with a length > 0")]
    Empty,
}

/// Where the pattern grows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum TargetSpec {
    /// Along a polyline (a 1D pattern): `[[x, y], ...]`, closed when its ends meet.
    Along(Vec<[f64; 2]>),
    /// Inside a simple polygon (a 2D pattern): its outline `[[x, y], ...]`.
    Region(Vec<[f64; 2]>),
    /// Inside the rectangle (0, 0)–(W, H): `[W, H]`.
    Rect([f64; 2]),
}

fn default_seed() -> u64 {
    1
}

crate::choice_option!(FitPoints: "skeleton", "contour");

crate::declare_options! {
    /// Every option of `motif strokes` that is neither a file (nor the flattening tolerance of
    /// one), the scale ε nor the target, declared once.
    pub struct StrokesOptions {
        /// Points the element boxes are fitted to: the strokes' skeletons (the default; each
        /// gesture's own polyline, ignoring its width) or their contours (the outline stroked at
        /// the stroke's width with round caps, so that thick strokes give thick boxes).
        [value_name: "skeleton|contour"]
        fit: FitPoints = DEFAULTS.fit,
        /// Neighbourhood size in rings of the neighbour graph (default: 5 along a path, 2 in a
        /// region).
        [value_name: "K", range: (1.0, 5.0)]
        rings: Option<usize> = DEFAULTS.rings,
        /// Parameter exchange amount: orientation, length, thickness and colour swapped with
        /// similar reference elements within this fraction of the matching thresholds; 0 copies
        /// exactly.
        [value_name: "V", range: (0.0, 1.0)]
        variation: f64 = DEFAULTS.variation,
        /// Reintroduce the reference's irregular spacing from its shift vectors.
        position_variation: bool = DEFAULTS.position_variation,
        /// Let elements overlap. By default an element whose ink meets an already placed one goes
        /// back to its seed, drops its variation, is swapped for another matching element, moves
        /// slightly, or is removed (the report's `overlap` says how many of each), unless the
        /// reference's own elements overlap.
        allow_overlaps: bool = !DEFAULTS.avoid_overlaps,
        /// Override matching thresholds: shape and sup in units of the mean element length L
        /// (defaults 0.1), par in radians (π/20), ov a length ratio > 1 (1.5), col an RGB distance
        /// in the unit cube (0.15), attr the largest difference of relative stroke width and dash
        /// period, opacity, filled or dashed share and fill colour (0.2). Example:
        /// shape=0.2,col=0.3.
        [value_name: "NAME=VALUE,..."]
        thresholds: ThresholdOverrides = ThresholdOverrides::default(),
        /// Lloyd relaxation iterations for the seeds (stops early once converged).
        [value_name: "N", range: (1.0, 1000.0)]
        lloyd_iterations: usize = DEFAULTS.lloyd_iterations,
    }
}

/// The engine's defaults, which the options take theirs from.
const DEFAULTS: Params = Params::DEFAULT;

/// The field of one matching threshold in the engine's thresholds.
type ThresholdField = fn(&mut Thresholds) -> &mut f64;

/// Each matching threshold's name in a job (`--thresholds shape=0.2`) and its engine field.
const THRESHOLDS: [(&str, ThresholdField); 6] = [
    ("shape", |t| &mut t.shape),
    ("par", |t| &mut t.parallelism),
    ("ov", |t| &mut t.overlap),
    ("sup", |t| &mut t.superimposition),
    ("col", |t| &mut t.colour),
    ("attr", |t| &mut t.attributes),
];

/// The matching thresholds a job sets, by name (`shape`, `par`, `ov`, `sup`, `col`, `attr`); the
/// others keep the engine's. Its serde form is a map, `{"shape": 0.2, "col": 0.3}` (on the
/// command line `shape=0.2,col=0.3`); other names are refused.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "BTreeMap<String, f64>", into = "BTreeMap<String, f64>")]
pub struct ThresholdOverrides(BTreeMap<String, f64>);

impl ThresholdOverrides {
    /// The value set for the threshold `name`, if any.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.0.get(name).copied()
    }

    /// `thresholds` with the ones set here replaced.
    pub fn applied_to(&self, mut thresholds: Thresholds) -> Thresholds {
        for (name, field) in THRESHOLDS {
            if let Some(value) = self.get(name) {
                *field(&mut thresholds) = value;
            }
        }
        thresholds
    }
}

impl TryFrom<BTreeMap<String, f64>> for ThresholdOverrides {
    type Error = InvalidParameter;
    fn try_from(values: BTreeMap<String, f64>) -> Result<Self, InvalidParameter> {
        let unknown = values.iter().find(|(name, _)| !THRESHOLDS.iter().any(|(known, _)| known == name));
        if let Some((name, &value)) = unknown {
            let shown = format!("{name}={}", number(value));
            return Err(InvalidParameter::new(
                "thresholds",
                shown,
                "a threshold named shape, par, ov, sup, col or attr",
            ));
        }
        Ok(Self(values))
    }
}

impl From<ThresholdOverrides> for BTreeMap<String, f64> {
    fn from(overrides: ThresholdOverrides) -> Self {
        overrides.0
    }
}

impl crate::options::OptionValue for ThresholdOverrides {
    const KIND: crate::options::Kind = crate::options::Kind::Weights;
    fn shown(&self) -> Option<String> {
        self.0.shown()
    }
}

/// A strokes job: the pattern's scale ε (or none, to infer it) and where it grows, the run's seed
/// and memory bound, and every other option ([`StrokesOptions`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", try_from = "crate::options::Described<StrokesJobFields>")]
pub struct StrokesJob {
    /// ε, the pattern's scale in drawing units (> 0); `None` infers it from the reference
    /// ([`motif_strokes::infer_scale`]).
    pub scale: Option<f64>,
    /// Where the pattern grows.
    pub target: TargetSpec,
    /// Seed of every random choice (default 1, as on the command line).
    pub seed: u64,
    /// Refuse runs whose estimated peak memory passes this: bytes, or a size such as `"8G"`
    /// (default: the engine's, 4 GiB; the CLI passes half of the machine's memory).
    pub max_memory: Option<u64>,
    /// Every other option.
    #[serde(flatten)]
    pub options: StrokesOptions,
}

/// The fields of a [`StrokesJob`] outside its options, as a description holds them.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub struct StrokesJobFields {
    #[serde(default)]
    scale: Option<f64>,
    target: TargetSpec,
    #[serde(default = "default_seed")]
    seed: u64,
    #[serde(default, deserialize_with = "crate::memory_size::optional")]
    max_memory: Option<u64>,
}

impl TryFrom<crate::options::Described<StrokesJobFields>> for StrokesJob {
    type Error = String;
    fn try_from(described: crate::options::Described<StrokesJobFields>) -> Result<Self, String> {
        let (fields, options) = described.split()?;
        Ok(Self {
            scale: fields.scale,
            target: fields.target,
            seed: fields.seed,
            max_memory: fields.max_memory,
            options,
        })
    }
}

/// A finished strokes job.
#[derive(Debug, Clone)]
pub struct StrokesRun {
    /// The engine's output (strokes, elements, analysis and its `Report`).
    pub output: Output,
    /// The ε the run used: the job's, or the one inferred from the reference.
    pub scale: RunScale,
    /// The report's figures as one JSON object, the keys every front end writes.
    pub figures: Map<String, Value>,
}

impl StrokesJob {
    /// A job with every option at its default, at scale ε = `scale` (`None`: inferred).
    pub fn new(scale: Option<f64>, target: TargetSpec) -> Self {
        Self { scale, target, seed: default_seed(), max_memory: None, options: StrokesOptions::default() }
    }

    /// The engine's parameters, with the job's ε (the engine's default stands in for an ε left to
    /// be inferred: [`StrokesJob::scale_for`] gives the run's).
    pub fn params(&self) -> Result<Params, JobError> {
        use crate::options::Declared;
        let options = &self.options;
        options.check_ranges()?;
        let params = Params::DEFAULT
            .with_scale(self.scale.unwrap_or(DEFAULTS.scale))
            .with_fit(options.fit)
            .with_rings(options.rings)
            .with_thresholds(options.thresholds.applied_to(DEFAULTS.thresholds))
            .with_variation(options.variation)
            .with_position_variation(options.position_variation)
            .with_avoid_overlaps(!options.allow_overlaps)
            .with_lloyd_iterations(options.lloyd_iterations)
            .with_max_memory(self.max_memory.unwrap_or(DEFAULTS.max_memory))
            .with_seed(self.seed);
        params.validate()?;
        Ok(params)
    }

    /// The ε of a run on `reference` with `params`: the job's, or inferred from the strokes.
    pub fn scale_for(&self, reference: &[Stroke], params: &Params) -> RunScale {
        match self.scale {
            Some(value) => RunScale { value, inferred: None },
            None => {
                let inferred = motif_strokes::infer_scale(reference, params);
                RunScale { value: inferred.value, inferred: Some(inferred) }
            }
        }
    }

    /// The analysis of `reference` alone into elements (§2), at the job's ε or the one inferred
    /// from it, as a synthesis in a region makes it.
    pub fn analyse(&self, reference: &[Stroke]) -> Result<(Analysis, RunScale), JobError> {
        let mut params = self.params()?;
        let scale = self.scale_for(reference, &params);
        params.scale = scale.value;
        Ok((motif_strokes::analyse(reference, &params, false)?, scale))
    }

    /// The engine's target.
    pub fn engine_target(&self) -> Result<Target, JobError> {
        let points = |list: &[[f64; 2]]| list.iter().map(|p| Point::new(p[0], p[1])).collect::<Vec<_>>();
        let invalid = |what: String, error: String| JobError::from(InvalidParameter::new("target", what, error));
        Ok(match &self.target {
            TargetSpec::Along(list) => {
                let mut line = points(list);
                let closed = line.len() > 2 && line.first() == line.last();
                if closed {
                    line.pop();
                }
                let polyline = Polyline::new(line, closed)
                    .map_err(|error| invalid(format!("a path of {} points", list.len()), error.to_string()))?;
                Target::Path(polyline)
            }
            TargetSpec::Region(list) => Target::Region(motif_strokes::region_from_outline(points(list))?),
            TargetSpec::Rect([width, height]) => {
                if !(width.is_finite() && height.is_finite() && *width > 0.0 && *height > 0.0) {
                    return Err(invalid(
                        format!("rect {},{}", number(*width), number(*height)),
                        "the target region needs a width and a height > 0".into(),
                    ));
                }
                let corners = vec![
                    Point::new(0.0, 0.0),
                    Point::new(*width, 0.0),
                    Point::new(*width, *height),
                    Point::new(0.0, *height),
                ];
                Target::Region(Polygon::new(corners).map_err(|error| invalid("rect".into(), error.to_string()))?)
            }
        })
    }
}

/// The ε a strokes run used.
#[derive(Debug, Clone, PartialEq)]
pub struct RunScale {
    /// ε in drawing units.
    pub value: f64,
    /// How it was inferred, when the job gave none.
    pub inferred: Option<InferredScale>,
}

impl RunScale {
    /// True when ε was inferred from the reference.
    pub fn is_inferred(&self) -> bool {
        self.inferred.is_some()
    }
}

/// The decoded inputs of a strokes job.
#[derive(Debug, Clone)]
pub struct StrokesInputs {
    /// The reference pattern's strokes.
    pub reference: Vec<Stroke>,
    /// A density map over the target region (see [`motif_strokes::ToneMap`]).
    pub density_map: Option<ToneMap>,
    /// A scale map over the target region.
    pub scale_map: Option<ToneMap>,
}

impl StrokesInputs {
    /// The reference strokes alone, without maps.
    pub fn new(reference: Vec<Stroke>) -> Self {
        Self { reference, density_map: None, scale_map: None }
    }
}

impl crate::Job for StrokesJob {
    const NAME: &'static str = "strokes";
    const FIELDS: &'static [&'static str] = &["scale", "target", "seed", "max-memory"];
    const SUMMARY: &'static str = "Grow a vector stroke pattern along a path or inside a region";
    const DETAILS: &'static str = "Hatching, stippling, brush marks and small figures analysed into elements and \
        synthesized by neighbourhood matching (Barla et al. 2006).";
    type Options = StrokesOptions;
    type Inputs<'a> = StrokesInputs;
    type Run = StrokesRun;

    fn run(&self, inputs: StrokesInputs, progress: &mut dyn Progress) -> Result<StrokesRun, JobError> {
        let mut params = self.params()?;
        let StrokesInputs { reference, density_map, scale_map } = inputs;
        let target = self.engine_target()?;
        let scale = self.scale_for(&reference, &params);
        params.scale = scale.value;
        let input = Input { density_map, scale_map, ..Input::new(reference, target) };
        let output = motif_strokes::synthesize(&input, &params, progress)?;
        let figures = figures(&output.report, &scale);
        Ok(StrokesRun { output, scale, figures })
    }
}

impl crate::Finished for StrokesRun {
    fn figures(&self) -> &Map<String, Value> {
        &self.figures
    }
}

/// The figures of a strokes run under the keys of `motif strokes --report`: ε (`scale`, with
/// `scale_inferred` and, when inferred, `scale_inference`: the merge heights around it) and the
/// engine's report.
pub fn figures(report: &motif_strokes::Report, scale: &RunScale) -> Map<String, Value> {
    let value = json!({
        "command": "strokes",
        "scale": scale.value,
        "scale_inferred": scale.is_inferred(),
        "scale_inference": scale.inferred,
        "estimated_memory_bytes": report.estimated_memory_bytes,
        "reference_strokes": report.reference_strokes,
        "reference_elements": report.reference_elements,
        "border_elements": report.border_elements,
        "fragment_elements": report.fragment_elements,
        "output_elements": report.output_elements,
        "output_strokes": report.output_strokes,
        "expected_elements": report.expected_elements,
        "matched_elements": report.matched_elements,
        "fallback_elements": report.fallback_elements,
        "candidate_fraction": report.candidate_fraction,
        "mean_candidates": report.mean_candidates,
        "rings": report.rings,
        "lloyd_iterations": report.lloyd_iterations,
        "skewed_triangles_removed": report.skewed_triangles_removed,
        "overlap": report.overlap,
        "stages_ms": crate::stages(&report.stages_ms),
    });
    crate::object(value)
}

#[cfg(test)]
mod tests {
    use motif_core::NoProgress;
    use motif_strokes::samples::{HatchRow, hatch_row};

    use super::*;
    use crate::Job;

    #[test]
    fn a_described_job_runs_with_the_flag_names() {
        let job: StrokesJob = serde_json::from_value(json!({
            "scale": 6,
            "target": { "rect": [200, 120] },
            "fit": "contour",
            "thresholds": { "col": 0.3 },
            "lloyd-iterations": 5,
            "seed": 3,
        }))
        .unwrap();
        let params = job.params().unwrap();
        assert_eq!(params.fit, FitPoints::Contour);
        assert_eq!(params.thresholds.colour, 0.3);
        assert_eq!(params.lloyd_iterations, 5);
        assert_eq!(params.thresholds.shape, Thresholds::default().shape);
        let row = HatchRow { count: 12, ..HatchRow::default() };
        let strokes = hatch_row(&row, Point::new(10.0, 30.0), |i| 0.05 * i as f64, |_| [20, 20, 20, 255], 1);
        let run = job.run(StrokesInputs::new(strokes), &mut NoProgress).unwrap();
        assert!(run.output.report.output_elements > 20);
        assert_eq!(run.figures["output_elements"], run.output.report.output_elements);
    }

    #[test]
    fn a_job_without_a_scale_infers_it_and_a_given_one_wins() {
        let row = HatchRow { count: 12, ..HatchRow::default() };
        let strokes = hatch_row(&row, Point::new(10.0, 30.0), |_| 0.0, |_| [20, 20, 20, 255], 1);
        let job: StrokesJob = serde_json::from_value(json!({ "target": { "rect": [200, 120] } })).unwrap();
        assert_eq!(job.scale, None);
        let run = job.run(StrokesInputs::new(strokes.clone()), &mut NoProgress).unwrap();
        let inferred = run.scale.inferred.clone().expect("inferred");
        assert_eq!(inferred, motif_strokes::infer_scale(&strokes, &job.params().unwrap()));
        assert_eq!((run.scale.value, run.output.report.reference_elements), (inferred.value, 12));
        let figures = &run.figures;
        assert_eq!((figures["scale"].as_f64(), &figures["scale_inferred"]), (Some(inferred.value), &json!(true)));
        assert_eq!(figures["scale_inference"]["method"], "gap");
        assert!(figures["scale_inference"]["below"].as_f64() < figures["scale_inference"]["above"].as_f64());
        let given = StrokesJob { scale: Some(2.5), ..job };
        let run = given.run(StrokesInputs::new(strokes), &mut NoProgress).unwrap();
        assert_eq!((run.scale.value, run.scale.is_inferred()), (2.5, false));
        assert_eq!((&run.figures["scale"], &run.figures["scale_inferred"]), (&json!(2.5), &json!(false)));
        assert!(run.figures["scale_inference"].is_null());
    }

    #[test]
    fn options_default_to_the_engines_parameters() {
        let params = StrokesJob::new(Some(Params::DEFAULT.scale), TargetSpec::Rect([10.0, 10.0])).params().unwrap();
        assert_eq!(params, Params::DEFAULT.with_seed(1));
    }

    #[test]
    fn thresholds_are_a_map_of_the_names_set() {
        use crate::options::{Declared, OptionValue};
        let job: StrokesJob = serde_json::from_value(
            json!({ "scale": 6, "target": { "rect": [9, 9] }, "thresholds": { "ov": 2, "par": 0.5 } }),
        )
        .unwrap();
        let thresholds = &job.options.thresholds;
        assert_eq!((thresholds.get("ov"), thresholds.get("shape")), (Some(2.0), None));
        assert_eq!(thresholds.shown().as_deref(), Some("ov=2,par=0.5"));
        let applied = thresholds.applied_to(Thresholds::DEFAULT);
        assert_eq!((applied.overlap, applied.parallelism, applied.colour), (2.0, 0.5, Thresholds::DEFAULT.colour));
        let again: StrokesJob = serde_json::from_str(&serde_json::to_string(&job).unwrap()).unwrap();
        assert_eq!(again, job);
        let spec = StrokesOptions::options().into_iter().find(|spec| spec.name == "thresholds").unwrap();
        assert_eq!((spec.kind, spec.default), (crate::options::Kind::Weights, None));
    }

    #[test]
    fn bad_descriptions_name_what_is_wrong() {
        let bad = |description: Value| serde_json::from_value::<StrokesJob>(description).unwrap_err().to_string();
        let rect = json!({ "rect": [10, 10] });
        let unknown = bad(json!({ "scale": 5, "target": rect, "thresholds": { "colour": 0.2 } }));
        assert!(unknown.contains("colour=0.2"), "{unknown}");
        assert!(bad(json!({ "scale": 5, "target": rect, "stiffness": 1 })).contains("stiffness"));
        let mut job = StrokesJob::new(Some(5.0), TargetSpec::Rect([10.0, 10.0]));
        job.options.rings = Some(6);
        assert!(job.params().unwrap_err().to_string().contains("rings"));
        assert!(StrokesJob::new(Some(5.0), TargetSpec::Rect([0.0, 10.0])).engine_target().is_err());
        let crossed = TargetSpec::Region(vec![[0.0, 0.0], [10.0, 10.0], [10.0, 0.0], [0.0, 10.0]]);
        assert!(
            StrokesJob::new(Some(5.0), crossed).engine_target().unwrap_err().to_string().contains("self-intersecting")
        );
        let error = serde_json::from_value::<StrokesJob>(json!({ "scale": 5, "target": { "circle": 3 } })).unwrap_err();
        assert!(error.to_string().contains("circle"), "{error}");
    }
}
