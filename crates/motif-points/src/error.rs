//! The engine's errors: typed, so that a front end can tell them apart; messages are lower-case
//! and say what to change.

use motif_core::InvalidParameter;

/// Everything that can go wrong, grouped as image-rs groups its errors: a parameter out of its
/// range, an input the engine cannot use, or a run that would pass a limit. Messages are
/// lower-case and say what to change.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is outside its range.
    #[error(transparent)]
    Parameter(#[from] InvalidParameter),
    /// An input point set, domain, mesh or attribute cannot be used as given.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The run would pass a limit on points, quadrature points or memory.
    #[error(transparent)]
    Limit(#[from] LimitError),
}

impl From<motif_core::TooMuchMemory> for Error {
    fn from(error: motif_core::TooMuchMemory) -> Self {
        Self::Limit(LimitError::Memory(error))
    }
}

/// An input point set, domain, mesh or attribute cannot be used as given ([`Error::Input`]).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum InputError {
    /// A point set's shape or values are unusable.
    #[error("{set}: {problem}")]
    PointSet {
        /// Which set ("exemplar", "existing points").
        set: String,
        /// What is wrong with it.
        problem: PointSetProblem,
    },
    /// The exemplar has fewer than 3 points.
    #[error("the exemplar has {count} points; it needs at least 3")]
    TooFewPoints {
        /// Its points.
        count: usize,
    },
    /// The existing points and the exemplar differ in dimension.
    #[error("the existing points are {existing}D but the exemplar is {exemplar}D")]
    DimensionMismatch {
        /// Dimension of the existing points.
        existing: usize,
        /// Dimension of the exemplar.
        exemplar: usize,
    },
    /// Every exemplar point lies at one place.
    #[error("the exemplar's points all coincide; they need a positive spacing")]
    CoincidentPoints,
    /// Every exemplar point has another at the same place (a doubled set), so no point has a
    /// positive distance to its nearest neighbour.
    #[error(
        "every exemplar point has a duplicate at the same place (points {first} and {second} coincide, for one), so \
         the nearest-neighbour spacing is 0: remove the duplicated points"
    )]
    DuplicatedPoints {
        /// One point of a coinciding pair.
        first: usize,
        /// The other point of that pair.
        second: usize,
    },
    /// An attribute named in the parameters (or needed by the existing points) is not there.
    #[error("{}", role.message(name, available))]
    UnknownAttribute {
        /// The attribute's name.
        name: String,
        /// Where it was named.
        role: AttributeRole,
        /// The attributes there are.
        available: Vec<String>,
    },
    /// The rotation or scale field gives an unusable frame somewhere.
    #[error(
        "the guidance fields give scale {scale} and rotation {rotation} at a quadrature point; the scale must be \
         positive and finite"
    )]
    InvalidField {
        /// The scale there.
        scale: f64,
        /// The rotation there, radians.
        rotation: f64,
    },
    /// The domain is unusable: malformed, or holding less than one point at the exemplar's density.
    #[error("unusable domain: {0}")]
    EmptyDomain(DomainProblem),
}

/// The run would pass a limit on points, quadrature points or memory ([`Error::Limit`]).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LimitError {
    /// The domain needs more quadrature points than the memory cap allows.
    #[error(
        "domain too large: it needs {count} quadrature points, more than the {limit} allowed (about 2 GB); make it \
         smaller, raise the quadrature spacing or sigma"
    )]
    TooManyQuadraturePoints {
        /// Quadrature points the domain needs.
        count: usize,
        /// The cap.
        limit: usize,
    },
    /// The domain asks for more points than `max_points`.
    #[error(
        "domain too large: it asks for about {expected:.0} points at the exemplar's density, more than the {limit} \
         allowed (max-points); use a smaller domain or a larger scale, or raise max-points"
    )]
    TooManyPoints {
        /// Points the exemplar's density asks for over the domain.
        expected: f64,
        /// [`Params::max_points`](crate::Params::max_points).
        limit: usize,
    },
    /// The run's estimated memory passes [`Params::max_memory`](crate::Params::max_memory).
    #[error(transparent)]
    Memory(#[from] motif_core::TooMuchMemory),
}

/// What is wrong with a point set ([`InputError::PointSet`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PointSetProblem {
    /// Points have neither 2 nor 3 coordinates.
    #[error("points must have 2 or 3 coordinates, not {0}")]
    Dimension(usize),
    /// The coordinate list does not split into points.
    #[error("coordinate count is not a multiple of the dimension")]
    RaggedCoordinates,
    /// The attribute values do not match points × attributes.
    #[error("{values} attribute values for {points} points and {attributes} attributes")]
    AttributeCount {
        /// Values given.
        values: usize,
        /// Points.
        points: usize,
        /// Attribute names.
        attributes: usize,
    },
    /// The element ids do not match the points.
    #[error("{ids} element ids for {points} points")]
    ElementCount {
        /// Ids given.
        ids: usize,
        /// Points.
        points: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("point {point} has a non-finite coordinate (NaN or infinity)")]
    NonFiniteCoordinate {
        /// The point's index.
        point: usize,
    },
    /// A coordinate so large that distances, areas and volumes of the set would overflow.
    #[error(
        "point {point} has coordinate {value:e}; coordinates must lie within ±{limit:e} (beyond it the set's \
         distances, areas and volumes overflow)"
    )]
    CoordinateOutOfRange {
        /// The point's index.
        point: usize,
        /// The coordinate.
        value: f64,
        /// [`MAX_COORDINATE`](crate::MAX_COORDINATE).
        limit: f64,
    },
    /// An attribute value is NaN or infinite.
    #[error(
        "point {point} has a non-finite value (NaN or infinity) in attribute {name:?}; every attribute needs a number \
         at every point"
    )]
    NonFiniteAttribute {
        /// The point's index.
        point: usize,
        /// The attribute.
        name: String,
    },
}

/// What is wrong with a domain ([`InputError::EmptyDomain`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DomainProblem {
    /// A box's corner has the wrong number of coordinates.
    #[error("the box has {coordinates} coordinates but the exemplar is {exemplar}D")]
    BoxDimension {
        /// Coordinates given.
        coordinates: usize,
        /// The exemplar's dimension.
        exemplar: usize,
    },
    /// A box side is zero, negative or not finite.
    #[error("the box has zero or negative size (every side must be > 0)")]
    EmptyBox,
    /// A polygon region with a 3D exemplar.
    #[error("a polygon region needs a 2D exemplar")]
    PolygonIn3d,
    /// A polygon region without area.
    #[error("the polygon region has zero area")]
    ZeroAreaPolygon,
    /// A brush width that is not a positive number.
    #[error("brush width {0} must be > 0")]
    BrushWidth(f64),
    /// A stroke scale outside `[1 / MAX_STROKE_SCALE, MAX_STROKE_SCALE]` ([`crate::MAX_STROKE_SCALE`]).
    #[error(
        "stroke scale (scale-along) {0:e} must lie between {min:e} and {max:e}",
        min = 1.0 / crate::MAX_STROKE_SCALE,
        max = crate::MAX_STROKE_SCALE
    )]
    StrokeScale(f64),
    /// A stroke vertex with the wrong number of coordinates.
    #[error("a stroke vertex has {coordinates} coordinates but the exemplar is {exemplar}D")]
    StrokeVertexDimension {
        /// Coordinates given.
        coordinates: usize,
        /// The exemplar's dimension.
        exemplar: usize,
    },
    /// A stroke vertex that is NaN or infinite.
    #[error("a stroke vertex is not finite")]
    NonFiniteStrokeVertex,
    /// A volume domain's mesh without triangles.
    #[error("the mesh has no triangles")]
    EmptyMesh,
    /// A mesh vertex that is NaN or infinite.
    #[error("mesh vertex {0} is not finite")]
    NonFiniteMeshVertex(usize),
    /// A triangle index past the vertices.
    #[error("mesh triangle {triangle} refers to a vertex past the {vertices} vertices")]
    MeshIndex {
        /// The triangle.
        triangle: usize,
        /// Vertices in the mesh.
        vertices: usize,
    },
    /// A triangle without area.
    #[error("mesh triangle {0} is degenerate (no area): remove it or weld the mesh")]
    DegenerateTriangle(usize),
    /// A volume mesh with boundary edges.
    #[error("the mesh is open ({0} edges belong to an odd number of triangles): a volume needs a closed surface")]
    OpenMesh(usize),
    /// A volume domain with a 2D exemplar.
    #[error("a volume domain needs a 3D exemplar")]
    VolumeIn2d,
    /// A surface domain with a 3D exemplar.
    #[error("a surface domain needs a 2D exemplar (its plane is laid on the surface); this one is {0}D")]
    SurfaceExemplar(usize),
    /// A surface direction that is NaN, infinite or zero.
    #[error("the surface direction field has a vector that is not finite, or is zero")]
    SurfaceDirection,
    /// A per-vertex direction field of the wrong length.
    #[error("the surface direction field has {given} vectors but the mesh has {vertices} vertices")]
    SurfaceDirectionCount {
        /// Vectors given.
        given: usize,
        /// Vertices in the mesh.
        vertices: usize,
    },
    /// A stroke of fewer than two distinct vertices.
    #[error("the stroke needs at least two distinct vertices")]
    ShortStroke,
    /// The domain holds less than one point at the exemplar's density.
    #[error("the domain holds {expected:.2} points at the exemplar's density; make it larger")]
    TooSmall {
        /// Points the exemplar's density asks for over it.
        expected: f64,
    },
}

/// Where an unknown attribute was named ([`InputError::UnknownAttribute`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum AttributeRole {
    /// In the list of attributes to synthesize.
    Synthesized,
    /// As discrete or continuous.
    DiscreteOrContinuous,
    /// With a weight.
    Weighted,
    /// Needed by the existing points (the exemplar has it, they do not).
    Existing,
}

impl AttributeRole {
    fn message(self, name: &str, available: &[String]) -> String {
        let list = available.join(", ");
        match self {
            Self::Synthesized => format!("the exemplar has no attribute {name:?} (it has: {list})"),
            Self::DiscreteOrContinuous => format!(
                "attribute {name:?} (named as discrete or continuous) is not among the synthesized attributes ({list})"
            ),
            Self::Weighted => format!("attribute weight for {name:?}: no such synthesized attribute ({list})"),
            Self::Existing => format!("the existing points have no attribute {name:?}"),
        }
    }
}
