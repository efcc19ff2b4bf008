//! Tests of the curve job.

use motif_core::{NoProgress, Point};

use super::*;
use crate::Job;

pub(super) fn rings() -> RgbaImage {
    RgbaImage::from_fn(96, 24, |x, y| {
        let (dx, dy) = ((x % 16) as f64 - 7.5, y as f64 - 11.5);
        if (4.0..7.0).contains(&motif_core::math::hypot(dx, dy)) { [210, 170, 40, 255] } else { [0; 4] }
    })
}

pub(super) fn line() -> Polyline {
    let points = (0..=20).map(|i| Point::new(20.0 + 10.0 * f64::from(i), 60.0)).collect();
    Polyline::new(points, false).unwrap()
}

#[test]
fn a_described_job_runs_with_the_flag_names() {
    let job: CurveJob = serde_json::from_value(json!({
        "width": 24,
        "piece-length": 12,
        "closed": "no",
        "method": "synth",
        "pieces-shape": "bent",
        "width-profile": [[0, 1], [1, 1.5]],
        "canvas": [260, 120],
        "fidelity": true,
    }))
    .unwrap();
    let (exemplar, curve) = (rings(), line());
    let inputs = CurveInputs::new(&exemplar, &curve);
    let (params, dimensions) = job.params(&inputs).unwrap();
    assert_eq!((params.width, params.piece_length), (24.0, 12.0));
    assert!(!dimensions.width.inferred && !dimensions.piece_length.inferred);
    assert_eq!(params.closed, ClosedMode::Open);
    assert_eq!(params.method, Method::Synthesis);
    assert_eq!(params.piece_shape, PieceShape::Bent);
    assert_eq!(params.width_profile, vec![(0.0, 1.0), (1.0, 1.5)]);
    assert_eq!(params.canvas, Canvas::Size { width: 260, height: 120 });
    assert_eq!(params.mismatch_penalty, Params::default().mismatch_penalty);
    let run = job.run(inputs, &mut NoProgress).unwrap();
    assert!(run.output.report.pieces > 10);
    assert_eq!(run.figures["pieces"], run.output.report.pieces);
    assert_eq!(run.figures["width_inferred"], false);
    assert!(run.fidelity.is_some() && run.figures.contains_key("fidelity"));
}

#[test]
fn a_job_without_width_and_piece_length_infers_them() {
    let (exemplar, curve) = (rings(), line());
    let inputs = CurveInputs::new(&exemplar, &curve);
    let job: CurveJob = serde_json::from_value(json!({ "closed": "no" })).unwrap();
    let run = job.run(inputs, &mut NoProgress).unwrap();
    // Rings 16 px apart, 14 rows tall: the inferred width holds 16 rows with a margin.
    assert_eq!(run.dimensions.period, Some(16));
    assert_eq!(run.dimensions.pattern_height, Some(14));
    assert_eq!(run.figures["width_inferred"], true);
    assert_eq!(run.figures["piece_length_inferred"], true);
    // The size search starts from the guess read off the exemplar, tries piece lengths around it
    // and then wider ribbons, and keeps the trial of lowest score.
    let trials: Vec<Trial> = serde_json::from_value(run.figures["size_search"].clone()).unwrap();
    assert_eq!((trials[0].width, trials[0].piece_length), (19.0, 8.0));
    let lengths: Vec<f64> = trials.iter().map(|t| t.piece_length).collect();
    assert_eq!(&lengths[..5], &[8.0, 6.0, 10.0, 13.0, 16.0]);
    let best = trials.iter().min_by(|a, b| a.score.total_cmp(&b.score)).unwrap();
    assert_eq!(
        (run.figures["width"].as_f64(), run.figures["piece_length"].as_f64()),
        (Some(best.width), Some(best.piece_length))
    );
    assert!(trials.iter().all(|t| t.score >= t.patch_distance && t.patch_distance > 0.0), "{trials:?}");
    // The kept output is the one a run given that width and piece length draws.
    let mut settled = job.clone();
    (settled.options.width, settled.options.piece_length) = (Some(best.width), Some(best.piece_length));
    let again = settled.run(inputs, &mut NoProgress).unwrap();
    assert_eq!(again.output.image, run.output.image);
    assert!(!again.figures.contains_key("size_search"));
    let mut given = job;
    given.options.width = Some(30.0);
    let (params, dimensions) = given.params(&inputs).unwrap();
    assert_eq!((params.width, params.piece_length), (30.0, 8.0));
    assert!(!dimensions.width.inferred && dimensions.piece_length.inferred);
}

#[test]
fn bad_descriptions_name_what_is_wrong() {
    let error = serde_json::from_value::<CurveJob>(json!({ "width": 24, "piece-length": 12, "closed": "maybe" }));
    assert!(error.unwrap_err().to_string().contains("maybe"));
    let (exemplar, curve) = (rings(), line());
    let inputs = CurveInputs::new(&exemplar, &curve);
    for mut job in [CurveJob::new(24.0, 12.0), CurveJob::default()] {
        job.options.scale = 0.0;
        assert!(job.params(&inputs).unwrap_err().to_string().contains("invalid scale = 0"));
    }
    let unknown = serde_json::from_value::<CurveJob>(json!({ "widht": 24 })).unwrap_err().to_string();
    assert!(unknown.contains("widht"), "{unknown}");
    let job = CurveJob { options: CurveOptions { cut_alpha: 255, ..CurveOptions::default() }, ..CurveJob::default() };
    assert!(job.params(&inputs).unwrap_err().to_string().contains("invalid cut-alpha = 255"));
    let clear = RgbaImage::from_fn(40, 20, |_, _| [0; 4]);
    let inputs = CurveInputs { exemplar: &clear, ..inputs };
    let error = CurveJob::default().params(&inputs).unwrap_err().to_string();
    assert!(error.contains("no pattern found"), "{error}");
}

/// The choices are named as on the command line, and a description may also use the engine's
/// longer names; the defaults are the engine's, the memory bound stays a field of the job.
#[test]
fn options_are_named_as_the_flags_and_default_to_the_engine() {
    let job: CurveJob = serde_json::from_value(json!({
        "closed": "approximate",
        "method": "synthesis",
        "max-memory": "64M",
    }))
    .unwrap();
    assert_eq!((job.options.closed, job.options.method), (ClosedMode::Approximate, Method::Synthesis));
    assert_eq!(job.max_memory, Some(64 << 20));
    let written = serde_json::to_value(&job).unwrap();
    assert_eq!((written["closed"].as_str(), written["method"].as_str()), (Some("approx"), Some("synth")));
    let written = serde_json::to_value(CurveJob::new(24.0, 12.0)).unwrap();
    assert!(written.get("max-memory").is_some_and(Value::is_null), "{written}");
    let (exemplar, curve) = (rings(), line());
    let inputs = CurveInputs::new(&exemplar, &curve);
    let (params, _) = CurveJob::new(24.0, 12.0).params(&inputs).unwrap();
    assert_eq!(params, Params::DEFAULT.with_width(24.0).with_piece_length(12.0));
    let names: Vec<String> = CurveOptions::options().into_iter().map(|spec| spec.name).collect();
    assert_eq!(names[..2], ["width", "piece-length"]);
    assert!(names.iter().all(|name| written.get(name).is_some()), "{names:?}");
}
