//! Criterion benchmark of one guided stylization (0.05 MP, 3+3 channels, 3×3 patches).
#![allow(missing_docs, reason = "criterion's macros generate undocumented items")]

use criterion::{Criterion, criterion_group, criterion_main};
use motif_core::{FloatImage, NoProgress};
use motif_stylize::{Guide, Input, Params, synthesize};

fn image(width: usize, height: usize, phase: f32) -> FloatImage {
    let data = (0..width * height * 3)
        .map(|i| {
            let (p, c) = (i / 3, i % 3);
            let (x, y) = ((p % width) as f32, (p / width) as f32);
            0.5 + 0.5 * (motif_core::math::sin_f32(x * 0.11 + phase) * motif_core::math::cos_f32(y * 0.07 + c as f32))
        })
        .collect();
    FloatImage::from_data(width, height, 3, data).expect("sizes match")
}

fn bench(c: &mut Criterion) {
    let style = image(160, 160, 0.0);
    let guide = Guide { source: image(160, 160, 1.0), target: image(224, 224, 2.0), weight: None };
    let input = Input::guided(style, vec![guide]);
    let mut params = Params::default();
    params.patch_size = 3;
    c.bench_function("stylize 224x224 patch 3", |b| {
        b.iter(|| synthesize(&input, &params, &mut NoProgress).expect("valid input"))
    });
}

criterion_group! { name = benches; config = Criterion::default().sample_size(10); targets = bench }
criterion_main!(benches);
