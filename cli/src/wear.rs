//! `railcontact wear`: the wear-prediction loop's profile update (docs/theory.md §10.6,
//! [`railcontact::damage::update`]): wear records written by the FMU (`wearOutput`) turned into
//! worn wheel and rail profiles that the element reads.
//!
//! The case is read as `solve` reads it: its profiles (`wheelProfile`, `railProfile`,
//! `profileSmoothing`) and track set-up (`railInclination` and the rest) are the ones the
//! records were made with. The worn wheel is written in the wheel profile's frame; the worn rail
//! in the **mounted** rail's frame (inclined by `railInclination` and referred to its top, as the
//! records' rail coordinate is), so it is used with `railInclination` = 0. Both files are
//! two-column text in mm and are checked by loading them as the element does.

use crate::Failure;
use railcontact::damage::update::{at_bins, worn_points, WearRecords};
use railcontact::fmi::variables::Values;
use railcontact::geometry::profile::{Profile, ProfileKind};
use railcontact::geometry::track::MountedRail;
use railcontact::models::wheel_rail_contact::{generated::var, profiles, settings};
use serde_json::{json, Value};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// What the update does.
#[derive(Debug, Clone, PartialEq)]
pub struct WearOptions {
    /// The records (CSV files of `wearOutput`).
    pub records: Vec<PathBuf>,
    /// Running distance the update stands for [m], > 0.
    pub distance: f64,
    /// Largest depth removed by the update [m], > 0.
    pub max_depth: f64,
    /// Smoothing of the depths: the Gaussian's standard deviation [m], ≥ 0.
    pub smoothing: f64,
    /// Directory of the worn profiles.
    pub out: PathBuf,
}

/// The largest depth one update removes unless told [m].
pub const DEFAULT_MAX_DEPTH: f64 = 1e-4;
/// The Gaussian smoothing of the depths unless told: its standard deviation [m].
pub const DEFAULT_SMOOTHING: f64 = 1e-3;

/// File names of the worn profiles and of the depths removed in the output directory.
pub const WORN_WHEEL: &str = "worn_wheel.txt";
pub const WORN_RAIL: &str = "worn_rail.txt";
pub const DEPTHS: &str = "depth.csv";

/// Runs the update for the case `values`; returns the summary JSON.
pub fn update(values: &Values, options: &WearOptions) -> Result<Value, Failure> {
    let positive = |name: &str, v: f64| {
        if v > 0.0 && v.is_finite() {
            Ok(())
        } else {
            Err(Failure::Error(format!("{name} = {v} must be > 0 (finite)")))
        }
    };
    positive("--distance", options.distance)?;
    positive("--max-depth", options.max_depth)?;
    if !(options.smoothing >= 0.0 && options.smoothing.is_finite()) {
        return Err(Failure::Error(format!(
            "--smoothing = {} must be >= 0 (finite)",
            options.smoothing
        )));
    }
    let records = read_records(&options.records)?;
    let (wheel, rail) = profiles(values, None)?;
    let setup = settings(values)?.setup;
    let mounted = MountedRail::new(&rail, &setup)
        .map_err(|e| Failure::Error(format!("railProfile: {e:?}")))?;
    // Depths at the requested distance, then limited.
    let mut distance = options.distance;
    let deepest = |d: f64| {
        (0..2)
            .flat_map(|body| records.depth(body, d, options.smoothing))
            .fold(0.0, f64::max)
    };
    let full = deepest(distance);
    if full > options.max_depth {
        distance *= options.max_depth / full;
    }
    let depths = [0, 1].map(|body| records.depth(body, distance, options.smoothing));
    let worn = |profile: &Profile, body: usize| {
        worn_points(
            profile.points(),
            body == 0,
            |y| at_bins(&records.y[body], &depths[body], y),
            |y| profile.dz(y),
        )
    };
    std::fs::create_dir_all(&options.out).map_err(|e| {
        Failure::Error(format!(
            "--out {}: cannot create: {e}",
            options.out.display()
        ))
    })?;
    let wheel_path = options.out.join(WORN_WHEEL);
    let rail_path = options.out.join(WORN_RAIL);
    let header = |what: &str| {
        format!(
            "# {what} worn by railcontact wear: {distance:e} m of running ({} records, {:e} m \
             recorded), smoothing {:e} m\n# y [mm], z [mm] in the {} frame\n",
            options.records.len(),
            records.distance,
            options.smoothing,
            if what == "wheel" {
                "wheel profile"
            } else {
                "mounted (inclined) rail: use railInclination = 0"
            }
        )
    };
    write_profile(&wheel_path, &header("wheel"), worn(&wheel, 0))?;
    write_profile(&rail_path, &header("rail"), worn(mounted.profile(), 1))?;
    let mut table = String::from("# the depths removed per 0.5 mm bin [m]\nbody,y,depth\n");
    for (body, name) in ["wheel", "rail"].iter().enumerate() {
        for (y, d) in records.y[body].iter().zip(&depths[body]) {
            let _ = writeln!(table, "{name},{y:e},{d:e}");
        }
    }
    let depth_path = options.out.join(DEPTHS);
    std::fs::write(&depth_path, table)
        .map_err(|e| Failure::Error(format!("{}: cannot write: {e}", depth_path.display())))?;
    // The element's own reading and checks of the written files.
    let smoothing = values.real(var::profileSmoothing);
    for (path, kind) in [
        (&wheel_path, ProfileKind::Wheel),
        (&rail_path, ProfileKind::Rail),
    ] {
        let spec = path.to_string_lossy();
        Profile::load(&spec, kind, smoothing)
            .and_then(|p| p.check_plausibility())
            .map_err(|e| {
                Failure::Error(format!("the worn profile fails the profile checks: {e}"))
            })?;
    }
    let max = |d: &[f64]| d.iter().copied().fold(0.0, f64::max);
    Ok(json!({
        "distance": distance,
        "requestedDistance": options.distance,
        "recordedDistance": records.distance,
        "wheelDepthMax": max(&depths[0]),
        "railDepthMax": max(&depths[1]),
        "wheelProfile": wheel_path.to_string_lossy(),
        "railProfile": rail_path.to_string_lossy(),
        "depths": depth_path.to_string_lossy(),
        "railInclination": 0.0,
    }))
}

/// Reads and sums the records.
fn read_records(paths: &[PathBuf]) -> Result<WearRecords, Failure> {
    let mut sum: Option<WearRecords> = None;
    for path in paths {
        let source = path.display().to_string();
        let text = std::fs::read_to_string(path)
            .map_err(|e| Failure::Error(format!("{source}: cannot read the wear record: {e}")))?;
        let record = WearRecords::parse(&text, &source).map_err(Failure::Error)?;
        match &mut sum {
            None => sum = Some(record),
            Some(s) => s.add(&record, &source).map_err(Failure::Error)?,
        }
    }
    let sum = sum.ok_or_else(|| Failure::Error("no wear record given (--record FILE)".into()))?;
    if sum.distance.is_nan() || sum.distance <= 0.0 {
        return Err(Failure::Error(
            "the wear records hold no distance rolled (were they written by a run?)".into(),
        ));
    }
    Ok(sum)
}

/// Writes points [m] as two-column text in mm (6 decimals: 1 nm) after the comment lines
/// `header` — the format the element reads as a two-column profile file.
pub fn write_profile(
    path: &Path,
    header: &str,
    (y, z): (Vec<f64>, Vec<f64>),
) -> Result<(), Failure> {
    let mut text = header.to_string();
    for (y, z) in y.iter().zip(&z) {
        let _ = writeln!(text, "{:.6} {:.6}", y * 1e3, z * 1e3);
    }
    std::fs::write(path, text)
        .map_err(|e| Failure::Error(format!("{}: cannot write: {e}", path.display())))
}
