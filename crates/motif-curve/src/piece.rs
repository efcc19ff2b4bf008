//! A piece seen from the exemplar (§1.3) and its valid positions (§1.3, §3.1).
//!
//! Each piece is copied rigidly: its left edge is kept vertical in the exemplar, so the canvas →
//! exemplar map is a rotation `M` (taking the left edge `l_i` to the exemplar's downward vertical)
//! and the scale `s`. In exemplar coordinates relative to the top-left corner the piece is
//! `(0, s·M l_i = (0, h), s·M d_i, s·M t_i)` with `h = s·b`, and its right edge `R_i` runs from
//! `s·M t_i` to `s·M d_i`. The top-left corner of a piece placed at integer position `u` sits at
//! `(u.x + 0.5, u.y)`, so the left edge runs through the centres of column `u.x` and the left
//! edge samples are plain pixels; every other lookup has a fractional offset that is the same
//! for all positions, which lets us precompute pixel offsets and bilinear weights once per piece.

use motif_core::{Point, Vec2};
use motif_core::{math, vector};

use crate::exemplar::{Exemplar, Run, runs_from_offsets};
use crate::ribbon::PieceQuad;

/// An integer exemplar position `u` of a piece's top-left corner (before the half-pixel shift).
pub(crate) type Position = [i32; 2];

/// One bilinear tap of a right-edge sample: the top-left pixel offset and the four weights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Tap {
    pub dx: i32,
    pub dy: i32,
    pub weights: [f32; 4],
}

/// A piece in exemplar space, with everything the validity test and the edge extraction need.
#[derive(Debug, Clone)]
pub(crate) struct PieceFrame {
    /// `T(x_i)`, the canvas position of the top-left corner.
    pub origin: Point,
    /// Rotation canvas → exemplar (cosine, sine).
    pub rotation: (f64, f64),
    /// Scale `s` (exemplar pixels per canvas unit).
    pub scale: f64,
    /// Left edge length in the exemplar, `h = s·b`.
    pub height: f64,
    /// `s·M t_i`: the top-right corner relative to the top-left corner.
    pub top_right: Vec2,
    /// `s·M d_i`: the bottom-right corner relative to the top-left corner.
    pub bottom_right: Vec2,
    /// Unit direction of the right edge, top to bottom.
    pub right_direction: Vec2,
    /// `C`, samples per edge.
    pub samples: usize,
    /// Bilinear taps of the right edge samples, one per `k < C`.
    pub right_taps: Vec<Tap>,
    /// Pixel offsets read when sampling the top and bottom edges.
    pub edge_runs: Vec<Run>,
    /// Pixel offsets whose centres lie inside the piece.
    pub interior_runs: Vec<Run>,
    /// Local x extent of the piece.
    pub x_range: (f64, f64),
    /// Local y extent of the piece.
    pub y_range: (f64, f64),
}

impl PieceFrame {
    /// The frame of `quad` at scale `scale`, with `samples` = C samples per edge.
    pub(crate) fn new(quad: &PieceQuad, scale: f64, samples: usize) -> Self {
        let [top_left, bottom_left, bottom_right, top_right] = quad.corners;
        let left = bottom_left - top_left;
        // Rotate so that the left edge points down the exemplar (+y).
        let angle = std::f64::consts::FRAC_PI_2 - math::atan2(left.y, left.x);
        let rotation = (math::cos(angle), math::sin(angle));
        let mut frame = Self {
            origin: top_left,
            rotation,
            scale,
            height: scale * vector::length(left),
            top_right: Vec2::ZERO,
            bottom_right: Vec2::ZERO,
            right_direction: Vec2::new(0.0, 1.0),
            samples,
            right_taps: Vec::new(),
            edge_runs: Vec::new(),
            interior_runs: Vec::new(),
            x_range: (0.0, 0.0),
            y_range: (0.0, 0.0),
        };
        frame.top_right = frame.to_local(top_right);
        frame.bottom_right = frame.to_local(bottom_right);
        let right = frame.bottom_right - frame.top_right;
        frame.right_direction =
            if vector::length(right) > 1e-12 { vector::normalized(right) } else { Vec2::new(0.0, 1.0) };
        frame.right_taps = (0..samples)
            .map(|k| {
                let p = frame.top_right + frame.right_direction * (k as f64 + 0.5);
                let (fx, fy) = (p.x, p.y - 0.5);
                let (ix, iy) = (fx.floor(), fy.floor());
                let (tx, ty) = ((fx - ix) as f32, (fy - iy) as f32);
                Tap {
                    dx: ix as i32,
                    dy: iy as i32,
                    weights: [(1.0 - tx) * (1.0 - ty), tx * (1.0 - ty), (1.0 - tx) * ty, tx * ty],
                }
            })
            .collect();
        let corners = frame.local_corners();
        frame.x_range = corners.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| (a.min(c.x), b.max(c.x)));
        frame.y_range = corners.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| (a.min(c.y), b.max(c.y)));
        frame.edge_runs = frame.compute_edge_runs();
        frame.interior_runs = frame.compute_interior_runs();
        frame
    }

    /// The piece corners relative to the top-left corner: top-left, bottom-left, bottom-right, top-right.
    pub(crate) fn local_corners(&self) -> [Vec2; 4] {
        [Vec2::ZERO, Vec2::new(0.0, self.height), self.bottom_right, self.top_right]
    }

    /// Canvas point → exemplar offset from the top-left corner: `s·M (p − T(x_i))`.
    pub(crate) fn to_local(&self, p: Point) -> Vec2 {
        let v = p - self.origin;
        let (c, s) = self.rotation;
        Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y) * self.scale
    }

    /// Exemplar offset from the top-left corner → canvas point.
    pub(crate) fn to_canvas(&self, local: Vec2) -> Point {
        let v = local / self.scale;
        let (c, s) = self.rotation;
        self.origin + Vec2::new(c * v.x + s * v.y, -s * v.x + c * v.y)
    }

    /// The rotation canvas → exemplar, in radians.
    pub(crate) fn angle(&self) -> f64 {
        math::atan2(self.rotation.1, self.rotation.0)
    }

    /// Continuous exemplar coordinates of local point `local` for a piece at `u`.
    pub(crate) fn exemplar_point(u: Position, local: Vec2) -> (f64, f64) {
        (f64::from(u[0]) + 0.5 + local.x, f64::from(u[1]) + local.y)
    }

    fn compute_edge_runs(&self) -> Vec<Run> {
        let mut offsets = Vec::new();
        for (start, end) in [(Vec2::ZERO, self.top_right), (Vec2::new(0.0, self.height), self.bottom_right)] {
            let steps = (vector::length(end - start) * 2.0).ceil().max(1.0) as usize;
            for step in 0..=steps {
                let p = start.lerp(end, step as f64 / steps as f64);
                let (ix, iy) = (p.x.floor() as i32, (p.y - 0.5).floor() as i32);
                offsets.extend([(ix, iy), (ix + 1, iy), (ix, iy + 1), (ix + 1, iy + 1)]);
            }
        }
        runs_from_offsets(offsets)
    }

    fn compute_interior_runs(&self) -> Vec<Run> {
        let corners = self.local_corners();
        let mut runs = Vec::new();
        let (y0, y1) = (self.y_range.0.floor() as i32 - 1, self.y_range.1.ceil() as i32 + 1);
        let mut crossings = Vec::with_capacity(4);
        for dy in y0..=y1 {
            let y = f64::from(dy) + 0.5;
            crossings.clear();
            for i in 0..4 {
                let (a, b) = (corners[i], corners[(i + 1) % 4]);
                if (a.y > y) != (b.y > y) {
                    crossings.push(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
                }
            }
            crossings.sort_by(f64::total_cmp);
            for pair in crossings.chunks_exact(2) {
                let (x0, x1) = (pair[0].ceil() as i32, pair[1].ceil() as i32);
                if x1 > x0 {
                    runs.push(Run { dy, x0, x1 });
                }
            }
        }
        runs
    }

    /// True when `p` (local exemplar coordinates) lies inside the piece (even-odd rule).
    pub(crate) fn contains_local(&self, p: Vec2) -> bool {
        let corners = self.local_corners();
        let mut inside = false;
        for i in 0..4 {
            let (a, b) = (corners[i], corners[(i + 1) % 4]);
            if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
                inside = !inside;
            }
        }
        inside
    }

    /// A position where the piece covers only the transparent margin above the exemplar: the one
    /// "empty" placement used when avoidance leaves a piece no valid position at all.
    pub(crate) fn empty_position(&self) -> Position {
        [0, -(self.y_range.1.ceil() as i32 + 3)]
    }

    /// Margin (pixels) the exemplar storage needs around the exemplar for this piece's lookups,
    /// including the empty position.
    pub(crate) fn required_margin(&self) -> i32 {
        let extent = self.x_range.0.abs().max(self.x_range.1.abs()).max(self.y_range.0.abs()).max(self.y_range.1.abs());
        2 * (extent.ceil() as i32 + self.samples as i32) + 8
    }

    /// The slicing part of the validity test (§1.3) at `u`: the piece stays inside the pattern's
    /// horizontal extent (the exemplar is cut at its left and right borders, and transparent
    /// columns beside the pattern are margin, not pattern: a piece reaching into them draws a gap
    /// that its seams, transparent against transparent, do not pay for) and its top and bottom
    /// edges stay in transparent pixels.
    fn is_cut(&self, exemplar: &Exemplar, u: Position) -> bool {
        let left = f64::from(u[0]) + 0.5;
        let (low, high) = (left + self.x_range.0, left + self.x_range.1);
        let inside = |&(first, last): &(i32, i32)| low >= f64::from(first) - 1e-9 && high <= f64::from(last + 1) + 1e-9;
        if !exemplar.pattern_columns.iter().any(inside) {
            return false;
        }
        self.edge_runs.iter().all(|run| exemplar.run_is_clear(run, u[0], u[1]))
    }

    /// The pixels under the left and right edges, one per edge sample (offsets from the top-left
    /// corner). A window whose sides are clear of the pattern holds whole motifs: none is cut at
    /// its ends, which a spaced piece ([`Fit::Space`](crate::Fit::Space)) needs, since no
    /// neighbour continues the motif across its gap.
    pub(crate) fn side_runs(&self) -> Vec<Run> {
        let mut offsets = Vec::with_capacity(2 * self.samples);
        for k in 0..self.samples {
            let right = self.top_right + self.right_direction * (k as f64 + 0.5);
            offsets.push((0, k as i32));
            offsets.push((right.x.floor() as i32, (right.y - 0.5).floor() as i32));
        }
        crate::exemplar::runs_from_offsets(offsets)
    }

    /// Coverage of the piece at `u`: how many exemplar pixels inside it belong to the pattern
    /// (alpha > `cut_alpha`). One prefix-count difference per interior row run, so the cost is
    /// the piece's height in rows, not its area.
    pub(crate) fn coverage(&self, exemplar: &Exemplar, u: Position) -> u32 {
        self.interior_runs.iter().map(|run| exemplar.run_occupied(run, u[0], u[1])).sum()
    }

    /// The paper's validity test (§1.3 and §3.1) at `u`: the piece is cut cleanly
    /// (see [`valid_positions`](Self::valid_positions)), it is not empty, and none of its visible
    /// pixels falls in a forbidden canvas area (`forbidden`: offsets whose exemplar pixels must
    /// have alpha 0). The coverage rule of `valid_positions` comes on top of this. A plain
    /// reference for the tests.
    #[cfg(test)]
    pub(crate) fn is_valid(&self, exemplar: &Exemplar, u: Position, forbidden: &[Run]) -> bool {
        self.is_cut(exemplar, u)
            && self.coverage(exemplar, u) > 0
            && forbidden.iter().all(|run| exemplar.run_is_invisible(run, u[0], u[1]))
    }

    /// The typical coverage of this piece over the exemplar: the (lower) median coverage over the
    /// cleanly cut, non-empty positions `cut` whose left edge spans the pattern's whole height
    /// ("full-pattern windows"); over all of `cut` when no position spans it (a pattern taller
    /// than the piece in places). 0 when `cut` is empty.
    fn typical_coverage(&self, exemplar: &Exemplar, cut: &[(Position, u32)]) -> u32 {
        let mut full: Vec<u32> = match exemplar.pattern_rows {
            Some((top, bottom)) => cut
                .iter()
                .filter(|(u, _)| u[1] <= top && f64::from(bottom + 1) <= f64::from(u[1]) + self.height + 1e-9)
                .map(|&(_, coverage)| coverage)
                .collect(),
            None => Vec::new(),
        };
        if full.is_empty() {
            full = cut.iter().map(|&(_, coverage)| coverage).collect();
        }
        if full.is_empty() {
            return 0;
        }
        let middle = (full.len() - 1) / 2;
        *full.select_nth_unstable(middle).1
    }

    /// Every position `u ∈ [0, W) × [−C, H)` (the paper's `U = W × (H + C)`) passing
    /// [`is_valid`](Self::is_valid) and carrying a representative share of the pattern: its
    /// [`coverage`](Self::coverage) is at least `min_coverage` × the piece's typical coverage
    /// (the median over full-pattern windows, computed without forbidden areas). This keeps the
    /// optimum from copying one thin sliver of the pattern along the whole curve, which has a
    /// near-zero seam cost; `min_coverage` 0 is the paper's rule. Row-major order.
    pub(crate) fn valid_positions(&self, exemplar: &Exemplar, forbidden: &[Run], min_coverage: f64) -> Vec<Position> {
        let c = self.samples as i32;
        let mut cut: Vec<(Position, u32)> = Vec::new();
        for y in -c..exemplar.height {
            for x in 0..exemplar.width {
                if self.is_cut(exemplar, [x, y]) {
                    let coverage = self.coverage(exemplar, [x, y]);
                    if coverage > 0 {
                        cut.push(([x, y], coverage));
                    }
                }
            }
        }
        let threshold =
            if min_coverage > 0.0 { min_coverage * f64::from(self.typical_coverage(exemplar, &cut)) } else { 0.0 };
        cut.into_iter()
            .filter(|&(u, coverage)| {
                f64::from(coverage) >= threshold
                    && forbidden.iter().all(|run| exemplar.run_is_invisible(run, u[0], u[1]))
            })
            .map(|(u, _)| u)
            .collect()
    }
}

/// `U = W × (H + C)`, the number of candidate positions of a piece (§1.4).
pub(crate) fn candidate_count(width: usize, height: usize, samples: usize) -> usize {
    width * (height + samples)
}

#[cfg(test)]
mod tests {
    use super::*;
    use motif_core::RgbaImage;

    fn straight_quad(width: f64, length: f64) -> PieceQuad {
        PieceQuad {
            start: 0.0,
            end: length,
            corners: [
                Point::new(10.0, 10.0),
                Point::new(10.0, 10.0 + width),
                Point::new(10.0 + length, 10.0 + width),
                Point::new(10.0 + length, 10.0),
            ],
        }
    }

    #[test]
    fn straight_piece_maps_to_an_upright_rectangle() {
        let frame = PieceFrame::new(&straight_quad(8.0, 5.0), 2.0, 16);
        assert!((frame.height - 16.0).abs() < 1e-12);
        assert!(vector::length(frame.top_right - Vec2::new(10.0, 0.0)) < 1e-9);
        assert!(vector::length(frame.bottom_right - Vec2::new(10.0, 16.0)) < 1e-9);
        assert!(frame.angle().abs() < 1e-12);
        let back = frame.to_canvas(frame.to_local(Point::new(12.0, 13.0)));
        assert!(vector::distance(back, Point::new(12.0, 13.0)) < 1e-12);
        // Right samples sit exactly on pixel centres of column 9 (offset 10 − 0.5 → dx 10 from the anchor).
        assert_eq!(frame.right_taps[0].dx, 10);
        assert_eq!(frame.right_taps[0].dy, 0);
        assert_eq!(frame.right_taps[0].weights, [1.0, 0.0, 0.0, 0.0]);
        let pixels: i32 = frame.interior_runs.iter().map(|run| run.x1 - run.x0).sum();
        assert_eq!(pixels, 10 * 16);
    }

    #[test]
    fn tilted_piece_rotates_the_left_edge_to_vertical() {
        let quad = PieceQuad {
            start: 0.0,
            end: 1.0,
            corners: [Point::new(0.0, 0.0), Point::new(6.0, 8.0), Point::new(14.0, 2.0), Point::new(8.0, -6.0)],
        };
        let frame = PieceFrame::new(&quad, 1.0, 10);
        let bottom_left = frame.to_local(Point::new(6.0, 8.0));
        assert!(vector::length(bottom_left - Vec2::new(0.0, 10.0)) < 1e-9, "{bottom_left:?}");
        assert!(vector::length(frame.top_right - Vec2::new(10.0, 0.0)) < 1e-9, "{:?}", frame.top_right);
    }

    #[test]
    fn validity_requires_a_complete_slice() {
        // A horizontal bar in rows 4..8 of a 20×12 exemplar.
        let image = RgbaImage::from_fn(20, 12, |_, y| if (4..8).contains(&y) { [200, 10, 10, 255] } else { [0; 4] });
        let frame = PieceFrame::new(&straight_quad(8.0, 3.0), 1.0, 8);
        let exemplar = Exemplar::new(&image, frame.required_margin() as usize, 0);
        // Top edge at y = u.y must be clear with its 2×2 footprint: rows u.y − 1 .. and bottom rows.
        assert!(frame.is_valid(&exemplar, [2, 2], &[]));
        assert!(!frame.is_valid(&exemplar, [2, 4], &[]), "top edge inside the bar");
        assert!(!frame.is_valid(&exemplar, [2, -4], &[]), "bottom edge inside the bar");
        assert!(!frame.is_valid(&exemplar, [2, -8], &[]), "empty piece");
        assert!(!frame.is_valid(&exemplar, [18, 2], &[]), "crosses the right border");
        let forbidden = [Run { dy: 3, x0: 1, x1: 2 }];
        assert!(!frame.is_valid(&exemplar, [2, 2], &forbidden));
        let positions = frame.valid_positions(&exemplar, &[], 0.0);
        assert!(positions.iter().all(|p| p[1] == 1 || p[1] == 2 || p[1] == 3), "{positions:?}");
        assert!(!positions.is_empty());
        let empty = frame.empty_position();
        assert!(frame.interior_runs.iter().all(|run| exemplar.run_is_invisible(run, empty[0], empty[1])));
    }

    #[test]
    fn pieces_stay_out_of_the_transparent_side_margins() {
        // A bar in columns 6..24 of a 30-wide exemplar: the columns beside it are margin.
        let image = RgbaImage::from_fn(30, 12, |x, y| {
            if (4..8).contains(&y) && (6..24).contains(&x) { [9, 9, 9, 255] } else { [0; 4] }
        });
        let frame = PieceFrame::new(&straight_quad(8.0, 5.0), 1.0, 8);
        let exemplar = Exemplar::new(&image, frame.required_margin() as usize, 0);
        assert_eq!(exemplar.pattern_columns, vec![(6, 23)]);
        let positions = frame.valid_positions(&exemplar, &[], 0.0);
        assert!(!positions.is_empty());
        // The piece spans [u.x + 0.5, u.x + 5.5]: inside [6, 24].
        assert!(positions.iter().all(|p| p[0] >= 6 && p[0] + 5 <= 23), "{positions:?}");
        assert!(positions.iter().any(|p| p[0] == 6) && positions.iter().any(|p| p[0] == 18));
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]
        #[test]
        fn prefix_sum_coverage_equals_a_naive_count(
            width in 3_usize..14,
            height in 3_usize..12,
            cells in proptest::collection::vec(0_u8..=255, 1..64),
            corners in proptest::collection::vec(-6.0_f64..6.0, 4),
            length in 1.0_f64..7.0,
            ribbon in 2.0_f64..9.0,
            scale in 0.5_f64..2.0,
            cut_alpha in 0_u8..200,
        ) {
            let image = RgbaImage::from_fn(width, height, |x, y| {
                let v = cells[(y * width + x) % cells.len()];
                [v, v / 2, 9, if v % 3 == 0 { 0 } else { v }]
            });
            // A straight or tilted (trapezoid-like) quad: left edge along −y rotated, jittered right corners.
            let quad = PieceQuad {
                start: 0.0,
                end: length,
                corners: [
                    Point::new(20.0, 20.0),
                    Point::new(20.0 + corners[0] * 0.3, 20.0 + ribbon),
                    Point::new(20.0 + length + corners[1], 20.0 + ribbon + corners[2] * 0.3),
                    Point::new(20.0 + length + corners[3] * 0.5, 20.0),
                ],
            };
            let samples = (ribbon * scale).ceil() as usize;
            let frame = PieceFrame::new(&quad, scale, samples);
            let exemplar = Exemplar::new(&image, frame.required_margin() as usize, cut_alpha);
            for y in -(samples as i32)..height as i32 {
                for x in -2..width as i32 + 2 {
                    let mut naive = 0;
                    for py in 0..height {
                        for px in 0..width {
                            let local = Vec2::new(f64::from(px as i32 - x), f64::from(py as i32 - y) + 0.5);
                            if image.get(px, py)[3] > cut_alpha && frame.contains_local(local) {
                                naive += 1;
                            }
                        }
                    }
                    proptest::prop_assert_eq!(frame.coverage(&exemplar, [x, y]), naive, "at ({}, {})", x, y);
                }
            }
        }
    }

    #[test]
    fn the_coverage_rule_keeps_the_typical_windows_only() {
        // A 2-row bar at x < 10 next to a 6-row band at x ≥ 10, 40 wide: most full-pattern windows
        // lie in the band, so half the typical coverage rules the bar out.
        let image = RgbaImage::from_fn(40, 14, |x, y| {
            let rows = if x < 10 { 6..8 } else { 4..10 };
            if rows.contains(&y) { [50, 60, 70, 255] } else { [0; 4] }
        });
        let frame = PieceFrame::new(&straight_quad(12.0, 3.0), 1.0, 12);
        let exemplar = Exemplar::new(&image, frame.required_margin() as usize, 0);
        assert_eq!(exemplar.pattern_rows, Some((4, 9)));
        let paper = frame.valid_positions(&exemplar, &[], 0.0);
        let kept = frame.valid_positions(&exemplar, &[], 0.5);
        assert!(paper.iter().any(|p| p[0] + 3 <= 10), "the paper's rule keeps the bar");
        assert!(!kept.is_empty());
        assert!(kept.iter().all(|&p| frame.coverage(&exemplar, p) >= 9), "{kept:?}");
        assert!(kept.iter().all(|p| paper.contains(p)));
        let all = frame.valid_positions(&exemplar, &[], 1.0);
        assert!(all.iter().all(|&p| frame.coverage(&exemplar, p) == 18));
    }
}
