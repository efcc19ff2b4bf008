//! The curve as used and the canvas around it: a closed curve cut open on request, the ribbon's
//! borders, and the canvas size with the document → canvas translation.

use motif_core::{InvalidParameter, Point, Polyline, RgbaImage, Vec2};

use crate::Error;
use crate::params::{Canvas, MAX_CANVAS_PIXELS, MAX_CANVAS_SIDE, Params};
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
    params: &Params,
    avoidance: Option<&RgbaImage>,
) -> Result<(usize, usize, Vec2), Error> {
    let ribbon = Ribbon::new(curve, params.width)?.with_profile(&params.width_profile);
    let (top, bottom) = ribbon_borders(&ribbon);
    let bounds = motif_core::geometry::bounds_of(&[top, bottom].concat());
    let (width, height, shift) = match (avoidance, params.canvas) {
        (Some(map), canvas) => {
            if let Canvas::Size { width, height } = canvas
                && (width, height) != (map.width(), map.height())
            {
                return Err(InvalidParameter::new(
                    "avoid",
                    format!("{}×{}", map.width(), map.height()),
                    format!("the avoidance map must have the canvas size {width}×{height}"),
                )
                .into());
            }
            (map.width(), map.height(), Vec2::ZERO)
        }
        (None, Canvas::Size { width, height }) => (width, height, Vec2::ZERO),
        (None, Canvas::Fit { margin }) => {
            let origin = Vec2::new((bounds.x0 - margin).floor(), (bounds.y0 - margin).floor());
            let width = (bounds.x1 + margin - origin.x).ceil().max(1.0) as usize;
            let height = (bounds.y1 + margin - origin.y).ceil().max(1.0) as usize;
            (width, height, -origin)
        }
    };
    let name = if avoidance.is_some() { "avoid" } else { "canvas" };
    if width == 0 || height == 0 || width > MAX_CANVAS_SIDE || height > MAX_CANVAS_SIDE {
        return Err(InvalidParameter::new(
            name,
            format!("{width}×{height}"),
            format!("each side must be between 1 and {MAX_CANVAS_SIDE} pixels; scale the curve down"),
        )
        .into());
    }
    if width * height > MAX_CANVAS_PIXELS {
        return Err(InvalidParameter::new(
            name,
            format!("{width}×{height}"),
            format!(
                "the canvas would hold {:.0} megapixels, at most {} (about 10 bytes each); scale the curve down",
                (width * height) as f64 / 1e6,
                MAX_CANVAS_PIXELS / 1_000_000
            ),
        )
        .into());
    }
    // A canvas that shows no part of the ribbon would be written empty without a word.
    let (x0, y0, x1, y1) = (bounds.x0 + shift.x, bounds.y0 + shift.y, bounds.x1 + shift.x, bounds.y1 + shift.y);
    if x1 <= 0.0 || y1 <= 0.0 || x0 >= width as f64 || y0 >= height as f64 {
        return Err(InvalidParameter::new(
            name,
            format!("{width}×{height}"),
            format!(
                "the ribbon ({:.0}, {:.0})–({:.0}, {:.0}) lies outside the canvas; the canvas starts at the document \
                 origin: use a larger canvas, or leave --canvas out to fit it",
                x0, y0, x1, y1
            ),
        )
        .into());
    }
    Ok((width, height, shift))
}
