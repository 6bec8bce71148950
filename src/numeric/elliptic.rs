//! Complete elliptic integrals of the first and second kind by the arithmetic–geometric mean.
//!
//! Implements docs/theory.md §9.1 (used by Hertz H1–H7, §2): with the complementary modulus
//! k' = √(1 − k²) start a₀ = 1, b₀ = k', c₀ = k and iterate
//! a ← (a + b)/2, b ← √(ab), c ← (a − b)/2 while accumulating S = Σ_{n≥0} 2^{n−1} c_n².
//! Then K = π/(2a_∞), E = K(1 − S) and **K − E = K·S**, which has no cancellation near the
//! circle (k → 0) where K − E = O(k²). Classical references: Abramowitz & Stegun §17.6;
//! King (1924), "On the direct numerical calculation of elliptic functions and integrals".
//!
//! Known limits: k' must lie in (0, 1]. k' → 0 (k → 1) is fine numerically down to the
//! smallest normal f64 (K grows like ln(4/k')), but K is infinite at k' = 0. Relative accuracy is
//! a few ulp.

use std::f64::consts::FRAC_PI_2;

/// Complete elliptic integrals K(k), E(k) and their difference K − E (computed without
/// cancellation), all dimensionless.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompleteElliptic {
    /// K(k), complete elliptic integral of the first kind.
    pub k: f64,
    /// E(k), complete elliptic integral of the second kind.
    pub e: f64,
    /// K(k) − E(k), accurate also for k → 0.
    pub k_minus_e: f64,
}

/// Hard cap on AGM iterations. Quadratic convergence needs 5–6 for k ≤ 0.999 and about
/// log₂(ln(4/k')) + 5 ≈ 15 at k' = 1e−300, so 64 is never reached in practice.
const MAX_AGM_ITERATIONS: usize = 64;

/// Stop when c_n < `AGM_TOLERANCE`·a_n (docs/theory.md §9.1): c_n² then lies below 1e−32 of the
/// accumulated S, far under f64 resolution.
const AGM_TOLERANCE: f64 = 1e-16;

/// K, E and K − E from the complementary modulus k' = √(1 − k²) ∈ (0, 1].
///
/// Hertz (docs/theory.md §2.2) gives k' = g = b'/a' directly, which is why this is the argument.
/// Values outside (0, 1] are a caller error (checked in debug builds); the Hertz code never
/// passes them.
pub fn complete_elliptic_from_complementary(k_prime: f64) -> CompleteElliptic {
    debug_assert!(
        k_prime > 0.0 && k_prime <= 1.0,
        "complementary modulus k' = {k_prime} outside (0, 1]"
    );
    // k = √((1 − k')(1 + k')) avoids the cancellation of 1 − k'² for k' near 1.
    let modulus = ((1.0 - k_prime) * (1.0 + k_prime)).sqrt();
    let mut a = 1.0_f64;
    let mut b = k_prime;
    let mut c = modulus;
    // n = 0 term: 2^{−1} c₀².
    let mut weight = 0.5_f64;
    let mut sum = weight * c * c;
    for _ in 0..MAX_AGM_ITERATIONS {
        if c <= AGM_TOLERANCE * a {
            break;
        }
        let a_next = 0.5 * (a + b);
        let b_next = (a * b).sqrt();
        c = 0.5 * (a - b);
        a = a_next;
        b = b_next;
        weight *= 2.0;
        sum += weight * c * c;
    }
    let k = FRAC_PI_2 / a;
    let k_minus_e = k * sum;
    CompleteElliptic {
        k,
        e: k - k_minus_e,
        k_minus_e,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative difference; reference values carry 16 significant digits.
    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    #[test]
    fn circle_limit_is_pi_over_two() {
        let r = complete_elliptic_from_complementary(1.0);
        assert_eq!(r.k, FRAC_PI_2);
        assert_eq!(r.e, FRAC_PI_2);
        assert_eq!(r.k_minus_e, 0.0);
    }

    #[test]
    fn parameter_one_half() {
        // k² = 0.5 → k' = √0.5. Reference values (A&S Table 17.1 / SciPy ellipk, ellipe):
        // K = 1.854074677301372, E = 1.350643881047675. Tolerance 4e−15: a few ulp, the
        // accuracy the AGM reaches in f64.
        let r = complete_elliptic_from_complementary(0.5_f64.sqrt());
        assert!(rel(r.k, 1.854_074_677_301_372) < 4e-15, "K = {}", r.k);
        assert!(rel(r.e, 1.350_643_881_047_675) < 4e-15, "E = {}", r.e);
        assert!(rel(r.k_minus_e, 1.854_074_677_301_372 - 1.350_643_881_047_675) < 1e-14);
    }

    #[test]
    fn other_known_values() {
        // SciPy: ellipk(m), ellipe(m) with m = k².
        // m = 0.9: K = 2.5780921133481733, E = 1.1047747327040733.
        let r = complete_elliptic_from_complementary(0.1_f64.sqrt());
        assert!(rel(r.k, 2.578_092_113_348_173_3) < 4e-15);
        assert!(rel(r.e, 1.104_774_732_704_073_3) < 4e-15);
        // m = 0.1: K = 1.6124413487202192, E = 1.5307576368977633.
        let r = complete_elliptic_from_complementary(0.9_f64.sqrt());
        assert!(rel(r.k, 1.612_441_348_720_219_2) < 4e-15);
        assert!(rel(r.e, 1.530_757_636_897_763_3) < 4e-15);
    }

    #[test]
    fn k_minus_e_without_cancellation_near_circle() {
        // Series: K − E = (π/4) m (1 + 3m/8 + …) for m = k² → 0. At m ≈ 1e−12 the naive
        // difference K − E would carry a relative error of ~1e−4; the AGM form must be within
        // the next series term (3m/8 ≈ 4e−13) plus rounding.
        // k' = 1 − 5e−13 is exact enough; m = (1 − k')(1 + k') then is exact to rounding
        // (1 − k' is exact by Sterbenz' lemma).
        let kp = 1.0 - 5e-13_f64;
        let m = (1.0 - kp) * (1.0 + kp);
        let r = complete_elliptic_from_complementary(kp);
        let series = std::f64::consts::FRAC_PI_4 * m * (1.0 + 3.0 * m / 8.0);
        assert!(
            rel(r.k_minus_e, series) < 1e-9,
            "{} vs {}",
            r.k_minus_e,
            series
        );
    }

    #[test]
    fn long_ellipse_logarithmic_limit() {
        // k' → 0: K = ln(4/k') + O(k'² ln k'), E = 1 + O(k'² ln k'). At k' = 1e−8 the
        // correction is ~1e−15.
        let kp = 1e-8_f64;
        let r = complete_elliptic_from_complementary(kp);
        assert!(rel(r.k, (4.0 / kp).ln()) < 1e-12);
        assert!((r.e - 1.0).abs() < 1e-12);
        let tiny = complete_elliptic_from_complementary(1e-300);
        assert!(tiny.k.is_finite() && tiny.e.is_finite() && tiny.k_minus_e.is_finite());
    }

    #[test]
    fn legendre_relation() {
        // E K' + E' K − K K' = π/2 for complementary moduli — an independent check of both
        // integrals over the whole range (tolerance: a few ulp of terms of order K·K').
        for &kp in &[0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99] {
            let k: f64 = (1.0_f64 - kp * kp).sqrt();
            let a = complete_elliptic_from_complementary(kp);
            let b = complete_elliptic_from_complementary(k);
            let lhs = a.e * b.k + b.e * a.k - a.k * b.k;
            assert!((lhs - FRAC_PI_2).abs() < 2e-14, "k' = {kp}: {lhs}");
        }
    }
}
