//! Map legends: a folder of CLASS.png textures or a STYLE.json, else the built-in legend.

use std::path::Path;

use motif_maps::{Fill, Legend, MapClass};

use crate::{IoError, Result};

/// The built-in legend: real GIMP textures (`data/real/maps/legend`, see its README), one per
/// class, compiled in so that `motif tiles` works from any folder.
const BUILT_IN: [(&str, &[u8]); 8] = [
    ("land", include_bytes!("../../../data/real/maps/legend/land.png")),
    ("water", include_bytes!("../../../data/real/maps/legend/water.png")),
    ("grass", include_bytes!("../../../data/real/maps/legend/grass.png")),
    ("forest", include_bytes!("../../../data/real/maps/legend/forest.png")),
    ("building", include_bytes!("../../../data/real/maps/legend/building.png")),
    ("rail", include_bytes!("../../../data/real/maps/legend/rail.png")),
    ("minor-road", include_bytes!("../../../data/real/maps/legend/minor-road.png")),
    ("major-road", include_bytes!("../../../data/real/maps/legend/major-road.png")),
];

/// Largest side of a legend texture: the atlas holds every class at the largest one's size.
const MAX_TEXTURE_SIDE: usize = 512;

/// The legend at `path` (a folder of CLASS.png textures, or a JSON file mapping class names to
/// texture files relative to it or `"#RRGGBB"` colours; classes left out keep their plain colour),
/// or the built-in one when `path` is `None`. Textures are checked against `max_memory` before
/// they are decoded.
pub fn read_legend(path: Option<&Path>, max_memory: u64) -> Result<Legend> {
    let Some(path) = path else { return built_in() };
    if path.is_dir() { from_folder(path, max_memory) } else { from_json(path, max_memory) }
}

fn built_in() -> Result<Legend> {
    let mut legend = Legend::plain();
    for (class, (name, bytes)) in MapClass::ALL.into_iter().zip(BUILT_IN) {
        debug_assert_eq!(class.name(), name);
        let image = crate::decode_image(bytes.to_vec(), Path::new(&format!("built-in legend {name}.png")))?;
        legend = legend.with(class, Fill::Texture(image));
    }
    Ok(legend)
}

fn texture(path: &Path, max_memory: u64) -> Result<Fill> {
    let image = crate::read_image_within(path, crate::ImageBudget::max_memory(max_memory))?;
    if image.width() > MAX_TEXTURE_SIDE || image.height() > MAX_TEXTURE_SIDE {
        return Err(IoError::format(
            path,
            format!(
                "a legend texture is {}×{}, at most {MAX_TEXTURE_SIDE} pixels a side are allowed (a tileable \
                 pattern, not a whole picture)",
                image.width(),
                image.height()
            ),
        ));
    }
    Ok(Fill::Texture(image))
}

fn class_names() -> String {
    MapClass::ALL.iter().map(|class| class.name()).collect::<Vec<_>>().join(", ")
}

fn from_folder(folder: &Path, max_memory: u64) -> Result<Legend> {
    let mut legend = Legend::plain();
    let mut found = 0;
    for class in MapClass::ALL {
        for extension in ["png", "jpg", "jpeg"] {
            let file = folder.join(format!("{}.{extension}", class.name()));
            if file.is_file() {
                legend = legend.with(class, texture(&file, max_memory)?);
                found += 1;
                break;
            }
        }
    }
    if found == 0 {
        return Err(IoError::format(
            folder,
            format!("the legend folder has no CLASS.png texture; classes are {}", class_names()),
        ));
    }
    Ok(legend)
}

fn from_json(path: &Path, max_memory: u64) -> Result<Legend> {
    let text = crate::read_text(path)?;
    let refused = |message: String| IoError::format(path, message);
    let value: serde_json::Value = serde_json::from_str(&text)
        .map_err(|error| refused(format!("a legend is a folder or a JSON file, and this is neither: {error}")))?;
    let Some(entries) = value.as_object() else {
        return Err(refused("a legend is a JSON object {\"CLASS\": \"texture.png\" or \"#RRGGBB\"}".into()));
    };
    let folder = path.parent().unwrap_or(Path::new("."));
    let mut legend = Legend::plain();
    for (name, fill) in entries {
        let Some(class) = MapClass::named(name) else {
            return Err(refused(format!("no class named '{name}'; classes are {}", class_names())));
        };
        let Some(fill) = fill.as_str() else {
            return Err(refused(format!("the fill of '{name}' must be a texture file name or \"#RRGGBB\"")));
        };
        let fill = match fill.strip_prefix('#') {
            Some(hex) => Fill::Colour(colour(hex).ok_or_else(|| {
                refused(format!("'{name}': `{fill}` is not a colour: write #RRGGBB in hexadecimal, e.g. #8b1a1a"))
            })?),
            None => texture(&folder.join(fill), max_memory)?,
        };
        legend = legend.with(class, fill);
    }
    Ok(legend)
}

/// `RRGGBB` in hexadecimal.
fn colour(hex: &str) -> Option<[u8; 3]> {
    if hex.len() != 6 || !hex.is_ascii() {
        return None;
    }
    let channel = |k: usize| u8::from_str_radix(&hex[2 * k..2 * k + 2], 16).ok();
    Some([channel(0)?, channel(1)?, channel(2)?])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn legends_come_from_folders_json_or_the_built_in_textures() {
        let built = read_legend(None, u64::MAX).unwrap();
        assert_eq!(built.textured().len(), 8);
        let dir = tempfile::tempdir().unwrap();
        let water = motif_core::RgbaImage::from_fn(4, 3, |x, y| [x as u8, y as u8, 9, 255]);
        crate::write_png(&dir.path().join("water.png"), &water).unwrap();
        let folder = read_legend(Some(dir.path()), u64::MAX).unwrap();
        assert_eq!(folder.textured(), vec![MapClass::Water]);
        let style = dir.path().join("style.json");
        crate::write_text(&style, r##"{"water": "water.png", "land": "#102030"}"##).unwrap();
        let json = read_legend(Some(&style), u64::MAX).unwrap();
        assert_eq!(json.fill(MapClass::Land), &Fill::Colour([16, 32, 48]));
        assert_eq!(json.fill(MapClass::Water), &Fill::Texture(water));
        for (text, says) in [
            (r##"{"sea": "#000000"}"##, "no class named 'sea'"),
            (r##"{"land": "#12345"}"##, "not a colour"),
            (r#"{"land": 3}"#, "texture file name"),
            ("[1]", "JSON object"),
            ("not json", "neither"),
        ] {
            crate::write_text(&style, text).unwrap();
            let error = read_legend(Some(&style), u64::MAX).unwrap_err().to_string();
            assert!(error.contains(says) && error.contains("style.json"), "{text}: {error}");
        }
        let empty = tempfile::tempdir().unwrap();
        assert!(read_legend(Some(empty.path()), u64::MAX).unwrap_err().to_string().contains("no CLASS.png"));
    }
}
