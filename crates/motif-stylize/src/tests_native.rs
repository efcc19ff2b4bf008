//! Texture synthesis from exemplars much larger than the output ([`Params::local_search_above`]):
//! which levels refine upsampled matches, determinism over threads, and the memory they save.

use motif_core::NoProgress;

use crate::tests::texture;
use crate::{Input, Params, synthesize};

/// A 40 × 36 texture from a 150 × 140 exemplar (more than 4 times its pixels) with local search
/// above 2 000 exemplar pixels.
fn native_case() -> (Input, Params) {
    let input = Input::texture(texture(150, 140, 3, 41), 40, 36);
    (input, Params::default().with_seed(3).with_local_search_above(2_000))
}

/// The finer levels whose exemplar is large refine upsampled matches; the coarsest never does,
/// nor any level of a run whose exemplar is small or whose bound is the maximum.
#[test]
fn large_exemplars_refine_their_finer_levels_only() {
    let (input, params) = native_case();
    let output = synthesize(&input, &params, &mut NoProgress).unwrap();
    let local: Vec<bool> = output.report.levels.iter().map(|level| level.local_search).collect();
    assert_eq!(local.len(), 2, "{local:?}");
    assert_eq!(local, [false, true], "coarsest first");
    assert_eq!(output.report.energy.occurrence, 0.0, "no penalty on a local finest level");
    let whole = synthesize(&input, &params.clone().with_local_search_above(usize::MAX), &mut NoProgress).unwrap();
    assert!(whole.report.levels.iter().all(|level| !level.local_search));
    assert!(whole.report.energy.occurrence > 0.0);
    assert!(whole.report.estimated_memory_bytes > output.report.estimated_memory_bytes);
    let small = Input::texture(texture(60, 60, 3, 41), 40, 36);
    let output = synthesize(&small, &params, &mut NoProgress).unwrap();
    assert!(output.report.levels.iter().all(|level| !level.local_search), "exemplar under 4× the output");
    assert!(Params::default().with_local_search_above(0).validate().is_err());
}

/// Local refinement gives the same bytes on any number of threads.
#[test]
fn local_refinement_is_the_same_on_any_number_of_threads() {
    let (input, params) = native_case();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| synthesize(&input, &params, &mut NoProgress).unwrap())
    };
    let first = run(1);
    for threads in [2, 3] {
        let other = run(threads);
        assert_eq!(other.image, first.image, "{threads} threads");
        assert_eq!(other.field, first.field, "{threads} threads");
    }
}
