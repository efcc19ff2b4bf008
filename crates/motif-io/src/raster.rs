//! PNG and JPEG through the `image` crate.

use std::io::BufWriter;
use std::path::Path;

use image::{ImageDecoder, ImageReader, Limits};
use motif_core::RgbaImage;

use crate::{IoError, Result, write_with};

/// The largest image accepted, in pixels (16 384 × 16 384); larger files are refused with a
/// message instead of exhausting memory.
pub const MAX_PIXELS: u64 = 16_384 * 16_384;

/// Reads a PNG (8-bit or 16-bit; grey, grey-alpha, RGB or RGBA) or JPEG as 8-bit RGBA.
///
/// The format is detected from the content, not the name, so a text file named `.png` is
/// reported as such.
pub fn read_image(path: &Path) -> Result<RgbaImage> {
    decode_image(crate::read_bytes(path)?, path)
}

/// Decodes PNG or JPEG bytes as [`read_image`] does; `path` is the file (or label) errors name.
pub fn decode_image(bytes: Vec<u8>, path: &Path) -> Result<RgbaImage> {
    let (width, height, decoded) = decode(bytes, path)?;
    let rgba = decoded.to_rgba8();
    let pixels = rgba.pixels().map(|pixel| pixel.0).collect();
    RgbaImage::from_pixels(width as usize, height as usize, pixels)
        .map_err(|error| IoError::format(path, error.to_string()))
}

/// A 16-bit RGBA raster, row by row.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Rgba16 {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Row-major pixels.
    pub pixels: Vec<[u16; 4]>,
}

/// Reads a 16-bit PNG as 16-bit RGBA; `None` when the file holds 8-bit samples (or is a JPEG).
pub fn read_png16(path: &Path) -> Result<Option<Rgba16>> {
    let (width, height, decoded) = decode(crate::read_bytes(path)?, path)?;
    if decoded.color().bytes_per_pixel() / decoded.color().channel_count() < 2 {
        return Ok(None);
    }
    let pixels = decoded.to_rgba16().pixels().map(|pixel| pixel.0).collect();
    Ok(Some(Rgba16 { width: width as usize, height: height as usize, pixels }))
}

/// Writes a 16-bit RGBA PNG atomically.
pub fn write_png16(path: &Path, image: &Rgba16) -> Result<()> {
    if image.width == 0 || image.height == 0 || image.pixels.len() != image.width * image.height {
        return Err(IoError::format(path, "refusing to write an empty or inconsistent image"));
    }
    let width = u32::try_from(image.width).map_err(|_| IoError::format(path, "image too wide"))?;
    let height = u32::try_from(image.height).map_err(|_| IoError::format(path, "image too tall"))?;
    // The encoder takes 16-bit samples in native byte order (it writes them big-endian).
    let bytes: Vec<u8> = image.pixels.iter().flatten().flat_map(|v| v.to_ne_bytes()).collect();
    write_with(path, |file| {
        let encoder = image::codecs::png::PngEncoder::new(BufWriter::new(file));
        image::ImageEncoder::write_image(encoder, &bytes, width, height, image::ExtendedColorType::Rgba16)
            .map_err(std::io::Error::other)
    })
}

/// Decodes PNG or JPEG bytes within the size limits.
fn decode(bytes: Vec<u8>, path: &Path) -> Result<(u32, u32, image::DynamicImage)> {
    let reader = ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|source| IoError::Io { path: path.to_path_buf(), source })?;
    if reader.format().is_none() {
        return Err(IoError::format(path, "is not a PNG or JPEG image (unrecognized content)"));
    }
    let mut decoder =
        reader.into_decoder().map_err(|error| IoError::format(path, format!("cannot decode image: {error}")))?;
    let (width, height) = decoder.dimensions();
    if u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(IoError::format(
            path,
            format!("image is {width}×{height}; at most {MAX_PIXELS} pixels (16384×16384) are accepted"),
        ));
    }
    let mut limits = Limits::default();
    limits.max_alloc = Some(MAX_PIXELS * 8 * 2);
    decoder.set_limits(limits).map_err(|error| IoError::format(path, error.to_string()))?;
    let decoded = image::DynamicImage::from_decoder(decoder)
        .map_err(|error| IoError::format(path, format!("cannot decode image: {error}")))?;
    if width == 0 || height == 0 {
        return Err(IoError::format(path, "image is empty (0 pixels)"));
    }
    Ok((width, height, decoded))
}

/// Writes an 8-bit RGBA PNG atomically.
pub fn write_png(path: &Path, image: &RgbaImage) -> Result<()> {
    if image.is_empty() {
        return Err(IoError::format(path, "refusing to write an empty image"));
    }
    let width = u32::try_from(image.width()).map_err(|_| IoError::format(path, "image too wide"))?;
    let height = u32::try_from(image.height()).map_err(|_| IoError::format(path, "image too tall"))?;
    write_with(path, |file| {
        let encoder = image::codecs::png::PngEncoder::new(BufWriter::new(file));
        image::ImageEncoder::write_image(encoder, image.as_bytes(), width, height, image::ExtendedColorType::Rgba8)
            .map_err(std::io::Error::other)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png16_round_trip_is_exact_and_8_bit_files_are_told_apart() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a16.png");
        let pixels =
            (0..13 * 7).map(|i| [i as u16 * 701, 65535 - i as u16, 300 + i as u16, (i % 2) as u16 * 65535]).collect();
        let image = Rgba16 { width: 13, height: 7, pixels };
        write_png16(&path, &image).unwrap();
        assert_eq!(read_png16(&path).unwrap(), Some(image));
        let eight = dir.path().join("a8.png");
        write_png(&eight, &RgbaImage::from_fn(3, 2, |x, y| [x as u8, y as u8, 0, 255])).unwrap();
        assert_eq!(read_png16(&eight).unwrap(), None);
    }

    #[test]
    fn png_round_trip_is_exact() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.png");
        let image = RgbaImage::from_fn(13, 7, |x, y| [(x * 19) as u8, (y * 37) as u8, 200, (x * y * 3) as u8]);
        write_png(&path, &image).unwrap();
        assert_eq!(read_image(&path).unwrap(), image);
    }

    #[test]
    fn grey_rgb_and_sixteen_bit_pngs_read_as_rgba() {
        let dir = tempfile::tempdir().unwrap();
        let grey = dir.path().join("grey.png");
        image::GrayImage::from_fn(3, 2, |x, _| image::Luma([(x * 100) as u8])).save(&grey).unwrap();
        assert_eq!(read_image(&grey).unwrap().get(2, 1), [200, 200, 200, 255]);
        let rgb = dir.path().join("rgb.png");
        image::RgbImage::from_fn(2, 2, |_, _| image::Rgb([1, 2, 3])).save(&rgb).unwrap();
        assert_eq!(read_image(&rgb).unwrap().get(1, 1), [1, 2, 3, 255]);
        let deep = dir.path().join("deep.png");
        image::ImageBuffer::<image::Rgba<u16>, _>::from_fn(2, 1, |_, _| image::Rgba([65535, 0, 32896, 65535]))
            .save(&deep)
            .unwrap();
        assert_eq!(read_image(&deep).unwrap().get(0, 0), [255, 0, 128, 255]);
        let jpeg = dir.path().join("photo.jpg");
        image::RgbImage::from_fn(8, 8, |_, _| image::Rgb([128, 128, 128])).save(&jpeg).unwrap();
        let photo = read_image(&jpeg).unwrap();
        assert!((i32::from(photo.get(4, 4)[0]) - 128).abs() <= 2);
    }

    #[test]
    fn missing_and_fake_pngs_give_errors_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("missing.png");
        assert!(read_image(&missing).unwrap_err().to_string().contains("missing.png"));
        let fake = dir.path().join("fake.png");
        std::fs::write(&fake, "this is text, not an image").unwrap();
        let message = read_image(&fake).unwrap_err().to_string();
        assert!(message.contains("fake.png") && message.contains("not a PNG"), "{message}");
        let truncated = dir.path().join("truncated.png");
        let good = dir.path().join("good.png");
        write_png(&good, &RgbaImage::filled(40, 40, [1, 2, 3, 4])).unwrap();
        let bytes = std::fs::read(&good).unwrap();
        std::fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
        assert!(read_image(&truncated).unwrap_err().to_string().contains("truncated.png"));
    }
}
