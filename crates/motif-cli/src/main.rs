//! `motif`: one command line for every motif engine.
//!
//! Modules, from the bottom up (each uses only those above it; `main` wires them together):
//! - [`options`]: the options every command accepts; [`progress`]: progress bars on stderr.
//! - [`context`]: what a running command gets (seed, threads, progress, report figures, the
//!   checks that keep outputs off inputs).
//! - [`gallery`]: the cases of `motif demo` and their HTML page; [`suite`]: what a benchmark gets.
//! - [`registry`]: the [`registry::Engine`] trait that `demo` and `bench` receive.
//! - [`engines`]: one folder per engine subcommand (`curve`, `points`, `strokes`, `stylize` with
//!   `texture`) and the list of engines.
//! - [`demo`](mod@demo): `motif demo`; [`bench`](mod@bench): `motif bench`, the single entry point for performance figures.
//! - `main.rs`: argument parsing (clap derive), running a subcommand with its report, error
//!   printing and exit codes.

mod bench;
mod context;
mod demo;
mod engines;
mod gallery;
mod options;
mod progress;
mod registry;
mod suite;

use std::process::ExitCode;

use anyhow::{Context as _, bail};
use clap::{Parser, Subcommand};
use serde_json::{Map, Value};

use crate::context::Context;
use crate::engines::{ENGINES, EngineCommand};
use crate::options::GlobalArgs;

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

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    #[command(flatten)]
    /// Engine subcommands.
    Engine(Box<EngineCommand>),
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
    // Ctrl-C or SIGTERM: let a commit of the outputs in progress finish (a run's outputs replace
    // the previous files all together or not at all), remove the temporary files of writes in
    // progress and of outputs not committed, and exit as interrupted.
    let interrupted = ctrlc::set_handler(|| {
        motif_io::stop_outputs();
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
        Command::Engine(command) => run_engine(command, &cli.global, threads),
        Command::Demo(args) => demo::run(args, &cli.global, threads, ENGINES, &run_demo_case),
        Command::Bench(args) => bench::run(args, &cli.global, threads, ENGINES),
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

/// Runs an engine subcommand and writes `--report` if asked.
///
/// Every output, the report included, is staged and committed together once all were written:
/// a run that fails at any point (the report too) leaves every previous file as it was. A failed
/// run still writes its report, with its error, where that replaces neither an input nor one of
/// the run's outputs.
fn run_engine(command: &EngineCommand, global: &GlobalArgs, threads: usize) -> anyhow::Result<()> {
    let start = std::time::Instant::now();
    let mut context = Context::new(global.seed, threads, global.quiet)
        .with_max_memory(options::max_memory(global))
        .with_report(global.report.as_deref());
    motif_io::begin_outputs();
    let mut result = match &global.report {
        Some(path) => context.check_writable(path),
        None => Ok(()),
    };
    if result.is_ok() {
        result = command.run(&mut context);
    }
    let report_path = global.report.as_deref().filter(|path| !context.is_input_or_output(path));
    let failed_report = report_path.filter(|path| context.check_writable(path).is_ok());
    let mut report = Map::new();
    report.insert("motif_version".into(), Value::from(env!("CARGO_PKG_VERSION")));
    report.insert("command".into(), Value::from(command.name()));
    report.insert("arguments".into(), Value::from(std::env::args().skip(1).collect::<Vec<_>>()));
    report.insert("seed".into(), Value::from(global.seed));
    report.insert("threads".into(), Value::from(threads));
    report.insert("total_ms".into(), Value::from(start.elapsed().as_secs_f64() * 1000.0));
    report.extend(context.into_figures());
    let with_status = |mut report: Map<String, Value>, result: &anyhow::Result<()>| {
        report.insert("status".into(), Value::from(if result.is_ok() { "ok" } else { "failed" }));
        if let Err(error) = result {
            report.insert("error".into(), Value::from(format!("{error:#}")));
        }
        Value::Object(report)
    };
    if result.is_ok()
        && let Some(path) = report_path
    {
        // Staged like the outputs: the report is committed with them, last.
        result = motif_io::write_json(path, &with_status(report.clone(), &result))
            .with_context(|| "cannot write the report");
    }
    if result.is_ok() {
        result = motif_io::commit_outputs().map_err(anyhow::Error::from);
    } else {
        motif_io::discard_outputs();
    }
    if result.is_err()
        && let Some(path) = failed_report
    {
        // Written at once (the run's outputs are discarded); the run keeps its own error.
        let _ = motif_io::write_json(path, &with_status(report, &result));
    }
    result
}

/// Runs one demo case: its arguments (after `motif`) parsed as the command line would be.
fn run_demo_case(args: &[String], context: &mut Context) -> anyhow::Result<()> {
    let cli = Cli::try_parse_from(std::iter::once("motif".to_string()).chain(args.iter().cloned()))
        .context("invalid arguments")?;
    let Command::Engine(command) = &cli.command else { bail!("a demo case must run an engine") };
    command.run(context)
}

#[cfg(test)]
mod tests {
    use clap::{CommandFactory, Parser};
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngSeed};

    use super::Cli;

    /// Every `--flag` of every subcommand (and the global ones).
    fn flags() -> Vec<String> {
        let command = Cli::command();
        let mut flags: Vec<String> = command.get_arguments().filter_map(|a| a.get_long()).map(str::to_string).collect();
        for sub in command.get_subcommands() {
            flags.extend(sub.get_arguments().filter_map(|a| a.get_long()).map(str::to_string));
        }
        flags.sort_unstable();
        flags.dedup();
        flags.into_iter().map(|flag| format!("--{flag}")).collect()
    }

    fn subcommands() -> Vec<String> {
        Cli::command().get_subcommands().map(|sub| sub.get_name().to_string()).collect()
    }

    /// Values as careless hands and scripts write them.
    fn token() -> impl Strategy<Value = String> {
        prop_oneof![
            proptest::sample::select(vec![
                "-1",
                "0",
                "1e-300",
                "1e300",
                "NaN",
                "inf",
                "-inf",
                "64x64",
                "0x0",
                "16384x16384",
                "99999999999x2",
                "box:4,4",
                "box:1e300,1",
                "box:",
                "corners",
                "1,2,3,4",
                "a=1",
                "=",
                "8G",
                "0.5M",
                "auto",
                "exact",
                "",
                "x",
                ",",
                "#ff00ff",
                "-",
                "--",
            ])
            .prop_map(str::to_string),
            "[ -~]{0,12}",
        ]
    }

    proptest! {
        #![proptest_config(Config { cases: 512, rng_seed: RngSeed::Fixed(20261202), failure_persistence: None, ..Config::default() })]

        /// Any command line parses or gives clap's usage error; none panics (value parsers
        /// included: sizes, memory sizes, ranges, enums).
        #[test]
        fn random_command_lines_parse_or_fail_cleanly(
            sub in proptest::sample::select(subcommands()),
            parts in proptest::collection::vec((proptest::sample::select(flags()), token(), any::<bool>()), 0..8),
        ) {
            let mut arguments = vec!["motif".to_string(), sub];
            for (flag, value, with_value) in parts {
                arguments.push(flag);
                if with_value {
                    arguments.push(value);
                }
            }
            if let Err(error) = Cli::try_parse_from(&arguments) {
                prop_assert!(!error.to_string().is_empty());
            }
        }
    }
}
