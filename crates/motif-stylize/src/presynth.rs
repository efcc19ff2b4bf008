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
    segments_memory(style, size, segments, false)
}

/// [`presynth_memory`], or with `guided` that of [`presynthesize_closer`]: each segment's
/// synthesis also guided (the style blurred, as a source guide of the style's channels, and the
/// coarser texture magnified twice, as the target guide), with the blurred style kept for them all.
fn segments_memory(
    style: (usize, usize, usize),
    size: (usize, usize),
    segments: usize,
    guided: bool,
) -> motif_core::MemoryEstimate {
    let (style_pixels, channels) = (style.0.saturating_mul(style.1), style.2);
    let pixels = size.0.saturating_mul(size.1);
    let guide_channels = if guided { channels } else { 0 };
    let mut estimate = memory_estimate(style_pixels, channels, guide_channels, pixels, 4, style_pixels);
    estimate.add("finished textures", (pixels as f64) * segments as f64, (channels + 3) as f64 * 4.0);
    if guided {
        estimate.add("blurred style", style_pixels as f64, channels as f64 * 4.0);
    }
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
    let segments = Segments::new(input, params, false)?;
    let labels = 0..segments.colours.len();
    labels.map(|label| segments.texture(input, label, None, params, progress)).collect()
}

/// The textures of `coarser` (made by [`presynthesize`] or by this function from the same
/// `input`) one zoom level closer, for a slippy map whose zoom level `z + 1` shows each
/// texture pixel of level `z` as two by two: each texture twice the side, synthesized again from
/// the style at full detail but guided by the coarser one magnified twice, against the style
/// blurred by the same factor (what it looks like from twice as far: `motif zoom`'s guide,
/// §5.3). Texture pixel `v` continues pixel `v / 2` of the coarser one, so the layout seen at one
/// zoom level stays where it was at the next. `input.size` must be twice the coarser textures'
/// size, with one coarser texture per segment (matched by colour, in any order); the result is in
/// [`presynthesize`]'s order.
pub fn presynthesize_closer(
    input: &PresynthInput,
    coarser: &[SegmentTexture],
    params: &Params,
    progress: &mut dyn Progress,
) -> Result<Vec<SegmentTexture>, Error> {
    let segments = Segments::new(input, params, true)?;
    let (width, height) = input.size;
    let fits = |t: &SegmentTexture| {
        (2 * t.image.width(), 2 * t.image.height(), t.image.channels()) == (width, height, input.style.channels())
    };
    let by_segment: Vec<Option<&SegmentTexture>> =
        segments.colours.iter().map(|colour| coarser.iter().find(|t| &t.colour == colour)).collect();
    if coarser.len() != segments.colours.len() || !coarser.iter().all(fits) || by_segment.contains(&None) {
        let allowed = format!(
            "one texture per segment colour ({}), half the size {width}×{height} a side, with the style's {} channels",
            segments.colours.len(),
            input.style.channels()
        );
        return Err(InvalidParameter::new("coarser textures", format!("{} given", coarser.len()), allowed).into());
    }
    let blurred = crate::zoom::blurred_by(&input.style, 2.0);
    let labels = 0..segments.colours.len();
    labels
        .map(|label| {
            let coarse = by_segment[label].expect("checked: every segment has its coarser texture");
            let guide = (&blurred, magnified_twice(&coarse.image));
            segments.texture(input, label, Some(guide), params, progress)
        })
        .collect()
}

/// `image` (which tiles) magnified twice, bilinear, wrapping around its borders: pixel `v` of the
/// result lies over pixel `v / 2` of `image`.
fn magnified_twice(image: &FloatImage) -> FloatImage {
    let (width, height, channels) = (image.width(), image.height(), image.channels());
    let mut out = FloatImage::new(2 * width, 2 * height, channels);
    // Output pixel centre v + 0.5 lies at (v + 0.5) / 2 in the image: between centres c and c + 1
    // with c = floor((v + 0.5) / 2 − 0.5), in whole quarters.
    let taps = |v: usize, side: usize| -> (usize, usize, f32) {
        let at = (v as f32 + 0.5) / 2.0 - 0.5;
        let low = at.floor();
        let low_index = (low as isize).rem_euclid(side as isize) as usize;
        (low_index, (low_index + 1) % side, at - low)
    };
    for y in 0..2 * height {
        let (y0, y1, ty) = taps(y, height);
        for x in 0..2 * width {
            let (x0, x1, tx) = taps(x, width);
            let (a, b, c, d) = (image.pixel(x0, y0), image.pixel(x1, y0), image.pixel(x0, y1), image.pixel(x1, y1));
            for (k, slot) in out.pixel_mut(x, y).iter_mut().enumerate() {
                *slot = (a[k] * (1.0 - tx) + b[k] * tx) * (1.0 - ty) + (c[k] * (1.0 - tx) + d[k] * tx) * ty;
            }
        }
    }
    out
}

/// The checked input of a presynthesis: its segment colours and the source's labels.
struct Segments {
    colours: Vec<Vec<f32>>,
    source_labels: Vec<u16>,
}

impl Segments {
    /// Checks `input` and `params` (images, sizes, work and memory, of a `guided` synthesis per
    /// segment when making a closer level) and finds the segments.
    fn new(input: &PresynthInput, params: &Params, guided: bool) -> Result<Self, Error> {
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
        segments_memory((sw, sh, input.style.channels()), (width, height), colours.len(), guided)
            .check(params.max_memory, MEMORY_ADVICE)?;
        let r = patch / 2;
        for (label, colour) in colours.iter().enumerate() {
            let has_centre = (r..sh - r).any(|y| (r..sw - r).any(|x| usize::from(source_labels[y * sw + x]) == label));
            if !has_centre {
                return Err(Error::Input(InputError::SegmentTooThin { colour: hex(colour), patch }));
            }
        }
        Ok(Self { colours, source_labels })
    }

    /// The texture of segment `label`, `input.size`, tiling; with `zoom` (the source guide and
    /// its target, the style blurred and the coarser texture magnified), one zoom level closer.
    fn texture(
        &self,
        input: &PresynthInput,
        label: usize,
        zoom: Option<(&FloatImage, FloatImage)>,
        params: &Params,
        progress: &mut dyn Progress,
    ) -> Result<SegmentTexture, Error> {
        let (width, height) = input.size;
        let style_weights: Vec<f32> =
            channel_weights(params.style_weight.max(f32::MIN_POSITIVE), input.style.channels()).collect();
        let (source_guides, target_guides, guide_weights) = match &zoom {
            Some((source, target)) => (vec![*source], vec![target], channel_weights(1.0, source.channels()).collect()),
            None => (Vec::new(), Vec::new(), Vec::new()),
        };
        let problem = synthesis::Problem {
            style: &input.style,
            source_guides,
            target_guides,
            style_weights,
            guide_weights,
            target_size: input.size,
            labels: Some((
                std::borrow::Cow::Borrowed(&self.source_labels[..]),
                vec![label as u16; width * height],
                self.colours.len(),
            )),
            tileable: true,
            composition: None,
            seeds: None,
            origin: (0, 0),
            mask: None,
            structure_weight: None,
            prepared: None,
        };
        let mut segment_params = params.clone();
        let seeds = motif_core::SeedStreams::new(params.seed);
        // The first textures keep their seeds; each closer level has its own, by its size.
        segment_params.seed = match zoom {
            None => seeds.child("presynth", label as u64).seed(),
            Some(_) => seeds.child("presynth closer", ((width as u64) << 32) | label as u64).seed(),
        };
        let segments = self.colours.len();
        let mut report = |stage: &str, fraction: f64| {
            progress.report(&format!("segment {} of {segments}: {stage}", label + 1), fraction)
        };
        let output = synthesis::run(problem, &segment_params, &mut report)?;
        Ok(SegmentTexture { colour: self.colours[label].clone(), image: output.image, field: Some(output.field) })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tests::texture;
    use motif_core::NoProgress;

    /// Mean absolute difference between `closer` (twice the side) seen from twice as far and
    /// `coarser`, pixel by pixel.
    fn disagreement(coarser: &FloatImage, closer: &FloatImage) -> f64 {
        let reduced = crate::zoom::blurred_by(closer, 2.0);
        let mut total = 0.0;
        for y in 0..coarser.height() {
            for x in 0..coarser.width() {
                let (a, b) = (reduced.pixel(2 * x, 2 * y), coarser.pixel(x, y));
                total += a.iter().zip(b).map(|(p, q)| f64::from((p - q).abs())).sum::<f64>() / a.len() as f64;
            }
        }
        total / (coarser.width() * coarser.height()) as f64
    }

    /// The closer level's memory bound counts its guides: the magnified coarser texture (the
    /// target guide, with its coarser levels), the blurred style and its stacked channels. A
    /// limit that a plain presynthesis of the same size fits refuses it.
    #[test]
    fn a_closer_level_counts_its_guides_against_the_memory_limit() {
        let (style, size) = ((1024, 128, 3), (512, 512));
        let (plain, closer) = (presynth_memory(style, size, 8), segments_memory(style, size, 8, true));
        let target_guide = 512 * 512 * 3 * 4;
        assert!(closer.total() >= plain.total() + target_guide, "{} against {}", closer.total(), plain.total());
        let limit = plain.total() + target_guide / 2;
        assert!(plain.check(limit, "").is_ok() && closer.check(limit, "").is_err());
    }

    /// Two segments (left and right halves of the style): each texture of the closer level keeps
    /// the layout of its coarser one, far closer than a texture of its size made without it.
    #[test]
    fn a_closer_level_keeps_the_coarser_layout() {
        let style = texture(48, 48, 3, 31);
        let mut guide = FloatImage::new(48, 48, 3);
        for y in 0..48 {
            for x in 0..48 {
                // Red on the left, green on the right.
                guide.pixel_mut(x, y)[usize::from(x >= 24)] = 1.0;
            }
        }
        let params = Params::default().with_seed(3);
        let coarse_input = PresynthInput { style: style.clone(), guide: guide.clone(), size: (32, 32) };
        let coarser = presynthesize(&coarse_input, &params, &mut NoProgress).unwrap();
        let input = PresynthInput { size: (64, 64), ..coarse_input };
        let closer = presynthesize_closer(&input, &coarser, &params, &mut NoProgress).unwrap();
        // What the closer level would be without its guide: textures of its size, other seed.
        let free = presynthesize(&input, &params.clone().with_seed(99), &mut NoProgress).unwrap();
        for ((coarse, close), free) in coarser.iter().zip(&closer).zip(&free) {
            assert_eq!(close.colour, coarse.colour);
            assert_eq!((close.image.width(), close.image.height()), (64, 64));
            let (guided, unguided) =
                (disagreement(&coarse.image, &close.image), disagreement(&coarse.image, &free.image));
            assert!(guided < 0.6 * unguided, "closer level differs by {guided:.3} (unguided {unguided:.3})");
        }
        // Same input, same bytes, whatever the coarser textures' order; the wrong size is refused
        // by name.
        let reversed: Vec<SegmentTexture> = coarser.iter().rev().cloned().collect();
        let again = presynthesize_closer(&input, &reversed, &params, &mut NoProgress).unwrap();
        assert_eq!(again[1].image, closer[1].image);
        let wrong = PresynthInput { size: (48, 48), ..input };
        let error = presynthesize_closer(&wrong, &coarser, &params, &mut NoProgress).unwrap_err();
        assert!(error.to_string().contains("coarser textures"), "{error}");
    }

    #[test]
    fn magnifying_twice_wraps_around() {
        let image = FloatImage::from_data(2, 1, 1, vec![0.0, 1.0]).unwrap();
        let big = magnified_twice(&image);
        let row: Vec<f32> = (0..4).map(|x| big.pixel(x, 0)[0]).collect();
        // Centres at −0.25, 0.25, 0.75, 1.25 of the image: the first and last wrap to the other side.
        assert_eq!(row, vec![0.25, 0.25, 0.75, 0.75]);
    }
}
