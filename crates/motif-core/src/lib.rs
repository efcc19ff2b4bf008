//! Shared machinery for every motif engine.
//!
//! motif-core is pure: it never touches files and never prints, so every engine built on it also
//! builds for `wasm32-unknown-unknown`. Its modules:
//!
//! - [`image`]: 8-bit RGBA images ([`RgbaImage`]) and N-channel float images ([`FloatImage`]), alpha
//!   helpers, bilinear sampling, resizing and Gaussian pyramids (used by the curve and stylize engines).
//! - [`channel_image`]: 8-bit images of any channel count ([`ByteImage`]) and [`ChannelImage`], which
//!   lets the stylize engine take float or 8-bit inputs alike.
//! - [`geometry`]: polylines with arc-length parameterization, resampling, tangents, normals, offsets,
//!   curvature and closed curves, built on `kurbo` points; flattening of `kurbo` Bézier paths; simple
//!   polygons (area, containment).
//! - [`random`]: [`SeedStreams`], one `--seed` fanned out into independent streams per (stage, index),
//!   so that results never depend on the thread count.
//! - [`progress`]: the [`Progress`] trait engines report to (closures implement it).
//! - [`error`]: [`InvalidParameter`], the shared vocabulary for rejecting a parameter (its name, its
//!   value and what is allowed), and the checks that build it.
//! - [`builders!`]: the `with_*` builder methods of every engine's `Params`.
//! - [`timing`]: [`StageTimer`], wall-clock milliseconds per named stage (works on wasm too).
//! - [`math`] and [`vector`]: transcendental functions and vector lengths, directions, angles and
//!   rotations with the same bits natively and in WebAssembly (the platforms' math libraries round
//!   differently; engines use these instead of the `f64` methods and kurbo's).
//! - `tone`: [`ToneMap`], a grey image stretched over a rectangle of a drawing (the density, scale
//!   and rotation maps of the strokes and points engines).
//! - `mesh`: [`TriangleMesh`], vertices and triangles (volume domains, reconstructed surfaces).
//!
//! Conventions (see `ARCHITECTURE.md`): y points down; pixel `(i, j)` covers `[i, i+1) × [j, j+1)`
//! so its centre is at `(i + 0.5, j + 0.5)`; colours are 8-bit sRGB with straight (not premultiplied)
//! alpha unless a type says otherwise.

mod builders;
pub mod channel_image;
pub mod error;
pub mod geometry;
pub mod image;
pub mod limits;
pub mod math;
pub mod memory;
mod mesh;
pub mod progress;
pub mod random;
pub mod timing;
mod tone;
pub mod vector;

pub use channel_image::{ByteImage, ChannelImage, Samples};
pub use error::InvalidParameter;
pub use geometry::{Polygon, Polyline};
pub use image::{FloatImage, RgbaImage};
pub use kurbo;
pub use kurbo::{Point, Vec2};
pub use memory::{DEFAULT_MAX_MEMORY, MemoryEstimate, TooMuchMemory};
pub use mesh::TriangleMesh;
pub use progress::{NoProgress, Progress};
pub use random::SeedStreams;
pub use timing::StageTimer;
pub use tone::ToneMap;
