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

use std::path::Path;

use motif_core::{FloatImage, NoProgress, RgbaImage};
use motif_stylize::samples::{self, CameraPath, Footage};
use motif_stylize::{Guide, Input, Keyframe, Params, VideoInput, VideoParams, flicker, stylize_video, synthesize};
use serde_json::{Map, Value, json};

use crate::gallery::{Demo, DemoCase};
use crate::suite::Bench;

/// The bench's and the demo's footage over the photo and their keyframe style, on the canvas.
fn footage(photo: &RgbaImage, canvas: &RgbaImage, frames: usize, width: usize, height: usize) -> (Footage, FloatImage) {
    let photo = motif_jobs::stylize::style_image_channels(photo).to_float();
    let canvas = motif_jobs::stylize::style_image_channels(canvas).to_float();
    let path = CameraPath { start_centre: [160.0, 140.0], end_centre: [290.0, 165.0], start_zoom: 1.0, end_zoom: 1.3 };
    let footage = samples::pan_and_zoom(&photo, width, height, frames, path);
    let style = samples::painted_keyframe(&footage.frames[0], &canvas);
    (footage, style)
}

/// The photo and canvas from `data/real/stylize`, built into the binary so the demo runs anywhere.
fn photo_and_canvas() -> anyhow::Result<(RgbaImage, RgbaImage)> {
    let photo = include_bytes!("../../../../../data/real/stylize/chelsea.png");
    let canvas = include_bytes!("../../../../../data/real/stylize/burlap.png");
    Ok((
        motif_io::decode_image(photo.to_vec(), Path::new("chelsea.png"))?,
        motif_io::decode_image(canvas.to_vec(), Path::new("burlap.png"))?,
    ))
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

pub(super) fn video(bench: &Bench) -> anyhow::Result<Value> {
    let (frame_count, width, height) = if bench.quick { (4, 96, 64) } else { (16, 192, 128) };
    let (photo, canvas) = photo_and_canvas()?;
    let (footage, style) = footage(&photo, &canvas, frame_count, width, height);
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
    let independent = per_frame(&footage, &style, &params)?;
    record("per_frame_stylization", &independent, start.elapsed().as_secs_f64(), frame_count - 1, 0.0);
    figures.insert(
        "footage".into(),
        json!({ "frames": frame_count, "size": [width, height], "photo": "chelsea.png (scikit-image, CC0)" }),
    );
    Ok(Value::Object(figures))
}

/// Each frame stylized on its own from the keyframe, with the frames' colours as the guide.
fn per_frame(footage: &Footage, style: &FloatImage, params: &Params) -> anyhow::Result<Vec<FloatImage>> {
    let mut out = vec![style.clone()];
    for (index, frame) in footage.frames.iter().enumerate().skip(1) {
        let guide = Guide { source: footage.frames[0].clone(), target: frame.clone(), weight: None };
        let frame_params = params.clone().with_seed(params.seed.wrapping_add(index as u64));
        out.push(synthesize(&Input::guided(style.clone(), vec![guide]), &frame_params, &mut NoProgress)?.image);
    }
    Ok(out)
}

/// `motif demo`'s video case: 16 frames over the photo, a keyframe painted over the first, the
/// command on them, and a strip (frames 0, 5, 10, 15: the footage, per-frame stylization, the
/// video) for the gallery.
pub(super) fn demo_case(demo: &mut Demo) -> anyhow::Result<()> {
    let (photo, canvas) = photo_and_canvas()?;
    let (footage, style) = footage(&photo, &canvas, 16, 192, 128);
    let (input_dir, output_dir) = (demo.path("video-in"), demo.path("video-out"));
    std::fs::create_dir_all(&input_dir)?;
    std::fs::create_dir_all(&output_dir)?;
    for (index, frame) in footage.frames.iter().enumerate() {
        motif_io::write_png(&input_dir.join(format!("{index:04}.png")), &RgbaImage::from_float(frame))?;
    }
    motif_io::write_png(&demo.path("video-key-0000.png"), &RgbaImage::from_float(&style))?;
    let (frames, out) = (input_dir.join("%04d.png"), output_dir.join("%04d.png"));
    let (frames, out) = (frames.to_string_lossy().into_owned(), out.to_string_lossy().into_owned());
    demo.case(DemoCase {
        title: "video: a keyframe carried through real footage".into(),
        description: "16 frames panning and zooming over a photo (scikit-image's cat, CC0); frame 0 painted \
                      over (flat colours, outlines, the weave of GIMP's burlap). motif video carries the paint \
                      along the motion with edge, positional and temporal guides; the strip compares it with \
                      stylizing every frame on its own (frames 0, 5, 10, 15)."
            .into(),
        inputs: vec![("keyframe 0".into(), "video-key-0000.png".into())],
        outputs: vec![("footage, per-frame, video".into(), "video-strip.png".into())],
        args: ["video", "--frames", &frames, "--key", "0:video-key-0000.png", "--out", &out].map(String::from).to_vec(),
    })?;
    let mut video = Vec::new();
    for index in 0..16 {
        video.push(motif_io::read_image(&output_dir.join(format!("{index:04}.png")))?.to_float_channels(&[0, 1, 2]));
    }
    let independent = per_frame(&footage, &style, &Params::default().with_seed(demo.seed()))?;
    let rows = [&footage.frames, &independent, &video];
    let (width, height, gap) = (192, 128, 4);
    let strip = RgbaImage::from_fn(4 * width + 3 * gap, 3 * height + 2 * gap, |x, y| {
        let (column, row) = (x / (width + gap), y / (height + gap));
        let (inner_x, inner_y) = (x % (width + gap), y % (height + gap));
        if inner_x >= width || inner_y >= height {
            return [255, 255, 255, 255];
        }
        let pixel = rows[row][column * 5].pixel(inner_x, inner_y);
        let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        [byte(pixel[0]), byte(pixel[1]), byte(pixel[2]), 255]
    });
    motif_io::write_png(&demo.path("video-strip.png"), &strip)?;
    Ok(())
}
