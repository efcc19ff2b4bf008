use super::*;

#[test]
fn painted_maps_become_rotation_and_scale_fields() {
    // Left half black, right half white (rotation), left black right mid-grey (scale).
    let rotation = ToneMap::from_grey(4, 2, vec![0.0, 0.0, 0.25, 0.25, 0.0, 0.0, 0.25, 0.25]).unwrap();
    let scale = ToneMap::from_grey(4, 2, vec![0.0, 0.0, 0.5, 0.5, 0.0, 0.0, 0.5, 0.5]).unwrap();
    let mut job = PointsJob::new(2.0, DomainSpec::Box(vec![40.0, 20.0]));
    job.options.rotation = 10.0;
    let mut params = job.params(2, &[]).unwrap();
    let maps = FieldMaps { rotation: Some(rotation), scale: Some(scale) };
    maps.apply(&job.engine_domain().unwrap(), 2, &mut params).unwrap();
    assert!((params.rotation.value(&[2.0, 5.0], 0.0) - 10.0).abs() < 1e-9);
    assert!((params.rotation.value(&[38.0, 5.0], 0.0) - 100.0).abs() < 1e-9);
    assert!((params.scale.value(&[2.0, 5.0], 1.0) - 0.5).abs() < 1e-9);
    assert!((params.scale.value(&[38.0, 5.0], 1.0) - 1.0).abs() < 1e-9);
    // Maps need a 2D domain of their aspect ratio.
    let square = FieldMaps { scale: Some(ToneMap::from_grey(3, 3, vec![0.5; 9]).unwrap()), rotation: None };
    let error = square.apply(&job.engine_domain().unwrap(), 2, &mut params).unwrap_err().to_string();
    assert!(error.contains("scale-map") && error.contains("aspect"), "{error}");
    let job3 = PointsJob::new(2.0, DomainSpec::Box(vec![4.0, 4.0, 4.0]));
    let error = maps.apply(&job3.engine_domain().unwrap(), 3, &mut params).unwrap_err().to_string();
    assert!(error.contains("2D"), "{error}");
}

#[test]
fn descriptions_use_the_flag_names_and_the_engine_defaults() {
    let job: PointsJob = serde_json::from_value(json!({
        "neighbourhood": 14,
        "domain": { "box": [400, 400] },
        "exemplar-window": [200, 200],
        "attribute-weight": { "dbh": 0.5 },
        "refine": "everywhere",
        "init": "random",
    }))
    .unwrap();
    let params = job.params(2, &["label".to_string()]).unwrap();
    assert_eq!(params.exemplar_window, Some((vec![0.0, 0.0], vec![200.0, 200.0])));
    assert_eq!(params.attribute_weights, vec![("dbh".to_string(), 0.5)]);
    assert_eq!(params.refinement, Refinement::Everywhere);
    assert_eq!(params.initialization, Initialization::Random);
    assert_eq!(params.discrete_attributes, vec!["label".to_string()]);
    assert_eq!(params.seed, 1);
    let defaults = Params::default();
    assert_eq!(params.patch_size, defaults.patch_size);
    assert_eq!(params.merge_iterations, defaults.merge_iterations);
    // Corners instead of sizes, and a round trip through JSON.
    let mut corners = job.clone();
    corners.options.exemplar_window = Some(vec![1.0, 2.0, 5.0, 6.0]);
    let params = corners.params(2, &[]).unwrap();
    assert_eq!(params.exemplar_window, Some((vec![1.0, 2.0], vec![5.0, 6.0])));
    let text = serde_json::to_string(&corners).unwrap();
    assert_eq!(serde_json::from_str::<PointsJob>(&text).unwrap(), corners);
    // max-memory as bytes or as a size people write; a round trip keeps it.
    let sized = |value: Value| {
        let mut description = json!({ "neighbourhood": 14, "domain": { "box": [400, 400] } });
        description["max-memory"] = value;
        serde_json::from_value::<PointsJob>(description)
    };
    assert_eq!(sized(json!("1.5G")).unwrap().params(2, &[]).unwrap().max_memory, 3 << 29);
    let bytes = sized(json!(1 << 24)).unwrap();
    assert_eq!(bytes.max_memory, Some(1 << 24));
    let text = serde_json::to_string(&bytes).unwrap();
    assert_eq!(serde_json::from_str::<PointsJob>(&text).unwrap(), bytes);
    assert!(sized(json!("8 parsecs")).unwrap_err().to_string().contains("not a size"));
    let tiny = sized(json!(1000)).unwrap().params(2, &[]).unwrap_err().to_string();
    assert!(tiny.contains("max-memory"), "{tiny}");
}

#[test]
fn bad_descriptions_name_the_option() {
    let bad = |value: Value| serde_json::from_value::<PointsJob>(value).unwrap_err().to_string();
    assert!(bad(json!({ "neighbourhood": 1, "domain": { "box": [4, 4] }, "patchsize": 3 })).contains("patchsize"));
    assert!(bad(json!({ "neighbourhood": 1 })).contains("domain"));
    let inferred: PointsJob = serde_json::from_value(json!({ "domain": { "box": [4, 4] } })).unwrap();
    assert_eq!(inferred.params(2, &[]).unwrap().neighbourhood, None);
    assert!(bad(json!({ "neighbourhood": 1, "domain": { "box": [4, 4] }, "refine": "most" })).contains("most"));
    let job = PointsJob::new(1.0, DomainSpec::Box(vec![4.0]));
    assert!(job.engine_domain().unwrap_err().to_string().contains("domain"));
    let mut job = PointsJob::new(1.0, DomainSpec::Box(vec![4.0, 4.0]));
    job.options.exemplar_window = Some(vec![1.0, 2.0, 3.0]);
    assert!(job.params(2, &[]).unwrap_err().to_string().contains("exemplar-window"));
    let mut job = PointsJob::new(1.0, DomainSpec::Box(vec![4.0, 4.0]));
    job.options.patch_size = 0.0;
    assert!(job.params(2, &[]).unwrap_err().to_string().contains("patch-size"));
}
