//! Bracketed root finding: bisection and the Illinois variant of regula falsi.
//!
//! Both keep the root inside a bracket whose ends have residuals of opposite sign, so they cannot
//! diverge. The callers keep their own stopping rules and safeguards (they differ with what is
//! solved: a load to a relative tolerance, a position to 1e−10 m, an axis ratio to a few ulp),
//! and use these for the bracket and its update.
//!
//! **Illinois** (Dowell & Jarratt 1971, "A modified regula falsi method for computing the root
//! of an equation", BIT 11): the next point is the secant of the two ends,
//! x = (x₋ f₊ − x₊ f₋)/(f₊ − f₋); it replaces the end of the same sign, and when the same end is
//! replaced twice in a row the residual kept at the other end is halved, which restores
//! superlinear convergence where plain regula falsi keeps one end for ever.

/// A bracket of a root for the Illinois iteration: `neg` = (x, f) with f < 0 and `pos` = (x, f)
/// with f ≥ 0, in either order along x. Callers that solve for a decreasing function store −f.
#[derive(Debug, Clone, Copy)]
pub struct Illinois {
    /// End with a negative residual (x, f).
    pub neg: (f64, f64),
    /// End with a non-negative residual (x, f).
    pub pos: (f64, f64),
    /// +1 if the last update replaced `pos`, −1 if it replaced `neg`, 0 before any.
    last: i8,
    /// The residuals of `neg` and `pos` as evaluated (before any halving).
    evaluated: (f64, f64),
}

impl Illinois {
    /// The bracket between `neg` (f < 0) and `pos` (f ≥ 0).
    pub fn new(neg: (f64, f64), pos: (f64, f64)) -> Self {
        Self {
            neg,
            pos,
            last: 0,
            evaluated: (neg.1, pos.1),
        }
    }

    /// The ends `neg` and `pos` with their residuals as evaluated: the kept end's residual in
    /// `neg`/`pos` is halved by the updates and is no measure of how close that end is.
    pub fn evaluated_ends(&self) -> ((f64, f64), (f64, f64)) {
        (
            (self.neg.0, self.evaluated.0),
            (self.pos.0, self.evaluated.1),
        )
    }

    /// The regula-falsi point of the bracket with the ends' positions mapped by `coordinate`
    /// (the identity, or a variable in which the residual is closer to linear; the caller maps
    /// the result back).
    pub fn secant_in(&self, coordinate: impl Fn(f64) -> f64) -> f64 {
        let ((x_neg, f_neg), (x_pos, f_pos)) = (self.neg, self.pos);
        (coordinate(x_neg) * f_pos - coordinate(x_pos) * f_neg) / (f_pos - f_neg)
    }

    /// The regula-falsi point of the bracket.
    pub fn secant(&self) -> f64 {
        self.secant_in(|x| x)
    }

    /// `x` if it lies strictly inside the bracket, else the bracket's midpoint (also for NaN).
    pub fn inside_or_midpoint(&self, x: f64) -> f64 {
        let (a, b) = (self.neg.0, self.pos.0);
        if x > a.min(b) && x < a.max(b) {
            x
        } else {
            0.5 * (a + b)
        }
    }

    /// The bracket's width |x₊ − x₋|.
    pub fn width(&self) -> f64 {
        (self.pos.0 - self.neg.0).abs()
    }

    /// Replaces the end of the same sign as `f` by (x, f), halving the other end's residual when
    /// the same end was replaced the last time too.
    pub fn update(&mut self, x: f64, f: f64) {
        if f < 0.0 {
            self.neg = (x, f);
            self.evaluated.0 = f;
            if self.last < 0 {
                self.pos.1 *= 0.5;
            }
            self.last = -1;
        } else {
            self.pos = (x, f);
            self.evaluated.1 = f;
            if self.last > 0 {
                self.neg.1 *= 0.5;
            }
            self.last = 1;
        }
    }
}

/// Bisection on [`low`, `high`] (in either order) of a predicate that holds at `low` and not at
/// `high`: halves the bracket, keeping that property, until it is at most `tolerance` wide or
/// cannot be halved further in f64, and returns its midpoint.
pub fn bisect(
    mut low: f64,
    mut high: f64,
    tolerance: f64,
    mut holds: impl FnMut(f64) -> bool,
) -> f64 {
    while (high - low).abs() > tolerance {
        let mid = 0.5 * (low + high);
        if mid == low || mid == high {
            break;
        }
        if holds(mid) {
            low = mid;
        } else {
            high = mid;
        }
    }
    0.5 * (low + high)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisection_finds_a_square_root_to_the_last_bit() {
        let root = bisect(0.0, 2.0, 0.0, |x| x * x < 2.0);
        assert!((root - std::f64::consts::SQRT_2).abs() <= 2.0 * f64::EPSILON);
        // Reversed bracket: the predicate holds at the upper end.
        let root = bisect(2.0, 0.0, 1e-9, |x| x * x > 2.0);
        assert!((root - std::f64::consts::SQRT_2).abs() <= 1e-9);
    }

    #[test]
    fn illinois_converges_superlinearly_on_a_cubic() {
        // f(x) = x³ − 2 on [0, 2]: plain regula falsi keeps the upper end for ever and needs
        // hundreds of steps to 1e−12; the Illinois halving reaches it in about a dozen.
        let f = |x: f64| x * x * x - 2.0;
        let mut bracket = Illinois::new((0.0, f(0.0)), (2.0, f(2.0)));
        let exact = 2f64.cbrt();
        let mut steps = 0;
        let mut x = 0.0;
        while (x - exact).abs() > 1e-12 {
            x = bracket.inside_or_midpoint(bracket.secant());
            bracket.update(x, f(x));
            steps += 1;
            assert!(steps < 30, "too slow: {steps} steps, x = {x}");
        }
        assert!(bracket.neg.1 < 0.0 && bracket.pos.1 >= 0.0);
    }

    #[test]
    fn evaluated_ends_keep_the_residuals_the_halving_scales() {
        // A step at x = 1 from −0.5 to +0.2: the bracket closes on the step, and the end kept
        // while the other moves has its residual halved each time — not its value.
        let f = |x: f64| if x < 1.0 { -0.5 } else { 0.2 };
        let mut bracket = Illinois::new((0.0, f(0.0)), (3.0, f(3.0)));
        let mut halved = 0;
        for _ in 0..60 {
            let x = bracket.inside_or_midpoint(bracket.secant());
            bracket.update(x, f(x));
            let ((x_neg, f_neg), (x_pos, f_pos)) = bracket.evaluated_ends();
            assert_eq!((f_neg, f_pos), (f(x_neg), f(x_pos)), "{bracket:?}");
            if bracket.neg.1 != f_neg || bracket.pos.1 != f_pos {
                halved += 1;
            }
        }
        assert!(halved > 0);
        assert!(bracket.neg.0 < 1.0 && bracket.pos.0 >= 1.0 && bracket.width() < 1e-12);
    }

    #[test]
    fn secant_in_a_mapped_coordinate_solves_a_power_law_in_one_step() {
        // f(x) = x^{3/2} − 8 is linear in u = x^{3/2}: one secant step in u lands on x = 4.
        let f = |x: f64| x * x.sqrt() - 8.0;
        let bracket = Illinois::new((1.0, f(1.0)), (9.0, f(9.0)));
        let u = bracket.secant_in(|x| x * x.sqrt());
        assert!((u.cbrt().powi(2) - 4.0).abs() < 1e-12);
    }
}
