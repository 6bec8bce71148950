//! The `railcontact` command, run as a process: `solve` (JSON with every WheelRailContact output
//! and strip tables; identical to the FMU's model run in-process), case-file errors and exit
//! codes, `sweep`, and the help and usage errors.

// The root crate's shared test set-up (the vendored data of `tests/data`).
#[allow(dead_code)]
#[path = "../../tests/common/mod.rs"]
mod common;

use railcontact::fmi::model::InstanceContext;
use railcontact::fmi::variables::{Causality, Values, VarType};
use railcontact::models::wheel_rail_contact::INFO;
use serde_json::{Map, Value};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_railcontact"))
        .args(args)
        .output()
        .expect("railcontact runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).expect("UTF-8 output")
}

fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).expect("UTF-8 messages")
}

/// Asserts that `text` holds every one of `parts`.
fn assert_mentions<S: AsRef<str>>(text: &str, parts: &[S]) {
    for part in parts.iter().map(AsRef::as_ref) {
        assert!(text.contains(part), "{part:?} in {text}");
    }
}

/// Runs `solve` on `case`, asserts its exit code; returns the output and the messages.
fn solve_exiting(case: &Path, code: i32) -> (Output, String) {
    let o = run(&["solve", case.to_str().unwrap()]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(code), "{err}");
    (o, err)
}

/// Runs `sweep` on `case` with `options`.
fn sweep(case: &Path, options: &[&str]) -> Output {
    let case = case.to_str().unwrap();
    run(&[&["sweep", case][..], options].concat())
}

/// The table rows of `sweep`'s output: the lines after the comments and the header.
fn sweep_rows(text: &str) -> Vec<&str> {
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .collect()
}

/// A fresh file in a per-process temporary directory.
fn temp_file(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("railcontact-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Runs `solve` and parses its JSON.
fn solve(args: &[&str]) -> Value {
    let o = run(args);
    assert_eq!(o.status.code(), Some(0), "stderr: {}", stderr(&o));
    parse(&stdout(&o))
}

fn parse(text: &str) -> Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("invalid JSON: {e}"))
}

fn outputs() -> impl Iterator<Item = &'static railcontact::fmi::variables::VarInfo> {
    INFO.variables
        .iter()
        .filter(|v| v.causality == Causality::Output)
}

fn real(doc: &Value, name: &str) -> f64 {
    doc.get(name)
        .and_then(Value::as_f64)
        .unwrap_or_else(|| panic!("{name} missing"))
}

/// Every output present, finite, integers written as integers; strips for every patch in
/// contact and for no other.
fn check_solution(doc: &Value) {
    for v in outputs() {
        let Some(Value::Number(x)) = doc.get(v.name) else {
            panic!("output {} missing or not a number", v.name);
        };
        assert!(x.as_f64().is_some_and(f64::is_finite), "{} = {x}", v.name);
        if v.ty == VarType::Integer {
            assert!(x.is_i64(), "{} = {x}", v.name);
        }
    }
    let members = doc.as_object().unwrap();
    assert_eq!(
        members.len(),
        outputs().count() + 1,
        "outputs and strips only"
    );
    let strips = doc
        .get("strips")
        .and_then(Value::as_object)
        .expect("strips");
    let mut expected = Vec::new();
    for side in ["left", "right"] {
        let n = real(doc, &format!("{side}.nPatches")) as usize;
        assert!(n >= 1, "{side} wheel in contact");
        for k in 1..=n {
            expected.push(format!("{side}.p{k}"));
        }
    }
    let keys: Vec<&str> = strips.keys().map(String::as_str).collect();
    assert_eq!(keys, expected);
    for (patch, table) in strips {
        let rows = table.as_array().expect("strip array");
        assert_eq!(rows.len(), 21, "{patch}");
        let p = |q: &str| real(doc, &format!("{patch}.{q}"));
        let (half_length, half_width) = (p("length") / 2.0, p("width") / 2.0);
        let mut peak: f64 = 0.0;
        let mut last_s = f64::NEG_INFINITY;
        for row in rows {
            let f = |q: &str| {
                let x = row.get(q).and_then(Value::as_f64).expect(q);
                assert!(x.is_finite(), "{patch}.{q} = {x}");
                x
            };
            let (s, x_lead, x_trail, pmax) = (f("s"), f("xLead"), f("xTrail"), f("pmax"));
            assert!(s > last_s && s.abs() < half_width, "{patch}: s = {s}");
            last_s = s;
            assert!(x_lead > 0.0 && x_lead <= half_length && x_trail == -x_lead);
            assert!(pmax > 0.0 && pmax <= p("pmax"));
            let expected_y = p("yRail") + s * p("contactAngle").cos();
            assert!((f("yRail") - expected_y).abs() < 1e-12, "{patch}");
            assert!(f("A") > 0.0 && f("B") > 0.0);
            peak = peak.max(pmax);
        }
        // The middle strip runs through the centre of the ellipse.
        let mid = &rows[10];
        assert!(mid.get("s").and_then(Value::as_f64).unwrap().abs() < 1e-15);
        assert_eq!(peak, p("pmax"), "{patch}");
        assert!((mid.get("xLead").and_then(Value::as_f64).unwrap() - half_length).abs() < 1e-15);
    }
}

/// The FMU's model run in-process on the start values with `changes`.
fn direct(changes: &[(&str, f64)]) -> Values {
    let mut values = Values::from_start(INFO.variables, INFO.counts);
    for (name, x) in changes {
        let v = INFO.variable(name).unwrap();
        values.reals[v.slot] = *x;
    }
    let mut model = (INFO.create)(&InstanceContext::default());
    model.initialize(&values).unwrap();
    model.evaluate(&mut values, 0.0).unwrap();
    values
}

fn assert_equals_direct(doc: &Value, values: &Values) {
    for v in outputs() {
        let expected = match v.ty {
            VarType::Real => values.reals[v.slot],
            VarType::Integer => f64::from(values.integers[v.slot]),
            _ => unreachable!("outputs are Real or Integer"),
        };
        assert_eq!(real(doc, v.name), expected, "{}", v.name);
    }
}

#[test]
fn solve_without_a_file_gives_every_output_and_strips() {
    let doc = solve(&["solve"]);
    check_solution(&doc);
    assert_equals_direct(&doc, &direct(&[]));
    // Centred wheelset: symmetric, each wheel carries its 78.5 kN.
    assert_eq!(real(&doc, "left.p1.yRail"), real(&doc, "right.p1.yRail"));
    // The load balance holds to the creep iteration's tolerance, 1e−7 of the load.
    assert!((real(&doc, "right.Fz") + 78_500.0).abs() < 1e-7 * 78_500.0);
}

#[test]
fn solve_with_a_case_file_follows_qright_and_y() {
    let base = solve(&["solve"]);
    let case = temp_file("case.json", "{\"Qright\": 100000, \"y\": 0.003}\n");
    let doc = solve(&["solve", case.to_str().unwrap()]);
    check_solution(&doc);
    assert_equals_direct(&doc, &direct(&[("Qright", 1e5), ("y", 0.003)]));
    // The load balance holds to the creep iteration's tolerance, 1e−7 of the load.
    assert!((real(&doc, "right.Fz") + 1e5).abs() < 1e-7 * 1e5);
    assert!((real(&doc, "left.Fz") + 78_500.0).abs() < 1e-7 * 78_500.0);
    // Shifted towards the right rail: the right contact moves to the gauge side (negative yRail)
    // and steepens, and the left one moves away from it.
    assert!(real(&doc, "right.p1.yRail") < real(&base, "right.p1.yRail") - 1e-3);
    assert!(real(&doc, "right.p1.contactAngle") > real(&base, "right.p1.contactAngle"));
    assert!(real(&doc, "left.p1.yRail") > real(&base, "left.p1.yRail") + 1e-3);
    assert!(real(&doc, "right.p1.Fn") > real(&base, "right.p1.Fn") + 20e3);
}

/// Case files with one error each, one a line: file name | case text (`\n` for a line break) |
/// the parts its message must hold.
const CASE_ERRORS: &str = r#"
unknown.json | {"y": 0.001, "gauge": 1.5} | unknown key "gauge" = 1.5 | allowed keys: wheelProfile
nu.json | {"nu": 0.7} | nu = 0.7 is outside the allowed range [0, 0.5]
mu.json | {"mu": 0} | mu = 0 is outside the allowed range (0, 10]
type.json | {"Qright": "90 kN"} | Qright = "90 kN" has the wrong type: expected a number in [0, 10000000] [N]
int.json | {"nx": 2.5} | nx = 2.5 has the wrong type: expected an integer in [1, 1000]
output.json | {"left.Fy": 0} | 'left.Fy' is an output
syntax.json | {\n  "y": 0.001,\n} | syntax.json', line 3, column 1: trailing comma
"#;

#[test]
fn case_errors_name_key_value_and_range() {
    for line in CASE_ERRORS.lines().filter(|l| !l.is_empty()) {
        let mut fields = line.split(" | ");
        let (name, text) = (fields.next().unwrap(), fields.next().unwrap());
        let case = temp_file(name, &text.replace("\\n", "\n"));
        let (o, err) = solve_exiting(&case, 1);
        assert!(o.stdout.is_empty(), "{name}");
        let parts: Vec<&str> = std::iter::once(name).chain(fields).collect();
        assert_mentions(&err, &parts);
    }
    let o = run(&["solve", "/nonexistent/case.json"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("case file '/nonexistent/case.json': cannot read the file"));
}

#[test]
fn malformed_profile_file_names_file_line_and_reason() {
    // Non-numeric value on line 7 of a Simpack wheel file.
    let prw = "header.begin\n type = 1\nheader.end\npoint.begin\n0 0\n1 1\n2 abc\n3 1\npoint.end\n";
    let profile = temp_file("bad.prw", prw);
    // Relative to the case file's directory, whatever the working directory.
    let case = temp_file("bad_profile.json", "{\"wheelProfile\": \"bad.prw\"}");
    let o = Command::new(env!("CARGO_BIN_EXE_railcontact"))
        .args(["solve", case.to_str().unwrap()])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    let located = format!(
        "profile file '{}', line 7: non-numeric value \"abc\"",
        profile.display()
    );
    assert!(err.contains(&located), "{err}");
}

/// A wheel profile with its flange on the field side (the benchmark wheel file with its
/// `mirror.y` switched off) exits with 1 and says so, naming the parameter and the file; the
/// unmodified file solves.
#[test]
fn a_wheel_with_its_flange_on_the_wrong_side_exits_with_1() {
    let benchmark = common::data_file("profiles/MBench_S1002_v3.prw");
    let text = std::fs::read_to_string(&benchmark).expect("the benchmark wheel");
    let unmirrored = text.replacen("mirror.y       =  1", "mirror.y       =  0", 1);
    assert_ne!(unmirrored, text, "the benchmark file sets mirror.y = 1");
    let wheel = temp_file("unmirrored.prw", &unmirrored);
    let case = temp_file(
        "unmirrored.json",
        "{\"wheelProfile\": \"unmirrored.prw\", \"railProfile\": \"UIC60\"}",
    );
    let (o, err) = solve_exiting(&case, 1);
    assert!(o.stdout.is_empty());
    assert_mentions(
        &err,
        &[
            "wheelProfile = \"".to_string(),
            format!("profile file '{}', line ", wheel.display()),
            "the flange (its tip 30.6 mm high at y = +54.9 mm) lies on the field side".to_string(),
            "the profile is not mirrored".to_string(),
            "toggle mirror.y".to_string(),
        ],
    );
    let good = temp_file(
        "benchmark_wheel.json",
        &format!(
            "{{\"wheelProfile\": {}}}",
            Value::from(benchmark.to_str().unwrap())
        ),
    );
    solve_exiting(&good, 0);
}

#[test]
fn pose_off_the_rail_exits_with_2() {
    // On standard gauge the built-in S1002 still finds the rail at |y| <= 0.05 (its flange tip
    // rides on the crown); on 1.5 m gauge the left wheel falls inside its rail at y = 0.04.
    let case = temp_file("off.json", "{\"y\": 0.04, \"trackGauge\": 1.5}");
    let (o, err) = solve_exiting(&case, 2);
    assert!(o.stdout.is_empty());
    assert!(
        err.contains("no contact: left wheel: no rigid contact inside the profiles' range"),
        "{err}"
    );
}

#[test]
fn sweep_prints_a_header_and_one_row_per_shift() {
    let o = run(&["sweep"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = stdout(&o);
    let lines: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
    let header: Vec<&str> = lines[0].split_whitespace().collect();
    assert_eq!(header[0], "y[mm]");
    for col in [
        "L.n",
        "L.p1.yRail[mm]",
        "L.p1.gamma[rad]",
        "L.p1.Fn[kN]",
        "L.p1.r[mm]",
    ] {
        assert!(header.contains(&col), "{col} in {header:?}");
    }
    assert_eq!(header.last(), Some(&"R.Fy[kN]"));
    let rows = &lines[1..];
    assert_eq!(rows.len(), 21, "-2 … 8 mm in 0.5 mm steps");
    for (k, row) in rows.iter().enumerate() {
        let cells: Vec<&str> = row.split_whitespace().collect();
        assert_eq!(cells.len(), header.len(), "{row}");
        let y: f64 = cells[0].parse().unwrap();
        assert!((y - (-2.0 + 0.5 * k as f64)).abs() < 1e-9, "{row}");
    }
    // Row at y = 3 mm equals the FMU outputs, rounded as printed.
    let values = direct(&[("y", 0.003)]);
    let fy = values.reals[INFO.variable("right.Fy").unwrap().slot];
    let row: Vec<&str> = rows[10].split_whitespace().collect();
    assert_eq!(row[0], "3.000");
    assert_eq!(*row.last().unwrap(), format!("{:.3}", fy / 1e3));

    // Shifts where a wheel leaves the profiles get a note, and the sweep goes on.
    let case = temp_file("wide_gauge.json", "{\"trackGauge\": 1.5}");
    let o = sweep(&case, &["--from", "0.03", "--to=0.045", "--step", "0.005"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = stdout(&o);
    let rows = sweep_rows(&text);
    assert_eq!(rows.len(), 4, "{text}");
    assert!(!rows[0].contains("no contact"), "{text}");
    for row in &rows[2..] {
        assert!(row.contains("-- no contact: left wheel"), "{row}");
    }

    let o = run(&["sweep", "--step", "0"]);
    assert_eq!(o.status.code(), Some(1));
    let o = run(&["sweep", "--from", "0.2"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("y = 0.2 is outside the allowed range [-0.05, 0.05] [m]"));
}

/// An implausible contact state (`railcontact::wheelset::validity`: a patch's approach above 1 mm) —
/// here the prescribed position z = +50 mm, inside the declared range — exits with 3: the JSON
/// with finite outputs on stdout (the same numbers as the FMU's model), the warning on stderr
/// naming the quantity, its value, the limit and the cause. z = +0.5 mm (approach 0.32 mm) is
/// plausible: exit 0. `sweep` marks the rows and exits with 3, too.
#[test]
fn implausible_state_exits_with_3_and_prints_the_outputs() {
    let case = temp_file("deep.json", "{\"verticalMode\": 2, \"z\": 0.05}");
    let (o, err) = solve_exiting(&case, 3);
    let doc = parse(&stdout(&o));
    check_solution(&doc);
    let penetration = real(&doc, "left.p1.penetration");
    assert!(penetration > 1e-3, "{penetration}");
    assert_mentions(
        &err,
        &[
            "railcontact: warning: implausible contact state: left wheel, patch 1:".to_string(),
            format!("penetration = {penetration:.4e} m exceeds the limit 1e-3 m"),
            "the prescribed position z = 0.05 m (verticalMode = 2) pushes the left wheel"
                .to_string(),
            "not physical".to_string(),
        ],
    );

    let fine = temp_file("shallow.json", "{\"verticalMode\": 2, \"z\": 0.0005}");
    let (_, err) = solve_exiting(&fine, 0);
    assert!(err.is_empty(), "{err}");

    let o = sweep(&case, &["--from", "0", "--to", "0.001", "--step", "0.001"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(3), "{err}");
    assert!(
        err.contains("2 of the shifts give implausible contact states"),
        "{err}"
    );
    let text = stdout(&o);
    let rows = sweep_rows(&text);
    assert_eq!(rows.len(), 2, "{text}");
    for row in rows {
        assert!(
            row.contains(" -- warning: implausible contact state"),
            "{row}"
        );
    }
}

#[test]
fn help_and_bad_arguments() {
    for args in [&["--help"][..], &["-h"], &["help"]] {
        let o = run(args);
        assert_eq!(o.status.code(), Some(0));
        let parts = [
            "railcontact solve [CASE.json]",
            "railcontact sweep [CASE.json]",
            "railcontact report [CASE.json]",
            "Exit codes:",
            "3  implausible contact state",
        ];
        assert_mentions(&stdout(&o), &parts);
    }
    for (command, option) in [("solve", "--grid <NX>"), ("sweep", "--step <DY>")] {
        for args in [&[command, "--help"][..], &["help", command]] {
            let o = run(args);
            assert_eq!(o.status.code(), Some(0), "{args:?}");
            let text = stdout(&o);
            assert!(
                text.contains(&format!("Usage: railcontact {command}")),
                "{text}"
            );
            assert!(
                text.contains(option) && text.contains("Exit codes:"),
                "{text}"
            );
        }
    }
    let o = run(&["report", "--help"]);
    assert_eq!(o.status.code(), Some(0));
    assert!(
        stdout(&o).contains("tests/data/reference"),
        "{}",
        stdout(&o)
    );
    for args in [
        &[][..],
        &["frobnicate"],
        &["solve", "--bogus"],
        &["solve", "a", "b"],
        &["sweep", "--from", "x"],
    ] {
        let o = run(args);
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        assert!(!stderr(&o).is_empty());
        assert!(o.stdout.is_empty(), "{args:?}");
    }
}

#[test]
fn solve_with_a_strip_model_gives_its_strips_and_the_pressure_grid() {
    // ANALYN (normalModel 6) with 30 strips: the strip tables are the model's own strips in
    // contact; `--grid 8` adds 8 pressure points per strip whose largest value is below the
    // patch maximum (element centres never sit on the strip's peak) and whose integral
    // Σ p Δx Δs approximates the normal force to the midpoint rule's accuracy.
    let case = temp_file(
        "analyn.json",
        "{\"normalModel\": 6, \"nStrips\": 30, \"y\": 0.002}\n",
    );
    let doc = solve(&["solve", case.to_str().unwrap(), "--grid", "8"]);
    let strips = doc.get("strips").and_then(Value::as_object).unwrap();
    let grid = doc.get("grid").and_then(Value::as_object).expect("grid");
    assert_eq!(strips.len(), grid.len());
    for ((patch, table), (grid_patch, points)) in strips.iter().zip(grid) {
        assert_eq!(patch, grid_patch);
        let rows = table.as_array().unwrap();
        assert!(
            !rows.is_empty() && rows.len() <= 30,
            "{patch}: {} strips",
            rows.len()
        );
        let p = |q: &str| real(&doc, &format!("{patch}.{q}"));
        let peak = rows
            .iter()
            .map(|r| r.get("pmax").and_then(Value::as_f64).unwrap())
            .fold(0.0, f64::max);
        assert_eq!(peak, p("pmax"), "{patch}");
        let points = points.as_array().unwrap();
        assert_eq!(points.len(), 8 * rows.len());
        let s: Vec<f64> = rows
            .iter()
            .map(|r| r.get("s").and_then(Value::as_f64).unwrap())
            .collect();
        let ds = (s[s.len() - 1] - s[0]) / (s.len() - 1).max(1) as f64;
        let mut force = 0.0;
        for (k, row) in rows.iter().enumerate() {
            let f = |q: &str| row.get(q).and_then(Value::as_f64).unwrap();
            let dx = (f("xLead") - f("xTrail")) / 8.0;
            for pt in &points[8 * k..8 * k + 8] {
                let v: Vec<f64> = pt
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap())
                    .collect();
                assert!(v[0] > f("xTrail") && v[0] < f("xLead") && v[1] == f("s"));
                assert!(v[2] > 0.0 && v[2] < p("pmax"));
                force += v[2] * dx * ds;
            }
        }
        // 8 points per semi-ellipse: midpoint rule within ~1 % of (π/2) p0 x_l.
        assert!(
            (force / p("Fn") - 1.0).abs() < 0.02,
            "{patch}: {force} vs {}",
            p("Fn")
        );
    }
    // Bad --grid values are usage errors naming the option, the value and the range.
    let o = run(&["solve", "--grid", "1"]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(
        err.contains("'1'") && err.contains("--grid") && err.contains("[2, 1000]"),
        "{err}"
    );
}

#[test]
fn solve_with_traction_gives_the_tangential_field() {
    // ANALYN, prescribed ξ = 1e−3, planar patch, nx = 20: `--traction` lists nx elements per
    // strip in contact of every patch; summing px over the elements times their area
    // (2 x_l/nx × Δs, Δs from the strip table) gives the patch's Fx output back (same numbers,
    // 1e−9 relative); every |traction| ≤ the maxTraction output.
    let case = temp_file(
        "traction.json",
        "{\"normalModel\": 6, \"nStrips\": 30, \"nx\": 20, \"creepageMode\": 2, \"xi\": 0.001, \
         \"planarPatch\": true}\n",
    );
    let doc = solve(&["solve", case.to_str().unwrap(), "--traction"]);
    let strips = doc.get("strips").and_then(Value::as_object).unwrap();
    let traction = doc
        .get("traction")
        .and_then(Value::as_object)
        .expect("traction");
    assert_eq!(traction.len(), strips.len());
    let entry = |o: &Map<String, Value>| {
        o.get("right.p1")
            .and_then(Value::as_array)
            .cloned()
            .expect("right.p1")
    };
    let (table, field) = (entry(strips), entry(traction));
    assert_eq!(field.len(), 20 * table.len());
    let num = |v: &Value, k: &str| v.get(k).and_then(Value::as_f64).unwrap();
    let ds = num(&table[1], "s") - num(&table[0], "s");
    let mut fx: f64 = 0.0;
    let max = real(&doc, "right.p1.maxTraction");
    for (k, strip) in table.iter().enumerate() {
        let dx = (num(strip, "xLead") - num(strip, "xTrail")) / 20.0;
        for e in &field[20 * k..20 * (k + 1)] {
            let e = e.as_array().unwrap();
            let (px, py): (f64, f64) = (e[2].as_f64().unwrap(), e[3].as_f64().unwrap());
            fx += px * dx * ds;
            assert!(px.hypot(py) <= max * (1.0 + 1e-12));
        }
    }
    let fx_out = real(&doc, "right.p1.Fx");
    assert!(
        fx < 0.0 && ((fx - fx_out) / fx_out).abs() < 1e-9,
        "{fx} vs {fx_out}"
    );
}

/// `conicity`: the JSON's λ(A) at the default amplitudes (the library's numbers, tested against
/// a cone and the benchmark profiles in `tests/conicity.rs`), the CSV tables and the figure in
/// `--out`, `--no-roll`, and a bad amplitude named with exit code 1.
#[test]
fn conicity_prints_the_table_and_writes_csv_and_figure() {
    let dir = std::env::temp_dir().join(format!("railcontact-conicity-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = dir.to_str().unwrap();
    let o = run(&["conicity", "--out", out]);
    assert_eq!(o.status.code(), Some(0), "stderr: {}", stderr(&o));
    let doc = parse(&stdout(&o));
    let table = doc["conicity"].as_array().expect("conicity");
    let amplitudes: Vec<f64> = table
        .iter()
        .map(|c| c["amplitude"].as_f64().unwrap())
        .collect();
    assert_eq!(amplitudes, [0.001, 0.002, 0.003, 0.004, 0.005, 0.006]);
    let at3 = &table[2];
    let (h, k) = (
        at3["harmonic"].as_f64().unwrap(),
        at3["klingel"].as_f64().unwrap(),
    );
    assert!((0.1..0.25).contains(&h) && (h - k).abs() < 0.01, "{at3}");
    // Klingel's formula links the wavelength and λ with the document's r0 and e0.
    let (r0, e0) = (doc["r0"].as_f64().unwrap(), doc["e0"].as_f64().unwrap());
    let wavelength = at3["wavelength"].as_f64().unwrap();
    let formula = 2.0 * std::f64::consts::PI * (r0 * e0 / k).sqrt();
    assert!((wavelength / formula - 1.0).abs() < 1e-12);
    let rows = doc["deltaR"].as_array().expect("deltaR");
    assert_eq!(rows.len(), 281, "±7 mm in 0.05 mm steps");
    assert_eq!(rows[0]["y"].as_f64(), Some(-0.007));
    for name in [
        "conicity.json",
        "conicity.csv",
        "delta_r.csv",
        "conicity.svg",
        "conicity.png",
    ] {
        assert!(dir.join(name).is_file(), "{name}");
    }
    let csv = std::fs::read_to_string(dir.join("conicity.csv")).unwrap();
    assert_eq!(csv.lines().count(), 7);
    assert!(csv.starts_with("amplitude_m,harmonic,klingel,wavelength_m\n0.001,"));
    let csv = std::fs::read_to_string(dir.join("delta_r.csv")).unwrap();
    assert_eq!(csv.lines().count(), 282);
    let _ = std::fs::remove_dir_all(&dir);

    let o = run(&["conicity", "--no-roll", "--amplitudes", "0.003"]);
    assert_eq!(o.status.code(), Some(0), "stderr: {}", stderr(&o));
    let level = parse(&stdout(&o));
    assert_eq!(level["roll"], Value::Bool(false));
    assert!(level["deltaR"]
        .as_array()
        .unwrap()
        .iter()
        .all(|r| r["roll"] == 0.0));

    let o = run(&["conicity", "--amplitudes", "0.003,0.05"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("amplitude = 0.05 is outside the allowed range (0, 0.02] [m]"),
        "{}",
        stderr(&o)
    );
}

/// `conicity --load`: the loaded element's Δr is made of the rolling radii the FMU reports
/// (`railcontact solve` at zero creepage under the same load: each wheel's patches' rolling
/// radii weighted by their normal forces), and a bad load is named with exit code 1.
#[test]
fn loaded_conicity_follows_the_elements_rolling_radii() {
    let o = run(&["conicity", "--load", "60000", "--step", "0.001"]);
    assert_eq!(o.status.code(), Some(0), "stderr: {}", stderr(&o));
    let doc = parse(&stdout(&o));
    assert_eq!(doc["load"].as_f64(), Some(60_000.0));
    let row = doc["deltaR"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["y"].as_f64() == Some(0.002))
        .expect("y = 2 mm")
        .clone();
    let case = temp_file(
        "loaded.json",
        r#"{"y": 0.002, "Qleft": 60000, "Qright": 60000, "creepageMode": 2, "xi": 0, "eta": 0, "phi": 0}"#,
    );
    let solved = solve(&["solve", case.to_str().unwrap()]);
    for (side, key) in [("right", "rRight"), ("left", "rLeft")] {
        let (mut normal, mut moment) = (0.0, 0.0);
        for k in 1..=3 {
            let fn_ = real(&solved, &format!("{side}.p{k}.Fn"));
            normal += fn_;
            moment += fn_ * real(&solved, &format!("{side}.p{k}.rollingRadius"));
        }
        let r = row[key].as_f64().unwrap();
        assert!(
            (r - moment / normal).abs() < 1e-12,
            "{side}: {r} vs {}",
            moment / normal
        );
    }
    let o = run(&["conicity", "--load=-5"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("--load: load = -5"), "{}", stderr(&o));
}

/// Writes the wear record of a closed-loop-like run (the FMU's model in-process: a wheelset
/// oscillating laterally by `amplitude` [m] at 2 Hz, kinematic creepages at 30 m/s, `steps` of
/// 1 ms) to `record`, for the case `case_file`.
fn record_run(case_file: &Path, amplitude: f64, steps: usize) {
    use railcontact::models::wheel_rail_contact::generated::var;
    let mut values = railcontact_cli::case::load(Some(case_file.to_str().unwrap())).unwrap();
    let mut model = railcontact_cli::model(&values).unwrap();
    let w = 2.0 * std::f64::consts::PI * 2.0;
    for k in 0..steps {
        let t = k as f64 * 1e-3;
        values.set_real(var::y, amplitude * (w * t).sin());
        values.set_real(var::vy, amplitude * w * (w * t).cos());
        model.evaluate(&mut values, t).unwrap();
        model.advance(&mut values, 1e-3).unwrap();
    }
    model.terminate(&values).unwrap();
}

#[test]
fn wear_turns_records_into_worn_profiles_that_load_and_run() {
    let dir = std::env::temp_dir().join(format!("railcontact-wear-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let record = dir.join("run.csv");
    let case = temp_file(
        "wear_case.json",
        &format!(
            r#"{{"wearModel": 1, "wearOutput": {:?}, "normalModel": 6, "vx": 30.0, "omega": 65.3}}"#,
            record.to_str().unwrap()
        ),
    );
    record_run(&case, 3e-3, 300);
    let out = dir.join("worn");
    let wear = |records: &[&Path], distance: &str, case: Option<&Path>| {
        let mut args = vec!["wear".to_string()];
        args.extend(case.map(|c| c.to_str().unwrap().to_string()));
        for r in records {
            args.extend(["--record".to_string(), r.to_str().unwrap().to_string()]);
        }
        args.extend(["--distance", distance, "--out", out.to_str().unwrap()].map(String::from));
        run(&args.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let o = wear(&[&record, &record], "1e9", Some(&case));
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let doc = parse(&stdout(&o));
    // 1e9 m would wear far deeper than the default limit of 0.1 mm: the distance is reduced.
    let depth = doc["wheelDepthMax"]
        .as_f64()
        .unwrap()
        .max(doc["railDepthMax"].as_f64().unwrap());
    assert!((depth - 1e-4).abs() < 1e-12, "{doc}");
    assert!(doc["distance"].as_f64().unwrap() < 1e9);
    assert!((doc["recordedDistance"].as_f64().unwrap() - 2.0 * 0.3 * 30.0).abs() < 1e-9);
    // The worn profiles run in the element: a sweep of the same oscillation without a Discard.
    let worn_case = temp_file(
        "worn_case.json",
        &format!(
            r#"{{"wheelProfile": {:?}, "railProfile": {:?}, "railInclination": 0.0, "normalModel": 6}}"#,
            out.join("worn_wheel.txt").to_str().unwrap(),
            out.join("worn_rail.txt").to_str().unwrap()
        ),
    );
    let s = sweep(
        &worn_case,
        &["--from", "-0.003", "--to", "0.003", "--step", "0.001"],
    );
    assert_eq!(s.status.code(), Some(0), "{}", stderr(&s));
    assert_eq!(sweep_rows(&stdout(&s)).len(), 7);
    // Errors name the file.
    let missing = dir.join("missing.csv");
    let o = wear(&[&missing], "1000", None);
    assert_eq!(o.status.code(), Some(1));
    assert_mentions(
        &stderr(&o),
        &[missing.to_str().unwrap(), "cannot read the wear record"],
    );
    let _ = std::fs::remove_dir_all(&dir);
}
