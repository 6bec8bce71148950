//! Coupled strips: strip loads coupled through the half-space, each strip's length following its
//! load by the local Hertz ratio of peak to length.
//!
//! Papers: the strip method of K. Knothe, H. Le The, "A contribution to the calculation of the
//! contact stress distribution between two elastic bodies of revolution with non-elliptical
//! contact area", Computers & Structures 18 (1984) 1025–1033 (semi-elliptic pressure along x on
//! lateral strips, strip loads from collocated half-space displacements); the strip kernel of
//! Kik–Piotrowski (KP6, `crate::normal::kernel`); the local Hertz ellipse per strip of ANALYN,
//! M. Sh. Sichani, R. Enblom, M. Berg, Vehicle System Dynamics 52 (2014) (A1,
//! `crate::normal::analyn`). Equations as docs/theory.md §5.10.
//!
//! # Equations (labels of docs/theory.md §5.10)
//!
//! * **C1** per strip i the semi-ellipse p_i(x) = p0_i √(1 − (x − x_c,i)²/a_i²) with
//!   p0_i = r_i E* a_i, r_i = √((A_i + B⁺_i)A_i/ε_x) P the Hertz peak-to-length ratio of the
//!   local ellipse (A_i, B⁺_i = max(B_i, 0)) — ANALYN's p_max,i/(E* x_l,i) where B_i ≥ B_min, a
//!   line contact's A_i where B_i ≤ 0 (the shape table's end, A/B = e¹⁶).
//! * **C2** the normal displacement at strip i's centre line, u_i = Σ_j G_ij y_j, of the strip
//!   loads y_j = 2F_j/(π²E*Δs) = p0_j a_j/(πE*), F_j = (π/2) p0_j a_j Δs (V1), with
//!   G_ij = Ĵ((|i−j| + ½)Δs/a_j) − Ĵ((|i−j| − ½)Δs/a_j) (i ≠ j), G_jj = 2Ĵ(Δs/(2a_j)),
//!   Ĵ(T) = ∫₀^T I(1, t) dt the scale-free integral of KP6's I(c, y) (Boussinesq:
//!   u = (p0/(πE*a)) ∫∫ √(a² − x²)/√(x² + y²) = y_j G_ij, [`ScaledStripIntegral`]).
//! * **C3** complementarity on every strip the rigid bodies overlap (δ − f_i > 0): y_i ≥ 0,
//!   u_i = δ − f_i where y_i > 0, u_i ≥ δ − f_i where y_i = 0.
//! * **C4** a_i² = π y_i/r_i (C1 with C2), N = Σ F_i.
//!
//! For fixed half-lengths C2–C3 is a linear complementarity problem; C4 closes the loop. The
//! fixed point of the half-lengths is solved in ln a_i (below). A strip entering contact has
//! y_i → 0 and a_i ∝ √y_i → 0; its own displacement y_i G_ii ~ y_i ln(1/y_i) vanishes with it,
//! so its load starts from zero and N(δ) and the pose dependence are continuous without a peak
//! bound or a length floor. On a Hertz gap r_i is the patch's Hertz p0/(E* a), so Hertz's a(y)
//! and p(y) satisfy C1 and C4, and C3 up to the collocation's midpoint rule in y. G is not
//! symmetric (it depends on the column's a_j); its symmetric part is positive definite at every
//! tested solution, which makes G a P-matrix and C3's solution at the final half-lengths unique
//! (tested).
//!
//! # Choices (ours)
//!
//! * The half-lengths: Newton's method in ln a_i on the loaded set after each solve of C2–C3
//!   (the derivative of G from T I(1, T) = dĴ/d ln T, tabulated beside Ĵ, once per column and
//!   offset; a step changes ln a_i by at most [`STEP_LIMIT`]; a plain step x_i ← ln √(π y_i/r_i)
//!   if the Newton matrix is singular), until every loaded strip's residual is below
//!   [`LENGTH_TOL`] with the loaded set unchanged, or [`LENGTH_ITERATIONS`] solves (counted,
//!   [`CoupledStrips::unsettled`]). A cold start takes a_i = √((δ − f_i)/((1 + α_i)A_i)) with B
//!   floored at B_min as ANALYN's (4–7 solves on the test gaps); a step starts from the previous
//!   step's lengths scaled by √((δ − f_i)/(δ − f_i)_previous) and its states (one solve on a
//!   steady pose, 2–5 while the pose changes).
//! * C3 by block principal pivoting (Júdice–Pires: flip every infeasible strip between free and
//!   unloaded while their number falls, three more tries, then Murty's least-index rule),
//!   warm-started from the previous solve's states, each step a partial-pivoting LU of the free
//!   block on fixed buffers. If the pivoting exceeds its iteration bound or a block is singular,
//!   projected Gauss–Seidel to 1e−12 takes over; both events are counted
//!   ([`CoupledStrips::fallbacks`], [`CoupledStrips::unconverged`]), never hidden.
//! * Ĵ from a table in ln T (one cubic interpolation; ln((k + ½)Δs) is prepared per strip
//!   offset), the far-field series where a strip is more than 64 of its half-lengths away
//!   ([`ScaledStripIntegral::far_difference`]); a column's entries once per offset k.
//!
//! # Known limits
//!
//! * The coupling uses the strips' centre lines x = 0: the small offsets x_c,i between strips
//!   under yaw are neglected in G (the pressure itself is placed at x_c,i). One collocation
//!   point per strip (errors O(Δs/b), measured in the tests).
//! * r_i is the local Hertz ellipse's ratio, not the curvature condition along x of the coupled
//!   displacement: the strip lengths are as good as that ratio (against the exact half-space on
//!   S1002/UIC60, −1…+6 mm: area −2.5…+2.2 %; Manchester A-2.2's flange states: −6…−8 %).
//! * A changing pose costs 2–5 solves of C2–C3 per normal solve (a steady pose one): on the
//!   hunting wheelset 3.2 M instructions per wheelset solve, 6.7 × ANALYN's (1.46 × steady).
//! * The fixed point of C1–C4 is not proven unique: on a two-region gap (`two_wells(120)` of
//!   the tests) two iteration schemes settled at normal forces 0.4 % apart; warm and cold starts
//!   agree on the tested sequences (1e−9).
//!
//! `prepare` and `solve` use buffers sized at construction ([`MAX_STRIPS`]): no allocation, no
//! panic, no NaN for any finite geometry and any δ.

use std::f64::consts::PI;

use crate::geometry::strips::{PerStrip, StripGeometry, MAX_STRIPS};
use crate::normal::kernel::ScaledStripIntegral;
use crate::normal::shape::{HertzShapeTable, SHAPE_TABLE_RANGE};
use crate::normal::strips::StripSolution;
use crate::normal::{NormalParams, StripModel};
use crate::numeric::dense::lu_solve;

/// Relative tolerance of a complementarity violation u_i − (δ − f_i) < 0 at an unloaded strip,
/// of the largest δ − f_i: rounding in the block solve is ~1e−15 of it.
const FEASIBILITY_TOL: f64 = 1e-12;

/// Extra flips of every infeasible strip after their number stopped falling (Júdice–Pires).
const BLOCK_TRIES: usize = 3;

/// Projected Gauss–Seidel sweeps of the fallback.
const PGS_SWEEPS: usize = 20_000;

/// Most solves of C2–C3 per normal solve while the half-lengths settle.
const LENGTH_ITERATIONS: usize = 100;

/// Largest change of ln a_i in one update.
const STEP_LIMIT: f64 = 1.0;

/// Relative change of every loaded strip's half-length below which they have settled.
const LENGTH_TOL: f64 = 1e-10;

/// The complementarity state of a candidate strip (C3).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
enum Load {
    /// y > 0, u = δ − f.
    #[default]
    Free,
    /// y = 0, u ≥ δ − f.
    Unloaded,
}

/// Coupled strips (docs/theory.md §5.10). See the module documentation.
#[derive(Debug, Clone)]
pub struct CoupledStrips {
    /// Per strip: whether it can carry load (A_i finite and positive, f_i finite), its local
    /// Hertz ratio r_i = p0/(E* a) [1/m] (C1) and (1 + α_i)A_i with B floored as ANALYN's (the
    /// cold start's half-length).
    active: PerStrip<bool>,
    strip_ratio: PerStrip<f64>,
    seed_coeff: PerStrip<f64>,
    /// Ĵ, tabulated at construction.
    kernel: ScaledStripIntegral,
    /// Strips prepared.
    n: usize,
    /// Candidates of the last solve.
    m: usize,
    /// ln((k + ½)Δs) per strip offset k.
    log_edge: PerStrip<f64>,
    /// (k + ½)Δs per strip offset k [m].
    edge: PerStrip<f64>,
    /// ln((k + ½)/(k − ½)) per offset k ≥ 1 (fixed: filled by `new`).
    log_ratio: PerStrip<f64>,
    /// Scratch of a solve, per candidate (strip with a_i > 0): its strip index, a_i, δ − f_i,
    /// load y_i, residual u_i − (δ − f_i), state; Ĵ at a column's strip edges.
    strip: PerStrip<usize>,
    half: PerStrip<f64>,
    /// Per candidate, the residual of C4, ln √(π y/ratio) − ln a.
    residual_log: PerStrip<f64>,
    rhs: PerStrip<f64>,
    load: PerStrip<f64>,
    residual: PerStrip<f64>,
    state: PerStrip<Load>,
    edge_integral: PerStrip<f64>,
    column: PerStrip<f64>,
    /// Per candidate: the local Hertz ratio p0/(E* a) [1/m] (C1) and whether it was loaded at
    /// the previous half-lengths.
    ratio: PerStrip<f64>,
    loaded: PerStrip<bool>,
    /// States and half-lengths of the last solve, per strip (the warm start).
    warm: PerStrip<Load>,
    warm_half: PerStrip<f64>,
    /// δ − f_i of the last solve per strip [m].
    warm_rhs: PerStrip<f64>,
    /// G of the candidates (row stride MAX_STRIPS) and the block being factorised.
    matrix: Vec<f64>,
    block: Vec<f64>,
    /// Positions of the loaded candidates; the block's right-hand side.
    block_index: PerStrip<usize>,
    block_rhs: PerStrip<f64>,
    /// Solves that needed the Gauss–Seidel fallback, and of them those that did not converge.
    fallbacks: u64,
    unconverged: u64,
    /// Solves of C2–C3 in all, and steps whose half-lengths did not settle.
    length_solves: u64,
    unsettled: u64,
}

impl Default for CoupledStrips {
    fn default() -> Self {
        Self::new()
    }
}

impl CoupledStrips {
    /// The model with its kernel table and buffers (allocates once, here).
    pub fn new() -> Self {
        Self {
            active: PerStrip::default(),
            strip_ratio: PerStrip::default(),
            seed_coeff: PerStrip::default(),
            kernel: ScaledStripIntegral::new(),
            n: 0,
            m: 0,
            log_edge: PerStrip::default(),
            edge: PerStrip::default(),
            log_ratio: PerStrip(std::array::from_fn(|k| {
                if k == 0 {
                    0.0
                } else {
                    ((k as f64 + 0.5) / (k as f64 - 0.5)).ln()
                }
            })),
            strip: PerStrip::default(),
            half: PerStrip::default(),
            residual_log: PerStrip::default(),
            rhs: PerStrip::default(),
            load: PerStrip::default(),
            residual: PerStrip::default(),
            state: PerStrip::default(),
            edge_integral: PerStrip::default(),
            column: PerStrip::default(),
            ratio: PerStrip::default(),
            loaded: PerStrip::default(),
            warm: PerStrip::default(),
            warm_half: PerStrip::default(),
            warm_rhs: PerStrip::default(),
            matrix: vec![0.0; MAX_STRIPS * MAX_STRIPS],
            block: vec![0.0; MAX_STRIPS * MAX_STRIPS],
            block_index: PerStrip::default(),
            block_rhs: PerStrip::default(),
            fallbacks: 0,
            unconverged: 0,
            length_solves: 0,
            unsettled: 0,
        }
    }

    /// Solves since construction that fell back to projected Gauss–Seidel (pivoting cycled or
    /// met a singular block).
    pub fn fallbacks(&self) -> u64 {
        self.fallbacks
    }

    /// Fallback solves that did not reach their tolerance (their last iterate was used).
    pub fn unconverged(&self) -> u64 {
        self.unconverged
    }

    /// Solves of the complementarity problem (C2–C3) since construction, over all steps: one
    /// per update of the half-lengths.
    pub fn length_solves(&self) -> u64 {
        self.length_solves
    }

    /// Steps whose half-lengths had not settled after [`LENGTH_ITERATIONS`] solves (their last
    /// iterate was used).
    pub fn unsettled(&self) -> u64 {
        self.unsettled
    }

    /// The last solve's candidates (test access): state, load y_i [m], residual
    /// u_i − (δ − f_i) [m].
    #[cfg(test)]
    fn candidates(&self, m: usize) -> impl Iterator<Item = (Load, f64, f64)> + '_ {
        (0..m).map(|r| (self.state[r], self.load[r], self.residual[r]))
    }

    /// One update of the loaded candidates' half-lengths towards C4 after a solve of C2–C3;
    /// `true` once every loaded strip's residual R_i = ln √(π y_i/r_i) − ln a_i is below
    /// [`LENGTH_TOL`] (and the loaded set unchanged). Newton's step in x = ln a on the loaded set
    /// L: with G y = δ − f on L, ∂y/∂x_j = −G⁻¹ D e_j, D_ij = y_j ∂G_ij/∂x_j, so
    /// (D + 2 G Y) Δx = 2 G Y R (Y = diag y); each Δx_i within ±[`STEP_LIMIT`]. A singular
    /// Newton matrix falls back to the plain step x_i ← ln √(π y_i/r_i).
    fn settle_lengths(&mut self, m: usize) -> bool {
        let mut change: f64 = 0.0;
        let mut size = 0;
        for r in 0..m {
            let y = self.load[r];
            let loaded = y > 0.0;
            if loaded != self.loaded[r] {
                change = f64::INFINITY;
            }
            self.loaded[r] = loaded;
            if loaded {
                let g = 0.5 * (PI * y / self.ratio[r]).ln();
                self.residual_log[r] = g - self.half[r].ln();
                change = change.max(self.residual_log[r].exp_m1().abs());
                self.block_index[size] = r;
                size += 1;
            }
        }
        if change <= LENGTH_TOL {
            return true;
        }
        let (first, last) = (self.block_index[0], self.block_index[size - 1]);
        for q in 0..size {
            let c = self.block_index[q];
            let (a, y) = (self.half[c], self.load[c]);
            let log_a = a.ln();
            let j = self.strip[c];
            // d/d ln a of Ĵ((k + ½)Δs/a) = −T I(1, T), once per offset k.
            let far = self.strip[first]
                .abs_diff(j)
                .max(self.strip[last].abs_diff(j));
            for k in 0..=far {
                let t = self.edge[k] / a;
                self.edge_integral[k] = -self.kernel.slope_at_log(t, self.log_edge[k] - log_a);
            }
            for (p, &r) in self.block_index[..size].iter().enumerate() {
                let k = self.strip[r].abs_diff(j);
                let derivative = if k == 0 {
                    2.0 * self.edge_integral[0]
                } else {
                    self.edge_integral[k] - self.edge_integral[k - 1]
                };
                let g = self.matrix[r * MAX_STRIPS + c];
                self.block[p * MAX_STRIPS + q] = y * (derivative + 2.0 * g);
            }
        }
        for p in 0..size {
            let r = self.block_index[p];
            let row = &self.matrix[r * MAX_STRIPS..r * MAX_STRIPS + m];
            self.block_rhs[p] = 2.0
                * self.block_index[..size]
                    .iter()
                    .map(|&c| row[c] * self.load[c] * self.residual_log[c])
                    .sum::<f64>();
        }
        let newton = lu_solve(
            &mut self.block,
            MAX_STRIPS,
            size,
            &mut self.block_rhs[..size],
        );
        for p in 0..size {
            let r = self.block_index[p];
            let step = if newton {
                self.block_rhs[p]
            } else {
                self.residual_log[r]
            };
            self.half[r] *= step.clamp(-STEP_LIMIT, STEP_LIMIT).exp();
        }
        false
    }

    /// G of the `m` candidates (C2) into `matrix`. Column c's strip acts with its own
    /// half-length a_c: Ĵ at its strip edges and their differences once per column and offset.
    fn assemble(&mut self, m: usize) {
        for c in 0..m {
            let a = self.half[c];
            let log_a = a.ln();
            let j = self.strip[c];
            let far = (self.strip[0].abs_diff(j)).max(self.strip[m - 1].abs_diff(j));
            // Beyond this edge the far-field series replaces the table.
            let far_field = self.kernel.t_max() * a;
            for k in 0..=far {
                let t = self.edge[k] / a;
                self.edge_integral[k] = self.kernel.at_log(t, self.log_edge[k] - log_a);
            }
            self.column[0] = 2.0 * self.edge_integral[0];
            for k in 1..=far {
                self.column[k] = if self.edge[k - 1] >= far_field {
                    let (t_lo, t_hi) = (self.edge[k - 1] / a, self.edge[k] / a);
                    ScaledStripIntegral::far_difference(t_lo, t_hi, self.log_ratio[k])
                } else {
                    self.edge_integral[k] - self.edge_integral[k - 1]
                };
            }
            for r in 0..m {
                self.matrix[r * MAX_STRIPS + c] = self.column[self.strip[r].abs_diff(j)];
            }
        }
    }

    /// Loads of the free strips (block solve, the unloaded ones at zero) and the residuals;
    /// `false` if the block is singular.
    fn solve_free(&mut self, m: usize) -> bool {
        let mut size = 0;
        for r in 0..m {
            self.load[r] = 0.0;
            if self.state[r] == Load::Free {
                self.block_index[size] = r;
                size += 1;
            }
        }
        for (p, &r) in self.block_index[..size].iter().enumerate() {
            let row = &self.matrix[r * MAX_STRIPS..r * MAX_STRIPS + m];
            for (q, &c) in self.block_index[..size].iter().enumerate() {
                self.block[p * MAX_STRIPS + q] = row[c];
            }
            self.block_rhs[p] = self.rhs[r];
        }
        if !lu_solve(
            &mut self.block,
            MAX_STRIPS,
            size,
            &mut self.block_rhs[..size],
        ) {
            return false;
        }
        for p in 0..size {
            self.load[self.block_index[p]] = self.block_rhs[p];
        }
        self.update_residuals(m);
        true
    }

    /// u − (δ − f) at every candidate from the current loads.
    fn update_residuals(&mut self, m: usize) {
        for r in 0..m {
            let row = &self.matrix[r * MAX_STRIPS..r * MAX_STRIPS + m];
            let u: f64 = row.iter().zip(&self.load[..m]).map(|(g, y)| g * y).sum();
            self.residual[r] = u - self.rhs[r];
        }
    }

    /// Whether candidate `r` violates C3: a free strip with a negative load, or an unloaded
    /// strip the others push through the surface.
    fn infeasible(&self, r: usize, tol: f64) -> bool {
        match self.state[r] {
            Load::Free => self.load[r] < 0.0,
            Load::Unloaded => self.residual[r] < -tol,
        }
    }

    /// The state candidate `r` moves to when it is infeasible.
    fn flip(&mut self, r: usize) {
        self.state[r] = match self.state[r] {
            Load::Free => Load::Unloaded,
            Load::Unloaded => Load::Free,
        };
    }

    /// C3 by block principal pivoting; `false` if it did not finish.
    fn pivot(&mut self, m: usize, tol: f64) -> bool {
        let mut best = usize::MAX;
        let mut tries = BLOCK_TRIES;
        let mut least_index = false;
        for _ in 0..(50 + 10 * m) {
            if !self.solve_free(m) {
                return false;
            }
            let count = (0..m).filter(|&r| self.infeasible(r, tol)).count();
            if count == 0 {
                return true;
            }
            if !least_index && count < best {
                best = count;
                tries = BLOCK_TRIES;
            } else if !least_index && tries > 0 {
                tries -= 1;
            } else {
                least_index = true;
            }
            if least_index {
                if let Some(r) = (0..m).find(|&r| self.infeasible(r, tol)) {
                    self.flip(r);
                }
            } else {
                for r in 0..m {
                    if self.infeasible(r, tol) {
                        self.flip(r);
                    }
                }
            }
        }
        false
    }

    /// C3 by projected Gauss–Seidel (onto y ≥ 0) from the current loads; `true` once a
    /// sweep changes no load by more than 1e−12 of the largest.
    fn gauss_seidel(&mut self, m: usize) -> bool {
        for r in 0..m {
            self.load[r] = self.load[r].max(0.0);
            if !self.load[r].is_finite() {
                self.load[r] = 0.0;
            }
        }
        let mut converged = false;
        for _ in 0..PGS_SWEEPS {
            let (mut change, mut largest) = (0.0_f64, 0.0_f64);
            for r in 0..m {
                let row = &self.matrix[r * MAX_STRIPS..r * MAX_STRIPS + m];
                let u: f64 = row.iter().zip(&self.load[..m]).map(|(g, y)| g * y).sum();
                let diagonal = row[r];
                let next = if diagonal > 0.0 {
                    (self.load[r] - (u - self.rhs[r]) / diagonal).max(0.0)
                } else {
                    0.0
                };
                change = change.max((next - self.load[r]).abs());
                largest = largest.max(next);
                self.load[r] = next;
            }
            if change <= 1e-12 * largest {
                converged = true;
                break;
            }
        }
        for r in 0..m {
            self.state[r] = if self.load[r] <= 0.0 {
                Load::Unloaded
            } else {
                Load::Free
            };
        }
        self.update_residuals(m);
        converged
    }
}

impl StripModel for CoupledStrips {
    fn prepare(&mut self, geom: &StripGeometry, params: &NormalParams, table: &HertzShapeTable) {
        let n = geom.len();
        self.n = n;
        let b_min = params.b_floor();
        for i in 0..n {
            let (a, b) = (geom.curv_a[i], geom.curv_b[i]);
            self.active[i] = a.is_finite() && a > 0.0 && geom.f[i].is_finite();
            if !self.active[i] {
                continue;
            }
            // C1: the Hertz ellipse of (A_i, max(B_i, 0)), a line contact where B_i ≤ 0 (the
            // table's end, A/B = e^16).
            let u = if b > 0.0 && b.is_finite() {
                (a / b).ln().min(SHAPE_TABLE_RANGE)
            } else {
                SHAPE_TABLE_RANGE
            };
            let shape = table.at_log_ratio(u);
            let b_line = a * (-u).exp();
            self.strip_ratio[i] = ((a + b_line) * a / shape.eps_x).sqrt() * shape.p0_coeff;
            let b_seed = if b > b_min && b.is_finite() { b } else { b_min };
            self.seed_coeff[i] = a / table.at_log_ratio((a / b_seed).ln()).eps_x;
        }
        let ds = geom.ds;
        for k in 0..n {
            let edge = (k as f64 + 0.5) * ds;
            self.edge[k] = edge;
            self.log_edge[k] = edge.ln();
        }
    }

    fn solve(
        &mut self,
        geom: &StripGeometry,
        params: &NormalParams,
        _shapes: &HertzShapeTable,
        delta: f64,
        out: &mut StripSolution,
    ) -> f64 {
        let n = match out.begin(geom, delta, params.e_star) {
            Some(n) => n.min(self.n),
            None => return 0.0,
        };
        // C1: the candidates, every strip the rigid bodies overlap.
        let mut m = 0;
        let mut rhs_max: f64 = 0.0;
        for i in 0..n {
            let rhs = delta - geom.f[i];
            let ratio = self.strip_ratio[i];
            if !(self.active[i] && rhs > 0.0 && rhs.is_finite() && ratio > 0.0 && ratio.is_finite())
            {
                continue;
            }
            let seed = if self.warm_half[i] > 0.0 {
                // The previous length, scaled as a local Hertz length with the overlap.
                self.warm_half[i] * (rhs / self.warm_rhs[i]).sqrt()
            } else {
                (rhs / self.seed_coeff[i]).sqrt()
            };
            if !(seed > 0.0 && seed.is_finite()) {
                continue;
            }
            self.strip[m] = i;
            self.half[m] = seed;
            self.loaded[m] = self.warm[i] != Load::Unloaded;
            self.ratio[m] = ratio;
            self.rhs[m] = rhs;
            self.state[m] = self.warm[i];
            rhs_max = rhs_max.max(rhs);
            m += 1;
        }
        self.warm_half[..n].fill(0.0);
        self.warm[..n].fill(Load::Free);
        self.m = m;
        if m == 0 {
            return 0.0;
        }
        let tol = FEASIBILITY_TOL * rhs_max;
        // C2, C3 at the current half-lengths; then Newton's step on the loaded strips' C4.
        let mut settled = false;
        for _ in 0..LENGTH_ITERATIONS {
            self.length_solves += 1;
            self.assemble(m);
            if !self.pivot(m, tol) {
                self.fallbacks += 1;
                if !self.gauss_seidel(m) {
                    self.unconverged += 1;
                }
            }
            if self.settle_lengths(m) {
                settled = true;
                break;
            }
        }
        if !settled {
            self.unsettled += 1;
        }
        // C4.
        for r in 0..m {
            let i = self.strip[r];
            self.warm[i] = self.state[r];
            let y = self.load[r];
            if y > 0.0 {
                let a = self.half[r];
                self.warm_half[i] = a;
                self.warm_rhs[i] = self.rhs[r];
                out.set(i, a, params.e_star * PI * y / a, geom.ds);
            }
        }
        out.normal_force()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::normal::strips::PatchSummary;
    use crate::normal::test_support::{
        self, assert_continuous_sweep, awkward_geometries, awkward_geometry, hertz_case, no_nan,
        table, two_wells, AWKWARD_DELTAS, CURV_B, DELTA, SECOND_MINIMUM,
    };

    fn params() -> NormalParams {
        NormalParams::default()
    }

    fn run(geom: &StripGeometry, delta: f64) -> (StripSolution, f64) {
        test_support::run(&mut CoupledStrips::default(), geom, &params(), delta)
    }

    /// A wheel–rail-like gap: a Hertz core with a quartic flattening and a lateral tilt of A
    /// (the strips at the field side in contact with B falling to 0).
    fn flattened(n: usize, shift: f64) -> StripGeometry {
        StripGeometry::from_fn(-9e-3, 9e-3, n, move |s| {
            let u = s - shift;
            let f = 0.5 * u * u + 4e3 * u.powi(4) * (1.0 - 0.3 * u / 9e-3);
            (f, 8.0 * (1.0 + 20.0 * u), 0.5 + 24e3 * u * u)
        })
    }

    #[test]
    fn hertz_gap_converges_to_hertz() {
        // A/B = 0.2, 1, 5 on strips not aligned with the patch ([−1.07 b, 1.13 b]). Hertz's a(y),
        // p(y) satisfy C1 and C4 exactly (r_i is the patch's Hertz p0/(E* a)); the loads come from
        // collocating the strips' displacements at their centres, a midpoint rule in y whose error
        // is O((Δs/b)²): measured N/N_H − 1 = 4.9e−4, 1.3e−4, 3.3e−5 (A/B = 1) at 24, 48, 96
        // strips, pmax smaller. Bound 0.1 (Δs/b)² (8.4e−4 at 24 strips), and 96 strips at least 4×
        // better than 24. The area, a midpoint sum of 2a_i Δs, within its edge strips' error
        // ≤ 2e−3 (as ANALYN's, analyn.rs; measured ≤ 2.4e−4).
        for ratio in [0.2, 1.0, 5.0] {
            let (curv_a, h) = hertz_case(ratio);
            let mut errors = Vec::new();
            for n in [24, 48, 96] {
                let geom = StripGeometry::quadratic(curv_a, CURV_B, -1.07 * h.b, 1.13 * h.b, n);
                let mut model = CoupledStrips::default();
                let (sol, force) = test_support::run(&mut model, &geom, &params(), DELTA);
                no_nan(&sol, force);
                let sum = PatchSummary::of(&geom, &sol);
                let (e_n, e_area, e_p) = (
                    force / h.normal_force - 1.0,
                    sum.area / h.area() - 1.0,
                    sum.pmax / h.p0 - 1.0,
                );
                eprintln!(
                    "A/B = {ratio}, {n} strips: N/N_H − 1 = {e_n:+.2e}, area {e_area:+.2e}, \
                     pmax {e_p:+.2e}, {} strips loaded",
                    sum.strips_in_contact
                );
                let bound = 0.1 * (geom.ds / h.b).powi(2);
                assert!(e_n.abs() < bound && e_p.abs() < bound, "{n}");
                assert!(e_area.abs() < 2e-3);
                assert_eq!(model.fallbacks(), 0);
                assert_eq!(model.unsettled(), 0);
                errors.push(e_n.abs().max(e_p.abs()));
            }
            assert!(errors[2] < 0.25 * errors[0]);
        }
    }

    /// The symmetric part of G on the last solve's `m` candidates is positive definite
    /// (Cholesky succeeds): then G is a P-matrix and C3 has one solution.
    fn symmetric_part_is_positive_definite(model: &CoupledStrips, m: usize) -> bool {
        let g = |r: usize, c: usize| model.matrix[r * MAX_STRIPS + c];
        nalgebra::DMatrix::from_fn(m, m, |r, c| 0.5 * (g(r, c) + g(c, r)))
            .cholesky()
            .is_some()
    }

    #[test]
    fn solution_is_the_unique_complementary_one() {
        // On a Hertz gap, two wells, the B-crossing family and a flattened gap: loads ≥ 0;
        // residual u − (δ − f) ≥ −1e−12 (δ − f)_max where unloaded, |residual| ≤ 1e−10 (δ − f)_max
        // where loaded (the block solve's rounding); G's symmetric part positive definite
        // (uniqueness at the final half-lengths); projected Gauss–Seidel from zero loads reaches
        // the same loads; every loaded strip's reported peak and half-length on its local Hertz
        // ratio, p0 = ratio E* a (C1), within 1e−9 (the half-lengths settle to 1e−10).
        let (curv_a, h) = hertz_case(0.3);
        let cases = [
            (
                StripGeometry::quadratic(curv_a, CURV_B, -1.2 * h.b, 1.1 * h.b, 40),
                DELTA,
            ),
            (two_wells(60), 40e-6),
            (two_wells(120), 25e-6),
            (test_support::b_crossing_geometry(4e-3, 10e-3), DELTA),
            (flattened(24, 0.0), 60e-6),
            (flattened(48, 1e-3), 30e-6),
        ];
        for (geom, delta) in &cases {
            let mut model = CoupledStrips::default();
            let (sol, force) = test_support::run(&mut model, geom, &params(), *delta);
            no_nan(&sol, force);
            assert!(force > 0.0);
            let m = model.m;
            let scale = (0..m).map(|r| model.rhs[r]).fold(0.0, f64::max);
            let mut free = 0;
            for (state, y, residual) in model.candidates(m) {
                match state {
                    Load::Free => {
                        free += 1;
                        assert!(y >= 0.0 && residual.abs() <= 1e-10 * scale, "{residual}");
                    }
                    Load::Unloaded => {
                        assert!(y == 0.0 && residual >= -1e-12 * scale, "{residual}");
                    }
                }
            }
            for r in 0..m {
                let i = model.strip[r];
                if sol.force[i] > 0.0 {
                    let ratio = sol.pmax[i] / (params().e_star * sol.half_length[i]);
                    assert!((ratio / model.ratio[r] - 1.0).abs() <= 1e-9, "strip {i}");
                }
            }
            assert!(symmetric_part_is_positive_definite(&model, m));
            let pivoted: Vec<f64> = (0..m).map(|r| model.load[r]).collect();
            model.load[..m].fill(0.0);
            assert!(model.gauss_seidel(m));
            let largest = pivoted.iter().copied().fold(0.0, f64::max);
            for (gs, pv) in model.load[..m].iter().zip(&pivoted) {
                assert!((gs - pv).abs() <= 1e-9 * largest);
            }
            eprintln!(
                "{m} candidates, {free} loaded, N = {force:.1} N, {} solves of C2–C3",
                model.length_solves(),
            );
            assert_eq!(model.fallbacks(), 0);
            assert_eq!(model.unsettled(), 0);
        }
    }

    #[test]
    fn warm_start_does_not_change_the_solution() {
        // The same δ sequence up and down on one model (warm) and on fresh models (cold): both
        // settle the half-lengths to 1e−10, so N agrees to 1e−9 (measured 4e−12).
        let geom = two_wells(80);
        let mut warm = CoupledStrips::default();
        warm.prepare(&geom, &params(), table());
        let mut out = StripSolution::default();
        let mut worst: f64 = 0.0;
        for k in (0..60).chain((0..60).rev()) {
            let delta = 1e-6 * (1.0 + k as f64);
            let n_warm = warm.solve(&geom, &params(), table(), delta, &mut out);
            let (_, n_cold) = run(&geom, delta);
            let e = (n_warm - n_cold).abs() / n_cold;
            worst = worst.max(e);
            assert!(e <= 1e-9, "δ = {delta}: {e:e}");
        }
        eprintln!(
            "warm against cold: largest |ΔN|/N = {worst:.1e}, {} solves, {} unsettled",
            warm.length_solves(),
            warm.unsettled()
        );
        assert_eq!(warm.fallbacks(), 0);
        assert_eq!(warm.unsettled(), 0);
    }

    #[test]
    fn mirrored_gap_gives_mirrored_pressure() {
        let n = 61;
        let geom = flattened(n, 0.7e-3);
        let mut mirror = geom.clone();
        for i in 0..n {
            let j = n - 1 - i;
            mirror.s[i] = -geom.s[j];
            mirror.f[i] = geom.f[j];
            mirror.curv_a[i] = geom.curv_a[j];
            mirror.curv_b[i] = geom.curv_b[j];
        }
        let (sol, n1) = run(&geom, 40e-6);
        let (sol_m, n2) = run(&mirror, 40e-6);
        let p_max = sol.pmax.iter().copied().fold(0.0, f64::max);
        assert!(p_max > 0.0);
        for i in 0..n {
            let j = n - 1 - i;
            let a_max = sol.half_length.iter().copied().fold(0.0, f64::max);
            assert!((sol.half_length[i] - sol_m.half_length[j]).abs() <= 1e-9 * a_max);
            assert!((sol.pmax[i] - sol_m.pmax[j]).abs() <= 1e-9 * p_max);
        }
        assert!((n1 - n2).abs() <= 1e-9 * n1);
    }

    #[test]
    fn awkward_inputs_give_no_nan_and_no_panic() {
        let mut model = CoupledStrips::default();
        for (name, geom) in &awkward_geometries() {
            for delta in AWKWARD_DELTAS {
                for p in [
                    params(),
                    NormalParams {
                        b_min: f64::NAN,
                        e_star: f64::NAN,
                        ..params()
                    },
                ] {
                    let (sol, n) = test_support::run(&mut model, geom, &p, delta);
                    no_nan(&sol, n);
                    if delta.is_nan() || delta <= 0.0 || p.e_star.is_nan() {
                        assert_eq!(n, 0.0, "{name}");
                    }
                }
            }
        }
        assert_eq!(model.unconverged(), 0);
        // Two minima: both regions carry load, the hump between them none.
        let geom = &awkward_geometry("two minima");
        let (sol, _) = run(geom, 1e-6);
        let loaded_near = |target: f64| {
            (0..geom.n).any(|i| (geom.s[i] - target).abs() < 1e-3 && sol.force[i] > 0.0)
        };
        assert!(loaded_near(0.0) && loaded_near(SECOND_MINIMUM));
        assert!((0..geom.n)
            .any(|i| (geom.s[i] - 0.5 * SECOND_MINIMUM).abs() < 2e-4 && sol.force[i] == 0.0));
    }

    #[test]
    fn normal_force_is_continuous_while_b_crosses_zero() {
        assert_continuous_sweep(
            CoupledStrips::default,
            1.5 * hertz_case(1.0 / 1.5).1.b,
            DELTA,
        );
    }

    /// Whether every run of loaded strips in `sol` has at least 3 strips.
    fn runs_of_three(sol: &StripSolution) -> bool {
        let mut run = 0;
        for i in 0..=sol.n {
            if i < sol.n && sol.force[i] > 0.0 {
                run += 1;
            } else if run > 0 {
                if run < 3 {
                    return false;
                }
                run = 0;
            }
        }
        true
    }

    #[test]
    fn force_is_monotone_and_continuous_in_the_approach() {
        // N(δ) from below the first strip's entry through strips entering and a second region
        // appearing: non-decreasing; while every loaded region spans ≥ 3 strips no 0.5 % step of
        // δ raises N by more than the trend δ^{3/2} (× 1.0075) and a margin for the entering edge
        // strips (measured ≤ 1.0097 on the Hertz gap, the two wells and the flattened gap at 24
        // strips): × 1.02. A region's first strips rise steeper (not bounded here).
        for geom in [hertz_gap_48(), two_wells(60), flattened(24, 0.4e-3)] {
            let mut model = CoupledStrips::default();
            model.prepare(&geom, &params(), table());
            let mut out = StripSolution::default();
            let mut delta = 1e-8;
            let mut last = model.solve(&geom, &params(), table(), delta, &mut out);
            let mut last_regular = false;
            let mut largest_step: f64 = 0.0;
            while delta < 3e-4 {
                delta *= 1.005;
                let n = model.solve(&geom, &params(), table(), delta, &mut out);
                no_nan(&out, n);
                assert!(n >= last * (1.0 - 1e-12), "δ = {delta}: {n} < {last}");
                let regular = runs_of_three(&out) && last > 0.0;
                if regular && last_regular {
                    largest_step = largest_step.max(n / last);
                }
                last = n;
                last_regular = regular;
            }
            eprintln!("largest step N(1.005 δ)/N(δ) = {largest_step:.5}");
            assert!(largest_step < 1.02);
            assert_eq!(model.fallbacks(), 0);
        }
    }

    fn hertz_gap_48() -> StripGeometry {
        let (curv_a, h) = hertz_case(0.5);
        StripGeometry::quadratic(curv_a, CURV_B, -2.0 * h.b, 2.0 * h.b, 48)
    }

    #[test]
    fn force_is_continuous_in_a_shifted_gap() {
        // The gap slid across the strips by two strip widths at fixed δ (strips entering and
        // leaving): the largest change between neighbouring shifts, bisected 40 times (to
        // 1e−12 of the strip width), falls below 1e−9 of N (a jump would stay; measured ~1e−15:
        // an entering strip's load and length start from zero). And N stays
        // within the strip discretisation of its mean (1e−2).
        for geom_of in [
            (|e: f64| flattened(24, e)) as fn(f64) -> StripGeometry,
            |e: f64| {
                let (curv_a, h) = hertz_case(0.5);
                StripGeometry::from_fn(-2.0 * h.b, 2.0 * h.b, 24, move |s| {
                    (CURV_B * (s - e) * (s - e), curv_a, CURV_B)
                })
            },
        ] {
            let width = geom_of(0.0).ds;
            let force = |e: f64| run(&geom_of(e), 40e-6).1;
            let steps = 200;
            let shifts: Vec<f64> = (0..=steps)
                .map(|k| 2.0 * width * k as f64 / steps as f64)
                .collect();
            let forces: Vec<f64> = shifts.iter().map(|&e| force(e)).collect();
            let mean = forces.iter().sum::<f64>() / forces.len() as f64;
            let spread = forces
                .iter()
                .map(|n| (n / mean - 1.0).abs())
                .fold(0.0, f64::max);
            let k = (0..steps)
                .max_by(|&a, &b| {
                    let jump = |k: usize| (forces[k + 1] - forces[k]).abs();
                    jump(a).total_cmp(&jump(b))
                })
                .unwrap();
            let coarse = (forces[k + 1] - forces[k]).abs();
            let (mut lo, mut hi) = (shifts[k], shifts[k + 1]);
            let (mut f_lo, mut f_hi) = (forces[k], forces[k + 1]);
            for _ in 0..40 {
                let mid = 0.5 * (lo + hi);
                let f_mid = force(mid);
                if (f_mid - f_lo).abs() > (f_hi - f_mid).abs() {
                    (hi, f_hi) = (mid, f_mid);
                } else {
                    (lo, f_lo) = (mid, f_mid);
                }
            }
            let fine = (f_hi - f_lo).abs();
            eprintln!(
                "shifted gap: N {mean:.0} N ± {spread:.1e}, largest step {:.1e} N → {:.1e} N \
                 bisected",
                coarse / mean,
                fine / mean
            );
            assert!(fine < 1e-9 * mean);
            assert!(spread < 1e-2);
        }
    }
}
