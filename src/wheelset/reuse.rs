//! A creep pass's tangential solution, carried into the next pass of the same step when the
//! normal forces moved by little (docs/theory.md §8.3).
//!
//! A prescribed wheel load is carried by the normal forces and the creep forces' vertical
//! component together ([`crate::wheelset::balance::creep_passes`]): the first pass balances the
//! normal forces against Q less the predicted component, solves the tangential problem and finds
//! the component; the next pass balances the normal forces against Q less that one. On a moving
//! wheelset the two targets differ by ~1e−6 of Q (the component's prediction from the last steps
//! misses by that much: FASTSIM's force is only piecewise smooth in the creepages, as elements
//! switch between adhesion and slip), so the second pass's normal forces differ from the first's
//! by that much, and solving the tangential problem again would change its forces by at most
//! ~μ/3 of that (see below).
//!
//! Where the targets differ by at most [`REUSE_WINDOW`] of Q, the second pass keeps the first
//! pass's tangential solution, scaled to each patch's new normal force N by the power law of its
//! similarity: on an elliptic patch (a, b ∝ N^{1/3}, p0 ∝ N^{1/3}, Kalker's flexibility ∝ a)
//! the normalised creepages ξ, η scale as N^{−1/3} and the spin as N^0, so at fixed creepages a
//! force goes as N^α with α from 2/3 (the linear theory) to 1 (full slip): α is taken from the
//! patch's saturation |F|/(μN) ([`force_exponent`]), the spin moment (one more length) scales by
//! N^{α+1/3}, the largest traction (μ p0) by N^{1/3}, the frictional power as the forces; the
//! adhesion fraction is kept. The contact point, angle and creepages are the new pass's own (the
//! patch's track-axes force follows its new angle). What the law leaves out — the force's
//! direction turning as the saturation changes, the spin's share, the patch's shape and point
//! moving with the lowering — is of the order of the normal forces' relative change times the
//! force: over the hunting wheelset of docs/performance.md the wheel forces differ from solving
//! again by at most 1.0e−7 of Q for Hertz patches, 7.5e−8 for strip FASTSIM and 1.3e−7 for
//! FaStrip (`tests/warm_start.rs`), the order of the creep iteration's own tolerance (1e−7 of Q). One
//! pass per step reuses, the first after a solved one whose target lies within the window (the
//! second pass, or a later one closing on the fixed point); a reused pass that does not
//! converge is followed by solved ones ([`crate::wheelset::balance::creep_passes`]).

use nalgebra::Vector3;

use crate::geometry::groups::MAX_GROUPS;
use crate::tangential::strip_fastsim::StripFastsimResult;

/// Largest change of a wheel's normal-force target between two creep passes, relative to the
/// wheel load, across which the later pass reuses the earlier pass's tangential solution
/// (scaled) instead of solving the tangential problem again.
pub(super) const REUSE_WINDOW: f64 = 3e-6;

/// The tangential solution of one patch, at the normal force it was solved for.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct PatchTangential {
    /// Normal force the tangential problem was solved at [N] (unweighted).
    pub normal_force: f64,
    /// The patch within its wheel's layout of the step (a Hertz patch's group, a strip patch's
    /// index among the strip patches): the same key, the same patch, whatever patches appear or
    /// vanish beside it between passes.
    pub key: usize,
    /// Its forces in its contact axes, adhesion fraction, frictional power and largest
    /// traction (on a Hertz patch FASTSIM's, on a strip patch the strip solver's).
    pub solution: StripFastsimResult,
    /// The tangential force in track axes [N] (unweighted; strip patches, whose strips have
    /// their own angles).
    pub tangential: Vector3<f64>,
}

impl PatchTangential {
    /// The solution scaled to the normal force `normal_force` at friction coefficient `mu`
    /// (see the module's text); `None` where either force is not positive.
    pub fn scaled(&self, normal_force: f64, mu: f64) -> Option<Self> {
        let ratio = normal_force / self.normal_force;
        if !(ratio.is_finite() && ratio > 0.0) {
            return None;
        }
        let s = &self.solution;
        let exponent = force_exponent(s.fx.hypot(s.fy) / (mu * self.normal_force));
        let force = ratio.powf(exponent);
        Some(Self {
            normal_force,
            key: self.key,
            solution: StripFastsimResult {
                fx: s.fx * force,
                fy: s.fy * force,
                mz: s.mz * ratio.powf(exponent + 1.0 / 3.0),
                adhesion_fraction: s.adhesion_fraction,
                frictional_power: s.frictional_power * force,
                max_traction: s.max_traction * ratio.cbrt(),
            },
            tangential: self.tangential * force,
        })
    }
}

/// The exponent α of F ∝ N^α at fixed creepages for a patch whose creep force uses the share
/// `saturation` = |F|/(μN) of its traction bound: with the saturation curve
/// F/(μN) = 1 − (1 − x/3)³ (x ≤ 3) of the normalised creepage x ∝ N^{−1/3} (Z. Y. Shen,
/// J. K. Hedrick, J. A. Elkins, Proc. 8th IAVSD Symposium, 1983), α = 1 − t²/(1 + t + t²), t = (1 − F/(μN))^{1/3}: 2/3 in the linear theory,
/// 1 in full slip.
fn force_exponent(saturation: f64) -> f64 {
    let t = (1.0 - saturation.clamp(0.0, 1.0)).cbrt();
    1.0 - t * t / (1.0 + t + t * t)
}

/// The tangential solutions of a wheel's patches from the last pass that solved them.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct TangentialMemo {
    patches: [PatchTangential; MAX_GROUPS],
    n: usize,
    /// The pass's normal-force target [N] (None: nothing recorded).
    target: Option<f64>,
    /// Whether a pass of this step has reused a record (at most one does).
    spent: bool,
}

impl TangentialMemo {
    /// Starts recording the solutions of a pass balanced against `target` [N] (NaN: a pass
    /// without a load target, never reused).
    pub fn start(&mut self, target: f64) {
        self.n = 0;
        self.target = Some(target);
    }

    /// Records the next patch's solution.
    pub fn push(&mut self, patch: PatchTangential) {
        if self.n < MAX_GROUPS {
            self.patches[self.n] = patch;
            self.n += 1;
        }
    }

    /// Whether a pass balanced against `target` [N] on a wheel of load `load` [N] may reuse the
    /// recorded solutions — within [`REUSE_WINDOW`], and once per step: the passes after a
    /// reused one (which did not converge) solve again — and marks the step's reuse spent if so.
    pub fn take(&mut self, target: f64, load: f64) -> bool {
        let allowed = !self.spent
            && self
                .target
                .is_some_and(|recorded| (target - recorded).abs() <= REUSE_WINDOW * load);
        self.spent |= allowed;
        allowed
    }

    /// The recorded solution of the patch `key` ([`PatchTangential::key`]) scaled to
    /// `normal_force` at friction coefficient `mu`; `None` where that patch was not recorded or
    /// either force is not positive (the patch then solves its tangential problem).
    pub fn scaled(&self, key: usize, normal_force: f64, mu: f64) -> Option<PatchTangential> {
        self.patches[..self.n]
            .iter()
            .find(|p| p.key == key)?
            .scaled(normal_force, mu)
    }
}

impl TangentialMemo {
    /// What creep pass `k` of a step, balanced against `target` [N] on a wheel of load `load`
    /// [N], does about the tangential problem: a later pass (k > 0) reuses the record where
    /// `reuse` allows and [`TangentialMemo::take`] grants it; otherwise it solves and records.
    pub fn pass(&mut self, k: usize, target: f64, load: f64, reuse: bool) -> Tangential<'_> {
        if k > 0 && reuse && self.take(target, load) {
            Tangential::Reuse(self)
        } else {
            self.start(target);
            Tangential::Solve(self)
        }
    }
}

/// What a wheel's evaluation does about the tangential problem.
pub(super) enum Tangential<'a> {
    /// Normal forces only.
    None,
    /// Solve it on every patch, recording the solutions.
    Solve(&'a mut TangentialMemo),
    /// Take every patch's from the record, scaled to its new normal force.
    Reuse(&'a TangentialMemo),
}

impl Tangential<'_> {
    /// Whether the pass takes its solutions from the record.
    pub fn reuses(&self) -> bool {
        matches!(self, Self::Reuse(_))
    }

    /// Patch `key`'s solution ([`PatchTangential::key`]) taken from the record, scaled to
    /// `normal_force` at friction coefficient `mu`, or solved by `solve` (and recorded when the
    /// pass records).
    pub fn patch<E>(
        &mut self,
        key: usize,
        normal_force: f64,
        mu: f64,
        solve: impl FnOnce() -> Result<PatchTangential, E>,
    ) -> Result<PatchTangential, E> {
        if let Self::Reuse(memo) = self {
            if let Some(t) = memo.scaled(key, normal_force, mu) {
                return Ok(t);
            }
        }
        let t = solve()?;
        if let Self::Solve(memo) = self {
            memo.push(t);
        }
        Ok(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaling_follows_the_similarity_exponents() {
        let p = PatchTangential {
            normal_force: 1e4,
            key: 0,
            solution: StripFastsimResult {
                fx: 100.0,
                fy: -200.0,
                mz: 3.0,
                adhesion_fraction: 0.4,
                frictional_power: 50.0,
                max_traction: 1e8,
            },
            tangential: Vector3::new(100.0, -190.0, 20.0),
        };
        let scaled = p.scaled(8e4, 0.3).unwrap();
        let s = &scaled.solution;
        // 8 = 2³: forces × 2^{3α}, the moment × 2^{3α+1}, the traction bound × 2, with α of
        // the saturation |F|/(μN) = √5·100/3000.
        let alpha = force_exponent(100.0 * 5f64.sqrt() / 3e3);
        assert!(alpha > 2.0 / 3.0 && alpha < 0.7, "{alpha}");
        let f = 2f64.powf(3.0 * alpha);
        assert!((s.fx / (100.0 * f) - 1.0).abs() < 1e-14);
        assert!((s.fy / (-200.0 * f) - 1.0).abs() < 1e-14);
        assert!((s.mz / (3.0 * 2.0 * f) - 1.0).abs() < 1e-14);
        assert!((s.max_traction / 2e8 - 1.0).abs() < 1e-14);
        assert_eq!(s.adhesion_fraction, 0.4);
        assert!((scaled.tangential.z / (20.0 * f) - 1.0).abs() < 1e-14);
        assert!(p.scaled(0.0, 0.3).is_none());
        // The exponent's ends: the linear theory and full slip.
        assert!((force_exponent(0.0) - 2.0 / 3.0).abs() < 1e-15);
        assert!((force_exponent(1.0) - 1.0).abs() < 1e-15);
        assert!(force_exponent(0.5) > force_exponent(0.2));
        assert!(p.scaled(f64::NAN, 0.3).is_none());
    }

    #[test]
    fn the_record_is_reused_only_within_its_window_and_for_its_own_patches() {
        let mut memo = TangentialMemo::default();
        assert!(!memo.take(4e4, 4e4), "nothing recorded");
        memo.start(4e4);
        memo.push(PatchTangential {
            normal_force: 4e4,
            key: 2,
            ..PatchTangential::default()
        });
        // Window 3e−6 of 40 kN: 0.12 N; once.
        assert!(!memo.take(4e4 + 0.2, 4e4));
        assert!(memo.take(4e4 + 0.1, 4e4));
        assert!(!memo.take(4e4 + 0.1, 4e4), "used once already");
        assert!(memo.scaled(2, 4.0001e4, 0.3).is_some());
        assert!(
            memo.scaled(0, 4e4, 0.3).is_none(),
            "another patch, not recorded"
        );
        assert!(memo.scaled(2, 0.0, 0.3).is_none(), "no normal force");
        memo.start(4e4);
        assert!(
            !memo.take(4e4, 4e4),
            "once per step, also after a new record"
        );
    }
}
