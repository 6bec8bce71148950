//! One wheelset on straight track: contact search on both wheels, normal contact (multi-Hertzian
//! or a strip model), creepages from the wheelset kinematics, FASTSIM or FaStrip per patch, and
//! the forces in track axes (docs/theory.md §7.6–§8.5).
//!
//! Per wheel (in its side frame, see [`crate::geometry::track`]):
//! 1. rigid contact search ([`crate::geometry::search`]) gives the gap function, its minima and
//!    the ridges between them;
//! 2. the minima form patch groups with continuous weights ([`crate::geometry::groups`],
//!    docs/theory.md §7.7); the outputs report one patch per contact region, at most
//!    [`MAX_PATCHES`] in the output slots ([`regions`]);
//! 3. `normalModel` 1 (`hertz_side`): each group is one Hertz ellipse, with its reference point
//!    at the centroid of the interpenetration above 0.8 of the group's depth (where `yRail`, the
//!    contact angle and the rolling radius are taken) and its lateral curvature from the spread of
//!    the interpenetration (multi-Hertzian: docs/theory.md §2, §7.8); `normalModel` 2–7
//!    ([`strip_side`]): strips on each group's contact plane, laid out once per step, solved by
//!    the strip model (docs/theory.md §5, §7.9);
//! 4. the wheel's vertical position is either prescribed (`z`) or found so that the vertical force
//!    of the rail on the wheel balances the prescribed wheel load Q — including the vertical
//!    components of the creep forces, which matter in flange contact (N cos γ + σ Fy sin γ = Q),
//!    warm-started from the previous step ([`balance`], docs/theory.md §8.3);
//! 5. creepages at the reference point from the wheelset's rigid-body motion (body 1 = wheel):
//!    v = v_C + Ω × (P − C), ξ = v·e_x/V, η = v·e_y/V, φ = Ω·e_z/V with V = max(|vx|, V_MIN), or
//!    prescribed (`kinematics`, docs/theory.md §8.1); on a non-planar strip patch every strip
//!    has its own contact angle, spin and rolling radius (docs/theory.md §5.8);
//! 6. the tangential problem per patch: FASTSIM on a Hertz ellipse, the `tangentialModel`'s
//!    solver on a strip patch (docs/theory.md §4, §6).
//!
//! Contact axes of a patch, in track axes (x forward, y right, z down), for both wheels
//! right-handed with e_y pointing to the right: e_x = (1, 0, 0), e_z = (0, σ sin γ, cos γ) (from the
//! wheel into the rail), e_y = (0, cos γ, −σ sin γ), σ = +1 right, −1 left. The force of the rail
//! on the wheel is F = Fx e_x + Fy e_y − N e_z.
//!
//! Known limits: vertical gap (δ_n = δ_v cos γ); each wheel's vertical position is found
//! independently at the given roll (as CONTACT does with per-wheel prescribed loads); straight
//! track; the wheelset's angular velocity has no roll-rate term.

pub mod balance;
pub mod conicity;
mod hertz_side;
mod kinematics;
pub mod regions;
mod reuse;
pub mod strip_side;
pub mod validity;

pub use balance::{Trend, WarmStart, LOAD_CHECK_FLOOR, LOAD_CHECK_TOLERANCE};
pub use regions::Slot;

use nalgebra::Vector3;

use crate::damage::profile::WearBins;
use crate::damage::{
    fatigue, DamageParams, DamageSum, FrictionElement, FrictionStrip, PatchDamage,
};
use crate::error::InputError;
use crate::geometry::groups::MAX_GROUPS;
use crate::geometry::profile::Profile;
use crate::geometry::search::{ContactPoint, SearchError, SidePose, WheelOnRail};
use crate::geometry::strips::MAX_STRIPS;
use crate::geometry::track::{GeometryError, TrackSetup};
use crate::material::Material;
use crate::normal::hertz::{contact_modulus, shear_modulus};
use crate::normal::shape::HertzShapeTable;
use crate::normal::{NormalModel, NormalParams, DEFAULT_B_SMOOTHING, DEFAULT_STRIPS};
use crate::tangential::fastsim::{Creepage, Fastsim, FastsimSettings};
use crate::tangential::patch::TangentialModel;
use crate::tangential::strip_fastsim::{StripFastsim, StripFastsimResult, TangentialStrip};
use balance::check_balance;
use kinematics::RailFrame;
use strip_side::{solve_strips, StripSettings, StripSide};

/// Patches reported per wheel.
pub const MAX_PATCHES: usize = 3;

/// Reference speed below which creepages are computed with this speed instead [m/s]: keeps
/// creepages finite at standstill (a spinning wheel at standstill is then in full sliding, a
/// wheel at rest has zero creepage). Documented in `docs/conventions.md`.
pub const V_MIN: f64 = 0.01;

/// Vertical wheel force below which the derailment quotient is 0 (no contact) [N].
pub const YQ_MIN_LOAD: f64 = 1e-6;

/// Iteration limit of the load balance (safeguarded secant; converges in ~5–10).
const LOAD_ITERATIONS: usize = 60;

/// Static settings of a wheelset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelsetSettings {
    pub setup: TrackSetup,
    pub material: Material,
    pub fastsim: FastsimSettings,
    /// Sampling step of the gap function [m].
    pub scan_step: f64,
    /// Floor of the relative lateral curvature B [1/m].
    pub b_min: f64,
    /// Normal contact model.
    pub normal_model: NormalModel,
    /// Strips across each non-elliptic patch.
    pub strips: usize,
    /// STRIPES-B smoothing window of B, fraction of the patch width [-].
    pub b_smoothing: f64,
    /// Kik–Piotrowski area-preserving shape correction.
    pub kp_shape_correction: bool,
    /// Tangential model on strip patches (Hertz patches always use FASTSIM on their ellipse).
    pub tangential: TangentialModel,
    /// Planar treatment of strip patches: one contact angle and one spin for the whole patch
    /// (as the half-space theory assumes). `false`: each strip its own angle, rolling radius
    /// and creepages (docs/theory.md §5.8).
    pub planar_patch: bool,
    /// A prescribed-load creep pass whose normal-force target moved by at most 3e−6 of the
    /// load since the last tangential solve keeps that solution, scaled to its normal forces
    /// (docs/theory.md §8.3). `false`: every pass solves the tangential problem again.
    pub reuse_tangential: bool,
    /// Wear model and fatigue parameters of the damage outputs (docs/theory.md §10).
    pub damage: DamageParams,
}

impl WheelsetSettings {
    /// Default settings for a track set-up: Hertz, default FASTSIM and strips.
    pub fn new(setup: TrackSetup, material: Material) -> Self {
        Self {
            setup,
            material,
            fastsim: FastsimSettings::online(),
            scan_step: crate::geometry::search::DEFAULT_SCAN_STEP,
            b_min: crate::geometry::search::DEFAULT_B_MIN,
            normal_model: NormalModel::Hertz,
            strips: DEFAULT_STRIPS,
            b_smoothing: DEFAULT_B_SMOOTHING,
            kp_shape_correction: false,
            tangential: TangentialModel::ModelDefault,
            planar_patch: false,
            reuse_tangential: true,
            damage: DamageParams::default(),
        }
    }
}

/// How the wheels' vertical positions are set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Vertical {
    /// Vertical wheel loads [N] (≥ 0; 0 means the wheel is lifted off).
    Loads { left: f64, right: f64 },
    /// Downward displacement of the wheelset centre from its nominal height (the taping-line
    /// radius above the rail tops) [m].
    Position { z: f64 },
}

/// How the creepages are obtained.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Creepages {
    /// From the wheelset motion: forward speed vx, lateral velocity vy [m/s], yaw rate [rad/s],
    /// angular velocity about the axle ω [rad/s], positive when rolling forward.
    Kinematic {
        vx: f64,
        vy: f64,
        yaw_rate: f64,
        omega: f64,
    },
    /// The same creepages at every patch's reference point; `vx` only scales the power.
    Prescribed { creepage: Creepage, vx: f64 },
}

/// A rail's displacement from its design position and its velocity, in track axes
/// (`docs/conventions.md`, "Track and rails"): lateral `dy` and vertical `dz` shifts [m] and the
/// roll [rad] of the rail profile about its origin (the top of the rail as mounted; positive
/// lowering the rail's right-hand side, as the wheelset's roll), and their rates.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RailInput {
    pub dy: f64,
    pub dz: f64,
    pub roll: f64,
    pub vy: f64,
    pub vz: f64,
    pub roll_rate: f64,
}

/// The FMU names of the rails' inputs ([`RailInput`]'s fields in order), left and right.
pub const RAIL_INPUTS: [[&str; 6]; 2] = [
    [
        "left.rail.dy",
        "left.rail.dz",
        "left.rail.roll",
        "left.rail.vy",
        "left.rail.vz",
        "left.rail.rollRate",
    ],
    [
        "right.rail.dy",
        "right.rail.dz",
        "right.rail.roll",
        "right.rail.vy",
        "right.rail.vz",
        "right.rail.rollRate",
    ],
];

/// The track at the wheelset: its curvature [1/m] (positive turning towards the right rail)
/// and the two rails' displacements and velocities. The default is straight, rigid track.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TrackInput {
    pub curvature: f64,
    pub left: RailInput,
    pub right: RailInput,
}

impl TrackInput {
    /// The rail of side `sigma` (+1 right, −1 left).
    pub fn rail(&self, sigma: f64) -> &RailInput {
        if sigma > 0.0 {
            &self.right
        } else {
            &self.left
        }
    }
}

/// Pose and motion of the wheelset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelsetInput {
    /// Lateral shift towards the right rail [m].
    pub y: f64,
    /// Yaw angle about z (down) [rad].
    pub yaw: f64,
    /// Roll angle about x [rad], positive lowering the right wheel.
    pub roll: f64,
    pub vertical: Vertical,
    pub creepages: Creepages,
    /// The track: curvature and rail motion (relative to which the pose and the velocities
    /// above are given).
    pub track: TrackInput,
}

/// One contact patch (forces of the rail on the wheel, contact axes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PatchResult {
    pub fn_: f64,
    pub fx: f64,
    pub fy: f64,
    pub mz: f64,
    pub area: f64,
    pub pmax: f64,
    /// Semi-axes of the patch ellipse along x and across [m] (non-elliptic patches: of the
    /// equivalent ellipse, same area and length/width ratio).
    pub a: f64,
    pub b: f64,
    /// Length along x (longest strip) and width across (in the contact plane) [m].
    pub length: f64,
    pub width: f64,
    pub y_rail: f64,
    /// The reference point (on the wheel, rigid) relative to the wheelset centre, track axes
    /// (x forward with the yaw lead, y right, z down) [m]; the patch's forces act there.
    pub position: [f64; 3],
    pub contact_angle: f64,
    pub rolling_radius: f64,
    /// Normal approach [m].
    pub penetration: f64,
    pub creepage: Creepage,
    pub adhesion_fraction: f64,
    pub frictional_power: f64,
    pub max_traction: f64,
    /// Curvatures used for the ellipse [1/m].
    pub curv_a: f64,
    pub curv_b: f64,
    /// Energy dissipated per metre rolled, Tγ = frictional power / rolling speed [N = J/m]
    /// (0 at zero speed).
    pub t_gamma: f64,
    /// Mass worn off the wheel and off the rail per metre rolled by the `wearModel`, summed
    /// element by element [kg/m] (0 with `wearModel` 0).
    pub wheel_wear_rate: f64,
    pub rail_wear_rate: f64,
    /// Ekberg's surface fatigue index μ_eff − k/p0 of the patch [-] (`crate::damage::fatigue`).
    pub fatigue_index: f64,
    /// The largest local fatigue index (|q| − k)/p over the patch's elements [-] (0 with
    /// `wearModel` 0).
    pub fatigue_index_local: f64,
    /// Weight of the patch in the wheel's forces (1 but where two contact descriptions are
    /// blended, `crate::geometry::groups`); `fn_`, `fx`, `fy`, `mz`, `area`,
    /// `frictional_power` and `t_gamma` include it, and the wear rates through `t_gamma` (they
    /// are scaled to it, [`patch_damage`]) [-].
    pub weight: f64,
}

impl PatchResult {
    /// Takes the tangential solution's forces (contact axes), adhesion fraction, frictional
    /// power and largest traction, and its Tγ at the rolling speed `speed` [m/s].
    fn set_tangential(&mut self, t: &StripFastsimResult, speed: f64) {
        self.fx = t.fx;
        self.fy = t.fy;
        self.mz = t.mz;
        self.adhesion_fraction = t.adhesion_fraction;
        self.frictional_power = t.frictional_power;
        self.max_traction = t.max_traction;
        self.t_gamma = if speed > 0.0 {
            t.frictional_power / speed
        } else {
            0.0
        };
    }

    /// Takes the damage of the patch's tangential field.
    fn set_damage(&mut self, d: &PatchDamage) {
        self.wheel_wear_rate = d.wheel_wear_rate;
        self.rail_wear_rate = d.rail_wear_rate;
        self.fatigue_index_local = d.fatigue_index_local;
    }
}

/// Tangential traction in one element of a patch (forces of the rail on the wheel).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TractionElement {
    /// Element centre along the rolling direction, from the patch's reference point [m].
    pub x: f64,
    /// Lateral coordinate in the contact plane, towards the field side [m].
    pub s: f64,
    /// Lateral rail coordinate (mounted rail frame, towards the field side) [m].
    pub y_rail: f64,
    /// Traction along x and along the element's lateral axis e_y [Pa].
    pub px: f64,
    pub py: f64,
    /// Normal pressure [Pa].
    pub pn: f64,
    /// Whether the element slips.
    pub slipping: bool,
}

/// One wheel's result.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SideResult {
    /// Patches in the output slots (`patches[k]` with `weight` > 0).
    pub n_patches: usize,
    /// The output slots: a reported patch keeps its slot while it exists (matched from step to
    /// step by its reference point, [`regions`]); a new patch takes the first free slot. Unused
    /// slots are zero.
    pub patches: [PatchResult; MAX_PATCHES],
    /// Every reported patch of the wheel, one per contact region ([`regions`]), also those
    /// beyond the output slots (their forces are in `force`): `regions[..n_regions]`.
    pub n_regions: usize,
    pub regions: [PatchResult; regions::MAX_REGIONS],
    /// The internal descriptions the wheel's forces are the weighted sum of (the patch groups'
    /// patches, [`crate::geometry::groups`]; forces, area and power weighted):
    /// `groups[..n_groups]`.
    pub n_groups: usize,
    pub groups: [PatchResult; MAX_GROUPS],
    /// Total force of the rail on the wheel in track axes [N].
    pub force: [f64; 3],
    /// Moment of the rail's forces on the wheel about the wheelset centre, track axes [N·m]:
    /// Σ over the patches of position × force + the spin moment about the patch normal.
    pub moment: [f64; 3],
    /// Derailment quotient Y/Q [-]: Y the lateral force of the rail on the wheel, positive
    /// towards the track centre (the flanging wheel's guiding force), over Q = −Fz, the
    /// wheel's vertical force; 0 when Q ≤ [`YQ_MIN_LOAD`] (a lifted wheel).
    pub derailment_quotient: f64,
    /// The wheel's downward displacement from nominal at which it carries its load [m].
    pub z: f64,
    /// The wheel's force on the rail, track axes [N] (−`force`), and its moment about the rail
    /// profile's origin (the top of the rail as mounted, displaced with the rail), about the
    /// track's x axis [N·m].
    pub rail_force: [f64; 3],
    pub rail_moment_x: f64,
    /// Sums over the wheel's reported patches: Tγ [J/m], wear rates [kg/m] and the Whole Life
    /// Rail Model's damage per wheel pass of each patch's Tγ [-] (`crate::damage::fatigue`).
    pub t_gamma: f64,
    pub wheel_wear_rate: f64,
    pub rail_wear_rate: f64,
    pub rcf_damage: f64,
}

impl SideResult {
    /// The patches in the output slots, in slot order (a slot may be empty: a patch keeps its
    /// slot while it exists).
    pub fn shown_patches(&self) -> impl Iterator<Item = &PatchResult> + '_ {
        self.patches.iter().filter(|p| p.weight > 0.0)
    }

    /// Turns the wheel's vectors (forces, moments, patch positions) by `angle` [rad] about the
    /// track's x axis (positive lowering the right-hand side, as the roll).
    fn turn_about_x(&mut self, angle: f64) {
        let (sin, cos) = angle.sin_cos();
        let turn = |v: &mut [f64; 3]| {
            let (y, z) = (v[1], v[2]);
            v[1] = y * cos - z * sin;
            v[2] = y * sin + z * cos;
        };
        turn(&mut self.force);
        turn(&mut self.moment);
        let (n, m, g) = (self.n_regions, self.n_groups, MAX_PATCHES);
        for p in self.patches[..g]
            .iter_mut()
            .chain(&mut self.regions[..n])
            .chain(&mut self.groups[..m])
        {
            turn(&mut p.position);
        }
    }

    /// Every reported patch of the wheel, also those beyond the output slots.
    pub fn all_patches(&self) -> &[PatchResult] {
        &self.regions[..self.n_regions]
    }

    /// Empties the result for a new evaluation at the lowering `z` [m]: no patch, no force. The
    /// patch arrays are left as they are (read only up to their counts; the output slots are
    /// written whole by [`regions::report`]), which spares clearing some 4 kB per evaluation.
    fn clear(&mut self, z: f64) {
        self.n_patches = 0;
        self.n_regions = 0;
        self.n_groups = 0;
        self.force = [0.0; 3];
        self.moment = [0.0; 3];
        self.derailment_quotient = 0.0;
        self.rail_force = [0.0; 3];
        self.rail_moment_x = 0.0;
        self.z = z;
        self.t_gamma = 0.0;
        self.wheel_wear_rate = 0.0;
        self.rail_wear_rate = 0.0;
        self.rcf_damage = 0.0;
    }

    /// The damage outputs that follow from the reported patches' own outputs: each patch's
    /// surface fatigue index (shear yield strength `k` [Pa]) and the wheel's sums.
    fn finish_damage(&mut self, k: f64) {
        let index = |p: &mut PatchResult| {
            p.fatigue_index = fatigue::surface_index(p.fx, p.fy, p.fn_, p.pmax, k);
        };
        self.patches
            .iter_mut()
            .filter(|p| p.weight > 0.0)
            .for_each(index);
        self.regions[..self.n_regions].iter_mut().for_each(index);
        for p in &self.regions[..self.n_regions] {
            self.t_gamma += p.t_gamma;
            self.wheel_wear_rate += p.wheel_wear_rate;
            self.rail_wear_rate += p.rail_wear_rate;
            self.rcf_damage += fatigue::wlrm_damage(p.t_gamma);
        }
    }
}

/// Both wheels.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WheelsetResult {
    pub left: SideResult,
    pub right: SideResult,
}

/// Why a wheelset evaluation failed.
#[derive(Debug, Clone, PartialEq)]
pub enum WheelsetError {
    /// An input is out of range (names the FMU variable).
    Input(InputError),
    /// The pose has no usable rigid contact on one wheel: the simulation cannot continue.
    NoContact {
        side: &'static str,
        reason: SearchError,
    },
    /// The normal model found no wheel height that carries the prescribed load to
    /// [`LOAD_CHECK_TOLERANCE`]: the result would be wrong, so none is given.
    Unbalanced {
        side: &'static str,
        /// Vertical force carried at the best height found [N].
        carried: f64,
        /// Prescribed wheel load [N].
        load: f64,
    },
}

impl std::fmt::Display for WheelsetError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            WheelsetError::Input(e) => e.fmt(f),
            WheelsetError::NoContact { side, reason } => {
                write!(f, "no contact: {side} wheel: {reason}")
            }
            WheelsetError::Unbalanced {
                side,
                carried,
                load,
            } => write!(
                f,
                "{side} wheel: the normal model carries {carried:.6e} N of the prescribed load \
                 {load:.6e} N (allowed deviation {:.0e} of the load + {} N) at the best wheel \
                 height found",
                LOAD_CHECK_TOLERANCE, LOAD_CHECK_FLOOR
            ),
        }
    }
}

impl std::error::Error for WheelsetError {}

impl From<InputError> for WheelsetError {
    fn from(e: InputError) -> Self {
        WheelsetError::Input(e)
    }
}

/// A multi-Hertzian patch of a normal solution: reference point, normal solution, weight, its
/// group's index in the layout and the group's lateral bounds.
type Ellipse = (ContactPoint, PatchResult, f64, usize, (f64, f64));

/// One wheel with its solver buffers.
struct Side {
    name: &'static str,
    /// +1 right, −1 left.
    sigma: f64,
    geometry: WheelOnRail,
    /// FASTSIM of the Hertz patches, one per patch group.
    fastsim: Vec<Fastsim>,
    /// Strip patches of the non-elliptic models (`None` for Hertz).
    strips: Option<StripSide>,
    /// Tangential solvers of the strip patches (one per patch group) and the strip buffer.
    strip_fastsim: Vec<StripFastsim>,
    tangential_strips: Vec<TangentialStrip>,
    /// `y_rail` of the Hertz patches of the last evaluation (for their traction field).
    last_y_rail: [f64; MAX_GROUPS],
    /// The rail's motion as the creepages of this evaluation see it.
    rail: RailFrame,
    /// The last prescribed-load solution, the next one's starting point.
    warm: Option<WarmStart>,
    /// The multi-Hertzian patches of the last normal solution: reference point, normal solution,
    /// weight, the index of its group in the step's layout and the group's lateral bounds
    /// (`evaluate_side`).
    ellipses: [Ellipse; MAX_GROUPS],
    n_ellipses: usize,
    /// For each entry of `SideResult::groups` of a strip model, its patch in `strips`.
    strip_of_group: [Option<usize>; MAX_GROUPS],
    /// For each entry of `SideResult::groups`, its patch's key ([`reuse::PatchTangential::key`]),
    /// and for each tangential solver (`fastsim` or `strip_fastsim`, by index) the key of the
    /// patch whose field it holds from this step (the damage pass, [`patch_damage`]).
    group_key: [usize; MAX_GROUPS],
    field_key: [Option<usize>; MAX_GROUPS],
    /// Per strip of the patch in the damage pass: its wear of the wheel and of the rail [kg/m]
    /// and its lateral; the wheel's wear rates of the last step across the profiles.
    strip_wear: Vec<(f64, f64, f64)>,
    wear: WearRates,
    /// For each entry of `SideResult::groups`, the laterals (wheelset frame) its load lies
    /// between: a Hertz patch's group's bounds, a strip patch's strips' (for [`regions`]).
    part_bounds: [(f64, f64); MAX_GROUPS],
    /// The patches in the output slots after the last solve: their `y_rail` (the identity
    /// matched in the next step) and their index in `SideResult::groups`.
    slots: [Option<Slot>; MAX_PATCHES],
    /// Buffers of the reported patches ([`regions::report`]; taken while it runs).
    scratch: Option<Box<regions::Scratch>>,
}

/// A wheelset contact solver; owns every buffer, so [`Wheelset::solve`] does not allocate.
pub struct Wheelset {
    settings: WheelsetSettings,
    e_star: f64,
    shear_modulus: f64,
    /// Hertz shapes: the multi-Hertzian patches and the strip models.
    table: HertzShapeTable,
    left: Side,
    right: Side,
}

impl Wheelset {
    /// Mounts `rail` on both sides and `wheel` on both ends of the axle (the left side mirrored).
    pub fn new(
        wheel: &Profile,
        rail: &Profile,
        settings: WheelsetSettings,
    ) -> Result<Self, GeometryError> {
        settings.material.validate()?;
        if !(1..=MAX_STRIPS).contains(&settings.strips) {
            return Err(InputError::new("nStrips", settings.strips as f64, "[1, 200]").into());
        }
        if !(settings.b_smoothing.is_finite() && (0.0..=1.0).contains(&settings.b_smoothing)) {
            return Err(InputError::new("bSmoothing", settings.b_smoothing, "[0, 1]").into());
        }
        let m = settings.material;
        let side = |name, sigma| -> Result<Side, GeometryError> {
            let geometry = WheelOnRail::new(
                wheel.clone(),
                rail,
                &settings.setup,
                settings.scan_step,
                settings.b_min,
            )?;
            let wear = {
                let (w0, w1) = wheel.y_range();
                let (r0, r1) = geometry.rail().profile().y_range();
                WearRates {
                    wheel: WearBins::covering(w0, w1),
                    rail: WearBins::covering(r0, r1),
                }
            };
            Ok(Side {
                name,
                sigma,
                geometry,
                // With the damage outputs on, the marches keep each element's slip.
                fastsim: (0..MAX_GROUPS)
                    .map(|_| {
                        let mut solver = Fastsim::new(settings.fastsim)?;
                        if settings.damage.element_wise() {
                            solver.record_slips();
                        }
                        Ok::<_, InputError>(solver)
                    })
                    .collect::<Result<_, _>>()?,
                strips: StripSide::new(settings.normal_model),
                strip_fastsim: if settings.normal_model == NormalModel::Hertz {
                    Vec::new()
                } else {
                    (0..MAX_GROUPS)
                        .map(|_| {
                            let mut solver =
                                StripFastsim::new(settings.fastsim.nx, settings.fastsim.scheme)?;
                            if settings.tangential == TangentialModel::FastripCoupled {
                                solver.reserve_coupled(settings.strips);
                            }
                            if settings.damage.element_wise() {
                                solver.record_slips();
                            }
                            Ok::<_, InputError>(solver)
                        })
                        .collect::<Result<_, _>>()?
                },
                tangential_strips: vec![TangentialStrip::default(); MAX_STRIPS],
                last_y_rail: [0.0; MAX_GROUPS],
                rail: RailFrame::default(),
                warm: None,
                ellipses: [(
                    ContactPoint::default(),
                    PatchResult::default(),
                    0.0,
                    0,
                    (0.0, 0.0),
                ); MAX_GROUPS],
                n_ellipses: 0,
                strip_of_group: [None; MAX_GROUPS],
                group_key: [0; MAX_GROUPS],
                field_key: [None; MAX_GROUPS],
                strip_wear: vec![(0.0, 0.0, 0.0); MAX_STRIPS.max(settings.fastsim.ny)],
                wear,
                part_bounds: [(0.0, 0.0); MAX_GROUPS],
                slots: [None; MAX_PATCHES],
                scratch: Some(Box::default()),
            })
        };
        Ok(Self {
            settings,
            e_star: contact_modulus(m.youngs_modulus, m.poisson_ratio),
            shear_modulus: shear_modulus(m.youngs_modulus, m.poisson_ratio),
            table: HertzShapeTable::new(),
            left: side("left", -1.0)?,
            right: side("right", 1.0)?,
        })
    }

    /// The wear rates of the last solve spread across the wheel's and the rail's profile, left
    /// and right wheel ([`WearRates`]; all zero with `wearModel` 0).
    pub fn wear_rates(&self) -> [&WearRates; 2] {
        [&self.left.wear, &self.right.wear]
    }

    pub fn settings(&self) -> &WheelsetSettings {
        &self.settings
    }

    /// The geometry of one wheel (`right = true` for the right wheel).
    pub fn geometry(&self, right: bool) -> &WheelOnRail {
        if right {
            &self.right.geometry
        } else {
            &self.left.geometry
        }
    }

    /// The strip patches of one wheel after the last solve (empty for Hertz): one per patch
    /// group, with its weight ([`crate::geometry::groups`]). Those whose
    /// [`crate::normal::strips::PatchSummary::in_contact`] holds carry load.
    pub fn strip_patches(&self, right: bool) -> &[crate::wheelset::strip_side::StripPatch] {
        let side = if right { &self.right } else { &self.left };
        side.strips.as_ref().map_or(&[], |s| s.patches())
    }

    /// The traction field of the patch in output slot `patch` (0-based, as in
    /// [`SideResult::patches`]) of one wheel after the last solve, or `None` if the slot is
    /// empty. Allocates (on request only). Tractions are those of the patch itself (not scaled
    /// by its weight). Strip patches: every element of every strip in contact, `s` the strip's
    /// lateral coordinate in its contact plane (towards the field side) and `y_rail` the rail
    /// point of the strip; Hertz patches: the FASTSIM grid, `s` from the ellipse centre towards
    /// the field side and `y_rail` = the patch's `y_rail` + `s`.
    pub fn traction_field(&self, right: bool, patch: usize) -> Option<Vec<TractionElement>> {
        let side = if right { &self.right } else { &self.left };
        let group = side.slots.get(patch).copied().flatten()?.group;
        if let Some(strips) = side.strips.as_ref() {
            let p = strips.patches().get(side.strip_of_group[group]?)?;
            let solver = side.strip_fastsim.get(group)?;
            return Some(
                solver
                    .tractions()
                    .map(|e| TractionElement {
                        x: e.x,
                        s: p.geom.s[e.strip],
                        y_rail: p.points.y_rail[e.strip],
                        px: e.px,
                        py: e.py,
                        pn: e.pn,
                        slipping: e.slipping,
                    })
                    .collect(),
            );
        }
        let y_rail = side.last_y_rail.get(group).copied()?;
        let solver = side.fastsim.get(group)?;
        let field: Vec<_> = solver
            .tractions()
            .map(|e| TractionElement {
                x: e.x,
                s: side.sigma * e.y,
                y_rail: y_rail + side.sigma * e.y,
                px: e.px,
                py: e.py,
                pn: e.pn,
                slipping: e.slipping,
            })
            .collect();
        (!field.is_empty()).then_some(field)
    }

    /// The elements of the patch in output slot `patch` as the damage models see them (area,
    /// pressure, traction and slip scaled to the patch's frictional power, [`FrictionElement`]),
    /// each with its lateral rail coordinate `y_rail` [m] as in [`Wheelset::traction_field`];
    /// `None` for an empty slot. Allocates (on request only); the field of the patch itself (not
    /// scaled by its weight).
    pub fn friction_field(&self, right: bool, patch: usize) -> Option<Vec<(f64, FrictionElement)>> {
        let side = if right { &self.right } else { &self.left };
        let group = side.slots.get(patch).copied().flatten()?.group;
        let mut field = Vec::new();
        if let Some(strips) = side.strips.as_ref() {
            let p = strips.patches().get(side.strip_of_group[group]?)?;
            side.strip_fastsim
                .get(group)?
                .friction_elements(|j, e| field.push((p.points.y_rail[j], *e)));
        } else {
            let y_rail = side.last_y_rail.get(group).copied()?;
            side.fastsim
                .get(group)?
                .friction_elements(|_, e| field.push((y_rail + side.sigma * e.lateral, *e)));
        }
        (!field.is_empty()).then_some(field)
    }

    /// The strip patch in output slot `slot` (0-based) of one wheel after the last solve, or
    /// `None` (an empty slot, or a multi-Hertzian patch).
    pub fn strip_patch_of_slot(
        &self,
        right: bool,
        slot: usize,
    ) -> Option<&crate::wheelset::strip_side::StripPatch> {
        let side = if right { &self.right } else { &self.left };
        let group = side.slots.get(slot).copied().flatten()?.group;
        side.strips
            .as_ref()?
            .patches()
            .get(side.strip_of_group[group]?)
    }

    /// The output slots of both wheels after the last solve, `[left, right]` (part of the state
    /// that decides which slot a patch of the next step takes).
    pub fn slots(&self) -> [[Option<Slot>; MAX_PATCHES]; 2] {
        [self.left.slots, self.right.slots]
    }

    /// Replaces the output slots (e.g. from a saved state).
    pub fn set_slots(&mut self, slots: [[Option<Slot>; MAX_PATCHES]; 2]) {
        [self.left.slots, self.right.slots] = slots;
    }

    /// The warm starts of the load iteration, `[left, right]` (`None`: the next solve starts
    /// cold). Save them with the outputs to reproduce a run from a restored state.
    pub fn warm_start(&self) -> [Option<WarmStart>; 2] {
        [self.left.warm, self.right.warm]
    }

    /// Replaces the warm starts (`[left, right]`; `None` for a cold start), e.g. from a saved state.
    pub fn set_warm_start(&mut self, warm: [Option<WarmStart>; 2]) {
        [self.left.warm, self.right.warm] = warm;
    }

    /// Solves both wheels.
    pub fn solve(
        &mut self,
        input: &WheelsetInput,
        out: &mut WheelsetResult,
    ) -> Result<(), WheelsetError> {
        check_input(input)?;
        let ctx = Context {
            e_star: self.e_star,
            shear_modulus: self.shear_modulus,
            material: self.settings.material,
            strips: StripSettings {
                model: self.settings.normal_model,
                strips: self.settings.strips,
                params: NormalParams {
                    e_star: self.e_star,
                    b_min: self.settings.b_min,
                    b_smoothing: self.settings.b_smoothing,
                    kp_shape_correction: self.settings.kp_shape_correction,
                },
                planar: self.settings.planar_patch,
            },
            table: &self.table,
            settings: &self.settings,
        };
        let (q_left, q_right, z) = match input.vertical {
            Vertical::Loads { left, right } => (Some(left), Some(right), 0.0),
            Vertical::Position { z } => (None, None, z),
        };
        solve_side(&mut self.left, &ctx, input, q_left, z, &mut out.left)?;
        solve_side(&mut self.right, &ctx, input, q_right, z, &mut out.right)?;
        Ok(())
    }
}

fn check_input(input: &WheelsetInput) -> Result<(), InputError> {
    use crate::error::{require_finite, require_non_negative};
    require_finite("y", input.y)?;
    require_finite("yaw", input.yaw)?;
    require_finite("roll", input.roll)?;
    require_finite("trackCurvature", input.track.curvature)?;
    for (rail, names) in [
        (&input.track.left, RAIL_INPUTS[0]),
        (&input.track.right, RAIL_INPUTS[1]),
    ] {
        let values = [
            rail.dy,
            rail.dz,
            rail.roll,
            rail.vy,
            rail.vz,
            rail.roll_rate,
        ];
        for (name, value) in names.into_iter().zip(values) {
            require_finite(name, value)?;
        }
    }
    match input.vertical {
        Vertical::Loads { left, right } => {
            require_non_negative("Qleft", left)?;
            require_non_negative("Qright", right)?;
        }
        Vertical::Position { z } => {
            require_finite("z", z)?;
        }
    }
    match input.creepages {
        Creepages::Kinematic {
            vx,
            vy,
            yaw_rate,
            omega,
        } => {
            require_finite("vx", vx)?;
            require_finite("vy", vy)?;
            require_finite("yawRate", yaw_rate)?;
            require_finite("omega", omega)?;
        }
        Creepages::Prescribed { creepage, vx } => {
            require_finite("xi", creepage.xi)?;
            require_finite("eta", creepage.eta)?;
            require_finite("phi", creepage.phi)?;
            require_finite("vx", vx)?;
        }
    }
    Ok(())
}

/// Material constants and model settings shared by both sides.
struct Context<'a> {
    e_star: f64,
    shear_modulus: f64,
    material: Material,
    strips: StripSettings,
    table: &'a HertzShapeTable,
    settings: &'a WheelsetSettings,
}

/// Stores a completed patch `result` with its `weight` in the next entry of `out.groups` and
/// adds its weighted force — the tangential part `tangential` (track axes) and the normal force
/// along −e_z — to `out.force`, and its moment about the wheelset centre — that force at the
/// patch's `position` and the spin moment `mz` about e_z — to `out.moment`. Returns its
/// weighted upward force on the wheel [N].
fn store_patch(
    sigma: f64,
    mut result: PatchResult,
    weight: f64,
    tangential: Vector3<f64>,
    out: &mut SideResult,
) -> f64 {
    let (_, e_z) = kinematics::contact_axes(sigma, result.contact_angle);
    let total = (tangential - e_z * result.fn_) * weight;
    out.force = (Vector3::from(out.force) + total).into();
    let moment = Vector3::from(result.position).cross(&total) + e_z * (result.mz * weight);
    out.moment = (Vector3::from(out.moment) + moment).into();
    result.weight = weight;
    for v in [
        &mut result.fn_,
        &mut result.fx,
        &mut result.fy,
        &mut result.mz,
        &mut result.area,
        &mut result.frictional_power,
        &mut result.t_gamma,
    ] {
        *v *= weight;
    }
    out.groups[out.n_groups] = result;
    out.n_groups += 1;
    // z points down: the upward force is −F_z.
    -total.z
}

/// Y/Q of the wheel on side `sigma` carrying the force `force` (track axes) [-]
/// ([`SideResult::derailment_quotient`]): towards the track centre is −σ y.
pub fn derailment_quotient(sigma: f64, force: [f64; 3]) -> f64 {
    let (lateral, vertical) = (-sigma * force[1], -force[2]);
    if vertical > YQ_MIN_LOAD {
        lateral / vertical
    } else {
        0.0
    }
}

/// The damage of each of the step's patches (`out.groups`) from the tangential field its solver
/// holds (`strip_model`: the strip solvers', else FASTSIM's on the ellipses), once per step
/// after the creep passes: its wear rates (scaled to the patch's own Tγ: a pass that reused a
/// recorded solution scaled it, and a patch's group weight shares it), its largest local
/// fatigue index, and its wear spread strip by strip over the side's distributions across the
/// wheel's and the rail's profile ([`WearRates`]); `mu` the friction coefficient (a patch that
/// dissipates with no slipping element, [`DamageSum::add_release`]). Nothing with `wearModel` 0.
fn patch_damage(
    side: &mut Side,
    params: &DamageParams,
    mu: f64,
    strip_model: bool,
    out: &mut SideResult,
) {
    if !params.element_wise() {
        return;
    }
    side.wear.wheel.clear();
    side.wear.rail.clear();
    let taping = side.geometry.setup().taping_line_offset();
    for g in 0..out.n_groups {
        let patch = &mut out.groups[g];
        let key = side.group_key[g];
        let Some(h) = side.field_key.iter().position(|k| *k == Some(key)) else {
            continue;
        };
        // The speed the patch's Tγ was taken at (Archard's sliding velocities); where the patch
        // dissipates nothing no element slips and the speed does not matter.
        let speed = if patch.t_gamma > 0.0 {
            patch.frictional_power / patch.t_gamma
        } else {
            0.0
        };
        let mut sum = DamageSum::new(*params, speed);
        // Each strip's wear and lateral (along e_y from the reference point), summed in
        // registers while the elements of one strip come and stored when the next begins; the
        // buffer is zero on entry and cleared again over the strips used.
        let strips = &mut side.strip_wear;
        let mut used = 0;
        let mut current = (usize::MAX, (0.0, 0.0, 0.0));
        let mut store = |(j, strip): (usize, (f64, f64, f64))| {
            if let Some(s) = strips.get_mut(j) {
                *s = strip;
                used = used.max(j + 1);
            }
        };
        // FASTSIM's recorded fields strip by strip; otherwise (FaStrip, or slips replayed)
        // element by element.
        let by_strip = |j: usize, s: &FrictionStrip| {
            let (wheel, rail) = sum.add_strip(s);
            store((j, (wheel, rail, s.lateral)));
        };
        let by_strips = if strip_model {
            side.strip_fastsim[h].friction_strips(by_strip)
        } else {
            side.fastsim[h].friction_strips(by_strip)
        };
        if !by_strips {
            let add = |j: usize, e: &FrictionElement| {
                let (wheel, rail) = sum.add(e);
                if j != current.0 {
                    store(std::mem::replace(&mut current, (j, (0.0, 0.0, e.lateral))));
                }
                let s = &mut current.1;
                s.0 += wheel;
                s.1 += rail;
            };
            if strip_model {
                side.strip_fastsim[h].friction_elements(add);
            } else {
                side.fastsim[h].friction_elements(add);
            }
        }
        store(current);
        if sum.t_gamma() == 0.0 && patch.t_gamma > 0.0 && patch.area > 0.0 && patch.fn_ > 0.0 {
            // Nothing slips on the grid, yet the patch dissipates: one element of the patch's
            // mean pressure and Tγ/A at its reference point (traction μp̄, slip Tγ/(μ Fn)).
            let pressure = patch.fn_ / patch.area;
            let release = FrictionElement {
                lateral: 0.0,
                area: patch.area,
                pressure,
                traction_sq: (mu * pressure).powi(2),
                bound: f64::NEG_INFINITY,
                slip: patch.t_gamma / (mu * patch.fn_),
            };
            let (wheel, rail) = sum.add_release(&release);
            // On the profiles at the middle strip (an ellipse's: its reference point).
            let middle = used / 2;
            if let Some(s) = side.strip_wear.get_mut(middle) {
                *s = (wheel, rail, 0.0);
                used = used.max(middle + 1);
            }
        }
        let damage = sum.finish(patch.t_gamma);
        patch.set_damage(&damage);
        // The strips' wear, scaled as the patch's, at their points on the two profiles.
        let scale = if sum.t_gamma() > 0.0 {
            patch.t_gamma / sum.t_gamma()
        } else {
            0.0
        };
        let wear = &mut side.wear;
        let strip_patch = side.strips.as_ref().and_then(|s| s.patches().get(key));
        let ellipse = side.ellipses[..side.n_ellipses].iter().find(|e| e.3 == key);
        let cos_angle = ellipse.map_or(1.0, |e| e.0.contact_angle.cos());
        for (j, strip) in side.strip_wear[..used].iter_mut().enumerate() {
            let (wheel, rail, lateral) = std::mem::take(strip);
            if wheel == 0.0 && rail == 0.0 {
                continue;
            }
            let (y_wheel, y_rail) = match (strip_model, strip_patch, ellipse) {
                (true, Some(p), _) => (p.points.lateral[j] - taping, p.points.y_rail[j]),
                (false, _, Some((reference, ..))) => {
                    // Along the profiles: the contact plane's lateral towards the field side
                    // (σ e_y), projected by the contact angle.
                    let d = side.sigma * lateral * cos_angle;
                    (reference.y_wheel + d, reference.y_rail + d)
                }
                _ => continue,
            };
            wear.wheel.add(y_wheel, wheel * scale);
            wear.rail.add(y_rail, rail * scale);
        }
    }
}

/// A wheel's wear rates of the last step spread across the profiles: mass per metre rolled in
/// bins of the wheel profile's lateral coordinate and of the mounted rail's [kg/m per bin]
/// (`crate::damage::profile`).
#[derive(Debug, Clone)]
pub struct WearRates {
    pub wheel: WearBins,
    pub rail: WearBins,
}

fn solve_side(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    load: Option<f64>,
    z: f64,
    out: &mut SideResult,
) -> Result<(), WheelsetError> {
    let s = side.sigma;
    // The contact is solved in the frame of the rail as displaced (docs/theory.md §8.5): there
    // the rail is at its design position and the wheelset carries the opposite displacement.
    // In the side frame (lateral ℓ = σ y towards the field side, z down) the wheelset centre
    // lies at (a, b) = (ℓ − Y_O − σ dy, z − h − dz) from the rail's origin (Y_O its design
    // lateral, h = wheelRadius the centre's nominal height; with prescribed loads the wheel sits
    // on its rail, b = −h); turned by −σθ about the origin it is at (a′, b′), the centre the rail
    // frame sees: lateral Y_O + a′, lowering b′ + h.
    let rail = *input.track.rail(s);
    let theta = s * rail.roll;
    let lift = ctx.settings.setup.wheel_radius;
    let origin = side.geometry.rail().origin_lateral();
    let (sin_t, cos_t) = theta.sin_cos();
    // The centre's height above the rail's origin beyond h (0 for a wheel on its rail).
    let above = if load.is_some() { 0.0 } else { rail.dz - z };
    let (lateral, z) = if theta == 0.0 {
        (s * (input.y - rail.dy), z - rail.dz)
    } else {
        let (a, b) = (s * (input.y - rail.dy) - origin, -lift - above);
        (origin + a * cos_t + b * sin_t, lift - a * sin_t + b * cos_t)
    };
    let pose = SidePose {
        lateral,
        yaw: s * input.yaw,
        roll: s * input.roll - theta,
    };
    let rolled = WheelsetInput {
        roll: input.roll - rail.roll,
        ..*input
    };
    let input = &rolled;
    side.rail = RailFrame {
        velocity: Vector3::new(0.0, rail.vy, rail.vz),
        roll_rate: rail.roll_rate,
        origin: Vector3::new(0.0, s * origin + rail.dy - input.y, lift + above),
    };
    side.geometry
        .search(&pose)
        .map_err(|reason| WheelsetError::NoContact {
            side: side.name,
            reason,
        })?;
    let touch = side
        .geometry
        .candidates()
        .as_slice()
        .iter()
        .map(|c| c.gap)
        .fold(f64::INFINITY, f64::min);
    let strip_model = side.strips.is_some();
    side.field_key = [None; MAX_GROUPS];
    let warm = side.warm.take();
    // The strip models start from the Hertz solution (normal forces only), so that their strips
    // are laid out the same way whatever the previous step was; the warm start shortens that
    // Hertz solution and the creep iteration.
    let (mut creep, slope) =
        hertz_side::hertz_side(side, ctx, input, load, z, touch, warm, out, !strip_model)?;
    let approach = out.z - touch;
    let mut strip_ratio = 1.0;
    if strip_model && load != Some(0.0) {
        let start = warm.map_or(0.0, |w| w.predicted().1);
        let ratio_hint = warm.map_or(1.0, |w| w.strip_ratio);
        creep = solve_strips(side, ctx, input, load, touch, start, ratio_hint, out)?;
        let final_approach = out.z - touch;
        if approach > 0.0 && final_approach > 0.0 {
            strip_ratio = final_approach / approach;
        }
    }
    check_balance(side.name, load, out)?;
    let mu = ctx.settings.material.friction;
    patch_damage(side, &ctx.settings.damage, mu, strip_model, out);
    regions::report(side, input, ctx.settings.planar_patch, out);
    out.finish_damage(ctx.settings.damage.shear_yield_strength);
    // The wheel's wrench on the rail about the rail's origin (in the rail's frame; a turn about
    // x keeps the x moment), then the rail frame's vectors turned back into track axes.
    let [_, fy, fz] = out.force;
    let (arm_y, arm_z) = (s * (lateral - origin), out.z - lift);
    out.rail_moment_x = -(out.moment[0] + arm_y * fz - arm_z * fy);
    if rail.roll != 0.0 {
        out.turn_about_x(rail.roll);
    }
    out.rail_force = out.force.map(|f| -f);
    // The wheel's lowering from the rail frame's back to the track's.
    if theta != 0.0 {
        out.z = (lateral - origin) * sin_t + (out.z - lift) * cos_t + lift;
    }
    out.z += rail.dz;
    out.derailment_quotient = derailment_quotient(s, out.force);
    // A load without a tangential problem (no patch) keeps the approach with no creep component.
    side.warm = (load.is_some_and(|q| q > 0.0) && approach > 0.0)
        .then(|| WarmStart::after(warm, approach, creep.unwrap_or(0.0), strip_ratio, slope));
    Ok(())
}
