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
    /// Dash pattern (lengths of dashes and gaps, drawing units), when the stroke is dashed.
    pub dash: Option<Vec<f64>>,
}

impl Stroke {
    /// A solid stroke along `polyline`.
    pub fn new(polyline: Polyline, width: f64, colour: [u8; 4], fill: Option<[u8; 4]>) -> Stroke {
        Stroke { polyline, width, colour, fill, dash: None }
    }

    /// Strokes of one drawn path: every subpath, flattened within `tolerance` drawing units,
    /// becomes a stroke carrying the path's width, colours and dash pattern. Subpaths that
    /// collapse to a point are skipped; a dash pattern without a positive length counts as solid.
    pub fn from_path(
        path: &BezPath,
        tolerance: f64,
        width: f64,
        colour: [u8; 4],
        fill: Option<[u8; 4]>,
        dash: Option<&[f64]>,
    ) -> Result<Vec<Stroke>, InvalidParameter> {
        if !(width.is_finite() && width >= 0.0) {
            return Err(InvalidParameter::new("stroke width", width, "must be a finite number >= 0"));
        }
        let dash = match dash {
            Some(lengths) if lengths.iter().any(|l| !(l.is_finite() && *l >= 0.0)) => {
                return Err(InvalidParameter::new(
                    "stroke dash pattern",
                    format!("{lengths:?}"),
                    "lengths must be finite numbers >= 0",
                ));
            }
            Some(lengths) if lengths.iter().any(|&l| l > 0.0) => Some(lengths.to_vec()),
            _ => None,
        };
        Ok(Polyline::from_bez_path(path, tolerance)?
            .into_iter()
            .map(|polyline| Stroke { polyline, width, colour, fill, dash: dash.clone() })
            .collect())
    }

    /// The share of the stroke's length that is inked: the dashes' share of the dash period, 1
    /// for a solid stroke.
    pub fn inked_share(&self) -> f64 {
        match &self.dash {
            None => 1.0,
            Some(lengths) => {
                // An odd-length pattern repeats twice, so dashes and gaps swap on the repeat.
                let doubled: Vec<f64> = if lengths.len() % 2 == 1 {
                    lengths.iter().chain(lengths).copied().collect()
                } else {
                    lengths.clone()
                };
                let period: f64 = doubled.iter().sum();
                if period > 0.0 { doubled.iter().step_by(2).sum::<f64>() / period } else { 1.0 }
            }
        }
    }

    /// The dash period (dash and gap lengths summed; an odd-length pattern repeats twice before
    /// it starts over, as SVG draws it), 0 for a solid stroke.
    pub fn dash_period(&self) -> f64 {
        self.dash.as_ref().map_or(0.0, |lengths| {
            let once: f64 = lengths.iter().sum();
            if lengths.len() % 2 == 1 { 2.0 * once } else { once }
        })
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
