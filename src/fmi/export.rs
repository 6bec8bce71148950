//! The 34 exported `fmi2*` functions of FMI 2.0 Co-Simulation (25 common + 9 CS).
//!
//! Each body: null-checks its pointers, refuses a component that is not a live instance (so a
//! second `fmi2FreeInstance` is ignored and a call after it returns `fmi2Error`), checks the
//! state machine, runs inside `catch_unwind` (a panic becomes `fmi2Error` with a log line, never
//! an abort of the host), and delegates to [`Instance`]. Every signature is pinned at compile
//! time against fmi-sys's `fmi2XxxTYPE`.
//! Functions this FMU does not support log the reason and return `fmi2Error`.

#![allow(non_snake_case)] // parameter names follow the FMI 2.0 standard headers

use super::instance::{mask, Instance, Logger, State, DISCARD, ERROR, OK};
use super::model::{InstanceContext, ModelInfo};
use super::uri::resource_dir_from_uri;
use super::variables::VarType;
use fmi_sys::fmi2::*;
use std::ffi::{c_char, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// Addresses of the instances `fmi2Instantiate` returned that `fmi2FreeInstance` has not freed.
/// A call with any other pointer — freed (a second `fmi2FreeInstance`, a call after it) or never
/// ours — returns `fmi2Error` (or nothing, for `fmi2FreeInstance`) without touching memory, as
/// long as the allocator has not handed the address to a newer instance. It holds no model data,
/// so instances stay independent; the lookup allocates nothing.
static LIVE: Mutex<Vec<usize>> = Mutex::new(Vec::new());

fn live() -> MutexGuard<'static, Vec<usize>> {
    LIVE.lock().unwrap_or_else(PoisonError::into_inner)
}

fn is_live(c: fmi2Component) -> bool {
    live().contains(&(c as usize))
}

/// Forgets `c`; false if it was not live.
fn forget(c: fmi2Component) -> bool {
    let mut live = live();
    match live.iter().position(|&p| p == c as usize) {
        Some(i) => {
            live.swap_remove(i);
            if live.is_empty() {
                // Nothing left allocated when the host unloads the library.
                live.shrink_to_fit();
            }
            true
        }
        None => false,
    }
}

/// Reads a possibly-NULL C string.
unsafe fn c_str<'a>(s: fmi2String) -> Option<&'a str> {
    if s.is_null() {
        None
    } else {
        // SAFETY: the host passes NUL-terminated strings (FMI 2.0 §2.1.2).
        unsafe { CStr::from_ptr(s) }.to_str().ok()
    }
}

unsafe fn slice<'a, T>(p: *const T, n: usize) -> &'a [T] {
    if n == 0 {
        &[]
    } else {
        // SAFETY: non-null checked by the caller; the host owns n elements.
        unsafe { std::slice::from_raw_parts(p, n) }
    }
}

unsafe fn slice_mut<'a, T>(p: *mut T, n: usize) -> &'a mut [T] {
    if n == 0 {
        &mut []
    } else {
        // SAFETY: non-null checked by the caller; the host owns n elements.
        unsafe { std::slice::from_raw_parts_mut(p, n) }
    }
}

fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown panic".to_string()
    }
}

/// Runs `body` on the instance behind `c` if `function` is allowed in its state; a panic is
/// caught, logged and turned into `fmi2Error` (the instance goes to the error state).
fn with_instance(
    c: fmi2Component,
    function: &str,
    allowed: u8,
    body: impl FnOnce(&mut Instance) -> fmi2Status,
) -> fmi2Status {
    if c.is_null() || !is_live(c) {
        return ERROR;
    }
    let ptr = c.cast::<Instance>();
    let result = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: `c` was returned by fmi2Instantiate and not yet freed (host contract).
        let inst = unsafe { &mut *ptr };
        if !inst.allowed(function, allowed) {
            return ERROR;
        }
        body(inst)
    }));
    result.unwrap_or_else(|payload| {
        let text = panic_text(payload.as_ref());
        let _ = catch_unwind(AssertUnwindSafe(|| {
            // SAFETY: as above; the panicking borrow has ended.
            let inst = unsafe { &mut *ptr };
            inst.state = State::Error;
            inst.error(&format!("{function}: internal error: {text}"));
        }));
        ERROR
    })
}

fn null_args(inst: &Instance, function: &str, n: usize, ptrs: &[bool]) -> bool {
    if n > 0 && ptrs.iter().any(|&is_null| is_null) {
        inst.error(&format!("{function}: NULL array with nvr = {n}"));
        return true;
    }
    false
}

// ---------------------------------------------------------------------------------------------
// Inquire version numbers and platform

#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}
const _: fmi2GetTypesPlatformTYPE = Some(fmi2GetTypesPlatform);

#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}
const _: fmi2GetVersionTYPE = Some(fmi2GetVersion);

// ---------------------------------------------------------------------------------------------
// Creation and destruction

/// `fmi2Instantiate` over the models `registry` a library serves (its exported
/// `fmi2Instantiate` passes them; the glue knows no model): picks the model by GUID.
///
/// # Safety
/// FMI 2.0 host contract: strings NUL-terminated or NULL, `functions` valid or NULL.
#[allow(clippy::too_many_arguments)]
pub unsafe fn instantiate(
    registry: &'static [&'static ModelInfo],
    instanceName: fmi2String,
    fmuType: fmi2Type,
    fmuGUID: fmi2String,
    fmuResourceLocation: fmi2String,
    functions: *const fmi2CallbackFunctions,
    _visible: fmi2Boolean,
    loggingOn: fmi2Boolean,
) -> fmi2Component {
    let result = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: host contract (see above).
        let (name, guid, location) = unsafe {
            (
                c_str(instanceName).unwrap_or(""),
                c_str(fmuGUID),
                c_str(fmuResourceLocation),
            )
        };
        // SAFETY: `functions` is NULL or points to the host's callback struct.
        let callbacks = unsafe { functions.as_ref() };
        let logger = Logger::new(
            callbacks.and_then(|f| f.logger),
            callbacks.map_or(std::ptr::null_mut(), |f| f.componentEnvironment),
            name,
            loggingOn != 0,
        );
        if name.is_empty() {
            logger.log(
                ERROR,
                "fmi2Instantiate: instanceName must be a non-empty string",
            );
            return std::ptr::null_mut();
        }
        if fmuType != fmi2Type_fmi2CoSimulation {
            logger.log(
                ERROR,
                &format!(
                    "fmi2Instantiate: fmuType = {fmuType}: only Co-Simulation (1) is supported"
                ),
            );
            return std::ptr::null_mut();
        }
        let Some(info) = guid.and_then(|g| registry.iter().find(|m| m.guid == g)) else {
            let known: Vec<String> = registry
                .iter()
                .map(|m| format!("{} {}", m.model_identifier, m.guid))
                .collect();
            logger.log(
                ERROR,
                &format!(
                    "fmi2Instantiate: GUID {:?} does not match this binary ({})",
                    guid.unwrap_or("NULL"),
                    known.join(", ")
                ),
            );
            return std::ptr::null_mut();
        };
        let context = InstanceContext {
            resource_dir: location.and_then(resource_dir_from_uri),
        };
        let inst = Box::new(Instance::new(info, name, context, logger));
        inst.logger.log(
            OK,
            &format!("instantiated {} ({})", info.model_identifier, info.guid),
        );
        let c: fmi2Component = Box::into_raw(inst).cast();
        live().push(c as usize);
        c
    }));
    result.unwrap_or(std::ptr::null_mut())
}

/// # Safety
/// `c` must come from `fmi2Instantiate` and not have been freed.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2FreeInstance(c: fmi2Component) {
    // NULL, already freed or not ours: nothing to free (a double free is ignored).
    if c.is_null() || !forget(c) {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: host contract; ownership returns to Rust exactly once.
        drop(unsafe { Box::from_raw(c.cast::<Instance>()) });
    }));
}
const _: fmi2FreeInstanceTYPE = Some(fmi2FreeInstance);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: fmi2Component,
    loggingOn: fmi2Boolean,
    nCategories: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    with_instance(c, "fmi2SetDebugLogging", mask::SET_DEBUG_LOGGING, |inst| {
        if null_args(
            inst,
            "fmi2SetDebugLogging",
            nCategories,
            &[categories.is_null()],
        ) {
            return ERROR;
        }
        // SAFETY: checked non-null for n > 0.
        for &cat in unsafe { slice(categories, nCategories) } {
            // SAFETY: host strings.
            let name = unsafe { c_str(cat) }.unwrap_or("");
            if !matches!(name, "logStatusError" | "logStatusWarning" | "logAll") {
                return inst.error(&format!(
                    "fmi2SetDebugLogging: unknown log category {name:?} (known: logStatusError, logStatusWarning, logAll)"
                ));
            }
        }
        inst.logger.logging_on = loggingOn != 0;
        OK
    })
}
const _: fmi2SetDebugLoggingTYPE = Some(fmi2SetDebugLogging);

// ---------------------------------------------------------------------------------------------
// Initialization, termination, reset

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: fmi2Component,
    _toleranceDefined: fmi2Boolean,
    _tolerance: fmi2Real,
    startTime: fmi2Real,
    stopTimeDefined: fmi2Boolean,
    stopTime: fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2SetupExperiment", mask::SETUP_EXPERIMENT, |inst| {
        inst.setup_experiment(startTime, (stopTimeDefined != 0).then_some(stopTime))
    })
}
const _: fmi2SetupExperimentTYPE = Some(fmi2SetupExperiment);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status {
    with_instance(
        c,
        "fmi2EnterInitializationMode",
        mask::ENTER_INITIALIZATION_MODE,
        Instance::enter_initialization_mode,
    )
}
const _: fmi2EnterInitializationModeTYPE = Some(fmi2EnterInitializationMode);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status {
    with_instance(
        c,
        "fmi2ExitInitializationMode",
        mask::EXIT_INITIALIZATION_MODE,
        Instance::exit_initialization_mode,
    )
}
const _: fmi2ExitInitializationModeTYPE = Some(fmi2ExitInitializationMode);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Terminate(c: fmi2Component) -> fmi2Status {
    with_instance(c, "fmi2Terminate", mask::TERMINATE, Instance::terminate)
}
const _: fmi2TerminateTYPE = Some(fmi2Terminate);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Reset(c: fmi2Component) -> fmi2Status {
    with_instance(c, "fmi2Reset", mask::RESET, Instance::reset)
}
const _: fmi2ResetTYPE = Some(fmi2Reset);

// ---------------------------------------------------------------------------------------------
// Getting and setting variable values

/// # Safety
/// FMI 2.0 host contract: `vr` and `value` hold `nvr` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2GetReal", mask::GET, |inst| {
        if null_args(inst, "fmi2GetReal", nvr, &[vr.is_null(), value.is_null()]) {
            return ERROR;
        }
        // SAFETY: checked non-null, host owns nvr elements.
        let (vrs, out) = unsafe { (slice(vr, nvr), slice_mut(value, nvr)) };
        inst.get(VarType::Real, vrs, out, |v, s| v.reals[s])
    })
}
const _: fmi2GetRealTYPE = Some(fmi2GetReal);

/// # Safety
/// FMI 2.0 host contract: `vr` and `value` hold `nvr` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Integer,
) -> fmi2Status {
    with_instance(c, "fmi2GetInteger", mask::GET, |inst| {
        if null_args(
            inst,
            "fmi2GetInteger",
            nvr,
            &[vr.is_null(), value.is_null()],
        ) {
            return ERROR;
        }
        // SAFETY: checked non-null, host owns nvr elements.
        let (vrs, out) = unsafe { (slice(vr, nvr), slice_mut(value, nvr)) };
        inst.get(VarType::Integer, vrs, out, |v, s| v.integers[s])
    })
}
const _: fmi2GetIntegerTYPE = Some(fmi2GetInteger);

/// # Safety
/// FMI 2.0 host contract: `vr` and `value` hold `nvr` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    with_instance(c, "fmi2GetBoolean", mask::GET, |inst| {
        if null_args(
            inst,
            "fmi2GetBoolean",
            nvr,
            &[vr.is_null(), value.is_null()],
        ) {
            return ERROR;
        }
        // SAFETY: checked non-null, host owns nvr elements.
        let (vrs, out) = unsafe { (slice(vr, nvr), slice_mut(value, nvr)) };
        inst.get(VarType::Boolean, vrs, out, |v, s| {
            fmi2Boolean::from(v.booleans[s])
        })
    })
}
const _: fmi2GetBooleanTYPE = Some(fmi2GetBoolean);

/// # Safety
/// FMI 2.0 host contract: `vr` and `value` hold `nvr` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2String,
) -> fmi2Status {
    with_instance(c, "fmi2GetString", mask::GET, |inst| {
        if null_args(inst, "fmi2GetString", nvr, &[vr.is_null(), value.is_null()]) {
            return ERROR;
        }
        // SAFETY: checked non-null, host owns nvr elements.
        let (vrs, out) = unsafe { (slice(vr, nvr), slice_mut(value, nvr)) };
        match inst.get_strings(vrs) {
            Ok(strings) => {
                for (o, s) in out.iter_mut().zip(strings) {
                    *o = s.as_ptr();
                }
                OK
            }
            Err(status) => status,
        }
    })
}
const _: fmi2GetStringTYPE = Some(fmi2GetString);

/// # Safety
/// FMI 2.0 host contract: `vr` and `value` hold `nvr` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2SetReal", mask::SET, |inst| {
        if null_args(inst, "fmi2SetReal", nvr, &[vr.is_null(), value.is_null()]) {
            return ERROR;
        }
        // SAFETY: checked non-null, host owns nvr elements.
        let (vrs, vals) = unsafe { (slice(vr, nvr), slice(value, nvr)) };
        inst.set(
            VarType::Real,
            vrs,
            vals,
            |v, x| v.accepts_real(x),
            |v, s, x| v.reals[s] = x,
        )
    })
}
const _: fmi2SetRealTYPE = Some(fmi2SetReal);

/// # Safety
/// FMI 2.0 host contract: `vr` and `value` hold `nvr` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Integer,
) -> fmi2Status {
    with_instance(c, "fmi2SetInteger", mask::SET, |inst| {
        if null_args(
            inst,
            "fmi2SetInteger",
            nvr,
            &[vr.is_null(), value.is_null()],
        ) {
            return ERROR;
        }
        // SAFETY: checked non-null, host owns nvr elements.
        let (vrs, vals) = unsafe { (slice(vr, nvr), slice(value, nvr)) };
        inst.set(
            VarType::Integer,
            vrs,
            vals,
            |v, k| v.accepts_integer(k),
            |v, s, k| v.integers[s] = k,
        )
    })
}
const _: fmi2SetIntegerTYPE = Some(fmi2SetInteger);

/// # Safety
/// FMI 2.0 host contract: `vr` and `value` hold `nvr` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Boolean,
) -> fmi2Status {
    with_instance(c, "fmi2SetBoolean", mask::SET, |inst| {
        if null_args(
            inst,
            "fmi2SetBoolean",
            nvr,
            &[vr.is_null(), value.is_null()],
        ) {
            return ERROR;
        }
        // SAFETY: checked non-null, host owns nvr elements.
        let (vrs, vals) = unsafe { (slice(vr, nvr), slice(value, nvr)) };
        inst.set(
            VarType::Boolean,
            vrs,
            vals,
            |_, _| true,
            |v, s, b| v.booleans[s] = b != 0,
        )
    })
}
const _: fmi2SetBooleanTYPE = Some(fmi2SetBoolean);

/// # Safety
/// FMI 2.0 host contract: `vr` and `value` hold `nvr` elements, strings NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2String,
) -> fmi2Status {
    with_instance(c, "fmi2SetString", mask::SET, |inst| {
        if null_args(inst, "fmi2SetString", nvr, &[vr.is_null(), value.is_null()]) {
            return ERROR;
        }
        // SAFETY: checked non-null, host owns nvr elements.
        let (vrs, vals) = unsafe { (slice(vr, nvr), slice(value, nvr)) };
        let mut texts = Vec::with_capacity(nvr);
        for &p in vals {
            // SAFETY: host strings.
            match unsafe { c_str(p) } {
                Some(s) => texts.push(StringArg(s.to_string())),
                None => return inst.error("fmi2SetString: NULL or non-UTF-8 string"),
            }
        }
        let refs: Vec<&StringArg> = texts.iter().collect();
        inst.set(
            VarType::String,
            vrs,
            &refs,
            |_, _| true,
            |v, s, x| v.strings[s] = x.0.clone(),
        )
    })
}
const _: fmi2SetStringTYPE = Some(fmi2SetString);

/// A string argument, displayed quoted in error messages.
struct StringArg(String);
impl std::fmt::Display for StringArg {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:?}", self.0)
    }
}

// ---------------------------------------------------------------------------------------------
// FMU state: values only (serialized bytes), never pointers

/// Stores `bytes` as the FMU state in `*slot`: a new `Box<Vec<u8>>` if the slot is NULL, else the
/// existing state is overwritten in place (FMI 2.0: `fmi2GetFMUstate` may reuse a state).
///
/// # Safety
/// `slot` is non-null and `*slot` is NULL or a state created by this library.
unsafe fn store_state(slot: *mut fmi2FMUstate, bytes: Vec<u8>) {
    // SAFETY: per the function's contract.
    unsafe {
        let slot = &mut *slot;
        if slot.is_null() {
            *slot = Box::into_raw(Box::new(bytes)).cast();
        } else {
            *(*slot).cast::<Vec<u8>>() = bytes;
        }
    }
}

/// # Safety
/// FMI 2.0 host contract: `FMUstate` points to NULL or to a state of this library.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetFMUstate(
    c: fmi2Component,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    with_instance(c, "fmi2GetFMUstate", mask::FMU_STATE, |inst| {
        if FMUstate.is_null() {
            return inst.error("fmi2GetFMUstate: FMUstate is NULL");
        }
        // SAFETY: checked non-null; *FMUstate is NULL or a state of ours.
        unsafe { store_state(FMUstate, inst.save_state()) };
        OK
    })
}
const _: fmi2GetFMUstateTYPE = Some(fmi2GetFMUstate);

/// # Safety
/// FMI 2.0 host contract: `FMUstate` was created by this library.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status {
    with_instance(c, "fmi2SetFMUstate", mask::FMU_STATE, |inst| {
        if FMUstate.is_null() {
            return inst.error("fmi2SetFMUstate: FMUstate is NULL");
        }
        // SAFETY: created by fmi2GetFMUstate/fmi2DeSerializeFMUstate as Box<Vec<u8>>.
        let bytes = unsafe { &*FMUstate.cast::<Vec<u8>>() };
        match inst.restore_state(bytes) {
            Ok(()) => OK,
            Err(m) => inst.error(&format!("fmi2SetFMUstate: {m}")),
        }
    })
}
const _: fmi2SetFMUstateTYPE = Some(fmi2SetFMUstate);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2FreeFMUstate(
    c: fmi2Component,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    with_instance(c, "fmi2FreeFMUstate", mask::FMU_STATE, |_inst| {
        if FMUstate.is_null() {
            return OK;
        }
        // SAFETY: *FMUstate is NULL or a Box<Vec<u8>> we allocated; set to NULL after.
        unsafe {
            let slot = &mut *FMUstate;
            if !slot.is_null() {
                drop(Box::from_raw((*slot).cast::<Vec<u8>>()));
                *slot = std::ptr::null_mut();
            }
        }
        OK
    })
}
const _: fmi2FreeFMUstateTYPE = Some(fmi2FreeFMUstate);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    size: *mut usize,
) -> fmi2Status {
    with_instance(c, "fmi2SerializedFMUstateSize", mask::FMU_STATE, |inst| {
        if FMUstate.is_null() || size.is_null() {
            return inst.error("fmi2SerializedFMUstateSize: NULL argument");
        }
        // SAFETY: state is a Box<Vec<u8>> of ours; size checked non-null.
        unsafe { *size = (*FMUstate.cast::<Vec<u8>>()).len() };
        OK
    })
}
const _: fmi2SerializedFMUstateSizeTYPE = Some(fmi2SerializedFMUstateSize);

/// # Safety
/// FMI 2.0 host contract: `serializedState` holds `size` bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    serializedState: *mut fmi2Byte,
    size: usize,
) -> fmi2Status {
    with_instance(c, "fmi2SerializeFMUstate", mask::FMU_STATE, |inst| {
        if FMUstate.is_null() || serializedState.is_null() {
            return inst.error("fmi2SerializeFMUstate: NULL argument");
        }
        // SAFETY: state is a Box<Vec<u8>> of ours.
        let bytes = unsafe { &*FMUstate.cast::<Vec<u8>>() };
        if size != bytes.len() {
            return inst.error(&format!(
                "fmi2SerializeFMUstate: size = {size}, the state needs exactly {} bytes",
                bytes.len()
            ));
        }
        // SAFETY: the host buffer holds `size` bytes.
        unsafe { slice_mut(serializedState.cast::<u8>(), size) }.copy_from_slice(bytes);
        OK
    })
}
const _: fmi2SerializeFMUstateTYPE = Some(fmi2SerializeFMUstate);

/// # Safety
/// FMI 2.0 host contract: `serializedState` holds `size` bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: fmi2Component,
    serializedState: *const fmi2Byte,
    size: usize,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    with_instance(c, "fmi2DeSerializeFMUstate", mask::FMU_STATE, |inst| {
        if serializedState.is_null() || FMUstate.is_null() {
            return inst.error("fmi2DeSerializeFMUstate: NULL argument");
        }
        // SAFETY: the host buffer holds `size` bytes.
        let bytes = unsafe { slice(serializedState.cast::<u8>(), size) }.to_vec();
        if let Err(m) = inst.validate_state(&bytes) {
            return inst.error(&format!("fmi2DeSerializeFMUstate: {m}"));
        }
        // SAFETY: checked non-null; *FMUstate is NULL or a state of ours.
        unsafe { store_state(FMUstate, bytes) };
        OK
    })
}
const _: fmi2DeSerializeFMUstateTYPE = Some(fmi2DeSerializeFMUstate);

// ---------------------------------------------------------------------------------------------
// Directional derivatives

/// # Safety
/// FMI 2.0 host contract: `vUnknown_ref` and `dvUnknown` hold `nUnknown` elements, `vKnown_ref`
/// and `dvKnown` hold `nKnown`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: fmi2Component,
    vUnknown_ref: *const fmi2ValueReference,
    nUnknown: usize,
    vKnown_ref: *const fmi2ValueReference,
    nKnown: usize,
    dvKnown: *const fmi2Real,
    dvUnknown: *mut fmi2Real,
) -> fmi2Status {
    const F: &str = "fmi2GetDirectionalDerivative";
    with_instance(c, F, mask::DIRECTIONAL_DERIVATIVE, |inst| {
        if null_args(
            inst,
            F,
            nUnknown,
            &[vUnknown_ref.is_null(), dvUnknown.is_null()],
        ) || null_args(inst, F, nKnown, &[vKnown_ref.is_null(), dvKnown.is_null()])
        {
            return ERROR;
        }
        // SAFETY: checked non-null, the host owns the elements.
        let (unknowns, knowns, seed, out) = unsafe {
            (
                slice(vUnknown_ref, nUnknown),
                slice(vKnown_ref, nKnown),
                slice(dvKnown, nKnown),
                slice_mut(dvUnknown, nUnknown),
            )
        };
        inst.directional_derivative(unknowns, knowns, seed, out)
    })
}
const _: fmi2GetDirectionalDerivativeTYPE = Some(fmi2GetDirectionalDerivative);

// ---------------------------------------------------------------------------------------------
// Unsupported: input/output derivatives, asynchronous steps

fn unsupported(c: fmi2Component, function: &str, why: &str) -> fmi2Status {
    with_instance(c, function, mask::UNSUPPORTED, |inst| {
        inst.error(&format!("{function} is not supported: {why}"))
    })
}

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _nvr: usize,
    _order: *const fmi2Integer,
    _value: *const fmi2Real,
) -> fmi2Status {
    unsupported(
        c,
        "fmi2SetRealInputDerivatives",
        "canInterpolateInputs=\"false\"",
    )
}
const _: fmi2SetRealInputDerivativesTYPE = Some(fmi2SetRealInputDerivatives);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _nvr: usize,
    _order: *const fmi2Integer,
    _value: *mut fmi2Real,
) -> fmi2Status {
    unsupported(
        c,
        "fmi2GetRealOutputDerivatives",
        "maxOutputDerivativeOrder=\"0\"",
    )
}
const _: fmi2GetRealOutputDerivativesTYPE = Some(fmi2GetRealOutputDerivatives);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2CancelStep(c: fmi2Component) -> fmi2Status {
    unsupported(
        c,
        "fmi2CancelStep",
        "steps run synchronously (canRunAsynchronuously=\"false\")",
    )
}
const _: fmi2CancelStepTYPE = Some(fmi2CancelStep);

// ---------------------------------------------------------------------------------------------
// Stepping and status

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2DoStep(
    c: fmi2Component,
    currentCommunicationPoint: fmi2Real,
    communicationStepSize: fmi2Real,
    _noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
) -> fmi2Status {
    with_instance(c, "fmi2DoStep", mask::DO_STEP, |inst| {
        inst.do_step(currentCommunicationPoint, communicationStepSize)
    })
}
const _: fmi2DoStepTYPE = Some(fmi2DoStep);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Status,
) -> fmi2Status {
    with_instance(c, "fmi2GetStatus", mask::STATUS, |inst| {
        if value.is_null() {
            return inst.error("fmi2GetStatus: value is NULL");
        }
        if s == fmi2StatusKind_fmi2DoStepStatus {
            // SAFETY: checked non-null.
            unsafe { *value = if inst.terminated() { DISCARD } else { OK } };
            OK
        } else {
            DISCARD
        }
    })
}
const _: fmi2GetStatusTYPE = Some(fmi2GetStatus);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetRealStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2GetRealStatus", mask::STATUS, |inst| {
        if value.is_null() {
            return inst.error("fmi2GetRealStatus: value is NULL");
        }
        if s == fmi2StatusKind_fmi2LastSuccessfulTime {
            // SAFETY: checked non-null.
            unsafe { *value = inst.last_successful_time() };
            OK
        } else {
            DISCARD
        }
    })
}
const _: fmi2GetRealStatusTYPE = Some(fmi2GetRealStatus);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetIntegerStatus(
    c: fmi2Component,
    _s: fmi2StatusKind,
    _value: *mut fmi2Integer,
) -> fmi2Status {
    // No integer status kind is defined by FMI 2.0 CS.
    with_instance(c, "fmi2GetIntegerStatus", mask::STATUS, |_| DISCARD)
}
const _: fmi2GetIntegerStatusTYPE = Some(fmi2GetIntegerStatus);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    with_instance(c, "fmi2GetBooleanStatus", mask::STATUS, |inst| {
        if value.is_null() {
            return inst.error("fmi2GetBooleanStatus: value is NULL");
        }
        if s == fmi2StatusKind_fmi2Terminated {
            // SAFETY: checked non-null.
            unsafe { *value = fmi2Boolean::from(inst.terminated()) };
            OK
        } else {
            DISCARD
        }
    })
}
const _: fmi2GetBooleanStatusTYPE = Some(fmi2GetBooleanStatus);

/// # Safety
/// FMI 2.0 host contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetStringStatus(
    c: fmi2Component,
    _s: fmi2StatusKind,
    _value: *mut fmi2String,
) -> fmi2Status {
    // fmi2PendingStatus is meaningful only for asynchronous steps, which this FMU never runs.
    with_instance(c, "fmi2GetStringStatus", mask::STATUS, |_| DISCARD)
}
const _: fmi2GetStringStatusTYPE = Some(fmi2GetStringStatus);
