//! Continuity of the wheel forces in the pose, as a host integrating a wheelset's motion needs
//! them (docs/reliability.md, "Continuity"): sweeps of the lateral shift, the yaw and the roll
//! through tread, flange-root and flange contact for every normal model, each step whose forces
//! change by more than 0.5 % of the wheel load bisected down to 1e−12 m (a steep but continuous
//! change shrinks with the interval; a jump does not). Also checked on every pose: no error, the
//! load balanced to 1e−6, and an output slot keeps its patch (its reference point moves by less
//! than the slot-matching distance from step to step).
//!
//! In release builds (`cargo test --release --test continuity`, run by `tests/run_all.sh`) the
//! sweeps step 0.01 mm (the acceptance's resolution); debug builds step 0.1 mm.

mod common;

use common::builtin_wheelset_with;
use railcontact::normal::NormalModel;
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::{
    Creepages, Vertical, Wheelset, WheelsetInput, WheelsetResult, MAX_PATCHES,
};

/// Largest change of a wheel force between two poses 1e−12 m apart, as a fraction of the load.
const JUMP: f64 = 5e-3;

/// Lateral-shift step of the sweeps [m].
const STEP: f64 = if cfg!(debug_assertions) { 1e-4 } else { 1e-5 };

/// A pose: lateral shift [m], yaw and roll [rad].
#[derive(Debug, Clone, Copy)]
struct Pose {
    y: f64,
    yaw: f64,
    roll: f64,
}

/// Both wheels' force vectors (track axes) [N].
fn forces(out: &WheelsetResult) -> [f64; 6] {
    let (l, r) = (out.left.force, out.right.force);
    [l[0], l[1], l[2], r[0], r[1], r[2]]
}

fn largest_change(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Largest relative miss of the wheel load a balanced pose may show: the creep iteration's
/// resolution (1e−7) with margin.
const BALANCE_TOLERANCE: f64 = 1e-6;

struct Sweep {
    ws: Wheelset,
    load: f64,
    out: WheelsetResult,
    /// Worst change that survived bisection, and where.
    worst: (f64, f64),
    solves: usize,
    /// Largest relative miss of the wheel load seen.
    worst_balance: f64,
}

impl Sweep {
    fn new(model: NormalModel, load: f64) -> Self {
        Self::with_tangential(model, TangentialModel::ModelDefault, false, load)
    }

    /// A sweep of `model` with tangential option `tangential`, planar patches or not.
    fn with_tangential(
        model: NormalModel,
        tangential: TangentialModel,
        planar: bool,
        load: f64,
    ) -> Self {
        Self {
            ws: builtin_wheelset_with(|s| {
                s.normal_model = model;
                s.tangential = tangential;
                s.planar_patch = planar;
            }),
            load,
            out: WheelsetResult::default(),
            worst: (0.0, 0.0),
            solves: 0,
            worst_balance: 0.0,
        }
    }

    /// Solves `pose` (kinematic creepages at 30 m/s, rolling at the nominal radius) and checks
    /// the balance; returns the forces.
    fn solve(&mut self, p: Pose) -> [f64; 6] {
        let input = WheelsetInput {
            y: p.y,
            yaw: p.yaw,
            roll: p.roll,
            vertical: Vertical::Loads {
                left: self.load,
                right: self.load,
            },
            creepages: Creepages::Kinematic {
                vx: 30.0,
                vy: 0.0,
                yaw_rate: 0.0,
                omega: 30.0 / 0.46,
            },
        };
        let previous = self.out;
        self.ws
            .solve(&input, &mut self.out)
            .unwrap_or_else(|e| panic!("{p:?}: {e}"));
        self.solves += 1;
        let f = forces(&self.out);
        for fz in [f[2], f[5]] {
            let miss = (fz + self.load).abs() / self.load;
            self.worst_balance = self.worst_balance.max(miss);
            assert!(
                miss <= BALANCE_TOLERANCE,
                "{p:?}: Fz {fz} for {}",
                self.load
            );
        }
        assert!(f.iter().all(|v| v.is_finite()), "{p:?}: {f:?}");
        // A patch keeps its slot while it exists: a slot occupied in both steps whose reference
        // point moved by more than the slot-matching distance (4 mm; poses a sweep step apart
        // move it by far less) holds a new patch only if the old one is gone — no patch of this
        // step lies within that distance of it, or the one that does kept a slot whose previous
        // patch lay nearer to it (two patches merged into one) — or is no longer among the three
        // heaviest that the slots show.
        for (a, b) in [
            (&previous.left, &self.out.left),
            (&previous.right, &self.out.right),
        ] {
            for k in 0..MAX_PATCHES {
                let (pa, pb) = (&a.patches[k], &b.patches[k]);
                if !(pa.weight > 0.0 && pb.weight > 0.0 && (pa.y_rail - pb.y_rail).abs() > 4e-3) {
                    continue;
                }
                for (j, q) in b.patches.iter().enumerate() {
                    if q.weight <= 0.0 || (q.y_rail - pa.y_rail).abs() > 4e-3 {
                        continue;
                    }
                    let earlier = &a.patches[j];
                    assert!(
                        earlier.weight > 0.0
                            && (earlier.y_rail - q.y_rail).abs() <= (pa.y_rail - q.y_rail).abs(),
                        "{p:?}: slot {k} from yRail {} to {} while the patch at {} is in slot {j}",
                        pa.y_rail,
                        pb.y_rail,
                        q.y_rail
                    );
                }
            }
        }
        f
    }

    /// Walks the poses `at(t)` for t = 0 … 1 and back in `n` steps, bisecting every step whose
    /// forces change by more than [`JUMP`] of the load down to a pose interval of 1e−12 (in the
    /// swept coordinate, scaled by `scale` to metres or radians).
    fn walk(&mut self, n: usize, at: impl Fn(f64) -> Pose) {
        let threshold = JUMP * self.load;
        let ts: Vec<f64> = (0..=n)
            .chain((0..n).rev())
            .map(|k| k as f64 / n as f64)
            .collect();
        let mut previous: Option<(f64, [f64; 6])> = None;
        for &t in &ts {
            let f = self.solve(at(t));
            if let Some((tp, fp)) = previous {
                if largest_change(&f, &fp) > threshold {
                    let (mut a, mut fa, mut b, mut fb) = (tp, fp, t, f);
                    // Down to 1e−12 m of the swept coordinate (the sweeps span ~2e−2 m or rad),
                    // following the half with the larger change.
                    while (b - a).abs() * 2e-2 > 1e-12 {
                        let m = 0.5 * (a + b);
                        let fm = self.solve(at(m));
                        if largest_change(&fm, &fa) > largest_change(&fm, &fb) {
                            (b, fb) = (m, fm);
                        } else {
                            (a, fa) = (m, fm);
                        }
                    }
                    let change = largest_change(&fa, &fb);
                    if change > self.worst.0 {
                        self.worst = (change, a);
                    }
                    self.solve(at(t));
                }
            }
            previous = Some((t, f));
        }
    }
}

fn check(label: &str, sweep: &Sweep) {
    eprintln!(
        "{label}: {} solves, largest change surviving bisection {:.3} % of Q, load missed by \
         at most {:.1e}",
        sweep.solves,
        100.0 * sweep.worst.0 / sweep.load,
        sweep.worst_balance
    );
    assert!(
        sweep.worst.0 <= JUMP * sweep.load,
        "{label}: a force jumps by {:.3} % of the load at sweep parameter {}",
        100.0 * sweep.worst.0 / sweep.load,
        sweep.worst.1
    );
}

/// The acceptance sweeps: y from −8 to +10 mm and back, yaw 0 and ±5 mrad, 78.5 kN, every model.
#[test]
fn lateral_sweeps_have_no_force_jump() {
    let n = (18e-3 / STEP).round() as usize;
    for model in NormalModel::ALL {
        for yaw in [0.0, 5e-3, -5e-3] {
            let mut sweep = Sweep::new(model, 78_500.0);
            sweep.walk(n, |t| Pose {
                y: -8e-3 + 18e-3 * t,
                yaw,
                roll: 0.0,
            });
            check(&format!("{} yaw {yaw}", model.name()), &sweep);
        }
    }
}

/// The lateral sweeps with FaStrip (`tangentialModel` 3) and with its strip-wise coefficients
/// from the half-space (5), whose coupled strips change as strips enter and leave contact:
/// ANALYN planar and non-planar, the coupled strips planar, yaw 0 and 5 mrad.
#[test]
fn lateral_sweeps_with_fastrip_have_no_force_jump() {
    let n = (18e-3 / STEP).round() as usize;
    let cases = [
        (NormalModel::Analyn, TangentialModel::Fastrip, true),
        (NormalModel::Analyn, TangentialModel::FastripCoupled, true),
        (NormalModel::Analyn, TangentialModel::FastripCoupled, false),
        (NormalModel::CoupledStrips, TangentialModel::Fastrip, true),
        (
            NormalModel::CoupledStrips,
            TangentialModel::FastripCoupled,
            true,
        ),
    ];
    for (model, tangential, planar) in cases {
        for yaw in [0.0, 5e-3] {
            let mut sweep = Sweep::with_tangential(model, tangential, planar, 78_500.0);
            sweep.walk(n, |t| Pose {
                y: -8e-3 + 18e-3 * t,
                yaw,
                roll: 0.0,
            });
            check(
                &format!(
                    "{} + {} planar {planar} yaw {yaw}",
                    model.name(),
                    tangential.name()
                ),
                &sweep,
            );
        }
    }
}

/// Yaw sweeps (−8 … +8 mrad) in tread, flange-root and flange contact, and roll sweeps
/// (−5 … +5 mrad), at a light and a heavy load.
#[test]
fn yaw_and_roll_sweeps_have_no_force_jump() {
    let n = if cfg!(debug_assertions) { 80 } else { 800 };
    for model in NormalModel::ALL {
        for load in [40_000.0, 120_000.0] {
            for y in [2e-3, 5.5e-3, 7e-3] {
                let mut sweep = Sweep::new(model, load);
                sweep.walk(n, |t| Pose {
                    y,
                    yaw: -8e-3 + 16e-3 * t,
                    roll: 0.0,
                });
                check(
                    &format!("{} {load} N y {y} yaw sweep", model.name()),
                    &sweep,
                );
                let mut sweep = Sweep::new(model, load);
                sweep.walk(n, |t| Pose {
                    y,
                    yaw: 2e-3,
                    roll: -5e-3 + 10e-3 * t,
                });
                check(
                    &format!("{} {load} N y {y} roll sweep", model.name()),
                    &sweep,
                );
            }
        }
    }
}
