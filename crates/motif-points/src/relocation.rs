//! Relocation: the reconstruction step of Tscheschel and Stoyan (2006, "Statistical reconstruction
//! of random point patterns") on the pair-statistics energy, after its gradient steps.
//!
//! Gradient steps move points by fractions of a spacing, so they cannot gather scattered points
//! into the clusters of a clustered exemplar (from random points longleaf stayed as far from its
//! g(r) as a random set) nor take a point out of a ring the exemplar never shows. Relocation moves
//! one movable point at a time to a proposed place and keeps the move only when the whole energy
//! goes down: the parent module's ring chi-square with hard rings (the bench's g(r) rings), plus
//! the Wasserstein distance between the counted nearest-neighbour distances and the exemplar's,
//! read off cumulative histograms of fine bins. Both are histograms, so the energy change of a
//! move is exact, local and cheap: the pairs within the rings' reach of its two places and the
//! nearest neighbours there. (The parent's rank-matched nearest-neighbour term needs a pass over
//! the sorted distances per move: 21 000 points spent 70 µs a proposal on it.) Proposals, a third
//! each:
//! - anywhere in the domain's bounding box (Tscheschel and Stoyan's uniform proposal);
//! - at one of the exemplar's nearest-neighbour distances (drawn from them) from a random point,
//!   in a random direction: where the exemplar's clusters and spacings say points sit;
//! - within one spacing of where the point is.
//!
//! Everything is sequential and drawn from one seeded stream: the same seed gives the same moves
//! on any thread count.

use motif_core::random::{Rng, Stream};

use super::{Output, REACH, StatisticsRefinement, Target, kernel, rings, touched, usable_rings};
use crate::grid::{DynamicGrid, bounds};
use crate::linear::{self, Vector};

/// A point's nearest neighbour and its distance (`usize::MAX`, infinity: none within reach).
type Nearest = (usize, f64);

/// The output's pairs and nearest neighbours, kept up to date move by move.
struct Book<'a, const D: usize> {
    target: &'a Target,
    positions: &'a mut [Vector<D>],
    depths: Vec<f64>,
    usable: Vec<usize>,
    grid: DynamicGrid<D>,
    /// Pair counts and usable centres per ring (as the parent's `evaluate`, with the target's rings).
    counts: Vec<f64>,
    centres: Vec<usize>,
    nearest: Vec<Nearest>,
    /// Histogram of the counted nearest-neighbour distances (a neighbour no farther than the point
    /// is deep), [`NEAREST_BINS`] bins, and how many are counted.
    histogram: Vec<f64>,
    counted: usize,
    /// The exemplar's share of counted nearest-neighbour distances in each bin.
    shares: Vec<f64>,
    density_ratio: f64,
    energy: f64,
}

/// What a proposed move changes.
struct Move<const D: usize> {
    point: usize,
    to: Vector<D>,
    depth: f64,
    usable: usize,
    /// Change of each ring's count.
    counts: Vec<f64>,
    /// New nearest neighbours, by point (the moved point's first).
    nearest: Vec<(usize, Nearest)>,
    /// Change of each nearest-neighbour bin, and of the count.
    histogram: Vec<(usize, f64)>,
    counted: usize,
    energy: f64,
}

/// How relocation runs.
#[derive(Debug, Clone, Copy)]
pub(super) struct Settings {
    /// Sweeps at least (a sweep proposes one move per movable point).
    pub sweeps: usize,
    /// Proposals in all, at least: fewer movable points get more sweeps (clusters form from few
    /// points, one move at a time: 62 redwood seedlings in a box four times their window, from
    /// random points, needed about 1 000 sweeps).
    pub proposals: usize,
    /// The exemplar's coordinate quantum in spacings ([`coordinate_quantum`]): proposed places are
    /// rounded to its multiples.
    pub quantum: Option<f64>,
}

/// Relocation stops once this many proposals in a row (whole sweeps, past the least sweeps) kept
/// no move: the playground's brush strokes (~90 new points) spent 0.5–0.7 s on the 250 000
/// proposals, their whole run 0.1 s before, though their points settle within a few sweeps. (100
/// idle sweeps instead stopped the redwood from patches, 60 movable points keeping a move every
/// ~9 sweeps, at 1.66 × the tiled copy's g(r) distance.)
const IDLE_PROPOSALS: usize = 25_000;

/// An exemplar's coordinate quantum is kept only when it is finer than this many spacings (a
/// coarser grid would decide where points go more than the rings do).
const COARSEST_QUANTUM: f64 = 1.0 / 3.0;

/// The coarsest power of ten of which every coordinate of `points` is a whole multiple (data
/// recorded to 0.01 gives 0.01), when it is finer than [`COARSEST_QUANTUM`] × `spacing`.
pub(super) fn coordinate_quantum<const D: usize>(points: &[Vector<D>], spacing: f64) -> Option<f64> {
    (-9..=9).rev().map(|k| 10f64.powi(k)).filter(|&q| q < COARSEST_QUANTUM * spacing).find(|&q| {
        points.iter().flatten().all(|&x| {
            let units = x / q;
            (units - units.round()).abs() <= 1e-6 * units.abs().max(1.0)
        })
    })
}

/// Relocates movable points of `output` (in spacings), each proposal kept when it lowers the
/// energy, for as many sweeps as `settings` give. Records the proposals tried and kept, the sweeps,
/// and the energy before and after them in `outcome`.
pub(super) fn relocate<const D: usize>(
    target: &Target,
    output: &mut Output<'_, D>,
    settings: Settings,
    stream: &mut Stream,
    outcome: &mut StatisticsRefinement,
) {
    let movable: Vec<usize> = (0..output.positions.len()).filter(|&i| output.movable[i]).collect();
    if movable.is_empty() || output.positions.len() < 2 || target.nearest.is_empty() {
        return;
    }
    let density_ratio = output.positions.len() as f64 / output.volume.max(1e-300) / target.density;
    let depths: Vec<f64> = output.positions.iter().map(|p| (output.depth)(p)).collect();
    let (low, high) = bounds(output.positions);
    let mut book = Book::new(target, &mut *output.positions, depths, density_ratio);
    outcome.relocation_energy_before = book.energy;
    let sweeps = settings.proposals.div_ceil(movable.len()).max(settings.sweeps);
    let mut last_kept = 0;
    for sweep in 0..sweeps {
        if sweep >= settings.sweeps && (sweep - last_kept) * movable.len() >= IDLE_PROPOSALS {
            break;
        }
        for _ in 0..movable.len() {
            let point = movable[stream.random_range(0..movable.len())];
            let mut to = (output.settle)(&propose(&book, point, (low, high), stream));
            if let Some(q) = settings.quantum {
                to = (output.settle)(&std::array::from_fn(|a| (to[a] / q).round() * q));
            }
            outcome.relocations_tried += 1;
            let depth = (output.depth)(&to);
            if !(output.allowed)(&to) || !deep_enough(depth, book.depths[point]) {
                continue;
            }
            let change = book.try_move(point, to, depth);
            if change.energy < book.energy && !book.isolates(&change) {
                book.apply(change);
                outcome.relocations_kept += 1;
                last_kept = sweep;
            }
        }
        outcome.relocation_sweeps += 1;
    }
    outcome.relocation_energy_after = book.energy;
}

/// Whether a point `from_depth` deep may move to a place `depth` deep (spacings): not nearer the
/// border than a spacing unless it was already. The statistics count a point near the border
/// only as another's neighbour (its own rings and nearest neighbour reach outside), so without
/// this rule surplus points were dumped along the borders, where they are nearly invisible.
fn deep_enough(depth: f64, from_depth: f64) -> bool {
    depth >= from_depth.min(1.0)
}

/// A place for `point`: uniform in `[low, high]`, at an exemplar nearest-neighbour distance from
/// another point, or within a spacing of its own place (a third each).
fn propose<const D: usize>(
    book: &Book<'_, D>,
    point: usize,
    (low, high): (Vector<D>, Vector<D>),
    stream: &mut Stream,
) -> Vector<D> {
    match stream.random_range(0..3u32) {
        0 => std::array::from_fn(|a| low[a] + (high[a] - low[a]) * stream.random::<f64>()),
        1 => {
            let other = stream.random_range(0..book.positions.len());
            let distance = book.target.nearest_at(stream.random::<f64>());
            linear::add(&book.positions[other], &linear::scale(&direction(stream), distance))
        }
        _ => {
            let distance = stream.random::<f64>();
            linear::add(&book.positions[point], &linear::scale(&direction(stream), distance))
        }
    }
}

/// Weight of the nearest-neighbour term against the ring chi-square. Redwood, seeds 1–4, both
/// starts, g(r) distance over the tiled copy's: 0.99–1.48 at weight 1, 0.81–1.35 at 0.6, 0.67–1.23
/// at 0.3; but at 0.3 a jittered grid from random points kept only 80 % of its nearest-neighbour
/// distances within 20 % of the spacing (the unit test asks for more). A chi-square of the
/// histogram instead left redwood's nearest-neighbour distance at 1.5–2 × the tiled copy's.
const NEAREST_WEIGHT: f64 = 0.6;

/// A uniform random unit vector (rejection from the cube).
fn direction<const D: usize>(stream: &mut Stream) -> Vector<D> {
    loop {
        let v: Vector<D> = std::array::from_fn(|_| 2.0 * stream.random::<f64>() - 1.0);
        let n2 = linear::norm2(&v);
        if (1e-4..=1.0).contains(&n2) {
            return linear::scale(&v, 1.0 / n2.sqrt());
        }
    }
}

impl<'a, const D: usize> Book<'a, D> {
    fn new(target: &'a Target, positions: &'a mut [Vector<D>], depths: Vec<f64>, density_ratio: f64) -> Self {
        let (low, high) = bounds(positions);
        let mut grid = DynamicGrid::new(low, high, REACH + target.ramp);
        positions.iter().enumerate().for_each(|(i, p)| grid.insert(i, p));
        let usable: Vec<usize> = depths.iter().map(|&d| usable_rings(d, target.ramp)).collect();
        let (mut counts, mut centres) = (vec![0.0; rings()], vec![0usize; rings()]);
        let mut nearest = vec![(usize::MAX, f64::INFINITY); positions.len()];
        let mut book = Self {
            target,
            positions,
            depths,
            usable,
            grid,
            counts: Vec::new(),
            centres: Vec::new(),
            nearest: Vec::new(),
            histogram: vec![0.0; NEAREST_BINS],
            counted: 0,
            shares: shares(target),
            density_ratio,
            energy: 0.0,
        };
        for i in 0..book.positions.len() {
            centres[..book.usable[i]].iter_mut().for_each(|c| *c += 1);
            book.for_each_neighbour(&book.positions[i], i, |j, d| {
                // Each pair once, from its lower index, for both its centres.
                if j > i {
                    add_pair(&mut counts, d, book.usable[i], book.usable[j], (1.0, target.ramp));
                }
                if d < nearest[i].1 || (d == nearest[i].1 && j < nearest[i].0) {
                    nearest[i] = (j, d);
                }
            });
        }
        for i in (0..book.positions.len()).filter(|&i| nearest[i].1 <= book.depths[i]) {
            book.histogram[bin(nearest[i].1)] += 1.0;
            book.counted += 1;
        }
        book.energy = pair_energy(target, density_ratio, |b| (counts[b], centres[b] as f64))
            + book.nearest_energy(|b| book.histogram[b], book.counted);
        (book.counts, book.centres, book.nearest) = (counts, centres, nearest);
        book
    }

    /// Calls `visit(j, d)` for every point `j ≠ skip` within the rings' reach of `p`.
    fn for_each_neighbour(&self, p: &Vector<D>, skip: usize, mut visit: impl FnMut(usize, f64)) {
        let reach = REACH + self.target.ramp;
        self.grid.for_each_candidate(p, reach, |j| {
            if j != skip {
                let d = linear::norm2(&linear::sub(p, &self.positions[j])).sqrt();
                if d < reach {
                    visit(j, d);
                }
            }
        });
    }

    /// What moving `point` to `to` (whose depth is `depth`) changes, and the energy after it.
    fn try_move(&self, point: usize, to: Vector<D>, depth: f64) -> Move<D> {
        let from = self.positions[point];
        let (usable, ramp) = (usable_rings(depth, self.target.ramp), self.target.ramp);
        let mut counts = vec![0.0; rings()];
        // Points whose nearest neighbour was the moved point look again; the others take it if it
        // came closer.
        let mut orphans = Vec::new();
        self.for_each_neighbour(&from, point, |j, d| {
            add_pair(&mut counts, d, self.usable[point], self.usable[j], (-1.0, ramp));
            if self.nearest[j].0 == point {
                orphans.push(j);
            }
        });
        let mut own = (usize::MAX, f64::INFINITY);
        let mut nearest = vec![(point, own)];
        self.for_each_neighbour(&to, point, |j, d| {
            add_pair(&mut counts, d, usable, self.usable[j], (1.0, ramp));
            if d < own.1 || (d == own.1 && j < own.0) {
                own = (j, d);
            }
            let (k, e) = self.nearest[j];
            if k != point && (d < e || (d == e && point < k)) {
                nearest.push((j, (point, d)));
            }
        });
        nearest[0].1 = own;
        nearest.extend(orphans.into_iter().map(|j| (j, self.nearest_without(j, point, &to))));
        let (histogram, counted) = self.histogram_change(&nearest, point, depth);
        let nearest_part = self.nearest_energy(
            |b| self.histogram[b] + histogram.iter().filter(|c| c.0 == b).map(|c| c.1).sum::<f64>(),
            counted,
        );
        let centre_change = |b: usize| usize::from(b < usable) as f64 - usize::from(b < self.usable[point]) as f64;
        let pair_part = pair_energy(self.target, self.density_ratio, |b| {
            (self.counts[b] + counts[b], self.centres[b] as f64 + centre_change(b))
        });
        Move { point, to, depth, usable, counts, nearest, histogram, counted, energy: pair_part + nearest_part }
    }

    /// Whether `change` drops the moved point farther from its nearest neighbour than any exemplar
    /// point is from its own: alone in empty space or along a border, which the statistics barely
    /// see (the nearest-neighbour term does not count a point nearer the border than its
    /// neighbour) but a user does (stray dots between a traced chain's rings). Points a move
    /// leaves behind are not held to it: forming clusters from random points leaves some alone
    /// for a while (holding them too left the redwood from random points at 1.6–2.5 × the tiled
    /// copy's g(r) distance, seeds 1–4).
    fn isolates(&self, change: &Move<D>) -> bool {
        change.nearest[0].1.1 > self.target.farthest_nearest()
    }

    /// The nearest neighbour of `j` when `moved` sits at `to`.
    fn nearest_without(&self, j: usize, moved: usize, to: &Vector<D>) -> Nearest {
        let p = self.positions[j];
        let mut best = (usize::MAX, f64::INFINITY);
        self.for_each_neighbour(&p, j, |k, d| {
            if k != moved && (d < best.1 || (d == best.1 && k < best.0)) {
                best = (k, d);
            }
        });
        let d = linear::norm2(&linear::sub(&p, to)).sqrt();
        if d < REACH + self.target.ramp && (d < best.1 || (d == best.1 && moved < best.0)) {
            best = (moved, d);
        }
        best
    }

    /// How the nearest-neighbour histogram changes with `changes` (the moved `point` now at
    /// `depth`): bins and their change, and the new count.
    fn histogram_change(&self, changes: &[(usize, Nearest)], point: usize, depth: f64) -> (Vec<(usize, f64)>, usize) {
        let mut bins = Vec::with_capacity(2 * changes.len());
        let mut counted = self.counted;
        for &(i, (_, d)) in changes {
            if self.nearest[i].1 <= self.depths[i] {
                bins.push((bin(self.nearest[i].1), -1.0));
                counted -= 1;
            }
            if d <= if i == point { depth } else { self.depths[i] } {
                bins.push((bin(d), 1.0));
                counted += 1;
            }
        }
        (bins, counted)
    }

    /// The nearest-neighbour term: `Σ_b |C_b − n F_b|` per ring, `C_b` the counted distances in bins
    /// up to `b` (`histogram(b)` in bin `b`, `n` counted) and `F_b` the exemplar's share up to `b`:
    /// the Wasserstein distance the bench reports, in points × rings.
    fn nearest_energy(&self, histogram: impl Fn(usize) -> f64, counted: usize) -> f64 {
        let n = counted as f64;
        let (mut cumulative, mut wanted, mut energy) = (0.0, 0.0, 0.0);
        for (b, share) in self.shares.iter().enumerate() {
            cumulative += histogram(b);
            wanted += share * n;
            energy += (cumulative - wanted).abs();
        }
        NEAREST_WEIGHT * energy * rings() as f64 / NEAREST_BINS as f64
    }

    fn apply(&mut self, change: Move<D>) {
        let Move { point, to, depth, usable, counts, nearest, histogram, counted, energy } = change;
        self.grid.remove(point, &self.positions[point]);
        self.grid.insert(point, &to);
        self.centres[..self.usable[point]].iter_mut().for_each(|c| *c -= 1);
        self.centres[..usable].iter_mut().for_each(|c| *c += 1);
        self.counts.iter_mut().zip(&counts).for_each(|(c, d)| *c += d);
        (self.positions[point], self.depths[point], self.usable[point]) = (to, depth, usable);
        nearest.into_iter().for_each(|(i, n)| self.nearest[i] = n);
        histogram.into_iter().for_each(|(b, change)| self.histogram[b] += change);
        (self.counted, self.energy) = (counted, energy);
    }
}

/// Adds `sign` × the pair at distance `d` to each ring it touches (kernels of ramp half-width
/// `ramp`), once for each of its two centres that may count the ring (`usable_i`, `usable_j` rings).
fn add_pair(counts: &mut [f64], d: f64, usable_i: usize, usable_j: usize, (sign, ramp): (f64, f64)) {
    for b in touched(d, ramp) {
        let centres = (b < usable_i) as usize + (b < usable_j) as usize;
        if centres > 0 {
            counts[b] += sign * centres as f64 * kernel(b, d, ramp).0;
        }
    }
}

/// The ring chi-square of the parent's `evaluate`, `ring(b)` giving ring `b`'s pair count and
/// usable centres.
fn pair_energy(target: &Target, density_ratio: f64, ring: impl Fn(usize) -> (f64, f64)) -> f64 {
    (0..rings())
        .filter_map(|b| {
            let (count, centres) = ring(b);
            target.wanted(b, centres, density_ratio).map(|wanted| (count - wanted).powi(2) / wanted)
        })
        .sum()
}

/// Bins of the nearest-neighbour histogram: a tenth of a ring's width up to the rings' reach.
/// Bins of a ring's width left the protein atoms' bond lengths free to drift within a bin: their
/// nearest-neighbour distance came out at 1.9 × the tiled copy's (0.026 against 0.014).
const NEAREST_BINS: usize = 400;

/// The histogram bin of a nearest-neighbour distance (the last bin takes the rest).
fn bin(d: f64) -> usize {
    ((d / REACH * NEAREST_BINS as f64) as usize).min(NEAREST_BINS - 1)
}

/// The exemplar's share of counted nearest-neighbour distances in each bin.
fn shares(target: &Target) -> Vec<f64> {
    let mut shares = vec![0.0; NEAREST_BINS];
    target.nearest.iter().for_each(|&d| shares[bin(d)] += 1.0);
    let n = target.nearest.len().max(1) as f64;
    shares.iter_mut().for_each(|s| *s /= n);
    shares
}

#[cfg(test)]
mod tests {
    use motif_core::SeedStreams;

    use super::super::tests::{box_depth, in_box, random_points};
    use super::*;
    use crate::fidelity;

    /// Tight clusters of `per` points (radius 0.4) around random centres in `[0, side)²`.
    fn clusters(count: usize, per: usize, side: f64, seed: u64) -> Vec<Vector<2>> {
        let mut stream = SeedStreams::new(seed).stream("clusters", 0);
        let mut points = Vec::new();
        for _ in 0..count {
            let centre = [1.0 + (side - 2.0) * stream.random::<f64>(), 1.0 + (side - 2.0) * stream.random::<f64>()];
            for _ in 0..per {
                let offset = linear::scale(&direction::<2>(&mut stream), 0.4 * stream.random::<f64>());
                points.push(linear::add(&centre, &offset));
            }
        }
        points
    }

    /// The energy, pair counts and nearest-neighbour histogram kept move by move equal those of a
    /// book built from scratch on the moved points, after every kept move, and so do the nearest
    /// neighbours at the end.
    #[test]
    fn the_energy_kept_move_by_move_is_the_energy_from_scratch() {
        let side = 12.0;
        let depth = box_depth(side);
        let target = Target::new(&clusters(20, 5, side, 1), &depth, side * side, 0.0);
        let mut points = random_points(100, side, 2);
        let depths: Vec<f64> = points.iter().map(&depth).collect();
        let ratio = 1.0;
        let mut book = Book::new(&target, &mut points, depths, ratio);
        let mut stream = SeedStreams::new(3).stream("moves", 0);
        let mut kept = 0;
        for _ in 0..600 {
            let point = stream.random_range(0..book.positions.len());
            let to = propose(&book, point, ([0.0; 2], [side; 2]), &mut stream);
            if !to.iter().all(|x| (0.0..side).contains(x)) {
                continue;
            }
            let change = book.try_move(point, to, depth(&to));
            if change.energy < book.energy {
                book.apply(change);
                kept += 1;
                let mut copy = book.positions.to_vec();
                let scratch = Book::new(&target, &mut copy, book.depths.clone(), ratio);
                assert!((scratch.energy - book.energy).abs() <= 1e-9 * scratch.energy.max(1.0));
                assert_eq!((&scratch.histogram, scratch.counted), (&book.histogram, book.counted));
                for (a, b) in scratch.counts.iter().zip(&book.counts) {
                    assert!((a - b).abs() <= 1e-9 * a.abs().max(1.0), "pair count {a} from scratch, {b} kept");
                }
            }
        }
        assert!(kept > 20, "{kept} moves kept");
        let (moved, nearest) = (book.positions.to_vec(), book.nearest.clone());
        let mut copy = moved.clone();
        let fresh = Book::new(&target, &mut copy, moved.iter().map(&depth).collect(), ratio);
        assert_eq!(fresh.nearest, nearest);
    }

    /// From random points, relocation gathers points into the exemplar's clusters: the g(r)
    /// distance to the exemplar falls to under half the random set's, and fixed points stay.
    #[test]
    fn relocation_forms_the_clusters_of_a_clustered_exemplar() {
        let side = 16.0;
        let depth = box_depth(side);
        let exemplar = clusters(30, 6, side, 4);
        let target = Target::new(&exemplar, &depth, side * side, 0.0);
        let mut points = random_points(exemplar.len(), side, 5);
        let before = points.clone();
        let movable: Vec<bool> = (0..points.len()).map(|i| i % 10 != 0).collect();
        let inside = |p: &Vector<2>| p.iter().all(|&x| (0.0..=side).contains(&x));
        let mut output = in_box(&mut points, &movable, &depth, &inside, side);
        let mut outcome = StatisticsRefinement::default();
        relocate(
            &target,
            &mut output,
            Settings { sweeps: 40, proposals: 0, quantum: None },
            &mut SeedStreams::new(6).stream("relocation", 0),
            &mut outcome,
        );
        assert!(outcome.relocation_energy_after < 0.2 * outcome.relocation_energy_before, "{outcome:?}");
        let statistics = |points: &[Vector<2>]| {
            let sample = fidelity::Sample { points, depth: &depth, volume: side * side, dimension: 2 };
            fidelity::statistics(&sample, 1.0)
        };
        let g_distance =
            |points: &[Vector<2>]| fidelity::distances(&statistics(&exemplar), &statistics(points)).radial_distribution;
        let (random, relocated) = (g_distance(&before), g_distance(&points));
        assert!(relocated < 0.5 * random, "g(r) distance {relocated}, random {random}");
        for i in (0..points.len()).filter(|&i| !movable[i]) {
            assert_eq!(points[i], before[i], "fixed point {i} moved");
        }
    }
}
