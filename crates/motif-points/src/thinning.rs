//! Thinning: the pair-statistics refinement's removal of a surplus over the exemplar's density,
//! where removing points helps the statistics most.

use rayon::prelude::*;

use super::{REACH, Target, evaluate, kernel, rings, touched, usable_rings};
use crate::grid::StaticGrid;
use crate::linear::{self, Vector};

/// Chooses up to `surplus` movable points to remove, each for how much its removal alone changes
/// the pair term, least first; the first `required` go in any case, the others only in batches that
/// lower the whole energy. Returns the removed indices, ascending.
pub(crate) fn thin<const D: usize>(
    target: &Target,
    positions: &[Vector<D>],
    movable: &[bool],
    depth: &(dyn Fn(&Vector<D>) -> f64 + Sync),
    volume: f64,
    required: usize,
    surplus: usize,
) -> Vec<usize> {
    let bins = rings();
    let ramp = target.ramp;
    let reach = REACH + ramp;
    let density_ratio = |n: usize| n as f64 / volume.max(1e-300) / target.density;
    // `kept[i]`: the original index of the i-th remaining point.
    let mut kept: Vec<usize> = (0..positions.len()).collect();
    let mut points = positions.to_vec();
    let mut depths: Vec<f64> = points.par_iter().map(depth).collect();
    let mut current = evaluate(target, &points, &depths, density_ratio(points.len()), None);
    let (mut removed, mut batch) = (0, surplus.div_ceil(4).max(1));
    while removed < surplus && batch > 0 {
        let ratio_after = density_ratio(points.len().saturating_sub(1));
        let usable: Vec<usize> = depths.iter().map(|&d| usable_rings(d, ramp)).collect();
        let grid = StaticGrid::new(&points, reach);
        let mut gains: Vec<(f64, usize)> = (0..points.len())
            .into_par_iter()
            .filter(|&i| movable[kept[i]])
            .map(|i| {
                // The pairs that go with point i: as a centre, and as a neighbour of other centres.
                let mut lost = vec![0.0; bins];
                grid.for_each_within(&points[i], reach, |j, _, d2| {
                    if j != i {
                        let d = d2.sqrt();
                        for b in touched(d, ramp) {
                            lost[b] +=
                                ((b < usable[i]) as usize + (b < usable[j]) as usize) as f64 * kernel(b, d, ramp).0;
                        }
                    }
                });
                let change: f64 = (0..bins)
                    .filter(|&b| current.weights[b] > 0.0)
                    .map(|b| {
                        let centres = current.centres[b] - (b < usable[i]) as usize;
                        let after = current.counts[b] - lost[b] - centres as f64 * target.per_centre[b] * ratio_after;
                        let before = current.counts[b] - current.wanted[b];
                        current.weights[b] * (after * after - before * before)
                    })
                    .sum();
                (change, i)
            })
            .filter(|(change, _)| *change < 0.0 || removed < required)
            .collect();
        gains.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        // Removals two spacings apart barely change each other's pairs, so a batch of them is
        // judged by their single changes, then checked as a whole.
        let mut picked: Vec<usize> = Vec::new();
        for &(_, i) in &gains {
            let size =
                if removed < required { (required - removed).min(batch.max(1)) } else { batch.min(surplus - removed) };
            if picked.len() >= size {
                break;
            }
            if picked.iter().all(|&q| linear::norm2(&linear::sub(&points[i], &points[q])) >= 4.0) {
                picked.push(i);
            }
        }
        if picked.is_empty() {
            break;
        }
        picked.sort_unstable();
        let staying: Vec<usize> = (0..points.len()).filter(|i| picked.binary_search(i).is_err()).collect();
        let next_points: Vec<Vector<D>> = staying.iter().map(|&i| points[i]).collect();
        let next_depths: Vec<f64> = staying.iter().map(|&i| depths[i]).collect();
        let next = evaluate(target, &next_points, &next_depths, density_ratio(next_points.len()), None);
        if next.energy < current.energy || removed < required {
            removed += picked.len();
            kept = staying.iter().map(|&i| kept[i]).collect();
            (points, depths, current) = (next_points, next_depths, next);
        } else {
            batch /= 2;
        }
    }
    let mut gone = vec![true; positions.len()];
    kept.iter().for_each(|&i| gone[i] = false);
    (0..positions.len()).filter(|&i| gone[i]).collect()
}
