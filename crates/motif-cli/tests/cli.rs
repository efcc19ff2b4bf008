//! The command line frame: help, usage errors and exit codes, demo and bench entry points.

use std::process::Command;

fn motif() -> Command {
    Command::new(env!("CARGO_BIN_EXE_motif"))
}

#[test]
fn help_lists_every_subcommand_and_global_option() {
    let output = motif().arg("--help").output().unwrap();
    assert!(output.status.success());
    let help = String::from_utf8(output.stdout).unwrap();
    for name in ["demo", "bench", "--seed", "--threads", "--quiet", "--report"] {
        assert!(help.contains(name), "`motif --help` does not mention {name}:\n{help}");
    }
    for engine in ["curve", "stylize", "texture", "points", "strokes"] {
        if help.contains(&format!("  {engine} ")) {
            let sub = motif().args([engine, "--help"]).output().unwrap();
            assert!(sub.status.success(), "`motif {engine} --help` failed");
        }
    }
}

#[test]
fn bad_usage_exits_2_with_a_message() {
    let output = motif().arg("no-such-command").output().unwrap();
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("no-such-command"));
    let output = motif().args(["--threads", "0", "demo"]).output().unwrap();
    assert_eq!(output.status.code(), Some(2));
    let output = motif().args(["--seed", "minus-one", "bench"]).output().unwrap();
    assert_eq!(output.status.code(), Some(2));
}

#[test]
fn a_negative_number_is_named_with_its_flag() {
    // Each said "unexpected argument '-5' found", without the flag.
    let cases: [&[&str]; 5] = [
        &["--seed", "-5", "texture", "--exemplar", "ex.png", "--size", "8x8", "--out", "out.png"],
        &["--threads", "-5", "texture", "--exemplar", "ex.png", "--size", "8x8", "--out", "out.png"],
        &["--max-memory", "-5", "texture", "--exemplar", "ex.png", "--size", "8x8", "--out", "out.png"],
        &["zoom", "--exemplar", "ex.png", "--size", "8x8", "--out-dir", "out", "--factor", "-5"],
        &["zoom", "--exemplar", "ex.png", "--size", "8x8", "--out-dir", "out", "--levels", "-5"],
    ];
    let dir = tempfile::tempdir().unwrap();
    motif_io::write_png(&dir.path().join("ex.png"), &motif_core::RgbaImage::filled(16, 16, [90, 60, 30, 255])).unwrap();
    for args in cases {
        let output = motif().current_dir(dir.path()).args(args).output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        let flag = args.windows(2).find(|pair| pair[1] == "-5").map(|pair| pair[0].trim_start_matches('-')).unwrap();
        assert!(!output.status.success(), "{args:?}");
        assert!(stderr.contains(flag) && !stderr.contains("unexpected argument"), "{args:?}: {stderr}");
    }
}

#[test]
fn a_failed_run_exits_1_and_names_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let blocker = dir.path().join("file");
    std::fs::write(&blocker, "x").unwrap();
    let output = motif().args(["--quiet", "demo", "--out"]).arg(blocker.join("inside")).output().unwrap();
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.starts_with("error: ") && stderr.contains("demo folder"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn demo_writes_a_gallery_and_bench_prints_json() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("demo");
    let report = dir.path().join("demo.json");
    let elsewhere = tempfile::tempdir().unwrap();
    let status = motif()
        .current_dir(elsewhere.path())
        .args(["--quiet", "--report"])
        .arg(&report)
        .args(["demo", "--out"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    // Everything goes into the demo folder, nothing into the working directory.
    assert_eq!(std::fs::read_dir(elsewhere.path()).unwrap().count(), 0);
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.starts_with("<!DOCTYPE html>"));
    let figures: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(figures["command"], "demo");
    // Every case of the gallery shows its command and at least one output that exists.
    for (title, case) in figures["cases"].as_object().unwrap() {
        assert!(case["command"].as_str().unwrap().starts_with("motif "), "{title}");
        assert!(html.contains(title.as_str()), "{title} missing from the gallery");
    }
    let output = motif().args(["bench", "--quick"]).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let bench: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(bench["quick"], true);
    let engines = bench["engines"].as_object().unwrap();
    assert_eq!(engines.keys().map(String::as_str).collect::<Vec<_>>(), ["curve", "points", "strokes", "stylize"]);
}

/// `--engine` takes the registry's names; another is a clear error that lists them.
#[test]
fn bench_runs_the_named_engine_and_refuses_an_unknown_one() {
    let output = motif().args(["bench", "--quick", "--engine", "strokes"]).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let bench: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(bench["engines"].as_object().unwrap().keys().collect::<Vec<_>>(), ["strokes"]);
    let output = motif().args(["bench", "--quick", "--engine", "nope"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("--engine nope") && stderr.contains("curve, points, strokes, stylize"), "{stderr}");
}

/// A reader that stops early (`motif bench | head -1`) ends the bench quietly, not with a panic.
#[test]
fn bench_output_into_a_closed_pipe_is_not_a_crash() {
    let mut child = motif()
        .args(["bench", "--quick", "--engine", "strokes"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success() && !stderr.contains("internal error"), "{stderr}");
}

/// Every file the demo writes, except the gallery and report (they hold timings).
fn demo_outputs(dir: &std::path::Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.is_file())
        .map(|path| (path.file_name().unwrap().to_string_lossy().into_owned(), std::fs::read(&path).unwrap()))
        .filter(|(name, _)| name != "index.html" && !name.ends_with(".json"))
        .collect();
    files.sort();
    files
}

#[test]
fn the_same_seed_gives_identical_bytes_with_one_and_two_threads() {
    let dir = tempfile::tempdir().unwrap();
    for threads in ["1", "2"] {
        let status = motif()
            .args(["--quiet", "--seed", "7", "--threads", threads, "demo", "--out"])
            .arg(dir.path().join(threads))
            .status()
            .unwrap();
        assert!(status.success());
    }
    let one = demo_outputs(&dir.path().join("1"));
    let two = demo_outputs(&dir.path().join("2"));
    assert_eq!(one.len(), two.len());
    for ((name, a), (_, b)) in one.iter().zip(&two) {
        assert!(a == b, "{name} differs between --threads 1 and --threads 2");
    }
}

#[test]
fn an_output_equal_to_an_input_is_refused_and_the_input_kept() {
    let dir = tempfile::tempdir().unwrap();
    let reference = dir.path().join("reference.svg");
    let text = r#"<svg xmlns="http://www.w3.org/2000/svg" width="40" height="40">
        <path d="M5 5 L9 9" stroke="black" stroke-width="1"/><path d="M20 5 L24 9" stroke="black" stroke-width="1"/>
        <path d="M5 20 L9 24" stroke="black" stroke-width="1"/><path d="M20 20 L24 24" stroke="black" stroke-width="1"/></svg>"#;
    std::fs::write(&reference, text).unwrap();
    // Spelled differently (through `.`), the output still names the input file.
    let same = dir.path().join(".").join("reference.svg");
    let output = motif()
        .args(["--quiet", "strokes", "--scale", "2", "--rect", "80,80", "--reference"])
        .arg(&reference)
        .arg("--out")
        .arg(&same)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("also an input"), "{stderr}");
    assert_eq!(std::fs::read_to_string(&reference).unwrap(), text);
}

/// `--report` naming an input, and `points --out` naming its stroke or region SVG, are refused
/// before any work and the input stays as it was (issue 13: both overwrote the input).
#[test]
fn a_report_or_points_output_equal_to_an_input_is_refused_and_the_input_kept() {
    let dir = tempfile::tempdir().unwrap();
    let exemplar = write_exemplar(dir.path());
    let before = std::fs::read(&exemplar).unwrap();
    let output = motif()
        .args(["--quiet", "texture", "--size", "32x32", "--exemplar"])
        .arg(&exemplar)
        .arg("--out")
        .arg(dir.path().join("t.png"))
        .arg("--report")
        .arg(&exemplar)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains("report"), "{}", String::from_utf8_lossy(&output.stderr));
    assert_eq!(std::fs::read(&exemplar).unwrap(), before);

    let points = dir.path().join("ex.csv");
    std::fs::write(&points, "x,y\n1,1\n3,2\n5,1\n2,4\n4,5\n").unwrap();
    let stroke = dir.path().join("stroke.svg");
    let text = r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 30 0"/></svg>"#;
    std::fs::write(&stroke, text).unwrap();
    for flags in [["--along", "stroke.svg"], ["--domain", "stroke.svg"]] {
        let output = motif()
            .current_dir(dir.path())
            .args(["--quiet", "points", "--exemplar", "ex.csv", "--neighbourhood", "3"])
            .args(flags)
            .args(["--out", "stroke.svg"])
            .output()
            .unwrap();
        assert_eq!(output.status.code(), Some(1), "{flags:?}");
        assert!(String::from_utf8_lossy(&output.stderr).contains("also an input"), "{flags:?}");
        assert_eq!(std::fs::read_to_string(&stroke).unwrap(), text);
    }
}

/// A secondary output into a missing folder (or onto a folder) is refused before any work, so the
/// previous main output is not replaced by a run that then fails (issue 13).
#[test]
fn an_unwritable_secondary_output_fails_before_the_main_output_is_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let exemplar = write_exemplar(dir.path());
    let out = dir.path().join("t.png");
    std::fs::write(&out, b"previous").unwrap();
    for (flag, target) in
        [("--report", dir.path().join("missing").join("r.json")), ("--report", dir.path().to_path_buf())]
    {
        let output = motif()
            .args(["--quiet", "texture", "--size", "32x32", "--exemplar"])
            .arg(&exemplar)
            .arg("--out")
            .arg(&out)
            .arg(flag)
            .arg(&target)
            .output()
            .unwrap();
        assert_eq!(output.status.code(), Some(1), "{target:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains("does not exist") || stderr.contains("is a folder"), "{stderr}");
        assert_eq!(std::fs::read(&out).unwrap(), b"previous", "{target:?}");
    }
}

/// A small opaque gradient exemplar, `ex.png` in `dir`.
fn write_exemplar(dir: &std::path::Path) -> std::path::PathBuf {
    let exemplar = dir.join("ex.png");
    let image = motif_core::RgbaImage::from_fn(24, 24, |x, y| [(x * 9) as u8, (y * 9) as u8, 40, 255]);
    motif_io::write_png(&exemplar, &image).unwrap();
    exemplar
}

/// SIGINT (and SIGTERM) end a run with exit code 130, no output and no temporary file left
/// behind (issue 13).
#[cfg(unix)]
#[test]
fn an_interrupted_run_leaves_nothing_behind() {
    let dir = tempfile::tempdir().unwrap();
    let exemplar = write_exemplar(dir.path());
    for signal in ["-INT", "-TERM"] {
        let out = dir.path().join("big.png");
        let mut child = motif()
            .args(["--quiet", "texture", "--size", "2400x2400", "--exemplar"])
            .arg(&exemplar)
            .arg("--out")
            .arg(&out)
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(1000));
        let killed = Command::new("kill").arg(signal).arg(child.id().to_string()).status().unwrap();
        assert!(killed.success());
        let status = child.wait().unwrap();
        assert_eq!(status.code(), Some(130), "{signal}");
        assert!(!out.exists(), "{signal}");
        let left: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|name| name.starts_with(".motif-"))
            .collect();
        assert!(left.is_empty(), "{signal}: {left:?}");
    }
}

/// Two outputs of one run on the same path are refused before any work (one would silently
/// replace the other).
#[test]
fn two_outputs_on_one_path_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let exemplar = write_exemplar(dir.path());
    let out = dir.path().join("t.png");
    let output = motif()
        .args(["--quiet", "texture", "--size", "32x32", "--exemplar"])
        .arg(&exemplar)
        .arg("--out")
        .arg(&out)
        .arg("--report")
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&output.stderr).contains("given twice"),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(!out.exists());
}
