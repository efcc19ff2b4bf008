//! Helpers shared by the CLI test files (each test file uses a subset: the rest would
//! be dead code in that crate).
#![allow(dead_code, reason = "each integration test uses part of the shared helpers")]

use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, Output};

pub(crate) fn motif(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_motif")).current_dir(dir).args(args).output().unwrap()
}

pub(crate) fn ok(output: &Output) {
    assert!(output.status.success(), "stderr: {}", String::from_utf8_lossy(&output.stderr));
}

pub(crate) fn error_of(output: &Output) -> String {
    assert!(!output.status.success(), "expected a failure");
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// A jittered 12 × 12 grid (spacing 1) with a `shade` attribute striped along y, as CSV.
pub(crate) fn grid_csv() -> String {
    let mut text = String::from("x,y,shade\n");
    for y in 0..12 {
        for x in 0..12 {
            let jitter = ((x * 7 + y * 13) % 10) as f64 * 0.01;
            let _ = writeln!(text, "{},{},{}", x as f64 + jitter, y as f64 - jitter, y % 2);
        }
    }
    text
}
