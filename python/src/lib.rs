//! railcontact for Python: the native module (`railcontact._native`) behind the `railcontact`
//! package (`python/railcontact/`), which turns its JSON and byte columns into dicts and NumPy
//! arrays.
//!
//! Every evaluation goes through the `railcontact` command's own library — case documents
//! ([`railcontact_cli::case`]), one evaluation as JSON ([`railcontact_cli::solve`]) — and so
//! through the `WheelRailContact` FMU's model: the package, the command and the FMU give the same
//! numbers bit for bit. Errors carry the command's messages: [`RailcontactError`] for bad input
//! (exit code 1 of the command), [`DiscardError`] for a state the element refuses (no contact
//! inside the profiles, a load the normal model cannot carry: exit code 2).
//!
//! The evaluations release the GIL.

mod profile;
mod studies;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use railcontact::fmi::model::Evaluation;
use railcontact::fmi::variables::{Causality, Values, VarInfo, VarType};
use railcontact::models::wheel_rail_contact::INFO;
use railcontact_cli::solve::Extras;
use railcontact_cli::{case, json, solve, Failure};

create_exception!(
    _native,
    RailcontactError,
    PyException,
    "Bad input: a case key, value, profile or argument (the railcontact command's exit code 1)."
);
create_exception!(
    _native,
    DiscardError,
    RailcontactError,
    "A state the element refuses: no contact inside the profiles, or a load the normal model \
     cannot carry (the command's exit code 2, FMI Discard)."
);

pub(crate) fn to_py(f: Failure) -> PyErr {
    match f {
        Failure::Error(m) => RailcontactError::new_err(m),
        Failure::Discard(m) => DiscardError::new_err(m),
    }
}

/// The FMU's values at their start values, overridden by the case document `text` (a JSON
/// object of parameter and input names; relative profile paths from the working directory).
pub(crate) fn case_values(text: &str) -> Result<Values, Failure> {
    let mut values = Values::from_start(INFO.variables, INFO.counts);
    let case = case::parse(text).map_err(|e| Failure::Error(e.message("case")))?;
    case.apply(&mut values, None);
    Ok(values)
}

/// `railcontact solve` on the case document `case` (JSON): the JSON text the command prints,
/// and the warning of an implausible contact state (or `None`). `grid`: pressure points per
/// strip; `traction`: the tangential solution's elements.
#[pyfunction]
#[pyo3(signature = (case, grid=None, traction=false))]
fn solve_json(
    py: Python<'_>,
    case: &str,
    grid: Option<usize>,
    traction: bool,
) -> PyResult<(String, Option<String>)> {
    if let Some(nx) = grid {
        if !solve::GRID_POINTS.contains(&nx) {
            return Err(RailcontactError::new_err(format!(
                "grid = {nx}: needs {}…{} points per strip",
                solve::GRID_POINTS.start(),
                solve::GRID_POINTS.end()
            )));
        }
    }
    let case = case.to_owned();
    py.allow_threads(move || {
        let mut values = case_values(&case)?;
        let (doc, warning) = solve::solve(&mut values, Extras { grid, traction })?;
        let text = json::to_text(&doc)
            .map_err(|e| Failure::Error(format!("cannot write the JSON: {e}")))?;
        Ok((text, warning))
    })
    .map_err(to_py)
}

/// The Real outputs' names, in the variable table's order.
#[pyfunction]
fn real_outputs() -> Vec<&'static str> {
    outputs().map(|v| v.name).collect()
}

fn outputs() -> impl Iterator<Item = &'static VarInfo> {
    INFO.variables
        .iter()
        .filter(|v| v.causality == Causality::Output && v.ty == VarType::Real)
}

/// The Real input `name` of `WheelRailContact` (what a batch or a [`Wheelset`] may set; the
/// parameters go in the case).
fn real_input(name: &str) -> Result<&'static VarInfo, Failure> {
    INFO.variable(name)
        .filter(|v| v.ty == VarType::Real && v.causality == Causality::Input)
        .ok_or_else(|| {
            Failure::Error(format!(
                "'{name}': not a Real input of WheelRailContact (parameters go in the case)"
            ))
        })
}

/// The error of a value outside `info`'s range, `what` naming it ("'y' = 0.2").
fn out_of_range(info: &VarInfo, what: &str) -> Failure {
    Failure::Error(format!(
        "{what} is outside the allowed range {}{}",
        info.allowed,
        railcontact_cli::unit_suffix(info)
    ))
}

/// A batch's outputs: the Real outputs' names, their values row by row (rows × names float64
/// bytes, native order) and the rows' status (int32 bytes).
type BatchOut<'py> = (Vec<&'static str>, Bound<'py, PyBytes>, Bound<'py, PyBytes>);

/// An input column of a batch: its variable and its values.
struct Column<'a> {
    info: &'static VarInfo,
    values: Vec<f64>,
    name: &'a str,
}

/// Many evaluations of the case document `case` (JSON) in one call: row k sets each input
/// `names[j]` (a Real input) to `columns[j]`'s k-th float64 (native byte order) and evaluates —
/// each row from the last, as the FMU's steps do (warm starts and output slots carried: what a
/// [`Wheelset`] gives row by row), or with `independent` each from the initialized model's
/// state (what [`solve_json`] gives for that case) — bit for bit, with the profiles loaded once. Returns every Real output as a column
/// of float64 bytes, and the rows' status (0 ok, 1 implausible state, 2 refused: its outputs
/// NaN) as int32 bytes — the outputs as one row-major matrix (names × rows), which NumPy views
/// column by column without a copy.
#[pyfunction]
#[pyo3(signature = (case, names, columns, independent=false))]
fn solve_batch<'py>(
    py: Python<'py>,
    case: &str,
    names: Vec<String>,
    columns: Vec<Bound<'py, PyBytes>>,
    independent: bool,
) -> PyResult<BatchOut<'py>> {
    if names.len() != columns.len() {
        return Err(RailcontactError::new_err(format!(
            "{} names for {} columns",
            names.len(),
            columns.len()
        )));
    }
    let mut inputs = Vec::with_capacity(names.len());
    let mut rows = None;
    for (name, column) in names.iter().zip(&columns) {
        let bytes = column.as_bytes();
        let info = real_input(name).map_err(to_py)?;
        if bytes.len() % 8 != 0 {
            return Err(RailcontactError::new_err(format!(
                "'{name}': {} bytes are not whole float64 values",
                bytes.len()
            )));
        }
        let values: Vec<f64> = bytes
            .chunks_exact(8)
            .map(|b| f64::from_ne_bytes(b.try_into().expect("8 bytes")))
            .collect();
        match rows {
            None => rows = Some(values.len()),
            Some(n) if n != values.len() => {
                return Err(RailcontactError::new_err(format!(
                    "'{name}': {} values, the first column has {n}",
                    values.len()
                )))
            }
            Some(_) => {}
        }
        inputs.push(Column { info, values, name });
    }
    let rows = rows.unwrap_or(1);
    let case = case.to_owned();
    let (out, status) = py
        .allow_threads(|| batch(&case, &inputs, rows, independent))
        .map_err(to_py)?;
    let bytes: Vec<u8> = out.iter().flat_map(|v| v.to_ne_bytes()).collect();
    let status: Vec<u8> = status.iter().flat_map(|s| s.to_ne_bytes()).collect();
    Ok((
        outputs().map(|v| v.name).collect(),
        PyBytes::new(py, &bytes),
        PyBytes::new(py, &status),
    ))
}

/// [`solve_batch`]'s loop: the Real outputs row by row (in `real_outputs()`'s order) and the
/// rows' status.
fn batch(
    case: &str,
    inputs: &[Column<'_>],
    rows: usize,
    independent: bool,
) -> Result<(Vec<f64>, Vec<i32>), Failure> {
    let mut values = case_values(case)?;
    // Range checks as `fmi2SetReal` does them, before the first evaluation.
    for c in inputs {
        if let Some((k, v)) = c
            .values
            .iter()
            .enumerate()
            .find(|(_, v)| !c.info.accepts_real(**v))
        {
            return Err(out_of_range(
                c.info,
                &format!("'{}' = {v} (row {k})", c.name),
            ));
        }
    }
    let mut model = railcontact_cli::model(&values)?;
    // `independent`: every row from the initialized model's state (each the evaluation
    // `solve_json` makes); else each from the last, as an FMU's steps.
    let mut initial = Vec::new();
    model.save_state(&mut initial);
    let slots: Vec<usize> = outputs().map(|v| v.slot).collect();
    let mut out = Vec::with_capacity(rows * slots.len());
    let mut status = Vec::with_capacity(rows);
    for k in 0..rows {
        if independent {
            model
                .restore_state(&initial)
                .map_err(|e| Failure::Error(format!("internal error: {e}")))?;
        }
        for c in inputs {
            values.reals[c.info.slot] = c.values[k];
        }
        let code = match model.evaluate(&mut values, 0.0) {
            Ok(Evaluation::Ok) => 0,
            Ok(Evaluation::Warning(_)) => 1,
            Err(railcontact::fmi::model::ModelError::Discard(_)) => 2,
            Err(e) => return Err(e.into()),
        };
        if code == 2 {
            out.extend(slots.iter().map(|_| f64::NAN));
        } else {
            out.extend(slots.iter().map(|&s| values.reals[s]));
        }
        status.push(code);
    }
    Ok((out, status))
}

/// A wheelset for loops: the case's model, initialized once; each [`Wheelset::solve`] sets
/// Real inputs and evaluates from the state the last left (as the FMU's steps).
#[pyclass(unsendable)]
struct Wheelset {
    model: Box<dyn railcontact::fmi::model::Model>,
    values: Values,
}

#[pymethods]
impl Wheelset {
    #[new]
    fn new(case: &str) -> PyResult<Self> {
        let values = case_values(case).map_err(to_py)?;
        let model = railcontact_cli::model(&values).map_err(to_py)?;
        Ok(Self { model, values })
    }

    /// Sets the Real inputs `names` to `values` and evaluates: the Real outputs (in
    /// `real_outputs()`'s order) and the status (0 ok, 1 implausible; a refused state raises
    /// `DiscardError`).
    fn solve(&mut self, names: Vec<String>, values: Vec<f64>) -> PyResult<(Vec<f64>, i32)> {
        if names.len() != values.len() {
            return Err(RailcontactError::new_err(format!(
                "{} names for {} values",
                names.len(),
                values.len()
            )));
        }
        for (name, &v) in names.iter().zip(&values) {
            let info = real_input(name).map_err(to_py)?;
            if !info.accepts_real(v) {
                return Err(to_py(out_of_range(info, &format!("'{name}' = {v}"))));
            }
            self.values.reals[info.slot] = v;
        }
        let code = match self.model.evaluate(&mut self.values, 0.0) {
            Ok(Evaluation::Ok) => 0,
            Ok(Evaluation::Warning(_)) => 1,
            Err(e) => return Err(to_py(e.into())),
        };
        Ok((outputs().map(|i| self.values.reals[i.slot]).collect(), code))
    }
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Wheelset>()?;
    m.add_class::<profile::Profile>()?;
    m.add_function(wrap_pyfunction!(studies::conicity_json, m)?)?;
    m.add_function(wrap_pyfunction!(studies::wear_update_json, m)?)?;
    m.add_function(wrap_pyfunction!(solve_json, m)?)?;
    m.add_function(wrap_pyfunction!(solve_batch, m)?)?;
    m.add_function(wrap_pyfunction!(real_outputs, m)?)?;
    m.add(
        "CONICITY_AMPLITUDES",
        railcontact::wheelset::conicity::DEFAULT_AMPLITUDES.to_vec(),
    )?;
    m.add(
        "CONICITY_STEP",
        railcontact::wheelset::conicity::DEFAULT_Y_STEP,
    )?;
    m.add("WEAR_MAX_DEPTH", railcontact_cli::wear::DEFAULT_MAX_DEPTH)?;
    m.add("WEAR_SMOOTHING", railcontact_cli::wear::DEFAULT_SMOOTHING)?;
    m.add("RailcontactError", m.py().get_type::<RailcontactError>())?;
    m.add("DiscardError", m.py().get_type::<DiscardError>())?;
    Ok(())
}
