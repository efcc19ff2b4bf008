//! `motif tiles serve`: tiles on demand over HTTP on 127.0.0.1 (`tiny_http`), each rendered once
//! into a disk cache, with ETags, by a bounded pool of workers.
//!
//! A tile's ETag names the run (a digest of the map file, the legend, the job and the version)
//! and the tile, so a client's copy stays valid across restarts while nothing changed; the cache
//! folder is keyed by the same digest.

use std::io::Read as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use anyhow::Context as _;
use motif_jobs::tiles::{Layer, TileId, TilesJob, TilesRun};
use tiny_http::{Header, Method, Request, Response, Server};

use super::TilesArgs;
use crate::context::Context;

/// The page `/` answers: what the server offers.
const INDEX: &str = "<!doctype html><meta charset=utf-8><title>motif tiles</title>\
<h1>motif tiles</h1><p>Stylized tiles: <code>/{z}/{x}/{y}.png</code>; the plain segment map: \
<code>/plain/{z}/{x}/{y}.png</code>; the run: <code>/tiles.json</code>.</p>";

/// What every worker shares.
struct Shared<'a> {
    run: &'a TilesRun,
    cache: PathBuf,
    key: String,
    served: AtomicU64,
    rendered: AtomicU64,
    max_requests: Option<u64>,
    info: String,
}

/// Serves until `--max-requests` requests were answered (or forever).
pub(super) fn serve(args: &TilesArgs, job: &TilesJob, run: &TilesRun, context: &mut Context) -> anyhow::Result<()> {
    let key = run_key(args, job)?;
    let cache = args.cache_dir.clone().unwrap_or_else(|| std::env::temp_dir().join("motif-tiles")).join(&key);
    motif_io::create_folder(&cache)?;
    let server = Server::http(("127.0.0.1", args.port))
        .map_err(|error| anyhow::anyhow!("cannot listen on 127.0.0.1:{}: {error}", args.port))?;
    let address = server.server_addr().to_ip().context("the server has no IP address")?;
    let workers = args.workers.map_or(context.threads, usize::from).max(1);
    let [x0, y0, x1, y1] = run.tiles.map().bounds();
    let centre = motif_jobs::tiles::unproject([(x0 + x1) / 2.0, (y0 + y1) / 2.0]);
    let info = serde_json::json!({
        "tiles": ["/{z}/{x}/{y}.png"], "plain": ["/plain/{z}/{x}/{y}.png"],
        "minzoom": run.zooms[0], "maxzoom": motif_jobs::tiles::MAX_ZOOM.min(20),
        "center": [centre.0, centre.1, run.zooms[0].max(14)], "tile_size": run.tiles.params().tile_size,
        "attribution": "© OpenStreetMap contributors (ODbL)",
    })
    .to_string();
    let shared = Shared {
        run,
        cache,
        key,
        served: AtomicU64::new(0),
        rendered: AtomicU64::new(0),
        max_requests: args.max_requests,
        info,
    };
    // The address on stdout (what a script reads, --port 0 included), the rest on stderr.
    #[allow(clippy::print_stdout, reason = "the server's address is the command's output")]
    {
        println!("http://{address}/");
    }
    let _ = std::io::Write::flush(&mut std::io::stdout());
    context.summary(&format!(
        "motif tiles: serving http://{address}/{{z}}/{{x}}/{{y}}.png and /plain/{{z}}/{{x}}/{{y}}.png ({workers} workers, \
         cache {}); Ctrl-C stops",
        shared.cache.display()
    ));
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| work(&server, &shared));
        }
    });
    context.figure("requests", shared.served.load(Ordering::SeqCst));
    context.figure("rendered", shared.rendered.load(Ordering::SeqCst));
    Ok(())
}

/// One worker: answers requests until the server is told to stop.
fn work(server: &Server, shared: &Shared<'_>) {
    while let Ok(request) = server.recv() {
        answer(request, shared);
        let served = shared.served.fetch_add(1, Ordering::SeqCst) + 1;
        if shared.max_requests.is_some_and(|max| served >= max) {
            server.unblock();
        }
        if shared.max_requests.is_some_and(|max| shared.served.load(Ordering::SeqCst) >= max) {
            // Wake every other worker too: each `unblock` releases one `recv`.
            server.unblock();
            return;
        }
    }
}

fn header(name: &str, value: &str) -> Header {
    Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("ASCII header")
}

fn answer(request: Request, shared: &Shared<'_>) {
    let url = request.url().split('?').next().unwrap_or("").to_string();
    if *request.method() != Method::Get && *request.method() != Method::Head {
        let _ = request.respond(Response::from_string("only GET and HEAD\n").with_status_code(405));
        return;
    }
    match url.as_str() {
        "/" => {
            let _ = request
                .respond(Response::from_string(INDEX).with_header(header("Content-Type", "text/html; charset=utf-8")));
            return;
        }
        "/tiles.json" => {
            let response = Response::from_string(shared.info.clone())
                .with_header(header("Content-Type", "application/json"))
                .with_header(header("Access-Control-Allow-Origin", "*"));
            let _ = request.respond(response);
            return;
        }
        _ => {}
    }
    let Some((layer, tile)) = parse_tile(&url) else {
        let _ = request.respond(
            Response::from_string(format!(
                "no tile at {url}: ask /{{z}}/{{x}}/{{y}}.png or /plain/{{z}}/{{x}}/{{y}}.png with x and y below 2^z\n"
            ))
            .with_status_code(404),
        );
        return;
    };
    let etag = format!("\"{}-{}-{}-{}-{}\"", shared.key, layer.name(), tile.z, tile.x, tile.y);
    let matches = request
        .headers()
        .iter()
        .any(|h| h.field.equiv("If-None-Match") && h.value.as_str().split(',').any(|v| v.trim() == etag));
    let common = |response: Response<std::io::Cursor<Vec<u8>>>| {
        response
            .with_header(header("ETag", &etag))
            .with_header(header("Cache-Control", "public, max-age=3600"))
            .with_header(header("Access-Control-Allow-Origin", "*"))
    };
    if matches {
        let _ = request.respond(common(Response::from_data(Vec::new())).with_status_code(304));
        return;
    }
    match tile_bytes(shared, layer, tile) {
        Ok(png) => {
            let _ = request.respond(common(Response::from_data(png)).with_header(header("Content-Type", "image/png")));
        }
        Err(error) => {
            let _ = request
                .respond(Response::from_string(format!("cannot render {url}: {error:#}\n")).with_status_code(500));
        }
    }
}

/// `/{z}/{x}/{y}.png` (stylized) or `/plain/{z}/{x}/{y}.png`, checked.
fn parse_tile(url: &str) -> Option<(Layer, TileId)> {
    let (layer, rest) = match url.strip_prefix("/plain/") {
        Some(rest) => (Layer::Plain, rest),
        None => (Layer::Stylized, url.strip_prefix('/')?),
    };
    let mut parts = rest.strip_suffix(".png")?.split('/');
    let z: u8 = parts.next()?.parse().ok()?;
    let x: u32 = parts.next()?.parse().ok()?;
    let y: u32 = parts.next()?.parse().ok()?;
    if parts.next().is_some() {
        return None;
    }
    Some((layer, TileId::new(z, x, y).ok()?))
}

/// The tile's PNG: from the cache, else rendered and cached (written atomically, so a worker
/// never reads half a file).
fn tile_bytes(shared: &Shared<'_>, layer: Layer, tile: TileId) -> anyhow::Result<Vec<u8>> {
    let path = shared
        .cache
        .join(layer.name())
        .join(tile.z.to_string())
        .join(tile.x.to_string())
        .join(format!("{}.png", tile.y));
    if let Ok(bytes) = std::fs::read(&path) {
        return Ok(bytes);
    }
    let image = shared.run.render(tile, layer)?;
    let png = motif_io::encode_png(&image);
    shared.rendered.fetch_add(1, Ordering::SeqCst);
    if let Some(folder) = path.parent() {
        motif_io::create_folder(folder)?;
    }
    motif_io::write_bytes(&path, &png)?;
    Ok(png)
}

/// A digest of everything a tile depends on: the map file, the legend, the job and the version.
fn run_key(args: &TilesArgs, job: &TilesJob) -> anyhow::Result<String> {
    let mut hasher = crc32fast::Hasher::new();
    hash_file(&mut hasher, &args.map)?;
    if let Some(legend) = &args.legend {
        if legend.is_dir() {
            let mut entries: Vec<PathBuf> = std::fs::read_dir(legend)
                .with_context(|| legend.display().to_string())?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .collect();
            entries.sort();
            for entry in entries.iter().filter(|entry| entry.is_file()) {
                hasher.update(entry.to_string_lossy().as_bytes());
                hash_file(&mut hasher, entry)?;
            }
        } else {
            hash_file(&mut hasher, legend)?;
        }
    }
    hasher.update(serde_json::to_string(job)?.as_bytes());
    hasher.update(env!("CARGO_PKG_VERSION").as_bytes());
    Ok(format!("{:08x}", hasher.finalize()))
}

fn hash_file(hasher: &mut crc32fast::Hasher, path: &Path) -> anyhow::Result<()> {
    let mut file = std::fs::File::open(path).with_context(|| path.display().to_string())?;
    let mut buffer = vec![0; 1 << 16];
    loop {
        let read = file.read(&mut buffer).with_context(|| path.display().to_string())?;
        if read == 0 {
            return Ok(());
        }
        hasher.update(&buffer[..read]);
    }
}
