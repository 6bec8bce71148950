//! `railcontact`: the `WheelRailContact` FMU's model on the command line.
//!
//! * `railcontact solve [CASE.json] [--grid NX] [--traction]` — one evaluation, printed as JSON
//!   ([`railcontact_cli::solve`]);
//! * `railcontact sweep [CASE.json] [--from Y0] [--to Y1] [--step DY]` — a text table over the
//!   lateral shift `y` ([`railcontact_cli::sweep`]);
//! * `railcontact conicity [CASE.json] [--amplitudes A,..] [--step DY] [--no-roll] [--load Q] [--out DIR]`
//!   — the equivalent conicity (EN 15302) as JSON, with CSV tables and a figure in DIR
//!   ([`railcontact_cli::conicity`], [`conicity_figure`]);
//! * `railcontact report [CASE.json] [--out DIR] [--reference DIR] [--markdown FILE] [--quick]`
//!   — the validation against CONTACT: figures, error tables and the validation document
//!   ([`report`]).
//!
//! Exit codes: 0 success, 1 usage / case / profile / value error, 2 step refused (no contact
//! inside the profiles, or a load the normal model cannot carry), 3 implausible contact state
//! (outputs printed, but beyond elastic half-space contact: [`railcontact::wheelset::validity`]).

mod conicity_figure;
mod report;

use clap::error::ErrorKind;
use clap::{Args, Parser, Subcommand};
use railcontact::models::wheel_rail_contact::generated::var;
use railcontact_cli::conicity::ConicityOptions;
use railcontact_cli::solve::{Extras, GRID_POINTS};
use railcontact_cli::sweep::SweepRange;
use railcontact_cli::{case, conicity, json, solve, sweep, Failure, IMPLAUSIBLE};
use std::io::Write as _;
use std::path::PathBuf;

const CASE_HELP: &str = "\
CASE.json is a JSON object whose keys are parameters and inputs of the WheelRailContact FMU
(modelDescription/WheelRailContact.json), in SI units, e.g.
  {\"y\": 0.004, \"Qright\": 90000, \"wheelProfile\": \"worn.prw\", \"mu\": 0.4}
Keys not given keep their start values; unknown keys, duplicate keys, wrong types and values
outside a variable's range are errors. Without a file (or with '-' for standard input): the
built-in S1002 wheel on UIC60 rails at the start values. Relative profile paths are looked up
next to the case file first, then in the working directory.

Profile files are checked when loaded (units, flange side, coverage of the running surface,
gaps, steps and spikes the smoothing cannot absorb); a failed check is exit code 1 with the
file, the reason and the fix.";

const EXIT_CODES: &str = "\
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
     (solve; sweep if any row is marked)";

/// railcontact - the WheelRailContact FMU's wheel-rail contact model on the command line
#[derive(Debug, Parser)]
#[command(
    name = "railcontact",
    version,
    args_override_self = true,
    after_help = format!("{CASE_HELP}\n\n{EXIT_CODES}"),
    override_usage = "\
railcontact solve [CASE.json] [--grid NX] [--traction]
       railcontact sweep [CASE.json] [--from Y0] [--to Y1] [--step DY]
       railcontact conicity [CASE.json] [--amplitudes A,..] [--step DY] [--no-roll] [--load Q] [--out DIR]
       railcontact report [CASE.json] [--out DIR] [--reference DIR] [--markdown FILE] [--quick]
       railcontact help [COMMAND] | --help | -h"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    Solve(SolveArgs),
    Sweep(SweepArgs),
    Conicity(ConicityArgs),
    Wear(WearArgs),
    Report(report::ReportArgs),
}

/// Updates the case's profiles by the wear that runs of the FMU recorded
///
/// Reads wear records (the CSV files the FMU writes to `wearOutput` with a `wearModel`), sums
/// them, scales their depths to a running distance, smooths them, limits the largest depth, and
/// writes the worn wheel and rail profiles as two-column text in mm (the wheel in its profile's
/// frame, the rail in the mounted frame: use it with railInclination = 0). The written files are
/// checked by loading them as the element does. Prints a JSON summary.
#[derive(Debug, Args)]
#[command(after_help = format!("{CASE_HELP}\n\n{EXIT_CODES}"))]
struct WearArgs {
    /// The case file the records were made with ('-': standard input; none: the start values)
    #[arg(value_name = "CASE.json")]
    case: Option<String>,
    /// A wear record (repeat for several runs; their masses and distances add up)
    #[arg(long = "record", value_name = "FILE", required = true)]
    records: Vec<PathBuf>,
    /// The running distance the update stands for [m], > 0
    #[arg(long, value_name = "METRES")]
    distance: f64,
    /// The largest depth one update removes [m] (the distance is reduced to it)
    #[arg(long, value_name = "METRES", default_value_t = railcontact_cli::wear::DEFAULT_MAX_DEPTH)]
    max_depth: f64,
    /// Standard deviation of the Gaussian smoothing of the depths [m]
    #[arg(long, value_name = "METRES", default_value_t = railcontact_cli::wear::DEFAULT_SMOOTHING)]
    smoothing: f64,
    /// Directory of the worn profiles (worn_wheel.txt, worn_rail.txt; created if missing)
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

/// Evaluates the model once and prints every output and each patch's strips as JSON
///
/// Evaluates the model once (the FMU's own code) and prints a JSON object: every output by name
/// (nPatches as integers), and "strips": for each patch in contact ("left.p1", ...) its strips
/// across the rolling direction (Hertz: the ellipse cut into 21 strips; normalModel 2-7: the
/// model's own strips in contact), each with s [m] (lateral coordinate in the contact plane,
/// towards the field side), yRail [m], xLead, xTrail [m] (leading and trailing edge), pmax [Pa]
/// (strip maximum pressure), A, B [1/m] (relative curvatures; B as the strip geometry gives it,
/// before any floor).
#[derive(Debug, Args)]
#[command(after_help = format!("{CASE_HELP}\n\n{EXIT_CODES}"))]
struct SolveArgs {
    /// The case file ('-': standard input; none: the start values)
    #[arg(value_name = "CASE.json")]
    case: Option<String>,
    /// Adds "grid": per patch the pressure at NX element centres along each strip, as [x, s, p]
    /// triples (m, m, Pa); NX in [2, 1000]
    #[arg(long, value_name = "NX", value_parser = grid_points)]
    grid: Option<usize>,
    /// Adds "traction": per patch every element of the tangential solution as
    /// [x, s, px, py, slip] (m, m, Pa, Pa, 1 slip / 0 adhesion); px along the rolling direction,
    /// py along the element's lateral axis, forces of the rail on the wheel
    #[arg(long)]
    traction: bool,
}

/// Evaluates the model over a range of lateral shifts and prints a table
///
/// Evaluates the model over the lateral shift y and prints a table per wheel: number of patches,
/// then per patch yRail [mm], contact angle [rad], normal force Fn [kN], rolling radius [mm], and
/// the wheel's total lateral force Fy [kN]. Shifts where the wheel leaves the profiles get a note
/// instead of numbers; implausible states (exit code 3) get their numbers and a warning at the
/// end of the row. The case's y is ignored.
#[derive(Debug, Args)]
#[command(after_help = format!("{CASE_HELP}\n\n{EXIT_CODES}"))]
struct SweepArgs {
    /// The case file ('-': standard input; none: the start values)
    #[arg(value_name = "CASE.json")]
    case: Option<String>,
    /// First lateral shift [m]
    #[arg(long, value_name = "Y0", default_value_t = -0.002, allow_negative_numbers = true)]
    from: f64,
    /// Last lateral shift [m]
    #[arg(
        long,
        value_name = "Y1",
        default_value_t = 0.008,
        allow_negative_numbers = true
    )]
    to: f64,
    /// Step between shifts [m], > 0; at most 100000 rows
    #[arg(
        long,
        value_name = "DY",
        default_value_t = 0.0005,
        allow_negative_numbers = true
    )]
    step: f64,
}

/// Computes the equivalent conicity (EN 15302) of the case's profiles on its track
///
/// Shifts the rigid wheelset laterally by y on its track (the case's wheelProfile, railProfile,
/// profileSmoothing, railInclination, trackGauge, flangeBackDistance, wheelRadius, scanStep; the
/// rest of the case is ignored), lets it roll until both wheels touch their rails, and takes the
/// rolling-radius difference dr(y) = r_right - r_left. Prints JSON: the set-up, r0 and e0 (mean
/// rolling radius and half the contact-point distance of the centred wheelset) [m], "conicity"
/// per amplitude A [m] (harmonic linearisation, EN 15302 Annex C; Klingel integration, Annex B,
/// with its wavelength [m]; null where the motion does not oscillate) and "deltaR" per shift
/// (y, deltaR, roll, rRight, rLeft, yRailRight, yRailLeft: the contact points in the mounted
/// rail frames, yWheelRight, yWheelLeft: in the wheel profile frames, contactAngleRight,
/// contactAngleLeft; m and rad).
///
/// With --load Q the rolling radii are the loaded element's instead (the case's normal model
/// and settings, Q [N] on each wheel, zero creepage, no roll): each wheel's normal-force-weighted
/// rolling radius over its patches, the radius where the load is — the same definition as the
/// FMU's rollingRadius outputs.
///
/// With --out DIR it also writes DIR/conicity.json, DIR/conicity.csv (lambda per amplitude),
/// DIR/delta_r.csv and the figure DIR/conicity.svg and DIR/conicity.png.
#[derive(Debug, Args)]
#[command(after_help = format!("{CASE_HELP}\n\n{EXIT_CODES}"))]
struct ConicityArgs {
    /// The case file ('-': standard input; none: the start values, S1002 on UIC60 at 1:40)
    #[arg(value_name = "CASE.json")]
    case: Option<String>,
    /// Amplitudes of the lateral motion [m], comma-separated, each in (0, 0.02]
    #[arg(
        long,
        value_name = "A,..",
        value_delimiter = ',',
        default_values_t = railcontact::wheelset::conicity::DEFAULT_AMPLITUDES
    )]
    amplitudes: Vec<f64>,
    /// Step between the lateral shifts of dr(y) [m], > 0
    #[arg(long, value_name = "DY", default_value_t = railcontact::wheelset::conicity::DEFAULT_Y_STEP)]
    step: f64,
    /// Keeps the wheelset level (no roll): each wheel touches its rail on its own
    #[arg(long)]
    no_roll: bool,
    /// The loaded element's rolling radii under this vertical load per wheel [N], > 0
    #[arg(long, value_name = "Q")]
    load: Option<f64>,
    /// Writes the JSON, the CSV tables and the figure into this directory (created if missing)
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
}

/// `--grid`: a whole number of points per strip in [`GRID_POINTS`].
fn grid_points(text: &str) -> Result<usize, String> {
    text.trim()
        .parse::<usize>()
        .ok()
        .filter(|n| GRID_POINTS.contains(n))
        .ok_or_else(|| {
            format!(
                "expected a whole number of points per strip in [{}, {}]",
                GRID_POINTS.start(),
                GRID_POINTS.end()
            )
        })
}

fn main() {
    let code = match Cli::try_parse() {
        Ok(cli) => match run(cli.command) {
            Ok(code) => code,
            Err(f) => {
                eprintln!("railcontact: {}", f.message());
                f.code()
            }
        },
        Err(e) => usage(&e),
    };
    std::process::exit(code);
}

/// Prints clap's help, version or usage error; the exit code: 0 for help and version, else 1.
fn usage(e: &clap::Error) -> i32 {
    let _ = e.print();
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => 0,
        _ => 1,
    }
}

fn run(command: Command) -> Result<i32, Failure> {
    match command {
        Command::Solve(a) => {
            let mut values = case::load(a.case.as_deref())?;
            let extras = Extras {
                grid: a.grid,
                traction: a.traction,
            };
            let (doc, warning) = solve::solve(&mut values, extras)?;
            let text = json::to_text(&doc)
                .map_err(|e| Failure::Error(format!("cannot write the JSON: {e}")))?;
            emit(&text)?;
            Ok(match warning {
                None => 0,
                Some(m) => {
                    eprintln!("railcontact: warning: {m}");
                    IMPLAUSIBLE
                }
            })
        }
        Command::Sweep(a) => {
            let values = case::load(a.case.as_deref())?;
            let range = SweepRange {
                from: a.from,
                to: a.to,
                step: a.step,
            };
            let (table, outcome) = sweep::sweep(values, range)?;
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
        Command::Conicity(a) => run_conicity(&a),
        Command::Wear(a) => run_wear(&a),
        Command::Report(a) => report::run(&a),
    }
}

fn run_wear(a: &WearArgs) -> Result<i32, Failure> {
    let values = case::load(a.case.as_deref())?;
    let options = railcontact_cli::wear::WearOptions {
        records: a.records.clone(),
        distance: a.distance,
        max_depth: a.max_depth,
        smoothing: a.smoothing,
        out: a.out.clone(),
    };
    let doc = railcontact_cli::wear::update(&values, &options)?;
    let text =
        json::to_text(&doc).map_err(|e| Failure::Error(format!("cannot write the JSON: {e}")))?;
    println!("{text}");
    Ok(0)
}

fn run_conicity(a: &ConicityArgs) -> Result<i32, Failure> {
    let values = case::load(a.case.as_deref())?;
    let options = ConicityOptions {
        amplitudes: a.amplitudes.clone(),
        step: a.step,
        roll: !a.no_roll,
        load: a.load,
    };
    let run = conicity::conicity(&values, &options)?;
    let doc = conicity::to_json(&values, &run);
    let text =
        json::to_text(&doc).map_err(|e| Failure::Error(format!("cannot write the JSON: {e}")))?;
    if let Some(dir) = &a.out {
        let write = |name: &str, content: &str| {
            let path = dir.join(name);
            std::fs::write(&path, content)
                .map_err(|e| Failure::Error(format!("{}: cannot write: {e}", path.display())))
        };
        std::fs::create_dir_all(dir)
            .map_err(|e| Failure::Error(format!("{}: cannot create: {e}", dir.display())))?;
        write("conicity.json", &text)?;
        write("conicity.csv", &conicity::conicity_csv(&run))?;
        write("delta_r.csv", &conicity::delta_r_csv(&run))?;
        report::plot::register_font().map_err(Failure::Error)?;
        let setup = format!(
            "{} on {}, inclination {:.4} rad, gauge {} mm, flange backs {} mm{}",
            values.string(var::wheelProfile),
            values.string(var::railProfile),
            values.real(var::railInclination),
            values.real(var::trackGauge) * 1e3,
            values.real(var::flangeBackDistance) * 1e3,
            if options.roll { "" } else { ", no roll" }
        );
        let figure = conicity_figure::ConicityFigure { run: &run, setup };
        report::plot::render(&figure, dir).map_err(Failure::Error)?;
    }
    emit(&text)?;
    Ok(0)
}

/// Writes `text` to standard output (an error such as a closed pipe is a failure, not a panic).
fn emit(text: &str) -> Result<(), Failure> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| Failure::Error(format!("cannot write the output: {e}")))
}

/// The workspace root (the repository), as known when the command was built.
fn workspace_root() -> PathBuf {
    let manifest = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().unwrap_or(manifest).to_path_buf()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<Cli, clap::Error> {
        Cli::try_parse_from(std::iter::once("railcontact").chain(args.iter().copied()))
    }

    #[test]
    fn the_command_line_is_consistent() {
        use clap::CommandFactory;
        Cli::command().debug_assert();
    }

    #[test]
    fn options_and_case_file() {
        let Command::Sweep(a) = parse(&["sweep", "c.json", "--from", "-0.001", "--to=0.002"])
            .unwrap()
            .command
        else {
            panic!("sweep");
        };
        assert_eq!(a.case.as_deref(), Some("c.json"));
        assert_eq!((a.from, a.to, a.step), (-0.001, 0.002, 0.0005));
        assert!(parse(&["solve", "--bogus"]).is_err());
        assert!(parse(&["solve", "a", "b"]).is_err());
        // The last of a repeated option counts.
        let Command::Solve(a) = parse(&["solve", "--grid", "3", "--grid", "5"])
            .unwrap()
            .command
        else {
            panic!("solve");
        };
        assert_eq!(a.grid, Some(5));
        let e = parse(&["solve", "--grid", "1"]).unwrap_err();
        assert!(
            e.to_string().contains("points per strip in [2, 1000]"),
            "{e}"
        );
        let Command::Solve(a) = parse(&["solve", "-"]).unwrap().command else {
            panic!("solve");
        };
        assert_eq!(a.case.as_deref(), Some("-"));
    }
}
