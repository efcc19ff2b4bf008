//! Preparing a synthesis (the [`Setup`]), stage by stage in the order its checks fail: the
//! attributes, the exemplar and its scales, the region, the quadrature and the expected count,
//! the exemplar's neighbour structures and the existing points.

use motif_core::InvalidParameter;
use motif_core::error::check_range;
use motif_core::error::number;
use motif_core::math;

use crate::PointSet;
use crate::domain::{Quadrature, Region};
use crate::error::{AttributeRole, DomainProblem, Error};
use crate::exemplar_pairs::ExemplarPairs;
use crate::fidelity;
use crate::grid::Neighbours;
use crate::grid::{CellLists, StaticGrid};
use crate::linear::{self, Vector};
use crate::model::{Exemplar, ExemplarElement, Rigid, State};
use crate::params::{Input, Params};
use crate::setup::{AttributeMap, Setup};
use crate::{InputError, LimitError};

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

/// The synthesized attributes' names and their columns in `source`: each name must be a column of
/// the exemplar, and every name the discrete, continuous and weight options give must be
/// synthesized (weights within their range).
fn attribute_columns(source: &PointSet, params: &Params) -> Result<(Vec<String>, Vec<usize>), Error> {
    let names: Vec<String> = match &params.attributes {
        Some(names) => names.clone(),
        None => source.attribute_names.clone(),
    };
    let mut columns = Vec::new();
    for name in &names {
        match source.attribute_names.iter().position(|c| c == name) {
            Some(c) => columns.push(c),
            None => {
                return Err(Error::Input(InputError::UnknownAttribute {
                    name: name.clone(),
                    role: AttributeRole::Synthesized,
                    available: source.attribute_names.clone(),
                }));
            }
        }
    }
    for name in params.discrete_attributes.iter().chain(&params.continuous_attributes) {
        if !names.contains(name) {
            return Err(Error::Input(InputError::UnknownAttribute {
                name: name.clone(),
                role: AttributeRole::DiscreteOrContinuous,
                available: names.clone(),
            }));
        }
    }
    for (name, weight) in &params.attribute_weights {
        if !names.contains(name) {
            return Err(Error::Input(InputError::UnknownAttribute {
                name: name.clone(),
                role: AttributeRole::Weighted,
                available: names.clone(),
            }));
        }
        check_range(&format!("attribute weight of {name}"), *weight, 1e-6, 100.0)?;
    }
    Ok((names, columns))
}

/// How the exemplar's attributes become features: each one's mean and factor (its weight over its
/// standard deviation), and the allowed values of those that are discrete (given, or detected as
/// labels).
fn attribute_map(source: &PointSet, params: &Params) -> Result<AttributeMap, Error> {
    let n = source.len();
    let (names, columns) = attribute_columns(source, params)?;
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
            // One value everywhere (a normal's zero component, a fixed label): it carries no
            // structure, so its feature is 0 at every point (no weight in any distance), and as
            // its one allowed value it is written back exactly at every output point.
            mean.push(mu);
            factor.push(1.0);
            discrete[c + 1] = vec![0.0];
            discrete_values[c + 1] = vec![mu];
            continue;
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
    Ok(AttributeMap { names, columns, mean, factor, discrete, discrete_values })
}

impl AttributeMap {
    /// Feature channels per point: the density channel and one per attribute.
    fn channels(&self) -> usize {
        1 + self.columns.len()
    }

    /// The features of point `i` of `set` (the density channel 1, then each attribute made
    /// unit-free); `map` gives the column of `set` that holds each attribute.
    fn features(&self, set: &PointSet, i: usize, map: &[usize]) -> Vec<f64> {
        let mut f = vec![1.0];
        for (c, &column) in map.iter().enumerate() {
            f.push((set.attributes_of(i)[column] - self.mean[c]) * self.factor[c]);
        }
        f
    }
}

/// The exemplar's elements (points sharing a non-negative element id) with their centres, and the
/// element of each point.
fn exemplar_elements<const D: usize>(
    source: &PointSet,
    positions: &[Vector<D>],
) -> (Vec<Option<u32>>, Vec<ExemplarElement<D>>) {
    let mut element_of = vec![None; source.len()];
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
    (element_of, elements)
}

/// Checks a length against the exemplar's mean spacing: a window narrower than half a spacing
/// holds no neighbour, a Gaussian wider than ten spacings blurs every structure away, and both
/// only cost time.
fn check_relative(name: &str, value: f64, low: f64, high: f64, spacing: f64) -> Result<(), Error> {
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
}

/// The kernel width σ and the neighbourhood δ of a synthesis.
#[derive(Debug, Clone, Copy)]
struct Scales {
    sigma: f64,
    delta: f64,
}

/// The exemplar as features (positions in `D` coordinates, features, elements, spacing, window),
/// and σ and δ, given or inferred, checked against its spacing.
fn exemplar<const D: usize>(
    input: &Input,
    params: &Params,
    attributes: &AttributeMap,
) -> Result<(Exemplar<D>, Scales), Error> {
    let source = &input.exemplar;
    let n = source.len();
    let positions: Vec<Vector<D>> = (0..n).map(|i| vector(source.position(i))).collect();
    let channels = attributes.channels();
    let mut features = Vec::with_capacity(n * channels);
    for i in 0..n {
        features.extend(attributes.features(source, i, &attributes.columns));
    }
    let (element_of, elements) = exemplar_elements(source, &positions);
    let spacing = fidelity::mean_spacing(&positions);
    if spacing <= 0.0 || !spacing.is_finite() {
        return Err(zero_spacing_error(&positions));
    }
    let sigma = params.sigma.unwrap_or(params.spacing_fraction * spacing);
    let delta = params
        .neighbourhood
        .unwrap_or_else(|| crate::Params::inferred_neighbourhood(input.exemplar.dimension, spacing));
    check_relative("neighbourhood", delta, 0.5, 200.0, spacing)?;
    check_relative("sigma", sigma, 0.02, 10.0, spacing)?;
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
    Ok((exemplar, Scales { sigma, delta }))
}

/// The region to fill, from the input's domain (a volume mesh's triangle tree checked against the
/// memory limit first).
fn region<const D: usize>(input: &Input, params: &Params) -> Result<Region<D>, Error> {
    if let crate::params::Domain::Volume(mesh) = &input.domain {
        // The triangle tree (corners and node bounds) and the sorted edge lists of the checks.
        let mut estimate = motif_core::MemoryEstimate::new();
        estimate.add("mesh triangles", mesh.triangles.len() as f64, 72.0 + 64.0 + 6.0 * 16.0);
        estimate.check(params.max_memory, MEMORY_ADVICE)?;
    }
    Region::<D>::new(&input.domain).map_err(|problem| Error::Input(InputError::EmptyDomain(problem)))
}

/// The points of an earlier synthesis (progressive synthesis; none otherwise) as the domain sees
/// them: where they lie, and the margin around the new region within which they may move.
struct Existing<const D: usize> {
    positions: Vec<Vector<D>>,
    /// `positions`, searched within `radius`.
    grid: StaticGrid<D>,
    /// 2σ: quadrature points this close to an existing point are not filled anew.
    radius: f64,
    /// The band around the region where existing points move and the quadrature extends; `None`
    /// without existing points.
    margin: Option<f64>,
}

impl<const D: usize> Existing<D> {
    fn new(input: &Input, params: &Params, scales: Scales) -> Self {
        let positions: Vec<Vector<D>> = match &input.existing {
            Some(set) => (0..set.len()).map(|i| vector(set.position(i))).collect(),
            None => Vec::new(),
        };
        let margin =
            input.existing.as_ref().map(|_| params.keep_margin.unwrap_or(Params::DEFAULT_KEEP_MARGIN * scales.delta));
        let radius = 2.0 * scales.sigma;
        let grid = StaticGrid::new(&positions, radius);
        Self { positions, grid, radius, margin }
    }

    /// Whether an existing point lies within 2σ of `q`.
    fn near(&self, q: &Vector<D>) -> bool {
        let mut found = false;
        self.grid.for_each_within(q, self.radius, |_, _, _| found = true);
        found
    }
}

/// The quadrature: a grid of spacing h over the region's bounds (widened by the margin around
/// existing points) keeping the nodes in the region or near existing points in its margin; on a
/// surface, the band the nodes round to (the exemplar's window thickened to match). Returns the
/// quadrature, the grid's cell count and h.
fn quadrature<const D: usize>(
    params: &Params,
    region: &mut Region<D>,
    exemplar: &mut Exemplar<D>,
    existing: &Existing<D>,
    scales: Scales,
) -> Result<(Quadrature<D>, f64, f64), Error> {
    let Scales { sigma, delta } = scales;
    let margin = existing.margin;
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
    if let Region::Surface { band, surface } = &mut *region {
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
    let region = &*region;
    let keep = |q: &Vector<D>| {
        region.contains(q) || margin.is_some_and(|margin| region.distance(q) < margin && existing.near(q))
    };
    let grid_cells: f64 = (0..D).map(|a| ((high[a] - low[a]) / h).floor().max(0.0) + 1.0).product();
    memory_estimate::<D>(grid_cells, grid_cells, 0.0, exemplar.channels, 0.0)
        .check(params.max_memory, MEMORY_ADVICE)?;
    let mut quadrature = Quadrature::new(low, high, h, keep, region, &params.rotation, &params.scale)?;
    quadrature.settle_on(region);
    Ok((quadrature, grid_cells, h))
}

/// The points the exemplar's density asks for over the domain and the share of a grid cell each
/// quadrature point stands for; fails when that is more than allowed or less than one point.
fn expected_points<const D: usize>(
    input: &Input,
    params: &Params,
    region: &Region<D>,
    quadrature: &Quadrature<D>,
    h: f64,
    exemplar: &Exemplar<D>,
    margin: Option<f64>,
) -> Result<(f64, f64), Error> {
    // The grid measures Ω with a boundary layer of half a cell on every side; where the region's
    // volume is known exactly (a fresh box or polygon) the expected count follows it instead (a
    // 9 × 9 box of a unit-density exemplar holds 81 points, not the grid's 91).
    let mut expected: f64 =
        (0..quadrature.len()).map(|k| h.powi(D as i32) / quadrature.density_scale(k) * exemplar.density()).sum();
    let grid_volume = quadrature.len() as f64 * h.powi(D as i32);
    let mut node_share = 1.0;
    if let (Some(volume), None) = (region.volume(), margin) {
        expected *= volume / grid_volume.max(1e-300);
        if let Region::Surface { .. } = region {
            node_share = volume / grid_volume.max(1e-300);
        }
    }
    if expected > params.max_points as f64 {
        return Err(Error::Limit(LimitError::TooManyPoints { expected, limit: params.max_points }));
    }
    if quadrature.len() == 0 || (expected < 1.0 && input.existing.is_none()) {
        return Err(Error::Input(InputError::EmptyDomain(DomainProblem::TooSmall { expected })));
    }
    Ok((expected, node_share))
}

/// The state the synthesis starts from: the existing points (progressive synthesis), free points
/// and rigid elements, each frozen unless within the margin of the new region; empty otherwise.
fn existing_state<const D: usize>(
    input: &Input,
    attributes: &AttributeMap,
    existing: &Existing<D>,
    region: &Region<D>,
) -> Result<State<D>, Error> {
    let mut state = State::new(attributes.channels());
    let Some(set) = &input.existing else {
        return Ok(state);
    };
    let mut map = Vec::new();
    for name in &attributes.names {
        match set.attribute_names.iter().position(|c| c == name) {
            Some(c) => map.push(c),
            None => {
                return Err(Error::Input(InputError::UnknownAttribute {
                    name: name.clone(),
                    role: AttributeRole::Existing,
                    available: set.attribute_names.clone(),
                }));
            }
        }
    }
    let margin = existing.margin.unwrap_or(0.0);
    let existing = &existing.positions;
    let mut groups: std::collections::BTreeMap<i64, Vec<usize>> = std::collections::BTreeMap::new();
    for i in 0..set.len() {
        let id = set.elements.as_ref().map_or(-1, |e| e[i]);
        let x = existing[i];
        if id < 0 {
            let frozen = region.distance(&x) > margin;
            state.add_free(x, &attributes.features(set, i, &map), frozen);
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
            features.extend(attributes.features(set, p, &map));
        }
        let frozen = region.distance(&centre) > margin;
        let rigid = Rigid { centre, rotation: linear::identity(), body };
        state.add_rigid(rigid, &features, 0, frozen);
    }
    Ok(state)
}

/// What is fixed for a synthesis, in the order its checks fail: the attributes, the exemplar and
/// its scales, the region, the quadrature and the expected count (each against the limits), the
/// exemplar's neighbour structures, the existing points and the quadrature points to fill.
pub(crate) fn prepare<const D: usize>(input: &Input, params: &Params) -> Result<Setup<D>, Error> {
    let attributes = attribute_map(&input.exemplar, params)?;
    let (mut exemplar, scales) = exemplar::<D>(input, params, &attributes)?;
    let Scales { sigma, delta } = scales;
    let mut region = region::<D>(input, params)?;
    let existing = Existing::new(input, params, scales);
    let margin = existing.margin;
    let (quadrature, grid_cells, h) = quadrature(params, &mut region, &mut exemplar, &existing, scales)?;
    let (expected, node_share) = expected_points(input, params, &region, &quadrature, h, &exemplar, margin)?;
    let s_min = quadrature.scale.iter().copied().fold(f64::INFINITY, f64::min);
    // Output points inside one window's reach (a cube of side 6δ), at the densest scale.
    let reach: f64 = (0..D).map(|_| 6.0 * delta / s_min).product::<f64>() * exemplar.density();
    let total = expected + existing.positions.len() as f64;
    let estimated_memory_bytes =
        memory_estimate::<D>(grid_cells, quadrature.len() as f64, total, exemplar.channels, reach.min(total))
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
    let state = existing_state(input, &attributes, &existing, &region)?;
    let fill: Vec<usize> = (0..quadrature.len())
        .filter(|&k| region.contains(&quadrature.points[k]) && !existing.near(&quadrature.points[k]))
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

/// Why an exemplar has no positive spacing: all its points at one place, or each doubled.
fn zero_spacing_error<const D: usize>(positions: &[Vector<D>]) -> Error {
    if positions.iter().all(|p| *p == positions[0]) {
        return Error::Input(InputError::CoincidentPoints);
    }
    let mut order: Vec<usize> = (0..positions.len()).collect();
    order.sort_by(|&a, &b| positions[a].partial_cmp(&positions[b]).expect("coordinates are finite"));
    match order.windows(2).find(|w| positions[w[0]] == positions[w[1]]) {
        Some(w) => Error::Input(InputError::DuplicatedPoints { first: w[0].min(w[1]), second: w[0].max(w[1]) }),
        None => Error::Input(InputError::CoincidentPoints),
    }
}
