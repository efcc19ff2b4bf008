//! `motif bench --engine points` on the real-data corpus (`data/real/points/`): for every case,
//! the time, the output count against the expected one, and the two fidelity distances next to
//! those of a uniform random set and of a tiled copy of the exemplar over the same domain.

use std::path::Path;

use anyhow::bail;
use motif_points::{Domain, Initialization, Input, Params};
use serde::Deserialize;
use serde_json::{Value, json};

use super::table_to_points;
use crate::suite::{corpus_folder, read_cases};

/// One case of `cases.json` (written by `data/real/points/make_manifest.py`).
#[derive(Debug, Deserialize)]
pub(super) struct CorpusCase {
    pub name: String,
    pub file: String,
    pub kind: String,
    pub neighbourhood: f64,
    pub domain: Vec<f64>,
    /// The observation window's size (from the origin): the exemplar's density is its count over it.
    pub window: Vec<f64>,
    #[serde(rename = "use")]
    pub purpose: String,
}

/// Runs one corpus case and returns its figures, with the targets checked; a clustered
/// case runs from random points too (`from_random_points`).
pub(super) fn run_case(folder: &Path, case: &CorpusCase, seed: u64) -> anyhow::Result<Value> {
    let mut figures = run_once(folder, case, seed, Initialization::Patches)?;
    if case.kind.starts_with("clustered") {
        figures["from_random_points"] = run_once(folder, case, seed, Initialization::Random)?;
    }
    Ok(figures)
}

/// One run of a corpus case from `initialization`.
fn run_once(folder: &Path, case: &CorpusCase, seed: u64, initialization: Initialization) -> anyhow::Result<Value> {
    let table = motif_io::read_points(&folder.join(&case.file))?;
    let (exemplar, discrete) = table_to_points(&table, &format!("corpus case {}", case.name))?;
    if case.domain.len() != exemplar.dimension {
        bail!("corpus case {}: a {}D domain for a {}D exemplar", case.name, case.domain.len(), exemplar.dimension);
    }
    let mut params = Params::default();
    params.neighbourhood = Some(case.neighbourhood);
    params.discrete_attributes = discrete;
    params.exemplar_window = Some((vec![0.0; case.window.len()], case.window.clone()));
    params.seed = seed;
    params.initialization = initialization;
    let domain = Domain::Box { min: vec![0.0; case.domain.len()], max: case.domain.clone() };
    let input = Input::new(exemplar, domain);
    let start = std::time::Instant::now();
    let output = motif_points::synthesize(&input, &params, &mut motif_core::NoProgress)?;
    let seconds = start.elapsed().as_secs_f64();
    let fidelity = &output.report.fidelity;
    let (o, r, t, h) = (&fidelity.output, &fidelity.random, &fidelity.tiled, &fidelity.halves);
    Ok(json!({
        "kind": case.kind,
        "use": case.purpose,
        "seconds": seconds,
        "exemplar_points": input.exemplar.len(),
        "output_points": output.points.len(),
        "expected_points": output.report.expected_points,
        "density_ratio": fidelity.density_ratio,
        "nearest_neighbour": {
            "output": o.nearest_neighbour, "random": r.nearest_neighbour, "tiled": t.nearest_neighbour,
            "exemplar_halves": h.nearest_neighbour,
        },
        "radial_distribution": {
            "output": o.radial_distribution, "random": r.radial_distribution, "tiled": t.radial_distribution,
            "exemplar_halves": h.radial_distribution,
        },
        // Mean size of the cluster a point belongs to (points closer than one spacing linked), the
        // exemplar's, and each set's over it.
        "cluster_size": {
            "exemplar": fidelity.exemplar_statistics.mean_cluster_size,
            "output": o.cluster_size_ratio, "random": r.cluster_size_ratio, "tiled": t.cluster_size_ratio,
        },
        // 3D cases: mean local thickness (a point and its 12 nearest neighbours off their plane,
        // in spacings), the exemplar's, and each set's over it (a sheet keeps its layers near 1).
        "thickness": (fidelity.exemplar_statistics.thickness > 0.0).then(|| json!({
            "exemplar": fidelity.exemplar_statistics.thickness,
            "output": o.thickness_ratio, "random": r.thickness_ratio, "tiled": t.thickness_ratio,
        })),
        "targets": {
            "density_within_3_percent": (fidelity.density_ratio - 1.0).abs() <= 0.03,
            "half_of_random": o.nearest_neighbour <= 0.5 * r.nearest_neighbour && o.radial_distribution <= 0.5 * r.radial_distribution,
            "within_1_5_of_tiled": o.nearest_neighbour <= 1.5 * t.nearest_neighbour && o.radial_distribution <= 1.5 * t.radial_distribution,
            // Whether a copy of the exemplar itself meets "half of random": where it does not, the
            // random set is already as close as the exemplar's own sampling noise allows.
            "tiled_copy_half_of_random": t.nearest_neighbour <= 0.5 * r.nearest_neighbour && t.radial_distribution <= 0.5 * r.radial_distribution,
        },
        "stages_ms": crate::context::stages_object(&output.report.stages_ms),
    }))
}

/// Cases that run only when named: the traced contour (825 points, δ = 35 σ; every window holds
/// ~230 output points) takes 10-20 s, more than the rest of the corpus together.
const SLOW_CASES: [&str; 1] = ["chain_contours"];

/// The corpus figures: every case of the manifest that `selected` accepts (slow cases only when
/// `named` accepts them), and a summary of how many runs (clustered cases run twice) meet each
/// target.
pub(super) fn bench(seed: u64, selected: &dyn Fn(&str) -> bool, named: &dyn Fn(&str) -> bool) -> anyhow::Result<Value> {
    let folder = corpus_folder("points");
    let cases: Vec<CorpusCase> = read_cases(&folder)?;
    let mut figures = serde_json::Map::new();
    let mut counts = [0usize; 5];
    for case in &cases {
        if !selected(&case.name) {
            continue;
        }
        if SLOW_CASES.contains(&case.name.as_str()) && !named(&case.name) {
            figures.insert(case.name.clone(), json!({ "skipped": "slow: runs only when named with --case" }));
            continue;
        }
        let value = run_case(&folder, case, seed)?;
        let keys = ["density_within_3_percent", "half_of_random", "within_1_5_of_tiled", "tiled_copy_half_of_random"];
        for run in std::iter::once(&value).chain(value.get("from_random_points")) {
            counts[0] += 1;
            for (slot, key) in keys.iter().enumerate() {
                counts[slot + 1] += usize::from(run["targets"][key].as_bool() == Some(true));
            }
        }
        figures.insert(case.name.clone(), value);
    }
    figures.insert(
        "summary".into(),
        json!({
            "cases": counts[0],
            "density_within_3_percent": counts[1],
            "half_of_random": counts[2],
            "within_1_5_of_tiled": counts[3],
            "tiled_copy_half_of_random": counts[4],
        }),
    );
    Ok(Value::Object(figures))
}
