//! Reliability of both FMUs through their exported C functions (docs/reliability.md):
//!
//! 1. every parameter and input rejects NaN, ±∞ and out-of-range values when set, with a message
//!    naming the variable, the value and the allowed range, and changes nothing; string
//!    parameters (profiles) and the one constraint between parameters are checked at
//!    initialization, with the file, line and reason;
//! 2. physical edge cases for every `normalModel` × `tangentialModel`: lift-off and re-contact,
//!    tiny and large loads, standstill, saturated creepage, flange climb towards and past the
//!    profile's end, poses off the profiles, conformal contact — documented status, finite outputs;
//! 3. FMI call-order misuse: the state machine, unknown value references, NULL pointers, double
//!    `fmi2FreeInstance`, reset and re-initialization;
//! 4. FMU states over long runs with time-varying inputs, bit for bit, and corrupted states;
//! 5. many instances in one process and in parallel threads.
//!
//! The soak test is `tests/soak.rs`; the fuzz targets are in `fuzz/`.

mod linked;
mod reliability_support;

use fmi_host::{Instance, Status};
use linked::*;
use railcontact::fmi::model::ModelInfo;
use railcontact::fmi::variables::{Causality, Start, VarType};
use railcontact::models::{hertz_contact, wheel_rail_contact};
use reliability_support::*;
use std::path::{Path, PathBuf};

const H: f64 = 1e-3;
const Q: f64 = 78_500.0;

fn hc() -> &'static ModelInfo {
    &hertz_contact::INFO
}

fn wrc() -> &'static ModelInfo {
    &wheel_rail_contact::INFO
}

/// A unique instance name per test and purpose (the log is routed by it).
fn name(parts: &[&dyn std::fmt::Display]) -> String {
    parts
        .iter()
        .map(|p| p.to_string())
        .collect::<Vec<_>>()
        .join("/")
}

/// A parameter or input value of any type.
#[derive(Debug, Clone)]
enum P {
    R(f64),
    I(i32),
    B(bool),
    S(String),
}

fn set(f: &Instance, var: &str, value: &P) -> Status {
    match value {
        P::R(x) => f.set_real(var, *x),
        P::I(k) => f.set_integer(var, *k),
        P::B(b) => f.set_boolean(var, *b),
        P::S(s) => f.set_string(var, s),
    }
}

/// An instance with `params` set before initialization; asserts every status.
#[track_caller]
fn initialized(info: &'static ModelInfo, name: &str, params: &[(&str, P)]) -> Instance {
    let f = instantiate(info, name);
    for (var, value) in params {
        assert_eq!(set(&f, var, value), OK, "{name}: {var} = {value:?}");
    }
    f.init();
    f
}

/// Steps an instance with consecutive communication points.
struct Run {
    f: Instance,
    t: f64,
}

impl Run {
    fn new(f: Instance) -> Self {
        Self { f, t: 0.0 }
    }

    /// Sets `inputs`, steps; returns the status (time advances only on OK).
    fn step(&mut self, inputs: &[(&str, f64)]) -> Status {
        for (var, x) in inputs {
            assert_eq!(
                self.f.set_real(var, *x),
                OK,
                "{}: {var} = {x}",
                self.f.name()
            );
        }
        let s = self.f.step(self.t, H);
        if s == OK {
            self.t += H;
        }
        s
    }

    #[track_caller]
    fn step_ok(&mut self, inputs: &[(&str, f64)]) -> Vec<f64> {
        let s = self.step(inputs);
        assert_eq!(
            s,
            OK,
            "{}: step with {inputs:?}: {:?}",
            self.f.name(),
            self.f.messages()
        );
        self.f.outputs()
    }
}

// =============================================================================================
// 1. Input validation

/// A value just outside `[lo, …`: below it, or `lo` itself when the bound is exclusive.
fn below(lo: f64, exclusive: bool) -> f64 {
    if exclusive {
        lo
    } else {
        lo - lo.abs().max(1.0) * 1e-3
    }
}

fn above(hi: f64) -> f64 {
    hi + hi.abs().max(1.0) * 1e-3
}

fn expected_message(v: &railcontact::fmi::variables::VarInfo, shown: &str) -> String {
    format!(
        "{} = {shown} is outside the allowed range {}",
        v.name, v.allowed
    )
}

#[test]
fn every_real_and_integer_parameter_and_input_has_a_finite_range() {
    for info in [hc(), wrc()] {
        for v in info.variables {
            if v.causality == Causality::Output || !matches!(v.ty, VarType::Real | VarType::Integer)
            {
                continue;
            }
            let (Some(lo), Some(hi)) = (v.min, v.max) else {
                panic!(
                    "{}.{} has no complete range (min {:?}, max {:?}): NaN-free inputs need \
                     both bounds",
                    info.model_identifier, v.name, v.min, v.max
                );
            };
            assert!(lo.is_finite() && hi.is_finite() && lo < hi, "{}", v.name);
            let start = match v.start {
                Start::Real(x) => x,
                Start::Integer(k) => k as f64,
                s => panic!("{}: start {s:?}", v.name),
            };
            let inside = if v.min_exclusive {
                start > lo
            } else {
                start >= lo
            } && start <= hi;
            assert!(inside, "{}: start {start} outside [{lo}, {hi}]", v.name);
        }
    }
}

#[test]
fn bad_values_are_rejected_when_set_with_a_message_and_nothing_changes() {
    for info in [hc(), wrc()] {
        let f = instantiate(info, &name(&[&"badValues", &info.model_identifier]));
        assert_eq!(f.setup_experiment(0.0, None), OK);
        assert_eq!(f.enter_initialization(), OK); // Get is allowed from here on; every variable is settable.
        let mut rejected = 0;
        for v in info
            .variables
            .iter()
            .filter(|v| v.causality != Causality::Output)
        {
            match v.ty {
                VarType::Real => {
                    let (lo, hi) = (v.min.unwrap_or(f64::MIN), v.max.unwrap_or(f64::MAX));
                    let before = f.real(v.name);
                    for x in [
                        f64::NAN,
                        f64::INFINITY,
                        f64::NEG_INFINITY,
                        below(lo, v.min_exclusive),
                        above(hi),
                        -f64::MAX,
                        f64::MAX,
                    ] {
                        if v.accepts_real(x) {
                            continue;
                        }
                        assert_eq!(f.set_real(v.name, x), ERROR, "{} = {x}", v.name);
                        f.assert_error_logged(&[&expected_message(v, &x.to_string())]);
                        assert_eq!(f.real(v.name).to_bits(), before.to_bits(), "{}", v.name);
                        rejected += 1;
                    }
                }
                VarType::Integer => {
                    let (lo, hi) = (v.min.unwrap_or(f64::MIN), v.max.unwrap_or(f64::MAX));
                    let before = f.integer(v.name);
                    for k in [lo as i32 - 1, hi as i32 + 1, i32::MIN, i32::MAX] {
                        if v.accepts_integer(k) {
                            continue;
                        }
                        assert_eq!(f.set_integer(v.name, k), ERROR, "{} = {k}", v.name);
                        f.assert_error_logged(&[&expected_message(v, &k.to_string())]);
                        assert_eq!(f.integer(v.name), before, "{}", v.name);
                        rejected += 1;
                    }
                }
                VarType::Boolean | VarType::String => {}
            }
        }
        assert!(rejected > 20, "{rejected}");
        // Every message names its instance's variable; none is a warning only.
        assert_eq!(f.errors().len(), rejected);
        // The instance initializes and steps as a fresh one does.
        assert_eq!(f.exit_initialization(), OK, "{:?}", f.errors());
        assert_eq!(f.step(0.0, H), OK);
        let fresh = initialized(
            info,
            &name(&[&"badValuesFresh", &info.model_identifier]),
            &[],
        );
        assert_eq!(fresh.step(0.0, H), OK);
        assert_eq!(bits(&f.outputs()), bits(&fresh.outputs()));
    }
}

fn bits(x: &[f64]) -> Vec<u64> {
    x.iter().map(|v| v.to_bits()).collect()
}

#[test]
fn a_rejected_multi_value_call_changes_nothing() {
    let f = initialized(wrc(), "atomicSet", &[]);
    let (y, yaw, qleft) = (f.vr("y"), f.vr("yaw"), f.vr("Qleft"));
    assert_eq!(f.set_reals(&[y, yaw, qleft], &[0.003, 0.001, -5.0]), ERROR);
    f.assert_error_logged(&["Qleft = -5 is outside the allowed range [0, 10000000] [N]"]);
    assert_eq!((f.real("y"), f.real("yaw"), f.real("Qleft")), (0.0, 0.0, Q));
    assert_eq!(f.set_reals(&[y, yaw, qleft], &[0.003, 0.001, 5.0]), OK);
    assert_eq!(
        (f.real("y"), f.real("yaw"), f.real("Qleft")),
        (0.003, 0.001, 5.0)
    );
}

/// A two-column profile file in mm in a fresh directory of the test.
fn temp_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "railcontact-reliability-{}-{test}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn write(dir: &Path, file: &str, text: &[u8]) -> String {
    let p = dir.join(file);
    std::fs::write(&p, text).expect("write temp file");
    p.to_string_lossy().into_owned()
}

/// The benchmark profile `file` (e.g. `MBench_S1002_v3.prw`).
fn benchmark(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/profiles")
        .join(file)
}

/// The benchmark rail as CSV text (mm) with each point mapped by `f` (y, z in mm).
fn benchmark_rail_csv(f: impl Fn(f64, f64) -> (f64, f64)) -> Vec<u8> {
    let rail = railcontact::geometry::profile::Profile::from_file(
        &benchmark("MBench_UIC60_v3.prr"),
        None,
        0.0,
    )
    .expect("the benchmark rail");
    let (y, z) = rail.points();
    let mut text = String::from("y,z\n");
    for (&a, &b) in y.iter().zip(z) {
        let (a, b) = f(a * 1e3, b * 1e3);
        text += &format!("{a},{b}\n");
    }
    text.into_bytes()
}

/// The benchmark wheel file with line `line` (1-based) replaced by `text`.
fn benchmark_wheel_with(line: usize, text: &str) -> Vec<u8> {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/profiles/MBench_S1002_v3.prw");
    let original =
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines: Vec<&str> = original.lines().collect();
    lines[line - 1] = text;
    (lines.join("\n") + "\n").into_bytes()
}

#[test]
fn bad_profiles_fail_initialization_with_variable_file_line_and_reason() {
    let dir = temp_dir("profiles");
    let malformed = write(
        &dir,
        "malformed.prw",
        &benchmark_wheel_with(60, "6.3414676E+01\t2.45x3554E+01"),
    );
    let unsorted = write(
        &dir,
        "unsorted.csv",
        b"y,z\n-70,28\n-60,20\n-65,10\n0,0\n60,1\n",
    );
    let few = write(&dir, "few.txt", b"0 0\n1 1\n2 2\n");
    let binary = write(&dir, "binary.prr", b"header.begin\n\0\0\0\n");
    let open_block = write(&dir, "open.prr", b"point.begin\n1 2\n3 4\n");
    let nan = write(&dir, "nan.csv", b"y z\n0 0\n1 nan\n2 0\n3 0\n");
    let empty = write(&dir, "empty.prw", b"");
    // Parse cleanly, but fail the plausibility checks (railcontact::geometry::profile::checks).
    let benchmark_wheel =
        std::fs::read_to_string(benchmark("MBench_S1002_v3.prw")).expect("the benchmark wheel");
    let unmirrored = write(
        &dir,
        "unmirrored.prw",
        benchmark_wheel
            .replacen("mirror.y       =  1", "mirror.y       =  0", 1)
            .as_bytes(),
    );
    let stepped = write(
        &dir,
        "stepped.csv",
        &benchmark_rail_csv(|y, z| (y, if y > 3.0 { z + 0.5 } else { z })),
    );
    let metres = write(
        &dir,
        "metres.csv",
        &benchmark_rail_csv(|y, z| (y / 1e3, z / 1e3)),
    );
    let missing = dir
        .join("does-not-exist.prw")
        .to_string_lossy()
        .into_owned();
    let directory = dir.to_string_lossy().into_owned();
    // (variable, value, fragments the error must name besides "variable = value").
    let value_case = |var: &'static str, spec: &str, parts: &[&str]| {
        let parts: Vec<String> = parts.iter().map(|p| p.to_string()).collect();
        (var, spec.to_string(), parts)
    };
    // A file that is read but refused: its path is named too.
    let file_case = |var: &'static str, path: &str, parts: &[&str]| {
        let (var, spec, rest) = value_case(var, path, parts);
        (var, spec, [vec![path.to_string()], rest].concat())
    };
    let cases = [
        file_case(
            "wheelProfile",
            &malformed,
            &["line 60", "non-numeric value \"2.45x3554E+01\""],
        ),
        file_case("wheelProfile", &unsorted, &["line 4", "non-monotonic"]),
        file_case("railProfile", &few, &["too few points (3"]),
        file_case("railProfile", &binary, &["line 2", "binary data"]),
        file_case(
            "railProfile",
            &open_block,
            &["line 1", "no matching 'point.end'"],
        ),
        file_case("wheelProfile", &nan, &["line 3", "not a finite number"]),
        file_case("wheelProfile", &empty, &["missing point block"]),
        file_case(
            "wheelProfile",
            &unmirrored,
            &[
                "the flange (its tip 30.6 mm high at y = +54.9 mm) lies on the field side",
                "the profile is not mirrored",
                "toggle mirror.y",
            ],
        ),
        file_case(
            "railProfile",
            &stepped,
            &[
                "a step or spike at y = ",
                "set profileSmoothing = 0.0005 m or more",
            ],
        ),
        file_case("railProfile", &metres, &["the values look like metres"]),
        file_case(
            "wheelProfile",
            &missing,
            &["unknown built-in profile", "no such file"],
        ),
        value_case("railProfile", &directory, &["not a regular file"]),
        value_case(
            "wheelProfile",
            "S9999",
            &["unknown built-in profile \"S9999\"", "S1002, UIC60, 60E1"],
        ),
        value_case("wheelProfile", "", &["empty name"]),
        value_case(
            "wheelProfile",
            "UIC60",
            &["rail profile but a wheel profile is required"],
        ),
        value_case(
            "railProfile",
            "S1002",
            &["wheel profile but a rail profile is required"],
        ),
    ];
    for (i, (var, spec, parts)) in cases.iter().enumerate() {
        let f = instantiate(wrc(), &name(&[&"badProfile", &i]));
        assert_eq!(
            f.set_string(var, spec),
            OK,
            "strings are checked at initialization"
        );
        assert_eq!(f.setup_experiment(0.0, None), OK);
        assert_eq!(f.enter_initialization(), OK);
        assert_eq!(f.exit_initialization(), ERROR, "{var} = {spec:?}");
        let mut want: Vec<&str> = vec!["initialization failed", var];
        let quoted = format!("{var} = {spec:?}");
        want.push(&quoted);
        want.extend(parts.iter().map(String::as_str));
        f.assert_error_logged(&want);
        // Still in initialization mode: a good value and a second exit recover.
        assert_eq!(
            f.step(0.0, H),
            ERROR,
            "no stepping before a successful initialization"
        );
        let good = if *var == "wheelProfile" {
            "S1002"
        } else {
            "UIC60"
        };
        assert_eq!(f.set_string(var, good), OK);
        assert_eq!(f.exit_initialization(), OK, "{:?}", f.errors());
        assert_eq!(f.step(0.0, H), OK);
        f.outputs();
    }
}

/// A profile defect that the smoothing absorbs is no error: the benchmark rail with a 0.5 mm
/// step across its crown (refused at profileSmoothing = 0, test above) initializes and steps
/// with the usual 1 mm smoothing, balancing the wheel load.
#[test]
fn a_step_absorbed_by_the_smoothing_initializes() {
    let dir = temp_dir("absorbed");
    let stepped = write(
        &dir,
        "stepped.csv",
        &benchmark_rail_csv(|y, z| (y, if y > 3.0 { z + 0.5 } else { z })),
    );
    let mut run = Run::new(initialized(
        wrc(),
        "absorbedStep",
        &[
            ("railProfile", P::S(stepped)),
            ("railInclination", P::R(0.0)),
            ("profileSmoothing", P::R(1e-3)),
        ],
    ));
    run.step_ok(&[]);
    assert_balanced(&run.f, "right", Q, "stepped rail, 1 mm smoothing");
}

#[test]
fn wheels_that_do_not_fit_between_the_rails_fail_initialization() {
    for (gauge, flange_backs) in [(1.0, 1.36), (1.435, 1.435), (1.435, 1.7)] {
        let f = instantiate(wrc(), &name(&[&"fit", &gauge, &flange_backs]));
        assert_eq!(f.set_real("trackGauge", gauge), OK);
        assert_eq!(f.set_real("flangeBackDistance", flange_backs), OK);
        assert_eq!(f.initialize(), ERROR);
        f.assert_error_logged(&[&format!(
            "flangeBackDistance = {flange_backs} is outside the allowed range < trackGauge = {gauge} [m]"
        )]);
    }
}

// =============================================================================================
// 2. Physical edge cases, for every normalModel × tangentialModel

const NORMAL_MODELS: std::ops::RangeInclusive<i32> = 1..=7;
const TANGENTIAL_MODELS: std::ops::RangeInclusive<i32> = 1..=5;

/// Every (normalModel, tangentialModel) pair, with the context naming it in messages.
fn model_pairs() -> impl Iterator<Item = (i32, i32, String)> {
    NORMAL_MODELS.flat_map(|nm| {
        TANGENTIAL_MODELS.map(move |tm| (nm, tm, format!("normalModel {nm}, tangentialModel {tm}")))
    })
}

fn models(nm: i32, tm: i32) -> Vec<(&'static str, P)> {
    vec![("normalModel", P::I(nm)), ("tangentialModel", P::I(tm))]
}

fn side_vars(side: &str) -> Vec<&'static str> {
    wrc()
        .variables
        .iter()
        .filter(|v| v.causality == Causality::Output && v.name.starts_with(side))
        .map(|v| v.name)
        .collect()
}

/// |Fz + Q| within 1e−6 of Q (the load balance's tolerance, with room), or 1e−2 N for tiny loads.
#[track_caller]
fn assert_balanced(f: &Instance, side: &str, q: f64, context: &str) {
    let fz = f.real(&format!("{side}.Fz"));
    assert!(
        (fz + q).abs() <= 1e-6 * q + 1e-2,
        "{}: {side}.Fz = {fz} for a load of {q} N ({context})",
        f.name()
    );
}

/// Largest |F| / (μ Fn) accepted: FASTSIM's traction bound sums to μ Fn exactly on every grid
/// (fastsim.rs), so only rounding is allowed.
const COULOMB: f64 = 1.0 + 1e-9;

/// The largest |F| / (μ Fn) over the patches of one wheel (0 without patches).
fn traction_ratio(f: &Instance, side: &str, mu: f64) -> f64 {
    (1..=3)
        .map(|k| {
            let fnv = f.real(&format!("{side}.p{k}.Fn"));
            if fnv <= 0.0 {
                return 0.0;
            }
            let fx = f.real(&format!("{side}.p{k}.Fx"));
            let fy = f.real(&format!("{side}.p{k}.Fy"));
            fx.hypot(fy) / (mu * fnv)
        })
        .fold(0.0, f64::max)
}

#[test]
fn lift_off_and_re_contact() {
    for (nm, tm, ctx) in model_pairs() {
        let mut run = Run::new(initialized(
            wrc(),
            &name(&[&"liftOff", &nm, &tm]),
            &models(nm, tm),
        ));
        run.step_ok(&[("y", 0.002)]);
        assert_balanced(&run.f, "left", Q, &ctx);
        // Left wheel lifted: no patch, every left output but z zero; the right wheel carries.
        run.step_ok(&[("Qleft", 0.0)]);
        assert_eq!(run.f.integer("left.nPatches"), 0, "{ctx}");
        for var in side_vars("left.") {
            if var != "left.z" && var != "left.nPatches" {
                assert_eq!(run.f.real(var), 0.0, "{var} ({ctx})");
            }
        }
        assert_balanced(&run.f, "right", Q, &ctx);
        // Both lifted.
        run.step_ok(&[("Qright", 0.0)]);
        assert_eq!(
            (
                run.f.integer("left.nPatches"),
                run.f.integer("right.nPatches")
            ),
            (0, 0)
        );
        // Re-contact: as a fresh instance in that pose.
        run.step_ok(&[("Qleft", Q), ("Qright", Q)]);
        let fresh = initialized(wrc(), &name(&[&"liftOffFresh", &nm, &tm]), &models(nm, tm));
        let mut fresh = Run::new(fresh);
        fresh.step_ok(&[("y", 0.002)]);
        for side in ["left", "right"] {
            assert!(run.f.integer(&format!("{side}.nPatches")) >= 1, "{ctx}");
            assert_balanced(&run.f, side, Q, &ctx);
            for k in 1..=3 {
                let var = format!("{side}.p{k}.contactAngle");
                assert!(
                    (run.f.real(&var) - fresh.f.real(&var)).abs() < 1e-9,
                    "{var} after re-contact ({ctx})"
                );
            }
        }
        assert!(run.f.errors().is_empty());
    }
}

#[test]
fn tiny_and_large_loads() {
    for (nm, tm, ctx) in model_pairs() {
        let mut run = Run::new(initialized(
            wrc(),
            &name(&[&"loads", &nm, &tm]),
            &models(nm, tm),
        ));
        for q in [1e-3, 1.0, 1e3, Q, 3e5] {
            run.step_ok(&[("y", 0.002), ("Qleft", q), ("Qright", q)]);
            for side in ["left", "right"] {
                assert_balanced(&run.f, side, q, &format!("{ctx}, Q = {q}"));
                let n = run.f.integer(&format!("{side}.nPatches"));
                assert!((0..=3).contains(&n));
                for k in 1..=n {
                    assert!(
                        run.f.real(&format!("{side}.p{k}.area")) > 0.0,
                        "{ctx}, Q = {q}"
                    );
                }
            }
        }
        // The largest allowed load, 10 MN: the documented status (fmi2Warning: the approach,
        // 1.7 mm with Hertz, is beyond the 1 mm of `railcontact::wheelset::validity`), a message
        // naming the load, and finite outputs.
        let s = run.step(&[("Qleft", 1e7), ("Qright", 1e7)]);
        assert_eq!(s, WARNING, "{ctx}: {:?}", run.f.messages());
        run.f.assert_warning_logged(&[
            "implausible contact state",
            "limit",
            "= 10000000 N is far beyond wheel loads",
        ]);
        run.f.outputs();
    }
}

/// A prescribed position far into the rail — z = +50 mm, inside the declared range of `z` —
/// is not answered with fmi2OK: `fmi2DoStep` returns fmi2Warning with finite outputs and a
/// message naming the quantity, its value, the limit and the cause (`railcontact::wheelset::validity`:
/// a patch's approach above 1 mm). z = +2 mm (approach ≈ 1.8 mm, Fz ≈ 10 MN with Hertz) warns too;
/// z = +0.5 mm (approach 0.32 mm, within the limit) and the prescribed loads are OK again right
/// after: the warning does not stick. The lazy evaluation in `fmi2GetReal` and an absurd start
/// value at `fmi2ExitInitializationMode` warn the same way.
#[test]
fn implausible_states_warn_with_finite_outputs() {
    for nm in NORMAL_MODELS {
        let ctx = format!("normalModel {nm}");
        let mut params = models(nm, 1);
        params.push(("verticalMode", P::I(2)));
        let mut run = Run::new(initialized(wrc(), &name(&[&"implausible", &nm]), &params));
        for (z, expected) in [(0.05, WARNING), (5e-4, OK), (0.002, WARNING), (5e-4, OK)] {
            let s = run.step(&[("z", z)]);
            assert_eq!(s, expected, "{ctx}, z = {z}: {:?}", run.f.messages());
            let (get, out) = run.f.read_outputs();
            assert_eq!(
                get, OK,
                "{ctx}, z = {z}: outputs read once the step is done"
            );
            run.f.assert_finite(&out);
            if expected == WARNING {
                run.t += H; // a warning is a completed step
            }
        }
        run.f.assert_warning_logged(&[
            "step at t = 0:",
            "implausible contact state:",
            "wheel, patch 1:",
            "exceeds the limit",
            "prescribed position z = 0.05 m (verticalMode = 2) pushes the",
            "mm into the rail",
            "not physical",
        ]);
        assert!(
            run.f.warnings().iter().any(|m| m.contains("z = 0.002 m")),
            "{ctx}: {:?}",
            run.f.warnings()
        );
        assert!(run.f.errors().is_empty(), "{ctx}: {:?}", run.f.errors());
    }

    // Severe but real: 300 kN per wheel in flange contact (y = -8 mm, yaw 4 mrad) is OK for
    // every normal model (approaches 0.49-0.65 mm, pmax up to 10 GPa, well inside the limit).
    for nm in NORMAL_MODELS {
        let mut run = Run::new(initialized(
            wrc(),
            &name(&[&"heavyFlange", &nm]),
            &models(nm, 1),
        ));
        run.step_ok(&[
            ("y", -0.008),
            ("yaw", 0.004),
            ("Qleft", 3e5),
            ("Qright", 3e5),
        ]);
        assert!(run.f.warnings().is_empty(), "{:?}", run.f.warnings());
        let flange = (1..=run.f.integer("left.nPatches"))
            .map(|k| run.f.real(&format!("left.p{k}.contactAngle")))
            .fold(0.0f64, f64::max);
        assert!(
            flange > 0.6,
            "normalModel {nm}: no flange contact ({flange} rad)"
        );
    }

    // Hertz: the message's numbers are the outputs' (the approach of the deepest patch).
    let mut params = models(1, 1);
    params.push(("verticalMode", P::I(2)));
    let mut run = Run::new(initialized(wrc(), "implausible/numbers", &params));
    assert_eq!(run.step(&[("z", 0.05)]), WARNING);
    let penetration = run.f.real("left.p1.penetration");
    assert!(penetration > 0.04, "{penetration}");
    run.f.assert_warning_logged(&[
        &format!("left wheel, patch 1: penetration = {penetration:.4e} m exceeds the limit 1e-3 m"),
        &format!(
            "pushes the left wheel {:.3} mm into the rail",
            penetration * 1e3
        ),
    ]);

    // Evaluated lazily by fmi2GetReal after the input changed: fmi2Warning there, too.
    let f = initialized(wrc(), "implausible/get", &params);
    assert_eq!(f.set_real("z", 0.05), OK);
    let (s, out) = f.read_outputs();
    assert_eq!(s, WARNING, "{:?}", f.messages());
    f.assert_finite(&out);
    f.assert_warning_logged(&["fmi2Get: implausible contact state"]);

    // An absurd start: fmi2ExitInitializationMode warns, and the instance steps.
    let f = instantiate(wrc(), "implausible/init");
    assert_eq!(f.set_integer("verticalMode", 2), OK);
    assert_eq!(f.set_real("z", 0.05), OK);
    assert_eq!(f.setup_experiment(0.0, None), OK);
    assert_eq!(f.enter_initialization(), OK);
    assert_eq!(f.exit_initialization(), WARNING, "{:?}", f.messages());
    f.assert_warning_logged(&["fmi2ExitInitializationMode: implausible contact state"]);
    assert_eq!(f.step(0.0, H), WARNING);
    assert_eq!(f.set_real("z", 5e-4), OK);
    assert_eq!(f.step(H, H), OK, "{:?}", f.messages());
}

/// Runs `body` on its own thread and fails if it has not returned after `seconds` (a hang in
/// the FMU must fail the test, not block the suite).
fn within(seconds: u64, what: &str, body: impl FnOnce() + Send + 'static) {
    let (tx, rx) = std::sync::mpsc::channel();
    let handle = std::thread::spawn(move || {
        body();
        let _ = tx.send(());
    });
    match rx.recv_timeout(std::time::Duration::from_secs(seconds)) {
        Ok(()) | Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
            if let Err(panic) = handle.join() {
                std::panic::resume_unwind(panic);
            }
        }
        Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
            panic!("{what} did not return within {seconds} s (a hang)")
        }
    }
}

/// Regression: a load of 5e−324 N (the smallest subnormal) made the load iteration's first
/// approach underflow to 0 and its bracketing loop double 0 for ever — `fmi2DoStep` never
/// returned. Loads below 1e−6 N now count as a lifted wheel (docs/reliability.md).
#[test]
fn subnormal_and_tiny_loads_return() {
    within(300, "fmi2DoStep with a subnormal wheel load", || {
        for nm in NORMAL_MODELS {
            let mut run = Run::new(initialized(
                wrc(),
                &name(&[&"subnormal", &nm]),
                &models(nm, 1),
            ));
            for q in [
                5e-324, 1e-320, 1e-310, 1e-300, 1e-12, 9.99e-7, 1e-6, 1e-5, Q,
            ] {
                run.step_ok(&[("y", 0.002), ("Qleft", q), ("Qright", q)]);
                for side in ["left", "right"] {
                    assert_balanced(&run.f, side, q, &format!("normalModel {nm}, Q = {q}"));
                    if q < 1e-6 {
                        assert_eq!(run.f.integer(&format!("{side}.nPatches")), 0, "Q = {q}");
                    }
                }
            }
        }
    });
}

#[test]
fn standstill_gives_finite_creepages_and_a_spinning_wheel_slides() {
    for (nm, tm, ctx) in model_pairs() {
        let mut run = Run::new(initialized(
            wrc(),
            &name(&[&"standstill", &nm, &tm]),
            &models(nm, tm),
        ));
        // At rest: no creepage, no creep force (reference speed 0.01 m/s, docs/conventions.md).
        run.step_ok(&[("y", 0.002), ("vx", 0.0), ("omega", 0.0)]);
        for side in ["left", "right"] {
            assert_eq!(run.f.real(&format!("{side}.Fx")), 0.0, "{ctx}");
            assert_eq!(run.f.real(&format!("{side}.p1.xi")), 0.0, "{ctx}");
        }
        // A wheel spinning at standstill is in full sliding: |F| = μ Fn.
        run.step_ok(&[("omega", 5.0)]);
        for side in ["left", "right"] {
            let r = traction_ratio(&run.f, side, 0.3);
            assert!(
                (0.95..=COULOMB).contains(&r),
                "{side}: |F|/μFn = {r} ({ctx})"
            );
            // Friction opposes the slip: the force has the opposite sign of the creepage.
            let (xi, fx) = (
                run.f.real(&format!("{side}.p1.xi")),
                run.f.real(&format!("{side}.Fx")),
            );
            assert!(
                xi.abs() > 1.0 && xi * fx < 0.0,
                "{side}: xi = {xi}, Fx = {fx} ({ctx})"
            );
        }
        // Backwards and very fast: still finite.
        run.step_ok(&[("vx", -30.0), ("omega", -65.0)]);
        run.step_ok(&[("vx", 1000.0), ("omega", 10000.0)]);
    }
}

#[test]
fn creepage_far_into_saturation_is_bounded_by_friction() {
    for (nm, tm, ctx) in model_pairs() {
        let mut params = models(nm, tm);
        params.push(("creepageMode", P::I(2)));
        params.push(("planarPatch", P::B(tm % 2 == 0)));
        let mut run = Run::new(initialized(
            wrc(),
            &name(&[&"saturation", &nm, &tm]),
            &params,
        ));
        for (xi, eta, phi) in [
            (10.0, 0.0, 0.0),
            (0.0, -10.0, 0.0),
            (-10.0, 10.0, 1000.0),
            (0.0, 0.0, -1000.0),
        ] {
            run.step_ok(&[("y", 0.002), ("xi", xi), ("eta", eta), ("phi", phi)]);
            for side in ["left", "right"] {
                let r = traction_ratio(&run.f, side, 0.3);
                assert!(
                    r <= COULOMB,
                    "{side}: |F|/μFn = {r} ({ctx}, {xi} {eta} {phi})"
                );
                if phi == 0.0 {
                    assert!(r >= 0.95, "{side}: |F|/μFn = {r} ({ctx}, {xi} {eta})");
                }
                assert_balanced(&run.f, side, Q, &ctx);
            }
            if xi > 0.0 {
                assert!(run.f.real("right.p1.Fx") < 0.0, "rail pushes back ({ctx})");
            }
        }
    }
}

/// Ramps `y` (and `yaw`) until the step is discarded; returns the y of the last good step.
fn ramp_until_discard(run: &mut Run, ys: &[f64], yaw: f64, ctx: &str) -> f64 {
    let mut last = None;
    let mut largest_angle = 0.0f64;
    for &y in ys {
        let s = run.step(&[("y", y), ("yaw", yaw)]);
        if s == DISCARD {
            let good = last.unwrap_or_else(|| panic!("discarded at once ({ctx})"));
            let at_good = run.f.read_outputs();
            // Terminated at the last successful time; outputs stay those of the last good step.
            assert_eq!(run.f.terminated(), (OK, true), "{ctx}");
            assert_eq!(run.f.last_successful_time(), (OK, run.t), "{ctx}");
            let message = run.f.messages().last().cloned().expect("a message");
            assert_eq!(message.status, DISCARD, "{ctx}");
            assert!(message.text.contains("cannot continue"), "{message:?}");
            assert_eq!(at_good.0, OK);
            run.f.assert_finite(&at_good.1);
            // The instance cannot step on; it can terminate and reset.
            assert_eq!(run.f.step(run.t, H), ERROR, "{ctx}");
            assert!(
                largest_angle > 0.6,
                "no flange contact before the discard ({ctx})"
            );
            return good;
        }
        assert_eq!(s, OK, "y = {y} ({ctx}): {:?}", run.f.messages());
        let out = run.f.outputs();
        run.f.assert_finite(&out);
        largest_angle = (1..=3)
            .map(|k| run.f.real(&format!("right.p{k}.contactAngle")))
            .fold(largest_angle, f64::max);
        last = Some(y);
    }
    panic!("never discarded up to y = {:?} ({ctx})", ys.last());
}

#[test]
fn flange_climb_towards_and_past_the_end_of_the_profile_discards() {
    let ys: Vec<f64> = (0..=50).map(|i| i as f64 * 1e-3).collect();
    for (nm, tm, ctx) in model_pairs() {
        let f = instantiate(wrc(), &name(&[&"climb", &nm, &tm]));
        for (var, v) in models(nm, tm) {
            assert_eq!(set(&f, var, &v), OK);
        }
        assert_eq!(f.setup_experiment(0.0, Some(1.0)), OK);
        assert_eq!(f.enter_initialization(), OK);
        assert_eq!(f.exit_initialization(), OK);
        let mut run = Run::new(f);
        let good = ramp_until_discard(&mut run, &ys, 0.0, &ctx);
        assert!(good >= 0.008, "discarded already after y = {good} ({ctx})");
        assert_eq!(run.f.terminate(), OK);
        assert_eq!(run.f.reset(), OK);
        run.f.init();
        assert_eq!(run.f.step(0.0, H), OK, "{ctx}: usable after reset");
    }
}

#[test]
fn poses_that_leave_the_profiles_discard() {
    let poses: [&[(&str, f64)]; 5] = [
        &[("y", 0.05)],
        &[("y", -0.05)],
        &[("y", -0.05), ("yaw", 0.2)],
        &[("roll", 0.1)],
        &[("roll", -0.1)],
    ];
    for nm in NORMAL_MODELS {
        for tm in [1, 3] {
            for pose in poses {
                let ctx = format!("normalModel {nm}, tangentialModel {tm}, {pose:?}");
                let mut run = Run::new(initialized(
                    wrc(),
                    &name(&[&"offRail", &nm, &tm, &format!("{pose:?}")]),
                    &models(nm, tm),
                ));
                let before = run.step_ok(&[]);
                assert_eq!(run.step(pose), DISCARD, "{ctx}");
                assert_eq!(run.f.terminated(), (OK, true));
                let (s, after) = run.f.read_outputs();
                assert_eq!(s, OK);
                assert_eq!(
                    bits(&after),
                    bits(&before),
                    "last good outputs kept ({ctx})"
                );
            }
        }
    }
}

/// A hollow (concave) wheel tread z = y²/(2R) [mm] over the whole profile width: against the
/// UIC60 crown (R = 300 mm, rail not inclined) R = 300 mm is conformal (zero relative lateral
/// curvature across the patch), smaller R gives negative curvature at the centre.
fn hollow_wheel(dir: &Path, radius_mm: f64) -> String {
    let mut text = String::from("y [mm], z [mm]\n");
    for i in 0..=260 {
        let y = -70.0 + 0.5 * i as f64;
        text += &format!("{y}, {}\n", y * y / (2.0 * radius_mm));
    }
    write(dir, &format!("hollow{radius_mm}.csv"), text.as_bytes())
}

#[test]
fn conformal_contact() {
    let dir = temp_dir("conformal");
    for radius in [300.0, 250.0, 150.0] {
        let wheel = hollow_wheel(&dir, radius);
        for (nm, tm, ctx) in model_pairs() {
            let ctx = format!("hollow R{radius}, {ctx}");
            let mut params = models(nm, tm);
            params.push(("wheelProfile", P::S(wheel.clone())));
            params.push(("railInclination", P::R(0.0)));
            let mut run = Run::new(initialized(
                wrc(),
                &name(&[&"conformal", &radius, &nm, &tm]),
                &params,
            ));
            for y in [0.0, 0.001, 0.003] {
                run.step_ok(&[("y", y)]);
                for side in ["left", "right"] {
                    assert_balanced(&run.f, side, Q, &ctx);
                    assert!(run.f.real(&format!("{side}.p1.area")) > 0.0, "{ctx}");
                }
            }
        }
    }
}

#[test]
fn prescribed_position_from_lifted_to_deep() {
    for nm in NORMAL_MODELS {
        let mut params = models(nm, 1);
        params.push(("verticalMode", P::I(2)));
        let mut run = Run::new(initialized(wrc(), &name(&[&"position", &nm]), &params));
        // Lifted 1 cm: no contact, zero forces.
        run.step_ok(&[("z", -0.01)]);
        assert_eq!(
            (
                run.f.integer("left.nPatches"),
                run.f.integer("right.nPatches")
            ),
            (0, 0)
        );
        assert_eq!((run.f.real("left.Fz"), run.f.real("right.Fz")), (0.0, 0.0));
        // Lowered step by step: the load never decreases and ends positive, never NaN.
        let mut previous = 0.0;
        // (At the nominal height the centred wheel clears its rail by 0.18 mm: the taping line
        // lies above the mounted rail's top, the contact point beside it.)
        for z in [-1e-3, -2e-4, 0.0, 1e-4, 2e-4, 3e-4] {
            run.step_ok(&[("z", z)]);
            let fz = -run.f.real("right.Fz");
            assert!(
                fz >= previous,
                "normalModel {nm}: z = {z}: load {fz} after {previous}"
            );
            previous = fz;
        }
        assert!(previous > 0.0, "normalModel {nm}: no contact at z = 0.3 mm");
    }
}

#[test]
fn hertz_contact_extremes_give_finite_bounded_forces() {
    let params = [
        vec![],
        vec![("tractionBound", P::I(2)), ("flexibility", P::I(3))],
        vec![("flexibility", P::I(2)), ("nx", P::I(1)), ("ny", P::I(1))],
        vec![("mu", P::R(10.0)), ("nu", P::R(0.0))],
        vec![("mu", P::R(1e-9)), ("nu", P::R(0.5)), ("E", P::R(1e6))],
    ];
    for (i, p) in params.iter().enumerate() {
        let mu = p
            .iter()
            .find_map(|(n, v)| match (n, v) {
                (&"mu", P::R(x)) => Some(*x),
                _ => None,
            })
            .unwrap_or(0.3);
        // A 1 × 1 FASTSIM grid sums the traction bound over one 2a × 2b element at the peak
        // pressure: 6/π μN (known discretization error of fastsim.rs; docs/reliability.md).
        let coarse = p.iter().any(|(n, v)| matches!((n, v), (&"nx", P::I(1))));
        let bound = if coarse {
            6.0 / std::f64::consts::PI
        } else {
            1.0
        } * COULOMB;
        let mut run = Run::new(initialized(hc(), &name(&[&"hertzExtremes", &i]), p));
        for n in [0.0, 5e-324, 1e-300, 1e-6, 1e8] {
            for (a, b) in [(1e-3, 1e-3), (1e-3, 1e5), (1e5, 1e-3), (1e5, 1e5)] {
                for (xi, eta, phi) in [
                    (0.0, 0.0, 0.0),
                    (10.0, -10.0, 1000.0),
                    (1e-300, 0.0, -1000.0),
                ] {
                    for v in [0.0, 1e3] {
                        let out = run.step_ok(&[
                            ("N", n),
                            ("A", a),
                            ("B", b),
                            ("xi", xi),
                            ("eta", eta),
                            ("phi", phi),
                            ("V", v),
                        ]);
                        let ctx =
                            format!("{p:?}: N {n} A {a} B {b} creepage {xi} {eta} {phi} V {v}");
                        let (fx, fy) = (run.f.real("Fx"), run.f.real("Fy"));
                        assert!(fx.hypot(fy) <= mu * n * bound + 1e-300, "{ctx}: {out:?}");
                        assert!(run.f.real("frictionalPower") >= 0.0, "{ctx}");
                        let adhesion = run.f.real("adhesionFraction");
                        assert!((0.0..=1.0).contains(&adhesion), "{ctx}");
                        if n == 0.0 {
                            assert_eq!((fx, fy, run.f.real("a")), (0.0, 0.0, 0.0), "{ctx}");
                        }
                    }
                }
            }
        }
    }
}

// =============================================================================================
// 3. FMI call-order misuse

#[test]
fn the_state_machine_refuses_calls_out_of_order() {
    for info in [hc(), wrc()] {
        let id = info.model_identifier;
        let f = instantiate(info, &name(&[&"order", &id]));
        let input = info
            .variables
            .iter()
            .find(|v| v.causality == Causality::Input && v.ty == VarType::Real)
            .expect("a Real input");
        let fixed = var(info, "E");
        // Instantiated: no step, no get, no exit, no terminate, no status.
        assert_eq!(f.step(0.0, H), ERROR, "{id}: DoStep before initialization");
        assert_eq!(
            f.get_real_vr(input.vr).0,
            ERROR,
            "{id}: GetReal when instantiated"
        );
        assert_eq!(f.exit_initialization(), ERROR, "{id}: exit without enter");
        assert_eq!(
            f.terminate(),
            ERROR,
            "{id}: terminate before initialization"
        );
        assert_eq!(
            f.terminated().0,
            ERROR,
            "{id}: status before initialization"
        );
        f.assert_error_logged(&["fmi2DoStep must not be called in state Instantiated"]);
        // Initialization mode: no step, no second enter, no setup.
        assert_eq!(f.setup_experiment(0.0, None), OK);
        assert_eq!(f.enter_initialization(), OK);
        assert_eq!(f.enter_initialization(), ERROR, "{id}: enter twice");
        assert_eq!(
            f.setup_experiment(0.0, None),
            ERROR,
            "{id}: setup in initialization mode"
        );
        assert_eq!(f.step(0.0, H), ERROR, "{id}: DoStep in initialization mode");
        assert_eq!(
            f.set_real(fixed.name, 2.0e11),
            OK,
            "fixed parameters settable until exit"
        );
        assert_eq!(f.exit_initialization(), OK);
        // Step complete: fixed parameters and outputs cannot be set; inputs can.
        assert_eq!(
            f.set_real(fixed.name, 2.0e11),
            ERROR,
            "{id}: fixed parameter after init"
        );
        f.assert_error_logged(&["E (Parameter, Fixed) cannot be set in state StepComplete"]);
        let output = info
            .variables
            .iter()
            .find(|v| v.causality == Causality::Output && v.ty == VarType::Real)
            .expect("a Real output");
        assert_eq!(f.set_real_vr(output.vr, 1.0), ERROR, "{id}: set an output");
        assert_eq!(f.set_real_vr(input.vr, f.get_real_vr(input.vr).1), OK);
        assert_eq!(f.exit_initialization(), ERROR, "{id}: exit twice");
        assert_eq!(f.enter_initialization(), ERROR, "{id}: enter after init");
        // Bad steps: zero, negative, NaN, past the stop time is checked below.
        for (t, h) in [
            (0.0, 0.0),
            (0.0, -H),
            (0.0, f64::NAN),
            (f64::NAN, H),
            (f64::INFINITY, H),
            (0.0, f64::INFINITY),
            (f64::MAX, f64::MAX),
        ] {
            assert_eq!(f.step(t, h), ERROR, "{id}: DoStep({t}, {h})");
        }
        f.assert_error_logged(&["currentCommunicationPoint = NaN"]);
        // A communication point off the instance's time is only a warning.
        assert_eq!(f.step(0.5, H), WARNING, "{id}");
        assert_eq!(
            f.last_successful_time(),
            (OK, 0.5 + H),
            "time follows the host"
        );
        // Terminated: only get, status, reset, free.
        assert_eq!(f.terminate(), OK);
        assert_eq!(f.terminate(), ERROR, "{id}: terminate twice");
        assert_eq!(f.step(0.5 + H, H), ERROR, "{id}: DoStep after terminate");
        assert_eq!(
            f.set_real_vr(input.vr, 0.0),
            ERROR,
            "{id}: set after terminate"
        );
        assert_eq!(
            f.read_outputs().0,
            OK,
            "{id}: outputs readable after terminate"
        );
        assert_eq!(f.reset(), OK);
        assert_eq!(
            f.set_real(fixed.name, 2.0e11),
            OK,
            "{id}: parameters settable after reset"
        );
        f.init();
        assert_eq!(f.step(0.0, H), OK);
    }
}

#[test]
fn stepping_past_the_stop_time_is_an_error() {
    let f = instantiate(hc(), "stopTime");
    assert_eq!(f.setup_experiment(0.0, Some(2.0 * H)), OK);
    assert_eq!(f.enter_initialization(), OK);
    assert_eq!(f.exit_initialization(), OK);
    assert_eq!(f.step(0.0, H), OK);
    assert_eq!(f.step(H, H), OK);
    assert_eq!(f.step(2.0 * H, H), ERROR);
    f.assert_error_logged(&["goes past stopTime"]);
    let g = instantiate(hc(), "badSetup");
    assert_eq!(
        g.setup_experiment(0.0, Some(-1.0)),
        ERROR,
        "stop before start"
    );
}

#[test]
fn unknown_value_references_and_wrong_types_are_errors() {
    for info in [hc(), wrc()] {
        let f = initialized(info, &name(&[&"unknownVr", &info.model_identifier]), &[]);
        let n = info.variables.len() as u32;
        for vr in [n, n + 1, 10_000, u32::MAX] {
            assert_eq!(f.get_real_vr(vr).0, ERROR, "GetReal({vr})");
            assert_eq!(f.set_real_vr(vr, 0.0), ERROR, "SetReal({vr})");
            let mut k = 0;
            // SAFETY: one value reference, one slot.
            let s = unsafe { (f.functions().fmi2GetInteger)(f.component(), &vr, 1, &mut k) };
            assert_eq!(Status::from(s), ERROR, "GetInteger({vr})");
        }
        f.assert_error_logged(&[&format!("unknown value reference {}", u32::MAX)]);
        // A Real read of an Integer or String variable.
        for v in info.variables.iter().filter(|v| v.ty != VarType::Real) {
            assert_eq!(f.get_real_vr(v.vr).0, ERROR, "{} as Real", v.name);
        }
        // A mixed call with one bad reference fails as a whole and reports it.
        let good = info.variables[0].vr;
        let vrs = [good, n];
        let mut out = [0.0; 2];
        assert_eq!(f.get_reals(&vrs, &mut out), ERROR);
        // NULL arrays with nvr > 0 are errors; with nvr = 0 a no-op.
        let (c, get, set) = (
            f.component(),
            f.functions().fmi2GetReal,
            f.functions().fmi2SetReal,
        );
        // SAFETY: NULL arrays are checked before use.
        unsafe {
            use std::ptr::{null, null_mut};
            assert_eq!(Status::from(get(c, null(), 1, out.as_mut_ptr())), ERROR);
            assert_eq!(Status::from(set(c, &good, 1, null())), ERROR);
            assert_eq!(Status::from(get(c, null(), 0, null_mut())), OK);
            assert_eq!(Status::from(set(c, null(), 0, null())), OK);
        }
        f.assert_error_logged(&["NULL array with nvr = 1"]);
        assert_eq!(f.step(0.0, H), OK, "usable after the rejected calls");
    }
}

#[test]
fn null_and_freed_instances_are_refused_and_a_second_free_is_ignored() {
    let f = initialized(wrc(), "doubleFree", &[]);
    let (c, fmi) = (f.component(), *f.functions());
    // SAFETY: a NULL component is checked before use.
    unsafe {
        assert_eq!(
            Status::from((fmi.fmi2DoStep)(std::ptr::null_mut(), 0.0, H, 1)),
            ERROR
        );
        (fmi.fmi2FreeInstance)(std::ptr::null_mut());
    }
    // The first fmi2FreeInstance.
    f.free();
    // SAFETY: c was freed just above; the calls are refused before the pointer is dereferenced
    // (the instance registry), as long as no new instance got the same address — none is
    // created in between.
    unsafe {
        (fmi.fmi2FreeInstance)(c);
        assert_eq!(Status::from((fmi.fmi2DoStep)(c, 0.0, H, 1)), ERROR);
        let vr = 0u32;
        let mut x = 0.0;
        assert_eq!(Status::from((fmi.fmi2GetReal)(c, &vr, 1, &mut x)), ERROR);
        assert_eq!(Status::from((fmi.fmi2Reset)(c)), ERROR);
        let mut foreign = 0u64;
        let fake: fmi_host::sys::fmi2Component = (&mut foreign as *mut u64).cast();
        assert_eq!(
            Status::from((fmi.fmi2Terminate)(fake)),
            ERROR,
            "a pointer that is not an instance"
        );
        (fmi.fmi2FreeInstance)(fake);
    }
}

#[test]
fn instantiation_is_refused_with_a_message() {
    for (label, guid) in [
        ("wrongGuid", "{00000000-0000-0000-0000-000000000000}"),
        ("emptyGuid", ""),
    ] {
        let refused = linked::fmu(wrc()).instantiate_as(label, guid, None);
        let Err(fmi_host::Error::Instantiate { messages, .. }) = refused else {
            panic!("{label}: instantiated");
        };
        assert!(
            messages
                .iter()
                .any(|m| m.status == ERROR && m.text.contains("does not match")),
            "{messages:?}"
        );
    }
    // No resource location: the built-in profiles still work (docs/integration.md, "Bundled
    // profiles and `resourceLocation`").
    let fmu = linked::fmu(wrc());
    let f = fmu
        .instantiate_as("noResources", wrc().guid, None)
        .expect("instantiated");
    f.init();
    assert_eq!(f.step(0.0, H), OK);
    let f = fmu
        .instantiate_as("oddResources", wrc().guid, Some("http://example.org/x"))
        .expect("instantiated");
    f.init();
}

#[test]
fn reset_and_re_initialization_with_other_parameters_match_a_fresh_instance() {
    let f = initialized(wrc(), "reinit", &[]);
    let mut run = Run::new(f);
    run.step_ok(&[("y", 0.004)]);
    // From every state that allows it: after steps, after a discard, after an error.
    assert_eq!(run.step(&[("y", 0.05)]), DISCARD);
    assert_eq!(run.f.reset(), OK);
    for (var, v) in models(6, 3) {
        assert_eq!(set(&run.f, var, &v), OK);
    }
    run.f.init();
    run.t = 0.0;
    let again = run.step_ok(&[("y", 0.003)]);
    let mut fresh = Run::new(initialized(wrc(), "reinitFresh", &models(6, 3)));
    let expected = fresh.step_ok(&[("y", 0.003)]);
    assert_eq!(bits(&again), bits(&expected));
}

// =============================================================================================
// 4. FMU states

/// Runs `steps` steps of the random walk from `seed`, starting at step `from`, returning the
/// outputs of every step.
fn walk(f: &Instance, walk: &mut PoseWalk, from: usize, steps: usize) -> Vec<Vec<f64>> {
    (from..from + steps)
        .map(|k| {
            let x = walk.next();
            assert_eq!(f.set_reals(&walk.vrs, &x), OK, "{}", f.name());
            let s = f.step(k as f64 * H, H);
            assert_eq!(
                s,
                OK,
                "{} step {k} with {x:?}: {:?}",
                f.name(),
                f.messages()
            );
            f.outputs()
        })
        .collect()
}

/// A state saved at step 1 000 of a random walk of y, yaw, roll, loads and speeds and restored
/// reproduces the outputs of steps 1 000–2 000 bit for bit — in the same instance (after it ran on
/// to 2 000, so any internal state not in the FMU state differs) and, serialized, in a fresh
/// instance.
#[test]
fn a_state_saved_at_step_1000_reproduces_steps_1000_to_2000_bit_for_bit() {
    for (nm, tm) in [(1, 1), (4, 2), (6, 3)] {
        let params = models(nm, tm);
        let f = initialized(wrc(), &name(&[&"state1000", &nm]), &params);
        let mut pose = PoseWalk::new(wrc(), 2024 + nm as u64);
        walk(&f, &mut pose, 0, 1000);
        let state = f.get_state().unwrap();
        let serialized = f.serialized_state().unwrap();
        let pose_at_1000 = pose.clone();
        let first = walk(&f, &mut pose, 1000, 1000);

        assert_eq!(f.set_state(&state), OK);
        let again = walk(&f, &mut pose_at_1000.clone(), 1000, 1000);
        for (k, (a, b)) in first.iter().zip(&again).enumerate() {
            assert_eq!(
                bits(a),
                bits(b),
                "normalModel {nm}: step {} differs after SetFMUstate",
                1000 + k
            );
        }

        let g = instantiate(wrc(), &name(&[&"state1000fresh", &nm]));
        assert_eq!(g.restore_serialized(&serialized), OK, "{:?}", g.errors());
        let fresh = walk(&g, &mut pose_at_1000.clone(), 1000, 1000);
        for (k, (a, b)) in first.iter().zip(&fresh).enumerate() {
            assert_eq!(
                bits(a),
                bits(b),
                "normalModel {nm}: step {} differs in a fresh instance",
                1000 + k
            );
        }
        assert_eq!(state.free().0, OK);
        assert!(f.errors().is_empty() && g.errors().is_empty());
    }
}

#[test]
fn hertz_contact_state_round_trip_over_a_random_walk() {
    let f = initialized(hc(), "hertzState", &[]);
    let vrs: Vec<u32> = ["N", "A", "B", "xi", "eta", "phi", "V"]
        .iter()
        .map(|n| f.vr(n))
        .collect();
    let mut rng = Rng::new(7);
    let mut inputs = move || {
        let mut u = || 0.5 * (1.0 + rng.signed_unit());
        [
            1e5 * u(),
            0.5 + u(),
            2.0 + u(),
            1e-2 * (u() - 0.5),
            1e-2 * (u() - 0.5),
            u() - 0.5,
            30.0 * u(),
        ]
    };
    let run = |f: &Instance, from: usize, xs: &[[f64; 7]]| -> Vec<Vec<f64>> {
        xs.iter()
            .enumerate()
            .map(|(i, x)| {
                assert_eq!(f.set_reals(&vrs, x), OK);
                assert_eq!(f.step((from + i) as f64 * H, H), OK);
                f.outputs()
            })
            .collect()
    };
    let before: Vec<[f64; 7]> = (0..300).map(|_| inputs()).collect();
    let after: Vec<[f64; 7]> = (0..300).map(|_| inputs()).collect();
    run(&f, 0, &before);
    let saved = f.serialized_state().unwrap();
    let first = run(&f, 300, &after);
    assert_eq!(f.restore_serialized(&saved), OK);
    let again = run(&f, 300, &after);
    assert_eq!(
        first
            .concat()
            .iter()
            .map(|x| x.to_bits())
            .collect::<Vec<_>>(),
        again
            .concat()
            .iter()
            .map(|x| x.to_bits())
            .collect::<Vec<_>>()
    );
}

/// FNV-1a 64, as the FMU checksums its serialized states (to build a state with a foreign
/// GUID but a valid checksum).
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

#[test]
fn corrupted_serialized_states_are_rejected_and_change_nothing() {
    let f = initialized(wrc(), "corrupt", &[("normalModel", P::I(6))]);
    let mut pose = PoseWalk::new(wrc(), 99);
    walk(&f, &mut pose, 0, 20);
    let good = f.serialized_state().unwrap();
    let outputs = f.outputs();
    let n = good.len();
    let mut rejected = 0usize;
    let mut expect_rejected = |bytes: &[u8], what: &str| {
        let (s, state) = f.deserialize(bytes);
        assert_eq!(s, ERROR, "{what} accepted");
        assert!(state.is_none(), "{what}: a state was allocated");
        rejected += 1;
    };
    // Every truncation, and one byte more.
    for len in 0..n {
        expect_rejected(&good[..len], &format!("truncated to {len} of {n} bytes"));
    }
    let mut longer = good.clone();
    longer.push(0);
    expect_rejected(&longer, "one byte longer");
    // Every single byte flipped (two patterns).
    for i in 0..n {
        for mask in [0x01u8, 0xFF] {
            let mut bad = good.clone();
            bad[i] ^= mask;
            expect_rejected(&bad, &format!("byte {i} ^ {mask:#04x}"));
        }
    }
    assert_eq!(rejected, n + 1 + 2 * n);
    let errors = f.errors();
    assert!(
        errors.iter().any(|m| m.contains("checksum mismatch")),
        "{:?}",
        &errors[..3]
    );
    assert!(errors
        .iter()
        .any(|m| m.contains("not a railcontact FMU state")));
    // A well-formed state of another FMU (its GUID), and this FMU's state with a foreign GUID
    // and a valid checksum.
    let other = initialized(hc(), "corruptOther", &[]);
    let foreign = other.serialized_state().unwrap();
    assert_eq!(f.deserialize(&foreign).0, ERROR);
    f.assert_error_logged(&["FMU state belongs to GUID", hc().guid]);
    let mut renamed = good.clone();
    let at = renamed
        .windows(wrc().guid.len())
        .position(|w| w == wrc().guid.as_bytes())
        .expect("the GUID is in the state");
    renamed[at + 1] = if renamed[at + 1] == b'0' { b'1' } else { b'0' };
    let body = renamed.len() - 8;
    let sum = fnv1a(&renamed[..body]).to_le_bytes();
    renamed[body..].copy_from_slice(&sum);
    assert_eq!(f.deserialize(&renamed).0, ERROR);
    f.assert_error_logged(&["FMU state belongs to GUID"]);
    // Nothing changed: the same outputs, and the good state still restores.
    assert_eq!(bits(&f.outputs()), bits(&outputs));
    assert_eq!(f.restore_serialized(&good), OK);
    assert_eq!(bits(&f.outputs()), bits(&outputs));
}

// =============================================================================================
// 5. Many instances

/// 8 configurations: normal and tangential models and a seed each.
fn configurations() -> Vec<(i32, i32, u64)> {
    (0..8)
        .map(|i| (1 + i % 7, 1 + (i * 3 / 2) % 5, 1000 + i as u64))
        .collect()
}

fn run_alone(
    i: usize,
    (nm, tm, seed): (i32, i32, u64),
    steps: usize,
    label: &str,
) -> Vec<Vec<f64>> {
    let f = initialized(wrc(), &name(&[&label, &i]), &models(nm, tm));
    walk(&f, &mut PoseWalk::new(wrc(), seed), 0, steps)
}

/// [`run_alone`] of each configuration.
fn run_each_alone(configs: &[(i32, i32, u64)], steps: usize, label: &str) -> Vec<Vec<Vec<f64>>> {
    configs
        .iter()
        .enumerate()
        .map(|(i, c)| run_alone(i, *c, steps, label))
        .collect()
}

/// Each step's outputs of `got` equal those of `want` bit for bit.
fn assert_same_bits(got: &[Vec<f64>], want: &[Vec<f64>], what: &str) {
    for (k, (a, b)) in got.iter().zip(want).enumerate() {
        assert_eq!(bits(a), bits(b), "{what} step {k}");
    }
}

#[test]
fn eight_instances_interleaved_in_one_thread_match_each_alone() {
    let steps = 150;
    let configs = configurations();
    let alone = run_each_alone(&configs, steps, "alone");
    let fmus: Vec<Instance> = configs
        .iter()
        .enumerate()
        .map(|(i, (nm, tm, _))| initialized(wrc(), &name(&[&"together", &i]), &models(*nm, *tm)))
        .collect();
    let mut walks: Vec<PoseWalk> = configs.iter().map(|c| PoseWalk::new(wrc(), c.2)).collect();
    let mut together: Vec<Vec<Vec<f64>>> = vec![Vec::new(); fmus.len()];
    for k in 0..steps {
        for (i, f) in fmus.iter().enumerate() {
            together[i].extend(walk(f, &mut walks[i], k, 1));
        }
    }
    for i in 0..fmus.len() {
        assert_eq!(together[i].len(), steps);
        assert_same_bits(
            &together[i],
            &alone[i],
            &format!("instance {i} ({:?})", configs[i]),
        );
    }
    assert_ne!(alone[0], alone[1], "the configurations differ");
}

#[test]
fn eight_instances_in_parallel_threads_match_each_alone() {
    let steps = 150;
    let configs = configurations();
    let alone = run_each_alone(&configs, steps, "aloneT");
    let threads: Vec<_> = configs
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let c = *c;
            std::thread::spawn(move || run_alone(i, c, steps, "thread"))
        })
        .collect();
    for (i, t) in threads.into_iter().enumerate() {
        assert_same_bits(
            &t.join().expect("thread"),
            &alone[i],
            &format!("thread {i}"),
        );
    }
    // One instance handed from thread to thread, one call at a time.
    let f = initialized(wrc(), "handedOver", &[]);
    let mut pose = PoseWalk::new(wrc(), configs[0].2);
    let mut outputs = Vec::new();
    let mut f = Some(f);
    for k in 0..10 {
        let (g, out, p) = std::thread::spawn({
            let g = f.take().expect("instance");
            let mut p = std::mem::replace(&mut pose, PoseWalk::new(wrc(), 0));
            move || {
                let out = walk(&g, &mut p, k, 1);
                (g, out, p)
            }
        })
        .join()
        .expect("thread");
        outputs.extend(out);
        pose = p;
        f = Some(g);
    }
    let reference = run_alone(99, (1, 1, configs[0].2), 10, "handedOverAlone");
    assert_eq!(outputs, reference);
}

// =============================================================================================
// Regressions of the bugs A–D of docs/reliability.md ("Bugs found").

/// The strip models returned fmi2OK with the prescribed load not carried:
/// (a) ANALYN with kinematic creepages: the creep fixed point stopped after its pass limit
///     (wheelset.rs `creep_passes`, `CREEP_PASSES` = 12) 6.6 N short of 83 kN;
/// (b) STRIPES-A&B and ANALYN in yawed flange contact: no strip in contact, the wheel lowered
///     by 32 mm, nPatches = 0, Fz = 0 (the yawed wheel's lowest-point Newton oscillated);
/// (c) ANALYN in flange contact near two-point contact, without creepage: 18 % of the load
///     missing (strips past the rail's fold had a gap of −0.3 mm; the soak's random walk met
///     it at step 3 991).
/// A load the model cannot carry is now refused with fmi2Discard (wheelset.rs `check_balance`).
#[test]
fn strip_models_carry_the_prescribed_load_in_yawed_and_two_point_contact() {
    let pose = [
        ("y", 0.0022194094633860083),
        ("yaw", -0.003178205887356309),
        ("roll", -0.0008349859312849373),
        ("Qleft", 81867.98548675612),
        ("Qright", 82969.87874821029),
        ("vx", 8.44411478056185),
        ("vy", 0.08670452889942926),
        ("yawRate", 0.10107005338463664),
        ("omega", 18.391453018572204),
    ];
    let mut run = Run::new(initialized(wrc(), "knownBugCreep", &models(6, 1)));
    run.step_ok(&pose);
    assert_balanced(&run.f, "right", pose[4].1, "ANALYN, kinematic creepage");
    let mut params = models(6, 1);
    params.push(("creepageMode", P::I(2)));
    let mut run = Run::new(initialized(wrc(), "knownBugTwoPoint", &params));
    let q = 92536.29825032441;
    run.step_ok(&[
        ("y", 0.005764834807364837),
        ("yaw", 0.0036803000335407336),
        ("roll", -0.0017719845820689645),
        ("Qright", q),
    ]);
    assert_balanced(&run.f, "right", q, "ANALYN near two-point contact");
    for (nm, yaw) in NORMAL_MODELS.flat_map(|nm| [0.02, 0.05, 0.1].map(|yaw| (nm, yaw))) {
        let mut run = Run::new(initialized(
            wrc(),
            &name(&[&"knownBugYaw", &nm]),
            &models(nm, 1),
        ));
        run.step_ok(&[("y", 0.008), ("yaw", yaw)]);
        assert!(
            run.f.integer("right.nPatches") >= 1,
            "normalModel {nm}, yaw {yaw}: no patch"
        );
        assert_balanced(&run.f, "right", Q, &format!("normalModel {nm}, yaw {yaw}"));
    }
}

/// Two poses of the ANALYN soak (seed 20 240 601) that earlier versions of the strip layout
/// failed, each from a cold start at the default strips. Step 111 358: the half-strip first layout put
/// one strip centre in a notch of the right wheel's patch, and the restriping made two patches
/// with overlapping strip ranges over the same contact (each run's range reaches one old strip
/// beyond it): their forces added up — 17 % too much where the balance could not compensate,
/// a wheel lifted by the double count where it could. Runs one strip apart are now one run: one
/// patch, as at 20 and 40 strips. Step 114 652: plane projections continued from the
/// neighbouring strip's converged point followed the rail onto another branch, and the left
/// wheel carried nothing (reverted to the tangent start).
#[test]
fn analyn_soak_poses_of_the_speed_work_carry_their_loads() {
    let poses: [[f64; 9]; 2] = [
        [
            0.006499759647372999,
            -0.00010739958479321604,
            -0.0018114900061986497,
            135011.6290655077,
            78420.34485277129,
            31.192129148785668,
            -0.026691806856716613,
            -0.17383265086475136,
            67.737954341668,
        ],
        [
            -0.006127203467362513,
            0.002602038334723795,
            0.0019042527319006967,
            127249.81124040764,
            147708.18576791493,
            30.389849588440168,
            0.09547994305127466,
            -0.1447425842461549,
            66.1359092732993,
        ],
    ];
    let names = [
        "y", "yaw", "roll", "Qleft", "Qright", "vx", "vy", "yawRate", "omega",
    ];
    for (k, x) in poses.iter().enumerate() {
        let mut run = Run::new(initialized(wrc(), &name(&[&"soakPose", &k]), &models(6, 1)));
        let pose: Vec<(&str, f64)> = names.iter().copied().zip(x.iter().copied()).collect();
        run.step_ok(&pose);
        assert_balanced(&run.f, "left", x[3], &format!("soak pose {k}, left"));
        assert_balanced(&run.f, "right", x[4], &format!("soak pose {k}, right"));
        if k == 0 {
            assert_eq!(run.f.integer("right.nPatches"), 1, "one contact, one patch");
        }
    }
}

/// FASTSIM on a 1 × 1 grid (nx = ny = 1, allowed) gave |F| = 6/π μN in full sliding: the one
/// 2a × 2b element carried the peak pressure. The bound now sums to μN on every grid.
#[test]
fn coarse_fastsim_grid_keeps_to_coulomb() {
    let mut run = Run::new(initialized(
        hc(),
        "knownBugGrid",
        &[("nx", P::I(1)), ("ny", P::I(1))],
    ));
    run.step_ok(&[("xi", 1.0), ("eta", 0.0), ("phi", 0.0)]);
    let (fx, fy, n) = (run.f.real("Fx"), run.f.real("Fy"), run.f.real("N"));
    assert!(
        fx.hypot(fy) <= 0.3 * n * COULOMB,
        "|F| = {} μN",
        fx.hypot(fy) / (0.3 * n)
    );
}
