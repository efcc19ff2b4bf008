//! Output domains and guidance fields (§6.2): membership, projection onto a surface, and the
//! rotation/scale frame each quadrature point stores (see `quadrature`).

use motif_core::Point;

use crate::InputError;
use crate::error::{DomainProblem, Error};
use crate::linear::{self, Matrix, Vector};
use crate::mesh_surface::MeshSurface;
use crate::params::{Domain, Field};
use crate::volume::MeshVolume;

pub(crate) use crate::quadrature::Quadrature;

/// A domain prepared for dimension `D`.
#[derive(Debug, Clone)]
pub(crate) enum Region<const D: usize> {
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

/// The scales along a stroke lie in `[1 / MAX_STROKE_SCALE, MAX_STROKE_SCALE]`: the scale is
/// interpolated between the stroke's two ends, and a ratio wider than 1e12 between them rounds the
/// smaller end away (1e300 to 1 gives 0 at the far end).
pub const MAX_STROKE_SCALE: f64 = 1e6;

/// Where along a stroke a position projects.
#[derive(Debug, Clone, Copy)]
pub(crate) struct StrokeProjection<const D: usize> {
    pub distance: f64,
    pub arc: f64,
    pub tangent: Vector<D>,
}

impl<const D: usize> Region<D> {
    /// Checks the domain against the dimension.
    pub(crate) fn new(domain: &Domain) -> Result<Self, DomainProblem> {
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
                    if !((1.0 / MAX_STROKE_SCALE..=MAX_STROKE_SCALE).contains(&s)) {
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
    pub(crate) fn bounds(&self) -> (Vector<D>, Vector<D>) {
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
    pub(crate) fn project(vertices: &[Vector<D>], cumulative: &[f64], p: &Vector<D>) -> StrokeProjection<D> {
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
    pub(crate) fn volume(&self) -> Option<f64> {
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
    pub(crate) fn distance(&self, p: &Vector<D>) -> f64 {
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
    pub(crate) fn depth(&self, p: &Vector<D>) -> f64 {
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
    pub(crate) fn contains(&self, p: &Vector<D>) -> bool {
        match self {
            Region::Box { min, max } => (0..D).all(|a| p[a] >= min[a] && p[a] <= max[a]),
            Region::Polygon(polygon) => polygon.contains(Point::new(p[0], p[1])),
            Region::Stroke { .. } => self.distance(p) <= 0.0,
            Region::Volume(volume) => volume.contains(&Self::point3(p)),
            Region::Surface { surface, band } => surface.within(&Self::point3(p), *band),
        }
    }

    /// Where a position is kept: its closest point on a surface domain, itself elsewhere.
    pub(crate) fn keep_on(&self, p: &Vector<D>) -> Vector<D> {
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
    pub(crate) fn guided_frame(
        &self,
        p: &Vector<D>,
        rotation: &Field,
        scale: &Field,
    ) -> Result<(Matrix<D>, f64), Error> {
        let (own_rotation, own_scale) = self.frame(p);
        let angle = rotation.value(p, 0.0).to_radians();
        let s = own_scale * scale.value(p, 1.0);
        if !(s.is_finite() && s > 0.0 && angle.is_finite()) {
            return Err(Error::Input(InputError::InvalidField { scale: s, rotation: angle }));
        }
        Ok((linear::mat_mul(&own_rotation, &linear::rotation_xy::<D>(angle)), s))
    }

    /// The rotation and scale the domain itself imposes at `p` (strokes: tangent and scale along).
    pub(crate) fn frame(&self, p: &Vector<D>) -> (Matrix<D>, f64) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::BrushStroke;
    #[test]
    fn stroke_frames_follow_the_tangent_and_scale() {
        let stroke =
            BrushStroke { points: vec![vec![0.0, 0.0], vec![0.0, 10.0]], width: 2.0, scale_start: 1.0, scale_end: 3.0 };
        let region = Region::<2>::new(&Domain::Stroke(stroke)).unwrap();
        assert!(region.contains(&[0.5, 5.0]));
        assert!(!region.contains(&[1.5, 5.0]));
        let (rotation, scale) = region.frame(&[0.2, 5.0]);
        assert!((scale - 2.0).abs() < 1e-12);
        let x = linear::mat_vec(&rotation, &[1.0, 0.0]);
        assert!(x[0].abs() < 1e-12 && (x[1] - 1.0).abs() < 1e-12);
    }
}
