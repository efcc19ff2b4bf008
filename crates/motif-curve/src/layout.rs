//! The first stage of a synthesis ("ribbon"): the curve, its bends rounded, moved onto the
//! canvas; the ribbon sliced into pieces; each piece's frame on the canvas and in the exemplar;
//! the padded exemplar and the cost model that every later stage reads.

use std::sync::Arc;

use motif_core::kurbo::Affine;
use motif_core::{InvalidParameter, Point, Polyline, RgbaImage, Vec2};

use crate::atlas::Atlas;
use crate::avoidance::ForbiddenMask;
use crate::brush::TileKind;
use crate::canvas::{canvas_geometry, ribbon_borders, working_curve};
use crate::cost::CostModel;
use crate::exemplar::Exemplar;
use crate::piece::PieceFrame;
use crate::ribbon::{PieceQuad, Ribbon};
use crate::{Error, Input, Output, Params, PieceShape, PlacedPiece, Report};
use crate::{brush, corners, incremental, ribbon, ribbon_pieces, tight_bends};

/// Advice of the memory errors of a synthesis.
pub(crate) const MEMORY_ADVICE: &str = "use a smaller canvas, longer pieces or a narrower ribbon";

/// The peak memory of a synthesis: the canvas with its forbidden mask and render tiles (about 10
/// bytes a pixel), the valid positions of every piece, the dynamic program's costs and back
/// pointers per position, and the edge samples of two rows.
pub(crate) fn memory_estimate(
    canvas_pixels: f64,
    pieces: f64,
    mean_valid: f64,
    samples: usize,
) -> motif_core::MemoryEstimate {
    let mut estimate = motif_core::MemoryEstimate::new();
    estimate
        .add("canvas", canvas_pixels, 10.0)
        .add("valid positions", pieces * mean_valid, std::mem::size_of::<crate::piece::Position>() as f64)
        .add("dynamic program", pieces * mean_valid, 12.0)
        .add("edge samples", 2.0 * mean_valid * samples as f64, 16.0);
    estimate
}

/// The pieces laid out along the ribbon, on the canvas and in the exemplar: what the later stages
/// of a synthesis share.
pub(crate) struct Layout {
    /// Whether the curve is treated as closed.
    pub closed: bool,
    /// Canvas width and height, pixels.
    pub canvas: (usize, usize),
    /// The document → canvas translation.
    pub shift: Vec2,
    /// The canvas's share of the memory estimate (checked before the ribbon is made).
    pub canvas_memory: u64,
    /// Bends rounded, the largest shift that rounding made, and whether a bend stayed too tight.
    pub rounded_bends: usize,
    pub bend_shift_max: f64,
    pub unresolved_bend: bool,
    /// The ribbon around the canvas curve.
    pub ribbon: Ribbon,
    /// Its pieces.
    pub quads: Vec<PieceQuad>,
    /// `C`, samples per piece edge.
    pub samples: usize,
    /// The rigid frame of each piece: its canvas geometry (fold-overs, rotation) always is.
    pub rigid_frames: Vec<PieceFrame>,
    /// The exemplar side of each piece: the rigid frame or the straightened one.
    pub frames: Vec<PieceFrame>,
    /// Exemplar pixels per canvas pixel along each piece (the scale over the width factor, times
    /// the stretch of a fitted piece).
    pub along_scales: Vec<f64>,
    /// The canvas length of a whole piece as fitted (the piece length unless stretched), and the
    /// gap after each piece (0 unless spaced).
    pub fitted_piece_length: f64,
    pub fit_gap: f64,
    /// The start, end and corner tiles' exemplar columns, within the pattern's extent.
    pub tile_columns: [Option<[u32; 2]>; 3],
    /// Which pieces are tiles.
    pub piece_tiles: Vec<Option<TileKind>>,
    /// Whether pieces bend with the ribbon.
    pub bent: bool,
    /// The ribbon's offset curves, for the debug drawing.
    pub ribbon_top: Vec<Point>,
    pub ribbon_bottom: Vec<Point>,
    /// The exemplars side by side.
    pub atlas: Atlas,
    /// The padded atlas (shared with a session's cache).
    pub exemplar: Arc<Exemplar>,
    /// The matching cost ξ.
    pub model: CostModel,
}

impl Layout {
    /// Lays out the pieces of `input`'s curve; a session's `cache` lends (and keeps) the padded
    /// exemplar.
    pub(crate) fn new(
        input: &Input<'_>,
        params: &Params,
        closed: bool,
        cache: Option<&mut incremental::Cache>,
    ) -> Result<Self, Error> {
        let curve = working_curve(input.curve, closed)?;
        // Rounding moves the curve by at most half the ribbon's width.
        let rounded = tight_bends::round_bends(&curve, params.round_bends * params.width, 0.5 * params.width)?;
        let drawn = curve;
        let curve = rounded.curve;
        let (canvas_width, canvas_height, shift) = canvas_geometry(&curve, params, input.avoidance)?;
        let canvas_pixels = (canvas_width * canvas_height) as f64;
        let canvas_memory = memory_estimate(canvas_pixels, 0.0, 0.0, 0).check(params.max_memory, MEMORY_ADVICE)?;
        let curve = curve.transformed(Affine::translate(shift))?;
        let atlas = Atlas::new(input.exemplar, input.more_exemplars);
        let tile_columns = tile_columns(&atlas, input.exemplar, params);
        // A window at position x covers exemplar x + 0.5 to x + 0.5 + length: columns X0..X1 are
        // drawn from the centre of the first to the centre of the last.
        let [start_tile, end_tile, corner_tile] =
            tile_columns.map(|tile| tile.map_or(0.0, |[x0, x1]| f64::from(x1 - x0 - 1) / params.scale));
        // Corners are those of the curve as drawn; rounding turns each into an arc around it.
        let corners = if corner_tile > 0.0 {
            corners::corner_points(&drawn, 0.5 * corner_tile, params.corner_angle)
                .into_iter()
                .map(|p| p + shift)
                .collect()
        } else {
            Vec::new()
        };
        let (ribbon, corners) = corner_ribbon(&curve, params, closed, [start_tile, end_tile], corner_tile, &corners)?;
        let slices =
            brush::slices(ribbon.length(), params.piece_length, params.fit, closed, [start_tile, end_tile], &corners);
        let quads = ribbon::quads(&ribbon, &slices.bounds);
        let samples = ((params.width * params.scale).ceil() as usize).max(1);
        let bent = params.piece_shape == PieceShape::Bent;
        let (rigid_frames, frames, along_scales) = piece_frames(&ribbon, &quads, params, &slices, closed, samples);
        let (ribbon_top, ribbon_bottom) = ribbon_borders(&ribbon);
        let margin = frames.iter().map(PieceFrame::required_margin).max().unwrap_or(8);
        let exemplar = prepared_exemplar(&atlas, margin, params, cache);
        Ok(Self {
            closed,
            canvas: (canvas_width, canvas_height),
            shift,
            canvas_memory,
            rounded_bends: rounded.bends,
            bend_shift_max: rounded.max_shift,
            unresolved_bend: rounded.unresolved,
            ribbon,
            quads,
            samples,
            rigid_frames,
            frames,
            along_scales,
            fitted_piece_length: slices.piece_length,
            fit_gap: slices.gap,
            tile_columns,
            piece_tiles: slices.tiles.clone(),
            bent,
            ribbon_top,
            ribbon_bottom,
            atlas,
            exemplar,
            model: CostModel::new(params.alpha_mode, params.mismatch_penalty),
        })
    }

    /// The kind of tile piece `i` is and its exemplar columns, when it is one.
    pub(crate) fn tile(&self, i: usize) -> Option<(TileKind, [u32; 2])> {
        let kind = self.piece_tiles[i]?;
        let columns = self.tile_columns[kind.index()]?;
        Some((kind, columns))
    }

    /// Canvas pixels, for the memory estimate.
    pub(crate) fn canvas_pixels(&self) -> f64 {
        (self.canvas.0 * self.canvas.1) as f64
    }

    /// The run's result, the ribbon's borders moved into it.
    pub(crate) fn into_output(
        self,
        image: RgbaImage,
        pieces: Vec<PlacedPiece>,
        report: Report,
        forbidden: ForbiddenMask,
    ) -> Output {
        Output { image, pieces, report, forbidden, ribbon_top: self.ribbon_top, ribbon_bottom: self.ribbon_bottom }
    }
}

/// The ribbon around `curve` and the stretches of it that corner tiles `corner_tile` long take,
/// centred on the points of the ribbon nearest to `corners` (none without a corner tile). A closed
/// curve with corners is restarted where its first tile begins, so that that tile is the first
/// piece.
fn corner_ribbon(
    curve: &Polyline,
    params: &Params,
    closed: bool,
    ends: [f64; 2],
    corner_tile: f64,
    corners: &[Point],
) -> Result<(Ribbon, Vec<(f64, f64)>), InvalidParameter> {
    let ribbon_of = |curve: &Polyline| Ribbon::new(curve, params.width).map(|r| r.with_profile(&params.width_profile));
    let ribbon = ribbon_of(curve)?;
    if corner_tile <= 0.0 || corners.is_empty() {
        return Ok((ribbon, Vec::new()));
    }
    let min_gap = 0.5 * params.piece_length;
    let stretches = |ribbon: &Ribbon| {
        let span = [ends[0], ribbon.length() - ends[1]];
        corners::corner_stretches(ribbon, corners, corner_tile, closed, span, min_gap)
    };
    let found = stretches(&ribbon);
    match found.first() {
        Some(&(start, _)) if closed && start > 0.0 => {
            let ribbon = ribbon_of(&corners::restarted(curve, start))?;
            let found = stretches(&ribbon);
            Ok((ribbon, found))
        }
        _ => Ok((ribbon, found)),
    }
}

/// The start, end and corner tiles' atlas columns: a tile exemplar's whole pattern, or columns of
/// the first exemplar narrowed to the pattern's extent.
fn tile_columns(atlas: &Atlas, first: &RgbaImage, params: &Params) -> [Option<[u32; 2]>; 3] {
    let columns = [params.start_tile, params.end_tile, params.corner_tile];
    let mut tiles = [None; 3];
    for (k, tile) in tiles.iter_mut().enumerate() {
        *tile = match params.tile_exemplars[k] {
            Some(source) => {
                let (x0, x1) = atlas.sources[source];
                let (start, end) = crate::exemplar::pattern_extent(&atlas.image, x0, x1, params.cut_alpha);
                (start + 2 <= end + 1).then_some([start as u32, end as u32 + 1])
            }
            None => tile_in_pattern(first, columns[k], params),
        };
    }
    tiles
}

/// A tile's columns narrowed to the pattern's extent in the first exemplar (the transparent
/// margin beside the pattern is not part of a cap), so that `0,W` takes the pattern's last motif
/// whole; `None` when the narrowed tile is under two columns wide.
fn tile_in_pattern(exemplar: &RgbaImage, tile: Option<[u32; 2]>, params: &Params) -> Option<[u32; 2]> {
    let [x0, x1] = tile?;
    let (first, last) = crate::exemplar::pattern_extent(exemplar, 0, exemplar.width(), params.cut_alpha);
    let x0 = x0.max(first as u32);
    let x1 = x1.min(last as u32 + 1);
    (x0 + 2 <= x1).then_some([x0, x1])
}

/// Each piece's rigid frame, its exemplar-side frame (the rigid one, or straightened for bent
/// pieces) and its scale along the curve.
fn piece_frames(
    ribbon: &Ribbon,
    quads: &[PieceQuad],
    params: &Params,
    slices: &brush::Slices,
    closed: bool,
    samples: usize,
) -> (Vec<PieceFrame>, Vec<PieceFrame>, Vec<f64>) {
    // The canvas geometry of the pieces (fold-overs, rotation) is always the rigid frame's; the
    // exemplar side is the rigid or the straightened frame.
    let rigid_frames: Vec<PieceFrame> = quads.iter().map(|quad| PieceFrame::new(quad, params.scale, samples)).collect();
    let stretch = |i: usize| slices.along[i].0;
    let along_scales: Vec<f64> =
        quads.iter().enumerate().map(|(i, quad)| params.scale * stretch(i) / ribbon.factor(quad.start)).collect();
    let frames: Vec<PieceFrame> = if params.piece_shape == PieceShape::Bent {
        quads
            .iter()
            .zip(&along_scales)
            .enumerate()
            .map(|(i, (quad, &along))| {
                // The shorter last piece of an open curve takes a full-length window and is drawn
                // up to the curve's end: its right edge meets no seam, and every piece then has
                // the same frame, so an edit that keeps the number of pieces changes no DP row.
                // A tile keeps its own length, and so does a piece that a tile follows (its right
                // edge meets the tile's seam).
                let keep = closed || slices.is_tile(i) || (i + 1 < quads.len() && slices.is_tile(i + 1));
                let quad = if keep { *quad } else { PieceQuad { end: quad.start + slices.along[i].1, ..*quad } };
                ribbon_pieces::straight_frame(&quad, params.width * params.scale / along, along, samples)
            })
            .collect()
    } else {
        rigid_frames.clone()
    };
    (rigid_frames, frames, along_scales)
}

/// The atlas padded by `margin`, taken from a session's cache when it has one of that margin
/// (megabytes for wide ribbons, the same for every edit of a session) and left there.
fn prepared_exemplar(
    atlas: &Atlas,
    margin: i32,
    params: &Params,
    cache: Option<&mut incremental::Cache>,
) -> Arc<Exemplar> {
    let cached = cache.as_deref().and_then(|cache| cache.exemplar.clone()).filter(|e| e.pad == margin);
    let prepared: Arc<Exemplar> = cached.unwrap_or_else(|| {
        Arc::new(Exemplar::new(&atlas.image, margin as usize, params.cut_alpha).with_sources(
            &atlas.image,
            &atlas.sources,
            params.cut_alpha,
        ))
    });
    if let Some(cache) = cache {
        cache.exemplar = Some(prepared.clone());
    }
    prepared
}
