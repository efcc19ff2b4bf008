//! The curve as used and the canvas around it: a closed curve cut open on request, the ribbon's
//! borders, and the canvas size with the document → canvas translation.

use motif_core::{InvalidParameter, Point, Polyline, RgbaImage, Vec2};

use crate::Error;
use crate::params::{Canvas, CurveParams, MAX_CANVAS_SIDE};
use crate::ribbon::Ribbon;

/// The curve as used: cut open when a closed curve is treated as open.
pub(crate) fn working_curve(curve: &Polyline, closed: bool) -> Result<Polyline, InvalidParameter> {
    if curve.is_closed() && !closed {
        let mut points = curve.points().to_vec();
        points.push(points[0]);
        Polyline::new(points, false)
    } else {
        Ok(curve.clone())
    }
}

/// Border points of the ribbon at about one canvas pixel apart.
pub(crate) fn ribbon_borders(ribbon: &Ribbon) -> (Vec<Point>, Vec<Point>) {
    let length = ribbon.length();
    let steps = (length.ceil() as usize).max(2);
    let xs = (0..=steps).map(|i| length * i as f64 / steps as f64);
    xs.map(|x| (ribbon.top(x), ribbon.bottom(x))).unzip()
}

/// Canvas size and the document → canvas translation.
pub(crate) fn canvas_geometry(
    curve: &Polyline,
    params: &CurveParams,
    avoidance: Option<&RgbaImage>,
) -> Result<(usize, usize, Vec2), Error> {
    if let Some(map) = avoidance {
        if let Canvas::Size { width, height } = params.canvas {
            if (width, height) != (map.width(), map.height()) {
                return Err(InvalidParameter::new(
                    "avoid",
                    format!("{}×{}", map.width(), map.height()),
                    format!("the avoidance map must have the canvas size {width}×{height}"),
                )
                .into());
            }
        }
        if map.width() == 0 || map.height() == 0 || map.width() > MAX_CANVAS_SIDE || map.height() > MAX_CANVAS_SIDE {
            return Err(InvalidParameter::new(
                "avoid",
                format!("{}×{}", map.width(), map.height()),
                format!("each side must be between 1 and {MAX_CANVAS_SIDE}"),
            )
            .into());
        }
        return Ok((map.width(), map.height(), Vec2::ZERO));
    }
    match params.canvas {
        Canvas::Size { width, height } => Ok((width, height, Vec2::ZERO)),
        Canvas::Fit { margin } => {
            let ribbon = Ribbon::new(curve, params.width)?.with_profile(&params.width_profile);
            let (top, bottom) = ribbon_borders(&ribbon);
            let bounds = motif_core::geometry::bounds_of(&[top, bottom].concat());
            let origin = Vec2::new((bounds.x0 - margin).floor(), (bounds.y0 - margin).floor());
            let width = (bounds.x1 + margin - origin.x).ceil() as usize;
            let height = (bounds.y1 + margin - origin.y).ceil() as usize;
            if width > MAX_CANVAS_SIDE || height > MAX_CANVAS_SIDE {
                return Err(InvalidParameter::new(
                    "canvas",
                    format!("{width}×{height}"),
                    format!("the fitted canvas exceeds {MAX_CANVAS_SIDE} pixels per side; scale the curve down"),
                )
                .into());
            }
            Ok((width.max(1), height.max(1), -origin))
        }
    }
}
