//! FMU `HertzContact`: a single elliptic contact point (Hertz + Kalker + FASTSIM) for hosts that
//! compute their own contact geometry. Variables: `modelDescription/HertzContact.json`; physics:
//! [`crate::point_contact`].

use crate::fastsim::{Creepage, FastsimSettings, Flexibility, TractionBound};
use crate::fmi::model::{InstanceContext, Model, ModelError, ModelInfo};
use crate::fmi::variables::Values;
use crate::point_contact::{Material, PointContact, PointContactInput};

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

/// FASTSIM settings from the integer parameters (ranges already checked against the table).
fn fastsim_settings(values: &Values) -> Result<FastsimSettings, ModelError> {
    let bound = match values.integer(var::tractionBound) {
        1 => TractionBound::Elliptic,
        2 => TractionBound::Parabolic,
        k => {
            return Err(ModelError::Error(format!(
                "tractionBound = {k} is not 1 or 2"
            )))
        }
    };
    let flexibility = match values.integer(var::flexibility) {
        1 => Flexibility::Three,
        2 => Flexibility::Single,
        3 => Flexibility::Blended,
        k => {
            return Err(ModelError::Error(format!(
                "flexibility = {k} is not 1, 2 or 3"
            )))
        }
    };
    let count = |name: &str, k: i32| {
        usize::try_from(k)
            .ok()
            .filter(|&n| n >= 1)
            .ok_or_else(|| ModelError::Error(format!("{name} = {k} must be >= 1")))
    };
    Ok(FastsimSettings {
        nx: count("nx", values.integer(var::nx))?,
        ny: count("ny", values.integer(var::ny))?,
        bound,
        flexibility,
    })
}

impl Model for HertzContact {
    fn initialize(&mut self, values: &Values) -> Result<(), ModelError> {
        let material = Material {
            youngs_modulus: values.real(var::E),
            poisson_ratio: values.real(var::nu),
            friction: values.real(var::mu),
        };
        self.solver = Some(PointContact::new(material, fastsim_settings(values)?)?);
        Ok(())
    }

    fn evaluate(&mut self, values: &mut Values, _time: f64) -> Result<(), ModelError> {
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
            if !x.is_finite() {
                return Err(ModelError::Error(format!(
                    "internal error: non-finite output ({x}) for N = {}, A = {}, B = {}",
                    input.normal_force, input.curv_a, input.curv_b
                )));
            }
            values.set_real(v, x);
        }
        Ok(())
    }
}
