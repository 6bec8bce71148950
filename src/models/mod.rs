//! The FMUs built from this crate. Each model is one file: its generated variable table
//! (`modelDescription/<Model>.json` → `build.rs`) and the mapping from variables to the physics
//! core. One shared library serves all of them; `fmi2Instantiate` selects the model by GUID.

use crate::fmi::model::{ModelError, ModelInfo};
use crate::fmi::variables::{RealVar, Values};
use crate::tangential::fastsim::{FastsimSettings, Flexibility, MarchScheme, TractionBound};

pub mod export;
pub mod hertz_contact;
pub mod wheel_rail_contact;

/// Every model compiled into the library.
pub static MODELS: &[&ModelInfo] = &[&hertz_contact::INFO, &wheel_rail_contact::INFO];

/// Looks a model up by its `modelIdentifier`.
pub fn by_identifier(id: &str) -> Option<&'static ModelInfo> {
    MODELS.iter().copied().find(|m| m.model_identifier == id)
}

/// FASTSIM settings from the integer parameters `tractionBound`, `flexibility`, `nx`, `ny`,
/// `fastsimScheme` (ranges already checked against the variable table; anything else is an
/// error).
pub(crate) fn fastsim_settings(
    traction_bound: i32,
    flexibility: i32,
    nx: i32,
    ny: i32,
    scheme: i32,
) -> Result<FastsimSettings, ModelError> {
    let scheme = option_of(
        "fastsimScheme",
        scheme,
        &[MarchScheme::Midpoint, MarchScheme::Contact],
    )?;
    let bound = option_of(
        "tractionBound",
        traction_bound,
        &[TractionBound::Elliptic, TractionBound::Parabolic],
    )?;
    let flexibility = option_of(
        "flexibility",
        flexibility,
        &[
            Flexibility::Three,
            Flexibility::Single,
            Flexibility::Blended,
        ],
    )?;
    let count = |name: &str, k: i32| {
        usize::try_from(k)
            .ok()
            .filter(|&n| n >= 1)
            .ok_or_else(|| ModelError::Error(format!("{name} = {k} must be >= 1")))
    };
    Ok(FastsimSettings {
        nx: count("nx", nx)?,
        ny: count("ny", ny)?,
        bound,
        flexibility,
        scheme,
    })
}

/// The option that the integer parameter `name` selects by its 1-based `code` among `options`;
/// any other code is an error listing the valid ones.
fn option_of<T: Copy>(name: &str, code: i32, options: &[T]) -> Result<T, ModelError> {
    let chosen = usize::try_from(code)
        .ok()
        .and_then(|k| k.checked_sub(1))
        .and_then(|i| options.get(i));
    chosen.copied().ok_or_else(|| {
        let codes: Vec<String> = (1..=options.len()).map(|k| k.to_string()).collect();
        let (last, others) = codes.split_last().expect("at least one option");
        ModelError::Error(format!(
            "{name} = {code} is not {} or {last}",
            others.join(", ")
        ))
    })
}

/// Writes the output values `xs` to the variables `vars`, in order ([`set_output`]).
pub(crate) fn set_outputs<const N: usize>(
    values: &mut Values,
    vars: [RealVar; N],
    xs: [f64; N],
) -> Result<(), ModelError> {
    for (v, x) in vars.into_iter().zip(xs) {
        set_output(values, v, x)?;
    }
    Ok(())
}

/// Writes an output value; a non-finite one is an internal error (outputs are never NaN).
pub(crate) fn set_output(values: &mut Values, v: RealVar, x: f64) -> Result<(), ModelError> {
    if !x.is_finite() {
        return Err(ModelError::Error(format!(
            "internal error: non-finite output ({x}) in slot {}",
            v.0
        )));
    }
    values.set_real(v, x);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error_of(r: Result<FastsimSettings, ModelError>) -> String {
        match r {
            Err(ModelError::Error(message)) => message,
            other => panic!("expected an error, got {other:?}"),
        }
    }

    #[test]
    fn fastsim_options_are_one_based_and_a_bad_code_names_the_valid_ones() {
        let s = fastsim_settings(2, 3, 10, 11, 2).unwrap();
        assert_eq!(
            (s.bound, s.flexibility, s.scheme, s.nx, s.ny),
            (
                TractionBound::Parabolic,
                Flexibility::Blended,
                MarchScheme::Contact,
                10,
                11
            )
        );
        let s = fastsim_settings(1, 1, 1, 1, 1).unwrap();
        assert_eq!(
            (s.bound, s.flexibility, s.scheme),
            (
                TractionBound::Elliptic,
                Flexibility::Three,
                MarchScheme::Midpoint
            )
        );
        assert_eq!(
            error_of(fastsim_settings(1, 1, 10, 10, 3)),
            "fastsimScheme = 3 is not 1 or 2"
        );
        assert_eq!(
            error_of(fastsim_settings(0, 1, 10, 10, 1)),
            "tractionBound = 0 is not 1 or 2"
        );
        assert_eq!(
            error_of(fastsim_settings(1, -1, 10, 10, 1)),
            "flexibility = -1 is not 1, 2 or 3"
        );
        assert_eq!(
            error_of(fastsim_settings(1, 1, 0, 10, 1)),
            "nx = 0 must be >= 1"
        );
    }
}
