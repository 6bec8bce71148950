//! `railcontact conicity`: the equivalent conicity (EN 15302) of the case's wheel and rail
//! profiles on its track ([`railcontact::wheelset::conicity`]): the rolling-radius difference
//! Δr(y) and λ(A) by harmonic linearisation and by Klingel integration, as JSON and CSV.
//!
//! The case is read as `solve` reads it; the profiles (`wheelProfile`, `railProfile`,
//! `profileSmoothing`), `railInclination`, `trackGauge`, `flangeBackDistance`, `wheelRadius`
//! and `scanStep` are used, the rest ignored.

use crate::Failure;
use railcontact::fmi::variables::Values;
use railcontact::models::wheel_rail_contact::{generated::var, profiles, settings};
use railcontact::wheelset::conicity::{Conicity, RollingRadiusDifference, ShiftGrid};
use railcontact::wheelset::Wheelset;
use serde_json::{json, Map, Value};
use std::fmt::Write as _;

/// Most amplitudes one run may ask for.
pub const MAX_AMPLITUDES: usize = 1000;

/// What to compute.
#[derive(Debug, Clone, PartialEq)]
pub struct ConicityOptions {
    /// Amplitudes of the λ(A) table [m], each in (0, 0.02].
    pub amplitudes: Vec<f64>,
    /// Step of the Δr table [m].
    pub step: f64,
    /// Whether the wheelset rolls to rest on both rails.
    pub roll: bool,
    /// The loaded element's rolling radii under this load per wheel [N]
    /// ([`RollingRadiusDifference::loaded`]); `None`: the rigid contact's (EN 15302).
    pub load: Option<f64>,
}

/// The result of a run.
#[derive(Debug, Clone)]
pub struct ConicityRun {
    pub delta_r: RollingRadiusDifference,
    /// The load of the loaded element's Δr [N] (`None`: rigid).
    pub load: Option<f64>,
    pub table: Vec<Conicity>,
    /// λ(A) on a fine amplitude grid (0.25 mm to the largest amplitude, 0.05 mm apart) for the
    /// figure.
    pub curve: Vec<Conicity>,
}

/// Margin of the Δr table beyond the largest amplitude [m] (an asymmetric Δr swings the Klingel
/// motion beyond −A).
const TABLE_MARGIN: f64 = 0.001;
/// Largest amplitude accepted [m] (beyond, the wheel climbs the flange).
const MAX_AMPLITUDE: f64 = 0.02;
/// Spacing and start of the figure's amplitude grid [m].
const CURVE_STEP: f64 = 5e-5;
const CURVE_START: f64 = 2.5e-4;

/// Computes Δr and λ(A) for the case `values`.
pub fn conicity(values: &Values, options: &ConicityOptions) -> Result<ConicityRun, Failure> {
    if options.amplitudes.is_empty() || options.amplitudes.len() > MAX_AMPLITUDES {
        return Err(Failure::Error(format!(
            "--amplitudes: {} amplitudes given, 1 to {MAX_AMPLITUDES} are allowed",
            options.amplitudes.len()
        )));
    }
    for &a in &options.amplitudes {
        if !(a.is_finite() && a > 0.0 && a <= MAX_AMPLITUDE) {
            return Err(Failure::Error(format!(
                "--amplitudes: amplitude = {a} is outside the allowed range (0, {MAX_AMPLITUDE}] \
                 [m]"
            )));
        }
    }
    let largest = options.amplitudes.iter().copied().fold(0.0, f64::max);
    let settings = settings(values)?;
    let (wheel, rail) = profiles(values, None)?;
    let grid = ShiftGrid {
        y_max: largest + TABLE_MARGIN,
        y_step: options.step,
        roll: options.roll,
    };
    let delta_r = match options.load {
        None => RollingRadiusDifference::compute(
            &wheel,
            &rail,
            &settings.setup,
            values.real(var::scanStep),
            grid,
        ),
        Some(load) => {
            if !(load.is_finite() && load > 0.0) {
                return Err(Failure::Error(format!(
                    "--load: load = {load} is outside the allowed range (0, inf) [N]"
                )));
            }
            let mut wheelset = Wheelset::new(&wheel, &rail, settings)
                .map_err(|e| Failure::Error(e.to_string()))?;
            RollingRadiusDifference::loaded(&mut wheelset, load, grid)
        }
    }
    .map_err(|e| Failure::Error(e.to_string()))?;
    let at = |a: f64| {
        delta_r
            .conicity(a)
            .map_err(|e| Failure::Error(e.to_string()))
    };
    let table = options
        .amplitudes
        .iter()
        .map(|&a| at(a))
        .collect::<Result<_, _>>()?;
    let n = ((largest - CURVE_START) / CURVE_STEP).floor().max(0.0) as usize;
    let curve = (0..=n)
        .map(|k| at(CURVE_START + CURVE_STEP * k as f64))
        .collect::<Result<_, _>>()?;
    Ok(ConicityRun {
        delta_r,
        load: options.load,
        table,
        curve,
    })
}

/// A number, or JSON null when absent.
fn number(x: Option<f64>) -> Value {
    x.map_or(Value::Null, Value::from)
}

/// The run as a JSON document: the set-up, "conicity" (one object per amplitude) and "deltaR"
/// (one object per shift). SI units: m, rad.
pub fn to_json(values: &Values, run: &ConicityRun) -> Value {
    let d = &run.delta_r;
    let mut doc = Map::new();
    doc.insert(
        "wheelProfile".into(),
        Value::from(values.string(var::wheelProfile)),
    );
    doc.insert(
        "railProfile".into(),
        Value::from(values.string(var::railProfile)),
    );
    for (name, v) in [
        ("railInclination", var::railInclination),
        ("trackGauge", var::trackGauge),
        ("flangeBackDistance", var::flangeBackDistance),
        ("wheelRadius", var::wheelRadius),
    ] {
        doc.insert(name.into(), Value::from(values.real(v)));
    }
    doc.insert("roll".into(), Value::from(d.grid().roll));
    doc.insert("load".into(), number(run.load));
    doc.insert("r0".into(), Value::from(d.r0()));
    doc.insert("e0".into(), Value::from(d.e0()));
    let table: Vec<Value> = run
        .table
        .iter()
        .map(|c| {
            json!({
                "amplitude": c.amplitude,
                "harmonic": c.harmonic,
                "klingel": number(c.klingel),
                "wavelength": number(c.wavelength),
            })
        })
        .collect();
    doc.insert("conicity".into(), Value::from(table));
    let rows: Vec<Value> = d
        .points()
        .iter()
        .map(|p| {
            json!({
                "y": p.y,
                "deltaR": p.delta_r,
                "roll": p.roll,
                "rRight": p.right.rolling_radius,
                "rLeft": p.left.rolling_radius,
                "yRailRight": p.right.y_rail,
                "yRailLeft": p.left.y_rail,
                "yWheelRight": p.right.y_wheel,
                "yWheelLeft": p.left.y_wheel,
                "contactAngleRight": p.right.contact_angle,
                "contactAngleLeft": p.left.contact_angle,
            })
        })
        .collect();
    doc.insert("deltaR".into(), Value::from(rows));
    Value::Object(doc)
}

/// "" for an absent value, else the number in its shortest round-trip form.
fn cell(x: Option<f64>) -> String {
    x.map_or_else(String::new, |v| format!("{v}"))
}

/// λ(A) as CSV: amplitude_m, harmonic, klingel, wavelength_m (empty where undefined).
pub fn conicity_csv(run: &ConicityRun) -> String {
    let mut out = String::from("amplitude_m,harmonic,klingel,wavelength_m\n");
    for c in &run.table {
        let _ = writeln!(
            out,
            "{},{},{},{}",
            c.amplitude,
            c.harmonic,
            cell(c.klingel),
            cell(c.wavelength)
        );
    }
    out
}

/// Δr(y) as CSV: y_m, delta_r_m, roll_rad, r_right_m, r_left_m, y_rail_right_m, y_rail_left_m,
/// contact_angle_right_rad, contact_angle_left_rad.
pub fn delta_r_csv(run: &ConicityRun) -> String {
    let mut out = String::from(
        "y_m,delta_r_m,roll_rad,r_right_m,r_left_m,y_rail_right_m,y_rail_left_m,\
         contact_angle_right_rad,contact_angle_left_rad\n",
    );
    for p in run.delta_r.points() {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{},{}",
            p.y,
            p.delta_r,
            p.roll,
            p.right.rolling_radius,
            p.left.rolling_radius,
            p.right.y_rail,
            p.left.y_rail,
            p.right.contact_angle,
            p.left.contact_angle
        );
    }
    out
}
