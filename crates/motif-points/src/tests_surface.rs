//! Surface domains: points on the mesh, the same statistics on a flat mesh as in a box, frames
//! along a cylinder's principal directions, bad meshes refused.

use motif_core::{NoProgress, TriangleMesh};

use crate::mesh_surface::MeshSurface;
use crate::samples::{hex_exemplar, torus_mesh};
use crate::{
    Domain, DomainProblem, Error, Field, Initialization, Input, InputError, Params, SurfaceDirections, synthesize,
};

/// The square `[0, side]²` in the plane z = `height`, as `cells × cells` pairs of triangles.
pub(crate) fn flat_mesh(side: f64, cells: u32, height: f64) -> TriangleMesh {
    let step = side / f64::from(cells);
    let vertices = (0..(cells + 1) * (cells + 1))
        .map(|i| [f64::from(i % (cells + 1)) * step, f64::from(i / (cells + 1)) * step, height])
        .collect();
    let mut triangles = Vec::new();
    for y in 0..cells {
        for x in 0..cells {
            let a = y * (cells + 1) + x;
            triangles.push([a, a + 1, a + cells + 2]);
            triangles.push([a, a + cells + 2, a + cells + 1]);
        }
    }
    TriangleMesh { vertices, triangles }
}

/// A cylinder of radius `r` and height `height` around the z axis, open at both ends.
pub(crate) fn cylinder(r: f64, height: f64, rings: usize, around: usize) -> TriangleMesh {
    let mut vertices = Vec::new();
    for i in 0..rings {
        for j in 0..around {
            let angle = std::f64::consts::TAU * j as f64 / around as f64;
            let z = height * i as f64 / (rings - 1) as f64;
            vertices.push([r * motif_core::math::cos(angle), r * motif_core::math::sin(angle), z]);
        }
    }
    let mut triangles = Vec::new();
    for i in 0..rings - 1 {
        for j in 0..around {
            let (a, b) = ((i * around + j) as u32, (i * around + (j + 1) % around) as u32);
            let (c, d) = (a + around as u32, b + around as u32);
            triangles.push([a, b, d]);
            triangles.push([a, d, c]);
        }
    }
    TriangleMesh { vertices, triangles }
}

/// The 71 Swedish pines of the real-data corpus (positions in decimetres).
fn swedish_pines() -> crate::PointSet {
    let text = include_str!("../../../data/real/points/swedishpines.csv");
    let positions: Vec<f64> = text
        .lines()
        .skip(1)
        .flat_map(|line| line.split(',').take(2).map(|v| v.trim().parse::<f64>().unwrap()).collect::<Vec<_>>())
        .collect();
    crate::PointSet::new(2, positions)
}

fn params() -> Params {
    Params::default().with_neighbourhood(Some(2.0)).with_seed(3).with_initialization(Initialization::Random)
}

#[test]
fn a_flat_mesh_gives_the_statistics_of_a_box() {
    let exemplar = swedish_pines();
    let side = 300.0;
    // Patch initialization (the default), whose copies on a surface are laid in the tangent planes;
    // without the pair-statistics refinement, whose relocation runs in flat domains only.
    let params = Params::default().with_neighbourhood(Some(32.0)).with_seed(3).with_statistics_iterations(0);
    let in_box = synthesize(
        &Input::new(exemplar.clone(), Domain::Box { min: vec![0.0, 0.0], max: vec![side, side] }),
        &params,
        &mut NoProgress,
    )
    .unwrap();
    let surface = Domain::Surface { mesh: flat_mesh(side, 9, 2.5), directions: SurfaceDirections::Curvature };
    let on_mesh = synthesize(&Input::new(exemplar, surface), &params, &mut NoProgress).unwrap();
    assert_eq!(on_mesh.points.dimension, 3);
    for i in 0..on_mesh.points.len() {
        let z = on_mesh.points.position(i)[2];
        assert!((z - 2.5).abs() <= 1e-6 * side, "point {i} is off the plane: z = {z}");
    }
    let (a, b) = (&in_box.report.fidelity, &on_mesh.report.fidelity);
    assert!(
        (b.density_ratio - a.density_ratio).abs() < 0.05,
        "density ratio: box {}, mesh {}",
        a.density_ratio,
        b.density_ratio
    );
    assert!((b.density_ratio - 1.0).abs() < 0.1, "density ratio on the mesh {}", b.density_ratio);
    for (name, box_figure, mesh_figure, random) in [
        ("nearest-neighbour", a.output.nearest_neighbour, b.output.nearest_neighbour, b.random.nearest_neighbour),
        ("g(r)", a.output.radial_distribution, b.output.radial_distribution, b.random.radial_distribution),
    ] {
        assert!(
            (mesh_figure - box_figure).abs() < 0.05 + 0.5 * box_figure,
            "{name}: box {box_figure:.3}, flat mesh {mesh_figure:.3}"
        );
        assert!(mesh_figure < random, "{name}: flat mesh {mesh_figure:.3}, random {random:.3}");
    }
}

/// A scale `s` on a surface divides the pattern's density by `s²` (it is planar there): the
/// count once divided by `s³`, the lifted exemplar's own dimension (41 % of the density on a torus
/// at `--scale 2.5`).
#[test]
fn a_scaled_pattern_keeps_its_density_on_a_surface() {
    let exemplar = swedish_pines();
    let side = 300.0;
    let run = |scale: f64| {
        let params = Params::default().with_neighbourhood(Some(32.0)).with_seed(3).with_scale(Field::Uniform(scale));
        let surface = Domain::Surface { mesh: flat_mesh(side, 9, 2.5), directions: SurfaceDirections::Curvature };
        synthesize(&Input::new(exemplar.clone(), surface), &params, &mut NoProgress).unwrap()
    };
    let unscaled = run(1.0).report.expected_points;
    for scale in [1.5, 2.0] {
        let output = run(scale);
        let expected = unscaled / (scale * scale);
        let n = output.points.len() as f64;
        assert!(
            (output.report.expected_points / expected - 1.0).abs() < 0.02,
            "{scale}: {}",
            output.report.expected_points
        );
        assert!((n / expected - 1.0).abs() < 0.05, "scale {scale}: {n} points for {expected:.0}");
    }
}

/// Patch copies laid in tangent planes land on the surface: on a torus whose tube is as narrow
/// as the patches, the copies put 82 % of the points the density asks for when the points laid
/// off the thin band were dropped; now they are settled onto the surface.
#[test]
fn patch_copies_fill_a_torus() {
    let exemplar = swedish_pines();
    let surface = Domain::Surface { mesh: torus_mesh(100.0, 40.0, 64, 32), directions: SurfaceDirections::Curvature };
    let params = Params::default().with_neighbourhood(Some(32.0)).with_seed(3);
    let output = synthesize(&Input::new(exemplar, surface), &params, &mut NoProgress).unwrap();
    let expected = output.report.expected_points;
    let initial = output.report.initial_points as f64;
    assert!((initial / expected - 1.0).abs() < 0.1, "{initial} initial points for {expected:.0}");
    let n = output.points.len() as f64;
    assert!((n / expected - 1.0).abs() < 0.05, "{n} points for {expected:.0}");
    let fidelity = &output.report.fidelity;
    assert!(fidelity.output.radial_distribution < 0.5 * fidelity.random.radial_distribution, "{fidelity:?}");
}

#[test]
fn points_stay_on_a_cylinder_and_frames_follow_its_axis() {
    let mesh = cylinder(4.0, 12.0, 25, 64);
    let surface = MeshSurface::new(&mesh, &SurfaceDirections::Curvature).unwrap();
    for p in [[4.0, 0.0, 6.0], [0.0, -4.1, 3.0], [2.0, 2.0, 9.0]] {
        let frame = surface.frame(&p);
        // The exemplar's x axis (first column) runs along the axis; its third axis is radial.
        assert!(frame[2][0].abs() > 0.99, "x axis {:?} at {p:?}", [frame[0][0], frame[1][0], frame[2][0]]);
        let radial = [p[0], p[1]];
        let length = (radial[0] * radial[0] + radial[1] * radial[1]).sqrt();
        assert!((frame[0][2] * radial[0] + frame[1][2] * radial[1]).abs() / length > 0.99);
    }
    let input =
        Input::new(hex_exemplar(8, 8, 0.08, 2), Domain::Surface { mesh, directions: SurfaceDirections::Curvature });
    let output = synthesize(&input, &params(), &mut NoProgress).unwrap();
    let n = output.points.len() as f64;
    let expected = output.report.expected_points;
    assert!((n - expected).abs() < 0.1 * expected, "{n} points for {expected}");
    for i in 0..output.points.len() {
        let p = output.points.position(i);
        let distance = surface.closest(&[p[0], p[1], p[2]]).distance;
        assert!(distance <= 1e-6 * 12.0, "point {i} is {distance} off the surface");
    }
    assert!(output.report.fidelity.output.nearest_neighbour < 0.5 * output.report.fidelity.random.nearest_neighbour);
}

#[test]
fn bad_surfaces_are_refused() {
    let exemplar = hex_exemplar(6, 6, 0.05, 1);
    let refuse = |mesh: TriangleMesh, directions: SurfaceDirections| match synthesize(
        &Input::new(exemplar.clone(), Domain::Surface { mesh, directions }),
        &params(),
        &mut NoProgress,
    ) {
        Err(Error::Input(InputError::EmptyDomain(problem))) => problem,
        other => panic!("expected a domain error, got {:?}", other.map(|o| o.points.len())),
    };
    let curvature = SurfaceDirections::Curvature;
    assert_eq!(refuse(TriangleMesh::default(), curvature.clone()), DomainProblem::EmptyMesh);
    let mut nan = flat_mesh(5.0, 2, 0.0);
    nan.vertices[4][2] = f64::NAN;
    assert_eq!(refuse(nan, curvature.clone()), DomainProblem::NonFiniteMeshVertex(4));
    let mut degenerate = flat_mesh(5.0, 2, 0.0);
    degenerate.triangles[1] = [0, 1, 2];
    assert_eq!(refuse(degenerate, curvature.clone()), DomainProblem::DegenerateTriangle(1));
    assert_eq!(refuse(flat_mesh(5.0, 2, 0.0), SurfaceDirections::Constant([0.0; 3])), DomainProblem::SurfaceDirection);
    assert_eq!(
        refuse(flat_mesh(5.0, 2, 0.0), SurfaceDirections::PerVertex(vec![[1.0, 0.0, 0.0]; 3])),
        DomainProblem::SurfaceDirectionCount { given: 3, vertices: 9 }
    );
    let cloud = crate::tests::jittered_cloud(1);
    let surface = Domain::Surface { mesh: flat_mesh(5.0, 2, 0.0), directions: curvature };
    assert!(matches!(
        synthesize(&Input::new(cloud, surface), &params(), &mut NoProgress),
        Err(Error::Input(InputError::EmptyDomain(DomainProblem::SurfaceExemplar(3))))
    ));
}
