//! `motif tiles` end to end on the real Helsinki extract (data/real/maps): a pyramid packed into
//! PMTiles and read back, the same bytes whatever the thread count, the server's tiles, ETags,
//! cache and errors, and bad input.

mod common;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use common::{error_of, motif, ok};
use motif_jobs::tiles::{project, tiles_covering};

fn helsinki() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/maps/Helsinki.osm.pbf")
}

/// The tiles of a PMTiles archive, read with the `pmtiles` crate's own reader: (z, x, y) and
/// the tile's bytes, for every tile id up to zoom 16 the header's bounds hold.
fn archive_tiles(path: &Path) -> Vec<((u8, u32, u32), Vec<u8>)> {
    let runtime = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    runtime.block_on(async {
        let backend = pmtiles::MmapBackend::try_from(path).await.unwrap();
        let reader = pmtiles::AsyncPmTilesReader::try_from_source(backend).await.unwrap();
        let header = reader.get_header();
        let mut tiles = Vec::new();
        for z in header.min_zoom..=header.max_zoom {
            let [x0, y0] = project(header.min_longitude, header.max_latitude);
            let [x1, y1] = project(header.max_longitude, header.min_latitude);
            for tile in tiles_covering([x0, y0, x1, y1], z) {
                let coord = pmtiles::TileCoord::new(tile.z, tile.x, tile.y).unwrap();
                if let Some(bytes) = reader.get_tile(coord).await.unwrap() {
                    tiles.push(((tile.z, tile.x, tile.y), bytes.to_vec()));
                }
            }
        }
        assert_eq!(header.n_addressed_tiles().map(|n| n.get() as usize), Some(tiles.len()));
        tiles
    })
}

#[test]
fn a_pyramid_is_packed_read_back_and_the_same_on_any_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    let map = helsinki();
    let map = map.to_str().unwrap();
    let run = |threads: &str, out: &str| {
        let args = [
            "--seed",
            "3",
            "--threads",
            threads,
            "--report",
            "r.json",
            "tiles",
            "render",
            "--map",
            map,
            "--zoom",
            "15-16",
            "--out",
            out,
        ];
        ok(&motif(dir.path(), &args));
    };
    run("2", "a.pmtiles");
    run("1", "b.pmtiles");
    assert_eq!(
        std::fs::read(dir.path().join("a.pmtiles")).unwrap(),
        std::fs::read(dir.path().join("b.pmtiles")).unwrap()
    );
    let report: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.path().join("r.json")).unwrap()).unwrap();
    let tiles = archive_tiles(&dir.path().join("a.pmtiles"));
    assert_eq!(tiles.len() as u64, report["tiles"].as_u64().unwrap());
    // The extract spans columns 37307–37310 and rows 18966–18971 at zoom 16, 3 × 3 tiles at 15.
    assert_eq!(tiles.iter().filter(|((z, _, _), _)| *z == 16).count(), 24);
    assert_eq!(tiles.iter().filter(|((z, _, _), _)| *z == 15).count(), 9);
    assert_eq!(report["margin"], 2 + 5, "the band plus the patch size");
    assert!(report["features"]["building"].as_u64().unwrap() > 400, "{}", report["features"]);
    for (_, png) in &tiles {
        let image = image::load_from_memory(png).unwrap();
        assert_eq!((image.width(), image.height()), (256, 256));
    }
}

/// One GET to the server (a `ureq` client; the server is `axum`): status, headers (lower-case
/// names) and body.
fn get(address: &str, path: &str, headers: &[(&str, &str)]) -> (u16, Vec<(String, String)>, Vec<u8>) {
    let agent: ureq::Agent = ureq::Agent::config_builder().http_status_as_error(false).build().into();
    let mut request = agent.get(format!("http://{address}{path}"));
    for &(name, value) in headers {
        request = request.header(name, value);
    }
    let mut response = request.call().unwrap();
    let status = response.status().as_u16();
    let headers = response
        .headers()
        .iter()
        .map(|(name, value)| (name.as_str().to_string(), value.to_str().unwrap().to_string()))
        .collect();
    (status, headers, response.body_mut().read_to_vec().unwrap())
}

fn header<'a>(headers: &'a [(String, String)], name: &str) -> Option<&'a str> {
    headers.iter().find(|(n, _)| n == name).map(|(_, v)| v.as_str())
}

#[test]
fn the_server_answers_tiles_with_etags_from_its_cache_and_matches_the_archive() {
    let dir = tempfile::tempdir().unwrap();
    let map = helsinki();
    let map = map.to_str().unwrap();
    ok(&motif(dir.path(), &["--seed", "2", "tiles", "render", "--map", map, "--zoom", "16", "--out", "t.pmtiles"]));
    let archive = archive_tiles(&dir.path().join("t.pmtiles"));
    let ((z, x, y), packed) = archive[5].clone();
    let requests = 7;
    let mut server = Command::new(env!("CARGO_BIN_EXE_motif"))
        .current_dir(dir.path())
        .args(["--seed", "2", "--quiet", "tiles", "serve", "--map", map, "--port", "0", "--cache-dir", "cache"])
        .args(["--max-requests", &requests.to_string(), "--workers", "2"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let address = served_address(&mut server);
    assert!(address.starts_with("127.0.0.1:"), "{address}");
    let tile = format!("/{z}/{x}/{y}.png");
    let (status, headers, body) = get(&address, &tile, &[]);
    assert_eq!(status, 200);
    assert_eq!(header(&headers, "content-type"), Some("image/png"));
    assert_eq!(body, packed, "the served tile has the archive's bytes");
    let etag = header(&headers, "etag").unwrap().to_string();
    let (status, _, body) = get(&address, &tile, &[("If-None-Match", &etag)]);
    assert_eq!((status, body.len()), (304, 0));
    // Rendered once, then read from the cache folder.
    let cached = dir.path().join("cache").read_dir().unwrap().next().unwrap().unwrap().path();
    assert_eq!(std::fs::read(cached.join(format!("stylized/{z}/{x}/{y}.png"))).unwrap(), packed);
    let (status, _, plain) = get(&address, &format!("/plain{tile}"), &[]);
    assert_eq!(status, 200);
    assert_ne!(plain, packed);
    assert_eq!(get(&address, "/16/99999999/1.png", &[]).0, 404);
    assert_eq!(get(&address, "/nothing", &[]).0, 404);
    let (status, _, info) = get(&address, "/tiles.json", &[]);
    assert_eq!(status, 200);
    assert!(String::from_utf8_lossy(&info).contains("/plain/{z}/{x}/{y}.png"));
    assert_eq!(get(&address, "/", &[]).0, 200);
    // The seventh request was the last: the server stops by itself.
    assert!(server.wait().unwrap().success());
}

/// The `host:port` a starting `motif tiles serve` prints on its first line (`http://…/`).
fn served_address(server: &mut std::process::Child) -> String {
    let mut line = String::new();
    BufReader::new(server.stdout.take().unwrap()).read_line(&mut line).unwrap();
    line.trim().trim_start_matches("http://").trim_end_matches('/').to_string()
}

/// Ctrl-C is how a server normally ends: the first SIGINT stops it gracefully, exit code 0, with
/// its figures in the report and a summary of what it served (not "error: interrupted").
#[cfg(unix)]
#[test]
fn ctrl_c_stops_the_server_gracefully() {
    let dir = tempfile::tempdir().unwrap();
    let map = helsinki();
    let mut server = Command::new(env!("CARGO_BIN_EXE_motif"))
        .current_dir(dir.path())
        .args(["tiles", "serve", "--map", map.to_str().unwrap(), "--port", "0", "--texture-levels", "1"])
        .args(["--cache-dir", "cache", "--report", "served.json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let address = served_address(&mut server);
    assert_eq!(get(&address, "/tiles.json", &[]).0, 200);
    let killed = Command::new("kill").arg("-INT").arg(server.id().to_string()).status().unwrap();
    assert!(killed.success());
    let output = server.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains("stopped (interrupted) after 1 requests"), "{stderr}");
    assert!(!stderr.contains("error"), "{stderr}");
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("served.json")).unwrap()).unwrap();
    assert_eq!(report["requests"], 1, "{report}");
}

#[test]
fn bad_maps_legends_and_arguments_are_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("fake.osm.pbf"), b"not a protocol buffer at all").unwrap();
    let map = helsinki();
    let map = map.to_str().unwrap();
    let error = error_of(&motif(dir.path(), &["tiles", "render", "--map", "fake.osm.pbf", "--out", "t.pmtiles"]));
    assert!(error.contains("fake.osm.pbf") && error.contains("OpenStreetMap"), "{error}");
    let error = error_of(&motif(dir.path(), &["tiles", "render", "--map", map]));
    assert!(error.contains("--out"), "{error}");
    std::fs::write(dir.path().join("style.json"), br#"{"lava": "lava.png"}"#).unwrap();
    let error = error_of(&motif(
        dir.path(),
        &["tiles", "render", "--map", map, "--legend", "style.json", "--out", "t.pmtiles"],
    ));
    assert!(error.contains("style.json") && error.contains("lava") && error.contains("minor-road"), "{error}");
    let error = error_of(&motif(dir.path(), &["tiles", "render", "--map", map, "--out", "t.pmtiles", "--band", "99"]));
    assert!(error.contains("--band") || error.contains("band"), "{error}");
    let error =
        error_of(&motif(dir.path(), &["tiles", "render", "--map", map, "--zoom", "16-24", "--out", "t.pmtiles"]));
    assert!(error.contains("zoom = 16-24") && error.contains("100000"), "{error}");
    let output = motif(dir.path(), &["tiles", "render", "--map", map, "--zoom", "9-3", "--out", "t.pmtiles"]);
    assert_eq!(output.status.code(), Some(2));
    assert!(!dir.path().join("t.pmtiles").exists());
    // The archive never replaces the map.
    let error = error_of(&motif(dir.path(), &["tiles", "render", "--map", map, "--out", map]));
    assert!(error.contains("Helsinki.osm.pbf"), "{error}");
}
