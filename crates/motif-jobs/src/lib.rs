//! Jobs: the one place where a description of a run, as any front end states it, becomes an
//! engine run.
//!
//! The `motif` CLI, the Python package and the browser playground all describe a run the same
//! way: a job, a serde value whose field names are the CLI's flag names (`patch-size`,
//! `exemplar-window`, …) with the CLI's defaults, plus the decoded inputs (point sets, images,
//! curves: decoding files is the front end's business, through `motif-io` for the CLI). A job
//! turns into validated engine parameters ([`points::PointsJob::params`]), runs
//! ([`points::PointsJob::run`]) and reports its figures as one JSON object
//! ([`points::figures`]) under the same keys whichever front end asked. No front end parses sizes,
//! fields or enums itself; text forms that a command line writes (`--domain box:W,H`,
//! `--scale-along A,B`) are parsed here too ([`points::DomainArgument`]).
//!
//! The crate is pure (no I/O, builds for `wasm32`). Every engine has its jobs here: `curve`, `points`,
//! `strokes` and `stylize` (with `texture` and `presynth`).
//!
//! ```
//! use motif_jobs::Job;
//! use motif_jobs::points::{PointsInputs, PointsJob};
//! use motif_points::samples::hex_exemplar;
//!
//! // The JSON a front end sends: required fields, and any option by its flag name.
//! let job: PointsJob = serde_json::from_str(
//!     r#"{ "neighbourhood": 1.5, "domain": { "box": [10, 8] }, "seed": 7, "refine": "seams" }"#,
//! ).unwrap();
//! let run = job.run(PointsInputs::new(hex_exemplar(8, 8, 0.05, 1)), &mut motif_core::NoProgress).unwrap();
//! assert!(run.output.points.len() > 60);
//! assert_eq!(run.figures["command"], "points");
//! assert!(run.figures["fidelity"]["density_ratio"].as_f64().unwrap() > 0.9);
//! // A misspelt option is an error that names it.
//! let error = serde_json::from_str::<PointsJob>(r#"{ "neighbourhood": 1, "domain": { "box": [4, 4] }, "patchsize": 3 }"#);
//! assert!(error.unwrap_err().to_string().contains("patchsize"));
//! ```

pub mod columns;
pub mod curve;
mod error;
mod job;
mod memory_size;
pub mod options;
pub mod points;
pub mod strokes;
pub mod stylize;
pub mod tiles;

pub use error::{ErrorKind, JobError};
pub use job::{Finished, Job, JobEntry};

/// Every job, in the order front ends list them. The CLI's subcommands, Python's functions and
/// keywords, and `docs/cli.md` are checked against it.
pub const JOBS: &[JobEntry] = &[
    JobEntry::of::<curve::CurveJob>(),
    JobEntry::of::<points::PointsJob>(),
    JobEntry::of::<strokes::StrokesJob>(),
    JobEntry::of::<stylize::StylizeJob>(),
    JobEntry::of::<stylize::PresynthJob>(),
    JobEntry::of::<stylize::TextureJob>(),
    JobEntry::of::<stylize::InpaintJob>(),
    JobEntry::of::<stylize::ZoomJob>(),
    JobEntry::of::<stylize::VideoJob>(),
    JobEntry::of::<tiles::TilesJob>(),
];

/// Per-stage milliseconds as a JSON object, in order.
fn stages(stages: &[(String, f64)]) -> serde_json::Value {
    serde_json::Value::Object(stages.iter().map(|(name, ms)| (name.clone(), serde_json::json!(ms))).collect())
}

/// The fields of a JSON object built with `json!({...})`.
fn object(value: serde_json::Value) -> serde_json::Map<String, serde_json::Value> {
    match value {
        serde_json::Value::Object(map) => map,
        _ => serde_json::Map::new(),
    }
}
