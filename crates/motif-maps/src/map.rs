//! The map: classified features in the unit square of Web Mercator, indexed for tiles.

use rstar::RTree;
use rstar::primitives::{GeomWithData, Rectangle};

use crate::class::{MapClass, Shape};
use crate::mercator::{UnitPoint, metres_per_unit};
use crate::rings::{join_chains, join_rings, land_polygons};

/// What a feature covers.
#[derive(Debug, Clone, PartialEq)]
pub enum Geometry {
    /// Closed rings filled together by the even-odd rule (outer rings and their holes).
    Area(Vec<Vec<UnitPoint>>),
    /// A line `width` units of the square wide.
    Line {
        /// Its points.
        points: Vec<UnitPoint>,
        /// Its width in units of the square.
        width: f64,
    },
}

/// One drawn feature of the map.
#[derive(Debug, Clone, PartialEq)]
pub struct Feature {
    /// Its class: the colour it is drawn in and the texture it is stylized with.
    pub class: MapClass,
    /// Its shape.
    pub geometry: Geometry,
}

impl Feature {
    /// The rectangle `[x0, y0, x1, y1]` it covers, lines with their half width.
    fn bounds(&self) -> [f64; 4] {
        let (points, pad): (Box<dyn Iterator<Item = &UnitPoint>>, f64) = match &self.geometry {
            Geometry::Area(rings) => (Box::new(rings.iter().flatten()), 0.0),
            Geometry::Line { points, width } => (Box::new(points.iter()), width / 2.0),
        };
        let mut bounds = [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
        for &[x, y] in points {
            bounds = [bounds[0].min(x), bounds[1].min(y), bounds[2].max(x), bounds[3].max(y)];
        }
        [bounds[0] - pad, bounds[1] - pad, bounds[2] + pad, bounds[3] + pad]
    }
}

/// Collects a map's features as a reader finds them ([`MapBuilder::add`]) and makes the
/// [`MapData`].
#[derive(Debug, Default)]
pub struct MapBuilder {
    features: Vec<Feature>,
    coastlines: Vec<Vec<UnitPoint>>,
    bounds: Option<[f64; 4]>,
}

impl MapBuilder {
    /// An empty map.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds one way (or the member ways of a multipolygon relation, `pieces`) of class `class`
    /// drawn as `shape` (from [`classify`](crate::classify)); points in the unit square.
    pub fn add(&mut self, class: MapClass, shape: Shape, pieces: Vec<Vec<UnitPoint>>) {
        match shape {
            Shape::Coastline => self.coastlines.extend(pieces),
            Shape::Area => {
                let rings = join_rings(pieces);
                if !rings.is_empty() {
                    self.features.push(Feature { class, geometry: Geometry::Area(rings) });
                }
            }
            Shape::Line(metres) => {
                for points in pieces.into_iter().filter(|points| points.len() >= 2) {
                    let middle = points[points.len() / 2][1];
                    let width = metres / metres_per_unit(middle);
                    self.features.push(Feature { class, geometry: Geometry::Line { points, width } });
                }
            }
        }
    }

    /// Sets the map's rectangle `[x0, y0, x1, y1]` in the unit square (the extract's bounds;
    /// coastlines are closed along it). Without it, the features' own bounds are used.
    pub fn set_bounds(&mut self, bounds: [f64; 4]) {
        self.bounds = Some(bounds);
    }

    /// The map: features indexed, coastlines turned into land polygons over a sea.
    pub fn build(self) -> MapData {
        let mut bounds = self.bounds.unwrap_or_else(|| {
            let mut all = [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
            for feature in &self.features {
                let b = feature.bounds();
                all = [all[0].min(b[0]), all[1].min(b[1]), all[2].max(b[2]), all[3].max(b[3])];
            }
            all
        });
        if !bounds.iter().all(|v| v.is_finite()) {
            bounds = [0.0; 4];
        }
        // Coastlines: the map's rectangle is sea, and the land they cut from it is drawn over it;
        // outside the rectangle (nothing is known there) stays land.
        let mut features = Vec::new();
        if !self.coastlines.is_empty() {
            let [x0, y0, x1, y1] = bounds;
            let rectangle = vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]];
            features.push(Feature { class: MapClass::Water, geometry: Geometry::Area(vec![rectangle]) });
        }
        features.extend(
            land_polygons(join_chains(self.coastlines), bounds)
                .into_iter()
                .map(|ring| Feature { class: MapClass::Land, geometry: Geometry::Area(vec![ring]) }),
        );
        let mut rest = self.features;
        // Drawing order: by class, then as read.
        rest.sort_by_key(|feature| feature.class);
        features.extend(rest);
        let index = RTree::bulk_load(
            features
                .iter()
                .enumerate()
                .map(|(i, feature)| {
                    let [x0, y0, x1, y1] = feature.bounds();
                    GeomWithData::new(Rectangle::from_corners([x0, y0], [x1, y1]), i)
                })
                .collect(),
        );
        MapData { features, index, bounds }
    }
}

/// A map ready for tiles: its features in drawing order and a spatial index of them.
#[derive(Debug, Clone)]
pub struct MapData {
    features: Vec<Feature>,
    index: RTree<GeomWithData<Rectangle<[f64; 2]>, usize>>,
    bounds: [f64; 4],
}

impl MapData {
    /// Every feature, in drawing order (the sea and the land that coastlines cut from it first,
    /// then by class); land lies under them all.
    pub fn features(&self) -> &[Feature] {
        &self.features
    }

    /// The map's rectangle `[x0, y0, x1, y1]` in the unit square.
    pub fn bounds(&self) -> [f64; 4] {
        self.bounds
    }

    /// The features meeting the rectangle `[x0, y0, x1, y1]`, in drawing order.
    pub fn features_in(&self, [x0, y0, x1, y1]: [f64; 4]) -> impl Iterator<Item = &Feature> {
        let query = rstar::AABB::from_corners([x0, y0], [x1, y1]);
        let mut found: Vec<usize> = self.index.locate_in_envelope_intersecting(&query).map(|item| item.data).collect();
        found.sort_unstable();
        found.into_iter().map(|i| &self.features[i])
    }

    /// How many features of each class ([`MapClass::ALL`]'s order).
    pub fn class_counts(&self) -> [usize; 8] {
        let mut counts = [0; 8];
        for feature in &self.features {
            counts[feature.class.index()] += 1;
        }
        counts
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mercator::project;

    #[test]
    fn features_are_found_by_rectangle_in_drawing_order() {
        let mut builder = MapBuilder::new();
        let square = |x: f64, y: f64| vec![vec![[x, y], [x + 0.1, y], [x + 0.1, y + 0.1], [x, y + 0.1], [x, y]]];
        builder.add(MapClass::Building, Shape::Area, square(0.1, 0.1));
        builder.add(MapClass::Water, Shape::Area, square(0.15, 0.15));
        builder.add(MapClass::Grass, Shape::Area, square(0.7, 0.7));
        builder.add(MapClass::MajorRoad, Shape::Line(14.0), vec![vec![project(0.0, 0.0), project(1.0, 0.0)]]);
        let map = builder.build();
        let classes: Vec<MapClass> = map.features_in([0.0, 0.0, 0.3, 0.3]).map(|f| f.class).collect();
        assert_eq!(classes, vec![MapClass::Water, MapClass::Building]);
        let Geometry::Line { width, .. } = &map.features().last().unwrap().geometry else { panic!() };
        assert!((width * crate::mercator::EARTH_CIRCUMFERENCE - 14.0).abs() < 1e-6);
        assert_eq!(map.class_counts()[MapClass::Grass.index()], 1);
    }

    #[test]
    fn coastlines_make_land_over_a_sea() {
        let mut builder = MapBuilder::new();
        builder.set_bounds([0.0, 0.0, 1.0, 1.0]);
        builder.add(MapClass::Water, Shape::Coastline, vec![vec![[0.0, 0.5], [1.0, 0.5]]]);
        let map = builder.build();
        let classes: Vec<MapClass> = map.features().iter().map(|feature| feature.class).collect();
        assert_eq!(classes, vec![MapClass::Water, MapClass::Land]);
    }
}
