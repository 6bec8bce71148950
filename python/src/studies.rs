//! The command's studies for Python: the equivalent conicity (`railcontact conicity`) and the
//! wear loop's profile update (`railcontact wear`), through the command's own library.

use crate::{case_values, to_py};
use pyo3::prelude::*;
use railcontact_cli::conicity::{self, ConicityOptions};
use railcontact_cli::wear::{self, WearOptions};
use railcontact_cli::{json, Failure};
use std::path::PathBuf;

fn text(doc: &serde_json::Value) -> Result<String, Failure> {
    json::to_text(doc).map_err(|e| Failure::Error(format!("cannot write the JSON: {e}")))
}

/// `railcontact conicity` on the case document `case` (JSON): the JSON text the command prints
/// (Δr(y), the rigid contact points, λ(A) by harmonic linearisation and Klingel).
#[pyfunction]
#[pyo3(signature = (case, amplitudes, step, roll=true, load=None))]
pub fn conicity_json(
    py: Python<'_>,
    case: &str,
    amplitudes: Vec<f64>,
    step: f64,
    roll: bool,
    load: Option<f64>,
) -> PyResult<String> {
    let options = ConicityOptions {
        amplitudes,
        step,
        roll,
        load,
    };
    py.allow_threads(|| {
        let values = case_values(case)?;
        let run = conicity::conicity(&values, &options)?;
        text(&conicity::to_json(&values, &run))
    })
    .map_err(to_py)
}

/// `railcontact wear` on the case document `case` (JSON): worn profiles from the wear records
/// `records` written into `out`; the JSON summary the command prints.
#[pyfunction]
pub fn wear_update_json(
    py: Python<'_>,
    case: &str,
    records: Vec<PathBuf>,
    distance: f64,
    max_depth: f64,
    smoothing: f64,
    out: PathBuf,
) -> PyResult<String> {
    let options = WearOptions {
        records,
        distance,
        max_depth,
        smoothing,
        out,
    };
    py.allow_threads(|| {
        let values = case_values(case)?;
        text(&wear::update(&values, &options)?)
    })
    .map_err(to_py)
}
