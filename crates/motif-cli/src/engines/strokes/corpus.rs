//! `motif bench --engine strokes` on the real-data corpus (`data/real/strokes/`): for every case,
//! the time, the element count against the expected one, and the fidelity figures (size, spacing
//! and orientation distances, overlap rate; `motif_strokes::fidelity`) of the output next to
//! those of a tiled copy of the reference and of reference elements placed at random, and the
//! same run with overlaps allowed and with position variation; and (`--case scale`) the ε
//! inferred from each drawing against the hand-picked one.

use std::path::Path;

use motif_core::NoProgress;
use motif_jobs::strokes::reference_from_svg;
use motif_strokes::fidelity::{self, Fidelity, MeasuredPattern};
use motif_strokes::{Input, Params, Target};
use serde::Deserialize;
use serde_json::{Value, json};

use crate::suite::{corpus_folder, read_cases};

/// One case of `cases.json`.
#[derive(Debug, Deserialize)]
pub(super) struct CorpusCase {
    pub name: String,
    pub file: String,
    pub kind: String,
    /// ε in drawing units.
    pub scale: f64,
    /// The target rectangle (0, 0)–(W, H).
    pub rect: [f64; 2],
    /// Elements a person counts in the drawing.
    pub elements_expected: usize,
}

fn figures(f: &Fidelity) -> Value {
    json!({
        "elements": f.elements,
        "size": f.size,
        "spacing": f.spacing,
        "orientation": f.orientation,
        "overlap_rate": f.overlap_rate,
    })
}

/// Runs one corpus case.
pub(super) fn run_case(folder: &Path, case: &CorpusCase, seed: u64) -> anyhow::Result<Value> {
    let document = motif_io::read_svg(&folder.join(&case.file))?;
    let strokes = reference_from_svg(&document, 0.1)?;
    let [width, height] = case.rect;
    let frame = kurbo::Rect::new(0.0, 0.0, width, height);
    let region = motif_core::Polygon::new(vec![
        motif_core::Point::new(0.0, 0.0),
        motif_core::Point::new(width, 0.0),
        motif_core::Point::new(width, height),
        motif_core::Point::new(0.0, height),
    ])?;
    let params = Params::default().with_scale(case.scale).with_seed(seed);
    let input = Input::new(strokes.clone(), Target::Region(region));
    let start = std::time::Instant::now();
    let output = motif_strokes::synthesize(&input, &params, &mut NoProgress)?;
    let seconds = start.elapsed().as_secs_f64();
    let loose = motif_strokes::synthesize(&input, &params.clone().with_avoid_overlaps(false), &mut NoProgress)?;
    let shifted = motif_strokes::synthesize(&input, &params.clone().with_position_variation(true), &mut NoProgress)?;

    let reference = fidelity::reference_pattern(&output.analysis, &strokes);
    let measure = |pattern: &MeasuredPattern| fidelity::fidelity(&reference, pattern);
    let synthesized = measure(&fidelity::output_pattern(&output, frame));
    let overlapping = measure(&fidelity::output_pattern(&loose, frame));
    let with_shifts = measure(&fidelity::output_pattern(&shifted, frame));
    let tiled = measure(&fidelity::tiled_copy(&output.analysis, &strokes, frame));
    let count = output.report.expected_elements.round() as usize;
    let random = measure(&fidelity::random_placement(&output.analysis, &strokes, count, frame, seed));
    let itself = measure(&reference);
    let report = &output.report;
    Ok(json!({
        "kind": case.kind,
        "seconds": seconds,
        "reference_strokes": report.reference_strokes,
        "reference_elements": report.reference_elements,
        "border_elements": report.border_elements,
        "fragment_elements": report.fragment_elements,
        "output_elements": report.output_elements,
        "expected_elements": report.expected_elements,
        "fallback_elements": report.fallback_elements,
        "overlap": report.overlap,
        "fidelity": {
            "output": figures(&synthesized),
            "output_with_overlaps_allowed": figures(&overlapping),
            "output_with_position_variation": figures(&with_shifts),
            "tiled": figures(&tiled),
            "random": figures(&random),
            "reference": figures(&itself),
        },
        "targets": {
            "no_more_overlap_than_the_reference": synthesized.overlap_rate <= itself.overlap_rate + 0.01,
            "spacing_closer_than_random": synthesized.spacing < random.spacing,
        },
    }))
}

/// The corpus figures of every case `selected` accepts.
pub(super) fn bench(seed: u64, selected: &dyn Fn(&str) -> bool) -> anyhow::Result<Value> {
    let folder = corpus_folder("strokes");
    let cases: Vec<CorpusCase> = read_cases(&folder)?;
    let mut all = serde_json::Map::new();
    for case in &cases {
        if selected(&case.name) {
            all.insert(case.name.clone(), run_case(&folder, case, seed)?);
        }
    }
    Ok(Value::Object(all))
}

/// Elements the analysis finds in `strokes` at ε = `scale`.
fn elements_at(strokes: &[motif_strokes::Stroke], scale: f64) -> anyhow::Result<usize> {
    Ok(motif_strokes::analyse(strokes, &Params::default().with_scale(scale), false)?.elements.len())
}

/// The inferred ε of one case against its hand-picked one (`scale` in `cases.json`), with the
/// element counts of both and the count a person makes.
pub(super) fn scale_case(folder: &Path, case: &CorpusCase) -> anyhow::Result<Value> {
    let document = motif_io::read_svg(&folder.join(&case.file))?;
    let strokes = reference_from_svg(&document, 0.1)?;
    let params = Params::default();
    let inferred = motif_strokes::infer_scale(&strokes, &params);
    Ok(json!({
        "strokes": strokes.len(),
        "human_elements": case.elements_expected,
        "hand_scale": case.scale,
        "hand_elements": elements_at(&strokes, case.scale)?,
        "inferred_scale": inferred.value,
        "inferred_elements": elements_at(&strokes, inferred.value)?,
        "inference": inferred,
    }))
}

/// [`scale_case`] for every case `selected` accepts.
pub(super) fn scale_bench(selected: &dyn Fn(&str) -> bool) -> anyhow::Result<Value> {
    let folder = corpus_folder("strokes");
    let cases: Vec<CorpusCase> = read_cases(&folder)?;
    let mut all = serde_json::Map::new();
    for case in &cases {
        if selected(&case.name) {
            all.insert(case.name.clone(), scale_case(&folder, case)?);
        }
    }
    Ok(Value::Object(all))
}
