//! `strokes` jobs: vector stroke patterns along a path or in a region (`motif_strokes`).
//!
//! Field names are the flags of `motif strokes`; only the scale ε and the target are required.
//! The reference strokes come decoded (the CLI reads them from SVG with its `--tolerance`).

use std::collections::BTreeMap;

use motif_core::error::number;
use motif_core::{InvalidParameter, Point, Polygon, Polyline, Progress};
use motif_strokes::{FitPoints, Input, Output, Params, Stroke, Target, Thresholds, ToneMap};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value, json};

use crate::JobError;

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

/// Every option of `motif strokes` that is not a file (or the flattening tolerance of one).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct StrokesJob {
    /// ε, the pattern's scale in drawing units (> 0).
    pub scale: f64,
    /// Where the pattern grows.
    pub target: TargetSpec,
    /// Seed of every random choice (default 1, as on the command line).
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Points the element boxes are fitted to: `skeleton` (default) or `contour`.
    #[serde(default)]
    pub fit: Option<FitPoints>,
    /// Neighbourhood size in rings, 1–5 (default 5 along a path, 2 in a region).
    #[serde(default)]
    pub rings: Option<usize>,
    /// Parameter exchange amount, 0–1 (default 0).
    #[serde(default)]
    pub variation: Option<f64>,
    /// Reintroduce the reference's irregular spacing.
    #[serde(default)]
    pub position_variation: bool,
    /// Let elements overlap (by default an element whose ink meets a placed one is changed, moved
    /// or removed, unless the reference's own elements overlap).
    #[serde(default)]
    pub allow_overlaps: bool,
    /// Matching thresholds to override by name: `shape`, `par`, `ov`, `sup`, `col`, `attr`.
    #[serde(default)]
    pub thresholds: BTreeMap<String, f64>,
    /// Lloyd relaxation iterations for the seeds.
    #[serde(default)]
    pub lloyd_iterations: Option<usize>,
    /// Refuse runs whose estimated peak memory passes this: bytes, or a size such as `"8G"`
    /// (default: the engine's, 4 GiB; the CLI passes half of the machine's memory).
    #[serde(default, deserialize_with = "crate::memory_size::optional")]
    pub max_memory: Option<u64>,
}

/// A finished strokes job.
#[derive(Debug, Clone)]
pub struct StrokesRun {
    /// The engine's output (strokes, elements, analysis and its `Report`).
    pub output: Output,
    /// The report's figures as one JSON object, the keys every front end writes.
    pub figures: Map<String, Value>,
}

impl StrokesJob {
    /// A job with every option at its default.
    pub fn new(scale: f64, target: TargetSpec) -> Self {
        Self {
            scale,
            target,
            seed: default_seed(),
            fit: None,
            rings: None,
            variation: None,
            position_variation: false,
            allow_overlaps: false,
            thresholds: BTreeMap::new(),
            lloyd_iterations: None,
            max_memory: None,
        }
    }

    /// The engine's parameters.
    pub fn params(&self) -> Result<Params, JobError> {
        let defaults = Params::default();
        let mut thresholds = Thresholds::default();
        for (name, &value) in &self.thresholds {
            let slot = match name.as_str() {
                "shape" => &mut thresholds.shape,
                "par" => &mut thresholds.parallelism,
                "ov" => &mut thresholds.overlap,
                "sup" => &mut thresholds.superimposition,
                "col" => &mut thresholds.colour,
                "attr" => &mut thresholds.attributes,
                other => {
                    return Err(InvalidParameter::new(
                        "thresholds",
                        format!("{other}={}", number(value)),
                        "a threshold named shape, par, ov, sup, col or attr",
                    )
                    .into());
                }
            };
            *slot = value;
        }
        let params = defaults
            .clone()
            .with_scale(self.scale)
            .with_fit(self.fit.unwrap_or(defaults.fit))
            .with_rings(self.rings)
            .with_thresholds(thresholds)
            .with_variation(self.variation.unwrap_or(defaults.variation))
            .with_position_variation(self.position_variation)
            .with_avoid_overlaps(!self.allow_overlaps)
            .with_lloyd_iterations(self.lloyd_iterations.unwrap_or(defaults.lloyd_iterations))
            .with_max_memory(self.max_memory.unwrap_or(defaults.max_memory))
            .with_seed(self.seed);
        params.validate()?;
        Ok(params)
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

    /// Runs the job on the decoded reference strokes.
    pub fn run(&self, strokes: Vec<Stroke>, progress: &mut dyn Progress) -> Result<StrokesRun, JobError> {
        self.run_with_maps(strokes, None, None, progress)
    }

    /// Runs the job with a density map and a scale map (decoded images, see
    /// [`motif_strokes::ToneMap`]) over the target region.
    pub fn run_with_maps(
        &self,
        strokes: Vec<Stroke>,
        density_map: Option<ToneMap>,
        scale_map: Option<ToneMap>,
        progress: &mut dyn Progress,
    ) -> Result<StrokesRun, JobError> {
        let params = self.params()?;
        let input = Input { density_map, scale_map, ..Input::new(strokes, self.engine_target()?) };
        let output = motif_strokes::synthesize(&input, &params, progress)?;
        let figures = figures(&output.report);
        Ok(StrokesRun { output, figures })
    }
}

/// The figures of a strokes run under the keys of `motif strokes --report`.
pub fn figures(report: &motif_strokes::Report) -> Map<String, Value> {
    let value = json!({
        "command": "strokes",
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
        let run = job.run(strokes, &mut NoProgress).unwrap();
        assert!(run.output.report.output_elements > 20);
        assert_eq!(run.figures["output_elements"], run.output.report.output_elements);
    }

    #[test]
    fn bad_descriptions_name_what_is_wrong() {
        let job = StrokesJob {
            thresholds: BTreeMap::from([("colour".into(), 0.2)]),
            ..StrokesJob::new(5.0, TargetSpec::Rect([10.0, 10.0]))
        };
        assert!(job.params().unwrap_err().to_string().contains("colour=0.2"));
        assert!(StrokesJob::new(5.0, TargetSpec::Rect([0.0, 10.0])).engine_target().is_err());
        let crossed = TargetSpec::Region(vec![[0.0, 0.0], [10.0, 10.0], [10.0, 0.0], [0.0, 10.0]]);
        assert!(StrokesJob::new(5.0, crossed).engine_target().unwrap_err().to_string().contains("self-intersecting"));
        let error = serde_json::from_value::<StrokesJob>(json!({ "scale": 5, "target": { "circle": 3 } })).unwrap_err();
        assert!(error.to_string().contains("circle"), "{error}");
    }
}
