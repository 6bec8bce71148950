//! Soak test of the `WheelRailContact` FMU through its exported C functions, driven by the
//! `fmi_host` harness (docs/reliability.md): a random walk of the wheelset pose (lateral shift,
//! yaw, roll, both wheel loads, forward and lateral speed, yaw rate, axle speed) from a fixed
//! seed, one `fmi2SetReal`, `fmi2DoStep` and `fmi2GetReal`/`fmi2GetInteger` of every output per
//! step, with every 1 000 steps an FMU state taken, serialized and freed. Checked: every status
//! OK, no output NaN or infinite, the vertical balance of both wheels, and a flat resident set
//! size after warm-up.
//!
//! * the full run, 1 000 000 steps (about 2 minutes in release):
//!   `cargo test --release --test soak -- --ignored --nocapture`
//! * a short run of 20 000 steps is part of the default suite.
//!
//! `RAILCONTACT_SOAK_STEPS` overrides the number of steps of the full run, and
//! `RAILCONTACT_SOAK_NORMAL_MODEL` (1–6) the normal model (default 1, Hertz).

mod linked;
mod reliability_support;

use linked::*;
use railcontact::fmi::variables::{Causality, VarType};
use railcontact::models::wheel_rail_contact::INFO;
use reliability_support::*;
use std::time::Instant;

const H: f64 = 1e-3;

/// Growth of VmRSS after warm-up that counts as a leak [kB]: well above allocator noise, far
/// below what leaking even 8 bytes per step would add over 20 000 steps or more.
const RSS_GROWTH_LIMIT_KB: u64 = 2048;

/// Index of the Real output `name` in [`Instance::read_outputs`].
fn output_index(name: &str) -> usize {
    INFO.variables
        .iter()
        .filter(|v| v.causality == Causality::Output && v.ty == VarType::Real)
        .position(|v| v.name == name)
        .unwrap_or_else(|| panic!("no Real output {name}"))
}

fn env_number<T: std::str::FromStr>(name: &str, default: T) -> T {
    match std::env::var(name) {
        Ok(v) => v
            .parse()
            .unwrap_or_else(|_| panic!("{name} = {v:?} is not a number")),
        Err(_) => default,
    }
}

struct Report {
    steps: usize,
    seconds: f64,
    rss_after_warmup_kb: u64,
    rss_max_kb: u64,
    rss_end_kb: u64,
}

fn soak(steps: usize, normal_model: i32, warmup: usize) -> Report {
    let label = format!("soak{normal_model}");
    let f = instantiate(&INFO, &label);
    assert_eq!(f.set_integer("normalModel", normal_model), OK);
    f.init();
    let mut pose = PoseWalk::new(&INFO, 20_240_601);
    let fz = [output_index("left.Fz"), output_index("right.Fz")];
    let sample_every = (steps / 100).clamp(1000, 10_000);
    let start = Instant::now();
    let mut rss_after_warmup = None;
    let mut rss_max = 0;
    for k in 0..steps {
        let x = pose.next();
        assert_eq!(f.set_reals(&pose.vrs, &x), OK, "step {k}");
        let s = f.step(k as f64 * H, H);
        assert_eq!(s, OK, "step {k}, inputs {x:?}: {:?}", f.messages());
        let (s, out) = f.read_outputs();
        assert_eq!(s, OK, "outputs at step {k}");
        f.assert_finite(&out);
        // Vertical balance (z down: Fz = −Q), 1e−6 of the load or 10 mN.
        for (side, &i) in fz.iter().enumerate() {
            let q = x[3 + side];
            assert!(
                (out[i] + q).abs() <= 1e-6 * q + 1e-2,
                "step {k}: Fz = {} for Q = {q} (side {side}), inputs {x:?}",
                out[i]
            );
        }
        if k % 1000 == 999 {
            // State machinery: allocate, serialize, free.
            let bytes = f.serialized_state().unwrap();
            assert!(bytes.len() > 1000);
        }
        if (k + 1) % sample_every == 0 {
            let rss = vm_rss_kb().expect("VmRSS in /proc/self/status");
            if k + 1 >= warmup {
                let base = *rss_after_warmup.get_or_insert(rss);
                rss_max = rss_max.max(rss);
                assert!(
                    rss <= base + RSS_GROWTH_LIMIT_KB,
                    "VmRSS grew from {base} kB after warm-up to {rss} kB at step {}",
                    k + 1
                );
            }
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    assert!(f.errors().is_empty(), "{:?}", f.errors());
    let rss_end = vm_rss_kb().expect("VmRSS");
    let rss_after_warmup_kb = rss_after_warmup.expect("sampled after warm-up");
    assert!(rss_end <= rss_after_warmup_kb + RSS_GROWTH_LIMIT_KB);
    Report {
        steps,
        seconds,
        rss_after_warmup_kb,
        rss_max_kb: rss_max,
        rss_end_kb: rss_end,
    }
}

fn print(r: &Report, normal_model: i32) {
    eprintln!(
        "soak: normalModel {normal_model}, {} steps in {:.1} s ({:.1} µs/step); VmRSS after \
         warm-up {} kB, max {} kB, end {} kB (growth {} kB)",
        r.steps,
        r.seconds,
        r.seconds / r.steps as f64 * 1e6,
        r.rss_after_warmup_kb,
        r.rss_max_kb,
        r.rss_end_kb,
        r.rss_max_kb.saturating_sub(r.rss_after_warmup_kb)
    );
}

#[test]
fn soak_short() {
    let r = soak(20_000, 1, 5_000);
    print(&r, 1);
}

/// The random walk for every normal model: 50 000 steps each in release builds (`cargo test
/// --release --test soak`, run by `tests/run_all.sh`), 2 000 in debug builds.
#[test]
fn soak_every_normal_model() {
    let steps = if cfg!(debug_assertions) {
        2_000
    } else {
        50_000
    };
    for normal_model in 1..=6 {
        let r = soak(steps, normal_model, steps / 4);
        print(&r, normal_model);
    }
}

#[test]
#[ignore = "1 000 000 steps, ~2 min in release: cargo test --release --test soak -- --ignored"]
fn soak_one_million_steps() {
    let steps = env_number("RAILCONTACT_SOAK_STEPS", 1_000_000usize);
    let normal_model = env_number("RAILCONTACT_SOAK_NORMAL_MODEL", 1i32);
    let r = soak(steps, normal_model, steps / 20);
    print(&r, normal_model);
}
