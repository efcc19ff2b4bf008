//! `--legend`: a folder of CLASS.png textures or a STYLE.json, else the built-in legend.

use std::path::Path;

use anyhow::{Context as _, bail};
use motif_jobs::tiles::{Fill, Legend, MapClass};

/// The built-in legend: real GIMP textures (`data/real/maps/legend`, see its README), one per
/// class, compiled in so that `motif tiles` works from any folder.
const BUILT_IN: [(&str, &[u8]); 8] = [
    ("land", include_bytes!("../../../../../data/real/maps/legend/land.png")),
    ("water", include_bytes!("../../../../../data/real/maps/legend/water.png")),
    ("grass", include_bytes!("../../../../../data/real/maps/legend/grass.png")),
    ("forest", include_bytes!("../../../../../data/real/maps/legend/forest.png")),
    ("building", include_bytes!("../../../../../data/real/maps/legend/building.png")),
    ("rail", include_bytes!("../../../../../data/real/maps/legend/rail.png")),
    ("minor-road", include_bytes!("../../../../../data/real/maps/legend/minor-road.png")),
    ("major-road", include_bytes!("../../../../../data/real/maps/legend/major-road.png")),
];

/// Largest side of a legend texture: the atlas holds every class at the largest one's size.
const MAX_TEXTURE_SIDE: usize = 512;

/// The legend `--legend` names, or the built-in one.
pub(super) fn read(path: Option<&Path>, max_memory: u64) -> anyhow::Result<Legend> {
    let Some(path) = path else { return built_in() };
    if path.is_dir() { from_folder(path, max_memory) } else { from_json(path, max_memory) }
}

fn built_in() -> anyhow::Result<Legend> {
    let mut legend = Legend::plain();
    for (name, bytes) in BUILT_IN {
        let class = MapClass::named(name).context("a built-in class")?;
        let image = motif_io::decode_image(bytes.to_vec(), Path::new(&format!("built-in legend {name}.png")))?;
        legend = legend.with(class, Fill::Texture(image));
    }
    Ok(legend)
}

fn texture(path: &Path, max_memory: u64) -> anyhow::Result<Fill> {
    let image = motif_io::read_image_within(path, motif_io::ImageBudget::max_memory(max_memory))?;
    if image.width() > MAX_TEXTURE_SIDE || image.height() > MAX_TEXTURE_SIDE {
        bail!(
            "{}: a legend texture is {}×{}, at most {MAX_TEXTURE_SIDE} pixels a side are allowed (a tileable pattern, \
             not a whole picture)",
            path.display(),
            image.width(),
            image.height()
        );
    }
    Ok(Fill::Texture(image))
}

fn class_names() -> String {
    MapClass::ALL.iter().map(|class| class.name()).collect::<Vec<_>>().join(", ")
}

fn from_folder(folder: &Path, max_memory: u64) -> anyhow::Result<Legend> {
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
        bail!("{}: the legend folder has no CLASS.png texture; classes are {}", folder.display(), class_names());
    }
    Ok(legend)
}

fn from_json(path: &Path, max_memory: u64) -> anyhow::Result<Legend> {
    let text = motif_io::read_text(path)?;
    let value: serde_json::Value = serde_json::from_str(&text)
        .with_context(|| format!("{}: --legend is neither a folder nor a JSON file", path.display()))?;
    let Some(entries) = value.as_object() else {
        bail!("{}: a legend is a JSON object {{\"CLASS\": \"texture.png\" or \"#RRGGBB\"}}", path.display())
    };
    let folder = path.parent().unwrap_or(Path::new("."));
    let mut legend = Legend::plain();
    for (name, fill) in entries {
        let Some(class) = MapClass::named(name) else {
            bail!("{}: no class named '{name}'; classes are {}", path.display(), class_names())
        };
        let Some(fill) = fill.as_str() else {
            bail!("{}: the fill of '{name}' must be a texture file name or \"#RRGGBB\"", path.display())
        };
        let fill = if let Some(hex) = fill.strip_prefix('#') {
            let colour: motif_jobs::options::Colour = format!("#{hex}")
                .try_into()
                .map_err(|error: String| anyhow::anyhow!("{}: '{name}': {error}", path.display()))?;
            Fill::Colour(colour.0)
        } else {
            texture(&folder.join(fill), max_memory)?
        };
        legend = legend.with(class, fill);
    }
    Ok(legend)
}
