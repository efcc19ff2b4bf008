//! SVG in (through `usvg`), SVG out ([`SvgWriter`]) and SVG to pixels (through `resvg`).

use std::fmt::Write as _;
use std::path::Path;

use kurbo::{Affine, BezPath, Point};
use motif_core::RgbaImage;
use resvg::tiny_skia;

use crate::{IoError, Result};

/// A stroke's paint: width in document units (the path's transform applied) and colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrokePaint {
    /// Width in document units.
    pub width: f64,
    /// sRGB colour with the stroke's opacity as alpha.
    pub colour: [u8; 4],
}

/// One path of an SVG document.
#[derive(Debug, Clone, PartialEq)]
pub struct SvgPath {
    /// The element's `id` (empty when it had none).
    pub id: String,
    /// The geometry in document coordinates (all transforms applied).
    pub path: BezPath,
    /// The stroke, when the path is stroked with a plain colour.
    pub stroke: Option<StrokePaint>,
    /// The fill colour, when the path is filled with a plain colour.
    pub fill: Option<[u8; 4]>,
    /// The stroke's dash pattern (lengths of dashes and gaps in document units), when dashed.
    pub dash: Option<Vec<f64>>,
}

/// The paths of an SVG document, in drawing order.
#[derive(Debug, Clone, PartialEq)]
pub struct SvgDocument {
    /// Document width (user units).
    pub width: f64,
    /// Document height (user units).
    pub height: f64,
    /// Every visible path, in drawing order (shapes such as `rect` and `circle` become paths).
    pub paths: Vec<SvgPath>,
}

/// Reads an SVG file; fails if it holds no path.
pub fn read_svg(path: &Path) -> Result<SvgDocument> {
    let text = crate::read_text(path)?;
    parse_svg(&text, path)
}

/// Parses SVG text; `name` is the file (or label) errors refer to. Fails if it holds no path.
pub fn parse_svg(text: &str, name: &Path) -> Result<SvgDocument> {
    let tree = usvg::Tree::from_str(text, &usvg::Options::default())
        .map_err(|error| IoError::format(name, format!("is not a valid SVG document: {error}")))?;
    let mut paths = Vec::new();
    collect_paths(tree.root(), &mut paths);
    if paths.is_empty() {
        return Err(IoError::format(
            name,
            "SVG contains no path (expected at least one <path>, <line>, <polyline>, <rect>...)",
        ));
    }
    let size = tree.size();
    Ok(SvgDocument { width: f64::from(size.width()), height: f64::from(size.height()), paths })
}

fn collect_paths(group: &usvg::Group, out: &mut Vec<SvgPath>) {
    for node in group.children() {
        match node {
            usvg::Node::Group(child) => collect_paths(child, out),
            usvg::Node::Path(path) if path.is_visible() => out.push(convert_path(path)),
            _ => {}
        }
    }
}

fn convert_path(path: &usvg::Path) -> SvgPath {
    let t = path.abs_transform();
    let transform = Affine::new([
        f64::from(t.sx),
        f64::from(t.ky),
        f64::from(t.kx),
        f64::from(t.sy),
        f64::from(t.tx),
        f64::from(t.ty),
    ]);
    let point = |p: tiny_skia::Point| transform * Point::new(f64::from(p.x), f64::from(p.y));
    let mut bez = BezPath::new();
    for segment in path.data().segments() {
        match segment {
            tiny_skia::PathSegment::MoveTo(p) => bez.move_to(point(p)),
            tiny_skia::PathSegment::LineTo(p) => bez.line_to(point(p)),
            tiny_skia::PathSegment::QuadTo(a, b) => bez.quad_to(point(a), point(b)),
            tiny_skia::PathSegment::CubicTo(a, b, c) => bez.curve_to(point(a), point(b), point(c)),
            tiny_skia::PathSegment::Close => bez.close_path(),
        }
    }
    let colour = |paint: &usvg::Paint, opacity: f32| match paint {
        usvg::Paint::Color(c) => Some([c.red, c.green, c.blue, (opacity.clamp(0.0, 1.0) * 255.0).round() as u8]),
        _ => None,
    };
    let stroke = path.stroke().and_then(|stroke| {
        let scale = transform.determinant().abs().sqrt();
        colour(stroke.paint(), stroke.opacity().get())
            .map(|colour| StrokePaint { width: f64::from(stroke.width().get()) * scale, colour })
    });
    let fill = path.fill().and_then(|fill| colour(fill.paint(), fill.opacity().get()));
    let dash = path.stroke().and_then(|stroke| {
        let scale = transform.determinant().abs().sqrt();
        stroke.dasharray().map(|lengths| lengths.iter().map(|&l| f64::from(l) * scale).collect())
    });
    SvgPath { id: path.id().to_string(), path: bez, stroke, fill, dash }
}

/// Rasterizes SVG text with `resvg` at `scale` pixels per user unit, on a transparent background.
pub fn render_svg(text: &str, scale: f64, name: &Path) -> Result<RgbaImage> {
    let tree = usvg::Tree::from_str(text, &usvg::Options::default())
        .map_err(|error| IoError::format(name, format!("is not a valid SVG document: {error}")))?;
    let size = tree.size();
    let width = (f64::from(size.width()) * scale).ceil().max(1.0) as u32;
    let height = (f64::from(size.height()) * scale).ceil().max(1.0) as u32;
    if u64::from(width) * u64::from(height) > crate::raster::MAX_PIXELS {
        return Err(IoError::format(
            name,
            format!(
                "rendering at {width}×{height} exceeds the {side}×{side} pixel limit",
                side = motif_core::limits::MAX_IMAGE_SIDE
            ),
        ));
    }
    let mut pixmap = tiny_skia::Pixmap::new(width, height)
        .ok_or_else(|| IoError::format(name, format!("cannot allocate a {width}×{height} canvas")))?;
    resvg::render(&tree, tiny_skia::Transform::from_scale(scale as f32, scale as f32), &mut pixmap.as_mut());
    let pixels = pixmap
        .pixels()
        .iter()
        .map(|p| {
            let c = p.demultiply();
            [c.red(), c.green(), c.blue(), c.alpha()]
        })
        .collect();
    RgbaImage::from_pixels(width as usize, height as usize, pixels)
        .map_err(|error| IoError::format(name, error.to_string()))
}

/// Builds an SVG document as text: paths, circles, rectangles, text labels and groups.
///
/// Numbers are written with at most 3 decimals so that files are compact and byte-stable.
#[derive(Debug, Clone)]
pub struct SvgWriter {
    body: String,
    width: f64,
    height: f64,
    depth: usize,
}

/// `#rrggbb` for a colour (alpha goes to the matching `-opacity` attribute).
fn hex(colour: [u8; 4]) -> String {
    format!("#{:02x}{:02x}{:02x}", colour[0], colour[1], colour[2])
}

fn number(value: f64) -> String {
    let rounded = (value * 1000.0).round() / 1000.0;
    let rounded = if rounded == 0.0 { 0.0 } else { rounded };
    format!("{rounded}")
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

impl SvgWriter {
    /// A document of `width × height` user units (the viewBox starts at the origin).
    pub fn new(width: f64, height: f64) -> Self {
        Self { body: String::new(), width, height, depth: 1 }
    }

    fn line(&mut self, text: &str) {
        for _ in 0..self.depth {
            self.body.push_str("  ");
        }
        self.body.push_str(text);
        self.body.push('\n');
    }

    fn paint(stroke: Option<StrokePaint>, fill: Option<[u8; 4]>) -> String {
        let mut attributes = String::new();
        match fill {
            Some(colour) => {
                let _ = write!(attributes, " fill=\"{}\"", hex(colour));
                if colour[3] != 255 {
                    let _ = write!(attributes, " fill-opacity=\"{}\"", number(f64::from(colour[3]) / 255.0));
                }
            }
            None => attributes.push_str(" fill=\"none\""),
        }
        if let Some(stroke) = stroke {
            let _ = write!(
                attributes,
                " stroke=\"{}\" stroke-width=\"{}\" stroke-linecap=\"round\" stroke-linejoin=\"round\"",
                hex(stroke.colour),
                number(stroke.width)
            );
            if stroke.colour[3] != 255 {
                let _ = write!(attributes, " stroke-opacity=\"{}\"", number(f64::from(stroke.colour[3]) / 255.0));
            }
        }
        attributes
    }

    /// Adds a path with optional stroke and fill.
    pub fn path(&mut self, path: &BezPath, stroke: Option<StrokePaint>, fill: Option<[u8; 4]>) -> &mut Self {
        self.dashed_path(path, stroke, fill, &[])
    }

    /// Adds a path with optional stroke, fill and dash pattern (none when `dash` is empty).
    pub fn dashed_path(
        &mut self,
        path: &BezPath,
        stroke: Option<StrokePaint>,
        fill: Option<[u8; 4]>,
        dash: &[f64],
    ) -> &mut Self {
        let mut data = String::new();
        for element in path.elements() {
            let p = |point: &Point| format!("{} {}", number(point.x), number(point.y));
            match element {
                kurbo::PathEl::MoveTo(a) => data.push_str(&format!("M{} ", p(a))),
                kurbo::PathEl::LineTo(a) => data.push_str(&format!("L{} ", p(a))),
                kurbo::PathEl::QuadTo(a, b) => data.push_str(&format!("Q{} {} ", p(a), p(b))),
                kurbo::PathEl::CurveTo(a, b, c) => data.push_str(&format!("C{} {} {} ", p(a), p(b), p(c))),
                kurbo::PathEl::ClosePath => data.push_str("Z "),
            }
        }
        let mut paint = Self::paint(stroke, fill);
        if stroke.is_some() && !dash.is_empty() {
            let lengths: Vec<String> = dash.iter().map(|&l| number(l)).collect();
            let _ = write!(paint, " stroke-dasharray=\"{}\"", lengths.join(" "));
        }
        let line = format!("<path d=\"{}\"{}/>", data.trim_end(), paint);
        self.line(&line);
        self
    }

    /// Adds a polyline through `points` (closed with `Z` when `closed`).
    pub fn polyline(
        &mut self,
        points: &[Point],
        closed: bool,
        stroke: Option<StrokePaint>,
        fill: Option<[u8; 4]>,
    ) -> &mut Self {
        self.dashed_polyline(points, closed, stroke, fill, &[])
    }

    /// Adds a polyline with a dash pattern (none when `dash` is empty).
    pub fn dashed_polyline(
        &mut self,
        points: &[Point],
        closed: bool,
        stroke: Option<StrokePaint>,
        fill: Option<[u8; 4]>,
        dash: &[f64],
    ) -> &mut Self {
        let mut path = BezPath::new();
        if let Some((first, rest)) = points.split_first() {
            path.move_to(*first);
            for &point in rest {
                path.line_to(point);
            }
            if closed {
                path.close_path();
            }
        }
        self.dashed_path(&path, stroke, fill, dash)
    }

    /// Adds a circle.
    pub fn circle(
        &mut self,
        centre: Point,
        radius: f64,
        stroke: Option<StrokePaint>,
        fill: Option<[u8; 4]>,
    ) -> &mut Self {
        let line = format!(
            "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"{}/>",
            number(centre.x),
            number(centre.y),
            number(radius),
            Self::paint(stroke, fill)
        );
        self.line(&line);
        self
    }

    /// Adds an axis-aligned rectangle.
    pub fn rect(
        &mut self,
        x: f64,
        y: f64,
        width: f64,
        height: f64,
        stroke: Option<StrokePaint>,
        fill: Option<[u8; 4]>,
    ) -> &mut Self {
        let line = format!(
            "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"{}/>",
            number(x),
            number(y),
            number(width),
            number(height),
            Self::paint(stroke, fill)
        );
        self.line(&line);
        self
    }

    /// Adds a text label (sans-serif, `size` user units, filled with `colour`).
    pub fn text(&mut self, position: Point, size: f64, colour: [u8; 4], text: &str) -> &mut Self {
        let line = format!(
            "<text x=\"{}\" y=\"{}\" font-family=\"sans-serif\" font-size=\"{}\" fill=\"{}\">{}</text>",
            number(position.x),
            number(position.y),
            number(size),
            hex(colour),
            escape(text)
        );
        self.line(&line);
        self
    }

    /// Opens a group with an `id` (close it with [`end_group`](Self::end_group)).
    pub fn begin_group(&mut self, id: &str) -> &mut Self {
        let line = format!("<g id=\"{}\">", escape(id));
        self.line(&line);
        self.depth += 1;
        self
    }

    /// Closes the innermost group.
    pub fn end_group(&mut self) -> &mut Self {
        self.depth = self.depth.saturating_sub(1).max(1);
        self.line("</g>");
        self
    }

    /// The finished document.
    pub fn finish(&self) -> String {
        let (w, h) = (number(self.width), number(self.height));
        format!(
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n{}</svg>\n",
            self.body
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_svg_reads_back_with_transforms_strokes_and_fills() {
        let mut writer = SvgWriter::new(100.0, 50.0);
        let mut path = BezPath::new();
        path.move_to((10.0, 10.0));
        path.curve_to((20.0, 0.0), (30.0, 20.0), (40.0, 10.0));
        let stroke = StrokePaint { width: 2.5, colour: [255, 0, 0, 255] };
        writer.path(&path, Some(stroke), None);
        writer.begin_group("g").circle(Point::new(50.0, 25.0), 5.0, None, Some([0, 0, 255, 128])).end_group();
        let text = writer.finish();
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("drawing.svg");
        crate::write_text(&file, &text).unwrap();
        let document = read_svg(&file).unwrap();
        assert_eq!((document.width, document.height), (100.0, 50.0));
        assert_eq!(document.paths.len(), 2);
        assert_eq!(document.paths[0].stroke, Some(stroke));
        assert_eq!(document.paths[0].path.elements().len(), 2);
        let circle = kurbo::Shape::bounding_box(&document.paths[1].path);
        assert!((circle.center().x - 50.0).abs() < 1e-3 && (circle.width() - 10.0).abs() < 1e-3);
        assert_eq!(document.paths[1].fill, Some([0, 0, 255, 128]));
    }

    #[test]
    fn transforms_are_applied() {
        let text = r#"<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10">
            <g transform="translate(5,1) scale(2)"><path d="M0 0 L1 0" stroke="black" stroke-width="1"/></g></svg>"#;
        let document = parse_svg(text, Path::new("inline.svg")).unwrap();
        let elements = document.paths[0].path.elements();
        assert_eq!(elements[0], kurbo::PathEl::MoveTo(Point::new(5.0, 1.0)));
        assert_eq!(elements[1], kurbo::PathEl::LineTo(Point::new(7.0, 1.0)));
        assert_eq!(document.paths[0].stroke.unwrap().width, 2.0);
    }

    #[test]
    fn svg_without_paths_and_non_svg_give_errors_naming_the_file() {
        let empty = r#"<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10"></svg>"#;
        let message = parse_svg(empty, Path::new("empty.svg")).unwrap_err().to_string();
        assert!(message.contains("empty.svg") && message.contains("no path"), "{message}");
        let message = parse_svg("hello", Path::new("text.svg")).unwrap_err().to_string();
        assert!(message.contains("text.svg"), "{message}");
        assert!(read_svg(Path::new("/nonexistent/x.svg")).unwrap_err().to_string().contains("x.svg"));
    }

    #[test]
    fn rendering_draws_where_the_shape_is() {
        let mut writer = SvgWriter::new(20.0, 10.0);
        writer.rect(0.0, 0.0, 10.0, 10.0, None, Some([0, 255, 0, 255]));
        let image = render_svg(&writer.finish(), 2.0, Path::new("mem.svg")).unwrap();
        assert_eq!((image.width(), image.height()), (40, 20));
        assert_eq!(image.get(5, 5), [0, 255, 0, 255]);
        assert_eq!(image.get(35, 5)[3], 0);
    }
}
