//! Stylized navigation maps, the application of Texler et al.'s "Example-Based Stylization of
//! Navigation Maps on Mobile Devices": OpenStreetMap features rasterized per slippy-map tile into
//! segment maps, each stylized by the band mode of [`motif_stylize`] (§3.7) from textures
//! pre-synthesized once per class.
//!
//! Modules:
//! - `class`: the segment classes (land, water, grass, forest, buildings, rail, minor and major
//!   roads) and [`classify`], which OpenStreetMap tags make each.
//! - `mercator`: Web Mercator's unit square, [`TileId`] and the tiles covering a rectangle.
//! - `rings`: multipolygon rings joined from their ways, and the land that coastlines cut from
//!   the map's rectangle.
//! - `map`: [`MapBuilder`] and [`MapData`], the features in drawing order with an `rstar` index.
//! - `raster`: a tile's segment map drawn with `tiny-skia`, anti-aliased, with a margin; the
//!   stylized layer's aliased guide ([`guide_map`]), drawn a little beyond it.
//! - `legend`: a [`Legend`] (a texture or a colour per class) and its atlas, the style exemplar.
//! - `seams`: [`seam_error`], how visible the borders of tiles rendered apart are.
//! - `tiles`: [`TileSet`]: the presynthesis (§3.7, once) and any tile rendered on demand, its
//!   textures laid in the zoom level's coordinates so neighbouring tiles continue each other; a
//!   pyramid of textures, each level twice the side and guided by the one before (§5.3's zoom,
//!   [`Params::texture_levels`]), so that zooming in keeps the layout.
//! - `zoom`: [`zoom_error`], how far a tile's four tiles at the next zoom stray from it, seen
//!   from as far ([`halved`]).
//!
//! The crate does no I/O (readers of `.osm.pbf` files live in `motif-io`) and builds for
//! `wasm32`.
//!
//! ```
//! use motif_core::NoProgress;
//! use motif_maps::{Layer, Legend, MapBuilder, MapClass, Params, Shape, TileId, TileSet, project};
//!
//! // A park and a road across it, near Helsinki's railway station.
//! let mut map = MapBuilder::new();
//! let corner = |dx: f64, dy: f64| project(24.940 + dx, 60.172 - dy);
//! let park = vec![corner(0.0, 0.0), corner(0.004, 0.0), corner(0.004, 0.002), corner(0.0, 0.002), corner(0.0, 0.0)];
//! map.add(MapClass::Forest, Shape::Area, vec![park]);
//! map.add(MapClass::MajorRoad, Shape::Line(14.0), vec![vec![corner(-0.001, 0.001), corner(0.005, 0.001)]]);
//! let params = Params::default().with_tile_size(64).with_texture_size(32);
//! let tiles = TileSet::new(map.build(), &Legend::plain(), &params, &mut NoProgress).unwrap();
//! let [x, y] = project(24.942, 60.171);
//! let tile = TileId::new(16, (x * 65536.0) as u32, (y * 65536.0) as u32).unwrap();
//! let image = tiles.render(tile, Layer::Stylized).unwrap();
//! assert_eq!((image.width(), image.height()), (64, 64));
//! ```

mod class;
mod error;
mod legend;
mod map;
mod mercator;
mod params;
mod raster;
mod rings;
mod seams;
mod tiles;
mod zoom;

pub use class::{MapClass, Shape, classify};
pub use error::Error;
pub use legend::{Fill, Legend};
pub use map::{Feature, Geometry, MapBuilder, MapData};
pub use mercator::{
    EARTH_CIRCUMFERENCE, MAX_LATITUDE, MAX_ZOOM, TileId, UnitPoint, metres_per_unit, project, tiles_covering, unproject,
};
pub use params::Params;
pub use raster::{GUIDE_CLEARANCE, TileFrame, crop_margin, guide_map, segment_map};
pub use seams::seam_error;
pub use tiles::{Layer, TileSet, TileSetReport};
pub use zoom::{halved, zoom_error};
