//! Grey images stretched over a rectangle of a drawing: the density, scale and rotation maps the
//! engines take (`motif strokes --density-map`, `motif points --rotation-map`, ...).
//!
//! Grey is the sRGB value's Rec. 709 luma in [0, 1] over a white background (transparent pixels
//! are paper). Each engine documents how it reads the grey.

use kurbo::{Point, Rect};

use crate::{InvalidParameter, RgbaImage};

/// The aspect ratio mismatch accepted between a map and the rectangle it covers, besides one
/// pixel of rounding.
const ASPECT_TOLERANCE: f64 = 0.02;

/// A grey image stretched over a rectangle of the drawing.
#[derive(Debug, Clone, PartialEq)]
pub struct ToneMap {
    width: usize,
    height: usize,
    grey: Vec<f32>,
}

impl ToneMap {
    /// The map of an image: each pixel's luma in [0, 1] over white.
    pub fn from_image(image: &RgbaImage) -> ToneMap {
        let grey = image
            .pixels()
            .iter()
            .map(|p| {
                let luma = (0.2126 * f32::from(p[0]) + 0.7152 * f32::from(p[1]) + 0.0722 * f32::from(p[2])) / 255.0;
                let alpha = f32::from(p[3]) / 255.0;
                alpha * luma + (1.0 - alpha)
            })
            .collect();
        ToneMap { width: image.width(), height: image.height(), grey }
    }

    /// A map from grey values in [0, 1], row by row from the top.
    pub fn from_grey(width: usize, height: usize, grey: Vec<f32>) -> Result<ToneMap, InvalidParameter> {
        if width == 0 || height == 0 || grey.len() != width * height {
            return Err(InvalidParameter::new(
                "tone map",
                format!("{width}×{height} with {} values", grey.len()),
                "needs width × height grey values and a size of at least 1×1",
            ));
        }
        if grey.iter().any(|g| !(0.0..=1.0).contains(g)) {
            return Err(InvalidParameter::new("tone map", "a value outside [0, 1]", "grey values in [0, 1]"));
        }
        Ok(ToneMap { width, height, grey })
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// The grey at `point` read as a fraction of a full turn (black and white both 0): the four
    /// nearest pixels' turns are averaged as unit vectors, so that a black pixel next to a white
    /// one, the same direction, does not average to half a turn. In [0, 1).
    pub fn turn_at(&self, bounds: &Rect, point: Point) -> f64 {
        if self.grey.is_empty() {
            return 0.0;
        }
        let u = (point.x - bounds.x0) / bounds.width().max(1e-300) * self.width as f64 - 0.5;
        let v = (point.y - bounds.y0) / bounds.height().max(1e-300) * self.height as f64 - 0.5;
        let (u, v) = (u.clamp(0.0, (self.width - 1) as f64), v.clamp(0.0, (self.height - 1) as f64));
        let (x0, y0) = (u.floor() as usize, v.floor() as usize);
        let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
        let (fx, fy) = (u - x0 as f64, v - y0 as f64);
        let tau = std::f64::consts::TAU;
        let (mut cosine, mut sine) = (0.0, 0.0);
        for (x, y, w) in
            [(x0, y0, (1.0 - fx) * (1.0 - fy)), (x1, y0, fx * (1.0 - fy)), (x0, y1, (1.0 - fx) * fy), (x1, y1, fx * fy)]
        {
            let angle = tau * f64::from(self.grey[y * self.width + x]);
            cosine += w * crate::math::cos(angle);
            sine += w * crate::math::sin(angle);
        }
        (crate::math::atan2(sine, cosine) / tau).rem_euclid(1.0)
    }

    /// Checks that the map can be stretched over `bounds` without distorting it: the aspect ratios
    /// agree within 2 % (and a pixel of rounding). `name` is the flag or field named in the error.
    pub fn check_fits(&self, bounds: &Rect, name: &str) -> Result<(), InvalidParameter> {
        if self.width == 0 || self.height == 0 {
            return Err(InvalidParameter::new(name, "an empty image", "an image of at least 1×1 pixel"));
        }
        let map = self.width as f64 / self.height as f64;
        let target = bounds.width() / bounds.height();
        let rounding = 1.0 / self.width.min(self.height) as f64;
        if !target.is_finite() || (map / target - 1.0).abs() > ASPECT_TOLERANCE + rounding {
            return Err(InvalidParameter::new(
                name,
                format!("a {}×{} px image (aspect {:.3})", self.width, self.height, map),
                format!(
                    "an image with the target's aspect ratio {:.3} ({} × {} drawing units); it is stretched over the target's bounding box",
                    target,
                    crate::error::number(bounds.width()),
                    crate::error::number(bounds.height())
                ),
            ));
        }
        Ok(())
    }

    /// The grey value at `point` of a drawing whose bounding box `bounds` the map covers
    /// (bilinear, clamped at the edges).
    pub fn grey_at(&self, bounds: &Rect, point: Point) -> f64 {
        if self.grey.is_empty() {
            return 1.0;
        }
        let u = (point.x - bounds.x0) / bounds.width().max(1e-300) * self.width as f64 - 0.5;
        let v = (point.y - bounds.y0) / bounds.height().max(1e-300) * self.height as f64 - 0.5;
        let clamp = |t: f64, size: usize| t.clamp(0.0, (size - 1) as f64);
        let (u, v) = (clamp(u, self.width), clamp(v, self.height));
        let (x0, y0) = (u.floor() as usize, v.floor() as usize);
        let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
        let (fx, fy) = (u - x0 as f64, v - y0 as f64);
        let at = |x: usize, y: usize| f64::from(self.grey[y * self.width + x]);
        let top = at(x0, y0) * (1.0 - fx) + at(x1, y0) * fx;
        let bottom = at(x0, y1) * (1.0 - fx) + at(x1, y1) * fx;
        top * (1.0 - fy) + bottom * fy
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grey_is_bilinear_and_clamped() {
        let map = ToneMap::from_grey(2, 1, vec![0.0, 1.0]).unwrap();
        let bounds = Rect::new(0.0, 0.0, 20.0, 10.0);
        assert_eq!(map.grey_at(&bounds, Point::new(5.0, 5.0)), 0.0);
        assert_eq!(map.grey_at(&bounds, Point::new(-5.0, 5.0)), 0.0);
        assert_eq!(map.grey_at(&bounds, Point::new(15.0, 5.0)), 1.0);
        assert!((map.grey_at(&bounds, Point::new(10.0, 5.0)) - 0.5).abs() < 1e-12);
        // Black and white are the same direction: their blend stays 0, not half a turn.
        let turns = ToneMap::from_grey(2, 1, vec![0.0, 1.0]).unwrap();
        assert!(
            turns.turn_at(&bounds, Point::new(10.0, 5.0)).min(1.0 - turns.turn_at(&bounds, Point::new(10.0, 5.0)))
                < 1e-9
        );
        let quarter = ToneMap::from_grey(2, 1, vec![0.25, 0.25]).unwrap();
        assert!((quarter.turn_at(&bounds, Point::new(10.0, 5.0)) - 0.25).abs() < 1e-12);
        let image = RgbaImage::from_fn(1, 1, |_, _| [0, 0, 0, 0]);
        assert_eq!(ToneMap::from_image(&image).grey_at(&bounds, Point::new(1.0, 1.0)), 1.0);
    }

    #[test]
    fn maps_must_have_the_target_aspect() {
        let map = ToneMap::from_grey(200, 100, vec![0.5; 20_000]).unwrap();
        assert!(map.check_fits(&Rect::new(0.0, 0.0, 400.0, 200.0), "density-map").is_ok());
        let error = map.check_fits(&Rect::new(0.0, 0.0, 400.0, 400.0), "density-map").unwrap_err();
        assert!(error.to_string().contains("density-map") && error.to_string().contains("200×100"), "{error}");
        assert!(ToneMap::from_grey(2, 2, vec![0.5; 3]).is_err());
        assert!(ToneMap::from_grey(1, 1, vec![f32::NAN]).is_err());
    }
}
