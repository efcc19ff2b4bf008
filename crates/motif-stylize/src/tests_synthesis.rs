//! Properties of whole runs: EM energy decrease, determinism, identity, uniformity, segments,
//! band mode, tileable textures, field re-application, bad input.

use motif_core::random::Rng;
use motif_core::{ByteImage, FloatImage, NoProgress, SeedStreams};

use crate::occurrence::Occurrence;
use crate::search::{Field, patchmatch_tiles};
use crate::tests::{flat, psnr, small_level, texture};
use crate::*;
use crate::{InputError, LimitError};

fn guided_input(size: usize) -> Input {
    let style = texture(size, size, 3, 21);
    let source = flat(size, size, |x, y| if (x / 8 + y / 8) % 2 == 0 { [0.2, 0.2, 0.2] } else { [0.8, 0.8, 0.8] });
    let target = flat(size + 7, size - 5, |x, y| if (x + y) / 12 % 2 == 0 { [0.2, 0.2, 0.2] } else { [0.8, 0.8, 0.8] });
    Input::guided(style, vec![Guide { source, target, weight: None }])
}

#[test]
fn em_energy_decreases_within_each_level() {
    let output = synthesize(&guided_input(48), &Params::default(), &mut NoProgress).unwrap();
    assert!(output.report.levels.len() >= 2);
    for level in &output.report.levels {
        let (first, last) = (level.energies[0], *level.energies.last().unwrap());
        assert!(last < first, "{}: {:?}", level.name, level.energies);
    }
    assert_eq!((output.image.width(), output.image.height()), (55, 43));
    assert!(
        output.report.energy.total > 0.0 && output.report.energy.guide > 0.0 && output.report.energy.occurrence > 0.0
    );
    let parts = output.report.energy.style + output.report.energy.guide + output.report.energy.occurrence;
    assert!((parts - output.report.energy.total).abs() < 1e-6 * output.report.energy.total);
}

#[test]
fn same_seed_same_bytes_on_one_and_two_threads() {
    let input = guided_input(40);
    let params = Params { seed: 77, extra_pass_3x3: true, ..Default::default() };
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| synthesize(&input, &params, &mut NoProgress).unwrap())
    };
    let (one, two) = (run(1), run(2));
    let bits = |o: &Output| o.image.data().iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&one), bits(&two));
    assert_eq!(one.field, two.field);
    let mut other = params.clone();
    other.seed = 78;
    let three = synthesize(&input, &other, &mut NoProgress).unwrap();
    assert_ne!(bits(&one), bits(&three));
}

/// The texture paths of issue 16 (8-bit exemplar, quilted start, structure guidance) give the
/// same bytes on one and two threads.
#[test]
fn texture_paths_give_the_same_bytes_on_one_and_two_threads() {
    let exemplar = ByteImage::from_float(&texture(40, 36, 3, 5));
    let input = Input::texture(exemplar, 64, 56);
    for params in [
        Params::default().with_seed(4).with_quilt_block(16),
        Params::default().with_seed(4).with_structure_weight(3.0).with_coarse_patch_size(7),
    ] {
        let run = |threads| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| synthesize(&input, &params, &mut NoProgress).unwrap())
        };
        let (one, two) = (run(1), run(2));
        assert_eq!(one.image, two.image);
        assert_eq!(one.field, two.field);
    }
}

#[test]
fn identity_guides_reproduce_the_style() {
    let style = texture(48, 48, 3, 31);
    let guide = style.clone();
    let input = Input::guided(style.clone(), vec![Guide { source: guide.clone(), target: guide, weight: None }]);
    let output = synthesize(&input, &Params::default(), &mut NoProgress).unwrap();
    let value = psnr(&output.image, &style);
    assert!(value > 30.0, "PSNR {value}");
}

#[test]
fn uniformity_raises_coverage_and_prevents_wash_out() {
    // Two regions: the target is mostly the dark region, the source half and half.
    let size = 40;
    let style = texture(size, size, 3, 41);
    let source = flat(size, size, |x, _| if x < size / 2 { [0.0; 3] } else { [1.0; 3] });
    let target = flat(size, size, |x, _| if x < 3 * size / 4 { [0.0; 3] } else { [1.0; 3] });
    let input = Input::guided(style.clone(), vec![Guide { source, target, weight: Some(4.0) }]);
    let mut params = Params { uniformity: 0.0, ..Default::default() };
    let off = synthesize(&input, &params, &mut NoProgress).unwrap();
    params.uniformity = 3500.0;
    let on = synthesize(&input, &params, &mut NoProgress).unwrap();
    assert!(
        on.report.source_coverage > off.report.source_coverage + 0.05,
        "{} vs {}",
        on.report.source_coverage,
        off.report.source_coverage
    );
    // The dark region keeps the style's contrast instead of flattening out.
    let spread = |image: &FloatImage, x1: usize| {
        let values: Vec<f32> =
            (4..size - 4).flat_map(|y| (4..x1).map(move |x| (x, y))).map(|(x, y)| image.pixel(x, y)[0]).collect();
        let mean = values.iter().sum::<f32>() / values.len() as f32;
        values.iter().map(|v| (v - mean).powi(2)).sum::<f32>() / values.len() as f32
    };
    assert!(spread(&on.image, 3 * size / 4 - 4) > 0.5 * spread(&style, size / 2 - 4));
}

pub(crate) fn two_segment_case() -> Input {
    let size = 48;
    let red = texture(size, size, 3, 51);
    // Style: reddish on the left segment, bluish on the right (separable colours).
    let style = FloatImage::from_data(
        size,
        size,
        3,
        (0..size * size)
            .flat_map(|i| {
                let v = red.pixel(i % size, i / size)[0] * 0.4;
                if i % size < size / 2 { [0.6 + v, 0.1, 0.1] } else { [0.1, 0.1, 0.6 + v] }
            })
            .collect(),
    )
    .unwrap();
    let source = flat(size, size, |x, _| if x < size / 2 { [1.0, 0.0, 0.0] } else { [0.0, 0.0, 1.0] });
    let target = flat(50, 44, |x, y| {
        if (x as f32 - 25.0).powi(2) + (y as f32 - 22.0).powi(2) < 225.0 { [0.0, 0.0, 1.0] } else { [1.0, 0.0, 0.0] }
    });
    Input::guided(style, vec![Guide { source, target, weight: None }])
}

#[test]
fn segments_never_match_across_separable_segments() {
    let input = two_segment_case();
    let params = Params { segments: Some(Segmentation::Palette), ..Default::default() };
    let output = synthesize(&input, &params, &mut NoProgress).unwrap();
    let target = &input.guides[0].target;
    let source = &input.guides[0].source;
    let r = params.patch_size / 2;
    for y in 0..44 {
        for x in 0..50 {
            let [sx, sy] = output.field.matches[y * 50 + x].unwrap();
            assert_eq!(target.pixel(x, y), source.pixel(sx as usize, sy as usize), "at {x},{y}");
            // Pixels whose whole patch neighbourhood is one segment carry only that segment's colours.
            let uniform = (y.saturating_sub(2 * r)..(y + 2 * r + 1).min(44)).all(|yy| {
                (x.saturating_sub(2 * r)..(x + 2 * r + 1).min(50)).all(|xx| target.pixel(xx, yy) == target.pixel(x, y))
            });
            if uniform {
                let blue = target.pixel(x, y)[2] > 0.5;
                let pixel = output.image.pixel(x, y);
                assert_eq!(pixel[2] > pixel[0], blue, "colour at {x},{y}: {pixel:?}");
            }
        }
    }
}

#[test]
fn band_mode_keeps_textures_outside_the_band() {
    let input = two_segment_case();
    let mut params = Params { segments: Some(Segmentation::Palette), ..Default::default() };
    let presynth = PresynthInput { style: input.style.clone(), guide: input.guides[0].source.clone(), size: (32, 32) };
    let textures = presynthesize(&presynth, &params, &mut NoProgress).unwrap();
    assert_eq!(textures.len(), 2);
    // Each texture draws only from its own segment's colours.
    for texture in &textures {
        let blue = texture.colour[2] > 0.5;
        assert!(texture.image.data().chunks_exact(3).all(|p| (p[2] > p[0]) == blue));
    }
    let mut banded = input.clone();
    banded.textures = Some(textures.clone().into());
    params.band = 0;
    let composed = synthesize(&banded, &params, &mut NoProgress).unwrap();
    assert!(composed.field.matches.iter().all(Option::is_none));
    assert_eq!(composed.report.searched_pixels, 0);
    params.band = 2;
    let output = synthesize(&banded, &params, &mut NoProgress).unwrap();
    let mask = band::band_mask(
        &label_guides(&input.guides[0].source, &input.guides[0].target, Segmentation::Palette, 0).unwrap().target,
        50,
        44,
        2,
    );
    let mut changed = 0;
    for (index, inside) in mask.iter().enumerate() {
        let (x, y) = (index % 50, index / 50);
        if *inside {
            changed += usize::from(output.image.pixel(x, y) != composed.image.pixel(x, y));
        } else {
            assert_eq!(output.image.pixel(x, y), composed.image.pixel(x, y));
        }
    }
    assert!(changed > 0);
    assert!(output.report.searched_pixels > 0 && output.report.searched_pixels < 50 * 44);
}

/// Segments with a cache: a target guide whose disc edge is anti-aliased (blends of the two
/// segment colours the cache does not hold, and a blue off the cache's) takes each pixel to the
/// nearest texture's colour instead of failing; a colour of its own is refused by name.
#[test]
fn quantized_segments_with_a_cache_accept_anti_aliased_guides() {
    let mut input = two_segment_case();
    let params = Params { segments: Some(Segmentation::KMeans(2)), band: 2, ..Default::default() };
    let presynth = PresynthInput { style: input.style.clone(), guide: input.guides[0].source.clone(), size: (32, 32) };
    let textures = presynthesize(&presynth, &params, &mut NoProgress).unwrap();
    assert_eq!(textures.len(), 2);
    // Coverage of the disc of radius 15 on a 4 × 4 grid inside each pixel: blends on its edge.
    input.guides[0].target = flat(50, 44, |x, y| {
        let inside = (0..16)
            .filter(|i| {
                let (dx, dy) = (x as f32 + 0.125 + 0.25 * (i % 4) as f32, y as f32 + 0.125 + 0.25 * (i / 4) as f32);
                (dx - 25.5).powi(2) + (dy - 22.5).powi(2) < 225.0
            })
            .count() as f32
            / 16.0;
        [1.0 - inside, 0.0, 0.9 * inside + 0.1 * (1.0 - inside)]
    });
    let blends = input.guides[0].target.data().chunks_exact(3).filter(|p| p[0] > 0.02 && p[0] < 0.98).count();
    assert!(blends > 20, "{blends} anti-aliased pixels");
    input.textures = Some(textures.into());
    let output = synthesize(&input, &params, &mut NoProgress).unwrap();
    // Far from the edge each pixel keeps its segment's colours.
    let (centre, corner) = (output.image.pixel(25, 22), output.image.pixel(2, 2));
    assert!(centre[2] > centre[0] && corner[0] > corner[2], "{centre:?} {corner:?}");
    // With a cache its colours are the segments whatever the mode: the palette gives the same.
    let palette = Params { segments: Some(Segmentation::Palette), ..params.clone() };
    assert_eq!(synthesize(&input, &palette, &mut NoProgress).unwrap().image, output.image);
    // A region of a colour far from both textures' and their blends is refused, naming it.
    input.guides[0].target = flat(50, 44, |x, y| if x < 8 && y < 8 { [0.0, 1.0, 0.0] } else { [1.0, 0.0, 0.0] });
    match synthesize(&input, &params, &mut NoProgress) {
        Err(error @ Error::Input(InputError::MissingTexture { .. })) => {
            let message = error.to_string();
            let named =
                message.contains("#00ff00 (64 pixels)") && message.contains("#ff0000") && message.contains("#0000ff");
            assert!(named, "{message}");
        }
        other => panic!("{other:?}"),
    }
}

/// The specialized kernels (row length fixed at compile time) give exactly the generic sums, and
/// so the very same PatchMatch field.
#[test]
fn specialized_kernels_equal_the_generic_one() {
    let mut stream = SeedStreams::new(3).stream("bytes", 0);
    let a: Vec<u8> = (0..70).map(|_| stream.random_range(0..=255)).collect();
    let b: Vec<u8> = (0..70).map(|_| stream.random_range(0..=255)).collect();
    assert_eq!(level::row_distance_n::<18>(&a, &b), level::row_distance(&a[..18], &b[..18]));
    assert_eq!(level::row_distance_n::<30>(&a, &b), level::row_distance(&a[..30], &b[..30]));
    assert_eq!(level::row_distance_n::<65>(&a, &b), level::row_distance(&a[..65], &b[..65]));
    assert_eq!(level::row_distance_n::<0>(&a[..9], &b[..9]), level::row_distance(&a[..9], &b[..9]));
    // 3×3 patches of 3 style + 4 guide channels: 21-byte rows, a specialized length.
    let (level, ..) = small_level(3);
    assert_eq!(level.patch * level.channels, 21);
    let occurrence = Occurrence::new(&level, 3500.0);
    let streams = SeedStreams::new(8);
    let mut generic = Field::random(&level, &streams);
    generic.recompute_costs(&level);
    let mut special = generic.clone();
    let previous = generic.matches.clone();
    patchmatch_tiles::<0>(&level, &mut generic, &previous, &occurrence, &streams, 0, None);
    patchmatch_tiles::<21>(&level, &mut special, &previous, &occurrence, &streams, 0, None);
    assert_eq!(generic.matches, special.matches);
    assert_eq!(generic.costs, special.costs);
    assert_ne!(generic.matches, previous, "the iteration must have moved some matches");
}

/// Band mode seeded from the textures' own fields (§3.7): outside the band the output is the
/// composition, the band starts at a lower energy than from a random start with the same work,
/// optimizing lowers it, and the bytes do not depend on the thread count.
#[test]
fn seeded_band_starts_lower_and_keeps_textures_outside() {
    let input = two_segment_case();
    let mut params = Params { segments: Some(Segmentation::Palette), band: 3, ..Default::default() };
    let presynth = PresynthInput { style: input.style.clone(), guide: input.guides[0].source.clone(), size: (32, 32) };
    let textures = presynthesize(&presynth, &params, &mut NoProgress).unwrap();
    assert!(textures.iter().all(|t| t.field.as_ref().is_some_and(|f| f.matches.iter().all(Option::is_some))));
    let mut seeded = input.clone();
    seeded.textures = Some(textures.clone().into());
    let mut unseeded = input.clone();
    unseeded.textures = Some(textures.iter().cloned().map(|t| SegmentTexture { field: None, ..t }).collect());
    let run = |input: &Input, params: &Params, threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| synthesize(input, params, &mut NoProgress).unwrap())
    };
    let with_seeds = run(&seeded, &params, 1);
    assert_eq!(with_seeds.image, run(&seeded, &params, 2).image);
    // The same work from a random start.
    let mut same_work = params.clone();
    same_work.search_vote_iterations = params.band_search_vote_iterations;
    same_work.patchmatch_iterations = params.band_patchmatch_iterations;
    let without = run(&unseeded, &same_work, 1);
    let (seeded_energies, random_energies) =
        (&with_seeds.report.levels[0].energies, &without.report.levels[0].energies);
    assert_eq!(seeded_energies.len(), params.band_search_vote_iterations);
    assert!(seeded_energies[0] < random_energies[0], "{seeded_energies:?} vs {random_energies:?}");
    assert!(seeded_energies.last().unwrap() < &seeded_energies[0], "{seeded_energies:?}");
    params.band = 0;
    let composed = run(&seeded, &params, 1).image;
    let labels = label_guides(&input.guides[0].source, &input.guides[0].target, Segmentation::Palette, 0).unwrap();
    let mask = band::band_mask(&labels.target, 50, 44, 3);
    for (index, inside) in mask.iter().enumerate() {
        if !inside {
            assert_eq!(with_seeds.image.pixel(index % 50, index / 50), composed.pixel(index % 50, index / 50));
        }
    }
}

/// The band's local search (`Params::band_local_search`) on two overlapping windows of one
/// plane (a guide of discs drawn in the plane's coordinates, each window with its own
/// `texture_origin`): where both see `band + 2 · patch` pixels around a pixel, they give it the
/// same bytes, and the band was optimized (it differs from the composition). Without the local
/// search the windows disagree in the band.
#[test]
fn local_band_search_gives_overlapping_windows_the_same_pixels() {
    let case = two_segment_case();
    let params = Params { segments: Some(Segmentation::Palette), band: 2, ..Default::default() }
        .with_band_search_vote_iterations(1)
        .with_band_patchmatch_iterations(1)
        .with_uniformity(0.0)
        .with_band_local_search(true);
    let presynth = PresynthInput { style: case.style.clone(), guide: case.guides[0].source.clone(), size: (32, 32) };
    let textures = presynthesize(&presynth, &params, &mut NoProgress).unwrap();
    let plane = |x: i64, y: i64| {
        let (dx, dy) = ((x.rem_euclid(30) - 15) as f32, (y.rem_euclid(26) - 13) as f32);
        if dx * dx + dy * dy < 64.0 { [0.0, 0.0, 1.0] } else { [1.0, 0.0, 0.0] }
    };
    let window = |origin: (i64, i64), params: &Params| {
        let target = flat(80, 64, |x, y| plane(x as i64 + origin.0, y as i64 + origin.1));
        let mut input = Input::guided(
            case.style.clone(),
            vec![Guide { source: case.guides[0].source.clone(), target, weight: None }],
        );
        input.textures = Some(textures.clone().into());
        input.texture_origin = origin;
        synthesize(&input, params, &mut NoProgress).unwrap().image
    };
    let (a_origin, b_origin) = ((-7, 3), (10, 12));
    let reach = (params.band + 2 * params.patch_size) as i64;
    let agreement = |params: &Params| {
        let (a, b) = (window(a_origin, params), window(b_origin, params));
        let (mut same, mut all) = (0, 0);
        for y in reach..64 - reach {
            for x in reach..80 - reach {
                let (u, v) = (x + b_origin.0 - a_origin.0, y + b_origin.1 - a_origin.1);
                if (reach..80 - reach).contains(&u) && (reach..64 - reach).contains(&v) {
                    all += 1;
                    same += usize::from(b.pixel(x as usize, y as usize) == a.pixel(u as usize, v as usize));
                }
            }
        }
        (same, all)
    };
    let (same, all) = agreement(&params);
    assert!(all > 1000, "{all} pixels overlap");
    assert_eq!(same, all, "the local search: {same} of {all} overlapping pixels agree");
    let composed = window(a_origin, &params.clone().with_band(0));
    assert_ne!(window(a_origin, &params), composed, "the band was optimized");
    let (same, all) = agreement(&params.clone().with_band_local_search(false));
    assert!(same < all, "PatchMatch's scan order and window-keyed draws: {same} of {all} agree");
    // Without the final figures (map tiles): the same bytes, and no field or error map.
    let bare = params.clone().with_final_figures(false);
    assert_eq!(window(a_origin, &bare), window(a_origin, &params));
    let target = flat(80, 64, |x, y| plane(x as i64, y as i64));
    let mut input =
        Input::guided(case.style.clone(), vec![Guide { source: case.guides[0].source.clone(), target, weight: None }]);
    input.textures = Some(textures.clone().into());
    let output = synthesize(&input, &bare, &mut NoProgress).unwrap();
    assert_eq!((output.field.matches.len(), output.error_map.width()), (0, 0));
    assert!(output.report.searched_pixels > 0 && !output.report.levels.is_empty());
}

#[test]
fn texture_fields_must_fit_their_texture_and_the_style() {
    let input = two_segment_case();
    let params = Params { segments: Some(Segmentation::Palette), ..Default::default() };
    let presynth = PresynthInput { style: input.style.clone(), guide: input.guides[0].source.clone(), size: (20, 20) };
    let textures = presynthesize(&presynth, &params, &mut NoProgress).unwrap();
    let mut wrong_size = textures.clone();
    wrong_size[0].field.as_mut().unwrap().width = 19;
    let mut wrong_source = textures.clone();
    wrong_source[1].field.as_mut().unwrap().source_width = 40;
    let mut outside = textures.clone();
    // Checked where the composition reads the field: every match of texture 1 is outside.
    outside[0].field.as_mut().unwrap().matches.fill(Some([u32::MAX, 7]));
    for bad in [wrong_size, wrong_source, outside] {
        let mut banded = input.clone();
        banded.textures = Some(bad.into());
        let error = synthesize(&banded, &params, &mut NoProgress).unwrap_err();
        assert!(
            matches!(
                error,
                Error::Input(InputError::TextureFieldSize { .. })
                    | Error::Input(InputError::TextureFieldSource { .. })
                    | Error::Input(InputError::TextureFieldOutside { .. })
            ),
            "{error}"
        );
    }
}

#[test]
fn tileable_textures_wrap_seamlessly() {
    let exemplar = texture(40, 40, 3, 61);
    let params = Params { tileable: true, ..Default::default() };
    let output = synthesize(&Input::texture(exemplar, 64, 48), &params, &mut NoProgress).unwrap();
    let image = &output.image;
    let column_gap = |a: usize, b: usize| -> f32 {
        (0..48)
            .map(|y| image.pixel(a, y).iter().zip(image.pixel(b, y)).map(|(p, q)| (p - q).powi(2)).sum::<f32>())
            .sum()
    };
    let interior: f32 = (1..63).map(|x| column_gap(x - 1, x)).sum::<f32>() / 62.0;
    assert!(column_gap(63, 0) < 2.0 * interior, "seam {} vs {interior}", column_gap(63, 0));
}

#[test]
fn extra_pass_and_field_reapplication() {
    let input = guided_input(40);
    let params = Params { extra_pass_3x3: true, ..Default::default() };
    let output = synthesize(&input, &params, &mut NoProgress).unwrap();
    let last = output.report.levels.last().unwrap();
    assert_eq!((last.patch_size, output.field.patch_size), (3, 3));
    assert_eq!(output.report.energy.occurrence, 0.0);
    let reapplied = apply_field(&output.field, &input.style).unwrap();
    assert!(psnr(&reapplied, &output.image) > 20.0);
}

#[test]
fn bad_input_gives_clear_errors() {
    let good = guided_input(32);
    let params = Params::default();
    let mut wrong_size = good.clone();
    wrong_size.guides[0].source = texture(31, 32, 3, 1);
    let message = synthesize(&wrong_size, &params, &mut NoProgress).unwrap_err().to_string();
    assert!(message.contains("source guide must have the style's size") && message.contains("31×32"), "{message}");
    let mut channels = good.clone();
    channels.guides[0].target = texture(39, 27, 1, 1);
    let message = synthesize(&channels, &params, &mut NoProgress).unwrap_err().to_string();
    assert!(message.contains("3 channels but the target guide has 1"), "{message}");
    for patch in [4, 1, 2] {
        let mut bad = params.clone();
        bad.patch_size = patch;
        let message = synthesize(&good, &bad, &mut NoProgress).unwrap_err().to_string();
        assert!(message.contains("patch-size") && message.contains("odd"), "{message}");
    }
    let mut empty = good.clone();
    empty.style = FloatImage::new(0, 0, 3);
    assert_eq!(
        synthesize(&empty, &params, &mut NoProgress).unwrap_err(),
        Error::Input(InputError::EmptyImage("style".into()))
    );
    let mut empty_target = good.clone();
    empty_target.guides[0].target = FloatImage::new(0, 5, 3);
    assert!(synthesize(&empty_target, &params, &mut NoProgress).unwrap_err().to_string().contains("empty"));
    let no_size = Input { size: None, ..Input::texture(texture(8, 8, 3, 1), 1, 1) };
    assert_eq!(
        synthesize(&no_size, &params, &mut NoProgress).unwrap_err(),
        Error::Input(InputError::MissingTargetSize)
    );
    let tiny = Input::texture(texture(4, 9, 3, 1), 10, 10);
    assert!(matches!(synthesize(&tiny, &params, &mut NoProgress), Err(Error::Input(InputError::StyleTooSmall { .. }))));
    let two_channels = Input::texture(FloatImage::new(8, 8, 2), 10, 10);
    assert!(synthesize(&two_channels, &params, &mut NoProgress).unwrap_err().to_string().contains("1, 3 or 4"));
}

#[test]
fn the_memory_limit_refuses_at_the_reported_estimate() {
    let input = guided_input(40);
    let output = synthesize(&input, &Params::default(), &mut NoProgress).unwrap();
    let estimate = output.report.estimated_memory_bytes;
    // At least the output image and its field.
    let pixels = (output.image.width() * output.image.height()) as u64;
    assert!(estimate >= pixels * (3 * 4 + 8), "{estimate}");
    // The guided input is small: a texture of 4096² passes a limit of 64 MiB.
    let texture = Input::texture(texture(32, 32, 3, 5), 4096, 4096);
    let error = synthesize(&texture, &Params::default().with_max_memory(64 << 20), &mut NoProgress).unwrap_err();
    assert!(
        matches!(error, Error::Limit(LimitError::Memory(_))) && error.to_string().contains("max-memory"),
        "{error}"
    );
    let error = Params::default().with_max_memory(0).validate().unwrap_err();
    assert!(error.to_string().contains("max-memory"), "{error}");
}

#[test]
fn coarse_patches_shrink_level_by_level_to_the_patch_size() {
    let input = Input::texture(texture(96, 96, 3, 4), 160, 160);
    let params = Params::default().with_coarse_patch_size(11).with_seed(2);
    let output = synthesize(&input, &params, &mut NoProgress).unwrap();
    let sides: Vec<usize> = output.report.levels.iter().map(|level| level.patch_size).collect();
    assert!(sides.len() >= 3, "{sides:?}");
    // Coarsest first: odd, at most 11, larger than 5 at some level and shrinking from there to
    // exactly 5 (the coarsest level may hold less than the schedule asks), and each fits its level.
    let largest = sides.iter().position(|&side| side == *sides.iter().max().unwrap()).unwrap();
    assert!(sides[largest..].windows(2).all(|pair| pair[0] >= pair[1]), "{sides:?}");
    assert!(sides.iter().all(|&side| side % 2 == 1 && side <= 11) && sides[largest] > 5, "{sides:?}");
    assert_eq!(*sides.last().unwrap(), 5, "{sides:?}");
    for level in &output.report.levels {
        assert!(2 * level.patch_size < level.width.min(level.height).min(96), "{level:?}");
    }
    // Off, or no larger than the patch size: 5 everywhere.
    let plain = synthesize(&input, &Params::default().with_seed(2), &mut NoProgress).unwrap();
    assert!(plain.report.levels.iter().all(|level| level.patch_size == 5));
    for bad in [4, 33] {
        let error = Params::default().with_coarse_patch_size(bad).validate().unwrap_err();
        assert!(error.to_string().contains("coarse-patch-size"), "{error}");
    }
}

/// An input with every image in 8-bit values: as [`ByteImage`]s and as their float conversion.
fn byte_and_float(input: &Input) -> (Input<ByteImage>, Input) {
    let bytes = |image: &FloatImage| ByteImage::from_float(image);
    let guides: Vec<Guide<ByteImage>> = input
        .guides
        .iter()
        .map(|g| Guide { source: bytes(&g.source), target: bytes(&g.target), weight: g.weight })
        .collect();
    let mut byte_input = Input::guided(bytes(&input.style), guides);
    byte_input.size = input.size;
    byte_input.mask = input.mask.as_ref().map(|m| Mask {
        keep: bytes(&m.keep),
        hole: m.hole.clone(),
        exclude_hole_from_style: m.exclude_hole_from_style,
    });
    let float_input = Input {
        style: byte_input.style.to_float(),
        guides: byte_input
            .guides
            .iter()
            .map(|g| Guide { source: g.source.to_float(), target: g.target.to_float(), weight: g.weight })
            .collect(),
        size: input.size,
        textures: None,
        texture_origin: input.texture_origin,
        prepared: None,
        mask: byte_input.mask.as_ref().map(|m| Mask {
            keep: m.keep.to_float(),
            hole: m.hole.clone(),
            exclude_hole_from_style: m.exclude_hole_from_style,
        }),
    };
    (byte_input, float_input)
}

/// 8-bit inputs read the values of their float conversion: their votes sum exactly in integers
/// where the float ones round (`crate::vote::ByteVotes`), a difference of the last float bit that
/// can change which of the equally good matches a run settles on, not how good they are; with
/// one pyramid level and over a pyramid (whose coarser 8-bit levels are rounded), guided
/// stylization and inpainting.
#[test]
fn byte_inputs_read_the_values_of_their_float_conversion() {
    let guided = guided_input(48);
    let style = texture(40, 36, 3, 31);
    let hole = (0..40 * 36).map(|i| (12..26).contains(&(i % 40)) && (10..22).contains(&(i / 40))).collect();
    let inpaint = Input::inpaint(style, hole);
    for input in [guided, inpaint] {
        let (byte_input, float_input) = byte_and_float(&input);
        for params in [Params::default().with_pyramid_levels(1).with_seed(3), Params::default().with_seed(3)] {
            let from_bytes = synthesize(&byte_input, &params, &mut NoProgress).unwrap();
            let from_floats = synthesize(&float_input, &params, &mut NoProgress).unwrap();
            let (bytes_energy, floats_energy) = (from_bytes.report.energy.total, from_floats.report.energy.total);
            assert!((bytes_energy / floats_energy - 1.0).abs() < 0.02, "energy {bytes_energy} against {floats_energy}");
        }
        let pyramid = Params::default().with_seed(3);
        let from_bytes = synthesize(&byte_input, &pyramid, &mut NoProgress).unwrap();
        assert!(from_bytes.report.levels.len() >= 2);
        // The re-applied field gives back the output from the 8-bit style too (inpainting keeps
        // pixels the field does not cover).
        if input.mask.is_none() {
            assert_eq!(apply_field(&from_bytes.field, &byte_input.style).unwrap(), from_bytes.image);
        }
    }
}
