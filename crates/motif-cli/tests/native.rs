//! Texture synthesis from exemplars much larger than the output (issue 34, item 5): the finer
//! levels refine the matches found on the reduced exemplar (`Params::local_search_above`). On a
//! real exemplar the refinement keeps the fidelity of a search of the whole exemplar at every
//! level, within a stated bound, and the same seed gives the same bytes on any number of threads.

use std::path::Path;

use motif_core::{ByteImage, FloatImage, NoProgress};
use motif_stylize::{Input, Params, synthesize};

/// GIMP's stone wall (156 × 156), 8-bit RGB as `motif texture` hands it to the engine.
fn stone() -> ByteImage {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/stylize/stone33.png");
    motif_jobs::stylize::style_image_channels(&motif_io::read_image(&path).unwrap())
}

/// A 48 × 48 texture (about a tenth of the exemplar's pixels) with local refinement above `above`
/// exemplar pixels: with 2 000 the two finer of its three levels refine.
fn grown(exemplar: &ByteImage, seed: u64, above: usize) -> motif_stylize::Output {
    let params = Params::default().with_seed(seed).with_local_search_above(above);
    synthesize(&Input::texture(exemplar.clone(), 48, 48), &params, &mut NoProgress).unwrap()
}

/// Over seeds 1–3: the mean nearest 15 × 15 patch distance of the refined textures within 1.25×
/// the whole search's, and their sharpness at least 0.9 of it (measured: 481 against 626,
/// sharpness 14.3 against 11.5: the refined run's penalty, measured as if the exemplar had the
/// output's pixels, keeps coherent copies that the whole search's breaks up).
#[test]
fn local_refinement_keeps_the_fidelity_of_a_whole_search_on_a_real_exemplar() {
    let exemplar = stone();
    let reference = exemplar.to_float();
    let distance = |image: &FloatImage| motif_stylize::nearest_patch_distance(image, &reference, 15, 100).unwrap();
    let (mut local, mut whole, mut sharp_local, mut sharp_whole) = (0.0, 0.0, 0.0, 0.0);
    for seed in 1..=3 {
        let refined = grown(&exemplar, seed, 2_000);
        assert!(refined.report.levels.iter().filter(|level| level.local_search).count() == 2);
        let searched = grown(&exemplar, seed, usize::MAX);
        assert!(searched.report.levels.iter().all(|level| !level.local_search));
        local += distance(&refined.image) / 3.0;
        whole += distance(&searched.image) / 3.0;
        sharp_local += motif_stylize::sharpness(&refined.image) / 3.0;
        sharp_whole += motif_stylize::sharpness(&searched.image) / 3.0;
    }
    assert!(local <= 1.25 * whole, "nearest 15×15 patch distance {local:.0} against {whole:.0}");
    assert!(sharp_local >= 0.9 * sharp_whole, "sharpness {sharp_local:.4} against {sharp_whole:.4}");
}

/// The same seed gives the same bytes on 1, 2 and 3 threads with local refinement.
#[test]
fn local_refinement_gives_the_same_bytes_on_any_number_of_threads() {
    let exemplar = stone();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| grown(&exemplar, 7, 2_000).image)
    };
    let first = run(1);
    assert_eq!(run(2), first);
    assert_eq!(run(3), first);
}
