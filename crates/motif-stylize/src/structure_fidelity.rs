//! A fidelity figure that sees structure: for output patches of a large size (15 × 15 by default,
//! larger than the synthesis patches), the distance to the nearest patch of the exemplar. A
//! texture that keeps its exemplar's bricks and straight mortar lines is made of such patches; one
//! that breaks them into wavy strips is not, even when every 5 × 5 patch matches.

use motif_core::FloatImage;

/// Mean over `samples` output patches of side `patch` (on a regular grid) of the smallest mean
/// squared difference to an exemplar patch, in 8-bit units squared; `None` when either image is
/// smaller than a patch or their channels differ. Exhaustive over the exemplar's patches.
pub fn nearest_patch_distance(output: &FloatImage, exemplar: &FloatImage, patch: usize, samples: usize) -> Option<f64> {
    let channels = output.channels();
    if channels != exemplar.channels()
        || patch == 0
        || output.width() < patch
        || output.height() < patch
        || exemplar.width() < patch
        || exemplar.height() < patch
    {
        return None;
    }
    let per_side = (samples as f64).sqrt().ceil().max(1.0) as usize;
    let span = |size: usize, i: usize| (size - patch) * i / (per_side - 1).max(1);
    let row = patch * channels;
    let (ex_width, ex_height) = (exemplar.width(), exemplar.height());
    let (out_data, ex_data) = (output.data(), exemplar.data());
    let mut total = 0.0;
    let mut count = 0usize;
    for sy in 0..per_side {
        for sx in 0..per_side {
            let (ox, oy) = (span(output.width(), sx), span(output.height(), sy));
            let mut best = f64::INFINITY;
            for ey in 0..=ex_height - patch {
                for ex in 0..=ex_width - patch {
                    let mut sum = 0.0_f32;
                    for dy in 0..patch {
                        let a = ((oy + dy) * output.width() + ox) * channels;
                        let b = ((ey + dy) * ex_width + ex) * channels;
                        for (p, q) in out_data[a..a + row].iter().zip(&ex_data[b..b + row]) {
                            let d = p - q;
                            sum += d * d;
                        }
                        if f64::from(sum) >= best {
                            break;
                        }
                    }
                    best = best.min(f64::from(sum));
                }
            }
            total += best * 255.0 * 255.0 / (patch * patch * channels) as f64;
            count += 1;
        }
    }
    Some(total / count as f64)
}

/// Mean absolute difference between horizontally and vertically adjacent pixels, in 8-bit units:
/// the nearest-patch distance alone rewards a washed-out output (a blurred patch is near many
/// exemplar patches), so it is read next to this, as a ratio to the exemplar's.
pub fn sharpness(image: &FloatImage) -> f64 {
    let (width, height, channels) = (image.width(), image.height(), image.channels());
    let data = image.data();
    let (mut sum, mut count) = (0.0_f64, 0usize);
    for y in 0..height {
        for x in 0..width {
            let here = (y * width + x) * channels;
            for next in [(x + 1 < width).then(|| here + channels), (y + 1 < height).then(|| here + width * channels)]
                .into_iter()
                .flatten()
            {
                for c in 0..channels {
                    sum += f64::from((data[here + c] - data[next + c]).abs());
                }
                count += channels;
            }
        }
    }
    if count == 0 { 0.0 } else { 255.0 * sum / count as f64 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tests::texture;

    #[test]
    fn a_crop_of_the_exemplar_is_at_distance_zero_and_noise_is_far() {
        let exemplar = texture(40, 36, 3, 5);
        let mut crop = FloatImage::new(24, 20, 3);
        for y in 0..20 {
            for x in 0..24 {
                crop.pixel_mut(x, y).copy_from_slice(exemplar.pixel(x + 9, y + 7));
            }
        }
        assert_eq!(nearest_patch_distance(&crop, &exemplar, 15, 9), Some(0.0));
        let other = texture(24, 20, 3, 6);
        assert!(nearest_patch_distance(&other, &exemplar, 15, 9).unwrap() > 20.0);
        assert_eq!(nearest_patch_distance(&crop, &exemplar, 25, 9), None);
        // A box blur lowers the sharpness.
        let mut blurred = crop.clone();
        for y in 1..19 {
            for x in 1..23 {
                for c in 0..3 {
                    let mean = (0..9).map(|k| crop.pixel(x + k % 3 - 1, y + k / 3 - 1)[c]).sum::<f32>() / 9.0;
                    blurred.pixel_mut(x, y)[c] = mean;
                }
            }
        }
        assert!(sharpness(&blurred) < 0.8 * sharpness(&crop), "{} vs {}", sharpness(&blurred), sharpness(&crop));
    }
}
