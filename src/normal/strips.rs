//! Strip solutions shared by the non-elliptic normal models.
//!
//! Every model (`linder`, `kik_piotrowski`, `stripes`, `analyn`) writes the same
//! [`StripSolution`] on a patch's [`StripGeometry`]: per strip a semi-elliptic pressure
//! p(x) = p0 √(1 − ((x − x_c)/x_l)²) with half-length x_l and peak p0, and its force (V1)
//! F = (π/2) p0 x_l Δs. [`PatchSummary`] reduces a solution to the patch figures the FMU reports;
//! [`first_contact_points`] finds where the gap has its local minima. All buffers are fixed-size
//! arrays: a solve allocates nothing.

use crate::geometry::strips::{PerStrip, StripGeometry};

/// Per-strip pressure of a normal model at one approach δ.
#[derive(Debug, Clone, Default)]
pub struct StripSolution {
    pub n: usize,
    /// Half-length x_l,i of the strip's contact [m]; 0 when the strip is out of contact.
    pub half_length: PerStrip<f64>,
    /// Peak pressure p0_i of the strip's semi-ellipse [Pa]; 0 out of contact.
    pub pmax: PerStrip<f64>,
    /// Strip normal force (π/2) p0_i x_l,i Δs [N].
    pub force: PerStrip<f64>,
    /// The model's own local ellipse of strip i, semi-axes (along x, across) [m], for the
    /// tangential problem's strip-wise flexibilities (docs/theory.md §4.7); (0, 0) where the model
    /// defines none (only Linder sets it: (a_j, b_L)).
    pub local_axes: PerStrip<(f64, f64)>,
    /// Correction of strip i's contact area 2 x_l,i Δs [m²] (0 unless the model sets it): Linder
    /// bounds its patch laterally by its virtual ellipse, so the strips at its edges lie partly
    /// inside it (docs/theory.md §5.3, "area").
    pub area_correction: PerStrip<f64>,
}

impl StripSolution {
    /// Starts a model's solve on `geom` at approach `delta` [m] with contact modulus `e_star`
    /// [Pa]: clears the solution's strips and returns their count, or `None` when there is
    /// nothing to solve (no strips, or δ, Δs or E* not finite and positive) — the solution then
    /// stays empty and the model's normal force is zero.
    pub fn begin(&mut self, geom: &StripGeometry, delta: f64, e_star: f64) -> Option<usize> {
        let n = geom.len();
        self.reset(n);
        let positive = |v: f64| v > 0.0 && v.is_finite();
        (n > 0 && positive(delta) && positive(geom.ds) && positive(e_star)).then_some(n)
    }

    /// Clears the first `n` strips and sets the count.
    pub fn reset(&mut self, n: usize) {
        self.n = n;
        self.half_length[..n].fill(0.0);
        self.pmax[..n].fill(0.0);
        self.force[..n].fill(0.0);
        self.local_axes[..n].fill((0.0, 0.0));
        self.area_correction[..n].fill(0.0);
    }

    /// Sets strip `i` to a semi-ellipse of half-length `half_length` and peak `pmax`; strip width
    /// `ds`. Non-positive or non-finite values leave the strip out of contact.
    pub fn set(&mut self, i: usize, half_length: f64, pmax: f64, ds: f64) {
        if half_length > 0.0 && pmax > 0.0 && half_length.is_finite() && pmax.is_finite() {
            self.half_length[i] = half_length;
            self.pmax[i] = pmax;
            self.force[i] = 0.5 * std::f64::consts::PI * pmax * half_length * ds;
        } else {
            self.half_length[i] = 0.0;
            self.pmax[i] = 0.0;
            self.force[i] = 0.0;
        }
    }

    /// Total normal force Σ F_i [N].
    pub fn normal_force(&self) -> f64 {
        self.force[..self.n].iter().sum()
    }
}

/// Patch figures of a strip solution.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PatchSummary {
    /// Normal force [N].
    pub normal_force: f64,
    /// Area Σ 2 x_l,i Δs [m²].
    pub area: f64,
    /// Largest strip peak pressure [Pa].
    pub pmax: f64,
    /// Longest strip 2 max x_l,i [m].
    pub length: f64,
    /// Lateral extent from the first to the last strip in contact, whole strips [m].
    pub width: f64,
    /// Lateral extent in the contact plane: outer edges of the first and last strips in contact [m].
    pub s_min: f64,
    pub s_max: f64,
    /// Pressure-weighted mean lateral position Σ F_i s_i / N [m].
    pub s_centroid: f64,
    /// Number of strips in contact.
    pub strips_in_contact: usize,
    /// Width of the ellipse with the same area-weighted spread of s: 4 × the standard
    /// deviation of s over the contact area (an ellipse's is b/2) [m]. Unlike [`Self::width`],
    /// which jumps by Δs when a strip enters contact, it is continuous in the strips'
    /// half-lengths (a strip enters with zero area), so quantities derived from it (the
    /// equivalent ellipse of the tangential problem) do not jump with the wheel height.
    pub spread_width: f64,
}

impl PatchSummary {
    /// Whether the patch carries load: a positive normal force on strips of positive area.
    pub fn in_contact(&self) -> bool {
        self.normal_force > 0.0 && self.area > 0.0 && self.width > 0.0
    }

    /// Reduces `sol` on `geom`.
    pub fn of(geom: &StripGeometry, sol: &StripSolution) -> Self {
        let mut out = Self::default();
        let mut first = None;
        let mut last = 0;
        let mut moment = 0.0;
        let (mut area_s, mut area_s2) = (0.0, 0.0);
        for i in 0..sol.n.min(geom.n) {
            let strip_area = 2.0 * sol.half_length[i] * geom.ds + sol.area_correction[i];
            if strip_area > 0.0 {
                out.area += strip_area;
                area_s += strip_area * geom.s[i];
                area_s2 += strip_area * geom.s[i] * geom.s[i];
            }
            if sol.half_length[i] <= 0.0 {
                continue;
            }
            first.get_or_insert(i);
            last = i;
            out.strips_in_contact += 1;
            out.normal_force += sol.force[i];
            moment += sol.force[i] * geom.s[i];
            out.pmax = out.pmax.max(sol.pmax[i]);
            out.length = out.length.max(2.0 * sol.half_length[i]);
        }
        if let Some(first) = first {
            out.s_min = geom.s[first] - 0.5 * geom.ds;
            out.s_max = geom.s[last] + 0.5 * geom.ds;
            out.width = out.s_max - out.s_min;
            if out.normal_force > 0.0 {
                out.s_centroid = moment / out.normal_force;
            }
            if out.area > 0.0 {
                let mean = area_s / out.area;
                // Each strip spreads its area uniformly over Δs: + Δs²/12.
                let variance =
                    (area_s2 / out.area - mean * mean).max(0.0) + geom.ds * geom.ds / 12.0;
                out.spread_width = 4.0 * variance.sqrt();
            }
        }
        out
    }
}

/// Most first-contact points (local minima of the gap across the strips) a patch is solved for.
pub const MAX_CONTACT_POINTS: usize = 4;

/// The first-contact points of a patch (Kik–Piotrowski's KP4 condition, Linder's centre at
/// small approaches): the local minima of the gap f over the strips,
/// each at the vertex of the parabola through its strip and the two neighbours (within half a
/// strip of its centre; exact for a quadratic gap, so a Hertz gap's y0 is its minimum however
/// the strips lie), weighted by e⁴, e the minimum's height below its lowest neighbouring ridge
/// of f (as the patch groups share a first-contact point, `crate::geometry::groups`). One minimum
/// gets weight 1. Where a patch spans two lobes of comparable depth, KP4 is imposed at both,
/// blended by these weights, so that the solution does not jump where their depths cross; the
/// weights do not depend on δ, so N(δ) stays increasing.
pub fn first_contact_points(
    geom: &StripGeometry,
    n: usize,
    out: &mut [(f64, f64, f64); MAX_CONTACT_POINTS],
) -> usize {
    let f = &geom.f;
    let usable = |j: usize| f[j].is_finite() && f[j] < crate::geometry::search::UNREACHED_GAP;
    let mut minima = [0usize; MAX_CONTACT_POINTS];
    let mut ridges = [f64::INFINITY; MAX_CONTACT_POINTS];
    let mut count = 0;
    let mut ridge = f64::NEG_INFINITY;
    for j in 0..n {
        if !usable(j) {
            continue;
        }
        ridge = ridge.max(f[j]);
        let lower_left = j == 0 || !usable(j - 1) || f[j] <= f[j - 1];
        let lower_right = j + 1 == n || !usable(j + 1) || f[j] < f[j + 1];
        if !(lower_left && lower_right) {
            continue;
        }
        if count == MAX_CONTACT_POINTS {
            // Keep the deepest: replace the shallowest if this one is deeper.
            let shallowest = (0..count).max_by(|&a, &b| f[minima[a]].total_cmp(&f[minima[b]]));
            if let Some(k) = shallowest.filter(|&k| f[minima[k]] > f[j]) {
                minima[k] = j;
            }
            continue;
        }
        if count > 0 {
            ridges[count - 1] = ridge;
        }
        minima[count] = j;
        count += 1;
        ridge = f[j];
    }
    let mut total = 0.0;
    for k in 0..count {
        let j = minima[k];
        let left = if k > 0 { ridges[k - 1] } else { f64::INFINITY };
        let right = if k + 1 < count {
            ridges[k]
        } else {
            f64::INFINITY
        };
        let height = (left.min(right) - f[j]).max(0.0);
        let weight = if count == 1 {
            1.0
        } else if height.is_finite() {
            height.powi(16)
        } else {
            0.0
        };
        // Vertex of the parabola through the neighbours, within half a strip.
        let (mut y0, mut f0) = (geom.s[j], f[j]);
        if j > 0 && j + 1 < n && usable(j - 1) && usable(j + 1) {
            let curvature = f[j - 1] - 2.0 * f[j] + f[j + 1];
            if curvature > 0.0 {
                let t = (0.5 * (f[j - 1] - f[j + 1]) / curvature).clamp(-0.5, 0.5);
                y0 += t * geom.ds;
                f0 = f[j] + 0.25 * (f[j + 1] - f[j - 1]) * t + 0.5 * curvature * t * t;
            }
        }
        out[k] = (y0, f0, weight);
        total += weight;
    }
    if total > 0.0 && total.is_finite() {
        for p in &mut out[..count] {
            p.2 /= total;
        }
    } else {
        for p in &mut out[..count] {
            p.2 = 1.0 / count as f64;
        }
    }
    count
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_width_is_an_ellipses_width_and_continuous_where_strips_enter() {
        // An elliptic patch on 40 strips over [−b, b]: x_l = a √(1 − s²/b²).
        let (a, b, n) = (6e-3, 4e-3, 40);
        let mut geom = StripGeometry {
            n: n + 1,
            ds: 2.0 * b / n as f64,
            ..StripGeometry::default()
        };
        let mut sol = StripSolution {
            n: n + 1,
            ..StripSolution::default()
        };
        for i in 0..=n {
            geom.s[i] = -b + (i as f64 + 0.5) * geom.ds;
            let t = (geom.s[i] / b).min(1.0);
            sol.half_length[i] = a * ((1.0 - t) * (1.0 + t)).max(0.0).sqrt();
            sol.force[i] = sol.half_length[i];
        }
        // Strip n lies beyond b: out of contact.
        assert_eq!(sol.half_length[n], 0.0);
        let base = PatchSummary::of(&geom, &sol);
        // The area-weighted spread of an ellipse is b/2: 4σ = 2b, here to the midpoint rule's
        // edge error (√-edges, ~(Δs/b)^{3/2}).
        assert!(
            (base.spread_width / (2.0 * b) - 1.0).abs() < 5e-3,
            "{}",
            base.spread_width
        );
        // A strip entering contact with a vanishing half-length moves the whole-strip width by
        // Δs but the spread width by next to nothing.
        sol.half_length[n] = 1e-12;
        sol.force[n] = 1e-12;
        let entered = PatchSummary::of(&geom, &sol);
        assert!((entered.width - base.width - geom.ds).abs() < 1e-15);
        assert!((entered.spread_width / base.spread_width - 1.0).abs() < 1e-8);
    }

    #[test]
    fn summary_of_a_quadratic_gap() {
        let g = StripGeometry::quadratic(1.0, 2.0, -1e-3, 1e-3, 4);
        assert_eq!(g.strip_at_origin(), Some(2));
        let mut sol = StripSolution::default();
        sol.reset(4);
        sol.set(1, 2e-3, 1e8, g.ds);
        sol.set(2, 3e-3, 2e8, g.ds);
        let s = PatchSummary::of(&g, &sol);
        assert_eq!(s.strips_in_contact, 2);
        assert!((s.width - 1e-3).abs() < 1e-15);
        assert!((s.length - 6e-3).abs() < 1e-15);
        assert_eq!(s.pmax, 2e8);
        assert!((s.area - 2.0 * 5e-3 * 0.5e-3).abs() < 1e-15);
    }
}
