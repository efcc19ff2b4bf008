//! What is fixed for a synthesis (the exemplar as features, the domain and its quadrature, the
//! exemplar's neighbour structures), the initial output, and what is read off the final state
//! (the output point set, the count bounds of sampling control, the fidelity figures).

use motif_core::InvalidParameter;
use motif_core::SeedStreams;
use motif_core::error::check_range;
use motif_core::error::number;
use motif_core::math;

use crate::domain::{Quadrature, Region};
use crate::energy::Problem;
use crate::error::{AttributeRole, DomainProblem, Error};
use crate::exemplar_pairs::ExemplarPairs;
use crate::fidelity::{self, Fidelity};
use crate::grid::Neighbours;
use crate::grid::{CellLists, StaticGrid};
use crate::linear::{self, Vector};
use crate::model::{Exemplar, ExemplarElement, Kernel, Rigid, State};
use crate::params::{Initialization, Input, Params, Refinement};
use crate::{PointSet, init, placement, sampling};

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

/// Three significant digits, for limits quoted in messages.
const MEMORY_ADVICE: &str = "use a smaller domain, a larger scale or a smaller neighbourhood";

/// The peak memory of a synthesis: the quadrature grid's look-up, the quadrature points with their
/// frames, sources and matches, the output points with attributes, gradients and merge systems,
/// and per output point the list of output points within a window's reach (the neighbour lists of
/// matching and merging).
fn memory_estimate<const D: usize>(
    grid_cells: f64,
    quadrature: f64,
    points: f64,
    channels: usize,
    window_points: f64,
) -> motif_core::MemoryEstimate {
    let d = D as f64;
    let mut estimate = motif_core::MemoryEstimate::new();
    estimate
        .add("quadrature grid", grid_cells, 4.0)
        .add("quadrature points", quadrature, 8.0 * (3.0 * d + 2.0 * d * d + 3.0))
        .add("output points", points, 8.0 * 8.0 * (d + channels as f64))
        .add("neighbour lists", points * window_points, 8.0)
        // Tables of a fixed size that 2D runs build whatever their size (measured: 3.4–3.7 MiB
        // over the rest for 41 to 820 output points, 1 or 2 threads; none in 3D).
        .add("2D statistics tables", if D == 2 { 1.0 } else { 0.0 }, 3.5 * 1024.0 * 1024.0);
    estimate
}

fn significant(value: f64) -> String {
    if value == 0.0 || !value.is_finite() {
        return number(value);
    }
    let decimals = 2 - math::log10(value.abs()).floor() as i32;
    if (0..=12).contains(&decimals) { format!("{value:.*}", decimals as usize) } else { number(value) }
}

/// The first `D` values; missing ones are 0 (a 2D exemplar lifted into the plane z = 0 for a
/// surface domain).
fn vector<const D: usize>(values: &[f64]) -> Vector<D> {
    std::array::from_fn(|a| values.get(a).copied().unwrap_or(0.0))
}

pub(crate) fn prepare<const D: usize>(input: &Input, params: &Params) -> Result<Setup<D>, Error> {
    let source = &input.exemplar;
    let n = source.len();
    let positions: Vec<Vector<D>> = (0..n).map(|i| vector(source.position(i))).collect();
    // Attributes.
    let names: Vec<String> = match &params.attributes {
        Some(names) => names.clone(),
        None => source.attribute_names.clone(),
    };
    let mut columns = Vec::new();
    for name in &names {
        match source.attribute_names.iter().position(|c| c == name) {
            Some(c) => columns.push(c),
            None => {
                return Err(Error::UnknownAttribute {
                    name: name.clone(),
                    role: AttributeRole::Synthesized,
                    available: source.attribute_names.clone(),
                });
            }
        }
    }
    for name in params.discrete_attributes.iter().chain(&params.continuous_attributes) {
        if !names.contains(name) {
            return Err(Error::UnknownAttribute {
                name: name.clone(),
                role: AttributeRole::DiscreteOrContinuous,
                available: names.clone(),
            });
        }
    }
    for (name, weight) in &params.attribute_weights {
        if !names.contains(name) {
            return Err(Error::UnknownAttribute {
                name: name.clone(),
                role: AttributeRole::Weighted,
                available: names.clone(),
            });
        }
        check_range(&format!("attribute weight of {name}"), *weight, 1e-6, 100.0)?;
    }
    let channels = 1 + columns.len();
    let mut mean = Vec::new();
    let mut factor = Vec::new();
    let mut discrete = vec![Vec::new(); channels];
    let mut discrete_values = vec![Vec::new(); channels];
    for (c, &column) in columns.iter().enumerate() {
        let values: Vec<f64> = (0..n).map(|i| source.attributes_of(i)[column]).collect();
        let mu = values.iter().sum::<f64>() / n as f64;
        let variance = values.iter().map(|v| (v - mu).powi(2)).sum::<f64>() / n as f64;
        let std = variance.sqrt();
        if std <= 1e-12 * mu.abs().max(1.0) {
            return Err(Error::ConstantAttribute { name: names[c].clone(), value: mu });
        }
        let weight =
            params.attribute_weights.iter().find(|(n, _)| n == &names[c]).map_or(params.attribute_weight, |w| w.1);
        let f = weight / std;
        mean.push(mu);
        factor.push(f);
        let mut distinct = values.clone();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup();
        // Labels: whole numbers with at most 32 values, or at most 4 values of any kind among 20
        // or more points (the demo lattice's radius 0.5/1).
        let labels = (values.iter().all(|v| v.fract() == 0.0) && distinct.len() <= 32)
            || (distinct.len() <= 4 && values.len() >= 20);
        let detected = params.detect_discrete && labels && !params.continuous_attributes.contains(&names[c]);
        if params.discrete_attributes.contains(&names[c]) || detected {
            let mut raw = values.clone();
            raw.sort_by(f64::total_cmp);
            raw.dedup_by(|a, b| (*a - *b).abs() < 1e-12 * a.abs().max(1.0));
            discrete[c + 1] = raw.iter().map(|v| (v - mu) * f).collect();
            discrete_values[c + 1] = raw;
        }
    }
    let attributes = AttributeMap { names, columns, mean, factor, discrete, discrete_values };
    let features_of = |set: &PointSet, i: usize, map: &[usize]| -> Vec<f64> {
        let mut f = vec![1.0];
        for (c, &column) in map.iter().enumerate() {
            f.push((set.attributes_of(i)[column] - attributes.mean[c]) * attributes.factor[c]);
        }
        f
    };
    let mut features = Vec::with_capacity(n * channels);
    for i in 0..n {
        features.extend(features_of(source, i, &attributes.columns));
    }
    // Elements.
    let mut element_of = vec![None; n];
    let mut elements: Vec<ExemplarElement<D>> = Vec::new();
    if let Some(ids) = &source.elements {
        let mut index: std::collections::BTreeMap<i64, u32> = std::collections::BTreeMap::new();
        for (i, &id) in ids.iter().enumerate() {
            if id < 0 {
                continue;
            }
            let e = *index.entry(id).or_insert_with(|| {
                elements.push(ExemplarElement { centre: [0.0; D], members: Vec::new() });
                (elements.len() - 1) as u32
            });
            element_of[i] = Some(e);
            elements[e as usize].members.push(i);
        }
        for element in &mut elements {
            let mut centre = [0.0; D];
            for &p in &element.members {
                linear::axpy(&mut centre, 1.0, &positions[p]);
            }
            element.centre = linear::scale(&centre, 1.0 / element.members.len() as f64);
        }
    }
    let spacing = fidelity::mean_spacing(&positions);
    if spacing <= 0.0 || !spacing.is_finite() {
        return Err(zero_spacing_error(&positions));
    }
    let sigma = params.sigma.unwrap_or(params.spacing_fraction * spacing);
    let delta = params
        .neighbourhood
        .unwrap_or_else(|| crate::Params::inferred_neighbourhood(input.exemplar.dimension, spacing));
    // Measured against the exemplar: a window narrower than half a spacing holds no neighbour, a
    // Gaussian wider than ten spacings blurs every structure away, and both only cost time.
    let relative = |name: &str, value: f64, low: f64, high: f64| -> Result<(), Error> {
        if value >= low * spacing && value <= high * spacing {
            return Ok(());
        }
        let allowed = format!(
            "must be between {} and {} (exemplar units: {low}–{high} times its mean spacing {})",
            significant(low * spacing),
            significant(high * spacing),
            significant(spacing)
        );
        Err(InvalidParameter::new(name, number(value), allowed).into())
    };
    relative("neighbourhood", delta, 0.5, 200.0)?;
    relative("sigma", sigma, 0.02, 10.0)?;
    let (low, high) = crate::grid::bounds(&positions);
    // Without a given window, each point owns about a spacing-sized cell, so the bounding box is
    // padded by half a spacing per side (a 14 × 14 grid of spacing 1 has density 1, not 196/169).
    let (window_low, window_high) = match &params.exemplar_window {
        Some((l, h)) => (vector(l), vector(h)),
        None => fidelity::exemplar_window(&positions, spacing),
    };
    let mut exemplar = Exemplar {
        positions,
        features,
        channels,
        element_of,
        elements,
        low,
        high,
        spacing,
        window_low,
        window_high,
        ranges: Vec::new(),
    };
    exemplar.ranges = crate::model::feature_ranges(&exemplar.features, channels);
    // Domain and quadrature.
    if let crate::params::Domain::Volume(mesh) = &input.domain {
        // The triangle tree (corners and node bounds) and the sorted edge lists of the checks.
        let mut estimate = motif_core::MemoryEstimate::new();
        estimate.add("mesh triangles", mesh.triangles.len() as f64, 72.0 + 64.0 + 6.0 * 16.0);
        estimate.check(params.max_memory, MEMORY_ADVICE)?;
    }
    let mut region = Region::<D>::new(&input.domain).map_err(Error::EmptyDomain)?;
    let existing: Vec<Vector<D>> = match &input.existing {
        Some(set) => (0..set.len()).map(|i| vector(set.position(i))).collect(),
        None => Vec::new(),
    };
    let margin = input.existing.as_ref().map(|_| params.keep_margin.unwrap_or(Params::DEFAULT_KEEP_MARGIN * delta));
    let existing_grid = StaticGrid::new(&existing, 2.0 * sigma);
    let near_existing = |q: &Vector<D>| {
        let mut found = false;
        existing_grid.for_each_within(q, 2.0 * sigma, |_, _, _| found = true);
        found
    };
    let (mut low, mut high) = region.bounds();
    if let Some(margin) = margin {
        for a in 0..D {
            low[a] -= margin;
            high[a] += margin;
        }
    }
    let h = params
        .quadrature_spacing
        .map_or((Params::DEFAULT_QUADRATURE_SPACING * sigma).max(delta / 8.0), |spacing| spacing * sigma);
    if let Region::Surface { band, surface } = &mut region {
        // Every point of the surface rounds to a grid node within the band (half a cell's
        // diagonal), and the lifted exemplar's window is as thick as the band.
        *band = 0.5 * 3f64.sqrt() * h * (1.0 + 1e-9);
        surface.mark_band(*band);
        exemplar.window_low[2] = -*band;
        exemplar.window_high[2] = *band;
        for a in 0..D {
            low[a] = low[a].min(region.bounds().0[a]);
            high[a] = high[a].max(region.bounds().1[a]);
        }
    }
    let keep = |q: &Vector<D>| {
        region.contains(q) || margin.is_some_and(|margin| region.distance(q) < margin && near_existing(q))
    };
    let grid_cells: f64 = (0..D).map(|a| ((high[a] - low[a]) / h).floor().max(0.0) + 1.0).product();
    memory_estimate::<D>(grid_cells, grid_cells, 0.0, channels, 0.0).check(params.max_memory, MEMORY_ADVICE)?;
    let mut quadrature = Quadrature::new(low, high, h, keep, &region, &params.rotation, &params.scale)?;
    quadrature.settle_on(&region);
    // The grid measures Ω with a boundary layer of half a cell on every side; where the region's
    // volume is known exactly (a fresh box or polygon) the expected count follows it instead (a
    // 9 × 9 box of a unit-density exemplar holds 81 points, not the grid's 91).
    let mut expected: f64 = quadrature.scale.iter().map(|s| (h / s).powi(D as i32) * exemplar.density()).sum();
    let grid_volume = quadrature.len() as f64 * h.powi(D as i32);
    let mut node_share = 1.0;
    if let (Some(volume), None) = (region.volume(), margin) {
        expected *= volume / grid_volume.max(1e-300);
        if let Region::Surface { .. } = region {
            node_share = volume / grid_volume.max(1e-300);
        }
    }
    if expected > params.max_points as f64 {
        return Err(Error::TooManyPoints { expected, limit: params.max_points });
    }
    if quadrature.len() == 0 || (expected < 1.0 && input.existing.is_none()) {
        return Err(Error::EmptyDomain(DomainProblem::TooSmall { expected }));
    }
    let s_min = quadrature.scale.iter().copied().fold(f64::INFINITY, f64::min);
    // Output points inside one window's reach (a cube of side 6δ), at the densest scale.
    let reach: f64 = (0..D).map(|_| 6.0 * delta / s_min).product::<f64>() * exemplar.density();
    let total = expected + existing.len() as f64;
    let estimated_memory_bytes =
        memory_estimate::<D>(grid_cells, quadrature.len() as f64, total, channels, reach.min(total))
            .check(params.max_memory, MEMORY_ADVICE)?;
    let cutoff = params.kernel_cutoff * sigma;
    // Cells of the pair cut-off: a query of that radius scans 3 rows (2D) or 9 rows (3D) of 3 cells.
    // Half-size cells scan less volume but, measured in 3D, cost more in per-row overhead.
    let exemplar_grid = StaticGrid::new(&exemplar.positions, cutoff / s_min);
    let exemplar_cells = CellLists::new(&exemplar.positions, cutoff / s_min);
    let exemplar_neighbours = Neighbours::build(&exemplar.positions, cutoff / s_min);
    let exemplar_pairs =
        ExemplarPairs::new(&exemplar, &exemplar_neighbours, cutoff / s_min, params.window_cutoff * delta / s_min);
    // Existing points (progressive synthesis): fixed unless near the new region.
    let mut state = State::new(channels);
    if let Some(set) = &input.existing {
        let mut map = Vec::new();
        for name in &attributes.names {
            match set.attribute_names.iter().position(|c| c == name) {
                Some(c) => map.push(c),
                None => {
                    return Err(Error::UnknownAttribute {
                        name: name.clone(),
                        role: AttributeRole::Existing,
                        available: set.attribute_names.clone(),
                    });
                }
            }
        }
        let margin = margin.unwrap_or(0.0);
        let mut groups: std::collections::BTreeMap<i64, Vec<usize>> = std::collections::BTreeMap::new();
        for i in 0..set.len() {
            let id = set.elements.as_ref().map_or(-1, |e| e[i]);
            let x = existing[i];
            if id < 0 {
                let frozen = region.distance(&x) > margin;
                state.add_free(x, &features_of(set, i, &map), frozen);
            } else {
                groups.entry(id).or_default().push(i);
            }
        }
        for (_, members) in groups {
            let mut centre = [0.0; D];
            for &p in &members {
                linear::axpy(&mut centre, 1.0, &existing[p]);
            }
            let centre = linear::scale(&centre, 1.0 / members.len() as f64);
            let body = members.iter().map(|&p| linear::sub(&existing[p], &centre)).collect();
            let mut features = Vec::new();
            for &p in &members {
                features.extend(features_of(set, p, &map));
            }
            let frozen = region.distance(&centre) > margin;
            let rigid = Rigid { centre, rotation: linear::identity(), body };
            state.add_rigid(rigid, &features, 0, frozen);
        }
    }
    let fill: Vec<usize> = (0..quadrature.len())
        .filter(|&k| region.contains(&quadrature.points[k]) && !near_existing(&quadrature.points[k]))
        .collect();
    let has_elements = !exemplar.elements.is_empty()
        || input.existing.as_ref().is_some_and(|e| e.elements.as_ref().is_some_and(|ids| ids.iter().any(|&i| i >= 0)));
    Ok(Setup {
        estimated_memory_bytes,
        exemplar,
        attributes,
        sigma,
        delta,
        region,
        quadrature,
        exemplar_grid,
        exemplar_cells,
        exemplar_pairs,
        exemplar_neighbours,
        state,
        fill,
        margin,
        has_elements,
        expected_points: expected,
        node_share,
        patch_interiors: 0,
        patch_usage_variation: None,
    })
}

impl<const D: usize> Setup<D> {
    pub fn allowed(&self, p: &Vector<D>) -> bool {
        // Existing points near the new region may move within the band of Ω around it.
        self.region.contains(p) || self.margin.is_some_and(|m| self.region.distance(p) < m && self.quadrature.inside(p))
    }

    /// Creates the initial output; returns the matches the initialization knows (the source of
    /// each copied patch; empty for random points).
    pub fn initialize(&mut self, params: &Params, streams: &SeedStreams) -> Vec<Vector<D>> {
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
                let copies =
                    init::patches(&self.exemplar, &self.quadrature, &self.fill, layout, &mut state, streams, &allowed);
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

    pub fn problem(&self, delta: f64, params: &Params) -> Problem<'_, D> {
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

/// Why an exemplar has no positive spacing: all its points at one place, or each doubled.
fn zero_spacing_error<const D: usize>(positions: &[Vector<D>]) -> Error {
    if positions.iter().all(|p| *p == positions[0]) {
        return Error::CoincidentPoints;
    }
    let mut order: Vec<usize> = (0..positions.len()).collect();
    order.sort_by(|&a, &b| positions[a].partial_cmp(&positions[b]).expect("coordinates are finite"));
    match order.windows(2).find(|w| positions[w[0]] == positions[w[1]]) {
        Some(w) => Error::DuplicatedPoints { first: w[0].min(w[1]), second: w[0].max(w[1]) },
        None => Error::CoincidentPoints,
    }
}
