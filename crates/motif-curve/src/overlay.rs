//! The debug overlay: the result with the ribbon, the piece borders, the forbidden areas and the
//! cost of every seam as a heat colour drawn on top.

use motif_core::vector;
use motif_core::{Point, RgbaImage};

use crate::Output;

/// Heat colour for `t ∈ [0, 1]`: green (cheap) → yellow → red (expensive).
pub(crate) fn heat(t: f64) -> [u8; 3] {
    let t = t.clamp(0.0, 1.0);
    if t < 0.5 { [(510.0 * t) as u8, 200, 40] } else { [255, (200.0 * (2.0 - 2.0 * t)) as u8, 40] }
}

/// Blends `colour` with coverage `amount` over `pixel` (straight alpha, "over").
fn blend(pixel: &mut [u8; 4], colour: [u8; 3], amount: f64) {
    let src_alpha = amount.clamp(0.0, 1.0);
    let dst_alpha = f64::from(pixel[3]) / 255.0;
    let out_alpha = src_alpha + dst_alpha * (1.0 - src_alpha);
    if out_alpha <= 0.0 {
        return;
    }
    for c in 0..3 {
        let value =
            (f64::from(colour[c]) * src_alpha + f64::from(pixel[c]) * dst_alpha * (1.0 - src_alpha)) / out_alpha;
        pixel[c] = value.round().clamp(0.0, 255.0) as u8;
    }
    pixel[3] = (out_alpha * 255.0).round() as u8;
}

/// Draws an anti-aliased segment of `thickness` pixels.
fn draw_line(image: &mut RgbaImage, a: Point, b: Point, thickness: f64, colour: [u8; 3], opacity: f64) {
    let half = thickness / 2.0;
    let x0 = (a.x.min(b.x) - half - 1.0).floor().max(0.0) as usize;
    let y0 = (a.y.min(b.y) - half - 1.0).floor().max(0.0) as usize;
    let x1 = ((a.x.max(b.x) + half + 1.0).ceil().max(0.0) as usize).min(image.width());
    let y1 = ((a.y.max(b.y) + half + 1.0).ceil().max(0.0) as usize).min(image.height());
    let direction = b - a;
    let length_sq = direction.hypot2();
    for y in y0..y1 {
        for x in x0..x1 {
            let p = Point::new(x as f64 + 0.5, y as f64 + 0.5);
            let t = if length_sq > 0.0 { ((p - a).dot(direction) / length_sq).clamp(0.0, 1.0) } else { 0.0 };
            let distance = vector::distance(p, a + direction * t);
            let coverage = (half + 0.5 - distance).clamp(0.0, 1.0);
            if coverage > 0.0 {
                let mut pixel = image.get(x, y);
                blend(&mut pixel, colour, coverage * opacity);
                image.set(x, y, pixel);
            }
        }
    }
}

/// The result of `output` with the debug drawing on top: forbidden pixels in translucent red
/// (dark red for fold-overs), the ribbon borders in blue, piece borders in grey and each seam in
/// its heat colour (green = cheapest seam, red = most expensive).
pub fn debug_overlay(output: &Output) -> RgbaImage {
    let mut image = output.image.clone();
    let mask = &output.forbidden;
    for y in 0..mask.height.min(image.height()) {
        for x in 0..mask.width.min(image.width()) {
            let flag = mask.flags[y * mask.width + x];
            if flag != 0 {
                let colour = if flag & crate::avoidance::FROM_MAP != 0 { [230, 40, 40] } else { [150, 0, 60] };
                let mut pixel = image.get(x, y);
                blend(&mut pixel, colour, 0.35);
                image.set(x, y, pixel);
            }
        }
    }
    for border in [&output.ribbon_top, &output.ribbon_bottom] {
        for pair in border.windows(2) {
            draw_line(&mut image, pair[0], pair[1], 1.5, [40, 90, 230], 0.9);
        }
    }
    let max_cost = output.pieces.iter().map(|piece| piece.seam_cost).fold(0.0, f64::max);
    for piece in &output.pieces {
        let [tl, bl, br, tr] = piece.quad.map(|[x, y]| Point::new(x, y));
        draw_line(&mut image, tl, tr, 1.0, [128, 128, 128], 0.6);
        draw_line(&mut image, bl, br, 1.0, [128, 128, 128], 0.6);
        draw_line(&mut image, tl, bl, 1.0, [128, 128, 128], 0.6);
        if piece.has_seam {
            let t = if max_cost > 0.0 { piece.seam_cost / max_cost } else { 0.0 };
            draw_line(&mut image, tr, br, 2.5, heat(t), 0.95);
        }
    }
    image
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heat_runs_from_green_to_red_and_lines_cover_pixels() {
        assert_eq!(heat(0.0), [0, 200, 40]);
        assert_eq!(heat(1.0), [255, 0, 40]);
        let mut image = RgbaImage::new(10, 10);
        draw_line(&mut image, Point::new(1.0, 5.0), Point::new(9.0, 5.0), 2.0, [255, 0, 0], 1.0);
        assert_eq!(image.get(5, 4), [255, 0, 0, 255]);
        assert_eq!(image.get(5, 0)[3], 0);
    }
}
