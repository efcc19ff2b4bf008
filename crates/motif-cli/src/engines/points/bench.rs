//! `motif bench --engine points`: the paper's three sizes (Table 1) on generated exemplars, and the
//! real-data corpus (`points_corpus`).

use motif_core::TriangleMesh;
use motif_points::samples::{hex_exemplar, lattice_exemplar, ripple_exemplar, sphere_mesh, torus_mesh};
use motif_points::{Domain, Evaluator, Field, Input, Params, PointSet};
use serde_json::{Value, json};

use crate::suite::Bench;

/// One benchmark case: seconds, final T, fidelity.
fn bench_case(
    exemplar: &PointSet,
    domain: Domain,
    neighbourhood: f64,
    quadrature: f64,
    seed: u64,
    with_reference: bool,
) -> anyhow::Result<Value> {
    let mut params = Params::default();
    params.neighbourhood = Some(neighbourhood);
    params.quadrature_spacing = Some(quadrature);
    params.seed = seed;
    let input = Input::new(exemplar.clone(), domain);
    let start = std::time::Instant::now();
    let output = motif_points::synthesize(&input, &params, &mut motif_core::NoProgress)?;
    let seconds = start.elapsed().as_secs_f64();
    let comparison = motif_points::compare_evaluators(&input, &params)?;
    // The whole synthesis again with the plain reference energy (small cases only): the fast path
    // must give the same structure fidelity.
    let reference = if with_reference {
        params.evaluator = Evaluator::Reference;
        let start = std::time::Instant::now();
        let output = motif_points::synthesize(&input, &params, &mut motif_core::NoProgress)?;
        json!({
            "seconds": start.elapsed().as_secs_f64(),
            "final_energy": output.report.final_energy,
            "output_points": output.points.len(),
            "nearest_neighbour_distance": output.report.fidelity.output.nearest_neighbour,
            "radial_distribution_distance": output.report.fidelity.output.radial_distribution,
        })
    } else {
        Value::Null
    };
    Ok(json!({
        "reference_synthesis": reference,
        "exemplar_points": exemplar.len(),
        "output_points": output.points.len(),
        "neighbourhood": neighbourhood,
        "quadrature_spacing_sigma": quadrature,
        "quadrature_points": output.report.quadrature_points,
        "seconds": seconds,
        "final_energy": output.report.final_energy,
        "density_ratio": output.report.fidelity.density_ratio,
        "nearest_neighbour_distance": output.report.fidelity.output.nearest_neighbour,
        "radial_distribution_distance": output.report.fidelity.output.radial_distribution,
        "stages_ms": crate::context::stages_object(&output.report.stages_ms),
        "merge_steps_per_scale": output.report.energy.iter().map(|e| e.merge_steps).collect::<Vec<_>>(),
        "energy_evaluation": {
            "fast_ms": comparison.fast_ms,
            "reference_ms": comparison.reference_ms,
            "speedup": comparison.reference_ms / comparison.fast_ms.max(1e-9),
            "relative_difference": (comparison.fast_energy - comparison.reference_energy).abs() / comparison.reference_energy.abs().max(1e-300),
        },
    }))
}

/// Surface reconstruction of `count` points with normals on a sphere of radius 100 (run with
/// `--case reconstruction`): seconds, triangles and the largest radius error.
fn reconstruction(count: usize) -> anyhow::Result<Value> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let normals: Vec<[f64; 3]> = (0..count)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / count as f64;
            let r = (1.0 - z * z).sqrt();
            let angle = golden * i as f64;
            [r * motif_core::math::cos(angle), r * motif_core::math::sin(angle), z]
        })
        .collect();
    let positions: Vec<[f64; 3]> = normals.iter().map(|n| n.map(|v| 100.0 * v)).collect();
    let start = std::time::Instant::now();
    let mesh = motif_points::reconstruct_surface(&positions, &normals)?;
    let seconds = start.elapsed().as_secs_f64();
    let error = mesh
        .vertices
        .iter()
        .map(|v| ((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt() - 100.0).abs())
        .fold(0.0, f64::max);
    Ok(json!({
        "points": count,
        "seconds": seconds,
        "target_seconds": 10.0,
        "triangles": mesh.triangles.len(),
        "largest_radius_error_percent": error,
    }))
}

/// A real pattern on surfaces (run with `--case surface`): the Swedish pines of the corpus on
/// CGAL's bull (12 396 triangles) scaled so that it holds about 20 000 trees, and on a torus and
/// a sphere, each beside the same exemplar in a square box of the mesh's area: seconds of both,
/// count and fidelity against the random and tiled baselines (issue 35: density within 5 %, time
/// within 3× the box's).
fn surfaces(seed: u64) -> anyhow::Result<Value> {
    let table = motif_io::read_points(&crate::suite::corpus_folder("points").join("swedishpines.csv"))?;
    let (exemplar, _) = super::table_to_points(&table, "swedishpines.csv")?;
    let mut bull = motif_io::read_mesh(&crate::suite::corpus_folder("meshes").join("bull.obj"))?;
    // 1 585 dm long: about 20 000 pines come out (the plot's density asks for 21 200).
    bull.vertices.iter_mut().for_each(|v| *v = v.map(|c| 1585.0 * c));
    Ok(json!({
        "bull_20000": surface_case(&exemplar, bull, 1.0, seed)?,
        "torus_400_150_scale_2_5": surface_case(&exemplar, torus_mesh(400.0, 150.0, 96, 48), 2.5, seed)?,
        "sphere_200": surface_case(&exemplar, sphere_mesh(200.0, 48, 96), 1.0, seed)?,
        "target_seconds_bull": 60.0,
        "target_time_over_box": 3.0,
    }))
}

/// A real 3D sheet inside a real mesh's volume (run with `--case volume`): CGAL's fin (the
/// corpus's `fin_sheet`, 757 points with normals) at half scale inside CGAL's bull, with the
/// fidelity and thickness figures against the random and tiled baselines (issue 35: within 1.5×
/// of the tiled copy, layers kept).
fn sheet_in_volume(seed: u64) -> anyhow::Result<Value> {
    let folder = crate::suite::corpus_folder("points");
    let table = motif_io::read_points(&folder.join("fin_sheet.csv"))?;
    let (exemplar, _) = super::table_to_points(&table, "fin_sheet.csv")?;
    let bull = motif_io::read_mesh(&crate::suite::corpus_folder("meshes").join("bull.obj"))?;
    let mut params = Params::default().with_neighbourhood(Some(0.058)).with_seed(seed).with_scale(Field::Uniform(0.5));
    params.exemplar_window = Some((vec![0.0; 3], vec![1.1593, 0.7426, 0.7861]));
    let start = std::time::Instant::now();
    let input = motif_points::Input::new(exemplar, Domain::Volume(bull));
    let output = motif_points::synthesize(&input, &params, &mut motif_core::NoProgress)?;
    let fidelity = &output.report.fidelity;
    let (o, r, t) = (&fidelity.output, &fidelity.random, &fidelity.tiled);
    Ok(json!({
        "seconds": start.elapsed().as_secs_f64(),
        "points": output.points.len(),
        "expected_points": output.report.expected_points,
        "density_ratio": fidelity.density_ratio,
        "nearest_neighbour_distance": { "output": o.nearest_neighbour, "random": r.nearest_neighbour, "tiled": t.nearest_neighbour },
        "radial_distribution_distance": { "output": o.radial_distribution, "random": r.radial_distribution, "tiled": t.radial_distribution },
        "thickness": {
            "exemplar": fidelity.exemplar_statistics.thickness,
            "output": o.thickness_ratio, "random": r.thickness_ratio, "tiled": t.thickness_ratio,
        },
        "stages_ms": output.report.stages_ms,
    }))
}

/// `exemplar` on `mesh` at `scale`, and in a square box of the mesh's area.
fn surface_case(exemplar: &PointSet, mesh: TriangleMesh, scale: f64, seed: u64) -> anyhow::Result<Value> {
    let triangles = mesh.triangles.len();
    let params = Params::default().with_neighbourhood(Some(32.0)).with_seed(seed).with_scale(Field::Uniform(scale));
    let run = |domain: Domain| -> anyhow::Result<(motif_points::Output, f64)> {
        let start = std::time::Instant::now();
        let input = motif_points::Input::new(exemplar.clone(), domain);
        let output = motif_points::synthesize(&input, &params, &mut motif_core::NoProgress)?;
        Ok((output, start.elapsed().as_secs_f64()))
    };
    let directions = motif_points::SurfaceDirections::Curvature;
    let (output, seconds) = run(Domain::Surface { mesh, directions })?;
    let side = output.report.surface.as_ref().map_or(0.0, |s| s.area.sqrt());
    let (in_box, box_seconds) = run(Domain::Box { min: vec![0.0; 2], max: vec![side, side] })?;
    let fidelity = &output.report.fidelity;
    Ok(json!({
        "triangles": triangles,
        "scale": scale,
        "points": output.points.len(),
        "initial_points": output.report.initial_points,
        "expected_points": output.report.expected_points,
        "seconds": seconds,
        "box_seconds": box_seconds,
        "box_points": in_box.points.len(),
        "time_over_box": seconds / box_seconds.max(1e-9),
        "density_ratio": fidelity.density_ratio,
        "nearest_neighbour_distance": { "output": fidelity.output.nearest_neighbour, "random": fidelity.random.nearest_neighbour, "tiled": fidelity.tiled.nearest_neighbour },
        "radial_distribution_distance": { "output": fidelity.output.radial_distribution, "random": fidelity.random.radial_distribution, "tiled": fidelity.tiled.radial_distribution },
        "surface": output.report.surface,
        "stages_ms": output.report.stages_ms,
        "box_stages_ms": in_box.report.stages_ms,
    }))
}

/// Figures for `motif bench`: the paper's three sizes (Table 1) on generated exemplars, and every
/// case of the real-data corpus with its fidelity against the random and tiled baselines.
pub(super) fn bench(bench: &Bench) -> anyhow::Result<Value> {
    if bench.quick {
        let exemplar = hex_exemplar(8, 8, 0.1, bench.seed);
        let box2 = Domain::Box { min: vec![0.0; 2], max: vec![4.0, 4.0] };
        let quick_case = |name: &str| name == "swedishpines";
        return Ok(json!({
            "quick_64_to_16": bench_case(&exemplar, box2, 1.0, 2.0, bench.seed, true)?,
            "real_data": super::corpus::bench(bench.seed, &quick_case, &quick_case)?,
        }));
    }
    // helix-size: 600 → 100 (2D), sand-size: 1600 → 7200 (2D), chair-size: 1100 → 23000 (3D box),
    // then the corpus cases by name; `--case helix`, `--case longleaf`, ... runs those alone, and
    // `--case generated` or `--case corpus` each group (default: everything but the slow cases).
    let generated = ["helix", "sand", "chair"];
    let selected = |name: &str| {
        let group = if generated.contains(&name) { "generated" } else { "corpus" };
        bench.selects(name, group)
    };
    let mut figures = serde_json::Map::new();
    let named = |name: &str| bench.names(name);
    let corpus = super::corpus::bench(bench.seed, &|name| !generated.contains(&name) && selected(name), &named)?;
    figures.insert("real_data".into(), corpus);
    if selected("helix") {
        let helix = hex_exemplar(30, 20, 0.1, bench.seed);
        let domain = Domain::Box { min: vec![0.0; 2], max: vec![11.5, 7.5] };
        figures.insert("helix_600_to_100".into(), bench_case(&helix, domain, 1.0, 2.0, bench.seed, true)?);
    }
    if selected("sand") {
        let sand = ripple_exemplar(1600, bench.seed);
        let domain = Domain::Box { min: vec![0.0; 2], max: vec![90.0, 80.0] };
        figures.insert("sand_1600_to_7200".into(), bench_case(&sand, domain, 1.0, 2.0, bench.seed, false)?);
    }
    if selected("chair") {
        let chair = lattice_exemplar(1100, bench.seed);
        let domain = Domain::Box { min: vec![0.0; 3], max: vec![31.0, 31.0, 27.2] };
        figures.insert("chair_1100_to_23000".into(), bench_case(&chair, domain, 0.75, 2.0, bench.seed, false)?);
    }
    if bench.names("surface") {
        figures.insert("surfaces".into(), surfaces(bench.seed)?);
    }
    if bench.names("volume") {
        figures.insert("fin_sheet_in_bull".into(), sheet_in_volume(bench.seed)?);
    }
    if bench.names("reconstruction") {
        figures.insert("reconstruction_50000".into(), reconstruction(50_000)?);
    }
    figures.insert("paper_seconds".into(), json!({ "helix": 4.0, "sand": 120.0, "chair": 360.0 }));
    figures.insert("target_seconds".into(), json!({ "helix": 0.3, "sand": 10.0, "chair": 60.0 }));
    Ok(Value::Object(figures))
}
