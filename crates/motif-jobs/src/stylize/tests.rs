//! The stylize-family jobs described with the flag names, and their errors.

use motif_core::NoProgress;
use motif_stylize::samples::{crayon_style, map_guide};

use serde_json::json;

use super::*;

#[test]
fn described_jobs_run_with_the_flag_names() {
    let job: StylizeJob = serde_json::from_value(json!({
        "search-vote-iters": 2,
        "patch-size": 7,
        "segment-count": 3,
        "segment-guide": 1,
        "nnf": "patchmatch",
        "extra-pass-3x3": true,
        "seed": 4,
    }))
    .unwrap();
    let params = job.params(false).unwrap();
    assert_eq!(params.search_vote_iterations, 2);
    assert_eq!(params.patch_size, 7);
    assert_eq!(params.segments, Some(Segmentation::KMeans(3)));
    assert_eq!(params.segment_guide, 0);
    assert!(params.extra_pass_3x3);
    assert_eq!(params.uniformity, Params::default().uniformity);
    let source = map_guide(48, 40, 3, 1);
    let style = crayon_style(&source, 2);
    let target = map_guide(56, 44, 3, 3);
    let run = job.run_on(StylizeInputs::new(style.clone(), vec![(source, target)]), &mut NoProgress).unwrap();
    assert_eq!(run.figures["output_size"], json!([56, 44]));
    let texture: TextureJob = serde_json::from_value(json!({ "size": [40, 30], "tileable": true })).unwrap();
    let run = texture.run_on(TextureInputs { exemplar: style, mask: None }, &mut NoProgress).unwrap();
    assert_eq!((run.output.image.width(), run.output.image.height()), (40, 30));
}

#[test]
fn bad_descriptions_name_what_is_wrong() {
    let error = serde_json::from_value::<StylizeJob>(json!({ "patchsize": 5 })).unwrap_err();
    assert!(error.to_string().contains("patchsize"), "{error}");
    let error = serde_json::from_value::<TextureJob>(json!({ "tileable": true })).unwrap_err();
    assert!(error.to_string().contains("size"), "{error}");
    let job: StylizeJob = serde_json::from_value(json!({ "segment-guide": 0 })).unwrap();
    assert!(job.params(false).unwrap_err().to_string().contains("segment-guide"));
    let job: StylizeJob = serde_json::from_value(json!({ "patch-size": 4 })).unwrap();
    assert!(job.params(false).unwrap_err().to_string().contains("patch"));
    let job: StylizeJob = serde_json::from_value(json!({ "weight": [0.5, 0.5] })).unwrap();
    let source = map_guide(32, 32, 2, 1);
    let style = crayon_style(&source, 2);
    let error = job.run_on(StylizeInputs::new(style, vec![(source.clone(), source)]), &mut NoProgress).unwrap_err();
    assert!(error.to_string().contains("weight"), "{error}");
}
