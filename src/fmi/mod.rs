//! Generic FMI 2.0 Co-Simulation glue, shared by every model in [`crate::models`].
//!
//! * [`variables`]: the generated variable tables and an instance's values;
//! * [`model`]: the [`model::Model`] trait a model implements;
//! * [`instance`]: state machine, checked get/set, logging, FMU states;
//! * [`derivative`]: directional derivatives by differences of the model's solution;
//! * [`export`]: the 34 `extern "C"` functions;
//! * [`uri`]: `resourceLocation` parsing.

pub mod derivative;
pub mod export;
pub mod instance;
pub mod model;
pub mod uri;
pub mod variables;
