//! The curve job of the playground's determinism check, natively: a generated gold chain strip
//! along a fixed bent polyline. Prints the strip's RGBA bytes (hexadecimal, so that the page can
//! be given the very same exemplar) and the FNV-1a digest of the result's RGBA bytes, which
//! `web/test_page.py` compares with the page's WebAssembly result for the same inputs:
//! `cargo run --release -p motif-jobs --example curve_digest`.

use std::io::Write;

use motif_core::{Point, Polyline};
use motif_jobs::Job;
use motif_jobs::curve::{CurveInputs, CurveJob};

/// The job, as the page sends it (a JSON object of `motif curve` options).
pub const JOB: &str = r#"{"width": 60, "piece-length": 14, "canvas": [420, 240], "samples": 1}"#;

fn main() {
    let exemplar = motif_curve::samples::gold_chain(96, 40, 24.0, 30.0);
    // A wave with turns of both signs and a tight bend, so that pieces bend, rotate and overlap.
    let points: Vec<Point> = (0..=40)
        .map(|i| {
            let t = i as f64 / 40.0;
            Point::new(
                30.0 + 360.0 * t,
                120.0 + 70.0 * (t * 7.0 - 3.5) / (1.0 + (t * 7.0 - 3.5).abs()) * (1.0 - 2.0 * t * t),
            )
        })
        .collect();
    let curve = Polyline::new(points.clone(), false).expect("a polyline");
    let job: CurveJob = serde_json::from_str(JOB).expect("job");
    let inputs = CurveInputs::new(&exemplar, &curve);
    let run = job.run(inputs, &mut motif_core::NoProgress).expect("run");
    let image = &run.output.image;
    let mut digest = 0xcbf2_9ce4_8422_2325_u64;
    for &byte in image.as_bytes().iter() {
        digest = (digest ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
    }
    let hex: String = exemplar.as_bytes().iter().map(|b| format!("{b:02x}")).collect();
    let flat: Vec<f64> = points.iter().flat_map(|p| [p.x, p.y]).collect();
    let mut out = std::io::stdout().lock();
    writeln!(out, "exemplar {} {} {hex}", exemplar.width(), exemplar.height()).expect("stdout");
    writeln!(out, "points {}", serde_json::to_string(&flat).expect("json")).expect("stdout");
    writeln!(out, "job {JOB}").expect("stdout");
    writeln!(out, "{}x{} image, digest {digest:016x}", image.width(), image.height()).expect("stdout");
}
