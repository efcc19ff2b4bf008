//! The strokes job of the playground's determinism check, natively: the page's built-in
//! `figures` reference synthesized into a 300 × 300 square. Prints the FNV-1a digest of the
//! output's coordinates and widths (their bits), which `web/test_page.py` compares with the page's
//! WebAssembly result: `cargo run --release -p motif-jobs --example strokes_digest`.

use std::io::Write;

use motif_core::Point;
use motif_jobs::Job;
use motif_jobs::strokes::{StrokesInputs, StrokesJob, TargetSpec};
use motif_strokes::samples::{FigureField, figure_field};

/// The job, as the page's determinism check sends it.
pub const JOB: &str = r#"{"scale": 6, "target": {"rect": [1, 1]}}"#;

fn main() {
    // As `StrokesPanel::new("figures")` in web/src/lib.rs builds it.
    let reference =
        figure_field(&FigureField { columns: 5, rows: 4, ..FigureField::default() }, Point::new(20.0, 20.0), 1);
    let mut job: StrokesJob = serde_json::from_str(JOB).expect("job");
    job.target = TargetSpec::Rect([300.0, 300.0]);
    let run = job.run(StrokesInputs::new(reference), &mut motif_core::NoProgress).expect("run");
    let mut digest = 0xcbf2_9ce4_8422_2325_u64;
    for stroke in &run.output.strokes {
        for p in stroke.polyline.points() {
            for value in [p.x, p.y] {
                digest = (digest ^ value.to_bits()).wrapping_mul(0x0100_0000_01b3);
            }
        }
        digest = (digest ^ stroke.width.to_bits()).wrapping_mul(0x0100_0000_01b3);
    }
    let mut out = std::io::stdout().lock();
    writeln!(out, "job {JOB}").expect("stdout");
    writeln!(out, "{} strokes, digest {digest:016x}", run.output.strokes.len()).expect("stdout");
}
