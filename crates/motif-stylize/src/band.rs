//! The band around segment edges and the bitmap composition of pre-synthesized textures (§3.7).
//!
//! A pixel is an edge pixel when one of its 4-neighbours has another label. The band holds every
//! pixel whose Euclidean distance to the nearest edge pixel is below T (exact distance transform
//! of Felzenszwalb and Huttenlocher); everything else is copied from its segment's texture. The
//! textures' fields are composed the same way, so every band pixel starts at the source patch
//! its texture pixel came from: next to the band's edge that is the true match, and propagation
//! carries it inwards from the first PatchMatch iteration.

use std::ops::Range;

use motif_core::FloatImage;

use crate::InputError;
use crate::{Error, NearestNeighbourField, SegmentTexture};

/// Pixels closer than `band` to a segment edge (none when `band` is 0 or there is one segment).
pub(crate) fn band_mask(labels: &[u16], width: usize, height: usize, band: usize) -> Vec<bool> {
    if band == 0 {
        return vec![false; width * height];
    }
    let edges: Vec<bool> = (0..width * height)
        .map(|index| {
            let (x, y) = (index % width, index / width);
            let label = labels[index];
            (x > 0 && labels[index - 1] != label)
                || (x + 1 < width && labels[index + 1] != label)
                || (y > 0 && labels[index - width] != label)
                || (y + 1 < height && labels[index + width] != label)
        })
        .collect();
    if band <= 3 {
        // Offsets of squared length below band² are exactly those within band − 1 on both axes
        // when band ≤ 3 ((band − 1)² · 2 < band², and an axis at band or more is too far): the
        // band is the edges dilated by a square, much cheaper than the transform.
        return crate::synthesis::dilate(&edges, width, height, band - 1);
    }
    let mut distance: Vec<f32> = edges.iter().map(|&edge| if edge { 0.0 } else { f32::INFINITY }).collect();
    squared_distance_transform(&mut distance, width, height);
    let limit = (band * band) as f32;
    distance.iter().map(|&d| d < limit).collect()
}

/// In-place 2-D squared Euclidean distance transform (columns, then rows).
fn squared_distance_transform(grid: &mut [f32], width: usize, height: usize) {
    let n = width.max(height);
    let (mut f, mut d) = (vec![0.0; n], vec![0.0; n]);
    let (mut v, mut z) = (vec![0usize; n], vec![0.0; n + 1]);
    for x in 0..width {
        for y in 0..height {
            f[y] = grid[y * width + x];
        }
        transform_1d(&f[..height], &mut d[..height], &mut v, &mut z);
        for y in 0..height {
            grid[y * width + x] = d[y];
        }
    }
    for y in 0..height {
        f[..width].copy_from_slice(&grid[y * width..(y + 1) * width]);
        transform_1d(&f[..width], &mut d[..width], &mut v, &mut z);
        grid[y * width..(y + 1) * width].copy_from_slice(&d[..width]);
    }
}

/// Lower envelope of parabolas: `d[q] = min_p (q − p)² + f[p]` in linear time.
fn transform_1d(f: &[f32], d: &mut [f32], v: &mut [usize], z: &mut [f32]) {
    let n = f.len();
    let finite: Vec<usize> = (0..n).filter(|&q| f[q].is_finite()).collect();
    if finite.is_empty() {
        d.fill(f32::INFINITY);
        return;
    }
    let mut k = 0;
    v[0] = finite[0];
    z[0] = f32::NEG_INFINITY;
    z[1] = f32::INFINITY;
    for &q in &finite[1..] {
        loop {
            let p = v[k];
            let s = ((f[q] + (q * q) as f32) - (f[p] + (p * p) as f32)) / (2.0 * (q as f32 - p as f32));
            // z[0] is -inf, so this never steps below the first parabola.
            if s <= z[k] {
                k -= 1;
                continue;
            }
            k += 1;
            v[k] = q;
            z[k] = s;
            z[k + 1] = f32::INFINITY;
            break;
        }
    }
    let mut k = 0;
    for (q, out) in d.iter_mut().enumerate() {
        while z[k + 1] < q as f32 {
            k += 1;
        }
        let p = v[k];
        *out = (q as f32 - p as f32).powi(2) + f[p];
    }
}

/// The output being composed: its size, and where its top-left lies in the textures' plane.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Target {
    pub size: (usize, usize),
    pub origin: (i64, i64),
}

impl Target {
    /// The pixel of a `width × height` texture that output pixel `(x, y)` takes: the textures
    /// tile the plane.
    #[cfg(test)]
    fn texture_pixel(&self, (x, y): (usize, usize), (width, height): (usize, usize)) -> (usize, usize) {
        (wrap(x, self.origin.0, width), wrap(y, self.origin.1, height))
    }

    /// Calls `piece(texture, texture_row, columns, out)` for every piece of output row `y`
    /// (labels `row_labels`) that one texture fills: a run of one label, split where its texture
    /// wraps. `texture` is `texture_of[label]`, `columns` the texture's columns and `out` the
    /// output's (as long). Textures of no size (`None` in `sizes`) are skipped.
    fn for_each_piece(
        &self,
        (y, row_labels): (usize, &[u16]),
        texture_of: &[usize],
        sizes: &[Option<(usize, usize)>],
        mut piece: impl FnMut(usize, usize, Range<usize>, Range<usize>),
    ) {
        let mut start = 0;
        while start < row_labels.len() {
            let label = row_labels[start];
            let end = start + row_labels[start..].iter().take_while(|&&l| l == label).count();
            let index = texture_of[usize::from(label)];
            if let Some((width, height)) = sizes[index] {
                let texture_row = wrap(y, self.origin.1, height);
                let (mut x, mut column) = (start, wrap(start, self.origin.0, width));
                while x < end {
                    let n = (end - x).min(width - column);
                    piece(index, texture_row, column..column + n, x..x + n);
                    (x, column) = (x + n, 0);
                }
            }
            start = end;
        }
    }
}

/// Output coordinate `v` shifted by `origin` in the plane, on a texture axis of `side` pixels.
fn wrap(v: usize, origin: i64, side: usize) -> usize {
    (v as i64 + origin).rem_euclid(side as i64) as usize
}

/// The target filled from the textures: pixel `(x, y)` of label `l` takes
/// `textures[texture_of[l]]` at its [`Target::texture_pixel`], a run of one label at a time.
pub(crate) fn compose(
    labels: &[u16],
    target: Target,
    textures: &[&FloatImage],
    texture_of: &[usize],
    channels: usize,
) -> FloatImage {
    let (width, height) = target.size;
    let sizes: Vec<Option<(usize, usize)>> = textures.iter().map(|t| Some((t.width(), t.height()))).collect();
    let mut out = FloatImage::new(width, height, channels);
    let rows = out.data_mut().chunks_exact_mut(width * channels).zip(labels.chunks_exact(width));
    for (y, (row, row_labels)) in rows.enumerate() {
        target.for_each_piece((y, row_labels), texture_of, &sizes, |index, texture_row, columns, out| {
            let texture = textures[index];
            let texture_row = &texture.data()[texture_row * texture.width() * channels..];
            let values = &texture_row[columns.start * channels..columns.end * channels];
            // An element loop, not `copy_from_slice`: most runs are short, and a `memcpy` call
            // costs more than copying them.
            for (out, &value) in row[out.start * channels..out.end * channels].iter_mut().zip(values) {
                *out = value;
            }
        });
    }
    out
}

/// Marks a target pixel with no starting match in [`compose_field`].
pub(crate) const NO_SEED: u32 = u32::MAX;

/// The textures' fields composed like [`compose`]: the source centre (`y · source_width + x`) that
/// the texture pixel of output pixel `(x, y)` came from, or [`NO_SEED`] where the texture has no
/// field. A match outside the `source_width × source_height` style is an error (checked for the
/// matches composed only: a tile reads a small part of its textures).
pub(crate) fn compose_field(
    labels: &[u16],
    target: Target,
    fields: &[Option<&crate::NearestNeighbourField>],
    texture_of: &[usize],
    (source_width, source_height): (usize, usize),
) -> Result<Vec<u32>, Error> {
    let (width, height) = target.size;
    let sizes: Vec<Option<(usize, usize)>> = fields.iter().map(|f| f.map(|f| (f.width, f.height))).collect();
    let mut out = vec![NO_SEED; width * height];
    let mut outside = None;
    let rows = out.chunks_exact_mut(width).zip(labels.chunks_exact(width));
    for (y, (row, row_labels)) in rows.enumerate() {
        target.for_each_piece((y, row_labels), texture_of, &sizes, |index, texture_row, columns, out| {
            let Some(field) = fields[index] else { return };
            let matches = &field.matches[texture_row * field.width..][columns];
            for (seed, texture_match) in row[out].iter_mut().zip(matches) {
                if let Some([sx, sy]) = *texture_match {
                    if sx as usize >= source_width || sy as usize >= source_height {
                        outside.get_or_insert(index);
                    }
                    *seed = sy.wrapping_mul(source_width as u32).wrapping_add(sx);
                }
            }
        });
        if let Some(index) = outside {
            return Err(Error::Input(InputError::TextureFieldOutside {
                texture: index + 1,
                style_width: source_width,
                style_height: source_height,
            }));
        }
    }
    Ok(out)
}

/// The composed target, the band, and (when the textures carry fields) the starting source centre
/// of every target pixel.
pub(crate) type Composition = (FloatImage, Vec<bool>, Option<Vec<u32>>);

/// Composes the target from the textures (and their fields), label `l` from texture `l` (the
/// labels are the textures' colours), and marks the band.
pub(crate) fn compose_textures(
    textures: &[SegmentTexture],
    labels: &[u16],
    (style_width, style_height, channels): (usize, usize, usize),
    target: Target,
    band_width: usize,
) -> Result<Composition, Error> {
    let (width, height) = target.size;
    if textures.is_empty() {
        return Err(Error::Input(InputError::NoTextures));
    }
    for (index, texture) in textures.iter().enumerate() {
        if texture.image.is_empty() {
            return Err(Error::Input(InputError::EmptyImage(format!("pre-synthesized texture {}", index + 1))));
        }
        if texture.image.channels() != channels {
            return Err(Error::Input(InputError::TextureChannels {
                texture: index + 1,
                channels: texture.image.channels(),
                style_channels: channels,
            }));
        }
        if let Some(field) = &texture.field {
            let (tw, th) = (texture.image.width(), texture.image.height());
            if field.width != tw || field.height != th || field.matches.len() != tw * th {
                return Err(Error::Input(InputError::TextureFieldSize {
                    texture: index + 1,
                    field_width: field.width,
                    field_height: field.height,
                    width: tw,
                    height: th,
                }));
            }
            if field.source_width != style_width || field.source_height != style_height {
                return Err(Error::Input(InputError::TextureFieldSource {
                    texture: index + 1,
                    source_width: field.source_width,
                    source_height: field.source_height,
                    style_width,
                    style_height,
                }));
            }
        }
    }
    // The labels were made from the textures' colours ([`crate::label_by_colours`]): label `l` is
    // texture `l`.
    let texture_of: Vec<usize> = (0..textures.len()).collect();
    let images: Vec<&FloatImage> = textures.iter().map(|t| &t.image).collect();
    let composed = compose(labels, target, &images, &texture_of, channels);
    let domain = band_mask(labels, width, height, band_width);
    let fields: Vec<Option<&NearestNeighbourField>> = textures.iter().map(|t| t.field.as_ref()).collect();
    let seeds = match fields.iter().any(Option::is_some) {
        true => Some(compose_field(labels, target, &fields, &texture_of, (style_width, style_height))?),
        false => None,
    };
    Ok((composed, domain, seeds))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_transform_matches_brute_force() {
        let (w, h) = (23, 17);
        let seeds = [(3usize, 4usize), (20, 2), (11, 15), (12, 8)];
        let mut grid: Vec<f32> =
            (0..w * h).map(|i| if seeds.contains(&(i % w, i / w)) { 0.0 } else { f32::INFINITY }).collect();
        squared_distance_transform(&mut grid, w, h);
        for y in 0..h {
            for x in 0..w {
                let best = seeds
                    .iter()
                    .map(|&(sx, sy)| (x as f32 - sx as f32).powi(2) + (y as f32 - sy as f32).powi(2))
                    .fold(f32::INFINITY, f32::min);
                assert_eq!(grid[y * w + x], best, "at {x},{y}");
            }
        }
    }

    #[test]
    fn composed_field_takes_each_segment_textures_match_where_it_tiles() {
        let field = |offset: u32| crate::NearestNeighbourField {
            width: 2,
            height: 2,
            source_width: 10,
            source_height: 10,
            patch_size: 3,
            matches: vec![Some([offset + 1, 1]), Some([offset + 2, 1]), None, Some([offset + 2, 2])],
            weights: None,
        };
        let (first, second) = (field(0), field(5));
        let labels: Vec<u16> = vec![0, 0, 1, 1, 1, 0];
        // Label 0 takes texture 1, label 1 texture 0.
        let target = Target { size: (3, 2), origin: (0, 0) };
        let out = compose_field(&labels, target, &[Some(&first), Some(&second)], &[1, 0], (10, 10)).unwrap();
        // (0,0) label 0 → second at (0,0) = [6,1]; (2,0) label 1 → first at (0,0) = [1,1];
        // (0,1) label 1 → first at (0,1) = none; (2,1) label 0 → second at (0,1) = none.
        assert_eq!(out, vec![16, 17, 11, NO_SEED, 22, NO_SEED]);
        assert_eq!(
            compose_field(&labels, target, &[None, Some(&second)], &[0, 0], (10, 10)).unwrap(),
            vec![NO_SEED; 6]
        );
        // Shifted by one column in the plane: (0,0) takes texture pixel (1,0), (1,0) pixel (0,0).
        let shifted = Target { size: (3, 2), origin: (-1, 0) };
        let out = compose_field(&labels, shifted, &[Some(&first), Some(&second)], &[1, 0], (10, 10)).unwrap();
        assert_eq!(out[..2], [17, 16]);
    }

    /// The band by its definition (distance to the nearest edge pixel below T), on a map of
    /// irregular segments, for the narrow bands (a dilation) and the wider ones (the transform).
    #[test]
    fn band_matches_its_definition() {
        let (w, h) = (31, 23);
        let labels: Vec<u16> = (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as i64, (i / w) as i64);
                u16::from((x - 12).pow(2) + (y - 9).pow(2) < 40) + 2 * u16::from(x + 2 * y > 50)
            })
            .collect();
        let edge = |i: usize| {
            let (x, y) = (i % w, i / w);
            (x > 0 && labels[i - 1] != labels[i])
                || (x + 1 < w && labels[i + 1] != labels[i])
                || (y > 0 && labels[i - w] != labels[i])
                || (y + 1 < h && labels[i + w] != labels[i])
        };
        for t in 1..=6_usize {
            let expected: Vec<bool> = (0..w * h)
                .map(|i| {
                    let (x, y) = ((i % w) as i64, (i / w) as i64);
                    (0..w * h).filter(|&j| edge(j)).any(|j| {
                        let (u, v) = ((j % w) as i64, (j / w) as i64);
                        (u - x).pow(2) + (v - y).pow(2) < (t * t) as i64
                    })
                })
                .collect();
            assert_eq!(band_mask(&labels, w, h, t), expected, "T = {t}");
        }
    }

    /// Composition gives every pixel its texture pixel, and the composed field its texture
    /// pixel's match, for runs of one label longer than a texture row and origins on both sides
    /// of the plane's zero.
    #[test]
    fn composition_takes_each_pixel_from_its_texture_pixel() {
        let texture = |w: usize, h: usize, base: f32| {
            let data = (0..w * h * 2).map(|i| base + i as f32).collect();
            FloatImage::from_data(w, h, 2, data).expect("sizes match")
        };
        // Each texture's field: every third pixel unmatched, the others matched by their index.
        let field = |w: usize, h: usize| crate::NearestNeighbourField {
            width: w,
            height: h,
            source_width: 40,
            source_height: 40,
            patch_size: 3,
            matches: (0..w * h).map(|i| (i % 3 != 0).then_some([i as u32 % 40, i as u32 / 2])).collect(),
            weights: None,
        };
        let (a, b) = (texture(3, 2, 0.0), texture(5, 3, 100.0));
        let fields = [field(3, 2), field(5, 3)];
        let (width, height) = (17, 4);
        let labels: Vec<u16> = (0..width * height).map(|i| u16::from((i % width) / 6 == 1 || i / width == 2)).collect();
        for origin in [(0, 0), (-7, 3), (11, -5)] {
            let target = Target { size: (width, height), origin };
            let out = compose(&labels, target, &[&a, &b], &[0, 1], 2);
            let seeds =
                compose_field(&labels, target, &[Some(&fields[0]), Some(&fields[1])], &[0, 1], (40, 40)).unwrap();
            for y in 0..height {
                for x in 0..width {
                    let label = usize::from(labels[y * width + x]);
                    let (texture, field) = ([&a, &b][label], &fields[label]);
                    let (tx, ty) = target.texture_pixel((x, y), (texture.width(), texture.height()));
                    assert_eq!(out.pixel(x, y), texture.pixel(tx, ty), "({x}, {y}) at {origin:?}");
                    let seed = field.matches[ty * field.width + tx].map_or(NO_SEED, |[sx, sy]| sy * 40 + sx);
                    assert_eq!(seeds[y * width + x], seed, "({x}, {y}) at {origin:?}");
                }
            }
        }
    }

    #[test]
    fn band_widens_with_t_and_is_empty_at_zero() {
        let (w, h) = (20, 10);
        let labels: Vec<u16> = (0..w * h).map(|i| u16::from(i % w >= 10)).collect();
        let count = |t| band_mask(&labels, w, h, t).iter().filter(|&&b| b).count();
        assert_eq!(count(0), 0);
        assert_eq!(count(1), 2 * h);
        assert_eq!(count(3), 6 * h);
        assert!(band_mask(&vec![0; w * h], w, h, 5).iter().all(|&b| !b));
    }
}
