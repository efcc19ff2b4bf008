//! `stylize`, `texture`, `inpaint`, `zoom`, `presynth` and `video` jobs: guided patch-based
//! synthesis (`motif_stylize`).
//!
//! Field names are the flags of `motif stylize`, `motif texture` and `motif presynth`
//! (ebsynth's names where it has them). Images come decoded as 8-bit images with their channels
//! chosen by the helpers here (the front ends decode PNG or arrays to RGBA first); the engine
//! keeps them as bytes (a quarter of the memory of floats). Zoom, video and presynth work on
//! floats (their guides are computed) and convert.

use motif_core::{ByteImage, ChannelImage, InvalidParameter, Progress, RgbaImage};
use motif_stylize::{Guide, Input, Mask, NnfMethod, Output, Params, PresynthInput, SegmentTexture, Segmentation};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value, json};

use crate::JobError;

/// Channels of a decoded guide image: 4 with any transparency, else 1 when grey, else 3.
fn guide_channel_count(image: &RgbaImage) -> usize {
    if !image.is_fully_opaque() {
        4
    } else if image.pixels().iter().all(|p| p[0] == p[1] && p[1] == p[2]) {
        1
    } else {
        3
    }
}

fn channel_list(channels: usize) -> Vec<usize> {
    match channels {
        1 => vec![0],
        3 => vec![0, 1, 2],
        _ => vec![0, 1, 2, 3],
    }
}

/// A style (or texture exemplar) as the engine takes it: RGB when fully opaque, else RGBA.
pub fn style_image_channels(image: &RgbaImage) -> ByteImage {
    let channels = if image.is_fully_opaque() { 3 } else { 4 };
    ByteImage::from_rgba_channels(image, &channel_list(channels))
}

/// A guide on its own (presynth's segment guide): grey, RGB or RGBA as its pixels are.
pub fn guide_image_channels(image: &RgbaImage) -> ByteImage {
    ByteImage::from_rgba_channels(image, &channel_list(guide_channel_count(image)))
}

/// A source and target guide pair with matching channels: equal counts stay; a grey image next
/// to an RGB one is read as RGB (grey is a special RGB); transparency on one side only is a
/// mismatch the engine reports.
pub fn guide_pair(source: &RgbaImage, target: &RgbaImage) -> GuidePair {
    let (a, b) = match (guide_channel_count(source), guide_channel_count(target)) {
        (1, 3) | (3, 1) => (3, 3),
        pair => pair,
    };
    (ByteImage::from_rgba_channels(source, &channel_list(a)), ByteImage::from_rgba_channels(target, &channel_list(b)))
}

fn default_seed() -> u64 {
    1
}

/// The synthesis options every stylize-family job shares, by flag name.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Synthesis {
    seed: u64,
    style_weight: Option<f32>,
    uniformity: Option<f32>,
    patch_size: Option<usize>,
    coarse_patch_size: Option<usize>,
    structure_weight: Option<f32>,
    quilt_block: Option<usize>,
    pyramid_levels: Option<usize>,
    search_vote_iters: Option<usize>,
    patchmatch_iters: Option<usize>,
    stop_threshold: Option<f32>,
    nnf: Option<NnfMethod>,
    extra_pass_3x3: bool,
    max_pixels: Option<usize>,
    max_memory: Option<u64>,
}

impl Synthesis {
    fn params(self) -> Params {
        let d = Params::default();
        d.clone()
            .with_style_weight(self.style_weight.unwrap_or(d.style_weight))
            .with_uniformity(self.uniformity.unwrap_or(d.uniformity))
            .with_patch_size(self.patch_size.unwrap_or(d.patch_size))
            .with_coarse_patch_size(self.coarse_patch_size.unwrap_or(d.coarse_patch_size))
            .with_structure_weight(self.structure_weight.unwrap_or(d.structure_weight))
            .with_quilt_block(self.quilt_block.unwrap_or(d.quilt_block))
            .with_pyramid_levels(self.pyramid_levels.unwrap_or(d.pyramid_levels))
            .with_search_vote_iterations(self.search_vote_iters.unwrap_or(d.search_vote_iterations))
            .with_patchmatch_iterations(self.patchmatch_iters.unwrap_or(d.patchmatch_iterations))
            .with_stop_threshold(self.stop_threshold.unwrap_or(d.stop_threshold))
            .with_nnf(self.nnf.unwrap_or(d.nnf))
            .with_extra_pass_3x3(self.extra_pass_3x3)
            .with_max_pixels(self.max_pixels.unwrap_or(d.max_pixels))
            .with_max_memory(self.max_memory.unwrap_or(d.max_memory))
            .with_seed(self.seed)
    }
}

/// Declares a job struct with the shared synthesis options plus its own fields, and the
/// conversion to [`Synthesis`] (serde cannot deny unknown fields across a flattened struct, and a
/// misspelt option must be an error).
macro_rules! job_with_synthesis {
    ($(#[$meta:meta])* pub struct $name:ident { $($(#[$field_meta:meta])* pub $field:ident: $ty:ty,)* }) => {
        $(#[$meta])*
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
        #[serde(rename_all = "kebab-case", deny_unknown_fields)]
        pub struct $name {
            $($(#[$field_meta])* pub $field: $ty,)*
            /// Seed of every random choice (default 1, as on the command line).
            #[serde(default = "default_seed")]
            pub seed: u64,
            /// α: weight of the style term.
            #[serde(default)]
            pub style_weight: Option<f32>,
            /// λ: weight of the occurrence penalty (0 = off).
            #[serde(default)]
            pub uniformity: Option<f32>,
            /// Patch side in pixels (odd).
            #[serde(default)]
            pub patch_size: Option<usize>,
            /// Patch side at the coarsest level, shrinking to `patch-size` at the finest (0 = off).
            #[serde(default)]
            pub coarse_patch_size: Option<usize>,
            /// Texture synthesis: weight of the exemplar's feature-distance channel at the
            /// coarsest level (Kaspar et al.'s structure guidance; 0 = off).
            #[serde(default)]
            pub structure_weight: Option<f32>,
            /// Texture synthesis: start from an image quilt of blocks of this side, optimized at
            /// the finest level only (0 = off).
            #[serde(default)]
            pub quilt_block: Option<usize>,
            /// Pyramid levels (0 = as many as fit).
            #[serde(default)]
            pub pyramid_levels: Option<usize>,
            /// Search-then-vote iterations per level.
            #[serde(default)]
            pub search_vote_iters: Option<usize>,
            /// PatchMatch iterations per search.
            #[serde(default)]
            pub patchmatch_iters: Option<usize>,
            /// Per-pixel convergence threshold (8-bit units).
            #[serde(default)]
            pub stop_threshold: Option<f32>,
            /// `patchmatch` (default) or `exact`.
            #[serde(default)]
            pub nnf: Option<NnfMethod>,
            /// One more search-and-vote with 3×3 patches at the end.
            #[serde(default, rename = "extra-pass-3x3")]
            pub extra_pass_3x3: bool,
            /// Refuse runs that would synthesize more output pixels than this.
            #[serde(default)]
            pub max_pixels: Option<usize>,
            /// Refuse runs whose estimated peak memory passes this: bytes, or a size such as `"8G"`
            /// (default: the engine's, 4 GiB; the CLI passes half of the machine's memory).
            #[serde(default, deserialize_with = "crate::memory_size::optional")]
            pub max_memory: Option<u64>,
        }

        impl $name {
            fn synthesis(&self) -> Synthesis {
                Synthesis {
                    seed: self.seed,
                    style_weight: self.style_weight,
                    uniformity: self.uniformity,
                    patch_size: self.patch_size,
                    coarse_patch_size: self.coarse_patch_size,
                    structure_weight: self.structure_weight,
                    quilt_block: self.quilt_block,
                    pyramid_levels: self.pyramid_levels,
                    search_vote_iters: self.search_vote_iters,
                    patchmatch_iters: self.patchmatch_iters,
                    stop_threshold: self.stop_threshold,
                    nnf: self.nnf,
                    extra_pass_3x3: self.extra_pass_3x3,
                    max_pixels: self.max_pixels,
                    max_memory: self.max_memory,
                }
            }
        }
    };
}

job_with_synthesis! {
    /// Every option of `motif stylize` that is not a file.
    pub struct StylizeJob {
        /// β per guide pair, in order (none: each guide weighs 1 / number of guides).
        #[serde(default)]
        pub weight: Vec<f32>,
        /// Segment guidance with an exact palette of the segment guide's colours.
        #[serde(default)]
        pub segments: bool,
        /// Segment guidance with the segment guide quantized into this many colours (2–64).
        #[serde(default)]
        pub segment_count: Option<usize>,
        /// Which guide pair defines the segments, counted from 1 (default 1).
        #[serde(default)]
        pub segment_guide: Option<usize>,
        /// Band half-width in pixels when pre-synthesized textures are given.
        #[serde(default)]
        pub band: Option<usize>,
        /// Search-vote iterations of a band seeded by the textures' fields.
        #[serde(default)]
        pub band_iters: Option<usize>,
        /// PatchMatch iterations per search of such a band.
        #[serde(default)]
        pub band_patchmatch_iters: Option<usize>,
    }
}

job_with_synthesis! {
    /// Every option of `motif texture` that is not a file.
    pub struct TextureJob {
        /// Output size `[W, H]` in pixels.
        pub size: [usize; 2],
        /// Wrap patches around the borders so the output tiles seamlessly.
        #[serde(default)]
        pub tileable: bool,
    }
}

job_with_synthesis! {
    /// Every option of `motif inpaint` that is not a file.
    pub struct InpaintJob {}
}

job_with_synthesis! {
    /// Every option of `motif zoom` that is not a file.
    pub struct ZoomJob {
        /// Output size `[W, H]` in pixels, the same at every zoom level.
        pub size: [usize; 2],
        /// How much closer each level is than the one before (1.05–8, default 2).
        #[serde(default)]
        pub factor: Option<f64>,
        /// Zoom levels, the first unzoomed (1–64, default 4).
        #[serde(default)]
        pub levels: Option<usize>,
    }
}

job_with_synthesis! {
    /// Every option of `motif presynth` that is not a file.
    pub struct PresynthJob {
        /// Texture size `[W, H]` in pixels (default 256 × 256).
        #[serde(default)]
        pub size: Option<[usize; 2]>,
        /// Quantize the segment guide into this many colours instead of an exact palette.
        #[serde(default)]
        pub segment_count: Option<usize>,
    }
}

mod video;
pub use video::{VideoJob, video_frame, video_styles};

/// One decoded guide pair: source (the style's size) and target, with equal channel counts
/// (8-bit as decoded by default; float images work too).
pub type GuidePair<I = ByteImage> = (I, I);

/// A finished stylize or texture job.
#[derive(Debug, Clone)]
pub struct StylizeRun {
    /// The engine's output (image, field, error map and its `Report`).
    pub output: Output,
    /// The report's figures as one JSON object, the keys every front end writes.
    pub figures: Map<String, Value>,
}

/// A job from its description's defaults (an empty description, plus `fields`), so that the
/// defaults are stated once, in the serde attributes.
fn described<T: serde::de::DeserializeOwned>(fields: Value) -> T {
    serde_json::from_value(fields).expect("the defaults of a job describe a valid job")
}

impl StylizeJob {
    /// A job with every option at its default.
    pub fn new() -> Self {
        described(json!({}))
    }

    /// The engine's parameters (`textures` tells whether pre-synthesized textures are given:
    /// they imply segment guidance).
    pub fn params(&self, textures: bool) -> Result<Params, JobError> {
        let d = Params::default();
        let segments = match (self.segments, self.segment_count) {
            (_, Some(k)) => Some(Segmentation::KMeans(k)),
            (true, None) => Some(Segmentation::Palette),
            (false, None) if textures => Some(Segmentation::Palette),
            (false, None) => None,
        };
        let segment_guide = match self.segment_guide {
            Some(0) => {
                return Err(InvalidParameter::new("segment-guide", 0, "guides are counted from 1").into());
            }
            Some(index) => index - 1,
            None => d.segment_guide,
        };
        let params = self
            .synthesis()
            .params()
            .with_segments(segments)
            .with_segment_guide(segment_guide)
            .with_band(self.band.unwrap_or(d.band))
            .with_band_search_vote_iterations(self.band_iters.unwrap_or(d.band_search_vote_iterations))
            .with_band_patchmatch_iterations(self.band_patchmatch_iters.unwrap_or(d.band_patchmatch_iterations));
        params.validate()?;
        Ok(params)
    }

    /// Runs the job: the style A', the guide pairs (A, B) and, for the band mode of §3.7, the
    /// pre-synthesized textures.
    pub fn run<I: ChannelImage>(
        &self,
        style: I,
        guides: Vec<GuidePair<I>>,
        textures: Option<Vec<SegmentTexture>>,
        progress: &mut dyn Progress,
    ) -> Result<StylizeRun, JobError> {
        self.run_masked(style, guides, textures, None, progress)
    }

    /// [`StylizeJob::run`] that synthesizes only the mask's hole and keeps the rest.
    pub fn run_masked<I: ChannelImage>(
        &self,
        style: I,
        guides: Vec<GuidePair<I>>,
        textures: Option<Vec<SegmentTexture>>,
        mask: Option<Mask<I>>,
        progress: &mut dyn Progress,
    ) -> Result<StylizeRun, JobError> {
        if !self.weight.is_empty() && self.weight.len() != guides.len() {
            let allowed = format!("none or exactly one per guide ({} guides), in order", guides.len());
            return Err(InvalidParameter::new("weight", format!("{} values", self.weight.len()), allowed).into());
        }
        let params = self.params(textures.is_some())?;
        let guides = guides
            .into_iter()
            .enumerate()
            .map(|(index, (source, target))| Guide { source, target, weight: self.weight.get(index).copied() })
            .collect();
        let mut input = Input::guided(style, guides);
        input.textures = textures;
        input.mask = mask;
        let output = motif_stylize::synthesize(&input, &params, progress)?;
        let figures = figures(&output);
        Ok(StylizeRun { output, figures })
    }
}

impl Default for StylizeJob {
    fn default() -> Self {
        Self::new()
    }
}

impl TextureJob {
    /// A job for a `width × height` texture with every other option at its default.
    pub fn new(width: usize, height: usize) -> Self {
        described(json!({ "size": [width, height] }))
    }

    /// The engine's parameters.
    pub fn params(&self) -> Result<Params, JobError> {
        let params = self.synthesis().params().with_tileable(self.tileable);
        params.validate()?;
        Ok(params)
    }

    /// Runs the job on the decoded exemplar.
    pub fn run<I: ChannelImage>(&self, exemplar: I, progress: &mut dyn Progress) -> Result<StylizeRun, JobError> {
        self.run_masked(exemplar, None, progress)
    }

    /// [`TextureJob::run`] that synthesizes only the mask's hole and keeps the rest.
    pub fn run_masked<I: ChannelImage>(
        &self,
        exemplar: I,
        mask: Option<Mask<I>>,
        progress: &mut dyn Progress,
    ) -> Result<StylizeRun, JobError> {
        let params = self.params()?;
        let mut input = Input::texture(exemplar, self.size[0], self.size[1]);
        input.mask = mask;
        let output = motif_stylize::synthesize(&input, &params, progress)?;
        let figures = figures(&output);
        Ok(StylizeRun { output, figures })
    }
}

impl InpaintJob {
    /// A job with every option at its default.
    pub fn new() -> Self {
        described(json!({}))
    }

    /// Fills the `hole` of `image` (per pixel, `true` = fill) from the rest of it.
    pub fn run<I: ChannelImage>(
        &self,
        image: I,
        hole: Vec<bool>,
        progress: &mut dyn Progress,
    ) -> Result<StylizeRun, JobError> {
        let params = self.synthesis().params();
        params.validate()?;
        let output = motif_stylize::synthesize(&Input::inpaint(image, hole), &params, progress)?;
        let figures = figures(&output);
        Ok(StylizeRun { output, figures })
    }
}

impl ZoomJob {
    /// A job for `width × height` levels with every other option at its default.
    pub fn new(width: usize, height: usize) -> Self {
        described(json!({ "size": [width, height] }))
    }

    /// The whole run's estimated peak memory for `exemplar`, bytes (checked by [`ZoomJob::run`]
    /// before the first level).
    pub fn memory_bytes(&self, exemplar: &motif_core::FloatImage) -> u64 {
        let style = (exemplar.width(), exemplar.height(), exemplar.channels());
        let levels = self.levels.unwrap_or(4);
        motif_stylize::zoom_memory(style, 0, (self.size[0], self.size[1]), levels).total()
    }

    /// Synthesizes the zoom levels of a texture of `exemplar`, outermost first.
    pub fn run(
        &self,
        exemplar: motif_core::FloatImage,
        progress: &mut dyn Progress,
    ) -> Result<Vec<StylizeRun>, JobError> {
        let params = self.synthesis().params();
        params.validate()?;
        let input = Input::texture(exemplar, self.size[0], self.size[1]);
        let (factor, levels) = (self.factor.unwrap_or(2.0), self.levels.unwrap_or(4));
        let outputs = motif_stylize::zoom(&input, factor, levels, &params, progress)?;
        Ok(outputs.into_iter().map(|output| StylizeRun { figures: figures(&output), output }).collect())
    }
}

impl Default for InpaintJob {
    fn default() -> Self {
        Self::new()
    }
}

/// A mask image read as a hole: pixels at least half white and half opaque are synthesized
/// (white: synthesize, black or transparent: keep).
pub fn hole_of(mask: &RgbaImage) -> Vec<bool> {
    mask.pixels()
        .iter()
        .map(|&[r, g, b, a]| {
            let luma = 0.299 * f32::from(r) + 0.587 * f32::from(g) + 0.114 * f32::from(b);
            luma >= 127.5 && a >= 128
        })
        .collect()
}

/// The image kept outside a mask, with `channels` channels (the style's: 3 or 4; 1 for grey).
pub fn kept_image(image: &RgbaImage, channels: usize) -> ByteImage {
    ByteImage::from_rgba_channels(image, &channel_list(channels))
}

impl PresynthJob {
    /// A job with every option at its default.
    pub fn new() -> Self {
        described(json!({}))
    }

    /// The texture size (256 × 256 unless given).
    pub fn texture_size(&self) -> [usize; 2] {
        self.size.unwrap_or([256, 256])
    }

    /// The engine's parameters (segments by palette unless `segment-count` is given).
    pub fn params(&self) -> Result<Params, JobError> {
        let segments = self.segment_count.map_or(Segmentation::Palette, Segmentation::KMeans);
        let params = self.synthesis().params().with_segments(Some(segments));
        params.validate()?;
        Ok(params)
    }

    /// One seamless texture per segment of `guide` (the style's size) from `style`.
    pub fn run(
        &self,
        style: motif_core::FloatImage,
        guide: motif_core::FloatImage,
        progress: &mut dyn Progress,
    ) -> Result<Vec<SegmentTexture>, JobError> {
        let params = self.params()?;
        let [width, height] = self.texture_size();
        let input = PresynthInput { style, guide, size: (width, height) };
        Ok(motif_stylize::presynthesize(&input, &params, progress)?)
    }
}

impl Default for PresynthJob {
    fn default() -> Self {
        Self::new()
    }
}

/// The figures of a stylize or texture run under the keys of `--report`.
pub fn figures(output: &Output) -> Map<String, Value> {
    let report = &output.report;
    let value = json!({
        "energy": report.energy,
        "estimated_memory_bytes": report.estimated_memory_bytes,
        "source_coverage": report.source_coverage,
        "stages_ms": crate::stages(&report.stages_ms),
        "engine_ms": report.total_ms,
        "levels": report.levels,
        "searched_pixels": report.searched_pixels,
        "output_size": [output.image.width(), output.image.height()],
    });
    crate::object(value)
}

#[cfg(test)]
mod tests {
    use motif_core::NoProgress;
    use motif_stylize::samples::{crayon_style, map_guide};

    use super::*;

    #[test]
    fn described_jobs_run_with_the_flag_names() {
        let job: StylizeJob = serde_json::from_value(json!({
            "search-vote-iters": 2,
            "patch-size": 7,
            "segment-count": 3,
            "segment-guide": 1,
            "nnf": "patchmatch",
            "extra-pass-3x3": true,
            "seed": 4,
        }))
        .unwrap();
        let params = job.params(false).unwrap();
        assert_eq!(params.search_vote_iterations, 2);
        assert_eq!(params.patch_size, 7);
        assert_eq!(params.segments, Some(Segmentation::KMeans(3)));
        assert_eq!(params.segment_guide, 0);
        assert!(params.extra_pass_3x3);
        assert_eq!(params.uniformity, Params::default().uniformity);
        let source = map_guide(48, 40, 3, 1);
        let style = crayon_style(&source, 2);
        let target = map_guide(56, 44, 3, 3);
        let run = job.run(style.clone(), vec![(source, target)], None, &mut NoProgress).unwrap();
        assert_eq!(run.figures["output_size"], json!([56, 44]));
        let texture: TextureJob = serde_json::from_value(json!({ "size": [40, 30], "tileable": true })).unwrap();
        let run = texture.run(style, &mut NoProgress).unwrap();
        assert_eq!((run.output.image.width(), run.output.image.height()), (40, 30));
    }

    #[test]
    fn bad_descriptions_name_what_is_wrong() {
        let error = serde_json::from_value::<StylizeJob>(json!({ "patchsize": 5 })).unwrap_err();
        assert!(error.to_string().contains("patchsize"), "{error}");
        let error = serde_json::from_value::<TextureJob>(json!({ "tileable": true })).unwrap_err();
        assert!(error.to_string().contains("size"), "{error}");
        let job: StylizeJob = serde_json::from_value(json!({ "segment-guide": 0 })).unwrap();
        assert!(job.params(false).unwrap_err().to_string().contains("segment-guide"));
        let job: StylizeJob = serde_json::from_value(json!({ "patch-size": 4 })).unwrap();
        assert!(job.params(false).unwrap_err().to_string().contains("patch"));
        let job: StylizeJob = serde_json::from_value(json!({ "weight": [0.5, 0.5] })).unwrap();
        let source = map_guide(32, 32, 2, 1);
        let style = crayon_style(&source, 2);
        let error = job.run(style, vec![(source.clone(), source)], None, &mut NoProgress).unwrap_err();
        assert!(error.to_string().contains("weight"), "{error}");
    }
}
