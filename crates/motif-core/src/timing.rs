//! Wall-clock timing of named stages, for the figures in reports.

use web_time::Instant;

/// Accumulates milliseconds per named stage, in the order stages first ran.
///
/// Uses `web-time`, so it also works in `wasm32-unknown-unknown` builds.
#[derive(Debug, Clone)]
pub struct StageTimer {
    stages: Vec<(String, f64)>,
    current: Option<(String, Instant)>,
}

impl Default for StageTimer {
    fn default() -> Self {
        Self::new()
    }
}

impl StageTimer {
    /// An empty timer.
    pub fn new() -> Self {
        Self { stages: Vec::new(), current: None }
    }

    /// Ends the running stage (if any) and starts timing `name`.
    pub fn start(&mut self, name: &str) {
        self.stop();
        self.current = Some((name.to_string(), Instant::now()));
    }

    /// Ends the running stage, adding its time to the stage's total.
    pub fn stop(&mut self) {
        if let Some((name, start)) = self.current.take() {
            let ms = start.elapsed().as_secs_f64() * 1000.0;
            self.add(&name, ms);
        }
    }

    /// Adds `ms` milliseconds to stage `name`.
    pub fn add(&mut self, name: &str, ms: f64) {
        match self.stages.iter_mut().find(|(stage, _)| stage == name) {
            Some((_, total)) => *total += ms,
            None => self.stages.push((name.to_string(), ms)),
        }
    }

    /// Times `work` as stage `name` and returns its result.
    pub fn time<T>(&mut self, name: &str, work: impl FnOnce() -> T) -> T {
        let start = Instant::now();
        let result = work();
        self.add(name, start.elapsed().as_secs_f64() * 1000.0);
        result
    }

    /// Stops the running stage and returns `(stage, milliseconds)` in first-run order.
    pub fn finish(mut self) -> Vec<(String, f64)> {
        self.stop();
        self.stages
    }

    /// The stages recorded so far (the running one excluded).
    pub fn stages(&self) -> &[(String, f64)] {
        &self.stages
    }
}

/// Milliseconds elapsed since `start`; a small helper for per-row or per-iteration timings.
pub fn elapsed_ms(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1000.0
}

pub use web_time::Instant as Clock;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stages_accumulate_in_first_run_order() {
        let mut timer = StageTimer::new();
        timer.start("a");
        timer.start("b");
        timer.stop();
        timer.add("a", 5.0);
        let value = timer.time("c", || 7);
        assert_eq!(value, 7);
        let stages = timer.finish();
        let names: Vec<&str> = stages.iter().map(|(name, _)| name.as_str()).collect();
        assert_eq!(names, ["a", "b", "c"]);
        assert!(stages[0].1 >= 5.0);
    }
}

/// The median of `values` (the mean of the two middle values for an even count; 0 when empty):
/// the one summary of repeated timings every engine and bench reports.
pub fn median(values: &[f64]) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let middle = sorted.len() / 2;
    if sorted.len() % 2 == 1 { sorted[middle] } else { 0.5 * (sorted[middle - 1] + sorted[middle]) }
}

#[cfg(test)]
mod median_tests {
    #[test]
    fn median_of_odd_even_and_empty() {
        assert_eq!(super::median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(super::median(&[4.0, 1.0, 3.0, 2.0]), 2.5);
        assert_eq!(super::median(&[]), 0.0);
    }
}
