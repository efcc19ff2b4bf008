//! Elements cut by the reference's frame.
//!
//! A reference cropped out of a larger drawing holds pieces of the elements its frame cut through:
//! half a star, the stub of a hatch. Copied as whole elements they would scatter small fragments
//! over the output. An element is at the border when its ink comes within a hair of the bounding
//! box of the whole reference (every pattern has some: the outermost elements define that box);
//! a border element is a fragment when no element away from the border resembles it in size (the
//! shape test, or the length ratio and thickness tests of §3.1). Fragments stay in the analysis as
//! neighbours, so the neighbourhoods around them keep their geometry, but are never copied, never
//! taken as the best match, and never lend their parameters to an exchange.

use motif_core::Point;

use crate::analysis::Analysis;
use crate::attributes::Appearance;
use crate::matching::{Limits, Measures};
use crate::stroke::Stroke;

/// The border elements' share of the frame's larger side within which an element touches it.
const TOUCH_TOLERANCE: f64 = 0.005;

/// Border and fragment flags of the analysed elements.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct BorderFlags {
    /// Elements whose ink touches the reference's bounding box.
    pub border: Vec<bool>,
    /// Border elements unlike every element away from the border: pieces cut by the frame.
    pub fragment: Vec<bool>,
}

/// Flags the elements of `analysis` (clustered from `strokes`) that touch the reference's frame
/// and those that are fragments.
pub fn flag_border(analysis: &Analysis, strokes: &[Stroke], limits: &Limits) -> BorderFlags {
    let count = analysis.elements.len();
    let mut low = Point::new(f64::INFINITY, f64::INFINITY);
    let mut high = Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
    for stroke in strokes {
        for p in stroke.polyline.points() {
            low = Point::new(low.x.min(p.x), low.y.min(p.y));
            high = Point::new(high.x.max(p.x), high.y.max(p.y));
        }
    }
    let tolerance = TOUCH_TOLERANCE * (high.x - low.x).max(high.y - low.y);
    let border: Vec<bool> = analysis
        .elements
        .iter()
        .map(|element| {
            element.strokes.iter().flat_map(|&s| strokes[s].polyline.points()).any(|p| {
                p.x - low.x <= tolerance
                    || high.x - p.x <= tolerance
                    || p.y - low.y <= tolerance
                    || high.y - p.y <= tolerance
            })
        })
        .collect();
    let frames: Vec<_> = (0..count).map(|i| analysis.pattern_frame(i)).collect();
    let interior: Vec<usize> = (0..count).filter(|&i| !border[i]).collect();
    let fragment = (0..count)
        .map(|i| {
            border[i]
                && !interior.is_empty()
                && interior.iter().all(|&j| {
                    let plain = Appearance::default();
                    let [shape, _, overlap, superimposition, _, _] =
                        Measures::of_pair(&frames[j], &frames[i], &plain, &plain).normalized(limits);
                    shape >= 1.0 && overlap.max(superimposition) >= 1.0
                })
        })
        .collect();
    BorderFlags { border, fragment }
}
