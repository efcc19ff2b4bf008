//! Masks: synthesize only the pixels of a hole and keep the others exactly (ebsynth's masks),
//! and inpainting, where the kept image is also the style and no source patch may overlap the hole.

use motif_core::{ChannelImage, FloatImage};

use crate::InputError;
use crate::error::Error;
use crate::synthesis;

/// Which output pixels to synthesize and what the others keep (ebsynth's masks; inpainting).
///
/// At every pyramid level the kept pixels hold the kept image's own level and only the patches
/// that touch the hole are searched, so the fill is optimized against its surroundings: the
/// border is seamless and the pixels outside the hole come out exactly as kept.
#[derive(Debug, Clone, PartialEq)]
pub struct Mask<I = FloatImage> {
    /// The pixels kept outside the hole: an image of the output's size with the style's channels.
    pub keep: I,
    /// Per output pixel, row by row: `true` where the output is synthesized.
    pub hole: Vec<bool>,
    /// Inpainting: the style is the kept image itself, and no source patch may overlap the hole
    /// (its content is what is being replaced).
    pub exclude_hole_from_style: bool,
}

/// A mask must fit the output, mark some pixels and keep some, keep the style's channels, and
/// for inpainting leave at least one whole patch outside the hole to copy from.
pub(crate) fn check<I: ChannelImage>(
    mask: &Mask<I>,
    style: &I,
    (width, height): (usize, usize),
    patch: usize,
    textures: bool,
) -> Result<(), Error> {
    if textures {
        return Err(Error::Input(InputError::MaskWithTextures));
    }
    let size = (mask.keep.width(), mask.keep.height());
    if size != (width, height) {
        return Err(Error::Input(InputError::MaskSize {
            kept: format!("{}×{}", size.0, size.1),
            target: format!("{width}×{height}"),
        }));
    }
    if mask.hole.len() != width * height {
        return Err(Error::Input(InputError::MaskPixels {
            pixels: mask.hole.len(),
            target: format!("{width}×{height}"),
        }));
    }
    if mask.keep.channels() != style.channels() {
        return Err(Error::Input(InputError::MaskChannels { kept: mask.keep.channels(), style: style.channels() }));
    }
    let holes = mask.hole.iter().filter(|&&h| h).count();
    if holes == 0 {
        return Err(Error::Input(InputError::MaskCoverage("no pixel")));
    }
    if holes == mask.hole.len() {
        return Err(Error::Input(InputError::MaskCoverage("every pixel")));
    }
    if mask.exclude_hole_from_style {
        let touched = synthesis::dilate(&mask.hole, width, height, patch / 2);
        let radius = patch / 2;
        let whole = (radius..height.saturating_sub(radius))
            .any(|y| (radius..width.saturating_sub(radius)).any(|x| !touched[y * width + x]));
        if !whole {
            return Err(Error::Input(InputError::NoSourceOutsideHole { patch }));
        }
    }
    Ok(())
}
