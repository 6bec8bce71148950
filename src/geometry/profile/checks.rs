//! Plausibility checks of a profile read from a file: defects that parse cleanly but would make
//! every contact result wrong, each reported with the file, the reason and the fix.
//!
//! A file can be well-formed and still describe no usable wheel or rail: written in metres where
//! mm are expected, a wheel that was not mirrored into the frame of `docs/conventions.md`, a point
//! block cut short, a step or a spike from a measurement glitch. The contact search then fails
//! with messages that blame the pose, or worse, it succeeds with absurd forces. These checks run
//! when a file is loaded ([`Profile::from_file`](super::Profile::from_file) and the other readers;
//! the FMU's `fmi2ExitInitializationMode` and the command line report their message);
//! [`Profile::check_plausibility`](super::Profile::check_plausibility) runs them on any profile.
//! In order:
//!
//! 1. **Units** ([`check_units`]): a lateral extent below [`MIN_SPAN_M`] = 1 mm. A wheel profile
//!    spans ~130 mm, a rail head ~70 mm; the same numbers written in metres and read as mm span
//!    0.13 and 0.07 mm. (Checked on the raw points, before the ordering checks, which the
//!    thousandfold smaller steps would trip first.)
//! 2. **Wheel orientation**: the wheel frame has y towards the field side and the flange at
//!    negative y. The flange tip is the highest point (largest z, radius increase); a wheel has a
//!    flange if that point stands at least [`MIN_FLANGE_HEIGHT_M`] = 15 mm above the lowest point
//!    (flanges are 25–36 mm high; a hollow-worn tread without flange rises less). A flange in the
//!    half of the lateral range towards +y means the profile was not mirrored.
//! 3. **Coverage of the running surface**: a wheel must cover y = −20 … +20 mm around the taping
//!    line (the origin), where tread contact lies for lateral shifts up to the flange; a rail must
//!    descend at least [`MIN_RAIL_DEPTH_M`] = 10 mm below its highest point on both sides (the
//!    head's corners lie ~14 mm below the top). A truncated point block, or a wheel whose origin
//!    is not the taping line, fails here.
//! 4. **Gaps**: neighbouring points more than [`MAX_GAP_M`] = 3 mm apart (arc length) in the
//!    contact region (below). A Hertz patch is 5–15 mm wide: across a 3 mm hole the spline guesses
//!    a third of a patch. The benchmark files have at most 0.64 mm (wheel) and 0.93 mm (rail)
//!    there; decimated or partly deleted data fail.
//! 5. **Steps and spikes the smoothing does not absorb**: a point that lies more than
//!    [`DEFECT_OFFSET_M`] = 0.03 mm off the cubic through its four neighbours (two on each side,
//!    interpolated over the chord length, so the offset is measured normal to the curve also on
//!    steep flanks), *and* a fitted spline (with the file's smoothing length ℓ) that bends within
//!    three points and 3ℓ of it with a radius below [`MIN_RADIUS_M`] = 2 mm. The offset threshold
//!    is 7–20 times the offsets that the scatter of careful measurements gives (σ = 1–3 µm gives
//!    offsets of 1.4σ ≈ 1.4–4 µm; the benchmark files: ≤ 5 µm); a smooth curve of radius R sampled
//!    at h deviates by ≈ h⁴/(4R³): 1.1e−4 mm at h = 1 mm on R = 13 mm, 0.009 mm at the largest
//!    allowed spacing of 3 mm. The radius limit is well below the sharpest feature in any wheel or
//!    rail running surface (S1002: 9.2 mm at s = −35 mm; UIC60 gauge corner 13 mm; the benchmark
//!    files, interpolated, ≥ 11 mm); a Hertz patch on a 2 mm radius is wider than the feature. A
//!    0.5 mm step or a 0.1 mm spike on a rail crown (points 0.46 mm apart) bends an interpolating
//!    spline (ℓ = 0) to radii of 0.1–1 mm; a smoothing length of 0.5–1 mm spreads it over ~4ℓ (the
//!    spline's impulse response) and absorbs it. The message suggests the smallest of
//!    [`SMOOTHING_CANDIDATES_M`] that does (refitted and checked), or says that none up to the
//!    parameter's maximum does.
//!
//! The contact region of checks 4 and 5: for a wheel, from the flange tip (or, without a flange,
//! from the start) to y = [`WHEEL_CHECK_FIELD_M`] = +40 mm — tread contact lies within ±20 mm
//! of the taping line, a patch is at most ~15 mm wide, and neither the flange back nor the
//! field-side chamfer and face (with their sharp corners in measured data) ever touch the rail;
//! for a rail, the points at most [`CHECK_DEPTH_M`] = 20 mm below its highest point (crown,
//! corners, the upper gauge face). The near-vertical flanks below, where measured data are
//! sparse and contact cannot occur, are not checked.
//!
//! Limits: rails are not checked for orientation (a mirrored, symmetric rail head is the same
//! rail); a profile whose z points upwards is not recognised as such.

use super::error::ErrorReason;
use super::ProfileKind;
use crate::numeric::spline::CubicSpline;

/// Smallest lateral extent of a profile [m]; below, its numbers look like metres read as mm.
pub const MIN_SPAN_M: f64 = 1e-3;
/// Smallest height of a flange tip above the lowest point of a wheel profile [m].
pub const MIN_FLANGE_HEIGHT_M: f64 = 15e-3;
/// A wheel profile must cover the lateral coordinates −this … +this around its origin [m].
pub const WHEEL_COVERAGE_M: f64 = 20e-3;
/// A rail profile must descend this far below its highest point on both sides [m].
pub const MIN_RAIL_DEPTH_M: f64 = 10e-3;
/// Depth below the rail's highest point to which the rail is checked for gaps and defects [m].
pub const CHECK_DEPTH_M: f64 = 20e-3;
/// Lateral coordinate up to which a wheel is checked for gaps and defects [m].
pub const WHEEL_CHECK_FIELD_M: f64 = 40e-3;
/// Largest distance between neighbouring points in the contact region [m].
pub const MAX_GAP_M: f64 = 3e-3;
/// Offset of a point from the curve through its neighbours that marks a step or spike [m].
pub const DEFECT_OFFSET_M: f64 = 0.03e-3;
/// Smallest radius of curvature the fitted spline may have next to a step or spike [m].
pub const MIN_RADIUS_M: f64 = 2e-3;
/// Smoothing lengths tried for the suggestion [m] (the FMU's `profileSmoothing` allows 0.01 m).
pub const SMOOTHING_CANDIDATES_M: [f64; 7] = [0.5e-3, 1e-3, 1.5e-3, 2e-3, 3e-3, 5e-3, 10e-3];

/// Millimetres per metre (messages are in mm, the unit of profile files).
const MM: f64 = 1000.0;

/// A failed check: the reason, and the point to blame (index into the ascending points).
#[derive(Debug, Clone, PartialEq)]
pub struct Finding {
    pub point: Option<usize>,
    pub reason: ErrorReason,
}

impl Finding {
    fn at(point: usize, reason: ErrorReason) -> Self {
        Self {
            point: Some(point),
            reason,
        }
    }

    fn whole(reason: ErrorReason) -> Self {
        Self {
            point: None,
            reason,
        }
    }
}

/// Check 1 (module header): the lateral extent of the points `y` [m], in any order. Fewer than
/// two finite points pass (the ordering checks report them).
pub fn check_units(y: &[f64]) -> Result<(), ErrorReason> {
    let finite = y.iter().copied().filter(|v| v.is_finite());
    let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if y.len() >= 2 && hi >= lo && hi - lo < MIN_SPAN_M {
        return Err(ErrorReason::LooksLikeMetres {
            span_mm: (hi - lo) * MM,
        });
    }
    Ok(())
}

/// Checks 2–5 (module header) on a validated profile: points `y` (strictly ascending), `z`
/// [m], relative weights `w`, fitted with smoothing length `smoothing` [m] into `spline`.
pub fn check_shape(
    kind: ProfileKind,
    y: &[f64],
    z: &[f64],
    w: &[f64],
    smoothing: f64,
    spline: &CubicSpline,
) -> Result<(), Finding> {
    let n = y.len();
    let region = match kind {
        ProfileKind::Wheel => {
            let tip = flange_tip(z);
            if let Some(tip) = tip {
                if y[tip] > 0.5 * (y[0] + y[n - 1]) {
                    return Err(Finding::at(
                        tip,
                        ErrorReason::FlangeOnFieldSide {
                            y_mm: y[tip] * MM,
                            height_mm: (z[tip] - min(z)) * MM,
                        },
                    ));
                }
            }
            if y[0] > -WHEEL_COVERAGE_M || y[n - 1] < WHEEL_COVERAGE_M {
                return Err(Finding::whole(ErrorReason::WheelNotCovered {
                    from_mm: y[0] * MM,
                    to_mm: y[n - 1] * MM,
                    needed_mm: WHEEL_COVERAGE_M * MM,
                }));
            }
            // From the flange tip to WHEEL_CHECK_FIELD_M.
            let end = y.partition_point(|&v| v <= WHEEL_CHECK_FIELD_M);
            tip.unwrap_or(0)..end
        }
        ProfileKind::Rail => {
            let top = argmin(z);
            let depth = |range: std::ops::Range<usize>| {
                z[range].iter().fold(0.0f64, |d, &v| d.max(v - z[top]))
            };
            for (gauge_side, reached) in [(true, depth(0..top)), (false, depth(top + 1..n))] {
                if reached < MIN_RAIL_DEPTH_M {
                    return Err(Finding::whole(ErrorReason::RailNotCovered {
                        gauge_side,
                        depth_mm: reached * MM,
                        needed_mm: MIN_RAIL_DEPTH_M * MM,
                        from_mm: y[0] * MM,
                        to_mm: y[n - 1] * MM,
                    }));
                }
            }
            // The head down to CHECK_DEPTH_M: the contiguous run around the top.
            let shallow = |i: usize| z[i] - z[top] <= CHECK_DEPTH_M;
            let first = (0..=top)
                .rev()
                .take_while(|&i| shallow(i))
                .last()
                .unwrap_or(top);
            let last = (top..n).take_while(|&i| shallow(i)).last().unwrap_or(top);
            first..last + 1
        }
    };
    check_gaps(y, z, region.clone())?;
    check_defects(y, z, w, smoothing, spline, region)
}

/// The index of the wheel's flange tip (highest point), if it stands at least
/// [`MIN_FLANGE_HEIGHT_M`] above the lowest point.
fn flange_tip(z: &[f64]) -> Option<usize> {
    let tip = argmax(z);
    (z[tip] - min(z) >= MIN_FLANGE_HEIGHT_M).then_some(tip)
}

fn argmax(v: &[f64]) -> usize {
    (0..v.len()).fold(0, |best, i| if v[i] > v[best] { i } else { best })
}

fn argmin(v: &[f64]) -> usize {
    (0..v.len()).fold(0, |best, i| if v[i] < v[best] { i } else { best })
}

fn min(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::INFINITY, f64::min)
}

/// Distance between points `i` and `j` [m].
fn distance(y: &[f64], z: &[f64], i: usize, j: usize) -> f64 {
    (y[j] - y[i]).hypot(z[j] - z[i])
}

/// Check 4: no two neighbouring points of `region` further apart than [`MAX_GAP_M`].
fn check_gaps(y: &[f64], z: &[f64], region: std::ops::Range<usize>) -> Result<(), Finding> {
    for i in region.start + 1..region.end {
        let gap = distance(y, z, i - 1, i);
        if gap > MAX_GAP_M {
            return Err(Finding::at(
                i,
                ErrorReason::PointGap {
                    gap_mm: gap * MM,
                    from_y_mm: y[i - 1] * MM,
                    to_y_mm: y[i] * MM,
                    limit_mm: MAX_GAP_M * MM,
                },
            ));
        }
    }
    Ok(())
}

/// Distance [m] of point `i` from the cubic through its neighbours i−2, i−1, i+1, i+2, with y
/// and z interpolated over the chord length between those four (point i's own chords left out,
/// so that a spike does not stretch the parameter), evaluated at point i's projection onto the
/// chord from i−1 to i+1. Needs 2 ≤ i ≤ n − 3.
fn offset_from_neighbours(y: &[f64], z: &[f64], i: usize) -> f64 {
    let nodes = [i - 2, i - 1, i + 1, i + 2];
    let mut t = [0.0; 4];
    for k in 1..4 {
        t[k] = t[k - 1] + distance(y, z, nodes[k - 1], nodes[k]);
    }
    let (dy, dz) = (y[i + 1] - y[i - 1], z[i + 1] - z[i - 1]);
    let chord2 = dy * dy + dz * dz;
    let along = ((y[i] - y[i - 1]) * dy + (z[i] - z[i - 1]) * dz) / chord2;
    let at = t[1] + along.clamp(0.0, 1.0) * (t[2] - t[1]);
    let lagrange = |v: &[f64]| {
        (0..4)
            .map(|a| {
                let basis: f64 = (0..4)
                    .filter(|&b| b != a)
                    .map(|b| (at - t[b]) / (t[a] - t[b]))
                    .product();
                v[nodes[a]] * basis
            })
            .sum::<f64>()
    };
    (lagrange(y) - y[i]).hypot(lagrange(z) - z[i])
}

/// Largest |curvature| [1/m] of `spline` at the knots of `y` and the interval midpoints within
/// [`lo`, `hi`], with the lateral position where it occurs.
fn sharpest(spline: &CubicSpline, y: &[f64], lo: f64, hi: f64) -> (f64, f64) {
    let start = y.partition_point(|&v| v < lo);
    let mut worst = (0.0f64, lo);
    for i in start..y.len() {
        if y[i] > hi {
            break;
        }
        let mut probe = |v: f64| {
            let (_, d, dd) = spline.eval(v);
            let kappa = (dd / (1.0 + d * d).powf(1.5)).abs();
            if kappa > worst.0 {
                worst = (kappa, v);
            }
        };
        probe(y[i]);
        if i + 1 < y.len() && y[i + 1] <= hi {
            probe(0.5 * (y[i] + y[i + 1]));
        }
    }
    worst
}

/// The lateral window around point `i` in which the spline must stay flatter than
/// [`MIN_RADIUS_M`]: three points and 3ℓ on each side.
fn window(y: &[f64], i: usize, smoothing: f64) -> (f64, f64) {
    let lo = y[i.saturating_sub(3)] - 3.0 * smoothing;
    let hi = y[(i + 3).min(y.len() - 1)] + 3.0 * smoothing;
    (lo, hi)
}

/// Check 5: steps and spikes in `region` that the spline does not absorb.
fn check_defects(
    y: &[f64],
    z: &[f64],
    w: &[f64],
    smoothing: f64,
    spline: &CubicSpline,
    region: std::ops::Range<usize>,
) -> Result<(), Finding> {
    let n = y.len();
    let from = region.start.max(2);
    let to = region.end.min(n.saturating_sub(2));
    let defects: Vec<(usize, f64)> = (from..to)
        .map(|i| (i, offset_from_neighbours(y, z, i)))
        .filter(|&(_, offset)| offset > DEFECT_OFFSET_M)
        .collect();
    let max_curvature = 1.0 / MIN_RADIUS_M;
    // The defects around which `spline` (fitted with `length`) bends too sharply.
    let unabsorbed = |spline: &CubicSpline, length: f64| {
        defects
            .iter()
            .filter_map(|&(i, offset)| {
                let (lo, hi) = window(y, i, length);
                let (kappa, _) = sharpest(spline, y, lo, hi);
                (kappa > max_curvature).then_some((i, offset, kappa))
            })
            .collect::<Vec<_>>()
    };
    // Reported: the point furthest off its neighbours (a spike itself, the middle of a step).
    let Some((i, offset, kappa)) = unabsorbed(spline, smoothing)
        .into_iter()
        .max_by(|a, b| a.1.total_cmp(&b.1))
    else {
        return Ok(());
    };
    let suggestion = SMOOTHING_CANDIDATES_M
        .into_iter()
        .filter(|&length| length > smoothing)
        .find(|&length| {
            CubicSpline::fit(y, z, Some(w), length).is_ok_and(|s| unabsorbed(&s, length).is_empty())
        });
    Err(Finding::at(
        i,
        ErrorReason::StepOrSpike {
            y_mm: y[i] * MM,
            z_mm: z[i] * MM,
            offset_mm: offset * MM,
            radius_mm: MM / kappa,
            smoothing_m: smoothing,
            suggestion_m: suggestion,
            min_radius_mm: MIN_RADIUS_M * MM,
            largest_tried_m: SMOOTHING_CANDIDATES_M[SMOOTHING_CANDIDATES_M.len() - 1],
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The offset of a point on a circle of radius R sampled at h is ≈ h⁴/(4R³) (module header):
    /// 1.1e−4 mm at h = 1 mm, R = 13 mm, far below the 0.03 mm threshold; a spike of 0.1 mm on
    /// it is measured as 0.1 mm (to the curve's own 1e−4 mm), also on a vertical flank.
    #[test]
    fn offset_on_a_circle_and_of_a_spike() {
        let r = 13e-3;
        let h = 1e-3;
        let (y, z): (Vec<f64>, Vec<f64>) = (0..9)
            .map(|k| {
                let a = (k as f64 - 4.0) * h / r;
                (r * a.sin(), r * (1.0 - a.cos()))
            })
            .unzip();
        let offset = offset_from_neighbours(&y, &z, 4);
        assert!(offset < 2e-7 && offset > 0.5e-7, "{offset}");
        let mut spiked = z.clone();
        spiked[4] += 0.1e-3;
        let offset = offset_from_neighbours(&y, &spiked, 4);
        assert!((offset - 0.1e-3).abs() < 2e-7, "{offset}");
        // The same circle turned by 90°: a vertical flank (y and z swapped), y ascending.
        let offset = offset_from_neighbours(&z[4..], &y[4..], 2);
        assert!(offset < 2e-7, "{offset}");
    }

    #[test]
    fn units() {
        assert!(check_units(&[0.0, 0.13]).is_ok());
        assert!(check_units(&[]).is_ok());
        let e = check_units(&[-0.0696e-3, 0.06e-3, 0.0]).unwrap_err();
        let ErrorReason::LooksLikeMetres { span_mm } = e else {
            panic!("{e}");
        };
        assert!((span_mm - 0.1296).abs() < 1e-12, "{span_mm}");
    }
}
