//! Influence coefficients: the surface displacement due to a uniformly loaded rectangle.

use std::f64::consts::PI;

/// Displacement [m] at offset (x, y) [m] from the centre of a dx × dy element carrying unit
/// uniform pressure (1 Pa), combined for both bodies of contact modulus `e_star` [Pa]
/// (Love 1929; see the crate documentation). Symmetric in ±x, ±y; → dx dy/(π E* r) far away.
pub fn influence_coefficient(dx: f64, dy: f64, x: f64, y: f64, e_star: f64) -> f64 {
    let (a, b) = (0.5 * dx, 0.5 * dy);
    let s = corner_integral(x + a, y + b)
        - corner_integral(x - a, y + b)
        - corner_integral(x + a, y - b)
        + corner_integral(x - a, y - b);
    s / (PI * e_star)
}

/// Signed ∫₀^x ∫₀^y dt ds / √(s² + t²) = sgn(x) sgn(y) (|x| asinh(|y|/|x|) + |y| asinh(|x|/|y|)),
/// zero on the axes.
pub(crate) fn corner_integral(x: f64, y: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    if ax == 0.0 || ay == 0.0 {
        return 0.0;
    }
    let v = ax * (ay / ax).asinh() + ay * (ax / ay).asinh();
    if (x < 0.0) != (y < 0.0) {
        -v
    } else {
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{e_star, rel};

    #[test]
    fn influence_coefficient_limits() {
        let es = e_star();
        let (dx, dy) = (1e-3, 2e-3);
        // Centre of a uniformly loaded square of side d: u = 4 ln(1 + √2) p d/(π E*), i.e. the
        // classical 2.24 (1 − ν²) p a/E per body for a square of side 2a.
        let c = influence_coefficient(dx, dx, 0.0, 0.0, es);
        assert!(rel(c, 4.0 * (1.0 + 2f64.sqrt()).ln() * dx / (PI * es)) < 1e-14);
        // Even in x and y.
        let c1 = influence_coefficient(dx, dy, 3e-3, -5e-3, es);
        for &(x, y) in &[(-3e-3, -5e-3), (3e-3, 5e-3), (-3e-3, 5e-3)] {
            assert!(rel(influence_coefficient(dx, dy, x, y, es), c1) < 1e-14);
        }
        // Far field: point force dx dy p/(π E* r), relative error O((d/r)²).
        let (x, y) = (0.3, 0.4);
        let c = influence_coefficient(dx, dy, x, y, es);
        assert!(rel(c, dx * dy / (PI * es * 0.5)) < 1e-5);
    }
}
