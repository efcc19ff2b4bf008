//! Guided patch-based stylization and texture synthesis, after Texler, "Example-Based
//! Stylization of Navigation Maps on Mobile Devices" (and Kwatra's texture optimization, StyLit's
//! guided energy, Kaspar's occurrence penalty, as in ebsynth).
//!
//! Given a style A' with its guides A and target guides B, [`synthesize`] produces B' so that
//! A : A' :: B : B'. Without guides it synthesizes a texture of any size (optionally tileable).
//!
//! Modules, by section of the paper:
//! - `params`: every tunable with ebsynth's defaults (α, λ of Eq. 5, patch size, levels, N).
//! - `level`: one pyramid level with all channels stacked as 8-bit values (as ebsynth stores
//!   them) so the weighted patch distance of Eq. 4 is a sum over contiguous rows against one row
//!   of per-channel weights (any number of 1/3/4-channel guides, each with its own weight; target
//!   guides of any size).
//! - `occurrence`: the occurrence map Ω and penalty λ·Ω/ω_best of Eq. 5, ω_best global or
//!   per segment (Eq. 6).
//! - `search`: nearest-neighbour fields (Eq. 2): deterministic parallel PatchMatch and the
//!   exact brute-force search of §4.2; `search::local_band`, the band's local search (§3.7),
//!   keyed by the pixel's place in the textures' plane so that a map's tiles agree.
//! - `vote`: voting, the E-step of §3.3 (patch weights rounded to 16 bits, so a saved field holds them).
//! - `synthesis`: Algorithm 1, multi-resolution EM with Gaussian pyramids and field
//!   upsampling (§3.5), the optional 3×3 pass, the report; `outcome`: the figures of the final
//!   field (energy parts, coverage, error map) and the field in public form.
//! - `native`: for an exemplar much larger than the output, the coarse levels search the whole
//!   (reduced) exemplar and the finer ones refine the upsampled matches within a few pixels
//!   ([`Params::local_search_above`]), so the time grows with the output, not the exemplar.
//! - `segments`: segment labels from guide colours, exact palette or k-means (`segments/kmeans`)
//!   (§3.6); an 8-bit target guide of segment colours only (a map tile's) is labelled on its bytes.
//! - `centres`: each segment's valid source centres and their box, where the random search draws
//!   in-segment candidates and drops far ones by position (§3.6's restriction).
//! - `mask`: masks (ebsynth's) and inpainting: only the hole is synthesized, the rest kept.
//! - `presynth`: one seamless texture per segment of the source guide, made once (§3.7), and
//!   the same one zoom level closer, twice the side, guided by it magnified (§5.3's zoom guide).
//! - `prepared`: the style side of band mode made once for many targets (a slippy map's tiles):
//!   [`prepare`] and [`Input::prepared`].
//! - `band`: the edge band and texture composition of the pre-synthesized speed-up (§3.7), and
//!   the composition of the textures' fields that starts the band's search.
//! - `field`: the public nearest-neighbour field with the final vote's weights, its PNG encodings and
//!   re-application (the same style gives back the output).
//! - `zoom` (§5.3): infinite zoom, every level synthesized at full resolution and guided by the
//!   centre of the level above.
//! - `motion` and `video`: video stylization from keyframes (Jamriška et al. 2019): motion by
//!   the engine's own PatchMatch, edge, positional and temporal guides, forward and backward
//!   passes blended between keyframes, in independent keyframe intervals.
//! - `video_pass`: one pass of video synthesis from a keyframe along the motion, and the blend of
//!   the passes from an interval's two keyframes (Jamriška et al. §3).
//! - `structure_fidelity`: the nearest-patch distance at a large patch size, a figure that sees whether a
//!   texture keeps its exemplar's structure.
//! - `structure_guidance`: Kaspar et al. 2015's automatic structure guidance for texture synthesis
//!   (the distance to the exemplar's gaps as a channel weighted at the coarse levels), and
//!   [`mean_feature_distance`] and [`line_contrast`], figures that see merged or cut elements and
//!   broken courses.
//! - `quilting`: image quilting (Efros and Freeman 2001) as the start of texture optimization
//!   ([`Params::quilt_block`]): whole elements in continuous courses, mended at the finest level;
//!   [`inferred_quilt_block`], the block `motif texture` uses when none is given, and
//!   [`inferred_coarse_patch_size`], its coarse patch side when there is no quilt.
//! - [`samples`]: seeded map-like guides and styles for demos and benchmarks.
//!
//! All randomness comes from [`motif_core::SeedStreams`] keyed by (level, iteration, tile), and
//! every parallel reduction has a fixed order: the same seed gives the same bytes on any number
//! of threads.
//!
//! The crate does no I/O and builds for `wasm32`.
//!
//! ```
//! use motif_core::NoProgress;
//! use motif_stylize::samples::{crayon_style, map_guide};
//! use motif_stylize::{Guide, Input, Params, synthesize};
//!
//! // A 48 × 40 map guide A with its crayon style A', and a new 56 × 44 guide B to paint.
//! let source = map_guide(48, 40, 3, 1);
//! let style = crayon_style(&source, 2);
//! let target = map_guide(56, 44, 3, 3);
//! let params = Params::default().with_search_vote_iterations(2).with_seed(5);
//! params.validate().unwrap();
//! let input = Input::guided(style, vec![Guide { source, target, weight: None }]);
//! let output = synthesize(&input, &params, &mut NoProgress).unwrap();
//! assert_eq!((output.image.width(), output.image.height()), (56, 44));
//! assert!(output.report.energy.total > 0.0 && output.report.source_coverage > 0.1);
//! ```

mod band;
mod centres;
mod error;
mod field;
mod level;
mod mask;
mod motion;
mod native;
mod occurrence;
mod outcome;
mod params;
mod prepared;
mod presynth;
mod quilting;
pub mod samples;
mod search;
mod segments;
mod structure_fidelity;
mod structure_guidance;
mod synthesis;
mod video;
mod video_pass;
mod vote;
mod zoom;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_mask;
#[cfg(test)]
mod tests_native;
#[cfg(test)]
mod tests_synthesis;
#[cfg(test)]
mod tests_video;

use motif_core::{ChannelImage, FloatImage, InvalidParameter, Progress};
use serde::Serialize;

pub use error::{Error, InputError, LimitError};
pub use field::{NearestNeighbourField, apply_field};
pub use mask::Mask;
pub use motion::{MotionField, coordinate_guide, edge_guide, estimate_motion, flicker};
pub use native::{LOCAL_SEARCH_RADIUS, LOCAL_SEARCH_RATIO};
pub use params::{NnfMethod, Params, Segmentation};
pub use prepared::{PreparedStyle, prepare};
pub use presynth::{PresynthInput, presynth_memory, presynthesize, presynthesize_closer};
pub use quilting::{inferred_coarse_patch_size, inferred_quilt_block};
pub use segments::{BLEND_TOLERANCE, MAX_PALETTE, SegmentLabels, label_by_colours, label_guides};
pub use structure_fidelity::{nearest_patch_distance, sharpness};
pub use structure_guidance::{line_contrast, mean_feature_distance};
pub use video::{
    Interval, IntervalOutput, IntervalReport, Keyframe, VIDEO_MEMORY_ADVICE, VideoInput, VideoOutput, VideoParams,
    VideoReport, intervals, mean_flicker, stylize_interval, stylize_video, video_memory,
};
pub use zoom::{zoom, zoom_memory};

/// One guide pair: a source guide (aligned with the style) and the matching target guide.
///
/// Images are [`FloatImage`]s or, to hold a quarter of the memory, 8-bit
/// [`ByteImage`](motif_core::ByteImage)s (what the front ends decode); one kind per [`Input`].
#[derive(Debug, Clone, PartialEq)]
pub struct Guide<I = FloatImage> {
    /// Source guide A (same size as the style), 1, 3 or 4 channels, values in `[0, 1]`.
    pub source: I,
    /// Target guide B (any size, the same for all guides), same channel count as `source`.
    pub target: I,
    /// β of Eq. 4 for this guide, shared by its channels; `None` = 1 / number of guides
    /// (ebsynth's default). Range `[0, 1000]`.
    pub weight: Option<f32>,
}

/// A pre-synthesized texture of one segment (§3.7).
#[derive(Debug, Clone, PartialEq)]
pub struct SegmentTexture {
    /// The segment's colour in the segment guide (values in `[0, 1]`, the guide's channels).
    pub colour: Vec<f32>,
    /// The texture (tiles seamlessly), the style's channel count.
    pub image: FloatImage,
    /// Where each texture pixel came from: the presynthesis field (texture size, source = the
    /// style). Band pixels start from it (at the composed position's source patch), so pixels
    /// next to the band's edge begin at their true matches and propagation spreads them at once
    /// (§3.7); `None` = random start. [`presynthesize`] fills it.
    pub field: Option<NearestNeighbourField>,
}

/// What to synthesize: float images ([`FloatImage`], the default) or 8-bit ones
/// ([`ByteImage`](motif_core::ByteImage), a quarter of the memory; values `v / 255`).
#[derive(Debug, Clone, PartialEq)]
pub struct Input<I = FloatImage> {
    /// The style exemplar A' (or the texture exemplar), 1, 3 or 4 channels, values in `[0, 1]`.
    pub style: I,
    /// Guide pairs; empty for non-guided texture synthesis.
    pub guides: Vec<Guide<I>>,
    /// Output size `(width, height)`: required without guides, else must equal the target
    /// guides' size (or be `None`).
    pub size: Option<(usize, usize)>,
    /// Pre-synthesized textures, one per segment: fill everything outside the band around
    /// segment edges from them and optimize only the band (§3.7). Needs guides. Shared (`Arc`):
    /// a tile server hands the same textures to every tile without copying them.
    pub textures: Option<std::sync::Arc<[SegmentTexture]>>,
    /// Synthesize only the masked pixels and keep the others exactly.
    pub mask: Option<Mask<I>>,
    /// Where the output's top-left pixel lies in the textures' plane: output pixel `(x, y)` takes
    /// texture pixel `((x + origin.0) mod w, (y + origin.1) mod h)`, and the band's local search
    /// ([`Params::band_local_search`]) keys its random draws by that position. Windows of one
    /// large picture (a slippy map's tiles) pass their own top-left; `(0, 0)` otherwise.
    pub texture_origin: (i64, i64),
    /// With textures: their style side made once by [`prepare`] from an input with this style,
    /// these source guides, weights and texture colours (checked; refused otherwise), so that a
    /// run stacks and labels only its target. The same output as without it.
    pub prepared: Option<std::sync::Arc<PreparedStyle<I>>>,
}

impl<I: ChannelImage> Input<I> {
    /// Guided stylization of the target guides' size.
    pub fn guided(style: I, guides: Vec<Guide<I>>) -> Self {
        Self { style, guides, size: None, textures: None, mask: None, texture_origin: (0, 0), prepared: None }
    }

    /// Non-guided texture synthesis of `width × height` from `exemplar`.
    pub fn texture(exemplar: I, width: usize, height: usize) -> Self {
        Self { size: Some((width, height)), ..Self::guided(exemplar, Vec::new()) }
    }

    /// Inpainting: fills the `hole` of `image` (per pixel, row by row, `true` = fill) from the
    /// rest of the image, with the occurrence penalty so the fill does not clone one patch.
    pub fn inpaint(image: I, hole: Vec<bool>) -> Self {
        let size = Some((image.width(), image.height()));
        let mask = Mask { keep: image.clone(), hole, exclude_hole_from_style: true };
        Self { size, mask: Some(mask), ..Self::guided(image, Vec::new()) }
    }
}

/// Mean per-pixel energy of Eq. 5 and its parts (squared 8-bit differences, weighted).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EnergyParts {
    /// style + guide + occurrence.
    pub total: f64,
    /// α · patch distance between A' and B'.
    pub style: f64,
    /// Σ β · patch distance between A and B.
    pub guide: f64,
    /// λ · Ω / ω_best.
    pub occurrence: f64,
}

/// What happened on one pyramid level.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LevelReport {
    /// Stage name ("level 2 of 5", "extra 3×3 pass").
    pub name: String,
    /// Target width at this level.
    pub width: usize,
    /// Target height at this level.
    pub height: usize,
    /// Patch side used.
    pub patch_size: usize,
    /// Whether the level refined the matches upsampled from the coarser one (random search within
    /// [`LOCAL_SEARCH_RADIUS`] pixels, no occurrence penalty: [`Params::local_search_above`])
    /// instead of searching the whole exemplar.
    pub local_search: bool,
    /// Mean per-pixel energy after each search (before its vote), one per iteration.
    pub energies: Vec<f64>,
    /// Wall-clock milliseconds.
    pub ms: f64,
}

/// The result of [`synthesize`].
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    /// B', the style's channel count, values in `[0, 1]`.
    pub image: FloatImage,
    /// The final nearest-neighbour field.
    pub field: NearestNeighbourField,
    /// Per-pixel energy (patch distance + penalty) of the final field, 1 channel; 0 outside
    /// the band in band mode.
    pub error_map: FloatImage,
    /// Figures of the run.
    pub report: Report,
}

/// Figures of a run of [`synthesize`], for reports.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Final mean per-pixel energy of the output and its parts.
    pub energy: EnergyParts,
    /// Fraction of source patches used by at least one output patch.
    pub source_coverage: f64,
    /// One report per level, coarsest first (plus the 3×3 pass).
    pub levels: Vec<LevelReport>,
    /// Milliseconds per stage (per level), in order.
    pub stages_ms: Vec<(String, f64)>,
    /// Total milliseconds.
    pub total_ms: f64,
    /// Number of target patches that were optimized (all, or the band's in §3.7 mode).
    pub searched_pixels: usize,
    /// The run's estimated peak memory, bytes (checked against `max-memory` before allocating).
    pub estimated_memory_bytes: u64,
}

fn size_of(image: &impl ChannelImage) -> String {
    format!("{}×{}", image.width(), image.height())
}

fn check_image(image: &impl ChannelImage, what: &str) -> Result<(), Error> {
    if image.width() == 0 || image.height() == 0 {
        return Err(Error::Input(InputError::EmptyImage(what.to_string())));
    }
    if ![1, 3, 4].contains(&image.channels()) {
        return Err(Error::Input(InputError::UnsupportedChannels {
            what: what.to_string(),
            channels: image.channels(),
        }));
    }
    Ok(())
}

/// Refuses work on more than `max_pixels` output pixels before anything is allocated for it.
fn check_work(pixels: usize, max_pixels: usize) -> Result<(), Error> {
    if pixels > max_pixels { Err(Error::Limit(LimitError::TooMuchWork { pixels, max_pixels })) } else { Ok(()) }
}

/// The peak memory of one synthesis: the inputs with their coarser pyramid levels (4/3 of the
/// finest, `sample_bytes` a value: 1 for 8-bit inputs, 4 for floats), the finest level's 8-bit
/// patch stacks, the output with the vote's weights and change flags, the field with its costs
/// and the occurrence counts with the search workers' changes over `occurrence_pixels` of the
/// style (all of it, unless the finer levels refine upsampled matches without them; the public
/// field made at the end replaces the stacks).
pub(crate) fn memory_estimate(
    style_pixels: usize,
    style_channels: usize,
    guide_channels: usize,
    target_pixels: usize,
    sample_bytes: usize,
    occurrence_pixels: usize,
) -> motif_core::MemoryEstimate {
    const PYRAMID: f64 = 4.0 / 3.0;
    let (style_pixels, target_pixels) = (style_pixels as f64, target_pixels as f64);
    let (style_channels, guide_channels, sample_bytes) =
        (style_channels as f64, guide_channels as f64, sample_bytes as f64);
    let mut estimate = motif_core::MemoryEstimate::new();
    estimate
        .add("style and source guides", style_pixels * PYRAMID, (style_channels + guide_channels) * sample_bytes)
        .add("target guides", target_pixels * PYRAMID, guide_channels * sample_bytes)
        .add("patch stacks", style_pixels + target_pixels, style_channels + guide_channels)
        .add("output and vote", target_pixels, style_channels * 4.0 + 5.0)
        .add("nearest-neighbour field", target_pixels, 8.0)
        // The counts, and the changes each search worker keeps (two workers counted).
        .add("occurrence counts", occurrence_pixels as f64, 12.0);
    estimate
}

/// Bytes per stored value of an input image.
fn sample_bytes(image: &impl ChannelImage) -> usize {
    match image.samples() {
        motif_core::Samples::Float(_) => 4,
        motif_core::Samples::Byte(_) => 1,
    }
}

const MEMORY_ADVICE: &str = "use a smaller size or fewer guides";

/// Most guide channels in all (so a patch row's integer sum of squares cannot overflow).
pub const MAX_GUIDE_CHANNELS: usize = 252;

/// Per-channel weights: an image's weight shared equally by its channels (as ebsynth does).
fn channel_weights(weight: f32, channels: usize) -> impl Iterator<Item = f32> {
    std::iter::repeat_n(weight / channels as f32, channels)
}

/// Stylizes (with guides) or synthesizes a texture (without), per the paper's Algorithm 1.
///
/// Validates everything first: images non-empty with 1, 3 or 4 channels, source guides the
/// style's size, target guides one common size, guide pairs with equal channels, parameters in
/// range. Progress is reported per level.
pub fn synthesize<I: ChannelImage>(
    input: &Input<I>,
    params: &Params,
    progress: &mut dyn Progress,
) -> Result<Output, Error> {
    params.validate()?;
    check_images(input, params.patch_size)?;
    let target_size = target_size(input)?;
    check_work(target_size.0 * target_size.1, params.max_pixels)?;
    let estimated_memory_bytes = check_memory(input, params, target_size)?;
    let style = &input.style;
    let prepared = input.prepared.as_deref();
    if let Some(prepared) = prepared {
        prepared.check(input, params)?;
    }
    let (style_weights, guide_weights) = weights(input, params);
    let labels = segments::segment_labels(input, params)?;
    let (composition, seeds) = match (&input.textures, &labels) {
        (Some(textures), Some((_, target_labels, _))) => {
            let style_shape = (style.width(), style.height(), style.channels());
            let target = band::Target { size: target_size, origin: input.texture_origin };
            let (composed, domain, seeds) =
                band::compose_textures(textures, target_labels, style_shape, target, params.band)?;
            (Some((composed, domain)), seeds)
        }
        _ => (None, None),
    };
    if let Some(mask) = &input.mask {
        mask::check(mask, style, target_size, params.patch_size, input.textures.is_some())?;
    }
    let texture_only = input.guides.is_empty() && input.mask.is_none() && input.textures.is_none();
    let quilting_start = motif_core::timing::Clock::now();
    let seeds = if params.quilt_block > 0 {
        Some(quilted_start(style, target_size, params, texture_only, progress)?)
    } else {
        seeds
    };
    let quilting_ms = (params.quilt_block > 0).then(|| motif_core::timing::elapsed_ms(quilting_start));
    if params.structure_weight > 0.0 {
        if !texture_only {
            let allowed = "applies to texture synthesis only (no guides, mask or textures); 0 turns it off";
            return Err(InvalidParameter::new("structure-weight", params.structure_weight, allowed).into());
        }
        let mut output =
            structure_guidance::synthesize_with_structure(style, &style_weights, target_size, params, progress)?;
        output.report.estimated_memory_bytes = estimated_memory_bytes;
        return Ok(output);
    }
    let problem = synthesis::Problem {
        style,
        // Guides stay as given (one borrowed image each, no stacked copy): the level stacks their
        // channels as it quantizes them.
        source_guides: input.guides.iter().map(|g| &g.source).collect(),
        target_guides: input.guides.iter().map(|g| &g.target).collect(),
        style_weights,
        guide_weights,
        target_size,
        labels,
        tileable: params.tileable,
        composition,
        seeds,
        origin: input.texture_origin,
        mask: input.mask.as_ref(),
        structure_weight: None,
        prepared,
    };
    let mut output = synthesis::run(problem, params, progress)?;
    output.report.estimated_memory_bytes = estimated_memory_bytes;
    if let Some(ms) = quilting_ms {
        output.report.stages_ms.insert(0, ("quilting".to_string(), ms));
        output.report.total_ms += ms;
    }
    Ok(output)
}

/// Checks the style (non-empty, 1, 3 or 4 channels, at least a patch a side) and every guide
/// pair: the source the style's size, the target the first target's, equal channels, the weight
/// in range.
fn check_images<I: ChannelImage>(input: &Input<I>, patch: usize) -> Result<(), Error> {
    let style = &input.style;
    check_image(style, "style")?;
    if style.width() < patch || style.height() < patch {
        return Err(Error::Input(InputError::StyleTooSmall { width: style.width(), height: style.height(), patch }));
    }
    for (index, guide) in input.guides.iter().enumerate() {
        let number = index + 1;
        check_image(&guide.source, &format!("source guide {number}"))?;
        check_image(&guide.target, &format!("target guide {number}"))?;
        if guide.source.width() != style.width() || guide.source.height() != style.height() {
            return Err(Error::Input(InputError::SizeMismatch {
                what: "a source guide must have the style's size".into(),
                first: "the style".into(),
                first_size: size_of(style),
                second: format!("source guide {number}"),
                second_size: size_of(&guide.source),
            }));
        }
        if guide.source.channels() != guide.target.channels() {
            return Err(Error::Input(InputError::ChannelMismatch {
                index: number,
                source_channels: guide.source.channels(),
                target_channels: guide.target.channels(),
            }));
        }
        let first = &input.guides[0].target;
        if guide.target.width() != first.width() || guide.target.height() != first.height() {
            return Err(Error::Input(InputError::SizeMismatch {
                what: "all target guides must have the same size".into(),
                first: "target guide 1".into(),
                first_size: size_of(first),
                second: format!("target guide {number}"),
                second_size: size_of(&guide.target),
            }));
        }
        if let Some(weight) = guide.weight {
            motif_core::error::check_range(&format!("weight of guide {number}"), f64::from(weight), 0.0, 1000.0)?;
        }
    }
    Ok(())
}

/// The output's size: the target guides', or the size asked for without guides.
fn target_size<I: ChannelImage>(input: &Input<I>) -> Result<(usize, usize), Error> {
    match (input.guides.first(), input.size) {
        (Some(guide), Some(size)) if size != (guide.target.width(), guide.target.height()) => {
            Err(Error::Input(InputError::SizeMismatch {
                what: "the output size must equal the target guides' size".into(),
                first: "the output".into(),
                first_size: format!("{}×{}", size.0, size.1),
                second: "target guide 1".into(),
                second_size: size_of(&guide.target),
            }))
        }
        (Some(guide), _) => Ok((guide.target.width(), guide.target.height())),
        (None, Some((w, h))) => {
            if w == 0 || h == 0 {
                return Err(Error::Input(InputError::EmptyImage("output".into())));
            }
            if w > 1 << 15 || h > 1 << 15 {
                return Err(InvalidParameter::new("size", format!("{w}×{h}"), "must be at most 32768 a side").into());
            }
            Ok((w, h))
        }
        (None, None) => Err(Error::Input(InputError::MissingTargetSize)),
    }
}

/// Checks the run's estimated peak memory against [`Params::max_memory`] and returns it, then
/// the guides' channels against [`MAX_GUIDE_CHANNELS`].
fn check_memory<I: ChannelImage>(input: &Input<I>, params: &Params, target_size: (usize, usize)) -> Result<u64, Error> {
    let style = &input.style;
    let guide_channels: usize = input.guides.iter().map(|g| g.source.channels()).sum();
    let (style_pixels, target_pixels) = (style.width() * style.height(), target_size.0 * target_size.1);
    let texture_only = input.guides.is_empty() && input.mask.is_none() && input.textures.is_none();
    // Texture synthesis from a large exemplar: the levels that keep Ω have at most
    // `local_search_above` exemplar pixels (`synthesis::is_local`).
    let local = texture_only
        && params.quilt_block == 0
        && style_pixels > params.local_search_above
        && style_pixels > LOCAL_SEARCH_RATIO * target_pixels;
    let occurrence_pixels = if local { params.local_search_above } else { style_pixels };
    let mut estimate = memory_estimate(
        style_pixels,
        style.channels(),
        guide_channels,
        target_pixels,
        sample_bytes(style),
        occurrence_pixels,
    );
    if params.quilt_block > 0 {
        // The quilt reads the exemplar as floats and lays the output as floats with its origins.
        estimate.add("image quilt", style_pixels as f64, style.channels() as f64 * 4.0);
        estimate.add("quilted output", target_pixels as f64, style.channels() as f64 * 4.0 + 8.0);
    }
    if input.mask.is_some() {
        // The kept image with its pyramid, the hole per level and its dilations, and the fill's
        // start (measured: 46–48 bytes a pixel beyond the rest, 77 k to 1.2 M pixels).
        estimate.add("mask and fill", target_pixels as f64, 48.0);
    }
    let estimated_memory_bytes = estimate.check(params.max_memory, MEMORY_ADVICE)?;
    if guide_channels > MAX_GUIDE_CHANNELS {
        return Err(InvalidParameter::new(
            "guide",
            format!("{} guides with {guide_channels} channels", input.guides.len()),
            format!("must have at most {MAX_GUIDE_CHANNELS} channels in all"),
        )
        .into());
    }
    Ok(estimated_memory_bytes)
}

/// Per-channel weights of the style (α) and of the guides' channels in order (β of each guide,
/// 1 / number of guides by default).
fn weights<I: ChannelImage>(input: &Input<I>, params: &Params) -> (Vec<f32>, Vec<f32>) {
    let style_weights: Vec<f32> = channel_weights(params.style_weight, input.style.channels()).collect();
    let mut guide_weights = Vec::new();
    for guide in &input.guides {
        let weight = guide.weight.unwrap_or(1.0 / input.guides.len() as f32);
        guide_weights.extend(channel_weights(weight, guide.source.channels()));
    }
    (style_weights, guide_weights)
}

/// The image quilt that starts texture optimization ([`Params::quilt_block`]), as a starting
/// field; refused outside plain texture synthesis.
fn quilted_start<I: ChannelImage>(
    style: &I,
    target_size: (usize, usize),
    params: &Params,
    texture_only: bool,
    progress: &mut dyn Progress,
) -> Result<Vec<u32>, Error> {
    if !texture_only || params.structure_weight > 0.0 || params.tileable {
        let allowed = "applies to texture synthesis only (no guides, mask, textures, structure weight or \
            tileable output); 0 turns it off";
        return Err(InvalidParameter::new("quilt-block", params.quilt_block, allowed).into());
    }
    quilting::starting_field(style, target_size, params, progress)
}
