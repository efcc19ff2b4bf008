//! The playground's brushing over many seeds, to judge a change of its settings on more than one
//! noisy stroke set: for each seed, two long strokes and one crossing both (as in the `brush`
//! example, shifted by a seed-dependent offset) on the built-in hex exemplar, with the page's
//! settings plus any extra job members. Prints the mean time of fresh and crossing strokes and the
//! mean fidelity of the grown structure. Run single-threaded, as the page runs:
//! `RAYON_NUM_THREADS=1 cargo run --release -p motif-jobs --example brush_sweep -- 100 '"merge-iterations": 6' [KEEP_MARGIN]`
//! (seeds, extra job members, the keep margin in spacings; the page's is 2).

use std::io::Write;

#[path = "shared/page.rs"]
mod shared;

use motif_core::random::Rng;
use motif_jobs::Job;
use motif_jobs::points::{DomainSpec, PointsInputs, PointsJob, StrokeSpec};

fn main() {
    let seeds: u64 = std::env::args().nth(1).map_or(10, |a| a.parse().expect("a number of seeds"));
    let extra = std::env::args().nth(2).unwrap_or_default();
    // The margin of grown points that may move, in spacings (the page uses 2).
    let keep_margin: f64 = std::env::args().nth(3).map_or(2.0, |a| a.parse().expect("a number"));
    let (exemplar, discrete, spacing, scale) = shared::hex_panel();
    let (mut fresh_ms, mut crossing_ms, mut crossing_added) = (Vec::new(), Vec::new(), Vec::new());
    let (mut nearest, mut radial) = (0.0, 0.0);
    let mut crossing_stages: std::collections::BTreeMap<String, f64> = Default::default();
    for seed in 1..=seeds {
        let mut stream = motif_core::SeedStreams::new(seed).stream("brush sweep", 0);
        let (dx, dy, tilt) = (stream.random::<f64>() * 40.0, stream.random::<f64>() * 40.0, stream.random::<f64>());
        let strokes: Vec<Vec<(f64, f64)>> = vec![
            (0..17).map(|k| (60.0 + dx + 25.0 * k as f64, 90.0 + dy + 10.0 * (-1f64).powi(k))).collect(),
            (0..17).map(|k| (60.0 + dx + 25.0 * k as f64, 220.0 + dy + 10.0 * (-1f64).powi(k))).collect(),
            (0..17).map(|k| (120.0 + dx + 20.0 * k as f64, 40.0 + dy + (10.0 + 10.0 * tilt) * k as f64)).collect(),
        ];
        let mut grown: Option<motif_points::PointSet> = None;
        for (index, stroke) in strokes.iter().enumerate() {
            let mut job = serde_json::json!({
                "neighbourhood": 2.0 * spacing, "domain": {"box": [1, 1]}, "seed": seed, "max-points": 20000,
                "shrink": 0.6, "patch-candidates": 16, "keep-margin": keep_margin * spacing,
            });
            // Extra members replace the page's.
            let extra: serde_json::Value = serde_json::from_str(&format!("{{{extra}}}")).expect("extra job members");
            for (key, value) in extra.as_object().expect("an object") {
                job[key] = value.clone();
            }
            let mut job: PointsJob = serde_json::from_value(job).expect("job");
            job.domain = DomainSpec::Stroke(StrokeSpec {
                points: stroke.iter().map(|&(x, y)| vec![x / scale, y / scale]).collect(),
                width: 3.0 * spacing,
                scale_along: None,
            });
            let before = grown.as_ref().map_or(0, |g| g.len());
            let start = std::time::Instant::now();
            let run = job
                .run(
                    PointsInputs {
                        existing: grown.clone(),
                        integer_columns: &discrete,
                        ..PointsInputs::new(exemplar.clone())
                    },
                    &mut motif_core::NoProgress,
                )
                .expect("run");
            let ms = start.elapsed().as_secs_f64() * 1000.0;
            if index < 2 {
                fresh_ms.push(ms);
            } else {
                crossing_ms.push(ms);
                crossing_added.push(run.output.points.len() as f64 - before as f64);
                nearest += run.output.report.fidelity.output.nearest_neighbour;
                for (stage, ms) in &run.output.report.stages_ms {
                    *crossing_stages.entry(stage.clone()).or_default() += ms / seeds as f64;
                }
                radial += run.output.report.fidelity.output.radial_distribution;
            }
            grown = Some(run.output.points);
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let range = |v: &[f64]| (v.iter().copied().fold(f64::MAX, f64::min), v.iter().copied().fold(f64::MIN, f64::max));
    let n = seeds as f64;
    writeln!(
        std::io::stdout().lock(),
        "fresh strokes {:.1} ms mean ({:.1}-{:.1}); crossing strokes {:.1} ms mean ({:.1}-{:.1}) adding {:.1} points; grown structure NN {:.4}, g(r) {:.4} (means over {seeds} seeds)",
        mean(&fresh_ms),
        range(&fresh_ms).0,
        range(&fresh_ms).1,
        mean(&crossing_ms),
        range(&crossing_ms).0,
        range(&crossing_ms).1,
        mean(&crossing_added),
        nearest / n,
        radial / n,
    )
    .expect("stdout");
    let stages: Vec<String> = crossing_stages.iter().map(|(stage, ms)| format!("{stage} {ms:.1}")).collect();
    writeln!(std::io::stdout().lock(), "crossing strokes, mean ms per stage: {}", stages.join(", ")).expect("stdout");
}
