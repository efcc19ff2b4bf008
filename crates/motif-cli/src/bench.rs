//! `motif bench`: fixed, seeded, generated workloads for every engine, printed as one JSON object.
//!
//! This is the single entry point for performance figures; tests never time anything.

use std::io::Write as _;
use std::path::PathBuf;

use clap::Args;
use serde_json::{Value, json};

use crate::options::GlobalArgs;
use crate::registry::Engine;
use crate::suite::Bench;

/// Options of `motif bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Run only this engine (repeat for several): curve, stylize, points or strokes.
    #[arg(long = "engine", value_name = "NAME")]
    pub engines: Vec<String>,
    /// Tiny workloads that finish in seconds (for smoke tests; the figures are not comparable).
    #[arg(long)]
    pub quick: bool,
    /// Run only the cases of this name (repeat for several): a corpus case (e.g. longleaf,
    /// chain_round), a generated workload (curve: 199x82, 325x64; points: helix, sand, chair;
    /// stylize: 0.15mp, 1mp, table1, exact; slow: structure, video, texture-native, surface, volume), or a group: corpus, generated, scale (strokes: the ε
    /// inferred from each corpus drawing). Slow cases run only when named. Default: every case but
    /// the slow ones.
    #[arg(long = "case", value_name = "NAME")]
    pub cases: Vec<String>,
    /// Also write the JSON object to this file.
    #[arg(long, value_name = "FILE.json")]
    pub out: Option<PathBuf>,
}

/// Runs `motif bench` over `engines` (those named with `--engine`, or all) and prints the figures
/// on stdout.
pub(crate) fn run(
    args: &BenchArgs,
    global: &GlobalArgs,
    threads: usize,
    engines: &[&dyn Engine],
) -> anyhow::Result<()> {
    let known: Vec<&str> = engines.iter().map(|engine| engine.name()).collect();
    if let Some(unknown) = args.engines.iter().find(|name| !known.contains(&name.as_str())) {
        anyhow::bail!("--engine {unknown}: there is no such engine; one of {}", known.join(", "));
    }
    let bench = Bench { seed: global.seed, quick: args.quick, threads, cases: args.cases.clone() };
    let start = std::time::Instant::now();
    let mut figures_by_engine = serde_json::Map::new();
    for engine in engines {
        if args.engines.is_empty() || args.engines.iter().any(|wanted| wanted == engine.name()) {
            figures_by_engine.insert(engine.name().to_string(), engine.bench(&bench)?);
        }
    }
    let figures = json!({
        "motif_version": env!("CARGO_PKG_VERSION"),
        "seed": global.seed,
        "threads": bench.threads,
        "quick": args.quick,
        "cases": args.cases,
        "profile": if cfg!(debug_assertions) { "debug" } else { "release" },
        "total_s": start.elapsed().as_secs_f64(),
        "engines": Value::Object(figures_by_engine),
    });
    // A reader that stops early (`motif bench | head`) is not an error of the bench.
    let text = serde_json::to_string_pretty(&figures)?;
    match writeln!(std::io::stdout().lock(), "{text}") {
        Err(error) if error.kind() != std::io::ErrorKind::BrokenPipe => return Err(error.into()),
        _ => {}
    }
    for path in args.out.iter().chain(&global.report) {
        motif_io::write_json(path, &figures)?;
    }
    Ok(())
}
