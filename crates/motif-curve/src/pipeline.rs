//! A synthesis, stage by stage as the report times them: ribbon (`layout`), avoidance, valid
//! positions, dynamic program, stitching, render; or, for the repeat baseline, ribbon, avoidance
//! and render.

use motif_core::timing::StageTimer;
use motif_core::{InvalidParameter, Progress, RgbaImage, Vec2};
use rayon::prelude::*;

use crate::InputError;
use crate::avoidance::{FROM_FOLDOVER, ForbiddenMask};
use crate::brush::TileKind;
use crate::cost::{COST_SCALE, edge_distance, left_edges, right_edges};
use crate::dp::{DpCounters, RowSpec};
use crate::exemplar::Exemplar;
use crate::exemplar::Run;
use crate::layout::{Layout, MEMORY_ADVICE, memory_estimate};
use crate::params::validate;
use crate::piece::{PieceFrame, Position, candidate_count};
use crate::render::{Shape, rigid_shape};
use crate::repeat::Triangle;
use crate::stitch::Stitch;
use crate::{ClosedMode, Error, Fit, Input, Method, Output, Params, PlacedPiece, Report};
use crate::{avoidance, incremental, render, repeat, ribbon_pieces, solve, stitch, thin, variety, warnings};

/// [`synthesize`](crate::synthesize), reusing and updating a session's cache when one is given
/// (see [`Incremental`](crate::Incremental)).
pub(crate) fn synthesize_with(
    input: &Input<'_>,
    params: &Params,
    progress: &mut dyn Progress,
    mut cache: Option<&mut incremental::Cache>,
) -> Result<Output, Error> {
    let closed = validate(input, params)?;
    let mut timer = StageTimer::new();
    timer.start("ribbon");
    // The exemplars as the brush draws them (flipped, tinted); every later stage reads these.
    let exemplar = params.styled_exemplar(input.exemplar);
    let more_exemplars: Vec<RgbaImage> = if params.styles_exemplars() {
        input.more_exemplars.iter().map(|image| params.styled_exemplar(image).into_owned()).collect()
    } else {
        Vec::new()
    };
    let more_exemplars = if params.styles_exemplars() { &more_exemplars } else { input.more_exemplars };
    let styled = Input { exemplar: &exemplar, more_exemplars, ..*input };
    let input = &styled;
    let layout = Layout::new(input, params, closed, cache.as_deref_mut())?;

    timer.start("avoidance");
    progress.report("avoidance", 0.0);
    let forbidden = forbidden_mask(input, params, &layout);
    let mut report = first_report(params, &layout, &forbidden);

    if params.method == Method::Repeat {
        timer.start("render");
        progress.report("render", 0.0);
        let image = render_repeat(params, &layout, &mut report);
        report.stages_ms = timer.finish();
        progress.report("render", 1.0);
        return Ok(layout.into_output(image, Vec::new(), report, forbidden));
    }

    timer.start("valid positions");
    progress.report("valid positions", 0.0);
    let candidates = Candidates::new(input, params, &layout, &forbidden, &mut report, cache.as_deref_mut())?;
    check_pin(params, &candidates)?;

    timer.start("dynamic program");
    let solved = dynamic_program(params, &layout, &candidates, &mut report, cache, progress);
    let (candidates, positions, optimum) = avoid_thin_strip(params, &layout, candidates, solved, &mut report, progress);

    timer.start("stitching");
    let stitches = stitch_seams(params, &layout, &candidates, &positions, optimum, &mut report);

    timer.start("render");
    progress.report("render", 0.0);
    let image = render_pieces(params, &layout, &candidates, &positions, &stitches, &mut report);
    progress.report("render", 1.0);

    let pieces = placed_pieces(params, &layout, &candidates, &positions, &stitches);
    report.stages_ms = timer.finish();
    Ok(layout.into_output(image, pieces, report, forbidden))
}

/// The forbidden pixels of the canvas (§3.1): the avoidance map's, and the fold-overs of the
/// ribbon when the synthesis avoids them.
fn forbidden_mask(input: &Input<'_>, params: &Params, layout: &Layout) -> ForbiddenMask {
    let mut forbidden = ForbiddenMask::empty(layout.canvas.0, layout.canvas.1);
    if let Some(map) = input.avoidance {
        forbidden.add_map(map);
    }
    if params.foldover_avoidance && params.method == Method::Synthesis {
        forbidden.add_foldovers(&layout.rigid_frames, params.samples_per_axis);
    }
    forbidden
}

/// The report as the layout and the forbidden mask leave it (the later stages fill the rest),
/// with the warning of a bend that rounding could not resolve.
fn first_report(params: &Params, layout: &Layout, forbidden: &ForbiddenMask) -> Report {
    let mut report = Report {
        method: params.method,
        estimated_memory_bytes: layout.canvas_memory,
        solver: params.solver,
        coarse: None,
        exact_optimum: None,
        cost_gap: None,
        cost_gap_fraction: None,
        pieces: 0,
        samples_per_edge: layout.samples,
        canvas: [layout.canvas.0, layout.canvas.1],
        canvas_origin: [-layout.shift.x, -layout.shift.y],
        total_cost: 0.0,
        total_cost_unstitched: 0.0,
        mean_seam_cost: 0.0,
        dp_optimum: 0.0,
        valid_fraction: 0.0,
        dp_row_ms: Vec::new(),
        dp_row_ms_median: 0.0,
        dp_row_ms_max: 0.0,
        stages_ms: Vec::new(),
        closed: layout.closed,
        closed_certified: None,
        closed_lower_bound: None,
        closed_gap: None,
        closed_starts_tried: 0,
        closed_directly: false,
        empty_pieces: 0,
        forbidden_pixels: forbidden.count(),
        foldover_pixels: forbidden.flags.iter().filter(|&&f| f & FROM_FOLDOVER != 0).count(),
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
        rounded_bends: layout.rounded_bends,
        bend_shift_max: layout.bend_shift_max,
        fit: params.fit,
        fitted_piece_length: layout.fitted_piece_length,
        fit_gap: layout.fit_gap,
        thin_strip: None,
        corner_tiles: layout.piece_tiles.iter().filter(|&&tile| tile == Some(TileKind::Corner)).count(),
    };
    if layout.unresolved_bend {
        report.warnings.push(format!(
            "a bend of the curve is tighter than {:.1} px and rounding it would move the curve more than half \
             the ribbon's width: the ribbon may fold there and leave pieces empty; use a narrower ribbon or a \
             smoother curve",
            params.round_bends * params.width
        ));
    }
    report
}

/// Mean and largest deviation of the ribbon's triangles' stretch from 1, into the report.
fn record_distortion(report: &mut Report, stretch: &[f64]) {
    let deviations: Vec<f64> = stretch.iter().map(|s| (s - 1.0).abs()).collect();
    report.distortion_mean = deviations.iter().sum::<f64>() / deviations.len().max(1) as f64;
    report.distortion_max = deviations.iter().copied().fold(0.0, f64::max);
}

/// The repeat baseline: the exemplar repeated along the arc length and bent with the ribbon.
fn render_repeat(params: &Params, layout: &Layout, report: &mut Report) -> RgbaImage {
    let exemplar = &*layout.exemplar;
    let (triangles, stretch) = repeat::triangulate(&layout.ribbon);
    let shapes = repeat::shapes(&triangles, exemplar, params.width, params.scale, layout.canvas);
    let image = render::render(layout.canvas.0, layout.canvas.1, params.samples_per_axis, &shapes);
    record_distortion(report, &stretch);
    report.wrap_seams = (params.scale * layout.ribbon.length() / f64::from(exemplar.width)).floor() as usize;
    image
}

/// A piece's valid positions, whether it was left empty by a forbidden area, and its signature
/// (the key of the incremental cache).
type PieceValid = (Vec<Position>, bool, u64);

/// Number of rows of the exemplar holding non-transparent pixels (for error messages).
fn pattern_height(image: &RgbaImage) -> usize {
    image.opaque_bounds().map_or(0, |(_, y0, _, y1)| y1 - y0)
}

/// What the valid-positions stage finds: every piece's valid positions (§1.3, §3.1) and the
/// forbidden samples they avoid, and for bent pieces the ribbon's triangles they are drawn through.
struct Candidates {
    /// Valid positions per piece (one empty position for a piece left empty).
    valid: Vec<Vec<Position>>,
    /// Pieces left empty: a forbidden area leaves them no valid position.
    empty: Vec<bool>,
    /// Forbidden sample points per piece, in piece-local coordinates.
    forbidden_samples: Vec<Vec<Vec2>>,
    /// Bent pieces: the ribbon's triangles and their stretch (empty for rigid pieces).
    triangles: Vec<Triangle>,
    stretch: Vec<f64>,
}

impl Candidates {
    /// Lists the valid positions of every piece, after checking the memory they and the dynamic
    /// program will take, and records the validity figures and warnings.
    fn new(
        input: &Input<'_>,
        params: &Params,
        layout: &Layout,
        forbidden: &ForbiddenMask,
        report: &mut Report,
        mut cache: Option<&mut incremental::Cache>,
    ) -> Result<Self, Error> {
        // Bent pieces are drawn (and tested against forbidden pixels) through the ribbon's triangles.
        let (triangles, stretch, spacing) = if layout.bent {
            let (triangles, stretch) = repeat::triangulate(&layout.ribbon);
            let slices = repeat::slice_count(&layout.ribbon);
            (triangles, stretch, (layout.ribbon.length() / slices as f64, slices))
        } else {
            (Vec::new(), Vec::new(), (1.0, 1))
        };
        let forbidden_samples = piece_forbidden_samples(params, layout, forbidden, &triangles, spacing);
        let previous = cache.as_deref_mut().map(|cache| std::mem::take(&mut cache.valid)).unwrap_or_default();
        let valid = valid_positions(params, layout, &forbidden_samples, &previous, report)?;
        if let Some(cache) = cache {
            cache.valid = valid.iter().filter(|(_, empty, _)| !empty).map(|(p, _, s)| (*s, p.clone())).collect();
        }
        if let Some(piece) = valid.iter().position(|(positions, _, _)| positions.is_empty()) {
            if let Some((kind, [x0, x1])) = layout.tile(piece) {
                return Err(InvalidParameter::new(
                    kind.option_name(),
                    format!("{x0},{x1}"),
                    "no vertical position of these columns is cut cleanly (the tile must lie inside the pattern's \
                     extent, with its top and bottom edges in transparent pixels): widen the ribbon (--width) or \
                     choose other columns",
                )
                .into());
            }
            let samples = layout.samples;
            return Err(Error::Input(InputError::NoValidPosition {
                piece,
                samples,
                pattern_height: pattern_height(input.exemplar),
            }));
        }
        let (valid, empty): (Vec<Vec<Position>>, Vec<bool>) = valid.into_iter().map(|(p, e, _)| (p, e)).unzip();
        let candidates = Self { valid, empty, forbidden_samples, triangles, stretch };
        candidates.record(params, layout, report);
        Ok(candidates)
    }

    /// The share of valid positions, the empty pieces and the warnings they call for.
    fn record(&self, params: &Params, layout: &Layout, report: &mut Report) {
        let (valid, empty) = (&self.valid, &self.empty);
        let candidates = candidate_count(layout.atlas.image.width(), layout.atlas.image.height(), layout.samples);
        report.empty_pieces = empty.iter().filter(|&&e| e).count();
        report.valid_fraction = valid
            .iter()
            .zip(empty)
            .map(|(positions, &is_empty)| if is_empty { 0.0 } else { positions.len() as f64 / candidates as f64 })
            .sum::<f64>()
            / valid.len() as f64;
        report.warnings.extend(warnings::warnings(
            &layout.exemplar,
            params,
            layout.samples,
            report.valid_fraction,
            report.empty_pieces,
        ));
    }
}

/// The forbidden sample points each piece covers (none when no pixel is forbidden).
fn piece_forbidden_samples(
    params: &Params,
    layout: &Layout,
    forbidden: &ForbiddenMask,
    triangles: &[Triangle],
    spacing: (f64, usize),
) -> Vec<Vec<Vec2>> {
    let forbidden_pixels = forbidden.count();
    let n_samples = params.samples_per_axis;
    (0..layout.frames.len())
        .into_par_iter()
        .map(|i| match (forbidden_pixels, layout.bent) {
            (0, _) => Vec::new(),
            (_, true) => ribbon_pieces::forbidden_samples(
                triangles,
                spacing,
                &layout.quads[i],
                params.width,
                [layout.along_scales[i], params.scale],
                forbidden,
                n_samples,
            ),
            (_, false) => avoidance::forbidden_samples(&layout.frames[i], forbidden, n_samples),
        })
        .collect()
}

/// Every piece's valid positions, taken from `previous` (a session's last run, by piece
/// signature) where it has them. The DP's memory follows the valid positions per piece: a few
/// pieces go first, and their counts decide whether the rest may be computed (their lists are
/// kept, not redone). Pieces with the same signature (every bent piece of an open curve but the
/// last, without forbidden areas) have the same list, computed once: on a 600 × 250 exemplar a
/// list took 50 ms, 5 s for a curve of 100 pieces.
fn valid_positions(
    params: &Params,
    layout: &Layout,
    forbidden_samples: &[Vec<Vec2>],
    previous: &std::collections::HashMap<u64, Vec<Position>>,
    report: &mut Report,
) -> Result<Vec<PieceValid>, Error> {
    let frames = &layout.frames;
    let keys: Vec<(u64, Vec<Run>)> = (0..frames.len())
        .into_par_iter()
        .map(|i| {
            let runs = avoidance::forbidden_runs(&forbidden_samples[i]);
            // A tile keeps other positions than a piece of the same frame.
            let tile = match layout.tile(i) {
                Some((TileKind::Start, _)) => 1,
                Some((TileKind::End, _)) => 2,
                Some((TileKind::Corner, _)) => 3,
                None => 0,
            };
            (incremental::piece_signature(&frames[i], &runs).wrapping_add(tile * 0x9e37_79b9_7f4a_7c15), runs)
        })
        .collect();
    let valid_of = |i: usize| -> PieceValid {
        let (signature, runs) = (keys[i].0, &keys[i].1);
        let positions = match previous.get(&signature) {
            Some(positions) => positions.clone(),
            None => frames[i].valid_positions(&layout.exemplar, runs, params.min_coverage),
        };
        let positions =
            if params.fit == Fit::Space { whole_motifs(&frames[i], &layout.exemplar, positions) } else { positions };
        let positions = match layout.tile(i) {
            Some((_, [x0, _])) => positions.into_iter().filter(|u| i64::from(u[0]) == i64::from(x0)).collect(),
            None => outside_tiles(&frames[i], layout, positions),
        };
        // A piece that a forbidden area (a fold-over, the avoidance map) leaves with no valid
        // position stays empty; the DP pays for the gap at its seams.
        if positions.is_empty() && !runs.is_empty() {
            (vec![frames[i].empty_position()], true, signature)
        } else {
            (positions, false, signature)
        }
    };
    let probe_count = frames.len().min(8);
    let probed: Vec<(usize, PieceValid)> =
        (0..probe_count).into_par_iter().map(|k| k * frames.len() / probe_count).map(|i| (i, valid_of(i))).collect();
    let mean_valid = probed.iter().map(|(_, (p, _, _))| p.len()).sum::<usize>() as f64 / probe_count.max(1) as f64;
    report.estimated_memory_bytes =
        memory_estimate(layout.canvas_pixels(), frames.len() as f64, mean_valid, layout.samples)
            .check(params.max_memory, MEMORY_ADVICE)?;
    let mut lists: std::collections::HashMap<u64, PieceValid> =
        probed.into_iter().map(|(_, lists)| (lists.2, lists)).collect();
    let mut missing: Vec<usize> = Vec::new();
    let mut wanted = std::collections::HashSet::new();
    for (i, (signature, _)) in keys.iter().enumerate() {
        if !lists.contains_key(signature) && wanted.insert(*signature) {
            missing.push(i);
        }
    }
    let computed: Vec<PieceValid> = missing.into_par_iter().map(valid_of).collect();
    lists.extend(computed.into_iter().map(|lists| (lists.2, lists)));
    Ok(keys.iter().map(|(signature, _)| lists[signature].clone()).collect())
}

/// The positions whose sides cut the fewest pattern pixels (spaced pieces, whose motifs no
/// neighbour continues across a gap): those with clear sides, which hold whole motifs, or, for a
/// pattern with no clear column (interlocked links, a rope), those that cut it least.
fn whole_motifs(frame: &PieceFrame, exemplar: &Exemplar, positions: Vec<Position>) -> Vec<Position> {
    let sides = frame.side_runs();
    let cut = |u: &Position| sides.iter().map(|run| exemplar.run_occupied(run, u[0], u[1])).sum::<u32>();
    let cuts: Vec<u32> = positions.iter().map(cut).collect();
    let least = cuts.iter().copied().min().unwrap_or(0);
    positions.into_iter().zip(cuts).filter(|&(_, c)| c == least).map(|(u, _)| u).collect()
}

/// The positions of a piece between the tiles whose window stays clear of the tiles' columns: a
/// cap, clasp or corner piece is drawn where its tile goes only.
fn outside_tiles(frame: &PieceFrame, layout: &Layout, positions: Vec<Position>) -> Vec<Position> {
    let tiles: Vec<[u32; 2]> = layout.tile_columns.into_iter().flatten().collect();
    if tiles.is_empty() {
        return positions;
    }
    let corners = frame.local_corners();
    let low = corners.iter().map(|c| c.x).fold(f64::INFINITY, f64::min);
    let high = corners.iter().map(|c| c.x).fold(f64::NEG_INFINITY, f64::max);
    positions
        .into_iter()
        .filter(|u| {
            let (left, right) = (f64::from(u[0]) + 0.5 + low, f64::from(u[0]) + 0.5 + high);
            tiles.iter().all(|&[x0, x1]| right <= f64::from(x0) || left >= f64::from(x1))
        })
        .collect()
}

/// Degenerate optima (module `thin`): when the optimum's pieces hold on average less than half of
/// their motif (a thin strip repeated at no seam cost), the windows that thin are taken out and
/// the dynamic program runs again; otherwise the optimum stands as it is.
fn avoid_thin_strip(
    params: &Params,
    layout: &Layout,
    mut candidates: Candidates,
    (positions, optimum): (Vec<Position>, u64),
    report: &mut Report,
    progress: &mut dyn Progress,
) -> (Candidates, Vec<Position>, u64) {
    let (frames, exemplar) = (&layout.frames, &*layout.exemplar);
    let free: Vec<bool> = (0..frames.len())
        .map(|i| !candidates.empty[i] && layout.tile(i).is_none() && !(i == 0 && params.pin_first.is_some()))
        .collect();
    let motifs = thin::motif_coverages(frames, exemplar, &candidates.valid, &free);
    let before = thin::mean_share(frames, exemplar, &motifs, &positions);
    if before >= thin::THIN_SHARE {
        return (candidates, positions, optimum);
    }
    let (valid, dropped) = thin::without_thin(frames, exemplar, &candidates.valid, &motifs);
    if dropped == 0 {
        return (candidates, positions, optimum);
    }
    candidates.valid = valid;
    let (positions, optimum) = dynamic_program(params, layout, &candidates, report, None, progress);
    let after = thin::mean_share(frames, exemplar, &motifs, &positions);
    report.warnings.push(format!(
        "the optimum repeated a thin strip of the exemplar (its pieces held {:.0}% of their motif on average): \
         {dropped} windows holding less than half of it were taken out, and the pieces now hold {:.0}%",
        100.0 * before,
        100.0 * after
    ));
    report.thin_strip = Some(thin::ThinStrip { share_before: before, share_after: after, positions_dropped: dropped });
    (candidates, positions, optimum)
}

/// Refuses a pinned first position that is not one of the first piece's valid positions.
fn check_pin(params: &Params, candidates: &Candidates) -> Result<(), Error> {
    let (valid, empty) = (&candidates.valid[0], candidates.empty[0]);
    match params.pin_first {
        Some(pin) if !valid.contains(&pin) || empty => Err(Error::Input(InputError::InvalidPin {
            x: pin[0],
            y: pin[1],
            count: if empty { 0 } else { valid.len() },
        })),
        _ => Ok(()),
    }
}

/// The dynamic program of Eq. 1 (§1.4, §2) over the pieces' valid positions, with the repetition
/// control of `variety`: the chosen position of every piece and the optimum Ω (cost units), its
/// figures into the report.
fn dynamic_program(
    params: &Params,
    layout: &Layout,
    candidates: &Candidates,
    report: &mut Report,
    mut cache: Option<&mut incremental::Cache>,
    progress: &mut dyn Progress,
) -> (Vec<Position>, u64) {
    let (frames, closed, samples) = (&layout.frames, layout.closed, layout.samples);
    let pinned = params.pin_first.map(|pin| [pin]);
    let first_positions: &[Position] = pinned.as_ref().map_or(candidates.valid[0].as_slice(), |pin| pin.as_slice());
    let mut rows: Vec<RowSpec<'_>> =
        frames.iter().zip(&candidates.valid).map(|(frame, positions)| RowSpec { frame, positions }).collect();
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
        check_gap: params.check_gap,
    };
    let (exemplar, model, empty) = (&layout.exemplar, &layout.model, &candidates.empty);
    let optimised = solve::optimise(exemplar, model, &rows, setup, empty, cache.as_deref_mut(), &mut on_row);
    report.dp_rows_reused = cache.map_or(0, |cache| cache.reused_rows);
    let solve::Optimised { solution, dp_cost, exact_optimum, repeated_pairs, distinct_windows, variety } = optimised;
    record_gap(report, dp_cost, exact_optimum);
    report.coarse = solution.coarse.clone();
    if closed {
        report.closed_certified =
            if params.pin_first.is_some() && setup.exact_closed { Some(true) } else { solution.closed_certified };
        record_closed_bound(report, dp_cost, solution.closed_lower_bound, report.closed_certified);
        report.closed_starts_tried = solution.closed_starts_tried;
        report.closed_directly = solution.closed_directly;
    }
    report.repeated_pairs = repeated_pairs;
    report.distinct_windows = distinct_windows;
    report.variety = variety;
    let (path, optimum, row_ms, counters) = (solution.path, solution.cost, solution.row_ms, solution.counters);
    report.dp_optimum = optimum as f64 / COST_SCALE;
    report.dp_row_ms_median = motif_core::timing::median(&row_ms);
    report.dp_row_ms_max = row_ms.iter().copied().fold(0.0, f64::max);
    report.dp_row_ms = row_ms;
    report.dp_counters = counters;
    report.columns_skipped_fraction = counters.skipped_fraction();
    ((0..frames.len()).map(|i| rows[i].positions[path[i]]).collect(), optimum)
}

/// The exact optimum beside the coarse-to-fine solver's `Ω`, and the gap between them, into the
/// report (when the exact solver ran too).
/// Exact closed mode: the bound no cycle goes below, and the gap to it as a fraction of the
/// cycle's cost (0 when certified, also when a pinned first position leaves one start).
fn record_closed_bound(report: &mut Report, cycle_cost: u64, bound: Option<u64>, certified: Option<bool>) {
    let Some(bound) = bound else { return };
    let bound = if certified == Some(true) { cycle_cost } else { bound.min(cycle_cost) };
    report.closed_lower_bound = Some(bound as f64 / COST_SCALE);
    let gap = cycle_cost - bound;
    report.closed_gap = Some(if cycle_cost == 0 { 0.0 } else { gap as f64 / cycle_cost as f64 });
}

fn record_gap(report: &mut Report, dp_cost: u64, exact_optimum: Option<u64>) {
    if let Some(exact) = exact_optimum {
        report.exact_optimum = Some(exact as f64 / COST_SCALE);
        let gap = dp_cost.saturating_sub(exact);
        report.cost_gap = Some(gap as f64 / COST_SCALE);
        report.cost_gap_fraction = Some(if dp_cost == 0 { 0.0 } else { gap as f64 / dp_cost as f64 });
    }
}

/// The edge alignment of every seam (Eq. 2–3, §3.2; identity without stitching), and the seam
/// costs before and after it into the report.
fn stitch_seams(
    params: &Params,
    layout: &Layout,
    candidates: &Candidates,
    positions: &[Position],
    optimum: u64,
    report: &mut Report,
) -> Vec<Stitch> {
    let n = layout.frames.len();
    let seam_count = if layout.closed { n } else { n - 1 };
    let stitches: Vec<Stitch> =
        (0..seam_count).into_par_iter().map(|i| stitch_seam(params, layout, candidates, positions, i)).collect();
    report.stitched_seams = stitches.iter().filter(|s| !s.is_identity()).count();
    let before: u64 = stitches.iter().map(|s| s.before).sum();
    let after: u64 = stitches.iter().map(|s| s.after).sum();
    // The seams recomputed at the chosen positions add up to the DP optimum Ω.
    debug_assert_eq!(before, optimum, "seam costs must add up to the DP optimum");
    report.total_cost_unstitched = before as f64 / COST_SCALE;
    report.total_cost = after as f64 / COST_SCALE;
    report.mean_seam_cost = if seam_count == 0 { 0.0 } else { report.total_cost / seam_count as f64 };
    report.pieces = n;
    stitches
}

/// The stitch of the seam between piece `i` and the next: identity where stitching is off or a
/// side is empty, or where the deformation would draw pattern into a forbidden pixel.
fn stitch_seam(params: &Params, layout: &Layout, candidates: &Candidates, positions: &[Position], i: usize) -> Stitch {
    let (exemplar, model, samples) = (&*layout.exemplar, &layout.model, layout.samples);
    let (frames, empty) = (&layout.frames, &candidates.empty);
    let next = (i + 1) % frames.len();
    let rights = right_edges(exemplar, model, &frames[i], &[positions[i]]);
    let lefts = left_edges(exemplar, model, &[positions[next]], samples);
    let cost = u64::from(edge_distance(model, &rights, 0, &lefts, 0));
    if !params.stitch || empty[i] || empty[next] {
        return Stitch::identity(samples, cost);
    }
    let stitch = stitch::align(model, &rights, 0, &lefts, 0, params.stitch_penalty);
    // The deformation must not draw pattern into a forbidden pixel.
    let safe = candidates.forbidden_samples[i].iter().all(|&local| {
        let moved = stitch::deform(&frames[i], &stitch.remap, local);
        avoidance::footprint(moved).iter().all(|&(dx, dy)| {
            let (x, y) = (positions[i][0] + dx, positions[i][1] + dy);
            !exemplar.in_storage(x, y) || exemplar.rgba[exemplar.index(x, y)][3] == 0
        })
    });
    if safe { stitch } else { Stitch::identity(samples, cost) }
}

/// Draws the placed pieces, anti-aliased: rigid pieces as rotated copies, bent ones through the
/// ribbon's triangles (whose distortion goes into the report).
fn render_pieces(
    params: &Params,
    layout: &Layout,
    candidates: &Candidates,
    positions: &[Position],
    stitches: &[Stitch],
    report: &mut Report,
) -> RgbaImage {
    let (exemplar, canvas, empty) = (&*layout.exemplar, layout.canvas, &candidates.empty);
    let n = layout.frames.len();
    let remap_of = |i: usize| stitches.get(i).filter(|s| !s.is_identity()).map(|s| s.remap.clone());
    if layout.bent {
        record_distortion(report, &candidates.stretch);
    }
    let bent_pieces: Vec<ribbon_pieces::BentPiece<'_>> = if layout.bent {
        (0..n)
            .map(|i| ribbon_pieces::BentPiece {
                start: layout.quads[i].start,
                visible_end: if layout.fit_gap > 0.0 { layout.quads[i].end } else { f64::INFINITY },
                position: (!empty[i]).then_some(positions[i]),
                frame: &layout.frames[i],
                remap: remap_of(i),
                along_scale: layout.along_scales[i],
            })
            .collect()
    } else {
        Vec::new()
    };
    let shapes: Vec<Shape<'_>> = if layout.bent {
        ribbon_pieces::shapes(&candidates.triangles, &bent_pieces, exemplar, params.width, params.scale, canvas)
    } else {
        (0..n)
            .filter(|&i| !empty[i])
            .map(|i| rigid_shape(&layout.frames[i], positions[i], remap_of(i), exemplar, canvas))
            .collect()
    };
    render::render(canvas.0, canvas.1, params.samples_per_axis, &shapes)
}

/// The pieces as the pieces JSON lists them.
fn placed_pieces(
    params: &Params,
    layout: &Layout,
    candidates: &Candidates,
    positions: &[Position],
    stitches: &[Stitch],
) -> Vec<PlacedPiece> {
    let (quads, atlas, empty) = (&layout.quads, &layout.atlas, &candidates.empty);
    (0..layout.frames.len())
        .map(|i| {
            let stitch = stitches.get(i);
            PlacedPiece {
                index: i,
                arc: [quads[i].start, quads[i].end],
                quad: quads[i].corners.map(|c| [c.x, c.y]),
                position: if empty[i] { None } else { Some(atlas.local(positions[i]).1) },
                exemplar: if empty[i] { 0 } else { atlas.local(positions[i]).0 },
                rotation: layout.rigid_frames[i].angle(),
                scale: params.scale,
                valid_positions: if empty[i] { 0 } else { candidates.valid[i].len() },
                has_seam: stitch.is_some(),
                seam_cost: stitch.map_or(0.0, |s| s.after as f64 / COST_SCALE),
                seam_cost_unstitched: stitch.map_or(0.0, |s| s.before as f64 / COST_SCALE),
                stitch: stitch.map_or_else(|| (0..layout.samples).collect(), |s| s.remap.clone()),
            }
        })
        .collect()
}
