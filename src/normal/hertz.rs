//! Hertz normal contact of two elastic bodies with identical materials.
//!
//! Papers: H. Hertz (1882), "Über die Berührung fester elastischer Körper"; K.L. Johnson,
//! *Contact Mechanics* (1985) §4.2 and Table 4.1 (m, n, r). Equations as labelled in
//! docs/theory.md §2:
//!
//! * **H1** axis ratio g = b'/a' from B'/A' = (E(e)/g² − K(e)) / (K(e) − E(e)), e² = 1 − g², solved
//!   by a bracketed Illinois (modified regula falsi) iteration on ln(B'/A') versus ln g, started from
//!   Greenwood's estimate g ≈ (B'/A')^{−2/3} (`solve_axis_ratio`). No table, no global state, no
//!   allocation.
//! * **H2** a'³ = 3N E/(2π E* g² (A+B)), b' = g a';
//! * **H3** δ = 3N K/(2π E* a') = (A+B) b'² K/E;
//! * **H4** p0 = 3N/(2πab);
//! * **H5** inverse for a prescribed approach δ: b'² = δE/((A+B)K), N = 2π E* a' δ/(3K);
//! * **H6** shape factors ε_x = A a²/δ, ε_y = B b²/δ, ε_x + ε_y = 1;
//! * **H7** m, n, r coefficients (`mnr_coefficients`).
//!
//! The elliptic integrals come from the AGM (`crate::numeric::elliptic`, docs/theory.md §9.1), with
//! K − E free of cancellation so that H1 and H6 stay accurate near the circle.
//!
//! Conventions: A is the relative curvature in the rolling direction x, B the lateral one [1/m];
//! the semi-axis `a` lies along x and `b` along y, whichever is larger. E* = E/(2(1 − ν²)) for two
//! bodies of the same material.
//!
//! Known limits: A, B > 0 are required (conformal or concave-lateral contact is not Hertzian;
//! docs/theory.md §5.9 handles it elsewhere). H1 is solved for B'/A' from 1 up to about 1e12 (g
//! down to ~1e−7); the acceptance range is 1…1e6. Half-space, frictionless, small-strain theory.

use crate::error::{require_non_negative, require_positive, InputError};
use crate::numeric::elliptic::{complete_elliptic_from_complementary, CompleteElliptic};
use crate::numeric::roots::Illinois;
use std::f64::consts::PI;

/// Contact modulus E* = E/(2(1 − ν²)) [Pa] of two bodies with the same Young's modulus `e` [Pa] and
/// Poisson ratio `nu` [-] (docs/theory.md §2.1).
pub fn contact_modulus(e: f64, nu: f64) -> f64 {
    e / (2.0 * (1.0 - nu * nu))
}

/// Shear modulus G = E/(2(1 + ν)) [Pa].
pub fn shear_modulus(e: f64, nu: f64) -> f64 {
    e / (2.0 * (1.0 + nu))
}

/// A Hertzian contact ellipse.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HertzPatch {
    /// Semi-axis along x (rolling direction, the A curvature) [m].
    pub a: f64,
    /// Semi-axis along y (lateral, the B curvature) [m].
    pub b: f64,
    /// Rigid approach (penetration) δ [m].
    pub approach: f64,
    /// Maximum pressure p0 [Pa].
    pub p0: f64,
    /// Normal force N [N].
    pub normal_force: f64,
}

impl HertzPatch {
    /// Contact area π a b [m²].
    pub fn area(&self) -> f64 {
        PI * self.a * self.b
    }

    /// Hertz pressure p0 √(1 − x²/a² − y²/b²) at (x, y) [m]; zero outside the ellipse (H4) [Pa].
    pub fn pressure_at(&self, x: f64, y: f64) -> f64 {
        if self.a <= 0.0 || self.b <= 0.0 {
            return 0.0;
        }
        let s = 1.0 - (x / self.a).powi(2) - (y / self.b).powi(2);
        if s > 0.0 {
            self.p0 * s.sqrt()
        } else {
            0.0
        }
    }
}

/// Solution of H1 for one curvature ratio, everything needed by H2–H7.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisRatio {
    /// g = b'/a' ∈ (0, 1], minor over major semi-axis [-].
    pub g: f64,
    /// K(e), E(e), K − E at eccentricity e = √(1 − g²).
    pub integrals: CompleteElliptic,
}

impl AxisRatio {
    /// e² = 1 − g² computed as (1 − g)(1 + g) [-].
    pub fn eccentricity_squared(&self) -> f64 {
        (1.0 - self.g) * (1.0 + self.g)
    }
}

/// Right-hand side of H1: B'/A' as a function of g ∈ (0, 1] (1 at the circle).
fn curvature_ratio_of(g: f64, ell: &CompleteElliptic) -> f64 {
    if g >= 1.0 {
        return 1.0;
    }
    let e2 = (1.0 - g) * (1.0 + g);
    // E/g² − K = E e²/g² − (K − E): two terms of ratio ~2 near the circle, no cancellation.
    (ell.e * e2 / (g * g) - ell.k_minus_e) / ell.k_minus_e
}

/// Largest curvature ratio B'/A' accepted by [`solve_axis_ratio`]. Beyond ~1e12 the ellipse is
/// a line contact for every practical purpose (g < 1e−7) and the H1 bracket search would need
/// more expansion steps; the tested range ends at 1e6.
pub const MAX_CURVATURE_RATIO: f64 = 1e12;

/// Iteration cap of the Illinois solve. Convergence is superlinear (about 8–12 steps from the
/// Greenwood start); the cap only bounds the work should round-off stall the bracket.
const MAX_H1_ITERATIONS: usize = 100;

/// Solves H1 for g = b'/a' given the curvature ratio B'/A' = max(A,B)/min(A,B) ≥ 1.
///
/// Works in t = ln g on h(t) = ln(B'/A'(g)) − ln(target), which is monotone decreasing and nearly
/// linear (slope ≈ −1.5 for small g), with an Illinois-safeguarded secant inside a bracket: every
/// iterate stays in the bracket, so the solve cannot diverge. Converged to |Δt| ≤ 4 ulp.
pub fn solve_axis_ratio(curvature_ratio: f64) -> Result<AxisRatio, InputError> {
    if !(curvature_ratio.is_finite() && (1.0..=MAX_CURVATURE_RATIO).contains(&curvature_ratio)) {
        return Err(InputError::new(
            "B/A",
            curvature_ratio,
            "[1, 1e12] (max/min curvature)",
        ));
    }
    if curvature_ratio == 1.0 {
        return Ok(AxisRatio {
            g: 1.0,
            integrals: complete_elliptic_from_complementary(1.0),
        });
    }
    let ln_target = curvature_ratio.ln();
    let h = |t: f64| -> (f64, CompleteElliptic) {
        let g = t.exp().min(1.0);
        let ell = complete_elliptic_from_complementary(g);
        (curvature_ratio_of(g, &ell).ln() - ln_target, ell)
    };
    // Bracket: h(t_hi) ≤ 0 ≤ h(t_lo), t_lo < t_hi ≤ 0. h(0) = −ln target < 0.
    let mut t_hi = 0.0_f64;
    let mut h_hi = -ln_target;
    // Greenwood's start 1/g ≈ (B'/A')^{2/3} (docs/theory.md §2.2).
    let mut t_lo = -(2.0 / 3.0) * ln_target;
    let (mut h_lo, mut ell_best) = h(t_lo);
    if h_lo < 0.0 {
        // The estimate undershoots the elongation for long ellipses (K grows like ln(4/g)):
        // it is a valid upper end; step down until the sign changes. Each step halves g at least
        // 4-fold in ln, so a few steps reach g ~ 1e−7.
        let mut step = 0.5 * ln_target.max(1.0);
        loop {
            t_hi = t_lo;
            h_hi = h_lo;
            t_lo -= step;
            step *= 2.0;
            let (hl, ell) = h(t_lo);
            h_lo = hl;
            ell_best = ell;
            if h_lo >= 0.0 {
                break;
            }
        }
    }
    if h_lo == 0.0 {
        return Ok(AxisRatio {
            g: t_lo.exp(),
            integrals: ell_best,
        });
    }
    // Illinois iteration on −h, which increases with t.
    let mut bracket = Illinois::new((t_lo, -h_lo), (t_hi, -h_hi));
    let mut t = t_lo;
    for _ in 0..MAX_H1_ITERATIONS {
        t = bracket.inside_or_midpoint(bracket.secant());
        let (ht, ell) = h(t);
        ell_best = ell;
        if ht == 0.0 {
            break;
        }
        bracket.update(t, -ht);
        let (t_lo, t_hi) = (bracket.neg.0, bracket.pos.0);
        if (t_hi - t_lo) <= 4.0 * f64::EPSILON * t_lo.abs().max(1e-3) {
            break;
        }
    }
    let g = t.exp().min(1.0);
    Ok(AxisRatio {
        g,
        integrals: ell_best,
    })
}

/// Validated curvatures: A, B finite and > 0, named "A" and "B" in errors.
fn check_curvatures(curv_a: f64, curv_b: f64) -> Result<(), InputError> {
    require_positive("A", curv_a)?;
    require_positive("B", curv_b)?;
    Ok(())
}

/// Semi-axes (a along x, b along y) from the major/minor pair and which curvature is smaller.
fn orient(curv_a: f64, curv_b: f64, major: f64, minor: f64) -> (f64, f64) {
    if curv_a <= curv_b {
        (major, minor)
    } else {
        (minor, major)
    }
}

/// Hertz ellipse for a prescribed normal force (H1–H4).
///
/// `curv_a`, `curv_b`: relative curvatures A (rolling direction) and B (lateral) [1/m], > 0;
/// `normal_force` N ≥ 0 [N]; `e_star` contact modulus E* > 0 [Pa]. N = 0 gives the all-zero patch.
pub fn hertz_from_load(
    curv_a: f64,
    curv_b: f64,
    normal_force: f64,
    e_star: f64,
) -> Result<HertzPatch, InputError> {
    check_curvatures(curv_a, curv_b)?;
    require_non_negative("N", normal_force)?;
    require_positive("E*", e_star)?;
    if normal_force == 0.0 {
        return Ok(HertzPatch::default());
    }
    let ratio = solve_axis_ratio(curv_a.max(curv_b) / curv_a.min(curv_b))?;
    let g = ratio.g;
    let ell = ratio.integrals;
    let sum_curv = curv_a + curv_b;
    // H2
    let major = (3.0 * normal_force * ell.e / (2.0 * PI * e_star * g * g * sum_curv)).cbrt();
    let minor = g * major;
    // H3
    let approach = sum_curv * minor * minor * ell.k / ell.e;
    let (a, b) = orient(curv_a, curv_b, major, minor);
    Ok(HertzPatch {
        a,
        b,
        approach,
        // H4
        p0: 3.0 * normal_force / (2.0 * PI * a * b),
        normal_force,
    })
}

/// Hertz ellipse for a prescribed rigid approach δ ≥ 0 [m] (H5, then H4).
pub fn hertz_from_approach(
    curv_a: f64,
    curv_b: f64,
    approach: f64,
    e_star: f64,
) -> Result<HertzPatch, InputError> {
    check_curvatures(curv_a, curv_b)?;
    require_non_negative("delta", approach)?;
    require_positive("E*", e_star)?;
    if approach == 0.0 {
        return Ok(HertzPatch::default());
    }
    let ratio = solve_axis_ratio(curv_a.max(curv_b) / curv_a.min(curv_b))?;
    let g = ratio.g;
    let ell = ratio.integrals;
    // H5
    let minor = (approach * ell.e / ((curv_a + curv_b) * ell.k)).sqrt();
    let major = minor / g;
    let normal_force = 2.0 * PI * e_star * major * approach / (3.0 * ell.k);
    let (a, b) = orient(curv_a, curv_b, major, minor);
    Ok(HertzPatch {
        a,
        b,
        approach,
        p0: 3.0 * normal_force / (2.0 * PI * a * b),
        normal_force,
    })
}

/// Shape factors (ε_x, ε_y) of H6: ε_x = A a²/δ, ε_y = B b²/δ, ε_x + ε_y = 1 [-].
///
/// Independent of load and material. For A ≤ B, ε_x = (K − E)/(e² K) (docs/theory.md §2.4); ε_y is
/// the complement.
pub fn shape_factors(curv_a: f64, curv_b: f64) -> Result<(f64, f64), InputError> {
    check_curvatures(curv_a, curv_b)?;
    let ratio = solve_axis_ratio(curv_a.max(curv_b) / curv_a.min(curv_b))?;
    let ell = ratio.integrals;
    let e2 = ratio.eccentricity_squared();
    // Factor along the major axis (smaller curvature): (K − E)/(e² K); 1/2 at the circle.
    let eps_major = if e2 > 0.0 {
        ell.k_minus_e / (e2 * ell.k)
    } else {
        0.5
    };
    Ok(if curv_a <= curv_b {
        (eps_major, 1.0 - eps_major)
    } else {
        (1.0 - eps_major, eps_major)
    })
}

/// Hertz m, n, r coefficients of H7 (Johnson Table 4.1 style) for curvatures A, B > 0:
/// a' = m Q^{1/3}, b' = n Q^{1/3}, δ = r (3N/(4E*))^{2/3} (A+B)^{1/3}, Q = 3N/(4E*(A+B)).
pub fn mnr_coefficients(curv_a: f64, curv_b: f64) -> Result<(f64, f64, f64), InputError> {
    check_curvatures(curv_a, curv_b)?;
    let ratio = solve_axis_ratio(curv_a.max(curv_b) / curv_a.min(curv_b))?;
    let g = ratio.g;
    let ell = ratio.integrals;
    let m = (2.0 * ell.e / (PI * g * g)).cbrt();
    let n = (2.0 * ell.e * g / PI).cbrt();
    let r = 2.0 * ell.k / (PI * m);
    Ok((m, n, r))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    /// Oracle 1 material: G = 82 GPa, ν = 0.28 → E = 2G(1 + ν) = 209.92 GPa.
    const E_ORACLE1: f64 = 209.92e9;
    const NU_ORACLE1: f64 = 0.28;

    #[test]
    fn moduli() {
        // E* = G/(1 − ν) (docs/theory.md §2.1) and G = 82 GPa for oracle 1; exact up to rounding.
        let e_star = contact_modulus(E_ORACLE1, NU_ORACLE1);
        let g = shear_modulus(E_ORACLE1, NU_ORACLE1);
        assert!(rel(g, 82e9) < 1e-15);
        assert!(rel(e_star, g / (1.0 - NU_ORACLE1)) < 1e-15);
    }

    #[test]
    fn oracle_contact_fastsim_example() {
        // docs/theory.md §2.7, first check: CONTACT's printed A, B (4 digits) → a = 8.000 mm,
        // b = 4.000 mm (±0.2 %), δ = 0.09267 mm, p0 = 1223.5 MPa (±0.3 %). The tolerances are
        // those of the acceptance criteria; the printed digits alone allow ~1e−4.
        let e_star = contact_modulus(E_ORACLE1, NU_ORACLE1);
        let p = hertz_from_load(0.8464, 2.406, 82_000.0, e_star).unwrap();
        assert!(rel(p.a, 8.000e-3) < 2e-3, "a = {}", p.a);
        assert!(rel(p.b, 4.000e-3) < 2e-3, "b = {}", p.b);
        assert!(rel(p.approach, 0.09267e-3) < 3e-3, "delta = {}", p.approach);
        assert!(rel(p.p0, 1223.5e6) < 3e-3, "p0 = {}", p.p0);
        // The printed digits actually allow a much tighter check (~1e−4, §2.7):
        assert!(rel(p.a, 8.000e-3) < 2e-4 && rel(p.b, 4.0001e-3) < 2e-4);
        assert!(rel(p.approach, 0.09267e-3) < 1e-4);
    }

    #[test]
    fn oracle_wheel_on_crown() {
        // docs/theory.md §2.7, second check: A = 1/920 mm⁻¹, B = 1/600 mm⁻¹, E = 210 GPa, ν = 0.3,
        // N = 100 kN → a = 7.162, b = 5.387 mm, δ = 0.1041 mm, p0 = 1238 MPa. Tolerance: half a
        // unit in the last printed digit (≤ 5e−4 relative).
        let e_star = contact_modulus(210e9, 0.3);
        let p = hertz_from_load(1.0 / 0.920, 1.0 / 0.600, 100e3, e_star).unwrap();
        assert!(rel(p.a, 7.162e-3) < 1e-4, "a = {}", p.a);
        assert!(rel(p.b, 5.387e-3) < 1e-4, "b = {}", p.b);
        assert!(rel(p.approach, 0.1041e-3) < 5e-4, "delta = {}", p.approach);
        assert!(rel(p.p0, 1238e6) < 5e-4, "p0 = {}", p.p0);
        // Oracle 3: ν = 0.28, N = 10 kN, E = 210 GPa → a = 3.338, b = 2.511, δ = 0.02262 mm,
        // p0 = 569.6 MPa.
        let e_star = contact_modulus(210e9, 0.28);
        let p = hertz_from_load(1.0 / 0.920, 1.0 / 0.600, 10e3, e_star).unwrap();
        assert!(rel(p.a, 3.338e-3) < 2e-4, "a = {}", p.a);
        assert!(rel(p.b, 2.511e-3) < 2e-4, "b = {}", p.b);
        assert!(rel(p.approach, 0.02262e-3) < 3e-4, "delta = {}", p.approach);
        assert!(rel(p.p0, 569.6e6) < 1e-4, "p0 = {}", p.p0);
        // With E = 2G(1 + ν) from G = 82 GPa instead (209.92 GPa): p0 = 569.4 MPa.
        let e_star = contact_modulus(209.92e9, 0.28);
        let p = hertz_from_load(1.0 / 0.920, 1.0 / 0.600, 10e3, e_star).unwrap();
        assert!(rel(p.p0, 569.4e6) < 1e-4, "p0 = {}", p.p0);
    }

    #[test]
    fn h6_identity_and_shape_factors() {
        // A a² + B b² = δ holds only at the exact root of H1: checks the solve to 1e−12 across
        // B'/A' = 1 … 1e6 in both orientations.
        let e_star = contact_modulus(210e9, 0.3);
        for &ratio in &[
            1.0,
            1.0 + 1e-9,
            1.001,
            1.5,
            3.0,
            10.0,
            100.0,
            1e3,
            1e4,
            1e5,
            1e6,
        ] {
            for &(ca, cb) in &[(1.0, ratio), (ratio, 1.0)] {
                let p = hertz_from_load(ca, cb, 5e4, e_star).unwrap();
                let lhs = ca * p.a * p.a + cb * p.b * p.b;
                assert!(
                    rel(lhs, p.approach) < 1e-12,
                    "ratio {ratio}: {lhs} vs {}",
                    p.approach
                );
                let (ex, ey) = shape_factors(ca, cb).unwrap();
                assert!((ex + ey - 1.0).abs() < 1e-15);
                assert!(rel(ex, ca * p.a * p.a / p.approach) < 1e-12);
            }
        }
    }

    #[test]
    fn shape_factor_table() {
        // the classical table of the shape factors (4 decimals for ε_x, 3–4 significant digits for
        // a/b): tolerance half a unit in the last printed digit.
        let table = [
            (0.02, 12.071, 0.7445, 2.914),
            (0.05, 6.929, 0.7059, 2.400),
            (0.1, 4.499, 0.6694, 2.025),
            (0.2, 2.890, 0.6256, 1.671),
            (0.5, 1.586, 0.5570, 1.257),
            (1.0, 1.0, 0.5, 1.0),
            (2.0, 0.631, 0.4430, 0.795),
            (5.0, 0.346, 0.3744, 0.599),
            (10.0, 0.222, 0.3306, 0.494),
        ];
        let e_star = contact_modulus(210e9, 0.3);
        for &(a_over_b, ab, eps_x, ratio) in &table {
            let p = hertz_from_load(a_over_b, 1.0, 1e4, e_star).unwrap();
            let (ex, ey) = shape_factors(a_over_b, 1.0).unwrap();
            assert!(
                (p.a / p.b - ab).abs() <= 0.5e-3 + 1e-12,
                "A/B {a_over_b}: a/b {}",
                p.a / p.b
            );
            assert!(
                (ex - eps_x).abs() <= 0.5e-4 + 1e-12,
                "A/B {a_over_b}: eps_x {ex}"
            );
            assert!(
                (ex / ey - ratio).abs() <= 0.5e-3 + 1e-12,
                "A/B {a_over_b}: {}",
                ex / ey
            );
        }
    }

    #[test]
    fn mnr_table() {
        // docs/theory.md §2.5: θ = arccos(|B − A|/(A + B)); B'/A' = (1 + cos θ)/(1 − cos θ).
        // g printed to 5 decimals, m, n, r to 4–5 significant digits: tolerance half a unit in
        // the last printed digit (plus 1e−12 slack for exact ties).
        let table = [
            (90.0, 1.00000, 1.0000, 1.0000, 1.0000),
            (80.0, 0.79155, 1.1278, 0.8927, 0.9932),
            (70.0, 0.62246, 1.2851, 0.7999, 0.9726),
            (60.0, 0.48263, 1.4858, 0.7171, 0.9376),
            (50.0, 0.36524, 1.7541, 0.6407, 0.8867),
            (40.0, 0.26562, 2.1357, 0.5673, 0.8177),
            (30.0, 0.18057, 2.7306, 0.4931, 0.7263),
            (20.0, 0.10801, 3.8160, 0.4121, 0.6038),
            (10.0, 0.04704, 6.6115, 0.3110, 0.4280),
            (5.0, 0.02119, 11.238, 0.2381, 0.2969),
        ];
        for &(theta_deg, g, m, n, r) in &table {
            let c = f64::to_radians(theta_deg).cos();
            let ratio = (1.0 + c) / (1.0 - c);
            let sol = solve_axis_ratio(ratio).unwrap();
            assert!(
                (sol.g - g).abs() <= 0.5e-5 + 1e-12,
                "θ {theta_deg}: g {}",
                sol.g
            );
            let (mm, nn, rr) = mnr_coefficients(1.0, ratio).unwrap();
            let tol = |v: f64| if v >= 10.0 { 0.5e-3 } else { 0.5e-4 } + 1e-12;
            assert!((mm - m).abs() <= tol(m), "θ {theta_deg}: m {mm}");
            assert!((nn - n).abs() <= tol(n), "θ {theta_deg}: n {nn}");
            assert!((rr - r).abs() <= tol(r), "θ {theta_deg}: r {rr}");
        }
    }

    #[test]
    fn circle_limit() {
        // A = B: g = 1, K = E = π/2, so H2 gives a³ = 3N/(4E*(A+B)) and H3 δ = (A+B)a²;
        // exact to rounding.
        let e_star = contact_modulus(210e9, 0.3);
        let (n, c) = (1e4, 2.0);
        let p = hertz_from_load(c, c, n, e_star).unwrap();
        let a = (3.0 * n / (4.0 * e_star * 2.0 * c)).cbrt();
        assert!(rel(p.a, a) < 1e-14 && rel(p.b, a) < 1e-14);
        assert!(rel(p.approach, 2.0 * c * a * a) < 1e-14);
        assert_eq!(shape_factors(c, c).unwrap(), (0.5, 0.5));
        // Nearly circular: continuous towards the circle (relative change O(1e−9)).
        let q = hertz_from_load(c, c * (1.0 + 1e-9), n, e_star).unwrap();
        assert!(rel(q.a, a) < 1e-8 && rel(q.b, a) < 1e-8);
    }

    #[test]
    fn swapping_a_and_b_swaps_axes() {
        let e_star = contact_modulus(210e9, 0.3);
        let p = hertz_from_load(0.8464, 2.406, 82e3, e_star).unwrap();
        let q = hertz_from_load(2.406, 0.8464, 82e3, e_star).unwrap();
        assert!(rel(p.a, q.b) < 1e-15 && rel(p.b, q.a) < 1e-15);
        assert!(rel(p.approach, q.approach) < 1e-15 && rel(p.p0, q.p0) < 1e-15);
    }

    #[test]
    fn load_scales_with_approach_to_three_halves() {
        // N ∝ δ^{3/2} (H5): doubling δ multiplies N by 2^{3/2}, to rounding.
        let e_star = contact_modulus(210e9, 0.3);
        let p1 = hertz_from_approach(0.8464, 2.406, 5e-5, e_star).unwrap();
        let p2 = hertz_from_approach(0.8464, 2.406, 1e-4, e_star).unwrap();
        assert!(rel(p2.normal_force / p1.normal_force, 2f64.powf(1.5)) < 1e-13);
    }

    #[test]
    fn approach_inverts_load() {
        // H5 inverts H2–H3 (same g, same integrals): round trip to rounding, across shapes.
        let e_star = contact_modulus(210e9, 0.28);
        for &(ca, cb) in &[
            (0.8464, 2.406),
            (2.406, 0.8464),
            (1.0, 1.0),
            (1.0, 1e5),
            (3e4, 0.3),
        ] {
            let p = hertz_from_load(ca, cb, 82e3, e_star).unwrap();
            let q = hertz_from_approach(ca, cb, p.approach, e_star).unwrap();
            assert!(
                rel(q.normal_force, 82e3) < 1e-13,
                "{ca},{cb}: {}",
                q.normal_force
            );
            assert!(rel(q.a, p.a) < 1e-13 && rel(q.b, p.b) < 1e-13 && rel(q.p0, p.p0) < 1e-13);
        }
    }

    #[test]
    fn peak_pressure_relations() {
        // The local-peak form of §2.4 for a ≥ b, p0 = E* A a² e²/(b (K − E)), must equal H4's
        // p0 = 3N/(2πab) (an exact identity; tolerance = rounding of a dozen operations).
        let e_star = contact_modulus(210e9, 0.3);
        let p = hertz_from_load(0.8464, 2.406, 82e3, e_star).unwrap();
        let sol = solve_axis_ratio(2.406 / 0.8464).unwrap();
        let e2 = sol.eccentricity_squared();
        let p0 = e_star * 0.8464 * p.a * p.a * e2 / (p.b * sol.integrals.k_minus_e);
        assert!(rel(p0, p.p0) < 1e-12);
        assert!(rel(p.pressure_at(0.0, 0.0), p.p0) < 1e-15);
        assert_eq!(p.pressure_at(p.a, 0.0), 0.0);
        assert!(rel(p.area(), PI * p.a * p.b) < 1e-15);
    }

    #[test]
    fn zero_load_and_invalid_inputs() {
        let e_star = contact_modulus(210e9, 0.3);
        assert_eq!(
            hertz_from_load(1.0, 2.0, 0.0, e_star).unwrap(),
            HertzPatch::default()
        );
        assert_eq!(
            hertz_from_approach(1.0, 2.0, 0.0, e_star).unwrap(),
            HertzPatch::default()
        );
        assert_eq!(
            hertz_from_load(0.0, 2.0, 1.0, e_star).unwrap_err().name,
            "A"
        );
        assert_eq!(
            hertz_from_load(-1.0, 2.0, 1.0, e_star).unwrap_err().name,
            "A"
        );
        assert_eq!(
            hertz_from_load(1.0, f64::NAN, 1.0, e_star)
                .unwrap_err()
                .name,
            "B"
        );
        assert_eq!(
            hertz_from_load(1.0, f64::INFINITY, 1.0, e_star)
                .unwrap_err()
                .name,
            "B"
        );
        assert_eq!(
            hertz_from_load(1.0, 2.0, -1.0, e_star).unwrap_err().name,
            "N"
        );
        assert_eq!(
            hertz_from_load(1.0, 2.0, f64::NAN, e_star)
                .unwrap_err()
                .name,
            "N"
        );
        assert_eq!(hertz_from_load(1.0, 2.0, 1.0, 0.0).unwrap_err().name, "E*");
        assert_eq!(
            hertz_from_approach(1.0, 2.0, -1e-6, e_star)
                .unwrap_err()
                .name,
            "delta"
        );
        assert_eq!(shape_factors(1.0, -2.0).unwrap_err().name, "B");
        // Ratio beyond the supported range: an error, not NaN.
        assert!(hertz_from_load(1.0, 1e13, 1.0, e_star).is_err());
    }

    #[test]
    fn extreme_ratios_are_finite_and_monotone() {
        let e_star = contact_modulus(210e9, 0.3);
        let mut last_g = 1.0;
        for k in 0..=24 {
            let ratio = 10f64.powf(k as f64 * 0.5);
            let sol = solve_axis_ratio(ratio).unwrap();
            assert!(sol.g > 0.0 && sol.g <= last_g, "ratio {ratio}: g {}", sol.g);
            last_g = sol.g;
            let p = hertz_from_load(1.0, ratio, 1e3, e_star).unwrap();
            assert!(p.a.is_finite() && p.b.is_finite() && p.approach > 0.0 && p.p0 > 0.0);
        }
    }
}
