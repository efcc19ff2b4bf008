//! The shared vocabulary for rejecting a parameter.
//!
//! Every engine validates its parameters once, at its entry point, and reports the first bad one as
//! an [`InvalidParameter`]: which parameter, the value it had, and what would have been accepted.

use std::fmt::Display;

/// A parameter outside what an engine accepts.
///
/// Displayed as `invalid <name> = <value>: <allowed>`, for example
/// `invalid width = -2: must be > 0`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("invalid {name} = {value}: {allowed}")]
pub struct InvalidParameter {
    /// The parameter's name as the user knows it (the CLI flag without dashes).
    pub name: String,
    /// The rejected value, formatted for a person.
    pub value: String,
    /// What is allowed, as a short phrase ("must be > 0", "must be odd and >= 3").
    pub allowed: String,
}

impl InvalidParameter {
    /// Builds an error for parameter `name` with rejected `value` and the `allowed` phrase.
    pub fn new(name: impl Into<String>, value: impl Display, allowed: impl Into<String>) -> Self {
        Self { name: name.into(), value: value.to_string(), allowed: allowed.into() }
    }
}

/// A number as a person reads it: plain for everyday magnitudes, in scientific notation for the
/// tiny and the huge (`1e-300`, not three hundred zeros).
pub fn number(value: f64) -> String {
    let magnitude = value.abs();
    if value == 0.0 || !value.is_finite() || (1e-4..1e15).contains(&magnitude) {
        value.to_string()
    } else {
        format!("{value:e}")
    }
}

/// Requires a finite value strictly greater than zero.
pub fn check_positive(name: &str, value: f64) -> Result<f64, InvalidParameter> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(InvalidParameter::new(name, number(value), "must be a finite number > 0"))
    }
}

/// Requires a finite value (rejects NaN and infinities).
pub fn check_finite(name: &str, value: f64) -> Result<f64, InvalidParameter> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(InvalidParameter::new(name, number(value), "must be a finite number"))
    }
}

/// Requires a finite value in the closed range `[low, high]`.
pub fn check_range(name: &str, value: f64, low: f64, high: f64) -> Result<f64, InvalidParameter> {
    if value.is_finite() && value >= low && value <= high {
        Ok(value)
    } else {
        Err(InvalidParameter::new(name, number(value), format!("must be between {low} and {high}")))
    }
}

/// Requires an integer in the closed range `[low, high]`.
pub fn check_count(name: &str, value: usize, low: usize, high: usize) -> Result<usize, InvalidParameter> {
    if (low..=high).contains(&value) {
        Ok(value)
    } else {
        Err(InvalidParameter::new(name, value, format!("must be an integer between {low} and {high}")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_the_parameter_value_and_range() {
        let error = check_positive("width", -2.0).unwrap_err();
        assert_eq!(error.to_string(), "invalid width = -2: must be a finite number > 0");
        assert!(check_positive("width", f64::NAN).is_err());
        assert!(check_range("amount", 1.5, 0.0, 1.0).is_err());
        assert_eq!(check_range("amount", 0.5, 0.0, 1.0), Ok(0.5));
        assert!(check_count("rings", 6, 1, 5).unwrap_err().to_string().contains("between 1 and 5"));
        assert!(check_finite("x", f64::INFINITY).is_err());
        assert_eq!(check_positive("step", -1e-300).unwrap_err().value, "-1e-300");
        assert_eq!(number(0.25), "0.25");
        assert_eq!(number(3e20), "3e20");
    }
}
