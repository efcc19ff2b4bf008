//! `stylize`, `texture`, `inpaint`, `zoom`, `presynth` and `video` jobs: guided patch-based
//! synthesis (`motif_stylize`).
//!
//! Field names are the flags of `motif stylize`, `motif texture` and `motif presynth`
//! (ebsynth's names where it has them). Images come decoded as 8-bit images with their channels
//! chosen by the helpers here (the front ends decode PNG or arrays to RGBA first); the engine
//! keeps them as bytes (a quarter of the memory of floats). Zoom, video and presynth work on
//! floats (their guides are computed) and convert.

use motif_core::{ByteImage, InvalidParameter};
use motif_stylize::{NnfMethod, Params, Segmentation};
use serde::{Deserialize, Serialize};

use crate::JobError;
use crate::options::{Declared, Described, Joined};

fn default_seed() -> u64 {
    1
}

crate::choice_option!(NnfMethod: "patchmatch", "exact");

/// The engine's defaults, which the options take theirs from.
const DEFAULTS: Params = Params::DEFAULT;

crate::declare_options! {
    /// The synthesis options every stylize-family job shares (ebsynth's names and defaults),
    /// declared once.
    pub struct SynthesisOptions {
        /// α: weight of the style term (A' against B' patches).
        [value_name: "W", range: (0.0, 1000.0)]
        style_weight: f32 = DEFAULTS.style_weight,
        /// λ: weight of the occurrence penalty that spreads the use of source patches evenly and
        /// prevents wash-out (ebsynth's units: squared 8-bit differences); 0 = off.
        [value_name: "U", range: (0.0, 1e6)]
        uniformity: f32 = DEFAULTS.uniformity,
        /// Patch side in pixels, odd. Larger keeps bigger structures of the style.
        [value_name: "P", range: (3.0, 31.0)]
        patch_size: usize = DEFAULTS.patch_size,
        /// Patch side at the coarsest pyramid level, shrinking level by level to --patch-size at
        /// the finest: odd, or 0 for --patch-size everywhere. The coarse levels decide the
        /// layout; larger patches there keep regular structures (bricks, weaves, parquet) whole.
        /// Not given: `texture` infers it when it has no quilt (11, or 15 for an exemplar of
        /// 1024 pixels a side or more; the report's `coarse_patch_size` and
        /// `coarse_patch_size_inferred`), the other commands use --patch-size everywhere.
        [value_name: "P", range: (0.0, 31.0)]
        coarse_patch_size: Option<usize> = None,
        /// Texture synthesis: weight of the exemplar's distance to its features (mortar, gaps,
        /// grooves; found by splitting its luminance in two) as one more channel, relative to a
        /// colour channel, at the coarsest level and falling to 0 at the finest (Kaspar et al.
        /// 2015's structure guidance); 0 = off. Keeps the elements of regular textures whole.
        [value_name: "W", range: (0.0, 1000.0)]
        structure_weight: f32 = DEFAULTS.structure_weight,
        /// Texture synthesis: start from an image quilt (Efros and Freeman 2001) of square blocks
        /// of B pixels, at most the exemplar's smaller side, and optimize at the finest level only:
        /// blocks keep whole elements in continuous courses (bricks, tiles), the optimization mends
        /// the seams. 0 = off, else at least 8. Not given: `texture` infers it (half the
        /// exemplar's smaller side when the output is larger than the exemplar, else off; the
        /// report's `quilt_block` and `quilt_block_inferred`), the other commands leave it off.
        [value_name: "B", range: (0.0, 4096.0)]
        quilt_block: Option<usize> = None,
        /// Pyramid levels; 0 = as many as fit (the coarsest at least 2·P+1 pixels a side).
        [value_name: "L", range: (0.0, 32.0)]
        pyramid_levels: usize = DEFAULTS.pyramid_levels,
        /// Search-then-vote iterations per pyramid level (N of Algorithm 1).
        [value_name: "N", range: (1.0, 100.0)]
        search_vote_iters: usize = DEFAULTS.search_vote_iterations,
        /// PatchMatch iterations per search.
        [value_name: "K", range: (1.0, 100.0)]
        patchmatch_iters: usize = DEFAULTS.patchmatch_iterations,
        /// Stop improving a pixel once a vote changes it by less than this (largest channel change,
        /// 8-bit units); 0 = search every pixel every time.
        [value_name: "T", range: (0.0, 1020.0)]
        stop_threshold: f32 = DEFAULTS.stop_threshold,
        /// Nearest-neighbour search: patchmatch (fast) or exact (brute force, small images only).
        [value_name: "patchmatch|exact"]
        nnf: NnfMethod = DEFAULTS.nnf,
        /// After the finest level, one more search-and-vote with 3×3 patches and no uniformity
        /// (ebsynth's extrapass3x3): crisper fine detail.
        extra_pass_3x3: bool = DEFAULTS.extra_pass_3x3,
        /// Refuse runs that would synthesize more output pixels than this (summed over presynth's
        /// textures): a guard against a typo in a size; about 15 CPU-seconds per megapixel.
        [value_name: "N", range: (1.0, f64::MAX)]
        max_pixels: usize = DEFAULTS.max_pixels,
    }
}

impl SynthesisOptions {
    /// The engine's parameters with these options, the run's `seed` and its memory bound
    /// (`None`: the engine's).
    pub fn params(&self, seed: u64, max_memory: Option<u64>) -> Params {
        DEFAULTS
            .with_style_weight(self.style_weight)
            .with_uniformity(self.uniformity)
            .with_patch_size(self.patch_size)
            .with_coarse_patch_size(self.coarse_patch_size.unwrap_or(DEFAULTS.coarse_patch_size))
            .with_structure_weight(self.structure_weight)
            .with_quilt_block(self.quilt_block.unwrap_or(DEFAULTS.quilt_block))
            .with_pyramid_levels(self.pyramid_levels)
            .with_search_vote_iterations(self.search_vote_iters)
            .with_patchmatch_iterations(self.patchmatch_iters)
            .with_stop_threshold(self.stop_threshold)
            .with_nnf(self.nnf)
            .with_extra_pass_3x3(self.extra_pass_3x3)
            .with_max_pixels(self.max_pixels)
            .with_max_memory(max_memory.unwrap_or(DEFAULTS.max_memory))
            .with_seed(seed)
    }
}

/// Validates `params` (the engine's ranges and messages first), then every declared range of
/// `options`.
fn checked<O: Declared>(params: Params, options: &O) -> Result<Params, JobError> {
    params.validate()?;
    options.check_ranges()?;
    Ok(params)
}

crate::declare_options! {
    /// The options of `motif stylize` of its own (besides [`SynthesisOptions`]), declared once.
    pub struct StylizeOptions {
        /// β: weight of a guide. Give none (each guide then weighs 1/number of guides, as in
        /// ebsynth) or one per --guide, in the same order.
        [value_name: "W", range: (0.0, 1000.0)]
        weight: Vec<f32> = Vec::new(),
        /// Treat the colours of the segment guide as segment labels: ω_best per segment (Eq. 6) and
        /// no match across segments. The source guide's exact palette (at most 64 colours) unless
        /// --segment-count; every target pixel takes the nearest segment colour.
        segments: bool = false,
        /// Quantize the source segment guide into K colours by k-means (for anti-aliased or JPEG
        /// guides): every pixel of both guides takes the nearest; implies --segments.
        [value_name: "K", range: (2.0, 64.0)]
        segment_count: Option<usize> = None,
        /// Which --guide pair defines the segments, counted from 1.
        [value_name: "I", range: (1.0, f64::MAX)]
        segment_guide: usize = DEFAULTS.segment_guide + 1,
        /// Band half-width T in pixels for --presynth; 0 = pure bitmap composition.
        [value_name: "T", range: (0.0, 4096.0)]
        band: usize = DEFAULTS.band,
        /// Search-vote iterations for the band when the textures carry their fields (caches made
        /// by this version): the band starts at the textures' own matches, so fewer are needed.
        /// Older caches (no fields) use --search-vote-iters.
        [value_name: "N", range: (1.0, 100.0)]
        band_iters: usize = DEFAULTS.band_search_vote_iterations,
        /// PatchMatch iterations per search for such a band (else --patchmatch-iters).
        [value_name: "K", range: (1.0, 100.0)]
        band_patchmatch_iters: usize = DEFAULTS.band_patchmatch_iterations,
    }
}

crate::declare_options! {
    /// The options of `motif texture` of its own (besides [`SynthesisOptions`]), declared once.
    pub struct TextureOptions {
        /// Wrap patches around the borders so the output tiles seamlessly.
        tileable: bool = DEFAULTS.tileable,
    }
}

crate::declare_options! {
    /// The options of `motif zoom` of its own (besides [`SynthesisOptions`]), declared once.
    pub struct ZoomOptions {
        /// How much closer each level is than the one before.
        [value_name: "F", range: (1.05, 8.0)]
        factor: f64 = 2.0,
        /// Zoom levels, the first unzoomed.
        [value_name: "N", range: (1.0, 64.0)]
        levels: usize = 4,
    }
}

crate::declare_options! {
    /// The options of `motif presynth` of its own (besides [`SynthesisOptions`]), declared once.
    pub struct PresynthOptions {
        /// Quantize the guide into K colours by k-means instead of an exact palette (for
        /// anti-aliased or JPEG guides: every pixel takes the nearest).
        [value_name: "K", range: (2.0, 64.0)]
        segment_count: Option<usize> = None,
    }
}

/// The fields of a stylize-family job outside its options, as a description holds them.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub struct RunFields {
    #[serde(default = "default_seed")]
    seed: u64,
    #[serde(default, deserialize_with = "crate::memory_size::optional")]
    max_memory: Option<u64>,
}

/// The fields of a `texture` or `zoom` job outside its options: the output size too.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub struct SizedFields {
    size: [usize; 2],
    #[serde(default = "default_seed")]
    seed: u64,
    #[serde(default, deserialize_with = "crate::memory_size::optional")]
    max_memory: Option<u64>,
}

/// The fields of a `presynth` job outside its options: the optional texture size too.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub struct PresynthFields {
    #[serde(default)]
    size: Option<[usize; 2]>,
    #[serde(default = "default_seed")]
    seed: u64,
    #[serde(default, deserialize_with = "crate::memory_size::optional")]
    max_memory: Option<u64>,
}

/// Every option of `motif stylize` that is not a file: the shared synthesis options and its own.
pub type StylizeJobOptions = Joined<SynthesisOptions, StylizeOptions>;
/// Every option of `motif texture` that is not a file or the size.
pub type TextureJobOptions = Joined<SynthesisOptions, TextureOptions>;
/// Every option of `motif zoom` that is not a file or the size.
pub type ZoomJobOptions = Joined<SynthesisOptions, ZoomOptions>;
/// Every option of `motif presynth` that is not a file or the size.
pub type PresynthJobOptions = Joined<SynthesisOptions, PresynthOptions>;

/// A `stylize` job: the run's seed and memory bound, and every option ([`StylizeJobOptions`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "crate::options::Described<RunFields>")]
pub struct StylizeJob {
    /// Seed of every random choice (default 1, as on the command line).
    pub seed: u64,
    /// Refuse runs whose estimated peak memory passes this: bytes, or a size such as `"8G"`
    /// (default: the engine's, 4 GiB; the CLI passes half of the machine's memory).
    #[serde(rename = "max-memory")]
    pub max_memory: Option<u64>,
    /// Every other option.
    #[serde(flatten)]
    pub options: StylizeJobOptions,
}

impl TryFrom<Described<RunFields>> for StylizeJob {
    type Error = String;
    fn try_from(described: Described<RunFields>) -> Result<Self, String> {
        let (fields, options) = described.split()?;
        Ok(Self { seed: fields.seed, max_memory: fields.max_memory, options })
    }
}

/// A `texture` job: the output size, the run's seed and memory bound, and every option.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "crate::options::Described<SizedFields>")]
pub struct TextureJob {
    /// Output size `[W, H]` in pixels.
    pub size: [usize; 2],
    /// Seed of every random choice (default 1, as on the command line).
    pub seed: u64,
    /// Refuse runs whose estimated peak memory passes this (see [`StylizeJob::max_memory`]).
    #[serde(rename = "max-memory")]
    pub max_memory: Option<u64>,
    /// Every other option.
    #[serde(flatten)]
    pub options: TextureJobOptions,
}

impl TryFrom<Described<SizedFields>> for TextureJob {
    type Error = String;
    fn try_from(described: Described<SizedFields>) -> Result<Self, String> {
        let (fields, options) = described.split()?;
        Ok(Self { size: fields.size, seed: fields.seed, max_memory: fields.max_memory, options })
    }
}

/// An `inpaint` job: the run's seed and memory bound, and the synthesis options.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "crate::options::Described<RunFields>")]
pub struct InpaintJob {
    /// Seed of every random choice (default 1, as on the command line).
    pub seed: u64,
    /// Refuse runs whose estimated peak memory passes this (see [`StylizeJob::max_memory`]).
    #[serde(rename = "max-memory")]
    pub max_memory: Option<u64>,
    /// Every other option.
    #[serde(flatten)]
    pub options: SynthesisOptions,
}

impl TryFrom<Described<RunFields>> for InpaintJob {
    type Error = String;
    fn try_from(described: Described<RunFields>) -> Result<Self, String> {
        let (fields, options) = described.split()?;
        Ok(Self { seed: fields.seed, max_memory: fields.max_memory, options })
    }
}

/// A `zoom` job: the size of every level, the run's seed and memory bound, and every option.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "crate::options::Described<SizedFields>")]
pub struct ZoomJob {
    /// Output size `[W, H]` in pixels, the same at every zoom level.
    pub size: [usize; 2],
    /// Seed of every random choice (default 1, as on the command line).
    pub seed: u64,
    /// Refuse runs whose estimated peak memory passes this (see [`StylizeJob::max_memory`]).
    #[serde(rename = "max-memory")]
    pub max_memory: Option<u64>,
    /// Every other option.
    #[serde(flatten)]
    pub options: ZoomJobOptions,
}

impl TryFrom<Described<SizedFields>> for ZoomJob {
    type Error = String;
    fn try_from(described: Described<SizedFields>) -> Result<Self, String> {
        let (fields, options) = described.split()?;
        Ok(Self { size: fields.size, seed: fields.seed, max_memory: fields.max_memory, options })
    }
}

/// A `presynth` job: the texture size, the run's seed and memory bound, and every option.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "crate::options::Described<PresynthFields>")]
pub struct PresynthJob {
    /// Texture size `[W, H]` in pixels (default 256 × 256).
    pub size: Option<[usize; 2]>,
    /// Seed of every random choice (default 1, as on the command line).
    pub seed: u64,
    /// Refuse runs whose estimated peak memory passes this (see [`StylizeJob::max_memory`]).
    #[serde(rename = "max-memory")]
    pub max_memory: Option<u64>,
    /// Every other option.
    #[serde(flatten)]
    pub options: PresynthJobOptions,
}

impl TryFrom<Described<PresynthFields>> for PresynthJob {
    type Error = String;
    fn try_from(described: Described<PresynthFields>) -> Result<Self, String> {
        let (fields, options) = described.split()?;
        Ok(Self { size: fields.size, seed: fields.seed, max_memory: fields.max_memory, options })
    }
}

mod images;
mod run;
mod video;
pub use images::{guide_image_channels, guide_pair, hole_of, kept_image, style_image_channels};
/// The engine's types that stylize inputs and runs are made of, named here so that front ends
/// need no engine crate.
pub use motif_stylize::{
    Interval, IntervalReport, Keyframe, Mask, NearestNeighbourField, Output, SegmentTexture, VideoInput, apply_field,
    mean_flicker,
};
pub use run::{InpaintInputs, PresynthInputs, PresynthRun, StylizeInputs, StylizeRun, TextureInputs, ZoomRun, figures};
pub use video::{VideoJob, VideoJobOptions, VideoOptions, VideoRun, video_frame, video_styles};

/// One decoded guide pair: source (the style's size) and target, with equal channel counts
/// (8-bit as decoded by default; float images work too).
pub type GuidePair<I = ByteImage> = (I, I);

impl StylizeJob {
    /// A job with every option at its default.
    pub fn new() -> Self {
        Self { seed: default_seed(), max_memory: None, options: StylizeJobOptions::default() }
    }

    /// The engine's parameters (`textures` tells whether pre-synthesized textures are given:
    /// they imply segment guidance).
    pub fn params(&self, textures: bool) -> Result<Params, JobError> {
        let own = &self.options.own;
        let segments = match (own.segments, own.segment_count) {
            (_, Some(k)) => Some(Segmentation::KMeans(k)),
            (true, None) => Some(Segmentation::Palette),
            (false, None) if textures => Some(Segmentation::Palette),
            (false, None) => None,
        };
        let segment_guide = match own.segment_guide {
            0 => {
                return Err(InvalidParameter::new("segment-guide", 0, "guides are counted from 1").into());
            }
            index => index - 1,
        };
        let params = self
            .options
            .shared
            .params(self.seed, self.max_memory)
            .with_segments(segments)
            .with_segment_guide(segment_guide)
            .with_band(own.band)
            .with_band_search_vote_iterations(own.band_iters)
            .with_band_patchmatch_iterations(own.band_patchmatch_iters);
        checked(params, &self.options)
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
        Self { size: [width, height], seed: default_seed(), max_memory: None, options: TextureJobOptions::default() }
    }

    /// The engine's parameters (a quilt block given, or none: see [`TextureJob::quilt_block`]).
    pub fn params(&self) -> Result<Params, JobError> {
        let params = self.options.shared.params(self.seed, self.max_memory).with_tileable(self.options.own.tileable);
        checked(params, &self.options)
    }

    /// The quilt block for an `exemplar_size` exemplar, `masked` or not, and whether it was
    /// inferred: the one given, else [`motif_stylize::inferred_quilt_block`] where a quilt
    /// applies (no mask, structure weight or tileable output), else 0 (off).
    pub fn quilt_block(&self, exemplar_size: (usize, usize), masked: bool) -> (usize, bool) {
        let shared = &self.options.shared;
        match shared.quilt_block {
            Some(block) => (block, false),
            None if masked || self.options.own.tileable || shared.structure_weight > 0.0 => (0, true),
            None => (motif_stylize::inferred_quilt_block(exemplar_size, (self.size[0], self.size[1])), true),
        }
    }

    /// The coarse patch side for an `exemplar_size` exemplar with `quilt_block` (0: none), and
    /// whether it was inferred: the one given, else [`motif_stylize::inferred_coarse_patch_size`].
    pub fn coarse_patch_size(&self, exemplar_size: (usize, usize), quilt_block: usize) -> (usize, bool) {
        let shared = &self.options.shared;
        match shared.coarse_patch_size {
            Some(side) => (side, false),
            None => (motif_stylize::inferred_coarse_patch_size(exemplar_size, shared.patch_size, quilt_block), true),
        }
    }
}

impl InpaintJob {
    /// A job with every option at its default.
    pub fn new() -> Self {
        Self { seed: default_seed(), max_memory: None, options: SynthesisOptions::default() }
    }

    /// The engine's parameters.
    pub fn params(&self) -> Result<Params, JobError> {
        checked(self.options.params(self.seed, self.max_memory), &self.options)
    }
}

impl ZoomJob {
    /// A job for `width × height` levels with every other option at its default.
    pub fn new(width: usize, height: usize) -> Self {
        Self { size: [width, height], seed: default_seed(), max_memory: None, options: ZoomJobOptions::default() }
    }

    /// The engine's parameters for every level.
    pub fn params(&self) -> Result<Params, JobError> {
        checked(self.options.shared.params(self.seed, self.max_memory), &self.options)
    }

    /// The whole run's estimated peak memory for `exemplar`, bytes (checked by [`Job::run`](crate::Job::run)
    /// before the first level).
    pub fn memory_bytes(&self, exemplar: &motif_core::FloatImage) -> u64 {
        let style = (exemplar.width(), exemplar.height(), exemplar.channels());
        let levels = self.options.own.levels;
        motif_stylize::zoom_memory(style, 0, (self.size[0], self.size[1]), levels).total()
    }
}

impl Default for InpaintJob {
    fn default() -> Self {
        Self::new()
    }
}

impl PresynthJob {
    /// A job with every option at its default.
    pub fn new() -> Self {
        Self { size: None, seed: default_seed(), max_memory: None, options: PresynthJobOptions::default() }
    }

    /// The texture size (256 × 256 unless given).
    pub fn texture_size(&self) -> [usize; 2] {
        self.size.unwrap_or([256, 256])
    }

    /// The engine's parameters (segments by palette unless `segment-count` is given).
    pub fn params(&self) -> Result<Params, JobError> {
        let segments = self.options.own.segment_count.map_or(Segmentation::Palette, Segmentation::KMeans);
        let params = self.options.shared.params(self.seed, self.max_memory).with_segments(Some(segments));
        checked(params, &self.options)
    }
}

impl Default for PresynthJob {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests;
