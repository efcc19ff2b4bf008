//! `curve` jobs: structured raster patterns along curves (`motif_curve`).
//!
//! Option names are the flags of `motif curve` ([`CurveOptions`], declared once); none is
//! required: a missing width or piece length is inferred from the first exemplar
//! (`motif_curve::Dimensions::resolve`) and settled by a short search over whole runs
//! (module `search`), every other option takes the engine's default
//! ([`motif_curve::Params::DEFAULT`]). The exemplars, the curve and the avoidance map come
//! decoded (the CLI reads PNG and SVG).

use motif_core::{Polyline, Progress, RgbaImage};
use motif_curve::{AlphaMode, Canvas, ClosedMode, Dimensions, Input, Method, Output, Params, PieceShape, Solver};
use motif_curve::{PatchFidelity, patch_fidelity};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value, json};

/// The engine's types that curve runs are made of, named here so that front ends need no engine
/// crate: an editing session re-solves only what changed ([`CurveJob::run_in_session`]).
pub use motif_curve::{Dimension, Fit, Flip, Incremental, debug_overlay};

use crate::JobError;
use crate::options::{Colour, Declared, Described};

mod search;

pub use search::Trial;

/// The exemplars after the first with the tile images appended, and for each of the start, end
/// and corner tiles the index of its image among all exemplars.
type TileExemplars<'a> = (std::borrow::Cow<'a, [RgbaImage]>, [Option<usize>; 3]);

crate::choice_option!(ClosedMode: "auto", "approx", "exact", "no");
crate::choice_option!(Method: "synth", "repeat");
crate::choice_option!(Solver: "exact", "reference", "coarse", "auto");
crate::choice_option!(AlphaMode: "binary", "continuous");
crate::choice_option!(PieceShape: "rigid", "bent");
crate::choice_option!(Fit: "none", "stretch", "space");
crate::choice_option!(Flip: "none", "along", "across", "both");

crate::declare_options! {
    /// Every option of `motif curve` that is neither a file nor the flattening tolerance of one,
    /// declared once.
    pub struct CurveOptions {
        /// Ribbon width b in canvas pixels, > 0. Width × scale is the number of samples per piece
        /// edge (C) and should exceed the pattern's height in the exemplar. Default: inferred from
        /// the first exemplar, the pattern's height (rows with alpha above --cut-alpha) plus the
        /// clear row above and below, 15% wider, divided by the scale; then every whole width
        /// within 4% of it, and 5% narrower, 5% and 10% wider, are tried at the settled piece
        /// length and the best-scoring output kept (report `size_search`).
        [value_name: "B"]
        width: Option<f64> = None,
        /// Piece length δ along the curve in canvas pixels, > 0 and at most the curve's length.
        /// Default: inferred from the first exemplar, 0.55 of the pattern's period along x (the
        /// first strong peak of the autocorrelation of its columns), kept between a quarter and
        /// 0.6 of the pattern's height, divided by the scale; 0.3 of the pattern's height when it
        /// has no period. That guess, 0.8, 1.25, 1.6, 2 and 2.5 times it and half the period are
        /// each run, then twice the lengths halfway to the best one's neighbours, and the output
        /// whose patches are closest to the exemplar's (fewest motifs cut) is kept; giving the
        /// value skips this search.
        [value_name: "D"]
        piece_length: Option<f64> = None,
        /// Scale s: exemplar pixels per canvas pixel (2 draws the pattern at half size).
        [value_name: "S", range: (0.05, 20.0)]
        scale: f64 = DEFAULTS.scale,
        /// Closed-curve handling: auto (approx for a closed curve, no for an open one); approx, the
        /// paper's single dynamic program with backtracking from every terminal position; exact,
        /// branch and bound over start positions with a certificate of optimality; no, the curve
        /// treated as open (a closed curve is cut at its first point).
        [value_name: "auto|approx|exact|no"]
        closed: ClosedMode = DEFAULTS.closed,
        /// Do not detect fold-overs and overlaps of the ribbon (by default the pattern avoids them).
        no_foldover_avoidance: bool = !DEFAULTS.foldover_avoidance,
        /// Stitch piece boundaries (edge alignment with penalty P, propagated inside the pieces).
        stitch: bool = DEFAULTS.stitch,
        /// Stitching penalty P for moving opaque samples.
        [value_name: "P", range: (0.0, 100_000.0)]
        stitch_penalty: f64 = DEFAULTS.stitch_penalty,
        /// Pattern generator: synth, the paper's synthesis (undistorted pieces placed by dynamic
        /// programming), or repeat, the classic baseline (the exemplar repeated along the arc length
        /// and bent with the ribbon).
        [value_name: "synth|repeat"]
        method: Method = DEFAULTS.method,
        /// Dynamic-programming solver: exact (merged identical edges, branch and bound over a
        /// profile tree, lower bounds and early exit) or reference (the plain O(V²C) dynamic
        /// program), which find the same optimum; or coarse, for large or dense exemplars: the
        /// program on cells of 2–4 pixels first, then the exact one in bands of positions around
        /// the best cells (a cost at least the optimum's; --check-gap measures the difference);
        /// or auto: exact, but coarse on an open curve whose program has over 10^10 position
        /// pairs (a large exemplar along a long curve). The report names the solver that ran.
        [value_name: "auto|exact|reference|coarse"]
        solver: Solver = DEFAULTS.solver,
        /// With --solver coarse, also run the exact solver and report the exact optimum and the
        /// coarse solver's cost gap (exact_optimum, cost_gap); takes at least an exact run's time.
        check_gap: bool = DEFAULTS.check_gap,
        /// Alpha in the matching cost: binary, the paper's ξ (alpha thresholded at 128, opaque or
        /// transparent), or continuous, ξ blended by alpha for anti-aliased and semi-transparent
        /// exemplars.
        [value_name: "binary|continuous"]
        alpha: AlphaMode = DEFAULTS.alpha_mode,
        /// γ, the matching cost of an opaque against a transparent pixel.
        [value_name: "GAMMA", range: (1.0, 100_000.0)]
        gamma: f64 = DEFAULTS.mismatch_penalty,
        /// Pin the first piece's exemplar position (top-left corner, pixels; must be a valid
        /// position).
        [value_name: "X,Y"]
        pin_first: Option<[i32; 2]> = DEFAULTS.pin_first,
        /// Canvas size in pixels (document origin at the top-left); default: fitted to the ribbon.
        [value_name: "WxH"]
        canvas: Option<[usize; 2]> = None,
        /// Margin around the ribbon when the canvas is fitted, pixels.
        [value_name: "PX", range: (0.0, 4096.0)]
        margin: f64 = fitted_margin(),
        /// Anti-aliasing: render samples per pixel along each axis.
        [value_name: "N", range: (1.0, 8.0)]
        samples: usize = DEFAULTS.samples_per_axis,
        /// Alpha at or below which a pixel counts as transparent when checking that a piece slices
        /// the pattern completely.
        [value_name: "A", range: (0.0, 254.0)]
        cut_alpha: u8 = DEFAULTS.cut_alpha,
        /// Minimum coverage: a piece position is valid only if it holds at least this share of the
        /// pattern pixels a typical piece holds (the median over exemplar windows spanning the
        /// pattern's height). Keeps the optimum from repeating a thin sliver; 0 = the paper's rule
        /// (and no check for an optimum that repeats a thin strip either).
        [value_name: "F", range: (0.0, 1.0)]
        min_coverage: f64 = DEFAULTS.min_coverage,
        /// Repetition penalty W (not in the paper), in seam-cost units: each pair of pieces at most
        /// --variety-radius pieces apart that copy the same exemplar window costs W. 0 = the
        /// paper's energy, which may alternate two windows along a straight line.
        [value_name: "W", range: (0.0, 1e6)]
        variety: f64 = DEFAULTS.variety,
        /// How many pieces apart a repeated window is penalised by --variety.
        [value_name: "R", range: (1.0, 1000.0)]
        variety_radius: usize = DEFAULTS.variety_radius,
        /// Piece shape: bent pieces follow the ribbon (seams compare vertical columns, so the
        /// exemplar continues across them; stretched outside bends); rigid pieces are the paper's
        /// undistorted, rotated copies.
        [value_name: "rigid|bent"]
        pieces_shape: PieceShape = DEFAULTS.piece_shape,
        /// Width profile: comma-separated T:F pairs, T the fraction of the curve's length (0–1,
        /// ascending) and F the factor (0.1–10) multiplying --width there, interpolated in between;
        /// the pattern scales with the width (e.g. 0:0.5,0.5:1.5,1:0.5 swells in the middle).
        /// Needs bent pieces.
        [value_name: "T:F,..."]
        width_profile: Vec<[f64; 2]> = Vec::new(),
        /// Round bends of the curve tighter than F × width to that radius, so that the ribbon does
        /// not fold at cusps and corners (where the paper leaves pieces empty); 0 keeps the curve
        /// as given.
        [value_name: "F", range: (0.0, 8.0)]
        round_bends: f64 = DEFAULTS.round_bends,
        /// Measure the result against the exemplar (patches read back along the curve, nearest
        /// exemplar patch) and add the figures to the report and the summary.
        fidelity: bool = false,
        /// Exact closed mode: start positions tried at most before giving up the certificate.
        [value_name: "N", range: (1.0, 100_000.0)]
        closed_max_starts: usize = DEFAULTS.closed_max_starts,
        /// How the pieces meet the curve's length, as a pattern brush fits its tiles: none cuts
        /// the last piece where an open curve ends (the paper); stretch draws a whole number of
        /// pieces, each stretched or squeezed along the curve; space draws as many whole pieces as
        /// fit, with equal gaps between them, each cut where the exemplar is clear so that no motif
        /// is cut at a gap. Stretch needs bent pieces.
        [value_name: "none|stretch|space"]
        fit: Fit = DEFAULTS.fit,
        /// Mirror the exemplar before synthesis: along (the pattern runs the other way), across
        /// (its top faces the other side of the curve) or both.
        [value_name: "none|along|across|both"]
        flip: Flip = DEFAULTS.flip,
        /// Colourize the pattern as tints of this colour (#RRGGBB): black becomes the colour,
        /// white stays white, greys become lighter tints; transparency is kept.
        [value_name: "#RRGGBB"]
        tint: Option<Colour> = None,
        /// A start tile: columns X0,X1 (X0 < X1) of the first exemplar, drawn whole as the first
        /// piece of an open curve (an end cap, a clasp) and joined to the next piece by the same
        /// seam cost; the dynamic program chooses its height. Its length along the curve is
        /// (X1 − X0) / scale. The command line also takes a PNG file of the tile here (as
        /// --start-tile-image).
        [value_name: "X0,X1"]
        start_tile: Option<[i32; 2]> = None,
        /// An end tile: columns X0,X1 of the first exemplar, drawn whole as the last piece, ending
        /// at the curve's end (or, on the command line, a PNG file of the tile).
        [value_name: "X0,X1"]
        end_tile: Option<[i32; 2]> = None,
        /// A corner tile: columns X0,X1 of the first exemplar, drawn whole and centred on every
        /// corner sharper than --corner-angle (a frame's corner piece), on open and closed curves,
        /// joined to the pieces beside it by the same seam cost. A corner too close to another or
        /// to an end to leave half a piece between them is left to the pieces. The command line
        /// also takes a PNG file of the tile here.
        [value_name: "X0,X1"]
        corner_tile: Option<[i32; 2]> = None,
        /// With --corner-tile: the turn, in degrees, that makes a corner (the angle between the
        /// curve's directions half a tile before and half a tile after it).
        [value_name: "DEG", range: (10.0, 179.0)]
        corner_angle: f64 = DEFAULTS.corner_angle,
    }
}

/// The engine's defaults, which the options take theirs from.
const DEFAULTS: Params = Params::DEFAULT;

/// A tile's columns as the engine takes them (the engine checks them against the exemplar).
fn tile_columns(name: &str, columns: Option<[i32; 2]>) -> Result<Option<[u32; 2]>, JobError> {
    let Some([x0, x1]) = columns else { return Ok(None) };
    match (u32::try_from(x0), u32::try_from(x1)) {
        (Ok(x0), Ok(x1)) => Ok(Some([x0, x1])),
        _ => Err(motif_core::InvalidParameter::new(name, format!("{x0},{x1}"), "columns must not be negative").into()),
    }
}

/// The margin of the engine's default canvas, fitted to the ribbon.
fn fitted_margin() -> f64 {
    match DEFAULTS.canvas {
        Canvas::Fit { margin } => margin,
        Canvas::Size { .. } => 0.0,
    }
}

/// A curve job: the run's memory bound and every option ([`CurveOptions`]).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(try_from = "Described<CurveJobFields>")]
pub struct CurveJob {
    /// Refuse runs whose estimated peak memory passes this: bytes, or a size such as `"8G"`
    /// (default: the engine's, 4 GiB; the CLI passes half of the machine's memory).
    #[serde(rename = "max-memory")]
    pub max_memory: Option<u64>,
    /// Every option.
    #[serde(flatten)]
    pub options: CurveOptions,
}

/// The fields of a [`CurveJob`] outside its options, as a description holds them.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub struct CurveJobFields {
    #[serde(default, deserialize_with = "crate::memory_size::optional")]
    max_memory: Option<u64>,
}

impl TryFrom<Described<CurveJobFields>> for CurveJob {
    type Error = String;
    fn try_from(described: Described<CurveJobFields>) -> Result<Self, String> {
        let (fields, options) = described.split()?;
        Ok(Self { max_memory: fields.max_memory, options })
    }
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
    /// The widths and piece lengths the size search tried (empty when both were given); the
    /// output is the one of the lowest score.
    pub size_trials: Vec<Trial>,
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
    /// Start, end and corner tiles drawn from images of their own (their whole pattern), in place
    /// of the columns of `start-tile`, `end-tile` and `corner-tile`.
    pub tile_images: [Option<&'a RgbaImage>; 3],
}

impl<'a> CurveInputs<'a> {
    /// One exemplar along `curve`: no more exemplars, no avoidance map, no tile images.
    pub fn new(exemplar: &'a RgbaImage, curve: &'a Polyline) -> Self {
        Self { exemplar, more_exemplars: &[], curve, avoidance: None, tile_images: [None; 3] }
    }
}

impl CurveJob {
    /// A job with the given width and piece length and every other option at its default
    /// ([`default`](Default::default) leaves the width and piece length to be inferred).
    pub fn new(width: f64, piece_length: f64) -> Self {
        let options = CurveOptions { width: Some(width), piece_length: Some(piece_length), ..CurveOptions::default() };
        Self { max_memory: None, options }
    }

    /// The engine's parameters for `inputs`, with the width and piece length each given or
    /// inferred from the first exemplar (an inferred piece length is capped at the curve's length).
    pub fn params(&self, inputs: &CurveInputs<'_>) -> Result<(Params, Dimensions), JobError> {
        self.options.check_ranges()?;
        let dimensions = self.dimensions(inputs)?;
        let params = self.params_with(dimensions.width.value, dimensions.piece_length.value)?;
        Ok((params, dimensions))
    }

    /// The width and piece length: the job's, or inferred where it has none.
    fn dimensions(&self, inputs: &CurveInputs<'_>) -> Result<Dimensions, JobError> {
        let options = &self.options;
        let mut dimensions = Dimensions::resolve(
            inputs.exemplar,
            options.width,
            options.piece_length,
            options.scale,
            options.cut_alpha,
        )?;
        let length = inputs.curve.length();
        if dimensions.piece_length.inferred && dimensions.piece_length.value > length {
            dimensions.piece_length.value = length;
        }
        Ok(dimensions)
    }

    /// The engine's parameters with this width and piece length.
    fn params_with(&self, width: f64, piece_length: f64) -> Result<Params, JobError> {
        let options = &self.options;
        let canvas = match options.canvas {
            Some([width, height]) => Canvas::Size { width, height },
            None => Canvas::Fit { margin: options.margin },
        };
        let params = Params::DEFAULT
            .with_width(width)
            .with_piece_length(piece_length)
            .with_scale(options.scale)
            .with_closed(options.closed)
            .with_method(options.method)
            .with_solver(options.solver)
            .with_check_gap(options.check_gap)
            .with_alpha_mode(options.alpha)
            .with_mismatch_penalty(options.gamma)
            .with_stitch(options.stitch)
            .with_stitch_penalty(options.stitch_penalty)
            .with_foldover_avoidance(!options.no_foldover_avoidance)
            .with_pin_first(options.pin_first)
            .with_canvas(canvas)
            .with_samples_per_axis(options.samples)
            .with_cut_alpha(options.cut_alpha)
            .with_min_coverage(options.min_coverage)
            .with_closed_max_starts(options.closed_max_starts)
            .with_variety(options.variety)
            .with_variety_radius(options.variety_radius)
            .with_round_bends(options.round_bends)
            .with_width_profile(options.width_profile.iter().map(|&[t, f]| (t, f)).collect())
            .with_piece_shape(options.pieces_shape)
            .with_fit(options.fit)
            .with_flip(options.flip)
            .with_tint(options.tint.map(|Colour(rgb)| rgb))
            .with_start_tile(tile_columns("start-tile", options.start_tile)?)
            .with_end_tile(tile_columns("end-tile", options.end_tile)?)
            .with_corner_tile(tile_columns("corner-tile", options.corner_tile)?)
            .with_corner_angle(options.corner_angle)
            .with_max_memory(self.max_memory.unwrap_or(DEFAULTS.max_memory));
        params.validate()?;
        Ok(params)
    }

    /// [`Job::run`](crate::Job::run) within an editing session: what the session's previous run computed
    /// and still holds is reused (the playground calls this while a curve is dragged; the result
    /// is byte-identical to a fresh run).
    pub fn run_in_session(
        &self,
        inputs: CurveInputs<'_>,
        session: &mut Incremental,
        progress: &mut dyn Progress,
    ) -> Result<CurveRun, JobError> {
        self.run_in(inputs, Some(session), progress)
    }

    fn run_in(
        &self,
        inputs: CurveInputs<'_>,
        session: Option<&mut Incremental>,
        progress: &mut dyn Progress,
    ) -> Result<CurveRun, JobError> {
        self.options.check_ranges()?;
        let mut dimensions = self.dimensions(&inputs)?;
        let (exemplars, sources) = self.tile_exemplars(&inputs)?;
        let input = Input { avoidance: inputs.avoidance, ..Input::new(inputs.exemplar, inputs.curve) }
            .with_more_exemplars(&exemplars);
        let measure = |params: &Params, output: &Output| {
            let exemplar = params.styled_exemplar(inputs.exemplar);
            patch_fidelity(&exemplar, &output.image, &output.ribbon_top, &output.ribbon_bottom, params.scale)
        };
        let (output, fidelity, trials) = if dimensions.width.inferred || dimensions.piece_length.inferred {
            let limits = (inputs.curve.length(), self.options.scale, search::MAX_PAIRS_TO_SEARCH);
            let (best, trials) = search::search(&mut dimensions, limits, progress, |width, piece_length, progress| {
                let params = self.params_with(width, piece_length)?.with_tile_exemplars(sources);
                let output = motif_curve::synthesize(&input, &params, progress)?;
                let fidelity = measure(&params, &output);
                Ok((output, fidelity))
            })?;
            (best.output, self.options.fidelity.then_some(best.fidelity), Some(trials))
        } else {
            let params =
                self.params_with(dimensions.width.value, dimensions.piece_length.value)?.with_tile_exemplars(sources);
            let output = match session {
                Some(session) => session.synthesize(&input, &params, progress)?,
                None => motif_curve::synthesize(&input, &params, progress)?,
            };
            let fidelity = self.options.fidelity.then(|| measure(&params, &output));
            (output, fidelity, None)
        };
        let mut figures = figures(&output.report);
        figures.extend(dimension_figures(&dimensions));
        if let Some(trials) = &trials {
            figures.insert("size_search".into(), json!(trials));
        }
        if let Some(fidelity) = fidelity {
            figures.insert("fidelity".into(), json!(fidelity));
        }
        Ok(CurveRun { output, dimensions, fidelity, size_trials: trials.unwrap_or_default(), figures })
    }

    /// The exemplars after the first with the tile images appended, and for each of the start,
    /// end and corner tiles the index of its image among all exemplars (the engine draws those
    /// tiles from them). A tile given both as columns and as an image is refused.
    fn tile_exemplars<'a>(&self, inputs: &CurveInputs<'a>) -> Result<TileExemplars<'a>, JobError> {
        let mut exemplars = std::borrow::Cow::Borrowed(inputs.more_exemplars);
        let mut sources = [None; 3];
        let columns = [self.options.start_tile, self.options.end_tile, self.options.corner_tile];
        let names = ["start-tile", "end-tile", "corner-tile"];
        for (k, (source, image)) in sources.iter_mut().zip(inputs.tile_images).enumerate() {
            if let (Some(_), Some([x0, x1])) = (image, columns[k]) {
                let allowed = "give the tile as columns X0,X1 of the exemplar or as an image, not both";
                return Err(
                    motif_core::InvalidParameter::new(names[k], format!("{x0},{x1} and an image"), allowed).into()
                );
            }
            if let Some(image) = image {
                exemplars.to_mut().push(image.clone());
                *source = Some(exemplars.len());
            }
        }
        Ok((exemplars, sources))
    }
}

impl crate::Job for CurveJob {
    const NAME: &'static str = "curve";
    const FIELDS: &'static [&'static str] = &["max-memory"];
    const SUMMARY: &'static str = "Grow a structured raster pattern (chain, lace, frieze) along a curve";
    const DETAILS: &'static str = "Undistorted pieces of the exemplar placed by a globally optimal dynamic program \
        (Zhou, Lasram, Lefebvre 2013).";
    type Options = CurveOptions;
    type Inputs<'a> = CurveInputs<'a>;
    type Run = CurveRun;

    fn run(&self, inputs: CurveInputs<'_>, progress: &mut dyn Progress) -> Result<CurveRun, JobError> {
        self.run_in(inputs, None, progress)
    }
}

impl crate::Finished for CurveRun {
    fn figures(&self) -> &Map<String, Value> {
        &self.figures
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
    if report.coarse.is_some() {
        put("coarse", json!(report.coarse));
    }
    if report.exact_optimum.is_some() {
        put("exact_optimum", json!(report.exact_optimum));
        put("cost_gap", json!(report.cost_gap));
        put("cost_gap_fraction", json!(report.cost_gap_fraction));
    }
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
        put("closed_lower_bound", json!(report.closed_lower_bound));
        put("closed_gap", json!(report.closed_gap));
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
    if let Some(thin) = &report.thin_strip {
        put("thin_strip", json!(thin));
    }
    if report.corner_tiles > 0 {
        put("corner_tiles", json!(report.corner_tiles));
    }
    if report.fit != motif_curve::Fit::None {
        put("fit", json!(report.fit));
        put("fitted_piece_length", json!(report.fitted_piece_length));
        put("fit_gap", json!(report.fit_gap));
    }
    put("warnings", json!(report.warnings));
    figures
}

#[cfg(test)]
mod tests;
