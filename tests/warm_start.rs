//! The load iteration's warm start (docs/theory.md §8.3) changes the cost of a step, not its result: a
//! wheelset solved after another pose gives the cold solution of the new pose, for the Hertz and
//! the strip models, in tread and flange contact.

mod common;

use common::benchmark_wheelset;
use railcontact::material::Material;
use railcontact::normal::NormalModel;
use railcontact::tangential::fastsim::Creepage;
use railcontact::wheelset::{Creepages, PatchResult, Vertical, WheelsetInput, WheelsetResult};

#[test]
fn a_warm_started_solve_gives_the_cold_solution() {
    let material = Material {
        youngs_modulus: 210e9,
        poisson_ratio: 0.28,
        friction: 0.3,
    };
    let q = 78_500.0;
    let pose = |y: f64| WheelsetInput {
        y,
        yaw: 0.0,
        roll: 0.0,
        vertical: Vertical::Loads { left: q, right: q },
        creepages: Creepages::Prescribed {
            creepage: Creepage {
                xi: 1e-3,
                eta: 5e-4,
                phi: 0.05,
            },
            vx: 2.0,
        },
        track: Default::default(),
    };
    for model in [
        NormalModel::Hertz,
        NormalModel::StripesAB,
        NormalModel::Analyn,
        NormalModel::CoupledStrips,
    ] {
        for y in [0.0, 2e-3, 6e-3] {
            let mut cold = benchmark_wheelset(material, model);
            let mut c = WheelsetResult::default();
            cold.solve(&pose(y), &mut c).expect("cold");
            let mut warm = benchmark_wheelset(material, model);
            let mut w = WheelsetResult::default();
            warm.solve(&pose(y - 1e-3), &mut w).expect("previous pose");
            assert!(warm.warm_start()[1].is_some());
            warm.solve(&pose(y), &mut w).expect("warm");
            // Tolerance: the creep component's iteration stops at 1e−7 Q (8 mN) and the load
            // balance at 1e−9 Q, so forces agree to ~1e−6 of μQ; the patch layout is the same.
            let tol = 1e-6 * 0.3 * q;
            assert_eq!(c.right.n_patches, w.right.n_patches, "{model:?} y {y}");
            // The output slots may differ (a patch keeps the slot it had in the previous step):
            // compare the patches themselves.
            for (a, b) in patches_by_rail(&c.right)
                .iter()
                .zip(&patches_by_rail(&w.right))
            {
                for (u, v) in [(a.fn_, b.fn_), (a.fx, b.fx), (a.fy, b.fy)] {
                    assert!((u - v).abs() < tol, "{model:?} y {y}: {u} vs {v}");
                }
                assert!((a.area - b.area).abs() <= 1e-6 * a.area, "{model:?} y {y}");
            }
        }
    }
}

/// A wheel's patches ordered by their position on the rail (output slots may differ between two
/// solutions of the same pose: a patch keeps the slot it had in the previous step).
fn patches_by_rail(side: &railcontact::wheelset::SideResult) -> Vec<PatchResult> {
    let mut v: Vec<_> = side.all_patches().to_vec();
    v.sort_by(|x, y| x.y_rail.total_cmp(&y.y_rail));
    v
}

/// Largest difference, over both wheels, between two solutions' wheel forces and moments
/// (moments over the wheel radius, 0.46 m, as forces) and their patches' normal and creep
/// forces (patches matched by rail position), relative to the wheel load `q`.
fn largest_difference(a: &WheelsetResult, b: &WheelsetResult, q: f64) -> f64 {
    let mut worst: f64 = 0.0;
    for (sa, sb) in [(&a.left, &b.left), (&a.right, &b.right)] {
        for k in 0..3 {
            worst = worst.max((sa.force[k] - sb.force[k]).abs());
            worst = worst.max((sa.moment[k] - sb.moment[k]).abs() / 0.46);
        }
        let (pa, pb) = (patches_by_rail(sa), patches_by_rail(sb));
        if pa.len() != pb.len() {
            return f64::INFINITY;
        }
        for (x, y) in pa.iter().zip(&pb) {
            for (u, v) in [(x.fn_, y.fn_), (x.fx, y.fx), (x.fy, y.fy)] {
                worst = worst.max((u - v).abs());
            }
        }
    }
    worst / q
}

#[test]
fn reusing_a_creep_pass_tangential_solution_stays_within_the_creep_tolerance() {
    // The hunting wheelset of the benches (y 3 mm, yaw 1 mrad at 5 Hz, kinematic creepages at
    // 30 m/s, 78.5 kN per wheel) solved step by step with the later creep passes reusing the
    // earlier pass's tangential solution scaled (the default) and with every pass solving it
    // again. The passes' normal-force targets differ by ~1e−6 of Q (reused up to 3e−6), and
    // the scaled forces follow them to a fraction of that: the two runs agree to the order of
    // the creep iteration's own tolerance, 2e−7 of Q (16 mN; a run whose iteration stopped one
    // pass earlier differs by up to 1e−7 Q by itself; measured 0.7–1.3e−7), for Hertz patches
    // and for strip patches with FASTSIM and FaStrip. Over 400 steps (0.4 s, two periods).
    use railcontact::tangential::patch::TangentialModel;
    let q = 78_500.0;
    let configs = [
        (NormalModel::Hertz, TangentialModel::ModelDefault, false),
        (NormalModel::Analyn, TangentialModel::ModelDefault, true),
        (NormalModel::Analyn, TangentialModel::Fastrip, true),
        (
            NormalModel::KikPiotrowski,
            TangentialModel::ModelDefault,
            false,
        ),
    ];
    for (model, tangential, planar) in configs {
        let make = |reuse: bool| {
            common::builtin_wheelset_with(|s| {
                s.normal_model = model;
                s.tangential = tangential;
                s.planar_patch = planar;
                s.reuse_tangential = reuse;
            })
        };
        let (mut reused, mut solved) = (make(true), make(false));
        let (mut a, mut b) = (WheelsetResult::default(), WheelsetResult::default());
        let mut worst: f64 = 0.0;
        for k in 0..400 {
            let input = common::hunting_input(k);
            reused.solve(&input, &mut a).expect("reused");
            solved.solve(&input, &mut b).expect("solved");
            worst = worst.max(largest_difference(&a, &b, q));
        }
        println!("{model:?} {tangential:?} planar {planar}: largest difference {worst:.2e} Q");
        assert!(worst < 2e-7, "{model:?} {tangential:?}: {worst:e} Q");
    }
}
