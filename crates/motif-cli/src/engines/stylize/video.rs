//! `motif video`: a frame sequence stylized from keyframes, interval by interval (only one
//! interval's frames are in memory at a time).

use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use clap::Args;
use motif_core::{FloatImage, RgbaImage};
use motif_io::FramePattern;
use motif_jobs::stylize::{IntervalReport, mean_flicker};
use motif_jobs::stylize::{VideoJob, VideoJobOptions, hole_of, video_frame, video_styles};
use serde_json::json;

use super::load;
use crate::context::Context;
use crate::job_args::JobArgs;

/// Options of `motif video`.
#[derive(Args, Debug)]
pub struct VideoArgs {
    /// The frames: a pattern with %d or %0Nd for the frame number, e.g. 'in/%04d.png'. Every
    /// file of that folder that matches is a frame, in order of its number.
    #[arg(long, value_name = "PATTERN")]
    pub frames: String,
    /// A keyframe: a frame number and the image of that frame as the artist stylized it (the
    /// frames' size). Repeat for several keyframes; frames between two keyframes blend both.
    #[arg(long = "key", value_name = "N:STYLE.png", required = true, action = clap::ArgAction::Append)]
    pub keys: Vec<String>,
    /// Synthesize only where this image (the frames' size) is white, at least half white and
    /// half opaque, and keep the frames' own pixels elsewhere.
    #[arg(long, value_name = "MASK.png")]
    pub mask: Option<PathBuf>,
    /// Run only this keyframe interval, counted from 1 (the report lists them): intervals are
    /// independent, so several machines can share a video and give the same frames.
    #[arg(long, value_name = "I")]
    pub interval: Option<usize>,
    /// Every option of the synthesis, declared in `motif_jobs::stylize` (`SynthesisOptions`,
    /// `VideoOptions`).
    #[command(flatten)]
    pub options: JobArgs<VideoJobOptions>,
    /// The stylized frames: a pattern like --frames, in an existing folder; each output frame
    /// has its input frame's number.
    #[arg(long, value_name = "PATTERN")]
    pub out: String,
}

/// A frame read as the engine takes it (colour channels) within `max_memory`, with its size checked.
fn read_frame(path: &Path, size: Option<(usize, usize)>, max_memory: u64) -> anyhow::Result<FloatImage> {
    let image = load(path, max_memory)?;
    if let Some((width, height)) = size
        && (image.width(), image.height()) != (width, height)
    {
        bail!("frame {} is {}×{} but the frames are {width}×{height}", path.display(), image.width(), image.height());
    }
    Ok(video_frame(&image))
}

/// Runs `motif video`.
pub(crate) fn run_video(args: &VideoArgs, context: &mut Context) -> anyhow::Result<()> {
    let pattern = FramePattern::parse(&args.frames).context("--frames")?;
    let out = FramePattern::parse(&args.out).context("--out")?;
    let frames = pattern.find_consecutive().context("--frames")?;
    let numbers: Vec<u64> = frames.iter().map(|(number, _)| *number).collect();
    let keys = parse_keys(args, &numbers)?;
    let mut inputs: Vec<&Path> = frames.iter().map(|(_, path)| path.as_path()).collect();
    inputs.extend(keys.iter().map(|(_, path)| path.as_path()));
    inputs.extend(args.mask.as_deref());
    let intervals = VideoJob::intervals(frames.len(), &keys.iter().map(|(p, _)| *p).collect::<Vec<_>>());
    let chosen = chosen_intervals(args.interval, intervals.len())?;
    // A keyframe ends one interval and starts the next: each output is checked once.
    let mut positions: Vec<usize> = chosen.iter().flat_map(|&i| intervals[i].first..=intervals[i].last).collect();
    positions.dedup();
    for position in positions {
        context.check_output(&out.path(numbers[position]), &inputs)?;
    }

    let first = read_frame(&frames[0].1, None, context.max_memory)?;
    let size = (first.width(), first.height());
    let styles = video_styles(&read_keyframes(&keys, size, context.max_memory)?);
    let mask = read_mask(args.mask.as_deref(), size, context.max_memory)?;

    let job =
        VideoJob { seed: context.seed, max_memory: Some(context.max_memory), options: args.options.options.clone() };
    job.params()?;
    // The whole run, checked before the first frame is stylized.
    let channels = first.channels().max(styles.first().map_or(3, FloatImage::channels));
    let lengths = chosen.iter().map(|&i| intervals[i].last - intervals[i].first + 1);
    let estimate = job.check_memory(&VideoJob::memory(lengths, size, channels, styles.len(), mask.is_some()))?;
    context.figure("estimated_memory_bytes", estimate);
    let style_at = |position: usize| keys.iter().position(|(p, _)| *p == position).map(|k| &styles[k]);
    let mut reports = Vec::new();
    let mut written: Vec<usize> = Vec::new();
    let count = chosen.len();
    for (done, &i) in chosen.iter().enumerate() {
        let interval = intervals[i];
        let mut interval_frames = Vec::with_capacity(interval.last - interval.first + 1);
        for (_, path) in &frames[interval.first..=interval.last] {
            interval_frames.push(read_frame(path, Some(size), context.max_memory)?);
        }
        let (first_number, last_number) = (numbers[interval.first], numbers[interval.last]);
        let progress = context.progress();
        let mut report = |stage: &str, fraction: f64| {
            progress.report(
                &format!("interval {} of {count} (frames {first_number}–{last_number}): {stage}", done + 1),
                fraction,
            )
        };
        let output = job
            .run_interval(
                &interval_frames,
                interval,
                style_at(interval.first),
                style_at(interval.last),
                mask.as_deref(),
                &mut report,
            )
            .with_context(|| format!("cannot stylize frames {first_number}–{last_number} of {}", args.frames))?;
        for (offset, image) in output.frames.iter().enumerate() {
            let position = interval.first + offset;
            if written.last().is_some_and(|&last| last >= position) {
                continue;
            }
            motif_io::write_png(&out.path(numbers[position]), &RgbaImage::from_float(image))?;
            written.push(position);
        }
        reports.push((i + 1, [first_number, last_number], output.report));
    }
    let keyframes: Vec<u64> = keys.iter().map(|(p, _)| numbers[*p]).collect();
    report_video(context, args, frames.len(), keyframes, reports);
    Ok(())
}

/// The `--key` arguments as (frame position, style file), in frame order; each names an existing
/// frame, at most once.
fn parse_keys(args: &VideoArgs, numbers: &[u64]) -> anyhow::Result<Vec<(usize, PathBuf)>> {
    let describe_range = || {
        format!("{} frames numbered {}–{} match {}", numbers.len(), numbers[0], numbers[numbers.len() - 1], args.frames)
    };
    let mut keys: Vec<(usize, PathBuf)> = Vec::new();
    for key in &args.keys {
        let (number, path) = key
            .split_once(':')
            .with_context(|| format!("--key {key}: give a frame number and a file, as 0:style.png"))?;
        let number: u64 =
            number.trim().parse().with_context(|| format!("--key {key}: {number:?} is not a frame number"))?;
        let position = numbers
            .binary_search(&number)
            .map_err(|_| anyhow::anyhow!("--key {key}: there is no frame {number} ({})", describe_range()))?;
        if keys.iter().any(|(p, _)| *p == position) {
            bail!("--key {key}: frame {number} has two keyframes; give one");
        }
        keys.push((position, PathBuf::from(path)));
    }
    keys.sort();
    Ok(keys)
}

/// The intervals to run (indices from 0): `--interval`, counted from 1, or all of them.
fn chosen_intervals(interval: Option<usize>, count: usize) -> anyhow::Result<Vec<usize>> {
    Ok(match interval {
        Some(i) if i == 0 || i > count => {
            bail!("--interval {i}: the keyframes make {count} intervals, counted from 1")
        }
        Some(i) => vec![i - 1],
        None => (0..count).collect(),
    })
}

/// The keyframes' style images, each of the frames' size.
fn read_keyframes(keys: &[(usize, PathBuf)], size: (usize, usize), max_memory: u64) -> anyhow::Result<Vec<RgbaImage>> {
    let mut styles: Vec<RgbaImage> = Vec::new();
    for (_, path) in keys {
        let style = load(path, max_memory)?;
        if (style.width(), style.height()) != size {
            bail!(
                "keyframe {} is {}×{} but the frames are {}×{}",
                path.display(),
                style.width(),
                style.height(),
                size.0,
                size.1
            );
        }
        styles.push(style);
    }
    Ok(styles)
}

/// `--mask` as the hole to synthesize, of the frames' size.
fn read_mask(path: Option<&Path>, size: (usize, usize), max_memory: u64) -> anyhow::Result<Option<Vec<bool>>> {
    let Some(path) = path else { return Ok(None) };
    let image = load(path, max_memory)?;
    if (image.width(), image.height()) != size {
        bail!(
            "the mask {} is {}×{} but the frames are {}×{}",
            path.display(),
            image.width(),
            image.height(),
            size.0,
            size.1
        );
    }
    Ok(Some(hole_of(&image)))
}

/// The run's figures (intervals, frames synthesized, time per frame, flicker) and summary line.
fn report_video(
    context: &mut Context,
    args: &VideoArgs,
    frame_count: usize,
    keyframes: Vec<u64>,
    reports: Vec<(usize, [u64; 2], IntervalReport)>,
) {
    let keyframe_count = keyframes.len();
    let figures: Vec<IntervalReport> = reports.iter().map(|(_, _, report)| report.clone()).collect();
    let synthesized: usize = figures.iter().map(|r| r.synthesized_frames).sum();
    let motion_ms: f64 = figures.iter().map(|r| r.motion_ms).sum();
    let synthesis_ms: f64 = figures.iter().map(|r| r.synthesis_ms).sum();
    let flicker = mean_flicker(&figures);
    let reports: Vec<_> = reports
        .into_iter()
        .map(|(interval, frames, figures)| json!({ "interval": interval, "frames": frames, "figures": figures }))
        .collect();
    let seconds_per_frame = (motion_ms + synthesis_ms) / 1000.0 / synthesized.max(1) as f64;
    context.figure("frames", frame_count);
    context.figure("keyframes", keyframes);
    context.figure("intervals", reports);
    context.figure("synthesized_frames", synthesized);
    context.figure("seconds_per_frame", seconds_per_frame);
    context.figure("flicker", flicker);
    context.summary(&format!(
        "motif video: {synthesized} frames synthesized from {} keyframes, {seconds_per_frame:.2} s per frame, flicker \
         {flicker:.4} → {}",
        keyframe_count, args.out
    ));
}
