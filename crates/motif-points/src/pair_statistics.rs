//! Pair-statistics refinement: after the paper's optimization, the points near the seams between
//! copied patches (every point, from random initialization) move by gradient descent so that the
//! output's pair statistics follow the exemplar's measured ones, then jump one at a time where
//! that brings them closer (child module `relocation`, which forms clusters the small steps
//! cannot; not on surfaces), and a surplus over the exemplar's density is removed where that helps
//! them most (child module `thinning`).
//!
//! Roveri et al.'s energy T rewards windows that some exemplar window explains on average; it has
//! no term for the distribution of pair distances over the whole output, and on the real corpus
//! the seams kept pairs that the exemplar never shows (docs/points.md). The energy here is the one
//! synthesis by pair correlation uses (Öztireli and Gross 2012), against the exemplar's own
//! estimate rather than a smooth model of it, plus the nearest-neighbour distribution:
//! - **pair distances**: for each ring `b` of width `h` (0.1 spacing) up to 4 spacings, the pairs
//!   around centres deep enough for the ring, counted with kernels that share a distance between
//!   the two nearest ring centres (linear binning, so the count is differentiable), against the
//!   exemplar's count per centre times the output's centres and its density relative to the
//!   exemplar's (what makes the two g(r) equal); a chi-square `Σ (N_b − T_b)² / T_b`;
//! - **nearest neighbours**: each counted nearest-neighbour distance against the exemplar's at the
//!   same rank (the 1D optimal transport behind the Wasserstein distance the bench reports),
//!   `Σ ((d_i − q_i) / h)²`.
//!
//! Rings, depths (reduced-sample estimators) and ranks are those of `fidelity`, in units of the
//! exemplar's mean spacing. Points farther than 4 spacings from every seam keep the pairs they
//! were copied with; existing points and rigid elements keep their places; a move that would leave
//! the domain is not made; a step is kept only when it lowers the energy.

use motif_core::random::Stream;
use rayon::prelude::*;

use crate::domain::Region;
use crate::fidelity;
use crate::grid::StaticGrid;
use crate::linear::{self, Vector};
use crate::model::State;
use crate::setup::Setup;

/// Ring width, in spacings (the bench's ring).
const RING: f64 = 0.1;
/// Rings cover `[0, REACH)` spacings.
const REACH: f64 = 4.0;
/// Half-width of the ramp across a ring's edges, in spacings: half a ring makes each kernel a
/// triangle over its two neighbours' centres. Narrower ramps (a quarter, a tenth of a ring: closer
/// to hard rings but with fewer pairs feeling a gradient) left fewer corpus cases within 1.5× of
/// the tiled copy.
const RAMP: f64 = 0.5 * RING;
/// Points within this many spacings of a point the optimization moved move too: pairs across a
/// seam reach this far. 2, 3, 4, 6 and 8 were tried on the corpus (seeds 1–4); 4 was best.
const BAND: f64 = 4.0;
/// Weight of the nearest-neighbour term against the pair term.
const NEAREST_WEIGHT: f64 = 1.0;
/// First step, in spacings, of a point whose gradient is at least the mean.
const FIRST_STEP: f64 = 0.02;
/// The step grows after each kept step up to this.
const LARGEST_STEP: f64 = 0.1;
/// Relocation after the gradient steps (module `relocation`): at least 10 sweeps and 250 000
/// proposals. Measured on the corpus: docs/points.md, "Relocation".
const RELOCATION: relocation::Settings = relocation::Settings { sweeps: 10, proposals: 250_000, quantum: None };
/// A surplus over the expected count below this fraction of it is left alone.
const COUNT_SLACK: f64 = 0.01;

fn rings() -> usize {
    (REACH / RING).round() as usize
}

/// Rings whose kernel (of ramp half-width `ramp`) lies within `depth` spacings of the centre: ring
/// `b` reaches `(b + 1) h + ramp`.
fn usable_rings(depth: f64, ramp: f64) -> usize {
    if depth <= 0.0 { 0 } else { (((depth - ramp) / RING).floor().max(0.0) as usize).min(rings()) }
}

/// The kernel of ring `b` at distance `d` and its derivative: 1 inside the ring, ramps of half-width
/// `ramp` across its edges (neighbouring rings' kernels sum to 1), so a distance near an edge is
/// shared; a ramp of 0 makes hard rings `[b h, (b + 1) h)`.
fn kernel(b: usize, d: f64, ramp: f64) -> (f64, f64) {
    let e = ramp;
    let (low, high) = (b as f64 * RING, (b + 1) as f64 * RING);
    if e == 0.0 {
        return (f64::from(u8::from(low <= d && d < high)), 0.0);
    }
    let rise = (d - (low - e)) / (2.0 * e);
    let fall = ((high + e) - d) / (2.0 * e);
    if rise <= 0.0 || fall <= 0.0 {
        (0.0, 0.0)
    } else if rise < 1.0 {
        (rise, 1.0 / (2.0 * e))
    } else if fall < 1.0 {
        (fall, -1.0 / (2.0 * e))
    } else {
        (1.0, 0.0)
    }
}

/// The rings a distance `d` touches (kernels of ramp half-width `ramp`).
fn touched(d: f64, ramp: f64) -> std::ops::Range<usize> {
    let low = ((d - ramp) / RING).floor().max(0.0) as usize;
    let high = (((d + ramp) / RING).floor().max(0.0) as usize + 1).min(rings());
    low.min(high)..high
}

/// What the output is matched to: the exemplar's pairs per centre per ring and its sorted
/// nearest-neighbour distances, in spacings.
#[derive(Debug, Clone)]
pub(crate) struct Target {
    /// Half-width of the rings' ramps (`RAMP`, or 0 for hard rings).
    ramp: f64,
    per_centre: Vec<f64>,
    nearest: Vec<f64>,
    /// Points per unit volume, in spacings.
    density: f64,
}

impl Target {
    /// The exemplar's statistics: `points` and `depth` in spacings, `volume` its window's, pairs
    /// counted with ring kernels of ramp half-width `ramp`.
    pub(crate) fn new<const D: usize>(
        points: &[Vector<D>],
        depth: &dyn Fn(&Vector<D>) -> f64,
        volume: f64,
        ramp: f64,
    ) -> Self {
        let grid = StaticGrid::new(points, REACH + ramp);
        let mut sums = vec![0.0; rings()];
        let mut centres = vec![0usize; rings()];
        let mut nearest = Vec::new();
        for (i, p) in points.iter().enumerate() {
            let depth = depth(p);
            let usable = usable_rings(depth, ramp);
            let mut closest = f64::INFINITY;
            grid.for_each_within(p, REACH + ramp, |j, _, d2| {
                if j == i {
                    return;
                }
                let d = d2.sqrt();
                closest = closest.min(d);
                for b in touched(d, ramp).take_while(|&b| b < usable) {
                    sums[b] += kernel(b, d, ramp).0;
                }
            });
            centres[..usable].iter_mut().for_each(|c| *c += 1);
            if closest <= depth {
                nearest.push(closest);
            }
        }
        nearest.sort_by(f64::total_cmp);
        let per_centre =
            sums.iter().zip(&centres).map(|(s, &c)| if c == 0 { f64::NAN } else { s / c as f64 }).collect();
        Self { ramp, per_centre, nearest, density: points.len() as f64 / volume.max(1e-300) }
    }

    /// The pair count ring `b` asks for around `centres` usable centres of an output
    /// `density_ratio` times as dense as the exemplar (at least 1); `None` when the ring is not
    /// compared (no centre, or the exemplar cannot estimate it).
    fn wanted(&self, b: usize, centres: f64, density_ratio: f64) -> Option<f64> {
        let per_centre = self.per_centre[b];
        (centres > 0.0 && !per_centre.is_nan()).then(|| (centres * per_centre * density_ratio).max(1.0))
    }

    /// The exemplar's largest counted nearest-neighbour distance.
    fn farthest_nearest(&self) -> f64 {
        self.nearest.last().copied().unwrap_or(f64::INFINITY)
    }

    /// The exemplar's nearest-neighbour distance at quantile `q ∈ [0, 1]`.
    fn nearest_at(&self, q: f64) -> f64 {
        let n = self.nearest.len();
        let place = (q * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
        let low = place.floor() as usize;
        let high = (low + 1).min(n - 1);
        let t = place - low as f64;
        self.nearest[low] * (1.0 - t) + self.nearest[high] * t
    }
}

/// The output as the refinement sees it, in spacings.
pub(crate) struct Output<'a, const D: usize> {
    pub positions: &'a mut [Vector<D>],
    /// Which points may move.
    pub movable: &'a [bool],
    /// Distance to the domain's border (≤ 0 outside).
    pub depth: &'a (dyn Fn(&Vector<D>) -> f64 + Sync),
    /// Where a point may go.
    pub allowed: &'a (dyn Fn(&Vector<D>) -> bool + Sync),
    /// Brings a moved point back onto the domain (onto a surface; the identity elsewhere).
    pub settle: &'a (dyn Fn(&Vector<D>) -> Vector<D> + Sync),
    /// The domain's volume.
    pub volume: f64,
}

/// What the pair-statistics refinement did (in the report).
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct StatisticsRefinement {
    /// Points allowed to move: the optimization's movable points and the free points within 4
    /// spacings of them.
    pub movable_points: usize,
    /// Points removed from a surplus over the expected count.
    pub removed_points: usize,
    /// The energy (pair chi-square with ramped rings plus nearest-neighbour term) before the
    /// gradient steps.
    pub energy_before: f64,
    /// The energy after them.
    pub energy_after: f64,
    /// Relocations proposed after the gradient steps (Tscheschel and Stoyan's moves of one point
    /// to a new place).
    pub relocations_tried: usize,
    /// Relocations kept (they lowered the energy with hard rings).
    pub relocations_kept: usize,
    /// Sweeps of relocation run (a sweep proposes a move per movable point).
    pub relocation_sweeps: usize,
    /// The energy with hard rings (the bench's g(r) rings) before the relocations.
    pub relocation_energy_before: f64,
    /// The energy with hard rings after them.
    pub relocation_energy_after: f64,
    /// Gradient steps kept (they lowered the energy).
    pub steps_kept: usize,
    /// Gradient steps tried.
    pub steps_tried: usize,
}

/// One evaluation of the energy.
struct Evaluation<const D: usize> {
    energy: f64,
    /// `∂E/∂x` per point (zero for points that do not move; empty when not asked for).
    gradient: Vec<Vector<D>>,
    /// Per ring: the kernel-weighted pair count, the usable centres, the count the exemplar asks
    /// for, and the ring's weight `1 / T_b` (0 for a ring not compared).
    counts: Vec<f64>,
    centres: Vec<usize>,
    wanted: Vec<f64>,
    weights: Vec<f64>,
}

/// The energy of `positions` and, when `movable` is given, its gradient for those points.
fn evaluate<const D: usize>(
    target: &Target,
    positions: &[Vector<D>],
    depths: &[f64],
    density_ratio: f64,
    movable: Option<&[bool]>,
) -> Evaluation<D> {
    let bins = rings();
    let ramp = target.ramp;
    let reach = REACH + ramp;
    let usable: Vec<usize> = depths.iter().map(|&d| usable_rings(d, ramp)).collect();
    let pairs = Pairs { positions, grid: StaticGrid::new(positions, reach), reach, ramp, usable };
    let per_point = pairs.per_point();
    let mut counts = vec![0.0; bins];
    let mut centres = vec![0usize; bins];
    for (i, (own, _, _)) in per_point.iter().enumerate() {
        counts.iter_mut().zip(own).for_each(|(c, o)| *c += o);
        centres[..pairs.usable[i]].iter_mut().for_each(|c| *c += 1);
    }
    let mut energy = 0.0;
    let (mut wanted, mut weights, mut slopes) = (vec![0.0; bins], vec![0.0; bins], vec![0.0; bins]);
    for b in 0..bins {
        let Some(asked) = target.wanted(b, centres[b] as f64, density_ratio) else { continue };
        wanted[b] = asked;
        weights[b] = 1.0 / wanted[b];
        let excess = counts[b] - wanted[b];
        energy += excess * excess * weights[b];
        slopes[b] = 2.0 * excess * weights[b];
    }
    let nearest_pull = nearest_term(target, depths, &per_point, &mut energy);
    let Some(movable) = movable else {
        return Evaluation { energy, gradient: Vec::new(), counts, centres, wanted, weights };
    };
    let gradient = pairs.gradient(&per_point, &slopes, &nearest_pull, movable);
    Evaluation { energy, gradient, counts, centres, wanted, weights }
}

/// Per point: its ring counts (its usable rings), its nearest neighbour and that one's distance.
type PerPoint = Vec<(Vec<f64>, usize, f64)>;

/// The nearest-neighbour term: nearest neighbours counted when no farther than the point is deep,
/// matched by rank to the exemplar's; adds its energy to `energy` and returns per point the slope
/// of the term along its nearest pair.
fn nearest_term(target: &Target, depths: &[f64], per_point: &PerPoint, energy: &mut f64) -> Vec<f64> {
    let mut counted: Vec<usize> =
        (0..per_point.len()).filter(|&i| per_point[i].1 != usize::MAX && per_point[i].2 <= depths[i]).collect();
    counted.sort_by(|&a, &b| per_point[a].2.total_cmp(&per_point[b].2).then(a.cmp(&b)));
    let mut nearest_pull = vec![0.0; per_point.len()];
    // An exemplar too small for any of its nearest neighbours to count has no such term.
    if target.nearest.is_empty() {
        counted.clear();
    }
    for (rank, &i) in counted.iter().enumerate() {
        let wanted = target.nearest_at((rank as f64 + 0.5) / counted.len() as f64);
        let miss = (per_point[i].2 - wanted) / RING;
        *energy += NEAREST_WEIGHT * miss * miss;
        nearest_pull[i] = 2.0 * NEAREST_WEIGHT * miss / RING;
    }
    nearest_pull
}

/// The pairs of points within the rings' reach, and the rings each point may centre.
struct Pairs<'a, const D: usize> {
    positions: &'a [Vector<D>],
    grid: StaticGrid<D>,
    reach: f64,
    ramp: f64,
    /// Per point, how many rings fit inside the domain around it.
    usable: Vec<usize>,
}

impl<const D: usize> Pairs<'_, D> {
    /// Pass 1: each centre's ring counts and each point's nearest neighbour, summed in point order
    /// afterwards (the same bytes on any thread count).
    fn per_point(&self) -> PerPoint {
        let (positions, usable) = (self.positions, &self.usable);
        (0..positions.len())
            .into_par_iter()
            .map(|i| {
                let mut counts = vec![0.0; usable[i]];
                let (mut closest, mut nearest) = (f64::INFINITY, usize::MAX);
                self.grid.for_each_within(&positions[i], self.reach, |j, _, d2| {
                    if j == i {
                        return;
                    }
                    let d = d2.sqrt();
                    if d < closest || (d == closest && j < nearest) {
                        closest = d;
                        nearest = j;
                    }
                    for b in touched(d, self.ramp).take_while(|&b| b < usable[i]) {
                        counts[b] += kernel(b, d, self.ramp).0;
                    }
                });
                (counts, nearest, closest)
            })
            .collect()
    }

    /// Pass 2: ∂E/∂x_i for the movable points (`slopes`: ∂E/∂count per ring). Every pair term is
    /// symmetric in (i, j), so each point gathers its own and no two threads write one place.
    fn gradient(&self, per_point: &PerPoint, slopes: &[f64], nearest_pull: &[f64], movable: &[bool]) -> Vec<Vector<D>> {
        let (positions, usable) = (self.positions, &self.usable);
        (0..positions.len())
            .into_par_iter()
            .map(|i| {
                let mut g = [0.0; D];
                if !movable[i] {
                    return g;
                }
                let p = positions[i];
                self.grid.for_each_within(&p, self.reach, |j, q, d2| {
                    if j == i || d2 == 0.0 {
                        return;
                    }
                    let d = d2.sqrt();
                    let mut slope = 0.0;
                    for b in touched(d, self.ramp) {
                        let centres = (b < usable[i]) as usize + (b < usable[j]) as usize;
                        if centres > 0 {
                            slope += slopes[b] * centres as f64 * kernel(b, d, self.ramp).1;
                        }
                    }
                    if per_point[i].1 == j {
                        slope += nearest_pull[i];
                    }
                    if per_point[j].1 == i {
                        slope += nearest_pull[j];
                    }
                    for a in 0..D {
                        g[a] += slope * (p[a] - q[a]) / d;
                    }
                });
                g
            })
            .collect()
    }
}

/// Moves the movable points to lower the energy: at most `iterations` steps along the gradient,
/// each point moving at most `step` spacings, the step growing after a kept step and shrinking
/// after a refused one.
pub(crate) fn refine<const D: usize>(
    target: &Target,
    output: &mut Output<'_, D>,
    iterations: usize,
    outcome: &mut StatisticsRefinement,
) {
    let Output { positions, movable, depth, allowed, settle, volume } = output;
    let (movable, depth, allowed, settle, volume) = (*movable, *depth, *allowed, *settle, *volume);
    if positions.len() < 2 || target.nearest.is_empty() || !movable.iter().any(|&m| m) {
        return;
    }
    let density_ratio = positions.len() as f64 / volume.max(1e-300) / target.density;
    let depths: Vec<f64> = positions.iter().map(depth).collect();
    let mut current = evaluate(target, positions, &depths, density_ratio, Some(movable));
    outcome.energy_before = current.energy;
    let mut step = FIRST_STEP;
    let mut candidate = positions.to_vec();
    for _ in 0..iterations {
        let longest = current.gradient.iter().map(|g| linear::norm2(g).sqrt()).fold(0.0, f64::max);
        if longest == 0.0 || step < 1e-4 {
            break;
        }
        // Points whose gradient is above the mean move `step`, the others in proportion: scaling
        // by the longest gradient alone left most points nearly still (corpus, seeds 1-4: 25 of
        // 44 runs within 1.5x the tiled copy; 27 with the mean; 24 and 26 with half and twice it).
        let norms: Vec<f64> =
            current.gradient.iter().zip(movable).filter(|(_, m)| **m).map(|(g, _)| linear::norm2(g).sqrt()).collect();
        let reference = norms.iter().sum::<f64>() / norms.len().max(1) as f64;
        candidate.par_iter_mut().zip(positions.par_iter()).zip(&current.gradient).for_each(|((c, p), g)| {
            let scale = step / linear::norm2(g).sqrt().max(reference);
            let moved = settle(&linear::add(p, &linear::scale(g, -scale)));
            *c = if allowed(&moved) { moved } else { *p };
        });
        let candidate_depths: Vec<f64> = candidate.par_iter().map(depth).collect();
        let next = evaluate(target, &candidate, &candidate_depths, density_ratio, Some(movable));
        outcome.steps_tried += 1;
        if next.energy < current.energy {
            positions.copy_from_slice(&candidate);
            current = next;
            outcome.steps_kept += 1;
            step = (step * 1.5).min(LARGEST_STEP);
        } else {
            step *= 0.3;
        }
    }
    outcome.energy_after = current.energy;
}

/// Whether the refinement runs on `setup` (a uniform scale, `iterations` above 0).
fn applies<const D: usize>(setup: &Setup<D>, iterations: usize) -> bool {
    let scales = &setup.quadrature.scale;
    iterations > 0 && scales.windows(2).all(|w| (w[0] - w[1]).abs() <= 1e-12 * w[0].abs())
}

/// Whether the refinement will thin a surplus over the count tolerance (a fresh synthesis it
/// applies to, without rigid elements, which it cannot remove): sampling control then leaves that
/// surplus to it.
pub(crate) fn thins<const D: usize>(setup: &Setup<D>, iterations: usize) -> bool {
    applies(setup, iterations) && setup.margin.is_none() && !setup.has_elements
}

/// Runs the refinement on a finished synthesis, in place, at a uniform scale; `None` where it does
/// not apply (scale fields, `iterations` 0). On a surface, distances are taken in 3D (the same as
/// along the surface at the scale of a few spacings, as in `fidelity`) and moved points are brought
/// back onto it.
pub(crate) fn refine_state<const D: usize>(
    setup: &Setup<D>,
    state: &mut State<D>,
    iterations: usize,
    count_tolerance: f64,
    stream: &mut Stream,
) -> Option<StatisticsRefinement> {
    if !applies(setup, iterations) {
        return None;
    }
    let scales = &setup.quadrature.scale;
    if state.alive.iter().any(|alive| !alive) {
        state.compact();
    }
    // Everything in units of the exemplar's spacing at the output's scale.
    let scale = scales.first().copied().unwrap_or(1.0);
    let spacing = setup.exemplar.spacing * scale;
    let to_spacings = |p: &Vector<D>| linear::scale(p, 1.0 / spacing);
    let to_output = |p: &Vector<D>| linear::scale(p, spacing);
    let exemplar = &setup.exemplar;
    let exemplar_points: Vec<Vector<D>> =
        exemplar.positions.iter().map(|p| linear::scale(p, scale / spacing)).collect();
    let low = linear::scale(&exemplar.window_low, scale / spacing);
    let high = linear::scale(&exemplar.window_high, scale / spacing);
    // A surface's exemplar is planar (lifted into a thin 3D window): measured in its plane.
    let (region, quadrature) = (&setup.region, &setup.quadrature);
    let plane = if let Region::Surface { .. } = region { 2 } else { D };
    let window_volume: f64 = (0..plane).map(|a| high[a] - low[a]).product();
    let target = Target::new(&exemplar_points, &|p| fidelity::box_depth(p, &low, &high, plane), window_volume, RAMP);
    let volume = match region {
        Region::Surface { surface, .. } => surface.area(),
        _ => region.volume().unwrap_or(quadrature.len() as f64 * quadrature.spacing().powi(D as i32)),
    } / spacing.powi(plane as i32);
    let depth = |p: &Vector<D>| region.depth(&to_output(p)) / spacing;
    let allowed = |p: &Vector<D>| setup.allowed(&to_output(p));
    let settle = |p: &Vector<D>| to_spacings(&region.keep_on(&to_output(p)));
    let mut positions: Vec<Vector<D>> = state.positions.iter().map(to_spacings).collect();
    let mut movable = movable_points(state, &positions, setup.margin.is_none());
    let mut outcome = StatisticsRefinement::default();
    // A fresh synthesis drops what it has over the exemplar's density where that helps the
    // statistics, and always what passes sampling control's bound: with few patches (one, in a
    // small domain) no point may be movable, and a copy of a lattice holds as many points as its
    // phase puts into the box (up to +23 % in a 9 × 9 box). Progressive synthesis keeps its count.
    let surplus = positions.len() as f64 - (1.0 + COUNT_SLACK) * setup.expected_points;
    let most = ((1.0 + count_tolerance) * setup.expected_points).floor() as usize;
    if surplus >= 1.0 && setup.margin.is_none() {
        let required = positions.len().saturating_sub(most).min(surplus as usize);
        let candidates = if movable.iter().filter(|&&m| m).count() < 2 * required {
            state.unit_of.iter().map(|&u| state.units[u as usize].rigid.is_none()).collect()
        } else {
            movable.clone()
        };
        let removed = thin(&target, &positions, &candidates, &depth, volume, required, surplus as usize);
        outcome.removed_points = removed.len();
        if !removed.is_empty() {
            removed.iter().for_each(|&i| state.kill(state.unit_of[i] as usize));
            state.compact();
            positions = state.positions.iter().map(to_spacings).collect();
            movable = movable_points(state, &positions, true);
        }
    }
    outcome.movable_points = movable.iter().filter(|&&m| m).count();
    let mut output = Output {
        positions: &mut positions,
        movable: &movable,
        depth: &depth,
        allowed: &allowed,
        settle: &settle,
        volume,
    };
    refine(&target, &mut output, iterations, &mut outcome);
    // Relocation moves the same points: the copied patches' interiors keep what the isotropic
    // statistics do not see (orientation, types, curves; moving them too made rows of points lose
    // their direction). Not on a surface: bringing every proposal onto the mesh took the torus to
    // 3.4 × the time of the same count in a box (issue 35 allows 3), and surfaces already meet
    // their statistics without it.
    if matches!(region, Region::Surface { .. }) {
        return Some(write_back(state, &positions, &movable, spacing, outcome));
    }
    let quantum = relocation::coordinate_quantum(&exemplar.positions, exemplar.spacing).map(|q| q * scale / spacing);
    // Progressive synthesis (existing points kept: the playground's brush) takes the least sweeps
    // alone: its new points join structure that is already there (0.1 s a stroke rather than 0.2).
    let proposals = if setup.margin.is_none() { RELOCATION.proposals } else { 0 };
    let settings = relocation::Settings { quantum, proposals, ..RELOCATION };
    let hard = Target::new(&exemplar_points, &|p| fidelity::box_depth(p, &low, &high, plane), window_volume, 0.0);
    relocation::relocate(&hard, &mut output, settings, stream, &mut outcome);
    Some(write_back(state, &positions, &movable, spacing, outcome))
}

/// Writes the `movable` points of `positions` (in spacings of `spacing`) back into `state` (only
/// those: the trip through spacings is not exact), and returns `outcome`.
fn write_back<const D: usize>(
    state: &mut State<D>,
    positions: &[Vector<D>],
    movable: &[bool],
    spacing: f64,
    outcome: StatisticsRefinement,
) -> StatisticsRefinement {
    for ((p, moved), _) in state.positions.iter_mut().zip(positions).zip(movable).filter(|(_, m)| **m) {
        *p = linear::scale(moved, spacing);
    }
    outcome
}

/// The points the refinement moves: free points the optimization moved and, when `grow`, every
/// free point within [`BAND`] of one (rigid elements move only as wholes, in the optimization).
fn movable_points<const D: usize>(state: &State<D>, positions: &[Vector<D>], grow: bool) -> Vec<bool> {
    let free: Vec<bool> = state.unit_of.iter().map(|&u| state.units[u as usize].rigid.is_none()).collect();
    let moved: Vec<bool> = state.movable().iter().zip(&free).map(|(&m, &f)| m && f).collect();
    if !grow {
        return moved;
    }
    let grid = StaticGrid::new(positions, BAND);
    (0..positions.len())
        .map(|i| {
            let mut near = moved[i];
            if free[i] && !near {
                grid.for_each_within(&positions[i], BAND, |j, _, _| near |= moved[j]);
            }
            near
        })
        .collect()
}

#[path = "relocation.rs"]
mod relocation;
#[path = "thinning.rs"]
mod thinning;
pub(crate) use thinning::thin;

#[cfg(test)]
#[path = "tests_pair_statistics.rs"]
mod tests;
