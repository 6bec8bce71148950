//! The crate's models as FMUs linked into the test binary: `fmi_host` drives them through the
//! exported `fmi2*` functions, the same C ABI a host resolves from the packed library.

#![allow(dead_code)] // each test crate uses a different part

use fmi_host::{Fmu, Instance};
use railcontact::fmi::model::ModelInfo;
use std::sync::Arc;

/// The resource location of linked instances: the `file:` URI of a directory that does not
/// exist (the tests use built-in profiles or absolute paths).
pub const NO_RESOURCES: &str = "file:///nonexistent/resources";

/// The FMU of `info`, linked, described by its generated model description.
pub fn fmu(info: &ModelInfo) -> Arc<Fmu> {
    let functions = fmi_host::linked_functions!(railcontact::fmi::export);
    Fmu::linked(
        functions,
        info.model_description_xml,
        Some(NO_RESOURCES.to_string()),
    )
    .unwrap_or_else(|e| panic!("{}: {e}", info.model_identifier))
}

/// An instance `name` of `info`; panics with the FMU's messages if it is refused.
#[track_caller]
pub fn instantiate(info: &ModelInfo, name: &str) -> Instance {
    fmu(info)
        .instantiate(name)
        .unwrap_or_else(|e| panic!("{e}"))
}
