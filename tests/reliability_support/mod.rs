//! Shared driver of the reliability and soak tests (`tests/reliability.rs`, `tests/soak.rs`):
//! the linked FMUs and checked reads of `tests/linked`, a seeded random walk of the
//! `WheelRailContact` inputs and the resident set size.
//!
//! The harness returns every `fmi2Status` to the test, which asserts it.

#![allow(dead_code)] // each test crate uses a different part of the driver

use railcontact::fmi::model::ModelInfo;
use railcontact::fmi::variables::VarInfo;

/// The variable `name` of `info`; panics in the test (never in the FMU) if it does not exist.
pub fn var(info: &ModelInfo, name: &str) -> &'static VarInfo {
    info.variable(name)
        .unwrap_or_else(|| panic!("{} has no variable {name}", info.model_identifier))
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
