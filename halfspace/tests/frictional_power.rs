//! The frictional power — the Tγ every wear model starts from — and its distribution across the
//! patch against the exact steady rolling solution: Kalker's planar problem on the exact pressure
//! (`ExactWheel::planar_rolling`), creepages about the plane's origin as CONTACT prescribes them.
//!
//! Set-up as the root crate's `tests/tangential.rs` (benchmark profiles, E = 210 GPa, ν = 0.28,
//! μ = 0.3, 78.5 kN, right wheel), at lateral shifts 0 and +2 mm, on creep curves: ξ or η =
//! 0.002, 0.005, 0.01, without spin and with the rolling spin sin γ / r0 of the exact plane
//! (r0 = 0.46 m; 0.0761 and 0.1638 1/m).
//!
//! The exact dissipation −Σ q·s ΔA converges at first order in the element size (the
//! steady-state difference ∂u/∂x, `rolling.rs`), from below; CONTACT's reference is its 0.2 mm
//! solution, where the oracle's dense Newton systems (≈ 9 000 unknowns) are out of reach. The
//! reference here is therefore the oracle at 0.4, 0.6 and 0.8 mm extrapolated linearly in the
//! element size to 0.2 mm (`ExactWheel::planar_t_gamma`) — at 0 mm within 1.5 % of CONTACT's own 0.2 mm power on all twelve
//! points of `creep_curves_dy0.csv` with creepage ≥ 0.002 (checked below).
//!
//! Run in release builds only (`tests/run_all.sh`): the exact solutions take about a minute per
//! shift.

#[path = "../../tests/common/mod.rs"]
mod common;

use railcontact::material::Material;
use railcontact::normal::NormalModel;
use railcontact::tangential::fastsim::Creepage;
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::{Creepages, Wheelset};
use railcontact_halfspace::wheel_rail::{DissipationEstimate, ExactWheel};

const Q: f64 = 78_500.0;
const E: f64 = 210e9;
const NU: f64 = 0.28;
const MU: f64 = 0.3;
/// Nominal rolling radius of the kinematic spin [m].
const R0: f64 = 0.46;

/// The configuration whose frictional power is closest to the exact theory (docs/theory.md
/// §10.7): ANALYN with its FASTSIM on the equivalent ellipse (`tangentialModel` 1), on the
/// default non-planar patch.
const BEST: (NormalModel, TangentialModel, bool) =
    (NormalModel::Analyn, TangentialModel::ModelDefault, false);

fn material() -> Material {
    Material {
        youngs_modulus: E,
        poisson_ratio: NU,
        friction: MU,
    }
}

fn wheelset((model, tangential, planar): (NormalModel, TangentialModel, bool)) -> Wheelset {
    common::benchmark_wheelset_with(material(), common::patch_options(model, tangential, planar))
}

/// The exact wheel at lateral shift `shift` [m] (zero yaw), from a coupled-strips wheelset's
/// lowering.
fn exact_wheel(shift: f64) -> ExactWheel {
    let mut ws = wheelset((
        NormalModel::CoupledStrips,
        TangentialModel::ModelDefault,
        true,
    ));
    let out = common::solve_pose(&mut ws, shift, 0.0, Q, common::at_rest(1.0));
    ExactWheel::solve(ws.geometry(true), out.right.z, Q, 0.2e-3, (E, NU)).expect("exact")
}

/// One creep-curve point and its exact Tγ.
struct ExactPoint {
    creepage: Creepage,
    estimate: DissipationEstimate,
}

fn exact_point(exact: &ExactWheel, creepage: Creepage) -> ExactPoint {
    let g = E / (2.0 * (1.0 + NU));
    let estimate = exact
        .planar_t_gamma((creepage.xi, creepage.eta, creepage.phi), (g, NU, MU))
        .expect("exact rolling");
    ExactPoint { creepage, estimate }
}

/// The right wheel's Tγ of `ws` at lateral shift `shift` [m] with `creepage` prescribed [N].
fn model_t_gamma(ws: &mut Wheelset, shift: f64, creepage: Creepage) -> f64 {
    let creepages = Creepages::Prescribed { creepage, vx: 1.0 };
    let out = common::solve_pose(ws, shift, 0.0, Q, creepages);
    out.right.all_patches().iter().map(|p| p.t_gamma).sum()
}

/// The creep-curve points at a shift whose plane has contact angle `angle` [rad].
fn creep_points(angle: f64) -> Vec<Creepage> {
    let spin = angle.sin() / R0;
    let mut v = Vec::new();
    for c in [0.002, 0.005, 0.01] {
        for phi in [0.0, spin] {
            v.push(Creepage {
                xi: c,
                eta: 0.0,
                phi,
            });
            v.push(Creepage {
                xi: 0.0,
                eta: c,
                phi,
            });
        }
    }
    v
}

/// Every option's worst and mean relative error of Tγ against `exact` at `shift` (printed);
/// returns the best configuration's (worst, mean).
fn compare_models(shift: f64, exact: &[ExactPoint]) -> (f64, f64) {
    let mut options = vec![(NormalModel::Hertz, TangentialModel::ModelDefault, true)];
    for model in [NormalModel::Analyn, NormalModel::CoupledStrips] {
        for t in TangentialModel::ALL {
            options.push((model, t, false));
        }
    }
    let mut best = (f64::NAN, f64::NAN);
    for option in options {
        let mut ws = wheelset(option);
        let errors: Vec<f64> = exact
            .iter()
            .map(|p| model_t_gamma(&mut ws, shift, p.creepage) / p.estimate.t_gamma - 1.0)
            .collect();
        let (worst, mean, line) = common::error_summary(&errors);
        println!(
            "{:>14} {:>18}: worst {:4.1} % mean {:4.1} % |{line}",
            option.0.name(),
            option.1.name(),
            100.0 * worst,
            100.0 * mean
        );
        if option == BEST {
            best = (worst, mean);
        }
    }
    best
}

/// The exact dissipation's discretisation: below the work on the rigid slip, and closer to it on
/// a finer grid (docs/theory.md §4.5).
fn assert_power_converges_to_the_work(points: &[ExactPoint]) {
    for p in points {
        let ratios: Vec<f64> = p.estimate.per_element.iter().map(|e| e.1 / e.2).collect();
        println!("{:?}: Tγ/work by element {ratios:.4?}", p.creepage);
        for pair in ratios.windows(2) {
            // The elements grow: the ratio falls with them, and stays below 1.
            assert!(pair[0] < 1.0 && pair[1] < pair[0], "{ratios:?}");
        }
    }
}

/// Dissipation-weighted mean and standard deviation of the rail coordinate over `points`
/// (y_rail [m], dissipation [N]) [m].
fn spread(points: impl Iterator<Item = (f64, f64)>) -> (f64, f64) {
    let (mut w, mut m1, mut m2) = (0.0, 0.0, 0.0);
    for (y, d) in points {
        w += d;
        m1 += d * y;
        m2 += d * y * y;
    }
    let mean = m1 / w;
    (mean, (m2 / w - mean * mean).max(0.0).sqrt())
}

/// The best configuration's slip field against the exact one at `point` (ξ = 0.002 with the
/// rolling spin): where across the profile the energy is dissipated (its mean rail coordinate
/// and spread) and the slipping share of the patch. Returns (mean, spread) differences [m] and
/// the slipping shares (model, exact).
fn compare_fields(shift: f64, exact: &ExactWheel, point: &ExactPoint) -> ([f64; 2], [f64; 2]) {
    let (grid, sol) = &point.estimate.finest;
    let fine = &exact.grid;
    let exact_points = (0..grid.len()).map(|k| {
        let j = (((grid.y(k / grid.nx) - fine.y0) / fine.dy) as usize).min(fine.ny - 1);
        let d = -(sol.traction_x[k] * sol.slip_x[k] + sol.traction_y[k] * sol.slip_y[k]);
        (exact.rows.y_rail[j], d * grid.element_area())
    });
    let (mean_e, spread_e) = spread(exact_points);
    let slip_share_e = 1.0 - sol.adhesion_fraction;
    let mut ws = wheelset(BEST);
    let creepages = Creepages::Prescribed {
        creepage: point.creepage,
        vx: 1.0,
    };
    let out = common::solve_pose(&mut ws, shift, 0.0, Q, creepages);
    let field = ws.friction_field(true, 0).expect("a patch");
    let (mean_m, spread_m) = spread(
        field
            .iter()
            .map(|(y, e)| (*y, e.traction_sq.sqrt() * e.slip * e.area)),
    );
    let slip_share_m = 1.0 - out.right.patches[0].adhesion_fraction;
    println!(
        "y = {:.0} mm: dissipation at yRail {:.2} ± {:.2} mm (exact {:.2} ± {:.2}), slipping \
         share {slip_share_m:.3} (exact {slip_share_e:.3})",
        shift * 1e3,
        mean_m * 1e3,
        spread_m * 1e3,
        mean_e * 1e3,
        spread_e * 1e3
    );
    (
        [mean_m - mean_e, spread_m - spread_e],
        [slip_share_m, slip_share_e],
    )
}

/// The dissipation lies where the exact one does: its mean rail coordinate and its spread within
/// 0.5 mm (one bin of the wear distribution across the profiles; measured 0.23 and 0.15 mm at
/// 0 mm, 0.43 and 0.33 mm at +2 mm). The slip zone is the simplified theory's, smaller than the
/// exact one (slipping share 0.52 against 0.74 at 0 mm, 0.32 against 0.60 at +2 mm: FASTSIM's
/// slip is concentrated where the exact solution's is spread): only reported, and checked to be
/// a partial slip in both.
fn assert_fields_agree(([mean, spread], shares): ([f64; 2], [f64; 2])) {
    assert!(
        mean.abs() < 0.5e-3 && spread.abs() < 0.5e-3,
        "{mean} {spread}"
    );
    for share in shares {
        assert!(share > 0.05 && share < 0.95, "{shares:?}");
    }
}

#[test]
fn frictional_power_at_the_centre() {
    // The oracle against CONTACT's 0.2 mm power at the same creepages (its creep curves, creepage
    // ≥ 0.002): within 1.5 % (measured 0.2–0.7 %: the extrapolation's error).
    if !common::rolling_comparisons_run() {
        return;
    }
    let exact = exact_wheel(0.0);
    let rows = common::read_csv("reference/central/creep_curves_dy0.csv");
    let mut points = Vec::new();
    for r in &rows {
        let creepage = Creepage {
            xi: r["cksi"],
            eta: r["ceta"],
            phi: r["cphi_per_mm"] * 1e3,
        };
        if creepage.xi.abs().max(creepage.eta.abs()) < 0.002 - 1e-6 {
            continue;
        }
        let p = exact_point(&exact, creepage);
        let contact = -r["fric_power_W"] / (r["veloc_mm_s"] * 1e-3);
        println!(
            "{creepage:?}: oracle {:.2} N, CONTACT {contact:.2} N",
            p.estimate.t_gamma
        );
        assert!((p.estimate.t_gamma / contact - 1.0).abs() < 0.015);
        points.push(p);
    }
    assert_eq!(points.len(), 12);
    assert_power_converges_to_the_work(&points);
    let rolling = points
        .iter()
        .find(|p| (p.creepage.xi - 0.002).abs() < 1e-6 && p.creepage.phi > 0.0)
        .expect("ξ = 0.002 with the rolling spin");
    assert_fields_agree(compare_fields(0.0, &exact, rolling));
    let (worst, mean) = compare_models(0.0, &points);
    // Required of the best configuration: 5 % worst, 2.5 % mean (measured 4.9 %, 1.7 %).
    assert!(worst < 0.05 && mean < 0.025, "{worst} {mean}");
}

#[test]
fn frictional_power_at_two_millimetres() {
    if !common::rolling_comparisons_run() {
        return;
    }
    let shift = 2e-3;
    let exact = exact_wheel(shift);
    let points: Vec<ExactPoint> = creep_points(exact.reference.angle)
        .into_iter()
        .map(|c| exact_point(&exact, c))
        .collect();
    assert_power_converges_to_the_work(&points);
    assert_fields_agree(compare_fields(shift, &exact, &points[2]));
    let (worst, mean) = compare_models(shift, &points);
    // Required of the best configuration: 5 % worst, 2.5 % mean (measured 4.0 %, 1.9 %).
    assert!(worst < 0.05 && mean < 0.025, "{worst} {mean}");
}
