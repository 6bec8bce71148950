//! Shared test fixtures of the strip models: the shape table, one solve, the no-NaN check and
//! the awkward geometries every model must survive.

use crate::geometry::strips::StripGeometry;
use crate::normal::hertz::{hertz_from_approach, HertzPatch};
use crate::normal::shape::HertzShapeTable;
use crate::normal::strips::StripSolution;
use crate::normal::{NormalParams, StripModel};
use std::sync::OnceLock;

/// The Hertz shape table, built once per test binary.
pub fn table() -> &'static HertzShapeTable {
    static TABLE: OnceLock<HertzShapeTable> = OnceLock::new();
    TABLE.get_or_init(HertzShapeTable::new)
}

/// `model` prepared on `geom` and solved at the approach `delta`: the strips and the force [N].
pub fn run<M: StripModel + ?Sized>(
    model: &mut M,
    geom: &StripGeometry,
    params: &NormalParams,
    delta: f64,
) -> (StripSolution, f64) {
    let mut out = StripSolution::default();
    model.prepare(geom, params, table());
    let n = model.solve(geom, params, table(), delta, &mut out);
    (out, n)
}

/// A default `M` prepared on `geom` and solved at the approach `delta` [m] with the default
/// parameters: the strips and the force [N].
pub fn run_default<M: StripModel + Default>(
    geom: &StripGeometry,
    delta: f64,
) -> (StripSolution, f64) {
    run(&mut M::default(), geom, &NormalParams::default(), delta)
}

/// Lateral curvature B of the Hertz cases [1/m] (flat-tread wheel on a 600 mm crown).
pub const CURV_B: f64 = 1.5;
/// Approach δ of the Hertz cases [m].
pub const DELTA: f64 = 50e-6;

/// The Hertz patch of the curvatures `curv_a`, `curv_b` [1/m] at the approach `delta` [m], with
/// the default parameters' E*.
pub fn hertz_patch(curv_a: f64, curv_b: f64, delta: f64) -> HertzPatch {
    hertz_from_approach(curv_a, curv_b, delta, NormalParams::default().e_star).unwrap()
}

/// The Hertz case of curvature ratio A/B = `ratio`: A = `ratio` · [`CURV_B`] [1/m] and its
/// patch at the approach [`DELTA`].
pub fn hertz_case(ratio: f64) -> (f64, HertzPatch) {
    let a = ratio * CURV_B;
    (a, hertz_patch(a, CURV_B, DELTA))
}

/// Every strip's half-length, peak and force, and the total, finite and non-negative.
pub fn no_nan(sol: &StripSolution, n_total: f64) {
    assert!(n_total.is_finite() && n_total >= 0.0, "N = {n_total}");
    for i in 0..sol.n {
        for v in [sol.half_length[i], sol.pmax[i], sol.force[i]] {
            assert!(v.is_finite() && v >= 0.0, "strip {i}: {v}");
        }
    }
}

/// Half-width of the awkward geometries [m].
pub const AWKWARD_HALF_WIDTH: f64 = 0.01;

/// Second minimum of the "two minima" geometry [m].
pub const SECOND_MINIMUM: f64 = 0.6 * AWKWARD_HALF_WIDTH;

/// Approaches every model must survive [m]: none, touching, tiny, usual, deep, absurd, NaN, ∞.
pub const AWKWARD_DELTAS: [f64; 8] = [-1e-5, 0.0, 1e-12, 5e-5, 1e-2, 1e3, f64::NAN, f64::INFINITY];

/// Awkward geometries: conformal, concave, two minima (f = k s²(s − s₂)², a concave hump
/// between them), zero and negative A, non-finite B, non-finite f and A, extreme curvature
/// ratios, one strip, one strip off the origin, no strip.
pub fn awkward_geometries() -> Vec<(&'static str, StripGeometry)> {
    let w = AWKWARD_HALF_WIDTH;
    let two_min = |s: f64| {
        let (k, s2) = (2e4, SECOND_MINIMUM);
        let f = k * s * s * (s - s2).powi(2);
        (f, 1.0, k * (6.0 * s * s - 6.0 * s * s2 + s2 * s2))
    };
    let mut nan_b = StripGeometry::quadratic(1.0, 2.0, -w, w, 30);
    nan_b.curv_b[3] = f64::NAN;
    nan_b.curv_b[4] = f64::INFINITY;
    nan_b.curv_b[5] = f64::NEG_INFINITY;
    let mut nan_f_a = StripGeometry::quadratic(1.0, 2.0, -w, w, 30);
    nan_f_a.f[5] = f64::NAN;
    nan_f_a.curv_a[6] = f64::INFINITY;
    vec![
        (
            "conformal",
            StripGeometry::from_fn(-w, w, 40, |_| (0.0, 1.0, 0.0)),
        ),
        (
            "concave",
            StripGeometry::from_fn(-w, w, 40, |s| (-s * s, 1.0, -1.0)),
        ),
        (
            "concave f ≥ 0",
            StripGeometry::from_fn(-w, w, 40, |s| (0.01 * s.abs(), 1.0, -2.0)),
        ),
        (
            "two minima",
            StripGeometry::from_fn(-0.5 * w, 1.2 * w, 120, two_min),
        ),
        (
            "A ≤ 0",
            StripGeometry::from_fn(-w, w, 40, |s| (s * s, s * 1e3, 1.0)),
        ),
        ("non-finite B", nan_b),
        ("non-finite f and A", nan_f_a),
        (
            "extreme ratios",
            StripGeometry::from_fn(-w, w, 40, |s| (s * s, 1e-9, 1e9)),
        ),
        ("one strip", StripGeometry::quadratic(1.0, 2.0, -w, w, 1)),
        (
            "one strip off origin",
            StripGeometry::quadratic(1.0, -2.0, 0.2 * w, w, 1),
        ),
        ("no strip", StripGeometry::default()),
    ]
}

/// The awkward geometry called `name`.
pub fn awkward_geometry(name: &str) -> StripGeometry {
    awkward_geometries()
        .into_iter()
        .find(|(n, _)| *n == name)
        .map(|(_, geom)| geom)
        .expect("an awkward geometry of that name")
}

/// Two contact regions on `n` strips over [−8, 20] mm: a Hertz gap of curvature
/// [`SWEEP_CURV_B`] around 0 and a second well (curvature 4.5 1/m, 20 µm deeper gap) at 12 mm.
pub fn two_wells(n: usize) -> StripGeometry {
    StripGeometry::from_fn(-8e-3, 20e-3, n, |s| {
        let first = SWEEP_CURV_B * s * s;
        let second = 20e-6 + 4.5 * (s - 12e-3).powi(2);
        if first <= second {
            (first, 0.5, SWEEP_CURV_B)
        } else {
            (second, 0.5, 4.5)
        }
    })
}

/// Largest step of `values` between neighbours.
pub fn max_jump(values: &[f64]) -> f64 {
    values
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .fold(0.0, f64::max)
}

/// Lateral curvature at the origin of the B-crossing family [1/m].
pub const SWEEP_CURV_B: f64 = 1.5;

/// Approach scale of the continuity sweep [m]: N(δ) is swept over [0, 4 × this].
pub const SWEEP_DELTA: f64 = 50e-6;

/// A family where B crosses zero inside the strip set: B = B0(1 − s/s_t), f consistent
/// (f = B0 s²(1 − s/(3 s_t)) > 0 for s < 3 s_t), A = 1 1/m, 80 strips on [−w, w]. s_t from 3w
/// down to 0.4w moves the zero of B from outside the set to well inside it.
pub fn b_crossing_geometry(s_t: f64, w: f64) -> StripGeometry {
    StripGeometry::from_fn(-w, w, 80, |s| {
        (
            SWEEP_CURV_B * s * s * (1.0 - s / (3.0 * s_t)),
            1.0,
            SWEEP_CURV_B * (1.0 - s / s_t),
        )
    })
}

/// N along a lateral sweep of the B-crossing family (half-width `w`, approach `sweep_delta`)
/// and along δ ∈ [0, 4 [`SWEEP_DELTA`]] on its last member: continuous, i.e. the largest jump
/// between neighbours shrinks ≥ 5× when the sweep step is refined 10× (a discontinuity would
/// keep it; a smooth function shrinks it 10×), and N(δ) non-decreasing. The sweep is meaningful:
/// at its end strips with B < 0 are in contact.
pub fn assert_continuous_sweep<M: StripModel>(make: impl Fn() -> M, w: f64, sweep_delta: f64) {
    let params = NormalParams::default();
    let family = |steps: usize| -> Vec<f64> {
        (0..=steps)
            .map(|k| {
                let s_t = w * (3.0 - 2.6 * k as f64 / steps as f64);
                run(
                    &mut make(),
                    &b_crossing_geometry(s_t, w),
                    &params,
                    sweep_delta,
                )
                .1
            })
            .collect()
    };
    let (coarse, fine) = (family(40), family(400));
    let (j_coarse, j_fine) = (max_jump(&coarse), max_jump(&fine));
    let last = b_crossing_geometry(0.4 * w, w);
    let in_delta = |steps: usize| -> Vec<f64> {
        let mut model = make();
        let mut out = StripSolution::default();
        model.prepare(&last, &params, table());
        (0..=steps)
            .map(|k| {
                let delta = 4.0 * SWEEP_DELTA * k as f64 / steps as f64;
                model.solve(&last, &params, table(), delta, &mut out)
            })
            .collect()
    };
    let (d_coarse, d_fine) = (in_delta(40), in_delta(400));
    let (k_coarse, k_fine) = (max_jump(&d_coarse), max_jump(&d_fine));
    eprintln!(
        "sweep: N {:.0}…{:.0} N, max jump {j_coarse:.1} → {j_fine:.2} N; \
         N(δ) max jump {k_coarse:.1} → {k_fine:.2} N",
        fine[0], fine[400]
    );
    assert!(fine.iter().all(|n| n.is_finite() && *n > 0.0));
    assert!(j_fine < 0.2 * j_coarse);
    assert!(d_fine.windows(2).all(|w| w[1] >= w[0]));
    assert!(k_fine < 0.2 * k_coarse);
    let (sol, _) = run(&mut make(), &last, &params, sweep_delta);
    assert!((0..last.n).any(|i| last.curv_b[i] < 0.0 && sol.half_length[i] > 0.0));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::normal::NormalModel;

    /// Every strip model, on every awkward geometry and approach, with usual and unusable
    /// parameters: finite, non-negative strips and force; no contact for δ ≤ 0 or NaN.
    #[test]
    fn every_strip_model_survives_the_awkward_geometries() {
        let unusable = NormalParams {
            b_min: f64::NAN,
            b_smoothing: f64::NAN,
            ..NormalParams::default()
        };
        for model in NormalModel::ALL {
            let Some(mut strips) = model.strip_model() else {
                continue;
            };
            for (name, geom) in awkward_geometries() {
                for params in [NormalParams::default(), unusable] {
                    for delta in AWKWARD_DELTAS {
                        let (sol, n) = run(&mut *strips, &geom, &params, delta);
                        no_nan(&sol, n);
                        if delta.is_nan() || delta <= 0.0 {
                            assert_eq!(n, 0.0, "{} on {name}, δ = {delta}", model.name());
                        }
                    }
                }
            }
        }
    }
}
