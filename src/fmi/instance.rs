//! One FMU instance: the FMI 2.0 Co-Simulation state machine, value access checked against the
//! generated variable table, logging through the host's callback, and FMU states.
//!
//! This file knows nothing about contact mechanics; the C ABI in [`crate::fmi::export`] only
//! converts pointers to slices and calls the methods here.

use super::model::{Evaluation, InstanceContext, Model, ModelError, ModelInfo};
use super::variables::{ByteReader, Causality, Values, VarInfo, VarType, Variability};
use fmi_sys::fmi2::{
    fmi2CallbackLogger, fmi2ComponentEnvironment, fmi2Status, fmi2Status_fmi2Discard,
    fmi2Status_fmi2Error, fmi2Status_fmi2OK, fmi2Status_fmi2Warning,
};
use std::ffi::CString;

pub const OK: fmi2Status = fmi2Status_fmi2OK;
pub const WARNING: fmi2Status = fmi2Status_fmi2Warning;
pub const DISCARD: fmi2Status = fmi2Status_fmi2Discard;
pub const ERROR: fmi2Status = fmi2Status_fmi2Error;

/// States of the FMI 2.0 CS state machine (bit flags, as in modelica/Reference-FMUs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum State {
    Instantiated = 1,
    InitializationMode = 2,
    StepComplete = 4,
    StepFailed = 8,
    Terminated = 16,
    Error = 32,
}

impl State {
    fn from_code(c: u8) -> Option<Self> {
        [
            State::Instantiated,
            State::InitializationMode,
            State::StepComplete,
            State::StepFailed,
            State::Terminated,
            State::Error,
        ]
        .into_iter()
        .find(|s| *s as u8 == c)
    }
}

/// Allowed-state masks per function.
pub mod mask {
    use super::State::*;
    const ANY_BUT_FATAL: u8 = Instantiated as u8
        | InitializationMode as u8
        | StepComplete as u8
        | StepFailed as u8
        | Terminated as u8
        | Error as u8;
    pub const FREE_INSTANCE: u8 = ANY_BUT_FATAL;
    pub const RESET: u8 = ANY_BUT_FATAL;
    pub const SET_DEBUG_LOGGING: u8 = ANY_BUT_FATAL;
    pub const SETUP_EXPERIMENT: u8 = Instantiated as u8;
    pub const ENTER_INITIALIZATION_MODE: u8 = Instantiated as u8;
    pub const EXIT_INITIALIZATION_MODE: u8 = InitializationMode as u8;
    pub const TERMINATE: u8 = StepComplete as u8 | StepFailed as u8;
    pub const GET: u8 = InitializationMode as u8
        | StepComplete as u8
        | StepFailed as u8
        | Terminated as u8
        | Error as u8;
    pub const SET: u8 = Instantiated as u8 | InitializationMode as u8 | StepComplete as u8;
    pub const FMU_STATE: u8 = ANY_BUT_FATAL;
    pub const DO_STEP: u8 = StepComplete as u8;
    /// At the inputs of initialization or between steps (the model's history is that of the
    /// last step).
    pub const DIRECTIONAL_DERIVATIVE: u8 = InitializationMode as u8 | StepComplete as u8;
    pub const STATUS: u8 = StepComplete as u8 | StepFailed as u8 | Terminated as u8;
    pub const UNSUPPORTED: u8 = ANY_BUT_FATAL;
}

/// The host's logger, copied at instantiation.
pub struct Logger {
    callback: fmi2CallbackLogger,
    environment: fmi2ComponentEnvironment,
    instance_name: CString,
    /// Debug/info output is gated on this; errors and warnings are always reported.
    pub logging_on: bool,
}

// SAFETY: the environment pointer is only handed back to the host's own callback, never
// dereferenced here; FMI allows an instance to be used from another thread, one call at a time.
unsafe impl Send for Logger {}

impl Logger {
    pub fn new(
        callback: fmi2CallbackLogger,
        environment: fmi2ComponentEnvironment,
        instance_name: &str,
        logging_on: bool,
    ) -> Self {
        Self {
            callback,
            environment,
            instance_name: to_cstring(instance_name),
            logging_on,
        }
    }

    /// Sends `message` to the host with the `"%s"` format (never the message as the format).
    pub fn log(&self, status: fmi2Status, message: &str) {
        let category: &std::ffi::CStr = match status {
            s if s >= ERROR => c"logStatusError",
            s if s == WARNING || s == DISCARD => c"logStatusWarning",
            _ => c"logAll",
        };
        if status == OK && !self.logging_on {
            return;
        }
        if let Some(cb) = self.callback {
            let msg = to_cstring(message);
            // SAFETY: the host's printf-style logger gets valid NUL-terminated strings and
            // exactly one vararg for the single `%s`.
            unsafe {
                cb(
                    self.environment,
                    self.instance_name.as_ptr(),
                    status,
                    category.as_ptr(),
                    c"%s".as_ptr(),
                    msg.as_ptr(),
                );
            }
        }
    }
}

fn to_cstring(s: &str) -> CString {
    CString::new(s.replace('\0', "?")).expect("NULs replaced")
}

/// Header of a serialized FMU state (version 2: with a trailing checksum).
const STATE_MAGIC: &[u8; 8] = b"RCFMUST2";
/// Length of the trailing checksum of a serialized FMU state.
const CHECKSUM_BYTES: usize = 8;

/// FNV-1a (64 bit) of `bytes`: the checksum that ends a serialized FMU state. Any change of a
/// single byte changes it (each step is a bijection of the running hash), so a flipped byte is
/// always detected; other corruptions with probability 1 − 2⁻⁶⁴.
fn checksum(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// Tolerance for comparing communication points (docs/integration.md, "Communication points and
/// step sizes").
const TIME_TOLERANCE: f64 = 1e-9;

/// One instance of a model.
pub struct Instance {
    pub info: &'static ModelInfo,
    pub name: String,
    pub logger: Logger,
    context: InstanceContext,
    model: Box<dyn Model>,
    values: Values,
    pub state: State,
    time: f64,
    stop_time: Option<f64>,
    /// Parameters changed since the model was last initialized.
    needs_initialize: bool,
    /// Inputs or parameters changed since the outputs were last evaluated.
    dirty: bool,
    /// The model discarded a step: the simulation cannot continue (answered by GetStatus).
    terminated_by_model: bool,
    last_successful_time: f64,
    /// Strings handed out by the last `fmi2GetString`, valid until the next call.
    string_cache: Vec<CString>,
    /// Scratch values of directional derivatives (made at the first call).
    probe_values: Option<Values>,
}

impl Instance {
    pub fn new(
        info: &'static ModelInfo,
        name: &str,
        context: InstanceContext,
        logger: Logger,
    ) -> Self {
        Self {
            info,
            name: name.to_string(),
            logger,
            model: (info.create)(&context),
            context,
            values: Values::from_start(info.variables, info.counts),
            state: State::Instantiated,
            time: 0.0,
            stop_time: None,
            needs_initialize: true,
            dirty: true,
            terminated_by_model: false,
            last_successful_time: 0.0,
            string_cache: Vec::new(),
            probe_values: None,
        }
    }

    /// Logs an error and returns `fmi2Error`.
    pub fn error(&self, message: &str) -> fmi2Status {
        self.logger.log(ERROR, message);
        ERROR
    }

    /// Checks that `function` may be called in the current state.
    pub fn allowed(&self, function: &str, mask: u8) -> bool {
        if self.state as u8 & mask != 0 {
            return true;
        }
        self.error(&format!(
            "{function} must not be called in state {:?}",
            self.state
        ));
        false
    }

    pub fn values(&self) -> &Values {
        &self.values
    }

    pub fn time(&self) -> f64 {
        self.time
    }

    fn variable(&self, vr: u32, ty: VarType) -> Result<&'static VarInfo, String> {
        match self.info.variables.get(vr as usize) {
            Some(v) if v.ty == ty => Ok(v),
            Some(v) => Err(format!(
                "value reference {vr} is {} ({:?}), not a {ty:?}",
                v.name, v.ty
            )),
            None => Err(format!(
                "unknown value reference {vr} ({} has {} variables)",
                self.info.model_identifier,
                self.info.variables.len()
            )),
        }
    }

    /// Brings outputs up to date before they are read. A warning is returned once, by the call
    /// that evaluated.
    fn refresh(&mut self) -> Result<Evaluation, ModelError> {
        if self.needs_initialize {
            self.model.initialize(&self.values)?;
            self.needs_initialize = false;
            self.dirty = true;
        }
        let mut outcome = Evaluation::Ok;
        if self.dirty {
            outcome = self.model.evaluate(&mut self.values, self.time)?;
            self.dirty = false;
        }
        Ok(outcome)
    }

    /// Logs a model warning (`during`: the function or step) and returns `fmi2Warning`; `OK`
    /// for [`Evaluation::Ok`].
    fn report(&self, outcome: Evaluation, during: &str) -> fmi2Status {
        match outcome {
            Evaluation::Ok => OK,
            Evaluation::Warning(m) => {
                self.logger.log(WARNING, &format!("{during}: {m}"));
                WARNING
            }
        }
    }

    /// Evaluates the outputs if `vrs` reads one and they are out of date: `Ok(OK)`, `Ok(WARNING)`
    /// (outputs valid, warning logged), or `Err(status)` (failed, nothing to read).
    fn refresh_for_get(&mut self, vrs: &[u32]) -> Result<fmi2Status, fmi2Status> {
        let reads_output = vrs.iter().any(|&vr| {
            self.info
                .variables
                .get(vr as usize)
                .is_some_and(|v| v.causality == Causality::Output)
        });
        // After a failed or final step the outputs keep their last good values: the inputs that
        // failed are not evaluated again.
        let settled = matches!(
            self.state,
            State::StepFailed | State::Terminated | State::Error
        );
        if !reads_output || settled {
            return Ok(OK);
        }
        match self.refresh() {
            Ok(outcome) => Ok(self.report(outcome, "fmi2Get")),
            Err(e) => Err(self.model_failure(e, "fmi2Get")),
        }
    }

    fn model_failure(&mut self, e: ModelError, during: &str) -> fmi2Status {
        match e {
            ModelError::Error(m) => self.error(&format!("{during}: {m}")),
            ModelError::Discard(m) => {
                self.logger.log(DISCARD, &format!("{during}: {m}"));
                DISCARD
            }
        }
    }

    /// Reads values of one type through `read`, after refreshing outputs.
    pub fn get<T>(
        &mut self,
        ty: VarType,
        vrs: &[u32],
        out: &mut [T],
        read: impl Fn(&Values, usize) -> T,
    ) -> fmi2Status {
        let status = match self.refresh_for_get(vrs) {
            Ok(status) => status,
            Err(status) => return status,
        };
        for (&vr, slot) in vrs.iter().zip(out.iter_mut()) {
            match self.variable(vr, ty) {
                Ok(v) => *slot = read(&self.values, v.slot),
                Err(m) => return self.error(&m),
            }
        }
        status
    }

    /// Strings for `fmi2GetString`: pointers stay valid until the next call.
    pub fn get_strings(&mut self, vrs: &[u32]) -> Result<&[CString], fmi2Status> {
        self.string_cache.clear();
        for &vr in vrs {
            match self.variable(vr, VarType::String) {
                Ok(v) => self
                    .string_cache
                    .push(to_cstring(&self.values.strings[v.slot])),
                Err(m) => return Err(self.error(&m)),
            }
        }
        Ok(&self.string_cache)
    }

    /// Checks that `v` may be set now.
    fn settable(&self, v: &VarInfo) -> Result<(), String> {
        let ok = match (v.causality, v.variability, self.state) {
            (Causality::Output, _, _) => false,
            (Causality::Input, _, _) => true,
            (Causality::Parameter, Variability::Tunable, _) => true,
            (Causality::Parameter, _, s) => {
                matches!(s, State::Instantiated | State::InitializationMode)
            }
        };
        if ok {
            Ok(())
        } else {
            Err(format!(
                "{} ({:?}, {:?}) cannot be set in state {:?}",
                v.name, v.causality, v.variability, self.state
            ))
        }
    }

    /// Sets values of one type. Each value is checked against the table (type, settable now,
    /// range); if any is rejected, the call returns `fmi2Error` with a message naming it and
    /// no value changes.
    pub fn set<T: Copy + std::fmt::Display>(
        &mut self,
        ty: VarType,
        vrs: &[u32],
        values: &[T],
        accepts: impl Fn(&VarInfo, T) -> bool,
        mut write: impl FnMut(&mut Values, usize, T),
    ) -> fmi2Status {
        // Every value is checked before any is written: a rejected call changes nothing.
        for (&vr, &x) in vrs.iter().zip(values) {
            let v = match self.variable(vr, ty) {
                Ok(v) => v,
                Err(m) => return self.error(&m),
            };
            if let Err(m) = self.settable(v) {
                return self.error(&m);
            }
            if !accepts(v, x) {
                return self.error(&format!(
                    "{} = {x} is outside the allowed range {}{}",
                    v.name,
                    v.allowed,
                    if v.unit.is_empty() {
                        String::new()
                    } else {
                        format!(" [{}]", v.unit)
                    }
                ));
            }
        }
        for (&vr, &x) in vrs.iter().zip(values) {
            let Some(v) = self.info.variables.get(vr as usize) else {
                continue; // unreachable: checked above
            };
            write(&mut self.values, v.slot, x);
            if v.causality == Causality::Parameter {
                self.needs_initialize = true;
            }
            self.dirty = true;
        }
        OK
    }

    /// `fmi2GetDirectionalDerivative`: `out[j]` = Σ_i ∂unknowns[j]/∂knowns[i] · seed[i] at the
    /// current inputs, by [`super::derivative`]. Unknowns must be Real outputs, knowns continuous
    /// Real inputs. Neither the values nor the model's history change: the next step gives the
    /// same outputs as without this call.
    pub fn directional_derivative(
        &mut self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
        out: &mut [f64],
    ) -> fmi2Status {
        const F: &str = "fmi2GetDirectionalDerivative";
        if !self.info.provides_directional_derivative {
            return self.error(&format!(
                "{F} is not supported by {} (providesDirectionalDerivative=\"false\")",
                self.info.model_identifier
            ));
        }
        for &vr in unknowns {
            match self.variable(vr, VarType::Real) {
                Ok(v) if v.causality == Causality::Output => {}
                Ok(v) => return self.error(&format!("{F}: unknown {} is not an output", v.name)),
                Err(m) => return self.error(&format!("{F}: {m}")),
            }
        }
        for (&vr, &x) in knowns.iter().zip(seed) {
            match self.variable(vr, VarType::Real) {
                Ok(v)
                    if v.causality == Causality::Input
                        && v.variability == Variability::Continuous =>
                {
                    if !x.is_finite() {
                        return self.error(&format!("{F}: seed of {} = {x} is not finite", v.name));
                    }
                }
                Ok(v) => {
                    return self.error(&format!("{F}: known {} is not a continuous input", v.name))
                }
                Err(m) => return self.error(&format!("{F}: {m}")),
            }
        }
        if self.needs_initialize {
            if let Err(e) = self.model.initialize(&self.values) {
                return self.model_failure(e, F);
            }
            self.needs_initialize = false;
            self.dirty = true;
        }
        let scratch = self.probe_values.get_or_insert_with(|| self.values.clone());
        let variables = self.info.variables;
        let result = super::derivative::directional_derivative(
            self.model.as_mut(),
            &self.values,
            scratch,
            knowns
                .iter()
                .zip(seed)
                .map(|(&vr, &x)| (&variables[vr as usize], x)),
            unknowns.iter().map(|&vr| &variables[vr as usize]),
            out,
        );
        match result {
            Ok(()) => OK,
            Err(e) => self.model_failure(e, F),
        }
    }

    pub fn setup_experiment(&mut self, start_time: f64, stop_time: Option<f64>) -> fmi2Status {
        if !start_time.is_finite() {
            return self.error(&format!("startTime = {start_time} must be finite"));
        }
        if let Some(stop) = stop_time {
            if !(stop.is_finite() && stop >= start_time) {
                return self.error(&format!(
                    "stopTime = {stop} must be finite and >= startTime = {start_time}"
                ));
            }
        }
        self.time = start_time;
        self.last_successful_time = start_time;
        self.stop_time = stop_time;
        OK
    }

    pub fn enter_initialization_mode(&mut self) -> fmi2Status {
        self.state = State::InitializationMode;
        OK
    }

    pub fn exit_initialization_mode(&mut self) -> fmi2Status {
        self.needs_initialize = true;
        self.dirty = true;
        match self.refresh() {
            Ok(outcome) => {
                self.state = State::StepComplete;
                self.report(outcome, "fmi2ExitInitializationMode")
            }
            Err(e) => {
                let message = format!("initialization failed: {}", e.message());
                self.error(&message)
            }
        }
    }

    pub fn do_step(&mut self, current: f64, step: f64) -> fmi2Status {
        if !(step.is_finite() && step > 0.0) {
            return self.error(&format!(
                "communicationStepSize = {step} must be finite and > 0"
            ));
        }
        if !(current.is_finite() && (current + step).is_finite()) {
            return self.error(&format!(
                "currentCommunicationPoint = {current} and communicationStepSize = {step} must \
                 give a finite time"
            ));
        }
        let mut status = OK;
        if (current - self.time).abs() > TIME_TOLERANCE * (1.0 + self.time.abs()) {
            self.logger.log(
                WARNING,
                &format!(
                    "currentCommunicationPoint = {current} differs from the instance time {}",
                    self.time
                ),
            );
            status = WARNING;
        }
        let end = current + step;
        if let Some(stop) = self.stop_time {
            if end > stop + TIME_TOLERANCE * (1.0 + stop.abs()) {
                return self.error(&format!("step to t = {end} goes past stopTime = {stop}"));
            }
        }
        self.dirty = true;
        let stepped = self
            .refresh()
            .and_then(|outcome| self.model.advance(&mut self.values, step).map(|()| outcome));
        match stepped {
            Ok(outcome) => {
                self.time = end;
                self.last_successful_time = end;
                if let Evaluation::Warning(m) = outcome {
                    self.logger
                        .log(WARNING, &format!("step at t = {current}: {m}"));
                    status = WARNING;
                }
                status
            }
            Err(ModelError::Discard(m)) => {
                self.logger.log(
                    DISCARD,
                    &format!("step at t = {current} discarded, simulation cannot continue: {m}"),
                );
                self.terminated_by_model = true;
                self.state = State::StepFailed;
                DISCARD
            }
            Err(ModelError::Error(m)) => {
                self.state = State::Error;
                self.error(&format!("step at t = {current} failed: {m}"))
            }
        }
    }

    pub fn terminate(&mut self) -> fmi2Status {
        let initialized = !self.needs_initialize;
        self.state = State::Terminated;
        if !initialized {
            return OK;
        }
        match self.model.terminate(&self.values) {
            Ok(()) => OK,
            Err(e) => self.error(&format!("fmi2Terminate: {}", e.message())),
        }
    }

    /// Back to the freshly instantiated state, start values restored.
    pub fn reset(&mut self) -> fmi2Status {
        self.model = (self.info.create)(&self.context);
        self.values = Values::from_start(self.info.variables, self.info.counts);
        self.state = State::Instantiated;
        self.time = 0.0;
        self.stop_time = None;
        self.needs_initialize = true;
        self.dirty = true;
        self.terminated_by_model = false;
        self.last_successful_time = 0.0;
        OK
    }

    pub fn terminated(&self) -> bool {
        self.terminated_by_model
    }

    pub fn last_successful_time(&self) -> f64 {
        self.last_successful_time
    }

    /// Serializes the complete mutable state: header (magic, GUID), state-machine data, all
    /// values, and the model's own state (warm starts). No pointers; little-endian.
    pub fn save_state(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(64 + 8 * self.values.reals.len());
        out.extend_from_slice(STATE_MAGIC);
        let guid = self.info.guid.as_bytes();
        out.extend_from_slice(&(guid.len() as u64).to_le_bytes());
        out.extend_from_slice(guid);
        out.push(self.state as u8);
        for x in [
            self.time,
            self.stop_time.unwrap_or(f64::NAN),
            self.last_successful_time,
        ] {
            out.extend_from_slice(&x.to_bits().to_le_bytes());
        }
        out.push(u8::from(self.stop_time.is_some()));
        out.push(u8::from(self.needs_initialize));
        out.push(u8::from(self.dirty));
        out.push(u8::from(self.terminated_by_model));
        self.values.write_bytes(&mut out);
        let mut model = Vec::new();
        self.model.save_state(&mut model);
        out.extend_from_slice(&(model.len() as u64).to_le_bytes());
        out.extend_from_slice(&model);
        let sum = checksum(&out);
        out.extend_from_slice(&sum.to_le_bytes());
        out
    }

    /// Checks a serialized state fully before anything of it is applied.
    pub fn validate_state(&self, bytes: &[u8]) -> Result<(), String> {
        self.parse_state(bytes).map(|_| ())
    }

    fn parse_state<'a>(&self, bytes: &'a [u8]) -> Result<ParsedState<'a>, String> {
        if !bytes.starts_with(STATE_MAGIC) {
            return Err(format!(
                "not a railcontact FMU state of this version (the first {} bytes are not {:?})",
                STATE_MAGIC.len(),
                String::from_utf8_lossy(STATE_MAGIC)
            ));
        }
        if bytes.len() < STATE_MAGIC.len() + CHECKSUM_BYTES {
            return Err(format!("serialized state truncated: {} bytes", bytes.len()));
        }
        let (body, sum) = bytes.split_at(bytes.len() - CHECKSUM_BYTES);
        let mut stored = [0u8; CHECKSUM_BYTES];
        stored.copy_from_slice(sum);
        if u64::from_le_bytes(stored) != checksum(body) {
            return Err(format!(
                "FMU state corrupt: checksum mismatch over its {} bytes (truncated, extended or \
                 altered)",
                bytes.len()
            ));
        }
        let mut r = ByteReader::new(body);
        r.take(STATE_MAGIC.len())?;
        let guid = r.string()?;
        if guid != self.info.guid {
            return Err(format!(
                "FMU state belongs to GUID {guid}, this instance is {}",
                self.info.guid
            ));
        }
        let state = State::from_code(r.u8()?).ok_or("FMU state corrupt: state code")?;
        let time = r.f64()?;
        let stop = r.f64()?;
        let last_successful_time = r.f64()?;
        let has_stop = r.bool()?;
        let needs_initialize = r.bool()?;
        let dirty = r.bool()?;
        let terminated_by_model = r.bool()?;
        if ![time, last_successful_time].iter().all(|t| t.is_finite())
            || (has_stop && !stop.is_finite())
        {
            return Err("FMU state corrupt: non-finite time".into());
        }
        let values = Values::read_bytes(self.info.counts, &mut r)?;
        for v in self.info.variables {
            let ok = match (v.ty, v.causality) {
                (VarType::Real, Causality::Output) => values.reals[v.slot].is_finite(),
                (VarType::Real, _) => v.accepts_real(values.reals[v.slot]),
                (VarType::Integer, _) => v.accepts_integer(values.integers[v.slot]),
                (VarType::Boolean | VarType::String, _) => true,
            };
            if !ok {
                return Err(format!("FMU state corrupt: {} out of range", v.name));
            }
        }
        let n = usize::try_from(r.u64()?).map_err(|_| "FMU state corrupt: length")?;
        let model = r.take(n)?;
        if !r.is_empty() {
            return Err(format!("FMU state has {} trailing bytes", r.remaining()));
        }
        Ok(ParsedState {
            state,
            time,
            stop_time: has_stop.then_some(stop),
            last_successful_time,
            needs_initialize,
            dirty,
            terminated_by_model,
            values,
            model,
        })
    }

    /// Restores a state written by [`Instance::save_state`]; on error nothing changes.
    pub fn restore_state(&mut self, bytes: &[u8]) -> Result<(), String> {
        let p = self.parse_state(bytes)?;
        let mut model = (self.info.create)(&self.context);
        let initialized = !p.needs_initialize;
        if initialized {
            model
                .initialize(&p.values)
                .map_err(|e| format!("restoring FMU state: {}", e.message()))?;
        }
        model.restore_state(p.model)?;
        self.model = model;
        self.values = p.values;
        self.state = p.state;
        self.time = p.time;
        self.stop_time = p.stop_time;
        self.last_successful_time = p.last_successful_time;
        self.needs_initialize = p.needs_initialize;
        self.dirty = p.dirty;
        self.terminated_by_model = p.terminated_by_model;
        Ok(())
    }
}

struct ParsedState<'a> {
    state: State,
    time: f64,
    stop_time: Option<f64>,
    last_successful_time: f64,
    needs_initialize: bool,
    dirty: bool,
    terminated_by_model: bool,
    values: Values,
    model: &'a [u8],
}
