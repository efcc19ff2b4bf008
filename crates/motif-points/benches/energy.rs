//! Criterion benchmarks of one evaluation of T with its position gradient (the merging step's unit
//! of work), fast against reference, on the bench's generated 2D and 3D exemplars after the first
//! matching step. `motif bench --engine points` reports whole syntheses at the paper's sizes.

use criterion::{Criterion, criterion_group, criterion_main};
use motif_points::samples::{hex_exemplar, lattice_exemplar};
use motif_points::{Domain, EnergyCase, Evaluator, Input, Params};

fn case(exemplar: motif_points::PointSet, neighbourhood: f64, max: Vec<f64>) -> EnergyCase {
    let mut params = Params::default();
    params.neighbourhood = Some(neighbourhood);
    params.seed = 1;
    EnergyCase::new(&Input::new(exemplar, Domain::Box { min: vec![0.0; max.len()], max }), &params)
        .expect("a valid case")
}

fn energy(c: &mut Criterion) {
    let mut group = c.benchmark_group("points energy");
    group.sample_size(10);
    let plane = case(hex_exemplar(30, 20, 0.1, 1), 1.0, vec![11.5, 7.5]);
    group.bench_function("fast 2D hex 600 -> 100", |b| b.iter(|| plane.evaluate(Evaluator::Fast, false)));
    group.bench_function("reference 2D hex 600 -> 100", |b| b.iter(|| plane.evaluate(Evaluator::Reference, false)));
    let volume = case(lattice_exemplar(1100, 1), 0.75, vec![8.0, 8.0, 7.0]);
    group.bench_function("fast 3D lattice 1100 -> 450", |b| b.iter(|| volume.evaluate(Evaluator::Fast, false)));
    group.bench_function("fast 3D lattice 1100 -> 450, attribute form", |b| {
        b.iter(|| volume.evaluate(Evaluator::Fast, true))
    });
    group.bench_function("reference 3D lattice 1100 -> 450", |b| {
        b.iter(|| volume.evaluate(Evaluator::Reference, false))
    });
    group.finish();
}

criterion_group!(benches, energy);
criterion_main!(benches);
