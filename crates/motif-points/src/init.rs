//! Patch initialization of the output (§5.2): copies of exemplar patches, chosen by quilting and
//! joined along cuts. The solver is meant to reach the same kind of result from these as from
//! random points (`placement::random`).

use motif_core::SeedStreams;
use motif_core::random::Rng;

use crate::cut::Overlap;
use crate::domain::Quadrature;
use crate::grid::StaticGrid;
use crate::linear::{self, Matrix, Vector};
use crate::model::{Exemplar, State};
use crate::placement::place;
use crate::quilting::{Band, Tile};

/// How patch initialization cuts and chooses its patches.
#[derive(Debug, Clone, Copy)]
pub struct PatchLayout {
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
pub struct Copies<const D: usize> {
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
pub fn patches<const D: usize>(
    exemplar: &Exemplar<D>,
    quadrature: &Quadrature<D>,
    fill: &[usize],
    layout: PatchLayout,
    state: &mut State<D>,
    streams: &SeedStreams,
    allowed: &dyn Fn(&Vector<D>) -> bool,
) -> Copies<D> {
    let PatchLayout { side: patch, band, candidates, balance, seam, on_surface, node_share, count_tolerance } = layout;
    let mut sources = vec![None; quadrature.len()];
    if fill.is_empty() {
        return Copies { sources, interiors: 0, usage_variation: 0.0 };
    }
    let points: Vec<Vector<D>> = fill.iter().map(|&k| quadrature.points[k]).collect();
    // The tiles cover the cells the quadrature points stand for, not only the points: tiles from
    // the lowest point left a strip of up to half a cell along the domain's lower borders empty.
    let (low, high) = crate::grid::bounds(&points);
    let half_cell = 0.5 * quadrature.spacing();
    let (low, high): (Vector<D>, Vector<D>) =
        (std::array::from_fn(|a| low[a] - half_cell), std::array::from_fn(|a| high[a] + half_cell));
    let dims: [usize; D] = std::array::from_fn(|a| ((high[a] - low[a]) / patch).ceil().max(1.0) as usize);
    // Tiles fit the domain's extent exactly, each side at most `patch`: a last tile reaching past
    // the domain held only a strip of its copy, which the running count could not steer, and
    // balancing filled such strips from the least-copied places, the exemplar's borders (bei's
    // right edge came out at 1.9× the density). Where fitting would shrink the tiles below three
    // quarters of a patch (a domain under three patches across), they keep the patch's side: on
    // the generated hex lattice, 11.5 × 7.5 with patches of 6, tiles of 3.75 put seams through
    // the lattice every few rows (nearest-neighbour distance 0.01 → 0.10).
    let sides: Vector<D> = std::array::from_fn(|a| {
        let fitted = (high[a] - low[a]) / dims[a] as f64;
        if fitted >= 0.75 * patch { fitted } else { patch }
    });
    let total: usize = dims.iter().product();
    // Which tile each fill point belongs to, so that tiles outside the domain are skipped.
    let tile_of = |x: &Vector<D>| -> usize {
        let mut index = 0;
        for a in (0..D).rev() {
            let c = (((x[a] - low[a]) / sides[a]).floor().max(0.0) as usize).min(dims[a] - 1);
            index = index * dims[a] + c;
        }
        index
    };
    let mut representative: Vec<Option<usize>> = vec![None; total];
    let tile_centre = |tile: usize| -> Vector<D> {
        let mut rest = tile;
        std::array::from_fn(|a| {
            let c = rest % dims[a];
            rest /= dims[a];
            low[a] + (c as f64 + 0.5) * sides[a]
        })
    };
    // On a surface: per tile, the fill point nearest its centre and its squared distance.
    let nearest_to_centre = on_surface.then(|| {
        let mut nearest = vec![(usize::MAX, f64::INFINITY); total];
        for &k in fill {
            let t = tile_of(&quadrature.points[k]);
            let d2 = linear::norm2(&linear::sub(&quadrature.points[k], &tile_centre(t)));
            if d2 < nearest[t].1 {
                nearest[t] = (k, d2);
            }
        }
        nearest
    });
    // What the exemplar's density asks for in each tile (the part of the tile inside Ω).
    let mut expected: Vec<f64> = vec![0.0; total];
    let cell = quadrature.spacing();
    for &k in fill {
        let t = tile_of(&quadrature.points[k]);
        representative[t].get_or_insert(k);
        expected[t] += (cell / quadrature.scale[k]).powi(D as i32) * exemplar.density() * node_share;
    }
    let (mut expected_so_far, mut placed_so_far) = (0.0, 0.0);
    let extent: Vector<D> = std::array::from_fn(|a| exemplar.high[a] - exemplar.low[a]);
    let exemplar_grid = StaticGrid::new(&exemplar.positions, exemplar.spacing);
    let mut interiors = 0;
    // In 2D, copies of free points overlap the placed ones by a band and are joined along a
    // minimum error boundary cut (`crate::cut`); elsewhere they meet at the tile borders.
    let cuts = D == 2 && exemplar.element_of.iter().all(Option::is_none);
    let first_copy = state.positions.len();
    let mut provenance =
        Provenance { copy_of: Vec::new(), source_of: Vec::new(), usage: vec![0.0; exemplar.positions.len()] };
    // Per tile: (output centre, exemplar origin, representative quadrature point).
    let mut copies: Vec<Option<(Vector<D>, Vector<D>, usize)>> = vec![None; total];
    for (tile, k) in representative.iter().enumerate() {
        let Some(mut k) = *k else { continue };
        let mut stream = streams.stream("initial patch", tile as u64);
        let mut centre = tile_centre(tile);
        if let Some(nearest) = &nearest_to_centre {
            k = nearest[tile].0;
            centre = quadrature.points[k];
        }
        let s = quadrature.scale[k];
        let half: Vector<D> = std::array::from_fn(|a| 0.5 * sides[a] / s);
        // On a surface a copy reaches the whole tile from its centre's tangent plane (half the
        // tile's diagonal) and keeps only the points that land in the tile, since copies centred
        // off the tiles' centres would otherwise overlap (+27 % points on the bull).
        let reach: Vector<D> = if on_surface { [0.5 * 3f64.sqrt() * patch / s; D] } else { half };
        let in_tile = |x: &Vector<D>| !on_surface || tile_of(x) == tile;
        // Patch centres whose patch lies inside the exemplar where possible: uniform draws and,
        // with balancing, as many with one axis at an end of its range (the others drawn), since
        // only those copy the exemplar's borders, which balancing then can choose.
        let mut candidate = |end: Option<(usize, f64)>| -> Vector<D> {
            std::array::from_fn(|a| {
                let margin = half[a].min(0.5 * extent[a]);
                let t = match end {
                    Some((axis, t)) if axis == a => t,
                    _ => stream.random::<f64>(),
                };
                exemplar.low[a] + margin + t * (extent[a] - 2.0 * margin).max(0.0)
            })
        };
        let frame = Tile {
            centre,
            half: std::array::from_fn(|a| 0.5 * sides[a]),
            band,
            inverse: &quadrature.inverse[k],
            frame: &quadrature.transform[k],
            scale: s,
        };
        let alive: Vec<Vector<D>> =
            state.positions.iter().zip(&state.alive).filter(|(_, alive)| **alive).map(|(p, _)| *p).collect();
        let placed = Band::gather(&alive, &frame, exemplar.spacing * s);
        let filled = |x: &Vector<D>| {
            let t = tile_of(x);
            t != tile && copies[t].is_some() && allowed(x)
        };
        // The points a copy from `o` would put into Ω, and how often their sources are used.
        let usage = &provenance.usage;
        let count = |o: &Vector<D>| {
            let transform = &quadrature.transform[k];
            let (mut count, mut used) = (0.0, 0.0);
            for (e, u) in exemplar.positions.iter().zip(usage) {
                let offset = linear::sub(e, o);
                let x = linear::add(&centre, &linear::mat_vec(transform, &offset));
                if (0..D).all(|a| offset[a].abs() <= reach[a]) && in_tile(&x) && allowed(&x) {
                    count += 1.0;
                    used += u;
                }
            }
            (count, used)
        };
        let mean_usage = usage.iter().sum::<f64>() / usage.len() as f64;
        // A candidate is judged on its seams (in squared exemplar spacings, at most 1) and on the
        // running count it leaves, relative to one tile's share. Without the count, an
        // inhomogeneous exemplar is copied too densely: sources are drawn where a whole patch
        // fits, which over-weights the exemplar's middle (the traced chain runs along its
        // diagonal: +24 % points in the output).
        let goal = expected_so_far + expected[tile];
        let share = expected[tile].max(1.0);
        let judge = |o: &Vector<D>| {
            let seams = if placed.is_empty() {
                0.0
            } else {
                placed.disagreement(
                    &frame,
                    o,
                    &exemplar.positions,
                    &exemplar_grid,
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
            let drift = ((placed_so_far + count - goal).abs() / goal.max(3.0 * share) - 0.2).max(0.0) / 0.05;
            let overuse = if mean_usage > 0.0 && count > 0.0 { used / count / mean_usage - 1.0 } else { 0.0 };
            (seams + drift * drift, drift * drift, overuse)
        };
        // With balancing, `candidates` more places each put one axis at an end of its range.
        let extra = if balance > 0.0 { candidates } else { 0 };
        let places: Vec<Vector<D>> = (0..candidates + extra)
            .map(|n| candidate((n >= candidates).then_some((n % D, (n / D % 2) as f64))))
            .collect();
        let judged: Vec<(f64, f64, f64)> = places.iter().map(&judge).collect();
        // Image quilting's rule (Efros and Freeman 2001: any block within a tolerance of the best
        // error): every place whose score is within `balance` of the best is as good, and of
        // those the least copied so far is taken. Adding the overuse to the score instead let it
        // outweigh the seams of lattices (brushed hex structure: NN distance +8 % over 100 seeds).
        // The tolerance is for the seams: a place must not drift the count more than the best.
        let (best, best_drift) =
            judged.iter().fold((f64::INFINITY, 0.0), |b, j| if j.0 < b.0 { (j.0, j.1) } else { b });
        let good_enough = |&(score, drift, _): &(f64, f64, f64)| {
            balance > 0.0 && score <= best * (1.0 + balance) + 1e-3 && drift <= best_drift
        };
        let mut choice = 0;
        for (n, judgement) in judged.iter().enumerate() {
            let chosen = &judged[choice];
            let better = if good_enough(chosen) {
                good_enough(judgement) && judgement.2 < chosen.2
            } else {
                judgement.0 < chosen.0
            };
            if better {
                choice = n;
            }
        }
        let origin = places[choice];
        expected_so_far = goal;
        copies[tile] = Some((centre, origin, k));
        if cuts {
            // The tile's lower neighbours along each axis, when already copied.
            let mut rest = tile;
            let mut stride = 1;
            let lower_placed: [bool; D] = std::array::from_fn(|a| {
                let c = rest % dims[a];
                rest /= dims[a];
                let placed = c > 0 && copies[tile - stride].is_some();
                stride *= dims[a];
                placed
            });
            let change = copy_with_cuts(
                exemplar,
                state,
                &mut provenance,
                tile as u32,
                first_copy,
                CopyFrame {
                    centre,
                    origin,
                    transform: &quadrature.transform[k],
                    inverse: &quadrature.inverse[k],
                    scale: s,
                },
                (std::array::from_fn(|a| 0.5 * sides[a]), band),
                lower_placed,
                allowed,
            );
            placed_so_far += change;
            continue;
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
            if (0..D).any(|a| offset[a].abs() > reach[a]) {
                continue;
            }
            let x = linear::add(&centre, &linear::mat_vec(&quadrature.transform[k], &offset));
            if !in_tile(&x) {
                continue;
            }
            let frozen = seam.is_some_and(|seam| (0..D).all(|a| (x[a] - centre[a]).abs() < 0.5 * sides[a] - seam));
            let placed =
                place(exemplar, state, j, &centre, &origin, &quadrature.transform[k], s, None, allowed, frozen);
            placed_so_far += placed as f64;
            provenance.usage[j] += placed as f64;
            if frozen {
                interiors += placed;
            }
        }
    }
    if cuts {
        let expected = (expected.iter().sum(), count_tolerance);
        interiors = freeze_interiors(state, &provenance.copy_of, first_copy, seam, expected);
    }
    for &k in fill {
        if let Some((centre, origin, representative)) = copies[tile_of(&quadrature.points[k])] {
            let offset = linear::sub(&quadrature.points[k], &centre);
            sources[k] = Some(linear::add(&origin, &linear::mat_vec(&quadrature.inverse[representative], &offset)));
        }
    }
    let usage = &provenance.usage;
    let mean = usage.iter().sum::<f64>() / usage.len() as f64;
    let variance = usage.iter().map(|u| (u - mean) * (u - mean)).sum::<f64>() / usage.len() as f64;
    let usage_variation = if mean > 0.0 { variance.sqrt() / mean } else { 0.0 };
    Copies { sources, interiors, usage_variation }
}

/// What the copies made so far came from, per copied point and per exemplar point.
struct Provenance {
    /// The copy (tile) each point placed since the first copy came from.
    copy_of: Vec<u32>,
    /// The exemplar point each point placed since the first copy is a copy of (2D free points).
    source_of: Vec<u32>,
    /// How many living output points are copies of each exemplar point.
    usage: Vec<f64>,
}

/// Where a tile's copy comes from: `x = centre + transform (e − origin)`.
struct CopyFrame<'a, const D: usize> {
    centre: Vector<D>,
    origin: Vector<D>,
    transform: &'a Matrix<D>,
    inverse: &'a Matrix<D>,
    scale: f64,
}

/// Copies the exemplar into one tile (2D, free points) and into the bands of width `sizes.1` on
/// its already copied lower sides (`lower_placed`), replacing there the points beyond the minimum
/// error boundary cut. `sizes.0` is half the tile's side per axis. Returns the change in the point
/// count.
#[allow(
    clippy::too_many_arguments,
    reason = "one tile copy of the quilted start; state, provenance and frame are borrowed apart"
)]
fn copy_with_cuts<const D: usize>(
    exemplar: &Exemplar<D>,
    state: &mut State<D>,
    provenance: &mut Provenance,
    tile: u32,
    first_copy: usize,
    frame: CopyFrame<'_, D>,
    sizes: (Vector<D>, f64),
    lower_placed: [bool; D],
    allowed: &dyn Fn(&Vector<D>) -> bool,
) -> f64 {
    let (half, band) = sizes;
    let flat = |p: &Vector<D>| [p[0], p[1]];
    let low: [f64; 2] = std::array::from_fn(|a| frame.centre[a] - half[a]);
    let high: [f64; 2] = std::array::from_fn(|a| frame.centre[a] + half[a]);
    let extension: [f64; 2] = std::array::from_fn(|a| if lower_placed[a] { band } else { 0.0 });
    // The new copy over the tile and its bands.
    let copy: Vec<(usize, Vector<D>)> = (0..exemplar.positions.len())
        .filter_map(|j| {
            let x = linear::add(
                &frame.centre,
                &linear::mat_vec(frame.transform, &linear::sub(&exemplar.positions[j], &frame.origin)),
            );
            let inside = (0..2).all(|a| x[a] >= low[a] - extension[a] && x[a] < high[a]);
            (inside && allowed(&x)).then_some((j, x))
        })
        .collect();
    // One band per copied lower side; the horizontal one also covers the corner.
    let cell = band / 8.0;
    let reach = exemplar.spacing * frame.scale;
    let overlaps = [
        lower_placed[0].then_some(Overlap {
            across: 0,
            along_range: (low[1], high[1]),
            across_range: (low[0] - band, low[0]),
            cell,
            reach,
        }),
        lower_placed[1].then_some(Overlap {
            across: 1,
            along_range: (low[0] - extension[0], high[0]),
            across_range: (low[1] - band, low[1]),
            cell,
            reach,
        }),
    ];
    let mut cuts = Vec::new();
    let mut removed = 0usize;
    for overlap in overlaps.into_iter().flatten() {
        let placed: Vec<usize> = (first_copy..state.positions.len())
            .filter(|&i| state.alive[i] && overlap.contains(&flat(&state.positions[i])))
            .collect();
        let placed_points: Vec<[f64; 2]> = placed.iter().map(|&i| flat(&state.positions[i])).collect();
        let copy_points: Vec<[f64; 2]> = copy.iter().map(|(_, x)| flat(x)).filter(|x| overlap.contains(x)).collect();
        // Where the copy's source lies inside the exemplar's window.
        let covered = |p: &[f64; 2]| {
            let mut offset = [0.0; D];
            offset[0] = p[0] - frame.centre[0];
            offset[1] = p[1] - frame.centre[1];
            let source = linear::add(&frame.origin, &linear::mat_vec(frame.inverse, &offset));
            (0..D).all(|a| source[a] >= exemplar.window_low[a] && source[a] <= exemplar.window_high[a])
        };
        let cut = overlap.minimum_cut(&placed_points, &copy_points, &covered);
        for (&i, p) in placed.iter().zip(&placed_points) {
            if cut.on_new_side(p) {
                state.kill(state.unit_of[i] as usize);
                provenance.usage[provenance.source_of[i - first_copy] as usize] -= 1.0;
                removed += 1;
            }
        }
        cuts.push(cut);
    }
    let mut added = 0usize;
    for (j, x) in copy {
        let p = flat(&x);
        let keep = match cuts.iter().find(|cut| cut.contains(&p)) {
            Some(cut) => cut.on_new_side(&p),
            None => (0..2).all(|a| p[a] >= low[a]),
        };
        if keep {
            let placed = place(
                exemplar,
                state,
                j,
                &frame.centre,
                &frame.origin,
                frame.transform,
                frame.scale,
                None,
                allowed,
                false,
            );
            if placed > 0 {
                provenance.usage[j] += 1.0;
                provenance.source_of.push(j as u32);
            }
            added += placed;
        }
    }
    provenance.copy_of.resize(state.positions.len() - first_copy, tile);
    added as f64 - removed as f64
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
