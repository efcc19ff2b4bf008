"""The keyword options of each engine, rendered from motif-jobs' declarations (do not edit).

Regenerate with `MOTIF_BLESS=1 cargo test --release -p motif-jobs --test declarations`.
"""

from typing import Any, Literal, Mapping, Sequence, TypedDict


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
    #: Use the plain reference implementation of the energy (slow; for comparisons).
    reference: bool
    #: Progressive synthesis: existing points farther than this from the new domain stay fixed (output units;
    #: default 3δ). Allowed: ≥ 0.
    keep_margin: float
