//! Tests of what motif adds to the paper's curve method: bent pieces, repetition control, width
//! profiles, several exemplars and incremental runs.

use motif_core::math;
use motif_core::{NoProgress, Point, Polyline, RgbaImage};

use crate::tests::{chain_strip, circle, line, params, random_exemplar};
use crate::{Canvas, ClosedMode, Input, PieceShape, synthesize};

#[test]
fn variety_uses_more_windows_on_a_straight_line() {
    // Rings of growing size: every window differs, and the plain optimum repeats a few of them.
    let image = RgbaImage::from_fn(160, 28, |x, y| {
        let cell = x / 16;
        let (cx, cy) = (cell as f64 * 16.0 + 8.0, 14.0);
        let radius = 3.0 + (cell % 5) as f64;
        let ring = (math::hypot(x as f64 + 0.5 - cx, y as f64 + 0.5 - cy) - radius).abs();
        if ring < 1.5 || (y as f64 + 0.5 - cy).abs() < 1.0 { [180, 120 + cell as u8 * 9, 40, 255] } else { [0; 4] }
    });
    let curve = line(10.0, 40.0, 330.0, 40.0);
    let input = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
    let plain = synthesize(&input, &params(28.0, 16.0), &mut NoProgress).unwrap();
    let mut varied_params = params(28.0, 16.0);
    varied_params.variety = 5000.0;
    let varied = synthesize(&input, &varied_params, &mut NoProgress).unwrap();
    let figures = varied.report.variety.clone().unwrap();
    assert!(plain.report.repeated_pairs > 0, "{:?}", plain.report.repeated_pairs);
    assert!(varied.report.repeated_pairs < plain.report.repeated_pairs, "{figures:?}");
    assert!(
        varied.report.distinct_windows > plain.report.distinct_windows,
        "{} vs {}",
        varied.report.distinct_windows,
        plain.report.distinct_windows
    );
    assert!(figures.energy <= figures.energy_unpenalised);
    assert_eq!(figures.lower_bound, plain.report.dp_optimum);
    assert!(figures.energy >= figures.lower_bound);
    assert_eq!(varied.report.dp_optimum, varied.report.total_cost_unstitched, "Ω of the result, without charges");
    // Bad values are refused with the parameter named.
    for (weight, radius) in [(-1.0, 8), (f64::NAN, 8), (1.0, 0), (1.0, 5000)] {
        let mut bad = params(28.0, 16.0);
        bad.variety = weight;
        bad.variety_radius = radius;
        let message = synthesize(&input, &bad, &mut NoProgress).unwrap_err().to_string();
        assert!(message.contains("variety"), "{message}");
    }
}

#[test]
fn no_opaque_pixel_falls_in_the_avoidance_map_on_a_curve_with_either_shape() {
    let image = chain_strip(96, 24, 12, 6, 12);
    let curve = circle(80.0, 80.0, 50.0, 120);
    // Forbid a block straddling the ribbon on the right of the circle.
    let map = RgbaImage::from_fn(170, 170, |x, y| {
        if (115..145).contains(&x) && (60..100).contains(&y) { [255, 255, 255, 255] } else { [0, 0, 0, 0] }
    });
    for shape in [PieceShape::Rigid, PieceShape::Bent] {
        let mut p = params(24.0, 14.0);
        p.piece_shape = shape;
        let output = synthesize(
            &Input { exemplar: &image, curve: &curve, avoidance: Some(&map), more_exemplars: &[] },
            &p,
            &mut NoProgress,
        )
        .unwrap();
        for y in 60..100 {
            for x in 115..145 {
                assert_eq!(output.image.get(x, y)[3], 0, "{shape:?}: pattern at forbidden pixel ({x}, {y})");
            }
        }
        assert!(output.image.count_alpha_at_least(128) > 1000, "{shape:?}");
    }
}

#[test]
fn a_width_profile_swells_the_ribbon_and_the_pattern_with_it() {
    let image = chain_strip(96, 24, 12, 6, 12);
    let curve = line(10.0, 60.0, 250.0, 60.0);
    let input = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
    let mut p = params(24.0, 12.0);
    p.canvas = Canvas::Size { width: 260, height: 120 };
    p.width_profile = vec![(0.0, 1.0), (0.5, 2.0), (1.0, 1.0)];
    let output = synthesize(&input, &p, &mut NoProgress).unwrap();
    let column_height = |x: usize| (0..120).filter(|&y| output.image.get(x, y)[3] > 128).count();
    let (end, middle) = (column_height(20), (125..135).map(column_height).max().unwrap());
    assert!(end > 0 && middle as f64 > 1.6 * end as f64, "end {end}, middle {middle}");
    // The exemplar keeps C samples per edge everywhere: the DP compares like with like.
    assert_eq!(output.report.samples_per_edge, 24);
    // Bad profiles are refused with the flag named.
    for profile in [vec![(0.5, 1.0), (0.2, 1.0)], vec![(0.0, 0.0)], vec![(1.5, 1.0)], vec![(0.0, f64::NAN)]] {
        let mut bad = params(24.0, 12.0);
        bad.width_profile = profile;
        let message = synthesize(&input, &bad, &mut NoProgress).unwrap_err().to_string();
        assert!(message.contains("width-profile"), "{message}");
    }
    let mut rigid = params(24.0, 12.0);
    rigid.width_profile = vec![(0.0, 2.0)];
    rigid.piece_shape = PieceShape::Rigid;
    assert!(synthesize(&input, &rigid, &mut NoProgress).unwrap_err().to_string().contains("bent"));
}

#[test]
fn pieces_mix_several_exemplars_with_the_same_seam_cost() {
    let image = chain_strip(96, 24, 12, 6, 12);
    let curve = line(10.0, 40.0, 400.0, 40.0);
    let single = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
    let copies = [image.clone()];
    let mixed = Input { more_exemplars: &copies, ..single };
    let p = params(24.0, 16.0);
    let one = synthesize(&single, &p, &mut NoProgress).unwrap();
    let two = synthesize(&mixed, &p, &mut NoProgress).unwrap();
    // A copy of the exemplar adds windows, not cheaper seams.
    assert_eq!(two.report.dp_optimum, one.report.dp_optimum);
    // Repetition control spreads the pieces over both, and every position lies in its source.
    let mut varied = p.clone();
    varied.variety = 5000.0;
    let spread = synthesize(&mixed, &varied, &mut NoProgress).unwrap();
    let sources: std::collections::BTreeSet<usize> = spread.pieces.iter().map(|piece| piece.exemplar).collect();
    assert_eq!(sources.into_iter().collect::<Vec<_>>(), vec![0, 1]);
    for piece in &spread.pieces {
        let [x, _] = piece.position.unwrap();
        assert!((0..96).contains(&x), "{piece:?}");
    }
    // A bad second exemplar is named as such.
    let blank = [RgbaImage::from_fn(20, 20, |_, _| [0; 4])];
    let message = synthesize(&Input { more_exemplars: &blank, ..single }, &p, &mut NoProgress).unwrap_err();
    assert!(message.to_string().contains("exemplar 2"), "{message}");
}

#[test]
fn incremental_runs_equal_runs_from_scratch_and_reuse_rows() {
    let image = random_exemplar(40, 14, &(0..200).map(|i| (i * 37 % 251) as u8).collect::<Vec<_>>());
    let image = RgbaImage::from_fn(40, 16, |x, y| if y == 0 || y == 15 { [0; 4] } else { image.get(x, y - 1) });
    let control = |middle: f64| {
        let points = (0..=40)
            .map(|i| {
                let t = i as f64 / 40.0;
                // A quadratic Bézier whose middle control point moves.
                let (a, b, c) = (Point::new(10.0, 60.0), Point::new(120.0, middle), Point::new(230.0, 60.0));
                a.lerp(b, t).lerp(b.lerp(c, t), t)
            })
            .collect();
        Polyline::new(points, false).unwrap()
    };
    for shape in [PieceShape::Bent, PieceShape::Rigid] {
        let mut p = params(16.0, 9.0);
        p.piece_shape = shape;
        p.min_coverage = 0.0;
        let mut session = crate::Incremental::new();
        for (k, middle) in [20.0, 26.0, 26.0, 40.0].into_iter().enumerate() {
            let curve = control(middle);
            let input = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
            let incremental = session.synthesize(&input, &p, &mut NoProgress).unwrap();
            let scratch = synthesize(&input, &p, &mut NoProgress).unwrap();
            assert_eq!(incremental.image, scratch.image, "{shape:?}, edit {k}");
            assert_eq!(incremental.pieces, scratch.pieces, "{shape:?}, edit {k}");
            assert_eq!(incremental.report.dp_optimum, scratch.report.dp_optimum);
            if k == 2 {
                // The same curve again: every row is reused.
                assert_eq!(session.reused_rows(), incremental.report.pieces - 1, "{shape:?}");
            }
            if k > 0 && shape == PieceShape::Bent {
                assert!(session.reused_rows() > 0, "{shape:?}, edit {k}");
            }
        }
    }
}

#[test]
fn bent_pieces_continue_the_exemplar_across_seams_on_a_curve() {
    // A periodic chain around a circle: a bent piece that continues the exemplar matches its
    // neighbour exactly, so the optimum costs nothing; rigid pieces pay for the tilt of every seam.
    let image = chain_strip(96, 24, 12, 6, 12);
    let curve = circle(80.0, 80.0, 50.0, 120);
    let input = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
    let mut p = params(24.0, 18.0);
    p.closed = ClosedMode::Open;
    let bent = synthesize(&input, &p, &mut NoProgress).unwrap();
    p.piece_shape = PieceShape::Rigid;
    let rigid = synthesize(&input, &p, &mut NoProgress).unwrap();
    assert_eq!(bent.report.total_cost, 0.0);
    assert!(rigid.report.total_cost > 0.0);
    assert!(bent.image.count_alpha_at_least(128) > 1000, "the pattern is drawn");
    // On a straight line both shapes place the same pieces
    let straight = line(10.0, 40.0, 200.0, 40.0);
    let input = Input { exemplar: &image, curve: &straight, avoidance: None, more_exemplars: &[] };
    let rigid = synthesize(&input, &p, &mut NoProgress).unwrap();
    p.piece_shape = PieceShape::Bent;
    let bent = synthesize(&input, &p, &mut NoProgress).unwrap();
    // (but for the last, shorter piece, which a bent open curve fits with a full-length window).
    let last = bent.pieces.len() - 1;
    assert_eq!(bent.pieces[..last], rigid.pieces[..last]);
    assert_eq!(bent.report.dp_optimum, rigid.report.dp_optimum);
    let differing = bent.image.pixels().iter().zip(rigid.image.pixels()).filter(|(a, b)| a != b).count();
    assert!(differing * 100 < bent.image.pixels().len(), "{differing} pixels differ");
}

#[test]
fn the_memory_limit_refuses_at_the_reported_estimate() {
    let image = chain_strip(96, 24, 12, 6, 12);
    let curve = circle(80.0, 80.0, 50.0, 120);
    let input = Input { exemplar: &image, curve: &curve, avoidance: None, more_exemplars: &[] };
    let output = synthesize(&input, &params(24.0, 14.0), &mut NoProgress).unwrap();
    let estimate = output.report.estimated_memory_bytes;
    // The estimate counts at least the canvas it rendered.
    assert!(estimate >= (output.image.width() * output.image.height() * 4) as u64, "{estimate}");
    let exact = synthesize(&input, &params(24.0, 14.0).with_max_memory(estimate), &mut NoProgress).unwrap();
    assert_eq!(exact.image, output.image);
    let error = synthesize(&input, &params(24.0, 14.0).with_max_memory(estimate - 1), &mut NoProgress).unwrap_err();
    assert!(matches!(error, crate::Error::Limit(crate::LimitError::Memory(_))), "{error}");
    assert!(error.to_string().contains("max-memory"), "{error}");
    assert!(params(24.0, 14.0).with_max_memory(1000).validate().unwrap_err().to_string().contains("max-memory"));
}
