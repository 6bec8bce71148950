//! Readers for profile files: Simpack `.prr`/`.prw`, MiniProf-style text `.ban`, and plain
//! two-column text/CSV.
//!
//! Sources: docs/theory.md §7.4 (what is known of the Simpack format), the three benchmark files in
//! `tests/data/profiles/` (layouts as found), `tests/data/README.md`.
//!
//! Every reader returns the points in **metres, in the file's order, after the file's own
//! transformations**, each with the line it came from; [`Profile`](super::Profile) then checks
//! monotonicity, orders them by ascending y and fits the spline. No reader panics on any input:
//! files larger than [`MAX_FILE_BYTES`] or containing a NUL byte are refused, other bytes are
//! decoded leniently (invalid UTF-8 becomes U+FFFD and then fails as a non-numeric value if it is
//! where a number should be), every number must be finite, coordinates beyond
//! [`MAX_ABS_COORD_M`](super::MAX_ABS_COORD_M) are refused.
//!
//! # Simpack `.prr` (rail) / `.prw` (wheel)
//!
//! `!` starts a comment (outside single quotes); so a point row can be commented out. Blocks
//! `header.begin … header.end`, `spline.begin … spline.end` and `point.begin … point.end` (names
//! case-insensitive; other blocks and unknown keys are ignored). `key = value` settings:
//!
//! * header `type` = 0 rail / 1 wheel (`type` inside the spline block is the original data file
//!   type and is ignored); `version` ignored;
//! * applied in Simpack's numbering order (our inference from the numbering):
//!   1 `point.dist.min` (drop a point closer than this to the last kept one; 0 = off),
//!   2 `shift.y`, `shift.z` (added), 3 `rotate` (must be 0: its sign convention is undocumented,
//!   a non-zero value is refused rather than guessed), 4 `bound.y.min/max`, `bound.z.min/max`
//!   (points outside are dropped; only when min < max — the benchmark files have min > max,
//!   which means "no bounds"), 5 `mirror.y`, `mirror.z` (0/1: y → −y, z → −z), 6 `inversion`
//!   (0/1: reverse the point order), 7 `units.len.f` (file units per metre; 1000 = mm; if absent,
//!   `units.len` = 'm' | 'cm' | 'mm' is used, else mm is assumed);
//! * `approx.smooth` is ignored (as CONTACT does): smoothing is the caller's parameter;
//!   `units.ang.f`, `units.ang`, `file`, `file.mtime`, `comment` are ignored.
//!
//! Point rows: `y z [weight]` separated by blanks, tabs, commas or semicolons; the weight (default
//! 1, must be > 0) scales the point's influence in a smoothing fit.
//!
//! # MiniProf-style `.ban` (text)
//!
//! `Key=Value` header lines, then one row per point, `X<TAB>Y` in mm; rows may start with a `"`
//! (in the benchmark file the first 11 and last 8 rows — the near-vertical ends of the flanks —
//! carry it; its meaning is undocumented; the mark is stripped and the point kept, which makes
//! the file identical to `MBench_UIC60_v3.prr`). Orientation, inferred from that pair of files:
//! X points to the **gauge** side and Y downwards, so y = −X, z = Y. `XYPoints`, when
//! present, must equal the number of rows; `ColumnDef` must be `X,Y`; non-zero `XOffset`,
//! `YOffset`, `Tilt`, `BaseTilt`, `BaseOffset` are refused (meaning undocumented). Real MiniProf
//! `.ban` files are binary: they are refused as such (NUL byte).
//!
//! # Plain text / CSV
//!
//! Two columns (lateral y, vertical z, in the profile frame of `docs/conventions.md`: y towards the
//! field side, z downwards), separated by commas, semicolons, tabs or blanks; further columns are
//! ignored. With semicolon or tab separators a decimal comma is accepted. Lines starting with `#`,
//! `!`, `%` or `//` are comments; one non-numeric header line before the first point is allowed.
//! Units: mm unless the caller states otherwise (`units_per_metre`).

use std::io::Read;
use std::path::Path;

use super::error::{ErrorReason, Location, ProfileError};
use super::{ProfileKind, MAX_ABS_COORD_M, MAX_POINTS};

/// Largest profile file read [bytes] (the benchmark files are ~25 kB).
pub const MAX_FILE_BYTES: u64 = 16 * 1024 * 1024;

/// Longest excerpt of an offending token quoted in an error message [chars].
const MAX_EXCERPT_CHARS: usize = 40;

/// File units per metre when nothing is declared: millimetres.
pub const MM_PER_M: f64 = 1000.0;

/// Points as read: metres, file order, after the file's transformations.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RawPoints {
    /// Lateral coordinate [m].
    pub y: Vec<f64>,
    /// Vertical coordinate [m].
    pub z: Vec<f64>,
    /// Relative weights (> 0).
    pub w: Vec<f64>,
    /// Source line of each point (1-based).
    pub lines: Vec<usize>,
    /// The kind the file declares (Simpack header `type`), if any.
    pub declared_kind: Option<ProfileKind>,
}

impl RawPoints {
    fn push(&mut self, y: f64, z: f64, w: f64, line: usize) {
        self.y.push(y);
        self.z.push(z);
        self.w.push(w);
        self.lines.push(line);
    }
}

/// Reads a text file: at most [`MAX_FILE_BYTES`], no NUL byte, lenient UTF-8, BOM stripped.
pub fn read_text(path: &Path, source: &str) -> Result<String, ProfileError> {
    let io_err = |e: std::io::Error| {
        ProfileError::new(source, Location::Whole, ErrorReason::Io(e.to_string()))
    };
    let file = std::fs::File::open(path).map_err(io_err)?;
    let mut bytes = Vec::new();
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io_err)?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(ProfileError::new(
            source,
            Location::Whole,
            ErrorReason::FileTooLarge {
                bytes: std::fs::metadata(path).map_or(bytes.len() as u64, |m| m.len()),
                limit: MAX_FILE_BYTES,
            },
        ));
    }
    text_from_bytes(&bytes, source)
}

/// Decodes file bytes (see [`read_text`]).
pub fn text_from_bytes(bytes: &[u8], source: &str) -> Result<String, ProfileError> {
    if let Some(pos) = bytes.iter().position(|&b| b == 0) {
        let line = 1 + bytes[..pos].iter().filter(|&&b| b == b'\n').count();
        return Err(ProfileError::new(
            source,
            Location::Line(line),
            ErrorReason::Binary,
        ));
    }
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    Ok(String::from_utf8_lossy(bytes).into_owned())
}

/// Lines with 1-based numbers; `\n`, `\r\n` and (if there is no `\n` at all) lone `\r` end lines.
fn numbered_lines(text: &str) -> Box<dyn Iterator<Item = (usize, &str)> + '_> {
    if text.contains('\n') {
        Box::new(
            text.split('\n')
                .map(|l| l.strip_suffix('\r').unwrap_or(l))
                .enumerate()
                .map(|(i, l)| (i + 1, l)),
        )
    } else {
        Box::new(text.split('\r').enumerate().map(|(i, l)| (i + 1, l)))
    }
}

/// The first `MAX_EXCERPT_CHARS` characters of `s` (char-safe), for error messages.
fn excerpt(s: &str) -> String {
    let mut out: String = s.chars().take(MAX_EXCERPT_CHARS).collect();
    if s.chars().nth(MAX_EXCERPT_CHARS).is_some() {
        out.push('…');
    }
    out
}

/// Parses one number: optional surrounding double quotes, Fortran `D` exponents accepted; NaN and
/// infinities (also by overflow, "1e999") refused.
pub fn parse_number(token: &str) -> Result<f64, ErrorReason> {
    let t = token.trim();
    let t = t
        .strip_prefix('"')
        .and_then(|s| s.strip_suffix('"'))
        .unwrap_or(t)
        .trim();
    let parsed = match t.parse::<f64>() {
        Ok(v) => Ok(v),
        Err(_) if t.contains(['d', 'D']) && !t.contains(['e', 'E']) => {
            t.replace(['d', 'D'], "e").parse::<f64>()
        }
        Err(e) => Err(e),
    };
    match parsed {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(ErrorReason::NonFinite { text: excerpt(t) }),
        Err(_) => Err(ErrorReason::NonNumeric { text: excerpt(t) }),
    }
}

/// Splits a point row on blanks, tabs, commas and semicolons.
fn split_fields(row: &str) -> Vec<&str> {
    row.split(|c: char| c.is_whitespace() || c == ',' || c == ';')
        .filter(|f| !f.is_empty())
        .collect()
}

/// Removes a `!` comment (outside single quotes).
fn strip_comment(line: &str) -> &str {
    let mut quoted = false;
    for (i, c) in line.char_indices() {
        match c {
            '\'' => quoted = !quoted,
            '!' if !quoted => return &line[..i],
            _ => {}
        }
    }
    line
}

/// Checks a coordinate [m] after all transformations.
fn check_coordinate(v: f64, source: &str, line: usize) -> Result<f64, ProfileError> {
    if !v.is_finite() {
        return Err(ProfileError::new(
            source,
            Location::Line(line),
            ErrorReason::NonFinite {
                text: format!("{v}"),
            },
        ));
    }
    if v.abs() > MAX_ABS_COORD_M {
        return Err(ProfileError::new(
            source,
            Location::Line(line),
            ErrorReason::OutOfRange { value_m: v },
        ));
    }
    Ok(v)
}

/// Settings of a Simpack spline block (file units).
#[derive(Debug, Clone, PartialEq)]
struct SimpackSettings {
    kind: Option<ProfileKind>,
    dist_min: f64,
    shift_y: f64,
    shift_z: f64,
    bound_y: (f64, f64),
    bound_z: (f64, f64),
    mirror_y: bool,
    mirror_z: bool,
    inversion: bool,
    units_len_f: Option<f64>,
    units_len_name: Option<f64>,
}

impl Default for SimpackSettings {
    fn default() -> Self {
        Self {
            kind: None,
            dist_min: 0.0,
            shift_y: 0.0,
            shift_z: 0.0,
            // min > max: no bounds (as in the benchmark files).
            bound_y: (1.0, 0.0),
            bound_z: (1.0, 0.0),
            mirror_y: false,
            mirror_z: false,
            inversion: false,
            units_len_f: None,
            units_len_name: None,
        }
    }
}

/// Strips single quotes around a string value.
fn unquote(v: &str) -> &str {
    v.strip_prefix('\'')
        .and_then(|s| s.strip_suffix('\''))
        .unwrap_or(v)
        .trim()
}

impl SimpackSettings {
    /// Applies `key = value` found in block `block` (lower case, "" at top level).
    fn apply(
        &mut self,
        block: &str,
        key: &str,
        value: &str,
        source: &str,
        line: usize,
    ) -> Result<(), ProfileError> {
        let invalid = |expected: &'static str| {
            ProfileError::new(
                source,
                Location::Line(line),
                ErrorReason::InvalidSetting {
                    key: excerpt(key),
                    value: excerpt(value),
                    expected,
                },
            )
        };
        let number = || {
            parse_number(unquote(value))
                .map_err(|r| ProfileError::new(source, Location::Line(line), r))
        };
        let flag = || -> Result<bool, ProfileError> {
            match parse_number(unquote(value)) {
                Ok(0.0) => Ok(false),
                Ok(1.0) => Ok(true),
                _ => Err(invalid("0 or 1")),
            }
        };
        match key {
            "type" if block == "header" => {
                self.kind = match parse_number(unquote(value)) {
                    Ok(0.0) => Some(ProfileKind::Rail),
                    Ok(1.0) => Some(ProfileKind::Wheel),
                    _ => return Err(invalid("0 (rail) or 1 (wheel)")),
                }
            }
            "point.dist.min" => {
                let v = number()?;
                if v < 0.0 {
                    return Err(invalid(">= 0"));
                }
                self.dist_min = v;
            }
            "shift.y" => self.shift_y = number()?,
            "shift.z" => self.shift_z = number()?,
            "rotate" => {
                let angle = number()?;
                if angle != 0.0 {
                    return Err(ProfileError::new(
                        source,
                        Location::Line(line),
                        ErrorReason::Unsupported {
                            key: key.to_string(),
                            value: excerpt(value),
                        },
                    ));
                }
            }
            "bound.y.min" => self.bound_y.0 = number()?,
            "bound.y.max" => self.bound_y.1 = number()?,
            "bound.z.min" => self.bound_z.0 = number()?,
            "bound.z.max" => self.bound_z.1 = number()?,
            "mirror.y" => self.mirror_y = flag()?,
            "mirror.z" => self.mirror_z = flag()?,
            "inversion" => self.inversion = flag()?,
            "units.len.f" => {
                let v = number()?;
                if v <= 0.0 {
                    return Err(invalid("> 0 (file length units per metre)"));
                }
                self.units_len_f = Some(v);
            }
            "units.len" => {
                self.units_len_name = Some(match unquote(value).to_ascii_lowercase().as_str() {
                    "m" => 1.0,
                    "cm" => 100.0,
                    "mm" => MM_PER_M,
                    _ => return Err(invalid("'m', 'cm' or 'mm'")),
                })
            }
            _ => {} // unknown or ignored keys (approx.smooth, file, comment, units.ang.f, …)
        }
        Ok(())
    }
}

/// Reads a Simpack `.prr`/`.prw` text (see the module header).
pub fn parse_simpack(text: &str, source: &str) -> Result<RawPoints, ProfileError> {
    let err = |loc: Location, reason: ErrorReason| ProfileError::new(source, loc, reason);
    let mut settings = SimpackSettings::default();
    let mut blocks: Vec<String> = Vec::new();
    let mut point_begin: Option<usize> = None;
    let mut points_done = false;
    // (y, z, weight, line) in file units.
    let mut rows: Vec<(f64, f64, f64, usize)> = Vec::new();
    for (ln, line) in numbered_lines(text) {
        let content = strip_comment(line).trim();
        if content.is_empty() {
            continue;
        }
        let lower = content.to_ascii_lowercase();
        if point_begin.is_some() {
            match lower.as_str() {
                "point.end" => {
                    point_begin = None;
                    points_done = true;
                }
                "point.begin" => {
                    return Err(err(Location::Line(ln), ErrorReason::DuplicatePointBlock))
                }
                l if l.ends_with(".end") || l.ends_with(".begin") => {
                    // Another block's marker: the point block was never closed.
                    let begin = point_begin.unwrap_or(ln);
                    return Err(err(
                        Location::Line(begin),
                        ErrorReason::UnterminatedPointBlock,
                    ));
                }
                _ => {
                    let fields = split_fields(content);
                    if !(2..=3).contains(&fields.len()) {
                        return Err(err(
                            Location::Line(ln),
                            ErrorReason::WrongColumnCount {
                                found: fields.len(),
                                expected: "2 or 3 numbers (y z [weight])",
                            },
                        ));
                    }
                    let mut v = [0.0, 0.0, 1.0];
                    for (slot, f) in v.iter_mut().zip(&fields) {
                        *slot = parse_number(f).map_err(|r| err(Location::Line(ln), r))?;
                    }
                    if v[2] <= 0.0 {
                        return Err(err(
                            Location::Line(ln),
                            ErrorReason::InvalidWeight { value: v[2] },
                        ));
                    }
                    if rows.len() >= MAX_POINTS {
                        return Err(err(
                            Location::Line(ln),
                            ErrorReason::TooManyPoints { limit: MAX_POINTS },
                        ));
                    }
                    rows.push((v[0], v[1], v[2], ln));
                }
            }
            continue;
        }
        if lower == "point.begin" {
            if points_done {
                return Err(err(Location::Line(ln), ErrorReason::DuplicatePointBlock));
            }
            point_begin = Some(ln);
            continue;
        }
        if lower == "point.end" {
            return Err(err(Location::Line(ln), ErrorReason::UnexpectedPointEnd));
        }
        if let Some((key, value)) = content.split_once('=') {
            let key = key.trim().to_ascii_lowercase();
            let block = blocks.last().map_or("", |b| b.as_str());
            settings.apply(block, &key, value.trim(), source, ln)?;
            continue;
        }
        if let Some(name) = lower.strip_suffix(".begin") {
            blocks.push(name.trim().to_string());
            continue;
        }
        if let Some(name) = lower.strip_suffix(".end") {
            // Tolerant: close the innermost block of that name, ignore an unmatched end.
            if let Some(pos) = blocks.iter().rposition(|b| b == name.trim()) {
                blocks.truncate(pos);
            }
            continue;
        }
        // Anything else outside the point block is ignored (tolerant reading).
    }
    if let Some(begin) = point_begin {
        return Err(err(
            Location::Line(begin),
            ErrorReason::UnterminatedPointBlock,
        ));
    }
    if !points_done {
        return Err(err(Location::Whole, ErrorReason::MissingPointBlock));
    }

    // 1. minimum point distance (file units).
    if settings.dist_min > 0.0 {
        let mut kept: Vec<(f64, f64, f64, usize)> = Vec::with_capacity(rows.len());
        for r in rows {
            let keep = kept
                .last()
                .is_none_or(|k| (r.0 - k.0).hypot(r.1 - k.1) >= settings.dist_min);
            if keep {
                kept.push(r);
            }
        }
        rows = kept;
    }
    // 2. shift; 3. rotation (only 0 accepted); 4. bounds (min < max only); 5. mirroring.
    let (by, bz) = (settings.bound_y, settings.bound_z);
    let mut out = RawPoints {
        declared_kind: settings.kind,
        ..RawPoints::default()
    };
    let f = settings
        .units_len_f
        .or(settings.units_len_name)
        .unwrap_or(MM_PER_M);
    let mut transformed: Vec<(f64, f64, f64, usize)> = Vec::with_capacity(rows.len());
    for (y, z, w, ln) in rows {
        let (y, z) = (y + settings.shift_y, z + settings.shift_z);
        if by.0 < by.1 && !(by.0..=by.1).contains(&y) {
            continue;
        }
        if bz.0 < bz.1 && !(bz.0..=bz.1).contains(&z) {
            continue;
        }
        let y = if settings.mirror_y { -y } else { y };
        let z = if settings.mirror_z { -z } else { z };
        transformed.push((y, z, w, ln));
    }
    // 6. inversion.
    if settings.inversion {
        transformed.reverse();
    }
    // 7. units.
    for (y, z, w, ln) in transformed {
        let y = check_coordinate(y / f, source, ln)?;
        let z = check_coordinate(z / f, source, ln)?;
        out.push(y, z, w, ln);
    }
    Ok(out)
}

/// Whether a `.ban` header value is empty or zero.
fn empty_or_zero(v: &str) -> bool {
    let v = v.trim();
    v.is_empty() || parse_number(v).is_ok_and(|x| x == 0.0)
}

/// Reads a MiniProf-style text `.ban` (see the module header); lengths in mm.
pub fn parse_ban(text: &str, source: &str) -> Result<RawPoints, ProfileError> {
    let err = |loc: Location, reason: ErrorReason| ProfileError::new(source, loc, reason);
    let mut out = RawPoints {
        declared_kind: Some(ProfileKind::Rail),
        ..RawPoints::default()
    };
    let mut declared: Option<(usize, usize)> = None; // (count, line)
    let mut in_data = false;
    for (ln, line) in numbered_lines(text) {
        let t = line.trim();
        if t.is_empty() {
            continue;
        }
        let row = t.trim_start_matches('"').trim_end_matches('"').trim();
        let looks_numeric = row
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_digit() || matches!(c, '-' | '+' | '.'));
        if !in_data && !looks_numeric {
            if let Some((key, value)) = t.split_once('=') {
                let key = key.trim();
                let bad = || {
                    err(
                        Location::Line(ln),
                        ErrorReason::Unsupported {
                            key: excerpt(key),
                            value: excerpt(value.trim()),
                        },
                    )
                };
                match key.to_ascii_lowercase().as_str() {
                    "xypoints" => {
                        let v = parse_number(value).map_err(|r| err(Location::Line(ln), r))?;
                        if !(v >= 0.0 && v.fract() == 0.0 && v <= MAX_POINTS as f64) {
                            return Err(err(
                                Location::Line(ln),
                                ErrorReason::InvalidSetting {
                                    key: key.to_string(),
                                    value: excerpt(value.trim()),
                                    expected: "a point count",
                                },
                            ));
                        }
                        declared = Some((v as usize, ln));
                    }
                    "xoffset" | "yoffset" | "tilt" | "basetilt" | "baseoffset"
                        if !empty_or_zero(value) =>
                    {
                        return Err(bad());
                    }
                    "columndef" => {
                        let cols: String = value.chars().filter(|c| !c.is_whitespace()).collect();
                        if !cols.eq_ignore_ascii_case("X,Y") {
                            return Err(bad());
                        }
                    }
                    _ => {}
                }
            }
            // Other header lines are ignored (tolerant reading).
            continue;
        }
        in_data = true;
        let fields = split_fields(row);
        if fields.len() != 2 {
            return Err(err(
                Location::Line(ln),
                ErrorReason::WrongColumnCount {
                    found: fields.len(),
                    expected: "2 numbers (X Y)",
                },
            ));
        }
        let x = parse_number(fields[0]).map_err(|r| err(Location::Line(ln), r))?;
        let yv = parse_number(fields[1]).map_err(|r| err(Location::Line(ln), r))?;
        if out.y.len() >= MAX_POINTS {
            return Err(err(
                Location::Line(ln),
                ErrorReason::TooManyPoints { limit: MAX_POINTS },
            ));
        }
        let y = check_coordinate(-x / MM_PER_M, source, ln)?;
        let z = check_coordinate(yv / MM_PER_M, source, ln)?;
        out.push(y, z, 1.0, ln);
    }
    if let Some((count, ln)) = declared {
        if count != out.y.len() {
            return Err(err(
                Location::Line(ln),
                ErrorReason::PointCountMismatch {
                    declared: count,
                    found: out.y.len(),
                },
            ));
        }
    }
    Ok(out)
}

/// Splits a plain-text row: `;` or tab separated rows accept decimal commas.
fn split_columns(row: &str) -> Vec<String> {
    let decimal_comma = |f: &str| {
        if f.contains(',') && !f.contains('.') {
            f.replace(',', ".")
        } else {
            f.to_string()
        }
    };
    if row.contains(';') || row.contains('\t') {
        row.split([';', '\t'])
            .map(str::trim)
            .filter(|f| !f.is_empty())
            .map(decimal_comma)
            .collect()
    } else {
        row.split(|c: char| c.is_whitespace() || c == ',')
            .filter(|f| !f.is_empty())
            .map(str::to_string)
            .collect()
    }
}

/// Reads plain two-column text/CSV (see the module header); `units_per_metre` file units per
/// metre (1000 for mm).
pub fn parse_columns(
    text: &str,
    source: &str,
    units_per_metre: f64,
) -> Result<RawPoints, ProfileError> {
    let err = |loc: Location, reason: ErrorReason| ProfileError::new(source, loc, reason);
    let mut out = RawPoints::default();
    let mut header_seen = false;
    for (ln, line) in numbered_lines(text) {
        let t = line.trim();
        if t.is_empty() || t.starts_with(['#', '!', '%']) || t.starts_with("//") {
            continue;
        }
        let fields = split_columns(t);
        let mut parsed = fields.iter().take(2).map(|f| parse_number(f));
        let (y, z) = match (parsed.next(), parsed.next()) {
            (Some(Ok(y)), Some(Ok(z))) => (y, z),
            (first, second) => {
                let non_numeric = |r: &Option<Result<f64, ErrorReason>>| {
                    matches!(r, Some(Err(ErrorReason::NonNumeric { .. })))
                };
                if out.y.is_empty() && !header_seen && (non_numeric(&first) || non_numeric(&second))
                {
                    header_seen = true; // one optional header line
                    continue;
                }
                let reason = match (first, second) {
                    (Some(Err(r)), _) | (_, Some(Err(r))) => r,
                    _ => ErrorReason::WrongColumnCount {
                        found: fields.len(),
                        expected: "2 numbers (y z)",
                    },
                };
                return Err(err(Location::Line(ln), reason));
            }
        };
        if out.y.len() >= MAX_POINTS {
            return Err(err(
                Location::Line(ln),
                ErrorReason::TooManyPoints { limit: MAX_POINTS },
            ));
        }
        let y = check_coordinate(y / units_per_metre, source, ln)?;
        let z = check_coordinate(z / units_per_metre, source, ln)?;
        out.push(y, z, 1.0, ln);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SRC: &str = "test";

    #[test]
    fn numbers() {
        assert_eq!(parse_number(" 1.5E+01 "), Ok(15.0));
        assert_eq!(parse_number("\"-2\""), Ok(-2.0));
        assert_eq!(parse_number("1.0D+02"), Ok(100.0));
        assert!(matches!(
            parse_number("nan"),
            Err(ErrorReason::NonFinite { .. })
        ));
        assert!(matches!(
            parse_number("1e999"),
            Err(ErrorReason::NonFinite { .. })
        ));
        assert!(matches!(
            parse_number("-inf"),
            Err(ErrorReason::NonFinite { .. })
        ));
        assert!(matches!(
            parse_number("1.2.3"),
            Err(ErrorReason::NonNumeric { .. })
        ));
        assert!(matches!(
            parse_number(""),
            Err(ErrorReason::NonNumeric { .. })
        ));
    }

    #[test]
    fn simpack_transformations_in_order() {
        let text = "header.begin\n type = 1 ! wheel\nheader.end\nspline.begin\n type = 0\n \
                    comment = 'a ! not a comment'\n shift.y = 1\n mirror.y = 1\n inversion = 1\n \
                    units.len.f = 1000\n point.begin\n ! 9 9\n 1 0.5\n 2 0.25 2\n 3, 0.125\n\
                    4;0\n point.end\nspline.end\n";
        let p = parse_simpack(text, SRC).unwrap();
        assert_eq!(p.declared_kind, Some(ProfileKind::Wheel));
        // shift then mirror then reverse: y = −(x + 1)/1000 in reversed order.
        assert_eq!(p.y, vec![-0.005, -0.004, -0.003, -0.002]);
        assert_eq!(p.z, vec![0.0, 0.000125, 0.00025, 0.0005]);
        assert_eq!(p.w, vec![1.0, 1.0, 2.0, 1.0]);
        assert_eq!(p.lines, vec![16, 15, 14, 13]);
    }

    #[test]
    fn simpack_bounds_distance_and_units_name() {
        let text = "units.len = 'm'\nbound.y.min = 0.5\nbound.y.max = 3.5\npoint.dist.min = 0.9\n\
                    point.begin\n0 0\n1 0\n1.5 0\n2 0\n3 0\n4 0\npoint.end\n";
        let p = parse_simpack(text, SRC).unwrap();
        assert_eq!(p.y, vec![1.0, 2.0, 3.0]);
    }

    #[test]
    fn simpack_errors_have_lines() {
        let e = parse_simpack("point.begin\n1 2\n3 x\npoint.end\n", SRC).unwrap_err();
        assert_eq!(e.location, Location::Line(3));
        let e = parse_simpack("point.begin\n1 2\n", SRC).unwrap_err();
        assert_eq!(
            (e.location, &e.reason),
            (Location::Line(1), &ErrorReason::UnterminatedPointBlock)
        );
        let e = parse_simpack("a = 1\n", SRC).unwrap_err();
        assert_eq!(e.reason, ErrorReason::MissingPointBlock);
        let e = parse_simpack("rotate = 0.1\npoint.begin\npoint.end", SRC).unwrap_err();
        assert!(matches!(e.reason, ErrorReason::Unsupported { .. }));
        let e = parse_simpack("mirror.y = 2\n", SRC).unwrap_err();
        assert_eq!(e.location, Location::Line(1));
        let e = parse_simpack("point.begin\n1 2 0\npoint.end", SRC).unwrap_err();
        assert!(matches!(e.reason, ErrorReason::InvalidWeight { .. }));
        let e = parse_simpack("shift.y = 1e308\npoint.begin\n1e308 2\npoint.end", SRC).unwrap_err();
        assert!(matches!(e.reason, ErrorReason::NonFinite { .. }), "{e}");
        let e = parse_simpack("point.begin\n1e7 2\npoint.end", SRC).unwrap_err();
        assert!(matches!(e.reason, ErrorReason::OutOfRange { .. }), "{e}");
    }

    #[test]
    fn ban_layout() {
        let text = "Filename=x.ban\nXYPoints=3\nXOffset=0.0000\nTilt=\nColumnDef=X,Y\n\n\
                    \x20 1.0\t2.0\n\"-1.0\t3.0\n -2.0\t4.0\n";
        let p = parse_ban(text, SRC).unwrap();
        assert_eq!(p.y, vec![-0.001, 0.001, 0.002]);
        assert_eq!(p.z, vec![0.002, 0.003, 0.004]);
        let e = parse_ban("XYPoints=4\n1 2\n2 3\n", SRC).unwrap_err();
        assert!(matches!(e.reason, ErrorReason::PointCountMismatch { .. }));
        let e = parse_ban("XOffset=2.5\n1 2\n", SRC).unwrap_err();
        assert!(matches!(e.reason, ErrorReason::Unsupported { .. }));
    }

    #[test]
    fn columns_with_header_separators_and_decimal_comma() {
        let text = "# comment\ny [mm];z [mm]\n1,5;0,25\n2.5;0.5\n\n3\t0,75\n4 1 99\n5,1.5\n";
        let p = parse_columns(text, SRC, 1000.0).unwrap();
        assert_eq!(p.y, vec![0.0015, 0.0025, 0.003, 0.004, 0.005]);
        assert_eq!(p.z, vec![0.00025, 0.0005, 0.00075, 0.001, 0.0015]);
        assert_eq!(p.lines, vec![3, 4, 6, 7, 8]);
        let e = parse_columns("1 2\n2 3\n3 abc\n", SRC, 1000.0).unwrap_err();
        assert_eq!(e.location, Location::Line(3));
        assert!(matches!(e.reason, ErrorReason::NonNumeric { .. }));
        let e = parse_columns("1 2\n2\n", SRC, 1000.0).unwrap_err();
        assert!(matches!(e.reason, ErrorReason::WrongColumnCount { .. }));
    }

    #[test]
    fn bytes_nul_bom_and_line_endings() {
        let e = text_from_bytes(b"a\nb\n\0", SRC).unwrap_err();
        assert_eq!(
            (e.location, e.reason),
            (Location::Line(3), ErrorReason::Binary)
        );
        assert_eq!(text_from_bytes(b"\xEF\xBB\xBFx", SRC).unwrap(), "x");
        assert_eq!(text_from_bytes(b"\xFFx", SRC).unwrap(), "\u{FFFD}x");
        let l: Vec<_> = numbered_lines("a\r\nb\r\n").collect();
        assert_eq!(l, vec![(1, "a"), (2, "b"), (3, "")]);
        let l: Vec<_> = numbered_lines("a\rb").collect();
        assert_eq!(l, vec![(1, "a"), (2, "b")]);
    }
}
