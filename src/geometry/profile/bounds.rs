//! Bounds of a profile's height and slope over lateral ranges.
//!
//! The exact smallest and largest z and dz/dy of the profile's spline over uniform bins of its
//! lateral range (each bin from the cubics' and their derivatives' end values and stationary
//! points, [`CubicSpline::value_range`](super::CubicSpline::value_range) and
//! [`CubicSpline::slope_range`](super::CubicSpline::slope_range)), kept as sparse tables
//! (level j: the extremes over 2^j consecutive bins), so that a query over any range [y0, y1]
//! costs two table reads: the extremes of the bins it touches, with the linear continuation
//! outside the data taken exactly. The result always contains the true range; it is wider by at
//! most the profile's variation within the two end bins.
//!
//! Used by the contact search to skip the fine sampling of the gap where the surfaces cannot come
//! near each other (`contact_search`).

use super::Profile;

/// Extremes of one quantity over runs of bins (a sparse table).
#[derive(Debug, Clone, PartialEq)]
struct RunExtremes {
    bins: usize,
    /// Smallest and largest value over bins k .. k + 2^j − 1 at [j × bins + k].
    min: Vec<f64>,
    max: Vec<f64>,
}

impl RunExtremes {
    fn new(per_bin: impl Iterator<Item = (f64, f64)>) -> Self {
        let (mut min, mut max): (Vec<f64>, Vec<f64>) = per_bin.unzip();
        let bins = min.len();
        for j in 1..=bins.ilog2() as usize {
            let (prev, half) = ((j - 1) * bins, 1usize << (j - 1));
            for k in 0..bins {
                // Entries running past the last bin repeat a shorter run (never read).
                let other = prev + (k + half).min(bins - 1);
                let (lo, hi) = (min[prev + k].min(min[other]), max[prev + k].max(max[other]));
                min.push(lo);
                max.push(hi);
            }
        }
        Self { bins, min, max }
    }

    /// (min, max) over bins k0 ..= k1.
    #[inline]
    fn over(&self, k0: usize, k1: usize) -> (f64, f64) {
        let j = (k1 - k0 + 1).ilog2() as usize;
        let (e0, e1) = (j * self.bins + k0, j * self.bins + k1 + 1 - (1 << j));
        (
            self.min[e0].min(self.min[e1]),
            self.max[e0].max(self.max[e1]),
        )
    }
}

/// Per-bin extremes of z and dz/dy over a profile's lateral range.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightBounds {
    /// First and last data abscissa [m] and the inverse bin width [1/m].
    first: f64,
    last: f64,
    inv_bin: f64,
    bins: usize,
    /// Heights [m] and slopes [-].
    z: RunExtremes,
    dz: RunExtremes,
    /// Value and slope at both ends (the linear continuation).
    start: (f64, f64),
    end: (f64, f64),
}

impl HeightBounds {
    /// Bins of width at most `bin` [m] (> 0) over the profile's lateral range.
    pub fn new(profile: &Profile, bin: f64) -> Self {
        let (first, last) = profile.y_range();
        let bins = (((last - first) / bin).ceil() as usize).max(1);
        let width = (last - first) / bins as f64;
        let spline = profile.spline();
        let edges = |k: usize| {
            let y0 = first + width * k as f64;
            let y1 = if k + 1 == bins {
                last
            } else {
                first + width * (k + 1) as f64
            };
            (y0, y1)
        };
        let z = RunExtremes::new((0..bins).map(|k| {
            let (y0, y1) = edges(k);
            spline.value_range(y0, y1)
        }));
        let dz = RunExtremes::new((0..bins).map(|k| {
            let (y0, y1) = edges(k);
            spline.slope_range(y0, y1)
        }));
        let (z0, dz0, _) = profile.eval(first);
        let (z1, dz1, _) = profile.eval(last);
        Self {
            first,
            last,
            inv_bin: 1.0 / width,
            bins,
            z,
            dz,
            start: (z0, dz0),
            end: (z1, dz1),
        }
    }

    /// The bins touched by [y0, y1] inside the data; `None` if it lies outside.
    #[inline]
    fn bins_of(&self, y0: f64, y1: f64) -> Option<(usize, usize)> {
        let (a, b) = (y0.max(self.first), y1.min(self.last));
        if a > b {
            return None;
        }
        let top = self.bins - 1;
        let bin = |y: f64| (((y - self.first) * self.inv_bin) as usize).min(top);
        Some((bin(a), bin(b)))
    }

    /// Bounds (lower, upper) on z over [y0, y1] [m] (y0 ≤ y1).
    #[inline]
    pub fn range(&self, y0: f64, y1: f64) -> (f64, f64) {
        let (mut lo, mut hi) = match self.bins_of(y0, y1) {
            Some((k0, k1)) => self.z.over(k0, k1),
            None => (f64::INFINITY, f64::NEG_INFINITY),
        };
        // The linear continuation: extremes at the ends of the parts outside the data.
        let mut take = |v: f64| {
            lo = lo.min(v);
            hi = hi.max(v);
        };
        if y0 < self.first {
            let (z, dz) = self.start;
            take(z + dz * (y0 - self.first));
            take(z + dz * (y1.min(self.first) - self.first));
        }
        if y1 > self.last {
            let (z, dz) = self.end;
            take(z + dz * (y1 - self.last));
            take(z + dz * (y0.max(self.last) - self.last));
        }
        (lo, hi)
    }

    /// Bounds (lower, upper) on dz/dy over [y0, y1] [-] (y0 ≤ y1).
    #[inline]
    pub fn slope_range(&self, y0: f64, y1: f64) -> (f64, f64) {
        let (mut lo, mut hi) = match self.bins_of(y0, y1) {
            Some((k0, k1)) => self.dz.over(k0, k1),
            None => (f64::INFINITY, f64::NEG_INFINITY),
        };
        for (outside, slope) in [
            (y0 < self.first, self.start.1),
            (y1 > self.last, self.end.1),
        ] {
            if outside {
                lo = lo.min(slope);
                hi = hi.max(slope);
            }
        }
        (lo, hi)
    }

    /// Smallest and largest z over the data [m].
    pub fn overall(&self) -> (f64, f64) {
        self.range(self.first, self.last)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::profile::ProfileKind;

    /// Brute force: the bounds contain every sampled value of the range, and are tight to the
    /// bin's variation (the dense samples reach within one bin's variation of them).
    #[test]
    fn bounds_contain_the_profile_and_are_tight_to_a_bin() {
        for (name, kind) in [("S1002", ProfileKind::Wheel), ("UIC60", ProfileKind::Rail)] {
            let profile = Profile::load(name, kind, 0.0).unwrap();
            let bin = 2.5e-4;
            let bounds = HeightBounds::new(&profile, bin);
            let (first, last) = profile.y_range();
            for k in 0..400 {
                let y0 = first - 2e-3 + (last - first + 4e-3) * k as f64 / 400.0;
                let y1 = y0 + 1e-3 + 1e-5 * k as f64;
                let (lo, hi) = bounds.range(y0, y1);
                let (mut s_lo, mut s_hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for j in 0..=2000 {
                    let z = profile.z(y0 + (y1 - y0) * j as f64 / 2000.0);
                    s_lo = s_lo.min(z);
                    s_hi = s_hi.max(z);
                }
                // Contained (1e−15 m: the rounding of the cubic's evaluation).
                assert!(
                    lo <= s_lo + 1e-15 && hi >= s_hi - 1e-15,
                    "{name} [{y0}, {y1}]"
                );
                // Tight: the widening is bounded by the variation over one bin beyond each end.
                let (w_lo, w_hi) = {
                    let (mut a, mut b) = (f64::INFINITY, f64::NEG_INFINITY);
                    for j in 0..=4000 {
                        let y = (y0 - bin) + (y1 - y0 + 2.0 * bin) * j as f64 / 4000.0;
                        let z = profile.z(y);
                        a = a.min(z);
                        b = b.max(z);
                    }
                    (a, b)
                };
                assert!(
                    lo >= w_lo - 1e-9 && hi <= w_hi + 1e-9,
                    "{name} [{y0}, {y1}] loose"
                );
            }
        }
    }

    /// Exactness: a bin's extremes are those of the profile over the bin (a stationary point
    /// inside a bin is found, not only the end values), to the rounding of the cubics.
    #[test]
    fn a_bins_extremes_are_the_profiles_extremes_over_it() {
        // A wave through knots 10 mm apart, its crests between the knots and inside bins.
        let y: Vec<f64> = (0..7).map(|i| 0.01 * i as f64).collect();
        let z: Vec<f64> = y
            .iter()
            .map(|v| 2e-3 * (std::f64::consts::TAU * (v - 3.3e-3) / 0.04).sin())
            .collect();
        let wave = Profile::from_points("wave", ProfileKind::Rail, &y, &z, 0.0).unwrap();
        let uic60 = Profile::load("UIC60", ProfileKind::Rail, 0.0).unwrap();
        let mut interior_extremes = 0;
        for (profile, bin) in [(wave, 5e-3), (uic60, 2.5e-4)] {
            let bounds = HeightBounds::new(&profile, bin);
            let (first, _) = profile.y_range();
            let width = 1.0 / bounds.inv_bin;
            for k in 0..bounds.bins {
                let (y0, y1) = (first + width * k as f64, first + width * (k + 1) as f64);
                let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for j in 0..=20_000 {
                    let z = profile.z(y0 + (y1 - y0) * j as f64 / 20_000.0);
                    lo = lo.min(z);
                    hi = hi.max(z);
                }
                // Dense sampling misses a stationary value by z''(h/2)²/2, h ≤ 0.25 µm: < 1e−13 m.
                let (b_lo, b_hi) = bounds.z.over(k, k);
                assert!((b_lo - lo).abs() < 1e-12, "bin {k}: {b_lo} {lo}");
                assert!((b_hi - hi).abs() < 1e-12, "bin {k}: {b_hi} {hi}");
                let (z0, z1) = (profile.z(y0), profile.z(y1));
                if lo < z0.min(z1) - 1e-9 || hi > z0.max(z1) + 1e-9 {
                    interior_extremes += 1;
                }
            }
        }
        // The wave's crests and troughs lie inside bins: the stationary points were found.
        assert!(interior_extremes >= 3, "{interior_extremes}");
    }
}
