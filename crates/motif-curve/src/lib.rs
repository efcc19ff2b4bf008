//! Structured patterns along curves, after Zhou, Lasram and Lefebvre, *By-example synthesis of
//! curvilinear structured patterns* (Eurographics 2013).
//!
//! A ribbon around the curve is sliced into pieces; each piece copies a window of the exemplar, and
//! a dynamic program picks the exemplar position of every piece so that the colours across all
//! piece boundaries match best (a global optimum). Modules, by section of the paper:
//!
//! - `ribbon`: the ribbon's offset curves (constant width or a width profile, §1.1) and the
//!   slicing into quadrilateral pieces (§1.3); `tight_bends` first rounds bends tighter than the ribbon
//!   (not in the paper, whose fold-over rule leaves those pieces empty).
//! - `piece`: a piece in exemplar space (rotation `M`, scale `s`, edges `L_i`, `R_i`) and the
//!   validity test of positions (§1.3, §3.1), over `U = W × (H + C)` candidates (§1.4), plus a
//!   minimum-coverage rule and the pattern's side margins (not in the paper); `ribbon_pieces` straightens
//!   pieces that follow the ribbon (the default; the paper's pieces are rigid).
//! - `cost`: the matching cost ξ (binary and continuous alpha, `γ`) and the edge distance `D`
//!   with `C = ⌈‖L‖⌉` bilinear samples (§1, §1.3); `bounds`: lower bounds of `D` from block-sum
//!   profiles and alpha masks, for the exact solver's pruning (not in the paper).
//! - `dp`: the dynamic program of Eq. 1 with backtracking (§1.4, §2): the plain reference
//!   solver, the exact fast solver (its branch and bound in `profile_tree`) and a brute-force
//!   enumerator for tests; `coarse`, the coarse-to-fine solver (not in the paper: the DP on
//!   cells of `f × f` positions, then the exact DP in bands around the coarse optimum); `solve`
//!   runs them (or `closed`) and the repetition control of `variety` (not in the paper).
//! - `closed`: closed curves, the single-DP approximation and an exact, certified mode (§1.5).
//! - `avoidance`: avoidance maps and fold-over detection (§3.1).
//! - `stitch`: the edge alignment of Eq. 2–3 and its propagation inside pieces (§3.2).
//! - `render`: anti-aliased rasterization of the pieces; `repeat`: the classic arc-length
//!   texture-mapping baseline; `overlay`: the debug drawing; `fidelity`: the result read back
//!   along the curve and compared with the exemplar patch by patch; [`samples`]: generated
//!   exemplars for benchmarks.
//! - `brush` (not in the paper; a pattern brush's options): the exemplar flipped along or across
//!   the curve and tinted, pieces fitted to the curve's length ([`Fit`], [`Flip`]), and the start,
//!   end and corner tiles drawn whole between them; `corners` finds the corners that get a corner
//!   tile.
//! - `atlas` (several exemplars, §4's "matches across exemplars") and `incremental`
//!   ([`Incremental`], §4's re-synthesis while the curve is edited).
//! - `pipeline`: a synthesis stage by stage, as the report times them (ribbon, avoidance, valid
//!   positions, dynamic program, stitching, render), the paper's §1–§3 in order; `layout`, its
//!   first stage, lays the pieces out along the ribbon, on the canvas and in the exemplar;
//!   `candidates`, the valid-positions stage (§1.3, §3.1); `thin`, the check for a degenerate
//!   optimum (a thin strip repeated at no cost) after the dynamic program.
//!
//! The entry point is [`synthesize`]. The crate does no I/O and builds for `wasm32`.
//!
//! ```
//! use motif_core::{NoProgress, Point, Polyline, RgbaImage};
//! use motif_curve::{Input, Params, synthesize};
//!
//! // A strip of rings with a transparent background, along a gentle arc.
//! let exemplar = RgbaImage::from_fn(96, 24, |x, y| {
//!     let (dx, dy) = ((x % 16) as f64 - 7.5, y as f64 - 11.5);
//!     let r = (dx * dx + dy * dy).sqrt();
//!     if (4.0..7.0).contains(&r) { [210, 170, 40, 255] } else { [0; 4] }
//! });
//! let arc: Vec<Point> = (0..=40).map(|i| {
//!     let a = f64::from(i) / 40.0;
//!     Point::new(20.0 + 200.0 * a, 80.0 - 60.0 * motif_core::math::sin(a * std::f64::consts::PI))
//! }).collect();
//! let curve = Polyline::new(arc, false).unwrap();
//! let params = Params::default().with_width(24.0).with_piece_length(12.0);
//! params.validate().unwrap();
//! let input = Input::new(&exemplar, &curve);
//! let output = synthesize(&input, &params, &mut NoProgress).unwrap();
//! assert!(output.report.pieces > 10);
//! // Bent pieces continue the rings across every seam.
//! assert_eq!(output.report.total_cost, 0.0);
//! assert!(output.report.warnings.is_empty());
//! ```

mod atlas;
mod avoidance;
mod bounds;
mod brush;
mod candidates;
mod canvas;
mod closed;
mod coarse;
mod corners;
mod cost;
mod dp;
mod error;
mod exemplar;
mod fidelity;
mod incremental;
mod infer;
mod layout;
mod overlay;
mod params;
mod piece;
mod pipeline;
mod profile_tree;
mod render;
mod repeat;
mod report;
mod ribbon;
mod ribbon_pieces;
pub mod samples;
mod solve;
mod stitch;
mod thin;
mod tight_bends;
mod variety;
mod warnings;

use motif_core::{Polyline, Progress, RgbaImage};

pub use crate::brush::{Fit, Flip};
pub use crate::coarse::CoarseReport;
pub use crate::cost::AlphaMode;
pub use crate::dp::{AUTO_COARSE_PAIRS, Solver};
pub use crate::error::{Error, InputError, LimitError};
pub use crate::fidelity::{PatchFidelity, patch_fidelity};
pub use crate::incremental::Incremental;
pub use crate::infer::{Dimension, Dimensions, pattern_period};
pub use crate::overlay::debug_overlay;
pub use crate::params::{Canvas, ClosedMode, MAX_CANVAS_SIDE, Method, Params, PieceShape};
pub use crate::report::{Output, PlacedPiece, Report};
pub use crate::solve::VarietyReport;
pub use crate::thin::ThinStrip;

/// What the engine works on.
#[derive(Debug, Clone, Copy)]
pub struct Input<'a> {
    /// The exemplar: opaque pixels are the pattern, transparent ones the background.
    pub exemplar: &'a RgbaImage,
    /// The curve, in document coordinates (pixels); open or closed.
    pub curve: &'a Polyline,
    /// More exemplars to mix with the first (§4, the paper's future work: "matches across
    /// exemplars"): pieces may come from any of them and seams across exemplars cost the same ξ.
    /// Empty for one exemplar; the repeat baseline uses the first only.
    pub more_exemplars: &'a [RgbaImage],
    /// Optional avoidance map over the canvas (white = forbidden, §3.1); it must have the canvas
    /// size, and with a fitted canvas it sets the canvas size (origin at the document origin).
    pub avoidance: Option<&'a RgbaImage>,
}

impl<'a> Input<'a> {
    /// One exemplar along `curve`, with no avoidance map.
    pub fn new(exemplar: &'a RgbaImage, curve: &'a Polyline) -> Self {
        Self { exemplar, curve, more_exemplars: &[], avoidance: None }
    }

    /// These exemplars mixed with the first.
    pub fn with_more_exemplars(self, more_exemplars: &'a [RgbaImage]) -> Self {
        Self { more_exemplars, ..self }
    }

    /// With an avoidance map over the canvas.
    pub fn with_avoidance(self, avoidance: &'a RgbaImage) -> Self {
        Self { avoidance: Some(avoidance), ..self }
    }
}

/// Synthesizes the pattern of `input.exemplar` along `input.curve`.
pub fn synthesize(input: &Input<'_>, params: &Params, progress: &mut dyn Progress) -> Result<Output, Error> {
    pipeline::synthesize_with(input, params, progress, None)
}

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_brush;
#[cfg(test)]
mod tests_coarse;
#[cfg(test)]
mod tests_features;
