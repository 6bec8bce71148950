//! FMU `HertzContact`: a single elliptic contact point (Hertz + Kalker + FASTSIM) for hosts that
//! compute their own contact geometry. Variables: `modelDescription/HertzContact.json`; physics:
//! [`crate::point_contact`].

use super::{fastsim_settings, set_output};
use crate::fmi::model::{Evaluation, InstanceContext, Model, ModelError, ModelInfo};
use crate::fmi::variables::{RealVar, Values, VarInfo};
use crate::material::Material;
use crate::point_contact::{PointContact, PointContactInput};
use crate::tangential::fastsim::Creepage;

/// Generated from `modelDescription/HertzContact.json` by `build.rs`.
pub mod generated {
    include!(concat!(env!("OUT_DIR"), "/HertzContact_vars.rs"));
}
use generated::var;

pub static INFO: ModelInfo = ModelInfo {
    model_identifier: generated::MODEL_IDENTIFIER,
    guid: generated::GUID,
    model_description_xml: generated::MODEL_DESCRIPTION_XML,
    variables: &generated::VARIABLES,
    counts: generated::COUNTS,
    default_experiment: generated::DEFAULT_EXPERIMENT,
    provides_directional_derivative: generated::PROVIDES_DIRECTIONAL_DERIVATIVE,
    create,
};

fn create(_context: &InstanceContext) -> Box<dyn Model> {
    Box::new(HertzContact { solver: None })
}

/// The instance's physics: built at initialization from the parameters.
struct HertzContact {
    solver: Option<PointContact>,
}

impl Model for HertzContact {
    fn initialize(&mut self, values: &Values) -> Result<(), ModelError> {
        let material = Material {
            youngs_modulus: values.real(var::E),
            poisson_ratio: values.real(var::nu),
            friction: values.real(var::mu),
        };
        self.solver = Some(PointContact::new(
            material,
            fastsim_settings(
                values.integer(var::tractionBound),
                values.integer(var::flexibility),
                values.integer(var::nx),
                values.integer(var::ny),
                values.integer(var::fastsimScheme),
            )?,
        )?);
        Ok(())
    }

    fn evaluate(&mut self, values: &mut Values, _time: f64) -> Result<Evaluation, ModelError> {
        let solver = self
            .solver
            .as_mut()
            .ok_or_else(|| ModelError::Error("model used before initialization".into()))?;
        let input = PointContactInput {
            normal_force: values.real(var::N),
            curv_a: values.real(var::A),
            curv_b: values.real(var::B),
            rolling_speed: values.real(var::V),
            creepage: Creepage {
                xi: values.real(var::xi),
                eta: values.real(var::eta),
                phi: values.real(var::phi),
            },
        };
        let r = solver.solve(&input)?;
        let t = &r.tangential;
        for (v, x) in [
            (var::a, r.patch.a),
            (var::b, r.patch.b),
            (var::penetration, r.patch.approach),
            (var::pmax, r.patch.p0),
            (var::area, r.patch.area()),
            (var::Fx, t.fx),
            (var::Fy, t.fy),
            (var::Mz, t.mz),
            (var::adhesionFraction, t.adhesion_fraction),
            (var::frictionalPower, t.frictional_power),
            (var::maxTraction, t.max_traction),
            (var::C11, r.coefficients.c11),
            (var::C22, r.coefficients.c22),
            (var::C23, r.coefficients.c23),
        ] {
            set_output(values, v, x)?;
        }
        Ok(Evaluation::Ok)
    }

    /// The point contact has no history: a probe is an evaluation.
    fn probe(&mut self, values: &mut Values) -> Result<(), ModelError> {
        self.evaluate(values, 0.0).map(|_| ())
    }

    /// 1e−6 of the curvatures A, B (they span 1e−3 … 1e5 1/m); 1e−4 1/m of the spin (φ·a ≈ 6e−7
    /// on a 6 mm patch, like the creepages' 1e−6); the default for the others (1e−6 of the
    /// creepages ξ, η, of N and V above 1).
    fn difference_step(&self, values: &Values, v: &VarInfo) -> f64 {
        match RealVar(v.slot) {
            var::A | var::B => 1e-6 * values.reals[v.slot],
            var::phi => 1e-4,
            _ => crate::fmi::derivative::default_step(values, v),
        }
    }
}
