//! The load iteration's warm start (docs/theory.md §8.3) changes the cost of a step, not its result: a
//! wheelset solved after another pose gives the cold solution of the new pose, for the Hertz and
//! the strip models, in tread and flange contact.

mod common;

use common::benchmark_wheelset;
use railcontact::material::Material;
use railcontact::normal::NormalModel;
use railcontact::tangential::fastsim::Creepage;
use railcontact::wheelset::{Creepages, Vertical, WheelsetInput, WheelsetResult};

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
            let sorted = |r: &WheelsetResult| {
                let mut v: Vec<_> = r.right.all_patches().to_vec();
                v.sort_by(|a, b| a.y_rail.total_cmp(&b.y_rail));
                v
            };
            for (a, b) in sorted(&c).iter().zip(&sorted(&w)) {
                for (u, v) in [(a.fn_, b.fn_), (a.fx, b.fx), (a.fy, b.fy)] {
                    assert!((u - v).abs() < tol, "{model:?} y {y}: {u} vs {v}");
                }
                assert!((a.area - b.area).abs() <= 1e-6 * a.area, "{model:?} y {y}");
            }
        }
    }
}
