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

/// The engine subcommands.
#[derive(Subcommand, Debug)]
pub enum EngineCommand {}

impl EngineCommand {
    /// The subcommand's name, as typed.
    pub fn name(&self) -> &'static str {
        match *self {}
    }

    /// Runs the subcommand.
    pub fn run(&self, _context: &mut Context) -> anyhow::Result<()> {
        match *self {}
    }
}

/// Adds every engine's built-in examples to the gallery.
pub fn demos(_demo: &mut Demo) -> anyhow::Result<()> {
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
            _ => continue,
        };
        figures.insert(name.to_string(), value);
    }
    let _ = bench;
    Ok(figures)
}

/// The engines `motif bench --engine` accepts.
pub const ENGINE_NAMES: &[&str] = &["curve", "stylize", "points", "strokes"];
