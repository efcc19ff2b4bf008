//! Parameters of analysis and synthesis, validated once at [`crate::synthesize`].

use motif_core::InvalidParameter;
use motif_core::error::{check_count, check_positive, check_range};

use crate::Error;

/// Which points an element's oriented box is fitted to (§2.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FitPoints {
    /// The stroke's skeleton: the gesture's own polyline, ignoring its width.
    #[default]
    Skeleton,
    /// The stroke's contour: its outline stroked at its width (round caps), so that thick strokes
    /// give thick boxes.
    Contour,
}

/// Perceptual similarity thresholds of the neighbourhood test (§3.1):
/// `colour and (shape or (parallelism and overlap and superimposition))`.
///
/// A measure passes when its value, averaged over the matched element pairs, is below its
/// threshold. The defaults are the paper's.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Thresholds {
    /// σ_shape, in units of L (the mean principal-axis length of the reference elements): the
    /// symmetric Hausdorff distance between two boxes with their centres aligned. Default 0.1 (0.1 L).
    pub shape: f64,
    /// σ_par, radians: the angle between principal axes. Default π/20.
    pub parallelism: f64,
    /// σ_ov, a ratio > 1: the larger over the smaller principal-axis length. Default 1.5.
    pub overlap: f64,
    /// σ_sup, in units of L: the difference of secondary-axis lengths (thickness). Default 0.1 (0.1 L).
    pub superimposition: f64,
    /// σ_col: the Euclidean distance between mean colours in the RGB unit cube. Default 0.15.
    pub colour: f64,
    /// σ_attr: the largest difference of the other stroke attributes (not in the paper, which
    /// compares colour only): relative stroke width and dash period, opacity, filled and inked
    /// (dashed) share of the length, fill colour distance. Default 0.2 (widths within a ratio of
    /// 1.25, opacities within 0.2).
    pub attributes: f64,
}

impl Default for Thresholds {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl Thresholds {
    /// The paper's thresholds (and 0.2 for the attributes it does not compare).
    pub const DEFAULT: Thresholds = Thresholds {
        shape: 0.1,
        parallelism: std::f64::consts::PI / 20.0,
        overlap: 1.5,
        superimposition: 0.1,
        colour: 0.15,
        attributes: 0.2,
    };
}

/// Parameters of [`crate::synthesize`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Params {
    /// ε, the pattern's scale in drawing units (§2): the distance below which two strokes are
    /// perceived as one element. Drives clustering (proximity < ε, continuation within ε/2 of an
    /// axis with a gap < ε). Must be > 0. Default 10.
    pub scale: f64,
    /// Points the element boxes are fitted to (§2.1). Default [`FitPoints::Skeleton`].
    pub fit: FitPoints,
    /// Neighbourhood size in rings of the neighbour graph (§3.2), 1..=5. `None` uses the paper's
    /// choices: 5 rings along a path (smooth trends need them, Fig. 5c–e) and 2 in a region (Fig. 6c–d).
    pub rings: Option<usize>,
    /// Perceptual thresholds of the neighbourhood test (§3.1). Default: the paper's.
    pub thresholds: Thresholds,
    /// Amount of parameter exchange (§3.3), 0..=1: each synthesized element's orientation, length,
    /// thickness and colour are swapped for a reference value within `variation ×` the matching
    /// threshold of that parameter. 0 (the default) leaves exact copies of reference elements.
    pub variation: f64,
    /// Position variation (§3.3): moves every element with at least k neighbours (2 along a path,
    /// 4 in a region) to its neighbours' barycentre plus its reference element's shift vector,
    /// scaled by the ratio of neighbourhood areas. Default false.
    pub position_variation: bool,
    /// Keep elements from overlapping (beyond the reference's own rate): an element whose ink meets
    /// an already placed one is moved back to its seed, left unchanged by variation, swapped for
    /// another matching element, moved slightly, or removed. Default true.
    pub avoid_overlaps: bool,
    /// Lloyd relaxation iterations for the target seeds (§3.2), 1..=1000; stops earlier once no
    /// seed moves more than 0.1 % of the element spacing. Default 20: from the stratified start,
    /// the spread of nearest-neighbour distances (coefficient of variation on 2 450 seeds in a
    /// square) falls from 0.148 after one iteration to 0.052 after 20 and only to 0.047 after 40
    /// or 80, so more iterations cost time without visible gain.
    pub lloyd_iterations: usize,
    /// Refuses targets that would need more elements than this (guards against a unit mix-up).
    /// Default 200 000.
    pub max_elements: usize,
    /// Refuse runs whose estimated peak memory (the reference's pair table, the output strokes,
    /// the layout) passes this many bytes. Default
    /// [`DEFAULT_MAX_MEMORY`](motif_core::DEFAULT_MAX_MEMORY) (4 GiB); the CLI sets half of the
    /// machine's memory.
    pub max_memory: u64,
    /// Seed of every random choice (initial seeds, candidate picks, exchanges). Default 0.
    pub seed: u64,
}

impl Default for Params {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl Params {
    /// Every parameter at its default (the values the field documentation states).
    pub const DEFAULT: Params = Params {
        scale: 10.0,
        fit: FitPoints::Skeleton,
        rings: None,
        thresholds: Thresholds::DEFAULT,
        variation: 0.0,
        position_variation: false,
        avoid_overlaps: true,
        lloyd_iterations: 20,
        max_elements: 200_000,
        max_memory: motif_core::DEFAULT_MAX_MEMORY,
        seed: 0,
    };

    /// Checks every field; the first bad one is returned ([`Error::Parameter`]).
    pub fn validate(&self) -> Result<(), Error> {
        Ok(self.check()?)
    }

    /// [`Params::validate`]'s checks, with the parameter's error itself.
    fn check(&self) -> Result<(), InvalidParameter> {
        check_positive("scale", self.scale)?;
        if let Some(rings) = self.rings {
            check_count("rings", rings, 1, 5)?;
        }
        let t = &self.thresholds;
        check_positive("thresholds.shape", t.shape)?;
        check_positive("thresholds.par", t.parallelism)?;
        if !(t.overlap.is_finite() && t.overlap > 1.0) {
            return Err(InvalidParameter::new("thresholds.ov", t.overlap, "must be a finite ratio > 1"));
        }
        check_positive("thresholds.sup", t.superimposition)?;
        check_positive("thresholds.col", t.colour)?;
        check_positive("thresholds.attr", t.attributes)?;
        check_range("variation", self.variation, 0.0, 1.0)?;
        check_count("lloyd-iterations", self.lloyd_iterations, 1, 1000)?;
        check_count("max-elements", self.max_elements, 1, usize::MAX)?;
        motif_core::memory::check_max_memory(self.max_memory)?;
        Ok(())
    }

    /// The ring count for a target kind (the paper's defaults when unset).
    pub fn rings_for(&self, along_path: bool) -> usize {
        self.rings.unwrap_or(if along_path { 5 } else { 2 })
    }
}

// One `with_*` method per field: `Params::default().with_scale(12.0).with_variation(0.3)`.
motif_core::builders! { Params {
    with_scale => scale: f64,
    with_fit => fit: FitPoints,
    with_rings => rings: Option<usize>,
    with_thresholds => thresholds: Thresholds,
    with_variation => variation: f64,
    with_position_variation => position_variation: bool,
    with_avoid_overlaps => avoid_overlaps: bool,
    with_lloyd_iterations => lloyd_iterations: usize,
    with_max_elements => max_elements: usize,
    with_max_memory => max_memory: u64,
    with_seed => seed: u64,
}}
