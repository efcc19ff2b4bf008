//! Generated reference drawings, for demos, benchmarks and tests: a 1D row of sketchy hatches and
//! a 2D field of small three-stroke figures. Pure functions of their arguments and seed.

use motif_core::math;
use motif_core::random::Rng;
use motif_core::{Point, Polyline, SeedStreams};

use crate::stroke::Stroke;

/// A row of hatches along +x.
#[derive(Debug, Clone, PartialEq)]
pub struct HatchRow {
    /// Number of hatch elements.
    pub count: usize,
    /// Distance between hatch centres along x.
    pub spacing: f64,
    /// Hatch length.
    pub length: f64,
    /// Overlapping near-collinear strokes per hatch (a sketchy gesture), ≥ 1.
    pub strokes_per_hatch: usize,
    /// Stroke width.
    pub width: f64,
    /// Largest random displacement of a hatch centre across the row (position variation).
    pub jitter: f64,
}

impl Default for HatchRow {
    fn default() -> Self {
        HatchRow { count: 60, spacing: 8.0, length: 24.0, strokes_per_hatch: 3, width: 1.2, jitter: 0.0 }
    }
}

/// Strokes of a hatch row whose `i`-th hatch is turned by `angle(i)` radians from vertical and
/// drawn in `colour(i)`, starting at `origin`.
pub fn hatch_row(
    row: &HatchRow,
    origin: Point,
    angle: impl Fn(usize) -> f64,
    colour: impl Fn(usize) -> [u8; 4],
    seed: u64,
) -> Vec<Stroke> {
    let streams = SeedStreams::new(seed);
    let mut strokes = Vec::new();
    let parts = row.strokes_per_hatch.max(1);
    for i in 0..row.count {
        let mut random = streams.stream("hatch", i as u64);
        let jitter = if row.jitter > 0.0 { random.random_range(-row.jitter..=row.jitter) } else { 0.0 };
        let centre = origin + kurbo::Vec2::new(i as f64 * row.spacing, jitter);
        let theta = angle(i);
        let direction = kurbo::Vec2::new(math::sin(theta), -math::cos(theta));
        let normal = kurbo::Vec2::new(-direction.y, direction.x);
        // Pieces of length 1.6 L / parts that overlap and together cover [-L/2, L/2].
        let piece = (1.6 * row.length / parts as f64).min(row.length);
        for k in 0..parts {
            let start = if parts == 1 {
                -0.5 * row.length
            } else {
                -0.5 * row.length + k as f64 * (row.length - piece) / (parts - 1) as f64
            };
            let wobble = |random: &mut motif_core::random::Stream| random.random_range(-0.3..=0.3) * row.width;
            let a = centre + direction * start + normal * wobble(&mut random);
            let b = centre + direction * (start + piece) + normal * wobble(&mut random);
            // A zero hatch length gives no stroke rather than a panic.
            if let Ok(polyline) = Polyline::new(vec![a, a.midpoint(b) + normal * wobble(&mut random), b], false) {
                strokes.push(Stroke::new(polyline, row.width, colour(i), None));
            }
        }
    }
    strokes
}

/// A jittered grid of small three-stroke figures alternating between two kinds: a three-armed
/// star (dark blue) and a triangle drawn as three strokes (red), each randomly turned.
#[derive(Debug, Clone, PartialEq)]
pub struct FigureField {
    /// Columns of the grid.
    pub columns: usize,
    /// Rows of the grid.
    pub rows: usize,
    /// Grid spacing.
    pub spacing: f64,
    /// Figure radius.
    pub radius: f64,
    /// Largest random displacement of a figure from its grid point.
    pub jitter: f64,
    /// Stroke width.
    pub width: f64,
}

impl Default for FigureField {
    fn default() -> Self {
        FigureField { columns: 12, rows: 10, spacing: 28.0, radius: 5.0, jitter: 3.0, width: 1.5 }
    }
}

/// Strokes of a figure field with its first grid point at `origin`.
pub fn figure_field(field: &FigureField, origin: Point, seed: u64) -> Vec<Stroke> {
    let streams = SeedStreams::new(seed);
    let mut strokes = Vec::new();
    for row in 0..field.rows {
        for column in 0..field.columns {
            let index = row * field.columns + column;
            let mut random = streams.stream("figure", index as u64);
            let centre = origin
                + kurbo::Vec2::new(
                    column as f64 * field.spacing + random.random_range(-field.jitter..=field.jitter),
                    row as f64 * field.spacing + random.random_range(-field.jitter..=field.jitter),
                );
            let turn: f64 = random.random_range(0.0..std::f64::consts::TAU);
            let corner = |k: usize| {
                let a = turn + std::f64::consts::TAU * k as f64 / 3.0;
                centre + kurbo::Vec2::new(math::cos(a), math::sin(a)) * field.radius
            };
            let star = (row + column) % 2 == 0;
            for k in 0..3 {
                let points = if star { vec![centre, corner(k)] } else { vec![corner(k), corner(k + 1)] };
                let colour = if star { [30, 50, 140, 255] } else { [200, 40, 40, 255] };
                if let Ok(polyline) = Polyline::new(points, false) {
                    strokes.push(Stroke::new(polyline, field.width, colour, None));
                }
            }
        }
    }
    strokes
}
