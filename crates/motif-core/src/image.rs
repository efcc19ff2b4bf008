//! Raster images: 8-bit RGBA for input and output, N-channel float for computation.
//!
//! [`RgbaImage`] holds 8-bit sRGB with straight alpha, the way PNG files store it. [`FloatImage`]
//! holds any number of `f32` channels (1 for a mask, 3 for a guide, 4 for RGBA, more for stacked
//! guides), the form engines compute with. Both are row-major with y down. Continuous coordinates
//! put the centre of pixel `(i, j)` at `(i + 0.5, j + 0.5)`.

use crate::error::InvalidParameter;

/// An 8-bit RGBA image, straight alpha, row-major, y down.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RgbaImage {
    width: usize,
    height: usize,
    pixels: Vec<[u8; 4]>,
}

impl RgbaImage {
    /// A fully transparent image.
    pub fn new(width: usize, height: usize) -> Self {
        Self::filled(width, height, [0, 0, 0, 0])
    }

    /// An image with every pixel set to `colour`.
    pub fn filled(width: usize, height: usize, colour: [u8; 4]) -> Self {
        Self { width, height, pixels: vec![colour; width * height] }
    }

    /// Wraps `pixels` (row-major); fails if their number is not `width × height`.
    pub fn from_pixels(width: usize, height: usize, pixels: Vec<[u8; 4]>) -> Result<Self, InvalidParameter> {
        if pixels.len() != width * height {
            return Err(InvalidParameter::new(
                "pixels",
                pixels.len(),
                format!("must hold width × height = {} pixels", width * height),
            ));
        }
        Ok(Self { width, height, pixels })
    }

    /// Builds an image by calling `colour(x, y)` for every pixel.
    pub fn from_fn(width: usize, height: usize, mut colour: impl FnMut(usize, usize) -> [u8; 4]) -> Self {
        let mut pixels = Vec::with_capacity(width * height);
        for y in 0..height {
            for x in 0..width {
                pixels.push(colour(x, y));
            }
        }
        Self { width, height, pixels }
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// True when the image has no pixels.
    pub fn is_empty(&self) -> bool {
        self.pixels.is_empty()
    }

    /// All pixels, row-major.
    pub fn pixels(&self) -> &[[u8; 4]] {
        &self.pixels
    }

    /// All pixels, row-major, mutable.
    pub fn pixels_mut(&mut self) -> &mut [[u8; 4]] {
        &mut self.pixels
    }

    /// The pixels as one flat byte slice (RGBARGBA...).
    pub fn as_bytes(&self) -> &[u8] {
        self.pixels.as_flattened()
    }

    /// The pixel at `(x, y)`; panics when out of bounds (callers index inside the image).
    #[inline]
    pub fn get(&self, x: usize, y: usize) -> [u8; 4] {
        self.pixels[y * self.width + x]
    }

    /// Sets the pixel at `(x, y)`.
    pub fn set(&mut self, x: usize, y: usize, colour: [u8; 4]) {
        self.pixels[y * self.width + x] = colour;
    }

    /// One alpha value per pixel, row-major.
    pub fn alpha(&self) -> Vec<u8> {
        self.pixels.iter().map(|pixel| pixel[3]).collect()
    }

    /// Number of pixels whose alpha is at least `threshold`.
    pub fn count_alpha_at_least(&self, threshold: u8) -> usize {
        self.pixels.iter().filter(|pixel| pixel[3] >= threshold).count()
    }

    /// True when every pixel has alpha 0.
    pub fn is_fully_transparent(&self) -> bool {
        self.pixels.iter().all(|pixel| pixel[3] == 0)
    }

    /// True when every pixel has alpha 255.
    pub fn is_fully_opaque(&self) -> bool {
        self.pixels.iter().all(|pixel| pixel[3] == 255)
    }

    /// The smallest rectangle `(x0, y0, x1, y1)` (exclusive ends) holding every pixel with alpha > 0,
    /// or `None` for a fully transparent image.
    pub fn opaque_bounds(&self) -> Option<(usize, usize, usize, usize)> {
        let mut bounds: Option<(usize, usize, usize, usize)> = None;
        for y in 0..self.height {
            for x in 0..self.width {
                if self.get(x, y)[3] > 0 {
                    bounds = Some(match bounds {
                        None => (x, y, x + 1, y + 1),
                        Some((x0, y0, x1, y1)) => (x0.min(x), y0.min(y), x1.max(x + 1), y1.max(y + 1)),
                    });
                }
            }
        }
        bounds
    }

    /// Composites `self` over an opaque background colour, dropping alpha.
    pub fn over_background(&self, background: [u8; 3]) -> RgbaImage {
        let pixels = self
            .pixels
            .iter()
            .map(|pixel| {
                let alpha = u32::from(pixel[3]);
                let mix = |c: u8, b: u8| ((u32::from(c) * alpha + u32::from(b) * (255 - alpha) + 127) / 255) as u8;
                [mix(pixel[0], background[0]), mix(pixel[1], background[1]), mix(pixel[2], background[2]), 255]
            })
            .collect();
        RgbaImage { width: self.width, height: self.height, pixels }
    }

    /// Converts to a 4-channel float image with values in `[0, 1]` (straight alpha).
    pub fn to_float(&self) -> FloatImage {
        // Sized up front: collecting a flat map grows by doubling, up to twice the image.
        let mut data = Vec::with_capacity(self.pixels.len() * 4);
        data.extend(self.pixels.iter().flat_map(|pixel| pixel.map(|c| f32::from(c) / 255.0)));
        FloatImage { width: self.width, height: self.height, channels: 4, data }
    }

    /// Converts to a float image keeping only the listed channels (0 = red ... 3 = alpha),
    /// values in `[0, 1]`.
    pub fn to_float_channels(&self, channels: &[usize]) -> FloatImage {
        let mut data = Vec::with_capacity(self.pixels.len() * channels.len());
        data.extend(self.pixels.iter().flat_map(|pixel| channels.iter().map(move |&c| f32::from(pixel[c]) / 255.0)));
        FloatImage { width: self.width, height: self.height, channels: channels.len(), data }
    }

    /// Converts from a float image with values in `[0, 1]`: 1 channel is grey, 2 grey + alpha,
    /// 3 RGB, 4 RGBA; channels beyond 4 are ignored. Values are clamped and rounded.
    pub fn from_float(image: &FloatImage) -> RgbaImage {
        let to_byte = crate::math::unit_to_byte;
        // One loop per channel count (the layout is decided once, not per pixel).
        let samples = |channels| image.data.chunks_exact(channels);
        let pixels = match image.channels.max(1) {
            1 => samples(1).map(|p| [to_byte(p[0]), to_byte(p[0]), to_byte(p[0]), 255]).collect(),
            2 => samples(2).map(|p| [to_byte(p[0]), to_byte(p[0]), to_byte(p[0]), to_byte(p[1])]).collect(),
            3 => samples(3).map(|p| [to_byte(p[0]), to_byte(p[1]), to_byte(p[2]), 255]).collect(),
            n => samples(n).map(|p| [to_byte(p[0]), to_byte(p[1]), to_byte(p[2]), to_byte(p[3])]).collect(),
        };
        RgbaImage { width: image.width, height: image.height, pixels }
    }
}

/// A float image with any number of interleaved channels, row-major, y down.
#[derive(Debug, Clone, PartialEq)]
pub struct FloatImage {
    width: usize,
    height: usize,
    channels: usize,
    data: Vec<f32>,
}

impl FloatImage {
    /// An image of zeros.
    pub fn new(width: usize, height: usize, channels: usize) -> Self {
        Self { width, height, channels, data: vec![0.0; width * height * channels] }
    }

    /// Wraps interleaved `data`; fails if its length is not `width × height × channels`.
    pub fn from_data(width: usize, height: usize, channels: usize, data: Vec<f32>) -> Result<Self, InvalidParameter> {
        check_layout(width, height, channels, data.len())?;
        Ok(Self { width, height, channels, data })
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

    /// True when the image has no pixels.
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// All values, interleaved.
    pub fn data(&self) -> &[f32] {
        &self.data
    }

    /// All values, interleaved, mutable.
    pub fn data_mut(&mut self) -> &mut [f32] {
        &mut self.data
    }

    /// The channels of pixel `(x, y)`.
    #[inline]
    pub fn pixel(&self, x: usize, y: usize) -> &[f32] {
        let start = (y * self.width + x) * self.channels;
        &self.data[start..start + self.channels]
    }

    /// The channels of pixel `(x, y)`, mutable.
    #[inline]
    pub fn pixel_mut(&mut self, x: usize, y: usize) -> &mut [f32] {
        let start = (y * self.width + x) * self.channels;
        &mut self.data[start..start + self.channels]
    }

    /// Bilinear sample at continuous coordinates `(x, y)` (pixel centres at `+0.5`), clamped to
    /// the border, written into `out` (length = channels).
    pub fn sample_bilinear(&self, x: f64, y: f64, out: &mut [f32]) {
        let fx = (x - 0.5).clamp(0.0, (self.width - 1) as f64);
        let fy = (y - 0.5).clamp(0.0, (self.height - 1) as f64);
        let x0 = fx.floor() as usize;
        let y0 = fy.floor() as usize;
        let x1 = (x0 + 1).min(self.width - 1);
        let y1 = (y0 + 1).min(self.height - 1);
        let tx = (fx - x0 as f64) as f32;
        let ty = (fy - y0 as f64) as f32;
        let (p00, p10, p01, p11) = (self.pixel(x0, y0), self.pixel(x1, y0), self.pixel(x0, y1), self.pixel(x1, y1));
        for c in 0..self.channels {
            let top = p00[c] + (p10[c] - p00[c]) * tx;
            let bottom = p01[c] + (p11[c] - p01[c]) * tx;
            out[c] = top + (bottom - top) * ty;
        }
    }

    /// Multiplies colour channels by alpha (the last channel); use before filtering RGBA so
    /// transparent pixels do not bleed their colour.
    pub fn premultiply(&mut self) {
        let channels = self.channels;
        for pixel in self.data.chunks_exact_mut(channels) {
            let alpha = pixel[channels - 1];
            for value in &mut pixel[..channels - 1] {
                *value *= alpha;
            }
        }
    }

    /// Inverse of [`premultiply`](Self::premultiply); pixels with zero alpha get zero colour.
    pub fn unpremultiply(&mut self) {
        let channels = self.channels;
        for pixel in self.data.chunks_exact_mut(channels) {
            let alpha = pixel[channels - 1];
            let scale = if alpha > 0.0 { 1.0 / alpha } else { 0.0 };
            for value in &mut pixel[..channels - 1] {
                *value *= scale;
            }
        }
    }

    /// Resamples to `width × height` by bilinear interpolation (pixel centres aligned).
    pub fn resize_bilinear(&self, width: usize, height: usize) -> FloatImage {
        let mut out = FloatImage::new(width, height, self.channels);
        let scale_x = self.width as f64 / width as f64;
        let scale_y = self.height as f64 / height as f64;
        let channels = self.channels;
        for y in 0..height {
            for x in 0..width {
                let start = (y * width + x) * channels;
                let (sx, sy) = ((x as f64 + 0.5) * scale_x, (y as f64 + 0.5) * scale_y);
                self.sample_bilinear(sx, sy, &mut out.data[start..start + channels]);
            }
        }
        out
    }

    /// Separable binomial blur `[1 4 6 4 1] / 16` (a Gaussian of σ ≈ 1), border clamped.
    pub fn blur(&self) -> FloatImage {
        let (w, h, c) = (self.width, self.height, self.channels);
        let mut horizontal = FloatImage::new(w, h, c);
        for y in 0..h {
            for x in 0..w {
                for (k, tap) in TAPS.iter().enumerate() {
                    let sx = (x as isize + k as isize - 2).clamp(0, w as isize - 1) as usize;
                    let src = (y * w + sx) * c;
                    let dst = (y * w + x) * c;
                    for channel in 0..c {
                        horizontal.data[dst + channel] += tap * self.data[src + channel];
                    }
                }
            }
        }
        let mut out = FloatImage::new(w, h, c);
        for y in 0..h {
            for (k, tap) in TAPS.iter().enumerate() {
                let sy = (y as isize + k as isize - 2).clamp(0, h as isize - 1) as usize;
                let src_row = &horizontal.data[sy * w * c..(sy + 1) * w * c];
                let dst_row = &mut out.data[y * w * c..(y + 1) * w * c];
                for (dst, src) in dst_row.iter_mut().zip(src_row) {
                    *dst += tap * src;
                }
            }
        }
        out
    }

    /// Blurs, then keeps every other pixel: the next coarser pyramid level,
    /// `ceil(width / 2) × ceil(height / 2)`.
    pub fn downsample(&self) -> FloatImage {
        let blurred = self.blur();
        let (w, h) = (self.width.div_ceil(2), self.height.div_ceil(2));
        let c = self.channels;
        let mut out = FloatImage::new(w, h, c);
        for y in 0..h {
            for x in 0..w {
                let src = ((2 * y) * self.width + 2 * x) * c;
                let dst = (y * w + x) * c;
                out.data[dst..dst + c].copy_from_slice(&blurred.data[src..src + c]);
            }
        }
        out
    }

    /// A Gaussian pyramid, finest level first: at most `levels` images, stopping before a level
    /// would be smaller than `min_size` pixels on either side.
    pub fn gaussian_pyramid(&self, levels: usize, min_size: usize) -> Vec<FloatImage> {
        let mut pyramid = vec![self.clone()];
        while pyramid.len() < levels {
            let last = pyramid.last().expect("pyramid starts with one level");
            if last.width.div_ceil(2) < min_size || last.height.div_ceil(2) < min_size {
                break;
            }
            let next = last.downsample();
            pyramid.push(next);
        }
        pyramid
    }

    /// The levels of [`gaussian_pyramid`](Self::gaussian_pyramid) above this one (without a copy
    /// of this image): at most `levels − 1` images, coarser and coarser.
    pub fn coarser_levels(&self, levels: usize, min_size: usize) -> Vec<FloatImage> {
        coarser_chain(self, levels, min_size, |image| (image.width, image.height), FloatImage::downsample)
    }

    /// Stacks the channels of several images of the same size into one image.
    pub fn stack(images: &[&FloatImage]) -> Result<FloatImage, InvalidParameter> {
        let first = images.first().ok_or_else(|| InvalidParameter::new("images", 0, "must list at least one image"))?;
        let (w, h) = (first.width, first.height);
        if let Some(other) = images.iter().find(|image| image.width != w || image.height != h) {
            return Err(InvalidParameter::new(
                "images",
                format!("{}×{}", other.width, other.height),
                format!("must all be {w}×{h}"),
            ));
        }
        let channels: usize = images.iter().map(|image| image.channels).sum();
        let mut data = Vec::with_capacity(w * h * channels);
        for index in 0..w * h {
            for image in images {
                data.extend_from_slice(&image.data[index * image.channels..(index + 1) * image.channels]);
            }
        }
        Ok(FloatImage { width: w, height: h, channels, data })
    }
}

/// The binomial filter `[1 4 6 4 1] / 16` of the pyramids (float and 8-bit levels share it, so an
/// 8-bit level is the float level rounded).
pub(crate) const TAPS: [f32; 5] = [1.0 / 16.0, 4.0 / 16.0, 6.0 / 16.0, 4.0 / 16.0, 1.0 / 16.0];

/// Fails unless `values` is `width × height × channels` with at least one channel.
pub(crate) fn check_layout(
    width: usize,
    height: usize,
    channels: usize,
    values: usize,
) -> Result<(), InvalidParameter> {
    if channels == 0 || values != width * height * channels {
        return Err(InvalidParameter::new(
            "data",
            values,
            format!("must hold width × height × channels = {} values (channels ≥ 1)", width * height * channels),
        ));
    }
    Ok(())
}

/// The pyramid levels above `finest`, each `next` of the one before: at most `levels − 1`,
/// stopping before one would be smaller than `min_size` on either side.
pub(crate) fn coarser_chain<T>(
    finest: &T,
    levels: usize,
    min_size: usize,
    size: impl Fn(&T) -> (usize, usize),
    next: impl Fn(&T) -> T,
) -> Vec<T> {
    let mut coarser: Vec<T> = Vec::new();
    while coarser.len() + 1 < levels {
        let last = coarser.last().unwrap_or(finest);
        let (width, height) = size(last);
        if width.div_ceil(2) < min_size || height.div_ceil(2) < min_size {
            break;
        }
        let level = next(last);
        coarser.push(level);
    }
    coarser
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float_round_trip_is_exact() {
        let image = RgbaImage::from_fn(7, 5, |x, y| [(x * 30) as u8, (y * 50) as u8, 7, (x * y * 9) as u8]);
        assert_eq!(RgbaImage::from_float(&image.to_float()), image);
        let rgb = image.to_float_channels(&[0, 1, 2]);
        assert_eq!(rgb.channels(), 3);
        assert_eq!(RgbaImage::from_float(&rgb).get(3, 2), [90, 100, 7, 255]);
    }

    #[test]
    fn bilinear_interpolates_between_centres_and_clamps() {
        let image = FloatImage::from_data(2, 1, 1, vec![0.0, 1.0]).unwrap();
        let mut out = [0.0];
        image.sample_bilinear(1.0, 0.5, &mut out);
        assert!((out[0] - 0.5).abs() < 1e-6);
        image.sample_bilinear(-10.0, 0.5, &mut out);
        assert_eq!(out[0], 0.0);
        image.sample_bilinear(1.5, 0.5, &mut out);
        assert_eq!(out[0], 1.0);
    }

    #[test]
    fn pyramid_halves_sizes_and_keeps_the_mean() {
        let image = RgbaImage::from_fn(33, 20, |x, y| [((x * 7 + y * 3) % 256) as u8, 0, 0, 255]).to_float();
        let pyramid = image.gaussian_pyramid(10, 4);
        let sizes: Vec<(usize, usize)> = pyramid.iter().map(|level| (level.width(), level.height())).collect();
        assert_eq!(sizes, [(33, 20), (17, 10), (9, 5)]);
        let mean = |img: &FloatImage| img.data().iter().step_by(4).sum::<f32>() / (img.width() * img.height()) as f32;
        assert!((mean(&pyramid[0]) - mean(&pyramid[1])).abs() < 0.05);
    }

    #[test]
    fn blur_preserves_constants() {
        let image = FloatImage::from_data(4, 3, 2, vec![0.25; 24]).unwrap();
        assert!(image.blur().data().iter().all(|v| (v - 0.25).abs() < 1e-6));
    }

    #[test]
    fn premultiply_round_trips_and_alpha_helpers() {
        let image = RgbaImage::from_fn(4, 4, |x, y| if x == 1 && y == 2 { [200, 100, 50, 128] } else { [9, 9, 9, 0] });
        assert_eq!(image.opaque_bounds(), Some((1, 2, 2, 3)));
        assert_eq!(image.count_alpha_at_least(1), 1);
        assert!(!image.is_fully_transparent() && !image.is_fully_opaque());
        let mut float = image.to_float();
        float.premultiply();
        assert!(float.pixel(0, 0)[0] == 0.0);
        float.unpremultiply();
        assert!((float.pixel(1, 2)[0] - 200.0 / 255.0).abs() < 1e-5);
        assert_eq!(image.over_background([255, 255, 255]).get(0, 0), [255, 255, 255, 255]);
    }

    #[test]
    fn stack_concatenates_channels_and_rejects_mismatched_sizes() {
        let a = FloatImage::from_data(2, 1, 1, vec![1.0, 2.0]).unwrap();
        let b = FloatImage::from_data(2, 1, 2, vec![3.0, 4.0, 5.0, 6.0]).unwrap();
        let stacked = FloatImage::stack(&[&a, &b]).unwrap();
        assert_eq!(stacked.data(), &[1.0, 3.0, 4.0, 2.0, 5.0, 6.0]);
        let c = FloatImage::new(3, 1, 1);
        assert!(FloatImage::stack(&[&a, &c]).is_err());
        assert!(FloatImage::from_data(2, 2, 1, vec![0.0; 3]).is_err());
    }
}
