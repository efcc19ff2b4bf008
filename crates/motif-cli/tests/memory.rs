//! `--max-memory` estimates against the measured peak (issue 32, D12): every subcommand on a small
//! and a moderately large input, each run in its own process with `--report`; the estimate
//! compared with the limit (`estimated_peak_bytes`: the job's estimate, the resident size at the
//! start and what the CLI holds beside the job) must lie within 1.5× of `peak_resident_bytes`
//! either way. `zoom` and `video` check their whole run before the first level or frame.

#![allow(
    clippy::disallowed_methods,
    reason = "the command line never runs in WebAssembly: its own arithmetic (demo inputs, previews, bench shapes) \
              may use the platform's math library, which the workspace's clippy.toml forbids in the engines"
)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Instant;

use motif_core::RgbaImage;
use serde_json::Value;

const BAND: f64 = 1.5;

fn real(path: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real").join(path).to_str().unwrap().to_string()
}

fn motif(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_motif")).current_dir(dir).args(args).output().unwrap()
}

/// A textured colour image: smooth waves with a little hash noise.
fn pattern(width: usize, height: usize, seed: u32) -> RgbaImage {
    RgbaImage::from_fn(width, height, |x, y| {
        let h =
            (x as u32).wrapping_mul(73_856_093) ^ (y as u32).wrapping_mul(19_349_663) ^ seed.wrapping_mul(83_492_791);
        let wave = |k: f64| (127.0 + 100.0 * ((x as f64 + k) * 0.21).sin() * ((y as f64 - k) * 0.17).cos()) as u8;
        [wave(0.0).wrapping_add((h % 23) as u8), wave(3.0), wave(7.0), 255]
    })
}

/// A centred white rectangle of a third of each side on black.
fn hole(width: usize, height: usize) -> RgbaImage {
    RgbaImage::from_fn(width, height, |x, y| {
        let inside = (width / 3..2 * width / 3).contains(&x) && (height / 3..2 * height / 3).contains(&y);
        if inside { [255; 4] } else { [0, 0, 0, 255] }
    })
}

/// Runs `args` with a report; the report.
fn report(dir: &Path, args: &[&str]) -> Value {
    let path = dir.join("report.json");
    let _ = std::fs::remove_file(&path);
    let mut all = vec!["--quiet", "--report", path.to_str().unwrap()];
    all.extend_from_slice(args);
    let output = motif(dir, &all);
    assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
    serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap()
}

/// Runs each case and checks its estimate against its peak; all failures are listed together.
fn check_cases(dir: &Path, cases: &[(&str, Vec<&str>)]) {
    let mut failures = Vec::new();
    for (name, args) in cases {
        let report = report(dir, args);
        let Some(peak) = report["peak_resident_bytes"].as_u64() else { return }; // no /proc here
        let estimate = report["estimated_peak_bytes"].as_u64().unwrap_or_else(|| panic!("{name}: no estimate"));
        let ratio = peak as f64 / estimate as f64;
        let line = format!("{name}: estimate {estimate} B, peak {peak} B (peak / estimate {ratio:.2})");
        if !(1.0 / BAND..=BAND).contains(&ratio) {
            failures.push(line);
        }
    }
    assert!(failures.is_empty(), "estimates more than {BAND}× off the peak:\n{}", failures.join("\n"));
}

fn files() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().to_path_buf();
    motif_io::write_png(&path.join("small.png"), &pattern(96, 80, 1)).unwrap();
    motif_io::write_png(&path.join("small-hole.png"), &hole(96, 80)).unwrap();
    motif_io::write_png(&path.join("large.png"), &pattern(360, 280, 2)).unwrap();
    motif_io::write_png(&path.join("large-hole.png"), &hole(360, 280)).unwrap();
    motif_io::write_png(&path.join("target.png"), &pattern(200, 160, 3)).unwrap();
    // Two segments for presynth: left and right halves.
    let halves = |w, h| RgbaImage::from_fn(w, h, |x, _| if x < w / 2 { [255, 0, 0, 255] } else { [0, 0, 255, 255] });
    motif_io::write_png(&path.join("segments.png"), &halves(96, 80)).unwrap();
    std::fs::create_dir(path.join("frames")).unwrap();
    for frame in 0..6 {
        let image = pattern(128, 96, 4);
        let shifted = RgbaImage::from_fn(128, 96, |x, y| image.get((x + 2 * frame) % 128, y));
        motif_io::write_png(&path.join(format!("frames/{frame:02}.png")), &shifted).unwrap();
    }
    motif_io::write_png(&path.join("key.png"), &pattern(128, 96, 5)).unwrap();
    (dir, path)
}

#[test]
fn image_estimates_are_within_the_band_of_the_peak() {
    let (_dir, d) = files();
    let cases: Vec<(&str, Vec<&str>)> = vec![
        ("texture small", vec!["texture", "--exemplar", "small.png", "--size", "64x64", "--out", "t1.png"]),
        ("texture large", vec!["texture", "--exemplar", "large.png", "--size", "360x280", "--out", "t2.png"]),
        ("stylize", vec!["stylize", "--style", "small.png", "--guide", "small.png", "target.png", "--out", "s.png"]),
        ("inpaint small", vec!["inpaint", "--image", "small.png", "--mask", "small-hole.png", "--out", "i1.png"]),
        ("inpaint large", vec!["inpaint", "--image", "large.png", "--mask", "large-hole.png", "--out", "i2.png"]),
        (
            "presynth",
            vec!["presynth", "--style", "small.png", "--guide", "segments.png", "--size", "128x128", "--out-dir", "p"],
        ),
        ("zoom small", vec!["zoom", "--exemplar", "small.png", "--size", "64x64", "--levels", "2", "--out-dir", "z1"]),
        (
            "zoom large",
            vec!["zoom", "--exemplar", "small.png", "--size", "240x180", "--levels", "3", "--out-dir", "z2"],
        ),
        ("video", vec!["video", "--frames", "frames/%02d.png", "--key", "0:key.png", "--out", "v-%02d.png"]),
    ];
    check_cases(&d, &cases);
}

#[test]
fn geometry_estimates_are_within_the_band_of_the_peak() {
    let (_dir, d) = files();
    let mut lattice = String::from("x,y,z\n");
    for i in 0..4 * 4 * 4 {
        let jitter = (i * 37 % 11) as f64 * 0.02;
        lattice += &format!("{},{},{}\n", (i % 4) as f64 + jitter, (i / 4 % 4) as f64 - jitter, (i / 16) as f64);
    }
    std::fs::write(d.join("lattice.csv"), lattice).unwrap();
    let (longleaf, melon) = (real("points/longleaf.csv"), real("strokes/melon_seeds.svg"));
    let (heart, chain) = (real("curve/heart.svg"), real("curve/chain_small.png"));
    let cases: Vec<(&str, Vec<&str>)> = vec![
        (
            "points 2D small",
            vec![
                "points",
                "--exemplar",
                &longleaf,
                "--neighbourhood",
                "14",
                "--domain",
                "box:120,120",
                "--out",
                "a.csv",
            ],
        ),
        (
            "points 2D preview",
            vec![
                "points",
                "--exemplar",
                &longleaf,
                "--neighbourhood",
                "14",
                "--domain",
                "box:200,200",
                "--out",
                "b.csv",
                "--preview",
                "b.png",
            ],
        ),
        (
            "points 3D",
            vec![
                "points",
                "--exemplar",
                "lattice.csv",
                "--neighbourhood",
                "1.0",
                "--domain",
                "box:6,6,5",
                "--quadrature-spacing",
                "1.5",
                "--out",
                "c.csv",
            ],
        ),
        (
            "strokes",
            vec![
                "strokes",
                "--reference",
                &melon,
                "--scale",
                "1",
                "--rect",
                "310,144",
                "--out",
                "e.svg",
                "--png",
                "e.png",
            ],
        ),
        (
            "curve",
            vec![
                "curve",
                "--exemplar",
                &chain,
                "--path",
                &heart,
                "--width",
                "40",
                "--piece-length",
                "20",
                "--method",
                "repeat",
                "--out",
                "f.png",
            ],
        ),
    ];
    check_cases(&d, &cases);
}

/// A `--max-memory` between one level's (or interval's) estimate and the whole run's: refused at
/// once, nothing written.
#[test]
fn zoom_and_video_check_their_whole_run_before_any_work() {
    let (_dir, d) = files();
    let zoom = |levels: &'static str, out: &'static str| {
        vec!["zoom", "--exemplar", "large.png", "--size", "360x280", "--levels", levels, "--out-dir", out]
    };
    let one = report(&d, &zoom("1", "one"));
    let held = one["resident_at_start_bytes"].as_u64().unwrap() + one["reserved_memory_bytes"].as_u64().unwrap();
    let one_level = one["estimated_memory_bytes"].as_u64().unwrap();
    // Twelve levels keep eleven finished ones: well above one level plus its margin.
    let limit = format!("{}", held + one_level + one_level / 2);
    let start = Instant::now();
    let mut args = vec!["--max-memory", &limit];
    args.extend(zoom("12", "refused"));
    let output = motif(&d, &args);
    let error = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "twelve levels ran under the limit of one and a half");
    assert!(error.contains("--max-memory") && error.contains("allowed"), "{error}");
    assert!(!d.join("refused").exists());
    assert!(start.elapsed().as_secs_f64() < 2.0, "refused only after {:?}", start.elapsed());

    let video = report(&d, &["video", "--frames", "frames/%02d.png", "--key", "0:key.png", "--out", "w-%02d.png"]);
    let estimate = video["estimated_memory_bytes"].as_u64().unwrap();
    let limit = format!("{}", held + estimate / 2);
    let start = Instant::now();
    let output = motif(
        &d,
        &["--max-memory", &limit, "video", "--frames", "frames/%02d.png", "--key", "0:key.png", "--out", "x-%02d.png"],
    );
    let error = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(error.contains("--max-memory") && error.contains("allowed"), "{error}");
    assert!(!d.join("x-00.png").exists());
    assert!(start.elapsed().as_secs_f64() < 2.0, "refused only after {:?}", start.elapsed());
}

/// A 2D exemplar on a small surface mesh (once 1.85× over its estimate: the exemplar's mean
/// spacing was searched with a grid sized by its zero thickness in z).
#[test]
fn surface_estimates_are_within_the_band_of_the_peak() {
    let (_dir, d) = files();
    let mut grid = String::from("x,y\n");
    for i in 0..144 {
        let (x, y) = (i % 12, i / 12);
        grid += &format!("{},{}\n", x as f64 * 0.05 + ((x * 7 + y * 13) % 10) as f64 * 0.001, y as f64 * 0.05);
    }
    std::fs::write(d.join("grid.csv"), grid).unwrap();
    let surface = format!("surface:{}", real("meshes/tripod.obj"));
    let case =
        vec!["points", "--exemplar", "grid.csv", "--neighbourhood", "0.2", "--domain", &surface, "--out", "s.csv"];
    check_cases(&d, &[("points surface", case)]);
}
