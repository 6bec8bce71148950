//! One elliptic contact point: Hertz normal contact, Kalker's creep coefficients and FASTSIM.
//!
//! This is the classic baseline of vehicle dynamics (Kalker 1982; docs/theory.md §2–§4):
//! * normal problem: Hertz (H1–H4) from the normal force N and the relative curvatures A, B;
//! * tangential problem: FASTSIM (F1–F4) on the Hertz ellipse, with C11, C22, C23 from Kalker's
//!   table (K1–K3) for the ellipse's a/b.
//!
//! Signs: forces are those of the rail on the wheel, creepages those of the wheel relative to the
//! rail (`docs/conventions.md`). N = 0 is legal and means no contact: every force is zero.
//!
//! Known limits: identical elastic materials for wheel and rail; a single planar contact; the
//! creep coefficients still describe the ellipse shape at N = 0 (a/b depends on A/B only).

use crate::error::{require_non_negative, require_positive, InputError};
use crate::material::Material;
use crate::normal::hertz::{contact_modulus, hertz_from_load, shear_modulus, HertzPatch};
use crate::tangential::fastsim::{
    Creepage, EllipticContact, Fastsim, FastsimResult, FastsimSettings,
};
use crate::tangential::kalker::{creep_coefficients, CreepCoefficients};

/// Inputs of one contact-point evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointContactInput {
    /// Normal force N [N], ≥ 0.
    pub normal_force: f64,
    /// Relative curvature in the rolling direction A [1/m], > 0.
    pub curv_a: f64,
    /// Relative lateral curvature B [1/m], > 0.
    pub curv_b: f64,
    /// Rolling speed V [m/s], ≥ 0 (scales the frictional power only).
    pub rolling_speed: f64,
    /// Creepages of the wheel relative to the rail.
    pub creepage: Creepage,
}

/// Result of one contact-point evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointContactResult {
    /// The Hertz ellipse (a along the rolling direction).
    pub patch: HertzPatch,
    /// Kalker's coefficients for the ellipse's a/b and ν.
    pub coefficients: CreepCoefficients,
    /// Creep forces on the wheel, adhesion fraction, frictional power.
    pub tangential: FastsimResult,
}

/// Solver for one contact point; owns the FASTSIM buffers, so [`PointContact::solve`] does not
/// allocate.
pub struct PointContact {
    material: Material,
    fastsim: Fastsim,
}

impl PointContact {
    /// Validates the material and sizes the FASTSIM grid.
    pub fn new(material: Material, settings: FastsimSettings) -> Result<Self, InputError> {
        material.validate()?;
        Ok(Self {
            material,
            fastsim: Fastsim::new(settings)?,
        })
    }

    pub fn material(&self) -> Material {
        self.material
    }

    /// The last solve's element tractions.
    pub fn fastsim(&self) -> &Fastsim {
        &self.fastsim
    }

    /// Solves the normal and tangential problems.
    pub fn solve(&mut self, input: &PointContactInput) -> Result<PointContactResult, InputError> {
        let m = self.material;
        require_non_negative("N", input.normal_force)?;
        require_positive("A", input.curv_a)?;
        require_positive("B", input.curv_b)?;
        require_non_negative("V", input.rolling_speed)?;
        let e_star = contact_modulus(m.youngs_modulus, m.poisson_ratio);
        let mut patch = hertz_from_load(input.curv_a, input.curv_b, input.normal_force, e_star)?;
        // A load so small that the ellipse underflows to zero size is no contact.
        let in_contact = patch.a.is_normal() && patch.b.is_normal();
        if !in_contact {
            patch = HertzPatch::default();
        }
        let normal_force = if in_contact { input.normal_force } else { 0.0 };
        // The axis ratio a/b depends on A/B only; without contact take it from a unit-load
        // ellipse so the coefficients still describe the contact's shape.
        let shape = if in_contact {
            patch
        } else {
            hertz_from_load(input.curv_a, input.curv_b, 1.0, e_star)?
        };
        let coefficients = creep_coefficients(shape.a, shape.b, m.poisson_ratio)?;
        let contact = EllipticContact {
            a: patch.a,
            b: patch.b,
            normal_force,
            shear_modulus: shear_modulus(m.youngs_modulus, m.poisson_ratio),
            nu: m.poisson_ratio,
            mu: m.friction,
        };
        let tangential = self
            .fastsim
            .solve(&contact, &input.creepage, input.rolling_speed)?;
        Ok(PointContactResult {
            patch,
            coefficients,
            tangential,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solver() -> PointContact {
        let material = Material {
            youngs_modulus: 2.1e11,
            poisson_ratio: 0.28,
            friction: 0.3,
        };
        PointContact::new(material, FastsimSettings::default()).unwrap()
    }

    fn input(normal_force: f64) -> PointContactInput {
        PointContactInput {
            normal_force,
            curv_a: 0.8464,
            curv_b: 2.406,
            rolling_speed: 30.0,
            creepage: Creepage {
                xi: 1e-3,
                eta: -6.25e-4,
                phi: 0.625,
            },
        }
    }

    #[test]
    fn no_load_and_underflowing_load_mean_no_contact() {
        let mut s = solver();
        let reference = s.solve(&input(82_000.0)).unwrap();
        // The smallest positive f64 load: the ellipse underflows; treated as no contact, and
        // the coefficients still describe the shape (a/b from A/B only, so equal to the loaded
        // case's to rounding).
        for n in [0.0, 5e-324] {
            let r = s.solve(&input(n)).unwrap();
            assert_eq!(r.patch, HertzPatch::default());
            assert_eq!(
                (r.tangential.fx, r.tangential.fy, r.tangential.mz),
                (0.0, 0.0, 0.0)
            );
            assert!((r.coefficients.c11 / reference.coefficients.c11 - 1.0).abs() < 1e-9);
        }
    }

    #[test]
    fn material_ranges_are_checked_by_name() {
        let bad = Material {
            youngs_modulus: 2.1e11,
            poisson_ratio: 0.6,
            friction: 0.3,
        };
        let e = PointContact::new(bad, FastsimSettings::default())
            .err()
            .unwrap();
        assert_eq!(e.name, "nu");
        let mut s = solver();
        let mut i = input(1e4);
        i.curv_b = -1.0;
        assert_eq!(s.solve(&i).unwrap_err().name, "B");
    }
}
