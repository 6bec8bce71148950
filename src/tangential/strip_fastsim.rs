//! FASTSIM on the strips of a non-elliptic patch: the actual pressure as the traction bound,
//! per-strip flexibilities and per-strip creepages.
//!
//! Papers: J.J. Kalker (1982), "A fast algorithm for the simplified theory of rolling contact",
//! *Vehicle System Dynamics* 11:1–13 (FASTSIM); W. Kik, J. Piotrowski (1996) and Piotrowski & Kik
//! (2008) (equivalent ellipse, actual pressure as the bound); J.-B. Ayasse, H. Chollet (2005),
//! "Determination of the wheel rail contact patch in semi-Hertzian conditions", *VSD* 43(3)
//! 161–172 (STRIPES: local ellipses and per-strip creepages on a non-planar patch); M. Sh.
//! Sichani, R. Enblom, M. Berg, *Wear* 314 (2014) 111–117 (the comparison of the strip models).
//! Equations: docs/theory.md §4.1 (F1), §4.2 (F3), §4.3, §4.7, §4.8 and §5.8.
//!
//! # Equations
//!
//! Strip j of a patch (centre s_j, width Δs_j, lever y_j = s_j − s_ref from the patch's reference
//! point in the contact plane) is in contact over x ∈ [x_c,j − x_l,j, x_c,j + x_l,j] with the
//! normal model's pressure p_j(x) = p_max,j √(1 − ((x − x_c,j)/x_l,j)²) (elliptic in x per strip).
//! It is cut into `nx` equal elements Δx_j = 2x_l,j/nx, marched from the leading edge
//! x_c,j + x_l,j (material enters there, docs/conventions.md) to the trailing edge (F3):
//!
//! ```text
//!   p_x ← p_x − (ξ_j/L1,j − φ_ref y_j/L3,j) Δx_j
//!   p_y ← p_y − (η_j/L2,j + φ_j (x + Δx_j/6)/L3,j) Δx_j
//!   |p| > μ p_j(x)  ⇒  p ← p μ p_j(x)/|p|           (slip, direction kept)
//! ```
//!
//! with (L1, L2, L3)_j the strip's flexibilities (F1 of the equivalent ellipse or of the strip's
//! local ellipse — the caller's choice, docs/theory.md §4.7) and (ξ_j, η_j, φ_j, φ_ref) its
//! creepages:
//!
//! * **planar patch** (one contact angle and one spin, as the half-space theory assumes): the
//!   patch's (ξ, η, φ) on every strip and φ_ref = φ — exactly Kalker's F3 with the spin's lever
//!   y_j measured from the reference point;
//! * **non-planar patch** (docs/theory.md §5.8, STRIPES' treatment): φ_j and η_j are the
//!   strip's own, from the wheelset kinematics at its contact point in its own axes; the
//!   longitudinal rigid slip of the strip, ξ_kin,j, is split as ξ_j − φ_ref y_j with φ_ref the
//!   patch's spin, so that a flat patch (constant contact angle, ξ_kin,j = ξ − φ y_j) gives back
//!   the planar result exactly, and only the curvature of the surface changes the strips' slip.
//!
//! The march follows the elliptic FASTSIM's [`MarchScheme`]: by default (`Midpoint`) the leading
//! element steps Δx/2 from the strip's edge and the spin term sits at each step's midpoint
//! (second order); `Contact` takes full steps with the spin term at Δx/6. Per strip the sums give F_x,j = Σ p_x Δx_j Δs_j, F_y,j likewise and
//! Σ x p_y Δx_j Δs_j; the patch's spin moment about its reference point (planar lever arms) is
//! M_z = Σ_j (Σ x p_y ΔA − y_j F_x,j). Frictional power: as `crate::tangential::fastsim`, the
//! work of the tractions on each strip's rigid slip, P = −V Σ_j [(ξ_j − φ_ref y_j) F_x,j +
//! η_j F_y,j + φ_j Σ x p_y ΔA]; the element slips (FASTSIM's slip displacement
//! S = (L1 (p − p*)_x, L2 (p − p*)_y), p* the adhesion trial, or FaStrip's) are scaled to it.
//!
//! # Choices
//!
//! * A fixed element count per strip (docs/theory.md §4.8) rather than
//!   a uniform Δx over the patch: every strip — also the short ones at the patch ends — is
//!   resolved equally, the cost is `nx` × strips in contact, and the first-order overshoot of
//!   full adhesion (≈ 1/nx, `crate::tangential::fastsim` header) is the same on every strip.
//! * The bound is sampled at element centres, like `crate::tangential::fastsim`.
//!
//! # Known limits
//!
//! Kalker's simplified theory (Winkler bed): no shear coupling between strips, which Sichani et al.
//! (2014) names as the missing piece where B ≤ 0 at a patch end; first-order in Δx. Steady rolling,
//! constant μ. No heap allocation in [`StripFastsim::solve`]: the traction field buffers are
//! sized in [`StripFastsim::new`].

use crate::error::InputError;
use crate::geometry::strips::MAX_STRIPS;
use crate::tangential::fastrip::{semi_ellipse_midpoint_ratio, StripGrid};
use crate::tangential::fastsim::{
    centre_out, slip_scale, strip_outs, Creepage, FastsimResult, FrictionElement, FrictionStrip,
    MarchScheme, StripMarch, StripOut, StripPower, StripSums, MAX_GROUP,
};
use crate::tangential::kalker::CreepCoefficients;
use crate::tangential::strip_coefficients::{CouplingStrip, StripCoefficients};
use std::sync::Arc;

/// Largest element count per strip (the FMU's `nx` range).
pub const MAX_ELEMENTS: usize = 1000;

/// One strip as the tangential solver sees it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TangentialStrip {
    /// Lateral lever y_j of the strip centre from the patch's reference point, in the contact
    /// plane, positive along the patch's e_y [m].
    pub lever: f64,
    /// Strip width Δs_j [m].
    pub width: f64,
    /// Centre of the strip's contact along x [m] (the yaw lead x_c,j).
    pub x_c: f64,
    /// Half-length x_l,j [m]; 0 means out of contact.
    pub half_length: f64,
    /// Peak pressure p_max,j of the strip's semi-ellipse [Pa].
    pub pmax: f64,
    /// Flexibilities [L1, L2, L3] [m/Pa].
    pub flexibility: [f64; 3],
    /// The strip's creepages (ξ_j, η_j, φ_j) of the module header.
    pub creepage: Creepage,
    /// The patch's reference spin φ_ref [1/m] (the lever term's spin).
    pub reference_spin: f64,
}

/// Result of one patch (forces of the rail on the wheel, each strip in its own axes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StripFastsimResult {
    /// Σ F_x,j [N].
    pub fx: f64,
    /// Σ F_y,j [N] (each along its own strip's lateral axis).
    pub fy: f64,
    /// Spin moment about the reference point [N m] (planar lever arms).
    pub mz: f64,
    /// Adhesion elements / contact elements [-].
    pub adhesion_fraction: f64,
    /// Frictional power ≥ 0 [W].
    pub frictional_power: f64,
    /// Largest |tangential traction| [Pa].
    pub max_traction: f64,
}

impl From<&FastsimResult> for StripFastsimResult {
    /// The same quantities of FASTSIM on one ellipse.
    fn from(t: &FastsimResult) -> Self {
        Self {
            fx: t.fx,
            fy: t.fy,
            mz: t.mz,
            adhesion_fraction: t.adhesion_fraction,
            frictional_power: t.frictional_power,
            max_traction: t.max_traction,
        }
    }
}

/// One strip's sums (forces in N in the strip's own axes).
#[derive(Debug, Clone, Copy, Default)]
struct StripTotals {
    /// FASTSIM's march sums of the strip (zero after FaStrip).
    march_power: StripPower,
    fx: f64,
    fy: f64,
    /// Σ x p_y ΔA [N m].
    x_fy: f64,
    /// Frictional power per unit rolling speed [N].
    power_per_speed: f64,
    max_traction: f64,
    n_elements: usize,
    n_adhesion: usize,
}

/// Traction in one element of the last solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StripElementTraction {
    /// Strip index.
    pub strip: usize,
    /// Element centre along x [m].
    pub x: f64,
    /// Tangential traction on the wheel along x and along the strip's lateral axis [Pa].
    pub px: f64,
    pub py: f64,
    /// Normal pressure (the bound over μ) [Pa].
    pub pn: f64,
    /// Whether the element slips.
    pub slipping: bool,
}

/// Range of FaStrip's per-strip factors C_j/C from the coupled coefficients
/// (`crate::tangential::strip_coefficients`). On the built-in profiles' tread patches (−3…+4 mm,
/// ANALYN and coupled strips) they lie within 0.15–1.9, the lowest on the short strips at a
/// patch's lateral ends, which carry little force (clamping them changes the validated creep
/// curves by < 1e−4 μN); in flange-root and flange contact (+5…+7 mm), where a strip lies beside
/// one twice as long, the one-point collocation gives factors from below zero to 7. The clamp
/// keeps those from the force, continuously: the load balance's creep iteration needs a map
/// without jumps.
const GAIN_MIN: f64 = 0.25;
/// See [`GAIN_MIN`].
const GAIN_MAX: f64 = 4.0;

/// FASTSIM over strips with preallocated buffers.
#[derive(Debug, Clone)]
pub struct StripFastsim {
    nx: usize,
    /// Integration of the rigid slip along a strip.
    scheme: MarchScheme,
    /// Per-strip force of the last solve, in the strip's own axes [N].
    strip_fx: Vec<f64>,
    strip_fy: Vec<f64>,
    /// Element tractions, row-major by strip, element 0 at the trailing edge [Pa].
    px: Vec<f64>,
    py: Vec<f64>,
    slipping: Vec<bool>,
    /// FaStrip's frictional power density |q| |S| per element [N/m] (its solves only).
    power: Vec<f64>,
    /// FASTSIM's slip displacement |S| per element [m], where recorded
    /// ([`StripFastsim::record_slips`]; empty otherwise).
    slip: Vec<f64>,
    /// Whether the last solve was FaStrip's ([`StripFastsim::friction_elements`]).
    last_fastrip: bool,
    /// Factor on the last solve's element slips that makes them dissipate the reported
    /// frictional power (`crate::tangential::fastsim::slip_scale`).
    slip_scale: f64,
    /// Per strip of the last solve: its march and x step (`None`: no traction) and its width,
    /// for [`StripFastsim::friction_elements`].
    marches: Vec<Option<(StripMarch, f64)>>,
    widths: Vec<f64>,
    levers: Vec<f64>,
    /// Strip geometry of the last solve (for [`StripFastsim::tractions`]).
    geometry: Vec<(f64, f64, f64)>,
    /// Per-strip sums of the last solve.
    totals: Vec<StripTotals>,
    n_strips: usize,
    /// The bound's shape √(1 − u_i²) at the element centres u_i ∈ (−1, 1), the same for every
    /// strip (precomputed: no square root per element in the march).
    shape: Vec<f64>,
    /// [`semi_ellipse_midpoint_ratio`] of `nx` (FaStrip's bound is divided by it).
    midpoint_ratio: f64,
    /// The largest of `shape`.
    top_shape: f64,
    /// FaStrip's element centres and semi-ellipse on a strip of `nx` elements.
    fastrip_grid: Arc<StripGrid>,
    /// The strip-wise creep coefficients' solver and its strips (sized by
    /// [`StripFastsim::reserve_coupled`]).
    coupling: StripCoefficients,
    coupling_strips: Vec<CouplingStrip>,
    /// FaStrip's per-strip factors (C11_j/C11, C22_j/C22) on its starred creepages (1 without
    /// the coupled coefficients).
    gains: Vec<(f64, f64)>,
}

/// The bound's shape √(1 − u_i²) at the element centres of a strip of `nx` elements, scaled so
/// that its midpoint sum equals the semi-ellipse's integral π/2 (the strip's load): full sliding
/// then gives exactly μ × the strip's normal force, where the plain midpoint sum is +0.34 % high
/// at 20 elements (+0.12 % at 40): `ratio` = [`semi_ellipse_midpoint_ratio`] of `nx`.
fn bound_shape(nx: usize, ratio: f64) -> Vec<f64> {
    (0..nx)
        .map(|i| {
            let u = element_centre(i, nx);
            (1.0 - u * u).max(0.0).sqrt() / ratio
        })
        .collect()
}

impl StripFastsim {
    /// Buffers for up to [`MAX_STRIPS`] strips of `nx` ∈ [1, [`MAX_ELEMENTS`]] elements.
    pub fn new(nx: usize, scheme: MarchScheme) -> Result<Self, InputError> {
        if !(1..=MAX_ELEMENTS).contains(&nx) {
            return Err(InputError::new("nx", nx as f64, "[1, 1000]"));
        }
        let midpoint_ratio = semi_ellipse_midpoint_ratio(nx);
        Ok(Self {
            nx,
            scheme,
            slip_scale: 1.0,
            strip_fx: vec![0.0; MAX_STRIPS],
            strip_fy: vec![0.0; MAX_STRIPS],
            px: vec![0.0; MAX_STRIPS * nx],
            py: vec![0.0; MAX_STRIPS * nx],
            slipping: vec![false; MAX_STRIPS * nx],
            power: vec![0.0; MAX_STRIPS * nx],
            slip: Vec::new(),
            last_fastrip: false,
            marches: vec![None; MAX_STRIPS],
            widths: vec![0.0; MAX_STRIPS],
            levers: vec![0.0; MAX_STRIPS],
            geometry: vec![(0.0, 0.0, 0.0); MAX_STRIPS],
            totals: vec![StripTotals::default(); MAX_STRIPS],
            n_strips: 0,
            shape: bound_shape(nx, midpoint_ratio),
            top_shape: bound_shape(nx, midpoint_ratio)
                .into_iter()
                .fold(0.0, f64::max),
            midpoint_ratio,
            fastrip_grid: Arc::new(StripGrid::new(nx)),
            coupling: StripCoefficients::default(),
            coupling_strips: Vec::new(),
            gains: vec![(1.0, 1.0); MAX_STRIPS],
        })
    }

    /// Keeps each element's slip from every FASTSIM solve on (for
    /// [`StripFastsim::friction_elements`], which then needs no replay of the march): one more
    /// store per element.
    pub fn record_slips(&mut self) {
        self.slip = vec![0.0; self.px.len()];
    }

    /// Sizes the buffers of FaStrip's coupled coefficients for patches of up to `n_strips`
    /// strips (and builds their kernel table), so that [`Self::solve_fastrip`] with `coupled`
    /// does not allocate.
    pub fn reserve_coupled(&mut self, n_strips: usize) {
        let n = n_strips.min(MAX_STRIPS);
        self.coupling = StripCoefficients::with_capacity(n);
        self.coupling_strips = Vec::with_capacity(n);
    }

    /// Solves the patch made of `strips` (at most [`MAX_STRIPS`]; strips out of contact are
    /// skipped) with friction `mu` and rolling speed `speed` ≥ 0 [m/s] (scales the power only).
    /// Strips with non-finite or non-positive flexibilities carry no traction. No allocation.
    pub fn solve(&mut self, strips: &[TangentialStrip], mu: f64, speed: f64) -> StripFastsimResult {
        let nx = self.nx;
        // Element rows are cleared only for strips that carry nothing; the march writes every
        // element of the others.
        let n = self.take_geometry(strips, mu);
        self.last_fastrip = false;
        let scheme = self.scheme;
        let march_of = |strip: &TangentialStrip| strip_march(strip, nx, scheme, mu);
        let totals = |strip: &TangentialStrip, march: &StripMarch, sums: &StripSums| {
            let area = march.dx * strip.width;
            StripTotals {
                fx: sums.sum_px * area,
                fy: sums.sum_py * area,
                x_fy: sums.sum_x_py * area,
                power_per_speed: sums.sum_power * strip.width,
                march_power: StripPower::of(sums),
                max_traction: sums.max_traction_sq.sqrt(),
                n_elements: nx,
                n_adhesion: sums.n_adhesion,
            }
        };
        // Strips in contact marched in groups (`StripMarch::run_group`: independent chains in
        // SIMD lanes) of MAX_GROUP, the rest in a group of four, one of two and alone.
        let mut group = [(0usize, StripMarch::default(), 0.0); MAX_GROUP];
        let mut waiting = 0;
        for (j, strip) in strips[..n].iter().enumerate() {
            if let Some((march, step_x)) = march_of(strip) {
                group[waiting] = (j, march, step_x);
                waiting += 1;
            } else {
                self.clear_rows(j..j + 1);
            }
            if waiting == MAX_GROUP {
                self.march_group(&group, strips, &totals);
                waiting = 0;
            }
        }
        let mut done = 0;
        for size in [4, 2] {
            if waiting - done >= size {
                self.march_group(&group[done..done + size], strips, &totals);
                done += size;
            }
        }
        if done < waiting {
            let (i, march, step_x) = group[done];
            let row = i * nx..(i + 1) * nx;
            let rows = std::slice::from_ref(&row);
            let field = (&mut self.px[..], &mut self.py[..], &mut self.slipping[..]);
            let [mut out] = strip_outs(field, &mut self.slip, rows);
            let sums = march.run(step_x, &self.shape, &mut out);
            self.totals[i] = totals(&strips[i], &march, &sums);
        }
        self.summarize(strips, speed)
    }

    /// FaStrip (`crate::tangential::fastrip`, Sichani et al. 2016) on the same strips: the strip-theory
    /// tractions in each strip's adhesion zone, μ p in the FASTSIM pass's direction in its slip
    /// zone, with FS1's dimensionless creepages from the patch's equivalent ellipse `equivalent`
    /// (its Kalker coefficients and peak pressure 3N/(2π a_e b_e)) and each strip's own creepages
    /// (the strip's spin also in the lever term). With `coupled`, strip j's starred ξ and φ
    /// are scaled by C11_j/C11 and its η by C22_j/C22, its own coefficients from the strips
    /// coupled through the half-space (`crate::tangential::strip_coefficients`; the ratios
    /// clamped to [0.25, 4], the ellipse's where that system cannot be solved). Same outputs
    /// and buffers as [`StripFastsim::solve`]; no allocation (with `coupled`, after
    /// [`StripFastsim::reserve_coupled`]).
    pub fn solve_fastrip(
        &mut self,
        strips: &[TangentialStrip],
        equivalent: &crate::tangential::patch::EquivalentEllipse,
        speed: f64,
        coupled: bool,
    ) -> StripFastsimResult {
        use crate::tangential::fastrip::{
            solve_strip_on_grid, FastripScales, FastripStrip, StripPressure, StripProblem,
            ZoneSampling,
        };
        let nx = self.nx;
        let ratio = self.midpoint_ratio;
        let e = &equivalent.contact;
        let (a_e, b_e, g, nu, mu) = (e.a, e.b, e.shear_modulus, e.nu, e.mu);
        let (coefficients, p0_e) = (&equivalent.coefficients, equivalent.peak_pressure());
        // FS1's factors once per patch; each strip's starred creepages by multiplication.
        let patch_scales =
            FastripScales::new(a_e, b_e, coefficients, g, nu, mu, p0_e, 0.0, 0.0, 0.0);
        // A shared handle on the grid (no allocation), so that the solve can borrow `self`.
        let grid = Arc::clone(&self.fastrip_grid);
        let n = strips.len().min(MAX_STRIPS);
        if coupled {
            self.coupled_gains(&strips[..n], nu, coefficients);
        } else {
            self.gains[..n].fill((1.0, 1.0));
        }
        // FaStrip's strip theory takes the longitudinal rigid slip as ξ* − φ* y/a with the
        // strip's own φ; the lever term of the module header's equations is the reference
        // spin's. ξ is shifted so that ξ* − φ_j* y/a = ξ_j* − φ_ref* y/a (the starred factors
        // are linear): on a planar patch (φ_j = φ_ref) nothing changes. The slip zone's FASTSIM
        // pass then sees the lever through 9π²/(128(1 − ν)) L3/L1 ≈ 0.96 of its own L3 term
        // (both from the ellipse's coefficients), a second-order difference in its direction.
        let lever_factor = patch_scales.phi_star_per_phi / (a_e * patch_scales.xi_star_per_xi);
        let k_lever = |strip: &TangentialStrip| {
            let k = strip.creepage;
            let shift = (k.phi - strip.reference_spin) * strip.lever * lever_factor;
            if shift.is_finite() {
                k.xi + shift
            } else {
                k.xi
            }
        };
        // `run` visits the strips in order: the gains go by a running index.
        let gains = std::mem::take(&mut self.gains);
        let mut next = gains.iter();
        let result = self.run(
            strips,
            speed,
            |strip, px_row, py_row, slip_row, power_row| {
                let (gain_x, gain_y) = next.next().copied().unwrap_or((1.0, 1.0));
                if !(strip.half_length > 0.0 && strip.pmax > 0.0 && strip.width > 0.0) {
                    return None;
                }
                let k = Creepage {
                    xi: k_lever(strip),
                    ..strip.creepage
                };
                let scales =
                    patch_scales.with_creepage(k.xi * gain_x, k.eta * gain_y, k.phi * gain_x);
                let strip_input = FastripStrip {
                    y: strip.lever,
                    x_c: strip.x_c,
                    half_length: strip.half_length,
                    pmax: strip.pmax,
                };
                let (flex, w) = (strip.flexibility, strip.width);
                // The bound sums to the strip's load on its elements, as in `fastrip::solve_strip`.
                let bound = StripPressure::scaled(&strip_input, ratio);
                let problem = StripProblem {
                    strip: &strip_input,
                    pressure: bound,
                    scales: &scales,
                    mu,
                    flex,
                    creepage: [k.xi, k.eta, k.phi],
                    sampling: ZoneSampling::ExactZone,
                };
                let sums = solve_strip_on_grid(
                    &problem,
                    &grid,
                    &mut px_row[..nx],
                    &mut py_row[..nx],
                    &mut slip_row[..nx],
                    &mut power_row[..nx],
                );
                // FaStrip's sums are per unit strip width.
                Some(StripTotals {
                    fx: sums.fx * w,
                    fy: sums.fy * w,
                    x_fy: sums.x_fy * w,
                    power_per_speed: sums.power_density * w,
                    march_power: StripPower::default(),
                    max_traction: sums.max_traction,
                    n_elements: sums.n_elements,
                    n_adhesion: sums.n_adhesion,
                })
            },
        );
        self.gains = gains;
        self.last_fastrip = true;
        result
    }

    /// Fills `gains` with (C11_j/C11, C22_j/C22) of the strips coupled through the half-space
    /// (Poisson ratio `nu`) against the ellipse's `coefficients`, clamped to [[`GAIN_MIN`],
    /// [`GAIN_MAX`]]; 1 where a ratio is NaN, and for every strip if the coupled system fails.
    fn coupled_gains(
        &mut self,
        strips: &[TangentialStrip],
        nu: f64,
        coefficients: &CreepCoefficients,
    ) {
        self.coupling_strips.clear();
        self.coupling_strips
            .extend(strips.iter().map(|t| CouplingStrip {
                s: t.lever,
                width: t.width,
                x_c: t.x_c,
                half_length: t.half_length,
            }));
        let n = strips.len();
        let out = &mut self.gains[..n];
        if !self.coupling.solve(&self.coupling_strips, nu, out) {
            out.fill((1.0, 1.0));
            return;
        }
        // Clamped (continuously) into [GAIN_MIN, GAIN_MAX]: a strip beside a much longer one
        // can get a coefficient near or below zero from the single collocation point.
        let gain = |r: f64| {
            if r.is_nan() {
                1.0
            } else {
                r.clamp(GAIN_MIN, GAIN_MAX)
            }
        };
        for g in out.iter_mut() {
            *g = (gain(g.0 / coefficients.c11), gain(g.1 / coefficients.c22));
        }
    }

    /// Marches the strips of `group` (strip index, march, x step; 2, 4 or [`MAX_GROUP`] of
    /// them, in increasing strip order) together and stores their totals.
    fn march_group(
        &mut self,
        group: &[(usize, StripMarch, f64)],
        strips: &[TangentialStrip],
        totals: &impl Fn(&TangentialStrip, &StripMarch, &StripSums) -> StripTotals,
    ) {
        let nx = self.nx;
        let n = group.len();
        let mut rows: [std::ops::Range<usize>; MAX_GROUP] = Default::default();
        for (r, &(j, ..)) in rows.iter_mut().zip(group) {
            *r = j * nx..(j + 1) * nx;
        }
        let field = (&mut self.px[..], &mut self.py[..], &mut self.slipping[..]);
        let mut out: [StripOut<'_>; MAX_GROUP] = strip_outs(field, &mut self.slip, &rows[..n]);
        let mut marches = [&group[0].1; MAX_GROUP];
        let mut step_x = [0.0; MAX_GROUP];
        for (k, (_, march, step)) in group.iter().enumerate() {
            marches[k] = march;
            step_x[k] = *step;
        }
        let sums = StripMarch::run_group(&marches[..n], &step_x[..n], &self.shape, &mut out[..n]);
        for ((j, march, _), s) in group.iter().zip(&sums) {
            self.totals[*j] = totals(&strips[*j], march, s);
        }
    }

    /// The bookkeeping of a solver that solves one strip at a time: lets `solve_one` fill each
    /// strip's row (every element of it) or return `None` for a strip that carries nothing (its
    /// row is then cleared) and sums the patch.
    fn run(
        &mut self,
        strips: &[TangentialStrip],
        speed: f64,
        mut solve_one: impl FnMut(
            &TangentialStrip,
            &mut [f64],
            &mut [f64],
            &mut [bool],
            &mut [f64],
        ) -> Option<StripTotals>,
    ) -> StripFastsimResult {
        let n = self.take_geometry(strips, 1.0);
        let nx = self.nx;
        for (j, strip) in strips[..n].iter().enumerate() {
            let row = j * nx..(j + 1) * nx;
            match solve_one(
                strip,
                &mut self.px[row.clone()],
                &mut self.py[row.clone()],
                &mut self.slipping[row.clone()],
                &mut self.power[row],
            ) {
                Some(t) => self.totals[j] = t,
                None => self.clear_rows(j..j + 1),
            }
        }
        self.summarize(strips, speed)
    }

    /// Takes the geometry of `strips` (at most [`MAX_STRIPS`]: returns how many) and clears
    /// their totals (not their element rows).
    /// `mu`: the friction of the marches kept for [`StripFastsim::friction_elements`].
    fn take_geometry(&mut self, strips: &[TangentialStrip], mu: f64) -> usize {
        let n = strips.len().min(MAX_STRIPS);
        self.n_strips = n;
        for (j, strip) in strips[..n].iter().enumerate() {
            self.geometry[j] = (strip.x_c, strip.half_length, strip.pmax);
            self.marches[j] = strip_march(strip, self.nx, self.scheme, mu);
            self.widths[j] = strip.width;
            self.levers[j] = strip.lever;
        }
        self.totals[..n].fill(StripTotals::default());
        n
    }

    /// Zeroes the element rows of the strips `rows`.
    fn clear_rows(&mut self, rows: std::ops::Range<usize>) {
        let elements = rows.start * self.nx..rows.end * self.nx;
        self.px[elements.clone()].fill(0.0);
        self.py[elements.clone()].fill(0.0);
        self.slipping[elements.clone()].fill(false);
        self.power[elements].fill(0.0);
    }

    /// The patch's sums over the strips' totals (in strip order), stored per strip as well.
    fn summarize(&mut self, strips: &[TangentialStrip], speed: f64) -> StripFastsimResult {
        let n = self.n_strips;
        let mut out = StripFastsimResult::default();
        let (mut n_contact, mut n_adhesion) = (0usize, 0usize);
        let mut power = 0.0;
        // Σ q·w ΔA with each strip's rigid slip w = (ξ_j − φ_ref y_j, η_j + φ_j x) [N].
        let mut work = 0.0;
        for (j, strip) in strips[..n].iter().enumerate() {
            let t = self.totals[j];
            self.strip_fx[j] = t.fx;
            self.strip_fy[j] = t.fy;
            out.fx += t.fx;
            out.fy += t.fy;
            out.mz += t.x_fy - strip.lever * t.fx;
            let k = strip.creepage;
            work +=
                (k.xi - strip.reference_spin * strip.lever) * t.fx + k.eta * t.fy + k.phi * t.x_fy;
            power += t.power_per_speed;
            out.max_traction = out.max_traction.max(t.max_traction);
            n_contact += t.n_elements;
            n_adhesion += t.n_adhesion;
        }
        out.adhesion_fraction = if n_contact > 0 {
            n_adhesion as f64 / n_contact as f64
        } else {
            0.0
        };
        let raw_power = speed * power;
        let slip_power = if raw_power > 0.0 {
            raw_power.min(f64::MAX)
        } else {
            0.0
        };
        // The work on the rigid slip (`crate::tangential::fastsim`'s header).
        let rigid = -speed * work;
        out.frictional_power = if rigid > 0.0 {
            rigid.min(f64::MAX)
        } else {
            0.0
        };
        self.slip_scale = slip_scale(out.frictional_power, slip_power);
        out
    }

    /// Force of strip `j` in its own axes after the last solve: (F_x,j, F_y,j) [N].
    pub fn strip_force(&self, j: usize) -> (f64, f64) {
        if j < self.n_strips {
            (self.strip_fx[j], self.strip_fy[j])
        } else {
            (0.0, 0.0)
        }
    }

    /// Element tractions of the last solve (strips in contact only).
    pub fn tractions(&self) -> impl Iterator<Item = StripElementTraction> + '_ {
        let nx = self.nx;
        (0..self.n_strips).flat_map(move |j| {
            let (x_c, half_length, pmax) = self.geometry[j];
            let n = if half_length > 0.0 && pmax > 0.0 {
                nx
            } else {
                0
            };
            (0..n).map(move |i| {
                let u = element_centre(i, nx);
                let e = j * nx + i;
                StripElementTraction {
                    strip: j,
                    x: x_c + u * half_length,
                    px: self.px[e],
                    py: self.py[e],
                    pn: pmax * (1.0 - u * u).max(0.0).sqrt(),
                    slipping: self.slipping[e],
                }
            })
        })
    }
}

impl StripFastsim {
    /// The strips of the last solve as the damage models see them (`visit(strip, field)`,
    /// [`FrictionStrip`]; the lateral is the strip's lever); `false` (nothing visited) after a
    /// FaStrip solve or where FASTSIM's slips are not recorded (use
    /// [`StripFastsim::friction_elements`]).
    pub fn friction_strips(&self, mut visit: impl FnMut(usize, &FrictionStrip)) -> bool {
        if self.last_fastrip || self.slip.is_empty() {
            return false;
        }
        let nx = self.nx;
        for j in centre_out(self.n_strips) {
            let Some((march, _)) = self.marches[j] else {
                continue;
            };
            let row = j * nx..(j + 1) * nx;
            visit(
                j,
                &FrictionStrip {
                    lateral: self.levers[j],
                    area: march.dx * self.widths[j],
                    pressure_scale: self.geometry[j].2,
                    bound_scale: march.bound_scale,
                    slip_scale: self.slip_scale / march.dx,
                    shape: &self.shape,
                    slip: &self.slip[row.clone()],
                    px: &self.px[row.clone()],
                    py: &self.py[row],
                    top_shape: self.top_shape,
                    power: self.totals[j].march_power,
                },
            );
        }
        true
    }

    /// The elements in contact of the last solve as the damage models see them
    /// (`visit(strip, element)`, [`FrictionElement`]; the lateral is the strip's lever):
    /// FASTSIM's slip replayed from its field ([`StripMarch::slips`]), FaStrip's from its power
    /// density (|s| = |q| |S|/(|q| Δx)).
    pub fn friction_elements(&self, mut visit: impl FnMut(usize, &FrictionElement)) {
        let nx = self.nx;
        for j in 0..self.n_strips {
            let Some((march, step_x)) = self.marches[j] else {
                continue;
            };
            let row = j * nx..(j + 1) * nx;
            let (px, py) = (&self.px[row.clone()], &self.py[row.clone()]);
            let area = march.dx * self.widths[j];
            let pmax = self.geometry[j].2;
            let lateral = self.levers[j];
            let element = |i: usize, traction_sq: f64, bound: f64, slip: f64| FrictionElement {
                lateral,
                area,
                pressure: pmax * self.shape[i],
                traction_sq,
                bound,
                slip,
            };
            if self.last_fastrip {
                // FaStrip's adhesion-zone tractions are not FASTSIM's: no bound is assumed.
                for (i, &density) in self.power[row].iter().enumerate() {
                    let traction_sq = px[i] * px[i] + py[i] * py[i];
                    let slip = if traction_sq > 0.0 {
                        density * self.slip_scale / (traction_sq.sqrt() * march.dx)
                    } else {
                        0.0
                    };
                    visit(j, &element(i, traction_sq, f64::INFINITY, slip));
                }
            } else if !self.slip.is_empty() {
                // Recorded in the march: |s| = |S|/Δx.
                let per_length = self.slip_scale / march.dx;
                for (i, &slip) in self.slip[row].iter().enumerate() {
                    let traction_sq = px[i] * px[i] + py[i] * py[i];
                    let bound = march.bound_scale * self.shape[i];
                    visit(j, &element(i, traction_sq, bound, slip * per_length));
                }
            } else {
                let field = (px, py, &self.slipping[row]);
                march.slips(step_x, &self.shape, field, |i, traction_sq, bound, slip| {
                    visit(j, &element(i, traction_sq, bound, slip * self.slip_scale))
                });
            }
        }
    }
}

/// The F3 march of `strip` on `nx` elements with `scheme` and friction `mu` (module header) and
/// its x step (ξ_j/L1 − φ_ref y_j/L3)Δx; `None` for a strip that carries no traction
/// (non-finite or non-positive length, pressure, width or flexibility).
fn strip_march(
    strip: &TangentialStrip,
    nx: usize,
    scheme: MarchScheme,
    mu: f64,
) -> Option<(StripMarch, f64)> {
    let [l1, l2, l3] = strip.flexibility;
    let usable = |v: f64| v.is_finite() && v > 0.0;
    if !(usable(strip.half_length)
        && usable(strip.pmax)
        && usable(strip.width)
        && usable(l1)
        && usable(l2)
        && usable(l3))
    {
        return None;
    }
    let dx = 2.0 * strip.half_length / nx as f64;
    let k = strip.creepage;
    let march = StripMarch {
        x_first: strip.x_c - strip.half_length + 0.5 * dx,
        dx,
        step_y_at_zero: k.eta / l2 * dx,
        step_y_per_x: k.phi / l3 * dx,
        spin_offset: scheme.spin_offset_fraction() * dx,
        // The elements tile the strip: the leading centre lies Δx/2 behind its edge.
        lead_fraction: scheme.lead_fraction(0.5),
        bound_scale: mu * strip.pmax,
        slip_flexibility: [l1, l2],
    };
    let step_x = (k.xi / l1 - strip.reference_spin * strip.lever / l3) * dx;
    Some((march, step_x))
}

/// Centre of element `i` of `n` equal elements on (−1, 1).
fn element_centre(i: usize, n: usize) -> f64 {
    -1.0 + (2.0 * i as f64 + 1.0) / n as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tangential::fastsim::CONTACT_EXAMPLE;
    use crate::tangential::fastsim::{three_flexibilities, Fastsim, FastsimSettings};
    use crate::tangential::kalker::creep_coefficients;
    use std::f64::consts::PI;

    // CONTACT's `fastsim` example ellipse (docs/theory.md §4.6) in SI units.
    use crate::tangential::fastsim::contact_example::{A, B, G, MU, N, NU};

    /// The Hertz ellipse cut into `ny` strips with its own F1 flexibilities and planar creepages.
    fn hertz_strips(ny: usize, creepage: Creepage) -> Vec<TangentialStrip> {
        let c = creep_coefficients(A, B, NU).unwrap();
        let l = three_flexibilities(A, B, G, &c);
        let p0 = 3.0 * N / (2.0 * PI * A * B);
        let dy = 2.0 * B / ny as f64;
        (0..ny)
            .map(|j| {
                let y = -B + (j as f64 + 0.5) * dy;
                let w = (1.0 - (y / B).powi(2)).sqrt();
                TangentialStrip {
                    lever: y,
                    width: dy,
                    x_c: 0.0,
                    half_length: A * w,
                    pmax: p0 * w,
                    flexibility: l,
                    creepage,
                    reference_spin: creepage.phi,
                }
            })
            .collect()
    }

    fn solve(ny: usize, nx: usize, creepage: Creepage) -> StripFastsimResult {
        let mut s = StripFastsim::new(nx, MarchScheme::Contact).unwrap();
        s.solve(&hertz_strips(ny, creepage), MU, 1.0)
    }

    /// Σ |q| |s| ΔA over [`StripFastsim::friction_elements`] [N], and the number of elements.
    fn element_power(s: &StripFastsim) -> (f64, usize) {
        let (mut sum, mut count) = (0.0, 0);
        s.friction_elements(|_, e| {
            assert!(e.slip >= 0.0 && e.traction_sq >= 0.0 && e.pressure > 0.0 && e.area > 0.0);
            // FASTSIM's elements lie within their bound.
            assert!(e.traction_sq.sqrt() <= e.bound * (1.0 + 1e-12));
            sum += e.traction_sq.sqrt() * e.slip * e.area;
            count += 1;
        });
        (sum, count)
    }

    #[test]
    fn element_slips_add_up_to_the_frictional_power() {
        // The slip field the damage models read (replayed from FASTSIM's stored tractions, or
        // FaStrip's own element terms, scaled) carries the solver's frictional power:
        // V Σ |q| |s| ΔA = P to rounding (1e−12), for both schemes, partial and full slip, with spin, and both
        // FaStrip variants on the patch's equivalent ellipse.
        let cases = [
            (2e-4, 1e-4, 0.0),
            (1e-3, -5e-4, 0.3),
            (0.0, 0.0, 2.0),
            (0.05, 0.02, 0.0),
        ];
        let ellipse = crate::tangential::patch::EquivalentEllipse {
            contact: crate::tangential::fastsim::CONTACT_EXAMPLE,
            coefficients: creep_coefficients(A, B, NU).unwrap(),
        };
        let speed = 12.5;
        for (xi, eta, phi) in cases {
            let k = Creepage { xi, eta, phi };
            let strips = hertz_strips(30, k);
            for (scheme, record) in [
                (MarchScheme::Contact, false),
                (MarchScheme::Midpoint, false),
                (MarchScheme::Midpoint, true),
            ] {
                let mut s = StripFastsim::new(24, scheme).unwrap();
                s.reserve_coupled(30);
                if record {
                    s.record_slips();
                }
                for run in 0..3 {
                    let r = match run {
                        0 => s.solve(&strips, MU, speed),
                        1 => s.solve_fastrip(&strips, &ellipse, speed, false),
                        _ => s.solve_fastrip(&strips, &ellipse, speed, true),
                    };
                    let (sum, count) = element_power(&s);
                    assert_eq!(count, 30 * 24);
                    let power = speed * sum;
                    // A field that slips nowhere (full adhesion on the grid) dissipates only
                    // the energy released at the trailing edge, which no element carries.
                    let expected = if sum > 0.0 { r.frictional_power } else { 0.0 };
                    assert!(
                        (power - expected).abs() <= 1e-12 * r.frictional_power.max(1.0),
                        "{k:?} {scheme:?} run {run}: {power} vs {}",
                        r.frictional_power
                    );
                    if xi == 0.05 {
                        assert!(power > 0.0);
                    }
                }
            }
        }
    }

    #[test]
    fn linear_limit_is_kalkers() {
        // Tiny creepage: full adhesion. FASTSIM's full-adhesion force exceeds the linear theory by
        // ≈ 1/nx (the leading element's full step, crate::tangential::fastsim header): +0.5 % at nx = 200;
        // the strip sum of a b C11 ∝ Σ (1 − y²/b²) Δy errs by O((Δy/b)²) ≈ 1e−4. Allow 1 %.
        let c = creep_coefficients(A, B, NU).unwrap();
        let xi = 1e-7;
        let r = solve(
            100,
            200,
            Creepage {
                xi,
                eta: 0.0,
                phi: 0.0,
            },
        );
        let linear = -G * A * B * c.c11 * xi;
        assert!((r.fx / linear - 1.0).abs() < 0.01, "{} vs {linear}", r.fx);
        assert!(r.adhesion_fraction == 1.0);
        let eta = 1e-7;
        let r = solve(
            100,
            200,
            Creepage {
                xi: 0.0,
                eta,
                phi: 0.0,
            },
        );
        let linear = -G * A * B * c.c22 * eta;
        assert!((r.fy / linear - 1.0).abs() < 0.01, "{} vs {linear}", r.fy);
    }

    #[test]
    fn full_sliding_reaches_mu_n() {
        // |F| → μ Σ p ΔA; the midpoint sums of the semi-ellipsoid on 100 × 100 elements are
        // within 0.5 % of N.
        for creepage in [
            Creepage {
                xi: 1.0,
                eta: 0.0,
                phi: 0.0,
            },
            Creepage {
                xi: 0.0,
                eta: -1.0,
                phi: 0.0,
            },
            Creepage {
                xi: 0.3,
                eta: 0.4,
                phi: 0.0,
            },
        ] {
            let r = solve(100, 100, creepage);
            let f = r.fx.hypot(r.fy);
            assert!((f / (MU * N) - 1.0).abs() < 5e-3, "{creepage:?}: {f}");
            assert_eq!(r.adhesion_fraction, 0.0);
            assert!(r.frictional_power > 0.0);
        }
    }

    #[test]
    fn mirrored_creepage_mirrors_forces() {
        // Bitwise symmetric strips (centres ±y) give exact mirror images: 1e−12 relative.
        let k = Creepage {
            xi: 2e-4,
            eta: -3e-4,
            phi: 0.4,
        };
        let r = solve(40, 40, k);
        let m = solve(40, 40, Creepage { xi: -k.xi, ..k });
        assert!(
            (r.fx + m.fx).abs() <= 1e-12 * r.fx.abs() + 1e-9,
            "{r:?} {m:?}"
        );
        let m = solve(
            40,
            40,
            Creepage {
                eta: -k.eta,
                phi: -k.phi,
                ..k
            },
        );
        assert!((r.fy + m.fy).abs() <= 1e-9 * r.fy.abs().max(1.0));
        assert!((r.mz + m.mz).abs() <= 1e-9 * r.mz.abs().max(1.0));
        assert!((r.fx - m.fx).abs() <= 1e-9 * r.fx.abs().max(1.0));
    }

    #[test]
    fn hertz_strips_agree_with_the_elliptic_fastsim() {
        // The same ellipse, flexibilities and bound; only the element layout differs (fixed nx
        // per strip here, a uniform Δx there), a first-order difference: at 200 × 200 both are
        // within ~0.5 % of their converged value (crate::tangential::fastsim header: Fy/(μN) −0.5979 at 160²,
        // −0.5968 at 400²). Allow 1 % of μN on the forces and 2 % on Mz (its converged value
        // still moves 1 % between 160² and 400²).
        let k = Creepage {
            xi: 0.0,
            eta: -6.25e-4,
            phi: 0.625,
        };
        let r = solve(200, 200, k);
        let mut f = Fastsim::new(FastsimSettings {
            nx: 200,
            ny: 200,
            ..Default::default()
        })
        .unwrap();
        let contact = CONTACT_EXAMPLE;
        let e = f.solve(&contact, &k, 1.0).unwrap();
        eprintln!(
            "strips: Fy/μN {:.4} Mz {:.2}; elliptic: {:.4} {:.2}",
            r.fy / (MU * N),
            r.mz,
            e.fy / (MU * N),
            e.mz
        );
        assert!((r.fy - e.fy).abs() < 0.01 * MU * N);
        assert!((r.fx - e.fx).abs() < 0.01 * MU * N);
        assert!((r.mz / e.mz - 1.0).abs() < 0.02);
    }

    #[test]
    fn unusable_strips_carry_nothing() {
        let mut strips = hertz_strips(
            10,
            Creepage {
                xi: 1e-3,
                eta: 0.0,
                phi: 0.0,
            },
        );
        strips[0].flexibility = [f64::NAN, 1.0, 1.0];
        strips[1].half_length = 0.0;
        strips[2].pmax = -1.0;
        let mut s = StripFastsim::new(20, MarchScheme::Midpoint).unwrap();
        let r = s.solve(&strips, MU, 1.0);
        for j in 0..3 {
            assert_eq!(s.strip_force(j), (0.0, 0.0));
        }
        assert!(r.fx.is_finite() && r.fx < 0.0);
        assert!(StripFastsim::new(0, MarchScheme::Midpoint).is_err());
        assert!(StripFastsim::new(MAX_ELEMENTS + 1, MarchScheme::Midpoint).is_err());
    }
}
