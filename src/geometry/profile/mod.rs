//! Wheel and rail profiles: built-in S1002 and UIC60/60E1, Simpack / MiniProf / CSV readers, and
//! a smoothing cubic spline z(y) with first and second derivatives.
//!
//! Sources: docs/theory.md §7.1–§7.4 (S1002, UIC60 head, profile files), tests/data/README.md
//! (benchmark files); Reinsch (1967) for the smoothing spline. Details and limits in the
//! submodules: [`spline`] (fit, smoothing length, evaluation), [`s1002`], [`uic60`], [`parse`],
//! [`checks`] (plausibility of profiles read from files: units, wheel orientation, coverage, gaps,
//! steps and spikes).
//!
//! # The profile frame (fixed; `docs/conventions.md`)
//!
//! Every [`Profile`] is stored in SI metres in its own frame:
//!
//! * **y** lateral, positive towards the **field side** (away from the track centre); points in
//!   ascending y;
//! * **z** vertical, positive **downwards**;
//! * **rail**: origin at the top of the rail head as given — for the built-in UIC60/60E1 the crown
//!   top of the un-inclined rail, head symmetric about y = 0; for a file, the file's origin
//!   (the benchmark rail is already canted 1:40 with the origin at its highest point). z ≥ 0 is
//!   the depth below the origin;
//! * **wheel**: origin at the taping line, z = radius increase over the taping-line radius (S1002:
//!   z(y) = F(s = y)); the flange is at negative y, its back at y = −0.070 m, the flange tip at
//!   z = +0.028 m. Simpack wheel files come out in this frame after their own `mirror.y` and
//!   `inversion` settings.
//!
//! # Evaluation
//!
//! [`Profile::eval`] returns z, dz/dy, d²z/dy² (no allocation; binary search over the knots).
//! Outside [`Profile::y_range`] the profile is continued **linearly** with its end value and
//! slope (d²z = 0); contact searches should stay inside the range.
//!
//! # Smoothing
//!
//! `smoothing` is a length ℓ [m] (0 = interpolate the points): the spline removes undulations
//! shorter than ≈ 2πℓ (transfer function 1/(1 + (kℓ)⁴)), independent of the point spacing. For
//! noise σ at spacing h the curvature noise is σ √(h/(8√2 ℓ⁵)) ([`smoothing_length_for_noise`]
//! inverts it); the bias is the leakage of curvature jumps within ~7ℓ (see [`spline`]).
//! Recommendation for measured rail and wheel profiles: **ℓ = 1e−3 m** (1 mm): the UIC60
//! R300|R80 junctions bias the crown curvature by < 0.3 %, and noise of σ = 2 µm at h = 0.1 mm
//! leaves 0.19 1/m (6 % of the crown curvature, 0.3 % of the gauge corner's). Go to 1.5–2 mm only
//! for noisier or sparser data, accepting 1–6 % crown bias. Built-in profiles are exact and never
//! smoothed.

pub mod bounds;
pub mod checks;
pub mod error;
pub mod parse;
pub mod s1002;
pub mod uic60;

use crate::numeric::roots::bisect;
use std::path::Path;

pub use crate::numeric::spline::{smoothing_length_for_noise, CubicSpline};
pub use error::{ErrorReason, Location, ProfileError};

/// Fewest points a profile may have.
pub const MIN_POINTS: usize = 4;
/// Most points a profile may have (a measured profile has ~500–2000).
pub const MAX_POINTS: usize = 100_000;
/// Plausibility bound on |y| and |z| [m] (a profile is ~0.15 m wide; this also keeps the spline
/// arithmetic far from overflow).
pub const MAX_ABS_COORD_M: f64 = 10.0;
/// Smallest accepted step between consecutive lateral coordinates [m] (the benchmark rail has
/// steps of 1e−9 m on its near-vertical flanks).
pub const MIN_DY_M: f64 = 1e-12;
/// Largest accepted smoothing length [m]; far beyond it the fit is just the least-squares line.
pub const MAX_SMOOTHING_M: f64 = 1.0;
/// Names accepted by [`Profile::builtin`] (case-insensitive).
pub const BUILTIN_NAMES: [&str; 3] = ["S1002", "UIC60", "60E1"];

/// Millimetres per metre (the unit of the built-in geometry modules).
const MM: f64 = 1000.0;

/// Wheel or rail.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ProfileKind {
    /// A wheel profile: origin at the taping line, z = radius increase.
    Wheel,
    /// A rail profile: origin at the top of the head, z = depth.
    Rail,
}

impl ProfileKind {
    /// "wheel" or "rail".
    pub fn as_str(self) -> &'static str {
        match self {
            ProfileKind::Wheel => "wheel",
            ProfileKind::Rail => "rail",
        }
    }
}

/// A wheel or rail profile z(y) in its profile frame (module header), metres.
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    name: String,
    kind: ProfileKind,
    y: Vec<f64>,
    z: Vec<f64>,
    smoothing: f64,
    spline: CubicSpline,
}

/// Points with their provenance, before validation.
struct Points<'a> {
    y: Vec<f64>,
    z: Vec<f64>,
    w: Vec<f64>,
    /// Location of each point (file line or array index).
    loc: Vec<Location>,
    source: &'a str,
}

impl Profile {
    /// A profile through the points (`y`, `z`) [m] in the profile frame, strictly monotonic in y
    /// (descending input is reversed), smoothed with length `smoothing` [m] (0 = interpolate).
    /// The plausibility checks of files are not run; [`Profile::check_plausibility`] does.
    pub fn from_points(
        name: &str,
        kind: ProfileKind,
        y: &[f64],
        z: &[f64],
        smoothing: f64,
    ) -> Result<Profile, ProfileError> {
        let source = format!("points of profile '{name}'");
        if y.len() != z.len() {
            return Err(ProfileError::new(
                &source,
                Location::Whole,
                ErrorReason::LengthMismatch {
                    y: y.len(),
                    z: z.len(),
                },
            ));
        }
        let points = Points {
            y: y.to_vec(),
            z: z.to_vec(),
            w: vec![1.0; y.len()],
            loc: (0..y.len()).map(Location::Point).collect(),
            source: &source,
        };
        Self::build(name, kind, points, smoothing)
    }

    /// A built-in profile: "S1002" (wheel), "UIC60" or "60E1" (rail, the same head);
    /// case-insensitive, surrounding blanks ignored.
    pub fn builtin(name: &str) -> Result<Profile, ProfileError> {
        let key = name.trim().to_ascii_uppercase();
        let source = format!("built-in profile '{}'", name.trim());
        let (canonical, kind, (y_mm, z_mm)) = match key.as_str() {
            "S1002" => ("S1002", ProfileKind::Wheel, s1002::sample_mm()),
            "UIC60" | "60E1" => (
                if key == "UIC60" { "UIC60" } else { "60E1" },
                ProfileKind::Rail,
                uic60::HeadGeometry::nominal().sample_mm(),
            ),
            _ => {
                return Err(ProfileError::new(
                    "built-in profile name",
                    Location::Whole,
                    ErrorReason::UnknownBuiltin {
                        name: name.trim().chars().take(80).collect(),
                        io: None,
                    },
                ))
            }
        };
        let n = y_mm.len();
        let points = Points {
            y: y_mm.iter().map(|v| v / MM).collect(),
            z: z_mm.iter().map(|v| v / MM).collect(),
            w: vec![1.0; n],
            loc: (0..n).map(Location::Point).collect(),
            source: &source,
        };
        Self::build(canonical, kind, points, 0.0)
    }

    /// Reads a profile file, by extension: `.prr` (Simpack rail), `.prw` (Simpack wheel) — the
    /// header `type` decides if present —, `.ban` (MiniProf text, rail); anything else is
    /// two-column text/CSV in mm, which needs `kind_hint`. A `kind_hint` that contradicts the file
    /// is an error. `smoothing` as in [`Profile::from_points`]. The profile must then pass the
    /// plausibility checks ([`checks`]: units, wheel orientation, coverage, gaps, steps and
    /// spikes).
    pub fn from_file(
        path: &Path,
        kind_hint: Option<ProfileKind>,
        smoothing: f64,
    ) -> Result<Profile, ProfileError> {
        Self::read_file(path, kind_hint, parse::MM_PER_M, smoothing)
    }

    /// Reads a two-column text/CSV file whose lengths are in units with `units_per_metre` units
    /// per metre (1000 for mm, 1 for m), regardless of the extension.
    pub fn from_text_file(
        path: &Path,
        kind: ProfileKind,
        units_per_metre: f64,
        smoothing: f64,
    ) -> Result<Profile, ProfileError> {
        let source = error::file_source(path);
        if !(units_per_metre.is_finite() && units_per_metre > 0.0) {
            return Err(ProfileError::new(
                &source,
                Location::Whole,
                ErrorReason::InvalidSetting {
                    key: "units_per_metre".into(),
                    value: format!("{units_per_metre}"),
                    expected: "> 0 (finite)",
                },
            ));
        }
        let text = parse::read_text(path, &source)?;
        let raw = parse::parse_columns(&text, &source, units_per_metre)?;
        Self::from_raw(path, &source, raw, kind, smoothing)
    }

    /// A built-in name or a file path — what the FMU parameters `wheelProfile` / `railProfile`
    /// hold. Built-in names win over files of the same name. The profile must be of `kind`.
    pub fn load(spec: &str, kind: ProfileKind, smoothing: f64) -> Result<Profile, ProfileError> {
        let t = spec.trim();
        if BUILTIN_NAMES.iter().any(|b| b.eq_ignore_ascii_case(t)) {
            let p = Self::builtin(t)?;
            if p.kind != kind {
                return Err(ProfileError::new(
                    &format!("built-in profile '{t}'"),
                    Location::Whole,
                    ErrorReason::KindMismatch {
                        requested: kind,
                        found: p.kind,
                    },
                ));
            }
            return Ok(p);
        }
        let path = Path::new(t);
        if t.is_empty() || !path.is_file() {
            let io = if t.is_empty() {
                "empty name".to_string()
            } else if path.exists() {
                "not a regular file".to_string()
            } else {
                "no such file".to_string()
            };
            return Err(ProfileError::new(
                &format!("{} profile", kind.as_str()),
                Location::Whole,
                ErrorReason::UnknownBuiltin {
                    name: t.chars().take(200).collect(),
                    io: Some(io),
                },
            ));
        }
        Self::from_file(path, Some(kind), smoothing)
    }

    /// Reads a profile from the bytes of a file in memory, exactly as [`Profile::from_file`]
    /// reads the file `file_name` (the format is chosen by its extension; the name appears in
    /// error messages). Used by the fuzz targets (`fuzz/`) and by hosts that hold profiles in
    /// memory. Never panics: every input gives a profile or a [`ProfileError`].
    pub fn from_bytes(
        bytes: &[u8],
        file_name: &str,
        kind_hint: Option<ProfileKind>,
        smoothing: f64,
    ) -> Result<Profile, ProfileError> {
        let path = Path::new(file_name);
        let source = error::file_source(path);
        if bytes.len() as u64 > parse::MAX_FILE_BYTES {
            return Err(ProfileError::new(
                &source,
                Location::Whole,
                ErrorReason::FileTooLarge {
                    bytes: bytes.len() as u64,
                    limit: parse::MAX_FILE_BYTES,
                },
            ));
        }
        Self::read(
            path,
            &source,
            kind_hint,
            parse::MM_PER_M,
            smoothing,
            |source| parse::text_from_bytes(bytes, source),
        )
    }

    fn read_file(
        path: &Path,
        kind_hint: Option<ProfileKind>,
        units_per_metre: f64,
        smoothing: f64,
    ) -> Result<Profile, ProfileError> {
        let source = error::file_source(path);
        Self::read(
            path,
            &source,
            kind_hint,
            units_per_metre,
            smoothing,
            |source| parse::read_text(path, source),
        )
    }

    /// Chooses the reader by the extension of `path`, reads the text through `text` and builds
    /// the profile.
    fn read(
        path: &Path,
        source: &str,
        kind_hint: Option<ProfileKind>,
        units_per_metre: f64,
        smoothing: f64,
        text: impl FnOnce(&str) -> Result<String, ProfileError>,
    ) -> Result<Profile, ProfileError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .unwrap_or_default();
        // Refuse a missing kind before reading a plain text file.
        let by_extension = match ext.as_str() {
            "prr" | "ban" => Some(ProfileKind::Rail),
            "prw" => Some(ProfileKind::Wheel),
            _ => None,
        };
        if by_extension.is_none() && kind_hint.is_none() {
            return Err(ProfileError::new(
                source,
                Location::Whole,
                ErrorReason::KindRequired,
            ));
        }
        let text = text(source)?;
        let raw = match ext.as_str() {
            "prr" | "prw" => parse::parse_simpack(&text, source)?,
            "ban" => parse::parse_ban(&text, source)?,
            _ => parse::parse_columns(&text, source, units_per_metre)?,
        };
        let kind = match raw.declared_kind.or(by_extension).or(kind_hint) {
            Some(k) => k,
            None => {
                return Err(ProfileError::new(
                    source,
                    Location::Whole,
                    ErrorReason::KindRequired,
                ))
            }
        };
        if let Some(requested) = kind_hint {
            if requested != kind {
                return Err(ProfileError::new(
                    source,
                    Location::Whole,
                    ErrorReason::KindMismatch {
                        requested,
                        found: kind,
                    },
                ));
            }
        }
        Self::from_raw(path, source, raw, kind, smoothing)
    }

    /// Builds a profile from a file's points and runs the plausibility checks ([`checks`]) on
    /// it; their errors name the line of the point to blame.
    fn from_raw(
        path: &Path,
        source: &str,
        raw: parse::RawPoints,
        kind: ProfileKind,
        smoothing: f64,
    ) -> Result<Profile, ProfileError> {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| path.display().to_string());
        checks::check_units(&raw.y)
            .map_err(|reason| ProfileError::new(source, Location::Whole, reason))?;
        // The points in the profile's ascending order (`build` reverses descending input).
        let descending = raw.y.len() >= 2 && raw.y[0] > raw.y[1];
        let (mut lines, mut weights) = (raw.lines.clone(), raw.w.clone());
        if descending {
            lines.reverse();
            weights.reverse();
        }
        let points = Points {
            loc: raw.lines.iter().map(|&l| Location::Line(l)).collect(),
            y: raw.y,
            z: raw.z,
            w: raw.w,
            source,
        };
        let profile = Self::build(&name, kind, points, smoothing)?;
        profile.check_shape(&weights).map_err(|finding| {
            let loc = finding
                .point
                .map_or(Location::Whole, |i| Location::Line(lines[i]));
            ProfileError::new(source, loc, finding.reason)
        })?;
        Ok(profile)
    }

    /// The shape checks ([`checks::check_shape`]) with point weights `weights` (ascending order).
    fn check_shape(&self, weights: &[f64]) -> Result<(), checks::Finding> {
        checks::check_shape(
            self.kind,
            &self.y,
            &self.z,
            weights,
            self.smoothing,
            &self.spline,
        )
    }

    /// Runs the plausibility checks that files get when they are read ([`checks`]: units, wheel
    /// orientation, coverage of the running surface, gaps, steps and spikes the smoothing does
    /// not absorb) on this profile, e.g. one built with [`Profile::from_points`] (which does not
    /// run them). Errors name the point by its index in ascending y; unit weights are assumed
    /// for the suggested smoothing length.
    pub fn check_plausibility(&self) -> Result<(), ProfileError> {
        let source = format!("profile '{}'", self.name);
        checks::check_units(&self.y)
            .map_err(|reason| ProfileError::new(&source, Location::Whole, reason))?;
        self.check_shape(&vec![1.0; self.y.len()])
            .map_err(|finding| {
                let loc = finding.point.map_or(Location::Whole, Location::Point);
                ProfileError::new(&source, loc, finding.reason)
            })
    }

    /// Validates, orders and fits.
    fn build(
        name: &str,
        kind: ProfileKind,
        mut p: Points<'_>,
        smoothing: f64,
    ) -> Result<Profile, ProfileError> {
        let err = |loc: Location, reason: ErrorReason| ProfileError::new(p.source, loc, reason);
        if !(smoothing.is_finite() && (0.0..=MAX_SMOOTHING_M).contains(&smoothing)) {
            return Err(err(
                Location::Whole,
                ErrorReason::InvalidSmoothing { value: smoothing },
            ));
        }
        let n = p.y.len();
        if n > MAX_POINTS {
            return Err(err(
                Location::Whole,
                ErrorReason::TooManyPoints { limit: MAX_POINTS },
            ));
        }
        for i in 0..n {
            for v in [p.y[i], p.z[i]] {
                if !v.is_finite() {
                    return Err(err(
                        p.loc[i],
                        ErrorReason::NonFinite {
                            text: format!("{v}"),
                        },
                    ));
                }
                if v.abs() > MAX_ABS_COORD_M {
                    return Err(err(p.loc[i], ErrorReason::OutOfRange { value_m: v }));
                }
            }
            if !(p.w[i].is_finite() && p.w[i] > 0.0) {
                return Err(err(p.loc[i], ErrorReason::InvalidWeight { value: p.w[i] }));
            }
        }
        if n < MIN_POINTS {
            return Err(err(Location::Whole, ErrorReason::TooFewPoints { found: n }));
        }
        let direction = if p.y[1] > p.y[0] { 1.0 } else { -1.0 };
        for i in 1..n {
            let step = direction * (p.y[i] - p.y[i - 1]);
            if step.is_nan() || step < MIN_DY_M {
                return Err(err(
                    p.loc[i],
                    ErrorReason::NotMonotonic {
                        y_mm: p.y[i] * MM,
                        previous_y_mm: p.y[i - 1] * MM,
                        previous: p.loc[i - 1],
                    },
                ));
            }
        }
        if direction < 0.0 {
            p.y.reverse();
            p.z.reverse();
            p.w.reverse();
        }
        let spline = CubicSpline::fit(&p.y, &p.z, Some(&p.w), smoothing)
            .map_err(|_| err(Location::Whole, ErrorReason::NumericalFailure))?;
        Ok(Profile {
            name: name.to_string(),
            kind,
            y: p.y,
            z: p.z,
            smoothing,
            spline,
        })
    }

    /// The profile's name (built-in name or file name).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Wheel or rail.
    pub fn kind(&self) -> ProfileKind {
        self.kind
    }

    /// The smoothing length ℓ [m] the profile was fitted with.
    pub fn smoothing(&self) -> f64 {
        self.smoothing
    }

    /// Lateral extent of the data (first, last y) [m].
    pub fn y_range(&self) -> (f64, f64) {
        (self.y[0], self.y[self.y.len() - 1])
    }

    /// z [m] at y [m].
    pub fn z(&self, y: f64) -> f64 {
        self.spline.eval(y).0
    }

    /// dz/dy [–] at y [m].
    pub fn dz(&self, y: f64) -> f64 {
        self.spline.eval(y).1
    }

    /// d²z/dy² [1/m] at y [m].
    pub fn d2z(&self, y: f64) -> f64 {
        self.spline.eval(y).2
    }

    /// The spline piece that [`Profile::eval`] uses at y [m] (not NaN): cheap evaluations
    /// nearby without the interval lookup.
    #[inline(always)]
    pub fn piece_at(&self, y: f64) -> crate::numeric::spline::SplinePiece {
        self.spline.piece_at(y)
    }

    /// (z [m], dz/dy [–], d²z/dy² [1/m]) at y [m]. No allocation; linear continuation outside
    /// [`Profile::y_range`]; NaN for NaN.
    #[inline]
    pub fn eval(&self, y: f64) -> (f64, f64, f64) {
        self.spline.eval(y)
    }

    /// Curvature of the profile curve z''/(1 + z'²)^{3/2} [1/m] at y [m] (positive where the
    /// profile is convex seen from above, z down: e.g. +1/0.3 at the UIC60 crown).
    pub fn curvature(&self, y: f64) -> f64 {
        let (_, d, dd) = self.spline.eval(y);
        dd / (1.0 + d * d).powf(1.5)
    }

    /// The processed data points (y, z) [m], ascending y (not the smoothed values).
    pub fn points(&self) -> (&[f64], &[f64]) {
        (&self.y, &self.z)
    }

    /// The spline.
    pub fn spline(&self) -> &CubicSpline {
        &self.spline
    }

    /// The first y [m] from `y_start` towards +y (`towards_positive`) or −y where z(y) = `level`
    /// [m], within the data range; `None` if there is none. Sign changes are detected at the knots
    /// (a double crossing inside one knot interval is missed), then refined by bisection.
    pub fn level_crossing(&self, level: f64, y_start: f64, towards_positive: bool) -> Option<f64> {
        let (y0, yn) = self.y_range();
        if !(level.is_finite() && y_start.is_finite()) {
            return None;
        }
        let f = |y: f64| self.z(y) - level;
        let mut a = y_start.clamp(y0, yn);
        let mut fa = f(a);
        if fa == 0.0 {
            return Some(a);
        }
        let knots = self.spline.knots();
        let start = knots.partition_point(|&k| k <= a);
        let mut check = |b: f64| -> Option<f64> {
            let fb = f(b);
            if fb == 0.0 {
                return Some(b);
            }
            if (fb > 0.0) != (fa > 0.0) {
                let above_at_a = fa > 0.0;
                return Some(bisect(a, b, 0.0, |mid| (f(mid) > 0.0) == above_at_a));
            }
            a = b;
            fa = fb;
            None
        };
        if towards_positive {
            knots[start..].iter().find_map(|&k| check(k))
        } else {
            knots[..start].iter().rev().find_map(|&k| check(k))
        }
    }

    /// Width [m] of the set where z ≤ `depth` [m] around the lowest-z knot (the top of a rail
    /// head): for a rail, the head width at `depth` below the origin. `None` if a side does not
    /// reach that depth within the data.
    pub fn width_at_depth(&self, depth: f64) -> Option<f64> {
        let knots = self.spline.knots();
        let top = (0..knots.len())
            .min_by(|&i, &j| {
                self.spline
                    .knot_value(i)
                    .total_cmp(&self.spline.knot_value(j))
            })
            .map(|i| knots[i])?;
        let left = self.level_crossing(depth, top, false)?;
        let right = self.level_crossing(depth, top, true)?;
        Some(right - left)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mm(v: f64) -> f64 {
        v / MM
    }

    /// Built-in S1002 through the spline against the analytic F. Measured: 9.8e−5 mm next to
    /// s = −35, where the published coefficients leave a 1.2e−4 mm jump that the C² spline must
    /// bridge (tolerance 1.5e−4 mm); 1.2e−8 mm and 1.2e−6 in slope more than 1 mm from every joint
    /// and the flange back (tolerances 1e−6 mm and 1e−5). Then the checks of docs/theory.md §7.2
    /// through the Profile API.
    #[test]
    fn builtin_s1002_matches_the_analytic_profile() {
        let p = Profile::builtin("s1002").unwrap();
        assert_eq!((p.name(), p.kind()), ("S1002", ProfileKind::Wheel));
        let (a, b) = p.y_range();
        assert_eq!((a, b), (mm(-70.0), mm(60.0)));
        let (mut worst, mut worst_away, mut worst_slope_away) = (0.0f64, 0.0f64, 0.0f64);
        for i in 0..=13_000 {
            let s = -70.0 + 0.01 * i as f64;
            let f = s1002::s1002_mm(s).unwrap();
            let (v, d, _) = p.eval(mm(s));
            let err = (v * MM - f[0]).abs();
            worst = worst.max(err);
            if s > -69.0 && s1002::JOINTS_MM.iter().all(|j| (s - j).abs() > 1.0) {
                worst_away = worst_away.max(err);
                worst_slope_away = worst_slope_away.max((d - f[1]).abs());
            }
        }
        assert!(worst < 1.5e-4, "{worst} mm");
        assert!(worst_away < 1e-6, "{worst_away} mm");
        assert!(worst_slope_away < 1e-5, "{worst_slope_away}");
        // Flange height, taping line, flange thickness through the spline.
        assert!((p.z(mm(-55.0)) * MM - 28.0).abs() < 1e-9);
        assert!(p.z(0.0).abs() < 1e-12);
        assert!((p.dz(0.0) + 0.03359).abs() < 0.5e-5);
        assert!(
            (p.d2z(0.0) / MM - 3.13e-3).abs() < 0.5e-5,
            "{}",
            p.d2z(0.0) / MM
        );
        let s10 = p.level_crossing(mm(10.0), mm(-55.0), true).unwrap() * MM;
        assert!((s10 + 37.5).abs() < 1e-5, "{s10}");
        assert!((s10 - (-70.0) - 32.5).abs() < 1e-5);
    }

    /// Built-in UIC60 through the spline: head width 72 mm at 14 mm (measured 71.999996: z = 14 mm
    /// lies 0.02 mm in y from the R13|flank junction, where the curvature jumps from 1/13 mm⁻¹ to
    /// 0 and the C² spline deviates; tolerance 1e−5 mm); symmetric; crown radius 300 mm from d²z
    /// at 0 (0.01 %: O(h²) curvature error of 0.1 mm steps); normal distance to the exact
    /// construction ≤ 2e−5 mm (measured 1.5e−5 at the R80|R13 curvature jump, ≈ Δκ h²/40).
    #[test]
    fn builtin_uic60_head() {
        let p = Profile::builtin(" 60e1 ").unwrap();
        assert_eq!((p.name(), p.kind()), ("60E1", ProfileKind::Rail));
        let q = Profile::builtin("UIC60").unwrap();
        assert_eq!(p.points(), q.points());
        let w = p.width_at_depth(mm(14.0)).unwrap() * MM;
        assert!((w - 72.0).abs() < 1e-5, "{w}");
        let r = 1.0 / p.d2z(0.0);
        assert!((r - 0.3).abs() < 0.3e-4, "{r}");
        assert!((p.curvature(0.0) * 0.3 - 1.0).abs() < 1e-4);
        let g = uic60::HeadGeometry::nominal();
        for i in 0..=3720 {
            let y = 0.01 * i as f64;
            let (zl, dl, _) = p.eval(mm(-y));
            let (zr, dr, _) = p.eval(mm(y));
            assert!((zl - zr).abs() < 1e-12 && (dl + dr).abs() < 1e-9 * dr.abs().max(1.0));
            let [exact, slope, _] = g.eval_mm(y).unwrap();
            let normal = (zr * MM - exact).abs() / (1.0 + slope * slope).sqrt();
            assert!(normal < 2e-5, "{y}: {} vs {exact}", zr * MM);
        }
    }

    #[test]
    fn evaluation_outside_the_range_is_linear() {
        let p = Profile::builtin("UIC60").unwrap();
        let (_, b) = p.y_range();
        let (z1, d1, _) = p.eval(b);
        let (z2, d2, c2) = p.eval(b + 1e-3);
        assert!((z2 - (z1 + 1e-3 * d1)).abs() < 1e-12 && d2 == d1 && c2 == 0.0);
        assert!(p.eval(f64::NAN).0.is_nan());
    }

    #[test]
    fn from_points_validation_and_descending_input() {
        let y = [0.0, 0.01, 0.02, 0.03];
        let z = [0.0, 0.001, 0.0, 0.002];
        let p = Profile::from_points("d", ProfileKind::Rail, &[0.03, 0.02, 0.01, 0.0], &z, 0.0)
            .unwrap();
        assert_eq!(p.points().0, &y);
        assert_eq!(p.points().1, &[0.002, 0.0, 0.001, 0.0]);
        let e = Profile::from_points("x", ProfileKind::Rail, &y[..3], &z[..3], 0.0).unwrap_err();
        assert!(e.to_string().contains("too few points (3"), "{e}");
        let e = Profile::from_points("x", ProfileKind::Rail, &[0.0, 0.01, 0.005, 0.03], &z, 0.0)
            .unwrap_err();
        assert_eq!(e.location, Location::Point(2));
        assert!(e.to_string().contains("non-monotonic"), "{e}");
        let e = Profile::from_points("x", ProfileKind::Rail, &y, &[0.0, f64::NAN, 0.0, 0.0], 0.0)
            .unwrap_err();
        assert!(matches!(e.reason, ErrorReason::NonFinite { .. }));
        for bad in [-1e-3, f64::NAN, f64::INFINITY, 2.0] {
            let e = Profile::from_points("x", ProfileKind::Rail, &y, &z, bad).unwrap_err();
            assert!(matches!(e.reason, ErrorReason::InvalidSmoothing { .. }));
        }
        let e = Profile::from_points("x", ProfileKind::Rail, &y, &z[..2], 0.0).unwrap_err();
        assert!(matches!(e.reason, ErrorReason::LengthMismatch { .. }));
        let e = Profile::from_points("x", ProfileKind::Rail, &[0.0, 0.0, 1.0, 2.0], &z, 0.0)
            .unwrap_err();
        assert_eq!(e.location, Location::Point(1));
    }

    #[test]
    fn builtin_and_load_names() {
        let e = Profile::builtin("S1003").unwrap_err();
        assert!(
            e.to_string().contains("unknown built-in profile \"S1003\""),
            "{e}"
        );
        assert!(Profile::load("s1002", ProfileKind::Wheel, 0.0).is_ok());
        let e = Profile::load("S1002", ProfileKind::Rail, 0.0).unwrap_err();
        assert!(matches!(e.reason, ErrorReason::KindMismatch { .. }), "{e}");
        let e = Profile::load("/nonexistent/rail.prr", ProfileKind::Rail, 0.0).unwrap_err();
        assert!(e.to_string().contains("/nonexistent/rail.prr"), "{e}");
        let e = Profile::load("", ProfileKind::Rail, 0.0).unwrap_err();
        assert!(matches!(e.reason, ErrorReason::UnknownBuiltin { .. }));
    }

    /// `from_bytes` (the fuzz targets' entry) reads exactly as `from_file` does, by extension.
    #[test]
    fn from_bytes_reads_as_from_file() {
        // A flangeless wheel z = y²/1000 [mm] over −30 … 30 mm (it covers the running surface
        // the plausibility checks ask for), in a Simpack wheel file.
        let mut text = String::from("header.begin\n type = 1\nheader.end\npoint.begin\n");
        for k in -30..=30 {
            text += &format!("{k} {}\n", f64::from(k * k) / 1000.0);
        }
        text += "point.end\n";
        let path = std::env::temp_dir().join(format!("from_bytes_{}.prw", std::process::id()));
        std::fs::write(&path, &text).unwrap();
        let from_file = Profile::from_file(&path, None, 1e-4).unwrap();
        let _ = std::fs::remove_file(&path);
        let from_bytes = Profile::from_bytes(text.as_bytes(), "x.prw", None, 1e-4).unwrap();
        assert_eq!(from_file.points(), from_bytes.points());
        assert_eq!(from_file.eval(0.0005), from_bytes.eval(0.0005));
        // Errors name the file name given, with the line.
        let e = Profile::from_bytes(b"point.begin\n1 x\npoint.end\n", "bad.prr", None, 0.0)
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "profile file 'bad.prr', line 2: non-numeric value \"x\" (expected a number)"
        );
        let e = Profile::from_bytes(b"1 2\n", "plain.csv", None, 0.0).unwrap_err();
        assert_eq!(e.reason, ErrorReason::KindRequired);
        let e = Profile::from_bytes(b"a\0b", "nul.csv", Some(ProfileKind::Rail), 0.0).unwrap_err();
        assert_eq!(e.reason, ErrorReason::Binary);
    }
}
