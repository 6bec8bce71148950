//! A step performs no heap allocation after initialisation: `Fastsim::solve` (physics core
//! contract, `src/lib.rs`), the wheelset solver for every normal model and tangential option,
//! and `fmi2DoStep` and `fmi2GetDirectionalDerivative` of the WheelRailContact FMU through its
//! exported C functions (driven by the `fmi_host` harness). Counted with a global allocator
//! wrapper; one test in this binary so that no other test thread allocates meanwhile.

mod common;
mod linked;

use fmi_host::Status;
use railcontact::damage::WearModel;
use railcontact::models::wheel_rail_contact::INFO;
use railcontact::normal::NormalModel;
use railcontact::tangential::fastsim::{
    Creepage, EllipticContact, Fastsim, FastsimSettings, Flexibility, TractionBound,
};
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::WheelsetResult;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Lateral shifts of a ramp over tread and flange contact [m].
fn ramp(k: usize) -> f64 {
    -1e-3 + 7e-3 * (k as f64 / 40.0)
}

fn wheelset_steps_do_not_allocate() {
    for model in NormalModel::ALL {
        for tangential in TangentialModel::ALL {
            for planar in [false, true] {
                // The damage outputs on (the element-wise wear sums) with every other model.
                let wear_model = if planar {
                    WearModel::Usfd
                } else {
                    WearModel::ArchardKth
                };
                let mut ws = common::builtin_wheelset_with(|settings| {
                    settings.normal_model = model;
                    settings.tangential = tangential;
                    settings.planar_patch = planar;
                    settings.damage.wear_model = wear_model;
                });
                let mut out = WheelsetResult::default();
                let input = |y| common::central_input(y, 0.1);
                ws.solve(&input(0.0), &mut out).unwrap();
                let before = ALLOCATIONS.load(Ordering::SeqCst);
                for k in 0..=40 {
                    ws.solve(&input(ramp(k)), &mut out).unwrap();
                }
                let n = ALLOCATIONS.load(Ordering::SeqCst) - before;
                assert_eq!(
                    n,
                    0,
                    "{} + {} planar={planar}: {n} allocations in 41 steps",
                    model.name(),
                    tangential.name()
                );
            }
        }
    }
}

fn do_step_does_not_allocate(model: i32) {
    let f = linked::instantiate(&INFO, &format!("alloc{model}"));
    assert_eq!(f.set_integer("normalModel", model), Status::Ok);
    assert_eq!(f.initialize(), Status::Ok);
    let (y, fx) = (f.vr("y"), f.vr("right.Fx"));
    let h = 1e-3;
    // Directional derivatives of both forces along y and omega (the first call makes the
    // scratch values; the later ones allocate nothing either).
    let unknowns = [fx, f.vr("right.Fy")];
    let knowns = [y, f.vr("omega")];
    let seed = [1.0, 0.5];
    let mut derivative = [0.0; 2];
    assert_eq!(f.step(0.0, h), Status::Ok);
    assert_eq!(
        f.directional_derivative_vr(&unknowns, &knowns, &seed, &mut derivative),
        Status::Ok
    );
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let mut value = 0.0;
    for k in 0..=40 {
        assert_eq!(f.set_real_vr(y, ramp(k)), Status::Ok);
        assert_eq!(f.step((k + 1) as f64 * h, h), Status::Ok);
        let (s, x) = f.get_real_vr(fx);
        assert_eq!(s, Status::Ok);
        value = x;
        assert_eq!(
            f.directional_derivative_vr(&unknowns, &knowns, &seed, &mut derivative),
            Status::Ok
        );
    }
    let n = ALLOCATIONS.load(Ordering::SeqCst) - before;
    f.free();
    assert_eq!(
        n, 0,
        "normalModel {model}: {n} allocations in 41 DoSteps and derivative calls"
    );
    assert!(value.is_finite() && derivative.iter().all(|d| d.is_finite()));
}

#[test]
fn steps_do_not_allocate() {
    fastsim_solve_does_not_allocate();
    wheelset_steps_do_not_allocate();
    for model in 1..=6 {
        do_step_does_not_allocate(model);
    }
}

fn fastsim_solve_does_not_allocate() {
    let contact = common::FASTSIM_CONTACT;
    let creepages = [
        common::FASTSIM_CREEPAGE,
        Creepage {
            xi: 1e-3,
            eta: 2e-3,
            phi: -3.0,
        },
        Creepage {
            xi: 1e300,
            eta: 0.0,
            phi: 0.0,
        },
        Creepage::default(),
    ];
    let mut solvers: Vec<Fastsim> = Vec::new();
    for bound in [TractionBound::Elliptic, TractionBound::Parabolic] {
        for flexibility in [
            Flexibility::Three,
            Flexibility::Single,
            Flexibility::Blended,
        ] {
            solvers.push(
                Fastsim::new(FastsimSettings {
                    nx: 40,
                    ny: 41,
                    bound,
                    flexibility,
                    ..FastsimSettings::online()
                })
                .unwrap(),
            );
        }
    }
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let mut checksum = 0.0;
    for f in solvers.iter_mut() {
        for k in &creepages {
            let r = f.solve(&contact, k, 30.0).unwrap();
            checksum += r.fy + f.tractions().map(|e| e.px).sum::<f64>();
        }
        // Errors and the zero-load path must not allocate either.
        assert!(f
            .solve(
                &contact,
                &Creepage {
                    xi: f64::NAN,
                    ..creepages[0]
                },
                1.0
            )
            .is_err());
        let none = EllipticContact {
            normal_force: 0.0,
            ..contact
        };
        checksum += f.solve(&none, &creepages[0], 1.0).unwrap().fx;
    }
    let after = ALLOCATIONS.load(Ordering::SeqCst);
    assert_eq!(after - before, 0, "solve allocated (checksum {checksum})");
}
