//! `motif demo`: every engine of the registry on its built-in examples, and an HTML gallery of
//! the results (see [`crate::gallery`]).

use std::path::PathBuf;

use anyhow::Context as _;
use clap::Args;

use crate::gallery::{Demo, Runner};
use crate::options::GlobalArgs;
use crate::registry::Engine;

/// Options of `motif demo`.
#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Folder for the inputs, the outputs and `index.html` (created if missing; files in it with
    /// the demo's names are replaced).
    #[arg(long, default_value = "motif-demo", value_name = "DIR")]
    pub out: PathBuf,
}

/// Runs `motif demo`: every engine's cases, each through `runner`.
#[allow(clippy::print_stderr)]
pub fn run(
    args: &DemoArgs,
    global: &GlobalArgs,
    threads: usize,
    engines: &[&dyn Engine],
    runner: Runner<'_>,
) -> anyhow::Result<()> {
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create the demo folder {}", args.out.display()))?;
    let mut demo = Demo::new(args.out.clone(), global.seed, threads, global.quiet, runner);
    let start = std::time::Instant::now();
    if !global.quiet {
        eprintln!("motif demo: writing into {}", args.out.display());
    }
    for engine in engines {
        engine.demo(&mut demo)?;
    }
    let total_ms = start.elapsed().as_secs_f64() * 1000.0;
    let (html, figures) = demo.finish(total_ms);
    let index = args.out.join("index.html");
    motif_io::write_text(&index, &html)?;
    let report = serde_json::json!({ "command": "demo", "seed": global.seed, "threads": threads, "total_ms": total_ms, "cases": figures });
    motif_io::write_json(&args.out.join("demo-report.json"), &report)?;
    if let Some(path) = &global.report {
        motif_io::write_json(path, &report)?;
    }
    if !global.quiet {
        eprintln!("motif demo: {} cases in {:.1} s; open {}", demo.len(), total_ms / 1000.0, index.display());
    }
    Ok(())
}
