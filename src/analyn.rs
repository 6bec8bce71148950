//! ANALYN normal contact: per strip a local Hertz problem with a locally reduced approach.
//!
//! Papers: M. Sh. Sichani, R. Enblom, M. Berg, "A novel method to model wheel–rail normal contact
//! in vehicle dynamics simulation", Vehicle System Dynamics 52 (2014) (ANALYN); compared
//! with the other non-elliptic models in M. Sh. Sichani, R. Enblom, M. Berg, "Comparison of
//! non-elliptic contact models: towards fast and accurate modelling of wheel–rail contact",
//! Wear 314 (2014) 111–117. The equations follow physics.md §5.8 (**A1**, the form of CONTACT's
//! "modified ANALYN"), with B handled as in §5.10.
//!
//! # Equations (A1), per strip i with centre s_i
//!
//! * B_i ← max(B_i, B_min) (replacement floor, §5.10; CONTACT clamps at 1e−4 1/mm);
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
//! an ellipse with x-semi-axis x_l (physics.md §2.4), the same rule as STRIPES' S5.
//!
//! # Choices ([U] items of §5.8)
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

use crate::strips::{
    HertzShapeTable, NormalParams, StripGeometry, StripModel, StripSolution, MAX_STRIPS,
};

/// ANALYN (A1, physics.md §5.8). See the module documentation.
#[derive(Debug, Clone)]
pub struct Analyn {
    /// Strips prepared (≤ [`MAX_STRIPS`]).
    n: usize,
    /// Strip can be in contact (A_i finite and positive).
    active: [bool; MAX_STRIPS],
    /// Floored lateral curvature B_i [1/m].
    curv_b: [f64; MAX_STRIPS],
    /// Longitudinal curvature A_i [1/m].
    curv_a: [f64; MAX_STRIPS],
    /// Gap f_i of the strip's locus [m].
    gap: [f64; MAX_STRIPS],
    /// 1 + α_i = 1/ε_x [-].
    one_plus_alpha: [f64; MAX_STRIPS],
    /// 1 + β_i = 1/ε_y [-].
    one_plus_beta: [f64; MAX_STRIPS],
    /// √(A_i + B_i) P_i: p_max = E* √δ_loc · this [1/√m].
    peak_coeff: [f64; MAX_STRIPS],
}

impl Default for Analyn {
    fn default() -> Self {
        Self {
            n: 0,
            active: [false; MAX_STRIPS],
            curv_b: [0.0; MAX_STRIPS],
            curv_a: [0.0; MAX_STRIPS],
            gap: [0.0; MAX_STRIPS],
            one_plus_alpha: [0.0; MAX_STRIPS],
            one_plus_beta: [0.0; MAX_STRIPS],
            peak_coeff: [0.0; MAX_STRIPS],
        }
    }
}

/// The B floor B_min of `params`, or the default floor when the parameter is not a finite
/// positive number [1/m].
fn lateral_curvature_floor(params: &NormalParams) -> f64 {
    if params.b_min.is_finite() && params.b_min > 0.0 {
        params.b_min
    } else {
        NormalParams::default().b_min
    }
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
        let n = geom.n.min(MAX_STRIPS);
        let b_min = lateral_curvature_floor(params);
        self.n = n;
        for i in 0..n {
            let raw_b = geom.curv_b[i];
            // `!(b > b_min)` also floors a non-finite B.
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
        let n = geom.n.min(MAX_STRIPS);
        out.reset(n);
        if !(delta > 0.0 && delta.is_finite() && geom.ds > 0.0 && geom.ds.is_finite()) {
            return 0.0;
        }
        for i in 0..n.min(self.n) {
            if !self.active[i] {
                continue;
            }
            let delta_loc = local_approach(delta, self.one_plus_beta[i], self.gap[i]);
            if delta_loc > 0.0 {
                let half_length =
                    strip_half_length(delta_loc, self.one_plus_alpha[i], self.curv_a[i]);
                let pmax = params.e_star * delta_loc.sqrt() * self.peak_coeff[i];
                out.set(i, half_length, pmax, geom.ds);
            }
        }
        out.normal_force()
    }
}
