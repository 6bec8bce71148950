//! Wear functions, applied element by element to the contact's pressure and slip fields.
//!
//! Papers: R. Lewis, R.S. Dwyer-Joyce, "Wear mechanisms and transitions in railway wheel steels",
//! *Proc. IMechE Part J* 218 (2004) 467–478 (the USFD Tγ/A function, twin-disc tests of R8T wheel
//! on UIC60 900A rail steel), applied per FASTSIM element as in F. Braghin, R. Lewis,
//! R.S. Dwyer-Joyce, S. Bruni, "A mathematical model to predict railway wheel profile evolution
//! due to wear", *Wear* 261 (2006) 1253–1264; T. Jendel, "Prediction of wheel profile wear —
//! comparisons with field measurements", *Wear* 253 (2002) 89–99 (Archard's law with the KTH
//! wear map from Olofsson and Telliskivi's pin-on-disc data). Equations and choices:
//! docs/theory.md §10.1–10.2.
//!
//! # Equations
//!
//! USFD, per element of area ΔA with traction |q| and slip |s| (sliding distance per distance
//! rolled), local Tγ/A = |q| |s| in N/mm²:
//!
//! ```text
//!   w = 5.3 Tγ/A                       Tγ/A < 10.4   (mild)
//!   w = 55.0                           10.4 ≤ Tγ/A ≤ 77.2   (severe)
//!   w = max(55.0, 61.9 Tγ/A − 4778.7)  Tγ/A > 77.2   (catastrophic)
//! ```
//!
//! in µg per metre rolled per mm² of contact; the element removes w ΔA per metre rolled.
//!
//! Archard, per element: volume per metre rolled k p |s| ΔA / H with the KTH map's k by contact
//! pressure p and sliding velocity v = V |s|: k1 where p > 0.8 H, else k2 (v < 0.2 m/s),
//! k3 (0.2 ≤ v ≤ 0.7 m/s), k4 (v > 0.7 m/s); mass = ρ × volume.
//!
//! # Choices
//!
//! * The catastrophic line as published starts near zero at 77.2 N/mm² (61.9 × 77.2 − 4778.7 ≈
//!   0) below the severe plateau: the function is taken as the larger of the two, so that the
//!   wear rate never falls as Tγ/A grows (it rejoins the line at 78.1 N/mm²).
//! * The USFD function was measured for the wheel steel of an R8T/900A pair; it is applied to
//!   the rail of the same contact as well (same mass per metre rolled), for lack of a rail
//!   function measured on the same pair.
//! * The map's coefficients are the middles of Jendel's ranges (k1 300–400, k2 and k4 1–10,
//!   k3 30–40, × 10⁻⁴); wear coefficients scatter by ±40–60 % between tests.
//!
//! # Limits
//!
//! Both functions are steady-state laboratory fits: the element-wise local Tγ/A follows the
//! simplified theory's slip field (FASTSIM or FaStrip), which puts all slip in the slip zone.
//! The KTH map's steps in v and p make the Archard wear rate jump where an element's sliding
//! velocity crosses 0.2 or 0.7 m/s, as published.

/// Density of wheel and rail steel [kg/m³].
pub const STEEL_DENSITY: f64 = 7850.0;

/// USFD regime limits of Tγ/A [Pa] (10.4 and 77.2 N/mm²).
pub const USFD_MILD_LIMIT: f64 = 10.4e6;
pub const USFD_SEVERE_LIMIT: f64 = 77.2e6;
/// The mild regime's wear per unit Tγ: 5.3 µg/(m mm²) per N/mm² = 5.3e−9 kg/(m N).
pub const USFD_MILD_RATE: f64 = 5.3e-9;

/// The KTH map's wear coefficients [-] (middles of the published ranges).
pub const KTH_K1: f64 = 350e-4;
pub const KTH_K2: f64 = 5.5e-4;
pub const KTH_K3: f64 = 35e-4;
pub const KTH_K4: f64 = 5.5e-4;

/// The USFD wear rate at local Tγ/A = `t_gamma_per_area` [Pa]: mass removed per metre rolled
/// per unit contact area [kg/(m m²)].
pub fn usfd_rate(t_gamma_per_area: f64) -> f64 {
    // µg/(m mm²) → kg/(m m²): 1e−9 / 1e−6.
    const SI: f64 = 1e-3;
    let t = t_gamma_per_area * 1e-6;
    if t_gamma_per_area < USFD_MILD_LIMIT {
        return (USFD_MILD_RATE * t_gamma_per_area).max(0.0);
    }
    let published = if t_gamma_per_area <= USFD_SEVERE_LIMIT {
        55.0
    } else {
        (61.9 * t - 4778.7).max(55.0)
    };
    published.max(0.0) * SI
}

/// The KTH map's wear coefficient at contact pressure `pressure` [Pa], sliding velocity
/// `sliding_velocity` [m/s] and hardness `hardness` [Pa].
pub fn kth_coefficient(pressure: f64, sliding_velocity: f64, hardness: f64) -> f64 {
    if pressure > 0.8 * hardness {
        KTH_K1
    } else {
        kth_sliding_coefficient(sliding_velocity)
    }
}

/// The KTH map's sliding velocities [m/s] between its regions k2 and k3, and k3 and k4.
pub const KTH_SLOW: f64 = 0.2;
pub const KTH_FAST: f64 = 0.7;

/// The KTH map's coefficient below its seizure pressure, by the sliding velocity [m/s].
pub fn kth_sliding_coefficient(sliding_velocity: f64) -> f64 {
    if sliding_velocity < KTH_SLOW {
        KTH_K2
    } else if sliding_velocity <= KTH_FAST {
        KTH_K3
    } else {
        KTH_K4
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn usfd_regimes() {
        // Mild: 5.3 µg/(m mm²) per N/mm²; continuous at 10.4 within the published rounding
        // (5.3 × 10.4 = 55.12 against 55.0).
        assert!((usfd_rate(1e6) - 5.3e-3).abs() < 1e-15);
        assert!((usfd_rate(10.39e6) - 5.3 * 10.39e-3).abs() < 1e-12);
        assert_eq!(usfd_rate(10.4e6), 55.0e-3);
        assert_eq!(usfd_rate(50e6), 55.0e-3);
        // Catastrophic: never below the plateau, on the published line beyond 78.1.
        assert_eq!(usfd_rate(77.5e6), 55.0e-3);
        assert!((usfd_rate(100e6) - (6190.0 - 4778.7) * 1e-3).abs() < 1e-9);
        assert_eq!(usfd_rate(0.0), 0.0);
        // Monotone over the range.
        let mut last = 0.0;
        for i in 0..2000 {
            let r = usfd_rate(i as f64 * 0.1e6);
            assert!(r >= last - 0.2e-3, "{i}");
            last = r;
        }
    }

    #[test]
    fn kth_map_regions() {
        let h = 2.6e9;
        assert_eq!(kth_coefficient(0.9 * h, 0.1, h), KTH_K1);
        assert_eq!(kth_coefficient(1e9, 0.1, h), KTH_K2);
        assert_eq!(kth_coefficient(1e9, 0.5, h), KTH_K3);
        assert_eq!(kth_coefficient(1e9, 1.0, h), KTH_K4);
    }
}
