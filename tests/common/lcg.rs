//! Deterministic pseudo-random numbers for tests: a 64-bit linear congruential generator
//! (Knuth's MMIX constants), so that randomised tests need no extra crate and never change.
//! Included by `tests/profiles.rs` and by the unit tests of `src/numeric/spline.rs`.

/// The generator; the field is its state (the seed at construction).
pub struct Lcg(pub u64);

#[allow(dead_code)] // not every crate that includes this module uses every method
impl Lcg {
    /// Advances the state and returns it.
    fn advance(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        self.0
    }

    /// The top 31 bits of the next state.
    pub fn next_u31(&mut self) -> u64 {
        self.advance() >> 33
    }

    /// Uniform in [0, 1) from the top 53 bits of the next state.
    pub fn uniform(&mut self) -> f64 {
        (self.advance() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Standard normal by Box–Muller.
    pub fn normal(&mut self) -> f64 {
        let u1 = self.uniform().max(1e-300);
        let u2 = self.uniform();
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }
}
