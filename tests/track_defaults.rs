//! The element as users run it first: the built-in S1002/UIC60 pair at the default rail
//! inclination, yawed wheelsets, the default inputs. Checked against the benchmark profile files
//! (which carry the 1:40 cant in the rail file), the exact theory's central case (CONTACT) and
//! the linear theory's statements about yaw and spin.

mod common;

use common::{benchmark_wheelset, builtin_wheelset_with, read_csv, STEEL};
use railcontact::fmi::variables::Start;
use railcontact::normal::NormalModel;
use railcontact::tangential::fastsim::Creepage;
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::{
    Creepages, PatchResult, SideResult, Vertical, Wheelset, WheelsetInput, WheelsetResult,
};

const Q: f64 = 78_500.0;
const MU_Q: f64 = 0.3 * Q;

fn input(y: f64, yaw: f64, creepages: Creepages) -> WheelsetInput {
    WheelsetInput {
        y,
        yaw,
        roll: 0.0,
        vertical: Vertical::Loads { left: Q, right: Q },
        creepages,
        track: Default::default(),
    }
}

fn rolling(vx: f64, vy: f64) -> Creepages {
    Creepages::Kinematic {
        vx,
        vy,
        yaw_rate: 0.0,
        omega: vx / 0.46,
    }
}

fn solve(ws: &mut Wheelset, input: &WheelsetInput) -> WheelsetResult {
    let mut out = WheelsetResult::default();
    ws.solve(input, &mut out)
        .unwrap_or_else(|e| panic!("{input:?}: {e}"));
    out
}

/// The patch carrying the largest normal force.
fn main_patch(side: &SideResult) -> PatchResult {
    *side
        .all_patches()
        .iter()
        .max_by(|a, b| a.fn_.total_cmp(&b.fn_))
        .expect("a patch")
}

/// The built-in pair at the default inclination (the rail leaning 1:40 towards the track
/// centre) is the benchmark pair, whose rail file carries the cant: the main patch's contact
/// angle and rail position agree over tread and flange contact on both wheels. Tolerances: the
/// built-in UIC60 is built from the EN arcs, the benchmark file is a measured-style polyline of
/// the same head (they differ by up to 0.03 mm, `profile::uic60`); measured 0.0016 rad and
/// 0.14 mm at worst (Hertz, 78.5 kN, −8 … +10 mm); bounds 0.005 rad and 0.5 mm.
#[test]
fn built_in_pair_at_the_default_inclination_is_the_benchmark_pair() {
    for model in [NormalModel::Hertz, NormalModel::Analyn] {
        let mut built_in = builtin_wheelset_with(|s| s.normal_model = model);
        let mut files = benchmark_wheelset(STEEL, model);
        // ANALYN on the tread shifts only (its strips resolve flange contact differently on
        // the two rails' slightly different gauge corners).
        let range = if model == NormalModel::Hertz {
            -16..=20
        } else {
            -2..=8
        };
        for k in range {
            let y = k as f64 * 0.5e-3;
            let pose = input(y, 0.0, rolling(30.0, 0.0));
            let (a, b) = (solve(&mut built_in, &pose), solve(&mut files, &pose));
            for (name, sa, sb) in [("left", &a.left, &b.left), ("right", &a.right, &b.right)] {
                let (pa, pb) = (main_patch(sa), main_patch(sb));
                assert!(
                    (pa.contact_angle - pb.contact_angle).abs() < 0.005,
                    "{model:?} y {y}: {name} angle {} vs {}",
                    pa.contact_angle,
                    pb.contact_angle
                );
                assert!(
                    (pa.y_rail - pb.y_rail).abs() < 5e-4,
                    "{model:?} y {y}: {name} yRail {} vs {}",
                    pa.y_rail,
                    pb.y_rail
                );
            }
        }
    }
}

/// The central case with the built-in profiles at their default inclination against the exact
/// theory (CONTACT, `reference/central`, computed on the benchmark files): the contact angle
/// within 0.005 rad (CONTACT's right-wheel angle is −our sign, `docs/conventions.md`).
#[test]
fn built_in_central_case_contact_angle_matches_the_exact_theory() {
    let reference = read_csv("reference/central/normal_dy0_summary.csv");
    let angle = -reference[0]["delta_cp_rail_rad"];
    for model in [NormalModel::Hertz, NormalModel::Analyn] {
        let mut ws = builtin_wheelset_with(|s| s.normal_model = model);
        let out = solve(&mut ws, &input(0.0, 0.0, rolling(2.0, 0.0)));
        let p = main_patch(&out.right);
        assert!(
            (p.contact_angle - angle).abs() < 0.005,
            "{model:?}: {} vs CONTACT {angle}",
            p.contact_angle
        );
    }
}

/// With prescribed creepages (η = −4e−4, φ = 0.2 1/m) the creep forces hold at the patch's
/// reference point: a yaw of ±4 mrad moves it (the yaw lead) but does not change the rigid slip
/// there, so the lateral force changes only by the patch's small geometric change. Every model,
/// every tangential option, planar and non-planar; measured ≤ 0.12 % of μQ, bound 1 %.
#[test]
fn prescribed_creepages_give_forces_independent_of_the_yaw_angle() {
    let creepages = Creepages::Prescribed {
        creepage: Creepage {
            xi: 0.0,
            eta: -4e-4,
            phi: 0.2,
        },
        vx: 30.0,
    };
    for model in NormalModel::ALL {
        for tangential in [TangentialModel::ModelDefault, TangentialModel::Fastrip] {
            for planar in [false, true] {
                let mut ws = builtin_wheelset_with(|s| {
                    s.normal_model = model;
                    s.tangential = tangential;
                    s.planar_patch = planar;
                });
                let straight = solve(&mut ws, &input(0.0, 0.0, creepages)).right.force[1];
                for yaw in [4e-3, -4e-3] {
                    let yawed = solve(&mut ws, &input(0.0, yaw, creepages)).right.force[1];
                    assert!(
                        (yawed - straight).abs() < 0.01 * MU_Q,
                        "{model:?} {tangential:?} planar {planar} yaw {yaw}: Fy {yawed} vs \
                         {straight}"
                    );
                }
            }
        }
    }
}

/// With kinematic creepages a yaw ψ slips the wheel laterally like a lateral velocity −Vψ
/// (the linear theory's η = vy/V − ψ): the change of the total lateral force from ψ = 0.5 mrad
/// and from vy = −Vψ agree. Every model, planar and non-planar; measured within 0.2 %, bound
/// 1 % (the yaw also shifts the contact point and adds its lead to the rolling radius).
#[test]
fn a_yaw_angle_and_the_equivalent_lateral_velocity_give_the_same_lateral_force() {
    let (v, yaw) = (30.0, 5e-4);
    for model in NormalModel::ALL {
        for planar in [false, true] {
            let mut ws = builtin_wheelset_with(|s| {
                s.normal_model = model;
                s.planar_patch = planar;
            });
            let fy = |ws: &mut Wheelset, yaw: f64, vy: f64| {
                let out = solve(ws, &input(0.0, yaw, rolling(v, vy)));
                out.left.force[1] + out.right.force[1]
            };
            let base = fy(&mut ws, 0.0, 0.0);
            let by_yaw = fy(&mut ws, yaw, 0.0) - base;
            let by_vy = fy(&mut ws, 0.0, -v * yaw) - base;
            assert!(
                (by_yaw / by_vy - 1.0).abs() < 0.01,
                "{model:?} planar {planar}: {by_yaw} N per yaw, {by_vy} N per vy"
            );
        }
    }
}

/// The default inputs (the variables' start values: centred, 78.5 kN, vx = 30 m/s and the
/// default `omega`) roll freely: |Fx| of each wheel within 2 % of μQ.
#[test]
fn default_inputs_roll_freely() {
    let info = &railcontact::models::wheel_rail_contact::INFO;
    let start = |name: &str| match info.variable(name).map(|v| v.start) {
        Some(Start::Real(x)) => x,
        other => panic!("start value of {name}: {other:?}"),
    };
    let mut ws = builtin_wheelset_with(|_| {});
    let out = solve(
        &mut ws,
        &WheelsetInput {
            y: start("y"),
            yaw: start("yaw"),
            roll: start("roll"),
            vertical: Vertical::Loads {
                left: start("Qleft"),
                right: start("Qright"),
            },
            creepages: Creepages::Kinematic {
                vx: start("vx"),
                vy: start("vy"),
                yaw_rate: start("yawRate"),
                omega: start("omega"),
            },
            track: Default::default(),
        },
    );
    let mu_q = start("mu") * start("Qright");
    for side in [&out.left, &out.right] {
        assert!(side.force[0].abs() < 0.02 * mu_q, "Fx {}", side.force[0]);
    }
}
