//! Placing the chosen reference elements on their seeds, and keeping them from overlapping.
//!
//! The seed layout spaces seeds evenly, but reference elements differ in size, position variation
//! moves seeds towards their neighbours and parameter exchange turns and stretches elements, so two
//! neighbours can end up with their ink crossing, which the reference never shows (its clustering
//! merges any strokes closer than ε). Elements are settled in growth order; one that meets an
//! already settled element tries, in turn: its seed's own position (undoing position variation),
//! its element unchanged (undoing the exchange), other reference elements whose neighbourhood
//! passes the test there, small moves away from the elements it meets (in a region), and is
//! removed when none of these clears it. When the reference's own elements overlap, the output
//! keeps overlaps up to the reference's rate.

use kurbo::{Affine, Vec2};
use motif_core::random::Rng;
use motif_core::{Point, SeedStreams, math, vector};
use rayon::prelude::*;
use serde::Serialize;

use crate::Target;
use crate::analysis::Analysis;
use crate::element::OrientedBox;
use crate::matching::MeasureTable;
use crate::overlap::{Footprint, FootprintIndex, bounds_centre};
use crate::stroke::Stroke;
use crate::synthesis::{Layout, ReferenceRings, SeedScratch, score_seed};
use crate::variation::Exchange;

/// Where and how one reference element is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Placement {
    /// The reference element copied.
    pub reference: u32,
    /// Where its centre goes.
    pub position: Point,
    /// Its rotation about its centre (path tangent plus exchanged orientation).
    pub rotation: f64,
    /// The parameter exchange applied.
    pub exchange: Exchange,
    /// Uniform scale about its centre, stroke widths and dashes included (the scale map's).
    pub scale: f64,
}

/// How overlaps between placed elements were resolved.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct OverlapFigures {
    /// Whether overlaps were resolved (`avoid_overlaps`).
    pub avoided: bool,
    /// Share of the reference's usable elements whose ink meets another element's.
    pub reference_rate: f64,
    /// Share of the output elements whose ink meets another's, after resolution.
    pub output_rate: f64,
    /// Elements that met a settled neighbour when first placed and were not tolerated (the
    /// reference's own rate lets some overlaps stand).
    pub met_when_placed: usize,
    /// Cleared by going back to the seed's own position (undoing position variation).
    pub cleared_by_seed_position: usize,
    /// Cleared by undoing the parameter exchange.
    pub cleared_by_unchanged_element: usize,
    /// Cleared by another reference element that passes the neighbourhood test there.
    pub cleared_by_other_element: usize,
    /// Cleared by a small move away from the elements met.
    pub cleared_by_move: usize,
    /// Removed: nothing cleared them.
    pub removed: usize,
}

/// The map taking a reference element's strokes to a seed: scale in the element's own frame
/// (exchanged length and thickness), rotate about its centre, move the centre to `position`.
pub(crate) fn placement_transform(frame: &OrientedBox, position: Point, rotation: f64, exchange: &Exchange) -> Affine {
    let to_origin = Affine::translate(-frame.centre.to_vec2());
    let axis_angle = math::atan2(frame.axis.y, frame.axis.x);
    let scale = if exchange.length_scale != 1.0 || exchange.thickness_scale != 1.0 {
        vector::rotation(axis_angle)
            * Affine::scale_non_uniform(exchange.length_scale, exchange.thickness_scale)
            * vector::rotation(-axis_angle)
    } else {
        Affine::IDENTITY
    };
    Affine::translate(position.to_vec2()) * vector::rotation(rotation) * scale * to_origin
}

/// Scaling by `scale` about `centre` (the identity at 1).
fn uniform_scale_about(centre: Point, scale: f64) -> Affine {
    if scale == 1.0 {
        Affine::IDENTITY
    } else {
        Affine::translate(centre.to_vec2()) * Affine::scale(scale) * Affine::translate(-centre.to_vec2())
    }
}

fn shift_colour(colour: [u8; 4], shift: [f64; 3]) -> [u8; 4] {
    let mut out = colour;
    for c in 0..3 {
        out[c] = (f64::from(colour[c]) + 255.0 * shift[c]).round().clamp(0.0, 255.0) as u8;
    }
    out
}

/// The strokes of reference element `placement.reference` drawn at `placement`.
pub(crate) fn placed_strokes(analysis: &Analysis, strokes: &[Stroke], placement: &Placement) -> Vec<Stroke> {
    let element = &analysis.elements[placement.reference as usize];
    let exchange = &placement.exchange;
    let transform = placement_transform(&element.frame, placement.position, placement.rotation, exchange)
        * uniform_scale_about(element.frame.centre, placement.scale);
    element
        .strokes
        .iter()
        .map(|&s| {
            let mut stroke = strokes[s].transformed(transform);
            if placement.scale != 1.0 {
                stroke.width *= placement.scale;
                if let Some(dash) = &mut stroke.dash {
                    dash.iter_mut().for_each(|length| *length *= placement.scale);
                }
            }
            if exchange.colour_shift != [0.0; 3] {
                stroke.colour = shift_colour(stroke.colour, exchange.colour_shift);
                stroke.fill = stroke.fill.map(|fill| shift_colour(fill, exchange.colour_shift));
            }
            stroke
        })
        .collect()
}

/// The share of the reference's usable elements whose ink meets another element's.
pub(crate) fn reference_overlap_rate(analysis: &Analysis, strokes: &[Stroke]) -> f64 {
    let footprints: Vec<Footprint> = analysis
        .elements
        .iter()
        .map(|element| Footprint::of_strokes(element.strokes.iter().map(|&s| &strokes[s])))
        .collect();
    let index = FootprintIndex::new(&footprints);
    let usable: Vec<usize> = (0..footprints.len()).filter(|&i| analysis.is_usable(i)).collect();
    let meeting = usable
        .iter()
        .filter(|&&i| index.near(&footprints[i]).into_iter().any(|j| j != i && footprints[i].overlaps(&footprints[j])))
        .count();
    if usable.is_empty() { 0.0 } else { meeting as f64 / usable.len() as f64 }
}

/// Everything overlap resolution reads.
pub(crate) struct Scene<'a> {
    /// The analysed reference.
    pub analysis: &'a Analysis,
    /// The reference strokes.
    pub strokes: &'a [Stroke],
    /// The target.
    pub target: &'a Target,
    /// The seed layout.
    pub layout: &'a Layout,
    /// Neighbourhood rings.
    pub rings: usize,
    /// The reference neighbourhoods.
    pub reference: &'a ReferenceRings,
    /// The pair measures.
    pub table: &'a MeasureTable,
    /// Random streams of the run.
    pub streams: &'a SeedStreams,
}

/// Other reference elements tried per element that meets a neighbour.
const OTHER_ELEMENTS_TRIED: usize = 24;

/// Moves tried away from the elements met, in units of the seed spacing.
const MOVES: [f64; 3] = [0.1, 0.2, 0.3];

/// Settles `placements` (one per seed, `assigned` their reference elements) in growth `order`
/// so that no element's ink meets an already settled one, beyond the reference's own rate. Returns
/// which seeds are kept and the figures.
pub(crate) fn resolve_overlaps(
    scene: &Scene<'_>,
    placements: &mut [Placement],
    assigned: &mut [u32],
    matched: &mut [bool],
    order: &[usize],
) -> (Vec<bool>, OverlapFigures) {
    let analysis = scene.analysis;
    let reference_rate = reference_overlap_rate(analysis, scene.strokes);
    let mut figures = OverlapFigures { avoided: true, reference_rate, ..OverlapFigures::default() };
    let mut footprints: Vec<Footprint> =
        placements.par_iter().map(|placement| footprint_of(scene, placement)).collect();
    let mut kept = vec![false; placements.len()];
    let mut index = FootprintIndex::empty();
    let mut settled = 0usize;
    // Settled elements whose ink meets another settled element's (both sides of each overlap).
    let mut overlapping = vec![false; placements.len()];
    let mut overlapping_count = 0usize;
    let spacing = if analysis.along_path { analysis.area_per_element } else { analysis.area_per_element.sqrt() };
    let mut scratch = SeedScratch::default();
    for &seed in order {
        let met = meets(&footprints[seed], &index, &footprints);
        let newly = 1 + met.iter().filter(|&&j| !overlapping[j]).count();
        let tolerated =
            reference_rate > 0.0 && ((overlapping_count + newly) as f64) <= reference_rate * (settled + 1) as f64;
        if met.is_empty() || tolerated {
            if !met.is_empty() {
                overlapping_count += newly;
                overlapping[seed] = true;
                met.iter().for_each(|&j| overlapping[j] = true);
            }
            settled += 1;
            kept[seed] = true;
            index.insert(seed, &footprints[seed]);
            continue;
        }
        figures.met_when_placed += 1;
        let clearing = Clearing { scene, index: &index, footprints: &footprints, spacing };
        match clearing.clear(seed, placements[seed], &met, assigned, &mut scratch) {
            Some((placement, footprint, way)) => {
                match way {
                    0 => figures.cleared_by_seed_position += 1,
                    1 => figures.cleared_by_unchanged_element += 1,
                    2 => {
                        // The replacement passed the neighbourhood test.
                        figures.cleared_by_other_element += 1;
                        matched[seed] = true;
                    }
                    _ => figures.cleared_by_move += 1,
                }
                placements[seed] = placement;
                assigned[seed] = placement.reference;
                footprints[seed] = footprint;
                settled += 1;
                kept[seed] = true;
                index.insert(seed, &footprints[seed]);
            }
            None => {
                figures.removed += 1;
                assigned[seed] = u32::MAX;
            }
        }
    }
    // Without tolerated overlaps every kept element was checked against every element kept
    // before it, and later ones against it: no pair meets.
    if overlapping_count > 0 {
        let kept_footprints: Vec<Footprint> =
            footprints.into_iter().zip(&kept).filter(|(_, k)| **k).map(|(f, _)| f).collect();
        figures.output_rate = crate::overlap::overlap_rate(&kept_footprints);
    }
    (kept, figures)
}

/// The ink footprint of a placed element.
fn footprint_of(scene: &Scene<'_>, placement: &Placement) -> Footprint {
    Footprint::of_strokes(&placed_strokes(scene.analysis, scene.strokes, placement))
}

/// The settled elements whose ink meets `footprint`.
fn meets(footprint: &Footprint, index: &FootprintIndex, footprints: &[Footprint]) -> Vec<usize> {
    index.near(footprint).into_iter().filter(|&j| footprint.overlaps(&footprints[j])).collect()
}

/// A placement that meets no settled element, its footprint, and how it was found (0: the seed's
/// own position, 1: the unchanged element, 2: another reference element, 3: a move away).
type Cleared = (Placement, Footprint, usize);

/// What clearing one seed's overlap reads: the scene and the elements settled so far.
struct Clearing<'a, 's> {
    scene: &'a Scene<'s>,
    index: &'a FootprintIndex,
    footprints: &'a [Footprint],
    /// The seed spacing, in drawing units.
    spacing: f64,
}

impl Clearing<'_, '_> {
    /// `placement` with its footprint, if it meets no settled element.
    fn if_clear(&self, placement: Placement, way: usize) -> Option<Cleared> {
        let footprint = footprint_of(self.scene, &placement);
        meets(&footprint, self.index, self.footprints).is_empty().then_some((placement, footprint, way))
    }

    /// The first clear placement of `seed` among: its own seed position, the element unchanged,
    /// other reference elements that pass the neighbourhood test, and moves away from the elements
    /// met (in a region).
    fn clear(
        &self,
        seed: usize,
        original: Placement,
        met: &[usize],
        assigned: &[u32],
        scratch: &mut SeedScratch,
    ) -> Option<Cleared> {
        let scene = self.scene;
        let own_position = scene.layout.positions[seed];
        let own_rotation = scene.layout.rotations[seed];
        let mut tries: Vec<(Placement, usize)> = Vec::new();
        if original.position != own_position {
            tries.push((Placement { position: own_position, ..original }, 0));
        }
        let unchanged =
            Placement { position: own_position, rotation: own_rotation, exchange: Exchange::default(), ..original };
        if original.exchange != Exchange::default() {
            tries.push((unchanged, 1));
        }
        if let Some(cleared) = tries.into_iter().find_map(|(placement, way)| self.if_clear(placement, way)) {
            return Some(cleared);
        }
        if score_seed(scene.layout, seed, scene.rings, assigned, scene.reference, scene.table, scratch)
            && let Some(cleared) = self.by_other_element(seed, unchanged, scratch)
        {
            return Some(cleared);
        }
        self.by_move(seed, unchanged, met)
    }

    /// Up to [`OTHER_ELEMENTS_TRIED`] other usable reference elements that pass the neighbourhood
    /// test (scored in `scratch`), in random order.
    fn by_other_element(&self, seed: usize, unchanged: Placement, scratch: &SeedScratch) -> Option<Cleared> {
        let analysis = self.scene.analysis;
        let mut others: Vec<u32> = (0..self.scene.reference.len() as u32)
            .filter(|&r| {
                r != unchanged.reference && analysis.is_usable(r as usize) && scratch.violations[r as usize] < 1.0
            })
            .collect();
        let mut stream = self.scene.streams.stream("overlap", seed as u64);
        // A partial Fisher–Yates shuffle: the first few in random order.
        let tried = others.len().min(OTHER_ELEMENTS_TRIED);
        for i in 0..tried {
            let j = stream.random_range(i..others.len());
            others.swap(i, j);
        }
        others[..tried].iter().find_map(|&other| self.if_clear(Placement { reference: other, ..unchanged }, 2))
    }

    /// The unchanged element moved away from the elements met, in steps of [`MOVES`], while it
    /// stays in the region (regions only).
    fn by_move(&self, seed: usize, unchanged: Placement, met: &[usize]) -> Option<Cleared> {
        let Target::Region(region) = self.scene.target else { return None };
        let here = bounds_centre(&self.footprints[seed]);
        let away = met.iter().fold(Vec2::ZERO, |sum, &j| {
            let d = here - bounds_centre(&self.footprints[j]);
            let length = vector::length(d);
            if length > 1e-12 { sum + d / length } else { sum }
        });
        if vector::length(away) > 1e-12 {
            let direction = vector::normalized(away);
            for step in MOVES {
                let position = unchanged.position + direction * (step * self.spacing);
                if !region.contains(position) {
                    break;
                }
                if let Some(cleared) = self.if_clear(Placement { position, ..unchanged }, 3) {
                    return Some(cleared);
                }
            }
        }
        None
    }
}
