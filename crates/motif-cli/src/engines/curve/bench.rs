//! `motif bench --engine curve`: the real-exemplar corpus (`data/real/curve/`: for every case, the
//! DP time per row, the seam cost per piece, the valid fraction and the patch fidelity of the
//! synthesis next to the repeat baseline's, see `motif_curve::patch_fidelity`), the incremental edit,
//! and the generated exemplars of the paper's two sizes (both solvers).

use std::path::Path;

use anyhow::Context as _;
use motif_core::NoProgress;
use motif_core::{Point, Polyline};
use motif_curve::{Input as CurveInput, Method, Output as CurveOutput, Params as CurveParams, Solver};
use motif_curve::{PatchFidelity, patch_fidelity};

use crate::suite::Bench;
use crate::suite::{corpus_folder, read_cases};
use motif_curve::samples::gold_chain;
use serde::Deserialize;
use serde_json::{Value, json};

/// One case of `cases.json`.
#[derive(Debug, Deserialize)]
pub(super) struct CorpusCase {
    pub name: String,
    pub exemplar: String,
    pub path: String,
    pub width: f64,
    pub piece_length: f64,
    #[serde(default = "one")]
    pub scale: f64,
    /// `--variety` of the case (0 when absent).
    #[serde(default)]
    pub variety: f64,
    #[serde(default)]
    pub kind: String,
    /// Small and fast: run by the tests and by `--quick`.
    #[serde(default)]
    pub test: bool,
}

fn one() -> f64 {
    1.0
}

/// The parameters of a case (the exact solver).
pub(super) fn params_of(case: &CorpusCase, method: Method) -> CurveParams {
    let mut params = CurveParams::default().with_solver(Solver::Exact);
    params.width = case.width;
    params.piece_length = case.piece_length;
    params.scale = case.scale;
    params.method = method;
    params.variety = case.variety;
    params
}

/// One run of a case: the output, its wall time and its patch fidelity.
pub(super) fn run(
    folder: &Path,
    case: &CorpusCase,
    method: Method,
) -> anyhow::Result<(CurveOutput, f64, PatchFidelity)> {
    run_with(folder, case, params_of(case, method))
}

/// One run of a case with `params`.
fn run_with(
    folder: &Path,
    case: &CorpusCase,
    params: CurveParams,
) -> anyhow::Result<(CurveOutput, f64, PatchFidelity)> {
    let exemplar = motif_io::read_image(&folder.join(&case.exemplar))?;
    let curve = super::read_curve(&folder.join(&case.path), 0.1)?;
    let input = CurveInput { exemplar: &exemplar, curve: &curve, avoidance: None, more_exemplars: &[] };
    let start = std::time::Instant::now();
    let output = motif_curve::synthesize(&input, &params, &mut NoProgress)
        .with_context(|| format!("curve corpus case {}", case.name))?;
    let seconds = start.elapsed().as_secs_f64();
    let fidelity = patch_fidelity(&exemplar, &output.image, &output.ribbon_top, &output.ribbon_bottom, case.scale);
    Ok((output, seconds, fidelity))
}

fn fidelity_json(figures: &PatchFidelity) -> Value {
    json!({
        "mean_patch_distance": figures.mean_distance,
        "p90_patch_distance": figures.p90_distance,
        "broken_patch_fraction": figures.broken_fraction,
        "exemplar_coverage": figures.exemplar_coverage,
        "patches": figures.patches,
    })
}

/// The coarse-to-fine solver on a case, against the exact solver's optimum `exact` (paper units):
/// its DP time, its cost and the gap, and its fidelity.
fn coarse_figures(folder: &Path, case: &CorpusCase, exact: f64) -> anyhow::Result<Value> {
    let params = params_of(case, Method::Synthesis).with_solver(Solver::CoarseToFine);
    let (output, seconds, fidelity) = run_with(folder, case, params)?;
    let report = &output.report;
    let gap = report.dp_optimum - exact;
    Ok(json!({
        "seconds": seconds,
        "dp_row_ms_median": report.dp_row_ms_median,
        "dp_row_ms_max": report.dp_row_ms_max,
        "dp_optimum": report.dp_optimum,
        "exact_optimum": exact,
        "cost_gap": gap,
        "cost_gap_fraction": if report.dp_optimum > 0.0 { gap / report.dp_optimum } else { 0.0 },
        "coarse": report.coarse,
        "fidelity": fidelity_json(&fidelity),
    }))
}

/// The figures of one case: synthesis (the exact solver, then the coarse-to-fine one) and the
/// repeat baseline.
pub(super) fn run_case(folder: &Path, case: &CorpusCase) -> anyhow::Result<Value> {
    let (output, seconds, fidelity) = run(folder, case, Method::Synthesis)?;
    let coarse = coarse_figures(folder, case, output.report.dp_optimum)?;
    let (_, repeat_seconds, repeat) = run(folder, case, Method::Repeat)?;
    let report = &output.report;
    Ok(json!({
        "kind": case.kind,
        "width": case.width,
        "piece_length": case.piece_length,
        "variety": case.variety,
        "samples_per_edge": report.samples_per_edge,
        "pieces": report.pieces,
        "seconds": seconds,
        "dp_row_ms_median": report.dp_row_ms_median,
        "dp_row_ms_max": report.dp_row_ms_max,
        "seam_cost_per_piece": report.total_cost / report.pieces.max(1) as f64,
        "valid_fraction": report.valid_fraction,
        "distinct_windows": report.distinct_windows,
        "repeated_pairs": report.repeated_pairs,
        "empty_pieces": report.empty_pieces,
        "warnings": report.warnings,
        "fidelity": fidelity_json(&fidelity),
        "coarse_to_fine": coarse,
        "repeat_baseline": { "seconds": repeat_seconds, "fidelity": fidelity_json(&repeat) },
    }))
}

/// Milliseconds per edit of an [`Incremental`](motif_curve::Incremental) session against a run
/// from scratch: a real exemplar along the hand-drawn flourish in 50 pieces, one bump of the curve
/// (as a dragged control point makes) moved ten times; `samples_per_axis` 1 is an interactive
/// preview's anti-aliasing, 3 the default.
pub(super) fn incremental_edit(samples_per_axis: usize) -> anyhow::Result<Value> {
    let folder = corpus_folder("curve");
    let exemplar = motif_io::read_image(&folder.join("chain_round.png"))?;
    let base = super::read_curve(&folder.join("flourish.svg"), 0.1)?;
    let mut params = CurveParams::default();
    params.width = 108.0;
    params.piece_length = base.length() / 50.0;
    params.samples_per_axis = samples_per_axis;
    let lengths = base.cumulative_lengths().to_vec();
    let normals = base.vertex_normals();
    let middle = 0.6 * base.length();
    let dragged = |offset: f64| -> anyhow::Result<Polyline> {
        let points = base
            .points()
            .iter()
            .zip(&lengths)
            .zip(&normals)
            .map(|((&p, &s), &n)| p + n * (offset * (-((s - middle) / 60.0).powi(2)).exp()))
            .collect();
        Ok(Polyline::new(points, false)?)
    };
    let mut session = motif_curve::Incremental::new();
    let (mut edits, mut scratch, mut reused) = (Vec::new(), Vec::new(), Vec::new());
    let mut last_stages = Vec::new();
    for step in 0..=10 {
        let curve = dragged(2.0 * step as f64)?;
        let input = CurveInput { exemplar: &exemplar, curve: &curve, avoidance: None, more_exemplars: &[] };
        let start = std::time::Instant::now();
        let output = session.synthesize(&input, &params, &mut NoProgress)?;
        let edit_ms = start.elapsed().as_secs_f64() * 1e3;
        let start = std::time::Instant::now();
        let fresh = motif_curve::synthesize(&input, &params, &mut NoProgress)?;
        scratch.push(start.elapsed().as_secs_f64() * 1e3);
        anyhow::ensure!(fresh.image == output.image, "incremental run differs from a run from scratch");
        if step == 10 {
            last_stages = output.report.stages_ms.clone();
        }
        if step > 0 {
            edits.push(edit_ms);
            reused.push(output.report.dp_rows_reused);
        }
    }
    let median = |values: &mut Vec<f64>| {
        values.sort_by(f64::total_cmp);
        values[values.len() / 2]
    };
    Ok(json!({
        "exemplar": "chain_round.png",
        "pieces": 50,
        "samples_per_axis": samples_per_axis,
        "last_edit_stages_ms": last_stages,
        "edit_ms_median": median(&mut edits.clone()),
        "edit_ms_max": edits.iter().copied().fold(0.0, f64::max),
        "scratch_ms_median": median(&mut scratch),
        "dp_rows_reused": reused,
        "target_edit_ms": 33.0,
    }))
}

/// The corpus figures: every case `selected` accepts (only the test cases when `quick`).
pub(super) fn corpus_figures(selected: &dyn Fn(&str) -> bool, quick: bool) -> anyhow::Result<Value> {
    let folder = corpus_folder("curve");
    let cases: Vec<CorpusCase> = read_cases(&folder)?;
    let mut figures = serde_json::Map::new();
    let (mut count, mut better, mut clean) = (0, 0, 0);
    for case in cases.iter().filter(|case| selected(&case.name) && (!quick || case.test)) {
        let value = run_case(&folder, case)?;
        count += 1;
        let synthesis = value["fidelity"]["broken_patch_fraction"].as_f64().unwrap_or(1.0);
        let repeat = value["repeat_baseline"]["fidelity"]["broken_patch_fraction"].as_f64().unwrap_or(1.0);
        better += usize::from(synthesis <= repeat);
        clean += usize::from(value["warnings"].as_array().is_some_and(Vec::is_empty));
        figures.insert(case.name.clone(), value);
    }
    figures.insert(
        "summary".into(),
        json!({
            "cases": count,
            "broken_patches_at_most_repeat": better,
            "without_warnings": clean,
        }),
    );
    Ok(Value::Object(figures))
}

/// One measured workload: a generated chain exemplar, a gentle wave, DP rows of both solvers.
fn bench_case(width: usize, height: usize, rows: usize) -> anyhow::Result<Value> {
    let chain_height = (height as f64 * 0.55).round();
    let exemplar = gold_chain(width, height, (width as f64 / 5.3).round(), chain_height);
    let piece_length = 24.0;
    let mut params = CurveParams::default();
    params.width = height as f64; // C = H, as in the paper's timings.
    params.piece_length = piece_length;
    params.samples_per_axis = 1;
    // A gentle arc (radius 300 px): every piece is tilted by about 4.6° against the previous one.
    let wave = |pieces: usize| -> anyhow::Result<Polyline> {
        let length = piece_length * pieces as f64;
        let radius = 300.0;
        let points = (0..=200)
            .map(|i| {
                let angle = i as f64 / 200.0 * length / radius;
                Point::new(radius * angle.sin(), 400.0 - radius * angle.cos())
            })
            .collect();
        Ok(Polyline::new(points, false)?)
    };
    let mut figures = serde_json::Map::new();
    let mut medians = [0.0; 2];
    // Both solvers run on the same curve, so they fill the same rows.
    let curve = wave(rows + 1)?;
    for (slot, solver) in [Solver::Exact, Solver::Reference].into_iter().enumerate() {
        params.solver = solver;
        let output = motif_curve::synthesize(
            &CurveInput { exemplar: &exemplar, curve: &curve, avoidance: None, more_exemplars: &[] },
            &params,
            &mut NoProgress,
        )?;
        let report = &output.report;
        medians[slot] = report.dp_row_ms_median;
        let name = if solver == Solver::Exact { "exact" } else { "reference" };
        figures.insert(
            name.into(),
            json!({
                "dp_row_ms": report.dp_row_ms,
                "dp_row_ms_median": report.dp_row_ms_median,
                "dp_row_ms_max": report.dp_row_ms_max,
                "valid_ms_per_piece": report.stages_ms.iter().find(|(s, _)| s == "valid positions").map(|(_, ms)| *ms / report.pieces as f64),
                "valid_fraction": report.valid_fraction,
                "columns_skipped_fraction": report.columns_skipped_fraction,
                "columns_compared_to_completion_fraction": report.dp_counters.completed as f64 / report.dp_counters.pairs.max(1) as f64,
                "pairs_per_row": report.dp_counters.pairs as f64 / report.dp_row_ms.len().max(1) as f64,
                "columns_visited_fraction": report.dp_counters.visited as f64 / report.dp_counters.pairs.max(1) as f64,
                "columns_compared_fraction": report.dp_counters.compared as f64 / report.dp_counters.pairs.max(1) as f64,
                "total_cost": report.total_cost,
            }),
        );
    }
    figures.insert("exemplar".into(), json!([width, height]));
    figures.insert("samples_per_edge".into(), json!(height));
    figures.insert("speedup_reference_over_exact".into(), json!(medians[1] / medians[0].max(1e-9)));
    Ok(Value::Object(figures))
}

/// Figures for `motif bench`: DP milliseconds per row of both solvers on generated exemplars of
/// the paper's two sizes (199×82 and 325×64), with C equal to the exemplar height.
pub(super) fn bench(bench: &Bench) -> anyhow::Result<Value> {
    let corpus_selected = |name: &str| bench.selects(name, "corpus");
    if bench.quick {
        return Ok(json!({
            "quick_48x24": bench_case(48, 24, 3)?,
            "real_data": corpus_figures(&corpus_selected, true)?,
        }));
    }
    let mut figures = serde_json::Map::new();
    figures.insert("real_data".into(), corpus_figures(&corpus_selected, false)?);
    if bench.selects("incremental", "generated") {
        figures.insert("incremental_edit_preview".into(), incremental_edit(1)?);
        figures.insert("incremental_edit".into(), incremental_edit(3)?);
    }
    for (name, width, height) in [("199x82", 199, 82), ("325x64", 325, 64)] {
        if bench.selects(name, "generated") {
            figures.insert(format!("exemplar_{name}"), bench_case(width, height, 4)?);
        }
    }
    figures.insert("paper_gpu_ms_per_row".into(), json!({ "199x82": 30.0, "325x64": 650.0 }));
    Ok(Value::Object(figures))
}
