//! The playground's points brushing, natively: the three strokes of `web/test_page.py` (two long
//! ones, then one crossing both) on the built-in hex exemplar with the page's settings, with the
//! engine's stage times per stroke. Run single-threaded to compare with the browser:
//! `RAYON_NUM_THREADS=1 cargo run --release -p motif-jobs --example brush`.

use std::io::Write;

#[path = "shared/page.rs"]
mod shared;

use motif_jobs::Job;
use motif_jobs::points::{DomainSpec, PointsInputs, PointsJob, StrokeSpec};

fn main() {
    let (exemplar, discrete, spacing, scale) = shared::hex_panel();
    let strokes: Vec<Vec<(f64, f64)>> = vec![
        std::iter::once((60.0, 90.0))
            .chain((1..17).map(|k| (60.0 + 25.0 * k as f64, 90.0 + 10.0 * (-1f64).powi(k))))
            .collect(),
        std::iter::once((60.0, 220.0))
            .chain((1..17).map(|k| (60.0 + 25.0 * k as f64, 220.0 + 10.0 * (-1f64).powi(k))))
            .collect(),
        std::iter::once((120.0, 40.0))
            .chain((1..17).map(|k| (120.0 + 20.0 * k as f64, 40.0 + 15.0 * k as f64)))
            .collect(),
    ];
    // The margin of grown points that may move, in spacings (the page uses 2).
    let keep_margin: f64 = std::env::args().nth(1).map_or(2.0, |a| a.parse().expect("a number"));
    // Extra job settings as JSON members, e.g. `"merge-iterations": 10`.
    let extra = std::env::args().nth(2).map_or(String::new(), |members| format!(", {members}"));
    let mut grown = None;
    for stroke in strokes {
        let job = format!(
            r#"{{"neighbourhood": {}, "domain": {{"box": [1, 1]}}, "max-points": 20000, "shrink": 0.6, "patch-candidates": 16, "keep-margin": {}{}}}"#,
            2.0 * spacing,
            keep_margin * spacing,
            extra
        );
        let mut job: PointsJob = serde_json::from_str(&job).expect("job");
        job.domain = DomainSpec::Stroke(StrokeSpec {
            points: stroke.iter().map(|&(x, y)| vec![x / scale, y / scale]).collect(),
            width: 3.0 * spacing,
            scale_along: None,
        });
        let before = grown.as_ref().map_or(0, |g: &motif_points::PointSet| g.len());
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
        let added = run.output.points.len() as i64 - before as i64;
        let report = &run.output.report;
        let steps: Vec<usize> = report.energy.iter().map(|e| e.merge_steps).collect();
        writeln!(
            std::io::stdout().lock(),
            "added {added:4} in {ms:6.1} ms ({} points, {} fixed, {} quadrature points, merge steps {steps:?}, NN {:.3}, g(r) {:.3}); stages {}",
            report.final_points,
            report.fixed_points,
            report.quadrature_points,
            report.fidelity.output.nearest_neighbour,
            report.fidelity.output.radial_distribution,
            serde_json::to_string(&report.stages_ms).unwrap()
        )
        .expect("stdout");
        grown = Some(run.output.points);
    }
    // A digest of the final structure as the playground returns it (x, y, first attribute), to
    // compare with the page's result for the same strokes.
    let set = grown.expect("three strokes");
    let mut digest = 0xcbf2_9ce4_8422_2325_u64;
    for i in 0..set.len() {
        for value in [set.position(i)[0], set.position(i)[1], set.attributes_of(i).first().copied().unwrap_or(0.0)] {
            digest = (digest ^ value.to_bits()).wrapping_mul(0x0100_0000_01b3);
        }
    }
    writeln!(std::io::stdout().lock(), "{} points, digest {digest:016x}", set.len()).expect("stdout");
    if let Ok(path) = std::env::var("BRUSH_DUMP") {
        let values: Vec<f64> = (0..set.len())
            .flat_map(|i| {
                [set.position(i)[0], set.position(i)[1], set.attributes_of(i).first().copied().unwrap_or(0.0)]
            })
            .collect();
        std::fs::write(path, serde_json::to_string(&values).expect("json")).expect("dump");
    }
}
