//! Criterion benchmarks of the dynamic program: the exact solver on the 199×82 size, and
//! the exact and reference solvers side by side on a small exemplar (`motif bench --engine curve`
//! reports the per-row figures of both solvers at full size as JSON).

use criterion::{Criterion, criterion_group, criterion_main};
use motif_core::math;
use motif_core::{NoProgress, Point, Polyline, RgbaImage};
use motif_curve::samples::chain;
use motif_curve::{Input as CurveInput, Params as CurveParams, Solver, synthesize};

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
            Point::new(radius * math::sin(angle), 400.0 - radius * math::cos(angle))
        })
        .collect();
    let curve = Polyline::new(points, false).expect("curve");
    let input = CurveInput { exemplar, curve: &curve, avoidance: None, more_exemplars: &[] };
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
