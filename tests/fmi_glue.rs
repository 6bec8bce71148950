//! The FMI 2.0 glue through its exported C functions, driven by the `fmi_host` harness as linked
//! functions (the same functions a host resolves from the shared library): state machine,
//! checked set/get with log messages, FMU state round trips, and the generated model
//! description.

mod linked;

use fmi_host::{Error, Instance, Status};
use linked::Checked;
use railcontact::models::hertz_contact::{generated, INFO};

fn new(name: &str) -> Instance {
    linked::instantiate(&INFO, name)
}

/// The texts of the messages `f` logged.
fn texts(f: &Instance) -> Vec<String> {
    f.messages().into_iter().map(|m| m.text).collect()
}

fn bits(x: &[Vec<f64>]) -> Vec<u64> {
    x.iter().flatten().map(|v| v.to_bits()).collect()
}

#[test]
fn platform_and_version() {
    let fmu = linked::fmu(&INFO);
    assert_eq!(fmu.types_platform(), "default");
    assert_eq!(fmu.version(), "2.0");
}

#[test]
fn wrong_guid_is_refused_with_a_message() {
    let refused = linked::fmu(&INFO).instantiate_as(
        "wrongGuid",
        "{00000000-0000-0000-0000-000000000000}",
        Some(linked::NO_RESOURCES),
    );
    let Err(Error::Instantiate { messages, .. }) = refused else {
        panic!("instantiated with a wrong GUID");
    };
    assert!(
        messages.iter().any(|m| m.text.contains("does not match")),
        "{messages:?}"
    );
}

#[test]
fn start_values_are_set_at_instantiation() {
    let f = new("starts");
    f.init();
    // From modelDescription/HertzContact.json.
    assert_eq!(f.get_real("E").unwrap(), 2.1e11);
    assert_eq!(f.get_real("nu").unwrap(), 0.28);
    assert_eq!(f.get_real("N").unwrap(), 82000.0);
    assert_eq!(f.get_real("eta").unwrap(), -6.25e-4);
}

#[test]
fn rejected_value_names_variable_value_and_range_and_keeps_the_old_value() {
    let f = new("badInput");
    assert_eq!(f.set_real("N", -1.0), Status::Error);
    assert_eq!(f.set_real("A", 0.0), Status::Error);
    assert_eq!(f.set_real("xi", f64::NAN), Status::Error);
    assert_eq!(f.set_real("mu", f64::INFINITY), Status::Error);
    assert_eq!(f.set_integer("nx", 0), Status::Error);
    let m = texts(&f);
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
    assert_eq!(
        f.get_real("N").unwrap(),
        82000.0,
        "rejected value must not be stored"
    );
    assert_eq!(f.step(0.0, 1e-3), Status::Ok);
    assert!(f.outputs().iter().all(|x| x.is_finite()));
}

#[test]
fn call_order_misuse_is_an_error() {
    let f = new("misuse");
    assert_eq!(f.step(0.0, 1e-3), Status::Error, "DoStep before init");
    f.init();
    assert_eq!(
        f.set_real("E", 2.0e11),
        Status::Error,
        "fixed parameter after init"
    );
    assert_eq!(f.step(0.0, 0.0), Status::Error, "zero step");
    assert_eq!(f.get_real_vr(10_000).0, Status::Error);
    let nx = f.vr("nx");
    assert_eq!(f.get_real_vr(nx).0, Status::Error, "type mismatch");
    // nvr = 0 with NULL arrays is legal.
    // SAFETY: no element is read.
    let s = unsafe {
        (f.functions().fmi2GetReal)(f.component(), std::ptr::null(), 0, std::ptr::null_mut())
    };
    assert_eq!(Status::from(s), Status::Ok);
    // Still usable after the rejected calls.
    assert_eq!(f.step(0.0, 1e-3), Status::Ok);
    let m = texts(&f);
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
    let f = new("unsupported");
    f.init();
    let (c, functions) = (f.component(), f.functions());
    // SAFETY: arguments are not read by the unsupported functions.
    unsafe {
        assert_eq!(Status::from((functions.fmi2CancelStep)(c)), Status::Error);
        let s = (functions.fmi2SetRealInputDerivatives)(
            c,
            std::ptr::null(),
            0,
            std::ptr::null(),
            std::ptr::null(),
        );
        assert_eq!(Status::from(s), Status::Error);
        // Directional derivatives are provided: an empty request is answered.
        let s = (functions.fmi2GetDirectionalDerivative)(
            c,
            std::ptr::null(),
            0,
            std::ptr::null(),
            0,
            std::ptr::null(),
            std::ptr::null_mut(),
        );
        assert_eq!(Status::from(s), Status::Ok);
    }
    assert!(texts(&f)
        .iter()
        .any(|m| m.contains("fmi2CancelStep is not supported")));
}

#[test]
fn reset_returns_to_start_values() {
    let f = new("reset");
    f.init();
    assert_eq!(f.set_real("N", 1000.0), Status::Ok);
    assert_eq!(f.step(0.0, 1e-3), Status::Ok);
    assert_eq!(f.reset(), Status::Ok);
    assert_eq!(
        f.set_real("E", 2.0e11),
        Status::Ok,
        "parameters settable again"
    );
    f.init();
    assert_eq!(f.get_real("N").unwrap(), 82000.0);
    assert_eq!(f.step(0.0, 1e-3), Status::Ok);
}

#[test]
fn fmu_state_round_trip_is_bit_exact_and_corruption_is_rejected() {
    let f = new("state");
    f.init();
    let drive = |k: usize| {
        let eta = -1e-4 * k as f64;
        assert_eq!(f.set_real("eta", eta), Status::Ok);
        assert_eq!(f.step(k as f64 * 1e-3, 1e-3), Status::Ok);
        f.outputs()
    };
    for k in 0..3 {
        drive(k);
    }
    let state = f.get_state().unwrap();
    let first: Vec<Vec<f64>> = (3..8).map(drive).collect();
    assert_eq!(f.set_state(&state), Status::Ok);
    let again: Vec<Vec<f64>> = (3..8).map(drive).collect();
    assert_eq!(bits(&first), bits(&again));

    // Serialize, deserialize into a new state, restore: same again.
    let bytes = f.serialize(&state).unwrap();
    let size = bytes.len();
    let (s, copy) = f.deserialize(&bytes);
    assert_eq!(s, Status::Ok);
    let copy = copy.expect("a deserialized state");
    assert_eq!(f.set_state(&copy), Status::Ok);
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
        let (st, s) = f.deserialize(&bad);
        assert_eq!(st, Status::Error);
        assert!(s.is_none());
        rejected += 1;
    }
    // A NaN written over an output value (found by its bit pattern) is rejected too: a
    // restored state must never bring back a NaN output.
    let a_bits = f.get_real("a").unwrap().to_bits().to_le_bytes();
    let at = bytes
        .windows(8)
        .position(|w| w == a_bits)
        .expect("output a is in the state");
    let mut nan_output = bytes.clone();
    nan_output[at..at + 8].copy_from_slice(&f64::NAN.to_bits().to_le_bytes());
    let (st, s) = f.deserialize(&nan_output);
    assert_eq!(st, Status::Error);
    assert!(s.is_none());
    rejected += 1;
    assert_eq!(rejected, 4);
    // The instance still works after the rejections.
    assert_eq!(drive(8).len(), first[0].len());
    let (freed_state, state_cleared) = state.free();
    let (freed_copy, copy_cleared) = copy.free();
    assert_eq!((freed_state, freed_copy), (Status::Ok, Status::Ok));
    assert!(state_cleared && copy_cleared);
}

#[test]
fn instances_are_independent() {
    let a = new("indepA");
    let b = new("indepB");
    a.init();
    b.init();
    assert_eq!(a.set_real("eta", -2e-3), Status::Ok);
    assert_eq!(a.step(0.0, 1e-3), Status::Ok);
    assert_eq!(b.step(0.0, 1e-3), Status::Ok);
    let alone = new("indepAlone");
    alone.init();
    assert_eq!(alone.step(0.0, 1e-3), Status::Ok);
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
