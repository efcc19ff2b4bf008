//! `video` jobs: a frame sequence stylized from keyframes (`motif_stylize::stylize_video`).
//!
//! A video runs as independent keyframe intervals ([`VideoJob::intervals`]): a front end may
//! run them in any order, in parallel or on other machines ([`VideoJob::run_interval`]), and
//! gets the same bytes as one whole run ([`VideoJob::run`]).

use motif_core::{FloatImage, Progress, RgbaImage};
use motif_stylize::{
    Interval, IntervalOutput, Keyframe, Params, VideoInput, VideoOutput, VideoParams, intervals, stylize_interval,
};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value, json};

use super::{RunFields, SynthesisOptions, checked, default_seed};
use crate::JobError;
use crate::options::{Described, Joined};

crate::declare_options! {
    /// The options of `motif video` of its own (besides [`SynthesisOptions`]), declared once.
    pub struct VideoOptions {
        /// Weight of the frames' colours (keyframe against each frame).
        [value_name: "W", range: (0.0, 1000.0)]
        colour_weight: f32 = VideoParams::DEFAULT.colour_weight,
        /// Weight of the edge guide (the frames' blurred edges).
        [value_name: "W", range: (0.0, 1000.0)]
        edge_weight: f32 = VideoParams::DEFAULT.edge_weight,
        /// Weight of the positional guide (the keyframe's pixel positions carried along the
        /// motion, so the style stays on the surfaces it was painted on).
        [value_name: "W", range: (0.0, 1000.0)]
        position_weight: f32 = VideoParams::DEFAULT.position_weight,
        /// Weight of the temporal guide (the previous output carried along the motion; against
        /// flicker); 0 stylizes frames independently of each other.
        [value_name: "W", range: (0.0, 1000.0)]
        temporal_weight: f32 = VideoParams::DEFAULT.temporal_weight,
    }
}

/// Every option of `motif video` that is not a file: the shared synthesis options and its own.
pub type VideoJobOptions = Joined<SynthesisOptions, VideoOptions>;

/// A `video` job: the run's seed and memory bound, and every option ([`VideoJobOptions`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "crate::options::Described<RunFields>")]
pub struct VideoJob {
    /// Seed of every random choice (default 1, as on the command line).
    pub seed: u64,
    /// Refuse runs whose estimated peak memory passes this (see
    /// [`StylizeJob::max_memory`](super::StylizeJob::max_memory)).
    #[serde(rename = "max-memory")]
    pub max_memory: Option<u64>,
    /// Every other option.
    #[serde(flatten)]
    pub options: VideoJobOptions,
}

impl TryFrom<Described<RunFields>> for VideoJob {
    type Error = String;
    fn try_from(described: Described<RunFields>) -> Result<Self, String> {
        let (fields, options) = described.split()?;
        Ok(Self { seed: fields.seed, max_memory: fields.max_memory, options })
    }
}

impl VideoJob {
    /// A job with every option at its default.
    pub fn new() -> Self {
        Self { seed: default_seed(), max_memory: None, options: VideoJobOptions::default() }
    }

    /// The engine's parameters and guide weights, validated.
    pub fn params(&self) -> Result<(Params, VideoParams), JobError> {
        let params = self.options.shared.params(self.seed, self.max_memory);
        params.validate()?;
        let own = &self.options.own;
        let video = VideoParams::DEFAULT
            .with_colour_weight(own.colour_weight)
            .with_edge_weight(own.edge_weight)
            .with_position_weight(own.position_weight)
            .with_temporal_weight(own.temporal_weight);
        video.validate()?;
        Ok((checked(params, &self.options)?, video))
    }

    /// The peak memory of running the intervals of `lengths` frames (of `size`, `channels`
    /// floats) one after the other, as `motif video` does: the longest interval's (see
    /// [`motif_stylize::video_memory`]) with its frames as read and the copy its check makes,
    /// and the `keyframes` styles and the mask, kept throughout.
    pub fn memory(
        lengths: impl IntoIterator<Item = usize>,
        size: (usize, usize),
        channels: usize,
        keyframes: usize,
        mask: bool,
    ) -> motif_core::MemoryEstimate {
        let longest = lengths.into_iter().max().unwrap_or(0);
        let pixels = size.0 as f64 * size.1 as f64;
        let mut estimate = motif_stylize::video_memory(longest, size, channels);
        estimate
            .add("frames as read and checked", 2.0 * longest as f64 * pixels, 4.0 * channels as f64)
            .add("keyframe styles", keyframes as f64 * pixels, 4.0 * channels as f64)
            .add("mask", if mask { pixels } else { 0.0 }, 1.0);
        estimate
    }

    /// Refuses a whole run whose estimate (see [`VideoJob::memory`]) passes `max-memory`, before
    /// any frame is stylized; the estimate in bytes otherwise.
    pub fn check_memory(&self, estimate: &motif_core::MemoryEstimate) -> Result<u64, JobError> {
        let (params, _) = self.params()?;
        estimate
            .check(params.max_memory, motif_stylize::VIDEO_MEMORY_ADVICE)
            .map_err(|error| JobError::Stylize(error.into()))
    }

    /// The independent intervals of `frame_count` frames with keyframes at `key_frames`
    /// (positions from 0, increasing).
    pub fn intervals(frame_count: usize, key_frames: &[usize]) -> Vec<Interval> {
        intervals(frame_count, key_frames)
    }

    /// Stylizes one interval: `frames` are its frames, `interval` where it lies (from
    /// [`intervals`](Self::intervals)), and the styles of its keyframe ends. The interval is
    /// checked as a video of its own (sizes, channels, mask) before any work.
    pub fn run_interval(
        &self,
        frames: &[FloatImage],
        interval: Interval,
        first_style: Option<&FloatImage>,
        last_style: Option<&FloatImage>,
        mask: Option<&[bool]>,
        progress: &mut dyn Progress,
    ) -> Result<IntervalOutput, JobError> {
        let (params, video) = self.params()?;
        let mut keys = Vec::new();
        if let (true, Some(style)) = (interval.starts_at_key, first_style) {
            keys.push(Keyframe { frame: 0, style: style.clone() });
        }
        if let (true, Some(style)) = (interval.ends_at_key, last_style) {
            keys.push(Keyframe { frame: frames.len().saturating_sub(1), style: style.clone() });
        }
        let check = VideoInput { frames: frames.to_vec(), keys, mask: mask.map(<[bool]>::to_vec) };
        check.validate(&params)?;
        let first = interval.starts_at_key.then_some(first_style).flatten();
        let last = interval.ends_at_key.then_some(last_style).flatten();
        Ok(stylize_interval(frames, interval.first, first, last, mask, &params, &video, progress)?)
    }
}

/// A finished video job.
#[derive(Debug, Clone)]
pub struct VideoRun {
    /// The engine's output: the stylized frames and its report.
    pub output: VideoOutput,
    /// The run's figures: `frames`, `keyframes`, `intervals`, `engine_ms`, `ms_per_frame`,
    /// `flicker`.
    pub figures: Map<String, Value>,
}

impl crate::Finished for VideoRun {
    fn figures(&self) -> &Map<String, Value> {
        &self.figures
    }
}

impl crate::Job for VideoJob {
    const NAME: &'static str = "video";
    const FIELDS: &'static [&'static str] = &["seed", "max-memory"];
    const SUMMARY: &'static str = "Stylize a video from one or more keyframes painted by an artist";
    const DETAILS: &'static str = "Each frame is synthesized from the nearest keyframes with the frame's colours \
        and edges, the keyframe's positions carried along the motion and the previous output (against flicker), \
        forward and backward from keyframes and blended between them (Jamriška et al. 2019). Keyframe intervals \
        are independent (--interval).";
    type Options = VideoJobOptions;
    type Inputs<'a> = VideoInput;
    type Run = VideoRun;

    /// Stylizes the whole sequence.
    fn run(&self, input: VideoInput, progress: &mut dyn Progress) -> Result<VideoRun, JobError> {
        let (params, video) = self.params()?;
        let output = motif_stylize::stylize_video(&input, &params, &video, progress)?;
        let figures = crate::object(json!({
            "frames": output.report.frames,
            "keyframes": output.report.keyframes,
            "intervals": output.report.intervals,
            "engine_ms": output.report.total_ms,
            "ms_per_frame": output.report.ms_per_frame,
            "flicker": output.report.flicker,
        }));
        Ok(VideoRun { output, figures })
    }
}

/// A frame as the engine takes it: its colour channels (alpha is not part of a video frame).
pub fn video_frame(image: &RgbaImage) -> FloatImage {
    image.to_float_channels(&[0, 1, 2])
}

/// Keyframe styles with one channel count: RGBA when any has transparency, else RGB.
pub fn video_styles(images: &[RgbaImage]) -> Vec<FloatImage> {
    let alpha = images.iter().any(|image| !image.is_fully_opaque());
    images
        .iter()
        .map(|image| if alpha { image.to_float() } else { super::style_image_channels(image).to_float() })
        .collect()
}

impl Default for VideoJob {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use motif_core::NoProgress;
    use motif_stylize::samples::{CameraPath, crayon_style, map_guide, pan_and_zoom};

    use super::*;
    use crate::Job;

    #[test]
    fn intervals_run_apart_give_the_bytes_of_one_whole_run() {
        let photo = crayon_style(&map_guide(120, 90, 5, 3), 4);
        let path = CameraPath { start_centre: [40.0, 40.0], end_centre: [70.0, 50.0], start_zoom: 1.0, end_zoom: 1.1 };
        let footage = pan_and_zoom(&photo, 48, 40, 5, path);
        let styles = [crayon_style(&footage.frames[1], 7), crayon_style(&footage.frames[3], 8)];
        let keys =
            vec![Keyframe { frame: 1, style: styles[0].clone() }, Keyframe { frame: 3, style: styles[1].clone() }];
        let job: VideoJob = serde_json::from_value(json!({ "seed": 5, "search-vote-iters": 2 })).unwrap();
        let VideoRun { output: whole, figures } =
            job.run(VideoInput { frames: footage.frames.clone(), keys, mask: None }, &mut NoProgress).unwrap();
        assert_eq!(figures["frames"], json!(5));
        let parts = VideoJob::intervals(5, &[1, 3]);
        assert_eq!(parts.len(), 3);
        // In reverse order, each on its own.
        for interval in parts.iter().rev() {
            let style_at = |frame: usize| match frame {
                1 => Some(&styles[0]),
                3 => Some(&styles[1]),
                _ => None,
            };
            let part = job
                .run_interval(
                    &footage.frames[interval.first..=interval.last],
                    *interval,
                    style_at(interval.first),
                    style_at(interval.last),
                    None,
                    &mut NoProgress,
                )
                .unwrap();
            for (offset, frame) in part.frames.iter().enumerate() {
                assert_eq!(frame, &whole.frames[interval.first + offset], "frame {}", interval.first + offset);
            }
        }
        let error = serde_json::from_value::<VideoJob>(json!({ "temporal-weight": -1 })).unwrap().params().unwrap_err();
        assert!(error.to_string().contains("temporal-weight"), "{error}");
    }
}
