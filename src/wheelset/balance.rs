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

/// Newton and secant steps from a known slope before the bracketing takes over: on a smooth
/// force law each gains about as many digits as the last had, so three reach the tolerance
/// from a first trial within a few per cent of the root.
const NEWTON_STEPS: usize = 3;

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
    /// The residual F − load at `lowering` [N] (within the tolerance unless the iteration
    /// closed on a jump of the force).
    pub residual: f64,
}

/// Secant slope through the last two points evaluated, (u, residual) [N/m^{3/2}] or [N/m].
fn secant(recent: &[(f64, f64); 2]) -> f64 {
    let [(u0, f0), (u1, f1)] = *recent;
    (f1 - f0) / (u1 - u0)
}

/// A balanced lowering whose solution the caller holds, with the force there: where the next
/// balance of the same wheel under a slightly changed load starts ([`Root::guess`]) — without
/// evaluating it again, and with Newton's step on its slope.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Root {
    /// The lowering [m].
    pub lowering: f64,
    /// The force there [N].
    pub force: f64,
    /// The force's slope there ([`Balanced::slope`]; NaN where not measured).
    pub slope: f64,
}

impl Root {
    /// Where the balance of `load` [N] starts from this root, first touch at `touch`.
    pub fn guess(&self, touch: f64, load: f64) -> Guess {
        Guess {
            approach: self.lowering - touch,
            residual: Some(self.force - load),
            slope: Some(self.slope),
        }
    }
}

impl Balanced {
    /// The root of a balance of `load` [N].
    pub fn root(&self, load: f64) -> Root {
        Root {
            lowering: self.lowering,
            force: self.residual + load,
            slope: self.slope,
        }
    }

    /// The root `lowering`, the last point evaluated, with its `residual`.
    fn evaluated_at(lowering: f64, residual: f64, recent: &[(f64, f64); 2]) -> Self {
        Self {
            lowering,
            evaluated: true,
            slope: secant(recent),
            residual,
        }
    }
}

/// Where [`balance`] starts.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Guess {
    /// First approach beyond first touch to try [m] (> 0).
    pub approach: f64,
    /// The residual F − load at `approach` [N], where the caller has just evaluated it there
    /// (the previous pass's root under a changed load: its residual is the old one less the
    /// change) — the first trial then costs no evaluation. `None`: evaluate it.
    pub residual: Option<f64>,
    /// The force's slope dF/du near the root from an earlier balance of the same wheel
    /// ([`Balanced::slope`]), if known: the first correction is then Newton's step with it.
    pub slope: Option<f64>,
}

/// How the force grows with the approach, which sets the variable of the regula falsi.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ForceLaw {
    /// Any increasing force: regula falsi in the lowering dz.
    General,
    /// Close to a Hertz patch's F ∝ δ^{3/2}: regula falsi in u = δ^{3/2}.
    Hertzian,
}

/// Finds the lowering dz at which `residual(dz)` = F(dz) − load [N] vanishes (to `tolerance` ×
/// load, normally [`LOAD_TOLERANCE`]), given the touching lowering `touch` (where the residual is
/// −load), a first approach estimate ([`Guess`]) and at most `iterations` Illinois
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
/// With the force's slope dF/du from a previous balance of the same wheel ([`Guess::slope`]) the
/// first trial's correction is Newton's step with it, aimed at the root itself, which under a
/// load changed by ~1e−6 (the creep iteration's second pass) lands within the tolerance, where
/// the Hertzian law's step overshoots on purpose and needs a regula falsi step more. With the
/// residual at the first approach already known ([`Guess::residual`]) that pass costs one
/// evaluation.
pub fn balance<E>(
    touch: f64,
    guess: Guess,
    load: f64,
    tolerance: f64,
    iterations: usize,
    law: ForceLaw,
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
    let mut known = guess.residual.filter(|f| f.is_finite());
    let mut evaluate = |dz: f64, recent: &mut [(f64, f64); 2]| -> Result<f64, E> {
        let f = match known.take() {
            Some(f) => f,
            None => residual(dz)?,
        };
        *recent = [recent[1], (u_of(dz), f)];
        Ok(f)
    };
    let mut newton_slope = guess.slope.filter(|s| s.is_finite() && *s > 0.0);
    let mut newton_steps = 0;
    let (mut lo, mut f_lo) = (touch, -load);
    let (mut hi, mut f_hi) = (f64::NAN, f64::NAN);
    let mut approach = guess.approach.max(f64::MIN_POSITIVE);
    for _ in 0..BRACKET_TRIALS {
        let dz = touch + approach;
        let f = evaluate(dz, &mut recent)?;
        if f.abs() <= tolerance * load {
            return Ok(Balanced::evaluated_at(dz, f, &recent));
        }
        if newton_steps > 0 {
            // After a Newton step: the secant through the last two points.
            newton_slope = Some(secant(&recent)).filter(|s| s.is_finite() && *s > 0.0);
        }
        // Newton's step with a known slope, then secant steps: aimed at the root (no overshoot).
        if let Some(s) = newton_slope.take().filter(|_| newton_steps < NEWTON_STEPS) {
            let u = u_of(dz);
            let next = dz_of(u - f / s) - touch;
            if next.is_finite() && next > 0.5 * approach && next < 2.0 * approach {
                if f > 0.0 {
                    (hi, f_hi) = (dz, f);
                } else {
                    (lo, f_lo) = (dz, f);
                }
                approach = next;
                newton_steps += 1;
                continue;
            }
        }
        let force = f + load;
        if f > 0.0 {
            (hi, f_hi) = (dz, f);
            if dz - lo <= tolerance * approach || f_lo > -load {
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
        return Ok(Balanced::evaluated_at(lo, f_lo, &recent));
    }
    let mut bracket = Illinois::new((lo, f_lo), (hi, f_hi));
    let mut last = hi;
    for _ in 0..iterations {
        let mid = bracket.inside_or_midpoint(dz_of(bracket.secant_in(u_of)));
        let f_mid = evaluate(mid, &mut recent)?;
        last = mid;
        if f_mid.abs() <= tolerance * load {
            return Ok(Balanced::evaluated_at(mid, f_mid, &recent));
        }
        bracket.update(mid, f_mid);
    }
    // The nearer end by the residuals as evaluated (Illinois halves the one it keeps).
    let ((lo, f_lo), (hi, f_hi)) = bracket.evaluated_ends();
    let (best, f_best) = if f_lo.abs() < f_hi.abs() {
        (lo, f_lo)
    } else {
        (hi, f_hi)
    };
    Ok(Balanced {
        lowering: best,
        evaluated: best == last,
        slope: secant(&recent),
        residual: f_best,
    })
}

/// Smallest share of the wheel load the normal forces carry when the creep forces' vertical
/// components are subtracted (they cannot carry the wheel: |Fy| ≤ μN).
pub(super) const MIN_NORMAL_SHARE: f64 = 0.05;

/// Passes of the strip models' load balance that update the creep forces' vertical component.
pub(super) const CREEP_PASSES: usize = 20;

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

/// A quantity followed from step to step: its last value, its change over the last step and the
/// change of that change, for the quadratic extrapolation through the last three steps (a
/// moving wheelset's approach, creep component and force slope change smoothly from step to
/// step: the quadratic extrapolation misses a 5 Hz hunting motion at 1 ms steps by
/// (ωh)³ ≈ 3e−5 of its swing, where the last value alone misses by ωh ≈ 3e−2 and the linear
/// extrapolation by (ωh)² ≈ 1e−3).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Trend {
    /// Value after the last step.
    pub value: f64,
    /// Its change over that step (0 until known).
    pub step: f64,
    /// The change of that change (0 until known).
    pub bend: f64,
}

impl Trend {
    /// A value with no history.
    pub fn new(value: f64) -> Self {
        Self {
            value,
            ..Self::default()
        }
    }

    /// The extrapolation to the next step.
    pub fn predicted(&self) -> f64 {
        self.value + self.step + self.bend
    }

    /// The trend after a step that found `value`, following `previous` with `history` steps of
    /// history (0: none, 1: its change is known, 2: also its bend).
    fn after(previous: &Trend, value: f64, history: u8) -> Self {
        let step = if history >= 1 {
            value - previous.value
        } else {
            0.0
        };
        let bend = if history >= 2 {
            step - previous.step
        } else {
            0.0
        };
        Self { value, step, bend }
    }

    /// Whether all three numbers are finite.
    pub fn is_finite(&self) -> bool {
        self.value.is_finite() && self.step.is_finite() && self.bend.is_finite()
    }
}

/// Where the prescribed-load iteration of a wheel starts: the previous steps' solutions,
/// extrapolated ([`Trend`]; −11 % of the instructions of a hunting Hertz step against the linear
/// extrapolation). With it a step whose inputs changed little needs one tangential solve and a
/// few cheap normal-force evaluations instead of a cold search. Part of the FMU state (outputs
/// depend on it at the level of the iteration tolerances).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WarmStart {
    /// Lowering beyond first touch at which the multi-Hertzian normal forces carried the load
    /// [m] (> 0; for the strip models their normal-only Hertz estimate).
    pub approach: Trend,
    /// Vertical component of the creep forces on the wheel, upwards positive [N].
    pub creep: Trend,
    /// Slope dF/du of the multi-Hertzian load balance at its root (u = δ^{3/2},
    /// [`Balanced::slope`]) [N/m^{3/2}]; value 0 where unknown. The next step's first correction
    /// is Newton's step with its extrapolation, which on a moving wheelset lands within ~1e−5 of
    /// the prediction's error.
    pub slope: Trend,
    /// Steps behind this one whose solutions are known, at most 2 (0: a cold start, 1: the
    /// changes are known, 2: also the bends).
    pub history: u8,
    /// Strip models: the approach at which their patches carried the load less the creep
    /// forces' vertical component, over `approach` [-] (the first trial of the next step's
    /// iteration is `approach` times this; 1 for the multi-Hertzian solution).
    pub strip_ratio: f64,
}

impl WarmStart {
    /// The first guess for the next step: the extrapolated approach (kept within [½, 2] × the
    /// last one, so that a jump in the inputs cannot send it far off), creep component and slope
    /// (`None` where unknown or not positive).
    pub fn predicted(&self) -> (f64, f64, Option<f64>) {
        let last = self.approach.value;
        let approach = self.approach.predicted().clamp(0.5 * last, 2.0 * last);
        let slope = Some(self.slope.predicted()).filter(|s| *s > 0.0 && self.slope.value > 0.0);
        (approach, self.creep.predicted(), slope)
    }

    /// The warm start after a step that found `approach`, `creep`, the strip ratio
    /// [`WarmStart::strip_ratio`] and the slope (NaN where the step measured none — it balanced
    /// at its first trial: the previous slope is kept, without its changes), following
    /// `previous`.
    pub(super) fn after(
        previous: Option<WarmStart>,
        approach: f64,
        creep: f64,
        strip_ratio: f64,
        slope: f64,
    ) -> Self {
        let measured = slope.is_finite() && slope > 0.0;
        let Some(p) = previous else {
            return Self {
                approach: Trend::new(approach),
                creep: Trend::new(creep),
                slope: Trend::new(if measured { slope } else { 0.0 }),
                history: 0,
                strip_ratio,
            };
        };
        let history = (p.history + 1).min(2);
        let slope = if !measured {
            Trend::new(p.slope.value)
        } else if p.slope.value > 0.0 {
            // Its change is known; its bend only if the last one had a change (a slope first
            // measured, or kept over a step that measured none, has none).
            let known = if p.slope.step == 0.0 { 1 } else { 2 };
            Trend::after(&p.slope, slope, known)
        } else {
            Trend::new(slope)
        };
        Self {
            approach: Trend::after(&p.approach, approach, history),
            creep: Trend::after(&p.creep, creep, history),
            slope,
            history,
            strip_ratio,
        }
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

/// What a creep pass found ([`creep_passes`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct CreepPass {
    /// The creep forces' vertical component on the wheel, upwards positive [N].
    pub creep: f64,
    /// Whether the pass's load balance met [`LOAD_TOLERANCE`].
    pub tight: bool,
    /// Whether its tangential solution was the previous pass's, scaled
    /// ([`crate::wheelset::reuse`]): an approximation of the creep map, kept out of the fixed
    /// point's history.
    pub reused: bool,
}

/// The prescribed wheel load `q` [N] is carried by the normal forces and the creep forces'
/// vertical component together. `pass(k, target)` balances the normal forces against `target`
/// = q less the current estimate of that component, solves the tangential problem there (or
/// reuses the last solution, scaled) and returns what it found ([`CreepPass`]; `None`: no
/// tangential problem, stop). The estimate starts from `start` (zero, or the previous step's)
/// and is updated by [`CreepFixedPoint`] until it changes by at most [`CREEP_TOLERANCE`] of q in
/// a pass balanced to [`LOAD_TOLERANCE`], or for [`CREEP_PASSES`] passes. (A first pass may
/// balance only to [`CREEP_TOLERANCE`]: its target carries the estimate's error, and the next
/// pass starts from its root.) A reused pass that has not converged hands its component on as
/// the next estimate without entering [`CreepFixedPoint`]'s secant and bracket, which hold the
/// solved passes only (a scaled solution is a slightly different map: mixed, the two can leave
/// a bracket around their step, ~1e−6 of q in flange contact). Returns the last component found
/// (`None` if no pass solved a tangential problem).
pub(super) fn creep_passes(
    q: f64,
    start: f64,
    mut pass: impl FnMut(usize, f64) -> Result<Option<CreepPass>, WheelsetError>,
) -> Result<Option<f64>, WheelsetError> {
    let mut creep = if start.is_finite() { start } else { 0.0 };
    let mut fixed_point = CreepFixedPoint::default();
    let mut found = None;
    for k in 0..CREEP_PASSES {
        let target = (q - creep).max(MIN_NORMAL_SHARE * q);
        let Some(found_here) = pass(k, target)? else {
            break;
        };
        let new_creep = found_here.creep;
        found = Some(new_creep);
        let converged = (new_creep - creep).abs() <= CREEP_TOLERANCE * q;
        if k + 1 == CREEP_PASSES || (converged && found_here.tight) {
            break;
        }
        creep = if found_here.reused {
            new_creep
        } else {
            fixed_point.next(creep, new_creep)
        };
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
/// wheel height, and across such jumps (or through its small ripples) a secant can point the
/// wrong way. So the iterates on either side of the root are kept (h > 0 below it, h < 0 above
/// it): a step that would leave the bracket bisects it, closing on the root or on the jump, and
/// while only one side is known a step back behind it is replaced by the plain step from that
/// side's end (towards the root, as the contraction guarantees). Where the map is not
/// contracting — a two-lobe patch whose normal direction turns with the load, on which g has
/// slopes near or above 1 over a few newtons — plain steps crawl: while a step in the plain
/// direction does not halve h, the next one is at least twice as long, until the other side
/// is found.
#[derive(Debug, Default)]
pub(super) struct CreepFixedPoint {
    previous: Option<(f64, f64)>,
    /// Largest iterate with h > 0 and smallest with h < 0 so far, each with its h.
    below: Option<(f64, f64)>,
    above: Option<(f64, f64)>,
}

impl CreepFixedPoint {
    /// The next iterate after evaluating g(`c`) = `g`.
    pub(super) fn next(&mut self, c: f64, g: f64) -> f64 {
        let h = g - c;
        if h > 0.0 && self.below.is_none_or(|(b, _)| c > b) {
            self.below = Some((c, h));
        } else if h < 0.0 && self.above.is_none_or(|(a, _)| c < a) {
            self.above = Some((c, h));
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
        // A step in the plain direction (that of h) that did not halve h: crawling.
        let crawl = self.previous.and_then(|(c0, h0)| {
            let step = c - c0;
            (h * h0 > 0.0 && step * h > 0.0 && h.abs() > 0.5 * h0.abs()).then_some(step)
        });
        self.previous = Some((c, h));
        let one_sided = |end: f64, h_end: f64, behind: bool| {
            let step = if behind { end + h_end } else { next };
            match crawl {
                Some(last) if h_end > 0.0 => step.max(c + 2.0 * last),
                Some(last) => step.min(c + 2.0 * last),
                None => step,
            }
        };
        match (self.below, self.above) {
            (Some((lo, _)), Some((hi, _))) if lo < hi && !(next > lo && next < hi) => {
                0.5 * (lo + hi)
            }
            (Some((lo, h_lo)), None) => one_sided(lo, h_lo, next <= lo),
            (None, Some((hi, h_hi))) => one_sided(hi, h_hi, next >= hi),
            _ => next,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn start(approach: f64) -> Guess {
        Guess {
            approach,
            ..Guess::default()
        }
    }

    #[test]
    fn hertzian_force_is_balanced() {
        // F = k (dz − touch)^{3/2}: the root is known in closed form.
        let (k, touch, load): (f64, f64, f64) = (1e10, -2e-4, 8e4);
        let exact = touch + (load / k).powf(2.0 / 3.0);
        let mut evaluations = [0usize; 2];
        let laws = [ForceLaw::General, ForceLaw::Hertzian];
        for (law, calls) in laws.into_iter().zip(&mut evaluations) {
            let b = balance(touch, start(1e-5), load, LOAD_TOLERANCE, 60, law, |dz| {
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
    fn creep_fixed_point_never_steps_back_behind_its_known_side() {
        // A contracting map with a ripple (a discretised tangential solution's element set
        // changing with the load): g(c) = c* + 0.3 (c − c*) + ripple, the ripple a staircase of
        // ±0.02 N over 0.01 N of c, so h = g − c > 0 below c* − 0.03 and the secant through two
        // rippled points can point anywhere. Every iterate after one with h > 0 lies above the
        // largest such iterate until an iterate with h < 0 is seen; the iteration reaches 1e−7
        // of a 40 kN load (4 mN) in the passes the wheel has.
        let root = 6303.74;
        let ripple = |c: f64| {
            if (c * 100.0).floor() as i64 % 2 == 0 {
                0.02
            } else {
                -0.02
            }
        };
        let g = |c: f64| root + 0.3 * (c - root) + ripple(c);
        let mut fp = CreepFixedPoint::default();
        let mut c = 6303.2;
        let mut largest_below = f64::NEG_INFINITY;
        let mut converged = false;
        for _ in 0..CREEP_PASSES {
            let gc = g(c);
            if (gc - c).abs() <= CREEP_TOLERANCE * 40_000.0 {
                converged = true;
                break;
            }
            if gc > c {
                largest_below = largest_below.max(c);
            }
            let next = fp.next(c, gc);
            if fp.above.is_none() {
                assert!(next > largest_below, "{next} behind {largest_below}");
            }
            c = next;
        }
        // The ripple has no exact fixed point everywhere: the bracket closes on a jump, where
        // the iterates end within the ripple of the root.
        assert!(converged || (c - root).abs() < 0.1, "{c}");
    }

    #[test]
    fn a_jump_across_the_load_gives_the_nearer_bracket_end() {
        // F jumps at dz = 1e−4 (two regions merging): from 0.9 to 1.2 load the end below the
        // jump is nearer (residual −0.1 load), from 0.5 to 1.2 the end above it (+0.2 load). The
        // bracket closes on the jump while the Illinois halving scales the kept end's residual
        // far below both: the ends must be compared by their residuals as evaluated, and the
        // returned residual is the force's there.
        let load = 1e4;
        for (below, above, nearer) in [(0.9, 1.2, -0.1), (0.5, 1.2, 0.2)] {
            let residual = |dz: f64| {
                let force = if dz < 1e-4 {
                    below * load * dz / 1e-4
                } else {
                    above * load
                };
                force - load
            };
            let b = balance(
                0.0,
                start(1e-5),
                load,
                LOAD_TOLERANCE,
                60,
                ForceLaw::General,
                |dz| Ok::<_, ()>(residual(dz)),
            )
            .unwrap();
            assert!((b.lowering - 1e-4).abs() < 1e-12, "{b:?}");
            assert_eq!(b.residual, residual(b.lowering), "{b:?}");
            assert!((b.residual - nearer * load).abs() < 1e-6 * load, "{b:?}");
        }
    }

    #[test]
    fn residual_errors_are_passed_on() {
        assert_eq!(
            balance(
                0.0,
                start(1e-5),
                1.0,
                LOAD_TOLERANCE,
                10,
                ForceLaw::General,
                |_| { Err::<f64, _>("bad") }
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
