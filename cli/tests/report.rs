//! `railcontact report` run as a process: regenerates the validation report into a temporary
//! directory with the vendored CONTACT reference (`tests/data/reference`;
//! missing data fail the test, never skip it) and checks that every figure exists as a valid SVG
//! and PNG, that report.md embeds them, and that the error table's numbers are the library's own:
//! the central case's area and pmax of ANALYN and STRIPES-A&B and ANALYN's pure-spin forces,
//! computed here through the library API on the benchmark wheelset (set-up as
//! `tests/central.rs` and `tests/tangential.rs`), to the precision the table prints. A second
//! run without reference data checks that the figures still come and the table is left out. A
//! third regenerates the validation document at the defaults and checks that the repository's
//! `docs/validation.md` and `docs/figures/errors.csv` are exactly its output, so that they cannot
//! go stale.

// The root crate's shared test set-up (the vendored data of `tests/data`, the benchmark wheelset).
#[path = "../../tests/common/mod.rs"]
mod common;

use common::{benchmark_wheelset_with, data_dir, data_file, patch_options, read_csv, solve_pose};
use railcontact::material::Material;
use railcontact::normal::NormalModel;
use railcontact::tangential::fastsim::Creepage;
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::{Creepages, WheelsetResult};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The figures the report writes, each as .svg and .png.
const FIGURES: [&str; 7] = [
    "patch_outlines",
    "pressure_per_strip",
    "pure_spin_planar",
    "pure_spin_nonplanar",
    "lateral_shifts",
    "creep_curves",
    "power_density",
];

const Q: f64 = 78_500.0;
const VX: f64 = 2.0;

/// A fresh, empty directory under the system's temporary directory.
fn temp_dir(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("railcontact-report-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temporary directory");
    dir
}

fn report(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_railcontact"))
        .arg("report")
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("railcontact runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Width and height of a PNG file, after checking its signature, its IHDR chunk and its IEND
/// trailer.
fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(
        bytes.len() > 100,
        "{}: only {} bytes",
        path.display(),
        bytes.len()
    );
    assert_eq!(
        &bytes[..8],
        b"\x89PNG\r\n\x1a\n",
        "{}: not a PNG signature",
        path.display()
    );
    assert_eq!(
        &bytes[8..12],
        &[0, 0, 0, 13],
        "{}: IHDR length",
        path.display()
    );
    assert_eq!(&bytes[12..16], b"IHDR", "{}: first chunk", path.display());
    let be = |k: usize| u32::from_be_bytes([bytes[k], bytes[k + 1], bytes[k + 2], bytes[k + 3]]);
    assert_eq!(
        &bytes[bytes.len() - 8..bytes.len() - 4],
        b"IEND",
        "{}: no IEND trailer",
        path.display()
    );
    (be(16), be(20))
}

/// Checks that an SVG file is non-empty XML-ish text with labels.
fn check_svg(path: &Path) {
    let s = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let t = s.trim_start();
    assert!(
        t.starts_with("<svg") || t.starts_with("<?xml"),
        "{}: does not start as SVG",
        path.display()
    );
    assert!(
        s.contains("</svg>"),
        "{}: no closing </svg>",
        path.display()
    );
    assert!(
        s.contains("<text"),
        "{}: no text (axis labels)",
        path.display()
    );
}

fn check_figures(out: &Path) {
    for name in FIGURES {
        check_svg(&out.join(format!("{name}.svg")));
        let (w, h) = png_size(&out.join(format!("{name}.png")));
        assert!(w > 0 && h > 0, "{name}.png: {w} × {h}");
    }
}

/// `errors.csv` as (case, normal model, tangential, planar, quantity) → (model, reference,
/// error) texts.
type Table = HashMap<(String, String, String, String, String), (String, String, String)>;

fn read_table(path: &Path) -> Table {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    assert_eq!(
        header,
        [
            "case",
            "normal_model",
            "tangential_model",
            "planar_patch",
            "quantity",
            "unit",
            "model",
            "reference",
            "error",
            "error_unit"
        ]
    );
    lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<String> = l.split(',').map(str::to_string).collect();
            assert_eq!(f.len(), header.len(), "row {l}");
            (
                (
                    f[0].clone(),
                    f[1].clone(),
                    f[2].clone(),
                    f[3].clone(),
                    f[4].clone(),
                ),
                (f[6].clone(), f[7].clone(), f[8].clone()),
            )
        })
        .collect()
}

/// Asserts that `printed` is `value` to the printed number of decimals.
fn assert_printed(printed: &str, value: f64, what: &str) {
    let decimals = printed.split_once('.').map_or(0, |(_, d)| d.len());
    let x: f64 = printed
        .parse()
        .unwrap_or_else(|_| panic!("{what}: '{printed}' is not a number"));
    let tolerance = 0.5 * 10f64.powi(-(decimals as i32)) * (1.0 + 1e-9) + 1e-12;
    assert!(
        (x - value).abs() <= tolerance,
        "{what}: table {printed}, library {value}"
    );
}

fn material() -> Material {
    Material {
        youngs_modulus: 210e9,
        poisson_ratio: 0.28,
        friction: 0.3,
    }
}

/// The benchmark wheelset solved as the report's central case (as `tests/central.rs` and
/// `tests/tangential.rs` solve it).
fn solve(
    model: NormalModel,
    tangential: TangentialModel,
    planar: bool,
    creepages: Creepages,
) -> WheelsetResult {
    let mut ws = benchmark_wheelset_with(material(), patch_options(model, tangential, planar));
    solve_pose(&mut ws, 0.0, 0.0, Q, creepages)
}

const ROLLING: Creepages = Creepages::Kinematic {
    vx: VX,
    vy: 0.0,
    yaw_rate: 0.0,
    omega: VX / 0.46,
};

#[test]
fn report_reproduces_the_figures_and_the_error_table() {
    // Fails (never skips) without the vendored data.
    data_file("reference/central/normal_dy0_summary.csv");
    data_file("profiles/MBench_S1002_v3.prw");
    let reference = data_dir().join("reference");
    let out = temp_dir("with-reference");
    let o = report(
        &[
            "--out",
            out.to_str().unwrap(),
            "--reference",
            reference.to_str().unwrap(),
            "--quick",
        ],
        Path::new(env!("CARGO_MANIFEST_DIR")),
    );
    let stderr = text(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "stderr: {stderr}");
    // One progress line per figure.
    for k in 1..=FIGURES.len() {
        assert!(
            stderr.contains(&format!("[{k}/{}]", FIGURES.len())),
            "no progress line {k}: {stderr}"
        );
    }
    check_figures(&out);
    let md = std::fs::read_to_string(out.join("report.md")).expect("report.md");
    for name in FIGURES {
        assert!(
            md.contains(&format!("({name}.png)")),
            "report.md lacks {name}.png"
        );
    }
    assert!(md.contains("Errors against the exact theory") && md.contains("| 6 ANALYN |"));
    assert!(md.contains("MBench_S1002_v3.prw"), "the benchmark files");

    let table = read_table(&out.join("errors.csv"));
    let key = |case: &str, model: &str, t: &str, planar: &str, q: &str| {
        let k = (
            case.to_string(),
            model.to_string(),
            t.to_string(),
            planar.to_string(),
            q.to_string(),
        );
        table
            .get(&k)
            .unwrap_or_else(|| panic!("errors.csv has no row {k:?}"))
            .clone()
    };
    let summary = &read_csv("reference/central/normal_dy0_summary.csv")[0];
    for (model, label) in [
        (NormalModel::Analyn, "6 ANALYN"),
        (NormalModel::StripesAB, "5 STRIPES-A&B"),
    ] {
        let right = solve(model, TangentialModel::ModelDefault, false, ROLLING).right;
        let patches: Vec<_> = right.shown_patches().copied().collect();
        let area_mm2 = patches.iter().map(|p| p.area).sum::<f64>() * 1e6;
        let pmax_mpa = patches.iter().map(|p| p.pmax).fold(0.0, f64::max) * 1e-6;
        for (quantity, model_value, column) in [
            ("area", area_mm2, "area_mm2"),
            ("pmax", pmax_mpa, "pmax_MPa"),
        ] {
            let (value, reference, error) = key("central", label, "-", "-", quantity);
            assert_printed(&value, model_value, &format!("{label} {quantity}"));
            assert_printed(
                &reference,
                summary[column],
                &format!("reference {quantity}"),
            );
            assert_printed(
                &error,
                100.0 * (model_value / summary[column] - 1.0),
                &format!("{label} {quantity} error"),
            );
        }
    }
    // ANALYN's pure spin 0.052 rad/m, planar, tangentialModel 1 (the case's).
    let spin = Creepages::Prescribed {
        creepage: Creepage {
            xi: 0.0,
            eta: 0.0,
            phi: 0.052,
        },
        vx: VX,
    };
    let p = solve(
        NormalModel::Analyn,
        TangentialModel::ModelDefault,
        true,
        spin,
    )
    .right
    .patches[0];
    for (q, value) in [("Fx", p.fx), ("Fy", p.fy), ("Mz", p.mz)] {
        let (printed, _, _) = key("pure_spin", "6 ANALYN", "1", "true", q);
        assert_printed(&printed, value, &format!("ANALYN pure spin {q}"));
    }
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn report_without_reference_draws_the_models_alone() {
    // A working directory outside the repository, built-in profiles, no reference.
    let cwd = temp_dir("cwd");
    let work = cwd.join("work");
    std::fs::create_dir_all(&work).unwrap();
    std::fs::write(
        work.join("builtin.json"),
        "{\"wheelProfile\": \"S1002\", \"railProfile\": \"UIC60\"}",
    )
    .unwrap();
    let o = report(
        &[
            "builtin.json",
            "--out",
            "figures",
            "--no-reference",
            "--quick",
        ],
        &work,
    );
    let stderr = text(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "stderr: {stderr}");
    let out = work.join("figures");
    check_figures(&out);
    assert!(
        !out.join("errors.csv").exists(),
        "no error table without reference"
    );
    let md = std::fs::read_to_string(out.join("report.md")).expect("report.md");
    assert!(md.contains("error table is omitted"), "{md}");
    assert!(
        md.contains("`S1002` on rail `UIC60`"),
        "built-in profiles: {md}"
    );
    // A bad reference directory is an error naming it.
    let o = report(&["--reference", "no/such/dir"], &work);
    assert_eq!(o.status.code(), Some(1));
    assert!(text(&o.stderr).contains("no/such/dir"));
    let _ = std::fs::remove_dir_all(&cwd);
}

/// The repository's root (the parent of this crate's directory).
fn repository() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the workspace root")
        .to_path_buf()
}

#[test]
fn validation_document_is_the_report_output() {
    // The command the document names, into a temporary directory, from a working directory
    // outside the repository (the defaults do not depend on it).
    let tmp = temp_dir("validation");
    let (figures, markdown) = (tmp.join("figures"), tmp.join("validation.md"));
    let o = report(
        &[
            "--out",
            figures.to_str().unwrap(),
            "--markdown",
            markdown.to_str().unwrap(),
        ],
        &tmp,
    );
    assert_eq!(o.status.code(), Some(0), "stderr: {}", text(&o.stderr));
    let generated = std::fs::read_to_string(&markdown)
        .expect("the document")
        .replace(
            &format!("--out {}", figures.display()),
            "--out docs/figures",
        )
        .replace(
            &format!("--markdown {}", markdown.display()),
            "--markdown docs/validation.md",
        );
    let docs = repository().join("docs");
    let committed =
        std::fs::read_to_string(docs.join("validation.md")).expect("docs/validation.md");
    let regenerate = "cargo run --release -p railcontact-cli -- report --out docs/figures \
                      --markdown docs/validation.md";
    assert!(
        committed.contains(regenerate),
        "the document names its command"
    );
    assert_lines_equal(&committed, &generated, "docs/validation.md", regenerate);
    assert_critical_speeds_agree(&generated);
    let csv = std::fs::read_to_string(figures.join("errors.csv")).expect("errors.csv");
    let committed_csv =
        std::fs::read_to_string(docs.join("figures/errors.csv")).expect("docs/figures/errors.csv");
    assert_lines_equal(&committed_csv, &csv, "docs/figures/errors.csv", regenerate);
    // Every figure the document shows is in docs/figures.
    for name in FIGURES {
        for ext in ["png", "svg"] {
            let link = format!("figures/{name}.{ext}");
            assert!(committed.contains(&format!("({link})")), "{link}");
            assert!(docs.join(&link).is_file(), "docs/{link}");
        }
    }
    let _ = std::fs::remove_dir_all(&tmp);
}

/// The linear critical speeds of ANALYN and the coupled strips (the document's table, planar
/// and non-planar patches) lie within 5 % of each other: with their reference points at the
/// interpenetration's weighted centre both report the same loaded conicity, and their creep
/// coefficients agree within 2 %; what is left is ANALYN's gravitational stiffness on non-planar
/// patches (measured 72.2 against 69.9 m/s, 3.3 %; planar 70.0 against 69.6 m/s).
fn assert_critical_speeds_agree(document: &str) {
    let table = document
        .split("### Critical speed of a suspended wheelset")
        .nth(1)
        .and_then(|rest| rest.split("\n## ").next())
        .expect("the critical-speed section");
    let speed = |model: &str, planar: &str| -> f64 {
        table
            .lines()
            .find_map(|line| {
                let cells: Vec<&str> = line.split('|').map(str::trim).collect();
                (cells.len() > 8 && cells[1] == model && cells[2] == planar)
                    .then(|| cells[7].parse().expect("a speed"))
            })
            .unwrap_or_else(|| panic!("row {model}, planar {planar}"))
    };
    for planar in ["yes", "no"] {
        let (analyn, coupled) = (speed("6 ANALYN", planar), speed("7 coupled strips", planar));
        println!("critical speeds, planar {planar}: ANALYN {analyn}, coupled strips {coupled}");
        assert!(
            (analyn / coupled - 1.0).abs() < 0.05 && (coupled / analyn - 1.0).abs() < 0.05,
            "planar {planar}: {analyn} against {coupled} m/s"
        );
    }
}

/// Fails at the first differing line, naming the file and the command that regenerates it.
fn assert_lines_equal(committed: &str, generated: &str, file: &str, regenerate: &str) {
    for (k, (c, g)) in committed.lines().zip(generated.lines()).enumerate() {
        assert_eq!(
            c,
            g,
            "{file}, line {}: the committed line (left) differs from the regenerated one \
             (right); regenerate with `{regenerate}`",
            k + 1
        );
    }
    assert_eq!(
        committed.lines().count(),
        generated.lines().count(),
        "{file}: line counts differ; regenerate with `{regenerate}`"
    );
    assert_eq!(
        committed, generated,
        "{file}: regenerate with `{regenerate}`"
    );
}
