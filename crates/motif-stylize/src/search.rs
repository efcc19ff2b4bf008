//! Nearest-neighbour field search: PatchMatch (Barnes et al. 2009) made deterministic, and brute force (§4.2).
//!
//! PatchMatch visits the target in row tiles of [`TILE_ROWS`] rows. Tiles run in parallel; each
//! owns its rows of the field, reads rows of other tiles from the field as it was when the
//! iteration started, draws its random candidates from its own stream keyed by
//! (level, iteration, tile), and sees its own occurrence updates through a private
//! [`OmegaDelta`]. Nothing a tile computes depends on another tile's progress, so the field is
//! the same for any number of threads. Tiles alternate scan direction per iteration (forward:
//! propagate from left and above; backward: from right and below).

use motif_core::SeedStreams;
use motif_core::random::{Rng, RngCore};
use rayon::prelude::*;

use crate::centres::SegmentCentres;
use crate::level::{Level, WHOLE_PATCH_SIDE};
use crate::occurrence::{Occurrence, OmegaDelta};

/// `$function::<ROW>` for the level's patch row length (`patch × channels` bytes) when it has a
/// specialized kernel, else `$function::<0>`: 3×3 and 5×5 patches of grey, RGB and RGBA styles
/// with 0, 1, 3 or 4 guide channels, and with 10 (the benchmark's 13 channels).
macro_rules! specialize {
    ($level:expr, $function:ident) => {
        match $level.patch * $level.channels {
            9 => $function::<9>,
            12 => $function::<12>,
            15 => $function::<15>,
            18 => $function::<18>,
            20 => $function::<20>,
            21 => $function::<21>,
            24 => $function::<24>,
            30 => $function::<30>,
            35 => $function::<35>,
            39 => $function::<39>,
            40 => $function::<40>,
            65 => $function::<65>,
            70 => $function::<70>,
            _ => $function::<0>,
        }
    };
}

mod local_band;

pub(crate) use local_band::{local_band_iteration, plane_key};

/// Rows per PatchMatch tile (fixed, so results never depend on the thread count).
pub(crate) const TILE_ROWS: usize = 16;

/// A field under optimization: for each target pixel, the matched source patch centre
/// (`y · source_width + x`) and its patch distance D (style + guides, without the penalty).
#[derive(Debug, Clone)]
pub(crate) struct Field {
    pub matches: Vec<u32>,
    pub costs: Vec<f32>,
}

impl Field {
    /// Uniformly random valid centres (within the target pixel's segment when restricted).
    pub(crate) fn random(level: &Level, streams: &SeedStreams) -> Field {
        let (x0, x1) = level.valid_x();
        let (y0, y1) = level.valid_y();
        let width = level.target_width;
        let mut matches = vec![0_u32; level.target_len()];
        matches.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
            let mut stream = streams.stream("init", y as u64);
            for (x, slot) in row.iter_mut().enumerate() {
                *slot = random_centre(level, y * width + x, &mut stream, (x0, x1, y0, y1));
            }
        });
        let costs = vec![0.0; matches.len()];
        Field { matches, costs }
    }

    /// The given starting centres (source index, e.g. composed from the pre-synthesized textures'
    /// fields), each kept where it is a valid centre the pixel may use, else a random one: drawn
    /// from the row's stream, or with `plane` (the target's origin in the textures' plane) from
    /// the pixel's own ([`plane_key`]).
    pub(crate) fn seeded(level: &Level, seeds: &[u32], streams: &SeedStreams, plane: Option<(i64, i64)>) -> Field {
        let (x0, x1) = level.valid_x();
        let (y0, y1) = level.valid_y();
        let width = level.target_width;
        let mut matches = vec![0_u32; level.target_len()];
        matches.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
            // The row's stream, made at its first draw (with `plane`, draws use the pixel's own).
            let mut row_stream = None;
            for (x, slot) in row.iter_mut().enumerate() {
                let t = y * width + x;
                let (sx, sy) = level.source_xy(seeds[t]);
                let valid = seeds[t] != crate::band::NO_SEED && (x0..x1).contains(&sx) && (y0..y1).contains(&sy);
                *slot = if valid && level.allowed(t, seeds[t]) {
                    seeds[t]
                } else if let Some(origin) = plane {
                    let mut own = streams.stream("init pixel", plane_key((x, y), origin));
                    random_centre(level, t, &mut own, (x0, x1, y0, y1))
                } else {
                    let stream = row_stream.get_or_insert_with(|| streams.stream("init", y as u64));
                    random_centre(level, t, stream, (x0, x1, y0, y1))
                };
            }
        });
        let costs = vec![0.0; matches.len()];
        Field { matches, costs }
    }

    /// The coarser level's field doubled: target pixel `(x, y)` takes the coarse match of
    /// `(x/2, y/2)` scaled by two plus the same sub-pixel offset, clamped to valid centres
    /// (Algorithm 1's upsampling of B' through the field).
    pub(crate) fn upsample(coarse: &Field, coarse_level: &Level, level: &Level, streams: &SeedStreams) -> Field {
        let (x0, x1) = level.valid_x();
        let (y0, y1) = level.valid_y();
        let width = level.target_width;
        let mut matches = vec![0_u32; level.target_len()];
        matches.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
            let mut stream = streams.stream("upsample", y as u64);
            let cy = (y / 2).min(coarse_level.target_height - 1);
            for (x, slot) in row.iter_mut().enumerate() {
                let cx = (x / 2).min(coarse_level.target_width - 1);
                let s = coarse.matches[cy * coarse_level.target_width + cx] as usize;
                let (sx, sy) = (s % coarse_level.source_width, s / coarse_level.source_width);
                let fx = (2 * sx + (x & 1)).clamp(x0, x1 - 1);
                let fy = (2 * sy + (y & 1)).clamp(y0, y1 - 1);
                let candidate = (fy * level.source_width + fx) as u32;
                let t = y * width + x;
                *slot = if level.allowed(t, candidate) {
                    candidate
                } else {
                    random_centre(level, t, &mut stream, (x0, x1, y0, y1))
                };
            }
        });
        let costs = vec![0.0; matches.len()];
        Field { matches, costs }
    }

    /// Recomputes every searched pixel's distance D (after the target changed by voting).
    pub(crate) fn recompute_costs(&mut self, level: &Level) {
        specialize!(level, recompute_costs_n)(self, level);
    }
}

/// [`Field::recompute_costs`] with the row length fixed at compile time (or 0).
fn recompute_costs_n<const ROW: usize>(field: &mut Field, level: &Level) {
    let width = level.target_width;
    let matches = &field.matches;
    field.costs.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
        for (x, cost) in row.iter_mut().enumerate() {
            let t = y * width + x;
            *cost = if level.is_active(t) { level.distance::<ROW>(matches[t], x, y, f32::INFINITY) } else { 0.0 };
        }
    });
}

impl Field {
    /// Mean over searched pixels of D + penalty (with the occurrence snapshot).
    pub(crate) fn mean_energy(&self, level: &Level, occurrence: &Occurrence) -> f64 {
        let width = level.target_width;
        let rows: Vec<(f64, usize)> = (0..level.target_height)
            .into_par_iter()
            .map(|y| {
                let mut sum = 0.0;
                let mut count = 0;
                for t in y * width..(y + 1) * width {
                    if level.is_active(t) {
                        sum += f64::from(self.costs[t] + occurrence.snapshot_cost(self.matches[t]));
                        count += 1;
                    }
                }
                (sum, count)
            })
            .collect();
        let (sum, count) = rows.iter().fold((0.0, 0), |(s, c), &(rs, rc)| (s + rs, c + rc));
        if count == 0 { 0.0 } else { sum / count as f64 }
    }
}

/// A random valid centre for target pixel `t`: from its segment's centres when restricted.
fn random_centre(level: &Level, t: usize, stream: &mut impl Rng, bounds: (usize, usize, usize, usize)) -> u32 {
    if let Some(centres) = level.segment_of(t) {
        return centres.get(stream.random_range(0..centres.len()));
    }
    let (x0, x1, y0, y1) = bounds;
    let x = stream.random_range(x0..x1);
    let y = stream.random_range(y0..y1);
    (y * level.source_width + x) as u32
}

/// A uniform offset in `[-radius, radius]` from 32 random bits (multiply-shift; the bias of at
/// most `2·radius+1` in 2³² is irrelevant here and it is much cheaper than rejection sampling).
#[inline]
fn offset(bits: u32, radius: i64) -> i64 {
    ((u64::from(bits) * (2 * radius as u64 + 1)) >> 32) as i64 - radius
}

/// The best match found so far for one target pixel.
struct Best {
    centre: u32,
    distance: f32,
    total: f32,
}

impl Best {
    /// Tries source centre `candidate` for target `(x, y)`: keeps it when D + penalty is lower.
    #[inline(always)]
    fn consider<const ROW: usize>(
        &mut self,
        level: &Level,
        occurrence: &Occurrence,
        delta: &OmegaDelta,
        candidate: u32,
        (t, x, y): (usize, usize, usize),
    ) {
        if candidate == self.centre || !level.allowed(t, candidate) {
            return;
        }
        let penalty = occurrence.cost(candidate, delta);
        let limit = self.total - penalty;
        if limit <= 0.0 {
            return;
        }
        let distance = level.distance_small::<ROW>(candidate, x, y, 0, 0.0, limit);
        if distance < limit {
            self.centre = candidate;
            self.distance = distance;
            self.total = distance + penalty;
        }
    }
}

/// The candidates of one pixel, on the stack (no allocation in the hot loop): their centres,
/// penalties and distances (whole, or their first rows for patches above
/// [`WHOLE_PATCH_SIDE`]).
struct Candidates {
    centres: [u32; 66],
    penalties: [f32; 66],
    distances: [f32; 66],
}

impl Candidates {
    fn new() -> Self {
        Self { centres: [0; 66], penalties: [0.0; 66], distances: [0.0; 66] }
    }

    /// Random search around the match after propagation, radius halving from the level's search
    /// radius (the source size, or a few pixels when the level refines upsampled matches) to 1
    /// (Barnes et al.), plus one candidate anywhere in the pixel's own segment so that small
    /// segments far from the current match are still found. The candidates are drawn first, then
    /// processed in passes with no data-dependent branch between their memory reads, so the cache
    /// misses of all of them overlap instead of queueing one after another.
    #[inline(always)]
    fn random_search<const ROW: usize>(
        &mut self,
        level: &Level,
        occurrence: &Occurrence,
        delta: &OmegaDelta,
        stream: &mut impl RngCore,
        best: &mut Best,
        (t, x, y): (usize, usize, usize),
    ) {
        let (x0, x1) = level.valid_x();
        let (y0, y1) = level.valid_y();
        let (sx, sy) = level.source_xy(best.centre);
        let (sx, sy) = (sx as i64, sy as i64);
        let segment = level.segment_of(t);
        let mut count = 0;
        let mut radius = level.search_radius as i64;
        while radius >= 1 {
            let bits = stream.next_u64();
            let cx = (sx + offset(bits as u32, radius)).clamp(x0 as i64, x1 as i64 - 1) as usize;
            let cy = (sy + offset((bits >> 32) as u32, radius)).clamp(y0 as i64, y1 as i64 - 1) as usize;
            self.centres[count] = (cy * level.source_width + cx) as u32;
            // Outside the box of the segment's centres it cannot be one: dropped by position
            // (the segment rule of pass 1 would drop it after reading its label).
            count += usize::from(segment.is_none_or(|centres| centres.may_hold(cx, cy)));
            radius /= 2;
        }
        if let Some(centres) = segment {
            let pick = (u64::from(stream.next_u32()) * centres.len() as u64) >> 32;
            self.centres[count] = centres.get(pick as usize);
            count += 1;
        }
        // Pass 1: drop the current match and candidates of other segments (the segment rule),
        // before any of their patch memory is read: far candidates mostly land in other segments.
        // In a segment that fills its box, a candidate inside the box is in the segment.
        let inside_is_enough = segment.is_some_and(SegmentCentres::fills_box);
        let mut kept = 0;
        for index in 0..count {
            let candidate = self.centres[index];
            if candidate != best.centre && (inside_is_enough || level.allowed(t, candidate)) {
                self.centres[kept] = candidate;
                kept += 1;
            }
        }
        // Pass 2: penalties (independent loads, so their misses overlap).
        for (penalty, &candidate) in self.penalties.iter_mut().zip(&self.centres[..kept]) {
            *penalty = occurrence.cost(candidate, delta);
        }
        if level.patch <= WHOLE_PATCH_SIDE {
            self.keep_best::<ROW>(level, kept, best, (x, y));
            return;
        }
        let centres = &self.centres[..kept];
        // Larger patches: first every row of every candidate whose penalty alone does not
        // already lose is touched, so their many cache misses overlap (a software prefetch
        // without `unsafe`).
        let touched = centres
            .iter()
            .zip(&self.penalties)
            .filter(|&(_, &penalty)| penalty < best.total)
            .fold(0_u32, |sum, (&c, _)| sum.wrapping_add(level.touch(c)));
        std::hint::black_box(touched);
        // Pass 3: first rows, skipped where the penalty alone already loses (it is most of the
        // energy once matches settle).
        let rows = self.distances.iter_mut().zip(&self.penalties).zip(centres);
        for ((partial, &penalty), &candidate) in rows {
            *partial = if penalty < best.total { level.first_row::<ROW>(candidate, x, y) } else { f32::INFINITY };
        }
        // Pass 4: finish the survivors in order, with early exit against the best so far.
        for ((&partial, &penalty), &candidate) in self.distances.iter().zip(&self.penalties).zip(centres) {
            let limit = best.total - penalty;
            if partial >= limit {
                continue;
            }
            let distance = level.distance_small::<ROW>(candidate, x, y, 1, partial, limit);
            if distance < limit {
                best.centre = candidate;
                best.distance = distance;
                best.total = distance + penalty;
            }
        }
    }

    /// The first `count` candidates, their penalties given, for patches of at most
    /// [`WHOLE_PATCH_SIDE`]: their whole distances are summed one candidate after another, with
    /// no branch on the data between them (so their cache misses overlap), skipped where the
    /// penalty alone already loses; then the best is kept in order. The same choice as
    /// [`Best::consider`] taking them one by one: a whole distance at or above the limit loses
    /// as a sum stopped early there does.
    #[inline(always)]
    fn keep_best<const ROW: usize>(&mut self, level: &Level, count: usize, best: &mut Best, (x, y): (usize, usize)) {
        let centres = &self.centres[..count];
        for ((distance, &penalty), &candidate) in self.distances.iter_mut().zip(&self.penalties).zip(centres) {
            *distance = if penalty < best.total {
                level.distance_small::<ROW>(candidate, x, y, 0, 0.0, f32::INFINITY)
            } else {
                f32::INFINITY
            };
        }
        for ((&distance, &penalty), &candidate) in self.distances.iter().zip(&self.penalties).zip(centres) {
            if candidate != best.centre && distance < best.total - penalty {
                best.centre = candidate;
                best.distance = distance;
                best.total = distance + penalty;
            }
        }
    }
}

/// One PatchMatch iteration over all tiles (propagation + random search), `iteration` picks the
/// scan direction; `previous` is scratch for the field as it was at the start. With `converged`,
/// pixels marked true keep their match (ebsynth's stop threshold).
pub(crate) fn patchmatch_iteration(
    level: &Level,
    field: &mut Field,
    previous: &mut Vec<u32>,
    occurrence: &Occurrence,
    streams: &SeedStreams,
    iteration: usize,
    converged: Option<&[bool]>,
) {
    previous.clear();
    previous.extend_from_slice(&field.matches);
    let run = specialize!(level, patchmatch_tiles);
    run(level, field, previous, occurrence, streams, iteration, converged);
}

/// [`patchmatch_iteration`] with the patch row length `ROW` (bytes) fixed at compile time, or 0.
pub(crate) fn patchmatch_tiles<const ROW: usize>(
    level: &Level,
    field: &mut Field,
    previous: &[u32],
    occurrence: &Occurrence,
    streams: &SeedStreams,
    iteration: usize,
    converged: Option<&[bool]>,
) {
    let width = level.target_width;
    let forward = iteration.is_multiple_of(2);
    let (x0, x1) = level.valid_x();
    let (y0, y1) = level.valid_y();
    field
        .matches
        .par_chunks_mut(TILE_ROWS * width)
        .zip(field.costs.par_chunks_mut(TILE_ROWS * width))
        .enumerate()
        .for_each_init(
            || OmegaDelta::new(level, Some(occurrence)),
            |delta, (tile, (matches, costs))| {
                let mut stream = streams.stream("tile", tile as u64);
                let mut scratch = Candidates::new();
                let first_row = tile * TILE_ROWS;
                let rows = matches.len() / width;
                for row_step in 0..rows {
                    let local_y = if forward { row_step } else { rows - 1 - row_step };
                    let y = first_row + local_y;
                    for col_step in 0..width {
                        let x = if forward { col_step } else { width - 1 - col_step };
                        let t = y * width + x;
                        if !level.is_active(t) || converged.is_some_and(|c| c[t]) {
                            continue;
                        }
                        let local = local_y * width + x;
                        let start = matches[local];
                        let mut best = Best {
                            centre: start,
                            distance: costs[local],
                            total: costs[local] + occurrence.cost(start, delta),
                        };
                        let here = (t, x, y);
                        // Propagation: the horizontal neighbour already visited this pass.
                        let nx = if forward { x.checked_sub(1) } else { Some(x + 1).filter(|&n| n < width) };
                        if let Some(nx) = nx.filter(|&nx| level.is_active(y * width + nx)) {
                            let s = matches[local_y * width + nx];
                            let sx = level.source_x(s);
                            let shifted = if forward { sx + 1 } else { sx.wrapping_sub(1) };
                            if (x0..x1).contains(&shifted) {
                                let candidate = (s as usize - sx + shifted) as u32;
                                best.consider::<ROW>(level, occurrence, delta, candidate, here);
                            }
                        }
                        // Propagation: the vertical neighbour (from the start-of-iteration field
                        // when it lies in another tile).
                        let ny =
                            if forward { y.checked_sub(1) } else { Some(y + 1).filter(|&n| n < level.target_height) };
                        if let Some(ny) = ny.filter(|&ny| level.is_active(ny * width + x)) {
                            let s = if (first_row..first_row + rows).contains(&ny) {
                                matches[(ny - first_row) * width + x]
                            } else {
                                previous[ny * width + x]
                            };
                            let (sx, sy) = level.source_xy(s);
                            let shifted = if forward { sy + 1 } else { sy.wrapping_sub(1) };
                            if (y0..y1).contains(&shifted) {
                                let candidate = shifted * level.source_width + sx;
                                best.consider::<ROW>(level, occurrence, delta, candidate as u32, here);
                            }
                        }
                        scratch.random_search::<ROW>(level, occurrence, delta, &mut stream, &mut best, here);
                        if best.centre != start {
                            delta.moved(start, best.centre);
                            matches[local] = best.centre;
                            costs[local] = best.distance;
                        }
                    }
                }
                delta.clear();
            },
        );
}

/// Brute-force search: every target pixel tries every allowed valid source centre, with the
/// occurrence snapshot (the paper's own search, §4.2). Ties keep the current match, then the
/// lowest centre index.
pub(crate) fn exact_search(level: &Level, field: &mut Field, occurrence: &Occurrence) {
    let width = level.target_width;
    let (x0, x1) = level.valid_x();
    let (y0, y1) = level.valid_y();
    let inert = OmegaDelta::new(level, None);
    field.matches.par_chunks_mut(width).zip(field.costs.par_chunks_mut(width)).enumerate().for_each(
        |(y, (matches, costs))| {
            for x in 0..width {
                let t = y * width + x;
                if !level.is_active(t) {
                    continue;
                }
                let start = matches[x];
                let mut best =
                    Best { centre: start, distance: costs[x], total: costs[x] + occurrence.snapshot_cost(start) };
                for sy in y0..y1 {
                    for sx in x0..x1 {
                        let candidate = (sy * level.source_width + sx) as u32;
                        best.consider::<0>(level, occurrence, &inert, candidate, (t, x, y));
                    }
                }
                matches[x] = best.centre;
                costs[x] = best.distance;
            }
        },
    );
}
