//! Incremental re-synthesis (the paper's future work, §4: re-synthesis while the curve is edited).
//!
//! [`Incremental`] keeps what the last run computed and reuses every part an edit leaves as it
//! was: the valid positions of each piece, keyed by what decides them (the piece's shape in the
//! exemplar and the forbidden pixels it covers), and the rows of the dynamic program from the
//! first piece up to the first one whose row differs (a row of Eq. 1 depends only on the rows
//! before it). Bent pieces are all the same straight rectangle in the exemplar, whatever the
//! curve, so after an edit that keeps the number of pieces only the last row, the render and the
//! fold-over test are redone; rigid pieces are redone from the first piece the edit moved. The
//! result is the same, byte for byte, as a run from scratch.

use std::collections::HashMap;
use std::hash::{DefaultHasher, Hash, Hasher};

use motif_core::{Progress, RgbaImage};

use crate::dp::DpTable;
use crate::exemplar::Run;
use crate::piece::{PieceFrame, Position};
use crate::{Error, Input, Output, Params};

/// A synthesis session that re-solves only what changed since its last run.
///
/// ```
/// use motif_core::{NoProgress, Point, Polyline, RgbaImage};
/// use motif_curve::{Input, Params, Incremental};
///
/// // A strip of dots, drawn along a line, then along the same line with its end moved.
/// let exemplar = RgbaImage::from_fn(60, 16, |x, y| {
///     let (dx, dy) = ((x % 12) as f64 - 5.5, y as f64 - 7.5);
///     if dx * dx + dy * dy < 16.0 { [200, 60, 20, 255] } else { [0; 4] }
/// });
/// let params = Params::default().with_width(16.0).with_piece_length(10.0);
/// let mut session = Incremental::new();
/// for end in [200.0, 210.0] {
///     let curve = Polyline::new(vec![Point::new(10.0, 20.0), Point::new(end, 40.0)], false).unwrap();
///     let input = Input { exemplar: &exemplar, curve: &curve, avoidance: None, more_exemplars: &[] };
///     let output = session.synthesize(&input, &params, &mut NoProgress).unwrap();
///     assert!(output.report.pieces >= 19);
/// }
/// assert!(session.reused_rows() > 0);
/// ```
#[derive(Debug, Default)]
pub struct Incremental {
    cache: Cache,
}

impl Incremental {
    /// An empty session.
    pub fn new() -> Self {
        Self::default()
    }

    /// [`synthesize`](crate::synthesize), reusing what the previous call of this session computed.
    /// Changing the parameters or the exemplars starts afresh.
    pub fn synthesize(
        &mut self,
        input: &Input<'_>,
        params: &Params,
        progress: &mut dyn Progress,
    ) -> Result<Output, Error> {
        let key = session_key(input, params);
        if key != self.cache.key {
            self.cache = Cache { key, ..Cache::default() };
        }
        crate::pipeline::synthesize_with(input, params, progress, Some(&mut self.cache))
    }

    /// Rows of the dynamic program the last call took from the previous one.
    pub fn reused_rows(&self) -> usize {
        self.cache.reused_rows
    }
}

/// What a session keeps between runs.
#[derive(Debug, Default)]
pub(crate) struct Cache {
    /// The parameters and exemplars the cache belongs to.
    key: u64,
    /// Valid positions by piece signature (see [`piece_signature`]), of the last run.
    pub valid: HashMap<u64, Vec<Position>>,
    /// Chain signature of each row of the last run's DP (row `r` depends on rows `..=r`).
    pub chain: Vec<u64>,
    /// `P` after each row of the last run.
    pub costs: Vec<Vec<u64>>,
    /// Best predecessors of rows `1..` of the last run.
    pub predecessors: Vec<Vec<u32>>,
    /// Rows reused by the last run.
    pub reused_rows: usize,
    /// The prepared (padded) exemplar of the last run.
    pub exemplar: Option<std::sync::Arc<crate::exemplar::Exemplar>>,
}

impl Cache {
    /// Runs the open-curve DP over rows with chain signatures `chain`, reusing the longest prefix
    /// of rows that the last run computed with the same signatures. `solve_from(start, costs)`
    /// computes rows `start..` given `P` of row `start − 1`, keeping `P` of every row.
    pub(crate) fn solve_rows(
        &mut self,
        chain: Vec<u64>,
        first_row: usize,
        solve_from: impl FnOnce(usize, Vec<u64>) -> DpTable,
    ) -> DpTable {
        let same = chain.iter().zip(&self.chain).take_while(|(a, b)| a == b).count();
        // Row 0 costs nothing anywhere; the first computed row is 1 at least.
        let start = same.max(1);
        let initial = if same >= 1 { self.costs[start - 1].clone() } else { vec![0; first_row] };
        let tail = solve_from(start, initial.clone());
        let mut costs = if same >= 1 { self.costs[..start].to_vec() } else { vec![initial] };
        costs.extend(tail.row_costs.iter().cloned());
        let mut predecessors = self.predecessors[..start - 1].to_vec();
        predecessors.extend(tail.predecessors.iter().cloned());
        self.reused_rows = start - 1;
        self.chain = chain;
        self.costs = costs;
        self.predecessors = predecessors.clone();
        DpTable { predecessors, row_costs: Vec::new(), ..tail }
    }
}

/// A hash of everything the cache is valid for: the parameters and the exemplars' pixels.
fn session_key(input: &Input<'_>, params: &Params) -> u64 {
    let mut hasher = DefaultHasher::new();
    format!("{params:?}").hash(&mut hasher);
    for image in std::iter::once(input.exemplar).chain(input.more_exemplars) {
        hash_image(image, &mut hasher);
    }
    hasher.finish()
}

fn hash_image(image: &RgbaImage, hasher: &mut DefaultHasher) {
    (image.width(), image.height()).hash(hasher);
    image.pixels().hash(hasher);
}

/// What decides a piece's valid positions besides the exemplar and the parameters: its shape in
/// the exemplar and the footprints that must stay invisible.
pub(crate) fn piece_signature(frame: &PieceFrame, forbidden: &[Run]) -> u64 {
    let mut hasher = DefaultHasher::new();
    frame.samples.hash(&mut hasher);
    for value in [frame.height, frame.top_right.x, frame.top_right.y, frame.bottom_right.x, frame.bottom_right.y] {
        value.to_bits().hash(&mut hasher);
    }
    for run in forbidden {
        (run.dy, run.x0, run.x1).hash(&mut hasher);
    }
    hasher.finish()
}

/// The chain signature of each DP row: row `r` is determined by the frames and positions of
/// rows `0..=r`.
pub(crate) fn chain_signatures(frames: &[&PieceFrame], positions: &[&[Position]]) -> Vec<u64> {
    let mut chain = Vec::with_capacity(frames.len());
    let mut previous = 0_u64;
    for (frame, positions) in frames.iter().zip(positions) {
        let mut hasher = DefaultHasher::new();
        previous.hash(&mut hasher);
        piece_signature(frame, &[]).hash(&mut hasher);
        positions.hash(&mut hasher);
        previous = hasher.finish();
        chain.push(previous);
    }
    chain
}
