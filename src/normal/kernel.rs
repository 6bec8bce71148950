//! The Boussinesq kernel of a semi-elliptic strip load, shared by the strip models that couple
//! strips through the half-space (`kik_piotrowski`'s D3, `coupled_strips`' influence matrix).
//!
//! A strip of half-length c carrying p(x) = p0 √(1 − x²/c²) displaces the surface at lateral
//! distance y (x = 0) by (p0/(πE* c)) I(c, y) per unit width, with (KP6, docs/theory.md §5.4)
//! I(c, y) = ∫_{−c}^{c} √(c² − x²)/√(x² + y²) dx = 2√(c² + y²) [K(k) − E(k)], k² = c²/(c² + y²);
//! a strip of width Δs integrates I over y. The integral J(c, Y) = ∫₀^Y I dy is split into the
//! closed-form integral Φ of a model kernel S = 2c asinh(α/|y|) with I's log singularity and a
//! bounded remainder R = I − S ([`kernel_integral_from_origin`]), tabulated scale-free
//! ([`RemainderTable`]); [`ScaledStripIntegral`] tabulates Ĵ(T) = J(1, T) itself for the
//! coupled strips, whose influence matrix needs n² strip integrals per solve. Kik–Piotrowski's
//! module documentation details the rules and their measured accuracy.

use std::f64::consts::{E, FRAC_PI_2, PI};

use crate::numeric::elliptic::complete_elliptic_from_complementary;
use crate::numeric::interp::UniformCubic;
use crate::numeric::quadrature::gauss_legendre;

/// Scale of the model kernel S(y) = 2c asinh(α/|y|): α = (2/e) c makes S's log singularity
/// 2c(ln(4c/|y|) − 1) equal to I's (KP6 small-y asymptote, docs/theory.md §5.4).
const MODEL_KERNEL_SCALE: f64 = 2.0 / E;

/// |y| ≤ this × c counts as y = 0 in the kernel remainder R = I − S, whose limit there is 0:
/// R = O((y²/c) ln(c/|y|)) < 1e−16 c below it, and I would need K at k' = 0 (infinite).
const REMAINDER_ORIGIN: f64 = 1e-9;

/// Beyond |y| = this × c the remainder R is integrated by its two-term expansion in c/|y|: the
/// neglected ≈ 0.041 c⁶/y⁵ term integrates to < 1e−8 c², against ∫₀^Y I dy > 8 c² there.
const TAIL_START: f64 = 32.0;

/// Leading coefficient of R = I − S for |y| ≫ c: R ≈ TAIL_R1 c²/|y| + TAIL_R3 c⁴/|y|³, from
/// I = πc²/(2y) − πc⁴/(16y³) + … and S = (4/e)c²/y − (8/(3e³))c⁴/y³ + ….
const TAIL_R1: f64 = FRAC_PI_2 - 4.0 / E;
/// Second coefficient of the expansion of R (see [`TAIL_R1`]).
const TAIL_R3: f64 = 8.0 / (3.0 * E * E * E) - PI / 16.0;

/// KP6: I(c, y) = ∫_{−c}^{c} √(c² − x²)/√(x² + y²) dx = 2√(c² + y²) [K(k) − E(k)],
/// k² = c²/(c² + y²) [m], for a strip half-length `c` = c > 0 and lateral distance `y` ≠ 0 [m].
/// Log-singular at y = 0 (returns +∞ there); 0 for c ≤ 0 or non-finite input.
pub fn inner_integral(c: f64, y: f64) -> f64 {
    if !(c.is_finite() && c > 0.0 && y.is_finite()) {
        return 0.0;
    }
    let y = y.abs();
    if y == 0.0 {
        return f64::INFINITY;
    }
    let radius = c.hypot(y);
    // Complementary modulus k' = |y|/√(c² + y²) ∈ (0, 1]; floored against underflow for
    // |y| ≪ c (then K ≈ ln(4/k') is still the right log).
    let k_prime = (y / radius).clamp(f64::MIN_POSITIVE, 1.0);
    2.0 * radius * complete_elliptic_from_complementary(k_prime).k_minus_e
}

/// asinh z for z ≥ 0 (or +∞) in closed form, ln(z + √(z² + 1)), without the standard
/// library's `hypot` and, above 1, its `ln_1p`: ln_1p(z + z²/(1 + √(1 + z²))) up to 1 (no
/// cancellation near 0), ln(z + √(z² + 1)) from 1 to 1e150 (the argument ≥ 2.4, so the log
/// loses nothing), ln 2z beyond (the next term, 1/(4z²), is below 1e−300). Within a few units
/// in the last place of `f64::asinh`, at about a third of its cost: the kernel's integrals take
/// two per strip pair.
fn asinh_non_negative(z: f64) -> f64 {
    if z <= 1.0 {
        let root = (1.0 + z * z).sqrt();
        (z + z * z / (1.0 + root)).ln_1p()
    } else if z < 1e150 {
        (z + (z * z + 1.0).sqrt()).ln()
    } else {
        (2.0 * z).ln()
    }
}

/// Model kernel S(c, y) = 2c asinh(α/|y|), α = 2c/e [m]: I's log singularity, similar decay.
fn model_kernel(c: f64, y: f64) -> f64 {
    let y = y.abs();
    if y == 0.0 {
        return f64::INFINITY;
    }
    2.0 * c * asinh_non_negative(MODEL_KERNEL_SCALE * c / y)
}

/// Φ(c, Y) = ∫₀^Y S(c, y) dy = 2c sgn(Y) [|Y| asinh(α/|Y|) + α asinh(|Y|/α)], α = 2c/e [m²]
/// (odd in Y, Φ(0) = 0; 0 for c ≤ 0). Check: d/dY [Y asinh(α/Y)] = asinh(α/Y) − α/√(α² + Y²) and
/// d/dY [α asinh(Y/α)] = α/√(α² + Y²).
pub fn model_kernel_antiderivative(c: f64, y: f64) -> f64 {
    let abs_y = y.abs();
    if abs_y == 0.0 || !(c.is_finite() && c > 0.0) {
        return 0.0;
    }
    let alpha = MODEL_KERNEL_SCALE * c;
    let value = 2.0
        * c
        * (abs_y * asinh_non_negative(alpha / abs_y) + alpha * asinh_non_negative(abs_y / alpha));
    value.copysign(y)
}

/// Kernel remainder R(c, y) = I(c, y) − S(c, y) [m]: bounded, 0 at y = 0.
fn kernel_remainder(c: f64, y: f64) -> f64 {
    let y = y.abs();
    if y <= REMAINDER_ORIGIN * c {
        return 0.0;
    }
    inner_integral(c, y) - model_kernel(c, y)
}

/// ∫₀^Y R(c, y) dy for Y ≥ 0 [m²]: Gauss–Legendre on [0, min(Y, c)] in t = √(y/min(Y, c)),
/// Gauss–Legendre in u = ln y on [c, min(Y, 32c)], the two-term expansion of R beyond.
fn remainder_integral(c: f64, big_y: f64) -> f64 {
    if big_y.is_nan() || big_y <= 0.0 {
        return 0.0;
    }
    let near_end = big_y.min(c);
    // y = Y₁ t², dy = 2Y₁ t dt: turns R's y² ln y term into t⁵ ln t, smooth enough for the rule.
    let mut sum = gauss_legendre(0.0, 1.0, |t| {
        2.0 * near_end * t * kernel_remainder(c, near_end * t * t)
    });
    if big_y > c {
        let mid_end = big_y.min(TAIL_START * c);
        // y = c eᵘ, dy = y du.
        sum += gauss_legendre(0.0, (mid_end / c).ln(), |u| {
            let y = c * u.exp();
            kernel_remainder(c, y) * y
        });
        if big_y > mid_end {
            let c2 = c * c;
            sum += TAIL_R1 * c2 * (big_y / mid_end).ln()
                + 0.5 * TAIL_R3 * c2 * c2 * (1.0 / (mid_end * mid_end) - 1.0 / (big_y * big_y));
        }
    }
    sum
}

/// J(c, Y) = ∫₀^Y I(c, y) dy for Y ≥ 0 [m²]: the log-singular part in closed form (Φ) plus the
/// regular remainder. For Y ≪ c, J ≈ 2cY ln(4c/Y) (the central-strip estimate).
pub fn kernel_integral_from_origin(c: f64, big_y: f64) -> f64 {
    if !(c.is_finite() && c > 0.0 && big_y > 0.0) {
        return 0.0;
    }
    model_kernel_antiderivative(c, big_y) + remainder_integral(c, big_y)
}

/// ∫ I(c, y) dy over the strip [lo, hi] (y from y0) [m²]: split at y0 with
/// [`kernel_integral_from_origin`] if the strip contains y0 (lo ≤ 0 < hi, as
/// [`StripGeometry::strip_at_origin`]), else product integration with midpoint remainder.
#[cfg(test)]
fn strip_kernel_integral(c: f64, lo: f64, hi: f64) -> f64 {
    split_strip_integral(c, lo, hi, kernel_integral_from_origin, kernel_remainder)
}

/// The rule of [`strip_kernel_integral`] with J(c, Y) = `from_origin` and R(c, y) =
/// `remainder` (the direct functions, or [`RemainderTable`]'s).
fn split_strip_integral(
    c: f64,
    lo: f64,
    hi: f64,
    from_origin: impl Fn(f64, f64) -> f64,
    remainder: impl Fn(f64, f64) -> f64,
) -> f64 {
    if lo <= 0.0 && 0.0 < hi {
        from_origin(c, hi) + from_origin(c, -lo)
    } else {
        let mid = 0.5 * (lo + hi);
        model_kernel_antiderivative(c, hi) - model_kernel_antiderivative(c, lo)
            + (hi - lo) * remainder(c, mid)
    }
}

/// Smallest t = y/c in [`RemainderTable`]; below it the remainder is computed directly (strips
/// whose centre lies within 1e−3 c of y0 are rare and R is ~1e−5 c there).
const TABLE_T_MIN: f64 = 1e-3;
/// Largest t in [`RemainderTable`] (twice [`TAIL_START`], so that the node at the tail's start
/// is interior); beyond it directly — strips more than 64 of their half-lengths from y0 are the
/// narrow ends of a patch, and there R = I − S cancels (both ≈ c/t; K − E ≈ πk²/4 with
/// k² ≈ 1/t²), so the direct values carry ~1e−16 t² relative noise a table would only copy.
const TABLE_T_MAX: f64 = 64.0;
/// Node spacing in u = ln t: cubic interpolation in u is relatively exact to ~(Δu)⁴/40 of the
/// tabulated functions' fourth derivatives in u (O(1) relative: power laws and t² ln t in t),
/// ~3e−10; tested against the direct evaluation to 1e−9.
const TABLE_DU: f64 = 0.01;

/// The scale-free kernel remainder, tabulated once per model instance. I(c, y) = c Î(y/c) and
/// S(c, y) = c Ŝ(y/c) (KP6 and the model kernel depend on y/c alone, times c), so
/// R(c, y) = c R̂(y/c) and ∫₀^Y R dy = c² Ĝ(Y/c) with Ĝ(T) = ∫₀^T R̂ dt: one-dimensional
/// functions. Tabulated on u = ln t, they replace an AGM per strip and the Gauss–Legendre sums
/// of the strip at the origin (~30 AGMs) at every load-iteration step — most of the model's cost
/// — by cubic interpolation. Built from the direct functions ([`kernel_remainder`], and
/// [`remainder_integral`] once at t = [`TABLE_T_MIN`]), Ĝ by integrating the interpolating cubics
/// cell by cell; outside [`TABLE_T_MIN`, `TABLE_T_MAX`] the direct functions are used.
#[derive(Debug, Clone)]
pub(crate) struct RemainderTable {
    /// R̂ at t_k = TABLE_T_MIN e^{k Δu}, as interval cubics.
    remainder: UniformCubic,
    /// Ĝ at the same nodes, as interval cubics.
    integral: UniformCubic,
}

impl RemainderTable {
    pub(crate) fn new() -> Self {
        let nodes = ((TABLE_T_MAX / TABLE_T_MIN).ln() / TABLE_DU).ceil() as usize + 1;
        let t_of = |k: usize| TABLE_T_MIN * (TABLE_DU * k as f64).exp();
        let remainder: Vec<f64> = (0..nodes).map(|k| kernel_remainder(1.0, t_of(k))).collect();
        // ∫ R̂ dt = ∫ R̂(e^u) e^u du: integrate g(u) = R̂ t over each cell with the cubic through
        // the four nearest nodes (weights (−1, 13, 13, −1)/24 inside, one-sided at the ends).
        let g: Vec<f64> = (0..nodes).map(|k| remainder[k] * t_of(k)).collect();
        let mut integral = Vec::with_capacity(nodes);
        integral.push(remainder_integral(1.0, TABLE_T_MIN));
        for k in 0..nodes - 1 {
            let cell = if k == 0 {
                9.0 * g[0] + 19.0 * g[1] - 5.0 * g[2] + g[3]
            } else if k == nodes - 2 {
                g[k - 2] - 5.0 * g[k - 1] + 19.0 * g[k] + 9.0 * g[k + 1]
            } else {
                -g[k - 1] + 13.0 * g[k] + 13.0 * g[k + 1] - g[k + 2]
            };
            integral.push(integral[k] + TABLE_DU / 24.0 * cell);
        }
        Self {
            remainder: UniformCubic::new(&remainder),
            integral: UniformCubic::new(&integral),
        }
    }

    /// Cubic (Lagrange) interpolation of `values` at t ∈ [TABLE_T_MIN, TABLE_T_MAX].
    fn at(values: &UniformCubic, t: f64) -> f64 {
        values.at((t / TABLE_T_MIN).ln() / TABLE_DU)
    }

    /// R(c, y) = c R̂(|y|/c) [m] (as [`kernel_remainder`]).
    pub(crate) fn remainder(&self, c: f64, y: f64) -> f64 {
        let t = y.abs() / c;
        if (TABLE_T_MIN..=TABLE_T_MAX).contains(&t) {
            c * Self::at(&self.remainder, t)
        } else {
            kernel_remainder(c, y)
        }
    }

    /// J(c, Y) = ∫₀^Y I(c, y) dy for Y ≥ 0 [m²] (as [`kernel_integral_from_origin`]).
    pub(crate) fn integral_from_origin(&self, c: f64, big_y: f64) -> f64 {
        if !(c.is_finite() && c > 0.0 && big_y > 0.0) {
            return 0.0;
        }
        let t = big_y / c;
        if !(TABLE_T_MIN..=TABLE_T_MAX).contains(&t) {
            return kernel_integral_from_origin(c, big_y);
        }
        let g_hat = if t <= TAIL_START {
            Self::at(&self.integral, t)
        } else {
            // Beyond 32 the same two-term tail as `remainder_integral`, from the node at 32.
            let at_tail = Self::at(&self.integral, TAIL_START);
            at_tail
                + TAIL_R1 * (t / TAIL_START).ln()
                + 0.5 * TAIL_R3 * (1.0 / (TAIL_START * TAIL_START) - 1.0 / (t * t))
        };
        model_kernel_antiderivative(c, big_y) + c * c * g_hat
    }

    /// ∫ I(c, y) dy over the strip [lo, hi] (as [`strip_kernel_integral`]).
    pub(crate) fn strip_integral(&self, c: f64, lo: f64, hi: f64) -> f64 {
        split_strip_integral(
            c,
            lo,
            hi,
            |c, y| self.integral_from_origin(c, y),
            |c, y| self.remainder(c, y),
        )
    }
}
/// Smallest T = Y/c tabulated by [`ScaledStripIntegral`] (as [`RemainderTable`]).
const SCALED_T_MIN: f64 = TABLE_T_MIN;
/// Largest T tabulated by [`ScaledStripIntegral`]; beyond it Ĵ follows I's far-field series.
const SCALED_T_MAX: f64 = TABLE_T_MAX;

/// I(1, t) for t ≫ 1, term by term: π/(2t) − π/(16t³) + 3π/(128t⁵) − 25π/(2048t⁷) (the
/// expansion of 1/√(x² + t²) in x²/t² integrated against √(1 − x²); the next term is
/// 0.0075 π/t⁹, below 4e−12 of the first beyond t = 16). Returns the antiderivative's
/// non-logarithmic part: P(t) = π/(32t²) − 3π/(512t⁴) + 25π/(12288t⁶), so that
/// ∫_{t₁}^{t₂} I(1, t) dt = (π/2) ln(t₂/t₁) + P(t₂) − P(t₁).
fn far_field_polynomial(t: f64) -> f64 {
    let u = 1.0 / (t * t);
    u * (PI / 32.0 + u * (-3.0 * PI / 512.0 + u * (25.0 * PI / 12288.0)))
}

/// t I(1, t) for t ≫ 1 from the same series: π/2 + t P′(t) =
/// π/2 − π/(16t²) + 3π/(128t⁴) − 25π/(2048t⁶).
fn far_field_slope(t: f64) -> f64 {
    let u = 1.0 / (t * t);
    FRAC_PI_2 + u * (-PI / 16.0 + u * (3.0 * PI / 128.0 + u * (-25.0 * PI / 2048.0)))
}

/// Ĵ(T) = J(1, T) = ∫₀^T I(1, t) dt tabulated on u = ln T, so that a strip's integral is
/// ∫_{lo}^{hi} I(c, y) dy = c² [Ĵ(hi/c) − Ĵ(lo/c)] (0 < lo < hi; I(c, y) = c Î(y/c)) with one
/// cubic interpolation per end and no transcendental function when ln T is known. Built once per
/// instance from [`RemainderTable::integral_from_origin`]; below [`SCALED_T_MIN`] the direct
/// function, beyond [`SCALED_T_MAX`] the far-field series from the last node (accuracy: tested
/// against the direct J to 1e−9).
#[derive(Debug, Clone)]
pub(crate) struct ScaledStripIntegral {
    /// Ĵ at T_k = SCALED_T_MIN e^{k Δu}, as interval cubics.
    values: UniformCubic,
    /// dĴ/d ln T = T_k I(1, T_k) at the same nodes, as interval cubics.
    slopes: UniformCubic,
    /// Nodes of the tables.
    nodes: usize,
    /// Ĵ(SCALED_T_MAX) − (π/2) ln SCALED_T_MAX − P(SCALED_T_MAX): the far-field constant.
    far_constant: f64,
    /// For T < SCALED_T_MIN.
    remainder: RemainderTable,
    /// The largest T of the table, SCALED_T_MIN e^{(nodes − 1) Δu}.
    t_max: f64,
}

impl ScaledStripIntegral {
    pub(crate) fn new() -> Self {
        let remainder = RemainderTable::new();
        let nodes = ((SCALED_T_MAX / SCALED_T_MIN).ln() / TABLE_DU).ceil() as usize + 1;
        let node = |k: usize| SCALED_T_MIN * (TABLE_DU * k as f64).exp();
        let values: Vec<f64> = (0..nodes)
            .map(|k| remainder.integral_from_origin(1.0, node(k)))
            .collect();
        let slopes: Vec<f64> = (0..nodes)
            .map(|k| node(k) * inner_integral(1.0, node(k)))
            .collect();
        let t_last = node(nodes - 1);
        let far_constant =
            values[nodes - 1] - FRAC_PI_2 * t_last.ln() - far_field_polynomial(t_last);
        Self {
            values: UniformCubic::new(&values),
            slopes: UniformCubic::new(&slopes),
            nodes,
            far_constant,
            remainder,
            t_max: t_last,
        }
    }

    /// Largest T of the table; at and beyond it [`Self::at_log`] is the far-field series.
    pub(crate) fn t_max(&self) -> f64 {
        self.t_max
    }

    /// Ĵ(T) from `log_t` = ln T (and T itself, for the ends) [-]; 0 for T ≤ 0 or NaN.
    pub(crate) fn at_log(&self, t: f64, log_t: f64) -> f64 {
        self.look_up(
            &self.values,
            t,
            log_t,
            |t| self.remainder.integral_from_origin(1.0, t),
            |t| self.far_constant + FRAC_PI_2 * log_t + far_field_polynomial(t),
        )
    }

    /// dĴ/d ln T = T I(1, T) from `log_t` = ln T (and T itself) [-], as [`Self::at_log`]: one
    /// cubic interpolation inside the table, the direct function below it, the far-field series
    /// at and beyond its end; 0 for T ≤ 0 or NaN.
    pub(crate) fn slope_at_log(&self, t: f64, log_t: f64) -> f64 {
        self.look_up(
            &self.slopes,
            t,
            log_t,
            |t| t * inner_integral(1.0, t),
            far_field_slope,
        )
    }

    /// `table` (on the nodes T_k) at T from `log_t` = ln T: 0 for T ≤ 0 or NaN, `below(T)` under
    /// the first node, `beyond(T)` at and past the last, else one cubic interpolation.
    #[inline(always)]
    fn look_up(
        &self,
        table: &UniformCubic,
        t: f64,
        log_t: f64,
        below: impl Fn(f64) -> f64,
        beyond: impl Fn(f64) -> f64,
    ) -> f64 {
        let x = (log_t - SCALED_T_MIN.ln()) / TABLE_DU;
        if t.is_nan() || t <= 0.0 {
            0.0
        } else if x < 0.0 {
            below(t)
        } else if x >= (self.nodes - 1) as f64 {
            beyond(t)
        } else {
            table.at(x)
        }
    }

    /// ∫_{t_lo}^{t_hi} I(1, t) dt for t_max ≤ t_lo < t_hi from the far-field series, with the
    /// logarithm's ratio `log_ratio` = ln(t_hi/t_lo) given (no cancellation between two Ĵ of
    /// nearly equal size) [-].
    pub(crate) fn far_difference(t_lo: f64, t_hi: f64, log_ratio: f64) -> f64 {
        FRAC_PI_2 * log_ratio + far_field_polynomial(t_hi) - far_field_polynomial(t_lo)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Composite Simpson rule with `m` (even) intervals.
    fn simpson(lo: f64, hi: f64, m: usize, g: impl Fn(f64) -> f64) -> f64 {
        let h = (hi - lo) / m as f64;
        let mut sum = g(lo) + g(hi);
        for k in 1..m {
            sum += g(lo + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        sum * h / 3.0
    }

    #[test]
    fn closed_form_asinh_agrees_with_the_standard_library() {
        // Log-spaced over 1e−300 … 1e300 and both sides of the branch points 1 and 1e150.
        let mut worst = 0.0f64;
        for k in 0..=6000 {
            let z = 10f64.powf(-300.0 + 0.1 * k as f64);
            for z in [z, 1.0, 1.0 + 1e-15, 1e150, 1e150 * (1.0 - 1e-15)] {
                let (fast, exact) = (asinh_non_negative(z), z.asinh());
                worst = worst.max((fast - exact).abs() / exact);
            }
        }
        // A few units in the last place (2.2e−16 each).
        assert!(worst < 1e-15, "worst relative deviation {worst:e}");
        assert_eq!(asinh_non_negative(0.0), 0.0);
        assert_eq!(asinh_non_negative(f64::INFINITY), f64::INFINITY);
    }

    #[test]
    fn inner_integral_matches_quadrature_and_asymptotes() {
        // KP6 against Simpson in x = c sin θ (integrand c² cos²θ/√(c² sin²θ + y²), smooth for
        // y > 0, peak width y/c ≥ 0.05 resolved by 40 000 intervals): 1e−10.
        let c = 3e-3;
        for ratio in [0.05, 0.3, 1.0, 3.0, 30.0] {
            let y = ratio * c;
            let reference = simpson(-FRAC_PI_2, FRAC_PI_2, 40_000, |t| {
                c * c * t.cos().powi(2) / (c * c * t.sin().powi(2) + y * y).sqrt()
            });
            let i = inner_integral(c, y);
            assert!(
                (i / reference - 1.0).abs() < 1e-10,
                "y/c = {ratio}: {i} vs {reference}"
            );
            assert_eq!(inner_integral(c, -y), i);
        }
        // Small y: 2c(ln(4c/y) − 1), next term O((y/c)² ln) ≈ 1e−7 at y = 1e−4 c.
        let y = 1e-4 * c;
        let i = inner_integral(c, y);
        assert!((i / (2.0 * c * ((4.0 * c / y).ln() - 1.0)) - 1.0).abs() < 1e-7);
        // Large y: πc²/(2y) (1 − c²/(8y²)).
        let y = 1e3 * c;
        let i = inner_integral(c, y);
        assert!((i / (PI * c * c / (2.0 * y)) - 1.0).abs() < 2e-7);
        assert_eq!(inner_integral(0.0, 1.0), 0.0);
        assert!(kernel_remainder(c, 0.0) == 0.0 && kernel_remainder(c, c).abs() < 0.1 * c);
    }

    #[test]
    fn tabulated_kernel_remainder_matches_the_direct_functions() {
        // The table against the direct evaluation over t = y/c from 1e−4 to 1e5 (through both
        // ends of the table): R to 1e−9 of c (R itself is O(0.1 c) at t ~ 1 and decays like
        // 0.02 c/t; an absolute bound is what enters D3, a sum of terms of order c Δs); J and the
        // strip integrals to 5e−9 relative — the direct J's own Gauss–Legendre error is up to
        // 2.4e−9 (kernel_integral_from_origin_matches_reference), so the two differ by that.
        let table = RemainderTable::new();
        let c = 3e-3;
        let mut t: f64 = 1e-4;
        let (mut worst_r, mut worst_j, mut worst_strip) = (0.0_f64, 0.0_f64, 0.0_f64);
        while t < 1e5 {
            let y = t * c;
            worst_r = worst_r.max((table.remainder(c, y) - kernel_remainder(c, y)).abs() / c);
            let j = kernel_integral_from_origin(c, y);
            worst_j = worst_j.max((table.integral_from_origin(c, y) / j - 1.0).abs());
            for (lo, hi) in [(0.5 * y, 1.5 * y), (-0.3 * y, y)] {
                let direct = strip_kernel_integral(c, lo, hi);
                let tabulated = table.strip_integral(c, lo, hi);
                worst_strip = worst_strip.max((tabulated / direct - 1.0).abs());
            }
            t *= 1.0379;
        }
        assert!(worst_r < 1e-9, "R: {worst_r:e}");
        assert!(worst_j < 5e-9, "J: {worst_j:e}");
        assert!(worst_strip < 5e-9, "strip: {worst_strip:e}");
    }

    #[test]
    fn kernel_integral_from_origin_matches_reference() {
        // J(c, Y) = 2c² ∫₀^{π/2} cos²θ asinh(Y/(c sin θ)) dθ; with ∫₀^{π/2} cos²θ ln sin θ dθ
        // = −(π/4) ln 2 − π/8 the log is removed and the rest, ln(Y + √(Y² + c² sin²θ)), is
        // smooth (layer width Y/c ≥ 0.01 rad, 400 000 Simpson intervals): reference to ~1e−12.
        // Tolerance 2e−8: the 8-point rules on the remainder (measured ≤ 2.4e−9, at Y = c) and
        // the tail expansion (< 1e−9), with margin.
        let c = 3e-3;
        let table = RemainderTable::new();
        for ratio in [0.01, 0.1, 0.5, 1.0, 2.0, 10.0, 16.0, 100.0, 1e4] {
            let big_y = ratio * c;
            let smooth = simpson(0.0, FRAC_PI_2, 400_000, |t| {
                t.cos().powi(2) * (big_y + (big_y * big_y + (c * t.sin()).powi(2)).sqrt()).ln()
            });
            let reference =
                2.0 * c * c * (smooth - FRAC_PI_2 / 2.0 * c.ln() + PI / 4.0 * 2f64.ln() + PI / 8.0);
            let j = kernel_integral_from_origin(c, big_y);
            eprintln!("Y/c = {ratio}: J/ref − 1 = {:.2e}", j / reference - 1.0);
            assert!(
                (j / reference - 1.0).abs() < 2e-8,
                "Y/c = {ratio}: {j} vs {reference}"
            );
            // The tabulated J (what the model uses) against the same reference.
            let tabulated = table.integral_from_origin(c, big_y);
            eprintln!(
                "  tabulated: J/ref − 1 = {:.2e}",
                tabulated / reference - 1.0
            );
            assert!(
                (tabulated / reference - 1.0).abs() < 2e-8,
                "Y/c = {ratio}: tabulated {tabulated} vs {reference}"
            );
        }
        // The central-strip estimate 2cΔ ln(8c/Δ), error < 0.03 % for Δ ≤ 0.1c.
        for width in [0.1 * c, 0.03 * c, 0.001 * c] {
            let central = 2.0 * kernel_integral_from_origin(c, 0.5 * width);
            let estimate = 2.0 * c * width * (8.0 * c / width).ln();
            assert!((central / estimate - 1.0).abs() < 3e-4);
        }
    }

    #[test]
    fn strip_integrals_are_additive() {
        // A strip split into 64 pieces gives the same total as the whole, whichever rule each
        // piece uses (the strip containing y0: J on both sides, ~1e−9 (tested above); other
        // strips: product
        // integration, whose midpoint remainder errs by O(Δs³ ln Δs) per strip, largest next to
        // y0: measured 2.1e−5, 6.4e−6 relative for Δs = c/20, c/40; ≤ 5.5e−3 for strips wider
        // than c). Bound: 0.02 min((Δs/c)², 1).
        let c = 2e-3;
        for width in [0.05 * c, 0.025 * c, 0.5 * c, 5.0 * c] {
            for lo in [-0.3, -1.0, 0.4, 3.0, -40.0].map(|k| k * width) {
                let whole = strip_kernel_integral(c, lo, lo + width);
                let fine: f64 = (0..64)
                    .map(|k| {
                        let a = lo + width * k as f64 / 64.0;
                        strip_kernel_integral(c, a, a + width / 64.0)
                    })
                    .sum();
                let err = (whole / fine - 1.0).abs();
                let bound = 0.02 * (width / c).powi(2).min(1.0);
                assert!(
                    err < bound,
                    "Δs/c = {}, lo/Δs = {}: {err:.1e}",
                    width / c,
                    lo / width
                );
            }
        }
    }
    #[test]
    fn scaled_strip_integral_matches_the_direct_function() {
        // Ĵ(T) against the direct J(1, T) (2.4e−9, kernel_integral_from_origin_matches_reference)
        // from 1e−4 to 1e4, through both ends of the table: 5e−9 relative. The far-field
        // difference against Ĵ's difference where both are in the series: 1e−12 relative.
        // The slope dĴ/d ln T = T I(1, T) against the direct I (inner_integral, itself checked
        // against quadrature): measured 2.2e−8 (the cubic in ln T; the far-field series is good
        // to 4e−12 beyond T = 16), bound 5e−8 — ample for the Newton matrix of the coupled
        // strips' half-lengths, its one user; and it is Ĵ's derivative (central difference).
        let table = ScaledStripIntegral::new();
        let mut t: f64 = 1e-4;
        let (mut worst, mut worst_slope): (f64, f64) = (0.0, 0.0);
        while t < 1e4 {
            let direct = kernel_integral_from_origin(1.0, t);
            worst = worst.max((table.at_log(t, t.ln()) / direct - 1.0).abs());
            let slope = t * inner_integral(1.0, t);
            worst_slope = worst_slope.max((table.slope_at_log(t, t.ln()) / slope - 1.0).abs());
            let h: f64 = 1e-4;
            let (lo, hi) = (t * (-h).exp(), t * h.exp());
            let numeric = (table.at_log(hi, hi.ln()) - table.at_log(lo, lo.ln())) / (2.0 * h);
            assert!(
                (numeric / slope - 1.0).abs() < 1e-6,
                "{t}: {numeric} {slope}"
            );
            t *= 1.0173;
        }
        eprintln!("Ĵ table against direct J: {worst:.2e}, slope {worst_slope:.2e}");
        assert!(worst < 5e-9, "{worst:e}");
        assert!(worst_slope < 5e-8, "{worst_slope:e}");
        let (lo, hi) = (100.0_f64, 101.5_f64);
        let far = ScaledStripIntegral::far_difference(lo, hi, (hi / lo).ln());
        let diff = table.at_log(hi, hi.ln()) - table.at_log(lo, lo.ln());
        assert!((far / diff - 1.0).abs() < 1e-10);
        // Continuity across the table's end.
        let end = table.t_max();
        let below = table.at_log(end * (1.0 - 1e-12), (end * (1.0 - 1e-12)).ln());
        let above = table.at_log(end, end.ln());
        assert!((above / below - 1.0).abs() < 1e-11);
        let below = table.slope_at_log(end * (1.0 - 1e-12), (end * (1.0 - 1e-12)).ln());
        let above = table.slope_at_log(end, end.ln());
        assert!((above / below - 1.0).abs() < 1e-9, "{above} {below}");
        assert_eq!(table.at_log(0.0, f64::NEG_INFINITY), 0.0);
        assert_eq!(table.at_log(f64::NAN, f64::NAN), 0.0);
        assert_eq!(table.slope_at_log(0.0, f64::NEG_INFINITY), 0.0);
        assert_eq!(table.slope_at_log(f64::NAN, f64::NAN), 0.0);
    }
}
