//! `motif tiles serve`: tiles on demand over HTTP on 127.0.0.1 (`axum` on `tokio`), each rendered
//! once into a disk cache, with ETags, by a bounded pool of workers (`--workers` renders at once,
//! the other requests wait their turn).
//!
//! A tile's ETag names the run (a digest of the map file, the legend, the job and the version)
//! and the tile, so a client's copy stays valid across restarts while nothing changed; the cache
//! folder is keyed by the same digest.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use anyhow::Context as _;
use axum::extract::State;
use axum::http::{HeaderMap, HeaderValue, StatusCode, Uri, header};
use axum::response::{Html, IntoResponse, Response};
use motif_jobs::tiles::{Fill, Layer, Legend, MapClass, TileId, TilesJob, TilesRun};
use tokio::sync::{Notify, Semaphore};

use super::TilesArgs;
use crate::context::Context;

/// The page `/` answers: what the server offers.
const INDEX: &str = "<!doctype html><meta charset=utf-8><title>motif tiles</title>\
<h1>motif tiles</h1><p>Stylized tiles: <code>/{z}/{x}/{y}.png</code>; the plain segment map: \
<code>/plain/{z}/{x}/{y}.png</code>; the run: <code>/tiles.json</code>. A map to pan: \
<code>web/maps</code> (see docs/maps.md).</p>";

/// What every request shares.
struct Shared {
    run: TilesRun,
    cache: PathBuf,
    key: String,
    info: String,
    workers: Semaphore,
    served: AtomicU64,
    rendered: AtomicU64,
    max_requests: Option<u64>,
    stop: Notify,
}

impl Shared {
    /// Counts an answered request; the last one allowed by `--max-requests` stops the server.
    fn answered(&self) {
        let served = self.served.fetch_add(1, Ordering::SeqCst) + 1;
        if self.max_requests.is_some_and(|max| served >= max) {
            self.stop.notify_one();
        }
    }
}

/// Serves until `--max-requests` requests were answered or until Ctrl-C (or SIGTERM), which
/// lets the requests in progress finish and ends with exit code 0 (a second one exits at once).
pub(super) fn serve(args: &TilesArgs, key: String, run: TilesRun, context: &mut Context) -> anyhow::Result<()> {
    let cache = args.cache_dir.clone().unwrap_or_else(|| std::env::temp_dir().join("motif-tiles")).join(&key);
    motif_io::create_folder(&cache)?;
    let workers = args.workers.map_or(context.threads, usize::from).max(1);
    let info = info(&run);
    // Every level of the texture pyramid before the first request, so that none waits for one.
    context.progress().report("the texture pyramid's levels", 0.0);
    let started = std::time::Instant::now();
    run.make_texture_levels(motif_jobs::tiles::MAX_ZOOM)?;
    context.figure("texture_levels_ms", started.elapsed().as_secs_f64() * 1000.0);
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .max_blocking_threads(workers.max(2))
        .enable_all()
        .build()
        .context("cannot start the server's runtime")?;
    let listener = runtime
        .block_on(tokio::net::TcpListener::bind(("127.0.0.1", args.port)))
        .with_context(|| format!("cannot listen on 127.0.0.1:{}", args.port))?;
    let address = listener.local_addr().context("the server has no address")?;
    let shared = Arc::new(Shared {
        run,
        cache,
        key,
        info,
        workers: Semaphore::new(workers),
        served: AtomicU64::new(0),
        rendered: AtomicU64::new(0),
        max_requests: args.max_requests,
        stop: Notify::new(),
    });
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
    let app = axum::Router::new()
        .route("/", axum::routing::get(index))
        .route("/tiles.json", axum::routing::get(tiles_json))
        .fallback(tile)
        .with_state(shared.clone());
    let interrupted = Arc::new(AtomicBool::new(false));
    crate::stop_on_interrupt_with({
        let (shared, interrupted) = (shared.clone(), interrupted.clone());
        move || {
            interrupted.store(true, Ordering::SeqCst);
            shared.stop.notify_one();
        }
    });
    let stopping = shared.clone();
    runtime
        .block_on(async move {
            axum::serve(listener, app).with_graceful_shutdown(async move { stopping.stop.notified().await }).await
        })
        .context("the tile server stopped")?;
    let (served, rendered) = (shared.served.load(Ordering::SeqCst), shared.rendered.load(Ordering::SeqCst));
    let why = if interrupted.load(Ordering::SeqCst) { "interrupted" } else { "--max-requests reached" };
    context.summary(&format!("motif tiles: stopped ({why}) after {served} requests, {rendered} tiles rendered"));
    context.figure("requests", served);
    context.figure("rendered", rendered);
    Ok(())
}

/// What `/tiles.json` says: the URL templates, zoom levels, the map's bounds and centre.
fn info(run: &TilesRun) -> String {
    let [x0, y0, x1, y1] = run.tiles.map().bounds();
    let centre = motif_jobs::tiles::unproject([(x0 + x1) / 2.0, (y0 + y1) / 2.0]);
    let ((west, north), (east, south)) =
        (motif_jobs::tiles::unproject([x0, y0]), motif_jobs::tiles::unproject([x1, y1]));
    serde_json::json!({
        "tiles": ["/{z}/{x}/{y}.png"], "plain": ["/plain/{z}/{x}/{y}.png"],
        "minzoom": run.zooms[0], "maxzoom": motif_jobs::tiles::MAX_ZOOM.min(20),
        "center": [centre.0, centre.1, run.zooms[0].max(14)], "bounds": [west, south, east, north],
        "tile_size": run.tiles.params().tile_size,
        "attribution": "© OpenStreetMap contributors (ODbL)",
    })
    .to_string()
}

async fn index(State(shared): State<Arc<Shared>>) -> Html<&'static str> {
    shared.answered();
    Html(INDEX)
}

async fn tiles_json(State(shared): State<Arc<Shared>>) -> Response {
    shared.answered();
    let headers = [(header::CONTENT_TYPE, "application/json"), (header::ACCESS_CONTROL_ALLOW_ORIGIN, "*")];
    (headers, shared.info.clone()).into_response()
}

/// `/{z}/{x}/{y}.png` or `/plain/{z}/{x}/{y}.png`: from the cache or rendered by one of the
/// workers; 304 when the client's ETag is the tile's; 404 for anything else.
async fn tile(State(shared): State<Arc<Shared>>, uri: Uri, request_headers: HeaderMap) -> Response {
    let response = tile_response(&shared, uri.path(), &request_headers).await;
    shared.answered();
    response
}

async fn tile_response(shared: &Arc<Shared>, url: &str, request_headers: &HeaderMap) -> Response {
    let Some((layer, tile)) = parse_tile(url) else {
        let message = format!(
            "no tile at {url}: ask /{{z}}/{{x}}/{{y}}.png or /plain/{{z}}/{{x}}/{{y}}.png with x and y below 2^z\n"
        );
        return (StatusCode::NOT_FOUND, message).into_response();
    };
    let etag = format!("\"{}-{}-{}-{}-{}\"", shared.key, layer.name(), tile.z, tile.x, tile.y);
    let matches = request_headers
        .get_all(header::IF_NONE_MATCH)
        .iter()
        .filter_map(|value| value.to_str().ok())
        .any(|value| value.split(',').any(|v| v.trim() == etag));
    let mut headers = HeaderMap::new();
    if let Ok(value) = HeaderValue::from_str(&etag) {
        headers.insert(header::ETAG, value);
    }
    headers.insert(header::CACHE_CONTROL, HeaderValue::from_static("public, max-age=3600"));
    headers.insert(header::ACCESS_CONTROL_ALLOW_ORIGIN, HeaderValue::from_static("*"));
    if matches {
        return (StatusCode::NOT_MODIFIED, headers).into_response();
    }
    let Ok(permit) = shared.workers.acquire().await else {
        return (StatusCode::SERVICE_UNAVAILABLE, "the server is stopping\n").into_response();
    };
    let worker = shared.clone();
    let rendered = tokio::task::spawn_blocking(move || tile_bytes(&worker, layer, tile)).await;
    drop(permit);
    match rendered {
        Ok(Ok(png)) => {
            headers.insert(header::CONTENT_TYPE, HeaderValue::from_static("image/png"));
            (headers, png).into_response()
        }
        Ok(Err(error)) => {
            (StatusCode::INTERNAL_SERVER_ERROR, format!("cannot render {url}: {error:#}\n")).into_response()
        }
        Err(error) => (StatusCode::INTERNAL_SERVER_ERROR, format!("cannot render {url}: {error}\n")).into_response(),
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
fn tile_bytes(shared: &Shared, layer: Layer, tile: TileId) -> anyhow::Result<Vec<u8>> {
    let path = shared
        .cache
        .join(layer.name())
        .join(tile.z.to_string())
        .join(tile.x.to_string())
        .join(format!("{}.png", tile.y));
    if let Ok(bytes) = motif_io::read_bytes(&path) {
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

/// A digest of everything a tile depends on: the map file's bytes, the legend as read (each
/// class's colour or texture pixels), the job and the version.
pub(super) fn run_key(map: &Path, legend: &Legend, job: &TilesJob) -> anyhow::Result<String> {
    let mut hasher = crc32fast::Hasher::new();
    hasher.update(&motif_io::read_bytes(map)?);
    for class in MapClass::ALL {
        match legend.fill(class) {
            Fill::Colour(rgb) => hasher.update(rgb),
            Fill::Texture(image) => {
                hasher.update(&(image.width() as u64).to_le_bytes());
                hasher.update(&(image.height() as u64).to_le_bytes());
                hasher.update(image.as_bytes());
            }
        }
    }
    hasher.update(serde_json::to_string(job)?.as_bytes());
    hasher.update(env!("CARGO_PKG_VERSION").as_bytes());
    Ok(format!("{:08x}", hasher.finalize()))
}
