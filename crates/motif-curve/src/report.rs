//! What a run returns: the image, the placed pieces and the figures.

use motif_core::{Point, RgbaImage};
use serde::Serialize;

use crate::avoidance::ForbiddenMask;
use crate::brush::Fit;
use crate::coarse::CoarseReport;
use crate::dp::{DpCounters, Solver};
use crate::params::Method;
use crate::solve::VarietyReport;

/// One placed piece, as written to the pieces JSON.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlacedPiece {
    /// Index along the curve.
    pub index: usize,
    /// Arc length range `[x_i, x_{i+1}]` on the curve.
    pub arc: [f64; 2],
    /// Canvas corners: top-left, bottom-left, bottom-right, top-right.
    pub quad: [[f64; 2]; 4],
    /// Which exemplar the piece copies (0: the first; see `Input::more_exemplars`).
    pub exemplar: usize,
    /// `u_i`: exemplar position of the top-left corner (the corner sits at `(x + 0.5, y)`);
    /// `None` for a piece left empty because avoidance forbade every position.
    pub position: Option<[i32; 2]>,
    /// Rotation canvas → exemplar of the piece's left edge, radians (a bent piece turns with the
    /// ribbon from there).
    pub rotation: f64,
    /// Scale `s` (exemplar pixels per canvas pixel).
    pub scale: f64,
    /// Number of valid positions of this piece.
    pub valid_positions: usize,
    /// True when the piece has a seam to a next piece (all but the last of an open curve).
    pub has_seam: bool,
    /// Seam cost `D` to the next piece (paper units), after stitching when enabled.
    pub seam_cost: f64,
    /// Seam cost before stitching (paper units).
    pub seam_cost_unstitched: f64,
    /// Stitch remapping `T` of the right edge (identity without stitching).
    pub stitch: Vec<usize>,
}

/// Figures of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Synthesis or repeat.
    pub method: Method,
    /// The run's estimated peak memory, bytes (checked against `max-memory` before allocating).
    pub estimated_memory_bytes: u64,

    /// Solver used.
    pub solver: Solver,
    /// The coarse-to-fine solver's figures (cell side, positions and band sizes per row, coarse
    /// and refinement milliseconds); `None` with the other solvers.
    pub coarse: Option<CoarseReport>,
    /// `Ω` of the exact solver (paper units), when it ran beside the coarse-to-fine one
    /// (`Params::check_gap`).
    pub exact_optimum: Option<f64>,
    /// The coarse-to-fine solver's `Ω` less the exact optimum (paper units, ≥ 0; 0: it found an
    /// optimum), when the exact solver ran too.
    pub cost_gap: Option<f64>,
    /// `cost_gap` as a fraction of the coarse-to-fine `Ω` (0 when that is 0).
    pub cost_gap_fraction: Option<f64>,
    /// Number of pieces.
    pub pieces: usize,
    /// `C`, samples per edge.
    pub samples_per_edge: usize,
    /// Canvas size.
    pub canvas: [usize; 2],
    /// Document coordinates of canvas pixel (0, 0)'s corner.
    pub canvas_origin: [f64; 2],
    /// `Ω` of the result (paper units), after stitching when enabled (the DP optimum is
    /// `total_cost_unstitched`).
    pub total_cost: f64,
    /// `Ω` of the DP optimum (paper units).
    pub total_cost_unstitched: f64,
    /// Mean seam cost (paper units).
    pub mean_seam_cost: f64,
    /// `Ω` as found by the dynamic program (paper units); equals `total_cost_unstitched`.
    pub dp_optimum: f64,
    /// Mean over pieces of (valid positions / `U`).
    pub valid_fraction: f64,
    /// Milliseconds per DP row.
    pub dp_row_ms: Vec<f64>,
    /// Median of `dp_row_ms`.
    pub dp_row_ms_median: f64,
    /// Maximum of `dp_row_ms`.
    pub dp_row_ms_max: f64,
    /// Milliseconds per stage.
    pub stages_ms: Vec<(String, f64)>,
    /// True when the curve was handled as closed.
    pub closed: bool,
    /// Exact closed mode: whether the optimum was proven.
    pub closed_certified: Option<bool>,
    /// Exact closed mode: no cycle's `Ω` is below this (paper units, as `dp_optimum`); equal to
    /// `dp_optimum` when certified.
    pub closed_lower_bound: Option<f64>,
    /// Exact closed mode: how far the dynamic program's cycle may be from the optimum of `Ω`, `(dp_optimum − bound) /
    /// dp_optimum` (0 when certified).
    pub closed_gap: Option<f64>,
    /// Closed curves: start positions evaluated by pinned DPs.
    pub closed_starts_tried: usize,
    /// Closed curves: whether the single DP found a cycle directly.
    pub closed_directly: bool,
    /// Pieces left empty because avoidance forbade every position.
    pub empty_pieces: usize,
    /// Forbidden canvas pixels (avoidance map and fold-overs).
    pub forbidden_pixels: usize,
    /// Canvas pixels flagged by fold-over detection.
    pub foldover_pixels: usize,
    /// DP work counters.
    pub dp_counters: DpCounters,
    /// Fraction of predecessor/position pairs whose columns were never compared.
    pub columns_skipped_fraction: f64,
    /// Seams whose stitch is not the identity.
    pub stitched_seams: usize,
    /// Repeat baseline: mean |stretch − 1| of the ribbon borders (0 for synthesis: pieces are rigid).
    pub distortion_mean: f64,
    /// Repeat baseline: max |stretch − 1| of the ribbon borders.
    pub distortion_max: f64,
    /// Repeat baseline: number of places where the tiled exemplar wraps around.
    pub wrap_seams: usize,
    /// Pairs of pieces at most `variety_radius` pieces apart that copy the same exemplar window.
    pub repeated_pairs: usize,
    /// Distinct exemplar windows among the pieces (positions closer than half a piece length
    /// horizontally and a quarter of `C` vertically count as one window).
    pub distinct_windows: usize,
    /// Repetition control figures (with `variety` > 0).
    pub variety: Option<VarietyReport>,
    /// DP rows taken from the previous run of an [`Incremental`](crate::Incremental) session.
    pub dp_rows_reused: usize,
    /// Bends of the curve tighter than `round_bends × width` that were rounded.
    pub rounded_bends: usize,
    /// Largest distance the rounding moved a point of the curve, canvas pixels.
    pub bend_shift_max: f64,
    /// How the pieces met the curve's length ([`Fit`]).
    pub fit: Fit,
    /// The canvas length of a whole piece: the piece length, or the stretched one.
    pub fitted_piece_length: f64,
    /// The gap after each piece, canvas pixels (0 unless the pieces are spaced out).
    pub fit_gap: f64,
    /// Corner tiles placed (one per corner sharper than the corner angle that leaves room for
    /// pieces beside it; 0 without a corner tile).
    pub corner_tiles: usize,
    /// A degenerate optimum found and avoided: a thin strip of the exemplar repeated at no seam
    /// cost (see [`ThinStrip`](crate::ThinStrip)); none when the pieces held their motifs.
    pub thin_strip: Option<crate::ThinStrip>,
    /// What looks wrong with the run and what to change (few valid positions, empty pieces, a
    /// ribbon no wider than the pattern).
    pub warnings: Vec<String>,
}

/// The result of [`synthesize`](crate::synthesize).
#[derive(Debug, Clone)]
pub struct Output {
    /// The rendered canvas (transparent background).
    pub image: RgbaImage,
    /// The placed pieces (empty for the repeat baseline).
    pub pieces: Vec<PlacedPiece>,
    /// Figures.
    pub report: Report,
    /// Forbidden canvas pixels.
    pub forbidden: ForbiddenMask,
    /// Top border of the ribbon, canvas coordinates.
    pub ribbon_top: Vec<Point>,
    /// Bottom border of the ribbon, canvas coordinates.
    pub ribbon_bottom: Vec<Point>,
}
