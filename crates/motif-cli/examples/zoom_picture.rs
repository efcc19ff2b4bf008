//! The picture of `docs/maps.md`'s "Zooming in": a Helsinki tile at the base zoom (15), then its
//! four tiles at zoom 16 with the texture pyramid (the default), then the same four with one
//! level of textures for every zoom, side by side, each zoom-16 block shrunk to the tile's size
//! by averaging 2 × 2 pixels. `cargo run --release -p motif-cli --example zoom_picture OUT.png`.

use motif_core::RgbaImage;
use motif_jobs::Job;
use motif_jobs::tiles::{Layer, TileId, TileSet, TilesInputs, TilesJob, halved};

fn main() -> anyhow::Result<()> {
    let out = std::env::args().nth(1).ok_or_else(|| anyhow::anyhow!("usage: zoom_picture OUT.png"))?;
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/maps");
    let (map, _) = motif_io::read_osm(&folder.join("Helsinki.osm.pbf"), u64::MAX)?;
    let legend = motif_io::read_legend(None, u64::MAX)?;
    let run = TilesJob { seed: 1, zoom: Some([15, 16]), ..TilesJob::new() }
        .run(TilesInputs { map, legend: legend.clone() }, &mut motif_core::NoProgress)?;
    let one_level = run.tiles.params().clone().with_texture_levels(1);
    let flat = TileSet::with_textures(run.tiles.map().clone(), &legend, &one_level, run.tiles.textures().to_vec())?;
    // The zoom-15 tile over the seam figure's block (16/37307/18967).
    let parent = TileId::new(15, 18653, 9483)?;
    let shrunk = |tiles: &TileSet| -> anyhow::Result<RgbaImage> { Ok(halved(&tiles.render_zooming_in(parent)?.1)) };
    let panels = [run.tiles.render(parent, Layer::Stylized)?, shrunk(&run.tiles)?, shrunk(&flat)?];
    let (size, gap) = (panels[0].width(), 8);
    let picture = RgbaImage::from_fn(3 * size + 2 * gap, size, |x, y| {
        let (panel, at) = (x / (size + gap), x % (size + gap));
        if at >= size { [255, 255, 255, 255] } else { panels[panel].get(at, y) }
    });
    motif_io::write_png(std::path::Path::new(&out), &picture)?;
    Ok(())
}
