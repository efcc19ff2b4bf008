//! Structured patterns along curves, after Zhou, Lasram and Lefebvre, *By-example synthesis of
//! curvilinear structured patterns* (Eurographics 2013).
//!
//! A ribbon around the curve is sliced into pieces; each piece copies an undistorted, rotated
//! part of the exemplar, and a dynamic program picks the exemplar position of every piece so that
//! the colours across all piece boundaries match best (a global optimum). Modules, by section of
//! the paper:
//!
//! - [`ribbon`]: the ribbon's offset curves and the slicing into quadrilateral pieces (§1.1, §1.3).
//! - [`piece`]: a piece in exemplar space (rotation `M`, scale `s`, edges `L_i`, `R_i`) and the
//!   validity test of positions (§1.3, §3.1), over `U = W × (H + C)` candidates (§1.4), plus a
//!   minimum-coverage rule (not in the paper) that keeps thin slivers of the pattern out.
//! - [`cost`]: the matching cost ξ (binary and continuous alpha, `γ`) and the edge distance `D`
//!   with `C = ⌈‖L‖⌉` bilinear samples (§1, §1.3).
//! - [`dp`]: the dynamic program of Eq. 1 with backtracking (§1.4, §2): the plain reference
//!   solver, the exact fast solver and a brute-force enumerator for tests.
//! - [`closed`]: closed curves, the single-DP approximation and an exact, certified mode (§1.5).
//! - [`avoidance`]: avoidance maps and fold-over detection (§3.1).
//! - [`stitch`]: the edge alignment of Eq. 2–3 and its propagation inside pieces (§3.2).
//! - `render`: anti-aliased rasterization of the pieces; `repeat`: the classic arc-length
//!   texture-mapping baseline; [`overlay`]: the debug drawing; [`samples`]: generated exemplars
//!   for benchmarks.
//!
//! The entry point is [`synthesize`]. The crate does no I/O and builds for `wasm32`.

pub mod avoidance;
pub mod closed;
pub mod cost;
pub mod dp;
mod exemplar;
pub mod fidelity;
pub mod overlay;
pub mod piece;
mod render;
mod repeat;
pub mod ribbon;
pub mod samples;
pub mod stitch;

use motif_core::error::{check_positive, check_range};
use motif_core::kurbo::Affine;
use motif_core::timing::StageTimer;
use motif_core::{InvalidParameter, Point, Polyline, Progress, RgbaImage, Vec2};
use rayon::prelude::*;
use serde::Serialize;

use crate::avoidance::{FROM_FOLDOVER, ForbiddenMask};
pub use crate::cost::AlphaMode;
use crate::cost::{COST_SCALE, CostModel, edge_distance, left_edges, right_edges};
pub use crate::dp::Solver;
use crate::dp::{DpCounters, RowSpec};
use crate::exemplar::Exemplar;
pub use crate::overlay::debug_overlay;
use crate::piece::{PieceFrame, Position, candidate_count};
use crate::render::Shape;
use crate::ribbon::Ribbon;
use crate::stitch::Stitch;

/// How a closed curve is treated (§1.5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ClosedMode {
    /// `Approximate` for a closed curve, `Open` for an open one.
    Auto,
    /// The paper's single DP with backtracking from every terminal position.
    Approximate,
    /// Branch and bound over start positions with a certificate of optimality.
    Exact,
    /// Treat the curve as open (a closed curve is cut at its first point).
    Open,
}

/// Which pattern generator to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// The paper's synthesis: undistorted pieces placed by dynamic programming.
    Synthesis,
    /// The classic baseline: the exemplar repeated along the arc length and bent with the ribbon.
    Repeat,
}

/// Size of the output canvas.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Canvas {
    /// Fitted to the ribbon's bounds plus `margin` pixels; the curve is translated accordingly.
    Fit {
        /// Empty border around the ribbon, in pixels.
        margin: f64,
    },
    /// A fixed size; canvas pixel `(0, 0)` is the curve's document origin.
    Size {
        /// Width in pixels.
        width: usize,
        /// Height in pixels.
        height: usize,
    },
}

/// Parameters of the curve engine.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct CurveParams {
    /// Ribbon width `b` in canvas pixels (§1.1). Finite, > 0. Default 64. With scale `s`, each
    /// edge takes `C = ⌈s·b⌉` samples, so `s·b` should exceed the pattern's height in the exemplar.
    pub width: f64,
    /// Piece length `δ` along the curve, canvas pixels (§1.3). Finite, > 0, at most the curve's
    /// length. Default 24. Shorter pieces follow bends better but repeat more.
    pub piece_length: f64,
    /// Scale `s`: exemplar pixels per canvas pixel (§1.3). Finite, in `[0.05, 20]`. Default 1;
    /// 2 draws the pattern at half size.
    pub scale: f64,
    /// Closed-curve handling (§1.5). Default [`ClosedMode::Auto`].
    pub closed: ClosedMode,
    /// Synthesis or the repeat baseline. Default [`Method::Synthesis`].
    pub method: Method,
    /// DP solver (§1.4, §2). Default [`Solver::Exact`]; both give the same optimum.
    pub solver: Solver,
    /// Binary (the paper's ξ) or continuous alpha in ξ (§1). Default [`AlphaMode::Continuous`].
    pub alpha_mode: AlphaMode,
    /// `γ`, the cost of matching an opaque with a transparent pixel (§1). Finite, in
    /// `[1, 100000]`. Default 1024 (the paper's value).
    pub mismatch_penalty: f64,
    /// Run the stitching post-process (§3.2). Default false.
    pub stitch: bool,
    /// `P`, the stitching penalty for moving opaque samples (Eq. 3). Finite, in `[0, 100000]`.
    /// Default 32 (the paper's value).
    pub stitch_penalty: f64,
    /// Detect fold-overs and overlaps of the ribbon and keep the pattern out of them (§3.1).
    /// Default true.
    pub foldover_avoidance: bool,
    /// Pin the exemplar position of the first piece (`[x, y]`, top-left corner; must be a valid
    /// position). Default none: the first piece is free (§2).
    pub pin_first: Option<[i32; 2]>,
    /// Output canvas. Default fitted with a margin of 4 pixels.
    pub canvas: Canvas,
    /// Render samples per pixel along each axis (anti-aliasing; the forbidden-area test uses the
    /// same samples). Integer in `[1, 8]`. Default 3.
    pub samples_per_axis: usize,
    /// Alpha at or below which a pixel counts as transparent for the slicing test (§1.3). In
    /// `[0, 254]`. Default 8, so faint anti-aliasing fringes may be cut.
    pub cut_alpha: u8,
    /// Exact closed mode: most start positions tried with a pinned DP before giving up the
    /// certificate. Integer in `[1, 100000]`. Default 64.
    pub closed_max_starts: usize,
    /// Minimum coverage (§1.3, an addition to the paper's validity test): a piece position is
    /// valid only if the pattern pixels inside the piece number at least `min_coverage` × the
    /// piece's typical coverage (the median over the exemplar windows that are cut cleanly and
    /// hold the pattern's whole height). Without it the global optimum may copy one thin sliver
    /// of the pattern (the edge of one ring of a chain) along the whole curve: it is valid and its
    /// seams cost almost nothing. Finite, in `[0, 1]`; 0 is the paper's rule. Default 0.5.
    pub min_coverage: f64,
}

impl Default for CurveParams {
    fn default() -> Self {
        Self {
            width: 64.0,
            piece_length: 24.0,
            scale: 1.0,
            closed: ClosedMode::Auto,
            method: Method::Synthesis,
            solver: Solver::Exact,
            alpha_mode: AlphaMode::Continuous,
            mismatch_penalty: 1024.0,
            stitch: false,
            stitch_penalty: 32.0,
            foldover_avoidance: true,
            pin_first: None,
            canvas: Canvas::Fit { margin: 4.0 },
            samples_per_axis: 3,
            cut_alpha: 8,
            closed_max_starts: 64,
            min_coverage: 0.5,
        }
    }
}

/// What the engine works on.
#[derive(Debug, Clone, Copy)]
pub struct CurveInput<'a> {
    /// The exemplar: opaque pixels are the pattern, transparent ones the background.
    pub exemplar: &'a RgbaImage,
    /// The curve, in document coordinates (pixels); open or closed.
    pub curve: &'a Polyline,
    /// Optional avoidance map over the canvas (white = forbidden, §3.1); it must have the canvas
    /// size, and with a fitted canvas it sets the canvas size (origin at the document origin).
    pub avoidance: Option<&'a RgbaImage>,
}

/// Errors of the curve engine.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A parameter or input is outside what the engine accepts.
    #[error(transparent)]
    InvalidParameter(#[from] InvalidParameter),
    /// A piece has no position that slices the pattern completely.
    #[error(
        "no valid exemplar position for piece {piece}: the ribbon is {samples} exemplar pixels wide (width × scale) \
         but the pattern is {pattern_height} pixels tall; use a wider ribbon, a larger scale or shorter pieces"
    )]
    NoValidPosition {
        /// The piece.
        piece: usize,
        /// `C`.
        samples: usize,
        /// Height of the exemplar's non-transparent rows.
        pattern_height: usize,
    },
    /// The pinned first position is not valid.
    #[error("pin-first position ({x}, {y}) is not a valid position of the first piece ({count} valid positions exist)")]
    InvalidPin {
        /// x.
        x: i32,
        /// y.
        y: i32,
        /// Number of valid positions of the first piece.
        count: usize,
    },
}

/// One placed piece, as written to the pieces JSON.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlacedPiece {
    /// Index along the curve.
    pub index: usize,
    /// Arc length range `[x_i, x_{i+1}]` on the curve.
    pub arc: [f64; 2],
    /// Canvas corners: top-left, bottom-left, bottom-right, top-right.
    pub quad: [[f64; 2]; 4],
    /// `u_i`: exemplar position of the top-left corner (the corner sits at `(x + 0.5, y)`);
    /// `None` for a piece left empty because avoidance forbade every position.
    pub position: Option<[i32; 2]>,
    /// Rotation canvas → exemplar, radians.
    pub rotation: f64,
    /// Scale `s` (exemplar pixels per canvas pixel).
    pub scale: f64,
    /// Number of valid positions of this piece.
    pub valid_positions: usize,
    /// True when the piece has a seam to a next piece (all but the last of an open curve).
    pub has_seam: bool,
    /// Seam cost `D` to the next piece (paper units), after stitching when enabled.
    pub seam_cost: f64,
    /// Seam cost before stitching (paper units).
    pub seam_cost_unstitched: f64,
    /// Stitch remapping `T` of the right edge (identity without stitching).
    pub stitch: Vec<usize>,
}

/// Figures of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CurveReport {
    /// Synthesis or repeat.
    pub method: Method,
    /// Solver used.
    pub solver: Solver,
    /// Number of pieces.
    pub pieces: usize,
    /// `C`, samples per edge.
    pub samples_per_edge: usize,
    /// Canvas size.
    pub canvas: [usize; 2],
    /// Document coordinates of canvas pixel (0, 0)'s corner.
    pub canvas_origin: [f64; 2],
    /// `Ω` of the result (paper units), after stitching when enabled (the DP optimum is
    /// `total_cost_unstitched`).
    pub total_cost: f64,
    /// `Ω` of the DP optimum (paper units).
    pub total_cost_unstitched: f64,
    /// Mean seam cost (paper units).
    pub mean_seam_cost: f64,
    /// `Ω` as found by the dynamic program (paper units); equals `total_cost_unstitched`.
    pub dp_optimum: f64,
    /// Mean over pieces of (valid positions / `U`).
    pub valid_fraction: f64,
    /// Milliseconds per DP row.
    pub dp_row_ms: Vec<f64>,
    /// Median of `dp_row_ms`.
    pub dp_row_ms_median: f64,
    /// Maximum of `dp_row_ms`.
    pub dp_row_ms_max: f64,
    /// Milliseconds per stage.
    pub stages_ms: Vec<(String, f64)>,
    /// True when the curve was handled as closed.
    pub closed: bool,
    /// Exact closed mode: whether the optimum was proven.
    pub closed_certified: Option<bool>,
    /// Closed curves: start positions evaluated by pinned DPs.
    pub closed_starts_tried: usize,
    /// Closed curves: whether the single DP found a cycle directly.
    pub closed_directly: bool,
    /// Pieces left empty because avoidance forbade every position.
    pub empty_pieces: usize,
    /// Forbidden canvas pixels (avoidance map and fold-overs).
    pub forbidden_pixels: usize,
    /// Canvas pixels flagged by fold-over detection.
    pub foldover_pixels: usize,
    /// DP work counters.
    pub dp_counters: DpCounters,
    /// Fraction of predecessor/position pairs whose columns were never compared.
    pub columns_skipped_fraction: f64,
    /// Seams whose stitch is not the identity.
    pub stitched_seams: usize,
    /// Repeat baseline: mean |stretch − 1| of the ribbon borders (0 for synthesis: pieces are rigid).
    pub distortion_mean: f64,
    /// Repeat baseline: max |stretch − 1| of the ribbon borders.
    pub distortion_max: f64,
    /// Repeat baseline: number of places where the tiled exemplar wraps around.
    pub wrap_seams: usize,
}

/// The result of [`synthesize`].
#[derive(Debug, Clone)]
pub struct CurveOutput {
    /// The rendered canvas (transparent background).
    pub image: RgbaImage,
    /// The placed pieces (empty for the repeat baseline).
    pub pieces: Vec<PlacedPiece>,
    /// Figures.
    pub report: CurveReport,
    /// Forbidden canvas pixels.
    pub forbidden: ForbiddenMask,
    /// Top border of the ribbon, canvas coordinates.
    pub ribbon_top: Vec<Point>,
    /// Bottom border of the ribbon, canvas coordinates.
    pub ribbon_bottom: Vec<Point>,
}

/// Largest canvas side accepted.
pub const MAX_CANVAS_SIDE: usize = 16384;

/// Checks the parameters and inputs; returns the resolved closed flag.
fn validate(input: &CurveInput<'_>, params: &CurveParams) -> Result<bool, Error> {
    check_positive("width", params.width)?;
    check_positive("piece-length", params.piece_length)?;
    check_range("scale", params.scale, 0.05, 20.0)?;
    check_range("mismatch-penalty", params.mismatch_penalty, 1.0, 100_000.0)?;
    check_range("stitch-penalty", params.stitch_penalty, 0.0, 100_000.0)?;
    motif_core::error::check_count("samples-per-axis", params.samples_per_axis, 1, 8)?;
    motif_core::error::check_count("closed-max-starts", params.closed_max_starts, 1, 100_000)?;
    check_range("min-coverage", params.min_coverage, 0.0, 1.0)?;
    if params.cut_alpha == 255 {
        return Err(InvalidParameter::new("cut-alpha", 255, "must be between 0 and 254").into());
    }
    // Pieces live in exemplar space: keep them (and the transparent margin around the exemplar
    // that their positions need) to a sane size.
    if params.width * params.scale > 1024.0 {
        return Err(
            InvalidParameter::new("width", params.width, "width × scale must be at most 1024 exemplar pixels").into()
        );
    }
    if params.piece_length * params.scale > 1024.0 {
        return Err(InvalidParameter::new(
            "piece-length",
            params.piece_length,
            "piece-length × scale must be at most 1024 exemplar pixels",
        )
        .into());
    }
    let exemplar = input.exemplar;
    if exemplar.is_empty() {
        return Err(InvalidParameter::new("exemplar", "0×0", "must have pixels").into());
    }
    if exemplar.width() > 2048 || exemplar.height() > 2048 {
        return Err(InvalidParameter::new(
            "exemplar",
            format!("{}×{}", exemplar.width(), exemplar.height()),
            "must be at most 2048×2048 (the dynamic program grows with the square of the pixel count)",
        )
        .into());
    }
    if exemplar.is_fully_transparent() {
        return Err(InvalidParameter::new(
            "exemplar",
            "fully transparent",
            "must contain opaque pixels (the pattern) on a transparent background",
        )
        .into());
    }
    if exemplar.is_fully_opaque() {
        return Err(InvalidParameter::new(
            "exemplar",
            "fully opaque",
            "must have a transparent background around the pattern (pieces are cut in transparent pixels)",
        )
        .into());
    }
    if let Canvas::Size { width, height } = params.canvas {
        if width == 0 || height == 0 || width > MAX_CANVAS_SIDE || height > MAX_CANVAS_SIDE {
            return Err(InvalidParameter::new(
                "canvas",
                format!("{width}×{height}"),
                format!("each side must be between 1 and {MAX_CANVAS_SIDE}"),
            )
            .into());
        }
    }
    if let Canvas::Fit { margin } = params.canvas {
        check_range("margin", margin, 0.0, 4096.0)?;
    }
    let length = input.curve.length();
    if params.piece_length > length {
        return Err(InvalidParameter::new(
            "piece-length",
            params.piece_length,
            format!("must not exceed the curve's length ({length:.2})"),
        )
        .into());
    }
    let closed = match (params.closed, input.curve.is_closed()) {
        (ClosedMode::Auto, closed) => closed,
        (ClosedMode::Open, _) => false,
        (ClosedMode::Approximate | ClosedMode::Exact, true) => true,
        (mode, false) => {
            return Err(InvalidParameter::new(
                "closed",
                format!("{mode:?}").to_lowercase(),
                "the curve is open; use auto or no (close the path with Z in SVG)",
            )
            .into());
        }
    };
    Ok(closed)
}

/// The curve as used: cut open when a closed curve is treated as open.
fn working_curve(curve: &Polyline, closed: bool) -> Result<Polyline, InvalidParameter> {
    if curve.is_closed() && !closed {
        let mut points = curve.points().to_vec();
        points.push(points[0]);
        Polyline::new(points, false)
    } else {
        Ok(curve.clone())
    }
}

/// Border points of the ribbon at about one canvas pixel apart.
fn ribbon_borders(ribbon: &Ribbon) -> (Vec<Point>, Vec<Point>) {
    let length = ribbon.length();
    let steps = (length.ceil() as usize).max(2);
    let xs = (0..=steps).map(|i| length * i as f64 / steps as f64);
    xs.map(|x| (ribbon.top(x), ribbon.bottom(x))).unzip()
}

/// Canvas size and the document → canvas translation.
fn canvas_geometry(
    curve: &Polyline,
    params: &CurveParams,
    avoidance: Option<&RgbaImage>,
) -> Result<(usize, usize, Vec2), Error> {
    if let Some(map) = avoidance {
        if let Canvas::Size { width, height } = params.canvas {
            if (width, height) != (map.width(), map.height()) {
                return Err(InvalidParameter::new(
                    "avoid",
                    format!("{}×{}", map.width(), map.height()),
                    format!("the avoidance map must have the canvas size {width}×{height}"),
                )
                .into());
            }
        }
        if map.width() == 0 || map.height() == 0 || map.width() > MAX_CANVAS_SIDE || map.height() > MAX_CANVAS_SIDE {
            return Err(InvalidParameter::new(
                "avoid",
                format!("{}×{}", map.width(), map.height()),
                format!("each side must be between 1 and {MAX_CANVAS_SIDE}"),
            )
            .into());
        }
        return Ok((map.width(), map.height(), Vec2::ZERO));
    }
    match params.canvas {
        Canvas::Size { width, height } => Ok((width, height, Vec2::ZERO)),
        Canvas::Fit { margin } => {
            let ribbon = Ribbon::new(curve, params.width)?;
            let (top, bottom) = ribbon_borders(&ribbon);
            let bounds = motif_core::geometry::bounds_of(&[top, bottom].concat());
            let origin = Vec2::new((bounds.x0 - margin).floor(), (bounds.y0 - margin).floor());
            let width = (bounds.x1 + margin - origin.x).ceil() as usize;
            let height = (bounds.y1 + margin - origin.y).ceil() as usize;
            if width > MAX_CANVAS_SIDE || height > MAX_CANVAS_SIDE {
                return Err(InvalidParameter::new(
                    "canvas",
                    format!("{width}×{height}"),
                    format!("the fitted canvas exceeds {MAX_CANVAS_SIDE} pixels per side; scale the curve down"),
                )
                .into());
            }
            Ok((width.max(1), height.max(1), -origin))
        }
    }
}

fn median(values: &[f64]) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let mid = sorted.len() / 2;
    if sorted.len() % 2 == 1 { sorted[mid] } else { 0.5 * (sorted[mid - 1] + sorted[mid]) }
}

/// Number of rows of the exemplar holding non-transparent pixels (for error messages).
fn pattern_height(image: &RgbaImage) -> usize {
    image.opaque_bounds().map_or(0, |(_, y0, _, y1)| y1 - y0)
}

/// Synthesizes the pattern of `input.exemplar` along `input.curve`.
pub fn synthesize(
    input: &CurveInput<'_>,
    params: &CurveParams,
    progress: &mut dyn Progress,
) -> Result<CurveOutput, Error> {
    let closed = validate(input, params)?;
    let mut timer = StageTimer::new();
    timer.start("ribbon");
    let curve = working_curve(input.curve, closed)?;
    let (canvas_width, canvas_height, shift) = canvas_geometry(&curve, params, input.avoidance)?;
    let curve = curve.transformed(Affine::translate(shift))?;
    let ribbon = Ribbon::new(&curve, params.width)?;
    let quads = ribbon::slice(&ribbon, params.piece_length);
    let samples = ((params.width * params.scale).ceil() as usize).max(1);
    let frames: Vec<PieceFrame> = quads.iter().map(|quad| PieceFrame::new(quad, params.scale, samples)).collect();
    let (ribbon_top, ribbon_bottom) = ribbon_borders(&ribbon);
    let margin = frames.iter().map(PieceFrame::required_margin).max().unwrap_or(8);
    let exemplar = Exemplar::new(input.exemplar, margin as usize, params.cut_alpha);
    let model = CostModel::new(params.alpha_mode, params.mismatch_penalty);
    let n_samples = params.samples_per_axis;

    timer.start("avoidance");
    progress.report("avoidance", 0.0);
    let mut forbidden = ForbiddenMask::empty(canvas_width, canvas_height);
    if let Some(map) = input.avoidance {
        forbidden.add_map(map);
    }
    if params.foldover_avoidance && params.method == Method::Synthesis {
        forbidden.add_foldovers(&frames, n_samples);
    }
    let foldover_pixels = forbidden.flags.iter().filter(|&&f| f & FROM_FOLDOVER != 0).count();
    let forbidden_pixels = forbidden.count();

    let candidates = candidate_count(input.exemplar.width(), input.exemplar.height(), samples);
    let mut report = CurveReport {
        method: params.method,
        solver: params.solver,
        pieces: 0,
        samples_per_edge: samples,
        canvas: [canvas_width, canvas_height],
        canvas_origin: [-shift.x, -shift.y],
        total_cost: 0.0,
        total_cost_unstitched: 0.0,
        mean_seam_cost: 0.0,
        dp_optimum: 0.0,
        valid_fraction: 0.0,
        dp_row_ms: Vec::new(),
        dp_row_ms_median: 0.0,
        dp_row_ms_max: 0.0,
        stages_ms: Vec::new(),
        closed,
        closed_certified: None,
        closed_starts_tried: 0,
        closed_directly: false,
        empty_pieces: 0,
        forbidden_pixels,
        foldover_pixels,
        dp_counters: DpCounters::default(),
        columns_skipped_fraction: 0.0,
        stitched_seams: 0,
        distortion_mean: 0.0,
        distortion_max: 0.0,
        wrap_seams: 0,
    };

    if params.method == Method::Repeat {
        timer.start("render");
        progress.report("render", 0.0);
        let (triangles, stretch) = repeat::triangulate(&ribbon);
        let shapes = repeat::shapes(&triangles, &exemplar, params.width, params.scale, (canvas_width, canvas_height));
        let image = render::render(canvas_width, canvas_height, n_samples, &shapes);
        let deviations: Vec<f64> = stretch.iter().map(|s| (s - 1.0).abs()).collect();
        report.distortion_mean = deviations.iter().sum::<f64>() / deviations.len().max(1) as f64;
        report.distortion_max = deviations.iter().copied().fold(0.0, f64::max);
        report.wrap_seams = (params.scale * ribbon.length() / f64::from(exemplar.width)).floor() as usize;
        report.stages_ms = timer.finish();
        progress.report("render", 1.0);
        return Ok(CurveOutput { image, pieces: Vec::new(), report, forbidden, ribbon_top, ribbon_bottom });
    }

    timer.start("valid positions");
    progress.report("valid positions", 0.0);
    let piece_forbidden: Vec<Vec<Vec2>> = frames
        .par_iter()
        .map(|frame| {
            if forbidden_pixels == 0 { Vec::new() } else { avoidance::forbidden_samples(frame, &forbidden, n_samples) }
        })
        .collect();
    let valid: Vec<(Vec<Position>, bool)> = frames
        .par_iter()
        .zip(&piece_forbidden)
        .map(|(frame, samples)| {
            let runs = avoidance::forbidden_runs(samples);
            let positions = frame.valid_positions(&exemplar, &runs, params.min_coverage);
            // A piece that a forbidden area (a fold-over, the avoidance map) leaves with no valid
            // position stays empty; the DP pays for the gap at its seams.
            if positions.is_empty() && !runs.is_empty() {
                (vec![frame.empty_position()], true)
            } else {
                (positions, false)
            }
        })
        .collect();
    if let Some(piece) = valid.iter().position(|(positions, _)| positions.is_empty()) {
        return Err(Error::NoValidPosition { piece, samples, pattern_height: pattern_height(input.exemplar) });
    }
    let (valid, empty): (Vec<Vec<Position>>, Vec<bool>) = valid.into_iter().unzip();
    report.empty_pieces = empty.iter().filter(|&&e| e).count();
    report.valid_fraction = valid
        .iter()
        .zip(&empty)
        .map(|(positions, &is_empty)| if is_empty { 0.0 } else { positions.len() as f64 / candidates as f64 })
        .sum::<f64>()
        / valid.len() as f64;
    let pin_storage: Vec<Position>;
    let first_positions: &[Position] = match params.pin_first {
        Some(pin) => {
            if !valid[0].contains(&pin) || empty[0] {
                return Err(Error::InvalidPin {
                    x: pin[0],
                    y: pin[1],
                    count: if empty[0] { 0 } else { valid[0].len() },
                });
            }
            pin_storage = vec![pin];
            &pin_storage
        }
        None => &valid[0],
    };

    timer.start("dynamic program");
    let mut rows: Vec<RowSpec<'_>> =
        frames.iter().zip(&valid).map(|(frame, positions)| RowSpec { frame, positions }).collect();
    rows[0].positions = first_positions;
    if closed {
        rows.push(RowSpec { frame: &frames[0], positions: first_positions });
    }
    let total_rows = rows.len();
    let mut on_row = |row: usize| progress.report("dynamic program", row as f64 / total_rows.max(1) as f64);
    let (path, optimum, row_ms, counters) = if closed {
        let exact = params.closed == ClosedMode::Exact;
        let cycle =
            closed::solve_closed(&exemplar, &model, &rows, params.solver, exact, params.closed_max_starts, &mut on_row);
        report.closed_certified = if params.pin_first.is_some() && exact { Some(true) } else { cycle.certified };
        report.closed_starts_tried = cycle.starts_tried;
        report.closed_directly = cycle.closed_directly;
        (cycle.path, cycle.cost, cycle.row_ms, cycle.counters)
    } else {
        let table = dp::solve(&exemplar, &model, &rows, params.solver, &mut on_row);
        let last = (0..table.last_costs.len()).min_by_key(|&i| (table.last_costs[i], i)).expect("non-empty row");
        (table.backtrack(last), table.last_costs[last], table.row_ms, table.counters)
    };
    let positions: Vec<Position> = (0..frames.len()).map(|i| rows[i].positions[path[i]]).collect();
    report.dp_row_ms_median = median(&row_ms);
    report.dp_row_ms_max = row_ms.iter().copied().fold(0.0, f64::max);
    report.dp_row_ms = row_ms;
    report.dp_counters = counters;
    report.columns_skipped_fraction = counters.skipped_fraction();

    timer.start("stitching");
    let n = frames.len();
    let seam_count = if closed { n } else { n - 1 };
    let stitches: Vec<Stitch> = (0..seam_count)
        .into_par_iter()
        .map(|i| {
            let next = (i + 1) % n;
            let rights = right_edges(&exemplar, &model, &frames[i], &[positions[i]]);
            let lefts = left_edges(&exemplar, &model, &[positions[next]], samples);
            let cost = u64::from(edge_distance(&model, &rights, 0, &lefts, 0));
            if !params.stitch || empty[i] || empty[next] {
                return Stitch::identity(samples, cost);
            }
            let stitch = stitch::align(&model, &rights, 0, &lefts, 0, params.stitch_penalty);
            // The deformation must not draw pattern into a forbidden pixel.
            let safe = piece_forbidden[i].iter().all(|&local| {
                let moved = stitch::deform(&frames[i], &stitch.remap, local);
                avoidance::footprint(moved).iter().all(|&(dx, dy)| {
                    let (x, y) = (positions[i][0] + dx, positions[i][1] + dy);
                    !exemplar.in_storage(x, y) || exemplar.rgba[exemplar.index(x, y)][3] == 0
                })
            });
            if safe { stitch } else { Stitch::identity(samples, cost) }
        })
        .collect();
    report.stitched_seams = stitches.iter().filter(|s| !s.is_identity()).count();
    let before: u64 = stitches.iter().map(|s| s.before).sum();
    let after: u64 = stitches.iter().map(|s| s.after).sum();
    // The seams recomputed at the chosen positions add up to the DP optimum Ω.
    debug_assert_eq!(before, optimum, "seam costs must add up to the DP optimum");
    report.dp_optimum = optimum as f64 / COST_SCALE;
    report.total_cost_unstitched = before as f64 / COST_SCALE;
    report.total_cost = after as f64 / COST_SCALE;
    report.mean_seam_cost = if seam_count == 0 { 0.0 } else { report.total_cost / seam_count as f64 };
    report.pieces = n;

    timer.start("render");
    progress.report("render", 0.0);
    let shapes: Vec<Shape<'_>> = (0..n)
        .filter(|&i| !empty[i])
        .map(|i| {
            let frame = &frames[i];
            let u = positions[i];
            let remap = stitches.get(i).filter(|s| !s.is_identity()).map(|s| s.remap.clone());
            let exemplar = &exemplar;
            Shape {
                bounds: avoidance::canvas_box(frame, canvas_width, canvas_height),
                sampler: Box::new(move |p: Point| {
                    let local = frame.to_local(p);
                    if !frame.contains_local(local) {
                        return None;
                    }
                    let local = match &remap {
                        Some(remap) => stitch::deform(frame, remap, local),
                        None => local,
                    };
                    let (x, y) = PieceFrame::exemplar_point(u, local);
                    Some(exemplar.sample_premultiplied(x, y))
                }),
            }
        })
        .collect();
    let image = render::render(canvas_width, canvas_height, n_samples, &shapes);
    progress.report("render", 1.0);

    let pieces = (0..n)
        .map(|i| {
            let stitch = stitches.get(i);
            PlacedPiece {
                index: i,
                arc: [quads[i].start, quads[i].end],
                quad: quads[i].corners.map(|c| [c.x, c.y]),
                position: if empty[i] { None } else { Some(positions[i]) },
                rotation: frames[i].angle(),
                scale: params.scale,
                valid_positions: if empty[i] { 0 } else { valid[i].len() },
                has_seam: stitch.is_some(),
                seam_cost: stitch.map_or(0.0, |s| s.after as f64 / COST_SCALE),
                seam_cost_unstitched: stitch.map_or(0.0, |s| s.before as f64 / COST_SCALE),
                stitch: stitch.map_or_else(|| (0..samples).collect(), |s| s.remap.clone()),
            }
        })
        .collect();
    report.stages_ms = timer.finish();
    Ok(CurveOutput { image, pieces, report, forbidden, ribbon_top, ribbon_bottom })
}

#[cfg(test)]
mod tests;
