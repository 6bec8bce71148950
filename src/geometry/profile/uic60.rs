//! The UIC60 / 60E1 rail head (EN 13674-1), built from tangent arcs and flanks, and its sampling
//! for the built-in [`Profile`](super::Profile) "UIC60" / "60E1".
//!
//! Source: EN 13674-1 (docs/theory.md §7.3) — nominal head radii R300 (crown) – R80 – R13 (gauge
//! corner), flanks 1:20, head width 72 mm measured 14 mm below the top; the junction positions are
//! a construction of ours (the EN drawing was not at hand).
//!
//! # Construction (mm, origin at the crown top of the un-inclined rail, y lateral, z down; the
//! head is symmetric about y = 0 — the right half is described)
//!
//! 1. **Crown R300**, centre (0, 300), for 0 ≤ y ≤ y₁ with y₁ = [`CROWN_END_Y_MM`] = 10.5 mm.
//! 2. **R80**, internally tangent to the crown at angle α₁ = asin(y₁/300): centre
//!    c₈₀ = (220 sin α₁, 300 − 220 cos α₁) = (7.700, 80.135), from α₁ to α₂.
//! 3. **R13**, internally tangent to R80 at α₂: centre c₁₃ = c₈₀ + 67 (sin α₂, −cos α₂), from α₂ to
//!    α₃ = atan 20, where its tangent has the flank slope.
//! 4. **Flank** 1:20 (the head widens downwards by 1 mm per 20 mm; dz/dy = 20), tangent to R13 at
//!    α₃, down to z = [`FLANK_END_DEPTH_MM`].
//!
//! (A point at angle α on an arc of centre c and radius r is c + r (sin α, −cos α).) Tangency
//! makes value and slope continuous at every junction; the curvature jumps (1/300 → 1/80 → 1/13 →
//! 0 mm⁻¹), as on the real rail. α₂ is the one free parameter left: it is solved (bisection) so
//! that the head is **72.000 mm** wide at 14 mm below the top. The result: R80 ends at
//! |y| = 26.01 mm (z = 2.26), c₁₃ = (±23.03, 14.91), the flank starts at |y| = 36.02 mm
//! (z = 14.26) — as a fit of the arcs to the de-inclined benchmark rail gives (R80 to |y| ≈ 26.0, z
//! ≈ 2.3; c₁₃ ≈ (23.03, 14.94); R13 to z ≈ 14.3).
//!
//! y₁ = 10.5 mm was chosen by fitting the crown and R80 to the benchmark rail
//! `MBench_UIC60_v3.prr`, de-canted by atan(1/40) about its crown (translation 300·(sin θ,
//! 1 − cos θ), θ = atan 1/40): over |y| < 25 mm the rms vertical deviation is 0.7 µm at y₁ = 10.5
//! and rises to 13 µm at y₁ = 10.3. The benchmark's gauge corner
//! differs from this construction by up to 0.03 mm (its head width is 71.95, not 72.00 mm).
//!
//! Known limits: only the head (z ≤ 38.5 mm, the depth the benchmark file covers; not an EN
//! dimension); no fishing surfaces, web or foot; no inclination (cant the rail in the
//! wheel–rail geometry, not here).

use crate::numeric::roots::bisect;

/// Crown radius [mm].
pub const R_CROWN_MM: f64 = 300.0;
/// Shoulder radius [mm].
pub const R_SHOULDER_MM: f64 = 80.0;
/// Gauge-corner radius [mm].
pub const R_CORNER_MM: f64 = 13.0;
/// Flank inclination: the flank drops 20 mm per mm of widening (1:20).
pub const FLANK_SLOPE: f64 = 20.0;
/// End of the crown arc, |y| [mm] (fitted to the benchmark rail; module header).
pub const CROWN_END_Y_MM: f64 = 10.5;
/// Nominal head width [mm] …
pub const HEAD_WIDTH_MM: f64 = 72.0;
/// … measured this far below the top [mm] (also the gauge measuring depth, docs/theory.md §7.5).
pub const GAUGE_DEPTH_MM: f64 = 14.0;
/// Depth where the sampled flank ends [mm] (the extent of the benchmark file; not an EN value).
pub const FLANK_END_DEPTH_MM: f64 = 38.5;
/// Arc-length step of the built-in sampling [mm].
pub const SAMPLE_ARC_STEP_MM: f64 = 0.1;

/// The head geometry: arc centres and junction angles (right half, mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadGeometry {
    /// Junction angle crown | R80 [rad].
    pub alpha1: f64,
    /// Junction angle R80 | R13 [rad].
    pub alpha2: f64,
    /// Junction angle R13 | flank [rad] = atan(FLANK_SLOPE).
    pub alpha3: f64,
    /// Centre of R80 (y, z) [mm].
    pub c80: (f64, f64),
    /// Centre of R13 (y, z) [mm].
    pub c13: (f64, f64),
}

/// Point of an arc with centre `c` and radius `r` at angle `a` (0 = top of the circle).
fn arc_point(c: (f64, f64), r: f64, a: f64) -> (f64, f64) {
    (c.0 + r * a.sin(), c.1 - r * a.cos())
}

impl HeadGeometry {
    /// Geometry for a given R80 | R13 junction angle `alpha2`.
    fn with_alpha2(alpha2: f64) -> Self {
        let alpha1 = (CROWN_END_Y_MM / R_CROWN_MM).asin();
        let c80 = arc_point((0.0, R_CROWN_MM), R_CROWN_MM - R_SHOULDER_MM, alpha1);
        let c13 = arc_point(c80, R_SHOULDER_MM - R_CORNER_MM, alpha2);
        Self {
            alpha1,
            alpha2,
            alpha3: FLANK_SLOPE.atan(),
            c80,
            c13,
        }
    }

    /// The nominal head: α₂ solved so that the width at [`GAUGE_DEPTH_MM`] is [`HEAD_WIDTH_MM`].
    pub fn nominal() -> Self {
        let target = 0.5 * HEAD_WIDTH_MM;
        let alpha1 = (CROWN_END_Y_MM / R_CROWN_MM).asin();
        // The half-width at the gauge depth grows with α₂ (the gauge corner moves outwards).
        let alpha2 = bisect(alpha1, FLANK_SLOPE.atan(), 0.0, |alpha2| {
            Self::with_alpha2(alpha2)
                .half_width_at_mm(GAUGE_DEPTH_MM)
                .is_some_and(|w| w < target)
        });
        Self::with_alpha2(alpha2)
    }

    /// Junctions (|y|, z) [mm] of the right half: crown|R80, R80|R13, R13|flank, flank end.
    pub fn junctions_mm(&self) -> [(f64, f64); 4] {
        let j1 = arc_point((0.0, R_CROWN_MM), R_CROWN_MM, self.alpha1);
        let j2 = arc_point(self.c80, R_SHOULDER_MM, self.alpha2);
        let j3 = arc_point(self.c13, R_CORNER_MM, self.alpha3);
        let j4 = (
            j3.0 + (FLANK_END_DEPTH_MM - j3.1) / FLANK_SLOPE,
            FLANK_END_DEPTH_MM,
        );
        [j1, j2, j3, j4]
    }

    /// z, dz/dy, d²z/dy² [mm, –, 1/mm] of segment `seg` (0 crown, 1 R80, 2 R13, 3 flank) at
    /// |y| = `ya` ≥ 0 [mm], without a range check (to compare both sides of a junction).
    pub fn segment_eval_mm(&self, seg: usize, ya: f64) -> [f64; 3] {
        let arc = |c: (f64, f64), r: f64| {
            let u = ya - c.0;
            let w = (r * r - u * u).sqrt();
            [c.1 - w, u / w, r * r / (w * w * w)]
        };
        match seg {
            0 => arc((0.0, R_CROWN_MM), R_CROWN_MM),
            1 => arc(self.c80, R_SHOULDER_MM),
            2 => arc(self.c13, R_CORNER_MM),
            _ => {
                let j3 = self.junctions_mm()[2];
                [j3.1 + FLANK_SLOPE * (ya - j3.0), FLANK_SLOPE, 0.0]
            }
        }
    }

    /// z, dz/dy, d²z/dy² [mm, –, 1/mm] at y [mm]; `None` beyond the flank ends (or NaN).
    pub fn eval_mm(&self, y: f64) -> Option<[f64; 3]> {
        let ya = y.abs();
        let j = self.junctions_mm();
        let seg = j.iter().position(|p| ya <= p.0)?;
        let [v, d, dd] = self.segment_eval_mm(seg, ya);
        Some([v, d * y.signum(), dd])
    }

    /// Half-width [mm] of the head at depth `z` [mm] below the top (right half; `None` below the
    /// flank end or above the top).
    pub fn half_width_at_mm(&self, z: f64) -> Option<f64> {
        if !(0.0..=FLANK_END_DEPTH_MM).contains(&z) {
            return None;
        }
        let j = self.junctions_mm();
        let arc_y = |c: (f64, f64), r: f64| c.0 + (r * r - (c.1 - z) * (c.1 - z)).sqrt();
        Some(if z <= j[0].1 {
            arc_y((0.0, R_CROWN_MM), R_CROWN_MM)
        } else if z <= j[1].1 {
            arc_y(self.c80, R_SHOULDER_MM)
        } else if z <= j[2].1 {
            arc_y(self.c13, R_CORNER_MM)
        } else {
            j[2].0 + (z - j[2].1) / FLANK_SLOPE
        })
    }

    /// Samples the whole head (both halves, ascending y) every [`SAMPLE_ARC_STEP_MM`] of arc
    /// length, junctions included, directly on the arcs and the flank. Returns (y, z) in mm.
    pub fn sample_mm(&self) -> (Vec<f64>, Vec<f64>) {
        let mut right: Vec<(f64, f64)> = Vec::with_capacity(600);
        // Each segment starts where the previous one ended (the crown at y = 0, added below).
        let mut arc = |c: (f64, f64), r: f64, a0: f64, a1: f64| {
            let n = ((r * (a1 - a0) / SAMPLE_ARC_STEP_MM).ceil() as usize).max(1);
            for k in 1..=n {
                right.push(arc_point(c, r, a0 + (a1 - a0) * k as f64 / n as f64));
            }
        };
        arc((0.0, R_CROWN_MM), R_CROWN_MM, 0.0, self.alpha1);
        arc(self.c80, R_SHOULDER_MM, self.alpha1, self.alpha2);
        arc(self.c13, R_CORNER_MM, self.alpha2, self.alpha3);
        let [_, _, j3, j4] = self.junctions_mm();
        let flank_len = ((j4.0 - j3.0).powi(2) + (j4.1 - j3.1).powi(2)).sqrt();
        let n = ((flank_len / SAMPLE_ARC_STEP_MM).ceil() as usize).max(1);
        for k in 1..n {
            let t = k as f64 / n as f64;
            right.push((j3.0 + t * (j4.0 - j3.0), j3.1 + t * (j4.1 - j3.1)));
        }
        right.push(j4);
        let mut y = Vec::with_capacity(2 * right.len() + 1);
        let mut z = Vec::with_capacity(2 * right.len() + 1);
        for &(py, pz) in right.iter().rev() {
            y.push(-py);
            z.push(pz);
        }
        y.push(0.0);
        z.push(0.0);
        for &(py, pz) in &right {
            y.push(py);
            z.push(pz);
        }
        (y, z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Head width 72.000 mm at 14 mm (solved to machine precision; 1e−9 mm).
    #[test]
    fn head_width_is_72_mm_at_14_mm() {
        let g = HeadGeometry::nominal();
        let w = 2.0 * g.half_width_at_mm(GAUGE_DEPTH_MM).unwrap();
        assert!((w - 72.0).abs() < 1e-9, "{w}");
        // On the R13 arc, as the fit to the benchmark rail has it.
        let j = g.junctions_mm();
        assert!(j[1].1 < 14.0 && 14.0 < j[2].1);
    }

    /// The junctions agree with a fit of the arcs to the benchmark rail (quoted to ~0.1 mm for the
    /// positions and ~0.03 mm for the R13 centre).
    #[test]
    fn junctions_close_to_the_reconstruction() {
        let g = HeadGeometry::nominal();
        let j = g.junctions_mm();
        assert!((j[0].0 - 10.5).abs() < 1e-12);
        assert!(
            (j[1].0 - 26.0).abs() < 0.1 && (j[1].1 - 2.3).abs() < 0.1,
            "{:?}",
            j[1]
        );
        assert!((g.c13.0 - 23.03).abs() < 0.03 && (g.c13.1 - 14.94).abs() < 0.05);
        assert!(
            (j[2].0 - 36.0).abs() < 0.1 && (j[2].1 - 14.3).abs() < 0.1,
            "{:?}",
            j[2]
        );
        assert!((g.c80.1 - 80.13).abs() < 0.01);
    }

    /// Value and slope continuous at every junction (tangent arcs: rounding only, 1e−9 mm and
    /// 1e−9 in slope, relative to the slope for the steep R13|flank junction).
    #[test]
    fn continuity_at_every_junction() {
        let g = HeadGeometry::nominal();
        let j = g.junctions_mm();
        for (k, &(jy, jz)) in j.iter().take(3).enumerate() {
            let a = g.segment_eval_mm(k, jy);
            let b = g.segment_eval_mm(k + 1, jy);
            assert!((a[0] - b[0]).abs() < 1e-9, "junction {k}: {a:?} {b:?}");
            assert!(
                (a[1] - b[1]).abs() < 1e-9 * a[1].abs().max(1.0),
                "junction {k}"
            );
            assert!((a[0] - jz).abs() < 1e-9);
        }
        // Curvature jumps as designed: 1/300 → 1/80 at junction 0 (slope ~0.035).
        let a = g.segment_eval_mm(0, j[0].0);
        let b = g.segment_eval_mm(1, j[0].0);
        let k = |v: [f64; 3]| v[2] / (1.0 + v[1] * v[1]).powf(1.5);
        assert!((k(a) - 1.0 / 300.0).abs() < 1e-12 && (k(b) - 1.0 / 80.0).abs() < 1e-12);
    }

    #[test]
    fn symmetric_and_crown_radius() {
        let g = HeadGeometry::nominal();
        for i in 0..=370 {
            let y = 0.1 * i as f64;
            let a = g.eval_mm(y).unwrap();
            let b = g.eval_mm(-y).unwrap();
            assert!(a[0] == b[0] && a[1] == -b[1] && a[2] == b[2]);
        }
        let c = g.eval_mm(0.0).unwrap();
        assert!(c[0] == 0.0 && c[1] == 0.0 && (1.0 / c[2] - 300.0).abs() < 1e-9);
        assert!(g.eval_mm(40.0).is_none() && g.eval_mm(f64::NAN).is_none());
    }

    #[test]
    fn sampling_is_ascending_and_on_the_curve() {
        let g = HeadGeometry::nominal();
        let (y, z) = g.sample_mm();
        assert!(y.windows(2).all(|p| p[1] > p[0]));
        for (yi, zi) in y.iter().zip(&z) {
            let v = g.eval_mm(*yi).unwrap()[0];
            assert!((v - zi).abs() < 1e-9, "{yi} {zi} {v}");
        }
        assert_eq!(y.len() % 2, 1);
        assert_eq!(y[y.len() / 2], 0.0);
    }
}
