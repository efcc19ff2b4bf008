//! One tile's copy joined to the copies around it along minimum error boundary cuts (2D free
//! points; see `crate::cut`), and what the copies made so far came from.

use crate::cut::{Cut, Overlap};
use crate::linear::{self, Matrix, Vector};
use crate::model::{Exemplar, State};
use crate::placement::{Placement, place};

/// What the copies made so far came from, per copied point and per exemplar point.
pub(crate) struct Provenance {
    /// The index of the first point the copies placed.
    pub(crate) first_copy: usize,
    /// The copy (tile) each point placed since the first copy came from.
    pub(crate) copy_of: Vec<u32>,
    /// The exemplar point each point placed since the first copy is a copy of (2D free points).
    pub(crate) source_of: Vec<u32>,
    /// How many living output points are copies of each exemplar point.
    pub(crate) usage: Vec<f64>,
}

/// Where a tile's copy comes from: `x = centre + transform (e − origin)`.
pub(crate) struct CopyFrame<'a, const D: usize> {
    pub(crate) centre: Vector<D>,
    pub(crate) origin: Vector<D>,
    pub(crate) transform: &'a Matrix<D>,
    pub(crate) inverse: &'a Matrix<D>,
    pub(crate) scale: f64,
}

/// One tile's copy joined along cuts: its frame, its size and the bands on its copied lower sides.
pub(crate) struct CutCopy<'a, const D: usize> {
    pub(crate) tile: u32,
    pub(crate) frame: CopyFrame<'a, D>,
    /// Half the tile's side per axis.
    pub(crate) half: Vector<D>,
    /// Width of the bands where the copy overlaps its neighbours.
    pub(crate) band: f64,
    /// Per axis, whether the lower neighbour is copied (and the copy extends into a band there).
    pub(crate) lower_placed: [bool; D],
}

/// The first two coordinates of a point (the plane of cut copies).
fn flat<const D: usize>(p: &Vector<D>) -> [f64; 2] {
    [p[0], p[1]]
}

/// Copies the exemplar into one tile (2D, free points) and into the bands on its already copied
/// lower sides, replacing there the points beyond the minimum error boundary cut. Returns the
/// change in the point count.
pub(crate) fn copy_with_cuts<const D: usize>(
    exemplar: &Exemplar<D>,
    state: &mut State<D>,
    provenance: &mut Provenance,
    cut: &CutCopy<'_, D>,
    allowed: &dyn Fn(&Vector<D>) -> bool,
) -> f64 {
    let frame = &cut.frame;
    let low: [f64; 2] = std::array::from_fn(|a| frame.centre[a] - cut.half[a]);
    let high: [f64; 2] = std::array::from_fn(|a| frame.centre[a] + cut.half[a]);
    let extension: [f64; 2] = std::array::from_fn(|a| if cut.lower_placed[a] { cut.band } else { 0.0 });
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
    let cell = cut.band / 8.0;
    let reach = exemplar.spacing * frame.scale;
    let overlaps = [
        cut.lower_placed[0].then_some(Overlap {
            across: 0,
            along_range: (low[1], high[1]),
            across_range: (low[0] - cut.band, low[0]),
            cell,
            reach,
        }),
        cut.lower_placed[1].then_some(Overlap {
            across: 1,
            along_range: (low[0] - extension[0], high[0]),
            across_range: (low[1] - cut.band, low[1]),
            cell,
            reach,
        }),
    ];
    let mut cuts = Vec::new();
    let mut removed = 0usize;
    for overlap in overlaps.into_iter().flatten() {
        let (boundary, killed) = cut_overlap(exemplar, state, provenance, frame, &overlap, &copy);
        removed += killed;
        cuts.push(boundary);
    }
    let mut added = 0usize;
    for (j, x) in copy {
        let p = flat(&x);
        let keep = match cuts.iter().find(|cut| cut.contains(&p)) {
            Some(cut) => cut.on_new_side(&p),
            None => (0..2).all(|a| p[a] >= low[a]),
        };
        if keep {
            let placement = Placement {
                anchor: &frame.centre,
                origin: &frame.origin,
                frame: frame.transform,
                scale: frame.scale,
                extra: None,
            };
            let placed = place(exemplar, state, j, &placement, allowed, false);
            if placed > 0 {
                provenance.usage[j] += 1.0;
                provenance.source_of.push(j as u32);
            }
            added += placed;
        }
    }
    provenance.copy_of.resize(state.positions.len() - provenance.first_copy, cut.tile);
    added as f64 - removed as f64
}

/// Cuts one band where a new copy overlaps the copies placed: the minimum error boundary between
/// the placed points and the copy's, the copy's side limited to where its source lies inside the
/// exemplar's window. Removes the placed points on the new side; returns the cut and how many.
fn cut_overlap<const D: usize>(
    exemplar: &Exemplar<D>,
    state: &mut State<D>,
    provenance: &mut Provenance,
    frame: &CopyFrame<'_, D>,
    overlap: &Overlap,
    copy: &[(usize, Vector<D>)],
) -> (Cut, usize) {
    let first_copy = provenance.first_copy;
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
    let mut removed = 0;
    for (&i, p) in placed.iter().zip(&placed_points) {
        if cut.on_new_side(p) {
            state.kill(state.unit_of[i] as usize);
            provenance.usage[provenance.source_of[i - first_copy] as usize] -= 1.0;
            removed += 1;
        }
    }
    (cut, removed)
}
