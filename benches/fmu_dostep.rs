//! `fmi2DoStep` through the C ABI: a Rust host (the `fmi_host` harness) loads the packed
//! WheelRailContact FMU's shared library, instantiates it as any FMI host does, sets the normal
//! model and 78.5 kN per wheel, and times `fmi2DoStep` of 1 ms with constant inputs (the central
//! case) and with the lateral shift following 3 mm sin 2πt (set before each step). Compare with
//! `wheelset/*_central` and `moving/*` of the `contact` bench (the model alone): the difference
//! is the FMI layer's overhead.
//!
//! Needs the packed FMU: `cargo run --release -p fmu-pack` first (`FMU_DIR` overrides
//! `target/fmu`); without it the bench says so and measures nothing.
//! `cargo bench --bench fmu_dostep`; figures in docs/performance.md.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use criterion::{criterion_group, criterion_main, Criterion};
use fmi_host::{Fmu, Instance, Status};

/// Wheel load of the central case [N].
const LOAD: f64 = 78_500.0;
/// Communication step [s].
const STEP: f64 = 1e-3;

/// Asserts that an FMU call returned OK, naming it and the instance's log.
#[track_caller]
fn ok(instance: &Instance, status: Status, call: &str) {
    assert_eq!(status, Status::Ok, "{call}: {:?}", instance.messages());
}

/// One initialized instance of the FMU, the value reference of `y` and the time it is at.
struct Stepper {
    instance: Instance,
    y: u32,
    time: f64,
}

impl Stepper {
    /// An instance with `normalModel` = `normal_model` and [`LOAD`] on both wheels, stepped
    /// once (the first step is a cold start; the timed ones are warm).
    fn new(fmu: &Arc<Fmu>, normal_model: i32) -> Self {
        let instance = fmu.instantiate("bench").unwrap_or_else(|e| panic!("{e}"));
        let f = &instance;
        ok(f, f.setup_experiment(0.0, None), "fmi2SetupExperiment");
        ok(f, f.set_integer("normalModel", normal_model), "normalModel");
        ok(f, f.enter_initialization(), "fmi2EnterInitializationMode");
        ok(f, f.set_real("Qleft", LOAD), "Qleft");
        ok(f, f.set_real("Qright", LOAD), "Qright");
        ok(f, f.exit_initialization(), "fmi2ExitInitializationMode");
        let y = instance.vr("y");
        let mut stepper = Self {
            instance,
            y,
            time: 0.0,
        };
        stepper.step(None);
        stepper
    }

    /// One `fmi2DoStep` of [`STEP`], after setting the lateral shift `y` [m] if given.
    fn step(&mut self, y: Option<f64>) {
        let f = &self.instance;
        if let Some(y) = y {
            ok(f, f.set_real_vr(self.y, y), "y");
        }
        let status = f.step(self.time, STEP);
        // Checked without formatting in the timed loop: the message is built only on failure.
        if status != Status::Ok {
            ok(f, status, &format!("fmi2DoStep at t = {}", self.time));
        }
        self.time += STEP;
    }
}

fn bench_dostep(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let fmu_dir = std::env::var_os("FMU_DIR").map_or(root.join("target/fmu"), PathBuf::from);
    let fmu = fmu_dir.join("WheelRailContact.fmu");
    if !fmu.is_file() {
        eprintln!(
            "fmu_dostep: {} is missing — run `cargo run --release -p fmu-pack` first; nothing \
             measured",
            fmu.display()
        );
        return;
    }
    let dir = std::env::temp_dir().join(format!("railcontact-bench-{}", std::process::id()));
    fmi_host::unzip(&fmu, &dir).unwrap_or_else(|e| panic!("{e}"));
    let fmu = Fmu::load(&dir, "linux64").unwrap_or_else(|e| panic!("{e}"));
    let mut group = c.benchmark_group("fmu_dostep");
    for (code, name) in [(1, "hertz"), (5, "stripes-ab"), (6, "analyn")] {
        let mut steady = Stepper::new(&fmu, code);
        group.bench_function(format!("{name}_constant"), |b| b.iter(|| steady.step(None)));
        let mut moving = Stepper::new(&fmu, code);
        group.bench_function(format!("{name}_moving"), |b| {
            b.iter(|| {
                let y = 3e-3 * (2.0 * std::f64::consts::PI * moving.time).sin();
                moving.step(Some(y))
            })
        });
    }
    group.finish();
    std::fs::remove_dir_all(&dir).ok();
}

criterion_group!(benches, bench_dostep);
criterion_main!(benches);
