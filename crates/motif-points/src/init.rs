//! Patch initialization of the output (§5.2): copies of exemplar patches, chosen by quilting and
//! joined along cuts. The solver is meant to reach the same kind of result from these as from
//! random points (`placement::random`).

use motif_core::SeedStreams;
use motif_core::random::{Rng, Stream};

use crate::cut_copy::{CopyFrame, CutCopy, Provenance, copy_with_cuts};
use crate::domain::Quadrature;
use crate::grid::StaticGrid;
use crate::linear::{self, Vector};
use crate::model::{Exemplar, State};
use crate::placement::{Placement, place};
use crate::quilting::{Band, Tile};

/// How patch initialization cuts and chooses its patches.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PatchLayout {
    /// Side of a patch (output units).
    pub side: f64,
    /// Width of the band around a patch where its candidates are judged.
    pub band: f64,
    /// Candidate sources judged per patch.
    pub candidates: usize,
    /// Tolerance above the best candidate's score (seams and count) within which the candidate
    /// whose exemplar points were copied least so far is taken (0: the best score alone).
    pub balance: f64,
    /// When set, points farther than this from every border of their patch are frozen.
    pub seam: Option<f64>,
    /// The quadrature points lie on a surface: each copy is centred on the one nearest its
    /// tile's centre (the centre itself is off the surface) and laid in the tangent plane there.
    pub on_surface: bool,
    /// The share of a grid cell's volume each quadrature point stands for (1, but on a surface,
    /// whose band holds one or two layers of nodes).
    pub node_share: f64,
    /// How far the copies' count may miss the expected count (a fraction of it) before more
    /// points near the seams are left movable: sampling control's count tolerance, since it
    /// can correct the count only with movable points.
    pub count_tolerance: f64,
}

/// What a patch initialization made.
pub(crate) struct Copies<const D: usize> {
    /// For every quadrature point in a tile, the exemplar location its tile was copied from.
    pub sources: Vec<Option<Vector<D>>>,
    /// Points frozen as copied.
    pub interiors: usize,
    /// Coefficient of variation of how many output points copy each exemplar point (0: every
    /// exemplar point is copied equally often, as in a tiled copy).
    pub usage_variation: f64,
}

/// Patch initialization: the domain is tiled with cubes of side `patch`; each receives a copy of a
/// random exemplar patch placed with the frame of its nearest quadrature point. Returns, for every
/// quadrature point in a tile, the exemplar location its tile was copied from: the exact match of
/// the copy, which the first matching step starts from (without it, the first merging step follows
/// random matches and undoes the copies before any match has been found).
pub(crate) fn patches<const D: usize>(
    exemplar: &Exemplar<D>,
    quadrature: &Quadrature<D>,
    fill: &[usize],
    layout: PatchLayout,
    state: &mut State<D>,
    streams: &SeedStreams,
    domain: DomainTests<'_, D>,
) -> Copies<D> {
    let DomainTests { allowed, settle } = domain;
    let mut sources = vec![None; quadrature.len()];
    if fill.is_empty() {
        return Copies { sources, interiors: 0, usage_variation: 0.0 };
    }
    let tiling = Tiling::new(quadrature, fill, layout.side);
    let quilt = Quilt {
        exemplar,
        quadrature,
        layout,
        extent: std::array::from_fn(|a| exemplar.high[a] - exemplar.low[a]),
        exemplar_grid: StaticGrid::new(&exemplar.positions, exemplar.spacing),
        // In 2D, copies of free points overlap the placed ones by a band and are joined along a
        // minimum error boundary cut (`crate::cut`); elsewhere they meet at the tile borders.
        cuts: D == 2 && exemplar.element_of.iter().all(Option::is_none),
        allowed,
        settle,
        tiling,
    };
    let (representative, expected) = quilt.tile_shares(fill);
    let nearest_to_centre = layout.on_surface.then(|| quilt.nearest_to_centres(fill));
    let mut running = Running {
        copies: vec![None; quilt.tiling.total],
        provenance: Provenance {
            first_copy: state.positions.len(),
            copy_of: Vec::new(),
            source_of: Vec::new(),
            usage: vec![0.0; exemplar.positions.len()],
        },
        expected_so_far: 0.0,
        placed_so_far: 0.0,
        interiors: 0,
    };
    for (tile, k) in representative.iter().enumerate() {
        let Some(mut k) = *k else { continue };
        let mut stream = streams.stream("initial patch", tile as u64);
        let mut centre = quilt.tiling.centre(tile);
        if let Some(nearest) = &nearest_to_centre {
            k = nearest[tile].0;
            centre = quadrature.points[k];
        }
        let copy = quilt.tile_copy(tile, k, centre);
        let places = quilt.candidate_origins(&copy, &mut stream);
        let goal = running.expected_so_far + expected[tile];
        let judged = quilt.judge_origins(&copy, &places, state, &running, (goal, expected[tile].max(1.0)));
        let origin = places[pick_origin(&judged, layout.balance)];
        running.expected_so_far = goal;
        running.copies[tile] = Some((centre, origin, k));
        quilt.copy_tile(&copy, origin, state, &mut running);
    }
    let Running { copies, provenance, mut interiors, .. } = running;
    if quilt.cuts {
        let expected = (expected.iter().sum(), layout.count_tolerance);
        interiors = freeze_interiors(state, &provenance.copy_of, provenance.first_copy, layout.seam, expected);
    }
    for &k in fill {
        if let Some((centre, origin, representative)) = copies[quilt.tiling.tile_of(&quadrature.points[k])] {
            let offset = linear::sub(&quadrature.points[k], &centre);
            sources[k] = Some(linear::add(&origin, &linear::mat_vec(&quadrature.inverse[representative], &offset)));
        }
    }
    Copies { sources, interiors, usage_variation: variation(&provenance.usage) }
}

/// The coefficient of variation of how often each exemplar point was copied (0 when none was).
fn variation(usage: &[f64]) -> f64 {
    let mean = usage.iter().sum::<f64>() / usage.len() as f64;
    let variance = usage.iter().map(|u| (u - mean) * (u - mean)).sum::<f64>() / usage.len() as f64;
    if mean > 0.0 { variance.sqrt() / mean } else { 0.0 }
}

/// The tiles of a patch initialization: a grid over the cells of the fill points, tile `t` at
/// `low + (c + ½) sides` for its cell `c`, numbered with the first axis fastest.
struct Tiling<const D: usize> {
    low: Vector<D>,
    sides: Vector<D>,
    dims: [usize; D],
    total: usize,
}

impl<const D: usize> Tiling<D> {
    fn new(quadrature: &Quadrature<D>, fill: &[usize], patch: f64) -> Self {
        let points: Vec<Vector<D>> = fill.iter().map(|&k| quadrature.points[k]).collect();
        // The tiles cover the cells the quadrature points stand for, not only the points: tiles
        // from the lowest point left a strip of up to half a cell along the domain's lower
        // borders empty.
        let (low, high) = crate::grid::bounds(&points);
        let half_cell = 0.5 * quadrature.spacing();
        let (low, high): (Vector<D>, Vector<D>) =
            (std::array::from_fn(|a| low[a] - half_cell), std::array::from_fn(|a| high[a] + half_cell));
        let dims: [usize; D] = std::array::from_fn(|a| ((high[a] - low[a]) / patch).ceil().max(1.0) as usize);
        // Tiles fit the domain's extent exactly, each side at most `patch`: a last tile reaching
        // past the domain held only a strip of its copy, which the running count could not steer,
        // and balancing filled such strips from the least-copied places, the exemplar's borders
        // (bei's right edge came out at 1.9× the density). Where fitting would shrink the tiles
        // below three quarters of a patch (a domain under three patches across), they keep the
        // patch's side: on the generated hex lattice, 11.5 × 7.5 with patches of 6, tiles of 3.75
        // put seams through the lattice every few rows (nearest-neighbour distance 0.01 → 0.10).
        let sides: Vector<D> = std::array::from_fn(|a| {
            let fitted = (high[a] - low[a]) / dims[a] as f64;
            if fitted >= 0.75 * patch { fitted } else { patch }
        });
        let total: usize = dims.iter().product();
        Self { low, sides, dims, total }
    }

    /// The tile that holds `x` (clamped to the grid).
    fn tile_of(&self, x: &Vector<D>) -> usize {
        let mut index = 0;
        for a in (0..D).rev() {
            let c = (((x[a] - self.low[a]) / self.sides[a]).floor().max(0.0) as usize).min(self.dims[a] - 1);
            index = index * self.dims[a] + c;
        }
        index
    }

    /// The centre of `tile`.
    fn centre(&self, tile: usize) -> Vector<D> {
        let mut rest = tile;
        std::array::from_fn(|a| {
            let c = rest % self.dims[a];
            rest /= self.dims[a];
            self.low[a] + (c as f64 + 0.5) * self.sides[a]
        })
    }

    /// Half a tile's side per axis.
    fn half(&self) -> Vector<D> {
        std::array::from_fn(|a| 0.5 * self.sides[a])
    }

    /// Per axis, whether the tile's lower neighbour along it has been copied already.
    fn lower_placed<T>(&self, tile: usize, copies: &[Option<T>]) -> [bool; D] {
        let mut rest = tile;
        let mut stride = 1;
        std::array::from_fn(|a| {
            let c = rest % self.dims[a];
            rest /= self.dims[a];
            let placed = c > 0 && copies[tile - stride].is_some();
            stride *= self.dims[a];
            placed
        })
    }
}

/// Where copied points may go: `allowed` says whether a place is in Ω, and on a surface `settle`
/// moves a place to the surface's closest point.
#[derive(Clone, Copy)]
pub(crate) struct DomainTests<'a, const D: usize> {
    pub allowed: &'a dyn Fn(&Vector<D>) -> bool,
    pub settle: Option<&'a dyn Fn(&Vector<D>) -> Vector<D>>,
}

impl<const D: usize> std::fmt::Debug for DomainTests<'_, D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DomainTests").field("settle", &self.settle.is_some()).finish_non_exhaustive()
    }
}

/// What every tile's copy reads: the exemplar, the quadrature and its tiling, the layout.
struct Quilt<'a, const D: usize> {
    exemplar: &'a Exemplar<D>,
    quadrature: &'a Quadrature<D>,
    layout: PatchLayout,
    tiling: Tiling<D>,
    /// The exemplar's bounding box's side per axis.
    extent: Vector<D>,
    /// The exemplar's points, searched within a spacing (the seams of candidates).
    exemplar_grid: StaticGrid<D>,
    /// Copies are joined along minimum error boundary cuts (2D free points).
    cuts: bool,
    allowed: &'a dyn Fn(&Vector<D>) -> bool,
    /// On a surface, the closest point of the surface (copies are laid in tangent planes).
    settle: Option<&'a dyn Fn(&Vector<D>) -> Vector<D>>,
}

/// The copies made so far and the running counts that steer the next one.
struct Running<const D: usize> {
    /// Per tile: (output centre, exemplar origin, representative quadrature point).
    copies: Vec<Option<(Vector<D>, Vector<D>, usize)>>,
    provenance: Provenance,
    /// Points the exemplar's density asks for in the tiles copied so far.
    expected_so_far: f64,
    /// Points the copies placed so far.
    placed_so_far: f64,
    /// Points frozen as copied (without cuts).
    interiors: usize,
}

/// One tile's copy: where it is centred and with which quadrature point's frame.
struct TileCopy<const D: usize> {
    tile: usize,
    /// The representative quadrature point, whose frame the copy takes.
    k: usize,
    centre: Vector<D>,
    scale: f64,
    /// Half the tile's side per axis, in exemplar units.
    half: Vector<D>,
    /// How far from its origin the copy reaches, per axis, in exemplar units.
    reach: Vector<D>,
}

impl<const D: usize> Quilt<'_, D> {
    /// Per tile, its first fill point (none for tiles outside the domain) and what the exemplar's
    /// density asks for in it (the part of the tile inside Ω).
    fn tile_shares(&self, fill: &[usize]) -> (Vec<Option<usize>>, Vec<f64>) {
        let quadrature = self.quadrature;
        let mut representative: Vec<Option<usize>> = vec![None; self.tiling.total];
        let mut expected: Vec<f64> = vec![0.0; self.tiling.total];
        let cell = quadrature.spacing();
        for &k in fill {
            let t = self.tiling.tile_of(&quadrature.points[k]);
            representative[t].get_or_insert(k);
            expected[t] +=
                cell.powi(D as i32) / quadrature.density_scale(k) * self.exemplar.density() * self.layout.node_share;
        }
        (representative, expected)
    }

    /// On a surface: per tile, the fill point nearest its centre and its squared distance.
    fn nearest_to_centres(&self, fill: &[usize]) -> Vec<(usize, f64)> {
        let mut nearest = vec![(usize::MAX, f64::INFINITY); self.tiling.total];
        for &k in fill {
            let t = self.tiling.tile_of(&self.quadrature.points[k]);
            let d2 = linear::norm2(&linear::sub(&self.quadrature.points[k], &self.tiling.centre(t)));
            if d2 < nearest[t].1 {
                nearest[t] = (k, d2);
            }
        }
        nearest
    }

    /// The copy of `tile` centred at `centre` with the frame of quadrature point `k`.
    fn tile_copy(&self, tile: usize, k: usize, centre: Vector<D>) -> TileCopy<D> {
        let s = self.quadrature.scale[k];
        let half: Vector<D> = std::array::from_fn(|a| 0.5 * self.tiling.sides[a] / s);
        // On a surface a copy reaches the whole tile from its centre's tangent plane (half the
        // tile's diagonal) and keeps only the points that land in the tile, since copies centred
        // off the tiles' centres would otherwise overlap (+27 % points on the bull).
        let reach: Vector<D> =
            if self.layout.on_surface { [0.5 * 3f64.sqrt() * self.layout.side / s; D] } else { half };
        TileCopy { tile, k, centre, scale: s, half, reach }
    }

    /// Whether a copied point at `x` is kept in its tile (on a surface, only those landing in it).
    fn in_tile(&self, copy: &TileCopy<D>, x: &Vector<D>) -> bool {
        !self.layout.on_surface || self.tiling.tile_of(x) == copy.tile
    }

    /// Where a copy's point laid at `x` lands, if it is kept: on a surface, the end of a walk
    /// along the surface from the copy's centre towards `x` ([`walk_on_surface`]), kept when it
    /// lands in the copy's tile and in Ω. The tangent plane departs from a curved surface by
    /// `u²/2R` at `u` from the copy's centre, far more than the thin band Ω is there: points
    /// laid in the plane and tested as they were were dropped beyond about 19 units on a tube of
    /// radius 60, and patch initialization placed 82 % of a torus's points.
    fn landing(&self, copy: &TileCopy<D>, x: &Vector<D>) -> Option<Vector<D>> {
        let x = match self.settle {
            Some(settle) => walk_on_surface(settle, &copy.centre, x, self.exemplar.spacing * copy.scale),
            None => *x,
        };
        (self.in_tile(copy, &x) && (self.allowed)(&x)).then_some(x)
    }

    /// Patch centres whose patch lies inside the exemplar where possible: `candidates` uniform
    /// draws and, with balancing, as many with one axis at an end of its range (the others
    /// drawn), since only those copy the exemplar's borders, which balancing then can choose.
    fn candidate_origins(&self, copy: &TileCopy<D>, stream: &mut Stream) -> Vec<Vector<D>> {
        let exemplar = self.exemplar;
        let mut candidate = |end: Option<(usize, f64)>| -> Vector<D> {
            std::array::from_fn(|a| {
                let margin = copy.half[a].min(0.5 * self.extent[a]);
                let t = match end {
                    Some((axis, t)) if axis == a => t,
                    _ => stream.random::<f64>(),
                };
                exemplar.low[a] + margin + t * (self.extent[a] - 2.0 * margin).max(0.0)
            })
        };
        let candidates = self.layout.candidates;
        let extra = if self.layout.balance > 0.0 { candidates } else { 0 };
        (0..candidates + extra).map(|n| candidate((n >= candidates).then_some((n % D, (n / D % 2) as f64)))).collect()
    }

    /// Judges each place a tile's copy may come from: (score, drift², overuse), the score being
    /// the seams with the copies around (in squared exemplar spacings, at most 1) plus the drift²
    /// of the running count the copy leaves against `goal` (relative to one tile's `share`), the
    /// overuse how much more often than the mean its points were copied already. Without the
    /// count, an inhomogeneous exemplar is copied too densely: sources are drawn where a whole
    /// patch fits, which over-weights the exemplar's middle (the traced chain runs along its
    /// diagonal: +24 % points in the output).
    fn judge_origins(
        &self,
        copy: &TileCopy<D>,
        places: &[Vector<D>],
        state: &State<D>,
        running: &Running<D>,
        (goal, share): (f64, f64),
    ) -> Vec<(f64, f64, f64)> {
        let (exemplar, quadrature) = (self.exemplar, self.quadrature);
        let (tile, k, centre, s) = (copy.tile, copy.k, copy.centre, copy.scale);
        let frame = Tile {
            centre,
            half: self.tiling.half(),
            band: self.layout.band,
            inverse: &quadrature.inverse[k],
            frame: &quadrature.transform[k],
            scale: s,
        };
        let alive: Vec<Vector<D>> =
            state.positions.iter().zip(&state.alive).filter(|(_, alive)| **alive).map(|(p, _)| *p).collect();
        let placed = Band::gather(&alive, &frame, exemplar.spacing * s);
        let filled = |x: &Vector<D>| {
            let t = self.tiling.tile_of(x);
            t != tile && running.copies[t].is_some() && (self.allowed)(x)
        };
        // The points a copy from `o` would put into Ω, and how often their sources are used.
        let usage = &running.provenance.usage;
        let count = |o: &Vector<D>| {
            let transform = &quadrature.transform[k];
            let (mut count, mut used) = (0.0, 0.0);
            for (e, u) in exemplar.positions.iter().zip(usage) {
                let offset = linear::sub(e, o);
                let x = linear::add(&centre, &linear::mat_vec(transform, &offset));
                // On a surface the laid point is counted where it was laid, not settled on the
                // surface (a closest-point query per point and candidate tripled the
                // initialization's time): the count only steers the choice of origin.
                let kept = self.in_tile(copy, &x) && (self.settle.is_some() || (self.allowed)(&x));
                if (0..D).all(|a| offset[a].abs() <= copy.reach[a]) && kept {
                    count += 1.0;
                    used += u;
                }
            }
            (count, used)
        };
        let mean_usage = usage.iter().sum::<f64>() / usage.len() as f64;
        let judge = |o: &Vector<D>| {
            let seams = if placed.is_empty() {
                0.0
            } else {
                placed.disagreement(
                    &frame,
                    o,
                    &exemplar.positions,
                    &self.exemplar_grid,
                    &exemplar.low,
                    &exemplar.high,
                    exemplar.spacing,
                    &filled,
                ) / (exemplar.spacing * exemplar.spacing)
            };
            // The running count may drift by 20 % (of at least three tiles' shares) for free:
            // sampling control corrects the rest, and a tighter allowance (8 %, 5 %) made the
            // clustered longleaf pines lose their clusters of small trees (patches are chosen for
            // their count), g(r) distance 0.10 -> 0.21-0.37.
            let (count, used) = count(o);
            let drift = ((running.placed_so_far + count - goal).abs() / goal.max(3.0 * share) - 0.2).max(0.0) / 0.05;
            let overuse = if mean_usage > 0.0 && count > 0.0 { used / count / mean_usage - 1.0 } else { 0.0 };
            (seams + drift * drift, drift * drift, overuse)
        };
        places.iter().map(judge).collect()
    }

    /// Copies the exemplar from `origin` into the tile: along cuts (2D free points) or every
    /// point (or element, from its first member) within the copy's reach, the points deeper in
    /// the tile than the seam width frozen.
    fn copy_tile(&self, copy: &TileCopy<D>, origin: Vector<D>, state: &mut State<D>, running: &mut Running<D>) {
        let (exemplar, quadrature) = (self.exemplar, self.quadrature);
        let (k, centre, s) = (copy.k, copy.centre, copy.scale);
        if self.cuts {
            let cut = CutCopy {
                tile: copy.tile as u32,
                frame: CopyFrame {
                    centre,
                    origin,
                    transform: &quadrature.transform[k],
                    inverse: &quadrature.inverse[k],
                    scale: s,
                },
                half: self.tiling.half(),
                band: self.layout.band,
                lower_placed: self.tiling.lower_placed(copy.tile, &running.copies),
            };
            running.placed_so_far += copy_with_cuts(exemplar, state, &mut running.provenance, &cut, self.allowed);
            return;
        }
        for j in 0..exemplar.positions.len() {
            let anchor = match exemplar.element_of[j] {
                None => exemplar.positions[j],
                Some(e) => {
                    // Each element is placed once, from its first member.
                    if exemplar.elements[e as usize].members[0] != j {
                        continue;
                    }
                    exemplar.elements[e as usize].centre
                }
            };
            let offset = linear::sub(&anchor, &origin);
            if (0..D).any(|a| offset[a].abs() > copy.reach[a]) {
                continue;
            }
            let laid = linear::add(&centre, &linear::mat_vec(&quadrature.transform[k], &offset));
            let Some(x) = self.landing(copy, &laid) else { continue };
            let frozen = self
                .layout
                .seam
                .is_some_and(|seam| (0..D).all(|a| (x[a] - centre[a]).abs() < 0.5 * self.tiling.sides[a] - seam));
            let placed = if self.settle.is_some() && exemplar.element_of[j].is_none() {
                state.add_free(x, exemplar.feature(j), frozen);
                1
            } else {
                let frame = &quadrature.transform[k];
                let placement = Placement { anchor: &centre, origin: &origin, frame, scale: s, extra: None };
                place(exemplar, state, j, &placement, self.allowed, frozen)
            };
            running.placed_so_far += placed as f64;
            running.provenance.usage[j] += placed as f64;
            if frozen {
                running.interiors += placed;
            }
        }
    }
}

/// The point reached by walking along a surface from `start` (on it) towards `target` (in its
/// tangent plane there) in steps of at most `step`, each step moved onto the surface by `settle`
/// and the next one taken along the last step's chord: an approximate exponential map, which keeps
/// the distance from `start` along the surface within a few percent of `|target − start|` where a
/// single closest-point projection squeezes it (a tube of radius 40 took a patch's 58 units out
/// to 38, and its copies placed 20 % too many points).
fn walk_on_surface<const D: usize>(
    settle: &dyn Fn(&Vector<D>) -> Vector<D>,
    start: &Vector<D>,
    target: &Vector<D>,
    step: f64,
) -> Vector<D> {
    let offset = linear::sub(target, start);
    let length = linear::norm2(&offset).sqrt();
    let steps = (length / step.max(1e-12)).ceil().clamp(1.0, 64.0) as usize;
    let stride = length / steps as f64;
    let mut direction = linear::scale(&offset, 1.0 / length.max(1e-300));
    let mut here = *start;
    for _ in 0..steps {
        let next = settle(&linear::add(&here, &linear::scale(&direction, stride)));
        let chord = linear::sub(&next, &here);
        let chord_length = linear::norm2(&chord).sqrt();
        if chord_length > 1e-12 * stride {
            direction = linear::scale(&chord, 1.0 / chord_length);
        }
        here = next;
    }
    here
}

/// Image quilting's rule (Efros and Freeman 2001: any block within a tolerance of the best error):
/// every place whose score is within `balance` of the best is as good, and of those the least
/// copied so far is taken. Adding the overuse to the score instead let it outweigh the seams of
/// lattices (brushed hex structure: NN distance +8 % over 100 seeds). The tolerance is for the
/// seams: a place must not drift the count more than the best. Returns the chosen index.
fn pick_origin(judged: &[(f64, f64, f64)], balance: f64) -> usize {
    let (best, best_drift) = judged.iter().fold((f64::INFINITY, 0.0), |b, j| if j.0 < b.0 { (j.0, j.1) } else { b });
    let good_enough = |&(score, drift, _): &(f64, f64, f64)| {
        balance > 0.0 && score <= best * (1.0 + balance) + 1e-3 && drift <= best_drift
    };
    let mut choice = 0;
    for (n, judgement) in judged.iter().enumerate() {
        let chosen = &judged[choice];
        let better =
            if good_enough(chosen) { good_enough(judgement) && judgement.2 < chosen.2 } else { judgement.0 < chosen.0 };
        if better {
            choice = n;
        }
    }
    choice
}

/// After cut copies: a point stays as copied (frozen) unless a point of another copy lies within
/// `seam` of it, so that only the points where two copies meet move; drops the points the cuts
/// replaced. Returns the number of frozen points.
///
/// Where the cuts run through empty space (a clustered pattern), few points have another copy's
/// point that close, and sampling control, which moves and removes only movable points, could not
/// correct the count of the copies. So when the copies miss the expected count (`expected.0`) by
/// more than the count tolerance (`expected.1`; 5 % before the tolerance became 2 %), the reach
/// grows (up to 4 × `seam`) until three times the surplus or deficit is movable. Freezing by this rule instead of by the distance to the cut gave lower
/// nearest-neighbour distances on 8 of 11 corpus cases over three seeds (see docs/points.md).
fn freeze_interiors<const D: usize>(
    state: &mut State<D>,
    copy_of: &[u32],
    first_copy: usize,
    seam: Option<f64>,
    expected: (f64, f64),
) -> usize {
    let (expected, tolerance) = expected;
    let mut frozen = 0;
    if let Some(seam) = seam {
        let copied: Vec<usize> = (first_copy..state.positions.len()).filter(|&i| state.alive[i]).collect();
        let points: Vec<Vector<D>> = copied.iter().map(|&i| state.positions[i]).collect();
        let miss = (copied.len() as f64 - expected).abs() - tolerance * expected;
        let needed = if miss > 0.0 { (3.0 * miss).ceil() as usize } else { 0 };
        let mut movable = vec![false; copied.len()];
        for factor in [1.0, 1.5, 2.0, 3.0, 4.0] {
            let reach = factor * seam;
            let grid = StaticGrid::new(&points, reach);
            for (n, &i) in copied.iter().enumerate() {
                grid.for_each_within(&points[n], reach, |m, _, _| {
                    movable[n] |= copy_of[copied[m] - first_copy] != copy_of[i - first_copy];
                });
            }
            if movable.iter().filter(|m| **m).count() >= needed {
                break;
            }
        }
        for (n, &i) in copied.iter().enumerate() {
            if !movable[n] {
                state.units[state.unit_of[i] as usize].frozen = true;
                frozen += 1;
            }
        }
    }
    state.compact();
    frozen
}
