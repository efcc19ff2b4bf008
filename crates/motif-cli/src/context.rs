//! What a running command gets from the CLI, and the report it leaves behind.

use std::io::IsTerminal;
use std::path::Path;

use anyhow::bail;
use motif_core::Progress;
use serde::Serialize;
use serde_json::{Map, Value};

use crate::progress::CliProgress;

/// The environment of one engine run: seed, threads, progress and the figures for the report.
pub struct Context {
    /// The run's seed (`--seed`).
    pub seed: u64,
    /// Worker threads in use.
    pub threads: usize,
    /// True with `--quiet`: engines print no summary.
    pub quiet: bool,
    /// `--max-memory` in bytes (default: half of the machine's memory), passed to every job.
    pub max_memory: u64,
    progress: CliProgress,
    figures: Map<String, Value>,
    /// `--report`, checked against every input the engine names.
    report: Option<std::path::PathBuf>,
    /// Every input path the engine named (see [`Context::check_output`]).
    inputs: std::cell::RefCell<Vec<std::path::PathBuf>>,
    /// Every output path checked so far.
    outputs: std::cell::RefCell<Vec<std::path::PathBuf>>,
}

impl Context {
    /// A context for one run.
    pub fn new(seed: u64, threads: usize, quiet: bool) -> Self {
        let visible = !quiet && std::io::stderr().is_terminal();
        Self {
            seed,
            threads,
            quiet,
            max_memory: motif_core::DEFAULT_MAX_MEMORY,
            progress: CliProgress::new(visible),
            figures: Map::new(),
            report: None,
            inputs: std::cell::RefCell::new(Vec::new()),
            outputs: std::cell::RefCell::new(Vec::new()),
        }
    }

    /// The same context with a memory limit for every job.
    pub fn with_max_memory(mut self, bytes: u64) -> Self {
        self.max_memory = bytes;
        self
    }

    /// The same context with `--report` to check against the inputs.
    pub fn with_report(mut self, report: Option<&Path>) -> Self {
        self.report = report.map(Path::to_path_buf);
        self
    }

    /// True when `path` names one of the inputs the engine checked its outputs against, or one of
    /// its outputs.
    pub fn is_input_or_output(&self, path: &Path) -> bool {
        self.inputs.borrow().iter().chain(self.outputs.borrow().iter()).any(|other| motif_io::same_file(path, other))
    }

    /// The progress sink to hand to an engine.
    pub fn progress(&mut self) -> &mut dyn Progress {
        &mut self.progress
    }

    /// Records a figure for the report (later values replace earlier ones under the same key).
    pub fn figure(&mut self, key: &str, value: impl Serialize) {
        let value =
            serde_json::to_value(value).unwrap_or_else(|error| Value::String(format!("unserializable: {error}")));
        self.figures.insert(key.to_string(), value);
    }

    /// Records a job's figures (`motif_jobs`), except its `command`: the report names the
    /// subcommand as typed.
    pub fn job_figures(&mut self, figures: Map<String, Value>) {
        for (key, value) in figures {
            if key != "command" {
                self.figures.insert(key, value);
            }
        }
    }

    /// Records an engine's own per-stage timings as the report's `stages_ms` (replacing the
    /// timings the CLI took from progress).
    pub fn stages(&mut self, stages: &[(String, f64)]) {
        self.figures.insert("stages_ms".to_string(), stages_object(stages));
    }

    /// Refuses an output path (and `--report`) that names one of the inputs: motif never
    /// overwrites its input.
    pub fn check_output(&self, output: &Path, inputs: &[&Path]) -> anyhow::Result<()> {
        self.inputs.borrow_mut().extend(inputs.iter().map(|input| input.to_path_buf()));
        if let Some(report) = &self.report {
            check_writable(report)?;
            if inputs.iter().any(|input| motif_io::same_file(report, input)) {
                bail!(
                    "report {} is also an input; choose another --report path (motif never overwrites an input)",
                    report.display()
                );
            }
        }
        check_writable(output)?;
        let earlier = self.outputs.borrow().iter().chain(&self.report).any(|other| motif_io::same_file(output, other));
        // Recorded first, so that a report on the same path is not written either.
        self.outputs.borrow_mut().push(output.to_path_buf());
        if earlier {
            bail!("output {} is given twice; each output needs its own path", output.display());
        }
        for input in inputs {
            if motif_io::same_file(output, input) {
                bail!(
                    "output {} is also an input; choose another output path (motif never overwrites an input)",
                    output.display()
                );
            }
        }
        Ok(())
    }

    /// Prints a one-line summary on stderr unless quiet.
    #[allow(clippy::print_stderr)]
    pub fn summary(&self, line: &str) {
        if !self.quiet {
            eprintln!("{line}");
        }
    }

    /// Ends the run: the figures, with `stages_ms` from progress unless the engine gave its own.
    pub fn into_figures(mut self) -> Map<String, Value> {
        let stages = self.progress.finish();
        if !self.figures.contains_key("stages_ms") {
            let stages: Map<String, Value> = stages.into_iter().map(|(name, ms)| (name, Value::from(ms))).collect();
            self.figures.insert("stages_ms".to_string(), Value::Object(stages));
        }
        self.figures
    }
}

/// Refuses, before any work, an output that cannot be written: a folder that does not exist, or a
/// path that is a folder. (Found only at write time, such a path failed the run after the main
/// output had already replaced the previous file.)
pub fn check_writable(output: &Path) -> anyhow::Result<()> {
    if output.is_dir() {
        bail!("output {} is a folder; give a file name", output.display());
    }
    let folder = match output.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    if !folder.is_dir() {
        bail!("cannot write {}: the folder {} does not exist", output.display(), folder.display());
    }
    Ok(())
}

/// `(stage, milliseconds)` pairs as a JSON object, in order.
pub fn stages_object(stages: &[(String, f64)]) -> Value {
    Value::Object(stages.iter().map(|(name, ms)| (name.clone(), Value::from(*ms))).collect())
}
