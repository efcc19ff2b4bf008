//! The engine's one error type.

use motif_core::InvalidParameter;

/// Everything that can go wrong, grouped as image-rs groups its errors: a parameter out of its
/// range, an input the engine cannot use, or a run that would pass a limit. Messages are
/// lower-case and say what to change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is outside its range.
    #[error(transparent)]
    Parameter(#[from] InvalidParameter),
    /// An input image, mask, guide, texture cache, field or video cannot be used as given.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The run would pass a limit on pixels, memory or a field encoding.
    #[error(transparent)]
    Limit(#[from] LimitError),
}

impl From<motif_core::TooMuchMemory> for Error {
    fn from(error: motif_core::TooMuchMemory) -> Self {
        Self::Limit(LimitError::Memory(error))
    }
}

/// An input image, mask, guide, texture cache, field or video cannot be used as given ([`Error::Input`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InputError {
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
    /// A kept image whose size is not the output's.
    #[error("the kept image is {kept} but the output is {target}: they must have the same size")]
    MaskSize {
        /// The kept image's size, `W×H`.
        kept: String,
        /// The output's size, `W×H`.
        target: String,
    },
    /// A hole with another number of pixels than the output.
    #[error("the mask has {pixels} pixels but the output is {target}: they must have the same size")]
    MaskPixels {
        /// Pixels in the mask.
        pixels: usize,
        /// The output's size, `W×H`.
        target: String,
    },
    /// A mask that marks no pixel, or every pixel, for synthesis.
    #[error("the mask marks {0}: mark the pixels to synthesize (white) and leave some to keep (black)")]
    MaskCoverage(&'static str),
    /// The image kept outside a mask has other channels than the style.
    #[error("the kept image has {kept} channels but the style has {style}")]
    MaskChannels {
        /// Channels of the kept image.
        kept: usize,
        /// Channels of the style.
        style: usize,
    },
    /// Inpainting with no whole patch outside the hole to copy from.
    #[error("no {patch}×{patch} patch of the image lies wholly outside the hole: nothing to fill it from")]
    NoSourceOutsideHole {
        /// Patch size.
        patch: usize,
    },
    /// A mask combined with pre-synthesized textures.
    #[error("a mask cannot be combined with pre-synthesized textures")]
    MaskWithTextures,
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
    /// An exact palette of the segment guide would have too many colours.
    #[error(
        "segments: the segment guide has {colours} distinct colours (more than {max}); quantize it with k-means (a \
         segment count) instead"
    )]
    TooManyColours {
        /// Distinct colours of the guide.
        colours: usize,
        /// The palette's limit.
        max: usize,
    },
    /// Segment guidance (or pre-synthesized textures) without a guide pair.
    #[error("segments: segment guidance needs a guide pair")]
    SegmentsWithoutGuide,
    /// A prepared style was given with an input it was not made from.
    #[error("prepared style: it was made for another {what}; prepare it again from this input")]
    PreparedMismatch {
        /// What differs: the style, the source guides, the textures' colours, the weights or the
        /// patch size.
        what: String,
    },
    /// Band mode was asked for with an empty list of textures.
    #[error("pre-synthesized textures: no textures given")]
    NoTextures,
    /// A texture's channel count differs from the style's.
    #[error("pre-synthesized textures: texture {texture} has {channels} channels but the style has {style_channels}")]
    TextureChannels {
        /// The texture, counted from 1.
        texture: usize,
        /// Its channels.
        channels: usize,
        /// The style's channels.
        style_channels: usize,
    },
    /// A texture's field does not have the texture's size.
    #[error(
        "pre-synthesized textures: the field of texture {texture} is {field_width}×{field_height} but the texture is {width}×{height}"
    )]
    TextureFieldSize {
        /// The texture, counted from 1.
        texture: usize,
        /// The field's width.
        field_width: usize,
        /// The field's height.
        field_height: usize,
        /// The texture's width.
        width: usize,
        /// The texture's height.
        height: usize,
    },
    /// A texture's field has a match outside the style.
    #[error(
        "pre-synthesized textures: the field of texture {texture} points outside the {style_width}×{style_height} style"
    )]
    TextureFieldOutside {
        /// The texture, counted from 1.
        texture: usize,
        /// The style's width.
        style_width: usize,
        /// The style's height.
        style_height: usize,
    },
    /// A texture's field points into a source of another size than the style.
    #[error(
        "pre-synthesized textures: the field of texture {texture} points into a {source_width}×{source_height} source \
         but the style is {style_width}×{style_height}"
    )]
    TextureFieldSource {
        /// The texture, counted from 1.
        texture: usize,
        /// The width the field points into.
        source_width: usize,
        /// The height the field points into.
        source_height: usize,
        /// The style's width.
        style_width: usize,
        /// The style's height.
        style_height: usize,
    },
    /// A segment of the target guide is far from every texture's colour and from their blends.
    #[error(
        "pre-synthesized textures: no texture for the target segment of colour #{colour} ({pixels} pixels): the \
         textures are of {textures}, and its colour distance to the nearest of them or of their blends is {distance} \
         (in 8-bit levels; up to {tolerance} is taken for an anti-aliased or compressed edge); presynthesize from a \
         source guide that has this colour"
    )]
    MissingTexture {
        /// The segment's (mean) colour, `rrggbb` (or the guide's channels in hex).
        colour: String,
        /// Its pixels in the target guide.
        pixels: usize,
        /// The textures' colours, `#rrggbb, …`.
        textures: String,
        /// Its distance from the nearest texture colour or blend of two, in 8-bit levels.
        distance: u32,
        /// The largest distance taken for an edge's blend, in 8-bit levels.
        tolerance: u32,
    },
    /// A texture's segment colour has another channel count than the segment guide.
    #[error(
        "pre-synthesized textures: texture {texture}'s segment colour is for a guide of {channels} channel(s) but the \
         segment guide has {guide_channels} (the cache was made from a guide of another kind: grey, RGB or RGBA)"
    )]
    TextureColour {
        /// The texture, counted from 1.
        texture: usize,
        /// Its colour's channels.
        channels: usize,
        /// The segment guide's channels.
        guide_channels: usize,
    },
    /// A segment of the source guide is too thin to hold one whole patch.
    #[error(
        "pre-synthesized textures: segment #{colour} has no pixel where a whole {patch}×{patch} patch fits inside the \
         style (an anti-aliased edge's blend read as a colour of its own? quantize the guide with k-means, a segment \
         count)"
    )]
    SegmentTooThin {
        /// The segment's colour in hex.
        colour: String,
        /// The patch side.
        patch: usize,
    },
    /// A decoded field points where no whole patch of the source fits.
    #[error(
        "nearest-neighbour field: pixel ({x}, {y}) points at ({source_x}, {source_y}), outside the \
         {source_width}×{source_height} source for {patch}×{patch} patches"
    )]
    FieldOutside {
        /// The field pixel's column.
        x: usize,
        /// The field pixel's row.
        y: usize,
        /// The column it points at.
        source_x: u32,
        /// The row it points at.
        source_y: u32,
        /// The source's width.
        source_width: usize,
        /// The source's height.
        source_height: usize,
        /// The patch side.
        patch: usize,
    },
    /// A video with no frames.
    #[error("video: no frames given")]
    NoFrames,
    /// A video with no keyframe.
    #[error("video: no keyframe given: stylize at least one frame and pass it as a keyframe")]
    NoKeyframes,
    /// A keyframe past the last frame.
    #[error("video: keyframe {frame} is past the last frame (the sequence has {frames} frames, numbered from 0)")]
    KeyframeOutOfRange {
        /// The keyframe's position.
        frame: usize,
        /// Frames in the sequence.
        frames: usize,
    },
    /// Keyframes out of order, or two at one frame.
    #[error("video: keyframe {frame} comes after keyframe {previous}: give keyframes once each, in frame order")]
    KeyframeOrder {
        /// The keyframe's position.
        frame: usize,
        /// The keyframe before it.
        previous: usize,
    },
}

/// The run would pass a limit on pixels, memory or a field encoding ([`Error::Limit`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LimitError {
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
    /// The run's estimated memory passes [`crate::Params::max_memory`].
    #[error(transparent)]
    Memory(#[from] motif_core::TooMuchMemory),
    /// A field's source is too large for its PNG encoding.
    #[error("nearest-neighbour field: a {width}×{height} source does not fit the PNG encoding (at most {max} a side)")]
    FieldTooLarge {
        /// The source's width.
        width: usize,
        /// The source's height.
        height: usize,
        /// The encoding's limit.
        max: usize,
    },
}
