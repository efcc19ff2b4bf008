//! The valid-positions stage of a synthesis (§1.3, §3.1): every piece's positions in the
//! exemplar that cut the pattern cleanly, keep out of forbidden canvas areas and carry a share of
//! the pattern, with the rules of the pattern-brush options (tiles, spaced pieces) on top.

use motif_core::{InvalidParameter, RgbaImage, Vec2};
use rayon::prelude::*;

use crate::InputError;
use crate::avoidance::ForbiddenMask;
use crate::brush::TileKind;
use crate::exemplar::{Exemplar, Run};
use crate::layout::{Layout, MEMORY_ADVICE, memory_estimate};
use crate::piece::{PieceFrame, Position, candidate_count};
use crate::repeat::Triangle;
use crate::{Error, Fit, Input, Params, Report};
use crate::{avoidance, incremental, repeat, ribbon_pieces, warnings};

/// A piece's valid positions, whether it was left empty by a forbidden area, and its signature
/// (the key of the incremental cache).
type PieceValid = (Vec<Position>, bool, u64);

/// Number of rows of the exemplar holding non-transparent pixels (for error messages).
fn pattern_height(image: &RgbaImage) -> usize {
    image.opaque_bounds().map_or(0, |(_, y0, _, y1)| y1 - y0)
}

/// What the valid-positions stage finds: every piece's valid positions (§1.3, §3.1) and the
/// forbidden samples they avoid, and for bent pieces the ribbon's triangles they are drawn through.
pub(crate) struct Candidates {
    /// Valid positions per piece (one empty position for a piece left empty).
    pub valid: Vec<Vec<Position>>,
    /// Pieces left empty: a forbidden area leaves them no valid position.
    pub empty: Vec<bool>,
    /// Forbidden sample points per piece, in piece-local coordinates.
    pub forbidden_samples: Vec<Vec<Vec2>>,
    /// Bent pieces: the ribbon's triangles and their stretch (empty for rigid pieces).
    pub triangles: Vec<Triangle>,
    pub stretch: Vec<f64>,
    /// Each piece's signature: pieces with one signature have the same frame and list.
    pub signatures: Vec<u64>,
}

impl Candidates {
    /// Lists the valid positions of every piece, after checking the memory they and the dynamic
    /// program will take, and records the validity figures and warnings.
    pub(crate) fn new(
        input: &Input<'_>,
        params: &Params,
        layout: &Layout,
        forbidden: &ForbiddenMask,
        report: &mut Report,
        mut cache: Option<&mut incremental::Cache>,
    ) -> Result<Self, Error> {
        // Bent pieces are drawn (and tested against forbidden pixels) through the ribbon's triangles.
        let (triangles, stretch, spacing) = if layout.bent {
            let (triangles, stretch) = repeat::triangulate(&layout.ribbon);
            let slices = repeat::slice_count(&layout.ribbon);
            (triangles, stretch, (layout.ribbon.length() / slices as f64, slices))
        } else {
            (Vec::new(), Vec::new(), (1.0, 1))
        };
        let forbidden_samples = piece_forbidden_samples(params, layout, forbidden, &triangles, spacing);
        let previous = cache.as_deref_mut().map(|cache| std::mem::take(&mut cache.valid)).unwrap_or_default();
        let valid = valid_positions(params, layout, &forbidden_samples, &previous, report)?;
        if let Some(cache) = cache {
            cache.valid = valid.iter().filter(|(_, empty, _)| !empty).map(|(p, _, s)| (*s, p.clone())).collect();
        }
        if let Some(piece) = valid.iter().position(|(positions, _, _)| positions.is_empty()) {
            if let Some((kind, [x0, x1])) = layout.tile(piece) {
                return Err(uncut_tile(params, kind, [x0, x1]).into());
            }
            let samples = layout.samples;
            return Err(Error::Input(InputError::NoValidPosition {
                piece,
                samples,
                pattern_height: pattern_height(input.exemplar),
            }));
        }
        let signatures: Vec<u64> = valid.iter().map(|(_, _, signature)| *signature).collect();
        let (valid, empty): (Vec<Vec<Position>>, Vec<bool>) = valid.into_iter().map(|(p, e, _)| (p, e)).unzip();
        let candidates = Self { valid, empty, signatures, forbidden_samples, triangles, stretch };
        candidates.record(params, layout, report);
        Ok(candidates)
    }

    /// The share of valid positions, the empty pieces and the warnings they call for.
    fn record(&self, params: &Params, layout: &Layout, report: &mut Report) {
        let (valid, empty) = (&self.valid, &self.empty);
        let candidates = candidate_count(layout.atlas.image.width(), layout.atlas.image.height(), layout.samples);
        report.empty_pieces = empty.iter().filter(|&&e| e).count();
        report.valid_fraction = valid
            .iter()
            .zip(empty)
            .map(|(positions, &is_empty)| if is_empty { 0.0 } else { positions.len() as f64 / candidates as f64 })
            .sum::<f64>()
            / valid.len() as f64;
        report.warnings.extend(warnings::warnings(
            &layout.exemplar,
            params,
            layout.samples,
            report.valid_fraction,
            report.empty_pieces,
        ));
    }
}

/// The forbidden sample points each piece covers (none when no pixel is forbidden).
fn piece_forbidden_samples(
    params: &Params,
    layout: &Layout,
    forbidden: &ForbiddenMask,
    triangles: &[Triangle],
    spacing: (f64, usize),
) -> Vec<Vec<Vec2>> {
    let forbidden_pixels = forbidden.count();
    let n_samples = params.samples_per_axis;
    (0..layout.frames.len())
        .into_par_iter()
        .map(|i| match (forbidden_pixels, layout.bent) {
            (0, _) => Vec::new(),
            (_, true) => ribbon_pieces::forbidden_samples(
                triangles,
                spacing,
                &layout.quads[i],
                params.width,
                [layout.along_scales[i], params.scale],
                forbidden,
                n_samples,
            ),
            (_, false) => avoidance::forbidden_samples(&layout.frames[i], forbidden, n_samples),
        })
        .collect()
}

/// Every piece's valid positions, taken from `previous` (a session's last run, by piece
/// signature) where it has them. The DP's memory follows the valid positions per piece: a few
/// pieces go first, and their counts decide whether the rest may be computed (their lists are
/// kept, not redone). Pieces with the same signature (every bent piece of an open curve but the
/// last, without forbidden areas) have the same list, computed once: on a 600 × 250 exemplar a
/// list took 50 ms, 5 s for a curve of 100 pieces.
fn valid_positions(
    params: &Params,
    layout: &Layout,
    forbidden_samples: &[Vec<Vec2>],
    previous: &std::collections::HashMap<u64, Vec<Position>>,
    report: &mut Report,
) -> Result<Vec<PieceValid>, Error> {
    let frames = &layout.frames;
    let keys: Vec<(u64, Vec<Run>)> = (0..frames.len())
        .into_par_iter()
        .map(|i| {
            let runs = avoidance::forbidden_runs(&forbidden_samples[i]);
            // A tile keeps other positions than a piece of the same frame.
            let tile = layout.tile(i).map_or(0, |(kind, _)| kind.index() as u64 + 1);
            (incremental::piece_signature(&frames[i], &runs).wrapping_add(tile * 0x9e37_79b9_7f4a_7c15), runs)
        })
        .collect();
    let valid_of = |i: usize| -> PieceValid {
        let (signature, runs) = (keys[i].0, &keys[i].1);
        let positions = match previous.get(&signature) {
            Some(positions) => positions.clone(),
            None => frames[i].valid_positions(&layout.exemplar, runs, params.min_coverage),
        };
        let positions =
            if params.fit == Fit::Space { whole_motifs(&frames[i], &layout.exemplar, positions) } else { positions };
        let positions = match layout.tile(i) {
            Some((_, [x0, _])) => positions.into_iter().filter(|u| i64::from(u[0]) == i64::from(x0)).collect(),
            None => outside_tiles(&frames[i], layout, positions),
        };
        // A piece that a forbidden area (a fold-over, the avoidance map) leaves with no valid
        // position stays empty; the DP pays for the gap at its seams.
        if positions.is_empty() && !runs.is_empty() {
            (vec![frames[i].empty_position()], true, signature)
        } else {
            (positions, false, signature)
        }
    };
    let probe_count = frames.len().min(8);
    let probed: Vec<(usize, PieceValid)> =
        (0..probe_count).into_par_iter().map(|k| k * frames.len() / probe_count).map(|i| (i, valid_of(i))).collect();
    let mean_valid = probed.iter().map(|(_, (p, _, _))| p.len()).sum::<usize>() as f64 / probe_count.max(1) as f64;
    report.estimated_memory_bytes =
        memory_estimate(layout.canvas_pixels(), frames.len() as f64, mean_valid, layout.samples)
            .check(params.max_memory, MEMORY_ADVICE)?;
    let mut lists: std::collections::HashMap<u64, PieceValid> =
        probed.into_iter().map(|(_, lists)| (lists.2, lists)).collect();
    let mut missing: Vec<usize> = Vec::new();
    let mut wanted = std::collections::HashSet::new();
    for (i, (signature, _)) in keys.iter().enumerate() {
        if !lists.contains_key(signature) && wanted.insert(*signature) {
            missing.push(i);
        }
    }
    let computed: Vec<PieceValid> = missing.into_par_iter().map(valid_of).collect();
    lists.extend(computed.into_iter().map(|lists| (lists.2, lists)));
    Ok(keys.iter().map(|(signature, _)| lists[signature].clone()).collect())
}

/// The positions whose sides cut the fewest pattern pixels (spaced pieces, whose motifs no
/// neighbour continues across a gap): those with clear sides, which hold whole motifs, or, for a
/// pattern with no clear column (interlocked links, a rope), those that cut it least.
fn whole_motifs(frame: &PieceFrame, exemplar: &Exemplar, positions: Vec<Position>) -> Vec<Position> {
    let sides = frame.side_runs();
    let cut = |u: &Position| sides.iter().map(|run| exemplar.run_occupied(run, u[0], u[1])).sum::<u32>();
    let cuts: Vec<u32> = positions.iter().map(cut).collect();
    let least = cuts.iter().copied().min().unwrap_or(0);
    positions.into_iter().zip(cuts).filter(|&(_, c)| c == least).map(|(u, _)| u).collect()
}

/// The positions of a piece between the tiles whose window stays clear of the tiles' columns: a
/// cap, clasp or corner piece is drawn where its tile goes only.
fn outside_tiles(frame: &PieceFrame, layout: &Layout, positions: Vec<Position>) -> Vec<Position> {
    let tiles: Vec<[u32; 2]> = layout.tile_columns.into_iter().flatten().collect();
    if tiles.is_empty() {
        return positions;
    }
    let corners = frame.local_corners();
    let low = corners.iter().map(|c| c.x).fold(f64::INFINITY, f64::min);
    let high = corners.iter().map(|c| c.x).fold(f64::NEG_INFINITY, f64::max);
    positions
        .into_iter()
        .filter(|u| {
            let (left, right) = (f64::from(u[0]) + 0.5 + low, f64::from(u[0]) + 0.5 + high);
            tiles.iter().all(|&[x0, x1]| right <= f64::from(x0) || left >= f64::from(x1))
        })
        .collect()
}

/// Refuses a pinned first position that is not one of the first piece's valid positions.
pub(crate) fn check_pin(params: &Params, candidates: &Candidates) -> Result<(), Error> {
    let (valid, empty) = (&candidates.valid[0], candidates.empty[0]);
    match params.pin_first {
        Some(pin) if !valid.contains(&pin) || empty => Err(Error::Input(InputError::InvalidPin {
            x: pin[0],
            y: pin[1],
            count: if empty { 0 } else { valid.len() },
        })),
        _ => Ok(()),
    }
}

/// The error for a tile no vertical position of which is cut cleanly, naming the columns or the
/// tile's image.
fn uncut_tile(params: &Params, kind: TileKind, [x0, x1]: [u32; 2]) -> InvalidParameter {
    let advice = "widen the ribbon (--width)";
    if params.tile_exemplars[kind.index()].is_some() {
        return InvalidParameter::new(
            format!("{}-image", kind.option_name()),
            format!("a tile {} px wide", x1 - x0),
            format!(
                "no vertical position of the image is cut cleanly (its pattern needs transparent rows above and \
                 below it, within the ribbon): {advice}, or give an image with a transparent margin"
            ),
        );
    }
    InvalidParameter::new(
        kind.option_name(),
        format!("{x0},{x1}"),
        format!(
            "no vertical position of these columns is cut cleanly (the tile must lie inside the pattern's extent, \
             with its top and bottom edges in transparent pixels): {advice} or choose other columns"
        ),
    )
}
