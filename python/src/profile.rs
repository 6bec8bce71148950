//! Profiles for Python: read (built-in names and every file format the element reads), checked,
//! evaluated, worn and written — the element's own [`railcontact::geometry::profile::Profile`].

use crate::{to_py, RailcontactError};
use pyo3::prelude::*;
use railcontact::damage::update::{at_bins, worn_points};
use railcontact::geometry::profile::{Profile as Inner, ProfileKind};
use railcontact_cli::Failure;
use std::path::Path;

/// "wheel" or "rail" as a [`ProfileKind`].
fn kind_of(kind: &str) -> PyResult<ProfileKind> {
    match kind {
        "wheel" => Ok(ProfileKind::Wheel),
        "rail" => Ok(ProfileKind::Rail),
        other => Err(RailcontactError::new_err(format!(
            "kind = '{other}': needs 'wheel' or 'rail'"
        ))),
    }
}

fn error(e: impl std::fmt::Display) -> PyErr {
    RailcontactError::new_err(e.to_string())
}

/// A wheel or rail profile z(y) in its profile frame (SI metres; `docs/conventions.md`).
#[pyclass(frozen, module = "railcontact._native")]
pub struct Profile {
    inner: Inner,
}

#[pymethods]
impl Profile {
    /// A built-in name ("S1002", "UIC60", "60E1") or a file (`.prw`, `.prr`, `.ban`, two-column
    /// text in mm) as the parameters `wheelProfile` / `railProfile` take it, of `kind`, smoothed
    /// with `smoothing` [m]; a file must pass the element's plausibility checks.
    #[staticmethod]
    #[pyo3(signature = (spec, kind, smoothing=0.0))]
    fn load(py: Python<'_>, spec: &str, kind: &str, smoothing: f64) -> PyResult<Self> {
        let kind = kind_of(kind)?;
        let inner = py
            .allow_threads(|| Inner::load(spec, kind, smoothing))
            .map_err(error)?;
        Ok(Self { inner })
    }

    /// A profile through the points (`y`, `z`) [m] in the profile frame (not checked: see
    /// `check`).
    #[staticmethod]
    #[pyo3(signature = (name, kind, y, z, smoothing=0.0))]
    fn from_points(
        name: &str,
        kind: &str,
        y: Vec<f64>,
        z: Vec<f64>,
        smoothing: f64,
    ) -> PyResult<Self> {
        let inner = Inner::from_points(name, kind_of(kind)?, &y, &z, smoothing).map_err(error)?;
        Ok(Self { inner })
    }

    /// The plausibility checks of profile files (units, wheel orientation, coverage of the
    /// running surface, gaps, steps, spikes): raises `RailcontactError` naming the point.
    fn check(&self) -> PyResult<()> {
        self.inner.check_plausibility().map_err(error)
    }

    #[getter]
    fn name(&self) -> String {
        self.inner.name().to_string()
    }

    #[getter]
    fn kind(&self) -> &'static str {
        self.inner.kind().as_str()
    }

    #[getter]
    fn smoothing(&self) -> f64 {
        self.inner.smoothing()
    }

    /// The profile's points [m]: (y ascending, z).
    fn points(&self) -> (Vec<f64>, Vec<f64>) {
        let (y, z) = self.inner.points();
        (y.to_vec(), z.to_vec())
    }

    /// The fitted spline at `y` [m]: z [m], dz/dy, d²z/dy² [1/m] (continued linearly outside the
    /// points).
    fn eval(&self, y: Vec<f64>) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let mut out = (
            Vec::with_capacity(y.len()),
            Vec::with_capacity(y.len()),
            Vec::with_capacity(y.len()),
        );
        for y in y {
            let (z, dz, d2z) = self.inner.eval(y);
            out.0.push(z);
            out.1.push(dz);
            out.2.push(d2z);
        }
        out
    }

    /// The profile worn by `depth` [m] at the lateral positions `y` [m] (ascending; linear in
    /// between, 0 outside): each point moves into the material along the surface normal by
    /// depth/√(1 + z′²), as the wear loop's update does (`docs/theory.md` §10.6). The result
    /// keeps the name (with `name` if given), kind and smoothing; it is not checked.
    #[pyo3(signature = (y, depth, name=None))]
    fn worn(&self, y: Vec<f64>, depth: Vec<f64>, name: Option<&str>) -> PyResult<Self> {
        if y.len() != depth.len() || !y.windows(2).all(|w| w[1] > w[0]) {
            return Err(RailcontactError::new_err(format!(
                "worn: needs as many depths as positions ({} and {}), positions ascending",
                depth.len(),
                y.len()
            )));
        }
        if let Some(d) = depth.iter().find(|d| !d.is_finite()) {
            return Err(RailcontactError::new_err(format!(
                "worn: depth = {d} is not finite"
            )));
        }
        let wheel = self.inner.kind() == ProfileKind::Wheel;
        let (wy, wz) = worn_points(
            self.inner.points(),
            wheel,
            |p| at_bins(&y, &depth, p),
            |p| self.inner.dz(p),
        );
        let inner = Inner::from_points(
            name.unwrap_or(self.inner.name()),
            self.inner.kind(),
            &wy,
            &wz,
            self.inner.smoothing(),
        )
        .map_err(error)?;
        Ok(Self { inner })
    }

    /// Writes the points as a two-column text file in mm (the format the element reads, with
    /// `header` as comment lines), then reads it back as the element does and runs the checks:
    /// raises `RailcontactError` if the file would not be accepted.
    #[pyo3(signature = (path, header=None))]
    fn write(&self, path: &str, header: Option<&str>) -> PyResult<()> {
        let mut text = String::new();
        for line in header.unwrap_or("").lines() {
            text.push_str("# ");
            text.push_str(line);
            text.push('\n');
        }
        text.push_str(&format!(
            "# y [mm], z [mm] in the {} profile frame\n",
            self.inner.kind().as_str()
        ));
        let (y, z) = self.inner.points();
        railcontact_cli::wear::write_profile(Path::new(path), &text, (y.to_vec(), z.to_vec()))
            .map_err(to_py)?;
        Inner::load(path, self.inner.kind(), self.inner.smoothing())
            .and_then(|p| p.check_plausibility())
            .map_err(|e| {
                to_py(Failure::Error(format!(
                    "{path}: the written profile fails the profile checks: {e}"
                )))
            })
    }

    fn __repr__(&self) -> String {
        format!(
            "Profile('{}', {}, {} points, smoothing {} m)",
            self.inner.name(),
            self.inner.kind().as_str(),
            self.inner.points().0.len(),
            self.inner.smoothing()
        )
    }
}
