//! Generated exemplars for demos, benchmarks and profiling: a chain strip with alpha whose colours
//! can be jittered, so that the dynamic program can be timed with and without exactly repeating
//! columns, and a shaded gold chain of oval and edge-on links.

use motif_core::RgbaImage;
use motif_core::math;

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
        let g = math::hypot(dx / (rx * rx), dy / (ry * ry)) / e.max(1e-9);
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

/// A procedural gold chain: face-on oval links alternating with edge-on links (thick bars), with
/// anti-aliased alpha and simple shading, `period` pixels per link pair, in a strip whose rows
/// above and below the chain are transparent.
pub fn gold_chain(width: usize, height: usize, period: f64, chain_height: f64) -> RgbaImage {
    let cy = height as f64 / 2.0;
    let ring_rx = period * 0.36;
    let ring_ry = chain_height / 2.0 - 1.0;
    let thickness = (chain_height * 0.16).max(2.0);
    RgbaImage::from_fn(width, height, |x, y| {
        let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
        let phase = px.rem_euclid(period);
        // Face-on oval link centred at period / 2 + jitter-free; edge-on link around 0 / period.
        let dx = phase - period * 0.5;
        let dy = py - cy;
        // Distance to the ellipse, to first order: (e − 1) / |∇e|.
        let ellipse = ((dx / ring_rx).powi(2) + (dy / ring_ry).powi(2)).sqrt();
        let gradient = math::hypot(dx / (ring_rx * ring_rx), dy / (ring_ry * ring_ry)) / ellipse.max(1e-9);
        let ring_distance = (ellipse - 1.0).abs() / gradient.max(1e-9);
        let ring = (thickness / 2.0 + 0.5 - ring_distance).clamp(0.0, 1.0);
        let edge_dx = if phase < period * 0.5 { phase } else { period - phase };
        let bar_half_length = period * 0.3;
        let bar_distance = math::hypot((edge_dx - bar_half_length).max(0.0), (dy.abs() - thickness * 0.45).max(0.0));
        let bar = (1.0 - bar_distance).clamp(0.0, 1.0) * if dy.abs() < thickness { 1.0 } else { 0.0 };
        let coverage = ring.max(bar);
        if coverage <= 0.0 {
            return [0, 0, 0, 0];
        }
        let light = 0.75 + 0.25 * (-dy / ring_ry).clamp(-1.0, 1.0);
        let shade = |c: f64| (c * light).clamp(0.0, 255.0) as u8;
        if bar >= ring {
            [shade(170.0), shade(120.0), shade(30.0), (coverage * 255.0).round() as u8]
        } else {
            [shade(235.0), shade(185.0), shade(60.0), (coverage * 255.0).round() as u8]
        }
    })
}
