//! The report's wheel-level validation: what a vehicle model integrates — the wheel's forces —
//! against the exact solution of the whole wheel ([`railcontact_halfspace::wheel_rail`]), and what
//! follows for the wheelset: its gravitational stiffness, its contact-angle difference parameter
//! and the critical speed of the closed-loop example's suspended wheelset, for every normal model.
//!
//! * **Lateral force at zero creepage** over the lateral shifts [`SHIFTS_MM`] (the case's profiles
//!   and loads, creepages prescribed zero): the right wheel's force towards its field side against
//!   the exact planar solution (Q tan γ of CONTACT's plane) with `planarPatch` true, and against the
//!   exact pressure acting on the curved surface with `planarPatch` false; contact angle and
//!   rolling radius at the load against the exact solution's (planar patches).
//! * **Gravitational stiffness** k_g = −ΔF/Δy of the wheelset's lateral force (secant over ±1 mm,
//!   Fy_right(y) − Fy_right(−y) by symmetry) and the contact-angle difference parameter
//!   ε = e0 (tan γ_R − tan γ_L)/(2y) at y = 1 mm (e0 half the distance between the contact
//!   points), so that k_g = 2Qε/e0.
//! * **Creep forces** of the wheel (track axes: its force less its patches' normal forces) with
//!   kinematic creepages at 2 m/s over −1…+4 mm — pure rolling (ω = V/r0) and ξ ≈ η ≈ 1e−3 —
//!   against the exact rolling solution with each element's rigid slip on the actual surfaces.
//! * **Critical speed** of the linear (Wickens) model of `examples/wheelset_hunting.py`'s wheelset
//!   (built-in S1002/UIC60 1:40, 60 kN per wheel) with the element's own coefficients: f11, f22
//!   from prescribed creepages of 1e−6 at the centred pose, k_g and the loaded conicity
//!   λ = (Δr(+1 mm) − Δr(−1 mm))/(4 mm) from its zero-creepage forces and Fn-weighted rolling
//!   radii (secants over ±1 mm).

use super::plot::model_label;
use super::study::{tangential_code, Options, Runner, Study};
use crate::Failure;
use nalgebra::Matrix4;
use railcontact::fmi::variables::Values;
use railcontact::models::wheel_rail_contact::{generated::var, INFO};
use railcontact::normal::NormalModel;
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::{SideResult, WheelsetResult};
use railcontact_halfspace::wheel_rail::{model_creep_force, ExactWheel, WheelsetMotion};
use std::fmt::Write as _;

/// Lateral shifts of the lateral-force tables [mm].
const SHIFTS_MM: [f64; 8] = [-1.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
/// Lateral shifts of the creep-force comparison [mm].
const CREEP_SHIFTS_MM: [f64; 6] = [-1.0, 0.0, 1.0, 2.0, 3.0, 4.0];
/// Element size of the exact normal solutions (as CONTACT's reference) and of the rolling
/// solutions (their dense Newton systems) [m].
const NORMAL_ELEMENT: f64 = 0.2e-3;
const ROLLING_ELEMENT: f64 = 0.5e-3;
/// Yaw of the yawed lateral-force comparison [rad].
const YAW: f64 = 5e-3;
/// Speed of the creep-force comparison [m/s] and the nominal radius of its pure rolling [m].
const CREEP_SPEED: f64 = 2.0;

/// The closed-loop example's wheelset (`examples/wheelset_hunting.py`): mass [kg], yaw inertia
/// [kg m²], wheel load [N], lateral and yaw stiffness of the primary springs [N/m, N m/rad].
const MASS: f64 = 1500.0;
const YAW_INERTIA: f64 = 700.0;
const EXAMPLE_LOAD: f64 = 60_000.0;
const LATERAL_STIFFNESS: f64 = 2.0e6;
const YAW_STIFFNESS: f64 = 2.0e6;

/// The right wheel at one pose: what the tables compare.
#[derive(Debug, Clone, Copy, Default)]
struct Wheel {
    /// Lateral force towards the field side (−Fy of the right wheel) [N].
    lateral: f64,
    /// Contact angle and rolling radius of the heaviest patch [rad, m].
    angle: f64,
    rolling_radius: f64,
    /// Fn-weighted rolling radius of the wheel [m].
    mean_radius: f64,
    /// Half the distance between the contact points (|yPos|) [m].
    lever: f64,
}

/// The patch of `side` carrying the largest normal force (a default patch where none does).
pub(super) fn heaviest(side: &SideResult) -> railcontact::wheelset::PatchResult {
    side.all_patches()
        .iter()
        .max_by(|a, b| a.fn_.total_cmp(&b.fn_))
        .copied()
        .unwrap_or_default()
}

fn wheel(side: &SideResult) -> Wheel {
    let patches = side.all_patches();
    let normal: f64 = patches.iter().map(|p| p.fn_).sum();
    let heaviest = heaviest(side);
    let mean = |f: &dyn Fn(&railcontact::wheelset::PatchResult) -> f64| {
        patches.iter().map(|p| p.fn_ * f(p)).sum::<f64>() / normal
    };
    Wheel {
        lateral: -side.force[1],
        angle: heaviest.contact_angle,
        rolling_radius: heaviest.rolling_radius,
        mean_radius: mean(&|p| p.rolling_radius),
        lever: mean(&|p| p.position[1].abs()),
    }
}

/// Sets the pose, zero prescribed creepages and solves.
fn at_rest(runner: &mut Runner, y: f64, yaw: f64) -> Result<WheelsetResult, Failure> {
    let v = runner.values_mut();
    v.set_real(var::y, y);
    v.set_real(var::yaw, yaw);
    v.set_integer(var::creepageMode, 2);
    for c in [var::xi, var::eta, var::phi] {
        v.set_real(c, 0.0);
    }
    runner.solve()
}

fn options(model: NormalModel, planar: bool) -> Options {
    Options {
        planar: Some(planar),
        ..Options::normal(model)
    }
}

/// The exact solution at one shift.
struct ExactRow {
    y_mm: f64,
    planar: f64,
    curved: f64,
    angle: f64,
    rolling_radius: f64,
    regions: usize,
}

/// The case's material and load: (E, ν), Qright.
fn material(study: &Study) -> ((f64, f64), f64) {
    let v = study.values();
    ((v.real(var::E), v.real(var::nu)), v.real(var::Qright))
}

/// The exact solution of the right wheel at the pose `runner` last solved, from the lowering of
/// its result `out`.
fn exact(study: &Study, runner: &Runner, out: &WheelsetResult) -> Result<ExactWheel, Failure> {
    let (elastic, load) = material(study);
    ExactWheel::solve(
        runner.wheelset().geometry(true),
        out.right.z,
        load,
        NORMAL_ELEMENT,
        elastic,
    )
    .map_err(|e| Failure::Error(format!("exact solution of the wheel: {e:?}")))
}

/// The whole wheel-level section of the document.
pub fn section(study: &Study) -> Result<String, Failure> {
    let mut md = String::from("\n## Wheel forces\n\n");
    let _ = writeln!(
        md,
        "What a vehicle model integrates: the wheel's forces, against the exact solution of the \
         whole wheel (`halfspace/src/wheel_rail.rs`, docs/theory.md §9.6) — Kalker's planar \
         theory with CONTACT's contact plane (the weighted centre and mean inclination of the rigid \
         interpenetration), its exact pressure on 0.2 mm elements, that pressure acting on the \
         curved surface (each row along its own rail normal), and the exact rolling solution \
         with each element's rigid slip on the actual surfaces. The case's profiles and loads, \
         right wheel, creepages prescribed zero unless stated.\n"
    );
    let mut oracle = study.runner(options(NormalModel::CoupledStrips, true))?;
    let mut exact_rows = Vec::new();
    for y_mm in SHIFTS_MM {
        let out = at_rest(&mut oracle, y_mm * 1e-3, 0.0)?;
        let e = exact(study, &oracle, &out)?;
        exact_rows.push(ExactRow {
            y_mm,
            planar: e.planar_lateral(),
            curved: e.curved_lateral(),
            angle: e.reference.angle,
            rolling_radius: e.reference.rolling_radius,
            regions: e.regions(),
        });
    }
    md.push_str(&lateral_tables(study, &exact_rows)?);
    md.push_str(&stiffness_table(study, &exact_rows)?);
    md.push_str(&creep_table(study)?);
    md.push_str(&critical_speeds()?);
    Ok(md)
}

/// The lateral-force, angle and radius tables, planar and non-planar.
fn lateral_tables(study: &Study, exact: &[ExactRow]) -> Result<String, Failure> {
    let mut md = String::new();
    let header = |md: &mut String, first: &str| {
        let _ = write!(md, "| {first} |");
        for r in exact {
            let _ = write!(
                md,
                " {:+} mm{} |",
                r.y_mm,
                if r.regions > 1 { "²" } else { "" }
            );
        }
        let _ = writeln!(md, "\n|---|{}", "---|".repeat(exact.len()));
    };
    let _ = writeln!(
        md,
        "### Lateral force at zero creepage\n\nThe right wheel's lateral force towards its field \
         side; errors in % of the exact value. ² two separate regions in the exact solution (the \
         tread and the flange root, 5 mm apart; CONTACT combines them under one plane).\n"
    );
    header(&mut md, "exact planar (CONTACT's plane) N");
    let _ = write!(md, "| |");
    for r in exact {
        let _ = write!(md, " {:.0} |", r.planar);
    }
    let _ = writeln!(md);
    let mut yawed = Vec::new();
    for planar in [true, false] {
        if !planar {
            let _ = writeln!(
                md,
                "\n`planarPatch` = false: against the exact pressure acting on the curved surface \
                 (each row along its own rail normal; the lateral force a curved patch carrying \
                 the exact pressure has).\n"
            );
            header(&mut md, "exact on the curved surface N");
            let _ = write!(md, "| |");
            for r in exact {
                let _ = write!(md, " {:.0} |", r.curved);
            }
            let _ = writeln!(md);
        }
        for model in NormalModel::ALL {
            if model == NormalModel::Hertz && !planar {
                continue;
            }
            let mut runner = study.runner(options(model, planar))?;
            let _ = write!(
                md,
                "| {}{} |",
                model_label(model),
                if planar { ", planar" } else { ", non-planar" }
            );
            for r in exact {
                let out = at_rest(&mut runner, r.y_mm * 1e-3, 0.0)?;
                let target = if planar { r.planar } else { r.curved };
                let _ = write!(
                    md,
                    " {:+.1} % |",
                    100.0 * (wheel(&out.right).lateral / target - 1.0)
                );
            }
            let _ = writeln!(md);
            if planar && matches!(model, NormalModel::Analyn | NormalModel::CoupledStrips) {
                yawed.push((model, yawed_error(study, &mut runner)?));
            }
        }
    }
    let _ = writeln!(
        md,
        "\nYawed ±{} mrad, planar patches, worst over the shifts with one exact region: {}.\n",
        YAW * 1e3,
        yawed
            .iter()
            .map(|(m, e)| format!("{} {:.2} %", model_label(*m), 100.0 * e))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(
        md,
        "Contact angle and rolling radius of the heaviest patch (planar patches) against the \
         exact solution's plane and its rolling radius at the weighted centre, worst over the \
         shifts with one exact region:\n\n| model | angle mrad | rolling radius µm |\n|---|---|---|"
    );
    for model in NormalModel::ALL {
        let mut runner = study.runner(options(model, true))?;
        let (mut angle, mut radius): (f64, f64) = (0.0, 0.0);
        for r in exact.iter().filter(|r| r.regions == 1) {
            let out = at_rest(&mut runner, r.y_mm * 1e-3, 0.0)?;
            let w = wheel(&out.right);
            angle = angle.max((w.angle - r.angle).abs());
            radius = radius.max((w.rolling_radius - r.rolling_radius).abs());
        }
        let _ = writeln!(
            md,
            "| {} | {:.2} | {:.1} |",
            model_label(model),
            angle * 1e3,
            radius * 1e6
        );
    }
    let _ = writeln!(
        md,
        "\nThe multi-Hertzian patches (model 1) keep the classic single point: the rail's tangent \
         at their reference point, short of the mean inclination of a wide patch on a rail whose \
         curvature changes under it (+1 and +2 mm: the rail's radius drops from 300 to 80 mm \
         under the patch). ANALYN's non-planar lateral force follows its own pressure, whose \
         load centre lies up to 1.1 mm gauge-side of the exact one at +1 mm (its local reduction \
         of the approach cuts the flat field side of the patch). ANALYN and the coupled strips \
         take their reference point where the exact solution does (the interpenetration's \
         weighted centre), Linder, Kik–Piotrowski and STRIPES at the force centroid of their \
         own pressure (docs/conventions.md, \"Reference point\").\n"
    );
    Ok(md)
}

/// Worst |model/exact − 1| of the lateral force at yaw ±[`YAW`] over the one-region shifts.
fn yawed_error(study: &Study, runner: &mut Runner) -> Result<f64, Failure> {
    let mut worst: f64 = 0.0;
    for yaw in [YAW, -YAW] {
        for y_mm in SHIFTS_MM {
            let out = at_rest(runner, y_mm * 1e-3, yaw)?;
            let e = exact(study, runner, &out)?;
            if e.regions() == 1 {
                worst = worst.max((wheel(&out.right).lateral / e.planar_lateral() - 1.0).abs());
            }
        }
    }
    Ok(worst)
}

/// Gravitational stiffness and contact-angle difference parameter of every model against the
/// exact ones (from the rows at ±1 mm).
fn stiffness_table(study: &Study, exact: &[ExactRow]) -> Result<String, Failure> {
    let (_, load) = material(study);
    let at = |y: f64| exact.iter().find(|r| r.y_mm == y).expect("±1 mm rows");
    let (plus, minus) = (at(1.0), at(-1.0));
    let k_exact = 2.0 * (plus.planar - minus.planar) / 2e-3;
    let mut md = String::new();
    let _ = writeln!(
        md,
        "### Gravitational stiffness\n\nThe wheelset's lateral force at zero creepage, secant \
         over ±1 mm (k_g, restoring), and the contact-angle difference parameter \
         ε = e0 (tan γ_R − tan γ_L)/(2y) at y = 1 mm (k_g = 2Qε/e0, e0 half the distance between \
         the contact points). Exact: k_g = {:.3} MN/m (planar; on the curved surface {:.3} MN/m).\n",
        k_exact * 1e-6,
        2.0 * (plus.curved - minus.curved) / 2e-3 * 1e-6
    );
    let _ = writeln!(
        md,
        "| model | planar | k_g MN/m | error | ε |\n|---|---|---|---|---|"
    );
    for model in NormalModel::ALL {
        for planar in [true, false] {
            if model == NormalModel::Hertz && !planar {
                continue;
            }
            let mut runner = study.runner(options(model, planar))?;
            let p = wheel(&at_rest(&mut runner, 1e-3, 0.0)?.right);
            let m = wheel(&at_rest(&mut runner, -1e-3, 0.0)?.right);
            let k = 2.0 * (p.lateral - m.lateral) / 2e-3;
            let lever = 0.5 * (p.lever + m.lever);
            let epsilon = lever * (p.lateral - m.lateral) / load / 2e-3;
            let _ = writeln!(
                md,
                "| {} | {} | {:.3} | {:+.1} % | {:.2} |",
                model_label(model),
                if planar { "yes" } else { "no" },
                k * 1e-6,
                100.0 * (k / k_exact - 1.0),
                epsilon
            );
        }
    }
    Ok(md)
}

/// The creep forces of every tangential option against the exact rolling solution.
fn creep_table(study: &Study) -> Result<String, Failure> {
    let (elastic, _) = material(study);
    let v = study.values();
    let (mu, r0) = (v.real(var::mu), v.real(var::wheelRadius));
    let shear = elastic.0 / (2.0 * (1.0 + elastic.1));
    let cases: Vec<(f64, f64)> = CREEP_SHIFTS_MM
        .iter()
        .flat_map(|&y| [(y, 0.0), (y, 1e-3)])
        .collect();
    let motion = |c: f64| WheelsetMotion {
        vx: CREEP_SPEED,
        vy: c * CREEP_SPEED,
        yaw_rate: 0.0,
        omega: (1.0 - c) * CREEP_SPEED / r0,
        yaw: 0.0,
    };
    let kinematic = |runner: &mut Runner, y: f64, c: f64| {
        let m = motion(c);
        let v = runner.values_mut();
        v.set_real(var::y, y);
        v.set_real(var::yaw, 0.0);
        v.set_integer(var::creepageMode, 1);
        v.set_real(var::vx, m.vx);
        v.set_real(var::vy, m.vy);
        v.set_real(var::yawRate, 0.0);
        v.set_real(var::omega, m.omega);
        runner.solve()
    };
    let mut oracle = study.runner(options(NormalModel::CoupledStrips, true))?;
    let mut exact_forces = Vec::new();
    for &(y_mm, c) in &cases {
        let out = kinematic(&mut oracle, y_mm * 1e-3, c)?;
        let e = exact(study, &oracle, &out)?;
        let f = e
            .rolling(&motion(c), 1.0, ROLLING_ELEMENT, (shear, elastic.1, mu))
            .map_err(|e| Failure::Error(format!("exact rolling solution: {e:?}")))?;
        exact_forces.push(f);
    }
    let mut md = String::new();
    let _ = writeln!(
        md,
        "\n### Creep forces on the actual surfaces\n\nThe right wheel's creep force (its force \
         less its patches' normal forces, track axes) with kinematic creepages at {} m/s over \
         −1…+4 mm — pure rolling (ω = V/r0) and ξ ≈ η ≈ 1e−3 (ω = (1 − 1e−3)V/r0, \
         vy = 1e−3 V) — against the exact rolling solution with each element's rigid slip on \
         the actual surfaces ({} mm elements); worst and mean of |ΔFx|, |ΔFy| in % of μN.\n",
        CREEP_SPEED,
        ROLLING_ELEMENT * 1e3
    );
    let _ = writeln!(
        md,
        "| model | tangential option | non-planar worst | mean | planar worst | mean |\n\
         |---|---|---|---|---|---|"
    );
    let mut configs = vec![(NormalModel::Hertz, TangentialModel::ModelDefault)];
    for model in [NormalModel::Analyn, NormalModel::CoupledStrips] {
        configs.extend(TangentialModel::ALL.iter().map(|&t| (model, t)));
    }
    for (model, t) in configs {
        let mut cells = Vec::new();
        for planar in [false, true] {
            if model == NormalModel::Hertz && !planar {
                cells.push("– | –".to_string());
                continue;
            }
            let mut runner = study.runner(Options {
                tangential: Some(t),
                ..options(model, planar)
            })?;
            let (mut worst, mut sum): (f64, f64) = (0.0, 0.0);
            for (&(y_mm, c), e) in cases.iter().zip(&exact_forces) {
                let out = kinematic(&mut runner, y_mm * 1e-3, c)?;
                let (fx, fy) = model_creep_force(&out.right, 1.0);
                let dx = ((fx - e.fx) / e.mu_n).abs();
                let dy = ((fy - e.fy) / e.mu_n).abs();
                worst = worst.max(dx.max(dy));
                sum += dx + dy;
            }
            cells.push(format!(
                "{:.1} | {:.1}",
                100.0 * worst,
                100.0 * sum / (2 * cases.len()) as f64
            ));
        }
        let _ = writeln!(
            md,
            "| {} | {} {} | {} | {} |",
            model_label(model),
            tangential_code(t),
            t.name(),
            cells[0],
            cells[1]
        );
    }
    let _ = writeln!(
        md,
        "\nWhich configuration to choose for a curved (wide) tread patch: the coupled strips \
         (normalModel 7) with non-planar patches (`planarPatch` = false) and FASTSIM \
         (tangentialModel 1) or FaStrip with the coupled coefficients (5). Planar patches carry \
         the planar theory's creep forces, which miss the curvature's (up to 8 % of μN here). \
         The exact solution on the actual surfaces has a longitudinal force in pure rolling at \
         the load centre's radius (+6 % of μN centred) that the planar one does not.\n"
    );
    Ok(md)
}

/// The example wheelset's values: the FMU's defaults (built-in S1002 on UIC60 at 1:40) at
/// [`EXAMPLE_LOAD`] per wheel.
fn example_values() -> Values {
    let mut v = Values::from_start(INFO.variables, INFO.counts);
    v.set_real(var::Qleft, EXAMPLE_LOAD);
    v.set_real(var::Qright, EXAMPLE_LOAD);
    v.set_integer(var::verticalMode, 1);
    v
}

/// The linear model's coefficients of one normal model.
struct Linear {
    f11: f64,
    f22: f64,
    gravity: f64,
    conicity: f64,
    r0: f64,
    e0: f64,
}

/// State matrix of (y, ψ, ẏ, ψ̇) of the linear wheelset at speed `v` (Wickens 2003, ch. 2):
/// m ÿ = −2 f22 (ẏ/V − ψ) − (ky + kg) y,  Iz ψ̈ = −2 f11 e0² ψ̇/V − 2 f11 e0 λ y/r0 − kψ ψ.
fn wickens(l: &Linear, v: f64) -> Matrix4<f64> {
    let mut a = Matrix4::zeros();
    a[(0, 2)] = 1.0;
    a[(1, 3)] = 1.0;
    a[(2, 0)] = -(LATERAL_STIFFNESS + l.gravity) / MASS;
    a[(2, 1)] = 2.0 * l.f22 / MASS;
    a[(2, 2)] = -2.0 * l.f22 / (MASS * v);
    a[(3, 0)] = -2.0 * l.f11 * l.e0 * l.conicity / (l.r0 * YAW_INERTIA);
    a[(3, 1)] = -YAW_STIFFNESS / YAW_INERTIA;
    a[(3, 3)] = -2.0 * l.f11 * l.e0 * l.e0 / (YAW_INERTIA * v);
    a
}

/// The speed where the largest real part of the eigenvalues crosses zero, by bisection on
/// [1, 500] m/s; `None` where the bracket holds none.
fn critical_speed(l: &Linear) -> Option<f64> {
    let unstable = |v: f64| {
        wickens(l, v)
            .complex_eigenvalues()
            .iter()
            .any(|e| e.re > 0.0)
    };
    let (mut lo, mut hi) = (1.0, 500.0);
    if unstable(lo) || !unstable(hi) {
        return None;
    }
    while hi - lo > 1e-3 {
        let mid = 0.5 * (lo + hi);
        if unstable(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

/// The element's own linear coefficients of `model` (planar or not) for the example wheelset.
fn linear(study: &Study, model: NormalModel, planar: bool) -> Result<Linear, Failure> {
    let mut runner = study.runner(options(model, planar))?;
    let prescribed = |runner: &mut Runner, xi: f64, eta: f64| {
        let v = runner.values_mut();
        v.set_real(var::y, 0.0);
        v.set_integer(var::creepageMode, 2);
        v.set_real(var::xi, xi);
        v.set_real(var::eta, eta);
        v.set_real(var::phi, 0.0);
        v.set_real(var::vx, 30.0);
        runner.solve().map(|out| out.right.force)
    };
    let small = 1e-6;
    let base = prescribed(&mut runner, 0.0, 0.0)?;
    let f11 = -(prescribed(&mut runner, small, 0.0)?[0] - base[0]) / small;
    let f22 = -(prescribed(&mut runner, 0.0, small)?[1] - base[1]) / small;
    let mut lateral = [0.0; 2];
    let mut delta_r = [0.0; 2];
    let mut lever = 0.0;
    for (k, y) in [1e-3, -1e-3].into_iter().enumerate() {
        let out = at_rest(&mut runner, y, 0.0)?;
        let (l, r) = (wheel(&out.left), wheel(&out.right));
        lateral[k] = out.left.force[1] + out.right.force[1];
        delta_r[k] = r.mean_radius - l.mean_radius;
        lever += 0.25 * (l.lever + r.lever);
    }
    Ok(Linear {
        f11,
        f22,
        gravity: -(lateral[0] - lateral[1]) / 2e-3,
        conicity: (delta_r[0] - delta_r[1]) / 4e-3,
        r0: study.values().real(var::wheelRadius),
        e0: lever,
    })
}

/// The critical speeds of every normal model for the closed-loop example's wheelset.
fn critical_speeds() -> Result<String, Failure> {
    let study = Study::new(example_values())?;
    let mut md = String::new();
    let _ = writeln!(
        md,
        "### Critical speed of a suspended wheelset\n\nThe linear (Wickens) model of \
         `examples/wheelset_hunting.py`'s wheelset (mass {MASS} kg, yaw inertia {YAW_INERTIA} \
         kg·m², {} kN per wheel, primary springs {} MN/m lateral and {} MN·m/rad yaw; the FMU's \
         defaults: built-in S1002 on UIC60 at 1:40) with the element's own coefficients: f11, \
         f22 per wheel from prescribed creepages of 1e−6, the gravitational stiffness k_g and the \
         loaded conicity λ (Fn-weighted rolling radii) as secants over ±1 mm at zero creepage.\n",
        EXAMPLE_LOAD * 1e-3,
        LATERAL_STIFFNESS * 1e-6,
        YAW_STIFFNESS * 1e-6
    );
    let _ = writeln!(
        md,
        "| model | planar | f11 MN | f22 MN | k_g MN/m | λ | critical speed m/s |\n\
         |---|---|---|---|---|---|---|"
    );
    for model in NormalModel::ALL {
        for planar in [false, true] {
            if model == NormalModel::Hertz && !planar {
                continue;
            }
            let l = linear(&study, model, planar)?;
            let speed = critical_speed(&l).map_or("–".to_string(), |v| format!("{v:.1}"));
            let _ = writeln!(
                md,
                "| {} | {} | {:.2} | {:.2} | {:.3} | {:.3} | {speed} |",
                model_label(model),
                if planar { "yes" } else { "no" },
                l.f11 * 1e-6,
                l.f22 * 1e-6,
                l.gravity * 1e-6,
                l.conicity
            );
        }
    }
    Ok(md)
}
