//! What is fixed for a synthesis (the exemplar as features, the domain and its quadrature, the
//! exemplar's neighbour structures), the initial output, and what is read off the final state
//! (the output point set, the count bounds of sampling control, the fidelity figures).

use motif_core::SeedStreams;

use crate::domain::{Quadrature, Region};
use crate::energy::Problem;
use crate::exemplar_pairs::ExemplarPairs;
use crate::fidelity::{self, Fidelity};
use crate::grid::Neighbours;
use crate::grid::{CellLists, StaticGrid};
use crate::linear::{self, Vector};
use crate::model::{Exemplar, Kernel, State};
use crate::params::{Initialization, Params, Refinement};
use crate::{PointSet, init, placement, sampling};

pub(crate) use crate::prepare::prepare;

/// Attribute bookkeeping: which exemplar columns are used and how they are made unit-free.
#[derive(Debug, Clone)]
pub(crate) struct AttributeMap {
    pub names: Vec<String>,
    pub columns: Vec<usize>,
    pub mean: Vec<f64>,
    /// Feature = (value − mean) · factor.
    pub factor: Vec<f64>,
    /// Allowed normalized values per channel (index = channel; channel 0 is the density).
    pub discrete: Vec<Vec<f64>>,
    /// The exemplar values behind `discrete` (same order), written back exactly.
    pub discrete_values: Vec<Vec<f64>>,
}

/// Everything fixed for a synthesis.
pub(crate) struct Setup<const D: usize> {
    pub exemplar: Exemplar<D>,
    /// Estimated peak memory, bytes.
    pub estimated_memory_bytes: u64,
    pub attributes: AttributeMap,
    pub sigma: f64,
    pub delta: f64,
    pub region: Region<D>,
    pub quadrature: Quadrature<D>,
    pub exemplar_grid: StaticGrid<D>,
    pub exemplar_cells: CellLists<D>,
    pub exemplar_pairs: ExemplarPairs<D>,
    pub exemplar_neighbours: Neighbours,
    pub state: State<D>,
    pub fill: Vec<usize>,
    pub margin: Option<f64>,
    pub has_elements: bool,
    /// Points the exemplar's density asks for over the quadrature domain.
    pub expected_points: f64,
    /// The share of a grid cell's volume each quadrature point stands for (see
    /// [`init::PatchLayout::node_share`]).
    pub node_share: f64,
    /// Points initialized in patch interiors and kept as copied (see `Refinement::Seams`).
    pub patch_interiors: usize,
    /// See [`crate::init::Copies::usage_variation`] (`None` without patch initialization).
    pub patch_usage_variation: Option<f64>,
}

impl<const D: usize> Setup<D> {
    pub(crate) fn allowed(&self, p: &Vector<D>) -> bool {
        // Existing points near the new region may move within the band of Ω around it.
        self.region.contains(p) || self.margin.is_some_and(|m| self.region.distance(p) < m && self.quadrature.inside(p))
    }

    /// Creates the initial output; returns the matches the initialization knows (the source of
    /// each copied patch; empty for random points).
    pub(crate) fn initialize(&mut self, params: &Params, streams: &SeedStreams) -> Vec<Vector<D>> {
        let mut state = std::mem::take(&mut self.state);
        let allowed = |p: &Vector<D>| self.allowed(p);
        let on_surface = matches!(self.region, Region::Surface { .. });
        let matches = match params.initialization {
            Initialization::Random => {
                let share = self.node_share;
                placement::random(&self.exemplar, &self.quadrature, &self.fill, &mut state, streams, &allowed, share);
                Vec::new()
            }
            Initialization::Patches => {
                // Patches of 6δ (capped at 0.7 of the exemplar's smallest side): a window reaches
                // about 2δ, so with the 2δ patches of the first version every window straddled
                // several copies, no match could explain it, and the first merging step tore the
                // copies apart (longleaf pines: g(r) distance 0.35 against 0.15 now).
                // A surface's lifted exemplar is flat along its third axis.
                let extent = (0..if on_surface { 2 } else { D })
                    .map(|a| self.exemplar.high[a] - self.exemplar.low[a])
                    .fold(f64::INFINITY, f64::min);
                let s_min = self.quadrature.scale.iter().copied().fold(f64::INFINITY, f64::min);
                let patch = (params.patch_size * self.delta).min(0.7 * extent * s_min).max(3.0 * self.sigma);
                // Candidates are judged on a band of δ (at most a third of the patch) around it;
                // interiors stay as copied: points farther than a quarter band from every border (half a
                // band moved more than it repaired: see docs/points.md; a tenth let the count drift).
                let band = self.delta.min(patch / 3.0);
                let layout = init::PatchLayout {
                    side: patch,
                    band,
                    candidates: params.patch_candidates,
                    balance: params.patch_balance,
                    seam: (params.refinement == Refinement::Seams).then_some(0.25 * band),
                    on_surface,
                    node_share: self.node_share,
                    count_tolerance: params.count_tolerance,
                };
                let settle = |p: &Vector<D>| self.region.keep_on(p);
                let settle: Option<&dyn Fn(&Vector<D>) -> Vector<D>> = on_surface.then_some(&settle);
                let (exemplar, quadrature, fill) = (&self.exemplar, &self.quadrature, &self.fill);
                let domain = init::DomainTests { allowed: &allowed, settle };
                let copies = init::patches(exemplar, quadrature, fill, layout, &mut state, streams, domain);
                self.patch_interiors = copies.interiors;
                self.patch_usage_variation = Some(copies.usage_variation);
                let centre = std::array::from_fn(|a| 0.5 * (self.exemplar.low[a] + self.exemplar.high[a]));
                copies.sources.into_iter().map(|m| m.unwrap_or(centre)).collect()
            }
        };
        state.compact();
        self.state = state;
        matches
    }

    pub(crate) fn problem(&self, delta: f64, params: &Params) -> Problem<'_, D> {
        let kernel = Kernel::new(params.window, self.sigma, delta, params.kernel_cutoff, params.window_cutoff);
        // A window is interior when everything it reaches (and the grid node each place rounds to)
        // is inside Ω; then the exemplar needs no masking there.
        let h = self.quadrature.spacing();
        let interior = self.quadrature.depth.iter().map(|&d| d as f64 * h > kernel.gather + h).collect();
        Problem {
            kernel,
            interior,
            exemplar: &self.exemplar,
            exemplar_grid: &self.exemplar_grid,
            exemplar_cells: &self.exemplar_cells,
            exemplar_pairs: &self.exemplar_pairs,
            exemplar_neighbours: &self.exemplar_neighbours,
            quadrature: &self.quadrature,
        }
    }
}

/// The count bounds of sampling control, on the points it may add or remove (those not frozen):
/// the count the exemplar's density asks for over the quadrature domain (which, in a progressive
/// synthesis, is the new region and the band of existing points that may move) ± `tolerance`.
/// When the pair-statistics refinement thins the surplus afterwards (`thinned`), the upper bound
/// is [`SURPLUS_ALLOWANCE`] instead: its removals are chosen by the pair statistics (it brings the
/// count down to the tolerance in any case). Removing the surplus here, by T, left the Swedish
/// pines from patches (`points_real`'s case, no observation window, seeds 1–6) at nearest-neighbour
/// distances of 0.012–0.058 (mean 0.038) against 0.010–0.028 (mean 0.014), and their g(r)
/// distances at 0.149–0.190 against 0.127–0.155, over half the random set's on three seeds.
pub(crate) fn count_bounds<const D: usize>(setup: &Setup<D>, tolerance: f64, thinned: bool) -> sampling::CountBounds {
    // Patch interiors lie inside the domain and count towards its density, but are not movable.
    let fixed = setup.patch_interiors;
    let above = if thinned { tolerance.max(SURPLUS_ALLOWANCE) } else { tolerance };
    sampling::CountBounds {
        least: (((1.0 - tolerance) * setup.expected_points).ceil() as usize).saturating_sub(fixed),
        most: (((1.0 + above) * setup.expected_points).floor() as usize).saturating_sub(fixed),
    }
}

/// How far over the expected count sampling control may leave the output when the pair-statistics
/// refinement thins it afterwards (the count tolerance's default before issue 34).
const SURPLUS_ALLOWANCE: f64 = 0.1;

/// The output's fidelity figures, in output units: the exemplar is scaled by the domain's mean scale.
pub(crate) fn measure_fidelity<const D: usize>(setup: &Setup<D>, output: &[Vector<D>], seed: u64) -> Fidelity {
    let quadrature = &setup.quadrature;
    let scale = quadrature.scale.iter().sum::<f64>() / quadrature.len().max(1) as f64;
    let exemplar: Vec<Vector<D>> = setup.exemplar.positions.iter().map(|p| linear::scale(p, scale)).collect();
    let region = &setup.region;
    let (low, high) = region.bounds();
    let volume = region.volume().unwrap_or(quadrature.len() as f64 * quadrature.spacing().powi(D as i32));
    let window = (linear::scale(&setup.exemplar.window_low, scale), linear::scale(&setup.exemplar.window_high, scale));
    let spacing = setup.exemplar.spacing * scale;
    let contains = |p: &Vector<D>| region.contains(p);
    let depth = |p: &Vector<D>| region.depth(p);
    if let Region::Surface { surface, .. } = region {
        // Measured along the surface (in 3D, which is the same at the scale of a few spacings):
        // areas, rings and a uniform random set of the surface; the tiled baseline tiles a square
        // of the same area in the exemplar's plane.
        let side = surface.area().sqrt();
        // As thick as the lifted exemplar's window, so that tiles stack once across it.
        let (square_low, square_high): (Vector<D>, Vector<D>) = (
            std::array::from_fn(|a| if a < 2 { 0.0 } else { window.0[a] }),
            std::array::from_fn(|a| if a < 2 { side } else { window.1[a] }),
        );
        let square_contains = |p: &Vector<D>| (0..D).all(|a| p[a] >= square_low[a] && p[a] <= square_high[a]);
        let square_depth = |p: &Vector<D>| fidelity::box_depth(p, &square_low, &square_high, 2);
        let tiling = fidelity::Domain {
            contains: &square_contains,
            depth: &square_depth,
            low: square_low,
            high: square_high,
            volume: side * side,
            dimension: 2,
            sample: None,
            tiling: None,
        };
        let sample = |choice: f64, s: f64, t: f64| -> Vector<D> {
            let p = surface.sample(choice, s, t);
            std::array::from_fn(|a| p[a])
        };
        let domain = fidelity::Domain {
            contains: &contains,
            depth: &depth,
            low,
            high,
            volume: surface.area(),
            dimension: 2,
            sample: Some(&sample),
            tiling: Some(&tiling),
        };
        return fidelity::compare(&exemplar, &window, output, &domain, spacing, seed);
    }
    let domain = fidelity::Domain {
        contains: &contains,
        depth: &depth,
        low,
        high,
        volume,
        dimension: D,
        sample: None,
        tiling: None,
    };
    fidelity::compare(&exemplar, &window, output, &domain, spacing, seed)
}

pub(crate) fn to_point_set<const D: usize>(setup: &Setup<D>, state: &State<D>) -> PointSet {
    let map = &setup.attributes;
    let mut positions = Vec::with_capacity(state.positions.len() * D);
    let mut attributes = Vec::with_capacity(state.positions.len() * map.names.len());
    for (i, p) in state.positions.iter().enumerate() {
        positions.extend_from_slice(p);
        let f = state.feature(i);
        for c in 0..map.names.len() {
            let allowed = &map.discrete[c + 1];
            let value = match allowed.iter().position(|&a| a == f[c + 1]) {
                // A snapped label: the exemplar's own value, without the round trip's rounding.
                Some(index) => map.discrete_values[c + 1][index],
                None => f[c + 1] / map.factor[c] + map.mean[c],
            };
            attributes.push(value);
        }
    }
    PointSet {
        dimension: D,
        positions,
        attribute_names: map.names.clone(),
        attributes,
        elements: setup.has_elements.then(|| state.element_id.clone()),
    }
}
