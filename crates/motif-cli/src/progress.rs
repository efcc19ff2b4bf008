//! Progress bars on stderr, and the time spent in each stage an engine reports.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use motif_core::Progress;
use motif_core::timing::Clock;

/// Shows one bar per stage (hidden when quiet or when stderr is not a terminal) and records how
/// long each stage took.
#[derive(Debug)]
pub(crate) struct CliProgress {
    visible: bool,
    bar: Option<ProgressBar>,
    stage: Option<(String, Clock)>,
    stages_ms: Vec<(String, f64)>,
}

impl CliProgress {
    /// `visible` is false for `--quiet` and when stderr is not a terminal.
    pub(crate) fn new(visible: bool) -> Self {
        Self { visible, bar: None, stage: None, stages_ms: Vec::new() }
    }

    fn close_stage(&mut self) {
        if let Some((name, start)) = self.stage.take() {
            let ms = start.elapsed().as_secs_f64() * 1000.0;
            match self.stages_ms.iter_mut().find(|(stage, _)| *stage == name) {
                Some((_, total)) => *total += ms,
                None => self.stages_ms.push((name, ms)),
            }
        }
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }

    /// Ends the current stage and returns `(stage, milliseconds)` in the order stages first ran.
    pub(crate) fn finish(&mut self) -> Vec<(String, f64)> {
        self.close_stage();
        std::mem::take(&mut self.stages_ms)
    }
}

impl Progress for CliProgress {
    fn report(&mut self, stage: &str, fraction: f64) {
        if self.stage.as_ref().is_none_or(|(name, _)| name != stage) {
            self.close_stage();
            self.stage = Some((stage.to_string(), Clock::now()));
            if self.visible {
                let bar = ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::stderr());
                bar.set_style(
                    ProgressStyle::with_template("{prefix:>24} [{bar:30}] {percent:>3}% {elapsed}")
                        .expect("static template is valid")
                        .progress_chars("=> "),
                );
                bar.set_prefix(stage.to_string());
                self.bar = Some(bar);
            }
        }
        if let Some(bar) = &self.bar {
            bar.set_position((fraction.clamp(0.0, 1.0) * 1000.0) as u64);
        }
    }
}

impl Drop for CliProgress {
    fn drop(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}
