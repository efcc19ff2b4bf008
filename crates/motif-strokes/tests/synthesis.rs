//! End-to-end properties of analysis and synthesis.

use motif_core::{NoProgress, Point, Polygon, Polyline};
use motif_core::{math, vector};
use motif_strokes::samples::{FigureField, HatchRow, figure_field, hatch_row};
use motif_strokes::{Error, Input, Output, Params, Stroke, Target, region_from_outline, synthesize};
use motif_strokes::{InputError, LimitError};

const RED: [u8; 4] = [220, 30, 30, 255];
const BLUE: [u8; 4] = [30, 30, 220, 255];

fn straight_path(length: f64) -> Polyline {
    Polyline::new(vec![Point::new(0.0, 100.0), Point::new(length, 100.0)], false).unwrap()
}

fn params(scale: f64) -> Params {
    let mut params = Params::default();
    params.scale = scale;
    params
}

fn run(strokes: Vec<Stroke>, target: Target, params: &Params) -> Output {
    synthesize(&Input::new(strokes, target), params, &mut NoProgress).unwrap()
}

/// Output elements along a path in path order (seeds come sorted by arc length).
fn element_colours(output: &Output) -> Vec<[u8; 4]> {
    output.elements.iter().map(|e| output.strokes[e.strokes.start].colour).collect()
}

#[test]
fn alternating_colours_stay_alternating_along_a_path() {
    let row = HatchRow { count: 30, ..HatchRow::default() };
    let strokes = hatch_row(&row, Point::ORIGIN, |_| 0.0, |i| if i % 2 == 0 { RED } else { BLUE }, 1);
    let output = run(strokes, Target::Path(straight_path(2400.0)), &params(4.0));
    assert_eq!(output.analysis.elements.len(), 30, "each sketchy hatch is one element");
    assert!((output.elements.len() as f64 - 300.0).abs() <= 3.0, "{}", output.elements.len());
    let colours = element_colours(&output);
    let alternations = colours.windows(2).filter(|w| w[0] != w[1]).count();
    assert_eq!(alternations, colours.len() - 1, "{colours:?}");
    assert_eq!(output.report.fallback_elements, 0);
}

#[test]
fn a_closed_path_gets_a_closed_chain_of_hatches_along_its_tangent() {
    let row = HatchRow { count: 20, strokes_per_hatch: 1, ..HatchRow::default() };
    let strokes = hatch_row(&row, Point::ORIGIN, |_| 0.0, |_| BLUE, 8);
    let radius = 150.0;
    let circle: Vec<Point> = (0..720)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / 720.0;
            Point::new(200.0 + radius * math::cos(a), 200.0 + radius * math::sin(a))
        })
        .collect();
    let path = Polyline::new(circle, true).unwrap();
    let output = run(strokes, Target::Path(path.clone()), &params(4.0));
    let expected = path.length() / 8.0;
    assert!((output.elements.len() as f64 - expected).abs() <= 1.0);
    // A closed chain: every element has two neighbours.
    assert_eq!(output.target_edges.len(), output.elements.len());
    for element in &output.elements {
        let radial = vector::normalized(element.position - Point::new(200.0, 200.0));
        assert!((vector::length(element.position - Point::new(200.0, 200.0)) - radius).abs() < 0.1);
        // The reference hatches stand across their row, so the copies stand across the circle.
        let copy = &output.strokes[element.strokes.start];
        let points = copy.polyline.points();
        let direction = vector::normalized(points[points.len() - 1] - points[0]);
        assert!(direction.dot(radial).abs() > 0.95, "a hatch is not across the path");
    }
}

fn axis_angle(output: &Output, index: usize) -> f64 {
    let element = &output.elements[index];
    let reference = &output.analysis.elements[element.reference];
    (reference.frame.angle() + element.rotation).rem_euclid(std::f64::consts::PI)
}

fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::PI);
    d.min(std::f64::consts::PI - d)
}

#[test]
fn a_smooth_orientation_trend_is_kept_with_five_rings() {
    let step = 3f64.to_radians();
    let row = HatchRow { count: 40, strokes_per_hatch: 1, ..HatchRow::default() };
    let strokes = hatch_row(&row, Point::ORIGIN, |i| i as f64 * step - 1.0, |_| BLUE, 2);
    let mut p = params(4.0);
    p.rings = Some(5);
    let output = run(strokes, Target::Path(straight_path(3200.0)), &p);
    assert_eq!(output.analysis.elements.len(), 40);
    let angles: Vec<f64> = (0..output.elements.len()).map(|i| axis_angle(&output, i)).collect();
    let gaps: Vec<f64> = angles.windows(2).map(|w| angle_gap(w[0], w[1])).collect();
    let smooth = gaps.iter().filter(|&&g| g <= 2.0 * step + 1e-9).count() as f64 / gaps.len() as f64;
    let mean_gap = gaps.iter().sum::<f64>() / gaps.len() as f64;
    // A random arrangement of the same 40 angles has mean gaps near 40°.
    assert!(smooth > 0.8, "only {smooth} of consecutive pairs turn smoothly");
    assert!(mean_gap < 3.0 * step, "mean turn {}°", mean_gap.to_degrees());
}

fn l_shape(size: f64) -> Polygon {
    Polygon::new(vec![
        Point::new(0.0, 0.0),
        Point::new(size, 0.0),
        Point::new(size, 0.45 * size),
        Point::new(0.45 * size, 0.45 * size),
        Point::new(0.45 * size, size),
        Point::new(0.0, size),
    ])
    .unwrap()
}

#[test]
fn region_count_matches_density_and_centres_stay_inside() {
    let field = FigureField::default();
    let strokes = figure_field(&field, Point::new(20.0, 20.0), 3);
    let region = l_shape(900.0);
    let output = run(strokes, Target::Region(region.clone()), &params(8.0));
    assert_eq!(output.analysis.elements.len(), 120, "each three-stroke figure is one element");
    // The reference was drawn on a grid of spacing s: one element per s².
    let expected = region.area() / (field.spacing * field.spacing);
    let count = output.elements.len() as f64;
    assert!((count - expected).abs() <= 0.1 * expected, "{count} elements, expected about {expected}");
    assert!(output.elements.iter().all(|e| region.contains(e.position)));
    assert!(output.report.candidate_fraction > 0.5, "{:?}", output.report);
}

#[test]
fn variation_zero_gives_exact_copies_and_variation_changes_parameters() {
    let strokes = figure_field(&FigureField { columns: 6, rows: 5, ..FigureField::default() }, Point::ORIGIN, 4);
    let region = l_shape(400.0);
    let output = run(strokes.clone(), Target::Region(region.clone()), &params(8.0));
    for element in &output.elements {
        let reference = &output.analysis.elements[element.reference];
        assert!(element.exchange.is_identity() && element.rotation == 0.0);
        let shift = element.position - reference.frame.centre;
        let copied = &output.strokes[element.strokes.clone()];
        assert_eq!(copied.len(), reference.strokes.len());
        for (copy, &source) in copied.iter().zip(&reference.strokes) {
            let original = &strokes[source];
            assert_eq!((copy.width, copy.colour, copy.fill), (original.width, original.colour, original.fill));
            for (p, q) in copy.polyline.points().iter().zip(original.polyline.points()) {
                assert!(vector::distance(*p, *q + shift) < 1e-9);
            }
        }
    }
    let mut varied = params(8.0);
    varied.variation = 1.0;
    let output = run(strokes, Target::Region(region), &varied);
    let changed = output.elements.iter().filter(|e| !e.exchange.is_identity()).count();
    assert!(changed > output.elements.len() / 2, "{changed} of {}", output.elements.len());
    let limits = varied.thresholds;
    for e in &output.elements {
        assert!(e.exchange.rotation.abs() <= limits.parallelism + 1e-12);
        let ratio = e.exchange.length_scale.max(1.0 / e.exchange.length_scale);
        assert!(ratio <= limits.overlap + 1e-12);
        let shift = e.exchange.colour_shift.iter().map(|c| c * c).sum::<f64>().sqrt();
        assert!(shift <= limits.colour + 1e-12);
    }
}

#[test]
fn position_variation_brings_back_the_reference_jitter() {
    let row = HatchRow { count: 30, jitter: 3.0, strokes_per_hatch: 1, ..HatchRow::default() };
    let strokes = hatch_row(&row, Point::ORIGIN, |_| 0.0, |_| BLUE, 5);
    let path = straight_path(1200.0);
    let mut p = params(4.0);
    let plain = run(strokes.clone(), Target::Path(path.clone()), &p);
    p.position_variation = true;
    let varied = run(strokes, Target::Path(path), &p);
    let spread = |output: &Output| {
        let offsets: Vec<f64> = output.elements.iter().map(|e| e.position.y - 100.0).collect();
        (offsets.iter().map(|o| o * o).sum::<f64>() / offsets.len() as f64).sqrt()
    };
    assert_eq!(spread(&plain), 0.0);
    let s = spread(&varied);
    // The reference centres deviate by up to 3 (uniform: RMS about 1.7) from their row.
    assert!(s > 0.8 && s < 4.0, "RMS offset {s}");
}

fn run_in_pool(threads: usize, input: &Input, params: &Params) -> Output {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| synthesize(input, params, &mut NoProgress).unwrap())
}

#[test]
fn same_seed_same_output_for_any_thread_count() {
    let strokes = figure_field(&FigureField { columns: 8, rows: 6, ..FigureField::default() }, Point::ORIGIN, 6);
    let input = Input::new(strokes, Target::Region(l_shape(500.0)));
    let mut p = params(8.0);
    p.variation = 0.5;
    p.position_variation = true;
    p.seed = 9;
    let strip = |mut o: Output| {
        o.report.stages_ms.clear();
        o
    };
    let one = strip(run_in_pool(1, &input, &p));
    let two = strip(run_in_pool(2, &input, &p));
    assert_eq!(one, two);
    p.seed = 10;
    let other = strip(run_in_pool(2, &input, &p));
    assert_ne!(one.strokes, other.strokes);
}

#[test]
fn bad_input_gives_clear_errors() {
    let strokes = figure_field(&FigureField { columns: 3, rows: 3, ..FigureField::default() }, Point::ORIGIN, 7);
    let region = Target::Region(l_shape(200.0));
    let error = synthesize(&Input::new(vec![], region.clone()), &params(4.0), &mut NoProgress).unwrap_err();
    assert_eq!(error, Error::Input(InputError::NoStrokes));
    assert!(error.to_string().contains("no strokes"));
    for scale in [0.0, -1.0, f64::NAN] {
        let error =
            synthesize(&Input::new(strokes.clone(), region.clone()), &params(scale), &mut NoProgress).unwrap_err();
        assert!(error.to_string().starts_with("invalid scale"), "{error}");
    }
    let bowtie = Polygon::new(vec![
        Point::new(0.0, 0.0),
        Point::new(100.0, 100.0),
        Point::new(100.0, 0.0),
        Point::new(0.0, 60.0),
    ])
    .unwrap();
    let error =
        synthesize(&Input::new(strokes.clone(), Target::Region(bowtie)), &params(4.0), &mut NoProgress).unwrap_err();
    assert_eq!(error, Error::Input(InputError::SelfIntersectingRegion));
    let symmetric_bowtie =
        vec![Point::new(0.0, 0.0), Point::new(100.0, 100.0), Point::new(100.0, 0.0), Point::new(0.0, 100.0)];
    assert_eq!(region_from_outline(symmetric_bowtie), Err(Error::Input(InputError::SelfIntersectingRegion)));
    let flat = vec![Point::new(0.0, 0.0), Point::new(10.0, 0.0), Point::new(20.0, 0.0)];
    let error = region_from_outline(flat).unwrap_err();
    assert!(error.to_string().contains("area > 0"), "{error}");
    let huge =
        Target::Region(Polygon::new(vec![Point::new(0.0, 0.0), Point::new(1e6, 0.0), Point::new(1e6, 1e6)]).unwrap());
    let error = synthesize(&Input::new(strokes.clone(), huge), &params(4.0), &mut NoProgress).unwrap_err();
    assert!(matches!(error, Error::Limit(LimitError::TooManyElements { .. })), "{error}");
    let mut bad = params(4.0);
    bad.thresholds.overlap = 1.0;
    let error = synthesize(&Input::new(strokes, region), &bad, &mut NoProgress).unwrap_err();
    assert!(error.to_string().contains("thresholds.ov"), "{error}");
}

#[test]
fn arbitrary_drawings_never_panic() {
    use motif_core::SeedStreams;
    use motif_core::random::Rng;
    let streams = SeedStreams::new(12);
    for trial in 0..12u64 {
        let mut random = streams.stream("scribbles", trial);
        let count = random.random_range(1..40);
        let strokes: Vec<Stroke> = (0..count)
            .filter_map(|_| {
                let start = Point::new(random.random_range(0.0..200.0), random.random_range(0.0..100.0));
                let points: Vec<Point> = (0..random.random_range(2..6))
                    .map(|_| {
                        start + kurbo::Vec2::new(random.random_range(-15.0..15.0), random.random_range(-15.0..15.0))
                    })
                    .collect();
                let polyline = Polyline::new(points, random.random_bool(0.3)).ok()?;
                let width = random.random_range(0.0..4.0);
                let fill = random.random_bool(0.3).then_some([10, 200, 30, 255]);
                Some(Stroke::new(polyline, width, [random.random(), random.random(), random.random(), 255], fill))
            })
            .collect();
        if strokes.is_empty() {
            continue;
        }
        let mut p = params(random.random_range(0.5..30.0));
        p.rings = Some(random.random_range(1..=5));
        p.variation = random.random_range(0.0..1.0);
        p.position_variation = random.random_bool(0.5);
        p.fit = if random.random_bool(0.5) {
            motif_strokes::FitPoints::Contour
        } else {
            motif_strokes::FitPoints::Skeleton
        };
        let target = if trial % 2 == 0 {
            Target::Path(straight_path(random.random_range(10.0..800.0)))
        } else {
            Target::Region(l_shape(random.random_range(20.0..400.0)))
        };
        let output = synthesize(&Input::new(strokes, target.clone()), &p, &mut NoProgress).unwrap();
        assert!(!output.elements.is_empty());
        assert_eq!(output.report.matched_elements + output.report.fallback_elements, output.elements.len());
        if let Target::Region(region) = &target {
            assert!(output.elements.iter().all(|e| region.contains(e.position)));
        }
    }
}

#[test]
fn the_memory_limit_refuses_at_the_reported_estimate() {
    let row = HatchRow { count: 12, ..HatchRow::default() };
    let strokes = hatch_row(&row, Point::new(10.0, 30.0), |i| 0.05 * i as f64, |_| [20, 20, 20, 255], 1);
    let target = Target::Path(straight_path(4000.0));
    let output = run(strokes.clone(), target.clone(), &params(6.0));
    let estimate = output.report.estimated_memory_bytes;
    let points: usize = output.strokes.iter().map(|s| s.polyline.points().len()).sum();
    assert!(estimate >= 16 * points as u64, "{estimate} for {points} output points");
    let limited = params(6.0).with_max_memory(estimate.max(1 << 20));
    assert_eq!(run(strokes.clone(), target.clone(), &limited).strokes, output.strokes);
    // A region a hundred times larger than a 1 MiB limit allows.
    let square = Polygon::new(vec![
        Point::new(0.0, 0.0),
        Point::new(8_000.0, 0.0),
        Point::new(8_000.0, 8_000.0),
        Point::new(0.0, 8_000.0),
    ])
    .unwrap();
    let error = synthesize(
        &Input::new(strokes, Target::Region(square)),
        &params(6.0).with_max_memory(1 << 20),
        &mut NoProgress,
    )
    .unwrap_err();
    assert!(
        matches!(error, Error::Limit(LimitError::Memory(_))) && error.to_string().contains("max-memory"),
        "{error}"
    );
}
