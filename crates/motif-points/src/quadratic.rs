//! T as a function of the attributes alone (§4.4, the attribute half of the merging step).
//!
//! At fixed positions and matches, Eq. 5 is bilinear in the feature vectors, so T is a quadratic
//! form in the attributes:
//!
//! `T(a) = C + Σ_i Σ_j A_ij a_i·a_j − 2 Σ_i a_i·B_i`,
//!
//! with `A_ij = Σ_k K(u_i, u_j)` (symmetric, sparse: pairs within the cut-off), `B_i = Σ_k Σ_j b_j
//! K(u_i, v_j)` and `C = Σ_k C_k`. One pass over the quadrature (the same work as one evaluation of
//! T) gives `A`, `B` and `C`; after that the energy, its gradient `∂T/∂a_i = 2(Σ_j A_ij a_j − B_i)`
//! and exact line searches cost a sparse product each, so the attribute descent needs no further
//! passes. Channels do not interact, so each is minimized on its own by conjugate gradients (steepest
//! descent with exact line search, made conjugate).

/// Rounds of [`AttributeQuadratic::minimize_channel_within`]: each holds the values that left
/// the range at its ends and minimizes the rest again.
const BOUND_ROUNDS: usize = 3;

/// The coefficients of one output point's row: `(j, A_ij)` for every pair (itself included) and
/// `B_i` (one value per channel).
#[derive(Debug, Clone, Default)]
pub(crate) struct RowQuadratic {
    pub coefficients: Vec<(u32, f64)>,
    pub linear: Vec<f64>,
}

/// The quadratic form `T(a)` (see the module documentation), rows in compressed form.
#[derive(Debug, Clone, Default)]
pub(crate) struct AttributeQuadratic {
    starts: Vec<u32>,
    others: Vec<u32>,
    coefficients: Vec<f64>,
    /// `B_i`, `n × channels`.
    linear: Vec<f64>,
    channels: usize,
    constant: f64,
}

impl AttributeQuadratic {
    /// Assembles the form from per-point rows and the constant `C`.
    pub(crate) fn from_rows(rows: Vec<RowQuadratic>, channels: usize, constant: f64) -> Self {
        let mut starts = Vec::with_capacity(rows.len() + 1);
        let total = rows.iter().map(|r| r.coefficients.len()).sum();
        let mut others = Vec::with_capacity(total);
        let mut coefficients = Vec::with_capacity(total);
        let mut linear = Vec::with_capacity(rows.len() * channels);
        starts.push(0);
        for row in rows {
            for (j, a) in row.coefficients {
                others.push(j);
                coefficients.push(a);
            }
            starts.push(others.len() as u32);
            debug_assert_eq!(row.linear.len(), channels);
            linear.extend_from_slice(&row.linear);
        }
        Self { starts, others, coefficients, linear, channels, constant }
    }

    fn len(&self) -> usize {
        self.starts.len() - 1
    }

    fn row(&self, i: usize) -> (&[u32], &[f64]) {
        let range = self.starts[i] as usize..self.starts[i + 1] as usize;
        (&self.others[range.clone()], &self.coefficients[range])
    }

    /// `Σ_j A_ij x_j` for one channel column `x` (one value per point).
    fn multiply_row(&self, i: usize, x: &[f64]) -> f64 {
        let (others, coefficients) = self.row(i);
        let mut sum = 0.0;
        for (&j, &a) in others.iter().zip(coefficients) {
            sum += a * x[j as usize];
        }
        sum
    }

    /// `T(a)` for the features `a` (`n × channels`).
    pub(crate) fn energy(&self, features: &[f64]) -> f64 {
        let channels = self.channels;
        let mut total = self.constant;
        for i in 0..self.len() {
            let (others, coefficients) = self.row(i);
            let a = &features[i * channels..(i + 1) * channels];
            for (&j, &coefficient) in others.iter().zip(coefficients) {
                let b = &features[j as usize * channels..(j as usize + 1) * channels];
                total += coefficient * crate::model::feature_dot(a, b);
            }
            total -= 2.0 * crate::model::feature_dot(a, &self.linear[i * channels..(i + 1) * channels]);
        }
        total
    }

    /// `∂T/∂a_i = 2(Σ_j A_ij a_j − B_i)` for every point (`n × channels`).
    #[cfg(test)]
    pub(crate) fn gradient(&self, features: &[f64]) -> Vec<f64> {
        let channels = self.channels;
        let mut gradient = vec![0.0; features.len()];
        for i in 0..self.len() {
            let (others, coefficients) = self.row(i);
            let g = &mut gradient[i * channels..(i + 1) * channels];
            for (&j, &coefficient) in others.iter().zip(coefficients) {
                for (gc, &aj) in g.iter_mut().zip(&features[j as usize * channels..(j as usize + 1) * channels]) {
                    *gc += 2.0 * coefficient * aj;
                }
            }
            for (gc, &b) in g.iter_mut().zip(&self.linear[i * channels..(i + 1) * channels]) {
                *gc -= 2.0 * b;
            }
        }
        gradient
    }

    /// Lowers `T` over channel `channel` of the points in `free` with every value kept within
    /// `range` (the values start inside it): conjugate gradients, then the values that left the
    /// range are projected onto its nearest end and held there while the others are minimized
    /// again (an active-set method), at most [`BOUND_ROUNDS`] times. The caller keeps the result
    /// only where `T` fell, since a projection can raise it.
    pub(crate) fn minimize_channel_within(
        &self,
        features: &mut [f64],
        channel: usize,
        free: &[usize],
        iterations: usize,
        range: (f64, f64),
    ) {
        let channels = self.channels;
        let mut free = free.to_vec();
        for _ in 0..BOUND_ROUNDS {
            self.minimize_channel(features, channel, &free, iterations);
            let before = free.len();
            free.retain(|&i| {
                let value = &mut features[i * channels + channel];
                let inside = *value >= range.0 && *value <= range.1;
                *value = value.clamp(range.0, range.1);
                inside
            });
            if free.len() == before || free.is_empty() {
                break;
            }
        }
    }

    /// Lowers `T` over channel `channel` of the points in `free` (the others stay) by at most
    /// `iterations` conjugate-gradient steps; each step is an exact line search, so `T` never rises.
    pub(crate) fn minimize_channel(&self, features: &mut [f64], channel: usize, free: &[usize], iterations: usize) {
        let channels = self.channels;
        let n = self.len();
        let mut x: Vec<f64> = (0..n).map(|i| features[i * channels + channel]).collect();
        // The residual r = B − A x is −½ the gradient; fixed points keep r = 0 (they do not move).
        let mut residual = vec![0.0; n];
        for &i in free {
            residual[i] = self.linear[i * channels + channel] - self.multiply_row(i, &x);
        }
        let mut direction = residual.clone();
        let mut rr: f64 = free.iter().map(|&i| residual[i] * residual[i]).sum();
        let mut product = vec![0.0; n];
        for _ in 0..iterations {
            if rr <= 0.0 || !rr.is_finite() {
                break;
            }
            // A p restricted to the free rows (p is zero on fixed points).
            let mut curvature = 0.0;
            for &i in free {
                product[i] = self.multiply_row(i, &direction);
                curvature += direction[i] * product[i];
            }
            if curvature <= 0.0 || !curvature.is_finite() {
                break;
            }
            let step = rr / curvature;
            for &i in free {
                x[i] += step * direction[i];
                residual[i] -= step * product[i];
            }
            let next: f64 = free.iter().map(|&i| residual[i] * residual[i]).sum();
            let beta = next / rr;
            rr = next;
            for &i in free {
                direction[i] = residual[i] + beta * direction[i];
            }
        }
        for &i in free {
            features[i * channels + channel] = x[i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3-point chain with 2 channels: `A` tridiagonal and diagonally dominant.
    fn chain() -> AttributeQuadratic {
        let rows = vec![
            RowQuadratic { coefficients: vec![(0, 2.0), (1, 0.5)], linear: vec![1.0, 0.3] },
            RowQuadratic { coefficients: vec![(0, 0.5), (1, 2.0), (2, 0.5)], linear: vec![1.0, -0.4] },
            RowQuadratic { coefficients: vec![(1, 0.5), (2, 2.0)], linear: vec![1.0, 0.8] },
        ];
        AttributeQuadratic::from_rows(rows, 2, 5.0)
    }

    #[test]
    fn gradient_matches_finite_differences() {
        let q = chain();
        let a = vec![1.0, 0.2, 1.0, -0.7, 1.0, 0.4];
        let g = q.gradient(&a);
        let h = 1e-6;
        for c in 0..a.len() {
            let (mut plus, mut minus) = (a.clone(), a.clone());
            plus[c] += h;
            minus[c] -= h;
            let numeric = (q.energy(&plus) - q.energy(&minus)) / (2.0 * h);
            assert!((numeric - g[c]).abs() < 1e-6, "{c}: {numeric} vs {}", g[c]);
        }
    }

    #[test]
    fn conjugate_gradients_reach_the_minimum_of_a_small_system() {
        let q = chain();
        let mut a = vec![1.0, 0.0, 1.0, 0.0, 1.0, 0.0];
        let before = q.energy(&a);
        // n = 3 free unknowns: CG is exact after 3 steps.
        q.minimize_channel(&mut a, 1, &[0, 1, 2], 3);
        assert!(q.energy(&a) < before);
        let g = q.gradient(&a);
        for i in 0..3 {
            assert!(g[i * 2 + 1].abs() < 1e-12, "gradient of channel 1 at {i}: {}", g[i * 2 + 1]);
            assert_eq!(a[i * 2], 1.0, "channel 0 untouched");
        }
    }

    #[test]
    fn fixed_points_keep_their_values() {
        let q = chain();
        let mut a = vec![1.0, 0.9, 1.0, 0.0, 1.0, -0.9];
        let before = q.energy(&a);
        q.minimize_channel(&mut a, 1, &[1], 5);
        assert_eq!((a[1], a[5]), (0.9, -0.9));
        assert!(q.energy(&a) <= before);
        // With only point 1 free the optimum is B_1 = Σ_j A_1j x_j solved for x_1.
        let expected = (-0.4 - 0.5 * 0.9 - 0.5 * -0.9) / 2.0;
        assert!((a[3] - expected).abs() < 1e-12, "{} vs {expected}", a[3]);
    }

    #[test]
    fn bounded_minimization_stays_within_the_range() {
        let q = chain();
        let mut free = vec![1.0, 0.0, 1.0, 0.0, 1.0, 0.0];
        q.minimize_channel(&mut free, 1, &[0, 1, 2], 3);
        let (low, high) = (-0.1, 0.1);
        // The free minimum leaves the range, so the bounds matter here.
        assert!((0..3).any(|i| free[i * 2 + 1] < low || free[i * 2 + 1] > high), "{free:?}");
        let mut bounded = vec![1.0, 0.0, 1.0, 0.0, 1.0, 0.0];
        let before = q.energy(&bounded);
        q.minimize_channel_within(&mut bounded, 1, &[0, 1, 2], 3, (low, high));
        for i in 0..3 {
            let value = bounded[i * 2 + 1];
            assert!((low..=high).contains(&value), "point {i}: {value}");
        }
        assert!(q.energy(&bounded) < before, "{} against {before}", q.energy(&bounded));
    }
}
