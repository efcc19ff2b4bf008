//! Engine-level tests: solver optimality against brute force, closed curves, avoidance,
//! stitching, determinism and bad input.

use motif_core::math;
use motif_core::{NoProgress, Point, Polyline, RgbaImage};
use proptest::prelude::*;

use crate::InputError;
use crate::closed::solve_closed;
use crate::cost::{AlphaMode, CostModel};
use crate::dp::{RowSpec, Solver, brute_force, path_cost, solve};
use crate::exemplar::Exemplar;
use crate::piece::{PieceFrame, Position};
use crate::ribbon::{Ribbon, slice};
use crate::{Canvas, ClosedMode, Error, Input, Method, Params, PieceShape, synthesize};

/// A small problem built from raw parts, for solver tests.
pub(crate) struct Problem {
    pub(crate) exemplar: Exemplar,
    pub(crate) model: CostModel,
    pub(crate) frames: Vec<PieceFrame>,
    pub(crate) valid: Vec<Vec<Position>>,
}

impl Problem {
    pub(crate) fn new(image: &RgbaImage, curve: &Polyline, width: f64, delta: f64, mode: AlphaMode) -> Self {
        let ribbon = Ribbon::new(curve, width).unwrap();
        let samples = width.ceil() as usize;
        let frames: Vec<PieceFrame> = slice(&ribbon, delta).iter().map(|q| PieceFrame::new(q, 1.0, samples)).collect();
        let margin = frames.iter().map(PieceFrame::required_margin).max().unwrap();
        let exemplar = Exemplar::new(image, margin as usize, 8);
        let valid = frames.iter().map(|f| f.valid_positions(&exemplar, &[], 0.0)).collect();
        Self { exemplar, model: CostModel::new(mode, 1024.0), frames, valid }
    }

    pub(crate) fn rows(&self, terminal: bool) -> Vec<RowSpec<'_>> {
        let mut rows: Vec<RowSpec<'_>> =
            self.frames.iter().zip(&self.valid).map(|(frame, positions)| RowSpec { frame, positions }).collect();
        if terminal {
            rows.push(RowSpec { frame: &self.frames[0], positions: &self.valid[0] });
        }
        rows
    }

    pub(crate) fn combinations(&self) -> usize {
        self.valid.iter().map(Vec::len).product()
    }
}

pub(crate) fn random_exemplar(width: usize, height: usize, cells: &[u8]) -> RgbaImage {
    RgbaImage::from_fn(width, height, |x, y| {
        if y == 0 || y + 1 == height {
            return [0; 4];
        }
        let v = cells[(y * width + x) % cells.len()];
        let alpha = match v % 4 {
            0 | 1 => 0,
            2 => 255,
            _ => v,
        };
        [v.wrapping_mul(37), v.wrapping_mul(91), v, alpha]
    })
}

pub(crate) fn best_open(problem: &Problem, solver: Solver) -> (u64, Vec<usize>) {
    let rows = problem.rows(false);
    let table = solve(&problem.exemplar, &problem.model, &rows, solver, &mut |_| {});
    let last = (0..table.last_costs.len()).min_by_key(|&i| (table.last_costs[i], i)).unwrap();
    (table.last_costs[last], table.backtrack(last))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, max_global_rejects: 100_000, .. ProptestConfig::default() })]

    /// The exact solver's optimum equals the reference DP's and a brute-force enumeration.
    #[test]
    fn exact_solver_is_optimal(
        width in 10_usize..16,
        height in 4_usize..7,
        cells in proptest::collection::vec(any::<u8>(), 64),
        points in proptest::collection::vec((0.0_f64..12.0, 0.0_f64..12.0), 3),
        pieces in 1.6_f64..2.9,
        continuous in any::<bool>(),
        closed in any::<bool>(),
    ) {
        let image = random_exemplar(width, height, &cells);
        prop_assume!(!image.is_fully_transparent());
        let curve = Polyline::new(points.iter().map(|&(x, y)| Point::new(x, y)).collect(), closed);
        prop_assume!(curve.is_ok());
        let curve = curve.unwrap();
        prop_assume!(curve.length() > 4.0);
        let delta = curve.length() / pieces;
        let mode = if continuous { AlphaMode::Continuous } else { AlphaMode::Binary };
        let problem = Problem::new(&image, &curve, height as f64 + 1.0, delta, mode);
        prop_assume!(problem.valid.iter().all(|v| !v.is_empty()));
        prop_assume!(problem.combinations() <= 30_000);
        let (reference, reference_path) = best_open(&problem, Solver::Reference);
        let (exact, exact_path) = best_open(&problem, Solver::Exact);
        let (brute, _) = brute_force(&problem.exemplar, &problem.model, &problem.rows(false), false).unwrap();
        prop_assert_eq!(exact, reference);
        prop_assert_eq!(exact, brute);
        prop_assert_eq!(&exact_path, &reference_path);
        prop_assert_eq!(path_cost(&problem.exemplar, &problem.model, &problem.rows(false), &exact_path), exact);

        // Closed: the certified exact cycle equals the best brute-force cycle; approx is never better.
        let rows = problem.rows(true);
        if let Some((brute_cycle, _)) = brute_force(&problem.exemplar, &problem.model, &rows, true) {
            let exact_cycle = solve_closed(&problem.exemplar, &problem.model, &rows, Solver::Exact, true, 100_000, &mut |_| {});
            let approx = solve_closed(&problem.exemplar, &problem.model, &rows, Solver::Reference, false, 1, &mut |_| {});
            let plain_cycle = solve_closed(&problem.exemplar, &problem.model, &rows, Solver::Reference, true, 100_000, &mut |_| {});
            prop_assert_eq!(plain_cycle.cost, brute_cycle);
            prop_assert_eq!(exact_cycle.certified, Some(true));
            prop_assert_eq!(exact_cycle.cost, brute_cycle);
            prop_assert!(approx.cost >= exact_cycle.cost);
            let last = rows.len() - 1;
            prop_assert_eq!(exact_cycle.path[0], exact_cycle.path[last]);
            prop_assert_eq!(approx.path[0], approx.path[last]);
            prop_assert_eq!(path_cost(&problem.exemplar, &problem.model, &rows, &exact_cycle.path), exact_cycle.cost);
            // The bound: the cost itself when certified; with one start allowed, a bound no cycle
            // goes below, and the cycle found is a real cycle at or above the optimum.
            prop_assert_eq!(exact_cycle.lower_bound, Some(exact_cycle.cost));
            let hurried = solve_closed(&problem.exemplar, &problem.model, &rows, Solver::Exact, true, 1, &mut |_| {});
            let bound = hurried.lower_bound.unwrap();
            prop_assert!(bound <= brute_cycle && brute_cycle <= hurried.cost, "{bound} {brute_cycle} {}", hurried.cost);
            prop_assert_eq!(hurried.path[0], hurried.path[last]);
            prop_assert_eq!(path_cost(&problem.exemplar, &problem.model, &rows, &hurried.path), hurried.cost);
        }
    }
}

/// Small crops of real drawings (`data/real/curve/`): the exact solver's optimum equals the
/// reference DP's and brute force's on a curved ribbon.
#[test]
fn exact_solver_is_optimal_on_real_crops() {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/curve");
    for (file, crop) in [("beads.png", (30, 0, 22, 40)), ("teeth.png", (40, 0, 20, 52)), ("rope.png", (60, 0, 18, 76))]
    {
        let full = motif_io::read_image(&folder.join(file)).unwrap();
        let (x0, y0, w, h) = crop;
        // Downsampled by 2 so that brute force stays small; a transparent row above and below.
        let image = RgbaImage::from_fn(w / 2, h / 2 + 2, |x, y| {
            if y == 0 || y == h / 2 + 1 { [0; 4] } else { full.get(x0 + 2 * x, y0 + 2 * (y - 1)) }
        });
        // A gentle arc (radius 30) in three pieces of 4 px: every seam is tilted by about 8°.
        let arc: Vec<Point> = (0..=24)
            .map(|i| f64::from(i) / 24.0 * 0.4)
            .map(|a| Point::new(30.0 * math::sin(a), 40.0 - 30.0 * math::cos(a)))
            .collect();
        let curve = Polyline::new(arc, false).unwrap();
        let height = image.height() as f64;
        let problem = Problem::new(&image, &curve, height + 1.0, curve.length() / 2.9, AlphaMode::Continuous);
        assert!(problem.valid.iter().all(|v| !v.is_empty()), "{file}");
        assert!((1_000..=3_000_000).contains(&problem.combinations()), "{file}: {}", problem.combinations());
        assert_eq!(problem.frames.len(), 3);
        let (reference, _) = best_open(&problem, Solver::Reference);
        let (exact, path) = best_open(&problem, Solver::Exact);
        let (brute, _) = brute_force(&problem.exemplar, &problem.model, &problem.rows(false), false).unwrap();
        assert_eq!((exact, reference), (brute, brute), "{file}");
        assert_eq!(path_cost(&problem.exemplar, &problem.model, &problem.rows(false), &path), exact);
    }
}

/// A chain-like strip: rings every `period` pixels, with anti-aliased alpha, in rows
/// `[top, top + size)` of a `width × height` image.
pub(crate) fn chain_strip(width: usize, height: usize, period: usize, top: usize, size: usize) -> RgbaImage {
    let radius = size as f64 / 2.0 - 0.5;
    RgbaImage::from_fn(width, height, |x, y| {
        let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
        let cy = top as f64 + size as f64 / 2.0;
        let cx = ((px / period as f64).floor() + 0.5) * period as f64;
        let ring = (math::hypot(px - cx, (py - cy) * 1.3) - radius * 0.75).abs();
        let bar = if (py - cy).abs() < 1.5 { 1.0 } else { 0.0 };
        let coverage = (2.0 - ring).clamp(0.0, 1.0).max(bar * if (py - top as f64) > 0.0 { 1.0 } else { 0.0 });
        let alpha = (coverage * 255.0).round() as u8;
        if alpha == 0 { [0; 4] } else { [200, 160, (40 + (x % period) * 4) as u8, alpha] }
    })
}

pub(crate) fn line(x0: f64, y0: f64, x1: f64, y1: f64) -> Polyline {
    Polyline::new(vec![Point::new(x0, y0), Point::new(x1, y1)], false).unwrap()
}

pub(crate) fn circle(cx: f64, cy: f64, radius: f64, count: usize) -> Polyline {
    let points = (0..count).map(|i| {
        let a = i as f64 / count as f64 * std::f64::consts::TAU;
        Point::new(cx + radius * math::cos(a), cy + radius * math::sin(a))
    });
    Polyline::new(points.collect(), true).unwrap()
}

/// A synthesis on a pool of `threads` threads.
pub(crate) fn on_threads(threads: usize, input: &Input<'_>, params: &Params) -> crate::Output {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| synthesize(input, params, &mut NoProgress).unwrap())
}

pub(crate) fn params(width: f64, piece_length: f64) -> Params {
    Params { width, piece_length, ..Params::default() }
}

#[test]
fn a_periodic_exemplar_along_a_straight_line_has_no_seam_cost() {
    let image = chain_strip(96, 24, 12, 6, 12);
    let curve = line(10.0, 40.0, 200.0, 40.0);
    for mode in [AlphaMode::Binary, AlphaMode::Continuous] {
        let mut p = params(24.0, 20.0);
        p.alpha_mode = mode;
        let output = synthesize(
            &Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] },
            &p,
            &mut NoProgress,
        )
        .unwrap();
        assert_eq!(output.report.total_cost, 0.0, "{mode:?}");
        assert!(output.report.pieces >= 9);
        assert!(output.image.count_alpha_at_least(128) > 500, "the pattern is drawn");
        assert_eq!(output.report.distortion_max, 0.0);
    }
}

#[test]
fn exact_and_reference_solvers_agree_on_a_curved_ribbon() {
    let image = chain_strip(40, 16, 10, 4, 8);
    let points: Vec<Point> =
        (0..40).map(|i| Point::new(i as f64 * 3.0, 30.0 + 12.0 * math::sin(i as f64 * 0.15))).collect();
    let curve = Polyline::new(points, false).unwrap();
    let mut p = params(16.0, 14.0);
    let input = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
    let exact = synthesize(&input, &p, &mut NoProgress).unwrap();
    p.solver = Solver::Reference;
    let reference = synthesize(&input, &p, &mut NoProgress).unwrap();
    assert_eq!(exact.report.total_cost, reference.report.total_cost);
    assert_eq!(exact.report.dp_optimum, exact.report.total_cost_unstitched);
    let positions = |o: &crate::Output| o.pieces.iter().map(|p| p.position).collect::<Vec<_>>();
    assert_eq!(positions(&exact), positions(&reference));
    assert_eq!(exact.image, reference.image);
    assert!(exact.report.columns_skipped_fraction > 0.0);
    assert_eq!(reference.report.columns_skipped_fraction, 0.0);
}

#[test]
fn no_opaque_pixel_falls_in_the_avoidance_map() {
    let image = chain_strip(96, 24, 12, 6, 12);
    let curve = line(10.0, 40.0, 190.0, 40.0);
    // Forbid a block over the lower half of the ribbon between x = 80 and 120.
    let map = RgbaImage::from_fn(200, 80, |x, y| {
        if (80..120).contains(&x) && (40..60).contains(&y) { [255, 255, 255, 255] } else { [0, 0, 0, 0] }
    });
    let output = synthesize(
        &Input { exemplar: &image, curve: &curve, avoidance: Some(&map), more_exemplars: &[] },
        &params(36.0, 16.0),
        &mut NoProgress,
    )
    .unwrap();
    assert_eq!(output.image.width(), 200);
    assert!(output.report.forbidden_pixels >= 40 * 20);
    for y in 40..60 {
        for x in 80..120 {
            assert_eq!(output.image.get(x, y)[3], 0, "pattern at forbidden pixel ({x}, {y})");
        }
    }
    assert!(output.image.count_alpha_at_least(128) > 500);
    // Without the map the pattern does cross that block.
    let free = synthesize(
        &Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] },
        &{
            let mut p = params(36.0, 16.0);
            p.canvas = Canvas::Size { width: 200, height: 80 };
            p
        },
        &mut NoProgress,
    )
    .unwrap();
    let crossing = (40..60).flat_map(|y| (80..120).map(move |x| (x, y))).filter(|&(x, y)| free.image.get(x, y)[3] > 0);
    assert!(crossing.count() > 0);
}

#[test]
fn foldovers_of_a_tight_curve_stay_empty() {
    let image = chain_strip(48, 20, 12, 6, 8);
    // A hairpin: radius 7 with a ribbon 20 wide folds over on the inside.
    let mut points = vec![Point::new(10.0, 30.0), Point::new(60.0, 30.0)];
    for i in 1..24 {
        let a = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * i as f64 / 24.0;
        points.push(Point::new(60.0 + 7.0 * math::cos(a), 37.0 + 7.0 * math::sin(a)));
    }
    points.extend([Point::new(60.0, 44.0), Point::new(10.0, 44.0)]);
    let curve = Polyline::new(points, false).unwrap();
    let output = synthesize(
        &Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] },
        &params(20.0, 8.0),
        &mut NoProgress,
    )
    .unwrap();
    assert!(output.report.foldover_pixels > 100, "{}", output.report.foldover_pixels);
    let mask = &output.forbidden;
    for y in 0..mask.height {
        for x in 0..mask.width {
            if mask.is_forbidden(x, y) {
                assert_eq!(output.image.get(x, y)[3], 0, "pattern in a fold-over at ({x}, {y})");
            }
        }
    }
}

#[test]
fn closed_curves_cycle_and_exact_is_never_worse() {
    let image = chain_strip(40, 16, 10, 4, 8);
    let curve = circle(50.0, 50.0, 30.0, 90);
    let input = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
    let mut p = params(16.0, 16.0);
    p.closed = ClosedMode::Approximate;
    let approx = synthesize(&input, &p, &mut NoProgress).unwrap();
    p.closed = ClosedMode::Exact;
    let exact = synthesize(&input, &p, &mut NoProgress).unwrap();
    assert!(approx.report.closed && exact.report.closed);
    assert!(exact.report.total_cost <= approx.report.total_cost);
    assert!(exact.report.closed_certified.is_some());
    assert!(approx.report.closed_certified.is_none());
    // The last piece has a seam back to the first one.
    assert!(exact.pieces.iter().all(|piece| piece.has_seam));
    let seams: f64 = exact.pieces.iter().map(|piece| piece.seam_cost).sum();
    assert!((seams - exact.report.total_cost).abs() < 1e-6);
    // Treated as open, the same curve has one seam fewer.
    p.closed = ClosedMode::Open;
    let open = synthesize(&input, &p, &mut NoProgress).unwrap();
    assert!(!open.pieces.last().unwrap().has_seam);
    assert!(open.report.total_cost <= exact.report.total_cost);
}

#[test]
fn pinning_fixes_the_first_position() {
    let image = chain_strip(40, 16, 10, 4, 8);
    let curve = line(0.0, 20.0, 80.0, 20.0);
    let input = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
    let free = synthesize(&input, &params(16.0, 16.0), &mut NoProgress).unwrap();
    let mut p = params(16.0, 16.0);
    let first = free.pieces[0].position.unwrap();
    let pin = [(first[0] + 13) % 20, first[1]];
    p.pin_first = Some(pin);
    match synthesize(&input, &p, &mut NoProgress) {
        Ok(pinned) => {
            assert_eq!(pinned.pieces[0].position, Some(pin));
            assert!(pinned.report.total_cost >= free.report.total_cost);
        }
        Err(error) => assert!(matches!(error, Error::Input(InputError::InvalidPin { .. })), "{error}"),
    }
    p.pin_first = Some(first);
    let pinned = synthesize(&input, &p, &mut NoProgress).unwrap();
    assert_eq!(pinned.pieces[0].position, Some(first));
    assert_eq!(pinned.report.total_cost, free.report.total_cost);
    p.pin_first = Some([-1000, 5]);
    assert!(matches!(synthesize(&input, &p, &mut NoProgress), Err(Error::Input(InputError::InvalidPin { .. }))));
}

#[test]
fn stitching_never_increases_seam_cost_and_keeps_matching_edges() {
    let image = chain_strip(60, 20, 12, 5, 10);
    let curve = circle(60.0, 60.0, 25.0, 80);
    let input = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
    let mut p = params(20.0, 12.0);
    // Rigid pieces: bent ones continue this periodic chain around the circle at no cost at all.
    p.piece_shape = PieceShape::Rigid;
    let plain = synthesize(&input, &p, &mut NoProgress).unwrap();
    p.stitch = true;
    let stitched = synthesize(&input, &p, &mut NoProgress).unwrap();
    assert_eq!(stitched.report.total_cost_unstitched, plain.report.total_cost);
    assert!(stitched.report.total_cost <= plain.report.total_cost);
    for piece in &stitched.pieces {
        assert!(piece.seam_cost <= piece.seam_cost_unstitched);
        if piece.seam_cost_unstitched == 0.0 {
            assert!(piece.stitch.iter().enumerate().all(|(s, &t)| s == t));
        }
    }
    assert!(stitched.report.stitched_seams > 0, "a bent chain leaves seams to stitch");
    // On a straight periodic case every seam matches and every T stays the identity.
    let straight = line(10.0, 40.0, 200.0, 40.0);
    let strip = chain_strip(96, 24, 12, 6, 12);
    let mut p = params(24.0, 20.0);
    p.stitch = true;
    let output = synthesize(
        &Input { exemplar: &strip, curve: &straight, avoidance: None, more_exemplars: &[] },
        &p,
        &mut NoProgress,
    )
    .unwrap();
    assert_eq!(output.report.stitched_seams, 0);
    assert_eq!(output.report.total_cost, 0.0);
}

#[test]
fn same_input_same_bytes_for_any_thread_count() {
    let image = chain_strip(40, 16, 10, 4, 8);
    let curve = circle(50.0, 50.0, 30.0, 90);
    let mut p = params(16.0, 14.0);
    p.stitch = true;
    p.closed = ClosedMode::Exact;
    let run = |threads: usize| on_threads(threads, &Input::new(&image, &curve), &p);
    let (one, two) = (run(1), run(2));
    assert_eq!(one.image, two.image);
    assert_eq!(one.pieces, two.pieces);
}

#[test]
fn repeat_baseline_bends_the_pattern_and_synthesis_does_not() {
    let image = chain_strip(40, 16, 10, 4, 8);
    let curve = circle(50.0, 50.0, 30.0, 90);
    let input = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
    let mut p = params(16.0, 14.0);
    p.method = Method::Repeat;
    let repeat = synthesize(&input, &p, &mut NoProgress).unwrap();
    assert!(repeat.report.distortion_max > 0.2, "{}", repeat.report.distortion_max);
    assert!(repeat.report.wrap_seams >= 4);
    assert!(repeat.pieces.is_empty());
    assert!(repeat.image.count_alpha_at_least(128) > 300);
    p.method = Method::Synthesis;
    p.piece_shape = PieceShape::Rigid;
    let rigid = synthesize(&input, &p, &mut NoProgress).unwrap();
    assert_eq!(rigid.report.distortion_max, 0.0);
    // Bent pieces stretch as the repeat baseline does, but seams sit where the optimum puts them.
    p.piece_shape = PieceShape::Bent;
    let bent = synthesize(&input, &p, &mut NoProgress).unwrap();
    assert!((bent.report.distortion_max - repeat.report.distortion_max).abs() < 1e-9);
}

#[test]
fn bad_input_gives_clear_errors() {
    let image = chain_strip(40, 16, 10, 4, 8);
    let curve = line(0.0, 0.0, 100.0, 0.0);
    let input = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
    let message = |result: Result<crate::Output, Error>| result.unwrap_err().to_string();

    let transparent = RgbaImage::new(10, 10);
    let m = message(synthesize(&Input { exemplar: &transparent, ..input }, &params(16.0, 10.0), &mut NoProgress));
    assert!(m.contains("fully transparent"), "{m}");
    let opaque = RgbaImage::filled(10, 10, [1, 2, 3, 255]);
    let m = message(synthesize(&Input { exemplar: &opaque, ..input }, &params(16.0, 10.0), &mut NoProgress));
    assert!(m.contains("fully opaque"), "{m}");
    for width in [0.0, -3.0, f64::NAN] {
        let m = message(synthesize(&input, &params(width, 10.0), &mut NoProgress));
        assert!(m.starts_with("invalid width"), "{m}");
    }
    let m = message(synthesize(&input, &params(16.0, 150.0), &mut NoProgress));
    assert!(m.contains("piece-length") && m.contains("curve's length"), "{m}");
    let m = message(synthesize(&input, &params(16.0, f64::NAN), &mut NoProgress));
    assert!(m.starts_with("invalid piece-length"), "{m}");
    // Zero-length and NaN curves are refused when the curve is built.
    assert!(Polyline::new(vec![Point::new(3.0, 3.0), Point::new(3.0, 3.0)], false).is_err());
    assert!(Polyline::new(vec![Point::new(f64::NAN, 3.0), Point::new(3.0, 3.0)], false).is_err());
    // A ribbon narrower than the pattern has no valid position.
    let m = message(synthesize(&input, &params(4.0, 10.0), &mut NoProgress));
    assert!(m.contains("no valid exemplar position"), "{m}");
    let mut p = params(16.0, 10.0);
    p.closed = ClosedMode::Exact;
    let m = message(synthesize(&input, &p, &mut NoProgress));
    assert!(m.contains("the curve is open"), "{m}");
    let map = RgbaImage::new(5, 5);
    let mut p = params(16.0, 10.0);
    p.canvas = Canvas::Size { width: 10, height: 10 };
    let m = message(synthesize(&Input { avoidance: Some(&map), ..input }, &p, &mut NoProgress));
    assert!(m.contains("canvas size"), "{m}");
}

#[test]
fn long_edges_stay_exact() {
    // C = 300 samples: 75 alpha block sums per edge in the profile tree, 19 chunks in the
    // early-exit comparison.
    let image = RgbaImage::from_fn(9, 290, |x, y| {
        if (5..285).contains(&y) && x % 3 != 1 { [40 * x as u8, 200, (y % 200) as u8, 255] } else { [0; 4] }
    });
    let curve = line(0.0, 400.0, 30.0, 400.0);
    let mut p = params(300.0, 3.0);
    p.foldover_avoidance = false;
    let input = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
    let exact = synthesize(&input, &p, &mut NoProgress).unwrap();
    p.solver = Solver::Reference;
    let reference = synthesize(&input, &p, &mut NoProgress).unwrap();
    assert_eq!(exact.report.samples_per_edge, 300);
    assert_eq!(exact.report.total_cost, reference.report.total_cost);
    let positions = |o: &crate::Output| o.pieces.iter().map(|p| p.position).collect::<Vec<_>>();
    assert_eq!(positions(&exact), positions(&reference));
}

/// A 2-pixel uniform bar at the left (a sliver: valid, and free to repeat) next to a tall band of
/// columns of distinct colours (the pattern proper: every seam costs something).
fn sliver_and_band() -> RgbaImage {
    RgbaImage::from_fn(80, 24, |x, y| {
        if x < 20 {
            if (11..13).contains(&y) { [90, 90, 90, 255] } else { [0; 4] }
        } else if (4..19).contains(&y) {
            [(x * 37 % 251) as u8, (x * 91 % 241) as u8, (y * 13) as u8, 255]
        } else {
            [0; 4]
        }
    })
}

#[test]
fn a_sliver_only_optimum_is_excluded_by_the_coverage_rule_and_allowed_without_it() {
    let image = sliver_and_band();
    let curve = line(0.0, 30.0, 90.0, 30.0);
    let input = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
    // Opaque pixels of the exemplar window a straight piece covers at `position`.
    let coverage = |position: [i32; 2], length: i32| {
        let mut count = 0;
        for y in position[1]..position[1] + 20 {
            for x in position[0]..position[0] + length {
                if (0..80).contains(&x) && (0..24).contains(&y) && image.get(x as usize, y as usize)[3] > 8 {
                    count += 1;
                }
            }
        }
        count
    };
    let mut p = params(20.0, 6.0);
    p.min_coverage = 0.0;
    let paper = synthesize(&input, &p, &mut NoProgress).unwrap();
    assert_eq!(paper.report.dp_optimum, 0.0, "the paper's rule: the sliver repeats for free");
    for piece in &paper.pieces {
        let position = piece.position.unwrap();
        assert!(position[0] + 6 <= 20 && coverage(position, 6) == 12, "piece {} at {position:?}", piece.index);
    }
    let default = synthesize(&input, &params(20.0, 6.0), &mut NoProgress).unwrap();
    // 15 pieces need 90 columns; the band has 60, so the pattern proper cannot be copied seamlessly.
    assert!(default.report.dp_optimum > 0.0);
    assert!(default.report.valid_fraction < paper.report.valid_fraction);
    for piece in &default.pieces {
        let position = piece.position.unwrap();
        // The typical window holds 15 × 6 = 90 pattern pixels; half of it is required.
        assert!(coverage(position, 6) >= 45, "piece {} at {position:?}", piece.index);
    }
    // The same holds with the reference solver.
    let mut p = params(20.0, 6.0);
    p.solver = Solver::Reference;
    let reference = synthesize(&input, &p, &mut NoProgress).unwrap();
    assert_eq!(reference.report.dp_optimum, default.report.dp_optimum);
}

#[test]
fn min_coverage_out_of_range_is_rejected() {
    let image = sliver_and_band();
    let curve = line(0.0, 30.0, 90.0, 30.0);
    for bad in [-0.1, 1.5, f64::NAN] {
        let mut p = params(20.0, 6.0);
        p.min_coverage = bad;
        let result = synthesize(
            &Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] },
            &p,
            &mut NoProgress,
        );
        assert!(matches!(result, Err(Error::Parameter(_))), "{bad}");
    }
}

/// Exact closed mode on a real chain (`data/real/curve/chain_round.png`) around a circle: with a
/// budget of two starts the search stops uncertified but says how far it may be from the optimum
/// (a bound no cycle goes below); with a forbidden area that leaves one piece empty, the cycle is
/// cut at that piece, whose single position needs one pinned DP at most (none when the first DP
/// already closes there), and the optimum is certified.
#[test]
fn exact_closed_mode_reports_its_gap_and_certifies_through_an_empty_piece() {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/curve");
    let chain = motif_io::read_image(&folder.join("chain_round.png")).unwrap();
    let curve = circle(160.0, 160.0, 90.0, 180);
    let mut p = params(108.0, 25.0);
    p.closed = ClosedMode::Exact;
    p.closed_max_starts = 2;
    p.canvas = Canvas::Size { width: 320, height: 320 };
    let hurried = synthesize(&Input::new(&chain, &curve), &p, &mut NoProgress).unwrap().report;
    assert_eq!((hurried.closed_certified, hurried.closed_starts_tried), (Some(false), 2));
    let (bound, gap) = (hurried.closed_lower_bound.unwrap(), hurried.closed_gap.unwrap());
    assert!(bound < hurried.dp_optimum && gap > 0.0 && gap < 1.0, "{bound} {} {gap}", hurried.dp_optimum);
    assert!((gap - (hurried.dp_optimum - bound) / hurried.dp_optimum).abs() < 1e-9);

    // A block over the ribbon left of the centre, half way round from where the circle starts.
    let block = |x: usize, y: usize| (55..85).contains(&x) && (140..180).contains(&y);
    let map = RgbaImage::from_fn(320, 320, |x, y| if block(x, y) { [255; 4] } else { [0; 4] });
    let blocked = synthesize(&Input::new(&chain, &curve).with_avoidance(&map), &p, &mut NoProgress).unwrap().report;
    assert!(blocked.empty_pieces >= 1, "{}", blocked.empty_pieces);
    assert_eq!((blocked.closed_certified, blocked.closed_gap), (Some(true), Some(0.0)));
    assert!(blocked.closed_starts_tried <= 1, "{}", blocked.closed_starts_tried);
    assert_eq!(blocked.closed_lower_bound, Some(blocked.dp_optimum));
}
