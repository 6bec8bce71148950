//! Exact steady rolling with dry friction: Kalker's tangential problem for quasi-identical
//! bodies on the grid of the normal solution.
//!
//! Kalker 1990, *Three-dimensional elastic bodies in rolling contact* (Kluwer), ch. 2 and 5:
//! two bodies of the same elastic material roll steadily; the normal pressure p is known (the
//! normal problem decouples), the tangential traction q (on the wheel) and the slip s [-] (per
//! unit rolling speed) satisfy on every loaded element
//!
//! ```text
//! s = w − ∂u/∂x,    w = (ξ − φ y, η + φ x),          rigid slip of the creepages ξ, η, φ
//! adhesion: s = 0, |q| ≤ μ p;      slip: q = −μ p s/|s|
//! ```
//!
//! with the material flowing from the leading edge (+x) to the trailing edge, and u the combined
//! tangential surface displacement of both bodies (Cerruti),
//!
//! ```text
//! u_x(x) = 1/(π G) ∫∫ [((1 − ν)/r + ν X²/r³) q_x + ν X Y/r³ q_y] dA,   (X, Y) = x − x'
//! u_y(x) = 1/(π G) ∫∫ [ν X Y/r³ q_x + ((1 − ν)/r + ν Y²/r³) q_y] dA.
//! ```
//!
//! The sign conventions are those of railcontact's FASTSIM (docs/conventions.md): a positive
//! creepage gives a negative force. Quasi-identity leaves out the normal displacement of the
//! tangential traction (zero for identical materials).
//!
//! # Discretisation
//!
//! Piecewise-constant tractions on the elements; the influence of a uniformly loaded element at
//! another element's centre in closed form from the corner functions of the three kernels:
//! ∂²F/∂X∂Y = 1/r for `J` (as in the normal problem), X²/r³ for Y asinh(X/|Y|), X Y/r³ for −r.
//! ∂u/∂x at an element is the difference to its leading neighbour, u(x + Δx) − u(x) over Δx
//! (Kalker's steady-state discretisation; first order in Δx), the displacement there taken from
//! the same influence coefficients whether or not that neighbour is loaded.
//!
//! # Solver
//!
//! Newton's method on the element equations with an active set (as Kalker's KOMBI): an adhering
//! element has s = 0 (two linear equations), a slipping one |q| = μp and q × s = 0 with q · s < 0;
//! after each step an adhering element whose traction exceeds μp slips (its traction projected
//! onto the bound) and a slipping one whose traction no longer opposes its slip adheres. It
//! starts from full adhesion and stops when the sets hold and every equation is met to `tol`
//! (slip relative to the largest rigid slip, tractions relative to μ × the peak pressure). Each
//! step factorises the dense Jacobian (2n unknowns for n loaded elements, LU ~(2n)³/3): an
//! off-line oracle for grids of up to ~1000 loaded elements.

use std::f64::consts::PI;

use nalgebra::{DMatrix, DVector};
use railcontact::error::{require_finite, require_non_negative, require_positive, InputError};

use crate::grid::Grid;
use crate::influence::corner_integral;
use crate::solver::SolveError;

/// Creepages and material of a steady rolling problem.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rolling {
    /// Longitudinal creepage ξ [-].
    pub xi: f64,
    /// Lateral creepage η [-].
    pub eta: f64,
    /// Spin creepage φ [1/m] about the grid's origin.
    pub phi: f64,
    /// Combined shear modulus G of the (identical) materials [Pa].
    pub shear_modulus: f64,
    /// Poisson's ratio ν [-].
    pub poisson_ratio: f64,
    /// Coefficient of friction μ [-].
    pub friction: f64,
}

/// Tractions and totals of a steady rolling solution.
#[derive(Debug, Clone, PartialEq)]
pub struct RollingSolution {
    /// Element tractions on the wheel along x, row-major like the pressure [Pa].
    pub traction_x: Vec<f64>,
    /// Element tractions on the wheel along y [Pa].
    pub traction_y: Vec<f64>,
    /// Whether a loaded element slips.
    pub slipping: Vec<bool>,
    /// Element slip s = w − ∂u/∂x along x and y (sliding distance per distance rolled, 0 in
    /// adhesion to the tolerance) [-].
    pub slip_x: Vec<f64>,
    pub slip_y: Vec<f64>,
    /// Dissipation per distance rolled, −Σ q·s ΔA (the frictional power over the rolling
    /// speed, Tγ) [N].
    pub t_gamma: f64,
    /// Work of the tractions on the rigid slip per distance rolled, −Σ q·w ΔA [N]: equal to
    /// `t_gamma` in the continuum (steady rolling), the two differ by the discretisation.
    pub rigid_work: f64,
    /// Force Σ q_x ΔA [N].
    pub fx: f64,
    /// Force Σ q_y ΔA [N].
    pub fy: f64,
    /// Moment about the grid's origin Σ (x q_y − y q_x) ΔA [N·m].
    pub mz: f64,
    /// Share of the loaded elements that adhere [-].
    pub adhesion_fraction: f64,
    /// Newton steps used.
    pub iterations: usize,
}

/// Influence coefficients (A_xx, A_xy, A_yy) [m/Pa]: the combined displacement of both bodies at
/// offset (x, y) from the centre of a dx × dy element carrying a unit uniform shear traction.
pub fn tangential_influence(dx: f64, dy: f64, x: f64, y: f64, g: f64, nu: f64) -> [f64; 3] {
    let (a, b) = (0.5 * dx, 0.5 * dy);
    let corners = |f: &dyn Fn(f64, f64) -> f64| {
        f(x + a, y + b) - f(x - a, y + b) - f(x + a, y - b) + f(x - a, y - b)
    };
    let xx = |u: f64, v: f64| (1.0 - nu) * corner_integral(u, v) + nu * along(v, u);
    let yy = |u: f64, v: f64| (1.0 - nu) * corner_integral(u, v) + nu * along(u, v);
    let xy = |u: f64, v: f64| -nu * u.hypot(v);
    let scale = 1.0 / (PI * g);
    [
        corners(&xx) * scale,
        corners(&xy) * scale,
        corners(&yy) * scale,
    ]
}

/// t asinh(s/|t|), zero at t = 0: the corner function of s²/r³ (∂²/∂s∂t).
fn along(t: f64, s: f64) -> f64 {
    if t == 0.0 {
        0.0
    } else {
        t * (s / t.abs()).asinh()
    }
}

/// Newton steps before giving up.
const MAX_ITERATIONS: usize = 100;

/// Solves the steady rolling problem on `grid` under the normal `pressure` (row-major, ≥ 0 [Pa]).
/// `tol`: the largest equation residual at the end, relative (see the module's text).
pub fn solve_rolling(
    grid: &Grid,
    pressure: &[f64],
    rolling: &Rolling,
    tol: f64,
) -> Result<RollingSolution, SolveError> {
    require_finite("xi", rolling.xi)?;
    require_finite("eta", rolling.eta)?;
    require_finite("phi", rolling.phi)?;
    solve_rolling_with_slip(
        grid,
        pressure,
        |x, y| [rolling.xi - rolling.phi * y, rolling.eta + rolling.phi * x],
        rolling,
        tol,
    )
}

/// [`solve_rolling`] with the rigid slip w(x, y) [-] of each element given by `rigid_slip` at its
/// centre (the creepages of `rolling` are not used; its material and friction are): the exact
/// theory on a surface whose rigid slip is not that of one plane (Kalker's w = (ξ − φy, η + φx)),
/// e.g. each element's own rolling radius, contact angle and spin on a curved wheel–rail patch.
pub fn solve_rolling_with_slip(
    grid: &Grid,
    pressure: &[f64],
    rigid_slip: impl Fn(f64, f64) -> [f64; 2],
    rolling: &Rolling,
    tol: f64,
) -> Result<RollingSolution, SolveError> {
    grid.validate()?;
    if pressure.len() != grid.len() {
        return Err(InputError::new(
            "pressure",
            pressure.len() as f64,
            "needs one value per grid element",
        )
        .into());
    }
    for &p in pressure {
        require_non_negative("pressure", p)?;
    }
    require_positive("shear_modulus", rolling.shear_modulus)?;
    require_non_negative("poisson_ratio", rolling.poisson_ratio)?;
    require_positive("friction", rolling.friction)?;
    require_positive("tol", tol)?;

    let Grid { nx, ny, dx, dy, .. } = *grid;
    let (g, nu, mu) = (
        rolling.shear_modulus,
        rolling.poisson_ratio,
        rolling.friction,
    );
    let loaded: Vec<usize> = (0..grid.len()).filter(|&k| pressure[k] > 0.0).collect();
    let n = loaded.len();
    let rigid: Vec<[f64; 2]> = loaded
        .iter()
        .map(|&k| {
            let w = rigid_slip(grid.x(k % nx), grid.y(k / nx));
            for (name, v) in [("rigid slip x", w[0]), ("rigid slip y", w[1])] {
                require_finite(name, v)?;
            }
            Ok(w)
        })
        .collect::<Result<_, InputError>>()?;
    let bound: Vec<f64> = loaded.iter().map(|&k| mu * pressure[k]).collect();
    // Influence coefficients per offset field − source: columns −(nx − 1) … nx (one beyond, for
    // the leading neighbour), rows −(ny − 1) … ny − 1.
    let (wi, wj) = (2 * nx, 2 * ny - 1);
    let mut table = vec![[0.0; 3]; wi * wj];
    for (t, entry) in table.iter_mut().enumerate() {
        let di = (t % wi) as f64 - (nx as f64 - 1.0);
        let dj = (t / wi) as f64 - (ny as f64 - 1.0);
        *entry = tangential_influence(dx, dy, di * dx, dj * dy, g, nu);
    }
    let at = |di: usize, dj: usize| table[dj * wi + di];
    // s = w − M q: M's 2 × 2 block (a, b) is the x-difference of the displacement at element a
    // and its leading neighbour due to b's traction, over Δx.
    let mut m = DMatrix::<f64>::zeros(2 * n, 2 * n);
    for (a, &ka) in loaded.iter().enumerate() {
        for (b, &kb) in loaded.iter().enumerate() {
            // Offsets shifted to table indices (field a, source b).
            let di = ka % nx + nx - 1 - kb % nx;
            let dj = ka / nx + ny - 1 - kb / nx;
            let (here, ahead) = (at(di, dj), at(di + 1, dj));
            let d = [0, 1, 2].map(|c| (ahead[c] - here[c]) / dx);
            m[(2 * a, 2 * b)] = d[0];
            m[(2 * a, 2 * b + 1)] = d[1];
            m[(2 * a + 1, 2 * b)] = d[1];
            m[(2 * a + 1, 2 * b + 1)] = d[2];
        }
    }
    let w = DVector::from_iterator(2 * n, rigid.iter().flat_map(|r| *r));
    let slip_scale = w.amax().max(f64::MIN_POSITIVE);
    let traction_scale = bound
        .iter()
        .copied()
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);

    let mut q = DVector::<f64>::zeros(2 * n);
    let mut slipping = vec![false; n];
    let mut jacobian = DMatrix::<f64>::zeros(2 * n, 2 * n);
    let mut residual = DVector::<f64>::zeros(2 * n);
    let mut iterations = 0;
    loop {
        let s = &w - &m * &q;
        // Set changes first: an adhering element above its bound slips (projected onto it), a
        // slipping one whose traction no longer opposes its slip adheres.
        let mut changed = false;
        for a in 0..n {
            let (r0, r1) = (2 * a, 2 * a + 1);
            let norm = q[r0].hypot(q[r1]);
            if !slipping[a] && norm > bound[a] * (1.0 + tol) {
                slipping[a] = true;
                changed = true;
                q[r0] *= bound[a] / norm;
                q[r1] *= bound[a] / norm;
            } else if slipping[a] && q[r0] * s[r0] + q[r1] * s[r1] > 0.0 {
                slipping[a] = false;
                changed = true;
            }
        }
        if changed {
            continue;
        }
        // Residuals and the Newton system: s_a = 0 where adhering; |q_a| = μp_a and
        // q_a × s_a = 0 where slipping.
        let mut largest: f64 = 0.0;
        jacobian.copy_from(&m);
        jacobian.neg_mut();
        for a in 0..n {
            let (r0, r1) = (2 * a, 2 * a + 1);
            let (sx, sy) = (s[r0], s[r1]);
            if !slipping[a] {
                residual[r0] = sx;
                residual[r1] = sy;
                largest = largest.max(sx.abs().max(sy.abs()) / slip_scale);
                continue;
            }
            let (qx, qy) = (q[r0], q[r1]);
            let norm = qx.hypot(qy);
            let cross = qx * sy - qy * sx;
            residual[r0] = norm - bound[a];
            residual[r1] = cross;
            for c in 0..2 * n {
                jacobian[(r1, c)] = -qx * m[(r1, c)] + qy * m[(r0, c)];
                jacobian[(r0, c)] = 0.0;
            }
            jacobian[(r0, r0)] = qx / norm;
            jacobian[(r0, r1)] = qy / norm;
            jacobian[(r1, r0)] += sy;
            jacobian[(r1, r1)] -= sx;
            let s_norm = sx.hypot(sy).max(f64::MIN_POSITIVE);
            largest = largest
                .max((norm - bound[a]).abs() / traction_scale)
                .max(cross.abs() / (norm * s_norm));
        }
        if largest <= tol {
            break;
        }
        iterations += 1;
        if iterations > MAX_ITERATIONS {
            return Err(SolveError::NotConverged {
                iterations,
                change: largest,
            });
        }
        let step = jacobian
            .clone()
            .lu()
            .solve(&(-&residual))
            .ok_or(SolveError::NotConverged {
                iterations,
                change: largest,
            })?;
        q += step;
    }

    let area = grid.element_area();
    let s = &w - &m * &q;
    let mut traction_x = vec![0.0; grid.len()];
    let mut traction_y = vec![0.0; grid.len()];
    let mut slip_x = vec![0.0; grid.len()];
    let mut slip_y = vec![0.0; grid.len()];
    let mut slip_field = vec![false; grid.len()];
    let (mut fx, mut fy, mut mz) = (0.0, 0.0, 0.0);
    let (mut t_gamma, mut rigid_work) = (0.0, 0.0);
    for (a, &k) in loaded.iter().enumerate() {
        let (x, y) = (grid.x(k % nx), grid.y(k / nx));
        let (qx, qy) = (q[2 * a], q[2 * a + 1]);
        traction_x[k] = qx;
        traction_y[k] = qy;
        if slipping[a] {
            slip_x[k] = s[2 * a];
            slip_y[k] = s[2 * a + 1];
            t_gamma -= (qx * s[2 * a] + qy * s[2 * a + 1]) * area;
        }
        rigid_work -= (qx * w[2 * a] + qy * w[2 * a + 1]) * area;
        slip_field[k] = slipping[a];
        fx += qx * area;
        fy += qy * area;
        mz += (x * qy - y * qx) * area;
    }
    let adhering = slipping.iter().filter(|s| !**s).count();
    Ok(RollingSolution {
        traction_x,
        traction_y,
        slipping: slip_field,
        slip_x,
        slip_y,
        t_gamma,
        rigid_work,
        fx,
        fy,
        mz,
        adhesion_fraction: if n > 0 {
            adhering as f64 / n as f64
        } else {
            0.0
        },
        iterations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn influence_is_symmetric_and_reduces_to_the_point_force_far_away() {
        let (g, nu, d) = (80e9, 0.28, 1e-3);
        let [xx, xy, yy] = tangential_influence(d, d, 0.3, 0.4, g, nu);
        let r: f64 = 0.5;
        let point = |c: f64| d * d / (PI * g) * c;
        assert!((xx / point((1.0 - nu) / r + nu * 0.09 / r.powi(3)) - 1.0).abs() < 1e-5);
        assert!((yy / point((1.0 - nu) / r + nu * 0.16 / r.powi(3)) - 1.0).abs() < 1e-5);
        assert!((xy / point(nu * 0.12 / r.powi(3)) - 1.0).abs() < 1e-5);
        // Self influence: A_xy vanishes, A_xx = A_yy on a square element.
        let [xx, xy, yy] = tangential_influence(d, d, 0.0, 0.0, g, nu);
        assert!(xy.abs() < 1e-30 && ((xx - yy) / xx).abs() < 1e-14);
    }

    /// A Hertz circle of radius 5 mm (p0 = 1 GPa, G = 80 GPa, ν = 0.28, μ = 0.3) on 15 × 15
    /// elements: at ξ = 1e−6 (full adhesion) Kalker's linear theory Fx = −G c² C11 ξ within 4 %,
    /// the lateral creepage likewise with C22 (measured +1.6 % and +2.2 %; at 9, 25 and 35
    /// elements across +11 %, +0.4 % and +1.7 % for Fx — the loaded elements' outline, not the
    /// element size, sets most of the difference); full slip at ξ = 0.01 with every element
    /// slipping and |Fx| within 1e−3 of μN (the slip turns slightly from x near the edges:
    /// −1.7e−4 measured).
    #[test]
    fn hertz_circle_follows_kalker_and_coulomb() {
        let (g, nu, mu, a) = (80e9, 0.28, 0.3, 5e-3);
        let d = 2.0 * a / 15.0;
        let grid = Grid::centred(15, 15, d, d);
        let p = grid.sample(|x, y| 1e9 * (1.0 - (x * x + y * y) / (a * a)).max(0.0).sqrt());
        let normal: f64 = p.iter().sum::<f64>() * d * d;
        let solve = |xi, eta| {
            let rolling = Rolling {
                xi,
                eta,
                phi: 0.0,
                shear_modulus: g,
                poisson_ratio: nu,
                friction: mu,
            };
            solve_rolling(&grid, &p, &rolling, 1e-10).expect("solves")
        };
        let c = railcontact::tangential::kalker::creep_coefficients(a, a, nu).unwrap();
        let adhesion = solve(1e-6, 0.0);
        assert_eq!(adhesion.adhesion_fraction, 1.0);
        let kalker = -g * a * a * c.c11 * 1e-6;
        assert!(
            (adhesion.fx / kalker - 1.0).abs() < 0.04,
            "{} vs {kalker}",
            adhesion.fx
        );
        assert!(adhesion.fy.abs() < 1e-9 * adhesion.fx.abs());
        let lateral = solve(0.0, 1e-6);
        let kalker = -g * a * a * c.c22 * 1e-6;
        assert!(
            (lateral.fy / kalker - 1.0).abs() < 0.04,
            "{} vs {kalker}",
            lateral.fy
        );
        let sliding = solve(1e-2, 0.0);
        assert_eq!(sliding.adhesion_fraction, 0.0);
        assert!(
            (-sliding.fx / (mu * normal) - 1.0).abs() < 1e-3,
            "{}",
            sliding.fx
        );
    }
}
