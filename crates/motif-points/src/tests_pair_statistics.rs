//! Tests of the pair-statistics refinement: the kernels, the gradient against finite differences,
//! monotone descent that leaves fixed points alone, thinning, and thread-count independence.

use motif_core::SeedStreams;
use motif_core::random::Rng;

use super::*;

/// `n` uniform random points in `[0, side)²` (distances in spacings).
pub(super) fn random_points(n: usize, side: f64, seed: u64) -> Vec<Vector<2>> {
    let mut stream = SeedStreams::new(seed).stream("points", 0);
    (0..n).map(|_| [side * stream.random::<f64>(), side * stream.random::<f64>()]).collect()
}

/// A jittered grid of spacing about 1 over `[0, side)²`: an inhibited pattern, unlike a random set.
fn jittered_grid(side: usize, seed: u64) -> Vec<Vector<2>> {
    let mut stream = SeedStreams::new(seed).stream("grid", 0);
    let mut points = Vec::new();
    for y in 0..side {
        for x in 0..side {
            let jitter = [stream.random::<f64>() - 0.5, stream.random::<f64>() - 0.5];
            points.push([x as f64 + 0.5 + 0.3 * jitter[0], y as f64 + 0.5 + 0.3 * jitter[1]]);
        }
    }
    points
}

pub(super) fn box_depth(side: f64) -> impl Fn(&Vector<2>) -> f64 + Sync {
    move |p: &Vector<2>| fidelity::box_depth(p, &[0.0, 0.0], &[side, side], 2)
}

/// The refinement's view of `positions` in the box `[0, side]²`: `movable` points may go where
/// `allowed` says, nothing is settled.
pub(super) fn in_box<'a>(
    positions: &'a mut [Vector<2>],
    movable: &'a [bool],
    depth: &'a (dyn Fn(&Vector<2>) -> f64 + Sync),
    allowed: &'a (dyn Fn(&Vector<2>) -> bool + Sync),
    side: f64,
) -> Output<'a, 2> {
    fn unmoved(p: &Vector<2>) -> Vector<2> {
        *p
    }
    Output { positions, movable, depth, allowed, settle: &unmoved, volume: side * side }
}

/// Refines every point of `points` in the box `[0, side)²` with no other constraint: `sweeps`
/// relocations per point, then `iterations` gradient steps.
fn refine_all(
    target: &Target,
    points: &mut [Vector<2>],
    side: f64,
    (sweeps, iterations): (usize, usize),
) -> StatisticsRefinement {
    let movable = vec![true; points.len()];
    let depth = box_depth(side);
    let mut output = in_box(points, &movable, &depth, &|_: &Vector<2>| true, side);
    let mut outcome = StatisticsRefinement::default();
    refine(target, &mut output, iterations, &mut outcome);
    let mut stream = SeedStreams::new(1).stream("relocation", 0);
    relocation::relocate(
        target,
        &mut output,
        relocation::Settings { sweeps, proposals: 0, quantum: None },
        &mut stream,
        &mut outcome,
    );
    outcome
}

fn grid_target(side: usize) -> Target {
    let s = side as f64;
    Target::new(&jittered_grid(side, 1), &box_depth(s), s * s, RAMP)
}

#[test]
fn ring_kernels_share_each_distance() {
    for step in 1..390 {
        let d = 0.05 + step as f64 * 0.01;
        let total: f64 = touched(d, RAMP).map(|b| kernel(b, d, RAMP).0).sum();
        let everywhere: f64 = (0..rings()).map(|b| kernel(b, d, RAMP).0).sum();
        assert!((total - 1.0).abs() < 1e-12, "d = {d}: kernels sum to {total}");
        assert!((everywhere - total).abs() < 1e-12, "d = {d}: a ring outside `touched` counts");
    }
}

#[test]
fn gradient_matches_finite_differences() {
    let target = grid_target(14);
    let side = 9.0;
    let points = random_points(70, side, 5);
    let depth = box_depth(side);
    let depths: Vec<f64> = points.iter().map(&depth).collect();
    let movable = vec![true; points.len()];
    let evaluation = evaluate(&target, &points, &depths, 1.0, Some(&movable));
    let energy = |p: &[Vector<2>]| evaluate(&target, p, &depths, 1.0, None).energy;
    let h = 1e-6;
    let mut checked = 0;
    for i in (0..points.len()).step_by(7) {
        for a in 0..2 {
            let (mut plus, mut minus) = (points.clone(), points.clone());
            plus[i][a] += h;
            minus[i][a] -= h;
            let numeric = (energy(&plus) - energy(&minus)) / (2.0 * h);
            let analytic = evaluation.gradient[i][a];
            assert!(
                (numeric - analytic).abs() <= 1e-4 * (1.0 + analytic.abs()),
                "point {i} axis {a}: analytic {analytic}, finite differences {numeric}"
            );
            checked += 1;
        }
    }
    assert!(checked >= 20);
}

#[test]
fn refinement_lowers_the_energy_and_leaves_fixed_points_alone() {
    let target = grid_target(14);
    let side = 10.0;
    let mut points = random_points(100, side, 7);
    let before = points.clone();
    let movable: Vec<bool> = (0..points.len()).map(|i| i % 3 != 0).collect();
    let depth = box_depth(side);
    let inside = |p: &Vector<2>| p.iter().all(|&x| (0.0..=side).contains(&x));
    let mut output = in_box(&mut points, &movable, &depth, &inside, side);
    let mut outcome = StatisticsRefinement::default();
    refine(&target, &mut output, 30, &mut outcome);
    assert!(outcome.steps_kept > 5, "{outcome:?}");
    assert!(outcome.energy_after < 0.7 * outcome.energy_before, "{outcome:?}");
    for i in 0..points.len() {
        assert!(inside(&points[i]), "point {i} left the domain: {:?}", points[i]);
        if !movable[i] {
            assert_eq!(points[i], before[i], "fixed point {i} moved");
        }
    }
    assert!(points.iter().zip(&before).zip(&movable).any(|((p, q), &m)| m && p != q));
}

#[test]
fn thinning_removes_movable_points_only_and_lowers_the_energy() {
    let side = 10usize;
    let target = grid_target(14);
    // The exemplar's own structure plus 12 random points too many.
    let mut points = jittered_grid(side, 2);
    let grid_points = points.len();
    points.extend(random_points(12, side as f64, 3));
    let movable: Vec<bool> = (0..points.len()).map(|i| i >= grid_points || i % 2 == 0).collect();
    let depth = box_depth(side as f64);
    let volume = (side * side) as f64;
    let removed = thin(&target, &points, &movable, &depth, volume, 0, 12);
    assert!(!removed.is_empty() && removed.len() <= 12, "{} removed", removed.len());
    assert!(removed.windows(2).all(|w| w[0] < w[1]));
    assert!(removed.iter().all(|&i| movable[i]), "a fixed point was removed");
    let energy = |p: &[Vector<2>]| {
        let depths: Vec<f64> = p.iter().map(&depth).collect();
        evaluate(&target, p, &depths, p.len() as f64 / volume / target.density, None).energy
    };
    let kept: Vec<Vector<2>> =
        (0..points.len()).filter(|i| removed.binary_search(i).is_err()).map(|i| points[i]).collect();
    assert!(energy(&kept) < energy(&points));
    // Most of what goes is the random surplus, not the grid.
    let surplus_removed = removed.iter().filter(|&&i| i >= grid_points).count();
    assert!(2 * surplus_removed > removed.len(), "{surplus_removed} of {} removed were random", removed.len());
}

#[test]
fn the_same_points_whatever_the_thread_count() {
    let target = grid_target(14);
    let side = 10.0;
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let mut points = random_points(120, side, 11);
            refine_all(&target, &mut points, side, (5, 10));
            points
        })
    };
    assert_eq!(run(1), run(2));
}

#[test]
fn thinning_removes_what_is_required_even_when_the_energy_rises() {
    // The exemplar's own structure: no removal improves it, yet 5 must go.
    let side = 10usize;
    let target = grid_target(side);
    let points = jittered_grid(side, 1);
    let movable = vec![true; points.len()];
    let depth = box_depth(side as f64);
    let volume = (side * side) as f64;
    let improving = thin(&target, &points, &movable, &depth, volume, 0, 5);
    let required = thin(&target, &points, &movable, &depth, volume, 5, 5);
    assert!(improving.len() < 5, "{} removed although none was required", improving.len());
    assert_eq!(required.len(), 5);
}

#[test]
fn an_exemplar_without_counted_neighbours_still_refines() {
    // Three points, each nearer the window's border than its nearest neighbour.
    let exemplar = [[0.2, 0.2], [1.8, 0.2], [1.0, 1.8]];
    let target = Target::new(&exemplar, &box_depth(2.0), 4.0, RAMP);
    assert!(target.nearest.is_empty());
    let side = 6.0;
    let mut points = random_points(20, side, 3);
    let movable = vec![true; points.len()];
    let depth = box_depth(side);
    let removed = thin(&target, &points, &movable, &depth, side * side, 5, 5);
    assert!(removed.len() <= 5);
    refine_all(&target, &mut points, side, (5, 5));
    assert!(points.iter().all(|p| p.iter().all(|x| x.is_finite())));
}
