//! Rolling contact fatigue: Ekberg's surface fatigue index and the Whole Life Rail Model.
//!
//! Papers: A. Ekberg, E. Kabo, H. Andersson, "An engineering model for prediction of rolling
//! contact fatigue of railway wheels", *Fatigue Fract. Engng Mater. Struct.* 25 (2002) 899–909
//! (surface fatigue index from shakedown theory); its local form per element as documented in
//! CONTACT's user guide (E.A.H. Vollebregt, Vtech CMCC); M.C. Burstow, "Whole Life Rail Model
//! application and development for RSSB — Continued development of an RCF damage parameter",
//! AEATR-ES-2004-880 (2004) (damage per wheel pass from Tγ). Equations: docs/theory.md §10.3.
//!
//! # Equations
//!
//! ```text
//!   FI_surf = μ_eff − k/p0,   μ_eff = √(Fx² + Fy²)/Fn,  p0 the patch's peak pressure
//!   FI_local = max over the elements in contact of (|q| − k)/p
//!   D(Tγ) = 0                          Tγ < 20 J/m
//!         = (Tγ − 20)/45 × 1e−5         20 ≤ Tγ ≤ 65   (crack initiation grows)
//!         = (175 − Tγ)/110 × 1e−5       65 < Tγ ≤ 175  (wear removes the cracks)
//!         = 0                          Tγ > 175
//! ```
//!
//! Surface-initiated fatigue (ratchetting) is predicted where FI_surf > 0; D is the damage
//! per wheel pass (failure at 1).
//!
//! # Limits
//!
//! FI_surf uses the patch's peak pressure as p0 (exact on a Hertz patch: 3N/(2πab)); on a
//! non-elliptic patch it is the model's peak. The WLRM function was calibrated for rail on
//! British main lines with Tγ from elliptic contact; 15 J/m is quoted as the threshold in later
//! publications (20 J/m here, as in the 2004 report's function).

/// Ekberg's surface fatigue index of a patch with force (`fx`, `fy`) on normal force `fn_` [N]
/// and peak pressure `p0` [Pa], shear yield strength `k` [Pa]; 0 without load.
pub fn surface_index(fx: f64, fy: f64, fn_: f64, p0: f64, k: f64) -> f64 {
    if !(fn_ > 0.0 && p0 > 0.0) {
        return 0.0;
    }
    let index = fx.hypot(fy) / fn_ - k / p0;
    if index.is_finite() {
        index
    } else {
        0.0
    }
}

/// The local fatigue term (|q| − k)/p of an element with traction `traction` and pressure
/// `pressure` > 0 [Pa].
pub fn local_term(traction: f64, pressure: f64, k: f64) -> f64 {
    (traction - k) / pressure
}

/// WLRM threshold, peak and end of the damage function [J/m] and the peak damage [-].
pub const WLRM_THRESHOLD: f64 = 20.0;
pub const WLRM_PEAK: f64 = 65.0;
pub const WLRM_END: f64 = 175.0;
pub const WLRM_PEAK_DAMAGE: f64 = 1e-5;

/// The Whole Life Rail Model's damage per wheel pass of a contact dissipating `t_gamma` [J/m].
pub fn wlrm_damage(t_gamma: f64) -> f64 {
    let inside = t_gamma > WLRM_THRESHOLD && t_gamma < WLRM_END;
    if !inside {
        0.0
    } else if t_gamma <= WLRM_PEAK {
        WLRM_PEAK_DAMAGE * (t_gamma - WLRM_THRESHOLD) / (WLRM_PEAK - WLRM_THRESHOLD)
    } else {
        WLRM_PEAK_DAMAGE * (WLRM_END - t_gamma) / (WLRM_END - WLRM_PEAK)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surface_index_of_a_hertz_patch() {
        // μ_eff = 0.25, k/p0 = 0.3: FI = −0.05.
        let fi = surface_index(3e3, 4e3, 20e3, 1e9, 300e6);
        assert!((fi + 0.05).abs() < 1e-15);
        assert_eq!(surface_index(1.0, 1.0, 0.0, 1e9, 3e8), 0.0);
    }

    #[test]
    fn wlrm_shape() {
        // The published lines: 2.22e−7 Tγ − 4.44e−6 rising, −9.09e−8 Tγ + 1.59e−5 falling.
        for t in [25.0, 40.0, 60.0] {
            assert!((wlrm_damage(t) - (2.222_222e-7 * t - 4.444_444e-6)).abs() < 1e-11);
        }
        for t in [70.0, 120.0, 170.0] {
            assert!((wlrm_damage(t) - (-9.090_909e-8 * t + 1.590_909e-5)).abs() < 1e-11);
        }
        assert_eq!(wlrm_damage(10.0), 0.0);
        assert_eq!(wlrm_damage(200.0), 0.0);
        assert_eq!(wlrm_damage(f64::NAN), 0.0);
        assert!((wlrm_damage(65.0) - 1e-5).abs() < 1e-20);
    }
}
