//! Elastic and frictional properties of the wheel–rail pair.

use crate::error::{require_positive, InputError};

/// Elastic and frictional properties of the wheel–rail pair (identical materials).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus E [Pa].
    pub youngs_modulus: f64,
    /// Poisson's ratio ν [-], in [0, 0.5].
    pub poisson_ratio: f64,
    /// Coefficient of friction μ [-], > 0.
    pub friction: f64,
}

impl Material {
    /// Checks the ranges; returns the error naming the first bad quantity.
    pub fn validate(&self) -> Result<(), InputError> {
        require_positive("E", self.youngs_modulus)?;
        if !(0.0..=0.5).contains(&self.poisson_ratio) {
            return Err(InputError::new("nu", self.poisson_ratio, "[0, 0.5]"));
        }
        require_positive("mu", self.friction)?;
        Ok(())
    }
}
