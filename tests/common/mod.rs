//! Shared set-up of the integration tests: the vendored data of `tests/data` and the benchmark
//! wheelset (`tests/data/README.md`), and the built-in S1002/UIC60 wheelset (also
//! included by `benches/contact.rs` and `examples/solve_loop.rs`).

use std::path::{Path, PathBuf};

use railcontact::geometry::profile::{Profile, ProfileKind};
use railcontact::geometry::track::TrackSetup;
use railcontact::material::Material;
use railcontact::normal::NormalModel;
use railcontact::tangential::fastsim::{Creepage, EllipticContact};
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::{
    Creepages, Vertical, Wheelset, WheelsetInput, WheelsetResult, WheelsetSettings,
};

/// The vendored test data: `tests/data` of the repository root (profiles and reference
/// solutions, see its README). This module is also included by other workspace members (e.g.
/// `halfspace/tests`), whose manifest directory lies below the root: the data is looked up in
/// the including crate's directory and then in its ancestors.
pub fn data_dir() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest
        .ancestors()
        .map(|dir| dir.join("tests/data"))
        .find(|data| data.join("README.md").is_file())
        .unwrap_or_else(|| manifest.join("tests/data"))
}

/// A file of the test data; fails (never skips) when it is missing.
pub fn data_file(relative: &str) -> PathBuf {
    let p = data_dir().join(relative);
    assert!(p.is_file(), "test data file {} not found", p.display());
    p
}

/// The benchmark wheelset: `MBench_S1002_v3.prw` on `MBench_UIC60_v3.prr` (rail already inclined
/// 1:40 in the file, so `rail_inclination = 0`), gauge 1435 mm at 14 mm, flange-back distance
/// 1360 mm, nominal radius 460 mm, with the given material and normal model.
#[allow(dead_code)] // not every test crate that includes this module uses it
pub fn benchmark_wheelset(material: Material, model: NormalModel) -> Wheelset {
    benchmark_wheelset_with(material, |s| s.normal_model = model)
}

/// The benchmark wheelset with settings adjusted by `adjust` (from the defaults of
/// [`WheelsetSettings::new`] on the benchmark set-up).
pub fn benchmark_wheelset_with(
    material: Material,
    adjust: impl FnOnce(&mut WheelsetSettings),
) -> Wheelset {
    let load = |file: &str, kind| {
        let p = data_file(&format!("profiles/{file}"));
        Profile::load(p.to_str().unwrap(), kind, 0.0)
            .unwrap_or_else(|e| panic!("loading {}: {e}", p.display()))
    };
    let setup = TrackSetup {
        rail_inclination: 0.0,
        ..TrackSetup::default()
    };
    let mut settings = WheelsetSettings::new(setup, material);
    adjust(&mut settings);
    Wheelset::new(
        &load("MBench_S1002_v3.prw", ProfileKind::Wheel),
        &load("MBench_UIC60_v3.prr", ProfileKind::Rail),
        settings,
    )
    .expect("benchmark wheelset")
}

/// The settings' adjustment (for [`benchmark_wheelset_with`] and [`builtin_wheelset_with`]) to
/// the normal model `model`, the tangential option `tangential` and planar (`planar`) or
/// non-planar patches.
#[allow(dead_code)] // not every crate that includes this module uses it
pub fn patch_options(
    model: NormalModel,
    tangential: TangentialModel,
    planar: bool,
) -> impl FnOnce(&mut WheelsetSettings) {
    move |s| {
        s.normal_model = model;
        s.tangential = tangential;
        s.planar_patch = planar;
    }
}

/// Zero creepage (ξ = η = 0, φ = 0 1/m) prescribed at the rolling speed `vx` [m/s].
#[allow(dead_code)] // not every crate that includes this module uses it
pub const fn at_rest(vx: f64) -> Creepages {
    Creepages::Prescribed {
        creepage: Creepage {
            xi: 0.0,
            eta: 0.0,
            phi: 0.0,
        },
        vx,
    }
}

/// The solution of `ws` at lateral shift `y` [m] and yaw `yaw` [rad], no roll, with the vertical
/// load `load` [N] on each wheel and `creepages`; fails naming the pose when the solve fails.
#[allow(dead_code)] // not every crate that includes this module uses it
pub fn solve_pose(
    ws: &mut Wheelset,
    y: f64,
    yaw: f64,
    load: f64,
    creepages: Creepages,
) -> WheelsetResult {
    let input = WheelsetInput {
        y,
        yaw,
        roll: 0.0,
        vertical: Vertical::Loads {
            left: load,
            right: load,
        },
        creepages,
        track: Default::default(),
    };
    let mut out = WheelsetResult::default();
    ws.solve(&input, &mut out)
        .unwrap_or_else(|e| panic!("y {y} yaw {yaw}: {e}"));
    out
}

/// Whether the comparisons with the exact rolling solution run: their dense Newton systems take
/// minutes in a debug build, so in release builds only (`tests/run_all.sh`); otherwise says so
/// on stderr.
#[allow(dead_code)] // not every crate that includes this module uses it
pub fn rolling_comparisons_run() -> bool {
    if cfg!(debug_assertions) {
        eprintln!("the rolling comparisons run in release builds (tests/run_all.sh)");
        return false;
    }
    true
}

/// Steel as the built-in-profile set-ups use it: E = 210 GPa, ν = 0.28, μ = 0.3.
#[allow(dead_code)] // not every crate that includes this module uses it
pub const STEEL: Material = Material {
    youngs_modulus: 210e9,
    poisson_ratio: 0.28,
    friction: 0.3,
};

/// The benches' single FASTSIM patch: a = 8 mm, b = 4 mm, N = 82 kN, steel (G = 82 GPa,
/// ν = 0.28), μ = 0.3.
#[allow(dead_code)] // not every crate that includes this module uses it
pub const FASTSIM_CONTACT: EllipticContact = EllipticContact {
    a: 8e-3,
    b: 4e-3,
    normal_force: 82e3,
    shear_modulus: 82e9,
    nu: 0.28,
    mu: 0.3,
};

/// The benches' FASTSIM creepage on [`FASTSIM_CONTACT`]: pure lateral creepage with spin
/// (η = −6.25e-4, φ = 0.625 1/m).
#[allow(dead_code)] // not every crate that includes this module uses it
pub const FASTSIM_CREEPAGE: Creepage = Creepage {
    xi: 0.0,
    eta: -6.25e-4,
    phi: 0.625,
};

/// The built-in S1002 wheel on the built-in UIC60 rail on the default track (1:40, gauge
/// 1435 mm), steel, with settings adjusted by `adjust` (from the defaults of
/// [`WheelsetSettings::new`]): the benches' and the speed tests' wheelset (no shared data).
#[allow(dead_code)] // not every crate that includes this module uses it
pub fn builtin_wheelset_with(adjust: impl FnOnce(&mut WheelsetSettings)) -> Wheelset {
    let wheel = Profile::load("S1002", ProfileKind::Wheel, 0.0).expect("built-in S1002");
    let rail = Profile::load("UIC60", ProfileKind::Rail, 0.0).expect("built-in UIC60");
    let mut settings = WheelsetSettings::new(TrackSetup::default(), STEEL);
    adjust(&mut settings);
    Wheelset::new(&wheel, &rail, settings).expect("built-in wheelset")
}

/// The benches' central case on [`builtin_wheelset_with`]'s wheelset at lateral shift `y` [m]
/// and lateral velocity `vy` [m/s]: 78.5 kN per wheel, kinematic creepages at 30 m/s with 0.1 %
/// longitudinal creepage (ω = V/r₀ · 1.001, r₀ = 460 mm).
#[allow(dead_code)] // not every crate that includes this module uses it
pub fn central_input(y: f64, vy: f64) -> WheelsetInput {
    WheelsetInput {
        y,
        yaw: 0.0,
        roll: 0.0,
        vertical: Vertical::Loads {
            left: 78_500.0,
            right: 78_500.0,
        },
        creepages: Creepages::Kinematic {
            vx: 30.0,
            vy,
            yaw_rate: 0.0,
            omega: 30.0 / 0.46 * (1.0 + 1e-3),
        },
        track: Default::default(),
    }
}

/// Lateral shift of the benches' moving wheelset at step `k`: 3 mm · sin 2πt at 1 ms steps [m].
#[allow(dead_code)] // not every crate that includes this module uses it
pub fn moving_y(k: u64) -> f64 {
    3e-3 * (2.0 * std::f64::consts::PI * k as f64 * 1e-3).sin()
}

/// Frequency of the benches' hunting wheelset [Hz].
#[allow(dead_code)] // not every crate that includes this module uses it
pub const HUNTING_FREQUENCY: f64 = 5.0;

/// The central case of a hunting wheelset at step `k` of 1 ms: y = 3 mm · sin 2πft and
/// yaw = 1 mrad · sin 2πft at f = [`HUNTING_FREQUENCY`], with the consistent lateral velocity
/// and yaw rate (their time derivatives) in the kinematic creepages; otherwise
/// [`central_input`]. Every solve meets a new, yawed pose, as in a vehicle run.
#[allow(dead_code)] // not every crate that includes this module uses it
pub fn hunting_input(k: u64) -> WheelsetInput {
    let omega = 2.0 * std::f64::consts::PI * HUNTING_FREQUENCY;
    let phase = omega * k as f64 * 1e-3;
    let (sin, cos) = phase.sin_cos();
    let mut input = central_input(3e-3 * sin, 3e-3 * omega * cos);
    input.yaw = 1e-3 * sin;
    if let Creepages::Kinematic { yaw_rate, .. } = &mut input.creepages {
        *yaw_rate = 1e-3 * omega * cos;
    }
    input
}

/// Rows of a reference CSV file of the vendored data as (header → value) maps; non-numeric fields
/// are left out.
#[allow(dead_code)] // not every test crate that includes this module reads CSV files
pub fn read_csv(relative: &str) -> Vec<std::collections::HashMap<String, f64>> {
    let path = data_file(relative);
    let text = std::fs::read_to_string(&path).expect("readable reference file");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            header
                .iter()
                .zip(l.split(','))
                .filter_map(|(h, v)| v.trim().parse::<f64>().ok().map(|x| (h.to_string(), x)))
                .collect()
        })
        .collect()
}

/// Worst and mean |error| of relative errors `errors` and their line in per cent ("  +1.2 …").
#[allow(dead_code)] // not every crate that includes this module uses it
pub fn error_summary(errors: &[f64]) -> (f64, f64, String) {
    let worst = errors.iter().fold(0.0f64, |w, e| w.max(e.abs()));
    let mean = errors.iter().map(|e| e.abs()).sum::<f64>() / errors.len().max(1) as f64;
    let line = errors
        .iter()
        .map(|e| format!(" {:+5.1}", 100.0 * e))
        .collect();
    (worst, mean, line)
}
