//! `railcontact`: the `WheelRailContact` FMU's model on the command line.
//!
//! * `railcontact solve [CASE.json]` — one evaluation, printed as JSON: every output by name, and
//!   per patch in contact a strip table of the patch;
//! * `railcontact sweep [CASE.json] [--from Y0] [--to Y1] [--step DY]` — a text table over the
//!   lateral shift `y`.
//!
//! A case is a JSON object whose keys are the FMU's parameter and input names; values are checked
//! against the generated variable table exactly as `fmi2Set*` checks them. The outputs come from
//! the FMU's own model (`INFO.create`, `initialize`, `evaluate`), so the command and the FMU give
//! identical numbers; the strip tables come from the same wheelset solver run directly (its patch
//! semi-axes and curvatures are not FMU outputs).
//!
//! Exit codes: 0 success, 1 usage / case / profile / value error, 2 step refused (no contact
//! inside the profiles, or a load the normal model cannot carry), 3 implausible contact state
//! (outputs printed, but beyond elastic half-space contact: [`railcontact::wheelset::validity`]).

use railcontact::case_json as json;
#[path = "railcontact/report.rs"]
mod report;

use railcontact::fmi::model::{Evaluation, InstanceContext, Model, ModelError};
use railcontact::fmi::variables::{Causality, Values, VarInfo, VarType};
use railcontact::geometry::profile::{Profile, ProfileKind, BUILTIN_NAMES};
use railcontact::models::wheel_rail_contact::{self as wrc, generated::var, INFO};
use railcontact::wheelset::{PatchResult, Wheelset, WheelsetResult, MAX_PATCHES};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

const USAGE: &str = "\
railcontact - the WheelRailContact FMU's wheel-rail contact model on the command line

Usage:
  railcontact solve [CASE.json] [--grid NX] [--traction]
  railcontact sweep [CASE.json] [--from Y0] [--to Y1] [--step DY]
  railcontact report [CASE.json] [--out DIR] [--reference DIR] [--quick]
  railcontact help | --help | -h

CASE.json is a JSON object whose keys are parameters and inputs of the WheelRailContact FMU
(modelDescription/WheelRailContact.json), in SI units, e.g.
  {\"y\": 0.004, \"Qright\": 90000, \"wheelProfile\": \"worn.prw\", \"mu\": 0.4}
Keys not given keep their start values; unknown keys, wrong types and values outside a variable's
range are errors. Without a file (or with '-' for standard input): the built-in S1002 wheel on
UIC60 rails at the start values. Relative profile paths are looked up next to the case file
first, then in the working directory.

solve   Evaluates the model once (the FMU's own code) and prints a JSON object: every output by
        name (nPatches as integers), and \"strips\": for each patch in contact (\"left.p1\", ...)
        its strips across the rolling direction (Hertz: the ellipse cut into 21 strips;
        normalModel 2-6: the model's own strips in contact), each with
        s [m] (lateral coordinate in the contact plane, towards the field side), yRail [m],
        xLead, xTrail [m] (leading and trailing edge), pmax [Pa] (strip maximum pressure),
        A, B [1/m] (relative curvatures; B as the strip geometry gives it, before any floor).
        --grid NX adds \"grid\": per patch the pressure at NX element centres along each
        strip, as [x, s, p] triples (m, m, Pa).
        --traction adds \"traction\": per patch every element of the tangential solution as
        [x, s, px, py, slip] (m, m, Pa, Pa, 1 slip / 0 adhesion); px along the rolling
        direction, py along the element's lateral axis, forces of the rail on the wheel.
sweep   Evaluates the model over the lateral shift y from Y0 to Y1 in steps of DY (metres;
        default -0.002 to 0.008, step 0.0005; the case's y is ignored) and prints a table per
        wheel: number of patches, then per patch yRail [mm], contact angle [rad], normal force
        Fn [kN], rolling radius [mm], and the wheel's total lateral force Fy [kN]. Shifts where
        the wheel leaves the profiles get a note instead of numbers; implausible states (see
        exit code 3) get their numbers and a warning at the end of the row.
report  Reproduces the seed study's validation: writes SVG and PNG figures (patch outlines,
        pressure per strip, pure-spin traction planar and non-planar, STRIPES over lateral
        shifts, creep curves), report.md and errors.csv into --out DIR (default report/).
        Without CASE.json: the seed's central case (benchmark profiles from the reference's
        ../profiles or tests/data/profiles, else the built-in S1002/UIC60 at 1:40; 78.5 kN,
        E = 210 GPa, nu = 0.28, mu = 0.3, centred). --reference DIR: CONTACT's reference
        directory (default tests/data/reference if it exists; without it no error table).
        --quick draws the creep curves at the reference creepages only. Progress on stderr.

Profile files are checked when loaded (units, flange side, coverage of the running surface,
gaps, steps and spikes the smoothing cannot absorb); a failed check is exit code 1 with the
file, the reason and the fix.

Exit codes:
  0  success
  1  bad arguments, case file, profile file or value (the message names the key or file, the
     value or line, and the reason)
  2  (solve) the step is refused: the pose has no contact inside the profiles, or the normal
     model cannot carry the prescribed load
  3  implausible contact state: the outputs are printed, but a patch's penetration (normal
     approach) exceeds 1 mm, far beyond elastic half-space contact (e.g. a prescribed
     position z that pushes a wheel millimetres into the rail, or a wheel load of
     meganewtons); stderr names the wheel, patch, quantity, value, limit and likely cause
     (solve; sweep if any row is marked)
";

/// Strips per patch in `solve`'s strip tables of Hertz patches.
const STRIPS: usize = 21;
/// Most pressure-grid points per strip (`solve --grid`).
const MAX_GRID: usize = 1000;
/// Most rows a sweep may have.
const MAX_ROWS: usize = 100_000;
/// Exit code of an implausible contact state (outputs printed; [`railcontact::wheelset::validity`]).
const IMPLAUSIBLE: i32 = 3;

/// Why the command failed, with its exit code.
#[derive(Debug)]
enum Failure {
    /// Bad arguments, case, profile or value: exit code 1.
    Error(String),
    /// The step was refused (FMI Discard): the pose has no contact inside the profiles, or the
    /// normal model cannot carry the load: exit code 2.
    Discard(String),
}

impl Failure {
    fn code(&self) -> i32 {
        match self {
            Failure::Error(_) => 1,
            Failure::Discard(_) => 2,
        }
    }
}

impl From<ModelError> for Failure {
    fn from(e: ModelError) -> Self {
        match e {
            ModelError::Error(m) => Failure::Error(m),
            ModelError::Discard(m) => Failure::Discard(m),
        }
    }
}

fn main() {
    let code = match run() {
        Ok(code) => code,
        Err(f) => {
            let (Failure::Error(m) | Failure::Discard(m)) = &f;
            eprintln!("railcontact: {m}");
            f.code()
        }
    };
    std::process::exit(code);
}

fn run() -> Result<i32, Failure> {
    let args = std::env::args_os()
        .skip(1)
        .map(|a| {
            a.into_string()
                .map_err(|a| Failure::Error(format!("argument {a:?} is not valid UTF-8")))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let Some((command, rest)) = args.split_first() else {
        eprint!("{USAGE}");
        return Ok(1);
    };
    if is_help(command) || rest.iter().any(|a| is_help(a)) {
        emit(USAGE)?;
        return Ok(0);
    }
    match command.as_str() {
        "solve" => {
            let traction = rest.iter().any(|a| a == "--traction");
            let rest: Vec<String> = rest
                .iter()
                .filter(|a| *a != "--traction")
                .cloned()
                .collect();
            let a = positional(&rest, &["--grid"])?;
            let grid = match a.options.iter().rev().find(|(k, _)| k == "--grid") {
                None => None,
                Some((_, v)) => Some(
                    v.trim()
                        .parse::<usize>()
                        .ok()
                        .filter(|n| (2..=MAX_GRID).contains(n))
                        .ok_or_else(|| {
                            Failure::Error(format!(
                                "--grid {v}: expected a whole number of points per strip in \
                                 [2, {MAX_GRID}]"
                            ))
                        })?,
                ),
            };
            let (text, warning) = solve(a.case.as_deref(), grid, traction)?;
            emit(&text)?;
            Ok(match warning {
                None => 0,
                Some(m) => {
                    eprintln!("railcontact: warning: {m}");
                    IMPLAUSIBLE
                }
            })
        }
        "sweep" => {
            let a = positional(rest, &["--from", "--to", "--step"])?;
            let option = |name: &str, default: f64| -> Result<f64, Failure> {
                match a.options.iter().rev().find(|(k, _)| k == name) {
                    None => Ok(default),
                    Some((_, v)) => v.trim().parse::<f64>().map_err(|_| {
                        Failure::Error(format!("{name} {v}: expected a number in metres"))
                    }),
                }
            };
            let range = SweepRange {
                from: option("--from", -0.002)?,
                to: option("--to", 0.008)?,
                step: option("--step", 0.0005)?,
            };
            let (table, outcome) = sweep(a.case.as_deref(), range)?;
            emit(&table)?;
            if outcome.warnings > 0 {
                eprintln!(
                    "railcontact: warning: {} of the shifts give implausible contact states \
                     (marked in the table)",
                    outcome.warnings
                );
            }
            Ok(if outcome.errors {
                1
            } else if outcome.warnings > 0 {
                IMPLAUSIBLE
            } else {
                0
            })
        }
        "report" => report::run(rest),
        other => Err(Failure::Error(format!(
            "unknown command '{other}' (commands: solve, sweep, report, help; see railcontact \
             --help)"
        ))),
    }
}

fn is_help(a: &str) -> bool {
    matches!(a, "-h" | "--help" | "help")
}

/// Writes `text` to standard output (an error such as a closed pipe is a failure, not a panic).
fn emit(text: &str) -> Result<(), Failure> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| Failure::Error(format!("cannot write the output: {e}")))
}

/// Arguments after the command: at most one case file, and `--name value` / `--name=value`.
struct Args {
    case: Option<String>,
    options: Vec<(String, String)>,
}

fn positional(rest: &[String], known: &[&str]) -> Result<Args, Failure> {
    let mut args = Args {
        case: None,
        options: Vec::new(),
    };
    let mut it = rest.iter();
    while let Some(a) = it.next() {
        if a.starts_with("--") {
            let (name, inline) = match a.split_once('=') {
                Some((n, v)) => (n, Some(v.to_string())),
                None => (a.as_str(), None),
            };
            if !known.contains(&name) {
                return Err(Failure::Error(format!(
                    "unknown option '{name}' (see railcontact --help)"
                )));
            }
            let value = match inline {
                Some(v) => v,
                None => it
                    .next()
                    .cloned()
                    .ok_or_else(|| Failure::Error(format!("option {name} needs a value")))?,
            };
            args.options.push((name.to_string(), value));
        } else if a.starts_with('-') && a != "-" && a.parse::<f64>().is_err() {
            return Err(Failure::Error(format!(
                "unknown option '{a}' (see railcontact --help)"
            )));
        } else if let Some(first) = &args.case {
            return Err(Failure::Error(format!(
                "more than one case file ('{first}', '{a}')"
            )));
        } else {
            args.case = Some(a.clone());
        }
    }
    Ok(args)
}

// ---------------------------------------------------------------------------------------------
// Cases

/// The FMU's values at their start values, overridden by the case file (if any).
fn load_case(path: Option<&str>) -> Result<Values, Failure> {
    let mut values = Values::from_start(INFO.variables, INFO.counts);
    let Some(path) = path else {
        return Ok(values);
    };
    let (text, source, dir) = if path == "-" {
        let mut text = String::new();
        std::io::Read::read_to_string(&mut std::io::stdin(), &mut text)
            .map_err(|e| Failure::Error(format!("cannot read the case from stdin: {e}")))?;
        (text, "case on stdin".to_string(), None)
    } else {
        let source = format!("case file '{path}'");
        let text = std::fs::read_to_string(path)
            .map_err(|e| Failure::Error(format!("{source}: cannot read the file: {e}")))?;
        (text, source, Path::new(path).parent())
    };
    let doc = json::parse(&text).map_err(|e| Failure::Error(format!("{source}, {e}")))?;
    apply_case(&mut values, &doc, dir).map_err(|m| Failure::Error(format!("{source}: {m}")))?;
    Ok(values)
}

/// Sets the variables a case document names, checked as `fmi2Set*` checks them.
fn apply_case(values: &mut Values, doc: &json::Value, dir: Option<&Path>) -> Result<(), String> {
    let members = doc.as_object().ok_or_else(|| {
        format!(
            "expected a JSON object of parameter and input names, found {}",
            doc.type_name()
        )
    })?;
    for (key, value) in members {
        let info = INFO.variable(key).ok_or_else(|| unknown_key(key, value))?;
        if info.causality == Causality::Output {
            return Err(format!(
                "{} = {value}: '{key}' is an output of WheelRailContact; a case sets parameters \
                 and inputs only",
                json::quote(key)
            ));
        }
        set_value(values, info, value, dir)?;
    }
    Ok(())
}

fn unknown_key(key: &str, value: &json::Value) -> String {
    let names: Vec<&str> = INFO
        .variables
        .iter()
        .filter(|v| v.causality != Causality::Output)
        .map(|v| v.name)
        .collect();
    format!(
        "unknown key {} = {value}: not a parameter or input of WheelRailContact (allowed keys: \
         {})",
        json::quote(key),
        names.join(", ")
    )
}

/// " [unit]" or "".
fn unit_suffix(info: &VarInfo) -> String {
    if info.unit.is_empty() {
        String::new()
    } else {
        format!(" [{}]", info.unit)
    }
}

fn set_value(
    values: &mut Values,
    info: &VarInfo,
    value: &json::Value,
    dir: Option<&Path>,
) -> Result<(), String> {
    let out_of_range = |text: &str| {
        format!(
            "{} = {text} is outside the allowed range {}{}",
            info.name,
            info.allowed,
            unit_suffix(info)
        )
    };
    let wrong_type = |expected: &str| {
        let found = match value {
            json::Value::Number(..) if info.ty == VarType::Integer => {
                "a number that is not an integer"
            }
            other => other.type_name(),
        };
        format!(
            "{} = {value} has the wrong type: expected {expected}{}, found {found}",
            info.name,
            unit_suffix(info),
        )
    };
    match (info.ty, value) {
        (VarType::Real, json::Value::Number(x, text)) => {
            if !info.accepts_real(*x) {
                return Err(out_of_range(text));
            }
            values.reals[info.slot] = *x;
        }
        (VarType::Real, _) => {
            return Err(wrong_type(&format!("a number in {}", info.allowed)));
        }
        (VarType::Integer, json::Value::Number(x, text)) if x.fract() == 0.0 => {
            let k = if x.abs() <= f64::from(i32::MAX) {
                *x as i32
            } else {
                return Err(out_of_range(text));
            };
            if !info.accepts_integer(k) {
                return Err(out_of_range(text));
            }
            values.integers[info.slot] = k;
        }
        (VarType::Integer, _) => return Err(wrong_type(&format!("an {}", info.allowed))),
        (VarType::Boolean, json::Value::Bool(b)) => values.booleans[info.slot] = *b,
        (VarType::Boolean, _) => return Err(wrong_type("true or false")),
        (VarType::String, json::Value::String(s)) => {
            values.strings[info.slot] = resolve_profile(s, dir);
        }
        (VarType::String, _) => {
            return Err(wrong_type(
                "a string (a built-in profile name or a file path)",
            ))
        }
    }
    Ok(())
}

/// A relative profile path that names a file next to the case file becomes that file's path;
/// built-in names and everything else are kept as written.
fn resolve_profile(spec: &str, dir: Option<&Path>) -> String {
    let t = spec.trim();
    let builtin = BUILTIN_NAMES.iter().any(|b| b.eq_ignore_ascii_case(t));
    match dir {
        Some(dir) if !builtin && !t.is_empty() && Path::new(t).is_relative() => {
            let next_to_case = dir.join(t);
            if next_to_case.is_file() {
                next_to_case.to_string_lossy().into_owned()
            } else {
                spec.to_string()
            }
        }
        _ => spec.to_string(),
    }
}

/// The FMU's model, initialized with `values`' parameters (profiles loaded).
fn model(values: &Values) -> Result<Box<dyn Model>, Failure> {
    let mut model = (INFO.create)(&InstanceContext::default());
    model.initialize(values)?;
    Ok(model)
}

// ---------------------------------------------------------------------------------------------
// solve

/// The JSON text, and the warning of an implausible state (if any).
fn solve(
    case: Option<&str>,
    grid: Option<usize>,
    traction: bool,
) -> Result<(String, Option<String>), Failure> {
    let mut values = load_case(case)?;
    let mut model = model(&values)?;
    let warning = match model.evaluate(&mut values, 0.0)? {
        Evaluation::Ok => None,
        Evaluation::Warning(m) => Some(m),
    };
    let (wheelset, patches) = wheelset_result(&values)?;
    check_same(&values, &patches)?;

    let mut out = String::from("{\n");
    for info in INFO
        .variables
        .iter()
        .filter(|v| v.causality == Causality::Output)
    {
        let value = match info.ty {
            VarType::Real => json::number(values.reals[info.slot]),
            VarType::Integer => values.integers[info.slot].to_string(),
            VarType::Boolean => values.booleans[info.slot].to_string(),
            VarType::String => json::quote(&values.strings[info.slot]),
        };
        let _ = writeln!(out, "  {}: {value},", json::quote(info.name));
    }
    out.push_str("  \"strips\": {");
    let mut first = true;
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
    for (name, table) in &tables {
        {
            out.push_str(if first { "\n" } else { ",\n" });
            first = false;
            let _ = write!(out, "    \"{name}\": [");
            for (i, strip) in table.iter().enumerate() {
                let _ = write!(
                    out,
                    "{}\n      {{\"s\": {}, \"yRail\": {}, \"xLead\": {}, \"xTrail\": {}, \
                     \"pmax\": {}, \"A\": {}, \"B\": {}}}",
                    if i == 0 { "" } else { "," },
                    json::number(strip.s),
                    json::number(strip.y_rail),
                    json::number(strip.x_lead),
                    json::number(strip.x_trail),
                    json::number(strip.pmax),
                    json::number(strip.a),
                    json::number(strip.b),
                );
            }
            out.push_str("\n    ]");
        }
    }
    out.push_str(if first { "}" } else { "\n  }" });
    if let Some(nx) = grid {
        out.push_str(",\n  \"grid\": {");
        for (k, (name, table)) in tables.iter().enumerate() {
            let _ = write!(out, "{}\n    \"{name}\": [", if k == 0 { "" } else { "," });
            let mut first_point = true;
            for strip in table.iter().filter(|s| s.x_lead > s.x_trail) {
                let (centre, half) = (
                    0.5 * (strip.x_lead + strip.x_trail),
                    0.5 * (strip.x_lead - strip.x_trail),
                );
                for j in 0..nx {
                    // Element centres of nx equal elements along the strip.
                    let u = (2 * j + 1) as f64 / nx as f64 - 1.0;
                    let p = strip.pmax * (1.0 - u * u).max(0.0).sqrt();
                    let _ = write!(
                        out,
                        "{}\n      [{}, {}, {}]",
                        if first_point { "" } else { "," },
                        json::number(centre + half * u),
                        json::number(strip.s),
                        json::number(p)
                    );
                    first_point = false;
                }
            }
            out.push_str("\n    ]");
        }
        out.push_str(if tables.is_empty() { "}" } else { "\n  }" });
    }
    if traction {
        out.push_str(",\n  \"traction\": {");
        let mut first = true;
        for (side, result, right) in [
            ("left", &patches.left, false),
            ("right", &patches.right, true),
        ] {
            for k in 0..result.patches.len() {
                let Some(field) = wheelset.traction_field(right, k) else {
                    continue;
                };
                let _ = write!(
                    out,
                    "{}\n    \"{side}.p{}\": [",
                    if first { "" } else { "," },
                    k + 1
                );
                first = false;
                for (i, e) in field.iter().enumerate() {
                    let _ = write!(
                        out,
                        "{}\n      [{}, {}, {}, {}, {}]",
                        if i == 0 { "" } else { "," },
                        json::number(e.x),
                        json::number(e.s),
                        json::number(e.px),
                        json::number(e.py),
                        u8::from(e.slipping)
                    );
                }
                out.push_str("\n    ]");
            }
        }
        out.push_str(if first { "}" } else { "\n  }" });
    }
    out.push_str("\n}\n");
    Ok((out, warning))
}

/// The strips of a non-elliptic patch as the model solved them (strips in contact only).
fn patch_strips(p: &railcontact::wheelset::strip_side::StripPatch) -> Vec<Strip> {
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
        let n = output_integer(values, &format!("{side}.nPatches"));
        let same = usize::try_from(n) == Ok(r.n_patches)
            && r.patches.iter().enumerate().all(|(k, p)| {
                output_real(values, &format!("{side}.p{}.Fn", k + 1)) == p.fn_
                    && output_real(values, &format!("{side}.p{}.width", k + 1)) == p.width
            });
        if !same {
            return Err(Failure::Error(format!(
                "internal error: the strip tables' solve differs from the FMU outputs on the \
                 {side} wheel"
            )));
        }
    }
    Ok(())
}

fn output_real(values: &Values, name: &str) -> f64 {
    let info = INFO.variable(name).expect("output of the generated table");
    values.reals[info.slot]
}

fn output_integer(values: &Values, name: &str) -> i32 {
    let info = INFO.variable(name).expect("output of the generated table");
    values.integers[info.slot]
}

/// One strip of a patch.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Strip {
    s: f64,
    y_rail: f64,
    x_lead: f64,
    x_trail: f64,
    pmax: f64,
    a: f64,
    b: f64,
}

/// The Hertz ellipse of `p` cut into [`STRIPS`] strips of equal width across the rolling
/// direction, sampled at the strip centres.
fn strips(p: &PatchResult) -> Vec<Strip> {
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

// ---------------------------------------------------------------------------------------------
// sweep

#[derive(Debug, Clone, Copy)]
struct SweepRange {
    from: f64,
    to: f64,
    step: f64,
}

/// One wheel in one row.
struct SideRow {
    /// Per patch: yRail [m], contact angle [rad], Fn [N], rolling radius [m].
    patches: Vec<[f64; 4]>,
    fy: f64,
}

enum Row {
    /// The outputs, and the warning of an implausible state.
    Values([SideRow; 2], Option<String>),
    Note(String),
}

/// What went wrong in a sweep's rows.
struct SweepOutcome {
    /// A row failed with an error (other than leaving the profiles).
    errors: bool,
    /// Rows with an implausible contact state.
    warnings: usize,
}

/// Returns the table and what went wrong in its rows.
fn sweep(case: Option<&str>, range: SweepRange) -> Result<(String, SweepOutcome), Failure> {
    let y_info = INFO.variable("y").expect("input y");
    for (name, x) in [("--from", range.from), ("--to", range.to)] {
        if !y_info.accepts_real(x) {
            return Err(Failure::Error(format!(
                "{name} {x}: y = {x} is outside the allowed range {}{}",
                y_info.allowed,
                unit_suffix(y_info)
            )));
        }
    }
    if !(range.step.is_finite() && range.step > 0.0) {
        return Err(Failure::Error(format!(
            "--step {}: the step must be a number > 0 [m]",
            range.step
        )));
    }
    let span = (range.to - range.from).abs();
    let intervals = (span / range.step * (1.0 + 1e-9)).floor();
    if intervals >= MAX_ROWS as f64 {
        return Err(Failure::Error(format!(
            "--step {}: {} rows, at most {MAX_ROWS} are allowed",
            range.step,
            intervals + 1.0
        )));
    }
    let direction = if range.to >= range.from { 1.0 } else { -1.0 };

    let mut values = load_case(case)?;
    let mut model = model(&values)?;
    let mut rows = Vec::new();
    let mut errors = false;
    let mut warnings = 0;
    for k in 0..=intervals as usize {
        // Rounded to 1e-12 m so that the printed shifts are exact (no "-0.000").
        let y = (range.from + direction * k as f64 * range.step) * 1e12;
        let y = y.round() / 1e12 + 0.0;
        values.set_real(var::y, y);
        let row = match model.evaluate(&mut values, 0.0) {
            Ok(outcome) => {
                let warning = match outcome {
                    Evaluation::Ok => None,
                    Evaluation::Warning(m) => {
                        warnings += 1;
                        Some(m)
                    }
                };
                Row::Values(
                    ["left", "right"].map(|side| side_row(&values, side)),
                    warning,
                )
            }
            Err(ModelError::Discard(m)) => Row::Note(m),
            Err(ModelError::Error(m)) => {
                errors = true;
                Row::Note(format!("error: {m}"))
            }
        };
        rows.push((y, row));
    }
    Ok((
        table(&values, range, &rows),
        SweepOutcome { errors, warnings },
    ))
}

fn side_row(values: &Values, side: &str) -> SideRow {
    let n = usize::try_from(output_integer(values, &format!("{side}.nPatches")))
        .unwrap_or(0)
        .min(MAX_PATCHES);
    let patches = (1..=n)
        .map(|k| {
            ["yRail", "contactAngle", "Fn", "rollingRadius"]
                .map(|q| output_real(values, &format!("{side}.p{k}.{q}")))
        })
        .collect();
    SideRow {
        patches,
        fy: output_real(values, &format!("{side}.Fy")),
    }
}

fn table(values: &Values, range: SweepRange, rows: &[(f64, Row)]) -> String {
    // Patch column groups per wheel: as many as the sweep needs (at least one).
    let groups: [usize; 2] = [0, 1].map(|s| {
        rows.iter()
            .filter_map(|(_, r)| match r {
                Row::Values(sides, _) => Some(sides[s].patches.len()),
                Row::Note(_) => None,
            })
            .max()
            .unwrap_or(0)
            .max(1)
    });
    let mut header = vec!["y[mm]".to_string()];
    for (s, letter) in ["L", "R"].iter().enumerate() {
        header.push(format!("{letter}.n"));
        for k in 1..=groups[s] {
            for q in ["yRail[mm]", "gamma[rad]", "Fn[kN]", "r[mm]"] {
                header.push(format!("{letter}.p{k}.{q}"));
            }
        }
        header.push(format!("{letter}.Fy[kN]"));
    }
    let widths: Vec<usize> = header.iter().map(|h| h.len().max(9)).collect();

    let mut out = String::new();
    let mode = if values.integer(var::verticalMode) == 2 {
        "vertical position z prescribed".to_string()
    } else {
        format!(
            "Qleft = {} kN, Qright = {} kN",
            values.real(var::Qleft) / 1e3,
            values.real(var::Qright) / 1e3
        )
    };
    let _ = writeln!(
        out,
        "# railcontact sweep: WheelRailContact, wheel {}, rail {}, {mode}; y from {} to {} mm, \
         step {} mm",
        values.string(var::wheelProfile),
        values.string(var::railProfile),
        range.from * 1e3,
        range.to * 1e3,
        range.step * 1e3
    );
    let _ = writeln!(
        out,
        "# y = lateral shift of the wheelset; L/R = left/right wheel: n = number of patches; pK = \
         patch K (field side first): yRail, gamma = contact angle, Fn = normal force, r = rolling \
         radius; Fy = total lateral force of the rail on the wheel ('-': no such patch)"
    );
    let cells: Vec<String> = header
        .iter()
        .zip(&widths)
        .map(|(h, w)| format!("{h:>w$}"))
        .collect();
    let _ = writeln!(out, "{}", cells.join(" "));

    for (y, row) in rows {
        let mut cells = vec![format!("{:.3}", y * 1e3)];
        let warning = match row {
            Row::Note(note) => {
                let _ = writeln!(out, "{:>w$} -- {note}", cells[0], w = widths[0]);
                continue;
            }
            Row::Values(sides, warning) => {
                for (s, side) in sides.iter().enumerate() {
                    cells.push(side.patches.len().to_string());
                    for k in 0..groups[s] {
                        match side.patches.get(k) {
                            Some([y_rail, gamma, fn_, r]) => cells.extend([
                                format!("{:.3}", y_rail * 1e3),
                                format!("{gamma:.5}"),
                                format!("{:.3}", fn_ / 1e3),
                                format!("{:.3}", r * 1e3),
                            ]),
                            None => cells.extend(std::iter::repeat_n("-".to_string(), 4)),
                        }
                    }
                    cells.push(format!("{:.3}", side.fy / 1e3));
                }
                warning.as_deref()
            }
        };
        let cells: Vec<String> = cells
            .iter()
            .zip(&widths)
            .map(|(c, w)| format!("{c:>w$}"))
            .collect();
        match warning {
            None => {
                let _ = writeln!(out, "{}", cells.join(" "));
            }
            Some(m) => {
                let _ = writeln!(out, "{} -- warning: {m}", cells.join(" "));
            }
        }
    }
    out
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
    fn options_and_case_file() {
        let args: Vec<String> = ["c.json", "--from", "-0.001", "--to=0.002"]
            .map(String::from)
            .to_vec();
        let a = positional(&args, &["--from", "--to", "--step"]).unwrap();
        assert_eq!(a.case.as_deref(), Some("c.json"));
        assert_eq!(a.options[0], ("--from".into(), "-0.001".into()));
        assert_eq!(a.options[1], ("--to".into(), "0.002".into()));
        assert!(positional(&["--bogus".to_string()], &[]).is_err());
        assert!(positional(&["a".to_string(), "b".to_string()], &[]).is_err());
    }
}
