//! Non-elliptic patches of one wheel: strips on each patch's contact plane, a strip normal model
//! per patch, and the wheel's vertical position for a prescribed load (docs/theory.md §5.1–§5.2,
//! §7.9).
//!
//! For a wheel lowered by dz from its nominal height:
//! 1. **Layout** at the level L = touch + [`LAYOUT_FACTOR`] × (the multi-Hertzian approach): the
//!    patch groups of the gap's minima at L ([`crate::geometry::groups`]) each become a patch. Its
//!    contact plane passes through the share-weighted mean of its members' first-contact points,
//!    inclined by their shares' mean angle (a single minimum's tangent plane; blended, so that
//!    the plane moves continuously where two minima exchange the role). Its strips cover the
//!    interpenetration at L around its members, up to the ridges that separate it from the
//!    other groups ([`crate::geometry::search::WheelOnRail::crossing`]). The strips are fixed for
//!    the whole load iteration of the step, and every quantity of the layout is a continuous
//!    function of the pose and of the multi-Hertzian approach.
//! 2. the patch's normal approach is δ_p = dz cos γ_p − g_p (g_p its normal gap at nominal
//!    height) and the strip model gives its pressure; the wheel's vertical force is the sum over
//!    the patches, weighted by their groups' weights w_p, of their normal forces' vertical parts
//!    ([`StripPatch::frame`]: a planar patch's N along the normal of the planar theory's plane at
//!    this lowering, a non-planar one's strips each along their own normals), plus the creep
//!    forces' vertical components (held fixed during the iteration);
//! 3. prescribed load: dz by a bracketed Illinois iteration (N(dz) is continuous and increasing).
//!
//! Known limits: one layout plane per patch for the normal problem (the strips' own angles,
//! kept in [`StripPoints`], give the normal forces' directions of non-planar patches and their
//! tangential problem); a patch that would extend beyond its strips' range (a model much softer
//! than Hertz) is cut at the range's end.

use nalgebra::Vector3;

use super::balance::{creep_passes, CreepPass};
use super::kinematics::{
    contact_axes, creepages_at, planar_tangential, point_position, tangential_in_axes, NonPlanar,
};
use super::reuse::{PatchTangential, Tangential, TangentialMemo};
use super::{store_patch, Context, PatchResult, Side, SideResult, WheelsetError, WheelsetInput};
use crate::error::InputError;
use crate::geometry::groups::{group_bounds, groups_at, MAX_GROUPS};
use crate::geometry::search::{ContactPlane, ContactPoint, StripPoints, WheelOnRail};
use crate::geometry::strips::{PerStrip, StripGeometry};
use crate::normal::shape::HertzShapeTable;
use crate::normal::strips::{PatchSummary, StripSolution};
use crate::normal::{NormalModel, NormalParams, StripModel};
use crate::tangential::fastsim::Creepage;
use crate::tangential::patch::{strip_flexibilities, EquivalentEllipse, TangentialModel};
use crate::tangential::strip_fastsim::{StripFastsimResult, TangentialStrip};
use crate::wheelset::balance::{balance, ForceLaw, Guess, Root, LOAD_TOLERANCE};

/// One non-elliptic patch: its plane, strips, model state, solution and weight.
pub struct StripPatch {
    pub plane: ContactPlane,
    pub geom: StripGeometry,
    pub points: StripPoints,
    pub sol: StripSolution,
    /// Weight of the patch in the wheel's forces ([`crate::geometry::groups`]) [-].
    pub weight: f64,
    /// The smallest normal gap of the strips relative to the plane's origin [m]: the strips'
    /// `geom.f` are measured from it (their minimum is zero), and the patch's approach is the
    /// plane's approach less it — the approach of its deepest strip.
    pub gap_offset: f64,
    /// Per strip, the factor of d_j^{5/2} in its weight for the reference point
    /// ([`StripPatch::interpenetration_centre`]) [m^{-1/2}].
    reference_weight: PerStrip<f64>,
    model: Box<dyn StripModel + Send>,
}

impl StripPatch {
    fn new(model: NormalModel) -> Option<Self> {
        Some(Self {
            plane: ContactPlane::default(),
            geom: StripGeometry::default(),
            points: StripPoints::default(),
            sol: StripSolution::default(),
            weight: 0.0,
            gap_offset: 0.0,
            reference_weight: PerStrip::default(),
            model: model.strip_model()?,
        })
    }

    /// Sets the patch up on `plane` with `strips` strips between the rail points at the
    /// laterals `ends` (either order), and prepares its model.
    fn set_up(
        &mut self,
        geometry: &WheelOnRail,
        plane: ContactPlane,
        ends: (f64, f64),
        strips: usize,
        settings: &StripSettings,
        table: &HertzShapeTable,
    ) {
        let s_a = geometry.plane_coordinate_of(&plane, ends.0);
        let s_b = geometry.plane_coordinate_of(&plane, ends.1);
        self.plane = plane;
        geometry.strip_geometry(
            &plane,
            s_a.min(s_b),
            s_a.max(s_b),
            strips,
            &mut self.geom,
            &mut self.points,
        );
        // The models measure the gap from the patch's deepest point (f ≥ 0).
        let n = self.geom.len();
        let offset = self.geom.f[..n]
            .iter()
            .copied()
            .filter(|f| *f < crate::geometry::search::UNREACHED_GAP)
            .fold(f64::INFINITY, f64::min);
        self.gap_offset = if offset.is_finite() { offset } else { 0.0 };
        for f in &mut self.geom.f[..n] {
            if *f < crate::geometry::search::UNREACHED_GAP {
                *f -= self.gap_offset;
            }
        }
        // The interpenetration's weight per strip is ∫ over its lateral extent dy (track) of
        // d_v^{5/2}/√A: dy = ds cos γ_j / cos(γ_j − γ_p) along the rail, γ_p the plane's angle.
        let gamma_p = self.plane.gamma_rail;
        for j in 0..n {
            let angle = self.points.angle[j];
            let lateral_per_s = angle.cos() / (angle - gamma_p).cos();
            let a = self.geom.curv_a[j];
            self.reference_weight[j] = if a > 0.0 && lateral_per_s > 0.0 {
                lateral_per_s / a.sqrt()
            } else {
                0.0
            };
        }
        self.model.prepare(&self.geom, &settings.params, table);
    }

    /// Normal approach of the patch's deepest strip when the wheel is lowered by `dz` [m].
    pub fn approach(&self, dz: f64) -> f64 {
        self.plane.approach(dz) - self.gap_offset
    }

    /// Normal force at wheel lowering `dz` [N] (writes the solution).
    fn solve(&mut self, dz: f64, params: &NormalParams, table: &HertzShapeTable) -> f64 {
        let delta = self.approach(dz);
        self.model
            .solve(&self.geom, params, table, delta, &mut self.sol)
    }

    pub fn summary(&self) -> PatchSummary {
        PatchSummary::of(&self.geom, &self.sol)
    }

    /// The weighted centre of the patch's interpenetration with the wheel lowered by `dz` [m]
    /// and the weighted mean of the rail's inclination over it: (s [m], γ [rad], track frame),
    /// or `None` where no strip overlaps. The vertical interpenetration d(x, y) = d_y − A_y x²
    /// at the lateral y weighs it by ∫ d² dx = (16/15) d_y^{5/2}/√A_y — the contact reference
    /// of Kalker's planar theory as CONTACT places it (docs/theory.md §7.9) — summed over the
    /// strips (d_j = dz less the strip's vertical gap, over its lateral extent,
    /// `reference_weight`). Continuous in dz and in the strips' gaps (a strip enters with zero
    /// weight).
    pub fn interpenetration_centre(&self, dz: f64) -> Option<(f64, f64)> {
        let g = &self.geom;
        let (mut total, mut s_sum, mut angle_sum) = (0.0, 0.0, 0.0);
        for j in 0..g.n {
            let depth = dz - self.points.vertical_gap[j];
            if depth.is_nan() || depth <= 0.0 {
                continue;
            }
            let weight = depth * depth * depth.sqrt() * self.reference_weight[j];
            total += weight;
            s_sum += weight * g.s[j];
            angle_sum += weight * self.points.angle[j];
        }
        (total > 0.0 && total.is_finite()).then(|| (s_sum / total, angle_sum / total))
    }

    /// Σ N_j sin γ_j and Σ N_j cos γ_j of the last solution: the lateral and vertical parts of
    /// the strips' normal forces, each along its own surface normal (track frame, before the
    /// side's sign) [N].
    pub fn normal_resultant(&self) -> (f64, f64) {
        let (mut lateral, mut vertical) = (0.0, 0.0);
        for j in 0..self.geom.n.min(self.sol.n) {
            let n = self.sol.force[j];
            if n > 0.0 {
                lateral += n * self.points.sin_angle[j];
                vertical += n * self.points.cos_angle[j];
            }
        }
        (lateral, vertical)
    }

    /// Where and along which normal the last solution's normal force acts, with the wheel
    /// lowered by `dz` [m] (docs/conventions.md, "Reference point"): the reference point at the
    /// weighted centre of the interpenetration ([`StripPatch::interpenetration_centre`], CONTACT's
    /// contact reference point) where the model takes it there
    /// ([`NormalModel::reference_at_interpenetration`]), else (and where nothing interpenetrates)
    /// at the force centroid of the strips; on a planar patch (`settings.planar`) the force
    /// Σ N_j along the normal of the plane of Kalker's planar theory, inclined by the
    /// interpenetration's weighted mean inclination; on a non-planar one each strip's N_j along
    /// its own normal, whose resultant gives the angle and the force.
    pub fn frame(&self, dz: f64, settings: &StripSettings) -> PatchFrame {
        let n = self.geom.n.min(self.sol.n);
        let (mut normal_force, mut moment) = (0.0, 0.0);
        for j in 0..n {
            let force = self.sol.force[j].max(0.0);
            normal_force += force;
            moment += force * self.geom.s[j];
        }
        // The interpenetration's centre where the reference point or the plane's angle needs it.
        let at_centre = settings.model.reference_at_interpenetration();
        let centre = (at_centre || settings.planar || normal_force <= 0.0)
            .then(|| self.interpenetration_centre(dz))
            .flatten();
        let s = match centre {
            Some((s, _)) if at_centre => s,
            _ if normal_force > 0.0 => moment / normal_force,
            _ => 0.0,
        };
        let plane_angle = || self.plane_angle(centre);
        if settings.planar {
            return PatchFrame {
                s,
                angle: plane_angle(),
                normal_force,
                resultant: normal_force,
            };
        }
        let (lateral, vertical) = self.normal_resultant();
        PatchFrame {
            s,
            angle: if normal_force > 0.0 {
                lateral.atan2(vertical)
            } else {
                plane_angle()
            },
            normal_force,
            resultant: lateral.hypot(vertical),
        }
    }

    /// The upward part of the last solution's normal forces with the wheel lowered by `dz` [m]
    /// ([`PatchFrame::vertical`] of [`StripPatch::frame`], without its reference point): on a
    /// planar patch Σ N_j cos γ of the plane's angle, on a non-planar one Σ N_j cos γ_j [N].
    pub fn vertical(&self, dz: f64, planar: bool) -> f64 {
        if planar {
            let n = self.geom.n.min(self.sol.n);
            let normal_force: f64 = self.sol.force[..n].iter().map(|f| f.max(0.0)).sum();
            normal_force * self.plane_angle(self.interpenetration_centre(dz)).cos()
        } else {
            self.normal_resultant().1
        }
    }

    /// The planar contact angle from the interpenetration's `centre` (its weighted mean
    /// inclination), the layout plane's where nothing interpenetrates [rad].
    fn plane_angle(&self, centre: Option<(f64, f64)>) -> f64 {
        centre.map_or(self.plane.gamma_rail, |(_, angle)| angle)
    }

    /// Linear interpolation of a per-strip quantity at in-plane coordinate `s`.
    pub fn interpolate(&self, values: &[f64], s: f64) -> f64 {
        self.interpolate_by(s, |j| values[j])
    }

    /// [`StripPatch::interpolate`] of the per-strip quantity `value(j)`, evaluated at the (at
    /// most two) strips the interpolation uses.
    pub fn interpolate_by(&self, s: f64, value: impl Fn(usize) -> f64) -> f64 {
        let g = &self.geom;
        if g.n == 1 {
            return value(0);
        }
        let t = ((s - g.s[0]) / g.ds).clamp(0.0, (g.n - 1) as f64);
        // `as usize` floors a non-negative value (and saturates below 0) without a call to
        // libm's floor, which baseline x86-64 (no SSE4.1 rounding) would need.
        let i = (t as usize).min(g.n - 2);
        let u = t - i as f64;
        let (lo, hi) = (value(i), value(i + 1));
        lo + (hi - lo) * u
    }
}

/// Where a strip patch's normal force acts ([`StripPatch::frame`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchFrame {
    /// In-plane coordinate of the reference point [m].
    pub s: f64,
    /// Contact angle in the track frame, positive rising towards the flange [rad].
    pub angle: f64,
    /// Normal force Σ N_j: the patch's normal load, reported along the normal of `angle` [N]
    /// (unweighted).
    pub normal_force: f64,
    /// |Σ N_j n_j|, the resultant of the strips' normal forces along their own normals n_j
    /// (the normal force of a planar patch): less than `normal_force` by a factor
    /// ≈ 1 − var(γ_j)/2 on a non-planar one [N].
    pub resultant: f64,
}

impl PatchFrame {
    /// The vertical part of the normal forces' resultant [N] (Σ N_j cos γ_j on a non-planar
    /// patch): with the creep forces' vertical component, the wheel's vertical force.
    pub fn vertical(&self) -> f64 {
        self.resultant * self.angle.cos()
    }
}

/// The strip patches of one wheel.
pub struct StripSide {
    patches: Vec<StripPatch>,
    count: usize,
    /// The last balanced lowering, to which the patches' solutions belong: a rebalance under a
    /// slightly changed force starts there without evaluating it again (slope in dF/dz [N/m]).
    last_root: Option<Root>,
}

/// Settings of the strip solve.
#[derive(Debug, Clone, Copy)]
pub struct StripSettings {
    pub model: NormalModel,
    pub strips: usize,
    pub params: NormalParams,
    /// Planar patches (one normal per patch) or each strip's normal force along its own
    /// normal ([`StripPatch::frame`]).
    pub planar: bool,
}

/// Iteration limit of the load balance.
const LOAD_ITERATIONS: usize = 80;

/// Level of the strip layout, as a multiple of the multi-Hertzian approach beyond first touch:
/// the strips cover the interpenetration region at that lowering. Every model's patch lies
/// inside the rigid interpenetration region at its own approach (a virtual penetration ε < 1, or
/// ANALYN's δ − (1 + β) f > 0, which on wheel–rail gaps reaches 0.5–0.8 of the approach), and at
/// a given load the models' approaches stay within ~1.5 × Hertz's, so 1.3 contains their patches
/// while the patch still spans most of the strips: the defaults' creep forces stay within 1 % of
/// the converged strips' (`tests/defaults_accuracy.rs`; at 1.5, 1.07 %).
pub const LAYOUT_FACTOR: f64 = 1.3;

/// Fraction of a group's depth at the layout level whose interpenetration's centroid is the
/// origin of its contact plane: Kik–Piotrowski's ε, as the multi-Hertzian reference point.
const ANCHOR_FRACTION: f64 = crate::normal::kik_piotrowski::KP_EPSILON;

impl StripSide {
    /// Buffers for `model`; `None` for Hertz.
    pub fn new(model: NormalModel) -> Option<Self> {
        Some(Self {
            patches: (0..MAX_GROUPS)
                .map(|_| StripPatch::new(model))
                .collect::<Option<_>>()?,
            count: 0,
            last_root: None,
        })
    }

    pub fn patches(&self) -> &[StripPatch] {
        &self.patches[..self.count]
    }

    /// Vertical force of the rail on the wheel lowered by `dz` (upwards positive) [N]: the upward
    /// part of each patch's normal forces, planar or not ([`StripPatch::vertical`]).
    fn vertical_force(
        &mut self,
        dz: f64,
        settings: &StripSettings,
        table: &HertzShapeTable,
    ) -> f64 {
        self.patches[..self.count]
            .iter_mut()
            .map(|p| {
                let n = p.solve(dz, &settings.params, table);
                if n > 0.0 {
                    p.weight * p.vertical(dz, settings.planar)
                } else {
                    0.0
                }
            })
            .sum()
    }

    /// Step 1: one patch per group at the level `level` [m].
    fn lay_out(
        &mut self,
        geometry: &mut WheelOnRail,
        level: f64,
        settings: &StripSettings,
        table: &HertzShapeTable,
    ) {
        let (layout, candidates, m) = groups_at(geometry, level, level, 0.0);
        let candidates = &candidates[..m];
        let mut ridges = [None; crate::geometry::search::MAX_CANDIDATES];
        ridges[..m.saturating_sub(1)].copy_from_slice(geometry.ridges());
        let ridges = &ridges[..m.saturating_sub(1)];
        let scan = geometry.scan_range();
        self.count = 0;
        for group in layout.groups() {
            let (gauge_bound, field_bound) = group_bounds(candidates, ridges, group, scan);
            let field = geometry.crossing(candidates[group.first].lateral, field_bound, level);
            let gauge = geometry.crossing(candidates[group.last].lateral, gauge_bound, level);
            if field.is_nan() || gauge.is_nan() || field <= gauge {
                continue;
            }
            // The plane through the centroid of the group's virtual interpenetration at the
            // layout level (the deepest point on a Hertzian gap), tangent to the rail there.
            let deepest = candidates[group.first..=group.last]
                .iter()
                .map(|c| c.gap)
                .fold(f64::INFINITY, f64::min);
            let virtual_level = deepest + ANCHOR_FRACTION * (level - deepest);
            let w0 = geometry
                .depth_moments(gauge_bound, field_bound, virtual_level)
                .map_or(candidates[group.first].lateral, |m| m.mean);
            let plane = geometry.contact_plane(w0, geometry.gap_at(w0));
            let patch = &mut self.patches[self.count];
            patch.set_up(
                geometry,
                plane,
                (gauge, field),
                settings.strips,
                settings,
                table,
            );
            patch.weight = group.weight;
            self.count += 1;
        }
    }

    /// Solves the wheel: prescribed vertical force `target` [N] (`Some`, > 0) or prescribed
    /// lowering `dz_hint` (`None`). `touch` is the lowering at first contact and `dz_hint` the
    /// multi-Hertzian lowering that carries the load (or the prescribed one): the strips are
    /// laid out at [`LAYOUT_FACTOR`] times its approach. The load iteration starts at
    /// `ratio_hint` (within [½, 2]) × the multi-Hertzian approach (the previous step's ratio: a
    /// warm start that changes the balanced lowering only within the iteration's tolerance),
    /// its first correction Newton's step with the Hertzian slope dF/dδ = 3F/(2δ) there
    /// (docs/theory.md §8.3).
    /// Returns the lowering.
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        geometry: &mut WheelOnRail,
        settings: &StripSettings,
        table: &HertzShapeTable,
        target: Option<f64>,
        touch: f64,
        dz_hint: f64,
        ratio_hint: f64,
    ) -> f64 {
        let approach = (dz_hint - touch).max(0.0);
        self.last_root = None;
        self.lay_out(geometry, touch + LAYOUT_FACTOR * approach, settings, table);
        match target {
            Some(q) => {
                let trial_approach = approach * ratio_hint.clamp(0.5, 2.0);
                let trial = Guess {
                    approach: trial_approach,
                    slope: (trial_approach > 0.0).then(|| 1.5 * q / trial_approach),
                    ..Guess::default()
                };
                self.iterate(q, touch, trial, settings, table)
            }
            None => {
                self.vertical_force(dz_hint, settings, table);
                dz_hint
            }
        }
    }

    /// Re-solves the lowering for a new vertical force `target` [N] > 0 on the current patches
    /// (no new strips: the creep-force update of the load balance must not move strip edges),
    /// starting from the lowering `dz`. Returns the new lowering.
    pub fn rebalance(
        &mut self,
        settings: &StripSettings,
        table: &HertzShapeTable,
        target: f64,
        touch: f64,
        dz: f64,
    ) -> f64 {
        let guess = match self.last_root {
            Some(root) if root.lowering == dz => root.guess(touch, target),
            _ => Guess {
                approach: dz - touch,
                ..Guess::default()
            },
        };
        self.iterate(target, touch, guess, settings, table)
    }

    /// The lowering at which the vertical force equals `q` > 0 ([`balance`] from `guess`, its
    /// approach beyond `touch`); the patches' solutions are left at that lowering.
    fn iterate(
        &mut self,
        q: f64,
        touch: f64,
        guess: Guess,
        settings: &StripSettings,
        table: &HertzShapeTable,
    ) -> f64 {
        let guess = Guess {
            approach: guess.approach.max(1e-9),
            ..guess
        };
        let Ok(balanced) = balance(
            touch,
            guess,
            q,
            LOAD_TOLERANCE,
            LOAD_ITERATIONS,
            ForceLaw::General,
            |dz| Ok::<_, std::convert::Infallible>(self.vertical_force(dz, settings, table) - q),
        );
        if !balanced.evaluated {
            self.vertical_force(balanced.lowering, settings, table);
        }
        self.last_root = Some(balanced.root(q));
        balanced.lowering
    }
}

/// Writes the outputs of the strip patches of `side` (solved at lowering `dz`): patch figures
/// from the strips, reference point and normal force's direction from its [`StripPatch::frame`],
/// tangential forces by the strip solvers of [`crate::tangential::strip_fastsim`] (planar or non-planar,
/// flexibilities per [`TangentialModel`]; or a recorded solution scaled, as `tangential` says).
/// Returns the creep forces' upward component on the wheel: its upward force less that of the
/// patches' normal forces ([`PatchFrame::vertical`], weighted) [N].
pub(super) fn evaluate_strips(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    dz: f64,
    out: &mut SideResult,
    mut tangential: Tangential,
) -> Result<f64, InputError> {
    out.clear(dz);
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
        let slot = out.n_groups;
        let at = (slot, index);
        match strip_patch_result(side, ctx, input, patch, &summary, dz, at, &mut tangential) {
            Ok((result, tangential, normal_upward)) => {
                side.strip_of_group[out.n_groups] = Some(index);
                side.group_key[out.n_groups] = index;
                let lateral = &patch.points.lateral;
                side.part_bounds[out.n_groups] = (lateral[0], lateral[patch.geom.len() - 1]);
                upward += store_patch(side.sigma, result, patch.weight, tangential, out);
                upward -= patch.weight * normal_upward;
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

/// Normal and tangential result of one strip patch (in output slot `slot`, `key` its index
/// among the side's strip patches, [`PatchTangential::key`]), its tangential force in track
/// axes (with a non-planar patch's difference between its reported normal force and its strips'
/// resultant) and the upward part of its normal forces' resultant [N]; the tangential problem
/// solved or taken from a record as `tangential` says ([`Tangential::None`] solves it,
/// unrecorded).
#[allow(clippy::too_many_arguments)]
pub(super) fn strip_patch_result(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    patch: &StripPatch,
    summary: &crate::normal::strips::PatchSummary,
    dz: f64,
    (slot, key): (usize, usize),
    tangential: &mut Tangential,
) -> Result<(PatchResult, Vector3<f64>, f64), InputError> {
    let frame = patch.frame(dz, &ctx.strips);
    let at = |v: &[f64]| patch.interpolate(v, frame.s);
    let reference = ContactPoint {
        lateral: at(&patch.points.lateral),
        longitudinal: at(&patch.geom.x_c),
        y_rail: at(&patch.points.y_rail),
        contact_angle: frame.angle,
        rolling_radius: at(&patch.points.rolling_radius),
        curv_a: at(&patch.geom.curv_a),
        curv_b: at(&patch.geom.curv_b),
        ..ContactPoint::default()
    };
    let gamma = reference.contact_angle;
    let (creepage, speed) = creepages_at(input, side.sigma, &side.rail, &reference, gamma);
    let equivalent = EquivalentEllipse::of(
        summary,
        ctx.shear_modulus,
        ctx.material.poisson_ratio,
        ctx.material.friction,
    )?;
    let mu = ctx.material.friction;
    let t = tangential.patch(key, summary.normal_force, mu, || {
        let at_reference = (&reference, frame.s, creepage, speed);
        solve_strip_tangential(
            side,
            ctx,
            input,
            patch,
            summary,
            (slot, key),
            at_reference,
            &equivalent,
        )
    })?;
    let mut result = PatchResult {
        fn_: frame.normal_force,
        area: summary.area,
        pmax: summary.pmax,
        a: equivalent.contact.a,
        b: equivalent.contact.b,
        length: summary.length,
        width: summary.width,
        y_rail: reference.y_rail,
        position: point_position(side.sigma, &reference, input.yaw, input.roll).into(),
        contact_angle: gamma,
        rolling_radius: reference.rolling_radius,
        penetration: patch.approach(dz),
        creepage,
        curv_a: reference.curv_a,
        curv_b: reference.curv_b,
        weight: 1.0,
        ..PatchResult::default()
    };
    result.set_tangential(&t.solution, speed);
    if ctx.strips.planar {
        // In the patch's axes at this pass's angle (a reused solution's vector was summed in
        // the axes of the pass that solved it).
        let s = &t.solution;
        let tangential = planar_tangential(side.sigma, frame.angle, s.fx, s.fy);
        return Ok((result, tangential, frame.vertical()));
    }
    // The wheel's force carries the strips' normal forces along their own normals: their
    // resultant, less than the reported Σ N_j along e_z.
    let (_, e_z) = contact_axes(side.sigma, frame.angle);
    let tangential = t.tangential + e_z * (frame.normal_force - frame.resultant);
    Ok((result, tangential, frame.vertical()))
}

/// The tangential problem of one strip patch (in slot `slot`, recorded under `key`; its
/// reference point with the creepages and speed there, its equivalent ellipse): the strip
/// solver of the `tangentialModel`, planar or non-planar.
#[allow(clippy::too_many_arguments)]
fn solve_strip_tangential(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    patch: &StripPatch,
    summary: &crate::normal::strips::PatchSummary,
    (slot, key): (usize, usize),
    (reference, s_ref, creepage, speed): (&ContactPoint, f64, Creepage, f64),
    equivalent: &EquivalentEllipse,
) -> Result<PatchTangential, InputError> {
    let settings = ctx.settings;
    let gamma = reference.contact_angle;
    let source = settings
        .tangential
        .flexibility_source(settings.normal_model);
    let b_floor = ctx.strips.params.b_floor();
    // Prescribed creepages hold on every strip (in its own axes); kinematic ones are each
    // strip's own (docs/theory.md §5.8).
    let non_planar = if settings.planar_patch {
        None
    } else {
        NonPlanar::new(input, side.sigma, &side.rail)
    };
    let n = patch.geom.len();
    // The strips' x is measured from the reference point (its yaw lead x_ref), where the
    // patch's creepages hold: the spin's lateral slip φ·x is then zero there, as in Kalker's
    // rigid slip w = (ξ − φy, η + φx) about the reference point.
    let x_ref = reference.longitudinal;
    for j in 0..n {
        let lever = side.sigma * (patch.geom.s[j] - s_ref);
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
                // The strip's rigid slip is its own: no lever term of a reference spin.
                let trig = (patch.points.sin_angle[j], patch.points.cos_angle[j]);
                strip.creepage = non_planar.creepage(strip_point(patch, j, x_ref), trig);
                strip.reference_spin = 0.0;
            }
            strip.flexibility = strip_flexibilities(
                source,
                settings.fastsim.flexibility,
                &patch.geom,
                &patch.sol,
                j,
                b_floor,
                ctx.table,
                equivalent,
                &strip.creepage,
            )?;
        }
        side.tangential_strips[j] = strip;
    }
    let solver = &mut side.strip_fastsim[slot];
    let mu = ctx.material.friction;
    let t = if settings.tangential.is_fastrip() {
        let coupled = settings.tangential == TangentialModel::FastripCoupled;
        solver.solve_fastrip(&side.tangential_strips[..n], equivalent, speed, coupled)
    } else {
        solver.solve(&side.tangential_strips[..n], mu, speed)
    };
    side.field_key[slot] = Some(key);
    // Forces: planar — all strips in the patch's axes; non-planar — each strip's in its own.
    let mut tangential = Vector3::zeros();
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
        tangential += tangential_in_axes(side.sigma, (sin_j, cos_j), fx, fy);
        // cos(γ_j − γ).
        fy_patch += fy * (cos_j * cos_g + sin_j * sin_g);
    }
    Ok(PatchTangential {
        normal_force: summary.normal_force,
        key,
        solution: StripFastsimResult { fy: fy_patch, ..t },
        tangential,
    })
}

/// Replaces the Hertz solution in `out` by the side's strip model: `load` prescribed (`out.z`,
/// the Hertz solution's lowering or the warm start's, is the starting guess, and `creep` the
/// first estimate of the creep forces' vertical component) or the lowering `out.z`. Returns the
/// last evaluated creep component (prescribed load only).
#[allow(clippy::too_many_arguments)]
pub(super) fn solve_strips(
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
    let mut memo = TangentialMemo::default();
    let q = load.unwrap_or(0.0);
    // One pass: the strip layout and solve (the first, or without a load) or its re-balance to
    // `target`, then the tangential problem at the new lowering; returns the creep forces'
    // vertical component and whether it reused the last pass's tangential solution. The layout
    // follows from the multi-Hertzian lowering `out.z` alone.
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
        // A later pass whose target moved by little keeps the last solved tangential solution,
        // scaled, once per step ([`crate::wheelset::reuse`]).
        let target = target.unwrap_or(f64::NAN);
        let mode = memo.pass(k, target, q, ctx.settings.reuse_tangential);
        let reused = mode.reuses();
        let creep = evaluate_strips(side, ctx, input, dz, out, mode)?;
        Ok::<_, WheelsetError>((creep, reused))
    };
    match load {
        None => pass(side, 0, None).map(|_| None),
        Some(q) => creep_passes(q, creep, |k, target| {
            let (creep, reused) = pass(side, k, Some(target))?;
            Ok(Some(CreepPass {
                creep,
                tight: true,
                reused,
            }))
        }),
    }
}

/// The point of strip `j` of `patch` on the wheelset for its creepages: (longitudinal,
/// lateral, rolling radius) [m] (its contact angle enters through its sine and cosine). The
/// longitudinal position is the patch reference point's `x_ref`, not the strip's own yaw lead:
/// the tangential solvers measure x from the reference point and add the spin's φ_j·x along
/// the strip themselves, so the strip's creepages must hold at x = 0 of that frame.
fn strip_point(patch: &StripPatch, j: usize, x_ref: f64) -> Vector3<f64> {
    Vector3::new(
        x_ref,
        patch.points.lateral[j],
        patch.points.rolling_radius[j],
    )
}
