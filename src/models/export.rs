//! The library's C API: the generic FMI functions of [`crate::fmi::export`], and
//! `fmi2Instantiate` over this crate's models ([`super::MODELS`]). A host linked to the crate
//! finds all 34 `fmi2*` functions here.

#![allow(non_snake_case)]

pub use crate::fmi::export::*;

use fmi_sys::fmi2::*;

/// # Safety
/// FMI 2.0 host contract: strings NUL-terminated or NULL, `functions` valid or NULL.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Instantiate(
    instanceName: fmi2String,
    fmuType: fmi2Type,
    fmuGUID: fmi2String,
    fmuResourceLocation: fmi2String,
    functions: *const fmi2CallbackFunctions,
    visible: fmi2Boolean,
    loggingOn: fmi2Boolean,
) -> fmi2Component {
    // SAFETY: the host's contract, passed on.
    unsafe {
        instantiate(
            super::MODELS,
            instanceName,
            fmuType,
            fmuGUID,
            fmuResourceLocation,
            functions,
            visible,
            loggingOn,
        )
    }
}
const _: fmi2InstantiateTYPE = Some(fmi2Instantiate);
