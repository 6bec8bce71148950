//! The lowest point of a yawed wheel at a lateral of the wheelset frame.
//!
//! A wheel of revolution seen from below has, at lateral W, its lowest point at the
//! longitudinal position X where r(l)² − d² is largest, with l = −X sin ψ + W cos ψ the axial
//! coordinate, d = X cos ψ + W sin ψ the horizontal distance from the axle plane and r(l) the
//! wheel radius; a few Newton steps on X give the yaw lead/lag of the contact point (exact for
//! a surface of revolution; roll–yaw coupling neglected, second order).

use super::{Prepared, WheelOnRail, WheelPoint};
use crate::geometry::profile::Profile;

/// Iteration limit of the yawed wheel's lowest-point search (Newton converges in 2–3 steps from
/// the axle-plane guess at the yaw angles of running; bisection halves the 0.46 m bracket to
/// 1e−9 m in 29 steps where Newton cannot be trusted).
const WHEEL_NEWTON_STEPS: usize = 40;

/// Margin on the single-maximum condition tan²ψ (z'² + r z'')max < 1 of that search.
pub(super) const UNIMODAL_MARGIN: f64 = 0.9;

/// Samples of the coarse scan over the ±r0/2 bracket when the condition fails (0.46 m / 64 =
/// 7 mm apart; the two maxima of a yawed flange lie several centimetres apart in X).
const MULTI_START_SAMPLES: usize = 64;

/// Step below which that search has converged [m]: the gap error is second order in it.
const WHEEL_NEWTON_TOLERANCE: f64 = 1e-9;

/// Step in the wheel's axial coordinate below which the unimodal lowest-point search has
/// converged [m] (`WheelOnRail::unimodal_lowest_point`; the gap error is second order in it).
const LOWEST_POINT_TOLERANCE: f64 = 1e-12;

/// Bound on the second Newton step below which the unimodal lowest-point search stops after
/// one step [m] (`WheelOnRail::unimodal_lowest_point`): far below the load balance's resolution
/// of the approach (1e−9 of ~1e−4 m).
const ONE_STEP_ERROR: f64 = 1e-16;

/// Largest u = (z' tan ψ)² for which the yawed lowest point's roots √(1 − u) and 1/√(1 − u)
/// are taken from their series (`WheelOnRail::yawed_point`): the first neglected terms,
/// 7u⁵/256 and 63u⁵/256, stay below 3e−16.
const SERIES_LIMIT: f64 = 1e-3;

/// max of z'² + r z'' with r = `radius` + z (the radius at the point) [-] over the wheel profile
/// from the flange tip `from` to the field side, sampled every 10 µm. Where the spline's knots
/// cluster closer than that (1 µm near the S1002 flange tip) its z'' can spike between samples,
/// so this is a sampled maximum: `wheel_at` keeps its Newton inside the lead bound
/// ([`wheel_lead_bound`]) for that reason. The flange's back (z' → ∞ on its vertical face) is
/// left out: contact there is refused as flange climb, and a yawed wheel's lowest point cannot
/// lie on it (its lead r z' tan ψ would exceed r/2).
pub(super) fn wheel_convexity(wheel: &Profile, radius: f64, from: f64) -> f64 {
    running_side_max(wheel, from, |z, dz, d2z| dz * dz + (radius + z) * d2z)
}

/// max of r |z'| with r = `radius` + z [m] over the wheel profile's running side from `from`
/// (as [`wheel_convexity`]; also at every knot, where the slope of a clustered run of knots
/// peaks).
pub(super) fn wheel_lead_bound(wheel: &Profile, radius: f64, from: f64) -> f64 {
    let at = |z: f64, dz: f64, _: f64| (radius + z) * dz.abs();
    let on_grid = running_side_max(wheel, from, at);
    let (_, hi) = wheel.y_range();
    let at_knots = wheel
        .spline()
        .knots()
        .iter()
        .filter(|&&y| (from..=hi).contains(&y))
        .map(|&y| {
            let (z, dz, d2z) = wheel.eval(y);
            at(z, dz, d2z)
        })
        .fold(0.0, f64::max);
    on_grid.max(at_knots)
}

/// max of `f(z, z', z'')` over the wheel profile from `from` to the field side, every 10 µm.
fn running_side_max(wheel: &Profile, from: f64, f: impl Fn(f64, f64, f64) -> f64) -> f64 {
    const STEP: f64 = 1e-5;
    let (lo, hi) = wheel.y_range();
    let lo = lo.max(from).min(hi);
    let n = ((hi - lo) / STEP).ceil() as usize;
    (0..=n)
        .map(|i| {
            let (z, dz, d2z) = wheel.eval(lo + (hi - lo) * i as f64 / n as f64);
            f(z, dz, d2z)
        })
        .fold(0.0, f64::max)
}

impl WheelOnRail {
    /// Lowest point of the (yawed) wheel at lateral `w`.
    pub(super) fn wheel_at(&self, w: f64, p: &Prepared) -> WheelPoint {
        let r0 = self.setup.wheel_radius;
        let offset = self.setup.taping_line_offset();
        if p.sin_yaw == 0.0 {
            let y_w = w - offset;
            let (z_w, dz_w, _) = self.wheel.eval(y_w);
            return WheelPoint {
                z: r0 + z_w,
                slope: dz_w,
                x: 0.0,
                y_wheel: y_w,
                radius: r0 + z_w,
            };
        }
        if p.single_lowest_point {
            return self.unimodal_lowest_point(w, p);
        }
        // Newton on X for the maximum of q(X) = r(l)² − d², safeguarded by a bracket: the
        // lowest point of a wheel lies within |d| ≤ r0/2 of the axle plane for any yaw a
        // wheelset can have (the lead is r·tan γ·tan ψ), where q' = −2d cos ψ − 2r z' sin ψ
        // has the sign of −d. Each step narrows the bracket [lo, hi] (q' > 0 at lo, < 0 at hi)
        // and bisects it where Newton would leave it or q is not concave (a yawed flange's
        // tight curvature, where plain Newton oscillates).
        //
        // q'' = 2(z'² + r z'') sin²ψ − 2 cos²ψ < 0 everywhere when tan²ψ (z'² + r z'')max < 1:
        // then q has one maximum (at running yaw angles, |ψ| ≲ 0.03 rad for S1002). At larger
        // yaw a yawed flange can give two (the tread-side and flange-side maxima, millimetres
        // apart in height), so a coarse scan picks the higher one's bracket first.
        let x_of_d = |d: f64| (d - w * p.sin_yaw) / p.cos_yaw;
        // Where one lowest point is expected, the bracket is its lead bound |d| ≤ max(r|z'|)
        // |tan ψ| (× 1.5 against rounding, a few millimetres at running yaw): the spline's
        // curvature spikes where its knots cluster (1 µm apart near the flange tip) can make q
        // locally convex, and bisecting the all-yaw bracket ±r0/2 from there once jumped 115 mm
        // to another stationary point (a 14 mm gap error at one lateral of a soak pose).
        let lead = self.lead_bracket(p);
        let (mut lo, mut hi) = (x_of_d(-lead), x_of_d(lead));
        let mut x = -w * p.sin_yaw / p.cos_yaw;
        if !p.single_lowest_point {
            // Only where the wheel profile exists (y = l − offset inside its range; beyond it the
            // profile's linear continuation would invent a lower point).
            let (y_lo, y_hi) = self.wheel.y_range();
            let x_of_y = |y: f64| (w * p.cos_yaw - y - offset) / p.sin_yaw;
            let (a, b) = (x_of_y(y_lo), x_of_y(y_hi));
            (lo, hi) = (lo.max(a.min(b)), hi.min(a.max(b)));
            if lo >= hi {
                (lo, hi) = (x, x);
            }
            let q = |x: f64| {
                let l = -x * p.sin_yaw + w * p.cos_yaw;
                let d = x * p.cos_yaw + w * p.sin_yaw;
                let r = r0 + self.wheel.z(l - offset);
                r * r - d * d
            };
            let h = (hi - lo) / MULTI_START_SAMPLES as f64;
            let best = (0..=MULTI_START_SAMPLES)
                .map(|k| lo + h * k as f64)
                .max_by(|&a, &b| q(a).total_cmp(&q(b)))
                .unwrap_or(x);
            (lo, hi, x) = ((best - h).max(lo), (best + h).min(hi), best);
        }
        for _ in 0..WHEEL_NEWTON_STEPS {
            let l = -x * p.sin_yaw + w * p.cos_yaw;
            let d = x * p.cos_yaw + w * p.sin_yaw;
            let (z, dz, d2z) = self.wheel.eval(l - offset);
            let r = r0 + z;
            let q1 = -2.0 * r * dz * p.sin_yaw - 2.0 * d * p.cos_yaw;
            let q2 =
                2.0 * (dz * dz + r * d2z) * p.sin_yaw * p.sin_yaw - 2.0 * p.cos_yaw * p.cos_yaw;
            if q1 == 0.0 {
                // At the maximum exactly: stay (a bisection step from here would leave it).
                break;
            }
            if q1 > 0.0 {
                lo = x;
            } else {
                hi = x;
            }
            let newton = x - q1 / q2;
            let next = if q2 < 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            let moved = (next - x).abs();
            x = next;
            if moved <= WHEEL_NEWTON_TOLERANCE {
                break;
            }
        }
        let l = -x * p.sin_yaw + w * p.cos_yaw;
        let d = x * p.cos_yaw + w * p.sin_yaw;
        let (z_w, dz_w, _) = self.wheel.eval(l - offset);
        let r = r0 + z_w;
        let z = (r * r - d * d).max(0.0).sqrt();
        // At the maximiser X (q'(X) = 0) dz/dw = (∂q/∂w)/(2z) with ∂q/∂w = 2 r r' cos ψ − 2 d sin ψ.
        let slope = if z > 0.0 {
            (r * dz_w * p.cos_yaw - d * p.sin_yaw) / z
        } else {
            0.0
        };
        WheelPoint {
            z,
            slope,
            x,
            y_wheel: l - offset,
            radius: r,
        }
    }

    /// [`WheelOnRail::wheel_at`] where the yawed wheel has one lowest point per lateral
    /// ([`Prepared::single_lowest_point`]: q concave everywhere). At the maximum of q, q' = 0
    /// gives the lead d = −r z' tan ψ as a function of the axial coordinate l alone, and so the
    /// lateral of the lowest point, w(l) = l cos ψ + d sin ψ = l cos ψ − r z' sin²ψ / cos ψ,
    /// with w'(l) = −q''/(2 cos ψ) > 0. Newton on w(l) = w from l = w / cos ψ (the point in the
    /// axle plane), kept inside the lead bound's bracket, on the wheel spline's piece at hand (a
    /// new interval lookup only where l leaves it): the correction is r z' tan ψ sin ψ ≲ 1 µm
    /// at running yaw, so Newton's second step moves l by ~1e−15 m. One interval lookup and
    /// two cubic evaluations per lateral at running yaw (more where the safeguarded iteration
    /// below runs), where Newton in X took three full spline evaluations. The point is the same
    /// maximum (to rounding).
    ///
    /// At running yaw one Newton step suffices: from l0 = w / cos ψ the step is
    /// s = (r z' sin²ψ / cos ψ − (l0 cos ψ − w)) / w'(l0), and the next one would be about
    /// |w''| s² / (2 w') with w'' = −(3 z' z'' + r z‴) sin²ψ / cos ψ on the piece. Where that
    /// is below [`ONE_STEP_ERROR`] (s ~ 1e−8 m at 1 mrad: the bound is ~1e−20 m) the point at
    /// l0 + s is taken from the piece's cubic without a second step; elsewhere the safeguarded
    /// iteration runs to [`LOWEST_POINT_TOLERANCE`].
    fn unimodal_lowest_point(&self, w: f64, p: &Prepared) -> WheelPoint {
        let r0 = self.setup.wheel_radius;
        let offset = self.setup.taping_line_offset();
        let (cos, sin_tan) = (p.cos_yaw, p.sin_tan);
        let mut l = w * p.inv_cos;
        let mut piece = self.wheel.piece_at(l - offset);
        let mut at = piece.eval(l - offset);
        {
            // w'(l0) = cos ψ (1 − k): 1/w' = (1 + k + k²)/cos ψ within k³/(1 − k) of it.
            let (z, dz, d2z) = at;
            let r = r0 + z;
            let k = (dz * dz + r * d2z) * sin_tan * p.inv_cos;
            let step = (r * dz * sin_tan - (l * cos - w)) * p.inv_cos * (1.0 + k * (1.0 + k));
            let bend = (3.0 * dz * d2z + r * piece.third()) * sin_tan * p.inv_cos;
            let neglected = 0.5 * (bend * step * step).abs() + 2.0 * (step * k * k * k).abs();
            if k.abs() <= 0.5 && neglected <= ONE_STEP_ERROR {
                let next = l + step;
                if piece.contains(next - offset) {
                    return self.yawed_point(next, piece.eval(next - offset), p);
                }
            }
        }
        let spread = self.lead_bracket(p) * p.tan_yaw.abs();
        let (mut lo, mut hi) = (l - spread, l + spread);
        for _ in 0..WHEEL_NEWTON_STEPS {
            let (z, dz, d2z) = at;
            let r = r0 + z;
            let residual = l * cos - r * dz * sin_tan - w;
            if residual == 0.0 || residual.is_nan() {
                break;
            }
            if residual > 0.0 {
                hi = l;
            } else {
                lo = l;
            }
            let rate = cos - (dz * dz + r * d2z) * sin_tan;
            let newton = l - residual / rate;
            let next = if rate > 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            let step = next - l;
            l = next;
            if step.abs() <= LOWEST_POINT_TOLERANCE {
                // Converged: the profile at `l` from its expansion at the last point (the step's
                // square is far below rounding), without evaluating the spline again.
                at = (z + dz * step, dz + d2z * step, d2z);
                break;
            }
            if !piece.contains(l - offset) {
                piece = self.wheel.piece_at(l - offset);
            }
            at = piece.eval(l - offset);
        }
        self.yawed_point(l, at, p)
    }

    /// The yawed wheel's lowest point at axial coordinate `l` where the profile's value, slope
    /// and second derivative are `at` ([`WheelOnRail::unimodal_lowest_point`]): its lead
    /// d = −r z' tan ψ, height √(r² − d²) and slope.
    ///
    /// With u = (z' tan ψ)², the height is r √(1 − u) and the slope
    /// (r z' cos ψ − d sin ψ)/height = z' / (cos ψ √(1 − u)); for u ≤ [`SERIES_LIMIT`] (a yaw
    /// of ≲ 12 mrad on S1002's flange) both roots are their binomial series to u⁴ (remainders
    /// below 3e−16 of them), elsewhere a square root and a division.
    fn yawed_point(&self, l: f64, at: (f64, f64, f64), p: &Prepared) -> WheelPoint {
        let (z_w, dz_w, _) = at;
        let r = self.setup.wheel_radius + z_w;
        let d = -r * dz_w * p.tan_yaw;
        let lean = dz_w * p.tan_yaw;
        let u = lean * lean;
        let (root, inverse_root) = if u <= SERIES_LIMIT {
            (
                1.0 - u * (0.5 + u * (0.125 + u * (0.0625 + u * (5.0 / 128.0)))),
                1.0 + u * (0.5 + u * (0.375 + u * (0.3125 + u * (35.0 / 128.0)))),
            )
        } else {
            let root = (1.0 - u).max(0.0).sqrt();
            (root, if root > 0.0 { 1.0 / root } else { 0.0 })
        };
        let z = r.max(0.0) * root;
        let slope = dz_w * p.inv_cos * inverse_root;
        WheelPoint {
            z,
            slope,
            x: d * p.cos_yaw - l * p.sin_yaw,
            y_wheel: l - self.setup.taping_line_offset(),
            radius: r,
        }
    }

    /// Half-width of the bracket of the yawed wheel's lowest point in d (distance from the axle
    /// plane) [m] (`wheel_at`).
    pub(super) fn lead_bracket(&self, p: &Prepared) -> f64 {
        let half_radius = 0.5 * self.setup.wheel_radius;
        if p.single_lowest_point {
            (1.5 * self.wheel_lead_bound * p.tan_yaw.abs()).min(half_radius)
        } else {
            half_radius
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::search::{s1002_on_uic60, SidePose};

    #[test]
    fn yawed_wheels_lowest_point_is_the_maximum_over_the_rolling_direction() {
        // Brute force: the wheel's vertical extent sqrt(r(l)² − d²) over X on a 0.1 mm grid
        // against the search, from the tread (l ≈ 0.75 m from the wheelset centre) across the
        // flange, at yaw angles up to 0.1 rad (5.7°, far beyond running). Before the bracket the
        // plain Newton stopped where the flange makes r(l)² − d² locally convex, or oscillated
        // between two points, and was off by millimetres.
        let g = s1002_on_uic60();
        // S1002 (flange-tip side left out): one lowest point below |ψ| ≈ 0.032 rad, so yaw 0.003
        // and 0.02 take the plain Newton path and 0.05 and 0.1 the coarse scan.
        let limit = (UNIMODAL_MARGIN / g.wheel_convexity).sqrt().atan();
        assert!((0.025..0.04).contains(&limit), "{limit}");
        for yaw in [0.003_f64, 0.02, 0.05, 0.1] {
            let p = g.prepare(&SidePose {
                lateral: 0.0,
                yaw,
                roll: 0.0,
            });
            let r0 = g.setup.wheel_radius;
            let offset = g.setup.taping_line_offset();
            for k in 0..=60 {
                let w = 0.69 + 0.001 * k as f64;
                // Points of the wheel profile only (beyond it there is no wheel).
                let extent = |x: f64| {
                    let l = -x * p.sin_yaw + w * p.cos_yaw;
                    let d = x * p.cos_yaw + w * p.sin_yaw;
                    let (lo, hi) = g.wheel.y_range();
                    let y = l - offset;
                    let r = r0 + g.wheel.z(y);
                    if (lo..=hi).contains(&y) {
                        (r * r - d * d).max(0.0).sqrt()
                    } else {
                        0.0
                    }
                };
                let x0 = -w * p.sin_yaw / p.cos_yaw;
                let best = (-3000..=3000)
                    .map(|i| x0 + 1e-4 * i as f64)
                    .map(|x| (x, extent(x)))
                    .max_by(|a, b| a.1.total_cmp(&b.1))
                    .unwrap();
                let z = g.wheel_at(w, &p).z;
                // The extent is flat at its maximum: 0.1 mm in X changes it by ≲ 1e−8 m (r·ψ²
                // terms), so the brute force is good to 1e−8 m.
                assert!(
                    z >= best.1 - 1e-8 && z <= best.1 + 1e-8,
                    "yaw {yaw}, w {w}: Newton {z}, brute force {} at x {}",
                    best.1,
                    best.0
                );
            }
        }
    }

    #[test]
    fn yawed_flange_lowest_point_is_found_where_the_spline_curvature_spikes() {
        // The left wheel of the ANALYN soak at step 164 542 (yaw 1.6 mrad, flange contact at
        // 70°): at w = 0.711495177166 (bits below) Newton met a locally convex q (knots 1 µm
        // apart near the flange tip) and its bisection of the ±r0/2 bracket jumped to a point
        // 115 mm ahead, 14 mm higher. Against the brute-force maximum over X (10 µm grid within
        // ±5 mm of d = 0; the extent is flat at its maximum, so the grid is good to ~1e−9 m).
        let g = s1002_on_uic60();
        let p = g.prepare(&SidePose {
            lateral: 0.006258849843302311,
            yaw: -0.001611671378269739,
            roll: -0.0011269058042709089,
        });
        let r0 = g.setup.wheel_radius;
        let offset = g.setup.taping_line_offset();
        let spike = f64::from_bits(0x3fe6c49188a61bdd);
        for w in (0..=100).map(|k| 0.7110 + 1e-5 * k as f64).chain([spike]) {
            let x0 = -w * p.sin_yaw / p.cos_yaw;
            let brute = (-500..=500)
                .map(|i| {
                    let x = x0 + 1e-5 * i as f64;
                    let l = -x * p.sin_yaw + w * p.cos_yaw;
                    let d = x * p.cos_yaw + w * p.sin_yaw;
                    let r = r0 + g.wheel.z(l - offset);
                    (r * r - d * d).max(0.0).sqrt()
                })
                .fold(f64::NEG_INFINITY, f64::max);
            let z = g.wheel_at(w, &p).z;
            // 1 µm: the spline wiggles by ~0.3 µm where its knots cluster, and at the spike's
            // lateral Newton settles on that wiggle's local maximum (0.3 µm low, measured);
            // everywhere else it meets the brute force to 1e−8 m.
            assert!(
                (z - brute).abs() < 1e-6,
                "w {w}: Newton {z}, brute force {brute}"
            );
        }
    }
}
