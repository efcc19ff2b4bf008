//! Multilinear rasters of exemplar functions, for the cheap candidate search of the matching step.

use crate::linear::Vector;

/// Rasters never have more nodes than this.
const MAX_NODES: usize = 1 << 22;

/// Values with `channels` components on a regular grid, sampled multilinearly (clamped at the
/// border).
#[derive(Debug, Clone)]
pub struct Raster<const D: usize> {
    origin: Vector<D>,
    inverse_spacing: f64,
    dims: [usize; D],
    channels: usize,
    values: Vec<f64>,
}

impl<const D: usize> Raster<D> {
    /// Fills the raster over `[low, high]` with spacing about `spacing` from `value(node, out)`.
    pub fn new(
        low: Vector<D>,
        high: Vector<D>,
        spacing: f64,
        channels: usize,
        value: impl Fn(&Vector<D>, &mut [f64]) + Sync,
    ) -> Self {
        use rayon::prelude::*;
        // A sparse exemplar with far outliers could ask for a huge raster: coarsen instead.
        let mut spacing = spacing;
        let (dims, total) = loop {
            let dims: [usize; D] = std::array::from_fn(|a| ((high[a] - low[a]) / spacing).ceil().max(1.0) as usize + 1);
            match dims.iter().try_fold(1usize, |acc, &d| acc.checked_mul(d)) {
                Some(total) if total <= MAX_NODES => break (dims, total),
                _ => spacing *= 1.5,
            }
        };
        let mut values = vec![0.0; total * channels];
        values.par_chunks_mut(channels).enumerate().for_each(|(index, out)| {
            let mut rest = index;
            let node: Vector<D> = std::array::from_fn(|a| {
                let c = rest % dims[a];
                rest /= dims[a];
                low[a] + c as f64 * spacing
            });
            value(&node, out);
        });
        Self { origin: low, inverse_spacing: 1.0 / spacing, dims, channels, values }
    }

    /// Multilinear sample at `p` into `out` (`channels` values) and its spatial gradient into
    /// `gradient` (`channels` vectors).
    #[inline]
    pub fn sample(&self, p: &Vector<D>, out: &mut [f64], gradient: &mut [Vector<D>]) {
        let mut base = [0usize; D];
        let mut frac = [0.0; D];
        for a in 0..D {
            let t = ((p[a] - self.origin[a]) * self.inverse_spacing).clamp(0.0, (self.dims[a] - 1) as f64 - 1e-9);
            // t ≥ 0, so truncation is `floor` (without a libm call).
            let cell = (t as usize).min(self.dims[a].saturating_sub(2));
            base[a] = cell;
            frac[a] = (t - cell as f64).clamp(0.0, 1.0);
        }
        out.iter_mut().for_each(|v| *v = 0.0);
        gradient.iter_mut().for_each(|g| *g = [0.0; D]);
        for corner in 0..(1usize << D) {
            let mut weight = 1.0;
            let mut partial = [1.0; D];
            let mut index = 0;
            for a in (0..D).rev() {
                let bit = (corner >> a) & 1;
                let c = (base[a] + bit).min(self.dims[a] - 1);
                index = index * self.dims[a] + c;
                let w = if bit == 1 { frac[a] } else { 1.0 - frac[a] };
                let dw = if bit == 1 { self.inverse_spacing } else { -self.inverse_spacing };
                for (b, part) in partial.iter_mut().enumerate() {
                    *part *= if b == a { dw } else { w };
                }
                weight *= w;
            }
            let values = &self.values[index * self.channels..(index + 1) * self.channels];
            for c in 0..self.channels {
                out[c] += weight * values[c];
                for a in 0..D {
                    gradient[c][a] += partial[a] * values[c];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn multilinear_functions_are_reproduced_with_their_gradient() {
        let raster = Raster::<3>::new([0.0; 3], [2.0, 3.0, 1.0], 0.25, 1, |p, out| {
            out[0] = 1.0 + 2.0 * p[0] - p[1] + 0.5 * p[2]
        });
        let mut value = [0.0];
        let mut gradient = [[0.0; 3]];
        raster.sample(&[0.61, 1.37, 0.4], &mut value, &mut gradient);
        assert!((value[0] - (1.0 + 1.22 - 1.37 + 0.2)).abs() < 1e-9);
        assert!((gradient[0][0] - 2.0).abs() < 1e-9 && (gradient[0][1] + 1.0).abs() < 1e-9);
        assert!((gradient[0][2] - 0.5).abs() < 1e-9);
    }
}
