//! `railcontact report [CASE.json] [--out DIR] [--reference DIR] [--quick]`: reproduces the
//! comparison of the normal and tangential models against Kalker's exact theory as SVG
//! and PNG figures, a markdown summary (`report.md`) and an error table (`errors.csv`).
//!
//! The case: without CASE.json the central case (tests/data/README.md) — the benchmark profiles
//! `MBench_S1002_v3.prw` on `MBench_UIC60_v3.prr` from `<reference>/../profiles` (or
//! `tests/data/profiles`; rail already inclined 1:40, so `railInclination` = 0), gauge 1435 mm,
//! flange-back distance 1360 mm, radius 460 mm, E = 210 GPa, ν = 0.28, μ = 0.3, 78.5 kN per
//! wheel, centred, pure rolling at 2 m/s (as `tests/central.rs`); without those files the
//! built-in S1002/UIC60 with the rail inclined 1:40. A CASE.json is read as `railcontact solve`
//! reads it (keys not given keep the FMU's start values). Each figure sets `normalModel`,
//! `tangentialModel`, `planarPatch`, the creepages or the lateral shift `y` itself.
//!
//! The reference (CONTACT's solution of the central case): `--reference DIR`, else
//! `tests/data/reference` when that directory exists, else none — then the figures show the
//! models alone and the error table is left out.
//!
//! Figures ([`figures`]): patch outlines, pressure per strip, pure spin planar and non-planar,
//! lateral shifts of the STRIPES variants, creep curves. `--quick` computes the creep curves at
//! the reference's creepages only (the error table does not change). Progress: one line per
//! figure on stderr.

mod dissipation;
mod figures;
mod manchester;
pub mod plot;
mod reference;
mod study;
mod tables;
mod wheel;

use crate::{workspace_root, Failure};
use figures::{Creep, Dissipation, Outlines, Pressure, ReportFigure, ShiftRuns, Shifts, Spin};
use plot::render;
use railcontact::fmi::variables::Values;
use railcontact::models::wheel_rail_contact::{generated::var, INFO};
use railcontact::normal::NormalModel;
use railcontact::tangential::patch::TangentialModel;
use railcontact_cli::case;
use reference::Reference;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;
use study::{CreepCurve, NormalRun, Options, SpinRun, Study};

/// Pure spin of the tangential figures [1/m] (0.052 rad/m, the reference's 5.2e−5 1/mm).
const SPIN: f64 = 0.052;
/// Lateral shifts of the STRIPES figure [mm].
const SHIFTS_MM: [f64; 4] = [-1.0, 0.0, 1.0, 2.0];
/// Creepages of the creep curves (denser at the knee).
const CREEP_FULL: [f64; 16] = [
    0.0, 0.00025, 0.0005, 0.00075, 0.001, 0.00125, 0.0015, 0.00175, 0.002, 0.0025, 0.003, 0.004,
    0.005, 0.0065, 0.008, 0.01,
];
/// Creepages of the creep curves with `--quick` (the reference's).
const CREEP_QUICK: [f64; 6] = [0.0, 0.0005, 0.001, 0.002, 0.005, 0.01];
/// The benchmark profile files of the central case.
const WHEEL_FILE: &str = "MBench_S1002_v3.prw";
const RAIL_FILE: &str = "MBench_UIC60_v3.prr";
/// The central case: load per wheel [N], speed [m/s].
const CENTRAL_LOAD: f64 = 78_500.0;
const CENTRAL_SPEED: f64 = 2.0;
/// Number of figures (for the progress lines).
const FIGURES: usize = 7;
/// The vendored data, relative to the workspace root.
const REFERENCE_DIR: &str = "tests/data/reference";
const PROFILE_DIR: &str = "tests/data/profiles";

/// Regenerates the validation against CONTACT: figures, error tables and their document
///
/// Reproduces the validation against CONTACT (Kalker's exact theory): writes SVG
/// and PNG figures (patch outlines, pressure per strip, pure-spin traction planar and
/// non-planar, STRIPES over lateral shifts, creep curves), errors.csv and a markdown document
/// with the set-up and the error tables into --out DIR. Without CASE.json: the central
/// case of tests/data/README.md (the benchmark profiles next to the reference directory or in the
/// repository's tests/data/profiles, else the built-in S1002/UIC60 at 1:40; 78.5 kN, E = 210 GPa,
/// nu = 0.28, mu = 0.3, centred). Progress on stderr.
///
/// The repository's docs/validation.md and docs/figures/ are this command's output:
///   railcontact report --out docs/figures --markdown docs/validation.md
#[derive(Debug, Clone, PartialEq, clap::Args)]
pub struct ReportArgs {
    /// A case file, read as `solve` reads it (none: the central case)
    #[arg(value_name = "CASE.json")]
    pub case: Option<String>,
    /// Directory of the figures and errors.csv (created if needed)
    #[arg(long, value_name = "DIR", default_value = "report")]
    pub out: PathBuf,
    /// CONTACT's reference directory (with central/*.csv) [default: the repository's
    /// tests/data/reference, located when the command was built, so any working directory
    /// works]
    #[arg(long, value_name = "DIR")]
    pub reference: Option<PathBuf>,
    /// Draws the models alone, without reference data and error tables
    #[arg(long, conflicts_with = "reference")]
    pub no_reference: bool,
    /// The markdown document [default: DIR/report.md]; its figure links are relative to it
    #[arg(long, value_name = "FILE")]
    pub markdown: Option<PathBuf>,
    /// Draws the creep curves at the reference's creepages only (the error tables do not change)
    #[arg(long)]
    pub quick: bool,
}

/// The reference directory: `--reference`, else the repository's (if it exists), none with
/// `--no-reference`.
fn reference_dir(args: &ReportArgs) -> Result<Option<PathBuf>, Failure> {
    match &args.reference {
        Some(dir) if dir.is_dir() => Ok(Some(dir.clone())),
        Some(dir) => Err(Failure::Error(format!(
            "--reference {}: not a directory (expected CONTACT's reference directory with \
             central/*.csv)",
            dir.display()
        ))),
        None if args.no_reference => Ok(None),
        None => Ok(Some(workspace_root().join(REFERENCE_DIR)).filter(|d| d.is_dir())),
    }
}

/// The directory holding both benchmark profiles: next to the reference directory, else the
/// repository's `tests/data/profiles`.
fn profile_dir(reference: Option<&Path>) -> Option<PathBuf> {
    let beside = reference.and_then(Path::parent).map(|p| p.join("profiles"));
    [beside, Some(workspace_root().join(PROFILE_DIR))]
        .into_iter()
        .flatten()
        .find(|d| d.join(WHEEL_FILE).is_file() && d.join(RAIL_FILE).is_file())
}

/// The central case as FMU values: benchmark profiles from `profiles` (rail inclined in
/// the file), else the built-in S1002/UIC60 with 1:40.
fn central_values(profiles: Option<&Path>) -> Values {
    let mut v = Values::from_start(INFO.variables, INFO.counts);
    if let Some(dir) = profiles {
        v.strings[var::wheelProfile.0] = dir.join(WHEEL_FILE).to_string_lossy().into_owned();
        v.strings[var::railProfile.0] = dir.join(RAIL_FILE).to_string_lossy().into_owned();
        v.set_real(var::railInclination, 0.0);
    }
    v.set_real(var::E, 210e9);
    v.set_real(var::nu, 0.28);
    v.set_real(var::mu, 0.3);
    v.set_integer(var::verticalMode, 1);
    v.set_real(var::Qleft, CENTRAL_LOAD);
    v.set_real(var::Qright, CENTRAL_LOAD);
    for input in [var::y, var::yaw, var::roll, var::vy, var::yawRate] {
        v.set_real(input, 0.0);
    }
    v.set_integer(var::creepageMode, 1);
    v.set_real(var::vx, CENTRAL_SPEED);
    v.set_real(var::omega, CENTRAL_SPEED / v.real(var::wheelRadius));
    v
}

/// File name of a profile spec (a built-in name stays as it is).
fn profile_name(spec: &str) -> String {
    Path::new(spec)
        .file_name()
        .map_or_else(|| spec.to_string(), |n| n.to_string_lossy().into_owned())
}

/// One line describing the case, for the figure titles.
fn setup_line(v: &Values) -> String {
    format!(
        "right wheel, {} on {}, Q = {:.1} kN, y = {} mm",
        profile_name(v.string(var::wheelProfile)),
        profile_name(v.string(var::railProfile)),
        v.real(var::Qright) / 1e3,
        v.real(var::y) * 1e3
    )
}

/// Where the figures go, what they compare with, and the progress lines on stderr.
struct Output<'a> {
    dir: &'a Path,
    reference: Option<&'a Reference>,
    /// One line describing the case, for the titles.
    setup: String,
    /// Paths (SVG, PNG) of the figures written so far.
    files: Vec<[PathBuf; 2]>,
    start: Instant,
}

impl Output<'_> {
    /// Writes `figure` and prints its progress line ("[k/n] path … seconds since `started`").
    fn figure(&mut self, figure: ReportFigure, started: Instant) -> Result<(), Failure> {
        let paths = render(&figure, self.dir).map_err(Failure::Error)?;
        eprintln!(
            "railcontact report: [{}/{FIGURES}] {} (.svg, .png) in {:.2} s",
            self.files.len() + 1,
            paths[0].with_extension("").display(),
            started.elapsed().as_secs_f64()
        );
        self.files.push(paths);
        Ok(())
    }
}

/// Everything the figures and tables are drawn from.
struct Runs {
    normal: Vec<NormalRun>,
    unsmoothed: Option<NormalRun>,
    spin_planar: Vec<SpinRun>,
    spin_nonplanar: Vec<SpinRun>,
    shifts: Vec<ShiftRuns>,
    creep_own: Vec<CreepCurve>,
    creep_options: Vec<CreepCurve>,
}

/// `railcontact report`.
pub(crate) fn run(args: &ReportArgs) -> Result<i32, Failure> {
    plot::register_font().map_err(Failure::Error)?;
    let reference_dir = reference_dir(args)?;
    let reference = match &reference_dir {
        Some(dir) => Some(Reference::load(dir).map_err(Failure::Error)?),
        None => None,
    };
    let profiles = profile_dir(reference_dir.as_deref());
    let values = match &args.case {
        Some(path) => case::load(Some(path))?,
        None => central_values(profiles.as_deref()),
    };
    let study = Study::new(values)?;
    std::fs::create_dir_all(&args.out).map_err(|e| {
        Failure::Error(format!(
            "--out {}: cannot create the directory: {e}",
            args.out.display()
        ))
    })?;
    let mut out = Output {
        dir: &args.out,
        reference: reference.as_ref(),
        setup: setup_line(study.values()),
        files: Vec::new(),
        start: Instant::now(),
    };
    let (normal, unsmoothed) = normal_figures(&study, &mut out)?;
    let (spin_planar, spin_nonplanar) = spin_figures(&study, &mut out)?;
    let shifts = shift_figure(&study, &mut out)?;
    let grid: &[f64] = if args.quick {
        &CREEP_QUICK
    } else {
        &CREEP_FULL
    };
    let (creep_own, creep_options) = creep_figure(&study, &mut out, grid)?;
    let t = Instant::now();
    let panels = dissipation::panels(&study)?;
    let figure = Dissipation {
        panels: &panels,
        setup: out.setup.clone(),
    };
    out.figure(ReportFigure::Dissipation(figure), t)?;
    let t = Instant::now();
    let manchester = match (&reference_dir, &profiles) {
        (Some(reference), Some(profiles)) => {
            manchester::section(central_values(Some(profiles)), reference)?
        }
        _ => String::new(),
    };
    let wheel_forces = wheel::section(&study)? + &manchester + &dissipation::section(&panels);
    eprintln!(
        "railcontact report: wheel forces against the exact solution in {:.2} s",
        t.elapsed().as_secs_f64()
    );
    let runs = Runs {
        normal,
        unsmoothed,
        spin_planar,
        spin_nonplanar,
        shifts,
        creep_own,
        creep_options,
    };
    let rows = match out.reference {
        Some(r) => {
            let rows = error_rows(&study, &runs, r)?;
            write(&out.dir.join("errors.csv"), &tables::csv(&rows))?;
            Some(rows)
        }
        None => None,
    };
    let markdown = args
        .markdown
        .clone()
        .unwrap_or_else(|| args.out.join("report.md"));
    let md_dir = markdown
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(md_dir).map_err(|e| {
        Failure::Error(format!(
            "--markdown {}: cannot create its directory: {e}",
            markdown.display()
        ))
    })?;
    let links = out
        .files
        .iter()
        .map(|paths| paths.clone().map(|p| relative_link(md_dir, &p)))
        .collect::<Vec<_>>();
    let doc = Document {
        args,
        study: &study,
        runs: &runs,
        reference: out.reference,
        rows: rows.as_deref(),
        links: &links,
        wheel_forces: &wheel_forces,
    };
    write(&markdown, &doc.markdown())?;
    eprintln!(
        "railcontact report: {} written in {:.2} s",
        markdown.display(),
        out.start.elapsed().as_secs_f64()
    );
    Ok(0)
}

/// Patch outlines and pressure per strip of every normal model (and STRIPES-B without smoothing
/// of B, when the case smooths); returns the runs.
fn normal_figures(
    study: &Study,
    out: &mut Output,
) -> Result<(Vec<NormalRun>, Option<NormalRun>), Failure> {
    let t = Instant::now();
    let normal = NormalModel::ALL
        .iter()
        .map(|&m| study.central(m))
        .collect::<Result<Vec<_>, _>>()?;
    let outlines = Outlines {
        runs: &normal,
        reference: out.reference,
        setup: out.setup.clone(),
    };
    out.figure(ReportFigure::Outlines(outlines), t)?;

    let t = Instant::now();
    let unsmoothed = if study.b_smoothing() > 0.0 {
        let options = Options {
            b_smoothing: Some(0.0),
            ..Options::normal(NormalModel::StripesB)
        };
        Some(study.normal(options, study.values().real(var::y))?)
    } else {
        None
    };
    let pressure = Pressure {
        runs: &normal,
        unsmoothed: unsmoothed.as_ref(),
        reference: out.reference,
        setup: out.setup.clone(),
    };
    out.figure(ReportFigure::Pressure(pressure), t)?;
    Ok((normal, unsmoothed))
}

/// Pure spin of every normal model, planar and non-planar (one figure each, common colour scale
/// and axes); returns the runs.
fn spin_figures(study: &Study, out: &mut Output) -> Result<(Vec<SpinRun>, Vec<SpinRun>), Failure> {
    let mut t = Instant::now();
    let spin = |planar| -> Result<Vec<SpinRun>, Failure> {
        NormalModel::ALL
            .iter()
            .map(|&model| {
                let options = Options {
                    planar: Some(planar),
                    ..Options::normal(model)
                };
                study.spin(options, SPIN)
            })
            .collect()
    };
    let planar = spin(true)?;
    let nonplanar = spin(false)?;
    let all: Vec<SpinRun> = planar.iter().chain(&nonplanar).cloned().collect();
    let axes = figures::spin_axes(&all, out.reference);
    let scale_mpa = figures::spin_scale(&all, out.reference);
    for (runs, is_planar) in [(&planar, true), (&nonplanar, false)] {
        let figure = Spin {
            runs,
            reference: out.reference,
            planar: is_planar,
            scale_mpa,
            axes: axes.clone(),
        };
        out.figure(ReportFigure::Spin(figure), t)?;
        t = Instant::now();
    }
    Ok((planar, nonplanar))
}

/// Both STRIPES variants over [`SHIFTS_MM`]; returns the runs.
fn shift_figure(study: &Study, out: &mut Output) -> Result<Vec<ShiftRuns>, Failure> {
    let t = Instant::now();
    let shifts = SHIFTS_MM
        .iter()
        .map(|&y_mm| {
            let runs = [NormalModel::StripesB, NormalModel::StripesAB]
                .iter()
                .map(|&m| study.normal(Options::normal(m), y_mm * 1e-3))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(ShiftRuns {
                y: y_mm * 1e-3,
                runs,
            })
        })
        .collect::<Result<Vec<_>, Failure>>()?;
    let figure = Shifts {
        shifts: &shifts,
        reference: out.reference,
        setup: out
            .setup
            .split(", y =")
            .next()
            .unwrap_or_default()
            .to_string(),
    };
    out.figure(ReportFigure::Shifts(figure), t)?;
    Ok(shifts)
}

/// Creep curves over `grid`: every normal model with its own pairing, and ANALYN with the other
/// tangential options; returns (own pairings, ANALYN's options 2–4).
fn creep_figure(
    study: &Study,
    out: &mut Output,
    grid: &[f64],
) -> Result<(Vec<CreepCurve>, Vec<CreepCurve>), Failure> {
    let t = Instant::now();
    let creep = |model, tangential| {
        let options = Options {
            tangential: Some(tangential),
            planar: Some(true),
            ..Options::normal(model)
        };
        study.creep_curve(options, grid)
    };
    let own = NormalModel::ALL
        .iter()
        .map(|&m| creep(m, TangentialModel::ModelDefault))
        .collect::<Result<Vec<_>, _>>()?;
    let others = TangentialModel::ALL[1..]
        .iter()
        .map(|&t| creep(NormalModel::Analyn, t))
        .chain([
            creep(NormalModel::CoupledStrips, TangentialModel::Fastrip),
            creep(NormalModel::CoupledStrips, TangentialModel::FastripCoupled),
        ])
        .collect::<Result<Vec<_>, _>>()?;
    let mut by_option: Vec<&CreepCurve> = own
        .iter()
        .filter(|c| matches!(c.model, NormalModel::Analyn | NormalModel::Hertz))
        .collect();
    by_option.extend(&others);
    let figure = Creep {
        rows: vec![
            (
                "Every normal model with its own tangential pairing (tangentialModel 1)"
                    .to_string(),
                own.iter().collect(),
            ),
            (
                "ANALYN with each tangential option (tangentialModel 1–5), Hertz, and the coupled \
                 strips with FaStrip (3, 5)"
                    .to_string(),
                by_option,
            ),
        ],
        reference: out.reference,
        setup: out.setup.clone(),
    };
    out.figure(ReportFigure::Creep(figure), t)?;
    Ok((own, others))
}

/// The error table against `r`.
fn error_rows(study: &Study, runs: &Runs, r: &Reference) -> Result<Vec<tables::ErrorRow>, Failure> {
    let curves: Vec<&CreepCurve> = runs.creep_own.iter().chain(&runs.creep_options).collect();
    let mut rows = tables::central_rows(&runs.normal, r);
    rows.extend(tables::spin_rows(&runs.spin_planar, r));
    rows.extend(tables::spin_rows(&runs.spin_nonplanar, r));
    rows.extend(tables::creep_rows(study, &curves, r)?);
    Ok(rows)
}

fn write(path: &Path, text: &str) -> Result<(), Failure> {
    std::fs::write(path, text)
        .map_err(|e| Failure::Error(format!("{}: cannot write: {e}", path.display())))
}

/// The markdown document: what is compared, how to regenerate it, the set-up, the error tables,
/// the models' own figures and the figures.
struct Document<'a> {
    args: &'a ReportArgs,
    study: &'a Study,
    runs: &'a Runs,
    reference: Option<&'a Reference>,
    rows: Option<&'a [tables::ErrorRow]>,
    /// Links (SVG, PNG) of the figures, relative to the document.
    links: &'a [[String; 2]],
    /// The wheel-level section ([`wheel::section`]).
    wheel_forces: &'a str,
}

/// Captions of the figures, in drawing order.
const CAPTIONS: [&str; FIGURES] = [
    "Patch outlines (leading and trailing edge per strip) of every normal model over CONTACT's.",
    "Maximum pressure per strip along the rail's lateral coordinate.",
    "Pure spin 0.052 rad/m, planar patches: |traction| and slip elements.",
    "Pure spin 0.052 rad/m, non-planar patches (each strip its own contact angle and creepages).",
    "STRIPES-B and STRIPES-A&B at lateral shifts −1, 0, +1, +2 mm: outline, strip pressure, \
     lateral curvature B.",
    "Creep-force curves Fx(ξ) and Fy(η) over μN, planar patches.",
    "Frictional power density across the patch (Tγ per unit width) at lateral shifts 0 and \
     +2 mm, ξ = 0.002 with the rolling spin: every normal model with its own tangential pairing \
     against the exact steady rolling solution.",
];

impl Document<'_> {
    fn markdown(&self) -> String {
        let mut md = String::from("# Validation against Kalker's exact theory\n\n");
        md.push_str(&self.intro());
        md.push_str(&self.setup());
        md.push_str(&self.errors());
        md.push_str(self.wheel_forces);
        md.push_str(&self.model_figures());
        md.push_str(&self.figures());
        md
    }

    /// What is compared and how to regenerate.
    fn intro(&self) -> String {
        let mut md = String::new();
        let _ = writeln!(
            md,
            "railcontact's normal models (`normalModel` 1–7) and tangential options \
             (`tangentialModel` 1–5) against CONTACT, which solves Kalker's exact half-space \
             theory, on the central case of `tests/data/README.md`: normal contact (patch area, \
             maximum pressure, maximum pressure per strip), pure spin (forces, spin moment, slip \
             zone) and creep-force curves; the wheel's forces over lateral shifts against the \
             exact solution of the whole wheel (\"Wheel forces\"), and on the Manchester \
             benchmark's yawed wheelset against CONTACT's solution of each wheel; and the \
             frictional power \
             across the patch against the exact steady rolling solution (\"Frictional power \
             across the patch\"). CONTACT's numbers are read from \
             its solutions in the reference directory; railcontact's are computed by the FMU's own \
             code at its default settings.\n"
        );
        let _ = writeln!(
            md,
            "This document, the figures and `errors.csv` are the output of one command; edit the \
             command, not the document:\n\n```sh\n{}\n```\n",
            command(self.args)
        );
        let _ = writeln!(
            md,
            "`cargo test -p railcontact-cli --test report` regenerates them into a temporary \
             directory and fails if the repository's `docs/validation.md` or \
             `docs/figures/errors.csv` differ.\n"
        );
        md
    }

    /// The case, the models' settings and the reference.
    fn setup(&self) -> String {
        let v = self.study.values();
        let mut md = String::from("## Set-up\n\n");
        let case = match &self.args.case {
            Some(c) => format!("case file `{c}` (keys not given keep the FMU's start values)"),
            None => "the central case (no case file)".to_string(),
        };
        let _ = writeln!(md, "* Case: {case}.");
        let inclination = v.real(var::railInclination);
        let _ = writeln!(
            md,
            "* Profiles: wheel `{}` on rail `{}`, rail inclination {} rad{}; gauge {} mm, \
             flange-back distance {} mm, nominal radius {} mm.",
            profile_name(v.string(var::wheelProfile)),
            profile_name(v.string(var::railProfile)),
            inclination,
            if inclination == 0.0 {
                " (inclined in the file)"
            } else {
                ""
            },
            v.real(var::trackGauge) * 1e3,
            v.real(var::flangeBackDistance) * 1e3,
            v.real(var::wheelRadius) * 1e3
        );
        let _ = writeln!(
            md,
            "* Material and load: E = {} GPa, ν = {}, μ = {}, Qleft = {} kN, Qright = {} kN; \
             lateral shift y = {} mm, yaw {} rad.",
            v.real(var::E) / 1e9,
            v.real(var::nu),
            v.real(var::mu),
            v.real(var::Qleft) / 1e3,
            v.real(var::Qright) / 1e3,
            v.real(var::y) * 1e3,
            v.real(var::yaw)
        );
        let _ = writeln!(
            md,
            "* Models: {} strips per patch, FASTSIM {} × {}; normal-contact figures with the \
             case's creepages (creepageMode {}, vx = {} m/s); tangential figures with prescribed \
             creepages (creepageMode 2). Results are the right wheel's.",
            v.integer(var::nStrips),
            v.integer(var::nx),
            v.integer(var::ny),
            v.integer(var::creepageMode),
            v.real(var::vx)
        );
        match self.reference {
            Some(r) => {
                let _ = writeln!(
                    md,
                    "* Reference: CONTACT (Kalker's exact theory) in `{}`, central case (its \
                     set-up: benchmark profiles, 78.5 kN, centred).",
                    shown_path(&r.dir)
                );
                if self.args.case.is_some() {
                    let _ = writeln!(
                        md,
                        "* Note: the reference solves the central case, not this case file's; \
                         where the two differ the errors below are not errors of the models."
                    );
                }
            }
            None => {
                let _ = writeln!(
                    md,
                    "* Reference: none (`--no-reference`, or no `--reference DIR` and no \
                     `{REFERENCE_DIR}` in the repository): the figures show the models alone \
                     and the error table is omitted."
                );
            }
        }
        if self.args.quick {
            let _ = writeln!(
                md,
                "* `--quick`: the creep curves are drawn at the reference's creepages only."
            );
        }
        md.push('\n');
        md
    }

    /// The error tables against the reference.
    fn errors(&self) -> String {
        let mut md = String::from("## Errors against the exact theory\n\n");
        match (self.rows, self.reference) {
            (Some(rows), Some(r)) => {
                md.push_str(&tables::markdown(rows, r));
                let _ = writeln!(
                    md,
                    "\nThe same numbers in `errors.csv` (errors in % unless stated; creep-curve \
                     errors in units of μN at CONTACT's creepages, zero point skipped). \
                     \"Strip-pmax RMS\" is the root-mean-square difference of the maximum \
                     pressure per strip along the rail's lateral coordinate (the model \
                     interpolated at CONTACT's strips, zero outside its patch): it measures the \
                     pressure distribution rather than its peak."
                );
            }
            _ => {
                let _ = writeln!(
                    md,
                    "No reference data: the error table is omitted. Pass `--reference DIR` \
                     (CONTACT's reference directory, e.g. `{REFERENCE_DIR}`)."
                );
            }
        }
        md
    }

    /// The models' own figures: patches, areas and peaks; lateral shifts; pure spin.
    fn model_figures(&self) -> String {
        let (runs, reference, v) = (self.runs, self.reference, self.study.values());
        let mut md = String::new();
        let _ = writeln!(md, "\n## Model figures\n");
        let _ = writeln!(md, "| model | patches | area mm² | pmax MPa |");
        let _ = writeln!(md, "|---|---|---|---|");
        let unsmoothed = runs.unsmoothed.iter().map(|run| (run, ", bSmoothing = 0"));
        for (run, variant) in runs.normal.iter().map(|run| (run, "")).chain(unsmoothed) {
            let _ = writeln!(
                md,
                "| {}{variant} | {} | {:.2} | {:.2} |",
                plot::model_label(run.model),
                run.patches.len(),
                run.totals.area * 1e6,
                run.totals.pmax * 1e-6
            );
        }
        let _ = writeln!(md, "\nLateral shifts (STRIPES):\n");
        let _ = writeln!(md, "| y mm | model | area mm² | pmax MPa |");
        let _ = writeln!(md, "|---|---|---|---|");
        for shift in &runs.shifts {
            for run in &shift.runs {
                let _ = writeln!(
                    md,
                    "| {} | {} | {:.2} | {:.2} |",
                    figures::signed_mm(shift.y),
                    plot::model_label(run.model),
                    run.totals.area * 1e6,
                    run.totals.pmax * 1e-6
                );
            }
        }
        let _ = writeln!(
            md,
            "\nPure spin φ = {SPIN} rad/m (tangentialModel {}); the slip zone's centroid in yRail and \
             x:\n",
            v.integer(var::tangentialModel)
        );
        let _ = writeln!(
            md,
            "| model | planar | Fx N | Fy N | Mz N·m | slip share | slip centroid yRail mm | x mm |"
        );
        let _ = writeln!(md, "|---|---|---|---|---|---|---|---|");
        let centroid = |c: Option<(f64, f64)>| {
            c.map_or_else(
                || "– | –".to_string(),
                |(y, x)| format!("{:.2} | {:.2}", y * 1e3, x * 1e3),
            )
        };
        if let Some(r) = reference {
            let slip: Vec<_> = r.traction.iter().filter(|e| e.slip).collect();
            let n = slip.len().max(1) as f64;
            let c = (!slip.is_empty()).then(|| {
                (
                    slip.iter().map(|e| e.y_rail_mm).sum::<f64>() / n * 1e-3,
                    slip.iter().map(|e| e.x_mm).sum::<f64>() / n * 1e-3,
                )
            });
            let s = &r.spin;
            let [fx, fy, mz, slip] = tables::spin_cells(s.fx_n, s.fs_n, s.mz_nm(), s.slip_share());
            let _ = writeln!(
                md,
                "| CONTACT (exact) | yes | {fx} | {fy} | {mz} | {slip} | {} |",
                centroid(c)
            );
        }
        let nonplanar_strips = runs
            .spin_nonplanar
            .iter()
            .filter(|r| r.model != NormalModel::Hertz);
        for run in runs.spin_planar.iter().chain(nonplanar_strips) {
            let t = &run.normal.totals;
            let [fx, fy, mz, slip] =
                tables::spin_cells(t.fx, t.fy, t.mz, 100.0 * (1.0 - t.adhesion));
            let _ = writeln!(
                md,
                "| {} | {} | {fx} | {fy} | {mz} | {slip} | {} |",
                plot::model_label(run.model),
                if run.planar || run.model == NormalModel::Hertz {
                    "yes"
                } else {
                    "no"
                },
                centroid(study::slip_centroid(&run.cells))
            );
        }
        md
    }

    /// The figures, PNG with a link to the SVG.
    fn figures(&self) -> String {
        let mut md = String::from("\n## Figures\n\n");
        for ([svg, png], caption) in self.links.iter().zip(CAPTIONS) {
            let _ = writeln!(md, "![{caption}]({png})\n\n{caption} ([SVG]({svg}))\n");
        }
        md
    }
}

/// The command line that regenerates the document, with paths inside the repository relative
/// to its root.
fn command(args: &ReportArgs) -> String {
    let mut c = String::from("cargo run --release -p railcontact-cli -- report");
    if let Some(case) = &args.case {
        let _ = write!(c, " {case}");
    }
    let _ = write!(c, " --out {}", shown_path(&args.out));
    if let Some(r) = &args.reference {
        let _ = write!(c, " --reference {}", shown_path(r));
    }
    if args.no_reference {
        c.push_str(" --no-reference");
    }
    if let Some(m) = &args.markdown {
        let _ = write!(c, " --markdown {}", shown_path(m));
    }
    if args.quick {
        c.push_str(" --quick");
    }
    c
}

/// `path` relative to the repository's root if it lies inside it (so that the document does not
/// depend on where the repository is checked out), else as given.
fn shown_path(path: &Path) -> String {
    let root = workspace_root().canonicalize().ok();
    let inside = path
        .canonicalize()
        .ok()
        .zip(root)
        .and_then(|(p, r)| p.strip_prefix(&r).ok().map(Path::to_path_buf));
    match inside {
        Some(relative) => slash_path(&relative),
        None => path.display().to_string(),
    }
}

/// The link from a document in `dir` to `target` (both existing): relative, with '/'.
fn relative_link(dir: &Path, target: &Path) -> String {
    match (dir.canonicalize(), target.canonicalize()) {
        (Ok(from), Ok(to)) => slash_path(&relative_path(&from, &to)),
        _ => slash_path(target),
    }
}

/// `to` relative to the directory `from` (both absolute and normalised).
fn relative_path(from: &Path, to: &Path) -> PathBuf {
    let (from, to): (Vec<_>, Vec<_>) = (from.components().collect(), to.components().collect());
    let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
    let mut out = PathBuf::new();
    for _ in common..from.len() {
        out.push("..");
    }
    for c in &to[common..] {
        out.push(c);
    }
    out
}

/// A relative path written with '/' between its components (an absolute one as it is).
fn slash_path(path: &Path) -> String {
    if path.has_root() {
        return path.display().to_string();
    }
    path.components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect::<Vec<_>>()
        .join("/")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, clap::Parser)]
    struct Cli {
        #[command(flatten)]
        report: ReportArgs,
    }

    fn parse(list: &[&str]) -> Result<ReportArgs, clap::Error> {
        use clap::Parser;
        Cli::try_parse_from(std::iter::once("report").chain(list.iter().copied())).map(|c| c.report)
    }

    #[test]
    fn options_are_parsed() {
        let a = parse(&["c.json", "--out", "x", "--quick"]).unwrap();
        assert_eq!(a.case.as_deref(), Some("c.json"));
        assert_eq!(a.out, PathBuf::from("x"));
        assert!(a.quick);
        let a = parse(&["--reference", "/nonexistent/dir"]).unwrap();
        assert!(reference_dir(&a).is_err());
        assert!(parse(&["--bogus"]).is_err());
        assert!(parse(&["--reference", "r", "--no-reference"]).is_err());
        let a = parse(&[]).unwrap();
        assert_eq!(a.out, PathBuf::from("report"));
        // The default reference is the repository's, whatever the working directory.
        let default = reference_dir(&a)
            .unwrap()
            .expect("the repository's reference data");
        assert!(default.is_absolute() && default.ends_with(REFERENCE_DIR));
        assert_eq!(shown_path(&default), REFERENCE_DIR);
        assert_eq!(
            reference_dir(&parse(&["--no-reference"]).unwrap()),
            Ok(None)
        );
    }

    #[test]
    fn links_are_relative_to_the_document() {
        let p = |s: &str| PathBuf::from(s);
        assert_eq!(
            relative_path(&p("/r/docs"), &p("/r/docs/figures/a.png")),
            p("figures/a.png")
        );
        assert_eq!(relative_path(&p("/r/out"), &p("/r/out/a.png")), p("a.png"));
        assert_eq!(
            relative_path(&p("/r/a/b"), &p("/r/c/d.png")),
            p("../../c/d.png")
        );
        assert_eq!(slash_path(&p("figures/a.png")), "figures/a.png");
        assert_eq!(slash_path(&p("/tmp/a.png")), "/tmp/a.png");
    }

    #[test]
    fn seed_values_are_the_central_case() {
        let v = central_values(Some(Path::new("/p")));
        assert_eq!(v.string(var::wheelProfile), "/p/MBench_S1002_v3.prw");
        assert_eq!(v.real(var::railInclination), 0.0);
        assert_eq!(v.real(var::Qright), 78_500.0);
        assert_eq!(v.real(var::omega), 2.0 / 0.46);
        let builtin = central_values(None);
        assert_eq!(builtin.string(var::wheelProfile), "S1002");
        assert!(builtin.real(var::railInclination) > 0.02);
    }
}
