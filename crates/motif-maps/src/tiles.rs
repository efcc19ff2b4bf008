//! A tile set: the map, its legend's pre-synthesized textures (made once, §3.7), and any tile of
//! it rendered on demand, plain or stylized.
//!
//! A stylized tile is the band mode of `motif-stylize` over the tile's segment map with a margin:
//! the textures are laid in the zoom level's own pixel coordinates (each tile takes them shifted
//! by its position), so the copied pixels continue across tile borders exactly, and the band is
//! optimized from the textures' own matches with a seed of the tile's own. A tile's pixels
//! depend only on the map, the legend, the parameters and the tile: not on the tiles rendered
//! before it nor on the thread count.

use motif_core::{ByteImage, FloatImage, Progress, RgbaImage, SeedStreams};
use motif_stylize::{Guide, Input, NearestNeighbourField, PresynthInput, SegmentTexture, Segmentation};
use serde::Serialize;

use crate::class::MapClass;
use crate::legend::Legend;
use crate::map::MapData;
use crate::mercator::TileId;
use crate::raster::{TileFrame, crop_margin, segment_map};
use crate::{Error, Params};

/// Which picture of a tile.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Layer {
    /// The segment map: every class in its colour ([`MapClass::colour`]), anti-aliased.
    Plain,
    /// The segment map stylized with the legend's textures.
    Stylized,
}

impl Layer {
    /// Its name in URLs and reports: `plain` or `stylized`.
    pub fn name(self) -> &'static str {
        match self {
            Layer::Plain => "plain",
            Layer::Stylized => "stylized",
        }
    }
}

/// What making a tile set did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TileSetReport {
    /// Tile side in pixels.
    pub tile_size: usize,
    /// Pixels drawn around each tile and cut off.
    pub margin: usize,
    /// Whether the margin was inferred (band + 2 × patch size).
    pub margin_inferred: bool,
    /// The classes painted with a texture.
    pub textured_classes: Vec<&'static str>,
    /// Side of the pre-synthesized textures.
    pub texture_size: usize,
    /// The atlas the textures come from, `[width, height]`.
    pub atlas_size: [usize; 2],
    /// Milliseconds the presynthesis took.
    pub presynth_ms: f64,
    /// Features of the map per class, by class name.
    pub features: Vec<(&'static str, usize)>,
}

/// The style side of a stylized tile set: the atlas, its guide and one texture per class.
#[derive(Debug)]
struct Styled {
    style: ByteImage,
    guide: ByteImage,
    textures: Vec<SegmentTexture>,
}

/// A map ready to render any of its tiles (see the module's documentation).
#[derive(Debug)]
pub struct TileSet {
    map: MapData,
    params: Params,
    styled: Styled,
    report: TileSetReport,
}

impl TileSet {
    /// Validates the parameters and pre-synthesizes one texture per class from the legend's
    /// atlas (the slow step, made once; `progress` hears of it).
    pub fn new(map: MapData, legend: &Legend, params: &Params, progress: &mut dyn Progress) -> Result<Self, Error> {
        params.validate()?;
        let start = web_time::Instant::now();
        let (style, guide) = legend.atlas(2 * params.patch_size + 1);
        let stylize = presynth_params(params);
        let input = PresynthInput {
            style: style.to_float(),
            guide: guide.to_float(),
            size: (params.texture_size, params.texture_size),
        };
        let mut textures = motif_stylize::presynthesize(&input, &stylize, progress)?;
        // Presynthesis orders textures by its labels; tiles want them by class.
        textures.sort_by_key(|texture| class_of(&texture.colour).index());
        let report = TileSetReport {
            tile_size: params.tile_size,
            margin: params.resolved_margin(),
            margin_inferred: params.margin == 0,
            textured_classes: legend.textured().into_iter().map(MapClass::name).collect(),
            texture_size: params.texture_size,
            atlas_size: [style.width(), style.height()],
            presynth_ms: motif_core::timing::elapsed_ms(start),
            features: MapClass::ALL.iter().map(|class| (class.name(), map.class_counts()[class.index()])).collect(),
        };
        Ok(Self { map, params: params.clone(), styled: Styled { style, guide, textures }, report })
    }

    /// What making it did.
    pub fn report(&self) -> &TileSetReport {
        &self.report
    }

    /// The map.
    pub fn map(&self) -> &MapData {
        &self.map
    }

    /// The parameters it was made with.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// Where tile `tile`'s pixels lie, margin included.
    pub fn frame(&self, tile: TileId) -> TileFrame {
        TileFrame { tile, size: self.params.tile_size, margin: self.params.resolved_margin() }
    }

    /// Tile `tile` of layer `layer`, `tile_size` pixels a side.
    pub fn render(&self, tile: TileId, layer: Layer) -> Result<RgbaImage, Error> {
        let frame = self.frame(tile);
        let segments = segment_map(&self.map, &frame, self.params.min_line_width);
        let image = match layer {
            Layer::Plain => segments,
            Layer::Stylized => self.stylize(&frame, &segments)?,
        };
        Ok(crop_margin(&image, &frame))
    }

    /// The band synthesis of one drawn square (§3.7) with the textures laid in the zoom level's
    /// pixel coordinates.
    fn stylize(&self, frame: &TileFrame, segments: &RgbaImage) -> Result<RgbaImage, Error> {
        let (x, y) = frame.global_origin();
        let textures = self.styled.textures.iter().map(|texture| shifted(texture, x, y)).collect();
        let target = ByteImage::from_rgba_channels(segments, &[0, 1, 2]);
        let guides = vec![Guide { source: self.styled.guide.clone(), target, weight: None }];
        let mut input = Input::guided(self.styled.style.clone(), guides);
        input.textures = Some(textures);
        let tile = frame.tile;
        let index = (u64::from(tile.z) << 56) | (u64::from(tile.x) << 28) | u64::from(tile.y);
        let seed = SeedStreams::new(self.params.seed).child("tile", index).seed();
        let params = band_params(&self.params).with_seed(seed);
        let output = motif_stylize::synthesize(&input, &params, &mut motif_core::NoProgress)?;
        Ok(RgbaImage::from_float(&output.image))
    }
}

/// The nearest class of a segment colour (values in `[0, 1]`).
fn class_of(colour: &[f32]) -> MapClass {
    let distance = |class: &MapClass| -> f32 {
        class.colour().iter().zip(colour).map(|(&c, &v)| (f32::from(c) / 255.0 - v).powi(2)).sum()
    };
    MapClass::ALL.into_iter().min_by(|a, b| distance(a).total_cmp(&distance(b))).unwrap_or(MapClass::Land)
}

/// The parameters of the presynthesis.
fn presynth_params(params: &Params) -> motif_stylize::Params {
    motif_stylize::Params::default()
        .with_patch_size(params.patch_size)
        .with_segments(Some(Segmentation::Palette))
        .with_seed(params.seed)
}

/// The parameters of a tile's band.
fn band_params(params: &Params) -> motif_stylize::Params {
    presynth_params(params)
        .with_band(params.band)
        .with_band_search_vote_iterations(params.band_iterations)
        .with_band_patchmatch_iterations(params.band_patchmatch_iterations)
}

/// `texture` as seen from a drawn square whose top-left pixel is `(x, y)` of the zoom level: its
/// pixel `(i, j)` is the texture's `((x + i) mod w, (y + j) mod h)`, its field likewise.
fn shifted(texture: &SegmentTexture, x: i64, y: i64) -> SegmentTexture {
    let image = &texture.image;
    let (width, height, channels) = (image.width(), image.height(), image.channels());
    let (dx, dy) = (x.rem_euclid(width as i64) as usize, y.rem_euclid(height as i64) as usize);
    let at = |i: usize, j: usize| ((j + dy) % height) * width + (i + dx) % width;
    let mut data = Vec::with_capacity(width * height * channels);
    for j in 0..height {
        for i in 0..width {
            let from = at(i, j) * channels;
            data.extend_from_slice(&image.data()[from..from + channels]);
        }
    }
    let image = FloatImage::from_data(width, height, channels, data).expect("same size as the texture");
    let field = texture.field.as_ref().map(|field| NearestNeighbourField {
        matches: (0..height)
            .flat_map(|j| (0..width).map(move |i| (i, j)))
            .map(|(i, j)| field.matches[at(i, j)])
            .collect(),
        weights: field
            .weights
            .as_ref()
            .map(|w| (0..height).flat_map(|j| (0..width).map(move |i| (i, j))).map(|(i, j)| w[at(i, j)]).collect()),
        ..field.clone()
    });
    SegmentTexture { colour: texture.colour.clone(), image, field }
}
