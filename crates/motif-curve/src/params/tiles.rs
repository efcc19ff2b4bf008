//! The checks of the start, end and corner tiles (module `brush`), against the inputs.

use motif_core::InvalidParameter;

use crate::{Input, Params};

/// Checks the start, end and corner tiles: columns inside the first exemplar, and room left on
/// the curve for the end tiles and at least one piece between them (a corner tile that leaves no
/// room is not placed).
pub(super) fn check_tiles(input: &Input<'_>, params: &Params, length: f64) -> Result<(), InvalidParameter> {
    let mut used = 0.0;
    let tiles = [("start-tile", params.start_tile), ("end-tile", params.end_tile), ("corner-tile", params.corner_tile)];
    let mut lengths = [None; 3];
    for (k, ((name, columns), source)) in tiles.into_iter().zip(params.tile_exemplars).enumerate() {
        lengths[k] = match (source, columns) {
            (Some(source), _) => Some(check_tile_exemplar(input, params, name, source)?),
            (None, Some(columns)) => Some(check_tile_columns(input, params, name, columns)?),
            (None, None) => None,
        };
    }
    used += lengths[0].unwrap_or(0.0) + lengths[1].unwrap_or(0.0);
    if let Some(corner) = lengths[2]
        && corner + params.piece_length > length
    {
        return Err(InvalidParameter::new(
            "corner-tile",
            format!("{corner:.1} px"),
            format!("a corner tile and one piece must fit on the curve ({length:.1} px)"),
        ));
    }
    if used > 0.0 && used + params.piece_length > length {
        return Err(InvalidParameter::new(
            if lengths[0].is_some() { "start-tile" } else { "end-tile" },
            format!("{used:.1} px of tiles"),
            format!("the tiles and one piece must fit on the curve ({length:.1} px)"),
        ));
    }
    Ok(())
}

/// Checks a tile drawn from exemplar `source` (one of the more exemplars, with a pattern). Returns
/// the tile's length along the curve.
fn check_tile_exemplar(input: &Input<'_>, params: &Params, name: &str, source: usize) -> Result<f64, InvalidParameter> {
    let Some(image) = source.checked_sub(1).and_then(|k| input.more_exemplars.get(k)) else {
        return Err(InvalidParameter::new(
            format!("{name}-image"),
            format!("exemplar {source}"),
            format!(
                "must be one of the {} more exemplars (1 to {})",
                input.more_exemplars.len(),
                input.more_exemplars.len()
            ),
        ));
    };
    let (first, last) = crate::exemplar::pattern_extent(image, 0, image.width(), params.cut_alpha);
    if last < first + 1 {
        return Err(InvalidParameter::new(
            format!("{name}-image"),
            format!("{}×{}", image.width(), image.height()),
            "must hold a pattern at least 2 columns wide",
        ));
    }
    Ok(f64::from(last - first) / params.scale)
}

/// Checks a tile's columns `[x0, x1)`: inside the first exemplar and over its pattern. Returns the
/// tile's length along the curve.
fn check_tile_columns(
    input: &Input<'_>,
    params: &Params,
    name: &str,
    [x0, x1]: [u32; 2],
) -> Result<f64, InvalidParameter> {
    let width = input.exemplar.width();
    if x0 + 2 > x1 || x1 as usize > width {
        return Err(InvalidParameter::new(
            name,
            format!("{x0},{x1}"),
            format!("must be columns X0,X1 of the first exemplar with X0 + 2 ≤ X1 ≤ {width}"),
        ));
    }
    let (first, last) = crate::exemplar::pattern_extent(input.exemplar, 0, width, params.cut_alpha);
    if x0.max(first as u32) + 2 > x1.min(last as u32 + 1) {
        return Err(InvalidParameter::new(
            name,
            format!("{x0},{x1}"),
            format!("must cover the pattern, which spans columns {first} to {last} of the first exemplar"),
        ));
    }
    Ok(f64::from(x1 - x0 - 1) / params.scale)
}
