//! The discrete similarity error T of Eq. 6 and its analytic gradients ∂T/∂x_i and ∂T/∂a_i (fast
//! path); ∂S/∂m_k, the local step's objective, is in `match_objective`.
//!
//! `T = Σ_k S_k` with `S_k = Σ a_i·a_j K − 2 Σ a_i·b_j K + Σ b_i·b_j K` (see [`crate::model`]). The
//! fast path regroups the first two sums by output point: row `i` collects every term that holds
//! `x_i` over the quadrature points within reach, so each point's energy share and gradient are
//! computed independently (in parallel, in a fixed order, hence identical for any thread count),
//! with neighbour lists from a uniform grid instead of the window's all-pairs loops.

use motif_core::math;
use rayon::prelude::*;

use crate::domain::Quadrature;
use crate::exemplar_pairs::ExemplarPairs;
use crate::grid::{CellLists, Neighbours, StaticGrid};
use crate::linear::{self, Vector};
use crate::model::{Exemplar, Kernel, State, feature_dot};
use crate::params::Window;
use crate::quadratic::{AttributeQuadratic, RowQuadratic};

/// The fixed parts of the problem at one window size δ.
pub(crate) struct Problem<'a, const D: usize> {
    pub kernel: Kernel,
    pub exemplar: &'a Exemplar<D>,
    /// Exemplar grid with cells of the largest query radius (cut-off over the smallest scale).
    pub exemplar_grid: &'a StaticGrid<D>,
    /// Exemplar lists for queries of the cut-off over the smallest scale (the inner loops).
    pub exemplar_cells: &'a CellLists<D>,
    /// Exemplar pairs within the cut-off over the smallest scale (the unmasked `C_k`).
    pub exemplar_pairs: &'a ExemplarPairs<D>,
    /// Exemplar neighbour lists within the cut-off over the smallest scale.
    pub exemplar_neighbours: &'a Neighbours,
    pub quadrature: &'a Quadrature<D>,
    /// Per quadrature point: every place its window reaches is inside Ω (no masking needed).
    pub interior: Vec<bool>,
}

/// One output pair `(i, j)` of a row with its quadrature-independent factors.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PairCache<const D: usize> {
    other: u32,
    /// `exp(−|x_i − x_j|²/2σ²) − floor`.
    pair: f64,
    /// `−∂pair/∂x_i`.
    slope: Vector<D>,
    /// `(x_i + x_j)/2`.
    mid: Vector<D>,
    /// `a_i · a_j`.
    weight: f64,
    /// `Σ_k K(u_i, u_j)` over the row's quadrature points (collected only for the attribute form).
    coefficient: f64,
}

/// Per-thread buffers of [`Problem::point_row`], reused from row to row (no allocation in the loop).
#[derive(Debug, Clone, Default)]
pub(crate) struct RowScratch<const D: usize> {
    pairs: Vec<PairCache<D>>,
    /// Per pair and axis, the window factor `exp(−(mid_c − q_c)²/δ'²)` at every grid coordinate of
    /// the row's quadrature range: the Gaussian window is separable and the quadrature points lie
    /// on a grid, so `D` short tables replace one exponential per (pair, quadrature point).
    windows: Vec<f64>,
    /// Exemplar points within the cut-off of the current place, with squared distances.
    found: Vec<(u32, f64)>,
}

/// T and its gradients.
#[derive(Debug, Clone)]
pub(crate) struct Evaluation<const D: usize> {
    pub energy: f64,
    pub positions: Vec<Vector<D>>,
    /// T as a quadratic form in the attributes at these positions (when requested).
    pub quadratic: Option<AttributeQuadratic>,
}

impl<const D: usize> Problem<'_, D> {
    /// The row of output point `i`: `(Σ_k Σ_j a_i·a_j K(u_i, u_j), −2 Σ_k Σ_j a_i·b_j K(u_i, v_j))`,
    /// adding `∂T/∂x_i` to `gradient` and, when `quadratic` is given, writing the row's
    /// coefficients of the attribute form (see [`crate::quadratic`]) into it.
    ///
    /// The pair factor of `K` does not depend on the quadrature point, so it is computed once per
    /// neighbour (into `scratch`); the exemplar side is evaluated in exemplar coordinates, where the
    /// frame `sR` reduces to the scalar `s` (distances are rotation invariant), so candidates need no
    /// matrix product. With the Gaussian window the pairs' window factors come from per-axis
    /// tables (see [`RowScratch`]), equal to the direct exponential up to rounding.
    #[inline]
    #[allow(
        clippy::too_many_arguments,
        reason = "the inner energy row kernel: scratch and outputs are borrowed apart to stay allocation-free"
    )]
    pub(crate) fn point_row(
        &self,
        state: &State<D>,
        matches: &[Vector<D>],
        i: usize,
        neighbours: &[u32],
        gradient: &mut Vector<D>,
        mut quadratic: Option<&mut RowQuadratic>,
        scratch: &mut RowScratch<D>,
        with_pairs: bool,
    ) -> (f64, f64) {
        let kernel = &self.kernel;
        let x = state.positions[i];
        let a = state.feature(i);
        let (mut row_a, mut row_b) = (0.0, 0.0);
        let gaussian = kernel.window == Window::Gaussian;
        if let Some(row) = quadratic.as_deref_mut() {
            row.coefficients.clear();
            row.linear.clear();
            row.linear.resize(state.channels, 0.0);
        }
        let Some(range) = self.quadrature.node_range(&x, kernel.gather) else {
            return (0.0, 0.0);
        };
        let RowScratch { pairs: scratch, windows, found } = scratch;
        // Without pairs (they come from [`Problem::pair_terms`]) the node loop does only the
        // exemplar side.
        self.pair_caches(state, i, with_pairs.then_some(neighbours), scratch);
        let width = self.window_tables(scratch, &range, windows);
        let collect = quadratic.is_some();
        let identity = self.quadrature.identity_frames;
        self.quadrature.for_each_in_range(&x, kernel.gather, &range, |k, node| {
            let q = self.quadrature.points[k];
            let u = linear::sub(&x, &q);
            let u2 = linear::norm2(&u);
            for (p, cache) in scratch.iter_mut().enumerate() {
                // K = pair · window; ∂K/∂x_i = −slope · window − pair · ∂window (for j = i the
                // derivative doubles, which the factor 2 below supplies in both cases).
                let (value, du) = if gaussian {
                    let mid = linear::sub(&cache.mid, &q);
                    let mid2 = linear::norm2(&mid);
                    if mid2 >= kernel.window2 {
                        continue;
                    }
                    let table = &windows[p * D * width..(p + 1) * D * width];
                    let mut window_exp = table[node[0]];
                    for c in 1..D {
                        window_exp *= table[c * width + node[c]];
                    }
                    let window = window_exp - kernel.window_floor;
                    let b = cache.pair * window_exp * kernel.inv_delta_prime2;
                    let du: Vector<D> = std::array::from_fn(|c| -cache.slope[c] * window - b * mid[c]);
                    (cache.pair * window, du)
                } else {
                    let uj = linear::sub(&state.positions[cache.other as usize], &q);
                    if u2 >= kernel.window2 || linear::norm2(&uj) >= kernel.window2 {
                        continue;
                    }
                    (cache.pair, linear::scale(&cache.slope, -1.0))
                };
                row_a += cache.weight * value;
                linear::axpy(gradient, 2.0 * cache.weight, &du);
                if collect {
                    cache.coefficient += value;
                }
            }
            let m = matches[k];
            let inverse = &self.quadrature.inverse[k];
            let offset = if identity { u } else { linear::mat_vec(inverse, &u) };
            let y = linear::add(&m, &offset);
            let mut gy = [0.0; D];
            self.for_each_exemplar_term(k, &y, &m, u2, found, |j, value, by_offset, by_sum| {
                let b = self.exemplar.feature(j);
                let weight = feature_dot(a, b);
                row_b -= 2.0 * weight * value;
                // ∂/∂y: y moves both the offset y − e and the sum y + e − 2m.
                let dy = linear::add(&by_offset, &by_sum);
                linear::axpy(&mut gy, -2.0 * weight, &dy);
                if let Some(row) = quadratic.as_deref_mut() {
                    for (l, &bc) in row.linear.iter_mut().zip(b) {
                        *l += bc * value;
                    }
                }
            });
            // y = m + (sR)⁻¹ u, so ∂/∂u = ((sR)⁻¹)ᵀ ∂/∂y.
            if identity {
                linear::axpy(gradient, 1.0, &gy);
            } else {
                linear::axpy(gradient, 1.0, &linear::mat_t_vec(inverse, &gy));
            }
        });
        if let Some(row) = quadratic {
            row.coefficients.extend(scratch.iter().map(|cache| (cache.other, cache.coefficient)));
        }
        (row_a, row_b)
    }

    /// The pairs (i, j) of output point `i` within the cut-off, the point itself first (none when
    /// `neighbours` is `None`), with their quadrature-independent factors.
    fn pair_caches(&self, state: &State<D>, i: usize, neighbours: Option<&[u32]>, scratch: &mut Vec<PairCache<D>>) {
        let kernel = &self.kernel;
        let x = state.positions[i];
        let a = state.feature(i);
        scratch.clear();
        let Some(neighbours) = neighbours else { return };
        scratch.push(PairCache {
            other: i as u32,
            pair: 1.0 - kernel.pair_floor,
            slope: [0.0; D],
            mid: x,
            weight: feature_dot(a, a),
            coefficient: 0.0,
        });
        for &j in neighbours {
            let xj = state.positions[j as usize];
            let d = linear::sub(&x, &xj);
            let d2 = linear::norm2(&d);
            if d2 >= kernel.cutoff2 {
                continue;
            }
            let pair_exp = math::exp(-d2 * kernel.half_inv_sigma2);
            scratch.push(PairCache {
                other: j,
                pair: pair_exp - kernel.pair_floor,
                slope: linear::scale(&d, pair_exp * kernel.inv_sigma2),
                mid: std::array::from_fn(|c| 0.5 * (x[c] + xj[c])),
                weight: feature_dot(a, state.feature(j as usize)),
                coefficient: 0.0,
            });
        }
    }

    /// The Gaussian window's per-axis tables over the node range (empty for the box window): pair
    /// p, axis c, node n at `windows[(p·D + c)·width + n − low_c]`. Returns `width`.
    fn window_tables(
        &self,
        scratch: &[PairCache<D>],
        (low, high): &([usize; D], [usize; D]),
        windows: &mut Vec<f64>,
    ) -> usize {
        let width = (0..D).map(|c| high[c] - low[c] + 1).max().unwrap_or(1);
        windows.clear();
        if self.kernel.window == Window::Gaussian {
            for cache in scratch {
                for c in 0..D {
                    for n in 0..width {
                        let t = cache.mid[c] - self.quadrature.node_coordinate(c, low[c] + n);
                        windows.push(math::exp(-t * t * self.kernel.inv_delta_prime2));
                    }
                }
            }
        }
        width
    }

    /// T (given `exemplar_self = Σ_k C_k`) with gradients, point-centric and parallel.
    pub(crate) fn evaluate(
        &self,
        state: &State<D>,
        matches: &[Vector<D>],
        exemplar_self: f64,
        features: bool,
    ) -> Evaluation<D> {
        self.evaluate_rows(state, matches, exemplar_self, features, None)
    }

    /// The part of T that changes when only the `active` points move (matches fixed), with the
    /// gradients of the active points (the others' are zero): the active points' rows, each pair
    /// with an inactive point in both orders. T is this plus a constant, the rows of the inactive
    /// points among themselves; merging, where interiors of copied patches are frozen, evaluates
    /// this instead of every row (Gaussian window only: see [`Problem::restricts`]).
    pub(crate) fn evaluate_active(&self, state: &State<D>, matches: &[Vector<D>], active: &[bool]) -> Evaluation<D> {
        debug_assert!(self.restricts());
        self.evaluate_rows(state, matches, 0.0, false, Some(active))
    }

    /// Whether [`Problem::evaluate_active`] applies: with the box window a row's pair test depends
    /// on both points, so rows keep their pairs and cannot be split.
    pub(crate) fn restricts(&self) -> bool {
        self.kernel.window == Window::Gaussian
    }

    fn evaluate_rows(
        &self,
        state: &State<D>,
        matches: &[Vector<D>],
        exemplar_self: f64,
        features: bool,
        active: Option<&[bool]>,
    ) -> Evaluation<D> {
        let n = state.positions.len();
        let neighbours = Neighbours::build(&state.positions, self.kernel.cutoff);
        // With the Gaussian window the output pairs are summed pair by pair (see `crate::output_pairs`);
        // the box window's pair test depends on both points, so its rows keep them.
        let pairs = (self.kernel.window == Window::Gaussian).then(|| self.pair_terms(state, &neighbours, active));
        let row =
            |scratch: &mut RowScratch<D>, i: usize, gradient: &mut Vector<D>, mut q: Option<&mut RowQuadratic>| {
                if active.is_some_and(|a| !a[i]) {
                    return 0.0;
                }
                let (ra, rb) = self.point_row(
                    state,
                    matches,
                    i,
                    neighbours.of(i),
                    gradient,
                    q.as_deref_mut(),
                    scratch,
                    pairs.is_none(),
                );
                let pa = pairs
                    .as_ref()
                    .map_or(0.0, |p| p.row(i, state, &neighbours, gradient, q.map(|q| &mut q.coefficients), active));
                ra + rb + pa
            };
        // Rows are computed in the grid's cell order, so that consecutive rows read the same
        // quadrature points and matches (far fewer cache misses than in the points' own order), and
        // then put back in point order, where the energy is summed.
        let order = neighbours.order();
        let mut computed: Vec<(f64, Vector<D>)> = vec![(0.0, [0.0; D]); n];
        let mut quadratic = None;
        if features {
            let mut coefficients = vec![RowQuadratic::default(); n];
            computed
                .par_iter_mut()
                .zip(coefficients.par_iter_mut())
                .zip(order.par_iter())
                .for_each_init(RowScratch::default, |scratch, ((r, q), &i)| {
                    r.0 = row(scratch, i as usize, &mut r.1, Some(q))
                });
            let mut placed = vec![RowQuadratic::default(); n];
            for (q, &i) in coefficients.into_iter().zip(order) {
                placed[i as usize] = q;
            }
            quadratic = Some(AttributeQuadratic::from_rows(placed, state.channels, exemplar_self));
        } else {
            computed
                .par_iter_mut()
                .zip(order.par_iter())
                .for_each_init(RowScratch::default, |scratch, (r, &i)| r.0 = row(scratch, i as usize, &mut r.1, None));
        }
        let mut rows: Vec<(f64, Vector<D>)> = vec![(0.0, [0.0; D]); n];
        for (r, &i) in computed.into_iter().zip(order) {
            rows[i as usize] = r;
        }
        let mut energy = exemplar_self;
        for row in &rows {
            energy += row.0;
        }
        Evaluation { energy, positions: rows.into_iter().map(|r| r.1).collect(), quadratic }
    }
}
