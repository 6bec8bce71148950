//! FASTSIM — Kalker's simplified theory of steady rolling contact on a Hertzian ellipse.
//!
//! Papers: J.J. Kalker (1982), "A fast algorithm for the simplified theory of rolling contact",
//! *Vehicle System Dynamics* 11:1–13; J.J. Kalker (1990), *Three-dimensional elastic bodies in
//! rolling contact*, ch. 3; E.A.H. Vollebregt & P. Voltr (2023) for the blended flexibility.
//! Equations as labelled in physics.md §4:
//!
//! * **F1** flexibilities L1 = 8a/(3 C11 G), L2 = 8a/(3 C22 G), L3 = π a √(a/b)/(4 C23 G)
//!   ([`three_flexibilities`]; C11, C22, C23 from `crate::kalker`);
//! * **F2** single flexibility L = (|ξ|L1 + |η|L2 + c|φ|L3)/√(ξ² + η² + c²φ²), c = √(ab)
//!   ([`single_flexibility`], option [`Flexibility::Single`]);
//! * **F3** strip marching from the leading edge x = +a_y to the trailing edge:
//!   p_x ← p_x − (ξ/L1 − φy/L3)Δx, p_y ← p_y − (η/L2 + φx/L3)Δx; where |p| > μ p_n the traction is
//!   scaled back onto the bound, direction kept (slip);
//! * **F4** blending of one and three flexibilities (Vollebregt & Voltr 2023, as coded in CONTACT)
//!   ([`blended_flexibilities`], option [`Flexibility::Blended`]);
//! * **§4.3** traction bound μ p_n with the elliptic (Hertz, default) or parabolic (Kalker 1982)
//!   pressure ([`TractionBound`]).
//!
//! # Discretisation convention (physics.md §4.2, §4.6 — documented choice)
//!
//! A uniform grid of `nx × ny` rectangular elements covers the bounding box [−a, a] × [−b, b]
//! (Δx = 2a/nx, Δy = 2b/ny). An element belongs to the contact when its **centre** lies strictly
//! inside the ellipse; all quantities (rigid slip including the spin term φx, bound μ p_n) are
//! evaluated at element centres. Each strip (row of constant y) is marched from its leading
//! element to its trailing one; the leading element starts from zero traction and takes one full
//! step Δx. This is exactly CONTACT's uniform grid: CONTACT's `fastsim` example (44 × 44 elements
//! on 1.1 × the bounding box) has element edges on x = ±a, y = ±b and the same 40 × 40 elements
//! inside, so `nx = ny = 40` reproduces it element by element.
//!
//! The scheme is first order: the half-element offset of the leading element and of the spin
//! evaluation shifts results by O(Δx/a). Under refinement the elliptic-bound forces converge fast
//! (Fy/(μN) −0.599 → −0.595 for 40 → 400 elements in the oracle case), the parabolic bound slowly
//! (−0.61 → ≈ −0.64) and Mz by ~6 % (−48 → −45 N·m). CONTACT's published FASTSIM numbers — and the
//! acceptance oracle — are those of the 40 × 40 grid, so the default grid is 40 × 40; finer grids
//! converge to FASTSIM's own limit, *not* to the exact theory (§4.6: that limit is ~2 % under
//! CONTACT's full theory for Fy).
//!
//! The pressure used in the bound is the analytic p_n at the element centres (like CONTACT); its
//! discrete resultant Σ p_n ΔxΔy differs from N by the quadrature error of the grid (+0.3 % for
//! 40 × 40, elliptic). Full sliding therefore gives |F| = μ Σ p_n ΔxΔy, within that error of μN.
//!
//! # Outputs and conventions (docs/conventions.md)
//!
//! Contact frame x rolling, y lateral, z normal (right-handed); creepages of the wheel (body 1)
//! relative to the rail, rigid slip w = (ξ − φy, η + φx); forces and the spin moment are those of
//! the rail *on the wheel*, so Fx = −G ab C11 ξ in the linear limit. Frictional power uses the
//! slip displacement of an element, S = (L_x (p − p*)_x, L_y (p − p*)_y) with p* the adhesion trial
//! traction (L_x = L1, L_y = L2, or the single L; as CONTACT), slip velocity V S/Δx, power
//! Σ |p| |V S/Δx| ΔxΔy ≥ 0.
//!
//! # Known limits
//!
//! Simplified (Winkler) theory: force errors of ~5–15 % against the exact theory over wide
//! creepage/spin ranges (Vollebregt et al. 2012, *unverified*, §4.6); first-order grid
//! convergence; steady rolling only; constant μ; Hertzian patch only; no slope reduction (F5).
//! No heap allocation in [`Fastsim::solve`]; all buffers are sized in [`Fastsim::new`].

use crate::error::{require_finite, require_non_negative, require_positive, InputError};
use crate::kalker::{creep_coefficients, CreepCoefficients};
use std::f64::consts::PI;

/// Pressure shape used for the traction bound μ p_n (physics.md §4.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TractionBound {
    /// Hertz pressure p0 √(1 − x²/a² − y²/b²), p0 = 3N/(2πab) (CONTACT's advice; default).
    #[default]
    Elliptic,
    /// Kalker's original (2N/(πab))(1 − x²/a² − y²/b²); local peak 33 % above Hertz.
    Parabolic,
}

/// Which flexibilities FASTSIM uses (physics.md §4.1, §4.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Flexibility {
    /// L1, L2, L3 of F1 (Kalker's three-flexibility FASTSIM; default).
    #[default]
    Three,
    /// One weighted flexibility of F2 for all directions (Kalker 1982).
    Single,
    /// F1 blended towards the single weighted flexibility by F4 (Vollebregt & Voltr 2023).
    Blended,
}

/// Grid and model options, fixed for the lifetime of a [`Fastsim`] (buffers are sized from them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FastsimSettings {
    /// Elements along the rolling direction across the bounding box 2a (≥ 1).
    pub nx: usize,
    /// Strips across the lateral extent 2b (≥ 1).
    pub ny: usize,
    /// Traction-bound shape.
    pub bound: TractionBound,
    /// Flexibility model.
    pub flexibility: Flexibility,
}

/// Default grid: 40 × 40 elements inside the bounding box — CONTACT's grid for its `fastsim`
/// example, on which the published FASTSIM numbers (the acceptance oracle) were computed. See the
/// module header for the convergence behaviour; cost about 1600 element updates (a few µs).
pub const DEFAULT_GRID: usize = 40;

impl Default for FastsimSettings {
    fn default() -> Self {
        Self {
            nx: DEFAULT_GRID,
            ny: DEFAULT_GRID,
            bound: TractionBound::Elliptic,
            flexibility: Flexibility::Three,
        }
    }
}

/// Kalker creepages of the wheel relative to the rail.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Creepage {
    /// Longitudinal creepage ξ [-].
    pub xi: f64,
    /// Lateral creepage η [-].
    pub eta: f64,
    /// Spin creepage φ [1/m].
    pub phi: f64,
}

/// A Hertzian contact ellipse with its material and friction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipticContact {
    /// Semi-axis along the rolling direction x [m].
    pub a: f64,
    /// Lateral semi-axis along y [m].
    pub b: f64,
    /// Normal force N ≥ 0 [N].
    pub normal_force: f64,
    /// Combined shear modulus G > 0 [Pa].
    pub shear_modulus: f64,
    /// Combined Poisson ratio ν ∈ [0, 0.5] [-].
    pub nu: f64,
    /// Coefficient of friction μ > 0 [-].
    pub mu: f64,
}

/// Result of one FASTSIM solve (forces of the rail on the wheel, contact axes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FastsimResult {
    /// Longitudinal force on the wheel [N].
    pub fx: f64,
    /// Lateral force on the wheel [N].
    pub fy: f64,
    /// Spin moment about the patch centre on the wheel [N m].
    pub mz: f64,
    /// Adhesion elements / contact elements [-].
    pub adhesion_fraction: f64,
    /// Frictional power Σ |traction| |slip velocity| ΔA ≥ 0 [W].
    pub frictional_power: f64,
    /// Maximum |tangential traction| [Pa].
    pub max_traction: f64,
    /// Kalker coefficients used for the flexibilities.
    pub coefficients: CreepCoefficients,
    /// Flexibilities actually used for the ξ, η and φ terms [m/Pa].
    pub flexibilities: [f64; 3],
}

/// Traction in one contact element of the last solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementTraction {
    /// Element centre, rolling direction [m].
    pub x: f64,
    /// Element centre, lateral [m].
    pub y: f64,
    /// Tangential traction on the wheel along x [Pa].
    pub px: f64,
    /// Tangential traction on the wheel along y [Pa].
    pub py: f64,
    /// Normal pressure used for the traction bound [Pa].
    pub pn: f64,
    /// Whether the element is in slip (traction on the bound).
    pub slipping: bool,
}

/// F1: flexibilities [L1, L2, L3] [m/Pa] for semi-axes `a` (rolling), `b` [m], shear modulus
/// `shear_modulus` [Pa] and Kalker coefficients `c`.
pub fn three_flexibilities(a: f64, b: f64, shear_modulus: f64, c: &CreepCoefficients) -> [f64; 3] {
    [
        8.0 * a / (3.0 * c.c11 * shear_modulus),
        8.0 * a / (3.0 * c.c22 * shear_modulus),
        PI * a * (a / b).sqrt() / (4.0 * c.c23 * shear_modulus),
    ]
}

/// F2: Kalker's single weighted flexibility [m/Pa] from the three of F1, c = √(ab) [m].
///
/// At zero creepage the weighting is undefined (and irrelevant: there is no traction); the mean of
/// the three is returned so that the result stays finite.
pub fn single_flexibility(l: [f64; 3], creepage: &Creepage, c: f64) -> f64 {
    let spin = c * creepage.phi;
    let norm = creepage.xi.hypot(creepage.eta).hypot(spin);
    if norm > 0.0 && norm.is_finite() {
        // Normalise first so that huge creepages cannot overflow.
        (creepage.xi.abs() / norm) * l[0]
            + (creepage.eta.abs() / norm) * l[1]
            + (spin.abs() / norm) * l[2]
    } else {
        (l[0] + l[1] + l[2]) / 3.0
    }
}

/// F4 blending weight w ∈ [0, 1] (Vollebregt & Voltr 2023): w = √((ξ² + η²)/(chξ² + chη²))/3
/// with the characteristic creepages chξ = μN/(ab G C11), chη = μN/(ab G C22).
pub fn blending_weight(contact: &EllipticContact, c: &CreepCoefficients, creepage: &Creepage) -> f64 {
    let c2_g = contact.a * contact.b * contact.shear_modulus;
    let mu_n = contact.mu * contact.normal_force;
    let ch_xi = mu_n / (c2_g * c.c11);
    let ch_eta = mu_n / (c2_g * c.c22);
    // F4 divides by 3: full blending is reached at three times the characteristic creepage.
    let w = creepage.xi.hypot(creepage.eta) / ch_xi.hypot(ch_eta) / 3.0;
    if w.is_nan() {
        0.0
    } else {
        w.clamp(0.0, 1.0)
    }
}

/// F4: three flexibilities blended towards the single weighted one,
/// L× = (ξ² + η² + (φf)²)/(ξ²/L1 + η²/L2 + (φf)²/L3), f = 3πa/32, L_i ← (1 − w)L_i + w L×.
pub fn blended_flexibilities(
    l: [f64; 3],
    contact: &EllipticContact,
    c: &CreepCoefficients,
    creepage: &Creepage,
) -> [f64; 3] {
    let w = blending_weight(contact, c, creepage);
    if w == 0.0 {
        return l;
    }
    // Spin lever f = 3πa/32 of F4; creepages normalised by their largest magnitude so that the
    // squares can neither overflow nor underflow.
    let f = 3.0 * PI * contact.a / 32.0;
    let terms = [creepage.xi, creepage.eta, creepage.phi * f];
    let scale = terms.iter().fold(0.0_f64, |m, t| m.max(t.abs()));
    if !(scale > 0.0 && scale.is_finite()) {
        return l;
    }
    let sq = terms.map(|t| (t / scale) * (t / scale));
    let l_cross = (sq[0] + sq[1] + sq[2]) / (sq[0] / l[0] + sq[1] / l[1] + sq[2] / l[2]);
    l.map(|li| (1.0 - w) * li + w * l_cross)
}

/// Adhesion trials may exceed the bound by at most this factor after the overflow guard in
/// [`Fastsim::solve`]: beyond it the creepages are scaled down together (directions kept), which
/// changes tractions by < 1e−12 relative (the trial direction is that of the rigid slip to that
/// accuracy) and keeps every intermediate finite.
const MAX_OVERDRIVE: f64 = 1e100;

/// Where the spin term φx of the rigid slip is evaluated within the step from one element to the
/// next: at x + `SPIN_OFFSET_FRACTION`·Δx, towards the leading edge. CONTACT uses the same offset
/// for rolling problems (`facphi`, default 1/6 of the rolling step dq = Δx, routine
/// `set_tang_rhs` of CONTACT's `m_sdis.f90`); with it the 40 × 40 grid reproduces CONTACT's
/// published FASTSIM numbers (physics.md §4.2, §4.6). 0 would be the element centre, ½ the
/// midpoint of the step.
pub const SPIN_OFFSET_FRACTION: f64 = 1.0 / 6.0;

/// FASTSIM solver with preallocated buffers.
#[derive(Debug, Clone)]
pub struct Fastsim {
    settings: FastsimSettings,
    /// Bound shape per element on the normalised grid: √(1 − X² − Y²) or 1 − X² − Y² (X = x/a,
    /// Y = y/b at the element centre), 0 outside the ellipse. Row-major, strip j, element i
    /// (i = 0 at the trailing edge x = −a).
    shape: Vec<f64>,
    /// Contact elements of strip j are i ∈ [strip_range[j].0, strip_range[j].1).
    strip_range: Vec<(usize, usize)>,
    px: Vec<f64>,
    py: Vec<f64>,
    slipping: Vec<bool>,
    /// Geometry and pressure scale of the last solve (for [`Fastsim::tractions`]).
    last_a: f64,
    last_b: f64,
    last_peak_pressure: f64,
    has_field: bool,
}

/// Largest accepted `nx`, `ny` (memory guard: 1e4 × 1e4 elements would need ~2 GB).
pub const MAX_GRID: usize = 10_000;

impl Fastsim {
    /// Builds the solver; allocates all buffers. `nx`, `ny` ∈ [1, 10 000] (errors "nx", "ny").
    pub fn new(settings: FastsimSettings) -> Result<Self, InputError> {
        for (name, n) in [("nx", settings.nx), ("ny", settings.ny)] {
            if n == 0 || n > MAX_GRID {
                return Err(InputError::new(name, n as f64, "[1, 10000]"));
            }
        }
        let (nx, ny) = (settings.nx, settings.ny);
        let mut shape = vec![0.0; nx * ny];
        let mut strip_range = vec![(0, 0); ny];
        for j in 0..ny {
            let yn = normalised_centre(j, ny);
            let mut first = None;
            let mut end = 0;
            for i in 0..nx {
                let xn = normalised_centre(i, nx);
                let s = 1.0 - xn * xn - yn * yn;
                if s > 0.0 {
                    shape[j * nx + i] = match settings.bound {
                        TractionBound::Elliptic => s.sqrt(),
                        TractionBound::Parabolic => s,
                    };
                    first.get_or_insert(i);
                    end = i + 1;
                }
            }
            strip_range[j] = first.map_or((0, 0), |f| (f, end));
        }
        Ok(Self {
            settings,
            shape,
            strip_range,
            px: vec![0.0; nx * ny],
            py: vec![0.0; nx * ny],
            slipping: vec![false; nx * ny],
            last_a: 0.0,
            last_b: 0.0,
            last_peak_pressure: 0.0,
            has_field: false,
        })
    }

    /// The settings this solver was built with.
    pub fn settings(&self) -> FastsimSettings {
        self.settings
    }

    /// Solves steady rolling for `contact`, `creepage` and rolling speed V = `rolling_speed` ≥ 0
    /// [m/s] (V only scales the frictional power). No heap allocation.
    ///
    /// Errors name "xi", "eta", "phi", "V", "mu", "nu", "G", "N", "a", "b". N = 0 gives the
    /// all-zero result (a, b are then not checked).
    pub fn solve(
        &mut self,
        contact: &EllipticContact,
        creepage: &Creepage,
        rolling_speed: f64,
    ) -> Result<FastsimResult, InputError> {
        require_finite("xi", creepage.xi)?;
        require_finite("eta", creepage.eta)?;
        require_finite("phi", creepage.phi)?;
        require_non_negative("V", rolling_speed)?;
        require_positive("mu", contact.mu)?;
        if !(0.0..=0.5).contains(&contact.nu) {
            return Err(InputError::new("nu", contact.nu, "[0, 0.5]"));
        }
        require_positive("G", contact.shear_modulus)?;
        require_non_negative("N", contact.normal_force)?;
        self.has_field = false;
        if contact.normal_force == 0.0 {
            return Ok(FastsimResult::default());
        }
        let (a, b) = (contact.a, contact.b);
        require_positive("a", a)?;
        require_positive("b", b)?;
        let coefficients = creep_coefficients(a, b, contact.nu)?;
        let three = three_flexibilities(a, b, contact.shear_modulus, &coefficients);
        let flexibilities = match self.settings.flexibility {
            Flexibility::Three => three,
            Flexibility::Single => [single_flexibility(three, creepage, (a * b).sqrt()); 3],
            Flexibility::Blended => blended_flexibilities(three, contact, &coefficients, creepage),
        };
        let peak_pressure = match self.settings.bound {
            TractionBound::Elliptic => 3.0 * contact.normal_force / (2.0 * PI * a * b),
            TractionBound::Parabolic => 2.0 * contact.normal_force / (PI * a * b),
        };
        let (nx, ny) = (self.settings.nx, self.settings.ny);
        let dx = 2.0 * a / nx as f64;
        let dy = 2.0 * b / ny as f64;
        let [l1, l2, l3] = flexibilities;

        // Overflow guard (see MAX_OVERDRIVE): creepage rates in traction per step, relative to the
        // peak bound, computed on normalised creepages so nothing overflows.
        let magnitude = creepage
            .xi
            .abs()
            .max(creepage.eta.abs())
            .max(creepage.phi.abs() * a.max(b));
        let mut used = *creepage;
        let mut power_factor = 1.0;
        if magnitude > 0.0 {
            let unit = Creepage {
                xi: creepage.xi / magnitude,
                eta: creepage.eta / magnitude,
                phi: creepage.phi / magnitude,
            };
            let rate = ((unit.xi.abs() / l1 + unit.phi.abs() * b / l3)
                .max(unit.eta.abs() / l2 + unit.phi.abs() * a / l3))
                * dx
                / (contact.mu * peak_pressure);
            let overdrive = magnitude * rate;
            if overdrive > MAX_OVERDRIVE {
                let k = MAX_OVERDRIVE / rate;
                used = Creepage {
                    xi: unit.xi * k,
                    eta: unit.eta * k,
                    phi: unit.phi * k,
                };
                // Slip (hence power) scales with the creepage in this full-sliding regime.
                power_factor = magnitude / k;
            }
        }

        let bound_scale = contact.mu * peak_pressure;
        let (slip_lx, slip_ly) = (l1, l2);
        let mut sum_px = 0.0;
        let mut sum_py = 0.0;
        let mut sum_mz = 0.0;
        let mut sum_power = 0.0;
        let mut max_traction_sq = 0.0_f64;
        let mut n_contact = 0_usize;
        let mut n_adhesion = 0_usize;
        // Per-step increments: x part constant along a strip, y part linear in x.
        let step_eta = used.eta / l2 * dx;
        let step_phi_x = used.phi / l3 * dx;
        let spin_offset = SPIN_OFFSET_FRACTION * dx;
        for j in 0..ny {
            let (first, end) = self.strip_range[j];
            if first == end {
                continue;
            }
            let y = b * normalised_centre(j, ny);
            let step_x = (used.xi / l1 - used.phi * y / l3) * dx;
            let (mut px, mut py) = (0.0_f64, 0.0_f64);
            let row = j * nx;
            // Leading edge is x = +a: march from the last element towards i = 0.
            for i in (first..end).rev() {
                let k = row + i;
                let x = a * normalised_centre(i, nx);
                // F3: adhesion trial; spin term at x + Δx/6 (SPIN_OFFSET_FRACTION).
                let trial_x = px - step_x;
                let trial_y = py - (step_eta + step_phi_x * (x + spin_offset));
                let bound = bound_scale * self.shape[k];
                let trial_sq = trial_x * trial_x + trial_y * trial_y;
                let slipping = trial_sq > bound * bound;
                if slipping {
                    let f = bound / trial_sq.sqrt();
                    px = trial_x * f;
                    py = trial_y * f;
                    let sx = slip_lx * (px - trial_x);
                    let sy = slip_ly * (py - trial_y);
                    sum_power += bound * sx.hypot(sy);
                } else {
                    px = trial_x;
                    py = trial_y;
                    n_adhesion += 1;
                }
                n_contact += 1;
                self.px[k] = px;
                self.py[k] = py;
                self.slipping[k] = slipping;
                sum_px += px;
                sum_py += py;
                sum_mz += x * py - y * px;
                max_traction_sq = max_traction_sq.max(px * px + py * py);
            }
        }
        self.last_a = a;
        self.last_b = b;
        self.last_peak_pressure = peak_pressure;
        self.has_field = true;
        let area = dx * dy;
        // Power: Σ |p| |V S/Δx| ΔxΔy = V Σ |p| |S| Δy; saturate instead of overflowing to ∞.
        let power = (rolling_speed * sum_power * dy * power_factor).min(f64::MAX);
        Ok(FastsimResult {
            fx: sum_px * area,
            fy: sum_py * area,
            mz: sum_mz * area,
            adhesion_fraction: if n_contact > 0 {
                n_adhesion as f64 / n_contact as f64
            } else {
                0.0
            },
            frictional_power: power,
            max_traction: max_traction_sq.sqrt(),
            coefficients,
            flexibilities,
        })
    }

    /// Traction field of the last successful solve (contact elements only; empty after N = 0,
    /// an error, or before the first solve).
    pub fn tractions(&self) -> impl Iterator<Item = ElementTraction> + '_ {
        let ny = if self.has_field { self.settings.ny } else { 0 };
        let nx = self.settings.nx;
        (0..ny).flat_map(move |j| {
            let (first, end) = self.strip_range[j];
            let y = self.last_b * normalised_centre(j, self.settings.ny);
            (first..end).map(move |i| {
                let k = j * nx + i;
                ElementTraction {
                    x: self.last_a * normalised_centre(i, nx),
                    y,
                    px: self.px[k],
                    py: self.py[k],
                    pn: self.last_peak_pressure * self.shape[k],
                    slipping: self.slipping[k],
                }
            })
        })
    }
}

/// Centre of element `i` of `n` on [−1, 1]: −1 + (i + ½)·2/n.
fn normalised_centre(i: usize, n: usize) -> f64 {
    -1.0 + (2.0 * i as f64 + 1.0) / n as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// CONTACT `fastsim` example (physics.md §4.6) in SI units.
    fn oracle_contact() -> EllipticContact {
        EllipticContact {
            a: 8e-3,
            b: 4e-3,
            normal_force: 82_000.0,
            shear_modulus: 82e9,
            nu: 0.28,
            mu: 0.3,
        }
    }

    fn oracle_creepage() -> Creepage {
        Creepage {
            xi: 0.0,
            eta: -6.25e-4,
            phi: 0.625,
        }
    }

    fn solve(settings: FastsimSettings, c: &EllipticContact, k: &Creepage) -> FastsimResult {
        Fastsim::new(settings).unwrap().solve(c, k, 30.0).unwrap()
    }

    #[test]
    fn explore() {
        let c = oracle_contact();
        let g = c.shear_modulus;
        let ab = c.a * c.b;
        for n in [10, 20, 40, 80, 160, 320, 640] {
            let s = FastsimSettings { nx: n, ny: n, ..Default::default() };
            let mut f = Fastsim::new(s).unwrap();
            let r = f.solve(&c, &Creepage { xi: 1e-9, eta: 0.0, phi: 0.0 }, 1.0).unwrap();
            let k = r.coefficients;
            let fx_lin = -g * ab * k.c11 * 1e-9;
            let r2 = f.solve(&c, &Creepage { xi: 0.0, eta: 1e-9, phi: 0.0 }, 1.0).unwrap();
            let fy_lin = -g * ab * k.c22 * 1e-9;
            let mz_lin_eta = g * ab.powf(1.5) * k.c23 * 1e-9;
            let r3 = f.solve(&c, &Creepage { xi: 0.0, eta: 0.0, phi: 1e-9 }, 1.0).unwrap();
            let fy_spin = -g * ab.powf(1.5) * k.c23 * 1e-9;
            let r4 = f.solve(&c, &Creepage { xi: 10.0, eta: 0.0, phi: 0.0 }, 1.0).unwrap();
            let sum_pn: f64 = f.tractions().map(|e| e.pn).sum::<f64>() * (2.0 * c.a / n as f64) * (2.0 * c.b / n as f64);
            let t = std::time::Instant::now();
            let reps = 2000;
            let mut acc = 0.0;
            for _ in 0..reps { acc += f.solve(&c, &oracle_creepage(), 30.0).unwrap().fy; }
            let us = t.elapsed().as_secs_f64() / reps as f64 * 1e6;
            println!("n {n}: Fx/lin {:.5} Fy/lin {:.5} spinFy/lin {:.5} Mz(eta)/lin {:.5} | slide |F|/muN {:.5} sum_pn/N {:.5} adh {} | {us:.2} us {acc:.1}",
                r.fx / fx_lin, r2.fy / fy_lin, r3.fy / fy_spin, r2.mz / mz_lin_eta, r4.fx.hypot(r4.fy) / (0.3 * c.normal_force), sum_pn / c.normal_force, r4.adhesion_fraction);
        }
        for bound in [TractionBound::Elliptic, TractionBound::Parabolic] {
            for flexibility in [Flexibility::Three, Flexibility::Blended] {
                for n in [40, 160, 200] {
                    let s = FastsimSettings { nx: n, ny: n, bound, flexibility };
                    let r = solve(s, &oracle_contact(), &oracle_creepage());
                    println!(
                        "{bound:?} {flexibility:?} {n}: Fy/muN {:.5} Mz {:.4} P {:.3} adh {:.4} L {:?}",
                        r.fy / (0.3 * 82e3), r.mz, r.frictional_power, r.adhesion_fraction,
                        r.flexibilities.map(|l| l * 1e9)
                    );
                }
            }
        }
    }
}
