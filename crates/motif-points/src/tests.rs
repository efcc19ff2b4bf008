//! Property tests of the energy: gradients against finite differences, fast against reference
//! energy, monotone merging; and the fixtures the synthesis tests (`tests_synthesis`) share.

use motif_core::SeedStreams;
use motif_core::random::Rng;

use crate::PointSet;
use crate::linear::{self, Vector};
use crate::matching::{self, MatchSettings, SearchFields};
use crate::model::State;
use crate::params::{Domain, Evaluator, Field, Initialization, Input, Params, Window};
use crate::setup::prepare;
use crate::solver::evaluate_with;

/// A jittered square grid of `side × side` points with spacing 1, and one attribute "shade" that
/// alternates along x.
pub(crate) fn jittered_grid(side: usize, jitter: f64, seed: u64) -> PointSet {
    let mut stream = SeedStreams::new(seed).stream("grid", 0);
    let mut positions = Vec::new();
    let mut shade = Vec::new();
    for y in 0..side {
        for x in 0..side {
            positions.push(x as f64 + jitter * (stream.random::<f64>() - 0.5));
            positions.push(y as f64 + jitter * (stream.random::<f64>() - 0.5));
            shade.push((x % 2) as f64);
        }
    }
    PointSet { dimension: 2, positions, attribute_names: vec!["shade".into()], attributes: shade, elements: None }
}

/// A 6 × 6 × 6 lattice of spacing 1 with jitter 0.1 (3D).
pub(crate) fn jittered_cloud(seed: u64) -> PointSet {
    let mut stream = SeedStreams::new(seed).stream("cloud", 0);
    let mut positions = Vec::new();
    for z in 0..6 {
        for y in 0..6 {
            for x in 0..6 {
                for v in [x, y, z] {
                    positions.push(v as f64 + 0.1 * (stream.random::<f64>() - 0.5));
                }
            }
        }
    }
    PointSet::new(3, positions)
}

/// Rows of points: spacing 0.5 along x, 1.5 along y (an anisotropic structure).
pub(crate) fn rows(width: usize, height: usize) -> PointSet {
    let mut positions = Vec::new();
    for y in 0..height {
        for x in 0..width {
            positions.push(x as f64 * 0.5);
            positions.push(y as f64 * 1.5);
        }
    }
    PointSet::new(2, positions)
}

pub(crate) fn box_domain(w: f64, h: f64) -> Domain {
    Domain::Box { min: vec![0.0, 0.0], max: vec![w, h] }
}

pub(crate) fn positions_of(set: &PointSet) -> Vec<Vector<2>> {
    (0..set.len()).map(|i| [set.position(i)[0], set.position(i)[1]]).collect()
}

/// Nearest-neighbour distances of the points at least `margin` inside `[0, w] × [0, h]`.
pub(crate) fn interior_nearest(set: &PointSet, w: f64, h: f64, margin: f64) -> Vec<f64> {
    let points = positions_of(set);
    let mut out = Vec::new();
    for (i, p) in points.iter().enumerate() {
        if p[0] < margin || p[1] < margin || p[0] > w - margin || p[1] > h - margin {
            continue;
        }
        let nearest = points
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != i)
            .map(|(_, q)| linear::norm2(&linear::sub(p, q)).sqrt())
            .fold(f64::INFINITY, f64::min);
        out.push(nearest);
    }
    out
}

pub(crate) fn quick_params() -> Params {
    Params { neighbourhood: Some(1.5), shrink: Some(0.8), merge_iterations: 15, seed: 5, ..Params::default() }
}

/// A prepared problem with a random output and matches, for derivative checks.
struct Fixture<const D: usize> {
    setup: crate::setup::Setup<D>,
    matches: Vec<Vector<D>>,
    exemplar_self: f64,
}

fn fixture_2d(window: Window, attributes: bool) -> (Fixture<2>, Params) {
    let mut exemplar = jittered_grid(12, 0.3, 1);
    if !attributes {
        exemplar.attribute_names.clear();
        exemplar.attributes.clear();
    }
    let params = Params {
        window,
        rotation: Field::Uniform(20.0),
        scale: Field::Uniform(1.1),
        // Random points: the gradient checks want a dense, irregular state.
        initialization: Initialization::Random,
        ..quick_params()
    };
    let input = Input { exemplar, domain: box_domain(6.0, 5.0), existing: None };
    let mut setup = prepare::<2>(&input, &params).unwrap();
    setup.initialize(&params, &SeedStreams::new(3));
    // Perturb features so that attribute gradients are not trivially symmetric.
    let mut stream = SeedStreams::new(9).stream("perturb", 0);
    for f in setup.state.features.iter_mut().skip(1).step_by(2) {
        *f += 0.3 * (stream.random::<f64>() - 0.5);
    }
    let (matches, exemplar_self) = match_once(&setup, &params);
    (Fixture { setup, matches, exemplar_self }, params)
}

fn match_once<const D: usize>(setup: &crate::setup::Setup<D>, params: &Params) -> (Vec<Vector<D>>, f64) {
    let problem = setup.problem(setup.delta, params);
    let fields = SearchFields::new(&problem);
    let settings = MatchSettings { starts: 5, iterations: 10, polish: 1 };
    let found = matching::match_all(&problem, &fields, &setup.state, &[], settings, &SeedStreams::new(4));
    (found.iter().map(|m| m.location).collect(), found.iter().map(|m| m.exemplar_self).sum())
}

fn energy_of<const D: usize>(fixture: &Fixture<D>, params: &Params, state: &State<D>) -> f64 {
    let problem = fixture.setup.problem(fixture.setup.delta, params);
    evaluate_with(&problem, Evaluator::Fast, state, &fixture.matches, fixture.exemplar_self, false).energy
}

fn check_gradients(window: Window) {
    let (fixture, params) = fixture_2d(window, true);
    let problem = fixture.setup.problem(fixture.setup.delta, &params);
    let state = &fixture.setup.state;
    let analytic = evaluate_with(&problem, Evaluator::Fast, state, &fixture.matches, fixture.exemplar_self, true);
    let quadratic = analytic.quadratic.as_ref().expect("requested");
    // The attribute form is T itself at these positions.
    let from_form = quadratic.energy(&state.features);
    assert!(
        (from_form - analytic.energy).abs() < 1e-9 * (1.0 + analytic.energy.abs()),
        "{from_form} vs {}",
        analytic.energy
    );
    let feature_gradient = quadratic.gradient(&state.features);
    let h = 1e-6;
    let mut checked = 0;
    for i in (0..state.positions.len()).step_by(7) {
        for a in 0..2 {
            let mut plus = state.clone();
            plus.positions[i][a] += h;
            let mut minus = state.clone();
            minus.positions[i][a] -= h;
            let numeric = (energy_of(&fixture, &params, &plus) - energy_of(&fixture, &params, &minus)) / (2.0 * h);
            let exact = analytic.positions[i][a];
            assert!((numeric - exact).abs() < 1e-4 * (1.0 + exact.abs()), "x[{i}][{a}]: {numeric} vs {exact}");
            checked += 1;
        }
        let channel = i * state.channels + 1;
        let mut plus = state.clone();
        plus.features[channel] += h;
        let mut minus = state.clone();
        minus.features[channel] -= h;
        let numeric = (energy_of(&fixture, &params, &plus) - energy_of(&fixture, &params, &minus)) / (2.0 * h);
        let exact = feature_gradient[channel];
        assert!((numeric - exact).abs() < 1e-4 * (1.0 + exact.abs()), "a[{i}]: {numeric} vs {exact}");
    }
    assert!(checked >= 8, "{checked}");
    // ∂S/∂m_k.
    let grid = crate::grid::StaticGrid::new(&state.positions, problem.kernel.gather);
    let mut masked_checked = 0;
    for k in (0..problem.quadrature.len()).step_by(11) {
        let window_points = problem.output_window(k, &grid);
        let m = fixture.matches[k];
        let mut gradient = [0.0; 2];
        problem.match_objective(k, &m, &window_points, state, Some(&mut gradient));
        for a in 0..2 {
            let mut plus = m;
            plus[a] += h;
            let mut minus = m;
            minus[a] -= h;
            let numeric = (problem.match_objective(k, &plus, &window_points, state, None)
                - problem.match_objective(k, &minus, &window_points, state, None))
                / (2.0 * h);
            assert!(
                (numeric - gradient[a]).abs() < 1e-4 * (1.0 + gradient[a].abs()),
                "m[{k}][{a}]: {numeric} vs {}",
                gradient[a]
            );
        }
        // The unmasked exemplar term (interior windows) in exemplar coordinates: value against the
        // plain all-pairs sum, gradient against differences.
        let (transform, scale) = (problem.quadrature.transform[k], problem.quadrature.scale[k]);
        let mut gradient = [0.0; 2];
        let unmasked = problem.exemplar_self_with(&transform, scale, &m, None, Some(&mut gradient));
        let plain = plain_exemplar_self(&problem, &transform, scale, &m, None);
        assert!((unmasked - plain).abs() < 1e-9 * (1.0 + plain.abs()), "{unmasked} vs {plain}");
        // Masked (windows reaching out of Ω): the listed pairs against the plain sum.
        let q = problem.quadrature.points[k];
        let masked = problem.exemplar_self_with(&transform, scale, &m, Some(&q), None);
        let plain_masked = plain_exemplar_self(&problem, &transform, scale, &m, Some(&q));
        assert!((masked - plain_masked).abs() < 1e-9 * (1.0 + plain_masked.abs()), "{masked} vs {plain_masked}");
        if !problem.interior[k] {
            masked_checked += usize::from(plain_masked < plain - 1e-9);
        }
        for a in 0..2 {
            let mut plus = m;
            plus[a] += h;
            let mut minus = m;
            minus[a] -= h;
            let numeric = (problem.exemplar_self_with(&transform, scale, &plus, None, None)
                - problem.exemplar_self_with(&transform, scale, &minus, None, None))
                / (2.0 * h);
            assert!(
                (numeric - gradient[a]).abs() < 1e-4 * (1.0 + gradient[a].abs()),
                "C: {numeric} vs {}",
                gradient[a]
            );
        }
    }
    assert!(masked_checked > 0, "some checked windows should lose exemplar pairs to the mask");
}

/// `C(m)` as the plain all-pairs sum over the exemplar points in reach, frame applied by matrix.
fn plain_exemplar_self<const D: usize>(
    problem: &crate::energy::Problem<'_, D>,
    transform: &crate::linear::Matrix<D>,
    scale: f64,
    m: &Vector<D>,
    mask: Option<&Vector<D>>,
) -> f64 {
    let kernel = &problem.kernel;
    let exemplar = problem.exemplar;
    let mut window = Vec::new();
    problem.exemplar_grid.for_each_within(m, kernel.gather / scale, |j, e, _| {
        let v = linear::mat_vec(transform, &linear::sub(e, m));
        if mask.is_none_or(|q| problem.quadrature.inside(&linear::add(q, &v))) {
            window.push((j, v));
        }
    });
    let mut total = 0.0;
    for &(i, vi) in &window {
        for &(j, vj) in &window {
            if let Some((value, _, _)) = kernel.eval(&vi, &vj) {
                total += crate::model::feature_dot(exemplar.feature(i), exemplar.feature(j)) * value;
            }
        }
    }
    total
}

#[test]
fn gradients_match_finite_differences_gaussian_window() {
    check_gradients(Window::Gaussian);
}

#[test]
fn gradients_match_finite_differences_box_window() {
    check_gradients(Window::Box);
}

fn fixture_3d() -> (Fixture<3>, Params) {
    let mut stream = SeedStreams::new(2).stream("cloud", 0);
    let mut positions = Vec::new();
    for z in 0..5 {
        for y in 0..5 {
            for x in 0..5 {
                for (a, v) in [x, y, z].into_iter().enumerate() {
                    positions.push(v as f64 + 0.25 * (stream.random::<f64>() - 0.5) + 0.1 * a as f64);
                }
            }
        }
    }
    let exemplar = PointSet::new(3, positions);
    let params = Params {
        neighbourhood: Some(1.2),
        rotation: Field::Uniform(35.0),
        initialization: Initialization::Random,
        ..Params::default()
    };
    let input = Input { exemplar, domain: Domain::Box { min: vec![0.0; 3], max: vec![3.0, 3.0, 2.5] }, existing: None };
    let mut setup = prepare::<3>(&input, &params).unwrap();
    setup.initialize(&params, &SeedStreams::new(3));
    let (matches, exemplar_self) = match_once(&setup, &params);
    let fixture = Fixture { setup, matches, exemplar_self };
    (fixture, params)
}

#[test]
fn gradients_match_finite_differences_in_3d() {
    let (fixture, params) = fixture_3d();
    let problem = fixture.setup.problem(fixture.setup.delta, &params);
    let state = &fixture.setup.state;
    let analytic = evaluate_with(&problem, Evaluator::Fast, state, &fixture.matches, fixture.exemplar_self, false);
    let h = 1e-6;
    for i in (0..state.positions.len()).step_by(5) {
        for a in 0..3 {
            let mut plus = state.clone();
            plus.positions[i][a] += h;
            let mut minus = state.clone();
            minus.positions[i][a] -= h;
            let numeric = (energy_of(&fixture, &params, &plus) - energy_of(&fixture, &params, &minus)) / (2.0 * h);
            let exact = analytic.positions[i][a];
            assert!((numeric - exact).abs() < 1e-4 * (1.0 + exact.abs()), "x[{i}][{a}]: {numeric} vs {exact}");
        }
    }
}

#[test]
fn fast_and_reference_agree_in_3d() {
    // The fast path's window tables, exemplar grid rows and masking against the plain
    // per-quadrature-point evaluation, with a rotation field and boundary windows.
    let (fixture, params) = fixture_3d();
    let problem = fixture.setup.problem(fixture.setup.delta, &params);
    let state = &fixture.setup.state;
    let fast = evaluate_with(&problem, Evaluator::Fast, state, &fixture.matches, fixture.exemplar_self, false);
    let slow = evaluate_with(&problem, Evaluator::Reference, state, &fixture.matches, 0.0, false);
    assert!((fast.energy - slow.energy).abs() < 1e-9 * (1.0 + slow.energy.abs()), "{} vs {}", fast.energy, slow.energy);
    let mut largest: f64 = 0.0;
    for (f, s) in fast.positions.iter().zip(&slow.positions) {
        for a in 0..3 {
            assert!((f[a] - s[a]).abs() < 1e-9 * (1.0 + s[a].abs()), "{f:?} vs {s:?}");
            largest = largest.max(s[a].abs());
        }
    }
    assert!(largest > 1e-3, "the gradients should not all vanish");
}

#[test]
fn fast_and_reference_energies_agree() {
    for window in [Window::Gaussian, Window::Box] {
        let (fixture, params) = fixture_2d(window, true);
        let problem = fixture.setup.problem(fixture.setup.delta, &params);
        let state = &fixture.setup.state;
        let fast = evaluate_with(&problem, Evaluator::Fast, state, &fixture.matches, fixture.exemplar_self, true);
        let slow = evaluate_with(&problem, Evaluator::Reference, state, &fixture.matches, 0.0, true);
        assert!(
            (fast.energy - slow.energy).abs() < 1e-8 * (1.0 + slow.energy.abs()),
            "{} vs {}",
            fast.energy,
            slow.energy
        );
        for (f, s) in fast.positions.iter().zip(&slow.positions) {
            for a in 0..2 {
                assert!((f[a] - s[a]).abs() < 1e-8 * (1.0 + s[a].abs()));
            }
        }
        let fast_features = fast.quadratic.as_ref().expect("requested").gradient(&state.features);
        let slow_features = slow.quadratic.as_ref().expect("requested").gradient(&state.features);
        assert!(fast_features.iter().any(|g| g.abs() > 1e-6), "attribute gradients should not all vanish");
        for (f, s) in fast_features.iter().zip(&slow_features) {
            assert!((f - s).abs() < 1e-8 * (1.0 + s.abs()));
        }
    }
}

#[test]
fn energy_decreases_across_merging_steps() {
    let (fixture, params) = fixture_2d(Window::Gaussian, false);
    let problem = fixture.setup.problem(fixture.setup.delta, &params);
    let mut state = fixture.setup.state.clone();
    let evaluate =
        |s: &State<2>, f: bool| evaluate_with(&problem, Evaluator::Fast, s, &fixture.matches, fixture.exemplar_self, f);
    let settings = crate::merging::MergeSettings {
        iterations: 30,
        attribute_iterations: 0,
        step: 0.03,
        tolerance: 1e-6,
        stagnation: 0.0,
        sigma: fixture.setup.sigma,
    };
    let allowed = |p: &Vector<2>| fixture.setup.allowed(p);
    let (energies, _) = crate::merging::merge_positions(&mut state, settings, false, &evaluate, &allowed);
    assert!(energies.len() > 10, "only {} accepted steps", energies.len());
    for pair in energies.windows(2) {
        assert!(pair[1] < pair[0], "{energies:?}");
    }
    assert!(energies[energies.len() - 1] < energies[0] - 1e-3 * energies[0].abs());
    // The recorded energy is the energy of the final state.
    let final_energy = evaluate(&state, false).energy;
    assert!((final_energy - energies[energies.len() - 1]).abs() < 1e-9 * final_energy.abs().max(1.0));
}

#[test]
fn quasi_newton_merging_ends_lower_than_gradient_descent_in_as_many_steps() {
    let (fixture, params) = fixture_2d(Window::Gaussian, false);
    let problem = fixture.setup.problem(fixture.setup.delta, &params);
    let evaluate =
        |s: &State<2>, f: bool| evaluate_with(&problem, Evaluator::Fast, s, &fixture.matches, fixture.exemplar_self, f);
    let allowed = |p: &Vector<2>| fixture.setup.allowed(p);
    for iterations in [5, 15] {
        let settings = crate::merging::MergeSettings {
            iterations,
            attribute_iterations: 0,
            step: 0.03,
            tolerance: 1e-6,
            stagnation: 0.0,
            sigma: fixture.setup.sigma,
        };
        let mut quasi_newton = fixture.setup.state.clone();
        let (energies, _) = crate::merging::merge_positions(&mut quasi_newton, settings, false, &evaluate, &allowed);
        let mut plain = fixture.setup.state.clone();
        let (plain_energies, _) = crate::merging::gradient_descent(&mut plain, settings, false, &evaluate, &allowed);
        let (last, plain_last) = (energies[energies.len() - 1], plain_energies[plain_energies.len() - 1]);
        assert!(last < plain_last, "{iterations} steps: {last} against {plain_last}");
    }
}

#[test]
fn movable_rows_give_the_full_energy_change_and_gradient() {
    // Merging with frozen points evaluates the movable rows alone plus a constant: after moving
    // the movable points, that sum must equal a full evaluation, and their gradients must too.
    let (fixture, params) = fixture_2d(Window::Gaussian, true);
    let problem = fixture.setup.problem(fixture.setup.delta, &params);
    let mut state = fixture.setup.state.clone();
    for (u, unit) in state.units.iter_mut().enumerate() {
        unit.frozen = u % 3 != 0;
    }
    let movable = state.movable();
    assert!(movable.iter().any(|m| *m) && movable.iter().any(|m| !m));
    let (matches, exemplar_self) = (&fixture.matches, fixture.exemplar_self);
    let full = problem.evaluate(&state, matches, exemplar_self, false).energy;
    let constant = full - problem.evaluate_active(&state, matches, &movable).energy;
    let mut stream = SeedStreams::new(11).stream("move", 0);
    for (p, position) in state.positions.iter_mut().enumerate() {
        if movable[p] {
            for c in position.iter_mut() {
                *c += 0.2 * fixture.setup.sigma * (stream.random::<f64>() - 0.5);
            }
        }
    }
    let moved_full = problem.evaluate(&state, matches, exemplar_self, false);
    let moved_active = problem.evaluate_active(&state, matches, &movable);
    assert!((moved_full.energy - full).abs() > 1e-6 * full.abs(), "the move should change T");
    let restricted = moved_active.energy + constant;
    assert!(
        (restricted - moved_full.energy).abs() < 1e-9 * moved_full.energy.abs().max(1.0),
        "{restricted} vs {}",
        moved_full.energy
    );
    for (p, (a, f)) in moved_active.positions.iter().zip(&moved_full.positions).enumerate() {
        for c in 0..2 {
            if movable[p] {
                assert!((a[c] - f[c]).abs() < 1e-9 * (1.0 + f[c].abs()), "point {p}: {a:?} vs {f:?}");
            } else {
                assert_eq!(a[c], 0.0);
            }
        }
    }
}
