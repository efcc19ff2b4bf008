//! The [`Job`] trait: one command every front end offers, and [`JOBS`](crate::JOBS), the list
//! of them.

use motif_core::Progress;
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::{Map, Value};

use crate::JobError;
use crate::options::{Declared, OptionSpec};

/// One command every front end offers (a CLI subcommand, a Python function, a page panel): its
/// name and summary, its declared options, its typed inputs and its run.
///
/// A job is described as serde data named as the CLI's flags (options left out take their
/// declared defaults); the front end decodes the files or arrays into [`Job::Inputs`] and calls
/// [`Job::run`], which validates the description once and runs the engine. Adding an engine is
/// one module implementing this trait and one entry in [`JOBS`](crate::JOBS).
pub trait Job: Serialize + DeserializeOwned {
    /// The name front ends call it by: the CLI subcommand and the Python function.
    const NAME: &'static str;
    /// One line saying what it makes: the CLI's `about`, the first line of help everywhere.
    const SUMMARY: &'static str;
    /// A paragraph more: the method and its paper (the CLI's long help).
    const DETAILS: &'static str;
    /// The names of its fields outside its options (`seed`, `size`, `domain`, …), as a
    /// description holds them.
    const FIELDS: &'static [&'static str];
    /// Its options, declared once (see [`options`](crate::options)).
    type Options: Declared;
    /// Its decoded inputs: images, point sets, curves, as a front end hands them over.
    type Inputs<'a>;
    /// What a finished run gives: the engine's output and the report's figures.
    type Run: Finished;
    /// Validates the description for these inputs and runs the engine.
    fn run(&self, inputs: Self::Inputs<'_>, progress: &mut dyn Progress) -> Result<Self::Run, JobError>;
}

/// A finished run: whatever it made, and the figures of its report.
pub trait Finished {
    /// The report's figures as one JSON object, under the keys every front end writes.
    fn figures(&self) -> &Map<String, Value>;
}

/// One entry of [`JOBS`](crate::JOBS): what front ends list about a [`Job`] without its types.
#[derive(Debug, Clone, Copy)]
pub struct JobEntry {
    /// The name a front end calls it by ([`Job::NAME`]).
    pub name: &'static str,
    /// What it makes, in one line ([`Job::SUMMARY`]).
    pub summary: &'static str,
    /// The method and its paper, in a paragraph ([`Job::DETAILS`]).
    pub details: &'static str,
    /// The names of its fields outside its options ([`Job::FIELDS`]).
    pub fields: &'static [&'static str],
    /// Every option, as declared.
    pub options: fn() -> Vec<OptionSpec>,
}

impl JobEntry {
    /// The entry of job `J`.
    pub const fn of<J: Job>() -> Self {
        Self {
            name: J::NAME,
            summary: J::SUMMARY,
            details: J::DETAILS,
            fields: J::FIELDS,
            options: <J::Options as Declared>::options,
        }
    }

    /// Every name a description of this job may hold: its fields, then its options.
    pub fn names(&self) -> Vec<String> {
        let options = (self.options)().into_iter().map(|spec| spec.name);
        self.fields.iter().map(|field| field.to_string()).chain(options).collect()
    }

    /// The entry named `name`, if a job has it.
    pub fn named(name: &str) -> Option<&'static JobEntry> {
        crate::JOBS.iter().find(|entry| entry.name == name)
    }
}
