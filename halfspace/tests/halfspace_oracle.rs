//! The normal models against an exact half-space solution where no CONTACT data exist.
//!
//! `railcontact_halfspace` solves Kalker's frictionless normal problem exactly on a grid
//! (Polonsky–Keer conjugate gradients, Boussinesq influence coefficients). Here it is applied to
//! the undeformed gap of a patch as the strips see it — h(x, s) = f(s) + A(s)(x − x_c(s))² on the
//! patch's contact plane, 0.2 × 0.2 mm elements like the reference — at the patch's normal force.
//! First the oracle itself is checked against CONTACT on the central case (tests/data/README.md);
//! then ANALYN (the best fast model, docs/validation.md) is checked against the oracle over the
//! lateral shifts −1…+4 mm (tread) within ±10 % in area and ±15 % in pmax, and at the flange-root
//! shifts +5 and +6 mm with area error under 18 % and pmax error under 50 %.
//!
//! Set-up as the root crate's `tests/central.rs` (benchmark profiles, E = 210 GPa, ν = 0.28,
//! 78.5 kN per wheel, no yaw, right wheel). Known limit of the oracle: one contact plane per wheel
//! (the dominant patch's); at +5 mm, where tread and flange-root contact coexist, it is
//! approximate.

// The root crate's shared test set-up (benchmark wheelset, vendored data of `tests/data`).
#[path = "../../tests/common/mod.rs"]
mod common;

use railcontact::geometry::search::StripPoints;
use railcontact::geometry::strips::StripGeometry;
use railcontact::material::Material;
use railcontact::normal::hertz::contact_modulus;
use railcontact::normal::NormalModel;
use railcontact::wheelset::{Creepages, Vertical, Wheelset, WheelsetInput, WheelsetResult};
use railcontact_halfspace::{solve, Grid, Target};

use common::benchmark_wheelset;

const Q: f64 = 78_500.0;
const E: f64 = 210e9;
const NU: f64 = 0.28;
/// Element size of the oracle, as CONTACT's reference [m].
const ELEMENT: f64 = 0.2e-3;

fn wheelset(model: NormalModel) -> Wheelset {
    let material = Material {
        youngs_modulus: E,
        poisson_ratio: NU,
        friction: 0.3,
    };
    benchmark_wheelset(material, model)
}

/// (area [m²], pmax [Pa]) of the model's right wheel and of the exact solution on the dominant
/// patch's plane at the wheel's total normal force.
fn model_and_oracle(ws: &mut Wheelset, y: f64) -> ((f64, f64), (f64, f64)) {
    model_and_oracle_yawed(ws, y, 0.0)
}

/// [`model_and_oracle`] at yaw angle `yaw` [rad].
fn model_and_oracle_yawed(ws: &mut Wheelset, y: f64, yaw: f64) -> ((f64, f64), (f64, f64)) {
    let input = WheelsetInput {
        y,
        yaw,
        roll: 0.0,
        vertical: Vertical::Loads { left: Q, right: Q },
        creepages: Creepages::Prescribed {
            creepage: Default::default(),
            vx: 2.0,
        },
    };
    let mut out = WheelsetResult::default();
    ws.solve(&input, &mut out).expect("solve");
    let patches: Vec<_> = out.right.shown_patches().copied().collect();
    let area = patches.iter().map(|p| p.area).sum();
    let pmax = patches.iter().map(|p| p.pmax).fold(0.0, f64::max);
    let normal_force: f64 = patches.iter().map(|p| p.fn_).sum();

    let dominant = ws
        .strip_patches(true)
        .iter()
        .max_by(|a, b| {
            let (fa, fb) = (a.summary().normal_force, b.summary().normal_force);
            fa.total_cmp(&fb)
        })
        .expect("a strip patch");
    let summary = dominant.summary();
    // 4 mm beyond the model's patch on each side: the exact patch may be wider.
    let (lo, hi) = (summary.s_min - 4e-3, summary.s_max + 4e-3);
    let ny =
        (((hi - lo) / ELEMENT).round() as usize).min(railcontact::geometry::strips::MAX_STRIPS);
    let mut geom = StripGeometry::default();
    let mut points = StripPoints::default();
    ws.geometry(true).strip_geometry(
        &dominant.plane,
        lo,
        lo + ny as f64 * ELEMENT,
        ny,
        &mut geom,
        &mut points,
    );
    let half_x = 0.75 * summary.length + 1e-3;
    let nx = (2.0 * half_x / ELEMENT).ceil() as usize;
    let grid = Grid {
        nx,
        ny,
        dx: ELEMENT,
        dy: ELEMENT,
        x0: -(nx as f64) * ELEMENT / 2.0,
        y0: lo,
    };
    let gap: Vec<f64> = (0..ny)
        .flat_map(|j| {
            let geom = &geom;
            let grid = &grid;
            (0..nx).map(move |i| geom.f[j] + geom.curv_a[j] * (grid.x(i) - geom.x_c[j]).powi(2))
        })
        .collect();
    let exact = solve(
        &grid,
        &gap,
        Target::Force(normal_force),
        contact_modulus(E, NU),
        1e-9,
    )
    .expect("half-space solve");
    ((area, pmax), (exact.contact_area, exact.max_pressure))
}

#[test]
fn oracle_reproduces_contact_on_the_central_case() {
    // CONTACT: 168.4 mm², 888.3 MPa (reference/central/normal_dy0_summary.csv). Tolerance 1 %:
    // the same 0.2 mm elements; the area counts whole elements (one row of the ~20 mm wide patch
    // is 1 %).
    let (_, (area, pmax)) = model_and_oracle(&mut wheelset(NormalModel::Analyn), 0.0);
    println!("oracle: {:.1} mm², {:.1} MPa", area * 1e6, pmax / 1e6);
    assert!((area * 1e6 / 168.4 - 1.0).abs() < 0.01, "area {area}");
    assert!((pmax / 1e6 / 888.3 - 1.0).abs() < 0.01, "pmax {pmax}");
}

/// `model` against the oracle at the poses (lateral shift [mm], yaw [rad]): prints each and
/// returns the poses whose (area, pmax) errors reach `tolerance`(y in mm).
fn compare_over_poses(
    model: NormalModel,
    poses: &[(f64, f64)],
    tolerance: impl Fn(f64) -> (f64, f64),
) -> Vec<String> {
    let mut ws = wheelset(model);
    let mut failures = Vec::new();
    for &(y_mm, yaw) in poses {
        let ((area, pmax), (exact_area, exact_pmax)) =
            model_and_oracle_yawed(&mut ws, y_mm * 1e-3, yaw);
        let (ea, ep) = (area / exact_area - 1.0, pmax / exact_pmax - 1.0);
        println!(
            "y {y_mm:+.0} mm, yaw {:+.0} mrad: {} {:6.1} mm² {:6.0} MPa | exact {:6.1} mm² \
             {:6.0} MPa | {:+5.1} % {:+5.1} %",
            yaw * 1e3,
            model.name(),
            area * 1e6,
            pmax / 1e6,
            exact_area * 1e6,
            exact_pmax / 1e6,
            100.0 * ea,
            100.0 * ep
        );
        let (area_tol, pmax_tol) = tolerance(y_mm);
        if ea.abs() >= area_tol || ep.abs() >= pmax_tol {
            failures.push(format!(
                "y = {y_mm} mm, yaw {yaw}: area {ea:+.3}, pmax {ep:+.3}"
            ));
        }
    }
    failures
}

/// The lateral shifts of the comparisons [mm], at zero yaw.
const SHIFTS: [(f64, f64); 8] = [
    (-1.0, 0.0),
    (0.0, 0.0),
    (1.0, 0.0),
    (2.0, 0.0),
    (3.0, 0.0),
    (4.0, 0.0),
    (5.0, 0.0),
    (6.0, 0.0),
];

#[test]
fn analyn_against_the_exact_solution_over_lateral_shifts() {
    let failures = compare_over_poses(NormalModel::Analyn, &SHIFTS, |y_mm| {
        if y_mm <= 4.0 {
            (0.10, 0.15)
        } else {
            (0.18, 0.50)
        }
    });
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn coupled_strips_against_the_exact_solution_over_lateral_shifts() {
    // normalModel 7 over −1…+6 mm at zero yaw and ±4 mrad at 0 and +3 mm: pmax within 10 %
    // everywhere (measured ≤ 3.4 %), area within 5 % on the tread (−1…+4 mm; measured
    // −1.2…+0.9 %) and 10 % at the flange root (+5, +6 mm; measured +2.2 %, −2.5 %).
    let yawed = [(0.0, 4e-3), (0.0, -4e-3), (3.0, 4e-3), (3.0, -4e-3)];
    let poses: Vec<_> = SHIFTS.iter().chain(&yawed).copied().collect();
    let failures = compare_over_poses(NormalModel::CoupledStrips, &poses, |y_mm| {
        (if y_mm <= 4.0 { 0.05 } else { 0.10 }, 0.10)
    });
    assert!(failures.is_empty(), "{failures:#?}");
}
