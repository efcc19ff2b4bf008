//! The engine registry's shape: what `motif demo` and `motif bench` need from an engine.
//!
//! The list itself is `ENGINES` in the `engines` module; `main` hands it to `demo` and `bench`, so
//! neither knows the engines by name and adding an engine is one entry there (plus its
//! subcommand in `EngineCommand`). This module depends on no engine.

use serde_json::Value;

use crate::gallery::Demo;
use crate::suite::Bench;

/// One engine of the command line.
pub(crate) trait Engine: Sync {
    /// The name `motif bench --engine` takes and the bench figures are keyed by.
    fn name(&self) -> &'static str;
    /// Adds the engine's built-in examples to the gallery.
    fn demo(&self, demo: &mut Demo<'_>) -> anyhow::Result<()>;
    /// The engine's benchmark figures (the cases `bench` selects).
    fn bench(&self, bench: &Bench) -> anyhow::Result<Value>;
}
