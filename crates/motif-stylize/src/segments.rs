//! Segment labels from guide colours (§3.6): an exact palette for flat map renders, or k-means
//! quantization for anti-aliased guides. Labels are shared by source and target, so "the same
//! segment" means "the same guide colour (cluster)" on both sides.

use std::collections::BTreeMap;

use motif_core::random::Rng;
use motif_core::{FloatImage, SeedStreams};

use crate::{Error, Segmentation};

/// Most distinct colours the exact palette accepts; beyond it, k-means is the tool.
pub const MAX_PALETTE: usize = 64;

/// Segment labels of the source and target segment guides.
#[derive(Debug, Clone, PartialEq)]
pub struct SegmentLabels {
    /// Guide colour of each label (values in `[0, 1]`, the guide's channels).
    pub colours: Vec<Vec<f32>>,
    /// Label of every source pixel, row-major.
    pub source: Vec<u16>,
    /// Label of every target pixel, row-major.
    pub target: Vec<u16>,
}

/// Quantized colour key: 8 bits per channel, up to 4 channels.
fn key(pixel: &[f32]) -> [u8; 4] {
    let mut key = [0; 4];
    for (slot, value) in key.iter_mut().zip(pixel) {
        // Rounds half up like `round` on these non-negative values, without the libm call.
        *slot = (value.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    }
    key
}

/// Labels both guides' colours with `mode`; `seed` drives k-means initialization.
pub fn label_guides(
    source: &FloatImage,
    target: &FloatImage,
    mode: Segmentation,
    seed: u64,
) -> Result<SegmentLabels, Error> {
    let channels = source.channels();
    let mut histogram: BTreeMap<[u8; 4], usize> = BTreeMap::new();
    for image in [source, target] {
        // Guides are mostly flat runs of one colour: count runs, not pixels, into the map.
        let mut run: Option<([u8; 4], usize)> = None;
        for pixel in image.data().chunks_exact(channels) {
            let key = key(pixel);
            match &mut run {
                Some((current, count)) if *current == key => *count += 1,
                _ => {
                    if let Some((current, count)) = run.replace((key, 1)) {
                        *histogram.entry(current).or_default() += count;
                    }
                }
            }
        }
        if let Some((current, count)) = run {
            *histogram.entry(current).or_default() += count;
        }
    }
    let unique: Vec<([u8; 4], usize)> = histogram.into_iter().collect();
    let colours: Vec<Vec<f32>> = match mode {
        Segmentation::Palette => {
            if unique.len() > MAX_PALETTE {
                return Err(Error::TooManyColours { colours: unique.len(), max: MAX_PALETTE });
            }
            unique.iter().map(|(key, _)| key[..channels].iter().map(|&v| f32::from(v) / 255.0).collect()).collect()
        }
        Segmentation::KMeans(k) => kmeans(&unique, channels, k, seed),
    };
    Ok(label_by_colours(source, target, colours))
}

/// Labels every pixel of both guides with its nearest colour of `colours` (squared distance in
/// the guides' channels): the segments of a pre-synthesized cache, whose colours were fixed when
/// it was made, for guides whose anti-aliased or compressed edges hold colours of their own.
pub fn label_by_colours(source: &FloatImage, target: &FloatImage, colours: Vec<Vec<f32>>) -> SegmentLabels {
    let channels = source.channels();
    let label_of = |pixel: &[f32]| -> u16 {
        let mut best = (f32::INFINITY, 0);
        for (label, colour) in colours.iter().enumerate() {
            let d: f32 = colour.iter().zip(pixel).map(|(a, b)| (a - b) * (a - b)).sum();
            if d < best.0 {
                best = (d, label);
            }
        }
        best.1 as u16
    };
    let label_image = |image: &FloatImage| {
        // Runs of one colour share the label of their first pixel.
        let mut previous: Option<(&[f32], u16)> = None;
        image
            .data()
            .chunks_exact(channels)
            .map(|pixel| match previous {
                Some((colour, label)) if colour == pixel => label,
                _ => {
                    let label = label_of(pixel);
                    previous = Some((pixel, label));
                    label
                }
            })
            .collect()
    };
    SegmentLabels { source: label_image(source), target: label_image(target), colours }
}

/// Weighted k-means over the distinct colours (k-means++ seeding from one seeded stream, then
/// Lloyd iterations until stable); empty clusters are dropped.
fn kmeans(unique: &[([u8; 4], usize)], channels: usize, k: usize, seed: u64) -> Vec<Vec<f32>> {
    let points: Vec<Vec<f32>> =
        unique.iter().map(|(key, _)| key[..channels].iter().map(|&v| f32::from(v) / 255.0).collect()).collect();
    let weights: Vec<f64> = unique.iter().map(|&(_, count)| count as f64).collect();
    let distance = |a: &[f32], b: &[f32]| -> f64 { a.iter().zip(b).map(|(x, y)| f64::from((x - y) * (x - y))).sum() };
    if points.len() <= k {
        return points;
    }
    let mut stream = SeedStreams::new(seed).stream("kmeans", 0);
    let mut centres: Vec<Vec<f32>> = Vec::with_capacity(k);
    // k-means++: the heaviest colour first, then colours drawn in proportion to weight × d².
    let heaviest = (0..points.len()).max_by(|&a, &b| weights[a].total_cmp(&weights[b]).then(b.cmp(&a))).unwrap_or(0);
    centres.push(points[heaviest].clone());
    while centres.len() < k {
        let scores: Vec<f64> = points
            .iter()
            .zip(&weights)
            .map(|(p, w)| w * centres.iter().map(|c| distance(p, c)).fold(f64::INFINITY, f64::min))
            .collect();
        let total: f64 = scores.iter().sum();
        if total <= 0.0 {
            break;
        }
        let mut pick = stream.random::<f64>() * total;
        let mut chosen = points.len() - 1;
        for (index, score) in scores.iter().enumerate() {
            if pick < *score {
                chosen = index;
                break;
            }
            pick -= score;
        }
        centres.push(points[chosen].clone());
    }
    let mut assignment = vec![usize::MAX; points.len()];
    for _ in 0..100 {
        let mut changed = false;
        for (index, point) in points.iter().enumerate() {
            let nearest = (0..centres.len())
                .min_by(|&a, &b| distance(point, &centres[a]).total_cmp(&distance(point, &centres[b])))
                .unwrap_or(0);
            if assignment[index] != nearest {
                assignment[index] = nearest;
                changed = true;
            }
        }
        if !changed {
            break;
        }
        let mut sums = vec![vec![0.0_f64; channels]; centres.len()];
        let mut mass = vec![0.0_f64; centres.len()];
        for (index, point) in points.iter().enumerate() {
            mass[assignment[index]] += weights[index];
            for (sum, value) in sums[assignment[index]].iter_mut().zip(point) {
                *sum += weights[index] * f64::from(*value);
            }
        }
        for (centre, (sum, m)) in centres.iter_mut().zip(sums.iter().zip(&mass)) {
            if *m > 0.0 {
                *centre = sum.iter().map(|s| (s / m) as f32).collect();
            }
        }
    }
    let used: Vec<bool> = (0..centres.len()).map(|c| assignment.contains(&c)).collect();
    centres.into_iter().zip(used).filter(|(_, used)| *used).map(|(c, _)| c).collect()
}

/// Labels of a pyramid level `level` (0 = finest): every `2^level`-th pixel, matching the
/// pyramid's decimation.
pub(crate) fn decimate(labels: &[u16], width: usize, height: usize, size: (usize, usize), level: usize) -> Vec<u16> {
    let step = 1usize << level;
    let mut out = Vec::with_capacity(size.0 * size.1);
    for y in 0..size.1 {
        for x in 0..size.0 {
            out.push(labels[(y * step).min(height - 1) * width + (x * step).min(width - 1)]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(colours: &[[f32; 3]]) -> FloatImage {
        FloatImage::from_data(colours.len(), 1, 3, colours.iter().flatten().copied().collect()).unwrap()
    }

    #[test]
    fn palette_labels_equal_colours_alike_on_both_sides() {
        let source = image(&[[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]);
        let target = image(&[[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]);
        let labels = label_guides(&source, &target, Segmentation::Palette, 0).unwrap();
        assert_eq!(labels.colours.len(), 2);
        assert_eq!(labels.source[0], labels.source[2]);
        assert_ne!(labels.source[0], labels.source[1]);
        assert_eq!(labels.target, vec![labels.source[1], labels.source[0]]);
    }

    #[test]
    fn fixed_colours_take_each_pixel_to_the_nearest() {
        let source = image(&[[1.0, 0.0, 0.0], [0.55, 0.0, 0.45], [0.0, 0.0, 1.0]]);
        let target = image(&[[0.4, 0.0, 0.6], [0.9, 0.05, 0.0]]);
        let colours = vec![vec![0.0, 0.0, 1.0], vec![1.0, 0.0, 0.0]];
        let labels = label_by_colours(&source, &target, colours.clone());
        assert_eq!(labels.colours, colours);
        assert_eq!(labels.source, vec![1, 1, 0]);
        assert_eq!(labels.target, vec![0, 1]);
    }

    #[test]
    fn kmeans_groups_anti_aliased_shades() {
        let shades: Vec<[f32; 3]> = (0..40)
            .map(|i| if i < 20 { [0.1 + i as f32 * 0.002, 0.0, 0.0] } else { [0.9 - i as f32 * 0.002, 1.0, 1.0] })
            .collect();
        let source = image(&shades);
        let labels = label_guides(&source, &source, Segmentation::KMeans(2), 3).unwrap();
        assert_eq!(labels.colours.len(), 2);
        assert!(labels.source[..20].iter().all(|&l| l == labels.source[0]));
        assert!(labels.source[20..].iter().all(|&l| l == labels.source[20]));
        assert_ne!(labels.source[0], labels.source[20]);
        assert!(label_guides(&source, &source, Segmentation::Palette, 0).is_ok());
        let many: Vec<[f32; 3]> = (0..100).map(|i| [i as f32 / 100.0, 0.0, 0.0]).collect();
        let error = label_guides(&image(&many), &image(&many), Segmentation::Palette, 0).unwrap_err();
        assert!(error.to_string().contains("distinct colours"));
    }
}
