//! The public nearest-neighbour field: which source patch each output pixel came from.
//!
//! It can be saved as a PNG ([`NearestNeighbourField::to_rgba16`], with the final vote's weights;
//! [`NearestNeighbourField::to_rgba`] without) and re-applied to another style image of the same
//! size ([`apply_field`]), e.g. to stylize a second layer of a map with exactly the same patch
//! layout; applied to the style it was made with, it gives back the output.

use motif_core::{ChannelImage, FloatImage, RgbaImage, Samples};

use crate::Error;
use crate::vote::{ByteVotes, FloatVotes, Votes, weight_of_code};
use crate::{InputError, LimitError};

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
    /// Each target pixel's weight in the final vote as a 16-bit code (weight = code / 65535);
    /// `None` when unknown (fields read from 8-bit files): re-applied as a plain mean.
    pub weights: Option<Vec<u16>>,
}

/// Largest source side the PNG encoding holds (12 bits per coordinate).
pub(crate) const MAX_ENCODED_SIDE: usize = 4096;

impl NearestNeighbourField {
    /// Encodes the field as an image: red = x mod 256, green = y mod 256, blue = (x / 256) +
    /// 16 · (y / 256), alpha 255 for searched pixels and 0 for the others. Lossless for sources
    /// up to 4096 pixels a side.
    pub fn to_rgba(&self) -> Result<RgbaImage, Error> {
        if self.source_width > MAX_ENCODED_SIDE || self.source_height > MAX_ENCODED_SIDE {
            return Err(Error::Limit(LimitError::FieldTooLarge {
                width: self.source_width,
                height: self.source_height,
                max: MAX_ENCODED_SIDE,
            }));
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
        let mut field = Self::empty(image.width(), image.height(), source_width, source_height, patch_size);
        for (index, p) in image.pixels().iter().enumerate() {
            let source = (p[3] != 0).then(|| {
                [u32::from(p[0]) | (u32::from(p[2] & 15) << 8), u32::from(p[1]) | (u32::from(p[2] >> 4) << 8)]
            });
            field.push(index, source)?;
        }
        Ok(field)
    }

    /// Encodes the field with the final vote's weights as 16-bit RGBA pixels, row by row:
    /// red = source x, green = source y, blue = the weight's code (65535 when the field has no
    /// weights), alpha 65535 for searched pixels and 0 for the others.
    pub fn to_rgba16(&self) -> Vec<[u16; 4]> {
        self.matches
            .iter()
            .enumerate()
            .map(|(t, m)| match m {
                Some([x, y]) => [*x as u16, *y as u16, self.weights.as_ref().map_or(65535, |w| w[t]), 65535],
                None => [0, 0, 0, 0],
            })
            .collect()
    }

    /// Decodes [`to_rgba16`](Self::to_rgba16)'s encoding (`width × height` pixels) for a source of
    /// the given size and patch side, checking every match lies where a whole patch fits.
    pub fn from_rgba16(
        width: usize,
        height: usize,
        pixels: &[[u16; 4]],
        source_width: usize,
        source_height: usize,
        patch_size: usize,
    ) -> Result<Self, Error> {
        let mut field = Self::empty(width, height, source_width, source_height, patch_size);
        let mut weights = Vec::with_capacity(pixels.len());
        for (index, p) in pixels.iter().enumerate() {
            field.push(index, (p[3] != 0).then_some([u32::from(p[0]), u32::from(p[1])]))?;
            weights.push(p[2]);
        }
        field.weights = Some(weights);
        Ok(field)
    }

    fn empty(width: usize, height: usize, source_width: usize, source_height: usize, patch_size: usize) -> Self {
        let matches = Vec::with_capacity(width * height);
        Self { width, height, source_width, source_height, patch_size, matches, weights: None }
    }

    /// Appends target pixel `index`'s match, checking that a whole patch fits around it.
    fn push(&mut self, index: usize, source: Option<[u32; 2]>) -> Result<(), Error> {
        let radius = self.patch_size / 2;
        if let Some([x, y]) = source {
            let fits = |v: u32, side: usize| (radius..side.saturating_sub(radius)).contains(&(v as usize));
            if !fits(x, self.source_width) || !fits(y, self.source_height) {
                return Err(Error::Input(InputError::FieldOutside {
                    x: index % self.width.max(1),
                    y: index / self.width.max(1),
                    source_x: x,
                    source_y: y,
                    source_width: self.source_width,
                    source_height: self.source_height,
                    patch: self.patch_size,
                }));
            }
        }
        self.matches.push(source);
        Ok(())
    }
}

/// Re-applies a field to `style` (same size as the field's source): every pixel becomes the
/// average of what the overlapping matched patches say, weighted by the field's vote weights as
/// the synthesis weighed them (plain when the field has none), summed as the synthesis sums them
/// (in its order for a float style, exactly in integers for an 8-bit one), so that the style the
/// field was made with gives back the output bit for bit; unsearched pixels stay transparent
/// (zero). The style has 1, 3 or 4 channels, as a synthesis's.
pub fn apply_field(field: &NearestNeighbourField, style: &impl ChannelImage) -> Result<FloatImage, Error> {
    if style.width() != field.source_width || style.height() != field.source_height {
        return Err(Error::Input(InputError::SizeMismatch {
            what: "the style a field is applied to must have the field's source size".into(),
            first: "field source".into(),
            first_size: format!("{}×{}", field.source_width, field.source_height),
            second: "style".into(),
            second_size: format!("{}×{}", style.width(), style.height()),
        }));
    }
    crate::check_image(style, "style a field is applied to")?;
    let channels = style.channels();
    let mut out = FloatImage::new(field.width, field.height, channels);
    match style.samples() {
        Samples::Float(values) => {
            let weight = |t: usize| field.weights.as_ref().map_or(1.0, |w| weight_of_code(w[t]));
            reapply::<FloatVotes>(field, values, channels, weight, &mut out);
        }
        Samples::Byte(values) => {
            let code = |t: usize| field.weights.as_ref().map_or(1, |w| w[t]);
            reapply::<ByteVotes>(field, values, channels, code, &mut out);
        }
    }
    Ok(out)
}

/// [`apply_field`] with the vote's accumulator `V` over the style's samples, patches weighed by
/// `weight` of their centre.
fn reapply<V: Votes>(
    field: &NearestNeighbourField,
    samples: &[V::Sample],
    channels: usize,
    weight: impl Fn(usize) -> V::Weight,
    out: &mut FloatImage,
) {
    let (w, h, r) = (field.width as isize, field.height as isize, (field.patch_size / 2) as isize);
    for y in 0..h {
        for x in 0..w {
            let mut votes = V::default();
            for oy in -r..=r {
                for ox in -r..=r {
                    let (px, py) = (x + ox, y + oy);
                    if px < 0 || py < 0 || px >= w || py >= h {
                        continue;
                    }
                    let t = (py * w + px) as usize;
                    if let Some([sx, sy]) = field.matches[t] {
                        let (column, row) = ((sx as isize - ox) as usize, (sy as isize - oy) as usize);
                        let start = (row * field.source_width + column) * channels;
                        votes.add(&samples[start..start + channels], weight(t));
                    }
                }
            }
            votes.mean(out.pixel_mut(x as usize, y as usize));
        }
    }
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
            weights: None,
        };
        let image = field.to_rgba().unwrap();
        assert_eq!(NearestNeighbourField::from_rgba(&image, 3000, 700, 5).unwrap(), field);
        assert!(NearestNeighbourField::from_rgba(&image, 3000, 600, 5).is_err());
    }

    #[test]
    fn sixteen_bit_encoding_keeps_matches_and_weights() {
        let field = NearestNeighbourField {
            width: 3,
            height: 1,
            source_width: 9000,
            source_height: 700,
            patch_size: 5,
            matches: vec![Some([2, 2]), None, Some([8997, 697])],
            weights: Some(vec![65535, 0, 17]),
        };
        let pixels = field.to_rgba16();
        assert_eq!(NearestNeighbourField::from_rgba16(3, 1, &pixels, 9000, 700, 5).unwrap(), field);
        assert!(NearestNeighbourField::from_rgba16(3, 1, &pixels, 8000, 700, 5).is_err());
    }

    #[test]
    fn weights_shift_the_vote_towards_heavier_patches() {
        // Two patches cover pixel (1, 1): the one left of it puts a bright source pixel there, the
        // one right of it a dark one; weighing the left one three times as much gives 3/4.
        let style = FloatImage::from_data(4, 3, 1, [0.0, 0.0, 1.0, 1.0].repeat(3)).unwrap();
        let mut matches = vec![None; 9];
        matches[3] = Some([1, 1]);
        matches[5] = Some([2, 1]);
        let field = |weights| NearestNeighbourField {
            width: 3,
            height: 3,
            source_width: 4,
            source_height: 3,
            patch_size: 3,
            matches: matches.clone(),
            weights,
        };
        let plain = apply_field(&field(None), &style).unwrap().pixel(1, 1)[0];
        let weighted =
            apply_field(&field(Some(vec![0, 0, 0, 65535, 0, 21845, 0, 0, 0])), &style).unwrap().pixel(1, 1)[0];
        assert!((plain - 0.5).abs() < 1e-6, "{plain}");
        assert!((weighted - 0.75).abs() < 1e-4, "{weighted}");
    }

    #[test]
    fn identity_field_reproduces_the_style_inside() {
        let style = FloatImage::from_data(6, 6, 1, (0..36).map(|i| i as f32).collect()).unwrap();
        let matches =
            (0..36).map(|i| Some([(i % 6).clamp(1, 4) as u32, (i / 6).clamp(1, 4) as u32])).collect::<Vec<_>>();
        let field = NearestNeighbourField {
            width: 6,
            height: 6,
            source_width: 6,
            source_height: 6,
            patch_size: 3,
            matches,
            weights: None,
        };
        let out = apply_field(&field, &style).unwrap();
        assert_eq!(out.pixel(2, 3), style.pixel(2, 3));
        assert!(apply_field(&field, &FloatImage::new(5, 6, 1)).is_err());
    }
}
