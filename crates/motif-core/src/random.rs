//! Seeded random streams that do not depend on the thread count.
//!
//! A run has one seed (the CLI's `--seed`). Work that needs randomness asks for the stream of its
//! `(stage, index)` pair, for example `("patchmatch", tile)` or `("seeds", element)`. Each stream
//! is a PCG generator whose state is derived from the seed, the stage name and the index by a
//! fixed mixing function, so the numbers a piece of work draws are the same whichever thread runs
//! it and in whatever order. Never share one generator between parallel tasks.

use rand::SeedableRng;
pub use rand::{Rng, RngCore};
pub use rand_pcg::Pcg64Mcg as Stream;

/// The root of a run's randomness: hand out one [`Stream`] per `(stage, index)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SeedStreams {
    seed: u64,
}

impl SeedStreams {
    /// Root streams for `seed`.
    pub fn new(seed: u64) -> Self {
        Self { seed }
    }

    /// The seed these streams derive from.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The independent stream for work item `index` of `stage`.
    ///
    /// The same `(seed, stage, index)` always gives the same sequence, on every platform.
    pub fn stream(&self, stage: &str, index: u64) -> Stream {
        self.stage(stage).stream(index)
    }

    /// The streams of one `stage`, its name hashed once: for work that asks for many streams of
    /// one stage (one per pixel), each the same as [`stream`](Self::stream) gives.
    pub fn stage(&self, stage: &str) -> StageStreams {
        StageStreams { high: splitmix64(self.seed ^ splitmix64(fnv1a(stage.as_bytes()))) }
    }

    /// A child root, for a sub-computation that fans out streams of its own (for example one
    /// synthesis level inside a multi-level loop).
    pub fn child(&self, stage: &str, index: u64) -> SeedStreams {
        SeedStreams::new(self.stream(stage, index).next_u64())
    }
}

/// The streams of one stage of a [`SeedStreams`] ([`SeedStreams::stage`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct StageStreams {
    /// The half of every stream's state that depends on the seed and the stage only.
    high: u64,
}

impl StageStreams {
    /// The stream of work item `index` of this stage.
    #[inline]
    pub fn stream(&self, index: u64) -> Stream {
        let low = splitmix64(self.high ^ splitmix64(index.wrapping_add(0x9e37_79b9_7f4a_7c15)));
        Stream::from_seed(((u128::from(self.high) << 64) | u128::from(low)).to_le_bytes())
    }
}

/// 64-bit FNV-1a: a stable hash of stage names (std's hasher is not stable across releases).
fn fnv1a(bytes: &[u8]) -> u64 {
    let mut hash = 0xcbf2_9ce4_8422_2325_u64;
    for &byte in bytes {
        hash ^= u64::from(byte);
        hash = hash.wrapping_mul(0x0100_0000_01b3);
    }
    hash
}

/// SplitMix64's finalizer: a bijective mixer with good avalanche.
#[inline]
fn splitmix64(value: u64) -> u64 {
    let mut z = value.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first value of stream `("stage", 3)` of seed 7.
    const PINNED: u64 = 1_023_500_806_113_937_603;

    #[test]
    fn same_key_same_sequence_different_keys_differ() {
        let root = SeedStreams::new(7);
        let a: Vec<u64> = (0..4)
            .map({
                let mut s = root.stream("stage", 3);
                move |_| s.next_u64()
            })
            .collect();
        let b: Vec<u64> = (0..4)
            .map({
                let mut s = root.stream("stage", 3);
                move |_| s.next_u64()
            })
            .collect();
        assert_eq!(a, b);
        let mut other_index = root.stream("stage", 4);
        let mut other_stage = root.stream("stagf", 3);
        let mut other_seed = SeedStreams::new(8).stream("stage", 3);
        assert_ne!(a[0], other_index.next_u64());
        assert_ne!(a[0], other_stage.next_u64());
        assert_ne!(a[0], other_seed.next_u64());
    }

    /// A stage's streams are the root's streams of that stage, and the values are pinned: a
    /// changed derivation would change every seeded output.
    #[test]
    fn stage_streams_are_the_roots_and_pinned() {
        let root = SeedStreams::new(7);
        let stage = root.stage("pixel");
        for index in [0, 1, 3, u64::MAX] {
            assert_eq!(stage.stream(index).next_u64(), root.stream("pixel", index).next_u64());
        }
        assert_eq!(root.stream("stage", 3).next_u64(), PINNED);
    }

    #[test]
    fn streams_are_roughly_uniform() {
        let root = SeedStreams::new(1);
        let mut counts = [0_u32; 10];
        for index in 0..2000 {
            let mut stream = root.stream("uniform", index);
            let value: f64 = stream.random();
            counts[(value * 10.0) as usize] += 1;
        }
        assert!(counts.iter().all(|&count| (150..250).contains(&count)), "{counts:?}");
    }
}
