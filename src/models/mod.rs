//! The FMUs built from this crate. Each model is one file: its generated variable table
//! (`modelDescription/<Model>.json` → `build.rs`) and the mapping from variables to the physics
//! core. One shared library serves all of them; `fmi2Instantiate` selects the model by GUID.

use crate::fmi::model::ModelInfo;

pub mod hertz_contact;
pub mod wheel_rail_contact;

/// Every model compiled into the library.
pub static MODELS: &[&ModelInfo] = &[&hertz_contact::INFO, &wheel_rail_contact::INFO];

/// Looks a model up by its `modelIdentifier`.
pub fn by_identifier(id: &str) -> Option<&'static ModelInfo> {
    MODELS.iter().copied().find(|m| m.model_identifier == id)
}
