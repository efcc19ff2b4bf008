//! A tile's segment map: the map's features drawn with `tiny-skia`, anti-aliased, each class in
//! its colour, over a frame of `margin` pixels around the tile.

use motif_core::RgbaImage;
use tiny_skia::{Color, FillRule, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Stroke, Transform};

use crate::class::MapClass;
use crate::map::{Geometry, MapData};
use crate::mercator::{TileId, UnitPoint};

/// Subdivisions of a pixel that the geometry is snapped to (`tiny-skia`'s fixed point has six
/// fractional bits).
const SNAP: f64 = 64.0;

/// Where a tile's pixels lie: the tile, its side in pixels and the frame around it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TileFrame {
    /// The tile.
    pub tile: TileId,
    /// A tile's side in pixels.
    pub size: usize,
    /// Tiles a side drawn as one square from `tile` east and south (1: the tile alone).
    pub span: usize,
    /// Pixels drawn around it on every side.
    pub margin: usize,
}

impl TileFrame {
    /// Side of the drawn square, margin included.
    pub fn side(&self) -> usize {
        self.span * self.size + 2 * self.margin
    }

    /// Pixels per unit of the square at this zoom.
    pub fn scale(&self) -> f64 {
        self.tile.side() as f64 * self.size as f64
    }

    /// The drawn square's top-left pixel in the whole zoom level's pixels (negative at the
    /// world's west or north edge).
    pub fn global_origin(&self) -> (i64, i64) {
        let (x, y, size, margin) =
            (i64::from(self.tile.x), i64::from(self.tile.y), self.size as i64, self.margin as i64);
        (x * size - margin, y * size - margin)
    }

    /// A unit-square point in the drawn square's pixels: its position in the zoom level's pixels
    /// snapped to 1/64 pixel, less the square's origin. Both steps are exact, so two squares see
    /// the same point at positions that differ by whole pixels exactly (a tile and the block
    /// around it rasterize alike).
    fn pixel(&self, [x, y]: UnitPoint) -> (f32, f32) {
        let scale = self.scale() * SNAP;
        let (ox, oy) = self.global_origin();
        let local = |unit: f64, origin: i64| ((unit * scale).round() / SNAP - origin as f64) as f32;
        (local(x, ox), local(y, oy))
    }

    /// The drawn square in the unit square, `[x0, y0, x1, y1]`.
    fn unit_bounds(&self) -> [f64; 4] {
        let [x, y] = self.tile.origin();
        let (pad, span) = (self.margin as f64 / self.scale(), (self.span * self.size) as f64 / self.scale());
        [x - pad, y - pad, x + span + pad, y + span + pad]
    }
}

fn paint_of(class: MapClass, anti_alias: bool) -> Paint<'static> {
    let [r, g, b] = class.colour();
    let mut paint = Paint::default();
    paint.set_color_rgba8(r, g, b, 255);
    paint.anti_alias = anti_alias;
    paint
}

/// The segment map of `frame`: land, then every feature in drawing order, lines at least
/// `min_line_width` pixels wide so small roads stay visible at low zooms. Anti-aliased for the
/// plain map; aliased (every pixel exactly one class's colour) as the guide of the stylized one,
/// whose band blends the classes itself: a blend of two colours on an anti-aliased edge can lie
/// nearest a third class's colour and would take that class's texture.
pub fn segment_map(map: &MapData, frame: &TileFrame, min_line_width: f32, anti_alias: bool) -> RgbaImage {
    let side = frame.side();
    let Some(mut pixmap) = Pixmap::new(side as u32, side as u32) else {
        return RgbaImage::new(side, side);
    };
    let [r, g, b] = MapClass::Land.colour();
    pixmap.fill(Color::from_rgba8(r, g, b, 255));
    for feature in map.features_in(frame.unit_bounds()) {
        let paint = paint_of(feature.class, anti_alias);
        match &feature.geometry {
            Geometry::Area(rings) => {
                let mut path = PathBuilder::new();
                for ring in rings {
                    trace(&mut path, frame, ring);
                    path.close();
                }
                if let Some(path) = path.finish() {
                    pixmap.fill_path(&path, &paint, FillRule::EvenOdd, Transform::identity(), None);
                }
            }
            Geometry::Line { points, width } => {
                let mut path = PathBuilder::new();
                trace(&mut path, frame, points);
                let width = ((width * frame.scale()) as f32).max(min_line_width);
                let stroke =
                    Stroke { width, line_cap: LineCap::Round, line_join: LineJoin::Round, ..Stroke::default() };
                if let Some(path) = path.finish() {
                    pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
                }
            }
        }
    }
    // Every pixel is opaque (the background covers all), so premultiplied equals straight.
    let pixels = pixmap.pixels().iter().map(|p| [p.red(), p.green(), p.blue(), 255]).collect();
    RgbaImage::from_pixels(side, side, pixels).unwrap_or_else(|_| RgbaImage::new(side, side))
}

fn trace(path: &mut PathBuilder, frame: &TileFrame, points: &[UnitPoint]) {
    for (i, &point) in points.iter().enumerate() {
        let (x, y) = frame.pixel(point);
        if i == 0 { path.move_to(x, y) } else { path.line_to(x, y) }
    }
}

/// Pixels the stylized layer's guide is drawn beyond its frame on every side, then cut off:
/// `tiny-skia` clips and strokes lines a little differently near the drawing's edge, and with a
/// margin no wider than a band pixel's reach those differences would reach the tile's pixels
/// (with 4 the seam figure of Helsinki's 4 × 4 block rose from 0.927 to 0.933; with 5 its
/// guides are drawn over the 12-pixel square of the margin before it shrank to the reach, and
/// the 133 tiles of zoom 14–17 are those of that margin, to the byte).
pub const GUIDE_CLEARANCE: usize = 5;

/// The guide of the stylized layer: the aliased segment map of `frame`, drawn
/// [`GUIDE_CLEARANCE`] pixels wider on every side and cut back to the frame.
pub fn guide_map(map: &MapData, frame: &TileFrame, min_line_width: f32) -> RgbaImage {
    let wider = TileFrame { margin: frame.margin + GUIDE_CLEARANCE, ..*frame };
    let drawn = segment_map(map, &wider, min_line_width, false);
    let side = frame.side();
    RgbaImage::from_fn(side, side, |x, y| drawn.get(x + GUIDE_CLEARANCE, y + GUIDE_CLEARANCE))
}

/// The tiles' own pixels of a drawn square (the margin cut off).
pub fn crop_margin(image: &RgbaImage, frame: &TileFrame) -> RgbaImage {
    let (m, side) = (frame.margin, frame.span * frame.size);
    RgbaImage::from_fn(side, side, |x, y| image.get(x + m, y + m))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::class::Shape;
    use crate::map::MapBuilder;

    fn frame(z: u8, x: u32, y: u32, margin: usize) -> TileFrame {
        TileFrame { tile: TileId::new(z, x, y).unwrap(), size: 64, span: 1, margin }
    }

    #[test]
    fn areas_and_lines_land_where_the_projection_puts_them() {
        let mut builder = MapBuilder::new();
        // A building covering the left half of tile 1/0/0, a road along its bottom edge.
        builder.add(
            MapClass::Building,
            Shape::Area,
            vec![vec![[0.0, 0.0], [0.25, 0.0], [0.25, 0.5], [0.0, 0.5], [0.0, 0.0]]],
        );
        let map = builder.build();
        let image = segment_map(&map, &frame(1, 0, 0, 0), 1.0, true);
        let building = MapClass::Building.colour();
        let land = MapClass::Land.colour();
        assert_eq!(&image.get(10, 10)[..3], &building);
        assert_eq!(&image.get(40, 10)[..3], &land);
        // The edge at x = 32 is anti-aliased into a blend only where it is not on a pixel border.
        assert_eq!(&image.get(31, 20)[..3], &building);
        assert_eq!(&image.get(32, 20)[..3], &land);
    }

    #[test]
    fn neighbouring_tiles_agree_on_their_shared_margin() {
        let mut builder = MapBuilder::new();
        builder.add(MapClass::MajorRoad, Shape::Line(2.0e6), vec![vec![[0.1, 0.1], [0.9, 0.37]]]);
        builder.add(MapClass::Water, Shape::Area, vec![vec![[0.2, 0.2], [0.7, 0.3], [0.4, 0.45], [0.2, 0.2]]]);
        let map = builder.build();
        let (left, right) = (frame(2, 0, 1, 8), frame(2, 1, 1, 8));
        let (a, b) = (segment_map(&map, &left, 1.0, true), segment_map(&map, &right, 1.0, true));
        // Pixel column 64 + 8 of the left square is column 8 of the right one (the tile border);
        // the drawn squares overlap by 16 columns.
        let mut differences = 0;
        for y in 0..a.height() {
            for dx in 0..16 {
                let (pa, pb) = (a.get(64 + dx, y), b.get(dx, y));
                differences +=
                    pa.iter().zip(pb).map(|(p, q)| i32::from(*p).abs_diff(i32::from(q))).max().unwrap_or(0).min(1);
            }
        }
        assert!(differences <= 2, "{differences} pixels differ");
    }
}
