//! Property tests of whole syntheses: structure reproduction, sampling control, rigid elements,
//! guidance fields, determinism and input errors.

use motif_core::random::Rng;
use motif_core::{NoProgress, SeedStreams};

use crate::error::Error;
use crate::linear::{self, Vector};
use crate::params::{BrushStroke, Domain, Field, Initialization, Input, Params};
use crate::tests::{box_domain, interior_nearest, jittered_grid, positions_of, quick_params, rows};
use crate::{InputError, LimitError};
use crate::{PointSet, synthesize};

/// Fraction of interior nearest-neighbour distances within 20 % of the grid spacing 1.
fn grid_likeness(output: &PointSet, w: f64, h: f64) -> (f64, usize) {
    let nearest = interior_nearest(output, w, h, 1.0);
    let near = nearest.iter().filter(|&&d| (d - 1.0).abs() < 0.2).count();
    (near as f64 / nearest.len().max(1) as f64, nearest.len())
}

#[test]
fn jittered_grid_gives_grid_like_output_from_random_and_patch_starts() {
    let exemplar = jittered_grid(14, 0.1, 7);
    for initialization in [Initialization::Random, Initialization::Patches] {
        let params = Params { initialization, attributes: Some(vec![]), ..quick_params() };
        let output = synthesize(
            &Input { exemplar: exemplar.clone(), domain: box_domain(9.0, 9.0), existing: None },
            &params,
            &mut NoProgress,
        )
        .unwrap();
        let (fraction, count) = grid_likeness(&output.points, 9.0, 9.0);
        assert!(count > 20, "{initialization:?}: only {count} interior points");
        assert!(fraction > 0.8, "{initialization:?}: only {fraction} of nearest distances near the spacing");
        // One point per unit area: 81 in the 9 × 9 box.
        let n = output.points.len() as f64;
        let right = output.report.expected_points;
        assert!((right - 81.0).abs() < 81.0 * 0.02, "{right}");
        assert!((n - right).abs() <= 0.1 * right, "{initialization:?}: {n} points for {right}");
        let energies = &output.report.energy;
        assert!(energies.last().unwrap().after_merging < energies[0].after_matching);
    }
    // A uniformly random set of the same size is far less grid-like (the test can fail).
    let mut stream = SeedStreams::new(1).stream("uniform", 0);
    let random = PointSet::new(2, (0..200).map(|_| stream.random::<f64>() * 9.0).collect());
    assert!(grid_likeness(&random, 9.0, 9.0).0 < 0.5);
}

#[test]
fn sampling_control_reaches_the_right_count_from_half_and_double() {
    let exemplar = jittered_grid(14, 0.1, 8);
    let domain = box_domain(10.0, 10.0);
    // The exemplar has one point per unit area.
    let expected = 100.0;
    for factor in [0.5, 2.0] {
        // Start from `factor` times the right number of random points, given as existing points
        // inside the domain (none is fixed: they are all within keep_margin = 0 of it).
        let mut stream = SeedStreams::new(11).stream("start", factor as u64);
        let count = (expected * factor) as usize;
        let mut positions = Vec::new();
        for _ in 0..count {
            positions.push(stream.random::<f64>() * 10.0);
            positions.push(stream.random::<f64>() * 10.0);
        }
        let existing = PointSet::new(2, positions);
        let params = Params { keep_margin: Some(0.0), attributes: Some(vec![]), sampling_rounds: 3, ..quick_params() };
        let output = synthesize(
            &Input { exemplar: exemplar.clone(), domain: domain.clone(), existing: Some(existing) },
            &params,
            &mut NoProgress,
        )
        .unwrap();
        let n = output.points.len() as f64;
        // The right number: the exemplar's density (one point per unit cell) over the domain's
        // volume as the solver integrates it (each quadrature point stands for h² with h = 2σ; the
        // band of existing points that may move lies on the grid too).
        let right = output.report.expected_points;
        assert!(right > 0.95 * expected && right < 1.3 * expected, "{right}");
        assert!((n - right).abs() <= 0.1 * right, "start {count}: ended with {n}, expected {right}");
        let report = &output.report;
        if factor < 1.0 {
            assert!(report.initial_points + report.added > count, "{report:?}");
        } else {
            assert!(report.removed > 0, "{report:?}");
        }
    }
}

/// Elements: bars of three points on a jittered grid.
fn bar_exemplar() -> PointSet {
    let mut stream = SeedStreams::new(4).stream("bars", 0);
    let mut positions = Vec::new();
    let mut elements = Vec::new();
    let mut id = 0;
    for y in 0..7 {
        for x in 0..7 {
            let cx = x as f64 * 2.0 + 0.2 * (stream.random::<f64>() - 0.5);
            let cy = y as f64 * 2.0 + 0.2 * (stream.random::<f64>() - 0.5);
            for t in [-0.5, 0.0, 0.5] {
                positions.push(cx + t);
                positions.push(cy + 0.3 * t * t);
                elements.push(id);
            }
            id += 1;
        }
    }
    PointSet { dimension: 2, positions, attribute_names: vec![], attributes: vec![], elements: Some(elements) }
}

#[test]
fn discrete_elements_come_out_as_rigid_copies() {
    let exemplar = bar_exemplar();
    let params = Params { neighbourhood: Some(2.5), ..quick_params() };
    let output = synthesize(
        &Input { exemplar: exemplar.clone(), domain: box_domain(10.0, 8.0), existing: None },
        &params,
        &mut NoProgress,
    )
    .unwrap();
    let ids = output.points.elements.as_ref().expect("element ids");
    let mut groups: std::collections::BTreeMap<i64, Vec<usize>> = std::collections::BTreeMap::new();
    for (i, &id) in ids.iter().enumerate() {
        groups.entry(id).or_default().push(i);
    }
    assert!(groups.len() >= 8, "only {} elements", groups.len());
    // Exemplar element shape: pairwise distances of its three points.
    let shape = |set: &PointSet, members: &[usize]| -> Vec<f64> {
        let mut d = Vec::new();
        for a in 0..members.len() {
            for b in a + 1..members.len() {
                let (p, q) = (set.position(members[a]), set.position(members[b]));
                d.push(((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt());
            }
        }
        d
    };
    let reference = shape(&exemplar, &[0, 1, 2]);
    for members in groups.values() {
        assert_eq!(members.len(), 3);
        let distances = shape(&output.points, members);
        for (d, r) in distances.iter().zip(&reference) {
            assert!((d - r).abs() < 1e-6, "{distances:?} vs {reference:?}");
        }
    }
}

/// Mean |cos| of the angle between nearest-neighbour vectors and the x axis.
fn alignment_with_x(set: &PointSet, w: f64, h: f64) -> f64 {
    let points = positions_of(set);
    let mut total = 0.0;
    let mut count = 0;
    for (i, p) in points.iter().enumerate() {
        if p[0] < 1.5 || p[1] < 1.5 || p[0] > w - 1.5 || p[1] > h - 1.5 {
            continue;
        }
        let (mut best, mut vector) = (f64::INFINITY, [0.0; 2]);
        for (j, q) in points.iter().enumerate() {
            let d = linear::sub(q, p);
            let n = linear::norm2(&d);
            if j != i && n < best {
                best = n;
                vector = d;
            }
        }
        total += (vector[0] / best.sqrt()).abs();
        count += 1;
    }
    total / count as f64
}

#[test]
fn a_rotation_field_of_90_degrees_rotates_the_structure() {
    let exemplar = rows(24, 8);
    let base = Params { neighbourhood: Some(1.5), attributes: Some(vec![]), ..quick_params() };
    let plain = synthesize(
        &Input { exemplar: exemplar.clone(), domain: box_domain(8.0, 8.0), existing: None },
        &base,
        &mut NoProgress,
    )
    .unwrap();
    let rotated_params = Params { rotation: Field::Uniform(90.0), ..base };
    let rotated =
        synthesize(&Input { exemplar, domain: box_domain(8.0, 8.0), existing: None }, &rotated_params, &mut NoProgress)
            .unwrap();
    let plain_alignment = alignment_with_x(&plain.points, 8.0, 8.0);
    let rotated_alignment = alignment_with_x(&rotated.points, 8.0, 8.0);
    assert!(plain_alignment > 0.8, "unrotated rows: nearest neighbours along x? {plain_alignment}");
    assert!(rotated_alignment < 0.3, "rotated rows: nearest neighbours along y? {rotated_alignment}");
}

#[test]
fn same_seed_gives_identical_output_for_any_thread_count() {
    let exemplar = jittered_grid(10, 0.2, 3);
    let params = Params { local_global_iterations: 1, shrink: Some(0.7), ..quick_params() };
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            synthesize(
                &Input { exemplar: exemplar.clone(), domain: box_domain(5.0, 5.0), existing: None },
                &params,
                &mut NoProgress,
            )
            .unwrap()
        })
    };
    let one = run(1);
    let two = run(2);
    assert_eq!(one.points, two.points);
    assert_eq!(one.report.final_energy.to_bits(), two.report.final_energy.to_bits());
    let other = synthesize(
        &Input { exemplar: exemplar.clone(), domain: box_domain(5.0, 5.0), existing: None },
        &Params { seed: 99, ..params.clone() },
        &mut NoProgress,
    )
    .unwrap();
    assert_ne!(one.points, other.points);
}

#[test]
fn discrete_attributes_are_snapped_to_exemplar_values() {
    let exemplar = jittered_grid(10, 0.2, 3);
    let params = Params { discrete_attributes: vec!["shade".into()], ..quick_params() };
    let output =
        synthesize(&Input { exemplar, domain: box_domain(5.0, 5.0), existing: None }, &params, &mut NoProgress)
            .unwrap();
    assert_eq!(output.points.attribute_names, vec!["shade".to_string()]);
    for &v in &output.points.attributes {
        assert!(v.abs() < 1e-9 || (v - 1.0).abs() < 1e-9, "{v}");
    }
}

#[test]
fn progressive_synthesis_keeps_far_points_fixed() {
    let exemplar = jittered_grid(12, 0.1, 5);
    let first = synthesize(
        &Input { exemplar: exemplar.clone(), domain: box_domain(6.0, 6.0), existing: None },
        &Params { attributes: Some(vec![]), ..quick_params() },
        &mut NoProgress,
    )
    .unwrap();
    let stroke =
        BrushStroke { points: vec![vec![6.0, 3.0], vec![12.0, 3.0]], width: 3.0, scale_start: 1.0, scale_end: 1.0 };
    let params = Params { attributes: Some(vec![]), keep_margin: Some(2.0), ..quick_params() };
    let second = synthesize(
        &Input { exemplar, domain: Domain::Stroke(stroke), existing: Some(first.points.clone()) },
        &params,
        &mut NoProgress,
    )
    .unwrap();
    let before = positions_of(&first.points);
    let after = positions_of(&second.points);
    let far: Vec<&Vector<2>> =
        before.iter().filter(|p| p[0] < 6.0 - 1.5 - 2.0 - 0.01 || (p[1] - 3.0).abs() > 1.5 + 2.0 + 0.01).collect();
    assert!(!far.is_empty());
    for p in far {
        assert!(after.iter().any(|q| q == p), "fixed point {p:?} moved");
    }
    assert!(second.report.fixed_points > 0);
    let new_points = after.iter().filter(|p| p[0] > 7.0).count();
    assert!(new_points > 10, "only {new_points} points along the new stroke");
    // New points lie in the stroke or the band around it where existing points may move.
    for p in after.iter().filter(|p| p[0] > 6.0 + 2.0) {
        assert!((p[1] - 3.0).abs() <= 1.5 + 2.0 + 1e-9 && p[0] <= 12.0 + 1.5 + 2.0 + 1e-9, "{p:?} outside");
    }
    // Ω is resolved by the quadrature grid: a point is inside when its nearest node is.
    let h = 2.0 * second.report.sigma;
    let inside = after.iter().filter(|p| p[0] > 8.0 && (p[1] - 3.0).abs() <= 1.5 + 0.5 * h).count();
    let outside = after.iter().filter(|p| p[0] > 8.0 && (p[1] - 3.0).abs() > 1.5 + 0.5 * h).count();
    assert!(inside > 5 * outside, "{inside} points inside the stroke, {outside} outside");
}

#[test]
fn strokes_and_polygons_confine_the_output() {
    let exemplar = rows(24, 8);
    let stroke =
        BrushStroke { points: vec![vec![0.0, 0.0], vec![0.0, 8.0]], width: 3.0, scale_start: 1.0, scale_end: 1.5 };
    let params = Params { neighbourhood: Some(1.5), ..quick_params() };
    let output = synthesize(
        &Input { exemplar: exemplar.clone(), domain: Domain::Stroke(stroke), existing: None },
        &params,
        &mut NoProgress,
    )
    .unwrap();
    assert!(output.points.len() > 10);
    for p in positions_of(&output.points) {
        assert!(p[0].abs() <= 1.5 + 1e-9 && p[1] >= -1.5 && p[1] <= 9.5, "{p:?}");
    }
    // The exemplar's rows run along x; along a vertical stroke they must run along y.
    let points = positions_of(&output.points);
    let mut along = 0;
    let mut total = 0;
    for (i, p) in points.iter().enumerate() {
        let nearest = points
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != i)
            .min_by(|a, b| linear::norm2(&linear::sub(a.1, p)).total_cmp(&linear::norm2(&linear::sub(b.1, p))))
            .map(|(_, q)| linear::sub(q, p))
            .unwrap();
        total += 1;
        if nearest[1].abs() > nearest[0].abs() {
            along += 1;
        }
    }
    assert!(along as f64 > 0.7 * total as f64, "{along} of {total} nearest neighbours along the stroke");
    let polygon = motif_core::Polygon::new(vec![
        motif_core::Point::new(0.0, 0.0),
        motif_core::Point::new(8.0, 0.0),
        motif_core::Point::new(0.0, 8.0),
    ])
    .unwrap();
    let params = Params { neighbourhood: Some(1.5), ..quick_params() };
    let output =
        synthesize(&Input { exemplar, domain: Domain::Polygon(polygon), existing: None }, &params, &mut NoProgress)
            .unwrap();
    assert!(output.points.len() > 20);
    for p in positions_of(&output.points) {
        assert!(p[0] >= 0.0 && p[1] >= 0.0 && p[0] + p[1] <= 8.0 + 1e-9, "{p:?}");
    }
}

#[test]
fn three_dimensional_boxes_are_filled_at_the_exemplar_density() {
    let exemplar = crate::tests::jittered_cloud(2);
    let params = Params { neighbourhood: Some(1.2), shrink: Some(0.7), merge_iterations: 10, ..Params::default() };
    let output = synthesize(
        &Input { exemplar, domain: Domain::Box { min: vec![0.0; 3], max: vec![4.0, 4.0, 4.0] }, existing: None },
        &params,
        &mut NoProgress,
    )
    .unwrap();
    // One point per unit volume: between the box's volume (4³) and the volume Ω has for the solver
    // (quadrature points × h³, which counts the boundary layer where lattice points also fit).
    let n = output.points.len() as f64;
    let h = 2.0 * output.report.sigma;
    let omega = output.report.quadrature_points as f64 * h * h * h;
    assert!(n > 0.9 * 64.0 && n < 1.1 * omega, "{n} points for a volume between 64 and {omega}");
    // Spacing kept: the mean nearest-neighbour distance of the interior matches the exemplar's.
    let fidelity = &output.report.fidelity;
    let (a, b) = (fidelity.exemplar_statistics.mean_nearest, fidelity.output_statistics.mean_nearest);
    assert!(fidelity.output_statistics.nearest_counted > 0 && (a - b).abs() < 0.15 * a, "{a} vs {b}");
}

#[test]
fn extreme_exemplars_and_stroke_scales_are_refused_by_name() {
    let run = |exemplar: PointSet, domain: Domain| {
        synthesize(&Input { exemplar, domain, existing: None }, &quick_params(), &mut NoProgress)
    };
    // One point whose coordinates overflow the set's area: it looped forever in mean_spacing.
    let mut far = jittered_grid(5, 0.1, 1);
    far.positions.extend([1e200, -1e200]);
    far.attributes.extend(vec![0.5; far.attribute_names.len()]);
    let error = run(far, box_domain(5.0, 5.0)).unwrap_err();
    assert!(error.to_string().contains("1e200") && error.to_string().contains("±1e100"), "{error}");
    // Each point doubled: they do not all coincide, and the message says what they do.
    let mut doubled = PointSet::new(2, Vec::new());
    for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] {
        doubled.positions.extend(p.iter().chain(&p));
    }
    let error = run(doubled, box_domain(5.0, 5.0)).unwrap_err();
    assert!(
        matches!(error, Error::Input(InputError::DuplicatedPoints { .. })) && error.to_string().contains("duplicate"),
        "{error}"
    );
    let same = PointSet::new(2, vec![2.0; 8]);
    assert!(matches!(run(same, box_domain(5.0, 5.0)).unwrap_err(), Error::Input(InputError::CoincidentPoints)));
    // A scale ratio of 1e300 along a stroke rounded the far end to scale 0.
    let stroke =
        BrushStroke { points: vec![vec![0.0, 0.0], vec![0.0, 8.0]], width: 3.0, scale_start: 1e300, scale_end: 1.0 };
    let error = run(jittered_grid(5, 0.1, 1), Domain::Stroke(stroke)).unwrap_err();
    assert!(error.to_string().contains("scale-along") && error.to_string().contains("1e300"), "{error}");
}

#[test]
fn bad_input_gives_clear_errors() {
    let domain = box_domain(5.0, 5.0);
    let run = |exemplar: PointSet, params: Params, domain: Domain| {
        synthesize(&Input { exemplar, domain, existing: None }, &params, &mut NoProgress)
    };
    let two = PointSet::new(2, vec![0.0, 0.0, 1.0, 1.0]);
    let error = run(two, quick_params(), domain.clone()).unwrap_err();
    assert!(error.to_string().contains("at least 3"), "{error}");
    let nan = PointSet::new(2, vec![0.0, 0.0, 1.0, f64::NAN, 2.0, 2.0]);
    let error = run(nan, quick_params(), domain.clone()).unwrap_err();
    assert!(error.to_string().contains("non-finite coordinate"), "{error}");
    let grid = jittered_grid(5, 0.1, 1);
    let error = run(grid.clone(), Params { neighbourhood: Some(0.0), ..quick_params() }, domain.clone()).unwrap_err();
    assert!(matches!(error, Error::Parameter(_)) && error.to_string().contains("neighbourhood"), "{error}");
    let error = run(grid.clone(), Params { neighbourhood: Some(-1.0), ..quick_params() }, domain.clone()).unwrap_err();
    assert!(error.to_string().contains("neighbourhood"), "{error}");
    let empty = box_domain(0.0, 5.0);
    let error = run(grid.clone(), quick_params(), empty).unwrap_err();
    assert!(matches!(error, Error::Input(InputError::EmptyDomain(_))), "{error}");
    let tiny = Domain::Box { min: vec![0.0, 0.0], max: vec![0.1, 0.1] };
    let error = run(grid.clone(), quick_params(), tiny).unwrap_err();
    assert!(error.to_string().contains("unusable domain"), "{error}");
    // A huge domain is refused before anything is allocated, and says so.
    let huge = Domain::Box { min: vec![0.0, 0.0], max: vec![1e6, 1e6] };
    let error = run(grid.clone(), quick_params(), huge).unwrap_err();
    assert!(
        matches!(
            error,
            Error::Limit(LimitError::TooManyQuadraturePoints { .. })
                | Error::Limit(LimitError::TooManyPoints { .. })
                | Error::Limit(LimitError::Memory(_))
        ) && (error.to_string().contains("too large") || error.to_string().contains("max-memory")),
        "{error}"
    );
    let wrong_dimension = Domain::Box { min: vec![0.0; 3], max: vec![1.0; 3] };
    assert!(run(grid.clone(), quick_params(), wrong_dimension).is_err());
    let error = run(grid.clone(), Params { attributes: Some(vec!["colour".into()]), ..quick_params() }, domain.clone())
        .unwrap_err();
    assert!(error.to_string().contains("colour"), "{error}");
    for (cutoff, balance) in [(1.0, 0.5), (4.5, 0.5), (2.0, -0.1), (2.0, 11.0)] {
        let params = Params { window_cutoff: cutoff, patch_balance: balance, ..quick_params() };
        let error = run(grid.clone(), params, domain.clone()).unwrap_err();
        let named = if cutoff == 2.0 { "patch-balance" } else { "window-cutoff" };
        assert!(error.to_string().contains(named), "{error}");
    }
}

/// The window's truncation is the engine's to set: the default is 2δ, and a narrower window is a
/// different (cheaper) energy, so it gives other points.
#[test]
fn the_window_cutoff_takes_effect() {
    let exemplar = jittered_grid(10, 0.1, 3);
    let run = |params: Params| {
        let input = Input { exemplar: exemplar.clone(), domain: box_domain(8.0, 8.0), existing: None };
        positions_of(&synthesize(&input, &params, &mut NoProgress).unwrap().points)
    };
    assert_eq!(Params::default().window_cutoff, 2.0);
    let default = run(quick_params());
    assert_eq!(run(Params { window_cutoff: 2.0, ..quick_params() }), default);
    assert_ne!(run(Params { window_cutoff: 1.5, ..quick_params() }), default);
}

#[test]
fn the_memory_limit_refuses_at_the_reported_estimate() {
    let run = |exemplar: PointSet, params: Params, domain: Domain| {
        synthesize(&Input { exemplar, domain, existing: None }, &params, &mut NoProgress)
    };
    let grid = jittered_grid(6, 0.1, 2);
    let domain = box_domain(9.0, 9.0);
    let output = run(grid.clone(), quick_params(), domain.clone()).unwrap();
    let estimate = output.report.estimated_memory_bytes;
    // At least the output points' coordinates and the quadrature points'.
    assert!(estimate >= 16 * (output.points.len() + output.report.quadrature_points) as u64, "{estimate}");
    let same = run(grid.clone(), quick_params().with_max_memory(estimate.max(1 << 20)), domain.clone()).unwrap();
    assert_eq!(same.points, output.points);
    if estimate > 1 << 20 {
        let error = run(grid, quick_params().with_max_memory(estimate - 1), domain).unwrap_err();
        assert!(matches!(error, Error::Limit(LimitError::Memory(_))), "{error}");
    } else {
        // A domain a thousand times larger passes a 1 MiB limit.
        let large = box_domain(300.0, 300.0);
        let error = run(grid, quick_params().with_max_memory(1 << 20), large).unwrap_err();
        assert!(
            matches!(error, Error::Limit(LimitError::Memory(_))) && error.to_string().contains("max-memory"),
            "{error}"
        );
    }
}
