//! `motif`: one command line for every motif engine.
//!
//! - `main.rs`: argument parsing (clap derive), global options, error printing and exit codes.
//! - [`context`]: what a running command gets (seed, threads, progress, report figures).
//! - [`progress`]: progress bars on stderr and per-stage timings.
//! - [`engines`]: one module per engine subcommand (`curve`, `stylize`, `texture`, `points`, `strokes`).
//! - [`demo`]: `motif demo`, built-in examples and an HTML gallery.
//! - [`bench`]: `motif bench`, the single entry point for performance figures.

mod bench;
mod context;
mod demo;
mod engines;
mod progress;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

/// Grow new, non-repeating patterns from small examples: along curves, inside regions, or under
/// the control of guide images.
#[derive(Parser, Debug)]
#[command(name = "motif", version, about, long_about = None, propagate_version = true)]
pub struct Cli {
    /// Options every command accepts.
    #[command(flatten)]
    pub global: GlobalArgs,
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

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

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    #[command(flatten)]
    /// Engine subcommands.
    Engine(Box<engines::EngineCommand>),
    /// Run every engine on built-in examples and write an HTML gallery of inputs and outputs.
    Demo(demo::DemoArgs),
    /// Run fixed, seeded, generated workloads for every engine and print their figures as JSON.
    Bench(bench::BenchArgs),
}

fn main() -> ExitCode {
    // A panic is a bug in motif, never the user's fault: say so plainly instead of a backtrace.
    std::panic::set_hook(Box::new(|info| {
        #[allow(clippy::print_stderr)]
        {
            eprintln!("error: internal error (a bug in motif; please report it with the command you ran): {info}");
        }
    }));
    // Ctrl-C or SIGTERM: remove the temporary file of a write in progress (outputs are replaced
    // whole, by a rename, so no output is ever half-written) and exit as interrupted.
    let interrupted = ctrlc::set_handler(|| {
        motif_io::remove_temporaries();
        #[allow(clippy::print_stderr)]
        {
            eprintln!("error: interrupted");
        }
        std::process::exit(130);
    });
    if let Err(error) = interrupted {
        print_error(&anyhow::anyhow!("cannot install the interrupt handler: {error}"));
        return ExitCode::FAILURE;
    }
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(error) => {
            // clap prints help/version to stdout with exit 0, usage errors to stderr with exit 2.
            error.exit();
        }
    };
    let threads = cli
        .global
        .threads
        .map(usize::from)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from));
    if let Err(error) = rayon::ThreadPoolBuilder::new().num_threads(threads).build_global() {
        print_error(&anyhow::anyhow!("cannot start {threads} worker threads: {error}"));
        return ExitCode::FAILURE;
    }
    let result = match &cli.command {
        Command::Engine(command) => context::run_engine(command, &cli.global, threads),
        Command::Demo(args) => demo::run(args, &cli.global, threads),
        Command::Bench(args) => bench::run(args, &cli.global, threads),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            print_error(&error);
            ExitCode::FAILURE
        }
    }
}

/// Prints an error and its causes, one per line.
#[allow(clippy::print_stderr)]
fn print_error(error: &anyhow::Error) {
    eprintln!("error: {error}");
    for cause in error.chain().skip(1) {
        eprintln!("  caused by: {cause}");
    }
}
