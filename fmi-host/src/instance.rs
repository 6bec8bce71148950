//! One instance of an FMU, driven through the FMI 2.0 C API with typed, name-based calls.
//!
//! Every call returns the FMU's [`Status`] (or a [`CallError`] that carries it and the log);
//! nothing here panics inside a callback. Methods that take a variable name panic when the
//! model description has no such variable: that is a bug of the calling host, found by
//! [`ModelDescription::variable`](crate::ModelDescription::variable) beforehand when names come
//! from outside.

use crate::description::{VarType, Variable};
use crate::error::CallError;
use crate::fmu::Fmu;
use crate::functions::Functions;
use crate::log::{Message, Sink};
use crate::{Error, Status};
use fmi_sys::fmi2::*;
use std::ffi::{CStr, CString};
use std::sync::Arc;

/// A live FMU instance; freed (`fmi2FreeInstance`) when dropped.
pub struct Instance {
    component: fmi2Component,
    name: String,
    /// Where the FMU's messages arrive; must outlive the component (dropped after it is freed).
    sink: Box<Sink>,
    fmu: Arc<Fmu>,
    /// Value references of the Real outputs, then of the Integer outputs.
    real_outputs: Vec<u32>,
    integer_outputs: Vec<u32>,
}

// SAFETY: FMI 2.0 lets a host use an instance from any thread, one call at a time; `&self`
// methods are not `Sync`, so two threads cannot call into one instance at once.
unsafe impl Send for Instance {}

/// An FMU state (`fmi2FMUstate`) of an instance, freed when dropped.
pub struct FmuState<'a> {
    instance: &'a Instance,
    state: fmi2FMUstate,
}

fn c_string(what: &str, value: &str) -> Result<CString, Error> {
    CString::new(value).map_err(|_| Error::Nul {
        what: what.to_string(),
        value: value.to_string(),
    })
}

impl Instance {
    pub(crate) fn new(
        fmu: Arc<Fmu>,
        name: &str,
        guid: &str,
        resource_uri: Option<&str>,
    ) -> Result<Self, Error> {
        let c_name = c_string("instanceName", name)?;
        let c_guid = c_string("fmuGUID", guid)?;
        let c_uri = resource_uri
            .map(|uri| c_string("fmuResourceLocation", uri))
            .transpose()?;
        let sink = Sink::new();
        let callbacks = sink.callbacks();
        // SAFETY: NUL-terminated strings and callbacks valid for the call (the FMU copies what it
        // keeps); the component environment (`sink`) lives until the instance is freed.
        let component = unsafe {
            (fmu.functions().fmi2Instantiate)(
                c_name.as_ptr(),
                fmi2Type_fmi2CoSimulation,
                c_guid.as_ptr(),
                c_uri.as_ref().map_or(std::ptr::null(), |u| u.as_ptr()),
                &callbacks,
                0,
                0,
            )
        };
        if component.is_null() {
            let messages = sink.messages().clone();
            return Err(Error::Instantiate {
                name: name.to_string(),
                messages,
            });
        }
        let outputs = |ty| fmu.description().outputs(ty).map(|v| v.vr).collect();
        Ok(Self {
            component,
            name: name.to_string(),
            sink,
            real_outputs: outputs(VarType::Real),
            integer_outputs: outputs(VarType::Integer),
            fmu,
        })
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    pub fn fmu(&self) -> &Fmu {
        &self.fmu
    }

    /// The `fmi2Component`, for calls this API does not wrap (through [`Instance::functions`]).
    pub fn component(&self) -> fmi2Component {
        self.component
    }

    pub fn functions(&self) -> &Functions {
        self.fmu.functions()
    }

    /// The variable `name`; panics if the model has none (a bug of the caller).
    #[track_caller]
    pub fn variable(&self, name: &str) -> &Variable {
        self.fmu
            .description()
            .variable(name)
            .unwrap_or_else(|e| panic!("{}: {e}", self.name))
    }

    /// The value reference of variable `name`; panics if the model has none.
    #[track_caller]
    pub fn vr(&self, name: &str) -> u32 {
        self.variable(name).vr
    }

    // -- the log

    /// Every message the FMU logged for this instance, oldest first.
    pub fn messages(&self) -> Vec<Message> {
        self.sink.messages().clone()
    }

    /// Forgets the messages logged so far (long runs).
    pub fn clear_messages(&self) {
        self.sink.messages().clear();
    }

    fn call_error(&self, call: String, status: Status) -> CallError {
        CallError {
            instance: self.name.clone(),
            call,
            status,
            log: self.messages(),
        }
    }

    fn check(&self, status: Status, call: impl FnOnce() -> String) -> Result<(), CallError> {
        if status == Status::Ok {
            Ok(())
        } else {
            Err(self.call_error(call(), status))
        }
    }

    // -- life cycle

    /// `fmi2SetupExperiment` without tolerance, from `start`, to `stop` if given.
    pub fn setup_experiment(&self, start: f64, stop: Option<f64>) -> Status {
        let defined = fmi2Boolean::from(stop.is_some());
        // SAFETY: live instance.
        Status::from(unsafe {
            (self.functions().fmi2SetupExperiment)(
                self.component,
                0,
                0.0,
                start,
                defined,
                stop.unwrap_or(0.0),
            )
        })
    }

    /// `fmi2EnterInitializationMode`.
    pub fn enter_initialization(&self) -> Status {
        // SAFETY: live instance.
        Status::from(unsafe { (self.functions().fmi2EnterInitializationMode)(self.component) })
    }

    /// `fmi2ExitInitializationMode`.
    pub fn exit_initialization(&self) -> Status {
        // SAFETY: live instance.
        Status::from(unsafe { (self.functions().fmi2ExitInitializationMode)(self.component) })
    }

    /// Set-up from t = 0 without stop time, enter and exit initialization mode; the first
    /// status that is not `fmi2OK` (then the later calls are not made), else `fmi2OK`.
    pub fn initialize(&self) -> Status {
        let s = self.setup_experiment(0.0, None);
        if s != Status::Ok {
            return s;
        }
        let s = self.enter_initialization();
        if s != Status::Ok {
            return s;
        }
        self.exit_initialization()
    }

    /// `fmi2DoStep` from `t` over `h`.
    pub fn step(&self, t: f64, h: f64) -> Status {
        // SAFETY: live instance.
        Status::from(unsafe { (self.functions().fmi2DoStep)(self.component, t, h, 1) })
    }

    /// `fmi2Terminate`.
    pub fn terminate(&self) -> Status {
        // SAFETY: live instance.
        Status::from(unsafe { (self.functions().fmi2Terminate)(self.component) })
    }

    /// `fmi2Reset`.
    pub fn reset(&self) -> Status {
        // SAFETY: live instance.
        Status::from(unsafe { (self.functions().fmi2Reset)(self.component) })
    }

    /// `fmi2FreeInstance` now rather than at the end of the scope.
    pub fn free(self) {}

    /// (status, Terminated) of `fmi2GetBooleanStatus(fmi2Terminated)`.
    pub fn terminated(&self) -> (Status, bool) {
        let mut b: fmi2Boolean = 0;
        // SAFETY: live instance, one slot.
        let s = unsafe {
            (self.functions().fmi2GetBooleanStatus)(
                self.component,
                fmi2StatusKind_fmi2Terminated,
                &mut b,
            )
        };
        (Status::from(s), b != 0)
    }

    /// (status, time) of `fmi2GetRealStatus(fmi2LastSuccessfulTime)`.
    pub fn last_successful_time(&self) -> (Status, f64) {
        let mut t = f64::NAN;
        // SAFETY: live instance, one slot.
        let s = unsafe {
            (self.functions().fmi2GetRealStatus)(
                self.component,
                fmi2StatusKind_fmi2LastSuccessfulTime,
                &mut t,
            )
        };
        (Status::from(s), t)
    }

    // -- setting values

    /// `fmi2SetReal` of variable `name`.
    #[track_caller]
    pub fn set_real(&self, name: &str, x: f64) -> Status {
        self.set_reals(&[self.vr(name)], &[x])
    }

    /// `fmi2SetReal` of one value reference.
    pub fn set_real_vr(&self, vr: u32, x: f64) -> Status {
        self.set_reals(&[vr], &[x])
    }

    /// `fmi2SetReal` of several value references in one call; `fmi2Error` without a call when
    /// the two slices differ in length.
    pub fn set_reals(&self, vrs: &[u32], xs: &[f64]) -> Status {
        if vrs.len() != xs.len() {
            return Status::Error;
        }
        // SAFETY: both arrays hold vrs.len() elements.
        Status::from(unsafe {
            (self.functions().fmi2SetReal)(self.component, vrs.as_ptr(), vrs.len(), xs.as_ptr())
        })
    }

    /// `fmi2SetInteger` of variable `name`.
    #[track_caller]
    pub fn set_integer(&self, name: &str, k: i32) -> Status {
        let vr = self.vr(name);
        // SAFETY: one value reference, one value.
        Status::from(unsafe { (self.functions().fmi2SetInteger)(self.component, &vr, 1, &k) })
    }

    /// `fmi2SetBoolean` of variable `name`.
    #[track_caller]
    pub fn set_boolean(&self, name: &str, b: bool) -> Status {
        let vr = self.vr(name);
        let value = fmi2Boolean::from(b);
        // SAFETY: one value reference, one value.
        Status::from(unsafe { (self.functions().fmi2SetBoolean)(self.component, &vr, 1, &value) })
    }

    /// `fmi2SetString` of variable `name`; `fmi2Error` without a call when `s` holds a NUL byte
    /// (a C string cannot).
    #[track_caller]
    pub fn set_string(&self, name: &str, s: &str) -> Status {
        let vr = self.vr(name);
        let Ok(value) = CString::new(s) else {
            return Status::Error;
        };
        let p = value.as_ptr();
        // SAFETY: one value reference, one NUL-terminated string alive for the call.
        Status::from(unsafe { (self.functions().fmi2SetString)(self.component, &vr, 1, &p) })
    }

    // -- getting values

    /// `fmi2GetReal` of one value reference: (status, value; NaN unless the FMU wrote it).
    pub fn get_real_vr(&self, vr: u32) -> (Status, f64) {
        let mut x = [f64::NAN];
        let s = self.get_reals(&[vr], &mut x);
        (s, x[0])
    }

    /// `fmi2GetReal` of several value references in one call into `out`; `fmi2Error` without a
    /// call when the two slices differ in length.
    pub fn get_reals(&self, vrs: &[u32], out: &mut [f64]) -> Status {
        if vrs.len() != out.len() {
            return Status::Error;
        }
        // SAFETY: both arrays hold vrs.len() elements.
        Status::from(unsafe {
            (self.functions().fmi2GetReal)(
                self.component,
                vrs.as_ptr(),
                vrs.len(),
                out.as_mut_ptr(),
            )
        })
    }

    /// The value of Real variable `name`, or the call's error.
    #[track_caller]
    pub fn get_real(&self, name: &str) -> Result<f64, CallError> {
        let (s, x) = self.get_real_vr(self.vr(name));
        self.check(s, || format!("fmi2GetReal({name})"))?;
        Ok(x)
    }

    /// The value of Integer variable `name`, or the call's error.
    #[track_caller]
    pub fn get_integer(&self, name: &str) -> Result<i32, CallError> {
        let vr = self.vr(name);
        let mut k = i32::MIN;
        // SAFETY: one value reference, one slot.
        let s = unsafe { (self.functions().fmi2GetInteger)(self.component, &vr, 1, &mut k) };
        self.check(Status::from(s), || format!("fmi2GetInteger({name})"))?;
        Ok(k)
    }

    /// The value of Boolean variable `name`, or the call's error.
    #[track_caller]
    pub fn get_boolean(&self, name: &str) -> Result<bool, CallError> {
        let vr = self.vr(name);
        let mut b: fmi2Boolean = 0;
        // SAFETY: one value reference, one slot.
        let s = unsafe { (self.functions().fmi2GetBoolean)(self.component, &vr, 1, &mut b) };
        self.check(Status::from(s), || format!("fmi2GetBoolean({name})"))?;
        Ok(b != 0)
    }

    /// The value of String variable `name`, or the call's error.
    #[track_caller]
    pub fn get_string(&self, name: &str) -> Result<String, CallError> {
        let vr = self.vr(name);
        let mut p: fmi2String = std::ptr::null();
        // SAFETY: one value reference, one slot.
        let s = unsafe { (self.functions().fmi2GetString)(self.component, &vr, 1, &mut p) };
        self.check(Status::from(s), || format!("fmi2GetString({name})"))?;
        if p.is_null() {
            let call = format!("fmi2GetString({name}), which gave a NULL pointer,");
            return Err(self.call_error(call, Status::Ok));
        }
        // SAFETY: a NUL-terminated string, valid until the next call on this instance.
        Ok(unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned())
    }

    /// Every output: the Real ones in the order of the model description, then the Integer ones
    /// as f64, in one `fmi2GetReal` and one `fmi2GetInteger`. The worse of the two statuses.
    pub fn read_outputs(&self) -> (Status, Vec<f64>) {
        let mut reals = vec![f64::NAN; self.real_outputs.len()];
        let mut integers = vec![i32::MIN; self.integer_outputs.len()];
        let s_real = self.get_reals(&self.real_outputs, &mut reals);
        // SAFETY: arrays of matching lengths.
        let s_integer = Status::from(unsafe {
            (self.functions().fmi2GetInteger)(
                self.component,
                self.integer_outputs.as_ptr(),
                integers.len(),
                integers.as_mut_ptr(),
            )
        });
        reals.extend(integers.iter().map(|&k| f64::from(k)));
        (s_real.max(s_integer), reals)
    }

    /// The names of [`Instance::read_outputs`]'s values, in the same order.
    pub fn output_names(&self) -> Vec<&str> {
        let description = self.fmu.description();
        description
            .outputs(VarType::Real)
            .chain(description.outputs(VarType::Integer))
            .map(|v| v.name.as_str())
            .collect()
    }

    // -- directional derivatives

    /// `fmi2GetDirectionalDerivative` of the variables `unknowns` along the seed `seed` of the
    /// variables `knowns`, into `out` (one slot per unknown); `fmi2Error` without a call when
    /// the lengths do not match. Allocates nothing.
    pub fn directional_derivative_vr(
        &self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
        out: &mut [f64],
    ) -> Status {
        if knowns.len() != seed.len() || unknowns.len() != out.len() {
            return Status::Error;
        }
        // SAFETY: each array holds the count passed with it.
        Status::from(unsafe {
            (self.functions().fmi2GetDirectionalDerivative)(
                self.component,
                unknowns.as_ptr(),
                unknowns.len(),
                knowns.as_ptr(),
                knowns.len(),
                seed.as_ptr(),
                out.as_mut_ptr(),
            )
        })
    }

    /// [`Instance::directional_derivative_vr`] by variable names, the seed given per known
    /// variable as (name, seed value): the status and the derivatives (NaN unless the FMU wrote
    /// them).
    #[track_caller]
    pub fn directional_derivative(
        &self,
        unknowns: &[&str],
        knowns: &[(&str, f64)],
    ) -> (Status, Vec<f64>) {
        let unknown: Vec<u32> = unknowns.iter().map(|name| self.vr(name)).collect();
        let known: Vec<u32> = knowns.iter().map(|(name, _)| self.vr(name)).collect();
        let seed: Vec<f64> = knowns.iter().map(|&(_, x)| x).collect();
        let mut out = vec![f64::NAN; unknowns.len()];
        let s = self.directional_derivative_vr(&unknown, &known, &seed, &mut out);
        (s, out)
    }

    // -- FMU states

    /// `fmi2GetFMUstate`: a new state of this instance.
    pub fn get_state(&self) -> Result<FmuState<'_>, CallError> {
        let mut state: fmi2FMUstate = std::ptr::null_mut();
        // SAFETY: live instance; the slot is NULL, so the FMU allocates a new state.
        let s = unsafe { (self.functions().fmi2GetFMUstate)(self.component, &mut state) };
        self.check(Status::from(s), || "fmi2GetFMUstate".to_string())?;
        Ok(FmuState {
            instance: self,
            state,
        })
    }

    /// `fmi2SetFMUstate`.
    pub fn set_state(&self, state: &FmuState<'_>) -> Status {
        // SAFETY: a state this instance created and has not freed.
        Status::from(unsafe { (self.functions().fmi2SetFMUstate)(self.component, state.state) })
    }

    /// `fmi2SerializedFMUstateSize` and `fmi2SerializeFMUstate` of `state`.
    pub fn serialize(&self, state: &FmuState<'_>) -> Result<Vec<u8>, CallError> {
        let mut size = 0usize;
        // SAFETY: a live state, one slot.
        let s = unsafe {
            (self.functions().fmi2SerializedFMUstateSize)(self.component, state.state, &mut size)
        };
        self.check(Status::from(s), || "fmi2SerializedFMUstateSize".to_string())?;
        let mut bytes = vec![0 as fmi2Byte; size];
        // SAFETY: a buffer of `size` bytes.
        let s = unsafe {
            (self.functions().fmi2SerializeFMUstate)(
                self.component,
                state.state,
                bytes.as_mut_ptr(),
                size,
            )
        };
        self.check(Status::from(s), || "fmi2SerializeFMUstate".to_string())?;
        Ok(bytes.into_iter().map(|b| b as u8).collect())
    }

    /// `fmi2DeSerializeFMUstate` of `bytes`: the status, and the new state if the FMU returned
    /// one (a non-NULL pointer, whatever the status).
    pub fn deserialize(&self, bytes: &[u8]) -> (Status, Option<FmuState<'_>>) {
        let mut state: fmi2FMUstate = std::ptr::null_mut();
        // SAFETY: a buffer of bytes.len() bytes; the slot is NULL.
        let s = unsafe {
            (self.functions().fmi2DeSerializeFMUstate)(
                self.component,
                bytes.as_ptr().cast::<fmi2Byte>(),
                bytes.len(),
                &mut state,
            )
        };
        let state = (!state.is_null()).then_some(FmuState {
            instance: self,
            state,
        });
        (Status::from(s), state)
    }

    /// The current state, serialized: get, serialize, free.
    pub fn serialized_state(&self) -> Result<Vec<u8>, CallError> {
        let state = self.get_state()?;
        let bytes = self.serialize(&state)?;
        let (s, cleared) = state.free();
        self.check(s, || "fmi2FreeFMUstate".to_string())?;
        if !cleared {
            return Err(
                self.call_error("fmi2FreeFMUstate left the state pointer set".to_string(), s)
            );
        }
        Ok(bytes)
    }

    /// Deserializes `bytes` and sets the state; the first status that is not `fmi2OK`, else
    /// the worse of setting and freeing it.
    pub fn restore_serialized(&self, bytes: &[u8]) -> Status {
        let (s, state) = self.deserialize(bytes);
        if s != Status::Ok {
            return s;
        }
        let Some(state) = state else {
            return Status::Error;
        };
        let set = self.set_state(&state);
        set.max(state.free().0)
    }
}

impl Drop for Instance {
    fn drop(&mut self) {
        // SAFETY: freed exactly once; the sink is dropped after this.
        unsafe { (self.functions().fmi2FreeInstance)(self.component) };
    }
}

impl FmuState<'_> {
    /// `fmi2FreeFMUstate` now: the status, and whether the FMU set the pointer to NULL.
    pub fn free(mut self) -> (Status, bool) {
        let s = self.release();
        let cleared = self.state.is_null();
        // Released (or refused by the FMU): not again when dropped.
        std::mem::forget(self);
        (s, cleared)
    }

    fn release(&mut self) -> Status {
        if self.state.is_null() {
            return Status::Ok;
        }
        let instance = self.instance;
        // SAFETY: a state of this live instance, freed once (the pointer is NULL afterwards, or
        // the FMU failed to free it).
        let s =
            unsafe { (instance.functions().fmi2FreeFMUstate)(instance.component, &mut self.state) };
        Status::from(s)
    }
}

impl Drop for FmuState<'_> {
    fn drop(&mut self) {
        self.release();
    }
}
