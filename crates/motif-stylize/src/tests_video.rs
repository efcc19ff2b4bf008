//! Tests of video stylization (`video`).

use crate::InputError;
use crate::tests::texture;
use crate::video::*;
use crate::{Error, Params};
use motif_core::FloatImage;
use motif_core::NoProgress;

#[test]
fn intervals_run_from_key_to_key_and_out_to_both_ends() {
    let ends = |list: Vec<Interval>| -> Vec<(usize, usize, bool, bool)> {
        list.into_iter().map(|i| (i.first, i.last, i.starts_at_key, i.ends_at_key)).collect()
    };
    assert_eq!(ends(intervals(10, &[0])), vec![(0, 9, true, false)]);
    assert_eq!(ends(intervals(10, &[3, 9])), vec![(0, 3, false, true), (3, 9, true, true)]);
    assert_eq!(ends(intervals(10, &[0, 4, 6])), vec![(0, 4, true, true), (4, 6, true, true), (6, 9, true, false)]);
    assert_eq!(ends(intervals(1, &[0])), vec![(0, 0, true, false)]);
}

#[test]
fn a_static_sequence_keeps_the_keyframes_stylization_in_every_frame() {
    let frame = texture(56, 44, 3, 8);
    let style = texture(56, 44, 3, 9);
    let input =
        VideoInput { frames: vec![frame; 5], keys: vec![Keyframe { frame: 2, style: style.clone() }], mask: None };
    let output =
        stylize_video(&input, &Params::default().with_seed(4), &VideoParams::default(), &mut NoProgress).unwrap();
    assert_eq!(output.frames.len(), 5);
    assert_eq!(output.frames[2], style);
    for (index, frame) in output.frames.iter().enumerate() {
        let difference = frame.data().iter().zip(style.data()).map(|(a, b)| (a - b).abs()).fold(0.0, f32::max);
        assert!(difference < 1.5 / 255.0, "frame {index} differs from the keyframe's style by {difference}");
    }
    assert!(output.report.flicker < 1e-3, "flicker {}", output.report.flicker);
    assert_eq!(output.report.intervals.len(), 2);
}

#[test]
fn bad_sequences_are_refused_with_the_frame_named() {
    let frame = texture(24, 20, 3, 1);
    let params = Params::default();
    let video = VideoParams::default();
    let run = |frames: Vec<FloatImage>, keys: Vec<Keyframe>| {
        stylize_video(&VideoInput { frames, keys, mask: None }, &params, &video, &mut NoProgress).unwrap_err()
    };
    let key = |frame: usize| Keyframe { frame, style: frame_like(&frame_of(24, 20)) };
    assert_eq!(run(vec![], vec![key(0)]), Error::Input(InputError::NoFrames));
    assert_eq!(run(vec![frame.clone(); 3], vec![]), Error::Input(InputError::NoKeyframes));
    assert_eq!(
        run(vec![frame.clone(); 3], vec![key(3)]),
        Error::Input(InputError::KeyframeOutOfRange { frame: 3, frames: 3 })
    );
    assert_eq!(
        run(vec![frame.clone(); 3], vec![key(2), key(1)]),
        Error::Input(InputError::KeyframeOrder { frame: 1, previous: 2 })
    );
    let message = run(vec![frame.clone(), texture(20, 20, 3, 1)], vec![key(0)]).to_string();
    assert!(message.contains("frame 1") && message.contains("20×20×3"), "{message}");
    let small = Keyframe { frame: 0, style: texture(12, 20, 3, 1) };
    let message = run(vec![frame.clone(); 2], vec![small]).to_string();
    assert!(message.contains("keyframe 0") && message.contains("12×20"), "{message}");
    let all = VideoInput { frames: vec![frame; 2], keys: vec![key(0)], mask: Some(vec![true; 24 * 20]) };
    assert_eq!(all.validate(&params).unwrap_err(), Error::Input(InputError::MaskCoverage("every pixel")));
}

fn frame_of(width: usize, height: usize) -> FloatImage {
    texture(width, height, 3, 2)
}

fn frame_like(image: &FloatImage) -> FloatImage {
    image.clone()
}
