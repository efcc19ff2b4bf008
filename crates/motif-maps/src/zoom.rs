//! How well zooming in keeps a tile's look: its four tiles at the next zoom level, seen from as
//! far as the tile itself, against the tile.

use motif_core::RgbaImage;

/// The mean absolute difference (RGB, in `[0, 1]`) between `parent` and `children`, its four
/// tiles at the next zoom level joined into one image twice its side, reduced to the parent's
/// size by averaging each 2 × 2 block; with `coarser` > 0, both are then halved that many times
/// more, so that only the layout counts, not the textures' finest detail (which a closer level
/// draws at the same pixel scale, so it averages out at the parent's). Low when zooming in keeps
/// where things are; a closer level unrelated to its parent gives about the textures' own
/// contrast at that scale. Images of other sizes, or halved to nothing, give `NaN`.
pub fn zoom_error(parent: &RgbaImage, children: &RgbaImage, coarser: u32) -> f64 {
    let (width, height) = (parent.width(), parent.height());
    if (children.width(), children.height()) != (2 * width, 2 * height) {
        return f64::NAN;
    }
    let (mut parent, mut children) = (parent.clone(), halved(children));
    for _ in 0..coarser {
        (parent, children) = (halved(&parent), halved(&children));
    }
    let (width, height) = (parent.width(), parent.height());
    if width == 0 || height == 0 {
        return f64::NAN;
    }
    let mut total = 0.0;
    for y in 0..height {
        for x in 0..width {
            let (a, b) = (parent.get(x, y), children.get(x, y));
            total += (0..3).map(|c| f64::from(a[c].abs_diff(b[c]))).sum::<f64>() / 255.0;
        }
    }
    total / (3 * width * height) as f64
}

/// `image` at half its size (rounded down), each pixel the mean of a 2 × 2 block (rounded): a
/// tile's four children seen from as far as the tile.
pub fn halved(image: &RgbaImage) -> RgbaImage {
    RgbaImage::from_fn(image.width() / 2, image.height() / 2, |x, y| {
        let block = [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(dx, dy)| image.get(2 * x + dx, 2 * y + dy));
        std::array::from_fn(|c| ((block.iter().map(|p| u32::from(p[c])).sum::<u32>() + 2) / 4) as u8)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_magnified_parent_has_no_error_and_others_do() {
        let parent = RgbaImage::from_fn(4, 4, |x, y| [(x * 60) as u8, (y * 60) as u8, 0, 255]);
        let magnified = RgbaImage::from_fn(8, 8, |x, y| parent.get(x / 2, y / 2));
        assert_eq!(zoom_error(&parent, &magnified, 0), 0.0);
        assert_eq!(zoom_error(&parent, &magnified, 1), 0.0);
        let flipped = RgbaImage::from_fn(8, 8, |x, y| parent.get(3 - x / 2, y / 2));
        assert!(zoom_error(&parent, &flipped, 0) > 0.1);
        assert!(zoom_error(&parent, &flipped, 1) > 0.05);
        assert!(zoom_error(&parent, &parent, 0).is_nan());
        assert!(zoom_error(&parent, &magnified, 3).is_nan());
    }
}
