//! `Fastsim::solve` must not touch the heap (physics core contract, `src/lib.rs`): counted with a
//! global allocator wrapper. One test per binary, so no other thread allocates meanwhile.

use railcontact::fastsim::{
    Creepage, EllipticContact, Fastsim, FastsimSettings, Flexibility, TractionBound,
};
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

#[test]
fn solve_does_not_allocate() {
    let contact = EllipticContact {
        a: 8e-3,
        b: 4e-3,
        normal_force: 82e3,
        shear_modulus: 82e9,
        nu: 0.28,
        mu: 0.3,
    };
    let creepages = [
        Creepage {
            xi: 0.0,
            eta: -6.25e-4,
            phi: 0.625,
        },
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
