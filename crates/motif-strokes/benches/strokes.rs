//! Criterion benchmarks of the whole pipeline on the workloads: a 60-element 1D hatching
//! along a path 10× its length, and a 120-element 2D field of three-stroke figures in a region 10×
//! its area (`motif bench --engine strokes` reports the same workloads as JSON).

use criterion::{Criterion, criterion_group, criterion_main};
use motif_core::math;
use motif_core::{NoProgress, Point, Polygon, Polyline};
use motif_strokes::samples::{FigureField, HatchRow, figure_field, hatch_row};
use motif_strokes::{Input, Params, Target, synthesize};

fn one_d() -> (Input, Params) {
    let row = HatchRow { count: 60, jitter: 1.5, ..HatchRow::default() };
    let strokes = hatch_row(&row, Point::ORIGIN, |i| 0.3 * math::sin(i as f64 * 0.3), |_| [20, 20, 20, 255], 1);
    let length = 10.0 * row.count as f64 * row.spacing;
    let points = (0..=400)
        .map(|i| {
            let x = length * i as f64 / 400.0;
            Point::new(x, 0.05 * length * math::sin(x / length * std::f64::consts::TAU * 2.5))
        })
        .collect();
    let mut params = Params::default();
    params.scale = 4.0;
    (Input::new(strokes, Target::Path(Polyline::new(points, false).unwrap())), params)
}

fn two_d() -> (Input, Params) {
    let field = FigureField::default();
    let strokes = figure_field(&field, Point::ORIGIN, 1);
    let side = (10.0 * (field.columns * field.rows) as f64).sqrt() * field.spacing;
    let region =
        Polygon::new(vec![Point::new(0.0, 0.0), Point::new(side, 0.0), Point::new(side, side), Point::new(0.0, side)])
            .unwrap();
    let mut params = Params::default();
    params.scale = 8.0;
    (Input::new(strokes, Target::Region(region)), params)
}

fn pipeline(c: &mut Criterion) {
    let mut group = c.benchmark_group("strokes");
    group.sample_size(10);
    let (input, params) = one_d();
    group.bench_function("path_60_elements_10x", |b| b.iter(|| synthesize(&input, &params, &mut NoProgress).unwrap()));
    let (input, params) = two_d();
    group.bench_function("region_120_elements_10x", |b| {
        b.iter(|| synthesize(&input, &params, &mut NoProgress).unwrap())
    });
    group.finish();
}

criterion_group!(benches, pipeline);
criterion_main!(benches);
