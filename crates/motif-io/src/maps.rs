//! Map files: OpenStreetMap extracts in (`.osm.pbf`, through `osmpbf`) and tile pyramids out
//! (PMTiles archives, through `pmtiles`).

use std::collections::HashMap;
use std::path::Path;

use motif_maps::{MapBuilder, MapData, Shape, TileId, UnitPoint, classify, project};
use osmpbf::{Element, ElementReader, RelMemberType};

use crate::{IoError, Result, write_with};

/// Bytes of memory reading takes per byte of a `.osm.pbf` file, about (its blocks inflate about
/// tenfold, and every node and way is kept until the relations are read).
const MEMORY_PER_FILE_BYTE: u64 = 40;

/// What an extract holds besides the map: counts for reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct OsmCounts {
    /// Nodes read.
    pub nodes: usize,
    /// Ways read.
    pub ways: usize,
    /// Relations read.
    pub relations: usize,
}

/// Reads an OpenStreetMap extract (`.osm.pbf`) into a map: every way and multipolygon relation
/// that [`classify`] draws, projected into Web Mercator's unit square, the extract's rectangle
/// being its nodes' bounds. Refuses a file whose reading would pass `max_memory` bytes.
pub fn read_osm(path: &Path, max_memory: u64) -> Result<(MapData, OsmCounts)> {
    let length = std::fs::metadata(path).map_err(|source| IoError::io(path, source))?.len();
    if length.saturating_mul(MEMORY_PER_FILE_BYTE) > max_memory {
        return Err(IoError::format(
            path,
            format!(
                "a {} MB extract needs about {} MB to read, more than --max-memory ({} MB); cut a smaller extract \
                 (osmium extract --bbox) or raise --max-memory",
                length / 1_000_000,
                length.saturating_mul(MEMORY_PER_FILE_BYTE) / 1_000_000,
                max_memory / 1_000_000
            ),
        ));
    }
    let reader = ElementReader::from_path(path).map_err(|error| not_pbf(path, &error))?;
    let mut reading = Reading::default();
    reader.for_each(|element| reading.take(element)).map_err(|error| not_pbf(path, &error))?;
    if reading.counts.nodes == 0 {
        return Err(IoError::format(path, "has no nodes: it is not an OpenStreetMap extract with data"));
    }
    Ok((reading.builder.build(), reading.counts))
}

fn not_pbf(path: &Path, error: &osmpbf::Error) -> IoError {
    IoError::format(path, format!("is not a readable OpenStreetMap PBF extract (.osm.pbf): {error}"))
}

/// The state of one pass over an extract.
#[derive(Default)]
struct Reading {
    nodes: HashMap<i64, UnitPoint>,
    ways: HashMap<i64, Vec<UnitPoint>>,
    bounds: Option<[f64; 4]>,
    builder: MapBuilder,
    counts: OsmCounts,
}

impl Reading {
    fn take(&mut self, element: Element<'_>) {
        match element {
            Element::Node(node) => self.node(node.id(), node.lon(), node.lat()),
            Element::DenseNode(node) => self.node(node.id(), node.lon(), node.lat()),
            Element::Way(way) => {
                self.counts.ways += 1;
                let refs: Vec<i64> = way.refs().collect();
                let points: Vec<UnitPoint> = refs.iter().filter_map(|id| self.nodes.get(id).copied()).collect();
                let closed = refs.len() > 3 && refs.first() == refs.last() && points.len() == refs.len();
                if let Some((class, shape)) = classify(way.tags(), closed) {
                    self.builder.add(class, shape, vec![points.clone()]);
                }
                self.ways.insert(way.id(), points);
            }
            Element::Relation(relation) => {
                self.counts.relations += 1;
                let tags: Vec<(&str, &str)> = relation.tags().collect();
                if !tags.iter().any(|&(key, value)| key == "type" && value == "multipolygon") {
                    return;
                }
                let Some((class, Shape::Area)) = classify(tags.iter().copied(), true) else { return };
                let pieces = relation
                    .members()
                    .filter(|member| member.member_type == RelMemberType::Way)
                    .filter_map(|member| self.ways.get(&member.member_id).cloned())
                    .collect();
                self.builder.add(class, Shape::Area, pieces);
            }
        }
    }

    fn node(&mut self, id: i64, lon: f64, lat: f64) {
        self.counts.nodes += 1;
        let point = project(lon, lat);
        self.nodes.insert(id, point);
        let [x, y] = point;
        let b = self.bounds.get_or_insert([x, y, x, y]);
        *b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
        self.builder.set_bounds(*b);
    }
}

/// What a PMTiles archive says about itself besides its tiles.
#[derive(Debug, Clone, PartialEq)]
pub struct PyramidInfo {
    /// Zoom levels held, lowest and highest.
    pub zooms: (u8, u8),
    /// `[west, south, east, north]` in degrees.
    pub bounds: [f64; 4],
    /// The metadata, a JSON object as text.
    pub metadata: String,
}

/// Writes PNG tiles into one PMTiles (version 3) archive, atomically. Tiles come in any order;
/// they are stored by their tile id, identical tiles once.
pub fn write_pmtiles(path: &Path, info: &PyramidInfo, tiles: &[(TileId, Vec<u8>)]) -> Result<()> {
    let mut sorted: Vec<&(TileId, Vec<u8>)> = tiles.iter().collect();
    sorted.sort_by_key(|(tile, _)| pmtiles::TileId::from(coord(*tile)).value());
    let [west, south, east, north] = info.bounds;
    let (centre_lon, centre_lat) = ((west + east) / 2.0, (south + north) / 2.0);
    write_with(path, |file| {
        let to_io = |error: pmtiles::PmtError| std::io::Error::other(error.to_string());
        let mut writer = pmtiles::PmTilesWriter::new(pmtiles::TileType::Png)
            .min_zoom(info.zooms.0)
            .max_zoom(info.zooms.1)
            .bounds(west, south, east, north)
            .center(centre_lon, centre_lat)
            .center_zoom(info.zooms.0)
            .metadata(info.metadata.clone())
            .create(file)
            .map_err(to_io)?;
        for (tile, png) in sorted {
            writer.add_tile(coord(*tile), png).map_err(to_io)?;
        }
        writer.finalize().map_err(to_io)
    })
}

fn coord(tile: TileId) -> pmtiles::TileCoord {
    pmtiles::TileCoord::new(tile.z, tile.x, tile.y).expect("a checked TileId is a valid tile coordinate")
}
