//! The engine's one error type.

use motif_core::InvalidParameter;

/// Everything that can go wrong in stylization or texture synthesis.
///
/// All variants describe bad input; the engine itself never fails on valid input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A numeric parameter is out of its range.
    #[error(transparent)]
    InvalidParameter(#[from] InvalidParameter),
    /// An input image has no pixels.
    #[error("the {0} image is empty")]
    EmptyImage(String),
    /// Two images that must have the same size do not.
    #[error("{what}: {first} is {first_size} but {second} is {second_size}")]
    SizeMismatch {
        /// Which rule was broken.
        what: String,
        /// Name of the first image.
        first: String,
        /// Size of the first image, `W×H`.
        first_size: String,
        /// Name of the second image.
        second: String,
        /// Size of the second image, `W×H`.
        second_size: String,
    },
    /// The source and target images of one guide pair have different channel counts.
    #[error(
        "guide {index}: the source guide has {source_channels} channels but the target guide has {target_channels}"
    )]
    ChannelMismatch {
        /// Guide number, counted from 1.
        index: usize,
        /// Channels of the source guide.
        source_channels: usize,
        /// Channels of the target guide.
        target_channels: usize,
    },
    /// An image has a channel count the engine does not handle.
    #[error("the {what} image has {channels} channels; 1, 3 or 4 are supported")]
    UnsupportedChannels {
        /// Which image.
        what: String,
        /// Its channel count.
        channels: usize,
    },
    /// The style is smaller than one patch at the finest level.
    #[error("the style image is {width}×{height}, smaller than one {patch}×{patch} patch")]
    StyleTooSmall {
        /// Style width.
        width: usize,
        /// Style height.
        height: usize,
        /// Patch size.
        patch: usize,
    },
    /// Neither target guides nor an output size say how big the output is.
    #[error("no target guide and no output size: give guides or a size")]
    MissingTargetSize,
    /// The run would synthesize more pixels than the limit allows.
    #[error(
        "the run would synthesize {pixels} pixels, more than the {max_pixels} allowed (max-pixels; about 15 CPU-seconds \
         per megapixel): use a smaller size, or raise max-pixels"
    )]
    TooMuchWork {
        /// Output pixels (summed over the textures of a presynthesis).
        pixels: usize,
        /// The limit ([`crate::Params::max_pixels`]).
        max_pixels: usize,
    },
    /// Segment guidance could not label the guide.
    #[error("segments: {0}")]
    Segments(String),
    /// The pre-synthesized textures do not fit the target.
    #[error("pre-synthesized textures: {0}")]
    Presynth(String),
    /// A nearest-neighbour field does not fit the images it is applied to.
    #[error("nearest-neighbour field: {0}")]
    Field(String),
}
