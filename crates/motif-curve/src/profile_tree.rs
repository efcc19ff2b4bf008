//! The branch and bound of the exact solver (§2): the profile tree over distinct predecessors,
//! its lower bounds, and the search of one DP row (see the `dp` module for the whole solver).

use rayon::prelude::*;

use crate::bounds::{alpha_bound_of_distance, bound_of_distances, colour_profile_distance, l1_u16, mask_bound};
use crate::cost::{CostModel, EdgeSet, edge_distance_bounded};
use crate::dp::{DpCounters, RowResult, Seeds};

/// Predecessors per leaf of the profile tree (small under test, so that the tiny property-test
/// problems exercise deep trees too).
const LEAF_SIZE: usize = if cfg!(test) { 2 } else { 16 };

/// The alpha block sums of edge `index` (the last quarter of its profile).
#[inline]
fn alpha_profile(set: &EdgeSet, index: usize) -> &[u16] {
    &set.profile_of(index)[3 * set.profile_len..]
}

/// L1 distance from the alpha profile `point` to the box `low..=high` (0 inside). Every profile
/// inside the box is at least this far from `point`, and the profile distance never exceeds the
/// per-sample alpha distance, so [`alpha_bound`] of it bounds `D` for every edge of the box.
#[inline]
fn box_gap(point: &[u16], low: &[u16], high: &[u16]) -> u32 {
    // 16-bit lanes, widened every 64 chunks, as in `l1_u16` (block sums are at most 4 × 255).
    let mut total = 0_u32;
    for ((point, low), high) in point.chunks(64 * 8).zip(low.chunks(64 * 8)).zip(high.chunks(64 * 8)) {
        let mut lanes = [0_u16; 8];
        for ((p, l), h) in point.chunks_exact(8).zip(low.chunks_exact(8)).zip(high.chunks_exact(8)) {
            for i in 0..8 {
                lanes[i] = lanes[i].wrapping_add(l[i].saturating_sub(p[i]) | p[i].saturating_sub(h[i]));
            }
        }
        total += lanes.iter().map(|&lane| u32::from(lane)).sum::<u32>();
    }
    total
}

/// `D ≥ alpha_bound(L1)` for an alpha L1 distance (per sample or between block sums): per sample
/// ξ ≥ 8γ·|a − b|/255 − 1 (one unit for rounding), so `D ≥ L1·⌊8γ⌋/255 − C`. The fixed-point factor
/// is rounded down, so the product never exceeds the exact floor.
#[derive(Debug, Clone, Copy)]
struct AlphaBound {
    per_unit: u64,
    samples: u64,
}

impl AlphaBound {
    fn new(model: &CostModel, samples: usize) -> Self {
        Self { per_unit: (model.gamma_floor() << 16) / 255, samples: samples as u64 }
    }

    #[inline]
    fn of(&self, l1: u32) -> u64 {
        ((u64::from(l1) * self.per_unit) >> 16).saturating_sub(self.samples)
    }
}

/// Whether the coarse sums of an alpha profile of `dims` entries fit `u16` (each entry is at
/// most 4 × 255).
fn coarse_fits(dims: usize) -> bool {
    dims >= 8 && dims / 8 * 1020 <= usize::from(u16::MAX)
}

/// An alpha profile summed over eight consecutive runs of `len / 8` entries.
fn coarse_profile(alpha: &[u16]) -> [u16; 8] {
    let run = alpha.len() / 8;
    std::array::from_fn(|i| alpha[i * run..(i + 1) * run].iter().sum())
}

/// L1 distance of two coarse profiles (one SSE2 register each).
#[inline(always)]
fn coarse_distance(a: &[u16; 8], b: &[u16; 8]) -> u32 {
    let mut lanes = [0_u16; 8];
    for i in 0..8 {
        lanes[i] = a[i].saturating_sub(b[i]) | b[i].saturating_sub(a[i]);
    }
    lanes.iter().map(|&lane| u32::from(lane)).sum()
}

/// A node of the profile tree: arranged predecessors `start..end`, their lowest `P`, and the
/// children (`None` for a leaf, whose predecessors are sorted by ascending `P`).
#[derive(Debug, Clone, Copy)]
struct Node {
    start: usize,
    end: usize,
    lowest_cost: u64,
    children: Option<[u32; 2]>,
}

/// Predecessors in a k-d tree over their alpha profiles, each node with the bounding box of its
/// profiles and its lowest `P`, for a branch-and-bound search: a node whose lowest `P` plus the
/// alpha bound of its box distance cannot beat the best total is skipped whole. (The index has to
/// carry the lowest `P` of every subtree, which no k-d tree crate offers.)
struct ProfileTree {
    /// `P` in leaf order.
    costs: Vec<u64>,
    /// Original predecessor index in leaf order.
    original: Vec<u32>,
    /// Leaf-order position of each original predecessor.
    position_of: Vec<u32>,
    /// Nodes; the root is 0.
    nodes: Vec<Node>,
    /// Per node: the box's lows, then its highs (`dims` each).
    boxes: Vec<u16>,
    /// Entries of an alpha profile.
    dims: usize,
    /// The alpha profiles in leaf order, contiguous: the first filter of every visit reads only
    /// these, and a scan then walks memory in order (about 4 × less traffic than whole profiles).
    alphas: Vec<u16>,
    /// Per predecessor in leaf order: its alpha profile summed over eight runs of `dims / 8`
    /// entries (empty when a sum could pass `u16::MAX`). The L1 distance of these sums is at most
    /// that of the profiles, so one 8-lane difference rejects most visits before the full one.
    coarse: Vec<[u16; 8]>,
}

impl ProfileTree {
    fn new(previous: &[u64], rights: &EdgeSet) -> Self {
        let mut tree = Self {
            costs: Vec::with_capacity(previous.len()),
            original: Vec::with_capacity(previous.len()),
            position_of: vec![0; previous.len()],
            nodes: Vec::new(),
            boxes: Vec::new(),
            dims: rights.profile_len,
            alphas: Vec::new(),
            coarse: Vec::new(),
        };
        let mut members: Vec<u32> = (0..previous.len() as u32).collect();
        tree.build(&mut members, previous, rights);
        for (position, &v) in tree.original.iter().enumerate() {
            tree.position_of[v as usize] = position as u32;
        }
        // Only the alpha profiles are copied into leaf order: the first filter reads them for every
        // visit, the rest of an edge only for the tenth of visits that pass it (copying whole
        // edges, 7.6 MB a row on the wide chain, cost more than their locality saved).
        tree.alphas = tree.original.iter().flat_map(|&v| alpha_profile(rights, v as usize).iter().copied()).collect();
        if coarse_fits(tree.dims) {
            tree.coarse = tree.alphas.chunks_exact(tree.dims).map(coarse_profile).collect();
        }
        tree
    }

    /// Adds the subtree of `members` (split at the median of the widest profile entry) and
    /// returns its node index.
    fn build(&mut self, members: &mut [u32], previous: &[u64], rights: &EdgeSet) -> u32 {
        let dims = self.dims;
        let (mut low, mut high) = (vec![u16::MAX; dims], vec![0_u16; dims]);
        for &v in members.iter() {
            for (d, &value) in alpha_profile(rights, v as usize).iter().enumerate() {
                low[d] = low[d].min(value);
                high[d] = high[d].max(value);
            }
        }
        let index = self.nodes.len();
        let lowest_cost = members.iter().map(|&v| previous[v as usize]).min().unwrap_or(u64::MAX);
        self.nodes.push(Node { start: self.original.len(), end: 0, lowest_cost, children: None });
        self.boxes.extend_from_slice(&low);
        self.boxes.extend_from_slice(&high);
        let widest = (0..dims).max_by_key(|&d| (high[d] - low[d], std::cmp::Reverse(d)));
        match widest {
            Some(dimension) if members.len() > LEAF_SIZE && high[dimension] > low[dimension] => {
                let middle = members.len() / 2;
                members.select_nth_unstable_by_key(middle, |&v| (alpha_profile(rights, v as usize)[dimension], v));
                let (near, far) = members.split_at_mut(middle);
                let first = self.build(near, previous, rights);
                let second = self.build(far, previous, rights);
                self.nodes[index].children = Some([first, second]);
            }
            _ => {
                // A leaf (or identical profiles): ascending `P`, so its scan can stop early.
                members.sort_unstable_by_key(|&v| (previous[v as usize], v));
                self.costs.extend(members.iter().map(|&v| previous[v as usize]));
                self.original.extend_from_slice(members);
            }
        }
        self.nodes[index].end = self.original.len();
        index as u32
    }

    /// The box distance from `point` to node `node`.
    #[inline]
    fn gap(&self, node: u32, point: &[u16]) -> u32 {
        let at = node as usize * 2 * self.dims;
        box_gap(point, &self.boxes[at..at + self.dims], &self.boxes[at + self.dims..at + 2 * self.dims])
    }
}

/// Positions per parallel block of a row.
const BLOCK: usize = 64;

/// The exact fast row update (see the module comment).
///
/// For a position `u`, the tree is searched best-first along its depth: the child whose box is
/// nearer to `u`'s alpha profile is opened first, a node is dropped when its lowest `P` plus the
/// alpha bound of its box distance exceeds the best total so far, and a leaf (ascending `P`) is
/// scanned until `P` plus that bound exceeds it. Survivors go through the profile and mask
/// bounds before any pixel is read.
pub(crate) fn exact_row(
    model: &CostModel,
    previous: &[u64],
    rights: &EdgeSet,
    lefts: &EdgeSet,
    seeds: &Seeds,
) -> RowResult {
    let tree = ProfileTree::new(previous, rights);
    let search = RowSearch {
        model,
        rights,
        lefts,
        seeds,
        tree: &tree,
        cheapest: (0..previous.len()).min_by_key(|&v| (previous[v], v)).unwrap_or(0),
        weight: model.mask_weight(),
        samples: lefts.samples,
        alpha_bound: AlphaBound::new(model, lefts.samples),
    };
    let results: Vec<(Vec<(u64, u32)>, DpCounters)> = (0..lefts.len().div_ceil(BLOCK))
        .into_par_iter()
        .map(|block| search.block(block * BLOCK..((block + 1) * BLOCK).min(lefts.len())))
        .collect();
    let mut counters = DpCounters { pairs: (previous.len() * lefts.len()) as u64, ..DpCounters::default() };
    let mut costs = Vec::with_capacity(lefts.len());
    let mut predecessors = Vec::with_capacity(lefts.len());
    for (block, block_counters) in results {
        counters.visited += block_counters.visited;
        counters.compared += block_counters.compared;
        counters.completed += block_counters.completed;
        for (cost, v) in block {
            costs.push(cost);
            predecessors.push(v);
        }
    }
    (costs, predecessors, counters)
}

/// What the search of one row shares between its positions.
struct RowSearch<'a> {
    model: &'a CostModel,
    rights: &'a EdgeSet,
    lefts: &'a EdgeSet,
    seeds: &'a Seeds,
    tree: &'a ProfileTree,
    /// The predecessor of lowest `P` (lowest index among ties).
    cheapest: usize,
    /// The weight of the mask bound.
    weight: u32,
    /// `C`.
    samples: usize,
    alpha_bound: AlphaBound,
}

/// A position's left edge, as the bounds read it.
struct Target<'a> {
    u: usize,
    masks: (&'a [u64], &'a [u64]),
    profile: &'a [u16],
    alpha: &'a [u16],
    /// The alpha profile's coarse sums (zeros when the tree keeps none).
    coarse: [u16; 8],
}

impl RowSearch<'_> {
    /// The best (total, original predecessor index) of each position of `range`, with the work
    /// counters of the block.
    fn block(&self, range: std::ops::Range<usize>) -> (Vec<(u64, u32)>, DpCounters) {
        let mut counters = DpCounters::default();
        let first = range.start;
        let mut out: Vec<(u64, u32)> = Vec::with_capacity(range.len());
        let mut stack: Vec<(u64, u32)> = Vec::new();
        for u in range {
            let alpha = alpha_profile(self.lefts, u);
            let target = Target {
                u,
                masks: self.lefts.masks_of(u),
                profile: self.lefts.profile_of(u),
                alpha,
                coarse: if self.tree.coarse.is_empty() { [0; 8] } else { coarse_profile(alpha) },
            };
            // (total, original predecessor index); compare lexicographically for ties.
            let mut best = (u64::MAX, u32::MAX);
            self.try_seeds(&target, first, &out, &mut best, &mut counters);
            self.branch_and_bound(&target, &mut stack, &mut best, &mut counters);
            out.push(best);
        }
        (out, counters)
    }

    /// Tries the predecessors likely to be best first, so that the bounds prune early: the one
    /// continuing `u`'s window, the one below the predecessor of the position above, the
    /// predecessor of the previous position (similar u, low P) and the cheapest overall.
    fn try_seeds(
        &self,
        target: &Target<'_>,
        first: usize,
        out: &[(u64, u32)],
        best: &mut (u64, u32),
        counters: &mut DpCounters,
    ) {
        let (seeds, position_of) = (self.seeds, &self.tree.position_of);
        let u = target.u;
        let continuation = seeds.continuation[u];
        if continuation != u32::MAX {
            self.consider(target, position_of[continuation as usize] as usize, best, counters);
        }
        let above = seeds.above[u] as usize;
        if above != u32::MAX as usize && above >= first && above < u {
            let above_predecessor = out[above - first].1;
            if above_predecessor != u32::MAX {
                let [x, y] = seeds.previous[above_predecessor as usize];
                if let Some(v) = seeds.previous_index([x, y + 1]) {
                    self.consider(target, position_of[v as usize] as usize, best, counters);
                }
            }
        }
        if let Some(&(_, previous_best)) = out.last()
            && previous_best != u32::MAX
        {
            self.consider(target, position_of[previous_best as usize] as usize, best, counters);
        }
        self.consider(target, position_of[self.cheapest] as usize, best, counters);
    }

    /// Branch and bound over the tree; the stack holds (alpha bound of the box distance, node).
    /// Pruning is strict (`>`), so a tie with a lower index is still found.
    fn branch_and_bound(
        &self,
        target: &Target<'_>,
        stack: &mut Vec<(u64, u32)>,
        best: &mut (u64, u32),
        counters: &mut DpCounters,
    ) {
        let (tree, alpha_bound) = (self.tree, &self.alpha_bound);
        stack.clear();
        stack.push((alpha_bound.of(tree.gap(0, target.alpha)), 0));
        while let Some((bound, index)) = stack.pop() {
            let node = tree.nodes[index as usize];
            if node.lowest_cost.saturating_add(bound) > best.0 {
                continue;
            }
            match node.children {
                Some(children) => {
                    let [near, far] = children.map(|child| (alpha_bound.of(tree.gap(child, target.alpha)), child));
                    let (near, far) = if far.0 < near.0 { (far, near) } else { (near, far) };
                    // Pushed last, popped first: the nearer child.
                    for (bound, child) in [far, near] {
                        if tree.nodes[child as usize].lowest_cost.saturating_add(bound) <= best.0 {
                            stack.push((bound, child));
                        }
                    }
                }
                None => {
                    for (position, &cost) in tree.costs.iter().enumerate().take(node.end).skip(node.start) {
                        if cost + bound > best.0 {
                            break;
                        }
                        self.consider(target, position, best, counters);
                    }
                }
            }
        }
    }

    /// Compares the predecessor at leaf-order `position` with `target`, cheapest bounds first
    /// (coarse alpha, alpha, colour profile, masks), and keeps it in `best` when its total is lower.
    #[inline]
    fn consider(&self, target: &Target<'_>, position: usize, best: &mut (u64, u32), counters: &mut DpCounters) {
        let (model, rights, tree, samples) = (self.model, self.rights, self.tree, self.samples);
        let cost = tree.costs[position];
        let v = tree.original[position];
        counters.visited += 1;
        if !tree.coarse.is_empty() {
            let near = coarse_distance(&tree.coarse[position], &target.coarse);
            if (cost + alpha_bound_of_distance(model, near, samples), v) >= *best {
                return;
            }
        }
        let dims = tree.dims;
        let alpha = l1_u16(&tree.alphas[position * dims..(position + 1) * dims], target.alpha);
        if (cost + alpha_bound_of_distance(model, alpha, samples), v) >= *best {
            return;
        }
        let right_profile = rights.profile_of(v as usize);
        let colour = if model.colour_bounds() {
            let colour = colour_profile_distance(right_profile, target.profile);
            if (cost + bound_of_distances(model, colour, alpha, samples), v) >= *best {
                return;
            }
            colour
        } else {
            0
        };
        if (cost + mask_bound(self.weight, rights.masks_of(v as usize), target.masks), v) >= *best {
            return;
        }
        counters.compared += 1;
        let limit = best.0.saturating_sub(cost);
        if let Some(distance) =
            edge_distance_bounded(model, rights, v as usize, self.lefts, target.u, limit, (colour, alpha))
        {
            counters.completed += 1;
            let total = cost + u64::from(distance);
            if (total, v) < *best {
                *best = (total, v);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cost::{AlphaMode, edge_distance};
    use crate::dp::tests::edge_set;
    use proptest::prelude::*;

    proptest! {
        /// Every node's box bound is a true lower bound of `D` for all its predecessors, its
        /// lowest `P` is theirs, and the tree holds every predecessor once, leaves by ascending `P`.
        #[test]
        fn tree_bounds_never_exceed_the_distance(
            samples in 1_usize..70,
            columns in proptest::collection::vec(proptest::collection::vec(any::<(u8, u8)>(), 70), 1..40),
            costs in proptest::collection::vec(0_u64..50_000, 40),
            left in proptest::collection::vec(any::<(u8, u8)>(), 70),
            gamma in 1.0_f64..3000.0,
            binary in any::<bool>(),
        ) {
            let model = CostModel::new(if binary { AlphaMode::Binary } else { AlphaMode::Continuous }, gamma);
            let rights = edge_set(samples, &columns);
            let lefts = edge_set(samples, &[left]);
            let previous = &costs[..columns.len()];
            let tree = ProfileTree::new(previous, &rights);
            let alpha_bound = AlphaBound::new(&model, samples);
            let mut seen = tree.original.clone();
            seen.sort_unstable();
            prop_assert_eq!(seen, (0..columns.len() as u32).collect::<Vec<_>>());
            for (position, &v) in tree.original.iter().enumerate() {
                prop_assert_eq!(tree.position_of[v as usize] as usize, position);
                prop_assert_eq!(tree.costs[position], previous[v as usize]);
            }
            let gap_of_left = |node: u32| alpha_bound.of(tree.gap(node, alpha_profile(&lefts, 0)));
            for (index, node) in tree.nodes.iter().enumerate() {
                let range = node.start..node.end;
                prop_assert_eq!(node.lowest_cost, tree.costs[range.clone()].iter().copied().min().unwrap());
                let bound = gap_of_left(index as u32);
                for position in range.clone() {
                    let distance = u64::from(edge_distance(&model, &rights, tree.original[position] as usize, &lefts, 0));
                    prop_assert!(bound <= distance, "node {} bound {} > D {}", index, bound, distance);
                }
                match node.children {
                    Some([a, b]) => {
                        let (a, b) = (tree.nodes[a as usize], tree.nodes[b as usize]);
                        prop_assert_eq!((a.start, a.end, b.end), (node.start, b.start, node.end));
                    }
                    None => prop_assert!(tree.costs[range].is_sorted()),
                }
            }
        }
    }
}
