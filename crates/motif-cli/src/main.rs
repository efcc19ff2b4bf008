//! `motif`: one command line for every motif engine.
//!
//! Modules, from the bottom up (each uses only those above it; `main` wires them together):
//! - [`options`]: the options every command accepts; [`job_args`]: a job's declared options as
//!   flags; [`progress`]: progress bars on stderr.
//! - [`context`]: what a running command gets (seed, threads, progress, report figures, the
//!   checks that keep outputs off inputs).
//! - [`gallery`]: the cases of `motif demo` and their HTML page; [`suite`]: what a benchmark gets.
//! - [`registry`]: the [`registry::Engine`] trait that `demo` and `bench` receive.
//! - [`engines`]: one folder per engine subcommand (`curve`, `points`, `strokes`, `stylize` with
//!   `texture`) and the list of engines.
//! - [`demo`](mod@demo): `motif demo`; [`bench`](mod@bench): `motif bench`, the single entry point for performance figures.
//! - `reference` (tests only): `docs/cli.md`, rendered from the clap definitions.
//! - `main.rs`: argument parsing (clap derive), running a subcommand with its report, error
//!   printing and exit codes.

#![allow(
    clippy::disallowed_methods,
    reason = "the command line never runs in WebAssembly: its own arithmetic (demo inputs, previews, bench shapes) \
              may use the platform's math library, which the workspace's clippy.toml forbids in the engines"
)]
mod bench;
mod context;
mod demo;
mod engines;
mod gallery;
mod job_args;
mod options;
mod progress;
#[cfg(test)]
mod reference;
mod registry;
mod suite;

use std::process::ExitCode;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};

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

/// How a command whose normal end is Ctrl-C (the tile server) stops gracefully: the first
/// interrupt calls it (the command then ends as it does by itself, exit code 0), a second one
/// exits at once as interrupted. Other commands register none: an interrupt stops them at once.
static GRACEFUL_STOP: OnceLock<Box<dyn Fn() + Send + Sync>> = OnceLock::new();

/// Makes Ctrl-C (and SIGTERM) call `stop` instead of ending the process (see [`GRACEFUL_STOP`]).
pub(crate) fn stop_on_interrupt_with(stop: impl Fn() + Send + Sync + 'static) {
    let _ = GRACEFUL_STOP.set(Box::new(stop));
}

/// glibc's allocator set for a long-running process, first thing (before any other thread):
/// blocks of up to 32 MiB come from its arenas, and up to 64 MiB of freed memory at an arena's
/// top stay there. glibc moves its own thresholds towards these values only once the process has
/// freed a large block; until then it handed every freed top over 128 KiB back to the kernel,
/// so a tile server's or the bench's thread faulted its whole working set in again for every
/// map tile (about 4.5 MB; `motif bench --engine stylize --case tiles` took 237 000 page faults,
/// 40 500 with these values), 2–3 ms of a 13–16 ms tile. The peak resident size of a
/// 2048 × 1536 texture moved by 1 % (`docs/maps.md`, "Speed").
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn tune_allocator() {
    const MMAP_THRESHOLD: i32 = 32 << 20;
    const TRIM_THRESHOLD: i32 = 64 << 20;
    // SAFETY: `mallopt` only sets two parameters of glibc's allocator (it takes the allocator's
    // own lock), with values in the ranges glibc documents.
    #[allow(unsafe_code, reason = "glibc's allocator thresholds, measured: see the doc comment")]
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD);
        libc::mallopt(libc::M_TRIM_THRESHOLD, TRIM_THRESHOLD);
    }
}

fn main() -> ExitCode {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    tune_allocator();
    // A panic is a bug in motif, never the user's fault: say so plainly instead of a backtrace.
    std::panic::set_hook(Box::new(|info| {
        #[allow(clippy::print_stderr, reason = "errors and warnings go to the terminal")]
        {
            eprintln!("error: internal error (a bug in motif; please report it with the command you ran): {info}");
        }
    }));
    // Ctrl-C or SIGTERM: let a commit of the outputs in progress finish (a run's outputs replace
    // the previous files all together or not at all), remove the temporary files of writes in
    // progress and of outputs not committed, and exit as interrupted. A server stops gracefully
    // on the first one instead.
    static INTERRUPTED_ONCE: AtomicBool = AtomicBool::new(false);
    let interrupted = ctrlc::set_handler(|| {
        if let Some(stop) = GRACEFUL_STOP.get()
            && !INTERRUPTED_ONCE.swap(true, Ordering::SeqCst)
        {
            stop();
            return;
        }
        motif_io::stop_outputs();
        #[allow(clippy::print_stderr, reason = "errors and warnings go to the terminal")]
        {
            eprintln!("error: interrupted");
        }
        std::process::exit(130);
    });
    if let Err(error) = interrupted {
        print_error(&anyhow::anyhow!("cannot install the interrupt handler: {error}"));
        return ExitCode::FAILURE;
    }
    let cli = match Cli::try_parse_from(engines::curve::tile_files_as_image_flags(std::env::args_os())) {
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
#[allow(clippy::print_stderr, reason = "errors and warnings go to the terminal")]
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
    // The peak is measured from here; what the process holds now counts in every estimate
    // compared with --max-memory (small runs are mostly the program itself).
    motif_io::reset_peak_memory();
    let resident = motif_io::resident_memory().unwrap_or(0);
    let mut context = Context::new(global.seed, threads, global.quiet)
        .with_max_memory(options::max_memory(global), resident)
        .with_report(global.report.as_deref());
    motif_io::begin_outputs();
    let mut result = context.check_resident();
    if result.is_ok()
        && let Some(path) = &global.report
    {
        result = context.check_writable(path);
    }
    if result.is_ok() {
        result = command.run(&mut context).map_err(|error| context.whole_process_memory(error));
    }
    let peak = motif_io::peak_memory();
    let report_path = global.report.as_deref().filter(|path| !context.is_input_or_output(path));
    let failed_report = report_path.filter(|path| context.check_writable(path).is_ok());
    let mut report = Map::new();
    report.insert("motif_version".into(), Value::from(env!("CARGO_PKG_VERSION")));
    report.insert("command".into(), Value::from(command.name()));
    report.insert("arguments".into(), Value::from(std::env::args().skip(1).collect::<Vec<_>>()));
    report.insert("seed".into(), Value::from(global.seed));
    report.insert("threads".into(), Value::from(threads));
    report.insert("total_ms".into(), Value::from(start.elapsed().as_secs_f64() * 1000.0));
    report.insert("max_memory_bytes".into(), Value::from(context.memory_limit));
    report.insert("resident_at_start_bytes".into(), Value::from(resident));
    report.insert("reserved_memory_bytes".into(), Value::from(context.reserved));
    report.insert("peak_resident_bytes".into(), peak.map_or(Value::Null, Value::from));
    let held = context.held_beside_job();
    report.extend(context.into_figures());
    // The estimate compared with --max-memory: the job's, what the process held at the start and
    // what the CLI holds beside the job.
    if let Some(estimate) = report.get("estimated_memory_bytes").and_then(Value::as_u64) {
        report.insert("estimated_peak_bytes".into(), Value::from(estimate.saturating_add(held)));
    }
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

    /// `docs/cli.md` is the reference rendered from these definitions (`MOTIF_BLESS=1` rewrites it).
    #[test]
    fn cli_reference_is_current() {
        let mut command = Cli::command();
        command.build();
        let rendered = crate::reference::markdown(&command);
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").join(crate::reference::PATH);
        if std::env::var_os("MOTIF_BLESS").is_some() {
            std::fs::write(&path, &rendered).unwrap();
        }
        let committed = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            committed == rendered,
            "{} is stale: regenerate it with `MOTIF_BLESS=1 cargo test --release -p motif-cli cli_reference`",
            crate::reference::PATH
        );
    }

    /// Every option a job declares is a flag of its subcommand with the declared default and
    /// help, and is in `docs/cli.md`; a command line without it gives the job's default options.
    #[test]
    fn every_declared_option_is_a_flag_and_documented() {
        let mut command = Cli::command();
        command.build();
        let reference = crate::reference::markdown(&command);
        for job in motif_jobs::JOBS {
            let sub = command.find_subcommand(job.name).unwrap_or_else(|| panic!("no subcommand {}", job.name));
            for spec in (job.options)() {
                let arg = sub
                    .get_arguments()
                    .find(|arg| arg.get_long() == Some(spec.name.as_str()))
                    .unwrap_or_else(|| panic!("motif {} has no --{}", job.name, spec.name));
                if spec.kind != motif_jobs::options::Kind::Flag {
                    let default = arg.get_default_values().first().map(|v| v.to_string_lossy().into_owned());
                    assert_eq!(default, spec.default, "motif {} --{}", job.name, spec.name);
                }
                assert_eq!(arg.get_help().map(ToString::to_string), Some(spec.described()), "--{}", spec.name);
                assert!(reference.contains(&format!("--{}", spec.name)), "docs/cli.md lacks --{}", spec.name);
            }
        }
    }

    /// Every job of `motif_jobs::JOBS` is a subcommand whose help opens with the job's summary,
    /// has a section in `docs/cli.md`, and every subcommand but `demo`, `bench` and `help` is a job.
    #[test]
    fn every_job_is_a_subcommand_and_documented() {
        let mut command = Cli::command();
        command.build();
        let reference = crate::reference::markdown(&command);
        for job in motif_jobs::JOBS {
            let sub = command.find_subcommand(job.name).unwrap_or_else(|| panic!("no subcommand {}", job.name));
            assert_eq!(sub.get_about().map(ToString::to_string).as_deref(), Some(job.summary), "motif {}", job.name);
            let long = sub.get_long_about().map(ToString::to_string).unwrap_or_default();
            assert!(long.starts_with(job.summary) && long.ends_with(job.details), "motif {}: {long}", job.name);
            let section = format!("## motif {}\n", job.name);
            assert!(reference.contains(&section) && reference.contains(job.details), "docs/cli.md lacks {section}");
        }
        for sub in command.get_subcommands().map(|sub| sub.get_name()) {
            let tools = ["demo", "bench", "help"];
            assert!(tools.contains(&sub) || motif_jobs::JobEntry::named(sub).is_some(), "{sub} is not a job");
        }
    }

    /// Every command's help lists the global options under their own heading, after its own.
    #[test]
    fn global_options_have_their_own_heading() {
        let mut command = Cli::command();
        command.build();
        for sub in command.get_subcommands_mut().filter(|sub| sub.get_name() != "help") {
            let help = sub.render_long_help().to_string();
            let heading =
                help.find("Global options:").unwrap_or_else(|| panic!("{}: no heading\n{help}", sub.get_name()));
            for flag in ["--seed", "--threads", "--max-memory", "--quiet", "--report"] {
                let at = help.find(&format!("{flag} ")).or_else(|| help.find(&format!("{flag}\n")));
                assert!(at.is_some_and(|at| at > heading), "{}: {flag} is not under the heading", sub.get_name());
            }
        }
    }

    /// The first number after each "default" in `text` (a stated default), as written.
    fn stated_defaults(text: &str) -> Vec<String> {
        let lower = text.to_lowercase();
        lower
            .match_indices("default")
            .filter_map(|(at, _)| {
                let after: String = lower[at..].chars().skip("default".len()).take(24).collect();
                let clause = after.split("; ").next().and_then(|c| c.split(". ").next()).unwrap_or("").to_string();
                let start = clause.find(|c: char| c.is_ascii_digit())?;
                Some(clause[start..].chars().take_while(|c| c.is_ascii_digit() || *c == '.').collect())
            })
            .filter(|number: &String| !number.is_empty())
            .collect()
    }

    /// A default a help text states in prose is the one in effect: for an option with a declared
    /// default, that value; for one whose default the engine infers or computes, the engine's.
    #[test]
    fn defaults_stated_in_help_are_the_real_ones() {
        let points = motif_points::Params::default();
        let all = points.clone().with_refinement(motif_points::Refinement::Everywhere);
        let strokes = motif_strokes::Params::default();
        let inferred: &[(&str, &str, f64)] = &[
            ("points", "keep-margin", motif_points::Params::DEFAULT_KEEP_MARGIN),
            ("points", "neighbourhood", motif_points::Params::NEIGHBOURHOOD_SPACINGS[0]),
            ("points", "attribute-weight", points.attribute_weight),
            ("points", "quadrature-spacing", motif_points::Params::DEFAULT_QUADRATURE_SPACING),
            ("points", "shrink", all.effective_shrink()),
            ("strokes", "rings", strokes.rings_for(true) as f64),
            ("strokes", "thresholds", strokes.thresholds.shape),
        ];
        let mut command = Cli::command();
        command.build();
        let mut checked = 0;
        for sub in command.get_subcommands() {
            for arg in sub.get_arguments().filter(|arg| !arg.is_global_set() || sub.get_name() == "curve") {
                let mut help = arg.get_long_help().or(arg.get_help()).map(ToString::to_string).unwrap_or_default();
                for value in arg.get_possible_values() {
                    help.push(' ');
                    help.push_str(&value.get_help().map(ToString::to_string).unwrap_or_default());
                }
                let flag = arg.get_id().as_str();
                for stated in stated_defaults(&help) {
                    let stated: f64 = stated.trim_end_matches('.').parse().unwrap();
                    let declared = arg.get_default_values().first().and_then(|v| v.to_str()?.parse::<f64>().ok());
                    let engine = inferred
                        .iter()
                        .find(|(command, name, _)| *command == sub.get_name() && name.replace('-', "_") == flag)
                        .map(|entry| entry.2);
                    let real = declared.or(engine).unwrap_or_else(|| {
                        panic!(
                            "{} --{flag}: its help states a default of {stated}; list the engine's value here",
                            sub.get_name()
                        )
                    });
                    assert!(
                        (stated - real).abs() < 1e-9,
                        "{} --{flag}: help says default {stated}, the default is {real}",
                        sub.get_name()
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked >= inferred.len(), "only {checked} stated defaults found");
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
