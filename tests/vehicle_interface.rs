//! What a vehicle host reads from the WheelRailContact FMU, through its exported C functions:
//! the wheels' wrenches about the wheelset centre, the patches' positions and Y/Q
//! (`docs/conventions.md`, "The wheelset on the track"), and their directional derivatives
//! (`src/fmi/derivative.rs`; HertzContact's too).

mod linked;

use fmi_host::Instance;
use linked::{Checked, ERROR, OK};
use railcontact::fmi::variables::{Causality, Variability};
use railcontact::models::{hertz_contact, wheel_rail_contact::INFO};

const SIDES: [(&str, f64); 2] = [("left", -1.0), ("right", 1.0)];
const PATCHES: [&str; 3] = ["p1", "p2", "p3"];

/// A WheelRailContact instance with the integer parameters `ints` and `planarPatch` set,
/// initialized, with the inputs `inputs` set.
fn instance(name: &str, ints: &[(&str, i32)], planar: bool, inputs: &[(&str, f64)]) -> Instance {
    let f = linked::instantiate(&INFO, name);
    for &(n, k) in ints {
        assert_eq!(f.set_integer(n, k), OK, "{n} = {k}");
    }
    assert_eq!(f.set_boolean("planarPatch", planar), OK);
    f.init();
    set_all(&f, inputs);
    f
}

fn set_all(f: &Instance, inputs: &[(&str, f64)]) {
    for &(n, x) in inputs {
        assert_eq!(f.set_real(n, x), OK, "{n} = {x}: {:?}", f.errors());
    }
}

/// One communication step of 1 ms from t = 0.
#[track_caller]
fn step(f: &Instance) {
    assert_eq!(f.step(0.0, 1e-3), OK, "{:?}", f.errors());
}

type V3 = [f64; 3];

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: V3) -> f64 {
    a.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// A wheel's force and moment about the wheelset centre rebuilt from its patch outputs alone,
/// with the contact axes of `docs/conventions.md`: F_k = Fx e_x + Fy e_y − Fn e_z at the
/// patch's position r_k, M = Σ r_k × F_k + Mz_k e_z; and the largest |r_k||F_k| (the scale of
/// the moment's round-off).
fn rebuilt_wrench(f: &Instance, side: &str, sigma: f64) -> (V3, V3, f64) {
    let (mut force, mut moment, mut scale) = ([0.0; 3], [0.0; 3], 0.0f64);
    for p in PATCHES {
        let g = |q: &str| f.real(&format!("{side}.{p}.{q}"));
        if g("Fn") == 0.0 {
            continue;
        }
        let (sin_g, cos_g) = g("contactAngle").sin_cos();
        let e_y = [0.0, cos_g, -sigma * sin_g];
        let e_z = [0.0, sigma * sin_g, cos_g];
        let (fx, fy, fn_, mz) = (g("Fx"), g("Fy"), g("Fn"), g("Mz"));
        let fk: V3 = std::array::from_fn(|i| fy * e_y[i] - fn_ * e_z[i] + [fx, 0.0, 0.0][i]);
        let r = [g("xPos"), g("yPos"), g("zPos")];
        let m = cross(r, fk);
        for i in 0..3 {
            force[i] += fk[i];
            moment[i] += m[i] + mz * e_z[i];
        }
        scale = scale.max(norm(r) * norm(fk));
    }
    (force, moment, scale)
}

fn totals(f: &Instance, side: &str) -> (V3, V3) {
    let g = |q: &str| f.real(&format!("{side}.{q}"));
    ([g("Fx"), g("Fy"), g("Fz")], [g("Mx"), g("My"), g("Mz")])
}

/// Poses over tread, two-point and flange contact with yaw and roll, and their creep motion.
fn poses() -> Vec<Vec<(&'static str, f64)>> {
    let mut out = Vec::new();
    for (y, yaw, roll) in [
        (0.0, 0.0, 0.0),
        (3e-3, 4e-3, 1e-3),
        (6.5e-3, -3e-3, 2e-3),
        (8e-3, 8e-3, -1e-3),
        (-7.5e-3, 5e-3, 0.0),
    ] {
        out.push(vec![
            ("y", y),
            ("yaw", yaw),
            ("roll", roll),
            ("vx", 20.0),
            ("vy", 0.05),
            ("yawRate", 0.02),
            ("omega", 20.0 / 0.46 * (1.0 + 5e-4)),
        ]);
    }
    out
}

/// The moment outputs equal Σ r × F + Mz e_z rebuilt from the patch outputs (positions, angles,
/// forces) and the forces their sum. Hertz patches and planar strip patches: the forces to
/// round-off (a reported patch's force is the whole force of its region decomposed in its axes);
/// the moments to round-off where a reported patch is one internal patch, and within the lever
/// of its pieces about its load centre where it combines several (a two-lobe region, 2.5 N·m
/// of 41 kN·m at 6.5 mm: 1e−4 allowed). Non-planar strip patches sum each strip's force in its
/// own axes, and `pk.Fy` is only the component along the patch's e_y: their forces and moments
/// agree within the out-of-plane part, (γ_j − γ)²/2 of Fy with the strips' angles γ_j a few
/// hundredths of a radian from the patch's on the tread (2 % of the force's magnitude allowed).
#[test]
fn moments_are_the_patch_forces_at_their_positions() {
    for (model, planar, force_tolerance, moment_tolerance) in [
        (1, true, 1e-9, 1e-4),
        (6, true, 1e-9, 1e-4),
        (2, false, 2e-2, 2e-2),
    ] {
        for (i, pose) in poses().into_iter().enumerate() {
            let name = format!("wrench{model}{planar}{i}");
            let f = instance(&name, &[("normalModel", model)], planar, &pose);
            step(&f);
            for (side, sigma) in SIDES {
                let (force, moment) = totals(&f, side);
                let (f_sum, m_sum, scale) = rebuilt_wrench(&f, side, sigma);
                let what = format!("model {model} planar {planar} pose {pose:?} {side}");
                for k in 0..3 {
                    assert!(
                        (force[k] - f_sum[k]).abs() <= force_tolerance * norm(force),
                        "{what}: F[{k}] {} vs patches {}",
                        force[k],
                        f_sum[k]
                    );
                    assert!(
                        (moment[k] - m_sum[k]).abs() <= moment_tolerance * scale,
                        "{what}: M[{k}] {} vs patches {}",
                        moment[k],
                        m_sum[k]
                    );
                }
            }
        }
    }
}

/// The mirror image of a pose (y → −y: lateral shift, yaw, roll, lateral velocity and yaw rate
/// change sign) swaps the wheels and mirrors their wrenches: Fx, Fz, My unchanged, Fy, Mx, Mz
/// negated (a moment is a pseudo-vector); positions keep x and z and negate y; Y/Q is the same.
/// Both wheels are mirror images (the left side mounted mirrored), so this holds to round-off.
#[test]
fn a_mirrored_pose_mirrors_the_wrench() {
    for model in [1, 6] {
        for (i, pose) in poses().into_iter().enumerate() {
            let mirrored: Vec<_> = pose
                .iter()
                .map(|&(n, x)| {
                    let odd = matches!(n, "y" | "yaw" | "roll" | "vy" | "yawRate");
                    (n, if odd { -x } else { x })
                })
                .collect();
            let a = instance(
                &format!("mirrorA{model}{i}"),
                &[("normalModel", model)],
                false,
                &pose,
            );
            let b = instance(
                &format!("mirrorB{model}{i}"),
                &[("normalModel", model)],
                false,
                &mirrored,
            );
            step(&a);
            step(&b);
            for (side, other) in [("left", "right"), ("right", "left")] {
                let close = |q: &str, sign: f64| {
                    let (x, y) = (
                        a.real(&format!("{side}.{q}")),
                        b.real(&format!("{other}.{q}")),
                    );
                    let tol = 1e-7 * (1.0 + x.abs());
                    assert!(
                        (x - sign * y).abs() <= tol,
                        "{pose:?} {side}.{q}: {x} vs {sign} × {y}"
                    );
                };
                for (q, sign) in [
                    ("Fx", 1.0),
                    ("Fy", -1.0),
                    ("Fz", 1.0),
                    ("Mx", -1.0),
                    ("My", 1.0),
                    ("Mz", -1.0),
                    ("YQ", 1.0),
                ] {
                    close(q, sign);
                }
                // The heaviest patch (slots may be numbered differently) sits at the mirrored
                // position.
                let heaviest = |f: &Instance, s: &str| {
                    PATCHES
                        .iter()
                        .max_by(|p, q| {
                            let n = |p: &&&str| f.real(&format!("{s}.{p}.Fn"));
                            n(p).total_cmp(&n(q))
                        })
                        .map(|p| {
                            let g = |q: &str| f.real(&format!("{s}.{p}.{q}"));
                            [g("xPos"), g("yPos"), g("zPos")]
                        })
                        .unwrap()
                };
                let (pa, pb) = (heaviest(&a, side), heaviest(&b, other));
                for (k, sign) in [1.0, -1.0, 1.0].into_iter().enumerate() {
                    assert!(
                        (pa[k] - sign * pb[k]).abs() <= 1e-9,
                        "{pose:?} {side}: position {pa:?} vs mirrored {pb:?}"
                    );
                }
            }
        }
    }
}

/// Positions: without yaw and roll the reference point lies in the axle's vertical plane
/// (xPos = 0) at the rolling radius below the centre (zPos = rollingRadius); under a yaw ψ the
/// wheel itself moves to x = −yPos tan ψ, and the lowest point of a yawed wheel of revolution
/// leads by r tan γ tan ψ (σ = +1 right, −1 left; `src/geometry/search/lowest_point.rs`): on the tread
/// (γ ≈ 0.03, lead 0.1 mm) the sum holds within 1e−3 of |xPos| (the rail's angle at the reference
/// point stands for the wheel's slope there); in flange contact (γ ≈ 1.2, a lead of 12 mm at
/// ψ = 0.01) within 5 % of the lead, the angle varying steeply across the flange patch whose
/// reference point is a centroid.
#[test]
fn positions_carry_the_yaw_lead() {
    let centred = instance("lead0", &[], false, &[]);
    for (side, sigma) in SIDES {
        let g = |q: &str| centred.real(&format!("{side}.p1.{q}"));
        assert_eq!(g("xPos"), 0.0, "{side}");
        assert!((g("zPos") - g("rollingRadius")).abs() < 1e-12, "{side}");
        assert!(
            (sigma * g("yPos") - 0.75).abs() < 5e-3,
            "{side}: {}",
            g("yPos")
        );
    }
    for (y, yaw) in [(0.0, 0.01), (8e-3, 0.01), (8e-3, 3e-3), (8e-3, -5e-3)] {
        let f = instance("lead", &[], false, &[("y", y), ("yaw", yaw)]);
        step(&f);
        for (side, sigma) in SIDES {
            for p in PATCHES {
                let g = |q: &str| f.real(&format!("{side}.{p}.{q}"));
                if g("Fn") == 0.0 {
                    continue;
                }
                let gamma = g("contactAngle");
                let lead = sigma * g("rollingRadius") * gamma.tan() * yaw.tan();
                let expected = (lead - g("yPos") * yaw.sin()) / yaw.cos();
                let allowed = if gamma > 0.5 {
                    0.05 * lead.abs()
                } else {
                    1e-3 * expected.abs()
                };
                assert!(
                    (g("xPos") - expected).abs() <= allowed,
                    "y {y} yaw {yaw} {side}.{p}: xPos {} vs {expected} (lead {lead})",
                    g("xPos")
                );
            }
        }
    }
}

/// Y/Q: the flanging wheel is pushed back towards the track centre, so its Y/Q is positive, and
/// bounded by Nadal's limit (tan γ + μ)/(1 − μ tan γ) at its contact angle; the definition
/// Y = −σ Fy, Q = −Fz holds exactly; on the centred wheelset |Y/Q| stays small (the gravitational
/// stiffness of a 0.03 rad tread angle and the creep forces of 0.05 % creepage).
#[test]
fn derailment_quotient_is_positive_on_the_flanging_wheel() {
    let mu = 0.3;
    for (y, flanging, sigma) in [(8e-3, "right", 1.0), (-8e-3, "left", -1.0)] {
        let f = instance("yq", &[], false, &[("y", y), ("yaw", 2e-3)]);
        step(&f);
        let g = |q: &str| f.real(&format!("{flanging}.{q}"));
        let yq = g("YQ");
        assert_eq!(yq, (-sigma * g("Fy")) / (-g("Fz")));
        let gamma = PATCHES
            .iter()
            .map(|p| g(&format!("{p}.contactAngle")))
            .fold(0.0, f64::max);
        let nadal = (gamma.tan() + mu) / (1.0 - mu * gamma.tan());
        assert!(
            gamma > 1.0,
            "{flanging}: flange contact expected, γ = {gamma}"
        );
        assert!(
            yq > 0.5 && yq < nadal,
            "{flanging}: Y/Q = {yq}, Nadal {nadal}"
        );
    }
    let centred = instance("yq0", &[], false, &[]);
    for (side, _) in SIDES {
        let yq = centred.real(&format!("{side}.YQ"));
        assert!(yq.abs() < 0.05, "{side}: {yq}");
    }
}

/// The wheel forces, moments and Y/Q of both wheels.
const WRENCH: [&str; 14] = [
    "left.Fx", "left.Fy", "left.Fz", "left.Mx", "left.My", "left.Mz", "left.YQ", "right.Fx",
    "right.Fy", "right.Fz", "right.Mx", "right.My", "right.Mz", "right.YQ",
];

/// A tread pose in the running range of the creep curves: 2 mm to the right, 0.5 mrad of yaw,
/// 20 m/s, a lateral velocity of 1 cm/s and 0.03 % of longitudinal creepage from ω.
fn tread_pose() -> Vec<(&'static str, f64)> {
    vec![
        ("y", 2e-3),
        ("yaw", 5e-4),
        ("vx", 20.0),
        ("vy", 0.01),
        ("omega", 20.0 / 0.46 * (1.0 + 3e-4)),
    ]
}

/// An instance of `model` at the tread pose after two steps (the warm start has its history),
/// and its serialized state.
fn at_tread(name: &str, model: i32) -> (Instance, Vec<u8>) {
    let f = instance(name, &[("normalModel", model)], false, &tread_pose());
    for k in 0..2 {
        assert_eq!(f.step(k as f64 * 1e-3, 1e-3), OK, "{:?}", f.errors());
    }
    let state = f.serialized_state().unwrap_or_else(|e| panic!("{e}"));
    (f, state)
}

/// The host's own central difference of `output` over `input` ± `h`: from the state `base`
/// (time 2 ms), set the input, step, read, for each side.
fn host_difference(f: &Instance, base: &[u8], output: &str, input: &str, h: f64) -> f64 {
    let x0 = f.real(input);
    let at = |x: f64| {
        assert_eq!(f.restore_serialized(base), OK);
        assert_eq!(f.set_real(input, x), OK);
        assert_eq!(f.step(2e-3, 1e-3), OK, "{:?}", f.errors());
        f.real(output)
    };
    (at(x0 + h) - at(x0 - h)) / (2.0 * h)
}

/// `fmi2GetDirectionalDerivative` with a unit seed on one input agrees with the central
/// differences a host computes by stepping the FMU from the same state with its own, three times
/// larger, steps — within 2 % (the curvature of the outputs over the host's steps and the load
/// balance's creep tolerance, 1e−7 of the load, over a force change of ~10 N per step stay far
/// below it). Hertz and ANALYN (strips).
#[test]
fn derivatives_agree_with_a_hosts_central_differences() {
    let speed: f64 = 20.0;
    let cases = [
        ("right.Fy", "y", 3e-5),
        ("right.Fy", "vy", 3e-6 * speed),
        ("right.Fx", "omega", 3e-6 * speed / 0.46),
        ("left.Fx", "yaw", 3e-5),
        ("right.Mz", "yawRate", 3e-6 * speed),
        ("left.YQ", "y", 3e-5),
        ("right.My", "omega", 3e-6 * speed / 0.46),
        ("right.Fz", "Qright", 3e-5 * 78_500.0),
        ("right.Fy", "right.rail.dy", 3e-5),
        ("left.Fx", "trackCurvature", 3e-6),
        ("right.Fy", "right.rail.vy", 3e-6 * speed),
    ];
    for model in [1, 6] {
        let (f, base) = at_tread(&format!("ddHost{model}"), model);
        for (output, input, h) in cases {
            assert_eq!(f.restore_serialized(&base), OK);
            let (status, d) = f.directional_derivative(&[output], &[(input, 1.0)]);
            assert_eq!(status, OK, "{:?}", f.errors());
            let host = host_difference(&f, &base, output, input, h);
            assert!(
                (d[0] - host).abs() <= 0.02 * host.abs() && host != 0.0,
                "model {model}: d {output} / d {input} = {} against the host's {host}",
                d[0]
            );
        }
    }
}

/// A derivative call changes nothing: the outputs read after it, and every output of the next
/// steps, are bit for bit those of an instance that was not asked — for every normal model, with
/// the call right after a step and after new inputs were set for the next one.
#[test]
fn a_derivative_call_leaves_the_state_alone() {
    let bits = |f: &Instance| -> Vec<u64> { f.outputs().iter().map(|x| x.to_bits()).collect() };
    for model in 1..=6 {
        let asked = instance(
            &format!("ddAsked{model}"),
            &[("normalModel", model)],
            false,
            &[],
        );
        let alone = instance(
            &format!("ddAlone{model}"),
            &[("normalModel", model)],
            false,
            &[],
        );
        for k in 0..5 {
            let y = 1e-3 * k as f64;
            for f in [&asked, &alone] {
                assert_eq!(f.set_real("y", y), OK);
                assert_eq!(f.set_real("vy", 0.02 * k as f64), OK);
            }
            if k % 2 == 1 {
                // Between new inputs and the step that uses them.
                let (s, _) = asked.directional_derivative(&WRENCH, &[("y", 1.0), ("vy", 0.3)]);
                assert_eq!(s, OK, "{:?}", asked.errors());
            }
            for f in [&asked, &alone] {
                assert_eq!(f.step(k as f64 * 1e-3, 1e-3), OK);
            }
            if k % 2 == 0 {
                // Right after a step: the outputs read afterwards are the step's.
                let before = bits(&asked);
                let (s, _) = asked.directional_derivative(&WRENCH, &[("omega", 1.0)]);
                assert_eq!(s, OK, "{:?}", asked.errors());
                assert_eq!(bits(&asked), before, "model {model} step {k}");
            }
            assert_eq!(bits(&asked), bits(&alone), "model {model} step {k}");
        }
    }
}

/// Every wheel force, moment and Y/Q has a finite derivative along every continuous input; the
/// inputs the modes leave unused (z with prescribed loads, the prescribed creepages with
/// kinematic ones) give exactly 0, the others move some output; a seed scaled by 2 gives twice
/// the derivative (the step is scaled with the seed, so the trial inputs are the same); a seed on
/// two inputs gives the sum of theirs within 2 % (different steps, the outputs linear over them).
#[test]
fn every_wrench_output_has_a_derivative_along_every_input() {
    let (f, base) = at_tread("ddAll", 1);
    let inputs: Vec<&str> = INFO
        .variables
        .iter()
        .filter(|v| v.causality == Causality::Input && v.variability == Variability::Continuous)
        .map(|v| v.name)
        .collect();
    // The pose, loads, velocities and prescribed creepages (13), the track's curvature and the
    // six displacements and velocities of each rail.
    assert_eq!(inputs.len(), 26, "{inputs:?}");
    let mut single = std::collections::HashMap::new();
    for input in &inputs {
        assert_eq!(f.restore_serialized(&base), OK);
        let (s, d) = f.directional_derivative(&WRENCH, &[(input, 1.0)]);
        assert_eq!(s, OK, "{input}: {:?}", f.errors());
        assert!(d.iter().all(|x| x.is_finite()), "{input}: {d:?}");
        // With prescribed loads a rail's vertical displacement leaves the contact as it is.
        let unused = matches!(
            *input,
            "z" | "xi" | "eta" | "phi" | "left.rail.dz" | "right.rail.dz"
        );
        assert_eq!(d.iter().all(|x| *x == 0.0), unused, "{input}: {d:?}");
        let (_, twice) = f.directional_derivative(&WRENCH, &[(input, 2.0)]);
        for (a, b) in d.iter().zip(&twice) {
            assert!((2.0 * a - b).abs() <= 1e-12 * b.abs(), "{input}: {a} {b}");
        }
        single.insert(*input, d);
    }
    // The balance makes Fz = −Q: ∂Fz/∂Q = −1 on the loaded wheel (to the creep update's
    // tolerance, 1e−7 of the load over a step of 1e−4 of it) and exactly 0 on the other.
    let index = |name: &str| WRENCH.iter().position(|n| *n == name).unwrap();
    let d_load = &single["Qright"];
    assert!((d_load[index("right.Fz")] + 1.0).abs() < 2e-3, "{d_load:?}");
    assert_eq!(d_load[index("left.Fz")], 0.0);
    let (_, both) = f.directional_derivative(&WRENCH, &[("y", 1.0), ("vy", 1.0)]);
    let fy = index("right.Fy");
    let sum = single["y"][fy] + single["vy"][fy];
    assert!(
        (both[fy] - sum).abs() <= 0.02 * sum.abs(),
        "{} vs {sum}",
        both[fy]
    );
}

/// Calls that cannot be answered are errors naming the reason: an input as unknown, an output or
/// a parameter as known, a NaN seed, a call before initialization.
#[test]
fn misused_derivative_calls_are_errors() {
    let (f, _) = at_tread("ddMisuse", 1);
    for (unknown, known, seed, reason) in [
        ("y", "y", 1.0, "unknown y is not an output"),
        (
            "right.Fy",
            "right.Fx",
            1.0,
            "known right.Fx is not a continuous input",
        ),
        ("right.Fy", "mu", 1.0, "known mu is not a continuous input"),
        ("right.Fy", "y", f64::NAN, "seed of y = NaN is not finite"),
    ] {
        let (s, _) = f.directional_derivative(&[unknown], &[(known, seed)]);
        assert_eq!(s, ERROR);
        f.assert_error_logged(&["fmi2GetDirectionalDerivative", reason]);
    }
    let fresh = linked::instantiate(&INFO, "ddFresh");
    let (s, _) = fresh.directional_derivative(&["right.Fy"], &[("y", 1.0)]);
    assert_eq!(s, ERROR);
    fresh.assert_error_logged(&["fmi2GetDirectionalDerivative must not be called"]);
}

/// HertzContact's derivatives in the creepages at zero creepage are Kalker's linear theory
/// (docs/conventions.md): ∂Fx/∂ξ = −G a b C11, ∂Fy/∂η = −G a b C22, ∂Fy/∂φ = −G (ab)^1.5 C23,
/// with the FMU's own a, b and C's. FASTSIM's second-order march (fastsimScheme 1) on the
/// default grid reproduces that limit within its discretisation error, 1 % allowed.
#[test]
fn point_contact_derivatives_are_kalkers_linear_theory() {
    let f = linked::instantiate(&hertz_contact::INFO, "ddHertz");
    assert_eq!(f.set_integer("fastsimScheme", 1), OK);
    f.init();
    for n in ["xi", "eta", "phi"] {
        assert_eq!(f.set_real(n, 0.0), OK);
    }
    assert_eq!(f.step(0.0, 1e-3), OK);
    let g = f.real("E") / (2.0 * (1.0 + f.real("nu")));
    let ab = f.real("a") * f.real("b");
    for (output, input, linear) in [
        ("Fx", "xi", -g * ab * f.real("C11")),
        ("Fy", "eta", -g * ab * f.real("C22")),
        ("Fy", "phi", -g * ab.powf(1.5) * f.real("C23")),
    ] {
        let (s, d) = f.directional_derivative(&[output], &[(input, 1.0)]);
        assert_eq!(s, OK, "{:?}", f.errors());
        assert!(
            (d[0] / linear - 1.0).abs() < 0.01,
            "d {output} / d {input} = {} against {linear}",
            d[0]
        );
    }
}
