//! The FMI 2.0 glue through its exported C functions, called directly from Rust (the same
//! functions a host resolves from the shared library): state machine, checked set/get with log
//! messages, FMU state round trips, and the generated model description.

use fmi_sys::fmi2::*;
use railcontact::fmi::export::*;
use railcontact::models::hertz_contact::{generated, INFO};
use std::ffi::{CStr, CString};
use std::sync::Mutex;

/// Collects log messages (routed by fmi-sys's variadic C logger through the `log` crate),
/// tagged with the instance name so parallel tests can tell theirs apart.
struct Capture(Mutex<Vec<(String, String)>>);
impl log::Log for Capture {
    fn enabled(&self, _: &log::Metadata<'_>) -> bool {
        true
    }
    fn log(&self, r: &log::Record<'_>) {
        self.0
            .lock()
            .unwrap()
            .push((r.target().to_string(), r.args().to_string()));
    }
    fn flush(&self) {}
}
static CAPTURE: Capture = Capture(Mutex::new(Vec::new()));

fn messages(instance: &str) -> Vec<String> {
    CAPTURE
        .0
        .lock()
        .unwrap()
        .iter()
        .filter(|(t, _)| t == instance)
        .map(|(_, m)| m.clone())
        .collect()
}

fn vr(name: &str) -> u32 {
    INFO.variable(name).expect("known variable").vr
}

struct Fmu {
    c: fmi2Component,
}

impl Fmu {
    fn new(name: &str) -> Self {
        Self::try_new(name, INFO.guid).expect("instantiated")
    }

    fn try_new(name: &str, guid: &str) -> Option<Self> {
        let _ = log::set_logger(&CAPTURE).map(|()| log::set_max_level(log::LevelFilter::Trace));
        let callbacks = fmi2CallbackFunctions {
            logger: Some(fmi_sys::fmi2::logger::callback_logger_handler),
            allocateMemory: None,
            freeMemory: None,
            stepFinished: None,
            componentEnvironment: std::ptr::null_mut(),
        };
        let cname = CString::new(name).unwrap();
        let cguid = CString::new(guid).unwrap();
        let uri = c"file:///nonexistent/resources";
        // SAFETY: valid strings and callbacks for the call's duration.
        let c = unsafe {
            fmi2Instantiate(
                cname.as_ptr(),
                fmi2Type_fmi2CoSimulation,
                cguid.as_ptr(),
                uri.as_ptr(),
                &callbacks,
                0,
                0,
            )
        };
        (!c.is_null()).then_some(Self { c })
    }

    fn set(&self, name: &str, x: f64) -> fmi2Status {
        let r = vr(name);
        // SAFETY: one value reference, one value.
        unsafe { fmi2SetReal(self.c, &r, 1, &x) }
    }

    fn set_int(&self, name: &str, k: i32) -> fmi2Status {
        let r = vr(name);
        // SAFETY: one value reference, one value.
        unsafe { fmi2SetInteger(self.c, &r, 1, &k) }
    }

    fn get(&self, name: &str) -> f64 {
        let r = vr(name);
        let mut x = f64::NAN;
        // SAFETY: one value reference, one slot.
        let s = unsafe { fmi2GetReal(self.c, &r, 1, &mut x) };
        assert_eq!(s, fmi2Status_fmi2OK, "GetReal({name})");
        x
    }

    fn init(&self) {
        // SAFETY: live instance.
        unsafe {
            assert_eq!(
                fmi2SetupExperiment(self.c, 0, 0.0, 0.0, 0, 0.0),
                fmi2Status_fmi2OK
            );
            assert_eq!(fmi2EnterInitializationMode(self.c), fmi2Status_fmi2OK);
            assert_eq!(fmi2ExitInitializationMode(self.c), fmi2Status_fmi2OK);
        }
    }

    fn step(&self, t: f64, h: f64) -> fmi2Status {
        // SAFETY: live instance.
        unsafe { fmi2DoStep(self.c, t, h, 1) }
    }

    fn outputs(&self) -> Vec<f64> {
        INFO.variables
            .iter()
            .filter(|v| v.causality == railcontact::fmi::variables::Causality::Output)
            .map(|v| self.get(v.name))
            .collect()
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        // SAFETY: freed exactly once.
        unsafe { fmi2FreeInstance(self.c) };
    }
}

#[test]
fn platform_and_version() {
    // SAFETY: static strings.
    unsafe {
        assert_eq!(CStr::from_ptr(fmi2GetTypesPlatform()), c"default");
        assert_eq!(CStr::from_ptr(fmi2GetVersion()), c"2.0");
    }
}

#[test]
fn wrong_guid_is_refused_with_a_message() {
    assert!(Fmu::try_new("wrongGuid", "{00000000-0000-0000-0000-000000000000}").is_none());
    let m = messages("wrongGuid");
    assert!(m.iter().any(|m| m.contains("does not match")), "{m:?}");
}

#[test]
fn start_values_are_set_at_instantiation() {
    let f = Fmu::new("starts");
    f.init();
    // From modelDescription/HertzContact.json.
    assert_eq!(f.get("E"), 2.1e11);
    assert_eq!(f.get("nu"), 0.28);
    assert_eq!(f.get("N"), 82000.0);
    assert_eq!(f.get("eta"), -6.25e-4);
}

#[test]
fn rejected_value_names_variable_value_and_range_and_keeps_the_old_value() {
    let f = Fmu::new("badInput");
    assert_eq!(f.set("N", -1.0), fmi2Status_fmi2Error);
    assert_eq!(f.set("A", 0.0), fmi2Status_fmi2Error);
    assert_eq!(f.set("xi", f64::NAN), fmi2Status_fmi2Error);
    assert_eq!(f.set("mu", f64::INFINITY), fmi2Status_fmi2Error);
    assert_eq!(f.set_int("nx", 0), fmi2Status_fmi2Error);
    let m = messages("badInput");
    for want in [
        "N = -1 is outside the allowed range [0, 100000000] [N]",
        "A = 0 is outside the allowed range [0.001, 100000] [1/m]",
        "xi = NaN is outside the allowed range [-10, 10]",
        "mu = inf is outside the allowed range (0, 10]",
        "nx = 0 is outside the allowed range integer in [1, 1000]",
    ] {
        assert!(
            m.iter().any(|x| x.contains(want)),
            "missing {want:?} in {m:?}"
        );
    }
    f.init();
    assert_eq!(f.get("N"), 82000.0, "rejected value must not be stored");
    assert_eq!(f.step(0.0, 1e-3), fmi2Status_fmi2OK);
    assert!(f.outputs().iter().all(|x| x.is_finite()));
}

#[test]
fn call_order_misuse_is_an_error() {
    let f = Fmu::new("misuse");
    assert_eq!(
        f.step(0.0, 1e-3),
        fmi2Status_fmi2Error,
        "DoStep before init"
    );
    f.init();
    assert_eq!(
        f.set("E", 2.0e11),
        fmi2Status_fmi2Error,
        "fixed parameter after init"
    );
    assert_eq!(f.step(0.0, 0.0), fmi2Status_fmi2Error, "zero step");
    let unknown = 10_000u32;
    let mut x = 0.0;
    // SAFETY: one value reference, one slot.
    let s = unsafe { fmi2GetReal(f.c, &unknown, 1, &mut x) };
    assert_eq!(s, fmi2Status_fmi2Error);
    let n = vr("nx");
    // SAFETY: as above; Integer variable read as Real.
    let s = unsafe { fmi2GetReal(f.c, &n, 1, &mut x) };
    assert_eq!(s, fmi2Status_fmi2Error, "type mismatch");
    // nvr = 0 with NULL arrays is legal.
    // SAFETY: no element is read.
    let s = unsafe { fmi2GetReal(f.c, std::ptr::null(), 0, std::ptr::null_mut()) };
    assert_eq!(s, fmi2Status_fmi2OK);
    // Still usable after the rejected calls.
    assert_eq!(f.step(0.0, 1e-3), fmi2Status_fmi2OK);
    let m = messages("misuse");
    assert!(
        m.iter()
            .any(|x| x.contains("unknown value reference 10000")),
        "{m:?}"
    );
    assert!(
        m.iter()
            .any(|x| x.contains("E (Parameter, Fixed) cannot be set")),
        "{m:?}"
    );
}

#[test]
fn unsupported_functions_log_and_fail() {
    let f = Fmu::new("unsupported");
    f.init();
    // SAFETY: arguments are not read by the unsupported functions.
    unsafe {
        assert_eq!(fmi2CancelStep(f.c), fmi2Status_fmi2Error);
        assert_eq!(
            fmi2SetRealInputDerivatives(
                f.c,
                std::ptr::null(),
                0,
                std::ptr::null(),
                std::ptr::null()
            ),
            fmi2Status_fmi2Error
        );
        // Directional derivatives are provided: an empty request is answered.
        assert_eq!(
            fmi2GetDirectionalDerivative(
                f.c,
                std::ptr::null(),
                0,
                std::ptr::null(),
                0,
                std::ptr::null(),
                std::ptr::null_mut()
            ),
            fmi2Status_fmi2OK
        );
    }
    assert!(messages("unsupported")
        .iter()
        .any(|m| m.contains("fmi2CancelStep is not supported")));
}

#[test]
fn reset_returns_to_start_values() {
    let f = Fmu::new("reset");
    f.init();
    assert_eq!(f.set("N", 1000.0), fmi2Status_fmi2OK);
    assert_eq!(f.step(0.0, 1e-3), fmi2Status_fmi2OK);
    // SAFETY: live instance.
    assert_eq!(unsafe { fmi2Reset(f.c) }, fmi2Status_fmi2OK);
    assert_eq!(
        f.set("E", 2.0e11),
        fmi2Status_fmi2OK,
        "parameters settable again"
    );
    f.init();
    assert_eq!(f.get("N"), 82000.0);
    assert_eq!(f.step(0.0, 1e-3), fmi2Status_fmi2OK);
}

#[test]
fn fmu_state_round_trip_is_bit_exact_and_corruption_is_rejected() {
    let f = Fmu::new("state");
    f.init();
    let drive = |k: usize| {
        let eta = -1e-4 * k as f64;
        assert_eq!(f.set("eta", eta), fmi2Status_fmi2OK);
        assert_eq!(f.step(k as f64 * 1e-3, 1e-3), fmi2Status_fmi2OK);
        f.outputs()
    };
    for k in 0..3 {
        drive(k);
    }
    let mut state: fmi2FMUstate = std::ptr::null_mut();
    // SAFETY: live instance, state slot initialised to NULL.
    assert_eq!(
        unsafe { fmi2GetFMUstate(f.c, &mut state) },
        fmi2Status_fmi2OK
    );
    let first: Vec<Vec<f64>> = (3..8).map(drive).collect();
    // SAFETY: state created above.
    assert_eq!(unsafe { fmi2SetFMUstate(f.c, state) }, fmi2Status_fmi2OK);
    let again: Vec<Vec<f64>> = (3..8).map(drive).collect();
    assert_eq!(
        first
            .iter()
            .flatten()
            .map(|x| x.to_bits())
            .collect::<Vec<_>>(),
        again
            .iter()
            .flatten()
            .map(|x| x.to_bits())
            .collect::<Vec<_>>()
    );

    // Serialize, deserialize into a new state, restore: same again.
    let mut size = 0usize;
    // SAFETY: valid state and out pointer.
    assert_eq!(
        unsafe { fmi2SerializedFMUstateSize(f.c, state, &mut size) },
        fmi2Status_fmi2OK
    );
    let mut bytes = vec![0 as fmi2Byte; size];
    // SAFETY: buffer of `size` bytes.
    assert_eq!(
        unsafe { fmi2SerializeFMUstate(f.c, state, bytes.as_mut_ptr(), size) },
        fmi2Status_fmi2OK
    );
    let mut copy: fmi2FMUstate = std::ptr::null_mut();
    // SAFETY: buffer of `size` bytes; copy slot NULL.
    assert_eq!(
        unsafe { fmi2DeSerializeFMUstate(f.c, bytes.as_ptr(), size, &mut copy) },
        fmi2Status_fmi2OK
    );
    // SAFETY: state created by deserialize.
    assert_eq!(unsafe { fmi2SetFMUstate(f.c, copy) }, fmi2Status_fmi2OK);
    let third: Vec<Vec<f64>> = (3..8).map(drive).collect();
    assert_eq!(first, third);

    // Corruptions: truncated, bad magic, wrong length, out-of-range input value.
    let mut rejected = 0;
    let mut truncated = bytes.clone();
    truncated.truncate(size / 2);
    let mut magic = bytes.clone();
    magic[0] ^= 0x55;
    let mut longer = bytes.clone();
    longer.push(0);
    for bad in [truncated, magic, longer] {
        let mut s: fmi2FMUstate = std::ptr::null_mut();
        // SAFETY: buffer of bad.len() bytes.
        let st = unsafe { fmi2DeSerializeFMUstate(f.c, bad.as_ptr(), bad.len(), &mut s) };
        assert_eq!(st, fmi2Status_fmi2Error);
        assert!(s.is_null());
        rejected += 1;
    }
    // A NaN written over an output value (found by its bit pattern) is rejected too: a
    // restored state must never bring back a NaN output.
    let a_bits = f.get("a").to_bits().to_le_bytes();
    let at = bytes
        .windows(8)
        .position(|w| w.iter().zip(&a_bits).all(|(x, y)| *x as u8 == *y))
        .expect("output a is in the state");
    let mut nan_output = bytes.clone();
    for (i, b) in f64::NAN.to_bits().to_le_bytes().iter().enumerate() {
        nan_output[at + i] = *b as fmi2Byte;
    }
    let mut s: fmi2FMUstate = std::ptr::null_mut();
    // SAFETY: buffer of nan_output.len() bytes.
    let st = unsafe { fmi2DeSerializeFMUstate(f.c, nan_output.as_ptr(), nan_output.len(), &mut s) };
    assert_eq!(st, fmi2Status_fmi2Error);
    assert!(s.is_null());
    rejected += 1;
    assert_eq!(rejected, 4);
    // The instance still works after the rejections.
    assert_eq!(drive(8).len(), first[0].len());
    // SAFETY: states created above, freed once.
    unsafe {
        assert_eq!(fmi2FreeFMUstate(f.c, &mut state), fmi2Status_fmi2OK);
        assert_eq!(fmi2FreeFMUstate(f.c, &mut copy), fmi2Status_fmi2OK);
    }
    assert!(state.is_null() && copy.is_null());
}

#[test]
fn instances_are_independent() {
    let a = Fmu::new("indepA");
    let b = Fmu::new("indepB");
    a.init();
    b.init();
    assert_eq!(a.set("eta", -2e-3), fmi2Status_fmi2OK);
    assert_eq!(a.step(0.0, 1e-3), fmi2Status_fmi2OK);
    assert_eq!(b.step(0.0, 1e-3), fmi2Status_fmi2OK);
    let alone = Fmu::new("indepAlone");
    alone.init();
    assert_eq!(alone.step(0.0, 1e-3), fmi2Status_fmi2OK);
    assert_eq!(b.outputs(), alone.outputs(), "b must not see a's input");
}

#[test]
fn generated_model_description_matches_the_table() {
    let xml = generated::MODEL_DESCRIPTION_XML;
    assert!(xml.contains(&format!("guid=\"{}\"", INFO.guid)));
    assert!(xml.contains("modelIdentifier=\"HertzContact\""));
    assert_eq!(
        xml.matches("<ScalarVariable ").count(),
        INFO.variables.len()
    );
    for v in INFO.variables {
        assert!(
            xml.contains(&format!("name=\"{}\" valueReference=\"{}\"", v.name, v.vr)),
            "{} missing",
            v.name
        );
        if v.causality == railcontact::fmi::variables::Causality::Output {
            // ModelStructure indices are 1-based positions in ModelVariables.
            let unknown = format!("<Unknown index=\"{}\"/>", v.vr + 1);
            assert_eq!(
                xml.matches(&unknown).count(),
                2,
                "{} in Outputs and InitialUnknowns",
                v.name
            );
        }
    }
    assert!(xml.contains("providesDirectionalDerivative=\"true\""));
    assert!(
        !xml.contains("<Derivatives"),
        "stateless CS FMU must not declare Derivatives"
    );
}
