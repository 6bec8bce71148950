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
//! The tangential side likewise: `railcontact_halfspace::solve_rolling` (Kalker's steady rolling
//! problem on the exact pressure) is checked against CONTACT's creep curves of the central case,
//! then the coupled strips' creep curves with FaStrip against it at 0 and +2 mm (release builds).
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
use railcontact::tangential::fastsim::Creepage;
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::{Creepages, Wheelset, WheelsetResult};
use railcontact_halfspace::wheel_rail::{strip_gap, strip_grid};
use railcontact_halfspace::{solve, solve_rolling, Grid, Rolling, Solution, Target};

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
    let o = exact_normal(ws, y, yaw, Creepage::default(), ELEMENT);
    let patches: Vec<_> = o.out.right.shown_patches().copied().collect();
    let area = patches.iter().map(|p| p.area).sum();
    let pmax = patches.iter().map(|p| p.pmax).fold(0.0, f64::max);
    ((area, pmax), (o.exact.contact_area, o.exact.max_pressure))
}

/// The model's solution of a pose with prescribed creepages and the exact normal solution on
/// the dominant patch's plane at the wheel's total normal force.
struct ExactNormal {
    out: WheelsetResult,
    grid: Grid,
    exact: Solution,
    /// Lateral coordinate on the plane of the patch's reference point (the strips' pressure
    /// centroid, where the creepages hold) [m].
    s_reference: f64,
    /// Longitudinal coordinate of the reference point (its yaw lead) [m]: the spin's lateral
    /// rigid slip φx is zero there.
    x_reference: f64,
}

/// [`ExactNormal`] of the right wheel at lateral shift `y` [m] and yaw `yaw` [rad], the model
/// solved with the prescribed `creepage`, the oracle on elements of `element` × `element`.
fn exact_normal(
    ws: &mut Wheelset,
    y: f64,
    yaw: f64,
    creepage: Creepage,
    element: f64,
) -> ExactNormal {
    let out = solve_pose(ws, y, yaw, creepage);
    let normal_force: f64 = out.right.shown_patches().map(|p| p.fn_).sum();

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
        (((hi - lo) / element).round() as usize).min(railcontact::geometry::strips::MAX_STRIPS);
    let mut geom = StripGeometry::default();
    let mut points = StripPoints::default();
    ws.geometry(true).strip_geometry(
        &dominant.plane,
        lo,
        lo + ny as f64 * element,
        ny,
        &mut geom,
        &mut points,
    );
    let half_x = 0.75 * summary.length + 1e-3;
    let grid = strip_grid(element, ny, lo, half_x, 0.0);
    let gap = strip_gap(&geom, &grid, 0.0);
    let exact = solve(
        &grid,
        &gap,
        Target::Force(normal_force),
        contact_modulus(E, NU),
        1e-9,
    )
    .expect("half-space solve");
    ExactNormal {
        out,
        grid,
        exact,
        s_reference: summary.s_centroid,
        x_reference: dominant.interpolate(&dominant.geom.x_c, summary.s_centroid),
    }
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

/// Element size of the rolling oracle [m]: 2.5 × the normal reference's, which keeps its dense
/// Newton system (two unknowns per loaded element, ~700 elements on the central patch) at about
/// a second per solve; against CONTACT's 0.2 mm solution it stays within 0.9 % of μN
/// (`exact_rolling_reproduces_contact_creep_curves`).
const ROLLING_ELEMENT: f64 = 0.5e-3;

/// Friction coefficient of the creep-curve comparisons (the reference's).
const MU: f64 = 0.3;

/// Exact steady rolling under the exact pressure of `o` with the prescribed `creepage` (about
/// the model patch's reference point): (Fx, Fy) over μN of the right wheel's patch.
fn exact_rolling(o: &ExactNormal, creepage: Creepage) -> (f64, f64) {
    let g = o.grid;
    let loaded = |i: usize, j: usize| o.exact.pressure[j * g.nx + i] > 0.0;
    let cols: Vec<usize> = (0..g.nx)
        .filter(|&i| (0..g.ny).any(|j| loaded(i, j)))
        .collect();
    let rows: Vec<usize> = (0..g.ny)
        .filter(|&j| (0..g.nx).any(|i| loaded(i, j)))
        .collect();
    let (i0, i1) = (cols[0], *cols.last().unwrap());
    let (j0, j1) = (rows[0], *rows.last().unwrap());
    // The loaded box; x and y from the patch's reference point.
    let crop = Grid {
        nx: i1 - i0 + 1,
        ny: j1 - j0 + 1,
        dx: g.dx,
        dy: g.dy,
        x0: g.x0 + i0 as f64 * g.dx - o.x_reference,
        y0: g.y0 + j0 as f64 * g.dy - o.s_reference,
    };
    let pressure: Vec<f64> = (j0..=j1)
        .flat_map(|j| (i0..=i1).map(move |i| (i, j)))
        .map(|(i, j)| o.exact.pressure[j * g.nx + i])
        .collect();
    let rolling = Rolling {
        xi: creepage.xi,
        eta: creepage.eta,
        phi: creepage.phi,
        shear_modulus: E / (2.0 * (1.0 + NU)),
        poisson_ratio: NU,
        friction: MU,
    };
    let sol = solve_rolling(&crop, &pressure, &rolling, 1e-9).expect("rolling solve");
    let mu_n = MU * o.exact.normal_force;
    (sol.fx / mu_n, sol.fy / mu_n)
}

#[test]
fn exact_rolling_reproduces_contact_creep_curves() {
    // CONTACT's creep curves of the central case (pure ξ and η, and with the spin of pure
    // rolling) against the rolling oracle on the oracle's own exact pressure: within 1.5 % of μN
    // at every point (measured 0.86 %, at ξ = 2e−3: the oracle's 0.5 mm elements against
    // CONTACT's 0.2 mm; first order in the element size).
    if !common::rolling_comparisons_run() {
        return;
    }
    let rows = common::read_csv("reference/central/creep_curves_dy0.csv");
    let mut ws = wheelset(NormalModel::Analyn);
    let mut worst: f64 = 0.0;
    for r in &rows {
        let creepage = Creepage {
            xi: r["cksi"],
            eta: r["ceta"],
            phi: r["cphi_per_mm"] * 1e3,
        };
        if creepage.xi.abs().max(creepage.eta.abs()) < 4e-4 {
            continue;
        }
        let o = exact_normal(&mut ws, 0.0, 0.0, creepage, ROLLING_ELEMENT);
        let (fx, fy) = exact_rolling(&o, creepage);
        let (fx_ref, fy_ref) = (r["fx_over_mufn"], r["fs_over_mufn"]);
        let e = (fx - fx_ref).abs().max((fy - fy_ref).abs());
        worst = worst.max(e);
        println!(
            "ξ {:.4} η {:.4} φ {:.4}: exact Fx {fx:+.4} CONTACT {fx_ref:+.4} | Fy {fy:+.4} \
             CONTACT {fy_ref:+.4} | {e:.4}",
            creepage.xi, creepage.eta, creepage.phi
        );
    }
    println!("worst {worst:.4}");
    assert!(worst < 0.015, "worst {worst}");
}

/// The tangential options compared with the rolling oracle, on the coupled strips' planar patch.
const CREEP_OPTIONS: [TangentialModel; 2] =
    [TangentialModel::Fastrip, TangentialModel::FastripCoupled];

/// The coupled strips with FaStrip (3) and FaStrip with coupled coefficients (5) on the planar
/// patch against the rolling oracle at the `poses` (lateral shift [m], yaw [rad]): pure ξ and η
/// from 5e−4 to 1e−2, without spin and with the spin of pure rolling, sin γ / r at the patch.
/// Prints the curves and returns the (option, shift, worst, mean) difference in units of μN
/// (mean over both force components of every point, as `tests/tangential.rs` does).
fn coupled_creep_curves_against_the_oracle(
    poses: &[(f64, f64)],
) -> Vec<(TangentialModel, f64, f64, f64)> {
    let material = Material {
        youngs_modulus: E,
        poisson_ratio: NU,
        friction: MU,
    };
    let mut wheelsets: Vec<Wheelset> = CREEP_OPTIONS
        .iter()
        .map(|&t| {
            common::benchmark_wheelset_with(
                material,
                common::patch_options(NormalModel::CoupledStrips, t, true),
            )
        })
        .collect();
    let steps = [5e-4, 1e-3, 2e-3, 5e-3, 1e-2];
    let mut summary = Vec::new();
    for &(y, yaw) in poses {
        let rest = exact_normal(
            &mut wheelsets[0],
            y,
            yaw,
            Creepage::default(),
            ROLLING_ELEMENT,
        );
        let patch = rest.out.right.patches[0];
        let spin = patch.contact_angle.sin() / patch.rolling_radius;
        // Linear limit: the creep stiffness for pure ξ and pure η of 1e−5 against the exact one.
        // Measured with FaStrip 0.932 and 0.915 at 0 mm, 0.963 and 0.953 at +2 mm; with the
        // coupled coefficients 0.960, 0.955, 0.991, 0.998. Bound 0.9: the lowest measured less
        // the oracle's own 1.6–2.2 % excess stiffness on 0.5 mm elements (its unit test against
        // Kalker's C11, C22).
        for (xi, eta) in [(1e-5, 0.0), (0.0, 1e-5)] {
            let creepage = Creepage { xi, eta, phi: 0.0 };
            let o = exact_normal(&mut wheelsets[0], y, yaw, creepage, ROLLING_ELEMENT);
            let (fx, fy) = exact_rolling(&o, creepage);
            for (ws, t) in wheelsets.iter_mut().zip(CREEP_OPTIONS) {
                let p = model_patch(ws, y, yaw, creepage);
                let ratio = if xi > 0.0 {
                    p.fx / (MU * p.fn_) / fx
                } else {
                    p.fy / (MU * p.fn_) / fy
                };
                println!(
                    "y {:+.0} mm ξ {xi:.0e} η {eta:.0e} {}: stiffness / exact {ratio:.3}",
                    y * 1e3,
                    t.name()
                );
                assert!(
                    (0.9..1.05).contains(&ratio),
                    "y {y} ξ {xi} η {eta} {}: {ratio}",
                    t.name()
                );
            }
        }
        let mut totals = [(0.0f64, 0.0f64, 0usize); CREEP_OPTIONS.len()];
        for phi in [0.0, spin] {
            let curves = steps
                .iter()
                .map(|&c| (c, 0.0))
                .chain(steps.iter().map(|&c| (0.0, c)));
            for (xi, eta) in curves {
                let creepage = Creepage { xi, eta, phi };
                let o = exact_normal(&mut wheelsets[0], y, yaw, creepage, ROLLING_ELEMENT);
                let (fx, fy) = exact_rolling(&o, creepage);
                let mut line = format!(
                    "y {:+.0} mm ξ {xi:.4} η {eta:.4} φ {phi:.4}: exact {fx:+.4} {fy:+.4}",
                    y * 1e3
                );
                for (k, ws) in wheelsets.iter_mut().enumerate() {
                    let p = model_patch(ws, y, yaw, creepage);
                    let (mx, my) = (p.fx / (MU * p.fn_), p.fy / (MU * p.fn_));
                    let (ex, ey) = ((mx - fx).abs(), (my - fy).abs());
                    let (worst, sum, count) = &mut totals[k];
                    *worst = worst.max(ex.max(ey));
                    *sum += ex + ey;
                    *count += 2;
                    line += &format!(
                        " | {} {mx:+.4} {my:+.4} {:.4}",
                        CREEP_OPTIONS[k].name(),
                        ex.max(ey)
                    );
                }
                println!("{line}");
            }
        }
        for (t, (worst, sum, count)) in CREEP_OPTIONS.iter().zip(totals) {
            let mean = sum / count as f64;
            println!(
                "y {:+.0} mm {}: worst {worst:.4}, mean {mean:.4}",
                y * 1e3,
                t.name()
            );
            summary.push((*t, y, worst, mean));
        }
    }
    summary
}

/// The solution of `ws` at lateral shift `y` [m] and yaw `yaw` [rad], 78.5 kN per wheel, with
/// `creepage` prescribed.
fn solve_pose(ws: &mut Wheelset, y: f64, yaw: f64, creepage: Creepage) -> WheelsetResult {
    let creepages = Creepages::Prescribed { creepage, vx: 2.0 };
    common::solve_pose(ws, y, yaw, Q, creepages)
}

/// The right wheel's first patch of [`solve_pose`].
fn model_patch(
    ws: &mut Wheelset,
    y: f64,
    yaw: f64,
    creepage: Creepage,
) -> railcontact::wheelset::PatchResult {
    solve_pose(ws, y, yaw, creepage).right.patches[0]
}

#[test]
fn coupled_strips_creep_curves_against_the_exact_solution() {
    // Measured (docs/validation.md), worst and mean difference in units of μN at 0 mm, +2 mm
    // and +2 mm with 4 mrad yaw:
    //   FaStrip (3):                       4.1 / 1.0 %, 7.7 / 1.6 %, 7.6 / 1.7 %
    //   FaStrip, coupled coefficients (5): 2.3 / 0.5 %, 2.1 / 0.4 %, 2.1 / 0.5 %
    // Option 5 is held to the accuracy the coupled strips are built for (4 % at every point,
    // 1.5 % on average; the oracle's own error on its 0.5 mm elements is ≤ 0.9 % of μN against
    // CONTACT's 0.2 mm, `exact_rolling_reproduces_contact_creep_curves`). Option 3's bounds are
    // its measured figures with 0.5 % of μN for the oracle's error, so that a change that makes
    // them worse fails here.
    if !common::rolling_comparisons_run() {
        return;
    }
    let summary = coupled_creep_curves_against_the_oracle(&[(0.0, 0.0), (2e-3, 0.0), (2e-3, 4e-3)]);
    for (t, y, worst, mean) in summary {
        let (worst_bound, mean_bound) = match (t, y == 0.0) {
            (TangentialModel::FastripCoupled, _) => (0.04, 0.015),
            (_, true) => (0.045, 0.015),
            (_, false) => (0.081, 0.021),
        };
        assert!(
            worst < worst_bound && mean < mean_bound,
            "{} y {y}: worst {worst}, mean {mean}",
            t.name()
        );
    }
}
