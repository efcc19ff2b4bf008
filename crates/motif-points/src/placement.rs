//! Placing exemplar points and elements into the output, and random initialization (§5.2):
//! random points at the exemplar's density.

use motif_core::SeedStreams;
use motif_core::math;
use motif_core::random::Rng;

use crate::domain::Quadrature;
use crate::linear::{self, Matrix, Vector};
use crate::model::{Exemplar, Rigid, State};

/// A random rotation (uniform angle in 2D; uniform axis and angle in 3D).
fn random_rotation<const D: usize>(stream: &mut impl Rng) -> Matrix<D> {
    let angle = stream.random::<f64>() * std::f64::consts::TAU;
    if D == 2 {
        return linear::rotation_xy::<D>(angle);
    }
    let z: f64 = stream.random::<f64>() * 2.0 - 1.0;
    let phi = stream.random::<f64>() * std::f64::consts::TAU;
    let r = (1.0 - z * z).max(0.0).sqrt();
    linear::rotation_axis_angle::<D>([r * math::cos(phi), r * math::sin(phi), z], angle)
}

/// Where a placement puts exemplar points: `x = anchor + frame (e − origin)`, the frame's scale
/// `scale`; elements get `extra` applied to their orientation.
pub(crate) struct Placement<'a, const D: usize> {
    pub anchor: &'a Vector<D>,
    pub origin: &'a Vector<D>,
    pub frame: &'a Matrix<D>,
    pub scale: f64,
    pub extra: Option<Matrix<D>>,
}

/// Adds exemplar point `j` (or its whole element) mapped by `placement` where `allowed`. Returns
/// the number of points added.
pub(crate) fn place<const D: usize>(
    exemplar: &Exemplar<D>,
    state: &mut State<D>,
    j: usize,
    placement: &Placement<'_, D>,
    allowed: &dyn Fn(&Vector<D>) -> bool,
    frozen: bool,
) -> usize {
    let Placement { anchor, origin, frame, scale, extra } = *placement;
    match exemplar.element_of[j] {
        None => {
            let x = linear::add(anchor, &linear::mat_vec(frame, &linear::sub(&exemplar.positions[j], origin)));
            if !allowed(&x) {
                return 0;
            }
            state.add_free(x, exemplar.feature(j), frozen);
            1
        }
        Some(element) => {
            let source = &exemplar.elements[element as usize];
            let centre = linear::add(anchor, &linear::mat_vec(frame, &linear::sub(&source.centre, origin)));
            if !allowed(&centre) {
                return 0;
            }
            let pure: Matrix<D> = std::array::from_fn(|r| std::array::from_fn(|c| frame[r][c] / scale));
            let rotation = match extra {
                Some(extra) => linear::mat_mul(&pure, &extra),
                None => pure,
            };
            let body: Vec<Vector<D>> = source
                .members
                .iter()
                .map(|&p| linear::scale(&linear::sub(&exemplar.positions[p], &source.centre), scale))
                .collect();
            let mut features = Vec::new();
            for &p in &source.members {
                features.extend_from_slice(exemplar.feature(p));
            }
            state.add_rigid(Rigid { centre, rotation, body }, &features, 0, frozen);
            source.members.len()
        }
    }
}

/// Random initialization: as many points as the exemplar's density asks for over the quadrature
/// points `fill` (each stands for `spacing^D` of volume), at uniformly random positions.
pub(crate) fn random<const D: usize>(
    exemplar: &Exemplar<D>,
    quadrature: &Quadrature<D>,
    fill: &[usize],
    state: &mut State<D>,
    streams: &SeedStreams,
    allowed: &dyn Fn(&Vector<D>) -> bool,
    node_share: f64,
) {
    if fill.is_empty() {
        return;
    }
    let h = quadrature.spacing();
    let density = exemplar.density() * node_share;
    let target: f64 = fill.iter().map(|&k| h.powi(D as i32) * density / quadrature.density_scale(k)).sum();
    let target = target.round() as usize;
    let mut placed = 0;
    let mut attempt = 0u64;
    while placed < target && attempt < 20 * target as u64 + 100 {
        let mut stream = streams.stream("initial point", attempt);
        attempt += 1;
        let k = fill[stream.random_range(0..fill.len())];
        let x: Vector<D> = std::array::from_fn(|a| quadrature.points[k][a] + (stream.random::<f64>() - 0.5) * h);
        let j = stream.random_range(0..exemplar.positions.len());
        let extra = random_rotation::<D>(&mut stream);
        // Map e_j onto x (the frame orients elements; a random extra turn randomizes them).
        let placement = Placement {
            anchor: &x,
            origin: &exemplar.positions[j],
            frame: &quadrature.transform[k],
            scale: quadrature.scale[k],
            extra: Some(extra),
        };
        placed += place(exemplar, state, j, &placement, allowed, false);
    }
}
