//! PNG, JPEG and WebP through the `image` crate.

use std::io::BufWriter;
use std::path::Path;

use image::{ImageDecoder, ImageFormat, ImageReader, Limits};
use motif_core::RgbaImage;
use motif_core::memory::Bytes;

use crate::{IoError, Result, write_with};

pub use motif_core::limits::{MAX_IMAGE_PIXELS as MAX_PIXELS, MAX_MAP_PIXELS};

/// What reading one image may cost, checked against the size its header declares before any
/// pixel is decoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ImageBudget {
    /// The most pixels accepted.
    pub max_pixels: u64,
    /// The most bytes the read may hold at once: the file, the decoded samples and the RGBA copy.
    pub max_bytes: u64,
    /// What sets `max_bytes`, for messages (a flag such as `--max-memory`).
    pub bytes_from: &'static str,
}

impl Default for ImageBudget {
    /// [`MAX_PIXELS`], and as many bytes as such an image needs.
    fn default() -> Self {
        Self { max_pixels: MAX_PIXELS, max_bytes: u64::MAX, bytes_from: "the image size limit" }
    }
}

impl ImageBudget {
    /// [`MAX_PIXELS`] and at most `bytes`, which come from `--max-memory`.
    pub fn max_memory(bytes: u64) -> Self {
        Self { max_bytes: bytes, bytes_from: "--max-memory", ..Self::default() }
    }

    /// The budget of a tone map: [`MAX_MAP_PIXELS`] and at most `bytes` from `--max-memory`.
    pub fn map(bytes: u64) -> Self {
        Self::max_memory(bytes).with_max_pixels(MAX_MAP_PIXELS)
    }

    /// The same budget with at most `pixels` pixels.
    pub fn with_max_pixels(self, pixels: u64) -> Self {
        Self { max_pixels: pixels.min(MAX_PIXELS), ..self }
    }
}

/// Reads a PNG (8-bit or 16-bit; grey, grey-alpha, RGB or RGBA), JPEG or WebP as 8-bit RGBA, within
/// the default [`ImageBudget`].
///
/// The format is detected from the content, not the name, so a text file named `.png` is
/// reported as such.
pub fn read_image(path: &Path) -> Result<RgbaImage> {
    read_image_within(path, ImageBudget::default())
}

/// [`read_image`] within `budget`: an image whose header declares more pixels or bytes is refused
/// before it is decoded.
pub fn read_image_within(path: &Path, budget: ImageBudget) -> Result<RgbaImage> {
    decode_image_within(crate::read_bytes(path)?, path, budget)
}

/// Decodes PNG, JPEG or WebP bytes as [`read_image`] does; `path` is the file (or label) errors name.
pub fn decode_image(bytes: Vec<u8>, path: &Path) -> Result<RgbaImage> {
    decode_image_within(bytes, path, ImageBudget::default())
}

/// [`decode_image`] within `budget`.
pub fn decode_image_within(bytes: Vec<u8>, path: &Path, budget: ImageBudget) -> Result<RgbaImage> {
    let (width, height, decoded) = decode(bytes, path, budget, 4)?;
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

/// Reads a 16-bit PNG as 16-bit RGBA within the default [`ImageBudget`]; `None` when the file
/// holds 8-bit samples (or is a JPEG).
pub fn read_png16(path: &Path) -> Result<Option<Rgba16>> {
    read_png16_within(path, ImageBudget::default())
}

/// [`read_png16`] within `budget`.
pub fn read_png16_within(path: &Path, budget: ImageBudget) -> Result<Option<Rgba16>> {
    let (width, height, decoded) = decode(crate::read_bytes(path)?, path, budget, 8)?;
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

/// Decodes PNG, JPEG or WebP bytes within `budget`, into samples a caller copies to `bytes_per_pixel`
/// RGBA (4 or 8): the declared size is checked before decoding, and a JPEG must be complete.
fn decode(
    bytes: Vec<u8>,
    path: &Path,
    budget: ImageBudget,
    bytes_per_pixel: u64,
) -> Result<(u32, u32, image::DynamicImage)> {
    let reader = ImageReader::new(std::io::Cursor::new(&bytes[..]))
        .with_guessed_format()
        .map_err(|source| IoError::Io { path: path.to_path_buf(), source })?;
    let format = reader
        .format()
        .ok_or_else(|| IoError::format(path, "is not a PNG, JPEG or WebP image (unrecognized content)"))?;
    if format == ImageFormat::Jpeg && !jpeg_is_complete(&bytes) {
        return Err(IoError::format(path, "the JPEG is truncated or damaged: it ends before its end-of-image marker"));
    }
    let mut decoder =
        reader.into_decoder().map_err(|error| IoError::format(path, format!("cannot decode image: {error}")))?;
    let (width, height) = decoder.dimensions();
    let needed =
        check_budget(path, (width, height), decoder.total_bytes(), bytes.len() as u64, bytes_per_pixel, budget)?;
    let mut limits = Limits::default();
    limits.max_alloc = Some(needed.max(1 << 20));
    decoder.set_limits(limits).map_err(|error| IoError::format(path, error.to_string()))?;
    let decoded = image::DynamicImage::from_decoder(decoder)
        .map_err(|error| IoError::format(path, format!("cannot decode image: {error}")))?;
    if width == 0 || height == 0 {
        return Err(IoError::format(path, "image is empty (0 pixels)"));
    }
    Ok((width, height, decoded))
}

/// The bytes reading a `width × height` image holds at once (the file, the decoded samples, the
/// RGBA copy and the pixel list made from it), or an error naming the declared size and the limit
/// it passes.
fn check_budget(
    path: &Path,
    (width, height): (u32, u32),
    decoded_bytes: u64,
    file_bytes: u64,
    bytes_per_pixel: u64,
    budget: ImageBudget,
) -> Result<u64> {
    let pixels = u64::from(width) * u64::from(height);
    if pixels > budget.max_pixels {
        return Err(IoError::format(
            path,
            format!(
                "image is declared {width}×{height} ({pixels} pixels); at most {} pixels are accepted",
                budget.max_pixels
            ),
        ));
    }
    let needed = file_bytes.saturating_add(decoded_bytes).saturating_add(2 * pixels * bytes_per_pixel);
    if needed > budget.max_bytes {
        return Err(IoError::format(
            path,
            format!(
                "image is declared {width}×{height}; decoding it needs about {}, more than the {} allowed by {}",
                Bytes(needed),
                Bytes(budget.max_bytes),
                budget.bytes_from
            ),
        ));
    }
    Ok(needed)
}

/// Whether a JPEG's marker segments run from its start-of-image to an end-of-image marker
/// (`FF D9`); the decoder fills a truncated file's missing blocks with grey without an error.
/// Segment lengths are followed, so a thumbnail's own end marker inside `APP1` does not count.
fn jpeg_is_complete(bytes: &[u8]) -> bool {
    let mut i = 2;
    while i + 1 < bytes.len() {
        if bytes[i] != 0xFF {
            // Stray bytes between segments: decoders skip them, and so does this walk.
            i += 1;
            continue;
        }
        let marker = bytes[i + 1];
        match marker {
            0xD9 => return true,
            // Fill bytes before a marker.
            0xFF => i += 1,
            // Markers without a length.
            0x01 | 0xD0..=0xD7 => i += 2,
            _ => {
                let Some(length) = bytes.get(i + 2..i + 4).map(|b| usize::from(u16::from_be_bytes([b[0], b[1]])))
                else {
                    return false;
                };
                i += 2 + length;
                if marker == 0xDA {
                    i = end_of_scan(bytes, i);
                }
            }
        }
    }
    false
}

/// Where the entropy-coded data starting at `start` ends: the first `FF` followed by a marker
/// other than a restart (`FF 00` is a stuffed data byte), or the end of the bytes.
fn end_of_scan(bytes: &[u8], start: usize) -> usize {
    let mut i = start;
    while i + 1 < bytes.len() {
        if bytes[i] == 0xFF && !matches!(bytes[i + 1], 0x00 | 0xD0..=0xD7 | 0xFF) {
            return i;
        }
        i += 1;
    }
    bytes.len()
}

/// An 8-bit RGBA image as PNG bytes (for tiles served or packed rather than written alone).
pub fn encode_png(image: &RgbaImage) -> Vec<u8> {
    let mut bytes = Vec::new();
    let encoder = image::codecs::png::PngEncoder::new(&mut bytes);
    // Writing into memory fails only for an image too large for PNG, which no tile is.
    let (width, height) = (image.width() as u32, image.height() as u32);
    let _ = image::ImageEncoder::write_image(encoder, image.as_bytes(), width, height, image::ExtendedColorType::Rgba8);
    bytes
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

    fn jpeg_bytes(width: u32, height: u32) -> Vec<u8> {
        let mut bytes = Vec::new();
        let photo = image::RgbImage::from_fn(width, height, |x, y| image::Rgb([(x * 9) as u8, (y * 5) as u8, 90]));
        image::codecs::jpeg::JpegEncoder::new_with_quality(&mut bytes, 90).encode_image(&photo).unwrap();
        bytes
    }

    #[test]
    fn truncated_jpegs_are_refused_and_complete_ones_read() {
        let dir = tempfile::tempdir().unwrap();
        let bytes = jpeg_bytes(64, 48);
        let path = dir.path().join("cut.jpg");
        // Cut inside the scan data, at its end, and just before the end marker's second byte.
        for length in [bytes.len() / 2, bytes.len() - 2, bytes.len() - 1] {
            std::fs::write(&path, &bytes[..length]).unwrap();
            let message = read_image(&path).unwrap_err().to_string();
            assert!(message.contains("cut.jpg") && message.contains("truncated"), "{length}: {message}");
        }
        // Bytes after the end marker (some cameras append data) do not make a complete file an error.
        let mut trailing = bytes.clone();
        trailing.extend_from_slice(b"\0\0trailer");
        std::fs::write(&path, &trailing).unwrap();
        assert_eq!(read_image(&path).unwrap().width(), 64);
    }

    #[test]
    fn lossless_webp_reads_exactly_and_a_cut_one_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let image = RgbaImage::from_fn(23, 11, |x, y| [(x * 11) as u8, (y * 23) as u8, 77, 255 - (x * y) as u8]);
        let mut bytes = Vec::new();
        let encoder = image::codecs::webp::WebPEncoder::new_lossless(&mut bytes);
        image::ImageEncoder::write_image(encoder, image.as_bytes(), 23, 11, image::ExtendedColorType::Rgba8).unwrap();
        let path = dir.path().join("texture.webp");
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(read_image(&path).unwrap(), image);
        let cut = dir.path().join("cut.webp");
        std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
        assert!(read_image(&cut).unwrap_err().to_string().contains("cut.webp"));
    }

    #[test]
    fn a_declared_size_past_the_budget_is_refused_before_decoding() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("large.png");
        write_png(&path, &RgbaImage::filled(300, 200, [1, 2, 3, 4])).unwrap();
        let fits = ImageBudget::max_memory(1 << 20);
        assert_eq!(read_image_within(&path, fits).unwrap().width(), 300);
        let small = ImageBudget::max_memory(500_000);
        let message = read_image_within(&path, small).unwrap_err().to_string();
        assert!(
            message.contains("large.png") && message.contains("300×200") && message.contains("--max-memory"),
            "{message}"
        );
        let message = read_image_within(&path, ImageBudget::default().with_max_pixels(50_000)).unwrap_err().to_string();
        assert!(message.contains("300×200") && message.contains("at most 50000 pixels"), "{message}");
        let message = read_png16_within(&path, small).unwrap_err().to_string();
        assert!(message.contains("--max-memory"), "{message}");
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
