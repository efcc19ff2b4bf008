//! Size limits every front end applies, one constant each: files and arrays larger than these are
//! refused with a message before anything is allocated for them.

/// The largest side of an image the CLI and Python accept, in pixels.
pub const MAX_IMAGE_SIDE: u64 = 16_384;

/// The largest image the CLI and Python accept, in pixels (16 384 × 16 384).
pub const MAX_IMAGE_PIXELS: u64 = MAX_IMAGE_SIDE * MAX_IMAGE_SIDE;

/// The largest tone map (density, scale or rotation map) accepted, in pixels (8192 × 8192): a map
/// is a smooth field stretched over the target, and a larger one only costs memory.
pub const MAX_MAP_PIXELS: u64 = 8192 * 8192;

/// The largest side of an image the browser playground accepts, in pixels: WebAssembly has a
/// 4 GiB address space, and a synthesis holds several float copies of its images (a 4096² RGBA
/// image is 64 MiB as bytes, 256 MiB per float copy).
pub const MAX_BROWSER_IMAGE_SIDE: usize = 4096;
