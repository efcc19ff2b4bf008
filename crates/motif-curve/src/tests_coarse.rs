//! Tests of the coarse-to-fine solver (`coarse`): never below the exact optimum, equal to it when
//! the bands hold the whole rows, valid paths on open and closed curves, and the same bytes for
//! any thread count.

use motif_core::math;
use motif_core::{NoProgress, Point, Polyline, RgbaImage};
use proptest::prelude::*;

use crate::closed::solve_closed;
use crate::coarse::{self, band_shape};
use crate::cost::AlphaMode;
use crate::dp::{Solver, path_cost};
use crate::solve::Setup;
use crate::tests::{Problem, best_open, chain_strip, line, params, random_exemplar};
use crate::variety::Rule;
use crate::{Input, synthesize};

/// How the solvers run on an open or closed test problem (no repetition rule).
fn setup(closed: bool) -> Setup {
    Setup {
        solver: Solver::CoarseToFine,
        closed,
        exact_closed: true,
        closed_max_starts: 100_000,
        rule: Rule { weight: 0, radius: 1, reach: [1, 1], closed },
        check_gap: false,
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, max_global_rejects: 100_000, .. ProptestConfig::default() })]

    /// With cells of 1 and 2 pixels, the coarse-to-fine path is valid, costs what it says, and
    /// never less than the exact optimum; when no row has more cells than are kept, every band is
    /// the whole row and it finds the optimum. Closed curves get cycles.
    #[test]
    fn coarse_to_fine_is_never_below_the_optimum(
        width in 10_usize..40,
        height in 4_usize..9,
        cells in proptest::collection::vec(any::<u8>(), 64),
        points in proptest::collection::vec((0.0_f64..30.0, 0.0_f64..30.0), 3),
        pieces in 1.6_f64..4.0,
        factor in 1_usize..3,
        closed in any::<bool>(),
    ) {
        let image = random_exemplar(width, height, &cells);
        prop_assume!(!image.is_fully_transparent());
        let curve = Polyline::new(points.iter().map(|&(x, y)| Point::new(x, y)).collect(), closed);
        prop_assume!(curve.is_ok());
        let curve = curve.unwrap();
        prop_assume!(curve.length() > 4.0);
        let problem = Problem::new(&image, &curve, height as f64 + 1.0, curve.length() / pieces, AlphaMode::Continuous);
        prop_assume!(problem.valid.iter().all(|v| !v.is_empty()));
        let (exemplar, model) = (&problem.exemplar, &problem.model);
        let rows = problem.rows(closed);
        let (solution, figures) = coarse::solve(exemplar, model, &rows, setup(closed), factor, &mut |_| {});
        prop_assert_eq!(solution.path.len(), rows.len());
        for (r, &i) in solution.path.iter().enumerate() {
            prop_assert!(i < rows[r].positions.len(), "row {} index {}", r, i);
        }
        prop_assert_eq!(path_cost(exemplar, model, &rows, &solution.path), solution.cost);
        let optimum = if closed {
            let last = rows.len() - 1;
            prop_assert_eq!(solution.path[0], solution.path[last]);
            solve_closed(exemplar, model, &rows, Solver::Exact, true, 100_000, &mut |_| {}).cost
        } else {
            best_open(&problem, Solver::Exact).0
        };
        prop_assert!(solution.cost >= optimum);
        let few_cells = rows.iter().all(|row| {
            let cells: std::collections::HashSet<[i32; 2]> =
                row.positions.iter().map(|p| [p[0].div_euclid(factor as i32), p[1].div_euclid(factor as i32)]).collect();
            cells.len() <= band_shape(factor).0
        });
        if few_cells || factor == 1 {
            prop_assert_eq!(solution.cost, optimum);
        }
        prop_assert!(figures.band_positions_per_row <= figures.positions_per_row);
    }
}

/// A chain strip wide and tall enough that the solver picks cells of 2 pixels, on a gentle arc.
fn dense_case() -> (RgbaImage, Polyline) {
    let image = chain_strip(240, 40, 24, 8, 22);
    let points = (0..=60)
        .map(|i| {
            let a = f64::from(i) / 60.0;
            Point::new(20.0 + 300.0 * a, 120.0 - 40.0 * math::sin(a * std::f64::consts::PI))
        })
        .collect();
    (image, Polyline::new(points, false).unwrap())
}

#[test]
fn coarse_to_fine_reports_its_gap_and_keeps_the_bytes_for_any_thread_count() {
    let (image, curve) = dense_case();
    let mut p = params(60.0, 20.0);
    p.solver = Solver::CoarseToFine;
    p.check_gap = true;
    let run = |threads: usize| crate::tests::on_threads(threads, &Input::new(&image, &curve), &p);
    let (one, two) = (run(1), run(2));
    assert_eq!(one.image, two.image);
    assert_eq!(one.pieces, two.pieces);
    let report = &one.report;
    let figures = report.coarse.clone().expect("coarse figures");
    assert_eq!(figures.factor, 2, "{figures:?}");
    assert!(figures.band_positions_per_row < figures.positions_per_row, "{figures:?}");
    let (exact, gap) = (report.exact_optimum.unwrap(), report.cost_gap.unwrap());
    assert!(gap >= 0.0 && exact <= report.dp_optimum, "{exact} {gap} {}", report.dp_optimum);
    assert_eq!(report.dp_optimum - exact, gap);
    assert!((0.0..=1.0).contains(&report.cost_gap_fraction.unwrap()));
}

#[test]
fn exact_solver_reports_no_coarse_figures() {
    let image = chain_strip(96, 24, 12, 6, 12);
    let curve = line(10.0, 40.0, 200.0, 40.0);
    let mut p = params(24.0, 20.0);
    p.check_gap = true;
    let output = synthesize(
        &Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] },
        &p,
        &mut NoProgress,
    )
    .unwrap();
    assert!(output.report.coarse.is_none() && output.report.cost_gap.is_none());
}
