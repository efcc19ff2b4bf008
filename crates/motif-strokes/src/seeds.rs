//! Seed distributions by Lloyd relaxation (§3.2): along a target path (1D, Voronoi cells in arc
//! length) and inside a target polygon (2D, clipped centroidal Voronoi tessellation).
//!
//! The 2D Voronoi cells are the duals of a `spade` Delaunay triangulation. Four far-away guard
//! sites around the region make every seed's cell bounded without changing it inside the region
//! (their bisectors with any seed lie far outside). Cells are clipped to the region with
//! Sutherland–Hodgman (a convex clip window, any simple subject polygon); cells that meet no region
//! edge skip the clip.

use motif_core::random::Rng;
use motif_core::vector;
use motif_core::{Point, Polygon, SeedStreams};
use rayon::prelude::*;
use rstar::primitives::Rectangle;
use rstar::{AABB, RTree};
use spade::{DelaunayTriangulation, Point2, Triangulation};

use crate::distribution::Site;
use crate::maps::Maps;

/// Seeds along a path of arc length `length`: `count` stratified random positions relaxed by
/// Lloyd's method, where each seed's Voronoi cell is the arc between the midpoints to its
/// neighbours (clipped to `[0, length]` on an open path, wrapping on a closed one). Returns the
/// sorted arc-length positions and the iterations run.
pub(crate) fn lloyd_path(
    length: f64,
    closed: bool,
    count: usize,
    iterations: usize,
    streams: &SeedStreams,
) -> (Vec<f64>, usize) {
    let spacing = length / count.max(1) as f64;
    let mut positions: Vec<f64> = (0..count)
        .map(|i| {
            let jitter: f64 = streams.stream("seeds", i as u64).random();
            (i as f64 + jitter) * spacing
        })
        .collect();
    let mut next = vec![0.0; count];
    let mut run = 0;
    while run < iterations && count > 0 {
        run += 1;
        let mut largest_move: f64 = 0.0;
        for i in 0..count {
            let here = positions[i];
            let low = match (i, closed) {
                (0, false) => 0.0,
                (0, true) => 0.5 * (positions[count - 1] - length + here),
                _ => 0.5 * (positions[i - 1] + here),
            };
            let high = match (i + 1 == count, closed) {
                (true, false) => length,
                (true, true) => 0.5 * (here + positions[0] + length),
                _ => 0.5 * (here + positions[i + 1]),
            };
            let centre = 0.5 * (low + high);
            largest_move = largest_move.max((centre - here).abs());
            next[i] = if closed { centre.rem_euclid(length) } else { centre };
        }
        std::mem::swap(&mut positions, &mut next);
        if closed {
            positions.sort_by(f64::total_cmp);
        }
        if largest_move < 1e-3 * spacing {
            break;
        }
    }
    (positions, run)
}

/// Per-thread buffers of a 2D Lloyd step.
#[derive(Default)]
struct CellScratch {
    cell: Vec<Point>,
    clipped: Vec<Point>,
    swap: Vec<Point>,
}

/// The largest oversampling of the stratified start for a density map (largest over mean density).
const MAX_OVERSAMPLING: f64 = 256.0;

/// The most cells the stratified start's grid may have; past it, random points are drawn instead.
const MAX_GRID_CELLS: f64 = 4_000_000.0;

/// `count` random points inside `region`, stratified: one jittered point per cell of a grid whose
/// cells hold one point on average; cells outside the region give none, and the shortfall or
/// excess is made up with uniform random points or by dropping random ones. A stratified start
/// leaves Lloyd's method only local work, so it converges in a few iterations.
///
/// With a density map, the grid is finer by the ratio of the largest density to the mean and each
/// point is kept with probability density / largest density (rejection sampling), so the start
/// already follows the map.
fn stratified_points(region: &Polygon, count: usize, density: &Density<'_>, streams: &SeedStreams) -> Vec<Point> {
    let bounds = region.bounds();
    let fallback = if region.contains(region.centroid()) { region.centroid() } else { interior_point(region) };
    // Capped, so that a map dark in one pixel only does not ask for a grid of billions of cells.
    let oversampling =
        if density.maps.is_uniform() { 1.0 } else { (density.largest / density.mean).min(MAX_OVERSAMPLING) };
    let cell = (region.area() / (count.max(1) as f64 * oversampling)).sqrt().max(1e-12);
    let keep = |p: Point, stream: &mut motif_core::random::Stream| {
        density.maps.is_uniform() || stream.random::<f64>() * density.largest < density.maps.density_at(p)
    };
    let columns = ((bounds.width() / cell).ceil() as usize).max(1);
    let rows = ((bounds.height() / cell).ceil() as usize).max(1);
    let mut points = Vec::with_capacity(count + count / 4);
    // Guard against a region whose bounds dwarf its area (a thin diagonal sliver): past this many
    // cells, fall back to plain uniform sampling.
    let cells = columns.saturating_mul(rows) as f64;
    if cells <= 16.0 * oversampling * count.max(1) as f64 + 16.0 && cells <= MAX_GRID_CELLS {
        for row in 0..rows {
            for column in 0..columns {
                let mut stream = streams.stream("seed grid", (row * columns + column) as u64);
                let p = Point::new(
                    bounds.x0 + (column as f64 + stream.random::<f64>()) * cell,
                    bounds.y0 + (row as f64 + stream.random::<f64>()) * cell,
                );
                if keep(p, &mut stream) && region.contains(p) {
                    points.push(p);
                }
            }
        }
    }
    let mut drop = streams.stream("seed drop", 0);
    while points.len() > count {
        let index = drop.random_range(0..points.len());
        points.swap_remove(index);
    }
    let mut extra = 0u64;
    while points.len() < count {
        let mut stream = streams.stream("seed extra", extra);
        extra += 1;
        if !density.maps.is_uniform()
            && let Some(p) = density.draw(region, &mut stream)
        {
            points.push(p);
            continue;
        }
        let mut found = None;
        for _ in 0..10_000 {
            let p = Point::new(
                bounds.x0 + stream.random::<f64>() * bounds.width(),
                bounds.y0 + stream.random::<f64>() * bounds.height(),
            );
            if region.contains(p) && keep(p, &mut stream) {
                found = Some(p);
                break;
            }
        }
        let p = found.unwrap_or(fallback);
        points.push(p);
    }
    points
}

/// Seeds inside `region`: `count` stratified random points relaxed by Lloyd's method towards a
/// centroidal Voronoi tessellation clipped to the region. Returns the points and the iterations
/// run. Every point stays inside the region: a centroid that falls outside a non-convex region
/// (possible for a cell split by the boundary) is not taken.
///
/// With a density map the tessellation is weighted: each cell's centroid is weighted by the
/// squared density (see [`crate::maps`]), integrated over the cell with 9 sub-triangles per
/// triangle of a fan.
pub(crate) fn lloyd_region(
    region: &Polygon,
    count: usize,
    iterations: usize,
    density: &Density<'_>,
    streams: &SeedStreams,
) -> (Vec<Point>, usize) {
    let bounds = region.bounds();
    if count == 1 && density.maps.is_uniform() {
        // Lloyd's fixed point for one seed: the region's centroid (when it lies inside).
        let centroid = region.centroid();
        return (vec![if region.contains(centroid) { centroid } else { interior_point(region) }], 0);
    }
    let mut positions = stratified_points(region, count, density, streams);
    let spacing = (region.area() / count.max(1) as f64).sqrt();
    let vertices = region.vertices();
    let edges: RTree<Rectangle<[f64; 2]>> = RTree::bulk_load(
        (0..vertices.len())
            .map(|i| {
                let (a, b) = (vertices[i], vertices[(i + 1) % vertices.len()]);
                Rectangle::from_corners([a.x.min(b.x), a.y.min(b.y)], [a.x.max(b.x), a.y.max(b.y)])
            })
            .collect(),
    );
    let extent = bounds.width().max(bounds.height()).max(1e-9) * 10.0;
    let middle = bounds.center();
    let guards = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(dx, dy)| Point2::new(middle.x + dx * extent, middle.y + dy * extent));
    let mut circumcentres: Vec<Point> = Vec::new();
    let mut run = 0;
    while run < iterations && count > 1 {
        run += 1;
        let mut sites: Vec<Site> =
            positions.iter().enumerate().map(|(index, p)| Site { position: Point2::new(p.x, p.y), index }).collect();
        sites.extend(guards.iter().map(|&position| Site { position, index: usize::MAX }));
        let Ok(triangulation) = DelaunayTriangulation::<Site>::bulk_load(sites) else { break };
        // Each Voronoi vertex (a triangle's circumcentre) is shared by three cells: compute it once.
        circumcentres.clear();
        circumcentres.resize(triangulation.num_all_faces(), Point::ORIGIN);
        for face in triangulation.inner_faces() {
            let c = face.circumcenter();
            circumcentres[face.fix().index()] = Point::new(c.x, c.y);
        }
        let mut handles = vec![None; count];
        for vertex in triangulation.vertices() {
            let index = vertex.data().index;
            if index != usize::MAX {
                handles[index] = Some(vertex.fix());
            }
        }
        let next: Vec<Point> = (0..count)
            .into_par_iter()
            .with_min_len(256)
            .map_init(CellScratch::default, |scratch, i| {
                let Some(handle) = handles[i] else { return positions[i] };
                scratch.cell.clear();
                for edge in triangulation.vertex(handle).out_edges() {
                    let face = edge.face();
                    if face.is_outer() {
                        return positions[i];
                    }
                    scratch.cell.push(circumcentres[face.fix().index()]);
                }
                cell_centroid(region, &edges, positions[i], density, scratch).unwrap_or(positions[i])
            })
            .collect();
        let largest_move = positions.iter().zip(&next).map(|(a, b)| vector::distance(*a, *b)).fold(0.0, f64::max);
        positions = next;
        if largest_move < 1e-3 * spacing {
            break;
        }
    }
    (positions, run)
}

/// Centroid of the Voronoi cell in `scratch.cell` intersected with the region, when it lies inside
/// the region.
fn cell_centroid(
    region: &Polygon,
    edges: &RTree<Rectangle<[f64; 2]>>,
    seed: Point,
    density: &Density<'_>,
    scratch: &mut CellScratch,
) -> Option<Point> {
    if signed_area(&scratch.cell) < 0.0 {
        scratch.cell.reverse();
    }
    let bounds = motif_core::geometry::bounds_of(&scratch.cell);
    let envelope = AABB::from_corners([bounds.x0, bounds.y0], [bounds.x1, bounds.y1]);
    let crosses_boundary = edges.locate_in_envelope_intersecting(&envelope).next().is_some();
    let cell = if !crosses_boundary && region.contains(seed) {
        &scratch.cell
    } else {
        clip_to_convex(region.vertices(), &scratch.cell, &mut scratch.clipped, &mut scratch.swap);
        &scratch.clipped
    };
    let centroid = if density.maps.is_uniform() {
        polygon_centroid(cell)?
    } else {
        weighted_centroid(cell, |p| {
            let d = density.maps.density_at(p);
            d * d
        })?
    };
    region.contains(centroid).then_some(centroid)
}

/// Sutherland–Hodgman: `subject` clipped by the convex counter-clockwise polygon `window`, into
/// `out`.
pub(crate) fn clip_to_convex(subject: &[Point], window: &[Point], out: &mut Vec<Point>, swap: &mut Vec<Point>) {
    out.clear();
    out.extend_from_slice(subject);
    for i in 0..window.len() {
        let (a, b) = (window[i], window[(i + 1) % window.len()]);
        let edge = b - a;
        let side = |p: Point| edge.cross(p - a);
        std::mem::swap(out, swap);
        out.clear();
        let n = swap.len();
        for j in 0..n {
            let (p, q) = (swap[j], swap[(j + 1) % n]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                out.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                let t = sp / (sp - sq);
                out.push(p.lerp(q, t));
            }
        }
        if out.is_empty() {
            return;
        }
    }
}

fn signed_area(points: &[Point]) -> f64 {
    let n = points.len();
    0.5 * (0..n).map(|i| points[i].to_vec2().cross(points[(i + 1) % n].to_vec2())).sum::<f64>()
}

/// Area centroid of a polygon (None when its area vanishes).
fn polygon_centroid(points: &[Point]) -> Option<Point> {
    let n = points.len();
    if n < 3 {
        return None;
    }
    // Relative to the first vertex, for precision far from the origin.
    let origin = points[0];
    let (mut twice_area, mut sum) = (0.0, kurbo::Vec2::ZERO);
    for i in 1..n - 1 {
        let (a, b) = (points[i] - origin, points[i + 1] - origin);
        let cross = a.cross(b);
        twice_area += cross;
        sum += (a + b) * cross;
    }
    (twice_area.abs() > 1e-12).then(|| origin + sum / (3.0 * twice_area))
}

/// Centroid of a polygon weighted by `weight`: the polygon as a fan of triangles from its first
/// vertex (signed, so a non-convex polygon integrates right), each split into 9 equal
/// sub-triangles weighted at their centroids. None when the weight vanishes on the polygon.
fn weighted_centroid(points: &[Point], weight: impl Fn(Point) -> f64) -> Option<Point> {
    const SPLITS: usize = 3;
    let n = points.len();
    if n < 3 {
        return None;
    }
    let origin = points[0];
    let (mut mass, mut moment) = (0.0, kurbo::Vec2::ZERO);
    for i in 1..n - 1 {
        let (a, b) = (points[i] - origin, points[i + 1] - origin);
        let area = 0.5 * a.cross(b);
        let at = |u: f64, v: f64| a * (u / SPLITS as f64) + b * (v / SPLITS as f64);
        let mut add = |p: kurbo::Vec2, q: kurbo::Vec2, r: kurbo::Vec2| {
            let centre = (p + q + r) / 3.0;
            let w = weight(origin + centre) * area;
            mass += w;
            moment += centre * w;
        };
        for u in 0..SPLITS {
            for v in 0..SPLITS - u {
                let (uf, vf) = (u as f64, v as f64);
                add(at(uf, vf), at(uf + 1.0, vf), at(uf, vf + 1.0));
                if u + v + 2 <= SPLITS {
                    add(at(uf + 1.0, vf), at(uf + 1.0, vf + 1.0), at(uf, vf + 1.0));
                }
            }
        }
    }
    (mass.abs() > 1e-300).then(|| origin + moment / mass)
}

/// The density a region's seeds follow, with its mean and largest value over the region.
pub(crate) struct Density<'a> {
    /// The maps (uniform without any).
    pub maps: &'a Maps<'a>,
    /// Mean relative density over the region.
    pub mean: f64,
    /// Largest relative density over the region.
    pub largest: f64,
    /// The sample grid's points inside the region with a positive density, and the running sum
    /// of their densities: draws follow the density without rejection.
    samples: Vec<Point>,
    cumulative: Vec<f64>,
    /// Size of a sample cell.
    cell: (f64, f64),
}

impl<'a> Density<'a> {
    /// Samples per side of the grid the statistics are taken on: at least the maps' resolution,
    /// so that a feature of one pixel is seen, within these bounds.
    const SAMPLES: (usize, usize) = (256, 512);

    /// The uniform density of a path target (maps need a region).
    pub(crate) fn over_path(maps: &'a Maps<'a>) -> Density<'a> {
        Density { maps, mean: 1.0, largest: 1.0, samples: Vec::new(), cumulative: Vec::new(), cell: (0.0, 0.0) }
    }

    /// The density of `maps` over `region`, its mean and largest value sampled on a grid.
    pub(crate) fn over(region: &Polygon, maps: &'a Maps<'a>) -> Density<'a> {
        if maps.is_uniform() {
            return Self::over_path(maps);
        }
        let resolution = [maps.density, maps.scale].iter().flatten().map(|m| m.size().0.max(m.size().1)).max();
        let side = resolution.unwrap_or(0).clamp(Self::SAMPLES.0, Self::SAMPLES.1);
        let bounds = region.bounds();
        let cell = (bounds.width() / side as f64, bounds.height() / side as f64);
        let (mut sum, mut inside, mut largest) = (0.0, 0usize, 0.0f64);
        let (mut samples, mut cumulative) = (Vec::new(), Vec::new());
        for row in 0..side {
            for column in 0..side {
                let p = Point::new(bounds.x0 + (column as f64 + 0.5) * cell.0, bounds.y0 + (row as f64 + 0.5) * cell.1);
                if region.contains(p) {
                    let d = maps.density_at(p);
                    sum += d;
                    inside += 1;
                    largest = largest.max(d);
                    if d > 0.0 {
                        samples.push(p);
                        cumulative.push(sum);
                    }
                }
            }
        }
        let mean = if inside > 0 { sum / inside as f64 } else { maps.density_at(region.centroid()) };
        Density { maps, mean, largest: largest.max(mean), samples, cumulative, cell }
    }

    /// A random point drawn with probability proportional to the density (a sample cell by its
    /// density, then a place in it, kept only if inside the region with a positive density);
    /// `None` without dark samples.
    fn draw(&self, region: &Polygon, stream: &mut motif_core::random::Stream) -> Option<Point> {
        let total = *self.cumulative.last()?;
        let target = stream.random::<f64>() * total;
        let index = self.cumulative.partition_point(|&c| c <= target).min(self.samples.len() - 1);
        let centre = self.samples[index];
        let p = centre
            + kurbo::Vec2::new(
                (stream.random::<f64>() - 0.5) * self.cell.0,
                (stream.random::<f64>() - 0.5) * self.cell.1,
            );
        Some(if region.contains(p) && self.maps.density_at(p) > 0.0 { p } else { centre })
    }
}

/// A point inside a simple polygon: the midpoint of the widest inside stretch of the horizontal
/// line through the middle of its bounds.
pub(crate) fn interior_point(region: &Polygon) -> Point {
    let bounds = region.bounds();
    let y = bounds.center().y;
    let vertices = region.vertices();
    let n = vertices.len();
    let mut crossings: Vec<f64> = (0..n)
        .filter_map(|i| {
            let (a, b) = (vertices[i], vertices[(i + 1) % n]);
            ((a.y > y) != (b.y > y)).then(|| a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x))
        })
        .collect();
    crossings.sort_by(f64::total_cmp);
    crossings
        .chunks_exact(2)
        .max_by(|p, q| (p[1] - p[0]).total_cmp(&(q[1] - q[0])))
        .map_or(region.centroid(), |pair| Point::new(0.5 * (pair[0] + pair[1]), y))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn path_seeds_converge_to_even_spacing() {
        let streams = SeedStreams::new(1);
        let (open, _) = lloyd_path(100.0, false, 10, 400, &streams);
        for (i, s) in open.iter().enumerate() {
            assert!((s - (i as f64 + 0.5) * 10.0).abs() < 0.2, "{open:?}");
        }
        let (closed, _) = lloyd_path(100.0, true, 10, 400, &streams);
        let gaps: Vec<f64> = (0..10).map(|i| (closed[(i + 1) % 10] - closed[i]).rem_euclid(100.0)).collect();
        assert!(gaps.iter().all(|g| (g - 10.0).abs() < 0.2), "{gaps:?}");
    }

    #[test]
    fn region_seeds_are_inside_and_evenly_spread() {
        // An L-shaped (non-convex) region.
        let region = Polygon::new(vec![
            Point::new(0.0, 0.0),
            Point::new(100.0, 0.0),
            Point::new(100.0, 40.0),
            Point::new(40.0, 40.0),
            Point::new(40.0, 100.0),
            Point::new(0.0, 100.0),
        ])
        .unwrap();
        let streams = SeedStreams::new(2);
        let maps = Maps { density: None, scale: None, bounds: region.bounds() };
        let (seeds, run) = lloyd_region(&region, 200, 60, &Density::over(&region, &maps), &streams);
        assert_eq!(seeds.len(), 200);
        assert!(run > 5);
        assert!(seeds.iter().all(|&p| region.contains(p)));
        // Lloyd spreads the seeds: nearest-neighbour distances are far more even than random.
        let nearest: Vec<f64> = seeds
            .iter()
            .enumerate()
            .map(|(i, p)| {
                seeds
                    .iter()
                    .enumerate()
                    .filter(|(j, _)| *j != i)
                    .map(|(_, q)| vector::distance(*p, *q))
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        let spacing = (region.area() / 200.0).sqrt();
        let smallest = nearest.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(smallest > 0.5 * spacing, "{smallest} vs spacing {spacing}");
    }

    #[test]
    fn clipping_a_square_by_a_triangle() {
        let square = [Point::new(0.0, 0.0), Point::new(2.0, 0.0), Point::new(2.0, 2.0), Point::new(0.0, 2.0)];
        let triangle = [Point::new(0.0, 0.0), Point::new(4.0, 0.0), Point::new(0.0, 4.0)];
        let (mut out, mut swap) = (Vec::new(), Vec::new());
        clip_to_convex(&square, &triangle, &mut out, &mut swap);
        assert!((signed_area(&out) - 4.0).abs() < 1e-12);
        let small = [Point::new(0.0, 0.0), Point::new(2.0, 0.0), Point::new(0.0, 2.0)];
        clip_to_convex(&square, &small, &mut out, &mut swap);
        assert!((signed_area(&out) - 2.0).abs() < 1e-12);
        assert!(vector::distance(polygon_centroid(&out).unwrap(), Point::new(2.0 / 3.0, 2.0 / 3.0)) < 1e-12);
    }
}
