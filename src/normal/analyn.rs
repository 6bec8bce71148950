//! ANALYN normal contact: per strip a local Hertz problem with a locally reduced approach.
//!
//! Papers: M. Sh. Sichani, R. Enblom, M. Berg, "A novel method to model wheel–rail normal contact
//! in vehicle dynamics simulation", Vehicle System Dynamics 52 (2014) (ANALYN); compared
//! with the other non-elliptic models in M. Sh. Sichani, R. Enblom, M. Berg, "Comparison of
//! non-elliptic contact models: towards fast and accurate modelling of wheel–rail contact",
//! Wear 314 (2014) 111–117. The equations follow docs/theory.md §5.7 (**A1**, the form of CONTACT's
//! "modified ANALYN"), with B handled as in §5.9.
//!
//! # Equations (A1), per strip i with centre s_i
//!
//! * B_i ← max(B_i, B_min) (replacement floor, §5.9; CONTACT clamps at 1e−4 1/mm);
//! * from the Hertz shape of (A_i, B_i) ([`HertzShapeTable`]): 1 + α_i = 1/ε_x, 1 + β_i = 1/ε_y
//!   (H6: A a² = ε_x δ, B b² = ε_y δ);
//! * δ_loc,i = δ − (1 + β_i) f_i, with f_i the gap of the strip's locus ([`StripGeometry::f`],
//!   measured from the first-contact point: g(y) = h(x_c, y) − h_min of A1);
//! * x_l,i = √(δ_loc,i/((1 + α_i) A_i)); no contact where δ_loc,i ≤ 0;
//! * p_max,i = Hertz p0 of (A_i, B_i, δ_loc,i) = E* √(δ_loc,i (A_i + B_i)) P(A_i/B_i);
//! * p(x) = p_max,i √(1 − ((x − x_c,i)/x_l,i)²), N = Σ (π/2) p_max,i x_l,i Δs (V1).
//!
//! Hertz gap f = B s², A constant: δ_loc = δ(1 − s²/b²) with b² = ε_y δ/B, so
//! x_l² = a²(1 − s²/b²) and p_max = p0 √(1 − s²/b²) — the Hertz pressure, strip by strip (tested
//! to the table's 1e−7). Since x_l² = ε_x δ_loc/A, the peak equals the A-based local Hertz peak of
//! an ellipse with x-semi-axis x_l (docs/theory.md §2.4), the same rule as STRIPES' S5.
//!
//! # Choices (ours, docs/theory.md §5.7)
//!
//! * Curvatures: A_i and B_i are taken from the strip geometry as given (its builder's estimate);
//!   the original paper's curvature estimation is not reproduced. No iteration on δ_loc: A1 is
//!   explicit in δ.
//! * B_min = `params.b_min` (default 0.1 1/m); a non-positive or non-finite value falls back to the
//!   default.
//!
//! # Known limits
//!
//! * The reduction (1 + β_i) f_i is local: for a non-Hertzian gap the strips do not interact, so
//!   the pressure is Hertz-exact only for elliptic cases (as the paper states).
//! * Where B ≤ B_min the floor makes 1 + β_i large (the strip's Hertz ellipse is long in s), which
//!   cuts the patch sharply wherever f > 0.
//! * Strips with A_i ≤ 0 or a non-finite A_i or f_i are out of contact (A > 0 is a precondition of
//!   the geometry). A gap with several minima gives several contact regions within one patch
//!   (each strip is independent); the caller normally cuts them into patches (§5.1).
//!
//! `prepare` and `solve` use fixed arrays of [`MAX_STRIPS`]: no allocation, no panic, no NaN for
//! any finite geometry and any δ (δ ≤ 0 or NaN: no contact).

use crate::geometry::strips::{PerStrip, StripGeometry};
use crate::normal::shape::HertzShapeTable;
use crate::normal::strips::StripSolution;
use crate::normal::{NormalParams, StripModel};

/// ANALYN (A1, docs/theory.md §5.7). See the module documentation.
#[derive(Debug, Clone, Default)]
pub struct Analyn {
    /// Strips prepared (≤ [`MAX_STRIPS`]).
    n: usize,
    /// Strip can be in contact (A_i finite and positive).
    active: PerStrip<bool>,
    /// Floored lateral curvature B_i [1/m].
    curv_b: PerStrip<f64>,
    /// Longitudinal curvature A_i [1/m].
    curv_a: PerStrip<f64>,
    /// Gap f_i of the strip's locus [m].
    gap: PerStrip<f64>,
    /// 1 + α_i = 1/ε_x [-].
    one_plus_alpha: PerStrip<f64>,
    /// 1 + β_i = 1/ε_y [-].
    one_plus_beta: PerStrip<f64>,
    /// √(A_i + B_i) P_i: p_max = E* √δ_loc · this [1/√m].
    peak_coeff: PerStrip<f64>,
}

/// Local approach δ_loc = δ − (1 + β) f [m] (A1).
fn local_approach(delta: f64, one_plus_beta: f64, gap: f64) -> f64 {
    delta - one_plus_beta * gap
}

/// Strip half-length x_l = √(δ_loc/((1 + α) A)) [m] (A1), for δ_loc > 0.
fn strip_half_length(delta_loc: f64, one_plus_alpha: f64, curv_a: f64) -> f64 {
    (delta_loc / (one_plus_alpha * curv_a)).sqrt()
}

impl Analyn {
    /// Floored lateral curvature B_i per strip, from the last `prepare` [1/m].
    pub fn curv_b(&self) -> &[f64] {
        &self.curv_b[..self.n]
    }

    /// Gap factor 1 + β_i = 1/ε_y per strip [-].
    pub fn one_plus_beta(&self) -> &[f64] {
        &self.one_plus_beta[..self.n]
    }
}

impl StripModel for Analyn {
    fn prepare(&mut self, geom: &StripGeometry, params: &NormalParams, table: &HertzShapeTable) {
        let n = geom.len();
        let b_min = params.b_floor();
        self.n = n;
        for i in 0..n {
            let raw_b = geom.curv_b[i];
            // Floor B < B_min (A1, §5.9); a non-finite B (input error) goes to the floor too.
            let b = if raw_b > b_min && raw_b.is_finite() {
                raw_b
            } else {
                b_min
            };
            let a = geom.curv_a[i];
            self.curv_b[i] = b;
            self.curv_a[i] = a;
            self.gap[i] = geom.f[i];
            self.active[i] = a.is_finite() && a > 0.0 && geom.f[i].is_finite();
            if self.active[i] {
                let shape = table.at_log_ratio((a / b).ln());
                self.one_plus_alpha[i] = 1.0 / shape.eps_x;
                self.one_plus_beta[i] = 1.0 / shape.eps_y();
                self.peak_coeff[i] = (a + b).sqrt() * shape.p0_coeff;
            } else {
                self.one_plus_alpha[i] = 0.0;
                self.one_plus_beta[i] = 0.0;
                self.peak_coeff[i] = 0.0;
            }
        }
    }

    fn solve(
        &mut self,
        geom: &StripGeometry,
        params: &NormalParams,
        _table: &HertzShapeTable,
        delta: f64,
        out: &mut StripSolution,
    ) -> f64 {
        let Some(n) = out.begin(geom, delta, params.e_star) else {
            return 0.0;
        };
        for i in 0..n.min(self.n) {
            if !self.active[i] {
                continue;
            }
            let delta_loc = local_approach(delta, self.one_plus_beta[i], self.gap[i]);
            if delta_loc > 0.0 {
                let half_length =
                    strip_half_length(delta_loc, self.one_plus_alpha[i], self.curv_a[i]);
                let pmax = params.e_star * (delta_loc.sqrt() * self.peak_coeff[i]);
                out.set(i, half_length, pmax, geom.ds);
            }
        }
        out.normal_force()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::strips::MAX_STRIPS;
    use crate::normal::strips::PatchSummary;
    use crate::normal::test_support::{
        self, assert_continuous_sweep, awkward_geometries, awkward_geometry, hertz_case, no_nan,
        table, AWKWARD_DELTAS, AWKWARD_HALF_WIDTH, CURV_B, DELTA, SECOND_MINIMUM,
    };

    /// Per-strip tolerance against exact Hertz, normalised by a² or p0: the table's 1e−7
    /// relative accuracy of ε_x and P (strips.rs), amplified at most a few times by
    /// δ_loc = δ − f/ε_y (two terms of size ≤ δ).
    const TABLE_TOL: f64 = 1e-6;

    fn params() -> NormalParams {
        NormalParams::default()
    }

    fn run(geom: &StripGeometry, params: &NormalParams, delta: f64) -> (StripSolution, f64) {
        test_support::run(&mut Analyn::default(), geom, params, delta)
    }

    #[test]
    fn hertz_gap_gives_hertz_pressure_strip_by_strip() {
        // x_l² = a²(1 − s²/b²), p_max = p0 √(1 − s²/b²) at every strip, for any alignment.
        for ratio in [1.0, 1.0 / 3.0, 0.1, 3.0, 0.02, 10.0] {
            let (curv_a, h) = hertz_case(ratio);
            for (lo, hi, n) in [
                (-1.0, 1.0, 199),
                (-1.3, 1.17, 200),
                (0.2, 1.5, 17),
                (-0.4, 0.3, 1),
            ] {
                let geom = StripGeometry::quadratic(curv_a, CURV_B, lo * h.b, hi * h.b, n);
                let (sol, _) = run(&geom, &params(), DELTA);
                let mut err: f64 = 0.0;
                for i in 0..n {
                    let q = 1.0 - (geom.s[i] / h.b).powi(2);
                    assert_eq!(sol.half_length[i] > 0.0, q > 0.0, "strip {i}");
                    let q = q.max(0.0);
                    err = err.max((sol.half_length[i].powi(2) - h.a * h.a * q).abs() / (h.a * h.a));
                    err = err.max((sol.pmax[i] - h.p0 * q.sqrt()).abs() / h.p0);
                }
                if lo == -1.0 {
                    eprintln!("A/B = {ratio:.4}: per-strip error {err:.2e}");
                }
                assert!(err < TABLE_TOL, "A/B = {ratio}, [{lo}, {hi}]: {err}");
            }
            // 199 strips on [−b, b]: exact a and p0 at the centre strip; V1's midpoint sum is
            // N_H (1 + Δs²/(8b²)) exactly.
            let geom = StripGeometry::quadratic(curv_a, CURV_B, -h.b, h.b, 199);
            let (sol, n) = run(&geom, &params(), DELTA);
            let sum = PatchSummary::of(&geom, &sol);
            let midpoint = 1.0 + (geom.ds / h.b).powi(2) / 8.0;
            assert!((sum.length / (2.0 * h.a) - 1.0).abs() < TABLE_TOL);
            assert!((sum.pmax / h.p0 - 1.0).abs() < TABLE_TOL);
            assert!((n / (h.normal_force * midpoint) - 1.0).abs() < TABLE_TOL);
        }
    }

    #[test]
    fn normal_force_tends_to_hertz_with_strip_count() {
        // Odd counts on [−b, b]: |N/N_H − 1| = Δs²/(8b²) = 1/(2 n²) → 0.
        let (curv_a, h) = hertz_case(0.25);
        let mut last = f64::INFINITY;
        for n in [25, 51, 101, 199] {
            let geom = StripGeometry::quadratic(curv_a, CURV_B, -h.b, h.b, n);
            let err = (run(&geom, &params(), DELTA).1 / h.normal_force - 1.0).abs();
            let expect = 0.5 / (n * n) as f64;
            eprintln!("{n} strips: |N/N_H − 1| = {err:.3e} (Δs²/8b² = {expect:.3e})");
            assert!((err - expect).abs() < TABLE_TOL);
            assert!(err < 0.3 * last);
            last = err;
        }
        // Strip set not aligned with the patch: |N/N_H − 1| ≤ (Δs/b)²/2 (interior Δs²/(6b),
        // each cut edge ≤ Δs²/(4b), of 4b/3).
        for n in [25, 50, 100, MAX_STRIPS] {
            let geom = StripGeometry::quadratic(curv_a, CURV_B, -1.3 * h.b, 1.17 * h.b, n);
            let err = (run(&geom, &params(), DELTA).1 / h.normal_force - 1.0).abs();
            let step = geom.ds / h.b;
            eprintln!("{n} strips, unaligned: |N/N_H − 1| = {err:.2e}");
            assert!(err <= 0.5 * step * step);
        }
    }

    #[test]
    fn mirrored_gap_gives_mirrored_pressure() {
        let w = 1.5 * hertz_case(1.0).1.b;
        let gap = move |s: f64| {
            (
                CURV_B * s * s * (1.0 - 0.5 * s / w),
                0.8 * (1.0 + 0.3 * s / w),
                CURV_B * (1.0 - 1.5 * s / w),
            )
        };
        let n = 77;
        let geom = StripGeometry::from_fn(-w, 0.7 * w, n, gap);
        let mirror = StripGeometry::from_fn(-0.7 * w, w, n, |s| gap(-s));
        let (sol, n1) = run(&geom, &params(), 2.0 * DELTA);
        let (sol_m, n2) = run(&mirror, &params(), 2.0 * DELTA);
        let x_max = sol.half_length.iter().copied().fold(0.0, f64::max);
        let p_max = sol.pmax.iter().copied().fold(0.0, f64::max);
        assert!(x_max > 0.0);
        for i in 0..n {
            let j = n - 1 - i;
            assert!((sol.half_length[i] - sol_m.half_length[j]).abs() <= 1e-9 * x_max);
            assert!((sol.pmax[i] - sol_m.pmax[j]).abs() <= 1e-9 * p_max);
        }
        assert!((n1 - n2).abs() <= 1e-9 * n1);
    }

    #[test]
    fn awkward_inputs_give_no_nan_and_no_panic() {
        let w = AWKWARD_HALF_WIDTH;
        let cases = awkward_geometries();
        for (name, geom) in &cases {
            for delta in AWKWARD_DELTAS {
                for p in [
                    params(),
                    NormalParams {
                        b_min: f64::NAN,
                        ..params()
                    },
                ] {
                    let (sol, n) = run(geom, &p, delta);
                    no_nan(&sol, n);
                    if delta.is_nan() || delta <= 0.0 {
                        assert_eq!(n, 0.0, "{name}");
                    }
                }
            }
        }
        // Two minima: ANALYN's strips are independent, so both regions carry load.
        let geom = &awkward_geometry("two minima");
        let (sol, _) = run(geom, &params(), 1e-6);
        let s2 = SECOND_MINIMUM;
        let near = |target: f64| {
            (0..geom.n).any(|i| (geom.s[i] - target).abs() < 0.1 * w && sol.half_length[i] > 0.0)
        };
        assert!(near(0.0) && near(s2));
        let hump_free =
            (0..geom.n).any(|i| (geom.s[i] - 0.5 * s2).abs() < 0.02 * w && sol.force[i] == 0.0);
        assert!(hump_free);
        // B ≤ 0 is floored to B_min.
        let (_, conformal) = &cases[0];
        let mut model = Analyn::default();
        model.prepare(conformal, &params(), table());
        assert!(model.curv_b().iter().all(|&b| b == params().b_min));
    }

    #[test]
    fn normal_force_is_continuous_while_b_crosses_zero() {
        assert_continuous_sweep(Analyn::default, 1.5 * hertz_case(1.0 / 1.5).1.b, DELTA);
    }
}
