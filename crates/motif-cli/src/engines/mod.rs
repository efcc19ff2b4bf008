//! One module per engine subcommand. Each module provides its clap `Args`, a `run` function, a
//! `demo` function (built-in examples for `motif demo`) and a `bench` function (figures for
//! `motif bench`); this file wires them into the CLI.
//!
//! To add an engine `foo`: `pub mod foo;`, a variant `Foo(foo::FooArgs)` whose doc comment is its
//! help line, its arms in `name` and `run`, a `foo::demo(demo)?;` line in `demos` and an arm in
//! `benches`.

use clap::Subcommand;
use serde_json::{Map, Value};

use crate::bench::Bench;
use crate::context::Context;
use crate::demo::Demo;

pub mod curve;
pub mod curve_corpus;
pub mod points;
pub mod points_bench;
pub mod points_corpus;
pub mod points_preview;
pub mod strokes;
pub mod stylize;
pub mod stylize_bench;
pub mod stylize_demo;

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
    /// Discrete elements, continuous structures and mixtures, in boxes, regions or brush strokes
    /// (Roveri et al. 2015).
    #[command(allow_negative_numbers = true)]
    Points(points::PointsArgs),
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
    /// Grow a texture of any size from an exemplar image, optionally tileable
    #[command(allow_negative_numbers = true)]
    Texture(stylize::TextureArgs),
}

impl EngineCommand {
    /// The subcommand's name, as typed.
    pub fn name(&self) -> &'static str {
        match self {
            EngineCommand::Curve(_) => "curve",
            EngineCommand::Points(_) => "points",
            EngineCommand::Strokes(_) => "strokes",
            EngineCommand::Stylize(_) => "stylize",
            EngineCommand::Texture(_) => "texture",
        }
    }

    /// Runs the subcommand.
    pub fn run(&self, context: &mut Context) -> anyhow::Result<()> {
        match self {
            EngineCommand::Curve(args) => curve::run(args, context),
            EngineCommand::Points(args) => points::run(args, context),
            EngineCommand::Strokes(args) => strokes::run(args, context),
            EngineCommand::Stylize(args) => stylize::run_stylize(args, context),
            EngineCommand::Texture(args) => stylize::run_texture(args, context),
        }
    }
}

/// Adds every engine's built-in examples to the gallery.
pub fn demos(demo: &mut Demo) -> anyhow::Result<()> {
    curve::demo(demo)?;
    points::demo(demo)?;
    strokes::demo(demo)?;
    stylize_demo::demo(demo)?;
    Ok(())
}

/// Every engine's benchmark figures, keyed by engine; `only` limits the engines run (empty: all).
pub fn benches(bench: &Bench, only: &[String]) -> anyhow::Result<Map<String, Value>> {
    let mut figures = Map::new();
    for &name in ENGINE_NAMES {
        if !only.is_empty() && !only.iter().any(|wanted| wanted == name) {
            continue;
        }
        let value = match name {
            "curve" => curve_corpus::bench(bench)?,
            "points" => points_bench::bench(bench)?,
            "strokes" => strokes::bench(bench)?,
            "stylize" => stylize_bench::bench(bench)?,
            _ => continue,
        };
        figures.insert(name.to_string(), value);
    }
    Ok(figures)
}

/// The engines `motif bench --engine` accepts.
pub const ENGINE_NAMES: &[&str] = &["curve", "stylize", "points", "strokes"];
