//! The wear-prediction loop's profile update (docs/theory.md §10.6): wear records of runs
//! ([`super::record::WearRecord::csv`]) turned into worn wheel and rail profiles.
//!
//! Steps (Jendel 2002; Enblom & Berg; the review of Bosso, Magelli & Zampieri 2022):
//!
//! 1. **Sum** the records' masses per bin and their distances L (several runs: several speeds,
//!    disturbances or curves, each a share of the traffic).
//! 2. **Scale** to the running distance D: the wheel's depth d_w(y) = m(y) D / (ρ Δy 2π r0 L),
//!    the rail's d_r(y) = m(y) D / (ρ Δy L²) × L (a rail section is passed once per run: D/L
//!    passages of the run's mean depth per passage) — both the record's depth times D/L.
//! 3. **Smooth** each depth with a Gaussian of standard deviation ℓ (bins beyond the ends taken
//!    as zero): the patches' strips and the 0.5 mm bins leave ripples no profile has.
//! 4. **Limit** the update: if the deepest point exceeds the largest depth per update, D is
//!    reduced so that it equals it (the effective distance is reported).
//! 5. **Remove** the depth along the surface's normal: the depth per bin is material per unit of
//!    lateral width; on a flank of slope z' the surface is longer by √(1 + z'²), so the normal
//!    depth is d/√(1 + z'²), and each point moves by it into the material (the wheel: towards
//!    smaller radius, −z; the rail: into the head, +z).
//!
//! Left and right records are averaged (a symmetric wheelset has one worn profile; the records'
//! coordinates are the profiles' own, towards the field side on both wheels).

use super::profile::WEAR_BIN;
use super::wear::STEEL_DENSITY;

/// The summed wear records: per body (0 wheel, 1 rail) the bins' centres [m] and the mean of the
/// left and right masses [kg], the distance rolled [m] and the nominal wheel radius [m].
#[derive(Debug, Clone, PartialEq)]
pub struct WearRecords {
    pub y: [Vec<f64>; 2],
    pub mass: [Vec<f64>; 2],
    pub distance: f64,
    pub wheel_radius: f64,
}

/// What went wrong reading a record (the line and the reason).
pub type RecordError = String;

impl WearRecords {
    /// Parses one record's CSV text (`source` names it in errors).
    pub fn parse(text: &str, source: &str) -> Result<Self, RecordError> {
        let mut distance = None;
        let mut wheel_radius = None;
        let mut rows: [[Vec<(f64, f64)>; 2]; 2] = Default::default();
        for (n, line) in text.lines().enumerate() {
            let at = |what: &str| format!("{source}, line {}: {what}", n + 1);
            let line = line.trim();
            if let Some(comment) = line.strip_prefix('#') {
                let mut parts = comment.trim().split(',');
                let (key, value) = (parts.next().unwrap_or(""), parts.next());
                let number = |v: Option<&str>| {
                    v.and_then(|v| v.trim().parse::<f64>().ok())
                        .filter(|x| x.is_finite() && *x >= 0.0)
                        .ok_or_else(|| at(&format!("{key} is not a non-negative number")))
                };
                match key {
                    "distance_m" => distance = Some(number(value)?),
                    "wheel_radius_m" => wheel_radius = Some(number(value)?),
                    "bin_m" if (number(value)? - WEAR_BIN).abs() > 1e-12 => {
                        return Err(at(&format!("bins of {WEAR_BIN} m expected")));
                    }
                    _ => {}
                }
                continue;
            }
            if line.is_empty() || line.starts_with("side,") {
                continue;
            }
            let f: Vec<&str> = line.split(',').collect();
            if f.len() < 4 {
                return Err(at("expected side,body,y,mass,depth"));
            }
            let side = match f[0] {
                "left" => 0,
                "right" => 1,
                other => return Err(at(&format!("side {other:?} is not left or right"))),
            };
            let body = match f[1] {
                "wheel" => 0,
                "rail" => 1,
                other => return Err(at(&format!("body {other:?} is not wheel or rail"))),
            };
            let number = |t: &str| {
                t.trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| at(&format!("{t:?} is not a finite number")))
            };
            let (y, m) = (number(f[2])?, number(f[3])?);
            if m < 0.0 {
                return Err(at(&format!("negative mass {m}")));
            }
            rows[side][body].push((y, m));
        }
        let distance = distance.ok_or_else(|| format!("{source}: no '# distance_m' line"))?;
        let wheel_radius =
            wheel_radius.ok_or_else(|| format!("{source}: no '# wheel_radius_m' line"))?;
        let mut y: [Vec<f64>; 2] = Default::default();
        let mut mass: [Vec<f64>; 2] = Default::default();
        for body in 0..2 {
            let [left, right] = [&rows[0][body], &rows[1][body]];
            if left.len() != right.len() || left.iter().zip(right).any(|(a, b)| a.0 != b.0) {
                return Err(format!(
                    "{source}: the left and right {} bins differ",
                    ["wheel", "rail"][body]
                ));
            }
            y[body] = left.iter().map(|r| r.0).collect();
            mass[body] = left
                .iter()
                .zip(right)
                .map(|(a, b)| 0.5 * (a.1 + b.1))
                .collect();
        }
        Ok(Self {
            y,
            mass,
            distance,
            wheel_radius,
        })
    }

    /// Adds another record of the same profiles (the same bins).
    pub fn add(&mut self, other: &Self, source: &str) -> Result<(), RecordError> {
        if self.y != other.y {
            return Err(format!(
                "{source}: its bins differ from the first record's (other profiles?)"
            ));
        }
        for body in 0..2 {
            for (m, o) in self.mass[body].iter_mut().zip(&other.mass[body]) {
                *m += o;
            }
        }
        self.distance += other.distance;
        Ok(())
    }

    /// The depth per bin of `body` after the running distance `distance` [m] (step 2), smoothed
    /// over `smoothing` [m] (step 3).
    pub fn depth(&self, body: usize, distance: f64, smoothing: f64) -> Vec<f64> {
        if self.distance.is_nan() || self.distance <= 0.0 {
            return vec![0.0; self.mass[body].len()];
        }
        let length = if body == 0 {
            2.0 * std::f64::consts::PI * self.wheel_radius
        } else {
            self.distance
        };
        let scale = distance / self.distance / (STEEL_DENSITY * WEAR_BIN * length);
        let raw: Vec<f64> = self.mass[body].iter().map(|m| m * scale).collect();
        smooth(&raw, smoothing / WEAR_BIN)
    }
}

/// `values` convolved with a Gaussian of standard deviation `sigma` bins (none for σ ≤ 0),
/// truncated at 4σ, zero beyond the ends.
fn smooth(values: &[f64], sigma: f64) -> Vec<f64> {
    if sigma.is_nan() || sigma <= 0.0 {
        return values.to_vec();
    }
    let reach = (4.0 * sigma).ceil() as isize;
    let weights: Vec<f64> = (-reach..=reach)
        .map(|k| (-0.5 * (k as f64 / sigma).powi(2)).exp())
        .collect();
    let total: f64 = weights.iter().sum();
    let n = values.len() as isize;
    (0..n)
        .map(|i| {
            (-reach..=reach)
                .zip(&weights)
                .filter_map(|(k, w)| {
                    let j = i + k;
                    (0..n).contains(&j).then(|| w * values[j as usize])
                })
                .sum::<f64>()
                / total
        })
        .collect()
}

/// The profile points (`y`, `z`) [m] with `depth(y)` removed along the normal (step 5): into
/// the material, −z for the wheel (`wheel` true) and +z for the rail; `slope(y)` is dz/dy.
pub fn worn_points(
    (y, z): (&[f64], &[f64]),
    wheel: bool,
    depth: impl Fn(f64) -> f64,
    slope: impl Fn(f64) -> f64,
) -> (Vec<f64>, Vec<f64>) {
    let into = if wheel { -1.0 } else { 1.0 };
    y.iter()
        .zip(z)
        .map(|(&y, &z)| {
            let s = slope(y);
            let norm = (1.0 + s * s).sqrt();
            // Normal depth d/√(1 + z'²) along the unit normal (−z', 1)/√(1 + z'²) × into.
            let d = depth(y) / norm;
            (y - into * d * s / norm, z + into * d / norm)
        })
        .unzip()
}

/// Linear interpolation of `values` at bin centres `ys` (ascending) at `y`; 0 outside.
pub fn at_bins(ys: &[f64], values: &[f64], y: f64) -> f64 {
    let (Some(&first), Some(&last)) = (ys.first(), ys.last()) else {
        return 0.0;
    };
    if !(y >= first && y <= last) || ys.len() < 2 {
        return 0.0;
    }
    let i = ys.partition_point(|&c| c <= y).clamp(1, ys.len() - 1);
    let (y0, y1) = (ys[i - 1], ys[i]);
    let f = if y1 > y0 { (y - y0) / (y1 - y0) } else { 0.0 };
    values[i - 1] * (1.0 - f) + values[i] * f
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(mass_wheel: &[f64], distance: f64) -> String {
        let mut s = format!("# distance_m,{distance:e}\n# wheel_radius_m,4.6e-1\n# bin_m,5e-4\n");
        s.push_str("side,body,y,mass,depth\n");
        for side in ["left", "right"] {
            for (body, masses) in [("wheel", mass_wheel), ("rail", mass_wheel)] {
                for (i, m) in masses.iter().enumerate() {
                    s.push_str(&format!(
                        "{side},{body},{:e},{m:e},0\n",
                        i as f64 * WEAR_BIN
                    ));
                }
            }
        }
        s
    }

    #[test]
    fn records_sum_scale_and_smooth() {
        let a = WearRecords::parse(&record(&[0.0, 1e-6, 0.0, 0.0], 10.0), "a").unwrap();
        let mut sum = a.clone();
        sum.add(&a, "b").unwrap();
        assert_eq!(sum.distance, 20.0);
        // Depths scale with D/L: the summed records over 20 m give what one gives over 10 m.
        let (one, two) = (a.depth(0, 1000.0, 0.0), sum.depth(0, 1000.0, 0.0));
        for (x, y) in one.iter().zip(&two) {
            assert!((x - y).abs() <= 1e-15 * x.abs().max(1e-30));
        }
        let expected =
            1e-6 * 1000.0 / 10.0 / (STEEL_DENSITY * WEAR_BIN * 2.0 * std::f64::consts::PI * 0.46);
        assert!((one[1] / expected - 1.0).abs() < 1e-12);
        // The smoothing keeps the volume (away from the ends).
        let wide = WearRecords::parse(
            &record(
                &[0.0; 20]
                    .iter()
                    .enumerate()
                    .map(|(i, _)| if i == 10 { 1e-6 } else { 0.0 })
                    .collect::<Vec<_>>(),
                10.0,
            ),
            "c",
        )
        .unwrap();
        let smoothed = wide.depth(1, 10.0, 1e-3);
        let raw = wide.depth(1, 10.0, 0.0);
        let (s1, s2): (f64, f64) = (smoothed.iter().sum(), raw.iter().sum());
        assert!((s1 / s2 - 1.0).abs() < 1e-9);
        assert!(smoothed[10] < raw[10] && smoothed[8] > 0.0);
        // Errors name the source and line.
        let e = WearRecords::parse("# distance_m,1\nleft,hub,0,1,0\n", "bad.csv").unwrap_err();
        assert!(e.contains("bad.csv, line 2") && e.contains("hub"), "{e}");
        assert!(WearRecords::parse("side,body\n", "x")
            .unwrap_err()
            .contains("distance_m"));
    }

    #[test]
    fn depth_is_removed_along_the_normal() {
        // A flat rail loses the depth vertically; a 45° flank loses d/√2 normal to it.
        let (y, z) = (vec![0.0, 1.0], vec![0.0, 0.0]);
        let (wy, wz) = worn_points((&y, &z), false, |_| 1e-4, |_| 0.0);
        assert_eq!(wy, y);
        assert!(wz.iter().all(|&z| (z - 1e-4).abs() < 1e-18));
        let (wy, wz) = worn_points((&[0.0], &[0.0]), true, |_| 1e-4, |_| 1.0);
        let moved = (wy[0].powi(2) + wz[0].powi(2)).sqrt();
        assert!((moved - 1e-4 / 2f64.sqrt()).abs() < 1e-18, "{moved}");
        assert!(wz[0] < 0.0, "the wheel loses radius");
        assert_eq!(at_bins(&[0.0, 1.0], &[0.0, 2.0], 0.25), 0.5);
        assert_eq!(at_bins(&[0.0, 1.0], &[0.0, 2.0], 2.0), 0.0);
    }
}
