//! What looks wrong with a run before it is solved, said with what to change.

use crate::exemplar::Exemplar;
use crate::params::Params;

/// Valid fraction below which the run warns that the pieces hardly fit the pattern.
const FEW_VALID: f64 = 0.01;

/// The fewest samples per piece edge (width × scale) that hold the pattern's rows `(top, bottom)`
/// whole, 0 without a pattern. The top edge reads the row above the corner's and the bottom edge
/// the row below the last, so a piece holds the pattern's whole height only with two clear rows to
/// spare.
pub(crate) fn samples_to_hold(pattern_rows: Option<(i32, i32)>) -> usize {
    pattern_rows.map_or(0, |(top, bottom)| (bottom - top + 3) as usize)
}

/// What looks wrong with a run before it is solved, with what to change.
pub(crate) fn warnings(
    exemplar: &Exemplar,
    params: &Params,
    samples: usize,
    valid_fraction: f64,
    empty: usize,
) -> Vec<String> {
    let mut warnings = Vec::new();
    let needed = samples_to_hold(exemplar.pattern_rows);
    let smallest_width = needed as f64 / params.scale;
    if samples < needed {
        warnings.push(format!(
            "the ribbon is {samples} exemplar pixels wide (width × scale) but the pattern is {} pixels tall: no piece \
             can hold its whole height, so pieces cut it where it has horizontal gaps; for whole motifs use --width {} \
             or more (at scale {})",
            needed - 2,
            smallest_width.ceil(),
            params.scale
        ));
    }
    if valid_fraction < FEW_VALID {
        warnings.push(format!(
            "only {:.2}% of exemplar positions are valid for an average piece: pieces must cut the pattern in \
             transparent pixels at their top and bottom edges; try a wider ribbon (--width {} or more), shorter \
             pieces or a lower --min-coverage",
            100.0 * valid_fraction,
            smallest_width.ceil().max(params.width.ceil() + 1.0)
        ));
    }
    if empty > 0 {
        warnings.push(format!(
            "{empty} piece(s) left empty: fold-overs at sharp bends or the avoidance map forbade every position; \
             shorter pieces (--piece-length) or a narrower ribbon follow sharp bends better"
        ));
    }
    warnings
}
