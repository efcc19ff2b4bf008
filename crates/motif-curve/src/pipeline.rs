//! A synthesis, stage by stage as the report times them: ribbon (`layout`), avoidance, valid
//! positions, dynamic program, stitching, render; or, for the repeat baseline, ribbon, avoidance
//! and render.

use motif_core::timing::StageTimer;
use motif_core::{Progress, RgbaImage};
use rayon::prelude::*;

use crate::avoidance::{FROM_FOLDOVER, ForbiddenMask};
use crate::brush::TileKind;
use crate::candidates::{Candidates, check_pin};
use crate::cost::{COST_SCALE, edge_distance, left_edges, right_edges};
use crate::dp::{DpCounters, RowSpec};
use crate::layout::Layout;
use crate::params::validate;
use crate::piece::Position;
use crate::render::{Shape, rigid_shape};
use crate::stitch::Stitch;
use crate::{ClosedMode, Error, Input, Method, Output, Params, PlacedPiece, Report};
use crate::{avoidance, incremental, render, repeat, ribbon_pieces, solve, stitch, thin, variety};

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
    timer.start("thin strip check");
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

/// Degenerate optima (module `thin`): when the optimum's pieces hold on average less than half of
/// their motif (a thin strip repeated at no seam cost), the windows that thin are taken out and
/// the dynamic program runs again; otherwise (and with `min_coverage` 0, the paper's rule) the
/// optimum stands as it is.
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
    let motifs = thin::motif_coverages(frames, exemplar, &candidates.valid, &free, &candidates.signatures);
    let before = thin::mean_share(frames, exemplar, &motifs, &positions);
    // `min_coverage` 0 asks for the paper's rule: no coverage rule at all.
    if before >= thin::THIN_SHARE || params.min_coverage == 0.0 {
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
    let positions: Vec<usize> = rows.iter().map(|row| row.positions.len()).collect();
    let solver = params.solver.resolve(&positions, closed);
    report.solver = solver;
    let setup = solve::Setup {
        solver,
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

/// Exact closed mode: the bound no cycle goes below, and the gap to it as a fraction of the
/// cycle's cost (0 when certified, also when a pinned first position leaves one start).
fn record_closed_bound(report: &mut Report, cycle_cost: u64, bound: Option<u64>, certified: Option<bool>) {
    let Some(bound) = bound else { return };
    let bound = if certified == Some(true) { cycle_cost } else { bound.min(cycle_cost) };
    report.closed_lower_bound = Some(bound as f64 / COST_SCALE);
    let gap = cycle_cost - bound;
    report.closed_gap = Some(if cycle_cost == 0 { 0.0 } else { gap as f64 / cycle_cost as f64 });
}

/// The exact optimum beside the coarse-to-fine solver's `Ω`, and the gap between them, into the
/// report (when the exact solver ran too).
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
