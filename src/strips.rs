//! Strip infrastructure shared by the non-elliptic normal models (physics.md §5.1).
//!
//! A patch is cut into `n` lateral strips of equal width Δs across its contact plane. Each strip
//! carries the undeformed geometry at its centre, independent of the approach δ
//! ([`StripGeometry`]): the normal gap f(s) measured from the patch's first-contact point
//! (f(0) = 0 at s = 0), the relative curvatures A(s) (rolling direction) and B(s) = ½ f''(s), and
//! the position x_c(s) of the gap minimum along x (shifted by yaw). The gap of the undeformed
//! surfaces is h(x, s) = f(s) + A(s)(x − x_c(s))².
//!
//! Every model (`linder`, `kik_piotrowski`, `stripes`, `analyn`) writes the same
//! [`StripSolution`]: per strip a semi-elliptic pressure p(x) = p0 √(1 − ((x − x_c)/x_l)²) with
//! half-length x_l and peak p0, and its force (V1) F = (π/2) p0 x_l Δs. [`PatchSummary`] reduces a
//! solution to the patch figures the FMU reports.
//!
//! [`HertzShapeTable`] holds the Hertz functions of the curvature ratio that the strip models need
//! per strip (shape factor ε_x, axis ratio a/b, peak-pressure coefficient), tabulated once at
//! start-up so that a step does no per-strip H1 solve. All buffers are fixed-size arrays: a solve
//! allocates nothing.

use crate::error::InputError;
use crate::hertz::{hertz_from_approach, shape_factors};

/// Largest number of strips per patch.
pub const MAX_STRIPS: usize = 200;

/// Default number of strips across a patch: on the central case the strip models' tangential
/// forces are as close to their 200-strip values with 24 strips as with 40 (the elements along
/// each strip set the error; docs/performance.md), at ~60 % of the cost. Not fewer: Linder's
/// force jumps as a strip enters contact (∝ 1/strips), and at 20 strips a jump near y = 2.9 mm
/// exceeds the 1 % load check.
pub const DEFAULT_STRIPS: usize = 24;

/// The undeformed geometry of one patch on its strips (independent of the approach δ).
#[derive(Debug, Clone)]
pub struct StripGeometry {
    /// Number of strips in use (≤ [`MAX_STRIPS`]).
    pub n: usize,
    /// Strip width Δs [m] (uniform).
    pub ds: f64,
    /// Strip centre s_i: lateral coordinate in the contact plane from the patch's first-contact
    /// point, positive towards the field side [m]. Increasing with i.
    pub s: [f64; MAX_STRIPS],
    /// Undeformed normal gap f(s_i) at the strip's locus, measured from the first-contact point
    /// (f = 0 at s = 0, f ≥ 0 across the patch) [m].
    pub f: [f64; MAX_STRIPS],
    /// Relative longitudinal curvature A(s_i) > 0 [1/m].
    pub curv_a: [f64; MAX_STRIPS],
    /// Relative lateral curvature B(s_i) = ½ f''(s_i), raw: may be zero or negative [1/m].
    pub curv_b: [f64; MAX_STRIPS],
    /// Longitudinal position x_c(s_i) of the gap minimum along the strip (yaw lead) [m].
    pub x_c: [f64; MAX_STRIPS],
}

impl Default for StripGeometry {
    fn default() -> Self {
        Self {
            n: 0,
            ds: 0.0,
            s: [0.0; MAX_STRIPS],
            f: [0.0; MAX_STRIPS],
            curv_a: [0.0; MAX_STRIPS],
            curv_b: [0.0; MAX_STRIPS],
            x_c: [0.0; MAX_STRIPS],
        }
    }
}

impl StripGeometry {
    /// A Hertzian gap f = B s², constant A, on `n` strips covering [s_lo, s_hi] (tests and
    /// examples).
    pub fn quadratic(curv_a: f64, curv_b: f64, s_lo: f64, s_hi: f64, n: usize) -> Self {
        Self::from_fn(s_lo, s_hi, n, |s| (curv_b * s * s, curv_a, curv_b))
    }

    /// A gap from a function s ↦ (f, A, B) sampled at the centres of `n` strips on [s_lo, s_hi].
    pub fn from_fn(s_lo: f64, s_hi: f64, n: usize, gap: impl Fn(f64) -> (f64, f64, f64)) -> Self {
        let n = n.clamp(1, MAX_STRIPS);
        let mut g = Self {
            n,
            ds: (s_hi - s_lo) / n as f64,
            ..Self::default()
        };
        for i in 0..n {
            let s = s_lo + (i as f64 + 0.5) * g.ds;
            let (f, a, b) = gap(s);
            g.s[i] = s;
            g.f[i] = f;
            g.curv_a[i] = a;
            g.curv_b[i] = b;
        }
        g
    }

    /// Number of strips in use, never more than [`MAX_STRIPS`] (the fields are public, so a
    /// model must not trust `n` alone).
    pub fn len(&self) -> usize {
        self.n.min(MAX_STRIPS)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Index of the strip whose extent contains s = 0 (the first-contact point), if any.
    pub fn strip_at_origin(&self) -> Option<usize> {
        (0..self.n).find(|&i| (self.s[i] - 0.5 * self.ds) <= 0.0 && 0.0 < self.s[i] + 0.5 * self.ds)
    }
}

/// Per-strip pressure of a normal model at one approach δ.
#[derive(Debug, Clone)]
pub struct StripSolution {
    pub n: usize,
    /// Half-length x_l,i of the strip's contact [m]; 0 when the strip is out of contact.
    pub half_length: [f64; MAX_STRIPS],
    /// Peak pressure p0_i of the strip's semi-ellipse [Pa]; 0 out of contact.
    pub pmax: [f64; MAX_STRIPS],
    /// Strip normal force (π/2) p0_i x_l,i Δs [N].
    pub force: [f64; MAX_STRIPS],
    /// The model's own local ellipse of strip i, semi-axes (along x, across) [m], for the
    /// tangential problem's strip-wise flexibilities (physics.md §4.8); (0, 0) where the model
    /// defines none (only Linder sets it: (a_j, b_L)).
    pub local_axes: [(f64, f64); MAX_STRIPS],
}

impl Default for StripSolution {
    fn default() -> Self {
        Self {
            n: 0,
            half_length: [0.0; MAX_STRIPS],
            pmax: [0.0; MAX_STRIPS],
            force: [0.0; MAX_STRIPS],
            local_axes: [(0.0, 0.0); MAX_STRIPS],
        }
    }
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
            if sol.half_length[i] <= 0.0 {
                continue;
            }
            let strip_area = 2.0 * sol.half_length[i] * geom.ds;
            area_s += strip_area * geom.s[i];
            area_s2 += strip_area * geom.s[i] * geom.s[i];
            first.get_or_insert(i);
            last = i;
            out.strips_in_contact += 1;
            out.normal_force += sol.force[i];
            moment += sol.force[i] * geom.s[i];
            out.area += 2.0 * sol.half_length[i] * geom.ds;
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
/// of f (as the patch groups share a first-contact point, `crate::patch_groups`). One minimum
/// gets weight 1. Where a patch spans two lobes of comparable depth, KP4 is imposed at both,
/// blended by these weights, so that the solution does not jump where their depths cross; the
/// weights do not depend on δ, so N(δ) stays increasing.
pub fn first_contact_points(
    geom: &StripGeometry,
    n: usize,
    out: &mut [(f64, f64, f64); MAX_CONTACT_POINTS],
) -> usize {
    let f = &geom.f;
    let usable = |j: usize| f[j].is_finite() && f[j] < crate::contact_search::UNREACHED_GAP;
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

/// Parameters shared by the strip normal models.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalParams {
    /// Contact modulus E* = E/(2(1 − ν²)) [Pa].
    pub e_star: f64,
    /// Floor of the lateral curvature B [1/m] (physics.md §5.10; default 0.1 1/m = CONTACT's
    /// 1e−4 1/mm): STRIPES-B and ANALYN replace B < b_min by b_min, STRIPES-A&B shifts all B by
    /// max(0, b_min − min B).
    pub b_min: f64,
    /// STRIPES-B smoothing window of B as a fraction of the strip set's width [-] (0 = none).
    pub b_smoothing: f64,
    /// Kik–Piotrowski area-preserving shape correction (KP8).
    pub kp_shape_correction: bool,
}

/// Default STRIPES-B smoothing window (fraction of the patch width).
pub const DEFAULT_B_SMOOTHING: f64 = 0.2;

impl NormalParams {
    /// The floor of B the models apply: `b_min`, or the default where it is not finite and
    /// positive (the models never fail on a bad parameter; the FMU validates it on setting).
    pub fn b_floor(&self) -> f64 {
        if self.b_min.is_finite() && self.b_min > 0.0 {
            self.b_min
        } else {
            Self::default().b_min
        }
    }
}

impl Default for NormalParams {
    fn default() -> Self {
        Self {
            e_star: crate::hertz::contact_modulus(2.1e11, 0.28),
            b_min: 0.1,
            b_smoothing: DEFAULT_B_SMOOTHING,
            kp_shape_correction: false,
        }
    }
}

/// A strip normal model. Implementations own fixed-size scratch buffers: neither method
/// allocates, panics or produces NaN for any finite geometry (B may be ≤ 0) and any δ.
pub trait StripModel {
    /// δ-independent work for a new geometry (curvature rules, smoothing, per-strip Hertz shapes).
    fn prepare(&mut self, geom: &StripGeometry, params: &NormalParams, table: &HertzShapeTable);
    /// Pressure at the normal approach δ [m] of the patch's first-contact point (δ ≤ 0: no
    /// contact). Writes all `geom.n` strips of `out` and returns the normal force [N].
    fn solve(
        &mut self,
        geom: &StripGeometry,
        params: &NormalParams,
        table: &HertzShapeTable,
        delta: f64,
        out: &mut StripSolution,
    ) -> f64;
}

/// The normal contact models (FMU parameter `normalModel`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum NormalModel {
    /// 1: Hertz per contact patch (multi-Hertzian), no strips.
    #[default]
    Hertz,
    /// 2: Linder's virtual penetration (`crate::linder`).
    Linder,
    /// 3: Kik–Piotrowski (`crate::kik_piotrowski`).
    KikPiotrowski,
    /// 4: STRIPES with B correction and smoothing (`crate::stripes::StripesB`).
    StripesB,
    /// 5: STRIPES with A-and-B correction, no smoothing (`crate::stripes::StripesAB`).
    StripesAB,
    /// 6: ANALYN (`crate::analyn`).
    Analyn,
}

impl NormalModel {
    /// All models in FMU order (`normalModel` = index + 1).
    pub const ALL: [NormalModel; 6] = [
        NormalModel::Hertz,
        NormalModel::Linder,
        NormalModel::KikPiotrowski,
        NormalModel::StripesB,
        NormalModel::StripesAB,
        NormalModel::Analyn,
    ];

    /// The model of FMU code `code` (1…6).
    pub fn from_code(code: i32) -> Option<Self> {
        usize::try_from(code - 1)
            .ok()
            .and_then(|i| Self::ALL.get(i).copied())
    }

    /// FMU code (1…6).
    pub fn code(self) -> i32 {
        Self::ALL
            .iter()
            .position(|m| *m == self)
            .map_or(1, |i| i as i32 + 1)
    }

    /// Short name (CLI, reports).
    pub fn name(self) -> &'static str {
        match self {
            NormalModel::Hertz => "hertz",
            NormalModel::Linder => "linder",
            NormalModel::KikPiotrowski => "kik-piotrowski",
            NormalModel::StripesB => "stripes-b",
            NormalModel::StripesAB => "stripes-ab",
            NormalModel::Analyn => "analyn",
        }
    }

    /// The model named `name` (as [`NormalModel::name`]).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|m| m.name() == name)
    }

    /// A solver for a strip model; `None` for Hertz (no strips).
    pub fn strip_model(self) -> Option<Box<dyn StripModel + Send>> {
        Some(match self {
            NormalModel::Hertz => return None,
            NormalModel::Linder => Box::new(crate::linder::Linder::default()),
            NormalModel::KikPiotrowski => Box::new(crate::kik_piotrowski::KikPiotrowski::default()),
            NormalModel::StripesB => Box::new(crate::stripes::StripesB::default()),
            NormalModel::StripesAB => Box::new(crate::stripes::StripesAB::default()),
            NormalModel::Analyn => Box::new(crate::analyn::Analyn::default()),
        })
    }
}

/// Hertz quantities that depend only on the curvature ratio A/B.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzShape {
    /// Shape factor ε_x = A a²/δ (H6) [-]; ε_y = 1 − ε_x.
    pub eps_x: f64,
    /// Axis ratio a/b (a along x) [-].
    pub a_over_b: f64,
    /// Peak-pressure coefficient P: p0 = E* √(δ (A + B)) · P [-].
    pub p0_coeff: f64,
}

impl HertzShape {
    /// ε_y = B b²/δ = 1 − ε_x.
    pub fn eps_y(&self) -> f64 {
        1.0 - self.eps_x
    }
}

/// Exact Hertz shape for curvatures A, B > 0 (solves H1; used to build the table and in tests).
pub fn hertz_shape_exact(curv_a: f64, curv_b: f64) -> Result<HertzShape, InputError> {
    let (eps_x, _) = shape_factors(curv_a, curv_b)?;
    let unit = hertz_from_approach(curv_a, curv_b, 1.0, 1.0)?;
    Ok(HertzShape {
        eps_x,
        a_over_b: unit.a / unit.b,
        p0_coeff: unit.p0 / (curv_a + curv_b).sqrt(),
    })
}

/// Half range of u = ln(A/B) covered by [`HertzShapeTable`]; beyond it u is clamped
/// (A/B outside [1.1e−7, 8.9e6]: line contact for every practical purpose).
pub const SHAPE_TABLE_RANGE: f64 = 16.0;
/// Node spacing in u of [`HertzShapeTable`]: cubic interpolation error ~ Δu⁴ ≈ 2e−7 of the
/// functions' fourth derivative (O(1)), below 1e−7 relative (tested).
const SHAPE_TABLE_STEP: f64 = 0.02;
const SHAPE_TABLE_NODES: usize = (2.0 * SHAPE_TABLE_RANGE / SHAPE_TABLE_STEP) as usize + 1;

/// Weights of 4-point (cubic) Lagrange interpolation on the nodes −1, 0, 1, 2 at offset `x`
/// (x ∈ [0, 1] between nodes 0 and 1).
pub(crate) fn cubic_lagrange_weights(x: f64) -> [f64; 4] {
    [
        -x * (x - 1.0) * (x - 2.0) / 6.0,
        (x + 1.0) * (x - 1.0) * (x - 2.0) / 2.0,
        -(x + 1.0) * x * (x - 2.0) / 2.0,
        (x + 1.0) * x * (x - 1.0) / 6.0,
    ]
}

/// [`HertzShape`] tabulated on a uniform grid in u = ln(A/B) with 4-point cubic (Lagrange)
/// interpolation in each of ε_x, a/b and P. They vary like e^{cu} with |c| ≤ 1 (power laws in
/// A/B towards line contact), whose cubic interpolation at this step is relatively exact to
/// ~c⁴Δu⁴/40 ≈ 4e−9 — interpolating the values, not their logarithms, spares three
/// exponentials per lookup (the per-strip cost of the strip models). Built once (~1600 exact
/// solves, a few milliseconds); lookups cost a logarithm and a few multiplications.
#[derive(Debug, Clone)]
pub struct HertzShapeTable {
    /// Per node: ε_x, a/b, P.
    nodes: Vec<[f64; 3]>,
}

impl Default for HertzShapeTable {
    fn default() -> Self {
        Self::new()
    }
}

impl HertzShapeTable {
    pub fn new() -> Self {
        let nodes = (0..SHAPE_TABLE_NODES)
            .map(|k| {
                let u = -SHAPE_TABLE_RANGE + SHAPE_TABLE_STEP * k as f64;
                let h = hertz_shape_exact((0.5 * u).exp(), (-0.5 * u).exp())
                    .expect("curvature ratios inside the table range are solvable");
                [h.eps_x, h.a_over_b, h.p0_coeff]
            })
            .collect();
        Self { nodes }
    }

    /// The Hertz ellipse of curvatures A, B > 0 [1/m] at approach δ ≥ 0 [m] with contact modulus
    /// E* [Pa], from the table: a = √(ε_x δ/A), b = a/(a/b), p0 = E*√(δ(A + B))·P, N = (2/3)π a b p0
    /// (relative error ≤ 1e−7, the table's; `crate::hertz::hertz_from_approach` outside its
    /// range). Same errors as `hertz_from_approach`.
    pub fn patch(
        &self,
        curv_a: f64,
        curv_b: f64,
        approach: f64,
        e_star: f64,
    ) -> Result<crate::hertz::HertzPatch, InputError> {
        let u = (curv_a / curv_b).ln();
        let usable = u.abs() <= SHAPE_TABLE_RANGE
            && approach > 0.0
            && approach.is_finite()
            && e_star > 0.0
            && e_star.is_finite();
        if !usable {
            return crate::hertz::hertz_from_approach(curv_a, curv_b, approach, e_star);
        }
        let shape = self.at_log_ratio(u);
        let a = (shape.eps_x * approach / curv_a).sqrt();
        let b = a / shape.a_over_b;
        let p0 = e_star * (approach * (curv_a + curv_b)).sqrt() * shape.p0_coeff;
        Ok(crate::hertz::HertzPatch {
            a,
            b,
            approach,
            p0,
            normal_force: 2.0 / 3.0 * std::f64::consts::PI * a * b * p0,
        })
    }

    /// Hertz shape for curvatures A, B > 0 [1/m]. Non-positive or non-finite curvatures are an
    /// error naming A or B.
    pub fn lookup(&self, curv_a: f64, curv_b: f64) -> Result<HertzShape, InputError> {
        crate::error::require_positive("A", curv_a)?;
        crate::error::require_positive("B", curv_b)?;
        Ok(self.at_log_ratio((curv_a / curv_b).ln()))
    }

    /// Hertz shape at u = ln(A/B) (clamped to ±[`SHAPE_TABLE_RANGE`]).
    pub fn at_log_ratio(&self, u: f64) -> HertzShape {
        let u = u.clamp(-SHAPE_TABLE_RANGE, SHAPE_TABLE_RANGE);
        let t = (u + SHAPE_TABLE_RANGE) / SHAPE_TABLE_STEP;
        // Interval [k, k+1] with neighbours k−1 and k+2 inside the table.
        // `as usize` floors a non-negative value (and saturates below 0) without a call to
        // libm's floor, which baseline x86-64 (no SSE4.1 rounding) would need.
        let k = (t as usize).clamp(1, SHAPE_TABLE_NODES - 3);
        let w = cubic_lagrange_weights(t - k as f64);
        let mut v = [0.0; 3];
        for (j, wj) in w.iter().enumerate() {
            let node = &self.nodes[k - 1 + j];
            for q in 0..3 {
                v[q] += wj * node[q];
            }
        }
        HertzShape {
            eps_x: v[0],
            a_over_b: v[1],
            p0_coeff: v[2],
        }
    }
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
    fn table_matches_exact_hertz_to_1e7() {
        // Tolerance: the interpolation error bound in SHAPE_TABLE_STEP's comment.
        let table = HertzShapeTable::new();
        let mut u: f64 = -15.0;
        let mut worst = 0.0_f64;
        while u < 15.0 {
            let exact = hertz_shape_exact((0.5 * u).exp(), (-0.5 * u).exp()).unwrap();
            let t = table.at_log_ratio(u);
            for (a, b) in [
                (t.eps_x, exact.eps_x),
                (t.a_over_b, exact.a_over_b),
                (t.p0_coeff, exact.p0_coeff),
            ] {
                assert!(((a - b) / b).abs() < 1e-7, "u = {u}: {a} vs {b}");
                worst = worst.max(((a - b) / b).abs());
            }
            u += 0.0137;
        }
        // Interpolating the values themselves reaches 8e−10 on this sweep.
        assert!(worst < 1e-8, "{worst}");
    }

    #[test]
    fn shape_reproduces_hertz_peak_pressure() {
        // p0 = E* √(δ(A+B)) P against hertz_from_approach, to round-off.
        let (a, b, delta, e_star) = (0.9, 3.7, 6.0e-5, 1.15e11);
        let exact = hertz_from_approach(a, b, delta, e_star).unwrap();
        let s = hertz_shape_exact(a, b).unwrap();
        let p0 = e_star * (delta * (a + b)).sqrt() * s.p0_coeff;
        assert!(((p0 - exact.p0) / exact.p0).abs() < 1e-12);
        assert!((s.eps_x - a * exact.a * exact.a / delta).abs() < 1e-12);
        assert!((s.a_over_b - exact.a / exact.b).abs() < 1e-12);
        // Circle: ε = 1/2, P = 2/π.
        let c = hertz_shape_exact(2.0, 2.0).unwrap();
        assert!((c.eps_x - 0.5).abs() < 1e-12);
        assert!((c.p0_coeff - 2.0 / std::f64::consts::PI).abs() < 1e-12);
    }

    #[test]
    fn table_patch_matches_hertz_from_approach() {
        // Within the table's 1e−7 (a, b, p0; N ∝ a b p0 compounds three: 3e−7), the exact
        // solver outside the table's range and at δ = 0, and the same errors.
        let table = HertzShapeTable::new();
        let e_star = 1.15e11;
        for (a, b) in [
            (1.087, 0.37),
            (0.9, 3.7),
            (2.0, 2.0),
            (1.0, 1e-3),
            (1.0, 1e-9),
        ] {
            for delta in [0.0, 1e-6, 6e-5] {
                let t = table.patch(a, b, delta, e_star).unwrap();
                let x = hertz_from_approach(a, b, delta, e_star).unwrap();
                for (p, q, tol) in [
                    (t.a, x.a, 1e-7),
                    (t.b, x.b, 2e-7),
                    (t.p0, x.p0, 1e-7),
                    (t.normal_force, x.normal_force, 3e-7),
                ] {
                    assert!(
                        (p - q).abs() <= tol * q.abs(),
                        "A {a} B {b} δ {delta}: {p} vs {q}"
                    );
                }
            }
        }
        assert!(table.patch(1.0, -1.0, 1e-5, e_star).is_err());
        assert!(table.patch(1.0, 1.0, -1e-5, e_star).is_err());
    }

    #[test]
    fn lookup_rejects_non_positive_curvature() {
        let table = HertzShapeTable::new();
        assert_eq!(table.lookup(1.0, 0.0).unwrap_err().name, "B");
        assert_eq!(table.lookup(f64::NAN, 1.0).unwrap_err().name, "A");
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
