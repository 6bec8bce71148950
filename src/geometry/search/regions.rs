//! Interpenetration regions and the moments of the interpenetration's depth, on the pieces of
//! the samples' cubic Hermite interpolant.

use super::{GapSample, WheelOnRail};
use crate::numeric::roots::Illinois;

/// Fraction of a region's depth at which its reference point is taken (see `regions`): Kik and
/// Piotrowski's virtual-penetration factor ε (`crate::normal::kik_piotrowski::KP_EPSILON`).
const VIRTUAL_FRACTION: f64 = 0.55;

/// An interpenetration region of one wheel at a given vertical position (sample indices of the
/// last search).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Region {
    /// First and last sample inside the region (gauge side first).
    pub first: usize,
    pub last: usize,
    /// Penetration-weighted centroid, as a fractional sample index.
    pub centroid_index: f64,
    /// Sample index of the deepest point.
    pub deepest: usize,
    /// Largest vertical interpenetration [m].
    pub depth: f64,
}

/// Moments of a wheel's interpenetration below a level ([`WheelOnRail::depth_moments`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DepthMoments {
    /// ∫ d dw [m²], d the depth below the level.
    pub integral: f64,
    /// d-weighted mean lateral (wheelset frame) [m].
    pub mean: f64,
    /// d-weighted variance of the lateral [m²].
    pub variance: f64,
}

impl WheelOnRail {
    /// The interpenetration regions of the last [`WheelOnRail::search`] when the wheel is
    /// lowered by `dz` [m] from its nominal height: maximal runs of samples with gap < dz.
    /// Each region gets its deepest point and its reference point: the force centroid of the
    /// virtual interpenetration {gap < dz − (1 − ε) depth}, ε = Kik–Piotrowski's 0.55, with
    /// their strip load ∝ ε depth − (gap − deepest gap) (Piotrowski & Kik 2008: the patch lies
    /// inside the virtual region, and a strip's load is linear in its virtual penetration — as
    /// it is for a Hertz ellipse). On a symmetric (Hertzian) gap it is the deepest point for
    /// any ε; on a near-conformal one (Manchester, right wheel at 0.5 mm: rigid region
    /// 17 mm wide, 25 µm deep) it lands within 1 mm of CONTACT's reference point, where the
    /// rigid region's (δ − f)^{3/2} centroid was 2 mm off and the deepest point 2.8 mm. Regions
    /// are written field side first; returns how many there are (at most `out.len()`; if more
    /// exist, the deepest are kept). Computes the samples below `dz` the search has not computed
    /// yet, and the candidates among them ([`WheelOnRail::candidates`]).
    pub fn regions(&mut self, dz: f64, out: &mut [Region]) -> usize {
        self.fill_to(dz);
        let s = &self.samples;
        let mut count = 0usize;
        // Every sample below dz lies in the filled span.
        let (span_lo, span_hi) = self.filled_span;
        let mut i = span_hi + 1;
        // Walk from the field side (last sample) to the gauge side.
        while i > span_lo {
            i -= 1;
            if s[i].gap >= dz {
                continue;
            }
            let end = i;
            let mut deepest = i;
            loop {
                if s[i].gap < s[deepest].gap {
                    deepest = i;
                }
                if i == 0 || s[i - 1].gap >= dz {
                    break;
                }
                i -= 1;
            }
            let start = i;
            // The contact patch lies inside the virtual interpenetration region at ε × the
            // depth (Kik–Piotrowski's ε): its force centroid is the reference point.
            let depth = dz - s[deepest].gap;
            let cut = dz - VIRTUAL_FRACTION * depth;
            let (mut weight, mut moment) = (0.0, 0.0);
            for (k, sample) in s.iter().enumerate().take(end + 1).skip(start) {
                let virtual_depth = cut - sample.gap;
                if virtual_depth > 0.0 {
                    weight += virtual_depth;
                    moment += virtual_depth * k as f64;
                }
            }
            let centroid = if weight > 0.0 {
                moment / weight
            } else {
                deepest as f64
            };
            let region = Region {
                first: start,
                last: end,
                centroid_index: centroid,
                deepest,
                depth: dz - s[deepest].gap,
            };
            if count < out.len() {
                out[count] = region;
                count += 1;
            } else if let Some(shallowest) =
                (0..count).min_by(|&a, &b| out[a].depth.total_cmp(&out[b].depth))
            {
                if region.depth > out[shallowest].depth {
                    out.copy_within(shallowest + 1..count, shallowest);
                    out[count - 1] = region;
                }
            }
        }
        count
    }

    /// The first lateral between `from` and `to` (either order) where the gap rises to `level`,
    /// walking from `from` (where it lies below `level`); `to` if it stays below. Bracketed by
    /// the samples, refined on the exact gap (Illinois) to 1e−10 m, so it moves continuously with
    /// the pose and the level. `level` must not exceed the filled level.
    pub fn crossing(&self, from: f64, to: f64, level: f64) -> f64 {
        let p = &self.pose;
        let s = &self.samples;
        let last = s.len() - 1;
        let forward = to > from;
        // Samples strictly between from and to, walking outwards.
        let (i_from, i_to) = (self.index_of(from), self.index_of(to));
        let mut i = if forward {
            (i_from.floor() + 1.0).max(0.0)
        } else {
            (i_from.ceil() - 1.0).min(last as f64)
        };
        let (mut a, mut ga) = (from, self.gap_at(from) - level);
        if ga >= 0.0 {
            return from;
        }
        loop {
            let inside = if forward { i < i_to } else { i > i_to };
            if !inside || i < 0.0 || i > last as f64 {
                break;
            }
            let k = i as usize;
            let g = s[k].gap - level;
            let w = self.scan_lo + self.scan_dw * i;
            if g >= 0.0 {
                return self.level_root((a, ga), (w, self.gap_at(w) - level), level);
            }
            (a, ga) = (w, g);
            i += if forward { 1.0 } else { -1.0 };
        }
        let gt = self.gap_at(to) - level;
        if gt >= 0.0 {
            self.level_root((a, ga), (to, gt), level)
        } else {
            let _ = p;
            to
        }
    }

    /// Root of gap(w) − `level` between the lateral `below` and the lateral `at_or_above` (each
    /// with its gap − level) by Illinois to 1e−10 m.
    fn level_root(&self, below: (f64, f64), at_or_above: (f64, f64), level: f64) -> f64 {
        let mut bracket = Illinois::new(below, at_or_above);
        let mut w = at_or_above.0;
        for _ in 0..60 {
            if bracket.width() < 1e-10 || bracket.pos.1 == 0.0 {
                return bracket.pos.0;
            }
            w = bracket.inside_or_midpoint(bracket.secant());
            bracket.update(w, self.gap_at(w) - level);
        }
        w
    }

    /// Moments of the interpenetration below `level` over the laterals [lo, hi] (wheelset
    /// frame): with the depth d(w) = max(0, level − gap(w)), its integral, the d-weighted mean
    /// lateral and the d-weighted variance of the lateral ([`DepthMoments`]); `None` where nothing
    /// lies below the level. The gap between two samples is the cubic Hermite interpolant of the
    /// samples' gaps and slopes (fourth order: a narrow flange region a few samples wide is
    /// resolved, and a dip between two samples counts), integrated exactly between its crossings
    /// of the level. Continuous in the pose, the level and the ends. `level` must not exceed the
    /// filled level.
    pub fn depth_moments(&self, lo: f64, hi: f64, level: f64) -> Option<DepthMoments> {
        let s = &self.samples;
        let last = s.len() - 1;
        let (lo, hi) = (lo.min(hi), lo.max(hi));
        let (span_lo, span_hi) = self.filled_span;
        if span_lo > span_hi {
            return None;
        }
        let ia = self.index_of(lo).clamp(span_lo as f64, span_hi as f64);
        let ib = self.index_of(hi).clamp(span_lo as f64, span_hi as f64);
        let h = self.scan_dw;
        // Moments in the sample index t (w = scan_lo + h t); converted at the end.
        let mut sums = [0.0; 3];
        let mut k = (ia as usize).min(last.saturating_sub(1));
        while (k as f64) < ib && k < last {
            let piece = &self.pieces[k];
            let (t0, t1) = ((ia - k as f64).max(0.0), (ib - k as f64).min(1.0));
            if t1 > t0 && piece.lowest < level {
                let depth = [
                    level - piece.cubic[0],
                    -piece.cubic[1],
                    -piece.cubic[2],
                    -piece.cubic[3],
                ];
                let m = if piece.highest < level && t0 == 0.0 && t1 == 1.0 {
                    // Wholly below the level over the whole piece: ∫ tʲ (level − H) dt.
                    std::array::from_fn(|j| level / (j + 1) as f64 - piece.whole[j])
                } else if piece.highest < level {
                    cubic_moments(&depth, t0, t1)
                } else {
                    positive_moments(&depth, t0, t1)
                };
                // Shift from the piece's t to the sample index: t → k + t.
                let kf = k as f64;
                sums[0] += m[0];
                sums[1] += m[1] + kf * m[0];
                sums[2] += m[2] + 2.0 * kf * m[1] + kf * kf * m[0];
            }
            k += 1;
        }
        if sums[0].is_nan() || sums[0] <= 0.0 {
            return None;
        }
        let mean_t = sums[1] / sums[0];
        let variance_t = (sums[2] / sums[0] - mean_t * mean_t).max(0.0);
        Some(DepthMoments {
            integral: sums[0] * h,
            mean: self.scan_lo + h * mean_t,
            variance: variance_t * h * h,
        })
    }

    /// The lowest point of the gap's interpolant (the one [`WheelOnRail::depth_moments`]
    /// integrates) on the pieces around the lateral `w` [m] (the piece holding it and its
    /// neighbours); +∞ where they are unfilled. At a contact candidate — a minimum of the
    /// interpolant, refined on the gap itself — the refined gap can lie slightly below it (the
    /// interpolant's error, ~0.1 µm on a narrow flange root): an interpenetration measured from
    /// the refined minimum then starts with nothing below its level to integrate.
    pub fn lowest_near(&self, w: f64) -> f64 {
        let last = self.samples.len() - 1;
        let (span_lo, span_hi) = self.filled_span;
        if span_lo > span_hi || last == 0 {
            return f64::INFINITY;
        }
        let k = (self.index_of(w).clamp(0.0, (last - 1) as f64)) as usize;
        let mut lowest = f64::INFINITY;
        for piece in &self.pieces[k.saturating_sub(1)..(k + 2).min(last)] {
            if piece.lowest < lowest {
                lowest = lowest.min(cubic_minimum(&piece.cubic, 0.0, 1.0));
            }
        }
        lowest
    }
}

/// The least value of the cubic `c` on [t0, t1]: at an end or where its slope vanishes.
fn cubic_minimum(c: &[f64; 4], t0: f64, t1: f64) -> f64 {
    critical_points(c)
        .into_iter()
        .filter(|&t| t > t0 && t < t1)
        .fold(cubic_at(c, t0).min(cubic_at(c, t1)), |least, t| {
            least.min(cubic_at(c, t))
        })
}

/// The critical points of the cubic `c` (the roots of c1 + 2 c2 t + 3 c3 t², cancellation-free),
/// ascending; NaN where there are fewer than two.
#[inline(always)]
fn critical_points(c: &[f64; 4]) -> [f64; 2] {
    let (a, b, cc) = (3.0 * c[3], 2.0 * c[2], c[1]);
    let mut roots = [f64::NAN; 2];
    if a != 0.0 {
        let disc = b * b - 4.0 * a * cc;
        if disc >= 0.0 {
            let r = disc.sqrt();
            let q = -0.5 * (b + b.signum() * r);
            roots = [q / a, if q != 0.0 { cc / q } else { f64::NAN }];
        }
    } else if b != 0.0 {
        roots[0] = -cc / b;
    }
    if roots[0] > roots[1] {
        roots.swap(0, 1);
    }
    roots
}

/// Coefficients (c0 + c1 t + c2 t² + c3 t³) of level − H(t) on t ∈ [0, 1], H the cubic Hermite
/// interpolant with values `g0`, `g1` and derivatives `d0`, `d1` (per unit t) at the ends.
pub(super) fn hermite_depth(level: f64, g0: f64, g1: f64, d0: f64, d1: f64) -> [f64; 4] {
    let c2 = 3.0 * (g1 - g0) - 2.0 * d0 - d1;
    let c3 = 2.0 * (g0 - g1) + d0 + d1;
    [level - g0, -d0, -c2, -c3]
}

/// One piece of the samples' cubic Hermite interpolant, H(t) = c0 + c1 t + c2 t² + c3 t³ on
/// t ∈ [0, 1] between two samples, with bounds of its values and its moments ∫₀¹ tʲ H dt.
#[derive(Debug, Clone, Copy)]
pub(super) struct Piece {
    lowest: f64,
    highest: f64,
    cubic: [f64; 4],
    whole: [f64; 3],
}

impl Piece {
    /// The piece between samples `a` and `b` a step `h` apart; at +∞ where either is unfilled.
    pub(super) fn of(a: &GapSample, b: &GapSample, h: f64) -> Self {
        if !(a.gap.is_finite() && b.gap.is_finite()) {
            return Self {
                lowest: f64::INFINITY,
                highest: f64::INFINITY,
                cubic: [0.0; 4],
                whole: [0.0; 3],
            };
        }
        let (d0, d1) = (a.slope * h, b.slope * h);
        let (lowest, highest) = hermite_bounds(a.gap, b.gap, d0, d1);
        // hermite_depth at level 0 is −H.
        let cubic = hermite_depth(0.0, a.gap, b.gap, d0, d1).map(|c| -c);
        Self {
            lowest,
            highest,
            cubic,
            whole: cubic_moments(&cubic, 0.0, 1.0),
        }
    }
}

/// Lower and upper bounds of the cubic Hermite interpolant with values `g0`, `g1` and
/// derivatives `d0`, `d1` (per unit t) on t ∈ [0, 1]: H = chord + t(1 − t)[(d0 − Δ)(1 − t) −
/// (d1 − Δ)t] with Δ = g1 − g0, t(1 − t) ≤ ¼ and the bracket within ±max|dᵢ − Δ|.
fn hermite_bounds(g0: f64, g1: f64, d0: f64, d1: f64) -> (f64, f64) {
    let chord = g1 - g0;
    let bulge = 0.25 * (d0 - chord).abs().max((d1 - chord).abs());
    (g0.min(g1) - bulge, g0.max(g1) + bulge)
}

pub(super) fn cubic_at(c: &[f64; 4], t: f64) -> f64 {
    c[0] + t * (c[1] + t * (c[2] + t * c[3]))
}

/// ∫ t^j p(t) dt over [t0, t1] for j = 0, 1, 2, p the cubic `c`: the antiderivatives
/// t^{j+1} Σ_i c_i t^i/(i + j + 1) by Horner's rule at both ends.
fn cubic_moments(c: &[f64; 4], t0: f64, t1: f64) -> [f64; 3] {
    let antiderivative = |t: f64, j: usize| {
        let k = j as f64;
        let inner = c[0] / (k + 1.0)
            + t * (c[1] / (k + 2.0) + t * (c[2] / (k + 3.0) + t * (c[3] / (k + 4.0))));
        let mut power = t;
        for _ in 0..j {
            power *= t;
        }
        power * inner
    };
    std::array::from_fn(|j| antiderivative(t1, j) - antiderivative(t0, j))
}

/// ∫ t^j max(0, p(t)) dt over [t0, t1] (j = 0, 1, 2) for the cubic `c`: the interval is cut
/// at p's critical points (the roots of p', where p turns), so that p is monotone on each piece
/// and has at most one root there, found by Newton's method kept in its bracket to 1e−13;
/// the positive parts are
/// integrated exactly. No root is missed, so the result is continuous in the coefficients.
fn positive_moments(c: &[f64; 4], t0: f64, t1: f64) -> [f64; 3] {
    let mut out = [0.0; 3];
    // Critical points inside (t0, t1), ascending.
    let mut knots = [t0, t1, t1, t1];
    let mut n = 1;
    for r in critical_points(c) {
        if r > t0 && r < t1 {
            knots[n] = r;
            n += 1;
        }
    }
    knots[n] = t1;
    n += 1;
    for w in knots[..n].windows(2) {
        let (a, b) = (w[0], w[1]);
        if b.partial_cmp(&a) != Some(std::cmp::Ordering::Greater) {
            continue;
        }
        let (pa, pb) = (cubic_at(c, a), cubic_at(c, b));
        let (lo, hi) = match (pa > 0.0, pb > 0.0) {
            (false, false) => continue,
            (true, true) => (a, b),
            (positive_a, _) => {
                // One root in (a, b): p is monotone here. Newton from the bracket's secant
                // point, kept inside the bracket (bisection where it would leave it).
                let (mut x0, mut x1) = (a, b);
                let mut x = a + (b - a) * pa / (pa - pb);
                for _ in 0..60 {
                    let v = cubic_at(c, x);
                    if (v > 0.0) == positive_a {
                        x0 = x;
                    } else {
                        x1 = x;
                    }
                    let slope = c[1] + x * (2.0 * c[2] + 3.0 * c[3] * x);
                    let newton = x - v / slope;
                    let next = if newton > x0 && newton < x1 {
                        newton
                    } else {
                        0.5 * (x0 + x1)
                    };
                    let moved = (next - x).abs();
                    x = next;
                    if moved <= 1e-13 || x1 - x0 <= 1e-13 {
                        break;
                    }
                }
                let root = x;
                if positive_a {
                    (a, root)
                } else {
                    (root, b)
                }
            }
        };
        let m = cubic_moments(c, lo, hi);
        for j in 0..3 {
            out[j] += m[j];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The least value of a cubic on an interval against 100 001 samples of it (which can only
    /// find a value at or above the least): within 1e−9 of the sampled least for cubics with
    /// interior minima, maxima, inflections and end minima.
    #[test]
    fn cubic_minimum_is_the_least_value() {
        let cubics = [
            [1.0, -3.0, 2.0, 0.5],
            [0.0, 1.0, -6.0, 4.0],
            [2.0, 0.0, 0.0, -1.0],
            [0.3, -0.1, 0.0, 0.0],
            [-1.0, 0.5, 1.5, -2.5],
        ];
        for c in cubics {
            for (t0, t1) in [(0.0, 1.0), (0.2, 0.7), (0.5, 0.5)] {
                let n = 100_000;
                let sampled = (0..=n)
                    .map(|i| cubic_at(&c, t0 + (t1 - t0) * i as f64 / n as f64))
                    .fold(f64::INFINITY, f64::min);
                let least = cubic_minimum(&c, t0, t1);
                assert!(least <= sampled + 1e-15, "{c:?} on [{t0}, {t1}]");
                assert!(
                    sampled - least <= 1e-9,
                    "{c:?} on [{t0}, {t1}]: {least} vs {sampled}"
                );
            }
        }
    }
}
