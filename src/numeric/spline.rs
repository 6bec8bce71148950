//! Cubic smoothing spline z(y) through profile points (Reinsch 1967), evaluated without allocation.
//!
//! Source: C.H. Reinsch (1967), "Smoothing by spline functions", *Numer. Math.* 10:177–183;
//! P.J. Green & B.W. Silverman (1994), *Nonparametric Regression and Generalized Linear Models*,
//! §2.3 (the Q, R band matrices used below). Written from the equations.
//!
//! # What is fitted
//!
//! Given knots y₁ < … < yₙ, data zᵢ and relative weights ωᵢ > 0, the spline g minimises
//!
//! ```text
//!   J(g) = Σᵢ wᵢ (zᵢ − g(yᵢ))²  +  ℓ⁴ ∫ g''(y)² dy,      wᵢ = ωᵢ (yᵢ₊₁ − yᵢ₋₁)/2
//! ```
//!
//! (end weights use the half interval). g is the natural cubic spline with knots at the data
//! (g'' = 0 at both ends). With γ the second derivatives at the interior knots (Reinsch):
//!
//! ```text
//!   (R + ℓ⁴ Qᵀ W⁻¹ Q) γ = Qᵀ z,        g = z − ℓ⁴ W⁻¹ Q γ
//! ```
//!
//! Q (n × n−2, column j: 1/hⱼ, −1/hⱼ − 1/hⱼ₊₁, 1/hⱼ₊₁) and R (n−2 × n−2, tridiagonal:
//! (hⱼ + hⱼ₊₁)/3 on, hⱼ₊₁/6 off the diagonal) as in Green & Silverman ch. 2; the matrix is
//! symmetric positive definite and pentadiagonal, solved by a banded LDLᵀ factorisation in O(n).
//!
//! # The smoothing length ℓ [m]
//!
//! The weights wᵢ are lengths, so the data term approximates ∫ (z − g)² dy and J no longer depends
//! on the point density. Its Euler–Lagrange equation is g + ℓ⁴ g'''' = z: the spline is a
//! low-pass filter with transfer function H(k) = 1 / (1 + (kℓ)⁴) for a wave of wavenumber k.
//! Undulations of wavelength 2πℓ are halved, longer ones pass (1 − (2πℓ/λ)⁴ for λ ≫ 2πℓ), shorter
//! ones are removed. ℓ = 0 gives the natural interpolating spline.
//!
//! For white measurement noise of standard deviation σ [m] at point spacing h [m], the filtered
//! second derivative has the standard deviation (integrate k⁴|H|² σ²h/2π over k)
//!
//! ```text
//!   s(g'') = σ · √( h / (8√2 ℓ⁵) )       ⇔      ℓ = ( σ² h / (8√2 s²) )^(1/5)
//! ```
//!
//! ([`smoothing_length_for_noise`]). For an interpolating spline (ℓ = 0) the noise in g'' is of
//! order σ/h², i.e. useless for curvature.
//!
//! The price is bias. The filter's impulse response is
//! (1/(2√2ℓ)) e^(−|x|/√2ℓ) (cos(x/√2ℓ) + sin(|x|/√2ℓ)), so a curvature jump Δκ at distance d
//! (an arc junction) leaks ½ Δκ e^(−d/√2ℓ) cos(d/√2ℓ) into the smoothed curvature: on the UIC60
//! crown (R300, R80 junctions ±10.5 mm from the centre, Δκ = 9.2 1/m) that is −6 % of the crown
//! curvature at the centre for ℓ = 2 mm, −1 % for 1.5 mm, < 0.3 % for 1 mm (measured on the
//! benchmark rail). Near the data ends the natural end condition g'' = 0 acts like a jump to
//! zero curvature (≈ 6 % of κ at 4ℓ from the end, < 0.5 % beyond 7ℓ). Rule: keep the curvature
//! features you need ≥ 5√2 ℓ ≈ 7ℓ from the nearest curvature jump and from the data ends.
//!
//! Known limits: the filter acts along y, so on steep parts (flange, gauge face, slope z' ≫ 1)
//! it acts over an arc length ℓ·√(1 + z'²); smoothing is a trade of noise against bias, not a
//! cure.
//!
//! # Evaluation
//!
//! Per interval the spline is stored as a + b t + c t² + d t³ (t = y − yᵢ); [`CubicSpline::eval`]
//! finds the interval by binary search (O(log n), no allocation). Outside [y₁, yₙ] the spline is
//! continued **linearly** with the end value and slope (g'' = 0 there, so value, slope and second
//! derivative stay continuous).

/// Standard deviation factor 1/(8√2) of the filtered second derivative (see the module header).
const NOISE_FACTOR: f64 = 0.088_388_347_648_318_44; // = 1/(8·√2)

/// Why a spline could not be fitted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SplineError {
    /// Fewer than 4 points.
    TooFewPoints(usize),
    /// Arrays of different length.
    LengthMismatch,
    /// A non-finite knot, value, weight or smoothing length (index of the point, or `usize::MAX`
    /// for the smoothing length).
    NonFinite(usize),
    /// Knot `i` is not strictly greater than knot `i − 1`.
    NotIncreasing(usize),
    /// Weight `i` is not > 0.
    BadWeight(usize),
    /// The factorisation broke down or produced non-finite coefficients.
    Numerical,
}

/// A cubic spline z(y) with knots at the data points.
#[derive(Debug, Clone, PartialEq)]
pub struct CubicSpline {
    /// Knots, strictly increasing.
    knots: Vec<f64>,
    /// Per interval i (between knots i and i + 1): [a, b, c, d] of a + b t + c t² + d t³.
    coef: Vec<[f64; 4]>,
    /// Value and slope at the last knot (for the right-hand linear continuation).
    end_value: f64,
    end_slope: f64,
    /// Interval lookup.
    index: IntervalIndex,
}

/// Uniform cells over [y₁, yₙ] mapping a coordinate to the interval that contains the cell's
/// start: the interval of y is then found among the few knots inside its cell.
#[derive(Debug, Clone, PartialEq)]
struct IntervalIndex {
    /// y₁ and 1/cell width.
    y0: f64,
    inv_cell: f64,
    /// `first[k]`: the interval containing the start of cell k; `first[cells]` = n − 2.
    first: Vec<u32>,
}

/// Cells per knot interval of the index (8: a cell holds on average an eighth of an interval,
/// so that even moderately clustered knots leave at most one knot inside most cells, where the
/// lookup is one comparison; 4 bytes per cell, ~50 kB for a 1500-knot profile).
const CELLS_PER_INTERVAL: usize = 8;

impl IntervalIndex {
    fn new(knots: &[f64]) -> Self {
        let n = knots.len();
        let cells = CELLS_PER_INTERVAL * (n - 1);
        let (y0, yn) = (knots[0], knots[n - 1]);
        let width = (yn - y0) / cells as f64;
        let first = (0..=cells)
            .map(|k| {
                let y = y0 + width * k as f64;
                (knots.partition_point(|&v| v <= y).saturating_sub(1)).min(n - 2) as u32
            })
            .collect();
        Self {
            y0,
            inv_cell: 1.0 / width,
            first,
        }
    }

    /// The interval i with knots[i] ≤ y < knots[i + 1], for y₁ < y < yₙ. (Always inlined: the
    /// per-sample evaluation is its hot caller.)
    #[inline(always)]
    fn interval(&self, knots: &[f64], y: f64) -> usize {
        let cells = self.first.len() - 1;
        // Through u32 (cells < 2³²): a saturating f64 → u32 conversion is a few instructions
        // cheaper than f64 → usize on x86-64.
        let k = (((y - self.y0) * self.inv_cell) as u32 as usize).min(cells - 1);
        let (lo, hi) = (self.first[k] as usize, self.first[k + 1] as usize);
        if hi - lo <= 1 {
            // At most one knot inside the cell (the common case): y lies in interval lo or hi
            // (no knot: lo = hi, one look-up fewer on the dependency chain). The bracket check
            // also covers a cell index rounded to the neighbouring cell.
            let i = if hi == lo || knots[hi] > y { lo } else { hi };
            if knots[i] <= y && y < knots[i + 1] {
                return i;
            }
        }
        let mut i = if hi - lo > 8 {
            // A cluster of knots in this cell: binary search within it.
            lo + knots[lo + 1..=hi].partition_point(|&v| v <= y)
        } else {
            lo
        };
        // Walk to the interval (a step or two at most; also absorbs a cell index rounded to
        // the neighbouring cell).
        let last = knots.len() - 2;
        while i < last && knots[i + 1] <= y {
            i += 1;
        }
        while i > 0 && knots[i] > y {
            i -= 1;
        }
        i
    }
}

impl CubicSpline {
    /// Fits the smoothing spline with length `length_scale` ℓ [same unit as the knots; 0 =
    /// interpolate] through (`y`, `z`) with optional relative weights (default 1).
    pub fn fit(
        y: &[f64],
        z: &[f64],
        weights: Option<&[f64]>,
        length_scale: f64,
    ) -> Result<Self, SplineError> {
        let n = y.len();
        if z.len() != n || weights.is_some_and(|w| w.len() != n) {
            return Err(SplineError::LengthMismatch);
        }
        if n < 4 {
            return Err(SplineError::TooFewPoints(n));
        }
        if !(length_scale.is_finite() && length_scale >= 0.0) {
            return Err(SplineError::NonFinite(usize::MAX));
        }
        for i in 0..n {
            if !(y[i].is_finite() && z[i].is_finite()) {
                return Err(SplineError::NonFinite(i));
            }
            if i > 0 {
                let h = y[i] - y[i - 1];
                if !(h > 0.0 && h.is_finite()) {
                    return Err(SplineError::NotIncreasing(i));
                }
            }
            if let Some(w) = weights {
                if !w[i].is_finite() {
                    return Err(SplineError::NonFinite(i));
                }
                if w[i] <= 0.0 {
                    return Err(SplineError::BadWeight(i));
                }
            }
        }
        let h: Vec<f64> = y.windows(2).map(|p| p[1] - p[0]).collect();
        let alpha = length_scale.powi(4);
        let m = n - 2;

        // Band of the (n−2)×(n−2) system: diagonal, first and second super-diagonals.
        let mut d0 = vec![0.0; m];
        let mut d1 = vec![0.0; m];
        let mut d2 = vec![0.0; m];
        let mut rhs = vec![0.0; m];
        for j in 0..m {
            d0[j] = (h[j] + h[j + 1]) / 3.0;
            if j + 1 < m {
                d1[j] = h[j + 1] / 6.0;
            }
            rhs[j] = (z[j + 2] - z[j + 1]) / h[j + 1] - (z[j + 1] - z[j]) / h[j];
        }
        // Inverse data weights W⁻¹ (only needed when smoothing).
        let inv_w: Vec<f64> = if alpha > 0.0 {
            (0..n)
                .map(|i| {
                    let left = if i > 0 { h[i - 1] } else { 0.0 };
                    let right = if i + 1 < n { h[i] } else { 0.0 };
                    let omega = weights.map_or(1.0, |w| w[i]);
                    1.0 / (omega * 0.5 * (left + right))
                })
                .collect()
        } else {
            Vec::new()
        };
        // Column j of Q has q0 = 1/h_j (row j), q1 = −1/h_j − 1/h_{j+1} (row j+1), q2 = 1/h_{j+1}.
        let q = |j: usize| -> [f64; 3] {
            let a = 1.0 / h[j];
            let b = 1.0 / h[j + 1];
            [a, -a - b, b]
        };
        if alpha > 0.0 {
            for j in 0..m {
                let qj = q(j);
                d0[j] += alpha
                    * (qj[0] * qj[0] * inv_w[j]
                        + qj[1] * qj[1] * inv_w[j + 1]
                        + qj[2] * qj[2] * inv_w[j + 2]);
                if j + 1 < m {
                    let qk = q(j + 1);
                    d1[j] += alpha * (qj[1] * qk[0] * inv_w[j + 1] + qj[2] * qk[1] * inv_w[j + 2]);
                }
                if j + 2 < m {
                    let qk = q(j + 2);
                    d2[j] += alpha * qj[2] * qk[0] * inv_w[j + 2];
                }
            }
        }
        let gamma = solve_pentadiagonal_spd(&d0, &d1, &d2, &rhs).ok_or(SplineError::Numerical)?;

        // Second derivatives at all knots (natural ends) and fitted values.
        let mut m2 = vec![0.0; n];
        m2[1..(m + 1)].copy_from_slice(&gamma);
        let mut g = z.to_vec();
        if alpha > 0.0 {
            for (i, gi) in g.iter_mut().enumerate() {
                // (Q γ)_i: column i−2 (its q2), i−1 (its q1), i (its q0).
                let mut qg = 0.0;
                if i >= 2 && i - 2 < m {
                    qg += q(i - 2)[2] * gamma[i - 2];
                }
                if i >= 1 && i - 1 < m {
                    qg += q(i - 1)[1] * gamma[i - 1];
                }
                if i < m {
                    qg += q(i)[0] * gamma[i];
                }
                *gi -= alpha * inv_w[i] * qg;
            }
        }
        let mut coef = Vec::with_capacity(n - 1);
        for i in 0..n - 1 {
            let hi = h[i];
            let a = g[i];
            let b = (g[i + 1] - g[i]) / hi - hi * (2.0 * m2[i] + m2[i + 1]) / 6.0;
            let c = 0.5 * m2[i];
            let d = (m2[i + 1] - m2[i]) / (6.0 * hi);
            coef.push([a, b, c, d]);
        }
        let last = coef[n - 2];
        let hl = h[n - 2];
        let end_value = g[n - 1];
        let end_slope = last[1] + hl * (2.0 * last[2] + 3.0 * last[3] * hl);
        let finite = coef.iter().flatten().all(|v| v.is_finite())
            && end_value.is_finite()
            && end_slope.is_finite();
        if !finite {
            return Err(SplineError::Numerical);
        }
        Ok(Self {
            index: IntervalIndex::new(y),
            knots: y.to_vec(),
            coef,
            end_value,
            end_slope,
        })
    }

    /// The knots (the data abscissae).
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The spline value at knot `i` (equal to the data value when interpolating).
    pub fn knot_value(&self, i: usize) -> f64 {
        match self.coef.get(i) {
            Some(c) => c[0],
            None => self.end_value,
        }
    }

    /// Smallest and largest value of the spline (with its linear continuation) over [y0, y1]
    /// (y0 ≤ y1), exact: per knot interval the cubic's end values and its stationary points
    /// inside. Cost ∝ the knot intervals crossed — for set-up tables, not per-step work.
    pub fn value_range(&self, y0: f64, y1: f64) -> (f64, f64) {
        let cubic = |[c0, c1, c2, c3]: [f64; 4], t: f64| c0 + t * (c1 + t * (c2 + t * c3));
        self.range_over_pieces(
            y0,
            y1,
            |y| self.eval(y).0,
            |c, (t0, t1), take| {
                take(cubic(c, t0));
                take(cubic(c, t1));
                // Stationary points: c1 + 2 c2 t + 3 c3 t² = 0.
                for t in quadratic_roots(3.0 * c[3], 2.0 * c[2], c[1])
                    .into_iter()
                    .flatten()
                {
                    if t > t0 && t < t1 {
                        take(cubic(c, t));
                    }
                }
            },
        )
    }

    /// Smallest and largest slope dz/dy over [y0, y1] (y0 ≤ y1), exact: per knot interval the
    /// quadratic's end values and its vertex inside. For set-up tables, as `value_range`.
    pub fn slope_range(&self, y0: f64, y1: f64) -> (f64, f64) {
        let slope = |[_, c1, c2, c3]: [f64; 4], t: f64| c1 + t * (2.0 * c2 + 3.0 * c3 * t);
        self.range_over_pieces(
            y0,
            y1,
            |y| self.eval(y).1,
            |c, (t0, t1), take| {
                take(slope(c, t0));
                take(slope(c, t1));
                if c[3] != 0.0 {
                    let vertex = -c[2] / (3.0 * c[3]);
                    if vertex > t0 && vertex < t1 {
                        take(slope(c, vertex));
                    }
                }
            },
        )
    }

    /// (min, max) over [y0, y1] of a quantity given by `at_end` at the two ends (which covers the
    /// linear continuation outside the knots) and by `piece` on each knot interval crossed:
    /// `piece(coefficients, (t0, t1), take)` passes every candidate extreme of the interval's
    /// part t ∈ [t0, t1] (t from the interval's first knot) to `take`.
    fn range_over_pieces(
        &self,
        y0: f64,
        y1: f64,
        at_end: impl Fn(f64) -> f64,
        mut piece: impl FnMut([f64; 4], (f64, f64), &mut dyn FnMut(f64)),
    ) -> (f64, f64) {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut take = |v: f64| {
            lo = lo.min(v);
            hi = hi.max(v);
        };
        take(at_end(y0));
        take(at_end(y1));
        let n = self.knots.len();
        let (first, last) = (self.knots[0], self.knots[n - 1]);
        let (a, b) = (y0.max(first), y1.min(last));
        if a < b {
            let mut i = if a <= first {
                0
            } else {
                self.index.interval(&self.knots, a)
            };
            while i < n - 1 && self.knots[i] < b {
                let (k0, k1) = (self.knots[i], self.knots[i + 1]);
                piece(self.coef[i], (a.max(k0) - k0, b.min(k1) - k0), &mut take);
                i += 1;
            }
        }
        (lo, hi)
    }

    /// The cubic piece that [`CubicSpline::eval`] uses at `y` (the linear continuation outside
    /// the knots): evaluated anywhere in its interval, [`SplinePiece::eval`] gives what `eval`
    /// gives, without the interval lookup. `y` must not be NaN. (Always inlined: returned
    /// through memory, the piece reaches its caller late.)
    #[inline(always)]
    pub fn piece_at(&self, y: f64) -> SplinePiece {
        let n = self.knots.len();
        let y0 = self.knots[0];
        let yn = self.knots[n - 1];
        if y <= y0 {
            let c = self.coef[0];
            return SplinePiece {
                from: f64::NEG_INFINITY,
                to: y0,
                origin: y0,
                coef: [c[0], c[1], 0.0, 0.0],
            };
        }
        if y >= yn {
            return SplinePiece {
                from: yn,
                to: f64::INFINITY,
                origin: yn,
                coef: [self.end_value, self.end_slope, 0.0, 0.0],
            };
        }
        let i = self.index.interval(&self.knots, y);
        SplinePiece {
            from: self.knots[i],
            to: self.knots[i + 1],
            origin: self.knots[i],
            coef: self.coef[i],
        }
    }

    /// Value, first and second derivative at `y`. Linear continuation outside the knots; NaN in,
    /// NaN out. No allocation.
    #[inline]
    pub fn eval(&self, y: f64) -> (f64, f64, f64) {
        if y.is_nan() {
            return (f64::NAN, f64::NAN, f64::NAN);
        }
        let n = self.knots.len();
        let y0 = self.knots[0];
        if y <= y0 {
            let c = self.coef[0];
            return (c[0] + c[1] * (y - y0), c[1], 0.0);
        }
        let yn = self.knots[n - 1];
        if y >= yn {
            return (
                self.end_value + self.end_slope * (y - yn),
                self.end_slope,
                0.0,
            );
        }
        // First knot > y, minus one: y_i ≤ y < y_{i+1}, 0 ≤ i ≤ n − 2.
        let i = self.index.interval(&self.knots, y);
        let [a, b, c, d] = self.coef[i];
        let t = y - self.knots[i];
        (
            a + t * (b + t * (c + t * d)),
            b + t * (2.0 * c + 3.0 * d * t),
            2.0 * c + 6.0 * d * t,
        )
    }
}

/// One cubic piece of a [`CubicSpline`] over the knot interval [`from`, `to`] (unbounded for the
/// linear continuations): a + b t + c t² + d t³ with t = y − `origin`.
///
/// [`from`]: SplinePiece::from
/// [`to`]: SplinePiece::to
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SplinePiece {
    pub from: f64,
    pub to: f64,
    origin: f64,
    coef: [f64; 4],
}

impl SplinePiece {
    /// Whether `y` lies in the piece's interval (ends included: the spline's value, slope and
    /// second derivative are continuous at a knot).
    #[inline]
    pub fn contains(&self, y: f64) -> bool {
        y >= self.from && y <= self.to
    }

    /// Value, first and second derivative at `y` (the spline's where [`SplinePiece::contains`]).
    #[inline]
    pub fn eval(&self, y: f64) -> (f64, f64, f64) {
        let [a, b, c, d] = self.coef;
        let t = y - self.origin;
        (
            a + t * (b + t * (c + t * d)),
            b + t * (2.0 * c + 3.0 * d * t),
            2.0 * c + 6.0 * d * t,
        )
    }

    /// Third derivative (constant over the piece).
    #[inline]
    pub fn third(&self) -> f64 {
        6.0 * self.coef[3]
    }
}

/// Real roots of a t² + b t + c (a linear or constant polynomial handled; `None` where there is
/// no root).
fn quadratic_roots(a: f64, b: f64, c: f64) -> [Option<f64>; 2] {
    if a == 0.0 {
        return [(b != 0.0).then(|| -c / b), None];
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return [None, None];
    }
    // The cancellation-free pair: q = −(b + sign(b) √disc)/2, roots q/a and c/q.
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q == 0.0 {
        return [Some(0.0), None];
    }
    [Some(q / a), Some(c / q)]
}

/// The smoothing length ℓ [m] that brings the noise in the second derivative down to
/// `curvature_noise` [1/m] (standard deviation), for white measurement noise of standard deviation
/// `noise` [m] at point spacing `spacing` [m]: ℓ = (σ² h / (8√2 s²))^(1/5) (module header).
/// Returns 0 for non-positive or non-finite inputs.
pub fn smoothing_length_for_noise(noise: f64, spacing: f64, curvature_noise: f64) -> f64 {
    let valid = |v: f64| v > 0.0 && v.is_finite();
    if !(valid(noise) && valid(spacing) && valid(curvature_noise)) {
        return 0.0;
    }
    (NOISE_FACTOR * noise * noise * spacing / (curvature_noise * curvature_noise)).powf(0.2)
}

/// Solves A x = r for a symmetric positive definite pentadiagonal A given by its diagonal `d0`,
/// first super-diagonal `d1` and second super-diagonal `d2` (LDLᵀ without pivoting). Returns `None`
/// if a pivot is not positive and finite.
fn solve_pentadiagonal_spd(d0: &[f64], d1: &[f64], d2: &[f64], r: &[f64]) -> Option<Vec<f64>> {
    let m = d0.len();
    // L has unit diagonal, sub-diagonals l1[i] = L[i+1][i], l2[i] = L[i+2][i].
    let mut dd = vec![0.0; m];
    let mut l1 = vec![0.0; m];
    let mut l2 = vec![0.0; m];
    for i in 0..m {
        let mut di = d0[i];
        if i >= 1 {
            di -= l1[i - 1] * l1[i - 1] * dd[i - 1];
        }
        if i >= 2 {
            di -= l2[i - 2] * l2[i - 2] * dd[i - 2];
        }
        if !(di > 0.0 && di.is_finite()) {
            return None;
        }
        dd[i] = di;
        if i + 1 < m {
            let mut a = d1[i];
            if i >= 1 {
                a -= l2[i - 1] * l1[i - 1] * dd[i - 1];
            }
            l1[i] = a / di;
        }
        if i + 2 < m {
            l2[i] = d2[i] / di;
        }
    }
    // Forward (L u = r), diagonal, backward (Lᵀ x = D⁻¹ u).
    let mut x = r.to_vec();
    for i in 0..m {
        if i >= 1 {
            x[i] -= l1[i - 1] * x[i - 1];
        }
        if i >= 2 {
            x[i] -= l2[i - 2] * x[i - 2];
        }
    }
    for i in 0..m {
        x[i] /= dd[i];
    }
    for i in (0..m).rev() {
        if i + 1 < m {
            x[i] -= l1[i] * x[i + 1];
        }
        if i + 2 < m {
            x[i] -= l2[i] * x[i + 2];
        }
    }
    if x.iter().all(|v| v.is_finite()) {
        Some(x)
    } else {
        None
    }
}

#[cfg(test)]
#[path = "../../tests/common/lcg.rs"]
mod lcg;

#[cfg(test)]
mod tests {
    use super::*;

    use super::lcg::Lcg;

    #[test]
    fn interval_index_agrees_with_binary_search_on_uneven_and_clustered_knots() {
        // Uneven spacing, a cluster of 30 knots 1e-9 apart (like the benchmark rail's flanks),
        // and queries at random points, at every knot and just beside every knot.
        let mut rng = Lcg(7);
        let mut y = vec![0.0];
        for i in 1..200 {
            let step = if (80..110).contains(&i) {
                1e-9
            } else {
                1e-4 * (0.2 + 3.0 * rng.uniform())
            };
            y.push(y[i - 1] + step);
        }
        let index = IntervalIndex::new(&y);
        let (y0, yn) = (y[0], y[y.len() - 1]);
        let mut queries: Vec<f64> = (0..5000).map(|_| y0 + (yn - y0) * rng.uniform()).collect();
        for &k in &y[1..y.len() - 1] {
            queries.extend([k, k * (1.0 + 1e-15), k * (1.0 - 1e-15)]);
        }
        for q in queries.into_iter().filter(|&q| q > y0 && q < yn) {
            let expected = y
                .partition_point(|&k| k <= q)
                .saturating_sub(1)
                .min(y.len() - 2);
            assert_eq!(index.interval(&y, q), expected, "y = {q:e}");
        }
    }

    #[test]
    fn interpolates_a_quadratic_in_the_interior_and_passes_through_the_data() {
        // A natural spline reproduces data exactly at the knots; on a quadratic with natural ends
        // the interior error decays away from the ends.
        let y: Vec<f64> = (0..41).map(|i| -1.0 + 0.05 * i as f64).collect();
        let z: Vec<f64> = y.iter().map(|v| 0.3 * v * v - 0.1 * v + 2.0).collect();
        let s = CubicSpline::fit(&y, &z, None, 0.0).unwrap();
        for (yi, zi) in y.iter().zip(&z) {
            assert!((s.eval(*yi).0 - zi).abs() < 1e-14);
        }
        // Interior (10 intervals from the ends: end error × 0.27^10 ≈ 2e-6 of the end error).
        let (v, d, dd) = s.eval(0.123);
        assert!((v - (0.3 * 0.123 * 0.123 - 0.1 * 0.123 + 2.0)).abs() < 1e-9);
        assert!((d - (0.6 * 0.123 - 0.1)).abs() < 1e-7);
        assert!((dd - 0.6).abs() < 1e-5);
    }

    #[test]
    fn a_piece_evaluates_as_the_spline_inside_its_interval_and_outside_the_knots() {
        let y: Vec<f64> = (0..40).map(|i| 1e-3 * (i as f64).powf(1.3)).collect();
        let z: Vec<f64> = y.iter().map(|&v| (30.0 * v).sin() * 1e-2).collect();
        let s = CubicSpline::fit(&y, &z, None, 0.0).unwrap();
        let (lo, hi) = (y[0] - 5e-3, y[y.len() - 1] + 5e-3);
        for k in 0..=2000 {
            let at = lo + (hi - lo) * k as f64 / 2000.0;
            let piece = s.piece_at(at);
            assert!(piece.contains(at), "{at} outside its piece {piece:?}");
            // Same interval, same arithmetic: bit for bit.
            assert_eq!(piece.eval(at), s.eval(at), "at {at}");
            // Elsewhere in the interval (its start, its middle) the spline uses the same piece.
            for other in [
                piece.from.max(lo),
                0.5 * (piece.from.max(lo) + piece.to.min(hi)),
            ] {
                assert_eq!(piece.eval(other), s.eval(other), "at {other} of {piece:?}");
            }
        }
    }

    #[test]
    fn continuous_value_slope_and_curvature_at_knots_and_linear_outside() {
        let y = [0.0, 0.1, 0.25, 0.3, 0.5, 0.9];
        let z = [0.0, 0.3, -0.2, 0.1, 0.4, 0.0];
        for ell in [0.0, 0.05] {
            let s = CubicSpline::fit(&y, &z, None, ell).unwrap();
            for &k in &y[1..5] {
                let a = s.eval(k - 1e-12);
                let b = s.eval(k + 1e-12);
                assert!((a.0 - b.0).abs() < 1e-9);
                assert!((a.1 - b.1).abs() < 1e-6);
                assert!((a.2 - b.2).abs() < 1e-3);
            }
            let (v0, s0, _) = s.eval(0.0);
            let (v, sl, c) = s.eval(-0.5);
            assert!((v - (v0 - 0.5 * s0)).abs() < 1e-12 && sl == s0 && c == 0.0);
            let (v1, s1, c1) = s.eval(0.9);
            assert!(c1.abs() < 1e-9, "natural end");
            let (v, sl, _) = s.eval(1.4);
            assert!((v - (v1 + 0.5 * s1)).abs() < 1e-12 && sl == s1);
        }
        assert!(s_nan());
    }

    fn s_nan() -> bool {
        let s = CubicSpline::fit(&[0.0, 1.0, 2.0, 3.0], &[0.0; 4], None, 0.0).unwrap();
        s.eval(f64::NAN).0.is_nan()
    }

    #[test]
    fn smoothing_leaves_a_straight_line_unchanged() {
        let y: Vec<f64> = (0..20).map(|i| i as f64 * 0.01).collect();
        let z: Vec<f64> = y.iter().map(|v| 2.0 * v + 1.0).collect();
        let s = CubicSpline::fit(&y, &z, None, 0.5).unwrap();
        // A straight line has g'''' = 0: not filtered at all (to rounding).
        assert!((s.eval(0.077).0 - (2.0 * 0.077 + 1.0)).abs() < 1e-10);
    }

    #[test]
    fn rejects_bad_input() {
        let y = [0.0, 1.0, 2.0, 3.0];
        assert_eq!(
            CubicSpline::fit(&y[..3], &[0.0; 3], None, 0.0),
            Err(SplineError::TooFewPoints(3))
        );
        assert_eq!(
            CubicSpline::fit(&[0.0, 1.0, 1.0, 3.0], &[0.0; 4], None, 0.0),
            Err(SplineError::NotIncreasing(2))
        );
        assert_eq!(
            CubicSpline::fit(&y, &[0.0, f64::NAN, 0.0, 0.0], None, 0.0),
            Err(SplineError::NonFinite(1))
        );
        assert_eq!(
            CubicSpline::fit(&y, &[0.0; 4], Some(&[1.0, 0.0, 1.0, 1.0]), 0.1),
            Err(SplineError::BadWeight(1))
        );
        assert!(CubicSpline::fit(&y, &[0.0; 4], None, f64::INFINITY).is_err());
        assert!(CubicSpline::fit(&y, &[0.0; 4], None, -1.0).is_err());
    }

    /// Curvature of a noisy sampled circle: the use case smoothing exists for.
    ///
    /// Circle of radius R = 0.3 m (the UIC60 crown), |y| ≤ 30 mm at h = 0.1 mm, Gaussian noise
    /// σ = 2 µm (order of a hand-held profilometer's noise). Prediction (module header) for
    /// ℓ = 2 mm: s(g'') = σ √(h/(8√2 ℓ⁵)) = 0.033 1/m = 1.0 % of κ = 3.33 1/m (checked on pure
    /// noise: 0.0336 1/m measured). Evaluated over |y| ≤ 15 mm, 7.5ℓ from the ends, where the
    /// natural end bias (decaying as exp(−d/(√2ℓ))) is below 0.5 %. Tolerances: rms error ≤ 2 %
    /// (twice the prediction), largest error ≤ 5 % (≈ 4 standard deviations plus the end bias).
    /// Without smoothing the error is of order σ/h² = 200 1/m: it must exceed 100 % somewhere.
    #[test]
    fn smoothing_recovers_the_curvature_of_a_noisy_circle() {
        let r = 0.3;
        let h = 1e-4;
        let sigma = 2e-6;
        let ell = 2e-3;
        let mut rng = Lcg(12345);
        let y: Vec<f64> = (0..=600).map(|i| -0.03 + h * i as f64).collect();
        let z: Vec<f64> = y
            .iter()
            .map(|v| r - (r * r - v * v).sqrt() + sigma * rng.normal())
            .collect();
        let kappa = 1.0 / r;
        let curvature = |s: &CubicSpline, v: f64| {
            let (_, d, dd) = s.eval(v);
            dd / (1.0 + d * d).powf(1.5)
        };
        let smooth = CubicSpline::fit(&y, &z, None, ell).unwrap();
        let raw = CubicSpline::fit(&y, &z, None, 0.0).unwrap();
        let (mut worst_s, mut worst_r, mut sum2, mut count) = (0.0f64, 0.0f64, 0.0, 0);
        for i in 0..=300 {
            let v = -0.015 + 1e-4 * i as f64;
            let es = (curvature(&smooth, v) - kappa).abs() / kappa;
            worst_s = worst_s.max(es);
            worst_r = worst_r.max((curvature(&raw, v + 0.3 * h) - kappa).abs() / kappa);
            sum2 += es * es;
            count += 1;
        }
        let rms = (sum2 / count as f64).sqrt();
        let predicted = sigma * (h * NOISE_FACTOR / ell.powi(5)).sqrt() / kappa;
        assert!((predicted - 0.010).abs() < 0.001, "{predicted}");
        assert!(rms < 2.0 * predicted, "rms {rms}, predicted {predicted}");
        assert!(worst_s < 0.05, "smoothed worst {worst_s}");
        assert!(worst_r > 1.0, "interpolated worst {worst_r}");
        // The helper inverts the prediction.
        let l = smoothing_length_for_noise(sigma, h, predicted * kappa);
        assert!((l - ell).abs() < 1e-9 * ell.max(1.0) + 1e-12, "{l}");
    }
}
