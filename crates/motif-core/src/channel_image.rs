//! 8-bit images with any number of channels ([`ByteImage`]) and the [`ChannelImage`] trait that
//! lets an engine take float or 8-bit images alike.
//!
//! Decoded PNGs are 8-bit: kept as bytes, a style with five guide channels on each side takes a
//! quarter of the memory it takes as floats (the stylize engine's peak on a 0.8 MP, three-guide
//! case is dominated by its inputs otherwise).

use std::borrow::Cow;

use crate::error::InvalidParameter;
use crate::image::{FloatImage, RgbaImage, TAPS, check_layout, coarser_chain};

/// The value an 8-bit sample stands for, `v / 255`, exactly as [`RgbaImage::to_float`] computes it
/// (so an 8-bit image and its float conversion read the same values).
pub const BYTE_VALUES: [f32; 256] = {
    let mut table = [0.0_f32; 256];
    let mut value = 0;
    while value < 256 {
        table[value] = value as f32 / 255.0;
        value += 1;
    }
    table
};

/// An image of 8-bit values with any number of interleaved channels, row-major, y down; a
/// value `v` stands for `v / 255`.
#[derive(Debug, Clone, PartialEq)]
pub struct ByteImage {
    width: usize,
    height: usize,
    channels: usize,
    data: Vec<u8>,
}

impl ByteImage {
    /// Wraps interleaved `data`; fails if its length is not `width × height × channels`.
    pub fn from_data(width: usize, height: usize, channels: usize, data: Vec<u8>) -> Result<Self, InvalidParameter> {
        check_layout(width, height, channels, data.len())?;
        Ok(Self { width, height, channels, data })
    }

    /// The listed channels (0 = red ... 3 = alpha) of an RGBA image.
    pub fn from_rgba_channels(image: &RgbaImage, channels: &[usize]) -> ByteImage {
        let mut data = Vec::with_capacity(image.pixels().len() * channels.len());
        data.extend(image.pixels().iter().flat_map(|pixel| channels.iter().map(move |&c| pixel[c])));
        ByteImage { width: image.width(), height: image.height(), channels: channels.len(), data }
    }

    /// A float image with values in `[0, 1]`, clamped and rounded to 8 bits.
    pub fn from_float(image: &FloatImage) -> ByteImage {
        let data = image.data().iter().map(|&v| crate::math::unit_to_byte(v)).collect();
        ByteImage { width: image.width(), height: image.height(), channels: image.channels(), data }
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Channels per pixel.
    pub fn channels(&self) -> usize {
        self.channels
    }

    /// All values, interleaved.
    pub fn data(&self) -> &[u8] {
        &self.data
    }

    /// The channels of pixel `(x, y)`.
    pub fn pixel(&self, x: usize, y: usize) -> &[u8] {
        let start = (y * self.width + x) * self.channels;
        &self.data[start..start + self.channels]
    }

    /// The float image of the same values (`v / 255`).
    pub fn to_float(&self) -> FloatImage {
        let data = self.data.iter().map(|&v| BYTE_VALUES[usize::from(v)]).collect();
        FloatImage::from_data(self.width, self.height, self.channels, data).expect("same layout")
    }

    /// The next coarser pyramid level, `ceil(width / 2) × ceil(height / 2)`: the values of
    /// [`FloatImage::downsample`] on [`to_float`](Self::to_float), rounded to 8 bits. Only the
    /// kept pixels are filtered (the float path blurs every pixel, then drops three in four), so
    /// no full-size float copy is made.
    pub fn downsample(&self) -> ByteImage {
        let (w, h, c) = (self.width, self.height, self.channels);
        let (out_w, out_h) = (w.div_ceil(2), h.div_ceil(2));
        let clamp = |v: isize, size: usize| v.clamp(0, size as isize - 1) as usize;
        // The horizontal pass at the kept columns of every row, in the float path's order of sums.
        let mut horizontal = vec![0.0_f32; out_w * h * c];
        for y in 0..h {
            for x in 0..out_w {
                let dst = (y * out_w + x) * c;
                for (k, tap) in TAPS.iter().enumerate() {
                    let src = (y * w + clamp(2 * x as isize + k as isize - 2, w)) * c;
                    for channel in 0..c {
                        horizontal[dst + channel] += tap * BYTE_VALUES[usize::from(self.data[src + channel])];
                    }
                }
            }
        }
        let mut data = vec![0_u8; out_w * out_h * c];
        let mut sums = vec![0.0_f32; out_w * c];
        for y in 0..out_h {
            sums.fill(0.0);
            for (k, tap) in TAPS.iter().enumerate() {
                let sy = clamp(2 * y as isize + k as isize - 2, h);
                for (sum, value) in sums.iter_mut().zip(&horizontal[sy * out_w * c..(sy + 1) * out_w * c]) {
                    *sum += tap * value;
                }
            }
            for (out, sum) in data[y * out_w * c..(y + 1) * out_w * c].iter_mut().zip(&sums) {
                *out = crate::math::unit_to_byte(*sum);
            }
        }
        ByteImage { width: out_w, height: out_h, channels: c, data }
    }
}

/// The samples of a [`ChannelImage`], as stored.
#[derive(Debug, Clone, Copy)]
pub enum Samples<'a> {
    /// Float values in `[0, 1]`.
    Float(&'a [f32]),
    /// 8-bit values, `v` standing for `v / 255`.
    Byte(&'a [u8]),
}

impl Samples<'_> {
    /// Sample `index` as a value in `[0, 1]`.
    #[inline]
    pub fn value(&self, index: usize) -> f32 {
        match self {
            Samples::Float(values) => values[index],
            Samples::Byte(values) => BYTE_VALUES[usize::from(values[index])],
        }
    }
}

/// An image an engine reads channel values from: [`FloatImage`] or [`ByteImage`].
pub trait ChannelImage: Clone + std::fmt::Debug + PartialEq + Send + Sync {
    /// Width in pixels.
    fn width(&self) -> usize;
    /// Height in pixels.
    fn height(&self) -> usize;
    /// Channels per pixel.
    fn channels(&self) -> usize;
    /// The interleaved samples.
    fn samples(&self) -> Samples<'_>;
    /// The levels of a Gaussian pyramid above this one, coarser and coarser, at most
    /// `levels − 1`, none smaller than `min_size` a side (see [`FloatImage::coarser_levels`]).
    fn coarser_levels(&self, levels: usize, min_size: usize) -> Vec<Self>;
    /// The image as floats (borrowed when it is one).
    fn to_float_image(&self) -> Cow<'_, FloatImage>;
}

impl ChannelImage for FloatImage {
    fn width(&self) -> usize {
        FloatImage::width(self)
    }
    fn height(&self) -> usize {
        FloatImage::height(self)
    }
    fn channels(&self) -> usize {
        FloatImage::channels(self)
    }
    fn samples(&self) -> Samples<'_> {
        Samples::Float(self.data())
    }
    fn coarser_levels(&self, levels: usize, min_size: usize) -> Vec<Self> {
        FloatImage::coarser_levels(self, levels, min_size)
    }
    fn to_float_image(&self) -> Cow<'_, FloatImage> {
        Cow::Borrowed(self)
    }
}

impl ChannelImage for ByteImage {
    fn width(&self) -> usize {
        self.width
    }
    fn height(&self) -> usize {
        self.height
    }
    fn channels(&self) -> usize {
        self.channels
    }
    fn samples(&self) -> Samples<'_> {
        Samples::Byte(&self.data)
    }
    fn coarser_levels(&self, levels: usize, min_size: usize) -> Vec<Self> {
        coarser_chain(self, levels, min_size, |image| (image.width, image.height), ByteImage::downsample)
    }
    fn to_float_image(&self) -> Cow<'_, FloatImage> {
        Cow::Owned(self.to_float())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_image() -> ByteImage {
        let data = (0..13 * 9 * 3).map(|i| ((i * 37 + i / 7 * 11) % 256) as u8).collect();
        ByteImage::from_data(13, 9, 3, data).unwrap()
    }

    #[test]
    fn byte_values_match_the_rgba_conversion() {
        let rgba = RgbaImage::from_fn(16, 16, |x, y| [(y * 16 + x) as u8, 0, 0, 255]);
        let float = rgba.to_float_channels(&[0]);
        let bytes = ByteImage::from_rgba_channels(&rgba, &[0]);
        assert_eq!(bytes.to_float(), float);
        assert_eq!(ByteImage::from_float(&float), bytes);
    }

    #[test]
    fn downsample_rounds_the_float_pyramid() {
        let image = sample_image();
        let float = image.to_float().downsample();
        let bytes = image.downsample();
        assert_eq!((bytes.width(), bytes.height(), bytes.channels()), (7, 5, 3));
        // The same sums in the same order: every value is the float level rounded.
        assert_eq!(bytes, ByteImage::from_float(&float));
    }

    #[test]
    fn coarser_levels_stop_at_the_minimum_size() {
        let image = sample_image();
        let levels = ChannelImage::coarser_levels(&image, 5, 3);
        let sizes: Vec<(usize, usize)> = levels.iter().map(|l| (l.width(), l.height())).collect();
        assert_eq!(sizes, vec![(7, 5), (4, 3)]);
        assert_eq!(levels[1], levels[0].downsample());
    }

    #[test]
    fn wrong_lengths_are_refused() {
        assert!(ByteImage::from_data(2, 2, 3, vec![0; 11]).is_err());
        assert!(ByteImage::from_data(2, 2, 0, vec![]).is_err());
    }
}
