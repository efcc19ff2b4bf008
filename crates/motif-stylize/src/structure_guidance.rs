//! Automatic structure guidance for texture synthesis, after Kaspar et al. 2015 ("Self Tuning
//! Texture Optimization", §4.2): a feature mask of the exemplar, the distance of every pixel to
//! the nearest feature as an extra channel synthesized along with the colours, weighted most at
//! the coarsest level and not at all at the finest.
//!
//! Patches then match where they sit inside a structure element (a brick's centre, its border, a
//! mortar line), not only what colours they hold, so the coarse levels lay out whole elements
//! and continuous gaps between them; the fine levels keep the colour detail.

use motif_core::{ChannelImage, FloatImage, Progress};

use crate::{Error, Output, Params, synthesis};

/// Texture synthesis of `target_size` with the exemplar's feature distance as one more style
/// channel (weighted `params.structure_weight` times a colour channel at the coarsest level, 0
/// at the finest); the output keeps the exemplar's channels.
pub(crate) fn synthesize_with_structure(
    style: &impl ChannelImage,
    style_weights: &[f32],
    target_size: (usize, usize),
    params: &Params,
    progress: &mut dyn Progress,
) -> Result<Output, Error> {
    let colours = style.to_float_image();
    let distance = feature_distance(&colours);
    let augmented = FloatImage::stack(&[&colours, &distance]).expect("the distance has the style's size");
    let colour_weight = style_weights.first().copied().unwrap_or(1.0);
    let mut weights = style_weights.to_vec();
    weights.push(0.0);
    let problem = synthesis::Problem {
        style: &augmented,
        source_guides: Vec::new(),
        target_guides: Vec::new(),
        style_weights: weights,
        guide_weights: Vec::new(),
        target_size,
        labels: None,
        tileable: params.tileable,
        composition: None,
        seeds: None,
        origin: (0, 0),
        mask: None,
        structure_weight: Some(params.structure_weight * colour_weight),
        prepared: None,
    };
    let mut output = synthesis::run(problem, params, progress)?;
    let channels = colours.channels();
    let image = &output.image;
    let data = image.data().chunks_exact(channels + 1).flat_map(|pixel| pixel[..channels].iter().copied()).collect();
    output.image = FloatImage::from_data(image.width(), image.height(), channels, data).expect("same pixels");
    Ok(output)
}

/// The exemplar's distance-to-feature channel, values in `[0, 1]`.
///
/// Features are the minority class of a two-class (Otsu) split of the blurred luminance: the
/// mortar, gaps or grooves that separate the elements of a regular texture. Each pixel holds its
/// Euclidean distance to the nearest feature pixel over the largest such distance (0 on
/// features, 1 at the centre of the widest element). A flat exemplar (one class) gives zeros.
pub(crate) fn feature_distance(style: &FloatImage) -> FloatImage {
    let (width, height) = (style.width(), style.height());
    let feature = feature_mask(style);
    let mut out = FloatImage::new(width, height, 1);
    if feature.iter().all(|&f| f) || !feature.iter().any(|&f| f) {
        return out;
    }
    let squared = squared_distance_transform(&feature, width, height);
    let largest = squared.iter().copied().fold(0.0_f64, f64::max).sqrt();
    for (value, &d) in out.data_mut().iter_mut().zip(&squared) {
        *value = (d.sqrt() / largest) as f32;
    }
    out
}

/// The mean distance, in pixels, from the pixels off the image's features to the nearest feature
/// (features: the darker or smaller class of a two-class split of the blurred luminance): about
/// half the width of the elements between the gaps.
/// Elements cut by stray gaps lower it; a figure of structure next to the patch distance. 0 for a
/// flat image.
pub fn mean_feature_distance(image: &FloatImage) -> f64 {
    let (width, height) = (image.width(), image.height());
    let feature = feature_mask(image);
    if feature.iter().all(|&f| f) || !feature.iter().any(|&f| f) {
        return 0.0;
    }
    let squared = squared_distance_transform(&feature, width, height);
    let off: Vec<f64> = squared.iter().zip(&feature).filter(|(_, f)| !**f).map(|(d, _)| d.sqrt()).collect();
    off.iter().sum::<f64>() / off.len() as f64
}

/// How straight and continuous the image's rows and columns of structure are: the standard
/// deviation of the mean luminance of each row (`[0]`) and of each column (`[1]`). A wall whose
/// mortar runs straight across has dark rows and light ones; courses that break or wave average
/// out. Compare with the exemplar's (an output wider than the exemplar averages more pixels per
/// row, so straight courses keep the exemplar's figure and broken ones fall below it).
pub fn line_contrast(image: &FloatImage) -> [f64; 2] {
    let (width, height) = (image.width(), image.height());
    let luminance = luminance(image);
    let deviation = |means: &[f64]| {
        let mean = means.iter().sum::<f64>() / means.len() as f64;
        (means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / means.len() as f64).sqrt()
    };
    let rows: Vec<f64> = (0..height)
        .map(|y| luminance[y * width..(y + 1) * width].iter().map(|&v| f64::from(v)).sum::<f64>() / width as f64)
        .collect();
    let columns: Vec<f64> = (0..width)
        .map(|x| (0..height).map(|y| f64::from(luminance[y * width + x])).sum::<f64>() / height as f64)
        .collect();
    [deviation(&rows), deviation(&columns)]
}

/// The minority class of the two-class (Otsu) split of the blurred luminance.
fn feature_mask(image: &FloatImage) -> Vec<bool> {
    let luminance = luminance(&image.blur());
    let threshold = otsu_threshold(&luminance);
    let below = luminance.iter().filter(|&&v| v <= threshold).count();
    // The class with fewer pixels is the feature (ties: the darker one, as mortar usually is).
    let features_are_dark = below <= luminance.len() - below;
    luminance.iter().map(|&v| if features_are_dark { v <= threshold } else { v > threshold }).collect()
}

/// Rec. 601 luma of each pixel (the value itself for one channel; alpha ignored).
fn luminance(image: &FloatImage) -> Vec<f32> {
    image
        .data()
        .chunks_exact(image.channels())
        .map(|p| if p.len() < 3 { p[0] } else { 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2] })
        .collect()
}

/// Otsu's threshold over a 256-bin histogram: the value that maximizes the between-class
/// variance of the two classes `≤ t` and `> t`.
fn otsu_threshold(values: &[f32]) -> f32 {
    let mut histogram = [0_usize; 256];
    for &v in values {
        histogram[(v.clamp(0.0, 1.0) * 255.0).round() as usize] += 1;
    }
    let total = values.len() as f64;
    let sum_all: f64 = histogram.iter().enumerate().map(|(i, &n)| i as f64 * n as f64).sum();
    let (mut below, mut sum_below) = (0.0, 0.0);
    let (mut best, mut best_bin) = (-1.0, 0);
    for (bin, &count) in histogram.iter().enumerate() {
        below += count as f64;
        sum_below += bin as f64 * count as f64;
        let above = total - below;
        if below == 0.0 || above == 0.0 {
            continue;
        }
        let difference = sum_below / below - (sum_all - sum_below) / above;
        let between = below * above * difference * difference;
        if between > best {
            (best, best_bin) = (between, bin);
        }
    }
    best_bin as f32 / 255.0
}

/// Squared Euclidean distance of every pixel to the nearest `true` one (Felzenszwalb and
/// Huttenlocher's separable transform: exact, linear in the pixels). At least one pixel is `true`.
fn squared_distance_transform(feature: &[bool], width: usize, height: usize) -> Vec<f64> {
    let far = ((width + height) * (width + height)) as f64;
    let mut grid: Vec<f64> = feature.iter().map(|&f| if f { 0.0 } else { far }).collect();
    let mut column = vec![0.0; height];
    let mut transformed = vec![0.0; width.max(height)];
    for x in 0..width {
        for y in 0..height {
            column[y] = grid[y * width + x];
        }
        lower_envelope(&column, &mut transformed[..height]);
        for y in 0..height {
            grid[y * width + x] = transformed[y];
        }
    }
    for y in 0..height {
        let row = grid[y * width..(y + 1) * width].to_vec();
        lower_envelope(&row, &mut transformed[..width]);
        grid[y * width..(y + 1) * width].copy_from_slice(&transformed[..width]);
    }
    grid
}

/// The 1D transform: `out[q] = min_p (q − p)² + f[p]`, by the lower envelope of the parabolas.
fn lower_envelope(f: &[f64], out: &mut [f64]) {
    let n = f.len();
    let mut vertices = vec![0_usize; n];
    let mut boundaries = vec![0.0_f64; n + 1];
    let mut k = 0;
    boundaries[0] = f64::NEG_INFINITY;
    boundaries[1] = f64::INFINITY;
    let intersection =
        |p: usize, q: usize| ((f[q] + (q * q) as f64) - (f[p] + (p * p) as f64)) / (2.0 * q as f64 - 2.0 * p as f64);
    for q in 1..n {
        let mut s = intersection(vertices[k], q);
        while s <= boundaries[k] {
            k -= 1;
            s = intersection(vertices[k], q);
        }
        k += 1;
        vertices[k] = q;
        boundaries[k] = s;
        boundaries[k + 1] = f64::INFINITY;
    }
    k = 0;
    for (q, value) in out.iter_mut().enumerate() {
        while boundaries[k + 1] < q as f64 {
            k += 1;
        }
        let p = vertices[k];
        *value = (q as f64 - p as f64).powi(2) + f[p];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The brute-force transform on a small irregular mask.
    #[test]
    fn distance_transform_equals_brute_force() {
        let (width, height) = (13, 9);
        let feature: Vec<bool> = (0..width * height).map(|i| (i * 7 + i / 5) % 11 == 0).collect();
        let fast = squared_distance_transform(&feature, width, height);
        for y in 0..height {
            for x in 0..width {
                let mut best = f64::INFINITY;
                for (j, &f) in feature.iter().enumerate() {
                    if f {
                        let (fx, fy) = ((j % width) as f64, (j / width) as f64);
                        best = best.min((fx - x as f64).powi(2) + (fy - y as f64).powi(2));
                    }
                }
                assert_eq!(fast[y * width + x], best, "({x}, {y})");
            }
        }
    }

    /// Light blocks in courses, separated by dark mortar two pixels wide.
    fn bricks(width: usize, height: usize) -> FloatImage {
        let mut image = FloatImage::new(width, height, 3);
        for y in 0..height {
            for x in 0..width {
                let offset = if (y / 12) % 2 == 0 { 0 } else { 10 };
                let mortar = y % 12 < 2 || (x + offset) % 20 < 2;
                let shade = if mortar { 0.15 } else { 0.6 + 0.2 * ((x * 3 + y * 5) % 7) as f32 / 7.0 };
                image.pixel_mut(x, y).copy_from_slice(&[shade, shade * 0.8, shade * 0.6]);
            }
        }
        image
    }

    /// The mortar is the feature (distance 0), block centres are farthest from it, and the split
    /// ignores the blocks' own shading.
    #[test]
    fn mortar_is_the_feature_and_brick_centres_the_farthest() {
        let image = bricks(40, 26);
        let distance = feature_distance(&image);
        let at = |x: usize, y: usize| distance.pixel(x, y)[0];
        assert_eq!(at(20, 12), 0.0);
        assert!(at(10, 6) > 0.8 && at(20, 18) > 0.8, "{} {}", at(10, 6), at(20, 18));
        assert!(at(10, 6) > at(10, 9) && at(10, 9) > at(10, 11));
        assert!(distance.data().iter().all(|v| (0.0..=1.0).contains(v)));
        assert!(feature_distance(&FloatImage::new(8, 8, 3)).data().iter().all(|&v| v == 0.0));
    }

    #[test]
    fn structure_guided_textures_keep_their_channels_and_refuse_guides() {
        use crate::{Guide, Input, synthesize};
        use motif_core::NoProgress;
        let exemplar = bricks(40, 26);
        let params = Params::default().with_structure_weight(3.0).with_seed(2);
        let input = Input::texture(exemplar.clone(), 60, 50);
        let first = synthesize(&input, &params, &mut NoProgress).unwrap();
        assert_eq!((first.image.width(), first.image.height(), first.image.channels()), (60, 50, 3));
        assert!(first.report.levels.len() >= 2);
        assert_eq!(synthesize(&input, &params, &mut NoProgress).unwrap().image, first.image);
        let guide = Guide { source: exemplar.clone(), target: exemplar.clone(), weight: None };
        let guided = Input::guided(exemplar, vec![guide]);
        let message = synthesize(&guided, &params, &mut NoProgress).unwrap_err().to_string();
        assert!(message.contains("structure-weight") && message.contains("texture synthesis only"), "{message}");
    }
}
