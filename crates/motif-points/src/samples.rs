//! Generated exemplars for the demo, the benchmarks and the tests: the paper's kinds of input
//! (a 2D grid-like arrangement, sand ripples, a 3D organic lattice, rigid leaves) drawn from a seed,
//! and two surface domains of known area (a torus and a sphere).

use motif_core::SeedStreams;
use motif_core::TriangleMesh;
use motif_core::math;
use motif_core::random::Rng;

use crate::PointSet;

/// A jittered hexagonal arrangement with a `shade` attribute that follows rows: the "grid"
/// exemplar of Fig. 7.
pub fn hex_exemplar(columns: usize, rows: usize, jitter: f64, seed: u64) -> PointSet {
    let mut stream = SeedStreams::new(seed).stream("hex exemplar", 0);
    let mut positions = Vec::new();
    let mut attributes = Vec::new();
    for row in 0..rows {
        for column in 0..columns {
            let x = column as f64 + if row % 2 == 1 { 0.5 } else { 0.0 };
            let y = row as f64 * 0.866;
            positions.push(x + jitter * (stream.random::<f64>() - 0.5));
            positions.push(y + jitter * (stream.random::<f64>() - 0.5));
            attributes.push(if row % 3 == 0 { 1.0 } else { 0.0 });
        }
    }
    PointSet { dimension: 2, positions, attribute_names: vec!["shade".into()], attributes, elements: None }
}

/// Wavy "sand ripple" points: rows of points whose height follows a sine, with a height attribute.
pub fn ripple_exemplar(count: usize, seed: u64) -> PointSet {
    let side = (count as f64).sqrt().ceil() as usize;
    let mut stream = SeedStreams::new(seed).stream("ripple exemplar", 0);
    let mut positions = Vec::new();
    let mut attributes = Vec::new();
    for i in 0..count {
        let (row, column) = (i / side, i % side);
        let x = column as f64 + 0.15 * (stream.random::<f64>() - 0.5);
        let y =
            row as f64 + 0.35 * math::sin(2.0 * std::f64::consts::PI * x / 6.0) + 0.1 * (stream.random::<f64>() - 0.5);
        positions.push(x);
        positions.push(y);
        attributes.push(math::sin(2.0 * std::f64::consts::PI * (x + y) / 5.0));
    }
    PointSet { dimension: 2, positions, attribute_names: vec!["height".into()], attributes, elements: None }
}

/// A 3D lattice-like organic structure: points on jittered cubic cells with a `radius` attribute.
pub fn lattice_exemplar(count: usize, seed: u64) -> PointSet {
    let side = math::cbrt(count as f64).ceil() as usize;
    let mut stream = SeedStreams::new(seed).stream("lattice exemplar", 0);
    let mut positions = Vec::new();
    let mut attributes = Vec::new();
    for i in 0..count {
        let (x, y, z) = (i % side, (i / side) % side, i / (side * side));
        let shift = if (x + y + z) % 2 == 0 { 0.15 } else { -0.15 };
        positions.push(x as f64 + shift + 0.1 * (stream.random::<f64>() - 0.5));
        positions.push(y as f64 + 0.1 * (stream.random::<f64>() - 0.5));
        positions.push(z as f64 - shift + 0.1 * (stream.random::<f64>() - 0.5));
        attributes.push(if z % 2 == 0 { 1.0 } else { 0.5 });
    }
    PointSet { dimension: 3, positions, attribute_names: vec!["radius".into()], attributes, elements: None }
}

/// Small rigid "leaves" (three points each) on a jittered grid, with a free-point background.
pub fn leaf_exemplar(seed: u64) -> PointSet {
    let mut stream = SeedStreams::new(seed).stream("leaf exemplar", 0);
    let mut positions = Vec::new();
    let mut elements = Vec::new();
    let mut id = 0;
    for row in 0..6 {
        for column in 0..6 {
            let cx = column as f64 * 3.0 + 0.3 * (stream.random::<f64>() - 0.5);
            let cy = row as f64 * 3.0 + 0.3 * (stream.random::<f64>() - 0.5);
            let angle = 0.5 * (stream.random::<f64>() - 0.5);
            for t in [-0.6, 0.0, 0.6] {
                positions.push(cx + t * math::cos(angle) - 0.25 * t * t * math::sin(angle));
                positions.push(cy + t * math::sin(angle) + 0.25 * t * t * math::cos(angle));
                elements.push(id);
            }
            id += 1;
            // A free background point between leaves.
            positions.push(cx + 1.5);
            positions.push(cy + 1.5);
            elements.push(-1);
        }
    }
    PointSet { dimension: 2, positions, attribute_names: vec![], attributes: vec![], elements: Some(elements) }
}

/// A torus about the z axis: tube radius `r` around a circle of radius `big_r`, `around` × `tube`
/// quads split in two (area `4π² big_r r` in the limit).
pub fn torus_mesh(big_r: f64, r: f64, around: usize, tube: usize) -> TriangleMesh {
    let mut vertices = Vec::with_capacity(around * tube);
    for i in 0..around {
        let (sin_u, cos_u) = math::sin_cos(std::f64::consts::TAU * i as f64 / around as f64);
        for j in 0..tube {
            let (sin_v, cos_v) = math::sin_cos(std::f64::consts::TAU * j as f64 / tube as f64);
            let radial = big_r + r * cos_v;
            vertices.push([radial * cos_u, radial * sin_u, r * sin_v]);
        }
    }
    let index = |i: usize, j: usize| ((i % around) * tube + j % tube) as u32;
    let mut triangles = Vec::with_capacity(2 * around * tube);
    for i in 0..around {
        for j in 0..tube {
            triangles.push([index(i, j), index(i + 1, j), index(i + 1, j + 1)]);
            triangles.push([index(i, j), index(i + 1, j + 1), index(i, j + 1)]);
        }
    }
    TriangleMesh { vertices, triangles }
}

/// A sphere of `radius` about the origin: `rings` bands of latitude, `segments` around, the poles
/// fanned (area `4π radius²` in the limit).
pub fn sphere_mesh(radius: f64, rings: usize, segments: usize) -> TriangleMesh {
    let mut vertices = vec![[0.0, 0.0, radius], [0.0, 0.0, -radius]];
    for ring in 1..rings {
        let (sin_t, cos_t) = math::sin_cos(std::f64::consts::PI * ring as f64 / rings as f64);
        for segment in 0..segments {
            let (sin_p, cos_p) = math::sin_cos(std::f64::consts::TAU * segment as f64 / segments as f64);
            vertices.push([radius * sin_t * cos_p, radius * sin_t * sin_p, radius * cos_t]);
        }
    }
    let at = |ring: usize, segment: usize| (2 + (ring - 1) * segments + segment % segments) as u32;
    let mut triangles = Vec::with_capacity(2 * rings * segments);
    for segment in 0..segments {
        triangles.push([0, at(1, segment), at(1, segment + 1)]);
        triangles.push([1, at(rings - 1, segment + 1), at(rings - 1, segment)]);
    }
    for ring in 1..rings - 1 {
        for segment in 0..segments {
            let (a, b) = (at(ring, segment), at(ring + 1, segment));
            let (c, d) = (at(ring + 1, segment + 1), at(ring, segment + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    TriangleMesh { vertices, triangles }
}
