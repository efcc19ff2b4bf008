//! What a finished run hands back besides its image: the figures of its final field (the energy
//! and its parts, the source coverage, the error map), the field itself in public form, and the
//! output of a band with nothing to optimize.

use motif_core::FloatImage;
use motif_core::timing::Clock;

use crate::field::NearestNeighbourField;
use crate::level::Level;
use crate::occurrence::Occurrence;
use crate::search::Field;
use crate::vote::weight_code;
use crate::{EnergyParts, Output, Params, Report};

/// Figures of the output itself: its final patch distances and the penalty of its field.
pub(crate) struct Figures {
    pub energy: EnergyParts,
    pub source_coverage: f64,
    /// Per-pixel energy of the final field (0 outside the band or hole).
    pub error_map: FloatImage,
    /// Target patches optimized.
    pub searched: usize,
    /// The weights the final vote gave each patch.
    pub vote_weights: Vec<u16>,
}

impl Figures {
    /// `local`: the finest level refined upsampled matches, without the occurrence penalty.
    /// `band_only`: the band's local search searched the band's own pixels only (not the patches
    /// around it), and the figures are of those.
    pub(crate) fn new(field: &mut Field, level: &Level, params: &Params, local: bool, band_only: bool) -> Self {
        let searched = |t: usize| if band_only { level.in_domain(t) } else { level.is_active(t) };
        // The weights the final vote gave each patch, before the costs are recomputed for the figures.
        let area = (level.patch * level.patch) as f32;
        let vote_weights = field.costs.iter().map(|&cost| weight_code(cost, area)).collect();
        let final_lambda = if params.extra_pass_3x3 || local { 0.0 } else { params.uniformity };
        let mut occurrence = Occurrence::new(level, final_lambda);
        occurrence.refresh(level, &field.matches);
        // One pass: the costs recomputed against the final image, and the energy's parts.
        let energy = energy_parts(level, field, &occurrence, &searched);
        let mut error_map = FloatImage::new(level.target_width, level.target_height, 1);
        for (t, value) in error_map.data_mut().iter_mut().enumerate() {
            if searched(t) {
                *value = field.costs[t] + occurrence.snapshot_cost(field.matches[t]);
            }
        }
        Self {
            energy,
            source_coverage: Occurrence::coverage(level, &field.matches),
            error_map,
            searched: (0..level.target_len()).filter(|&t| searched(t)).count(),
            vote_weights,
        }
    }
}

/// The public field of the final level, with the final vote's weights. It is the largest buffer
/// made at the end: the level's stacks and the costs are freed first.
pub(crate) fn public_field(field: Field, mut level: Level, vote_weights: Vec<u16>) -> NearestNeighbourField {
    let (width, height, source_width, source_height, patch_size) =
        (level.target_width, level.target_height, level.source_width, level.source_height, level.patch);
    let active = level.active.take();
    drop(level);
    let Field { matches, costs } = field;
    drop(costs);
    NearestNeighbourField {
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
    }
}

/// The output of a band with no pixels: the composed textures, no field, zero energy.
pub(crate) fn composition_only(
    composed: &FloatImage,
    source_size: (usize, usize),
    patch: usize,
    start: Clock,
) -> Output {
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

/// The output of a run without its final figures (`Params::final_figures` off): the image, an
/// empty field and error map, a zero energy, the levels' reports and times.
pub(crate) fn image_only(
    image: FloatImage,
    source_size: (usize, usize),
    patch: usize,
    (levels, timer, start): (Vec<crate::LevelReport>, motif_core::timing::StageTimer, Clock),
    searched_pixels: usize,
) -> Output {
    let mut output = composition_only(&FloatImage::new(0, 0, 1), source_size, patch, start);
    output.image = image;
    output.report.levels = levels;
    output.report.stages_ms = timer.finish();
    output.report.total_ms = motif_core::timing::elapsed_ms(start);
    output.report.searched_pixels = searched_pixels;
    output
}

/// Mean per searched pixel of the style distance, guide distance and penalty; recomputes every
/// searched pixel's cost on the way (as [`Field::recompute_costs`] does, to the same values).
fn energy_parts(
    level: &Level,
    field: &mut Field,
    occurrence: &Occurrence,
    searched: &(impl Fn(usize) -> bool + Sync),
) -> EnergyParts {
    use rayon::prelude::*;
    let width = level.target_width;
    let matches = &field.matches;
    let rows: Vec<(f64, f64, f64, usize)> = field
        .costs
        .par_chunks_mut(width)
        .enumerate()
        .map(|(y, costs)| {
            let (mut style, mut guide, mut penalty, mut count) = (0.0_f64, 0.0_f64, 0.0_f64, 0usize);
            for (x, cost) in costs.iter_mut().enumerate() {
                let t = y * width + x;
                if !searched(t) {
                    *cost = 0.0;
                    continue;
                }
                let (s, g, total) = level.distance_parts(matches[t], x, y);
                *cost = total;
                style += f64::from(s);
                guide += f64::from(g);
                penalty += f64::from(occurrence.snapshot_cost(matches[t]));
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
