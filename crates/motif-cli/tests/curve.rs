//! `motif curve` end to end: files in, files out, report figures, and clear errors.

#![allow(
    clippy::disallowed_methods,
    reason = "a test input drawn with the platform's math library: the command line never runs in WebAssembly"
)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use motif_core::RgbaImage;

fn motif() -> Command {
    Command::new(env!("CARGO_BIN_EXE_motif"))
}

/// A small chain strip: rings every 10 pixels with anti-aliased alpha, transparent above and below.
fn chain(width: usize, height: usize) -> RgbaImage {
    RgbaImage::from_fn(width, height, |x, y| {
        let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
        let cx = ((px / 10.0).floor() + 0.5) * 10.0;
        let ring = ((px - cx).hypot((py - height as f64 / 2.0) * 1.2) - 3.2).abs();
        let alpha = ((1.6 - ring).clamp(0.0, 1.0) * 255.0).round() as u8;
        if alpha == 0 { [0; 4] } else { [220, 170, 50, alpha] }
    })
}

struct Files {
    _dir: tempfile::TempDir,
    root: PathBuf,
}

impl Files {
    fn new() -> Self {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path().to_path_buf();
        motif_io::write_png(&root.join("chain.png"), &chain(60, 18)).unwrap();
        std::fs::write(
            root.join("loop.svg"),
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"160\" height=\"120\">\
             <path d=\"M 20 60 C 20 10 140 10 140 60 C 140 110 20 110 20 60 Z\"/></svg>",
        )
        .unwrap();
        std::fs::write(
            root.join("line.svg"),
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200\" height=\"60\"><path d=\"M 10 30 L 190 30\"/></svg>",
        )
        .unwrap();
        Self { _dir: dir, root }
    }

    fn path(&self, name: &str) -> PathBuf {
        self.root.join(name)
    }
}

fn run(args: &[&str], files: &Files) -> Output {
    let resolved: Vec<String> = args
        .iter()
        .map(|arg| {
            let candidate = files.path(arg);
            if arg.contains('.') && !arg.starts_with('-') && arg.parse::<f64>().is_err() {
                candidate.to_string_lossy().into_owned()
            } else {
                (*arg).to_string()
            }
        })
        .collect();
    motif().arg("--quiet").args(resolved).output().unwrap()
}

fn report(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn closed_exact_run_writes_pattern_pieces_overlay_and_report() {
    let files = Files::new();
    let output = run(
        &[
            "--report",
            "report.json",
            "curve",
            "--exemplar",
            "chain.png",
            "--path",
            "loop.svg",
            "--width",
            "20",
            "--piece-length",
            "12",
            "--closed",
            "exact",
            "--stitch",
            "--out",
            "out.png",
            "--pieces",
            "pieces.json",
            "--debug-overlay",
            "debug.png",
        ],
        &files,
    );
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let image = motif_io::read_image(&files.path("out.png")).unwrap();
    assert!(image.count_alpha_at_least(128) > 200, "the chain is drawn");
    assert!(image.count_alpha_at_least(1) < image.width() * image.height(), "the background stays transparent");
    let overlay = motif_io::read_image(&files.path("debug.png")).unwrap();
    assert_eq!((overlay.width(), overlay.height()), (image.width(), image.height()));
    assert_ne!(overlay, image);

    let figures = report(&files.path("report.json"));
    assert_eq!(figures["status"], "ok");
    for key in ["pieces", "total_cost", "mean_seam_cost", "valid_fraction", "stages_ms", "closed_certified"] {
        assert!(!figures[key].is_null(), "report lacks {key}: {figures}");
    }
    assert!(figures["dp_row_ms"]["median"].as_f64().unwrap() >= 0.0);
    assert!(figures["dp_row_ms"]["max"].as_f64().unwrap() >= figures["dp_row_ms"]["median"].as_f64().unwrap());
    assert_eq!(figures["closed"], true);
    let valid = figures["valid_fraction"].as_f64().unwrap();
    assert!(valid > 0.0 && valid < 1.0);

    let pieces = report(&files.path("pieces.json"));
    let list = pieces["pieces"].as_array().unwrap();
    assert_eq!(list.len() as u64, figures["pieces"].as_u64().unwrap());
    let samples = pieces["samples_per_edge"].as_u64().unwrap() as usize;
    for piece in list {
        assert_eq!(piece["quad"].as_array().unwrap().len(), 4);
        assert!(piece["rotation"].is_number());
        assert_eq!(piece["stitch"].as_array().unwrap().len(), samples);
        assert!(piece["position"].is_array() || piece["position"].is_null());
    }
    let seams: f64 = list.iter().map(|p| p["seam_cost"].as_f64().unwrap()).sum();
    assert!((seams - figures["total_cost"].as_f64().unwrap()).abs() < 1e-6);
}

#[test]
fn both_solvers_agree_and_repeat_baseline_runs() {
    let files = Files::new();
    let mut totals = Vec::new();
    for solver in ["exact", "reference"] {
        let name = format!("{solver}.json");
        let output = run(
            &[
                "--report",
                &name,
                "curve",
                "--exemplar",
                "chain.png",
                "--path",
                "loop.svg",
                "--width",
                "20",
                "--piece-length",
                "14",
                "--solver",
                solver,
                "--out",
                "out.png",
            ],
            &files,
        );
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        totals.push(report(&files.path(&name))["total_cost"].as_f64().unwrap());
    }
    assert_eq!(totals[0], totals[1]);
    let output = run(
        &[
            "--report",
            "repeat.json",
            "curve",
            "--exemplar",
            "chain.png",
            "--path",
            "loop.svg",
            "--width",
            "20",
            "--piece-length",
            "14",
            "--method",
            "repeat",
            "--out",
            "repeat.png",
        ],
        &files,
    );
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let figures = report(&files.path("repeat.json"));
    assert!(figures["distortion_max"].as_f64().unwrap() > 0.1);
    assert!(figures["wrap_seams"].as_u64().unwrap() > 0);
}

#[test]
fn the_avoidance_map_is_respected() {
    let files = Files::new();
    let mask = RgbaImage::from_fn(200, 60, |x, y| {
        if (90..130).contains(&x) && y >= 30 { [255, 255, 255, 255] } else { [0, 0, 0, 255] }
    });
    motif_io::write_png(&files.path("mask.png"), &mask).unwrap();
    let output = run(
        &[
            "curve",
            "--exemplar",
            "chain.png",
            "--path",
            "line.svg",
            "--width",
            "30",
            "--piece-length",
            "12",
            "--avoid",
            "mask.png",
            "--out",
            "out.png",
        ],
        &files,
    );
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let image = motif_io::read_image(&files.path("out.png")).unwrap();
    assert_eq!((image.width(), image.height()), (200, 60));
    for y in 30..60 {
        for x in 90..130 {
            assert_eq!(image.get(x, y)[3], 0, "pattern at forbidden ({x}, {y})");
        }
    }
    assert!(image.count_alpha_at_least(128) > 100);
}

fn failure(args: &[&str], files: &Files) -> String {
    let output = run(args, files);
    assert_eq!(output.status.code(), Some(1), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(stderr.starts_with("error: ") && !stderr.contains("panicked"), "{stderr}");
    stderr
}

/// `motif curve` on `exemplar` along `path`, width 20, pieces of 10, into `o.png`.
fn plain<'a>(exemplar: &'a str, path: &'a str) -> [&'a str; 11] {
    ["curve", "--exemplar", exemplar, "--path", path, "--width", "20", "--piece-length", "10", "--out", "o.png"]
}

#[test]
fn bad_input_gives_clear_errors() {
    let files = Files::new();
    let base = ["curve", "--exemplar", "chain.png", "--path", "line.svg", "--out", "out.png"];
    let with = |extra: &[&'static str]| -> Vec<&'static str> {
        let mut args: Vec<&'static str> = base.to_vec();
        args.extend_from_slice(extra);
        args
    };
    let e = failure(&with(&["--width", "0", "--piece-length", "10"]), &files);
    assert!(e.contains("invalid width"), "{e}");
    let e = failure(&with(&["--width", "-4", "--piece-length", "10"]), &files);
    assert!(e.contains("invalid width"), "{e}");
    let e = failure(&with(&["--width", "20", "--piece-length", "500"]), &files);
    assert!(e.contains("piece-length") && e.contains("curve's length"), "{e}");
    // A value that is not a finite number is a usage error naming the flag (exit 2).
    let output = run(&with(&["--width", "NaN", "--piece-length", "10"]), &files);
    let e = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{e}");
    assert!(e.contains("--width") && e.contains("NaN"), "{e}");
    let e = failure(&with(&["--width", "20", "--piece-length", "10", "--min-coverage", "1.5"]), &files);
    assert!(e.contains("invalid min-coverage"), "{e}");
    // Tiny and huge values are refused before any allocation, with readable numbers and the flag
    // that the user typed (issue 13: these panicked, aborted or hung).
    let e = failure(&with(&["--width", "20", "--piece-length", "1e-300"]), &files);
    assert!(e.contains("invalid piece-length = 1e-300") && e.contains("1 exemplar pixel"), "{e}");
    let e = failure(&with(&["--width", "20", "--piece-length", "0.01"]), &files);
    assert!(e.contains("piece-length"), "{e}");
    let e = failure(&with(&["--width", "20", "--piece-length", "10", "--tolerance", "1e-300"]), &files);
    assert!(e.contains("invalid tolerance = 1e-300"), "{e}");
    let e = failure(&with(&["--width", "20", "--piece-length", "10", "--gamma", "-5"]), &files);
    assert!(e.contains("invalid gamma = -5"), "{e}");
    let e = failure(&with(&["--width", "20", "--piece-length", "10", "--canvas", "1x1"]), &files);
    assert!(e.contains("invalid canvas") && e.contains("outside the canvas"), "{e}");
    let e = failure(&with(&["--width", "20", "--piece-length", "10", "--canvas", "16384x16384"]), &files);
    assert!(e.contains("megapixels"), "{e}");
    assert!(!files.path("out.png").exists(), "a failed run writes nothing");
    std::fs::write(files.path("far.csv"), "x,y\n0,0\n100,0\n1e9,5\n").unwrap();
    let e = failure(&plain("chain.png", "far.csv"), &files);
    assert!(e.contains("invalid path") && e.contains("1e6"), "{e}");

    motif_io::write_png(&files.path("clear.png"), &RgbaImage::new(20, 10)).unwrap();
    motif_io::write_png(&files.path("solid.png"), &RgbaImage::filled(20, 10, [9, 9, 9, 255])).unwrap();
    for (file, words) in [("clear.png", "fully transparent"), ("solid.png", "fully opaque")] {
        let e = failure(&plain(file, "line.svg"), &files);
        assert!(e.contains(words), "{e}");
    }

    std::fs::write(
        files.path("dot.svg"),
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\"><path d=\"M 5 5 L 5 5\" stroke=\"black\"/></svg>",
    )
    .unwrap();
    let e = failure(&plain("chain.png", "dot.svg"), &files);
    assert!(e.contains("zero length") || e.contains("no path"), "{e}");

    std::fs::write(files.path("nan.csv"), "x,y\n0,0\nNaN,4\n50,0\n").unwrap();
    let e = failure(&plain("chain.png", "nan.csv"), &files);
    assert!(e.contains("finite"), "{e}");

    let e = failure(
        &[
            "curve",
            "--exemplar",
            "chain.png",
            "--path",
            "line.svg",
            "--width",
            "20",
            "--piece-length",
            "10",
            "--out",
            "chain.png",
        ],
        &files,
    );
    assert!(e.contains("also an input"), "{e}");
}

#[test]
fn min_coverage_keeps_the_pattern_instead_of_a_free_sliver() {
    let files = Files::new();
    // A uniform 2-pixel bar (x < 20) beside a band of distinct columns (x ≥ 20): the paper's rule
    // repeats the bar for free; the default coverage rule must copy the band.
    let image = RgbaImage::from_fn(80, 24, |x, y| {
        if x < 20 {
            if (11..13).contains(&y) { [90, 90, 90, 255] } else { [0; 4] }
        } else if (4..19).contains(&y) {
            [(x * 37 % 251) as u8, (x * 91 % 241) as u8, (y * 13) as u8, 255]
        } else {
            [0; 4]
        }
    });
    motif_io::write_png(&files.path("sliver.png"), &image).unwrap();
    std::fs::write(
        files.path("long.svg"),
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"120\" height=\"60\"><path d=\"M 10 30 L 100 30\"/></svg>",
    )
    .unwrap();
    let mut costs = Vec::new();
    for (coverage, name) in [("0", "paper.json"), ("0.5", "default.json")] {
        let output = run(
            &[
                "--report",
                name,
                "curve",
                "--exemplar",
                "sliver.png",
                "--path",
                "long.svg",
                "--width",
                "20",
                "--piece-length",
                "6",
                "--min-coverage",
                coverage,
                "--out",
                "out.png",
            ],
            &files,
        );
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        let image = motif_io::read_image(&files.path("out.png")).unwrap();
        costs.push((report(&files.path(name))["total_cost"].as_f64().unwrap(), image.count_alpha_at_least(128)));
    }
    assert_eq!(costs[0].0, 0.0, "{costs:?}");
    assert!(costs[1].0 > 0.0, "{costs:?}");
    // The band is 7.5 times as tall as the bar: far more of the ribbon is drawn.
    assert!(costs[1].1 > 4 * costs[0].1, "{costs:?}");
}

/// Issue 34: `--exemplar` and `--path` alone run, with the width and piece length inferred from
/// the exemplar and named in the report and the summary; a given value still wins.
#[test]
fn width_and_piece_length_are_inferred_from_the_exemplar() {
    let dir = tempfile::tempdir().unwrap();
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/curve");
    let (exemplar, heart) = (corpus.join("chain_round.png"), corpus.join("heart.svg"));
    let args = ["curve", "--exemplar", exemplar.to_str().unwrap(), "--path", heart.to_str().unwrap(), "--out", "x.png"];
    let output = motif().current_dir(dir.path()).args(args).args(["--report", "r.json"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let figures = report(&dir.path().join("r.json"));
    assert_eq!(
        (figures["width_inferred"].as_bool(), figures["piece_length_inferred"].as_bool()),
        (Some(true), Some(true))
    );
    let (width, piece_length) = (figures["width"].as_f64().unwrap(), figures["piece_length"].as_f64().unwrap());
    // The hand-picked values of the corpus case are 108 and 25.
    assert!((95.0..=120.0).contains(&width) && (18.0..=40.0).contains(&piece_length), "{figures}");
    assert!(figures["pattern_period"].as_u64().is_some(), "{figures}");
    assert!(stderr.contains(&format!("width {width} (inferred), piece length {piece_length} (inferred)")), "{stderr}");

    let files = Files::new();
    let given = run(
        &[
            "curve",
            "--exemplar",
            "chain.png",
            "--path",
            "line.svg",
            "--width",
            "20",
            "--out",
            "o.png",
            "--report",
            "r.json",
        ],
        &files,
    );
    assert!(given.status.success(), "{}", String::from_utf8_lossy(&given.stderr));
    let figures = report(&files.path("r.json"));
    assert_eq!((figures["width"].as_f64(), figures["width_inferred"].as_bool()), (Some(20.0), Some(false)));
    assert_eq!(figures["piece_length_inferred"].as_bool(), Some(true));

    motif_io::write_png(&files.path("clear.png"), &RgbaImage::new(20, 10)).unwrap();
    let e = failure(&["curve", "--exemplar", "clear.png", "--path", "line.svg", "--out", "o.png"], &files);
    assert!(e.contains("no pattern found"), "{e}");
}
