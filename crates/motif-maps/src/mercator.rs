//! Web Mercator (EPSG:3857) as slippy maps use it: the world is the unit square, x east from
//! 180° W, y south from about 85.05° N, and tile `(z, x, y)` covers
//! `[x / 2^z, (x + 1) / 2^z) × [y / 2^z, (y + 1) / 2^z)` of it.

use std::f64::consts::PI;

use motif_core::InvalidParameter;
use motif_core::math::{atan, cos, ln, sin, sinh};
use serde::{Deserialize, Serialize};

/// The deepest zoom level a tile may have (tile indices then still fit 32 bits).
pub const MAX_ZOOM: u8 = 24;

/// Mean circumference of the Earth at the equator in metres (WGS 84 major axis × 2π), the
/// length of the unit square's side.
pub const EARTH_CIRCUMFERENCE: f64 = 40_075_016.686;

/// Latitude of Web Mercator's square's edges in degrees.
pub const MAX_LATITUDE: f64 = 85.051_128_779_806_59;

/// A point in the unit square of Web Mercator.
pub type UnitPoint = [f64; 2];

/// Longitude and latitude in degrees to the unit square (latitude clamped to Web Mercator's).
pub fn project(lon: f64, lat: f64) -> UnitPoint {
    let lat = lat.clamp(-MAX_LATITUDE, MAX_LATITUDE) * PI / 180.0;
    let s = sin(lat);
    let y = 0.5 - ln((1.0 + s) / (1.0 - s)) / (4.0 * PI);
    [(lon + 180.0) / 360.0, y]
}

/// The unit square back to longitude and latitude in degrees.
pub fn unproject([x, y]: UnitPoint) -> (f64, f64) {
    let lat = atan(sinh(PI * (1.0 - 2.0 * y))) * 180.0 / PI;
    (x * 360.0 - 180.0, lat)
}

/// Metres on the ground per unit of the square at unit height `y` (the scale grows with the
/// latitude as 1 / cos).
pub fn metres_per_unit(y: f64) -> f64 {
    let (_, lat) = unproject([0.5, y]);
    EARTH_CIRCUMFERENCE * cos(lat * PI / 180.0)
}

/// One slippy-map tile: zoom level `z`, column `x` from the west, row `y` from the north.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct TileId {
    /// Zoom level, 0..=[`MAX_ZOOM`].
    pub z: u8,
    /// Column, 0..2^z.
    pub x: u32,
    /// Row, 0..2^z.
    pub y: u32,
}

impl TileId {
    /// The tile, checked: `z` at most [`MAX_ZOOM`], `x` and `y` below 2^z.
    pub fn new(z: u8, x: u32, y: u32) -> Result<Self, InvalidParameter> {
        if z > MAX_ZOOM {
            return Err(InvalidParameter::new("zoom", z, format!("must be between 0 and {MAX_ZOOM}")));
        }
        let side = 1u64 << z;
        if u64::from(x) >= side || u64::from(y) >= side {
            return Err(InvalidParameter::new(
                "tile",
                format!("{z}/{x}/{y}"),
                format!("x and y must be below 2^{z} = {side} at zoom {z}"),
            ));
        }
        Ok(Self { z, x, y })
    }

    /// Tiles across the world at this zoom.
    pub fn side(self) -> u64 {
        1 << self.z
    }

    /// The tile's north-west corner in the unit square.
    pub fn origin(self) -> UnitPoint {
        let side = self.side() as f64;
        [f64::from(self.x) / side, f64::from(self.y) / side]
    }
}

/// The tiles of zoom `z` that meet the unit-square rectangle `[x0, x1] × [y0, y1]`, row by row.
pub fn tiles_covering(bounds: [f64; 4], z: u8) -> Vec<TileId> {
    let side = (1u64 << z) as f64;
    let index = |v: f64| (v * side).floor().clamp(0.0, side - 1.0) as u32;
    let [x0, y0, x1, y1] = bounds;
    let (column0, column1, row0, row1) = (index(x0), index(x1), index(y0), index(y1));
    (row0..=row1).flat_map(|y| (column0..=column1).map(move |x| TileId { z, x, y })).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projection_round_trips_and_meets_known_points() {
        assert_eq!(project(0.0, 0.0), [0.5, 0.5]);
        let [x, y] = project(-180.0, MAX_LATITUDE);
        assert!(x.abs() < 1e-12 && y.abs() < 1e-9, "{x} {y}");
        for (lon, lat) in [(24.94, 60.17), (-74.0, 40.7), (151.2, -33.9)] {
            let (back_lon, back_lat) = unproject(project(lon, lat));
            assert!((back_lon - lon).abs() < 1e-9 && (back_lat - lat).abs() < 1e-9);
        }
        // Helsinki's railway station: y = (1 − ln(tan φ + sec φ) / π) / 2 · 2^16 = 18969.4 by hand.
        let [x, y] = project(24.9414, 60.1710);
        assert_eq!(((x * 65536.0) as u32, (y * 65536.0) as u32), (37308, 18969));
    }

    #[test]
    fn scale_halves_at_sixty_degrees() {
        let ratio = metres_per_unit(project(0.0, 60.0)[1]) / EARTH_CIRCUMFERENCE;
        assert!((ratio - 0.5).abs() < 1e-9);
    }

    #[test]
    fn tiles_are_checked_and_cover_a_rectangle() {
        assert!(TileId::new(2, 3, 3).is_ok());
        assert!(TileId::new(2, 4, 0).is_err());
        assert!(TileId::new(MAX_ZOOM + 1, 0, 0).is_err());
        let tiles = tiles_covering([0.30, 0.49, 0.70, 0.51], 2);
        assert_eq!(
            tiles,
            vec![
                TileId { z: 2, x: 1, y: 1 },
                TileId { z: 2, x: 2, y: 1 },
                TileId { z: 2, x: 1, y: 2 },
                TileId { z: 2, x: 2, y: 2 }
            ]
        );
        assert_eq!(tiles_covering([0.0, 0.0, 1.0, 1.0], 0).len(), 1);
    }
}
