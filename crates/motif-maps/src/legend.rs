//! The legend: what each class looks like in the stylized map, a real texture or a flat colour,
//! and the style exemplar (an atlas of the textures) with its segment guide.

use motif_core::{ByteImage, RgbaImage};

use crate::class::MapClass;

/// How one class is painted.
#[derive(Debug, Clone, PartialEq)]
pub enum Fill {
    /// A flat colour (a painted legend).
    Colour([u8; 3]),
    /// A texture (any size; it is tiled into its block of the atlas).
    Texture(RgbaImage),
}

/// What every class looks like, in [`MapClass::ALL`]'s order.
#[derive(Debug, Clone, PartialEq)]
pub struct Legend {
    fills: Vec<Fill>,
}

impl Default for Legend {
    fn default() -> Self {
        Self::plain()
    }
}

impl Legend {
    /// Every class in its segment-map colour ([`MapClass::colour`]).
    pub fn plain() -> Self {
        Self { fills: MapClass::ALL.iter().map(|class| Fill::Colour(class.colour())).collect() }
    }

    /// This legend with `class` painted as `fill`.
    #[must_use]
    pub fn with(mut self, class: MapClass, fill: Fill) -> Self {
        self.fills[class.index()] = fill;
        self
    }

    /// How `class` is painted.
    pub fn fill(&self, class: MapClass) -> &Fill {
        &self.fills[class.index()]
    }

    /// Side of the square block each class takes in the atlas: the largest texture side, at
    /// least `min_side`.
    fn block_side(&self, min_side: usize) -> usize {
        self.fills
            .iter()
            .map(|fill| match fill {
                Fill::Colour(_) => 0,
                Fill::Texture(image) => image.width().max(image.height()),
            })
            .max()
            .unwrap_or(0)
            .max(min_side)
    }

    /// The style exemplar and its segment guide: one square block per class side by side, the
    /// class's texture tiled over it (or its flat colour), and the class's segment colour over the
    /// same block in the guide. Blocks are at least `min_side` pixels.
    pub(crate) fn atlas(&self, min_side: usize) -> (ByteImage, ByteImage) {
        let side = self.block_side(min_side);
        let width = side * MapClass::ALL.len();
        let mut style = Vec::with_capacity(width * side * 3);
        let mut guide = Vec::with_capacity(width * side * 3);
        for y in 0..side {
            for class in MapClass::ALL {
                let colour = class.colour();
                for x in 0..side {
                    let pixel = match &self.fills[class.index()] {
                        Fill::Colour(rgb) => *rgb,
                        Fill::Texture(image) => {
                            let [r, g, b, _] = image.get(x % image.width(), y % image.height());
                            [r, g, b]
                        }
                    };
                    style.extend_from_slice(&pixel);
                    guide.extend_from_slice(&colour);
                }
            }
        }
        let image = |data| ByteImage::from_data(width, side, 3, data).expect("the atlas's size is its data's");
        (image(style), image(guide))
    }

    /// The classes painted with a texture.
    pub fn textured(&self) -> Vec<MapClass> {
        MapClass::ALL.into_iter().filter(|class| matches!(self.fills[class.index()], Fill::Texture(_))).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_atlas_tiles_each_texture_over_its_block() {
        let texture = RgbaImage::from_fn(3, 2, |x, y| [x as u8 * 10, y as u8 * 10, 7, 255]);
        let legend = Legend::plain().with(MapClass::Water, Fill::Texture(texture));
        let (style, guide) = legend.atlas(4);
        assert_eq!((style.width(), style.height()), (32, 4));
        // Water is the second block: columns 4..8, the texture repeating every 3 columns and 2 rows.
        assert_eq!(style.pixel(4, 0), &[0, 0, 7]);
        assert_eq!(style.pixel(7, 3), &[0, 10, 7]);
        assert_eq!(style.pixel(0, 0), &MapClass::Land.colour());
        assert_eq!(guide.pixel(5, 1), &MapClass::Water.colour());
        assert_eq!(legend.textured(), vec![MapClass::Water]);
    }
}
