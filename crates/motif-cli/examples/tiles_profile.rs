//! The stylized tiles of `motif bench --engine stylize --case tiles` (Helsinki, zoom 16) rendered
//! again and again on one thread, for a profiler: `cargo run --release -p motif-cli --example
//! tiles_profile [PASSES] [TEXTURE_LEVELS]`, or under `perf record`. Prints the median tile of each
//! pass, once the textures of zoom 16 are made.

use std::io::Write;

use motif_jobs::Job;
use motif_jobs::tiles::{Layer, TilesInputs, TilesJob};

fn main() -> anyhow::Result<()> {
    let passes: usize = std::env::args().nth(1).map_or(Ok(5), |a| a.parse())?;
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/maps");
    let (map, _) = motif_io::read_osm(&folder.join("Helsinki.osm.pbf"), u64::MAX)?;
    let legend = motif_io::read_legend(None, u64::MAX)?;
    let mut job = TilesJob { seed: 1, zoom: Some([16, 16]), ..TilesJob::new() };
    if let Some(levels) = std::env::args().nth(2) {
        job.options.texture_levels = levels.parse()?;
    }
    let run = job.run(TilesInputs { map, legend }, &mut motif_core::NoProgress)?;
    let tiles = run.pyramid()?;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let start = std::time::Instant::now();
    pool.install(|| run.render(tiles[0], Layer::Stylized))?;
    let first = start.elapsed().as_secs_f64();
    writeln!(std::io::stdout().lock(), "first tile (with its textures): {first:.1} s")?;
    for pass in 0..passes {
        let mut ms: Vec<f64> = pool.install(|| {
            tiles
                .iter()
                .map(|&tile| {
                    let start = std::time::Instant::now();
                    run.render(tile, Layer::Stylized).map(|_| start.elapsed().as_secs_f64() * 1000.0)
                })
                .collect::<Result<_, _>>()
        })?;
        ms.sort_by(f64::total_cmp);
        let (median, max) = (ms[ms.len() / 2], ms[ms.len() - 1]);
        writeln!(std::io::stdout().lock(), "pass {pass}: {} tiles, median {median:.1} ms, max {max:.1} ms", ms.len())?;
    }
    Ok(())
}
