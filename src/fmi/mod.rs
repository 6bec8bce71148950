//! Generic FMI 2.0 Co-Simulation glue, shared by every model of the crate (they are registered
//! in `models`, which also exports `fmi2Instantiate` over them).
//!
//! * [`variables`]: the generated variable tables and an instance's values;
//! * [`model`]: the [`model::Model`] trait a model implements;
//! * [`instance`]: state machine, checked get/set, logging, FMU states;
//! * [`derivative`]: directional derivatives by differences of the model's solution;
//! * [`export`]: the `extern "C"` functions (33 of the 34; `instantiate` is `fmi2Instantiate`
//!   over a registry of models, exported by `models::export`);
//! * [`uri`]: `resourceLocation` parsing.

pub mod derivative;
pub mod export;
pub mod instance;
pub mod model;
pub mod uri;
pub mod variables;
