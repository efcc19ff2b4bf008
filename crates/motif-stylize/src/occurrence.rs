//! The occurrence map Ω and its penalty λ·Ω/ω_best (Eq. 5, after Kaspar et al. 2015).
//!
//! Every target patch matched to source centre `s` uses the `patch²` source pixels around `s`
//! once each. The per-pixel use count ideally equals ω_best = `patch² · |target| / |source|`
//! (Eq. 6 per segment; with [`Level::source_share_cap`](crate::level::Level) the source counts
//! at most that many times the target). The penalty of a candidate patch is
//! `λ · (Σ counts over its pixels / patch²) / ω_best`, i.e. 1·λ when the patch is used exactly as
//! often as uniform use would have it; ebsynth's units, so λ = 3500 means the same here.
//!
//! Ω is kept at patch level (the sum of pixel counts over each source patch) so a candidate's
//! penalty is one lookup. It is recomputed exactly from the field before every PatchMatch
//! iteration (two box filters), and each row tile adds its own changes in a private
//! [`OmegaDelta`], so a tile sees its own updates immediately while tiles never race.

use crate::level::Level;

/// Ω at patch level plus the per-centre penalty factor `λ / (patch² · ω_best)`.
pub(crate) struct Occurrence {
    /// False when λ = 0: every penalty is 0 and nothing is maintained.
    pub enabled: bool,
    factors: Vec<f32>,
    omega: Vec<f32>,
    /// `factors · omega`: the snapshot penalty of every centre, one lookup in the hot loop.
    penalty: Vec<f32>,
    /// The common factor when there are no segments.
    uniform: Option<f32>,
    counts: Vec<f32>,
    scratch: Vec<f32>,
}

impl Occurrence {
    /// Penalty factors from ω_best, global or per segment (Eq. 6), counting the searched target
    /// patches of each label.
    pub(crate) fn new(level: &Level, lambda: f32) -> Occurrence {
        let source_len = level.source_width * level.source_height;
        if lambda <= 0.0 {
            return Occurrence {
                enabled: false,
                factors: Vec::new(),
                omega: Vec::new(),
                penalty: Vec::new(),
                uniform: None,
                counts: Vec::new(),
                scratch: Vec::new(),
            };
        }
        let area = (level.patch * level.patch) as f32;
        let searched = (0..level.target_len()).filter(|&t| level.is_active(t)).count().max(1);
        // With a cap (a large exemplar), uniform use is measured as if the exemplar had at most
        // `cap` times the searched patches: uncapped, ω_best falls with the exemplar's size, the
        // penalty of a coherent copy grows with it, and it breaks up every coherent run.
        let sources = level.source_share_cap.map_or(source_len, |cap| source_len.min(cap * searched));
        let global_best = area * searched as f32 / sources as f32;
        let factors = match (&level.source_labels, &level.target_restrict) {
            (Some(source_labels), Some(restrict)) => {
                let labels = level.segment_centres.len();
                let mut source_sizes = vec![0usize; labels];
                for &label in source_labels.iter() {
                    source_sizes[usize::from(label)] += 1;
                }
                let mut target_sizes = vec![0usize; labels];
                for (t, &label) in restrict.iter().enumerate() {
                    if label != crate::level::UNRESTRICTED && level.is_active(t) {
                        target_sizes[usize::from(label)] += 1;
                    }
                }
                let best: Vec<f32> = (0..labels)
                    .map(|label| {
                        if target_sizes[label] == 0 || source_sizes[label] == 0 {
                            global_best
                        } else {
                            area * target_sizes[label] as f32 / source_sizes[label] as f32
                        }
                    })
                    .collect();
                source_labels.iter().map(|&label| lambda / (area * best[usize::from(label)])).collect()
            }
            _ => vec![lambda / (area * global_best); source_len],
        };
        let uniform = (level.source_labels.is_none()).then(|| lambda / (area * global_best));
        Occurrence {
            enabled: true,
            factors,
            omega: vec![0.0; source_len],
            penalty: vec![0.0; source_len],
            uniform,
            counts: vec![0.0; source_len],
            scratch: vec![0.0; source_len],
        }
    }

    /// The penalty of source centre `s` with the snapshot Ω plus a tile's own changes.
    #[inline]
    pub(crate) fn cost(&self, s: u32, delta: &OmegaDelta) -> f32 {
        if !self.enabled {
            return 0.0;
        }
        let s = s as usize;
        // A tile's delta holds its own copy of the penalties: one load instead of two.
        if delta.values.is_empty() { self.penalty[s] } else { delta.values[s] }
    }

    /// The penalty of source centre `s` with the snapshot Ω only.
    #[inline]
    pub(crate) fn snapshot_cost(&self, s: u32) -> f32 {
        if !self.enabled { 0.0 } else { self.penalty[s as usize] }
    }

    /// Recomputes Ω exactly from the matches of the searched target patches.
    pub(crate) fn refresh(&mut self, level: &Level, matches: &[u32]) {
        if !self.enabled {
            return;
        }
        self.counts.fill(0.0);
        for (t, &s) in matches.iter().enumerate() {
            if level.is_active(t) {
                self.counts[s as usize] += 1.0;
            }
        }
        // Pixel counts: each centre's count spread over its patch; then Ω: pixel counts summed
        // over each patch. Both are box filters of side `patch`.
        let (w, h, r) = (level.source_width, level.source_height, level.radius);
        box_filter(&self.counts, &mut self.scratch, &mut self.omega, w, h, r);
        std::mem::swap(&mut self.counts, &mut self.omega);
        box_filter(&self.counts, &mut self.scratch, &mut self.omega, w, h, r);
        for ((penalty, factor), omega) in self.penalty.iter_mut().zip(&self.factors).zip(&self.omega) {
            *penalty = factor * omega;
        }
    }

    /// Fraction of valid source patch centres used by at least one searched target patch.
    pub(crate) fn coverage(level: &Level, matches: &[u32]) -> f64 {
        let mut used = vec![false; level.source_width * level.source_height];
        for (t, &s) in matches.iter().enumerate() {
            if level.is_active(t) {
                used[s as usize] = true;
            }
        }
        let (x0, x1) = level.valid_x();
        let (y0, y1) = level.valid_y();
        let total = (x1 - x0) * (y1 - y0);
        let count = used.iter().filter(|&&u| u).count();
        count as f64 / total.max(1) as f64
    }
}

/// Box sum of side `2r + 1` (zero outside the image): `input` → `output`, via `scratch`.
fn box_filter(input: &[f32], scratch: &mut [f32], output: &mut [f32], w: usize, h: usize, r: usize) {
    for y in 0..h {
        let row = &input[y * w..(y + 1) * w];
        let out = &mut scratch[y * w..(y + 1) * w];
        let mut sum: f32 = row[..r.min(w)].iter().sum();
        for x in 0..w {
            if x + r < w {
                sum += row[x + r];
            }
            out[x] = sum;
            if x >= r {
                sum -= row[x - r];
            }
        }
    }
    // Vertical pass: the same running sum per column, in the same order, but all columns
    // advanced together row by row (contiguous, vectorized) instead of one column at a time (a
    // stride of a whole row per step).
    let mut sums = vec![0.0_f32; w];
    for y in 0..r.min(h) {
        for (sum, value) in sums.iter_mut().zip(&scratch[y * w..(y + 1) * w]) {
            *sum += value;
        }
    }
    for y in 0..h {
        if y + r < h {
            for (sum, value) in sums.iter_mut().zip(&scratch[(y + r) * w..(y + r + 1) * w]) {
                *sum += value;
            }
        }
        output[y * w..(y + 1) * w].copy_from_slice(&sums);
        if y >= r {
            for (sum, value) in sums.iter_mut().zip(&scratch[(y - r) * w..(y - r + 1) * w]) {
                *sum -= value;
            }
        }
    }
}

/// Adds the `SIDE × SIDE` table `steps` (row-major) to the window of `values` at its start (row
/// stride `stride`), row by row.
#[inline(always)]
fn add_window<const SIDE: usize>(values: &mut [f32], steps: &[f32], stride: usize) {
    for (row, steps) in steps.chunks_exact(SIDE).enumerate() {
        let values: &mut [f32; SIDE] =
            (&mut values[row * stride..row * stride + SIDE]).try_into().expect("a whole window row");
        let steps: &[f32; SIDE] = steps.try_into().expect("a whole table row");
        for (value, step) in values.iter_mut().zip(steps) {
            *value += step;
        }
    }
}

/// [`add_window`] for any side.
fn add_window_n(values: &mut [f32], steps: &[f32], stride: usize, side: usize) {
    for (row, steps) in steps.chunks_exact(side).enumerate() {
        for (value, step) in values[row * stride..row * stride + side].iter_mut().zip(steps) {
            *value += step;
        }
    }
}

/// One tile's private view of the penalty: the snapshot plus its own changes since (Ω times
/// its factor), restored to the snapshot after the tile. Keeping the sum rather than the changes
/// alone halves the memory a candidate's penalty reads.
pub(crate) struct OmegaDelta<'a> {
    values: Vec<f32>,
    snapshot: &'a [f32],
    factors: &'a [f32],
    /// The factor when all centres share one (no segments): saves a memory stream per move.
    uniform: Option<f32>,
    /// With a uniform factor: the change of every entry of a move's window, precomputed
    /// (`(factor · overlap_y · sign) · overlap_x`, the very products the general case forms, so
    /// the sums are the same), removal (`sign` −1) first, then addition; `(2·patch − 1)²` each.
    steps: Vec<f32>,
    log: Vec<u32>,
    /// Overlap of two patches whose centres differ by `k − (patch − 1)` on an axis:
    /// `patch − |k − (patch − 1)|`, for `k` in `0..2·patch − 1`.
    overlaps: Vec<f32>,
    width: usize,
    height: usize,
    patch: usize,
}

impl<'a> OmegaDelta<'a> {
    /// A zeroed delta for the level's source with the penalty factors of `occurrence`, or an
    /// inert one when `occurrence` is `None` or off.
    pub(crate) fn new(level: &Level, occurrence: Option<&'a Occurrence>) -> OmegaDelta<'a> {
        let enabled = occurrence.filter(|o| o.enabled);
        let factors: &'a [f32] = enabled.map_or(&[], |o| &o.factors);
        let snapshot: &'a [f32] = enabled.map_or(&[], |o| &o.penalty);
        let uniform = occurrence.and_then(|o| o.uniform);
        let overlaps: Vec<f32> =
            (0..2 * level.patch - 1).map(|k| (level.patch - k.abs_diff(level.patch - 1)) as f32).collect();
        let mut steps = Vec::new();
        if let Some(factor) = uniform {
            for sign in [-1.0_f32, 1.0] {
                for &overlap_y in &overlaps {
                    let scale = factor * (overlap_y * sign);
                    steps.extend(overlaps.iter().map(|&overlap_x| scale * overlap_x));
                }
            }
        }
        OmegaDelta {
            values: snapshot.to_vec(),
            snapshot,
            factors,
            uniform,
            steps,
            log: Vec::new(),
            overlaps,
            width: level.source_width,
            height: level.source_height,
            patch: level.patch,
        }
    }

    /// Records that one target patch moved from centre `old` to centre `new`: every source patch
    /// overlapping either changes its Ω by the overlap area.
    pub(crate) fn moved(&mut self, old: u32, new: u32) {
        if self.values.is_empty() {
            return;
        }
        self.add(old, -1.0);
        self.add(new, 1.0);
        self.log.push(old);
        self.log.push(new);
    }

    fn add(&mut self, centre: u32, sign: f32) {
        let (w, h, p) = (self.width, self.height, self.patch);
        let (cx, cy) = (centre as usize % w, centre as usize / w);
        // Overlap of two patches whose centres differ by d on an axis: p − |d|, |d| < p.
        let (x0, x1) = ((cx + 1).saturating_sub(p), (cx + p).min(w));
        let (y0, y1) = ((cy + 1).saturating_sub(p), (cy + p).min(h));
        if self.uniform.is_some() {
            let side = 2 * p - 1;
            let table = if sign < 0.0 { &self.steps[..side * side] } else { &self.steps[side * side..] };
            if x1 - x0 == side && y1 - y0 == side {
                // The whole window lies inside (nearly always): fixed-size rows for 3×3 and 5×5
                // patches, unrolled without per-element loop control or bounds checks.
                let start = y0 * w + x0;
                match side {
                    5 => add_window::<5>(&mut self.values[start..], table, w),
                    9 => add_window::<9>(&mut self.values[start..], table, w),
                    _ => add_window_n(&mut self.values[start..], table, w, side),
                }
                return;
            }
            for y in y0..y1 {
                let start = (y + p - 1 - cy) * side + x0 + p - 1 - cx;
                let steps = &table[start..start + (x1 - x0)];
                let row = y * w;
                for (value, step) in self.values[row + x0..row + x1].iter_mut().zip(steps) {
                    *value += step;
                }
            }
            return;
        }
        let overlap_x = &self.overlaps[x0 + p - 1 - cx..x1 + p - 1 - cx];
        for y in y0..y1 {
            let weight_y = self.overlaps[y + p - 1 - cy] * sign;
            let row = y * w;
            let values = &mut self.values[row + x0..row + x1];
            let factors = &self.factors[row + x0..row + x1];
            for ((value, factor), overlap) in values.iter_mut().zip(factors).zip(overlap_x) {
                *value += factor * weight_y * overlap;
            }
        }
    }

    /// Restores everything this tile changed to the snapshot, ready for the next tile.
    pub(crate) fn clear(&mut self) {
        if self.values.is_empty() {
            return;
        }
        // Many moves: one straight copy beats thousands of short scattered ones.
        let window = (2 * self.patch - 1) * (2 * self.patch - 1);
        if self.log.len() * window > self.values.len() / 2 {
            self.values.copy_from_slice(self.snapshot);
            self.log.clear();
            return;
        }
        let (w, h, p) = (self.width as isize, self.height as isize, self.patch as isize);
        for &centre in &self.log {
            let (cx, cy) = ((centre as usize % self.width) as isize, (centre as usize / self.width) as isize);
            for y in (cy - p + 1).max(0)..(cy + p).min(h) {
                let row = (y * w) as usize;
                let (x0, x1) = ((cx - p + 1).max(0) as usize, (cx + p).min(w) as usize);
                self.values[row + x0..row + x1].copy_from_slice(&self.snapshot[row + x0..row + x1]);
            }
        }
        self.log.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_filter_matches_direct_sums() {
        let (w, h, r) = (7, 5, 2);
        let input: Vec<f32> = (0..w * h).map(|i| ((i * 37) % 11) as f32).collect();
        let mut scratch = vec![0.0; w * h];
        let mut output = vec![0.0; w * h];
        box_filter(&input, &mut scratch, &mut output, w, h, r);
        for y in 0..h as isize {
            for x in 0..w as isize {
                let mut sum = 0.0;
                for yy in (y - 2).max(0)..(y + 3).min(h as isize) {
                    for xx in (x - 2).max(0)..(x + 3).min(w as isize) {
                        sum += input[(yy * w as isize + xx) as usize];
                    }
                }
                assert_eq!(output[(y * w as isize + x) as usize], sum);
            }
        }
    }
}
