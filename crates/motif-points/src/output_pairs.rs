//! The output–output term of T (the first sum of Eq. 5) with the Gaussian window, pair by pair.
//!
//! For a pair of output points the kernel is `K = pair(x_i − x_j) · window(mid − q_k)` with `mid`
//! their midpoint, so the pair factor leaves the sum over quadrature points: the term of the pair
//! is `pair · W(mid)` with `W(mid) = Σ_k (exp(−|mid − q_k|²/δ'²) − floor)` over the nodes within the window radius
//! of the midpoint, and its derivatives need `G(mid) = Σ_k exp(…)(mid − q_k)` besides. Each
//! unordered pair is summed once here (the point-centric row of [`crate::energy`] visits it from
//! both ends, each time over all of its point's nodes and testing the midpoint's reach), with
//! per-axis exponential tables over the few nodes around the midpoint (the window is separable
//! and the nodes lie on a grid). Results are stored per neighbour-list entry and gathered per point
//! afterwards, so the sums stay in a fixed order for any thread count.

use motif_core::math;
use rayon::prelude::*;

use crate::energy::Problem;
use crate::grid::Neighbours;
use crate::linear::{self, Vector};
use crate::model::{State, feature_dot};

/// The quadrature sums of one pair: `pair · W` and its derivatives by both points.
#[derive(Debug, Clone, Copy)]
struct PairTerm<const D: usize> {
    value: f64,
    /// `∂(pair · W)/∂x_i` for the point whose row holds the entry.
    first: Vector<D>,
    /// `∂(pair · W)/∂x_j` for the other point.
    second: Vector<D>,
}

impl<const D: usize> Default for PairTerm<D> {
    fn default() -> Self {
        Self { value: 0.0, first: [0.0; D], second: [0.0; D] }
    }
}

/// Every pair's term: the point itself (`K(u_i, u_i)`) and each neighbour-list entry `i → j` with
/// `j > i` (entries with `j < i` are read from `j`'s list).
pub(crate) struct PairTerms<const D: usize> {
    own: Vec<PairTerm<D>>,
    entries: Vec<Vec<PairTerm<D>>>,
}

impl<const D: usize> Problem<'_, D> {
    /// The sums of one pair with midpoint `mid` and pair factor `pair` (`slope = −∂pair/∂x_i`).
    fn pair_term(&self, mid: &Vector<D>, pair: f64, slope: &Vector<D>, tables: &mut Vec<f64>) -> PairTerm<D> {
        let kernel = &self.kernel;
        let reach = kernel.window_radius;
        let Some((low, high)) = self.quadrature.node_range(mid, reach) else {
            return PairTerm::default();
        };
        // Per axis c and node n: the offset t = mid_c − q_c, t² and exp(−t²/δ'²), at
        // tables[(c·3 + {0,1,2})·width + n].
        let width = (0..D).map(|c| high[c] - low[c] + 1).max().unwrap_or(1);
        tables.clear();
        tables.resize(3 * D * width, 0.0);
        for c in 0..D {
            for n in 0..=(high[c] - low[c]) {
                let t = mid[c] - self.quadrature.node_coordinate(c, low[c] + n);
                tables[(3 * c) * width + n] = t;
                tables[(3 * c + 1) * width + n] = t * t;
                tables[(3 * c + 2) * width + n] = math::exp(-t * t * kernel.inv_delta_prime2);
            }
        }
        let mut sum = 0.0;
        let mut moment = [0.0; D];
        self.quadrature.for_each_in_range(mid, reach, &(low, high), |_, node| {
            let mut e = tables[2 * width + node[0]];
            for c in 1..D {
                e *= tables[(3 * c + 2) * width + node[c]];
            }
            sum += e - kernel.window_floor;
            for c in 0..D {
                moment[c] += e * tables[(3 * c) * width + node[c]];
            }
        });
        // ∂W/∂x_i = ∂W/∂x_j = −G/δ'² (the midpoint moves by half of either point's motion).
        let window_slope = linear::scale(&moment, -pair * kernel.inv_delta_prime2);
        PairTerm {
            value: pair * sum,
            first: std::array::from_fn(|c| -slope[c] * sum + window_slope[c]),
            second: std::array::from_fn(|c| slope[c] * sum + window_slope[c]),
        }
    }

    /// The term of the pair `(i, j)` (`j = i` for a point with itself).
    pub(crate) fn pair_of(&self, state: &State<D>, i: usize, j: usize, tables: &mut Vec<f64>) -> (f64, Vector<D>) {
        let kernel = &self.kernel;
        let x = state.positions[i];
        if i == j {
            let term = self.pair_term(&x, 1.0 - kernel.pair_floor, &[0.0; D], tables);
            return (term.value, term.first);
        }
        let xj = state.positions[j];
        let d = linear::sub(&x, &xj);
        let pair_exp = math::exp(-linear::norm2(&d) * kernel.half_inv_sigma2);
        let mid = std::array::from_fn(|c| 0.5 * (x[c] + xj[c]));
        let slope = linear::scale(&d, pair_exp * kernel.inv_sigma2);
        let term = self.pair_term(&mid, pair_exp - kernel.pair_floor, &slope, tables);
        (term.value, term.first)
    }

    /// Point `i`'s share of the output–output term, `Σ_j a_i·a_j Σ_k K(u_i, u_j)` over itself and
    /// `neighbours` (all within the cut-off), adding its derivative by `x_i` to `gradient`: the
    /// one-point form of [`PairTerms::row`] for local changes (sampling control). Also returns the
    /// point's own term `Σ_k K(u_i, u_i)`.
    pub(crate) fn pair_row(
        &self,
        state: &State<D>,
        i: usize,
        neighbours: &[u32],
        gradient: &mut Vector<D>,
        tables: &mut Vec<f64>,
    ) -> (f64, f64) {
        let a = state.feature(i);
        let (own, derivative) = self.pair_of(state, i, i, tables);
        let weight = feature_dot(a, a);
        let mut total = weight * own;
        linear::axpy(gradient, 2.0 * weight, &derivative);
        for &j in neighbours {
            let (value, derivative) = self.pair_of(state, i, j as usize, tables);
            let weight = feature_dot(a, state.feature(j as usize));
            total += weight * value;
            linear::axpy(gradient, 2.0 * weight, &derivative);
        }
        (total, own)
    }

    /// The terms of every pair of output points within the cut-off, in parallel. With `active`,
    /// only the pairs with at least one active point (the others do not change while only the
    /// active points move; their entries stay zero).
    pub(crate) fn pair_terms(
        &self,
        state: &State<D>,
        neighbours: &Neighbours,
        active: Option<&[bool]>,
    ) -> PairTerms<D> {
        let kernel = &self.kernel;
        let is_active = |i: usize| active.is_none_or(|a| a[i]);
        // In the grid's cell order for cache locality (see `Problem::evaluate`), then placed back.
        let computed: Vec<(PairTerm<D>, Vec<PairTerm<D>>)> = neighbours
            .order()
            .par_iter()
            .map_init(Vec::new, |tables, &i| {
                let i = i as usize;
                let x = state.positions[i];
                let own = if is_active(i) {
                    self.pair_term(&x, 1.0 - kernel.pair_floor, &[0.0; D], tables)
                } else {
                    PairTerm::default()
                };
                let entries = neighbours
                    .of(i)
                    .iter()
                    .map(|&j| {
                        if (j as usize) < i || !(is_active(i) || is_active(j as usize)) {
                            return PairTerm::default();
                        }
                        let xj = state.positions[j as usize];
                        let d = linear::sub(&x, &xj);
                        let pair_exp = math::exp(-linear::norm2(&d) * kernel.half_inv_sigma2);
                        let mid = std::array::from_fn(|c| 0.5 * (x[c] + xj[c]));
                        let slope = linear::scale(&d, pair_exp * kernel.inv_sigma2);
                        self.pair_term(&mid, pair_exp - kernel.pair_floor, &slope, tables)
                    })
                    .collect();
                (own, entries)
            })
            .collect();
        let mut own = vec![PairTerm::default(); computed.len()];
        let mut entries = vec![Vec::new(); computed.len()];
        for ((term, list), &i) in computed.into_iter().zip(neighbours.order()) {
            own[i as usize] = term;
            entries[i as usize] = list;
        }
        PairTerms { own, entries }
    }
}

impl<const D: usize> PairTerms<D> {
    /// Point `i`'s share `Σ_j a_i·a_j Σ_k K(u_i, u_j)` (itself included), adding its derivative by
    /// `x_i` (both orders of each pair) to `gradient` and, when given, appending `(j, Σ_k K)` for the
    /// point itself and then each neighbour to `coefficients`.
    ///
    /// With `active` (an evaluation of the active rows alone, `i` active), a pair with an inactive
    /// point counts twice in the share: the inactive point's row, which held the other order, is
    /// not computed.
    pub(crate) fn row(
        &self,
        i: usize,
        state: &State<D>,
        neighbours: &Neighbours,
        gradient: &mut Vector<D>,
        mut coefficients: Option<&mut Vec<(u32, f64)>>,
        active: Option<&[bool]>,
    ) -> f64 {
        let a = state.feature(i);
        let own = &self.own[i];
        let weight = feature_dot(a, a);
        let mut total = weight * own.value;
        // Both of the self pair's ends move with x_i: its derivative counts twice, like the other
        // pairs' two orders.
        linear::axpy(gradient, 2.0 * weight, &own.first);
        if let Some(c) = coefficients.as_deref_mut() {
            c.push((i as u32, own.value));
        }
        for (slot, &j) in neighbours.of(i).iter().enumerate() {
            let j = j as usize;
            let (value, derivative) = if j > i {
                let term = &self.entries[i][slot];
                (term.value, term.first)
            } else {
                // The entry lives in j's list (lists are symmetric and sorted).
                let position = neighbours.of(j).binary_search(&(i as u32)).unwrap_or_default();
                let term = &self.entries[j][position];
                (term.value, term.second)
            };
            let weight = feature_dot(a, state.feature(j));
            let orders = if active.is_some_and(|a| !a[j]) { 2.0 } else { 1.0 };
            total += orders * weight * value;
            linear::axpy(gradient, 2.0 * weight, &derivative);
            if let Some(c) = coefficients.as_deref_mut() {
                c.push((j as u32, value));
            }
        }
        total
    }
}
