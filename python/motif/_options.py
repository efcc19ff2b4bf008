"""The keyword options of each engine, rendered from motif-jobs' declarations (do not edit).

Regenerate with `MOTIF_BLESS=1 cargo test --release -p motif-jobs --test declarations`.
"""

from typing import Any, Literal, Mapping, Sequence, Tuple, TypedDict


class CurveOptions(TypedDict, total=False):
    """Options of `motif.curve()` and `motif curve`."""

    #: Ribbon width b in canvas pixels, > 0. Width × scale is the number of samples per piece edge (C) and
    #: should exceed the pattern's height in the exemplar. Default: inferred from the first exemplar, the
    #: pattern's height (rows with alpha above --cut-alpha) plus the clear row above and below, 15% wider,
    #: divided by the scale; then every whole width within 4% of it, and 5% narrower, 5% and 10% wider, are
    #: tried at the settled piece length and the best-scoring output kept (report `size_search`).
    width: float
    #: Piece length δ along the curve in canvas pixels, > 0 and at most the curve's length. Default: inferred
    #: from the first exemplar, 0.55 of the pattern's period along x (the first strong peak of the
    #: autocorrelation of its columns), kept between a quarter and 0.6 of the pattern's height, divided by the
    #: scale; 0.3 of the pattern's height when it has no period. That guess, 0.8, 1.25, 1.6, 2 and 2.5 times it
    #: and half the period are each run, then twice the lengths halfway to the best one's neighbours, and the
    #: output whose patches are closest to the exemplar's (fewest motifs cut) is kept; giving the value skips
    #: this search.
    piece_length: float
    #: Scale s: exemplar pixels per canvas pixel (2 draws the pattern at half size). Allowed: 0.05–20. Default: 1.
    scale: float
    #: Closed-curve handling: auto (approx for a closed curve, no for an open one); approx, the paper's single
    #: dynamic program with backtracking from every terminal position; exact, branch and bound over start
    #: positions with a certificate of optimality; no, the curve treated as open (a closed curve is cut at its
    #: first point). Default: auto.
    closed: Literal["auto", "approx", "exact", "no"]
    #: Do not detect fold-overs and overlaps of the ribbon (by default the pattern avoids them).
    no_foldover_avoidance: bool
    #: Stitch piece boundaries (edge alignment with penalty P, propagated inside the pieces).
    stitch: bool
    #: Stitching penalty P for moving opaque samples. Allowed: 0–100000. Default: 32.
    stitch_penalty: float
    #: Pattern generator: synth, the paper's synthesis (undistorted pieces placed by dynamic programming), or
    #: repeat, the classic baseline (the exemplar repeated along the arc length and bent with the ribbon). Default: synth.
    method: Literal["synth", "repeat"]
    #: Dynamic-programming solver: exact (merged identical edges, branch and bound over a profile tree, lower
    #: bounds and early exit) or reference (the plain O(V²C) dynamic program), which find the same optimum; or
    #: coarse, for large or dense exemplars: the program on cells of 2–4 pixels first, then the exact one in
    #: bands of positions around the best cells (a cost at least the optimum's; --check-gap measures the
    #: difference); or auto: exact, but coarse on an open curve whose program has over 10^10 position pairs (a
    #: large exemplar along a long curve). The report names the solver that ran. Default: auto.
    solver: Literal["exact", "reference", "coarse", "auto"]
    #: With --solver coarse, also run the exact solver and report the exact optimum and the coarse solver's
    #: cost gap (exact_optimum, cost_gap); takes at least an exact run's time.
    check_gap: bool
    #: Alpha in the matching cost: binary, the paper's ξ (alpha thresholded at 128, opaque or transparent), or
    #: continuous, ξ blended by alpha for anti-aliased and semi-transparent exemplars. Default: continuous.
    alpha: Literal["binary", "continuous"]
    #: γ, the matching cost of an opaque against a transparent pixel. Allowed: 1–100000. Default: 1024.
    gamma: float
    #: Pin the first piece's exemplar position (top-left corner, pixels; must be a valid position).
    pin_first: Tuple[int, int]
    #: Canvas size in pixels (document origin at the top-left); default: fitted to the ribbon.
    canvas: Tuple[int, int]
    #: Margin around the ribbon when the canvas is fitted, pixels. Allowed: 0–4096. Default: 4.
    margin: float
    #: Anti-aliasing: render samples per pixel along each axis. Allowed: 1–8. Default: 3.
    samples: int
    #: Alpha at or below which a pixel counts as transparent when checking that a piece slices the pattern
    #: completely. Allowed: 0–254. Default: 8.
    cut_alpha: int
    #: Minimum coverage: a piece position is valid only if it holds at least this share of the pattern pixels a
    #: typical piece holds (the median over exemplar windows spanning the pattern's height). Keeps the optimum
    #: from repeating a thin sliver; 0 = the paper's rule (and no check for an optimum that repeats a thin
    #: strip either). Allowed: 0–1. Default: 0.5.
    min_coverage: float
    #: Repetition penalty W (not in the paper), in seam-cost units: each pair of pieces at most
    #: --variety-radius pieces apart that copy the same exemplar window costs W. 0 = the paper's energy, which
    #: may alternate two windows along a straight line. Allowed: 0–1000000. Default: 0.
    variety: float
    #: How many pieces apart a repeated window is penalised by --variety. Allowed: 1–1000. Default: 8.
    variety_radius: int
    #: Piece shape: bent pieces follow the ribbon (seams compare vertical columns, so the exemplar continues
    #: across them; stretched outside bends); rigid pieces are the paper's undistorted, rotated copies. Default: bent.
    pieces_shape: Literal["rigid", "bent"]
    #: Width profile: comma-separated T:F pairs, T the fraction of the curve's length (0–1, ascending) and F
    #: the factor (0.1–10) multiplying --width there, interpolated in between; the pattern scales with the
    #: width (e.g. 0:0.5,0.5:1.5,1:0.5 swells in the middle). Needs bent pieces.
    width_profile: Sequence[Tuple[float, float]]
    #: Round bends of the curve tighter than F × width to that radius, so that the ribbon does not fold at
    #: cusps and corners (where the paper leaves pieces empty); 0 keeps the curve as given. Allowed: 0–8. Default: 0.6.
    round_bends: float
    #: Measure the result against the exemplar (patches read back along the curve, nearest exemplar patch) and
    #: add the figures to the report and the summary.
    fidelity: bool
    #: Exact closed mode: start positions tried at most before giving up the certificate. Allowed: 1–100000. Default: 64.
    closed_max_starts: int
    #: How the pieces meet the curve's length, as a pattern brush fits its tiles: none cuts the last piece
    #: where an open curve ends (the paper); stretch draws a whole number of pieces, each stretched or squeezed
    #: along the curve; space draws as many whole pieces as fit, with equal gaps between them, each cut where
    #: the exemplar is clear so that no motif is cut at a gap. Stretch needs bent pieces. Default: none.
    fit: Literal["none", "stretch", "space"]
    #: Mirror the exemplar before synthesis: along (the pattern runs the other way), across (its top faces the
    #: other side of the curve) or both. Default: none.
    flip: Literal["none", "along", "across", "both"]
    #: Colourize the pattern as tints of this colour (#RRGGBB): black becomes the colour, white stays white,
    #: greys become lighter tints; transparency is kept.
    tint: str
    #: A start tile: columns X0,X1 (X0 < X1) of the first exemplar, drawn whole as the first piece of an open
    #: curve (an end cap, a clasp) and joined to the next piece by the same seam cost; the dynamic program
    #: chooses its height. Its length along the curve is (X1 − X0) / scale. The command line also takes a PNG
    #: file of the tile here (as --start-tile-image).
    start_tile: Tuple[int, int]
    #: An end tile: columns X0,X1 of the first exemplar, drawn whole as the last piece, ending at the curve's
    #: end (or, on the command line, a PNG file of the tile).
    end_tile: Tuple[int, int]
    #: A corner tile: columns X0,X1 of the first exemplar, drawn whole and centred on every corner sharper than
    #: --corner-angle (a frame's corner piece), on open and closed curves, joined to the pieces beside it by
    #: the same seam cost. A corner too close to another or to an end to leave half a piece between them is
    #: left to the pieces. The command line also takes a PNG file of the tile here.
    corner_tile: Tuple[int, int]
    #: With --corner-tile: the turn, in degrees, that makes a corner (the angle between the curve's directions
    #: half a tile before and half a tile after it). Allowed: 10–179. Default: 60.
    corner_angle: float


class PointsOptions(TypedDict, total=False):
    """Options of `motif.points()` and `motif points`."""

    #: Neighbourhood size δ in exemplar units (> 0): the width of the Gaussian window (truncated at
    #: --window-cutoff × δ) or the radius of the box window. Larger keeps larger structures; it shrinks to
    #: δ/2 during the synthesis. Default: 4 times the exemplar's mean nearest-neighbour spacing in 2D, 2 times
    #: in 3D (reported as `neighbourhood` and `exemplar_spacing`); continuous structures such as contours need
    #: about the size of their features.
    neighbourhood: float
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
    #: Let continuous attributes leave the exemplar's range. By default each stays between the exemplar's
    #: smallest and largest value of it (no negative diameters from a fit).
    attributes_beyond_range: bool
    #: Use the plain reference implementation of the energy (slow; for comparisons).
    reference: bool
    #: Progressive synthesis: existing points farther than this from the new domain stay fixed (output units;
    #: default 3δ). Allowed: ≥ 0.
    keep_margin: float


class StrokesOptions(TypedDict, total=False):
    """Options of `motif.strokes()` and `motif strokes`."""

    #: Points the element boxes are fitted to: the strokes' skeletons (the default; each gesture's own
    #: polyline, ignoring its width) or their contours (the outline stroked at the stroke's width with round
    #: caps, so that thick strokes give thick boxes). Default: skeleton.
    fit: Literal["skeleton", "contour"]
    #: Neighbourhood size in rings of the neighbour graph (default: 5 along a path, 2 in a region). Allowed:
    #: 1–5.
    rings: int
    #: Parameter exchange amount: orientation, length, thickness and colour swapped with similar reference
    #: elements within this fraction of the matching thresholds; 0 copies exactly. Allowed: 0–1. Default: 0.
    variation: float
    #: Reintroduce the reference's irregular spacing from its shift vectors.
    position_variation: bool
    #: Let elements overlap. By default an element whose ink meets an already placed one goes back to its seed,
    #: drops its variation, is swapped for another matching element, moves slightly, or is removed (the
    #: report's `overlap` says how many of each), unless the reference's own elements overlap.
    allow_overlaps: bool
    #: Override matching thresholds: shape and sup in units of the mean element length L (defaults 0.1), par in
    #: radians (π/20), ov a length ratio > 1 (1.5), col an RGB distance in the unit cube (0.15), attr the
    #: largest difference of relative stroke width and dash period, opacity, filled or dashed share and fill
    #: colour (0.2). Example: shape=0.2,col=0.3.
    thresholds: Mapping[str, float]
    #: Lloyd relaxation iterations for the seeds (stops early once converged). Allowed: 1–1000. Default: 20.
    lloyd_iterations: int


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
    #: structures (bricks, weaves, parquet) whole. Not given: `texture` infers it when it has no quilt (11, or
    #: 15 for an exemplar of 1024 pixels a side or more; the report's `coarse_patch_size` and
    #: `coarse_patch_size_inferred`), the other commands use --patch-size everywhere. Allowed: 0–31.
    coarse_patch_size: int
    #: Texture synthesis: weight of the exemplar's distance to its features (mortar, gaps, grooves; found by
    #: splitting its luminance in two) as one more channel, relative to a colour channel, at the coarsest level
    #: and falling to 0 at the finest (Kaspar et al. 2015's structure guidance); 0 = off. Keeps the elements of
    #: regular textures whole. Allowed: 0–1000. Default: 0.
    structure_weight: float
    #: Texture synthesis: start from an image quilt (Efros and Freeman 2001) of square blocks of B pixels, at
    #: most the exemplar's smaller side, and optimize at the finest level only: blocks keep whole elements in
    #: continuous courses (bricks, tiles), the optimization mends the seams. 0 = off, else at least 8. Not
    #: given: `texture` infers it (half the exemplar's smaller side when the output is larger than the
    #: exemplar, else off; the report's `quilt_block` and `quilt_block_inferred`), the other commands leave it
    #: off. Allowed: 0–4096.
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
    #: across segments. The source guide's exact palette (at most 64 colours) unless --segment-count; every
    #: target pixel takes the nearest segment colour.
    segments: bool
    #: Quantize the source segment guide into K colours by k-means (for anti-aliased or JPEG guides): every
    #: pixel of both guides takes the nearest; implies --segments. Allowed: 2–64.
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
    #: structures (bricks, weaves, parquet) whole. Not given: `texture` infers it when it has no quilt (11, or
    #: 15 for an exemplar of 1024 pixels a side or more; the report's `coarse_patch_size` and
    #: `coarse_patch_size_inferred`), the other commands use --patch-size everywhere. Allowed: 0–31.
    coarse_patch_size: int
    #: Texture synthesis: weight of the exemplar's distance to its features (mortar, gaps, grooves; found by
    #: splitting its luminance in two) as one more channel, relative to a colour channel, at the coarsest level
    #: and falling to 0 at the finest (Kaspar et al. 2015's structure guidance); 0 = off. Keeps the elements of
    #: regular textures whole. Allowed: 0–1000. Default: 0.
    structure_weight: float
    #: Texture synthesis: start from an image quilt (Efros and Freeman 2001) of square blocks of B pixels, at
    #: most the exemplar's smaller side, and optimize at the finest level only: blocks keep whole elements in
    #: continuous courses (bricks, tiles), the optimization mends the seams. 0 = off, else at least 8. Not
    #: given: `texture` infers it (half the exemplar's smaller side when the output is larger than the
    #: exemplar, else off; the report's `quilt_block` and `quilt_block_inferred`), the other commands leave it
    #: off. Allowed: 0–4096.
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
    #: Quantize the guide into K colours by k-means instead of an exact palette (for anti-aliased or JPEG
    #: guides: every pixel takes the nearest). Allowed: 2–64.
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
    #: structures (bricks, weaves, parquet) whole. Not given: `texture` infers it when it has no quilt (11, or
    #: 15 for an exemplar of 1024 pixels a side or more; the report's `coarse_patch_size` and
    #: `coarse_patch_size_inferred`), the other commands use --patch-size everywhere. Allowed: 0–31.
    coarse_patch_size: int
    #: Texture synthesis: weight of the exemplar's distance to its features (mortar, gaps, grooves; found by
    #: splitting its luminance in two) as one more channel, relative to a colour channel, at the coarsest level
    #: and falling to 0 at the finest (Kaspar et al. 2015's structure guidance); 0 = off. Keeps the elements of
    #: regular textures whole. Allowed: 0–1000. Default: 0.
    structure_weight: float
    #: Texture synthesis: start from an image quilt (Efros and Freeman 2001) of square blocks of B pixels, at
    #: most the exemplar's smaller side, and optimize at the finest level only: blocks keep whole elements in
    #: continuous courses (bricks, tiles), the optimization mends the seams. 0 = off, else at least 8. Not
    #: given: `texture` infers it (half the exemplar's smaller side when the output is larger than the
    #: exemplar, else off; the report's `quilt_block` and `quilt_block_inferred`), the other commands leave it
    #: off. Allowed: 0–4096.
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
    #: structures (bricks, weaves, parquet) whole. Not given: `texture` infers it when it has no quilt (11, or
    #: 15 for an exemplar of 1024 pixels a side or more; the report's `coarse_patch_size` and
    #: `coarse_patch_size_inferred`), the other commands use --patch-size everywhere. Allowed: 0–31.
    coarse_patch_size: int
    #: Texture synthesis: weight of the exemplar's distance to its features (mortar, gaps, grooves; found by
    #: splitting its luminance in two) as one more channel, relative to a colour channel, at the coarsest level
    #: and falling to 0 at the finest (Kaspar et al. 2015's structure guidance); 0 = off. Keeps the elements of
    #: regular textures whole. Allowed: 0–1000. Default: 0.
    structure_weight: float
    #: Texture synthesis: start from an image quilt (Efros and Freeman 2001) of square blocks of B pixels, at
    #: most the exemplar's smaller side, and optimize at the finest level only: blocks keep whole elements in
    #: continuous courses (bricks, tiles), the optimization mends the seams. 0 = off, else at least 8. Not
    #: given: `texture` infers it (half the exemplar's smaller side when the output is larger than the
    #: exemplar, else off; the report's `quilt_block` and `quilt_block_inferred`), the other commands leave it
    #: off. Allowed: 0–4096.
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
    #: structures (bricks, weaves, parquet) whole. Not given: `texture` infers it when it has no quilt (11, or
    #: 15 for an exemplar of 1024 pixels a side or more; the report's `coarse_patch_size` and
    #: `coarse_patch_size_inferred`), the other commands use --patch-size everywhere. Allowed: 0–31.
    coarse_patch_size: int
    #: Texture synthesis: weight of the exemplar's distance to its features (mortar, gaps, grooves; found by
    #: splitting its luminance in two) as one more channel, relative to a colour channel, at the coarsest level
    #: and falling to 0 at the finest (Kaspar et al. 2015's structure guidance); 0 = off. Keeps the elements of
    #: regular textures whole. Allowed: 0–1000. Default: 0.
    structure_weight: float
    #: Texture synthesis: start from an image quilt (Efros and Freeman 2001) of square blocks of B pixels, at
    #: most the exemplar's smaller side, and optimize at the finest level only: blocks keep whole elements in
    #: continuous courses (bricks, tiles), the optimization mends the seams. 0 = off, else at least 8. Not
    #: given: `texture` infers it (half the exemplar's smaller side when the output is larger than the
    #: exemplar, else off; the report's `quilt_block` and `quilt_block_inferred`), the other commands leave it
    #: off. Allowed: 0–4096.
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
    #: structures (bricks, weaves, parquet) whole. Not given: `texture` infers it when it has no quilt (11, or
    #: 15 for an exemplar of 1024 pixels a side or more; the report's `coarse_patch_size` and
    #: `coarse_patch_size_inferred`), the other commands use --patch-size everywhere. Allowed: 0–31.
    coarse_patch_size: int
    #: Texture synthesis: weight of the exemplar's distance to its features (mortar, gaps, grooves; found by
    #: splitting its luminance in two) as one more channel, relative to a colour channel, at the coarsest level
    #: and falling to 0 at the finest (Kaspar et al. 2015's structure guidance); 0 = off. Keeps the elements of
    #: regular textures whole. Allowed: 0–1000. Default: 0.
    structure_weight: float
    #: Texture synthesis: start from an image quilt (Efros and Freeman 2001) of square blocks of B pixels, at
    #: most the exemplar's smaller side, and optimize at the finest level only: blocks keep whole elements in
    #: continuous courses (bricks, tiles), the optimization mends the seams. 0 = off, else at least 8. Not
    #: given: `texture` infers it (half the exemplar's smaller side when the output is larger than the
    #: exemplar, else off; the report's `quilt_block` and `quilt_block_inferred`), the other commands leave it
    #: off. Allowed: 0–4096.
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


class TilesOptions(TypedDict, total=False):
    """Options of `motif.tiles()` and `motif tiles`."""

    #: Side of a tile in pixels (slippy maps use 256). Allowed: 64–1024. Default: 256.
    tile_size: int
    #: Pixels drawn and stylized around each tile and cut off, so the band's patches at a tile's edge see what
    #: its neighbour's see; 0 = the band plus the patch size, the reach of a band pixel's result (the report's
    #: `margin`). Allowed: 0–256. Default: 0.
    margin: int
    #: Band half-width T in pixels (Texler et al. §3.7): pixels farther than this from a class edge are copied
    #: from the class's pre-synthesized texture, only the band between is optimized; 0 = composition only.
    #: Wider bands blend the classes' edges more, slower. Allowed: 0–64. Default: 2.
    band: int
    #: Side of each class's pre-synthesized texture in pixels, made once for all tiles (they tile seamlessly;
    #: larger ones repeat less often and take longer to make). Allowed: 16–1024. Default: 128.
    texture_size: int
    #: Patch side in pixels, odd, of the presynthesis and the band. Allowed: 3–15. Default: 5.
    patch_size: int
    #: Search-vote iterations of the band (it starts from the textures' own matches). Allowed: 1–20. Default: 1.
    band_iters: int
    #: PatchMatch iterations per search of the band. Allowed: 1–20. Default: 1.
    band_patchmatch_iters: int
    #: Narrowest line drawn, in pixels, so that small roads stay visible at low zooms. Allowed: 0.25–16. Default: 1.
    min_line_width: float
    #: Levels of the texture pyramid, so that zooming in keeps the textures' layout: the first textures serve
    #: --base-zoom and below; each next level, twice the side and synthesized under the one before magnified
    #: twice, serves the next zoom (deeper zooms take the last). `serve` makes them before it listens, `render`
    #: those of its zooms before the first tile; 1 = the same textures at every zoom. Allowed: 1–4. Default: 2.
    texture_levels: int
    #: Zoom level of the first textures of the pyramid (see --texture-levels). Allowed: 0–24. Default: 15.
    base_zoom: int
