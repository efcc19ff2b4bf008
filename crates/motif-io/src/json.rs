//! JSON reports and piece lists.

use std::path::Path;

use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::{IoError, Result};

/// Writes `value` as pretty-printed JSON (with a final newline), atomically.
pub fn write_json<T: Serialize + ?Sized>(path: &Path, value: &T) -> Result<()> {
    let mut text = serde_json::to_string_pretty(value).map_err(|error| IoError::format(path, error.to_string()))?;
    text.push('\n');
    crate::write_text(path, &text)
}

/// Reads JSON into `T`; errors give the line and column.
pub fn read_json<T: DeserializeOwned>(path: &Path) -> Result<T> {
    let text = crate::read_text(path)?;
    serde_json::from_str(&text).map_err(|error| IoError::format(path, format!("invalid JSON: {error}")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_round_trip_and_errors() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("r.json");
        let value = serde_json::json!({"pieces": 3, "cost": [1.5, 2.0]});
        write_json(&path, &value).unwrap();
        assert_eq!(read_json::<serde_json::Value>(&path).unwrap(), value);
        std::fs::write(&path, "{ not json").unwrap();
        assert!(read_json::<serde_json::Value>(&path).unwrap_err().to_string().contains("r.json"));
    }
}
