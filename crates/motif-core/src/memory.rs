//! Memory estimates checked before a run allocates.
//!
//! Each engine adds up the large buffers a run will hold at its peak (from the validated inputs
//! only: pieces × candidate positions, pixels × channels × levels, quadrature points × window) and
//! refuses the run when the sum passes `max-memory`, so that a typo in a size gives a clear error
//! instead of an abort in the allocator or a machine that swaps for an hour.

use std::fmt;

/// The limit an engine uses when nobody sets one: 4 GiB. Front ends that know the machine pass a
/// share of its memory instead (the `motif` CLI: half of it).
pub const DEFAULT_MAX_MEMORY: u64 = 4 << 30;

/// Smallest limit accepted (below it even a small run cannot start).
pub const MIN_MAX_MEMORY: u64 = 1 << 20;

/// Checks a `max-memory` value: at least [`MIN_MAX_MEMORY`].
pub fn check_max_memory(value: u64) -> Result<u64, crate::InvalidParameter> {
    if value >= MIN_MAX_MEMORY {
        Ok(value)
    } else {
        Err(crate::InvalidParameter::new("max-memory", Bytes(value), "must be at least 1 MiB"))
    }
}

/// The large buffers of one run, by what they hold.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MemoryEstimate {
    parts: Vec<(&'static str, u64)>,
}

impl MemoryEstimate {
    /// An empty estimate.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds `count` items of `bytes_each` for `what`, saturating instead of overflowing (a huge
    /// input must give a huge estimate, never a wrapped small one).
    pub fn add(&mut self, what: &'static str, count: f64, bytes_each: f64) -> &mut Self {
        let bytes = (count.max(0.0) * bytes_each.max(0.0)).min(u64::MAX as f64);
        let bytes = if bytes.is_finite() { bytes as u64 } else { u64::MAX };
        self.parts.push((what, bytes));
        self
    }

    /// Total bytes.
    pub fn total(&self) -> u64 {
        self.parts.iter().fold(0u64, |sum, &(_, bytes)| sum.saturating_add(bytes))
    }

    /// The largest part and its bytes (`("nothing", 0)` for an empty estimate).
    pub fn largest(&self) -> (&'static str, u64) {
        self.parts.iter().copied().max_by_key(|&(_, bytes)| bytes).unwrap_or(("nothing", 0))
    }

    /// The parts in the order they were added.
    pub fn parts(&self) -> &[(&'static str, u64)] {
        &self.parts
    }

    /// Refuses the run when the total passes `limit`; `advice` says what to change.
    pub fn check(&self, limit: u64, advice: &'static str) -> Result<u64, TooMuchMemory> {
        let needed = self.total();
        if needed <= limit {
            return Ok(needed);
        }
        let (largest, largest_bytes) = self.largest();
        Err(TooMuchMemory { needed, limit, largest, largest_bytes, advice })
    }
}

/// A run whose estimated memory passes the limit.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "the run would need about {} of memory, more than the {} allowed (max-memory); the largest part is {} ({}): {}, \
     or raise max-memory",
    Bytes(*.needed), Bytes(*.limit), .largest, Bytes(*.largest_bytes), .advice
)]
pub struct TooMuchMemory {
    /// Estimated bytes.
    pub needed: u64,
    /// The limit, bytes.
    pub limit: u64,
    /// What the largest part holds.
    pub largest: &'static str,
    /// Bytes of the largest part.
    pub largest_bytes: u64,
    /// What to change.
    pub advice: &'static str,
}

/// A byte count as a person reads it (`512 B`, `3.2 MiB`, `18.0 GiB`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Bytes(pub u64);

impl fmt::Display for Bytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const UNITS: [&str; 6] = ["KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
        if self.0 < 1024 {
            return write!(f, "{} B", self.0);
        }
        let mut value = self.0 as f64 / 1024.0;
        let mut unit = 0;
        while value >= 1024.0 && unit + 1 < UNITS.len() {
            value /= 1024.0;
            unit += 1;
        }
        write!(f, "{value:.2} {}", UNITS[unit])
    }
}

/// Reads a memory size as people write it: bytes (`1048576`) or a number with a binary unit
/// (`512K`, `300M`, `1.5G`, `2T`; `KiB`/`MB`-style suffixes and lower case are accepted and all
/// mean powers of 1024).
pub fn parse_bytes(text: &str) -> Result<u64, String> {
    let trimmed = text.trim();
    let split = trimmed.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(trimmed.len());
    let (number, unit) = trimmed.split_at(split);
    let shift = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 0,
        "k" | "kb" | "kib" => 10,
        "m" | "mb" | "mib" => 20,
        "g" | "gb" | "gib" => 30,
        "t" | "tb" | "tib" => 40,
        _ => return Err(format!("`{text}` is not a size: write bytes or a number with K, M, G or T (e.g. 8G)")),
    };
    let value: f64 = number
        .parse()
        .map_err(|_| format!("`{text}` is not a size: write bytes or a number with K, M, G or T (e.g. 8G)"))?;
    let bytes = value * (1u64 << shift) as f64;
    if !bytes.is_finite() || bytes >= u64::MAX as f64 {
        return Err(format!("`{text}` is larger than any machine's memory"));
    }
    Ok(bytes as u64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn sizes_parse_with_binary_units() {
        assert_eq!(parse_bytes("1048576"), Ok(1 << 20));
        assert_eq!(parse_bytes("512K"), Ok(512 << 10));
        assert_eq!(parse_bytes("1.5G"), Ok(3 << 29));
        assert_eq!(parse_bytes("8gib"), Ok(8 << 30));
        assert_eq!(parse_bytes(" 2 T "), Ok(2 << 40));
        for bad in ["", "G", "-1G", "1.2.3M", "5 parsecs", "1e3M", "99999999999999999999T"] {
            assert!(parse_bytes(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn estimates_saturate_and_name_their_largest_part() {
        let mut estimate = MemoryEstimate::new();
        estimate.add("pixels", 1e6, 16.0).add("positions", 1e30, 1e30);
        assert_eq!(estimate.total(), u64::MAX);
        let error = estimate.check(8 << 30, "use a smaller size").unwrap_err();
        assert_eq!(error.largest, "positions");
        let message = error.to_string();
        assert!(message.contains("max-memory") && message.contains("8.00 GiB"), "{message}");
        let mut small = MemoryEstimate::new();
        small.add("pixels", 1000.0, 16.0).add("nothing at all", f64::NAN, 3.0);
        assert_eq!(small.check(1 << 20, "-"), Ok(16_000));
    }

    #[test]
    fn bytes_read_as_people_write_them() {
        assert_eq!(Bytes(512).to_string(), "512 B");
        assert_eq!(Bytes(3 << 20).to_string(), "3.00 MiB");
        assert_eq!(Bytes(u64::MAX).to_string(), "16.00 EiB");
    }

    proptest! {
        #[test]
        fn any_text_parses_or_is_refused_without_panic(text in ".{0,24}") {
            let _ = parse_bytes(&text);
        }

        #[test]
        fn a_printed_size_parses_back_within_rounding(bytes in 1024u64..(1 << 50)) {
            let printed = Bytes(bytes).to_string().replace(' ', "").replace("iB", "");
            let parsed = parse_bytes(&printed).unwrap() as f64;
            prop_assert!((parsed - bytes as f64).abs() <= 0.06 * bytes as f64, "{printed} {parsed} {bytes}");
        }
    }
}
