//! The map's segment classes and which OpenStreetMap tags make each.

use serde::{Deserialize, Serialize};

/// One segment class of the map: every pixel of a segment map is one of them (or a blend of two
/// on an anti-aliased edge), and each is stylized from its own texture.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MapClass {
    /// Everything not covered by another class (and the land side of a coastline).
    Land,
    /// Sea, lakes, ponds, basins, rivers and streams.
    Water,
    /// Lawns, pitches, playgrounds, meadows, wetland.
    Grass,
    /// Parks, woods, forests, scrub, heath.
    Forest,
    /// Buildings.
    Building,
    /// Railways, trams, subways.
    Rail,
    /// Residential and service streets, pedestrian ways, footways, cycleways, paths, steps.
    MinorRoad,
    /// Motorways, trunk, primary, secondary and tertiary roads and their links.
    MajorRoad,
}

impl MapClass {
    /// Every class, in drawing order (each drawn over the ones before it).
    pub const ALL: [MapClass; 8] = [
        MapClass::Land,
        MapClass::Water,
        MapClass::Grass,
        MapClass::Forest,
        MapClass::Building,
        MapClass::Rail,
        MapClass::MinorRoad,
        MapClass::MajorRoad,
    ];

    /// Its name in legends, files and reports (`land`, `water`, …, `minor-road`, `major-road`).
    pub fn name(self) -> &'static str {
        match self {
            MapClass::Land => "land",
            MapClass::Water => "water",
            MapClass::Grass => "grass",
            MapClass::Forest => "forest",
            MapClass::Building => "building",
            MapClass::Rail => "rail",
            MapClass::MinorRoad => "minor-road",
            MapClass::MajorRoad => "major-road",
        }
    }

    /// The class named `name` ([`MapClass::name`]).
    pub fn named(name: &str) -> Option<MapClass> {
        MapClass::ALL.into_iter().find(|class| class.name() == name)
    }

    /// Its colour in the plain segment map, which is also the segment guide of the stylized one
    /// (distinct enough that anti-aliased blends of two never come nearer a third).
    pub fn colour(self) -> [u8; 3] {
        match self {
            MapClass::Land => [242, 239, 233],
            MapClass::Water => [120, 170, 215],
            MapClass::Grass => [190, 225, 150],
            MapClass::Forest => [90, 160, 90],
            MapClass::Building => [170, 150, 140],
            MapClass::Rail => [60, 60, 70],
            MapClass::MinorRoad => [255, 255, 255],
            MapClass::MajorRoad => [250, 200, 90],
        }
    }

    /// Its index in [`MapClass::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }
}

/// How a way or relation is drawn: an area (closed rings, filled) or a line of a width in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A filled area.
    Area,
    /// A stroked line this many metres wide.
    Line(f64),
    /// A stretch of coastline: land on its left, water on its right.
    Coastline,
}

/// The class and shape of an OpenStreetMap way or relation from its tags, or `None` when the map
/// does not draw it. `closed` says whether the way's first and last nodes are the same.
pub fn classify<'a>(tags: impl IntoIterator<Item = (&'a str, &'a str)>, closed: bool) -> Option<(MapClass, Shape)> {
    let tags: Vec<(&str, &str)> = tags.into_iter().collect();
    let tag = |key: &str| tags.iter().find(|(k, _)| *k == key).map(|(_, v)| *v);
    let area_tag = tag("area");
    let area = closed && area_tag != Some("no");
    if tag("natural") == Some("coastline") {
        return Some((MapClass::Water, Shape::Coastline));
    }
    if let Some(building) = tag("building")
        && building != "no"
        && area
    {
        return Some((MapClass::Building, Shape::Area));
    }
    if let Some(highway) = tag("highway") {
        let (class, width) = match highway {
            "motorway" | "trunk" | "primary" | "secondary" | "tertiary" | "motorway_link" | "trunk_link"
            | "primary_link" | "secondary_link" | "tertiary_link" => (MapClass::MajorRoad, 14.0),
            "residential" | "service" | "unclassified" | "living_street" | "pedestrian" | "road" => {
                (MapClass::MinorRoad, 8.0)
            }
            "footway" | "cycleway" | "path" | "steps" | "track" | "bridleway" | "trail" => (MapClass::MinorRoad, 3.0),
            _ => return None,
        };
        let shape = if closed && area_tag == Some("yes") { Shape::Area } else { Shape::Line(width) };
        return Some((class, shape));
    }
    if let Some(railway) = tag("railway") {
        let width = match railway {
            "rail" | "subway" | "light_rail" | "narrow_gauge" | "monorail" => 4.0,
            "tram" => 2.5,
            _ => return None,
        };
        return Some((MapClass::Rail, Shape::Line(width)));
    }
    if let Some(waterway) = tag("waterway") {
        return match waterway {
            "riverbank" | "dock" if area => Some((MapClass::Water, Shape::Area)),
            "river" | "canal" => Some((MapClass::Water, Shape::Line(12.0))),
            "stream" | "drain" | "ditch" => Some((MapClass::Water, Shape::Line(3.0))),
            _ => None,
        };
    }
    if !area {
        return None;
    }
    let class = match (tag("natural"), tag("landuse"), tag("leisure")) {
        (Some("water" | "bay"), _, _) | (_, Some("basin" | "reservoir" | "pond"), _) => MapClass::Water,
        (Some("wood" | "scrub" | "heath"), _, _)
        | (_, Some("forest"), _)
        | (_, _, Some("park" | "garden" | "nature_reserve")) => MapClass::Forest,
        (Some("grassland" | "wetland"), _, _)
        | (_, Some("grass" | "meadow" | "recreation_ground" | "village_green" | "cemetery"), _)
        | (_, _, Some("pitch" | "playground" | "golf_course" | "common")) => MapClass::Grass,
        _ => return None,
    };
    Some((class, Shape::Area))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tags_give_classes_and_shapes() {
        let of = |tags: &[(&str, &str)], closed| classify(tags.iter().copied(), closed);
        assert_eq!(of(&[("building", "yes")], true), Some((MapClass::Building, Shape::Area)));
        assert_eq!(of(&[("building", "yes")], false), None);
        assert_eq!(of(&[("highway", "primary")], false), Some((MapClass::MajorRoad, Shape::Line(14.0))));
        assert_eq!(of(&[("highway", "footway")], true), Some((MapClass::MinorRoad, Shape::Line(3.0))));
        assert_eq!(of(&[("highway", "pedestrian"), ("area", "yes")], true), Some((MapClass::MinorRoad, Shape::Area)));
        assert_eq!(of(&[("highway", "bus_stop")], false), None);
        assert_eq!(of(&[("railway", "tram")], false), Some((MapClass::Rail, Shape::Line(2.5))));
        assert_eq!(of(&[("natural", "coastline")], false), Some((MapClass::Water, Shape::Coastline)));
        assert_eq!(of(&[("leisure", "park")], true), Some((MapClass::Forest, Shape::Area)));
        assert_eq!(of(&[("landuse", "grass")], true), Some((MapClass::Grass, Shape::Area)));
        assert_eq!(of(&[("landuse", "grass"), ("area", "no")], true), None);
        assert_eq!(of(&[("natural", "water")], true), Some((MapClass::Water, Shape::Area)));
        assert_eq!(of(&[("landuse", "commercial")], true), None);
    }

    #[test]
    fn names_round_trip_and_colours_differ() {
        for class in MapClass::ALL {
            assert_eq!(MapClass::named(class.name()), Some(class));
            assert_eq!(MapClass::ALL[class.index()], class);
        }
        for a in MapClass::ALL {
            for b in MapClass::ALL {
                if a != b {
                    assert_ne!(a.colour(), b.colour());
                }
            }
        }
    }
}
