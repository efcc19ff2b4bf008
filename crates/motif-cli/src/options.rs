//! The options every command accepts.

use std::path::PathBuf;

use clap::Args;

/// Options every command accepts.
#[derive(Args, Debug, Clone)]
pub struct GlobalArgs {
    /// Seed of every random choice; the same seed gives byte-identical output whatever the thread count.
    #[arg(long, global = true, default_value_t = 1, value_name = "N")]
    pub seed: u64,
    /// Worker threads (default: all cores). Results do not depend on it, only speed does.
    #[arg(long, global = true, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub threads: Option<u16>,
    /// No progress bars or summaries on stderr (errors are still printed).
    #[arg(long, short, global = true)]
    pub quiet: bool,
    /// Write the figures of the run (timings per stage, sizes, energies, costs) to this JSON file.
    #[arg(long, global = true, value_name = "FILE.json")]
    pub report: Option<PathBuf>,
}
