//! `motif bench --engine stylize --case tiles`: the stylized map of the real Helsinki extract
//! (`data/real/maps`), tile by tile on one thread (issue 36, item 4), and the seam figure of a
//! 4 × 4 block of tiles rendered apart against the same block rendered whole (item 3).

use motif_core::RgbaImage;
use motif_jobs::Job;
use motif_jobs::tiles::{Layer, Legend, TileId, TileSet, TilesInputs, TilesJob, TilesRun, seam_error, zoom_error};
use serde_json::{Value, json};

use std::io::{BufRead, BufReader};

use crate::suite::Bench;

/// Milliseconds of `f`, and its value.
fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let start = std::time::Instant::now();
    let value = f();
    (value, start.elapsed().as_secs_f64() * 1000.0)
}

/// The `q`-quantile of sorted values (nearest rank).
fn quantile(sorted: &[f64], q: f64) -> f64 {
    sorted[((sorted.len() as f64 * q).ceil() as usize).clamp(1, sorted.len()) - 1]
}

/// The `span × span` tiles from `first` rendered apart and joined.
fn joined(run: &TilesRun, first: TileId, span: u32, layer: Layer) -> anyhow::Result<RgbaImage> {
    let size = run.tiles.params().tile_size;
    let side = size * span as usize;
    let mut tiles = Vec::new();
    for dy in 0..span {
        for dx in 0..span {
            tiles.push(run.render(TileId::new(first.z, first.x + dx, first.y + dy)?, layer)?);
        }
    }
    let span = span as usize;
    Ok(RgbaImage::from_fn(side, side, |x, y| tiles[(y / size) * span + x / size].get(x % size, y % size)))
}

pub(super) fn tiles(bench: &Bench) -> anyhow::Result<Value> {
    let folder = crate::suite::corpus_folder("maps");
    let (map, _) = motif_io::read_osm(&folder.join("Helsinki.osm.pbf"), u64::MAX)?;
    let legend = motif_io::read_legend(None, u64::MAX)?;
    let job = TilesJob { seed: bench.seed, zoom: Some([16, 16]), ..TilesJob::new() };
    let inputs = TilesInputs { map, legend: legend.clone() };
    let (run, presynth_ms) = timed(|| job.run(inputs, &mut motif_core::NoProgress));
    let run = run?;
    let mut tiles = run.pyramid()?;
    if bench.quick {
        tiles.truncate(4);
    }
    // One core: the target is per tile on one thread once the presynthesis is made.
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let mut figures = serde_json::Map::new();
    // The texture pyramid's level for this zoom is made once, by the first tile that needs it:
    // the timing is of tiles once every texture is there (the "warm cache").
    let (warm, level_ms) = timed(|| tiles.first().map(|&tile| run.render(tile, Layer::Stylized)).transpose());
    warm?;
    figures.insert("texture_level_ms".into(), json!(level_ms));
    for layer in [Layer::Stylized, Layer::Plain] {
        let mut ms: Vec<f64> =
            pool.install(|| tiles.iter().map(|&tile| timed(|| run.render(tile, layer)).1).collect::<Vec<f64>>());
        ms.sort_by(f64::total_cmp);
        figures.insert(
            layer.name().into(),
            json!({"tiles": ms.len(), "median_ms": quantile(&ms, 0.5), "p95_ms": quantile(&ms, 0.95), "max_ms": quantile(&ms, 1.0)}),
        );
    }
    // Seams over a 4 × 4 block inside the map (2 × 2 when quick), apart against whole.
    let span = if bench.quick { 2 } else { 4 };
    let first =
        tiles.iter().copied().min().ok_or_else(|| anyhow::anyhow!("the Helsinki extract gave no tile at zoom 16"))?;
    let first = TileId::new(first.z, first.x, first.y + 1)?;
    let apart = joined(&run, first, span, Layer::Stylized)?;
    let whole = run.tiles.render_block(first, span as usize, Layer::Stylized)?;
    let size = run.tiles.params().tile_size;
    let differing = apart.pixels().iter().zip(whole.pixels()).filter(|(a, b)| a != b).count();
    figures.insert(
        "seams".into(),
        json!({
            "block": [span, span], "first_tile": [first.z, first.x, first.y],
            "apart": seam_error(&apart, size), "whole": seam_error(&whole, size),
            "pixels_differing_from_whole": differing as f64 / apart.pixels().len() as f64,
        }),
    );
    figures.insert("zoom".into(), zoom_figures(&run, &legend, first)?);
    let server = server_throughput(&folder.join("Helsinki.osm.pbf"), run.tiles.map().bounds(), bench)?;
    figures.insert("server".into(), server);
    figures.insert("presynth_ms".into(), json!(presynth_ms));
    figures.insert("margin".into(), run.figures["margin"].clone());
    figures.insert("threads".into(), json!(1));
    Ok(Value::Object(figures))
}

/// Zooming in (item 3): the tile of the base zoom over `child` against its four tiles at the
/// next zoom, with the run's texture pyramid and with one level of textures for every zoom (the
/// same first textures), at the tile's pixels and at half and a quarter of its scale.
fn zoom_figures(run: &TilesRun, legend: &Legend, child: TileId) -> anyhow::Result<Value> {
    let params = run.tiles.params();
    let parent = TileId::new(
        params.base_zoom,
        child.x >> (child.z - params.base_zoom),
        child.y >> (child.z - params.base_zoom),
    )?;
    let one_level = params.clone().with_texture_levels(1);
    let flat = TileSet::with_textures(run.tiles.map().clone(), legend, &one_level, run.tiles.textures().to_vec())?;
    let (tile, pyramid) = run.tiles.render_zooming_in(parent)?;
    let (same_tile, without) = flat.render_zooming_in(parent)?;
    anyhow::ensure!(tile == same_tile, "the base zoom's tile differs between the two tile sets");
    let errors =
        |children: &RgbaImage| (0..3).map(|coarser| zoom_error(&tile, children, coarser)).collect::<Vec<f64>>();
    Ok(json!({
        "parent_tile": [parent.z, parent.x, parent.y],
        "texture_levels": params.texture_levels,
        "pyramid": errors(&pyramid),
        "one_level": errors(&without),
        "scales": ["tile pixels", "half", "quarter"],
    }))
}

/// A load generator's client (`ureq`, one kept-alive connection per client): every request's
/// whole answer waited for at most 60 s, a status other than 200 counted as a failure.
fn client() -> ureq::Agent {
    ureq::Agent::config_builder()
        .timeout_global(Some(std::time::Duration::from_secs(60)))
        .http_status_as_error(false)
        .build()
        .into()
}

/// One GET of `url` by `agent`, read to its end: whether it answered 200 with a body.
fn fetched(agent: &ureq::Agent, url: &str) -> bool {
    agent.get(url).call().is_ok_and(|mut response| {
        response.status() == 200 && response.body_mut().read_to_vec().is_ok_and(|body| !body.is_empty())
    })
}

/// `motif tiles serve` (this binary, 2 workers) under a bounded local load: 4 clients request
/// the tiles of zoom 16 and 17 over the map (every one rendered: cold), then the same again (the
/// disk cache: warm); tiles per second of each pass. Requests go to 127.0.0.1 only, each pass
/// a fixed count, each request at most 60 s.
fn server_throughput(map: &std::path::Path, bounds: [f64; 4], bench: &Bench) -> anyhow::Result<Value> {
    let cache = std::env::temp_dir().join(format!("motif-bench-tiles-{}", std::process::id()));
    let mut server = std::process::Command::new(std::env::current_exe()?)
        .args(["--quiet", "--seed", &bench.seed.to_string(), "tiles", "serve", "--port", "0", "--workers", "2"])
        .arg("--map")
        .arg(map)
        .arg("--cache-dir")
        .arg(&cache)
        .stdout(std::process::Stdio::piped())
        .spawn()?;
    let result = (|| -> anyhow::Result<Value> {
        let mut line = String::new();
        BufReader::new(server.stdout.take().ok_or_else(|| anyhow::anyhow!("no server output"))?)
            .read_line(&mut line)?;
        let address = line.trim().trim_start_matches("http://").trim_end_matches('/').to_string();
        let zooms: &[u8] = if bench.quick { &[15] } else { &[16, 17] };
        let paths: Vec<String> = zooms
            .iter()
            .flat_map(|&z| motif_jobs::tiles::tiles_covering(bounds, z))
            .map(|tile| format!("/{}/{}/{}.png", tile.z, tile.x, tile.y))
            .collect();
        let pass = |paths: &[String]| -> anyhow::Result<(f64, usize)> {
            let start = std::time::Instant::now();
            let failures = std::thread::scope(|scope| {
                let clients: Vec<_> = (0..4)
                    .map(|k| {
                        let address = &address;
                        scope.spawn(move || {
                            let agent = client();
                            let url = |path: &String| format!("http://{address}{path}");
                            paths.iter().skip(k).step_by(4).filter(|path| !fetched(&agent, &url(path))).count()
                        })
                    })
                    .collect();
                clients.into_iter().map(|client| client.join().unwrap_or(usize::MAX)).sum::<usize>()
            });
            Ok((paths.len() as f64 / start.elapsed().as_secs_f64(), failures))
        };
        let (cold, cold_failures) = pass(&paths)?;
        let (warm, warm_failures) = pass(&paths)?;
        Ok(json!({
            "tiles": paths.len(), "clients": 4, "workers": 2, "zooms": zooms,
            "cold_tiles_per_s": cold, "warm_tiles_per_s": warm, "failed": cold_failures + warm_failures,
        }))
    })();
    let _ = server.kill();
    let _ = server.wait();
    let _ = std::fs::remove_dir_all(&cache);
    result
}
