//! The gallery of `motif demo`: the cases engines add and the HTML page that shows them.
//!
//! Each engine's demo writes its generated inputs into the demo folder and then calls
//! [`Demo::case`] with the exact arguments of a `motif` command. The case runs in-process through
//! the same code path as the command line (the runner `main` gives), so the command shown in the
//! gallery is the command that made the output.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde_json::{Map, Value};

use crate::context::Context;

/// Runs one command line (the arguments after `motif`) in a context; given by `main`.
pub(crate) type Runner<'a> = &'a dyn Fn(&[String], &mut Context) -> anyhow::Result<()>;

/// One built-in example: the files it reads and writes and the arguments of its command.
#[derive(Debug, Clone)]
pub(crate) struct DemoCase {
    /// A short title for the gallery.
    pub title: String,
    /// One or two sentences: what the example shows.
    pub description: String,
    /// `(label, file name)` of each input, relative to the demo folder.
    pub inputs: Vec<(String, String)>,
    /// `(label, file name)` of each output, relative to the demo folder.
    pub outputs: Vec<(String, String)>,
    /// The command's arguments after `motif` (file arguments are plain names in the demo folder).
    pub args: Vec<String>,
}

struct CaseRecord {
    case: DemoCase,
    figures: Map<String, Value>,
    ms: f64,
    /// The error and its causes, one per line, when the case failed.
    failure: Option<String>,
}

/// The demo folder and the cases run so far.
pub(crate) struct Demo<'a> {
    dir: PathBuf,
    seed: u64,
    threads: usize,
    quiet: bool,
    runner: Runner<'a>,
    records: Vec<CaseRecord>,
}

impl<'a> Demo<'a> {
    /// An empty gallery in `dir`, whose cases run through `runner`. `dir` should be absolute (see
    /// [`crate::demo::run`]): the cases' paths are joined to it once, whatever the working folder.
    pub(crate) fn new(dir: PathBuf, seed: u64, threads: usize, quiet: bool, runner: Runner<'a>) -> Self {
        Self { dir, seed, threads, quiet, runner, records: Vec::new() }
    }

    /// The titles of the cases that failed, in order.
    pub(crate) fn failures(&self) -> Vec<&str> {
        self.records.iter().filter(|record| record.failure.is_some()).map(|record| record.case.title.as_str()).collect()
    }

    /// The run's seed.
    pub(crate) fn seed(&self) -> u64 {
        self.seed
    }

    /// The number of cases run so far.
    pub(crate) fn len(&self) -> usize {
        self.records.len()
    }

    /// The gallery page, and each case's figures with its command and time, keyed by title.
    pub(crate) fn finish(&self, total_ms: f64) -> (String, Map<String, Value>) {
        let html = gallery(&self.records, self.seed, total_ms);
        let figures = self
            .records
            .iter()
            .map(|record| {
                let mut entry = record.figures.clone();
                entry.insert("command".into(), Value::from(command_line(&record.case.args)));
                entry.insert("case_ms".into(), Value::from(record.ms));
                if let Some(failure) = &record.failure {
                    entry.insert("error".into(), Value::from(failure.as_str()));
                }
                (record.case.title.clone(), Value::Object(entry))
            })
            .collect();
        (html, figures)
    }

    /// The path of `name` inside the demo folder.
    pub(crate) fn path(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }

    /// Runs `case` in-process and adds it to the gallery. A case that fails is recorded with its
    /// error (the gallery marks it) and the demo goes on; [`Demo::failures`] lists them.
    #[allow(clippy::print_stderr, reason = "a failed demo case is reported on the terminal")]
    pub(crate) fn case(&mut self, case: DemoCase) -> anyhow::Result<()> {
        let resolved = self.resolve(&case);
        let start = std::time::Instant::now();
        let mut context = Context::new(self.seed, self.threads, true);
        let result = (self.runner)(&resolved, &mut context);
        let ms = start.elapsed().as_secs_f64() * 1000.0;
        let failure = result.err().map(|error| error_lines(&error));
        if !self.quiet {
            match &failure {
                None => eprintln!("  {:<48} {:>8.0} ms", case.title, ms),
                Some(error) => eprintln!("  {:<48}   FAILED: {}", case.title, error.replace('\n', " / ")),
            }
        }
        let case = self.shown(case);
        self.records.push(CaseRecord { case, figures: context.into_figures(), ms, failure });
        Ok(())
    }

    /// Records that an engine's demo stopped before its cases ran (its inputs could not be made).
    pub(crate) fn engine_failed(&mut self, engine: &str, error: &anyhow::Error) {
        let case = DemoCase {
            title: format!("{engine}: the demo's inputs"),
            description: format!("The {engine} demo stopped before its remaining cases ran."),
            inputs: Vec::new(),
            outputs: Vec::new(),
            args: Vec::new(),
        };
        self.records.push(CaseRecord { case, figures: Map::new(), ms: 0.0, failure: Some(error_lines(error)) });
    }

    /// The case's arguments with every file it names inside the demo folder.
    fn resolve(&self, case: &DemoCase) -> Vec<String> {
        let listed: Vec<&str> = case.inputs.iter().chain(&case.outputs).map(|(_, file)| file.as_str()).collect();
        case.args
            .iter()
            .map(|arg| {
                // A listed file behind a kind prefix (`volume:MESH.obj`).
                if let Some((kind, file)) = arg.split_once(':')
                    && listed.contains(&file)
                {
                    return format!("{kind}:{}", self.dir.join(file).to_string_lossy());
                }
                let is_file = !arg.starts_with('-')
                    && (listed.contains(&arg.as_str()) || self.dir.join(arg).exists() || looks_like_file_name(arg));
                if is_file { self.dir.join(arg).to_string_lossy().into_owned() } else { arg.clone() }
            })
            .collect()
    }

    /// The case as shown: its command as run inside the demo folder, whichever way the engine
    /// spelled paths.
    fn shown(&self, mut case: DemoCase) -> DemoCase {
        let prefix = format!("{}{}", self.dir.display(), std::path::MAIN_SEPARATOR);
        for arg in &mut case.args {
            if let Some(relative) = arg.strip_prefix(&prefix) {
                *arg = relative.to_string();
            }
            if let Some((kind, file)) = arg.split_once(':')
                && let Some(relative) = file.strip_prefix(&prefix)
            {
                *arg = format!("{kind}:{relative}");
            }
        }
        case
    }
}

/// An error and its causes, one per line.
fn error_lines(error: &anyhow::Error) -> String {
    error.chain().map(ToString::to_string).collect::<Vec<_>>().join("\n")
}

/// A plain relative file name with an extension motif reads or writes (so an output that no case
/// lists still lands in the demo folder, never in the working directory).
fn looks_like_file_name(arg: &str) -> bool {
    let path = Path::new(arg);
    path.is_relative()
        && path.extension().and_then(|e| e.to_str()).is_some_and(|extension| {
            ["png", "jpg", "jpeg", "svg", "json", "ply", "csv"].contains(&extension.to_ascii_lowercase().as_str())
        })
}

/// The command as a person would type it, quoting arguments that need it.
pub(crate) fn command_line(args: &[String]) -> String {
    let quoted = args.iter().map(|arg| {
        if arg.is_empty() || arg.contains(|c: char| c.is_whitespace() || "'\"$;&|<>()*?".contains(c)) {
            format!("'{}'", arg.replace('\'', "'\\''"))
        } else {
            arg.clone()
        }
    });
    std::iter::once("motif".to_string()).chain(quoted).collect::<Vec<_>>().join(" ")
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

fn figure_text(value: &Value) -> String {
    match value {
        Value::Number(number) => match number.as_f64() {
            Some(x) if number.is_f64() => {
                if x.abs() >= 100.0 {
                    format!("{x:.0}")
                } else {
                    format!("{x:.4}")
                }
            }
            _ => number.to_string(),
        },
        Value::String(text) => text.clone(),
        other => {
            let text = other.to_string();
            if text.len() > 240 {
                format!("{}…", &text[..text.char_indices().nth(240).map_or(text.len(), |(i, _)| i)])
            } else {
                text
            }
        }
    }
}

fn file_cell(label: &str, file: &str) -> String {
    let lower = file.to_ascii_lowercase();
    let shown = if [".png", ".svg", ".jpg", ".jpeg"].iter().any(|ext| lower.ends_with(ext)) {
        format!("<a href=\"{0}\"><img src=\"{0}\" alt=\"{1}\"></a>", escape(file), escape(label))
    } else {
        format!("<a class=\"file\" href=\"{0}\">{0}</a>", escape(file))
    };
    format!("<figure>{shown}<figcaption>{} <code>{}</code></figcaption></figure>", escape(label), escape(file))
}

fn gallery(records: &[CaseRecord], seed: u64, total_ms: f64) -> String {
    let mut html = String::new();
    html.push_str(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>motif demo</title>\n<style>\n\
         body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1200px;color:#222;background:#fafafa}\n\
         section{background:#fff;border:1px solid #ddd;border-radius:8px;padding:1em 1.5em;margin:1.5em 0}\n\
         .row{display:flex;flex-wrap:wrap;gap:1.5em;align-items:flex-start}\n\
         figure{margin:0}figure img{max-width:520px;max-height:420px;border:1px solid #ccc;\
         background:repeating-conic-gradient(#eee 0 25%,#fff 0 50%) 50%/16px 16px}\n\
         figcaption{font-size:.85em;color:#555}pre{background:#f3f3f3;padding:.6em;overflow-x:auto;white-space:pre-wrap}\n\
         table{border-collapse:collapse;font-size:.85em}td{border-top:1px solid #eee;padding:2px 8px;vertical-align:top}\n\
         h3{font-size:.95em;margin:.8em 0 .3em}\n\
         section.failed{border:2px solid #c00}.failure{color:#a00;font-weight:bold}\n</style></head><body>\n",
    );
    let _ = writeln!(
        html,
        "<h1>motif demo</h1><p>{} examples, seed {seed}, {:.1} s in all. Each output was made by the command shown, \
         run in this folder.</p>",
        records.len(),
        total_ms / 1000.0
    );
    let failed: Vec<&CaseRecord> = records.iter().filter(|record| record.failure.is_some()).collect();
    if !failed.is_empty() {
        let _ = write!(html, "<p class=\"failure\">{} of {} cases FAILED:", failed.len(), records.len());
        for record in &failed {
            let _ = write!(html, " {};", escape(&record.case.title));
        }
        html.push_str("</p>\n");
    }
    for record in records {
        let case = &record.case;
        let class = if record.failure.is_some() { " class=\"failed\"" } else { "" };
        let _ = writeln!(html, "<section{class}><h2>{}</h2><p>{}</p>", escape(&case.title), escape(&case.description));
        if let Some(failure) = &record.failure {
            let _ = writeln!(html, "<p class=\"failure\">FAILED</p><pre>{}</pre>", escape(failure));
        }
        let _ = writeln!(html, "<pre>{}</pre>", escape(&command_line(&case.args)));
        html.push_str("<div class=\"row\"><div><h3>input</h3><div class=\"row\">");
        for (label, file) in &case.inputs {
            html.push_str(&file_cell(label, file));
        }
        html.push_str("</div></div><div><h3>output</h3><div class=\"row\">");
        for (label, file) in &case.outputs {
            html.push_str(&file_cell(label, file));
        }
        html.push_str("</div></div></div>\n<h3>figures</h3><table>");
        let _ = write!(html, "<tr><td>case_ms</td><td>{:.0}</td></tr>", record.ms);
        for (key, value) in &record.figures {
            let _ = write!(html, "<tr><td>{}</td><td>{}</td></tr>", escape(key), escape(&figure_text(value)));
        }
        html.push_str("</table></section>\n");
    }
    html.push_str("</body></html>\n");
    html
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_names_are_told_from_other_arguments() {
        assert!(looks_like_file_name("out.svg") && looks_like_file_name("a.PNG"));
        assert!(
            !looks_like_file_name("0.8,1.3")
                && !looks_like_file_name("box:14,10")
                && !looks_like_file_name("/tmp/x.png")
        );
    }

    #[test]
    fn command_lines_quote_what_a_shell_would_split() {
        let args: Vec<String> = ["curve", "--out", "my file.png", "--pin-first", "3,4"].map(String::from).to_vec();
        assert_eq!(command_line(&args), "motif curve --out 'my file.png' --pin-first 3,4");
    }

    #[test]
    fn gallery_shows_images_commands_and_figures() {
        let case = DemoCase {
            title: "A <case>".into(),
            description: "d".into(),
            inputs: vec![("exemplar".into(), "in.png".into())],
            outputs: vec![("points".into(), "out.ply".into())],
            args: vec!["curve".into()],
        };
        let mut figures = Map::new();
        figures.insert("total_cost".into(), Value::from(12.5));
        let html = gallery(&[CaseRecord { case, figures, ms: 3.0, failure: None }], 1, 10.0);
        assert!(html.contains("<img src=\"in.png\""));
        assert!(html.contains("href=\"out.ply\""));
        assert!(html.contains("A &lt;case&gt;"));
        assert!(html.contains("<td>total_cost</td><td>12.5000</td>"));
        assert!(html.contains("<pre>motif curve</pre>"));
    }

    #[test]
    fn figures_are_formatted_for_people() {
        assert_eq!(figure_text(&Value::from(1234.567)), "1235");
        assert_eq!(figure_text(&Value::from(7)), "7");
        assert_eq!(figure_text(&serde_json::json!({"a": 1})), "{\"a\":1}");
    }
}
