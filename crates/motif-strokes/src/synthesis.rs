//! Pattern synthesis (§3.2, Algorithm 1): seed layout on the target, then element-by-element
//! growth outward from the centre, each element taken from a reference neighbourhood that matches
//! its known neighbours.

use kurbo::Vec2;
use motif_core::random::Rng;
use motif_core::{Point, Polygon, Polyline, Progress, SeedStreams};
use motif_core::{math, vector};
use rayon::prelude::*;

use crate::analysis::Analysis;
use crate::distribution::{Graph, RingScratch, unskewed_delaunay};
use crate::matching::{CompareScratch, MeasureTable, Member, compare, violation};
use crate::seeds::{Density, lloyd_path, lloyd_region};

/// Seed positions on the target and their neighbour graph.
#[derive(Debug, Clone)]
pub(crate) struct Layout {
    /// Seed positions in document coordinates.
    pub positions: Vec<Point>,
    /// Angle by which a reference element is turned at each seed: the path tangent's angle minus
    /// the reference's main direction (1D), 0 (2D).
    pub rotations: Vec<f64>,
    /// Seed coordinates in the pattern frame: `(arc length, 0)` along a path, the position in a
    /// region. Neighbourhood offsets are differences of these.
    pub coords: Vec<Point>,
    /// Arc length of a closed path (offsets along x wrap), `None` otherwise.
    pub period: Option<f64>,
    /// The chain (1D) or unskewed Delaunay graph (2D) of the seeds.
    pub graph: Graph,
    /// Lloyd iterations run.
    pub lloyd_iterations: usize,
}

impl Layout {
    /// Offset of seed `to` from seed `from` in the pattern frame.
    pub(crate) fn offset(&self, from: usize, to: usize) -> Vec2 {
        let mut d = self.coords[to] - self.coords[from];
        if let Some(period) = self.period {
            d.x -= period * (d.x / period).round();
        }
        d
    }

    /// Number of seeds.
    pub(crate) fn len(&self) -> usize {
        self.positions.len()
    }

    /// True without seeds.
    pub(crate) fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }
}

/// Seeds along `path` (1D): Lloyd along the arc length, a chain graph, rotations from the path
/// tangent averaged over one spacing (so that a finely flattened curve does not jitter them).
pub(crate) fn layout_path(
    path: &Polyline,
    count: usize,
    frame_angle: f64,
    iterations: usize,
    streams: &SeedStreams,
) -> Layout {
    let length = path.length();
    let (arc, run) = lloyd_path(length, path.is_closed(), count, iterations, streams);
    let half = 0.5 * length / count.max(1) as f64;
    let positions: Vec<Point> = arc.iter().map(|&s| path.point_at(s)).collect();
    let rotations = arc
        .iter()
        .map(|&s| {
            let chord = path.point_at(s + half) - path.point_at(s - half);
            let tangent = if vector::length(chord) > 1e-12 { chord } else { path.tangent_at(s) };
            math::atan2(tangent.y, tangent.x) - frame_angle
        })
        .collect();
    Layout {
        positions,
        rotations,
        coords: arc.iter().map(|&s| Point::new(s, 0.0)).collect(),
        period: path.is_closed().then_some(length),
        graph: Graph::chain(count, path.is_closed()),
        lloyd_iterations: run,
    }
}

/// Seeds inside `region` (2D): clipped centroidal Voronoi by Lloyd, unskewed Delaunay graph.
pub(crate) fn layout_region(
    region: &Polygon,
    count: usize,
    iterations: usize,
    density: &Density<'_>,
    streams: &SeedStreams,
) -> Layout {
    let (positions, run) = lloyd_region(region, count, iterations, density, streams);
    let graph = unskewed_delaunay(&positions).graph;
    Layout {
        rotations: vec![0.0; positions.len()],
        coords: positions.clone(),
        positions,
        period: None,
        graph,
        lloyd_iterations: run,
    }
}

/// Each reference element's k-ring neighbourhood with offsets in the pattern frame.
#[derive(Debug, Clone)]
pub(crate) struct ReferenceRings {
    starts: Vec<usize>,
    members: Vec<Member>,
}

impl ReferenceRings {
    /// The k-rings of every reference element.
    pub(crate) fn new(analysis: &Analysis, rings: usize) -> ReferenceRings {
        let mut scratch = RingScratch::default();
        let mut ring = Vec::new();
        let mut starts = vec![0];
        let mut members = Vec::new();
        for i in 0..analysis.elements.len() {
            analysis.graph.ring(i, rings, &mut scratch, &mut ring);
            let here = analysis.pattern_position(i);
            members.extend(
                ring.iter().map(|&j| Member { element: j, offset: analysis.pattern_position(j as usize) - here }),
            );
            starts.push(members.len());
        }
        ReferenceRings { starts, members }
    }

    /// The neighbourhood of reference element `i`.
    pub(crate) fn get(&self, i: usize) -> &[Member] {
        &self.members[self.starts[i]..self.starts[i + 1]]
    }

    /// Total number of members over all neighbourhoods.
    pub(crate) fn member_count(&self) -> usize {
        self.members.len()
    }

    /// Number of reference elements.
    pub(crate) fn len(&self) -> usize {
        self.starts.len() - 1
    }
}

/// Distance evaluations (reference members × known target neighbours) above which one seed's
/// candidate search runs in parallel.
const PARALLEL_WORK: usize = 200_000;

/// The result of growing a pattern over a layout.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Growth {
    /// Reference element copied to each seed.
    pub assigned: Vec<u32>,
    /// Whether each seed found at least one candidate within the thresholds (false: fell back to
    /// the best match).
    pub matched: Vec<bool>,
    /// Mean number of candidates per seed.
    pub mean_candidates: f64,
    /// The seed synthesis started from.
    pub centre: usize,
    /// Seeds in the order they were grown (by distance from the centre).
    pub order: Vec<usize>,
}

/// The seed nearest to the middle of the target: the middle of an open path, the first seed of a
/// closed one, the seed nearest the centroid of a region's seeds.
fn centre_seed(layout: &Layout) -> usize {
    if layout.period.is_some() || layout.is_empty() {
        return 0;
    }
    let mean = layout.coords.iter().fold(Vec2::ZERO, |s, p| s + p.to_vec2()) / layout.len() as f64;
    (0..layout.len())
        .min_by(|&a, &b| {
            (layout.coords[a].to_vec2() - mean).hypot2().total_cmp(&(layout.coords[b].to_vec2() - mean).hypot2())
        })
        .unwrap_or(0)
}

/// Reusable buffers for scoring one seed against every reference neighbourhood.
#[derive(Default)]
pub(crate) struct SeedScratch {
    ring: RingScratch,
    members: Vec<u32>,
    known: Vec<Member>,
    compare: CompareScratch,
    /// Per reference element: how far its neighbourhood is from passing the test (below 1 passes).
    pub violations: Vec<f64>,
}

/// Scores every reference neighbourhood against the elements already assigned around `seed`
/// (those not `u32::MAX`), into `scratch.violations`. Returns false when no neighbour is known yet.
pub(crate) fn score_seed(
    layout: &Layout,
    seed: usize,
    rings: usize,
    assigned: &[u32],
    reference: &ReferenceRings,
    table: &MeasureTable,
    scratch: &mut SeedScratch,
) -> bool {
    layout.graph.ring(seed, rings, &mut scratch.ring, &mut scratch.members);
    scratch.known.clear();
    scratch.known.extend(
        scratch
            .members
            .iter()
            .filter(|&&j| assigned[j as usize] != u32::MAX)
            .map(|&j| Member { element: assigned[j as usize], offset: layout.offset(seed, j as usize) }),
    );
    if scratch.known.is_empty() {
        return false;
    }
    let known = &scratch.known;
    let score = |compare_scratch: &mut CompareScratch, r: usize| {
        compare(reference.get(r), known, table, compare_scratch).map_or(f64::INFINITY, |m| violation(&m))
    };
    // Fanning out costs a few microseconds per task: worth it only for large neighbourhoods.
    if reference.member_count() * known.len() >= PARALLEL_WORK {
        (0..reference.len())
            .into_par_iter()
            .with_min_len(8)
            .map_init(CompareScratch::default, score)
            .collect_into_vec(&mut scratch.violations);
    } else {
        scratch.violations.clear();
        let compare_scratch = &mut scratch.compare;
        scratch.violations.extend((0..reference.len()).map(|r| score(compare_scratch, r)));
    }
    true
}

/// Grows the pattern outward from the centre seed (seeds in order of distance from it), picking
/// for each seed a random reference element among those whose k-ring matches the seed's known
/// neighbours, or the best match when none does (§3.1, §3.2). Only `usable` reference elements
/// are copied (fragments cut by the reference's frame are not).
pub(crate) fn grow(
    layout: &Layout,
    rings: usize,
    reference: &ReferenceRings,
    table: &MeasureTable,
    usable: &[bool],
    streams: &SeedStreams,
    progress: &mut dyn Progress,
) -> Growth {
    let count = layout.len();
    let centre = centre_seed(layout);
    let mut order: Vec<usize> = (0..count).collect();
    let distance: Vec<f64> = (0..count).map(|i| layout.offset(centre, i).hypot2()).collect();
    order.sort_by(|&a, &b| distance[a].total_cmp(&distance[b]).then(a.cmp(&b)));
    let mut assigned = vec![u32::MAX; count];
    let mut matched = vec![false; count];
    let mut scratch = SeedScratch::default();
    let mut candidates: Vec<u32> = Vec::with_capacity(reference.len());
    let mut total_candidates = 0usize;
    let report_every = (count / 64).max(1);
    let usable_elements = || (0..reference.len() as u32).filter(|&r| usable[r as usize]);
    for (step, &seed) in order.iter().enumerate() {
        if step % report_every == 0 {
            progress.report("match", step as f64 / count as f64);
        }
        let mut stream = streams.stream("pick", seed as u64);
        candidates.clear();
        let scored = score_seed(layout, seed, rings, &assigned, reference, table, &mut scratch);
        if !scored {
            // Nothing to match yet (the centre element): every usable reference element is a candidate.
            candidates.extend(usable_elements());
        } else {
            candidates.extend(usable_elements().filter(|&r| scratch.violations[r as usize] < 1.0));
        }
        total_candidates += candidates.len();
        let choice = if candidates.is_empty() {
            usable_elements()
                .min_by(|&a, &b| scratch.violations[a as usize].total_cmp(&scratch.violations[b as usize]))
                .unwrap_or(0)
        } else {
            matched[seed] = true;
            candidates[stream.random_range(0..candidates.len())]
        };
        assigned[seed] = choice;
    }
    progress.report("match", 1.0);
    Growth { assigned, matched, mean_candidates: total_candidates as f64 / count.max(1) as f64, centre, order }
}
