//! Multi-resolution EM (Algorithm 1, §3.5): coarse to fine, N × (search, vote) per level, the
//! field upsampled between levels; optionally a final 3×3 pass; the report figures.

use motif_core::timing::Clock;
use motif_core::{ChannelImage, FloatImage, Progress, SeedStreams, StageTimer};

use crate::field::NearestNeighbourField;
use crate::level::{Level, LevelSpec};
use crate::occurrence::Occurrence;
use crate::search::{Field, exact_search, patchmatch_iteration};
use crate::vote::{vote, weight_code};
use crate::{EnergyParts, Error, LevelReport, NnfMethod, Output, Params, Report, segments};

/// A validated problem in the engine's terms (built by the public entry points).
pub(crate) struct Problem<'a, I: ChannelImage = FloatImage> {
    pub style: &'a I,
    /// One image per guide (none without guides), each with its own channels.
    pub source_guides: Vec<&'a I>,
    pub target_guides: Vec<&'a I>,
    pub style_weights: Vec<f32>,
    pub guide_weights: Vec<f32>,
    pub target_size: (usize, usize),
    /// Source labels, target labels, label count.
    pub labels: Option<(Vec<u16>, Vec<u16>, usize)>,
    pub tileable: bool,
    /// Band mode (§3.7): the composed image and the band of pixels to optimize.
    pub composition: Option<(FloatImage, Vec<bool>)>,
    /// Band mode: the starting source centre of every target pixel, from the textures' fields
    /// ([`crate::band::NO_SEED`] = none).
    pub seeds: Option<Vec<u32>>,
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
fn level_size(size: (usize, usize), level: usize) -> (usize, usize) {
    (0..level).fold(size, |(w, h), _| (w.div_ceil(2), h.div_ceil(2)))
}

/// Dilates a mask by `radius` (Chebyshev): the patch centres whose patch touches the mask.
pub(crate) fn dilate(mask: &[bool], width: usize, height: usize, radius: usize) -> Vec<bool> {
    let mut horizontal = vec![false; mask.len()];
    for y in 0..height {
        for x in 0..width {
            if mask[y * width + x] {
                for xx in x.saturating_sub(radius)..(x + radius + 1).min(width) {
                    horizontal[y * width + xx] = true;
                }
            }
        }
    }
    let mut out = vec![false; mask.len()];
    for y in 0..height {
        for x in 0..width {
            if horizontal[y * width + x] {
                for yy in y.saturating_sub(radius)..(y + radius + 1).min(height) {
                    out[yy * width + x] = true;
                }
            }
        }
    }
    out
}

/// Runs the whole optimization.
pub(crate) fn run<I: ChannelImage>(
    problem: &Problem<'_, I>,
    params: &Params,
    progress: &mut dyn Progress,
) -> Result<Output, Error> {
    let start = Clock::now();
    // A band that starts from the textures' fields is nearly converged: fewer iterations (§3.7).
    let seeded_band = problem.composition.is_some() && problem.seeds.is_some();
    let mut params = params.clone();
    if seeded_band {
        params.search_vote_iterations = params.band_search_vote_iterations;
        params.patchmatch_iterations = params.band_patchmatch_iterations;
    }
    let params = &params;
    let mut timer = StageTimer::new();
    let patch = params.patch_size;
    let streams = SeedStreams::new(params.seed);
    let source_size = (problem.style.width(), problem.style.height());
    let levels = if problem.composition.is_some() || problem.seeds.is_some() {
        // Band mode optimizes a thin band at full resolution only (§3.7); a quilted start is
        // already laid out at full resolution.
        1
    } else {
        let fit = fitting_levels(&[source_size, problem.target_size], 2 * patch + 1);
        if params.pyramid_levels == 0 { fit } else { params.pyramid_levels.min(fit) }
    };
    if let Some((composed, domain)) = &problem.composition
        && !domain.iter().any(|&inside| inside)
    {
        // Band 0 (or a single segment): the pure bitmap composition of §3.7, nothing to optimize.
        return Ok(composition_only(composed, source_size, patch, start));
    }
    // Pyramids hold the coarser levels only; level 0 is the problem's own image (no copy of the
    // largest images: the stacked guides are the biggest buffers of a run).
    let style_pyramid = Pyramid::new(problem.style, levels);
    let source_guide_pyramids: Vec<Pyramid<'_, I>> =
        problem.source_guides.iter().map(|&g| Pyramid::new(g, levels)).collect();
    let target_guide_pyramids: Vec<Pyramid<'_, I>> =
        problem.target_guides.iter().map(|&g| Pyramid::new(g, levels)).collect();
    let keep_pyramid = problem.mask.map(|mask| Pyramid::new(&mask.keep, levels));
    let holes: Option<Vec<Vec<bool>>> =
        problem.mask.map(|mask| (0..levels).map(|level| hole_at(&mask.hole, problem.target_size, level)).collect());
    // Per level, the style channels' weights (they differ only with structure guidance).
    let level_style_weights: Vec<Vec<f32>> = (0..levels)
        .map(|level| {
            let mut weights = problem.style_weights.clone();
            if let (Some(weight), Some(last)) = (problem.structure_weight, weights.last_mut()) {
                *last = if levels > 1 { weight * level as f32 / (levels - 1) as f32 } else { 0.0 };
            }
            weights
        })
        .collect();
    let spec = |level: usize, patch: usize| -> LevelSpec<'_, '_, I> {
        let target_size = level_size(problem.target_size, level);
        let inpainting = problem.mask.filter(|mask| mask.exclude_hole_from_style).and(holes.as_ref());
        let (source_labels, target_labels, label_count) = match (&problem.labels, inpainting) {
            // Inpainting: the source is the target image; patches touching its hole form a
            // second segment that no target patch may match.
            (_, Some(holes)) => {
                let touched = dilate(&holes[level], target_size.0, target_size.1, patch / 2);
                let source = touched.iter().map(|&t| u16::from(t)).collect();
                (Some(source), Some(vec![0; target_size.0 * target_size.1]), 2)
            }
            (Some((source, target, count)), None) => (
                Some(segments::decimate(source, source_size.0, source_size.1, level_size(source_size, level), level)),
                Some(segments::decimate(target, problem.target_size.0, problem.target_size.1, target_size, level)),
                *count,
            ),
            (None, None) => (None, None, 0),
        };
        LevelSpec {
            patch,
            style: style_pyramid.level(level),
            style_weights: &level_style_weights[level],
            source_guides: source_guide_pyramids.iter().map(|p| p.level(level)).collect(),
            target_guides: target_guide_pyramids.iter().map(|p| p.level(level)).collect(),
            guide_weights: &problem.guide_weights,
            target_size,
            tileable: problem.tileable,
            source_labels,
            target_labels,
            label_count,
        }
    };
    let band = |level: &mut Level, index: usize| {
        let domain = match (&problem.composition, &holes) {
            (Some((_, domain)), _) => domain,
            (None, Some(holes)) => &holes[index],
            (None, None) => return,
        };
        level.active = Some(dilate(domain, level.target_width, level.target_height, level.radius));
        level.domain = Some(domain.clone());
    };

    let mut reports = Vec::with_capacity(levels + 1);
    let mut previous: Option<(Field, Level)> = None;
    let mut image = FloatImage::new(0, 0, 1);
    let mut scratch = Vec::new();
    for level_index in (0..levels).rev() {
        let level_start = Clock::now();
        let stage = format!("level {} of {}", levels - level_index, levels);
        progress.report(&stage, 0.0);
        let level_streams = streams.child("level", level_index as u64);
        let level_patch = patch_at_level(params, levels, level_index, source_size, problem.target_size);
        let mut level = Level::new(spec(level_index, level_patch));
        band(&mut level, level_index);
        // The coarser level is dropped once its field is upsampled.
        let mut field = match (previous.take(), &problem.seeds) {
            (None, Some(seeds)) => Field::seeded(&level, seeds, &level_streams),
            (None, None) => Field::random(&level, &level_streams),
            (Some((coarse, coarse_level)), _) => Field::upsample(&coarse, &coarse_level, &level, &level_streams),
        };
        image = match (&problem.composition, &keep_pyramid) {
            (Some((composed, _)), _) => composed.clone(),
            (None, Some(keep)) => {
                // The kept pixels of this level; the hole from the field (random or upsampled).
                let mut fresh = keep.level(level_index).to_float_image().into_owned();
                vote(&level, &field, &mut fresh, false, 0.0);
                fresh
            }
            (None, None) => {
                let mut fresh = FloatImage::new(level.target_width, level.target_height, level.style_channels);
                vote(&level, &field, &mut fresh, false, 0.0);
                fresh
            }
        };
        level.set_target_style(&image, false);
        let mut occurrence = Occurrence::new(&level, params.uniformity);
        let mut energies = Vec::with_capacity(params.search_vote_iterations);
        let mut converged: Option<Vec<bool>> = None;
        for iteration in 0..params.search_vote_iterations {
            field.recompute_costs(&level);
            let mask = converged.as_deref();
            // From the second iteration on, Ω was refreshed after the last search and the field has
            // not moved since (voting changes only the target).
            let current = iteration > 0;
            search(&level, &mut field, &mut occurrence, &mut scratch, params, &level_streams, iteration, mask, current);
            occurrence.refresh(&level, &field.matches);
            energies.push(field.mean_energy(&level, &occurrence));
            let changed = vote(&level, &field, &mut image, true, params.stop_threshold);
            level.set_target_style(&image, true);
            converged = (params.stop_threshold > 0.0).then(|| converged_patches(&level, &changed));
            progress.report(&stage, (iteration + 1) as f64 / params.search_vote_iterations as f64);
        }
        let ms = motif_core::timing::elapsed_ms(level_start);
        timer.add(&stage, ms);
        reports.push(LevelReport {
            name: stage,
            width: level.target_width,
            height: level.target_height,
            patch_size: level_patch,
            energies,
            ms,
        });
        previous = Some((field, level));
    }
    let (mut field, mut level) = previous.expect("at least one level");

    if params.extra_pass_3x3 {
        let pass_start = Clock::now();
        let stage = "extra 3×3 pass".to_string();
        progress.report(&stage, 0.0);
        drop(level);
        let mut fine = Level::new(spec(0, 3));
        band(&mut fine, 0);
        fine.set_target_style(&image, false);
        let mut occurrence = Occurrence::new(&fine, 0.0);
        field.recompute_costs(&fine);
        let pass_streams = streams.child("extra pass", 0);
        search(&fine, &mut field, &mut occurrence, &mut scratch, params, &pass_streams, 0, None, false);
        let energies = vec![field.mean_energy(&fine, &occurrence)];
        vote(&fine, &field, &mut image, true, 0.0);
        fine.set_target_style(&image, true);
        let ms = motif_core::timing::elapsed_ms(pass_start);
        timer.add(&stage, ms);
        reports.push(LevelReport {
            name: stage.clone(),
            width: fine.target_width,
            height: fine.target_height,
            patch_size: 3,
            energies,
            ms,
        });
        progress.report(&stage, 1.0);
        level = fine;
    }

    // The weights the final vote gave each patch, before the costs are recomputed for the figures.
    let area = (level.patch * level.patch) as f32;
    let vote_weights = field.costs.iter().map(|&cost| weight_code(cost, area)).collect();
    // Figures of the output itself: its final patch distances and the penalty of its field.
    field.recompute_costs(&level);
    let final_lambda = if params.extra_pass_3x3 { 0.0 } else { params.uniformity };
    let mut occurrence = Occurrence::new(&level, final_lambda);
    occurrence.refresh(&level, &field.matches);
    let energy = energy_parts(&level, &field, &occurrence);
    let source_coverage = Occurrence::coverage(&level, &field.matches);
    let mut error_map = FloatImage::new(level.target_width, level.target_height, 1);
    for (t, value) in error_map.data_mut().iter_mut().enumerate() {
        if level.is_active(t) {
            *value = field.costs[t] + occurrence.snapshot_cost(field.matches[t]);
        }
    }
    let searched = level.active.as_ref().map_or(level.target_len(), |a| a.iter().filter(|&&b| b).count());
    // The public field is the largest buffer made at the end: the level's stacks, the costs and
    // the occurrence counts are freed first.
    let (width, height, source_width, source_height, patch_size) =
        (level.target_width, level.target_height, level.source_width, level.source_height, level.patch);
    let active = level.active.take();
    drop((level, occurrence));
    let Field { matches, costs } = field;
    drop(costs);
    let nnf = NearestNeighbourField {
        width,
        height,
        source_width,
        source_height,
        patch_size,
        matches: matches
            .iter()
            .enumerate()
            .map(|(t, &s)| {
                active.as_ref().is_none_or(|active| active[t]).then(|| {
                    let s = s as usize;
                    [(s % source_width) as u32, (s / source_width) as u32]
                })
            })
            .collect(),
        weights: Some(vote_weights),
    };
    Ok(Output {
        image,
        field: nnf,
        error_map,
        report: Report {
            energy,
            source_coverage,
            levels: reports,
            stages_ms: timer.finish(),
            total_ms: motif_core::timing::elapsed_ms(start),
            searched_pixels: searched,
            estimated_memory_bytes: 0,
        },
    })
}

/// Patches none of whose pixels `changed` (by the stop threshold, in the last vote).
fn converged_patches(level: &Level, changed: &[bool]) -> Vec<bool> {
    dilate(changed, level.target_width, level.target_height, level.radius).into_iter().map(|c| !c).collect()
}

/// The output of a band with no pixels: the composed textures, no field, zero energy.
fn composition_only(composed: &FloatImage, source_size: (usize, usize), patch: usize, start: Clock) -> Output {
    let (width, height) = (composed.width(), composed.height());
    let total_ms = motif_core::timing::elapsed_ms(start);
    Output {
        image: composed.clone(),
        field: NearestNeighbourField {
            width,
            height,
            source_width: source_size.0,
            source_height: source_size.1,
            patch_size: patch,
            matches: vec![None; width * height],
            weights: None,
        },
        error_map: FloatImage::new(width, height, 1),
        report: Report {
            energy: EnergyParts { total: 0.0, style: 0.0, guide: 0.0, occurrence: 0.0 },
            source_coverage: 0.0,
            levels: Vec::new(),
            stages_ms: vec![("composition".to_string(), total_ms)],
            total_ms,
            searched_pixels: 0,
            estimated_memory_bytes: 0,
        },
    }
}

/// One search: K PatchMatch iterations (Ω refreshed before each) or one exact pass.
/// `omega_current`: Ω already matches the field (its refresh before the first iteration is skipped).
#[allow(
    clippy::too_many_arguments,
    reason = "the search step's state is borrowed apart (field mutable, level shared) inside the EM loop"
)]
fn search(
    level: &Level,
    field: &mut Field,
    occurrence: &mut Occurrence,
    scratch: &mut Vec<u32>,
    params: &Params,
    streams: &SeedStreams,
    iteration: usize,
    converged: Option<&[bool]>,
    omega_current: bool,
) {
    match params.nnf {
        NnfMethod::PatchMatch => {
            for k in 0..params.patchmatch_iterations {
                if k > 0 || !omega_current {
                    occurrence.refresh(level, &field.matches);
                }
                let key = (iteration * params.patchmatch_iterations + k) as u64;
                patchmatch_iteration(level, field, scratch, occurrence, &streams.child("search", key), k, converged);
            }
        }
        NnfMethod::Exact => {
            if !omega_current {
                occurrence.refresh(level, &field.matches);
            }
            exact_search(level, field, occurrence);
        }
    }
}

/// Mean per searched pixel of the style distance, guide distance and penalty.
fn energy_parts(level: &Level, field: &Field, occurrence: &Occurrence) -> EnergyParts {
    use rayon::prelude::*;
    let rows: Vec<(f64, f64, f64, usize)> = (0..level.target_height)
        .into_par_iter()
        .map(|y| {
            let (mut style, mut guide, mut penalty, mut count) = (0.0_f64, 0.0_f64, 0.0_f64, 0usize);
            for x in 0..level.target_width {
                let t = y * level.target_width + x;
                if !level.is_active(t) {
                    continue;
                }
                let (s, g) = level.distance_parts(field.matches[t], x, y);
                style += f64::from(s);
                guide += f64::from(g);
                penalty += f64::from(occurrence.snapshot_cost(field.matches[t]));
                count += 1;
            }
            (style, guide, penalty, count)
        })
        .collect();
    let (style, guide, penalty, count) =
        rows.iter().fold((0.0, 0.0, 0.0, 0), |a, r| (a.0 + r.0, a.1 + r.1, a.2 + r.2, a.3 + r.3));
    let n = count.max(1) as f64;
    EnergyParts { total: (style + guide + penalty) / n, style: style / n, guide: guide / n, occurrence: penalty / n }
}
