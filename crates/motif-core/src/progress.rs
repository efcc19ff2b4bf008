//! Progress reporting from engines to whoever drives them.
//!
//! Engines call [`Progress::report`] from the thread that called their entry point (never from
//! worker threads), with a stage name and the fraction of that stage done. The CLI turns these
//! calls into progress bars; tests pass [`NoProgress`] or a closure that records the calls.

/// Receives progress from an engine.
pub trait Progress {
    /// `stage` names the current stage ("dynamic program", "level 3"); `fraction` is in `[0, 1]`
    /// and grows within a stage. A new stage name means the previous stage has finished.
    fn report(&mut self, stage: &str, fraction: f64);
}

impl<F: FnMut(&str, f64)> Progress for F {
    fn report(&mut self, stage: &str, fraction: f64) {
        self(stage, fraction)
    }
}

/// Discards all progress.
#[derive(Debug, Default, Clone, Copy)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn report(&mut self, _stage: &str, _fraction: f64) {}
}

#[cfg(test)]
mod tests {
    use super::*;

    fn engine(progress: &mut dyn Progress) {
        progress.report("a", 0.0);
        progress.report("a", 1.0);
        progress.report("b", 0.5);
    }

    #[test]
    fn closures_receive_every_report() {
        let mut seen = Vec::new();
        engine(&mut |stage: &str, fraction: f64| seen.push((stage.to_string(), fraction)));
        assert_eq!(seen.len(), 3);
        assert_eq!(seen[2], ("b".to_string(), 0.5));
        engine(&mut NoProgress);
    }
}
