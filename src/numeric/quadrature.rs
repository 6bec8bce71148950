//! Gauss–Legendre quadrature.

/// 8-point Gauss–Legendre rule on [−1, 1]: positive nodes and their weights (Abramowitz &
/// Stegun 1964, Table 25.4); exact for polynomials of degree ≤ 15 (tested).
const GAUSS_NODES: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
/// Weights of [`GAUSS_NODES`].
const GAUSS_WEIGHTS: [f64; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];

/// 8-point Gauss–Legendre integral of `g` over [lo, hi].
pub fn gauss_legendre(lo: f64, hi: f64, g: impl Fn(f64) -> f64) -> f64 {
    gauss_legendre_pair(lo, hi, |x| (g(x), 0.0)).0
}

/// [`gauss_legendre`] of two integrands at once, `g` returning both at each node (one
/// evaluation per node where they share their work).
pub fn gauss_legendre_pair(lo: f64, hi: f64, g: impl Fn(f64) -> (f64, f64)) -> (f64, f64) {
    let mid = 0.5 * (lo + hi);
    let half = 0.5 * (hi - lo);
    let (mut first, mut second) = (0.0, 0.0);
    for (node, weight) in GAUSS_NODES.iter().zip(GAUSS_WEIGHTS.iter()) {
        let (a_lo, b_lo) = g(mid - half * node);
        let (a_hi, b_hi) = g(mid + half * node);
        first += weight * (a_lo + a_hi);
        second += weight * (b_lo + b_hi);
    }
    (first * half, second * half)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_rule_is_exact_to_degree_15() {
        let exact = |k: i32| {
            if k % 2 == 1 {
                0.0
            } else {
                2.0 / (k + 1) as f64
            }
        };
        for k in 0..=15 {
            let q = gauss_legendre(-1.0, 1.0, |x| x.powi(k));
            assert!((q - exact(k)).abs() < 1e-15, "x^{k}: {q}");
        }
        assert!((gauss_legendre(-1.0, 1.0, |x| x.powi(16)) - exact(16)).abs() > 1e-6);
    }
}
