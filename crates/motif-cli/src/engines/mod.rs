//! One folder per engine: `mod.rs` holds its clap `Args` and `run`, `demo.rs` its built-in
//! examples for `motif demo`, `bench.rs` its figures for `motif bench`, and `mod.rs` a unit
//! struct that implements [`Engine`] with them.
//!
//! To add an engine `foo`: `pub mod foo;`, a variant `Foo(foo::FooArgs)` of [`EngineCommand`]
//! whose doc comment is its help line (with its arms in `name` and `run`), and `&foo::Foo` in
//! [`ENGINES`].

use clap::Subcommand;

use crate::context::Context;
use crate::registry::Engine;

pub mod curve;
pub mod points;
pub mod strokes;
pub mod stylize;

/// The engine subcommands.
#[derive(Subcommand, Debug)]
pub enum EngineCommand {
    /// Grow a structured raster pattern (chain, lace, frieze) along a curve
    ///
    /// Undistorted pieces of the exemplar placed by a globally optimal dynamic program
    /// (Zhou, Lasram, Lefebvre 2013).
    #[command(allow_negative_numbers = true)]
    Curve(curve::CurveArgs),
    /// Grow a repetitive structure of points with attributes, in 2D or 3D
    ///
    /// Discrete elements, continuous structures and mixtures, in boxes, regions, brush strokes,
    /// mesh volumes or on mesh surfaces (Roveri et al. 2015).
    #[command(allow_negative_numbers = true)]
    Points(Box<points::PointsArgs>),
    /// Grow a vector stroke pattern along a path or inside a region
    ///
    /// Hatching, stippling, brush marks and small figures analysed into elements and synthesized
    /// by neighbourhood matching (Barla et al. 2006).
    #[command(allow_negative_numbers = true)]
    Strokes(strokes::StrokesArgs),
    /// Paint a target guide in the style of an exemplar (A : A' :: B : B')
    ///
    /// Guided patch-based synthesis with occurrence penalty, segments and pre-synthesized
    /// textures (Texler et al.); options mirror ebsynth's.
    #[command(allow_negative_numbers = true)]
    Stylize(stylize::StylizeArgs),
    /// Make one seamless texture per segment of a style's guide, for `motif stylize --presynth`
    ///
    /// The pre-synthesized textures of Texler et al. §3.7: the target is then filled from them
    /// and only a band along segment edges is optimized.
    #[command(allow_negative_numbers = true)]
    Presynth(stylize::PresynthArgs),
    /// Grow a texture of any size from an exemplar image, optionally tileable
    #[command(allow_negative_numbers = true)]
    Texture(stylize::TextureArgs),
    /// Fill a hole in an image from the rest of it
    ///
    /// Patch-based synthesis whose kept pixels are the image outside the hole and whose sources
    /// are its patches wholly outside it, with the occurrence penalty so the fill does not clone
    /// one patch.
    #[command(allow_negative_numbers = true)]
    Inpaint(stylize::InpaintArgs),
    /// Zoom into a texture without end: every level synthesized at full resolution
    ///
    /// Each level is guided by the centre of the level above, scaled up, so zooming keeps both
    /// the layout and the style's own detail (the map paper's §5.3).
    Zoom(stylize::ZoomArgs),
    /// Stylize a video from one or more keyframes painted by an artist
    ///
    /// Each frame is synthesized from the nearest keyframes with the frame's colours and edges,
    /// the keyframe's positions carried along the motion and the previous output (against
    /// flicker), forward and backward from keyframes and blended between them (Jamriška et al.
    /// 2019). Keyframe intervals are independent (--interval).
    #[command(allow_negative_numbers = true)]
    Video(stylize::VideoArgs),
}

impl EngineCommand {
    /// The subcommand's name, as typed.
    pub fn name(&self) -> &'static str {
        match self {
            EngineCommand::Curve(_) => "curve",
            EngineCommand::Points(_) => "points",
            EngineCommand::Strokes(_) => "strokes",
            EngineCommand::Stylize(_) => "stylize",
            EngineCommand::Presynth(_) => "presynth",
            EngineCommand::Texture(_) => "texture",
            EngineCommand::Inpaint(_) => "inpaint",
            EngineCommand::Zoom(_) => "zoom",
            EngineCommand::Video(_) => "video",
        }
    }

    /// Runs the subcommand.
    pub fn run(&self, context: &mut Context) -> anyhow::Result<()> {
        match self {
            EngineCommand::Curve(args) => curve::run(args, context),
            EngineCommand::Points(args) => points::run(args, context),
            EngineCommand::Strokes(args) => strokes::run(args, context),
            EngineCommand::Stylize(args) => stylize::run_stylize(args, context),
            EngineCommand::Presynth(args) => stylize::run_presynth(args, context),
            EngineCommand::Texture(args) => stylize::run_texture(args, context),
            EngineCommand::Inpaint(args) => stylize::run_inpaint(args, context),
            EngineCommand::Zoom(args) => stylize::run_zoom(args, context),
            EngineCommand::Video(args) => stylize::run_video(args, context),
        }
    }
}

/// Every engine, in the order `demo` and `bench` run them.
pub const ENGINES: &[&dyn Engine] = &[&curve::Curve, &points::Points, &strokes::Strokes, &stylize::Stylize];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn engine_names_are_unique_and_listed_in_the_bench_help() {
        let names: Vec<&str> = ENGINES.iter().map(|engine| engine.name()).collect();
        let mut unique = names.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), names.len(), "{names:?}");
        let help = include_str!("../bench.rs");
        for name in names {
            assert!(help.contains(&format!(" {name}")), "bench --engine help does not name {name}");
        }
    }
}
