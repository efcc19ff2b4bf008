//! The exemplar, prepared for fast lookups (the paper's `E`, §1.1).
//!
//! The exemplar is stored with a wide transparent margin on every side, so that every position a
//! piece can take (up to `C` pixels above the exemplar, §1.4) and every pixel such a piece covers
//! can be read without bounds checks: outside the exemplar everything is transparent. Row prefix
//! counts answer "is any pixel of this row span opaque?" in constant time, which is what the
//! validity test (§1.3, §3.1) asks over and over.

use motif_core::RgbaImage;

/// A horizontal span of pixel offsets `[x0, x1)` in row `dy`, relative to a piece position.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Run {
    pub dy: i32,
    pub x0: i32,
    pub x1: i32,
}

/// Turns a set of `(dx, dy)` offsets into row runs (sorted, merged).
pub(crate) fn runs_from_offsets(mut offsets: Vec<(i32, i32)>) -> Vec<Run> {
    offsets.sort_unstable_by_key(|&(dx, dy)| (dy, dx));
    offsets.dedup();
    let mut runs: Vec<Run> = Vec::new();
    for (dx, dy) in offsets {
        match runs.last_mut() {
            Some(run) if run.dy == dy && run.x1 == dx => run.x1 += 1,
            _ => runs.push(Run { dy, x0: dx, x1: dx + 1 }),
        }
    }
    runs
}

/// First and last columns of `[x0, x1)` holding a pixel with alpha > `cut_alpha` (the whole range
/// when none does).
pub(crate) fn pattern_extent(image: &RgbaImage, x0: usize, x1: usize, cut_alpha: u8) -> (i32, i32) {
    let occupied = |x: usize| (0..image.height()).any(|y| image.get(x, y)[3] > cut_alpha);
    match ((x0..x1).find(|&x| occupied(x)), (x0..x1).rev().find(|&x| occupied(x))) {
        (Some(a), Some(b)) => (a as i32, b as i32),
        _ => (x0 as i32, x1 as i32 - 1),
    }
}

/// The exemplar with a transparent margin, straight-alpha bytes (colour zeroed where alpha is 0)
/// and premultiplied floats for rendering.
#[derive(Debug, Clone)]
pub(crate) struct Exemplar {
    pub width: i32,
    pub height: i32,
    /// Margin on every side, in pixels.
    pub pad: i32,
    /// Padded row length.
    pub stride: usize,
    /// Padded row count.
    pub rows: usize,
    /// Straight-alpha RGBA, padded.
    pub rgba: Vec<[u8; 4]>,
    /// Premultiplied RGBA in `[0, 1]`, exemplar pixels only (for bilinear sampling at render time).
    premultiplied: Vec<[f32; 4]>,
    /// Per padded row, `stride + 1` prefix counts of pixels with alpha > `cut_alpha`.
    occupied_prefix: Vec<u32>,
    /// Per padded row, `stride + 1` prefix counts of pixels with alpha > 0.
    visible_prefix: Vec<u32>,
    /// First and last exemplar rows holding a pixel with alpha > `cut_alpha` (the pattern's
    /// vertical extent), `None` when there is none.
    pub pattern_rows: Option<(i32, i32)>,
    /// First and last exemplar columns holding a pixel with alpha > `cut_alpha` (the pattern's
    /// horizontal extent; the exemplar's width when there is none). Several exemplars laid side by
    /// side have one range each, and a piece stays inside one of them.
    pub pattern_columns: Vec<(i32, i32)>,
}

impl Exemplar {
    /// Prepares `image` with a margin of `pad` transparent pixels; pixels with alpha ≤ `cut_alpha`
    /// count as transparent for the slicing test (§1.3).
    pub(crate) fn new(image: &RgbaImage, pad: usize, cut_alpha: u8) -> Self {
        let (w, h) = (image.width(), image.height());
        let stride = w + 2 * pad;
        let rows = h + 2 * pad;
        let mut rgba = vec![[0_u8; 4]; stride * rows];
        let mut premultiplied = vec![[0.0_f32; 4]; w * h];
        for y in 0..h {
            for x in 0..w {
                let pixel = image.get(x, y);
                let index = (y + pad) * stride + x + pad;
                if pixel[3] > 0 {
                    rgba[index] = pixel;
                    let alpha = f32::from(pixel[3]) / 255.0;
                    premultiplied[y * w + x] = [
                        f32::from(pixel[0]) / 255.0 * alpha,
                        f32::from(pixel[1]) / 255.0 * alpha,
                        f32::from(pixel[2]) / 255.0 * alpha,
                        alpha,
                    ];
                }
            }
        }
        let prefix = |threshold: u8| {
            let mut counts = vec![0_u32; rows * (stride + 1)];
            for y in 0..rows {
                let row = &mut counts[y * (stride + 1)..(y + 1) * (stride + 1)];
                for x in 0..stride {
                    row[x + 1] = row[x] + u32::from(rgba[y * stride + x][3] > threshold);
                }
            }
            counts
        };
        let occupied_prefix = prefix(cut_alpha);
        let visible_prefix = prefix(0);
        let row_total = |y: usize| occupied_prefix[(y + pad) * (stride + 1) + stride];
        let first = (0..h).find(|&y| row_total(y) > 0);
        let last = (0..h).rev().find(|&y| row_total(y) > 0);
        let pattern_rows = first.zip(last).map(|(a, b)| (a as i32, b as i32));
        let pattern_columns = vec![pattern_extent(image, 0, w, cut_alpha)];
        Self {
            width: w as i32,
            height: h as i32,
            pad: pad as i32,
            stride,
            rows,
            rgba,
            premultiplied,
            occupied_prefix,
            visible_prefix,
            pattern_rows,
            pattern_columns,
        }
    }

    /// The same exemplar seen as several sources side by side: `sources` are the column ranges
    /// `[x0, x1)` of each, whose pattern extents replace the whole image's.
    pub(crate) fn with_sources(mut self, image: &RgbaImage, sources: &[(usize, usize)], cut_alpha: u8) -> Self {
        self.pattern_columns = sources.iter().map(|&(x0, x1)| pattern_extent(image, x0, x1, cut_alpha)).collect();
        self
    }

    /// Index into the padded arrays of exemplar pixel `(x, y)` (which may lie in the margin).
    #[inline]
    pub(crate) fn index(&self, x: i32, y: i32) -> usize {
        (y + self.pad) as usize * self.stride + (x + self.pad) as usize
    }

    /// True when `(x, y)` lies inside the padded storage.
    #[inline]
    pub(crate) fn in_storage(&self, x: i32, y: i32) -> bool {
        x + self.pad >= 0
            && y + self.pad >= 0
            && ((x + self.pad) as usize) < self.stride
            && ((y + self.pad) as usize) < self.rows
    }

    /// True when every pixel of run `run` placed at `(x, y)` has alpha ≤ `cut_alpha`.
    #[inline]
    pub(crate) fn run_is_clear(&self, run: &Run, x: i32, y: i32) -> bool {
        self.run_count(&self.occupied_prefix, run, x, y) == 0
    }

    /// True when every pixel of run `run` placed at `(x, y)` has alpha 0.
    #[inline]
    pub(crate) fn run_is_invisible(&self, run: &Run, x: i32, y: i32) -> bool {
        self.run_count(&self.visible_prefix, run, x, y) == 0
    }

    /// Number of pixels of run `run` placed at `(x, y)` with alpha > `cut_alpha` (the pattern's
    /// pixels), from the row prefix counts: constant time per run.
    #[inline]
    pub(crate) fn run_occupied(&self, run: &Run, x: i32, y: i32) -> u32 {
        self.run_count(&self.occupied_prefix, run, x, y)
    }

    #[inline]
    fn run_count(&self, prefix: &[u32], run: &Run, x: i32, y: i32) -> u32 {
        let row = (y + run.dy + self.pad) as usize * (self.stride + 1);
        let x0 = (x + run.x0 + self.pad) as usize;
        let x1 = (x + run.x1 + self.pad) as usize;
        prefix[row + x1] - prefix[row + x0]
    }

    /// The premultiplied pixel `(x, y)`; transparent outside the exemplar.
    #[inline]
    pub(crate) fn premultiplied_at(&self, x: i32, y: i32) -> [f32; 4] {
        if x < 0 || y < 0 || x >= self.width || y >= self.height {
            return [0.0; 4];
        }
        self.premultiplied[y as usize * self.width as usize + x as usize]
    }

    /// Premultiplied bilinear sample at continuous exemplar coordinates (pixel centres at `+0.5`);
    /// transparent outside the storage.
    pub(crate) fn sample_premultiplied(&self, x: f64, y: f64) -> [f32; 4] {
        let fx = x - 0.5;
        let fy = y - 0.5;
        let (x0, y0) = (fx.floor(), fy.floor());
        let (tx, ty) = ((fx - x0) as f32, (fy - y0) as f32);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let limit = i64::from(i32::MAX / 4);
        if x0.abs() > limit || y0.abs() > limit {
            return [0.0; 4];
        }
        let (x0, y0) = (x0 as i32, y0 as i32);
        let mut out = [0.0_f32; 4];
        for (dx, dy, weight) in
            [(0, 0, (1.0 - tx) * (1.0 - ty)), (1, 0, tx * (1.0 - ty)), (0, 1, (1.0 - tx) * ty), (1, 1, tx * ty)]
        {
            if weight == 0.0 {
                continue;
            }
            let pixel = self.premultiplied_at(x0 + dx, y0 + dy);
            for c in 0..4 {
                out[c] += weight * pixel[c];
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_merge_and_counts_see_the_margin_as_clear() {
        let runs = runs_from_offsets(vec![(2, 0), (0, 0), (1, 0), (1, 0), (5, 0), (0, 1)]);
        assert_eq!(runs, vec![Run { dy: 0, x0: 0, x1: 3 }, Run { dy: 0, x0: 5, x1: 6 }, Run { dy: 1, x0: 0, x1: 1 }]);
        let image = RgbaImage::from_fn(4, 3, |x, y| if x == 2 && y == 1 { [9, 9, 9, 200] } else { [7, 7, 7, 0] });
        let exemplar = Exemplar::new(&image, 5, 100);
        let run = Run { dy: 0, x0: 0, x1: 4 };
        assert!(!exemplar.run_is_clear(&run, 0, 1));
        assert!(exemplar.run_is_clear(&run, 0, 0));
        assert!(exemplar.run_is_clear(&run, -5, -5));
        assert!(!exemplar.run_is_invisible(&Run { dy: 0, x0: 2, x1: 3 }, 0, 1));
        // Transparent pixels lose their colour.
        assert_eq!(exemplar.rgba[exemplar.index(0, 0)], [0, 0, 0, 0]);
        let centre = exemplar.sample_premultiplied(2.5, 1.5);
        assert!((centre[3] - 200.0 / 255.0).abs() < 1e-6);
        assert_eq!(exemplar.sample_premultiplied(-100.0, 1e12), [0.0; 4]);
    }
}
