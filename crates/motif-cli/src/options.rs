//! The options every command accepts.

use std::path::PathBuf;

use clap::Args;

/// Options every command accepts (shown under their own heading in every command's help).
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Global options")]
pub struct GlobalArgs {
    /// Seed of every random choice; the same seed gives byte-identical output whatever the thread count.
    #[arg(long, global = true, default_value_t = 1, value_name = "N", allow_negative_numbers = true)]
    pub seed: u64,
    /// Worker threads (default: all cores). Results do not depend on it, only speed does.
    #[arg(long, global = true, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=1024), allow_negative_numbers = true)]
    pub threads: Option<u16>,
    /// Refuse runs whose estimated peak memory passes this: bytes or a size such as 512M or 8G
    /// [default: half of this machine's memory]. Each engine estimates it from its inputs before
    /// allocating (pixels × channels × levels, pieces × positions, quadrature points × window).
    #[arg(long, global = true, value_name = "SIZE", value_parser = parse_memory, allow_hyphen_values = true)]
    pub max_memory: Option<u64>,
    /// No progress bars or summaries on stderr (errors are still printed).
    #[arg(long, short, global = true)]
    pub quiet: bool,
    /// Write the figures of the run (timings per stage, sizes, energies, costs) to this JSON file.
    #[arg(long, global = true, value_name = "FILE.json")]
    pub report: Option<PathBuf>,
}

fn parse_memory(text: &str) -> Result<u64, String> {
    let bytes = motif_core::memory::parse_bytes(text)?;
    motif_core::memory::check_max_memory(bytes).map_err(|error| error.allowed)
}

/// `--max-memory`, or half of this machine's memory (4 GiB where it cannot be read).
pub(crate) fn max_memory(global: &GlobalArgs) -> u64 {
    global
        .max_memory
        .unwrap_or_else(|| motif_io::physical_memory().map_or(motif_core::DEFAULT_MAX_MEMORY, |total| total / 2))
}
