//! The wheel-height iteration for a prescribed wheel load, shared by the multi-Hertzian and the
//! strip solutions of a wheel (docs/theory.md §5.2, §8.3).
//!
//! The vertical force F(dz) of the rail on a wheel lowered by dz is zero at the touching height
//! and grows monotonically, but its slope jumps where patches or strips enter and it can jump
//! where two interpenetration regions merge. So: bracket the load by doubling the approach from
//! a first estimate, then Illinois (modified regula falsi) inside the bracket — bracketing,
//! superlinear, and when the force jumps across the load the bracket closes on the jump and the
//! end nearer to the load is taken.

use super::{SideResult, WheelsetError};
use crate::numeric::roots::Illinois;

/// Relative tolerance on the vertical force balance.
pub const LOAD_TOLERANCE: f64 = 1e-9;

/// Largest approach tried while bracketing [m] (5 cm is far beyond any elastic contact).
const MAX_APPROACH: f64 = 0.05;

/// Largest relative overshoot of the Hertzian predictor while bracketing: 2 % in the approach,
/// so a force law a little stiffer or softer than δ^{3/2} (strip models, a second patch) is
/// still bracketed in one trial.
const PREDICTOR_MARGIN: f64 = 0.02;

/// The overshoot as a fraction of the predictor's own correction, where that is smaller than
/// [`PREDICTOR_MARGIN`]: a first trial close to the root (a warm start on a moving pose: ~1e−5
/// of the approach) is followed by a second one just beyond the root, not 2 % beyond it, so the
/// bracket the regula falsi starts from is as tight as the prediction (a force law whose local
/// exponent differs from 3/2 by up to half of it is still bracketed in one trial).
const PREDICTOR_OVERSHOOT: f64 = 0.5;

/// The relative overshoot of a predicted approach ratio `ratio` (the Hertzian law's root over
/// the last trial) [-].
fn predictor_margin(ratio: f64) -> f64 {
    (PREDICTOR_OVERSHOOT * (ratio - 1.0).abs()).min(PREDICTOR_MARGIN)
}

/// Bracketing trials (doubling from 1e−9 m reaches MAX_APPROACH in 26).
const BRACKET_TRIALS: usize = 64;

/// Result of [`balance`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Balanced {
    /// The lowering that carries the load [m].
    pub lowering: f64,
    /// Whether `lowering` was the last point evaluated (so the caller's state belongs to it).
    pub evaluated: bool,
    /// Secant slope of the force through the last two points evaluated, per unit of the
    /// iteration's variable (u = δ^{3/2} for [`ForceLaw::Hertzian`], else dz) [N/m^{3/2}] or
    /// [N/m]; NaN where fewer than two points were evaluated. A good first step of the next
    /// balance of the same wheel under a slightly different load.
    pub slope: f64,
}

/// How the force grows with the approach, which sets the variable of the regula falsi.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ForceLaw {
    /// Any increasing force: regula falsi in the lowering dz.
    General,
    /// Close to a Hertz patch's F ∝ δ^{3/2}: regula falsi in u = δ^{3/2}.
    Hertzian,
}

/// Finds the lowering dz at which `residual(dz)` = F(dz) − load [N] vanishes (to
/// [`LOAD_TOLERANCE`] × load), given the touching lowering `touch` (where the residual is
/// −load), a first approach estimate `first_approach` > 0 [m] and at most `iterations` Illinois
/// steps. Errors of `residual` are passed on. With [`ForceLaw::Hertzian`] (the multi-Hertzian
/// wheel) the regula falsi runs in u = δ^{3/2} (δ = dz − touch), where a Hertz patch's force is
/// linear, so one step solves a single patch and a few steps several (the strip models' forces
/// are further from that law: with them it needs more steps than in dz, measured).
///
/// Bracketing starts at the first estimate, which is accepted at once when it balances the load
/// (a warm start from the previous step). Otherwise the next trial comes from the Hertzian law
/// F ∝ δ^{3/2} through the last point (aimed [`PREDICTOR_MARGIN`] beyond the root, so that it
/// brackets it; at most doubling or halving the approach per trial) until the root is bracketed;
/// the Illinois steps then work in that tight bracket.
///
/// `slope`: the force's slope dF/du near the root from a previous balance of the same wheel
/// ([`Balanced::slope`]), if known (else `None`): the first trial's correction is then Newton's
/// step with it, aimed at the root itself, which under a load changed by ~1e−6 (the creep
/// iteration's second pass) lands within the tolerance, where the Hertzian law's step overshoots
/// on purpose and needs a regula falsi step more.
pub fn balance<E>(
    touch: f64,
    first_approach: f64,
    load: f64,
    iterations: usize,
    law: ForceLaw,
    slope: Option<f64>,
    mut residual: impl FnMut(f64) -> Result<f64, E>,
) -> Result<Balanced, E> {
    let hertzian = law == ForceLaw::Hertzian;
    let u_of = |dz: f64| {
        if hertzian {
            let d = (dz - touch).max(0.0);
            d * d.sqrt()
        } else {
            dz
        }
    };
    let dz_of = |u: f64| {
        if hertzian {
            touch + u.cbrt().powi(2)
        } else {
            u
        }
    };
    // The last two points evaluated, (u, residual), for the secant slope.
    let mut recent = [(f64::NAN, f64::NAN); 2];
    let mut evaluate = |dz: f64| -> Result<f64, E> {
        let f = residual(dz)?;
        recent = [recent[1], (u_of(dz), f)];
        Ok(f)
    };
    let secant = |recent: &[(f64, f64); 2]| {
        let [(u0, f0), (u1, f1)] = *recent;
        (f1 - f0) / (u1 - u0)
    };
    let mut newton_slope = slope.filter(|s| s.is_finite() && *s > 0.0);
    let (mut lo, mut f_lo) = (touch, -load);
    let (mut hi, mut f_hi) = (f64::NAN, f64::NAN);
    let mut approach = first_approach.max(f64::MIN_POSITIVE);
    for _ in 0..BRACKET_TRIALS {
        let dz = touch + approach;
        let f = evaluate(dz)?;
        if f.abs() <= LOAD_TOLERANCE * load {
            return Ok(Balanced {
                lowering: dz,
                evaluated: true,
                slope: secant(&recent),
            });
        }
        // Newton's step with a known slope, once: aimed at the root (no overshoot).
        if let Some(s) = newton_slope.take() {
            let u = u_of(dz);
            let next = dz_of(u - f / s) - touch;
            if next.is_finite() && next > 0.5 * approach && next < 2.0 * approach {
                if f > 0.0 {
                    (hi, f_hi) = (dz, f);
                } else {
                    (lo, f_lo) = (dz, f);
                }
                approach = next;
                continue;
            }
        }
        let force = f + load;
        if f > 0.0 {
            (hi, f_hi) = (dz, f);
            if dz - lo <= LOAD_TOLERANCE * approach || f_lo > -load {
                // Bracketed on both sides by evaluated points.
                break;
            }
            // Too deep: predict the root from below.
            let hertz = (load / force).powf(2.0 / 3.0);
            let ratio = hertz * (1.0 - predictor_margin(hertz));
            let next = approach * ratio.max(0.5);
            if touch + next <= lo {
                break;
            }
            approach = next;
        } else {
            (lo, f_lo) = (dz, f);
            if f_hi > 0.0 {
                break;
            }
            if approach > MAX_APPROACH {
                break;
            }
            let ratio = if force > 0.0 {
                let hertz = (load / force).powf(2.0 / 3.0);
                hertz * (1.0 + predictor_margin(hertz))
            } else {
                2.0
            };
            approach *= ratio.min(2.0);
        }
    }
    if f_hi.is_nan() || f_hi <= 0.0 {
        // No point above the load (the force stays below it up to MAX_APPROACH): the deepest
        // point tried is the answer the caller gets, as before.
        return Ok(Balanced {
            lowering: lo,
            evaluated: true,
            slope: secant(&recent),
        });
    }
    let mut bracket = Illinois::new((lo, f_lo), (hi, f_hi));
    let mut last = hi;
    for _ in 0..iterations {
        let mid = bracket.inside_or_midpoint(dz_of(bracket.secant_in(u_of)));
        let f_mid = evaluate(mid)?;
        last = mid;
        if f_mid.abs() <= LOAD_TOLERANCE * load {
            return Ok(Balanced {
                lowering: mid,
                evaluated: true,
                slope: secant(&recent),
            });
        }
        bracket.update(mid, f_mid);
    }
    let ((lo, f_lo), (hi, f_hi)) = (bracket.neg, bracket.pos);
    let best = if f_lo.abs() < f_hi.abs() { lo } else { hi };
    Ok(Balanced {
        lowering: best,
        evaluated: best == last,
        slope: secant(&recent),
    })
}

/// Smallest share of the wheel load the normal forces carry when the creep forces' vertical
/// components are subtracted (they cannot carry the wheel: |Fy| ≤ μN).
pub(super) const MIN_NORMAL_SHARE: f64 = 0.05;

/// Passes of the strip models' load balance that update the creep forces' vertical component.
pub(super) const CREEP_PASSES: usize = 12;

/// Relative tolerance of that update on the wheel load.
pub(super) const CREEP_TOLERANCE: f64 = 1e-7;

/// Largest relative deviation of the carried vertical force from a prescribed wheel load before
/// a step is refused ([`WheelsetError::Unbalanced`]). Balanced solutions meet the iteration
/// tolerances (1e−9 normal, [`CREEP_TOLERANCE`] with creep); a normal force that jumps with the
/// wheel height (Linder's strips entering contact, two regions merging) leaves the nearer end of
/// the jump, ≤ 0.1 % in the tests; 1 % flags a solution that is wrong.
pub const LOAD_CHECK_TOLERANCE: f64 = 1e-2;

/// Absolute part of that check [N]: loads of micronewtons (1 µN and up is contact, below is
/// lift-off) need approaches of ~1e−15 m, below the strip models' round-off; 0.01 N is nothing
/// to a wheel that carries 1e4–1e5 N.
pub const LOAD_CHECK_FLOOR: f64 = 1e-2;

/// Where the prescribed-load iteration of a wheel starts: the previous step's solution,
/// extrapolated along its last two changes (a moving wheelset's approach and creep component
/// change smoothly from step to step: the quadratic extrapolation through the last three steps
/// misses a 5 Hz hunting motion at 1 ms steps by (ωh)³ ≈ 3e−5 of its swing, where the last
/// value alone misses by ωh ≈ 3e−2 and the linear extrapolation by (ωh)² ≈ 1e−3: −11 % of the
/// instructions of a hunting Hertz step against the linear one). With it a step whose inputs changed little
/// needs one tangential solve and a few cheap normal-force evaluations instead of a cold search.
/// Part of the FMU state (outputs depend on it at the level of the iteration tolerances).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WarmStart {
    /// Lowering beyond first touch at which the multi-Hertzian normal forces carried the load
    /// [m] (> 0; for the strip models their normal-only Hertz estimate).
    pub approach: f64,
    /// Vertical component of the creep forces on the wheel, upwards positive [N].
    pub creep: f64,
    /// Change of `approach` [m] and `creep` [N] over the step that produced them (0 after a
    /// cold start).
    pub approach_step: f64,
    pub creep_step: f64,
    /// Change of those changes over that step [m], [N] (0 until two changes are known).
    pub approach_bend: f64,
    pub creep_bend: f64,
    /// Steps behind this one whose solutions are known, at most 2 (0: a cold start, 1: the
    /// changes are known, 2: also the bends).
    pub history: u8,
    /// Strip models: the approach at which their patches carried the load less the creep
    /// forces' vertical component, over `approach` [-] (the first trial of the next step's
    /// iteration is `approach` times this; 1 for the multi-Hertzian solution).
    pub strip_ratio: f64,
}

impl WarmStart {
    /// The first guess for the next step: the quadratic extrapolation of the approach (kept
    /// within [½, 2] × the last one, so that a jump in the inputs cannot send it far off) and of
    /// the creep component.
    pub fn predicted(&self) -> (f64, f64) {
        let approach = (self.approach + self.approach_step + self.approach_bend)
            .clamp(0.5 * self.approach, 2.0 * self.approach);
        (approach, self.creep + self.creep_step + self.creep_bend)
    }

    /// The warm start after a step that found `approach`, `creep` and the strip ratio
    /// [`WarmStart::strip_ratio`], following `previous`.
    pub(super) fn after(
        previous: Option<WarmStart>,
        approach: f64,
        creep: f64,
        strip_ratio: f64,
    ) -> Self {
        let mut next = Self {
            approach,
            creep,
            approach_step: 0.0,
            creep_step: 0.0,
            approach_bend: 0.0,
            creep_bend: 0.0,
            history: 0,
            strip_ratio,
        };
        if let Some(p) = previous {
            next.approach_step = approach - p.approach;
            next.creep_step = creep - p.creep;
            next.history = 1;
            if p.history >= 1 {
                next.approach_bend = next.approach_step - p.approach_step;
                next.creep_bend = next.creep_step - p.creep_step;
                next.history = 2;
            }
        }
        next
    }
}

/// Vertical component of the creep forces of `out` on the wheel (upwards positive) [N]: the
/// total upward force less the normal forces' share (so that the non-planar strips' own
/// directions count).
pub(super) fn creep_upward(out: &SideResult) -> f64 {
    let normal: f64 = out.groups[..out.n_groups]
        .iter()
        .map(|p| p.fn_ * p.contact_angle.cos())
        .sum();
    -out.force[2] - normal
}

/// The prescribed wheel load `q` [N] is carried by the normal forces and the creep forces'
/// vertical component together. `pass(k, target)` balances the normal forces against `target`
/// = q less the current estimate of that component, solves the tangential problem there and
/// returns the component it finds (`None`: no tangential problem, stop). The estimate starts
/// from `start` (zero, or the previous step's) and is updated by [`CreepFixedPoint`] until it
/// changes by at most [`CREEP_TOLERANCE`] of q, or for [`CREEP_PASSES`] passes. Returns the last
/// component found (`None` if no pass solved a tangential problem).
pub(super) fn creep_passes(
    q: f64,
    start: f64,
    mut pass: impl FnMut(usize, f64) -> Result<Option<f64>, WheelsetError>,
) -> Result<Option<f64>, WheelsetError> {
    let mut creep = if start.is_finite() { start } else { 0.0 };
    let mut fixed_point = CreepFixedPoint::default();
    let mut found = None;
    for k in 0..CREEP_PASSES {
        let target = (q - creep).max(MIN_NORMAL_SHARE * q);
        let Some(new_creep) = pass(k, target)? else {
            break;
        };
        found = Some(new_creep);
        if k + 1 == CREEP_PASSES || (new_creep - creep).abs() <= CREEP_TOLERANCE * q {
            break;
        }
        creep = fixed_point.next(creep, new_creep);
    }
    Ok(found)
}

/// Refuses a wheel whose vertical force misses its prescribed `load` [N] by more than
/// [`LOAD_CHECK_TOLERANCE`] (or is not finite); no load (prescribed position) and lift-off pass.
pub(super) fn check_balance(
    side: &'static str,
    load: Option<f64>,
    out: &SideResult,
) -> Result<(), WheelsetError> {
    let Some(q) = load.filter(|&q| q > 0.0) else {
        return Ok(());
    };
    // The rail's vertical force on the wheel is −Fz (z down, docs/conventions.md).
    let carried = -out.force[2];
    if (carried - q).abs() <= LOAD_CHECK_TOLERANCE * q + LOAD_CHECK_FLOOR {
        Ok(())
    } else {
        Err(WheelsetError::Unbalanced {
            side,
            carried,
            load: q,
        })
    }
}

/// Fixed-point iteration c ← g(c) on the creep forces' vertical component, accelerated by the
/// secant on h(c) = g(c) − c once two iterates exist (Steffensen-like; falls back to the plain
/// step when the secant is degenerate). The map is contracting (|g'| ≲ μ sin γ), so a few passes
/// reach [`CREEP_TOLERANCE`] — but on strip patches g is only piecewise smooth: it jumps by a
/// few newtons where the discretised tangential solution changes its element set with the
/// wheel height, and across a jump the secant bounces between the two sides. So the iterates
/// that bracket the root of h (h > 0 below, h < 0 above) are kept, and a step that would leave
/// the bracket bisects it instead, closing on the root or on the jump.
#[derive(Debug, Default)]
pub(super) struct CreepFixedPoint {
    previous: Option<(f64, f64)>,
    /// Largest iterate with h > 0 and smallest with h < 0 so far.
    below: Option<f64>,
    above: Option<f64>,
}

impl CreepFixedPoint {
    /// The next iterate after evaluating g(`c`) = `g`.
    pub(super) fn next(&mut self, c: f64, g: f64) -> f64 {
        let h = g - c;
        if h > 0.0 {
            self.below = Some(self.below.map_or(c, |b| b.max(c)));
        } else if h < 0.0 {
            self.above = Some(self.above.map_or(c, |a| a.min(c)));
        }
        let next = match self.previous {
            Some((c0, h0)) if (h - h0).abs() > 0.0 && c != c0 => {
                let secant = c - h * (c - c0) / (h - h0);
                if secant.is_finite() {
                    secant
                } else {
                    g
                }
            }
            _ => g,
        };
        self.previous = Some((c, h));
        match (self.below, self.above) {
            (Some(lo), Some(hi)) if lo < hi && !(next > lo && next < hi) => 0.5 * (lo + hi),
            _ => next,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hertzian_force_is_balanced() {
        // F = k (dz − touch)^{3/2}: the root is known in closed form.
        let (k, touch, load): (f64, f64, f64) = (1e10, -2e-4, 8e4);
        let exact = touch + (load / k).powf(2.0 / 3.0);
        let mut evaluations = [0usize; 2];
        let laws = [ForceLaw::General, ForceLaw::Hertzian];
        for (law, calls) in laws.into_iter().zip(&mut evaluations) {
            let b = balance(touch, 1e-5, load, 60, law, None, |dz| {
                *calls += 1;
                Ok::<_, ()>(k * (dz - touch).max(0.0).powf(1.5) - load)
            })
            .unwrap();
            assert!(b.evaluated);
            assert!((b.lowering - exact).abs() < 1e-9 * exact.abs());
        }
        // In u = δ^{3/2} the force is linear: the regula falsi needs fewer evaluations.
        assert!(evaluations[1] < evaluations[0], "{evaluations:?}");
    }

    #[test]
    fn a_jump_across_the_load_gives_the_nearer_bracket_end() {
        // F jumps from 0.9 load to 1.2 load at dz = 1e−4: no exact root; the end with the
        // smaller residual (0.1 load below the jump) is returned.
        let load = 1e4;
        let b = balance(0.0, 1e-5, load, 60, ForceLaw::General, None, |dz| {
            Ok::<_, ()>(
                if dz < 1e-4 {
                    0.9 * load * dz / 1e-4
                } else {
                    1.2 * load
                } - load,
            )
        })
        .unwrap();
        assert!((b.lowering - 1e-4).abs() < 1e-12, "{b:?}");
    }

    #[test]
    fn residual_errors_are_passed_on() {
        assert_eq!(
            balance(
                0.0,
                1e-5,
                1.0,
                10,
                ForceLaw::General,
                None,
                |_| Err::<f64, _>("bad")
            ),
            Err("bad")
        );
    }

    fn carrying(upward: f64) -> SideResult {
        let mut out = SideResult::default();
        out.force[2] = -upward;
        out
    }

    #[test]
    fn a_load_not_carried_is_refused_with_both_forces_named() {
        let q = 92_536.0;
        // Within the tolerance (a Linder-type jump of 0.1 %) and exactly balanced: accepted.
        for upward in [q, q * (1.0 + 1e-3), q * (1.0 - 0.9 * LOAD_CHECK_TOLERANCE)] {
            assert!(check_balance("right", Some(q), &carrying(upward)).is_ok());
        }
        // 18 % short (the ANALYN two-point case before its fix), nothing carried, NaN: refused.
        for upward in [0.82 * q, 0.0, f64::NAN, 1.02 * q] {
            let e = check_balance("right", Some(q), &carrying(upward)).unwrap_err();
            assert!(matches!(e, WheelsetError::Unbalanced { side: "right", .. }));
            let message = e.to_string();
            assert!(
                message.starts_with("right wheel: the normal model carries")
                    && message.contains("9.253600e4 N")
                    && message.contains("1e-2"),
                "{message}"
            );
        }
        // The absolute floor: 1 µN carried as nothing passes.
        assert!(check_balance("right", Some(1e-6), &carrying(0.0)).is_ok());
        // Prescribed position and lift-off are not checked.
        assert!(check_balance("left", None, &carrying(0.0)).is_ok());
        assert!(check_balance("left", Some(0.0), &carrying(0.0)).is_ok());
    }
}
