//! Hertz functions of the curvature ratio, tabulated for the strip models.
//!
//! [`HertzShapeTable`] holds the Hertz functions of the curvature ratio that the strip models need
//! per strip (shape factor ε_x, axis ratio a/b, peak-pressure coefficient), tabulated once at
//! start-up so that a step does no per-strip H1 solve.

use crate::error::InputError;
use crate::normal::hertz::{hertz_from_approach, shape_factors};
use crate::numeric::interp::cubic_lagrange_weights;

/// Hertz quantities that depend only on the curvature ratio A/B.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzShape {
    /// Shape factor ε_x = A a²/δ (H6) [-]; ε_y = 1 − ε_x.
    pub eps_x: f64,
    /// Axis ratio a/b (a along x) [-].
    pub a_over_b: f64,
    /// Peak-pressure coefficient P: p0 = E* √(δ (A + B)) · P [-].
    pub p0_coeff: f64,
}

impl HertzShape {
    /// ε_y = B b²/δ = 1 − ε_x.
    pub fn eps_y(&self) -> f64 {
        1.0 - self.eps_x
    }
}

/// Exact Hertz shape for curvatures A, B > 0 (solves H1; used to build the table and in tests).
pub fn hertz_shape_exact(curv_a: f64, curv_b: f64) -> Result<HertzShape, InputError> {
    let (eps_x, _) = shape_factors(curv_a, curv_b)?;
    let unit = hertz_from_approach(curv_a, curv_b, 1.0, 1.0)?;
    Ok(HertzShape {
        eps_x,
        a_over_b: unit.a / unit.b,
        p0_coeff: unit.p0 / (curv_a + curv_b).sqrt(),
    })
}

/// Half range of u = ln(A/B) covered by [`HertzShapeTable`]; beyond it u is clamped
/// (A/B outside [1.1e−7, 8.9e6]: line contact for every practical purpose).
pub const SHAPE_TABLE_RANGE: f64 = 16.0;
/// Node spacing in u of [`HertzShapeTable`]: cubic interpolation error ~ Δu⁴ ≈ 2e−7 of the
/// functions' fourth derivative (O(1)), below 1e−7 relative (tested).
const SHAPE_TABLE_STEP: f64 = 0.02;
const SHAPE_TABLE_NODES: usize = (2.0 * SHAPE_TABLE_RANGE / SHAPE_TABLE_STEP) as usize + 1;

/// [`HertzShape`] tabulated on a uniform grid in u = ln(A/B) with 4-point cubic (Lagrange)
/// interpolation in each of ε_x, a/b and P. They vary like e^{cu} with |c| ≤ 1 (power laws in
/// A/B towards line contact), whose cubic interpolation at this step is relatively exact to
/// ~c⁴Δu⁴/40 ≈ 4e−9 — interpolating the values, not their logarithms, spares three
/// exponentials per lookup (the per-strip cost of the strip models). Built once (~1600 exact
/// solves, a few milliseconds); lookups cost a logarithm and a few multiplications.
#[derive(Debug, Clone)]
pub struct HertzShapeTable {
    /// Per node: ε_x, a/b, P.
    nodes: Vec<[f64; 3]>,
}

impl Default for HertzShapeTable {
    fn default() -> Self {
        Self::new()
    }
}

impl HertzShapeTable {
    pub fn new() -> Self {
        let nodes = (0..SHAPE_TABLE_NODES)
            .map(|k| {
                let u = -SHAPE_TABLE_RANGE + SHAPE_TABLE_STEP * k as f64;
                let h = hertz_shape_exact((0.5 * u).exp(), (-0.5 * u).exp())
                    .expect("curvature ratios inside the table range are solvable");
                [h.eps_x, h.a_over_b, h.p0_coeff]
            })
            .collect();
        Self { nodes }
    }

    /// The Hertz ellipse of curvatures A, B > 0 [1/m] at approach δ ≥ 0 [m] with contact modulus
    /// E* [Pa], from the table: a = √(ε_x δ/A), b = a/(a/b), p0 = E*√(δ(A + B))·P, N = (2/3)π a b p0
    /// (relative error ≤ 1e−7, the table's; `crate::normal::hertz::hertz_from_approach` outside its
    /// range). Same errors as `hertz_from_approach`.
    pub fn patch(
        &self,
        curv_a: f64,
        curv_b: f64,
        approach: f64,
        e_star: f64,
    ) -> Result<crate::normal::hertz::HertzPatch, InputError> {
        let u = (curv_a / curv_b).ln();
        let usable = u.abs() <= SHAPE_TABLE_RANGE
            && approach > 0.0
            && approach.is_finite()
            && e_star > 0.0
            && e_star.is_finite();
        if !usable {
            return crate::normal::hertz::hertz_from_approach(curv_a, curv_b, approach, e_star);
        }
        let shape = self.at_log_ratio(u);
        let a = (shape.eps_x * approach / curv_a).sqrt();
        let b = a / shape.a_over_b;
        let p0 = e_star * (approach * (curv_a + curv_b)).sqrt() * shape.p0_coeff;
        Ok(crate::normal::hertz::HertzPatch {
            a,
            b,
            approach,
            p0,
            normal_force: 2.0 / 3.0 * std::f64::consts::PI * a * b * p0,
        })
    }

    /// Hertz shape for curvatures A, B > 0 [1/m]. Non-positive or non-finite curvatures are an
    /// error naming A or B.
    pub fn lookup(&self, curv_a: f64, curv_b: f64) -> Result<HertzShape, InputError> {
        crate::error::require_positive("A", curv_a)?;
        crate::error::require_positive("B", curv_b)?;
        Ok(self.at_log_ratio((curv_a / curv_b).ln()))
    }

    /// Hertz shape at u = ln(A/B) (clamped to ±[`SHAPE_TABLE_RANGE`]).
    pub fn at_log_ratio(&self, u: f64) -> HertzShape {
        let u = u.clamp(-SHAPE_TABLE_RANGE, SHAPE_TABLE_RANGE);
        let t = (u + SHAPE_TABLE_RANGE) / SHAPE_TABLE_STEP;
        // Interval [k, k+1] with neighbours k−1 and k+2 inside the table.
        // `as usize` floors a non-negative value (and saturates below 0) without a call to
        // libm's floor, which baseline x86-64 (no SSE4.1 rounding) would need.
        let k = (t as usize).clamp(1, SHAPE_TABLE_NODES - 3);
        let w = cubic_lagrange_weights(t - k as f64);
        let mut v = [0.0; 3];
        for (j, wj) in w.iter().enumerate() {
            let node = &self.nodes[k - 1 + j];
            for q in 0..3 {
                v[q] += wj * node[q];
            }
        }
        HertzShape {
            eps_x: v[0],
            a_over_b: v[1],
            p0_coeff: v[2],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_matches_exact_hertz_to_1e7() {
        // Tolerance: the interpolation error bound in SHAPE_TABLE_STEP's comment.
        let table = HertzShapeTable::new();
        let mut u: f64 = -15.0;
        let mut worst = 0.0_f64;
        while u < 15.0 {
            let exact = hertz_shape_exact((0.5 * u).exp(), (-0.5 * u).exp()).unwrap();
            let t = table.at_log_ratio(u);
            for (a, b) in [
                (t.eps_x, exact.eps_x),
                (t.a_over_b, exact.a_over_b),
                (t.p0_coeff, exact.p0_coeff),
            ] {
                assert!(((a - b) / b).abs() < 1e-7, "u = {u}: {a} vs {b}");
                worst = worst.max(((a - b) / b).abs());
            }
            u += 0.0137;
        }
        // Interpolating the values themselves reaches 8e−10 on this sweep.
        assert!(worst < 1e-8, "{worst}");
    }

    #[test]
    fn shape_reproduces_hertz_peak_pressure() {
        // p0 = E* √(δ(A+B)) P against hertz_from_approach, to round-off.
        let (a, b, delta, e_star) = (0.9, 3.7, 6.0e-5, 1.15e11);
        let exact = hertz_from_approach(a, b, delta, e_star).unwrap();
        let s = hertz_shape_exact(a, b).unwrap();
        let p0 = e_star * (delta * (a + b)).sqrt() * s.p0_coeff;
        assert!(((p0 - exact.p0) / exact.p0).abs() < 1e-12);
        assert!((s.eps_x - a * exact.a * exact.a / delta).abs() < 1e-12);
        assert!((s.a_over_b - exact.a / exact.b).abs() < 1e-12);
        // Circle: ε = 1/2, P = 2/π.
        let c = hertz_shape_exact(2.0, 2.0).unwrap();
        assert!((c.eps_x - 0.5).abs() < 1e-12);
        assert!((c.p0_coeff - 2.0 / std::f64::consts::PI).abs() < 1e-12);
    }

    #[test]
    fn table_patch_matches_hertz_from_approach() {
        // Within the table's 1e−7 (a, b, p0; N ∝ a b p0 compounds three: 3e−7), the exact
        // solver outside the table's range and at δ = 0, and the same errors.
        let table = HertzShapeTable::new();
        let e_star = 1.15e11;
        for (a, b) in [
            (1.087, 0.37),
            (0.9, 3.7),
            (2.0, 2.0),
            (1.0, 1e-3),
            (1.0, 1e-9),
        ] {
            for delta in [0.0, 1e-6, 6e-5] {
                let t = table.patch(a, b, delta, e_star).unwrap();
                let x = hertz_from_approach(a, b, delta, e_star).unwrap();
                for (p, q, tol) in [
                    (t.a, x.a, 1e-7),
                    (t.b, x.b, 2e-7),
                    (t.p0, x.p0, 1e-7),
                    (t.normal_force, x.normal_force, 3e-7),
                ] {
                    assert!(
                        (p - q).abs() <= tol * q.abs(),
                        "A {a} B {b} δ {delta}: {p} vs {q}"
                    );
                }
            }
        }
        assert!(table.patch(1.0, -1.0, 1e-5, e_star).is_err());
        assert!(table.patch(1.0, 1.0, -1e-5, e_star).is_err());
    }

    #[test]
    fn lookup_rejects_non_positive_curvature() {
        let table = HertzShapeTable::new();
        assert_eq!(table.lookup(1.0, 0.0).unwrap_err().name, "B");
        assert_eq!(table.lookup(f64::NAN, 1.0).unwrap_err().name, "A");
    }
}
