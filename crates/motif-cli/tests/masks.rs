//! `motif inpaint`, and `--mask` with `--keep` on `motif texture` and `motif stylize`, end to end
//! on real textures (GIMP's patterns, data/real/stylize).

mod common;

use std::path::{Path, PathBuf};

use common::{error_of, motif, ok};
use motif_core::RgbaImage;

fn corpus(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/stylize").join(name)
}

/// A disc of radius `r` around `(cx, cy)`, white on black, as a mask image.
fn disc(width: usize, height: usize, (cx, cy, r): (f64, f64, f64)) -> RgbaImage {
    let mut mask = RgbaImage::new(width, height);
    for (i, pixel) in mask.pixels_mut().iter_mut().enumerate() {
        let (x, y) = ((i % width) as f64, (i / width) as f64);
        let inside = (x - cx).powi(2) + (y - cy).powi(2) < r * r;
        *pixel = if inside { [255, 255, 255, 255] } else { [0, 0, 0, 255] };
    }
    mask
}

fn is_hole(pixel: [u8; 4]) -> bool {
    pixel[0] > 127
}

#[test]
fn inpainting_real_textures_fills_only_the_hole_and_only_from_outside_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (name, hole) in
        [("stone33.png", (78.0, 70.0, 26.0)), ("walnut.png", (64.0, 60.0, 22.0)), ("bark.png", (41.0, 45.0, 16.0))]
    {
        let original = motif_io::read_image(&corpus(name)).unwrap();
        let (width, height) = (original.width(), original.height());
        let mask = disc(width, height, hole);
        // The hole painted pure red: what the fill must not copy.
        let mut image = original.clone();
        for (pixel, m) in image.pixels_mut().iter_mut().zip(mask.pixels()) {
            if is_hole(*m) {
                *pixel = [255, 0, 0, 255];
            }
        }
        motif_io::write_png(&d.join("image.png"), &image).unwrap();
        motif_io::write_png(&d.join("hole.png"), &mask).unwrap();
        ok(&motif(d, &["inpaint", "--image", "image.png", "--mask", "hole.png", "--out", "filled.png"]));
        let filled = motif_io::read_image(&d.join("filled.png")).unwrap();
        let (mut sum_filled, mut sum_original, mut count) = ([0.0; 3], [0.0; 3], 0.0);
        for ((out, kept), (m, truth)) in
            filled.pixels().iter().zip(image.pixels()).zip(mask.pixels().iter().zip(original.pixels()))
        {
            if is_hole(*m) {
                let from_red =
                    (255.0 - f64::from(out[0])).powi(2) + f64::from(out[1]).powi(2) + f64::from(out[2]).powi(2);
                assert!(from_red > 60.0 * 60.0, "{name}: a filled pixel {out:?} copies the red paint");
                for c in 0..3 {
                    sum_filled[c] += f64::from(out[c]);
                    sum_original[c] += f64::from(truth[c]);
                }
                count += 1.0;
            } else {
                assert_eq!(out, kept, "{name}: a pixel outside the hole changed");
            }
        }
        // The fill has the colour of what was there (the texture around it), within 20 levels.
        for c in 0..3 {
            let (a, b) = (sum_filled[c] / count, sum_original[c] / count);
            assert!((a - b).abs() < 20.0, "{name}: channel {c} of the fill averages {a:.1}, the original {b:.1}");
        }
    }
}

#[test]
fn masks_on_texture_and_stylize_keep_every_pixel_outside_them() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let keep = motif_io::read_image(&corpus("walnut.png")).unwrap();
    motif_io::write_png(&d.join("mask.png"), &disc(128, 128, (64.0, 64.0, 30.0))).unwrap();
    let bark = corpus("bark.png");
    let bark = bark.to_str().unwrap();
    let walnut = corpus("walnut.png");
    let walnut = walnut.to_str().unwrap();
    ok(&motif(
        d,
        &["texture", "--exemplar", bark, "--size", "128x128", "--mask", "mask.png", "--keep", walnut, "--out", "t.png"],
    ));
    ok(&motif(
        d,
        &[
            "stylize", "--style", bark, "--guide", bark, walnut, "--mask", "mask.png", "--keep", walnut, "--out",
            "s.png",
        ],
    ));
    let mask = motif_io::read_image(&d.join("mask.png")).unwrap();
    for out in ["t.png", "s.png"] {
        let output = motif_io::read_image(&d.join(out)).unwrap();
        let mut changed = 0;
        for ((pixel, kept), m) in output.pixels().iter().zip(keep.pixels()).zip(mask.pixels()) {
            if is_hole(*m) {
                changed += usize::from(pixel != kept);
            } else {
                assert_eq!(pixel, kept, "{out}: a pixel outside the mask changed");
            }
        }
        assert!(changed > 2000, "{out}: only {changed} of 2821 masked pixels were synthesized");
    }
}

#[test]
fn bad_masks_are_refused_with_the_files_named() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let walnut = corpus("walnut.png");
    let walnut = walnut.to_str().unwrap();
    motif_io::write_png(&d.join("small.png"), &disc(64, 64, (32.0, 32.0, 10.0))).unwrap();
    motif_io::write_png(&d.join("black.png"), &disc(128, 128, (0.0, 0.0, 0.0))).unwrap();
    motif_io::write_png(&d.join("white.png"), &disc(128, 128, (64.0, 64.0, 1000.0))).unwrap();
    std::fs::write(d.join("text.png"), "not an image").unwrap();
    let inpaint = |mask: &str| motif(d, &["inpaint", "--image", walnut, "--mask", mask, "--out", "never.png"]);
    let error = error_of(&inpaint("small.png"));
    assert!(error.contains("small.png") && error.contains("64×64") && error.contains("128×128"), "{error}");
    assert!(error_of(&inpaint("black.png")).contains("marks no pixel"));
    assert!(error_of(&inpaint("white.png")).contains("marks every pixel"));
    assert!(error_of(&inpaint("text.png")).contains("text.png"));
    let error = error_of(&motif(
        d,
        &["texture", "--exemplar", walnut, "--size", "128x128", "--mask", "small.png", "--out", "never.png"],
    ));
    assert!(error.contains("--keep"), "{error}");
    let error = error_of(&motif(d, &["inpaint", "--image", walnut, "--mask", "small.png", "--out", walnut]));
    assert!(error.contains("walnut.png"), "{error}");
    assert!(!d.join("never.png").exists());
}
