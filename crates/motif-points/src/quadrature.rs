//! The quadrature points `q_k` (§4.3): a regular grid over the domain's bounds, the nodes inside
//! it kept, each with the frame `s_k R_k` of Eq. 8; membership and neighbour queries on the grid.

use crate::LimitError;
use crate::domain::Region;
use crate::error::Error;
use crate::linear::{self, Matrix, Vector};
use crate::params::Field;

/// The quadrature points `q_k` on a regular grid, with the frame `s_k R_k` of Eq. 8 at each.
#[derive(Debug, Clone)]
pub(crate) struct Quadrature<const D: usize> {
    origin: Vector<D>,
    inverse_spacing: f64,
    dims: [usize; D],
    lookup: Vec<u32>,
    /// Every grid node is a quadrature point (a box domain): membership is a bounds test.
    full: bool,
    /// Every frame `s_k R_k` is the identity (no guidance fields, no stroke): the inner loops skip
    /// the frame products.
    pub identity_frames: bool,
    /// Positions `q_k`.
    pub points: Vec<Vector<D>>,
    /// `s_k R_k`: exemplar offsets to output offsets.
    pub transform: Vec<Matrix<D>>,
    /// `(s_k R_k)⁻¹ = R_kᵀ / s_k`.
    pub inverse: Vec<Matrix<D>>,
    /// `s_k`.
    pub scale: Vec<f64>,
    /// Dimension of the pattern in the output: `D`, or 2 on a surface (whose exemplar is planar,
    /// lifted into a band as thick as the grid's), so that scaling by `s` divides its density by
    /// `s²` there, not `s³` ([`Quadrature::density_scale`]).
    pub pattern_dimension: i32,
    /// Per quadrature point: the L∞ distance, in grid steps, to the nearest grid node that is not
    /// a quadrature point (or to the outside of the grid).
    pub depth: Vec<u32>,
}

const NONE: u32 = u32::MAX;

impl<const D: usize> Quadrature<D> {
    /// Grid nodes of spacing `spacing` over `[low, high]` accepted by `keep`, with frames from the
    /// region and the guidance fields. Errors when the grid would be absurdly large.
    pub(crate) fn new(
        low: Vector<D>,
        high: Vector<D>,
        spacing: f64,
        keep: impl Fn(&Vector<D>) -> bool + Sync,
        region: &Region<D>,
        rotation: &Field,
        scale: &Field,
    ) -> Result<Self, Error> {
        let dims: [usize; D] = std::array::from_fn(|a| ((high[a] - low[a]) / spacing).floor().max(0.0) as usize + 1);
        let total = dims.iter().try_fold(1usize, |acc, &d| acc.checked_mul(d)).unwrap_or(usize::MAX);
        if total > 60_000_000 {
            return Err(Error::Limit(LimitError::TooManyQuadraturePoints { count: total, limit: 60_000_000 }));
        }
        // Centre the grid inside the bounds so that both sides get the same margin.
        let origin: Vector<D> =
            std::array::from_fn(|a| low[a] + 0.5 * ((high[a] - low[a]) - (dims[a] - 1) as f64 * spacing));
        let mut lookup = vec![NONE; total];
        let mut points = Vec::new();
        for (linear_index, slot) in lookup.iter_mut().enumerate() {
            let mut rest = linear_index;
            let mut q = [0.0; D];
            for a in 0..D {
                q[a] = origin[a] + (rest % dims[a]) as f64 * spacing;
                rest /= dims[a];
            }
            if keep(&q) {
                *slot = points.len() as u32;
                points.push(q);
            }
        }
        let mut transform = Vec::with_capacity(points.len());
        let mut inverse = Vec::with_capacity(points.len());
        let mut scales = Vec::with_capacity(points.len());
        for q in &points {
            let (r, s) = region.guided_frame(q, rotation, scale)?;
            let sr: Matrix<D> = std::array::from_fn(|i| std::array::from_fn(|j| r[i][j] * s));
            let inv: Matrix<D> = std::array::from_fn(|i| std::array::from_fn(|j| r[j][i] / s));
            transform.push(sr);
            inverse.push(inv);
            scales.push(s);
        }
        let depth = depth_transform(&dims, &lookup, points.len());
        Ok(Self {
            origin,
            inverse_spacing: 1.0 / spacing,
            dims,
            full: lookup.iter().all(|&k| k != NONE),
            identity_frames: transform.iter().all(|t| *t == linear::identity::<D>()),
            lookup,
            points,
            transform,
            inverse,
            scale: scales,
            pattern_dimension: D as i32,
            depth,
        })
    }

    /// How much the scale at quadrature point `k` divides the exemplar's density by:
    /// `s_k` to the pattern's dimension.
    pub(crate) fn density_scale(&self, k: usize) -> f64 {
        self.scale[k].powi(self.pattern_dimension)
    }

    /// On a surface domain, moves the quadrature points onto the surface and measures their
    /// depth along it (to its border; a closed surface has none), since the grid's own depth only
    /// sees the thin band.
    pub(crate) fn settle_on(&mut self, region: &Region<D>) {
        if let Region::Surface { .. } = region {
            self.pattern_dimension = 2;
            for k in 0..self.points.len() {
                let q = region.keep_on(&self.points[k]);
                self.points[k] = q;
                self.depth[k] = (region.depth(&q) * self.inverse_spacing).min(f64::from(u32::MAX / 2)) as u32;
            }
        }
    }

    /// The number of quadrature points.
    pub(crate) fn len(&self) -> usize {
        self.points.len()
    }

    /// Grid spacing.
    pub(crate) fn spacing(&self) -> f64 {
        1.0 / self.inverse_spacing
    }

    /// Whether the grid node nearest to `p` is a quadrature point, i.e. whether `p` lies in the
    /// integration domain Ω (at the grid's resolution). The exemplar function is compared with the
    /// output only there: outside Ω the output has no points by construction.
    #[inline(always)]
    pub(crate) fn inside(&self, p: &Vector<D>) -> bool {
        let mut index = 0;
        for a in (0..D).rev() {
            let t = (p[a] - self.origin[a]) * self.inverse_spacing;
            // `t.round()` (half away from zero) without a libm call: negative t rounds below 0 from
            // −0.5 on; otherwise truncation plus the exact fractional part decides.
            if t <= -0.5 || t >= self.dims[a] as f64 - 0.5 {
                return false;
            }
            if self.full {
                continue;
            }
            let whole = t as usize;
            let c = if t - whole as f64 >= 0.5 { whole + 1 } else { whole };
            index = index * self.dims[a] + c;
        }
        self.full || self.lookup[index] != NONE
    }

    /// Calls `visit(k)` for every quadrature point within `radius` of `x`.
    #[inline(always)]
    pub(crate) fn for_each_within(&self, x: &Vector<D>, radius: f64, mut visit: impl FnMut(usize)) {
        if let Some(range) = self.node_range(x, radius) {
            self.for_each_in_range(x, radius, &range, |k, _| visit(k));
        }
    }

    /// The grid nodes `(low, high)` (inclusive, per axis) of the cube of half-side `radius` around
    /// `x`; `None` when it misses the grid.
    #[inline(always)]
    pub(crate) fn node_range(&self, x: &Vector<D>, radius: f64) -> Option<([usize; D], [usize; D])> {
        let mut low = [0usize; D];
        let mut high = [0usize; D];
        for a in 0..D {
            let lo = ((x[a] - radius - self.origin[a]) * self.inverse_spacing).ceil();
            let hi = ((x[a] + radius - self.origin[a]) * self.inverse_spacing).floor();
            if hi < 0.0 || lo > (self.dims[a] - 1) as f64 {
                return None;
            }
            low[a] = lo.max(0.0) as usize;
            high[a] = (hi as usize).min(self.dims[a] - 1);
        }
        Some((low, high))
    }

    /// The coordinate along `axis` of the grid nodes with index `node` on that axis.
    #[inline(always)]
    pub(crate) fn node_coordinate(&self, axis: usize, node: usize) -> f64 {
        self.origin[axis] + node as f64 * self.spacing()
    }

    /// Calls `visit(k, node − low)` for every quadrature point within `radius` of `x` inside the
    /// node range `(low, high)` of [`Quadrature::node_range`] (in the order of `for_each_within`).
    #[inline(always)]
    pub(crate) fn for_each_in_range(
        &self,
        x: &Vector<D>,
        radius: f64,
        (low, high): &([usize; D], [usize; D]),
        mut visit: impl FnMut(usize, [usize; D]),
    ) {
        let r2 = radius * radius;
        let spacing = self.spacing();
        if D == 2 {
            for y in low[1]..=high[1] {
                let dy = self.origin[1] + y as f64 * spacing - x[1];
                for xi in low[0]..=high[0] {
                    let dx = self.origin[0] + xi as f64 * spacing - x[0];
                    if dx * dx + dy * dy < r2 {
                        let k = self.lookup[y * self.dims[0] + xi];
                        if k != NONE {
                            visit(k as usize, std::array::from_fn(|a| [xi - low[0], y - low[1]][a]));
                        }
                    }
                }
            }
        } else {
            for z in low[D - 1]..=high[D - 1] {
                let dz = self.origin[D - 1] + z as f64 * spacing - x[D - 1];
                for y in low[1]..=high[1] {
                    let dy = self.origin[1] + y as f64 * spacing - x[1];
                    for xi in low[0]..=high[0] {
                        let dx = self.origin[0] + xi as f64 * spacing - x[0];
                        if dx * dx + dy * dy + dz * dz < r2 {
                            let k = self.lookup[(z * self.dims[1] + y) * self.dims[0] + xi];
                            if k != NONE {
                                visit(
                                    k as usize,
                                    std::array::from_fn(|a| [xi - low[0], y - low[1], z - low[D - 1]][a]),
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}

/// Breadth-first L∞ distance transform of the quadrature mask: distance 0 on non-quadrature nodes,
/// border nodes at most 1 (the outside counts as empty).
fn depth_transform<const D: usize>(dims: &[usize; D], lookup: &[u32], count: usize) -> Vec<u32> {
    let total = lookup.len();
    let mut distance = vec![u32::MAX; total];
    let mut queue = std::collections::VecDeque::new();
    let coordinates = |index: usize| -> [usize; D] {
        let mut rest = index;
        std::array::from_fn(|a| {
            let c = rest % dims[a];
            rest /= dims[a];
            c
        })
    };
    for index in 0..total {
        if lookup[index] == NONE {
            distance[index] = 0;
            queue.push_back(index);
        }
    }
    for index in 0..total {
        let c = coordinates(index);
        if lookup[index] != NONE && (0..D).any(|a| c[a] == 0 || c[a] + 1 == dims[a]) {
            distance[index] = 1;
            queue.push_back(index);
        }
    }
    let neighbours = 3usize.pow(D as u32);
    while let Some(index) = queue.pop_front() {
        let c = coordinates(index);
        for n in 0..neighbours {
            let mut rest = n;
            let mut next = 0usize;
            let mut valid = true;
            let mut stride = 1;
            for a in 0..D {
                let step = rest % 3;
                rest /= 3;
                let value = c[a] as isize + step as isize - 1;
                if value < 0 || value >= dims[a] as isize {
                    valid = false;
                    break;
                }
                next += value as usize * stride;
                stride *= dims[a];
            }
            if valid && distance[next] == u32::MAX {
                distance[next] = distance[index] + 1;
                queue.push_back(next);
            }
        }
    }
    let mut depth = vec![0; count];
    for index in 0..total {
        if lookup[index] != NONE {
            depth[lookup[index] as usize] = distance[index];
        }
    }
    depth
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Domain;

    #[test]
    fn quadrature_queries_match_brute_force() {
        let region = Region::<2>::new(&Domain::Box { min: vec![0.0, 0.0], max: vec![5.0, 3.0] }).unwrap();
        let quadrature =
            Quadrature::new([0.0, 0.0], [5.0, 3.0], 0.5, |q| region.contains(q), &region, &Field::Unset, &Field::Unset)
                .unwrap();
        assert_eq!(quadrature.len(), 11 * 7);
        let x = [2.2, 1.1];
        let mut found = Vec::new();
        quadrature.for_each_within(&x, 1.3, |k| found.push(k));
        found.sort();
        let expected: Vec<usize> =
            (0..quadrature.len()).filter(|&k| linear::norm2(&linear::sub(&quadrature.points[k], &x)) < 1.69).collect();
        assert_eq!(found, expected);
    }

    #[test]
    fn inside_rounds_like_round() {
        // `inside` avoids `f64::round`; it must agree with the plain definition everywhere,
        // including exact ties (half a spacing) and points beyond either end of the grid.
        let region = Region::<2>::new(&Domain::Box { min: vec![0.0, 0.0], max: vec![5.0, 3.0] }).unwrap();
        let quadrature = Quadrature::new(
            [0.0, 0.0],
            [5.0, 3.0],
            0.5,
            |q| region.contains(q) && q[0] < 4.2,
            &region,
            &Field::Unset,
            &Field::Unset,
        )
        .unwrap();
        let plain = |p: &Vector<2>| {
            let mut index = 0;
            for a in (0..2).rev() {
                let c = ((p[a] - quadrature.origin[a]) * quadrature.inverse_spacing).round();
                if c < 0.0 || c > (quadrature.dims[a] - 1) as f64 {
                    return false;
                }
                index = index * quadrature.dims[a] + c as usize;
            }
            quadrature.lookup[index] != NONE
        };
        let mut checked = 0;
        for i in -12..=130 {
            for j in -12..=80 {
                // Steps of a tenth of a spacing hit the ties (x.25, x.75) exactly.
                let p = [i as f64 * 0.05 - 0.03 * ((i + j) % 2) as f64, j as f64 * 0.05];
                assert_eq!(quadrature.inside(&p), plain(&p), "at {p:?}");
                checked += usize::from(plain(&p));
            }
        }
        assert!(checked > 1000, "the test should cover the inside, not only the outside");
        assert!(!quadrature.inside(&[-0.25, 1.0]) && quadrature.inside(&[-0.2499, 1.0]));
    }
}
