//! What an engine's benchmark gets: the run's settings and the real-data corpus.

use std::path::PathBuf;

use serde_json::Value;

/// What an engine's benchmark gets.
pub(crate) struct Bench {
    /// Seed of the generated workloads.
    pub seed: u64,
    /// True for tiny workloads (smoke tests).
    pub quick: bool,
    /// Worker threads in use.
    pub threads: usize,
    /// Cases named with `--case` (empty: all).
    pub cases: Vec<String>,
}

impl Bench {
    /// True when case `name` of group `group` (`corpus` or `generated`) should run: no `--case`
    /// given, or the name or its group named.
    pub(crate) fn selects(&self, name: &str, group: &str) -> bool {
        self.cases.is_empty() || self.names(name) || self.names(group)
    }

    /// True when case `name` was named with `--case` (slow cases run only then).
    pub(crate) fn names(&self, name: &str) -> bool {
        self.cases.iter().any(|c| c == name)
    }
}

/// The real-data corpus folder of `engine` in this source tree (`data/real/<engine>/`; the bench
/// is a developer's tool run from a checkout).
pub(crate) fn corpus_folder(engine: &str) -> PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real").join(engine)
}

/// The cases of a corpus manifest (`cases.json` in `folder`).
pub(crate) fn read_cases<T: serde::de::DeserializeOwned>(folder: &std::path::Path) -> anyhow::Result<Vec<T>> {
    use anyhow::Context as _;
    let path = folder.join("cases.json");
    let value: Value = motif_io::read_json(&path)?;
    serde_json::from_value(value).with_context(|| format!("{}: not a list of corpus cases", path.display()))
}
