//! Strokes as SVG, the one home of both directions for every front end that reads files (the
//! `svg` feature): the reference strokes of a parsed drawing, and a pattern as SVG text.

use motif_io::{StrokePaint, SvgDocument, SvgWriter};
use motif_strokes::Stroke;

use super::ReferenceProblem;
use crate::JobError;

/// Every visible path of `document` as reference strokes, in document order: each subpath
/// flattened within `tolerance` (document units, finite and > 0) carries its path's stroke width
/// and colour, or, for a path that is only filled, width 0 and the fill colour. Refused when a
/// path cannot be read (named by its `id`) or when nothing visible is left.
pub fn reference_from_svg(document: &SvgDocument, tolerance: f64) -> Result<Vec<Stroke>, JobError> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(motif_core::InvalidParameter::new("tolerance", tolerance, "must be a finite number > 0").into());
    }
    let mut strokes = Vec::new();
    for path in &document.paths {
        let (width, colour) = path.stroke.map_or((0.0, path.fill.unwrap_or([0, 0, 0, 255])), |s| (s.width, s.colour));
        let pieces = Stroke::from_path(&path.path, tolerance, width, colour, path.fill, path.dash.as_deref())
            .map_err(|source| ReferenceProblem::Path { id: path.id.clone(), source })?;
        strokes.extend(pieces.into_iter().filter(Stroke::is_visible));
    }
    if strokes.is_empty() {
        return Err(ReferenceProblem::Empty.into());
    }
    Ok(strokes)
}

/// Draws `stroke` as it was read: its polyline with its width, colour, fill and dash pattern.
pub fn draw_stroke(writer: &mut SvgWriter, stroke: &Stroke) {
    let line = (stroke.width > 0.0).then_some(StrokePaint { width: stroke.width, colour: stroke.colour });
    writer.dashed_polyline(
        stroke.polyline.points(),
        stroke.polyline.is_closed(),
        line,
        stroke.fill,
        stroke.dash.as_deref().unwrap_or_default(),
    );
}

/// `strokes` as an SVG document of `width` × `height` user units, in one group named `group`
/// when given.
pub fn strokes_svg(strokes: &[Stroke], width: f64, height: f64, group: Option<&str>) -> String {
    let mut writer = SvgWriter::new(width, height);
    if let Some(group) = group {
        writer.begin_group(group);
    }
    for stroke in strokes {
        draw_stroke(&mut writer, stroke);
    }
    if group.is_some() {
        writer.end_group();
    }
    writer.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    const DRAWING: &str = r##"<svg xmlns="http://www.w3.org/2000/svg" width="40" height="20">
        <path id="a" d="M 2 2 L 12 2" stroke="#102030" stroke-width="1.5" fill="none"/>
        <path id="b" d="M 20 5 L 30 5 L 30 15 Z" fill="#ff0000"/>
        <path id="c" d="M 5 5 L 5 5" stroke="#000" stroke-width="1" fill="none"/>
    </svg>"##;

    fn document(text: &str) -> SvgDocument {
        motif_io::parse_svg(text, std::path::Path::new("drawing.svg")).unwrap()
    }

    #[test]
    fn a_drawing_reads_as_its_visible_paths_and_writes_back_the_same_strokes() {
        let strokes = reference_from_svg(&document(DRAWING), 0.1).unwrap();
        assert_eq!(strokes.len(), 2, "the point-sized path is not a stroke");
        assert_eq!((strokes[0].width, strokes[0].colour), (1.5, [0x10, 0x20, 0x30, 255]));
        assert_eq!((strokes[1].width, strokes[1].fill), (0.0, Some([255, 0, 0, 255])));
        let again = reference_from_svg(&document(&strokes_svg(&strokes, 40.0, 20.0, Some("strokes"))), 0.1).unwrap();
        assert_eq!(again.len(), strokes.len());
        for (a, b) in again.iter().zip(&strokes) {
            assert_eq!(
                (a.width, a.colour, a.fill, a.polyline.is_closed()),
                (b.width, b.colour, b.fill, b.polyline.is_closed())
            );
            assert_eq!(a.polyline.points().len(), b.polyline.points().len());
        }
    }

    #[test]
    fn bad_tolerances_and_empty_drawings_are_refused_by_name() {
        let error = reference_from_svg(&document(DRAWING), 0.0).unwrap_err();
        assert!(error.to_string().contains("tolerance"), "{error}");
        let empty = r##"<svg xmlns="http://www.w3.org/2000/svg" width="4" height="4">
            <path d="M 1 1 L 1 1" stroke="#000" fill="none"/></svg>"##;
        let error = reference_from_svg(&document(empty), 0.1).unwrap_err();
        assert!(error.to_string().contains("no strokes"), "{error}");
        assert_eq!(error.kind(), crate::ErrorKind::Input);
    }
}
