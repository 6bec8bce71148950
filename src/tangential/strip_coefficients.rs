//! Strip-wise creep coefficients from the half-space: the strips of a patch coupled tangentially
//! in full adhesion, for FaStrip on non-elliptic patches.
//!
//! FaStrip (`crate::tangential::fastrip`) solves each strip as Kalker's 2-D strip theory and takes
//! the 3-D effects from one set of creep coefficients C11, C22, C23 — on a non-elliptic patch
//! those of an equivalent ellipse. Its linear regime then gives every strip the line force
//! (2/π) G C a_j ξ (a_j the strip's half-length): the same coefficient across the patch. Under
//! the exact theory the coefficient varies: strips in the middle of a wide patch behave like the
//! 2-D strip (C11 → π²/(4(1 − ν))), strips near its lateral ends and strips next to longer ones
//! carry more. This module computes one coefficient per strip and direction from the strips
//! themselves, coupled through the half-space, in Kalker's linear theory (full adhesion); FaStrip
//! then uses them strip by strip (`crate::tangential::strip_fastsim`, tangential option
//! "fastrip-coupled").
//!
//! # Equations
//!
//! Kalker, *Three-dimensional elastic bodies in rolling contact* (Kluwer 1990), ch. 2: in steady
//! rolling without slip the tangential surface displacement difference u (both bodies, identical
//! materials, shear modulus G, Poisson ratio ν) satisfies ∂u/∂x = w, the rigid slip (ξ, η) of a
//! pure creepage, where u follows from the traction q by Cerruti's solution,
//!
//! ```text
//! u_x = 1/(πG) ∫∫ [(1 − ν)/r + ν X²/r³] q_x dA,   u_y = 1/(πG) ∫∫ [(1 − ν)/r + ν Y²/r³] q_y dA
//! ```
//!
//! (the coupling terms ν X Y/r³ between q_x and u_y are left out, as in FaStrip). On an ellipse
//! the solution is q = t √((a(y) − x)/(a(y) + x)) with one amplitude t for the whole patch
//! (Kalker's linear theory: zero at the leading edge +a(y), singular at the trailing edge).
//!
//! **Choice 1, the traction.** Strip j (centre c_j along x, lateral position s_j, width w_j,
//! half-length a_j) carries q_j = t_j S((x − c_j)/a_j), S(ζ) = √((1 − ζ)/(1 + ζ)), uniform
//! across its width: one amplitude per strip and direction; its line force is π a_j t_j.
//!
//! **Choice 2, the condition.** ∂u/∂x = w at each strip's centre (c_i, s_i): n equations for the
//! n amplitudes. Integrating the kernel over strip j's width in closed form and its length in
//! the normalised u = (c_i − c_j)/a_j, v = Y/a_j (Y the lateral distance of the field point from
//! one of strip j's edges), with X = u − τ, r = √(X² + v²):
//!
//! ```text
//! ∂u_x/∂x (i) = Σ_j t_j/(πG) [A₁(u, v₊) − A₁(u, v₋)],   A₁ = −(1 − ν) P − ν Q
//! ∂u_y/∂x (i) = Σ_j t_j/(πG) [A₂(u, v₊) − A₂(u, v₋)],   A₂ = −P + ν Q
//! P(u, v) = PV ∫₋₁¹ S(τ) v/(X r) dτ = sgn v [H(u) + P̃(u, |v|)],   P̃(u, v) = −∫₋₁¹ S(τ) X/(r (r + v)) dτ
//! Q(u, v) = ∫₋₁¹ S(τ) X v/r³ dτ,    H(u) = PV ∫₋₁¹ S(τ)/(u − τ) dτ
//! ```
//!
//! with v₊, v₋ = (s_i − s_j ± w_j/2)/a_j. H is the 2-D strip's (Muskhelishvili): π on |u| < 1,
//! π (1 − √((u − 1)/(u + 1))) outside; P̃ and Q are regular for v > 0. A single infinitely wide
//! strip gives C11 = π²/(4(1 − ν)), C22 = π²/4, the strip theory's coefficients.
//!
//! **Coefficients.** With M τ = 1 (M_ij the brackets above, dimensionless) the amplitude for a
//! unit creepage is t = πG τ, and equating the line force π a_j t_j with strip theory's
//! −(2/π) G C a_j gives C_j = −π³ τ_j/2. On an ellipse they tend to Kalker's C11 and C22 as
//! the strips narrow (tested).
//!
//! # Evaluation
//!
//! P̃ and Q are tabulated once per process on |u| ≤ 4, 10⁻³ ≤ v ≤ 4 (u uniform, 64 nodes per
//! unit; ln v uniform, 16 per decade; bicubic Lagrange interpolation), each node by 8-point
//! Gauss–Legendre on panels graded geometrically towards τ = u in τ = −cos θ (which turns S dτ
//! into (1 + cos θ) dθ). Outside the table the integrands are smooth on the strip (|u| > 4 or
//! v > 4) and a 24-point midpoint rule in θ evaluates them (exponentially convergent). Below
//! v = 10⁻³ (a strip edge within a thousandth of a_j of another strip's centre) the table's
//! first column is used. The n × n systems for x and y are solved by Gaussian elimination on
//! buffers sized on first use (no allocation afterwards).
//!
//! # Known limits
//!
//! Linear theory only: the coefficients scale FaStrip's creepages strip by strip; saturation and
//! slip stay those of FaStrip's strip theory. One collocation point per strip; no coupling
//! between the x and y problems; spin enters FaStrip with the longitudinal coefficient of its
//! strip (its lever term ξ − φy is a longitudinal rigid slip). Strips are taken as parallel,
//! in the patch's plane.

use std::f64::consts::PI;
use std::sync::OnceLock;

use crate::numeric::dense::lu_solve;
use crate::numeric::interp::cubic_lagrange_weights;
use crate::numeric::quadrature::gauss_legendre;

/// Half-width of the table in u = (c_i − c_j)/a_j [-].
const TABLE_U: f64 = 4.0;
/// Nodes per unit of u.
const NODES_PER_U: f64 = 64.0;
/// Smallest tabulated v [-].
const TABLE_V_MIN: f64 = 1e-3;
/// Largest tabulated v [-].
const TABLE_V_MAX: f64 = 4.0;
/// Nodes per unit of ln v (16 per decade).
const NODES_PER_LN_V: f64 = 16.0 / std::f64::consts::LN_10;
/// Midpoint nodes in θ outside the table.
const FAR_NODES: usize = 24;
/// Ratio of successive panels of the graded quadrature.
const GRADING: f64 = 0.2;
/// Collocation point of strip i, x = c_i + κ a_i, as a fraction κ of its half-length
/// (module header, choice 2).
pub const COLLOCATION: f64 = 0.4;
/// Half-width in u of the bands around the strip's ends u = ±1 where, below v = [`HARD_V`],
/// the integrals vary on the scale v and are integrated directly instead of interpolated.
const HARD_U: f64 = 0.1;
/// See [`HARD_U`].
const HARD_V: f64 = 0.1;

/// H(u) = PV ∫₋₁¹ S(τ)/(u − τ) dτ, S(τ) = √((1 − τ)/(1 + τ)): the 2-D strip's ∂u/∂x kernel.
/// −∞ at u = −1 (the trailing edge's singularity seen from behind), π/u for |u| → ∞.
pub fn shape_hilbert(u: f64) -> f64 {
    if u.abs() <= 1.0 {
        PI
    } else {
        PI * (1.0 - ((u - 1.0) / (u + 1.0)).sqrt())
    }
}

/// The two integrands (P̃'s and Q's, without S) at X = u − τ and v > 0.
fn integrands(x: f64, v: f64) -> (f64, f64) {
    let r = x.hypot(v);
    (-x / (r * (r + v)), x * v / (r * r * r))
}

/// (P̃, Q) at (u, v > 0) by the midpoint rule with `nodes` nodes in θ, τ = −cos θ: accurate
/// where the integrands are smooth on the strip (far from τ = u, or v large).
fn midpoint_integrals(u: f64, v: f64, nodes: usize) -> (f64, f64) {
    let h = PI / nodes as f64;
    let (mut p, mut q) = (0.0, 0.0);
    for k in 0..nodes {
        let theta = (k as f64 + 0.5) * h;
        let (cos_half, cos) = ((0.5 * theta).cos(), theta.cos());
        // 1 + cos θ = 2 cos²(θ/2): no cancellation near θ = π.
        let weight = 2.0 * cos_half * cos_half;
        let (a, b) = integrands(u + cos, v);
        p += weight * a;
        q += weight * b;
    }
    (p * h, q * h)
}

/// (P̃, Q) at (u, v > 0) by 8-point Gauss–Legendre on panels in θ (τ = −cos θ) graded
/// geometrically towards θ* where τ = u (or the nearer end if |u| > 1), down to panels of
/// 10⁻³ min(v, √v) — the integrands' scale there.
pub fn graded_integrals(u: f64, v: f64) -> (f64, f64) {
    let theta_star = (-u.clamp(-1.0, 1.0)).acos();
    let smallest = 1e-3 * v.min(v.sqrt());
    let g = |theta: f64| {
        let c = (0.5 * theta).cos();
        let (a, b) = integrands(u + theta.cos(), v);
        (2.0 * c * c * a, 2.0 * c * c * b)
    };
    let (mut p, mut q) = (0.0, 0.0);
    for (from, to) in [(theta_star, 0.0), (theta_star, PI)] {
        let length = (to - from).abs();
        if length == 0.0 {
            continue;
        }
        // Breakpoints from + length q^k, k = K … 0, and the first panel [from, from + length q^K].
        let levels = ((smallest / length).ln() / GRADING.ln()).ceil().max(1.0) as i32;
        let mut inner = 0.0;
        for k in (0..=levels).rev() {
            let outer = length * GRADING.powi(k);
            let (lo, hi) = (inner, outer);
            let at = |s: f64| from + (to - from).signum() * s;
            p += gauss_legendre(lo, hi, |s| g(at(s)).0);
            q += gauss_legendre(lo, hi, |s| g(at(s)).1);
            inner = outer;
        }
    }
    (p, q)
}

/// P̃ and Q on the (u, ln v) grid, interleaved per node.
struct KernelTable {
    nodes_u: usize,
    nodes_v: usize,
    values: Vec<[f64; 2]>,
}

impl KernelTable {
    fn build() -> Self {
        let nodes_u = (2.0 * TABLE_U * NODES_PER_U).round() as usize + 1;
        let span = (TABLE_V_MAX / TABLE_V_MIN).ln();
        let nodes_v = (span * NODES_PER_LN_V).ceil() as usize + 1;
        let mut values = Vec::with_capacity(nodes_u * nodes_v);
        for j in 0..nodes_v {
            let v = TABLE_V_MIN * (j as f64 / NODES_PER_LN_V).exp();
            for i in 0..nodes_u {
                let u = -TABLE_U + i as f64 / NODES_PER_U;
                let (p, q) = graded_integrals(u, v);
                values.push([p, q]);
            }
        }
        Self {
            nodes_u,
            nodes_v,
            values,
        }
    }

    /// Bicubic interpolation at (u, v) inside the table's range (v clamped to its first column).
    fn at(&self, u: f64, v: f64) -> (f64, f64) {
        let x = (u + TABLE_U) * NODES_PER_U;
        let y = ((v.max(TABLE_V_MIN) / TABLE_V_MIN).ln() * NODES_PER_LN_V).max(0.0);
        let i = (x as usize).clamp(1, self.nodes_u - 3);
        let j = (y as usize).clamp(1, self.nodes_v - 3);
        let wu = cubic_lagrange_weights(x - i as f64);
        let wv = cubic_lagrange_weights(y - j as f64);
        let (mut p, mut q) = (0.0, 0.0);
        for (b, wb) in wv.iter().enumerate() {
            let row = &self.values[(j + b - 1) * self.nodes_u + i - 1..][..4];
            let (mut rp, mut rq) = (0.0, 0.0);
            for (value, wa) in row.iter().zip(&wu) {
                rp += wa * value[0];
                rq += wa * value[1];
            }
            p += wb * rp;
            q += wb * rq;
        }
        (p, q)
    }
}

/// The process-wide table (built on first use, ~0.1 s in a release build).
fn table() -> &'static KernelTable {
    static TABLE: OnceLock<KernelTable> = OnceLock::new();
    TABLE.get_or_init(KernelTable::build)
}

/// (P, Q) at (u, v), odd in v (zero at v = 0).
fn edge_integrals(u: f64, v: f64) -> (f64, f64) {
    if v == 0.0 || !(u.is_finite() && v.is_finite()) {
        return (0.0, 0.0);
    }
    let abs_v = v.abs();
    let near_end = (u.abs() - 1.0).abs() < HARD_U && abs_v < HARD_V;
    let (p_tilde, q) = if near_end {
        graded_integrals(u, abs_v.max(TABLE_V_MIN))
    } else if u.abs() <= TABLE_U && abs_v <= TABLE_V_MAX {
        table().at(u, abs_v)
    } else {
        midpoint_integrals(u, abs_v, FAR_NODES)
    };
    let p = shape_hilbert(u) + p_tilde;
    let sign = v.signum();
    (sign * p, sign * q)
}

/// One strip of the coupled problem.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CouplingStrip {
    /// Lateral position of the strip centre [m].
    pub s: f64,
    /// Width [m].
    pub width: f64,
    /// Centre along x [m].
    pub x_c: f64,
    /// Half-length [m]; strips with a_j ≤ 0 carry nothing.
    pub half_length: f64,
}

/// Solver of the strip-wise coefficients, with its buffers.
#[derive(Debug, Clone, Default)]
pub struct StripCoefficients {
    /// Matrices of the x and y problems (stride n).
    matrix_x: Vec<f64>,
    matrix_y: Vec<f64>,
    /// Right-hand sides, then the solutions τ.
    tau_x: Vec<f64>,
    tau_y: Vec<f64>,
    /// Indices of the loaded strips.
    loaded: Vec<usize>,
}

impl StripCoefficients {
    /// A solver with buffers for `n` strips (and the kernel table built): [`Self::solve`] then
    /// does not allocate for up to `n` loaded strips.
    pub fn with_capacity(n: usize) -> Self {
        let _ = table();
        Self {
            matrix_x: vec![0.0; n * n],
            matrix_y: vec![0.0; n * n],
            tau_x: Vec::with_capacity(n),
            tau_y: Vec::with_capacity(n),
            loaded: Vec::with_capacity(n),
        }
    }

    /// The coefficients (C11_j, C22_j) of `strips` with Poisson ratio `nu`, written into `out`
    /// (strips that carry nothing get (0, 0)); the buffers grow if more strips are loaded than
    /// they were sized for. Returns `false` if the system is singular or
    /// not finite (then `out` is left as it was): the caller keeps its ellipse's coefficients.
    pub fn solve(&mut self, strips: &[CouplingStrip], nu: f64, out: &mut [(f64, f64)]) -> bool {
        self.loaded.clear();
        self.loaded.extend((0..strips.len()).filter(|&j| {
            let s = &strips[j];
            s.half_length > 0.0
                && s.half_length.is_finite()
                && s.width > 0.0
                && s.width.is_finite()
                && s.s.is_finite()
                && s.x_c.is_finite()
        }));
        let n = self.loaded.len();
        if n == 0 || !(0.0..0.5).contains(&nu) {
            return false;
        }
        for buffer in [&mut self.matrix_x, &mut self.matrix_y] {
            if buffer.len() < n * n {
                buffer.resize(n * n, 0.0);
            }
        }
        for buffer in [&mut self.tau_x, &mut self.tau_y] {
            buffer.clear();
            buffer.resize(n, 1.0);
        }
        for (row, &i) in self.loaded.iter().enumerate() {
            let field = &strips[i];
            for (col, &j) in self.loaded.iter().enumerate() {
                let source = &strips[j];
                let a = source.half_length;
                let u = (field.x_c + COLLOCATION * field.half_length - source.x_c) / a;
                let offset = field.s - source.s;
                let half = 0.5 * source.width;
                let (p_hi, q_hi) = edge_integrals(u, (offset + half) / a);
                let (p_lo, q_lo) = edge_integrals(u, (offset - half) / a);
                let (p, q) = (p_hi - p_lo, q_hi - q_lo);
                self.matrix_x[row * n + col] = -(1.0 - nu) * p - nu * q;
                self.matrix_y[row * n + col] = -p + nu * q;
            }
        }
        if !(lu_solve(&mut self.matrix_x, n, n, &mut self.tau_x)
            && lu_solve(&mut self.matrix_y, n, n, &mut self.tau_y))
        {
            return false;
        }
        for o in out.iter_mut().take(strips.len()) {
            *o = (0.0, 0.0);
        }
        let scale = -0.5 * PI * PI * PI;
        for (k, &j) in self.loaded.iter().enumerate() {
            out[j] = (scale * self.tau_x[k], scale * self.tau_y[k]);
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tangential::kalker::creep_coefficients;

    #[test]
    fn hilbert_of_the_shape_matches_quadrature() {
        // H(u) outside the strip by the smooth midpoint rule on S(τ)/(u − τ) (no PV there).
        for u in [-5.0, -2.0, -1.2, 1.1, 1.5, 3.0, 10.0] {
            let n = 20_000;
            let h = PI / n as f64;
            let q: f64 = (0..n)
                .map(|k| {
                    let t = (k as f64 + 0.5) * h;
                    (1.0 + t.cos()) / (u + t.cos()) * h
                })
                .sum();
            assert!(
                (q - shape_hilbert(u)).abs() < 1e-6 * q.abs().max(1.0),
                "{u}: {q}"
            );
        }
    }

    #[test]
    fn graded_quadrature_matches_the_midpoint_rule_where_smooth() {
        for (u, v) in [(0.0, 3.0), (0.5, 6.0), (-0.9, 5.0), (6.0, 0.1), (-7.0, 2.0)] {
            let (p, q) = graded_integrals(u, v);
            let (pm, qm) = midpoint_integrals(u, v, 400);
            assert!((p - pm).abs() < 1e-10 && (q - qm).abs() < 1e-10, "{u} {v}");
        }
    }

    #[test]
    fn p_is_the_strip_kernel_near_and_its_direct_integral_far() {
        // v → ∞ (the 2-D strip): P → H(u) = π − π(u + 1/2)/(2v²) + …; v → 0: P → 0 (the odd
        // kernel's principal value).
        let (p, _) = edge_integrals(0.3, 1e3);
        assert!((p - PI).abs() < 1e-5, "{p}");
        // (At the table's smallest v, 1e−3: P = 0.0137, about v ln(1/v) times the slope.)
        let (p, _) = edge_integrals(0.3, 1e-3);
        assert!(p.abs() < 0.02 && p > 0.0, "{p}");
        // Off the strip (|u| > 1) P has no principal value: the midpoint rule on S v/(X r)
        // directly, against H + P̃ (table and far rule), also for negative v (odd).
        for (u, v) in [
            (30.0, 5.0),
            (-6.0, 0.5),
            (2.0, 0.3),
            (-3.0, 7.0),
            (1.5, -0.2),
        ] {
            let n = 20_000;
            let h = PI / n as f64;
            let direct: f64 = (0..n)
                .map(|k| {
                    let t = (k as f64 + 0.5) * h;
                    let x: f64 = u + t.cos();
                    (1.0 + t.cos()) * v / (x * x.hypot(v)) * h
                })
                .sum();
            let (p, _) = edge_integrals(u, v);
            assert!(
                (p - direct).abs() < 1e-3 * direct.abs().max(0.01),
                "{u} {v}: {p} {direct}"
            );
        }
    }

    #[test]
    fn table_matches_the_quadrature() {
        // 4000 quasi-random points of the table's range outside the bands near the strip's ends
        // (there the quadrature itself is used): relative to H's scale π.
        let mut worst: (f64, f64, f64) = (0.0, 0.0, 0.0);
        for k in 0..4000 {
            let u = -3.99 + 7.98 * ((k as f64 * 0.618_034) % 1.0);
            let v = 1e-3 * (4e3f64).powf((k as f64 * 0.414_214) % 1.0);
            if (u.abs() - 1.0).abs() < HARD_U && v < HARD_V {
                continue;
            }
            let (p, q) = table().at(u, v);
            let (pe, qe) = graded_integrals(u, v);
            let e = (p - pe).abs().max((q - qe).abs()) / PI;
            if e > worst.0 {
                worst = (e, u, v);
            }
        }
        println!("worst {worst:?}");
        assert!(worst.0 < 2e-3, "{worst:?}");
    }

    /// The strips of a Hertz ellipse of semi-axes a, b: n strips across [−b, b].
    fn ellipse_strips(a: f64, b: f64, n: usize) -> Vec<CouplingStrip> {
        let w = 2.0 * b / n as f64;
        (0..n)
            .map(|j| {
                let s = -b + (j as f64 + 0.5) * w;
                CouplingStrip {
                    s,
                    width: w,
                    x_c: 0.0,
                    half_length: a * (1.0 - (s / b).powi(2)).sqrt(),
                }
            })
            .collect()
    }

    #[test]
    fn ellipse_gives_kalkers_coefficients() {
        let nu = 0.28;
        for (a, b) in [(6e-3, 6e-3), (4e-3, 8e-3), (8e-3, 4e-3), (3e-3, 10e-3)] {
            let exact = creep_coefficients(a, b, nu).unwrap();
            let strips = ellipse_strips(a, b, 40);
            let mut out = vec![(0.0, 0.0); strips.len()];
            assert!(StripCoefficients::default().solve(&strips, nu, &mut out));
            // The patch's coefficient: line forces ∝ C_j a_j summed over the strips.
            let total: f64 = strips.iter().map(|s| s.half_length).sum();
            let c11: f64 = out
                .iter()
                .zip(&strips)
                .map(|(c, s)| c.0 * s.half_length)
                .sum::<f64>()
                / total;
            let c22: f64 = out
                .iter()
                .zip(&strips)
                .map(|(c, s)| c.1 * s.half_length)
                .sum::<f64>()
                / total;
            let centre = out[strips.len() / 2];
            println!(
                "a/b {:.2}: C11 {c11:.4} ({:.4}), C22 {c22:.4} ({:.4}); centre {:.4} {:.4}",
                a / b,
                exact.c11,
                exact.c22,
                centre.0,
                centre.1
            );
        }
    }
}
