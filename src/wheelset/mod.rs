//! One wheelset on straight track: contact search on both wheels, multi-Hertzian normal contact,
//! creepages from the wheelset kinematics, FASTSIM per patch, and the forces in track axes.
//!
//! Per wheel (in its side frame, see [`crate::geometry::track`]):
//! 1. rigid contact search ([`crate::geometry::search`]) gives the gap function and its minima;
//! 2. the wheel's vertical position is either prescribed (`z`) or found so that the vertical force
//!    of the rail on the wheel balances the prescribed wheel load Q — including the vertical
//!    components of the creep forces, which matter in flange contact (N cos γ + σ Fy sin γ = Q);
//! 3. each connected interpenetration region is one patch (at most [`MAX_PATCHES`], the deepest
//!    kept): its reference point is the volume-weighted centroid of the interpenetration
//!    (CONTACT's contact reference point), which gives `yRail`, the contact angle and the rolling
//!    radius; its Hertz ellipse uses the curvatures and the normal approach δ_v·cos γ at the
//!    region's deepest point (multi-Hertzian: physics.md §2, §5.1);
//! 4. creepages at the reference point from the wheelset's rigid-body motion (body 1 = wheel):
//!    v = v_C + Ω × (P − C), ξ = v·e_x/V, η = v·e_y/V, φ = Ω·e_z/V with V = max(|vx|, V_MIN), or
//!    prescribed;
//! 5. FASTSIM per patch (the patch is planar; per-strip spin is the non-elliptic issue's work).
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
pub mod strip_side;
pub mod validity;

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
use crate::tangential::fastsim::{Creepage, EllipticContact, Fastsim, FastsimSettings};
use crate::tangential::patch::{strip_flexibilities, EquivalentEllipse, TangentialModel};
use crate::tangential::strip_fastsim::{StripFastsim, TangentialStrip};
use crate::wheelset::balance::balance_hertzian;
use crate::wheelset::strip_side::{group_bounds, groups_at, StripPatch, StripSettings, StripSide};

/// Patches reported per wheel.
pub const MAX_PATCHES: usize = 3;

/// Reference speed below which creepages are computed with this speed instead [m/s]: keeps
/// creepages finite at standstill (a spinning wheel at standstill is then in full sliding, a
/// wheel at rest has zero creepage). Documented in `docs/conventions.md`.
pub const V_MIN: f64 = 0.01;

/// Smallest share of the wheel load the normal forces carry when the creep forces' vertical
/// components are subtracted (they cannot carry the wheel: |Fy| ≤ μN).
const MIN_NORMAL_SHARE: f64 = 0.05;
/// Passes of the strip models' load balance that update the creep forces' vertical component.
const CREEP_PASSES: usize = 12;
/// Relative tolerance of that update on the wheel load.
const CREEP_TOLERANCE: f64 = 1e-7;
/// Largest relative deviation of the carried vertical force from a prescribed wheel load before
/// a step is refused ([`WheelsetError::Unbalanced`]). Balanced solutions meet the iteration
/// tolerances (1e−9 normal, [`CREEP_TOLERANCE`] with creep); a normal force that jumps with the
/// wheel height (Linder's strips entering contact, two regions merging) leaves the nearer end of
/// the jump, ≤ 0.1 % in the tests; 1 % flags a solution that is wrong.
pub const LOAD_CHECK_TOLERANCE: f64 = 1e-2;
/// Absolute part of that check [N]: loads of micronewtons (1 µN and up is contact, below is
/// lift-off) need approaches of ~1e−15 m, below the strip models' round-off; 0.01 N is nothing
/// to a wheel that carries 1e4–1e5 N.
pub const LOAD_CHECK_FLOOR: f64 = 1e-2;
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
    /// and creepages (physics.md §5.9).
    pub planar_patch: bool,
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
    /// Weight of the patch in the wheel's forces (1 but where two contact descriptions are
    /// blended, `crate::geometry::groups`); `fn_`, `fx`, `fy`, `mz`, `area` and
    /// `frictional_power` include it [-].
    pub weight: f64,
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
    /// The output slots: a patch keeps its slot while it exists (matched from step to step by
    /// its reference point); a new patch takes the first free slot. Unused slots are zero.
    pub patches: [PatchResult; MAX_PATCHES],
    /// Every patch of the wheel, also those beyond the output slots (their forces are in
    /// `force`): `groups[..n_groups]`.
    pub n_groups: usize,
    pub groups: [PatchResult; MAX_GROUPS],
    /// Total force of the rail on the wheel in track axes [N].
    pub force: [f64; 3],
    /// The wheel's downward displacement from nominal at which it carries its load [m].
    pub z: f64,
}

impl SideResult {
    /// The patches in the output slots, in slot order (a slot may be empty: a patch keeps its
    /// slot while it exists).
    pub fn shown_patches(&self) -> impl Iterator<Item = &PatchResult> + '_ {
        self.patches.iter().filter(|p| p.weight > 0.0)
    }

    /// Every patch of the wheel, also those beyond the output slots.
    pub fn all_patches(&self) -> &[PatchResult] {
        &self.groups[..self.n_groups]
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
    /// The last prescribed-load solution, the next one's starting point.
    warm: Option<WarmStart>,
    /// The multi-Hertzian patches of the last normal solution: reference point, normal solution
    /// and weight (`evaluate_side`).
    ellipses: [(ContactPoint, PatchResult, f64); MAX_GROUPS],
    n_ellipses: usize,
    /// For each entry of `SideResult::groups` of a strip model, its patch in `strips`.
    strip_of_group: [Option<usize>; MAX_GROUPS],
    /// The patches in the output slots after the last solve: their `y_rail` (the identity
    /// matched in the next step) and their index in `SideResult::groups`.
    slots: [Option<Slot>; MAX_PATCHES],
}

/// A patch in an output slot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slot {
    /// The patch's reference point on the rail, `PatchResult::y_rail` [m].
    pub y_rail: f64,
    /// Index of the patch in `SideResult::groups`.
    pub group: usize,
}

/// Largest move of a patch's reference point (`y_rail`) between two steps for it to keep its
/// output slot [m]: 4 mm, more than a reference point moves in one communication step of any
/// vehicle run (a wheelset hunting at 5 Hz with 10 mm amplitude moves 0.3 mm per millisecond),
/// less than the distance between a tread and a flange contact (≳ 10 mm).
const SLOT_MATCH_DISTANCE: f64 = 4e-3;

/// Where the prescribed-load iteration of a wheel starts: the previous step's solution,
/// extrapolated by its change over that step (a moving wheelset's approach and creep component
/// change smoothly from step to step, so the linear extrapolation lands within the creep
/// iteration's tolerance where the last value alone does not: −26 % work per moving Hertz step).
/// With it a step whose inputs changed little needs one tangential solve and a few cheap
/// normal-force evaluations instead of a cold search. Part of the FMU state (outputs depend on
/// it at the level of the iteration tolerances).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WarmStart {
    /// Lowering beyond first touch at which the multi-Hertzian normal forces carried the load
    /// [m] (> 0; for the strip models their normal-only Hertz estimate).
    pub approach: f64,
    /// Vertical component of the creep forces on the wheel, upwards positive [N].
    pub creep: f64,
    /// Change of `approach` [m] and `creep` [N] over the step that produced them (0 after a
    /// cold start).
    pub approach_step: f64,
    pub creep_step: f64,
    /// Strip models: the approach at which their patches carried the load less the creep
    /// forces' vertical component, over `approach` [-] (the first trial of the next step's
    /// iteration is `approach` times this; 1 for the multi-Hertzian solution).
    pub strip_ratio: f64,
}

impl WarmStart {
    /// The first guess for the next step: the linear extrapolation of the approach (kept within
    /// [½, 2] × the last one, so that a jump in the inputs cannot send it far off) and of the
    /// creep component.
    pub fn predicted(&self) -> (f64, f64) {
        let approach =
            (self.approach + self.approach_step).clamp(0.5 * self.approach, 2.0 * self.approach);
        (approach, self.creep + self.creep_step)
    }

    /// The warm start after a step that found `approach`, `creep` and the strip ratio
    /// [`WarmStart::strip_ratio`], following `previous`.
    fn after(previous: Option<WarmStart>, approach: f64, creep: f64, strip_ratio: f64) -> Self {
        let (approach_step, creep_step) =
            previous.map_or((0.0, 0.0), |p| (approach - p.approach, creep - p.creep));
        Self {
            approach,
            creep,
            approach_step,
            creep_step,
            strip_ratio,
        }
    }
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
            Ok(Side {
                name,
                sigma,
                geometry: WheelOnRail::new(
                    wheel.clone(),
                    rail,
                    &settings.setup,
                    settings.scan_step,
                    settings.b_min,
                )?,
                fastsim: (0..MAX_GROUPS)
                    .map(|_| Fastsim::new(settings.fastsim))
                    .collect::<Result<_, _>>()?,
                strips: StripSide::new(settings.normal_model),
                strip_fastsim: if settings.normal_model == NormalModel::Hertz {
                    Vec::new()
                } else {
                    (0..MAX_GROUPS)
                        .map(|_| StripFastsim::new(settings.fastsim.nx, settings.fastsim.scheme))
                        .collect::<Result<_, _>>()?
                },
                tangential_strips: vec![TangentialStrip::default(); MAX_STRIPS],
                last_y_rail: [0.0; MAX_GROUPS],
                warm: None,
                ellipses: [(ContactPoint::default(), PatchResult::default(), 0.0); MAX_GROUPS],
                n_ellipses: 0,
                strip_of_group: [None; MAX_GROUPS],
                slots: [None; MAX_PATCHES],
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

/// Creepages of the wheel relative to the rail at contact point `p` with contact angle `gamma`.
fn creepages_at(
    input: &WheelsetInput,
    sigma: f64,
    p: &ContactPoint,
    gamma: f64,
) -> (Creepage, f64) {
    let arm = [p.longitudinal, p.lateral, p.rolling_radius];
    creepages_with(input, sigma, arm, gamma.sin_cos(), input.yaw.sin_cos())
}

/// [`creepages_at`] at the point (longitudinal, lateral, rolling radius) `point` [m] with the
/// contact angle's (sin γ, cos γ) and the yaw's (sin ψ, cos ψ) given (the strip loops have them
/// at hand).
fn creepages_with(
    input: &WheelsetInput,
    sigma: f64,
    [longitudinal, lateral, rolling_radius]: [f64; 3],
    (sin_g, cos_g): (f64, f64),
    (sin_y, cos_y): (f64, f64),
) -> (Creepage, f64) {
    match input.creepages {
        Creepages::Prescribed { creepage, vx } => (creepage, vx.abs()),
        Creepages::Kinematic {
            vx,
            vy,
            yaw_rate,
            omega,
        } => {
            let v_ref = vx.abs().max(V_MIN);
            // Lever arm from the wheelset centre to the contact point, track axes.
            let arm = [longitudinal, sigma * lateral, rolling_radius];
            // Ω = yaw rate about z, minus ω about the (yawed) axle direction (0, 1, 0) rotated.
            let omega_vec = [omega * sin_y, -omega * cos_y, yaw_rate];
            let cross = [
                omega_vec[1] * arm[2] - omega_vec[2] * arm[1],
                omega_vec[2] * arm[0] - omega_vec[0] * arm[2],
                omega_vec[0] * arm[1] - omega_vec[1] * arm[0],
            ];
            let v = [vx + cross[0], vy + cross[1], cross[2]];
            let creepage = Creepage {
                xi: v[0] / v_ref,
                eta: (v[1] * cos_g - sigma * v[2] * sin_g) / v_ref,
                phi: (sigma * omega_vec[1] * sin_g + omega_vec[2] * cos_g) / v_ref,
            };
            (creepage, v_ref)
        }
    }
}

/// Fraction of a patch group's depth at which its reference point is taken (see
/// [`evaluate_side`]): the force centroid of the interpenetration above this fraction of its
/// depth. On a symmetric gap any fraction gives the deepest point; on the conformal right wheel
/// of the Manchester benchmark at 0.5 mm (a rigid region 17 mm wide, 25 µm deep), 0.8 lands
/// within 0.5 mm of CONTACT's reference point (0.55, Kik–Piotrowski's ε, 2.2 mm off with the
/// spread-based ellipse; tests/manchester.rs).
const VIRTUAL_FRACTION: f64 = 0.8;

/// Evaluates one wheel lowered by `dz` (with FASTSIM per patch if `tangential`, else normal
/// forces only); returns the vertical force of the rail on the wheel, upwards positive [N].
///
/// Multi-Hertzian: every patch group at the level dz ([`crate::geometry::groups`]) is one Hertz
/// patch, described by integrals of its interpenetration between the ridges that separate it
/// from the other groups — never by the position of one minimum, which in a conformal contact
/// is round-off (the gap is flat to 0.1 µm over millimetres where S1002's R13 flange root meets
/// UIC60's R13 gauge corner):
/// The groups are those at `merge_level` (fixed for the wheel's load iteration, so that the
/// vertical force increases with dz: [`merge_level`]); a group whose minima all lie above dz
/// carries nothing.
/// * depth δ_v = dz − g_min (vertical), g_min the group's deepest gap;
/// * the interpenetration above the fraction ε = [`VIRTUAL_FRACTION`] of that depth, d(w) =
///   max(0, g_min + ε δ_v − gap(w)) ([`crate::geometry::search::WheelOnRail::depth_moments`]):
///   its d-weighted mean lateral is the patch's reference point — the force centroid of a
///   virtual region (as Piotrowski & Kik 2008: the patch lies inside the virtual region, and a
///   strip's load grows with its virtual penetration, as it does for a Hertz ellipse); on a
///   symmetric gap the deepest point, on a near-conformal one (Manchester, right wheel at
///   0.5 mm) within 0.5 mm of CONTACT's reference point where the deepest point is 2.5 mm off;
/// * the variance σ² of the lateral weighted by the whole interpenetration, max(0, dz − gap),
///   gives the lateral curvature: a parabolic gap B_v w² has σ² = δ_v/(5 B_v), so
///   B_v = δ_v/(5σ²) — the point curvature on a Hertzian gap, a mean over the patch otherwise
///   (as CONTACT's KPEC takes B from the virtual region's width). In the contact plane
///   B = B_v cos³γ (floored at `b_min`), A = cos γ/(2r) at the reference point, and the normal
///   approach δ_v cos γ.
#[allow(clippy::too_many_arguments)]
fn evaluate_side(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    dz: f64,
    merge_level: f64,
    out: &mut SideResult,
    tangential: bool,
) -> Result<f64, InputError> {
    *out = SideResult {
        z: dz,
        ..SideResult::default()
    };
    let (layout, candidates, m) = groups_at(
        &mut side.geometry,
        merge_level,
        dz,
        crate::geometry::groups::SHOULDER_FRACTION,
    );
    let candidates = &candidates[..m];
    let mut ridges = [None; crate::geometry::search::MAX_CANDIDATES];
    ridges[..m.saturating_sub(1)].copy_from_slice(side.geometry.ridges());
    let ridges = &ridges[..m.saturating_sub(1)];
    let scan = side.geometry.scan_range();
    let b_floor = ctx.strips.params.b_floor();
    side.n_ellipses = 0;
    for group in layout.groups() {
        let Some((reference, patch)) = group_ellipse(
            &side.geometry,
            ctx,
            candidates,
            ridges,
            group,
            scan,
            dz,
            b_floor,
        )?
        else {
            continue;
        };
        if side.n_ellipses < MAX_GROUPS {
            side.ellipses[side.n_ellipses] = (reference, patch, group.weight);
            side.n_ellipses += 1;
        }
    }
    complete_ellipses(side, ctx, input, out, tangential)
}

/// Writes the multi-Hertzian patches of the side's last normal solution ([`evaluate_side`]) to
/// `out` (lowering `out.z`), with FASTSIM per patch if `tangential`; returns the vertical force
/// of the rail on the wheel, upwards positive [N]. The tangential problem at a lowering whose
/// normal solution is at hand needs no new one.
fn complete_ellipses(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    out: &mut SideResult,
    tangential: bool,
) -> Result<f64, InputError> {
    *out = SideResult {
        z: out.z,
        ..SideResult::default()
    };
    let mut upward = 0.0;
    for k in 0..side.n_ellipses {
        let (reference, patch, weight) = side.ellipses[k];
        upward += add_patch(side, ctx, input, &reference, patch, weight, out, tangential)?;
    }
    Ok(upward)
}

/// The Hertz patch of `group` at lowering `dz` ([`evaluate_side`]): its reference point and its
/// normal solution, or `None` where it has no interpenetration.
#[allow(clippy::too_many_arguments)]
fn group_ellipse(
    geometry: &WheelOnRail,
    ctx: &Context,
    candidates: &[ContactPoint],
    ridges: &[Option<crate::geometry::search::Ridge>],
    group: &crate::geometry::groups::Group,
    scan: (f64, f64),
    dz: f64,
    b_floor: f64,
) -> Result<Option<(ContactPoint, PatchResult)>, InputError> {
    let deepest = candidates[group.first..=group.last]
        .iter()
        .map(|c| c.gap)
        .fold(f64::INFINITY, f64::min);
    let depth = dz - deepest;
    if depth.is_nan() || depth <= 0.0 {
        return Ok(None);
    }
    let (gauge, field) = group_bounds(candidates, ridges, group, scan);
    let virtual_depth = VIRTUAL_FRACTION * depth;
    let Some(moments) = geometry.depth_moments(gauge, field, deepest + virtual_depth) else {
        return Ok(None);
    };
    let reference = geometry.point_at_lateral(moments.mean);
    let cos_g = geometry.plane_angle_at(moments.mean).cos();
    // The lateral curvature from the spread of the whole interpenetration (the rigid region,
    // ε = 1): the scale of the contact's width (on the benchmark's two-lobed central case a
    // smaller fraction sees the flat bottom between the lobes and widens the ellipse: area +11 %
    // at 0.55 against CONTACT, ±0 % at 1).
    let Some(spread) = geometry.depth_moments(gauge, field, dz) else {
        return Ok(None);
    };
    let curv_b = (depth / (5.0 * spread.variance) * cos_g.powi(3)).max(b_floor);
    let approach = depth * cos_g;
    if !(curv_b.is_finite() && approach > 0.0) {
        return Ok(None);
    }
    let patch = ctx
        .table
        .patch(reference.curv_a, curv_b, approach, ctx.e_star)?;
    if !(patch.a.is_normal() && patch.b.is_normal()) {
        return Ok(None);
    }
    let result = PatchResult {
        fn_: patch.normal_force,
        area: patch.area(),
        pmax: patch.p0,
        a: patch.a,
        b: patch.b,
        length: 2.0 * patch.a,
        width: 2.0 * patch.b,
        penetration: approach,
        curv_a: reference.curv_a,
        curv_b,
        ..PatchResult::default()
    };
    Ok(Some((reference, result)))
}

/// Completes a patch whose normal solution is in `result` (normal force, size, approach): the
/// reference point's position and angle, creepages, FASTSIM on the patch's (equivalent)
/// ellipse; stores it with its `weight` in the next entry of `out.groups`, adds its force to
/// `out.force` (track axes) and returns its upward force on the wheel [N].
#[allow(clippy::too_many_arguments)]
fn add_patch(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    reference: &ContactPoint,
    mut result: PatchResult,
    weight: f64,
    out: &mut SideResult,
    tangential: bool,
) -> Result<f64, InputError> {
    if out.n_groups >= MAX_GROUPS {
        return Ok(0.0);
    }
    let gamma = reference.contact_angle;
    let (creepage, speed) = creepages_at(input, side.sigma, reference, gamma);
    result.y_rail = reference.y_rail;
    result.contact_angle = gamma;
    result.rolling_radius = reference.rolling_radius;
    result.creepage = creepage;
    let contact = EllipticContact {
        a: result.a,
        b: result.b,
        normal_force: result.fn_,
        shear_modulus: ctx.shear_modulus,
        nu: ctx.material.poisson_ratio,
        mu: ctx.material.friction,
    };
    side.last_y_rail[out.n_groups] = reference.y_rail;
    if !tangential {
        return Ok(store_patch(side.sigma, result, weight, [0.0; 3], out));
    }
    let t = side.fastsim[out.n_groups].solve(&contact, &creepage, speed)?;
    result.fx = t.fx;
    result.fy = t.fy;
    result.mz = t.mz;
    result.adhesion_fraction = t.adhesion_fraction;
    result.frictional_power = t.frictional_power;
    result.max_traction = t.max_traction;
    let tangential = planar_tangential(side.sigma, gamma, result.fx, result.fy);
    Ok(store_patch(side.sigma, result, weight, tangential, out))
}

/// Unit vectors e_y, e_z of the contact axes at contact angle `gamma` on side `sigma` (track
/// axes; e_x = (1, 0, 0)).
fn contact_axes(sigma: f64, gamma: f64) -> ([f64; 3], [f64; 3]) {
    contact_axes_of(sigma, gamma.sin_cos())
}

/// [`contact_axes`] from the angle's (sin γ, cos γ).
fn contact_axes_of(sigma: f64, (sin_g, cos_g): (f64, f64)) -> ([f64; 3], [f64; 3]) {
    ([0.0, cos_g, -sigma * sin_g], [0.0, sigma * sin_g, cos_g])
}

/// Track-axes vector of a tangential force (fx, fy) in the contact axes at angle `gamma`.
fn planar_tangential(sigma: f64, gamma: f64, fx: f64, fy: f64) -> [f64; 3] {
    tangential_in_axes(sigma, gamma.sin_cos(), fx, fy)
}

/// [`planar_tangential`] from the angle's (sin γ, cos γ).
fn tangential_in_axes(sigma: f64, angle_trig: (f64, f64), fx: f64, fy: f64) -> [f64; 3] {
    let (e_y, _) = contact_axes_of(sigma, angle_trig);
    // e_x = (1, 0, 0) and e_y has no x component.
    [fx, fy * e_y[1], fy * e_y[2]]
}

/// Stores a completed patch `result` with its `weight` in the next entry of `out.groups` and
/// adds its weighted force — the tangential part `tangential` (track axes) and the normal force
/// along −e_z — to `out.force`. Returns its weighted upward force on the wheel [N].
fn store_patch(
    sigma: f64,
    mut result: PatchResult,
    weight: f64,
    tangential: [f64; 3],
    out: &mut SideResult,
) -> f64 {
    let (_, e_z) = contact_axes(sigma, result.contact_angle);
    let mut total = [0.0; 3];
    for i in 0..3 {
        total[i] = weight * (tangential[i] - result.fn_ * e_z[i]);
        out.force[i] += total[i];
    }
    result.weight = weight;
    for v in [
        &mut result.fn_,
        &mut result.fx,
        &mut result.fy,
        &mut result.mz,
        &mut result.area,
        &mut result.frictional_power,
    ] {
        *v *= weight;
    }
    out.groups[out.n_groups] = result;
    out.n_groups += 1;
    // z points down: the upward force is −F_z.
    -total[2]
}

/// Fills the output slots of `out` from its patch groups, keeping each patch in the slot it had
/// in the last step (`slots`, matched by the reference point's `y_rail` within
/// [`SLOT_MATCH_DISTANCE`], nearest first); new patches take the first free slots, heaviest
/// first; where more patches carry load than there are slots, the lightest are not shown (their
/// forces are in the totals). Updates `slots`.
fn assign_slots(slots: &mut [Option<Slot>; MAX_PATCHES], out: &mut SideResult) {
    let n = out.n_groups;
    // The heaviest patches, at most one per slot.
    let mut order = [0usize; MAX_GROUPS];
    for (k, o) in order.iter_mut().enumerate() {
        *o = k;
    }
    let order = &mut order[..n];
    order.sort_by(|&a, &b| out.groups[b].fn_.total_cmp(&out.groups[a].fn_));
    let shown = &order[..n.min(MAX_PATCHES)];
    let mut taken = [false; MAX_GROUPS];
    let mut next: [Option<Slot>; MAX_PATCHES] = [None; MAX_PATCHES];
    // Matches nearest first.
    let mut pairs = [(f64::INFINITY, 0usize, 0usize); MAX_PATCHES * MAX_PATCHES];
    let mut count = 0;
    for (slot, old) in slots.iter().enumerate() {
        let Some(old) = old else { continue };
        for &g in shown {
            let d = (out.groups[g].y_rail - old.y_rail).abs();
            if d <= SLOT_MATCH_DISTANCE {
                pairs[count] = (d, slot, g);
                count += 1;
            }
        }
    }
    let pairs = &mut pairs[..count];
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    for &(_, slot, g) in pairs.iter() {
        if next[slot].is_none() && !taken[g] {
            next[slot] = Some(Slot {
                y_rail: out.groups[g].y_rail,
                group: g,
            });
            taken[g] = true;
        }
    }
    for &g in shown {
        if taken[g] {
            continue;
        }
        if let Some(free) = next.iter().position(|s| s.is_none()) {
            next[free] = Some(Slot {
                y_rail: out.groups[g].y_rail,
                group: g,
            });
            taken[g] = true;
        }
    }
    out.patches = [PatchResult::default(); MAX_PATCHES];
    out.n_patches = 0;
    for (slot, s) in next.iter().enumerate() {
        if let Some(s) = s {
            out.patches[slot] = out.groups[s.group];
            out.n_patches += 1;
        }
    }
    *slots = next;
}

/// Writes the outputs of the strip patches of `side` (solved at lowering `dz`): patch figures
/// from the strips, reference point at the patch's force centroid (interpolated between strips),
/// tangential forces by the strip solvers of [`crate::tangential::strip_fastsim`] (planar or non-planar,
/// flexibilities per [`TangentialModel`]). Returns the upward force on the wheel [N].
fn evaluate_strips(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    dz: f64,
    out: &mut SideResult,
) -> Result<f64, InputError> {
    *out = SideResult {
        z: dz,
        ..SideResult::default()
    };
    let Some(strips) = side.strips.take() else {
        return Ok(0.0);
    };
    let mut upward = 0.0;
    let mut status = Ok(());
    side.strip_of_group = [None; MAX_GROUPS];
    for (index, patch) in strips.patches().iter().enumerate() {
        if out.n_groups >= MAX_GROUPS {
            break;
        }
        let summary = patch.summary();
        if !summary.in_contact() {
            continue;
        }
        match strip_patch_result(side, ctx, input, patch, &summary, dz, out.n_groups) {
            Ok((result, tangential)) => {
                side.strip_of_group[out.n_groups] = Some(index);
                upward += store_patch(side.sigma, result, patch.weight, tangential, out);
            }
            Err(e) => {
                status = Err(e);
                break;
            }
        }
    }
    side.strips = Some(strips);
    status?;
    Ok(upward)
}

/// The point of strip `j` of `patch` on the wheelset for its creepages: (longitudinal,
/// lateral, rolling radius) [m] (its contact angle enters through its sine and cosine). The
/// longitudinal position is the patch reference point's `x_ref`, not the strip's own yaw lead:
/// the tangential solvers measure x from the reference point and add the spin's φ_j·x along
/// the strip themselves, so the strip's creepages must hold at x = 0 of that frame.
fn strip_point(patch: &StripPatch, j: usize, x_ref: f64) -> [f64; 3] {
    [
        x_ref,
        patch.points.lateral[j],
        patch.points.rolling_radius[j],
    ]
}

/// The kinematics of a non-planar patch (physics.md §5.9): the rigid-body motion the strips'
/// creepages come from — the wheelset's own, or with prescribed creepages (which hold at the
/// reference point) pure rolling at the nominal wheel radius — and its creepages at the patch's
/// reference point.
struct NonPlanar {
    kinematics: WheelsetInput,
    sigma: f64,
    at_reference: Creepage,
    /// (sin ψ, cos ψ) of the yaw.
    yaw_trig: (f64, f64),
}

impl NonPlanar {
    fn new(input: &WheelsetInput, sigma: f64, wheel_radius: f64, reference: &ContactPoint) -> Self {
        let kinematics = match input.creepages {
            Creepages::Kinematic { .. } => *input,
            Creepages::Prescribed { vx, .. } => {
                let v = vx.abs().max(V_MIN);
                WheelsetInput {
                    creepages: Creepages::Kinematic {
                        vx: v,
                        vy: 0.0,
                        yaw_rate: 0.0,
                        omega: v / wheel_radius,
                    },
                    ..*input
                }
            }
        };
        let (at_reference, _) =
            creepages_at(&kinematics, sigma, reference, reference.contact_angle);
        Self {
            kinematics,
            sigma,
            at_reference,
            yaw_trig: input.yaw.sin_cos(),
        }
    }

    /// The non-planar part of the creepages at strip point `point` ([`strip_point`]; lever
    /// `lever` along e_y from the reference point; `angle_trig` its contact angle's (sin, cos)):
    /// the strip's creepages in its own axes minus what a flat patch would give there,
    /// (ξ_ref − φ_ref·lever, η_ref, φ_ref).
    fn increment(&self, point: [f64; 3], lever: f64, angle_trig: (f64, f64)) -> Creepage {
        let (here, _) = creepages_with(
            &self.kinematics,
            self.sigma,
            point,
            angle_trig,
            self.yaw_trig,
        );
        let there = &self.at_reference;
        Creepage {
            xi: here.xi - (there.xi - there.phi * lever),
            eta: here.eta - there.eta,
            phi: here.phi - there.phi,
        }
    }
}

/// Normal and tangential result of one strip patch, and its tangential force in track axes.
fn strip_patch_result(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    patch: &StripPatch,
    summary: &crate::normal::strips::PatchSummary,
    dz: f64,
    slot: usize,
) -> Result<(PatchResult, [f64; 3]), InputError> {
    let sc = summary.s_centroid;
    let at = |v: &[f64]| patch.interpolate(v, sc);
    let reference = ContactPoint {
        lateral: at(&patch.points.lateral),
        longitudinal: at(&patch.geom.x_c),
        y_rail: at(&patch.points.y_rail),
        contact_angle: patch.contact_angle(),
        rolling_radius: at(&patch.points.rolling_radius),
        curv_a: at(&patch.geom.curv_a),
        curv_b: at(&patch.geom.curv_b),
        ..ContactPoint::default()
    };
    let gamma = reference.contact_angle;
    let (creepage, speed) = creepages_at(input, side.sigma, &reference, gamma);
    let settings = ctx.settings;
    let equivalent = EquivalentEllipse::of(
        summary,
        ctx.shear_modulus,
        ctx.material.poisson_ratio,
        ctx.material.friction,
    )?;
    let source = settings
        .tangential
        .flexibility_source(settings.normal_model);
    let b_floor = ctx.strips.params.b_floor();
    let non_planar = (!settings.planar_patch)
        .then(|| NonPlanar::new(input, side.sigma, settings.setup.wheel_radius, &reference));
    let n = patch.geom.len();
    // The strips' x is measured from the reference point (its yaw lead x_ref), where the
    // patch's creepages hold: the spin's lateral slip φ·x is then zero there, as in Kalker's
    // rigid slip w = (ξ − φy, η + φx) about the reference point.
    let x_ref = reference.longitudinal;
    for j in 0..n {
        let lever = side.sigma * (patch.geom.s[j] - sc);
        let mut strip = TangentialStrip {
            lever,
            width: patch.geom.ds,
            x_c: patch.geom.x_c[j] - x_ref,
            half_length: patch.sol.half_length[j],
            pmax: patch.sol.pmax[j],
            flexibility: [0.0; 3],
            creepage,
            reference_spin: creepage.phi,
        };
        if strip.half_length > 0.0 {
            if let Some(non_planar) = &non_planar {
                let trig = (patch.points.sin_angle[j], patch.points.cos_angle[j]);
                let d = non_planar.increment(strip_point(patch, j, x_ref), lever, trig);
                strip.creepage = Creepage {
                    xi: creepage.xi + d.xi,
                    eta: creepage.eta + d.eta,
                    phi: creepage.phi + d.phi,
                };
            }
            strip.flexibility = strip_flexibilities(
                source,
                settings.fastsim.flexibility,
                &patch.geom,
                &patch.sol,
                j,
                b_floor,
                ctx.table,
                &equivalent,
                &strip.creepage,
            )?;
        }
        side.tangential_strips[j] = strip;
    }
    let solver = &mut side.strip_fastsim[slot];
    let mu = ctx.material.friction;
    let t = if settings.tangential == TangentialModel::Fastrip {
        solver.solve_fastrip(&side.tangential_strips[..n], &equivalent, speed)
    } else {
        solver.solve(&side.tangential_strips[..n], mu, speed)
    };
    // Forces: planar — all strips in the patch's axes; non-planar — each strip's in its own.
    let mut tangential = [0.0; 3];
    let mut fy_patch = 0.0;
    let (sin_g, cos_g) = gamma.sin_cos();
    for j in 0..n {
        let (fx, fy) = solver.strip_force(j);
        if fx == 0.0 && fy == 0.0 {
            continue;
        }
        let (sin_j, cos_j) = if settings.planar_patch {
            (sin_g, cos_g)
        } else {
            (patch.points.sin_angle[j], patch.points.cos_angle[j])
        };
        let v = tangential_in_axes(side.sigma, (sin_j, cos_j), fx, fy);
        for i in 0..3 {
            tangential[i] += v[i];
        }
        // cos(γ_j − γ).
        fy_patch += fy * (cos_j * cos_g + sin_j * sin_g);
    }
    let result = PatchResult {
        fn_: summary.normal_force,
        fx: t.fx,
        fy: fy_patch,
        mz: t.mz,
        area: summary.area,
        pmax: summary.pmax,
        a: equivalent.contact.a,
        b: equivalent.contact.b,
        length: summary.length,
        width: summary.width,
        y_rail: reference.y_rail,
        contact_angle: gamma,
        rolling_radius: reference.rolling_radius,
        penetration: patch.approach(dz),
        creepage,
        adhesion_fraction: t.adhesion_fraction,
        frictional_power: t.frictional_power,
        max_traction: t.max_traction,
        curv_a: reference.curv_a,
        curv_b: reference.curv_b,
        weight: 1.0,
    };
    Ok((result, tangential))
}

/// Vertical component of the creep forces of `out` on the wheel (upwards positive) [N]: the
/// total upward force less the normal forces' share (so that the non-planar strips' own
/// directions count).
fn creep_upward(out: &SideResult) -> f64 {
    let normal: f64 = out.groups[..out.n_groups]
        .iter()
        .map(|p| p.fn_ * p.contact_angle.cos())
        .sum();
    -out.force[2] - normal
}

/// Replaces the Hertz solution in `out` by the side's strip model: `load` prescribed (`out.z`,
/// the Hertz solution's lowering or the warm start's, is the starting guess, and `creep` the
/// first estimate of the creep forces' vertical component) or the lowering `out.z`. Returns the
/// last evaluated creep component (prescribed load only).
#[allow(clippy::too_many_arguments)]
fn solve_strips(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    load: Option<f64>,
    touch: f64,
    creep: f64,
    ratio_hint: f64,
    out: &mut SideResult,
) -> Result<Option<f64>, WheelsetError> {
    if side.strips.is_none() {
        return Ok(None);
    }
    let table = ctx.table;
    let mut dz = out.z;
    // One pass: the strip layout and solve (the first, or without a load) or its re-balance to
    // `target`, then the tangential problem at the new lowering; returns the creep forces'
    // vertical component. The layout follows from the multi-Hertzian lowering `out.z` alone.
    let mut pass = |side: &mut Side, k: usize, target: Option<f64>| {
        let mut strips = side.strips.take().expect("strip buffers are present");
        dz = match target {
            Some(t) if k > 0 => strips.rebalance(&ctx.strips, table, t, touch, dz),
            _ => strips.solve(
                &mut side.geometry,
                &ctx.strips,
                table,
                target,
                touch,
                dz,
                ratio_hint,
            ),
        };
        side.strips = Some(strips);
        evaluate_strips(side, ctx, input, dz, out)?;
        Ok::<_, WheelsetError>(creep_upward(out))
    };
    match load {
        None => pass(side, 0, None).map(|_| None),
        Some(q) => creep_passes(q, creep, |k, target| Ok(Some(pass(side, k, Some(target))?))),
    }
}

/// The prescribed wheel load `q` [N] is carried by the normal forces and the creep forces'
/// vertical component together. `pass(k, target)` balances the normal forces against `target`
/// = q less the current estimate of that component, solves the tangential problem there and
/// returns the component it finds (`None`: no tangential problem, stop). The estimate starts
/// from `start` (zero, or the previous step's) and is updated by [`CreepFixedPoint`] until it
/// changes by at most [`CREEP_TOLERANCE`] of q, or for [`CREEP_PASSES`] passes. Returns the last
/// component found (`None` if no pass solved a tangential problem).
fn creep_passes(
    q: f64,
    start: f64,
    mut pass: impl FnMut(usize, f64) -> Result<Option<f64>, WheelsetError>,
) -> Result<Option<f64>, WheelsetError> {
    let mut creep = if start.is_finite() { start } else { 0.0 };
    let mut fixed_point = CreepFixedPoint::default();
    let mut found = None;
    for k in 0..CREEP_PASSES {
        let target = (q - creep).max(MIN_NORMAL_SHARE * q);
        let Some(new_creep) = pass(k, target)? else {
            break;
        };
        found = Some(new_creep);
        if k + 1 == CREEP_PASSES || (new_creep - creep).abs() <= CREEP_TOLERANCE * q {
            break;
        }
        creep = fixed_point.next(creep, new_creep);
    }
    Ok(found)
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
    let pose = SidePose {
        lateral: s * input.y,
        yaw: s * input.yaw,
        roll: s * input.roll,
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
    let warm = side.warm.take();
    // The strip models start from the Hertz solution (normal forces only), so that their strips
    // are laid out the same way whatever the previous step was; the warm start shortens that
    // Hertz solution and the creep iteration.
    let mut creep = hertz_side(side, ctx, input, load, z, touch, warm, out, !strip_model)?;
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
    assign_slots(&mut side.slots, out);
    // A load without a tangential problem (no patch) keeps the approach with no creep component.
    side.warm = (load.is_some_and(|q| q > 0.0) && approach > 0.0)
        .then(|| WarmStart::after(warm, approach, creep.unwrap_or(0.0), strip_ratio));
    Ok(())
}

/// Refuses a wheel whose vertical force misses its prescribed `load` [N] by more than
/// [`LOAD_CHECK_TOLERANCE`] (or is not finite); no load (prescribed position) and lift-off pass.
fn check_balance(
    side: &'static str,
    load: Option<f64>,
    out: &SideResult,
) -> Result<(), WheelsetError> {
    let Some(q) = load.filter(|&q| q > 0.0) else {
        return Ok(());
    };
    // The rail's vertical force on the wheel is −Fz (z down, docs/conventions.md).
    let carried = -out.force[2];
    if (carried - q).abs() <= LOAD_CHECK_TOLERANCE * q + LOAD_CHECK_FLOOR {
        Ok(())
    } else {
        Err(WheelsetError::Unbalanced {
            side,
            carried,
            load: q,
        })
    }
}

/// Multi-Hertzian solution of one wheel (also the starting guess of the strip models, then
/// without the tangential problem: `tangential` false).
///
/// Prescribed load: the normal forces are balanced against Q less the creep forces' vertical
/// component by the load iteration on normal forces alone (cheap), then FASTSIM runs once at the
/// balanced height; the creep component is updated by an accelerated fixed point
/// ([`CreepFixedPoint`]) until it changes by less than [`CREEP_TOLERANCE`] of Q. `warm` (the
/// previous step's solution) gives the first approach and creep estimate. Returns the last
/// creep component found (`None` without a tangential problem).
#[allow(clippy::too_many_arguments)]
fn hertz_side(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    load: Option<f64>,
    z: f64,
    touch: f64,
    warm: Option<WarmStart>,
    out: &mut SideResult,
    tangential: bool,
) -> Result<Option<f64>, WheelsetError> {
    let Some(q) = load else {
        evaluate_side(side, ctx, input, z, z, out, tangential)?;
        return Ok(None);
    };
    if q == 0.0 {
        // Lift-off: the wheel just touches; no force.
        *out = SideResult {
            z: touch,
            ..SideResult::default()
        };
        return Ok(None);
    }
    // First approach: a Hertzian estimate for the deepest point alone.
    let deepest = side
        .geometry
        .candidates()
        .as_slice()
        .iter()
        .min_by(|a, b| a.gap.total_cmp(&b.gap))
        .copied()
        .expect("search returns at least one candidate");
    let unit = ctx
        .table
        .patch(deepest.curv_a, deepest.curv_b, 1e-4, ctx.e_star)?;
    let stiffness = unit.normal_force / 1e-4f64.powf(1.5);
    let cos_g = deepest.contact_angle.cos().max(0.05);
    let cold_approach = (q / (stiffness * cos_g)).powf(2.0 / 3.0) / cos_g;
    let (mut first_approach, start_creep) = warm.map_or((cold_approach, 0.0), |w| {
        let (approach, creep) = w.predicted();
        (approach, if tangential { creep } else { 0.0 })
    });
    let level = merge_level(touch, q, ctx.e_star, ctx.settings.setup.wheel_radius);
    creep_passes(q, start_creep, |_, target| {
        let balanced = balance_hertzian(touch, first_approach, target, LOAD_ITERATIONS, |dz| {
            Ok::<_, InputError>(evaluate_side(side, ctx, input, dz, level, out, false)? - target)
        })?;
        first_approach = balanced.lowering - touch;
        if !tangential {
            if !balanced.evaluated {
                evaluate_side(side, ctx, input, balanced.lowering, level, out, false)?;
            }
            return Ok(None);
        }
        if balanced.evaluated {
            complete_ellipses(side, ctx, input, out, true)?;
        } else {
            evaluate_side(side, ctx, input, balanced.lowering, level, out, true)?;
        }
        Ok(Some(creep_upward(out)))
    })
}

/// The interpenetration level at which a wheel's multi-Hertzian patch groups are decided under
/// the wheel load `load` [N] ([`crate::geometry::groups`]): first touch plus the approach of a Hertz
/// contact of radius `radius` (the nominal wheel radius) on a plane under that load,
/// δ = (9 Q²/(16 E*² R))^{1/3} (83 µm for 78.5 kN on a 0.46 m steel wheel, about a tread
/// contact's). It does not depend on the lowering being iterated, so that the wheel's vertical
/// force, a sum of group forces with fixed weights, increases with the lowering and the load has
/// one balancing lowering; it is continuous in the pose and the load.
fn merge_level(touch: f64, load: f64, e_star: f64, radius: f64) -> f64 {
    touch + (9.0 * load * load / (16.0 * e_star * e_star * radius)).cbrt()
}

/// Fixed-point iteration c ← g(c) on the creep forces' vertical component, accelerated by the
/// secant on h(c) = g(c) − c once two iterates exist (Steffensen-like; falls back to the plain
/// step when the secant is degenerate). The map is contracting (|g'| ≲ μ sin γ), so a few passes
/// reach [`CREEP_TOLERANCE`] — but on strip patches g is only piecewise smooth: it jumps by a
/// few newtons where the discretised tangential solution changes its element set with the
/// wheel height, and across a jump the secant bounces between the two sides. So the iterates
/// that bracket the root of h (h > 0 below, h < 0 above) are kept, and a step that would leave
/// the bracket bisects it instead, closing on the root or on the jump.
#[derive(Debug, Default)]
struct CreepFixedPoint {
    previous: Option<(f64, f64)>,
    /// Largest iterate with h > 0 and smallest with h < 0 so far.
    below: Option<f64>,
    above: Option<f64>,
}

impl CreepFixedPoint {
    /// The next iterate after evaluating g(`c`) = `g`.
    fn next(&mut self, c: f64, g: f64) -> f64 {
        let h = g - c;
        if h > 0.0 {
            self.below = Some(self.below.map_or(c, |b| b.max(c)));
        } else if h < 0.0 {
            self.above = Some(self.above.map_or(c, |a| a.min(c)));
        }
        let next = match self.previous {
            Some((c0, h0)) if (h - h0).abs() > 0.0 && c != c0 => {
                let secant = c - h * (c - c0) / (h - h0);
                if secant.is_finite() {
                    secant
                } else {
                    g
                }
            }
            _ => g,
        };
        self.previous = Some((c, h));
        match (self.below, self.above) {
            (Some(lo), Some(hi)) if lo < hi && !(next > lo && next < hi) => 0.5 * (lo + hi),
            _ => next,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn carrying(upward: f64) -> SideResult {
        let mut out = SideResult::default();
        out.force[2] = -upward;
        out
    }

    #[test]
    fn a_load_not_carried_is_refused_with_both_forces_named() {
        let q = 92_536.0;
        // Within the tolerance (a Linder-type jump of 0.1 %) and exactly balanced: accepted.
        for upward in [q, q * (1.0 + 1e-3), q * (1.0 - 0.9 * LOAD_CHECK_TOLERANCE)] {
            assert!(check_balance("right", Some(q), &carrying(upward)).is_ok());
        }
        // 18 % short (the ANALYN two-point case before its fix), nothing carried, NaN: refused.
        for upward in [0.82 * q, 0.0, f64::NAN, 1.02 * q] {
            let e = check_balance("right", Some(q), &carrying(upward)).unwrap_err();
            assert!(matches!(e, WheelsetError::Unbalanced { side: "right", .. }));
            let message = e.to_string();
            assert!(
                message.starts_with("right wheel: the normal model carries")
                    && message.contains("9.253600e4 N")
                    && message.contains("1e-2"),
                "{message}"
            );
        }
        // The absolute floor: 1 µN carried as nothing passes.
        assert!(check_balance("right", Some(1e-6), &carrying(0.0)).is_ok());
        // Prescribed position and lift-off are not checked.
        assert!(check_balance("left", None, &carrying(0.0)).is_ok());
        assert!(check_balance("left", Some(0.0), &carrying(0.0)).is_ok());
    }
}
