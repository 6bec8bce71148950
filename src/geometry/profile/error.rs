//! Errors of the profile module: reading, validating and fitting wheel and rail profiles.
//!
//! Every error names **where** (the file, or the caller's point array, or the built-in name),
//! **which line** (1-based, where a line is to blame) or which point (0-based index, for
//! [`Profile::from_points`](super::Profile::from_points)), and **why**, so that the FMI layer can
//! log the message verbatim (see `docs/conventions.md`, "Errors"). Lengths in messages are in mm,
//! the unit profile files are written in.

use std::fmt;

use super::ProfileKind;

/// Where in the input an error was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Location {
    /// The input as a whole (e.g. "missing point block").
    Whole,
    /// A line of a file, 1-based.
    Line(usize),
    /// A point of an array passed by the caller, 0-based.
    Point(usize),
}

/// Why a profile was rejected.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ErrorReason {
    /// The file could not be opened or read (the operating system's message).
    Io(String),
    /// The file is larger than [`MAX_FILE_BYTES`](super::parse::MAX_FILE_BYTES).
    FileTooLarge { bytes: u64, limit: u64 },
    /// The file contains a NUL byte: not a text file.
    Binary,
    /// A token that should be a number is not one.
    NonNumeric { text: String },
    /// A number that is NaN or infinite (also after scaling or shifting).
    NonFinite { text: String },
    /// A coordinate beyond the plausibility bound [`MAX_ABS_COORD_M`](super::MAX_ABS_COORD_M).
    OutOfRange { value_m: f64 },
    /// The lateral coordinate does not increase (or decrease) strictly from point to point.
    NotMonotonic {
        y_mm: f64,
        previous_y_mm: f64,
        previous: Location,
    },
    /// Fewer than [`MIN_POINTS`](super::MIN_POINTS) points.
    TooFewPoints { found: usize },
    /// More than [`MAX_POINTS`](super::MAX_POINTS) points.
    TooManyPoints { limit: usize },
    /// A point row with the wrong number of columns.
    WrongColumnCount {
        found: usize,
        expected: &'static str,
    },
    /// A point weight that is not a finite positive number.
    InvalidWeight { value: f64 },
    /// A Simpack file without `point.begin`.
    MissingPointBlock,
    /// `point.begin` without a matching `point.end`; the location is the `point.begin` line.
    UnterminatedPointBlock,
    /// `point.end` without a preceding `point.begin`.
    UnexpectedPointEnd,
    /// A second `point.begin`.
    DuplicatePointBlock,
    /// A known setting with a value it cannot have.
    InvalidSetting {
        key: String,
        value: String,
        expected: &'static str,
    },
    /// A known setting whose meaning is not implemented (it would silently change the profile).
    Unsupported { key: String, value: String },
    /// A MiniProf header announces a different number of points than the file holds.
    PointCountMismatch { declared: usize, found: usize },
    /// `Profile::builtin` / `Profile::load` with a name that is neither built in nor a file.
    UnknownBuiltin { name: String, io: Option<String> },
    /// The profile is a wheel where a rail was asked for, or vice versa.
    KindMismatch {
        requested: ProfileKind,
        found: ProfileKind,
    },
    /// A plain two-column file does not say whether it is a wheel or a rail.
    KindRequired,
    /// A smoothing length that is negative, not finite or absurdly large.
    InvalidSmoothing { value: f64 },
    /// The y and z arrays differ in length.
    LengthMismatch { y: usize, z: usize },
    /// The spline fit produced non-finite coefficients (should not happen for validated input).
    NumericalFailure,
    /// The lateral extent is far below any wheel or rail profile's: the numbers look like
    /// metres read as mm ([`checks`](super::checks) 1).
    LooksLikeMetres { span_mm: f64 },
    /// A wheel's flange tip lies on the field side: the profile is not mirrored (checks 2).
    FlangeOnFieldSide { y_mm: f64, height_mm: f64 },
    /// A wheel profile does not cover the running surface around the taping line (checks 3).
    WheelNotCovered {
        from_mm: f64,
        to_mm: f64,
        needed_mm: f64,
    },
    /// A rail profile does not descend far enough on one side of its top (checks 3).
    RailNotCovered {
        gauge_side: bool,
        depth_mm: f64,
        needed_mm: f64,
        from_mm: f64,
        to_mm: f64,
    },
    /// Neighbouring points too far apart in the contact region (checks 4); the location is the
    /// point after the gap.
    PointGap {
        gap_mm: f64,
        from_y_mm: f64,
        to_y_mm: f64,
        limit_mm: f64,
    },
    /// A step or spike that the spline, at the given smoothing length, bends around more
    /// sharply than any real profile (checks 5); with the smallest smoothing length tried that
    /// absorbs it, if any.
    StepOrSpike {
        y_mm: f64,
        z_mm: f64,
        offset_mm: f64,
        radius_mm: f64,
        smoothing_m: f64,
        suggestion_m: Option<f64>,
        /// Smallest radius a real surface has [mm].
        min_radius_mm: f64,
        /// Largest smoothing length tried [m].
        largest_tried_m: f64,
    },
}

impl fmt::Display for ErrorReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ErrorReason::Io(msg) => write!(f, "cannot read the file: {msg}"),
            ErrorReason::FileTooLarge { bytes, limit } => write!(
                f,
                "file too large ({bytes} bytes; a profile file is at most {limit} bytes)"
            ),
            ErrorReason::Binary => write!(f, "binary data (NUL byte): not a text profile file"),
            ErrorReason::NonNumeric { text } => {
                write!(f, "non-numeric value \"{text}\" (expected a number)")
            }
            ErrorReason::NonFinite { text } => {
                write!(
                    f,
                    "value \"{text}\" is not a finite number (NaN or infinite)"
                )
            }
            ErrorReason::OutOfRange { value_m } => write!(
                f,
                "coordinate {value_m:e} m is out of range (|y|, |z| must be at most {} m)",
                super::MAX_ABS_COORD_M
            ),
            ErrorReason::NotMonotonic {
                y_mm,
                previous_y_mm,
                previous,
            } => write!(
                f,
                "non-monotonic lateral coordinate: y = {y_mm} mm after y = {previous_y_mm} mm \
                 ({}); y must increase (or decrease) strictly, by at least {} m",
                location_text(*previous),
                super::MIN_DY_M
            ),
            ErrorReason::TooFewPoints { found } => write!(
                f,
                "too few points ({found}; at least {} are needed): the point block looks \
                 truncated or empty; supply the whole profile (measured profiles have hundreds \
                 of points)",
                super::MIN_POINTS
            ),
            ErrorReason::TooManyPoints { limit } => {
                write!(f, "too many points (more than {limit})")
            }
            ErrorReason::WrongColumnCount { found, expected } => write!(
                f,
                "expected {expected} on a point row, found {found} value(s)"
            ),
            ErrorReason::InvalidWeight { value } => {
                write!(f, "point weight {value} is not a finite number > 0")
            }
            ErrorReason::MissingPointBlock => {
                write!(f, "missing point block (no 'point.begin' … 'point.end')")
            }
            ErrorReason::UnterminatedPointBlock => {
                write!(
                    f,
                    "'point.begin' has no matching 'point.end': the file looks truncated; \
                     supply the complete file, its points ended by 'point.end'"
                )
            }
            ErrorReason::UnexpectedPointEnd => write!(f, "'point.end' without 'point.begin'"),
            ErrorReason::DuplicatePointBlock => write!(f, "a second 'point.begin' block"),
            ErrorReason::InvalidSetting {
                key,
                value,
                expected,
            } => write!(f, "invalid setting {key} = {value} (expected {expected})"),
            ErrorReason::Unsupported { key, value } => write!(
                f,
                "setting {key} = {value} is not supported (its meaning is undocumented); \
                 transform the points beforehand and set it to 0"
            ),
            ErrorReason::PointCountMismatch { declared, found } => write!(
                f,
                "the header declares {declared} points but {found} point rows were found"
            ),
            ErrorReason::UnknownBuiltin { name, io } => {
                write!(
                    f,
                    "unknown built-in profile \"{name}\" (built-in: {})",
                    super::BUILTIN_NAMES.join(", ")
                )?;
                if let Some(io) = io {
                    write!(f, ", and not a readable file: {io}")?;
                }
                Ok(())
            }
            ErrorReason::KindMismatch { requested, found } => write!(
                f,
                "this is a {} profile but a {} profile is required",
                found.as_str(),
                requested.as_str()
            ),
            ErrorReason::KindRequired => write!(
                f,
                "a plain two-column file does not say whether it is a wheel or a rail: \
                 pass the profile kind"
            ),
            ErrorReason::InvalidSmoothing { value } => write!(
                f,
                "smoothing length {value} m is outside the allowed range [0, {}] m (finite)",
                super::MAX_SMOOTHING_M
            ),
            ErrorReason::LengthMismatch { y, z } => {
                write!(f, "{y} lateral but {z} vertical coordinates")
            }
            ErrorReason::NumericalFailure => {
                write!(f, "the spline fit failed (non-finite coefficients)")
            }
            ErrorReason::LooksLikeMetres { span_mm } => write!(
                f,
                "the profile spans only {span_mm:.4} mm laterally, where a wheel profile spans \
                 ~130 mm and a rail head ~70 mm: the values look like metres, but profile files \
                 are read in mm; write the coordinates in mm (multiply by 1000), or declare the \
                 unit (Simpack: units.len.f = 1)"
            ),
            ErrorReason::FlangeOnFieldSide { y_mm, height_mm } => write!(
                f,
                "the flange (its tip {height_mm:.1} mm high at y = {y_mm:+.1} mm) lies on the \
                 field side (towards +y): the profile is not mirrored. The wheel profile frame \
                 has y towards the field side and the flange at negative y (docs/conventions.md); \
                 mirror it (y -> -y; in a Simpack file toggle mirror.y)"
            ),
            ErrorReason::WheelNotCovered {
                from_mm,
                to_mm,
                needed_mm,
            } => write!(
                f,
                "the wheel profile covers only y = {from_mm:.1} ... {to_mm:.1} mm, not the running \
                 surface around the taping line (at least y = -{needed_mm} ... +{needed_mm} mm \
                 around the origin): the point block looks truncated, or the origin is not at \
                 the taping line; supply the whole profile with its origin at the taping line \
                 (docs/conventions.md)"
            ),
            ErrorReason::RailNotCovered {
                gauge_side,
                depth_mm,
                needed_mm,
                from_mm,
                to_mm,
            } => write!(
                f,
                "the rail profile (y = {from_mm:.1} ... {to_mm:.1} mm) descends only \
                 {depth_mm:.1} mm below its highest point on the {} side, not the {needed_mm} mm \
                 that cover the running surface (the head's corners lie ~14 mm below the top): \
                 the point block looks truncated; supply the whole rail head",
                if *gauge_side {
                    "gauge (-y)"
                } else {
                    "field (+y)"
                }
            ),
            ErrorReason::PointGap {
                gap_mm,
                from_y_mm,
                to_y_mm,
                limit_mm,
            } => write!(
                f,
                "no points between y = {from_y_mm:.3} and {to_y_mm:.3} mm: a gap of \
                 {gap_mm:.2} mm in the running surface, where at most {limit_mm} mm are allowed \
                 (a contact patch is 5-15 mm wide): points are missing (truncated, deleted or \
                 decimated data); supply the complete profile"
            ),
            ErrorReason::StepOrSpike {
                y_mm,
                z_mm,
                offset_mm,
                radius_mm,
                smoothing_m,
                suggestion_m,
                min_radius_mm,
                largest_tried_m,
            } => {
                write!(
                    f,
                    "a step or spike at y = {y_mm:.3} mm, z = {z_mm:.3} mm: the point lies \
                     {offset_mm:.3} mm off the curve through its neighbours, and the profile \
                     spline (profileSmoothing = {smoothing_m} m) bends there with a radius of \
                     {radius_mm:.3} mm, below the {min_radius_mm} mm of any real wheel or rail \
                     surface; "
                )?;
                match suggestion_m {
                    Some(s) => write!(
                        f,
                        "repair the data there, or smooth the profile: set profileSmoothing = \
                         {s} m or more (the smallest smoothing length that absorbs it; 0.001 m \
                         suits most measured profiles)"
                    ),
                    None => write!(
                        f,
                        "no smoothing length up to {largest_tried_m} m absorbs it: repair the \
                         data there"
                    ),
                }
            }
        }
    }
}

fn location_text(loc: Location) -> String {
    match loc {
        Location::Whole => "earlier".to_string(),
        Location::Line(k) => format!("line {k}"),
        Location::Point(k) => format!("point {k}"),
    }
}

/// A rejected profile: where, which line or point, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileError {
    /// What was being read, e.g. `profile file '/data/rail.prr'` or `points of profile 'x'`.
    pub source: String,
    /// The line (files) or point index (arrays) to blame, if any.
    pub location: Location,
    /// The reason.
    pub reason: ErrorReason,
}

impl ProfileError {
    /// Builds an error.
    pub fn new(source: &str, location: Location, reason: ErrorReason) -> Self {
        Self {
            source: source.to_string(),
            location,
            reason,
        }
    }

    /// The 1-based line number, if a line is to blame.
    pub fn line(&self) -> Option<usize> {
        match self.location {
            Location::Line(k) => Some(k),
            _ => None,
        }
    }
}

impl fmt::Display for ProfileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.location {
            Location::Whole => write!(f, "{}: {}", self.source, self.reason),
            loc => write!(
                f,
                "{}, {}: {}",
                self.source,
                location_text(loc),
                self.reason
            ),
        }
    }
}

impl std::error::Error for ProfileError {}

/// The `source` text for a file path.
pub(crate) fn file_source(path: &std::path::Path) -> String {
    format!("profile file '{}'", path.display())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn message_names_file_line_and_reason() {
        let e = ProfileError::new(
            "profile file '/tmp/x.prr'",
            Location::Line(12),
            ErrorReason::NonNumeric { text: "abc".into() },
        );
        assert_eq!(
            e.to_string(),
            "profile file '/tmp/x.prr', line 12: non-numeric value \"abc\" (expected a number)"
        );
        assert_eq!(e.line(), Some(12));
        let e = ProfileError::new("x", Location::Whole, ErrorReason::MissingPointBlock);
        assert!(e.to_string().starts_with("x: missing point block"));
    }
}
