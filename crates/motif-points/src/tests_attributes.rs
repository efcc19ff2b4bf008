//! Attributes of any unit and range: normalization, per-attribute weights, detected labels, and
//! columns that cannot be used.

use motif_core::NoProgress;

use crate::InputError;
use crate::error::Error;
use crate::params::{Domain, Initialization, Input, Params};
use crate::samples::{hex_exemplar, ripple_exemplar};
use crate::{PointSet, synthesize};

fn domain() -> Domain {
    Domain::Box { min: vec![0.0; 2], max: vec![8.0, 7.0] }
}

fn params() -> Params {
    Params { neighbourhood: Some(1.5), shrink: Some(0.8), merge_iterations: 10, seed: 3, ..Params::default() }
}

fn with_attribute(mut set: PointSet, values: impl Fn(usize, f64) -> f64) -> PointSet {
    for (i, value) in set.attributes.iter_mut().enumerate() {
        *value = values(i, *value);
    }
    set
}

#[test]
fn an_attribute_in_other_units_gives_the_same_positions() {
    let exemplar = ripple_exemplar(225, 4);
    // The same heights in thousandths and shifted: every attribute is divided by its standard
    // deviation after its mean is taken off, so the synthesis sees the same features.
    let scaled = with_attribute(exemplar.clone(), |_, v| 1000.0 * v + 5000.0);
    for initialization in [Initialization::Patches, Initialization::Random] {
        let params = Params { initialization, ..params() };
        let a = synthesize(
            &Input { exemplar: exemplar.clone(), domain: domain(), existing: None },
            &params,
            &mut NoProgress,
        )
        .unwrap();
        let b =
            synthesize(&Input { exemplar: scaled.clone(), domain: domain(), existing: None }, &params, &mut NoProgress)
                .unwrap();
        assert_eq!(a.points.len(), b.points.len(), "{initialization:?}");
        let largest =
            a.points.positions.iter().zip(&b.points.positions).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
        assert!(largest < 1e-6, "{initialization:?}: positions differ by {largest}");
        for (x, y) in a.points.attributes.iter().zip(&b.points.attributes) {
            assert!((1000.0 * x + 5000.0 - y).abs() < 1e-6 * y.abs().max(1.0), "{x} vs {y}");
        }
    }
}

#[test]
fn whole_number_labels_are_detected_and_kept() {
    // Labels 0, 3 and 7 by row, as floats: detected as discrete, so the output holds no shade in
    // between. With detection off (or the column named continuous) in-between values appear.
    let labels = [0.0, 3.0, 7.0];
    let exemplar = with_attribute(hex_exemplar(14, 14, 0.1, 2), |i, _| labels[(i / 14) % 3]);
    let output =
        synthesize(&Input { exemplar: exemplar.clone(), domain: domain(), existing: None }, &params(), &mut NoProgress)
            .unwrap();
    assert_eq!(output.report.discrete_attributes, vec!["shade".to_string()]);
    assert!(output.points.attributes.iter().all(|v| labels.contains(v)), "{:?}", output.points.attributes);
    let continuous = Params { continuous_attributes: vec!["shade".into()], ..params() };
    let output =
        synthesize(&Input { exemplar, domain: domain(), existing: None }, &continuous, &mut NoProgress).unwrap();
    assert!(output.report.discrete_attributes.is_empty());
    assert!(output.points.attributes.iter().any(|v| !labels.contains(v)));
}

/// The exemplar with one more attribute column, `name`, of `value` at every point.
fn with_constant_column(set: &PointSet, name: &str, value: f64) -> PointSet {
    let width = set.attribute_names.len();
    let mut attributes = Vec::with_capacity(set.len() * (width + 1));
    for i in 0..set.len() {
        attributes.extend_from_slice(set.attributes_of(i));
        attributes.push(value);
    }
    let mut attribute_names = set.attribute_names.clone();
    attribute_names.push(name.to_string());
    PointSet { attribute_names, attributes, ..set.clone() }
}

#[test]
fn a_constant_attribute_is_kept_and_changes_nothing_else() {
    // A sheet's normals have a zero component everywhere; such a column carries no structure, so
    // it must neither be refused nor move a point, and it comes back exactly.
    let exemplar = ripple_exemplar(225, 4);
    for value in [0.0, 2.5] {
        let with_constant = with_constant_column(&exemplar, "nz", value);
        for initialization in [Initialization::Patches, Initialization::Random] {
            let params = Params { initialization, ..params() };
            let run = |set: &PointSet| {
                synthesize(&Input { exemplar: set.clone(), domain: domain(), existing: None }, &params, &mut NoProgress)
                    .unwrap()
                    .points
            };
            let (plain, constant) = (run(&exemplar), run(&with_constant));
            assert_eq!(plain.positions, constant.positions, "{initialization:?}, value {value}");
            assert_eq!(constant.attribute_names.last().map(String::as_str), Some("nz"));
            for i in 0..constant.len() {
                let row = constant.attributes_of(i);
                assert_eq!(row[row.len() - 1], value, "point {i}");
                assert_eq!(&row[..row.len() - 1], plain.attributes_of(i), "point {i}");
            }
        }
    }
}

#[test]
fn unusable_attribute_columns_are_clear_errors() {
    let missing = with_attribute(hex_exemplar(8, 8, 0.1, 1), |i, v| if i == 5 { f64::NAN } else { v });
    let message =
        match synthesize(&Input { exemplar: missing, domain: domain(), existing: None }, &params(), &mut NoProgress) {
            Err(
                error @ (Error::Input(InputError::PointSet { .. }) | Error::Input(InputError::UnknownAttribute { .. })),
            ) => error.to_string(),
            other => panic!("{other:?}"),
        };
    assert!(message.contains("\"shade\"") && message.contains("point 5"), "{message}");
    let weights = Params { attribute_weights: vec![("size".into(), 2.0)], ..params() };
    let exemplar = hex_exemplar(8, 8, 0.1, 1);
    let message = match synthesize(&Input { exemplar, domain: domain(), existing: None }, &weights, &mut NoProgress) {
        Err(
            error @ (Error::Input(InputError::PointSet { .. }) | Error::Input(InputError::UnknownAttribute { .. })),
        ) => error.to_string(),
        other => panic!("{other:?}"),
    };
    assert!(message.contains("\"size\""), "{message}");
}
