//! Contact candidates and ridges: the local minima and maxima of the gap's cubic Hermite
//! interpolant, refined on the exact gap.

use super::regions::{cubic_at, hermite_depth};
use super::{ContactPoint, GapSample, Prepared, WheelOnRail};
use crate::numeric::roots::Illinois;

/// Largest number of separate contact candidates kept per wheel.
pub const MAX_CANDIDATES: usize = 8;

/// Local minima whose separating ridge is lower than this above the shallower minimum are one
/// candidate [m]: 1 nm, round-off of the gap's evaluation. Shallow ripples above it stay separate
/// candidates; where the interpenetration submerges their ridges, the patch groups blend them
/// continuously ([`crate::geometry::groups`]), where merging them here would make the candidate jump
/// between the ripple's minima as their depths cross.
pub const MIN_PROMINENCE: f64 = 1e-9;

/// Iteration limit of the minimum's refinement in [`WheelOnRail::search`] (regula falsi
/// converges in ~6; the limit only guards a pathological slope).
const REFINE_STEPS: usize = 40;

/// Contact candidates of one wheel, ordered from the field side to the gauge side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactCandidates {
    points: [ContactPoint; MAX_CANDIDATES],
    len: usize,
}

impl Default for ContactCandidates {
    fn default() -> Self {
        Self {
            points: [ContactPoint::default(); MAX_CANDIDATES],
            len: 0,
        }
    }
}

impl ContactCandidates {
    pub fn as_slice(&self) -> &[ContactPoint] {
        &self.points[..self.len]
    }
    pub fn len(&self) -> usize {
        self.len
    }
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
    pub(super) fn clear(&mut self) {
        self.len = 0;
    }
    fn push(&mut self, p: ContactPoint) {
        if self.len < MAX_CANDIDATES {
            self.points[self.len] = p;
            self.len += 1;
        }
    }
}

/// The highest point of the gap between two neighbouring contact candidates: the ridge a
/// wheel's interpenetration must submerge for the two minima to share one patch.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Ridge {
    /// Lateral coordinate (wheelset frame) [m].
    pub lateral: f64,
    /// Vertical gap there with the wheelset at its nominal height [m].
    pub gap: f64,
}

impl WheelOnRail {
    /// The contact candidates of the last search, ordered from the field side to the gauge
    /// side: the refined local minima of the gap below the filled level (at least the deepest
    /// point; [`WheelOnRail::regions`] adds those of the deeper levels it is asked for).
    pub fn candidates(&self) -> &ContactCandidates {
        &self.candidates
    }

    /// The ridges of the last search: `ridges()[k]` lies between candidates k and k + 1
    /// ([`WheelOnRail::candidates`], field side first); `None` where the gap between them rises
    /// above the filled level ([`WheelOnRail::fill_to_level`]).
    pub fn ridges(&self) -> &[Option<Ridge>] {
        &self.ridges[..self.candidates.len().saturating_sub(1)]
    }

    /// The refined local minima of the gap below the filled level (see `candidates`) and the
    /// ridges between them.
    ///
    /// The extrema are found on the cubic Hermite interpolant of the samples' gaps and slopes
    /// (one per sample interval: the roots of its derivative), not by comparing samples: a
    /// minimum narrower than the sample spacing — one just born at a fold, where a shoulder of
    /// the gap turns into a minimum and a ridge — is found as soon as the interpolant shows it
    /// (near a fold the gap is locally cubic, which the interpolant reproduces), so that its
    /// ridge is still low when it appears and the patch groups take it in without a jump.
    /// Each minimum is then refined on the exact gap inside the stretch between its
    /// neighbouring critical points of the interpolant, and each ridge likewise.
    pub(super) fn find_candidates(&mut self) {
        let s = std::mem::take(&mut self.samples);
        let n = s.len() - 1;
        let (lo, step, level, p) = (self.scan_lo, self.scan_dw, self.filled_level, self.pose);
        // Critical points of the interpolant, ascending in w (see [`Extremum`]). Minima below
        // the level lie in the filled span.
        let (span_lo, span_hi) = self.filled_span;
        let mut found = [Extremum::default(); MAX_CANDIDATES];
        let mut ridge_between = [Extremum::default(); MAX_CANDIDATES];
        let mut count = 0usize;
        let mut ridge = Extremum {
            value: f64::NEG_INFINITY,
            ..Extremum::default()
        };
        let mut unfilled_since_last = false;
        for k in span_lo..span_hi.min(n) {
            let (a, b) = (&s[k], &s[k + 1]);
            if !(a.gap.is_finite() && b.gap.is_finite()) {
                unfilled_since_last = true;
                continue;
            }
            // A sample is a ridge candidate too (the maximum between two minima may sit on a
            // sample where the interpolant's pieces meet with a kink).
            if a.gap > ridge.value && k > span_lo {
                ridge = Extremum {
                    at: k as f64,
                    value: a.gap,
                    bracket: ((k as f64 - 1.0).max(0.0), (k as f64 + 1.0).min(n as f64)),
                };
            }
            let cubic = hermite_depth(0.0, a.gap, b.gap, a.slope * step, b.slope * step);
            // The interpolant is −cubic: its derivative's roots in [0, 1).
            let (c1, c2, c3) = (-cubic[1], -cubic[2], -cubic[3]);
            let mut roots = [f64::NAN; 2];
            quadratic_roots(3.0 * c3, 2.0 * c2, c1, &mut roots);
            let valid = |t: f64| (0.0..1.0).contains(&t);
            let (r0, r1) = (roots[0], roots[1]);
            for (idx, t) in [r0, r1].into_iter().enumerate() {
                if !valid(t) {
                    continue;
                }
                let curvature = 2.0 * c2 + 6.0 * c3 * t;
                // cubic = 0 − H: the interpolant's value is −cubic(t).
                let value = -cubic_at(&cubic, t);
                let other = if idx == 0 { r1 } else { r0 };
                let (mut lo_t, mut hi_t) = (0.0, 1.0);
                if (0.0..=1.0).contains(&other) {
                    if other < t {
                        lo_t = other;
                    } else if other > t {
                        hi_t = other;
                    }
                }
                let kf = k as f64;
                let e = Extremum {
                    at: kf + t,
                    value,
                    bracket: (kf + lo_t, kf + hi_t),
                };
                if curvature < 0.0 {
                    if value > ridge.value {
                        ridge = e;
                    }
                    continue;
                }
                if !(curvature > 0.0 && value < level - MIN_PROMINENCE) {
                    continue;
                }
                if count > 0 {
                    let prev = found[count - 1];
                    let height = if unfilled_since_last {
                        f64::INFINITY
                    } else {
                        ridge.value - prev.value.max(value)
                    };
                    if height < MIN_PROMINENCE || count == MAX_CANDIDATES {
                        if value < prev.value {
                            found[count - 1] = e;
                        }
                        ridge = e;
                        unfilled_since_last = false;
                        continue;
                    }
                    ridge_between[count - 1] = if unfilled_since_last {
                        Extremum {
                            value: f64::INFINITY,
                            ..ridge
                        }
                    } else {
                        ridge
                    };
                }
                found[count] = e;
                count += 1;
                ridge = e;
                unfilled_since_last = false;
            }
        }
        let lateral = |t: f64| lo + step * t;
        // Refine and describe, field side first (largest w first); a minimum refined at a
        // lower level of this search is taken over (its samples are the same).
        let mut candidates = ContactCandidates::default();
        let mut minima = [0usize; MAX_CANDIDATES];
        for (k, e) in found[..count].iter().rev().enumerate() {
            let key = (e.at * 1024.0) as usize;
            minima[k] = key;
            let known = (0..self.candidates.len()).find(|&j| self.candidate_minima[j] == key);
            let point = match known {
                Some(j) => self.candidates.points[j],
                None => {
                    let (a, b) = (lateral(e.bracket.0), lateral(e.bracket.1));
                    let (sa, sb) = (self.sample(a, &p), self.sample(b, &p));
                    let mid = self.sample(lateral(e.at), &p);
                    let (w, refined) = self.refine((a, sa), (b, sb), mid, &p);
                    self.describe(w, &refined)
                }
            };
            candidates.push(point);
        }
        // Ridges between neighbouring candidates (field side first, as the candidates): the
        // highest critical point or sample between them refined to the gap's local maximum, or
        // none where an unfilled interval lies between them (the ridge is above the filled
        // level).
        let mut ridges = [None; MAX_CANDIDATES];
        for k in 0..count.saturating_sub(1) {
            // Candidate k (field side) is found[count − 1 − k]; the ridge before it is
            // ridge_between[count − 2 − k].
            let e = ridge_between[count - 2 - k];
            let (outer, inner) = (&candidates.points[k], &candidates.points[k + 1]);
            ridges[k] = e.value.is_finite().then(|| {
                let a = lateral(e.bracket.0).max(inner.lateral);
                let b = lateral(e.bracket.1).min(outer.lateral);
                let (w, top) = self.refine_ridge(a, b, &p);
                // A sample's gap is exact: the ridge is at least that high.
                let sampled = if e.at.fract() == 0.0 {
                    e.value
                } else {
                    f64::NEG_INFINITY
                };
                Ridge {
                    lateral: w,
                    gap: top.gap.max(sampled),
                }
            });
        }
        self.candidates = candidates;
        self.candidate_minima = minima;
        self.ridges = ridges;
        self.samples = s;
    }

    /// Refinement of the sampled minimum `mid` between its neighbours `lo` and `hi` (samples at
    /// the laterals `a` < `b`): the root of the gap's slope by the Illinois variant of regula
    /// falsi inside the bracket (superlinear: ~6 samples to 1e−10 m). Where the slopes do not
    /// bracket a root (a yawed wheel's lowest point jumping between two flange points makes the
    /// gap kinked) or the root found is not below the sampled minimum (a maximum between two
    /// minima), golden-section search on the gap itself.
    fn refine(
        &self,
        (a, lo): (f64, GapSample),
        (b, hi): (f64, GapSample),
        mid: GapSample,
        p: &Prepared,
    ) -> (f64, GapSample) {
        if lo.slope < 0.0 && hi.slope > 0.0 {
            let bracket = Illinois::new((a, lo.slope), (b, hi.slope));
            if let Ok((w, s, bracket)) = self.slope_root(bracket, 1.0, p) {
                return self.accept_refined(w, s, (bracket.neg.0, bracket.pos.0), mid, p);
            }
        }
        self.golden_section(a, b, p)
    }

    /// The root of the gap's slope times `sign` (±1) inside `bracket` by Illinois: the lateral,
    /// its sample and the last bracket once the step or the bracket is below 1e−10 m (the
    /// secant's error is then far smaller still: superlinear), or the last iterate if
    /// [`REFINE_STEPS`] do not get there.
    fn slope_root(
        &self,
        mut bracket: Illinois,
        sign: f64,
        p: &Prepared,
    ) -> Result<(f64, GapSample, Illinois), f64> {
        let mut w = bracket.neg.0;
        for _ in 0..REFINE_STEPS {
            let next = bracket.secant();
            let moved = (next - w).abs();
            w = next;
            let s = self.sample(w, p);
            if s.slope == 0.0 || moved < 1e-10 || bracket.width() < 1e-10 {
                return Ok((w, s, bracket));
            }
            bracket.update(w, sign * s.slope);
        }
        Err(w)
    }

    /// The slope root `w` (sample `s`) inside [a, b] if it lies below the sampled minimum `mid`,
    /// else golden-section search on [a, b].
    fn accept_refined(
        &self,
        w: f64,
        s: GapSample,
        (a, b): (f64, f64),
        mid: GapSample,
        p: &Prepared,
    ) -> (f64, GapSample) {
        if s.gap <= mid.gap {
            (w, s)
        } else {
            self.golden_section(a, b, p)
        }
    }

    /// Golden-section refinement of a sampled minimum on [a, b].
    fn golden_section(&self, a: f64, b: f64, p: &Prepared) -> (f64, GapSample) {
        self.golden_section_by(a, b, p, |g| g)
    }

    /// Golden-section search for the minimum of `key(gap)` on [a, b].
    fn golden_section_by(
        &self,
        mut a: f64,
        mut b: f64,
        p: &Prepared,
        key: impl Fn(f64) -> f64,
    ) -> (f64, GapSample) {
        const INV_PHI: f64 = 0.618_033_988_749_894_8;
        let mut c = b - INV_PHI * (b - a);
        let mut d = a + INV_PHI * (b - a);
        let mut fc = self.sample(c, p);
        let mut fd = self.sample(d, p);
        // 1e−8 m is far below every contact dimension; 40 iterations shrink 1 mm below it.
        while b - a > 1e-8 {
            if key(fc.gap) <= key(fd.gap) {
                b = d;
                d = c;
                fd = fc;
                c = b - INV_PHI * (b - a);
                fc = self.sample(c, p);
            } else {
                a = c;
                c = d;
                fc = fd;
                d = a + INV_PHI * (b - a);
                fd = self.sample(d, p);
            }
        }
        if key(fc.gap) <= key(fd.gap) {
            (c, fc)
        } else {
            (d, fd)
        }
    }

    /// The gap's local maximum inside [a, b] (a < b, around the highest sample between two
    /// minima): the root of its slope by the Illinois variant of regula falsi where the slopes
    /// at the ends bracket one (+ at a, − at b), else golden-section search on the gap.
    fn refine_ridge(&self, a: f64, b: f64, p: &Prepared) -> (f64, GapSample) {
        let (sa, sb) = (self.sample(a, p), self.sample(b, p));
        if sa.slope > 0.0 && sb.slope < 0.0 {
            // The slope decreases through the ridge: the bracket holds its negative.
            let bracket = Illinois::new((a, -sa.slope), (b, -sb.slope));
            return match self.slope_root(bracket, -1.0, p) {
                Ok((w, s, _)) => (w, s),
                Err(w) => (w, self.sample(w, p)),
            };
        }
        let (w, s) = self.golden_section_by(a, b, p, |g| -g);
        (w, s)
    }
}

/// A critical point of the gap's interpolant ([`WheelOnRail::find_candidates`]).
#[derive(Debug, Clone, Copy, Default)]
struct Extremum {
    /// Fractional sample index.
    at: f64,
    /// The interpolant's value there [m].
    value: f64,
    /// Fractional sample indices of the neighbouring critical points (or the interval's ends).
    bracket: (f64, f64),
}

/// Real roots of a t² + b t + c, ascending, into `out` (NaN where there are fewer than two).
fn quadratic_roots(a: f64, b: f64, c: f64, out: &mut [f64; 2]) {
    *out = [f64::NAN; 2];
    if a == 0.0 {
        if b != 0.0 {
            out[0] = -c / b;
        }
        return;
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return;
    }
    let r = disc.sqrt();
    // Cancellation-free roots.
    let q = -0.5 * (b + if b >= 0.0 { r } else { -r });
    let (x0, x1) = (q / a, if q != 0.0 { c / q } else { f64::NAN });
    *out = if x1 < x0 { [x1, x0] } else { [x0, x1] };
}
