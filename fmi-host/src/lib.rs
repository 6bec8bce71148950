//! A small FMI 2.0 Co-Simulation host, shared by railcontact's tests, its `fmu_dostep`
//! benchmark and the packer's check of the packed FMUs.
//!
//! * [`Fmu`]: the 34 `fmi2*` functions — of a library linked into this program
//!   ([`linked_functions!`]) or of a packed FMU's shared library ([`Fmu::load`], after
//!   [`unzip`]) — with the model description that maps variable names to value references.
//! * [`Instance`]: one instance with typed calls by variable name (`set_real("right.Q", …)`,
//!   `get_real(…)`, `step(t, h)`, FMU states) returning the FMU's [`Status`], and the messages
//!   it logged ([`Instance::messages`]: status, category, text), collected per instance by a
//!   logger callback that never unwinds into the FMU.
//!
//! ```no_run
//! # fn main() -> Result<(), fmi_host::Error> {
//! let dir = std::path::Path::new("target/fmu/run/HertzContact");
//! fmi_host::unzip(std::path::Path::new("target/fmu/HertzContact.fmu"), dir)?;
//! let fmu = fmi_host::Fmu::load(dir, "linux64")?;
//! let instance = fmu.instantiate("demo")?;
//! assert_eq!(instance.initialize(), fmi_host::Status::Ok);
//! assert_eq!(instance.set_real("eta", -1e-3), fmi_host::Status::Ok);
//! assert_eq!(instance.step(0.0, 1e-3), fmi_host::Status::Ok);
//! println!("Fy = {} N", instance.get_real("Fy")?);
//! # Ok(())
//! # }
//! ```

mod description;
mod error;
mod fmu;
mod functions;
mod instance;
mod log;
mod status;

pub use description::{Causality, DefaultExperiment, ModelDescription, VarType, Variable};
pub use error::{CallError, Error};
pub use fmu::{file_uri, unzip, Fmu};
pub use functions::{Entry, EntryPoint, Functions};
pub use instance::{FmuState, Instance};
pub use log::Message;
pub use status::Status;

/// fmi-sys's FMI 2.0 types, for calls through [`Instance::functions`].
pub use fmi_sys::fmi2 as sys;
