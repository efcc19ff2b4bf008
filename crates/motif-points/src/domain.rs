//! Output domains and guidance fields (§6.2): membership, the regular quadrature grid inside the
//! domain, and the rotation/scale frame stored at each quadrature point.

use motif_core::Point;

use crate::error::{DomainProblem, Error};
use crate::linear::{self, Matrix, Vector};
use crate::mesh_surface::MeshSurface;
use crate::params::{Domain, Field};
use crate::volume::MeshVolume;

/// A domain prepared for dimension `D`.
#[derive(Debug, Clone)]
pub enum Region<const D: usize> {
    /// Axis-aligned box.
    Box { min: Vector<D>, max: Vector<D> },
    /// 2D polygon.
    Polygon(motif_core::Polygon),
    /// Tube of radius `radius` around a polyline, with cumulative arc lengths.
    Stroke { vertices: Vec<Vector<D>>, cumulative: Vec<f64>, radius: f64, scale_start: f64, scale_end: f64 },
    /// The inside of a closed mesh (3D).
    Volume(Box<MeshVolume>),
    /// The band of half-width `band` around a mesh surface (3D, for a lifted 2D exemplar): the
    /// grid nodes in it are the quadrature points, moved onto the surface.
    Surface { surface: Box<MeshSurface>, band: f64 },
}

/// Where along a stroke a position projects.
#[derive(Debug, Clone, Copy)]
pub struct StrokeProjection<const D: usize> {
    pub distance: f64,
    pub arc: f64,
    pub tangent: Vector<D>,
}

impl<const D: usize> Region<D> {
    /// Checks the domain against the dimension.
    pub fn new(domain: &Domain) -> Result<Self, DomainProblem> {
        match domain {
            Domain::Box { min, max } => {
                if min.len() != D || max.len() != D {
                    return Err(DomainProblem::BoxDimension { coordinates: min.len(), exemplar: D });
                }
                let min: Vector<D> = std::array::from_fn(|i| min[i]);
                let max: Vector<D> = std::array::from_fn(|i| max[i]);
                if (0..D).any(|i| !(min[i].is_finite() && max[i].is_finite() && max[i] > min[i])) {
                    return Err(DomainProblem::EmptyBox);
                }
                Ok(Region::Box { min, max })
            }
            Domain::Polygon(polygon) => {
                if D != 2 {
                    return Err(DomainProblem::PolygonIn3d);
                }
                if polygon.area() <= 0.0 {
                    return Err(DomainProblem::ZeroAreaPolygon);
                }
                Ok(Region::Polygon(polygon.clone()))
            }
            Domain::Stroke(stroke) => {
                if !(stroke.width.is_finite() && stroke.width > 0.0) {
                    return Err(DomainProblem::BrushWidth(stroke.width));
                }
                for s in [stroke.scale_start, stroke.scale_end] {
                    if !(s.is_finite() && s > 0.0) {
                        return Err(DomainProblem::StrokeScale(s));
                    }
                }
                let mut vertices: Vec<Vector<D>> = Vec::new();
                for p in &stroke.points {
                    if p.len() != D {
                        return Err(DomainProblem::StrokeVertexDimension { coordinates: p.len(), exemplar: D });
                    }
                    if p.iter().any(|v| !v.is_finite()) {
                        return Err(DomainProblem::NonFiniteStrokeVertex);
                    }
                    let v: Vector<D> = std::array::from_fn(|i| p[i]);
                    if vertices.last().is_none_or(|last| linear::norm2(&linear::sub(&v, last)) > 1e-24) {
                        vertices.push(v);
                    }
                }
                if vertices.len() < 2 {
                    return Err(DomainProblem::ShortStroke);
                }
                let mut cumulative = vec![0.0];
                for w in vertices.windows(2) {
                    let length = linear::norm2(&linear::sub(&w[1], &w[0])).sqrt();
                    cumulative.push(cumulative.last().copied().unwrap_or(0.0) + length);
                }
                Ok(Region::Stroke {
                    vertices,
                    cumulative,
                    radius: stroke.width / 2.0,
                    scale_start: stroke.scale_start,
                    scale_end: stroke.scale_end,
                })
            }
            Domain::Volume(mesh) => {
                if D != 3 {
                    return Err(DomainProblem::VolumeIn2d);
                }
                Ok(Region::Volume(Box::new(MeshVolume::new(mesh)?)))
            }
            Domain::Surface { mesh, directions } => {
                if D != 3 {
                    return Err(DomainProblem::SurfaceExemplar(3));
                }
                Ok(Region::Surface { surface: Box::new(MeshSurface::new(mesh, directions)?), band: 0.0 })
            }
        }
    }

    /// A position of this (3D) region as a 3-vector.
    fn point3(p: &Vector<D>) -> [f64; 3] {
        std::array::from_fn(|i| if i < D { p[i] } else { 0.0 })
    }

    /// The bounding box.
    pub fn bounds(&self) -> (Vector<D>, Vector<D>) {
        match self {
            Region::Box { min, max } => (*min, *max),
            Region::Polygon(polygon) => {
                let b = polygon.bounds();
                (
                    std::array::from_fn(|i| if i == 0 { b.x0 } else { b.y0 }),
                    std::array::from_fn(|i| if i == 0 { b.x1 } else { b.y1 }),
                )
            }
            Region::Stroke { vertices, radius, .. } => {
                let (mut low, mut high) = crate::grid::bounds(vertices);
                for a in 0..D {
                    low[a] -= radius;
                    high[a] += radius;
                }
                (low, high)
            }
            Region::Volume(volume) => {
                let (low, high) = volume.bounds();
                (std::array::from_fn(|i| low[i]), std::array::from_fn(|i| high[i]))
            }
            Region::Surface { surface, band } => {
                let (low, high) = surface.bounds();
                (std::array::from_fn(|i| low[i] - band), std::array::from_fn(|i| high[i] + band))
            }
        }
    }

    /// Projection onto a stroke (nearest point of the polyline).
    pub fn project(vertices: &[Vector<D>], cumulative: &[f64], p: &Vector<D>) -> StrokeProjection<D> {
        let mut best = StrokeProjection { distance: f64::INFINITY, arc: 0.0, tangent: [0.0; D] };
        for s in 0..vertices.len() - 1 {
            let a = vertices[s];
            let d = linear::sub(&vertices[s + 1], &a);
            let length2 = linear::norm2(&d);
            let t = (linear::dot(&linear::sub(p, &a), &d) / length2).clamp(0.0, 1.0);
            let closest = linear::add(&a, &linear::scale(&d, t));
            let distance = linear::norm2(&linear::sub(p, &closest)).sqrt();
            if distance < best.distance {
                let length = length2.sqrt();
                best = StrokeProjection {
                    distance,
                    arc: cumulative[s] + t * length,
                    tangent: linear::scale(&d, 1.0 / length),
                };
            }
        }
        best
    }

    /// The exact volume (area in 2D) of a box, polygon or consistently oriented mesh; `None` for a
    /// stroke or an inconsistently oriented mesh, which the quadrature grid measures instead.
    pub fn volume(&self) -> Option<f64> {
        match self {
            Region::Box { min, max } => Some((0..D).map(|a| (max[a] - min[a]).max(0.0)).product()),
            Region::Polygon(polygon) => Some(polygon.area()),
            Region::Stroke { .. } => None,
            Region::Volume(volume) => volume.volume(),
            // The lifted exemplar's window is as thick as the band, so that points per volume of
            // band are points per area of surface.
            Region::Surface { surface, band } => Some(surface.area() * 2.0 * band),
        }
    }

    /// Distance from `p` to the domain (0 inside).
    pub fn distance(&self, p: &Vector<D>) -> f64 {
        match self {
            Region::Box { min, max } => {
                let mut d2 = 0.0;
                for a in 0..D {
                    let d = (min[a] - p[a]).max(p[a] - max[a]).max(0.0);
                    d2 += d * d;
                }
                d2.sqrt()
            }
            Region::Polygon(polygon) => {
                let point = Point::new(p[0], p[1]);
                if polygon.contains(point) { 0.0 } else { polygon.distance_to_boundary(point) }
            }
            Region::Stroke { vertices, cumulative, radius, .. } => {
                (Self::project(vertices, cumulative, p).distance - radius).max(0.0)
            }
            Region::Volume(volume) => {
                let p = Self::point3(p);
                if volume.contains(&p) { 0.0 } else { volume.distance_to_surface(&p) }
            }
            Region::Surface { surface, band } => (surface.closest(&Self::point3(p)).distance - band).max(0.0),
        }
    }

    /// Distance from `p` to the domain's border when inside (0 outside).
    pub fn depth(&self, p: &Vector<D>) -> f64 {
        match self {
            Region::Box { min, max } => crate::fidelity::box_depth(p, min, max, D).max(0.0),
            Region::Polygon(polygon) => {
                let point = Point::new(p[0], p[1]);
                if polygon.contains(point) { polygon.distance_to_boundary(point) } else { 0.0 }
            }
            Region::Stroke { vertices, cumulative, radius, .. } => {
                (radius - Self::project(vertices, cumulative, p).distance).max(0.0)
            }
            Region::Volume(volume) => {
                let p = Self::point3(p);
                if volume.contains(&p) { volume.distance_to_surface(&p) } else { 0.0 }
            }
            Region::Surface { surface, band } => {
                let closest = surface.closest(&Self::point3(p));
                if closest.distance <= *band { surface.border_distance(&closest.point) } else { 0.0 }
            }
        }
    }

    /// Whether `p` lies inside the domain.
    pub fn contains(&self, p: &Vector<D>) -> bool {
        match self {
            Region::Box { min, max } => (0..D).all(|a| p[a] >= min[a] && p[a] <= max[a]),
            Region::Polygon(polygon) => polygon.contains(Point::new(p[0], p[1])),
            Region::Stroke { .. } => self.distance(p) <= 0.0,
            Region::Volume(volume) => volume.contains(&Self::point3(p)),
            Region::Surface { surface, band } => surface.within(&Self::point3(p), *band),
        }
    }

    /// Where a position is kept: its closest point on a surface domain, itself elsewhere.
    pub fn keep_on(&self, p: &Vector<D>) -> Vector<D> {
        match self {
            Region::Surface { surface, .. } => {
                let point = surface.closest(&Self::point3(p)).point;
                std::array::from_fn(|i| point[i])
            }
            _ => *p,
        }
    }

    /// The rotation `R` and scale `s` at `p` of Eq. 8: the domain's own frame composed with the
    /// guidance fields' rotation (about the exemplar's z axis) and scale.
    pub fn guided_frame(&self, p: &Vector<D>, rotation: &Field, scale: &Field) -> Result<(Matrix<D>, f64), Error> {
        let (own_rotation, own_scale) = self.frame(p);
        let angle = rotation.value(p, 0.0).to_radians();
        let s = own_scale * scale.value(p, 1.0);
        if !(s.is_finite() && s > 0.0 && angle.is_finite()) {
            return Err(Error::InvalidField { scale: s, rotation: angle });
        }
        Ok((linear::mat_mul(&own_rotation, &linear::rotation_xy::<D>(angle)), s))
    }

    /// The rotation and scale the domain itself imposes at `p` (strokes: tangent and scale along).
    pub fn frame(&self, p: &Vector<D>) -> (Matrix<D>, f64) {
        match self {
            Region::Stroke { vertices, cumulative, scale_start, scale_end, .. } => {
                let projection = Self::project(vertices, cumulative, p);
                let total = cumulative.last().copied().unwrap_or(1.0).max(1e-300);
                let t = (projection.arc / total).clamp(0.0, 1.0);
                (linear::rotation_from_x(&projection.tangent), scale_start + (scale_end - scale_start) * t)
            }
            Region::Surface { surface, .. } => {
                let frame = surface.frame(&Self::point3(p));
                (std::array::from_fn(|i| std::array::from_fn(|j| frame[i][j])), 1.0)
            }
            _ => (linear::identity(), 1.0),
        }
    }
}

/// The quadrature points `q_k` on a regular grid, with the frame `s_k R_k` of Eq. 8 at each.
#[derive(Debug, Clone)]
pub struct Quadrature<const D: usize> {
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
    /// Per quadrature point: the L∞ distance, in grid steps, to the nearest grid node that is not
    /// a quadrature point (or to the outside of the grid).
    pub depth: Vec<u32>,
}

const NONE: u32 = u32::MAX;

impl<const D: usize> Quadrature<D> {
    /// Grid nodes of spacing `spacing` over `[low, high]` accepted by `keep`, with frames from the
    /// region and the guidance fields. Errors when the grid would be absurdly large.
    pub fn new(
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
            return Err(Error::TooManyQuadraturePoints { count: total, limit: 60_000_000 });
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
            depth,
        })
    }

    /// On a surface domain, moves the quadrature points onto the surface and measures their
    /// depth along it (to its border; a closed surface has none), since the grid's own depth only
    /// sees the thin band.
    pub fn settle_on(&mut self, region: &Region<D>) {
        if let Region::Surface { .. } = region {
            for k in 0..self.points.len() {
                let q = region.keep_on(&self.points[k]);
                self.points[k] = q;
                self.depth[k] = (region.depth(&q) * self.inverse_spacing).min(f64::from(u32::MAX / 2)) as u32;
            }
        }
    }

    /// The number of quadrature points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Grid spacing.
    pub fn spacing(&self) -> f64 {
        1.0 / self.inverse_spacing
    }

    /// Whether the grid node nearest to `p` is a quadrature point, i.e. whether `p` lies in the
    /// integration domain Ω (at the grid's resolution). The exemplar function is compared with the
    /// output only there: outside Ω the output has no points by construction.
    #[inline(always)]
    pub fn inside(&self, p: &Vector<D>) -> bool {
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
    pub fn for_each_within(&self, x: &Vector<D>, radius: f64, mut visit: impl FnMut(usize)) {
        if let Some(range) = self.node_range(x, radius) {
            self.for_each_in_range(x, radius, &range, |k, _| visit(k));
        }
    }

    /// The grid nodes `(low, high)` (inclusive, per axis) of the cube of half-side `radius` around
    /// `x`; `None` when it misses the grid.
    #[inline(always)]
    pub fn node_range(&self, x: &Vector<D>, radius: f64) -> Option<([usize; D], [usize; D])> {
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
    pub fn node_coordinate(&self, axis: usize, node: usize) -> f64 {
        self.origin[axis] + node as f64 * self.spacing()
    }

    /// Calls `visit(k, node − low)` for every quadrature point within `radius` of `x` inside the
    /// node range `(low, high)` of [`Quadrature::node_range`] (in the order of `for_each_within`).
    #[inline(always)]
    pub fn for_each_in_range(
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
    use crate::params::Stroke;

    #[test]
    fn quadrature_queries_match_brute_force() {
        let region = Region::<2>::new(&Domain::Box { min: vec![0.0, 0.0], max: vec![5.0, 3.0] }).unwrap();
        let quadrature =
            Quadrature::new([0.0, 0.0], [5.0, 3.0], 0.5, |q| region.contains(q), &region, &Field::None, &Field::None)
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
            &Field::None,
            &Field::None,
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

    #[test]
    fn stroke_frames_follow_the_tangent_and_scale() {
        let stroke =
            Stroke { points: vec![vec![0.0, 0.0], vec![0.0, 10.0]], width: 2.0, scale_start: 1.0, scale_end: 3.0 };
        let region = Region::<2>::new(&Domain::Stroke(stroke)).unwrap();
        assert!(region.contains(&[0.5, 5.0]));
        assert!(!region.contains(&[1.5, 5.0]));
        let (rotation, scale) = region.frame(&[0.2, 5.0]);
        assert!((scale - 2.0).abs() < 1e-12);
        let x = linear::mat_vec(&rotation, &[1.0, 0.0]);
        assert!(x[0].abs() < 1e-12 && (x[1] - 1.0).abs() < 1e-12);
    }
}
