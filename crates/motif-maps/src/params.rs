//! Every tunable of a tile set, with its default.

use motif_core::InvalidParameter;
use motif_core::error::check_count;

use crate::Error;

/// The tunables of a [`TileSet`](crate::TileSet). Defaults are [`Params::DEFAULT`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Params {
    /// Side of a tile in pixels. Range 64..=1024, default 256 (slippy maps' size).
    pub tile_size: usize,
    /// Pixels drawn and stylized around every tile and cut off, so that the band's patches at the
    /// tile's edge see the same guide as its neighbour's. 0 = inferred: the band plus the patch
    /// size ([`Params::resolved_margin`]). Range 0..=256, default 0.
    pub margin: usize,
    /// Band half-width T in pixels (§3.7): pixels farther than this from a class edge are copied
    /// from the class's pre-synthesized texture, the band between is optimized. 0 = pure
    /// composition. Range 0..=64, default 2.
    pub band: usize,
    /// Side of every pre-synthesized texture in pixels (they tile: larger repeats less often).
    /// Range 16..=1024, default 128.
    pub texture_size: usize,
    /// Patch side of the presynthesis and of the band's optimization, odd. Range 3..=15,
    /// default 5.
    pub patch_size: usize,
    /// Search-vote iterations of the band (it starts from the textures' own matches). Range
    /// 1..=20, default 1.
    pub band_iterations: usize,
    /// PatchMatch iterations per search of the band. Range 1..=20, default 1.
    pub band_patchmatch_iterations: usize,
    /// Narrowest line drawn, in pixels, so that small roads stay visible at low zooms. Range
    /// 0.25..=16, default 1.
    pub min_line_width: f32,
    /// Levels of the texture pyramid: the pre-synthesized textures serve zoom [`Params::base_zoom`]
    /// and below; each further level, twice the side of the one before and guided by it
    /// magnified (`motif_stylize::presynthesize_closer`), serves the next zoom, so that zooming in
    /// keeps the textures' layout; zooms past the last level take the last. Made when a tile
    /// first needs them. 1 = the same textures at every zoom. Range 1..=4, default 2.
    pub texture_levels: usize,
    /// The zoom level of the first textures (see [`Params::texture_levels`]). Range
    /// 0..=[`MAX_ZOOM`](crate::MAX_ZOOM), default 15.
    pub base_zoom: u8,
    /// Seed of every random choice (presynthesis and band). Default 0.
    pub seed: u64,
}

impl Default for Params {
    fn default() -> Self {
        Self::DEFAULT
    }
}

motif_core::builders! { Params {
    with_tile_size => tile_size: usize,
    with_margin => margin: usize,
    with_band => band: usize,
    with_texture_size => texture_size: usize,
    with_patch_size => patch_size: usize,
    with_band_iterations => band_iterations: usize,
    with_band_patchmatch_iterations => band_patchmatch_iterations: usize,
    with_min_line_width => min_line_width: f32,
    with_texture_levels => texture_levels: usize,
    with_base_zoom => base_zoom: u8,
    with_seed => seed: u64,
}}

impl Params {
    /// The defaults, as a constant: front ends declare their options' defaults from it.
    pub const DEFAULT: Self = Self {
        tile_size: 256,
        margin: 0,
        band: 2,
        texture_size: 128,
        patch_size: 5,
        band_iterations: 1,
        band_patchmatch_iterations: 1,
        min_line_width: 1.0,
        texture_levels: 2,
        base_zoom: 15,
        seed: 0,
    };

    /// Checks every field's range; the first bad one is the error.
    pub fn validate(&self) -> Result<(), Error> {
        check_count("tile-size", self.tile_size, 64, 1024)?;
        check_count("margin", self.margin, 0, 256)?;
        check_count("band", self.band, 0, 64)?;
        check_count("texture-size", self.texture_size, 16, 1024)?;
        check_count("patch-size", self.patch_size, 3, 15)?;
        if self.patch_size.is_multiple_of(2) {
            return Err(InvalidParameter::new("patch-size", self.patch_size, "must be odd, between 3 and 15").into());
        }
        check_count("band-iterations", self.band_iterations, 1, 20)?;
        check_count("band-patchmatch-iterations", self.band_patchmatch_iterations, 1, 20)?;
        motif_core::error::check_range("min-line-width", f64::from(self.min_line_width), 0.25, 16.0)?;
        check_count("texture-levels", self.texture_levels, 1, 4)?;
        check_count("base-zoom", usize::from(self.base_zoom), 0, usize::from(crate::MAX_ZOOM))?;
        // The last level's textures, 2^(levels − 1) times the first's side.
        let last_side = self.texture_size << (self.texture_levels - 1);
        if last_side > 2048 {
            let allowed = format!(
                "at most {} with --texture-size {}: the last level's textures would be {last_side} pixels a side, over 2048",
                1 + (2048 / self.texture_size).ilog2(),
                self.texture_size
            );
            return Err(InvalidParameter::new("texture-levels", self.texture_levels, allowed).into());
        }
        Ok(())
    }

    /// The texture pyramid's level for tiles of zoom `zoom` (0: the pre-synthesized textures).
    pub fn texture_level(&self, zoom: u8) -> usize {
        usize::from(zoom.saturating_sub(self.base_zoom)).min(self.texture_levels - 1)
    }

    /// The margin drawn around each tile: the given one, or the band plus the patch size, the reach
    /// of a band pixel's result (the band, two patch radii and one pixel of propagation).
    pub fn resolved_margin(&self) -> usize {
        if self.margin > 0 { self.margin } else { self.band + self.patch_size }
    }
}
