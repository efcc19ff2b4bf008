//! Times DP rows of the exact solver on a generated chain exemplar (for profiling):
//! `cargo run --release -p motif-curve --example dp_rows -- 199 82`. A third argument `1` runs the
//! reference solver; a fourth, `n > 0`, adds colour noise of ±n to visible pixels, so that
//! columns no longer repeat exactly (the periodic chain has many identical columns).

use motif_core::{NoProgress, Point, Polyline};
use motif_curve::samples::chain;
use motif_curve::{Input as CurveInput, Params as CurveParams, Solver, synthesize};

#[allow(clippy::print_stdout, reason = "the example prints its figures")]
fn main() {
    let args: Vec<usize> = std::env::args().skip(1).map(|a| a.parse().expect("integer")).collect();
    let (width, height) = (args.first().copied().unwrap_or(199), args.get(1).copied().unwrap_or(82));
    let solver = if args.get(2) == Some(&1) { Solver::Reference } else { Solver::Exact };
    let noise = args.get(3).copied().unwrap_or(0) as i32;
    let exemplar = chain(width, height, (width as f64 / 5.3).round(), (height as f64 * 0.55).round(), noise);
    let mut params = CurveParams::default();
    params.width = height as f64;
    params.piece_length = 24.0;
    params.samples_per_axis = 1;
    params.solver = solver;
    let radius = 300.0;
    let length = 24.0 * 9.0;
    let points = (0..=200)
        .map(|i| {
            let angle = i as f64 / 200.0 * length / radius;
            Point::new(radius * motif_core::math::sin(angle), 400.0 - radius * motif_core::math::cos(angle))
        })
        .collect();
    let curve = Polyline::new(points, false).expect("curve");
    let output = synthesize(
        &CurveInput { exemplar: &exemplar, curve: &curve, avoidance: None, more_exemplars: &[] },
        &params,
        &mut NoProgress,
    )
    .expect("synthesis");
    let report = &output.report;
    println!(
        "{width}x{height} {solver:?}: median {:.1} ms/row, rows {:?}, valid {:.3}, counters {:?}, cost {}",
        report.dp_row_ms_median, report.dp_row_ms, report.valid_fraction, report.dp_counters, report.total_cost
    );
}
