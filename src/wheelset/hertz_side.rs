//! The multi-Hertzian side of a wheel: one Hertz patch per patch group, FASTSIM on each, the
//! prescribed-load iteration.

use super::balance::{
    creep_passes, creep_upward, CreepPass, WarmStart, CREEP_TOLERANCE, LOAD_TOLERANCE,
};
use super::kinematics::{creepages_at, planar_tangential, point_position};
use super::reuse::{PatchTangential, Tangential, TangentialMemo};
use super::{
    store_patch, Context, PatchResult, Side, SideResult, WheelsetError, WheelsetInput,
    LOAD_ITERATIONS,
};
use crate::error::InputError;
use crate::geometry::groups::MAX_GROUPS;
use crate::geometry::groups::{group_bounds, groups_at};
use crate::geometry::search::{ContactPoint, WheelOnRail};
use crate::tangential::fastsim::EllipticContact;
use crate::tangential::strip_fastsim::StripFastsimResult;
use crate::wheelset::balance::{balance, ForceLaw, Guess, Root};

/// Fraction of a patch group's depth at which its reference point is taken (see
/// [`evaluate_side`]): the force centroid of the interpenetration above this fraction of its
/// depth. On a symmetric gap any fraction gives the deepest point; on the conformal right wheel
/// of the Manchester benchmark at 0.5 mm (a rigid region 17 mm wide, 25 µm deep), 0.8 lands
/// within 0.5 mm of CONTACT's reference point (0.55, Kik–Piotrowski's ε, 2.2 mm off with the
/// spread-based ellipse; tests/manchester.rs).
pub(super) const VIRTUAL_FRACTION: f64 = 0.8;

/// Evaluates one wheel lowered by `dz` (normal forces, and the tangential problem per patch as
/// `tangential` says: FASTSIM, or a recorded solution scaled); returns the vertical force of the rail on the wheel, upwards positive [N].
///
/// Multi-Hertzian: every patch group at the level dz ([`crate::geometry::groups`]) is one Hertz
/// patch, described by integrals of its interpenetration between the ridges that separate it
/// from the other groups — never by the position of one minimum, which in a conformal contact
/// is round-off (the gap is flat to 0.1 µm over millimetres where S1002's R13 flange root meets
/// UIC60's R13 gauge corner):
/// The groups are those at `merge_level` (fixed for the wheel's load iteration, so that the
/// vertical force increases with dz: [`merge_level`]); a group whose minima all lie above dz
/// carries nothing.
/// * depth δ_v = dz − g_min (vertical), g_min the group's deepest gap, no deeper than the
///   lowest point of the gap's interpolant over the group (which the moments below integrate:
///   a refined minimum can lie ~0.1 µm below it on a narrow flange root), so that a patch
///   enters contact from nothing;
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
pub(super) fn evaluate_side(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    dz: f64,
    merge_level: f64,
    out: &mut SideResult,
    tangential: Tangential,
) -> Result<f64, InputError> {
    out.clear(dz);
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
    for (key, group) in layout.groups().iter().enumerate() {
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
            let bounds = group_bounds(candidates, ridges, group, scan);
            side.ellipses[side.n_ellipses] = (reference, patch, group.weight, key, bounds);
            side.n_ellipses += 1;
        }
    }
    complete_ellipses(side, ctx, input, out, tangential)
}

/// Writes the multi-Hertzian patches of the side's last normal solution ([`evaluate_side`]) to
/// `out` (lowering `out.z`), with the tangential problem per patch as `tangential` says;
/// returns the vertical force of the rail on the wheel, upwards positive [N]. The tangential
/// problem at a lowering whose normal solution is at hand needs no new one.
pub(super) fn complete_ellipses(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    out: &mut SideResult,
    mut tangential: Tangential,
) -> Result<f64, InputError> {
    out.clear(out.z);
    let mut upward = 0.0;
    for k in 0..side.n_ellipses {
        let (reference, patch, weight, key, bounds) = side.ellipses[k];
        if out.n_groups < MAX_GROUPS {
            side.part_bounds[out.n_groups] = bounds;
        }
        upward += add_patch(
            side,
            ctx,
            input,
            &reference,
            patch,
            (weight, key),
            out,
            &mut tangential,
        )?;
    }
    Ok(upward)
}

/// The Hertz patch of `group` at lowering `dz` ([`evaluate_side`]): its reference point and its
/// normal solution, or `None` where it has no interpenetration.
#[allow(clippy::too_many_arguments)]
pub(super) fn group_ellipse(
    geometry: &WheelOnRail,
    ctx: &Context,
    candidates: &[ContactPoint],
    ridges: &[Option<crate::geometry::search::Ridge>],
    group: &crate::geometry::groups::Group,
    scan: (f64, f64),
    dz: f64,
    b_floor: f64,
) -> Result<Option<(ContactPoint, PatchResult)>, InputError> {
    // The deepest gap, and no deeper than the interpolant the moments below integrate (whose
    // minima are the candidates): the patch starts from nothing as the lowering reaches it.
    let group_candidates = &candidates[group.first..=group.last];
    let refined = group_candidates
        .iter()
        .map(|c| c.gap)
        .fold(f64::INFINITY, f64::min);
    let interpolated = group_candidates
        .iter()
        .map(|c| geometry.lowest_near(c.lateral))
        .fold(f64::INFINITY, f64::min);
    let deepest = refined.max(interpolated);
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
/// ellipse (or the recorded solution scaled, [`Tangential::Reuse`]); stores it with its group's
/// weight in the next entry of `out.groups`, adds its force to `out.force` (track axes) and
/// returns its upward force on the wheel [N]. `(weight, key)`: the group's weight and its index
/// in the step's layout ([`PatchTangential::key`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn add_patch(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    reference: &ContactPoint,
    mut result: PatchResult,
    (weight, key): (f64, usize),
    out: &mut SideResult,
    tangential: &mut Tangential,
) -> Result<f64, InputError> {
    if out.n_groups >= MAX_GROUPS {
        return Ok(0.0);
    }
    let gamma = reference.contact_angle;
    let (creepage, speed) = creepages_at(input, side.sigma, &side.rail, reference, gamma);
    result.y_rail = reference.y_rail;
    result.position = point_position(side.sigma, reference, input.yaw, input.roll).into();
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
    if let Tangential::None = tangential {
        return Ok(store_patch(
            side.sigma,
            result,
            weight,
            nalgebra::Vector3::zeros(),
            out,
        ));
    }
    let group = out.n_groups;
    let fastsim = &mut side.fastsim[group];
    let mut solved = false;
    let t = tangential.patch(key, result.fn_, ctx.material.friction, || {
        let t = fastsim.solve(&contact, &creepage, speed)?;
        solved = true;
        Ok::<_, InputError>(PatchTangential {
            normal_force: result.fn_,
            key,
            solution: StripFastsimResult::from(&t),
            tangential: nalgebra::Vector3::zeros(),
        })
    })?;
    if solved {
        side.field_key[group] = Some(key);
    }
    side.group_key[group] = key;
    result.set_tangential(&t.solution, speed);
    let tangential = planar_tangential(side.sigma, gamma, result.fx, result.fy);
    Ok(store_patch(side.sigma, result, weight, tangential, out))
}

/// Multi-Hertzian solution of one wheel (also the starting guess of the strip models, then
/// without the tangential problem: `tangential` false).
///
/// Prescribed load: the normal forces are balanced against Q less the creep forces' vertical
/// component by the load iteration on normal forces alone (cheap), then FASTSIM runs once at the
/// balanced height; the creep component is updated by an accelerated fixed point
/// ([`CreepFixedPoint`]) until it changes by less than [`CREEP_TOLERANCE`] of Q. `warm` (the
/// previous step's solution) gives the first approach, creep estimate and the force's slope.
/// Returns the last creep component found (`None` without a tangential problem) and the force's
/// slope at the root ([`crate::wheelset::balance::Balanced::slope`]; NaN where not measured).
#[allow(clippy::too_many_arguments)]
pub(super) fn hertz_side(
    side: &mut Side,
    ctx: &Context,
    input: &WheelsetInput,
    load: Option<f64>,
    z: f64,
    touch: f64,
    warm: Option<WarmStart>,
    out: &mut SideResult,
    tangential: bool,
) -> Result<(Option<f64>, f64), WheelsetError> {
    let mut memo = TangentialMemo::default();
    let Some(q) = load else {
        let mode = if tangential {
            Tangential::Solve(&mut memo)
        } else {
            Tangential::None
        };
        evaluate_side(side, ctx, input, z, z, out, mode)?;
        return Ok((None, f64::NAN));
    };
    if q == 0.0 {
        // Lift-off: the wheel just touches; no force.
        out.clear(touch);
        return Ok((None, f64::NAN));
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
    let (first_approach, start_creep, first_slope) = warm.map_or((cold_approach, 0.0, None), |w| {
        let (approach, creep, slope) = w.predicted();
        (approach, if tangential { creep } else { 0.0 }, slope)
    });
    let level = merge_level(touch, q, ctx.e_star, ctx.settings.setup.wheel_radius);
    let first = Guess {
        approach: first_approach,
        residual: None,
        slope: first_slope,
    };
    // The previous pass's root: the next pass starts there, without evaluating it again, with
    // Newton's step on its slope.
    let mut root: Option<Root> = None;
    let creep = creep_passes(q, start_creep, |k, target| {
        let guess = root.map_or(first, |r| r.guess(touch, target));
        // The first pass's target carries the creep estimate's error: balancing it beyond that
        // is wasted (the next pass starts from its root). Normal forces alone are the strip
        // models' starting point and the level of their strip layout, which a relative error of
        // the creep tolerance moves by ~1e−7 of the approach: balanced as loosely.
        let tolerance = if k == 0 {
            CREEP_TOLERANCE
        } else {
            LOAD_TOLERANCE
        };
        let balanced = balance(
            touch,
            guess,
            target,
            tolerance,
            LOAD_ITERATIONS,
            ForceLaw::Hertzian,
            |dz| {
                Ok::<_, InputError>(
                    evaluate_side(side, ctx, input, dz, level, out, Tangential::None)? - target,
                )
            },
        )?;
        // The side's patches belong to the root when the pass ends (evaluated last, or
        // evaluated again below).
        root = Some(balanced.root(target));
        // A later pass whose target moved by little keeps the last solved tangential solution,
        // scaled, once per step ([`crate::wheelset::reuse`]).
        let mode = if tangential {
            memo.pass(k, target, q, ctx.settings.reuse_tangential)
        } else {
            Tangential::None
        };
        let reused = mode.reuses();
        if balanced.evaluated {
            complete_ellipses(side, ctx, input, out, mode)?;
        } else {
            evaluate_side(side, ctx, input, balanced.lowering, level, out, mode)?;
        }
        if !tangential {
            return Ok(None);
        }
        let tight = balanced.residual.abs() <= LOAD_TOLERANCE * target;
        Ok(Some(CreepPass {
            creep: creep_upward(out),
            tight,
            reused,
        }))
    })?;
    Ok((creep, root.map_or(f64::NAN, |r| r.slope)))
}

/// The interpenetration level at which a wheel's multi-Hertzian patch groups are decided under
/// the wheel load `load` [N] ([`crate::geometry::groups`]): first touch plus the approach of a Hertz
/// contact of radius `radius` (the nominal wheel radius) on a plane under that load,
/// δ = (9 Q²/(16 E*² R))^{1/3} (83 µm for 78.5 kN on a 0.46 m steel wheel, about a tread
/// contact's). It does not depend on the lowering being iterated, so that the wheel's vertical
/// force, a sum of group forces with fixed weights, increases with the lowering and the load has
/// one balancing lowering; it is continuous in the pose and the load.
pub(super) fn merge_level(touch: f64, load: f64, e_star: f64, radius: f64) -> f64 {
    touch + (9.0 * load * load / (16.0 * e_star * e_star * radius)).cbrt()
}
