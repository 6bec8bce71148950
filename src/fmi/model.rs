//! What a model provides to the generic FMI glue.
//!
//! A model is its generated variable table (`ModelInfo`) plus a [`Model`] implementation that
//! turns parameters and inputs into outputs. Everything FMI-specific — the state machine,
//! value checks against the table, logging, FMU states — lives in [`crate::fmi::instance`].

use super::variables::{Counts, DefaultExperiment, Values, VarInfo};
use std::path::PathBuf;

/// How a model step failed.
#[derive(Debug, Clone, PartialEq)]
pub enum ModelError {
    /// The inputs or parameters are invalid: the call returns `fmi2Error`.
    Error(String),
    /// The simulation cannot continue (e.g. the wheel has left the profiles): `fmi2Discard`,
    /// and the instance reports itself terminated at the last successful time.
    Discard(String),
}

/// What a successful evaluation produced.
#[derive(Debug, Clone, PartialEq)]
pub enum Evaluation {
    /// The outputs are computed and valid: `fmi2OK`.
    Ok,
    /// The outputs are computed and finite, but the state lies outside the model's validity
    /// (e.g. an approach far beyond elastic contact): `fmi2Warning` with this message; the
    /// simulation may continue.
    Warning(String),
}

impl ModelError {
    pub fn message(&self) -> &str {
        match self {
            ModelError::Error(m) | ModelError::Discard(m) => m,
        }
    }
}

impl From<crate::error::InputError> for ModelError {
    fn from(e: crate::error::InputError) -> Self {
        ModelError::Error(e.to_string())
    }
}

/// Context handed to a model when it is created.
#[derive(Debug, Clone, Default)]
pub struct InstanceContext {
    /// The FMU's `resources/` directory, when the host gave a usable `file:` URI.
    pub resource_dir: Option<PathBuf>,
}

/// The physics behind one FMU.
pub trait Model: Send {
    /// Called when the parameters are final (leaving initialization mode, after a tunable
    /// parameter changed, after an FMU state was restored). May allocate workspaces.
    fn initialize(&mut self, values: &Values) -> Result<(), ModelError>;

    /// Computes all outputs from the current parameters and inputs. Called from `fmi2DoStep`
    /// and lazily from `fmi2Get*` after inputs changed. Must not allocate (except for the
    /// message of an [`Evaluation::Warning`]).
    fn evaluate(&mut self, values: &mut Values, time: f64) -> Result<Evaluation, ModelError>;

    /// Evaluates the outputs at `values` for a directional derivative ([`crate::fmi::derivative`]),
    /// leaving the model's history (warm starts) as the last [`Model::evaluate`] left it: the next
    /// `evaluate` gives bit for bit what it would have given without this call. Must not allocate
    /// (except for an error's message). Models that do not provide directional derivatives keep
    /// this default.
    fn probe(&mut self, _values: &mut Values) -> Result<(), ModelError> {
        Err(ModelError::Error(
            "the model provides no directional derivatives".into(),
        ))
    }

    /// The difference step of the continuous input `var` at `values` for [`Model::probe`]-based
    /// derivatives, in the input's unit: small enough that the outputs are linear over it, large
    /// enough that the solver's tolerances do not show. The default, 1e−6 of the value's
    /// magnitude (at least 1e−6 of its unit), suits inputs without a physical scale of their own.
    fn difference_step(&self, values: &Values, var: &VarInfo) -> f64 {
        super::derivative::default_step(values, var)
    }

    /// Called by `fmi2DoStep` after the step's [`Model::evaluate`] succeeded, with the step's
    /// size [s]: what the model accumulates over a run (its outputs may change). Must not
    /// allocate. The default accumulates nothing.
    fn advance(&mut self, _values: &mut Values, _step: f64) -> Result<(), ModelError> {
        Ok(())
    }

    /// Called by `fmi2Terminate`: what the model writes at the end of a run. The default writes
    /// nothing.
    fn terminate(&mut self, _values: &Values) -> Result<(), ModelError> {
        Ok(())
    }

    /// Appends internal state that is not a variable (warm starts) to an FMU state.
    fn save_state(&self, _out: &mut Vec<u8>) {}

    /// Restores what [`Model::save_state`] wrote (after [`Model::initialize`]).
    fn restore_state(&mut self, bytes: &[u8]) -> Result<(), String> {
        if bytes.is_empty() {
            Ok(())
        } else {
            Err(format!("unexpected {} bytes of model state", bytes.len()))
        }
    }
}

/// Static description of one FMU: generated table plus constructor.
pub struct ModelInfo {
    pub model_identifier: &'static str,
    pub guid: &'static str,
    pub model_description_xml: &'static str,
    pub variables: &'static [VarInfo],
    pub counts: Counts,
    pub default_experiment: DefaultExperiment,
    /// `providesDirectionalDerivative`: the model implements [`Model::probe`].
    pub provides_directional_derivative: bool,
    pub create: fn(&InstanceContext) -> Box<dyn Model>,
}

impl ModelInfo {
    /// Looks a variable up by name.
    pub fn variable(&self, name: &str) -> Option<&'static VarInfo> {
        self.variables.iter().find(|v| v.name == name)
    }
}

impl std::fmt::Debug for ModelInfo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ModelInfo")
            .field("model_identifier", &self.model_identifier)
            .field("guid", &self.guid)
            .finish()
    }
}
