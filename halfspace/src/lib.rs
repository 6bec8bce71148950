//! Exact contact of two elastic half-spaces: the validation oracle of railcontact's fast normal
//! models (frictionless normal contact, below) and tangential models (steady rolling with
//! friction on a given pressure, [`solve_rolling`]).
//!
//! Kalker's normal problem ("NORM"; Kalker 1990, *Three-dimensional elastic bodies in rolling
//! contact*, Kluwer, Dordrecht) for two bodies of the **same material** (quasi-identical, so the
//! normal problem decouples from the tangential one): on a rectangular grid of uniformly loaded
//! elements, find the pressure p ≥ 0 such that the deformed gap
//!
//! ```text
//! s = h + u(p) − δ ≥ 0,     p ≥ 0,     p · s = 0      (element by element)
//! ```
//!
//! with h the undeformed gap, δ the rigid approach and u the combined surface displacement of the
//! two bodies (Boussinesq), u(x) = 1/(π E*) ∫∫ p(ξ)/|x − ξ| dA. Either δ or the total force
//! W = ∫∫ p dA is prescribed.
//!
//! This is an off-line **oracle** for the fast non-elliptic models (strips, KP, STRIPES, ANALYN)
//! and for models that couple strips through the half-space: it is not part of the contact
//! element's per-step path (nor of its FMUs), and it allocates freely.
//!
//! # Use
//!
//! ```
//! use railcontact::normal::hertz::contact_modulus;
//! use railcontact_halfspace::{Grid, Solver, Target};
//!
//! // A sphere-like gap h = (x² + y²)/(2R), R = 0.5 m, on 40 × 40 elements of 0.25 mm.
//! let grid = Grid::centred(40, 40, 0.25e-3, 0.25e-3);
//! let gap = grid.sample(|x, y| x * x + y * y);
//! let mut solver = Solver::new(grid, contact_modulus(210e9, 0.3)).unwrap();
//! let by_force = solver.solve(&gap, Target::Force(10e3), 1e-10).unwrap();
//! assert_eq!(by_force.normal_force, 10e3);
//! // The same solver (same FFT plans) at the approach found.
//! let by_approach = solver.solve(&gap, Target::Approach(by_force.approach), 1e-10).unwrap();
//! assert!((by_approach.normal_force / 10e3 - 1.0).abs() < 1e-6);
//! println!(
//!     "{:.1} mm², {:.0} MPa",
//!     by_force.contact_area * 1e6,
//!     by_force.max_pressure / 1e6
//! );
//! ```
//!
//! * [`Grid`]: nx × ny elements of dx × dy, fields row-major (`j * nx + i`, x fastest);
//!   [`Grid::sample`] evaluates h(x, y) at the element centres.
//! * [`Solver::new`] plans the FFTs and transforms the influence coefficients of one grid and
//!   one contact modulus E*; [`Solver::solve`] takes the gap h [m] (+∞ where the surfaces can
//!   never touch), a [`Target`] (approach δ [m] or force W [N]) and the stopping tolerance, and
//!   returns a [`Solution`]: pressures [Pa], force [N], contact area [m²], peak pressure [Pa],
//!   approach [m] and iterations. [`Solver::displacement`] gives u = C * p for checking a
//!   solution (deformed gap h + u − δ).
//! * [`solve`] and [`surface_displacement`] do the same for a single call.
//!
//! # Method
//!
//! * **Influence coefficients.** Uniform pressure on a dx × dy element, displacement at another
//!   element's centre, closed form of Love (1929), "The stress produced in a semi-infinite solid
//!   by pressure on part of the boundary", Phil. Trans. R. Soc. A 228, 377–420; Johnson,
//!   *Contact Mechanics* (1985), Cambridge University Press, ch. 3 (uniform pressure on a
//!   rectangle). Written here as the integral of the Boussinesq kernel 1/r over the element: with
//!   the corner function `J(x, y) = ∫₀^x ∫₀^y dt ds / √(s² + t²) = x asinh(y/x) + y asinh(x/y)`
//!   (signed by quadrant), the coefficient for an offset (X, Y) between the field point and the
//!   element centre is `C = [J(X+a, Y+b) − J(X−a, Y+b) − J(X+a, Y−b) + J(X−a, Y−b)] / (π E*)`,
//!   a = dx/2, b = dy/2 ([`influence_coefficient`]).
//! * **Modulus.** E* is railcontact's contact modulus E/(2(1 − ν²))
//!   (`railcontact::normal::hertz::contact_modulus`): 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂, the
//!   combined compliance of both bodies. With that E* the Hertz formulas of
//!   `railcontact::normal::hertz` are the continuum limit of this solver (tested).
//! * **Matrix–vector product** u = C * p by the discrete-convolution FFT of Liu, Wang & Liu
//!   (2000), "A versatile method of discrete convolution and FFT (DC-FFT) for contact analyses",
//!   Wear 243, 101–111: the (2nx − 1) × (2ny − 1) coefficient block is wrapped onto a zero-padded
//!   periodic grid and the linear convolution is exact (no periodicity error). The padded sizes
//!   are the smallest even lengths ≥ 2n − 1 with prime factors 2, 3 and 5 only (200 × 200 →
//!   400 × 400); the transforms are real-to-complex along x (`realfft`) and complex along y
//!   (`rustfft`), planned once per [`Solver`].
//! * **Solver.** The constrained conjugate-gradient method of Polonsky & Keer (1999), "A numerical
//!   method for solving rough contact problems based on the multi-level multi-summation and
//!   conjugate gradient techniques", Wear 231, 206–219: CG on the current contact set,
//!   projection onto p ≥ 0, re-entry of penetrating free elements with a restart of the
//!   conjugate direction, and — for a prescribed force — the mean gap over the contact set as the
//!   running approach and a rescaling to Σ p ΔA = W at every iteration. Convergence is their
//!   criterion: the relative pressure change Σ|p − p_old| / Σ p ≤ `tol`.
//!
//! Known limits: half-space, small strain, frictionless, identical materials (no
//! normal–tangential coupling); piecewise-constant pressure, so the peak pressure and the contact
//! edge are resolved to O(element size) — see the tests for the error at ~30 elements across the
//! contact.

mod convolution;
mod grid;
mod influence;
mod rolling;
mod solver;
pub mod wheel_rail;

pub use grid::Grid;
pub use influence::influence_coefficient;
pub use rolling::{
    solve_rolling, solve_rolling_with_slip, tangential_influence, Rolling, RollingSolution,
};
pub use solver::{solve, surface_displacement, Solution, SolveError, Solver, Target};

#[cfg(test)]
mod test_support {
    use railcontact::normal::hertz::contact_modulus;

    /// |a − b| / |b|.
    pub fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    /// Steel on steel, E = 210 GPa, ν = 0.3 [Pa].
    pub fn e_star() -> f64 {
        contact_modulus(210e9, 0.3)
    }
}
