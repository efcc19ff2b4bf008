//! `motif tiles`: a stylized slippy map from an OpenStreetMap extract: `render` packs a pyramid
//! into one PMTiles archive, `serve` answers `/{z}/{x}/{y}.png` on 127.0.0.1.

mod serve;

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use clap::{Args, ValueEnum};
use motif_jobs::Job;
use motif_jobs::tiles::{Layer, MAX_ZOOM, TileId, TilesInputs, TilesJob, TilesOptions, TilesRun};
use rayon::prelude::*;

use crate::context::Context;
use crate::job_args::JobArgs;

/// What `motif tiles` does.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum TilesAction {
    /// Render every tile of --zoom over the map into one PMTiles archive (--out).
    Render,
    /// Serve tiles on demand on 127.0.0.1:--port (stylized at /{z}/{x}/{y}.png, plain at
    /// /plain/{z}/{x}/{y}.png), rendering each once into --cache-dir.
    Serve,
}

/// Which layer `render` packs.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayerArg {
    /// The map stylized with the legend's textures.
    Stylized,
    /// The plain segment map, each class in its colour.
    Plain,
}

impl From<LayerArg> for Layer {
    fn from(layer: LayerArg) -> Self {
        match layer {
            LayerArg::Stylized => Layer::Stylized,
            LayerArg::Plain => Layer::Plain,
        }
    }
}

/// Options of `motif tiles`.
#[derive(Args, Debug)]
pub struct TilesArgs {
    /// `render` a pyramid into one archive, or `serve` tiles over HTTP.
    #[arg(value_enum)]
    pub action: TilesAction,
    /// The OpenStreetMap extract (.osm.pbf), e.g. data/real/maps/Helsinki.osm.pbf.
    #[arg(long, value_name = "MAP.osm.pbf")]
    pub map: PathBuf,
    /// What each class looks like: a folder of CLASS.png textures (land, water, grass, forest,
    /// building, rail, minor-road, major-road), or a JSON file mapping class names to texture
    /// files (relative to it) or "#RRGGBB" colours. A class left out keeps its plain colour.
    /// Default: the built-in legend, real GIMP textures (data/real/maps/legend).
    #[arg(long, value_name = "DIR|STYLE.json")]
    pub legend: Option<PathBuf>,
    /// Zoom levels of the pyramid `render` packs, LOW-HIGH or one level; levels 12 to 16 when
    /// not given.
    #[arg(long, value_name = "LOW-HIGH", value_parser = parse_zoom)]
    pub zoom: Option<[u8; 2]>,
    /// The layer `render` packs.
    #[arg(long, value_enum, default_value = "stylized")]
    pub layer: LayerArg,
    /// The PMTiles archive `render` writes.
    #[arg(long, value_name = "TILES.pmtiles")]
    pub out: Option<PathBuf>,
    /// The port `serve` listens on, on 127.0.0.1 only; 0 = any free port (printed).
    #[arg(long, value_name = "N", default_value_t = 8080)]
    pub port: u16,
    /// Folder where `serve` keeps every tile it rendered, reused by later runs of the same map,
    /// legend, options and seed. Default: motif-tiles in the system's temporary folder.
    #[arg(long, value_name = "DIR")]
    pub cache_dir: Option<PathBuf>,
    /// Tiles `serve` renders at once (requests beyond wait their turn). Default: --threads.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=256))]
    pub workers: Option<u16>,
    /// `serve` stops after answering this many requests (for scripts and tests). Default: never.
    #[arg(long, value_name = "N")]
    pub max_requests: Option<u64>,
    /// Every option of the tiles, declared in `motif_jobs::tiles` (`TilesOptions`).
    #[command(flatten)]
    pub options: JobArgs<TilesOptions>,
}

fn parse_zoom(text: &str) -> Result<[u8; 2], String> {
    let bad = || format!("'{text}': expected LOW-HIGH or one zoom level, whole numbers from 0 to {MAX_ZOOM}");
    let (low, high) = text.split_once('-').unwrap_or((text, text));
    let low: u8 = low.trim().parse().map_err(|_| bad())?;
    let high: u8 = high.trim().parse().map_err(|_| bad())?;
    if low > high || high > MAX_ZOOM {
        return Err(bad());
    }
    Ok([low, high])
}

/// Runs `motif tiles`.
pub(crate) fn run(args: &TilesArgs, context: &mut Context) -> anyhow::Result<()> {
    let mut inputs: Vec<&Path> = vec![&args.map];
    if let Some(legend) = &args.legend {
        inputs.push(legend);
    }
    match args.action {
        TilesAction::Render => {
            let Some(out) = &args.out else { anyhow::bail!("motif tiles render needs --out TILES.pmtiles") };
            context.check_output(out, &inputs)?;
        }
        TilesAction::Serve => {
            if args.out.is_some() {
                anyhow::bail!("--out is for `motif tiles render`; `serve` answers requests (see --cache-dir)");
            }
        }
    }
    let (map, counts) = motif_io::read_osm(&args.map, context.max_memory)?;
    let legend = motif_io::read_legend(args.legend.as_deref(), context.max_memory)?;
    let job = TilesJob { seed: context.seed, zoom: args.zoom, options: args.options.options.clone() };
    // The server's cache and ETags name everything a tile depends on, read before the run takes them.
    let key = match args.action {
        TilesAction::Serve => Some(serve::run_key(&args.map, &legend, &job)?),
        TilesAction::Render => None,
    };
    let run = job.run(TilesInputs { map, legend }, context.progress())?;
    context.job_figures(run.figures.clone());
    context
        .figure("osm", serde_json::json!({"nodes": counts.nodes, "ways": counts.ways, "relations": counts.relations}));
    match args.action {
        TilesAction::Render => render(args, &job, &run, context),
        TilesAction::Serve => serve::serve(args, key.unwrap_or_default(), run, context),
    }
}

/// Renders the pyramid into one PMTiles archive.
fn render(args: &TilesArgs, job: &TilesJob, run: &TilesRun, context: &mut Context) -> anyhow::Result<()> {
    let out = args.out.as_deref().context("no --out")?;
    let tiles = run.pyramid()?;
    let layer = Layer::from(args.layer);
    // The texture pyramid's levels these zooms take, made once before the tiles (reported apart).
    let levels_start = std::time::Instant::now();
    if layer == Layer::Stylized {
        run.make_texture_levels(run.zooms[1])?;
    }
    let levels_ms = levels_start.elapsed().as_secs_f64() * 1000.0;
    let start = std::time::Instant::now();
    // In chunks, so that progress is told between them (the bar lives on this thread).
    let mut rendered: Vec<(TileId, Vec<u8>)> = Vec::with_capacity(tiles.len());
    for chunk in tiles.chunks(4 * context.threads.max(1)) {
        let pngs = chunk
            .par_iter()
            .map(|&tile| Ok((tile, motif_io::encode_png(&run.render(tile, layer)?))))
            .collect::<Result<Vec<_>, motif_jobs::JobError>>()?;
        rendered.extend(pngs);
        context.progress().report("rendering tiles", rendered.len() as f64 / tiles.len() as f64);
    }
    let ms = start.elapsed().as_secs_f64() * 1000.0;
    let name = args.map.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let header = job.archive_header(run, &name, layer);
    let info = motif_io::PyramidInfo {
        zooms: (header.zooms[0], header.zooms[1]),
        bounds: header.bounds,
        metadata: header.metadata,
    };
    motif_io::write_pmtiles(out, &info, &rendered)?;
    let bytes: usize = rendered.iter().map(|(_, png)| png.len()).sum();
    context.figure("tiles", rendered.len());
    context.figure("layer", layer.name());
    context.figure("render_ms", ms);
    context.figure("texture_levels_ms", levels_ms);
    context.figure("ms_per_tile", ms / rendered.len().max(1) as f64);
    context.figure("tile_bytes", bytes);
    context.summary(&format!(
        "motif tiles: {} {} tiles of zoom {}-{} ({:.0} ms a tile on {} threads, margin {}{}{}) → {}",
        rendered.len(),
        layer.name(),
        run.zooms[0],
        run.zooms[1],
        ms / rendered.len().max(1) as f64,
        context.threads,
        run.tiles.report().margin,
        if run.tiles.report().margin_inferred { " (inferred)" } else { "" },
        if levels_ms >= 1.0 {
            format!("; texture pyramid made first, {:.1} s", levels_ms / 1000.0)
        } else {
            String::new()
        },
        out.display()
    ));
    Ok(())
}
