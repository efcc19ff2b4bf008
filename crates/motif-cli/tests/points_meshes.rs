//! `motif points` with meshes end to end: volume and surface domains, surface reconstruction and
//! element meshes.

#![allow(
    clippy::disallowed_methods,
    reason = "a test input drawn with the platform's math library: the command line never runs in WebAssembly"
)]

use std::fmt::Write as _;

mod common;
use common::{error_of, grid_csv, motif, ok};

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
fn surface_out_without_normals_among_the_attributes_is_refused_before_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let mut sheet = String::from("x,y,z,nx,ny,nz,radius\n");
    for i in 0..216 {
        let (x, y, z) = ((i % 6) as f64, ((i / 6) % 6) as f64, (i / 36) as f64);
        let _ = writeln!(sheet, "{x},{y},{z},0,0,1,{}", 0.1 + 0.01 * (i % 7) as f64);
    }
    std::fs::write(dir.path().join("sheet.csv"), sheet).unwrap();
    let args = [
        "points",
        "--exemplar",
        "sheet.csv",
        "--neighbourhood",
        "1.2",
        "--domain",
        "box:6,6,6",
        "--attributes",
        "radius",
    ];
    let output = motif(dir.path(), &[&args[..], &["--out", "never.csv", "--surface-out", "never.obj"]].concat());
    // It panicked after the whole run; now it is an error, and no run.
    let error = error_of(&output);
    assert!(
        error.contains("--surface-out") && error.contains("--attributes radius") && error.contains("nx"),
        "{error}"
    );
    assert!(!String::from_utf8_lossy(&output.stderr).contains("panicked"));
    assert!(!dir.path().join("never.csv").exists() && !dir.path().join("never.obj").exists());
}

#[test]
fn surface_domains_keep_points_on_the_mesh_and_refuse_bad_fields() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("grid.csv"), grid_csv()).unwrap();
    std::fs::write(dir.path().join("solid.obj"), octahedron_obj(false)).unwrap();
    let base = ["points", "--exemplar", "grid.csv", "--neighbourhood", "1.5", "--domain", "surface:solid.obj"];
    let run = |extra: &[&str]| motif(dir.path(), &[&base[..], extra].concat());
    ok(&run(&["--out", "out.csv", "--report", "report.json", "--preview", "preview.png"]));
    // The preview draws the points over the domain mesh, shaded grey: the output panel (the
    // middle third) holds both grey mesh pixels and the points' dark ones.
    let preview = motif_io::read_image(&dir.path().join("preview.png")).unwrap();
    let (mut grey, mut dark) = (0, 0);
    for y in 0..preview.height() {
        for x in preview.width() / 3..2 * preview.width() / 3 {
            let [r, g, b, _] = preview.get(x, y);
            grey += usize::from(r == g && g == b && (100..250).contains(&r));
            dark += usize::from(r < 80 && g < 80 && b < 100);
        }
    }
    assert!(grey > 5_000 && dark > 500, "grey {grey}, dark {dark}");
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
