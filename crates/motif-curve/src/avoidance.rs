//! Region avoidance (§3.1): the canvas avoidance map, fold-over detection, and the per-piece
//! pixel offsets that a forbidden area turns into.
//!
//! The forbidden area is a set of canvas pixels: those the user's avoidance map marks, and those
//! where the ribbon overdraws itself (found by rasterizing every piece quad at the renderer's
//! sample points and flagging samples covered twice). For each piece, every render sample inside
//! a forbidden pixel and inside the piece is mapped into the exemplar; the pixels its bilinear
//! lookup reads become offsets that must be fully transparent for a position to be valid. The
//! renderer samples exactly these points, so a valid placement draws nothing in a forbidden pixel.

use motif_core::{Point, RgbaImage, Vec2};
use rayon::prelude::*;

use crate::exemplar::{Run, runs_from_offsets};
use crate::piece::PieceFrame;

/// Canvas pixels where the pattern may not appear.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ForbiddenMask {
    /// Canvas width in pixels.
    pub width: usize,
    /// Canvas height in pixels.
    pub height: usize,
    /// Row-major flags: 1 from the avoidance map, 2 from fold-over detection (bits may combine).
    pub flags: Vec<u8>,
}

/// Flag of pixels forbidden by the user's avoidance map.
pub(crate) const FROM_MAP: u8 = 1;
/// Flag of pixels forbidden because the ribbon folds over or overlaps itself.
pub(crate) const FROM_FOLDOVER: u8 = 2;

impl ForbiddenMask {
    /// Nothing forbidden.
    pub fn empty(width: usize, height: usize) -> Self {
        Self { width, height, flags: vec![0; width * height] }
    }

    /// True when pixel `(x, y)` is forbidden.
    pub fn is_forbidden(&self, x: usize, y: usize) -> bool {
        self.flags[y * self.width + x] != 0
    }

    /// Number of forbidden pixels.
    pub fn count(&self) -> usize {
        self.flags.iter().filter(|&&flag| flag != 0).count()
    }

    /// Marks the pixels of an avoidance map: a pixel forbids when its alpha-weighted grey level
    /// is at least one half (opaque white forbids; black or transparent allows).
    pub fn add_map(&mut self, map: &RgbaImage) {
        for (flag, pixel) in self.flags.iter_mut().zip(map.pixels()) {
            let grey = (u32::from(pixel[0]) * 2126 + u32::from(pixel[1]) * 7152 + u32::from(pixel[2]) * 722) / 10000;
            if grey * u32::from(pixel[3]) >= 128 * 255 {
                *flag |= FROM_MAP;
            }
        }
    }

    /// Marks fold-overs and overlaps: canvas pixels where some render sample is covered by two or
    /// more pieces.
    pub(crate) fn add_foldovers(&mut self, frames: &[PieceFrame], samples_per_axis: usize) {
        let n = samples_per_axis;
        let (w, h) = (self.width, self.height);
        let boxes: Vec<_> = frames.iter().map(|frame| canvas_box(frame, w, h)).collect();
        let rows: Vec<Vec<u8>> = (0..h)
            .into_par_iter()
            .map(|y| {
                let mut row = vec![0_u8; w];
                let mut counts = vec![0_u8; w * n * n];
                for (frame, &(x0, y0, x1, y1)) in frames.iter().zip(&boxes) {
                    if y < y0 || y >= y1 {
                        continue;
                    }
                    for x in x0..x1 {
                        for (k, p) in sample_points(x, y, n).enumerate() {
                            if frame.contains_local(frame.to_local(p)) {
                                let count = &mut counts[x * n * n + k];
                                *count = count.saturating_add(1);
                            }
                        }
                    }
                }
                for x in 0..w {
                    if counts[x * n * n..(x + 1) * n * n].iter().any(|&c| c >= 2) {
                        row[x] = FROM_FOLDOVER;
                    }
                }
                row
            })
            .collect();
        for (y, row) in rows.into_iter().enumerate() {
            for (x, flag) in row.into_iter().enumerate() {
                self.flags[y * w + x] |= flag;
            }
        }
    }
}

/// The `n × n` render sample points of canvas pixel `(x, y)`.
pub(crate) fn sample_points(x: usize, y: usize, n: usize) -> impl Iterator<Item = Point> {
    (0..n * n).map(move |k| {
        let (i, j) = (k % n, k / n);
        Point::new(x as f64 + (i as f64 + 0.5) / n as f64, y as f64 + (j as f64 + 0.5) / n as f64)
    })
}

/// The canvas pixel box `[x0, x1) × [y0, y1)` covering a piece, clipped to the canvas.
pub(crate) fn canvas_box(frame: &PieceFrame, width: usize, height: usize) -> (usize, usize, usize, usize) {
    let corners = frame.local_corners().map(|c| frame.to_canvas(c));
    let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
    for c in corners {
        x0 = x0.min(c.x);
        y0 = y0.min(c.y);
        x1 = x1.max(c.x);
        y1 = y1.max(c.y);
    }
    let clip = |v: f64, limit: usize| v.clamp(0.0, limit as f64) as usize;
    (
        clip(x0.floor() - 1.0, width),
        clip(y0.floor() - 1.0, height),
        clip(x1.ceil() + 1.0, width),
        clip(y1.ceil() + 1.0, height),
    )
}

/// The exemplar pixel offsets (relative to a piece position) read by the bilinear lookup at
/// local point `local`.
pub(crate) fn footprint(local: Vec2) -> [(i32, i32); 4] {
    let (ix, iy) = (local.x.floor() as i32, (local.y - 0.5).floor() as i32);
    [(ix, iy), (ix + 1, iy), (ix, iy + 1), (ix + 1, iy + 1)]
}

/// The local points of every render sample that lies in a forbidden pixel and inside the piece.
pub(crate) fn forbidden_samples(frame: &PieceFrame, mask: &ForbiddenMask, samples_per_axis: usize) -> Vec<Vec2> {
    let (x0, y0, x1, y1) = canvas_box(frame, mask.width, mask.height);
    let mut points = Vec::new();
    for y in y0..y1 {
        for x in x0..x1 {
            if !mask.is_forbidden(x, y) {
                continue;
            }
            for p in sample_points(x, y, samples_per_axis) {
                let local = frame.to_local(p);
                if frame.contains_local(local) {
                    points.push(local);
                }
            }
        }
    }
    points
}

/// Offsets that must stay invisible for a piece: the footprints of its forbidden samples.
pub(crate) fn forbidden_runs(samples: &[Vec2]) -> Vec<Run> {
    runs_from_offsets(samples.iter().flat_map(|&local| footprint(local)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ribbon::{Ribbon, slice};
    use motif_core::Polyline;
    use motif_core::math;

    #[test]
    fn a_tight_turn_folds_over_and_a_straight_ribbon_does_not() {
        let straight = Polyline::new(vec![Point::new(5.0, 30.0), Point::new(95.0, 30.0)], false).unwrap();
        let ribbon = Ribbon::new(&straight, 20.0).unwrap();
        let frames: Vec<_> = slice(&ribbon, 10.0).iter().map(|q| PieceFrame::new(q, 1.0, 20)).collect();
        let mut mask = ForbiddenMask::empty(100, 60);
        mask.add_foldovers(&frames, 2);
        assert_eq!(mask.count(), 0);

        // A hairpin whose radius (4) is smaller than half the ribbon width (10).
        let mut points = vec![Point::new(10.0, 20.0), Point::new(50.0, 20.0)];
        for i in 1..20 {
            let a = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * i as f64 / 20.0;
            points.push(Point::new(50.0 + 4.0 * math::cos(a), 24.0 + 4.0 * math::sin(a)));
        }
        points.extend([Point::new(50.0, 28.0), Point::new(10.0, 28.0)]);
        let hairpin = Polyline::new(points, false).unwrap();
        let ribbon = Ribbon::new(&hairpin, 20.0).unwrap();
        let frames: Vec<_> = slice(&ribbon, 6.0).iter().map(|q| PieceFrame::new(q, 1.0, 20)).collect();
        let mut mask = ForbiddenMask::empty(100, 60);
        mask.add_foldovers(&frames, 2);
        assert!(mask.count() > 200, "{}", mask.count());
        // The inside of the hairpin (between the two legs) is covered by both legs.
        assert!(mask.is_forbidden(30, 24));
        let samples = forbidden_samples(&frames[2], &mask, 2);
        assert!(!samples.is_empty());
        assert!(!forbidden_runs(&samples).is_empty());
    }

    #[test]
    fn avoidance_maps_forbid_white() {
        let map = RgbaImage::from_fn(4, 1, |x, _| match x {
            0 => [255, 255, 255, 255],
            1 => [0, 0, 0, 255],
            2 => [255, 255, 255, 0],
            _ => [200, 200, 200, 255],
        });
        let mut mask = ForbiddenMask::empty(4, 1);
        mask.add_map(&map);
        assert_eq!(mask.flags, vec![FROM_MAP, 0, 0, FROM_MAP]);
    }
}
