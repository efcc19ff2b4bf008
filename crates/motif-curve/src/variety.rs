//! Repetition control (not in the paper, which names repetition as its limitation: on a straight
//! line the optimum may alternate two exemplar windows at zero cost).
//!
//! The penalised energy is `E = Ω + W · #{(i, j) : 0 < |i − j| ≤ R, u_i ≈ u_j}`: every pair of
//! pieces at most `R` pieces apart that copy the same exemplar window (positions closer than half
//! a piece length horizontally and a quarter of the ribbon vertically) costs `W`. A pair term
//! between pieces that are not neighbours breaks the chain structure of the dynamic program, so
//! `E` is lowered from the exact optimum of `Ω` by exact coordinate descent: piece by piece, the
//! best position given all the others (its two seams plus its repeats), moving only when `E`
//! drops. The unpenalised optimum `Ω*` bounds `E` from below (penalties are never negative), so
//! the report says how far the result can be from the optimum of `E` at most.
//!
//! Tried and dropped: re-solving the whole DP in rounds, each charging the positions that repeat
//! the previous path's windows (an exact DP per round). A round cannot see a piece repeating
//! itself, so a straight line went from alternating two windows to alternating two others; with
//! growing charges over six rounds it found a 4.5 % lower `E` than the descent on a real chain
//! along an S-curve, at six times the time (43 s against 7 s).

use crate::piece::Position;

/// The per-position repetition charge of one piece: `weight` for each window in `centres` that a
/// position repeats.
#[derive(Debug, Clone)]
pub(crate) struct Penalty {
    weight: u64,
    centres: Vec<Position>,
    reach: [i32; 2],
}

impl Penalty {
    /// The charge of position `u`.
    pub(crate) fn cost(&self, u: Position) -> u64 {
        let repeats = self.centres.iter().filter(|&&c| same_window(c, u, self.reach)).count() as u64;
        self.weight * repeats
    }
}

/// True when positions `a` and `b` copy the same exemplar window (within `reach` pixels).
fn same_window(a: Position, b: Position, reach: [i32; 2]) -> bool {
    (a[0] - b[0]).abs() < reach[0] && (a[1] - b[1]).abs() < reach[1]
}

/// Pieces `i` and `j` (of `count`, cyclic when `closed`) are at most `radius` pieces apart.
fn within(i: usize, j: usize, count: usize, radius: usize, closed: bool) -> bool {
    let gap = i.abs_diff(j);
    let gap = if closed { gap.min(count - gap) } else { gap };
    gap > 0 && gap <= radius
}

/// The repetition rule of one synthesis.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rule {
    /// `W` in cost units.
    pub weight: u64,
    /// `R`, pieces.
    pub radius: usize,
    /// Half-extent of a window, exemplar pixels (x: half the piece length, y: a quarter of `C`).
    pub reach: [i32; 2],
    /// Whether the pieces form a cycle.
    pub closed: bool,
}

impl Rule {
    /// The penalty of each piece given the current `positions` (`None` for empty pieces, which
    /// copy nothing and are never charged).
    #[cfg(test)]
    pub(crate) fn penalties(&self, positions: &[Option<Position>]) -> Vec<Option<Penalty>> {
        (0..positions.len()).map(|i| self.penalty(i, positions)).collect()
    }

    /// The penalty of piece `i` given the current `positions` (`None` for an empty piece).
    pub(crate) fn penalty(&self, i: usize, positions: &[Option<Position>]) -> Option<Penalty> {
        positions[i]?;
        let count = positions.len();
        let centres = (0..count)
            .filter(|&j| within(i, j, count, self.radius, self.closed))
            .filter_map(|j| positions[j])
            .collect();
        Some(Penalty { weight: self.weight, centres, reach: self.reach })
    }

    /// Pairs of pieces at most `R` apart that repeat a window.
    pub(crate) fn repeated_pairs(&self, positions: &[Option<Position>]) -> usize {
        let count = positions.len();
        let mut pairs = 0;
        for i in 0..count {
            for j in i + 1..count {
                if let (Some(a), Some(b)) = (positions[i], positions[j])
                    && within(i, j, count, self.radius, self.closed)
                    && same_window(a, b, self.reach)
                {
                    pairs += 1;
                }
            }
        }
        pairs
    }
}

impl Rule {
    /// Number of distinct exemplar windows among `positions`: taken in order, a position that
    /// repeats no window counted so far counts as a new one.
    pub(crate) fn distinct_windows(&self, positions: &[Option<Position>]) -> usize {
        let mut windows: Vec<Position> = Vec::new();
        for &u in positions.iter().flatten() {
            if !windows.iter().any(|&w| same_window(w, u, self.reach)) {
                windows.push(u);
            }
        }
        windows.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairs_count_repeats_within_the_radius_only() {
        let rule = Rule { weight: 5, radius: 2, reach: [4, 3], closed: false };
        let a = Some([10, 0]);
        let b = Some([40, 0]);
        // A B A B A: pairs at distance 2 repeat (A–A twice, B–B once).
        let path = [a, b, a, b, a];
        assert_eq!(rule.repeated_pairs(&path), 3);
        let penalties = rule.penalties(&path);
        // Piece 2 (A) sees pieces 0 and 4 (A) within 2 pieces.
        assert_eq!(penalties[2].as_ref().unwrap().cost([11, 1]), 10);
        assert_eq!(penalties[2].as_ref().unwrap().cost([20, 0]), 0);
        assert_eq!(rule.distinct_windows(&path), 2);
        assert_eq!(rule.distinct_windows(&[a, Some([12, 1]), Some([14, 0])]), 2);
        // Cyclic: pieces 0 and 4 are neighbours.
        let cyclic = Rule { closed: true, ..rule };
        assert_eq!(cyclic.repeated_pairs(&path), 4);
        // Empty pieces neither charge nor are charged.
        let with_empty = [a, None, a];
        assert_eq!(rule.repeated_pairs(&with_empty), 1);
        assert!(rule.penalties(&with_empty)[1].is_none());
    }
}
