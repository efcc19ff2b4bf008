//! Decoded images chosen for the engine: style, guide and mask channels, as every front end
//! passes them.

use motif_core::{ByteImage, RgbaImage};

use super::GuidePair;

/// Channels of a decoded guide image: 4 with any transparency, else 1 when grey, else 3.
fn guide_channel_count(image: &RgbaImage) -> usize {
    if !image.is_fully_opaque() {
        4
    } else if image.pixels().iter().all(|p| p[0] == p[1] && p[1] == p[2]) {
        1
    } else {
        3
    }
}

fn channel_list(channels: usize) -> Vec<usize> {
    match channels {
        1 => vec![0],
        3 => vec![0, 1, 2],
        _ => vec![0, 1, 2, 3],
    }
}

/// A style (or texture exemplar) as the engine takes it: RGB when fully opaque, else RGBA.
pub fn style_image_channels(image: &RgbaImage) -> ByteImage {
    let channels = if image.is_fully_opaque() { 3 } else { 4 };
    ByteImage::from_rgba_channels(image, &channel_list(channels))
}

/// A guide on its own (presynth's segment guide): grey, RGB or RGBA as its pixels are.
pub fn guide_image_channels(image: &RgbaImage) -> ByteImage {
    ByteImage::from_rgba_channels(image, &channel_list(guide_channel_count(image)))
}

/// A source and target guide pair with matching channels: equal counts stay; a grey image next
/// to an RGB one is read as RGB (grey is a special RGB); transparency on one side only is a
/// mismatch the engine reports.
pub fn guide_pair(source: &RgbaImage, target: &RgbaImage) -> GuidePair {
    let (a, b) = match (guide_channel_count(source), guide_channel_count(target)) {
        (1, 3) | (3, 1) => (3, 3),
        pair => pair,
    };
    (ByteImage::from_rgba_channels(source, &channel_list(a)), ByteImage::from_rgba_channels(target, &channel_list(b)))
}

/// A mask image read as a hole: pixels at least half white and half opaque are synthesized
/// (white: synthesize, black or transparent: keep).
pub fn hole_of(mask: &RgbaImage) -> Vec<bool> {
    mask.pixels()
        .iter()
        .map(|&[r, g, b, a]| {
            let luma = 0.299 * f32::from(r) + 0.587 * f32::from(g) + 0.114 * f32::from(b);
            luma >= 127.5 && a >= 128
        })
        .collect()
}

/// The image kept outside a mask, with `channels` channels (the style's: 3 or 4; 1 for grey).
pub fn kept_image(image: &RgbaImage, channels: usize) -> ByteImage {
    ByteImage::from_rgba_channels(image, &channel_list(channels))
}
