//! Surface damage from the contact's own fields: wear and rolling contact fatigue per patch.
//!
//! * [`wear`] — the wear functions applied element by element: the USFD Tγ/A function and
//!   Archard's law with the KTH wear map;
//! * [`fatigue`] — Ekberg's surface fatigue index (patch and local forms) and the Whole Life Rail
//!   Model's damage per wheel pass;
//! * [`profile`] — wear distributions across the wheel's and the rail's profiles;
//! * [`record`] — wear accumulated over a run, its depths, bytes and CSV file;
//! * [`update`] — the wear-prediction loop's profile update from such records.
//!
//! The tangential solvers hand over their traction and slip fields element by element
//! ([`FrictionElement`]); [`PatchDamage`] sums a patch's wear and keeps its largest local fatigue
//! index. Equations, coefficients and their sources: docs/theory.md §10.

pub mod fatigue;
pub mod profile;
pub mod record;
pub mod update;
pub mod wear;

use crate::error::{require_positive, InputError};
pub use crate::tangential::fastsim::{FrictionElement, FrictionStrip};

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
    /// Archard: 1/H of the wheel and of the rail [1/Pa] and the map's seizure pressures 0.8 H.
    inverse_hardness: [f64; 2],
    seizure: [f64; 2],
    /// Wear of the elements outside the USFD mild regime (all of them with Archard) [kg/m].
    wheel: f64,
    rail: f64,
    /// Σ |q| |s| ΔA of the elements beyond the USFD mild regime [N] (the others' wear is the
    /// mild coefficient times the rest of `t_gamma`).
    beyond_mild: f64,
    /// The largest local fatigue term (|q| − k)/p so far.
    local: f64,
    /// Σ |q| |s| ΔA: the field's Tγ [N].
    t_gamma: f64,
}

impl DamageSum {
    pub fn new(params: DamageParams, speed: f64) -> Self {
        let h = [params.wheel_hardness, params.rail_hardness];
        Self {
            params,
            speed,
            inverse_hardness: h.map(|h| 1.0 / h),
            seizure: h.map(|h| 0.8 * h),
            wheel: 0.0,
            rail: 0.0,
            beyond_mild: 0.0,
            local: f64::NEG_INFINITY,
            t_gamma: 0.0,
        }
    }

    /// Adds one element of the patch (the per-element work of the damage outputs: a few
    /// operations for an adhering element, a few more for a slipping one); returns its wear of
    /// the wheel and of the rail [kg/m] (unscaled, as the sums).
    #[inline]
    pub fn add(&mut self, e: &FrictionElement) -> (f64, f64) {
        self.fatigue(e);
        self.wear(e)
    }

    /// Adds one element's Tγ and wear but not its fatigue term: a patch whose field slips
    /// nowhere while it dissipates (the energy released where the material leaves it on a grid
    /// that adheres throughout, docs/theory.md §4.5) wears as one element of its mean
    /// pressure and Tγ/A. Returns its wear of the wheel and of the rail [kg/m].
    pub fn add_release(&mut self, e: &FrictionElement) -> (f64, f64) {
        self.wear(e)
    }

    /// The local fatigue index of one element.
    #[inline]
    fn fatigue(&mut self, e: &FrictionElement) {
        let k = self.params.shear_yield_strength;
        // (|q| − k)/p > local ⇔ |q| > k + local p =: t. Only an element whose bound exceeds t
        // and whose |q|² exceeds t² (t ≥ 0) is evaluated; p = 0 gives NaN and is skipped.
        let t = k + self.local * e.pressure;
        if e.bound > t && (t < 0.0 || e.traction_sq > t * t) {
            let term = fatigue::local_term(e.traction_sq.sqrt(), e.pressure, k);
            if term > self.local {
                self.local = term;
            }
        }
    }

    /// The Tγ and wear of one element.
    #[inline]
    fn wear(&mut self, e: &FrictionElement) -> (f64, f64) {
        if e.slip == 0.0 {
            return (0.0, 0.0);
        }
        // Local Tγ/A [Pa] and the element's Tγ [N].
        let density = e.traction_sq.sqrt() * e.slip;
        let dissipated = density * e.area;
        self.t_gamma += dissipated;
        match self.params.wear_model {
            WearModel::Off => (0.0, 0.0),
            WearModel::Usfd => {
                if density >= wear::USFD_MILD_LIMIT {
                    let m = wear::usfd_rate(density) * e.area;
                    self.beyond_mild += dissipated;
                    self.wheel += m;
                    self.rail += m;
                    (m, m)
                } else {
                    let m = wear::USFD_MILD_RATE * dissipated;
                    (m, m)
                }
            }
            WearModel::ArchardKth => {
                // Mass per metre rolled per unit k/H: ρ p |s| ΔA; the map's k by the sliding
                // velocity, k1 where the pressure exceeds 0.8 H of that body.
                let mass = e.pressure * e.slip * e.area * wear::STEEL_DENSITY;
                let sliding = wear::kth_sliding_coefficient(e.slip * self.speed);
                let k = |body: usize| {
                    let k = if e.pressure > self.seizure[body] {
                        wear::KTH_K1
                    } else {
                        sliding
                    };
                    k * self.inverse_hardness[body]
                };
                let (wheel, rail) = (k(0) * mass, k(1) * mass);
                self.wheel += wheel;
                self.rail += rail;
                (wheel, rail)
            }
        }
    }

    /// Adds one strip of a FASTSIM field ([`FrictionStrip`]); returns its wear of the wheel and
    /// of the rail [kg/m] (unscaled). The same sums as [`DamageSum::add`] over its elements (to
    /// rounding: a slipping element's |q| is taken as its bound, where the march put it), from
    /// the march's own sums of the strip where they suffice: its elements' fatigue terms only
    /// where the strip's peak pressure could beat the largest term so far ((μp − k)/p grows
    /// with p); its wear at once where every element lies in USFD's mild regime (linear in
    /// Tγ/A), or for Archard below both seizure pressures by velocity class (at once where
    /// every element slides below 0.2 m/s).
    pub fn add_strip(&mut self, s: &FrictionStrip) -> (f64, f64) {
        let n = s.shape.len().min(s.slip.len());
        let k = self.params.shear_yield_strength;
        let peak = s.pressure_scale * s.top_shape;
        if s.bound_scale * s.top_shape > k + self.local * peak {
            for i in 0..n {
                self.fatigue(&s.element(i));
            }
        }
        if s.power.sum <= 0.0 {
            return (0.0, 0.0);
        }
        // Σ |q| |s| ΔA with |q| on the bound where an element slips.
        let dissipated = s.slip_scale * s.power.sum * s.area;
        match self.params.wear_model {
            WearModel::Off => {
                self.t_gamma += dissipated;
                (0.0, 0.0)
            }
            WearModel::Usfd if s.slip_scale * s.power.max < wear::USFD_MILD_LIMIT => {
                self.t_gamma += dissipated;
                let m = wear::USFD_MILD_RATE * dissipated;
                (m, m)
            }
            WearModel::ArchardKth if peak <= self.seizure[0].min(self.seizure[1]) => {
                // Below both seizure pressures the map's k depends on the sliding velocity
                // alone: ρ p |s| ΔA with p = |q| pressure_scale / bound_scale, k2 throughout
                // where every element slides below 0.2 m/s, else per velocity class.
                let per_slip = s.slip_scale * self.speed;
                let weighted = if s.power.max_slip * per_slip < wear::KTH_SLOW {
                    wear::KTH_K2 * s.power.sum
                } else {
                    // k2 on all, corrected where elements slide faster: Σ μp|S| = bound_scale
                    // Σ shape |S|.
                    let [middle, above] = velocity_classes(
                        &s.shape[..n],
                        &s.slip[..n],
                        (wear::KTH_SLOW / per_slip, wear::KTH_FAST / per_slip),
                    );
                    wear::KTH_K2 * s.power.sum
                        + s.bound_scale
                            * ((wear::KTH_K3 - wear::KTH_K2) * middle
                                + (wear::KTH_K4 - wear::KTH_K2) * above)
                };
                self.t_gamma += dissipated;
                let mass = s.slip_scale * weighted * s.area * s.pressure_scale / s.bound_scale
                    * wear::STEEL_DENSITY;
                let (wheel, rail) = (
                    self.inverse_hardness[0] * mass,
                    self.inverse_hardness[1] * mass,
                );
                self.wheel += wheel;
                self.rail += rail;
                (wheel, rail)
            }
            _ => {
                let (mut wheel, mut rail) = (0.0, 0.0);
                for i in 0..n {
                    let (w, r) = self.wear(&s.element(i));
                    wheel += w;
                    rail += r;
                }
                (wheel, rail)
            }
        }
    }

    /// The Tγ of the elements added, Σ |q| |s| ΔA [N].
    pub fn t_gamma(&self) -> f64 {
        self.t_gamma
    }

    /// The patch's damage, its wear rates scaled to the patch's Tγ `t_gamma` [N] (the field's
    /// own Tγ, [`DamageSum::t_gamma`], gives them unscaled: a patch that carries a share or a
    /// scaled copy of the field wears in proportion).
    pub fn finish(&self, t_gamma: f64) -> PatchDamage {
        let scale = if self.t_gamma > 0.0 && t_gamma.is_finite() {
            t_gamma / self.t_gamma
        } else {
            0.0
        };
        // The mild regime's elements all at once (W1: linear in Tγ/A); a sum that overflowed
        // saturates (absurd creepages), as the frictional power does.
        let in_mild = match self.params.wear_model {
            WearModel::Usfd => self.t_gamma - self.beyond_mild,
            _ => 0.0,
        };
        let total = |part: f64| {
            let w = (part + wear::USFD_MILD_RATE * in_mild) * scale;
            if w.is_nan() {
                0.0
            } else {
                w.min(f64::MAX)
            }
        };
        PatchDamage {
            wheel_wear_rate: total(self.wheel),
            rail_wear_rate: total(self.rail),
            fatigue_index_local: if self.local.is_finite() {
                self.local
            } else {
                0.0
            },
        }
    }
}

/// Σ shape_i slip_i over a strip's elements whose slip lies in [slow, fast] and above fast
/// (Archard's faster velocity classes, in the strip's raw slip). Few elements slide that fast:
/// one predictable comparison for the others.
fn velocity_classes(shape: &[f64], slip: &[f64], (slow, fast): (f64, f64)) -> [f64; 2] {
    let (mut middle, mut above) = (0.0, 0.0);
    for (&shape, &slip) in shape.iter().zip(slip) {
        if slip >= slow {
            if slip <= fast {
                middle += shape * slip;
            } else {
                above += shape * slip;
            }
        }
    }
    [middle, above]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn element(area: f64, pressure: f64, traction: f64, slip: f64) -> FrictionElement {
        FrictionElement {
            lateral: 0.0,
            area,
            pressure,
            traction_sq: traction * traction,
            bound: f64::INFINITY,
            slip,
        }
    }

    #[test]
    fn strips_sum_as_their_elements() {
        // A FASTSIM field's strips (`add_strip`, from the march's own sums where they suffice)
        // against its elements one by one (`add`): Tγ, both wear rates and the local fatigue
        // index to 1e−9 relative (a slipping element's |q| is its bound to rounding), for every
        // wear model, partial and full slip with spin, sliding velocities in each of Archard's
        // classes, and hardnesses with and without the seizure pressure reached.
        use crate::tangential::fastsim::{Creepage, Fastsim, FastsimSettings, CONTACT_EXAMPLE};
        let rel = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs()) + 1e-300;
        let mut f = Fastsim::new(FastsimSettings::online()).unwrap();
        f.record_slips();
        let creepages = [
            (2e-4, 1e-4, 0.0),
            (1e-3, -5e-4, 0.3),
            (4e-3, 0.0, 1.0),
            (0.05, 0.02, 0.0),
        ];
        for (xi, eta, phi) in creepages {
            for speed in [1.0, 30.0, 200.0] {
                f.solve(&CONTACT_EXAMPLE, &Creepage { xi, eta, phi }, speed)
                    .unwrap();
                for wear_model in [WearModel::Off, WearModel::Usfd, WearModel::ArchardKth] {
                    for hardness in [2.6e9, 0.9e9] {
                        let params = DamageParams {
                            wear_model,
                            wheel_hardness: hardness,
                            rail_hardness: 1.3 * hardness,
                            ..DamageParams::default()
                        };
                        let mut by_element = DamageSum::new(params, speed);
                        f.friction_elements(|_, e| {
                            by_element.add(e);
                        });
                        let mut by_strip = DamageSum::new(params, speed);
                        assert!(f.friction_strips(|_, s| {
                            by_strip.add_strip(s);
                        }));
                        let case =
                            format!("{xi} {eta} {phi} V {speed} {wear_model:?} H {hardness}");
                        assert!(rel(by_strip.t_gamma(), by_element.t_gamma()), "{case}");
                        let t = by_element.t_gamma();
                        let (a, b) = (by_strip.finish(t), by_element.finish(t));
                        assert!(
                            rel(a.wheel_wear_rate, b.wheel_wear_rate),
                            "{case}: {a:?} {b:?}"
                        );
                        assert!(
                            rel(a.rail_wear_rate, b.rail_wear_rate),
                            "{case}: {a:?} {b:?}"
                        );
                        // The largest term to rounding: the skip test k + local p against
                        // |q| may decide a near tie either way, by visiting order.
                        assert!(
                            rel(a.fatigue_index_local, b.fatigue_index_local),
                            "{case}: {a:?} {b:?}"
                        );
                    }
                }
            }
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
            let t: f64 = e.traction_sq.sqrt() * e.slip * 1e-6;
            let rate = if t < 10.4 {
                5.3 * t
            } else if t <= 77.2 {
                55.0
            } else {
                (61.9 * t - 4778.7).max(55.0)
            };
            expected += rate * (e.area * 1e6) * 1e-9;
        }
        let d = sum.finish(sum.t_gamma());
        assert!(
            (d.wheel_wear_rate / expected - 1.0).abs() < 1e-12,
            "{d:?} {expected}"
        );
        // A patch carrying half the field wears half.
        let half = sum.finish(0.5 * sum.t_gamma());
        assert!((half.wheel_wear_rate / (0.5 * expected) - 1.0).abs() < 1e-12);
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
        let d = sum.finish(sum.t_gamma());
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
        assert_eq!(sum.finish(1.0), PatchDamage::default());
        sum.add(&element(0.0, 1e9, 1e8, 0.1));
        sum.add(&element(1e-6, 0.0, 0.0, 0.1));
        sum.add(&element(1e-6, 1e9, f64::INFINITY, f64::INFINITY));
        let d = sum.finish(sum.t_gamma());
        assert!(d.wheel_wear_rate.is_finite() && d.rail_wear_rate.is_finite());
    }
}
