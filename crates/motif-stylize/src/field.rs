//! The public nearest-neighbour field: which source patch each output pixel came from.
//!
//! It can be saved as a PNG ([`NearestNeighbourField::to_rgba`]) and re-applied to another
//! style image of the same size ([`apply_field`]), e.g. to stylize a second layer of a map with
//! exactly the same patch layout.

use motif_core::{FloatImage, RgbaImage};

use crate::Error;

/// For each target pixel, the centre `[x, y]` of the source patch it was matched to (`None`
/// for pixels that were not searched, e.g. copied from pre-synthesized textures).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NearestNeighbourField {
    /// Target width.
    pub width: usize,
    /// Target height.
    pub height: usize,
    /// Source (style) width.
    pub source_width: usize,
    /// Source (style) height.
    pub source_height: usize,
    /// Side of the patches the field was computed with.
    pub patch_size: usize,
    /// Row-major matches.
    pub matches: Vec<Option<[u32; 2]>>,
}

/// Largest source side the PNG encoding holds (12 bits per coordinate).
pub const MAX_ENCODED_SIDE: usize = 4096;

impl NearestNeighbourField {
    /// Encodes the field as an image: red = x mod 256, green = y mod 256, blue = (x / 256) +
    /// 16 · (y / 256), alpha 255 for searched pixels and 0 for the others. Lossless for sources
    /// up to 4096 pixels a side.
    pub fn to_rgba(&self) -> Result<RgbaImage, Error> {
        if self.source_width > MAX_ENCODED_SIDE || self.source_height > MAX_ENCODED_SIDE {
            return Err(Error::FieldTooLarge {
                width: self.source_width,
                height: self.source_height,
                max: MAX_ENCODED_SIDE,
            });
        }
        let pixels = self
            .matches
            .iter()
            .map(|m| match m {
                Some([x, y]) => [(x & 255) as u8, (y & 255) as u8, ((x >> 8) | ((y >> 8) << 4)) as u8, 255],
                None => [0, 0, 0, 0],
            })
            .collect();
        RgbaImage::from_pixels(self.width, self.height, pixels).map_err(Error::from)
    }

    /// Decodes [`to_rgba`](Self::to_rgba)'s encoding for a source of the given size and patch
    /// side, checking every match lies where a whole patch fits.
    pub fn from_rgba(
        image: &RgbaImage,
        source_width: usize,
        source_height: usize,
        patch_size: usize,
    ) -> Result<Self, Error> {
        let radius = patch_size / 2;
        let mut matches = Vec::with_capacity(image.pixels().len());
        for (index, p) in image.pixels().iter().enumerate() {
            if p[3] == 0 {
                matches.push(None);
                continue;
            }
            let x = u32::from(p[0]) | (u32::from(p[2] & 15) << 8);
            let y = u32::from(p[1]) | (u32::from(p[2] >> 4) << 8);
            let fits = |v: u32, side: usize| (radius..side.saturating_sub(radius)).contains(&(v as usize));
            if !fits(x, source_width) || !fits(y, source_height) {
                return Err(Error::FieldOutside {
                    x: index % image.width(),
                    y: index / image.width(),
                    source_x: x,
                    source_y: y,
                    source_width,
                    source_height,
                    patch: patch_size,
                });
            }
            matches.push(Some([x, y]));
        }
        Ok(Self { width: image.width(), height: image.height(), source_width, source_height, patch_size, matches })
    }
}

/// Re-applies a field to `style` (same size as the field's source): every pixel becomes the
/// plain average of what the overlapping matched patches say; unsearched pixels stay
/// transparent (zero).
pub fn apply_field(field: &NearestNeighbourField, style: &FloatImage) -> Result<FloatImage, Error> {
    if style.width() != field.source_width || style.height() != field.source_height {
        return Err(Error::SizeMismatch {
            what: "the style a field is applied to must have the field's source size".into(),
            first: "field source".into(),
            first_size: format!("{}×{}", field.source_width, field.source_height),
            second: "style".into(),
            second_size: format!("{}×{}", style.width(), style.height()),
        });
    }
    let (w, h, r) = (field.width as isize, field.height as isize, (field.patch_size / 2) as isize);
    let channels = style.channels();
    let mut out = FloatImage::new(field.width, field.height, channels);
    let mut sum = vec![0.0_f32; channels];
    for y in 0..h {
        for x in 0..w {
            sum.fill(0.0);
            let mut count = 0.0;
            for oy in -r..=r {
                for ox in -r..=r {
                    let (px, py) = (x + ox, y + oy);
                    if px < 0 || py < 0 || px >= w || py >= h {
                        continue;
                    }
                    if let Some([sx, sy]) = field.matches[(py * w + px) as usize] {
                        let value = style.pixel((sx as isize - ox) as usize, (sy as isize - oy) as usize);
                        for (acc, v) in sum.iter_mut().zip(value) {
                            *acc += v;
                        }
                        count += 1.0;
                    }
                }
            }
            if count > 0.0 {
                for (out, acc) in out.pixel_mut(x as usize, y as usize).iter_mut().zip(&sum) {
                    *out = acc / count;
                }
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_encoding_round_trips_and_checks_bounds() {
        let field = NearestNeighbourField {
            width: 3,
            height: 1,
            source_width: 3000,
            source_height: 700,
            patch_size: 5,
            matches: vec![Some([2, 2]), None, Some([2997, 697])],
        };
        let image = field.to_rgba().unwrap();
        assert_eq!(NearestNeighbourField::from_rgba(&image, 3000, 700, 5).unwrap(), field);
        assert!(NearestNeighbourField::from_rgba(&image, 3000, 600, 5).is_err());
    }

    #[test]
    fn identity_field_reproduces_the_style_inside() {
        let style = FloatImage::from_data(6, 6, 1, (0..36).map(|i| i as f32).collect()).unwrap();
        let matches =
            (0..36).map(|i| Some([(i % 6).clamp(1, 4) as u32, (i / 6).clamp(1, 4) as u32])).collect::<Vec<_>>();
        let field =
            NearestNeighbourField { width: 6, height: 6, source_width: 6, source_height: 6, patch_size: 3, matches };
        let out = apply_field(&field, &style).unwrap();
        assert_eq!(out.pixel(2, 3), style.pixel(2, 3));
        assert!(apply_field(&field, &FloatImage::new(5, 6, 1)).is_err());
    }
}
