//! The track at the wheelset (docs/theory.md §8.1, §8.5; docs/conventions.md, "Track and rails"):
//! the curvature's creepages against the turning track frame's kinematics, a wheelset rolling
//! freely through a curve, rail displacements against the equivalent wheelset displacements,
//! rail velocities against the equivalent wheelset velocities, a rigid turn of track and wheelset
//! together, and the forces and moment on the rails.

mod common;

use common::builtin_wheelset_with;
use nalgebra::Vector3;
use railcontact::fmi::variables::Values;
use railcontact::models::wheel_rail_contact::INFO;
use railcontact::normal::NormalModel;
use railcontact::wheelset::{
    Creepages, PatchResult, RailInput, SideResult, TrackInput, Vertical, Wheelset, WheelsetInput,
    WheelsetResult, RAIL_INPUTS,
};

const Q: f64 = 78_500.0;
const MU_Q: f64 = 0.3 * Q;
const V: f64 = 30.0;
/// ω of free rolling at the centred wheelset's rolling radius (0.459987 m, the FMU's default).
const OMEGA: f64 = 65.2192;

fn kinematic(vy: f64, omega: f64) -> Creepages {
    Creepages::Kinematic {
        vx: V,
        vy,
        yaw_rate: 0.0,
        omega,
    }
}

fn input(y: f64, yaw: f64, track: TrackInput) -> WheelsetInput {
    WheelsetInput {
        y,
        yaw,
        roll: 0.0,
        vertical: Vertical::Loads { left: Q, right: Q },
        creepages: kinematic(0.0, OMEGA),
        track,
    }
}

fn solve(ws: &mut Wheelset, input: &WheelsetInput) -> WheelsetResult {
    let mut out = WheelsetResult::default();
    ws.solve(input, &mut out)
        .unwrap_or_else(|e| panic!("{input:?}: {e}"));
    out
}

fn wheelset(model: NormalModel, planar: bool) -> Wheelset {
    builtin_wheelset_with(|s| {
        s.normal_model = model;
        s.planar_patch = planar;
    })
}

fn curve(kappa: f64) -> TrackInput {
    TrackInput {
        curvature: kappa,
        ..TrackInput::default()
    }
}

fn loaded(side: &SideResult) -> impl Iterator<Item = (usize, &PatchResult)> + '_ {
    side.patches.iter().enumerate().filter(|(_, p)| p.fn_ > 0.0)
}

/// The creepages of every patch are those of the turning track frame's kinematics at the
/// patch's own point (xPos, yPos, zPos) from the wheelset centre and its contact angle γ:
/// Ω = (ω sin ψ, −ω cos ψ, ψ̇ + vx κ), v = (vx (1 − κ y), vy, 0) + Ω × r, ξ = v_x / V,
/// η = v·e_y / V, φ = Ω·e_z / V with e_y = (0, cos γ, −σ sin γ), e_z = (0, σ sin γ, cos γ).
/// Both wheels, R = ±300 m and 1200 m and straight, shifts ±6 mm (into flange contact), yaw
/// 0 and 2 mrad with a yaw rate, Hertz and ANALYN with a planar patch; r's vertical component
/// is the rolling radius (the kinematics' lever below the axle), 1e−12 the tolerance (round-off
/// of creepages of ~1e−3). The curvature's own share, Δφ = κ cos γ and Δξ = −κ (y + yPos), is
/// 1e−3 or more.
#[test]
fn curvature_enters_the_creepages_as_the_turning_track_frame() {
    for (model, planar) in [(NormalModel::Hertz, false), (NormalModel::Analyn, true)] {
        let mut ws = wheelset(model, planar);
        for kappa in [0.0, 1.0 / 300.0, -1.0 / 300.0, 1.0 / 1200.0] {
            for y in [0.0, 0.003, 0.006, -0.006] {
                for (yaw, yaw_rate) in [(0.0, 0.0), (0.002, 0.01)] {
                    let mut pose = input(y, yaw, curve(kappa));
                    pose.creepages = Creepages::Kinematic {
                        vx: V,
                        vy: 0.02,
                        yaw_rate,
                        omega: OMEGA,
                    };
                    let out = solve(&mut ws, &pose);
                    for (sigma, side) in [(-1.0, &out.left), (1.0, &out.right)] {
                        for (k, p) in loaded(side) {
                            let omega = Vector3::new(
                                OMEGA * yaw.sin(),
                                -OMEGA * yaw.cos(),
                                yaw_rate + V * kappa,
                            );
                            // The kinematics' lever below the axle is the rolling radius.
                            let r = Vector3::new(p.position[0], p.position[1], p.rolling_radius);
                            let v =
                                Vector3::new(V * (1.0 - kappa * y), 0.02, 0.0) + omega.cross(&r);
                            let (sin, cos) = p.contact_angle.sin_cos();
                            let e_y = Vector3::new(0.0, cos, -sigma * sin);
                            let e_z = Vector3::new(0.0, sigma * sin, cos);
                            let expected = [v.x / V, v.dot(&e_y) / V, omega.dot(&e_z) / V];
                            let got = [p.creepage.xi, p.creepage.eta, p.creepage.phi];
                            for (e, g) in expected.iter().zip(got) {
                                assert!(
                                    (g - e).abs() <= 1e-12,
                                    "{model:?} κ {kappa} y {y} yaw {yaw} σ {sigma} patch {k}: \
                                     {got:?}, expected {expected:?}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}

/// A rigid wheelset without yaw in a steady curve rolls freely where the rolling radii match the
/// curve: each wheel's contact at yPos from the centre covers 1 − κ (y + yPos) of the centre
/// line's distance, so ω r = vx (1 − κ (y + yPos)) on both wheels. At that shift and ω the
/// wheels carry no longitudinal force (below 1 % of μQ each); the same wheelset at the same ω
/// on straight track carries the curve's steering forces of several kN, so the curvature is
/// what cancels them. On the default elliptic (Hertz) patches, where spin carries no
/// longitudinal force by symmetry; a non-elliptic patch that is not symmetric about its centre
/// line carries one from its spin alone, on straight track as in the curve (ANALYN at −1.4 mm:
/// 0.7 kN), which no rolling speed removes.
#[test]
fn a_wheelset_rolling_freely_through_a_curve_carries_no_longitudinal_force() {
    {
        let model = NormalModel::Hertz;
        let mut ws = wheelset(model, false);
        for radius in [600.0, -600.0, 1200.0, -1200.0] {
            let kappa = 1.0 / radius;
            // ω each wheel needs to roll freely at the shift y; the shift where they agree.
            let mut omegas = |y: f64| {
                let out = solve(&mut ws, &input(y, 0.0, curve(kappa)));
                let rolling = |side: &SideResult| {
                    let (fn_sum, weighted) =
                        loaded(side).fold((0.0, [0.0; 2]), |(n, w), (_, p)| {
                            (
                                n + p.fn_,
                                [
                                    w[0] + p.fn_ * p.rolling_radius,
                                    w[1] + p.fn_ * p.position[1],
                                ],
                            )
                        });
                    let (r, y_pos) = (weighted[0] / fn_sum, weighted[1] / fn_sum);
                    V * (1.0 - kappa * (y + y_pos)) / r
                };
                (rolling(&out.left), rolling(&out.right))
            };
            let gap = |o: (f64, f64)| o.1 - o.0;
            let (mut lo, mut hi) = (-0.006, 0.006);
            let (g_lo, g_hi) = (gap(omegas(lo)), gap(omegas(hi)));
            assert!(
                g_lo * g_hi < 0.0,
                "{model:?} R {radius}: no shift in ±6 mm rolls freely"
            );
            for _ in 0..40 {
                let mid = 0.5 * (lo + hi);
                if gap(omegas(mid)) * g_lo > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let y = 0.5 * (lo + hi);
            let (omega_left, omega_right) = omegas(y);
            let omega = 0.5 * (omega_left + omega_right);
            // The curve's own shift: outwards (y < 0 in a right-hand curve).
            assert!(y * kappa < 0.0, "{model:?} R {radius}: shift {y}");
            let mut free = input(y, 0.0, curve(kappa));
            free.creepages = kinematic(0.0, omega);
            let out = solve(&mut ws, &free);
            let mut on_straight = free;
            on_straight.track = TrackInput::default();
            let straight = solve(&mut ws, &on_straight);
            for (side, s, t) in [
                ("left", &out.left, &straight.left),
                ("right", &out.right, &straight.right),
            ] {
                assert!(
                    s.force[0].abs() < 0.01 * MU_Q,
                    "{model:?} R {radius} {side}: Fx {} at y {y}",
                    s.force[0]
                );
                assert!(
                    t.force[0].abs() > 0.1 * MU_Q,
                    "{model:?} R {radius} {side}: Fx {} on straight track",
                    t.force[0]
                );
            }
            assert!((out.left.force[0] + out.right.force[0]).abs() < 0.01 * MU_Q);
        }
    }
}

fn rail(dy: f64) -> RailInput {
    RailInput {
        dy,
        ..RailInput::default()
    }
}

/// Straight track whose right rail moves as `rail`.
fn on_right(rail: RailInput) -> TrackInput {
    TrackInput {
        right: rail,
        ..TrackInput::default()
    }
}

fn assert_same_side(a: &SideResult, b: &SideResult, what: &str) {
    assert_eq!(a.n_patches, b.n_patches, "{what}");
    for (k, p) in loaded(a) {
        let q = &b.patches[k];
        let close = |x: f64, y: f64, tol: f64| (x - y).abs() <= tol;
        assert!(close(p.y_rail, q.y_rail, 1e-8), "{what} patch {k}: yRail");
        assert!(
            close(p.contact_angle, q.contact_angle, 1e-8),
            "{what} patch {k}: angle"
        );
        for i in 0..3 {
            assert!(
                close(p.position[i], q.position[i], 1e-8),
                "{what} patch {k}: position"
            );
        }
        assert!(close(p.fn_, q.fn_, 1e-6 * p.fn_), "{what} patch {k}: Fn");
        assert!(close(p.fx, q.fx, 1e-6 * Q), "{what} patch {k}: Fx");
        assert!(close(p.fy, q.fy, 1e-6 * Q), "{what} patch {k}: Fy");
        assert!(
            close(p.creepage.eta, q.creepage.eta, 1e-9),
            "{what} patch {k}: η"
        );
    }
    for i in 0..3 {
        assert!((a.force[i] - b.force[i]).abs() <= 1e-6 * Q, "{what}: force");
    }
}

/// A rail displaced by d on one side gives that wheel the contact of the wheelset displaced by
/// −d (the other wheel keeps its own); the two rails displaced apart by 1 mm each give the
/// contact of a gauge 2 mm wider. Yawed, on Hertz and ANALYN, into flange contact.
#[test]
fn a_rail_displacement_is_the_opposite_wheelset_displacement_on_its_side() {
    for model in [NormalModel::Hertz, NormalModel::Analyn] {
        let mut ws = wheelset(model, false);
        for d in [-0.002, 0.001, 0.004] {
            for (right, y) in [(true, 0.002), (false, -0.001)] {
                let mut track = TrackInput::default();
                *(if right {
                    &mut track.right
                } else {
                    &mut track.left
                }) = rail(d);
                let moved_rail = solve(&mut ws, &input(y, 0.001, track));
                let moved_wheelset = solve(&mut ws, &input(y - d, 0.001, TrackInput::default()));
                let still = solve(&mut ws, &input(y, 0.001, TrackInput::default()));
                let what = format!("{model:?} d {d} right {right}");
                let (rail_side, other, shifted, kept) = if right {
                    (
                        &moved_rail.right,
                        &moved_rail.left,
                        &moved_wheelset.right,
                        &still.left,
                    )
                } else {
                    (
                        &moved_rail.left,
                        &moved_rail.right,
                        &moved_wheelset.left,
                        &still.right,
                    )
                };
                assert_same_side(rail_side, shifted, &what);
                assert_same_side(other, kept, &format!("{what}, the other wheel"));
            }
        }
        let track = TrackInput {
            left: rail(-0.001),
            right: rail(0.001),
            ..TrackInput::default()
        };
        let rails = solve(&mut ws, &input(0.003, 0.001, track));
        let mut ws2 = builtin_wheelset_with(|s| {
            s.normal_model = model;
            s.setup.track_gauge += 0.002;
        });
        let gauge = solve(&mut ws2, &input(0.003, 0.001, TrackInput::default()));
        assert_same_side(&rails.left, &gauge.left, &format!("{model:?} gauge, left"));
        assert_same_side(
            &rails.right,
            &gauge.right,
            &format!("{model:?} gauge, right"),
        );
    }
}

/// A rail's lateral velocity u gives that wheel the creepages of the wheelset moving at −u. Its
/// vertical velocity w moves the rail's material under the contact: Δη = −v_R·e_y / V with
/// e_y = (0, cos γ, −σ sin γ), here w sin γ / V on the right wheel (the rail moving down under a
/// flange contact slides it up the flank). Its roll rate θ̇ moves the rail's point at
/// (σ yRail, depth) from its origin with θ̇ (−depth, σ yRail): Δη = θ̇ (depth cos γ + yRail sin γ)
/// / V, the depth that of the mounted rail at yRail; the kinematics takes it from the rolling
/// radius (r − wheelRadius), which leaves out the wheel's lowering and the approach.
#[test]
fn rail_velocities_enter_the_creepages_as_relative_velocities() {
    let mut ws = wheelset(NormalModel::Hertz, false);
    for y in [0.0, 0.006] {
        let rail_moving = on_right(RailInput {
            vy: 0.01,
            ..RailInput::default()
        });
        let a = solve(&mut ws, &input(y, 0.0, rail_moving));
        let mut wheelset_moving = input(y, 0.0, TrackInput::default());
        wheelset_moving.creepages = kinematic(-0.01, OMEGA);
        let b = solve(&mut ws, &wheelset_moving);
        assert_same_side(&a.right, &b.right, &format!("vy at y {y}"));
        let base = solve(&mut ws, &input(y, 0.0, TrackInput::default()));
        let (w, rate) = (0.01, 0.05);
        let vertical = on_right(RailInput {
            vz: w,
            ..RailInput::default()
        });
        let c = solve(&mut ws, &input(y, 0.0, vertical));
        let rolling = on_right(RailInput {
            roll_rate: rate,
            ..RailInput::default()
        });
        let d = solve(&mut ws, &input(y, 0.0, rolling));
        let mounted = ws.geometry(true).rail().profile().clone();
        for (k, p) in loaded(&base.right) {
            let (sin, cos) = p.contact_angle.sin_cos();
            let expected_w = w * sin / V;
            let got_w = c.right.patches[k].creepage.eta - p.creepage.eta;
            assert!(
                (got_w - expected_w).abs() <= 1e-3 * expected_w.abs() + 1e-9,
                "vz at y {y} patch {k}: {got_w} against {expected_w}"
            );
            let depth = mounted.z(p.y_rail);
            let expected_r = rate * (depth * cos + p.y_rail * sin) / V;
            let got_r = d.right.patches[k].creepage.eta - p.creepage.eta;
            let lowering = base.right.z.abs() + p.penetration;
            assert!(
                (got_r - expected_r).abs() <= rate * (lowering + 1e-5) * cos / V,
                "roll rate at y {y} patch {k}: {got_r} against {expected_r}"
            );
        }
    }
}

/// Turning track and wheelset together about the track centre line at the rails' top by θ
/// (each rail rolled by θ and carried by (dy, dz) = Y_O (cos θ − 1, sin θ), the wheelset's
/// centre from (y, −h) to (y cos θ + h sin θ, y sin θ − h cos θ) and rolled by θ) changes
/// nothing in the contact: the same patches at the same rail coordinates with the same normal
/// forces; the wheels' forces turn with it. With a prescribed height (`verticalMode` 2), so that
/// the loads need no direction; ANALYN, a tread and a flange-root state.
#[test]
fn turning_track_and_wheelset_together_changes_no_contact() {
    let mut ws = wheelset(NormalModel::Analyn, false);
    let h = ws.settings().setup.wheel_radius;
    let origin = ws.geometry(true).rail().origin_lateral();
    for (y, z) in [(0.0, 8e-5), (0.003, 3e-5)] {
        let level = WheelsetInput {
            y,
            yaw: 0.0,
            roll: 0.0,
            vertical: Vertical::Position { z },
            creepages: kinematic(0.0, OMEGA),
            track: TrackInput::default(),
        };
        let a = solve(&mut ws, &level);
        for theta in [0.002, -0.003] {
            let (sin, cos) = f64::sin_cos(theta);
            let carried = |sigma: f64| RailInput {
                dy: sigma * origin * (cos - 1.0),
                dz: sigma * origin * sin,
                roll: theta,
                ..RailInput::default()
            };
            let turned = WheelsetInput {
                y: y * cos + h * sin,
                roll: theta,
                vertical: Vertical::Position {
                    z: z + y * sin + h * (1.0 - cos),
                },
                track: TrackInput {
                    left: carried(-1.0),
                    right: carried(1.0),
                    ..TrackInput::default()
                },
                ..level
            };
            let b = solve(&mut ws, &turned);
            for (name, s, t) in [("left", &a.left, &b.left), ("right", &a.right, &b.right)] {
                let what = format!("θ {theta} y {y} {name}");
                assert_eq!(s.n_patches, t.n_patches, "{what}");
                for (k, p) in loaded(s) {
                    let q = &t.patches[k];
                    // The contact search's sampling and interpolation meet the turned pose
                    // at other points: µm and 1e−4 rad.
                    assert!((p.y_rail - q.y_rail).abs() < 1e-6, "{what} {k}: yRail");
                    assert!(
                        (p.contact_angle - q.contact_angle).abs() < 1e-4,
                        "{what} {k}: angle {} {} yRail {} {} Fn {} {}",
                        p.contact_angle,
                        q.contact_angle,
                        p.y_rail,
                        q.y_rail,
                        p.fn_,
                        q.fn_
                    );
                    assert!((p.fn_ - q.fn_).abs() < 1e-3 * p.fn_, "{what} {k}: Fn");
                    assert!(
                        p.fn_ < 2.0 * Q,
                        "{what} {k}: Fn {} (a plausible state)",
                        p.fn_
                    );
                }
                let [_, fy, fz] = s.force;
                let turned_force = [fy * cos - fz * sin, fy * sin + fz * cos];
                for (i, f) in turned_force.iter().enumerate() {
                    assert!(
                        (t.force[i + 1] - f).abs() < 2e-3 * Q,
                        "{what}: force {:?} against {turned_force:?}",
                        t.force
                    );
                }
            }
        }
    }
}

/// The wheel's force on the rail is the rail's on the wheel reversed, and its moment about the
/// rail's origin is that of the patches' forces at their points on the rail — on displaced and
/// rolled rails, in the rail's own frame (a turn about x keeps the x moment), where the patches'
/// contact angles and yRail are given: (σ yRail, depth of
/// the mounted rail at yRail) from the origin, the patch forces in track axes; within the
/// approach's vertical share (the reference point lies on the wheel's rigid surface, the approach
/// along the normal below the rail's) times the lateral force.
#[test]
fn the_rails_carry_the_wheels_forces_about_their_own_origin() {
    for (model, planar) in [(NormalModel::Hertz, false), (NormalModel::Analyn, true)] {
        let mut ws = wheelset(model, planar);
        for (y, dy, roll) in [
            (0.0, 0.0, 0.0),
            (0.004, 0.001, 0.0),
            (0.0065, -0.0005, 0.0),
            (0.002, 0.0005, 0.002),
            (0.005, 0.0, -0.003),
        ] {
            let moved = RailInput {
                dy,
                roll,
                ..RailInput::default()
            };
            let track = TrackInput {
                right: moved,
                left: moved,
                ..TrackInput::default()
            };
            let out = solve(&mut ws, &input(y, 0.001, track));
            for (right, side) in [(false, &out.left), (true, &out.right)] {
                let sigma = if right { 1.0 } else { -1.0 };
                for i in 0..3 {
                    assert_eq!(side.rail_force[i], -side.force[i]);
                }
                let mounted = ws.geometry(right).rail().profile().clone();
                let (mut moment, mut tolerance) = (0.0, 1e-9 * Q);
                for p in side.all_patches() {
                    let (sin, cos) = p.contact_angle.sin_cos();
                    // F = Fx e_x + Fy e_y − N e_z on the wheel; −F on the rail.
                    let fy = p.fy * cos - p.fn_ * sigma * sin;
                    let fz = -p.fy * sigma * sin - p.fn_ * cos;
                    let (ly, lz) = (sigma * p.y_rail, mounted.z(p.y_rail));
                    moment += -(ly * fz - lz * fy);
                    // The force acts at the reference point on the wheel's rigid surface, the
                    // approach below the rail's.
                    tolerance += fy.abs() * 1.01 * p.penetration / cos;
                    // Turned against its rail by θ, the wheel's reference point lies up to
                    // 0.01 θ m (20–30 µm) laterally off its rail point, as under the wheelset's
                    // own roll: 0.1 % of the moment.
                    tolerance += fz.abs() * 1e-2 * roll.abs();
                }
                assert!(
                    (side.rail_moment_x - moment).abs() < tolerance,
                    "{model:?} y {y} dy {dy} roll {roll} right {right}: Mx {} against {moment}",
                    side.rail_moment_x
                );
            }
        }
    }
}

/// The FMU's inputs and outputs by name: a rail displacement set through the variable table
/// moves that wheel's contact as the wheelset's opposite displacement, and the rail outputs
/// are the wheel's forces reversed.
#[test]
fn the_fmu_takes_the_track_inputs_and_gives_the_rail_forces() {
    let evaluate = |inputs: &[(&str, f64)]| {
        let mut values = Values::from_start(INFO.variables, INFO.counts);
        let mut model = (INFO.create)(&Default::default());
        model.initialize(&values).expect("initialize");
        for &(name, x) in inputs {
            let v = INFO
                .variable(name)
                .unwrap_or_else(|| panic!("no variable {name}"));
            values.reals[v.slot] = x;
        }
        model.evaluate(&mut values, 0.0).expect("evaluate");
        move |name: &str| values.reals[INFO.variable(name).expect(name).slot]
    };
    let rail = evaluate(&[("right.rail.dy", 0.002), ("trackCurvature", 0.0)]);
    let wheelset = evaluate(&[("y", -0.002)]);
    for name in [
        "right.p1.yRail",
        "right.p1.Fn",
        "right.p1.contactAngle",
        "right.Fy",
    ] {
        assert!((rail(name) - wheelset(name)).abs() < 1e-9 * wheelset(name).abs().max(1.0));
    }
    for side in ["left", "right"] {
        for q in ["Fy", "Fz"] {
            assert_eq!(
                rail(&format!("{side}.rail.{q}")),
                -rail(&format!("{side}.{q}"))
            );
        }
        assert!(rail(&format!("{side}.rail.Mx")).abs() > 0.0);
    }
    let curved = evaluate(&[("trackCurvature", 1.0 / 500.0)]);
    let straight = evaluate(&[]);
    let d_phi = curved("right.p1.phi") - straight("right.p1.phi");
    assert!((d_phi - curved("right.p1.contactAngle").cos() / 500.0).abs() < 1e-6);
}

/// A long run as a track model drives it: a random walk of the wheelset's shift and yaw, the
/// track's curvature (R ≥ 300 m either way) and both rails' displacements (±1 mm, ±1 mrad) and
/// velocities, stepped through the FMU's model with its warm starts. Every step is answered
/// with finite outputs and rails carrying the wheels' forces reversed; every 250th step equals a
/// fresh instance's answer at the same inputs (the warm start changes nothing beyond the load
/// balance's tolerance, 1e−6 of the load).
#[test]
fn a_random_walk_over_track_and_rails_stays_finite_balanced_and_history_free() {
    let names: Vec<&str> = ["y", "yaw", "trackCurvature"]
        .into_iter()
        .chain(RAIL_INPUTS.iter().flatten().copied())
        .collect();
    // (bound, step) per input: the pose, the curvature, then per rail dy, dz, roll, vy, vz,
    // rollRate.
    let rail = [
        (1e-3, 5e-5),
        (1e-3, 5e-5),
        (1e-3, 5e-5),
        (0.05, 5e-3),
        (0.05, 5e-3),
        (0.05, 5e-3),
    ];
    let bounds: Vec<(f64, f64)> = [(5e-3, 1e-4), (3e-3, 1e-4), (1.0 / 300.0, 2e-4)]
        .into_iter()
        .chain(rail)
        .chain(rail)
        .collect();
    let slot = |name: &str| INFO.variable(name).expect(name).slot;
    let fresh = |model: i32| {
        let mut values = Values::from_start(INFO.variables, INFO.counts);
        values.integers[slot("normalModel")] = model;
        let mut m = (INFO.create)(&Default::default());
        m.initialize(&values).expect("initialize");
        (m, values)
    };
    let outputs: Vec<usize> = INFO
        .variables
        .iter()
        .filter(|v| v.causality == railcontact::fmi::variables::Causality::Output)
        .filter(|v| v.ty == railcontact::fmi::variables::VarType::Real)
        .map(|v| v.slot)
        .collect();
    for (model, steps) in [(1, 1500), (6, 600)] {
        let (mut m, mut values) = fresh(model);
        let mut state = vec![0.0; names.len()];
        let mut seed = 0x2545_f491_4f6c_dd1d_u64 ^ model as u64;
        for k in 0..steps {
            for (x, &(bound, step)) in state.iter_mut().zip(&bounds) {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                let unit = (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
                *x = (*x + step * unit).clamp(-bound, bound);
            }
            for (name, &x) in names.iter().zip(&state) {
                values.reals[slot(name)] = x;
            }
            m.evaluate(&mut values, k as f64 * 1e-3)
                .unwrap_or_else(|e| panic!("model {model} step {k} {state:?}: {e:?}"));
            m.advance(&mut values, 1e-3).expect("advance");
            assert!(
                outputs.iter().all(|&s| values.reals[s].is_finite()),
                "step {k}"
            );
            for side in ["left", "right"] {
                for q in ["Fy", "Fz"] {
                    let (rail, wheel) = (format!("{side}.rail.{q}"), format!("{side}.{q}"));
                    assert_eq!(values.reals[slot(&rail)], -values.reals[slot(&wheel)]);
                }
            }
            if k % 250 == 249 {
                let (mut cold, mut cold_values) = fresh(model);
                for (name, &x) in names.iter().zip(&state) {
                    cold_values.reals[slot(name)] = x;
                }
                cold.evaluate(&mut cold_values, 0.0).expect("cold");
                for name in [
                    "left.Fy",
                    "right.Fy",
                    "left.Fz",
                    "right.Mx",
                    "right.rail.Mx",
                ] {
                    let (warm, cold) = (values.reals[slot(name)], cold_values.reals[slot(name)]);
                    assert!(
                        (warm - cold).abs() <= 1e-6 * Q,
                        "model {model} step {k} {name}: {warm} warm, {cold} cold"
                    );
                }
            }
        }
    }
}

/// The track inputs move the forces continuously: sweeps of a rail's roll over ±3 mrad and of
/// the curvature over R ≥ 250 m either way, 600 steps each (a rail's lateral shift is the
/// wheelset's, whose sweeps `tests/continuity.rs` runs), at a tread and a flange-root shift: no
/// step changes a wheel's force by more than 0.5 % of the load (a jump between contact states
/// would), and every sweep changes it.
#[test]
fn rail_roll_and_curvature_sweeps_are_continuous() {
    for model in [NormalModel::Hertz, NormalModel::Analyn] {
        let mut ws = wheelset(model, false);
        for y in [0.0, 0.004] {
            type Sweep = fn(&mut WheelsetInput, f64);
            let sweeps: [(&str, f64, Sweep); 2] = [
                ("roll", 3e-3, |i, x| i.track.right.roll = x),
                ("curvature", 1.0 / 250.0, |i, x| i.track.curvature = x),
            ];
            for (name, bound, apply) in sweeps {
                let mut last: Option<[f64; 3]> = None;
                let (mut largest, mut total) = (0.0f64, 0.0f64);
                for k in 0..=600 {
                    let x = -bound + 2.0 * bound * k as f64 / 600.0;
                    let mut pose = input(y, 0.0, TrackInput::default());
                    apply(&mut pose, x);
                    let out = solve(&mut ws, &pose);
                    let force = out.right.force;
                    if let Some(prev) = last {
                        let step = (0..3)
                            .map(|i| (force[i] - prev[i]).abs())
                            .fold(0.0, f64::max);
                        largest = largest.max(step);
                        total += step;
                    }
                    last = Some(force);
                }
                let what = format!("{model:?} y {y} {name}");
                assert!(largest < 5e-3 * Q, "{what}: a step of {largest} N");
                assert!(
                    total > 10.0,
                    "{what}: the sweep changes nothing ({total} N)"
                );
            }
        }
    }
}
