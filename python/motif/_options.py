"""The keyword options of each engine, rendered from motif-jobs' declarations (do not edit).

Regenerate with `MOTIF_BLESS=1 cargo test --release -p motif-jobs --test declarations`.
"""

from typing import Any, Literal, Mapping, Sequence, TypedDict


class PointsOptions(TypedDict, total=False):
    """Options of `motif.points()` and `motif points`."""

    #: Refuse domains that ask for more points than this at the exemplar's density (a guard against a unit
    #: mix-up; about 2 minutes of work per 150 000 points on two cores). Allowed: 1–100000000. Default: 150000.
    max_points: int
    #: Initialization: exemplar patches (default; each starts matched to where it came from) or random points
    #: (the paper's robustness claim does not hold on real, irregular exemplars). Default: patches.
    init: Literal["random", "patches"]
    #: Side of the copied patches, in units of the neighbourhood δ (capped at 0.7 of the exemplar's smallest
    #: side). Allowed: 1–20. Default: 6.
    patch_size: float
    #: Candidate sources judged for each patch: the one whose surroundings agree best with the points already
    #: placed around the patch is copied. 1 copies a random source. Allowed: 1–256. Default: 48.
    patch_candidates: int
    #: Balancing of patch sources (0 takes the best-scored candidate): of the candidates scored within this
    #: fraction of the best, the one whose exemplar points were copied least so far is taken, so that every
    #: part of the exemplar is copied about equally often. Allowed: 0–10. Default: 0.5.
    patch_balance: float
    #: Which points the optimization moves after a patch initialization: the seams between patches (default; on
    #: real exemplars moving the copies' interiors lowered fidelity), every point, or none (the patches are the
    #: output). Default: seams.
    refine: Literal["seams", "everywhere", "none"]
    #: Gradient steps of the pair-statistics refinement after the optimization (0 turns it off): the points the
    #: optimization moved move again so that the output's pair distances and nearest-neighbour distances follow
    #: the exemplar's. Flat domains at a uniform scale only. Allowed: 0–1000. Default: 40.
    statistics_iterations: int
    #: The window the exemplar was observed in: `W,H[,D]` from the origin, or its corners `X0,Y0,X1,Y1`
    #: (`X0,Y0,Z0,X1,Y1,Z1` in 3D). It must hold every point. The exemplar's density is its count over this
    #: window; without it, the bounding box grown by one mean spacing per axis (right for lattices, too dense
    #: for sparse irregular patterns).
    exemplar_window: Sequence[float]
    #: Attributes to synthesize (default: every float column other than x, y, z, element, plus integer
    #: columns).
    attributes: Sequence[str]
    #: Attributes with discrete values (snapped to the exemplar's values after each step). Integer columns are
    #: always discrete.
    discrete: Sequence[str]
    #: Attributes never treated as discrete. Without it, attributes whose exemplar values are all whole numbers
    #: (at most 32 distinct) are detected as discrete labels.
    continuous: Sequence[str]
    #: Weight of an attribute against point density, `NAME=W` (repeatable). Every attribute is divided by its
    #: exemplar standard deviation first, so units and ranges do not matter; the default weight is 1. Allowed:
    #: 0–100.
    attribute_weight: Mapping[str, float]
    #: Window shape: Gaussian, truncated at --window-cutoff × δ, or the box |s| < δ. Default: gaussian.
    window: Literal["gaussian", "box"]
    #: Gaussian width σ (exemplar units, > 0). Default: half the exemplar's mean nearest-neighbour spacing.
    sigma: float
    #: Uniform rotation field in degrees (counter-clockwise in the xy-plane), added to a stroke's tangent
    #: orientation. Default: 0.
    rotation: float
    #: Uniform scale field (> 0), multiplied with --scale-along. Default: 1.
    scale: float
    #: Quadrature grid spacing in units of σ (2 = the exemplar's point spacing). Default: 2, or an eighth of
    #: the neighbourhood when that is coarser (wide windows). Allowed: 0.25–4.
    quadrature_spacing: float
    #: Truncation radius of the Gaussian window, in units of the neighbourhood δ (its weight there is
    #: exp(-c²)). Smaller is faster. Allowed: 1.5–4. Default: 2.
    window_cutoff: float
    #: Sampling-control rounds per window size. Allowed: 1–20. Default: 1.
    sampling_rounds: int
    #: Gradient iterations of each position merging step (§7.1 uses 30). Allowed: 1–1000. Default: 30.
    merge_iterations: int
    #: Random starts of each quadrature point's matching search. Allowed: 1–64. Default: 5.
    matching_starts: int
    #: Descent iterations per matching start. Allowed: 1–200. Default: 8.
    matching_iterations: int
    #: Window shrink factor per scale α. Default: 0.9 (§7.1), or 0.8 after patches with --refine seams (the
    #: same fidelity in less time on the real-data corpus). Allowed: 0.5–0.99.
    shrink: float
    #: Turn sampling control (adding and removing points, Eq. 7) off.
    no_sampling_control: bool
    #: Use the plain reference implementation of the energy (slow; for comparisons).
    reference: bool
    #: Progressive synthesis: existing points farther than this from the new domain stay fixed (output units;
    #: default 3δ). Allowed: ≥ 0.
    keep_margin: float


class StylizeOptions(TypedDict, total=False):
    """Options of `motif.stylize()` and `motif stylize`."""

    #: α: weight of the style term (A' against B' patches). Allowed: 0–1000. Default: 1.
    style_weight: float
    #: λ: weight of the occurrence penalty that spreads the use of source patches evenly and prevents wash-out
    #: (ebsynth's units: squared 8-bit differences); 0 = off. Allowed: 0–1000000. Default: 3500.
    uniformity: float
    #: Patch side in pixels, odd. Larger keeps bigger structures of the style. Allowed: 3–31. Default: 5.
    patch_size: int
    #: Patch side at the coarsest pyramid level, shrinking level by level to --patch-size at the finest: odd,
    #: or 0 for --patch-size everywhere. The coarse levels decide the layout; larger patches there keep regular
    #: structures (bricks, weaves, parquet) whole. Allowed: 0–31. Default: 0.
    coarse_patch_size: int
    #: Texture synthesis: weight of the exemplar's distance to its features (mortar, gaps, grooves; found by
    #: splitting its luminance in two) as one more channel, relative to a colour channel, at the coarsest level
    #: and falling to 0 at the finest (Kaspar et al. 2015's structure guidance); 0 = off. Keeps the elements of
    #: regular textures whole. Allowed: 0–1000. Default: 0.
    structure_weight: float
    #: Texture synthesis: start from an image quilt (Efros and Freeman 2001) of square blocks of B pixels, at
    #: most the exemplar's smaller side, and optimize at the finest level only: blocks keep whole elements in
    #: continuous courses (bricks, tiles), the optimization mends the seams. 0 = off, else at least 8. Allowed:
    #: 0–4096. Default: 0.
    quilt_block: int
    #: Pyramid levels; 0 = as many as fit (the coarsest at least 2·P+1 pixels a side). Allowed: 0–32. Default: 0.
    pyramid_levels: int
    #: Search-then-vote iterations per pyramid level (N of Algorithm 1). Allowed: 1–100. Default: 6.
    search_vote_iters: int
    #: PatchMatch iterations per search. Allowed: 1–100. Default: 4.
    patchmatch_iters: int
    #: Stop improving a pixel once a vote changes it by less than this (largest channel change, 8-bit units); 0
    #: = search every pixel every time. Allowed: 0–1020. Default: 5.
    stop_threshold: float
    #: Nearest-neighbour search: patchmatch (fast) or exact (brute force, small images only). Default: patchmatch.
    nnf: Literal["patchmatch", "exact"]
    #: After the finest level, one more search-and-vote with 3×3 patches and no uniformity (ebsynth's
    #: extrapass3x3): crisper fine detail.
    extra_pass_3x3: bool
    #: Refuse runs that would synthesize more output pixels than this (summed over presynth's textures): a
    #: guard against a typo in a size; about 15 CPU-seconds per megapixel. Allowed: ≥ 1. Default: 64000000.
    max_pixels: int
    #: β: weight of a guide. Give none (each guide then weighs 1/number of guides, as in ebsynth) or one per
    #: --guide, in the same order. Allowed: 0–1000.
    weight: Sequence[float]
    #: Treat the colours of the segment guide as segment labels: ω_best per segment (Eq. 6) and no match
    #: across segments. Exact palette (at most 64 colours) unless --segment-count.
    segments: bool
    #: Quantize the segment guide into K colours by k-means (for anti-aliased guides); implies --segments.
    #: Allowed: 2–64.
    segment_count: int
    #: Which --guide pair defines the segments, counted from 1. Allowed: ≥ 1. Default: 1.
    segment_guide: int
    #: Band half-width T in pixels for --presynth; 0 = pure bitmap composition. Allowed: 0–4096. Default: 4.
    band: int
    #: Search-vote iterations for the band when the textures carry their fields (caches made by this version):
    #: the band starts at the textures' own matches, so fewer are needed. Older caches (no fields) use
    #: --search-vote-iters. Allowed: 1–100. Default: 3.
    band_iters: int
    #: PatchMatch iterations per search for such a band (else --patchmatch-iters). Allowed: 1–100. Default: 2.
    band_patchmatch_iters: int


class PresynthOptions(TypedDict, total=False):
    """Options of `motif.presynth()` and `motif presynth`."""

    #: α: weight of the style term (A' against B' patches). Allowed: 0–1000. Default: 1.
    style_weight: float
    #: λ: weight of the occurrence penalty that spreads the use of source patches evenly and prevents wash-out
    #: (ebsynth's units: squared 8-bit differences); 0 = off. Allowed: 0–1000000. Default: 3500.
    uniformity: float
    #: Patch side in pixels, odd. Larger keeps bigger structures of the style. Allowed: 3–31. Default: 5.
    patch_size: int
    #: Patch side at the coarsest pyramid level, shrinking level by level to --patch-size at the finest: odd,
    #: or 0 for --patch-size everywhere. The coarse levels decide the layout; larger patches there keep regular
    #: structures (bricks, weaves, parquet) whole. Allowed: 0–31. Default: 0.
    coarse_patch_size: int
    #: Texture synthesis: weight of the exemplar's distance to its features (mortar, gaps, grooves; found by
    #: splitting its luminance in two) as one more channel, relative to a colour channel, at the coarsest level
    #: and falling to 0 at the finest (Kaspar et al. 2015's structure guidance); 0 = off. Keeps the elements of
    #: regular textures whole. Allowed: 0–1000. Default: 0.
    structure_weight: float
    #: Texture synthesis: start from an image quilt (Efros and Freeman 2001) of square blocks of B pixels, at
    #: most the exemplar's smaller side, and optimize at the finest level only: blocks keep whole elements in
    #: continuous courses (bricks, tiles), the optimization mends the seams. 0 = off, else at least 8. Allowed:
    #: 0–4096. Default: 0.
    quilt_block: int
    #: Pyramid levels; 0 = as many as fit (the coarsest at least 2·P+1 pixels a side). Allowed: 0–32. Default: 0.
    pyramid_levels: int
    #: Search-then-vote iterations per pyramid level (N of Algorithm 1). Allowed: 1–100. Default: 6.
    search_vote_iters: int
    #: PatchMatch iterations per search. Allowed: 1–100. Default: 4.
    patchmatch_iters: int
    #: Stop improving a pixel once a vote changes it by less than this (largest channel change, 8-bit units); 0
    #: = search every pixel every time. Allowed: 0–1020. Default: 5.
    stop_threshold: float
    #: Nearest-neighbour search: patchmatch (fast) or exact (brute force, small images only). Default: patchmatch.
    nnf: Literal["patchmatch", "exact"]
    #: After the finest level, one more search-and-vote with 3×3 patches and no uniformity (ebsynth's
    #: extrapass3x3): crisper fine detail.
    extra_pass_3x3: bool
    #: Refuse runs that would synthesize more output pixels than this (summed over presynth's textures): a
    #: guard against a typo in a size; about 15 CPU-seconds per megapixel. Allowed: ≥ 1. Default: 64000000.
    max_pixels: int
    #: Quantize the guide into K colours by k-means instead of an exact palette. Allowed: 2–64.
    segment_count: int


class TextureOptions(TypedDict, total=False):
    """Options of `motif.texture()` and `motif texture`."""

    #: α: weight of the style term (A' against B' patches). Allowed: 0–1000. Default: 1.
    style_weight: float
    #: λ: weight of the occurrence penalty that spreads the use of source patches evenly and prevents wash-out
    #: (ebsynth's units: squared 8-bit differences); 0 = off. Allowed: 0–1000000. Default: 3500.
    uniformity: float
    #: Patch side in pixels, odd. Larger keeps bigger structures of the style. Allowed: 3–31. Default: 5.
    patch_size: int
    #: Patch side at the coarsest pyramid level, shrinking level by level to --patch-size at the finest: odd,
    #: or 0 for --patch-size everywhere. The coarse levels decide the layout; larger patches there keep regular
    #: structures (bricks, weaves, parquet) whole. Allowed: 0–31. Default: 0.
    coarse_patch_size: int
    #: Texture synthesis: weight of the exemplar's distance to its features (mortar, gaps, grooves; found by
    #: splitting its luminance in two) as one more channel, relative to a colour channel, at the coarsest level
    #: and falling to 0 at the finest (Kaspar et al. 2015's structure guidance); 0 = off. Keeps the elements of
    #: regular textures whole. Allowed: 0–1000. Default: 0.
    structure_weight: float
    #: Texture synthesis: start from an image quilt (Efros and Freeman 2001) of square blocks of B pixels, at
    #: most the exemplar's smaller side, and optimize at the finest level only: blocks keep whole elements in
    #: continuous courses (bricks, tiles), the optimization mends the seams. 0 = off, else at least 8. Allowed:
    #: 0–4096. Default: 0.
    quilt_block: int
    #: Pyramid levels; 0 = as many as fit (the coarsest at least 2·P+1 pixels a side). Allowed: 0–32. Default: 0.
    pyramid_levels: int
    #: Search-then-vote iterations per pyramid level (N of Algorithm 1). Allowed: 1–100. Default: 6.
    search_vote_iters: int
    #: PatchMatch iterations per search. Allowed: 1–100. Default: 4.
    patchmatch_iters: int
    #: Stop improving a pixel once a vote changes it by less than this (largest channel change, 8-bit units); 0
    #: = search every pixel every time. Allowed: 0–1020. Default: 5.
    stop_threshold: float
    #: Nearest-neighbour search: patchmatch (fast) or exact (brute force, small images only). Default: patchmatch.
    nnf: Literal["patchmatch", "exact"]
    #: After the finest level, one more search-and-vote with 3×3 patches and no uniformity (ebsynth's
    #: extrapass3x3): crisper fine detail.
    extra_pass_3x3: bool
    #: Refuse runs that would synthesize more output pixels than this (summed over presynth's textures): a
    #: guard against a typo in a size; about 15 CPU-seconds per megapixel. Allowed: ≥ 1. Default: 64000000.
    max_pixels: int
    #: Wrap patches around the borders so the output tiles seamlessly.
    tileable: bool


class InpaintOptions(TypedDict, total=False):
    """Options of `motif.inpaint()` and `motif inpaint`."""

    #: α: weight of the style term (A' against B' patches). Allowed: 0–1000. Default: 1.
    style_weight: float
    #: λ: weight of the occurrence penalty that spreads the use of source patches evenly and prevents wash-out
    #: (ebsynth's units: squared 8-bit differences); 0 = off. Allowed: 0–1000000. Default: 3500.
    uniformity: float
    #: Patch side in pixels, odd. Larger keeps bigger structures of the style. Allowed: 3–31. Default: 5.
    patch_size: int
    #: Patch side at the coarsest pyramid level, shrinking level by level to --patch-size at the finest: odd,
    #: or 0 for --patch-size everywhere. The coarse levels decide the layout; larger patches there keep regular
    #: structures (bricks, weaves, parquet) whole. Allowed: 0–31. Default: 0.
    coarse_patch_size: int
    #: Texture synthesis: weight of the exemplar's distance to its features (mortar, gaps, grooves; found by
    #: splitting its luminance in two) as one more channel, relative to a colour channel, at the coarsest level
    #: and falling to 0 at the finest (Kaspar et al. 2015's structure guidance); 0 = off. Keeps the elements of
    #: regular textures whole. Allowed: 0–1000. Default: 0.
    structure_weight: float
    #: Texture synthesis: start from an image quilt (Efros and Freeman 2001) of square blocks of B pixels, at
    #: most the exemplar's smaller side, and optimize at the finest level only: blocks keep whole elements in
    #: continuous courses (bricks, tiles), the optimization mends the seams. 0 = off, else at least 8. Allowed:
    #: 0–4096. Default: 0.
    quilt_block: int
    #: Pyramid levels; 0 = as many as fit (the coarsest at least 2·P+1 pixels a side). Allowed: 0–32. Default: 0.
    pyramid_levels: int
    #: Search-then-vote iterations per pyramid level (N of Algorithm 1). Allowed: 1–100. Default: 6.
    search_vote_iters: int
    #: PatchMatch iterations per search. Allowed: 1–100. Default: 4.
    patchmatch_iters: int
    #: Stop improving a pixel once a vote changes it by less than this (largest channel change, 8-bit units); 0
    #: = search every pixel every time. Allowed: 0–1020. Default: 5.
    stop_threshold: float
    #: Nearest-neighbour search: patchmatch (fast) or exact (brute force, small images only). Default: patchmatch.
    nnf: Literal["patchmatch", "exact"]
    #: After the finest level, one more search-and-vote with 3×3 patches and no uniformity (ebsynth's
    #: extrapass3x3): crisper fine detail.
    extra_pass_3x3: bool
    #: Refuse runs that would synthesize more output pixels than this (summed over presynth's textures): a
    #: guard against a typo in a size; about 15 CPU-seconds per megapixel. Allowed: ≥ 1. Default: 64000000.
    max_pixels: int


class ZoomOptions(TypedDict, total=False):
    """Options of `motif.zoom()` and `motif zoom`."""

    #: α: weight of the style term (A' against B' patches). Allowed: 0–1000. Default: 1.
    style_weight: float
    #: λ: weight of the occurrence penalty that spreads the use of source patches evenly and prevents wash-out
    #: (ebsynth's units: squared 8-bit differences); 0 = off. Allowed: 0–1000000. Default: 3500.
    uniformity: float
    #: Patch side in pixels, odd. Larger keeps bigger structures of the style. Allowed: 3–31. Default: 5.
    patch_size: int
    #: Patch side at the coarsest pyramid level, shrinking level by level to --patch-size at the finest: odd,
    #: or 0 for --patch-size everywhere. The coarse levels decide the layout; larger patches there keep regular
    #: structures (bricks, weaves, parquet) whole. Allowed: 0–31. Default: 0.
    coarse_patch_size: int
    #: Texture synthesis: weight of the exemplar's distance to its features (mortar, gaps, grooves; found by
    #: splitting its luminance in two) as one more channel, relative to a colour channel, at the coarsest level
    #: and falling to 0 at the finest (Kaspar et al. 2015's structure guidance); 0 = off. Keeps the elements of
    #: regular textures whole. Allowed: 0–1000. Default: 0.
    structure_weight: float
    #: Texture synthesis: start from an image quilt (Efros and Freeman 2001) of square blocks of B pixels, at
    #: most the exemplar's smaller side, and optimize at the finest level only: blocks keep whole elements in
    #: continuous courses (bricks, tiles), the optimization mends the seams. 0 = off, else at least 8. Allowed:
    #: 0–4096. Default: 0.
    quilt_block: int
    #: Pyramid levels; 0 = as many as fit (the coarsest at least 2·P+1 pixels a side). Allowed: 0–32. Default: 0.
    pyramid_levels: int
    #: Search-then-vote iterations per pyramid level (N of Algorithm 1). Allowed: 1–100. Default: 6.
    search_vote_iters: int
    #: PatchMatch iterations per search. Allowed: 1–100. Default: 4.
    patchmatch_iters: int
    #: Stop improving a pixel once a vote changes it by less than this (largest channel change, 8-bit units); 0
    #: = search every pixel every time. Allowed: 0–1020. Default: 5.
    stop_threshold: float
    #: Nearest-neighbour search: patchmatch (fast) or exact (brute force, small images only). Default: patchmatch.
    nnf: Literal["patchmatch", "exact"]
    #: After the finest level, one more search-and-vote with 3×3 patches and no uniformity (ebsynth's
    #: extrapass3x3): crisper fine detail.
    extra_pass_3x3: bool
    #: Refuse runs that would synthesize more output pixels than this (summed over presynth's textures): a
    #: guard against a typo in a size; about 15 CPU-seconds per megapixel. Allowed: ≥ 1. Default: 64000000.
    max_pixels: int
    #: How much closer each level is than the one before. Allowed: 1.05–8. Default: 2.
    factor: float
    #: Zoom levels, the first unzoomed. Allowed: 1–64. Default: 4.
    levels: int


class VideoOptions(TypedDict, total=False):
    """Options of `motif.video()` and `motif video`."""

    #: α: weight of the style term (A' against B' patches). Allowed: 0–1000. Default: 1.
    style_weight: float
    #: λ: weight of the occurrence penalty that spreads the use of source patches evenly and prevents wash-out
    #: (ebsynth's units: squared 8-bit differences); 0 = off. Allowed: 0–1000000. Default: 3500.
    uniformity: float
    #: Patch side in pixels, odd. Larger keeps bigger structures of the style. Allowed: 3–31. Default: 5.
    patch_size: int
    #: Patch side at the coarsest pyramid level, shrinking level by level to --patch-size at the finest: odd,
    #: or 0 for --patch-size everywhere. The coarse levels decide the layout; larger patches there keep regular
    #: structures (bricks, weaves, parquet) whole. Allowed: 0–31. Default: 0.
    coarse_patch_size: int
    #: Texture synthesis: weight of the exemplar's distance to its features (mortar, gaps, grooves; found by
    #: splitting its luminance in two) as one more channel, relative to a colour channel, at the coarsest level
    #: and falling to 0 at the finest (Kaspar et al. 2015's structure guidance); 0 = off. Keeps the elements of
    #: regular textures whole. Allowed: 0–1000. Default: 0.
    structure_weight: float
    #: Texture synthesis: start from an image quilt (Efros and Freeman 2001) of square blocks of B pixels, at
    #: most the exemplar's smaller side, and optimize at the finest level only: blocks keep whole elements in
    #: continuous courses (bricks, tiles), the optimization mends the seams. 0 = off, else at least 8. Allowed:
    #: 0–4096. Default: 0.
    quilt_block: int
    #: Pyramid levels; 0 = as many as fit (the coarsest at least 2·P+1 pixels a side). Allowed: 0–32. Default: 0.
    pyramid_levels: int
    #: Search-then-vote iterations per pyramid level (N of Algorithm 1). Allowed: 1–100. Default: 6.
    search_vote_iters: int
    #: PatchMatch iterations per search. Allowed: 1–100. Default: 4.
    patchmatch_iters: int
    #: Stop improving a pixel once a vote changes it by less than this (largest channel change, 8-bit units); 0
    #: = search every pixel every time. Allowed: 0–1020. Default: 5.
    stop_threshold: float
    #: Nearest-neighbour search: patchmatch (fast) or exact (brute force, small images only). Default: patchmatch.
    nnf: Literal["patchmatch", "exact"]
    #: After the finest level, one more search-and-vote with 3×3 patches and no uniformity (ebsynth's
    #: extrapass3x3): crisper fine detail.
    extra_pass_3x3: bool
    #: Refuse runs that would synthesize more output pixels than this (summed over presynth's textures): a
    #: guard against a typo in a size; about 15 CPU-seconds per megapixel. Allowed: ≥ 1. Default: 64000000.
    max_pixels: int
    #: Weight of the frames' colours (keyframe against each frame). Allowed: 0–1000. Default: 1.
    colour_weight: float
    #: Weight of the edge guide (the frames' blurred edges). Allowed: 0–1000. Default: 1.
    edge_weight: float
    #: Weight of the positional guide (the keyframe's pixel positions carried along the motion, so the style
    #: stays on the surfaces it was painted on). Allowed: 0–1000. Default: 4.
    position_weight: float
    #: Weight of the temporal guide (the previous output carried along the motion; against flicker); 0 stylizes
    #: frames independently of each other. Allowed: 0–1000. Default: 2.
    temporal_weight: float
