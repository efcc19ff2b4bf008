//! Segment guidance on real, anti-aliased guides (data/real/stylize, `segment_guides.py`): the
//! cat photo's segment map, painted with soft edges, and a target map from GIMP's stone wall
//! rendered at half size (and that map re-encoded as JPEG). `motif presynth --segment-count 3` then
//! `motif stylize --presynth` succeed, each target segment keeps its own texture, the same seed gives the same bytes, and a
//! target colour far from every texture's is refused by name.

mod common;

use std::path::{Path, PathBuf};

use common::{error_of, motif, ok};
use motif_core::FloatImage;

fn corpus(name: &str) -> String {
    let path: PathBuf = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/stylize").join(name);
    path.to_str().unwrap().to_string()
}

fn rgb(path: &str) -> FloatImage {
    motif_io::read_image(Path::new(path)).unwrap().to_float_channels(&[0, 1, 2])
}

/// The cache's segment colours, in its order, from `presynth.json`.
fn cache_colours(dir: &Path) -> Vec<[f32; 3]> {
    let text = std::fs::read_to_string(dir.join("presynth.json")).unwrap();
    let manifest: serde_json::Value = serde_json::from_str(&text).unwrap();
    let hex = |entry: &serde_json::Value| {
        let digits = entry["colour"].as_str().unwrap().trim_start_matches('#').to_string();
        [0, 2, 4].map(|i| f32::from(u8::from_str_radix(&digits[i..i + 2], 16).unwrap()) / 255.0)
    };
    manifest["segments"].as_array().unwrap().iter().map(hex).collect()
}

fn distance(a: &[f32], b: &[f32]) -> f32 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Mean colour of `image` over each segment of `guide` (pixels labelled by the nearest of
/// `colours`).
fn segment_means(image: &FloatImage, guide: &FloatImage, colours: &[[f32; 3]]) -> Vec<[f32; 3]> {
    let mut sums = vec![([0.0_f64; 3], 0usize); colours.len()];
    for (pixel, label) in image.data().chunks_exact(3).zip(guide.data().chunks_exact(3)) {
        let nearest =
            (0..colours.len()).min_by(|&a, &b| distance(label, &colours[a]).total_cmp(&distance(label, &colours[b])));
        let (sum, count) = &mut sums[nearest.unwrap()];
        for (s, v) in sum.iter_mut().zip(pixel) {
            *s += f64::from(*v);
        }
        *count += 1;
    }
    sums.iter().map(|(sum, count)| sum.map(|s| (s / *count as f64) as f32)).collect()
}

fn stylize(dir: &Path, target: &str, out: &str, extra: &[&str]) -> std::process::Output {
    let (style, source) = (corpus("chelsea.png"), corpus("chelsea_segments.png"));
    let mut args = vec!["stylize", "--style", &style, "--guide", &source, target, "--presynth", "cache", "--seed", "3"];
    args.extend(extra);
    args.extend(["--out", out, "--quiet"]);
    motif(dir, &args)
}

#[test]
fn presynth_and_stylize_on_anti_aliased_real_guides_keep_each_segments_texture() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (style, source, target) = (corpus("chelsea.png"), corpus("chelsea_segments.png"), corpus("stone_segments.png"));
    let presynth = ["presynth", "--style", &style, "--guide", &source, "--size", "48x48", "--seed", "3"];
    // The exact palette reads the soft edges' blends as segments of their own, too thin for a patch.
    let message = error_of(&motif(d, &[&presynth[..], &["--out-dir", "palette", "--quiet"]].concat()));
    assert!(message.contains("k-means") && !message.contains("panicked"), "{message}");
    ok(&motif(d, &[&presynth[..], &["--segment-count", "3", "--out-dir", "cache", "--quiet"]].concat()));
    let colours = cache_colours(&d.join("cache"));
    assert_eq!(colours.len(), 3);

    // With or without --segment-count, the target's blends take the nearest cache colour; so do
    // the target's JPEG artefacts (re-encoded at quality 70).
    let jpeg = d.join("stone.jpg");
    let decoded = image::open(&target).unwrap().to_rgb8();
    let mut file = std::fs::File::create(&jpeg).unwrap();
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut file, 70).encode_image(&decoded).unwrap();
    ok(&stylize(d, &target, "out.png", &["--segment-count", "3", "--threads", "1"]));
    ok(&stylize(d, &target, "palette.png", &[]));
    ok(&stylize(d, "stone.jpg", "jpeg.png", &["--segment-count", "3"]));
    let style_means = segment_means(&rgb(&style), &rgb(&source), &colours);
    for (out, guide) in [("out.png", target.clone()), ("jpeg.png", jpeg.to_str().unwrap().to_string())] {
        let output_means = segment_means(&rgb(d.join(out).to_str().unwrap()), &rgb(&guide), &colours);
        for (segment, mean) in output_means.iter().enumerate() {
            let nearest = (0..colours.len())
                .min_by(|&a, &b| distance(mean, &style_means[a]).total_cmp(&distance(mean, &style_means[b])))
                .unwrap();
            assert_eq!(nearest, segment, "{out}, segment {segment}: mean {mean:?}, style means {style_means:?}");
        }
    }

    // Same seed, same bytes (and for any thread count).
    ok(&stylize(d, &target, "again.png", &["--segment-count", "3", "--threads", "2"]));
    assert_eq!(std::fs::read(d.join("out.png")).unwrap(), std::fs::read(d.join("again.png")).unwrap());
}

#[test]
fn a_target_colour_far_from_every_texture_is_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (style, source) = (corpus("chelsea.png"), corpus("chelsea_segments.png"));
    let presynth = ["presynth", "--style", &style, "--guide", &source, "--size", "32x32", "--segment-count", "3"];
    ok(&motif(d, &[&presynth[..], &["--out-dir", "cache", "--quiet"]].concat()));
    // The real target with a green field painted into it: no texture is near green.
    let mut target = motif_io::read_image(Path::new(&corpus("stone_segments.png"))).unwrap();
    let width = target.width();
    for (index, pixel) in target.pixels_mut().iter_mut().enumerate() {
        if (10..30).contains(&(index % width)) && (10..30).contains(&(index / width)) {
            *pixel = [40, 200, 60, 255];
        }
    }
    motif_io::write_png(&d.join("green.png"), &target).unwrap();
    let output = stylize(d, "green.png", "out.png", &["--segment-count", "3"]);
    assert_eq!(output.status.code(), Some(1));
    let message = error_of(&output);
    assert!(message.contains("no texture for the target segment of colour #28c83c (400 pixels)"), "{message}");
    assert!(!d.join("out.png").exists());
}
