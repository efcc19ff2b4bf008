//! Strokes: the input and output primitives (§1: "connected vertices with attributes such as width
//! and color").

use kurbo::{Affine, BezPath};
use motif_core::{InvalidParameter, Point, Polyline};

/// One stroke: a polyline skeleton with a width and colours.
#[derive(Debug, Clone, PartialEq)]
pub struct Stroke {
    /// The skeleton, in drawing units (transforms already applied).
    pub polyline: Polyline,
    /// Stroke width in drawing units; 0 for a path that is only filled.
    pub width: f64,
    /// Stroke colour, 8-bit sRGB with straight alpha.
    pub colour: [u8; 4],
    /// Fill colour, when the path is filled (stipples and drops often are).
    pub fill: Option<[u8; 4]>,
}

impl Stroke {
    /// Strokes of one drawn path: every subpath, flattened within `tolerance` drawing units,
    /// becomes a stroke carrying the path's width and colours. Subpaths that collapse to a point
    /// are skipped.
    pub fn from_path(
        path: &BezPath,
        tolerance: f64,
        width: f64,
        colour: [u8; 4],
        fill: Option<[u8; 4]>,
    ) -> Result<Vec<Stroke>, InvalidParameter> {
        if !(width.is_finite() && width >= 0.0) {
            return Err(InvalidParameter::new("stroke width", width, "must be a finite number >= 0"));
        }
        Ok(Polyline::from_bez_path(path, tolerance)?
            .into_iter()
            .map(|polyline| Stroke { polyline, width, colour, fill })
            .collect())
    }

    /// True when the stroke leaves a mark: a visible stroke or a fill.
    pub fn is_visible(&self) -> bool {
        (self.width > 0.0 && self.colour[3] > 0) || self.fill.is_some_and(|fill| fill[3] > 0)
    }

    /// The colour that represents the stroke in the colour measure: its stroke colour when it is
    /// stroked, else its fill.
    pub fn representative_colour(&self) -> [u8; 4] {
        if self.width > 0.0 { self.colour } else { self.fill.unwrap_or(self.colour) }
    }

    /// The stroke under an affine map (width kept: the maps used here are rigid or mildly scaled).
    pub fn transformed(&self, transform: Affine) -> Stroke {
        let points: Vec<Point> = self.polyline.points().iter().map(|&p| transform * p).collect();
        let polyline = Polyline::new(points, self.polyline.is_closed()).unwrap_or_else(|_| self.polyline.clone());
        Stroke { polyline, ..self.clone() }
    }
}
