//! Wear distributions across a profile: mass per lateral bin of the wheel's or the rail's
//! profile coordinate.
//!
//! A patch's wear is spread strip by strip over fixed bins of [`WEAR_BIN`] (the profile's lateral
//! coordinate: the wheel profile frame or the mounted rail frame, docs/conventions.md); a strip's
//! mass goes to the two bins whose centres bracket its position, in proportion to its distance
//! from each (linear: a strip moving across a bin moves its mass continuously, and the mass
//! centre of what is added is the strip's position). Buffers are sized once (no allocation per
//! step).

/// Width of a distribution's bins [m].
pub const WEAR_BIN: f64 = 0.5e-3;

/// Mass per bin over a lateral range [kg] (or a rate, kg/m, per step).
#[derive(Debug, Clone)]
pub struct WearBins {
    /// Centre of bin 0 [m].
    origin: f64,
    mass: Vec<f64>,
    /// The bins that may be non-zero, `touched.0..touched.1` (empty when `.0 ≥ .1`): a step
    /// touches a few of a profile's hundreds of bins, and clearing and adding visit only those.
    touched: (usize, usize),
}

impl PartialEq for WearBins {
    /// The same layout and masses (whatever range is marked as touched).
    fn eq(&self, other: &Self) -> bool {
        self.origin == other.origin && self.mass == other.mass
    }
}

impl WearBins {
    /// Bins of [`WEAR_BIN`] whose centres cover [`lo`, `hi`] [m] (at least two).
    pub fn covering(lo: f64, hi: f64) -> Self {
        let span = if hi > lo && (hi - lo).is_finite() {
            hi - lo
        } else {
            0.0
        };
        let n = ((span / WEAR_BIN).ceil() as usize + 1).clamp(2, 100_000);
        Self {
            origin: if lo.is_finite() { lo } else { 0.0 },
            mass: vec![0.0; n],
            touched: (0, 0),
        }
    }

    pub fn len(&self) -> usize {
        self.mass.len()
    }

    pub fn is_empty(&self) -> bool {
        self.mass.is_empty()
    }

    /// Centre of bin `i` [m].
    pub fn centre(&self, i: usize) -> f64 {
        self.origin + i as f64 * WEAR_BIN
    }

    /// The bins' masses [kg] (or rates).
    pub fn mass(&self) -> &[f64] {
        &self.mass
    }

    pub fn mass_mut(&mut self) -> &mut [f64] {
        self.touched = (0, self.mass.len());
        &mut self.mass
    }

    /// Σ of the bins.
    pub fn total(&self) -> f64 {
        self.mass.iter().sum()
    }

    pub fn clear(&mut self) {
        let (lo, hi) = self.touched;
        if lo < hi {
            self.mass[lo..hi].fill(0.0);
        }
        self.touched = (0, 0);
    }

    /// Adds `mass` at lateral `y` [m], split linearly between the two bins around it (beyond
    /// the ends: into the end bin). Non-finite or non-positive values add nothing.
    #[inline]
    pub fn add(&mut self, y: f64, mass: f64) {
        if !(mass > 0.0 && mass.is_finite() && y.is_finite()) {
            return;
        }
        let last = self.mass.len() - 1;
        let u = ((y - self.origin) / WEAR_BIN).clamp(0.0, last as f64);
        // u ≥ 0: the cast truncates as floor would.
        let i = (u as usize).min(last - 1);
        let f = u - i as f64;
        self.mass[i] += mass * (1.0 - f);
        self.mass[i + 1] += mass * f;
        self.touch(i, i + 2);
    }

    /// Marks bins `lo..hi` as possibly non-zero.
    fn touch(&mut self, lo: usize, hi: usize) {
        self.touched = if self.touched.0 < self.touched.1 {
            (self.touched.0.min(lo), self.touched.1.max(hi))
        } else {
            (lo, hi)
        };
    }

    /// Adds `factor` × `other` bin by bin (the same layout) over the bins `other` touched;
    /// returns the sum added and the largest of the bins added to afterwards (with factor ≥ 0
    /// and masses ≥ 0, the other bins' largest is unchanged).
    pub fn add_scaled(&mut self, other: &WearBins, factor: f64) -> (f64, f64) {
        let (lo, hi) = other.touched;
        let hi = hi.min(self.mass.len()).min(other.mass.len());
        if lo >= hi {
            return (0.0, 0.0);
        }
        let (mut added, mut largest) = (0.0, 0.0_f64);
        for (m, o) in self.mass[lo..hi].iter_mut().zip(&other.mass[lo..hi]) {
            let a = o * factor;
            added += a;
            *m += a;
            largest = largest.max(*m);
        }
        self.touch(lo, hi);
        (added, largest)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mass_is_kept_and_centred() {
        let mut b = WearBins::covering(-10e-3, 10e-3);
        assert_eq!(b.len(), 41);
        assert_eq!(b.centre(20), 0.0);
        for (y, m) in [(0.3e-3, 2.0), (-4.1e-3, 1.0), (9.99e-3, 0.5)] {
            b.add(y, m);
        }
        assert!((b.total() - 3.5).abs() < 1e-15);
        // The first addition alone: its mass centre is its position.
        let mut one = WearBins::covering(-10e-3, 10e-3);
        one.add(0.3e-3, 2.0);
        let centre: f64 = (0..one.len())
            .map(|i| one.centre(i) * one.mass()[i])
            .sum::<f64>()
            / 2.0;
        assert!((centre - 0.3e-3).abs() < 1e-15);
        // Beyond the ends: the end bins; nothing for bad values.
        one.add(1.0, 1.0);
        assert_eq!(one.mass()[one.len() - 1], 1.0);
        one.add(f64::NAN, 1.0);
        one.add(0.0, f64::INFINITY);
        one.add(0.0, -1.0);
        assert!((one.total() - 3.0).abs() < 1e-15);
        let mut sum = WearBins::covering(-10e-3, 10e-3);
        sum.add_scaled(&one, 2.0);
        assert!((sum.total() - 6.0).abs() < 1e-15);
    }
}
