//! Video stylization from keyframes, after Jamriška et al. 2019, "Stylizing Video by Example".
//!
//! A keyframe is a frame the artist painted over. Other frames come from the nearest keyframes
//! with four guides (§3 of that paper):
//! - the frames' colours (keyframe against the frame), as ebsynth's video guide;
//! - G_edge, the frame's blurred edges ([`edge_guide`]);
//! - G_pos, the keyframe's coordinates carried along the motion ([`coordinate_guide`]);
//! - G_temp, the previous output carried along the motion, against the style (temporal coherence).
//!
//! Synthesis runs forward from a keyframe and backward from the next one; between two
//! keyframes the two results are blended per pixel, weighted by how far the frame is from each
//! keyframe and by each result's synthesis error (the paper picks the lower error; the blend
//! avoids seams where the pick flips). The frames between two keyframes form one [`Interval`],
//! independent of every other, so front ends can run intervals apart and get the same bytes.

use motif_core::timing::{Clock, elapsed_ms};
use motif_core::{FloatImage, Progress, SeedStreams};
use serde::Serialize;

use crate::motion::{MotionField, estimate_motion, flicker};
use crate::video_pass::{Pass, blend, kept_frame};
use crate::{Error, Mask, Params};
use crate::{InputError, LimitError};

/// The guide weights of video stylization (β of the map paper's Eq. 4, per guide).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct VideoParams {
    /// Weight of the frames' colours. Range `[0, 1000]`, default 1.
    pub colour_weight: f32,
    /// Weight of the edge guide G_edge. Range `[0, 1000]`, default 1.
    pub edge_weight: f32,
    /// Weight of the positional guide G_pos. Range `[0, 1000]`, default 4.
    pub position_weight: f32,
    /// Weight of the temporal guide G_temp (0 = frames stylized independently of each other,
    /// still with the positional guide). Range `[0, 1000]`, default 2.
    ///
    /// The defaults were chosen on the bench's footage over a real photo (`motif bench --engine
    /// stylize --case video`): temporal 0.5 → 2 and position 2 → 4 lowered the error against the
    /// ideal from 0.0172 to 0.0157 and the flicker from 0.0143 to 0.0117; 4 and 8 changed
    /// neither by more than 0.0008.
    pub temporal_weight: f32,
}

impl VideoParams {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self { colour_weight: 1.0, edge_weight: 1.0, position_weight: 4.0, temporal_weight: 2.0 };

    /// Checks every weight's range.
    pub fn validate(&self) -> Result<(), Error> {
        use motif_core::error::check_range;
        check_range("colour-weight", f64::from(self.colour_weight), 0.0, 1000.0)?;
        check_range("edge-weight", f64::from(self.edge_weight), 0.0, 1000.0)?;
        check_range("position-weight", f64::from(self.position_weight), 0.0, 1000.0)?;
        check_range("temporal-weight", f64::from(self.temporal_weight), 0.0, 1000.0)?;
        Ok(())
    }
}

impl Default for VideoParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

motif_core::builders! { VideoParams {
    with_colour_weight => colour_weight: f32,
    with_edge_weight => edge_weight: f32,
    with_position_weight => position_weight: f32,
    with_temporal_weight => temporal_weight: f32,
}}

/// A frame the artist stylized.
#[derive(Debug, Clone, PartialEq)]
pub struct Keyframe {
    /// Its position in the sequence, from 0.
    pub frame: usize,
    /// The stylized frame: the frames' size, 1, 3 or 4 channels (the same for every keyframe).
    pub style: FloatImage,
}

/// What to stylize: the frames in order and at least one keyframe.
#[derive(Debug, Clone, PartialEq)]
pub struct VideoInput {
    /// The frames, all of one size and channel count (1, 3 or 4).
    pub frames: Vec<FloatImage>,
    /// The keyframes, in increasing frame order.
    pub keys: Vec<Keyframe>,
    /// Synthesize only these pixels (row by row, `true` = synthesize) and keep the frame's own
    /// pixels elsewhere; `None` = every pixel.
    pub mask: Option<Vec<bool>>,
}

/// A run of frames synthesized together: from one keyframe to the next (both ends included),
/// or before the first keyframe, or after the last.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Interval {
    /// First frame.
    pub first: usize,
    /// Last frame (included).
    pub last: usize,
    /// Whether `first` is a keyframe (synthesis runs forward from it).
    pub starts_at_key: bool,
    /// Whether `last` is a keyframe (synthesis runs backward from it).
    pub ends_at_key: bool,
}

/// The intervals of a sequence of `frame_count` frames with keyframes at `key_frames`
/// (increasing, within the sequence).
pub fn intervals(frame_count: usize, key_frames: &[usize]) -> Vec<Interval> {
    let mut out = Vec::new();
    let (Some(&first_key), Some(&last_key)) = (key_frames.first(), key_frames.last()) else { return out };
    if first_key > 0 {
        out.push(Interval { first: 0, last: first_key, starts_at_key: false, ends_at_key: true });
    }
    for pair in key_frames.windows(2) {
        out.push(Interval { first: pair[0], last: pair[1], starts_at_key: true, ends_at_key: true });
    }
    if key_frames.len() == 1 || last_key + 1 < frame_count {
        out.push(Interval { first: last_key, last: frame_count - 1, starts_at_key: true, ends_at_key: false });
    }
    out
}

/// Figures of one interval.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct IntervalReport {
    /// The interval.
    pub interval: Interval,
    /// Frames synthesized (a frame between two keyframes counts once, though it is
    /// synthesized from both).
    pub synthesized_frames: usize,
    /// Milliseconds estimating motion.
    pub motion_ms: f64,
    /// Milliseconds of synthesis and blending.
    pub synthesis_ms: f64,
    /// Mean absolute difference between consecutive output frames after motion compensation
    /// (estimated motion, pixels visible in both, colour channels, values in `[0, 1]`).
    pub flicker: f64,
}

/// Figures of a whole video.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct VideoReport {
    /// Frames in the sequence.
    pub frames: usize,
    /// Keyframe positions.
    pub keyframes: Vec<usize>,
    /// Per interval.
    pub intervals: Vec<IntervalReport>,
    /// Wall-clock milliseconds of the whole run.
    pub total_ms: f64,
    /// `total_ms` over the synthesized frames.
    pub ms_per_frame: f64,
    /// Mean of the intervals' flicker, weighted by their frame pairs.
    pub flicker: f64,
}

/// The stylized frames and the report.
#[derive(Debug, Clone, PartialEq)]
pub struct VideoOutput {
    /// One image per input frame, the keyframes' styles' channels.
    pub frames: Vec<FloatImage>,
    /// What was done.
    pub report: VideoReport,
}

impl VideoInput {
    /// Checks the frames, keyframes and mask once, before any work.
    pub fn validate(&self, params: &Params) -> Result<(), Error> {
        validate(self, params)
    }
}

/// What to change when a video needs too much memory.
pub const VIDEO_MEMORY_ADVICE: &str = "use fewer frames between keyframes or smaller frames";

/// The peak memory of stylizing `frames` frames of `size` at once (one interval), floats of
/// `channels` channels: the frames, the forward and backward passes' results and errors, and the
/// two motion fields.
pub fn video_memory(frames: usize, size: (usize, usize), channels: usize) -> motif_core::MemoryEstimate {
    let pixels = frames as f64 * size.0 as f64 * size.1 as f64;
    let channels = channels as f64;
    let mut estimate = motif_core::MemoryEstimate::new();
    estimate
        .add("frames", pixels, 4.0 * channels)
        .add("forward and backward results", 2.0 * pixels, 4.0 * (channels + 1.0))
        .add("motion fields", 2.0 * pixels, 8.0);
    estimate
}

fn validate(input: &VideoInput, params: &Params) -> Result<(), Error> {
    let first = input.frames.first().ok_or(Error::Input(InputError::NoFrames))?;
    let (width, height) = (first.width(), first.height());
    if width == 0 || height == 0 {
        return Err(Error::Input(InputError::EmptyImage("frame 0".into())));
    }
    // Every frame is one synthesis: the pixel guard applies per frame, and the frames of an
    // interval are held together (frames, two passes' results and errors, two motion fields).
    let pixels = width.saturating_mul(height);
    if pixels > params.max_pixels {
        return Err(Error::Limit(LimitError::TooMuchWork { pixels, max_pixels: params.max_pixels }));
    }
    let channels = first.channels().max(input.keys.first().map_or(3, |k| k.style.channels()));
    video_memory(input.frames.len(), (width, height), channels).check(params.max_memory, VIDEO_MEMORY_ADVICE)?;
    for (index, frame) in input.frames.iter().enumerate() {
        if !matches!(frame.channels(), 1 | 3 | 4) {
            return Err(Error::Input(InputError::UnsupportedChannels {
                what: format!("frame {index}"),
                channels: frame.channels(),
            }));
        }
        if (frame.width(), frame.height(), frame.channels()) != (width, height, first.channels()) {
            return Err(size_mismatch(
                "every frame must have the first frame's size and channels",
                0,
                first,
                index,
                frame,
            ));
        }
    }
    if input.keys.is_empty() {
        return Err(Error::Input(InputError::NoKeyframes));
    }
    for (position, key) in input.keys.iter().enumerate() {
        if key.frame >= input.frames.len() {
            return Err(Error::Input(InputError::KeyframeOutOfRange { frame: key.frame, frames: input.frames.len() }));
        }
        if position > 0 && key.frame <= input.keys[position - 1].frame {
            return Err(Error::Input(InputError::KeyframeOrder {
                frame: key.frame,
                previous: input.keys[position - 1].frame,
            }));
        }
        if (key.style.width(), key.style.height()) != (width, height) {
            return Err(Error::Input(InputError::SizeMismatch {
                what: "a keyframe's style must have its frame's size".into(),
                first: format!("keyframe {}", key.frame),
                first_size: format!("{}×{}", key.style.width(), key.style.height()),
                second: "the frames".into(),
                second_size: format!("{width}×{height}"),
            }));
        }
        if !matches!(key.style.channels(), 1 | 3 | 4) || key.style.channels() != input.keys[0].style.channels() {
            return Err(Error::Input(InputError::UnsupportedChannels {
                what: format!("keyframe {} (every keyframe needs the first one's channels)", key.frame),
                channels: key.style.channels(),
            }));
        }
    }
    if let Some(mask) = &input.mask {
        let keep = kept_frame(first, input.keys[0].style.channels());
        crate::mask::check(
            &Mask { keep, hole: mask.clone(), exclude_hole_from_style: false },
            &input.keys[0].style,
            (width, height),
            params.patch_size,
            false,
        )?;
    }
    Ok(())
}

fn size_mismatch(what: &str, a: usize, first: &FloatImage, b: usize, second: &FloatImage) -> Error {
    Error::Input(InputError::SizeMismatch {
        what: what.into(),
        first: format!("frame {a}"),
        first_size: format!("{}×{}×{}", first.width(), first.height(), first.channels()),
        second: format!("frame {b}"),
        second_size: format!("{}×{}×{}", second.width(), second.height(), second.channels()),
    })
}

/// Stylizes every frame of `input`: each interval in turn (see [`stylize_interval`]).
pub fn stylize_video(
    input: &VideoInput,
    params: &Params,
    video: &VideoParams,
    progress: &mut dyn Progress,
) -> Result<VideoOutput, Error> {
    params.validate()?;
    video.validate()?;
    validate(input, params)?;
    let start = Clock::now();
    let key_frames: Vec<usize> = input.keys.iter().map(|k| k.frame).collect();
    let mut frames: Vec<Option<FloatImage>> = vec![None; input.frames.len()];
    let mut reports = Vec::new();
    let all = intervals(input.frames.len(), &key_frames);
    let count = all.len();
    for (number, interval) in all.into_iter().enumerate() {
        let style_at = |frame: usize| input.keys.iter().find(|k| k.frame == frame).map(|k| &k.style);
        let first_style = if interval.starts_at_key { style_at(interval.first) } else { None };
        let last_style = if interval.ends_at_key { style_at(interval.last) } else { None };
        let mut report = |stage: &str, fraction: f64| {
            progress.report(&format!("interval {} of {count}: {stage}", number + 1), fraction)
        };
        let part = stylize_interval(
            &input.frames[interval.first..=interval.last],
            interval.first,
            first_style,
            last_style,
            input.mask.as_deref(),
            params,
            video,
            &mut report,
        )?;
        for (offset, frame) in part.frames.into_iter().enumerate() {
            frames[interval.first + offset].get_or_insert(frame);
        }
        reports.push(part.report);
    }
    let total_ms = elapsed_ms(start);
    let flicker = mean_flicker(&reports);
    let synthesized: usize = reports.iter().map(|r| r.synthesized_frames).sum();
    Ok(VideoOutput {
        frames: frames.into_iter().map(|f| f.expect("every frame is in an interval")).collect(),
        report: VideoReport {
            frames: input.frames.len(),
            keyframes: key_frames,
            intervals: reports,
            total_ms,
            ms_per_frame: total_ms / synthesized.max(1) as f64,
            flicker,
        },
    })
}

/// A whole video's flicker from its intervals', weighted by their pairs of consecutive frames.
pub fn mean_flicker(reports: &[IntervalReport]) -> f64 {
    let pairs: usize = reports.iter().map(|r| r.interval.last - r.interval.first).sum();
    let weighted: f64 = reports.iter().map(|r| r.flicker * (r.interval.last - r.interval.first) as f64).sum();
    weighted / pairs.max(1) as f64
}

/// The frames of one interval and its figures.
#[derive(Debug, Clone, PartialEq)]
pub struct IntervalOutput {
    /// One image per frame of the interval, keyframes included (as their styles, or the style
    /// within the mask and the frame outside it).
    pub frames: Vec<FloatImage>,
    /// What was done.
    pub report: IntervalReport,
}

/// Stylizes one interval: `frames` are its frames (`first_frame` is the position of the first
/// in the whole sequence, which keys every random choice, so an interval gives the same bytes
/// wherever it runs). `first_style` is the stylized first frame (then synthesis runs forward
/// from it), `last_style` the stylized last one (backward); at least one is needed. The input
/// must have passed [`VideoInput::validate`] as part of its whole video.
#[allow(
    clippy::too_many_arguments,
    reason = "an interval is the public unit a front end runs apart; each argument is one input of it"
)]
pub fn stylize_interval(
    frames: &[FloatImage],
    first_frame: usize,
    first_style: Option<&FloatImage>,
    last_style: Option<&FloatImage>,
    mask: Option<&[bool]>,
    params: &Params,
    video: &VideoParams,
    progress: &mut dyn Progress,
) -> Result<IntervalOutput, Error> {
    let last = frames.len().checked_sub(1).ok_or(Error::Input(InputError::NoFrames))?;
    let interval = Interval {
        first: first_frame,
        last: first_frame + last,
        starts_at_key: first_style.is_some(),
        ends_at_key: last_style.is_some(),
    };
    let style_channels = first_style.or(last_style).ok_or(Error::Input(InputError::NoKeyframes))?.channels();
    let mut motion_ms = 0.0;
    let streams = SeedStreams::new(params.seed);
    // Motion between neighbours, both ways when both passes run: forward[i] carries frame i to
    // frame i + 1, backward[i] frame i + 1 to frame i.
    let mut forward = Vec::new();
    let mut backward = Vec::new();
    for i in 0..last {
        progress.report("motion", i as f64 / (2 * last.max(1)) as f64);
        let time = Clock::now();
        let global = (first_frame + i) as u64;
        if first_style.is_some() {
            forward.push(estimate_motion(&frames[i], &frames[i + 1], streams.child("forward motion", global).seed())?);
        }
        if last_style.is_some() {
            backward.push(estimate_motion(
                &frames[i + 1],
                &frames[i],
                streams.child("backward motion", global).seed(),
            )?);
        }
        motion_ms += elapsed_ms(time);
    }
    let synthesis_time = Clock::now();
    let context = Pass { frames, first_frame, mask, params, video, style_channels, streams: &streams };
    let mut done = 0;
    let total = if first_style.is_some() && last_style.is_some() { 2 * last } else { last };
    let mut step = |progress: &mut dyn Progress| {
        done += 1;
        progress.report("synthesis", 0.5 + 0.5 * done as f64 / total.max(1) as f64);
    };
    let from_first = match first_style {
        Some(style) => Some(context.run(style, 0, &forward, &mut |p| step(p), progress)?),
        None => None,
    };
    let from_last = match last_style {
        Some(style) => Some(context.run(style, last, &backward, &mut |p| step(p), progress)?),
        None => None,
    };
    let out: Vec<FloatImage> = match (from_first, from_last) {
        (Some(a), Some(b)) => (0..=last)
            .map(|i| {
                let along = i as f32 / last.max(1) as f32;
                blend(&a[i], &b[i], along)
            })
            .collect(),
        (Some(a), None) => a.into_iter().map(|r| r.image).collect(),
        (None, Some(b)) => b.into_iter().map(|r| r.image).collect(),
        (None, None) => return Err(Error::Input(InputError::NoKeyframes)),
    };
    // Measured along whichever motion the passes estimated: backward fields carry frame i + 1 to
    // frame i, so the frames are walked in reverse with them.
    let flicker = if first_style.is_some() {
        flicker(&out, &forward)
    } else {
        let reversed: Vec<FloatImage> = out.iter().rev().cloned().collect();
        let motion: Vec<MotionField> = backward.iter().rev().cloned().collect();
        flicker(&reversed, &motion)
    };
    Ok(IntervalOutput {
        report: IntervalReport {
            interval,
            synthesized_frames: last + 1 - usize::from(first_style.is_some()) - usize::from(last_style.is_some()),
            motion_ms,
            synthesis_ms: elapsed_ms(synthesis_time),
            flicker,
        },
        frames: out,
    })
}
