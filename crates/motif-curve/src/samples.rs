//! Generated exemplars for benchmarks and profiling: a chain strip with alpha whose colours can be
//! jittered, so that the dynamic program can be timed with and without exactly repeating columns.

use motif_core::RgbaImage;

/// A `width × height` strip of elliptical rings, one every `period` pixels and `chain_height`
/// pixels tall, on a transparent background. `noise > 0` adds a fixed per-pixel colour jitter of
/// ±`noise` to visible pixels (the same bytes on every run).
pub fn chain(width: usize, height: usize, period: f64, chain_height: f64, noise: i32) -> RgbaImage {
    let cy = height as f64 / 2.0;
    let (rx, ry) = (period * 0.36, chain_height / 2.0 - 1.0);
    let thickness = (chain_height * 0.16).max(2.0);
    RgbaImage::from_fn(width, height, |x, y| {
        let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
        let (dx, dy) = (px.rem_euclid(period) - period * 0.5, py - cy);
        let e = ((dx / rx).powi(2) + (dy / ry).powi(2)).sqrt();
        let g = (dx / (rx * rx)).hypot(dy / (ry * ry)) / e.max(1e-9);
        let ring = (thickness / 2.0 + 0.5 - (e - 1.0).abs() / g.max(1e-9)).clamp(0.0, 1.0);
        let a = (ring * 255.0).round() as u8;
        // A fixed hash of the pixel, so runs are repeatable.
        let hash = (x as u32).wrapping_mul(0x9e37_79b1) ^ (y as u32).wrapping_mul(0x85eb_ca6b);
        let jitter = |shift: u32, value: u8| {
            let offset = ((hash.rotate_left(shift) >> 8) % (2 * noise as u32 + 1)) as i32 - noise;
            (i32::from(value) + offset).clamp(0, 255) as u8
        };
        if a == 0 { [0; 4] } else { [jitter(0, 235), jitter(11, 185), jitter(22, (60.0 + 40.0 * dy / ry) as u8), a] }
    })
}
