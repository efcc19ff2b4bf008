//! Pre-synthesized textures (§3.7): one seamless texture per segment of the source guide, made
//! once and shared by every later run whose band mode fills the target from them.

use motif_core::{FloatImage, InvalidParameter, Progress};

use crate::InputError;
use crate::segments::{hex, label_image, segment_colours};
use crate::{
    Error, MEMORY_ADVICE, Params, SegmentTexture, Segmentation, channel_weights, check_image, check_work,
    memory_estimate, size_of, synthesis,
};

/// The peak memory of [`presynthesize`] (floats): one segment's synthesis at a time, and the
/// finished textures with their fields.
pub fn presynth_memory(
    style: (usize, usize, usize),
    size: (usize, usize),
    segments: usize,
) -> motif_core::MemoryEstimate {
    let (style_pixels, channels) = (style.0.saturating_mul(style.1), style.2);
    let pixels = size.0.saturating_mul(size.1);
    let mut estimate = memory_estimate(style_pixels, channels, 0, pixels, 4, style_pixels);
    estimate.add("finished textures", (pixels as f64) * segments as f64, (channels + 3) as f64 * 4.0);
    estimate
}

/// What [`presynthesize`] makes textures from.
#[derive(Debug, Clone, PartialEq)]
pub struct PresynthInput {
    /// The style A'.
    pub style: FloatImage,
    /// The source segment guide A (the style's size): its colours are the segments.
    pub guide: FloatImage,
    /// Size of every texture `(width, height)`; they tile, so any size ≥ a few patches works.
    pub size: (usize, usize),
}

/// Synthesizes one seamless texture per segment of the source guide from the style patches of
/// that segment (§3.7), for [`Input::textures`](crate::Input::textures). Segments are the guide's colours
/// ([`Params::segments`], palette by default). The textures tile (`tileable` is forced).
pub fn presynthesize(
    input: &PresynthInput,
    params: &Params,
    progress: &mut dyn Progress,
) -> Result<Vec<SegmentTexture>, Error> {
    params.validate()?;
    check_image(&input.style, "style")?;
    check_image(&input.guide, "source guide")?;
    if input.guide.width() != input.style.width() || input.guide.height() != input.style.height() {
        return Err(Error::Input(InputError::SizeMismatch {
            what: "the source guide must have the style's size".into(),
            first: "the style".into(),
            first_size: size_of(&input.style),
            second: "the source guide".into(),
            second_size: size_of(&input.guide),
        }));
    }
    let patch = params.patch_size;
    if input.style.width() < patch || input.style.height() < patch {
        return Err(Error::Input(InputError::StyleTooSmall {
            width: input.style.width(),
            height: input.style.height(),
            patch,
        }));
    }
    let (width, height) = input.size;
    if width < patch || height < patch || width > 1 << 14 || height > 1 << 14 {
        return Err(InvalidParameter::new(
            "size",
            format!("{width}×{height}"),
            format!("must be between {patch} and 16384 a side"),
        )
        .into());
    }
    check_work(width * height, params.max_pixels)?;
    let mode = params.segments.unwrap_or(Segmentation::Palette);
    // Every guide pixel, anti-aliased edges included, belongs to the nearest segment colour.
    let colours = segment_colours(&input.guide, mode, params.seed)?;
    let source_labels = label_image(&input.guide, &colours);
    check_work(width * height * colours.len(), params.max_pixels)?;
    let (sw, sh) = (input.style.width(), input.style.height());
    presynth_memory((sw, sh, input.style.channels()), (width, height), colours.len())
        .check(params.max_memory, MEMORY_ADVICE)?;
    let r = patch / 2;
    let mut textures = Vec::with_capacity(colours.len());
    let style_weights: Vec<f32> =
        channel_weights(params.style_weight.max(f32::MIN_POSITIVE), input.style.channels()).collect();
    for (label, colour) in colours.iter().enumerate() {
        let has_centre = (r..sh - r).any(|y| (r..sw - r).any(|x| usize::from(source_labels[y * sw + x]) == label));
        if !has_centre {
            return Err(Error::Input(InputError::SegmentTooThin { colour: hex(colour), patch }));
        }
        let problem = synthesis::Problem {
            style: &input.style,
            source_guides: Vec::new(),
            target_guides: Vec::new(),
            style_weights: style_weights.clone(),
            guide_weights: Vec::new(),
            target_size: input.size,
            labels: Some((source_labels.clone(), vec![label as u16; width * height], colours.len())),
            tileable: true,
            composition: None,
            seeds: None,
            origin: (0, 0),
            mask: None,
            structure_weight: None,
        };
        let mut segment_params = params.clone();
        segment_params.seed = motif_core::SeedStreams::new(params.seed).child("presynth", label as u64).seed();
        let mut report = |stage: &str, fraction: f64| {
            progress.report(&format!("segment {} of {}: {stage}", label + 1, colours.len()), fraction)
        };
        let output = synthesis::run(&problem, &segment_params, &mut report)?;
        textures.push(SegmentTexture { colour: colour.clone(), image: output.image, field: Some(output.field) });
    }
    Ok(textures)
}
