//! A plain reference implementation of T (Eq. 5–6) and ∂T/∂x_i, ∂T/∂a_i: one quadrature point at a
//! time, all pairs of the window's output and exemplar points, sequential. Used by the tests (the
//! fast path must agree with it) and for the speed-up figure.

use std::collections::BTreeMap;

use crate::energy::{Evaluation, Problem};
use crate::grid::StaticGrid;
use crate::linear::{self, Vector};
use crate::model::{State, feature_dot};
use crate::quadratic::{AttributeQuadratic, RowQuadratic};

/// T and its gradients, summed quadrature point by quadrature point.
pub(crate) fn evaluate<const D: usize>(
    problem: &Problem<'_, D>,
    state: &State<D>,
    matches: &[Vector<D>],
    features: bool,
) -> Evaluation<D> {
    let kernel = &problem.kernel;
    let quadrature = problem.quadrature;
    let exemplar = problem.exemplar;
    let n = state.positions.len();
    let channels = state.channels;
    let grid = StaticGrid::new(&state.positions, kernel.gather);
    let mut energy = 0.0;
    let mut gradient = vec![[0.0; D]; n];
    // The attribute form's rows: A_ij per ordered pair, B_i per channel.
    let mut pairs: Vec<BTreeMap<u32, f64>> = vec![BTreeMap::new(); if features { n } else { 0 }];
    let mut linear_terms = vec![0.0; if features { n * channels } else { 0 }];
    let mut constant = 0.0;
    let mut out: Vec<(usize, Vector<D>)> = Vec::new();
    let mut ex: Vec<(usize, Vector<D>)> = Vec::new();
    for k in 0..quadrature.len() {
        let q = quadrature.points[k];
        let m = matches[k];
        let transform = &quadrature.transform[k];
        out.clear();
        grid.for_each_within(&q, kernel.gather, |i, p, _| out.push((i, linear::sub(p, &q))));
        ex.clear();
        problem.exemplar_grid.for_each_within(&m, kernel.gather / quadrature.scale[k], |j, e, _| {
            let v = linear::mat_vec(transform, &linear::sub(e, &m));
            if quadrature.inside(&linear::add(&q, &v)) {
                ex.push((j, v));
            }
        });
        // Σ_ij a_i·a_j K(u_i, u_j)
        for &(i, ui) in &out {
            for &(j, uj) in &out {
                if let Some((value, du, dv)) = kernel.eval(&ui, &uj) {
                    let w = feature_dot(state.feature(i), state.feature(j));
                    energy += w * value;
                    linear::axpy(&mut gradient[i], w, &du);
                    linear::axpy(&mut gradient[j], w, &dv);
                    if features {
                        *pairs[i].entry(j as u32).or_insert(0.0) += value;
                    }
                }
            }
        }
        // −2 Σ_ij a_i·b_j K(u_i, v_j)
        for &(i, ui) in &out {
            for &(j, vj) in &ex {
                if let Some((value, du, _)) = kernel.eval(&ui, &vj) {
                    let w = feature_dot(state.feature(i), exemplar.feature(j));
                    energy -= 2.0 * w * value;
                    linear::axpy(&mut gradient[i], -2.0 * w, &du);
                    if features {
                        for c in 0..channels {
                            linear_terms[i * channels + c] += exemplar.feature(j)[c] * value;
                        }
                    }
                }
            }
        }
        // Σ_ij b_i·b_j K(v_i, v_j)
        for &(i, vi) in &ex {
            for &(j, vj) in &ex {
                if let Some((value, _, _)) = kernel.eval(&vi, &vj) {
                    let term = feature_dot(exemplar.feature(i), exemplar.feature(j)) * value;
                    energy += term;
                    constant += term;
                }
            }
        }
    }
    let quadratic = features.then(|| {
        let rows = pairs
            .into_iter()
            .zip(linear_terms.chunks(channels.max(1)))
            .map(|(row, linear)| RowQuadratic { coefficients: row.into_iter().collect(), linear: linear.to_vec() })
            .collect();
        AttributeQuadratic::from_rows(rows, channels, constant)
    });
    Evaluation { energy, positions: gradient, quadratic }
}
