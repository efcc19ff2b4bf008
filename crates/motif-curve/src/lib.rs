//! Structured patterns along curves, after Zhou, Lasram and Lefebvre, *By-example synthesis of
//! curvilinear structured patterns* (Eurographics 2013).
//!
//! A ribbon around the curve is sliced into pieces; each piece copies a window of the exemplar, and
//! a dynamic program picks the exemplar position of every piece so that the colours across all
//! piece boundaries match best (a global optimum). Modules, by section of the paper:
//!
//! - `ribbon`: the ribbon's offset curves (constant width or a width profile, §1.1) and the
//!   slicing into quadrilateral pieces (§1.3); `tight_bends` first rounds bends tighter than the ribbon
//!   (not in the paper, whose fold-over rule leaves those pieces empty).
//! - `piece`: a piece in exemplar space (rotation `M`, scale `s`, edges `L_i`, `R_i`) and the
//!   validity test of positions (§1.3, §3.1), over `U = W × (H + C)` candidates (§1.4), plus a
//!   minimum-coverage rule and the pattern's side margins (not in the paper); `ribbon_pieces` straightens
//!   pieces that follow the ribbon (the default; the paper's pieces are rigid).
//! - `cost`: the matching cost ξ (binary and continuous alpha, `γ`) and the edge distance `D`
//!   with `C = ⌈‖L‖⌉` bilinear samples (§1, §1.3); `bounds`: lower bounds of `D` from block-sum
//!   profiles and alpha masks, for the exact solver's pruning (not in the paper).
//! - `dp`: the dynamic program of Eq. 1 with backtracking (§1.4, §2): the plain reference
//!   solver, the exact fast solver (its branch and bound in `profile_tree`) and a brute-force
//!   enumerator for tests; `solve` runs it (or `closed`) and the repetition control of
//!   `variety` (not in the paper).
//! - `closed`: closed curves, the single-DP approximation and an exact, certified mode (§1.5).
//! - `avoidance`: avoidance maps and fold-over detection (§3.1).
//! - `stitch`: the edge alignment of Eq. 2–3 and its propagation inside pieces (§3.2).
//! - `render`: anti-aliased rasterization of the pieces; `repeat`: the classic arc-length
//!   texture-mapping baseline; `overlay`: the debug drawing; `fidelity`: the result read back
//!   along the curve and compared with the exemplar patch by patch; [`samples`]: generated
//!   exemplars for benchmarks.
//! - `atlas` (several exemplars, §4's "matches across exemplars") and `incremental`
//!   ([`Incremental`], §4's re-synthesis while the curve is edited).
//!
//! The entry point is [`synthesize`]. The crate does no I/O and builds for `wasm32`.
//!
//! ```
//! use motif_core::{NoProgress, Point, Polyline, RgbaImage};
//! use motif_curve::{Input, Params, synthesize};
//!
//! // A strip of rings with a transparent background, along a gentle arc.
//! let exemplar = RgbaImage::from_fn(96, 24, |x, y| {
//!     let (dx, dy) = ((x % 16) as f64 - 7.5, y as f64 - 11.5);
//!     let r = (dx * dx + dy * dy).sqrt();
//!     if (4.0..7.0).contains(&r) { [210, 170, 40, 255] } else { [0; 4] }
//! });
//! let arc: Vec<Point> = (0..=40).map(|i| {
//!     let a = f64::from(i) / 40.0;
//!     Point::new(20.0 + 200.0 * a, 80.0 - 60.0 * motif_core::math::sin(a * std::f64::consts::PI))
//! }).collect();
//! let curve = Polyline::new(arc, false).unwrap();
//! let params = Params::default().with_width(24.0).with_piece_length(12.0);
//! params.validate().unwrap();
//! let input = Input { exemplar: &exemplar, curve: &curve, avoidance: None, more_exemplars: &[] };
//! let output = synthesize(&input, &params, &mut NoProgress).unwrap();
//! assert!(output.report.pieces > 10);
//! // Bent pieces continue the rings across every seam.
//! assert_eq!(output.report.total_cost, 0.0);
//! assert!(output.report.warnings.is_empty());
//! ```

mod atlas;
mod avoidance;
mod bounds;
mod canvas;
mod closed;
mod cost;
mod dp;
mod exemplar;
mod fidelity;
mod incremental;
mod infer;
mod overlay;
mod params;
mod piece;
mod profile_tree;
mod render;
mod repeat;
mod report;
mod ribbon;
mod ribbon_pieces;
pub mod samples;
mod solve;
mod stitch;
mod tight_bends;
mod variety;
mod warnings;

use motif_core::kurbo::Affine;
use motif_core::timing::StageTimer;
use motif_core::{InvalidParameter, Polyline, Progress, RgbaImage, Vec2};
use rayon::prelude::*;

use crate::atlas::Atlas;
use crate::avoidance::{FROM_FOLDOVER, ForbiddenMask};
use crate::canvas::{canvas_geometry, ribbon_borders, working_curve};
pub use crate::cost::AlphaMode;
use crate::cost::{COST_SCALE, CostModel, edge_distance, left_edges, right_edges};
pub use crate::dp::Solver;
use crate::dp::{DpCounters, RowSpec};
use crate::exemplar::Exemplar;
pub use crate::fidelity::{PatchFidelity, patch_fidelity};
pub use crate::incremental::Incremental;
pub use crate::infer::{Dimension, Dimensions, pattern_period};
pub use crate::overlay::debug_overlay;
use crate::params::validate;
pub use crate::params::{Canvas, ClosedMode, MAX_CANVAS_SIDE, Method, Params, PieceShape};
use crate::piece::{PieceFrame, Position, candidate_count};
use crate::render::Shape;
use crate::render::rigid_shape;
pub use crate::report::{Output, PlacedPiece, Report};
use crate::ribbon::{PieceQuad, Ribbon};
pub use crate::solve::VarietyReport;
use crate::stitch::Stitch;

/// What the engine works on.
#[derive(Debug, Clone, Copy)]
pub struct Input<'a> {
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
#[non_exhaustive]
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
    /// The run's estimated memory passes [`Params::max_memory`].
    #[error(transparent)]
    TooMuchMemory(#[from] motif_core::TooMuchMemory),
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

const MEMORY_ADVICE: &str = "use a smaller canvas, longer pieces or a narrower ribbon";

/// The peak memory of a synthesis: the canvas with its forbidden mask and render tiles (about 10
/// bytes a pixel), the valid positions of every piece, the dynamic program's costs and back
/// pointers per position, and the edge samples of two rows.
fn memory_estimate(canvas_pixels: f64, pieces: f64, mean_valid: f64, samples: usize) -> motif_core::MemoryEstimate {
    let mut estimate = motif_core::MemoryEstimate::new();
    estimate
        .add("canvas", canvas_pixels, 10.0)
        .add("valid positions", pieces * mean_valid, std::mem::size_of::<piece::Position>() as f64)
        .add("dynamic program", pieces * mean_valid, 12.0)
        .add("edge samples", 2.0 * mean_valid * samples as f64, 16.0);
    estimate
}

/// A piece's valid positions, whether it was left empty by a forbidden area, and its signature
/// (the key of the incremental cache).
type PieceValid = (Vec<Position>, bool, u64);

/// Number of rows of the exemplar holding non-transparent pixels (for error messages).
fn pattern_height(image: &RgbaImage) -> usize {
    image.opaque_bounds().map_or(0, |(_, y0, _, y1)| y1 - y0)
}

/// Synthesizes the pattern of `input.exemplar` along `input.curve`.
pub fn synthesize(input: &Input<'_>, params: &Params, progress: &mut dyn Progress) -> Result<Output, Error> {
    synthesize_with(input, params, progress, None)
}

/// [`synthesize`], reusing and updating a session's cache when one is given (see [`Incremental`]).
pub(crate) fn synthesize_with(
    input: &Input<'_>,
    params: &Params,
    progress: &mut dyn Progress,
    mut cache: Option<&mut incremental::Cache>,
) -> Result<Output, Error> {
    let closed = validate(input, params)?;
    let mut timer = StageTimer::new();
    timer.start("ribbon");
    let curve = working_curve(input.curve, closed)?;
    // Rounding moves the curve by at most half the ribbon's width.
    let rounded = tight_bends::round_bends(&curve, params.round_bends * params.width, 0.5 * params.width)?;
    let curve = rounded.curve;
    let (canvas_width, canvas_height, shift) = canvas_geometry(&curve, params, input.avoidance)?;
    let canvas_pixels = (canvas_width * canvas_height) as f64;
    let canvas_memory = memory_estimate(canvas_pixels, 0.0, 0.0, 0).check(params.max_memory, MEMORY_ADVICE)?;
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
                ribbon_pieces::straight_frame(&quad, params.width * params.scale / along, along, samples)
            })
            .collect()
    } else {
        rigid_frames.clone()
    };
    let (ribbon_top, ribbon_bottom) = ribbon_borders(&ribbon);
    let margin = frames.iter().map(PieceFrame::required_margin).max().unwrap_or(8);
    let atlas = Atlas::new(input.exemplar, input.more_exemplars);
    // The padded exemplar (megabytes for wide ribbons) is the same for every edit of a session.
    let cached = cache.as_deref().and_then(|cache| cache.exemplar.clone()).filter(|e| e.pad == margin);
    let prepared: std::sync::Arc<Exemplar> = cached.unwrap_or_else(|| {
        std::sync::Arc::new(Exemplar::new(&atlas.image, margin as usize, params.cut_alpha).with_sources(
            &atlas.image,
            &atlas.sources,
            params.cut_alpha,
        ))
    });
    if let Some(cache) = cache.as_deref_mut() {
        cache.exemplar = Some(prepared.clone());
    }
    let exemplar: &Exemplar = &prepared;
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
    let mut report = Report {
        method: params.method,
        estimated_memory_bytes: canvas_memory,
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
        let shapes = repeat::shapes(&triangles, exemplar, params.width, params.scale, (canvas_width, canvas_height));
        let image = render::render(canvas_width, canvas_height, n_samples, &shapes);
        let deviations: Vec<f64> = stretch.iter().map(|s| (s - 1.0).abs()).collect();
        report.distortion_mean = deviations.iter().sum::<f64>() / deviations.len().max(1) as f64;
        report.distortion_max = deviations.iter().copied().fold(0.0, f64::max);
        report.wrap_seams = (params.scale * ribbon.length() / f64::from(exemplar.width)).floor() as usize;
        report.stages_ms = timer.finish();
        progress.report("render", 1.0);
        return Ok(Output { image, pieces: Vec::new(), report, forbidden, ribbon_top, ribbon_bottom });
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
            (_, true) => ribbon_pieces::forbidden_samples(
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
    let valid_of = |i: usize| -> PieceValid {
        let frame = &frames[i];
        let runs = avoidance::forbidden_runs(&piece_forbidden[i]);
        let signature = incremental::piece_signature(frame, &runs);
        let positions = match previous_valid.get(&signature) {
            Some(positions) => positions.clone(),
            None => frame.valid_positions(exemplar, &runs, params.min_coverage),
        };
        // A piece that a forbidden area (a fold-over, the avoidance map) leaves with no valid
        // position stays empty; the DP pays for the gap at its seams.
        if positions.is_empty() && !runs.is_empty() {
            (vec![frame.empty_position()], true, signature)
        } else {
            (positions, false, signature)
        }
    };
    // The DP's memory follows the valid positions per piece: a few pieces go first, and their
    // counts decide whether the rest may be computed (their lists are kept, not redone).
    let probe_count = frames.len().min(8);
    let mut slots: Vec<Option<PieceValid>> = vec![None; frames.len()];
    let probed: Vec<(usize, PieceValid)> =
        (0..probe_count).into_par_iter().map(|k| k * frames.len() / probe_count).map(|i| (i, valid_of(i))).collect();
    let mean_valid = probed.iter().map(|(_, (p, _, _))| p.len()).sum::<usize>() as f64 / probe_count.max(1) as f64;
    report.estimated_memory_bytes = memory_estimate(canvas_pixels, frames.len() as f64, mean_valid, samples)
        .check(params.max_memory, MEMORY_ADVICE)?;
    for (i, lists) in probed {
        slots[i] = Some(lists);
    }
    let valid: Vec<PieceValid> =
        slots.into_par_iter().enumerate().map(|(i, slot)| slot.unwrap_or_else(|| valid_of(i))).collect();
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
    report.warnings.extend(warnings::warnings(exemplar, params, samples, report.valid_fraction, report.empty_pieces));
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
    let rule = variety::Rule {
        weight: (params.variety * COST_SCALE).round() as u64,
        radius: params.variety_radius,
        reach: [((params.piece_length * params.scale / 2.0).round() as i32).max(1), (samples as i32 / 4).max(1)],
        closed,
    };
    let setup = solve::Setup {
        solver: params.solver,
        closed,
        exact_closed: params.closed == ClosedMode::Exact,
        closed_max_starts: params.closed_max_starts,
        rule,
    };
    let optimised = solve::optimise(exemplar, &model, &rows, setup, &empty, cache.as_deref_mut(), &mut on_row);
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
    report.dp_row_ms_median = motif_core::timing::median(&row_ms);
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
            let rights = right_edges(exemplar, &model, &frames[i], &[positions[i]]);
            let lefts = left_edges(exemplar, &model, &[positions[next]], samples);
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
    let bent_pieces: Vec<ribbon_pieces::BentPiece<'_>> = if bent {
        (0..n)
            .map(|i| ribbon_pieces::BentPiece {
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
        ribbon_pieces::shapes(
            &triangles,
            &bent_pieces,
            exemplar,
            params.width,
            params.scale,
            (canvas_width, canvas_height),
        )
    } else {
        (0..n)
            .filter(|&i| !empty[i])
            .map(|i| rigid_shape(&frames[i], positions[i], remap_of(i), exemplar, (canvas_width, canvas_height)))
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
    Ok(Output { image, pieces, report, forbidden, ribbon_top, ribbon_bottom })
}

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_features;
