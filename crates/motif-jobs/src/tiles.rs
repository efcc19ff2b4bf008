//! The `tiles` job: a stylized navigation map, any tile on demand (Texler et al.'s application).
//!
//! The run pre-synthesizes one texture per map class from the legend, once; the front end then
//! asks its [`TileSet`] for the tiles it serves or packs ([`TilesRun::pyramid`] lists those of
//! the job's zoom range over the map).

use motif_core::Progress;
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value, json};

use crate::options::Described;
use crate::{Finished, Job, JobError};
/// The map types tile inputs and runs are made of, named here so that front ends need no other
/// crate.
pub use motif_maps::{
    Fill, Layer, Legend, MAX_ZOOM, MapBuilder, MapClass, MapData, TileId, TileSet, TileSetReport, halved, project,
    seam_error, tiles_covering, unproject, zoom_error,
};

const DEFAULTS: motif_maps::Params = motif_maps::Params::DEFAULT;

/// The most tiles a packed pyramid may hold (about an hour on two cores at 40 ms a tile).
pub const MAX_PYRAMID_TILES: usize = 100_000;

/// The zoom levels a pyramid takes when the job names none.
pub const DEFAULT_ZOOM: [u8; 2] = [12, 16];

crate::declare_options! {
    /// The options of `motif tiles`, declared once.
    pub struct TilesOptions {
        /// Side of a tile in pixels (slippy maps use 256).
        [value_name: "PX", range: (64.0, 1024.0)]
        tile_size: usize = DEFAULTS.tile_size,
        /// Pixels drawn and stylized around each tile and cut off, so the band's patches at a
        /// tile's edge see what its neighbour's see; 0 = the band plus the patch size, the
        /// reach of a band pixel's result (the report's `margin`).
        [value_name: "PX", range: (0.0, 256.0)]
        margin: usize = DEFAULTS.margin,
        /// Band half-width T in pixels (Texler et al. §3.7): pixels farther than this from a class
        /// edge are copied from the class's pre-synthesized texture, only the band between is
        /// optimized; 0 = composition only. Wider bands blend the classes' edges more, slower.
        [value_name: "T", range: (0.0, 64.0)]
        band: usize = DEFAULTS.band,
        /// Side of each class's pre-synthesized texture in pixels, made once for all tiles (they
        /// tile seamlessly; larger ones repeat less often and take longer to make).
        [value_name: "PX", range: (16.0, 1024.0)]
        texture_size: usize = DEFAULTS.texture_size,
        /// Patch side in pixels, odd, of the presynthesis and the band.
        [value_name: "P", range: (3.0, 15.0)]
        patch_size: usize = DEFAULTS.patch_size,
        /// Search-vote iterations of the band (it starts from the textures' own matches).
        [value_name: "N", range: (1.0, 20.0)]
        band_iters: usize = DEFAULTS.band_iterations,
        /// PatchMatch iterations per search of the band.
        [value_name: "K", range: (1.0, 20.0)]
        band_patchmatch_iters: usize = DEFAULTS.band_patchmatch_iterations,
        /// Narrowest line drawn, in pixels, so that small roads stay visible at low zooms.
        [value_name: "PX", range: (0.25, 16.0)]
        min_line_width: f32 = DEFAULTS.min_line_width,
        /// Levels of the texture pyramid, so that zooming in keeps the textures' layout: the
        /// first textures serve --base-zoom and below; each next level, twice the side and
        /// synthesized under the one before magnified twice, serves the next zoom (deeper zooms
        /// take the last). `serve` makes them before it listens, `render` those of its zooms before
        /// the first tile; 1 = the same textures at every zoom.
        [value_name: "N", range: (1.0, 4.0)]
        texture_levels: usize = DEFAULTS.texture_levels,
        /// Zoom level of the first textures of the pyramid (see --texture-levels).
        [value_name: "Z", range: (0.0, 24.0)]
        base_zoom: usize = DEFAULTS.base_zoom as usize,
    }
}

/// The fields of a `tiles` job outside its options.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub struct TilesFields {
    #[serde(default = "default_seed")]
    seed: u64,
    #[serde(default)]
    zoom: Option<[u8; 2]>,
}

fn default_seed() -> u64 {
    1
}

/// A `tiles` job: the seed, the zoom levels of its pyramid, and every option.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "crate::options::Described<TilesFields>")]
pub struct TilesJob {
    /// Seed of every random choice (default 1, as on the command line).
    pub seed: u64,
    /// The lowest and highest zoom level of the pyramid (default [`DEFAULT_ZOOM`]).
    pub zoom: Option<[u8; 2]>,
    /// Every other option.
    #[serde(flatten)]
    pub options: TilesOptions,
}

impl TryFrom<Described<TilesFields>> for TilesJob {
    type Error = String;
    fn try_from(described: Described<TilesFields>) -> Result<Self, String> {
        let (fields, options) = described.split()?;
        Ok(Self { seed: fields.seed, zoom: fields.zoom, options })
    }
}

impl Default for TilesJob {
    fn default() -> Self {
        Self::new()
    }
}

impl TilesJob {
    /// A job with every option at its default.
    pub fn new() -> Self {
        Self { seed: default_seed(), zoom: None, options: TilesOptions::default() }
    }

    /// The tile set's parameters.
    pub fn params(&self) -> Result<motif_maps::Params, JobError> {
        let o = &self.options;
        let params = motif_maps::Params::default()
            .with_tile_size(o.tile_size)
            .with_margin(o.margin)
            .with_band(o.band)
            .with_texture_size(o.texture_size)
            .with_patch_size(o.patch_size)
            .with_band_iterations(o.band_iters)
            .with_band_patchmatch_iterations(o.band_patchmatch_iters)
            .with_min_line_width(o.min_line_width)
            .with_texture_levels(o.texture_levels)
            .with_base_zoom(u8::try_from(o.base_zoom).unwrap_or(u8::MAX))
            .with_seed(self.seed);
        params.validate().map_err(maps_error)?;
        Ok(params)
    }

    /// The zoom levels of the pyramid, checked: lowest first, at most [`motif_maps::MAX_ZOOM`].
    pub fn zooms(&self) -> Result<[u8; 2], JobError> {
        let [low, high] = self.zoom.unwrap_or(DEFAULT_ZOOM);
        if low > high || high > motif_maps::MAX_ZOOM {
            return Err(motif_core::InvalidParameter::new(
                "zoom",
                format!("{low}-{high}"),
                format!("must be LOW-HIGH with LOW ≤ HIGH ≤ {}", motif_maps::MAX_ZOOM),
            )
            .into());
        }
        Ok([low, high])
    }
}

/// What a pyramid's archive says about itself besides its tiles: the same from every front end,
/// so that archives of the same job have the same bytes.
#[derive(Debug, Clone, PartialEq)]
pub struct ArchiveHeader {
    /// The lowest and highest zoom level.
    pub zooms: [u8; 2],
    /// `[west, south, east, north]` in degrees: the map's rectangle.
    pub bounds: [f64; 4],
    /// A JSON object: the map's file name, a description, the attribution, the layer and the job.
    pub metadata: String,
}

impl TilesJob {
    /// The header of the archive of `run`'s pyramid of layer `layer`, for the map file named
    /// `map_name`.
    pub fn archive_header(&self, run: &TilesRun, map_name: &str, layer: Layer) -> ArchiveHeader {
        let [x0, y0, x1, y1] = run.tiles.map().bounds();
        let ((west, north), (east, south)) = (unproject([x0, y0]), unproject([x1, y1]));
        let metadata = json!({
            "name": map_name,
            "description": "motif tiles: a stylized OpenStreetMap extract",
            "attribution": "© OpenStreetMap contributors (ODbL)",
            "layer": layer.name(),
            "job": self,
        });
        ArchiveHeader { zooms: run.zooms, bounds: [west, south, east, north], metadata: metadata.to_string() }
    }
}

/// A map error as a job error (parameters as options, the stylization as the engine's).
fn maps_error(error: motif_maps::Error) -> JobError {
    match error {
        motif_maps::Error::Parameter(parameter) => JobError::InvalidParameter(parameter),
        motif_maps::Error::Stylize(stylize) => JobError::Stylize(stylize),
        other => JobError::InvalidParameter(motif_core::InvalidParameter::new("tiles", other, "")),
    }
}

/// What a `tiles` run starts from: the map and its legend.
#[derive(Debug)]
pub struct TilesInputs {
    /// The map (read from an OpenStreetMap extract by the front end).
    pub map: MapData,
    /// What each class looks like.
    pub legend: Legend,
}

/// A finished `tiles` run: the tile set, ready for any tile, and the run's figures.
#[derive(Debug)]
pub struct TilesRun {
    /// Every tile on demand.
    pub tiles: TileSet,
    /// The zoom levels of the job's pyramid.
    pub zooms: [u8; 2],
    /// The figures: the tile set's report (`margin`, `presynth_ms`, the features per class, …).
    pub figures: Map<String, Value>,
}

impl Finished for TilesRun {
    fn figures(&self) -> &Map<String, Value> {
        &self.figures
    }
}

impl TilesRun {
    /// The tiles of the pyramid: every tile of the job's zoom levels that meets the map, by zoom
    /// then row then column. Refused, by `zoom`, beyond [`MAX_PYRAMID_TILES`] (counted first).
    pub fn pyramid(&self) -> Result<Vec<TileId>, JobError> {
        let [x0, y0, x1, y1] = self.tiles.map().bounds();
        let count: f64 = (self.zooms[0]..=self.zooms[1])
            .map(|z| {
                let side = (1u64 << z) as f64;
                let span = |low: f64, high: f64| {
                    ((high * side).floor().min(side - 1.0) - (low * side).floor().max(0.0) + 1.0).max(1.0)
                };
                span(x0, x1) * span(y0, y1)
            })
            .sum();
        if count > MAX_PYRAMID_TILES as f64 {
            return Err(motif_core::InvalidParameter::new(
                "zoom",
                format!("{}-{}", self.zooms[0], self.zooms[1]),
                format!(
                    "gives {count:.0} tiles over this map, more than {MAX_PYRAMID_TILES} (hours of work and gigabytes); \
                     pack fewer zoom levels, or serve the deep ones on demand"
                ),
            )
            .into());
        }
        let bounds = [x0, y0, x1, y1];
        Ok((self.zooms[0]..=self.zooms[1]).flat_map(|z| tiles_covering(bounds, z)).collect())
    }

    /// Tile `tile` of layer `layer`.
    pub fn render(&self, tile: TileId, layer: Layer) -> Result<motif_core::RgbaImage, JobError> {
        self.tiles.render(tile, layer).map_err(maps_error)
    }

    /// Makes the levels of the texture pyramid (`--texture-levels`) that tiles up to zoom
    /// `up_to_zoom` take, now, not when a tile first needs them: the server makes them all before
    /// its first request, a pyramid's render those of its zooms before its first tile.
    pub fn make_texture_levels(&self, up_to_zoom: u8) -> Result<(), JobError> {
        self.tiles.make_texture_levels(up_to_zoom).map_err(maps_error)
    }
}

impl Job for TilesJob {
    const NAME: &'static str = "tiles";
    const FIELDS: &'static [&'static str] = &["seed", "zoom"];
    const SUMMARY: &'static str = "Stylize an OpenStreetMap extract as slippy-map tiles: serve them, or pack a pyramid";
    const DETAILS: &'static str = "The application of Texler et al.'s map stylization: every tile's segment map \
        (water, grass, forest, buildings, rail, minor and major roads over land) is drawn from the map, filled from \
        textures pre-synthesized once per class from the legend, and only a band along the class edges is optimized \
        (§3.7). Textures are laid in the zoom level's own pixels, so neighbouring tiles continue each other.";
    type Options = TilesOptions;
    type Inputs<'a> = TilesInputs;
    type Run = TilesRun;

    fn run(&self, inputs: TilesInputs, progress: &mut dyn Progress) -> Result<TilesRun, JobError> {
        let params = self.params()?;
        let tiles = TileSet::new(inputs.map, &inputs.legend, &params, progress).map_err(maps_error)?;
        self.finish(tiles)
    }
}

impl TilesJob {
    /// [`Job::run`] with the textures of an earlier run of the same job and legend
    /// ([`TileSet::textures`], e.g. shipped to a Dask worker): no presynthesis, the same tiles.
    pub fn run_with_textures(
        &self,
        inputs: TilesInputs,
        textures: Vec<motif_stylize::SegmentTexture>,
    ) -> Result<TilesRun, JobError> {
        let params = self.params()?;
        let tiles = TileSet::with_textures(inputs.map, &inputs.legend, &params, textures).map_err(maps_error)?;
        self.finish(tiles)
    }

    /// The run of `tiles`, with its figures.
    fn finish(&self, tiles: TileSet) -> Result<TilesRun, JobError> {
        let zooms = self.zooms()?;
        let report = tiles.report();
        let mut figures = crate::object(json!(report));
        figures.insert("zoom".into(), json!(zooms));
        let features =
            report.features.iter().map(|(class, count)| (class.to_string(), json!(count))).collect::<Map<_, _>>();
        figures.insert("features".into(), Value::Object(features));
        Ok(TilesRun { tiles, zooms, figures })
    }
}
