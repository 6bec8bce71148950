//! The wear accumulated over a run through the FMU's C functions (docs/theory.md §10.5): a
//! hunting wheelset stepped by one instance with a wear model.
//!
//! * `s.wheelWearMass` equals the sum over the steps of `s.wheelWearRate` times the distance
//!   rolled (|vx| × step) within 1e−9 relative (the record sums each step's rates bin by bin;
//!   the bins' sum and the patches' sum differ by rounding), and the rail's likewise.
//! * An FMU state taken mid-run and restored (also serialized) gives the same masses and the
//!   same wear file, bit for bit.
//! * A symmetric run (centred, no yaw) wears both wheels alike: the left and right records are
//!   mirror images.
//! * `wearOutput` without a wear model, and a file that cannot be written, are errors naming
//!   `wearOutput`.

mod linked;

use linked::{Checked, ERROR, OK};
use railcontact::models::wheel_rail_contact::INFO;

const STEP: f64 = 1e-3;
const SPEED: f64 = 30.0;

fn instance(name: &str, wear_model: i32, normal_model: i32, output: &str) -> fmi_host::Instance {
    let f = linked::instantiate(&INFO, name);
    assert_eq!(f.set_integer("wearModel", wear_model), OK);
    assert_eq!(f.set_integer("normalModel", normal_model), OK);
    assert_eq!(f.set_string("wearOutput", output), OK);
    f
}

/// Inputs of the hunting wheelset at step `k` (tests/common: 3 mm and 1 mrad at 5 Hz), kinematic
/// creepages at 30 m/s with 0.1 % longitudinal creepage.
fn set_hunting(f: &fmi_host::Instance, k: usize, amplitude: f64) {
    let w = 2.0 * std::f64::consts::PI * 5.0;
    let t = k as f64 * STEP;
    let (s, c) = (w * t).sin_cos();
    for (name, x) in [
        ("y", amplitude * 3e-3 * s),
        ("yaw", amplitude * 1e-3 * s),
        ("vy", amplitude * 3e-3 * w * c),
        ("yawRate", amplitude * 1e-3 * w * c),
        ("vx", SPEED),
        ("omega", SPEED / 0.46 * 1.001),
    ] {
        assert_eq!(f.set_real(name, x), OK);
    }
}

fn temp_file(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("railcontact-{}-{name}", std::process::id()))
}

#[test]
fn masses_are_the_sums_of_the_steps_and_states_restore_them() {
    // The models whose whole solver history is in the FMU state (tests/reliability.rs,
    // `a_state_saved_at_step_1000_…`).
    for normal_model in [1, 4, 6] {
        let file = temp_file(&format!("wear-{normal_model}.csv"));
        let f = instance("wear", 1, normal_model, file.to_str().unwrap());
        f.init();
        let (mut wheel, mut rail) = ([0.0; 2], [0.0; 2]);
        let mut state = None;
        let mut at_state = ([0.0; 2], [0.0; 2]);
        for k in 0..60 {
            set_hunting(&f, k, 1.0);
            assert_eq!(f.step(k as f64 * STEP, STEP), OK);
            for (i, s) in ["left", "right"].iter().enumerate() {
                wheel[i] += f.real(&format!("{s}.wheelWearRate")) * SPEED * STEP;
                rail[i] += f.real(&format!("{s}.railWearRate")) * SPEED * STEP;
                let (m_w, m_r) = (
                    f.real(&format!("{s}.wheelWearMass")),
                    f.real(&format!("{s}.railWearMass")),
                );
                assert!(
                    (m_w - wheel[i]).abs() <= 1e-9 * wheel[i]
                        && (m_r - rail[i]).abs() <= 1e-9 * rail[i],
                    "model {normal_model} step {k} {s}: {m_w} vs {}, {m_r} vs {}",
                    wheel[i],
                    rail[i]
                );
                assert!(f.real(&format!("{s}.wheelWearDepthMax")) > 0.0);
                assert!(f.real(&format!("{s}.railWearDepthMax")) > 0.0);
            }
            if k == 29 {
                state = Some(f.serialized_state().unwrap());
                at_state = (wheel, rail);
            }
        }
        assert!(wheel[0] > 0.0 && wheel[1] > 0.0);
        let masses = |f: &fmi_host::Instance| {
            ["left", "right"].map(|s| {
                (
                    f.real(&format!("{s}.wheelWearMass")).to_bits(),
                    f.real(&format!("{s}.railWearMass")).to_bits(),
                )
            })
        };
        let end = masses(&f);
        assert_eq!(f.terminate(), OK);
        let written = std::fs::read_to_string(&file).unwrap();
        assert!(written.starts_with("# railcontact wear record\n"));
        // Restore the state of step 29 into a second instance and run the rest again.
        let g = instance("restored", 1, normal_model, file.to_str().unwrap());
        g.init();
        let (status, restored) = g.deserialize(state.as_ref().unwrap());
        assert_eq!(status, OK);
        assert_eq!(g.set_state(restored.as_ref().unwrap()), OK);
        for k in 30..60 {
            set_hunting(&g, k, 1.0);
            assert_eq!(g.step(k as f64 * STEP, STEP), OK);
        }
        assert_eq!(masses(&g), end, "model {normal_model}: restored run");
        assert_eq!(g.terminate(), OK);
        assert_eq!(std::fs::read_to_string(&file).unwrap(), written);
        assert!(at_state.0[0] > 0.0);
        let _ = std::fs::remove_file(&file);
    }
}

#[test]
fn a_symmetric_run_wears_both_wheels_alike() {
    // Centred, no yaw, no lateral motion: the left wheel is the right one mirrored (both
    // distributions are in the profiles' own coordinates, towards the field side).
    let file = temp_file("symmetric.csv");
    let f = instance("symmetric", 1, 6, file.to_str().unwrap());
    f.init();
    for k in 0..20 {
        set_hunting(&f, k, 0.0);
        assert_eq!(f.step(k as f64 * STEP, STEP), OK);
    }
    let (l, r) = (f.real("left.wheelWearMass"), f.real("right.wheelWearMass"));
    assert!(l > 0.0 && (l - r).abs() <= 1e-9 * r, "{l} vs {r}");
    assert_eq!(f.terminate(), OK);
    let rows: Vec<Vec<String>> = std::fs::read_to_string(&file)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("side"))
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    for body in ["wheel", "rail"] {
        let of = |side: &str| -> Vec<f64> {
            rows.iter()
                .filter(|r| r[0] == side && r[1] == body)
                .map(|r| r[3].parse().unwrap())
                .collect()
        };
        let (left, right) = (of("left"), of("right"));
        let peak = right.iter().copied().fold(0.0, f64::max);
        assert!(peak > 0.0);
        for (a, b) in left.iter().zip(&right) {
            assert!((a - b).abs() <= 1e-6 * peak, "{body}: {a} vs {b}");
        }
    }
    let _ = std::fs::remove_file(&file);
}

#[test]
fn a_wear_file_needs_a_wear_model_and_a_writable_place() {
    let f = instance("noModel", 0, 1, "wear.csv");
    assert_eq!(f.setup_experiment(0.0, None), OK);
    assert_eq!(f.enter_initialization(), OK);
    assert_eq!(f.exit_initialization(), ERROR);
    f.assert_error_logged(&["wearOutput = \"wear.csv\"", "wearModel = 0"]);

    let bad = "/nonexistent-directory/wear.csv";
    let g = instance("unwritable", 1, 1, bad);
    g.init();
    set_hunting(&g, 0, 1.0);
    assert_eq!(g.step(0.0, STEP), OK);
    assert_eq!(g.terminate(), ERROR);
    g.assert_error_logged(&["wearOutput", bad]);
}
