//! One folder per engine: `mod.rs` holds its clap `Args` and `run`, `demo.rs` its built-in
//! examples for `motif demo`, `bench.rs` its figures for `motif bench`, and `mod.rs` a unit
//! struct that implements [`Engine`] with them.
//!
//! To add an engine `foo`: `pub mod foo;`, a variant `Foo(foo::FooArgs)` of [`EngineCommand`]
//! whose `about` is its job's summary (with its arms in `name` and `run`), and `&foo::Foo` in
//! [`ENGINES`].

use clap::Subcommand;
use motif_jobs::Job;
use motif_jobs::curve::CurveJob;
use motif_jobs::points::PointsJob;
use motif_jobs::strokes::StrokesJob;
use motif_jobs::stylize::{InpaintJob, PresynthJob, StylizeJob, TextureJob, VideoJob, ZoomJob};
use motif_jobs::tiles::TilesJob;

use crate::context::Context;
use crate::registry::Engine;

pub(crate) mod curve;
pub(crate) mod points;
pub(crate) mod strokes;
pub(crate) mod stylize;
pub(crate) mod tiles;

/// A job's long help: its summary, then its details.
fn long_about<J: Job>() -> String {
    format!("{}\n\n{}", J::SUMMARY, J::DETAILS)
}

/// The engine subcommands: one per job of `motif_jobs::JOBS`, whose name, summary and details
/// are the job's own.
#[derive(Subcommand, Debug)]
pub enum EngineCommand {
    #[command(about = CurveJob::SUMMARY, long_about = long_about::<CurveJob>(), allow_negative_numbers = true)]
    Curve(curve::CurveArgs),
    #[command(about = PointsJob::SUMMARY, long_about = long_about::<PointsJob>(), allow_negative_numbers = true)]
    Points(Box<points::PointsArgs>),
    #[command(about = StrokesJob::SUMMARY, long_about = long_about::<StrokesJob>(), allow_negative_numbers = true)]
    Strokes(strokes::StrokesArgs),
    #[command(about = StylizeJob::SUMMARY, long_about = long_about::<StylizeJob>(), allow_negative_numbers = true)]
    Stylize(stylize::StylizeArgs),
    #[command(about = PresynthJob::SUMMARY, long_about = long_about::<PresynthJob>(), allow_negative_numbers = true)]
    Presynth(stylize::PresynthArgs),
    #[command(about = TextureJob::SUMMARY, long_about = long_about::<TextureJob>(), allow_negative_numbers = true)]
    Texture(stylize::TextureArgs),
    #[command(about = InpaintJob::SUMMARY, long_about = long_about::<InpaintJob>(), allow_negative_numbers = true)]
    Inpaint(stylize::InpaintArgs),
    #[command(about = ZoomJob::SUMMARY, long_about = long_about::<ZoomJob>())]
    Zoom(stylize::ZoomArgs),
    #[command(about = VideoJob::SUMMARY, long_about = long_about::<VideoJob>(), allow_negative_numbers = true)]
    Video(stylize::VideoArgs),
    #[command(about = TilesJob::SUMMARY, long_about = long_about::<TilesJob>())]
    Tiles(tiles::TilesArgs),
}

impl EngineCommand {
    /// The subcommand's name, as typed.
    pub fn name(&self) -> &'static str {
        match self {
            EngineCommand::Curve(_) => CurveJob::NAME,
            EngineCommand::Points(_) => PointsJob::NAME,
            EngineCommand::Strokes(_) => StrokesJob::NAME,
            EngineCommand::Stylize(_) => StylizeJob::NAME,
            EngineCommand::Presynth(_) => PresynthJob::NAME,
            EngineCommand::Texture(_) => TextureJob::NAME,
            EngineCommand::Inpaint(_) => InpaintJob::NAME,
            EngineCommand::Zoom(_) => ZoomJob::NAME,
            EngineCommand::Video(_) => VideoJob::NAME,
            EngineCommand::Tiles(_) => TilesJob::NAME,
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
            EngineCommand::Tiles(args) => tiles::run(args, context),
        }
    }
}

/// Every engine, in the order `demo` and `bench` run them.
pub(crate) const ENGINES: &[&dyn Engine] = &[&curve::Curve, &points::Points, &strokes::Strokes, &stylize::Stylize];

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
