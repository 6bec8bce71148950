//! Contact planes, the projection of the rail and wheel surfaces on them, and the strips'
//! geometry in a plane.

use super::WheelOnRail;
use crate::geometry::strips::{PerStrip, StripGeometry, MAX_STRIPS};

/// The contact plane of a patch, in the wheelset frame of one side (lateral w towards the field
/// side, vertical z downwards from the axle): its origin is the rail point under the patch's
/// first-contact point (the local minimum of the gap). Tangent t = (cos γ, −sin γ) (towards the
/// field side), normal n = (sin γ, cos γ) (from the wheel into the rail).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactPlane {
    /// Lateral coordinate of the origin (wheelset frame) [m].
    pub w0: f64,
    /// Vertical coordinate of the origin below the axle [m].
    pub z0: f64,
    /// Inclination γ of the plane in the wheelset frame [rad], positive rising towards the flange.
    pub gamma: f64,
    /// Lowering of the wheel from its nominal height at which the geometry is taken: the
    /// vertical gap at the first-contact point, so that the surfaces just touch there [m]. (At
    /// the nominal height a shifted wheelset's wheel may overlap the rail by millimetres, where a
    /// normal projection of the two surfaces is meaningless.)
    pub lift: f64,
    /// Normal gap at the origin with the wheel lowered by `lift` [m] (zero up to round-off).
    pub gap_n: f64,
    /// sin γ and cos γ (every strip's projection needs them).
    pub sin_gamma: f64,
    pub cos_gamma: f64,
    /// Inclination of the plane in the rail's (track) frame [rad]: γ less the wheelset's roll
    /// on this side, the angle of the patch's normal force in track axes.
    pub gamma_rail: f64,
}

impl ContactPlane {
    /// The plane through (w0, z0) inclined by `gamma` [rad], for the wheel lowered by `lift`
    /// [m]; its normal gap `gap_n` is zero until set.
    pub fn new(w0: f64, z0: f64, gamma: f64, lift: f64) -> Self {
        let (sin_gamma, cos_gamma) = gamma.sin_cos();
        Self {
            w0,
            z0,
            gamma,
            lift,
            gap_n: 0.0,
            sin_gamma,
            cos_gamma,
            gamma_rail: gamma,
        }
    }

    /// Normal approach of the patch's first-contact point when the wheel is lowered by `dz` [m].
    pub fn approach(&self, dz: f64) -> f64 {
        (dz - self.lift) * self.cos_gamma - self.gap_n
    }
}

/// Points of the strips of a patch, for outputs and the tangential problem.
#[derive(Debug, Clone, Default)]
pub struct StripPoints {
    /// Lateral coordinate of the rail point in the mounted rail frame [m].
    pub y_rail: PerStrip<f64>,
    /// Slope dz_r/dy_r of the rail profile (rail frame: the track's, rails do not roll) at the
    /// strip's point.
    pub rail_slope: PerStrip<f64>,
    /// The local contact angle γ_j = −atan z_r' of the strip's rail point in the track frame
    /// (positive towards the flange) [rad], and its sine and cosine (the tangential problem and
    /// the strips' normal forces need them per strip).
    pub angle: PerStrip<f64>,
    pub sin_angle: PerStrip<f64>,
    pub cos_angle: PerStrip<f64>,
    /// Rolling radius of the wheel point [m].
    pub rolling_radius: PerStrip<f64>,
    /// Lateral coordinate of the rail point (wheelset frame) [m].
    pub lateral: PerStrip<f64>,
    /// Vertical gap between rail and wheel at the rail point's lateral with the wheel at its
    /// nominal height (the search's gap there) [m]: lowering the wheel by dz leaves dz less it
    /// of vertical interpenetration.
    pub vertical_gap: PerStrip<f64>,
}

impl StripPoints {
    /// Local contact angle γ_j of strip `j` in the track frame (positive towards the flange)
    /// [rad].
    pub fn contact_angle(&self, j: usize) -> f64 {
        self.angle[j]
    }
}

/// One point of a profile curve found by [`project_on_plane`].
#[derive(Debug, Clone, Copy)]
struct CurvePoint<T> {
    w: f64,
    z: f64,
    extra: T,
}

/// Normal gap given to in-plane coordinates where a surface has no point [m]: no approach
/// reaches it (the load iteration stops at 5 cm), so such a strip is never in contact.
pub const UNREACHED_GAP: f64 = 1.0;

/// Residual |t(w) − s| below which a plane projection has converged [m] (converged ones reach
/// ~1e−13; a failed one, where no point of the curve projects to s, stays at ≳ 1e−6).
const PROJECTION_TOLERANCE: f64 = 1e-9;

/// Residual |t(w) − s| at which a plane projection stops [m]. A point off by δs along the plane
/// moves the normal gap f by δs × f' (f' = 2Bs ≲ 0.05 across a patch), so 1e−10 m keeps f to
/// ~5e−12 m and the strips' B (central differences over ≥ 0.1 mm) to ~2e−3 1/m; at the
/// defaults the forces move by ~1e−8 relative against 1e−12 m, and one Newton step from the
/// tangent nearly always suffices (−11 k instructions per strip-model wheelset solve).
const PROJECTION_STOP: f64 = 1e-10;

/// Residual |t(w) − s| below which a plane projection takes its last Newton step δ along the
/// curve's tangent instead of evaluating the curve there [m]: the point's height is then off
/// the curve by ½ z'' δ² ≲ 4e−15 m (δ ≲ 1e−8 m, z'' ≤ 1/(13 mm) on S1002's flange root), and
/// its other quantities (rail coordinate, radius, slope, yaw lead) are the evaluated point's,
/// δ ≲ 10 nm away — what a start extrapolated from the neighbouring strips leaves
/// ([`ProjectionTrail`]), so that those projections need one curve evaluation.
const PROJECTION_FINISH: f64 = 1e-8;

/// Iterations of [`project_on_plane`]: Newton from the tangent converges in one or two steps
/// on a patch (quadratically: the start is off by ~s²z''/2).
const PROJECTION_STEPS: usize = 8;

/// Solves t(w) = (w − w0) cos γ − (z(w) − z0) sin γ = s for a curve w ↦ (z, dz/dw, extra) by
/// Newton's method (t' = cos γ − z' sin γ) started on the tangent, w = w0 + s cos γ. The flag
/// is false when it does not converge: beyond a point where the curve turns steeper than the
/// plane's normal (a rail's gauge face seen from a flange-root plane) t(w) has a maximum
/// (t' = 0), and in-plane coordinates past it have no point of the curve; an iterate with
/// t' ≤ 0 is past that maximum and ends the iteration.
fn project_on_plane<T: Copy>(
    plane: &ContactPlane,
    s: f64,
    curve: impl Fn(f64) -> (f64, f64, T),
) -> (CurvePoint<T>, bool) {
    project_from(plane, s, plane.w0 + s * plane.cos_gamma, &curve)
}

/// [`project_on_plane`] started at `start` (a point extrapolated from the projections of the
/// neighbouring in-plane coordinates, [`ProjectionTrail`]); where that does not converge, from
/// the tangent.
fn project_near<T: Copy>(
    plane: &ContactPlane,
    s: f64,
    start: Option<f64>,
    curve: impl Fn(f64) -> (f64, f64, T),
) -> (CurvePoint<T>, bool) {
    if let Some(w) = start {
        let found = project_from(plane, s, w, &curve);
        if found.1 {
            return found;
        }
    }
    project_on_plane(plane, s, &curve)
}

/// The Newton iteration of [`project_on_plane`] from `w`.
fn project_from<T: Copy>(
    plane: &ContactPlane,
    s: f64,
    mut w: f64,
    curve: &impl Fn(f64) -> (f64, f64, T),
) -> (CurvePoint<T>, bool) {
    let (sin_g, cos_g) = (plane.sin_gamma, plane.cos_gamma);
    let (z, slope, extra) = curve(w);
    let mut point = CurvePoint { w, z, extra };
    let mut slope = slope;
    let mut residual = in_plane_coordinate(plane, w, z) - s;
    for _ in 0..PROJECTION_STEPS {
        let dt = cos_g - slope * sin_g;
        if residual.abs() < PROJECTION_STOP || dt <= 0.0 || !dt.is_finite() {
            break;
        }
        let step = -residual / dt;
        if residual.abs() < PROJECTION_FINISH {
            // The last step along the tangent, without evaluating the curve again.
            point.w += step;
            point.z += slope * step;
            residual = in_plane_coordinate(plane, point.w, point.z) - s;
            break;
        }
        w += step;
        let (z, dz, extra) = curve(w);
        point = CurvePoint { w, z, extra };
        slope = dz;
        residual = in_plane_coordinate(plane, w, z) - s;
    }
    (point, residual.abs() <= PROJECTION_TOLERANCE)
}

/// The points of one surface projected at equally spaced in-plane coordinates, the last four,
/// for the next projection's start (`WheelOnRail::strip_geometry`): the cubic through them
/// lands within ~1e−9 m of the next point at strips 0.5 mm apart (the profile splines' third
/// derivatives jump at their knots), below [`PROJECTION_FINISH`], so that the projection needs
/// one curve evaluation instead of the tangent start's two; farther off (a fold, a coarse
/// strip spacing) it takes its Newton steps as before.
#[derive(Debug, Clone, Copy, Default)]
struct ProjectionTrail {
    /// Oldest first.
    w: [f64; 4],
    n: usize,
}

impl ProjectionTrail {
    /// The next point's start: the cubic extrapolation, once four points are known.
    fn start(&self) -> Option<f64> {
        let w = &self.w;
        (self.n >= 4).then(|| 4.0 * w[3] - 6.0 * w[2] + 4.0 * w[1] - w[0])
    }

    /// Appends a projected point (`found` false: the surface has none there, start again).
    fn push(&mut self, w: f64, found: bool) {
        if !found {
            self.n = 0;
            return;
        }
        self.w.copy_within(1.., 0);
        self.w[3] = w;
        self.n = (self.n + 1).min(4);
    }
}

/// Normal coordinate (n = (sin γ, cos γ)) of the wheelset-frame point (w, z) from the plane's
/// origin [m].
fn normal_coordinate(plane: &ContactPlane, w: f64, z: f64) -> f64 {
    (w - plane.w0) * plane.sin_gamma + (z - plane.z0) * plane.cos_gamma
}

/// In-plane coordinate t = (w − w0) cos γ − (z − z0) sin γ of the wheelset-frame point (w, z)
/// from the plane's origin [m].
fn in_plane_coordinate(plane: &ContactPlane, w: f64, z: f64) -> f64 {
    (w - plane.w0) * plane.cos_gamma - (z - plane.z0) * plane.sin_gamma
}

/// Gap and points at one in-plane coordinate (see [`WheelOnRail::strip_geometry`]).
#[derive(Debug, Clone, Copy)]
struct PlaneGap {
    /// Normal gap minus the origin's gap [m]; [`UNREACHED_GAP`] where a surface has no point
    /// at this in-plane coordinate.
    f: f64,
    /// Whether both surfaces have a point here ([`project_on_plane`] converged for both).
    found: bool,
    /// Longitudinal position of the wheel's lowest point [m].
    x: f64,
    /// Rail point: lateral (wheelset frame) and rail-frame coordinate [m].
    w_rail: f64,
    y_rail: f64,
    /// The rail profile's slope dz_r/dy_r there [-].
    rail_slope: f64,
    /// The wheel's radius at its point [m].
    radius: f64,
    /// Vertical gap at the rail point's lateral with the wheel at its nominal height [m].
    vertical_gap: f64,
}

impl WheelOnRail {
    /// The contact plane at lateral `w0` (wheelset frame) for the pose of the last search, with
    /// the wheel lowered by `lift` (the vertical gap at `w0`, so that the surfaces touch there):
    /// origin on the rail, inclination from the rail's slope there (at a gap minimum the rail and
    /// wheel slopes agree).
    pub fn contact_plane(&self, w0: f64, lift: f64) -> ContactPlane {
        let p = &self.pose;
        let rail = self.rail_at(w0, p);
        let mut plane = ContactPlane::new(w0, rail.z, -rail.slope.atan(), lift);
        plane.gamma_rail = plane.gamma - p.roll;
        // The tangent point itself always projects (dt/dw = 1/cos γ there).
        let (wheel, _) = project_on_plane(&plane, 0.0, |w| {
            let q = self.wheel_at(w, p);
            (q.z + lift, q.slope, ())
        });
        plane.gap_n = -normal_coordinate(&plane, wheel.w, wheel.z);
        plane
    }

    /// In-plane coordinate s of the rail point at wheelset-frame lateral `w` [m].
    pub fn plane_coordinate_of(&self, plane: &ContactPlane, w: f64) -> f64 {
        in_plane_coordinate(plane, w, self.rail_at(w, &self.pose).z)
    }

    /// Rail and wheel points at in-plane coordinate `s` and their normal gap, their projections
    /// started from the trails' extrapolations where known.
    fn gap_in_plane(
        &self,
        plane: &ContactPlane,
        s: f64,
        trails: &mut (ProjectionTrail, ProjectionTrail),
    ) -> PlaneGap {
        let p = &self.pose;
        let (rail, rail_found) = project_near(plane, s, trails.0.start(), |w| {
            let q = self.rail_at(w, p);
            (q.z, q.slope, (q.y_rail, q.profile_slope))
        });
        let (wheel, wheel_found) = project_near(plane, s, trails.1.start(), |w| {
            let q = self.wheel_at(w, p);
            (q.z + plane.lift, q.slope, (q.x, q.radius, q.slope))
        });
        trails.0.push(rail.w, rail_found);
        trails.1.push(wheel.w, wheel_found);
        let found = rail_found && wheel_found;
        PlaneGap {
            f: if found {
                normal_coordinate(plane, rail.w, rail.z)
                    - normal_coordinate(plane, wheel.w, wheel.z)
                    - plane.gap_n
            } else {
                UNREACHED_GAP
            },
            found,
            x: wheel.extra.0,
            w_rail: rail.w,
            y_rail: rail.extra.0,
            rail_slope: rail.extra.1,
            radius: wheel.extra.1,
            // The wheel's height at the rail point's lateral from its own point's tangent (the
            // two lie ~f sin γ apart, ≲ 0.1 mm: the tangent's error is below 1e−10 m).
            vertical_gap: rail.z - (wheel.z - plane.lift + wheel.extra.2 * (rail.w - wheel.w)),
        }
    }

    /// Fills `geom` and `points` with `n` strips of equal width covering [s_lo, s_hi] of the
    /// contact plane: the normal gap f from the origin's gap, A = cos γ_i/(2 r_i) at each strip's
    /// own contact angle and rolling radius (Meusnier, straight rail), B = ½ f'' by central
    /// differences over the strip spacing (one extra gap value beyond each end), and the yaw
    /// locus x_c. Known limits: A ignores the small tilt cos(γ_i − γ) between the strip and the
    /// plane, and the change of the wheel's lateral curvature by yaw.
    pub fn strip_geometry(
        &self,
        plane: &ContactPlane,
        s_lo: f64,
        s_hi: f64,
        n: usize,
        geom: &mut StripGeometry,
        points: &mut StripPoints,
    ) {
        let n = n.clamp(1, MAX_STRIPS);
        let ds = (s_hi - s_lo) / n as f64;
        geom.n = n;
        geom.ds = ds;
        let mut trails = Default::default();
        let mut previous = self.gap_in_plane(plane, s_lo - 0.5 * ds, &mut trails);
        let mut current = self.gap_in_plane(plane, s_lo + 0.5 * ds, &mut trails);
        // Strips whose B stencil reaches a point without surfaces take the B of the nearest
        // strip whose stencil is whole (such strips border a fold and are out of contact).
        let mut whole_stencil = [false; MAX_STRIPS];
        for (i, whole) in whole_stencil[..n].iter_mut().enumerate() {
            let s = s_lo + (i as f64 + 0.5) * ds;
            let next = self.gap_in_plane(plane, s + ds, &mut trails);
            let slope = current.rail_slope;
            let radius = current.radius;
            // γ = −atan z_r': cos γ = 1/√(1 + z_r'²), sin γ = −z_r' cos γ.
            let cos_gamma = 1.0 / (1.0 + slope * slope).sqrt();
            geom.s[i] = s;
            geom.f[i] = current.f;
            geom.curv_a[i] = 0.5 * cos_gamma / radius;
            geom.curv_b[i] = (next.f - 2.0 * current.f + previous.f) / (2.0 * ds * ds);
            *whole = previous.found && current.found && next.found;
            geom.x_c[i] = current.x;
            points.y_rail[i] = current.y_rail;
            points.rail_slope[i] = slope;
            points.angle[i] = -slope.atan();
            points.cos_angle[i] = cos_gamma;
            points.sin_angle[i] = -slope * cos_gamma;
            points.rolling_radius[i] = radius;
            points.lateral[i] = current.w_rail;
            points.vertical_gap[i] = current.vertical_gap;
            previous = current;
            current = next;
        }
        let whole = &whole_stencil[..n];
        if whole.iter().any(|&w| !w) {
            for i in 0..n {
                if whole[i] {
                    continue;
                }
                let nearest = (0..n).filter(|&j| whole[j]).min_by_key(|&j| j.abs_diff(i));
                if let Some(j) = nearest {
                    geom.curv_b[i] = geom.curv_b[j];
                }
            }
        }
    }

    /// Inclination of the rail at lateral `w0` in the wheelset frame, γ = −atan(dz/dw) [rad]
    /// (positive rising towards the flange): the angle of the contact plane at a gap minimum.
    pub fn plane_angle_at(&self, w0: f64) -> f64 {
        -self.rail_at(w0, &self.pose).slope.atan()
    }

    /// The contact plane through the rail point at lateral `w0` (wheelset frame) inclined by
    /// `gamma` [rad], with the wheel lowered by `lift` (see [`WheelOnRail::contact_plane`]).
    pub fn contact_plane_inclined(&self, w0: f64, lift: f64, gamma: f64) -> ContactPlane {
        let p = &self.pose;
        let rail = self.rail_at(w0, p);
        let mut plane = ContactPlane::new(w0, rail.z, gamma, lift);
        plane.gamma_rail = gamma - p.roll;
        let (wheel, _) = project_on_plane(&plane, 0.0, |w| {
            let q = self.wheel_at(w, p);
            (q.z + lift, q.slope, ())
        });
        plane.gap_n = -normal_coordinate(&plane, wheel.w, wheel.z);
        plane
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::search::{s1002_on_uic60, Region, SidePose};

    #[test]
    fn plane_coordinates_past_a_fold_have_no_point() {
        // z = c w² seen from a plane through the origin inclined by γ: t(w) = w cos γ − c w² sin γ
        // peaks at t_max = cos²γ / (4 c sin γ); beyond it no point of the curve projects.
        let plane = ContactPlane::new(0.0, 0.0, 0.5, 0.0);
        let c = 50.0;
        let (sin_g, cos_g) = plane.gamma.sin_cos();
        let t_max = cos_g * cos_g / (4.0 * c * sin_g);
        for fraction in [-0.9, -0.3, 0.0, 0.3, 0.6] {
            let s = fraction * t_max;
            let (point, found) = project_on_plane(&plane, s, |w| (c * w * w, 2.0 * c * w, ()));
            assert!(found, "{fraction}");
            let t = point.w * cos_g - point.z * sin_g;
            assert!((t - s).abs() < 1e-12, "{fraction}: {t} vs {s}");
        }
        for fraction in [1.05, 1.5, 3.0] {
            let (_, found) =
                project_on_plane(&plane, fraction * t_max, |w| (c * w * w, 2.0 * c * w, ()));
            assert!(!found, "{fraction}");
        }
    }

    #[test]
    fn strips_over_the_rails_gauge_face_are_out_of_contact() {
        // Right wheel in flange-root contact (lateral shift 6.5 mm on the standard track): the
        // flange-root plane (γ ≈ 0.5 rad) sees the rail's steep gauge face at its gauge end.
        // The secant projection used to fail there and leave a −0.3 mm gap (in contact at any
        // height); Newton with the profile's slope follows the face (t' = cos γ + |z'| sin γ
        // grows with the steepness), and any strip that still has no point would get
        // UNREACHED_GAP. Either way no strip of the range has a spurious negative gap.
        let mut g = s1002_on_uic60();
        let pose = SidePose {
            lateral: 0.0065,
            yaw: 0.0,
            roll: 0.0,
        };
        g.search(&pose).unwrap();
        // The regions 1 mm below first contact: every candidate up there is found.
        let touch = g
            .candidates()
            .as_slice()
            .iter()
            .map(|c| c.gap)
            .fold(1.0, f64::min);
        g.regions(touch + 1e-3, &mut [Region::default(); 4]);
        let root = g
            .candidates()
            .as_slice()
            .iter()
            .find(|c| (0.45..0.55).contains(&c.contact_angle))
            .copied()
            .expect("a flange-root candidate at about 0.5 rad");
        let plane = g.contact_plane(root.lateral, root.gap);
        let mut geom = StripGeometry::default();
        let mut points = StripPoints::default();
        g.strip_geometry(&plane, -0.014, 0.005, 40, &mut geom, &mut points);
        // The gauge face (s < −9 mm here) lies millimetres away from the wheel's flange root:
        // clearly out of contact (0.1 mm is twice a patch's depth at this load).
        for i in (0..geom.n).filter(|&i| geom.s[i] < -0.009) {
            assert!(
                geom.f[i] > 1e-4,
                "strip {i} at s {}: f {}",
                geom.s[i],
                geom.f[i]
            );
        }
        for i in 0..geom.n {
            assert!(
                geom.f[i] >= -1e-9,
                "strip {i} at s {}: f {}",
                geom.s[i],
                geom.f[i]
            );
            assert!(
                geom.curv_b[i].abs() < 1e4,
                "strip {i}: B {}",
                geom.curv_b[i]
            );
        }
    }
}
