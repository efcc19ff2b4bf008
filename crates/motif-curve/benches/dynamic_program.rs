//! Criterion benchmarks of the dynamic program: the exact solver on the 199×82 size, and
//! the exact and reference solvers side by side on a small exemplar (`motif bench --engine curve`
//! reports the per-row figures of both solvers at full size as JSON).

use criterion::{Criterion, criterion_group, criterion_main};
use motif_core::{NoProgress, Point, Polyline, RgbaImage};
use motif_curve::{CurveInput, CurveParams, Solver, synthesize};

/// A generated chain strip with alpha (the same drawing as `examples/dp_rows.rs`).
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

fn run(exemplar: &RgbaImage, solver: Solver, pieces: usize) -> f64 {
    let mut params = CurveParams::default();
    params.width = exemplar.height() as f64;
    params.piece_length = 24.0;
    params.samples_per_axis = 1;
    params.solver = solver;
    let radius = 300.0;
    let length = 24.0 * pieces as f64;
    let points = (0..=200)
        .map(|i| {
            let angle = i as f64 / 200.0 * length / radius;
            Point::new(radius * angle.sin(), 400.0 - radius * angle.cos())
        })
        .collect();
    let curve = Polyline::new(points, false).expect("curve");
    let input = CurveInput { exemplar, curve: &curve, avoidance: None };
    synthesize(&input, &params, &mut NoProgress).expect("synthesis").report.total_cost
}

fn dynamic_program(c: &mut Criterion) {
    let mut group = c.benchmark_group("curve");
    group.sample_size(10);
    let large = chain(199, 82, 38.0, 45.0, 0);
    group.bench_function("exact 199x82, 9 pieces", |b| b.iter(|| run(&large, Solver::Exact, 9)));
    let small = chain(80, 40, 15.0, 22.0, 0);
    group.bench_function("exact 80x40, 6 pieces", |b| b.iter(|| run(&small, Solver::Exact, 6)));
    group.bench_function("reference 80x40, 6 pieces", |b| b.iter(|| run(&small, Solver::Reference, 6)));
    group.finish();
}

criterion_group!(benches, dynamic_program);
criterion_main!(benches);
