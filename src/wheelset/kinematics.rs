//! Wheelset kinematics: creepages at a contact point from the rigid-body motion, contact axes.
//!
//! Track axes: x forward, y right, z down (`docs/conventions.md`), following the track's centre
//! line at the wheelset, so that on a curve of curvature κ they turn at vx κ about z
//! (docs/theory.md §8.1). The wheelset centre C, at lateral y, moves with
//! v_C = (vx (1 − κ y), vy, 0); the wheelset turns with Ω = (ψ̇ + vx κ) e_z − ω e_axle, the axle
//! direction e_axle = (−sin ψ, cos ψ cos θ, cos ψ sin θ) yawed by ψ and rolled by θ. A material
//! point P of the wheel (its lever from C turned by the roll) then moves with
//! v = v_C + Ω × (P − C); the rail's material point there with
//! v_R = (0, vy_R, vz_R) + θ̇_R e_x × (P − O_R) (its origin O_R's velocity and roll rate). The
//! creepages of the wheel relative to the rail at a contact point with contact axes
//! (e_x, e_y, e_z) are ξ = (v − v_R)·e_x/V, η = (v − v_R)·e_y/V, φ = Ω·e_z/V (the rail's roll
//! rate has no component along e_z), with V = max(|vx|, [`V_MIN`]). Contact axes at contact
//! angle γ on side σ (+1 right, −1 left): e_x = (1, 0, 0), e_y = (0, cos γ, −σ sin γ),
//! e_z = (0, σ sin γ, cos γ) (from the wheel into the rail).

use nalgebra::Vector3;

use super::{Creepages, WheelsetInput, V_MIN};
use crate::geometry::search::ContactPoint;
use crate::tangential::fastsim::Creepage;

/// The rail under a wheel as the creepages see it (track axes): its origin's velocity [m/s],
/// its roll rate [rad/s] and its origin relative to the wheelset centre [m].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct RailFrame {
    pub velocity: Vector3<f64>,
    pub roll_rate: f64,
    pub origin: Vector3<f64>,
}

impl RailFrame {
    /// The velocity of the rail's material point at `arm` from the wheelset centre.
    fn velocity_at(&self, arm: &Vector3<f64>) -> Vector3<f64> {
        let lever = arm - self.origin;
        // θ̇ e_x × (P − O_R) = θ̇ (0, −lever_z, lever_y).
        self.velocity + Vector3::new(0.0, -lever.z, lever.y) * self.roll_rate
    }
}

/// Creepages of the wheel relative to the rail `rail` at contact point `p` with contact angle
/// `gamma`, and the reference speed V [m/s].
pub(super) fn creepages_at(
    input: &WheelsetInput,
    sigma: f64,
    rail: &RailFrame,
    p: &ContactPoint,
    gamma: f64,
) -> (Creepage, f64) {
    let point = Vector3::new(p.longitudinal, p.lateral, p.rolling_radius);
    creepages_with(
        input,
        sigma,
        rail,
        point,
        gamma.sin_cos(),
        input.yaw.sin_cos(),
    )
}

/// [`creepages_at`] at the point `point` = (longitudinal, lateral from the wheelset centre
/// along the wheel's own side, rolling radius) [m], with the contact angle's (sin γ, cos γ) and
/// the yaw's (sin ψ, cos ψ) given (the strip loops have them at hand).
pub(super) fn creepages_with(
    input: &WheelsetInput,
    sigma: f64,
    rail: &RailFrame,
    point: Vector3<f64>,
    angle_trig: (f64, f64),
    (sin_yaw, cos_yaw): (f64, f64),
) -> (Creepage, f64) {
    match input.creepages {
        Creepages::Prescribed { creepage, vx } => (creepage, vx.abs()),
        Creepages::Kinematic {
            vx,
            vy,
            yaw_rate,
            omega,
        } => {
            let speed = vx.abs().max(V_MIN);
            // P − C in track axes: the side's lateral coordinate mirrored on the left wheel, the
            // wheelset's roll θ turning it about e_x (θ > 0 lowers the right wheel).
            let (sin_roll, cos_roll) = input.roll.sin_cos();
            let (lateral, depth) = (sigma * point.y, point.z);
            let arm = Vector3::new(
                point.x,
                lateral * cos_roll - depth * sin_roll,
                lateral * sin_roll + depth * cos_roll,
            );
            // The rail's lever from its origin, which sits `wheelRadius` below the unrolled centre
            // (docs/theory.md §8.1): the point unrolled.
            let rail_arm = Vector3::new(point.x, lateral, depth);
            let kappa = input.track.curvature;
            // ω about the yawed and rolled axle e_axle = (−sin ψ, cos ψ cos θ, cos ψ sin θ).
            let angular_velocity = Vector3::new(
                omega * sin_yaw,
                -omega * cos_yaw * cos_roll,
                -omega * cos_yaw * sin_roll + yaw_rate + vx * kappa,
            );
            let centre_velocity = Vector3::new(vx * (1.0 - kappa * input.y), vy, 0.0);
            let v = centre_velocity + angular_velocity.cross(&arm) - rail.velocity_at(&rail_arm);
            let (e_y, e_z) = contact_axes_of(sigma, angle_trig);
            let creepage = Creepage {
                xi: v.x / speed,
                eta: v.dot(&e_y) / speed,
                phi: angular_velocity.dot(&e_z) / speed,
            };
            (creepage, speed)
        }
    }
}

/// Position of the rigid contact point `p` of side `sigma` relative to the wheelset centre, in
/// track axes [m], at the wheelset's `yaw` and `roll` [rad]: in the side's rolled wheelset frame
/// ([`crate::geometry::search`]) the point lies at the longitudinal X (its yaw lead), the
/// lateral W from the centre and the depth √(r² − d²) below the axle, with r the rolling radius
/// and d = X cos ψ + W sin ψ its distance from the axle's vertical plane (ψ, θ the side's yaw
/// and roll); the roll θ turns it back into the track's side frame, whose lateral is mirrored on
/// the left wheel.
pub(super) fn point_position(sigma: f64, p: &ContactPoint, yaw: f64, roll: f64) -> Vector3<f64> {
    let (sin_yaw, cos_yaw) = (sigma * yaw).sin_cos();
    let (sin_roll, cos_roll) = (sigma * roll).sin_cos();
    let (x, w, r) = (p.longitudinal, p.lateral, p.rolling_radius);
    let d = x * cos_yaw + w * sin_yaw;
    let depth = (r * r - d * d).max(0.0).sqrt();
    let lateral = w * cos_roll - depth * sin_roll;
    let height = w * sin_roll + depth * cos_roll;
    Vector3::new(x, sigma * lateral, height)
}

/// Unit vectors e_y, e_z of the contact axes at contact angle `gamma` on side `sigma` (track
/// axes; e_x = (1, 0, 0)).
pub(super) fn contact_axes(sigma: f64, gamma: f64) -> (Vector3<f64>, Vector3<f64>) {
    contact_axes_of(sigma, gamma.sin_cos())
}

/// [`contact_axes`] from the angle's (sin γ, cos γ).
pub(super) fn contact_axes_of(
    sigma: f64,
    (sin_g, cos_g): (f64, f64),
) -> (Vector3<f64>, Vector3<f64>) {
    (
        Vector3::new(0.0, cos_g, -sigma * sin_g),
        Vector3::new(0.0, sigma * sin_g, cos_g),
    )
}

/// Track-axes vector of a tangential force (fx, fy) in the contact axes at angle `gamma`.
pub(super) fn planar_tangential(sigma: f64, gamma: f64, fx: f64, fy: f64) -> Vector3<f64> {
    tangential_in_axes(sigma, gamma.sin_cos(), fx, fy)
}

/// [`planar_tangential`] from the angle's (sin γ, cos γ): fx e_x + fy e_y.
pub(super) fn tangential_in_axes(
    sigma: f64,
    angle_trig: (f64, f64),
    fx: f64,
    fy: f64,
) -> Vector3<f64> {
    let (e_y, _) = contact_axes_of(sigma, angle_trig);
    // e_x = (1, 0, 0) and e_y has no x component.
    Vector3::new(fx, fy * e_y.y, fy * e_y.z)
}

/// The kinematics of a non-planar patch with kinematic creepages (docs/theory.md §5.8, §8.1):
/// the wheelset's rigid-body motion, from which every strip takes its own creepages.
pub(super) struct NonPlanar {
    kinematics: WheelsetInput,
    sigma: f64,
    rail: RailFrame,
    /// (sin ψ, cos ψ) of the yaw.
    yaw_trig: (f64, f64),
}

impl NonPlanar {
    /// `None` with prescribed creepages: they hold on every strip as given (in each strip's own
    /// axes), so that no creepage prescribed means no creep force.
    pub(super) fn new(input: &WheelsetInput, sigma: f64, rail: &RailFrame) -> Option<Self> {
        match input.creepages {
            Creepages::Prescribed { .. } => None,
            Creepages::Kinematic { .. } => Some(Self {
                kinematics: *input,
                sigma,
                rail: *rail,
                yaw_trig: input.yaw.sin_cos(),
            }),
        }
    }

    /// The creepages of the strip at `point` on the wheelset ((longitudinal, lateral, rolling
    /// radius) [m]) in its own contact axes (`angle_trig`: its contact angle's (sin, cos)).
    pub(super) fn creepage(&self, point: Vector3<f64>, angle_trig: (f64, f64)) -> Creepage {
        creepages_with(
            &self.kinematics,
            self.sigma,
            &self.rail,
            point,
            angle_trig,
            self.yaw_trig,
        )
        .0
    }
}
