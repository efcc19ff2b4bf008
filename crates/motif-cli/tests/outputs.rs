//! The output plan (issue 32): every file a command writes (main output, report, debug files,
//! zoom levels, presynth's folder) is checked against every input and for a folder that takes
//! files before any work, and all of them are committed together after the run, or none.

mod common;

use std::path::{Path, PathBuf};

use common::{error_of, motif, ok};

/// A small opaque gradient `ex.png` (24 × 24), the previous output `t.png` ("previous"), and a
/// grey `mask.png` of the exemplar's size with a white hole.
fn setup() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let exemplar = motif_core::RgbaImage::from_fn(24, 24, |x, y| [(x * 9) as u8, (y * 9) as u8, 40, 255]);
    motif_io::write_png(&dir.path().join("ex.png"), &exemplar).unwrap();
    let hole = |x: usize, y: usize| (8..14).contains(&x) && (8..14).contains(&y);
    let mask = motif_core::RgbaImage::from_fn(24, 24, |x, y| if hole(x, y) { [255; 4] } else { [0, 0, 0, 255] });
    motif_io::write_png(&dir.path().join("mask.png"), &mask).unwrap();
    std::fs::write(dir.path().join("t.png"), b"previous").unwrap();
    dir
}

/// Every file under `dir` with its bytes (folders by their relative paths).
fn snapshot(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut files = Vec::new();
    let mut folders = vec![dir.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                files.push((path.strip_prefix(dir).unwrap().to_path_buf(), Vec::new()));
                folders.push(path);
            } else {
                files.push((path.strip_prefix(dir).unwrap().to_path_buf(), std::fs::read(&path).unwrap()));
            }
        }
    }
    files.sort();
    files
}

/// Runs `args` in `dir`, expects a failure whose message holds `expected`, and that no file
/// under `dir` changed, appeared or vanished.
fn refused(dir: &Path, args: &[&str], expected: &str) -> String {
    let before = snapshot(dir);
    let stderr = error_of(&motif(dir, args));
    assert!(stderr.contains(expected), "{args:?}: {stderr}");
    assert!(snapshot(dir) == before, "{args:?} changed files: {stderr}");
    stderr
}

const TEXTURE: [&str; 6] = ["--quiet", "texture", "--exemplar", "ex.png", "--size", "32x32"];

/// D1: a report that cannot be written fails the run before its outputs replace anything: a
/// folder that takes no files is refused before any work, and a name only the final rename finds
/// too long undoes the outputs already renamed.
#[test]
fn a_report_that_cannot_be_written_replaces_no_output() {
    let dir = setup();
    let d = dir.path();
    let long = format!("{}.json", "r".repeat(300));
    for report in ["/proc/r.json", long.as_str()] {
        let args = [&["--report", report][..], &TEXTURE, &["--out", "t.png"]].concat();
        refused(d, &args, "");
        let zoom = [
            &["--quiet", "--report", report, "zoom", "--exemplar", "ex.png", "--size", "32x32"][..],
            &["--levels", "2", "--out-dir", "levels"],
        ]
        .concat();
        refused(d, &zoom, "");
        let inpaint = [
            &["--quiet", "--report", report, "inpaint", "--image", "ex.png", "--mask", "mask.png"][..],
            &["--debug-dir", "debug", "--out", "t.png"],
        ]
        .concat();
        refused(d, &inpaint, "");
    }
    // The same runs with a report that can be written: every output and the report, status ok.
    let args = [&["--report", "r.json"][..], &TEXTURE, &["--debug-dir", "debug", "--out", "t.png"]].concat();
    ok(&motif(d, &args));
    let report: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(d.join("r.json")).unwrap()).unwrap();
    assert_eq!(report["status"], "ok");
    assert_ne!(std::fs::read(d.join("t.png")).unwrap(), b"previous");
    assert!(d.join("debug/nnf.png").is_file() && d.join("debug/error.png").is_file());
}

/// A failed run still writes its report (status failed) where that replaces no input or output,
/// and leaves the outputs as they were.
#[test]
fn a_failed_run_writes_only_its_report() {
    let dir = setup();
    let d = dir.path();
    // The hole covers the whole image once the mask is the wrong size: the run fails after the
    // output plan was checked.
    let small = motif_core::RgbaImage::from_fn(8, 8, |_, _| [255; 4]);
    motif_io::write_png(&d.join("small.png"), &small).unwrap();
    let stderr = error_of(&motif(
        d,
        &["--quiet", "--report", "r.json", "inpaint", "--image", "ex.png", "--mask", "small.png", "--out", "t.png"],
    ));
    assert!(stderr.contains("small.png"), "{stderr}");
    assert_eq!(std::fs::read(d.join("t.png")).unwrap(), b"previous");
    let report: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(d.join("r.json")).unwrap()).unwrap();
    assert_eq!(report["status"], "failed");
    assert!(report["error"].as_str().unwrap().contains("small.png"), "{report}");
}

/// D2: `--debug-dir`'s files are outputs like any other: never an input (also through a hard
/// link), never `--out`, never a file's place.
#[test]
fn debug_files_never_replace_an_input_or_another_output() {
    let dir = setup();
    let d = dir.path();
    std::fs::create_dir(d.join("d")).unwrap();
    std::fs::copy(d.join("ex.png"), d.join("d/error.png")).unwrap();
    std::fs::hard_link(d.join("ex.png"), d.join("d/nnf.png")).unwrap();
    let inpaint = ["--quiet", "inpaint", "--image", "d/error.png", "--mask", "mask.png"];
    let stylize = ["--quiet", "stylize", "--style", "d/error.png", "--guide", "ex.png", "mask.png"];
    let texture = ["--quiet", "texture", "--size", "32x32", "--exemplar", "d/error.png"];
    for command in [&inpaint[..], &stylize, &texture] {
        refused(d, &[command, &["--debug-dir", "d", "--out", "t.png"]].concat(), "also an input");
    }
    // Through a hard link: d/nnf.png is ex.png.
    let args = [&TEXTURE[..], &["--debug-dir", "d", "--out", "t.png"]].concat();
    refused(d, &args, "also an input");
    std::fs::remove_file(d.join("d/nnf.png")).unwrap();
    refused(d, &[&TEXTURE[..], &["--debug-dir", ".", "--out", "nnf.png"]].concat(), "given twice");
    refused(d, &[&TEXTURE[..], &["--debug-dir", "t.png", "--out", "out.png"]].concat(), "is a file");
    refused(d, &[&TEXTURE[..], &["--debug-dir", "t.png/debug", "--out", "out.png"]].concat(), "is a file");
}

/// D3: the files of a `--presynth` folder are inputs of stylize.
#[test]
fn stylize_never_writes_into_its_presynth_folder() {
    let dir = setup();
    let d = dir.path();
    std::fs::create_dir(d.join("cache")).unwrap();
    std::fs::copy(d.join("ex.png"), d.join("cache/segment-1.png")).unwrap();
    let stylize = ["--quiet", "stylize", "--style", "ex.png", "--guide", "ex.png", "mask.png", "--presynth", "cache"];
    for out in ["cache/segment-1.png", "cache/new.png"] {
        refused(d, &[&stylize[..], &["--out", out]].concat(), "which is an input");
    }
    let args = [&["--report", "cache/presynth.json"][..], &stylize, &["--out", "t.png"]].concat();
    refused(d, &args, "also an input");
}

/// D9: zoom's levels are planned whether or not `--out-dir` exists yet: `--report` is checked
/// against the exemplar and the levels, and a file as `--out-dir` is refused before any work.
#[test]
fn zoom_levels_are_planned_before_the_folder_exists() {
    let dir = setup();
    let d = dir.path();
    let zoom = ["--quiet", "zoom", "--exemplar", "ex.png", "--size", "32x32", "--levels", "2"];
    refused(d, &[&["--report", "ex.png"][..], &zoom, &["--out-dir", "new"]].concat(), "also an input");
    // (The report's folder must exist: it is not one the command makes.)
    refused(d, &[&["--report", "new/./zoom-01.png"][..], &zoom, &["--out-dir", "new"]].concat(), "does not exist");
    std::fs::create_dir(d.join("new")).unwrap();
    refused(d, &[&["--report", "new/./zoom-01.png"][..], &zoom, &["--out-dir", "new"]].concat(), "given twice");
    refused(d, &[&zoom[..], &["--out-dir", "t.png"]].concat(), "is a file");
    // A zoom whose folder holds its exemplar.
    std::fs::create_dir(d.join("levels")).unwrap();
    std::fs::copy(d.join("ex.png"), d.join("levels/zoom-02.png")).unwrap();
    let zoom_in = ["--quiet", "zoom", "--exemplar", "levels/zoom-02.png", "--size", "32x32", "--levels", "2"];
    refused(d, &[&zoom_in[..], &["--out-dir", "levels"]].concat(), "also an input");
    // And one that succeeds makes its folder.
    ok(&motif(d, &[&zoom[..], &["--out-dir", "new/deeper"]].concat()));
    assert!(d.join("new/deeper/zoom-01.png").is_file() && d.join("new/deeper/zoom-02.png").is_file());
}

/// Output paths that cannot be written are refused before any input is read (the exemplar here
/// is not an image: an output refused first proves the order).
#[test]
fn unwritable_outputs_are_refused_before_any_work() {
    let dir = setup();
    let d = dir.path();
    std::fs::write(d.join("broken.png"), b"not a png").unwrap();
    let texture = ["--quiet", "texture", "--exemplar", "broken.png", "--size", "32x32"];
    refused(d, &[&texture[..], &["--out", "/proc/x.png"]].concat(), "cannot write /proc/x.png");
    refused(d, &[&texture[..], &["--out", "missing/x.png"]].concat(), "does not exist");
    refused(d, &[&texture[..], &["--debug-dir", "t.png", "--out", "x.png"]].concat(), "is a file");
    refused(d, &[&texture[..], &["--debug-dir", "/proc/debug", "--out", "x.png"]].concat(), "/proc/debug");
    let zoom = ["--quiet", "zoom", "--exemplar", "broken.png", "--size", "32x32", "--levels", "2"];
    refused(d, &[&zoom[..], &["--out-dir", "t.png"]].concat(), "is a file");
    refused(d, &[&zoom[..], &["--out-dir", "/proc/levels"]].concat(), "/proc/levels");
    let presynth = ["--quiet", "presynth", "--style", "broken.png", "--guide", "mask.png", "--size", "32x32"];
    refused(d, &[&presynth[..], &["--out-dir", "t.png"]].concat(), "is a file");
    refused(d, &[&presynth[..], &["--out-dir", "/proc/cache"]].concat(), "/proc/cache");
    std::fs::create_dir(d.join("cache")).unwrap();
    let args = [&["--report", "cache/r.json"][..], &presynth, &["--out-dir", "cache"]].concat();
    refused(d, &args, "lies in the --out-dir folder");
}

/// A run killed with SIGKILL leaves its temporary files; the next run writing into that folder
/// removes those of processes that are gone, and no other file.
#[test]
fn temporary_files_of_killed_runs_are_removed_by_the_next_run() {
    let dir = setup();
    let d = dir.path();
    // (Above Linux's largest pid, 2^22: a process that is gone.)
    let dead = d.join(".motif-999999999-a1b2c3.tmp");
    // This test's own pid: a process still running.
    let live = d.join(format!(".motif-{}-a1b2c3.tmp", std::process::id()));
    let other = d.join(".motif-notes.txt");
    for path in [&dead, &live, &other] {
        std::fs::write(path, b"x").unwrap();
    }
    let old = std::time::SystemTime::now() - std::time::Duration::from_secs(120);
    std::fs::File::options().write(true).open(&dead).unwrap().set_modified(old).unwrap();
    ok(&motif(d, &[&TEXTURE[..], &["--out", "t.png"]].concat()));
    assert!(!dead.exists());
    assert!(live.exists() && other.exists());
}
