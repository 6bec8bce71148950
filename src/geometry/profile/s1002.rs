//! The S1002 wheel profile (EN 13715 / UIC 510-2), analytic, and its sampling for the built-in
//! [`Profile`](super::Profile) "S1002".
//!
//! Source: EN 13715 (docs/theory.md §7.2: polynomial and circle sections A–H, all coefficients
//! below; its checks are this module's tests). Written from the equations; the widely copied
//! "courtesy H. Netter, DLR" teaching function was used for cross-checking only.
//!
//! s [mm] is measured from the taping line, positive towards the field side (the flange is at
//! negative s, its back at s = −70 mm); F(s) [mm] is the radius increase over the taping-line
//! radius (positive downwards in the profile frame). Sections, s from → to:
//!
//! | section | s [mm] | F(s) [mm] |
//! |---|---|---|
//! | A | +60 → +32.15796 | AA − BA s |
//! | B | +32.15796 → −26 | AB − BB s + CB s² − DB s³ + EB s⁴ − FB s⁵ + GB s⁶ − HB s⁷ + IB s⁸ |
//! | C | −26 → −35 | −AC − BC s − CC s² − … − HC s⁷ |
//! | D | −35 → −38.426669071 | AD − √(BD² − (s + CD)²) |
//! | E | −38.426669071 → −39.764473993 | −AE − BE s |
//! | F | −39.764473993 → −49.662510381 | AF + √(BF² − (s + CF)²) |
//! | G | −49.662510381 → −62.764705882 | AG + √(BG² − (s + CG)²) |
//! | H | −62.764705882 → −70 | AH + √(BH² − (s + CH)²) |
//!
//! Known limits: the published coefficients are rounded, so F jumps by 1.2e−4 mm at s = −35 and
//! 3.7e−5 mm at s = −26 (slope jumps ≤ 8e−6); F' → +∞ at the flange back s = −70 (vertical
//! tangent of arc H). The curvature is discontinuous at every section joint (as designed).
//!
//! The built-in profile samples F along its arc length every [`SAMPLE_ARC_STEP_MM`] (finer in y
//! where the profile is steep, down to [`MIN_SAMPLE_DY_MM`] at the flange back), with every
//! section joint as a sample, and interpolates the samples with the natural cubic spline
//! (`super::spline`): one evaluation path for built-in and measured profiles. The interpolation
//! error is O(h⁴) in value: measured 1.2e−8 mm more than 1 mm from the joints, 1e−4 mm next to
//! s = −35 where the published coefficients leave a 1.2e−4 mm jump. Being C², the spline rounds
//! the curvature jumps at the joints over a few samples (≈ ±0.3 mm).

/// Section A: F = AA − BA s.
const AA: f64 = 1.364_323_640;
const BA: f64 = 0.066_666_667;
/// Section B polynomial coefficients of s⁰ … s⁸ with their signs (AB, −BB, CB, −DB, …, IB).
const B_POLY: [f64; 9] = [
    0.0,
    -3.358_537_058e-2,
    1.565_681_624e-3,
    -2.810_427_944e-5,
    5.844_240_864e-8,
    -1.562_379_023e-8,
    5.309_217_349e-15,
    -5.957_839_843e-12,
    2.646_656_573e-13,
];
/// Section C polynomial coefficients of s⁰ … s⁷ with their signs (−AC, −BC, …, −HC).
const C_POLY: [f64; 8] = [
    -4.320_221_063e3,
    -1.038_384_026e3,
    -1.065_501_873e2,
    -6.051_367_875,
    -2.054_332_446e-1,
    -4.169_739_389e-3,
    -4.687_195_829e-5,
    -2.252_755_540e-7,
];
/// Section D: F = AD − √(BD² − (s + CD)²).
const AD: f64 = 16.446;
const BD: f64 = 13.0;
const CD: f64 = 26.210_665;
/// Section E: F = −AE − BE s.
const AE: f64 = 93.576_667_419;
const BE: f64 = 2.747_477_419;
/// Sections F, G, H: F = A + √(B² − (s + C)²).
const AF: f64 = 8.834_924_130;
const BF: f64 = 20.0;
const CF: f64 = 58.558_326_413;
const AG: f64 = 16.0;
const BG: f64 = 12.0;
const CG: f64 = 55.0;
const AH: f64 = 9.519_259_302;
const BH: f64 = 20.5;
const CH: f64 = 49.5;

/// Field-side end of the profile (start of section A) [mm].
pub const S_FIELD_END_MM: f64 = 60.0;
/// Flange back (end of section H) [mm]: 70 mm from the taping line.
pub const S_FLANGE_BACK_MM: f64 = -70.0;
/// Section joints A|B, B|C, …, G|H [mm], descending.
pub const JOINTS_MM: [f64; 7] = [
    32.157_96,
    -26.0,
    -35.0,
    -38.426_669_071,
    -39.764_473_993,
    -49.662_510_381,
    -62.764_705_882,
];
/// Arc-length step of the built-in sampling [mm] (interpolation error ~h⁴/384·F'''' ≪ 1 µm on the
/// tread; 0.1 mm is also the element size of the benchmark computations, tests/data/README.md).
pub const SAMPLE_ARC_STEP_MM: f64 = 0.1;
/// Smallest lateral step of the built-in sampling [mm], reached only at the vertical flange back.
pub const MIN_SAMPLE_DY_MM: f64 = 1e-3;

/// The section (0 = A … 7 = H) that holds `s` [mm] (joints belong to the section on their field
/// side, i.e. the one listed first).
pub fn section_of(s: f64) -> usize {
    JOINTS_MM.iter().position(|&j| s >= j).unwrap_or(7)
}

/// F, F' = dF/ds and F'' [mm, –, 1/mm] of section `section` (0 = A … 7 = H) at `s` [mm], without
/// a range check (used to compare both sides of a joint). NaN where a circle section is undefined.
pub fn section_eval(section: usize, s: f64) -> [f64; 3] {
    match section {
        0 => [AA - BA * s, -BA, 0.0],
        1 => polynomial(&B_POLY, s),
        2 => polynomial(&C_POLY, s),
        3 => circle(AD, BD, CD, s, -1.0),
        4 => [-AE - BE * s, -BE, 0.0],
        5 => circle(AF, BF, CF, s, 1.0),
        6 => circle(AG, BG, CG, s, 1.0),
        _ => circle(AH, BH, CH, s, 1.0),
    }
}

/// F(s), F'(s), F''(s) [mm, –, 1/mm] of the S1002 wheel at s [mm] from the taping line, for
/// −70 ≤ s ≤ 60; `None` outside (or for NaN). At s = −70, F' = +∞.
pub fn s1002_mm(s: f64) -> Option<[f64; 3]> {
    if (S_FLANGE_BACK_MM..=S_FIELD_END_MM).contains(&s) {
        Some(section_eval(section_of(s), s))
    } else {
        None
    }
}

/// Value and first two derivatives of Σ cₖ sᵏ (Horner).
fn polynomial(c: &[f64], s: f64) -> [f64; 3] {
    let (mut p, mut dp, mut ddp) = (0.0, 0.0, 0.0);
    for &ck in c.iter().rev() {
        ddp = ddp * s + 2.0 * dp;
        dp = dp * s + p;
        p = p * s + ck;
    }
    [p, dp, ddp]
}

/// F = a + sign·√(r² − (s + c)²) and its derivatives: F' = −sign·u/w, F'' = −sign·r²/w³, with
/// u = s + c and w = √(r² − u²).
fn circle(a: f64, r: f64, c: f64, s: f64, sign: f64) -> [f64; 3] {
    let u = s + c;
    let w = (r * r - u * u).sqrt();
    [a + sign * w, -sign * u / w, -sign * r * r / (w * w * w)]
}

/// Samples the profile from the flange back to the field end in ascending s: arc-length step
/// [`SAMPLE_ARC_STEP_MM`], lateral step at least [`MIN_SAMPLE_DY_MM`], every joint included.
/// Returns (s, F) in mm.
pub fn sample_mm() -> (Vec<f64>, Vec<f64>) {
    let mut joints: Vec<f64> = JOINTS_MM.to_vec();
    joints.reverse(); // ascending
    let mut s_out = Vec::with_capacity(1600);
    let mut f_out = Vec::with_capacity(1600);
    let mut s = S_FLANGE_BACK_MM;
    let mut next_joint = 0;
    loop {
        let [f, df, _] = section_eval(section_of(s), s);
        s_out.push(s);
        f_out.push(f);
        if s >= S_FIELD_END_MM {
            break;
        }
        // dy = ds / √(1 + F'²); F' = ±∞ at the flange back gives the minimum step.
        let dy = (SAMPLE_ARC_STEP_MM / (1.0 + df * df).sqrt()).max(MIN_SAMPLE_DY_MM);
        let mut next = s + dy;
        while next_joint < joints.len() && joints[next_joint] <= s {
            next_joint += 1;
        }
        if next_joint < joints.len() && next >= joints[next_joint] - 0.5 * MIN_SAMPLE_DY_MM {
            next = joints[next_joint];
        }
        if next > S_FIELD_END_MM - 0.5 * MIN_SAMPLE_DY_MM {
            next = S_FIELD_END_MM;
        }
        s = next;
    }
    (s_out, f_out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::roots::bisect;

    fn f(s: f64) -> [f64; 3] {
        s1002_mm(s).unwrap()
    }

    /// Bisection for F(s) = level on [a, b] (F(a) − level and F(b) − level of opposite sign).
    fn solve(level: f64, a: f64, b: f64) -> f64 {
        let above_at_a = f(a)[0] - level > 0.0;
        bisect(a, b, 0.0, |m| (f(m)[0] - level > 0.0) == above_at_a)
    }

    /// docs/theory.md §7.2: F(0) = 0, F'(0) = −0.03359, F''(0) = 3.13e−3 1/mm (quoted to 4 and 3
    /// significant digits: tolerances half a unit of the last quoted digit).
    #[test]
    fn taping_line_values() {
        let [v, d, dd] = f(0.0);
        assert_eq!(v, 0.0);
        assert!((d + 0.03359).abs() < 0.5e-5, "{d}");
        assert!((dd - 3.13e-3).abs() < 0.5e-5, "{dd}");
    }

    /// Flange height 28.000 mm = max F, at s = −55 (the top of arc G, centre (−55, 16), radius 12:
    /// exact by construction, so 1e−9 mm); taping line 70 mm from the flange back.
    #[test]
    fn flange_height_and_taping_line_position() {
        let [top, slope, _] = f(-55.0);
        assert!((top - 28.0).abs() < 1e-12);
        assert!(slope.abs() < 1e-12);
        let mut max = f64::MIN;
        let mut s_at = 0.0;
        for i in 0..=130_000 {
            let s = -70.0 + 1e-3 * i as f64;
            let v = f(s)[0];
            if v > max {
                max = v;
                s_at = s;
            }
        }
        assert!((max - 28.0).abs() < 1e-9 && (s_at + 55.0).abs() < 1e-9);
        assert_eq!(S_FLANGE_BACK_MM, -70.0);
        assert!(s1002_mm(-70.0 - 1e-9).is_none() && s1002_mm(60.0 + 1e-9).is_none());
        assert!(s1002_mm(f64::NAN).is_none());
    }

    /// Flange thickness 32.500 mm: the flange face passes F = 10 mm at s = −37.500 (arc D gives
    /// F(−37.5) = 10 + 5.8e−8 mm, slope −1.75, so the crossing is within 1e−7 mm of −37.5), measured
    /// to the flange back at −70. Tolerance 1e−6 mm.
    #[test]
    fn flange_thickness() {
        let s10 = solve(10.0, -55.0, -26.0);
        assert!((s10 + 37.5).abs() < 1e-6, "{s10}");
        assert!((s10 - S_FLANGE_BACK_MM - 32.5).abs() < 1e-6);
    }

    /// Joints: value and slope jumps from coefficient rounding (docs/theory.md §7.2: 1.2e−4 mm at
    /// −35, 3.6e−5 mm at −26). Measured: 1.18e−4 and 3.65e−5 mm, slope jumps 7.7e−6 and 3.2e−6;
    /// every other joint < 1e−7 mm and < 1e−8 in slope. Tolerances just above the measured values.
    #[test]
    fn continuity_at_every_joint() {
        for (k, &j) in JOINTS_MM.iter().enumerate() {
            let field_side = section_eval(k, j);
            let flange_side = section_eval(k + 1, j);
            let dv = (field_side[0] - flange_side[0]).abs();
            let ds = (field_side[1] - flange_side[1]).abs();
            let (tv, ts) = match j {
                -35.0 => (1.3e-4, 1e-5),
                -26.0 => (4e-5, 1e-5),
                _ => (1e-7, 1e-8),
            };
            assert!(dv < tv, "joint {j}: value jump {dv}");
            assert!(ds < ts, "joint {j}: slope jump {ds}");
        }
    }

    #[test]
    fn sampling_is_ascending_complete_and_on_the_curve() {
        let (s, v) = sample_mm();
        assert_eq!(s[0], -70.0);
        assert_eq!(*s.last().unwrap(), 60.0);
        assert!(s.windows(2).all(|p| p[1] - p[0] >= 0.5 * MIN_SAMPLE_DY_MM));
        for j in JOINTS_MM {
            assert!(s.contains(&j), "joint {j} sampled");
        }
        for (si, vi) in s.iter().zip(&v) {
            assert!(vi.is_finite() && (vi - f(*si)[0]).abs() < 1e-12);
        }
        assert!(s.len() > 1300 && s.len() < 2000, "{}", s.len());
    }
}
