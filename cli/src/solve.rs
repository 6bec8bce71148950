//! `railcontact solve`: one evaluation of the FMU's model as a JSON document — every output by
//! name (integers as integers), then "strips": per patch in contact its strips across the rolling
//! direction; optionally "grid" (pressure points along each strip) and "traction" (the elements
//! of the tangential solution).
//!
//! The outputs come from the FMU's own model; the strip tables from the same wheelset solver run
//! directly (its patch semi-axes and curvatures are not FMU outputs), checked to reproduce the
//! outputs bit for bit.

use crate::{model, output_integer, output_real, Failure};
use railcontact::fmi::model::Evaluation;
use railcontact::fmi::variables::{Causality, Values, VarType};
use railcontact::geometry::profile::{Profile, ProfileKind};
use railcontact::models::wheel_rail_contact::{self as wrc, generated::var, INFO};
use railcontact::wheelset::strip_side::StripPatch;
use railcontact::wheelset::{PatchResult, Wheelset, WheelsetResult};
use serde_json::{json, Map, Value};

/// Strips per patch in the strip tables of Hertz patches.
pub const STRIPS: usize = 21;
/// Fewest and most pressure-grid points per strip (`--grid`).
pub const GRID_POINTS: std::ops::RangeInclusive<usize> = 2..=1000;

/// What `solve` adds to the outputs and strip tables.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Extras {
    /// Pressure points per strip (`--grid NX`).
    pub grid: Option<usize>,
    /// The tangential solution's elements (`--traction`).
    pub traction: bool,
}

/// Evaluates the model on `values` (updated with the outputs): the JSON document, and the warning
/// of an implausible contact state (if any).
pub fn solve(values: &mut Values, extras: Extras) -> Result<(Value, Option<String>), Failure> {
    let mut model = model(values)?;
    let warning = match model.evaluate(values, 0.0)? {
        Evaluation::Ok => None,
        Evaluation::Warning(m) => Some(m),
    };
    let (wheelset, patches) = wheelset_result(values)?;
    check_same(values, &patches)?;

    let mut doc = outputs(values);
    let tables = strip_tables(&wheelset, &patches);
    let strips = tables
        .iter()
        .map(|(name, table)| {
            (
                name.clone(),
                table.iter().copied().map(Strip::to_json).collect(),
            )
        })
        .collect();
    doc.insert("strips".into(), Value::Object(strips));
    if let Some(nx) = extras.grid {
        let grid = tables
            .iter()
            .map(|(name, table)| (name.clone(), grid(table, nx)))
            .collect();
        doc.insert("grid".into(), Value::Object(grid));
    }
    if extras.traction {
        doc.insert(
            "traction".into(),
            Value::Object(traction(&wheelset, &patches)),
        );
    }
    Ok((Value::Object(doc), warning))
}

/// Every output by name, in the variable table's order.
fn outputs(values: &Values) -> Map<String, Value> {
    INFO.variables
        .iter()
        .filter(|v| v.causality == Causality::Output)
        .map(|info| {
            let value = match info.ty {
                VarType::Real => Value::from(values.reals[info.slot]),
                VarType::Integer => Value::from(values.integers[info.slot]),
                VarType::Boolean => Value::from(values.booleans[info.slot]),
                VarType::String => Value::from(values.strings[info.slot].clone()),
            };
            (info.name.to_string(), value)
        })
        .collect()
}

/// Per patch in contact ("left.p1", …): its strips.
fn strip_tables(wheelset: &Wheelset, patches: &WheelsetResult) -> Vec<(String, Vec<Strip>)> {
    let mut tables = Vec::new();
    for (side, result, right) in [
        ("left", &patches.left, false),
        ("right", &patches.right, true),
    ] {
        for (k, patch) in result
            .patches
            .iter()
            .enumerate()
            .filter(|(_, p)| p.weight > 0.0)
        {
            let table = match wheelset.strip_patch_of_slot(right, k) {
                Some(sp) => patch_strips(sp),
                None => strips(patch),
            };
            tables.push((format!("{side}.p{}", k + 1), table));
        }
    }
    tables
}

/// The pressure at `nx` element centres along each strip of `table` in contact, as [x, s, p].
fn grid(table: &[Strip], nx: usize) -> Value {
    let mut points = Vec::new();
    for strip in table.iter().filter(|s| s.x_lead > s.x_trail) {
        let (centre, half) = (
            0.5 * (strip.x_lead + strip.x_trail),
            0.5 * (strip.x_lead - strip.x_trail),
        );
        for j in 0..nx {
            // Element centres of nx equal elements along the strip.
            let u = (2 * j + 1) as f64 / nx as f64 - 1.0;
            let p = strip.pmax * (1.0 - u * u).max(0.0).sqrt();
            points.push(json!([centre + half * u, strip.s, p]));
        }
    }
    Value::Array(points)
}

/// Per patch with a tangential solution: its elements as [x, s, px, py, slip].
fn traction(wheelset: &Wheelset, patches: &WheelsetResult) -> Map<String, Value> {
    let mut out = Map::new();
    for (side, result, right) in [
        ("left", &patches.left, false),
        ("right", &patches.right, true),
    ] {
        for k in 0..result.patches.len() {
            let Some(field) = wheelset.traction_field(right, k) else {
                continue;
            };
            let elements = field
                .iter()
                .map(|e| json!([e.x, e.s, e.px, e.py, u8::from(e.slipping)]))
                .collect();
            out.insert(format!("{side}.p{}", k + 1), Value::Array(elements));
        }
    }
    out
}

/// The strips of a non-elliptic patch as the model solved them (strips in contact only).
fn patch_strips(p: &StripPatch) -> Vec<Strip> {
    (0..p.geom.n)
        .filter(|&i| p.sol.half_length[i] > 0.0)
        .map(|i| Strip {
            s: p.geom.s[i],
            y_rail: p.points.y_rail[i],
            x_lead: p.geom.x_c[i] + p.sol.half_length[i],
            x_trail: p.geom.x_c[i] - p.sol.half_length[i],
            pmax: p.sol.pmax[i],
            a: p.geom.curv_a[i],
            b: p.geom.curv_b[i],
        })
        .collect()
}

/// The wheelset solved directly with the model's own mapping from values to settings and input
/// (for the patch semi-axes and curvatures, which are not FMU outputs).
fn wheelset_result(values: &Values) -> Result<(Wheelset, WheelsetResult), Failure> {
    let smoothing = values.real(var::profileSmoothing);
    let load = |spec: &str, kind| {
        Profile::load(spec, kind, smoothing).map_err(|e| Failure::Error(e.to_string()))
    };
    let wheel = load(values.string(var::wheelProfile), ProfileKind::Wheel)?;
    let rail = load(values.string(var::railProfile), ProfileKind::Rail)?;
    let mut wheelset = Wheelset::new(&wheel, &rail, wrc::settings(values)?)
        .map_err(|e| Failure::Error(e.to_string()))?;
    let input = wrc::input(
        values,
        values.integer(var::verticalMode) == 2,
        values.integer(var::creepageMode) == 2,
    );
    let mut result = WheelsetResult::default();
    wheelset
        .solve(&input, &mut result)
        .map_err(|e| Failure::Error(format!("internal error: the direct solve failed: {e}")))?;
    Ok((wheelset, result))
}

/// The direct solve must reproduce the FMU outputs bit for bit (same code, same inputs).
fn check_same(values: &Values, result: &WheelsetResult) -> Result<(), Failure> {
    for (side, r) in [("left", &result.left), ("right", &result.right)] {
        let n = output_integer(values, &format!("{side}.nPatches"))?;
        let mut same = usize::try_from(n) == Ok(r.n_patches);
        for (k, p) in r.patches.iter().enumerate() {
            let patch = |q: &str| output_real(values, &format!("{side}.p{}.{q}", k + 1));
            same = same && patch("Fn")? == p.fn_ && patch("width")? == p.width;
        }
        if !same {
            return Err(Failure::Error(format!(
                "internal error: the strip tables' solve differs from the FMU outputs on the \
                 {side} wheel"
            )));
        }
    }
    Ok(())
}

/// One strip of a patch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strip {
    /// Lateral coordinate in the contact plane, towards the field side [m].
    pub s: f64,
    pub y_rail: f64,
    /// Leading and trailing edge [m].
    pub x_lead: f64,
    pub x_trail: f64,
    /// Strip maximum pressure [Pa].
    pub pmax: f64,
    /// Relative curvatures [1/m] (B as the strip geometry gives it, before any floor).
    pub a: f64,
    pub b: f64,
}

impl Strip {
    fn to_json(self) -> Value {
        json!({
            "s": self.s,
            "yRail": self.y_rail,
            "xLead": self.x_lead,
            "xTrail": self.x_trail,
            "pmax": self.pmax,
            "A": self.a,
            "B": self.b,
        })
    }
}

/// The Hertz ellipse of `p` cut into [`STRIPS`] strips of equal width across the rolling
/// direction, sampled at the strip centres.
pub fn strips(p: &PatchResult) -> Vec<Strip> {
    let cos_g = p.contact_angle.cos();
    (0..STRIPS)
        .map(|i| {
            let s = p.b * ((2 * i + 1) as f64 / STRIPS as f64 - 1.0);
            let root = (1.0 - (s / p.b).powi(2)).max(0.0).sqrt();
            Strip {
                s,
                y_rail: p.y_rail + s * cos_g,
                x_lead: p.a * root,
                x_trail: -p.a * root,
                pmax: p.pmax * root,
                a: p.curv_a,
                b: p.curv_b,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_cut_the_ellipse() {
        let p = PatchResult {
            a: 0.006,
            b: 0.004,
            pmax: 1e9,
            y_rail: 0.001,
            contact_angle: 0.3,
            curv_a: 1.2,
            curv_b: 3.4,
            ..PatchResult::default()
        };
        let s = strips(&p);
        assert_eq!(s.len(), STRIPS);
        let mid = s[STRIPS / 2];
        assert!(mid.s.abs() < 1e-15 && (mid.x_lead - 0.006).abs() < 1e-15);
        assert!((mid.pmax - 1e9).abs() < 1e-3 && mid.x_trail == -mid.x_lead);
        for st in &s {
            let r = (st.x_lead / p.a).powi(2) + (st.s / p.b).powi(2);
            assert!((r - 1.0).abs() < 1e-12);
            assert!((st.y_rail - (0.001 + st.s * 0.3f64.cos())).abs() < 1e-15);
            assert_eq!((st.a, st.b), (1.2, 3.4));
        }
        assert!(s[0].s < 0.0 && s[STRIPS - 1].s > 0.0);
    }

    #[test]
    fn grid_points_lie_on_the_strips() {
        let table = [Strip {
            s: 0.001,
            y_rail: 0.0,
            x_lead: 0.004,
            x_trail: -0.002,
            pmax: 1e9,
            a: 1.0,
            b: 1.0,
        }];
        let Value::Array(points) = grid(&table, 4) else {
            panic!("an array");
        };
        assert_eq!(points.len(), 4);
        let x: Vec<f64> = points.iter().map(|p| p[0].as_f64().unwrap()).collect();
        for (x, expected) in x.iter().zip([-0.00125, 0.00025, 0.00175, 0.00325]) {
            assert!((x - expected).abs() < 1e-15, "{x} vs {expected}");
        }
        assert!(points.iter().all(|p| p[1] == 0.001));
    }
}
