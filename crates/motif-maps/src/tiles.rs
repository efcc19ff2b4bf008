//! A tile set: the map, its legend's pre-synthesized textures (made once, §3.7), and any tile of
//! it rendered on demand, plain or stylized.
//!
//! A stylized tile is the band mode of `motif-stylize` over the tile's segment map with a margin:
//! the textures are laid in the zoom level's own pixel coordinates (each tile takes them from its
//! position), so the copied pixels continue across tile borders exactly, and the band is refined
//! by the local search of `motif_stylize::Params::band_local_search`, whose random draws are keyed
//! by the same coordinates and whose every pixel depends only on the picture a few pixels around
//! it. With a margin wider than that reach, a tile has the pixels of the map rendered whole, but
//! near the rare pixels where `tiny-skia` draws its segment map differently (see the tests): no
//! seam, and nothing depends on the tiles rendered before it nor on the thread count.

use motif_core::{ByteImage, Progress, RgbaImage};
use motif_stylize::{Guide, Input, PreparedStyle, PresynthInput, SegmentTexture, Segmentation};
use serde::Serialize;
use std::sync::{Arc, Mutex};

use crate::class::MapClass;
use crate::legend::Legend;
use crate::map::MapData;
use crate::mercator::TileId;
use crate::raster::{TileFrame, crop_margin, guide_map, segment_map};
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
    /// Levels of the texture pyramid (1: the same textures at every zoom); level `k` serves zoom
    /// `base_zoom + k`, with textures `texture_size · 2^k` a side, made when first needed.
    pub texture_levels: usize,
    /// The zoom level of the first textures.
    pub base_zoom: u8,
    /// The atlas the textures come from, `[width, height]`.
    pub atlas_size: [usize; 2],
    /// Milliseconds the presynthesis took (0 when the textures were given).
    pub presynth_ms: f64,
    /// Whether the textures were pre-synthesized here (false: given, made before by the same
    /// legend and parameters, see [`TileSet::with_textures`]).
    pub presynthesized: bool,
    /// Features of the map per class, by class name.
    pub features: Vec<(&'static str, usize)>,
}

/// The style side of a stylized tile set: the atlas, its guide, one texture per class, and what
/// every tile's band reads of them, made once ([`motif_stylize::prepare`]).
#[derive(Debug)]
struct Styled {
    style: ByteImage,
    guide: ByteImage,
    textures: Arc<[SegmentTexture]>,
    prepared: Arc<PreparedStyle<ByteImage>>,
}

impl Styled {
    fn new(
        style: ByteImage,
        guide: ByteImage,
        textures: Arc<[SegmentTexture]>,
        params: &Params,
    ) -> Result<Self, Error> {
        // Any target of the guide's colours serves: the guide itself.
        let guides = vec![Guide { source: guide.clone(), target: guide.clone(), weight: None }];
        let input = Input { textures: Some(textures.clone()), ..Input::guided(style.clone(), guides) };
        let prepared = Arc::new(motif_stylize::prepare(&input, &band_params(params))?);
        Ok(Self { style, guide, textures, prepared })
    }
}

/// A map ready to render any of its tiles (see the module's documentation).
#[derive(Debug)]
pub struct TileSet {
    map: MapData,
    params: Params,
    styled: Styled,
    /// The texture pyramid's levels past the first, made when a tile first needs them.
    closer: Mutex<Vec<Arc<[SegmentTexture]>>>,
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
        let presynth_ms = Some(motif_core::timing::elapsed_ms(start));
        let styled = Styled::new(style, guide, textures.into(), params)?;
        Ok(Self::assemble(map, legend, params, styled, presynth_ms))
    }

    /// The tile set of `map` with textures pre-synthesized before by [`TileSet::new`] with the
    /// same legend and parameters (its [`TileSet::textures`], e.g. shipped to another machine):
    /// no presynthesis, and the same tiles to the byte. Refused unless there is one texture per
    /// class, in class order, `texture_size` a side, with the legend's channels.
    pub fn with_textures(
        map: MapData,
        legend: &Legend,
        params: &Params,
        textures: Vec<SegmentTexture>,
    ) -> Result<Self, Error> {
        params.validate()?;
        let (style, guide) = legend.atlas(2 * params.patch_size + 1);
        let side = params.texture_size;
        let fits = |(index, texture): (usize, &SegmentTexture)| {
            let image = &texture.image;
            class_of(&texture.colour) == MapClass::ALL[index]
                && (image.width(), image.height(), image.channels()) == (side, side, style.channels())
        };
        if textures.len() != MapClass::ALL.len() || !textures.iter().enumerate().all(fits) {
            let allowed = format!(
                "one texture per class ({}), in that order, {side}×{side} with {} channels: those of a tile set \
                 made with the same legend and parameters",
                MapClass::ALL.len(),
                style.channels()
            );
            return Err(
                motif_core::InvalidParameter::new("textures", format!("{} given", textures.len()), allowed).into()
            );
        }
        Ok(Self::assemble(map, legend, params, Styled::new(style, guide, textures.into(), params)?, None))
    }

    /// The tile set and its report; `presynth_ms` when the textures were made here.
    fn assemble(map: MapData, legend: &Legend, params: &Params, styled: Styled, presynth_ms: Option<f64>) -> Self {
        let report = TileSetReport {
            tile_size: params.tile_size,
            margin: params.resolved_margin(),
            margin_inferred: params.margin == 0,
            textured_classes: legend.textured().into_iter().map(MapClass::name).collect(),
            texture_size: params.texture_size,
            texture_levels: params.texture_levels,
            base_zoom: params.base_zoom,
            atlas_size: [styled.style.width(), styled.style.height()],
            presynth_ms: presynth_ms.unwrap_or(0.0),
            presynthesized: presynth_ms.is_some(),
            features: MapClass::ALL.iter().map(|class| (class.name(), map.class_counts()[class.index()])).collect(),
        };
        Self { map, params: params.clone(), styled, closer: Mutex::new(Vec::new()), report }
    }

    /// Makes the levels of the texture pyramid ([`Params::texture_levels`]) that tiles up to zoom
    /// `up_to_zoom` take, now rather than when a tile first needs them: a server does this before
    /// it listens (so that no request waits), a pyramid's render before its first tile (so that
    /// its threads do not make the same level side by side). The same bytes either way.
    pub fn make_texture_levels(&self, up_to_zoom: u8) -> Result<(), Error> {
        match self.params.texture_level(up_to_zoom) {
            0 => Ok(()),
            level => self.closer_textures(level).map(|_| ()),
        }
    }

    /// The pre-synthesized textures, one per class in class order (for [`TileSet::with_textures`]).
    pub fn textures(&self) -> &[SegmentTexture] {
        &self.styled.textures
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

    /// Where the pixels of the `span × span` tiles from `tile` lie, margin included.
    pub fn frame(&self, tile: TileId, span: usize) -> TileFrame {
        TileFrame { tile, size: self.params.tile_size, span, margin: self.params.resolved_margin() }
    }

    /// Tile `tile` of layer `layer`, `tile_size` pixels a side.
    pub fn render(&self, tile: TileId, layer: Layer) -> Result<RgbaImage, Error> {
        self.render_block(tile, 1, layer)
    }

    /// Stylized tile `tile`, and its four tiles at the next zoom joined into one image twice its
    /// side: what [`zoom_error`](crate::zoom_error) compares.
    pub fn render_zooming_in(&self, tile: TileId) -> Result<(RgbaImage, RgbaImage), Error> {
        let parent = self.render(tile, Layer::Stylized)?;
        let size = parent.width();
        let mut children = Vec::with_capacity(4);
        for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            children.push(self.render(TileId::new(tile.z + 1, 2 * tile.x + dx, 2 * tile.y + dy)?, Layer::Stylized)?);
        }
        let joined = RgbaImage::from_fn(2 * size, 2 * size, |x, y| {
            children[usize::from(y >= size) * 2 + usize::from(x >= size)].get(x % size, y % size)
        });
        Ok((parent, joined))
    }

    /// The `span × span` tiles from `tile` east and south rendered as one piece (the reference
    /// that tiles rendered apart are compared with), `span · tile_size` pixels a side.
    pub fn render_block(&self, tile: TileId, span: usize, layer: Layer) -> Result<RgbaImage, Error> {
        let frame = self.frame(tile, span.max(1));
        let width = self.params.min_line_width;
        let image = match layer {
            Layer::Plain => segment_map(&self.map, &frame, width, true),
            Layer::Stylized => self.stylize(&frame, &guide_map(&self.map, &frame, width))?,
        };
        Ok(crop_margin(&image, &frame))
    }

    /// The band synthesis of one drawn square (§3.7) with the textures laid in the zoom level's
    /// pixel coordinates, and the band's local search keyed by them: one seed for the whole map,
    /// so a tile has the pixels of the map rendered whole.
    fn stylize(&self, frame: &TileFrame, segments: &RgbaImage) -> Result<RgbaImage, Error> {
        let target = ByteImage::from_rgba_channels(segments, &[0, 1, 2]);
        let guides = vec![Guide { source: self.styled.guide.clone(), target, weight: None }];
        let mut input = Input::guided(self.styled.style.clone(), guides);
        input.textures = Some(match self.params.texture_level(frame.tile.z) {
            0 => self.styled.textures.clone(),
            level => self.closer_textures(level)?,
        });
        input.texture_origin = frame.global_origin();
        input.prepared = Some(self.styled.prepared.clone());
        let params = band_params(&self.params);
        let output = motif_stylize::synthesize(&input, &params, &mut motif_core::NoProgress)?;
        Ok(RgbaImage::from_float(&output.image))
    }
}

impl TileSet {
    /// The textures of pyramid level `level` (≥ 1), made with the levels before it when first
    /// asked for. A level depends only on the one before, so its bytes do not depend on which
    /// tiles or threads asked first. It is made outside the lock: a thread making it may take up
    /// another tile's render while it waits for its own parallel work (rayon), which would then
    /// wait for that lock forever; two threads may make the same level once at the start, and
    /// the first one stored is kept (the same bytes).
    fn closer_textures(&self, level: usize) -> Result<Arc<[SegmentTexture]>, Error> {
        let lock = || self.closer.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let (mut made, mut coarser) = {
            let closer = lock();
            if let Some(textures) = closer.get(level - 1) {
                return Ok(textures.clone());
            }
            (closer.len(), closer.last().cloned())
        };
        loop {
            let textures = self.make_level(made + 1, coarser.as_deref().map_or(&self.styled.textures, |t| t))?;
            let kept = {
                let mut closer = lock();
                if closer.len() == made {
                    closer.push(textures.into());
                }
                closer[made].clone()
            };
            made += 1;
            if made == level {
                return Ok(kept);
            }
            coarser = Some(kept);
        }
    }

    /// Pyramid level `level` (≥ 1) from the level before it, `coarser`, in class order.
    fn make_level(&self, level: usize, coarser: &[SegmentTexture]) -> Result<Vec<SegmentTexture>, Error> {
        let side = self.params.texture_size << level;
        let input = PresynthInput {
            style: self.styled.style.to_float(),
            guide: self.styled.guide.to_float(),
            size: (side, side),
        };
        let stylize = presynth_params(&self.params);
        let mut textures = motif_stylize::presynthesize_closer(&input, coarser, &stylize, &mut motif_core::NoProgress)?;
        textures.sort_by_key(|texture| class_of(&texture.colour).index());
        Ok(textures)
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
        // The band starts at the textures' own matches: refine them locally, without the
        // occurrence penalty (made for whole images; a thin band has little to spread).
        .with_band_local_search(true)
        .with_final_figures(false)
        .with_uniformity(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::TileFrame;
    use crate::{MapBuilder, Shape, project, zoom_error};

    fn small_map() -> MapData {
        let mut map = MapBuilder::new();
        let at = |dx: f64, dy: f64| project(24.940 + dx, 60.172 - dy);
        map.add(
            MapClass::Forest,
            Shape::Area,
            vec![vec![at(0.0, 0.0), at(0.004, 0.0), at(0.004, 0.002), at(0.0, 0.002), at(0.0, 0.0)]],
        );
        map.add(MapClass::MajorRoad, Shape::Line(14.0), vec![vec![at(-0.001, 0.001), at(0.006, 0.0015)]]);
        map.add(
            MapClass::Water,
            Shape::Area,
            vec![vec![at(0.001, 0.0025), at(0.005, 0.0025), at(0.003, 0.004), at(0.001, 0.0025)]],
        );
        map.build()
    }

    fn legend() -> Legend {
        let stripes =
            RgbaImage::from_fn(12, 12, |x, y| if (x + y) % 6 < 3 { [30, 90, 30, 255] } else { [60, 140, 50, 255] });
        let ripples = RgbaImage::from_fn(10, 10, |x, y| [20, 60 + ((x * 7 + y * 3) % 10) as u8 * 8, 160, 255]);
        Legend::plain()
            .with(MapClass::Forest, crate::Fill::Texture(stripes))
            .with(MapClass::Water, crate::Fill::Texture(ripples))
    }

    fn tile_at(lon: f64, lat: f64, dx: u32) -> TileId {
        let [x, y] = project(lon, lat);
        TileId::new(17, (x * 131072.0) as u32 + dx, (y * 131072.0) as u32).unwrap()
    }

    #[test]
    fn a_tile_does_not_depend_on_the_tiles_before_it_nor_on_threads() {
        let params = Params::default().with_tile_size(64).with_texture_size(32).with_seed(4);
        let (a, b) = (tile_at(24.9415, 60.1712, 0), tile_at(24.9415, 60.1712, 1));
        let first = TileSet::new(small_map(), &legend(), &params, &mut motif_core::NoProgress).unwrap();
        let forward = [first.render(a, Layer::Stylized).unwrap(), first.render(b, Layer::Stylized).unwrap()];
        let second = TileSet::new(small_map(), &legend(), &params, &mut motif_core::NoProgress).unwrap();
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let backward =
            pool.install(|| [second.render(b, Layer::Stylized).unwrap(), second.render(a, Layer::Stylized).unwrap()]);
        assert_eq!(forward[0], backward[1]);
        assert_eq!(forward[1], backward[0]);
        // The stylized tile is not its plain segment map, and it uses the water texture's colours.
        let plain = first.render(a, Layer::Plain).unwrap();
        assert_ne!(plain, forward[0]);
        assert_eq!((plain.width(), plain.height()), (64, 64));
    }

    /// With a second texture level at the next zoom, that zoom's tiles keep the layout of the
    /// tile they zoom into; with one level for all zooms they do not (a texture laid at twice
    /// the scale has nothing to do with its first place).
    #[test]
    fn zooming_in_keeps_the_textures_layout_with_a_second_level() {
        let tile = tile_at(24.9415, 60.1712, 0);
        let params = Params::default().with_tile_size(64).with_texture_size(32).with_seed(6).with_base_zoom(tile.z);
        // Textures with a layout to keep: squares of 10 pixels, larger than a patch.
        let squares = |a: [u8; 4], b: [u8; 4]| {
            crate::Fill::Texture(RgbaImage::from_fn(40, 40, |x, y| if (x / 10 + y / 10) % 2 == 0 { a } else { b }))
        };
        let legend = Legend::plain()
            .with(MapClass::Forest, squares([30, 90, 30, 255], [90, 160, 70, 255]))
            .with(MapClass::Water, squares([20, 60, 160, 255], [80, 140, 220, 255]));
        let one =
            TileSet::new(small_map(), &legend, &params.clone().with_texture_levels(1), &mut motif_core::NoProgress)
                .unwrap();
        let two =
            TileSet::new(small_map(), &legend, &params.with_texture_levels(2), &mut motif_core::NoProgress).unwrap();
        let (parent, flat) = one.render_zooming_in(tile).unwrap();
        let (same_parent, pyramid) = two.render_zooming_in(tile).unwrap();
        // The base zoom's tiles are the same either way; only the next zoom differs.
        assert_eq!(parent, same_parent);
        // (0.0025 against 0.0475 at the tile's pixels when written.)
        for coarser in 0..2 {
            let (with, without) = (zoom_error(&parent, &pyramid, coarser), zoom_error(&parent, &flat, coarser));
            assert!(with < 0.25 * without, "zoom error {with:.4} with a second level, {without:.4} without");
        }
        // Zooms past the last level take the last; the levels are made once, in any order, now
        // or when a tile needs them.
        assert_eq!((two.params().texture_level(tile.z + 5), two.params().texture_level(0)), (1, 0));
        let eager = TileSet::new(small_map(), &legend, two.params(), &mut motif_core::NoProgress).unwrap();
        eager.make_texture_levels(crate::MAX_ZOOM).unwrap();
        let child = TileId::new(tile.z + 1, 2 * tile.x + 1, 2 * tile.y).unwrap();
        assert_eq!(eager.render(child, Layer::Stylized).unwrap(), two.render(child, Layer::Stylized).unwrap());
    }

    #[test]
    fn a_tile_set_made_from_shipped_textures_renders_the_same_bytes() {
        let params = Params::default().with_tile_size(64).with_texture_size(32).with_seed(5);
        let made = TileSet::new(small_map(), &legend(), &params, &mut motif_core::NoProgress).unwrap();
        let shipped = TileSet::with_textures(small_map(), &legend(), &params, made.textures().to_vec()).unwrap();
        assert!(made.report().presynthesized && !shipped.report().presynthesized);
        let tile = tile_at(24.9415, 60.1712, 0);
        assert_eq!(made.render(tile, Layer::Stylized).unwrap(), shipped.render(tile, Layer::Stylized).unwrap());
        // Textures of another size, or too few, are refused by name.
        let other = params.clone().with_texture_size(16);
        let error = TileSet::with_textures(small_map(), &legend(), &other, made.textures().to_vec()).unwrap_err();
        assert!(error.to_string().contains("textures") && error.to_string().contains("16×16"), "{error}");
        let error = TileSet::with_textures(small_map(), &legend(), &params, made.textures()[1..].to_vec()).unwrap_err();
        assert!(error.to_string().contains("7 given"), "{error}");
    }

    /// Pixels of `frame`'s aliased segment map that differ from `block`'s at the same place of
    /// the zoom level, as positions in the zoom level.
    fn guide_differences(set: &TileSet, frame: &TileFrame, block: &TileFrame) -> Vec<(i64, i64)> {
        let (a, b) = (guide_map(&set.map, frame, 1.0), guide_map(&set.map, block, 1.0));
        let ((ax, ay), (bx, by)) = (frame.global_origin(), block.global_origin());
        let mut out = Vec::new();
        for y in 0..a.height() {
            for x in 0..a.width() {
                let (gx, gy) = (ax + x as i64, ay + y as i64);
                let (u, v) = (gx - bx, gy - by);
                let inside = (0..b.width() as i64).contains(&u) && (0..b.height() as i64).contains(&v);
                if inside && a.get(x, y) != b.get(u as usize, v as usize) {
                    out.push((gx, gy));
                }
            }
        }
        out
    }

    #[test]
    fn tiles_apart_differ_from_the_block_rendered_whole_only_where_their_segment_maps_do() {
        // Copied pixels continue across tile borders (the textures lie in the zoom level's
        // coordinates), and the band's local search gives a band pixel the result it has in the
        // block rendered whole unless its segment map differs within the search's reach.
        // `tiny-skia` does not rasterize a shape translated by whole pixels quite alike (it
        // clips and strokes in floating point), so a few guide pixels differ; everything else
        // is the block's, to the byte.
        let params = Params::default().with_tile_size(64).with_texture_size(32).with_seed(2);
        let set = TileSet::new(small_map(), &legend(), &params, &mut motif_core::NoProgress).unwrap();
        let first = tile_at(24.9405, 60.17185, 0);
        let whole = set.render_block(first, 2, Layer::Stylized).unwrap();
        let plain = set.render_block(first, 2, Layer::Plain).unwrap();
        let block = set.frame(first, 2);
        let reach = params.resolved_margin() as i64;
        let (mut classes, mut differing) = (std::collections::BTreeSet::new(), 0);
        for (dx, dy) in [(0u32, 0u32), (1, 0), (0, 1), (1, 1)] {
            let id = TileId::new(first.z, first.x + dx, first.y + dy).unwrap();
            let tile = set.render(id, Layer::Stylized).unwrap();
            let guides = guide_differences(&set, &set.frame(id, 1), &block);
            let (ox, oy) = (i64::from(id.x) * 64, i64::from(id.y) * 64);
            for y in 0..64 {
                for x in 0..64 {
                    let (wx, wy) = (x + 64 * dx as usize, y + 64 * dy as usize);
                    classes.insert(plain.get(wx, wy));
                    if tile.get(x, y) == whole.get(wx, wy) {
                        continue;
                    }
                    differing += 1;
                    let (gx, gy) = (ox + x as i64, oy + y as i64);
                    let near = guides.iter().any(|&(u, v)| (u - gx).abs().max((v - gy).abs()) <= reach);
                    assert!(near, "tile {dx},{dy} at {x},{y}: differs with no guide difference within {reach} px");
                }
            }
        }
        assert!(differing <= 64 * 64 * 4 / 100, "{differing} pixels differ");
        // The block holds class edges, hence a band that was optimized.
        assert!(classes.len() >= 3, "{} colours", classes.len());
    }
}
