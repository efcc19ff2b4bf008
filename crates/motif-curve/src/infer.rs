//! The ribbon width and the piece length, inferred from the exemplar when a run does not give
//! them (not in the paper, which leaves both to the user).
//!
//! - **Width**: the smallest width whose pieces hold the pattern's whole height (the rows with
//!   alpha above `cut_alpha`, plus the clear row above and below that the slicing test reads),
//!   widened by [`WIDTH_MARGIN`] so that pieces can shift vertically and still cut through
//!   transparent rows at their top and bottom, divided by the scale.
//! - **Piece length**: [`PERIOD_FRACTION`] of the pattern's period along x, the first strong peak
//!   of the normalized autocorrelation of the exemplar's columns ([`pattern_period`]), kept
//!   between [`MIN_HEIGHT_FRACTION`] and [`MAX_HEIGHT_FRACTION`] of the pattern's height (a long
//!   period, such as a frieze whose motif repeats only once per exemplar, would make pieces too
//!   long to follow bends; a short one would cut every motif), divided by the scale; without a
//!   period, [`FALLBACK_FRACTION`] of the pattern's height.

use motif_core::error::check_range;
use motif_core::{InvalidParameter, RgbaImage};
use serde::Serialize;

use crate::exemplar::Exemplar;
use crate::warnings::samples_to_hold;

/// Share of the smallest width that holds the pattern added to the inferred width.
pub(crate) const WIDTH_MARGIN: f64 = 0.15;
/// Inferred piece length as a share of the pattern's period.
pub(crate) const PERIOD_FRACTION: f64 = 0.55;
/// Inferred piece length as a share of the pattern's height when no period is found.
pub(crate) const FALLBACK_FRACTION: f64 = 0.3;
/// Shortest inferred piece length from a period, as a share of the pattern's height.
pub(crate) const MIN_HEIGHT_FRACTION: f64 = 0.25;
/// Longest inferred piece length from a period, as a share of the pattern's height.
pub(crate) const MAX_HEIGHT_FRACTION: f64 = 0.6;
/// Least normalized autocorrelation of a peak that counts as the period.
const PEAK_MIN: f64 = 0.4;
/// How far the autocorrelation must have fallen below a peak, at a smaller lag, for the peak to
/// count (a valley between lag 0 and the period).
const PROMINENCE: f64 = 0.3;
/// Most row bands a column profile has (rows are summed into bands to bound the work).
const MAX_BANDS: usize = 64;

/// One ribbon dimension of a run: its value in canvas pixels and whether it was inferred.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Dimension {
    /// Canvas pixels.
    pub value: f64,
    /// True when inferred from the exemplar, false when given.
    pub inferred: bool,
}

/// The width and piece length of a run, given or inferred, and what the inference measured.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Dimensions {
    /// Ribbon width `b`.
    pub width: Dimension,
    /// Piece length `δ`.
    pub piece_length: Dimension,
    /// Rows of the pattern in the exemplar (alpha above `cut_alpha`); `None` when nothing was
    /// inferred.
    pub pattern_height: Option<usize>,
    /// The pattern's period along x in exemplar pixels; `None` when none was found or nothing was
    /// inferred.
    pub period: Option<usize>,
}

impl Dimensions {
    /// The given `width` and `piece_length`, the missing ones inferred from `exemplar` (drawn at
    /// `scale` exemplar pixels per canvas pixel, transparent at or below `cut_alpha`). Errors when
    /// one must be inferred and the scale is out of range or the exemplar holds no pattern.
    pub fn resolve(
        exemplar: &RgbaImage,
        width: Option<f64>,
        piece_length: Option<f64>,
        scale: f64,
        cut_alpha: u8,
    ) -> Result<Self, InvalidParameter> {
        let given = |value: f64| Dimension { value, inferred: false };
        if let (Some(width), Some(piece_length)) = (width, piece_length) {
            return Ok(Self {
                width: given(width),
                piece_length: given(piece_length),
                pattern_height: None,
                period: None,
            });
        }
        check_range("scale", scale, 0.05, 20.0)?;
        let rows = pattern_rows(exemplar, cut_alpha)?;
        let height = (rows.1 - rows.0 + 1) as usize;
        let period = pattern_period(exemplar, cut_alpha);
        let inferred = |value: f64| Dimension { value, inferred: true };
        Ok(Self {
            width: width.map_or_else(|| inferred(inferred_width(rows, scale)), given),
            piece_length: piece_length.map_or_else(|| inferred(inferred_piece_length(period, height, scale)), given),
            pattern_height: Some(height),
            period,
        })
    }
}

/// First and last rows with alpha above `cut_alpha`, or an error saying no pattern was found.
fn pattern_rows(exemplar: &RgbaImage, cut_alpha: u8) -> Result<(i32, i32), InvalidParameter> {
    if exemplar.is_empty() {
        return Err(InvalidParameter::new("exemplar", "0×0", "must have pixels"));
    }
    Exemplar::new(exemplar, 0, cut_alpha).pattern_rows.ok_or_else(|| {
        InvalidParameter::new(
            "exemplar",
            "no pattern",
            format!(
                "no pattern found to infer --width and --piece-length from: every pixel has alpha at or below \
                 --cut-alpha {cut_alpha}"
            ),
        )
    })
}

/// The smallest width that holds the pattern's rows, plus [`WIDTH_MARGIN`], in canvas pixels.
fn inferred_width(rows: (i32, i32), scale: f64) -> f64 {
    let smallest = samples_to_hold(Some(rows)) as f64;
    (smallest * (1.0 + WIDTH_MARGIN) / scale).ceil()
}

/// [`PERIOD_FRACTION`] of the period within the height's bounds, or [`FALLBACK_FRACTION`] of the
/// height, in whole canvas pixels (at least 1).
fn inferred_piece_length(period: Option<usize>, height: usize, scale: f64) -> f64 {
    let height = height as f64;
    let exemplar_pixels = match period {
        Some(period) => {
            (PERIOD_FRACTION * period as f64).clamp(MIN_HEIGHT_FRACTION * height, MAX_HEIGHT_FRACTION * height)
        }
        None => FALLBACK_FRACTION * height,
    };
    (exemplar_pixels / scale).round().max(1.0)
}

/// The pattern's period along x in exemplar pixels: the first lag at which the normalized
/// autocorrelation of the columns (premultiplied colour and alpha summed in row bands, their mean
/// removed) peaks at 0.4 or more, 0.3 above a valley at a smaller lag,
/// searched up to half the pattern's width. `None` when the exemplar holds no pattern or no such peak exists.
pub fn pattern_period(exemplar: &RgbaImage, cut_alpha: u8) -> Option<usize> {
    let columns = column_profiles(exemplar, cut_alpha)?;
    let correlation: Vec<f64> = (0..=columns.len() / 2).map(|lag| autocorrelation(&columns, lag)).collect();
    first_strong_peak(&correlation)
}

/// Per column of the pattern's horizontal extent, its premultiplied RGBA summed in row bands, with
/// the mean column subtracted. `None` without a pattern.
fn column_profiles(exemplar: &RgbaImage, cut_alpha: u8) -> Option<Vec<Vec<f64>>> {
    let prepared = Exemplar::new(exemplar, 0, cut_alpha);
    prepared.pattern_rows?;
    let (first, last) = prepared.pattern_columns[0];
    let bands = exemplar.height().min(MAX_BANDS);
    let mut columns: Vec<Vec<f64>> = (first..=last)
        .map(|x| {
            let mut profile = vec![0.0; 4 * bands];
            for y in 0..exemplar.height() {
                let pixel = exemplar.get(x as usize, y);
                let alpha = f64::from(pixel[3]) / 255.0;
                let band = y * bands / exemplar.height();
                for (channel, &value) in pixel.iter().enumerate() {
                    let value = if channel == 3 { alpha } else { alpha * f64::from(value) / 255.0 };
                    profile[4 * band + channel] += value;
                }
            }
            profile
        })
        .collect();
    let mean: Vec<f64> =
        (0..4 * bands).map(|k| columns.iter().map(|c| c[k]).sum::<f64>() / columns.len() as f64).collect();
    for column in &mut columns {
        column.iter_mut().zip(&mean).for_each(|(value, m)| *value -= m);
    }
    Some(columns)
}

/// Normalized correlation of the columns with themselves shifted by `lag` (1 at lag 0, 0 when
/// either side has no variation).
fn autocorrelation(columns: &[Vec<f64>], lag: usize) -> f64 {
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(p, q)| p * q).sum::<f64>();
    let (mut cross, mut left, mut right) = (0.0, 0.0, 0.0);
    for (a, b) in columns.iter().zip(&columns[lag..]) {
        cross += dot(a, b);
        left += dot(a, a);
        right += dot(b, b);
    }
    let norm = (left * right).sqrt();
    if norm > 0.0 { cross / norm } else { 0.0 }
}

/// The first local maximum of `correlation` (indexed by lag) of at least [`PEAK_MIN`] and
/// [`PROMINENCE`] above the lowest value at a smaller lag.
fn first_strong_peak(correlation: &[f64]) -> Option<usize> {
    let mut valley = f64::INFINITY;
    for lag in 1..correlation.len().saturating_sub(1) {
        let r = correlation[lag];
        valley = valley.min(r);
        if r >= PEAK_MIN && r - valley >= PROMINENCE && r >= correlation[lag - 1] && r >= correlation[lag + 1] {
            return Some(lag);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::samples;

    #[test]
    fn a_generated_chain_has_its_period_and_height() {
        for period in [16.0, 24.0, 37.0] {
            let chain = samples::chain(240, 48, period, 32.0, 0);
            let found = pattern_period(&chain, 8).unwrap();
            assert!((found as f64 - period).abs() <= 1.0, "period {period}: found {found}");
            let dimensions = Dimensions::resolve(&chain, None, None, 1.0, 8).unwrap();
            let height = dimensions.pattern_height.unwrap();
            assert!((35..=37).contains(&height), "height {height}");
            assert_eq!(dimensions.width.value, ((height + 2) as f64 * (1.0 + WIDTH_MARGIN)).ceil());
            let expected = (PERIOD_FRACTION * found as f64)
                .clamp(MIN_HEIGHT_FRACTION * height as f64, MAX_HEIGHT_FRACTION * height as f64);
            assert_eq!(dimensions.piece_length.value, expected.round());
            assert!(dimensions.width.inferred && dimensions.piece_length.inferred);
        }
    }

    #[test]
    fn the_gold_chain_period_is_the_link_pair() {
        let chain = samples::gold_chain(300, 60, 40.0, 40.0);
        let found = pattern_period(&chain, 8).unwrap();
        assert!((39..=41).contains(&found), "found {found}");
    }

    #[test]
    fn scale_divides_and_given_values_win() {
        let chain = samples::chain(240, 48, 24.0, 32.0, 0);
        let one = Dimensions::resolve(&chain, None, None, 1.0, 8).unwrap();
        let two = Dimensions::resolve(&chain, None, None, 2.0, 8).unwrap();
        assert_eq!(two.width.value, (one.width.value / 2.0).ceil().max(two.width.value));
        assert_eq!(two.piece_length.value, (one.piece_length.value / 2.0).round());
        let given = Dimensions::resolve(&chain, Some(50.0), None, 1.0, 8).unwrap();
        assert_eq!(given.width, Dimension { value: 50.0, inferred: false });
        assert_eq!(given.piece_length, one.piece_length);
    }

    #[test]
    fn without_a_period_the_piece_length_is_a_share_of_the_height() {
        // One ring: no repetition along x.
        let ring = samples::chain(60, 48, 60.0, 30.0, 0);
        assert_eq!(pattern_period(&ring, 8), None);
        let dimensions = Dimensions::resolve(&ring, None, None, 1.0, 8).unwrap();
        let height = dimensions.pattern_height.unwrap() as f64;
        assert_eq!(dimensions.piece_length.value, (FALLBACK_FRACTION * height).round());
    }

    #[test]
    fn no_pattern_is_a_clear_error() {
        let clear = RgbaImage::from_fn(40, 20, |_, _| [0; 4]);
        let error = Dimensions::resolve(&clear, None, None, 1.0, 8).unwrap_err();
        assert!(error.to_string().contains("no pattern found"), "{error}");
        let faint = RgbaImage::from_fn(40, 20, |_, _| [9, 9, 9, 5]);
        assert!(Dimensions::resolve(&faint, None, Some(10.0), 1.0, 8).is_err());
        let error = Dimensions::resolve(&faint, None, None, 0.0, 8).unwrap_err();
        assert_eq!(error.name, "scale");
        assert!(Dimensions::resolve(&clear, Some(10.0), Some(10.0), 1.0, 8).is_ok());
    }

    /// Three corpus exemplars (`data/real/curve/cases.json`): the inferred width within 10 % and the
    /// piece length within 25 % of the hand-picked ones.
    #[test]
    fn real_exemplars_infer_values_near_the_hand_picked_ones() {
        let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/curve");
        let cases = [("chain_round.png", 108.0, 25.0), ("chain_small.png", 82.0, 24.0), ("beads.png", 44.0, 20.0)];
        for (file, width, piece_length) in cases {
            let exemplar = motif_io::read_image(&folder.join(file)).unwrap();
            let d = Dimensions::resolve(&exemplar, None, None, 1.0, 8).unwrap();
            assert!((d.width.value / width - 1.0).abs() <= 0.10, "{file}: width {}", d.width.value);
            assert!((d.piece_length.value / piece_length - 1.0).abs() <= 0.25, "{file}: {}", d.piece_length.value);
        }
    }
}
