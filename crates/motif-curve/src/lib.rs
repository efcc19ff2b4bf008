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
mod bends;
mod bent;
pub mod closed;
pub mod cost;
pub mod dp;
mod exemplar;
pub mod fidelity;
mod incremental;
pub mod overlay;
mod params;
pub mod piece;
mod render;
mod repeat;
mod report;
pub mod ribbon;
pub mod samples;
mod solve;
pub mod stitch;
mod variety;

use motif_core::kurbo::Affine;
use motif_core::timing::StageTimer;
use motif_core::{InvalidParameter, Point, Polyline, Progress, RgbaImage, Vec2};
use rayon::prelude::*;

use crate::avoidance::{FROM_FOLDOVER, ForbiddenMask};
pub use crate::cost::AlphaMode;
use crate::cost::{COST_SCALE, CostModel, edge_distance, left_edges, right_edges};
pub use crate::dp::Solver;
use crate::dp::{DpCounters, RowSpec};
use crate::exemplar::Exemplar;
pub use crate::incremental::Incremental;
pub use crate::overlay::debug_overlay;
use crate::params::validate;
pub use crate::params::{Canvas, ClosedMode, CurveParams, MAX_CANVAS_SIDE, Method, PieceShape};
use crate::piece::{PieceFrame, Position, candidate_count};
use crate::render::Shape;
pub use crate::report::{CurveOutput, CurveReport, PlacedPiece};
use crate::ribbon::{PieceQuad, Ribbon};
pub use crate::solve::VarietyReport;
use crate::stitch::Stitch;

/// What the engine works on.
#[derive(Debug, Clone, Copy)]
pub struct CurveInput<'a> {
    /// The exemplar: opaque pixels are the pattern, transparent ones the background.
    pub exemplar: &'a RgbaImage,
    /// The curve, in document coordinates (pixels); open or closed.
    pub curve: &'a Polyline,
    /// More exemplars to mix with the first (§4, the paper's future work: "matches across
    /// exemplars"): pieces may come from any of them and seams across exemplars cost the same ξ.
    /// Empty for one exemplar; the repeat baseline uses the first only.
    pub more_exemplars: &'a [RgbaImage],
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
            let ribbon = Ribbon::new(curve, params.width)?.with_profile(&params.width_profile);
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

/// The shape drawing a rigid piece at exemplar position `u` (§1.3), deformed by its stitch.
fn rigid_shape<'a>(
    frame: &'a PieceFrame,
    u: Position,
    remap: Option<Vec<usize>>,
    exemplar: &'a Exemplar,
    canvas: (usize, usize),
) -> Shape<'a> {
    Shape {
        bounds: avoidance::canvas_box(frame, canvas.0, canvas.1),
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
}

/// Several exemplars side by side in one image, two transparent columns apart (pieces stay inside
/// one source's pattern extent, see `Exemplar::with_sources`), top-aligned.
struct Atlas {
    image: RgbaImage,
    /// Column range `[x0, x1)` of each source.
    sources: Vec<(usize, usize)>,
}

/// Transparent columns between two exemplars of an atlas.
const ATLAS_GAP: usize = 2;

impl Atlas {
    fn new(first: &RgbaImage, more: &[RgbaImage]) -> Self {
        if more.is_empty() {
            return Self { image: first.clone(), sources: vec![(0, first.width())] };
        }
        let all: Vec<&RgbaImage> = std::iter::once(first).chain(more).collect();
        let mut sources = Vec::with_capacity(all.len());
        let mut x = 0;
        for image in &all {
            sources.push((x, x + image.width()));
            x += image.width() + ATLAS_GAP;
        }
        let width = x - ATLAS_GAP;
        let height = all.iter().map(|image| image.height()).max().unwrap_or(0);
        let image = RgbaImage::from_fn(width, height, |x, y| {
            let source = sources.iter().position(|&(x0, x1)| (x0..x1).contains(&x));
            match source {
                Some(k) if y < all[k].height() => all[k].get(x - sources[k].0, y),
                _ => [0; 4],
            }
        });
        Self { image, sources }
    }

    /// The source of atlas position `u` and the position in that source's coordinates.
    fn local(&self, u: Position) -> (usize, Position) {
        let k = self.sources.iter().rposition(|&(x0, _)| u[0] >= x0 as i32).unwrap_or(0);
        (k, [u[0] - self.sources[k].0 as i32, u[1]])
    }
}

/// Valid fraction below which the run warns that the pieces hardly fit the pattern.
const FEW_VALID: f64 = 0.01;

/// What looks wrong with a run before it is solved, with what to change.
fn warnings(
    exemplar: &Exemplar,
    params: &CurveParams,
    samples: usize,
    valid_fraction: f64,
    empty: usize,
) -> Vec<String> {
    let mut warnings = Vec::new();
    // The top edge reads the row above the corner's and the bottom edge the row below the last,
    // so a piece holds the pattern's whole height only with two clear rows to spare.
    let needed = exemplar.pattern_rows.map_or(0, |(top, bottom)| (bottom - top + 3) as usize);
    let smallest_width = needed as f64 / params.scale;
    if samples < needed {
        warnings.push(format!(
            "the ribbon is {samples} exemplar pixels wide (width × scale) but the pattern is {} pixels tall: no piece \
             can hold its whole height, so pieces cut it where it has horizontal gaps; for whole motifs use --width {} \
             or more (at scale {})",
            needed - 2,
            smallest_width.ceil(),
            params.scale
        ));
    }
    if valid_fraction < FEW_VALID {
        warnings.push(format!(
            "only {:.2}% of exemplar positions are valid for an average piece: pieces must cut the pattern in \
             transparent pixels at their top and bottom edges; try a wider ribbon (--width {} or more), shorter \
             pieces or a lower --min-coverage",
            100.0 * valid_fraction,
            smallest_width.ceil().max(params.width.ceil() + 1.0)
        ));
    }
    if empty > 0 {
        warnings.push(format!(
            "{empty} piece(s) left empty: fold-overs at sharp bends or the avoidance map forbade every position; \
             shorter pieces (--piece-length) or a narrower ribbon follow sharp bends better"
        ));
    }
    warnings
}

/// Synthesizes the pattern of `input.exemplar` along `input.curve`.
pub fn synthesize(
    input: &CurveInput<'_>,
    params: &CurveParams,
    progress: &mut dyn Progress,
) -> Result<CurveOutput, Error> {
    synthesize_with(input, params, progress, None)
}

/// [`synthesize`], reusing and updating a session's cache when one is given (see [`Incremental`]).
pub(crate) fn synthesize_with(
    input: &CurveInput<'_>,
    params: &CurveParams,
    progress: &mut dyn Progress,
    mut cache: Option<&mut incremental::Cache>,
) -> Result<CurveOutput, Error> {
    let closed = validate(input, params)?;
    let mut timer = StageTimer::new();
    timer.start("ribbon");
    let curve = working_curve(input.curve, closed)?;
    // Rounding moves the curve by at most half the ribbon's width.
    let rounded = bends::round_bends(&curve, params.round_bends * params.width, 0.5 * params.width)?;
    let curve = rounded.curve;
    let (canvas_width, canvas_height, shift) = canvas_geometry(&curve, params, input.avoidance)?;
    let curve = curve.transformed(Affine::translate(shift))?;
    let ribbon = Ribbon::new(&curve, params.width)?.with_profile(&params.width_profile);
    let quads = ribbon::slice(&ribbon, params.piece_length);
    let samples = ((params.width * params.scale).ceil() as usize).max(1);
    // The canvas geometry of the pieces (fold-overs, rotation) is always the rigid frame's; the
    // exemplar side is the rigid or the straightened frame.
    let rigid_frames: Vec<PieceFrame> = quads.iter().map(|quad| PieceFrame::new(quad, params.scale, samples)).collect();
    let bent = params.piece_shape == PieceShape::Bent;
    let along_scales: Vec<f64> = quads.iter().map(|quad| params.scale / ribbon.factor(quad.start)).collect();
    let frames: Vec<PieceFrame> = if bent {
        quads
            .iter()
            .zip(&along_scales)
            .map(|(quad, &along)| {
                // The shorter last piece of an open curve takes a full-length window and is drawn
                // up to the curve's end: its right edge meets no seam, and every piece then has
                // the same frame, so an edit that keeps the number of pieces changes no DP row.
                let quad = if closed { *quad } else { PieceQuad { end: quad.start + params.piece_length, ..*quad } };
                bent::straight_frame(&quad, params.width * params.scale / along, along, samples)
            })
            .collect()
    } else {
        rigid_frames.clone()
    };
    let (ribbon_top, ribbon_bottom) = ribbon_borders(&ribbon);
    let margin = frames.iter().map(PieceFrame::required_margin).max().unwrap_or(8);
    let atlas = Atlas::new(input.exemplar, input.more_exemplars);
    let exemplar = Exemplar::new(&atlas.image, margin as usize, params.cut_alpha).with_sources(
        &atlas.image,
        &atlas.sources,
        params.cut_alpha,
    );
    let model = CostModel::new(params.alpha_mode, params.mismatch_penalty);
    let n_samples = params.samples_per_axis;

    timer.start("avoidance");
    progress.report("avoidance", 0.0);
    let mut forbidden = ForbiddenMask::empty(canvas_width, canvas_height);
    if let Some(map) = input.avoidance {
        forbidden.add_map(map);
    }
    if params.foldover_avoidance && params.method == Method::Synthesis {
        forbidden.add_foldovers(&rigid_frames, n_samples);
    }
    let foldover_pixels = forbidden.flags.iter().filter(|&&f| f & FROM_FOLDOVER != 0).count();
    let forbidden_pixels = forbidden.count();

    let candidates = candidate_count(atlas.image.width(), atlas.image.height(), samples);
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
        repeated_pairs: 0,
        distinct_windows: 0,
        variety: None,
        warnings: Vec::new(),
        dp_rows_reused: 0,
        rounded_bends: rounded.bends,
        bend_shift_max: rounded.max_shift,
    };
    if rounded.unresolved {
        report.warnings.push(format!(
            "a bend of the curve is tighter than {:.1} px and rounding it would move the curve more than half \
             the ribbon's width: the ribbon may fold there and leave pieces empty; use a narrower ribbon or a \
             smoother curve",
            params.round_bends * params.width
        ));
    }

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
    // Bent pieces are drawn (and tested against forbidden pixels) through the ribbon's triangles.
    let (triangles, stretch, spacing) = if bent {
        let (triangles, stretch) = repeat::triangulate(&ribbon);
        let slices = repeat::slice_count(&ribbon);
        (triangles, stretch, (ribbon.length() / slices as f64, slices))
    } else {
        (Vec::new(), Vec::new(), (1.0, 1))
    };
    let piece_forbidden: Vec<Vec<Vec2>> = (0..frames.len())
        .into_par_iter()
        .map(|i| match (forbidden_pixels, bent) {
            (0, _) => Vec::new(),
            (_, true) => bent::forbidden_samples(
                &triangles,
                spacing,
                &quads[i],
                params.width,
                [along_scales[i], params.scale],
                &forbidden,
                n_samples,
            ),
            (_, false) => avoidance::forbidden_samples(&frames[i], &forbidden, n_samples),
        })
        .collect();
    let previous_valid = cache.as_deref_mut().map(|cache| std::mem::take(&mut cache.valid)).unwrap_or_default();
    let valid: Vec<(Vec<Position>, bool, u64)> = frames
        .par_iter()
        .zip(&piece_forbidden)
        .map(|(frame, samples)| {
            let runs = avoidance::forbidden_runs(samples);
            let signature = incremental::piece_signature(frame, &runs);
            let positions = match previous_valid.get(&signature) {
                Some(positions) => positions.clone(),
                None => frame.valid_positions(&exemplar, &runs, params.min_coverage),
            };
            // A piece that a forbidden area (a fold-over, the avoidance map) leaves with no valid
            // position stays empty; the DP pays for the gap at its seams.
            if positions.is_empty() && !runs.is_empty() {
                (vec![frame.empty_position()], true, signature)
            } else {
                (positions, false, signature)
            }
        })
        .collect();
    if let Some(cache) = cache.as_deref_mut() {
        cache.valid = valid.iter().filter(|(_, empty, _)| !empty).map(|(p, _, s)| (*s, p.clone())).collect();
    }
    if let Some(piece) = valid.iter().position(|(positions, _, _)| positions.is_empty()) {
        return Err(Error::NoValidPosition { piece, samples, pattern_height: pattern_height(input.exemplar) });
    }
    let (valid, empty): (Vec<Vec<Position>>, Vec<bool>) = valid.into_iter().map(|(p, e, _)| (p, e)).unzip();
    report.empty_pieces = empty.iter().filter(|&&e| e).count();
    report.valid_fraction = valid
        .iter()
        .zip(&empty)
        .map(|(positions, &is_empty)| if is_empty { 0.0 } else { positions.len() as f64 / candidates as f64 })
        .sum::<f64>()
        / valid.len() as f64;
    report.warnings.extend(warnings(&exemplar, params, samples, report.valid_fraction, report.empty_pieces));
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
    let setup = solve::Setup {
        solver: params.solver,
        closed,
        exact_closed: params.closed == ClosedMode::Exact,
        closed_max_starts: params.closed_max_starts,
    };
    let rule = variety::Rule {
        weight: (params.variety * COST_SCALE).round() as u64,
        radius: params.variety_radius,
        reach: [((params.piece_length * params.scale / 2.0).round() as i32).max(1), (samples as i32 / 4).max(1)],
        closed,
    };
    let optimised = solve::optimise(&exemplar, &model, &rows, setup, rule, &empty, cache.as_deref_mut(), &mut on_row);
    report.dp_rows_reused = cache.map_or(0, |cache| cache.reused_rows);
    let solve::Optimised { solution, repeated_pairs, distinct_windows, variety } = optimised;
    if closed {
        report.closed_certified =
            if params.pin_first.is_some() && setup.exact_closed { Some(true) } else { solution.closed_certified };
        report.closed_starts_tried = solution.closed_starts_tried;
        report.closed_directly = solution.closed_directly;
    }
    report.repeated_pairs = repeated_pairs;
    report.distinct_windows = distinct_windows;
    report.variety = variety;
    let (path, optimum, row_ms, counters) = (solution.path, solution.cost, solution.row_ms, solution.counters);
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
    let remap_of = |i: usize| stitches.get(i).filter(|s| !s.is_identity()).map(|s| s.remap.clone());
    if bent {
        let deviations: Vec<f64> = stretch.iter().map(|s| (s - 1.0).abs()).collect();
        report.distortion_mean = deviations.iter().sum::<f64>() / deviations.len().max(1) as f64;
        report.distortion_max = deviations.iter().copied().fold(0.0, f64::max);
    }
    let bent_pieces: Vec<bent::BentPiece<'_>> = if bent {
        (0..n)
            .map(|i| bent::BentPiece {
                start: quads[i].start,
                position: (!empty[i]).then_some(positions[i]),
                frame: &frames[i],
                remap: remap_of(i),
                along_scale: along_scales[i],
            })
            .collect()
    } else {
        Vec::new()
    };
    let shapes: Vec<Shape<'_>> = if bent {
        bent::shapes(&triangles, &bent_pieces, &exemplar, params.width, params.scale, (canvas_width, canvas_height))
    } else {
        (0..n)
            .filter(|&i| !empty[i])
            .map(|i| rigid_shape(&frames[i], positions[i], remap_of(i), &exemplar, (canvas_width, canvas_height)))
            .collect()
    };
    let image = render::render(canvas_width, canvas_height, n_samples, &shapes);
    progress.report("render", 1.0);

    let pieces = (0..n)
        .map(|i| {
            let stitch = stitches.get(i);
            PlacedPiece {
                index: i,
                arc: [quads[i].start, quads[i].end],
                quad: quads[i].corners.map(|c| [c.x, c.y]),
                position: if empty[i] { None } else { Some(atlas.local(positions[i]).1) },
                exemplar: if empty[i] { 0 } else { atlas.local(positions[i]).0 },
                rotation: rigid_frames[i].angle(),
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
