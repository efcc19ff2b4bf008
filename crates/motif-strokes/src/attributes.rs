//! Stroke attributes of an element besides its colour: width, opacity, fill and dash.
//!
//! §3.1 compares neighbourhoods by geometry and colour; a drawing whose elements differ by line
//! weight, transparency, filling or dashing (a map's dashed paths next to solid ones, bold and
//! light hatching) needs those compared too, or a neighbourhood of thin strokes accepts a thick
//! one. Each attribute is averaged over the element's strokes, weighted by length; the attribute
//! measure of a pair is the largest of their differences: relative width and dash period,
//! opacity, filled and inked shares, each in [0, 1], and the fill colours' distance in the RGB unit
//! cube (up to √3, as for the colour measure); it must stay under its threshold like the colour
//! measure.

use crate::stroke::Stroke;

/// What the colour and attribute measures compare: an element's mean colour and attributes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Appearance {
    /// Mean colour in the RGB unit cube.
    pub colour: [f64; 3],
    /// Width, opacity, fill and dash.
    pub attributes: Attributes,
}

impl Appearance {
    /// An appearance of solid, opaque, unfilled strokes of width 1 in `colour`.
    pub fn coloured(colour: [f64; 3]) -> Appearance {
        Appearance {
            colour,
            attributes: Attributes { width: 1.0, opacity: 1.0, inked_share: 1.0, ..Attributes::default() },
        }
    }
}

/// Length-weighted attributes of an element's strokes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Attributes {
    /// Mean stroke width (0 for strokes that are only filled), drawing units.
    pub width: f64,
    /// Mean opacity of the visible paint, in [0, 1].
    pub opacity: f64,
    /// Share of the length that belongs to filled strokes, in [0, 1].
    pub filled_share: f64,
    /// Mean fill colour of the filled strokes in the RGB unit cube (zero without any).
    pub fill: [f64; 3],
    /// Mean share of the length that is inked (dashes over dash period; 1 for solid strokes).
    pub inked_share: f64,
    /// Mean dash period of the dashed strokes (0 without any), drawing units.
    pub dash_period: f64,
}

impl Attributes {
    /// The attributes of `strokes[indices]`.
    pub fn of_strokes(strokes: &[Stroke], indices: &[usize]) -> Attributes {
        let mut sum = Attributes::default();
        let (mut total, mut filled, mut dashed) = (0.0, 0.0, 0.0);
        for &s in indices {
            let stroke = &strokes[s];
            // A single point still counts, so that an element of dots has attributes.
            let length = stroke.polyline.length().max(1e-9);
            total += length;
            sum.width += length * stroke.width;
            sum.opacity += length * f64::from(stroke.representative_colour()[3]) / 255.0;
            if let Some(fill) = stroke.fill {
                filled += length;
                for (c, &v) in sum.fill.iter_mut().zip(&fill[..3]) {
                    *c += length * f64::from(v) / 255.0;
                }
            }
            sum.inked_share += length * stroke.inked_share();
            if stroke.dash.is_some() {
                dashed += length;
                sum.dash_period += length * stroke.dash_period();
            }
        }
        if total <= 0.0 {
            return Attributes { opacity: 1.0, inked_share: 1.0, ..Attributes::default() };
        }
        Attributes {
            width: sum.width / total,
            opacity: sum.opacity / total,
            filled_share: filled / total,
            fill: if filled > 0.0 { sum.fill.map(|c| c / filled) } else { [0.0; 3] },
            inked_share: sum.inked_share / total,
            dash_period: if dashed > 0.0 { sum.dash_period / dashed } else { 0.0 },
        }
    }

    /// The attribute measure of a pair: the largest difference, each on a unit scale.
    pub fn difference(&self, other: &Attributes) -> f64 {
        let relative = |a: f64, b: f64| {
            let larger = a.abs().max(b.abs());
            if larger > 0.0 { (a - b).abs() / larger } else { 0.0 }
        };
        let fill = if self.filled_share > 0.0 && other.filled_share > 0.0 {
            self.fill.iter().zip(&other.fill).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt()
        } else {
            0.0
        };
        let dash_period = if self.dash_period > 0.0 && other.dash_period > 0.0 {
            relative(self.dash_period, other.dash_period)
        } else {
            0.0
        };
        relative(self.width, other.width)
            .max((self.opacity - other.opacity).abs())
            .max((self.filled_share - other.filled_share).abs())
            .max(fill)
            .max((self.inked_share - other.inked_share).abs())
            .max(dash_period)
    }
}

#[cfg(test)]
mod tests {
    use motif_core::{Point, Polyline};

    use super::*;

    fn stroke(width: f64, alpha: u8, dash: Option<Vec<f64>>) -> Stroke {
        let polyline = Polyline::new(vec![Point::new(0.0, 0.0), Point::new(10.0, 0.0)], false).unwrap();
        Stroke { dash, ..Stroke::new(polyline, width, [0, 0, 0, alpha], None) }
    }

    #[test]
    fn differences_are_on_unit_scales() {
        let strokes = [
            stroke(1.0, 255, None),
            stroke(2.0, 255, None),
            stroke(1.0, 128, None),
            stroke(1.0, 255, Some(vec![3.0, 1.0])),
            stroke(1.0, 255, Some(vec![6.0, 2.0])),
        ];
        let of = |i: usize| Attributes::of_strokes(&strokes, &[i]);
        assert_eq!(of(0).difference(&of(0)), 0.0);
        assert!((of(0).difference(&of(1)) - 0.5).abs() < 1e-12);
        assert!((of(0).difference(&of(2)) - 127.0 / 255.0).abs() < 1e-12);
        // Dashes of 3 in 4: a quarter less ink than solid; the same share at twice the period.
        assert!((of(0).difference(&of(3)) - 0.25).abs() < 1e-12);
        assert!((of(3).difference(&of(4)) - 0.5).abs() < 1e-12);
        let mixed = Attributes::of_strokes(&strokes, &[0, 1]);
        assert!((mixed.width - 1.5).abs() < 1e-12);
    }
}
