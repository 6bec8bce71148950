//! The damage outputs (docs/theory.md §10) as a vehicle run produces them: every normal model and
//! tangential option, planar and non-planar patches, a hunting (moving, yawing) wheelset solved
//! step after step by one instance (warm starts and reused tangential solutions included).
//!
//! * Tγ of a patch is its frictional power over the rolling speed; the wheel's Tγ, wear rates and
//!   RCF damage are the sums over its patches.
//! * Ekberg's surface fatigue index is μ_eff − k/p0 from the patch's own outputs.
//! * In the USFD function's mild regime (the hunting wheelset's creepages of ~1e−3) the wear
//!   rate is the published 5.3 µg/(m mm²) per N/mm² times Tγ: the element-wise sum of a linear
//!   function is the function of the sum, so only rounding separates them.
//! * Archard's wear goes as 1/H: the wheel's and the rail's rates are in the ratio of the
//!   hardnesses (no element reaches the seizure region p > 0.8 H here).
//! * The wear rates spread across the wheel's and the rail's profiles add up to the wheel's.
//! * The wear model changes no force: `wearModel` 0 and 1 give the same wheel forces bit for
//!   bit, and 0 gives no wear and no local fatigue index.

mod common;

use common::{builtin_wheelset_with, hunting_input};
use railcontact::damage::fatigue::{surface_index, wlrm_damage};
use railcontact::damage::{DamageParams, WearModel};
use railcontact::normal::NormalModel;
use railcontact::tangential::fastsim::Creepage;
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::{
    Creepages, PatchResult, SideResult, Vertical, Wheelset, WheelsetInput, WheelsetResult,
};

/// Rolling speed of [`hunting_input`] [m/s].
const SPEED: f64 = 30.0;
/// The USFD mild-regime coefficient in SI: 5.3 µg/(m mm²) per N/mm² = 5.3e−9 kg/(m N).
const USFD_MILD: f64 = 5.3e-9;
/// Steps of the hunting run (1 ms each; a quarter period at 5 Hz is 50 steps).
const STEPS: u64 = 120;

fn wheelset(
    model: NormalModel,
    tangential: TangentialModel,
    planar: bool,
    damage: DamageParams,
) -> Wheelset {
    builtin_wheelset_with(|s| {
        common::patch_options(model, tangential, planar)(s);
        s.damage = damage;
    })
}

fn configurations() -> Vec<(NormalModel, TangentialModel, bool)> {
    let mut out = Vec::new();
    for model in NormalModel::ALL {
        if model == NormalModel::Hertz {
            out.push((model, TangentialModel::ModelDefault, true));
            continue;
        }
        for tangential in TangentialModel::ALL {
            for planar in [false, true] {
                out.push((model, tangential, planar));
            }
        }
    }
    out
}

fn usfd() -> DamageParams {
    DamageParams {
        wear_model: WearModel::Usfd,
        ..DamageParams::default()
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

/// Checks one wheel's damage outputs against their definitions (module header); returns the
/// wheel's Tγ.
fn check_side(side: &SideResult, k: f64, ctx: &str) -> f64 {
    let check_patch = |p: &PatchResult, what: &str| {
        if p.weight == 0.0 {
            return;
        }
        // Tγ = P/V: one division.
        assert!(
            rel(p.t_gamma, p.frictional_power / SPEED) < 1e-12,
            "{ctx} {what}: {p:?}"
        );
        let fi = surface_index(p.fx, p.fy, p.fn_, p.pmax, k);
        assert_eq!(p.fatigue_index, fi, "{ctx} {what}");
        assert!(
            p.fatigue_index < 1.0 && p.fatigue_index > -10.0,
            "{ctx} {what}"
        );
        // Mild regime: 5.3e−9 Tγ to rounding (1e−9 of sums of ~600 elements).
        if p.t_gamma > 0.0 {
            assert!(
                rel(p.wheel_wear_rate, USFD_MILD * p.t_gamma) < 1e-9,
                "{ctx} {what}: wear {} Tγ {}",
                p.wheel_wear_rate,
                p.t_gamma
            );
        }
        assert_eq!(p.wheel_wear_rate, p.rail_wear_rate, "{ctx} {what}");
        // The local index at least the patch-average one where the patch carries traction
        // (k/p is smallest at the peak; |q| ≤ μp everywhere), and below μ.
        assert!(p.fatigue_index_local < 0.3, "{ctx} {what}: {p:?}");
    };
    for p in side.all_patches() {
        check_patch(p, "patch");
    }
    for p in side.shown_patches() {
        check_patch(p, "slot");
    }
    let sum = |f: &dyn Fn(&PatchResult) -> f64| side.all_patches().iter().map(f).sum::<f64>();
    assert!(rel(side.t_gamma, sum(&|p| p.t_gamma)) < 1e-12, "{ctx}");
    assert!(rel(side.wheel_wear_rate, sum(&|p| p.wheel_wear_rate)) < 1e-12);
    assert!(rel(side.rail_wear_rate, sum(&|p| p.rail_wear_rate)) < 1e-12);
    assert!(rel(side.rcf_damage, sum(&|p| wlrm_damage(p.t_gamma))) < 1e-12);
    side.t_gamma
}

#[test]
fn damage_outputs_follow_their_definitions_on_a_hunting_wheelset() {
    let k = DamageParams::default().shear_yield_strength;
    for (model, tangential, planar) in configurations() {
        let mut ws = wheelset(model, tangential, planar, usfd());
        let mut out = WheelsetResult::default();
        let mut dissipated = 0.0;
        for step in 0..STEPS {
            let ctx = format!("{model:?} {tangential:?} planar {planar} step {step}");
            ws.solve(&hunting_input(step), &mut out)
                .unwrap_or_else(|e| panic!("{ctx}: {e}"));
            dissipated += check_side(&out.left, k, &ctx) + check_side(&out.right, k, &ctx);
            // The wear spread across the profiles is the wheel's wear rate.
            for (rates, side) in ws.wear_rates().into_iter().zip([&out.left, &out.right]) {
                let (wheel, rail) = (rates.wheel.total(), rates.rail.total());
                assert!(
                    rel(wheel, side.wheel_wear_rate) < 1e-9,
                    "{ctx}: {wheel} vs {side:?}"
                );
                assert!(rel(rail, side.rail_wear_rate) < 1e-9, "{ctx}");
            }
        }
        assert!(dissipated > 0.0, "{model:?} {tangential:?}");
    }
}

#[test]
fn a_patch_that_adheres_throughout_still_wears_mildly() {
    // Creepages so small that no element of the grid slips: the patch still dissipates (the
    // energy released where the material leaves it, its creep forces' work), and in USFD's mild
    // regime wears by the published rate times that Tγ, spread on the profiles.
    for (model, tangential, planar) in configurations() {
        let mut ws = wheelset(model, tangential, planar, usfd());
        let mut out = WheelsetResult::default();
        for xi in [1e-7, 1e-5] {
            let input = WheelsetInput {
                y: 0.0,
                yaw: 0.0,
                roll: 0.0,
                vertical: Vertical::Loads {
                    left: 78_500.0,
                    right: 78_500.0,
                },
                creepages: Creepages::Prescribed {
                    creepage: Creepage {
                        xi,
                        eta: 0.0,
                        phi: 0.0,
                    },
                    vx: SPEED,
                },
                track: Default::default(),
            };
            ws.solve(&input, &mut out).expect("solves");
            let ctx = format!("{model:?} {tangential:?} ξ {xi}");
            let p = out.right.patches[0];
            assert!(p.t_gamma > 0.0, "{ctx}");
            if xi == 1e-7 {
                assert_eq!(p.adhesion_fraction, 1.0, "{ctx}: no element slips");
            }
            assert!(
                rel(p.wheel_wear_rate, USFD_MILD * p.t_gamma) < 1e-9,
                "{ctx}: {p:?}"
            );
            let spread = ws.wear_rates()[1].wheel.total();
            assert!(rel(spread, out.right.wheel_wear_rate) < 1e-9, "{ctx}");
        }
    }
}

#[test]
fn the_wear_model_changes_no_force() {
    for (model, tangential, planar) in configurations() {
        let mut off = wheelset(model, tangential, planar, DamageParams::default());
        let mut on = wheelset(model, tangential, planar, usfd());
        let (mut a, mut b) = (WheelsetResult::default(), WheelsetResult::default());
        for step in (0..STEPS).step_by(7) {
            off.solve(&hunting_input(step), &mut a).unwrap();
            on.solve(&hunting_input(step), &mut b).unwrap();
            let ctx = format!("{model:?} {tangential:?} planar {planar} step {step}");
            for (x, y) in [(&a.left, &b.left), (&a.right, &b.right)] {
                assert_eq!(x.force, y.force, "{ctx}");
                assert_eq!(x.moment, y.moment, "{ctx}");
                assert_eq!(x.t_gamma, y.t_gamma, "{ctx}");
                assert_eq!(x.wheel_wear_rate, 0.0);
                assert!(y.wheel_wear_rate > 0.0, "{ctx}");
                assert!(x.all_patches().iter().all(|p| p.fatigue_index_local == 0.0));
            }
        }
    }
}

#[test]
fn archard_wear_goes_as_one_over_the_hardness() {
    let mut params = DamageParams::default();
    params.wear_model = WearModel::ArchardKth;
    params.wheel_hardness = 2.0 * params.rail_hardness;
    for (model, tangential) in [
        (NormalModel::Hertz, TangentialModel::ModelDefault),
        (NormalModel::CoupledStrips, TangentialModel::FastripCoupled),
        (NormalModel::Analyn, TangentialModel::ModelDefault),
    ] {
        let mut ws = wheelset(model, tangential, false, params);
        let mut out = WheelsetResult::default();
        for step in (0..STEPS).step_by(11) {
            ws.solve(&hunting_input(step), &mut out).unwrap();
            for side in [&out.left, &out.right] {
                for p in side.all_patches() {
                    assert!(p.pmax < 0.8 * params.rail_hardness, "seizure region: {p:?}");
                    if p.rail_wear_rate > 0.0 {
                        assert!(rel(p.wheel_wear_rate, 0.5 * p.rail_wear_rate) < 1e-12);
                    }
                }
                assert!(side.rail_wear_rate > 0.0, "{model:?} step {step}");
            }
        }
    }
}

/// Independent USFD function (Lewis & Dwyer-Joyce 2004 as docs/theory.md §10.2 states it): µg
/// per metre rolled per mm² at Tγ/A in N/mm².
fn usfd_published(t: f64) -> f64 {
    if t < 10.4 {
        5.3 * t
    } else if t <= 77.2 {
        55.0
    } else {
        (61.9 * t - 4778.7).max(55.0)
    }
}

#[test]
fn patch_sums_follow_the_functions_element_by_element() {
    // FASTSIM on CONTACT's example ellipse from the linear to the saturated range (mild,
    // severe and catastrophic elements): the wear rate equals an independent element-by-element
    // summation of the published function over the same field, and the local fatigue index the
    // brute-force maximum over its elements (the sum skips elements whose bound cannot beat the
    // maximum: no difference beyond rounding).
    use railcontact::damage::DamageSum;
    use railcontact::tangential::fastsim::{Creepage, Fastsim, FastsimSettings};
    let contact = common::FASTSIM_CONTACT;
    let mut fastsim = Fastsim::new(FastsimSettings::default()).unwrap();
    let speed = 20.0;
    let params = usfd();
    let k = params.shear_yield_strength;
    let mut regimes = [false; 3];
    for xi in [1e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.4] {
        let creepage = Creepage {
            xi,
            eta: -0.3 * xi,
            phi: 0.2,
        };
        let r = fastsim.solve(&contact, &creepage, speed).unwrap();
        let mut sum = DamageSum::new(params, speed);
        let (mut independent, mut local, mut dissipated) = (0.0, f64::NEG_INFINITY, 0.0);
        fastsim.friction_elements(|_, e| {
            sum.add(e);
            let q = e.traction_sq.sqrt();
            local = f64::max(local, (q - k) / e.pressure);
            let t = q * e.slip * 1e-6;
            if e.slip > 0.0 {
                regimes[usize::from(t >= 10.4) + usize::from(t > 77.2)] = true;
            }
            independent += usfd_published(t) * (e.area * 1e6) * 1e-9;
            dissipated += q * e.slip * e.area;
        });
        // The field's Tγ is the solver's P/V.
        assert!(
            rel(dissipated, r.frictional_power / speed) < 1e-12,
            "ξ {xi}"
        );
        let d = sum.finish(r.frictional_power / speed);
        assert!(
            rel(d.wheel_wear_rate, independent) < 1e-9,
            "ξ {xi}: {d:?} {independent}"
        );
        // A slipping element's |q| is its bound to rounding, so the skipped elements may
        // differ from the maximum by that much.
        assert!(
            (d.fatigue_index_local - local).abs() <= 1e-12 * local.abs().max(1.0),
            "ξ {xi}: {} vs {local}",
            d.fatigue_index_local
        );
    }
    assert_eq!(regimes, [true; 3], "the creepages reach every regime");
}
