//! How visible the borders of tiles rendered apart are.

use motif_core::RgbaImage;

/// How much a tiled picture jumps at tile borders: the mean colour step (mean over red, green and
/// blue of the absolute difference) between neighbouring pixels across the borders every `tile`
/// pixels, divided by the mean step everywhere else; about 1 where no seam shows. The figure of
/// Python's `motif.batch.seam_error`, for pictures the Rust side holds.
pub fn seam_error(image: &RgbaImage, tile: usize) -> f64 {
    let (width, height) = (image.width(), image.height());
    let step = |a: [u8; 4], b: [u8; 4]| -> f64 { (0..3).map(|c| f64::from(a[c].abs_diff(b[c]))).sum::<f64>() / 3.0 };
    let (mut border, mut borders, mut inner, mut inners) = (0.0, 0usize, 0.0, 0usize);
    let mut add = |value: f64, at_border: bool| {
        if at_border {
            border += value;
            borders += 1;
        } else {
            inner += value;
            inners += 1;
        }
    };
    for y in 0..height {
        for x in 0..width.saturating_sub(1) {
            add(step(image.get(x, y), image.get(x + 1, y)), tile > 0 && (x + 1) % tile == 0);
        }
    }
    for y in 0..height.saturating_sub(1) {
        for x in 0..width {
            add(step(image.get(x, y), image.get(x, y + 1)), tile > 0 && (y + 1) % tile == 0);
        }
    }
    if borders == 0 || inner == 0.0 {
        return 1.0;
    }
    (border / borders as f64) / (inner / inners as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_jump_at_the_borders_shows_and_a_smooth_ramp_does_not() {
        let ramp = RgbaImage::from_fn(16, 16, |x, y| [(x * 4 + y * 4) as u8, 0, 0, 255]);
        assert!((seam_error(&ramp, 8) - 1.0).abs() < 1e-9);
        // Each 8 × 8 tile a flat colour of its own: every step is at a border.
        let blocks = RgbaImage::from_fn(16, 16, |x, y| [((x / 8) * 90 + (y / 8) * 40) as u8, 0, 0, 255]);
        assert_eq!(seam_error(&blocks, 8), 1.0);
        let noisy = RgbaImage::from_fn(16, 16, |x, y| [((x * 7 + y * 13) % 5) as u8 + ((x / 8) * 60) as u8, 0, 0, 255]);
        assert!(seam_error(&noisy, 8) > 5.0, "{}", seam_error(&noisy, 8));
    }
}
