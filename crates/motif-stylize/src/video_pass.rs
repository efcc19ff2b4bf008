//! One synthesis pass of video stylization (Jamriška et al. 2019, §3): every frame of an
//! interval synthesized from one keyframe, walking away from it with the colour, edge, positional
//! and temporal guides carried along the motion; and the per-pixel blend of the pass from the
//! first keyframe with the pass from the last.

use motif_core::{FloatImage, Progress, SeedStreams};

use crate::motion::{MotionField, coordinate_guide, edge_guide};
use crate::{Error, Guide, Input, Mask, Params, VideoParams, synthesize};

/// One synthesized frame with its per-pixel error (for blending).
pub(crate) struct Synthesized {
    pub(crate) image: FloatImage,
    error: FloatImage,
}

/// What one pass over an interval's frames needs: the frames, the interval's place in the whole
/// video (it keys each frame's seed), the mask, the parameters and the seed streams.
pub(crate) struct Pass<'a> {
    pub(crate) frames: &'a [FloatImage],
    pub(crate) first_frame: usize,
    pub(crate) mask: Option<&'a [bool]>,
    pub(crate) params: &'a Params,
    pub(crate) video: &'a VideoParams,
    pub(crate) style_channels: usize,
    pub(crate) streams: &'a SeedStreams,
}

impl Pass<'_> {
    /// Synthesizes every frame from the keyframe at `key` (0 or the last), walking away from it;
    /// `motion[i]` carries frame `i` to `i + 1` forward, or `i + 1` to `i` backward.
    pub(crate) fn run(
        &self,
        style: &FloatImage,
        key: usize,
        motion: &[MotionField],
        step: &mut dyn FnMut(&mut dyn Progress),
        progress: &mut dyn Progress,
    ) -> Result<Vec<Synthesized>, Error> {
        let last = self.frames.len() - 1;
        let forward = key == 0;
        let key_frame = &self.frames[key];
        let (width, height) = (key_frame.width(), key_frame.height());
        let key_colour = crate::motion::colour_channels(key_frame);
        let key_edges = edge_guide(key_frame);
        let coordinates = coordinate_guide(width, height);
        let mut results: Vec<Option<Synthesized>> = (0..=last).map(|_| None).collect();
        let key_image = match self.mask {
            Some(hole) => composite(style, &kept_frame(key_frame, self.style_channels), hole),
            None => style.clone(),
        };
        results[key] = Some(Synthesized { image: key_image, error: FloatImage::new(width, height, 1) });
        let recolour = colour_mapping(&key_colour, style);
        let mut position = coordinates.clone();
        let order: Vec<usize> = if forward { (1..=last).collect() } else { (0..last).rev().collect() };
        let mut previous = key;
        for frame in order {
            let carried = if forward { &motion[previous] } else { &motion[frame] };
            position = carried.warp(&position);
            let target = &self.frames[frame];
            let mut temporal = carried.warp(&results[previous].as_ref().expect("walked in order").image);
            // Content entering the frame has no previous output to carry: the temporal guide
            // there is the frame recoloured by the keyframe's colour mapping, instead of the
            // border smeared inwards.
            let target_colour = crate::motion::colour_channels(target);
            for index in 0..width * height {
                if !carried.came_from_inside(index) {
                    let colour = &target_colour.data()[index * 3..index * 3 + 3];
                    let pixel = &mut temporal.data_mut()[index * style.channels()..(index + 1) * style.channels()];
                    for (c, value) in pixel.iter_mut().enumerate() {
                        let [slope, offset] = recolour[c];
                        *value = (slope * colour[c.min(2)] + offset).clamp(0.0, 1.0);
                    }
                }
            }
            let mut guides = Vec::with_capacity(4);
            let mut add = |source: &FloatImage, target: FloatImage, weight: f32| {
                if weight > 0.0 {
                    guides.push(Guide { source: source.clone(), target, weight: Some(weight) });
                }
            };
            add(&key_colour, crate::motion::colour_channels(target), self.video.colour_weight);
            add(&key_edges, edge_guide(target), self.video.edge_weight);
            add(&coordinates, position.clone(), self.video.position_weight);
            add(style, temporal, self.video.temporal_weight);
            let global = (self.first_frame + frame) as u64;
            let seed = self.streams.child(if forward { "forward frame" } else { "backward frame" }, global).seed();
            let params = self.params.clone().with_seed(seed);
            let mut input = Input::guided(style.clone(), guides);
            if input.guides.is_empty() {
                input.size = Some((width, height));
            }
            if let Some(hole) = self.mask {
                input.mask = Some(Mask {
                    keep: kept_frame(target, self.style_channels),
                    hole: hole.to_vec(),
                    exclude_hole_from_style: false,
                });
            }
            let output = synthesize(&input, &params, &mut motif_core::NoProgress)?;
            results[frame] = Some(Synthesized { image: output.image, error: output.error_map });
            step(progress);
            previous = frame;
        }
        Ok(results.into_iter().map(|r| r.expect("every frame synthesized")).collect())
    }
}

/// Per style channel, the least-squares line from the keyframe's matching colour channel to it
/// (`[slope, offset]`); alpha maps to its mean.
fn colour_mapping(key_colour: &FloatImage, style: &FloatImage) -> Vec<[f32; 2]> {
    let key_channels = key_colour.channels();
    (0..style.channels())
        .map(|c| {
            let source = c.min(key_channels - 1);
            let (mut sx, mut sy, mut sxx, mut sxy) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
            let n = (style.width() * style.height()) as f64;
            for (k, s) in key_colour.data().chunks_exact(key_channels).zip(style.data().chunks_exact(style.channels()))
            {
                let (x, y) = (f64::from(k[source]), f64::from(s[c]));
                sx += x;
                sy += y;
                sxx += x * x;
                sxy += x * y;
            }
            let variance = sxx - sx * sx / n;
            let is_alpha = c == 3;
            let slope = if is_alpha || variance < 1e-9 { 0.0 } else { (sxy - sx * sy / n) / variance };
            [slope as f32, ((sy - slope * sx) / n) as f32]
        })
        .collect()
}

/// The two passes' results for a frame `along` of the way (0–1) from the first keyframe to the
/// last: per pixel, each weighs by its nearness to its keyframe over its smoothed error.
pub(crate) fn blend(from_first: &Synthesized, from_last: &Synthesized, along: f32) -> FloatImage {
    if along <= 0.0 {
        return from_first.image.clone();
    }
    if along >= 1.0 {
        return from_last.image.clone();
    }
    let smooth = |error: &FloatImage| error.blur().blur().blur();
    let (error_first, error_last) = (smooth(&from_first.error), smooth(&from_last.error));
    let floor = 1e-3 + 0.01 * mean(&error_first).max(mean(&error_last));
    let mut out = from_first.image.clone();
    let channels = out.channels();
    for (index, pixel) in out.data_mut().chunks_exact_mut(channels).enumerate() {
        let first = (1.0 - along) / (error_first.data()[index] + floor);
        let last = along / (error_last.data()[index] + floor);
        let weight = last / (first + last);
        let other = &from_last.image.data()[index * channels..(index + 1) * channels];
        for (value, &theirs) in pixel.iter_mut().zip(other) {
            *value += weight * (theirs - *value);
        }
    }
    out
}

fn mean(image: &FloatImage) -> f32 {
    image.data().iter().sum::<f32>() / image.data().len().max(1) as f32
}

/// The frame as the pixels kept outside a mask: the style's channel count (alpha 1 added, or
/// dropped; grey repeated).
pub(crate) fn kept_frame(frame: &FloatImage, channels: usize) -> FloatImage {
    let colour = crate::motion::colour_channels(frame);
    let grey = colour.channels() == 1;
    let data = colour
        .data()
        .chunks_exact(colour.channels())
        .flat_map(|p| {
            let rgb = if grey { [p[0]; 3] } else { [p[0], p[1], p[2]] };
            match channels {
                1 => vec![0.299 * rgb[0] + 0.587 * rgb[1] + 0.114 * rgb[2]],
                3 => rgb.to_vec(),
                _ => vec![rgb[0], rgb[1], rgb[2], 1.0],
            }
        })
        .collect();
    FloatImage::from_data(frame.width(), frame.height(), channels, data).expect("sizes match")
}

fn composite(style: &FloatImage, kept: &FloatImage, hole: &[bool]) -> FloatImage {
    let mut out = kept.clone();
    let channels = out.channels();
    for (index, pixel) in out.data_mut().chunks_exact_mut(channels).enumerate() {
        if hole[index] {
            pixel.copy_from_slice(&style.data()[index * channels..(index + 1) * channels]);
        }
    }
    out
}
