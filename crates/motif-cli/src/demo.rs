//! `motif demo`: every engine of the registry on its built-in examples, and an HTML gallery of
//! the results (see [`crate::gallery`]).

use std::path::PathBuf;

use anyhow::{Context as _, bail};
use clap::Args;

use crate::gallery::{Demo, Runner};
use crate::options::GlobalArgs;
use crate::registry::Engine;

/// Options of `motif demo`.
#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Folder for the inputs, the outputs and `index.html` (created if missing; files in it with
    /// the demo's names are replaced).
    #[arg(long, default_value = "motif-demo", value_name = "DIR")]
    pub out: PathBuf,
}

/// Runs `motif demo`: every engine's cases, each through `runner`.
#[allow(clippy::print_stderr, reason = "the demo reports each case on the terminal")]
pub(crate) fn run(
    args: &DemoArgs,
    global: &GlobalArgs,
    threads: usize,
    engines: &[&dyn Engine],
    runner: Runner<'_>,
) -> anyhow::Result<()> {
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create the demo folder {}", args.out.display()))?;
    // Absolute, so that a case's paths are joined to the folder once whatever the working folder
    // and however `--out` was spelled (relative, `./x`, `../x`).
    let folder = std::fs::canonicalize(&args.out)
        .with_context(|| format!("cannot resolve the demo folder {}", args.out.display()))?;
    let mut demo = Demo::new(folder.clone(), global.seed, threads, global.quiet, runner);
    let start = std::time::Instant::now();
    if !global.quiet {
        eprintln!("motif demo: writing into {}", args.out.display());
    }
    for engine in engines {
        if let Err(error) = engine.demo(&mut demo) {
            demo.engine_failed(engine.name(), &error);
        }
    }
    let total_ms = start.elapsed().as_secs_f64() * 1000.0;
    let (html, figures) = demo.finish(total_ms);
    let index = args.out.join("index.html");
    motif_io::write_text(&folder.join("index.html"), &html)?;
    let failures = demo.failures();
    let report = serde_json::json!({
        "command": "demo", "seed": global.seed, "threads": threads, "total_ms": total_ms,
        "failed_cases": failures, "cases": figures,
    });
    motif_io::write_json(&folder.join("demo-report.json"), &report)?;
    if let Some(path) = &global.report {
        motif_io::write_json(path, &report)?;
    }
    if !failures.is_empty() {
        bail!(
            "{} of {} demo cases failed ({}); {} marks them",
            failures.len(),
            demo.len(),
            failures.join("; "),
            index.display()
        );
    }
    if !global.quiet {
        eprintln!("motif demo: {} cases in {:.1} s; open {}", demo.len(), total_ms / 1000.0, index.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::{Component, Path, PathBuf};

    use serde_json::Value;

    use super::*;
    use crate::context::Context;
    use crate::gallery::DemoCase;
    use crate::suite::Bench;

    /// An engine whose first case names a file through `Demo::path` (as the video demo's frame
    /// pattern does) and whose second case fails.
    struct Probe;

    impl Engine for Probe {
        fn name(&self) -> &'static str {
            "probe"
        }

        fn demo(&self, demo: &mut Demo<'_>) -> anyhow::Result<()> {
            let frames = demo.path("frames/%04d.png").to_string_lossy().into_owned();
            let case = |title: &str, args: Vec<String>| DemoCase {
                title: title.into(),
                description: String::new(),
                inputs: Vec::new(),
                outputs: vec![("out".into(), "out.png".into())],
                args,
            };
            demo.case(case(
                "frames",
                vec!["video".into(), "--frames".into(), frames, "--out".into(), "out.png".into()],
            ))?;
            demo.case(case("broken", vec!["fail".into()]))
        }

        fn bench(&self, _: &Bench) -> anyhow::Result<Value> {
            Ok(Value::Null)
        }
    }

    /// `to` relative to the working folder, however far apart.
    fn relative_to_cwd(to: &Path) -> PathBuf {
        let cwd = std::env::current_dir().unwrap();
        let ups = cwd.components().filter(|c| matches!(c, Component::Normal(_))).count();
        let mut path: PathBuf = std::iter::repeat_n("..", ups).collect();
        path.push(to.strip_prefix("/").unwrap());
        path
    }

    #[test]
    fn a_relative_folder_resolves_once_and_a_failed_case_is_marked() {
        let dir = tempfile::tempdir().unwrap();
        let out = relative_to_cwd(&dir.path().join("gallery"));
        assert!(out.is_relative());
        let seen = std::cell::RefCell::new(Vec::new());
        let runner = |args: &[String], _: &mut Context| -> anyhow::Result<()> {
            seen.borrow_mut().push(args.to_vec());
            if args[0] == "fail" { anyhow::bail!("this case fails") } else { Ok(()) }
        };
        let global = GlobalArgs { seed: 1, threads: None, max_memory: None, quiet: true, report: None };
        let result = run(&DemoArgs { out: out.clone() }, &global, 1, &[&Probe], &runner);
        let error = format!("{:#}", result.unwrap_err());
        assert!(error.contains("1 of 2 demo cases failed (broken)"), "{error}");
        let gallery = dir.path().join("gallery");
        let frames = &seen.borrow()[0][2];
        assert_eq!(Path::new(frames), gallery.join("frames/%04d.png"), "joined to the folder once");
        assert_eq!(Path::new(&seen.borrow()[0][4]), gallery.join("out.png"));
        let html = std::fs::read_to_string(gallery.join("index.html")).unwrap();
        assert!(html.contains("1 of 2 cases FAILED: broken;"), "{html}");
        assert!(html.contains("<section class=\"failed\"><h2>broken</h2>") && html.contains("this case fails"));
        assert!(html.contains("<pre>motif video --frames frames/%04d.png --out out.png</pre>"));
    }
}
