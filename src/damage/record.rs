//! Wear accumulated over a run: per wheel, the mass worn off the wheel and off the rail per bin of
//! their profiles, and the distance rolled (docs/theory.md §10.5).
//!
//! Each step adds its wear rates across the profiles ([`WearBins`], kg/m per bin) times the
//! distance rolled in it (|vx| Δt). What the bins hold is mass [kg]; the depths follow from the
//! bins' width Δy and the steel's density ρ:
//!
//! ```text
//!   wheel depth (the wheel's tread worn all round):  d_w(y) = m(y) / (ρ Δy 2π r0)
//!   rail depth per wheel passage (mean over the run): d_r(y) = m(y) / (ρ Δy L)
//! ```
//!
//! with r0 the nominal rolling radius and L the distance rolled. The record is plain data: it
//! serializes to bytes (FMU states) and writes a CSV file ([`WearRecord::write_csv`]).

use super::profile::{WearBins, WEAR_BIN};
use super::wear::STEEL_DENSITY;
use std::fmt::Write as _;

/// Wear accumulated over a run, both wheels.
#[derive(Debug, Clone, PartialEq)]
pub struct WearRecord {
    /// [left, right] × [wheel, rail] mass per bin [kg].
    bins: [[WearBins; 2]; 2],
    /// [left, right] × [wheel, rail]: the bins' sum and their largest [kg] (kept as steps are
    /// added, so that the summary costs nothing per step).
    totals: [[(f64, f64); 2]; 2],
    /// Distance rolled [m].
    distance: f64,
    /// Nominal rolling radius r0 [m] (the wheel's depth).
    wheel_radius: f64,
}

/// Summary of one wheel's record: masses [kg] and largest depths [m].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WearSummary {
    pub wheel_mass: f64,
    pub rail_mass: f64,
    pub wheel_depth_max: f64,
    pub rail_depth_max: f64,
}

impl WearRecord {
    /// An empty record with the layout of `rates` ([left, right] × [wheel, rail]), for a wheel
    /// of nominal radius `wheel_radius` [m].
    pub fn new(rates: [[&WearBins; 2]; 2], wheel_radius: f64) -> Self {
        let empty = |b: &WearBins| {
            let mut b = b.clone();
            b.clear();
            b
        };
        Self {
            bins: rates.map(|side| side.map(empty)),
            totals: [[(0.0, 0.0); 2]; 2],
            distance: 0.0,
            wheel_radius,
        }
    }

    /// Adds one step: the wear rates across the profiles ([left, right] × [wheel, rail], kg/m
    /// per bin) times the distance rolled `distance` [m].
    pub fn add(&mut self, rates: [[&WearBins; 2]; 2], distance: f64) {
        if !(distance > 0.0 && distance.is_finite()) {
            return;
        }
        for ((mine, step), totals) in self.bins.iter_mut().zip(rates).zip(&mut self.totals) {
            for ((m, s), (total, largest)) in mine.iter_mut().zip(step).zip(totals) {
                let (added, top) = m.add_scaled(s, distance);
                *total += added;
                *largest = largest.max(top);
            }
        }
        self.distance += distance;
    }

    pub fn distance(&self) -> f64 {
        self.distance
    }

    /// The bins of wheel `side` (0 left, 1 right), `body` 0 wheel or 1 rail.
    pub fn bins(&self, side: usize, body: usize) -> &WearBins {
        &self.bins[side][body]
    }

    /// Depth per bin of `body` (0 wheel: all round; 1 rail: per wheel passage, mean over the
    /// run) from its mass [m].
    fn depth(&self, body: usize, mass: f64) -> f64 {
        let length = if body == 0 {
            2.0 * std::f64::consts::PI * self.wheel_radius
        } else {
            self.distance
        };
        if length > 0.0 {
            mass / (STEEL_DENSITY * WEAR_BIN * length)
        } else {
            0.0
        }
    }

    /// Masses and largest depths of wheel `side` (0 left, 1 right).
    pub fn summary(&self, side: usize) -> WearSummary {
        let [(wheel, wheel_top), (rail, rail_top)] = self.totals[side];
        WearSummary {
            wheel_mass: wheel,
            rail_mass: rail,
            wheel_depth_max: self.depth(0, wheel_top),
            rail_depth_max: self.depth(1, rail_top),
        }
    }

    /// The record as a CSV text: comment lines with the distance rolled, the nominal radius and
    /// the bin width, then `side,body,y,mass,depth` per bin (y the bin centre in the profile's
    /// lateral coordinate [m], mass [kg], depth [m] as in the module header).
    pub fn csv(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "# railcontact wear record");
        let _ = writeln!(s, "# distance_m,{:e}", self.distance);
        let _ = writeln!(s, "# wheel_radius_m,{:e}", self.wheel_radius);
        let _ = writeln!(s, "# bin_m,{WEAR_BIN:e}");
        let _ = writeln!(s, "side,body,y,mass,depth");
        for (side, name) in ["left", "right"].iter().enumerate() {
            for (body, body_name) in ["wheel", "rail"].iter().enumerate() {
                let b = &self.bins[side][body];
                for (i, &m) in b.mass().iter().enumerate() {
                    let _ = writeln!(
                        s,
                        "{name},{body_name},{:e},{m:e},{:e}",
                        b.centre(i),
                        self.depth(body, m)
                    );
                }
            }
        }
        s
    }

    /// Appends the record's bytes (distance, the running totals, then every bin's mass;
    /// little-endian f64) to `out`. The layout is the record's own: [`WearRecord::restore`]
    /// needs a record of the same profiles.
    pub fn save(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.distance.to_le_bytes());
        for (total, largest) in self.totals.iter().flatten() {
            out.extend_from_slice(&total.to_le_bytes());
            out.extend_from_slice(&largest.to_le_bytes());
        }
        for side in &self.bins {
            for b in side {
                for m in b.mass() {
                    out.extend_from_slice(&m.to_le_bytes());
                }
            }
        }
    }

    /// Bytes of [`WearRecord::save`].
    pub fn saved_len(&self) -> usize {
        8 * (1 + 8 + self.bins.iter().flatten().map(WearBins::len).sum::<usize>())
    }

    /// Restores what [`WearRecord::save`] wrote; an error (nothing changed) when the length
    /// does not match or a value is not finite.
    pub fn restore(&mut self, bytes: &[u8]) -> Result<(), String> {
        if bytes.len() != self.saved_len() {
            return Err(format!(
                "wear record of {} bytes, expected {}",
                bytes.len(),
                self.saved_len()
            ));
        }
        let mut values = bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")));
        if bytes
            .chunks_exact(8)
            .any(|c| !f64::from_le_bytes(c.try_into().expect("8 bytes")).is_finite())
        {
            return Err("wear record holds a non-finite value".into());
        }
        self.distance = values.next().unwrap_or(0.0);
        for (total, largest) in self.totals.iter_mut().flatten() {
            *total = values.next().unwrap_or(0.0);
            *largest = values.next().unwrap_or(0.0);
        }
        for side in &mut self.bins {
            for b in side {
                for (m, v) in b.mass_mut().iter_mut().zip(&mut values) {
                    *m = v;
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_add_up_and_round_trip() {
        let mut rate = WearBins::covering(-5e-3, 5e-3);
        rate.add(1.1e-3, 2e-7);
        let rates = [[&rate, &rate], [&rate, &rate]];
        let mut r = WearRecord::new(rates, 0.46);
        assert_eq!(r.summary(0), WearSummary::default());
        r.add(rates, 0.03);
        r.add(rates, 0.03);
        r.add(rates, f64::NAN);
        assert!((r.distance() - 0.06).abs() < 1e-17);
        let s = r.summary(1);
        assert!((s.wheel_mass - 1.2e-8).abs() < 1e-22);
        // Rail depth per passage: 1.2e−8 kg over 0.06 m in the bin holding 80 % of it.
        let rail = 0.8 * 1.2e-8 / (STEEL_DENSITY * WEAR_BIN * 0.06);
        assert!((s.rail_depth_max / rail - 1.0).abs() < 1e-9, "{s:?} {rail}");
        let mut bytes = Vec::new();
        r.save(&mut bytes);
        assert_eq!(bytes.len(), r.saved_len());
        let mut back = WearRecord::new(rates, 0.46);
        back.restore(&bytes).unwrap();
        assert_eq!(back, r);
        assert!(back.restore(&bytes[1..]).is_err());
        let mut bad = bytes.clone();
        bad[..8].copy_from_slice(&f64::NAN.to_le_bytes());
        assert!(back.restore(&bad).is_err());
        assert_eq!(back, r, "a rejected state changes nothing");
        let csv = r.csv();
        assert!(csv.starts_with("# railcontact wear record\n"));
        assert_eq!(
            csv.lines().filter(|l| l.starts_with("right,rail,")).count(),
            rate.len()
        );
    }
}
