//! STRIPES semi-Hertzian normal contact: Approach 3 ([`StripesB`], B corrected and smoothed) and a
//! reconstruction of Approach 4 ([`StripesAB`], A and B corrected, no smoothing).
//!
//! Papers: M. Sh. Sichani, R. Enblom, M. Berg, "Comparison of non-elliptic contact models: towards
//! fast and accurate modelling of wheel–rail contact", Wear 314 (2014) 111–117 (the comparison,
//! which names the approaches); J.-B. Ayasse, H. Chollet, "Determination of the wheel rail contact
//! patch in semi-Hertzian conditions", Vehicle System Dynamics 43 (2005) (STRIPES). Neither
//! paper's equations were at hand: what follows is **our reading, docs/theory.md §5.5 (S0–S6)
//! and §5.6**, with the labels used there.
//!
//! # Approach 3, [`StripesB`] (docs/theory.md §5.5, our reading)
//!
//! On the strips of [`StripGeometry`] (centres s_i, width Δs, first-contact point s = 0):
//!
//! * **S0** B_i is smoothed by a centred least-squares parabola (below), then floored:
//!   B_i ≤ B_min → B_min (Ayasse–Chollet's replacement rule, docs/theory.md §5.9).
//! * **S1** ε_i = ε_x(A_i/B_i), the local Hertz split A a² = ε_x δ (H6), from [`HertzShapeTable`].
//! * **S2** B*_i = B_i ε_i/(1 − ε_i).
//! * **S3** f*(s) = ∫₀ˢ (s − t) 2B*(t) dt, i.e. f*'' = 2B*, f*(0) = f*'(0) = 0.
//! * **S4** x_l,i = √((ε_i δ − f*_i)/A_i) where positive, else the strip is out of contact.
//! * **S5** p0_i = Hertz peak of the local ellipse with the strip's ORIGINAL (smoothed, floored)
//!   curvatures A_i, B_i and x-semi-axis a = x_l,i (derivation below).
//! * **S6** N = Σ (π/2) p0_i x_l,i Δs (V1). The δ iteration for a prescribed load (V2) is the
//!   caller's.
//!
//! Exactness on a Hertz gap f = B s², A constant: B* = Bε/(1 − ε) is constant, f* = B* s², and
//! x_l² = (εδ/A)(1 − s²/b²) with b² = εδ/B* = (1 − ε)δ/B = ε_y δ/B, which is the Hertz half-width
//! (H6); with S5 the strip pressure is p0_H √(1 − s²/b² − x²/a²), the Hertz pressure.
//!
//! # Approach 4, [`StripesAB`] (docs/theory.md §5.6: reconstructed, experimental)
//!
//! The template of docs/theory.md §5.6 with the cube-root split ε̃(A/B) = 1/(1 + (A/B)^{1/3})
//! ([`approximate_shape_factor`]):
//!
//! * B_i ← B_i + max(0, B_min − min_j B_j), the minimum taken over all strips of the geometry
//!   (the δ-independent patch; a constant shift, unlike Approach 3's replacement);
//! * ε_i = ε_x(A_i/B_i) (exact, from the table) and ε̃_i = ε̃(A_i/B_i);
//! * A*_i = A_i ε̃_i/ε_i,  B*_i = B_i ε̃_i/(1 − ε̃_i);  f* from 2B* as in S3;
//! * x_l,i = √((ε̃_i δ − f*_i)/A*_i); p0_i as S5 with the (shifted) curvatures A_i, B_i.
//!
//! The virtual-penetration factor of the template ("A* = A ε/ε_x") is taken as ε = ε̃: any
//! strip-wise ε cancels from x_l = √(ε_x (δ − f*/ε)/A), so this choice only fixes the names. On a
//! Hertz gap x_l² = a_H²(1 − s²/b̃²), b̃² = (1 − ε̃)δ/B: the length 2a_H is exact, the width is
//! b̃/b_H = √((1 − ε̃)/(1 − ε_x)): exact at A/B = 1, −2.08 % at A/B = 0.1, +1.01 % at A/B = 10
//! (tested), −8.6 % at A/B = 0.02. The strip peaks are p0_H √(1 − s²/b̃²), so p0 = p0_H and
//! N/N_H = b̃/b_H.
//!
//! # Choices where the published description leaves the reading open
//!
//! * **S0 filter (our choice):** a least-squares parabola in s, centred on each strip, over the
//!   strips
//!   |j − i| ≤ m, m = ⌊w n / 2⌋ with w = `params.b_smoothing` (the window spans the fraction w of
//!   the strip set's width nΔs; w = 0 or m = 0: no smoothing). Near the ends the window is
//!   truncated and the fit is one-sided. The parabola (not a moving average) because it
//!   reproduces any B that is quadratic in s over the window, also at the truncated ends, so a
//!   Hertz gap stays exact with smoothing on and a linear trend of B is not biased at the patch
//!   ends. Smoothing acts on the raw B (non-finite values first replaced by B_min), the floor after
//!   it, as S0 orders it. The window is a fraction of the strip set, not of the δ-dependent contact
//!   width: `prepare` is δ-independent.
//! * **S3 (our choice): double integration, not f·B*/B.** Both are exact on a Hertz gap.
//!   Integration is chosen because Sichani et al. (2014) say that smoothing B smooths the patch
//!   boundary, which holds only if the boundary is built from the (smoothed) B; with f·B*/B the
//!   smoothing would only enter through ε. Discretisation: 2B* is taken piecewise constant on the
//!   strips (B*_i on [s_i − Δs/2, s_i + Δs/2], extended by the end strip's value beyond the set)
//!   and integrated exactly from s = 0 outwards, so the first-contact point may lie anywhere in a
//!   strip (or outside the set): f*_i = ∫₀^{s_i} (s_i − t) 2B*(t) dt exactly for that
//!   piecewise-constant B*. Constant B* gives f* = B* s² to round-off (the exactness above); for
//!   smooth B* the error of f*_i is O(Δs²). Consequence: the corrected gap is convex, so a second
//!   minimum of f inside the strip set is not found: a gap with disjoint contact regions must be
//!   cut into separate patches (docs/theory.md §5.1) before STRIPES sees it.
//! * **S5 (our reading): local peak from the strip length.** The strip carries the Hertz ellipse of
//!   (A_i, B_i) whose x-semi-axis is a = x_l,i. That ellipse has the approach δ_e = A_i a²/ε_i
//!   (H6) and the peak p0 = E* √(δ_e (A_i + B_i)) P(A_i/B_i) (the table's coefficient), so
//!   p0_i = E* P_i x_l,i √(A_i (A_i + B_i)/ε_i) — the A-based form of docs/theory.md §2.4
//!   (circle: 4E*A a/π). Using B* here would break exactness.
//! * **A4 pressure (our choice):** the same S5 rule with the shifted curvatures (exact peak on a
//!   Hertz gap).
//! * **B_min:** `params.b_min` (default 0.1 1/m, CONTACT's 1e−4 1/mm); a non-positive or
//!   non-finite value falls back to the default.
//!
//! # Known limits
//!
//! * The corrected gap f* uses only B (S3): where the real surfaces diverge (B < 0 floored to
//!   B_min) the Approach-3 patch can extend far along s, possibly to the end of the strip set;
//!   Approach 4's constant shift lets one strongly concave strip anywhere in the set lift every B.
//! * Approach 4's ε̃ is a candidate, not the paper's formula: its width error grows for
//!   A/B → 0 (b̃/b_H = 0.914 at A/B = 0.02) — replace when Ayasse & Chollet 2005 is at hand.
//! * Strips with A_i ≤ 0 or non-finite A_i are out of contact (A > 0 is a precondition of the
//!   geometry); in the S3 integration they carry B*_i = B_i.
//! * Per-strip contact angles (the non-planar patch, §5.8) are the caller's.
//!
//! `prepare` and `solve` use fixed arrays of [`MAX_STRIPS`] inside the structs: no allocation, no
//! panic, and no NaN for any finite geometry and any δ (δ ≤ 0 or NaN: no contact).

use crate::geometry::strips::{PerStrip, StripGeometry};
use crate::normal::shape::{HertzShape, HertzShapeTable};
use crate::normal::strips::StripSolution;
use crate::normal::{NormalParams, StripModel};

/// Approximate Hertz split ε̃(A/B) = 1/(1 + (A/B)^{1/3}) of the Approach-4 reconstruction
/// (docs/theory.md §5.6, from a/b ≈ (B/A)^{2/3}); exact (½) at A = B. Curvatures A, B > 0 [1/m].
pub fn approximate_shape_factor(curv_a: f64, curv_b: f64) -> f64 {
    1.0 / (1.0 + (curv_a / curv_b).cbrt())
}

/// [`approximate_shape_factor`] from u = ln(A/B), which the strip loop has at hand for the shape
/// table: (A/B)^{1/3} = e^{u/3} (an exponential is a third of a cube root's cost here).
fn approximate_shape_factor_of_log(log_ratio: f64) -> f64 {
    1.0 / (1.0 + (log_ratio / 3.0).exp())
}

/// Local Hertz peak per unit half-length and unit E* (S5): the Hertz ellipse of curvatures
/// A, B > 0 with x-semi-axis a has p0 = E* · a · P √(A (A + B)/ε_x) [1/m].
fn hertz_peak_per_half_length(curv_a: f64, curv_b: f64, shape: &HertzShape) -> f64 {
    shape.p0_coeff * (curv_a * (curv_a + curv_b) / shape.eps_x).sqrt()
}

/// Hertz shape of curvatures A, B > 0 from the table (no error path: callers check positivity).
fn local_shape(table: &HertzShapeTable, curv_a: f64, curv_b: f64) -> HertzShape {
    table.at_log_ratio((curv_a / curv_b).ln())
}

/// A usable longitudinal curvature: finite and positive.
fn valid_curvature(curv: f64) -> bool {
    curv.is_finite() && curv > 0.0
}

/// The strips' lateral curvatures B_i into `out`, a non-finite one replaced by the floor `b_min`
/// [1/m].
fn finite_curv_b(curv_b: &[f64], b_min: f64, out: &mut [f64]) {
    for (b, &raw) in out.iter_mut().zip(curv_b) {
        *b = if raw.is_finite() { raw } else { b_min };
    }
}

/// Half window m (in strips) of the S0 filter: the window |j − i| ≤ m spans the fraction
/// `fraction` of the `n` strips (m = ⌊fraction·n/2⌋; 0 = no smoothing).
fn smoothing_half_window(fraction: f64, n: usize) -> usize {
    if fraction.is_nan() || fraction <= 0.0 {
        return 0;
    }
    let m = (0.5 * fraction * n as f64).floor();
    // Saturating: a window wider than the set is the whole set.
    if m >= n as f64 {
        n
    } else {
        m as usize
    }
}

/// S0 filter: `out[i]` = value at strip i of the least-squares parabola through `values[j]`,
/// |j − i| ≤ `half_window` (truncated at the ends), in the strip index (uniform strips). Fewer than
/// three points in the window (or `half_window` = 0) copy the value. `out.len()` ≥ `values.len()`.
fn smooth_least_squares_parabola(values: &[f64], half_window: usize, out: &mut [f64]) {
    let n = values.len();
    for i in 0..n {
        let lo = i.saturating_sub(half_window);
        let hi = (i + half_window).min(n - 1);
        out[i] = if hi - lo < 2 {
            values[i]
        } else {
            parabola_value_at_centre(&values[lo..=hi], i - lo, half_window)
        };
    }
}

/// Value at index `centre` of the least-squares parabola through `window` (≥ 3 points, unit
/// spacing). Offsets are scaled by `scale` (the half window) so the normal equations stay well
/// conditioned. A singular system (not reachable with ≥ 3 distinct points) returns the raw value.
fn parabola_value_at_centre(window: &[f64], centre: usize, scale: usize) -> f64 {
    let inv_scale = 1.0 / scale.max(1) as f64;
    // Moments Σ t^k (k = 0…4) and Σ v t^k (k = 0…2), t = (j − centre)/scale.
    let mut m = [0.0_f64; 5];
    let mut r = [0.0_f64; 3];
    for (j, &v) in window.iter().enumerate() {
        let t = (j as f64 - centre as f64) * inv_scale;
        let t2 = t * t;
        m[0] += 1.0;
        m[1] += t;
        m[2] += t2;
        m[3] += t2 * t;
        m[4] += t2 * t2;
        r[0] += v;
        r[1] += v * t;
        r[2] += v * t2;
    }
    // Normal equations [[m0 m1 m2] [m1 m2 m3] [m2 m3 m4]] c = r; c0 by Cramer's rule.
    let det3 = |c0: [f64; 3], c1: [f64; 3], c2: [f64; 3]| {
        c0[0] * (c1[1] * c2[2] - c1[2] * c2[1]) - c1[0] * (c0[1] * c2[2] - c0[2] * c2[1])
            + c2[0] * (c0[1] * c1[2] - c0[2] * c1[1])
    };
    let col1 = [m[1], m[2], m[3]];
    let col2 = [m[2], m[3], m[4]];
    let det = det3([m[0], m[1], m[2]], col1, col2);
    if det.is_nan() || det.abs() <= f64::EPSILON * m[0] * m[2] * m[4] {
        return window[centre];
    }
    det3(r, col1, col2) / det
}

/// Index of the strip holding the first-contact point s = 0, or the end strip nearest to it when
/// the set does not cover s = 0.
fn origin_strip(geom: &StripGeometry, n: usize) -> usize {
    if let Some(k) = geom.strip_at_origin() {
        if k < n {
            return k;
        }
    }
    if n == 0 || geom.s[0] > 0.0 {
        0
    } else {
        n - 1
    }
}

/// S3: f*_i = ∫₀^{s_i} (s_i − t) 2B*(t) dt at the strip centres, 2B* piecewise constant on the
/// strips (B*_i on [s_i − Δs/2, s_i + Δs/2]) and extended by the end strips' values; `origin` is
/// the strip holding s = 0 (or the nearest end strip). Exact (to round-off) for constant B*:
/// f* = B* s².
fn integrate_corrected_gap(
    s: &[f64],
    half_width: f64,
    origin: usize,
    curv_b_corr: &[f64],
    gap_corr: &mut [f64],
) {
    let n = s.len();
    if n == 0 {
        return;
    }
    // Inside the origin strip the curvature is constant: f* = B* s².
    let b0 = curv_b_corr[origin];
    gap_corr[origin] = b0 * s[origin] * s[origin];
    // March outwards carrying (edge position, f*, f*') across strip edges.
    let edge_r = s[origin] + half_width;
    let (mut e, mut f, mut df) = (edge_r, b0 * edge_r * edge_r, 2.0 * b0 * edge_r);
    for i in origin + 1..n {
        let (to_centre, to_edge) = (s[i] - e, s[i] + half_width - e);
        let b = curv_b_corr[i];
        gap_corr[i] = f + df * to_centre + b * to_centre * to_centre;
        f += df * to_edge + b * to_edge * to_edge;
        df += 2.0 * b * to_edge;
        e += to_edge;
    }
    let edge_l = s[origin] - half_width;
    let (mut e, mut f, mut df) = (edge_l, b0 * edge_l * edge_l, 2.0 * b0 * edge_l);
    for i in (0..origin).rev() {
        // Distances are negative going left; the Taylor expansion is the same.
        let (to_centre, to_edge) = (s[i] - e, s[i] - half_width - e);
        let b = curv_b_corr[i];
        gap_corr[i] = f + df * to_centre + b * to_centre * to_centre;
        f += df * to_edge + b * to_edge * to_edge;
        df += 2.0 * b * to_edge;
        e += to_edge;
    }
}

/// Per-strip data after the curvature corrections, common to both approaches: the strip touches
/// where f*_i < ε_v,i δ, with x_l,i = √((ε_v,i δ − f*_i)/A*_i) and p0_i = E* κ_i x_l,i.
#[derive(Debug, Clone, Default)]
struct CorrectedStrips {
    /// Strips prepared (≤ [`MAX_STRIPS`]).
    n: usize,
    /// Strip can be in contact (A_i finite and positive).
    active: PerStrip<bool>,
    /// Lateral curvature the model uses: smoothed and floored (A3) or shifted (A4) [1/m].
    curv_b: PerStrip<f64>,
    /// Virtual-penetration factor ε_v,i: ε_i (A3), ε̃_i (A4) [-].
    penetration_factor: PerStrip<f64>,
    /// Longitudinal curvature in S4: A_i (A3), A*_i (A4) [1/m].
    curv_a_corr: PerStrip<f64>,
    /// Corrected lateral curvature B*_i [1/m].
    curv_b_corr: PerStrip<f64>,
    /// Corrected gap f*_i at the strip centre (S3) [m].
    gap_corr: PerStrip<f64>,
    /// κ_i = P √(A (A + B)/ε_x) of the original curvatures (S5) [1/m].
    peak_per_half_length: PerStrip<f64>,
}

impl CorrectedStrips {
    /// S3 on the prepared B*: fills `gap_corr`.
    fn integrate(&mut self, geom: &StripGeometry) {
        let n = self.n;
        let origin = origin_strip(geom, n);
        integrate_corrected_gap(
            &geom.s[..n],
            0.5 * geom.ds,
            origin,
            &self.curv_b_corr[..n],
            &mut self.gap_corr[..n],
        );
    }

    /// S4–S6 at approach δ: writes `out` and returns N.
    fn solve(&self, geom: &StripGeometry, e_star: f64, delta: f64, out: &mut StripSolution) -> f64 {
        let Some(n) = out.begin(geom, delta, e_star) else {
            return 0.0;
        };
        for i in 0..n.min(self.n) {
            if !self.active[i] {
                continue;
            }
            // S4: interpenetration budget ε_v δ − f* of the strip's centre line.
            let budget = self.penetration_factor[i] * delta - self.gap_corr[i];
            if budget > 0.0 {
                let half_length = (budget / self.curv_a_corr[i]).sqrt();
                // S5
                let pmax = e_star * self.peak_per_half_length[i] * half_length;
                out.set(i, half_length, pmax, geom.ds);
            }
        }
        out.normal_force()
    }
}

/// STRIPES Approach 3: local B corrected by the Hertz split, smoothed and floored (S0–S6,
/// docs/theory.md §5.5). See the module documentation.
#[derive(Debug, Clone, Default)]
pub struct StripesB {
    strips: CorrectedStrips,
    /// Raw B with non-finite values replaced by B_min (input of the S0 filter) [1/m].
    curv_b_raw: PerStrip<f64>,
}

impl StripesB {
    /// Lateral curvature after S0 (smoothed, floored) per strip, from the last `prepare` [1/m].
    pub fn curv_b(&self) -> &[f64] {
        &self.strips.curv_b[..self.strips.n]
    }

    /// Shape factor ε_i (S1) per strip [-].
    pub fn shape_factor(&self) -> &[f64] {
        &self.strips.penetration_factor[..self.strips.n]
    }

    /// Corrected gap f*_i at the strip centres (S3) [m].
    pub fn corrected_gap(&self) -> &[f64] {
        &self.strips.gap_corr[..self.strips.n]
    }
}

impl StripModel for StripesB {
    fn prepare(&mut self, geom: &StripGeometry, params: &NormalParams, table: &HertzShapeTable) {
        let n = geom.len();
        let b_min = params.b_floor();
        finite_curv_b(&geom.curv_b[..n], b_min, &mut self.curv_b_raw[..n]);
        let st = &mut self.strips;
        st.n = n;
        // S0: smoothing, then the replacement floor.
        let half_window = smoothing_half_window(params.b_smoothing, n);
        smooth_least_squares_parabola(&self.curv_b_raw[..n], half_window, &mut st.curv_b[..n]);
        for b in &mut st.curv_b[..n] {
            // A NaN (overflowing fit) goes to the floor too.
            if b.is_nan() || *b <= b_min {
                *b = b_min;
            }
        }
        for i in 0..n {
            let (a, b) = (geom.curv_a[i], st.curv_b[i]);
            st.active[i] = valid_curvature(a);
            if st.active[i] {
                let shape = local_shape(table, a, b);
                let eps = shape.eps_x; // S1
                st.penetration_factor[i] = eps;
                st.curv_a_corr[i] = a;
                st.curv_b_corr[i] = b * eps / (1.0 - eps); // S2
                st.peak_per_half_length[i] = hertz_peak_per_half_length(a, b, &shape);
            } else {
                st.penetration_factor[i] = 0.0;
                st.curv_a_corr[i] = 0.0;
                st.curv_b_corr[i] = b;
                st.peak_per_half_length[i] = 0.0;
            }
        }
        st.integrate(geom); // S3
    }

    fn solve(
        &mut self,
        geom: &StripGeometry,
        params: &NormalParams,
        _table: &HertzShapeTable,
        delta: f64,
        out: &mut StripSolution,
    ) -> f64 {
        self.strips.solve(geom, params.e_star, delta, out)
    }
}

/// STRIPES Approach 4 (reconstructed, experimental): A and B corrected with the cube-root split
/// ε̃, B shifted by one constant, no smoothing (docs/theory.md §5.6). See the module documentation.
#[derive(Debug, Clone, Default)]
pub struct StripesAB {
    strips: CorrectedStrips,
    /// The constant added to every B by the shift rule in the last `prepare` [1/m].
    curv_b_shift: f64,
}

impl StripesAB {
    /// Lateral curvature after the shift per strip, from the last `prepare` [1/m].
    pub fn curv_b(&self) -> &[f64] {
        &self.strips.curv_b[..self.strips.n]
    }

    /// Shift max(0, B_min − min_j B_j) applied to every B [1/m].
    pub fn curv_b_shift(&self) -> f64 {
        self.curv_b_shift
    }

    /// Corrected gap f*_i at the strip centres [m].
    pub fn corrected_gap(&self) -> &[f64] {
        &self.strips.gap_corr[..self.strips.n]
    }
}

impl StripModel for StripesAB {
    fn prepare(&mut self, geom: &StripGeometry, params: &NormalParams, table: &HertzShapeTable) {
        let n = geom.len();
        let b_min = params.b_floor();
        let st = &mut self.strips;
        st.n = n;
        finite_curv_b(&geom.curv_b[..n], b_min, &mut st.curv_b[..n]);
        // Shift rule: one constant for the whole patch.
        let b_lowest = st.curv_b[..n].iter().copied().fold(f64::INFINITY, f64::min);
        self.curv_b_shift = if b_lowest < b_min {
            b_min - b_lowest
        } else {
            0.0
        };
        for i in 0..n {
            let b = st.curv_b[i] + self.curv_b_shift;
            // Round-off of the shift must not leave B below the floor.
            let b = if b > b_min { b } else { b_min };
            st.curv_b[i] = b;
            let a = geom.curv_a[i];
            st.active[i] = valid_curvature(a);
            if st.active[i] {
                let log_ratio = (a / b).ln();
                let shape = table.at_log_ratio(log_ratio);
                let eps_approx = approximate_shape_factor_of_log(log_ratio);
                st.penetration_factor[i] = eps_approx;
                st.curv_a_corr[i] = a * eps_approx / shape.eps_x;
                st.curv_b_corr[i] = b * eps_approx / (1.0 - eps_approx);
                st.peak_per_half_length[i] = hertz_peak_per_half_length(a, b, &shape);
            } else {
                st.penetration_factor[i] = 0.0;
                st.curv_a_corr[i] = 0.0;
                st.curv_b_corr[i] = b;
                st.peak_per_half_length[i] = 0.0;
            }
        }
        st.integrate(geom);
    }

    fn solve(
        &mut self,
        geom: &StripGeometry,
        params: &NormalParams,
        _table: &HertzShapeTable,
        delta: f64,
        out: &mut StripSolution,
    ) -> f64 {
        self.strips.solve(geom, params.e_star, delta, out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::strips::MAX_STRIPS;
    use crate::normal::strips::PatchSummary;
    use crate::normal::test_support::{
        assert_continuous_sweep, awkward_geometries, hertz_case, no_nan, run, table,
        AWKWARD_DELTAS, CURV_B, DELTA,
    };

    /// Tolerance of per-strip comparisons with exact Hertz, normalised by a² or p0: the table's
    /// 1e−7 relative accuracy of ε_x and P (strips.rs), amplified at most a few times by
    /// x_l² = (εδ − B* s²)/A (two terms of size ≤ εδ).
    const TABLE_TOL: f64 = 1e-6;
    /// Curvature ratios A/B of the exactness check (docs/theory.md §5.5).
    const RATIOS: [f64; 5] = [1.0, 1.0 / 3.0, 0.1, 3.0, 0.02];

    fn params() -> NormalParams {
        NormalParams::default()
    }

    /// Largest deviation of the strips from the Hertz-like pressure x_l² = a²(1 − s²/w²),
    /// p0_i = p0 √(1 − s²/w²) (w: lateral semi-axis), normalised by a² and p0; also checks that
    /// exactly the strips with |s| < w are in contact.
    fn profile_error(geom: &StripGeometry, sol: &StripSolution, a: f64, w: f64, p0: f64) -> f64 {
        let mut err: f64 = 0.0;
        for i in 0..geom.n {
            let q = 1.0 - (geom.s[i] / w).powi(2);
            assert_eq!(
                sol.half_length[i] > 0.0,
                q > 0.0,
                "strip {i}, s = {}",
                geom.s[i]
            );
            let q = q.max(0.0);
            err = err.max((sol.half_length[i].powi(2) - a * a * q).abs() / (a * a));
            err = err.max((sol.pmax[i] - p0 * q.sqrt()).abs() / p0);
        }
        err
    }

    #[test]
    fn stripes_b_reproduces_hertz() {
        // 199 strips on [−b, b]: a strip centred on s = 0 and the Hertz edges on strip edges, so
        // a and p0 are sampled exactly and the V1 midpoint sum of ∝ (1 − s²/b²) is exactly
        // N_H (1 + Δs²/(8b²)) (1.26e−5 here; 400 strips are beyond MAX_STRIPS).
        for ratio in RATIOS {
            let (curv_a, h) = hertz_case(ratio);
            let geom = StripGeometry::quadratic(curv_a, CURV_B, -h.b, h.b, 199);
            let (sol, n) = run(&mut StripesB::default(), &geom, &params(), DELTA);
            let sum = PatchSummary::of(&geom, &sol);
            let err = profile_error(&geom, &sol, h.a, h.b, h.p0);
            let midpoint = 1.0 + (geom.ds / h.b).powi(2) / 8.0;
            eprintln!(
                "A/B = {ratio:.4}: profile {err:.2e}, a {:.2e}, p0 {:.2e}, N/N_H − 1 {:.2e}, \
                 N/(N_H·midpoint) − 1 {:.2e}",
                sum.length / (2.0 * h.a) - 1.0,
                sum.pmax / h.p0 - 1.0,
                n / h.normal_force - 1.0,
                n / (h.normal_force * midpoint) - 1.0
            );
            assert!(err < TABLE_TOL);
            assert!((sum.length / (2.0 * h.a) - 1.0).abs() < TABLE_TOL);
            assert!((sum.pmax / h.p0 - 1.0).abs() < TABLE_TOL);
            assert!((sum.width / (2.0 * h.b) - 1.0).abs() < 1e-12);
            assert!((n / (h.normal_force * midpoint) - 1.0).abs() < TABLE_TOL);
            assert!((n / h.normal_force - 1.0).abs() < 1.3e-5);
        }
    }

    #[test]
    fn stripes_b_hertz_exact_wherever_the_first_contact_point_lies() {
        // Off-centre origin (inside a strip at an arbitrary offset) and an origin outside the
        // strip set: S3's piecewise-constant integration from s = 0 keeps f* = B* s².
        let (curv_a, h) = hertz_case(0.1);
        for (lo, hi, n) in [
            (-1.3, 1.17, 200),
            (-0.83, 1.4, 37),
            (0.2, 1.5, 60),
            (-1.5, -0.1, 1),
        ] {
            let geom = StripGeometry::quadratic(curv_a, CURV_B, lo * h.b, hi * h.b, n);
            let mut model = StripesB::default();
            let (sol, _) = run(&mut model, &geom, &params(), DELTA);
            let err = profile_error(&geom, &sol, h.a, h.b, h.p0);
            eprintln!("range [{lo}, {hi}]·b, {n} strips: profile {err:.2e}");
            assert!(err < TABLE_TOL);
            let b_star = CURV_B * model.shape_factor()[0] / (1.0 - model.shape_factor()[0]);
            for (i, f) in model.corrected_gap().iter().enumerate() {
                let expect = b_star * geom.s[i] * geom.s[i];
                assert!(
                    (f - expect).abs() <= 1e-12 * b_star * h.b * h.b,
                    "strip {i}"
                );
            }
        }
    }

    #[test]
    fn shape_factor_from_the_log_ratio_equals_the_cube_root_form() {
        // Same function, two formulas: agreement to a few ulps (1e−14 relative) over
        // A/B = 1e−6 … 1e6.
        for k in -60..=60 {
            let ratio = 10f64.powf(0.1 * k as f64);
            let direct = approximate_shape_factor(ratio * CURV_B, CURV_B);
            let of_log = approximate_shape_factor_of_log(ratio.ln());
            assert!(
                (of_log / direct - 1.0).abs() < 1e-14,
                "{ratio}: {of_log} {direct}"
            );
        }
    }

    #[test]
    fn stripes_ab_length_exact_width_within_2_1_percent() {
        // Hertz gap: x_l² = a_H²(1 − s²/b̃²), b̃² = (1 − ε̃)δ/B, p0_i = p0_H √(1 − s²/b̃²).
        let mut worst: f64 = 0.0;
        let mut u: f64 = 0.1_f64.ln();
        while u <= 10.0_f64.ln() + 1e-9 {
            let ratio = u.exp();
            let (curv_a, h) = hertz_case(ratio);
            let eps_approx = approximate_shape_factor(curv_a, CURV_B);
            let width = ((1.0 - eps_approx) * DELTA / CURV_B).sqrt();
            let geom = StripGeometry::quadratic(curv_a, CURV_B, -1.1 * h.b, 1.1 * h.b, 199);
            let (sol, n) = run(&mut StripesAB::default(), &geom, &params(), DELTA);
            let sum = PatchSummary::of(&geom, &sol);
            assert!(profile_error(&geom, &sol, h.a, width, h.p0) < TABLE_TOL);
            assert!((sum.length / (2.0 * h.a) - 1.0).abs() < TABLE_TOL);
            assert!((sum.pmax / h.p0 - 1.0).abs() < TABLE_TOL);
            // N of the strip sum vs (2/3)π a b̃ p0: the midpoint-sum error (Δs/b)² ≈ 1e−4.
            let n_model = 2.0 / 3.0 * std::f64::consts::PI * h.a * width * h.p0;
            assert!((n / n_model - 1.0).abs() < 2e-4, "{}", n / n_model - 1.0);
            worst = worst.max((width / h.b - 1.0).abs());
            u += 0.05;
        }
        eprintln!("A4 worst |b̃/b_H − 1| on 0.1 ≤ A/B ≤ 10: {worst:.4}");
        assert!(worst < 0.021);
        for (ratio, expect) in [(0.1, 0.9792), (10.0, 1.0101), (0.02, 0.914)] {
            let (curv_a, h) = hertz_case(ratio);
            let eps_approx = approximate_shape_factor(curv_a, CURV_B);
            let width = ((1.0 - eps_approx) * DELTA / CURV_B).sqrt();
            eprintln!("A/B = {ratio}: b̃/b_H = {:.4}", width / h.b);
            assert!((width / h.b - expect).abs() < 1e-3);
        }
        // Exact at A/B = 1.
        let (curv_a, h) = hertz_case(1.0);
        let geom = StripGeometry::quadratic(curv_a, CURV_B, -h.b, h.b, 199);
        let (sol, _) = run(&mut StripesAB::default(), &geom, &params(), DELTA);
        assert!(profile_error(&geom, &sol, h.a, h.b, h.p0) < TABLE_TOL);
    }

    #[test]
    fn stripes_ab_shift_rule_and_no_smoothing() {
        // min B = −2 → every B shifted by B_min + 2; a positive minimum above B_min: no shift.
        let p = params();
        let geom = StripGeometry::from_fn(-0.01, 0.01, 50, |s| (s * s, 1.0, 1.0 - 3e4 * s * s));
        let mut model = StripesAB::default();
        model.prepare(&geom, &p, table());
        let b_low = (0..geom.n)
            .map(|i| geom.curv_b[i])
            .fold(f64::INFINITY, f64::min);
        assert!((model.curv_b_shift() - (p.b_min - b_low)).abs() < 1e-12);
        for i in 0..geom.n {
            assert!((model.curv_b()[i] - (geom.curv_b[i] + p.b_min - b_low)).abs() < 1e-12);
        }
        let lowest = model.curv_b().iter().copied().fold(f64::INFINITY, f64::min);
        assert!((lowest - p.b_min).abs() < 1e-12);
        let geom = StripGeometry::quadratic(1.0, 2.0, -0.01, 0.01, 50);
        model.prepare(&geom, &p, table());
        assert_eq!(model.curv_b_shift(), 0.0);
        // The smoothing parameter has no effect.
        let spiky = spike_geometry();
        let (a, _) = run(&mut StripesAB::default(), &spiky, &p, DELTA);
        let rough = NormalParams {
            b_smoothing: 0.0,
            ..p
        };
        let (b, _) = run(&mut StripesAB::default(), &spiky, &rough, DELTA);
        assert_eq!(a.pmax, b.pmax);
        assert_eq!(a.half_length, b.half_length);
    }

    /// f(s) = ∫₀ˢ (s − t) 2B(t) dt by composite Simpson (tests: a gap consistent with B).
    fn gap_of(curv_b: impl Fn(f64) -> f64, s: f64) -> f64 {
        const PANELS: usize = 2000;
        let h = s / PANELS as f64;
        let g = |t: f64| (s - t) * 2.0 * curv_b(t);
        let mut sum = g(0.0) + g(s);
        for k in 1..PANELS {
            sum += if k % 2 == 1 { 4.0 } else { 2.0 } * g(k as f64 * h);
        }
        sum * h / 3.0
    }

    /// Half-width of the spike-test patch's Hertz part [m].
    fn spike_half_width() -> f64 {
        hertz_case(1.0).1.b
    }

    /// A Hertz gap (A = B = 1.5 1/m) with a narrow lateral-curvature spike (×20, Gaussian of
    /// 1.5 strip widths) at 0.4 b inside the patch; 120 strips on [−1.5 b, 1.5 b].
    fn spike_geometry() -> StripGeometry {
        let b = spike_half_width();
        let n = 120;
        let sigma = 1.5 * 3.0 * b / n as f64;
        let curv_b = move |s: f64| CURV_B * (1.0 + 20.0 * (-((s - 0.4 * b) / sigma).powi(2)).exp());
        StripGeometry::from_fn(-1.5 * b, 1.5 * b, n, |s| {
            (gap_of(curv_b, s), CURV_B, curv_b(s))
        })
    }

    #[test]
    fn smoothing_flattens_a_curvature_spike() {
        let geom = spike_geometry();
        let rough = NormalParams {
            b_smoothing: 0.0,
            ..params()
        };
        let (sharp, n_sharp) = run(&mut StripesB::default(), &geom, &rough, DELTA);
        let (smooth, n_smooth) = run(&mut StripesB::default(), &geom, &params(), DELTA);
        let (p_sharp, p_smooth) = (
            PatchSummary::of(&geom, &sharp).pmax,
            PatchSummary::of(&geom, &smooth).pmax,
        );
        let p_hertz = hertz_case(1.0).1.p0;
        eprintln!(
            "spike: pmax/p0_H {:.3} raw, {:.3} smoothed; N {n_sharp:.1} / {n_smooth:.1} N",
            p_sharp / p_hertz,
            p_smooth / p_hertz
        );
        assert!(p_smooth < 0.9 * p_sharp);
    }

    #[test]
    fn least_squares_parabola_keeps_quadratics_and_damps_spikes() {
        let n = 40;
        let mut values = [0.0; MAX_STRIPS];
        let mut out = [0.0; MAX_STRIPS];
        for (i, v) in values[..n].iter_mut().enumerate() {
            let t = i as f64;
            *v = 3.0 - 0.2 * t + 0.01 * t * t;
        }
        for m in [1, 2, 4, 10, 40] {
            smooth_least_squares_parabola(&values[..n], m, &mut out[..n]);
            for i in 0..n {
                assert!((out[i] - values[i]).abs() < 1e-12, "m = {m}, i = {i}");
            }
        }
        values[..n].fill(1.0);
        values[20] = 11.0;
        smooth_least_squares_parabola(&values[..n], 4, &mut out[..n]);
        // Savitzky–Golay 9-point quadratic: centre weight 59/231.
        assert!((out[20] - (1.0 + 10.0 * 59.0 / 231.0)).abs() < 1e-12);
        assert_eq!(smoothing_half_window(0.2, 40), 4);
        assert_eq!(smoothing_half_window(0.0, 40), 0);
        assert_eq!(smoothing_half_window(f64::NAN, 40), 0);
        assert_eq!(smoothing_half_window(5.0, 40), 40);
    }

    /// An asymmetric gap with a concave end: B = B0(1 − 1.5 s/w), f consistent,
    /// A = A0(1 + 0.3 s/w).
    fn asymmetric_gap(w: f64) -> impl Fn(f64) -> (f64, f64, f64) {
        move |s: f64| {
            let (b0, a0) = (CURV_B, 0.8);
            (
                b0 * s * s * (1.0 - 0.5 * s / w),
                a0 * (1.0 + 0.3 * s / w),
                b0 * (1.0 - 1.5 * s / w),
            )
        }
    }

    fn assert_mirrored(model: &mut impl StripModel, params: &NormalParams) {
        let w = 1.5 * hertz_case(1.0).1.b;
        let gap = asymmetric_gap(w);
        let n = 77;
        let geom = StripGeometry::from_fn(-w, 0.7 * w, n, &gap);
        let mirror = StripGeometry::from_fn(-0.7 * w, w, n, |s| gap(-s));
        let (sol, n1) = run(model, &geom, params, 2.0 * DELTA);
        let (sol_m, n2) = run(model, &mirror, params, 2.0 * DELTA);
        let x_max = sol.half_length.iter().copied().fold(0.0, f64::max);
        let p_max = sol.pmax.iter().copied().fold(0.0, f64::max);
        assert!(x_max > 0.0);
        for i in 0..n {
            let j = n - 1 - i;
            assert!(
                (sol.half_length[i] - sol_m.half_length[j]).abs() <= 1e-9 * x_max,
                "{i}"
            );
            assert!((sol.pmax[i] - sol_m.pmax[j]).abs() <= 1e-9 * p_max, "{i}");
        }
        assert!((n1 - n2).abs() <= 1e-9 * n1);
    }

    #[test]
    fn mirrored_gap_gives_mirrored_pressure() {
        assert_mirrored(&mut StripesB::default(), &params());
        assert_mirrored(&mut StripesAB::default(), &params());
    }

    #[test]
    fn normal_force_converges_with_strip_count() {
        // Strip set not aligned with the patch. V1 is a midpoint sum of x_l·p0 ∝ (1 − s²/b²):
        // Δs²/(6b) from the interior and at most Δs²/(4b) from each cut edge (the integrand
        // vanishes linearly there, slope 2/b), so |N/N_lim − 1| ≤ (Δs/b)²/2 (of 4b/3).
        // Limits: Hertz gap, STRIPES-B: N_H; STRIPES-AB: (2/3)π a_H b̃ p0_H; non-Hertzian gap
        // f = B0 s² + c s⁴: the 200-strip result (bound doubled: its patch is narrower than b_H).
        let (curv_a, h) = hertz_case(1.0 / 3.0);
        let eps_approx = approximate_shape_factor(curv_a, CURV_B);
        let width_ab = ((1.0 - eps_approx) * DELTA / CURV_B).sqrt();
        let limit_ab = 2.0 / 3.0 * std::f64::consts::PI * h.a * width_ab * h.p0;
        let hertz_gap = |s: f64| (CURV_B * s * s, curv_a, CURV_B);
        let quartic = |s: f64| {
            let c = CURV_B / (3.0 * h.b * h.b);
            (
                CURV_B * s * s + c * s.powi(4),
                curv_a,
                CURV_B + 6.0 * c * s * s,
            )
        };
        for (model, limit) in [(0, h.normal_force), (1, limit_ab)] {
            let force = |n: usize, gap: &dyn Fn(f64) -> (f64, f64, f64)| {
                let geom = StripGeometry::from_fn(-1.3 * h.b, 1.17 * h.b, n, gap);
                let n_total = if model == 0 {
                    run(&mut StripesB::default(), &geom, &params(), DELTA).1
                } else {
                    run(&mut StripesAB::default(), &geom, &params(), DELTA).1
                };
                (n_total, geom.ds / h.b)
            };
            let (n_ref_q, step_ref) = force(MAX_STRIPS, &quartic);
            for n in [25, 50, 100, MAX_STRIPS] {
                let (n_h, step) = force(n, &hertz_gap);
                let err_h = (n_h / limit - 1.0).abs();
                let err_q = (force(n, &quartic).0 / n_ref_q - 1.0).abs();
                eprintln!(
                    "model {model}, {n} strips, Δs/b = {step:.4}: Hertz gap |N/N_lim − 1| = \
                     {err_h:.2e} (bound {:.2e}), quartic vs {MAX_STRIPS}: {err_q:.2e}",
                    0.5 * step * step
                );
                assert!(err_h <= 0.5 * step * step);
                assert!(err_q <= step * step + step_ref * step_ref);
            }
        }
    }

    fn assert_robust(model: &mut impl StripModel) {
        for (name, geom) in awkward_geometries() {
            for b_smoothing in [0.0, 0.2, 3.0] {
                let p = NormalParams {
                    b_smoothing,
                    ..params()
                };
                for delta in AWKWARD_DELTAS {
                    let (sol, n) = run(model, &geom, &p, delta);
                    no_nan(&sol, n);
                    if delta.is_nan() || delta <= 0.0 {
                        assert_eq!(n, 0.0, "{name}, δ = {delta}");
                    }
                    if name == "one strip" && delta == 5e-5 {
                        assert!(n > 0.0, "{name}");
                    }
                }
            }
        }
        // Unusable parameters fall back to defaults or give no contact, never NaN.
        let geom = StripGeometry::quadratic(1.0, -2.0, -0.01, 0.01, 20);
        for p in [
            NormalParams {
                b_min: 0.0,
                ..params()
            },
            NormalParams {
                b_min: f64::NAN,
                e_star: -1.0,
                b_smoothing: f64::NAN,
                ..params()
            },
        ] {
            let (sol, n) = run(model, &geom, &p, DELTA);
            no_nan(&sol, n);
        }
    }

    #[test]
    fn awkward_inputs_give_no_nan_and_no_panic() {
        assert_robust(&mut StripesB::default());
        assert_robust(&mut StripesAB::default());
    }

    #[test]
    fn normal_force_is_continuous_while_b_crosses_zero() {
        // Deep enough that STRIPES-AB's shifted (stiffer) B still lets B < 0 strips touch.
        let w = 1.5 * hertz_case(1.0 / 1.5).1.b;
        assert_continuous_sweep(StripesB::default, w, 3.0 * DELTA);
        assert_continuous_sweep(StripesAB::default, w, 3.0 * DELTA);
    }
}
