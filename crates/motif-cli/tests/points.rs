//! `motif points` end to end: files in, files out, reports, determinism, guidance and bad input.

use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, Output};

fn motif(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_motif")).current_dir(dir).args(args).output().unwrap()
}

fn ok(output: &Output) {
    assert!(output.status.success(), "stderr: {}", String::from_utf8_lossy(&output.stderr));
}

fn error_of(output: &Output) -> String {
    assert!(!output.status.success(), "expected a failure");
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// A jittered 12 × 12 grid (spacing 1) with a `shade` attribute striped along y, as CSV.
fn grid_csv() -> String {
    let mut text = String::from("x,y,shade\n");
    for y in 0..12 {
        for x in 0..12 {
            let jitter = ((x * 7 + y * 13) % 10) as f64 * 0.01;
            let _ = writeln!(text, "{},{},{}", x as f64 + jitter, y as f64 - jitter, y % 2);
        }
    }
    text
}

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

/// An octahedron |x − 4| + |y − 4| + |z − 4| ≤ 4 as OBJ, without its last face when `open`.
fn octahedron_obj(open: bool) -> String {
    let mut text = String::from("v 8 4 4\nv 0 4 4\nv 4 8 4\nv 4 0 4\nv 4 4 8\nv 4 4 0\n");
    let faces = [(1, 3, 5), (3, 2, 5), (2, 4, 5), (4, 1, 5), (3, 1, 6), (2, 3, 6), (4, 2, 6), (1, 4, 6)];
    for (a, b, c) in &faces[..if open { 7 } else { 8 }] {
        let _ = writeln!(text, "f {a} {b} {c}");
    }
    text
}

#[test]
fn a_volume_domain_fills_a_closed_mesh_and_refuses_open_ones() {
    let dir = tempfile::tempdir().unwrap();
    let mut cloud = String::from("x,y,z\n");
    for z in 0..6 {
        for y in 0..6 {
            for x in 0..6 {
                let jitter = ((x * 7 + y * 13 + z * 5) % 10) as f64 * 0.01;
                let _ = writeln!(cloud, "{},{},{}", x as f64 + jitter, y as f64 - jitter, z as f64 + jitter);
            }
        }
    }
    std::fs::write(dir.path().join("cloud.csv"), cloud).unwrap();
    std::fs::write(dir.path().join("solid.obj"), octahedron_obj(false)).unwrap();
    std::fs::write(dir.path().join("open.obj"), octahedron_obj(true)).unwrap();
    let base = ["points", "--exemplar", "cloud.csv", "--neighbourhood", "1.2"];
    let run = |extra: &[&str]| motif(dir.path(), &[&base[..], extra].concat());
    ok(&run(&["--domain", "volume:solid.obj", "--out", "out.csv", "--report", "report.json"]));
    let text = std::fs::read_to_string(dir.path().join("out.csv")).unwrap();
    let points: Vec<Vec<f64>> =
        text.lines().skip(1).map(|l| l.split(',').take(3).map(|v| v.parse().unwrap()).collect()).collect();
    // One point per unit volume: the octahedron holds 4/3 × 4³ ≈ 85.
    assert!((points.len() as f64 - 85.3).abs() < 13.0, "{} points", points.len());
    for p in &points {
        let l1: f64 = p.iter().map(|v| (v - 4.0).abs()).sum();
        assert!(l1 <= 4.0 + 1e-9, "{p:?} outside");
    }
    let error = error_of(&run(&["--domain", "volume:open.obj", "--out", "never.csv"]));
    assert!(error.contains("open.obj") && error.contains("closed surface"), "{error}");
    let error = error_of(&run(&["--domain", "volume:missing.obj", "--out", "never.csv"]));
    assert!(error.contains("missing.obj"), "{error}");
    std::fs::write(dir.path().join("grid.csv"), grid_csv()).unwrap();
    let flat = ["points", "--exemplar", "grid.csv", "--neighbourhood", "1.2", "--domain", "volume:solid.obj"];
    let error = error_of(&motif(dir.path(), &[&flat[..], &["--out", "never.csv"]].concat()));
    assert!(error.contains("3D exemplar"), "{error}");
    assert!(!dir.path().join("never.csv").exists());
}

#[test]
fn surface_out_reconstructs_points_with_normals_and_refuses_points_without() {
    let dir = tempfile::tempdir().unwrap();
    // A wavy sheet of points around z = 2 with its normals, in a 6 × 6 × 4 exemplar.
    let mut sheet = String::from("x,y,z,nx,ny,nz\n");
    for y in 0..12 {
        for x in 0..12 {
            let (u, v) = (0.5 * x as f64, 0.5 * y as f64);
            let z = 2.0 + 0.3 * u.sin() + 0.3 * v.sin();
            let n = [-0.3 * u.cos(), -0.3 * v.cos(), 1.0];
            let length = (n[0] * n[0] + n[1] * n[1] + 1.0f64).sqrt();
            let _ = writeln!(sheet, "{u},{v},{z},{},{},{}", n[0] / length, n[1] / length, n[2] / length);
        }
    }
    std::fs::write(dir.path().join("sheet.csv"), sheet).unwrap();
    ok(&motif(
        dir.path(),
        &[
            "points",
            "--exemplar",
            "sheet.csv",
            "--neighbourhood",
            "1.0",
            "--domain",
            "box:6,6,4",
            "--out",
            "out.csv",
            "--surface-out",
            "sheet.obj",
            "--preview",
            "sheet.png",
        ],
    ));
    // The preview draws the surface, shaded, in place of the output's points.
    assert!(motif_io::read_image(&dir.path().join("sheet.png")).is_ok());
    let text = std::fs::read_to_string(dir.path().join("sheet.obj")).unwrap();
    let vertices: Vec<f64> =
        text.lines().filter(|l| l.starts_with("v ")).map(|l| l.split(' ').nth(3).unwrap().parse().unwrap()).collect();
    assert!(vertices.len() > 20 && text.lines().any(|l| l.starts_with("f ")), "{text}");
    let (low, high) = vertices.iter().fold((f64::MAX, f64::MIN), |(a, b), &z| (a.min(z), b.max(z)));
    assert!(low > -1.0 && high < 5.0, "z from {low} to {high}");
    std::fs::write(dir.path().join("grid.csv"), grid_csv()).unwrap();
    let error = error_of(&motif(
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
            "never.csv",
            "--surface-out",
            "never.obj",
        ],
    ));
    assert!(error.contains("--surface-out") && error.contains("nx, ny, nz"), "{error}");
    assert!(!dir.path().join("never.csv").exists() && !dir.path().join("never.obj").exists());
}

#[test]
fn surface_domains_keep_points_on_the_mesh_and_refuse_bad_fields() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("grid.csv"), grid_csv()).unwrap();
    std::fs::write(dir.path().join("solid.obj"), octahedron_obj(false)).unwrap();
    let base = ["points", "--exemplar", "grid.csv", "--neighbourhood", "1.5", "--domain", "surface:solid.obj"];
    let run = |extra: &[&str]| motif(dir.path(), &[&base[..], extra].concat());
    ok(&run(&["--out", "out.csv", "--report", "report.json"]));
    let text = std::fs::read_to_string(dir.path().join("out.csv")).unwrap();
    let points: Vec<Vec<f64>> =
        text.lines().skip(1).map(|l| l.split(',').take(3).map(|v| v.parse().unwrap()).collect()).collect();
    // Eight faces of side 4√2: area 64√3 ≈ 110.9 at one point per unit area.
    assert!((points.len() as f64 - 110.9).abs() < 15.0, "{} points", points.len());
    for p in &points {
        let l1: f64 = p.iter().map(|v| (v - 4.0).abs()).sum();
        assert!((l1 - 4.0).abs() <= 1e-6 * 8.0, "{p:?} is off the surface");
    }
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("report.json")).unwrap()).unwrap();
    let area = report["surface"]["area"].as_f64().unwrap();
    assert!((area - 64.0 * 3f64.sqrt()).abs() < 1e-9, "area {area}");
    let error = error_of(&run(&["--surface-directions", "0,0,0", "--out", "never.csv"]));
    assert!(error.contains("solid.obj") && error.contains("not finite, or is zero"), "{error}");
    std::fs::write(dir.path().join("vectors.csv"), "x,y,z\n1,0,0\n0,1,0\n").unwrap();
    let error = error_of(&run(&["--surface-directions", "vectors.csv", "--out", "never.csv"]));
    assert!(error.contains("2 vectors but the mesh has 6 vertices"), "{error}");
    ok(&run(&["--surface-directions", "0,0,1", "--out", "along_z.csv"]));
    let error = error_of(&motif(
        dir.path(),
        &["points", "--exemplar", "grid.csv", "--neighbourhood", "1.5", "--domain", "box:6,6"]
            .into_iter()
            .chain(["--surface-directions", "1,0,0", "--out", "never.csv"])
            .collect::<Vec<_>>(),
    ));
    assert!(error.contains("--surface-directions needs --domain surface:"), "{error}");
    let cloud: String = std::iter::once("x,y,z".to_string())
        .chain((0..40).map(|i| format!("{},{},{}", i % 4, (i / 4) % 5, i / 20)))
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(dir.path().join("cloud.csv"), cloud).unwrap();
    let error = error_of(&motif(
        dir.path(),
        &[
            "points",
            "--exemplar",
            "cloud.csv",
            "--neighbourhood",
            "1.5",
            "--domain",
            "surface:solid.obj",
            "--out",
            "never.csv",
        ],
    ));
    assert!(error.contains("needs a 2D exemplar"), "{error}");
    assert!(!dir.path().join("never.csv").exists());
}

#[test]
fn element_meshes_stand_on_each_output_point_along_the_normal() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("grid.csv"), grid_csv()).unwrap();
    std::fs::write(dir.path().join("solid.obj"), octahedron_obj(false)).unwrap();
    // A tetrahedron standing on its base around the z axis: its apex is at z = 2.
    std::fs::write(
        dir.path().join("spike.obj"),
        "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nv 0 0 2\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n",
    )
    .unwrap();
    let base = ["points", "--exemplar", "grid.csv", "--neighbourhood", "1.5", "--domain", "surface:solid.obj"];
    let run = |extra: &[&str]| motif(dir.path(), &[&base[..], extra].concat());
    let placed = ["--element-mesh", "spike.obj", "--element-size", "0.5", "--surface-out", "spikes.obj"];
    ok(&run(&[&placed[..], &["--out", "out.csv", "--preview", "preview.png"]].concat()));
    let text = std::fs::read_to_string(dir.path().join("out.csv")).unwrap();
    let points: Vec<[f64; 3]> = text
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').take(3).map(|v| v.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    let mesh = std::fs::read_to_string(dir.path().join("spikes.obj")).unwrap();
    let vertices: Vec<[f64; 3]> = mesh
        .lines()
        .filter(|l| l.starts_with("v "))
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().skip(1).map(|v| v.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    assert_eq!(vertices.len(), 4 * points.len());
    assert_eq!(mesh.lines().filter(|l| l.starts_with("f ")).count(), 4 * points.len());
    let l1 = |p: &[f64; 3]| p.iter().map(|v| (v - 4.0).abs()).sum::<f64>();
    for (point, copy) in points.iter().zip(vertices.chunks(4)) {
        // Largest side 2 scaled to 0.5: the apex stands 0.5 off the point along the normal (the
        // vertex normals interpolated, so between a face's normal and its corners'), off the
        // surface (a tangent step would keep the L1 norm that measures it at 4).
        let apex = copy[3];
        let rise: Vec<f64> = (0..3).map(|a| apex[a] - point[a]).collect();
        let length = rise.iter().map(|r| r * r).sum::<f64>().sqrt();
        assert!((length - 0.5).abs() < 1e-9, "apex {length} from its point");
        assert!((l1(&apex) - l1(point)).abs() > 0.2, "apex {apex:?} should leave the surface at {point:?}");
        let middle: Vec<f64> = (0..3).map(|a| (copy[0][a] + copy[1][a]) / 2.0 - point[a]).collect();
        assert!(middle.iter().map(|m| m * m).sum::<f64>().sqrt() < 0.26, "base not on the point");
    }
    assert!(dir.path().join("preview.png").exists());
    let error = error_of(&run(&["--element-mesh", "missing.obj", "--surface-out", "never.obj", "--out", "never.csv"]));
    assert!(error.contains("missing.obj"), "{error}");
    let error =
        error_of(&run(
            &[&placed[..4], &["--surface-out", "never.obj", "--element-size", "-1", "--out", "never.csv"]].concat()
        ));
    assert!(error.contains("--element-size"), "{error}");
    assert!(!dir.path().join("never.csv").exists() && !dir.path().join("never.obj").exists());
}
