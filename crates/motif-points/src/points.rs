//! Point sets with attributes and optional element ids (§4.1, Eq. 1).

use crate::InputError;
use crate::{Error, PointSetProblem};

/// The largest coordinate magnitude a point set may hold: the extent of a set within ±1e100 is
/// at most 2e100, so its squared distances and its volume (at most 8e300 in 3D) stay finite.
pub const MAX_COORDINATE: f64 = 1e100;

/// A set of points `x_i ∈ R^d` (d = 2 or 3) with float attributes `a_i` and optional element ids.
///
/// Points that share an element id form one discrete element (§6.1) and move rigidly; points with
/// no element id (or a negative one) are free samples of a continuous structure.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PointSet {
    /// 2 or 3.
    pub dimension: usize,
    /// Coordinates, row-major: point `i` is `positions[i * dimension..(i + 1) * dimension]`.
    pub positions: Vec<f64>,
    /// Names of the attribute columns (colour channels, radius, normal components, labels...).
    pub attribute_names: Vec<String>,
    /// Attribute values, row-major: point `i` has `attributes[i * names.len()..]`.
    pub attributes: Vec<f64>,
    /// Element id per point, or `None` when the set has no element column. Negative ids mean "free".
    pub elements: Option<Vec<i64>>,
}

impl PointSet {
    /// A set of `dimension`-dimensional points without attributes.
    pub fn new(dimension: usize, positions: Vec<f64>) -> Self {
        Self { dimension, positions, ..Self::default() }
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.positions.len().checked_div(self.dimension).unwrap_or(0)
    }

    /// True when the set has no points.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The coordinates of point `i`.
    pub fn position(&self, i: usize) -> &[f64] {
        &self.positions[i * self.dimension..(i + 1) * self.dimension]
    }

    /// The attributes of point `i`.
    pub fn attributes_of(&self, i: usize) -> &[f64] {
        let n = self.attribute_names.len();
        &self.attributes[i * n..(i + 1) * n]
    }

    /// Checks shapes and values; `what` names the set in messages ("exemplar", "existing points").
    pub fn validate(&self, what: &str) -> Result<(), Error> {
        let problem = |problem: PointSetProblem| Error::Input(InputError::PointSet { set: what.to_string(), problem });
        if self.dimension != 2 && self.dimension != 3 {
            return Err(problem(PointSetProblem::Dimension(self.dimension)));
        }
        if !self.positions.len().is_multiple_of(self.dimension) {
            return Err(problem(PointSetProblem::RaggedCoordinates));
        }
        let n = self.len();
        if self.attributes.len() != n * self.attribute_names.len() {
            return Err(problem(PointSetProblem::AttributeCount {
                values: self.attributes.len(),
                points: n,
                attributes: self.attribute_names.len(),
            }));
        }
        if let Some(elements) = &self.elements
            && elements.len() != n
        {
            return Err(problem(PointSetProblem::ElementCount { ids: elements.len(), points: n }));
        }
        if let Some(i) = (0..n).find(|&i| self.position(i).iter().any(|v| !v.is_finite())) {
            return Err(problem(PointSetProblem::NonFiniteCoordinate { point: i }));
        }
        if let Some((i, &value)) = self.positions.iter().enumerate().find(|(_, v)| v.abs() > MAX_COORDINATE) {
            return Err(problem(PointSetProblem::CoordinateOutOfRange {
                point: i / self.dimension,
                value,
                limit: MAX_COORDINATE,
            }));
        }
        if let Some(i) = (0..n).find(|&i| self.attributes_of(i).iter().any(|v| !v.is_finite())) {
            let column = self.attributes_of(i).iter().position(|v| !v.is_finite()).unwrap_or(0);
            return Err(problem(PointSetProblem::NonFiniteAttribute {
                point: i,
                name: self.attribute_names[column].clone(),
            }));
        }
        Ok(())
    }
}
