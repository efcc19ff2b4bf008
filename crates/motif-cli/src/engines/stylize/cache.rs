//! The folder `motif presynth` writes and `motif stylize --presynth` reads (§3.7): per segment
//! colour a texture (`segment-N.png`) and the field it was copied by (`segment-N-nnf.png`), and
//! `presynth.json` listing them.
//!
//! A run's files are renamed into place in the order they were written and the manifest is
//! written last, so a killed `presynth` can leave new textures beside the previous manifest. The
//! manifest therefore records a checksum of each file's pixels and a generation id over all of
//! them; a file that does not match is reported as a partial cache, never used.

use std::path::Path;

use anyhow::{Context as _, bail};
use motif_core::RgbaImage;
use motif_jobs::stylize::{NearestNeighbourField, SegmentTexture};
use serde::{Deserialize, Serialize};

/// The manifest's file name.
pub(super) const MANIFEST: &str = "presynth.json";

/// The manifest of a presynth folder.
#[derive(Serialize, Deserialize, Debug)]
struct Manifest {
    patch_size: usize,
    /// Identifies this build of the cache: a checksum over the patch size and every entry.
    /// Absent in caches of older versions (their files are then used unchecked).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    generation: Option<String>,
    segments: Vec<Entry>,
}

#[derive(Serialize, Deserialize, Debug)]
struct Entry {
    /// Guide colour as `#rrggbb` (or `#rrggbbaa`, `#gg` for grey guides).
    colour: String,
    file: String,
    /// Checksum of the texture's decoded pixels (see [`checksum`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    checksum: Option<String>,
    /// Where each texture pixel came from (the presynthesis field as written by `--debug-dir`'s
    /// `nnf.png`): seeds the band's field. Absent in older caches (random start then).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    field: Option<String>,
    /// Checksum of the field image's decoded pixels.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    field_checksum: Option<String>,
}

/// CRC-32 of an image's size and RGBA bytes, as 8 hex digits: what was decoded, so a re-encoded
/// but identical image still matches, and a texture of another run does not.
fn checksum(image: &RgbaImage) -> String {
    let mut hasher = crc32fast::Hasher::new();
    hasher.update(&(image.width() as u64).to_le_bytes());
    hasher.update(&(image.height() as u64).to_le_bytes());
    hasher.update(image.as_bytes());
    format!("{:08x}", hasher.finalize())
}

fn generation(patch_size: usize, segments: &[Entry]) -> String {
    let mut hasher = crc32fast::Hasher::new();
    hasher.update(&(patch_size as u64).to_le_bytes());
    for entry in segments {
        for text in [&entry.colour, &entry.file, entry.checksum.as_ref().unwrap_or(&String::new())] {
            hasher.update(text.as_bytes());
            hasher.update(&[0]);
        }
    }
    format!("{:08x}", hasher.finalize())
}

fn hex(colour: &[f32]) -> String {
    colour.iter().map(|v| format!("{:02x}", (v.clamp(0.0, 1.0) * 255.0).round() as u8)).collect::<String>()
}

fn parse_hex(text: &str) -> anyhow::Result<Vec<f32>> {
    let digits = text.trim_start_matches('#');
    if digits.is_empty() || !digits.len().is_multiple_of(2) || digits.len() > 8 {
        bail!("`{text}` is not a #rrggbb colour");
    }
    (0..digits.len() / 2)
        .map(|i| {
            u8::from_str_radix(&digits[2 * i..2 * i + 2], 16)
                .map(|v| f32::from(v) / 255.0)
                .map_err(|_| anyhow::anyhow!("`{text}` is not a #rrggbb colour"))
        })
        .collect()
}

/// Writes the textures, their fields and, last, the manifest into `dir` (which must exist).
/// Returns the generation id.
pub(super) fn write(dir: &Path, patch_size: usize, textures: &[SegmentTexture]) -> anyhow::Result<String> {
    let mut segments = Vec::with_capacity(textures.len());
    for (index, texture) in textures.iter().enumerate() {
        let file = format!("segment-{}.png", index + 1);
        let image = RgbaImage::from_float(&texture.image);
        motif_io::write_png(&dir.join(&file), &image)?;
        // The field seeds the band's search; a source too large for its PNG encoding just goes without.
        let (field, field_checksum) = match texture.field.as_ref().map(NearestNeighbourField::to_rgba) {
            Some(Ok(encoded)) => {
                let name = format!("segment-{}-nnf.png", index + 1);
                motif_io::write_png(&dir.join(&name), &encoded)?;
                (Some(name), Some(checksum(&encoded)))
            }
            _ => (None, None),
        };
        let colour = format!("#{}", hex(&texture.colour));
        segments.push(Entry { colour, file, checksum: Some(checksum(&image)), field, field_checksum });
    }
    let generation = generation(patch_size, &segments);
    let manifest = Manifest { patch_size, generation: Some(generation.clone()), segments };
    motif_io::write_json(&dir.join(MANIFEST), &manifest)?;
    Ok(generation)
}

/// Reads the image `file` of the cache in `dir` and checks it against its manifest checksum.
fn read_checked(dir: &Path, file: &str, expected: Option<&String>) -> anyhow::Result<RgbaImage> {
    let path = dir.join(file);
    let image = motif_io::read_image(&path)?;
    if let Some(expected) = expected
        && checksum(&image) != *expected
    {
        bail!(
            "{} is a partial presynth cache: {} does not match {} (another run's file, or an interrupted `motif \
             presynth`); run `motif presynth` again to rebuild it",
            dir.display(),
            path.display(),
            MANIFEST
        );
    }
    Ok(image)
}

/// The textures of the cache in `dir` for a style of `style`'s size and channels, made with
/// `patch_size`, and the cache's generation id (`None` for caches of older versions).
pub(super) fn read(
    dir: &Path,
    style: &impl motif_core::ChannelImage,
    patch_size: usize,
) -> anyhow::Result<(Vec<SegmentTexture>, Option<String>)> {
    let manifest_path = dir.join(MANIFEST);
    let manifest: Manifest = motif_io::read_json(&manifest_path)
        .with_context(|| format!("cannot read {} (make it with `motif presynth`)", manifest_path.display()))?;
    if manifest.patch_size != patch_size {
        bail!(
            "the textures in {} were made with --patch-size {} but this run uses {patch_size}",
            dir.display(),
            manifest.patch_size,
        );
    }
    if let Some(recorded) = &manifest.generation
        && *recorded != generation(manifest.patch_size, &manifest.segments)
    {
        bail!(
            "{} does not match its own generation id {recorded} (edited by hand, or written by another version); run \
             `motif presynth` again to rebuild it",
            manifest_path.display()
        );
    }
    // Only files of the folder: a manifest names nothing elsewhere on the disk (checked before
    // any is read).
    for entry in &manifest.segments {
        for file in std::iter::once(&entry.file).chain(&entry.field) {
            motif_io::file_in_folder(dir, file)
                .with_context(|| format!("{} names files elsewhere", manifest_path.display()))?;
        }
    }
    let mut loaded = Vec::with_capacity(manifest.segments.len());
    for entry in &manifest.segments {
        let image = read_checked(dir, &entry.file, entry.checksum.as_ref())?;
        let image = if style.channels() == 4 { image.to_float() } else { image.to_float_channels(&[0, 1, 2]) };
        let field = match &entry.field {
            Some(file) => {
                let encoded = read_checked(dir, file, entry.field_checksum.as_ref())?;
                let field = NearestNeighbourField::from_rgba(&encoded, style.width(), style.height(), patch_size)
                    .with_context(|| format!("{} does not fit the style", dir.join(file).display()))?;
                Some(field)
            }
            None => None,
        };
        loaded.push(SegmentTexture { colour: parse_hex(&entry.colour)?, image, field });
    }
    Ok((loaded, manifest.generation))
}

#[cfg(test)]
mod tests {
    use super::*;
    use motif_core::FloatImage;

    fn texture(colour: f32, shade: f32) -> SegmentTexture {
        let image = FloatImage::from_data(6, 5, 3, vec![shade; 6 * 5 * 3]).unwrap();
        SegmentTexture { colour: vec![colour; 3], image, field: None }
    }

    #[test]
    fn a_cache_reads_back_and_a_mixed_one_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let style = FloatImage::new(6, 5, 3);
        let first = write(dir.path(), 5, &[texture(0.0, 0.2), texture(1.0, 0.8)]).unwrap();
        let (textures, generation) = read(dir.path(), &style, 5).unwrap();
        assert_eq!(generation.as_deref(), Some(first.as_str()));
        assert_eq!(textures.len(), 2);
        assert_eq!(RgbaImage::from_float(&textures[1].image), RgbaImage::from_float(&texture(1.0, 0.8).image));
        // Another run's texture in place of the first (a killed run renamed it, not the manifest).
        let other = tempfile::tempdir().unwrap();
        let second = write(other.path(), 5, &[texture(0.0, 0.5), texture(1.0, 0.8)]).unwrap();
        assert_ne!(first, second);
        std::fs::copy(other.path().join("segment-1.png"), dir.path().join("segment-1.png")).unwrap();
        let message = format!("{:#}", read(dir.path(), &style, 5).unwrap_err());
        assert!(message.contains("partial presynth cache") && message.contains("segment-1.png"), "{message}");
        // A manifest edited by hand no longer matches its generation.
        let text = std::fs::read_to_string(other.path().join(MANIFEST)).unwrap();
        std::fs::write(other.path().join(MANIFEST), text.replace("segment-2.png", "segment-1.png")).unwrap();
        let message = format!("{:#}", read(other.path(), &style, 5).unwrap_err());
        assert!(message.contains("generation"), "{message}");
        // A manifest naming files outside its folder is refused before any is read.
        for outside in ["/etc/passwd", "../segment-1.png", "sub/segment-1.png"] {
            let text = std::fs::read_to_string(dir.path().join(MANIFEST)).unwrap();
            let mut manifest: Manifest = serde_json::from_str(&text).unwrap();
            manifest.segments[0].file = outside.to_string();
            manifest.generation = Some(super::generation(manifest.patch_size, &manifest.segments));
            let edited = tempfile::tempdir().unwrap();
            std::fs::write(edited.path().join(MANIFEST), serde_json::to_string(&manifest).unwrap()).unwrap();
            let message = format!("{:#}", read(edited.path(), &style, 5).unwrap_err());
            assert!(message.contains("names files elsewhere") && message.contains(outside), "{message}");
        }
        #[cfg(unix)]
        {
            let linked = tempfile::tempdir().unwrap();
            std::fs::copy(dir.path().join(MANIFEST), linked.path().join(MANIFEST)).unwrap();
            std::fs::copy(dir.path().join("segment-2.png"), linked.path().join("segment-2.png")).unwrap();
            std::os::unix::fs::symlink(dir.path().join("segment-1.png"), linked.path().join("segment-1.png")).unwrap();
            let message = format!("{:#}", read(linked.path(), &style, 5).unwrap_err());
            assert!(message.contains("leads out of"), "{message}");
        }
        // Another patch size is refused by name.
        let message = format!("{:#}", read(dir.path(), &style, 7).unwrap_err());
        assert!(message.contains("--patch-size 5"), "{message}");
    }

    proptest::proptest! {
        #![proptest_config(proptest::test_runner::Config {
            cases: 128,
            rng_seed: proptest::test_runner::RngSeed::Fixed(20261202),
            failure_persistence: None,
            ..Default::default()
        })]

        /// A manifest with any bytes changed, cut or inserted reads as textures or as an error
        /// naming the folder or file; never a panic.
        #[test]
        fn damaged_manifests_are_refused_cleanly(
            edits in proptest::collection::vec((proptest::prelude::any::<usize>(), proptest::prelude::any::<u8>(), 0..3u8), 1..6),
        ) {
            let dir = tempfile::tempdir().unwrap();
            write(dir.path(), 5, &[texture(0.0, 0.2), texture(1.0, 0.8)]).unwrap();
            let mut bytes = std::fs::read(dir.path().join(MANIFEST)).unwrap();
            for (at, byte, kind) in edits {
                if bytes.is_empty() {
                    break;
                }
                let at = at % bytes.len();
                match kind {
                    0 => bytes[at] = byte,
                    1 => bytes.truncate(at),
                    _ => bytes.insert(at, byte),
                }
            }
            std::fs::write(dir.path().join(MANIFEST), &bytes).unwrap();
            if let Err(error) = read(dir.path(), &FloatImage::new(6, 5, 3), 5) {
                let message = format!("{error:#}");
                proptest::prop_assert!(message.contains(&dir.path().display().to_string()), "{}", message);
            }
        }
    }
}
