//! `motif points` end to end: files in, files out, reports, determinism, guidance and bad input.

use std::fmt::Write as _;

mod common;
use common::{error_of, grid_csv, motif, ok};

/// A 5 × 5 × 5 lattice with elements of two points each along x (ascii PLY).
fn lattice_ply() -> String {
    let mut rows = Vec::new();
    let mut id = 0;
    for z in 0..5 {
        for y in 0..5 {
            for x in 0..5 {
                let (cx, cy, cz) = (x as f64 * 1.5, y as f64 * 1.5, z as f64 * 1.5);
                rows.push(format!("{} {cy} {cz} {id}", cx - 0.3));
                rows.push(format!("{} {cy} {cz} {id}", cx + 0.3));
                id += 1;
            }
        }
    }
    format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\nproperty int element\nend_header\n{}\n",
        rows.len(),
        rows.join("\n")
    )
}

#[test]
fn a_2d_box_synthesis_writes_points_preview_and_report() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("grid.csv"), grid_csv()).unwrap();
    let output = motif(
        dir.path(),
        &[
            "points",
            "--exemplar",
            "grid.csv",
            "--neighbourhood",
            "1.2",
            "--domain",
            "box:6,5",
            "--out",
            "out.ply",
            "--preview",
            "preview.png",
            "--report",
            "report.json",
            "--discrete",
            "shade",
        ],
    );
    ok(&output);
    let table = motif_io::read_points(&dir.path().join("out.ply")).unwrap();
    assert!(table.rows > 20 && table.rows < 60, "{} points", table.rows);
    let (x, y, shade) = (table.column("x").unwrap(), table.column("y").unwrap(), table.column("shade").unwrap());
    for row in 0..table.rows {
        let values = table.row(row);
        assert!(values[x] >= 0.0 && values[x] <= 6.0 && values[y] >= 0.0 && values[y] <= 5.0);
        assert!(values[shade] == 0.0 || values[shade] == 1.0, "discrete shade {}", values[shade]);
    }
    let preview = motif_io::read_image(&dir.path().join("preview.png")).unwrap();
    assert!(preview.width() > 800 && preview.height() > 300);
    let report: serde_json::Value = motif_io::read_json(&dir.path().join("report.json")).unwrap();
    let energies = report["energy_per_iteration"].as_array().unwrap();
    assert!(energies.len() >= 4);
    assert!(energies.iter().all(|e| e["after_merging"].as_f64().unwrap() <= e["after_matching"].as_f64().unwrap()));
    for key in ["points_added", "points_removed", "stages_ms", "final_energy"] {
        assert!(!report[key].is_null(), "report lacks {key}");
    }
    assert!(report["stages_ms"]["matching"].as_f64().unwrap() > 0.0);
    let fidelity = &report["fidelity"];
    let output = fidelity["output"]["nearest_neighbour"].as_f64().unwrap();
    assert!(output >= 0.0 && output < fidelity["random"]["nearest_neighbour"].as_f64().unwrap());
    // The report carries the curves themselves: 40 rings of g(r) and 40 histogram bins.
    for curve in ["radial_distribution", "nearest_histogram"] {
        assert_eq!(fidelity["output_statistics"][curve].as_array().unwrap().len(), 40, "{curve}");
        assert_eq!(fidelity["exemplar_statistics"][curve].as_array().unwrap().len(), 40, "{curve}");
    }
}

#[test]
fn the_same_seed_gives_the_same_bytes_for_any_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("grid.csv"), grid_csv()).unwrap();
    let run = |threads: &str, out: &str| {
        ok(&motif(
            dir.path(),
            &[
                "points",
                "--exemplar",
                "grid.csv",
                "--neighbourhood",
                "1",
                "--domain",
                "box:5,4",
                "--threads",
                threads,
                "--seed",
                "4",
                "--out",
                out,
            ],
        ));
        std::fs::read(dir.path().join(out)).unwrap()
    };
    let one = run("1", "one.ply");
    let two = run("2", "two.ply");
    assert_eq!(one, two);
}

#[test]
fn elements_in_3d_come_out_rigid_with_their_ids() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("lattice.ply"), lattice_ply()).unwrap();
    ok(&motif(
        dir.path(),
        &[
            "points",
            "--exemplar",
            "lattice.ply",
            "--neighbourhood",
            "1.5",
            "--domain",
            "box:4,4,3",
            "--merge-iterations",
            "10",
            "--shrink",
            "0.7",
            "--out",
            "out.csv",
            "--preview",
            "view.png",
        ],
    ));
    let table = motif_io::read_points(&dir.path().join("out.csv")).unwrap();
    let (x, y, z, element) = (
        table.column("x").unwrap(),
        table.column("y").unwrap(),
        table.column("z").unwrap(),
        table.column("element").unwrap(),
    );
    let mut members: std::collections::BTreeMap<i64, Vec<[f64; 3]>> = std::collections::BTreeMap::new();
    for row in 0..table.rows {
        let v = table.row(row);
        members.entry(v[element] as i64).or_default().push([v[x], v[y], v[z]]);
    }
    assert!(members.len() >= 5, "{} elements", members.len());
    for points in members.values() {
        assert_eq!(points.len(), 2);
        let d = ((points[0][0] - points[1][0]).powi(2)
            + (points[0][1] - points[1][1]).powi(2)
            + (points[0][2] - points[1][2]).powi(2))
        .sqrt();
        // CSV keeps full precision; PLY floats would round to single precision.
        assert!((d - 0.6).abs() < 1e-6, "element length {d}");
    }
}

#[test]
fn brush_strokes_and_progressive_extension() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("grid.csv"), grid_csv()).unwrap();
    std::fs::write(
        dir.path().join("stroke.svg"),
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"20\" height=\"10\"><path d=\"M1 5 L 12 5\" stroke=\"black\"/></svg>",
    )
    .unwrap();
    ok(&motif(
        dir.path(),
        &[
            "points",
            "--exemplar",
            "grid.csv",
            "--neighbourhood",
            "1",
            "--along",
            "stroke.svg",
            "--brush-width",
            "3",
            "--scale-along",
            "1,1.5",
            "--out",
            "first.csv",
        ],
    ));
    let first = motif_io::read_points(&dir.path().join("first.csv")).unwrap();
    assert!(first.rows > 15);
    std::fs::write(dir.path().join("second.json"), "[[12, 5], [12, 12]]").unwrap();
    ok(&motif(
        dir.path(),
        &[
            "points",
            "--exemplar",
            "grid.csv",
            "--neighbourhood",
            "1",
            "--along",
            "second.json",
            "--brush-width",
            "3",
            "--existing",
            "first.csv",
            "--keep-margin",
            "1.5",
            "--out",
            "second.csv",
            "--report",
            "second.json.report",
        ],
    ));
    let second = motif_io::read_points(&dir.path().join("second.csv")).unwrap();
    assert!(second.rows > first.rows + 10, "{} then {}", first.rows, second.rows);
    // Points of the first stroke far from the second one are kept exactly.
    let (x, y) = (first.column("x").unwrap(), first.column("y").unwrap());
    let kept: Vec<(f64, f64)> = (0..second.rows).map(|r| (second.row(r)[x], second.row(r)[y])).collect();
    let far: Vec<(f64, f64)> =
        (0..first.rows).map(|r| (first.row(r)[x], first.row(r)[y])).filter(|p| p.0 < 12.0 - 1.5 - 1.5 - 1.0).collect();
    assert!(!far.is_empty());
    for p in far {
        assert!(kept.contains(&p), "{p:?} moved");
    }
}

#[test]
fn bad_input_gives_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| std::fs::write(dir.path().join(name), text).unwrap();
    write("two.csv", "x,y\n0,0\n1,1\n");
    write("nan.csv", "x,y\n0,0\n1,nan\n2,2\n3,3\n");
    write("noxy.csv", "a,b\n0,0\n1,1\n2,2\n");
    write("grid.csv", &grid_csv());
    let run = |exemplar: &str, delta: &str, domain: &str| {
        error_of(&motif(
            dir.path(),
            &["points", "--exemplar", exemplar, "--neighbourhood", delta, "--domain", domain, "--out", "out.ply"],
        ))
    };
    assert!(run("two.csv", "1", "box:5,5").contains("at least 3"));
    assert!(run("nan.csv", "1", "box:5,5").contains("non-finite coordinate"));
    assert!(run("noxy.csv", "1", "box:5,5").contains("x and y columns"));
    assert!(run("grid.csv", "0", "box:5,5").contains("invalid neighbourhood"));
    assert!(run("grid.csv", "-1", "box:5,5").contains("invalid neighbourhood"));
    assert!(run("grid.csv", "1", "box:0,5").contains("unusable domain"));
    assert!(run("grid.csv", "1", "box:0.1,0.1").contains("unusable domain"));
    assert!(run("grid.csv", "1", "box:a,5").contains("not a number"));
    assert!(run("missing.csv", "1", "box:5,5").contains("missing.csv"));
    let error = error_of(&motif(
        dir.path(),
        &["points", "--exemplar", "grid.csv", "--neighbourhood", "1", "--domain", "box:5,5", "--out", "grid.csv"],
    ));
    assert!(error.contains("also an input"), "{error}");
}

/// Sizes that once panicked, hung or succeeded with nonsense are refused up front, naming the
/// flag and the allowed range (issue 13's cases; `scripts/robustness.py` replays them all).
#[test]
fn windows_out_of_scale_and_huge_domains_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("grid.csv"), grid_csv()).unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec!["points", "--exemplar", "grid.csv", "--out", "out.csv"];
        args.extend_from_slice(extra);
        error_of(&motif(dir.path(), &args))
    };
    for (extra, expected) in [
        (&["--neighbourhood", "1e-300", "--domain", "box:8,8"][..], "invalid neighbourhood = 1e-300: must be between"),
        (&["--neighbourhood", "1e308", "--domain", "box:8,8"][..], "invalid neighbourhood = 1e308"),
        (&["--neighbourhood", "2", "--sigma", "1e300", "--domain", "box:8,8"][..], "invalid sigma = 1e300"),
        (&["--neighbourhood", "2", "--domain", "box:1000,1000"][..], "more than the 150000 allowed (max-points)"),
        (&["--neighbourhood", "2", "--domain", "box:20,20", "--max-points", "100"][..], "more than the 100 allowed"),
        (
            &["--neighbourhood", "2", "--domain", "box:8,8", "--statistics-iterations", "5000"][..],
            "invalid statistics-iterations = 5000: must be an integer between 0 and 1000",
        ),
    ] {
        let stderr = run(extra);
        assert!(stderr.contains(expected) && !stderr.contains("internal error"), "{extra:?}: {stderr}");
    }
    assert!(!dir.path().join("out.csv").exists());
    // Element ids are whole numbers.
    let mut elements = String::from("x,y,element\n");
    for i in 0..40 {
        let _ = writeln!(elements, "{},{},{}", i % 8, i / 8, f64::from(i) / 3.0);
    }
    std::fs::write(dir.path().join("elements.csv"), elements).unwrap();
    let stderr = error_of(&motif(
        dir.path(),
        &["points", "--exemplar", "elements.csv", "--neighbourhood", "2", "--domain", "box:8,8", "--out", "out.csv"],
    ));
    assert!(stderr.contains("element ids are whole numbers"), "{stderr}");
}

#[test]
fn painted_rotation_and_scale_maps_guide_a_2d_synthesis() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("grid.csv"), grid_csv()).unwrap();
    let ramp = motif_core::RgbaImage::from_fn(60, 50, |x, _| {
        let v = (x * 255 / 59) as u8;
        [v, v, v, 255]
    });
    motif_io::write_png(&dir.path().join("ramp.png"), &ramp).unwrap();
    let square = motif_core::RgbaImage::from_fn(10, 10, |_, _| [128, 128, 128, 255]);
    motif_io::write_png(&dir.path().join("square.png"), &square).unwrap();
    std::fs::write(dir.path().join("text.png"), "not an image").unwrap();
    let base = ["points", "--exemplar", "grid.csv", "--neighbourhood", "1.2", "--domain", "box:6,5"];
    let run = |extra: &[&str]| motif(dir.path(), &[&base[..], extra].concat());
    ok(&run(&["--rotation-map", "ramp.png", "--scale-map", "ramp.png", "--out", "out.csv"]));
    assert!(dir.path().join("out.csv").exists());
    let error = error_of(&run(&["--scale-map", "square.png", "--out", "never.csv"]));
    assert!(error.contains("--scale-map square.png") && error.contains("aspect"), "{error}");
    let error = error_of(&run(&["--rotation-map", "text.png", "--out", "never.csv"]));
    assert!(error.contains("text.png"), "{error}");
    let error = error_of(&run(&["--rotation-map", "missing.png", "--out", "never.csv"]));
    assert!(error.contains("missing.png"), "{error}");
    assert!(!dir.path().join("never.csv").exists());
}

#[test]
fn a_map_declaring_16384_squared_is_refused_from_its_header() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("grid.csv"), grid_csv()).unwrap();
    // 40 bytes of PNG whose header declares 16384 × 16384: it was decoded (3 GB) and accepted.
    let crafted = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../motif-io/tests/regressions/png-header-declares-16384x16384.png");
    std::fs::copy(crafted, dir.path().join("huge.png")).unwrap();
    let base = ["points", "--exemplar", "grid.csv", "--neighbourhood", "1.2", "--domain", "box:6,6"];
    let error = error_of(&motif(dir.path(), &[&base[..], &["--scale-map", "huge.png", "--out", "never.csv"]].concat()));
    assert!(error.contains("huge.png") && error.contains("16384×16384") && error.contains("67108864"), "{error}");
    let small = ["--max-memory", "50M", "stylize", "--style", "huge.png", "--guide", "huge.png", "huge.png"];
    let error = error_of(&motif(dir.path(), &[&small[..], &["--out", "never.png"]].concat()));
    assert!(error.contains("huge.png") && error.contains("--max-memory"), "{error}");
    assert!(!dir.path().join("never.csv").exists() && !dir.path().join("never.png").exists());
}

#[test]
fn a_rotation_map_turns_the_pattern_where_it_is_grey() {
    // Rows of points 1 apart along x, 3 apart along y: nearest neighbours lie along x.
    let mut rows = String::from("x,y\n");
    for y in 0..6 {
        for x in 0..24 {
            let jitter = ((x * 7 + y * 13) % 10) as f64 * 0.01;
            let _ = writeln!(rows, "{},{}", x as f64 + jitter, 3.0 * y as f64 + jitter);
        }
    }
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("rows.csv"), rows).unwrap();
    // Left half black (0°), right half grey 64 (about 90°).
    let map = motif_core::RgbaImage::from_fn(40, 20, |x, _| if x < 20 { [0, 0, 0, 255] } else { [64, 64, 64, 255] });
    motif_io::write_png(&dir.path().join("turn.png"), &map).unwrap();
    ok(&motif(
        dir.path(),
        &[
            "points",
            "--exemplar",
            "rows.csv",
            "--neighbourhood",
            "4",
            "--domain",
            "box:40,20",
            "--rotation-map",
            "turn.png",
            "--out",
            "out.csv",
        ],
    ));
    let text = std::fs::read_to_string(dir.path().join("out.csv")).unwrap();
    let points: Vec<(f64, f64)> = text
        .lines()
        .skip(1)
        .map(|line| {
            let mut values = line.split(',').map(|v| v.parse::<f64>().unwrap());
            (values.next().unwrap(), values.next().unwrap())
        })
        .collect();
    // Share of points whose nearest neighbour lies more along x than along y, per half (away
    // from the middle and the borders).
    let along_x = |x0: f64, x1: f64| {
        let chosen: Vec<&(f64, f64)> =
            points.iter().filter(|p| p.0 > x0 && p.0 < x1 && p.1 > 3.0 && p.1 < 17.0).collect();
        let horizontal = chosen
            .iter()
            .filter(|p| {
                let nearest = points
                    .iter()
                    .filter(|q| *q != **p)
                    .min_by(|a, b| {
                        let da = (a.0 - p.0).powi(2) + (a.1 - p.1).powi(2);
                        let db = (b.0 - p.0).powi(2) + (b.1 - p.1).powi(2);
                        da.total_cmp(&db)
                    })
                    .unwrap();
                (nearest.0 - p.0).abs() > (nearest.1 - p.1).abs()
            })
            .count();
        horizontal as f64 / chosen.len().max(1) as f64
    };
    let (left, right) = (along_x(3.0, 16.0), along_x(24.0, 37.0));
    assert!(left > 0.8 && right < 0.2, "left {left}, right {right}");
}

/// Without `--neighbourhood`, δ is inferred from the exemplar (4 mean nearest-neighbour spacings
/// in 2D), reported, and a real clustered pattern keeps its density and statistics: the nearest-
/// neighbour and pair-distance distances stay within 1.5× a tiled copy's and well under random's.
#[test]
fn the_neighbourhood_is_inferred_from_a_real_exemplar() {
    let dir = tempfile::tempdir().unwrap();
    let longleaf = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/points/longleaf.csv");
    let longleaf = longleaf.to_str().unwrap();
    let args = ["points", "--exemplar", longleaf, "--exemplar-window", "200,200", "--domain", "box:300,300"];
    let output = motif(dir.path(), &[&args[..], &["--out", "out.csv", "--report", "report.json"]].concat());
    ok(&output);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("report.json")).unwrap()).unwrap();
    let (delta, spacing) = (report["neighbourhood"].as_f64().unwrap(), report["exemplar_spacing"].as_f64().unwrap());
    assert_eq!(report["neighbourhood_inferred"], true);
    assert!((delta - 4.0 * spacing).abs() < 1e-9 && (3.0..4.0).contains(&spacing), "δ {delta}, spacing {spacing}");
    let fidelity = &report["fidelity"];
    let density = fidelity["density_ratio"].as_f64().unwrap();
    assert!((0.9..1.1).contains(&density), "density ratio {density}");
    for measure in ["nearest_neighbour", "radial_distribution"] {
        let of = |set: &str| fidelity[set][measure].as_f64().unwrap();
        assert!(
            of("output") <= 1.5 * of("tiled").max(0.02),
            "{measure}: {} against tiled {}",
            of("output"),
            of("tiled")
        );
        assert!(of("output") < 0.5 * of("random"), "{measure}: {} against random {}", of("output"), of("random"));
    }
    // A given value still wins.
    let given = motif(
        dir.path(),
        &[&args[..], &["--neighbourhood", "10", "--out", "given.csv", "--report", "given.json"]].concat(),
    );
    ok(&given);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("given.json")).unwrap()).unwrap();
    assert_eq!(
        (report["neighbourhood"].as_f64(), report["neighbourhood_inferred"].as_bool()),
        (Some(10.0), Some(false))
    );
}
