//! Degenerate optima (not in the paper; issue 37): a thin strip of the exemplar (a frieze's end
//! line, a border) that repeats at no seam cost wins the dynamic program over the motifs, whose
//! seams cost something, and `--variety` cannot help since the strip's windows are all different
//! positions. Detected after the DP: when the chosen pieces hold on average less than half of
//! what the exemplar's motif windows hold, windows that thin are taken out of every piece's list
//! (an infinite cost for covering less than half the motif) and the DP runs again; a piece none of
//! whose windows is that full keeps its list. Runs whose pieces hold their motifs are untouched,
//! and so are runs with `min_coverage` 0 (the paper's rule, without any coverage rule).

use std::collections::HashMap;

use rayon::prelude::*;
use serde::Serialize;

use crate::exemplar::Exemplar;
use crate::piece::{PieceFrame, Position};

/// The share of the motif below which a piece is thin.
pub(crate) const THIN_SHARE: f64 = 0.5;

/// What the check found and changed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ThinStrip {
    /// The chosen pieces' mean share of their motif (coverage over the 90th percentile of the
    /// piece's valid windows' coverage) in the first optimum.
    pub share_before: f64,
    /// The same after the thin windows were taken out.
    pub share_after: f64,
    /// Windows taken out of the pieces' lists.
    pub positions_dropped: usize,
}

/// Windows a piece's motif coverage is measured on, at most (evenly spaced over its list).
const MOTIF_SAMPLE: usize = 1024;

/// A piece's motif coverage: the 90th percentile of its valid windows' coverage (over at most
/// [`MOTIF_SAMPLE`] of them, evenly spaced).
fn motif_coverage(frame: &PieceFrame, exemplar: &Exemplar, positions: &[Position]) -> u32 {
    let stride = positions.len().div_ceil(MOTIF_SAMPLE).max(1);
    let mut coverages: Vec<u32> = positions.iter().step_by(stride).map(|&u| frame.coverage(exemplar, u)).collect();
    if coverages.is_empty() {
        return 0;
    }
    let rank = (coverages.len() - 1) * 9 / 10;
    *coverages.select_nth_unstable(rank).1
}

/// Per piece that the dynamic program chooses freely (`free[i]`), its motif coverage; measured
/// once per piece signature (every bent piece of an open curve shares one), in parallel.
pub(crate) fn motif_coverages(
    frames: &[PieceFrame],
    exemplar: &Exemplar,
    valid: &[Vec<Position>],
    free: &[bool],
    signatures: &[u64],
) -> Vec<Option<u32>> {
    let mut first_of: HashMap<u64, usize> = HashMap::new();
    for i in (0..frames.len()).filter(|&i| free[i]) {
        first_of.entry(signatures[i]).or_insert(i);
    }
    let mut representatives: Vec<usize> = first_of.values().copied().collect();
    representatives.sort_unstable();
    let measured: HashMap<u64, u32> = representatives
        .into_par_iter()
        .map(|i| (signatures[i], motif_coverage(&frames[i], exemplar, &valid[i])))
        .collect();
    (0..frames.len()).map(|i| free[i].then(|| measured[&signatures[i]]).filter(|&c| c > 0)).collect()
}

/// The chosen pieces' mean share of their motif (1 when no piece is measured).
pub(crate) fn mean_share(
    frames: &[PieceFrame],
    exemplar: &Exemplar,
    motifs: &[Option<u32>],
    chosen: &[Position],
) -> f64 {
    let shares: Vec<f64> = motifs
        .iter()
        .enumerate()
        .filter_map(|(i, motif)| motif.map(|m| f64::from(frames[i].coverage(exemplar, chosen[i])) / f64::from(m)))
        .collect();
    if shares.is_empty() { 1.0 } else { shares.iter().sum::<f64>() / shares.len() as f64 }
}

/// Every measured piece's windows that hold at least [`THIN_SHARE`] of its motif (its whole list
/// when none does), and how many windows were taken out.
pub(crate) fn without_thin(
    frames: &[PieceFrame],
    exemplar: &Exemplar,
    valid: &[Vec<Position>],
    motifs: &[Option<u32>],
) -> (Vec<Vec<Position>>, usize) {
    let mut dropped = 0;
    let kept = valid
        .iter()
        .enumerate()
        .map(|(i, positions)| {
            let Some(motif) = motifs[i] else { return positions.clone() };
            let floor = THIN_SHARE * f64::from(motif);
            let full: Vec<Position> =
                positions.iter().copied().filter(|&u| f64::from(frames[i].coverage(exemplar, u)) >= floor).collect();
            if full.is_empty() {
                return positions.clone();
            }
            dropped += positions.len() - full.len();
            full
        })
        .collect();
    (kept, dropped)
}
