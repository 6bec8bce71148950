//! The wheel-height iteration for a prescribed wheel load, shared by the multi-Hertzian and the
//! strip solutions of a wheel (physics.md §5.2).
//!
//! The vertical force F(dz) of the rail on a wheel lowered by dz is zero at the touching height
//! and grows monotonically, but its slope jumps where patches or strips enter and it can jump
//! where two interpenetration regions merge. So: bracket the load by doubling the approach from
//! a first estimate, then Illinois (modified regula falsi) inside the bracket — bracketing,
//! superlinear, and when the force jumps across the load the bracket closes on the jump and the
//! end nearer to the load is taken.

/// Relative tolerance on the vertical force balance.
pub const LOAD_TOLERANCE: f64 = 1e-9;

/// Largest approach tried while bracketing [m] (5 cm is far beyond any elastic contact).
const MAX_APPROACH: f64 = 0.05;

/// Relative overshoot of the Hertzian predictor while bracketing: 2 % in the approach, so a
/// force law a little stiffer or softer than δ^{3/2} (strip models, a second patch) is still
/// bracketed in one trial.
const PREDICTOR_MARGIN: f64 = 0.02;

/// Bracketing trials (doubling from 1e−9 m reaches MAX_APPROACH in 26).
const BRACKET_TRIALS: usize = 64;

/// Result of [`balance`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Balanced {
    /// The lowering that carries the load [m].
    pub lowering: f64,
    /// Whether `lowering` was the last point evaluated (so the caller's state belongs to it).
    pub evaluated: bool,
}

/// Finds the lowering dz at which `residual(dz)` = F(dz) − load [N] vanishes (to
/// [`LOAD_TOLERANCE`] × load), given the touching lowering `touch` (where the residual is
/// −load), a first approach estimate `first_approach` > 0 [m] and at most `iterations` Illinois
/// steps. Errors of `residual` are passed on.
///
/// Bracketing starts at the first estimate, which is accepted at once when it balances the load
/// (a warm start from the previous step). Otherwise the next trial comes from the Hertzian law
/// F ∝ δ^{3/2} through the last point (aimed [`PREDICTOR_MARGIN`] beyond the root, so that it
/// brackets it; at most doubling or halving the approach per trial) until the root is bracketed;
/// the Illinois steps then work in that tight bracket.
pub fn balance<E>(
    touch: f64,
    first_approach: f64,
    load: f64,
    iterations: usize,
    residual: impl FnMut(f64) -> Result<f64, E>,
) -> Result<Balanced, E> {
    balance_in(touch, first_approach, load, iterations, false, residual)
}

/// [`balance`] for a force that grows like a Hertz patch's, F ∝ δ^{3/2} (the multi-Hertzian
/// wheel): the regula falsi runs in u = δ^{3/2} (δ = dz − touch), where such a force is linear,
/// so one step solves a single patch and a few steps several (the strip models' forces are
/// further from that law: with them it needs more steps than in dz, measured).
pub fn balance_hertzian<E>(
    touch: f64,
    first_approach: f64,
    load: f64,
    iterations: usize,
    residual: impl FnMut(f64) -> Result<f64, E>,
) -> Result<Balanced, E> {
    balance_in(touch, first_approach, load, iterations, true, residual)
}

/// [`balance`] with the regula falsi in dz, or in u = δ^{3/2} if `hertzian`.
fn balance_in<E>(
    touch: f64,
    first_approach: f64,
    load: f64,
    iterations: usize,
    hertzian: bool,
    mut residual: impl FnMut(f64) -> Result<f64, E>,
) -> Result<Balanced, E> {
    let (mut lo, mut f_lo) = (touch, -load);
    let (mut hi, mut f_hi) = (f64::NAN, f64::NAN);
    let mut approach = first_approach.max(f64::MIN_POSITIVE);
    for _ in 0..BRACKET_TRIALS {
        let dz = touch + approach;
        let f = residual(dz)?;
        if f.abs() <= LOAD_TOLERANCE * load {
            return Ok(Balanced {
                lowering: dz,
                evaluated: true,
            });
        }
        let force = f + load;
        if f > 0.0 {
            (hi, f_hi) = (dz, f);
            if dz - lo <= LOAD_TOLERANCE * approach || f_lo > -load {
                // Bracketed on both sides by evaluated points.
                break;
            }
            // Too deep: predict the root from below.
            let ratio = (load / force).powf(2.0 / 3.0) * (1.0 - PREDICTOR_MARGIN);
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
                (load / force).powf(2.0 / 3.0) * (1.0 + PREDICTOR_MARGIN)
            } else {
                2.0
            };
            approach *= ratio.clamp(1.0 + PREDICTOR_MARGIN, 2.0);
        }
    }
    if f_hi.is_nan() || f_hi <= 0.0 {
        // No point above the load (the force stays below it up to MAX_APPROACH): the deepest
        // point tried is the answer the caller gets, as before.
        return Ok(Balanced {
            lowering: lo,
            evaluated: true,
        });
    }
    let mut kept = 0i8;
    let mut last = hi;
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
    for _ in 0..iterations {
        let (u_lo, u_hi) = (u_of(lo), u_of(hi));
        let mut mid = dz_of((u_lo * f_hi - u_hi * f_lo) / (f_hi - f_lo));
        if !mid.is_finite() || mid <= lo.min(hi) || mid >= lo.max(hi) {
            mid = 0.5 * (lo + hi);
        }
        let f_mid = residual(mid)?;
        last = mid;
        if f_mid.abs() <= LOAD_TOLERANCE * load {
            return Ok(Balanced {
                lowering: mid,
                evaluated: true,
            });
        }
        if (f_mid > 0.0) == (f_hi > 0.0) {
            hi = mid;
            f_hi = f_mid;
            if kept == -1 {
                f_lo *= 0.5;
            }
            kept = -1;
        } else {
            lo = mid;
            f_lo = f_mid;
            if kept == 1 {
                f_hi *= 0.5;
            }
            kept = 1;
        }
    }
    let best = if f_lo.abs() < f_hi.abs() { lo } else { hi };
    Ok(Balanced {
        lowering: best,
        evaluated: best == last,
    })
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
        for (hertzian, calls) in [false, true].into_iter().zip(&mut evaluations) {
            let b = balance_in(touch, 1e-5, load, 60, hertzian, |dz| {
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
        let b = balance(0.0, 1e-5, load, 60, |dz| {
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
            balance(0.0, 1e-5, 1.0, 10, |_| Err::<f64, _>("bad")),
            Err("bad")
        );
    }
}
