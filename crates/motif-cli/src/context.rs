//! What a running command gets from the CLI, and the report it leaves behind.
//!
//! Also the run's output plan: before any work, each engine names every file it will write (with
//! [`Context::check_output`], [`Context::check_outputs_in`] for files in a folder made if missing,
//! [`Context::check_output_folder`] for a folder whose files depend on the run) and the inputs to
//! keep them off. Each is checked against every input (the same file through another spelling or
//! a link, or a file in an input folder), against the other outputs and `--report`, and for a
//! folder that takes files. The outputs are staged and committed together after the run (see
//! `run_engine` in `main.rs`).

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use motif_core::Progress;
use motif_core::memory::Bytes;
use serde::Serialize;
use serde_json::{Map, Value};

use crate::progress::CliProgress;

/// What a run holds beyond the resident size at its start and the job's estimate, whatever the
/// job: files read and written, the report, the worker threads' allocator state (measured 2.0–2.6
/// MiB for runs whose job estimate is under 0.3 MiB, at 1 to 16 threads).
pub(crate) const WORKING_OVERHEAD: u64 = 2 << 20;

/// The environment of one engine run: seed, threads, progress and the figures for the report.
#[derive(Debug)]
pub struct Context {
    /// The run's seed (`--seed`).
    pub seed: u64,
    /// Worker threads in use.
    pub threads: usize,
    /// True with `--quiet`: engines print no summary.
    pub quiet: bool,
    /// The share of `--max-memory` passed to every job: the limit less what the process held
    /// when the run started (see [`Context::with_max_memory`]).
    pub max_memory: u64,
    /// `--max-memory` in bytes (default: half of the machine's memory).
    pub memory_limit: u64,
    /// Resident bytes when the run started (the program, its threads, the allocator): counted in
    /// every estimate compared with `--max-memory`.
    pub resident_at_start: u64,
    /// What the CLI itself holds beside the job (see [`Context::reserve`]), bytes.
    pub reserved: u64,
    progress: CliProgress,
    figures: Map<String, Value>,
    /// `--report`, checked against every input the engine names.
    report: Option<PathBuf>,
    /// The files this run writes and reads, as far as the engine has named them.
    plan: std::cell::RefCell<Plan>,
}

/// The output plan of a run (see the module's documentation).
#[derive(Debug, Default)]
struct Plan {
    /// Every input the engine named: files, or folders whose files it reads (a presynth cache).
    inputs: Vec<PathBuf>,
    /// Every output file checked so far.
    outputs: Vec<PathBuf>,
    /// Folders the outputs go into, made at write time if missing, each checked once.
    folders: Vec<PathBuf>,
    /// Folders whose files all count as outputs (their names depend on the run).
    whole_folders: Vec<PathBuf>,
}

/// The folder a file is in (`.` for a bare name).
fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    }
}

/// True when `path` lies directly in `folder`.
fn inside(path: &Path, folder: &Path) -> bool {
    motif_io::same_file(folder_of(path), folder)
}

/// True when writing `output` would replace `input`: the same file, or a file of an input folder.
fn replaces(output: &Path, input: &Path) -> bool {
    motif_io::same_file(output, input) || (input.is_dir() && inside(output, input))
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
            memory_limit: motif_core::DEFAULT_MAX_MEMORY,
            resident_at_start: 0,
            reserved: WORKING_OVERHEAD,
            progress: CliProgress::new(visible),
            figures: Map::new(),
            report: None,
            plan: std::cell::RefCell::new(Plan::default()),
        }
    }

    /// The same context with the memory limit `bytes` for the whole process, `resident` of which
    /// the process holds before the run: the jobs get the rest (at least the smallest limit they
    /// take; [`Context::check_resident`] refuses a limit below that first).
    pub fn with_max_memory(mut self, bytes: u64, resident: u64) -> Self {
        self.memory_limit = bytes;
        self.resident_at_start = resident;
        self.share();
        self
    }

    /// Counts `bytes` the CLI holds beside the job (a rendered preview, decoded maps) in the
    /// estimate compared with `--max-memory`: the jobs built after this get that much less.
    pub fn reserve(&mut self, bytes: u64) {
        self.reserved = self.reserved.saturating_add(bytes);
        self.share();
    }

    /// Counts rendering `svg` at `scale` (its parsed tree, about 1 KiB an element; its text; its
    /// pixels about three times: canvas, image, encoding) in the estimate, and refuses it before
    /// it starts when that and the job's estimate pass `--max-memory`.
    pub fn check_render(&mut self, job_estimate: u64, svg: &str, scale: f64) -> anyhow::Result<()> {
        let elements = svg.bytes().filter(|&b| b == b'<').count() as f64;
        let pixels = svg_size(svg).map_or(0.0, |(width, height)| width * height * scale * scale);
        let bytes = (elements * 1024.0 + svg.len() as f64 + pixels * 12.0).min(u64::MAX as f64) as u64;
        self.reserve(bytes);
        let needed = self.held_beside_job().saturating_add(job_estimate);
        if needed > self.memory_limit {
            bail!(
                "rendering the PNG would bring the run to about {} of memory, more than the {} allowed \
                 (--max-memory): {} for the rendering; render at a smaller scale or raise --max-memory",
                Bytes(needed),
                Bytes(self.memory_limit),
                Bytes(bytes)
            );
        }
        Ok(())
    }

    /// What the process holds beside the job's estimate: at the start, and reserved.
    pub fn held_beside_job(&self) -> u64 {
        self.resident_at_start.saturating_add(self.reserved)
    }

    fn share(&mut self) {
        let held = self.held_beside_job();
        self.max_memory = self.memory_limit.saturating_sub(held).max(motif_core::memory::MIN_MAX_MEMORY);
    }

    /// Refuses a `--max-memory` that leaves the run less than 1 MiB after what the process holds
    /// before any work.
    pub fn check_resident(&self) -> anyhow::Result<()> {
        let (limit, held) = (self.memory_limit, self.held_beside_job());
        if held.saturating_add(motif_core::memory::MIN_MAX_MEMORY) > limit {
            bail!(
                "--max-memory {} leaves no room for the run: this program holds about {} before any work (raise \
                 --max-memory)",
                Bytes(limit),
                Bytes(held)
            );
        }
        Ok(())
    }

    /// `error` with a memory refusal of a job restated for the whole process: the estimate plus
    /// what the process held at the start, against `--max-memory` itself.
    pub fn whole_process_memory(&self, error: anyhow::Error) -> anyhow::Error {
        let refusal = error.chain().find_map(|cause| {
            cause.downcast_ref::<motif_core::TooMuchMemory>().or_else(|| {
                cause.downcast_ref::<motif_jobs::JobError>().and_then(motif_jobs::JobError::too_much_memory)
            })
        });
        let Some(refusal) = refusal else { return error };
        let whole = motif_core::TooMuchMemory {
            needed: refusal.needed.saturating_add(self.held_beside_job()),
            limit: self.memory_limit,
            ..refusal.clone()
        };
        let message = format!(
            "{whole} (--max-memory; the estimate counts the {} this program holds beside the run: {} at its \
             start, {} for files and its own images)",
            Bytes(self.held_beside_job()),
            Bytes(self.resident_at_start),
            Bytes(self.reserved)
        );
        let outer = error.to_string();
        if outer == refusal.to_string() || error.chain().count() == 1 {
            anyhow::anyhow!(message)
        } else {
            anyhow::anyhow!(message).context(outer)
        }
    }

    /// The same context with `--report` to check against the inputs.
    pub fn with_report(mut self, report: Option<&Path>) -> Self {
        self.report = report.map(Path::to_path_buf);
        self
    }

    /// True when writing `path` would replace one of the inputs the engine named or one of its
    /// outputs (a failed run's report is then not written).
    pub fn is_input_or_output(&self, path: &Path) -> bool {
        let plan = self.plan.borrow();
        plan.inputs.iter().any(|input| replaces(path, input))
            || plan.outputs.iter().any(|output| motif_io::same_file(path, output))
            || plan.whole_folders.iter().any(|folder| inside(path, folder))
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

    /// Plans the output file `output`: refuses, before any work, one that would replace one of
    /// `inputs` (or a file of an input folder), one given twice (or as `--report`), one in a
    /// folder whose files are all outputs, and one that cannot be written (see
    /// [`Context::check_writable`]); refuses `--report` naming one of `inputs`. Motif never
    /// overwrites its input.
    pub fn check_output(&self, output: &Path, inputs: &[&Path]) -> anyhow::Result<()> {
        self.add_inputs(inputs)?;
        self.check_writable(output)?;
        let plan = &mut *self.plan.borrow_mut();
        let earlier = plan.outputs.iter().chain(&self.report).any(|other| motif_io::same_file(output, other));
        // Recorded first, so that a report on the same path is not written either.
        plan.outputs.push(output.to_path_buf());
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
            if input.is_dir() && inside(output, input) {
                bail!(
                    "output {} is in the folder {}, which is an input; choose another output path (motif never \
                     overwrites an input)",
                    output.display(),
                    input.display()
                );
            }
        }
        if let Some(folder) = plan.whole_folders.iter().find(|folder| inside(output, folder)) {
            bail!(
                "output {} is in {}, whose files this command writes; choose another output path",
                output.display(),
                folder.display()
            );
        }
        Ok(())
    }

    /// Plans the output files `outputs`, all in `folder`, which is made at write time if missing
    /// (`--debug-dir`, zoom levels): see [`Context::check_output`].
    pub fn check_outputs_in(&self, folder: &Path, outputs: &[PathBuf], inputs: &[&Path]) -> anyhow::Result<()> {
        self.plan_folder(folder)?;
        outputs.iter().try_for_each(|output| self.check_output(output, inputs))
    }

    /// Plans the folder `folder` (given as `flag`) as an output whose files depend on the run (presynth's cache),
    /// made at write time if missing: refuses, before any work, a folder that holds one of
    /// `inputs` or `--report`, and, later, every other output in it.
    pub fn check_output_folder(&self, flag: &str, folder: &Path, inputs: &[&Path]) -> anyhow::Result<()> {
        self.add_inputs(inputs)?;
        // Recorded first, so that a failed run's report does not go there either.
        self.plan.borrow_mut().whole_folders.push(folder.to_path_buf());
        self.plan_folder(folder)?;
        for input in inputs {
            if inside(input, folder) {
                bail!(
                    "input {} lies in the {flag} folder {}, whose files this command replaces; move it out or \
                     choose another folder (motif never overwrites an input)",
                    input.display(),
                    folder.display()
                );
            }
        }
        if let Some(report) = self.report.as_deref().filter(|report| inside(report, folder)) {
            bail!(
                "report {} lies in the {flag} folder {}, whose files this command writes; choose another --report \
                 path",
                report.display(),
                folder.display()
            );
        }
        Ok(())
    }

    /// Records `inputs`, and refuses `--report` naming one of them.
    fn add_inputs(&self, inputs: &[&Path]) -> anyhow::Result<()> {
        self.plan.borrow_mut().inputs.extend(inputs.iter().map(|input| input.to_path_buf()));
        if let Some(report) = &self.report
            && inputs.iter().any(|input| replaces(report, input))
        {
            bail!(
                "report {} is also an input; choose another --report path (motif never overwrites an input)",
                report.display()
            );
        }
        Ok(())
    }

    /// Plans a folder for outputs, made at write time if missing: refuses a file, and a folder
    /// that cannot be made or takes no files.
    fn plan_folder(&self, folder: &Path) -> anyhow::Result<()> {
        if self.plan.borrow().folders.iter().any(|planned| motif_io::same_file(planned, folder)) {
            return Ok(());
        }
        if folder.exists() && !folder.is_dir() {
            bail!("{} is a file; give a folder", folder.display());
        }
        // The folder itself, or the nearest one above it that exists (where it will be made).
        let mut existing = folder;
        while !existing.as_os_str().is_empty() && !existing.exists() {
            existing = existing.parent().unwrap_or(Path::new(""));
        }
        if existing.as_os_str().is_empty() {
            existing = Path::new(".");
        }
        if !existing.is_dir() {
            bail!("cannot make the folder {}: {} is a file", folder.display(), existing.display());
        }
        motif_io::check_folder_writable(existing)
            .with_context(|| format!("cannot write into the folder {}", folder.display()))?;
        self.plan.borrow_mut().folders.push(folder.to_path_buf());
        Ok(())
    }

    /// Refuses, before any work, an output that cannot be written: a path that is a folder, a
    /// folder that does not exist (unless planned), or one that takes no files (`/proc`, a
    /// read-only mount, permissions). Found only at write time, such a path failed the run
    /// after all its work.
    pub fn check_writable(&self, output: &Path) -> anyhow::Result<()> {
        if output.is_dir() {
            bail!("output {} is a folder; give a file name", output.display());
        }
        let folder = folder_of(output);
        if self.plan.borrow().folders.iter().any(|planned| motif_io::same_file(planned, folder)) {
            return Ok(());
        }
        if !folder.is_dir() {
            bail!("cannot write {}: the folder {} does not exist", output.display(), folder.display());
        }
        motif_io::check_folder_writable(folder).with_context(|| format!("cannot write {}", output.display()))?;
        // Checked once for all its outputs (video frames).
        self.plan.borrow_mut().folders.push(folder.to_path_buf());
        Ok(())
    }

    /// Prints a one-line summary on stderr unless quiet.
    #[allow(clippy::print_stderr, reason = "the summary line is the command's terminal output")]
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

/// `(stage, milliseconds)` pairs as a JSON object, in order.
pub(crate) fn stages_object(stages: &[(String, f64)]) -> Value {
    Value::Object(stages.iter().map(|(name, ms)| (name.clone(), Value::from(*ms))).collect())
}

/// The `width` and `height` of an SVG's root element, in user units.
fn svg_size(svg: &str) -> Option<(f64, f64)> {
    let start = svg.find("<svg")?;
    let tag = &svg[start..start + svg[start..].find('>')?];
    let attribute = |name: &str| -> Option<f64> {
        let at = tag.find(&format!(" {name}=\""))? + name.len() + 3;
        let value = &tag[at..at + tag[at..].find('"')?];
        value.trim_end_matches("px").parse().ok().filter(|v: &f64| v.is_finite() && *v >= 0.0)
    };
    Some((attribute("width")?, attribute("height")?))
}
