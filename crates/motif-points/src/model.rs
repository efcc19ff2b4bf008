//! The functional representation of §4.3: exemplar and output as sums of Gaussians over points
//! with feature vectors, and the kernel of the discrete error density (Eq. 5 and its Gaussian-window
//! form).
//!
//! Each point carries a feature vector `a_i = (1, w·(attributes − mean)/std)`: the constant first
//! channel makes `f` encode the point density even when attributes vanish, the others are the
//! attributes made unit-free.
//!
//! With `g(x, σ) = exp(-|x|²/σ²)` and the Gaussian window `w(s) = g(s, δ)`, the integral of Eq. 2
//! for two points at window-relative offsets `u` and `v` is, up to a constant factor,
//!
//! `K(u, v) = exp(-|u - v|² / 2σ²  -  |u + v|² / 4δ'²)`,   `δ'² = δ² + σ²/2`,
//!
//! (derivation: complete the square in `s` of `g(s+u, σ) g(s+v, σ) g(s, δ)`),
//!
//! i.e. the `g(·, √2σ)` of Eq. 5 times a window on the pair's midpoint; the box window of Eq. 5
//! instead keeps `exp(-|u - v|²/2σ²)` for points inside the window. Then
//! `S = Σ a_i·a_j K(u_i,u_j) − 2 Σ a_i·b_j K(u_i,v_j) + Σ b_i·b_j K(v_i,v_j)`.

use crate::linear::{self, Matrix, Vector};
use crate::params::Window;
use motif_core::math;

/// The kernel `K(u, v)` with its truncation (pairs beyond the cut-off, midpoints beyond the window radius).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Kernel {
    pub window: Window,
    pub sigma: f64,
    pub delta: f64,
    pub inv_sigma2: f64,
    pub half_inv_sigma2: f64,
    pub inv_delta_prime2: f64,
    pub window2: f64,
    pub cutoff2: f64,
    pub pair_floor: f64,
    pub window_floor: f64,
    /// Distance from the window centre beyond which a pair's midpoint is outside the window.
    pub window_radius: f64,
    /// Distance from the window centre beyond which a point takes part in no pair.
    pub gather: f64,
    /// The pair cut-off distance.
    pub cutoff: f64,
}

impl Kernel {
    /// `window_deltas`: the Gaussian window's truncation radius in units of δ.
    pub(crate) fn new(window: Window, sigma: f64, delta: f64, cutoff_sigmas: f64, window_deltas: f64) -> Self {
        let cutoff = cutoff_sigmas * sigma;
        let (window_radius, gather) = match window {
            Window::Gaussian => (window_deltas * delta, window_deltas * delta + 0.5 * cutoff),
            Window::Box => (delta, delta),
        };
        Self {
            window,
            sigma,
            delta,
            inv_sigma2: 1.0 / (sigma * sigma),
            half_inv_sigma2: 0.5 / (sigma * sigma),
            inv_delta_prime2: 1.0 / (delta * delta + 0.5 * sigma * sigma),
            window2: window_radius * window_radius,
            cutoff2: cutoff * cutoff,
            pair_floor: math::exp(-0.5 * cutoff_sigmas * cutoff_sigmas),
            window_floor: match window {
                Window::Gaussian => math::exp(-window_radius * window_radius / (delta * delta + 0.5 * sigma * sigma)),
                Window::Box => 0.0,
            },
            window_radius,
            gather,
            cutoff,
        }
    }

    /// `K(u, v)`, `∂K/∂u` and `∂K/∂v`; `None` when the pair is truncated.
    ///
    /// Truncation is made continuous by subtracting each Gaussian's value at its cut-off (the pair
    /// factor at `cutoff`, the window factor at the window radius), so that a pair leaving the neighbourhood does
    /// not make T jump — with plain truncation the jumps (about 1 % of a pair's weight at a 3σ
    /// cut-off) are larger than the decrease of a small gradient step and stall the descent.
    #[inline(always)]
    pub(crate) fn eval<const D: usize>(&self, u: &Vector<D>, v: &Vector<D>) -> Option<(f64, Vector<D>, Vector<D>)> {
        let d = linear::sub(u, v);
        let d2 = linear::norm2(&d);
        if d2 >= self.cutoff2 {
            return None;
        }
        // The window tests come first: they are cheaper than the exponential they may spare.
        let mid: Vector<D> = std::array::from_fn(|a| 0.5 * (u[a] + v[a]));
        let mid2 = linear::norm2(&mid);
        match self.window {
            Window::Gaussian if mid2 >= self.window2 => return None,
            Window::Box if linear::norm2(u) >= self.window2 || linear::norm2(v) >= self.window2 => return None,
            _ => {}
        }
        let pair_exp = math::exp(-d2 * self.half_inv_sigma2);
        let pair = pair_exp - self.pair_floor;
        // ∂pair/∂u = −pair_exp d/σ², ∂pair/∂v = +pair_exp d/σ².
        let pair_slope = pair_exp * self.inv_sigma2;
        match self.window {
            Window::Gaussian => {
                let window_exp = math::exp(-mid2 * self.inv_delta_prime2);
                let window = window_exp - self.window_floor;
                // ∂window/∂u = ∂window/∂v = −window_exp mid/δ'².
                let window_slope = pair * window_exp * self.inv_delta_prime2;
                let a = pair_slope * window;
                let du = std::array::from_fn(|c| -a * d[c] - window_slope * mid[c]);
                let dv = std::array::from_fn(|c| a * d[c] - window_slope * mid[c]);
                Some((pair * window, du, dv))
            }
            Window::Box => {
                Some((pair, std::array::from_fn(|c| -pair_slope * d[c]), std::array::from_fn(|c| pair_slope * d[c])))
            }
        }
    }

    /// The width `σ_P` of the sampling density of Eq. 7 with this window: `∫ g(s - u, σ) w(s) ds ∝
    /// exp(-|u|²/σ_P²)`, `σ_P² = σ² + δ²`. For the box window, `None` (counts inside δ are used).
    pub(crate) fn density_width(&self) -> Option<f64> {
        match self.window {
            Window::Gaussian => Some((self.sigma * self.sigma + self.delta * self.delta).sqrt()),
            Window::Box => None,
        }
    }
}

/// Dot product of two feature vectors.
#[inline(always)]
pub(crate) fn feature_dot(a: &[f64], b: &[f64]) -> f64 {
    let mut sum = 0.0;
    for (x, y) in a.iter().zip(b) {
        sum += x * y;
    }
    sum
}

/// A discrete element of the exemplar: its points and centre.
#[derive(Debug, Clone)]
pub(crate) struct ExemplarElement<const D: usize> {
    pub centre: Vector<D>,
    pub members: Vec<usize>,
}

/// The exemplar prepared for synthesis.
#[derive(Debug, Clone)]
pub(crate) struct Exemplar<const D: usize> {
    pub positions: Vec<Vector<D>>,
    /// `n × channels` features.
    pub features: Vec<f64>,
    pub channels: usize,
    pub element_of: Vec<Option<u32>>,
    pub elements: Vec<ExemplarElement<D>>,
    pub low: Vector<D>,
    pub high: Vector<D>,
    /// Mean nearest-neighbour spacing.
    pub spacing: f64,
    /// The observation window's corners (the given one, or the bounding box grown by one spacing
    /// per axis).
    pub window_low: Vector<D>,
    pub window_high: Vector<D>,
    /// Per channel, the smallest and the largest feature value (what the attribute step keeps
    /// output attributes within).
    pub ranges: Vec<(f64, f64)>,
}

/// Per channel of `channels`-wide feature vectors, the smallest and the largest value.
pub(crate) fn feature_ranges(features: &[f64], channels: usize) -> Vec<(f64, f64)> {
    (0..channels)
        .map(|c| {
            let values = features.iter().skip(c).step_by(channels.max(1));
            values.fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), &v| (low.min(v), high.max(v)))
        })
        .collect()
}

impl<const D: usize> Exemplar<D> {
    pub(crate) fn feature(&self, i: usize) -> &[f64] {
        &self.features[i * self.channels..(i + 1) * self.channels]
    }

    /// Points per unit volume of the observation window.
    pub(crate) fn density(&self) -> f64 {
        let volume: f64 = (0..D).map(|a| self.window_high[a] - self.window_low[a]).product();
        self.positions.len() as f64 / volume
    }
}

/// A rigid body: a discrete element of the output (§6.1).
#[derive(Debug, Clone)]
pub(crate) struct Rigid<const D: usize> {
    pub centre: Vector<D>,
    pub rotation: Matrix<D>,
    /// Offsets of the element's points from its centre, in body coordinates.
    pub body: Vec<Vector<D>>,
}

/// A unit that moves as one: a free point or a discrete element.
#[derive(Debug, Clone)]
pub(crate) struct Unit<const D: usize> {
    pub points: Vec<u32>,
    pub frozen: bool,
    pub alive: bool,
    pub rigid: Option<Rigid<D>>,
}

/// The output being synthesized.
#[derive(Debug, Clone, Default)]
pub(crate) struct State<const D: usize> {
    pub positions: Vec<Vector<D>>,
    pub features: Vec<f64>,
    pub channels: usize,
    pub unit_of: Vec<u32>,
    pub alive: Vec<bool>,
    pub units: Vec<Unit<D>>,
    /// Element id written out for each point (-1 = free).
    pub element_id: Vec<i64>,
}

impl<const D: usize> State<D> {
    pub(crate) fn new(channels: usize) -> Self {
        Self { channels, ..Self::default() }
    }

    pub(crate) fn feature(&self, i: usize) -> &[f64] {
        &self.features[i * self.channels..(i + 1) * self.channels]
    }

    /// Adds a free point; returns its unit.
    pub(crate) fn add_free(&mut self, position: Vector<D>, feature: &[f64], frozen: bool) -> usize {
        let unit = self.units.len();
        let point = self.positions.len() as u32;
        self.push_point(position, feature, unit, -1);
        self.units.push(Unit { points: vec![point], frozen, alive: true, rigid: None });
        unit
    }

    /// Adds a rigid element whose points are `centre + rotation · body[p]`; returns its unit.
    pub(crate) fn add_rigid(&mut self, rigid: Rigid<D>, features: &[f64], id: i64, frozen: bool) -> usize {
        let unit = self.units.len();
        let mut points = Vec::with_capacity(rigid.body.len());
        for (p, offset) in rigid.body.iter().enumerate() {
            let position = linear::add(&rigid.centre, &linear::mat_vec(&rigid.rotation, offset));
            points.push(self.positions.len() as u32);
            self.push_point(position, &features[p * self.channels..(p + 1) * self.channels], unit, id);
        }
        self.units.push(Unit { points, frozen, alive: true, rigid: Some(rigid) });
        unit
    }

    fn push_point(&mut self, position: Vector<D>, feature: &[f64], unit: usize, id: i64) {
        self.positions.push(position);
        self.features.extend_from_slice(feature);
        self.unit_of.push(unit as u32);
        self.alive.push(true);
        self.element_id.push(id);
    }

    /// Recomputes the positions of a rigid unit's points from its pose.
    pub(crate) fn place_rigid(&mut self, unit: usize) {
        if let Some(rigid) = &self.units[unit].rigid {
            for (p, &point) in self.units[unit].points.iter().enumerate() {
                self.positions[point as usize] =
                    linear::add(&rigid.centre, &linear::mat_vec(&rigid.rotation, &rigid.body[p]));
            }
        }
    }

    /// Moves every free point and element centre to `settle(position)` (a surface domain keeps
    /// its points on the surface this way).
    pub(crate) fn settle(&mut self, settle: impl Fn(&Vector<D>) -> Vector<D>) {
        for unit in 0..self.units.len() {
            if !self.units[unit].alive {
                continue;
            }
            match &mut self.units[unit].rigid {
                Some(rigid) => {
                    rigid.centre = settle(&rigid.centre);
                    self.place_rigid(unit);
                }
                None => {
                    let p = self.units[unit].points[0] as usize;
                    self.positions[p] = settle(&self.positions[p]);
                }
            }
        }
    }

    /// Per point: whether merging may move it (its unit is alive and not frozen).
    pub(crate) fn movable(&self) -> Vec<bool> {
        self.unit_of.iter().map(|&u| self.units[u as usize].alive && !self.units[u as usize].frozen).collect()
    }

    /// Marks a unit and its points dead (compacted later).
    pub(crate) fn kill(&mut self, unit: usize) {
        self.units[unit].alive = false;
        for &p in &self.units[unit].points {
            self.alive[p as usize] = false;
        }
    }

    /// Drops dead units and points, renumbering the rest in order.
    pub(crate) fn compact(&mut self) {
        let mut next = State::new(self.channels);
        for unit in &self.units {
            if !unit.alive {
                continue;
            }
            let new_unit = next.units.len();
            let mut points = Vec::with_capacity(unit.points.len());
            for &p in &unit.points {
                let p = p as usize;
                points.push(next.positions.len() as u32);
                next.push_point(self.positions[p], self.feature(p), new_unit, self.element_id[p]);
            }
            next.units.push(Unit { points, frozen: unit.frozen, alive: true, rigid: unit.rigid.clone() });
        }
        // Element ids are renumbered per unit so each output element has its own id.
        let mut id = 0;
        for unit in &next.units {
            if unit.rigid.is_some() {
                for &p in &unit.points {
                    next.element_id[p as usize] = id;
                }
                id += 1;
            }
        }
        *self = next;
    }
}
