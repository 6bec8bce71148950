//! Errors shared by the physics core and the FMI glue.
//!
//! Every rejected value names the quantity, the value and the allowed range, so that the FMI
//! layer can log it verbatim (see `docs/conventions.md`, "Errors").

use std::fmt;

/// A physical input outside the range a model accepts.
#[derive(Debug, Clone, PartialEq)]
pub struct InputError {
    /// Name of the quantity as the user knows it (FMU variable name where there is one).
    pub name: &'static str,
    /// The offending value (SI units).
    pub value: f64,
    /// Human-readable allowed range, e.g. `"> 0"` or `"[0, 0.5]"`.
    pub allowed: &'static str,
}

impl InputError {
    /// Builds the error for `name = value`, allowed `allowed`.
    pub fn new(name: &'static str, value: f64, allowed: &'static str) -> Self {
        Self {
            name,
            value,
            allowed,
        }
    }
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} = {} is outside the allowed range {}",
            self.name, self.value, self.allowed
        )
    }
}

impl std::error::Error for InputError {}

/// Checks that `value` is finite and strictly positive.
pub fn require_positive(name: &'static str, value: f64) -> Result<f64, InputError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(InputError::new(name, value, "> 0 (finite)"))
    }
}

/// Checks that `value` is finite and not negative.
pub fn require_non_negative(name: &'static str, value: f64) -> Result<f64, InputError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(InputError::new(name, value, ">= 0 (finite)"))
    }
}

/// Checks that `value` is finite.
pub fn require_finite(name: &'static str, value: f64) -> Result<f64, InputError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(InputError::new(name, value, "finite"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn message_names_variable_value_and_range() {
        let e = require_positive("N", -3.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "N = -3 is outside the allowed range > 0 (finite)"
        );
        assert!(require_non_negative("N", 0.0).is_ok());
        assert!(require_finite("xi", f64::NAN).is_err());
        assert!(require_positive("A", f64::INFINITY).is_err());
    }
}
