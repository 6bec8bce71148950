//! The exact solution of one wheel on its rail: the yardstick of the wheel's forces.
//!
//! Kalker's planar theory as CONTACT sets it up for a wheel–rail patch (Vollebregt 2020,
//! "Detailed wheel/rail geometry processing using the planar contact approach", Vehicle System
//! Dynamics 60(4)): the contact plane passes through the weighted centre of the (vertical) rigid
//! interpenetration d(x, y) at the wheel's actual lowering and is inclined by the weighted mean of
//! the rail's inclination, both weighted by d² integrated along the rolling direction (with
//! d(x, y) = d_y − A_y x², ∫ d² dx = (16/15) d_y^{5/2}/√A_y); the pressure is the exact
//! half-space solution of the undeformed gap measured normal to that plane ([`crate::solve`]), at
//! the normal force that carries the wheel load along the plane's normal; the lowering is
//! iterated until the plane and the exact approach agree.
//!
//! From it: the lateral force of the planar solution, Q tan γ; the lateral force of the same
//! pressure acting on the curved surface, each row (lateral strip of elements) along its own
//! rail normal, Q Σ F_j sin γ_j / Σ F_j cos γ_j; and the exact steady rolling solution with each
//! element's rigid slip taken from the wheelset's motion at its own point of the wheel and rail
//! surfaces (its rolling radius, contact angle and spin; [`crate::solve_rolling_with_slip`]),
//! the tractions of each row along its own contact axes — the planar elastic problem with the
//! kinematics of the actual surfaces, which CONTACT's conformal solution follows within a few
//! per cent of μN on tread patches.
//!
//! Limits: one plane for the wheel (CONTACT combines patches less than 8 mm apart into one; two
//! separate regions further apart are not one planar problem); identical materials; the grid's
//! element size (0.2 mm as CONTACT's reference solutions for the normal problem, coarser for the
//! rolling problem's dense Newton systems).

use railcontact::geometry::search::{StripPoints, WheelOnRail};
use railcontact::geometry::strips::{StripGeometry, MAX_STRIPS};
use railcontact::normal::hertz::contact_modulus;
use railcontact::wheelset::SideResult;

use crate::{
    solve, solve_rolling, solve_rolling_with_slip, Grid, Rolling, RollingSolution, Solution,
    SolveError,
};

/// Lateral sampling of the interpenetration for the plane's weights [m].
const WEIGHT_STEP: f64 = 1e-5;

/// Lowering iterations (plane → exact approach → plane); two settle the angle to 1e−7 rad.
const LOWERING_ITERATIONS: usize = 4;

/// Margin of the grid beyond the interpenetration region, laterally and along x [m].
const MARGIN: f64 = 1.5e-3;

/// The plane of the planar theory at one lowering: its rail point (wheelset-frame lateral),
/// inclination in the track frame and the interpenetration's extent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarReference {
    /// Wheelset-frame lateral of the weighted centre [m].
    pub lateral: f64,
    /// Its rail coordinate (mounted rail frame, towards the field side) [m].
    pub y_rail: f64,
    /// Weighted mean inclination of the rail (track frame, positive towards the flange) [rad].
    pub angle: f64,
    /// The wheel's rolling radius at the weighted centre [m].
    pub rolling_radius: f64,
    /// Lateral extent of the interpenetration (wheelset frame) [m].
    pub extent: (f64, f64),
    /// Separate runs of interpenetration (regions) at this lowering.
    pub regions: usize,
    /// Largest vertical interpenetration [m].
    pub depth: f64,
}

/// CONTACT's contact reference of the wheel `geometry` (searched at its pose; samples filled to
/// at least `dz`) lowered by `dz` [m]: see the module's text. `None` where nothing interpenetrates.
pub fn planar_reference(geometry: &WheelOnRail, dz: f64) -> Option<PlanarReference> {
    let (lo, hi) = geometry.scan_range();
    let n = ((hi - lo) / WEIGHT_STEP).ceil() as usize;
    let roll = roll_of(geometry, 0.5 * (lo + hi));
    let (mut total, mut w_sum, mut angle_sum) = (0.0, 0.0, 0.0);
    let (mut first, mut last) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut regions = 0;
    let mut inside = false;
    let mut deepest: f64 = 0.0;
    for k in 0..=n {
        let w = lo + (hi - lo) * k as f64 / n as f64;
        let depth = dz - geometry.gap_at(w);
        if depth <= 0.0 {
            inside = false;
            continue;
        }
        if !inside {
            regions += 1;
            inside = true;
        }
        let point = geometry.point_at_lateral(w);
        let weight = depth * depth * depth.sqrt() / point.curv_a.sqrt();
        total += weight;
        w_sum += weight * w;
        angle_sum += weight * (geometry.plane_angle_at(w) - roll);
        first = first.min(w);
        last = last.max(w);
        deepest = deepest.max(depth);
    }
    (total > 0.0).then(|| {
        let lateral = w_sum / total;
        let point = geometry.point_at_lateral(lateral);
        PlanarReference {
            lateral,
            y_rail: point.y_rail,
            angle: angle_sum / total,
            rolling_radius: point.rolling_radius,
            extent: (first, last),
            regions,
            depth: deepest,
        }
    })
}

/// The grid of square elements of side `element` [m] on the strips' rows: `ny` rows from the
/// in-plane lateral `y0` [m], and the fewest columns that cover 2 `half_x` [m], centred on the
/// longitudinal position `x_mid` [m].
pub fn strip_grid(element: f64, ny: usize, y0: f64, half_x: f64, x_mid: f64) -> Grid {
    let nx = (2.0 * half_x / element).ceil() as usize;
    Grid {
        nx,
        ny,
        dx: element,
        dy: element,
        x0: x_mid - 0.5 * nx as f64 * element,
        y0,
    }
}

/// The undeformed gap of the strips `geom` on `grid`, one grid row a strip, row after row:
/// h(x_i, s_j) = f_j − `base` + A_j (x_i − x_c,j)² [m], with f_j the strip's lowest gap, A_j its
/// longitudinal curvature [1/m] and x_c,j the position of its lowest point [m].
pub fn strip_gap(geom: &StripGeometry, grid: &Grid, base: f64) -> Vec<f64> {
    (0..grid.ny)
        .flat_map(|j| {
            (0..grid.nx)
                .map(move |i| geom.f[j] - base + geom.curv_a[j] * (grid.x(i) - geom.x_c[j]).powi(2))
        })
        .collect()
}

/// A model's creep force on one wheel in track axes, to set against [`CreepForces`]: the
/// wheel's longitudinal force, and its lateral force less its patches' normal forces along
/// their normals (−σ N sin γ each) on side `sigma` (+1 right, −1 left); (x, y) [N].
pub fn model_creep_force(side: &SideResult, sigma: f64) -> (f64, f64) {
    let normal_y: f64 = side
        .all_patches()
        .iter()
        .map(|p| -sigma * p.fn_ * p.contact_angle.sin())
        .sum();
    (side.force[0], side.force[1] - normal_y)
}

/// The roll angle of the geometry's pose (wheelset frame less track frame) [rad].
fn roll_of(geometry: &WheelOnRail, w: f64) -> f64 {
    let plane = geometry.contact_plane(w, geometry.gap_at(w));
    plane.gamma - plane.gamma_rail
}

/// Element sizes of [`ExactWheel::planar_t_gamma`]'s solutions [m] (whole multiples of the
/// 0.2 mm normal solution's).
pub const T_GAMMA_ELEMENTS: [f64; 3] = [0.4e-3, 0.6e-3, 0.8e-3];
/// CONTACT's element size, to which [`ExactWheel::planar_t_gamma`] extrapolates [m].
pub const CONTACT_ELEMENT: f64 = 0.2e-3;

/// Tγ of an exact rolling solution extrapolated in the element size.
#[derive(Debug, Clone, PartialEq)]
pub struct DissipationEstimate {
    /// At [`CONTACT_ELEMENT`] [N].
    pub t_gamma: f64,
    /// Per element size of [`T_GAMMA_ELEMENTS`]: (size [m], Tγ [N], work on the rigid slip
    /// per metre rolled [N]).
    pub per_element: Vec<(f64, f64, f64)>,
    /// The solution on the finest elements (the first of [`T_GAMMA_ELEMENTS`]) and its grid.
    pub finest: (Grid, RollingSolution),
}

/// The exact planar solution of one wheel.
#[derive(Debug, Clone)]
pub struct ExactWheel {
    /// The plane (at the final lowering).
    pub reference: PlanarReference,
    /// The wheel's lowering from its nominal height [m].
    pub lowering: f64,
    /// The grid on the plane (x along the rolling direction, absolute; y the in-plane lateral).
    pub grid: Grid,
    /// The exact pressure.
    pub solution: Solution,
    /// Per grid row: the rail and wheel points (lateral, rail coordinate, contact angle, rolling
    /// radius).
    pub rows: StripPoints,
    /// The vertical wheel load carried [N].
    pub load: f64,
}

/// Kinematics of the wheelset for [`ExactWheel::rolling`] (as `Creepages::Kinematic`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelsetMotion {
    pub vx: f64,
    pub vy: f64,
    pub yaw_rate: f64,
    pub omega: f64,
    /// Yaw angle of the wheelset [rad] (the axle's direction).
    pub yaw: f64,
}

/// Creep forces of the exact rolling solution on the actual surfaces, track axes [N].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CreepForces {
    /// Longitudinal (track x) [N].
    pub fx: f64,
    /// Lateral (track y) component of the tangential tractions [N].
    pub fy: f64,
    /// μN of the solution [N].
    pub mu_n: f64,
}

impl ExactWheel {
    /// The exact planar solution of the right (`right`) or left wheel described by `geometry`
    /// (searched at the wheelset's pose) carrying the vertical load `load` [N], starting from the
    /// lowering `dz` [m] (a model's), on elements of `element` × `element` [m], for materials of
    /// Young's modulus `e` [Pa] and Poisson's ratio `nu`.
    pub fn solve(
        geometry: &WheelOnRail,
        dz: f64,
        load: f64,
        element: f64,
        (e, nu): (f64, f64),
    ) -> Result<Self, SolveError> {
        let mut geometry = geometry.clone();
        let mut dz = dz;
        let mut result = None;
        for _ in 0..LOWERING_ITERATIONS {
            geometry.fill_to_level(dz + 2e-4);
            let Some(reference) = planar_reference(&geometry, dz) else {
                break;
            };
            let roll = roll_of(&geometry, reference.lateral);
            let plane = geometry.contact_plane_inclined(
                reference.lateral,
                geometry.gap_at(reference.lateral),
                reference.angle + roll,
            );
            let (w_lo, w_hi) = (reference.extent.0 - MARGIN, reference.extent.1 + MARGIN);
            let (s_a, s_b) = (
                geometry.plane_coordinate_of(&plane, w_lo),
                geometry.plane_coordinate_of(&plane, w_hi),
            );
            let (s_lo, s_hi) = (s_a.min(s_b), s_a.max(s_b));
            let ny = (((s_hi - s_lo) / element).ceil() as usize).min(MAX_STRIPS);
            let mut geom = StripGeometry::default();
            let mut rows = StripPoints::default();
            geometry.strip_geometry(
                &plane,
                s_lo,
                s_lo + ny as f64 * element,
                ny,
                &mut geom,
                &mut rows,
            );
            let f_min = geom.f[..ny].iter().copied().fold(f64::INFINITY, f64::min);
            let curv_a = geom.curv_a[..ny]
                .iter()
                .copied()
                .filter(|a| *a > 0.0)
                .fold(f64::INFINITY, f64::min);
            let half_x = (reference.depth / curv_a).sqrt().min(0.05) + MARGIN;
            let grid = strip_grid(element, ny, s_lo, half_x, geom.x_c[ny / 2]);
            let gap = strip_gap(&geom, &grid, f_min);
            let normal_force = load / reference.angle.cos();
            let solution = solve(
                &grid,
                &gap,
                crate::Target::Force(normal_force),
                contact_modulus(e, nu),
                1e-10,
            )?;
            // The lowering at which the deepest row has the exact approach: ContactPlane's
            // approach (dz − lift) cos γ − gap_n, less the deepest row's gap.
            let next = plane.lift + (solution.approach + f_min + plane.gap_n) / plane.cos_gamma;
            let moved = (next - dz).abs();
            dz = next;
            result = Some(Self {
                reference,
                lowering: dz,
                grid,
                solution,
                rows,
                load,
            });
            if moved < 1e-9 {
                break;
            }
        }
        result.ok_or(SolveError::NotConverged {
            iterations: 0,
            change: f64::NAN,
        })
    }

    /// Lateral force of the planar solution on the wheel (its normal force along the plane's
    /// normal), positive towards the field side: Q tan γ [N].
    pub fn planar_lateral(&self) -> f64 {
        self.load * self.reference.angle.tan()
    }

    /// Lateral force of the same pressure on the curved surface, each row along its own rail
    /// normal, positive towards the field side: Q Σ F_j sin γ_j / Σ F_j cos γ_j [N].
    pub fn curved_lateral(&self) -> f64 {
        let (mut lateral, mut vertical) = (0.0, 0.0);
        for (j, f) in self.row_forces().into_iter().enumerate() {
            lateral += f * self.rows.sin_angle[j];
            vertical += f * self.rows.cos_angle[j];
        }
        self.load * lateral / vertical
    }

    /// Normal force per grid row [N].
    pub fn row_forces(&self) -> Vec<f64> {
        let g = &self.grid;
        (0..g.ny)
            .map(|j| {
                self.solution.pressure[j * g.nx..(j + 1) * g.nx]
                    .iter()
                    .sum::<f64>()
                    * g.element_area()
            })
            .collect()
    }

    /// Separate runs of loaded rows (contact regions) of the exact pressure.
    pub fn regions(&self) -> usize {
        let mut regions = 0;
        let mut inside = false;
        for f in self.row_forces() {
            let loaded = f > 0.0;
            regions += usize::from(loaded && !inside);
            inside = loaded;
        }
        regions
    }

    /// The grid coarsened to elements of about `element` [m] (a whole multiple of the fine
    /// one's) and the pressure on it (each coarse element's force spread over it) [Pa].
    pub fn coarse(&self, element: f64) -> (Grid, Vec<f64>) {
        let fine = &self.grid;
        let ratio = ((element / fine.dx).round() as usize).max(1);
        let coarse = Grid {
            nx: fine.nx.div_ceil(ratio),
            ny: fine.ny.div_ceil(ratio),
            dx: fine.dx * ratio as f64,
            dy: fine.dy * ratio as f64,
            x0: fine.x0,
            y0: fine.y0,
        };
        let mut pressure = vec![0.0; coarse.len()];
        for j in 0..fine.ny {
            for i in 0..fine.nx {
                pressure[(j / ratio) * coarse.nx + i / ratio] +=
                    self.solution.pressure[j * fine.nx + i] / (ratio * ratio) as f64;
            }
        }
        (coarse, pressure)
    }

    /// Kalker's planar steady rolling problem on this pressure (coarsened to `element` [m],
    /// [`ExactWheel::coarse`]): creepages ξ, η and φ [1/m] about the plane's origin (CONTACT's
    /// reference point) with shear modulus `g` [Pa], Poisson's ratio `nu` and friction `mu`.
    pub fn planar_rolling(
        &self,
        (xi, eta, phi): (f64, f64, f64),
        element: f64,
        (g, nu, mu): (f64, f64, f64),
    ) -> Result<(Grid, RollingSolution), SolveError> {
        let (grid, pressure) = self.coarse(element);
        let rolling = Rolling {
            xi,
            eta,
            phi,
            shear_modulus: g,
            poisson_ratio: nu,
            friction: mu,
        };
        let solution = solve_rolling(&grid, &pressure, &rolling, 1e-9)?;
        Ok((grid, solution))
    }

    /// The dissipation per metre rolled (Tγ) of Kalker's planar problem at creepages
    /// `(ξ, η, φ)` on CONTACT's 0.2 mm elements, by extrapolation: solved on
    /// [`T_GAMMA_ELEMENTS`] (the dense Newton systems of 0.2 mm are out of reach) and the
    /// least-squares line through Tγ against the element size taken at 0.2 mm (the discrete
    /// dissipation converges at first order, from below).
    pub fn planar_t_gamma(
        &self,
        creepage: (f64, f64, f64),
        material: (f64, f64, f64),
    ) -> Result<DissipationEstimate, SolveError> {
        let mut finest = None;
        let mut per_element = Vec::with_capacity(T_GAMMA_ELEMENTS.len());
        for &h in &T_GAMMA_ELEMENTS {
            let (grid, sol) = self.planar_rolling(creepage, h, material)?;
            per_element.push((h, sol.t_gamma, sol.rigid_work));
            finest.get_or_insert((grid, sol));
        }
        let finest = finest.expect("T_GAMMA_ELEMENTS is not empty");
        let n = per_element.len() as f64;
        let mean_h = per_element.iter().map(|p| p.0).sum::<f64>() / n;
        let mean_t = per_element.iter().map(|p| p.1).sum::<f64>() / n;
        let (mut num, mut den) = (0.0, 0.0);
        for &(h, t, _) in &per_element {
            num += (h - mean_h) * (t - mean_t);
            den += (h - mean_h) * (h - mean_h);
        }
        Ok(DissipationEstimate {
            t_gamma: mean_t + num / den * (CONTACT_ELEMENT - mean_h),
            per_element,
            finest,
        })
    }

    /// The exact steady rolling solution on this pressure (the grid coarsened to `element` [m]
    /// by summing the pressure's force per coarse element) with each element's rigid slip from
    /// `motion` at its own wheel point, on side `sigma` (+1 right, −1 left), with shear modulus
    /// `g` [Pa], Poisson's ratio `nu` and friction `mu`: the creep forces in track axes.
    pub fn rolling(
        &self,
        motion: &WheelsetMotion,
        sigma: f64,
        element: f64,
        (g, nu, mu): (f64, f64, f64),
    ) -> Result<CreepForces, SolveError> {
        let fine = &self.grid;
        let (coarse, pressure) = self.coarse(element);
        // Each coarse row's kinematics from the fine row at its centre.
        let row_of = |y: f64| (((y - fine.y0) / fine.dy) as usize).min(fine.ny - 1);
        let speed = motion.vx.abs().max(0.01);
        let (sin_yaw, cos_yaw) = motion.yaw.sin_cos();
        let omega = [
            motion.omega * sin_yaw,
            -motion.omega * cos_yaw,
            motion.yaw_rate,
        ];
        let slip = |x: f64, y: f64| {
            let j = row_of(y);
            let (w, r) = (self.rows.lateral[j], self.rows.rolling_radius[j]);
            let (s, c) = (self.rows.sin_angle[j], self.rows.cos_angle[j]);
            // Wheel material velocity at P − C = (x, σW, r) (track axes, z down).
            let arm = [x, sigma * w, r];
            let v = [
                motion.vx + omega[1] * arm[2] - omega[2] * arm[1],
                motion.vy + omega[2] * arm[0] - omega[0] * arm[2],
                omega[0] * arm[1] - omega[1] * arm[0],
            ];
            // e_y = (0, cos γ, −σ sin γ); the grid's y runs towards the field side, σ e_y.
            let along_y = v[1] * c - sigma * v[2] * s;
            [v[0] / speed, sigma * along_y / speed]
        };
        let rolling = Rolling {
            xi: 0.0,
            eta: 0.0,
            phi: 0.0,
            shear_modulus: g,
            poisson_ratio: nu,
            friction: mu,
        };
        let sol = solve_rolling_with_slip(&coarse, &pressure, slip, &rolling, 1e-9)?;
        let (mut fx, mut fy) = (0.0, 0.0);
        let area = coarse.element_area();
        for jc in 0..coarse.ny {
            let j = row_of(coarse.y(jc));
            for ic in 0..coarse.nx {
                let k = jc * coarse.nx + ic;
                fx += sol.traction_x[k] * area;
                // Along σ e_y, whose track-y component is σ cos γ.
                fy += sol.traction_y[k] * area * sigma * self.rows.cos_angle[j];
            }
        }
        let normal: f64 = pressure.iter().sum::<f64>() * area;
        Ok(CreepForces {
            fx,
            fy,
            mu_n: mu * normal,
        })
    }
}
