//! Density and scale maps: grey images stretched over the target region's bounding box that make
//! the pattern follow an image's tones (the paper's future work: "non-uniform density").
//!
//! Encoding (documented for users in the README and `--help`):
//! - density: the darkness `1 − grey` of a pixel is the element density relative to the
//!   reference's. Black draws at the reference's density, mid-grey at half of it, white leaves the
//!   paper blank; so a hatching or stippling drawn from a photo shades it.
//! - scale: `2^(2·grey − 1)`: black halves the elements, mid-grey keeps them, white doubles them.
//!   Larger elements are spaced further apart (density divided by the scale squared), so they keep
//!   their reference spacing relative to their size.
//!
//! Grey is the sRGB value's Rec. 709 luma in [0, 1] over a white background (transparent pixels are
//! paper). The seeds follow the density by a weighted centroidal Voronoi tessellation: a CVT with
//! weight w spaces points with a density proportional to `w^(1/2)` in 2D (Gersho's asymptotic
//! result, as in Secord's weighted Voronoi stippling), so cells are weighted by the squared target
//! density to make the element density proportional to the map's darkness.

use kurbo::Rect;
use motif_core::{Point, ToneMap};

/// The density and scale maps of a synthesis, placed over the target's bounding box.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Maps<'a> {
    /// Relative element density (darkness), if any.
    pub density: Option<&'a ToneMap>,
    /// Element scale, if any.
    pub scale: Option<&'a ToneMap>,
    /// The target's bounding box.
    pub bounds: Rect,
}

impl Maps<'_> {
    /// True when neither map is given (the uniform pattern of the paper).
    pub(crate) fn is_uniform(&self) -> bool {
        self.density.is_none() && self.scale.is_none()
    }

    /// Element density at `point` relative to the reference's, in [0, 1] without a scale map.
    pub(crate) fn density_at(&self, point: Point) -> f64 {
        let darkness = self.density.map_or(1.0, |map| 1.0 - map.grey_at(&self.bounds, point));
        let scale = self.scale_at(point);
        darkness.max(0.0) / (scale * scale)
    }

    /// Element scale at `point`: `2^(2·grey − 1)`, 1 without a scale map.
    pub(crate) fn scale_at(&self, point: Point) -> f64 {
        self.scale.map_or(1.0, |map| {
            let grey = map.grey_at(&self.bounds, point);
            // 2^(2g − 1) through exact operations: the same bits natively and in WebAssembly.
            motif_core::math::powf(2.0, 2.0 * grey - 1.0)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grey_is_bilinear_and_encodings_follow_the_documentation() {
        let map = ToneMap::from_grey(2, 1, vec![0.0, 1.0]).unwrap();
        let bounds = Rect::new(0.0, 0.0, 20.0, 10.0);
        assert_eq!(map.grey_at(&bounds, Point::new(5.0, 5.0)), 0.0);
        assert_eq!(map.grey_at(&bounds, Point::new(15.0, 5.0)), 1.0);
        assert!((map.grey_at(&bounds, Point::new(10.0, 5.0)) - 0.5).abs() < 1e-12);
        let maps = Maps { density: Some(&map), scale: None, bounds };
        assert_eq!(maps.density_at(Point::new(1.0, 1.0)), 1.0);
        assert_eq!(maps.density_at(Point::new(19.0, 1.0)), 0.0);
        let scales = Maps { density: None, scale: Some(&map), bounds };
        assert!((scales.scale_at(Point::new(1.0, 1.0)) - 0.5).abs() < 1e-12);
        assert!((scales.scale_at(Point::new(19.0, 1.0)) - 2.0).abs() < 1e-12);
        assert!((scales.density_at(Point::new(1.0, 1.0)) - 4.0).abs() < 1e-12);
    }
}
