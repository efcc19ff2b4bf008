//! `motif curve` on the small cases of the real-exemplar corpus (`data/real/curve/`, the cases
//! marked `"test": true`): clean results measured by the engine's own patch fidelity, seams that
//! keep a frieze's alpha continuous, the warning for a ribbon as wide as the strip, repetition
//! control on a straight line, and clear errors for bad values of the new flags.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn corpus(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/curve").join(file)
}

fn motif(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_motif")).current_dir(dir).args(args).output().unwrap()
}

fn test_cases() -> Vec<Value> {
    let cases: Value = motif_io::read_json(&corpus("cases.json")).unwrap();
    let cases: Vec<Value> = cases.as_array().unwrap().iter().filter(|c| c["test"] == true).cloned().collect();
    assert!(cases.len() >= 2, "the corpus marks at least two small cases for tests");
    cases
}

/// `motif curve` on `exemplar` along `path` with the given width and piece length, into `out.png`.
fn curve_args<'a>(exemplar: &'a Path, path: &'a Path, width: &'a str, piece_length: &'a str) -> Vec<&'a str> {
    let (exemplar, path) = (exemplar.to_str().unwrap(), path.to_str().unwrap());
    vec![
        "curve",
        "--exemplar",
        exemplar,
        "--path",
        path,
        "--width",
        width,
        "--piece-length",
        piece_length,
        "--out",
        "out.png",
    ]
}

/// Runs `motif curve` on a corpus exemplar and curve with extra flags; returns the report, the
/// pieces document and stderr.
fn run(exemplar: &str, path: &Path, width: &str, piece_length: &str, extra: &[&str]) -> (Value, Value, String) {
    let dir = tempfile::tempdir().unwrap();
    let exemplar = corpus(exemplar);
    let mut args = curve_args(&exemplar, path, width, piece_length);
    args.extend_from_slice(&["--pieces", "pieces.json", "--report", "report.json"]);
    args.extend_from_slice(extra);
    let output = motif(dir.path(), &args);
    let stderr = String::from_utf8_lossy(&output.stderr).to_string();
    assert!(output.status.success(), "{stderr}");
    let report = motif_io::read_json(&dir.path().join("report.json")).unwrap();
    let pieces = motif_io::read_json(&dir.path().join("pieces.json")).unwrap();
    (report, pieces, stderr)
}

fn case_run(case: &Value, extra: &[&str]) -> (Value, Value, String) {
    let width = case["width"].to_string();
    let piece_length = case["piece_length"].to_string();
    run(case["exemplar"].as_str().unwrap(), &corpus(case["path"].as_str().unwrap()), &width, &piece_length, extra)
}

/// Every small real case runs without a warning; its patches are found in the exemplar (mean
/// distance and broken fraction low, as for an undistorted copy) and its seams keep the alpha
/// continuous: no seam costs more than 5 % of its samples mismatching opaque against clear.
#[test]
fn small_real_cases_are_clean() {
    for case in test_cases() {
        let name = case["name"].as_str().unwrap().to_string();
        let (report, pieces, _) = case_run(&case, &["--fidelity"]);
        assert_eq!(report["warnings"].as_array().unwrap().len(), 0, "{name}: {}", report["warnings"]);
        let fidelity = &report["fidelity"];
        assert!(fidelity["mean_distance"].as_f64().unwrap() < 0.02, "{name}: {fidelity}");
        assert!(fidelity["broken_fraction"].as_f64().unwrap() < 0.01, "{name}: {fidelity}");
        let samples = report["samples_per_edge"].as_f64().unwrap();
        for piece in pieces["pieces"].as_array().unwrap() {
            let seam = piece["seam_cost"].as_f64().unwrap();
            assert!(seam < 0.05 * samples * 1024.0, "{name}: seam {} costs {seam}", piece["index"]);
        }
    }
}

/// A ribbon exactly as wide as a frieze strip whose motif touches the strip's top and bottom
/// cannot hold a whole motif: the run says so and names the smallest width that can.
#[test]
fn a_ribbon_as_wide_as_the_strip_gets_a_warning() {
    let case = test_cases().into_iter().find(|c| c["fills_height"] == true).expect("a frieze test case");
    let height = case["exemplar_size"][1].as_u64().unwrap();
    let (report, _, stderr) = run(
        case["exemplar"].as_str().unwrap(),
        &corpus(case["path"].as_str().unwrap()),
        &height.to_string(),
        &case["piece_length"].to_string(),
        &[],
    );
    let warnings = report["warnings"].as_array().unwrap();
    let expected = format!("--width {}", height + 2);
    assert!(warnings.iter().any(|w| w.as_str().unwrap().contains(&expected)), "{warnings:?}");
    assert!(stderr.contains("warning:"), "{stderr}");
}

/// On a straight line the plain optimum repeats windows; `--variety` charges repeats and the
/// result repeats fewer, uses more distinct windows, and reports its bound.
#[test]
fn variety_uses_more_windows_of_a_real_exemplar_on_a_straight_line() {
    let dir = tempfile::tempdir().unwrap();
    let line = dir.path().join("line.svg");
    std::fs::write(&line, r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M 10 60 L 600 60"/></svg>"#).unwrap();
    let case = test_cases().into_iter().next().unwrap();
    let exemplar = case["exemplar"].as_str().unwrap();
    let (width, piece_length) = (case["width"].to_string(), case["piece_length"].to_string());
    let (plain, _, _) = run(exemplar, &line, &width, &piece_length, &[]);
    let (varied, _, _) = run(exemplar, &line, &width, &piece_length, &["--variety", "2000"]);
    let pairs = |r: &Value| r["repeated_pairs"].as_u64().unwrap();
    let windows = |r: &Value| r["distinct_windows"].as_u64().unwrap();
    assert!(pairs(&plain) > 0);
    assert!(pairs(&varied) < pairs(&plain), "{} vs {}", pairs(&varied), pairs(&plain));
    assert!(windows(&varied) > windows(&plain), "{} vs {}", windows(&varied), windows(&plain));
    let variety = &varied["variety"];
    assert!(variety["energy"].as_f64().unwrap() <= variety["energy_unpenalised"].as_f64().unwrap());
    assert!(variety["lower_bound"].as_f64().unwrap() <= variety["energy"].as_f64().unwrap());
}

#[test]
fn bad_values_of_the_new_flags_are_refused() {
    let case = test_cases().into_iter().next().unwrap();
    let exemplar = corpus(case["exemplar"].as_str().unwrap());
    let path = corpus(case["path"].as_str().unwrap());
    let dir = tempfile::tempdir().unwrap();
    for (flag, value) in [
        ("--variety", "-1"),
        ("--variety", "nan"),
        ("--variety", "1e9"),
        ("--variety-radius", "0"),
        ("--round-bends", "-0.5"),
        ("--round-bends", "9"),
        ("--width-profile", "0:1,0.5"),
        ("--width-profile", "0.5:1,0.2:1"),
        ("--width-profile", "0:20"),
        ("--pieces-shape", "wobbly"),
    ] {
        let mut args = curve_args(&exemplar, &path, "60", "20");
        args.extend_from_slice(&[flag, value]);
        let output = motif(dir.path(), &args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{flag} {value} accepted");
        assert!(stderr.contains(flag.trim_start_matches("--")), "{flag} {value}: {stderr}");
        assert!(!dir.path().join("out.png").exists());
    }
}

/// Tiles from PNGs of their own (a pattern brush's caps and corner pieces): the round-link
/// chain's first link, cut out and saved as a PNG, caps a sweep at both ends and sits on the
/// heart's cusp and tip; the pieces between never copy it.
#[test]
fn tiles_from_their_own_pngs_cap_the_ends_and_turn_the_corners() {
    let dir = tempfile::tempdir().unwrap();
    let chain = motif_io::read_image(&corpus("chain_round.png")).unwrap();
    let link = motif_core::RgbaImage::from_fn(95, chain.height(), |x, y| chain.get(x, y));
    motif_io::write_png(&dir.path().join("link.png"), &link).unwrap();
    let exemplar = corpus("chain_round.png");
    let sweep = corpus("flourish_sweep.svg");
    let mut args = curve_args(&exemplar, &sweep, "108", "25");
    args.extend_from_slice(&[
        "--start-tile-image",
        "link.png",
        "--end-tile-image",
        "link.png",
        "--pieces",
        "pieces.json",
    ]);
    let output = motif(dir.path(), &args);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let pieces: Value = motif_io::read_json(&dir.path().join("pieces.json")).unwrap();
    let pieces = pieces["pieces"].as_array().unwrap();
    let source = |piece: &Value| piece["exemplar"].as_u64().unwrap();
    // The start and end tile images are exemplars 1 and 2 (after the one given).
    assert_eq!((source(&pieces[0]), source(&pieces[pieces.len() - 1])), (1, 2));
    assert!(pieces[1..pieces.len() - 1].iter().all(|piece| source(piece) == 0));

    let heart = corpus("heart.svg");
    let mut args = curve_args(&exemplar, &heart, "108", "25");
    // A PNG given to --corner-tile is the tile image.
    args.extend_from_slice(&["--corner-tile", "link.png", "--pieces", "pieces.json", "--report", "report.json"]);
    let output = motif(dir.path(), &args);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let report: Value = motif_io::read_json(&dir.path().join("report.json")).unwrap();
    let corners = report["corner_tiles"].as_u64().unwrap();
    assert_eq!(corners, 2, "the heart's cusp and tip");
    assert!(stderr.contains(&format!("{corners} corner tiles")), "{stderr}");
    let pieces: Value = motif_io::read_json(&dir.path().join("pieces.json")).unwrap();
    let tiles = pieces["pieces"].as_array().unwrap().iter().filter(|piece| source(piece) == 1).count();
    assert_eq!(tiles as u64, corners);
}
