//! `motif video` end to end: footage filmed over a real photo (scikit-image's cat, CC0,
//! data/real/stylize) with a keyframe painted over a frame, a static sequence, intervals run
//! apart, and bad input.

mod common;

use std::path::{Path, PathBuf};

use common::{error_of, motif, ok};
use motif_core::{FloatImage, RgbaImage};
use motif_stylize::samples::{CameraPath, Footage, painted_keyframe, pan_and_zoom};

fn corpus(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/stylize").join(name)
}

fn colour(image: &RgbaImage) -> FloatImage {
    image.to_float_channels(&[0, 1, 2])
}

/// Seven 96 × 64 frames panning and zooming over the photo, written as `in/0000.png` …, and a
/// keyframe painted over frame `key` as `key.png`.
fn footage(dir: &Path, key: usize) -> (Footage, FloatImage) {
    let photo = colour(&motif_io::read_image(&corpus("chelsea.png")).unwrap());
    let canvas = colour(&motif_io::read_image(&corpus("burlap.png")).unwrap());
    let path = CameraPath { start_centre: [170.0, 140.0], end_centre: [215.0, 150.0], start_zoom: 1.0, end_zoom: 1.12 };
    let footage = pan_and_zoom(&photo, 96, 64, 7, path);
    std::fs::create_dir_all(dir.join("in")).unwrap();
    std::fs::create_dir_all(dir.join("out")).unwrap();
    for (index, frame) in footage.frames.iter().enumerate() {
        motif_io::write_png(&dir.join(format!("in/{index:04}.png")), &RgbaImage::from_float(frame)).unwrap();
    }
    let style = painted_keyframe(&footage.frames[key], &canvas);
    motif_io::write_png(&dir.join("key.png"), &RgbaImage::from_float(&style)).unwrap();
    (footage, style)
}

fn read_frames(dir: &Path, folder: &str, count: usize) -> Vec<FloatImage> {
    (0..count).map(|i| colour(&motif_io::read_image(&dir.join(format!("{folder}/{i:04}.png"))).unwrap())).collect()
}

#[test]
fn keyframes_carried_through_real_footage_flicker_less_than_frames_stylized_apart() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (footage, _) = footage(d, 0);
    ok(&motif(
        d,
        &["video", "--frames", "in/%04d.png", "--key", "0:key.png", "--out", "out/%04d.png", "--report", "r.json"],
    ));
    // Frames stylized independently: no positional and no temporal guide.
    std::fs::create_dir_all(d.join("apart")).unwrap();
    ok(&motif(
        d,
        &[
            "video",
            "--frames",
            "in/%04d.png",
            "--key",
            "0:key.png",
            "--out",
            "apart/%04d.png",
            "--position-weight",
            "0",
            "--temporal-weight",
            "0",
        ],
    ));
    // The same seed gives the same bytes on one thread.
    std::fs::create_dir_all(d.join("one")).unwrap();
    ok(&motif(
        d,
        &["--threads", "1", "video", "--frames", "in/%04d.png", "--key", "0:key.png", "--out", "one/%04d.png"],
    ));
    for index in 0..7 {
        let name = format!("{index:04}.png");
        assert_eq!(
            std::fs::read(d.join("one").join(&name)).unwrap(),
            std::fs::read(d.join("out").join(&name)).unwrap()
        );
    }
    let video = read_frames(d, "out", 7);
    let apart = read_frames(d, "apart", 7);
    // The keyframe's own output is the keyframe.
    assert_eq!(
        motif_io::read_image(&d.join("out/0000.png")).unwrap(),
        motif_io::read_image(&d.join("key.png")).unwrap()
    );
    // Flicker measured with the footage's exact motion.
    let (coherent, independent) =
        (motif_stylize::flicker(&video, &footage.motion), motif_stylize::flicker(&apart, &footage.motion));
    assert!(coherent < 0.8 * independent, "flicker {coherent:.4} against {independent:.4} frame by frame");
    let report: serde_json::Value = motif_io::read_json(&d.join("r.json")).unwrap();
    assert_eq!(report["frames"], 7);
    assert_eq!(report["synthesized_frames"], 6);
    assert!(report["flicker"].as_f64().unwrap() > 0.0 && report["seconds_per_frame"].as_f64().unwrap() > 0.0);
}

#[test]
fn a_static_sequence_gives_the_keyframe_in_every_frame_and_intervals_run_apart_agree() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (footage, style) = footage(d, 3);
    // Static: frame 3 five times over.
    std::fs::create_dir_all(d.join("still")).unwrap();
    std::fs::create_dir_all(d.join("still-out")).unwrap();
    for index in 0..5 {
        motif_io::write_png(&d.join(format!("still/{index}.png")), &RgbaImage::from_float(&footage.frames[3])).unwrap();
    }
    ok(&motif(d, &["video", "--frames", "still/%d.png", "--key", "3:key.png", "--out", "still-out/%d.png"]));
    let key = motif_io::read_image(&d.join("key.png")).unwrap();
    for index in 0..5 {
        let frame = motif_io::read_image(&d.join(format!("still-out/{index}.png"))).unwrap();
        let largest = frame.as_bytes().iter().zip(key.as_bytes()).map(|(a, b)| a.abs_diff(*b)).max().unwrap();
        assert!(largest <= 2, "frame {index} differs from the keyframe by {largest} levels");
    }
    // Two keyframes (3 and 6) make three intervals; the middle one run on its own gives the
    // bytes of the whole run.
    motif_io::write_png(&d.join("key6.png"), &RgbaImage::from_float(&footage.carried(&style, 3, 6).0)).unwrap();
    std::fs::create_dir_all(d.join("part")).unwrap();
    let keys = ["--key", "3:key.png", "--key", "6:key6.png"];
    let mut whole = vec!["video", "--frames", "in/%04d.png", "--out", "out/%04d.png"];
    whole.extend(keys);
    ok(&motif(d, &whole));
    let mut part = vec!["video", "--frames", "in/%04d.png", "--out", "part/%04d.png", "--interval", "2"];
    part.extend(keys);
    ok(&motif(d, &part));
    for index in 3..=6 {
        let name = format!("{index:04}.png");
        assert_eq!(
            std::fs::read(d.join("part").join(&name)).unwrap(),
            std::fs::read(d.join("out").join(&name)).unwrap(),
            "frame {index}"
        );
    }
    assert!(!d.join("part/0000.png").exists() && !d.join("part/0002.png").exists());
}

#[test]
fn bad_sequences_and_keyframes_are_refused_with_the_file_or_flag_named() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    footage(d, 0);
    let run = |extra: &[&str]| {
        let mut args = vec!["video"];
        args.extend(extra);
        error_of(&motif(d, &args))
    };
    let base = |frames: &'static str, key: &'static str, out: &'static str| {
        vec!["--frames", frames, "--key", key, "--out", out]
    };
    let message = run(&base("in/frame.png", "0:key.png", "out/%04d.png"));
    assert!(message.contains("--frames") && message.contains("%0Nd"), "{message}");
    let message = run(&base("in/x%04d.png", "0:key.png", "out/%04d.png"));
    assert!(message.contains("no file") && message.contains("x0001.png"), "{message}");
    let message = run(&base("in/%04d.png", "9:key.png", "out/%04d.png"));
    assert!(
        message.contains("--key 9:key.png") && message.contains("no frame 9") && message.contains("0–6"),
        "{message}"
    );
    let message = run(&base("in/%04d.png", "key.png", "out/%04d.png"));
    assert!(message.contains("--key key.png"), "{message}");
    let message = run(&base("in/%04d.png", "0:key.png", "in/%04d.png"));
    assert!(message.contains("also an input"), "{message}");
    let message = run(&base("in/%04d.png", "0:key.png", "missing/%04d.png"));
    assert!(message.contains("missing") && message.contains("does not exist"), "{message}");
    // A gap in the numbering was taken as consecutive frames without a word.
    std::fs::copy(d.join("in/0006.png"), d.join("in/0050.png")).unwrap();
    let message = run(&base("in/%04d.png", "0:key.png", "out/%04d.png"));
    assert!(message.contains("--frames") && message.contains("jump from 6 to 50"), "{message}");
    std::fs::remove_file(d.join("in/0050.png")).unwrap();
    motif_io::write_png(&d.join("small.png"), &RgbaImage::new(40, 30)).unwrap();
    let message = run(&base("in/%04d.png", "0:small.png", "out/%04d.png"));
    assert!(message.contains("small.png") && message.contains("40×30") && message.contains("96×64"), "{message}");
    let mut masked = base("in/%04d.png", "0:key.png", "out/%04d.png");
    masked.extend(["--mask", "small.png"]);
    let message = run(&masked);
    assert!(message.contains("mask small.png") && message.contains("40×30"), "{message}");
    let mut black = RgbaImage::new(96, 64);
    black.pixels_mut().iter_mut().for_each(|p| *p = [0, 0, 0, 255]);
    motif_io::write_png(&d.join("black.png"), &black).unwrap();
    let mut masked = base("in/%04d.png", "0:key.png", "out/%04d.png");
    masked.extend(["--mask", "black.png"]);
    let message = run(&masked);
    assert!(message.contains("no pixel"), "{message}");
    let mut interval = base("in/%04d.png", "0:key.png", "out/%04d.png");
    interval.extend(["--interval", "3"]);
    let message = run(&interval);
    assert!(message.contains("--interval 3") && message.contains("1 intervals"), "{message}");
    let mut weight = base("in/%04d.png", "0:key.png", "out/%04d.png");
    weight.extend(["--temporal-weight", "-1"]);
    let message = run(&weight);
    assert!(message.contains("temporal-weight"), "{message}");
    // Nothing was written by any failed run.
    assert_eq!(std::fs::read_dir(d.join("out")).unwrap().count(), 0);
}

#[test]
fn a_mask_keeps_every_frame_outside_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    footage(d, 0);
    // Synthesize the left half only.
    let mut mask = RgbaImage::new(96, 64);
    for (i, pixel) in mask.pixels_mut().iter_mut().enumerate() {
        *pixel = if i % 96 < 48 { [255, 255, 255, 255] } else { [0, 0, 0, 255] };
    }
    motif_io::write_png(&d.join("mask.png"), &mask).unwrap();
    ok(&motif(
        d,
        &["video", "--frames", "in/%04d.png", "--key", "0:key.png", "--out", "out/%04d.png", "--mask", "mask.png"],
    ));
    let key = motif_io::read_image(&d.join("key.png")).unwrap();
    for index in 0..7 {
        let name = format!("{index:04}.png");
        let (frame, out) = (
            motif_io::read_image(&d.join("in").join(&name)).unwrap(),
            motif_io::read_image(&d.join("out").join(&name)).unwrap(),
        );
        for (i, (kept, made)) in frame.pixels().iter().zip(out.pixels()).enumerate() {
            if i % 96 >= 48 {
                assert_eq!(kept, made, "frame {index}, pixel {i} outside the mask");
            }
        }
        // In the keyframe's own frame, the hole is the keyframe's style.
        let inside = |image: &RgbaImage| -> f64 {
            image.pixels().iter().enumerate().filter(|(i, _)| i % 96 < 48).map(|(_, p)| f64::from(p[0])).sum::<f64>()
        };
        if index == 0 {
            assert!((inside(&out) - inside(&key)).abs() < 1.0, "frame 0's hole is not the keyframe's style");
        }
    }
}
