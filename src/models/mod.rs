//! The FMUs built from this crate. Each model is one file: its generated variable table
//! (`modelDescription/<Model>.json` → `build.rs`) and the mapping from variables to the physics
//! core. One shared library serves all of them; `fmi2Instantiate` selects the model by GUID.

use crate::fmi::model::{ModelError, ModelInfo};
use crate::fmi::variables::{RealVar, Values};
use crate::tangential::fastsim::{FastsimSettings, Flexibility, MarchScheme, TractionBound};

pub mod export;
pub mod hertz_contact;
pub mod wheel_rail_contact;

/// Every model compiled into the library.
pub static MODELS: &[&ModelInfo] = &[&hertz_contact::INFO, &wheel_rail_contact::INFO];

/// Looks a model up by its `modelIdentifier`.
pub fn by_identifier(id: &str) -> Option<&'static ModelInfo> {
    MODELS.iter().copied().find(|m| m.model_identifier == id)
}

/// FASTSIM settings from the integer parameters `tractionBound`, `flexibility`, `nx`, `ny`,
/// `fastsimScheme` (ranges already checked against the variable table; anything else is an
/// error).
pub(crate) fn fastsim_settings(
    traction_bound: i32,
    flexibility: i32,
    nx: i32,
    ny: i32,
    scheme: i32,
) -> Result<FastsimSettings, ModelError> {
    let scheme = match scheme {
        1 => MarchScheme::Midpoint,
        2 => MarchScheme::Contact,
        k => {
            return Err(ModelError::Error(format!(
                "fastsimScheme = {k} is not 1 or 2"
            )))
        }
    };
    let bound = match traction_bound {
        1 => TractionBound::Elliptic,
        2 => TractionBound::Parabolic,
        k => {
            return Err(ModelError::Error(format!(
                "tractionBound = {k} is not 1 or 2"
            )))
        }
    };
    let flexibility = match flexibility {
        1 => Flexibility::Three,
        2 => Flexibility::Single,
        3 => Flexibility::Blended,
        k => {
            return Err(ModelError::Error(format!(
                "flexibility = {k} is not 1, 2 or 3"
            )))
        }
    };
    let count = |name: &str, k: i32| {
        usize::try_from(k)
            .ok()
            .filter(|&n| n >= 1)
            .ok_or_else(|| ModelError::Error(format!("{name} = {k} must be >= 1")))
    };
    Ok(FastsimSettings {
        nx: count("nx", nx)?,
        ny: count("ny", ny)?,
        bound,
        flexibility,
        scheme,
    })
}

/// Writes an output value; a non-finite one is an internal error (outputs are never NaN).
pub(crate) fn set_output(values: &mut Values, v: RealVar, x: f64) -> Result<(), ModelError> {
    if !x.is_finite() {
        return Err(ModelError::Error(format!(
            "internal error: non-finite output ({x}) in slot {}",
            v.0
        )));
    }
    values.set_real(v, x);
    Ok(())
}
