//! Segment labels from guide colours (§3.6): the source guide's exact palette for flat map
//! renders, or its k-means quantization for anti-aliased or compressed guides, or the colours of a
//! pre-synthesized cache (§3.7). Every pixel of both guides takes the nearest segment colour, so
//! "the same segment" means "the same guide colour (cluster)" on both sides and an edge's blends
//! join a segment; a target colour far from every segment colour and blend is set apart.

use std::borrow::Cow;
use std::collections::BTreeMap;

use motif_core::{ChannelImage, FloatImage, Samples};

mod kmeans;

use kmeans::kmeans;

use crate::InputError;
use crate::{Error, Guide, Input, InvalidParameter, Params, Segmentation};

/// Most distinct colours the exact palette accepts; beyond it, k-means is the tool.
pub const MAX_PALETTE: usize = 64;

/// Segment labels of the source and target segment guides.
#[derive(Debug, Clone, PartialEq)]
pub struct SegmentLabels {
    /// Guide colour of each label (values in `[0, 1]`, the guide's channels): the segment colours,
    /// then those of target segments far from all of them (no source pixel has those labels).
    pub colours: Vec<Vec<f32>>,
    /// Label of every source pixel, row-major.
    pub source: Vec<u16>,
    /// Label of every target pixel, row-major.
    pub target: Vec<u16>,
}

/// Quantized colour key: 8 bits per channel, up to 4 channels.
#[inline]
fn key(pixel: &[f32]) -> [u8; 4] {
    let mut key = [0; 4];
    for (slot, value) in key.iter_mut().zip(pixel) {
        // Rounds half up like `round` on these non-negative values, without the libm call.
        *slot = (value.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    }
    key
}

/// How far (Euclidean, channels in `[0, 1]`) a guide colour may lie from the nearest segment colour
/// or blend of two segment colours and still be taken for them: an anti-aliased edge is a blend,
/// JPEG's ringing and a soft brush's noise stay within this; a colour of its own lies farther.
pub const BLEND_TOLERANCE: f32 = 0.2;

/// Fewest pixels a run of far colours must cover to be a segment of its own (a 5 × 5 patch); a
/// thousandth of the target when that is more. Fewer are stray edge pixels and take the nearest.
const MIN_SEGMENT_PIXELS: usize = 25;

/// Share of the source guide's pixels whose distance from the blends of its segment colours
/// widens the tolerance (k-means with fewer segments than the guide has colours merges colours
/// that lie farther apart; its rarest strays do not count).
const SOURCE_SPREAD_SHARE: f64 = 0.995;

/// Distinct 8-bit colours of `image` with their pixel counts (in key order).
fn histogram(image: &FloatImage) -> Vec<([u8; 4], usize)> {
    let mut histogram: BTreeMap<[u8; 4], usize> = BTreeMap::new();
    // Guides are mostly flat runs of one colour: count runs, not pixels, into the map.
    let mut run: Option<([u8; 4], usize)> = None;
    for pixel in image.data().chunks_exact(image.channels()) {
        let key = key(pixel);
        match &mut run {
            Some((current, count)) if *current == key => *count += 1,
            _ => {
                if let Some((current, count)) = run.replace((key, 1)) {
                    *histogram.entry(current).or_default() += count;
                }
            }
        }
    }
    if let Some((current, count)) = run {
        *histogram.entry(current).or_default() += count;
    }
    histogram.into_iter().collect()
}

/// The colour a [`key`] stands for, in its first `channels` values (the others are 0).
fn unkey(key: &[u8; 4], channels: usize) -> [f32; 4] {
    let mut colour = [0.0; 4];
    for (value, &v) in colour.iter_mut().zip(&key[..channels]) {
        *value = f32::from(v) / 255.0;
    }
    colour
}

/// The segment colours of a source guide: its exact palette, or `k` k-means centres of its
/// colours (the target guide plays no part: its pixels take the nearest of these).
pub(crate) fn segment_colours(source: &FloatImage, mode: Segmentation, seed: u64) -> Result<Vec<Vec<f32>>, Error> {
    let unique = histogram(source);
    let channels = source.channels();
    match mode {
        Segmentation::Palette => {
            if unique.len() > MAX_PALETTE {
                return Err(Error::Input(InputError::TooManyColours { colours: unique.len(), max: MAX_PALETTE }));
            }
            Ok(unique.iter().map(|(key, _)| unkey(key, channels)[..channels].to_vec()).collect())
        }
        Segmentation::KMeans(k) => Ok(kmeans(&unique, channels, k, seed)),
    }
}

/// Labels both guides with `mode`: the segment colours are the source guide's (palette or
/// k-means, `seed` drives its initialization) and every pixel of both takes the nearest, so
/// anti-aliased or compressed edges join a segment. A target colour far from every segment and
/// its blends over a whole patch or more (a region the style's map lacks) is a segment of its
/// own, with no source pixels: its patches match anywhere.
pub fn label_guides(
    source: &FloatImage,
    target: &FloatImage,
    mode: Segmentation,
    seed: u64,
) -> Result<SegmentLabels, Error> {
    let mut colours = segment_colours(source, mode, seed)?;
    let far = far_segments(source, target, &colours);
    colours.extend(far.into_iter().map(|segment| segment.colour));
    Ok(nearest_labels(source, target, colours))
}

/// Labels every pixel of both guides with its nearest colour of `colours` (squared distance in
/// the guides' channels): the segments of a pre-synthesized cache, whose colours were fixed when
/// it was made, for guides whose anti-aliased or compressed edges hold colours of their own. A
/// target segment far from every colour and their blends is refused, naming it
/// ([`InputError::MissingTexture`]); so are no colours and colours of another channel count.
pub fn label_by_colours(
    source: &FloatImage,
    target: &FloatImage,
    colours: Vec<Vec<f32>>,
) -> Result<SegmentLabels, Error> {
    let target = label_target_by_colours(source, target, &colours)?;
    Ok(SegmentLabels { source: label_image(source, &colours), target, colours })
}

/// The target's labels of [`label_by_colours`], with its checks: the source is read only to
/// judge a target colour far from every segment colour (not at all for a target of segment
/// colours only, as map tiles are).
pub(crate) fn label_target_by_colours<S: ChannelImage>(
    source: &S,
    target: &FloatImage,
    colours: &[Vec<f32>],
) -> Result<Vec<u16>, Error> {
    check_colours(colours, source.channels())?;
    if let Some(far) = far_segments(source, target, colours).into_iter().next() {
        let textures: Vec<String> = colours.iter().map(|c| format!("#{}", hex(c))).collect();
        return Err(Error::Input(InputError::MissingTexture {
            colour: hex(&far.colour),
            pixels: far.pixels,
            textures: textures.join(", "),
            distance: levels(far.distance),
            tolerance: levels(far.tolerance),
        }));
    }
    Ok(label_image(target, colours))
}

/// [`label_target_by_colours`] for a target guide of either sample type: an 8-bit guide of
/// segment colours only (a map tile's) is labelled on its bytes, one look-up per distinct colour
/// and no float copy ([`segment_colour_labels`]); any other takes the float path.
fn label_target_guide<S: ChannelImage, T: ChannelImage>(
    source: &S,
    target: &T,
    colours: &[Vec<f32>],
) -> Result<Vec<u16>, Error> {
    check_colours(colours, source.channels())?;
    if let Samples::Byte(bytes) = target.samples()
        && target.channels() == source.channels()
        && let Some(labels) = segment_colour_labels(bytes, target.channels(), colours)
    {
        return Ok(labels);
    }
    label_target_by_colours(source, &target.to_float_image(), colours)
}

/// The labels [`label_image`] gives an 8-bit image (`channels` of at most 4 per pixel) whose
/// every pixel is exactly one of `colours`, or `None` as soon as one pixel is not: its colour may
/// lie far from them all, which [`label_target_by_colours`] judges.
fn segment_colour_labels(bytes: &[u8], channels: usize, colours: &[Vec<f32>]) -> Option<Vec<u16>> {
    if channels == 0 || channels > 4 {
        return None;
    }
    // The distinct colours met so far, with their labels (a map tile has a handful).
    let mut known: Vec<([u8; 4], u16)> = Vec::new();
    let mut previous: Option<(&[u8], u16)> = None;
    let mut labels = Vec::with_capacity(bytes.len() / channels);
    for pixel in bytes.chunks_exact(channels) {
        let label = match previous {
            Some((colour, label)) if colour == pixel => label,
            _ => {
                let mut key = [0; 4];
                key[..channels].copy_from_slice(pixel);
                let label = match known.iter().find(|(k, _)| *k == key) {
                    Some(&(_, label)) => label,
                    None => {
                        let colour = unkey(&key, channels);
                        let colour = &colour[..channels];
                        if !colours.iter().any(|c| squared(c, colour) == 0.0) {
                            return None;
                        }
                        let label = nearest_label(colour, colours);
                        known.push((key, label));
                        label
                    }
                };
                previous = Some((pixel, label));
                label
            }
        };
        labels.push(label);
    }
    Some(labels)
}

/// Refuses no segment colours, and colours of another channel count than the guide's.
pub(crate) fn check_colours(colours: &[Vec<f32>], guide_channels: usize) -> Result<(), Error> {
    if colours.is_empty() {
        return Err(Error::Input(InputError::NoTextures));
    }
    if let Some(index) = colours.iter().position(|c| c.len() != guide_channels) {
        let channels = colours[index].len();
        return Err(Error::Input(InputError::TextureColour { texture: index + 1, channels, guide_channels }));
    }
    Ok(())
}

/// The labels a run uses: the source's (borrowed from a [`crate::PreparedStyle`], else its own),
/// the target's, and how many.
pub(crate) type RunLabels<'a> = (Cow<'a, [u16]>, Vec<u16>, usize);

/// The guide that segments are found on ([`crate::Params::segment_guide`]).
pub(crate) fn segment_guide<'a, I: ChannelImage>(input: &'a Input<I>, params: &Params) -> Result<&'a Guide<I>, Error> {
    let guide_count = input.guides.len();
    input.guides.get(params.segment_guide).ok_or_else(|| {
        if guide_count == 0 {
            Error::Input(InputError::SegmentsWithoutGuide)
        } else {
            InvalidParameter::new(
                "segment-guide",
                params.segment_guide + 1,
                format!("must name one of the {guide_count} guides, counted from 1"),
            )
            .into()
        }
    })
}

/// Segment labels of the source and target (§3.6), when segments are asked for or textures are
/// given: from the textures' colours, else found on the segment guide. With a prepared style,
/// the source's are its own and only the target is labelled.
pub(crate) fn segment_labels<'a, I: ChannelImage>(
    input: &'a Input<I>,
    params: &Params,
) -> Result<Option<RunLabels<'a>>, Error> {
    if params.segments.is_none() && input.textures.is_none() {
        return Ok(None);
    }
    let guide = segment_guide(input, params)?;
    let labels = match (&input.textures, &input.prepared) {
        // With a cache, its colours are the segments (whatever the mode, which chose them when
        // it was made), and each pixel, anti-aliased edges included, belongs to the nearest
        // (Texler et al. §3.7).
        (Some(textures), prepared) => {
            let colours: Vec<Vec<f32>> = textures.iter().map(|t| t.colour.clone()).collect();
            let count = colours.len();
            match prepared {
                Some(prepared) => {
                    let target = label_target_guide(&guide.source, &guide.target, &colours)?;
                    (Cow::Borrowed(prepared.labels()), target, count)
                }
                None => {
                    let target = guide.target.to_float_image();
                    let labels = label_by_colours(&guide.source.to_float_image(), &target, colours)?;
                    (Cow::Owned(labels.source), labels.target, count)
                }
            }
        }
        (None, _) => {
            let mode = params.segments.unwrap_or(Segmentation::Palette);
            let target = guide.target.to_float_image();
            let labels = label_guides(&guide.source.to_float_image(), &target, mode, params.seed)?;
            let count = labels.colours.len();
            (Cow::Owned(labels.source), labels.target, count)
        }
    };
    Ok(Some(labels))
}

/// A colour as hex digits, two per channel (`rrggbb` for RGB).
pub(crate) fn hex(colour: &[f32]) -> String {
    colour.iter().map(|v| format!("{:02x}", (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8)).collect()
}

/// A distance in `[0, 1]` channel units as 8-bit levels, rounded.
fn levels(distance: f32) -> u32 {
    (distance * 255.0 + 0.5) as u32
}

fn nearest_labels(source: &FloatImage, target: &FloatImage, colours: Vec<Vec<f32>>) -> SegmentLabels {
    SegmentLabels { source: label_image(source, &colours), target: label_image(target, &colours), colours }
}

/// The label of every pixel of `image`: the index of its nearest colour of `colours`.
pub(crate) fn label_image(image: &FloatImage, colours: &[Vec<f32>]) -> Vec<u16> {
    let label_of = |pixel: &[f32]| nearest_label(pixel, colours);
    // Runs of one colour share the label of their first pixel.
    let mut previous: Option<(&[f32], u16)> = None;
    image
        .data()
        .chunks_exact(image.channels())
        .map(|pixel| match previous {
            Some((colour, label)) if colour == pixel => label,
            _ => {
                let label = label_of(pixel);
                previous = Some((pixel, label));
                label
            }
        })
        .collect()
}

/// The index of `pixel`'s nearest colour of `colours` (the first of equally near ones).
fn nearest_label(pixel: &[f32], colours: &[Vec<f32>]) -> u16 {
    let mut best = (f32::INFINITY, 0);
    for (label, colour) in colours.iter().enumerate() {
        let d = squared(colour, pixel);
        if d < best.0 {
            best = (d, label);
        }
    }
    best.1 as u16
}

#[inline]
fn squared(a: &[f32], b: &[f32]) -> f32 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Squared distance from `pixel` to the nearest segment colour or blend of two (the line between
/// them): what anti-aliasing cannot explain.
fn blend_residual(pixel: &[f32], colours: &[Vec<f32>]) -> f32 {
    let mut best = colours.iter().map(|c| squared(c, pixel)).fold(f32::INFINITY, f32::min);
    for (i, a) in colours.iter().enumerate() {
        for b in &colours[i + 1..] {
            let along: f32 = a.iter().zip(b).zip(pixel).map(|((a, b), p)| (b - a) * (p - a)).sum();
            let length = squared(a, b);
            if length <= 0.0 || along <= 0.0 || along >= length {
                continue;
            }
            let t = along / length;
            let d: f32 =
                a.iter().zip(b).zip(pixel).map(|((a, b), p)| (a + t * (b - a) - p) * (a + t * (b - a) - p)).sum();
            best = best.min(d);
        }
    }
    best
}

/// A run of target colours far from every segment colour and blend.
#[derive(Debug, Clone, PartialEq)]
struct FarSegment {
    /// Its mean colour.
    colour: Vec<f32>,
    /// Its pixels.
    pixels: usize,
    /// Distance of its mean from the nearest segment colour or blend.
    distance: f32,
    /// The tolerance it passes.
    tolerance: f32,
}

/// How far from the blends of `colours` the source guide's own pixels reach (all but its rarest
/// strays), at least [`BLEND_TOLERANCE`].
fn tolerance(source: &[([u8; 4], usize)], channels: usize, colours: &[Vec<f32>]) -> f32 {
    let mut residuals: Vec<(f32, usize)> = source
        .iter()
        .map(|(key, count)| (blend_residual(&unkey(key, channels)[..channels], colours), *count))
        .collect();
    residuals.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: usize = residuals.iter().map(|r| r.1).sum();
    let mut seen = 0;
    let mut spread = 0.0_f32;
    for (residual, count) in residuals {
        if seen as f64 >= SOURCE_SPREAD_SHARE * total as f64 {
            break;
        }
        spread = residual;
        seen += count;
    }
    spread.sqrt().max(BLEND_TOLERANCE)
}

/// The target's colours that lie farther than the tolerance from every segment colour and blend,
/// grouped by 16-level bins; a bin of at least a patch of pixels (a thousandth of the target when
/// more) is a segment. Largest first.
fn far_segments<S: ChannelImage>(source: &S, target: &FloatImage, colours: &[Vec<f32>]) -> Vec<FarSegment> {
    let channels = target.channels();
    if colours.is_empty() || colours.iter().any(|c| c.len() != channels) || source.channels() != channels {
        return Vec::new();
    }
    // A target of segment colours only (map tiles, exact guides) has no far colour whatever the
    // tolerance: no histogram is needed. Runs of one colour are checked once.
    let is_segment_colour =
        |key: &[u8; 4]| colours.iter().any(|c| squared(c, &unkey(key, channels)[..channels]) == 0.0);
    let mut previous: Option<&[f32]> = None;
    let only_segment_colours = target.data().chunks_exact(channels).all(|pixel| {
        let known = previous == Some(pixel) || is_segment_colour(&key(pixel));
        previous = Some(pixel);
        known
    });
    if only_segment_colours {
        return Vec::new();
    }
    let target_colours = histogram(target);
    let limit = tolerance(&histogram(&source.to_float_image()), channels, colours);
    let near = limit * limit;
    let mut bins: BTreeMap<[u8; 4], (usize, Vec<f64>)> = BTreeMap::new();
    for (key, count) in target_colours {
        let colour = unkey(&key, channels);
        let colour = &colour[..channels];
        let nearest = colours.iter().map(|c| squared(c, colour)).fold(f32::INFINITY, f32::min);
        if nearest <= near || blend_residual(colour, colours) <= near {
            continue;
        }
        let bin = bins.entry(key.map(|v| v >> 4)).or_insert_with(|| (0, vec![0.0; channels]));
        bin.0 += count;
        for (sum, value) in bin.1.iter_mut().zip(colour) {
            *sum += count as f64 * f64::from(*value);
        }
    }
    let least = MIN_SEGMENT_PIXELS.max(target.width() * target.height() / 1000);
    let mut far: Vec<FarSegment> = bins
        .into_values()
        .filter(|(pixels, _)| *pixels >= least)
        .map(|(pixels, sums)| {
            let colour: Vec<f32> = sums.iter().map(|s| (s / pixels as f64) as f32).collect();
            let distance = blend_residual(&colour, colours).sqrt();
            FarSegment { colour, pixels, distance, tolerance: limit }
        })
        .collect();
    far.sort_by_key(|segment| std::cmp::Reverse(segment.pixels));
    far
}

/// Labels of a pyramid level `level` (0 = finest): every `2^level`-th pixel, matching the
/// pyramid's decimation.
pub(crate) fn decimate(labels: &[u16], width: usize, height: usize, size: (usize, usize), level: usize) -> Vec<u16> {
    let step = 1usize << level;
    let mut out = Vec::with_capacity(size.0 * size.1);
    for y in 0..size.1 {
        for x in 0..size.0 {
            out.push(labels[(y * step).min(height - 1) * width + (x * step).min(width - 1)]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(colours: &[[f32; 3]]) -> FloatImage {
        FloatImage::from_data(colours.len(), 1, 3, colours.iter().flatten().copied().collect()).unwrap()
    }

    #[test]
    fn palette_labels_equal_colours_alike_on_both_sides() {
        let source = image(&[[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]);
        let target = image(&[[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]);
        let labels = label_guides(&source, &target, Segmentation::Palette, 0).unwrap();
        assert_eq!(labels.colours.len(), 2);
        assert_eq!(labels.source[0], labels.source[2]);
        assert_ne!(labels.source[0], labels.source[1]);
        assert_eq!(labels.target, vec![labels.source[1], labels.source[0]]);
    }

    #[test]
    fn fixed_colours_take_each_pixel_to_the_nearest() {
        let source = image(&[[1.0, 0.0, 0.0], [0.55, 0.0, 0.45], [0.0, 0.0, 1.0]]);
        let target = image(&[[0.4, 0.0, 0.6], [0.9, 0.05, 0.0]]);
        let colours = vec![vec![0.0, 0.0, 1.0], vec![1.0, 0.0, 0.0]];
        let labels = label_by_colours(&source, &target, colours.clone()).unwrap();
        assert_eq!(labels.colours, colours);
        assert_eq!(labels.source, vec![1, 1, 0]);
        assert_eq!(labels.target, vec![0, 1]);
    }

    /// A `width` × `height` guide of RGB colours from `colour(x, y)` (8-bit values).
    fn guide(width: usize, height: usize, colour: impl Fn(usize, usize) -> [u8; 3]) -> FloatImage {
        let data = (0..width * height).flat_map(|i| colour(i % width, i / width)).map(|v| f32::from(v) / 255.0);
        FloatImage::from_data(width, height, 3, data.collect()).unwrap()
    }

    const BLUE: [u8; 3] = [0x1e, 0x4b, 0x96];
    const SAND: [u8; 3] = [0xd8, 0xb8, 0x6a];

    /// A flat two-colour source; a target whose edge is anti-aliased (the fraction of each pixel
    /// left of a slanted line, over 4 × 4 samples) with JPEG-like noise of up to ±6 levels.
    fn anti_aliased_pair() -> (FloatImage, FloatImage) {
        let source = guide(40, 30, |x, _| if x < 20 { BLUE } else { SAND });
        let target = guide(40, 30, |x, y| {
            let left = (0..16).filter(|i| 4 * (4 * x + i % 4) < 4 * (12 + y / 2) + i / 4).count() as u32;
            let noise = ((x * 7 + y * 13) % 13) as i32 - 6;
            let mix =
                |c: usize| (f64::from(BLUE[c]) * f64::from(left) + f64::from(SAND[c]) * f64::from(16 - left)) / 16.0;
            [0, 1, 2].map(|c| (mix(c).round() as i32 + noise).clamp(0, 255) as u8)
        });
        (source, target)
    }

    #[test]
    fn anti_aliased_and_noisy_target_pixels_take_the_nearest_source_segment() {
        let (source, target) = anti_aliased_pair();
        let blends = target.data().chunks_exact(3).filter(|p| key(p)[..3] != BLUE && key(p)[..3] != SAND).count();
        assert!(blends > 600, "{blends} blended or noisy pixels");
        for mode in [Segmentation::Palette, Segmentation::KMeans(2)] {
            let labels = label_guides(&source, &target, mode, 5).unwrap();
            // The segments are the source's two colours: no blend becomes a segment of its own.
            assert_eq!(labels.colours.len(), 2, "{mode:?}");
            for (index, pixel) in target.data().chunks_exact(3).enumerate() {
                let near_blue = squared(pixel, &unkey(&[BLUE[0], BLUE[1], BLUE[2], 0], 3)[..3])
                    < squared(pixel, &unkey(&[SAND[0], SAND[1], SAND[2], 0], 3)[..3]);
                let label = usize::from(labels.target[index]);
                assert_eq!(
                    labels.colours[label] == unkey(&[BLUE[0], BLUE[1], BLUE[2], 0], 3)[..3],
                    near_blue,
                    "{index}"
                );
            }
        }
        // k-means finds the colours on the source side: the target's shades do not move them.
        let alone = label_guides(&source, &source, Segmentation::KMeans(2), 5).unwrap();
        assert_eq!(label_guides(&source, &target, Segmentation::KMeans(2), 5).unwrap().colours, alone.colours);
    }

    #[test]
    fn a_far_target_colour_is_its_own_segment_or_refused_by_name() {
        let (source, mut target) = anti_aliased_pair();
        // A 6 × 6 square of green, far from both colours and their blends.
        for y in 20..26 {
            for x in 2..8 {
                target.pixel_mut(x, y).copy_from_slice(&[0.1, 0.8, 0.1]);
            }
        }
        let labels = label_guides(&source, &target, Segmentation::Palette, 0).unwrap();
        assert_eq!(labels.colours.len(), 3);
        assert_eq!(labels.target.iter().filter(|&&l| l == 2).count(), 36);
        assert!(labels.source.iter().all(|&l| l < 2));
        let colours = labels.colours[..2].to_vec();
        let message = label_by_colours(&source, &target, colours).unwrap_err().to_string();
        assert!(message.contains("#1acc1a (36 pixels)") && message.contains("#1e4b96, #d8b86a"), "{message}");
        // No colours, or colours of another kind of guide (grey against RGB), are refused.
        assert!(matches!(label_by_colours(&source, &target, Vec::new()), Err(Error::Input(InputError::NoTextures))));
        let grey = label_by_colours(&source, &target, vec![vec![0.5]]).unwrap_err().to_string();
        assert!(grey.contains("guide of 1 channel(s) but the segment guide has 3"), "{grey}");
        // A few stray pixels are not a segment: they take the nearest.
        let (_, mut target) = anti_aliased_pair();
        target.pixel_mut(3, 3).copy_from_slice(&[0.1, 0.8, 0.1]);
        assert_eq!(label_guides(&source, &target, Segmentation::Palette, 0).unwrap().colours.len(), 2);
    }

    /// An 8-bit guide of segment colours only is labelled on its bytes as its float conversion
    /// is, a colour listed twice taking the first label; one other colour sends it to the float path.
    #[test]
    fn byte_guides_of_segment_colours_are_labelled_as_their_floats() {
        let colours: Vec<Vec<f32>> =
            [BLUE, SAND, BLUE, [0, 0, 0]].iter().map(|c| c.iter().map(|&v| f32::from(v) / 255.0).collect()).collect();
        let pick = |x: usize, y: usize| [BLUE, SAND, [0, 0, 0]][(x / 3 + y * 7 + x * y) % 3];
        let float = guide(23, 11, pick);
        let bytes: Vec<u8> = (0..23 * 11).flat_map(|i| pick(i % 23, i / 23)).collect();
        let labels = segment_colour_labels(&bytes, 3, &colours).unwrap();
        assert_eq!(labels, label_target_by_colours(&float, &float, &colours).unwrap());
        assert!(labels.contains(&0) && labels.contains(&1) && labels.contains(&3) && !labels.contains(&2));
        let mut stray = bytes.clone();
        stray[40] = 7;
        assert_eq!(segment_colour_labels(&stray, 3, &colours), None);
    }

    #[test]
    fn kmeans_groups_anti_aliased_shades() {
        let shades: Vec<[f32; 3]> = (0..40)
            .map(|i| if i < 20 { [0.1 + i as f32 * 0.002, 0.0, 0.0] } else { [0.9 - i as f32 * 0.002, 1.0, 1.0] })
            .collect();
        let source = image(&shades);
        let labels = label_guides(&source, &source, Segmentation::KMeans(2), 3).unwrap();
        assert_eq!(labels.colours.len(), 2);
        assert!(labels.source[..20].iter().all(|&l| l == labels.source[0]));
        assert!(labels.source[20..].iter().all(|&l| l == labels.source[20]));
        assert_ne!(labels.source[0], labels.source[20]);
        assert!(label_guides(&source, &source, Segmentation::Palette, 0).is_ok());
        let many: Vec<[f32; 3]> = (0..100).map(|i| [i as f32 / 100.0, 0.0, 0.0]).collect();
        let error = label_guides(&image(&many), &image(&many), Segmentation::Palette, 0).unwrap_err();
        assert!(error.to_string().contains("distinct colours"));
    }
}
