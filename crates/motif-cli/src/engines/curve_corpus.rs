//! `motif bench --engine curve` on the real-exemplar corpus (`data/real/curve/`): for every case,
//! the DP time per row, the seam cost per piece, the valid fraction and the patch fidelity of the
//! synthesis next to the repeat baseline's (see `motif_curve::fidelity`).

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use motif_core::NoProgress;
use motif_curve::fidelity::{PatchFidelity, patch_fidelity};
use motif_curve::{CurveInput, CurveOutput, CurveParams, Method};
use serde::Deserialize;
use serde_json::{Value, json};

/// One case of `cases.json`.
#[derive(Debug, Deserialize)]
pub struct CorpusCase {
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

/// The corpus folder of this source tree (the bench is a developer's tool run from a checkout).
pub fn corpus_folder() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/curve")
}

/// The cases of the corpus manifest.
pub fn read_cases(folder: &Path) -> anyhow::Result<Vec<CorpusCase>> {
    let path = folder.join("cases.json");
    let value: Value = motif_io::read_json(&path)?;
    serde_json::from_value(value).with_context(|| format!("{}: not a list of curve corpus cases", path.display()))
}

/// The parameters of a case.
pub fn params_of(case: &CorpusCase, method: Method) -> CurveParams {
    let mut params = CurveParams::default();
    params.width = case.width;
    params.piece_length = case.piece_length;
    params.scale = case.scale;
    params.method = method;
    params.variety = case.variety;
    params
}

/// One run of a case: the output, its wall time and its patch fidelity.
pub fn run(folder: &Path, case: &CorpusCase, method: Method) -> anyhow::Result<(CurveOutput, f64, PatchFidelity)> {
    let exemplar = motif_io::read_image(&folder.join(&case.exemplar))?;
    let curve = super::curve::read_curve(&folder.join(&case.path), 0.1)?;
    let params = params_of(case, method);
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

/// The figures of one case: synthesis and the repeat baseline.
pub fn run_case(folder: &Path, case: &CorpusCase) -> anyhow::Result<Value> {
    let (output, seconds, fidelity) = run(folder, case, Method::Synthesis)?;
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
        "repeat_baseline": { "seconds": repeat_seconds, "fidelity": fidelity_json(&repeat) },
    }))
}

/// Milliseconds per edit of an [`Incremental`](motif_curve::Incremental) session against a run
/// from scratch: a real exemplar along the hand-drawn flourish in 50 pieces, one bump of the curve
/// (as a dragged control point makes) moved ten times; `samples_per_axis` 1 is an interactive
/// preview's anti-aliasing, 3 the default.
pub fn incremental_edit(samples_per_axis: usize) -> anyhow::Result<Value> {
    let folder = corpus_folder();
    let exemplar = motif_io::read_image(&folder.join("chain_round.png"))?;
    let base = super::curve::read_curve(&folder.join("flourish.svg"), 0.1)?;
    let mut params = CurveParams::default();
    params.width = 108.0;
    params.piece_length = base.length() / 50.0;
    params.samples_per_axis = samples_per_axis;
    let lengths = base.cumulative_lengths().to_vec();
    let normals = base.vertex_normals();
    let middle = 0.6 * base.length();
    let dragged = |offset: f64| -> anyhow::Result<motif_core::Polyline> {
        let points = base
            .points()
            .iter()
            .zip(&lengths)
            .zip(&normals)
            .map(|((&p, &s), &n)| p + n * (offset * (-((s - middle) / 60.0).powi(2)).exp()))
            .collect();
        Ok(motif_core::Polyline::new(points, false)?)
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
pub fn bench(selected: &dyn Fn(&str) -> bool, quick: bool) -> anyhow::Result<Value> {
    let folder = corpus_folder();
    let cases = read_cases(&folder)?;
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
