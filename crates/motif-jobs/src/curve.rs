//! `curve` jobs: structured raster patterns along curves (`motif_curve`).
//!
//! Field names are the flags of `motif curve`; none is required: a missing width or piece length
//! is inferred from the first exemplar (`motif_curve::Dimensions::resolve`).
//! The exemplars, the curve and the avoidance map come decoded (the CLI reads PNG and SVG).

use motif_core::{Polyline, Progress, RgbaImage};
use motif_curve::{AlphaMode, Canvas, ClosedMode, Dimensions, Input, Method, Output, Params, PieceShape, Solver};
use motif_curve::{PatchFidelity, patch_fidelity};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value, json};

use crate::JobError;

/// Every option of `motif curve` that is not a file (or the flattening tolerance of one).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct CurveJob {
    /// Ribbon width in canvas pixels (> 0); inferred from the exemplar's pattern height when
    /// missing.
    #[serde(default)]
    pub width: Option<f64>,
    /// Piece length along the curve in canvas pixels (> 0); inferred from the exemplar's period
    /// when missing.
    #[serde(default)]
    pub piece_length: Option<f64>,
    /// Exemplar pixels per canvas pixel.
    #[serde(default)]
    pub scale: Option<f64>,
    /// Closed curves: `auto` (default), `approx`, `exact` or `no`.
    #[serde(default)]
    pub closed: Option<ClosedMode>,
    /// `synth` (the paper, default) or `repeat` (the baseline).
    #[serde(default)]
    pub method: Option<Method>,
    /// `exact` (default) or `reference`.
    #[serde(default)]
    pub solver: Option<Solver>,
    /// How alpha enters the seam cost: `continuous` (default) or `binary`.
    #[serde(default)]
    pub alpha: Option<AlphaMode>,
    /// Mismatch penalty γ.
    #[serde(default)]
    pub gamma: Option<f64>,
    /// Align the seams after the solve.
    #[serde(default)]
    pub stitch: bool,
    /// Cost per stitched pixel.
    #[serde(default)]
    pub stitch_penalty: Option<f64>,
    /// Turn fold-over avoidance off.
    #[serde(default)]
    pub no_foldover_avoidance: bool,
    /// Pin the first piece to this exemplar position `[x, y]`.
    #[serde(default)]
    pub pin_first: Option<[i32; 2]>,
    /// A fixed canvas `[W, H]` (default: fitted to the ribbon).
    #[serde(default)]
    pub canvas: Option<[usize; 2]>,
    /// Border of a fitted canvas, pixels.
    #[serde(default)]
    pub margin: Option<f64>,
    /// Render samples per pixel along each axis.
    #[serde(default)]
    pub samples: Option<usize>,
    /// Alpha below which a pixel counts as background.
    #[serde(default)]
    pub cut_alpha: Option<u8>,
    /// Least share of pattern a piece's window must hold.
    #[serde(default)]
    pub min_coverage: Option<f64>,
    /// Weight of the penalty on repeated exemplar windows.
    #[serde(default)]
    pub variety: Option<f64>,
    /// Windows closer than this (exemplar pixels) count as repeats.
    #[serde(default)]
    pub variety_radius: Option<usize>,
    /// `bent` (default) or `rigid` pieces.
    #[serde(default)]
    pub pieces_shape: Option<PieceShape>,
    /// Width factor along the curve, `[[t, factor], ...]` with t in [0, 1].
    #[serde(default)]
    pub width_profile: Vec<[f64; 2]>,
    /// Bends tighter than this many widths are rounded.
    #[serde(default)]
    pub round_bends: Option<f64>,
    /// Start positions tried by the exact closed solver.
    #[serde(default)]
    pub closed_max_starts: Option<usize>,
    /// Also measure patch fidelity (the result read back along the curve against the exemplar).
    #[serde(default)]
    pub fidelity: bool,
    /// Refuse runs whose estimated peak memory passes this: bytes, or a size such as `"8G"`
    /// (default: the engine's, 4 GiB; the CLI passes half of the machine's memory).
    #[serde(default, deserialize_with = "crate::memory_size::optional")]
    pub max_memory: Option<u64>,
}

/// A finished curve job.
#[derive(Debug, Clone)]
pub struct CurveRun {
    /// The engine's output (image, pieces and its `Report`).
    pub output: Output,
    /// The width and piece length the run used, each given or inferred.
    pub dimensions: Dimensions,
    /// Patch fidelity, when the job asked for it.
    pub fidelity: Option<PatchFidelity>,
    /// The report's figures as one JSON object, the keys every front end writes.
    pub figures: Map<String, Value>,
}

/// The decoded inputs of a curve job.
#[derive(Debug, Clone, Copy)]
pub struct CurveInputs<'a> {
    /// The first exemplar.
    pub exemplar: &'a RgbaImage,
    /// More exemplars to mix with it.
    pub more_exemplars: &'a [RgbaImage],
    /// The curve.
    pub curve: &'a Polyline,
    /// Forbidden areas of the canvas (white), if any.
    pub avoidance: Option<&'a RgbaImage>,
}

impl CurveJob {
    /// A job with the given width and piece length and every other option at its default
    /// ([`default`](Default::default) leaves the width and piece length to be inferred).
    pub fn new(width: f64, piece_length: f64) -> Self {
        Self { width: Some(width), piece_length: Some(piece_length), ..Self::default() }
    }

    /// The engine's parameters for `inputs`, with the width and piece length each given or
    /// inferred from the first exemplar (an inferred piece length is capped at the curve's length).
    pub fn params(&self, inputs: &CurveInputs<'_>) -> Result<(Params, Dimensions), JobError> {
        let dimensions = self.dimensions(inputs)?;
        let params = self.params_with(dimensions.width.value, dimensions.piece_length.value)?;
        Ok((params, dimensions))
    }

    /// The width and piece length: the job's, or inferred where it has none.
    fn dimensions(&self, inputs: &CurveInputs<'_>) -> Result<Dimensions, JobError> {
        let d = Params::default();
        let (scale, cut_alpha) = (self.scale.unwrap_or(d.scale), self.cut_alpha.unwrap_or(d.cut_alpha));
        if cut_alpha == 255 {
            return Err(motif_core::InvalidParameter::new("cut-alpha", 255, "must be between 0 and 254").into());
        }
        let mut dimensions = Dimensions::resolve(inputs.exemplar, self.width, self.piece_length, scale, cut_alpha)?;
        let length = inputs.curve.length();
        if dimensions.piece_length.inferred && dimensions.piece_length.value > length {
            dimensions.piece_length.value = length;
        }
        Ok(dimensions)
    }

    /// The engine's parameters with this width and piece length.
    fn params_with(&self, width: f64, piece_length: f64) -> Result<Params, JobError> {
        let d = Params::default();
        let margin = match d.canvas {
            Canvas::Fit { margin } => margin,
            Canvas::Size { .. } => 0.0,
        };
        let canvas = match self.canvas {
            Some([width, height]) => Canvas::Size { width, height },
            None => Canvas::Fit { margin: self.margin.unwrap_or(margin) },
        };
        let params = d
            .clone()
            .with_width(width)
            .with_piece_length(piece_length)
            .with_scale(self.scale.unwrap_or(d.scale))
            .with_closed(self.closed.unwrap_or(d.closed))
            .with_method(self.method.unwrap_or(d.method))
            .with_solver(self.solver.unwrap_or(d.solver))
            .with_alpha_mode(self.alpha.unwrap_or(d.alpha_mode))
            .with_mismatch_penalty(self.gamma.unwrap_or(d.mismatch_penalty))
            .with_stitch(self.stitch)
            .with_stitch_penalty(self.stitch_penalty.unwrap_or(d.stitch_penalty))
            .with_foldover_avoidance(!self.no_foldover_avoidance)
            .with_pin_first(self.pin_first)
            .with_canvas(canvas)
            .with_samples_per_axis(self.samples.unwrap_or(d.samples_per_axis))
            .with_cut_alpha(self.cut_alpha.unwrap_or(d.cut_alpha))
            .with_min_coverage(self.min_coverage.unwrap_or(d.min_coverage))
            .with_closed_max_starts(self.closed_max_starts.unwrap_or(d.closed_max_starts))
            .with_variety(self.variety.unwrap_or(d.variety))
            .with_variety_radius(self.variety_radius.unwrap_or(d.variety_radius))
            .with_round_bends(self.round_bends.unwrap_or(d.round_bends))
            .with_width_profile(self.width_profile.iter().map(|&[t, f]| (t, f)).collect())
            .with_piece_shape(self.pieces_shape.unwrap_or(d.piece_shape))
            .with_max_memory(self.max_memory.unwrap_or(d.max_memory));
        params.validate()?;
        Ok(params)
    }

    /// Runs the job on decoded inputs.
    pub fn run(&self, inputs: CurveInputs<'_>, progress: &mut dyn Progress) -> Result<CurveRun, JobError> {
        self.run_in(inputs, None, progress)
    }

    /// [`run`](Self::run) within an editing session: what the session's previous run computed
    /// and still holds is reused (the playground calls this while a curve is dragged; the result
    /// is byte-identical to a fresh run).
    pub fn run_in_session(
        &self,
        inputs: CurveInputs<'_>,
        session: &mut motif_curve::Incremental,
        progress: &mut dyn Progress,
    ) -> Result<CurveRun, JobError> {
        self.run_in(inputs, Some(session), progress)
    }

    fn run_in(
        &self,
        inputs: CurveInputs<'_>,
        session: Option<&mut motif_curve::Incremental>,
        progress: &mut dyn Progress,
    ) -> Result<CurveRun, JobError> {
        let (params, dimensions) = self.params(&inputs)?;
        let input = Input {
            exemplar: inputs.exemplar,
            curve: inputs.curve,
            avoidance: inputs.avoidance,
            more_exemplars: inputs.more_exemplars,
        };
        let output = match session {
            Some(session) => session.synthesize(&input, &params, progress)?,
            None => motif_curve::synthesize(&input, &params, progress)?,
        };
        let fidelity = self.fidelity.then(|| {
            patch_fidelity(inputs.exemplar, &output.image, &output.ribbon_top, &output.ribbon_bottom, params.scale)
        });
        let mut figures = figures(&output.report);
        figures.extend(dimension_figures(&dimensions));
        if let Some(fidelity) = fidelity {
            figures.insert("fidelity".into(), json!(fidelity));
        }
        Ok(CurveRun { output, dimensions, fidelity, figures })
    }
}

/// The width and piece length under the keys of `motif curve --report`: `width` and
/// `piece_length` (canvas pixels), `width_inferred` and `piece_length_inferred`, and what the
/// inference measured, `pattern_height` and `pattern_period` (exemplar pixels; null when not
/// measured or no period was found).
pub fn dimension_figures(dimensions: &Dimensions) -> Map<String, Value> {
    let mut figures = Map::new();
    figures.insert("width".into(), json!(dimensions.width.value));
    figures.insert("width_inferred".into(), json!(dimensions.width.inferred));
    figures.insert("piece_length".into(), json!(dimensions.piece_length.value));
    figures.insert("piece_length_inferred".into(), json!(dimensions.piece_length.inferred));
    figures.insert("pattern_height".into(), json!(dimensions.pattern_height));
    figures.insert("pattern_period".into(), json!(dimensions.period));
    figures
}

/// The figures of a curve run under the keys of `motif curve --report`.
pub fn figures(report: &motif_curve::Report) -> Map<String, Value> {
    let mut figures = Map::new();
    let mut put = |key: &str, value: Value| {
        figures.insert(key.to_string(), value);
    };
    put("command", json!("curve"));
    put("estimated_memory_bytes", json!(report.estimated_memory_bytes));
    put("method", json!(report.method));
    put("solver", json!(report.solver));
    put("pieces", json!(report.pieces));
    put("samples_per_edge", json!(report.samples_per_edge));
    put("canvas", json!(report.canvas));
    put("canvas_origin", json!(report.canvas_origin));
    put("total_cost", json!(report.total_cost));
    put("total_cost_unstitched", json!(report.total_cost_unstitched));
    put("mean_seam_cost", json!(report.mean_seam_cost));
    put("valid_fraction", json!(report.valid_fraction));
    put(
        "dp_row_ms",
        json!({ "median": report.dp_row_ms_median, "max": report.dp_row_ms_max, "rows": report.dp_row_ms.len() }),
    );
    put("stages_ms", crate::stages(&report.stages_ms));
    put("closed", json!(report.closed));
    if report.closed {
        put("closed_certified", json!(report.closed_certified));
        put("closed_starts_tried", json!(report.closed_starts_tried));
        put("closed_directly", json!(report.closed_directly));
    }
    put("empty_pieces", json!(report.empty_pieces));
    put("forbidden_pixels", json!(report.forbidden_pixels));
    put("foldover_pixels", json!(report.foldover_pixels));
    put("columns_skipped_fraction", json!(report.columns_skipped_fraction));
    put("dp_counters", json!(report.dp_counters));
    put("stitched_seams", json!(report.stitched_seams));
    put("distortion_mean", json!(report.distortion_mean));
    put("distortion_max", json!(report.distortion_max));
    if report.method == Method::Repeat {
        put("wrap_seams", json!(report.wrap_seams));
    } else {
        put("repeated_pairs", json!(report.repeated_pairs));
        put("distinct_windows", json!(report.distinct_windows));
        put("variety", json!(report.variety));
        put("rounded_bends", json!(report.rounded_bends));
        put("bend_shift_max", json!(report.bend_shift_max));
    }
    put("warnings", json!(report.warnings));
    figures
}

#[cfg(test)]
mod tests {
    use motif_core::{NoProgress, Point};

    use super::*;

    fn rings() -> RgbaImage {
        RgbaImage::from_fn(96, 24, |x, y| {
            let (dx, dy) = ((x % 16) as f64 - 7.5, y as f64 - 11.5);
            if (4.0..7.0).contains(&motif_core::math::hypot(dx, dy)) { [210, 170, 40, 255] } else { [0; 4] }
        })
    }

    fn line() -> Polyline {
        let points = (0..=20).map(|i| Point::new(20.0 + 10.0 * f64::from(i), 60.0)).collect();
        Polyline::new(points, false).unwrap()
    }

    #[test]
    fn a_described_job_runs_with_the_flag_names() {
        let job: CurveJob = serde_json::from_value(json!({
            "width": 24,
            "piece-length": 12,
            "closed": "no",
            "method": "synth",
            "pieces-shape": "bent",
            "width-profile": [[0, 1], [1, 1.5]],
            "canvas": [260, 120],
            "fidelity": true,
        }))
        .unwrap();
        let (exemplar, curve) = (rings(), line());
        let inputs = CurveInputs { exemplar: &exemplar, more_exemplars: &[], curve: &curve, avoidance: None };
        let (params, dimensions) = job.params(&inputs).unwrap();
        assert_eq!((params.width, params.piece_length), (24.0, 12.0));
        assert!(!dimensions.width.inferred && !dimensions.piece_length.inferred);
        assert_eq!(params.closed, ClosedMode::Open);
        assert_eq!(params.method, Method::Synthesis);
        assert_eq!(params.piece_shape, PieceShape::Bent);
        assert_eq!(params.width_profile, vec![(0.0, 1.0), (1.0, 1.5)]);
        assert_eq!(params.canvas, Canvas::Size { width: 260, height: 120 });
        assert_eq!(params.mismatch_penalty, Params::default().mismatch_penalty);
        let run = job.run(inputs, &mut NoProgress).unwrap();
        assert!(run.output.report.pieces > 10);
        assert_eq!(run.figures["pieces"], run.output.report.pieces);
        assert_eq!(run.figures["width_inferred"], false);
        assert!(run.fidelity.is_some() && run.figures.contains_key("fidelity"));
    }

    #[test]
    fn a_job_without_width_and_piece_length_infers_them() {
        let (exemplar, curve) = (rings(), line());
        let inputs = CurveInputs { exemplar: &exemplar, more_exemplars: &[], curve: &curve, avoidance: None };
        let job: CurveJob = serde_json::from_value(json!({ "closed": "no" })).unwrap();
        let run = job.run(inputs, &mut NoProgress).unwrap();
        // Rings 16 px apart, 14 rows tall: the inferred width holds 16 rows with a margin.
        assert_eq!(run.dimensions.period, Some(16));
        assert_eq!(run.dimensions.pattern_height, Some(14));
        assert_eq!(run.figures["width"], 19.0);
        assert_eq!(run.figures["width_inferred"], true);
        assert_eq!(run.figures["piece_length"], 8.0);
        assert_eq!(run.figures["piece_length_inferred"], true);
        let given = CurveJob { width: Some(30.0), ..job };
        let (params, dimensions) = given.params(&inputs).unwrap();
        assert_eq!((params.width, params.piece_length), (30.0, 8.0));
        assert!(!dimensions.width.inferred && dimensions.piece_length.inferred);
    }

    #[test]
    fn bad_descriptions_name_what_is_wrong() {
        let error = serde_json::from_value::<CurveJob>(json!({ "width": 24, "piece-length": 12, "closed": "maybe" }));
        assert!(error.unwrap_err().to_string().contains("maybe"));
        let (exemplar, curve) = (rings(), line());
        let inputs = CurveInputs { exemplar: &exemplar, more_exemplars: &[], curve: &curve, avoidance: None };
        let job = CurveJob { scale: Some(0.0), ..CurveJob::new(24.0, 12.0) };
        assert!(job.params(&inputs).unwrap_err().to_string().contains("scale"));
        let job = CurveJob { scale: Some(0.0), ..CurveJob::default() };
        assert!(job.params(&inputs).unwrap_err().to_string().contains("scale"));
        let clear = RgbaImage::from_fn(40, 20, |_, _| [0; 4]);
        let inputs = CurveInputs { exemplar: &clear, ..inputs };
        let error = CurveJob::default().params(&inputs).unwrap_err().to_string();
        assert!(error.contains("no pattern found"), "{error}");
    }
}
