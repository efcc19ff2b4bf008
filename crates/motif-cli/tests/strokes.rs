//! `motif strokes` end to end: files in, files out, reports, determinism and bad input.

use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, Output};

fn motif(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_motif")).current_dir(dir).args(args).output().unwrap()
}

fn svg(width: f64, height: f64, body: &str) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\">\n{body}</svg>\n"
    )
}

/// 20 vertical hatches, each two overlapping strokes, alternating red and blue.
fn hatch_reference() -> String {
    let mut body = String::new();
    for i in 0..20 {
        let x = 10.0 + 8.0 * i as f64;
        let colour = if i % 2 == 0 { "#d02020" } else { "#2020d0" };
        for (y0, y1, dx) in [(10.0, 26.0, 0.0), (20.0, 34.0, 0.4)] {
            let _ = writeln!(
                body,
                "<path d=\"M{x} {y0} L{} {y1}\" stroke=\"{colour}\" stroke-width=\"1.2\" fill=\"none\"/>",
                x + dx
            );
        }
    }
    svg(180.0, 44.0, &body)
}

/// 5 × 4 small crosses (two strokes each) on a grid of spacing 20.
fn cross_reference() -> String {
    let mut body = String::new();
    for row in 0..4 {
        for column in 0..5 {
            let (x, y) = (15.0 + 20.0 * column as f64, 15.0 + 20.0 * row as f64);
            let _ =
                writeln!(body, "<path d=\"M{} {y} L{} {y}\" stroke=\"black\" stroke-width=\"1\"/>", x - 4.0, x + 4.0);
            let _ =
                writeln!(body, "<path d=\"M{x} {} L{x} {}\" stroke=\"black\" stroke-width=\"1\"/>", y - 4.0, y + 4.0);
        }
    }
    svg(110.0, 90.0, &body)
}

fn setup() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("hatch.svg"), hatch_reference()).unwrap();
    std::fs::write(dir.path().join("cross.svg"), cross_reference()).unwrap();
    let curve = "<path d=\"M20 100 C200 20 400 180 580 100\" stroke=\"black\" fill=\"none\"/>\n";
    std::fs::write(dir.path().join("curve.svg"), svg(600.0, 200.0, curve)).unwrap();
    let disc = "<circle cx=\"150\" cy=\"150\" r=\"120\" fill=\"#eee\"/>\n";
    std::fs::write(dir.path().join("disc.svg"), svg(300.0, 300.0, disc)).unwrap();
    dir
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn hatching_along_a_curve_writes_svg_png_analysis_and_report() {
    let dir = setup();
    let output = motif(
        dir.path(),
        &[
            "--report",
            "report.json",
            "strokes",
            "--reference",
            "hatch.svg",
            "--scale",
            "3",
            "--along",
            "curve.svg",
            "--analysis",
            "analysis.svg",
            "--out",
            "out.svg",
            "--png",
            "out.png",
        ],
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let out = std::fs::read_to_string(dir.path().join("out.svg")).unwrap();
    assert!(out.matches("<path").count() > 100, "too few strokes written");
    assert!(dir.path().join("out.png").metadata().unwrap().len() > 100);
    let analysis = std::fs::read_to_string(dir.path().join("analysis.svg")).unwrap();
    assert!(analysis.contains("element-19") && !analysis.contains("element-20"), "20 hatch elements expected");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("report.json")).unwrap()).unwrap();
    assert_eq!(report["reference_strokes"], 40);
    assert_eq!(report["reference_elements"], 20);
    let elements = report["output_elements"].as_u64().unwrap();
    assert!(elements > 50, "{report}");
    let matched = report["matched_elements"].as_u64().unwrap();
    let fallback = report["fallback_elements"].as_u64().unwrap();
    assert_eq!(matched + fallback, elements);
    assert!(report["candidate_fraction"].as_f64().unwrap() > 0.9);
    for stage in ["fit", "cluster", "distribution", "seeds", "match", "variation", "output"] {
        assert!(report["stages_ms"][stage].is_number(), "missing stage {stage}: {report}");
    }
}

/// Without `--scale` ε is inferred from the reference (between the overlapping strokes of a hatch
/// and the 8 units between hatches), and the summary, the report and the analysis drawing say so;
/// a given `--scale` wins.
#[test]
fn the_scale_is_inferred_when_not_given() {
    let dir = setup();
    let run = |scale: &[&str]| {
        let mut args = vec!["--report", "report.json", "strokes", "--reference", "hatch.svg", "--along", "curve.svg"];
        args.extend_from_slice(scale);
        args.extend_from_slice(&["--analysis", "analysis.svg", "--out", "out.svg"]);
        let output = motif(dir.path(), &args);
        assert!(output.status.success(), "{}", stderr(&output));
        let text = std::fs::read_to_string(dir.path().join("report.json")).unwrap();
        let analysis = std::fs::read_to_string(dir.path().join("analysis.svg")).unwrap();
        (stderr(&output), serde_json::from_str::<serde_json::Value>(&text).unwrap(), analysis)
    };
    let (summary, report, analysis) = run(&[]);
    assert_eq!(report["reference_elements"], 20, "{report}");
    assert_eq!(report["scale_inferred"], true, "{report}");
    let scale = report["scale"].as_f64().unwrap();
    assert!(scale > 1.0 && scale < 8.0, "{report}");
    let inference = &report["scale_inference"];
    assert_eq!(inference["method"], "gap", "{report}");
    assert!(inference["below"].as_f64().unwrap() < scale && scale < inference["above"].as_f64().unwrap());
    assert!(summary.contains("(inferred)") && summary.contains("ε"), "{summary}");
    assert!(analysis.contains("(inferred)"), "the analysis drawing names how ε was chosen");
    let (summary, report, _) = run(&["--scale", "3"]);
    assert_eq!((&report["scale"], &report["scale_inferred"]), (&serde_json::json!(3.0), &serde_json::json!(false)));
    assert!(report["scale_inference"].is_null() && summary.contains("ε 3 (given)"), "{summary}");
}

#[test]
fn same_seed_gives_identical_bytes_for_any_thread_count() {
    let dir = setup();
    let run = |threads: &str, seed: &str, out: &str| {
        let output = motif(
            dir.path(),
            &[
                "--threads",
                threads,
                "--seed",
                seed,
                "strokes",
                "--reference",
                "cross.svg",
                "--scale",
                "3",
                "--region",
                "disc.svg",
                "--variation",
                "0.7",
                "--position-variation",
                "--out",
                out,
            ],
        );
        assert!(output.status.success(), "{}", stderr(&output));
        std::fs::read(dir.path().join(out)).unwrap()
    };
    let one = run("1", "5", "a.svg");
    let two = run("2", "5", "b.svg");
    assert_eq!(one, two);
    assert_ne!(one, run("2", "6", "c.svg"));
}

#[test]
fn a_rectangle_target_fills_with_the_reference_density() {
    let dir = setup();
    let output = motif(
        dir.path(),
        &[
            "--report",
            "r.json",
            "strokes",
            "--reference",
            "cross.svg",
            "--scale",
            "3",
            "--rect",
            "200,160",
            "--out",
            "o.svg",
        ],
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("r.json")).unwrap()).unwrap();
    assert_eq!(report["reference_elements"], 20);
    // One cross per 20 × 20 cell: about 80 in 200 × 160.
    let elements = report["output_elements"].as_f64().unwrap();
    assert!((elements - 80.0).abs() <= 8.0, "{elements}");
}

#[test]
fn bad_input_is_refused_with_a_clear_message() {
    let dir = setup();
    let invisible = "<path d=\"M0 0 L10 10\" stroke=\"none\" fill=\"none\"/>\n";
    std::fs::write(dir.path().join("empty.svg"), svg(20.0, 20.0, invisible)).unwrap();
    let bowtie = "<path d=\"M0 0 L100 100 L100 0 L0 100 Z\" fill=\"#ccc\"/>\n";
    std::fs::write(dir.path().join("bowtie.svg"), svg(100.0, 100.0, bowtie)).unwrap();
    let open = "<path d=\"M0 0 L100 100\" stroke=\"black\"/>\n";
    std::fs::write(dir.path().join("open.svg"), svg(100.0, 100.0, open)).unwrap();
    let cases: [(&[&str], &str); 6] = [
        // usvg drops invisible paths, so motif-io reports the drawing as empty.
        (&["--reference", "empty.svg", "--scale", "3", "--rect", "100,100"], "no path"),
        (&["--reference", "hatch.svg", "--scale", "0", "--rect", "100,100"], "invalid scale"),
        (&["--reference", "hatch.svg", "--scale", "-2", "--along", "curve.svg"], "invalid scale"),
        (&["--reference", "hatch.svg", "--scale", "3", "--rect", "0,100"], "invalid rect"),
        (&["--reference", "hatch.svg", "--scale", "3", "--region", "bowtie.svg"], "self-intersecting"),
        (&["--reference", "hatch.svg", "--scale", "3", "--region", "open.svg"], "no closed path"),
    ];
    for (args, message) in cases {
        let mut all = vec!["strokes"];
        all.extend_from_slice(args);
        all.extend_from_slice(&["--out", "never.svg"]);
        let output = motif(dir.path(), &all);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {}", stderr(&output));
        assert!(stderr(&output).contains(message), "{args:?}: expected `{message}` in {}", stderr(&output));
        assert!(!dir.path().join("never.svg").exists());
    }
    let output = motif(dir.path(), &["strokes", "--reference", "hatch.svg", "--scale", "3", "--out", "x.svg"]);
    assert_eq!(output.status.code(), Some(2), "a target is required");
    let output = motif(
        dir.path(),
        &["strokes", "--reference", "hatch.svg", "--scale", "3", "--rect", "9,9", "--out", "hatch.svg"],
    );
    assert_eq!(output.status.code(), Some(1));
}

#[test]
fn density_maps_shade_and_bad_maps_are_refused() {
    let dir = setup();
    // Left half black, right half white: every cross lands on the left.
    let half =
        motif_core::RgbaImage::from_fn(100, 80, |x, _| if x < 50 { [0, 0, 0, 255] } else { [255, 255, 255, 255] });
    motif_io::write_png(&dir.path().join("half.png"), &half).unwrap();
    let square = motif_core::RgbaImage::from_fn(50, 50, |_, _| [0, 0, 0, 255]);
    motif_io::write_png(&dir.path().join("square.png"), &square).unwrap();
    let white = motif_core::RgbaImage::from_fn(100, 80, |_, _| [255, 255, 255, 255]);
    motif_io::write_png(&dir.path().join("white.png"), &white).unwrap();
    std::fs::write(dir.path().join("text.png"), "not an image").unwrap();
    let base = ["--report", "r.json", "strokes", "--reference", "cross.svg", "--scale", "3", "--rect", "200,160"];
    let mut args = base.to_vec();
    args.extend_from_slice(&["--density-map", "half.png", "--scale-map", "square.png"]);
    let output = motif(dir.path(), &[&args[..], &["--out", "never.svg"]].concat());
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("--scale-map square.png") && stderr(&output).contains("aspect"),
        "{}",
        stderr(&output)
    );
    for (map, message) in [("text.png", "text.png"), ("white.png", "white"), ("missing.png", "missing.png")] {
        let mut args = base.to_vec();
        args.extend_from_slice(&["--density-map", map, "--out", "never.svg"]);
        let output = motif(dir.path(), &args);
        assert_eq!(output.status.code(), Some(1), "{map}");
        assert!(stderr(&output).contains(message), "{map}: {}", stderr(&output));
    }
    let along =
        ["strokes", "--reference", "hatch.svg", "--scale", "3", "--along", "curve.svg", "--density-map", "half.png"];
    let output = motif(dir.path(), &[&along[..], &["--out", "never.svg"]].concat());
    assert!(stderr(&output).contains("region target"), "{}", stderr(&output));
    assert!(!dir.path().join("never.svg").exists());

    let mut args = base.to_vec();
    args.extend_from_slice(&["--density-map", "half.png", "--out", "o.svg"]);
    let output = motif(dir.path(), &args);
    assert!(output.status.success(), "{}", stderr(&output));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("r.json")).unwrap()).unwrap();
    // Half the rectangle at the reference's density: about 40 crosses, none overlapping.
    let elements = report["output_elements"].as_f64().unwrap();
    assert!((elements - 40.0).abs() <= 5.0, "{elements}");
    assert_eq!(report["overlap"]["output_rate"], 0.0);
    let text = std::fs::read_to_string(dir.path().join("o.svg")).unwrap();
    let starts: Vec<f64> =
        text.split("<path d=\"M").skip(1).map(|rest| rest.split(' ').next().unwrap().parse::<f64>().unwrap()).collect();
    assert!(starts.len() >= 60);
    // Lloyd's cells straddle the tone edge by a fraction of a spacing (20).
    assert!(starts.iter().all(|&x| x < 115.0), "{starts:?}");
}
