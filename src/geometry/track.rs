//! Track and wheelset set-up: where the rails and the wheels sit (docs/theory.md §7.5).
//!
//! Standard set-up: gauge 1435 mm measured 14 mm below the top of the rails, rail inclination
//! 1:40 towards the track centre, flange-back (back-to-back) distance 1360 mm with the flange
//! back 70 mm from the taping line (so the taping lines are 1500 mm apart), nominal wheel radius
//! 460 mm at the taping line.
//!
//! Frames (`docs/conventions.md`): track axes x forward, y to the right, z down. Each side is
//! solved in its **side frame**: the track frame for the right wheel, mirrored in y for the left
//! wheel, so that in both the lateral coordinate points towards the field side of that side's
//! rail. Profiles are in their own frames (`crate::geometry::profile`): y towards the field side, z down.
//!
//! A [`MountedRail`] is the rail profile rotated by the inclination and re-referenced so its
//! origin is the top of the rail *as mounted* (its highest point); `yRail` outputs are in these
//! coordinates.
//!
//! Known limits: both rails level (no cant), straight track, identical set-up on both sides.

use crate::error::{require_positive, InputError};
use crate::geometry::profile::{Profile, ProfileKind};
use crate::numeric::roots::bisect;

/// Track and wheelset dimensions [m, rad].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackSetup {
    /// Rail inclination towards the track centre [rad] (1:40 → atan(1/40)). Zero for rail
    /// profiles that are already inclined (e.g. the Manchester benchmark file).
    pub rail_inclination: f64,
    /// Track gauge [m] between the gauge points of the two rails.
    pub track_gauge: f64,
    /// Depth below the top of the rail at which the gauge is measured [m].
    pub gauge_depth: f64,
    /// Distance between the flange backs of the two wheels [m].
    pub flange_back_distance: f64,
    /// Lateral wheel-profile coordinate of the flange back [m] (S1002: −0.070, the taping line
    /// being 70 mm from the flange back).
    pub flange_back_position: f64,
    /// Nominal rolling radius at the taping line (wheel-profile origin) [m].
    pub wheel_radius: f64,
}

impl Default for TrackSetup {
    fn default() -> Self {
        Self {
            rail_inclination: (1.0f64 / 40.0).atan(),
            track_gauge: 1.435,
            gauge_depth: 0.014,
            flange_back_distance: 1.360,
            flange_back_position: -0.070,
            wheel_radius: 0.46,
        }
    }
}

impl TrackSetup {
    /// Checks every dimension; the error names the FMU parameter.
    pub fn validate(&self) -> Result<(), InputError> {
        if !(self.rail_inclination.is_finite() && self.rail_inclination.abs() <= 0.2) {
            return Err(InputError::new(
                "railInclination",
                self.rail_inclination,
                "[-0.2, 0.2] rad",
            ));
        }
        require_positive("trackGauge", self.track_gauge)?;
        require_positive("gaugeDepth", self.gauge_depth)?;
        require_positive("flangeBackDistance", self.flange_back_distance)?;
        require_positive("wheelRadius", self.wheel_radius)?;
        if !self.flange_back_position.is_finite() {
            return Err(InputError::new(
                "flangeBackPosition",
                self.flange_back_position,
                "finite",
            ));
        }
        if self.flange_back_distance >= self.track_gauge {
            return Err(InputError::new(
                "flangeBackDistance",
                self.flange_back_distance,
                "< trackGauge",
            ));
        }
        Ok(())
    }

    /// Lateral distance from the wheelset centre to each wheel's profile origin (taping line)
    /// [m]: half the flange-back distance plus the flange back's distance from the origin.
    pub fn taping_line_offset(&self) -> f64 {
        0.5 * self.flange_back_distance - self.flange_back_position
    }
}

/// Errors building the mounted geometry.
#[derive(Debug, Clone, PartialEq)]
pub enum GeometryError {
    Input(InputError),
    /// A profile is unsuitable for the set-up (message says which and why).
    Profile(String),
}

impl std::fmt::Display for GeometryError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            GeometryError::Input(e) => e.fmt(f),
            GeometryError::Profile(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for GeometryError {}

impl From<InputError> for GeometryError {
    fn from(e: InputError) -> Self {
        GeometryError::Input(e)
    }
}

/// Sampling step used to rotate a rail profile [m]: 0.05 mm keeps the re-fitted interpolating
/// spline within ~1e−8 m of the rotated original on the R13 gauge corner (chord error
/// Δ²/(8R) = 2.4e−8 m) — far below contact-relevant scales.
const MOUNT_SAMPLE_STEP: f64 = 5e-5;

/// A rail profile as mounted in the track.
#[derive(Debug, Clone)]
pub struct MountedRail {
    /// The inclined profile, origin at its highest point, y towards the field side, z down.
    profile: Profile,
    /// Lateral coordinate (mounted rail frame) of the gauge point [m]; negative (gauge side).
    gauge_point: f64,
    /// Lateral position of the mounted rail's origin from the track centre, side frame [m].
    origin_lateral: f64,
}

impl MountedRail {
    /// Inclines `rail` by the set-up's inclination, re-references it to its top and places it
    /// so that its gauge point lies at half the gauge from the track centre.
    pub fn new(rail: &Profile, setup: &TrackSetup) -> Result<Self, GeometryError> {
        setup.validate()?;
        if rail.kind() != ProfileKind::Rail {
            return Err(GeometryError::Profile(format!(
                "{} is not a rail profile",
                rail.name()
            )));
        }
        let (y0, y1) = rail.y_range();
        let n = (((y1 - y0) / MOUNT_SAMPLE_STEP).ceil() as usize).max(8);
        let (sin_b, cos_b) = setup.rail_inclination.sin_cos();
        // Positive inclination leans the head towards the track centre (the standard 1:40 rail
        // matching the wheel's cone): in the profile frame (y towards the field side, z down) the
        // head turns so that its field side rises and its gauge side drops.
        let mut ys = Vec::with_capacity(n + 1);
        let mut zs = Vec::with_capacity(n + 1);
        for i in 0..=n {
            let y = y0 + (y1 - y0) * i as f64 / n as f64;
            let z = rail.z(y);
            ys.push(y * cos_b + z * sin_b);
            zs.push(-y * sin_b + z * cos_b);
        }
        let keep = monotone_run_around_top(&ys, &zs);
        let (ys, zs) = (&ys[keep.clone()], &zs[keep]);
        let top = zs
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1))
            .map(|(i, _)| i)
            .ok_or_else(|| GeometryError::Profile(format!("{}: empty rail", rail.name())))?;
        let (y_top, z_top) = (ys[top], zs[top]);
        let y: Vec<f64> = ys.iter().map(|v| v - y_top).collect();
        let z: Vec<f64> = zs.iter().map(|v| v - z_top).collect();
        let name = format!("{} (mounted)", rail.name());
        let profile = Profile::from_points(&name, ProfileKind::Rail, &y, &z, 0.0)
            .map_err(|e| GeometryError::Profile(e.to_string()))?;
        // The origin is the top, so the gauge-side search starts at y = 0.
        let gauge_point = gauge_point(&profile, 0.0, setup.gauge_depth).ok_or_else(|| {
            GeometryError::Profile(format!(
                "{}: the rail profile does not reach {} mm below its top on the gauge side, \
                     so the gauge point is undefined",
                rail.name(),
                setup.gauge_depth * 1e3
            ))
        })?;
        Ok(Self {
            profile,
            gauge_point,
            origin_lateral: 0.5 * setup.track_gauge - gauge_point,
        })
    }

    pub fn profile(&self) -> &Profile {
        &self.profile
    }

    /// Gauge point's lateral coordinate in the mounted rail frame [m].
    pub fn gauge_point(&self) -> f64 {
        self.gauge_point
    }

    /// Lateral position of the rail's origin (top) from the track centre, side frame [m].
    pub fn origin_lateral(&self) -> f64 {
        self.origin_lateral
    }
}

/// Index range of the part of a rotated curve whose y is strictly increasing and that contains
/// the highest point (a steep flank can fold over when rotated).
fn monotone_run_around_top(ys: &[f64], zs: &[f64]) -> std::ops::Range<usize> {
    let top = zs
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .map_or(0, |(i, _)| i);
    let mut lo = top;
    while lo > 0 && ys[lo - 1] < ys[lo] {
        lo -= 1;
    }
    let mut hi = top;
    while hi + 1 < ys.len() && ys[hi + 1] > ys[hi] {
        hi += 1;
    }
    lo..hi + 1
}

/// The gauge-side lateral coordinate where the profile first reaches `depth` below the top,
/// searching from `from` towards negative y; bisection to 1e−9 m.
fn gauge_point(profile: &Profile, from: f64, depth: f64) -> Option<f64> {
    let (y_min, _) = profile.y_range();
    let step = 1e-4;
    let mut right = from;
    while right > y_min {
        let left = (right - step).max(y_min);
        if profile.z(left) >= depth {
            return Some(bisect(left, right, 1e-9, |m| profile.z(m) >= depth));
        }
        right = left;
    }
    None
}
