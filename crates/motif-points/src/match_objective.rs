//! `S_k` as a function of the exemplar location `m_k`: the local step's objective (§5.1, Eq. 5)
//! and its gradient ∂S/∂m_k, on the exact exemplar window (the matching searches a rasterized
//! copy first; see `matching`). Beside `energy`, which holds the global step's `T` and its
//! gradients.

use motif_core::math;

use crate::energy::Problem;
use crate::grid::StaticGrid;
use crate::linear::{self, Vector};
use crate::model::{State, feature_dot};
use crate::params::Window;

impl<const D: usize> Problem<'_, D> {
    /// `C_k(m) = Σ b_j·b_j' K(v_j, v_j')` over the exemplar window at `m` (the third term of Eq. 5),
    /// adding `∂C_k/∂m` to `gradient` when given.
    pub(crate) fn exemplar_self(&self, k: usize, m: &Vector<D>, gradient: Option<&mut Vector<D>>) -> f64 {
        let q = self.quadrature.points[k];
        // Interior windows need no masking.
        let mask = if self.interior[k] { None } else { Some(&q) };
        self.exemplar_self_with(&self.quadrature.transform[k], self.quadrature.scale[k], m, mask, gradient)
    }

    /// [`Problem::exemplar_self`] for an explicit frame `transform = sR`.
    pub(crate) fn exemplar_self_with(
        &self,
        transform: &crate::linear::Matrix<D>,
        s: f64,
        m: &Vector<D>,
        q: Option<&Vector<D>>,
        mut gradient: Option<&mut Vector<D>>,
    ) -> f64 {
        let kernel = &self.kernel;
        if kernel.window == Window::Gaussian {
            let found = &mut Vec::new();
            return match q {
                None => self.exemplar_pairs.exemplar_self(kernel, s, m, found, None, gradient),
                Some(q) => {
                    // Exemplar points whose place in the output falls outside Ω do not take part.
                    let positions = &self.exemplar.positions;
                    let keep = |j: usize| {
                        self.quadrature
                            .inside(&linear::add(q, &linear::mat_vec(transform, &linear::sub(&positions[j], m))))
                    };
                    self.exemplar_pairs.exemplar_self(kernel, s, m, found, Some(&keep), gradient)
                }
            };
        }
        if q.is_none() {
            return self.exemplar_self_unmasked(s, m, gradient);
        }
        // Exemplar points whose place in the output falls outside Ω do not take part.
        let inside = |v: &Vector<D>| q.is_none_or(|q| self.quadrature.inside(&linear::add(q, v)));
        let mut total = 0.0;
        let positions = &self.exemplar.positions;
        self.exemplar_grid.for_each_within(m, kernel.gather / s, |j, e, _| {
            let v = linear::mat_vec(transform, &linear::sub(e, m));
            if !inside(&v) {
                return;
            }
            let b = self.exemplar.feature(j);
            let mut visit = |other: usize| {
                let w = linear::mat_vec(transform, &linear::sub(&positions[other], m));
                if !inside(&w) {
                    return;
                }
                if let Some((value, du, dv)) = kernel.eval(&v, &w) {
                    let weight = feature_dot(b, self.exemplar.feature(other));
                    total += weight * value;
                    if let Some(g) = gradient.as_deref_mut() {
                        // v and w both move by −sR dm.
                        let sum = linear::add(&du, &dv);
                        linear::axpy(g, -weight, &linear::mat_t_vec(transform, &sum));
                    }
                }
            };
            visit(j);
            for &other in self.exemplar_neighbours.of(j) {
                visit(other as usize);
            }
        });
        total
    }

    /// [`Problem::exemplar_self_with`] without masking, in exemplar coordinates: `K` depends on the
    /// frame only through the scale (`|v − w| = s|e − e'|`, `|v + w| = s|e + e' − 2m|`).
    fn exemplar_self_unmasked(&self, s: f64, m: &Vector<D>, gradient: Option<&mut Vector<D>>) -> f64 {
        let kernel = &self.kernel;
        let s2 = s * s;
        let gaussian = kernel.window == Window::Gaussian;
        let positions = &self.exemplar.positions;
        let mut total = 0.0;
        let mut g = [0.0; D];
        self.exemplar_grid.for_each_within(m, kernel.gather / s, |j, e, distance2| {
            if !gaussian && s2 * distance2 >= kernel.window2 {
                return;
            }
            let b = self.exemplar.feature(j);
            let mut visit = |other: usize| {
                let o = &positions[other];
                let d2 = s2 * linear::norm2(&linear::sub(e, o));
                if d2 >= kernel.cutoff2 {
                    return;
                }
                let weight = feature_dot(b, self.exemplar.feature(other));
                if gaussian {
                    let sum: Vector<D> = std::array::from_fn(|c| e[c] + o[c] - 2.0 * m[c]);
                    let mid2 = 0.25 * s2 * linear::norm2(&sum);
                    if mid2 >= kernel.window2 {
                        return;
                    }
                    let pair = math::exp(-d2 * kernel.half_inv_sigma2) - kernel.pair_floor;
                    let window_exp = math::exp(-mid2 * kernel.inv_delta_prime2);
                    total += weight * pair * (window_exp - kernel.window_floor);
                    linear::axpy(&mut g, weight * pair * window_exp * s2 * kernel.inv_delta_prime2, &sum);
                } else {
                    if s2 * linear::norm2(&linear::sub(o, m)) >= kernel.window2 {
                        return;
                    }
                    total += weight * (math::exp(-d2 * kernel.half_inv_sigma2) - kernel.pair_floor);
                }
            };
            visit(j);
            for &other in self.exemplar_neighbours.of(j) {
                visit(other as usize);
            }
        });
        if let Some(gradient) = gradient {
            linear::axpy(gradient, 1.0, &g);
        }
        total
    }

    /// Calls `visit(j, K, ∂K/∂(y − e), ∂K/∂(y + e − 2m))` for every exemplar point `e_j` that takes
    /// part in the cross term at quadrature point `k` for the output offset whose place in exemplar
    /// coordinates is `y` (`m` the match, `u2` the squared output offset, for the box window): within
    /// the pair cut-off, inside the window, and, for a window that reaches out of Ω, placed inside Ω.
    /// Works in exemplar coordinates, where the frame `sR` reduces to the scale (`|u − v|² = s²|y −
    /// e|²`, `|u + v|² = s²|y + e − 2m|²`); the evaluation rows and the matching share it.
    #[inline(always)]
    pub(crate) fn for_each_exemplar_term(
        &self,
        k: usize,
        y: &Vector<D>,
        m: &Vector<D>,
        u2: f64,
        found: &mut Vec<(u32, f64)>,
        mut visit: impl FnMut(usize, f64, Vector<D>, Vector<D>),
    ) {
        let kernel = &self.kernel;
        let gaussian = kernel.window == Window::Gaussian;
        if !gaussian && u2 >= kernel.window2 {
            return;
        }
        let s = self.quadrature.scale[k];
        let s2 = s * s;
        let count = self.exemplar_cells.collect_within(y, kernel.cutoff / s, found);
        for &(j, distance2) in &found[..count] {
            let j = j as usize;
            let e = &self.exemplar.positions[j];
            let d2 = s2 * distance2;
            if d2 >= kernel.cutoff2 {
                continue;
            }
            // The window tests come before the masking test and the exponentials: they are cheap
            // and reject about a third of the candidates near the rim of the reach.
            let sum: Vector<D> = std::array::from_fn(|c| y[c] + e[c] - 2.0 * m[c]);
            let mid2 = 0.25 * s2 * linear::norm2(&sum);
            if gaussian {
                if mid2 >= kernel.window2 {
                    continue;
                }
            } else if s2 * linear::norm2(&linear::sub(e, m)) >= kernel.window2 {
                continue;
            }
            if !self.interior[k] {
                let place = linear::mat_vec(&self.quadrature.transform[k], &linear::sub(e, m));
                if !self.quadrature.inside(&linear::add(&self.quadrature.points[k], &place)) {
                    continue;
                }
            }
            let pair_exp = math::exp(-d2 * kernel.half_inv_sigma2);
            let pair = pair_exp - kernel.pair_floor;
            let offset = linear::sub(y, e);
            if gaussian {
                let window_exp = math::exp(-mid2 * kernel.inv_delta_prime2);
                let window = window_exp - kernel.window_floor;
                let p = pair_exp * s2 * kernel.inv_sigma2 * window;
                let w = pair * window_exp * 0.5 * s2 * kernel.inv_delta_prime2;
                visit(j, pair * window, linear::scale(&offset, -p), linear::scale(&sum, -w));
            } else {
                let p = pair_exp * s2 * kernel.inv_sigma2;
                visit(j, pair, linear::scale(&offset, -p), [0.0; D]);
            }
        }
    }

    /// `−2 B_k(m) = −2 Σ a_i·b_j K(u_i, v_j)` for the output window `window` (offsets `u_i` from
    /// `q_k` with their point ids), adding `∂/∂m` to `gradient` when given.
    pub(crate) fn cross(
        &self,
        k: usize,
        m: &Vector<D>,
        window: &[(Vector<D>, u32)],
        state: &State<D>,
        gradient: Option<&mut Vector<D>>,
    ) -> f64 {
        let inverse = &self.quadrature.inverse[k];
        // In exemplar coordinates, as in `point_row`.
        let mut total = 0.0;
        let mut g = [0.0; D];
        let mut found = Vec::new();
        let collect = gradient.is_some();
        for (u, i) in window {
            let a = state.feature(*i as usize);
            let u2 = linear::norm2(u);
            let offset = if self.quadrature.identity_frames { *u } else { linear::mat_vec(inverse, u) };
            let y = linear::add(m, &offset);
            self.for_each_exemplar_term(k, &y, m, u2, &mut found, |j, value, by_offset, by_sum| {
                let weight = feature_dot(a, self.exemplar.feature(j));
                total -= 2.0 * weight * value;
                if collect {
                    // ∂/∂m: m moves the offset y − e by +1 (y = m + …) and the sum y + e − 2m by −1.
                    linear::axpy(&mut g, -2.0 * weight, &linear::sub(&by_offset, &by_sum));
                }
            });
        }
        if let Some(gradient) = gradient {
            linear::axpy(gradient, 1.0, &g);
        }
        total
    }

    /// The output points within reach of quadrature point `k`, as offsets from it.
    pub(crate) fn output_window(&self, k: usize, grid: &StaticGrid<D>) -> Vec<(Vector<D>, u32)> {
        let q = self.quadrature.points[k];
        let mut window = Vec::new();
        grid.for_each_within(&q, self.kernel.gather, |i, p, _| window.push((linear::sub(p, &q), i as u32)));
        window.sort_unstable_by_key(|w| w.1);
        window
    }

    /// The part of `S_k(m)` that depends on `m`: `C_k(m) − 2 B_k(m)`, and its gradient.
    #[cfg(test)]
    pub(crate) fn match_objective(
        &self,
        k: usize,
        m: &Vector<D>,
        window: &[(Vector<D>, u32)],
        state: &State<D>,
        gradient: Option<&mut Vector<D>>,
    ) -> f64 {
        let (c, cross) = self.match_parts(k, m, window, state, gradient);
        c + cross
    }

    /// `(C_k(m), −2 B_k(m))`, with the gradient of their sum.
    pub(crate) fn match_parts(
        &self,
        k: usize,
        m: &Vector<D>,
        window: &[(Vector<D>, u32)],
        state: &State<D>,
        gradient: Option<&mut Vector<D>>,
    ) -> (f64, f64) {
        match gradient {
            Some(g) => {
                *g = [0.0; D];
                let c = self.exemplar_self(k, m, Some(&mut *g));
                (c, self.cross(k, m, window, state, Some(g)))
            }
            None => (self.exemplar_self(k, m, None), self.cross(k, m, window, state, None)),
        }
    }
}
