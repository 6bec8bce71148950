//! FMU `HertzContact`: a single elliptic contact point (Hertz + Kalker + FASTSIM) for hosts that
//! compute their own contact geometry. Variables: `modelDescription/HertzContact.json`; physics:
//! [`crate::point_contact`].

use super::{fastsim_settings, set_output};
use crate::fmi::model::{Evaluation, InstanceContext, Model, ModelError, ModelInfo};
use crate::fmi::variables::Values;
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
}
