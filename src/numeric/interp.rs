//! Polynomial interpolation: cubic Lagrange weights and per-interval cubics of uniform tables.

/// Weights of 4-point (cubic) Lagrange interpolation on the nodes −1, 0, 1, 2 at offset `x`
/// (x ∈ [0, 1] between nodes 0 and 1).
pub fn cubic_lagrange_weights(x: f64) -> [f64; 4] {
    [
        -x * (x - 1.0) * (x - 2.0) / 6.0,
        (x + 1.0) * (x - 1.0) * (x - 2.0) / 2.0,
        -(x + 1.0) * x * (x - 2.0) / 2.0,
        (x + 1.0) * x * (x - 1.0) / 6.0,
    ]
}

/// Cubic (Lagrange) interpolation of uniformly spaced values (at least 4) at a fractional node
/// index x ≥ 0: on the interval [k, k + 1] containing x the cubic through nodes k − 1 … k + 2
/// ([`cubic_lagrange_weights`]), with the first and last intervals' cubics extrapolated beyond
/// them. Kept per interval in monomial form, c0 + c1 t + c2 t² + c3 t³ with t = x − k: three
/// multiply-adds per evaluation instead of the four weights (equal up to rounding, tested).
#[derive(Debug, Clone)]
pub struct UniformCubic {
    /// Per interval k = 1 … n − 3 (index 0 unused; x below 1 or beyond n − 2 takes the end
    /// intervals').
    coeffs: Vec<[f64; 4]>,
}

impl UniformCubic {
    /// The interval polynomials of `values` (at least 4).
    pub fn new(values: &[f64]) -> Self {
        let n = values.len();
        assert!(n >= 4, "a cubic needs four nodes");
        let mut coeffs = vec![[0.0; 4]; n - 2];
        for (k, c) in coeffs.iter_mut().enumerate().skip(1) {
            let (v0, v1, v2, v3) = (values[k - 1], values[k], values[k + 1], values[k + 2]);
            // The Lagrange weights of `cubic_lagrange_weights` expanded in powers of t.
            *c = [
                v1,
                -v0 / 3.0 - v1 / 2.0 + v2 - v3 / 6.0,
                (v0 + v2) / 2.0 - v1,
                (v3 - v0) / 6.0 + (v1 - v2) / 2.0,
            ];
        }
        Self { coeffs }
    }

    /// The interpolant at the fractional node index `x` ≥ 0.
    #[inline]
    pub fn at(&self, x: f64) -> f64 {
        // A signed cast is one conversion instruction (an unsigned one needs a fix-up).
        let k = (x as i64).clamp(1, self.coeffs.len() as i64 - 1) as usize;
        let t = x - k as f64;
        let c = &self.coeffs[k];
        c[0] + t * (c[1] + t * (c[2] + t * c[3]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Lagrange form, evaluated directly.
    fn lagrange(values: &[f64], x: f64) -> f64 {
        let k = (x as usize).clamp(1, values.len() - 3);
        let w = cubic_lagrange_weights(x - k as f64);
        w[0] * values[k - 1] + w[1] * values[k] + w[2] * values[k + 1] + w[3] * values[k + 2]
    }

    #[test]
    fn uniform_cubic_is_the_lagrange_cubic() {
        // Rounding only: a few ulps of the values' size (tabulated values of order 1 here).
        let values: Vec<f64> = (0..40)
            .map(|k| (0.3 * k as f64).sin() + 0.01 * k as f64)
            .collect();
        let table = UniformCubic::new(&values);
        let mut worst: f64 = 0.0;
        for i in 0..=4000 {
            let x = 39.5 * i as f64 / 4000.0;
            worst = worst.max((table.at(x) - lagrange(&values, x)).abs());
        }
        assert!(worst < 1e-14, "{worst}");
        // Exact at the nodes and for cubics.
        for (k, value) in values.iter().enumerate() {
            assert!((table.at(k as f64) - value).abs() < 1e-15);
        }
        let cubic: Vec<f64> = (0..10)
            .map(|k| (k as f64).powi(3) - 2.0 * k as f64)
            .collect();
        let table = UniformCubic::new(&cubic);
        for x in [0.0, 0.3, 4.7, 8.9, 9.0] {
            assert!((table.at(x) - (x * x * x - 2.0 * x)).abs() < 1e-12);
        }
    }
}
