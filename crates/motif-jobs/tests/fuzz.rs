//! Property tests of job descriptions, the JSON every front end hands this layer: any object
//! made of the jobs' own option names with values of any type and magnitude either fails to
//! deserialize, or is refused by `params` with what is wrong, or gives parameters the engine
//! accepts; never a panic. Curve jobs, the cheapest, also run to the end.

use motif_core::{NoProgress, Point, Polyline, RgbaImage};
use motif_jobs::Job;
use motif_jobs::curve::{CurveInputs, CurveJob};
use motif_jobs::points::{DomainSpec, PointsJob};
use motif_jobs::strokes::{StrokesJob, TargetSpec};
use motif_jobs::stylize::{PresynthJob, StylizeJob, TextureJob};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use serde_json::{Map, Value, json};

fn config(cases: u32) -> Config {
    Config { cases, rng_seed: RngSeed::Fixed(20261202), failure_persistence: None, ..Config::default() }
}

/// The option names of a job: the keys of its default description.
fn keys(job: &Value) -> Vec<String> {
    job.as_object().unwrap().keys().cloned().collect()
}

/// Values of every JSON type, with the magnitudes that broke engines before (1e-300, 1e300,
/// negatives, huge integers) and the words options take.
fn value() -> impl Strategy<Value = Value> {
    let number = prop_oneof![
        Just(0.0),
        Just(-1.0),
        Just(1e-300),
        Just(1e300),
        Just(0.5),
        Just(3.0),
        Just(7.0),
        Just(64.0),
        Just(1e9),
        -100.0..100.0f64
    ];
    let integer = prop_oneof![Just(u64::MAX), Just(0u64), Just(1u64), Just(5u64), 0..40u64];
    let word = prop_oneof![
        Just("NaN".to_string()),
        Just("8G".to_string()),
        Just("exact".to_string()),
        Just("auto".to_string()),
        Just("bent".to_string()),
        "[a-z0-9#.:,-]{0,12}"
    ];
    let leaf = prop_oneof![
        Just(Value::Null),
        any::<bool>().prop_map(Value::Bool),
        number.prop_map(|v| json!(v)),
        integer.prop_map(|v| json!(v)),
        word.prop_map(Value::String),
    ];
    leaf.prop_recursive(2, 12, 4, |inner| proptest::collection::vec(inner, 0..4).prop_map(Value::Array))
}

/// A description: `base` with some of its options set to random values.
fn description(base: Value) -> impl Strategy<Value = Value> {
    description_with(base, 6)
}

/// [`description`] with fewer than `most` options changed.
fn description_with(base: Value, most: usize) -> impl Strategy<Value = Value> {
    let keys = keys(&base);
    proptest::collection::vec((proptest::sample::select(keys), value()), 0..most).prop_map(move |pairs| {
        let mut object: Map<String, Value> = base.as_object().unwrap().clone();
        for (key, value) in pairs {
            object.insert(key, value);
        }
        Value::Object(object)
    })
}

/// A small diamond chain and a wavy line for curve jobs.
fn curve_exemplar_and_line() -> (RgbaImage, Polyline) {
    let exemplar =
        RgbaImage::from_fn(
            48,
            16,
            |x, y| {
                if (x % 12).abs_diff(6) + y.abs_diff(8) < 6 { [200, 150, 40, 255] } else { [0; 4] }
            },
        );
    let points: Vec<Point> = (0..=20)
        .map(|i| Point::new(20.0 + 8.0 * i as f64, 60.0 + 20.0 * motif_core::math::sin(i as f64 * 0.3)))
        .collect();
    (exemplar, Polyline::new(points, false).unwrap())
}

fn curve_base() -> Value {
    serde_json::to_value(CurveJob::new(24.0, 12.0)).unwrap()
}

fn points_base() -> Value {
    serde_json::to_value(PointsJob::new(2.0, DomainSpec::Box(vec![10.0, 10.0]))).unwrap()
}

fn strokes_base() -> Value {
    serde_json::to_value(StrokesJob::new(Some(6.0), TargetSpec::Rect([100.0, 100.0]))).unwrap()
}

fn stylize_base() -> Value {
    serde_json::to_value(StylizeJob::new()).unwrap()
}

/// An error says something (the option's name and what is allowed, or serde's type error).
fn check_message(message: &str) {
    assert!(message.len() > 8, "{message}");
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn curve_descriptions(description in description(curve_base())) {
        let (exemplar, curve) = curve_exemplar_and_line();
        match serde_json::from_value::<CurveJob>(description) {
            Ok(job) => match job.params(&CurveInputs::new(&exemplar, &curve)) {
                Ok((params, _)) => prop_assert!(params.validate().is_ok()),
                Err(error) => check_message(&error.to_string()),
            },
            Err(error) => check_message(&error.to_string()),
        }
    }

    #[test]
    fn points_descriptions(description in description(points_base())) {
        match serde_json::from_value::<PointsJob>(description) {
            Ok(job) => {
                if let Err(error) = job.engine_domain() {
                    check_message(&error.to_string());
                }
                for dimension in [2, 3] {
                    match job.params(dimension, &[]) {
                        Ok(params) => prop_assert!(params.validate().is_ok()),
                        Err(error) => check_message(&error.to_string()),
                    }
                }
            }
            Err(error) => check_message(&error.to_string()),
        }
    }

    #[test]
    fn strokes_descriptions(description in description(strokes_base())) {
        match serde_json::from_value::<StrokesJob>(description) {
            Ok(job) => {
                if let Err(error) = job.engine_target() {
                    check_message(&error.to_string());
                }
                match job.params() {
                    Ok(params) => prop_assert!(params.validate().is_ok()),
                    Err(error) => check_message(&error.to_string()),
                }
            }
            Err(error) => check_message(&error.to_string()),
        }
    }

    #[test]
    fn stylize_descriptions(description in description(stylize_base())) {
        match serde_json::from_value::<StylizeJob>(description.clone()) {
            Ok(job) => {
                for textures in [false, true] {
                    if let Err(error) = job.params(textures) {
                        check_message(&error.to_string());
                    }
                }
            }
            Err(error) => check_message(&error.to_string()),
        }
        if let Ok(job) = serde_json::from_value::<PresynthJob>(description.clone())
            && let Err(error) = job.params()
        {
            check_message(&error.to_string());
        }
        let mut texture = description;
        texture["width"] = json!(64);
        texture["height"] = json!(64);
        if let Ok(job) = serde_json::from_value::<TextureJob>(texture)
            && let Err(error) = job.params()
        {
            check_message(&error.to_string());
        }
    }
}

proptest! {
    #![proptest_config(config(128))]

    /// Curve jobs run to the end on a small exemplar and an arc: an `Ok` or a clean error.
    #[test]
    fn curve_jobs_run_or_refuse(
        width in prop_oneof![1 => Just(1e-300), 1 => Just(0.4), 8 => 10.0..40.0f64, 1 => Just(1e6)],
        piece_length in prop_oneof![1 => Just(1e-300), 1 => Just(0.3), 8 => 4.0..30.0f64, 1 => Just(1e6)],
        extra in description_with(curve_base(), 3),
    ) {
        let mut description = extra;
        description["width"] = json!(width);
        description["piece-length"] = json!(piece_length);
        // Runs stay small: a canvas of at most 256² and a modest memory limit.
        if description.get("canvas").is_some_and(|canvas| !canvas.is_null()) {
            description["canvas"] = json!([256, 256]);
        }
        description["max-memory"] = json!("64M");
        let Ok(job) = serde_json::from_value::<CurveJob>(description) else { return Ok(()) };
        let (exemplar, curve) = curve_exemplar_and_line();
        let inputs = CurveInputs::new(&exemplar, &curve);
        if let Err(error) = job.run(inputs, &mut NoProgress) {
            check_message(&error.to_string());
        }
    }
}
