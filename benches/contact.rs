//! Speed of the contact element: Hertz, FASTSIM, the normal models and a full wheelset evaluation
//! per model pair, on the built-in S1002/UIC60 pair at 78.5 kN per wheel, steady, moving and
//! hunting (`cargo bench --bench contact -- hunting` for the last).
//! `cargo bench --bench contact`; figures in docs/performance.md.

use criterion::{black_box, criterion_group, criterion_main, Criterion};

use railcontact::normal::hertz::hertz_from_approach;
use railcontact::normal::NormalModel;
use railcontact::tangential::fastsim::{Fastsim, FastsimSettings};
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::{Wheelset, WheelsetInput, WheelsetResult, WheelsetSettings};

#[path = "../tests/common/mod.rs"]
mod common;

fn wheelset(model: NormalModel, tangential: TangentialModel) -> Wheelset {
    wheelset_with(model, |s| s.tangential = tangential)
}

fn wheelset_with(model: NormalModel, adjust: impl FnOnce(&mut WheelsetSettings)) -> Wheelset {
    common::builtin_wheelset_with(|settings| {
        settings.normal_model = model;
        adjust(settings);
    })
}

/// The central case at lateral shift `y` (`common::central_input`).
fn input(y: f64) -> WheelsetInput {
    common::central_input(y, 0.0)
}

fn bench_point(c: &mut Criterion) {
    c.bench_function("hertz_from_approach", |b| {
        b.iter(|| hertz_from_approach(black_box(1.09), black_box(2.3), black_box(8e-5), 1.15e11))
    });
    for n in [20usize, 50] {
        let mut f = Fastsim::new(FastsimSettings {
            nx: n,
            ny: n,
            ..Default::default()
        })
        .unwrap();
        let (contact, k) = (common::FASTSIM_CONTACT, common::FASTSIM_CREEPAGE);
        c.bench_function(&format!("fastsim_{n}x{n}"), |b| {
            b.iter(|| f.solve(black_box(&contact), black_box(&k), 1.0).unwrap())
        });
    }
}

fn bench_wheelset(c: &mut Criterion) {
    let pairs = [
        (NormalModel::Hertz, TangentialModel::ModelDefault),
        (NormalModel::Linder, TangentialModel::ModelDefault),
        (NormalModel::KikPiotrowski, TangentialModel::ModelDefault),
        (NormalModel::StripesB, TangentialModel::ModelDefault),
        (NormalModel::StripesAB, TangentialModel::ModelDefault),
        (NormalModel::Analyn, TangentialModel::ModelDefault),
        (NormalModel::CoupledStrips, TangentialModel::ModelDefault),
    ];
    let mut group = c.benchmark_group("wheelset");
    for (model, tangential) in pairs {
        for (case, y) in [("central", 0.0), ("flange_6mm", 6e-3)] {
            let mut ws = wheelset(model, tangential);
            let mut out = WheelsetResult::default();
            let inp = input(y);
            ws.solve(&inp, &mut out).unwrap();
            group.bench_function(
                format!("{}_{}_{case}", model.name(), tangential.name()),
                |b| b.iter(|| ws.solve(black_box(&inp), &mut out).unwrap()),
            );
        }
    }
    group.finish();
}

/// Cost against the discretisation: strips per patch (ANALYN + strip FASTSIM) and the FASTSIM
/// grid (Hertz), central case.
fn bench_scaling(c: &mut Criterion) {
    let mut group = c.benchmark_group("scaling");
    for strips in [10usize, 20, 40, 80] {
        let mut ws = wheelset_with(NormalModel::Analyn, |s| s.strips = strips);
        let mut out = WheelsetResult::default();
        let inp = input(0.0);
        ws.solve(&inp, &mut out).unwrap();
        group.bench_function(format!("analyn_strips_{strips}"), |b| {
            b.iter(|| ws.solve(black_box(&inp), &mut out).unwrap())
        });
    }
    for n in [10usize, 20, 40, 80] {
        let mut ws = wheelset_with(NormalModel::Hertz, |s| {
            s.fastsim.nx = n;
            s.fastsim.ny = n;
        });
        let mut out = WheelsetResult::default();
        let inp = input(0.0);
        ws.solve(&inp, &mut out).unwrap();
        group.bench_function(format!("hertz_grid_{n}"), |b| {
            b.iter(|| ws.solve(black_box(&inp), &mut out).unwrap())
        });
    }
    group.finish();
}

/// Instances in threads: each thread owns one wheelset (ANALYN) and solves a moving pose; the
/// time is per solve and thread, so flat figures mean linear scaling.
fn bench_threads(c: &mut Criterion) {
    let mut group = c.benchmark_group("threads");
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    for threads in [1usize, 2, 4].into_iter().filter(|&t| t <= 2 * cores) {
        group.bench_function(format!("analyn_{threads}_threads"), |b| {
            b.iter_custom(|iters| {
                // The instances are built before the clock starts (a wheelset's set-up takes
                // milliseconds); each thread then owns one.
                let mut instances: Vec<_> = (0..threads)
                    .map(|_| {
                        let ws = wheelset(NormalModel::Analyn, TangentialModel::ModelDefault);
                        (ws, WheelsetResult::default())
                    })
                    .collect();
                let start = std::time::Instant::now();
                std::thread::scope(|scope| {
                    for (ws, out) in instances.iter_mut() {
                        scope.spawn(move || {
                            for k in 0..iters {
                                ws.solve(black_box(&input(common::moving_y(k))), out)
                                    .unwrap();
                            }
                        });
                    }
                });
                start.elapsed()
            })
        });
    }
    group.finish();
}

/// A moving wheelset: y = 3 mm sin(2πt) at 1 ms steps, so the warm start meets a new pose at
/// every solve (the steady benchmarks above repeat one pose).
fn bench_moving(c: &mut Criterion) {
    let mut group = c.benchmark_group("moving");
    for model in [
        NormalModel::Hertz,
        NormalModel::StripesAB,
        NormalModel::Analyn,
        NormalModel::CoupledStrips,
    ] {
        let mut ws = wheelset(model, TangentialModel::ModelDefault);
        let mut out = WheelsetResult::default();
        let mut k = 0u64;
        group.bench_function(model.name(), |b| {
            b.iter(|| {
                k += 1;
                ws.solve(black_box(&input(common::moving_y(k))), &mut out)
                    .unwrap()
            })
        });
    }
    group.finish();
}

/// Steps timed one by one for the per-step percentiles of the hunting benches.
const TIMED_STEPS: u64 = 4000;

/// The `q` quantile (0…1) of sorted `values`, nearest rank.
fn quantile(sorted: &[f64], q: f64) -> f64 {
    let rank = ((q * sorted.len() as f64).ceil() as usize).clamp(1, sorted.len());
    sorted[rank - 1]
}

/// A hunting wheelset (`common::hunting_input`: y = 3 mm and yaw = 1 mrad at 5 Hz, consistent
/// vy and yaw rate), every normal model with every tangential option on its strip patches
/// (non-planar) and ANALYN's planar patches: criterion's estimate per solve, and before it the
/// per-step median and 99th percentile of [`TIMED_STEPS`] solves timed one by one (tail latency
/// for real-time use).
fn bench_hunting(c: &mut Criterion) {
    let mut configs = vec![(NormalModel::Hertz, TangentialModel::ModelDefault, false)];
    for model in NormalModel::ALL.into_iter().skip(1) {
        for tangential in TangentialModel::ALL {
            configs.push((model, tangential, false));
        }
    }
    for tangential in TangentialModel::ALL {
        configs.push((NormalModel::Analyn, tangential, true));
    }
    let mut group = c.benchmark_group("hunting");
    for (model, tangential, planar) in configs {
        let mut ws = wheelset_with(model, |s| {
            s.tangential = tangential;
            s.planar_patch = planar;
        });
        let mut out = WheelsetResult::default();
        let name = format!(
            "{}_{}{}",
            model.name(),
            tangential.name(),
            if planar { "_planar" } else { "" }
        );
        let mut steps: Vec<f64> = (0..TIMED_STEPS)
            .map(|k| {
                let input = common::hunting_input(k);
                let start = std::time::Instant::now();
                ws.solve(black_box(&input), &mut out).unwrap();
                start.elapsed().as_secs_f64() * 1e6
            })
            .collect();
        steps.sort_by(f64::total_cmp);
        println!(
            "hunting/{name}: per step median {:.1} µs, p99 {:.1} µs, max {:.1} µs ({TIMED_STEPS} steps)",
            quantile(&steps, 0.5),
            quantile(&steps, 0.99),
            steps[steps.len() - 1]
        );
        let mut k = TIMED_STEPS;
        group.bench_function(name, |b| {
            b.iter(|| {
                k += 1;
                ws.solve(black_box(&common::hunting_input(k)), &mut out)
                    .unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(
    benches,
    bench_point,
    bench_wheelset,
    bench_moving,
    bench_hunting,
    bench_scaling,
    bench_threads
);
criterion_main!(benches);
