//! The short search that settles an inferred width and piece length (issue 34).
//!
//! `Dimensions::resolve` reads a first guess off the exemplar (the pattern's height and period).
//! How well a piece length keeps the motifs whole also depends on the curve, and the patch
//! fidelity of the result moves by several percent between neighbouring values, so a run whose
//! piece length (or width) was inferred tries a few values around the guess and keeps the one whose
//! output scores best:
//!
//! 1. piece lengths of [`PIECE_LENGTH_FACTORS`] × the guess, and half the pattern's period when
//!    it has one (a length that divides the period keeps the motifs' phase from piece to piece),
//!    at the guessed width;
//! 2. at the best piece length, every whole width within [`NEAR_WIDTH`] of the guess, nearest
//!    first, then [`WIDTH_FACTORS`] × the guess (a little narrower and wider: the guess's 15 %
//!    margin is a rule of thumb, and every one of them still holds the pattern's height). The
//!    output's fidelity moves by up to 7 % between widths one pixel apart, with no trend (measured
//!    on the corpus, `docs/curve.md`), so the widths near the guess are all tried;
//! 3. at the best width, the piece lengths halfway between the best length and its nearest tried
//!    neighbours below and above, twice (a bisection: the output's fidelity is not smooth in the
//!    length either, so the ladder of step 1 alone misses good lengths between its rungs).
//!
//! The score is the output's mean patch distance to the exemplar, raised by its share of broken
//! patches ([`score`]). Each trial is a whole run with the job's own solver and seed, so the kept
//! output is byte-identical to a run given that width and piece length. A value the job gives is
//! never searched. Two budgets in position pairs (not seconds, so the output is the same on any
//! machine) keep a large problem from taking a dozen trials' time: [`MAX_PAIRS_TO_SEARCH`] for
//! the first trial, [`SEARCH_BUDGET`] times it for the whole search.

use motif_core::Progress;
use motif_curve::{Dimensions, Output, PatchFidelity};
use serde::{Deserialize, Serialize};

use crate::JobError;

/// Piece lengths tried, as multiples of the inferred one (the inferred one first).
pub(crate) const PIECE_LENGTH_FACTORS: [f64; 6] = [1.0, 0.8, 1.25, 1.6, 2.0, 2.5];
/// Widths tried after the piece length is settled, besides those near the guess
/// ([`NEAR_WIDTH`]), as multiples of the inferred one.
pub(crate) const WIDTH_FACTORS: [f64; 3] = [0.95, 1.05, 1.1];
/// Every whole width within this share of the inferred one is tried (step 2).
pub(crate) const NEAR_WIDTH: f64 = 0.04;
/// Rounds of step 3's bisection of the piece length.
pub(crate) const LENGTH_BISECTIONS: usize = 2;
/// Most position pairs (`Σ V_{i−1} V_i`, the dynamic program's size) the first trial may have for
/// the others to run: the round chain on the heart has 1.8 × 10⁹, the dense chain 2.4 × 10⁹ (7
/// trials: 17 s), the 600 × 250 chain with the exact solver about 3.5 × 10¹⁰ (over two minutes a
/// trial). Larger problems keep the guess, with a warning.
pub(crate) const MAX_PAIRS_TO_SEARCH: u64 = 10_000_000_000;
/// The search's whole budget, in multiples of the largest first trial ([`MAX_PAIRS_TO_SEARCH`]
/// in a job): once its trials have compared that many position pairs, the rest are left out, so
/// that a large problem takes a few trials' time, not a dozen (the 600 × 250 chain on the
/// flourish: trials of up to 10¹⁰ pairs and 25 s each).
pub(crate) const SEARCH_BUDGET: u64 = 4;
/// Weight of the broken-patch share in [`score`]: a point of broken patches costs as much as 4 %
/// of patch distance.
pub(crate) const BROKEN_WEIGHT: f64 = 4.0;

/// One width and piece length tried, and how its output scored.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Trial {
    /// Ribbon width, canvas pixels.
    pub width: f64,
    /// Piece length, canvas pixels.
    pub piece_length: f64,
    /// Mean patch distance of the output to the exemplar.
    pub patch_distance: f64,
    /// Share of the output's patches far from every exemplar patch.
    pub broken_fraction: f64,
    /// Patch distance × (1 + 4 × broken share): lower is better.
    pub score: f64,
    /// Position pairs its dynamic program compared (what the search's budget counts).
    pub pairs: u64,
    /// Seconds the trial took.
    pub seconds: f64,
}

/// The figure the search minimizes: patch distance × (1 + [`BROKEN_WEIGHT`] × broken share).
pub(crate) fn score(fidelity: &PatchFidelity) -> f64 {
    fidelity.mean_distance * (1.0 + BROKEN_WEIGHT * fidelity.broken_fraction)
}

/// A finished trial: its figures, output and fidelity.
pub(crate) struct Tried {
    pub(crate) trial: Trial,
    pub(crate) output: Output,
    pub(crate) fidelity: PatchFidelity,
}

/// Runs `run` (one whole run at a width and piece length) over the search's candidates for what
/// `dimensions` inferred, and returns the best trial (its width and piece length written into
/// `dimensions`) with every trial's figures. `max_piece_length` caps the candidates (the curve's
/// length); `scale` turns the pattern's period into canvas pixels; when the first trial's
/// dynamic program has more than `max_pairs` position pairs ([`MAX_PAIRS_TO_SEARCH`] in a job),
/// it is kept alone, with a warning, and once the trials' dynamic programs have compared
/// [`SEARCH_BUDGET`] × `max_pairs` pairs in all, the search stops there, with a warning. Errors
/// of the first trial, the guess itself, are the run's errors; a later candidate that fails is
/// skipped.
pub(crate) fn search(
    dimensions: &mut Dimensions,
    (max_piece_length, scale, max_pairs): (f64, f64, u64),
    progress: &mut dyn Progress,
    mut run: impl FnMut(f64, f64, &mut dyn Progress) -> Result<(Output, PatchFidelity), JobError>,
) -> Result<(Tried, Vec<Trial>), JobError> {
    let (width, piece_length) = (dimensions.width, dimensions.piece_length);
    let lengths: Vec<f64> = if piece_length.inferred {
        piece_lengths(piece_length.value, dimensions.period, scale, max_piece_length)
    } else {
        vec![piece_length.value]
    };
    let widths: Vec<f64> = if width.inferred { widths_around(width.value) } else { Vec::new() };
    // Step 3 tries at most two lengths a round; the count is exact once step 1 has chosen.
    let bisections = if piece_length.inferred { LENGTH_BISECTIONS } else { 0 };
    let planned = lengths.len() + widths.len() + 2 * bisections;
    let mut state = Trials::new(planned, max_pairs.saturating_mul(SEARCH_BUDGET));
    state.attempt((width.value, lengths[0]), progress, &mut run)?;
    if too_large_to_search(state.best.as_mut().map(|b| &mut b.output), planned, max_pairs) {
        return Ok(state.finish(dimensions));
    }
    for &l in &lengths[1..] {
        state.attempt((width.value, l), progress, &mut run)?;
    }
    let best_length = state.best().piece_length;
    for &w in &widths {
        state.attempt((w, best_length), progress, &mut run)?;
    }
    let best_width = state.best().width;
    let mut tried = lengths;
    for round in 0..bisections {
        let between = lengths_between(state.best().piece_length, &tried);
        // Rounds after this one may try two lengths each.
        state.planned = state.trials.len() + state.skipped + between.len() + 2 * (bisections - round - 1);
        for &l in &between {
            state.attempt((best_width, l), progress, &mut run)?;
        }
        tried.extend(between);
    }
    Ok(state.finish(dimensions))
}

/// The search so far: the trials run, the best one, and the position pairs their dynamic
/// programs compared.
struct Trials {
    trials: Vec<Trial>,
    best: Option<Tried>,
    planned: usize,
    spent_pairs: u64,
    budget_pairs: u64,
    /// Trials left out because the budget was spent.
    skipped: usize,
}

impl Trials {
    fn new(planned: usize, budget_pairs: u64) -> Self {
        Self { trials: Vec::with_capacity(planned), best: None, planned, spent_pairs: 0, budget_pairs, skipped: 0 }
    }

    /// The best trial so far (there is one once the first trial has returned).
    fn best(&self) -> Trial {
        self.best.as_ref().expect("the first trial either succeeded or returned its error").trial
    }

    /// Runs one trial at `(width, piece_length)` unless the budget is spent, and keeps it if it
    /// scores best. Only the first trial's error is returned.
    fn attempt(
        &mut self,
        (width, piece_length): (f64, f64),
        progress: &mut dyn Progress,
        run: &mut impl FnMut(f64, f64, &mut dyn Progress) -> Result<(Output, PatchFidelity), JobError>,
    ) -> Result<(), JobError> {
        if self.spent_pairs >= self.budget_pairs {
            self.skipped += 1;
            return Ok(());
        }
        let mut labelled = Labelled { inner: progress, trial: self.trials.len() + 1, total: self.planned };
        let started = std::time::Instant::now();
        let (output, fidelity) = match run(width, piece_length, &mut labelled) {
            Ok(done) => done,
            Err(error) if self.best.is_none() => return Err(error),
            Err(_) => return Ok(()),
        };
        let pairs = output.report.dp_counters.pairs;
        self.spent_pairs = self.spent_pairs.saturating_add(pairs);
        let trial = Trial {
            pairs,
            width,
            piece_length,
            patch_distance: fidelity.mean_distance,
            broken_fraction: fidelity.broken_fraction,
            score: score(&fidelity),
            seconds: started.elapsed().as_secs_f64(),
        };
        self.trials.push(trial);
        if self.best.as_ref().is_none_or(|b| trial.score < b.trial.score) {
            self.best = Some(Tried { trial, output, fidelity });
        }
        Ok(())
    }

    /// The best trial (with a warning when the budget cut the search short) and every trial's
    /// figures; the best width and piece length written into `dimensions`.
    fn finish(self, dimensions: &mut Dimensions) -> (Tried, Vec<Trial>) {
        let mut best = self.best.expect("the first trial either succeeded or returned its error");
        if self.skipped > 0 {
            best.output.report.warnings.push(format!(
                "the size search stopped after {} of {} trials: their dynamic programs had compared {:.2e} position \
                 pairs, its budget; give --piece-length (and --width) to choose them, or use --solver coarse, whose \
                 trials are cheaper",
                self.trials.len(),
                self.trials.len() + self.skipped,
                self.spent_pairs as f64
            ));
        }
        dimensions.width.value = best.trial.width;
        dimensions.piece_length.value = best.trial.piece_length;
        (best, self.trials)
    }
}

/// Whether the first trial's dynamic program was too large for the others to run; if so, says so
/// in its output's warnings.
fn too_large_to_search(first: Option<&mut Output>, trials: usize, max_pairs: u64) -> bool {
    let Some(output) = first else { return false };
    let pairs = output.report.dp_counters.pairs;
    if trials <= 1 || pairs <= max_pairs {
        return false;
    }
    output.report.warnings.push(format!(
        "the width and piece length read off the exemplar were kept without trying others: the dynamic \
         program compared {pairs:.2e} position pairs, over the {max_pairs:.0e} the size search allows; \
         give --piece-length (and --width) to choose them, or use --solver coarse, whose trials are cheaper"
    ));
    true
}

/// The piece lengths tried around `guess`: [`PIECE_LENGTH_FACTORS`] × the guess, then half the
/// pattern's `period` (exemplar pixels, at `scale` exemplar pixels per canvas pixel) when it has
/// one and it is not among them; rounded, at most `max`.
fn piece_lengths(guess: f64, period: Option<usize>, scale: f64, max: f64) -> Vec<f64> {
    let mut lengths = candidates(guess, &PIECE_LENGTH_FACTORS, f64::round, max);
    let half_period = period.map(|period| (period as f64 / (2.0 * scale)).round().clamp(1.0, max));
    if let Some(half) = half_period.filter(|half| !lengths.contains(half)) {
        lengths.push(half);
    }
    lengths
}

/// The lengths halfway between `best` and its nearest neighbours below and above in `tried`
/// (rounded; those already tried or equal to `best` left out).
fn lengths_between(best: f64, tried: &[f64]) -> Vec<f64> {
    let below = tried.iter().copied().filter(|&l| l < best).max_by(f64::total_cmp);
    let above = tried.iter().copied().filter(|&l| l > best).min_by(f64::total_cmp);
    let mut between: Vec<f64> = Vec::with_capacity(2);
    for neighbour in [below, above].into_iter().flatten() {
        let middle = ((best + neighbour) / 2.0).round();
        if middle != best && middle != neighbour && !tried.contains(&middle) && !between.contains(&middle) {
            between.push(middle);
        }
    }
    between
}

/// `value × factor` for each factor, rounded with `round`, at least 1 and at most `max`, without
/// repeats, in the order of `factors`.
fn candidates(value: f64, factors: &[f64], round: fn(f64) -> f64, max: f64) -> Vec<f64> {
    let mut values: Vec<f64> = Vec::with_capacity(factors.len());
    for factor in factors {
        let candidate = round(value * factor).max(1.0).min(max);
        if !values.contains(&candidate) {
            values.push(candidate);
        }
    }
    values
}

/// The widths of step 2 around `guess`: every whole width within [`NEAR_WIDTH`] of it, nearest
/// first (the narrower of two equally near), then [`WIDTH_FACTORS`] × the guess (rounded up);
/// the guess itself and repeats left out.
fn widths_around(guess: f64) -> Vec<f64> {
    let (low, high) = ((guess * (1.0 - NEAR_WIDTH)).ceil(), (guess * (1.0 + NEAR_WIDTH)).floor());
    let mut widths: Vec<f64> = (low as i64..=high as i64).map(|w| w as f64).collect();
    widths.sort_by(|a, b| (a - guess).abs().total_cmp(&(b - guess).abs()).then(a.total_cmp(b)));
    for far in candidates(guess, &WIDTH_FACTORS, f64::ceil, f64::INFINITY) {
        if !widths.contains(&far) {
            widths.push(far);
        }
    }
    widths.retain(|&w| w != guess && w >= 1.0);
    widths
}

/// Progress of one trial, its stages named with the trial's number.
struct Labelled<'a> {
    inner: &'a mut dyn Progress,
    trial: usize,
    total: usize,
}

impl Progress for Labelled<'_> {
    fn report(&mut self, stage: &str, fraction: f64) {
        if self.total > 1 {
            self.inner.report(&format!("{stage} (size trial {}/{})", self.trial, self.total), fraction);
        } else {
            self.inner.report(stage, fraction);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Half the period joins the lengths around the guess (in canvas pixels, once).
    #[test]
    fn half_the_period_is_tried_too() {
        assert_eq!(piece_lengths(22.0, Some(40), 1.0, 100.0), vec![22.0, 18.0, 28.0, 35.0, 44.0, 55.0, 20.0]);
        assert_eq!(piece_lengths(20.0, Some(40), 1.0, 100.0), vec![20.0, 16.0, 25.0, 32.0, 40.0, 50.0]);
        assert_eq!(piece_lengths(22.0, Some(40), 2.0, 100.0), vec![22.0, 18.0, 28.0, 35.0, 44.0, 55.0, 10.0]);
        assert_eq!(piece_lengths(22.0, None, 1.0, 100.0), vec![22.0, 18.0, 28.0, 35.0, 44.0, 55.0]);
    }

    #[test]
    fn candidates_are_rounded_capped_and_unique() {
        assert_eq!(
            candidates(20.0, &PIECE_LENGTH_FACTORS, f64::round, 100.0),
            vec![20.0, 16.0, 25.0, 32.0, 40.0, 50.0]
        );
        assert_eq!(candidates(20.0, &PIECE_LENGTH_FACTORS, f64::round, 30.0), vec![20.0, 16.0, 25.0, 30.0]);
        assert_eq!(candidates(1.0, &PIECE_LENGTH_FACTORS, f64::round, 100.0), vec![1.0, 2.0, 3.0]);
        assert_eq!(candidates(76.0, &WIDTH_FACTORS, f64::ceil, f64::INFINITY), vec![73.0, 80.0, 84.0]);
    }

    /// Step 2: every whole width within 4 % of the guess, nearest first, then the farther ones.
    #[test]
    fn widths_near_the_guess_come_first() {
        assert_eq!(
            widths_around(136.0),
            vec![135.0, 137.0, 134.0, 138.0, 133.0, 139.0, 132.0, 140.0, 131.0, 141.0, 130.0, 143.0, 150.0]
        );
        assert_eq!(widths_around(20.0), vec![19.0, 21.0, 22.0]);
        assert_eq!(widths_around(1.0), vec![2.0]);
    }

    /// Step 3's lengths lie halfway to the best length's neighbours, never on a tried one.
    #[test]
    fn lengths_between_the_best_and_its_neighbours() {
        let tried = [20.0, 16.0, 25.0, 32.0, 40.0, 50.0];
        assert_eq!(lengths_between(25.0, &tried), vec![23.0, 29.0]);
        assert_eq!(lengths_between(16.0, &tried), vec![18.0]);
        assert_eq!(lengths_between(50.0, &tried), vec![45.0]);
        assert_eq!(lengths_between(2.0, &[1.0, 2.0, 3.0]), Vec::<f64>::new());
        assert_eq!(lengths_between(30.0, &[30.0]), Vec::<f64>::new());
    }

    /// The rings along a line, searched with a pair budget under and over the first trial's.
    #[test]
    fn a_problem_over_the_pair_budget_keeps_its_guess_with_a_warning() {
        use crate::curve::tests::{line, rings};
        let (exemplar, curve) = (rings(), line());
        let guess = motif_curve::Dimensions::resolve(&exemplar, None, None, 1.0, 8).unwrap();
        let run = |width: f64, piece_length: f64, progress: &mut dyn Progress| {
            let params = motif_curve::Params::DEFAULT.with_width(width).with_piece_length(piece_length);
            let output = motif_curve::synthesize(&motif_curve::Input::new(&exemplar, &curve), &params, progress)?;
            let fidelity =
                motif_curve::patch_fidelity(&exemplar, &output.image, &output.ribbon_top, &output.ribbon_bottom, 1.0);
            Ok((output, fidelity))
        };
        let mut searched = guess;
        let (best, all) = search(&mut searched, (1e9, 1.0, u64::MAX), &mut motif_core::NoProgress, run).unwrap();
        // Six lengths around the guess (half the rings' 16-pixel period among them), the two wider
        // ribbons (none is within 4 % of the guess's 19 pixels, and the narrower rounds back to
        // it), then two rounds of the bisection: 15 and 18, then 17.
        assert_eq!(guess.period, Some(16));
        assert_eq!(all.len(), 11, "{all:?}");
        let tried: Vec<(f64, f64)> = all.iter().map(|t| (t.width, t.piece_length)).collect();
        let unique: std::collections::BTreeSet<(u64, u64)> =
            tried.iter().map(|&(w, l)| (w.to_bits(), l.to_bits())).collect();
        assert_eq!(unique.len(), tried.len(), "a trial repeated: {tried:?}");
        assert!(all.iter().all(|t| t.score >= best.trial.score));
        assert!(best.output.report.warnings.is_empty());
        let pairs = all[0].pairs;
        assert!(pairs > 0);
        let mut kept = guess;
        let (best, trials) = search(&mut kept, (1e9, 1.0, pairs / 4), &mut motif_core::NoProgress, run).unwrap();
        assert_eq!(trials.len(), 1);
        assert_eq!(kept, guess);
        assert!(
            best.output.report.warnings.iter().any(|w| w.contains("without trying others")),
            "{:?}",
            best.output.report.warnings
        );
        // A first trial within the limit, a whole search over the budget (4 first trials' pairs):
        // it stops once the budget is spent, says so, and keeps the best of the trials it ran.
        let ran = 1 + all
            .iter()
            .scan(0, |spent, t| {
                *spent += t.pairs;
                Some(*spent)
            })
            .take_while(|&spent| spent < 4 * pairs)
            .count();
        assert!(ran < 11, "the budget stops this search part way: {all:?}");
        let (best, trials) = search(&mut guess.clone(), (1e9, 1.0, pairs), &mut motif_core::NoProgress, run).unwrap();
        let figures = |t: &Trial| (t.width, t.piece_length, t.score, t.pairs);
        assert_eq!(trials.iter().map(figures).collect::<Vec<_>>(), all[..ran].iter().map(figures).collect::<Vec<_>>());
        assert!(trials.iter().all(|t| t.score >= best.trial.score));
        let warning = best.output.report.warnings.iter().find(|w| w.contains("size search stopped after"));
        assert!(warning.is_some_and(|w| w.contains(&format!("after {ran} of "))), "{warning:?}");
    }

    #[test]
    fn broken_patches_raise_the_score() {
        let fidelity = |mean_distance, broken_fraction| PatchFidelity {
            mean_distance,
            p90_distance: 0.0,
            broken_fraction,
            patches: 10,
            exemplar_coverage: 1.0,
        };
        assert_eq!(score(&fidelity(0.02, 0.0)), 0.02);
        assert!(score(&fidelity(0.019, 0.05)) > score(&fidelity(0.02, 0.0)));
        assert!(score(&fidelity(0.019, 0.001)) < score(&fidelity(0.02, 0.0)));
    }
}
