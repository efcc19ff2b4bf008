//! Multilinear rasters of exemplar functions, for the cheap candidate search of the matching step.

use crate::linear::Vector;

/// Rasters never have more nodes than this.
const MAX_NODES: usize = 1 << 22;

/// Values with `channels` components on a regular grid, sampled multilinearly (clamped at the
/// border).
#[derive(Debug, Clone)]
pub(crate) struct Raster<const D: usize> {
    origin: Vector<D>,
    inverse_spacing: f64,
    dims: [usize; D],
    channels: usize,
    values: Vec<f64>,
}

impl<const D: usize> Raster<D> {
    /// Fills the raster over `[low, high]` with spacing about `spacing` from `value(node, out)`.
    pub(crate) fn new(
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
    pub(crate) fn sample(&self, p: &Vector<D>, out: &mut [f64], gradient: &mut [Vector<D>]) {
        let mut base = [0usize; D];
        let mut frac = [0.0; D];
        for a in 0..D {
            let t = ((p[a] - self.origin[a]) * self.inverse_spacing).clamp(0.0, (self.dims[a] - 1) as f64 - 1e-9);
            // t ≥ 0, so truncation is `floor` (without a libm call).
            let cell = (t as usize).min(self.dims[a].saturating_sub(2));
            base[a] = cell;
            frac[a] = (t - cell as f64).clamp(0.0, 1.0);
        }
        self.sample_separable(&base, &frac, out, gradient);
    }
}

impl<const D: usize> Raster<D> {
    /// Asks the processor to start loading the nodes that [`Raster::sample`] at `p` reads (the
    /// start of both rows of its cell's lower layer), so that a loop over many
    /// scattered samples overlaps their memory latency. No effect on any value.
    #[inline]
    pub(crate) fn prefetch(&self, p: &Vector<D>) {
        let mut index = 0usize;
        let mut stride = 1usize;
        for a in 0..D {
            let t = ((p[a] - self.origin[a]) * self.inverse_spacing).clamp(0.0, (self.dims[a] - 1) as f64);
            index += (t as usize) * stride;
            stride *= self.dims[a];
        }
        // The cell's two rows; in 3D, prefetching its upper layer too made no measurable
        // difference (docs/points.md), so it is left to the hardware.
        let row = self.dims[0] * self.channels;
        for offset in [0, row] {
            if let Some(value) = self.values.get(index * self.channels + offset) {
                prefetch_line(value);
            }
        }
    }
}

/// A hint to load the cache line holding `value` (x86-64's `prefetcht0`; nothing elsewhere).
#[inline(always)]
fn prefetch_line(value: &f64) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: prefetching is a hint that never faults, on any address; this one is a live reference.
    #[allow(unsafe_code, reason = "a prefetch hint, measured: see docs/points.md")]
    unsafe {
        std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(std::ptr::from_ref(value).cast());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}

impl<const D: usize> Raster<D> {
    /// [`Raster::sample`] (2D or 3D), one axis at a time: interpolate along x between the cell's
    /// pairs of nodes (adjacent in memory), then along y, then z, carrying the derivatives along
    /// (about 30 operations per channel instead of a weighted sum over the 2^D corners with a
    /// product of D weights per corner and derivative).
    #[inline(always)]
    fn sample_separable(&self, base: &[usize; D], frac: &[f64; D], out: &mut [f64], gradient: &mut [Vector<D>]) {
        let channels = self.channels;
        let h = self.inverse_spacing;
        // The upper node along each axis (the lower one clamped when an axis has a single node).
        let step: [usize; D] = std::array::from_fn(|a| usize::from(base[a] + 1 < self.dims[a]));
        let stride_y = self.dims[0];
        let stride_z = if D == 3 { self.dims[0] * self.dims[1] } else { 0 };
        let origin = if D == 3 {
            (base[2] * self.dims[1] + base[1]) * self.dims[0] + base[0]
        } else {
            base[1] * self.dims[0] + base[0]
        };
        let (fx, fy) = (frac[0], frac[1]);
        let fz = if D == 3 { frac[2] } else { 0.0 };
        let layers = if D == 3 { 2 } else { 1 };
        for c in 0..channels {
            // Along x for each (y, z) corner pair, then along y per z layer.
            let mut layer = [[0.0; 3]; 2];
            for (z, slot) in layer.iter_mut().enumerate().take(layers) {
                let mut rows = [[0.0; 2]; 2];
                for (y, row) in rows.iter_mut().enumerate() {
                    let index = origin + z * step[D - 1] * stride_z + y * step[1] * stride_y;
                    let v0 = self.values[index * channels + c];
                    let v1 = self.values[(index + step[0]) * channels + c];
                    *row = [v0 + fx * (v1 - v0), (v1 - v0) * h];
                }
                let [r0, r1] = rows;
                *slot = [r0[0] + fy * (r1[0] - r0[0]), r0[1] + fy * (r1[1] - r0[1]), (r1[0] - r0[0]) * h];
            }
            if D == 3 {
                let [l0, l1] = layer;
                out[c] = l0[0] + fz * (l1[0] - l0[0]);
                gradient[c][0] = l0[1] + fz * (l1[1] - l0[1]);
                gradient[c][1] = l0[2] + fz * (l1[2] - l0[2]);
                gradient[c][D - 1] = (l1[0] - l0[0]) * h;
            } else {
                out[c] = layer[0][0];
                gradient[c][0] = layer[0][1];
                gradient[c][1] = layer[0][2];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use motif_core::math;

    #[test]
    fn prefetching_anywhere_is_harmless() {
        let raster = Raster::<2>::new([0.0; 2], [2.0, 3.0], 0.25, 2, |p, out| out.copy_from_slice(p));
        for p in [[0.5, 0.5], [-1e9, 1e9], [2.0, 3.0], [f64::NAN, f64::INFINITY], [1e300, -0.0]] {
            raster.prefetch(&p);
        }
        let mut value = [0.0; 2];
        raster.sample(&[0.5, 1.25], &mut value, &mut [[0.0; 2]; 2]);
        assert_eq!(value, [0.5, 1.25]);
    }

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

    #[test]
    fn separable_sampling_equals_the_corner_sum() {
        // A non-multilinear function with two channels: the axis-by-axis interpolation must give
        // the corner-weighted sum and its derivatives exactly (up to rounding), also at clamped
        // borders and with a single node along an axis.
        let f = |p: &Vector<3>, out: &mut [f64]| {
            out[0] = math::sin(p[0] * 1.3) + p[1] * p[2];
            out[1] = math::exp(p[0] - p[1]) * (1.0 + p[2]);
        };
        for (high, point) in [
            ([2.0, 3.0, 1.0], [0.61, 1.37, 0.4]),
            ([2.0, 3.0, 1.0], [-0.3, 3.5, 0.99]),
            ([2.0, 3.0, 0.0], [1.1, 0.2, 0.0]),
        ] {
            let raster = Raster::<3>::new([0.0; 3], high, 0.25, 2, f);
            let (mut value, mut gradient) = ([0.0; 2], [[0.0; 3]; 2]);
            raster.sample(&point, &mut value, &mut gradient);
            // The corner sum, written out.
            let t: [f64; 3] = std::array::from_fn(|a| {
                (point[a] * raster.inverse_spacing).clamp(0.0, (raster.dims[a] - 1) as f64 - 1e-9)
            });
            let base: [usize; 3] = std::array::from_fn(|a| (t[a] as usize).min(raster.dims[a].saturating_sub(2)));
            let frac: [f64; 3] = std::array::from_fn(|a| (t[a] - base[a] as f64).clamp(0.0, 1.0));
            let mut expected = [0.0; 2];
            let mut expected_gradient = [[0.0; 3]; 2];
            for corner in 0..8usize {
                let bits: [usize; 3] = std::array::from_fn(|a| (corner >> a) & 1);
                let node: [usize; 3] = std::array::from_fn(|a| (base[a] + bits[a]).min(raster.dims[a] - 1));
                let index = (node[2] * raster.dims[1] + node[1]) * raster.dims[0] + node[0];
                let w: [f64; 3] = std::array::from_fn(|a| if bits[a] == 1 { frac[a] } else { 1.0 - frac[a] });
                let dw: [f64; 3] =
                    std::array::from_fn(
                        |a| if bits[a] == 1 { raster.inverse_spacing } else { -raster.inverse_spacing },
                    );
                for c in 0..2 {
                    let v = raster.values[index * 2 + c];
                    expected[c] += w[0] * w[1] * w[2] * v;
                    expected_gradient[c][0] += dw[0] * w[1] * w[2] * v;
                    expected_gradient[c][1] += w[0] * dw[1] * w[2] * v;
                    expected_gradient[c][2] += w[0] * w[1] * dw[2] * v;
                }
            }
            for c in 0..2 {
                assert!((value[c] - expected[c]).abs() < 1e-12, "{point:?} channel {c}");
                for a in 0..3 {
                    assert!((gradient[c][a] - expected_gradient[c][a]).abs() < 1e-9, "{point:?} {c} {a}");
                }
            }
        }
    }
}
