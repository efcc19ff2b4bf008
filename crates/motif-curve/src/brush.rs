//! Pattern-brush options (not in the paper; what users of the pattern brushes of Illustrator and
//! Inkscape expect): the exemplar mirrored along or across the curve, colourized as tints of one
//! colour, and whole pieces fitted to the curve's length by stretching them or spacing them out.

use std::borrow::Cow;

use motif_core::RgbaImage;
use serde::{Deserialize, Serialize};

/// How the exemplar is mirrored before synthesis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Flip {
    /// As drawn.
    #[default]
    None,
    /// Mirrored along the curve: the pattern runs the other way.
    Along,
    /// Mirrored across the curve: the pattern's top side faces the other side of the curve.
    Across,
    /// Both (a half turn).
    Both,
}

/// How the pieces meet the curve's length.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Fit {
    /// Pieces of the piece length; an open curve's last piece is cut where the curve ends (the
    /// paper, §1.3).
    #[default]
    None,
    /// A whole number of pieces, each stretched or squeezed along the curve (the nearest number
    /// to the curve's length over the piece length), so the last one ends at the curve's end.
    Stretch,
    /// As many whole pieces as fit, with equal gaps between them so the last one ends at the
    /// curve's end (on a closed curve, a gap after each piece).
    Space,
}

impl crate::Params {
    /// An exemplar as the synthesis draws it, flipped and tinted as these parameters ask
    /// (borrowed when they ask neither): what the output should be compared with.
    pub fn styled_exemplar<'a>(&self, exemplar: &'a RgbaImage) -> Cow<'a, RgbaImage> {
        styled(exemplar, self.flip, self.tint)
    }

    /// Whether these parameters flip or tint the exemplars.
    pub(crate) fn styles_exemplars(&self) -> bool {
        self.flip != Flip::None || self.tint.is_some()
    }
}

/// The exemplar as the synthesis draws it: mirrored and tinted as asked; borrowed when neither is.
fn styled(image: &RgbaImage, flip: Flip, tint: Option<[u8; 3]>) -> Cow<'_, RgbaImage> {
    if flip == Flip::None && tint.is_none() {
        return Cow::Borrowed(image);
    }
    let (width, height) = (image.width(), image.height());
    let (along, across) = (matches!(flip, Flip::Along | Flip::Both), matches!(flip, Flip::Across | Flip::Both));
    Cow::Owned(RgbaImage::from_fn(width, height, |x, y| {
        let source_x = if along { width - 1 - x } else { x };
        let source_y = if across { height - 1 - y } else { y };
        let pixel = image.get(source_x, source_y);
        tint.map_or(pixel, |colour| tinted(pixel, colour))
    }))
}

/// A pixel as a tint of `colour` (Illustrator's "Tints"): black becomes the colour, white stays
/// white, greys become lighter tints by their luma (Rec. 601); alpha is kept.
fn tinted([r, g, b, a]: [u8; 4], colour: [u8; 3]) -> [u8; 4] {
    let luma = (299 * u32::from(r) + 587 * u32::from(g) + 114 * u32::from(b) + 500) / 1000;
    let channel = |c: u8| {
        let c = u32::from(c);
        (c + ((255 - c) * luma + 127) / 255) as u8
    };
    [channel(colour[0]), channel(colour[1]), channel(colour[2]), a]
}

/// Where the pieces lie along the ribbon, as fitted.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Slices {
    /// Each piece's start and end (arc length, canvas pixels).
    pub bounds: Vec<(f64, f64)>,
    /// The canvas length of a whole piece (the piece length, or the stretched one).
    pub piece_length: f64,
    /// Exemplar pixels along a piece per exemplar pixel of an unfitted piece (1 unless stretched).
    pub stretch: f64,
    /// The gap after each piece (0 unless spaced).
    pub gap: f64,
    /// Whether the first piece is a start tile and the last an end tile (drawn whole, unstretched).
    pub tiles: [bool; 2],
}

impl Slices {
    /// Whether piece `i` of these slices is a start or end tile.
    pub fn is_tile(&self, i: usize) -> bool {
        (i == 0 && self.tiles[0]) || (i + 1 == self.bounds.len() && self.tiles[1])
    }
}

/// The pieces of a ribbon `length` long: a start tile `tiles[0]` long, pieces `delta` long fitted
/// as `fit` asks, an end tile `tiles[1]` long (a tile 0 long is none). The tiles and one piece fit
/// in `length` (checked by `validate`).
pub(crate) fn slices(length: f64, delta: f64, fit: Fit, closed: bool, tiles: [f64; 2]) -> Slices {
    let middle = length - tiles[0] - tiles[1];
    let mut slices = fitted(middle, delta.min(middle), fit, closed);
    for bound in &mut slices.bounds {
        *bound = (bound.0 + tiles[0], bound.1 + tiles[0]);
    }
    if tiles[0] > 0.0 {
        slices.bounds.insert(0, (0.0, tiles[0]));
    }
    if tiles[1] > 0.0 {
        slices.bounds.push((length - tiles[1], length));
    }
    slices.tiles = tiles.map(|tile| tile > 0.0);
    slices
}

/// The pieces of a ribbon `length` long for pieces `delta` long, fitted as `fit` asks; `delta` is
/// at most `length`.
fn fitted(length: f64, delta: f64, fit: Fit, closed: bool) -> Slices {
    let tiles = [false; 2];
    match fit {
        Fit::None => {
            let positions = crate::ribbon::slice_positions(length, delta);
            let bounds = positions.windows(2).map(|pair| (pair[0], pair[1])).collect();
            Slices { bounds, piece_length: delta, stretch: 1.0, gap: 0.0, tiles }
        }
        Fit::Stretch => {
            let count = (length / delta).round().max(1.0);
            let piece_length = length / count;
            let bounds =
                (0..count as usize).map(|i| (i as f64 * piece_length, (i + 1) as f64 * piece_length)).collect();
            Slices { bounds, piece_length, stretch: delta / piece_length, gap: 0.0, tiles }
        }
        Fit::Space => {
            let count = (length / delta).floor().max(1.0) as usize;
            let gaps = if closed { count } else { count - 1 };
            let gap = if gaps == 0 { 0.0 } else { (length - count as f64 * delta) / gaps as f64 };
            let bounds = (0..count)
                .map(|i| {
                    let start = i as f64 * (delta + gap);
                    (start, (start + delta).min(length))
                })
                .collect();
            Slices { bounds, piece_length: delta, stretch: 1.0, gap, tiles }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unfitted_slices_are_the_papers() {
        let slices = slices(10.0, 3.0, Fit::None, false, [0.0; 2]);
        assert_eq!(slices.bounds, vec![(0.0, 3.0), (3.0, 6.0), (6.0, 9.0), (9.0, 10.0)]);
        assert_eq!((slices.stretch, slices.gap), (1.0, 0.0));
    }

    #[test]
    fn fitted_pieces_end_exactly_at_the_curves_end() {
        for (length, delta) in [(10.0, 3.0), (100.0, 24.0), (7.5, 7.5), (61.0, 20.0), (59.0, 20.0)] {
            for closed in [false, true] {
                let stretched = slices(length, delta, Fit::Stretch, closed, [0.0; 2]);
                let last = stretched.bounds.last().unwrap().1;
                assert!((last - length).abs() < 1e-9, "{length} {delta}");
                let widths: Vec<f64> = stretched.bounds.iter().map(|(a, b)| b - a).collect();
                assert!(widths.iter().all(|w| (w - stretched.piece_length).abs() < 1e-9), "{widths:?}");
                // The nearest whole number of pieces.
                assert!((length / delta - stretched.bounds.len() as f64).abs() <= 0.5 + 1e-9);
                assert!((stretched.piece_length * stretched.stretch - delta).abs() < 1e-9);

                let spaced = slices(length, delta, Fit::Space, closed, [0.0; 2]);
                let count = spaced.bounds.len() as f64;
                assert_eq!(count, (length / delta).floor());
                assert!(spaced.bounds.iter().all(|(a, b)| ((b - a) - delta).abs() < 1e-9));
                let end = spaced.bounds.last().unwrap().1 + if closed { spaced.gap } else { 0.0 };
                assert!((end - length).abs() < 1e-9 || count == 1.0, "{length} {delta} {closed}: {spaced:?}");
                assert!(spaced.gap >= 0.0 && spaced.gap < delta * (1.0 + 1.0 / count));
            }
        }
    }

    #[test]
    fn end_tiles_take_the_ends_and_the_pieces_fit_between_them() {
        for fit in [Fit::None, Fit::Stretch, Fit::Space] {
            let slices = slices(100.0, 20.0, fit, false, [15.0, 12.0]);
            assert_eq!(slices.bounds[0], (0.0, 15.0));
            assert_eq!(*slices.bounds.last().unwrap(), (88.0, 100.0));
            assert!(slices.is_tile(0) && slices.is_tile(slices.bounds.len() - 1) && !slices.is_tile(1));
            // Contiguous but for the gaps of a spaced fit, and in order.
            for pair in slices.bounds.windows(2) {
                assert!(
                    pair[1].0 >= pair[0].1 - 1e-9 && pair[1].0 <= pair[0].1 + slices.gap + 1e-9,
                    "{fit:?} {pair:?}"
                );
            }
        }
        let untiled = slices(100.0, 20.0, Fit::None, false, [0.0, 12.0]);
        assert!(!untiled.is_tile(0) && untiled.is_tile(untiled.bounds.len() - 1));
    }

    #[test]
    fn tints_keep_black_as_the_colour_white_as_white_and_alpha() {
        let colour = [200, 30, 60];
        assert_eq!(tinted([0, 0, 0, 77], colour), [200, 30, 60, 77]);
        assert_eq!(tinted([255, 255, 255, 255], colour), [255, 255, 255, 255]);
        let grey = tinted([128, 128, 128, 255], colour);
        assert!(grey[1] > 30 && grey[1] < 255 && grey[0] >= 200, "{grey:?}");
    }

    #[test]
    fn flips_mirror_the_exemplar_and_compose_to_a_half_turn() {
        let image = RgbaImage::from_fn(5, 3, |x, y| [x as u8, y as u8, 0, 255]);
        let along = styled(&image, Flip::Along, None);
        let across = styled(&image, Flip::Across, None);
        let both = styled(&image, Flip::Both, None);
        assert_eq!(along.get(0, 1), [4, 1, 0, 255]);
        assert_eq!(across.get(0, 0), [0, 2, 0, 255]);
        assert_eq!(both.get(0, 0), [4, 2, 0, 255]);
        assert_eq!(styled(&along, Flip::Along, None).into_owned(), image);
        assert!(matches!(styled(&image, Flip::None, None), Cow::Borrowed(_)));
    }
}
