//! Times DP rows of the exact solver on a generated chain exemplar (for profiling):
//! `cargo run --release -p motif-curve --example dp_rows -- 199 82`. A third argument `1` runs the
//! reference solver; a fourth, `n > 0`, adds colour noise of ±n to visible pixels, so that
//! columns no longer repeat exactly (the periodic chain has many identical columns).

use motif_core::{NoProgress, Point, Polyline, RgbaImage};
use motif_curve::{CurveInput, CurveParams, Solver, synthesize};

fn chain(width: usize, height: usize, period: f64, chain_height: f64, noise: i32) -> RgbaImage {
    let cy = height as f64 / 2.0;
    let (rx, ry) = (period * 0.36, chain_height / 2.0 - 1.0);
    let thickness = (chain_height * 0.16).max(2.0);
    RgbaImage::from_fn(width, height, |x, y| {
        let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
        let (dx, dy) = (px.rem_euclid(period) - period * 0.5, py - cy);
        let e = ((dx / rx).powi(2) + (dy / ry).powi(2)).sqrt();
        let g = (dx / (rx * rx)).hypot(dy / (ry * ry)) / e.max(1e-9);
        let ring = (thickness / 2.0 + 0.5 - (e - 1.0).abs() / g.max(1e-9)).clamp(0.0, 1.0);
        let a = (ring * 255.0).round() as u8;
        // A fixed hash of the pixel, so runs are repeatable.
        let hash = (x as u32).wrapping_mul(0x9e37_79b1) ^ (y as u32).wrapping_mul(0x85eb_ca6b);
        let jitter = |shift: u32, value: u8| {
            let offset = ((hash.rotate_left(shift) >> 8) % (2 * noise as u32 + 1)) as i32 - noise;
            (i32::from(value) + offset).clamp(0, 255) as u8
        };
        if a == 0 { [0; 4] } else { [jitter(0, 235), jitter(11, 185), jitter(22, (60.0 + 40.0 * dy / ry) as u8), a] }
    })
}

#[allow(clippy::print_stdout)]
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
            Point::new(radius * angle.sin(), 400.0 - radius * angle.cos())
        })
        .collect();
    let curve = Polyline::new(points, false).expect("curve");
    let output =
        synthesize(&CurveInput { exemplar: &exemplar, curve: &curve, avoidance: None }, &params, &mut NoProgress)
            .expect("synthesis");
    let report = &output.report;
    println!(
        "{width}x{height} {solver:?}: median {:.1} ms/row, rows {:?}, valid {:.3}, counters {:?}, cost {}",
        report.dp_row_ms_median, report.dp_row_ms, report.valid_fraction, report.dp_counters, report.total_cost
    );
}
