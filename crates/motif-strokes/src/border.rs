//! Elements cut by the reference's frame.
//!
//! A reference cropped out of a larger drawing holds pieces of the elements its frame cut through:
//! half a star, the stub of a hatch. Copied as whole elements they would scatter small fragments
//! over the output. An element is at the border when its ink comes within a hair of the bounding
//! box of the whole reference (the outermost elements of an uncropped drawing do too: they define
//! that box). Border elements are not copied as long as enough elements lie away from the border
//! (a quarter of them, and at least three): a cut piece can resemble a whole element by its box
//! (a star missing a spoke still has a star's box), so resemblance cannot tell them apart, and the
//! whole elements at the border have their like inside. They stay in the analysis as neighbours,
//! so the neighbourhoods around them keep their geometry, but are never copied, never taken as
//! the best match, and never lend their parameters to an exchange.

use motif_core::Point;

use crate::analysis::Analysis;
use crate::stroke::Stroke;

/// The share of the frame's larger side within which an element touches it.
const TOUCH_TOLERANCE: f64 = 0.005;

/// Border elements are copied when fewer than this share of the elements (or 3) lie inside.
const INTERIOR_SHARE: f64 = 0.25;

/// Border and fragment flags of the analysed elements.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct BorderFlags {
    /// Elements whose ink touches the reference's bounding box.
    pub border: Vec<bool>,
    /// Border elements left out of copying because enough elements lie inside.
    pub fragment: Vec<bool>,
}

/// Flags the elements of `analysis` (clustered from `strokes`) that touch the reference's frame
/// and those that are not copied.
pub(crate) fn flag_border(analysis: &Analysis, strokes: &[Stroke]) -> BorderFlags {
    let count = analysis.elements.len();
    // In the pattern frame, where a 1D pattern runs along x: its frame cuts it at its two ends
    // only (the tallest elements of a row touch its top and bottom without being cut).
    let to_pattern = analysis.to_pattern();
    let mut low = Point::new(f64::INFINITY, f64::INFINITY);
    let mut high = Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
    for stroke in strokes {
        for &p in stroke.polyline.points() {
            let p = to_pattern * p;
            low = Point::new(low.x.min(p.x), low.y.min(p.y));
            high = Point::new(high.x.max(p.x), high.y.max(p.y));
        }
    }
    let tolerance = TOUCH_TOLERANCE * (high.x - low.x).max(high.y - low.y);
    let along_path = analysis.along_path;
    let border: Vec<bool> = analysis
        .elements
        .iter()
        .map(|element| {
            element.strokes.iter().flat_map(|&s| strokes[s].polyline.points()).any(|&p| {
                let p = to_pattern * p;
                p.x - low.x <= tolerance
                    || high.x - p.x <= tolerance
                    || (!along_path && (p.y - low.y <= tolerance || high.y - p.y <= tolerance))
            })
        })
        .collect();
    let interior = border.iter().filter(|&&b| !b).count();
    let enough = interior >= 3 && interior as f64 >= INTERIOR_SHARE * count as f64;
    let fragment = border.iter().map(|&b| b && enough).collect();
    BorderFlags { border, fragment }
}
