//! Surface damage from the contact's own fields: wear and rolling contact fatigue per patch.
//!
//! * [`wear`] — the wear functions applied element by element: the USFD Tγ/A function and
//!   Archard's law with the KTH wear map;
//! * [`fatigue`] — Ekberg's surface fatigue index (patch and local forms) and the Whole Life Rail
//!   Model's damage per wheel pass.
//!
//! The tangential solvers hand over their traction and slip fields element by element
//! ([`FrictionElement`]); [`PatchDamage`] sums a patch's wear and keeps its largest local fatigue
//! index. Equations, coefficients and their sources: docs/theory.md §10.

pub mod fatigue;
pub mod wear;

use crate::error::{require_positive, InputError};
pub use crate::tangential::fastsim::FrictionElement;

/// Wear model (`wearModel`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum WearModel {
    /// 0: no wear computed (and no cost).
    #[default]
    Off,
    /// 1: the USFD Tγ/A wear function (R8T wheel on UIC60 900A rail).
    Usfd,
    /// 2: Archard's law with the KTH wear map.
    ArchardKth,
}

impl WearModel {
    /// From the FMU code 0–2.
    pub fn from_code(code: i32) -> Option<Self> {
        match code {
            0 => Some(Self::Off),
            1 => Some(Self::Usfd),
            2 => Some(Self::ArchardKth),
            _ => None,
        }
    }
}

/// Parameters of the damage outputs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DamageParams {
    pub wear_model: WearModel,
    /// Hardness of the wheel and of the rail (Archard's law) [Pa].
    pub wheel_hardness: f64,
    pub rail_hardness: f64,
    /// Shear yield strength k of the (work-hardened) surface (fatigue indices) [Pa].
    pub shear_yield_strength: f64,
}

/// Brinell hardness 265 HB (R8T wheel, R260/900A rail) in pascal: 265 × 9.81 MPa.
pub const DEFAULT_HARDNESS: f64 = 2.6e9;
/// Shear yield strength of work-hardened wheel and rail steel (Ekberg, Kabo & Andersson 2002)
/// [Pa].
pub const DEFAULT_SHEAR_YIELD_STRENGTH: f64 = 300e6;

impl Default for DamageParams {
    fn default() -> Self {
        Self {
            wear_model: WearModel::Off,
            wheel_hardness: DEFAULT_HARDNESS,
            rail_hardness: DEFAULT_HARDNESS,
            shear_yield_strength: DEFAULT_SHEAR_YIELD_STRENGTH,
        }
    }
}

impl DamageParams {
    /// Checks the ranges; the error names the parameter.
    pub fn validate(&self) -> Result<(), InputError> {
        require_positive("wheelHardness", self.wheel_hardness)?;
        require_positive("railHardness", self.rail_hardness)?;
        require_positive("shearYieldStrength", self.shear_yield_strength)?;
        Ok(())
    }

    /// Whether the element-wise damage (wear rates, local fatigue index) is evaluated.
    pub fn element_wise(&self) -> bool {
        self.wear_model != WearModel::Off
    }
}

/// What one patch's fields give: wear per metre rolled and the largest local fatigue index.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PatchDamage {
    /// Mass removed from the wheel and from the rail per metre rolled [kg/m].
    pub wheel_wear_rate: f64,
    pub rail_wear_rate: f64,
    /// Largest (|q| − k)/p over the elements in contact [-] (0 without any).
    pub fatigue_index_local: f64,
}

/// Running sums of [`PatchDamage`] over a patch's elements.
#[derive(Debug, Clone, Copy)]
pub struct DamageSum {
    params: DamageParams,
    /// Rolling speed [m/s] (the sliding velocity of Archard's map is its slip times this).
    speed: f64,
    wheel: f64,
    rail: f64,
    local: f64,
}

impl DamageSum {
    pub fn new(params: DamageParams, speed: f64) -> Self {
        Self {
            params,
            speed,
            wheel: 0.0,
            rail: 0.0,
            local: f64::NEG_INFINITY,
        }
    }

    /// Adds one element of the patch.
    pub fn add(&mut self, e: &FrictionElement) {
        if !(e.pressure > 0.0 && e.area > 0.0) {
            return;
        }
        let p = &self.params;
        let local = fatigue::local_term(e.traction, e.pressure, p.shear_yield_strength);
        if local > self.local {
            self.local = local;
        }
        let (wheel, rail) = match p.wear_model {
            WearModel::Off => (0.0, 0.0),
            WearModel::Usfd => {
                let m = wear::usfd_rate(e.traction * e.slip) * e.area;
                (m, m)
            }
            WearModel::ArchardKth => {
                let v = e.slip * self.speed;
                let per_hardness = e.pressure * e.slip * e.area * wear::STEEL_DENSITY;
                let k = |h: f64| wear::kth_coefficient(e.pressure, v, h) / h;
                (
                    k(p.wheel_hardness) * per_hardness,
                    k(p.rail_hardness) * per_hardness,
                )
            }
        };
        if wheel.is_finite() && rail.is_finite() {
            self.wheel += wheel;
            self.rail += rail;
        }
    }

    /// The patch's damage.
    pub fn finish(&self) -> PatchDamage {
        PatchDamage {
            wheel_wear_rate: self.wheel,
            rail_wear_rate: self.rail,
            fatigue_index_local: if self.local.is_finite() {
                self.local
            } else {
                0.0
            },
        }
    }
}

impl PatchDamage {
    /// The damage of a patch whose forces were scaled by `force` (the wear rates go as the
    /// frictional power; the local fatigue index is kept, as the adhesion fraction is).
    pub fn scaled(&self, force: f64) -> Self {
        Self {
            wheel_wear_rate: self.wheel_wear_rate * force,
            rail_wear_rate: self.rail_wear_rate * force,
            ..*self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn element(area: f64, pressure: f64, traction: f64, slip: f64) -> FrictionElement {
        FrictionElement {
            area,
            pressure,
            traction,
            slip,
        }
    }

    #[test]
    fn codes_and_ranges() {
        assert_eq!(WearModel::from_code(0), Some(WearModel::Off));
        assert_eq!(WearModel::from_code(2), Some(WearModel::ArchardKth));
        assert_eq!(WearModel::from_code(3), None);
        let bad = DamageParams {
            rail_hardness: -1.0,
            ..DamageParams::default()
        };
        assert_eq!(bad.validate().unwrap_err().name, "railHardness");
        assert!(DamageParams::default().validate().is_ok());
    }

    #[test]
    fn sums_follow_the_wear_function_element_by_element() {
        // Elements in the three USFD regimes: the sum is the function applied to each, not to
        // the mean (the mean Tγ/A would fall in the severe plateau).
        let params = DamageParams {
            wear_model: WearModel::Usfd,
            ..DamageParams::default()
        };
        let elements = [
            element(1e-6, 1e9, 3e8, 0.0),     // adhesion: no slip, no wear
            element(1e-6, 1e9, 3e8, 1e-2),    // 3 N/mm²: mild
            element(2e-6, 1e9, 3e8, 1e-1),    // 30 N/mm²: severe
            element(1e-6, 1.2e9, 3.6e8, 0.5), // 180 N/mm²: catastrophic
        ];
        let mut sum = DamageSum::new(params, 10.0);
        let mut expected = 0.0;
        for e in &elements {
            sum.add(e);
            // µg/(m mm²) × mm² → kg/m.
            let t = e.traction * e.slip * 1e-6;
            let rate = if t < 10.4 {
                5.3 * t
            } else if t <= 77.2 {
                55.0
            } else {
                (61.9 * t - 4778.7).max(55.0)
            };
            expected += rate * (e.area * 1e6) * 1e-9;
        }
        let d = sum.finish();
        assert!(
            (d.wheel_wear_rate / expected - 1.0).abs() < 1e-12,
            "{d:?} {expected}"
        );
        assert_eq!(d.wheel_wear_rate, d.rail_wear_rate);
        // Local fatigue index: the largest (|q| − k)/p, here (3.6e8 − 3e8)/1.2e9 = 0.05.
        assert!((d.fatigue_index_local - 0.05).abs() < 1e-12);
    }

    #[test]
    fn archard_follows_the_map_and_the_hardness() {
        let params = DamageParams {
            wear_model: WearModel::ArchardKth,
            wheel_hardness: 2.0e9,
            rail_hardness: 4.0e9,
            ..DamageParams::default()
        };
        // Sliding at 1e-2 × 30 m/s = 0.3 m/s and p = 1 GPa < 0.8 H: the map's k3.
        let e = element(1e-6, 1e9, 3e8, 1e-2);
        let mut sum = DamageSum::new(params, 30.0);
        sum.add(&e);
        let d = sum.finish();
        let volume = |h: f64| wear::KTH_K3 * 1e9 * 1e-2 * 1e-6 / h;
        assert!((d.wheel_wear_rate / (volume(2.0e9) * wear::STEEL_DENSITY) - 1.0).abs() < 1e-12);
        assert!((d.rail_wear_rate / (volume(4.0e9) * wear::STEEL_DENSITY) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn empty_and_absurd_elements_give_finite_zero() {
        let mut sum = DamageSum::new(
            DamageParams {
                wear_model: WearModel::Usfd,
                ..DamageParams::default()
            },
            1.0,
        );
        assert_eq!(sum.finish(), PatchDamage::default());
        sum.add(&element(0.0, 1e9, 1e8, 0.1));
        sum.add(&element(1e-6, 0.0, 0.0, 0.1));
        sum.add(&element(1e-6, 1e9, f64::INFINITY, f64::INFINITY));
        let d = sum.finish();
        assert!(d.wheel_wear_rate.is_finite() && d.rail_wear_rate.is_finite());
    }
}
