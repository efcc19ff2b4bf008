//! Rings from pieces of ways: a multipolygon's member ways joined end to end, and the land
//! polygons that coastlines cut from the map's rectangle (land on the left of a coastline, as
//! OpenStreetMap draws them).

use crate::mercator::UnitPoint;

/// Joins pieces that share end points into rings, reversing pieces where needed (the members of
/// a multipolygon are in any direction). A chain that cannot be closed (its ways were cut off by
/// the extract) is closed by a straight side.
pub(crate) fn join_rings(pieces: Vec<Vec<UnitPoint>>) -> Vec<Vec<UnitPoint>> {
    let mut open: Vec<Vec<UnitPoint>> = pieces.into_iter().filter(|piece| piece.len() >= 2).collect();
    let mut rings = Vec::new();
    while let Some(mut ring) = open.pop() {
        while ring.first() != ring.last() {
            let end = ring[ring.len() - 1];
            let Some(index) = open.iter().position(|piece| piece[0] == end || piece[piece.len() - 1] == end) else {
                break;
            };
            let mut piece = open.swap_remove(index);
            if piece[0] != end {
                piece.reverse();
            }
            ring.extend_from_slice(&piece[1..]);
        }
        if ring.len() >= 3 {
            rings.push(ring);
        }
    }
    rings
}

/// Joins coastline ways into chains, keeping their direction (each way's end is the next one's
/// start).
pub(crate) fn join_chains(pieces: Vec<Vec<UnitPoint>>) -> Vec<Vec<UnitPoint>> {
    let mut open: Vec<Vec<UnitPoint>> = pieces.into_iter().filter(|piece| piece.len() >= 2).collect();
    let mut chains = Vec::new();
    while let Some(mut chain) = open.pop() {
        loop {
            let end = chain[chain.len() - 1];
            if chain.len() > 2 && chain[0] == end {
                break;
            }
            if let Some(index) = open.iter().position(|piece| piece[0] == end) {
                let piece = open.swap_remove(index);
                chain.extend_from_slice(&piece[1..]);
            } else if let Some(index) = open.iter().position(|piece| piece[piece.len() - 1] == chain[0]) {
                let mut piece = open.swap_remove(index);
                piece.extend_from_slice(&chain[1..]);
                chain = piece;
            } else {
                break;
            }
        }
        chains.push(chain);
    }
    chains
}

/// A position on the rectangle's boundary, growing counter-clockwise as the map is seen (north
/// up): from the north-east corner west along the top, south along the west side, east along the
/// bottom and north along the east side.
fn perimeter_position([x0, y0, x1, y1]: [f64; 4], [x, y]: UnitPoint) -> f64 {
    let (width, height) = (x1 - x0, y1 - y0);
    let distances = [(y - y0).abs(), (x - x0).abs(), (y1 - y).abs(), (x1 - x).abs()];
    let side = (0..4).min_by(|&a, &b| distances[a].total_cmp(&distances[b])).unwrap_or(0);
    match side {
        0 => x1 - x,
        1 => width + (y - y0),
        2 => width + height + (x - x0),
        _ => 2.0 * width + height + (y1 - y),
    }
}

/// The point of the rectangle's boundary nearest `point`.
fn onto_boundary([x0, y0, x1, y1]: [f64; 4], [x, y]: UnitPoint) -> UnitPoint {
    let (x, y) = (x.clamp(x0, x1), y.clamp(y0, y1));
    let distances = [y - y0, x - x0, y1 - y, x1 - x];
    match (0..4).min_by(|&a, &b| distances[a].total_cmp(&distances[b])).unwrap_or(0) {
        0 => [x, y0],
        1 => [x0, y],
        2 => [x, y1],
        _ => [x1, y],
    }
}

/// The land polygons that coastline chains cut from the rectangle `bounds`: closed chains are
/// islands; each open chain is extended to the boundary at both ends and joined to the next
/// chain by walking the boundary counter-clockwise (land stays on the left).
pub(crate) fn land_polygons(chains: Vec<Vec<UnitPoint>>, bounds: [f64; 4]) -> Vec<Vec<UnitPoint>> {
    let (mut polygons, mut open): (Vec<_>, Vec<_>) =
        chains.into_iter().partition(|chain| chain.len() > 3 && chain[0] == chain[chain.len() - 1]);
    for chain in &mut open {
        let (start, end) = (onto_boundary(bounds, chain[0]), onto_boundary(bounds, chain[chain.len() - 1]));
        chain.insert(0, start);
        chain.push(end);
    }
    let [x0, y0, x1, y1] = bounds;
    let perimeter = 2.0 * ((x1 - x0) + (y1 - y0));
    let corners = [[x1, y0], [x0, y0], [x0, y1], [x1, y1]];
    let starts: Vec<f64> = open.iter().map(|chain| perimeter_position(bounds, chain[0])).collect();
    let mut used = vec![false; open.len()];
    for first in 0..open.len() {
        if used[first] {
            continue;
        }
        let mut polygon = Vec::new();
        let mut current = first;
        loop {
            used[current] = true;
            polygon.extend_from_slice(&open[current]);
            let end = perimeter_position(bounds, open[current][open[current].len() - 1]);
            let ahead = |t: f64| (t - end).rem_euclid(perimeter);
            let next = (0..open.len())
                .filter(|&index| !used[index] || index == first)
                .min_by(|&a, &b| ahead(starts[a]).total_cmp(&ahead(starts[b])))
                .unwrap_or(first);
            let gap = ahead(starts[next]);
            let mut between: Vec<(f64, UnitPoint)> = corners
                .iter()
                .map(|&corner| (ahead(perimeter_position(bounds, corner)), corner))
                .filter(|&(t, _)| t > 0.0 && t < gap)
                .collect();
            between.sort_by(|a, b| a.0.total_cmp(&b.0));
            polygon.extend(between.into_iter().map(|(_, corner)| corner));
            if next == first {
                break;
            }
            current = next;
        }
        polygons.push(polygon);
    }
    polygons
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pieces_join_into_rings_in_any_direction() {
        let a = vec![[0.0, 0.0], [1.0, 0.0]];
        let b = vec![[1.0, 1.0], [1.0, 0.0]];
        let c = vec![[1.0, 1.0], [0.0, 1.0], [0.0, 0.0]];
        let rings = join_rings(vec![a, b, c]);
        assert_eq!(rings.len(), 1);
        assert_eq!(rings[0].len(), 5);
        assert_eq!(rings[0][0], rings[0][4]);
    }

    /// Twice the signed area as seen on the map (y down): positive when counter-clockwise.
    fn signed_area(ring: &[UnitPoint]) -> f64 {
        let n = ring.len();
        (0..n)
            .map(|i| {
                let ([ax, ay], [bx, by]) = (ring[i], ring[(i + 1) % n]);
                bx * ay - ax * by
            })
            .sum::<f64>()
    }

    #[test]
    fn a_coastline_across_the_map_keeps_the_land_on_its_left() {
        // A coastline running east across the middle of the unit square: land to its left, north.
        let bounds = [0.0, 0.0, 1.0, 1.0];
        let chains = join_chains(vec![vec![[0.1, 0.5], [0.5, 0.5]], vec![[0.5, 0.5], [0.9, 0.5]]]);
        assert_eq!(chains.len(), 1);
        let land = land_polygons(chains, bounds);
        assert_eq!(land.len(), 1);
        let area = signed_area(&land[0]).abs() / 2.0;
        assert!((area - 0.5).abs() < 1e-12, "{area}");
        assert!(land[0].iter().all(|&[_, y]| y <= 0.5), "{:?}", land[0]);
        // Running west, the land is the southern half.
        let land = land_polygons(vec![vec![[0.9, 0.5], [0.1, 0.5]]], bounds);
        assert!(land[0].iter().all(|&[_, y]| y >= 0.5), "{:?}", land[0]);
    }

    #[test]
    fn two_coastlines_bound_one_strip_of_land() {
        // A strait: land north of y = 0.3 (coast running east) and south of y = 0.7 (running west).
        let bounds = [0.0, 0.0, 1.0, 1.0];
        let land = land_polygons(vec![vec![[0.0, 0.3], [1.0, 0.3]], vec![[1.0, 0.7], [0.0, 0.7]]], bounds);
        let total: f64 = land.iter().map(|ring| signed_area(ring).abs() / 2.0).sum();
        assert_eq!(land.len(), 2);
        assert!((total - 0.6).abs() < 1e-12, "{total}");
    }

    #[test]
    fn a_closed_coastline_is_an_island() {
        let island = vec![[0.2, 0.2], [0.2, 0.4], [0.4, 0.4], [0.4, 0.2], [0.2, 0.2]];
        let land = land_polygons(vec![island.clone()], [0.0, 0.0, 1.0, 1.0]);
        assert_eq!(land, vec![island]);
    }
}
