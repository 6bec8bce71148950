//! Continuity of the wheel forces and of every output slot in the pose, as a host integrating a
//! wheelset's motion and following its patches needs them (docs/reliability.md, "Continuity";
//! docs/conventions.md, "Output slots"): sweeps of the lateral shift, the yaw and the roll
//! through tread, flange-root and flange contact for every normal model, each step whose outputs
//! change by more than 0.5 % of their scale refined along the path down to 1e−12 m (a steep but
//! continuous change shrinks with the interval; a jump does not). The outputs: both wheels' forces, and per
//! slot its normal and lateral force, area, peak pressure and reference point. Also checked on
//! every pose: no error, the load balanced to 1e−6, and no two reported patches of a wheel within
//! 1 mm of each other.
//!
//! In release builds (`cargo test --release --test continuity`, run by `tests/run_all.sh`) the
//! sweeps step 0.01 mm (the acceptance's resolution); debug builds step 0.1 mm.

mod common;

use common::builtin_wheelset_with;
use railcontact::normal::NormalModel;
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::{
    Creepages, PatchResult, SideResult, Slot, Vertical, WarmStart, Wheelset, WheelsetInput,
    WheelsetResult, MAX_PATCHES,
};

/// Largest change of an output between two poses 1e−12 m apart, as a fraction of its scale:
/// forces of the wheel load, areas of [`AREA_SCALE`], peak pressures and reference points
/// weighted by the smaller of the slot's loads at the two poses (a slot filling from or emptying
/// to zero load may place its patch anywhere).
const JUMP: f64 = 5e-3;

/// Scale of a patch's area [m²]: a full-load tread patch's (≈ 1.5e−4 m²); 0.5 % of it, 0.5 mm²,
/// is what a jump must stay below.
const AREA_SCALE: f64 = 1e-4;

/// Scale of a peak pressure [Pa].
const PRESSURE_SCALE: f64 = 1e9;

/// Scale of a reference point's move [m]: a fully loaded slot's reference point must not jump
/// by more than 0.5 % of 10 mm, 50 µm — half a wear map's 0.1 mm bin. (The internal patch groups'
/// blending weights still change by up to ~1 % within 1e−12 m where a flange contact's lobes
/// merge, which moves a reported reference point by up to ~20 µm.)
const POSITION_SCALE: f64 = 1e-2;

/// Two reported patches of a wheel lie at least this far apart [m].
const PATCH_DISTANCE: f64 = 1e-3;

/// Lateral-shift step of the sweeps [m].
const STEP: f64 = if cfg!(debug_assertions) { 1e-4 } else { 1e-5 };

/// A pose: lateral shift [m], yaw and roll [rad].
#[derive(Debug, Clone, Copy)]
struct Pose {
    y: f64,
    yaw: f64,
    roll: f64,
}

/// The largest change between two poses' outputs, as a fraction of its scale, and what changed.
fn largest_change(a: &WheelsetResult, b: &WheelsetResult, load: f64, shape: bool) -> (f64, String) {
    let mut worst = (0.0, String::new());
    let mut note = |change: f64, what: &dyn Fn() -> String| {
        if change > worst.0 {
            worst = (change, what());
        }
    };
    for (wheel, sa, sb) in [("left", &a.left, &b.left), ("right", &a.right, &b.right)] {
        for (axis, (fa, fb)) in ["Fx", "Fy", "Fz"]
            .iter()
            .zip(sa.force.iter().zip(&sb.force))
        {
            note((fa - fb).abs() / load, &|| format!("{wheel} {axis}"));
        }
        for k in 0..MAX_PATCHES {
            let (pa, pb) = (&sa.patches[k], &sb.patches[k]);
            let slot = |q: &str| format!("{wheel}.p{}.{q}", k + 1);
            note((pa.fn_ - pb.fn_).abs() / load, &|| slot("Fn"));
            note((pa.fy - pb.fy).abs() / load, &|| slot("Fy"));
            let loaded = pa.fn_.min(pb.fn_) / load;
            if shape {
                note((pa.area - pb.area).abs() / AREA_SCALE, &|| slot("area"));
                note(loaded * (pa.pmax - pb.pmax).abs() / PRESSURE_SCALE, &|| {
                    slot("pmax")
                });
            }
            note(
                loaded * (pa.y_rail - pb.y_rail).abs() / POSITION_SCALE,
                &|| slot("yRail"),
            );
            let moved = (0..3).fold(0.0_f64, |m, i| {
                m.max((pa.position[i] - pb.position[i]).abs())
            });
            note(loaded * moved / POSITION_SCALE, &|| slot("position"));
        }
    }
    worst
}

/// The closest two reported patches of a wheel [m] (+∞ with fewer than two).
fn closest_patches(side: &SideResult) -> f64 {
    let p: &[PatchResult] = side.all_patches();
    let mut closest = f64::INFINITY;
    for i in 0..p.len() {
        for q in &p[i + 1..] {
            closest = closest.min((p[i].y_rail - q.y_rail).abs());
        }
    }
    closest
}

/// Largest relative miss of the wheel load a balanced pose may show: the creep iteration's
/// resolution (1e−7) with margin.
const BALANCE_TOLERANCE: f64 = 1e-6;

struct Sweep {
    ws: Wheelset,
    load: f64,
    out: WheelsetResult,
    /// Worst change that survived bisection (fraction of its scale), where, and what.
    worst: (f64, f64, String),
    solves: usize,
    /// Largest relative miss of the wheel load seen.
    worst_balance: f64,
    /// Whether the slots' area and peak pressure are checked (see
    /// `yaw_and_roll_sweeps_have_no_force_jump`).
    shape: bool,
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
            worst: (0.0, 0.0, String::new()),
            solves: 0,
            worst_balance: 0.0,
            shape: true,
        }
    }

    /// Solves `pose` (kinematic creepages at 30 m/s, rolling at the nominal radius) and checks
    /// the balance, finiteness and the patches' distance; returns the outputs.
    fn solve(&mut self, p: Pose) -> WheelsetResult {
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
            track: Default::default(),
        };
        self.ws
            .solve(&input, &mut self.out)
            .unwrap_or_else(|e| panic!("{p:?}: {e}"));
        self.solves += 1;
        for side in [&self.out.left, &self.out.right] {
            let miss = (side.force[2] + self.load).abs() / self.load;
            self.worst_balance = self.worst_balance.max(miss);
            assert!(
                miss <= BALANCE_TOLERANCE,
                "{p:?}: Fz {} for {}",
                side.force[2],
                self.load
            );
            assert!(side.force.iter().all(|v| v.is_finite()), "{p:?}: {side:?}");
            let closest = closest_patches(side);
            assert!(
                closest >= PATCH_DISTANCE,
                "{p:?}: two reported patches {closest} m apart"
            );
        }
        self.out
    }

    /// The solver's history (what an FMU state holds: warm starts and output slots).
    fn history(&self) -> History {
        (self.ws.warm_start(), self.ws.slots())
    }

    fn restore(&mut self, h: History) {
        self.ws.set_warm_start(h.0);
        self.ws.set_slots(h.1);
    }

    /// Walks the poses `at(t)` for t = 0 … 1 and back in `n` steps. A step whose outputs change
    /// by more than [`JUMP`] is refined along the path, as a host reducing its step would: from
    /// the state at the step's start, the half with the larger change is walked again, down to a
    /// pose interval of 1e−12 (in the swept coordinate, scaled by 2e−2 to metres or radians).
    /// (The element's slots follow the path taken; solving poses out of order would mix two
    /// histories.)
    fn walk(&mut self, n: usize, at: impl Fn(f64) -> Pose) {
        let ts: Vec<f64> = (0..=n)
            .chain((0..n).rev())
            .map(|k| k as f64 / n as f64)
            .collect();
        let load = self.load;
        let shape = self.shape;
        let change = |a: &WheelsetResult, b: &WheelsetResult| largest_change(a, b, load, shape).0;
        let mut previous: Option<(f64, WheelsetResult, History)> = None;
        for &t in &ts {
            let f = self.solve(at(t));
            if let Some((tp, fp, hp)) = previous {
                if change(&f, &fp) > JUMP {
                    let after = self.history();
                    // (start pose, its outputs, the state after it), (end pose, its outputs).
                    let (mut a, mut fa, mut ha, mut b, mut fb) = (tp, fp, hp, t, f);
                    while (b - a).abs() * 2e-2 > 1e-12 {
                        let m = 0.5 * (a + b);
                        self.restore(ha);
                        let fm = self.solve(at(m));
                        let hm = self.history();
                        let fb_via_m = self.solve(at(b));
                        if change(&fm, &fa) >= change(&fb_via_m, &fm) {
                            (b, fb) = (m, fm);
                        } else {
                            (a, fa, ha, fb) = (m, fm, hm, fb_via_m);
                        }
                    }
                    let (size, what) = largest_change(&fa, &fb, load, shape);
                    if size > self.worst.0 {
                        self.worst = (size, a, what);
                    }
                    self.restore(after);
                }
            }
            previous = Some((t, f, self.history()));
        }
    }
}

/// An FMU state's solver history: warm starts and output slots of both wheels.
type History = ([Option<WarmStart>; 2], [[Option<Slot>; MAX_PATCHES]; 2]);

fn check(label: &str, sweep: &Sweep) {
    eprintln!(
        "{label}: {} solves, largest change surviving bisection {:.3} % ({}), load missed by \
         at most {:.1e}",
        sweep.solves,
        100.0 * sweep.worst.0,
        sweep.worst.2,
        sweep.worst_balance
    );
    assert!(
        sweep.worst.0 <= JUMP,
        "{label}: {} jumps by {:.3} % of its scale at sweep parameter {}",
        sweep.worst.2,
        100.0 * sweep.worst.0,
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
/// (−5 … +5 mrad), at a light and a heavy load. Kik–Piotrowski's area and peak pressure are not
/// checked here: on the near-conformal flange root rolled by a few mrad (gap flat to 0.1 µm over
/// 6 mm) its first-contact points, which set D3's origin, jump, and its area and peak with them
/// (≤ 6 % of a patch's area, 2 % of its peak; its forces by 0.1 % of Q; docs/theory.md §5.4).
#[test]
fn yaw_and_roll_sweeps_have_no_force_jump() {
    let n = if cfg!(debug_assertions) { 80 } else { 800 };
    for model in NormalModel::ALL {
        for load in [40_000.0, 120_000.0] {
            for y in [2e-3, 5.5e-3, 7e-3] {
                let mut sweep = Sweep::new(model, load);
                sweep.shape = model != NormalModel::KikPiotrowski;
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
                sweep.shape = model != NormalModel::KikPiotrowski;
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

/// The multi-Hertzian wheel's force is continuous in the lowering where a second patch enters
/// contact (the load balance needs it: a jump across the load leaves the wheel off its load by
/// the jump). A pose of the soak's random walk (y = 4.89 mm, the flange root about to touch)
/// with the wheelset's height prescribed: the lowering is stepped by 0.1 nm through the flange
/// root's first touch, where its patch must start from nothing — a Hertz patch carries
/// F ∝ δ^{3/2}, 2e−4 N at δ = 0.1 nm on this root, and the first step that shows it is checked
/// against 0.01 N (before the patch's depth was measured from the same gap interpolant its
/// moments integrate, it entered at 0.73 N).
#[test]
fn a_hertz_patch_enters_contact_from_nothing() {
    let mut wheelset = builtin_wheelset_with(|s| s.normal_model = NormalModel::Hertz);
    let mut input = WheelsetInput {
        y: 4.892_297_120_661_3e-3,
        yaw: 5.831_694_363_566_9e-4,
        roll: 6.204_511_599_834_1e-4,
        vertical: Vertical::Loads {
            left: 30_384.6,
            right: 63_754.4,
        },
        creepages: Creepages::Kinematic {
            vx: 22.95,
            vy: 0.0145,
            yaw_rate: -0.0494,
            omega: 49.67,
        },
        track: Default::default(),
    };
    let mut out = WheelsetResult::default();
    wheelset.solve(&input, &mut out).unwrap();
    let z_loaded = out.right.z;
    let root_force = |out: &WheelsetResult| -> f64 {
        out.right.groups[..out.right.n_groups]
            .iter()
            .filter(|g| g.contact_angle > 0.2)
            .map(|g| g.fn_)
            .sum()
    };
    // Find the first touch of the flange root within 0.2 µm of the loaded height.
    let (mut lo, mut hi) = (z_loaded - 2e-7, z_loaded + 2e-7);
    input.vertical = Vertical::Position { z: lo };
    wheelset.solve(&input, &mut out).unwrap();
    assert_eq!(root_force(&out), 0.0, "the root touches already at {lo}");
    input.vertical = Vertical::Position { z: hi };
    wheelset.solve(&input, &mut out).unwrap();
    assert!(root_force(&out) > 0.0, "the root does not touch at {hi}");
    while hi - lo > 1e-10 {
        let mid = 0.5 * (lo + hi);
        input.vertical = Vertical::Position { z: mid };
        wheelset.solve(&input, &mut out).unwrap();
        if root_force(&out) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    input.vertical = Vertical::Position { z: hi };
    wheelset.solve(&input, &mut out).unwrap();
    let entering = root_force(&out);
    assert!(
        entering < 0.01,
        "the flange root enters with {entering} N at z = {hi}"
    );
}
