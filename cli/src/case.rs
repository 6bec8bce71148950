//! Case files: a JSON object whose keys are parameters and inputs of the `WheelRailContact` FMU
//! (`modelDescription/WheelRailContact.json`), in SI units, e.g.
//! `{"y": 0.004, "Qright": 90000, "wheelProfile": "worn.prw", "mu": 0.4}`.
//!
//! [`Case`] deserializes (serde) against the generated variable table: every key must be a
//! parameter or input (unknown keys, outputs and duplicates are errors), and every value is
//! checked as `fmi2Set*` checks it (type, then range). Errors name the key, the value and the
//! reason; syntax errors the line and column. [`Case::apply`] sets the checked values; a
//! relative profile path that names a file next to the case file becomes that file's path.

use crate::{unit_suffix, Failure};
use railcontact::fmi::variables::{Causality, Values, VarInfo, VarType};
use railcontact::geometry::profile::BUILTIN_NAMES;
use railcontact::models::wheel_rail_contact::INFO;
use serde::de::{self, Deserialize, Deserializer, MapAccess, Visitor};
use serde_json::Value;
use std::fmt;
use std::path::Path;

/// Longest string shown in an error message [characters].
const SHOWN_CHARS: usize = 80;

/// A checked value of one variable.
#[derive(Debug, Clone, PartialEq)]
pub enum Setting {
    Real(f64),
    Integer(i32),
    Boolean(bool),
    /// A profile: a built-in name or a file path, as written.
    Text(String),
}

/// One key of a case: the variable and its checked value.
#[derive(Debug, Clone)]
pub struct Entry {
    pub info: &'static VarInfo,
    pub setting: Setting,
}

/// A case file's settings in file order.
#[derive(Debug, Clone, Default)]
pub struct Case {
    pub entries: Vec<Entry>,
}

impl<'de> Deserialize<'de> for Case {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_map(CaseVisitor)
    }
}

struct CaseVisitor;

impl<'de> Visitor<'de> for CaseVisitor {
    type Value = Case;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a JSON object of parameter and input names")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Case, A::Error> {
        let mut entries: Vec<Entry> = Vec::new();
        while let Some(key) = map.next_key::<String>()? {
            let value: Value = map.next_value()?;
            if entries.iter().any(|e| e.info.name == key) {
                return Err(de::Error::custom(format!("duplicate key {}", quote(&key))));
            }
            entries.push(entry(&key, &value).map_err(de::Error::custom)?);
        }
        Ok(Case { entries })
    }
}

/// Why a case document was rejected: a syntax error with its 1-based line and column, or a key or
/// value error (naming the key, the value and the reason).
#[derive(Debug, Clone, PartialEq)]
pub struct CaseError {
    /// Line and column of a syntax error.
    pub position: Option<(usize, usize)>,
    pub reason: String,
}

impl CaseError {
    /// The message for a document read from `source` (e.g. "case file 'x.json'").
    pub fn message(&self, source: &str) -> String {
        match self.position {
            Some((line, column)) => {
                format!("{source}, line {line}, column {column}: {}", self.reason)
            }
            None => format!("{source}: {}", self.reason),
        }
    }
}

impl fmt::Display for CaseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.position {
            Some((line, column)) => write!(f, "line {line}, column {column}: {}", self.reason),
            None => write!(f, "{}", self.reason),
        }
    }
}

impl From<serde_json::Error> for CaseError {
    fn from(e: serde_json::Error) -> Self {
        let text = e.to_string();
        let suffix = format!(" at line {} column {}", e.line(), e.column());
        let reason = text.strip_suffix(&suffix).unwrap_or(&text).to_string();
        // A key or value error is raised once the value has been read: its position would point
        // past it, so the message names the key instead.
        let position = match e.classify() {
            serde_json::error::Category::Data => None,
            _ => Some((e.line(), e.column())),
        };
        CaseError { position, reason }
    }
}

/// Reads a case document (one JSON object; surrounding whitespace allowed, nothing after it).
pub fn parse(text: &str) -> Result<Case, CaseError> {
    serde_json::from_str(text).map_err(CaseError::from)
}

impl Case {
    /// Sets the case's values in `values`; relative profile paths are resolved against `dir`
    /// (the case file's directory) when a file of that name is there.
    pub fn apply(&self, values: &mut Values, dir: Option<&Path>) {
        for Entry { info, setting } in &self.entries {
            match setting {
                Setting::Real(x) => values.reals[info.slot] = *x,
                Setting::Integer(k) => values.integers[info.slot] = *k,
                Setting::Boolean(b) => values.booleans[info.slot] = *b,
                Setting::Text(s) => values.strings[info.slot] = resolve_profile(s, dir),
            }
        }
    }
}

/// The FMU's values at their start values, overridden by the case file `path` (`-`: standard
/// input), if any.
pub fn load(path: Option<&str>) -> Result<Values, Failure> {
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
    let case = parse(&text).map_err(|e| Failure::Error(e.message(&source)))?;
    case.apply(&mut values, dir);
    Ok(values)
}

/// The checked entry of `key` = `value`.
fn entry(key: &str, value: &Value) -> Result<Entry, String> {
    let info = INFO.variable(key).ok_or_else(|| unknown_key(key, value))?;
    if info.causality == Causality::Output {
        return Err(format!(
            "{} = {}: '{key}' is an output of WheelRailContact; a case sets parameters and \
             inputs only",
            quote(key),
            shown(value)
        ));
    }
    Ok(Entry {
        info,
        setting: setting(info, value)?,
    })
}

fn unknown_key(key: &str, value: &Value) -> String {
    let names: Vec<&str> = INFO
        .variables
        .iter()
        .filter(|v| v.causality != Causality::Output)
        .map(|v| v.name)
        .collect();
    format!(
        "unknown key {} = {}: not a parameter or input of WheelRailContact (allowed keys: {})",
        quote(key),
        shown(value),
        names.join(", ")
    )
}

/// `value` checked against `info`'s type and range.
fn setting(info: &VarInfo, value: &Value) -> Result<Setting, String> {
    let out_of_range = || {
        format!(
            "{} = {} is outside the allowed range {}{}",
            info.name,
            shown(value),
            info.allowed,
            unit_suffix(info)
        )
    };
    let wrong_type = |expected: &str| {
        let found = match value {
            Value::Number(_) if info.ty == VarType::Integer => "a number that is not an integer",
            other => type_name(other),
        };
        format!(
            "{} = {} has the wrong type: expected {expected}{}, found {found}",
            info.name,
            shown(value),
            unit_suffix(info),
        )
    };
    match (info.ty, value) {
        (VarType::Real, Value::Number(n)) => match n.as_f64() {
            Some(x) if info.accepts_real(x) => Ok(Setting::Real(x)),
            _ => Err(out_of_range()),
        },
        (VarType::Real, _) => Err(wrong_type(&format!("a number in {}", info.allowed))),
        (VarType::Integer, Value::Number(n)) => match n.as_f64() {
            Some(x) if x.fract() == 0.0 => integer(x)
                .filter(|&k| info.accepts_integer(k))
                .map(Setting::Integer)
                .ok_or_else(out_of_range),
            _ => Err(wrong_type(&format!("an {}", info.allowed))),
        },
        (VarType::Integer, _) => Err(wrong_type(&format!("an {}", info.allowed))),
        (VarType::Boolean, Value::Bool(b)) => Ok(Setting::Boolean(*b)),
        (VarType::Boolean, _) => Err(wrong_type("true or false")),
        (VarType::String, Value::String(s)) => Ok(Setting::Text(s.clone())),
        (VarType::String, _) => Err(wrong_type(
            "a string (a built-in profile name or a file path)",
        )),
    }
}

/// A whole number `x` as an `i32`, if it is one.
fn integer(x: f64) -> Option<i32> {
    (x.abs() <= f64::from(i32::MAX)).then_some(x as i32)
}

/// The JSON type of `value`, for messages.
fn type_name(value: &Value) -> &'static str {
    match value {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// `value` as it appears in a message: JSON, strings shortened, arrays and objects elided.
fn shown(value: &Value) -> String {
    match value {
        Value::String(s) => {
            let short: String = s.chars().take(SHOWN_CHARS).collect();
            let more = if short.len() < s.len() { "…" } else { "" };
            format!("{}{more}", quote(&short))
        }
        Value::Array(_) => "[…]".to_string(),
        Value::Object(_) => "{…}".to_string(),
        other => other.to_string(),
    }
}

/// `s` as a JSON string literal.
fn quote(s: &str) -> String {
    Value::from(s).to_string()
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

#[cfg(test)]
mod tests {
    use super::*;

    fn reason(text: &str) -> String {
        parse(text).unwrap_err().reason
    }

    #[test]
    fn keys_set_their_variables_in_file_order() {
        let case = parse(
            r#"{"y": 0.004, "nx": 30, "planarPatch": true, "wheelProfile": "S1002", "nu": 2e-1}"#,
        )
        .unwrap();
        let names: Vec<&str> = case.entries.iter().map(|e| e.info.name).collect();
        assert_eq!(names, ["y", "nx", "planarPatch", "wheelProfile", "nu"]);
        let mut values = Values::from_start(INFO.variables, INFO.counts);
        case.apply(&mut values, None);
        let slot = |n: &str| INFO.variable(n).unwrap().slot;
        assert_eq!(values.reals[slot("y")], 0.004);
        assert_eq!(values.reals[slot("nu")], 0.2);
        assert_eq!(values.integers[slot("nx")], 30);
        assert!(values.booleans[slot("planarPatch")]);
        assert_eq!(values.strings[slot("wheelProfile")], "S1002");
        // A whole number written as a decimal is an integer.
        assert_eq!(
            parse(r#"{"nx": 30.0}"#).unwrap().entries[0].setting,
            Setting::Integer(30)
        );
    }

    #[test]
    fn errors_name_key_value_reason_and_position() {
        let e = parse("{\n  \"y\": 0.001,\n  \"gauge\": 1.5\n}").unwrap_err();
        assert_eq!(e.position, None, "{e}");
        let message = e.message("case file 'c.json'");
        assert!(
            message.starts_with("case file 'c.json': unknown key \"gauge\" = 1.5: not a parameter"),
            "{message}"
        );
        for (text, expected) in [
            (
                r#"{"nu": 0.7}"#,
                "nu = 0.7 is outside the allowed range [0, 0.5]",
            ),
            (
                r#"{"nx": 2.5}"#,
                "nx = 2.5 has the wrong type: expected an integer in [1, 1000]",
            ),
            (
                r#"{"nx": 1e12}"#,
                "nx = 1000000000000.0 is outside the allowed range",
            ),
            (r#"{"Qright": [1]}"#, "Qright = […] has the wrong type"),
            (
                r#"{"planarPatch": 1}"#,
                "expected true or false, found a number",
            ),
            (r#"{"left.Fy": 0}"#, "'left.Fy' is an output"),
            (r#"{"y": 0, "y": 1}"#, "duplicate key \"y\""),
            (
                "[1, 2]",
                "expected a JSON object of parameter and input names",
            ),
        ] {
            let r = reason(text);
            assert!(r.contains(expected), "{text}: {r}");
        }
        let long = format!(r#"{{"wheelProfile": 1, "{}": 0}}"#, "k".repeat(200));
        assert!(reason(&long).contains("found a number"));
        let long = format!(r#"{{"y": "{}"}}"#, "é".repeat(200));
        assert!(reason(&long).contains(&format!("\"{}\"…", "é".repeat(80))));
    }

    #[test]
    fn numbers_read_as_the_nearest_f64() {
        // Shortest round-trip texts of pseudo-random reals in y's range: each must read back to
        // the same f64, as `str::parse` reads it.
        let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..20_000 {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let x = ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 0.1;
            let case = parse(&format!("{{\"y\": {x:?}}}")).unwrap();
            assert_eq!(case.entries[0].setting, Setting::Real(x), "{x:?}");
        }
    }

    #[test]
    fn syntax_errors_have_line_and_column() {
        let e = parse("{\n  \"y\": 0.001,\n}").unwrap_err();
        assert_eq!(e.position, Some((3, 1)), "{e}");
        assert_eq!(
            e.message("case file 'c.json'"),
            "case file 'c.json', line 3, column 1: trailing comma"
        );
        for text in [
            "{\"y\": 0} x",
            "{\"y\": 1e999}",
            "{\"y\": 0",
            "{\"y\": nan}",
        ] {
            let e = parse(text).unwrap_err();
            assert_eq!(e.position.map(|p| p.0), Some(1), "{text}: {e}");
        }
    }
}
