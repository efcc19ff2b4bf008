//! `max-memory` in a job: bytes as a number, or a size as people write it (`"8G"`, `"512M"`).

use serde::{Deserialize, Deserializer};

#[derive(Deserialize)]
#[serde(untagged)]
enum Size {
    Bytes(u64),
    Text(String),
}

/// Reads an optional memory size (see [`motif_core::memory::parse_bytes`]).
pub(crate) fn optional<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Option<u64>, D::Error> {
    match Option::<Size>::deserialize(deserializer)? {
        None => Ok(None),
        Some(Size::Bytes(bytes)) => Ok(Some(bytes)),
        Some(Size::Text(text)) => motif_core::memory::parse_bytes(&text).map(Some).map_err(serde::de::Error::custom),
    }
}
