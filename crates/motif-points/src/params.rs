//! Parameters of the synthesis (§4.3, §5.1, §6.2, §7.1 defaults) and its inputs.

use std::sync::Arc;

use motif_core::error::{check_count, check_positive, check_range};

use crate::PointSet;
use crate::error::Error;

/// The window function `w` delimiting a neighbourhood (§4.2–4.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Window {
    /// `w(s) = exp(-|s|²/δ²)`, truncated at `window_cutoff` δ (default 2δ); smooth in the positions (default).
    #[default]
    Gaussian,
    /// The box `|s| < δ` of Eq. 5: only points inside the window count.
    Box,
}

/// How the output points are created before optimization (§5.2).
///
/// The paper finds its solver robust to either; on real exemplars (clustered, inhibited,
/// multi-type) it is not: from random points the output crystallizes (see the fidelity figures of
/// `motif bench --engine points`), so patches are the default.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Initialization {
    /// Uniformly random positions, as many as the exemplar's density asks for.
    Random,
    /// Copies of randomly chosen exemplar patches of side `patch_size · δ` (at most 0.7 of the
    /// exemplar's smallest side), tiled over the domain; each quadrature point starts matched to
    /// the place its copy came from (default).
    #[default]
    Patches,
}

/// Which points the optimization (§5.1) may move after a patch initialization.
///
/// On the real-data corpus, every pass of merging and sampling control over copied patches moved
/// the copies' interiors away from the exemplar's structure (nearest-neighbour distance up to 2×
/// that of the copies alone): a window of δ reaches across seams, and the matches of windows that
/// straddle two copies explain neither. Keeping the interiors as copied and optimizing only the
/// seams was better on 10 of 11 cases (figures in docs/points.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Refinement {
    /// Only points near the patches' borders move (in 2D: points with a point of another copy
    /// within a quarter band, copies meeting along cuts), and sampling control removes only those
    /// (default). With random initialization every point moves.
    #[default]
    Seams,
    /// Every point moves (the paper's solver, as from random points).
    Everywhere,
    /// No optimization: the quilted patches are the output (count not controlled).
    None,
}

/// Which implementation of the energy and its gradient the solver uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Evaluator {
    /// Point-centric, parallel, with cached neighbour lists (default).
    #[default]
    Fast,
    /// A plain, sequential transcription of Eq. 5–6 per quadrature point (for tests and the speed-up
    /// figure); gives the same energy.
    Reference,
}

/// A function of the position (output units) to a field value.
pub type FieldFunction = Arc<dyn Fn(&[f64]) -> f64 + Send + Sync>;

/// A scalar field over the output domain (positions in output units).
#[derive(Clone, Default)]
pub enum Field {
    /// No field: rotation 0°, scale 1.
    #[default]
    Unset,
    /// The same value everywhere.
    Uniform(f64),
    /// Any function of the position (called once per quadrature point).
    Custom(FieldFunction),
}

impl Field {
    /// The value at `p`, or `default` for [`Field::Unset`].
    pub fn value(&self, p: &[f64], default: f64) -> f64 {
        match self {
            Field::Unset => default,
            Field::Uniform(value) => *value,
            Field::Custom(f) => f(p),
        }
    }
}

impl std::fmt::Debug for Field {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Field::Unset => write!(f, "Unset"),
            Field::Uniform(value) => write!(f, "Uniform({value})"),
            Field::Custom(_) => write!(f, "Custom(..)"),
        }
    }
}

/// A brush stroke: the region within `width / 2` of a polyline, oriented along its tangent (§6.2).
#[derive(Debug, Clone, PartialEq)]
pub struct BrushStroke {
    /// Vertices of the curve, each with `dimension` coordinates (at least 2 distinct vertices).
    pub points: Vec<Vec<f64>>,
    /// Brush width (output units, > 0): the region covered is a tube of radius `width / 2`.
    pub width: f64,
    /// Scale of the exemplar at the start of the stroke (> 0, default 1).
    pub scale_start: f64,
    /// Scale at the end; the scale varies linearly with arc length in between (> 0, default 1).
    pub scale_end: f64,
}

/// Where the output is synthesized (§6.2): quadrature points are placed on a regular grid inside it.
#[derive(Debug, Clone, PartialEq)]
pub enum Domain {
    /// The axis-aligned box `[min, max]` (2 or 3 coordinates each).
    Box {
        /// Lower corner.
        min: Vec<f64>,
        /// Upper corner.
        max: Vec<f64>,
    },
    /// A polygonal region (2D only), for example read from an SVG.
    Polygon(motif_core::Polygon),
    /// A brush stroke; the exemplar's x axis follows the stroke tangent.
    Stroke(BrushStroke),
    /// The inside of a closed triangle mesh (3D only).
    Volume(motif_core::TriangleMesh),
    /// The surface of a triangle mesh (open or closed), for a 2D exemplar: the output is 3D,
    /// every point on the mesh, the exemplar's plane laid on the tangent planes.
    Surface {
        /// The mesh.
        mesh: motif_core::TriangleMesh,
        /// Where the exemplar's x axis points on the surface.
        directions: SurfaceDirections,
    },
}

/// The orientation field of a surface domain: where the exemplar's x axis points in each tangent
/// plane (its y axis is the normal's cross product with it).
#[derive(Debug, Clone, PartialEq, Default)]
#[non_exhaustive]
pub enum SurfaceDirections {
    /// The principal direction of least curvature (a cylinder's axis), as in Figure 6 of the
    /// paper (default). Where the surface curves the same way in every direction (a plane, a
    /// sphere) it fades into the fallback: the world x axis projected on the tangent plane (y
    /// where the normal is near x).
    #[default]
    Curvature,
    /// One direction everywhere, projected on the tangent plane.
    Constant([f64; 3]),
    /// One vector per mesh vertex, interpolated across each triangle and projected.
    PerVertex(Vec<[f64; 3]>),
}

/// Parameters of [`crate::synthesize`]. Defaults follow §7.1 of the paper.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Params {
    /// Neighbourhood size δ (output units, > 0): the width of the window `w` (§4.2). Large values
    /// keep large-scale structure, small ones leave more randomness (Fig. 10). `None` (default):
    /// inferred from the exemplar, see [`Params::inferred_neighbourhood`].
    pub neighbourhood: Option<f64>,
    /// Window shape (§4.3). Default Gaussian.
    pub window: Window,
    /// Gaussian width σ (output units, > 0). Default `None`: `spacing_fraction` times the mean
    /// nearest-neighbour spacing of the exemplar (§7.1).
    pub sigma: Option<f64>,
    /// σ as a fraction of the exemplar's mean nearest-neighbour spacing when `sigma` is `None`
    /// (0.1–2, default 0.5). The paper sets σ to the spacing itself; with `g = exp(-|x|²/σ²)` the
    /// lattice frequency of a regular structure then survives in `f` only with weight
    /// `exp(-π²) ≈ 1e-4`, so regular arrangements are indistinguishable from random ones of the same
    /// density; at half the spacing it keeps `exp(-π²/4) ≈ 0.08` and structure is reproduced.
    pub spacing_fraction: f64,
    /// Spacing of the quadrature grid, in units of σ (0.25–4). §4.3 derives the spacing from the
    /// band limit of the σ-Gaussians and §7.1 sets σ to the exemplar spacing; with σ at half the
    /// spacing (see `spacing_fraction`) 2 keeps the quadrature grid at the exemplar spacing, as in
    /// the paper. Default `None`: 2, or an eighth of the neighbourhood δ when that is coarser.
    ///
    /// Why the second: the sum over quadrature points integrates `S(q)`, a window average over δ,
    /// which varies on the window's scale wherever matches are coherent; a window of many σ (the
    /// traced chain contours: δ = 35σ) needs no node every 2σ. There, 4.4σ instead of 2σ gave the
    /// same fidelity figures (nearest-neighbour 0.0050 against 0.0048, g(r) 0.638 against 0.634) in
    /// a quarter of the time; at the usual δ of 4 spacings (8σ) the two rules agree.
    pub quadrature_spacing: Option<f64>,
    /// Pairs of points farther apart than this many σ are ignored (the σ-Gaussian is below
    /// `exp(-c²/2)` there; 2–6, default 3).
    pub kernel_cutoff: f64,
    /// The Gaussian window is truncated at this many δ (1.5–4, default 3: its weight is
    /// `exp(-9)` there). Smaller is faster (the work grows with the window's area).
    pub window_cutoff: f64,
    /// Window shrink factor α per scale (§5.1; 0.5–0.99). Default `None`: the paper's 0.9, or 0.8
    /// after a patch initialization with [`Refinement::Seams`], where the copies start close to
    /// the optimum and fewer window sizes give the same fidelity in 35–40 % less time (measured on
    /// the real-data corpus; see docs/points.md).
    pub shrink: Option<f64>,
    /// Stop shrinking once δ falls below this fraction of its start (§7.1; 0.05–1, default 0.5).
    pub final_fraction: f64,
    /// Sampling-control rounds per scale (Algorithm 1; 1–20, default 1).
    pub sampling_rounds: usize,
    /// Matching/merging alternations per sampling round (Algorithm 1; 1–20, default 1).
    pub local_global_iterations: usize,
    /// Descent iterations of one position merging step (§7.1; 1–1000, default 30).
    pub merge_iterations: usize,
    /// Descent iterations of one attribute merging step (§5.1, Gauss–Seidel after the positions):
    /// conjugate-gradient steps with exact line search, since T is quadratic in the attributes at fixed
    /// positions (0–1000, default 5; 0 keeps the attributes as initialized).
    pub attribute_iterations: usize,
    /// Initial gradient step, as the root-mean-square movement per iteration in units of σ (§7.1;
    /// 1e-4–1, default 0.03); free points continue with quasi-Newton steps. Steps that raise the
    /// energy are halved and retried.
    pub step: f64,
    /// Merging stops when the mean movement falls below this (units of σ; default 1e-6, §7.1).
    pub tolerance: f64,
    /// Random starts of the matching gradient descent per quadrature point (§5.1; 1–64, default 5).
    pub matching_starts: usize,
    /// Merging also stops when an accepted step lowers T by less than this fraction of what the
    /// merging step has gained so far (0–1, default 0.01; 0 turns it off).
    pub stagnation: f64,
    /// Gradient-descent iterations per matching start (1–200, default 8).
    pub matching_iterations: usize,
    /// Exact-gradient polishing iterations of the chosen match (0–50, default 1).
    pub matching_polish: usize,
    /// Add and remove points by the sampling error density P of Eq. 7 (default true).
    pub sampling_control: bool,
    /// Keep every continuous attribute within the exemplar's range of it (its smallest to its
    /// largest value; default true): the attribute step minimizes T with those bounds. Without
    /// them the unconstrained minimum can leave the range (negative trunk diameters on the
    /// longleaf pines, normals longer than 1).
    pub attributes_within_range: bool,
    /// A quadrature point asks for a point to be added (removed) when P < -t (P > t), P measured in
    /// peak contributions of one point (0.05–10, default 0.5; the paper's ε).
    pub sampling_threshold: f64,
    /// Sampling control keeps the point count within this fraction of the count the exemplar's
    /// density asks for (0.01–1, default 0.02). T alone would empty the parts of the domain matched
    /// to the gaps of a clustered exemplar, one removal inviting the next, and it is biased towards
    /// fewer points wherever a window reaches past the exemplar's observation window (which shows
    /// nothing there): with 0.1 the small corpus exemplars came out at 0.90–0.92 of their density,
    /// held at the bound. Beyond the bound, sampling control adds or removes where the sampling
    /// density P is most off, even if T rises.
    pub count_tolerance: f64,
    /// Side of the copied patches of [`Initialization::Patches`], in units of δ (1–20, default 6).
    pub patch_size: f64,
    /// Candidate sources judged for each patch (1–256, default 48): the one whose exemplar
    /// surroundings agree best with the points already placed around the patch is copied (image
    /// quilting for points). 1 copies a random source.
    pub patch_candidates: usize,
    /// Balancing of patch sources (0–10, default 0.5; 0 takes the best-scored candidate): every
    /// candidate whose score (seams and count) is within this fraction above the best is as good,
    /// and of those the one whose exemplar points were copied least so far is taken; twice as many
    /// candidates are judged, half of them at the ends of the source range. Sources are drawn
    /// where a whole patch fits, which over-weights the exemplar's middle; balancing copies every
    /// part about equally often, so the output keeps the exemplar's statistics (corpus, seeds 1–6:
    /// the summed g(r) distance over the random set's 4.7 on average without, 3.8 with).
    pub patch_balance: f64,
    /// The exemplar's observation window as its lower and upper corners (one value per axis each;
    /// it must hold every exemplar point). The exemplar's density is its count over this volume.
    /// Default `None`: the bounding box grown by one mean spacing per axis (right for lattices; a
    /// sparse irregular pattern's box is smaller than the window it was observed in, so its
    /// density comes out too high: 15 % for 71 Swedish pines).
    pub exemplar_window: Option<(Vec<f64>, Vec<f64>)>,
    /// Gradient steps of the pair-statistics refinement after the optimization (0–1000, default
    /// 40; 0 turns it off): the movable points move so that the output's pair distances and
    /// nearest-neighbour distances follow the exemplar's (flat domains at a uniform scale).
    pub statistics_iterations: usize,
    /// Initialization (§5.2). Default patches.
    pub initialization: Initialization,
    /// Which points the optimization moves after a patch initialization. Default seams.
    pub refinement: Refinement,
    /// Rotation field in degrees, counter-clockwise in the xy-plane (§6.2). Default none.
    pub rotation: Field,
    /// Scale field (> 0; §6.2). Default none (1).
    pub scale: Field,
    /// Attributes to synthesize, by name; `None` uses all of the exemplar's attributes.
    pub attributes: Option<Vec<String>>,
    /// Attributes that take discrete values: snapped to the nearest exemplar value after each step
    /// (§4.4). Default none besides those `detect_discrete` finds.
    pub discrete_attributes: Vec<String>,
    /// Also treat as discrete every attribute whose exemplar values are all whole numbers with at
    /// most 32 distinct values (labels, types, rows), or that takes at most 4 distinct values over
    /// 20 or more points, unless listed in `continuous_attributes`. Default true.
    pub detect_discrete: bool,
    /// Attributes never treated as discrete by detection. Default none.
    pub continuous_attributes: Vec<String>,
    /// Weight of attributes relative to point density in `f` (0–100, default 1). Each attribute is
    /// first divided by its exemplar standard deviation, so its unit and range do not matter
    /// (diameters in cm next to positions in m weigh as much as labels 0/1).
    pub attribute_weight: f64,
    /// Per-attribute weights that replace `attribute_weight` for the named attributes (0–100).
    pub attribute_weights: Vec<(String, f64)>,
    /// Progressive synthesis: existing points farther than this from the new domain stay fixed
    /// (output units ≥ 0; default `None` = 3δ).
    pub keep_margin: Option<f64>,
    /// Refuse domains that ask for more points than this at the exemplar's density (default
    /// 150 000: about 2 minutes on two cores; the paper's largest case has 23 000).
    pub max_points: usize,
    /// Refuse runs whose estimated peak memory (quadrature grid and points, output points, window
    /// lists) passes this many bytes. Default [`DEFAULT_MAX_MEMORY`](motif_core::DEFAULT_MAX_MEMORY)
    /// (4 GiB); the CLI sets half of the machine's memory.
    pub max_memory: u64,
    /// Energy implementation. Default fast.
    pub evaluator: Evaluator,
    /// Seed of every random choice (matching starts, initialization).
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
        neighbourhood: None,
        window: Window::Gaussian,
        sigma: None,
        spacing_fraction: 0.5,
        quadrature_spacing: None,
        kernel_cutoff: 3.0,
        window_cutoff: 2.0,
        shrink: None,
        final_fraction: 0.5,
        sampling_rounds: 1,
        local_global_iterations: 1,
        merge_iterations: 30,
        attribute_iterations: 5,
        step: 0.03,
        tolerance: 1e-6,
        matching_starts: 5,
        stagnation: 0.01,
        matching_iterations: 8,
        matching_polish: 1,
        sampling_control: true,
        attributes_within_range: true,
        sampling_threshold: 0.5,
        count_tolerance: 0.02,
        patch_size: 6.0,
        patch_candidates: 48,
        patch_balance: 0.5,
        exemplar_window: None,
        statistics_iterations: 40,
        initialization: Initialization::Patches,
        refinement: Refinement::Seams,
        rotation: Field::Unset,
        scale: Field::Unset,
        attributes: None,
        discrete_attributes: Vec::new(),
        detect_discrete: true,
        continuous_attributes: Vec::new(),
        attribute_weight: 1.0,
        attribute_weights: Vec::new(),
        keep_margin: None,
        max_points: 150_000,
        max_memory: motif_core::DEFAULT_MAX_MEMORY,
        evaluator: Evaluator::Fast,
        seed: 0,
    };
}

/// What [`crate::synthesize`] works on.
#[derive(Debug, Clone)]
pub struct Input {
    /// The exemplar `{(e_i, b_i)}` (at least 3 points).
    pub exemplar: PointSet,
    /// Where the output grows: a box, a polygon region or a brush stroke.
    pub domain: Domain,
    /// A previous result to extend (progressive synthesis, §6.2); `None` for a fresh synthesis.
    pub existing: Option<PointSet>,
}

impl Input {
    /// A fresh synthesis of `exemplar` over `domain`.
    pub fn new(exemplar: PointSet, domain: Domain) -> Self {
        Self { exemplar, domain, existing: None }
    }

    /// The same input extending `existing` (progressive synthesis).
    #[must_use]
    pub fn with_existing(mut self, existing: PointSet) -> Self {
        self.existing = Some(existing);
        self
    }
}

impl Params {
    /// The neighbourhood δ used when none is given, in units of the exemplar's mean
    /// nearest-neighbour spacing: 4 in 2D (a window holding about 50 neighbours, the value the
    /// real-data corpus is measured at), 2 in 3D (where 4 would hold about 270 and cost minutes).
    pub const NEIGHBOURHOOD_SPACINGS: [f64; 2] = [4.0, 2.0];

    /// The δ inferred for an exemplar of `dimension` whose mean nearest-neighbour spacing is
    /// `spacing` (see [`Params::NEIGHBOURHOOD_SPACINGS`]). Continuous structures (contours,
    /// strokes sampled densely) need more: give δ about the size of the structure's features.
    pub fn inferred_neighbourhood(dimension: usize, spacing: f64) -> f64 {
        let [flat, solid] = Self::NEIGHBOURHOOD_SPACINGS;
        (if dimension >= 3 { solid } else { flat }) * spacing
    }

    /// `keep_margin` when unset, in units of the neighbourhood δ.
    pub const DEFAULT_KEEP_MARGIN: f64 = 3.0;
    /// `quadrature_spacing` when unset, in units of σ (coarser where δ / 8 is: wide windows).
    pub const DEFAULT_QUADRATURE_SPACING: f64 = 2.0;

    /// The window shrink factor α in effect (see [`Params::shrink`]).
    pub fn effective_shrink(&self) -> f64 {
        let seams = self.initialization == Initialization::Patches && self.refinement == Refinement::Seams;
        self.shrink.unwrap_or(if seams { 0.8 } else { 0.9 })
    }

    /// Checks every parameter against its documented range (the checks that need the exemplar,
    /// such as `exemplar_window` holding its points, run in [`crate::synthesize`]).
    pub fn validate(&self) -> Result<(), Error> {
        if let Some(delta) = self.neighbourhood {
            check_positive("neighbourhood", delta)?;
        }
        if let Some(sigma) = self.sigma {
            check_positive("sigma", sigma)?;
        }
        check_range("spacing-fraction", self.spacing_fraction, 0.1, 2.0)?;
        if let Some(spacing) = self.quadrature_spacing {
            check_range("quadrature-spacing", spacing, 0.25, 4.0)?;
        }
        check_range("kernel-cutoff", self.kernel_cutoff, 2.0, 6.0)?;
        check_range("window-cutoff", self.window_cutoff, 1.5, 4.0)?;
        if let Some(shrink) = self.shrink {
            check_range("shrink", shrink, 0.5, 0.99)?;
        }
        check_range("final-fraction", self.final_fraction, 0.05, 1.0)?;
        check_count("sampling-rounds", self.sampling_rounds, 1, 20)?;
        check_count("local-global-iterations", self.local_global_iterations, 1, 20)?;
        check_count("merge-iterations", self.merge_iterations, 1, 1000)?;
        check_count("attribute-iterations", self.attribute_iterations, 0, 1000)?;
        check_range("step", self.step, 1e-4, 1.0)?;
        check_range("tolerance", self.tolerance, 0.0, 1.0)?;
        check_range("stagnation", self.stagnation, 0.0, 1.0)?;
        check_count("matching-starts", self.matching_starts, 1, 64)?;
        check_count("matching-iterations", self.matching_iterations, 1, 200)?;
        check_count("matching-polish", self.matching_polish, 0, 50)?;
        check_range("sampling-threshold", self.sampling_threshold, 0.05, 10.0)?;
        check_range("count-tolerance", self.count_tolerance, 0.01, 1.0)?;
        check_range("patch-size", self.patch_size, 1.0, 20.0)?;
        check_count("patch-candidates", self.patch_candidates, 1, 256)?;
        check_range("patch-balance", self.patch_balance, 0.0, 10.0)?;
        check_count("statistics-iterations", self.statistics_iterations, 0, 1000)?;
        check_range("attribute-weight", self.attribute_weight, 1e-6, 100.0)?;
        check_count("max-points", self.max_points, 1, 100_000_000)?;
        motif_core::memory::check_max_memory(self.max_memory)?;
        if let Some(margin) = self.keep_margin {
            check_range("keep-margin", margin, 0.0, f64::MAX)?;
        }
        Ok(())
    }
}

// One `with_*` method per field: `Params::default().with_neighbourhood(Some(14.0)).with_seed(3)`.
motif_core::builders! { Params {
    with_neighbourhood => neighbourhood: Option<f64>,
    with_window => window: Window,
    with_sigma => sigma: Option<f64>,
    with_spacing_fraction => spacing_fraction: f64,
    with_quadrature_spacing => quadrature_spacing: Option<f64>,
    with_kernel_cutoff => kernel_cutoff: f64,
    with_window_cutoff => window_cutoff: f64,
    with_shrink => shrink: Option<f64>,
    with_final_fraction => final_fraction: f64,
    with_sampling_rounds => sampling_rounds: usize,
    with_local_global_iterations => local_global_iterations: usize,
    with_merge_iterations => merge_iterations: usize,
    with_attribute_iterations => attribute_iterations: usize,
    with_step => step: f64,
    with_tolerance => tolerance: f64,
    with_matching_starts => matching_starts: usize,
    with_stagnation => stagnation: f64,
    with_matching_iterations => matching_iterations: usize,
    with_matching_polish => matching_polish: usize,
    with_sampling_control => sampling_control: bool,
    with_attributes_within_range => attributes_within_range: bool,
    with_sampling_threshold => sampling_threshold: f64,
    with_count_tolerance => count_tolerance: f64,
    with_patch_size => patch_size: f64,
    with_patch_candidates => patch_candidates: usize,
    with_patch_balance => patch_balance: f64,
    with_exemplar_window => exemplar_window: Option<(Vec<f64>, Vec<f64>)>,
    with_statistics_iterations => statistics_iterations: usize,
    with_initialization => initialization: Initialization,
    with_refinement => refinement: Refinement,
    with_rotation => rotation: Field,
    with_scale => scale: Field,
    with_attributes => attributes: Option<Vec<String>>,
    with_discrete_attributes => discrete_attributes: Vec<String>,
    with_detect_discrete => detect_discrete: bool,
    with_continuous_attributes => continuous_attributes: Vec<String>,
    with_attribute_weight => attribute_weight: f64,
    with_attribute_weights => attribute_weights: Vec<(String, f64)>,
    with_keep_margin => keep_margin: Option<f64>,
    with_max_points => max_points: usize,
    with_max_memory => max_memory: u64,
    with_evaluator => evaluator: Evaluator,
    with_seed => seed: u64,
}}
