//! Infinite zoom (§5.3 of the map paper): the texture is synthesized again at every zoom level,
//! at full resolution, so that zooming in keeps the style's appearance instead of magnifying its
//! pixels.
//!
//! Each level is made consistent with the one above: the centre of the coarser level, scaled up by
//! the zoom factor, is a target guide whose source guide is the style blurred by the same factor
//! (what the style looks like from that far away). The finer level thus keeps the coarse layout
//! the viewer was zooming into, with new detail synthesized within it. A user's guides zoom the
//! same way (their target's centre scaled up).

use motif_core::{FloatImage, InvalidParameter, Progress};

use crate::LimitError;
use crate::error::Error;
use crate::{Guide, Input, Output, Params, synthesize};

/// The centre `1 / factor` of `image`, scaled back up to its size (bilinear).
pub(crate) fn zoom_into(image: &FloatImage, factor: f64) -> FloatImage {
    let (width, height) = (image.width(), image.height());
    let mut out = FloatImage::new(width, height, image.channels());
    let (crop_width, crop_height) = (width as f64 / factor, height as f64 / factor);
    let (left, top) = (0.5 * (width as f64 - crop_width), 0.5 * (height as f64 - crop_height));
    for y in 0..height {
        for x in 0..width {
            let (sx, sy) = (left + (x as f64 + 0.5) / factor, top + (y as f64 + 0.5) / factor);
            image.sample_bilinear(sx, sy, out.pixel_mut(x, y));
        }
    }
    out
}

/// `image` as seen `factor` times farther away, at its own size: reduced (a Gaussian pyramid,
/// then bilinear for the rest of the factor) and scaled back up.
pub(crate) fn blurred_by(image: &FloatImage, factor: f64) -> FloatImage {
    let (width, height) = (image.width(), image.height());
    let mut reduced = image.clone();
    let mut remaining = factor;
    while remaining >= 2.0 && reduced.width() >= 4 && reduced.height() >= 4 {
        reduced = reduced.downsample();
        remaining /= 2.0;
    }
    let small = ((width as f64 / factor).round().max(1.0) as usize, (height as f64 / factor).round().max(1.0) as usize);
    reduced.resize_bilinear(small.0, small.1).resize_bilinear(width, height)
}

/// The peak memory of a whole zoom run of `levels` levels (floats): the largest level's synthesis
/// (the finer ones have one more guide, the coarser level's centre against the blurred style), the
/// style's blurred copy and the style and guides each level is given, and the finished levels kept
/// until the end (image, field with weights, error map). `guide_channels` are the user's guides'.
pub fn zoom_memory(
    style: (usize, usize, usize),
    guide_channels: usize,
    target: (usize, usize),
    levels: usize,
) -> motif_core::MemoryEstimate {
    let (style_pixels, channels) = (style.0.saturating_mul(style.1), style.2);
    let target_pixels = target.0.saturating_mul(target.1);
    let finer_guides = if levels > 1 { guide_channels + channels } else { guide_channels };
    let mut estimate = crate::memory_estimate(style_pixels, channels, finer_guides, target_pixels, 4, style_pixels);
    let (style_pixels, target_pixels, channels) = (style_pixels as f64, target_pixels as f64, channels as f64);
    estimate
        .add("blurred style and the level's copies", style_pixels, 4.0 * (2.0 * channels + guide_channels as f64))
        .add("user guides zoomed", target_pixels, 4.0 * guide_channels as f64)
        .add("finished levels", target_pixels * levels.saturating_sub(1) as f64, 4.0 * channels + 18.0);
    estimate
}

/// Synthesizes `levels` zoom levels of `input` (a texture or a guided stylization), each `factor`
/// times closer than the one before, all of the output's size. Level 0 is `input` as it is.
pub fn zoom(
    input: &Input,
    factor: f64,
    levels: usize,
    params: &Params,
    progress: &mut dyn Progress,
) -> Result<Vec<Output>, Error> {
    if !(factor.is_finite() && (1.05..=8.0).contains(&factor)) {
        return Err(InvalidParameter::new("factor", motif_core::error::number(factor), "must be 1.05–8").into());
    }
    if !(1..=64).contains(&levels) {
        return Err(InvalidParameter::new("zoom-levels", levels, "must be 1–64").into());
    }
    if input.mask.is_some() || input.textures.is_some() {
        return Err(InvalidParameter::new("zoom", "with a mask or textures", "takes a texture or guides only").into());
    }
    // Every level is a full synthesis: the pixel guard counts them all, before any work.
    let size = input.size.or_else(|| input.guides.first().map(|g| (g.target.width(), g.target.height())));
    if let Some((width, height)) = size {
        let pixels = width.saturating_mul(height).saturating_mul(levels);
        if pixels > params.max_pixels {
            return Err(Error::Limit(LimitError::TooMuchWork { pixels, max_pixels: params.max_pixels }));
        }
    }
    // The whole run is checked before the first level (each level checks its own part again).
    if let Some(target) = size {
        let guide_channels = input.guides.iter().map(|g| g.source.channels()).sum();
        let style = (input.style.width(), input.style.height(), input.style.channels());
        zoom_memory(style, guide_channels, target, levels)
            .check(params.max_memory, "use fewer or smaller zoom levels, or a smaller exemplar")?;
    }
    let mut outputs: Vec<Output> = Vec::with_capacity(levels);
    let blurred_style = blurred_by(&input.style, factor);
    let mut guides = input.guides.clone();
    for level in 0..levels {
        let mut report = |stage: &str, fraction: f64| {
            progress.report(&format!("zoom level {} of {levels}: {stage}", level + 1), fraction)
        };
        let mut level_params = params.clone();
        level_params.seed = motif_core::SeedStreams::new(params.seed).child("zoom level", level as u64).seed();
        let output = match outputs.last() {
            None => synthesize(input, &level_params, &mut report)?,
            Some(parent) => {
                let (width, height) = (parent.image.width(), parent.image.height());
                if (width as f64) / factor < params.patch_size as f64
                    || (height as f64) / factor < params.patch_size as f64
                {
                    return Err(InvalidParameter::new(
                        "factor",
                        motif_core::error::number(factor),
                        format!(
                            "leaves less than one {0}×{0} patch of the {width}×{height} output to zoom into",
                            params.patch_size
                        ),
                    )
                    .into());
                }
                for guide in &mut guides {
                    guide.target = zoom_into(&guide.target, factor);
                }
                let mut level_guides = guides.clone();
                level_guides.push(Guide {
                    source: blurred_style.clone(),
                    target: zoom_into(&parent.image, factor),
                    weight: None,
                });
                let next = Input { size: None, ..Input::guided(input.style.clone(), level_guides) };
                synthesize(&next, &level_params, &mut report)?
            }
        };
        outputs.push(output);
    }
    Ok(outputs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tests::texture;
    use motif_core::NoProgress;

    /// Mean absolute difference between the child level reduced by `factor` and the centre of
    /// its parent (both at the parent's crop size).
    fn disagreement(parent: &FloatImage, child: &FloatImage, factor: f64) -> f64 {
        let (width, height) = (parent.width(), parent.height());
        let (crop_width, crop_height) = ((width as f64 / factor) as usize, (height as f64 / factor) as usize);
        let (left, top) = ((width - crop_width) / 2, (height - crop_height) / 2);
        let reduced = blurred_by(child, factor);
        let mut total = 0.0;
        let mut count = 0;
        for y in 0..crop_height {
            for x in 0..crop_width {
                // The child pixel over parent pixel (left + x, top + y), blurred to the parent's scale.
                let (cx, cy) = (((x as f64 + 0.5) * factor) as usize, ((y as f64 + 0.5) * factor) as usize);
                let a = reduced.pixel(cx.min(width - 1), cy.min(height - 1));
                let b = parent.pixel(left + x, top + y);
                total += a.iter().zip(b).map(|(p, q)| f64::from((p - q).abs())).sum::<f64>() / a.len() as f64;
                count += 1;
            }
        }
        total / count as f64
    }

    #[test]
    fn each_zoom_level_agrees_with_the_centre_of_the_one_above() {
        let exemplar = texture(48, 48, 3, 31);
        let params = Params::default().with_seed(3);
        let levels = zoom(&Input::texture(exemplar.clone(), 64, 64), 2.0, 3, &params, &mut NoProgress).unwrap();
        assert_eq!(levels.len(), 3);
        for pair in levels.windows(2) {
            let guided = disagreement(&pair[0].image, &pair[1].image, 2.0);
            // An unguided texture of the same size: what a level would be without its parent.
            let free =
                synthesize(&Input::texture(exemplar.clone(), 64, 64), &params.clone().with_seed(99), &mut NoProgress)
                    .unwrap();
            let unguided = disagreement(&pair[0].image, &free.image, 2.0);
            assert!(
                guided < 0.04 && guided < 0.6 * unguided,
                "zoomed level differs by {guided:.3} (unguided {unguided:.3})"
            );
        }
        let error = zoom(&Input::texture(exemplar, 64, 64), 20.0, 2, &params, &mut NoProgress).unwrap_err();
        assert!(error.to_string().contains("invalid factor"), "{error}");
    }
}
