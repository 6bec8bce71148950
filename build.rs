//! Generates, for every `modelDescription/<Model>.json` (the single source of truth of an FMU's
//! variables), both
//! * `$OUT_DIR/<Model>.xml`: the FMI 2.0 `modelDescription.xml`, and
//! * `$OUT_DIR/<Model>_vars.rs`: the Rust table of value references, start values and ranges,
//!
//! with the same GUID in both: a hash of the XML body, the capabilities that vary between models
//! and the crate version (so a change of the variables, of a capability or of the release changes
//! the GUID, and hosts that cache unpacked FMUs by GUID see a new one).
//!
//! Value references are the 0-based positions in the JSON list; each type (Real, Integer, Boolean,
//! String) also gets a dense `slot` used as the index into the instance's value arrays.

use serde::Deserialize;
use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::Path;

#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename_all = "camelCase")]
struct ModelJson {
    model_name: String,
    model_identifier: String,
    description: String,
    default_experiment: DefaultExperiment,
    /// Whether the model computes `fmi2GetDirectionalDerivative` (false if absent).
    #[serde(default)]
    provides_directional_derivative: bool,
    /// Variables, or groups `{"foreach": [KEY, [VALUES…]], "variables": [...]}` repeated once per
    /// value with `{KEY}` replaced in names and descriptions (nested groups allowed).
    variables: Vec<serde_json::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename_all = "camelCase")]
struct DefaultExperiment {
    start_time: f64,
    stop_time: f64,
    step_size: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename_all = "camelCase")]
struct VariableJson {
    name: String,
    #[serde(rename = "type")]
    ty: String,
    causality: String,
    variability: String,
    start: Option<serde_json::Value>,
    unit: Option<String>,
    min: Option<f64>,
    max: Option<f64>,
    #[serde(default)]
    min_exclusive: bool,
    description: String,
}

/// A model description with its variable groups expanded.
struct Model {
    model_name: String,
    model_identifier: String,
    description: String,
    default_experiment: DefaultExperiment,
    provides_directional_derivative: bool,
    variables: Vec<VariableJson>,
}

/// Expands `foreach` groups depth-first, in the order written.
fn expand(
    entries: &[serde_json::Value],
    subs: &mut Vec<(String, String)>,
    out: &mut Vec<VariableJson>,
) -> Result<(), String> {
    let substitute = |text: &str, subs: &[(String, String)]| {
        subs.iter().fold(text.to_string(), |t, (k, v)| {
            t.replace(&format!("{{{k}}}"), v)
        })
    };
    for entry in entries {
        if let Some(spec) = entry.get("foreach") {
            let key = spec
                .get(0)
                .and_then(|k| k.as_str())
                .ok_or("foreach needs [KEY, [VALUES]]")?;
            let values = spec
                .get(1)
                .and_then(|v| v.as_array())
                .ok_or("foreach needs [KEY, [VALUES]]")?;
            let inner = entry
                .get("variables")
                .and_then(|v| v.as_array())
                .ok_or("foreach group needs \"variables\"")?;
            for value in values {
                let value = value.as_str().ok_or("foreach values must be strings")?;
                subs.push((key.to_string(), value.to_string()));
                expand(inner, subs, out)?;
                subs.pop();
            }
        } else {
            let mut v: VariableJson =
                serde_json::from_value(entry.clone()).map_err(|e| format!("{entry}: {e}"))?;
            v.name = substitute(&v.name, subs);
            v.description = substitute(&v.description, subs);
            if v.name.contains('{') {
                return Err(format!("unexpanded placeholder in {}", v.name));
            }
            out.push(v);
        }
    }
    Ok(())
}

/// SI base-unit exponents (kg, m, s, rad) of every unit a model may use.
const UNITS: &[(&str, [i32; 4])] = &[
    ("m", [0, 1, 0, 0]),
    ("m2", [0, 2, 0, 0]),
    ("1/m", [0, -1, 0, 0]),
    ("N", [1, 1, -2, 0]),
    ("N.m", [1, 2, -2, 0]),
    ("Pa", [1, -1, -2, 0]),
    ("W", [1, 2, -3, 0]),
    ("m/s", [0, 1, -1, 0]),
    ("rad", [0, 0, 0, 1]),
    ("rad/s", [0, 0, -1, 1]),
    ("s", [0, 0, 1, 0]),
    ("kg", [1, 0, 0, 0]),
    ("kg/m", [1, -1, 0, 0]),
];

const LOG_CATEGORIES: &[(&str, &str)] = &[
    (
        "logStatusError",
        "Errors: rejected values, failed steps, illegal calls",
    ),
    ("logStatusWarning", "Warnings"),
    ("logAll", "Debug information (only when logging is on)"),
];

fn main() {
    println!("cargo:rerun-if-changed=modelDescription");
    println!("cargo:rerun-if-changed=build.rs");
    // Keep the library mapped after dlclose: Rust thread-local destructors registered by the
    // cdylib must not outlive its code. `-z nodelete` is an ELF linker flag (GNU ld, lld, zig);
    // Apple's and Microsoft's linkers do not know it, so only ELF targets get it.
    let target_os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    if matches!(
        target_os.as_str(),
        "linux" | "android" | "freebsd" | "netbsd" | "openbsd" | "dragonfly" | "illumos"
    ) {
        println!("cargo:rustc-cdylib-link-arg=-Wl,-z,nodelete");
    }

    let out_dir = std::env::var("OUT_DIR").expect("OUT_DIR");
    let version = std::env::var("CARGO_PKG_VERSION").expect("CARGO_PKG_VERSION");
    let mut paths: Vec<_> = std::fs::read_dir("modelDescription")
        .expect("modelDescription/ must exist")
        .map(|e| e.expect("readable entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    paths.sort();
    for path in paths {
        let text = std::fs::read_to_string(&path).expect("readable JSON");
        let json: ModelJson =
            serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut variables = Vec::new();
        expand(&json.variables, &mut Vec::new(), &mut variables)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let model = Model {
            model_name: json.model_name,
            model_identifier: json.model_identifier,
            description: json.description,
            default_experiment: json.default_experiment,
            provides_directional_derivative: json.provides_directional_derivative,
            variables,
        };
        check_model(&model, &path);
        let body = xml_body(&model);
        // The capabilities are part of what a host caches by GUID.
        let capabilities = format!(
            "providesDirectionalDerivative={}\n",
            model.provides_directional_derivative
        );
        let guid = guid_of(&(capabilities + &body), &version);
        let xml = xml_document(&model, &guid, &version, &body);
        let id = &model.model_identifier;
        std::fs::write(Path::new(&out_dir).join(format!("{id}.xml")), &xml).expect("write xml");
        std::fs::write(
            Path::new(&out_dir).join(format!("{id}_vars.rs")),
            rust_table(&model, &guid),
        )
        .expect("write rs");
    }
}

fn check_model(model: &Model, path: &Path) {
    let fail = |msg: String| panic!("{}: {msg}", path.display());
    let id = &model.model_identifier;
    if id.is_empty()
        || !id.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        || id.starts_with(|c: char| c.is_ascii_digit())
    {
        fail(format!("modelIdentifier '{id}' is not a C identifier"));
    }
    let mut names = BTreeSet::new();
    let mut consts = BTreeSet::new();
    for v in &model.variables {
        if !names.insert(v.name.clone()) {
            fail(format!("duplicate variable name '{}'", v.name));
        }
        if !consts.insert(const_name(&v.name)) {
            fail(format!(
                "variable '{}' collides with another constant name",
                v.name
            ));
        }
        if !matches!(v.ty.as_str(), "Real" | "Integer" | "Boolean" | "String") {
            fail(format!("{}: unknown type {}", v.name, v.ty));
        }
        let ok = matches!(
            (v.causality.as_str(), v.variability.as_str()),
            ("parameter", "fixed" | "tunable")
                | ("input", "continuous" | "discrete")
                | ("output", "continuous" | "discrete")
        );
        if !ok {
            fail(format!("{}: unsupported causality/variability", v.name));
        }
        if v.ty != "Real" && v.variability == "continuous" {
            fail(format!("{}: only Real variables may be continuous", v.name));
        }
        let needs_start = v.causality != "output";
        if needs_start != v.start.is_some() {
            fail(format!(
                "{}: parameters and inputs need a start value, outputs have none",
                v.name
            ));
        }
        if let Some(u) = &v.unit {
            if !UNITS.iter().any(|(n, _)| n == u) {
                fail(format!(
                    "{}: unit '{u}' is not declared in build.rs UNITS",
                    v.name
                ));
            }
        }
        if let (Some(lo), Some(hi)) = (v.min, v.max) {
            if lo > hi {
                fail(format!("{}: min > max", v.name));
            }
        }
    }
}

/// `left.p1.Fn` → `left_p1_Fn`: the variable's own spelling, so `a` and `A` stay distinct.
fn const_name(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect()
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn start_text(v: &VariableJson) -> Option<String> {
    let s = v.start.as_ref()?;
    Some(match v.ty.as_str() {
        "Real" => format_real(s.as_f64().expect("Real start must be a number")),
        "Integer" => s.as_i64().expect("Integer start").to_string(),
        "Boolean" => s.as_bool().expect("Boolean start").to_string(),
        _ => s.as_str().expect("String start").to_string(),
    })
}

/// Shortest round-trip decimal text of an f64, valid as xs:double and as a Rust literal.
fn format_real(x: f64) -> String {
    let s = format!("{x:e}");
    s.replace("e0", "").replace('e', "E")
}

fn xml_body(model: &Model) -> String {
    let mut x = String::new();
    x.push_str("  <UnitDefinitions>\n");
    let used: BTreeSet<&str> = model
        .variables
        .iter()
        .filter_map(|v| v.unit.as_deref())
        .collect();
    for (name, [kg, m, s, rad]) in UNITS.iter().filter(|(n, _)| used.contains(n)) {
        let mut attrs = String::new();
        for (key, e) in [("kg", kg), ("m", m), ("s", s), ("rad", rad)] {
            if *e != 0 {
                write!(attrs, " {key}=\"{e}\"").unwrap();
            }
        }
        writeln!(
            x,
            "    <Unit name=\"{}\"><BaseUnit{attrs}/></Unit>",
            xml_escape(name)
        )
        .unwrap();
    }
    x.push_str("  </UnitDefinitions>\n  <LogCategories>\n");
    for (name, desc) in LOG_CATEGORIES {
        writeln!(x, "    <Category name=\"{name}\" description=\"{desc}\"/>").unwrap();
    }
    x.push_str("  </LogCategories>\n");
    let de = &model.default_experiment;
    writeln!(
        x,
        "  <DefaultExperiment startTime=\"{}\" stopTime=\"{}\" stepSize=\"{}\"/>",
        format_real(de.start_time),
        format_real(de.stop_time),
        format_real(de.step_size)
    )
    .unwrap();
    x.push_str("  <ModelVariables>\n");
    for (vr, v) in model.variables.iter().enumerate() {
        let initial = match v.causality.as_str() {
            "parameter" => " initial=\"exact\"",
            "output" => " initial=\"calculated\"",
            _ => "",
        };
        writeln!(
            x,
            "    <!-- index {} -->\n    <ScalarVariable name=\"{}\" valueReference=\"{vr}\" description=\"{}\" causality=\"{}\" variability=\"{}\"{initial}>",
            vr + 1,
            xml_escape(&v.name),
            xml_escape(&v.description),
            v.causality,
            v.variability
        )
        .unwrap();
        let mut attrs = String::new();
        if let Some(s) = start_text(v) {
            write!(attrs, " start=\"{}\"", xml_escape(&s)).unwrap();
        }
        if let Some(u) = &v.unit {
            write!(attrs, " unit=\"{}\"", xml_escape(u)).unwrap();
        }
        for (attr, bound) in [("min", v.min), ("max", v.max)] {
            if let Some(bound) = bound {
                let t = if v.ty == "Integer" {
                    format!("{}", bound as i64)
                } else {
                    format_real(bound)
                };
                write!(attrs, " {attr}=\"{t}\"").unwrap();
            }
        }
        writeln!(x, "      <{}{attrs}/>\n    </ScalarVariable>", v.ty).unwrap();
    }
    x.push_str("  </ModelVariables>\n  <ModelStructure>\n");
    let outputs: Vec<usize> = model
        .variables
        .iter()
        .enumerate()
        .filter(|(_, v)| v.causality == "output")
        .map(|(i, _)| i + 1)
        .collect();
    if !outputs.is_empty() {
        x.push_str("    <Outputs>\n");
        for i in &outputs {
            writeln!(x, "      <Unknown index=\"{i}\"/>").unwrap();
        }
        x.push_str("    </Outputs>\n    <InitialUnknowns>\n");
        for i in &outputs {
            writeln!(x, "      <Unknown index=\"{i}\"/>").unwrap();
        }
        x.push_str("    </InitialUnknowns>\n");
    }
    x.push_str("  </ModelStructure>\n");
    x
}

fn xml_document(model: &Model, guid: &str, version: &str, body: &str) -> String {
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
<fmiModelDescription fmiVersion=\"2.0\" modelName=\"{name}\" guid=\"{guid}\" description=\"{desc}\" \
version=\"{version}\" generationTool=\"railcontact {version} build.rs\" \
variableNamingConvention=\"structured\" numberOfEventIndicators=\"0\">\n\
  <CoSimulation modelIdentifier=\"{id}\" needsExecutionTool=\"false\" \
canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"false\" \
maxOutputDerivativeOrder=\"0\" canRunAsynchronuously=\"false\" \
canBeInstantiatedOnlyOncePerProcess=\"false\" canNotUseMemoryManagementFunctions=\"true\" \
canGetAndSetFMUstate=\"true\" canSerializeFMUstate=\"true\" \
providesDirectionalDerivative=\"{derivatives}\"/>\n{body}</fmiModelDescription>\n",
        name = xml_escape(&model.model_name),
        derivatives = model.provides_directional_derivative,
        desc = xml_escape(&model.description),
        id = model.model_identifier,
    )
}

/// FNV-1a over the bytes with the given offset basis (64-bit).
fn fnv1a(bytes: &[u8], basis: u64) -> u64 {
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    bytes
        .iter()
        .fold(basis, |h, &b| (h ^ u64::from(b)).wrapping_mul(PRIME))
}

/// A 128-bit GUID in registry format from two FNV-1a hashes of the XML body and the version.
fn guid_of(body: &str, version: &str) -> String {
    let input = format!("{version}\n{body}");
    let h1 = fnv1a(input.as_bytes(), 0xcbf2_9ce4_8422_2325);
    let h2 = fnv1a(input.as_bytes(), 0x6c62_272e_07bb_0142);
    format!(
        "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
        h1 >> 32,
        (h1 >> 16) & 0xffff,
        h1 & 0xffff,
        h2 >> 48,
        h2 & 0xffff_ffff_ffff
    )
}

fn rust_table(model: &Model, guid: &str) -> String {
    let mut r = String::new();
    let p = "crate::fmi::variables";
    writeln!(
        r,
        "// Generated by build.rs from modelDescription/{}.json. Do not edit.",
        model.model_identifier
    )
    .unwrap();
    writeln!(
        r,
        "pub const MODEL_IDENTIFIER: &str = {:?};",
        model.model_identifier
    )
    .unwrap();
    writeln!(r, "pub const GUID: &str = {guid:?};").unwrap();
    writeln!(
        r,
        "pub const PROVIDES_DIRECTIONAL_DERIVATIVE: bool = {};",
        model.provides_directional_derivative
    )
    .unwrap();
    writeln!(
        r,
        "pub const MODEL_DESCRIPTION_XML: &str = include_str!(concat!(env!(\"OUT_DIR\"), \"/{}.xml\"));",
        model.model_identifier
    )
    .unwrap();
    let de = &model.default_experiment;
    writeln!(
        r,
        "pub const DEFAULT_EXPERIMENT: {p}::DefaultExperiment = {p}::DefaultExperiment {{ start_time: {}, stop_time: {}, step_size: {} }};",
        format_real_rs(de.start_time),
        format_real_rs(de.stop_time),
        format_real_rs(de.step_size)
    )
    .unwrap();
    let mut counts = [0usize; 4];
    let mut entries = String::new();
    let mut handles = String::new();
    for (vr, v) in model.variables.iter().enumerate() {
        let k = ["Real", "Integer", "Boolean", "String"]
            .iter()
            .position(|t| *t == v.ty)
            .expect("checked type");
        let slot = counts[k];
        counts[k] += 1;
        let handle = ["RealVar", "IntegerVar", "BooleanVar", "StringVar"][k];
        writeln!(
            handles,
            "    /// `{}`: {}\n    pub const {}: {p}::{handle} = {p}::{handle}({slot});",
            v.name,
            v.description,
            const_name(&v.name)
        )
        .unwrap();
        let start = match (&v.start, v.ty.as_str()) {
            (None, _) => format!("{p}::Start::None"),
            (Some(s), "Real") => {
                format!("{p}::Start::Real({})", format_real_rs(s.as_f64().unwrap()))
            }
            (Some(s), "Integer") => format!("{p}::Start::Integer({})", s.as_i64().unwrap()),
            (Some(s), "Boolean") => format!("{p}::Start::Boolean({})", s.as_bool().unwrap()),
            (Some(s), _) => format!("{p}::Start::String({:?})", s.as_str().unwrap()),
        };
        let opt = |x: Option<f64>| match x {
            Some(x) => format!("Some({})", format_real_rs(x)),
            None => "None".into(),
        };
        let causality = match v.causality.as_str() {
            "parameter" => "Parameter",
            "input" => "Input",
            _ => "Output",
        };
        let variability = match v.variability.as_str() {
            "fixed" => "Fixed",
            "tunable" => "Tunable",
            "discrete" => "Discrete",
            _ => "Continuous",
        };
        writeln!(
            entries,
            "    {p}::VarInfo {{ name: {:?}, vr: {vr}, ty: {p}::VarType::{}, slot: {slot}, causality: {p}::Causality::{causality}, variability: {p}::Variability::{variability}, start: {start}, min: {}, max: {}, min_exclusive: {}, allowed: {:?}, unit: {:?}, description: {:?} }},",
            v.name,
            v.ty,
            opt(v.min),
            opt(v.max),
            v.min_exclusive,
            allowed_text(v),
            v.unit.as_deref().unwrap_or(""),
            v.description
        )
        .unwrap();
    }
    writeln!(
        r,
        "pub static VARIABLES: [{p}::VarInfo; {}] = [\n{entries}];",
        model.variables.len()
    )
    .unwrap();
    writeln!(
        r,
        "pub const COUNTS: {p}::Counts = {p}::Counts {{ real: {}, integer: {}, boolean: {}, string: {} }};",
        counts[0], counts[1], counts[2], counts[3]
    )
    .unwrap();
    writeln!(
        r,
        "/// Typed handles of every variable, spelled like the variable (`.` becomes `_`).\n#[allow(non_upper_case_globals)]\npub mod var {{\n{handles}}}"
    )
    .unwrap();
    r
}

fn format_real_rs(x: f64) -> String {
    let s = format!("{x:e}");
    // `1e0` is a valid Rust float literal only with a decimal point or exponent: keep the `e`.
    if s.contains('e') {
        s
    } else {
        format!("{s}.0")
    }
}

/// The allowed range as shown in error messages, e.g. `> 0`, `[0, 0.5]`, `{1, 2}`.
fn allowed_text(v: &VariableJson) -> String {
    let num = |x: f64| {
        if v.ty == "Integer" {
            format!("{}", x as i64)
        } else {
            format!("{x}")
        }
    };
    match (v.min, v.max) {
        (Some(lo), Some(hi)) if v.ty == "Integer" => {
            format!("integer in [{}, {}]", num(lo), num(hi))
        }
        (Some(lo), Some(hi)) if v.min_exclusive => format!("({}, {}]", num(lo), num(hi)),
        (Some(lo), Some(hi)) => format!("[{}, {}]", num(lo), num(hi)),
        (Some(lo), None) if v.min_exclusive => format!("> {} (finite)", num(lo)),
        (Some(lo), None) => format!(">= {} (finite)", num(lo)),
        (None, Some(hi)) => format!("<= {} (finite)", num(hi)),
        (None, None) if v.ty == "Real" => "finite".to_string(),
        (None, None) => "any".to_string(),
    }
}
