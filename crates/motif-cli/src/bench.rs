//! `motif bench`: fixed, seeded, generated workloads for every engine, printed as one JSON object.
//!
//! This is the single entry point for performance figures; tests never time anything.

use std::path::PathBuf;

use clap::Args;
use serde_json::{Value, json};

use crate::GlobalArgs;
use crate::engines::ENGINE_NAMES;

/// Options of `motif bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Run only this engine (repeat for several): curve, stylize, points or strokes.
    #[arg(long = "engine", value_name = "NAME", value_parser = clap::builder::PossibleValuesParser::new(ENGINE_NAMES))]
    pub engines: Vec<String>,
    /// Tiny workloads that finish in seconds (for smoke tests; the figures are not comparable).
    #[arg(long)]
    pub quick: bool,
    /// Run only the cases of this name (repeat for several): a corpus case (e.g. longleaf,
    /// chain_round), a generated workload (curve: 199x82, 325x64; points: helix, sand, chair;
    /// stylize: 0.15mp, 1mp, table1, exact), or a group: corpus, generated. Slow cases run only
    /// when named. Default: every case but the slow ones.
    #[arg(long = "case", value_name = "NAME")]
    pub cases: Vec<String>,
    /// Also write the JSON object to this file.
    #[arg(long, value_name = "FILE.json")]
    pub out: Option<PathBuf>,
}

/// What an engine's benchmark gets.
pub struct Bench {
    /// Seed of the generated workloads.
    pub seed: u64,
    /// True for tiny workloads (smoke tests).
    pub quick: bool,
    /// Worker threads in use.
    pub threads: usize,
    /// Cases named with `--case` (empty: all).
    pub cases: Vec<String>,
}

impl Bench {
    /// True when case `name` of group `group` (`corpus` or `generated`) should run: no `--case`
    /// given, or the name or its group named.
    pub fn selects(&self, name: &str, group: &str) -> bool {
        self.cases.is_empty() || self.names(name) || self.names(group)
    }

    /// True when case `name` was named with `--case` (slow cases run only then).
    pub fn names(&self, name: &str) -> bool {
        self.cases.iter().any(|c| c == name)
    }
}

/// The real-data corpus folder of `engine` in this source tree (`data/real/<engine>/`; the bench
/// is a developer's tool run from a checkout).
pub fn corpus_folder(engine: &str) -> PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real").join(engine)
}

/// The cases of a corpus manifest (`cases.json` in `folder`).
pub fn read_cases<T: serde::de::DeserializeOwned>(folder: &std::path::Path) -> anyhow::Result<Vec<T>> {
    use anyhow::Context as _;
    let path = folder.join("cases.json");
    let value: Value = motif_io::read_json(&path)?;
    serde_json::from_value(value).with_context(|| format!("{}: not a list of corpus cases", path.display()))
}

/// Runs `motif bench` and prints the figures on stdout.
#[allow(clippy::print_stdout)]
pub fn run(args: &BenchArgs, global: &GlobalArgs, threads: usize) -> anyhow::Result<()> {
    let bench = Bench { seed: global.seed, quick: args.quick, threads, cases: args.cases.clone() };
    let start = std::time::Instant::now();
    let engines = crate::engines::benches(&bench, &args.engines)?;
    let figures = json!({
        "motif_version": env!("CARGO_PKG_VERSION"),
        "seed": global.seed,
        "threads": bench.threads,
        "quick": args.quick,
        "cases": args.cases,
        "profile": if cfg!(debug_assertions) { "debug" } else { "release" },
        "total_s": start.elapsed().as_secs_f64(),
        "engines": Value::Object(engines),
    });
    println!("{}", serde_json::to_string_pretty(&figures)?);
    for path in args.out.iter().chain(&global.report) {
        motif_io::write_json(path, &figures)?;
    }
    Ok(())
}
