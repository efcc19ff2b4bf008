//! `motif stylize` and `motif texture` end to end: files in, files out, reports, determinism and
//! bad input.

use std::path::Path;
use std::process::{Command, Output};

use motif_core::{FloatImage, RgbaImage};
use motif_stylize::samples;

fn motif(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_motif")).current_dir(dir).args(args).output().unwrap()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

fn png(dir: &Path, name: &str, image: &FloatImage) {
    motif_io::write_png(&dir.join(name), &RgbaImage::from_float(image)).unwrap();
}

/// A small map-like style/guide pair and a target guide of another size.
fn setup() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let source = samples::map_guide(64, 64, 5, 1);
    png(dir.path(), "A.png", &source);
    png(dir.path(), "A1.png", &samples::crayon_style(&source, 2));
    png(dir.path(), "B.png", &samples::map_guide(80, 56, 5, 3));
    png(dir.path(), "exemplar.png", &samples::crayon_style(&samples::map_guide(40, 40, 2, 4), 5));
    dir
}

fn report(dir: &Path, name: &str) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join(name)).unwrap()).unwrap()
}

#[test]
fn stylize_writes_output_report_and_debug_files() {
    let dir = setup();
    let d = dir.path();
    let output = motif(
        d,
        &[
            "stylize",
            "--style",
            "A1.png",
            "--guide",
            "A.png",
            "B.png",
            "--segments",
            "--debug-dir",
            "debug",
            "--report",
            "report.json",
            "--out",
            "B1.png",
            "--quiet",
        ],
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let image = motif_io::read_image(&d.join("B1.png")).unwrap();
    assert_eq!((image.width(), image.height()), (80, 56));
    let report = report(d, "report.json");
    for key in ["total", "style", "guide", "occurrence"] {
        assert!(report["energy"][key].as_f64().unwrap() >= 0.0, "{report}");
    }
    let coverage = report["source_coverage"].as_f64().unwrap();
    assert!(coverage > 0.0 && coverage <= 1.0);
    assert!(report["stages_ms"].as_object().unwrap().keys().any(|k| k.starts_with("level")));
    assert!(report["total_ms"].as_f64().unwrap() > 0.0);
    let field = motif_io::read_image(&d.join("debug/nnf.png")).unwrap();
    assert_eq!((field.width(), field.height()), (80, 56));
    assert!(d.join("debug/error.png").is_file());
    // The saved field carries the final vote's weights: re-applied to the style, it gives back
    // the output byte for byte (a plain mean was off by 3.4 on average, 57 at most).
    let output = motif(d, &["stylize", "--style", "A1.png", "--apply-nnf", "debug/nnf.png", "--out", "again.png"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let again = motif_io::read_image(&d.join("again.png")).unwrap();
    assert_eq!(again, image, "re-applying the saved field to the same style must give B' again");
}

#[test]
fn same_seed_same_bytes_for_one_and_two_threads() {
    let dir = setup();
    let d = dir.path();
    for threads in ["1", "2"] {
        let out = format!("B1-{threads}.png");
        let output = motif(
            d,
            &[
                "stylize",
                "--style",
                "A1.png",
                "--guide",
                "A.png",
                "B.png",
                "--seed",
                "9",
                "--threads",
                threads,
                "--out",
                &out,
            ],
        );
        assert!(output.status.success(), "{}", stderr(&output));
    }
    assert_eq!(std::fs::read(d.join("B1-1.png")).unwrap(), std::fs::read(d.join("B1-2.png")).unwrap());
}

#[test]
fn texture_and_presynth_band_mode() {
    let dir = setup();
    let d = dir.path();
    let output =
        motif(d, &["texture", "--exemplar", "exemplar.png", "--size", "72x48", "--tileable", "--out", "tile.png"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let tile = motif_io::read_image(&d.join("tile.png")).unwrap();
    assert_eq!((tile.width(), tile.height()), (72, 48));

    let output =
        motif(d, &["presynth", "--style", "A1.png", "--guide", "A.png", "--size", "40x40", "--out-dir", "cache"]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(d.join("cache/presynth.json").is_file() && d.join("cache/segment-1.png").is_file());
    // An input inside the folder that presynth fills is refused (its files are replaced), and so is
    // a folder that is a file; nothing is written.
    std::fs::copy(d.join("A1.png"), d.join("cache/segment-1.png")).unwrap();
    let kept = std::fs::read(d.join("cache/segment-1.png")).unwrap();
    let output = motif(
        d,
        &["presynth", "--style", "cache/segment-1.png", "--guide", "A.png", "--size", "40x40", "--out-dir", "cache"],
    );
    assert_eq!(output.status.code(), Some(1));
    assert!(stderr(&output).contains("lies in the --out-dir folder"), "{}", stderr(&output));
    assert_eq!(std::fs::read(d.join("cache/segment-1.png")).unwrap(), kept);
    let output =
        motif(d, &["presynth", "--style", "A1.png", "--guide", "A.png", "--size", "40x40", "--out-dir", "A.png"]);
    assert!(stderr(&output).contains("is a file"), "{}", stderr(&output));
    let output =
        motif(d, &["presynth", "--style", "A1.png", "--guide", "A.png", "--size", "40x40", "--out-dir", "cache"]);
    assert!(output.status.success(), "{}", stderr(&output));
    // Each texture's field is cached beside it and seeds the band.
    assert!(d.join("cache/segment-1-nnf.png").is_file());
    let mut optimized = Vec::new();
    for band in ["0", "3"] {
        let out = format!("band-{band}.png");
        let rep = format!("band-{band}.json");
        let output = motif(
            d,
            &[
                "stylize",
                "--style",
                "A1.png",
                "--guide",
                "A.png",
                "B.png",
                "--presynth",
                "cache",
                "--band",
                band,
                "--report",
                &rep,
                "--out",
                &out,
            ],
        );
        assert!(output.status.success(), "{}", stderr(&output));
        optimized.push(report(d, &rep)["searched_pixels"].as_u64().unwrap());
    }
    assert_eq!(optimized[0], 0);
    assert!(optimized[1] > 0 && optimized[1] < 80 * 56);
    // Seeded from the cached fields, the band runs --band-iters (3) search-vote iterations; a
    // cache without fields (older versions) still works and runs --search-vote-iters (6).
    let iterations = |name: &str| report(d, name)["levels"][0]["energies"].as_array().unwrap().len();
    assert_eq!(iterations("band-3.json"), 3);
    let manifest = std::fs::read_to_string(d.join("cache/presynth.json")).unwrap();
    let mut manifest: serde_json::Value = serde_json::from_str(&manifest).unwrap();
    for entry in manifest["segments"].as_array_mut().unwrap() {
        entry.as_object_mut().unwrap().remove("field");
    }
    std::fs::write(d.join("cache/presynth.json"), manifest.to_string()).unwrap();
    let args = ["stylize", "--style", "A1.png", "--guide", "A.png", "B.png", "--presynth", "cache", "--band", "3"];
    let output = motif(d, &[&args[..], &["--report", "old.json", "--out", "old.png"]].concat());
    assert!(output.status.success(), "{}", stderr(&output));
    assert_eq!(iterations("old.json"), 6);
    // A cache made with another patch size is refused.
    let output = motif(
        d,
        &[
            "stylize",
            "--style",
            "A1.png",
            "--guide",
            "A.png",
            "B.png",
            "--presynth",
            "cache",
            "--patch-size",
            "3",
            "--out",
            "x.png",
        ],
    );
    assert!(!output.status.success());
    assert!(stderr(&output).contains("--patch-size 5"), "{}", stderr(&output));
}

#[test]
fn bad_input_is_refused_with_clear_messages() {
    let dir = setup();
    let d = dir.path();
    png(d, "small-A.png", &samples::map_guide(50, 64, 5, 1));
    let mut transparent = RgbaImage::from_float(&samples::map_guide(80, 56, 5, 3));
    transparent.set(0, 0, [0, 0, 0, 0]);
    motif_io::write_png(&d.join("B-alpha.png"), &transparent).unwrap();
    std::fs::write(d.join("empty.png"), b"").unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["--guide", "small-A.png", "B.png"], "50×64"),
        (vec!["--guide", "A.png", "B-alpha.png"], "the target guide has 4"),
        (vec!["--guide", "A.png", "B.png", "--patch-size", "4"], "must be odd"),
        (vec!["--guide", "A.png", "B.png", "--patch-size", "1"], "must be odd"),
        (vec!["--guide", "A.png", "empty.png"], "empty.png"),
        (vec!["--guide", "A.png", "B.png", "--weight", "1", "--weight", "2"], "one per guide"),
        (vec!["--guide", "A.png", "B.png", "--uniformity", "-1"], "uniformity"),
        (vec![], "--guide"),
    ];
    for (extra, expected) in cases {
        let mut args = vec!["stylize", "--style", "A1.png", "--out", "bad.png"];
        args.extend(extra.iter().copied());
        let output = motif(d, &args);
        assert!(!output.status.success(), "{args:?} should fail");
        assert!(stderr(&output).contains(expected), "{args:?}: {}", stderr(&output));
        assert!(!stderr(&output).contains("panicked"));
    }
    let output = motif(d, &["stylize", "--style", "A1.png", "--guide", "A.png", "B.png", "--out", "A1.png"]);
    assert!(!output.status.success() && stderr(&output).contains("also an input"));
    let output = motif(d, &["texture", "--exemplar", "exemplar.png", "--size", "0x10", "--out", "t.png"]);
    assert!(!output.status.success());
}

/// A size typo (16384 × 16384, or presynth textures of 4096² for every segment) is refused before
/// any work with the pixel count and the flag to raise, instead of running for hours.
#[test]
fn runs_over_the_pixel_limit_are_refused_up_front() {
    let dir = setup();
    let d = dir.path();
    let output = motif(d, &["texture", "--exemplar", "exemplar.png", "--size", "16384x16384", "--out", "out.png"]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("268435456 pixels") && stderr(&output).contains("max-pixels"),
        "{}",
        stderr(&output)
    );
    let output = motif(
        d,
        &[
            "presynth",
            "--style",
            "A1.png",
            "--guide",
            "A.png",
            "--size",
            "64x64",
            "--max-pixels",
            "10000",
            "--out-dir",
            "cache",
        ],
    );
    assert_eq!(output.status.code(), Some(1));
    assert!(stderr(&output).contains("more than the 10000 allowed"), "{}", stderr(&output));
    assert!(!d.join("out.png").exists() && !d.join("cache/presynth.json").exists());
}

/// Guides are counted from 1 on the command line, and the error says so in the same terms.
#[test]
fn a_segment_guide_beyond_the_guides_is_named_as_typed() {
    let dir = setup();
    let output = motif(
        dir.path(),
        &[
            "stylize",
            "--style",
            "A1.png",
            "--guide",
            "A.png",
            "B.png",
            "--segments",
            "--segment-guide",
            "2",
            "--out",
            "out.png",
        ],
    );
    assert_eq!(output.status.code(), Some(1));
    let message = stderr(&output);
    assert!(message.contains("segment-guide = 2") && message.contains("counted from 1"), "{message}");
    assert!(!dir.path().join("out.png").exists());
}
