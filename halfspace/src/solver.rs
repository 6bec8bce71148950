//! The constrained conjugate-gradient solver of Polonsky & Keer (1999) for the normal problem.

use std::fmt;

use railcontact::error::{require_finite, require_non_negative, require_positive, InputError};

use crate::convolution::Convolution;
use crate::grid::Grid;
use crate::influence::influence_coefficient;

/// What is prescribed besides the undeformed gap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// The rigid approach δ [m], finite: the deformed gap is h + u − δ.
    Approach(f64),
    /// The total normal force W = Σ p dx dy ≥ 0 [N]; the approach is part of the solution.
    Force(f64),
}

/// Solution of the normal contact problem on a [`Grid`].
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// Element pressures, row-major `[j * nx + i]`, ≥ 0 [Pa].
    pub pressure: Vec<f64>,
    /// Normal force Σ p dx dy [N] (the prescribed value under [`Target::Force`]).
    pub normal_force: f64,
    /// Rigid approach δ [m]: the deformed gap is h + u − δ. The prescribed value, or under a
    /// prescribed force the mean of h + u over the loaded elements (the smallest gap, i.e. first
    /// touch, for zero force).
    pub approach: f64,
    /// Area of the elements with p > 0 [m²].
    pub contact_area: f64,
    /// Largest element pressure [Pa] (0 without contact).
    pub max_pressure: f64,
    /// Polonsky–Keer iterations used (0 when the answer is trivial).
    pub iterations: usize,
}

/// Why a half-space solve produced no solution.
#[derive(Debug, Clone, PartialEq)]
pub enum SolveError {
    /// An input outside its allowed range.
    Input(InputError),
    /// The relative pressure change was still above `tol` after the iteration cap.
    NotConverged {
        /// Iterations performed.
        iterations: usize,
        /// Last relative pressure change Σ|p − p_old| / Σ p.
        change: f64,
    },
}

impl From<InputError> for SolveError {
    fn from(e: InputError) -> Self {
        Self::Input(e)
    }
}

impl fmt::Display for SolveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Input(e) => e.fmt(f),
            Self::NotConverged { iterations, change } => write!(
                f,
                "half-space solver not converged after {iterations} iterations \
                 (relative pressure change {change:e})"
            ),
        }
    }
}

impl std::error::Error for SolveError {}

/// The normal contact problem on one grid for one contact modulus: FFT plans and the
/// influence coefficients' spectrum are made once by [`Solver::new`], so repeated solves (other
/// gaps, approaches, forces) on the same grid only iterate.
pub struct Solver {
    grid: Grid,
    e_star: f64,
    convolution: Convolution,
    /// Displacement of an element under its own unit pressure [m/Pa].
    self_influence: f64,
}

impl Solver {
    /// Solver for `grid` and the contact modulus `e_star` E* [Pa], 1/E* = (1 − ν₁²)/E₁ +
    /// (1 − ν₂²)/E₂ (`railcontact::normal::hertz::contact_modulus` for two bodies of one
    /// material).
    pub fn new(grid: Grid, e_star: f64) -> Result<Self, InputError> {
        grid.validate()?;
        require_positive("E*", e_star)?;
        Ok(Self {
            convolution: Convolution::new(&grid, e_star),
            self_influence: influence_coefficient(grid.dx, grid.dy, 0.0, 0.0, e_star),
            grid,
            e_star,
        })
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The contact modulus E* [Pa].
    pub fn e_star(&self) -> f64 {
        self.e_star
    }

    /// Combined surface displacement u = C * p [m] of both bodies for element pressures
    /// `pressure` [Pa] (row-major). The deformed gap of a solution is `gap + u − approach`.
    pub fn displacement(&mut self, pressure: &[f64]) -> Result<Vec<f64>, InputError> {
        self.grid.check_field("pressure.len", pressure)?;
        for &p in pressure {
            require_finite("p", p)?;
        }
        let mut u = vec![0.0; self.grid.len()];
        self.convolution.apply(pressure, &mut u);
        Ok(u)
    }

    /// Contact for the undeformed gap `gap` and the prescribed approach or force.
    ///
    /// `gap`: undeformed gap h [m] at the element centres, row-major; finite, or +∞ for elements
    /// that can never touch (at least one finite under a positive force). `tol`: relative
    /// pressure change at which the iteration stops (e.g. 1e−10). A prescribed force is met to
    /// rounding whatever `tol` (enforced at every iteration). If a prescribed approach does not
    /// exceed the smallest gap the answer is zero pressure with no iteration.
    pub fn solve(&mut self, gap: &[f64], target: Target, tol: f64) -> Result<Solution, SolveError> {
        check_gap(&self.grid, gap)?;
        require_positive("tol", tol)?;
        let n = self.grid.len();
        let min_gap = gap.iter().copied().fold(f64::INFINITY, f64::min);
        match target {
            Target::Force(w) => {
                require_non_negative("N", w)?;
                if w == 0.0 {
                    // First touch; 0 if no element can ever touch (nothing is loaded anyway).
                    let first_touch = if min_gap.is_finite() { min_gap } else { 0.0 };
                    return Ok(no_contact(n, first_touch));
                }
                if !min_gap.is_finite() {
                    let e = InputError::new("gap", min_gap, "at least one finite element");
                    return Err(e.into());
                }
                self.iterate(gap, Some(w), 0.0, tol)
            }
            Target::Approach(d) => {
                require_finite("delta", d)?;
                if min_gap >= d {
                    return Ok(no_contact(n, d));
                }
                self.iterate(gap, None, d, tol)
            }
        }
    }

    /// The Polonsky–Keer iteration: CG on the contact set I_c = {p > 0}, projection onto p ≥ 0,
    /// re-entry of penetrating free elements, and under a prescribed force `load` the mean gap on
    /// I_c as the running approach and Σ p ΔA = W at every iteration. `shift`: the prescribed
    /// approach (0 under a force).
    fn iterate(
        &mut self,
        gap: &[f64],
        load: Option<f64>,
        shift: f64,
        tol: f64,
    ) -> Result<Solution, SolveError> {
        let n = self.grid.len();
        let area = self.grid.element_area();
        let mut p = vec![0.0; n];
        let mut p_old = vec![0.0; n];
        let mut u = vec![0.0; n];
        let mut g = vec![0.0; n];
        let mut t = vec![0.0; n];
        let mut r = vec![0.0; n];

        match load {
            Some(w) => uniform_start(gap, w, area, &mut p),
            None => {
                for (gk, &h) in g.iter_mut().zip(gap) {
                    *gk = h - shift;
                }
                restart_from_penetration(&mut self.convolution, &g, &mut p, &mut r);
            }
        }

        let mut approach = shift;
        let mut g_norm_old = 1.0;
        let mut conjugate = false;
        let mut change = f64::INFINITY;
        let cap = max_iterations(&self.grid);
        for iteration in 1..=cap {
            // (1) deformed gap; contact set I_c = {p > 0}.
            self.convolution.apply(&p, &mut u);
            deformed_gap(gap, &u, shift, &mut g);
            let n_c = p.iter().filter(|&&pk| pk > 0.0).count();
            if n_c == 0 {
                // Only with a prescribed approach (the force rescaling keeps p ≠ 0): every
                // element was released. Start afresh from the current penetration.
                if !g.iter().any(|&gk| gk < 0.0) {
                    return Ok(no_contact(n, shift));
                }
                restart_from_penetration(&mut self.convolution, &g, &mut p, &mut r);
                conjugate = false;
                continue;
            }
            // (2) force control: the mean gap on I_c is the running approach.
            if load.is_some() {
                approach = sum_on_contact(&p, &g) / n_c as f64;
                subtract(&mut g, approach);
            }
            // (3)–(4) conjugate direction on I_c.
            let g_norm = dot_on_contact(&p, &g, &g);
            let beta = if conjugate { g_norm / g_norm_old } else { 0.0 };
            conjugate_direction(&p, &g, beta, &mut t);
            g_norm_old = g_norm;
            // (5) r = C t, centred on I_c under force control.
            self.convolution.apply(&t, &mut r);
            if load.is_some() {
                let r_mean = sum_on_contact(&p, &r) / n_c as f64;
                subtract(&mut r, r_mean);
            }
            // (6) step length.
            let (num, den) = (dot_on_contact(&p, &g, &t), dot_on_contact(&p, &r, &t));
            let tau = if den > 0.0 && num.is_finite() {
                num / den
            } else if conjugate {
                // No descent along the conjugate direction (its force-centring can spoil the
                // curvature): retry from the same iterate with the steepest descent, t = g.
                conjugate = false;
                continue;
            } else {
                // t = g = 0 on I_c (C is positive definite): the contact set is in equilibrium.
                0.0
            };
            // (7)–(8) step on I_c, projection onto p ≥ 0.
            p_old.copy_from_slice(&p);
            step_and_project(&mut p, &t, tau);
            // (9) free elements that penetrate re-enter; the conjugacy is then lost. With no
            // step length from I_c (e.g. a one-element contact under force, where g = 0 on I_c),
            // the single-element stiffness 1/C₀₀ sets the entering pressures.
            let tau_entry = if tau > 0.0 {
                tau
            } else {
                1.0 / self.self_influence
            };
            conjugate = !enter_penetrating(&mut p, &g, tau_entry);
            // (10) force control: Σ p ΔA = W.
            if let Some(w) = load {
                if !rescale_to_force(&mut p, w, area) {
                    // Everything released (not expected: the elements with g < 0 on I_c
                    // re-enter when clipped): back to the previous iterate, steepest descent
                    // next time.
                    p.copy_from_slice(&p_old);
                    conjugate = false;
                    continue;
                }
            }
            // (11) relative pressure change.
            change = relative_change(&p, &p_old);
            if change <= tol {
                let approach = match load {
                    Some(_) if p.iter().any(|&pk| pk > 0.0) => {
                        self.recovered_approach(gap, &p, &mut u)
                    }
                    _ => approach,
                };
                return Ok(solution(p, area, load, approach, iteration));
            }
        }
        Err(SolveError::NotConverged {
            iterations: cap,
            change,
        })
    }

    /// δ from the final pressures under a prescribed force: the mean of h + u over the contact
    /// elements (at least one). Uses `u` as work space.
    fn recovered_approach(&mut self, gap: &[f64], pressure: &[f64], u: &mut [f64]) -> f64 {
        self.convolution.apply(pressure, u);
        let n_c = pressure.iter().filter(|&&p| p > 0.0).count();
        let s: f64 = pressure
            .iter()
            .zip(gap.iter().zip(u.iter()))
            .filter(|(&p, _)| p > 0.0)
            .map(|(_, (&h, &uk))| h + uk)
            .sum();
        s / n_c as f64
    }
}

/// Contact for the undeformed gap `gap` on `grid`, contact modulus `e_star` [Pa], as
/// [`Solver::solve`]; for one solve (a [`Solver`] keeps its FFT plans for the next).
pub fn solve(
    grid: &Grid,
    gap: &[f64],
    target: Target,
    e_star: f64,
    tol: f64,
) -> Result<Solution, SolveError> {
    Solver::new(*grid, e_star)?.solve(gap, target, tol)
}

/// Combined surface displacement u = C * p [m] of both bodies for element pressures `pressure`
/// [Pa] (row-major on `grid`), contact modulus `e_star` [Pa], as [`Solver::displacement`].
pub fn surface_displacement(
    grid: &Grid,
    pressure: &[f64],
    e_star: f64,
) -> Result<Vec<f64>, InputError> {
    Solver::new(*grid, e_star)?.displacement(pressure)
}

/// One value per element, each finite or +∞.
fn check_gap(grid: &Grid, gap: &[f64]) -> Result<(), InputError> {
    grid.check_field("gap.len", gap)?;
    for &h in gap {
        if h.is_nan() || h == f64::NEG_INFINITY {
            return Err(InputError::new("gap", h, "finite or +inf"));
        }
    }
    Ok(())
}

/// Iteration cap: generous (the Hertz cases of the tests need a few dozen iterations); it only
/// turns a stall into an error instead of an endless loop.
fn max_iterations(grid: &Grid) -> usize {
    2000 + 10 * (grid.nx + grid.ny)
}

/// Zero pressure on `n` elements at the approach `approach` [m].
fn no_contact(n: usize, approach: f64) -> Solution {
    Solution {
        pressure: vec![0.0; n],
        normal_force: 0.0,
        approach,
        contact_area: 0.0,
        max_pressure: 0.0,
        iterations: 0,
    }
}

/// The converged state: force, area and peak of `pressure` on elements of area `area`.
fn solution(
    pressure: Vec<f64>,
    area: f64,
    load: Option<f64>,
    approach: f64,
    iterations: usize,
) -> Solution {
    let n_c = pressure.iter().filter(|&&p| p > 0.0).count();
    let normal_force = match load {
        Some(w) => w,
        None => pressure.iter().sum::<f64>() * area,
    };
    Solution {
        normal_force,
        approach,
        contact_area: n_c as f64 * area,
        max_pressure: pressure.iter().copied().fold(0.0, f64::max),
        iterations,
        pressure,
    }
}

/// Polonsky & Keer's start under a force `w`: the same pressure on every element that can
/// touch (finite gap), elements of area `area`.
fn uniform_start(gap: &[f64], w: f64, area: f64, p: &mut [f64]) {
    let count = gap.iter().filter(|h| h.is_finite()).count();
    let p_mean = w / (count as f64 * area);
    for (pk, &h) in p.iter_mut().zip(gap) {
        if h.is_finite() {
            *pk = p_mean;
        }
    }
}

/// g = h + u − δ.
fn deformed_gap(gap: &[f64], u: &[f64], approach: f64, g: &mut [f64]) {
    for ((gk, &h), &uk) in g.iter_mut().zip(gap).zip(u) {
        *gk = h + uk - approach;
    }
}

/// Σ v over the contact set {p > 0}.
fn sum_on_contact(p: &[f64], v: &[f64]) -> f64 {
    let mut s = 0.0;
    for (&pk, &vk) in p.iter().zip(v) {
        if pk > 0.0 {
            s += vk;
        }
    }
    s
}

/// Σ a b over the contact set {p > 0}.
fn dot_on_contact(p: &[f64], a: &[f64], b: &[f64]) -> f64 {
    let mut s = 0.0;
    for ((&pk, &ak), &bk) in p.iter().zip(a).zip(b) {
        if pk > 0.0 {
            s += ak * bk;
        }
    }
    s
}

/// v − c, element by element.
fn subtract(v: &mut [f64], c: f64) {
    for vk in v.iter_mut() {
        *vk -= c;
    }
}

/// t = g + β t on the contact set {p > 0}, 0 elsewhere.
fn conjugate_direction(p: &[f64], g: &[f64], beta: f64, t: &mut [f64]) {
    for ((tk, &pk), &gk) in t.iter_mut().zip(p).zip(g) {
        *tk = if pk > 0.0 { gk + beta * *tk } else { 0.0 };
    }
}

/// p ← max(p − τ t, 0) on the contact set {p > 0}.
fn step_and_project(p: &mut [f64], t: &[f64], tau: f64) {
    for (pk, &tk) in p.iter_mut().zip(t) {
        if *pk > 0.0 {
            *pk = (*pk - tau * tk).max(0.0);
        }
    }
}

/// Free elements (p = 0) that penetrate (g < 0) get p = −τ g; true if any entered.
fn enter_penetrating(p: &mut [f64], g: &[f64], tau: f64) -> bool {
    let mut entered = false;
    for (pk, &gk) in p.iter_mut().zip(g) {
        if *pk == 0.0 && gk < 0.0 {
            let entry = -tau * gk;
            if entry > 0.0 {
                *pk = entry;
                entered = true;
            }
        }
    }
    entered
}

/// Scales p so that Σ p `area` = `w`; false (p unchanged) if p carries no force.
fn rescale_to_force(p: &mut [f64], w: f64, area: f64) -> bool {
    let total: f64 = p.iter().sum::<f64>() * area;
    if total > 0.0 {
        let s = w / total;
        for pk in p.iter_mut() {
            *pk *= s;
        }
        true
    } else {
        false
    }
}

/// Σ|p − p_old| / Σ p (0 for zero pressure).
fn relative_change(p: &[f64], p_old: &[f64]) -> f64 {
    let (mut diff, mut total) = (0.0, 0.0);
    for (&pk, &qk) in p.iter().zip(p_old) {
        diff += (pk - qk).abs();
        total += pk;
    }
    if total > 0.0 {
        diff / total
    } else {
        0.0
    }
}

/// p = α (−g)⁺ with the α that minimises the complementary energy along that direction, for the
/// deformed gap g of the current iterate (a good start for a prescribed approach). Uses
/// `scratch`.
fn restart_from_penetration(conv: &mut Convolution, g: &[f64], p: &mut [f64], scratch: &mut [f64]) {
    for (pk, &gk) in p.iter_mut().zip(g) {
        *pk = if gk < 0.0 { -gk } else { 0.0 };
    }
    conv.apply(p, scratch);
    let q2: f64 = p.iter().map(|q| q * q).sum();
    let qcq: f64 = p.iter().zip(scratch.iter()).map(|(q, c)| q * c).sum();
    let alpha = if qcq > 0.0 { q2 / qcq } else { 0.0 };
    for pk in p.iter_mut() {
        *pk *= alpha;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{e_star, rel};
    use railcontact::normal::hertz::{hertz_from_approach, hertz_from_load, HertzPatch};

    /// n × n grid centred on the origin with `across` elements over each Hertz diameter.
    fn hertz_grid(h: &HertzPatch, across: usize, n: usize) -> Grid {
        Grid::centred(n, n, 2.0 * h.a / across as f64, 2.0 * h.b / across as f64)
    }

    struct Errors {
        force: f64,
        approach: f64,
        p0: f64,
        area: f64,
    }

    fn compare(sol: &Solution, h: &HertzPatch) -> Errors {
        let p_max = sol.pressure.iter().copied().fold(0.0, f64::max);
        assert_eq!(sol.max_pressure, p_max);
        Errors {
            force: rel(sol.normal_force, h.normal_force),
            approach: rel(sol.approach, h.approach),
            p0: rel(p_max, h.p0),
            area: rel(sol.contact_area, h.area()),
        }
    }

    /// Hertz at prescribed approach and at prescribed load, 31 elements over each diameter on a
    /// 45 × 45 grid (element centres on the axes; the contact fills ±0.69 of the grid).
    ///
    /// Tolerances from the piecewise-constant, centre-collocated discretisation, h = 2a/31
    /// (observed values in brackets; `errors_decrease_with_refinement` scans 11…41 across):
    /// * force at a given approach, approach at a given load: integrated quantities, the edge
    ///   errors largely cancel; ≤ 7e−4 for 11…61 elements across whatever the alignment of the
    ///   grid with the edge, bound 1e−3 [2.8e−4, 1.9e−4];
    /// * peak pressure (centre element): ≤ 7e−4 from 21 across, 5e−3 at 11; bound 2e−3 [2.7e−4];
    /// * contact area, counted in whole elements: a lattice-point count of the ellipse
    ///   (fluctuates by ~1 % at this size) plus elements just outside the Hertz edge that carry a
    ///   little pressure (bias > 0); 0.8…2.3 % for 21…61 across depending on the alignment,
    ///   bound 3 % [0.83 %].
    fn check_hertz(curv_a: f64, curv_b: f64) {
        let es = e_star();
        let load = 50e3;
        let h = hertz_from_load(curv_a, curv_b, load, es).unwrap();
        let grid = hertz_grid(&h, 31, 45);
        let gap = grid.sample(|x, y| curv_a * x * x + curv_b * y * y);

        let by_load = solve(&grid, &gap, Target::Force(load), es, 1e-10).unwrap();
        let e = compare(&by_load, &h);
        eprintln!(
            "A/B {}: load  -> N {:.2e} delta {:.2e} p0 {:.2e} area {:.2e} ({} it)",
            curv_a / curv_b,
            e.force,
            e.approach,
            e.p0,
            e.area,
            by_load.iterations
        );
        assert!(e.force < 1e-12);
        assert!(e.approach < 1e-3 && e.p0 < 2e-3 && e.area < 3e-2);

        let h_d = hertz_from_approach(curv_a, curv_b, h.approach, es).unwrap();
        let by_delta = solve(&grid, &gap, Target::Approach(h.approach), es, 1e-10).unwrap();
        let e = compare(&by_delta, &h_d);
        eprintln!(
            "A/B {}: delta -> N {:.2e} delta {:.2e} p0 {:.2e} area {:.2e} ({} it)",
            curv_a / curv_b,
            e.force,
            e.approach,
            e.p0,
            e.area,
            by_delta.iterations
        );
        assert_eq!(by_delta.approach, h.approach);
        assert!(e.force < 1e-3 && e.p0 < 2e-3 && e.area < 3e-2);

        // The two solves are consistent with each other: the approach recovered under load
        // gives back the load.
        let back = solve(&grid, &gap, Target::Approach(by_load.approach), es, 1e-10).unwrap();
        assert!(rel(back.normal_force, load) < 1e-7, "{}", back.normal_force);
    }

    #[test]
    fn hertz_circle() {
        check_hertz(1.0, 1.0);
    }

    #[test]
    fn hertz_ellipse() {
        check_hertz(0.3, 1.0);
    }

    #[test]
    fn errors_decrease_with_refinement() {
        // Circle at the Hertz approach, 11 → 21 → 41 elements over the diameter: the RMS pressure
        // error over the elements loaded in either solution decreases (observed 3.5 %, 1.2 %,
        // 0.6 % of p0), and the force is within 1e−3 throughout (observed ≤ 7e−4: integrated
        // quantities converge much faster than the pointwise pressure at the edge).
        let es = e_star();
        let h = hertz_from_load(1.0, 1.0, 20e3, es).unwrap();
        let mut last = f64::INFINITY;
        for &across in &[11usize, 21, 41] {
            let grid = hertz_grid(&h, across, across + across / 2);
            let gap = grid.sample(|x, y| x * x + y * y);
            let s = solve(&grid, &gap, Target::Approach(h.approach), es, 1e-10).unwrap();
            let (mut sum2, mut count) = (0.0, 0);
            for j in 0..grid.ny {
                for i in 0..grid.nx {
                    let p = s.pressure[j * grid.nx + i];
                    let q = h.pressure_at(grid.x(i), grid.y(j));
                    if p > 0.0 || q > 0.0 {
                        sum2 += (p - q).powi(2);
                        count += 1;
                    }
                }
            }
            let rms = (sum2 / count as f64).sqrt() / h.p0;
            let e_force = rel(s.normal_force, h.normal_force);
            eprintln!("{across} across: RMS pressure error {rms:.2e}, force error {e_force:.2e}");
            assert!(rms < last && e_force < 1e-3);
            last = rms;
        }
        assert!(last < 1e-2);
    }

    /// Largest |deformed gap| on the loaded elements and largest penetration on the free ones,
    /// both relative to the rigid interpenetration δ − min h; also checks p ≥ 0 and the area.
    fn complementarity(grid: &Grid, gap: &[f64], s: &Solution) -> (f64, f64) {
        let u = surface_displacement(grid, &s.pressure, e_star()).unwrap();
        let depth = s.approach - gap.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(depth > 0.0);
        let (mut closed, mut penetration, mut n_c) = (0.0f64, 0.0f64, 0usize);
        for k in 0..grid.len() {
            let p = s.pressure[k];
            assert!(p >= 0.0 && p.is_finite());
            let sep = (gap[k] + u[k] - s.approach) / depth;
            if p > 0.0 {
                n_c += 1;
                closed = closed.max(sep.abs());
            } else {
                penetration = penetration.max(-sep);
            }
        }
        assert!(rel(s.contact_area, n_c as f64 * grid.element_area()) < 1e-15);
        (closed, penetration)
    }

    #[test]
    fn load_constraint_and_complementarity() {
        // Non-Hertzian gaps: two crowns near y = ±2 mm separated by a 12 µm ridge (two patches at low
        // load, one at high load), and a sphere with a one-element asperity 20 µm high (at
        // 200 N only that element is loaded — a one-element contact set under load control; at
        // higher loads the asperity is flattened into the sphere's contact).
        let es = e_star();
        let grid = Grid::centred(48, 40, 0.4e-3, 0.4e-3);
        let crowns = grid.sample(|x, y| 1.2 * x * x + 2.0 * (y.abs() - 3e-3).powi(2) + y * y);
        let mut asperity = grid.sample(|x, y| x * x + y * y);
        asperity[20 * 48 + 24] -= 20e-6;
        for (name, gap) in [("crowns", &crowns), ("asperity", &asperity)] {
            for &load in &[200.0, 2e3, 80e3] {
                for &tol in &[1e-6, 1e-10] {
                    let s = solve(&grid, gap, Target::Force(load), es, tol).unwrap();
                    // (2) Σ p ΔA = W to rounding, whatever the tolerance.
                    let sum = s.pressure.iter().sum::<f64>() * grid.element_area();
                    assert!(rel(sum, load) < 1e-13, "{name} {load} {tol}: {sum}");
                    assert_eq!(s.normal_force, load);
                    // (3) p ≥ 0, closed where loaded, no penetration where free: to the solver
                    // tolerance (observed |s| ≤ 0.3 tol (δ − min h), no penetration at all).
                    let (closed, pen) = complementarity(&grid, gap, &s);
                    eprintln!(
                        "{name} W {load}: tol {tol:.0e}: {} it, n_c {}, |s| {closed:.1e}, pen {pen:.1e}",
                        s.iterations,
                        (s.contact_area / grid.element_area()).round()
                    );
                    assert!(
                        closed < 10.0 * tol && pen < 10.0 * tol,
                        "{name} {load} {tol}"
                    );
                    if name == "crowns" {
                        // Ridge row (y = 0.2 mm): open at 200 N and 2 kN, closed at 80 kN.
                        let ridge = (0..48).any(|i| s.pressure[20 * 48 + i] > 0.0);
                        assert_eq!(ridge, load > 1e4, "ridge at {load} N");
                    }
                    // The same state at the recovered approach.
                    let d = solve(&grid, gap, Target::Approach(s.approach), es, tol).unwrap();
                    let (closed, pen) = complementarity(&grid, gap, &d);
                    assert!(
                        closed < 10.0 * tol && pen < 10.0 * tol,
                        "{name} {load} {tol}"
                    );
                    assert!(rel(d.normal_force, load) < 10.0 * tol);
                }
            }
        }
    }

    #[test]
    fn degenerate_inputs_give_no_nan() {
        let es = e_star();
        let grid = Grid::centred(16, 12, 1e-3, 1e-3);
        let gap = grid.sample(|x, y| 1e-4 + x * x + y * y);
        let finite = |s: &Solution| {
            s.pressure.iter().all(|p| p.is_finite() && *p >= 0.0)
                && s.normal_force.is_finite()
                && s.approach.is_finite()
                && s.contact_area.is_finite()
        };
        // Zero load: no pressure, approach = first touch.
        let s = solve(&grid, &gap, Target::Force(0.0), es, 1e-10).unwrap();
        assert!(finite(&s) && s.normal_force == 0.0 && s.contact_area == 0.0);
        let min_gap = gap.iter().copied().fold(f64::INFINITY, f64::min);
        assert_eq!(s.approach, min_gap);
        // Approach that never closes the gap, and exactly touching.
        for &d in &[0.0, 0.5e-4, min_gap] {
            let s = solve(&grid, &gap, Target::Approach(d), es, 1e-10).unwrap();
            assert!(finite(&s) && s.normal_force == 0.0 && s.iterations == 0);
        }
        // A gap that never closes anywhere: zero under any approach, an error under load.
        let never = vec![f64::INFINITY; grid.len()];
        let s = solve(&grid, &never, Target::Approach(1.0), es, 1e-10).unwrap();
        assert!(finite(&s) && s.normal_force == 0.0);
        let s = solve(&grid, &never, Target::Force(0.0), es, 1e-10).unwrap();
        assert!(finite(&s) && s.normal_force == 0.0);
        assert!(matches!(
            solve(&grid, &never, Target::Force(1e3), es, 1e-10),
            Err(SolveError::Input(_))
        ));
        // Partly non-contacting elements (+inf) are simply never loaded.
        let mut holed = gap.clone();
        for (k, h) in holed.iter_mut().enumerate() {
            if k % 3 == 0 {
                *h = f64::INFINITY;
            }
        }
        let s = solve(&grid, &holed, Target::Force(1e3), es, 1e-10).unwrap();
        assert!(finite(&s));
        assert!(s.pressure.iter().step_by(3).all(|&p| p == 0.0));
        // Flat punch-like gap (all equal): load spreads over the whole grid, finite.
        let flat = vec![0.0; grid.len()];
        let s = solve(&grid, &flat, Target::Force(1e3), es, 1e-10).unwrap();
        assert!(finite(&s) && s.contact_area == grid.len() as f64 * grid.element_area());
        // Single element.
        let one = Grid::centred(1, 1, 1e-3, 1e-3);
        let s = solve(&one, &[0.0], Target::Force(1e3), es, 1e-10).unwrap();
        assert!(finite(&s) && rel(s.pressure[0], 1e9) < 1e-15);
        assert!(
            rel(
                s.approach,
                1e9 * influence_coefficient(1e-3, 1e-3, 0.0, 0.0, es)
            ) < 1e-12
        );
        // Invalid inputs are errors, not NaN.
        assert!(solve(&grid, &gap, Target::Force(f64::NAN), es, 1e-10).is_err());
        assert!(solve(&grid, &gap, Target::Force(-1.0), es, 1e-10).is_err());
        assert!(solve(&grid, &gap, Target::Approach(f64::NAN), es, 1e-10).is_err());
        assert!(solve(&grid, &gap, Target::Force(1e3), 0.0, 1e-10).is_err());
        assert!(solve(&grid, &gap, Target::Force(1e3), es, 0.0).is_err());
        assert!(solve(&grid, &gap[1..], Target::Force(1e3), es, 1e-10).is_err());
        let mut bad = gap.clone();
        bad[5] = f64::NAN;
        assert!(solve(&grid, &bad, Target::Force(1e3), es, 1e-10).is_err());
        let empty = Grid::centred(0, 4, 1e-3, 1e-3);
        assert!(solve(&empty, &[], Target::Force(1e3), es, 1e-10).is_err());
    }

    #[test]
    fn a_solver_gives_the_same_answers_again() {
        // Plans, kernel and buffers are kept between solves: a second solve on the same solver,
        // after one of another kind, equals a fresh solver's answer bit for bit.
        let es = e_star();
        let grid = Grid::centred(24, 20, 0.5e-3, 0.5e-3);
        let gap = grid.sample(|x, y| 0.5 * x * x + y * y);
        let mut solver = Solver::new(grid, es).unwrap();
        assert_eq!((solver.grid(), solver.e_star()), (&grid, es));
        let first = solver.solve(&gap, Target::Force(10e3), 1e-10).unwrap();
        let other = solver
            .solve(&gap, Target::Approach(first.approach), 1e-10)
            .unwrap();
        assert!(rel(other.normal_force, 10e3) < 1e-7);
        let again = solver.solve(&gap, Target::Force(10e3), 1e-10).unwrap();
        assert_eq!(again, first);
        assert_eq!(
            solve(&grid, &gap, Target::Force(10e3), es, 1e-10).unwrap(),
            first
        );
        let u = solver.displacement(&first.pressure).unwrap();
        assert_eq!(u, surface_displacement(&grid, &first.pressure, es).unwrap());
        assert!(solver.displacement(&first.pressure[1..]).is_err());
    }

    /// Release-mode timing of the oracle on n × n grids (Hertz circle, diameter over 2/3 of the
    /// grid): `cargo test --release -p railcontact-halfspace --lib timing -- --ignored
    /// --nocapture`.
    #[test]
    #[ignore]
    fn timing_release() {
        let es = e_star();
        for &n in &[64usize, 100, 128, 200, 256] {
            for &(ca, cb) in &[(1.0, 1.0), (0.3, 1.0)] {
                let h = hertz_from_load(ca, cb, 50e3, es).unwrap();
                let across = (2 * n) as f64 / 3.0;
                let grid = Grid::centred(n, n, 2.0 * h.a / across, 2.0 * h.b / across);
                let gap = grid.sample(|x, y| ca * x * x + cb * y * y);
                let t0 = std::time::Instant::now();
                let s = solve(&grid, &gap, Target::Force(50e3), es, 1e-10).unwrap();
                let t1 = t0.elapsed();
                let t0 = std::time::Instant::now();
                let d = solve(&grid, &gap, Target::Approach(h.approach), es, 1e-10).unwrap();
                let t2 = t0.elapsed();
                let pm = s.pressure.iter().copied().fold(0.0, f64::max);
                eprintln!(
                    "{n}x{n} A/B {:.1}: by load {:.3} s ({} it, dδ/δ {:.1e}, dp0/p0 {:.1e}, \
                     dA/A {:.1e}); by approach {:.3} s ({} it, dN/N {:.1e})",
                    ca / cb,
                    t1.as_secs_f64(),
                    s.iterations,
                    (s.approach - h.approach) / h.approach,
                    (pm - h.p0) / h.p0,
                    (s.contact_area - h.area()) / h.area(),
                    t2.as_secs_f64(),
                    d.iterations,
                    (d.normal_force - h.normal_force) / h.normal_force,
                );
            }
        }
    }
}
