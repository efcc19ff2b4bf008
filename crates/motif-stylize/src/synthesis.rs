//! Multi-resolution EM (Algorithm 1, §3.5): coarse to fine, N × (search, vote) per level, the
//! field upsampled between levels; optionally a final 3×3 pass; the report figures.

use std::borrow::Cow;

use motif_core::timing::Clock;
use motif_core::{ChannelImage, FloatImage, Progress, SeedStreams, StageTimer};

use crate::level::{Level, LevelSpec};
use crate::native::{LOCAL_SEARCH_RADIUS, OCCURRENCE_SOURCE_SHARE, is_local, is_native};
use crate::occurrence::Occurrence;
use crate::outcome::{Figures, composition_only, image_only, public_field};
use crate::search::{Field, exact_search, local_band_iteration, patchmatch_iteration};
use crate::vote::vote;
use crate::{Error, LevelReport, NnfMethod, Output, Params, Report, segments};

/// A validated problem in the engine's terms (built by the public entry points).
pub(crate) struct Problem<'a, I: ChannelImage = FloatImage> {
    pub style: &'a I,
    /// One image per guide (none without guides), each with its own channels.
    pub source_guides: Vec<&'a I>,
    pub target_guides: Vec<&'a I>,
    pub style_weights: Vec<f32>,
    pub guide_weights: Vec<f32>,
    pub target_size: (usize, usize),
    /// Source labels (borrowed from a prepared style, else the run's own), target labels, label
    /// count.
    pub labels: Option<(Cow<'a, [u16]>, Vec<u16>, usize)>,
    /// The style side made once for many runs ([`crate::Input::prepared`], checked to fit).
    pub prepared: Option<&'a crate::PreparedStyle<I>>,
    pub tileable: bool,
    /// Band mode (§3.7): the composed image and the band of pixels to optimize.
    pub composition: Option<(FloatImage, Vec<bool>)>,
    /// Band mode: the starting source centre of every target pixel, from the textures' fields
    /// ([`crate::band::NO_SEED`] = none).
    pub seeds: Option<Vec<u32>>,
    /// The output's top-left in the textures' plane ([`crate::Input::texture_origin`]).
    pub origin: (i64, i64),
    /// Synthesize only the hole, keep the rest (checked: the output's size, the style's channels).
    pub mask: Option<&'a crate::Mask<I>>,
    /// Structure guidance: the style's last channel is the feature distance, of this weight at
    /// the coarsest level, falling linearly to 0 at the finest (`crate::structure_guidance`).
    pub structure_weight: Option<f32>,
}

/// A mask at pyramid level `level`: a coarse pixel is in the hole when any of the pixels it
/// stands for is.
fn hole_at(hole: &[bool], size: (usize, usize), level: usize) -> Vec<bool> {
    let mut current = hole.to_vec();
    let (mut width, mut height) = size;
    for _ in 0..level {
        let (next_width, next_height) = (width.div_ceil(2), height.div_ceil(2));
        let mut next = vec![false; next_width * next_height];
        for y in 0..height {
            for x in 0..width {
                if current[y * width + x] {
                    next[(y / 2) * next_width + x / 2] = true;
                }
            }
        }
        (current, width, height) = (next, next_width, next_height);
    }
    current
}

/// Number of pyramid levels whose sides all stay ≥ `min_side`.
fn fitting_levels(sizes: &[(usize, usize)], min_side: usize) -> usize {
    let mut levels = 1;
    let mut current: Vec<(usize, usize)> = sizes.to_vec();
    loop {
        current = current.iter().map(|&(w, h)| (w.div_ceil(2), h.div_ceil(2))).collect();
        if current.iter().any(|&(w, h)| w < min_side || h < min_side) || levels >= 32 {
            return levels;
        }
        levels += 1;
    }
}

/// A Gaussian pyramid over a borrowed finest level.
struct Pyramid<'a, I> {
    finest: &'a I,
    coarser: Vec<I>,
}

impl<'a, I: ChannelImage> Pyramid<'a, I> {
    fn new(finest: &'a I, levels: usize) -> Self {
        Self { finest, coarser: finest.coarser_levels(levels, 1) }
    }

    /// Level `index`, 0 = finest.
    fn level(&self, index: usize) -> &I {
        if index == 0 { self.finest } else { &self.coarser[index - 1] }
    }
}

/// The patch side at pyramid level `level` (0 = finest) of `levels`: from
/// [`Params::coarse_patch_size`] at the coarsest down to `patch_size` at the finest, linearly,
/// odd, and small enough that the level's source and target hold two patches a side.
fn patch_at_level(
    params: &Params,
    levels: usize,
    level: usize,
    source_size: (usize, usize),
    target_size: (usize, usize),
) -> usize {
    let fine = params.patch_size;
    if params.coarse_patch_size <= fine || levels < 2 {
        return fine;
    }
    let along = level as f64 / (levels - 1) as f64;
    let wanted = fine as f64 + along * (params.coarse_patch_size - fine) as f64;
    let mut side = (wanted / 2.0).floor() as usize * 2 + 1;
    let (source, target) = (level_size(source_size, level), level_size(target_size, level));
    let room = source.0.min(source.1).min(target.0).min(target.1).saturating_sub(1) / 2;
    let room = if room.is_multiple_of(2) { room.saturating_sub(1) } else { room };
    side = side.min(room).max(fine);
    side
}

/// Size of pyramid level `level` of an image of size `size`.
pub(crate) fn level_size(size: (usize, usize), level: usize) -> (usize, usize) {
    (0..level).fold(size, |(w, h), _| (w.div_ceil(2), h.div_ceil(2)))
}

/// Dilates a mask by `radius` (Chebyshev): the patch centres whose patch touches the mask.
/// Separable, each pass a sliding count of the set pixels in the window (linear in the pixels,
/// whatever the radius).
pub(crate) fn dilate(mask: &[bool], width: usize, height: usize, radius: usize) -> Vec<bool> {
    if mask.is_empty() {
        return Vec::new();
    }
    let mut horizontal = vec![false; mask.len()];
    for (row, out) in mask.chunks_exact(width).zip(horizontal.chunks_exact_mut(width)) {
        dilate_line(width, radius, |i| row[i], |i, v| out[i] = v);
    }
    // Vertically, row by row: a count per column of the set pixels in the window.
    let row = |y: usize| &horizontal[y * width..(y + 1) * width];
    let add = |counts: &mut [u32], y: usize, step: i32| {
        for (count, &set) in counts.iter_mut().zip(row(y)) {
            *count = count.wrapping_add_signed(step * i32::from(set));
        }
    };
    let mut counts = vec![0_u32; width];
    (0..radius.min(height)).for_each(|y| add(&mut counts, y, 1));
    let mut out = vec![false; mask.len()];
    for (y, out_row) in out.chunks_exact_mut(width).enumerate() {
        if y + radius < height {
            add(&mut counts, y + radius, 1);
        }
        out_row.iter_mut().zip(&counts).for_each(|(o, &c)| *o = c > 0);
        if y >= radius {
            add(&mut counts, y - radius, -1);
        }
    }
    out
}

/// One line of [`dilate`]: `set(i, any of get(i − radius ..= i + radius))` for `i` in `0..len`.
#[inline(always)]
fn dilate_line(len: usize, radius: usize, get: impl Fn(usize) -> bool, mut set: impl FnMut(usize, bool)) {
    let mut count = (0..radius.min(len)).filter(|&i| get(i)).count();
    for i in 0..len {
        if i + radius < len && get(i + radius) {
            count += 1;
        }
        set(i, count > 0);
        if i >= radius && get(i - radius) {
            count -= 1;
        }
    }
}

/// Runs the whole optimization.
pub(crate) fn run<I: ChannelImage>(
    mut problem: Problem<'_, I>,
    params: &Params,
    progress: &mut dyn Progress,
) -> Result<Output, Error> {
    let start = Clock::now();
    let params = &band_params(&problem, params);
    let levels = level_count(&problem, params);
    let source_size = (problem.style.width(), problem.style.height());
    if let Some((composed, domain)) = &problem.composition
        && !domain.iter().any(|&inside| inside)
    {
        // Band 0 (or a single segment): the pure bitmap composition of §3.7, nothing to optimize.
        return Ok(composition_only(composed, source_size, params.patch_size, start));
    }
    // Band mode (one level) starts from the composed textures: moved into the output, not copied.
    let mut image = match problem.composition.as_mut() {
        Some((composed, _)) => std::mem::replace(composed, FloatImage::new(0, 0, 1)),
        None => FloatImage::new(0, 0, 1),
    };
    let em = Em::new(&problem, params, levels);
    let mut timer = StageTimer::new();
    let mut reports = Vec::with_capacity(levels + 1);
    let mut previous: Option<(Field, Level)> = None;
    let mut scratch = Vec::new();
    for level_index in (0..levels).rev() {
        // The coarser level is dropped once its field is upsampled.
        let (field, level, report) = em.level(level_index, previous.take(), &mut image, &mut scratch, progress);
        timer.add(&report.name, report.ms);
        reports.push(report);
        previous = Some((field, level));
    }
    let (mut field, mut level) = previous.expect("at least one level");
    if params.extra_pass_3x3 {
        let report;
        (level, report) = em.extra_pass(&mut field, level, &mut image, &mut scratch, progress);
        timer.add(&report.name, report.ms);
        reports.push(report);
    }
    if !params.final_figures {
        let band_only = em.local_band().is_some();
        let searched = (0..level.target_len())
            .filter(|&t| if band_only { level.in_domain(t) } else { level.is_active(t) })
            .count();
        return Ok(image_only(image, source_size, params.patch_size, (reports, timer, start), searched));
    }
    let figures = Figures::new(&mut field, &level, params, em.local[0], em.local_band().is_some());
    let field = public_field(field, level, figures.vote_weights);
    Ok(Output {
        image,
        field,
        error_map: figures.error_map,
        report: Report {
            energy: figures.energy,
            source_coverage: figures.source_coverage,
            levels: reports,
            stages_ms: timer.finish(),
            total_ms: motif_core::timing::elapsed_ms(start),
            searched_pixels: figures.searched,
            estimated_memory_bytes: 0,
        },
    })
}
/// The parameters of the run: a band that starts from the textures' fields is nearly converged,
/// so it takes the band's (fewer) iterations (§3.7).
fn band_params<I: ChannelImage>(problem: &Problem<'_, I>, params: &Params) -> Params {
    let mut params = params.clone();
    if problem.composition.is_some() && problem.seeds.is_some() {
        params.search_vote_iterations = params.band_search_vote_iterations;
        params.patchmatch_iterations = params.band_patchmatch_iterations;
    }
    params
}

/// Number of pyramid levels: as many as fit two patches a side (or as asked, if fewer).
fn level_count<I: ChannelImage>(problem: &Problem<'_, I>, params: &Params) -> usize {
    if problem.composition.is_some() || problem.seeds.is_some() {
        // Band mode optimizes a thin band at full resolution only (§3.7); a quilted start is
        // already laid out at full resolution.
        return 1;
    }
    let source_size = (problem.style.width(), problem.style.height());
    let fit = fitting_levels(&[source_size, problem.target_size], 2 * params.patch_size + 1);
    if params.pyramid_levels == 0 { fit } else { params.pyramid_levels.min(fit) }
}

/// The multi-resolution EM of one problem: its pyramids and what every level reads.
struct Em<'p, 'a, I: ChannelImage> {
    problem: &'p Problem<'a, I>,
    params: &'p Params,
    streams: SeedStreams,
    levels: usize,
    source_size: (usize, usize),
    // Pyramids hold the coarser levels only; level 0 is the problem's own image (no copy of the
    // largest images: the stacked guides are the biggest buffers of a run).
    style: Pyramid<'a, I>,
    source_guides: Vec<Pyramid<'a, I>>,
    target_guides: Vec<Pyramid<'a, I>>,
    keep: Option<Pyramid<'a, I>>,
    /// The mask's hole at every level.
    holes: Option<Vec<Vec<bool>>>,
    /// Per level, the style channels' weights (they differ only with structure guidance).
    style_weights: Vec<Vec<f32>>,
    /// Per level, whether it refines upsampled matches (see `native::is_local`).
    local: Vec<bool>,
    /// Whether the occurrence penalty caps the exemplar's share (see `native::is_native`).
    native: bool,
}

impl<'p, 'a, I: ChannelImage> Em<'p, 'a, I> {
    fn new(problem: &'p Problem<'a, I>, params: &'p Params, levels: usize) -> Self {
        let style_weights = (0..levels)
            .map(|level| {
                let mut weights = problem.style_weights.clone();
                if let (Some(weight), Some(last)) = (problem.structure_weight, weights.last_mut()) {
                    *last = if levels > 1 { weight * level as f32 / (levels - 1) as f32 } else { 0.0 };
                }
                weights
            })
            .collect();
        Self {
            problem,
            params,
            streams: SeedStreams::new(params.seed),
            levels,
            source_size: (problem.style.width(), problem.style.height()),
            style: Pyramid::new(problem.style, levels),
            source_guides: problem.source_guides.iter().map(|&g| Pyramid::new(g, levels)).collect(),
            target_guides: problem.target_guides.iter().map(|&g| Pyramid::new(g, levels)).collect(),
            keep: problem.mask.map(|mask| Pyramid::new(&mask.keep, levels)),
            holes: problem
                .mask
                .map(|mask| (0..levels).map(|level| hole_at(&mask.hole, problem.target_size, level)).collect()),
            style_weights,
            local: (0..levels).map(|level| is_local(problem, params, levels, level)).collect(),
            native: is_native(problem, params),
        }
    }

    /// The images, weights and labels of pyramid level `level` with patches of side `patch`.
    fn spec(&self, level: usize, patch: usize) -> LevelSpec<'_, '_, I> {
        let (problem, source_size) = (self.problem, self.source_size);
        let target_size = level_size(problem.target_size, level);
        let inpainting = problem.mask.filter(|mask| mask.exclude_hole_from_style).and(self.holes.as_ref());
        let (source_labels, target_labels, label_count) = match (&problem.labels, inpainting) {
            // Inpainting: the source is the target image; patches touching its hole form a
            // second segment that no target patch may match.
            (_, Some(holes)) => {
                let touched = dilate(&holes[level], target_size.0, target_size.1, patch / 2);
                let source = touched.iter().map(|&t| u16::from(t)).collect();
                (Some(Cow::Owned(source)), Some(Cow::Owned(vec![0; target_size.0 * target_size.1])), 2)
            }
            // The finest level's labels are the run's own (borrowed, not copied).
            (Some((source, target, count)), None) => (
                Some(match level {
                    0 => Cow::Borrowed(&source[..]),
                    _ => {
                        let size = level_size(source_size, level);
                        Cow::Owned(segments::decimate(source, source_size.0, source_size.1, size, level))
                    }
                }),
                Some(match level {
                    0 => Cow::Borrowed(&target[..]),
                    _ => Cow::Owned(segments::decimate(
                        target,
                        problem.target_size.0,
                        problem.target_size.1,
                        target_size,
                        level,
                    )),
                }),
                *count,
            ),
            (None, None) => (None, None, 0),
        };
        LevelSpec {
            patch,
            style: self.style.level(level),
            style_weights: &self.style_weights[level],
            source_guides: self.source_guides.iter().map(|p| p.level(level)).collect(),
            target_guides: self.target_guides.iter().map(|p| p.level(level)).collect(),
            guide_weights: &problem.guide_weights,
            target_size,
            tileable: problem.tileable,
            source_labels,
            target_labels,
            label_count,
            // Prepared for the style itself: the finest level's.
            prepared: if level == 0 { problem.prepared } else { None },
        }
    }

    /// With [`Params::band_local_search`] on a band seeded from the textures' fields: the
    /// target's origin in the textures' plane, which keys the band's local search.
    fn local_band(&self) -> Option<(i64, i64)> {
        let seeded_band = self.problem.composition.is_some() && self.problem.seeds.is_some();
        (seeded_band && self.params.band_local_search).then_some(self.problem.origin)
    }

    /// Level `index` with patches of side `patch`, restricted to the band (§3.7) or the hole
    /// when there is one.
    fn level_of(&self, index: usize, patch: usize) -> Level<'_> {
        let mut level = Level::new(self.spec(index, patch));
        let seeded_band = self.problem.composition.is_some() && self.problem.seeds.is_some();
        if self.local[index] || (seeded_band && self.params.band_local_search) {
            level.search_radius = LOCAL_SEARCH_RADIUS;
        }
        if self.native {
            level.source_share_cap = Some(OCCURRENCE_SOURCE_SHARE);
        }
        let domain = match (&self.problem.composition, &self.holes) {
            (Some((_, domain)), _) => domain,
            (None, Some(holes)) => &holes[index],
            (None, None) => return level,
        };
        level.active = Some(dilate(domain, level.target_width, level.target_height, level.radius));
        level.domain = Some(domain.clone());
        level
    }

    /// One pyramid level of Algorithm 1: the field from `coarser` (or a seeded or random one at
    /// the coarsest level), the output's start from it, then N × (search, vote).
    fn level(
        &self,
        index: usize,
        coarser: Option<(Field, Level<'_>)>,
        image: &mut FloatImage,
        scratch: &mut Vec<u32>,
        progress: &mut dyn Progress,
    ) -> (Field, Level<'_>, LevelReport) {
        let (params, levels) = (self.params, self.levels);
        let level_start = Clock::now();
        let stage = format!("level {} of {}", levels - index, levels);
        progress.report(&stage, 0.0);
        let streams = self.streams.child("level", index as u64);
        let patch = patch_at_level(params, levels, index, self.source_size, self.problem.target_size);
        let mut level = self.level_of(index, patch);
        let mut field = match (coarser, &self.problem.seeds) {
            (None, Some(seeds)) => Field::seeded(&level, seeds, &streams, self.local_band()),
            (None, None) => Field::random(&level, &streams),
            (Some((coarse, coarse_level)), _) => Field::upsample(&coarse, &coarse_level, &level, &streams),
        };
        self.start_image(&level, index, &field, image);
        level.set_target_style(image, false);
        // A level that refines upsampled matches searches a few pixels around each: no patch can
        // gather many target patches, and Ω over the whole exemplar would cost what it saves.
        let mut occurrence = Occurrence::new(&level, if self.local[index] { 0.0 } else { params.uniformity });
        let mut searcher = Searcher { params, streams: &streams, scratch, local_band: self.local_band() };
        let mut energies = Vec::with_capacity(params.search_vote_iterations);
        let mut converged: Option<Vec<bool>> = None;
        for iteration in 0..params.search_vote_iterations {
            field.recompute_costs(&level);
            // From the second iteration on, Ω was refreshed after the last search and the field has
            // not moved since (voting changes only the target).
            let current = iteration > 0;
            searcher.search(&level, &mut field, &mut occurrence, iteration, converged.as_deref(), current);
            occurrence.refresh(&level, &field.matches);
            energies.push(field.mean_energy(&level, &occurrence));
            let changed = vote(&level, &field, image, true, params.stop_threshold);
            // The last iteration's converged patches, and its target, would serve no further
            // search; the final figures read the target.
            let more = iteration + 1 < params.search_vote_iterations;
            if more || params.final_figures {
                level.set_target_style(image, true);
            }
            converged = (params.stop_threshold > 0.0 && more).then(|| converged_patches(&level, &changed));
            progress.report(&stage, (iteration + 1) as f64 / params.search_vote_iterations as f64);
        }
        let ms = motif_core::timing::elapsed_ms(level_start);
        let (width, height) = (level.target_width, level.target_height);
        let local_search = self.local[index];
        let report = LevelReport { name: stage, width, height, patch_size: patch, local_search, energies, ms };
        (field, level, report)
    }

    /// The output at the start of level `index` into `image`: the composed textures in band mode
    /// (already there: [`run`] moved them in), else the vote of the starting field (over the kept
    /// pixels of this level when there is a mask).
    fn start_image(&self, level: &Level, index: usize, field: &Field, image: &mut FloatImage) {
        *image = match (&self.problem.composition, &self.keep) {
            (Some(_), _) => return,
            (None, Some(keep)) => {
                // The kept pixels of this level; the hole from the field (random or upsampled).
                let mut fresh = keep.level(index).to_float_image().into_owned();
                vote(level, field, &mut fresh, false, 0.0);
                fresh
            }
            (None, None) => {
                let mut fresh = FloatImage::new(level.target_width, level.target_height, level.style_channels);
                vote(level, field, &mut fresh, false, 0.0);
                fresh
            }
        };
    }

    /// The optional final pass with 3×3 patches at the finest level, without the occurrence
    /// penalty; `finest` is dropped before its replacement is stacked.
    fn extra_pass(
        &self,
        field: &mut Field,
        finest: Level<'_>,
        image: &mut FloatImage,
        scratch: &mut Vec<u32>,
        progress: &mut dyn Progress,
    ) -> (Level<'_>, LevelReport) {
        let pass_start = Clock::now();
        let stage = "extra 3×3 pass".to_string();
        progress.report(&stage, 0.0);
        drop(finest);
        let mut fine = self.level_of(0, 3);
        fine.set_target_style(image, false);
        let mut occurrence = Occurrence::new(&fine, 0.0);
        field.recompute_costs(&fine);
        let streams = self.streams.child("extra pass", 0);
        let mut searcher = Searcher { params: self.params, streams: &streams, scratch, local_band: None };
        searcher.search(&fine, field, &mut occurrence, 0, None, false);
        let energies = vec![field.mean_energy(&fine, &occurrence)];
        vote(&fine, field, image, true, 0.0);
        fine.set_target_style(image, true);
        let ms = motif_core::timing::elapsed_ms(pass_start);
        let (width, height) = (fine.target_width, fine.target_height);
        progress.report(&stage, 1.0);
        let local_search = self.local[0];
        (fine, LevelReport { name: stage, width, height, patch_size: 3, local_search, energies, ms })
    }
}

/// Patches none of whose pixels `changed` (by the stop threshold, in the last vote).
fn converged_patches(level: &Level, changed: &[bool]) -> Vec<bool> {
    dilate(changed, level.target_width, level.target_height, level.radius).into_iter().map(|c| !c).collect()
}

/// What the searches of one level share: the parameters, the level's random streams and the
/// workers' scratch space.
struct Searcher<'s> {
    params: &'s Params,
    streams: &'s SeedStreams,
    scratch: &'s mut Vec<u32>,
    /// The band's local search, at this origin in the textures' plane (see [`Em::local_band`]).
    local_band: Option<(i64, i64)>,
}

impl Searcher<'_> {
    /// One search: K PatchMatch iterations (Ω refreshed before each) or one exact pass.
    /// `omega_current`: Ω already matches the field (its refresh before the first iteration is skipped).
    fn search(
        &mut self,
        level: &Level,
        field: &mut Field,
        occurrence: &mut Occurrence,
        iteration: usize,
        converged: Option<&[bool]>,
        omega_current: bool,
    ) {
        let params = self.params;
        match (params.nnf, self.local_band) {
            (NnfMethod::PatchMatch, Some(origin)) => {
                for k in 0..params.patchmatch_iterations {
                    occurrence.refresh(level, &field.matches);
                    let key = (iteration * params.patchmatch_iterations + k) as u64;
                    let streams = self.streams.child("local search", key);
                    local_band_iteration(level, field, self.scratch, occurrence, &streams, (origin, converged));
                }
            }
            (NnfMethod::PatchMatch, None) => {
                for k in 0..params.patchmatch_iterations {
                    if k > 0 || !omega_current {
                        occurrence.refresh(level, &field.matches);
                    }
                    let key = (iteration * params.patchmatch_iterations + k) as u64;
                    let streams = self.streams.child("search", key);
                    patchmatch_iteration(level, field, self.scratch, occurrence, &streams, k, converged);
                }
            }
            (NnfMethod::Exact, _) => {
                if !omega_current {
                    occurrence.refresh(level, &field.matches);
                }
                exact_search(level, field, occurrence);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::dilate;

    /// The sliding-count dilation against the definition, on masks of every density and
    /// radii from none to wider than the image.
    #[test]
    fn dilation_matches_brute_force() {
        let mut state = 7_u64;
        for (width, height) in [(1, 1), (1, 9), (9, 1), (13, 7), (20, 20)] {
            for density in [0, 10, 50, 90] {
                let mask: Vec<bool> = (0..width * height)
                    .map(|_| {
                        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
                        (state >> 33) % 100 < density
                    })
                    .collect();
                for radius in 0..5 {
                    let expected: Vec<bool> = (0..width * height)
                        .map(|i| {
                            let (x, y) = ((i % width) as i64, (i / width) as i64);
                            (0..width * height).any(|j| {
                                let (u, v) = ((j % width) as i64, (j / width) as i64);
                                mask[j] && (u - x).abs() <= radius as i64 && (v - y).abs() <= radius as i64
                            })
                        })
                        .collect();
                    assert_eq!(dilate(&mask, width, height, radius), expected, "{width}×{height} r{radius}");
                }
            }
        }
    }
}
