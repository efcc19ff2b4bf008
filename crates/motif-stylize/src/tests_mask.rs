//! Masks and inpainting: pixels outside the hole are kept exactly, the hole is filled from
//! outside it only, bad masks are refused.

use motif_core::{FloatImage, NoProgress};

use crate::InputError;
use crate::tests::texture;
use crate::{Error, Input, Mask, Params, synthesize};

/// A `width × height` hole mask: the rectangle `[x0, x1) × [y0, y1)`.
fn rectangle(width: usize, height: usize, (x0, y0, x1, y1): (usize, usize, usize, usize)) -> Vec<bool> {
    (0..width * height).map(|i| (x0..x1).contains(&(i % width)) && (y0..y1).contains(&(i / width))).collect()
}

/// `image` with the hole painted pure red: what a fill must not copy.
fn painted(image: &FloatImage, hole: &[bool]) -> FloatImage {
    let mut out = image.clone();
    for (i, inside) in hole.iter().enumerate() {
        if *inside {
            out.pixel_mut(i % image.width(), i / image.width()).copy_from_slice(&[1.0, 0.0, 0.0]);
        }
    }
    out
}

#[test]
fn inpainting_fills_only_the_hole_and_only_from_outside_it() {
    let (width, height) = (64, 56);
    let original = texture(width, height, 3, 21);
    let hole = rectangle(width, height, (22, 18, 42, 36));
    let image = painted(&original, &hole);
    let params = Params::default().with_seed(4);
    let output = synthesize(&Input::inpaint(image.clone(), hole.clone()), &params, &mut NoProgress).unwrap();
    for (i, inside) in hole.iter().enumerate() {
        let (x, y) = (i % width, i / width);
        let (out, kept) = (output.image.pixel(x, y), image.pixel(x, y));
        if *inside {
            // Nothing of the red paint: every filled pixel is at least 0.3 from pure red.
            let from_red = (out[0] - 1.0).powi(2) + out[1].powi(2) + out[2].powi(2);
            assert!(from_red > 0.09, "pixel ({x}, {y}) = {out:?} copies the paint");
        } else {
            assert_eq!(out, kept, "pixel ({x}, {y}) outside the hole changed");
        }
    }
    // Every searched patch's source lies wholly outside the hole.
    let radius = output.field.patch_size / 2;
    for source in output.field.matches.iter().flatten() {
        let [sx, sy] = source.map(|v| v as usize);
        for y in sy - radius..=sy + radius {
            for x in sx - radius..=sx + radius {
                assert!(!hole[y * width + x], "source patch at ({sx}, {sy}) overlaps the hole");
            }
        }
    }
    // The fill looks like the texture around it: its mean is within 0.03 of the original's there.
    let mean = |image: &FloatImage| -> f32 {
        let values: Vec<f32> =
            (0..width * height).filter(|&i| hole[i]).flat_map(|i| image.pixel(i % width, i / width).to_vec()).collect();
        values.iter().sum::<f32>() / values.len() as f32
    };
    assert!((mean(&output.image) - mean(&original)).abs() < 0.03, "{} vs {}", mean(&output.image), mean(&original));
}

#[test]
fn a_masked_texture_keeps_every_pixel_outside_the_mask() {
    let exemplar = texture(40, 40, 3, 7);
    let keep = texture(72, 48, 3, 8);
    let hole = rectangle(72, 48, (10, 5, 50, 30));
    let input = Input {
        mask: Some(Mask { keep: keep.clone(), hole: hole.clone(), exclude_hole_from_style: false }),
        ..Input::texture(exemplar, 72, 48)
    };
    let output = synthesize(&input, &Params::default().with_seed(2), &mut NoProgress).unwrap();
    let mut changed = 0;
    for (i, inside) in hole.iter().enumerate() {
        let (x, y) = (i % 72, i / 72);
        if *inside {
            changed += usize::from(output.image.pixel(x, y) != keep.pixel(x, y));
        } else {
            assert_eq!(output.image.pixel(x, y), keep.pixel(x, y), "pixel ({x}, {y}) outside the mask changed");
        }
    }
    assert!(changed > 900, "only {changed} of 1000 masked pixels were synthesized");
    assert!(output.report.searched_pixels < 72 * 48, "patches away from the mask need no search");
}

#[test]
fn bad_masks_are_refused() {
    let image = texture(32, 32, 3, 3);
    let params = Params::default();
    let refuse =
        |hole: Vec<bool>| synthesize(&Input::inpaint(image.clone(), hole), &params, &mut NoProgress).unwrap_err();
    assert!(matches!(refuse(vec![false; 32 * 32]), Error::Input(InputError::MaskCoverage("no pixel"))));
    assert!(matches!(refuse(vec![true; 32 * 32]), Error::Input(InputError::MaskCoverage("every pixel"))));
    assert!(matches!(refuse(vec![true; 31 * 32]), Error::Input(InputError::MaskPixels { pixels: 992, .. })));
    // A hole that leaves no whole patch outside it.
    let error = refuse(rectangle(32, 32, (3, 3, 29, 29)));
    assert!(matches!(error, Error::Input(InputError::NoSourceOutsideHole { .. })), "{error}");
    let grey = Input {
        mask: Some(Mask {
            keep: texture(32, 32, 1, 1),
            hole: rectangle(32, 32, (4, 4, 8, 8)),
            exclude_hole_from_style: false,
        }),
        ..Input::texture(image.clone(), 32, 32)
    };
    let error = synthesize(&grey, &params, &mut NoProgress).unwrap_err();
    assert!(matches!(error, Error::Input(InputError::MaskChannels { kept: 1, style: 3 })), "{error}");
    assert!(error.to_string().contains("1 channels but the style has 3"));
}
