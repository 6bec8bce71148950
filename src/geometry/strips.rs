//! Strip layout of a patch: the undeformed geometry on lateral strips of equal width.
//!
//! A patch is cut into `n` lateral strips of equal width Δs across its contact plane. Each strip
//! carries the undeformed geometry at its centre, independent of the approach δ
//! ([`StripGeometry`]): the normal gap f(s) measured from the patch's first-contact point
//! (f(0) = 0 at s = 0), the relative curvatures A(s) (rolling direction) and B(s) = ½ f''(s), and
//! the position x_c(s) of the gap minimum along x (shifted by yaw). The gap of the undeformed
//! surfaces is h(x, s) = f(s) + A(s)(x − x_c(s))². All buffers are fixed-size arrays.

/// Largest number of strips per patch.
pub const MAX_STRIPS: usize = 200;

/// One value per strip in a fixed-size buffer of [`MAX_STRIPS`] (no allocation per step):
/// indexes, slices and iterates as `[T]`, and defaults to `T::default()` on every strip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PerStrip<T>(pub [T; MAX_STRIPS]);

impl<T: Copy + Default> Default for PerStrip<T> {
    fn default() -> Self {
        Self([T::default(); MAX_STRIPS])
    }
}

impl<T> std::ops::Deref for PerStrip<T> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        &self.0
    }
}

impl<T> std::ops::DerefMut for PerStrip<T> {
    fn deref_mut(&mut self) -> &mut [T] {
        &mut self.0
    }
}

/// The undeformed geometry of one patch on its strips (independent of the approach δ).
#[derive(Debug, Clone, Default)]
pub struct StripGeometry {
    /// Number of strips in use (≤ [`MAX_STRIPS`]).
    pub n: usize,
    /// Strip width Δs [m] (uniform).
    pub ds: f64,
    /// Strip centre s_i: lateral coordinate in the contact plane from the patch's first-contact
    /// point, positive towards the field side [m]. Increasing with i.
    pub s: PerStrip<f64>,
    /// Undeformed normal gap f(s_i) at the strip's locus, measured from the first-contact point
    /// (f = 0 at s = 0, f ≥ 0 across the patch) [m].
    pub f: PerStrip<f64>,
    /// Relative longitudinal curvature A(s_i) > 0 [1/m].
    pub curv_a: PerStrip<f64>,
    /// Relative lateral curvature B(s_i) = ½ f''(s_i), raw: may be zero or negative [1/m].
    pub curv_b: PerStrip<f64>,
    /// Longitudinal position x_c(s_i) of the gap minimum along the strip (yaw lead) [m].
    pub x_c: PerStrip<f64>,
}

impl StripGeometry {
    /// A Hertzian gap f = B s², constant A, on `n` strips covering [s_lo, s_hi] (tests and
    /// examples).
    pub fn quadratic(curv_a: f64, curv_b: f64, s_lo: f64, s_hi: f64, n: usize) -> Self {
        Self::from_fn(s_lo, s_hi, n, |s| (curv_b * s * s, curv_a, curv_b))
    }

    /// A gap from a function s ↦ (f, A, B) sampled at the centres of `n` strips on [s_lo, s_hi].
    pub fn from_fn(s_lo: f64, s_hi: f64, n: usize, gap: impl Fn(f64) -> (f64, f64, f64)) -> Self {
        let n = n.clamp(1, MAX_STRIPS);
        let mut g = Self {
            n,
            ds: (s_hi - s_lo) / n as f64,
            ..Self::default()
        };
        for i in 0..n {
            let s = s_lo + (i as f64 + 0.5) * g.ds;
            let (f, a, b) = gap(s);
            g.s[i] = s;
            g.f[i] = f;
            g.curv_a[i] = a;
            g.curv_b[i] = b;
        }
        g
    }

    /// Number of strips in use, never more than [`MAX_STRIPS`] (the fields are public, so a
    /// model must not trust `n` alone).
    pub fn len(&self) -> usize {
        self.n.min(MAX_STRIPS)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Index of the strip whose extent contains s = 0 (the first-contact point), if any.
    pub fn strip_at_origin(&self) -> Option<usize> {
        (0..self.n).find(|&i| (self.s[i] - 0.5 * self.ds) <= 0.0 && 0.0 < self.s[i] + 0.5 * self.ds)
    }
}
