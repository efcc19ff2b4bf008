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

/// A piece drawn whole from a tile's columns rather than chosen by the dynamic program's cost
/// alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum TileKind {
    /// The first piece of an open curve.
    Start,
    /// The last piece of an open curve.
    End,
    /// A piece centred on a corner.
    Corner,
}

impl TileKind {
    /// Its place in the per-kind arrays: [`Params::tile_exemplars`](crate::Params::tile_exemplars)
    /// and the layout's tile columns (start, end, corner).
    pub(crate) fn index(self) -> usize {
        match self {
            Self::Start => 0,
            Self::End => 1,
            Self::Corner => 2,
        }
    }

    /// The option that sets the tile.
    pub(crate) fn option_name(self) -> &'static str {
        match self {
            Self::Start => "start-tile",
            Self::End => "end-tile",
            Self::Corner => "corner-tile",
        }
    }
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
    /// Which pieces are tiles (drawn whole, unstretched).
    pub tiles: Vec<Option<TileKind>>,
    /// Each piece's stretch and the length of a whole piece of its stretch of the curve (the
    /// stretches between corner tiles are fitted apart; a tile has 1 and its own length).
    pub along: Vec<(f64, f64)>,
}

impl Slices {
    /// Whether piece `i` of these slices is a tile.
    pub(crate) fn is_tile(&self, i: usize) -> bool {
        self.tiles[i].is_some()
    }
}

/// The pieces of a ribbon `length` long: a start tile `ends[0]` long, the corner tiles over
/// `corners` (stretches `[start, end)`, ascending, after the start tile and before the end tile),
/// an end tile `ends[1]` long (a tile 0 long is none), and between them pieces `delta` long
/// fitted as `fit` asks. The tiles and one piece fit in `length` (checked by `validate`).
pub(crate) fn slices(
    length: f64,
    delta: f64,
    fit: Fit,
    closed: bool,
    ends: [f64; 2],
    corners: &[(f64, f64)],
) -> Slices {
    let mut pieces = Slices {
        bounds: Vec::new(),
        piece_length: delta,
        stretch: 1.0,
        gap: 0.0,
        tiles: Vec::new(),
        along: Vec::new(),
    };
    if ends[0] > 0.0 {
        pieces.push_tile((0.0, ends[0]), TileKind::Start);
    }
    let mut cursor = ends[0];
    // Between tiles, pieces as along an open stretch; a curve with no tile keeps its own ends.
    let stretch_closed = closed && ends == [0.0; 2] && corners.is_empty();
    for &(start, end) in corners {
        pieces.push_fitted(cursor, start - cursor, delta, fit, stretch_closed);
        pieces.push_tile((start, end), TileKind::Corner);
        cursor = end;
    }
    let middle = if corners.is_empty() { length - ends[0] - ends[1] } else { length - cursor - ends[1] };
    pieces.push_fitted(cursor, middle, delta, fit, stretch_closed);
    if ends[1] > 0.0 {
        pieces.push_tile((length - ends[1], length), TileKind::End);
    }
    pieces
}

impl Slices {
    fn push_tile(&mut self, bounds: (f64, f64), kind: TileKind) {
        self.bounds.push(bounds);
        self.tiles.push(Some(kind));
        self.along.push((1.0, bounds.1 - bounds.0));
    }

    /// Fitted pieces over `length` from `offset`; the fit's figures are the last stretch's.
    fn push_fitted(&mut self, offset: f64, length: f64, delta: f64, fit: Fit, closed: bool) {
        if length <= 0.0 {
            return;
        }
        let part = fitted(length, delta.min(length), fit, closed);
        self.bounds.extend(part.bounds.iter().map(|bound| (bound.0 + offset, bound.1 + offset)));
        self.tiles.extend(part.bounds.iter().map(|_| None));
        self.along.extend(part.bounds.iter().map(|_| (part.stretch, part.piece_length)));
        (self.piece_length, self.stretch, self.gap) = (part.piece_length, part.stretch, part.gap);
    }
}

/// The pieces of a ribbon `length` long for pieces `delta` long, fitted as `fit` asks; `delta` is
/// at most `length`.
fn fitted(length: f64, delta: f64, fit: Fit, closed: bool) -> Slices {
    let (tiles, along) = (Vec::new(), Vec::new());
    match fit {
        Fit::None => {
            let positions = crate::ribbon::slice_positions(length, delta);
            let bounds = positions.windows(2).map(|pair| (pair[0], pair[1])).collect();
            Slices { bounds, piece_length: delta, stretch: 1.0, gap: 0.0, tiles, along }
        }
        Fit::Stretch => {
            let count = (length / delta).round().max(1.0);
            let piece_length = length / count;
            let bounds =
                (0..count as usize).map(|i| (i as f64 * piece_length, (i + 1) as f64 * piece_length)).collect();
            Slices { bounds, piece_length, stretch: delta / piece_length, gap: 0.0, tiles, along }
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
            Slices { bounds, piece_length: delta, stretch: 1.0, gap, tiles, along }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unfitted_slices_are_the_papers() {
        let slices = slices(10.0, 3.0, Fit::None, false, [0.0; 2], &[]);
        assert_eq!(slices.bounds, vec![(0.0, 3.0), (3.0, 6.0), (6.0, 9.0), (9.0, 10.0)]);
        assert_eq!((slices.stretch, slices.gap), (1.0, 0.0));
    }

    #[test]
    fn fitted_pieces_end_exactly_at_the_curves_end() {
        for (length, delta) in [(10.0, 3.0), (100.0, 24.0), (7.5, 7.5), (61.0, 20.0), (59.0, 20.0)] {
            for closed in [false, true] {
                let stretched = slices(length, delta, Fit::Stretch, closed, [0.0; 2], &[]);
                let last = stretched.bounds.last().unwrap().1;
                assert!((last - length).abs() < 1e-9, "{length} {delta}");
                let widths: Vec<f64> = stretched.bounds.iter().map(|(a, b)| b - a).collect();
                assert!(widths.iter().all(|w| (w - stretched.piece_length).abs() < 1e-9), "{widths:?}");
                // The nearest whole number of pieces.
                assert!((length / delta - stretched.bounds.len() as f64).abs() <= 0.5 + 1e-9);
                assert!((stretched.piece_length * stretched.stretch - delta).abs() < 1e-9);

                let spaced = slices(length, delta, Fit::Space, closed, [0.0; 2], &[]);
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
            let slices = slices(100.0, 20.0, fit, false, [15.0, 12.0], &[]);
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
        let untiled = slices(100.0, 20.0, Fit::None, false, [0.0, 12.0], &[]);
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
