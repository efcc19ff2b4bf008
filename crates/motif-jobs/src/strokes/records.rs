//! Strokes as JSON records, the form the page exchanges with its module: `{points: [[x, y], …],
//! closed, width, colour: [r, g, b, a], fill: [r, g, b, a] | null, dash: [lengths] | null}`.

use motif_core::{Point, Polyline};
use motif_strokes::Stroke;
use serde::{Deserialize, Serialize};

use super::ReferenceProblem;
use crate::JobError;

/// One stroke as a JSON record. Read leniently, as drawings sampled in a browser come: a record
/// without two distinct points is skipped, colour channels are clamped to 0–255, and a dash
/// pattern without a positive length is solid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StrokeRecord {
    /// Vertices in drawing units.
    pub points: Vec<[f64; 2]>,
    /// Whether the last vertex joins the first.
    #[serde(default)]
    pub closed: bool,
    /// Stroke width (drawing units, finite and ≥ 0; default 1).
    #[serde(default = "unit_width")]
    pub width: f64,
    /// Stroke colour, sRGB with straight alpha (default opaque black).
    #[serde(default = "black")]
    pub colour: [f64; 4],
    /// Fill colour, for a filled stroke.
    #[serde(default)]
    pub fill: Option<[f64; 4]>,
    /// Dash and gap lengths, for a dashed stroke.
    #[serde(default)]
    pub dash: Option<Vec<f64>>,
}

fn unit_width() -> f64 {
    1.0
}

fn black() -> [f64; 4] {
    [0.0, 0.0, 0.0, 255.0]
}

fn channels(colour: [f64; 4]) -> [u8; 4] {
    colour.map(|channel| if channel.is_nan() { 0 } else { channel.clamp(0.0, 255.0) as u8 })
}

impl StrokeRecord {
    /// The record of `stroke`.
    pub fn of(stroke: &Stroke) -> Self {
        StrokeRecord {
            points: stroke.polyline.points().iter().map(|p| [p.x, p.y]).collect(),
            closed: stroke.polyline.is_closed(),
            width: stroke.width,
            colour: stroke.colour.map(f64::from),
            fill: stroke.fill.map(|fill| fill.map(f64::from)),
            dash: stroke.dash.clone(),
        }
    }

    /// The stroke, or `None` when the record's points do not make a polyline; an error names the
    /// record (1-based `index`) when its width is not a finite number ≥ 0.
    fn stroke(&self, index: usize) -> Result<Option<Stroke>, ReferenceProblem> {
        if !(self.width.is_finite() && self.width >= 0.0) {
            return Err(ReferenceProblem::Width { index, width: self.width });
        }
        let points = self.points.iter().map(|p| Point::new(p[0], p[1])).collect();
        let Ok(polyline) = Polyline::new(points, self.closed) else { return Ok(None) };
        let dash = self
            .dash
            .clone()
            .filter(|lengths| lengths.iter().all(|l| l.is_finite() && *l >= 0.0) && lengths.iter().any(|&l| l > 0.0));
        let fill = self.fill.map(channels);
        Ok(Some(Stroke { dash, ..Stroke::new(polyline, self.width, channels(self.colour), fill) }))
    }
}

/// `strokes` as a JSON list of [`StrokeRecord`]s.
pub fn strokes_to_json(strokes: &[Stroke]) -> serde_json::Value {
    serde_json::Value::Array(
        strokes.iter().map(|stroke| serde_json::to_value(StrokeRecord::of(stroke)).unwrap_or_default()).collect(),
    )
}

/// The visible strokes of a JSON list of [`StrokeRecord`]s; refused when the text is not such a
/// list, a width is invalid, or nothing visible is left.
pub fn strokes_from_json(text: &str) -> Result<Vec<Stroke>, JobError> {
    let records: Vec<StrokeRecord> =
        serde_json::from_str(text).map_err(|error| ReferenceProblem::Json(error.to_string()))?;
    let mut strokes = Vec::new();
    for (index, record) in records.iter().enumerate() {
        strokes.extend(record.stroke(index + 1)?.filter(Stroke::is_visible));
    }
    if strokes.is_empty() {
        return Err(ReferenceProblem::Empty.into());
    }
    Ok(strokes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strokes_survive_the_round_trip_through_json() {
        let line = Polyline::new(vec![Point::new(0.0, 0.0), Point::new(3.0, 1.5)], false).unwrap();
        let square = Polyline::new(
            vec![Point::new(5.0, 5.0), Point::new(6.0, 5.0), Point::new(6.0, 6.0), Point::new(5.0, 6.0)],
            true,
        )
        .unwrap();
        let strokes = vec![
            Stroke { dash: Some(vec![1.0, 0.5]), ..Stroke::new(line, 0.75, [10, 20, 30, 200], None) },
            Stroke::new(square, 0.0, [0, 0, 0, 255], Some([255, 0, 0, 255])),
        ];
        let text = strokes_to_json(&strokes).to_string();
        assert_eq!(strokes_from_json(&text).unwrap(), strokes);
    }

    #[test]
    fn records_are_read_leniently_but_bad_widths_and_empty_lists_are_refused() {
        let text = r#"[{"points": [[0, 0]]}, {"points": [[0, 0], [2, 0]], "colour": [300, -4, 12.7, 255],
            "dash": [0, 0]}]"#;
        let strokes = strokes_from_json(text).unwrap();
        assert_eq!(strokes.len(), 1, "a one-point record is skipped");
        assert_eq!((strokes[0].colour, strokes[0].width, &strokes[0].dash), ([255, 0, 12, 255], 1.0, &None));
        let error = strokes_from_json(r#"[{"points": [[0, 0], [1, 1]], "width": -1}]"#).unwrap_err();
        assert!(error.to_string().contains("stroke 1"), "{error}");
        for text in ["[]", "{}", "[{\"points\": [[1, 1], [1, 1]]}]"] {
            let error = strokes_from_json(text).unwrap_err();
            assert_eq!(error.kind(), crate::ErrorKind::Input, "{text}: {error}");
        }
    }
}
