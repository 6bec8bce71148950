//! Kalker's creep coefficients C11, C22, C23 of the linear theory of rolling contact.
//!
//! Papers: J.J. Kalker, *Three-dimensional elastic bodies in rolling contact* (Kluwer, 1990),
//! Table E.3 (the values CONTACT uses); asymptotes from Kalker (1967/1990) as coded in CONTACT.
//! Equations as labelled in docs/theory.md §3:
//!
//! * **Table E.3** (§3.2), rows g = 0.1 … 1.0 for a ≤ b (g = a/b) and for a ≥ b (g = b/a), columns
//!   ν = 0, 0.25, 0.5. The two typos of public ports are corrected: C23(a/b = 0.8, ν = 0.25) = 1.25
//!   and C11(b/a = 0.9, ν = 0) = 3.51 (tests `typo_cells` and `table_columns_are_smooth`).
//! * **Interpolation** (§3.3): linear in g between rows, then **K1**, quadratic Lagrange
//!   interpolation of 1/C through ν = 0, 0.25, 0.5.
//! * **K2** (a ≪ b) and **K3** (a ≫ b) asymptotes for g < 0.1 (§3.4).
//!
//! Linear theory (docs/conventions.md, docs/theory.md §3.1): Fx = −G c² C11 ξ, Fy = −G c² C22 η − G
//! c³ C23 φ, c² = ab; C32 = −C23.
//!
//! **Decision on the jump at g = 0.1 (our choice, docs/theory.md §3.4): blend.** The raw asymptotes
//! differ from the table at g = 0.1 by up to 3 % (ν = 0) … 6 % (ν = 0.5), which would show as a
//! force jump when a patch passes 10:1 and upset the step-size control of the co-simulation master.
//! Below g = 0.1 this module therefore uses
//!
//! ```text
//! C(g, ν) = C_asym(g, ν) · [1 + (ρ(ν) − 1) · g/0.1],   ρ(ν) = C_table(0.1, ν) / C_asym(0.1, ν)
//! ```
//!
//! i.e. the table value at g = 0.1 (continuity, C⁰) fading linearly into the pure asymptote as
//! g → 0 (where the asymptote is exact). The slope in g stays discontinuous at 0.1, as it is at
//! every table row. Tested in `blend_is_continuous_at_one_tenth` and `asymptotic_behaviour`.
//!
//! Known limits: ν ∈ [0, 0.5]; the ratio a/b must lie in [1e−9, 1e9] (beyond that the asymptotes
//! overflow nothing but the patch is a line contact outside Hertz's range anyway). Table values
//! have three significant digits (±0.5 % near g = 1), so forces from them carry that uncertainty.
//! C33 (linear spin moment, §3.5) is not provided.

use crate::error::{require_positive, InputError};
use std::f64::consts::PI;

/// Kalker's linear creep coefficients [-]. `Default` is all-zero (used for "no contact").
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CreepCoefficients {
    /// Longitudinal C11 (ξ → Fx).
    pub c11: f64,
    /// Lateral C22 (η → Fy).
    pub c22: f64,
    /// Lateral/spin coupling C23 = −C32 (φ → Fy, η → Mz).
    pub c23: f64,
}

/// One row of Table E.3: coefficient values at ν = 0, 0.25, 0.5.
#[derive(Debug, Clone, Copy)]
struct TableRow {
    c11: [f64; 3],
    c22: [f64; 3],
    c23: [f64; 3],
}

const fn row(c11: [f64; 3], c22: [f64; 3], c23: [f64; 3]) -> TableRow {
    TableRow { c11, c22, c23 }
}

/// Spacing of the table rows in g [-].
const TABLE_STEP: f64 = 0.1;
/// Smallest tabulated g; below it the asymptotes K2/K3 (blended) apply.
const TABLE_MIN_G: f64 = 0.1;
/// Smallest accepted minor/major ratio (see module header).
const MIN_RATIO: f64 = 1e-9;

/// Table E.3, a ≤ b, rows g = a/b = 0.1, 0.2, …, 1.0 (docs/theory.md §3.2). (The cell value 3.14 is
/// a creep coefficient, not π.)
#[allow(clippy::approx_constant)]
const TABLE_A_LE_B: [TableRow; 10] = [
    row(
        [2.51, 3.31, 4.85],
        [2.51, 2.52, 2.53],
        [0.334, 0.473, 0.731],
    ),
    row(
        [2.59, 3.37, 4.81],
        [2.59, 2.63, 2.66],
        [0.483, 0.603, 0.809],
    ),
    row(
        [2.68, 3.44, 4.80],
        [2.68, 2.75, 2.81],
        [0.607, 0.715, 0.889],
    ),
    row(
        [2.78, 3.53, 4.82],
        [2.78, 2.88, 2.98],
        [0.720, 0.823, 0.977],
    ),
    row([2.88, 3.62, 4.83], [2.88, 3.01, 3.14], [0.827, 0.929, 1.07]),
    row([2.98, 3.72, 4.91], [2.98, 3.14, 3.31], [0.930, 1.03, 1.18]),
    row([3.09, 3.81, 4.97], [3.09, 3.28, 3.48], [1.03, 1.14, 1.29]),
    // C23(ν = 0.25) = 1.25: public ports carry the typo 1.15.
    row([3.19, 3.91, 5.05], [3.19, 3.41, 3.65], [1.13, 1.25, 1.40]),
    row([3.29, 4.01, 5.12], [3.29, 3.54, 3.82], [1.23, 1.36, 1.51]),
    row([3.40, 4.12, 5.20], [3.40, 3.67, 3.98], [1.33, 1.47, 1.63]),
];

/// Table E.3, a ≥ b, rows g = b/a = 0.1, 0.2, …, 1.0 (ascending g; Kalker's table lists them
/// descending). The g = 1 row is the same circle row as above.
const TABLE_A_GE_B: [TableRow; 10] = [
    row([10.7, 11.7, 12.9], [10.7, 12.8, 16.0], [12.2, 14.6, 18.0]),
    row([6.96, 7.78, 8.82], [6.96, 8.14, 9.79], [5.72, 6.63, 7.89]),
    row([5.57, 6.34, 7.34], [5.57, 6.40, 7.51], [3.79, 4.32, 5.01]),
    row([4.84, 5.57, 6.57], [4.84, 5.48, 6.31], [2.88, 3.24, 3.70]),
    row([4.37, 5.10, 6.11], [4.37, 4.90, 5.56], [2.35, 2.62, 2.96]),
    row([4.06, 4.78, 5.80], [4.06, 4.50, 5.04], [2.01, 2.23, 2.50]),
    row([3.82, 4.54, 5.58], [3.82, 4.21, 4.67], [1.76, 1.95, 2.18]),
    row([3.65, 4.36, 5.42], [3.65, 3.99, 4.39], [1.58, 1.75, 1.94]),
    // C11(ν = 0) = 3.51: public ports carry the typo 3.61.
    row([3.51, 4.22, 5.30], [3.51, 3.81, 4.16], [1.44, 1.59, 1.77]),
    row([3.40, 4.12, 5.20], [3.40, 3.67, 3.98], [1.33, 1.47, 1.63]),
];

/// The Poisson ratios of the table columns.
const TABLE_NU: [f64; 3] = [0.0, 0.25, 0.5];

/// K1 weights of the quadratic Lagrange interpolation through the ν nodes 0, 0.25, 0.5:
/// w0 = (ν − 0.25)(ν − 0.5)/0.125, w1 = −ν(ν − 0.5)/0.0625, w2 = ν(ν − 0.25)/0.125.
fn k1_weights(nu: f64) -> [f64; 3] {
    let [n0, n1, n2] = TABLE_NU;
    [
        (nu - n1) * (nu - n2) / ((n0 - n1) * (n0 - n2)),
        (nu - n0) * (nu - n2) / ((n1 - n0) * (n1 - n2)),
        (nu - n0) * (nu - n1) / ((n2 - n0) * (n2 - n1)),
    ]
}

/// K1: 1/C(ν) = Σ w_i / C(ν_i).
fn interpolate_in_nu(values: [f64; 3], nu: f64) -> f64 {
    let w = k1_weights(nu);
    1.0 / (w[0] / values[0] + w[1] / values[1] + w[2] / values[2])
}

/// Linear interpolation between table rows at g ∈ [0.1, 1]; returns the three ν columns.
fn interpolate_rows(table: &[TableRow; 10], g: f64) -> TableRow {
    let pos = ((g - TABLE_MIN_G) / TABLE_STEP).clamp(0.0, 9.0);
    // `as usize` floors a non-negative value (and saturates below 0) without a call to
    // libm's floor, which baseline x86-64 (no SSE4.1 rounding) would need.
    let i = (pos as usize).min(8);
    let t = pos - i as f64;
    let (lo, hi) = (&table[i], &table[i + 1]);
    let lerp = |a: [f64; 3], b: [f64; 3]| {
        [
            a[0] + t * (b[0] - a[0]),
            a[1] + t * (b[1] - a[1]),
            a[2] + t * (b[2] - a[2]),
        ]
    };
    row(
        lerp(lo.c11, hi.c11),
        lerp(lo.c22, hi.c22),
        lerp(lo.c23, hi.c23),
    )
}

/// Table E.3 + K1 for g ∈ [0.1, 1]; `a_le_b` selects the half of the table.
fn tabulated(g: f64, a_le_b: bool, nu: f64) -> CreepCoefficients {
    let table = if a_le_b { &TABLE_A_LE_B } else { &TABLE_A_GE_B };
    let r = interpolate_rows(table, g);
    CreepCoefficients {
        c11: interpolate_in_nu(r.c11, nu),
        c22: interpolate_in_nu(r.c22, nu),
        c23: interpolate_in_nu(r.c23, nu),
    }
}

/// K2: asymptotes for a ≪ b, g = a/b → 0 (docs/theory.md §3.4).
pub fn asymptote_narrow(g: f64, nu: f64) -> CreepCoefficients {
    CreepCoefficients {
        c11: PI * PI / (4.0 * (1.0 - nu)),
        c22: PI * PI / 4.0,
        c23: PI * g.sqrt() / (3.0 * (1.0 - nu)) * (1.0 + nu * ((16.0 / g).ln() - 5.0)),
    }
}

/// K3: asymptotes for a ≫ b, g = b/a → 0, Λ = ln(16/g²) (docs/theory.md §3.4).
pub fn asymptote_long(g: f64, nu: f64) -> CreepCoefficients {
    let lambda = (16.0 / (g * g)).ln();
    // 3 − ln 4 appears in Kalker's expansion of both C11 and C22.
    let k = 3.0 - 4.0_f64.ln();
    let d11 = lambda - 2.0 * nu;
    let d22 = (1.0 - nu) * lambda + 2.0 * nu;
    CreepCoefficients {
        c11: 2.0 * PI / (g * d11) * (1.0 + k / d11),
        c22: 2.0 * PI / (g * d22) * (1.0 + (1.0 - nu) * k / d22),
        c23: 2.0 * PI / (3.0 * g.powf(1.5) * ((1.0 - nu) * lambda - 2.0 + 4.0 * nu)),
    }
}

/// Blended asymptote for g < 0.1 (see the module header): continuous with the table at 0.1.
fn blended_asymptote(g: f64, a_le_b: bool, nu: f64) -> CreepCoefficients {
    let asym = |g| {
        if a_le_b {
            asymptote_narrow(g, nu)
        } else {
            asymptote_long(g, nu)
        }
    };
    let at_edge = asym(TABLE_MIN_G);
    let table_edge = tabulated(TABLE_MIN_G, a_le_b, nu);
    let here = asym(g);
    let fade = g / TABLE_MIN_G;
    let blend = |c: f64, table: f64, edge: f64| c * (1.0 + (table / edge - 1.0) * fade);
    CreepCoefficients {
        c11: blend(here.c11, table_edge.c11, at_edge.c11),
        c22: blend(here.c22, table_edge.c22, at_edge.c22),
        c23: blend(here.c23, table_edge.c23, at_edge.c23),
    }
}

/// Kalker's C11, C22, C23 for a contact ellipse with semi-axis `a` [m] along the rolling direction,
/// `b` [m] lateral, and Poisson ratio `nu` ∈ [0, 0.5] [-].
///
/// Errors name "a", "b" (must be finite and > 0), "nu" and "a/b" (ratio outside [1e−9, 1e9]).
pub fn creep_coefficients(a: f64, b: f64, nu: f64) -> Result<CreepCoefficients, InputError> {
    require_positive("a", a)?;
    require_positive("b", b)?;
    if !(0.0..=0.5).contains(&nu) {
        return Err(InputError::new("nu", nu, "[0, 0.5]"));
    }
    let a_le_b = a <= b;
    let g = if a_le_b { a / b } else { b / a };
    // a, b are finite and positive, so g is a positive number (possibly underflowed to 0).
    if g < MIN_RATIO {
        return Err(InputError::new("a/b", a / b, "[1e-9, 1e9]"));
    }
    Ok(if g >= TABLE_MIN_G {
        tabulated(g, a_le_b, nu)
    } else {
        blended_asymptote(g, a_le_b, nu)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn column(table: &[TableRow; 10], which: usize, inu: usize) -> [f64; 10] {
        let mut out = [0.0; 10];
        for (o, r) in out.iter_mut().zip(table.iter()) {
            *o = [r.c11, r.c22, r.c23][which][inu];
        }
        out
    }

    /// The 19 distinct rows of one column ordered by a/b (0.1 … 1 … 10) with x = ln(a/b).
    fn full_column(which: usize, inu: usize) -> ([f64; 19], [f64; 19]) {
        let le = column(&TABLE_A_LE_B, which, inu);
        let ge = column(&TABLE_A_GE_B, which, inu);
        let mut x = [0.0; 19];
        let mut c = [0.0; 19];
        for i in 0..10 {
            x[i] = (TABLE_MIN_G + TABLE_STEP * i as f64).ln();
            c[i] = le[i];
        }
        for j in 0..9 {
            // b/a rows 0.9 … 0.1 → a/b = 1/0.9 … 10.
            let g = TABLE_MIN_G + TABLE_STEP * (8 - j) as f64;
            x[10 + j] = -g.ln();
            c[10 + j] = ge[8 - j];
        }
        (x, c)
    }

    /// Largest |d²(ln C)/d(ln a/b)²| by three-point divided differences along a column.
    fn max_log_curvature(x: &[f64; 19], c: &[f64; 19]) -> f64 {
        let mut worst = 0.0_f64;
        for i in 1..18 {
            let (f0, f1, f2) = (c[i - 1].ln(), c[i].ln(), c[i + 1].ln());
            let d = 2.0 * ((f2 - f1) / (x[i + 1] - x[i]) - (f1 - f0) / (x[i] - x[i - 1]))
                / (x[i + 1] - x[i - 1]);
            worst = worst.max(d.abs());
        }
        worst
    }

    /// Smoothness bound. The genuine curvature of ln C versus ln(a/b) is ≤ 0.45 over the table;
    /// rounding to three digits adds up to 4 · 0.0015/h² ≈ 0.54 near g = 1 (relative rounding
    /// ≤ 0.005/3.3, spacing h ≈ 0.105), so 1.2 is safe for a clean column. Each known typo
    /// produces ≥ 1.97 (measured: 10.8 for C23, 4.3 for C11).
    const SMOOTHNESS_BOUND: f64 = 1.2;

    #[test]
    fn table_columns_are_smooth() {
        for which in 0..3 {
            for inu in 0..3 {
                let (x, c) = full_column(which, inu);
                let k = max_log_curvature(&x, &c);
                assert!(
                    k < SMOOTHNESS_BOUND,
                    "coefficient {which}, ν column {inu}: {k}"
                );
            }
        }
    }

    #[test]
    fn smoothness_test_catches_the_known_typos() {
        // The same check applied to the erroneous public values must fail.
        let (x, mut c) = full_column(2, 1);
        c[7] = 1.15; // C23(a/b = 0.8, ν = 0.25)
        assert!(max_log_curvature(&x, &c) > SMOOTHNESS_BOUND);
        let (x, mut c) = full_column(0, 0);
        c[10] = 3.61; // C11(b/a = 0.9, ν = 0)
        assert!(max_log_curvature(&x, &c) > SMOOTHNESS_BOUND);
    }

    #[test]
    fn typo_cells() {
        let c = creep_coefficients(0.8, 1.0, 0.25).unwrap();
        assert_eq!(c.c23, 1.25);
        let c = creep_coefficients(1.0, 0.9, 0.0).unwrap();
        assert!((c.c11 - 3.51).abs() < 1e-12);
    }

    #[test]
    fn reproduces_table_points() {
        // At table rows and ν nodes the interpolation returns the table value (weights 1, 0, 0
        // exactly; linear interpolation with t = 0 or 1 up to rounding of g).
        for (half, table) in [(true, &TABLE_A_LE_B), (false, &TABLE_A_GE_B)] {
            for (i, r) in table.iter().enumerate() {
                let g = TABLE_MIN_G + TABLE_STEP * i as f64;
                let (a, b) = if half { (g, 1.0) } else { (1.0, g) };
                for (inu, &nu) in TABLE_NU.iter().enumerate() {
                    let c = creep_coefficients(a, b, nu).unwrap();
                    assert!((c.c11 - r.c11[inu]).abs() < 1e-12, "{half} {g} {nu}");
                    assert!((c.c22 - r.c22[inu]).abs() < 1e-12, "{half} {g} {nu}");
                    assert!((c.c23 - r.c23[inu]).abs() < 1e-12, "{half} {g} {nu}");
                }
            }
        }
    }

    #[test]
    fn k1_weights_match_the_lagrange_form() {
        // docs/theory.md §3.3 writes the weights with the factors 8 and −16; the same values.
        for &nu in &[0.0, 0.1, 0.25, 0.28, 0.4, 0.5] {
            let w = k1_weights(nu);
            assert!((w[0] - (nu - 0.25) * (nu - 0.5) / 0.125).abs() < 1e-15);
            assert!((w[1] + nu * (nu - 0.5) / 0.0625).abs() < 1e-15);
            assert!((w[2] - nu * (nu - 0.25) / 0.125).abs() < 1e-15);
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn k1_check_value() {
        // docs/theory.md §3.3: a/b = 2, ν = 0.28 → 5.2037, 4.9715, 2.6566 (4 decimals printed).
        let c = creep_coefficients(8e-3, 4e-3, 0.28).unwrap();
        assert!((c.c11 - 5.2037).abs() < 0.5e-4, "{}", c.c11);
        assert!((c.c22 - 4.9715).abs() < 0.5e-4, "{}", c.c22);
        assert!((c.c23 - 2.6566).abs() < 0.5e-4, "{}", c.c23);
    }

    #[test]
    fn nu_zero_gives_c11_equal_c22() {
        // At ν = 0 the longitudinal and lateral problems coincide: C11 = C22 in the table and in
        // both asymptotes (exact).
        for &ab in &[0.001, 0.05, 0.1, 0.35, 1.0, 2.5, 10.0, 40.0, 1e4] {
            let c = creep_coefficients(ab, 1.0, 0.0).unwrap();
            assert!((c.c11 - c.c22).abs() <= 1e-12 * c.c11, "a/b {ab}: {c:?}");
        }
    }

    #[test]
    fn documented_jump_of_raw_asymptotes() {
        // docs/theory.md §3.4: unblended asymptotes at g = 0.1 give C23(a/b = 0.1, ν = 0.5) = 0.687
        // (table 0.731) and C11(b/a = 0.1, ν = 0.5) = 12.34 (table 12.9). Checks K2/K3 as coded.
        let n = asymptote_narrow(0.1, 0.5);
        assert!((n.c23 - 0.687).abs() < 0.5e-3, "{}", n.c23);
        let l = asymptote_long(0.1, 0.5);
        assert!((l.c11 - 12.34).abs() < 0.5e-2, "{}", l.c11);
        // ≤ 3 % at ν = 0 for all three coefficients and both sides.
        for (asym, r) in [
            (asymptote_narrow(0.1, 0.0), &TABLE_A_LE_B[0]),
            (asymptote_long(0.1, 0.0), &TABLE_A_GE_B[0]),
        ] {
            for (x, t) in [
                (asym.c11, r.c11[0]),
                (asym.c22, r.c22[0]),
                (asym.c23, r.c23[0]),
            ] {
                assert!(((x - t) / t).abs() < 0.03, "{x} vs {t}");
            }
        }
    }

    #[test]
    fn blend_is_continuous_at_one_tenth() {
        // Across g = 0.1 the coefficients may change only by the table slope × 2e−9 (≪ 1e−6).
        for &nu in &[0.0, 0.1, 0.25, 0.28, 0.4, 0.5] {
            for a_le_b in [true, false] {
                let at = |g: f64| {
                    if a_le_b {
                        creep_coefficients(g, 1.0, nu).unwrap()
                    } else {
                        creep_coefficients(1.0, g, nu).unwrap()
                    }
                };
                let (lo, hi) = (at(0.1 - 1e-9), at(0.1 + 1e-9));
                for (x, y) in [(lo.c11, hi.c11), (lo.c22, hi.c22), (lo.c23, hi.c23)] {
                    assert!(
                        ((x - y) / y).abs() < 1e-6,
                        "ν {nu}, a≤b {a_le_b}: {x} vs {y}"
                    );
                }
            }
        }
    }

    #[test]
    fn asymptotic_behaviour() {
        // As g → 0 the blend fades: C/C_asym − 1 = (ρ − 1) g/0.1 with |ρ − 1| ≤ 6.4 %
        // (C23, ν = 0.5: 0.731/0.687), so at g = 1e−4 the deviation is ≤ 6.4e−5 < 1e−4.
        for &nu in &[0.0, 0.25, 0.5] {
            let g = 1e-4;
            let c = creep_coefficients(g, 1.0, nu).unwrap();
            let k2 = asymptote_narrow(g, nu);
            let l = creep_coefficients(1.0, g, nu).unwrap();
            let k3 = asymptote_long(g, nu);
            for (x, y) in [
                (c.c11, k2.c11),
                (c.c22, k2.c22),
                (c.c23, k2.c23),
                (l.c11, k3.c11),
                (l.c22, k3.c22),
                (l.c23, k3.c23),
            ] {
                assert!(((x - y) / y).abs() < 1e-4, "ν {nu}: {x} vs {y}");
            }
        }
        // Physical trends: a ≪ b → C11, C22 finite, C23 → 0 like √g; a ≫ b → all grow.
        let narrow = creep_coefficients(1e-6, 1.0, 0.28).unwrap();
        assert!(narrow.c23 < 0.01 && (narrow.c22 - PI * PI / 4.0).abs() < 1e-3);
        let long = creep_coefficients(1.0, 1e-3, 0.28).unwrap();
        assert!(long.c11 > 100.0 && long.c22 > 100.0 && long.c23 > 1000.0);
    }

    #[test]
    fn monotone_in_a_over_b_and_finite() {
        // C22 and C23 grow with a/b throughout (table, blend and asymptotes); C11 too except the
        // genuine dip of the ν = 0.5 column for a/b ≤ 0.4 (docs/theory.md §3.2), so C11 is checked
        // for ν ≤ 0.25.
        for &nu in &[0.0, 0.25, 0.5] {
            let mut prev: Option<CreepCoefficients> = None;
            for k in 0..=400 {
                let ab = 10f64.powf(-4.0 + 8.0 * k as f64 / 400.0);
                let c = creep_coefficients(ab, 1.0, nu).unwrap();
                assert!(c.c11.is_finite() && c.c22.is_finite() && c.c23.is_finite());
                if let Some(p) = prev {
                    assert!(c.c22 >= p.c22 - 1e-12 && c.c23 >= p.c23 - 1e-12, "ab {ab}");
                    if nu <= 0.25 {
                        assert!(c.c11 >= p.c11 - 1e-12, "ab {ab}");
                    }
                }
                prev = Some(c);
            }
        }
    }

    #[test]
    fn invalid_inputs() {
        assert_eq!(creep_coefficients(1.0, 1.0, -0.01).unwrap_err().name, "nu");
        assert_eq!(creep_coefficients(1.0, 1.0, 0.51).unwrap_err().name, "nu");
        assert_eq!(
            creep_coefficients(1.0, 1.0, f64::NAN).unwrap_err().name,
            "nu"
        );
        assert_eq!(creep_coefficients(0.0, 1.0, 0.3).unwrap_err().name, "a");
        assert_eq!(
            creep_coefficients(1.0, f64::INFINITY, 0.3)
                .unwrap_err()
                .name,
            "b"
        );
        assert_eq!(creep_coefficients(1e-10, 1.0, 0.3).unwrap_err().name, "a/b");
        assert!(creep_coefficients(1.0, 1.0, 0.0).is_ok());
        assert!(creep_coefficients(1.0, 1.0, 0.5).is_ok());
    }
}
