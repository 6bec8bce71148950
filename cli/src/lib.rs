//! The `railcontact` command's library: case files ([`case`]), one evaluation as JSON ([`solve`]),
//! the lateral-shift table ([`sweep`]), the equivalent conicity ([`conicity`]), the wear loop's
//! profile update ([`wear`]) and the JSON layout ([`json`]). The binary (`main.rs`)
//! parses the command line and draws the report; the fuzz target `fuzz/fuzz_targets/case.rs`
//! reads and applies case files through [`case`] and solves them through [`solve`].
//!
//! Every evaluation goes through the `WheelRailContact` FMU's own model (`INFO.create`,
//! `initialize`, `evaluate`), so the command and the FMU give identical numbers.

pub mod case;
pub mod conicity;
pub mod json;
pub mod solve;
pub mod sweep;
pub mod wear;

use railcontact::fmi::model::{InstanceContext, Model, ModelError};
use railcontact::fmi::variables::{Values, VarInfo};
use railcontact::models::wheel_rail_contact::INFO;

/// Exit code of an implausible contact state (outputs printed; [`railcontact::wheelset::validity`]).
pub const IMPLAUSIBLE: i32 = 3;

/// Why a command failed, with its exit code.
#[derive(Debug, Clone, PartialEq)]
pub enum Failure {
    /// Bad arguments, case, profile or value: exit code 1.
    Error(String),
    /// The step was refused (FMI Discard): the pose has no contact inside the profiles, or the
    /// normal model cannot carry the load: exit code 2.
    Discard(String),
}

impl Failure {
    /// The process exit code.
    pub fn code(&self) -> i32 {
        match self {
            Failure::Error(_) => 1,
            Failure::Discard(_) => 2,
        }
    }

    /// The message.
    pub fn message(&self) -> &str {
        let (Failure::Error(m) | Failure::Discard(m)) = self;
        m
    }
}

impl From<ModelError> for Failure {
    fn from(e: ModelError) -> Self {
        match e {
            ModelError::Error(m) => Failure::Error(m),
            ModelError::Discard(m) => Failure::Discard(m),
        }
    }
}

/// The FMU's model, initialized with `values`' parameters (profiles loaded).
pub fn model(values: &Values) -> Result<Box<dyn Model>, Failure> {
    let mut model = (INFO.create)(&InstanceContext::default());
    model.initialize(values)?;
    Ok(model)
}

/// The variable `name` of the generated table (an internal name: the table always has it).
fn variable(name: &str) -> Result<&'static VarInfo, Failure> {
    INFO.variable(name).ok_or_else(|| {
        Failure::Error(format!(
            "internal error: no variable '{name}' in WheelRailContact"
        ))
    })
}

/// The Real output `name`.
pub fn output_real(values: &Values, name: &str) -> Result<f64, Failure> {
    Ok(values.reals[variable(name)?.slot])
}

/// The Integer output `name`.
pub fn output_integer(values: &Values, name: &str) -> Result<i32, Failure> {
    Ok(values.integers[variable(name)?.slot])
}

/// " [unit]" or "".
pub fn unit_suffix(info: &VarInfo) -> String {
    if info.unit.is_empty() {
        String::new()
    } else {
        format!(" [{}]", info.unit)
    }
}
