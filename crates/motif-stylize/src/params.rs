//! Parameters of the engine, with ebsynth's defaults.

use motif_core::InvalidParameter;
use motif_core::error::{check_count, check_range};

use crate::Error;

/// How the nearest-neighbour field is searched (paper §4.2; PatchMatch by Barnes et al. 2009).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum NnfMethod {
    /// Randomized PatchMatch: propagation plus random search, deterministic under parallelism
    /// (row tiles with one seeded stream each). The default; near-linear in the image sizes.
    #[default]
    PatchMatch,
    /// Brute force over every source patch: the paper's own method (§4.2). Exact but
    /// `O(|target| · |source|)`, for small images and for tests.
    Exact,
}

/// How guide colours become segment labels (paper §3.6).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Segmentation {
    /// Every distinct colour of the segment guide is a segment (at most
    /// [`MAX_PALETTE`](crate::MAX_PALETTE) colours): for flat, aliased map renders.
    Palette,
    /// Quantize the guide colours into this many clusters by k-means (seeded, deterministic):
    /// for anti-aliased guides. Range 2..=64.
    KMeans(usize),
}

/// All tunables of [`synthesize`](crate::synthesize) and
/// [`presynthesize`](crate::presynthesize). Defaults are ebsynth's.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Params {
    /// α of Eq. 4–5: weight of the style term (A' against B' patches), shared equally by the
    /// style channels. Range `[0, 1000]`, default 1.
    pub style_weight: f32,
    /// λ of Eq. 5: weight of the occurrence penalty Ω/ω_best that keeps source patches in uniform
    /// use (against wash-out). Same units as ebsynth's `-uniformity` (squared 8-bit differences).
    /// Range `[0, 1e6]`, default 3500; 0 turns the penalty off.
    pub uniformity: f32,
    /// Side of the square patches in pixels. Odd, range 3..=31, default 5.
    pub patch_size: usize,
    /// Side of the patches at the coarsest pyramid level, shrinking level by level to
    /// `patch_size` at the finest (Kwatra et al.'s coarse-to-fine patch sizes): the coarse levels,
    /// which decide the layout, see whole structures (bricks and their mortar), the fine ones keep
    /// the detail sharp. Never smaller than `patch_size`, and at every level at most what the
    /// level's images hold. 0 = `patch_size` at every level. Odd or 0, range 0..=31, default 0.
    pub coarse_patch_size: usize,
    /// Texture synthesis only: weight of the exemplar's distance-to-feature channel (Kaspar et
    /// al.'s automatic structure guidance: mortar, gaps and grooves found by a two-class split of
    /// the luminance), relative to one colour channel, at the coarsest level; it falls linearly
    /// to 0 at the finest. Regular textures keep whole elements and continuous gaps. 0 = off.
    /// Range `[0, 1000]`, default 0.
    pub structure_weight: f32,
    /// Texture synthesis only: start from an image quilt (Efros and Freeman 2001) of square
    /// blocks of this side, at most the exemplar's smaller side, and optimize at the finest level
    /// only (no pyramid): blocks keep whole elements in continuous courses, the optimization mends
    /// the seams. 0 = off (start from random patches at the coarsest level). Range 0 or 8..=4096,
    /// default 0.
    pub quilt_block: usize,
    /// Texture synthesis from a large exemplar: a pyramid level (but the coarsest) whose exemplar
    /// has more pixels than this and more than [`LOCAL_SEARCH_RATIO`](crate::LOCAL_SEARCH_RATIO)
    /// times its output's refines the matches upsampled from the coarser level: its random search
    /// stays within [`LOCAL_SEARCH_RADIUS`](crate::LOCAL_SEARCH_RADIUS) pixels of them and it runs
    /// without the occurrence penalty (nothing of the exemplar is kept per pixel), so its time
    /// grows with the output, not the exemplar. The coarser levels, on the exemplar reduced to at
    /// most this many pixels, search all of it. `usize::MAX` = every level searches the whole
    /// exemplar. Range ≥ 1, default 262 144 (512²).
    pub local_search_above: usize,
    /// Number of pyramid levels (§3.5); 0 = as many as fit (coarsest level at least
    /// `2·patch_size + 1` pixels on each side of both source and target). Range 0..=32, default 0.
    pub pyramid_levels: usize,
    /// N of Algorithm 1: search-then-vote iterations per level. Range 1..=100, default 6.
    pub search_vote_iterations: usize,
    /// PatchMatch iterations per search (propagation + random search). Range 1..=100, default 4.
    pub patchmatch_iterations: usize,
    /// ebsynth's `-stopthreshold`: after a vote, a pixel whose colour moved by less than this
    /// (largest absolute change over the style channels, 8-bit units) is considered converged; a
    /// patch is searched again only while some pixel under it still changes. The first search
    /// of every level covers every pixel. Range `[0, 1020]`, default 5; 0 searches every pixel
    /// every time.
    pub stop_threshold: f32,
    /// Nearest-neighbour search method. Default PatchMatch.
    pub nnf: NnfMethod,
    /// After the finest level, one more search-and-vote with 3×3 patches and no uniformity
    /// (ebsynth's `extrapass3x3`): sharpens fine detail. Default off.
    pub extra_pass_3x3: bool,
    /// Segment guidance (§3.6): label the segment guide's colours, compute ω_best per segment
    /// (Eq. 6) and restrict matches to the same segment. Default off (global ω_best).
    pub segments: Option<Segmentation>,
    /// Which guide (index into the input's guides, from 0) defines the segments. Default 0.
    pub segment_guide: usize,
    /// Band half-width T in pixels for pre-synthesized textures (§3.7, Table 1): pixels at
    /// distance ≥ T from every segment edge are copied from the textures, only the band is
    /// optimized; 0 = pure bitmap composition. Used only when textures are given. Range 0..=4096,
    /// default 4.
    pub band: usize,
    /// Search-vote iterations in band mode when the band starts from the textures' fields
    /// ([`crate::SegmentTexture::field`], §3.7): the start is already the textures' own
    /// solution, so fewer iterations reach nearly the energy of N from a random start (measured
    /// on the Table 1 map, band 2: 3 × 2 iterations end 7 % above 6 × 4 from random, in 40 % of
    /// the time). Without fields, band mode uses N and K. Range 1..=100, default 3.
    pub band_search_vote_iterations: usize,
    /// PatchMatch iterations per search in band mode with a seeded start (see
    /// [`band_search_vote_iterations`](Self::band_search_vote_iterations)). Range 1..=100,
    /// default 2.
    pub band_patchmatch_iterations: usize,
    /// Band mode with a seeded start only: a local search. The random search stays within
    /// [`LOCAL_SEARCH_RADIUS`](crate::LOCAL_SEARCH_RADIUS) pixels of each band pixel's match
    /// instead of ranging over the whole style (the band starts at the textures' own matches, so
    /// a local refinement keeps them and costs about half), every pixel propagates from its four
    /// neighbours' matches as they were when the iteration began, and draws its random numbers
    /// from its position in the textures' plane ([`Input::texture_origin`](crate::Input)). A
    /// band pixel's result then depends only on the picture within a few pixels of it: windows
    /// of one map with margins of `band + 2 · patch_size` pixels (map tiles) have exactly the
    /// pixels of the whole map rendered at once, when the occurrence penalty is off
    /// (`uniformity` 0). Default off.
    pub band_local_search: bool,
    /// Compute the final figures: the report's energy and source coverage, the error map and the
    /// public nearest-neighbour field. Off, the output carries the image alone (a zero energy, an
    /// empty field and error map): map tiles use nothing else, and the figures took 9 % of a
    /// tile's time. Default on.
    pub final_figures: bool,
    /// Refuse runs that would synthesize more output pixels than this (summed over the textures of
    /// a presynthesis). Default 64 000 000 (about 8 × 8 k pixels; some 15 minutes on two cores).
    pub max_pixels: usize,
    /// Refuse runs whose estimated peak memory (style and guide stacks, output, fields and vote
    /// buffers over the pyramid) passes this many bytes. Default
    /// [`DEFAULT_MAX_MEMORY`](motif_core::DEFAULT_MAX_MEMORY) (4 GiB); the CLI sets half of the
    /// machine's memory.
    pub max_memory: u64,
    /// Non-guided synthesis only: wrap patches around the borders so the output tiles seamlessly.
    /// Default off.
    pub tileable: bool,
    /// Seed of every random choice (PatchMatch, initialization, k-means). Default 0.
    pub seed: u64,
}

impl Default for Params {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl Params {
    /// The defaults (ebsynth's), as a constant: front ends declare their options' defaults from it.
    pub const DEFAULT: Self = Self {
        style_weight: 1.0,
        uniformity: 3500.0,
        patch_size: 5,
        coarse_patch_size: 0,
        structure_weight: 0.0,
        quilt_block: 0,
        local_search_above: 512 * 512,
        pyramid_levels: 0,
        search_vote_iterations: 6,
        patchmatch_iterations: 4,
        stop_threshold: 5.0,
        nnf: NnfMethod::PatchMatch,
        extra_pass_3x3: false,
        segments: None,
        segment_guide: 0,
        band: 4,
        band_search_vote_iterations: 3,
        band_patchmatch_iterations: 2,
        band_local_search: false,
        final_figures: true,
        max_pixels: 64_000_000,
        max_memory: motif_core::DEFAULT_MAX_MEMORY,
        tileable: false,
        seed: 0,
    };
}

impl Params {
    /// Checks every field's range; the first bad one is the error.
    pub fn validate(&self) -> Result<(), Error> {
        check_range("style-weight", f64::from(self.style_weight), 0.0, 1000.0)?;
        check_count("max-pixels", self.max_pixels, 1, usize::MAX)?;
        check_count("local-search-above", self.local_search_above, 1, usize::MAX)?;
        motif_core::memory::check_max_memory(self.max_memory)?;
        check_range("uniformity", f64::from(self.uniformity), 0.0, 1e6)?;
        if self.patch_size < 3 || self.patch_size.is_multiple_of(2) || self.patch_size > 31 {
            return Err(InvalidParameter::new("patch-size", self.patch_size, "must be odd and between 3 and 31").into());
        }
        if self.coarse_patch_size != 0 && (self.coarse_patch_size.is_multiple_of(2) || self.coarse_patch_size > 31) {
            return Err(InvalidParameter::new(
                "coarse-patch-size",
                self.coarse_patch_size,
                "must be 0 (off) or odd and at most 31",
            )
            .into());
        }
        check_range("structure-weight", f64::from(self.structure_weight), 0.0, 1000.0)?;
        if self.quilt_block != 0 && !(8..=4096).contains(&self.quilt_block) {
            return Err(
                InvalidParameter::new("quilt-block", self.quilt_block, "must be 0 (off) or 8–4096 pixels").into()
            );
        }
        check_range("stop-threshold", f64::from(self.stop_threshold), 0.0, 1020.0)?;
        check_count("pyramid-levels", self.pyramid_levels, 0, 32)?;
        check_count("search-vote-iters", self.search_vote_iterations, 1, 100)?;
        check_count("patchmatch-iters", self.patchmatch_iterations, 1, 100)?;
        check_count("band", self.band, 0, 4096)?;
        check_count("band-iters", self.band_search_vote_iterations, 1, 100)?;
        check_count("band-patchmatch-iters", self.band_patchmatch_iterations, 1, 100)?;
        if let Some(Segmentation::KMeans(k)) = self.segments {
            check_count("segment-count", k, 2, 64)?;
        }
        Ok(())
    }
}

// One `with_*` method per field: `Params::default().with_patch_size(7).with_uniformity(0.0)`.
motif_core::builders! { Params {
    with_style_weight => style_weight: f32,
    with_uniformity => uniformity: f32,
    with_patch_size => patch_size: usize,
    with_coarse_patch_size => coarse_patch_size: usize,
    with_structure_weight => structure_weight: f32,
    with_quilt_block => quilt_block: usize,
    with_local_search_above => local_search_above: usize,
    with_pyramid_levels => pyramid_levels: usize,
    with_search_vote_iterations => search_vote_iterations: usize,
    with_patchmatch_iterations => patchmatch_iterations: usize,
    with_stop_threshold => stop_threshold: f32,
    with_nnf => nnf: NnfMethod,
    with_extra_pass_3x3 => extra_pass_3x3: bool,
    with_segments => segments: Option<Segmentation>,
    with_segment_guide => segment_guide: usize,
    with_band => band: usize,
    with_band_search_vote_iterations => band_search_vote_iterations: usize,
    with_band_patchmatch_iterations => band_patchmatch_iterations: usize,
    with_band_local_search => band_local_search: bool,
    with_final_figures => final_figures: bool,
    with_max_pixels => max_pixels: usize,
    with_max_memory => max_memory: u64,
    with_tileable => tileable: bool,
    with_seed => seed: u64,
}}
