//! Stroke pattern analysis and synthesis, after Barla, Breslav, Thollot, Sillion and Markosian,
//! "Stroke Pattern Analysis and Synthesis" (Eurographics 2006).
//!
//! A reference drawing (vector strokes with widths and colours) is analysed into perceptual
//! elements and their distribution, then a similar pattern is synthesized along a target path (1D)
//! or inside a target region (2D). Modules, by section of the paper:
//!
//! - `stroke`: strokes as polylines with width, colours and dash pattern (§1).
//! - `attributes`: stroke width, opacity, fill and dash of an element, compared beside colour
//!   (beyond the paper, which compares colour only).
//! - `element`: oriented bounding boxes from the covariance of skeleton or contour points, and
//!   box Hausdorff distances (§2.1).
//! - `cluster`: the greedy clustering queue with the proximity and continuation tests (§2.2).
//! - `scale`: ε inferred from the reference when none is given ([`infer_scale`]; the paper has
//!   the user choose it): the widest gap between the heights at which strokes join under §2.2.
//! - `distribution`: chain and unskewed-Delaunay neighbour graphs, k-rings, shift vectors (§2.3).
//! - `analysis`: the whole analysis of a reference (§2).
//! - `border`: elements touching the reference's frame, not copied when enough lie inside (pieces
//!   a crop cut through).
//! - `matching`: relevant pairs, the five perceptual measures (parallelism weighted by how
//!   elongated the boxes are) and the attribute measure, and the threshold test (§3.1).
//! - `seeds`: Lloyd relaxation along a path and clipped centroidal Voronoi in a polygon (§3.2),
//!   weighted by a density map (the paper's future work, §5).
//! - `maps`: density and scale maps from grey images.
//! - `synthesis`: seed layout and outward growth with partial neighbourhoods (§3.2, Algorithm 1).
//! - `variation`: parameter exchange and position variation (§3.3).
//! - `overlap` and `placement`: element footprints (through `geo`) and the settling of placed
//!   elements so that their ink does not meet beyond the reference's overlap rate.
//! - [`fidelity`]: size, spacing, orientation and overlap figures of a pattern against its
//!   reference, with tiled and random baselines (public: benches and tests use it).
//! - [`samples`]: generated reference drawings for demos, benchmarks and tests (public, like
//!   `fidelity`; everything else is re-exported flat below).
//!
//! The entry point is [`synthesize`]; [`analyse`] runs the analysis alone (for interactive tuning
//! of ε), [`infer_scale`] proposes ε. The crate does no I/O and builds for `wasm32`.
//!
//! ```
//! use motif_core::{NoProgress, Point, Polyline};
//! use motif_strokes::samples::{HatchRow, hatch_row};
//! use motif_strokes::{Input, Params, Target, synthesize};
//!
//! // A reference row of 12 hatches, each of three sketchy strokes, continued along a longer line.
//! let row = HatchRow { count: 12, ..HatchRow::default() };
//! let strokes = hatch_row(&row, Point::new(10.0, 30.0), |i| 0.05 * i as f64, |_| [20, 20, 20, 255], 1);
//! let path = Polyline::new(vec![Point::new(0.0, 0.0), Point::new(400.0, 0.0)], false).unwrap();
//! let params = Params::default().with_scale(6.0).with_seed(3);
//! params.validate().unwrap();
//! let output = synthesize(&Input::new(strokes, Target::Path(path)), &params, &mut NoProgress).unwrap();
//! // Clustering finds the 12 hatches; the line holds about 400 / 8 of them.
//! assert_eq!(output.report.reference_elements, 12);
//! assert!((output.report.output_elements as f64 - 50.0).abs() <= 3.0);
//! assert_eq!(output.report.output_strokes, 3 * output.report.output_elements);
//! ```

mod analysis;
mod attributes;
mod border;
mod cluster;
mod distribution;
mod element;
mod error;
pub mod fidelity;
mod maps;
mod matching;
mod overlap;
mod params;
mod placement;
pub mod samples;
mod scale;
mod seeds;
mod stroke;
mod synthesis;
mod variation;

use motif_core::vector;
use std::ops::Range;

use kurbo::Vec2;
use motif_core::{Point, Polygon, Polyline, Progress, SeedStreams, StageTimer};
use serde::Serialize;

pub use analysis::{Analysis, analyse};
pub use attributes::{Appearance, Attributes};
pub use cluster::{ClusteringComparison, Element, compare_clustering, merge_height};
pub use element::OrientedBox;
pub use error::{Error, InputError, LimitError};
pub use motif_core::ToneMap;
pub use params::{FitPoints, Params, Thresholds};
pub use placement::OverlapFigures;
pub use scale::{InferredScale, MIN_ELEMENTS, NEIGHBOURS, ScaleMethod, TOUCHING_FRACTION, infer_scale, merge_heights};
pub use stroke::Stroke;
pub use variation::Exchange;

use maps::Maps;
use matching::{Limits, MeasureTable};
use placement::{Placement, Scene, placed_strokes, resolve_overlaps};
use seeds::Density;
use synthesis::{Growth, Layout, ReferenceRings, grow, layout_path, layout_region};

/// Where to synthesize.
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    /// Along a path (a 1D pattern): elements are placed along it and turned with its tangent.
    Path(Polyline),
    /// Inside a simple polygon (a 2D pattern).
    Region(Polygon),
}

/// What [`synthesize`] works on.
#[derive(Debug, Clone, PartialEq)]
pub struct Input {
    /// The reference strokes, in drawing order (clustering follows it).
    pub strokes: Vec<Stroke>,
    /// The target path or region, in the same units as the strokes.
    pub target: Target,
    /// Element density relative to the reference's, stretched over a region target's bounding
    /// box: darkness `1 − grey` (black: the reference's density, white: none). See [`ToneMap`].
    pub density_map: Option<ToneMap>,
    /// Element scale `2^(2·grey − 1)` (black 0.5, mid-grey 1, white 2) over a region target's
    /// bounding box; larger elements are spaced further apart.
    pub scale_map: Option<ToneMap>,
}

impl Input {
    /// Uniform synthesis of `strokes` on `target` (no maps).
    pub fn new(strokes: Vec<Stroke>, target: Target) -> Input {
        Input { strokes, target, density_map: None, scale_map: None }
    }
}

/// One synthesized element.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthesizedElement {
    /// The reference element it copies (index into [`Analysis::elements`]).
    pub reference: usize,
    /// Where the reference element's centre was placed.
    pub position: Point,
    /// Rotation applied to the reference strokes about their element centre, radians (the path
    /// tangent in 1D, plus the exchanged orientation).
    pub rotation: f64,
    /// Uniform scale from the scale map (1 without one), widths and dashes included.
    pub scale: f64,
    /// False when no reference neighbourhood passed the thresholds and the best match was taken.
    pub matched: bool,
    /// The parameter exchange applied (identity without variation).
    pub exchange: Exchange,
    /// Its strokes in [`Output::strokes`].
    pub strokes: Range<usize>,
}

/// Figures of a run, for reports.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Strokes in the reference.
    pub reference_strokes: usize,
    /// The run's estimated peak memory, bytes (checked against `max-memory` before allocating).
    pub estimated_memory_bytes: u64,

    /// Elements found in the reference.
    pub reference_elements: usize,
    /// Reference elements whose ink touches the reference's bounding box.
    pub border_elements: usize,
    /// Border elements not copied (they may be pieces cut by the frame; enough lie inside).
    pub fragment_elements: usize,
    /// Elements synthesized (N_tar).
    pub output_elements: usize,
    /// Strokes written.
    pub output_strokes: usize,
    /// N_ref · A_tar / A_ref before rounding, times the mean relative density of the maps.
    pub expected_elements: f64,
    /// Output elements that found at least one candidate within the thresholds.
    pub matched_elements: usize,
    /// Output elements that fell back to the best match.
    pub fallback_elements: usize,
    /// matched_elements / output_elements.
    pub candidate_fraction: f64,
    /// Mean number of candidate reference neighbourhoods per output element.
    pub mean_candidates: f64,
    /// Neighbourhood rings used.
    pub rings: usize,
    /// Lloyd iterations run.
    pub lloyd_iterations: usize,
    /// Reference Delaunay triangles dropped by the unskewed filter (2D).
    pub skewed_triangles_removed: usize,
    /// Overlaps between elements: the reference's rate, the output's, and how they were resolved.
    pub overlap: OverlapFigures,
    /// Milliseconds per stage, in order.
    pub stages_ms: Vec<(String, f64)>,
}

/// Everything a synthesis produces.
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    /// The synthesized strokes, element by element.
    pub strokes: Vec<Stroke>,
    /// The synthesized elements, one per seed.
    pub elements: Vec<SynthesizedElement>,
    /// Edges of the target neighbour graph (between indices of `elements`).
    pub target_edges: Vec<(usize, usize)>,
    /// The reference analysis.
    pub analysis: Analysis,
    /// Figures of the run.
    pub report: Report,
}

/// Checks the input geometry.
fn validate(input: &Input, params: &Params) -> Result<(), Error> {
    params.validate()?;
    if input.strokes.is_empty() {
        return Err(Error::Input(InputError::NoStrokes));
    }
    if let Target::Region(region) = &input.target
        && !region.is_simple()
    {
        return Err(Error::Input(InputError::SelfIntersectingRegion));
    }
    for (name, map) in [("density-map", &input.density_map), ("scale-map", &input.scale_map)] {
        let Some(map) = map else { continue };
        match &input.target {
            Target::Path(_) => {
                return Err(motif_core::InvalidParameter::new(
                    name,
                    "given with a path target",
                    "a region target: maps are stretched over the region's bounding box",
                )
                .into());
            }
            Target::Region(region) => map.check_fits(&region.bounds(), name)?,
        }
    }
    Ok(())
}

/// Builds a target region from outline points, telling a self-intersecting outline (even one
/// whose signed area cancels out, like a symmetric bow tie) apart from a degenerate one.
pub fn region_from_outline(points: Vec<Point>) -> Result<Polygon, Error> {
    match Polygon::new(points.clone()) {
        Ok(region) if region.is_simple() => Ok(region),
        Ok(_) => Err(Error::Input(InputError::SelfIntersectingRegion)),
        Err(error) => {
            let mut kept: Vec<Point> = Vec::with_capacity(points.len());
            for p in points {
                if kept.last().is_none_or(|last: &Point| vector::distance(*last, p) > 1e-9) {
                    kept.push(p);
                }
            }
            if kept.len() > 1 && vector::distance(kept[0], kept[kept.len() - 1]) <= 1e-9 {
                kept.pop();
            }
            let crossing = motif_core::geometry::outline_crosses_itself(&kept);
            if crossing { Err(Error::Input(InputError::SelfIntersectingRegion)) } else { Err(error.into()) }
        }
    }
}

/// The most neighbourhood comparisons a synthesis may make: each output element is compared with
/// every reference element's neighbourhood (all of them, since the match is drawn among every
/// one that passes), so matching grows with outputs × reference elements; 2·10⁸ take about five
/// minutes.
pub const MAX_COMPARISONS: f64 = 2e8;

/// Seconds one neighbourhood comparison takes, about (measured at two rings: 3.3 million in 4.7 s).
const SECONDS_PER_COMPARISON: f64 = 1.5e-6;

/// Refuses a synthesis whose matching would pass [`MAX_COMPARISONS`], with its estimated time.
fn check_matching_cost(outputs: usize, references: usize) -> Result<(), Error> {
    let comparisons = outputs as f64 * references as f64;
    if comparisons <= MAX_COMPARISONS {
        return Ok(());
    }
    Err(Error::Limit(LimitError::TooMuchMatching {
        outputs,
        references,
        minutes: comparisons * SECONDS_PER_COMPARISON / 60.0,
        limit_minutes: MAX_COMPARISONS * SECONDS_PER_COMPARISON / 60.0,
    }))
}

const MEMORY_ADVICE: &str = "use a smaller target, a larger scale or a simpler reference";

/// The peak memory of a synthesis: the pair table of reference elements (when it is built), the
/// output strokes (each element's strokes copied with their points) and the layout and growth
/// state per output element.
fn memory_estimate(analysis: &Analysis, strokes: &[Stroke], count: usize) -> motif_core::MemoryEstimate {
    let elements = analysis.elements.len().max(1) as f64;
    let tabled = if analysis.elements.len() <= matching::MAX_TABLE_ELEMENTS { elements } else { 0.0 };
    let points: usize = strokes.iter().map(|stroke| stroke.polyline.points().len()).sum();
    let count = count as f64;
    let mut estimate = motif_core::MemoryEstimate::new();
    estimate
        .add("pair table", tabled * tabled, std::mem::size_of::<matching::Normalized>() as f64)
        .add("output strokes", count * points as f64 / elements, 16.0)
        .add("output stroke records", count * strokes.len() as f64 / elements, 96.0)
        .add("layout and growth", count, 256.0)
        // Overlap footprints: every output point again as a line, twice for closed strokes, and
        // each element's placed strokes while it is tried.
        .add("overlap footprints", count * points as f64 / elements, 2.0 * 16.0 + 16.0)
        .add("footprint records", count * strokes.len() as f64 / elements, 2.0 * 64.0);
    estimate
}

/// Analyses the reference and synthesizes a similar pattern on the target (the paper's whole
/// pipeline, §2–§3).
pub fn synthesize(input: &Input, params: &Params, progress: &mut dyn Progress) -> Result<Output, Error> {
    validate(input, params)?;
    let streams = SeedStreams::new(params.seed);
    let along_path = matches!(input.target, Target::Path(_));
    let rings = params.rings_for(along_path);
    let mut timer = StageTimer::new();

    progress.report("analysis", 0.0);
    timer.start("fit");
    let sets = analysis::fit_sets(&input.strokes, params);
    timer.start("cluster");
    let elements = cluster::cluster(&input.strokes, &sets, params.scale);
    timer.start("distribution");
    let analysis = analysis::relate(elements, &input.strokes, params, along_path);
    progress.report("analysis", 1.0);

    timer.start("seeds");
    let seeding = seed_target(input, params, &analysis, &streams, progress)?;

    timer.start("match");
    let limits = Limits::new(&params.thresholds, analysis.mean_length);
    let frames: Vec<OrientedBox> = (0..analysis.elements.len()).map(|i| analysis.pattern_frame(i)).collect();
    let appearances: Vec<Appearance> = analysis.elements.iter().map(|e| e.appearance()).collect();
    let table = MeasureTable::new(&frames, &appearances, &limits);
    let reference_rings = ReferenceRings::new(&analysis, rings);
    let usable: Vec<bool> = (0..analysis.elements.len()).map(|i| analysis.is_usable(i)).collect();
    let mut growth = grow(&seeding.layout, rings, &reference_rings, &table, &usable, &streams, progress);

    timer.start("variation");
    let mut placements = place_elements(input, params, &analysis, &seeding, &growth, &limits, &streams);

    timer.start("overlaps");
    let layout = &seeding.layout;
    let (kept, overlap) = if params.avoid_overlaps {
        let scene = Scene {
            analysis: &analysis,
            strokes: &input.strokes,
            target: &input.target,
            layout,
            rings,
            reference: &reference_rings,
            table: &table,
            streams: &streams,
        };
        resolve_overlaps(&scene, &mut placements, &mut growth.assigned, &mut growth.matched, &growth.order)
    } else {
        (vec![true; layout.len()], OverlapFigures::default())
    };

    timer.start("output");
    let placed = PlacedOutput::of(&analysis, &input.strokes, &placements, &kept, &growth.matched);
    let overlap =
        if params.avoid_overlaps { overlap } else { placed.overlap_rates(overlap, &analysis, &input.strokes) };
    let target_edges = layout
        .graph
        .edges()
        .filter(|&(a, b)| kept[a] && kept[b])
        .map(|(a, b)| (placed.output_index[a], placed.output_index[b]))
        .collect();
    let stages_ms = timer.finish();
    let PlacedOutput { strokes, elements: synthesized, .. } = placed;
    let matched_elements = synthesized.iter().filter(|element| element.matched).count();
    let report = Report {
        estimated_memory_bytes: seeding.estimated_memory_bytes,
        reference_strokes: input.strokes.len(),
        reference_elements: analysis.elements.len(),
        border_elements: analysis.border.iter().filter(|&&b| b).count(),
        fragment_elements: analysis.fragments.iter().filter(|&&f| f).count(),
        output_elements: synthesized.len(),
        output_strokes: strokes.len(),
        expected_elements: seeding.expected,
        matched_elements,
        fallback_elements: synthesized.len() - matched_elements,
        candidate_fraction: matched_elements as f64 / synthesized.len().max(1) as f64,
        mean_candidates: growth.mean_candidates,
        rings,
        lloyd_iterations: layout.lloyd_iterations,
        skewed_triangles_removed: analysis.skewed_triangles,
        overlap,
        stages_ms,
    };
    Ok(Output { strokes, elements: synthesized, target_edges, analysis, report })
}

/// The seeds stage's result: the maps over the target, the element count it was sized for, and
/// the seed layout.
struct Seeding<'a> {
    maps: Maps<'a>,
    /// N_ref · A_tar / A_ref times the maps' mean relative density, before rounding.
    expected: f64,
    estimated_memory_bytes: u64,
    layout: Layout,
}

/// The seeds stage: sizes the output from the reference's density (refusing blank maps and
/// counts, matching or memory past their limits) and lays the seeds out on the target.
fn seed_target<'a>(
    input: &'a Input,
    params: &Params,
    analysis: &Analysis,
    streams: &SeedStreams,
    progress: &mut dyn Progress,
) -> Result<Seeding<'a>, Error> {
    let target_area = match &input.target {
        Target::Path(path) => path.length(),
        Target::Region(region) => region.area(),
    };
    let maps = Maps {
        density: input.density_map.as_ref(),
        scale: input.scale_map.as_ref(),
        bounds: match &input.target {
            Target::Region(region) => region.bounds(),
            Target::Path(_) => kurbo::Rect::ZERO,
        },
    };
    let uniform = Maps { density: None, scale: None, bounds: maps.bounds };
    let density = match &input.target {
        Target::Region(region) => Density::over(region, &maps),
        Target::Path(_) => Density::over_path(&uniform),
    };
    let expected = analysis.elements.len() as f64 * target_area / analysis.reference_area() * density.mean;
    if !maps.is_uniform() && expected < 0.5 {
        return Err(Error::Input(InputError::BlankDensityMap));
    }
    if !expected.is_finite() || expected > params.max_elements as f64 {
        return Err(Error::Limit(LimitError::TooManyElements {
            count: expected.min(usize::MAX as f64) as usize,
            limit: params.max_elements,
        }));
    }
    let count = (expected.round() as usize).max(1);
    check_matching_cost(count, analysis.elements.len())?;
    let estimated_memory_bytes =
        memory_estimate(analysis, &input.strokes, count).check(params.max_memory, MEMORY_ADVICE)?;
    progress.report("seeds", 0.0);
    let layout = match &input.target {
        Target::Path(path) => layout_path(path, count, analysis.frame_angle, params.lloyd_iterations, streams),
        Target::Region(region) => layout_region(region, count, params.lloyd_iterations, &density, streams),
    };
    progress.report("seeds", 1.0);
    Ok(Seeding { maps, expected, estimated_memory_bytes, layout })
}

/// The variation stage: each seed's matched element with its exchanged parameters, its position
/// (shifted with position variation) and its scale from the scale map.
fn place_elements(
    input: &Input,
    params: &Params,
    analysis: &Analysis,
    seeding: &Seeding,
    growth: &Growth,
    limits: &Limits,
    streams: &SeedStreams,
) -> Vec<Placement> {
    let layout = &seeding.layout;
    let exchanges = variation::exchange(&growth.assigned, analysis, limits, params.variation, streams);
    let positions = if params.position_variation {
        shifted_positions(layout, &growth.assigned, analysis, &input.target)
    } else {
        layout.positions.clone()
    };
    (0..layout.len())
        .map(|seed| Placement {
            reference: growth.assigned[seed],
            position: positions[seed],
            rotation: layout.rotations[seed] + exchanges[seed].rotation,
            exchange: exchanges[seed],
            scale: seeding.maps.scale_at(positions[seed]),
        })
        .collect()
}

/// The output stage: the kept placements' strokes, element by element.
struct PlacedOutput {
    strokes: Vec<Stroke>,
    elements: Vec<SynthesizedElement>,
    /// Each seed's index in `elements` (`usize::MAX` for seeds dropped by overlap resolution).
    output_index: Vec<usize>,
}

impl PlacedOutput {
    fn of(
        analysis: &Analysis,
        reference: &[Stroke],
        placements: &[Placement],
        kept: &[bool],
        matched: &[bool],
    ) -> PlacedOutput {
        let mut strokes = Vec::new();
        let mut elements = Vec::with_capacity(placements.len());
        let mut output_index = vec![usize::MAX; placements.len()];
        for (seed, placement) in placements.iter().enumerate() {
            if !kept[seed] {
                continue;
            }
            let start = strokes.len();
            strokes.extend(placed_strokes(analysis, reference, placement));
            output_index[seed] = elements.len();
            elements.push(SynthesizedElement {
                reference: placement.reference as usize,
                position: placement.position,
                rotation: placement.rotation,
                scale: placement.scale,
                matched: matched[seed],
                exchange: placement.exchange,
                strokes: start..strokes.len(),
            });
        }
        PlacedOutput { strokes, elements, output_index }
    }

    /// Overlap rates measured after the fact, when overlaps were not resolved.
    fn overlap_rates(&self, mut overlap: OverlapFigures, analysis: &Analysis, reference: &[Stroke]) -> OverlapFigures {
        overlap.reference_rate = placement::reference_overlap_rate(analysis, reference);
        let footprints: Vec<overlap::Footprint> = self
            .elements
            .iter()
            .map(|element| overlap::Footprint::of_strokes(&self.strokes[element.strokes.clone()]))
            .collect();
        overlap.output_rate = overlap::overlap_rate(&footprints);
        overlap
    }
}

/// Position variation mapped back to the document; positions that would leave a region stay.
fn shifted_positions(layout: &Layout, assigned: &[u32], analysis: &Analysis, target: &Target) -> Vec<Point> {
    let coords = variation::shifted_coords(layout, assigned, analysis);
    coords
        .iter()
        .enumerate()
        .map(|(i, moved)| {
            let Some(moved) = moved else { return layout.positions[i] };
            match target {
                Target::Path(path) => {
                    // x is arc length along the path, y the offset along its normal.
                    let s = moved.x;
                    let chord = path.point_at(s + 1e-3 * path.length()) - path.point_at(s - 1e-3 * path.length());
                    let tangent =
                        if vector::length(chord) > 1e-12 { vector::normalized(chord) } else { path.tangent_at(s) };
                    path.point_at(s) + Vec2::new(-tangent.y, tangent.x) * moved.y
                }
                Target::Region(region) => {
                    if region.contains(*moved) {
                        *moved
                    } else {
                        layout.positions[i]
                    }
                }
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matching_past_its_limit_is_refused_with_its_estimated_time() {
        assert!(check_matching_cost(5_000, 40_000).is_ok());
        // A reference of 113 k strokes (38 k elements) grown over a target as large.
        let error = check_matching_cost(38_000, 38_000).unwrap_err();
        let message = error.to_string();
        assert!(matches!(error, Error::Limit(LimitError::TooMuchMatching { .. })), "{message}");
        assert!(message.contains("about 36 minutes") && message.contains("38000 reference elements"), "{message}");
    }
}
