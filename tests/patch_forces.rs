//! What a patch's outputs mean for the wheel's force (docs/conventions.md, "Reference point",
//! "Strips of a non-elliptic patch"): every strip model, planar and non-planar patches, tread to
//! flange contact, yawed.
//!
//! * No creepage prescribed, no creep force: every patch's Fx, Fy and Mz are zero, and the
//!   wheel's force is its patches' normal forces alone.
//! * Non-planar patches: the wheel's force is the sum of its strips' normal forces, each along its
//!   own rail normal (the strips of `Wheelset::strip_patches`, weighted by their groups), and a
//!   patch's contact angle is the direction of that resultant.
//! * Planar patches: the patch's normal force acts along the normal of its contact angle.
//! * A rigid, freely rolling, centred wheelset (no torque about its axle) carries no net
//!   longitudinal force.

mod common;

use common::builtin_wheelset_with;
use railcontact::normal::NormalModel;
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::{Creepages, PatchResult, Wheelset, WheelsetResult};

const Q: f64 = 78_500.0;

fn wheelset(model: NormalModel, planar: bool, tangential: TangentialModel) -> Wheelset {
    builtin_wheelset_with(common::patch_options(model, tangential, planar))
}

fn solve(ws: &mut Wheelset, y: f64, yaw: f64, creepages: Creepages) -> WheelsetResult {
    common::solve_pose(ws, y, yaw, Q, creepages)
}

/// Zero creepage, prescribed at 30 m/s.
const AT_REST: Creepages = common::at_rest(30.0);

/// Poses from the tread to the flange root and flange, with and without yaw: (y [m], yaw [rad]).
fn poses() -> Vec<(f64, f64)> {
    let mut poses = Vec::new();
    for y_mm in [-2.0, 0.0, 1.0, 2.5, 4.5, 5.5, 7.0] {
        for yaw in [0.0, 5e-3, -5e-3] {
            poses.push((y_mm * 1e-3, yaw));
        }
    }
    poses
}

#[test]
fn no_creepage_prescribed_gives_no_creep_force() {
    // Tolerance: rounding of sums of ~1e5 N.
    for model in NormalModel::ALL {
        for planar in [true, false] {
            for tangential in [
                TangentialModel::ModelDefault,
                TangentialModel::FastripCoupled,
            ] {
                if model == NormalModel::Hertz && tangential != TangentialModel::ModelDefault {
                    continue;
                }
                let mut ws = wheelset(model, planar, tangential);
                for (y, yaw) in poses() {
                    let out = solve(&mut ws, y, yaw, AT_REST);
                    for side in [&out.left, &out.right] {
                        for p in side.all_patches() {
                            let what = format!("{} planar {planar} y {y} yaw {yaw}", model.name());
                            assert!(p.fx.abs() < 1e-6 && p.fy.abs() < 1e-6, "{what}: {p:?}");
                            assert!(p.mz.abs() < 1e-9, "{what}: {p:?}");
                        }
                    }
                }
            }
        }
    }
}

/// (Σ N_j sin γ_j, Σ N_j cos γ_j) over the strips of every patch of one wheel, weighted by the
/// patches' group weights [N].
fn strip_normal_resultant(ws: &Wheelset, right: bool) -> (f64, f64) {
    ws.strip_patches(right)
        .iter()
        .map(|p| {
            let (lateral, vertical) = p.normal_resultant();
            (p.weight * lateral, p.weight * vertical)
        })
        .fold((0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1))
}

#[test]
fn non_planar_wheel_force_is_its_strips_normal_forces() {
    // At zero creepage the wheel's force is −Σ N_j e_z,j (e_z = (0, σ sin γ, cos γ) from the wheel
    // into the rail), to rounding; Fz = −Q by the load balance (1e−6 of Q). Each patch's contact
    // angle is the direction of its strips' resultant.
    for model in NormalModel::ALL.into_iter().skip(1) {
        let mut ws = wheelset(model, false, TangentialModel::ModelDefault);
        for (y, yaw) in poses() {
            let out = solve(&mut ws, y, yaw, AT_REST);
            for (right, side, sigma) in [(false, &out.left, -1.0), (true, &out.right, 1.0)] {
                let (lateral, vertical) = strip_normal_resultant(&ws, right);
                let what = format!("{} y {y} yaw {yaw} right {right}", model.name());
                assert!(
                    (side.force[1] + sigma * lateral).abs() < 1e-6 * Q,
                    "{what}: Fy {} strips {}",
                    side.force[1],
                    -sigma * lateral
                );
                assert!((side.force[2] + vertical).abs() < 1e-6 * Q, "{what}");
                assert!((side.force[2] + Q).abs() < 1e-6 * Q, "{what}");
                for (k, shown) in side.patches.iter().enumerate() {
                    // A slot holding one internal patch whole (a region described by several is
                    // the resultant of theirs: tests/continuity.rs, docs/conventions.md).
                    let whole = side.groups[..side.n_groups]
                        .iter()
                        .any(|g| PatchResult { weight: 1.0, ..*g } == *shown);
                    let Some(p) = ws.strip_patch_of_slot(right, k).filter(|_| whole) else {
                        continue;
                    };
                    let (l, v) = p.normal_resultant();
                    let d = shown.contact_angle - l.atan2(v);
                    assert!(d.abs() < 1e-12, "{what} slot {k}: {d}");
                }
            }
        }
    }
}

#[test]
fn planar_normal_force_acts_along_the_contact_angle() {
    // At zero creepage a planar wheel's force is −Σ N (0, σ sin γ, cos γ) over its patches.
    for model in NormalModel::ALL {
        let mut ws = wheelset(model, true, TangentialModel::ModelDefault);
        for (y, yaw) in poses() {
            let out = solve(&mut ws, y, yaw, AT_REST);
            for (side, sigma) in [(&out.left, -1.0), (&out.right, 1.0)] {
                let (lateral, vertical) = side
                    .all_patches()
                    .iter()
                    .map(|p| (p.fn_ * p.contact_angle.sin(), p.fn_ * p.contact_angle.cos()))
                    .fold((0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1));
                let what = format!("{} y {y} yaw {yaw}", model.name());
                assert!((side.force[1] + sigma * lateral).abs() < 1e-6 * Q, "{what}");
                assert!((side.force[2] + vertical).abs() < 1e-6 * Q, "{what}");
            }
        }
    }
}

#[test]
fn a_freely_rolling_centred_wheelset_carries_no_net_longitudinal_force() {
    // Kinematic creepages at 30 m/s, centred, no yaw: ω such that the moment about the axle of
    // both wheels is zero (secant iteration from ω = V/rolling radius), then the net Fx of the
    // wheelset is zero to 1e−3 of μN (what is left is the spin moment's component about the
    // axle over the rolling radius, σ Mz sin γ / r: measured ≤ 6 N, 1.3e−4 of μN).
    let (v, mu) = (30.0, 0.3);
    for model in NormalModel::ALL {
        for planar in [true, false] {
            let mut ws = wheelset(model, planar, TangentialModel::ModelDefault);
            let at = |ws: &mut Wheelset, omega: f64| {
                let creepages = Creepages::Kinematic {
                    vx: v,
                    vy: 0.0,
                    yaw_rate: 0.0,
                    omega,
                };
                let out = solve(ws, 0.0, 0.0, creepages);
                (out.left.moment[1] + out.right.moment[1], out)
            };
            let r = solve(&mut ws, 0.0, 0.0, AT_REST).right.patches[0].rolling_radius;
            let (mut w0, mut w1) = (v / r, v / r * (1.0 + 1e-5));
            let (mut m0, _) = at(&mut ws, w0);
            let mut out = WheelsetResult::default();
            for _ in 0..20 {
                let (m1, o) = at(&mut ws, w1);
                out = o;
                if m1.abs() < 1e-6 || m1 == m0 {
                    break;
                }
                let next = w1 - m1 * (w1 - w0) / (m1 - m0);
                (w0, m0, w1) = (w1, m1, next);
            }
            let fx = out.left.force[0] + out.right.force[0];
            assert!(
                fx.abs() < 1e-3 * mu * 2.0 * Q,
                "{} planar {planar}: net Fx {fx} N",
                model.name()
            );
        }
    }
}
