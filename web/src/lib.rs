//! The playground's WebAssembly module: one session type per panel, each running its engine
//! through `motif-jobs` (the layer the CLI and the Python package use), with job descriptions
//! as JSON named as the CLI's flags. The page's Web Worker owns the sessions; results come back
//! as flat arrays (RGBA bytes, coordinates) and the report as JSON text.

#![allow(unreachable_pub, reason = "a cdylib: its pub items are what it exports, reachable from outside Rust")]

use motif_core::{NoProgress, Point, Polyline, RgbaImage};
use motif_jobs::Job;
use motif_jobs::curve::{CurveInputs, CurveJob, Incremental};
use motif_jobs::points::{DomainSpec, PointSet, PointsInputs, PointsJob, StrokeSpec};
use motif_jobs::strokes::{Stroke, StrokesInputs, StrokesJob, TargetSpec, strokes_from_json, strokes_to_json};
use motif_jobs::stylize::{PresynthInputs, PresynthJob, StylizeInputs, StylizeJob};
use wasm_bindgen::prelude::*;

fn error(message: impl std::fmt::Display) -> JsError {
    JsError::new(&message.to_string())
}

/// The declared options of `job` (a name of `motif_jobs::JOBS`) as JSON: name, kind, help,
/// default and range of each. The page's controls take their help and ranges from it.
#[wasm_bindgen]
pub fn job_options(job: &str) -> Result<String, JsError> {
    let entry = motif_jobs::JobEntry::named(job).ok_or_else(|| error(format!("no job named {job}")))?;
    serde_json::to_string(&(entry.options)()).map_err(error)
}

fn elapsed_ms(start: web_time::Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1000.0
}

/// An image result: RGBA bytes, size, the report and the engine time.
#[wasm_bindgen]
#[derive(Debug)]
pub struct ImageResult {
    width: usize,
    height: usize,
    rgba: Vec<u8>,
    report: String,
    milliseconds: f64,
}

#[wasm_bindgen]
impl ImageResult {
    /// Width in pixels.
    #[wasm_bindgen(getter)]
    pub fn width(&self) -> usize {
        self.width
    }
    /// Height in pixels.
    #[wasm_bindgen(getter)]
    pub fn height(&self) -> usize {
        self.height
    }
    /// Straight-alpha RGBA bytes, row by row.
    #[wasm_bindgen(getter)]
    pub fn rgba(&self) -> Vec<u8> {
        self.rgba.clone()
    }
    /// The run's figures as JSON (the CLI's `--report`).
    #[wasm_bindgen(getter)]
    pub fn report(&self) -> String {
        self.report.clone()
    }
    /// Milliseconds the synthesis took in the module.
    #[wasm_bindgen(getter)]
    pub fn milliseconds(&self) -> f64 {
        self.milliseconds
    }
}

fn image_result(
    image: &RgbaImage,
    figures: &serde_json::Map<String, serde_json::Value>,
    start: web_time::Instant,
) -> ImageResult {
    ImageResult {
        width: image.width(),
        height: image.height(),
        rgba: image.as_bytes().to_vec(),
        report: serde_json::Value::Object(figures.clone()).to_string(),
        milliseconds: elapsed_ms(start),
    }
}

/// The largest image side the page accepts, in pixels (the page checks decoded files against it).
#[wasm_bindgen]
pub fn max_image_side() -> usize {
    motif_core::limits::MAX_BROWSER_IMAGE_SIDE
}

fn rgba_image(rgba: &[u8], width: usize, height: usize, what: &str) -> Result<RgbaImage, JsError> {
    let side = motif_core::limits::MAX_BROWSER_IMAGE_SIDE;
    if width == 0 || height == 0 || width > side || height > side {
        return Err(error(format!("{what}: {width}×{height} pixels; give an image of 1–{side} pixels a side")));
    }
    if rgba.len() != width * height * 4 {
        return Err(error(format!("{what}: {} bytes for {width}×{height} RGBA pixels", rgba.len())));
    }
    let pixels = rgba.chunks_exact(4).map(|p| [p[0], p[1], p[2], p[3]]).collect();
    RgbaImage::from_pixels(width, height, pixels).map_err(error)
}

fn polyline(points: &[f64], what: &str) -> Result<Polyline, JsError> {
    if points.len() < 4 || !points.len().is_multiple_of(2) {
        return Err(error(format!("{what}: give at least two x, y points")));
    }
    let list: Vec<Point> = points.chunks_exact(2).map(|p| Point::new(p[0], p[1])).collect();
    Polyline::new(list, false).map_err(|e| error(format!("{what}: {e}")))
}

/// The curve panel: an exemplar strip and an editing session, so that dragging a control point
/// re-solves only what changed.
#[wasm_bindgen]
#[derive(Debug)]
pub struct CurvePanel {
    exemplar: RgbaImage,
    session: Incremental,
}

#[wasm_bindgen]
impl CurvePanel {
    /// A panel for an exemplar strip given as RGBA bytes (transparent background = no pattern).
    #[wasm_bindgen(constructor)]
    pub fn new(rgba: &[u8], width: usize, height: usize) -> Result<CurvePanel, JsError> {
        let exemplar = rgba_image(rgba, width, height, "exemplar")?;
        if exemplar.is_fully_opaque() {
            return Err(error(
                "exemplar: the image has no transparent pixels; the curve engine needs the pattern on a transparent \
                 background (a PNG with alpha)",
            ));
        }
        Ok(CurvePanel { exemplar, session: Incremental::new() })
    }

    /// Synthesizes along the polyline `points` (x0, y0, x1, y1, ...) with the job `job`
    /// (JSON with `width`, `piece-length` and any `motif curve` option).
    pub fn synthesize(&mut self, points: &[f64], job: &str) -> Result<ImageResult, JsError> {
        let start = web_time::Instant::now();
        let job: CurveJob = serde_json::from_str(job).map_err(|e| error(format!("curve options: {e}")))?;
        let curve = polyline(points, "curve")?;
        let inputs = CurveInputs::new(&self.exemplar, &curve);
        let run = job.run_in_session(inputs, &mut self.session, &mut NoProgress).map_err(error)?;
        Ok(image_result(&run.output.image, &run.figures, start))
    }
}

/// The points panel: a built-in exemplar and the structure brushed so far.
#[wasm_bindgen]
#[derive(Debug)]
pub struct PointsPanel {
    exemplar: PointSet,
    grown: Option<PointSet>,
    discrete: Vec<String>,
}

#[wasm_bindgen]
impl PointsPanel {
    /// A panel growing the built-in exemplar: `hex` (a jittered hexagonal lattice with coloured
    /// rows, spacing 1) or `leaves` (rigid leaf-shaped elements).
    #[wasm_bindgen(constructor)]
    pub fn new(exemplar: &str) -> Result<PointsPanel, JsError> {
        let (exemplar, discrete) = match exemplar {
            "hex" => (motif_points::samples::hex_exemplar(9, 8, 0.08, 1), vec!["shade".to_string()]),
            "leaves" => (motif_points::samples::leaf_exemplar(1), Vec::new()),
            other => return Err(error(format!("no built-in exemplar named {other}; use hex or leaves"))),
        };
        Ok(PointsPanel { exemplar, grown: None, discrete })
    }

    /// Grows the structure along a brush stroke (`points` x0, y0, ... in exemplar units, `width`
    /// wide); points grown before stay fixed unless they are near the stroke. Returns the whole
    /// structure as x, y, attribute triples (the first attribute, or 0).
    pub fn brush(&mut self, points: &[f64], width: f64, job: &str) -> Result<PointsResult, JsError> {
        let start = web_time::Instant::now();
        let stroke = polyline(points, "brush stroke")?;
        let mut job: PointsJob = serde_json::from_str(job).map_err(|e| error(format!("points options: {e}")))?;
        job.domain = DomainSpec::Stroke(StrokeSpec {
            points: stroke.points().iter().map(|p| vec![p.x, p.y]).collect(),
            width,
            scale_along: None,
        });
        let inputs = PointsInputs {
            existing: self.grown.clone(),
            integer_columns: &self.discrete,
            ..PointsInputs::new(self.exemplar.clone())
        };
        let run = job.run(inputs, &mut NoProgress).map_err(error)?;
        let points = run.output.points;
        let mut flat = Vec::with_capacity(points.len() * 3);
        for i in 0..points.len() {
            flat.extend_from_slice(&points.position(i)[..2]);
            flat.push(points.attributes_of(i).first().copied().unwrap_or(0.0));
        }
        let report = serde_json::Value::Object(run.figures).to_string();
        self.grown = Some(points);
        Ok(PointsResult { flat, report, milliseconds: elapsed_ms(start) })
    }

    /// Forgets the grown structure.
    pub fn clear(&mut self) {
        self.grown = None;
    }

    /// The exemplar as x, y, attribute triples.
    pub fn exemplar(&self) -> Vec<f64> {
        let set = &self.exemplar;
        (0..set.len())
            .flat_map(|i| {
                [set.position(i)[0], set.position(i)[1], set.attributes_of(i).first().copied().unwrap_or(0.0)]
            })
            .collect()
    }
}

/// Points as x, y, attribute triples, the report and the time.
#[wasm_bindgen]
#[derive(Debug)]
pub struct PointsResult {
    flat: Vec<f64>,
    report: String,
    milliseconds: f64,
}

#[wasm_bindgen]
impl PointsResult {
    /// x, y, attribute for every point.
    #[wasm_bindgen(getter)]
    pub fn points(&self) -> Vec<f64> {
        self.flat.clone()
    }
    /// The run's figures as JSON.
    #[wasm_bindgen(getter)]
    pub fn report(&self) -> String {
        self.report.clone()
    }
    /// Milliseconds the synthesis took in the module.
    #[wasm_bindgen(getter)]
    pub fn milliseconds(&self) -> f64 {
        self.milliseconds
    }
}

/// The strokes panel: a built-in reference drawing, its analysis at any scale, and synthesis.
#[wasm_bindgen]
#[derive(Debug)]
pub struct StrokesPanel {
    reference: Vec<Stroke>,
}

#[wasm_bindgen]
impl StrokesPanel {
    /// A panel on a built-in reference: `hatching` (a row of sketchy hatches) or `figures`
    /// (small drawn figures).
    #[wasm_bindgen(constructor)]
    pub fn new(reference: &str) -> Result<StrokesPanel, JsError> {
        use motif_strokes::samples::{FigureField, HatchRow, figure_field, hatch_row};
        let reference = match reference {
            "hatching" => {
                let row = HatchRow { count: 14, ..HatchRow::default() };
                hatch_row(
                    &row,
                    Point::new(20.0, 40.0),
                    |i| 0.25 * motif_core::math::sin(i as f64 * 0.7),
                    |_| [30, 30, 30, 255],
                    1,
                )
            }
            "figures" => {
                figure_field(&FigureField { columns: 5, rows: 4, ..FigureField::default() }, Point::new(20.0, 20.0), 1)
            }
            other => return Err(error(format!("no built-in reference named {other}; use hatching or figures"))),
        };
        Ok(StrokesPanel { reference })
    }

    /// A panel on your own reference: strokes as JSON (`[{points: [[x, y], ...], closed, width,
    /// colour: [r, g, b, a], fill: [r, g, b, a] | null}]`), as the page samples them from an SVG.
    pub fn from_strokes(strokes: &str) -> Result<StrokesPanel, JsError> {
        let reference = strokes_from_json(strokes).map_err(error)?;
        Ok(StrokesPanel { reference })
    }

    /// The reference strokes as JSON (`[{points, closed, width, colour, fill}]`).
    pub fn reference(&self) -> String {
        strokes_to_json(&self.reference).to_string()
    }

    /// The analysis at scale ε (`undefined` or `null`: inferred from the reference, as a strokes
    /// job without `scale`): per element its strokes and oriented box corners, as JSON, with the ε
    /// used (`scale`, `scale_inferred`) and the time it took.
    pub fn analyse(&self, scale: Option<f64>) -> Result<String, JsError> {
        let start = web_time::Instant::now();
        let job = StrokesJob::new(scale, TargetSpec::Rect([1.0, 1.0]));
        let (analysis, used) = job.analyse(&self.reference).map_err(error)?;
        let elements: Vec<serde_json::Value> = analysis
            .elements
            .iter()
            .map(|element| {
                let corners: Vec<[f64; 2]> = element.frame.corners().iter().map(|p| [p.x, p.y]).collect();
                serde_json::json!({ "strokes": element.strokes, "corners": corners })
            })
            .collect();
        Ok(serde_json::json!({
            "elements": elements,
            "scale": used.value,
            "scale_inferred": used.is_inferred(),
            "milliseconds": elapsed_ms(start),
        })
        .to_string())
    }

    /// Synthesizes inside the rectangle (0, 0)–(`width`, `height`) with the job `job` (JSON with
    /// any `motif strokes` option, and `scale` unless it is to be inferred); returns the strokes as
    /// JSON with the report.
    pub fn synthesize(&self, width: f64, height: f64, job: &str) -> Result<String, JsError> {
        let start = web_time::Instant::now();
        let mut job: StrokesJob = serde_json::from_str(job).map_err(|e| error(format!("strokes options: {e}")))?;
        job.target = TargetSpec::Rect([width, height]);
        let run = job.run(StrokesInputs::new(self.reference.clone()), &mut NoProgress).map_err(error)?;
        Ok(serde_json::json!({
            "strokes": strokes_to_json(&run.output.strokes),
            "report": run.figures,
            "milliseconds": elapsed_ms(start),
        })
        .to_string())
    }
}

/// The stylize panel: a built-in map guide and its crayon style, the segment textures
/// pre-synthesized once, and band-mode stylizations of painted target guides.
#[wasm_bindgen]
#[derive(Debug)]
pub struct StylizePanel {
    style: motif_core::FloatImage,
    guide: RgbaImage,
    textures: Vec<motif_jobs::stylize::SegmentTexture>,
}

#[wasm_bindgen]
impl StylizePanel {
    /// The built-in map (`size` pixels square) and style; pre-synthesizes one texture per map
    /// colour (`motif presynth`).
    #[wasm_bindgen(constructor)]
    pub fn new(size: usize) -> Result<StylizePanel, JsError> {
        if !(32..=512).contains(&size) {
            return Err(error(format!("size {size}: give 32–512 pixels")));
        }
        let guide = motif_stylize::samples::map_guide(size, size, 4, 1);
        let style = motif_stylize::samples::crayon_style(&guide, 1);
        let presynth: PresynthJob =
            serde_json::from_value(serde_json::json!({ "size": [size, size] })).map_err(error)?;
        let inputs = PresynthInputs { style: style.clone(), guide: guide.clone() };
        let textures = presynth.run(inputs, &mut NoProgress).map_err(error)?.textures;
        Ok(StylizePanel { style, guide: RgbaImage::from_float(&guide), textures })
    }

    /// The map guide (RGBA bytes): the source guide A, and the starting target guide.
    pub fn guide(&self) -> Vec<u8> {
        self.guide.as_bytes().to_vec()
    }

    /// The style A' (RGBA bytes).
    pub fn style(&self) -> Vec<u8> {
        RgbaImage::from_float(&self.style).as_bytes().to_vec()
    }

    /// The map colours (RGBA, 4 bytes each) a target guide may be painted with.
    pub fn palette(&self) -> Vec<u8> {
        self.textures
            .iter()
            .flat_map(|t| {
                let c: Vec<u8> = t.colour.iter().map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8).collect();
                [c[0], c[1], c[2], 255]
            })
            .collect()
    }

    /// Stylizes a painted target guide (RGBA bytes, `width` × `height`) in band mode with the job
    /// `job` (JSON; `band` and any `motif stylize` option).
    pub fn stylize(&self, rgba: &[u8], width: usize, height: usize, job: &str) -> Result<ImageResult, JsError> {
        let start = web_time::Instant::now();
        let mut job: StylizeJob = serde_json::from_str(job).map_err(|e| error(format!("stylize options: {e}")))?;
        job.options.own.segments = true;
        let target = rgba_image(rgba, width, height, "target guide")?;
        let source = self.guide.clone();
        let guides = vec![motif_jobs::stylize::guide_pair(&source, &target)];
        // 8-bit, as every front end hands the engine its images.
        let style = motif_core::ByteImage::from_float(&self.style);
        let inputs = StylizeInputs { textures: Some(self.textures.clone()), ..StylizeInputs::new(style, guides) };
        let run = job.run(inputs, &mut NoProgress).map_err(error)?;
        Ok(image_result(&RgbaImage::from_float(&run.output.image), &run.figures, start))
    }
}
