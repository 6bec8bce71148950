//! Shared driver of the reliability and soak tests (`tests/reliability.rs`, `tests/soak.rs`): one
//! FMU instance driven through the crate's exported `fmi2*` functions — the same C ABI a host
//! resolves from the packed shared library — with the log captured per instance name, and a
//! seeded random walk of the `WheelRailContact` inputs.
//!
//! No `unwrap` across the C boundary: every call returns its `fmi2Status` to the test, which
//! asserts it.

#![allow(dead_code)] // each test crate uses a different part of the driver

use fmi_sys::fmi2::*;
use railcontact::fmi::export::*;
use railcontact::fmi::model::ModelInfo;
use railcontact::fmi::variables::{Causality, VarInfo, VarType};
use std::ffi::{CStr, CString};
use std::sync::Mutex;

pub use fmi_sys::fmi2::{
    fmi2Status_fmi2Discard as DISCARD, fmi2Status_fmi2Error as ERROR, fmi2Status_fmi2OK as OK,
    fmi2Status_fmi2Warning as WARNING,
};

/// One captured log message: the status it was logged with and its text.
#[derive(Debug, Clone, PartialEq)]
pub struct Message {
    pub status: fmi2Status,
    pub text: String,
}

/// Log messages, routed by fmi-sys's variadic C logger through the `log` crate, tagged with the
/// instance name (its `target`) so that parallel tests can tell theirs apart.
struct Capture(Mutex<Vec<(String, Message)>>);

impl log::Log for Capture {
    fn enabled(&self, _: &log::Metadata<'_>) -> bool {
        true
    }
    fn log(&self, r: &log::Record<'_>) {
        // fmi-sys maps Error and Fatal to Error, Warning to Warn, Discard to Trace, OK to Info.
        let status = match r.level() {
            log::Level::Error => ERROR,
            log::Level::Warn => WARNING,
            log::Level::Trace => DISCARD,
            _ => OK,
        };
        let message = Message {
            status,
            text: r.args().to_string(),
        };
        self.0
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push((r.target().to_string(), message));
    }
    fn flush(&self) {}
}

static CAPTURE: Capture = Capture(Mutex::new(Vec::new()));

/// The messages logged so far by the instance `name`.
pub fn messages_of(name: &str) -> Vec<Message> {
    CAPTURE
        .0
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .iter()
        .filter(|(t, _)| t == name)
        .map(|(_, m)| m.clone())
        .collect()
}

/// Forgets the messages of instance `name` (long runs).
pub fn clear_messages_of(name: &str) {
    CAPTURE
        .0
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .retain(|(t, _)| t != name);
}

fn install_logger() {
    let _ = log::set_logger(&CAPTURE).map(|()| log::set_max_level(log::LevelFilter::Trace));
}

/// The variable `name` of `info`; panics in the test (never in the FMU) if it does not exist.
pub fn var(info: &ModelInfo, name: &str) -> &'static VarInfo {
    info.variable(name)
        .unwrap_or_else(|| panic!("{} has no variable {name}", info.model_identifier))
}

/// An instance driven through the C ABI.
pub struct Fmu {
    pub c: fmi2Component,
    pub info: &'static ModelInfo,
    pub name: String,
    /// Value references of the Real outputs, in table order.
    real_outputs: Vec<u32>,
    /// Value references of the Integer outputs, in table order.
    integer_outputs: Vec<u32>,
    /// Whether `fmi2FreeInstance` is still due (tests of double freeing clear it).
    pub owned: bool,
}

// SAFETY: an FMU instance may be used from another thread, one call at a time (FMI 2.0); the
// tests move each instance into one thread.
unsafe impl Send for Fmu {}

impl Fmu {
    /// Instantiates `info` as `name` (resources: a nonexistent `file:` directory), or panics.
    pub fn new(info: &'static ModelInfo, name: &str) -> Self {
        Self::try_new(info, name, info.guid, Some("file:///nonexistent/resources"))
            .unwrap_or_else(|| panic!("fmi2Instantiate({name}) returned NULL"))
    }

    /// `fmi2Instantiate` with the given GUID and resource location; `None` if it returns NULL.
    pub fn try_new(
        info: &'static ModelInfo,
        name: &str,
        guid: &str,
        resources: Option<&str>,
    ) -> Option<Self> {
        install_logger();
        let callbacks = fmi2CallbackFunctions {
            logger: Some(fmi_sys::fmi2::logger::callback_logger_handler),
            allocateMemory: None,
            freeMemory: None,
            stepFinished: None,
            componentEnvironment: std::ptr::null_mut(),
        };
        let cname = CString::new(name).ok()?;
        let cguid = CString::new(guid).ok()?;
        let curi = resources.map(CString::new).transpose().ok()?;
        // SAFETY: valid NUL-terminated strings and callbacks for the call's duration (the FMU
        // copies what it keeps).
        let c = unsafe {
            fmi2Instantiate(
                cname.as_ptr(),
                fmi2Type_fmi2CoSimulation,
                cguid.as_ptr(),
                curi.as_ref().map_or(std::ptr::null(), |u| u.as_ptr()),
                &callbacks,
                0,
                0,
            )
        };
        if c.is_null() {
            return None;
        }
        let outputs = |ty| {
            info.variables
                .iter()
                .filter(|v| v.causality == Causality::Output && v.ty == ty)
                .map(|v| v.vr)
                .collect()
        };
        Some(Self {
            c,
            info,
            name: name.to_string(),
            real_outputs: outputs(VarType::Real),
            integer_outputs: outputs(VarType::Integer),
            owned: true,
        })
    }

    pub fn messages(&self) -> Vec<Message> {
        messages_of(&self.name)
    }

    /// Messages logged with `fmi2Error` (or worse).
    pub fn errors(&self) -> Vec<String> {
        self.messages()
            .into_iter()
            .filter(|m| m.status >= ERROR)
            .map(|m| m.text)
            .collect()
    }

    /// Messages logged with `fmi2Warning`.
    pub fn warnings(&self) -> Vec<String> {
        self.messages()
            .into_iter()
            .filter(|m| m.status == WARNING)
            .map(|m| m.text)
            .collect()
    }

    /// Asserts that some warning contains every one of `parts`.
    #[track_caller]
    pub fn assert_warning_logged(&self, parts: &[&str]) {
        let warnings = self.warnings();
        assert!(
            warnings.iter().any(|m| parts.iter().all(|p| m.contains(p))),
            "{}: no warning containing all of {parts:?}; warnings: {warnings:#?}",
            self.name
        );
    }

    /// Asserts that some error message contains every one of `parts`.
    #[track_caller]
    pub fn assert_error_logged(&self, parts: &[&str]) {
        let errors = self.errors();
        assert!(
            errors.iter().any(|m| parts.iter().all(|p| m.contains(p))),
            "{}: no error message containing all of {parts:?}; errors: {errors:#?}",
            self.name
        );
    }

    pub fn vr(&self, name: &str) -> u32 {
        var(self.info, name).vr
    }

    pub fn set_real(&self, name: &str, x: f64) -> fmi2Status {
        self.set_real_vr(self.vr(name), x)
    }

    pub fn set_real_vr(&self, vr: u32, x: f64) -> fmi2Status {
        // SAFETY: one value reference, one value.
        unsafe { fmi2SetReal(self.c, &vr, 1, &x) }
    }

    /// Sets several Real variables in one call.
    pub fn set_reals(&self, vrs: &[u32], xs: &[f64]) -> fmi2Status {
        assert_eq!(vrs.len(), xs.len());
        // SAFETY: both arrays hold vrs.len() elements.
        unsafe { fmi2SetReal(self.c, vrs.as_ptr(), vrs.len(), xs.as_ptr()) }
    }

    pub fn set_integer(&self, name: &str, k: i32) -> fmi2Status {
        let vr = self.vr(name);
        // SAFETY: one value reference, one value.
        unsafe { fmi2SetInteger(self.c, &vr, 1, &k) }
    }

    pub fn set_boolean(&self, name: &str, b: bool) -> fmi2Status {
        let vr = self.vr(name);
        let v = fmi2Boolean::from(b);
        // SAFETY: one value reference, one value.
        unsafe { fmi2SetBoolean(self.c, &vr, 1, &v) }
    }

    pub fn set_string(&self, name: &str, s: &str) -> fmi2Status {
        let vr = self.vr(name);
        let Ok(cs) = CString::new(s) else {
            return ERROR;
        };
        let p = cs.as_ptr();
        // SAFETY: one value reference, one NUL-terminated string alive for the call.
        unsafe { fmi2SetString(self.c, &vr, 1, &p) }
    }

    /// `fmi2GetReal` of one variable: (status, value; NaN if the call failed).
    pub fn get_real_vr(&self, vr: u32) -> (fmi2Status, f64) {
        let mut x = f64::NAN;
        // SAFETY: one value reference, one slot.
        let s = unsafe { fmi2GetReal(self.c, &vr, 1, &mut x) };
        (s, x)
    }

    /// The value of a Real variable; asserts that `fmi2GetReal` returns OK.
    #[track_caller]
    pub fn real(&self, name: &str) -> f64 {
        let (s, x) = self.get_real_vr(self.vr(name));
        assert_eq!(
            s,
            OK,
            "{}: fmi2GetReal({name}): {:?}",
            self.name,
            self.errors()
        );
        x
    }

    /// The value of an Integer variable; asserts that `fmi2GetInteger` returns OK.
    #[track_caller]
    pub fn integer(&self, name: &str) -> i32 {
        let vr = self.vr(name);
        let mut k = i32::MIN;
        // SAFETY: one value reference, one slot.
        let s = unsafe { fmi2GetInteger(self.c, &vr, 1, &mut k) };
        assert_eq!(s, OK, "{}: fmi2GetInteger({name})", self.name);
        k
    }

    /// The value of a String variable (`None` if `fmi2GetString` fails).
    pub fn string(&self, name: &str) -> Option<String> {
        let vr = self.vr(name);
        let mut p: fmi2String = std::ptr::null();
        // SAFETY: one value reference, one slot.
        let s = unsafe { fmi2GetString(self.c, &vr, 1, &mut p) };
        if s != OK || p.is_null() {
            return None;
        }
        // SAFETY: valid until the next fmi2GetString call on this instance.
        Some(unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned())
    }

    /// All outputs in one `fmi2GetReal` and one `fmi2GetInteger` call: Real outputs in table
    /// order, then the Integer outputs as f64. Returns the worse of the two statuses.
    pub fn try_outputs(&self) -> (fmi2Status, Vec<f64>) {
        let mut reals = vec![f64::NAN; self.real_outputs.len()];
        let mut ints = vec![i32::MIN; self.integer_outputs.len()];
        // SAFETY: arrays of matching lengths.
        let s1 = unsafe {
            fmi2GetReal(
                self.c,
                self.real_outputs.as_ptr(),
                reals.len(),
                reals.as_mut_ptr(),
            )
        };
        // SAFETY: arrays of matching lengths.
        let s2 = unsafe {
            fmi2GetInteger(
                self.c,
                self.integer_outputs.as_ptr(),
                ints.len(),
                ints.as_mut_ptr(),
            )
        };
        reals.extend(ints.iter().map(|&k| f64::from(k)));
        (s1.max(s2), reals)
    }

    /// All outputs; asserts OK and that every value is finite.
    #[track_caller]
    pub fn outputs(&self) -> Vec<f64> {
        let (s, out) = self.try_outputs();
        assert_eq!(
            s,
            OK,
            "{}: reading the outputs: {:?}",
            self.name,
            self.errors()
        );
        self.assert_finite(&out);
        out
    }

    /// Asserts that every output value is finite, naming the first that is not.
    #[track_caller]
    pub fn assert_finite(&self, out: &[f64]) {
        if let Some(i) = out.iter().position(|x| !x.is_finite()) {
            let names: Vec<&str> =
                self.info
                    .variables
                    .iter()
                    .filter(|v| v.causality == Causality::Output && v.ty == VarType::Real)
                    .chain(
                        self.info.variables.iter().filter(|v| {
                            v.causality == Causality::Output && v.ty == VarType::Integer
                        }),
                    )
                    .map(|v| v.name)
                    .collect();
            panic!("{}: output {} = {}", self.name, names[i], out[i]);
        }
    }

    pub fn setup(&self, stop: Option<f64>) -> fmi2Status {
        // SAFETY: live instance.
        unsafe {
            fmi2SetupExperiment(
                self.c,
                0,
                0.0,
                0.0,
                fmi2Boolean::from(stop.is_some()),
                stop.unwrap_or(0.0),
            )
        }
    }

    pub fn enter(&self) -> fmi2Status {
        // SAFETY: live instance.
        unsafe { fmi2EnterInitializationMode(self.c) }
    }

    pub fn exit(&self) -> fmi2Status {
        // SAFETY: live instance.
        unsafe { fmi2ExitInitializationMode(self.c) }
    }

    /// Setup, enter and exit initialization mode; returns the first status that is not OK.
    pub fn try_init(&self) -> fmi2Status {
        for s in [self.setup(None), self.enter(), self.exit()] {
            if s != OK {
                return s;
            }
        }
        OK
    }

    #[track_caller]
    pub fn init(&self) {
        let s = self.try_init();
        assert_eq!(s, OK, "{}: initialization: {:?}", self.name, self.errors());
    }

    pub fn step(&self, t: f64, h: f64) -> fmi2Status {
        // SAFETY: live instance.
        unsafe { fmi2DoStep(self.c, t, h, 1) }
    }

    pub fn terminate(&self) -> fmi2Status {
        // SAFETY: live instance.
        unsafe { fmi2Terminate(self.c) }
    }

    pub fn reset(&self) -> fmi2Status {
        // SAFETY: live instance.
        unsafe { fmi2Reset(self.c) }
    }

    /// (status, Terminated) from `fmi2GetBooleanStatus(fmi2Terminated)`.
    pub fn terminated(&self) -> (fmi2Status, bool) {
        let mut b: fmi2Boolean = 0;
        // SAFETY: live instance, one slot.
        let s = unsafe { fmi2GetBooleanStatus(self.c, fmi2StatusKind_fmi2Terminated, &mut b) };
        (s, b != 0)
    }

    /// (status, time) from `fmi2GetRealStatus(fmi2LastSuccessfulTime)`.
    pub fn last_successful_time(&self) -> (fmi2Status, f64) {
        let mut t = f64::NAN;
        // SAFETY: live instance, one slot.
        let s = unsafe { fmi2GetRealStatus(self.c, fmi2StatusKind_fmi2LastSuccessfulTime, &mut t) };
        (s, t)
    }

    /// `fmi2GetDirectionalDerivative` of the outputs `unknowns` along the seed `knowns` (input,
    /// seed): the status and the derivatives (NaN where the call failed).
    pub fn directional_derivative(
        &self,
        unknowns: &[&str],
        knowns: &[(&str, f64)],
    ) -> (fmi2Status, Vec<f64>) {
        let unknown: Vec<u32> = unknowns.iter().map(|n| self.vr(n)).collect();
        let known: Vec<u32> = knowns.iter().map(|(n, _)| self.vr(n)).collect();
        let seed: Vec<f64> = knowns.iter().map(|(_, x)| *x).collect();
        let mut out = vec![f64::NAN; unknowns.len()];
        // SAFETY: each array holds the count passed with it.
        let s = unsafe {
            fmi2GetDirectionalDerivative(
                self.c,
                unknown.as_ptr(),
                unknown.len(),
                known.as_ptr(),
                known.len(),
                seed.as_ptr(),
                out.as_mut_ptr(),
            )
        };
        (s, out)
    }

    /// The current FMU state, serialized (`fmi2GetFMUstate`, `fmi2SerializedFMUstateSize`,
    /// `fmi2SerializeFMUstate`, `fmi2FreeFMUstate`); asserts every status.
    #[track_caller]
    pub fn serialized_state(&self) -> Vec<u8> {
        let mut state: fmi2FMUstate = std::ptr::null_mut();
        // SAFETY: live instance; the slot is NULL.
        assert_eq!(unsafe { fmi2GetFMUstate(self.c, &mut state) }, OK);
        let mut size = 0usize;
        // SAFETY: state created above.
        assert_eq!(
            unsafe { fmi2SerializedFMUstateSize(self.c, state, &mut size) },
            OK
        );
        let mut bytes = vec![0 as fmi2Byte; size];
        // SAFETY: buffer of `size` bytes.
        assert_eq!(
            unsafe { fmi2SerializeFMUstate(self.c, state, bytes.as_mut_ptr(), size) },
            OK
        );
        // SAFETY: state created above, freed once.
        assert_eq!(unsafe { fmi2FreeFMUstate(self.c, &mut state) }, OK);
        assert!(state.is_null());
        bytes.iter().map(|&b| b as u8).collect()
    }

    /// `fmi2DeSerializeFMUstate` of `bytes`: the status, and the new state (NULL on failure).
    pub fn deserialize(&self, bytes: &[u8]) -> (fmi2Status, fmi2FMUstate) {
        let mut state: fmi2FMUstate = std::ptr::null_mut();
        // SAFETY: buffer of bytes.len() bytes; the slot is NULL.
        let s = unsafe {
            fmi2DeSerializeFMUstate(
                self.c,
                bytes.as_ptr().cast::<fmi2Byte>(),
                bytes.len(),
                &mut state,
            )
        };
        (s, state)
    }

    /// Deserializes `bytes` and sets the state; returns the first status that is not OK.
    pub fn restore_serialized(&self, bytes: &[u8]) -> fmi2Status {
        let (s, mut state) = self.deserialize(bytes);
        if s != OK {
            return s;
        }
        // SAFETY: state created by fmi2DeSerializeFMUstate.
        let set = unsafe { fmi2SetFMUstate(self.c, state) };
        // SAFETY: freed once.
        let free = unsafe { fmi2FreeFMUstate(self.c, &mut state) };
        set.max(free)
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        if self.owned {
            // SAFETY: freed exactly once.
            unsafe { fmi2FreeInstance(self.c) };
        }
    }
}

/// SplitMix64: a small deterministic generator for seeded input sequences.
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [−1, 1).
    pub fn signed_unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// One coordinate of a random walk: a step of at most `step` per call, reflected at the bounds.
#[derive(Debug, Clone, Copy)]
pub struct Walk {
    pub value: f64,
    pub lo: f64,
    pub hi: f64,
    pub step: f64,
}

impl Walk {
    pub fn advance(&mut self, rng: &mut Rng) -> f64 {
        let mut x = self.value + self.step * rng.signed_unit();
        if x > self.hi {
            x = 2.0 * self.hi - x;
        }
        if x < self.lo {
            x = 2.0 * self.lo - x;
        }
        self.value = x.clamp(self.lo, self.hi);
        self.value
    }
}

/// The random-walk wheelset pose of the `WheelRailContact` tests: lateral shift, yaw, roll,
/// both wheel loads, forward and lateral speed, yaw rate and the axle's angular velocity
/// (pure rolling plus a walking longitudinal creepage), inside a band where both wheels keep
/// tread or flange contact.
#[derive(Debug, Clone)]
pub struct PoseWalk {
    rng: Rng,
    walks: [Walk; 9],
    pub vrs: [u32; 9],
    wheel_radius: f64,
}

/// Input names of [`PoseWalk`], in the order of [`PoseWalk::next`].
pub const POSE_INPUTS: [&str; 9] = [
    "y", "yaw", "roll", "Qleft", "Qright", "vx", "vy", "yawRate", "omega",
];

impl PoseWalk {
    pub fn new(info: &'static ModelInfo, seed: u64) -> Self {
        let w = |value, lo, hi, step| Walk {
            value,
            lo,
            hi,
            step,
        };
        Self {
            rng: Rng::new(seed),
            walks: [
                w(0.0, -0.0065, 0.0065, 2e-4), // y [m]
                w(0.0, -4e-3, 4e-3, 2e-4),     // yaw [rad]
                w(0.0, -2e-3, 2e-3, 1e-4),     // roll [rad]
                w(78_500.0, 2e4, 1.5e5, 2e3),  // Qleft [N]
                w(78_500.0, 2e4, 1.5e5, 2e3),  // Qright [N]
                w(30.0, 1.0, 60.0, 0.5),       // vx [m/s]
                w(0.0, -0.2, 0.2, 0.02),       // vy [m/s]
                w(0.0, -0.2, 0.2, 0.02),       // yawRate [rad/s]
                w(0.0, -5e-3, 5e-3, 2e-4),     // longitudinal creepage of omega
            ],
            vrs: POSE_INPUTS.map(|n| var(info, n).vr),
            wheel_radius: 0.46,
        }
    }

    /// The next input values, in the order of [`POSE_INPUTS`].
    pub fn next(&mut self) -> [f64; 9] {
        let mut x = [0.0; 9];
        for (xi, w) in x.iter_mut().zip(self.walks.iter_mut()) {
            *xi = w.advance(&mut self.rng);
        }
        // omega: pure rolling at the nominal radius times (1 + creepage).
        x[8] = x[5] / self.wheel_radius * (1.0 + x[8]);
        x
    }
}

/// Resident set size of this process [kB] (`VmRSS` of /proc/self/status).
pub fn vm_rss_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.split_whitespace().next())
        .and_then(|v| v.parse().ok())
}
