//! `motif bench --engine stylize --case video`: video stylization on footage filmed over a real
//! photo (a pan and zoom over scikit-image's `chelsea.png`, so the true motion is known), with a
//! keyframe painted over the first frame (`samples::painted_keyframe`, GIMP's burlap as canvas).
//!
//! Figures per method: seconds per frame; flicker, the mean absolute difference between
//! consecutive frames after compensating the true motion; and the error against the ideal, the
//! keyframe carried along the true motion (pixels the keyframe saw). Methods: the video
//! stylization (one keyframe; two keyframes, first and last), without its temporal guide, and
//! per-frame stylization (each frame stylized from the keyframe with its colours as the only
//! guide, what running `motif stylize` on every frame does).

use motif_core::{FloatImage, NoProgress};
use motif_stylize::samples::{self, CameraPath, Footage};
use motif_stylize::{Guide, Input, Keyframe, Params, VideoInput, VideoParams, flicker, stylize_video, synthesize};
use serde_json::{Map, Value, json};

use crate::suite::Bench;

/// The bench's footage and keyframe style (also the demo's).
pub fn footage(frames: usize, width: usize, height: usize) -> anyhow::Result<(Footage, FloatImage)> {
    let folder = crate::suite::corpus_folder("stylize");
    let photo = motif_jobs::stylize::style_image_channels(&motif_io::read_image(&folder.join("chelsea.png"))?);
    let canvas = motif_jobs::stylize::style_image_channels(&motif_io::read_image(&folder.join("burlap.png"))?);
    let path = CameraPath { start_centre: [160.0, 140.0], end_centre: [290.0, 165.0], start_zoom: 1.0, end_zoom: 1.3 };
    let footage = samples::pan_and_zoom(&photo, width, height, frames, path);
    let style = samples::painted_keyframe(&footage.frames[0], &canvas);
    Ok((footage, style))
}

/// Mean absolute difference to the first keyframe carried along the true motion, over the pixels
/// the keyframe saw, frames after the first (colour channels).
fn ideal_error(footage: &Footage, style: &FloatImage, frames: &[FloatImage]) -> f64 {
    let mut total = 0.0;
    let mut count = 0usize;
    for (index, frame) in frames.iter().enumerate().skip(1) {
        let (ideal, visible) = footage.carried(style, 0, index);
        for (pixel, seen) in visible.iter().enumerate() {
            if *seen {
                let (a, b) = (&ideal.data()[pixel * 3..pixel * 3 + 3], &frame.data()[pixel * 3..pixel * 3 + 3]);
                total += a.iter().zip(b).map(|(p, q)| f64::from((p - q).abs())).sum::<f64>() / 3.0;
                count += 1;
            }
        }
    }
    total / count.max(1) as f64
}

pub fn video(bench: &Bench) -> anyhow::Result<Value> {
    let (frame_count, width, height) = if bench.quick { (4, 96, 64) } else { (16, 192, 128) };
    let (footage, style) = footage(frame_count, width, height)?;
    let params = Params::default().with_seed(bench.seed);
    let mut figures = Map::new();
    let mut record = |name: &str, frames: &[FloatImage], seconds: f64, synthesized: usize, motion_ms: f64| {
        figures.insert(
            name.into(),
            json!({
                "seconds_per_frame": seconds / synthesized.max(1) as f64,
                "motion_seconds_per_frame": motion_ms / 1000.0 / synthesized.max(1) as f64,
                "flicker": flicker(frames, &footage.motion),
                "error_against_ideal": ideal_error(&footage, &style, frames),
            }),
        );
    };
    let variants: [(&str, VideoParams, bool); 3] = [
        ("video_one_keyframe", VideoParams::default(), false),
        ("video_two_keyframes", VideoParams::default(), true),
        ("video_without_temporal_guide", VideoParams::default().with_temporal_weight(0.0), false),
    ];
    for (name, video, two) in variants {
        let mut keys = vec![Keyframe { frame: 0, style: style.clone() }];
        if two {
            let last = frame_count - 1;
            let (ideal_last, _) = footage.carried(&style, 0, last);
            keys.push(Keyframe { frame: last, style: ideal_last });
        }
        let input = VideoInput { frames: footage.frames.clone(), keys, mask: None };
        let start = std::time::Instant::now();
        let output = stylize_video(&input, &params, &video, &mut NoProgress)?;
        let synthesized = output.report.intervals.iter().map(|r| r.synthesized_frames).sum();
        let motion_ms = output.report.intervals.iter().map(|r| r.motion_ms).sum();
        record(name, &output.frames, start.elapsed().as_secs_f64(), synthesized, motion_ms);
    }
    let start = std::time::Instant::now();
    let mut independent = vec![style.clone()];
    for (index, frame) in footage.frames.iter().enumerate().skip(1) {
        let guide = Guide { source: footage.frames[0].clone(), target: frame.clone(), weight: None };
        let frame_params = params.clone().with_seed(bench.seed.wrapping_add(index as u64));
        independent.push(synthesize(&Input::guided(style.clone(), vec![guide]), &frame_params, &mut NoProgress)?.image);
    }
    record("per_frame_stylization", &independent, start.elapsed().as_secs_f64(), frame_count - 1, 0.0);
    figures.insert(
        "footage".into(),
        json!({ "frames": frame_count, "size": [width, height], "photo": "chelsea.png (scikit-image, CC0)" }),
    );
    Ok(Value::Object(figures))
}
