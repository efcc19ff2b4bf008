//! The parameters of the curve engine, their defaults and their validation.

use motif_core::InvalidParameter;
use motif_core::error::{check_count, check_positive, check_range};
use serde::Serialize;

mod tiles;

use crate::brush::{Fit, Flip};
use crate::cost::AlphaMode;
use crate::dp::Solver;
use crate::{Error, Input};

/// How a closed curve is treated (§1.5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ClosedMode {
    /// `Approximate` (`approx`) for a closed curve, `Open` (`no`) for an open one.
    Auto,
    /// The paper's single DP with backtracking from every terminal position.
    #[serde(rename = "approx", alias = "approximate")]
    Approximate,
    /// Branch and bound over start positions with a certificate of optimality.
    Exact,
    /// Treat the curve as open (a closed curve is cut at its first point).
    #[serde(rename = "no", alias = "open")]
    Open,
}

/// Which pattern generator to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// The paper's synthesis: undistorted pieces placed by dynamic programming.
    #[serde(rename = "synth", alias = "synthesis")]
    Synthesis,
    /// The classic baseline: the exemplar repeated along the arc length and bent with the ribbon.
    Repeat,
}

/// How a piece maps the exemplar onto the ribbon.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PieceShape {
    /// The paper's rigid pieces (§1.3): undistorted copies, rotated with their left edge; on a
    /// curve each seam compares a tilted column with a vertical one.
    Rigid,
    /// Pieces that bend with the ribbon (not in the paper): read in ribbon coordinates like the
    /// repeat baseline, so every seam compares vertical columns and continuing the exemplar is
    /// free; stretched outside bends and squeezed inside them.
    Bent,
}

/// Size of the output canvas.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Canvas {
    /// Fitted to the ribbon's bounds plus `margin` pixels; the curve is translated accordingly.
    Fit {
        /// Empty border around the ribbon, in pixels.
        margin: f64,
    },
    /// A fixed size; canvas pixel `(0, 0)` is the curve's document origin.
    Size {
        /// Width in pixels.
        width: usize,
        /// Height in pixels.
        height: usize,
    },
}

/// Parameters of the curve engine.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Params {
    /// Ribbon width `b` in canvas pixels (§1.1). Finite, > 0. Default 64. With scale `s`, each
    /// edge takes `C = ⌈s·b⌉` samples, so `s·b` should exceed the pattern's height in the exemplar.
    pub width: f64,
    /// Piece length `δ` along the curve, canvas pixels (§1.3). Finite, > 0, at most the curve's
    /// length. Default 24. Shorter pieces follow bends better but repeat more.
    pub piece_length: f64,
    /// Scale `s`: exemplar pixels per canvas pixel (§1.3). Finite, in `[0.05, 20]`. Default 1;
    /// 2 draws the pattern at half size.
    pub scale: f64,
    /// Closed-curve handling (§1.5). Default [`ClosedMode::Auto`].
    pub closed: ClosedMode,
    /// Synthesis or the repeat baseline. Default [`Method::Synthesis`].
    pub method: Method,
    /// DP solver (§1.4, §2). Default [`Solver::Auto`] (exact, coarse to fine on large open
    /// problems); the exact and reference solvers give the same optimum,
    /// [`Solver::CoarseToFine`] a cost at least as high (equal on small problems).
    pub solver: Solver,
    /// With [`Solver::CoarseToFine`], also run the exact solver and report the coarse solver's
    /// cost gap (`Report::exact_optimum`, `Report::cost_gap`); the run then takes at least as long
    /// as an exact one. Default false.
    pub check_gap: bool,
    /// Binary (the paper's ξ) or continuous alpha in ξ (§1). Default [`AlphaMode::Continuous`].
    pub alpha_mode: AlphaMode,
    /// `γ`, the cost of matching an opaque with a transparent pixel (§1). Finite, in
    /// `[1, 100000]`. Default 1024 (the paper's value).
    pub mismatch_penalty: f64,
    /// Run the stitching post-process (§3.2). Default false.
    pub stitch: bool,
    /// `P`, the stitching penalty for moving opaque samples (Eq. 3). Finite, in `[0, 100000]`.
    /// Default 32 (the paper's value).
    pub stitch_penalty: f64,
    /// Detect fold-overs and overlaps of the ribbon and keep the pattern out of them (§3.1).
    /// Default true.
    pub foldover_avoidance: bool,
    /// Pin the exemplar position of the first piece (`[x, y]`, top-left corner; must be a valid
    /// position). Default none: the first piece is free (§2).
    pub pin_first: Option<[i32; 2]>,
    /// Output canvas. Default fitted with a margin of 4 pixels.
    pub canvas: Canvas,
    /// Render samples per pixel along each axis (anti-aliasing; the forbidden-area test uses the
    /// same samples). Integer in `[1, 8]`. Default 3.
    pub samples_per_axis: usize,
    /// Alpha at or below which a pixel counts as transparent for the slicing test (§1.3). In
    /// `[0, 254]`. Default 8, so faint anti-aliasing fringes may be cut.
    pub cut_alpha: u8,
    /// Exact closed mode: most start positions tried with a pinned DP before giving up the
    /// certificate. Integer in `[1, 100000]`. Default 64.
    pub closed_max_starts: usize,
    /// Minimum coverage (§1.3, an addition to the paper's validity test): a piece position is
    /// valid only if the pattern pixels inside the piece number at least `min_coverage` × the
    /// piece's typical coverage (the median over the exemplar windows that are cut cleanly and
    /// hold the pattern's whole height). Without it the global optimum may copy one thin sliver
    /// of the pattern (the edge of one ring of a chain) along the whole curve: it is valid and its
    /// seams cost almost nothing. Finite, in `[0, 1]`; 0 is the paper's rule. Default 0.5.
    pub min_coverage: f64,
    /// `W`, the repetition penalty (not in the paper): each pair of pieces at most
    /// `variety_radius` pieces apart that copy the same exemplar window adds `W` to the energy,
    /// in the units of the seam cost (the report's `mean_seam_cost`). Finite, in `[0, 10^6]`.
    /// Default 0 (the paper's energy, which may repeat two windows along a straight line).
    pub variety: f64,
    /// Bends of the curve with a radius below `round_bends × width` are rounded to that radius
    /// before slicing (not in the paper, which leaves the pattern out where the ribbon folds,
    /// §3.1: whole pieces stay empty at cusps and corners). Below 0.5 the inner side of the
    /// ribbon may still fold. Finite, in `[0, 8]`; 0 keeps the curve as given. Default 0.6.
    pub round_bends: f64,
    /// Width profile (the paper: "the width b could vary freely along the ribbon", §1.1):
    /// `(t, factor)` pairs, `t` the fraction of the curve's arc length in `[0, 1]`, ascending,
    /// `factor` in `[0.1, 10]`; the ribbon's width at `t` is `width ×` the interpolated factor and
    /// the pattern scales with it. Needs bent pieces. Default empty (constant width).
    pub width_profile: Vec<(f64, f64)>,
    /// Rigid pieces (the paper) or pieces bent with the ribbon. Default [`PieceShape::Bent`].
    pub piece_shape: PieceShape,
    /// Refuse runs whose estimated peak memory (canvas, valid positions and dynamic program over
    /// all pieces, edge samples) passes this many bytes. Default
    /// [`DEFAULT_MAX_MEMORY`](motif_core::DEFAULT_MAX_MEMORY) (4 GiB); the CLI sets half of the
    /// machine's memory.
    pub max_memory: u64,
    /// `R`, how many pieces apart a repeated window is penalised. Integer in `[1, 1000]`.
    /// Default 8.
    pub variety_radius: usize,
    /// How the pieces meet the curve's length (not in the paper, which cuts the last piece):
    /// stretched to a whole number of pieces, or spaced out. Default [`Fit::None`]. Stretching
    /// needs bent pieces.
    pub fit: Fit,
    /// Mirror the exemplar along or across the curve. Default [`Flip::None`].
    pub flip: Flip,
    /// Colourize the exemplar as tints of this colour (sRGB): black becomes the colour, white
    /// stays white. Default none (the exemplar's own colours).
    pub tint: Option<[u8; 3]>,
    /// A start tile: columns `[x0, x1)` of the first exemplar drawn whole as the first piece of an
    /// open curve (from the centre of column `x0` to that of `x1 − 1`: its length is
    /// `(x1 − x0 − 1) / scale`), joined to the next piece by the same seam cost;
    /// the DP chooses its vertical position. Default none.
    pub start_tile: Option<[u32; 2]>,
    /// An end tile: columns `[x0, x1)` of the first exemplar drawn whole as the last piece, ending
    /// at the curve's end. Default none.
    pub end_tile: Option<[u32; 2]>,
    /// A corner tile: columns `[x0, x1)` of the first exemplar drawn whole, centred on every
    /// corner of the curve (open or closed) sharper than [`Params::corner_angle`], joined to the
    /// pieces beside it by the same seam cost. Default none.
    pub corner_tile: Option<[u32; 2]>,
    /// The turn, in degrees, that makes a corner for [`Params::corner_tile`]: the angle between
    /// the curve's directions half a tile before and half a tile after it. Default 60.
    pub corner_angle: f64,
    /// Tiles drawn from an image of their own: the start, end and corner tiles are the whole
    /// pattern of these exemplars (indices into the first exemplar and
    /// [`Input::more_exemplars`](crate::Input::more_exemplars), 1 for the first of those), in
    /// place of the columns of [`Params::start_tile`], [`Params::end_tile`] and
    /// [`Params::corner_tile`]. The pieces between never copy a tile's exemplar. Default none.
    pub tile_exemplars: [Option<usize>; 3],
}

impl Params {
    /// The defaults, as documented on each field.
    pub const DEFAULT: Params = Params {
        width: 64.0,
        piece_length: 24.0,
        scale: 1.0,
        closed: ClosedMode::Auto,
        method: Method::Synthesis,
        solver: Solver::Auto,
        check_gap: false,
        alpha_mode: AlphaMode::Continuous,
        mismatch_penalty: 1024.0,
        stitch: false,
        stitch_penalty: 32.0,
        foldover_avoidance: true,
        pin_first: None,
        canvas: Canvas::Fit { margin: 4.0 },
        samples_per_axis: 3,
        cut_alpha: 8,
        closed_max_starts: 64,
        min_coverage: 0.5,
        variety: 0.0,
        variety_radius: 8,
        round_bends: 0.6,
        piece_shape: PieceShape::Bent,
        width_profile: Vec::new(),
        max_memory: motif_core::DEFAULT_MAX_MEMORY,
        fit: Fit::None,
        flip: Flip::None,
        tint: None,
        start_tile: None,
        end_tile: None,
        corner_tile: None,
        corner_angle: 60.0,
        tile_exemplars: [None; 3],
    };
}

impl Default for Params {
    fn default() -> Self {
        Self::DEFAULT
    }
}

// `with_*` builders, one per field: `Params::default().with_width(80.0).with_piece_length(20.0)`.
motif_core::builders! { Params {
    with_width => width: f64,
    with_piece_length => piece_length: f64,
    with_scale => scale: f64,
    with_closed => closed: ClosedMode,
    with_method => method: Method,
    with_solver => solver: Solver,
    with_check_gap => check_gap: bool,
    with_alpha_mode => alpha_mode: AlphaMode,
    with_mismatch_penalty => mismatch_penalty: f64,
    with_stitch => stitch: bool,
    with_stitch_penalty => stitch_penalty: f64,
    with_foldover_avoidance => foldover_avoidance: bool,
    with_pin_first => pin_first: Option<[i32; 2]>,
    with_canvas => canvas: Canvas,
    with_samples_per_axis => samples_per_axis: usize,
    with_cut_alpha => cut_alpha: u8,
    with_closed_max_starts => closed_max_starts: usize,
    with_min_coverage => min_coverage: f64,
    with_variety => variety: f64,
    with_variety_radius => variety_radius: usize,
    with_round_bends => round_bends: f64,
    with_piece_shape => piece_shape: PieceShape,
    with_width_profile => width_profile: Vec<(f64, f64)>,
    with_max_memory => max_memory: u64,
    with_fit => fit: Fit,
    with_flip => flip: Flip,
    with_tint => tint: Option<[u8; 3]>,
    with_start_tile => start_tile: Option<[u32; 2]>,
    with_end_tile => end_tile: Option<[u32; 2]>,
    with_corner_tile => corner_tile: Option<[u32; 2]>,
    with_corner_angle => corner_angle: f64,
    with_tile_exemplars => tile_exemplars: [Option<usize>; 3],
}}

/// Largest canvas accepted, pixels (the image, the forbidden mask and the render's tiles take
/// about 10 bytes a pixel).
pub(crate) const MAX_CANVAS_PIXELS: usize = 100_000_000;
/// Farthest curve coordinate accepted, pixels from the origin.
pub(crate) const MAX_COORDINATE: f64 = 1e6;
/// Longest curve accepted, pixels.
pub(crate) const MAX_CURVE_LENGTH: f64 = 1e6;
/// Most pieces one synthesis takes (each is a row of the dynamic program).
pub(crate) const MAX_PIECES: usize = 20_000;

/// Largest canvas side accepted.
pub const MAX_CANVAS_SIDE: usize = 16384;

/// Checks the parameters and inputs; returns the resolved closed flag.
/// Checks the width profile: ascending fractions in `[0, 1]`, factors in `[0.1, 10]`, bent pieces,
/// and the widest part within the exemplar-space limit.
fn check_width_profile(params: &Params) -> Result<(), InvalidParameter> {
    let profile = &params.width_profile;
    if profile.is_empty() {
        return Ok(());
    }
    if params.piece_shape != PieceShape::Bent {
        return Err(InvalidParameter::new(
            "width-profile",
            "with rigid pieces",
            "a varying width needs bent pieces (--pieces-shape bent)",
        ));
    }
    if profile.len() > 10_000 {
        return Err(InvalidParameter::new("width-profile", profile.len(), "must have at most 10000 entries"));
    }
    for (k, &(t, factor)) in profile.iter().enumerate() {
        check_range("width-profile position", t, 0.0, 1.0)?;
        check_range("width-profile factor", factor, 0.1, 10.0)?;
        if k > 0 && t < profile[k - 1].0 {
            return Err(InvalidParameter::new(
                "width-profile",
                format!("{t} after {}", profile[k - 1].0),
                "positions must be in ascending order",
            ));
        }
    }
    Ok(())
}

/// Most exemplars besides the first that one synthesis mixes.
pub(crate) const MAX_MORE_EXEMPLARS: usize = 15;

/// How errors name exemplar `index`: "exemplar", "exemplar 2", …, or the tile image it holds
/// ("corner-tile-image").
fn exemplar_name(params: &Params, index: usize) -> String {
    let kinds = ["start-tile-image", "end-tile-image", "corner-tile-image"];
    match params.tile_exemplars.iter().position(|&source| source == Some(index)) {
        Some(kind) => kinds[kind].to_string(),
        None if index == 0 => "exemplar".to_string(),
        None => format!("exemplar {}", index + 1),
    }
}

/// Checks one exemplar, named `name` in errors ([`exemplar_name`]).
fn check_exemplar(exemplar: &motif_core::RgbaImage, name: &str) -> Result<(), InvalidParameter> {
    let name = name.to_string();
    if exemplar.is_empty() {
        return Err(InvalidParameter::new(&name, "0×0", "must have pixels"));
    }
    if exemplar.width() > 2048 || exemplar.height() > 2048 {
        return Err(InvalidParameter::new(
            &name,
            format!("{}×{}", exemplar.width(), exemplar.height()),
            "must be at most 2048×2048 (the dynamic program grows with the square of the pixel count)",
        ));
    }
    if exemplar.is_fully_transparent() {
        return Err(InvalidParameter::new(
            &name,
            "fully transparent",
            "must contain opaque pixels (the pattern) on a transparent background",
        ));
    }
    if exemplar.is_fully_opaque() {
        return Err(InvalidParameter::new(
            &name,
            "fully opaque",
            "must have a transparent background around the pattern (pieces are cut in transparent pixels)",
        ));
    }
    Ok(())
}

impl Params {
    /// Checks every parameter on its own (the checks that need the inputs, such as the piece
    /// length against the curve's length, run in [`synthesize`](crate::synthesize)). The error
    /// names the parameter as the CLI flag does and says what is allowed
    /// ([`Error::Parameter`]).
    pub fn validate(&self) -> Result<(), Error> {
        Ok(self.check()?)
    }

    /// [`Params::validate`]'s checks, with the parameter's error itself.
    fn check(&self) -> Result<(), InvalidParameter> {
        let params = self;
        check_positive("width", params.width)?;
        check_positive("piece-length", params.piece_length)?;
        check_range("scale", params.scale, 0.05, 20.0)?;
        check_range("gamma", params.mismatch_penalty, 1.0, 100_000.0)?;
        check_range("stitch-penalty", params.stitch_penalty, 0.0, 100_000.0)?;
        check_count("samples-per-axis", params.samples_per_axis, 1, 8)?;
        check_count("closed-max-starts", params.closed_max_starts, 1, 100_000)?;
        motif_core::memory::check_max_memory(params.max_memory)?;
        check_range("min-coverage", params.min_coverage, 0.0, 1.0)?;
        check_range("variety", params.variety, 0.0, 1e6)?;
        check_range("round-bends", params.round_bends, 0.0, 8.0)?;
        check_range("corner-angle", params.corner_angle, 10.0, 179.0)?;
        check_width_profile(params)?;
        if params.fit == Fit::Stretch && params.piece_shape != PieceShape::Bent {
            return Err(InvalidParameter::new(
                "fit",
                "stretch with rigid pieces",
                "stretching pieces along the curve needs bent pieces (--pieces-shape bent)",
            ));
        }
        check_count("variety-radius", params.variety_radius, 1, 1000)?;
        if params.cut_alpha == 255 {
            return Err(InvalidParameter::new("cut-alpha", 255, "must be between 0 and 254"));
        }
        // Pieces live in exemplar space: keep them (and the transparent margin around the exemplar
        // that their positions need) to a sane size.
        if params.width * params.scale > 1024.0 {
            return Err(InvalidParameter::new(
                "width",
                params.width,
                "width × scale must be at most 1024 exemplar pixels",
            ));
        }
        if params.piece_length * params.scale > 1024.0 {
            return Err(InvalidParameter::new(
                "piece-length",
                params.piece_length,
                "piece-length × scale must be at most 1024 exemplar pixels",
            ));
        }
        if params.piece_length * params.scale < 1.0 {
            return Err(InvalidParameter::new(
                "piece-length",
                motif_core::error::number(params.piece_length),
                "piece-length × scale must be at least 1 exemplar pixel (a piece copies whole columns)",
            ));
        }
        if let Canvas::Size { width, height } = params.canvas
            && (width == 0 || height == 0 || width > MAX_CANVAS_SIDE || height > MAX_CANVAS_SIDE)
        {
            return Err(InvalidParameter::new(
                "canvas",
                format!("{width}×{height}"),
                format!("each side must be between 1 and {MAX_CANVAS_SIDE}"),
            ));
        }
        if let Canvas::Fit { margin } = params.canvas {
            check_range("margin", margin, 0.0, 4096.0)?;
        }
        Ok(())
    }
}

pub(crate) fn validate(input: &Input<'_>, params: &Params) -> Result<bool, Error> {
    params.validate()?;
    if input.more_exemplars.len() > MAX_MORE_EXEMPLARS {
        return Err(InvalidParameter::new(
            "exemplar",
            input.more_exemplars.len() + 1,
            format!("at most {} exemplars can be mixed", MAX_MORE_EXEMPLARS + 1),
        )
        .into());
    }
    for (index, exemplar) in std::iter::once(input.exemplar).chain(input.more_exemplars).enumerate() {
        check_exemplar(exemplar, &exemplar_name(params, index))?;
    }
    let length = input.curve.length();
    let far = input.curve.points().iter().map(|p| p.x.abs().max(p.y.abs())).fold(0.0, f64::max);
    if !(length.is_finite() && far <= MAX_COORDINATE && length <= MAX_CURVE_LENGTH) {
        return Err(InvalidParameter::new(
            "path",
            format!("length {length:.3e}, farthest coordinate {far:.3e}"),
            format!(
                "the curve must stay within ±{MAX_COORDINATE:.0e} pixels of the origin and be at most \
                 {MAX_CURVE_LENGTH:.0e} pixels long; scale it down"
            ),
        )
        .into());
    }
    let pieces = (length / params.piece_length).ceil();
    if pieces > MAX_PIECES as f64 {
        return Err(InvalidParameter::new(
            "piece-length",
            params.piece_length,
            format!(
                "the curve ({length:.0} px) would take {pieces:.0} pieces, at most {MAX_PIECES}; use pieces of at least \
                 {:.2} px",
                length / MAX_PIECES as f64
            ),
        )
        .into());
    }
    if params.piece_length > length {
        return Err(InvalidParameter::new(
            "piece-length",
            params.piece_length,
            format!("must not exceed the curve's length ({length:.2})"),
        )
        .into());
    }
    tiles::check_tiles(input, params, length)?;
    let closed = match (params.closed, input.curve.is_closed()) {
        (ClosedMode::Auto, closed) => closed,
        (ClosedMode::Open, _) => false,
        (ClosedMode::Approximate | ClosedMode::Exact, true) => true,
        (mode, false) => {
            return Err(InvalidParameter::new(
                "closed",
                format!("{mode:?}").to_lowercase(),
                "the curve is open; use auto or no (close the path with Z in SVG)",
            )
            .into());
        }
    };
    let start = params.start_tile.is_some() || params.tile_exemplars[0].is_some();
    if closed && (start || params.end_tile.is_some() || params.tile_exemplars[1].is_some()) {
        let name = if start { "start-tile" } else { "end-tile" };
        return Err(
            InvalidParameter::new(name, "on a closed curve", "a closed curve has no ends; use --closed no").into()
        );
    }
    Ok(closed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builders_set_fields_and_validate_names_the_flag() {
        assert_eq!(Params::default(), Params::DEFAULT);
        let params = Params::default().with_width(80.0).with_piece_length(20.0).with_variety(5.0);
        assert_eq!((params.width, params.piece_length, params.variety), (80.0, 20.0, 5.0));
        assert!(params.validate().is_ok());
        let error = Params::default().with_round_bends(-1.0).check().unwrap_err();
        assert_eq!(error.name, "round-bends");
        let error = Params::default().with_piece_length(1e-300).check().unwrap_err();
        assert_eq!((error.name.as_str(), error.value.as_str()), ("piece-length", "1e-300"));
        let error = Params::default().with_width_profile(vec![(0.0, 2.0)]).with_piece_shape(PieceShape::Rigid);
        assert!(error.validate().unwrap_err().to_string().contains("bent"));
    }
}
