//! Rigid contact search between one wheel and its rail for a wheelset pose.
//!
//! Method (docs/theory.md §7.6): in the side frame (see [`crate::geometry::track`]) the wheelset
//! pose is a lateral shift, a yaw angle ψ and a roll angle θ. For each lateral coordinate W across
//! the rail (measured from the wheelset centre along the wheelset's own lateral axis):
//!
//! * **roll** is applied by rotating the rail curve by −θ about the wheelset centre into the
//!   wheelset frame (a rail is a 2-D curve extruded along x, so the rotated rail is again a curve);
//! * **yaw**: a wheel of revolution seen from below has, at lateral W, its lowest point at the
//!   longitudinal position X where r(l)² − d² is largest, with l = −X sin ψ + W cos ψ the axial
//!   coordinate, d = X cos ψ + W sin ψ the horizontal distance from the axle plane and r(l) the
//!   wheel radius; a few Newton steps on X give the yaw lead/lag of the contact point (exact for
//!   a surface of revolution; roll–yaw coupling neglected, second order);
//! * the **vertical gap** g(W) = z_rail(W) − z_wheel(W) (z down) is sampled on a uniform grid and
//!   its local minima are refined by regula falsi on its slope: each separate local minimum is a
//!   potential contact point (tread, flange root, flange). Minima whose gap rises between them by
//!   less than [`MIN_PROMINENCE`] are one point.
//! * the grid is sampled **lazily**: every `COARSE_STRIDE`-th sample first; between two coarse
//!   samples a lower bound of the gap (from exact per-bin bounds of both profiles' heights and
//!   slopes, [`crate::geometry::profile::bounds`]) decides whether the fine samples there are needed for
//!   the level asked for (the deepest point at the search; each region's lowering later). Below
//!   the filled level the samples, regions and candidates are those of the full grid (unit test
//!   `lazy_scan_equals_the_full_scan_below_the_filled_level`); above it nothing is computed.
//!   (The one difference: with more than [`MAX_CANDIDATES`] minima on the full grid, its later
//!   ones merge into the last kept; the lazy scan keeps every minimum below the level.)
//!
//! Per contact point: contact angle γ (from the rail slope; positive when the contact plane rises
//! towards the gauge side, i.e. towards the flange — the same sign on both wheels), rolling radius,
//! rail and wheel profile coordinates, and the relative curvatures
//! A = cos γ/(2r) (Meusnier, straight rail) and B = (κ_rail − κ_wheel)/2 with
//! κ = z''/(1 + z'²)^{3/2}, floored at `b_min` (CONTACT's floor 1e−4 1/mm, docs/theory.md §5.9).
//!
//! Known limits: the gap is measured vertically in the wheelset frame (δ_normal = δ_vertical·cos γ);
//! B ignores the small change of lateral curvature by yaw; straight track.

use crate::geometry::profile::bounds::HeightBounds;
use crate::geometry::profile::Profile;
use crate::geometry::strips::{PerStrip, StripGeometry, MAX_STRIPS};
use crate::geometry::track::{GeometryError, MountedRail, TrackSetup};
use crate::numeric::roots::Illinois;

/// Largest number of separate contact candidates kept per wheel.
pub const MAX_CANDIDATES: usize = 8;

/// Local minima whose separating ridge is lower than this above the shallower minimum are one
/// candidate [m]: 1 nm, round-off of the gap's evaluation. Shallow ripples above it stay separate
/// candidates; where the interpenetration submerges their ridges, the patch groups blend them
/// continuously ([`crate::geometry::groups`]), where merging them here would make the candidate jump
/// between the ripple's minima as their depths cross.
pub const MIN_PROMINENCE: f64 = 1e-9;

/// Default sampling step of the gap function [m].
pub const DEFAULT_SCAN_STEP: f64 = 5e-4;

/// A closest approach this close to the flange tip, or beyond it, means the wheel rides on its
/// flange [m]: within 2 mm of the top of the flange's tip radius (S1002: 12–20 mm) the contact
/// plane is inclined by less than ~10°, i.e. the flange no longer guides the wheel.
pub const FLANGE_TIP_MARGIN: f64 = 2e-3;

/// Inclination of the wheel profile below which a closest approach on the flange's tip side of
/// its steepest point means the wheel rides on its flange [rad]: 0.45 rad (26°), where the
/// flange's flank has turned into its tip radius (S1002: 5 mm from the tip on its R12 arc) and
/// Nadal's limit Y/Q = (tan γ − μ)/(1 + μ tan γ) has fallen below 0.2 at μ = 0.3. It catches a
/// wheel that a large roll sets on its flange top (the tip margin alone is measured along the
/// profile, not against the rail).
pub const FLANGE_CLIMB_ANGLE: f64 = 0.45;

/// Fraction of a region's depth at which its reference point is taken (see `regions`): Kik and
/// Piotrowski's virtual-penetration factor ε (`crate::normal::kik_piotrowski::KP_EPSILON`).
const VIRTUAL_FRACTION: f64 = 0.55;

/// Iteration limit of the yawed wheel's lowest-point search (Newton converges in 2–3 steps from
/// the axle-plane guess at the yaw angles of running; bisection halves the 0.46 m bracket to
/// 1e−9 m in 29 steps where Newton cannot be trusted).
const WHEEL_NEWTON_STEPS: usize = 40;

/// Margin on the single-maximum condition tan²ψ (z'² + r z'')max < 1 of that search.
const UNIMODAL_MARGIN: f64 = 0.9;

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

/// Fine samples per coarse interval of the scan. The search samples every `COARSE_STRIDE`-th
/// point first and fills in an interval's fine samples only where a lower bound of the gap over
/// it lies below the level asked for (see [`WheelOnRail::search`]). 12 (6 mm at the default
/// step): the slope bound is exact on the gap's monotone flanks, so wide intervals cost little
/// away from the contact; near it a wide interval fills samples the region does not need.
/// Measured (Hertz wheelset solve, instructions, when it was chosen): 8 → 141 k, 12 → 134 k,
/// 16 → 137 k.
const COARSE_STRIDE: usize = 12;

/// Depth above the deepest coarse sample to which a search fills the fine samples at once [m]
/// (regions asked for deeper fill more, and find the candidates below their level then):
/// 0.1 mm, about the approach of a tread contact under a 100 kN wheel load, so that the load
/// iteration's first lowering rarely fills again. (Any depth gives the same results; 10 µm,
/// 0.1 mm and 0.2 mm cost 147 k, 141 k and 145 k instructions per Hertz wheelset solve, at a
/// stride of 8 when it was chosen.)
const INITIAL_FILL_DEPTH: f64 = 1e-4;

/// Height-bound bins per scan step (see [`HeightBounds`]): half a step, so that an interval's
/// bound is widened by at most a quarter of its width at each end.
const BOUND_BINS_PER_STEP: f64 = 2.0;

/// Margin subtracted from the gap's lower bound against rounding [m].
const BOUND_ROUNDING: f64 = 1e-12;

/// Default floor of the relative lateral curvature B [1/m] (CONTACT: 1e−4 1/mm).
pub const DEFAULT_B_MIN: f64 = 0.1;

/// Wheelset pose in a side frame (lateral towards this side's field side).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SidePose {
    /// Lateral position of the wheelset centre [m].
    pub lateral: f64,
    /// Yaw angle about z (down) [rad].
    pub yaw: f64,
    /// Roll angle about x [rad], positive lowering this side.
    pub roll: f64,
}

/// One rigid contact point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactPoint {
    /// Lateral coordinate from the wheelset centre (wheelset frame, towards the field side) [m].
    pub lateral: f64,
    /// Longitudinal position (yaw lead/lag), positive forward [m].
    pub longitudinal: f64,
    /// Vertical gap at the point with the wheelset at its nominal height [m]; negative means
    /// interpenetration. Lowering the wheel by dz reduces it by dz.
    pub gap: f64,
    /// Lateral coordinate in the mounted rail frame (towards the field side) [m].
    pub y_rail: f64,
    /// Lateral coordinate in the wheel profile frame [m].
    pub y_wheel: f64,
    /// Contact angle, positive towards the flange [rad].
    pub contact_angle: f64,
    /// Rolling radius [m].
    pub rolling_radius: f64,
    /// Relative longitudinal curvature A [1/m].
    pub curv_a: f64,
    /// Relative lateral curvature B [1/m] (floored).
    pub curv_b: f64,
}

/// Contact candidates of one wheel, ordered from the field side to the gauge side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactCandidates {
    points: [ContactPoint; MAX_CANDIDATES],
    len: usize,
}

impl Default for ContactCandidates {
    fn default() -> Self {
        Self {
            points: [ContactPoint::default(); MAX_CANDIDATES],
            len: 0,
        }
    }
}

impl ContactCandidates {
    pub fn as_slice(&self) -> &[ContactPoint] {
        &self.points[..self.len]
    }
    pub fn len(&self) -> usize {
        self.len
    }
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
    fn clear(&mut self) {
        self.len = 0;
    }
    fn push(&mut self, p: ContactPoint) {
        if self.len < MAX_CANDIDATES {
            self.points[self.len] = p;
            self.len += 1;
        }
    }
}

/// Why a pose has no usable rigid contact.
#[derive(Debug, Clone, PartialEq)]
pub enum SearchError {
    /// The wheel and rail profiles do not overlap laterally at this pose.
    NoOverlap { lateral: f64 },
    /// The deepest point lies at the end of a profile (flange climb or wheel off the rail).
    AtProfileEnd { lateral: f64, y_rail: f64 },
    /// At the deepest point the (yawed) wheel is seen outside its profile's lateral range.
    OutsideWheel { lateral: f64, y_wheel: f64 },
    /// The wheel rides on its flange tip (or beyond it): it is derailing.
    FlangeClimb { lateral: f64, y_wheel: f64 },
}

impl std::fmt::Display for SearchError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SearchError::NoOverlap { lateral } => write!(
                f,
                "no rigid contact inside the profiles' range: wheel and rail profiles do not \
                 overlap at lateral wheelset position {lateral} m"
            ),
            SearchError::AtProfileEnd { lateral, y_rail } => write!(
                f,
                "no rigid contact inside the profiles' range: the closest approach lies at the \
                 end of a profile (yRail = {y_rail} m) at lateral wheelset position {lateral} m \
                 (flange climb or the wheel leaving the rail)"
            ),
            SearchError::FlangeClimb { lateral, y_wheel } => write!(
                f,
                "flange climb: the wheel rides on its flange tip (wheel coordinate {y_wheel} m) at \
                 lateral wheelset position {lateral} m; the wheelset is derailing"
            ),
            SearchError::OutsideWheel { lateral, y_wheel } => write!(
                f,
                "no rigid contact inside the profiles' range: the closest approach lies outside \
                 the wheel profile (wheel coordinate {y_wheel} m) at lateral wheelset position \
                 {lateral} m (large yaw or the wheel leaving the rail)"
            ),
        }
    }
}

impl std::error::Error for SearchError {}

/// An interpenetration region of one wheel at a given vertical position (sample indices of the
/// last search).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Region {
    /// First and last sample inside the region (gauge side first).
    pub first: usize,
    pub last: usize,
    /// Penetration-weighted centroid, as a fractional sample index.
    pub centroid_index: f64,
    /// Sample index of the deepest point.
    pub deepest: usize,
    /// Largest vertical interpenetration [m].
    pub depth: f64,
}

/// The highest point of the gap between two neighbouring contact candidates: the ridge a
/// wheel's interpenetration must submerge for the two minima to share one patch.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Ridge {
    /// Lateral coordinate (wheelset frame) [m].
    pub lateral: f64,
    /// Vertical gap there with the wheelset at its nominal height [m].
    pub gap: f64,
}

/// The flange tip of a wheel profile: the highest point (largest radius increase z) on the
/// flange side (y < 0), from the profile's data points.
fn flange_tip(wheel: &Profile) -> f64 {
    let (ys, zs) = wheel.points();
    ys.iter()
        .zip(zs)
        .filter(|(y, _)| **y < 0.0)
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map_or(f64::NEG_INFINITY, |(y, _)| *y)
}

/// The wheel-profile coordinate of the flange's steepest point: the largest |z'| between the
/// flange tip `tip` and the taping line (y = 0), sampled every 10 µm.
fn flange_steepest(wheel: &Profile, tip: f64) -> f64 {
    const STEP: f64 = 1e-5;
    let n = ((-tip) / STEP).ceil().max(1.0) as usize;
    (0..=n)
        .map(|i| tip * (1.0 - i as f64 / n as f64))
        .max_by(|&a, &b| wheel.dz(a).abs().total_cmp(&wheel.dz(b).abs()))
        .unwrap_or(tip)
}

/// A sample of the gap function.
#[derive(Debug, Clone, Copy, Default)]
struct GapSample {
    gap: f64,
    /// d gap / dw [-].
    slope: f64,
    x: f64,
    y_rail: f64,
    y_wheel: f64,
}

/// The rail surface at a lateral w of the wheelset frame.
#[derive(Debug, Clone, Copy)]
struct RailPoint {
    /// Vertical coordinate below the axle [m].
    z: f64,
    /// dz/dw in the wheelset frame [-].
    slope: f64,
    /// Rail-frame lateral coordinate [m].
    y_rail: f64,
    /// The rail profile's own slope dz_r/dy_r there (rail frame) [-].
    profile_slope: f64,
}

/// The lowest point of the (yawed) wheel at a lateral w of the wheelset frame.
#[derive(Debug, Clone, Copy)]
struct WheelPoint {
    /// Vertical coordinate below the axle [m].
    z: f64,
    /// dz/dw [-].
    slope: f64,
    /// Longitudinal position [m].
    x: f64,
    /// Wheel-profile lateral coordinate [m].
    y_wheel: f64,
    /// Wheel radius there, r0 + z_w(y_wheel) [m].
    radius: f64,
}

/// Trigonometry and offsets of a pose, computed once per search.
#[derive(Debug, Clone, Copy, Default)]
struct Prepared {
    lateral: f64,
    sin_yaw: f64,
    cos_yaw: f64,
    sin_roll: f64,
    cos_roll: f64,
    /// Roll angle of this side [rad].
    roll: f64,
    /// Whether the yawed wheel has one lowest point per lateral (see `WheelOnRail::wheel_at`).
    single_lowest_point: bool,
    /// tan ψ, sin²ψ / cos ψ and 1 / cos ψ of the yaw ψ (the lowest point's lead and lateral).
    tan_yaw: f64,
    sin_tan: f64,
    inv_cos: f64,
}

/// One wheel on its rail: mounted geometry plus the scan buffer (allocated once).
#[derive(Debug, Clone)]
pub struct WheelOnRail {
    rail: MountedRail,
    wheel: Profile,
    setup: TrackSetup,
    scan_step: f64,
    b_min: f64,
    /// Wheel-profile coordinate of the flange tip (highest z on the flange side, y < 0) [m].
    flange_tip: f64,
    /// Wheel-profile coordinate of the flange's steepest point (largest |z'| between the tip
    /// and the taping line) [m].
    flange_steepest: f64,
    /// max over the wheel profile's running side of z'² + r z'' [-] (r the radius there): the
    /// yawed wheel's lowest point is unique at yaw ψ with tan²ψ × this < 1 (`wheel_at`).
    wheel_convexity: f64,
    /// max over the same part of r |z'| [m]: the lowest point of a wheel yawed by ψ has its lead
    /// d = −r z' tan ψ (q'(X) = 0 in `wheel_at`), so |d| ≤ this × |tan ψ|.
    wheel_lead_bound: f64,
    /// Height bounds of the mounted rail and of the wheel (`gap_lower_bound`), and the mounted
    /// rail's smallest and largest height [m].
    rail_bounds: HeightBounds,
    wheel_bounds: HeightBounds,
    rail_heights: (f64, f64),
    /// The fine samples of the last search; those of unfilled coarse intervals are [`UNFILLED`].
    samples: Vec<GapSample>,
    /// The samples' cubic Hermite interpolant, one piece per sample interval (`pieces[k]` between
    /// samples k and k + 1; unfilled ones lie at +∞), for [`WheelOnRail::depth_moments`].
    pieces: Vec<Piece>,
    /// The contact candidates of the last search (see [`WheelOnRail::candidates`]) and the
    /// sample index of each one's minimum.
    candidates: ContactCandidates,
    candidate_minima: [usize; MAX_CANDIDATES],
    /// The ridges between neighbouring candidates of the last search ([`WheelOnRail::ridges`]).
    ridges: [Option<Ridge>; MAX_CANDIDATES],
    /// Fine samples per coarse interval ([`COARSE_STRIDE`]; 1 samples everything at once).
    coarse_stride: usize,
    /// The coarse intervals of the last search.
    coarse: Vec<CoarseInterval>,
    /// Every sample of the last search with a gap below this is computed [m], and lies in this
    /// span of sample indices (the coarse intervals whose bound lies below it).
    filled_level: f64,
    filled_span: (usize, usize),
    /// The overlap of the profiles at the last search's pose (wheelset frame) [m].
    scan_bounds: (f64, f64),
    /// Lateral coordinate of the first sample and the sample spacing of the last search [m].
    scan_lo: f64,
    scan_dw: f64,
    /// The pose of the last search.
    pose: Prepared,
}

/// A coarse interval of the scan: fine samples `first..=last` (the ends always computed).
#[derive(Debug, Clone, Copy)]
struct CoarseInterval {
    first: usize,
    last: usize,
    /// Lower bound of the gap over the interval [m].
    lower: f64,
    /// Whether its interior samples are computed.
    filled: bool,
}

/// A fine sample not computed: its gap lies above the search's filled level.
const UNFILLED: GapSample = GapSample {
    gap: f64::INFINITY,
    slope: 0.0,
    x: 0.0,
    y_rail: 0.0,
    y_wheel: 0.0,
};

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

/// Iteration limit of the minimum's refinement in [`WheelOnRail::search`] (regula falsi
/// converges in ~6; the limit only guards a pathological slope).
const REFINE_STEPS: usize = 40;

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

/// max of z'² + r z'' with r = `radius` + z (the radius at the point) [-] over the wheel profile
/// from the flange tip `from` to the field side, sampled every 10 µm. Where the spline's knots
/// cluster closer than that (1 µm near the S1002 flange tip) its z'' can spike between samples,
/// so this is a sampled maximum: `wheel_at` keeps its Newton inside the lead bound
/// ([`wheel_lead_bound`]) for that reason. The flange's back (z' → ∞ on its vertical face) is
/// left out: contact there is refused as flange climb, and a yawed wheel's lowest point cannot
/// lie on it (its lead r z' tan ψ would exceed r/2).
fn wheel_convexity(wheel: &Profile, radius: f64, from: f64) -> f64 {
    running_side_max(wheel, from, |z, dz, d2z| dz * dz + (radius + z) * d2z)
}

/// max of r |z'| with r = `radius` + z [m] over the wheel profile's running side from `from`
/// (as [`wheel_convexity`]; also at every knot, where the slope of a clustered run of knots
/// peaks).
fn wheel_lead_bound(wheel: &Profile, radius: f64, from: f64) -> f64 {
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

/// Moments of a wheel's interpenetration below a level ([`WheelOnRail::depth_moments`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DepthMoments {
    /// ∫ d dw [m²], d the depth below the level.
    pub integral: f64,
    /// d-weighted mean lateral (wheelset frame) [m].
    pub mean: f64,
    /// d-weighted variance of the lateral [m²].
    pub variance: f64,
}

/// Coefficients (c0 + c1 t + c2 t² + c3 t³) of level − H(t) on t ∈ [0, 1], H the cubic Hermite
/// interpolant with values `g0`, `g1` and derivatives `d0`, `d1` (per unit t) at the ends.
fn hermite_depth(level: f64, g0: f64, g1: f64, d0: f64, d1: f64) -> [f64; 4] {
    let c2 = 3.0 * (g1 - g0) - 2.0 * d0 - d1;
    let c3 = 2.0 * (g0 - g1) + d0 + d1;
    [level - g0, -d0, -c2, -c3]
}

/// One piece of the samples' cubic Hermite interpolant, H(t) = c0 + c1 t + c2 t² + c3 t³ on
/// t ∈ [0, 1] between two samples, with bounds of its values and its moments ∫₀¹ tʲ H dt.
#[derive(Debug, Clone, Copy)]
struct Piece {
    lowest: f64,
    highest: f64,
    cubic: [f64; 4],
    whole: [f64; 3],
}

impl Piece {
    /// The piece between samples `a` and `b` a step `h` apart; at +∞ where either is unfilled.
    fn of(a: &GapSample, b: &GapSample, h: f64) -> Self {
        if !(a.gap.is_finite() && b.gap.is_finite()) {
            return Self {
                lowest: f64::INFINITY,
                highest: f64::INFINITY,
                cubic: [0.0; 4],
                whole: [0.0; 3],
            };
        }
        let (d0, d1) = (a.slope * h, b.slope * h);
        let (lowest, highest) = hermite_bounds(a.gap, b.gap, d0, d1);
        // hermite_depth at level 0 is −H.
        let cubic = hermite_depth(0.0, a.gap, b.gap, d0, d1).map(|c| -c);
        Self {
            lowest,
            highest,
            cubic,
            whole: cubic_moments(&cubic, 0.0, 1.0),
        }
    }
}

/// Lower and upper bounds of the cubic Hermite interpolant with values `g0`, `g1` and
/// derivatives `d0`, `d1` (per unit t) on t ∈ [0, 1]: H = chord + t(1 − t)[(d0 − Δ)(1 − t) −
/// (d1 − Δ)t] with Δ = g1 − g0, t(1 − t) ≤ ¼ and the bracket within ±max|dᵢ − Δ|.
fn hermite_bounds(g0: f64, g1: f64, d0: f64, d1: f64) -> (f64, f64) {
    let chord = g1 - g0;
    let bulge = 0.25 * (d0 - chord).abs().max((d1 - chord).abs());
    (g0.min(g1) - bulge, g0.max(g1) + bulge)
}

fn cubic_at(c: &[f64; 4], t: f64) -> f64 {
    c[0] + t * (c[1] + t * (c[2] + t * c[3]))
}

/// ∫ t^j p(t) dt over [t0, t1] for j = 0, 1, 2, p the cubic `c`: the antiderivatives
/// t^{j+1} Σ_i c_i t^i/(i + j + 1) by Horner's rule at both ends.
fn cubic_moments(c: &[f64; 4], t0: f64, t1: f64) -> [f64; 3] {
    let antiderivative = |t: f64, j: usize| {
        let k = j as f64;
        let inner = c[0] / (k + 1.0)
            + t * (c[1] / (k + 2.0) + t * (c[2] / (k + 3.0) + t * (c[3] / (k + 4.0))));
        let mut power = t;
        for _ in 0..j {
            power *= t;
        }
        power * inner
    };
    std::array::from_fn(|j| antiderivative(t1, j) - antiderivative(t0, j))
}

/// ∫ t^j max(0, p(t)) dt over [t0, t1] (j = 0, 1, 2) for the cubic `c`: the interval is cut
/// at p's critical points (the roots of p', where p turns), so that p is monotone on each piece
/// and has at most one root there, found by Newton's method kept in its bracket to 1e−13;
/// the positive parts are
/// integrated exactly. No root is missed, so the result is continuous in the coefficients.
fn positive_moments(c: &[f64; 4], t0: f64, t1: f64) -> [f64; 3] {
    let mut out = [0.0; 3];
    // Critical points inside (t0, t1), ascending.
    let mut knots = [t0, t1, t1, t1];
    let mut n = 1;
    let (a, b, cc) = (3.0 * c[3], 2.0 * c[2], c[1]);
    let mut roots = [f64::NAN; 2];
    if a != 0.0 {
        let disc = b * b - 4.0 * a * cc;
        if disc >= 0.0 {
            let r = disc.sqrt();
            // Cancellation-free roots of a t² + b t + c.
            let q = -0.5 * (b + b.signum() * r);
            roots = [q / a, if q != 0.0 { cc / q } else { f64::NAN }];
        }
    } else if b != 0.0 {
        roots[0] = -cc / b;
    }
    if roots[0] > roots[1] {
        roots.swap(0, 1);
    }
    for r in roots {
        if r > t0 && r < t1 {
            knots[n] = r;
            n += 1;
        }
    }
    knots[n] = t1;
    n += 1;
    for w in knots[..n].windows(2) {
        let (a, b) = (w[0], w[1]);
        if b.partial_cmp(&a) != Some(std::cmp::Ordering::Greater) {
            continue;
        }
        let (pa, pb) = (cubic_at(c, a), cubic_at(c, b));
        let (lo, hi) = match (pa > 0.0, pb > 0.0) {
            (false, false) => continue,
            (true, true) => (a, b),
            (positive_a, _) => {
                // One root in (a, b): p is monotone here. Newton from the bracket's secant
                // point, kept inside the bracket (bisection where it would leave it).
                let (mut x0, mut x1) = (a, b);
                let mut x = a + (b - a) * pa / (pa - pb);
                for _ in 0..60 {
                    let v = cubic_at(c, x);
                    if (v > 0.0) == positive_a {
                        x0 = x;
                    } else {
                        x1 = x;
                    }
                    let slope = c[1] + x * (2.0 * c[2] + 3.0 * c[3] * x);
                    let newton = x - v / slope;
                    let next = if newton > x0 && newton < x1 {
                        newton
                    } else {
                        0.5 * (x0 + x1)
                    };
                    let moved = (next - x).abs();
                    x = next;
                    if moved <= 1e-13 || x1 - x0 <= 1e-13 {
                        break;
                    }
                }
                let root = x;
                if positive_a {
                    (a, root)
                } else {
                    (root, b)
                }
            }
        };
        let m = cubic_moments(c, lo, hi);
        for j in 0..3 {
            out[j] += m[j];
        }
    }
    out
}

impl WheelOnRail {
    /// Mounts `rail` per `setup` and pairs it with `wheel`. `scan_step` [m] is the sampling
    /// step of the gap function; `b_min` [1/m] the floor of B.
    pub fn new(
        wheel: Profile,
        rail: &Profile,
        setup: &TrackSetup,
        scan_step: f64,
        b_min: f64,
    ) -> Result<Self, GeometryError> {
        crate::error::require_positive("scanStep", scan_step)?;
        crate::error::require_positive("bMin", b_min)?;
        if wheel.kind() != crate::geometry::profile::ProfileKind::Wheel {
            return Err(GeometryError::Profile(format!(
                "{} is not a wheel profile",
                wheel.name()
            )));
        }
        let rail = MountedRail::new(rail, setup)?;
        let flange_tip = flange_tip(&wheel);
        let flange_steepest = flange_steepest(&wheel, flange_tip);
        let wheel_convexity = wheel_convexity(&wheel, setup.wheel_radius, flange_tip);
        let wheel_lead_bound = wheel_lead_bound(&wheel, setup.wheel_radius, flange_tip);
        let (r0, r1) = rail.profile().y_range();
        let capacity = ((r1 - r0) / scan_step).ceil() as usize + 3;
        let bin = scan_step / BOUND_BINS_PER_STEP;
        let rail_bounds = HeightBounds::new(rail.profile(), bin);
        let wheel_bounds = HeightBounds::new(&wheel, bin);
        let rail_heights = rail_bounds.overall();
        Ok(Self {
            rail,
            wheel,
            setup: *setup,
            scan_step,
            b_min,
            flange_tip,
            flange_steepest,
            wheel_convexity,
            wheel_lead_bound,
            rail_bounds,
            wheel_bounds,
            rail_heights,
            samples: Vec::with_capacity(capacity),
            pieces: Vec::with_capacity(capacity),
            candidates: ContactCandidates::default(),
            candidate_minima: [0; MAX_CANDIDATES],
            ridges: [None; MAX_CANDIDATES],
            coarse: Vec::with_capacity(capacity),
            coarse_stride: COARSE_STRIDE,
            filled_level: f64::NEG_INFINITY,
            filled_span: (usize::MAX, 0),
            scan_bounds: (0.0, 0.0),
            scan_lo: 0.0,
            scan_dw: scan_step,
            pose: Prepared::default(),
        })
    }

    pub fn rail(&self) -> &MountedRail {
        &self.rail
    }
    pub fn wheel(&self) -> &Profile {
        &self.wheel
    }
    pub fn setup(&self) -> &TrackSetup {
        &self.setup
    }

    /// Rail surface in the wheelset frame at lateral `w`.
    fn rail_at(&self, w: f64, p: &Prepared) -> RailPoint {
        let origin = self.rail.origin_lateral();
        let z_centre = -self.setup.wheel_radius;
        let rail = self.rail.profile();
        let mut y_r = w + p.lateral - origin;
        let (mut z_r, mut dz_r, _) = rail.eval(y_r);
        if p.sin_roll != 0.0 {
            // Fixed point for the rail point that the rotation maps to lateral w; converges at
            // rate |tan θ · z_r'|, tiny for wheelset roll angles.
            for _ in 0..3 {
                y_r = (w - (z_r - z_centre) * p.sin_roll) / p.cos_roll + p.lateral - origin;
                (z_r, dz_r, _) = rail.eval(y_r);
            }
        }
        let y = origin + y_r - p.lateral;
        let z = -y * p.sin_roll + (z_r - z_centre) * p.cos_roll;
        // w = y cos θ + (z_r − z_c) sin θ and z = −y sin θ + (z_r − z_c) cos θ along the rail
        // (dy = dy_r, dz_r = z_r' dy_r).
        let slope = if p.sin_roll == 0.0 {
            dz_r
        } else {
            (dz_r * p.cos_roll - p.sin_roll) / (p.cos_roll + dz_r * p.sin_roll)
        };
        RailPoint {
            z,
            slope,
            y_rail: y_r,
            profile_slope: dz_r,
        }
    }

    /// Trigonometry of `pose`, and whether its yaw leaves one lowest point per lateral.
    fn prepare(&self, pose: &SidePose) -> Prepared {
        let (sin_yaw, cos_yaw) = pose.yaw.sin_cos();
        let tan_sq = (sin_yaw / cos_yaw).powi(2);
        Prepared {
            lateral: pose.lateral,
            sin_yaw,
            cos_yaw,
            sin_roll: pose.roll.sin(),
            cos_roll: pose.roll.cos(),
            roll: pose.roll,
            single_lowest_point: tan_sq * self.wheel_convexity < UNIMODAL_MARGIN,
            tan_yaw: sin_yaw / cos_yaw,
            sin_tan: sin_yaw * sin_yaw / cos_yaw,
            inv_cos: 1.0 / cos_yaw,
        }
    }

    /// Lowest point of the (yawed) wheel at lateral `w`.
    fn wheel_at(&self, w: f64, p: &Prepared) -> WheelPoint {
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
    fn lead_bracket(&self, p: &Prepared) -> f64 {
        let half_radius = 0.5 * self.setup.wheel_radius;
        if p.single_lowest_point {
            (1.5 * self.wheel_lead_bound * p.tan_yaw.abs()).min(half_radius)
        } else {
            half_radius
        }
    }

    /// A lower bound of the gap over the laterals [wa, wb] (wa < wb) at pose `p`, where the
    /// samples give the gaps `ga` and `gb` [m]: the larger of two bounds.
    ///
    /// *Heights*: the rail's lowest possible height there less the wheel's largest possible
    /// radius. Rail: `rail_at` returns a point of the rail rotated by the roll, at a rail
    /// coordinate y_r = (w − (z_r − z_c) sin θ)/cos θ + shift for some height z_r of the rail
    /// (its fixed point; y_r = w + shift without roll), so y_r lies in the range of that
    /// expression over the rail's heights; over it z = (z_r − z_c) cos θ − (y_r + origin −
    /// lateral) sin θ is at least its value at the lowest height and the extreme y_r. Wheel: the
    /// lowest point at w has z = √(r(l)² − d²) ≤ r(l) with axial coordinate l = w/cos ψ − d tan ψ
    /// and |d| within the lead bracket of `wheel_at`.
    ///
    /// *Slopes*: with the gap's slope within [m, M] over the interval, the gap lies above both
    /// lines ga + m (w − wa) and gb − M (wb − w); the lowest point of their upper envelope is the
    /// bound (ga where m ≥ 0, gb where M ≤ 0 — exact on the monotone flanks of the gap, i.e. away
    /// from its minima). The rail's slope in the wheelset frame is (z_r' cos θ − sin θ)/(cos θ +
    /// z_r' sin θ), increasing in z_r'; the yawed wheel's is (r r' cos ψ − d sin ψ)/z over the
    /// same bracket (the envelope of the lowest points). The roll's fixed point leaves each
    /// sample's rail point off its lateral by at most e0 q³/(1 − q), q = |tan θ| max|z_r'|,
    /// e0 = (z_r − z_c + w)|tan θ|; the bound gives that much margin (beyond q = 1/2, none).
    fn gap_lower_bound(&self, (wa, ga): (f64, f64), (wb, gb): (f64, f64), p: &Prepared) -> f64 {
        let r0 = self.setup.wheel_radius;
        let z_centre = -r0;
        let origin = self.rail.origin_lateral();
        let shift = p.lateral - origin;
        let (h_lo, h_hi) = self.rail_heights;
        let (y_lo, y_hi) = if p.sin_roll == 0.0 {
            (wa + shift, wb + shift)
        } else {
            let (t_a, t_b) = (
                (h_lo - z_centre) * p.sin_roll,
                (h_hi - z_centre) * p.sin_roll,
            );
            let (t_min, t_max) = (t_a.min(t_b), t_a.max(t_b));
            // Also the fixed point's start w + shift.
            (
                ((wa - t_max) / p.cos_roll + shift).min(wa + shift),
                ((wb - t_min) / p.cos_roll + shift).max(wb + shift),
            )
        };
        let (rail_lowest, _) = self.rail_bounds.range(y_lo, y_hi);
        let rail_z = (rail_lowest - z_centre) * p.cos_roll
            - (origin - p.lateral) * p.sin_roll
            - (y_lo * p.sin_roll).max(y_hi * p.sin_roll);
        let offset = self.setup.taping_line_offset();
        let tan_yaw = p.tan_yaw;
        let lead = self.lead_bracket(p);
        let (l_lo, l_hi) = if p.sin_yaw == 0.0 {
            (wa, wb)
        } else {
            let spread = lead * tan_yaw.abs();
            (wa / p.cos_yaw - spread, wb / p.cos_yaw + spread)
        };
        let (wheel_z_lo, wheel_z_hi) = self.wheel_bounds.range(l_lo - offset, l_hi - offset);
        let by_heights = rail_z - (r0 + wheel_z_hi);

        // Slopes of the rail in the wheelset frame.
        let (rs_lo, rs_hi) = self.rail_bounds.slope_range(y_lo, y_hi);
        let (rail_slope, margin) = if p.sin_roll == 0.0 {
            ((rs_lo, rs_hi), 0.0)
        } else {
            let tan_roll = p.sin_roll / p.cos_roll;
            let q = tan_roll.abs() * rs_lo.abs().max(rs_hi.abs());
            if q >= 0.5 {
                return by_heights - BOUND_ROUNDING;
            }
            let in_frame = |d: f64| (d * p.cos_roll - p.sin_roll) / (p.cos_roll + d * p.sin_roll);
            let slope = (in_frame(rs_lo), in_frame(rs_hi));
            let e0 = (h_hi - z_centre + wb.abs()) * tan_roll.abs();
            let largest = slope.0.abs().max(slope.1.abs());
            (slope, e0 * q * q * q / (1.0 - q) * (1.0 + largest))
        };
        // Slopes of the wheel's lowest points.
        let (ws_lo, ws_hi) = self.wheel_bounds.slope_range(l_lo - offset, l_hi - offset);
        let wheel_slope = if p.sin_yaw == 0.0 {
            (ws_lo, ws_hi)
        } else {
            let (r_lo, r_hi) = (r0 + wheel_z_lo, r0 + wheel_z_hi);
            let r_slope = (
                (r_lo * ws_lo).min(r_hi * ws_lo) * p.cos_yaw,
                (r_lo * ws_hi).max(r_hi * ws_hi) * p.cos_yaw,
            );
            let lead_term = lead * p.sin_yaw.abs();
            let (n_lo, n_hi) = (r_slope.0 - lead_term, r_slope.1 + lead_term);
            let z_lo = (r_lo * r_lo - lead * lead).max(0.0).sqrt();
            if z_lo <= 0.0 {
                return by_heights - BOUND_ROUNDING;
            }
            (
                (n_lo / z_lo).min(n_lo / r_hi),
                (n_hi / z_lo).max(n_hi / r_hi),
            )
        };
        let (m, big_m) = (rail_slope.0 - wheel_slope.1, rail_slope.1 - wheel_slope.0);
        let h = wb - wa;
        let by_slopes = if m >= 0.0 {
            ga
        } else if big_m <= 0.0 {
            gb
        } else {
            // Where ga + m t = gb − M (h − t).
            let t = ((ga - gb + big_m * h) / (big_m - m)).clamp(0.0, h);
            ga + m * t
        };
        by_heights.max(by_slopes - margin) - BOUND_ROUNDING
    }

    /// Computes the fine samples of every coarse interval whose gap can lie below `level` [m].
    fn fill_to(&mut self, level: f64) {
        if level <= self.filled_level {
            return;
        }
        let p = self.pose;
        let (lo, step) = (self.scan_lo, self.scan_dw);
        let mut samples = std::mem::take(&mut self.samples);
        let mut coarse = std::mem::take(&mut self.coarse);
        let mut unfilled_left = false;
        let (mut span_lo, mut span_hi) = self.filled_span;
        for c in coarse.iter_mut() {
            if c.lower >= level {
                unfilled_left |= !c.filled;
                continue;
            }
            (span_lo, span_hi) = (span_lo.min(c.first), span_hi.max(c.last));
            if c.filled {
                continue;
            }
            for (i, s) in samples
                .iter_mut()
                .enumerate()
                .take(c.last)
                .skip(c.first + 1)
            {
                *s = self.sample(lo + step * i as f64, &p);
            }
            for k in c.first..c.last {
                self.pieces[k] = Piece::of(&samples[k], &samples[k + 1], step);
            }
            c.filled = true;
        }
        let searched = self.filled_level > f64::NEG_INFINITY;
        // With every sample computed, every sample lies below the level.
        (self.filled_level, self.filled_span) = if unfilled_left {
            (level, (span_lo, span_hi))
        } else {
            (f64::INFINITY, (0, samples.len() - 1))
        };
        self.samples = samples;
        self.coarse = coarse;
        // More minima may lie below the new level (the search itself finds them once).
        if searched {
            self.find_candidates();
        }
    }

    fn sample(&self, w: f64, p: &Prepared) -> GapSample {
        let rail = self.rail_at(w, p);
        let wheel = self.wheel_at(w, p);
        GapSample {
            gap: rail.z - wheel.z,
            slope: rail.slope - wheel.slope,
            x: wheel.x,
            y_rail: rail.y_rail,
            y_wheel: wheel.y_wheel,
        }
    }

    /// Lateral range (wheelset frame) where both profiles are defined at this pose. The rail's
    /// end points are mapped through the roll rotation exactly (at the rail's ends the lever arm
    /// to the wheelset centre is ~0.5 m, so a few mrad of roll shift them by millimetres).
    fn overlap(&self, p: &Prepared) -> Option<(f64, f64)> {
        let rail = self.rail.profile();
        let (r0, r1) = rail.y_range();
        let (w0, w1) = self.wheel.y_range();
        let origin = self.rail.origin_lateral();
        let offset = self.setup.taping_line_offset();
        let z_centre = -self.setup.wheel_radius;
        let mapped = |y_r: f64| {
            (origin + y_r - p.lateral) * p.cos_roll + (rail.z(y_r) - z_centre) * p.sin_roll
        };
        let (a, b) = (mapped(r0), mapped(r1));
        // A yawed wheel's axial coordinate at lateral W is l ≈ W / cos ψ (lowest point at
        // d = 0), so the wheel profile covers W = l cos ψ.
        let (wheel_lo, wheel_hi) = ((offset + w0) * p.cos_yaw, (offset + w1) * p.cos_yaw);
        // One scan step inside both ends, so the roll fixed point never leaves the rail.
        let lo = a.min(b).max(wheel_lo) + self.scan_step;
        let hi = a.max(b).min(wheel_hi) - self.scan_step;
        (hi - lo > 2.0 * self.scan_step).then_some((lo, hi))
    }

    /// Refinement of the sampled minimum `mid` between its neighbours `lo` and `hi` (samples at
    /// the laterals `a` < `b`): the root of the gap's slope by the Illinois variant of regula
    /// falsi inside the bracket (superlinear: ~6 samples to 1e−10 m). Where the slopes do not
    /// bracket a root (a yawed wheel's lowest point jumping between two flange points makes the
    /// gap kinked) or the root found is not below the sampled minimum (a maximum between two
    /// minima), golden-section search on the gap itself.
    fn refine(
        &self,
        (a, lo): (f64, GapSample),
        (b, hi): (f64, GapSample),
        mid: GapSample,
        p: &Prepared,
    ) -> (f64, GapSample) {
        if lo.slope < 0.0 && hi.slope > 0.0 {
            let bracket = Illinois::new((a, lo.slope), (b, hi.slope));
            if let Ok((w, s, bracket)) = self.slope_root(bracket, 1.0, p) {
                return self.accept_refined(w, s, (bracket.neg.0, bracket.pos.0), mid, p);
            }
        }
        self.golden_section(a, b, p)
    }

    /// The root of the gap's slope times `sign` (±1) inside `bracket` by Illinois: the lateral,
    /// its sample and the last bracket once the step or the bracket is below 1e−10 m (the
    /// secant's error is then far smaller still: superlinear), or the last iterate if
    /// [`REFINE_STEPS`] do not get there.
    fn slope_root(
        &self,
        mut bracket: Illinois,
        sign: f64,
        p: &Prepared,
    ) -> Result<(f64, GapSample, Illinois), f64> {
        let mut w = bracket.neg.0;
        for _ in 0..REFINE_STEPS {
            let next = bracket.secant();
            let moved = (next - w).abs();
            w = next;
            let s = self.sample(w, p);
            if s.slope == 0.0 || moved < 1e-10 || bracket.width() < 1e-10 {
                return Ok((w, s, bracket));
            }
            bracket.update(w, sign * s.slope);
        }
        Err(w)
    }

    /// The slope root `w` (sample `s`) inside [a, b] if it lies below the sampled minimum `mid`,
    /// else golden-section search on [a, b].
    fn accept_refined(
        &self,
        w: f64,
        s: GapSample,
        (a, b): (f64, f64),
        mid: GapSample,
        p: &Prepared,
    ) -> (f64, GapSample) {
        if s.gap <= mid.gap {
            (w, s)
        } else {
            self.golden_section(a, b, p)
        }
    }

    /// Golden-section refinement of a sampled minimum on [a, b].
    fn golden_section(&self, a: f64, b: f64, p: &Prepared) -> (f64, GapSample) {
        self.golden_section_by(a, b, p, |g| g)
    }

    /// Golden-section search for the minimum of `key(gap)` on [a, b].
    fn golden_section_by(
        &self,
        mut a: f64,
        mut b: f64,
        p: &Prepared,
        key: impl Fn(f64) -> f64,
    ) -> (f64, GapSample) {
        const INV_PHI: f64 = 0.618_033_988_749_894_8;
        let mut c = b - INV_PHI * (b - a);
        let mut d = a + INV_PHI * (b - a);
        let mut fc = self.sample(c, p);
        let mut fd = self.sample(d, p);
        // 1e−8 m is far below every contact dimension; 40 iterations shrink 1 mm below it.
        while b - a > 1e-8 {
            if key(fc.gap) <= key(fd.gap) {
                b = d;
                d = c;
                fd = fc;
                c = b - INV_PHI * (b - a);
                fc = self.sample(c, p);
            } else {
                a = c;
                c = d;
                fc = fd;
                d = a + INV_PHI * (b - a);
                fd = self.sample(d, p);
            }
        }
        if key(fc.gap) <= key(fd.gap) {
            (c, fc)
        } else {
            (d, fd)
        }
    }

    /// The gap's local maximum inside [a, b] (a < b, around the highest sample between two
    /// minima): the root of its slope by the Illinois variant of regula falsi where the slopes
    /// at the ends bracket one (+ at a, − at b), else golden-section search on the gap.
    fn refine_ridge(&self, a: f64, b: f64, p: &Prepared) -> (f64, GapSample) {
        let (sa, sb) = (self.sample(a, p), self.sample(b, p));
        if sa.slope > 0.0 && sb.slope < 0.0 {
            // The slope decreases through the ridge: the bracket holds its negative.
            let bracket = Illinois::new((a, -sa.slope), (b, -sb.slope));
            return match self.slope_root(bracket, -1.0, p) {
                Ok((w, s, _)) => (w, s),
                Err(w) => (w, self.sample(w, p)),
            };
        }
        let (w, s) = self.golden_section_by(a, b, p, |g| -g);
        (w, s)
    }

    fn describe(&self, w: f64, s: &GapSample) -> ContactPoint {
        let (_, dz_r, d2z_r) = self.rail.profile().eval(s.y_rail);
        let (z_w, dz_w, d2z_w) = self.wheel.eval(s.y_wheel);
        let contact_angle = -dz_r.atan();
        let rolling_radius = self.setup.wheel_radius + z_w;
        let curvature = |dz: f64, d2z: f64| {
            let q = 1.0 + dz * dz;
            d2z / (q * q.sqrt())
        };
        let curv_b = (0.5 * (curvature(dz_r, d2z_r) - curvature(dz_w, d2z_w))).max(self.b_min);
        ContactPoint {
            lateral: w,
            longitudinal: s.x,
            gap: s.gap,
            y_rail: s.y_rail,
            y_wheel: s.y_wheel,
            contact_angle,
            rolling_radius,
            curv_a: 0.5 * contact_angle.cos() / rolling_radius,
            curv_b,
        }
    }

    /// The interpenetration regions of the last [`WheelOnRail::search`] when the wheel is
    /// lowered by `dz` [m] from its nominal height: maximal runs of samples with gap < dz.
    /// Each region gets its deepest point and its reference point: the force centroid of the
    /// virtual interpenetration {gap < dz − (1 − ε) depth}, ε = Kik–Piotrowski's 0.55, with
    /// their strip load ∝ ε depth − (gap − deepest gap) (Piotrowski & Kik 2008: the patch lies
    /// inside the virtual region, and a strip's load is linear in its virtual penetration — as
    /// it is for a Hertz ellipse). On a symmetric (Hertzian) gap it is the deepest point for
    /// any ε; on a near-conformal one (Manchester A-2.2, right wheel at 0.5 mm: rigid region
    /// 17 mm wide, 25 µm deep) it lands within 1 mm of CONTACT's reference point, where the
    /// rigid region's (δ − f)^{3/2} centroid was 2 mm off and the deepest point 2.8 mm. Regions
    /// are written field side first; returns how many there are (at most `out.len()`; if more
    /// exist, the deepest are kept). Computes the samples below `dz` the search has not computed
    /// yet, and the candidates among them ([`WheelOnRail::candidates`]).
    pub fn regions(&mut self, dz: f64, out: &mut [Region]) -> usize {
        self.fill_to(dz);
        let s = &self.samples;
        let mut count = 0usize;
        // Every sample below dz lies in the filled span.
        let (span_lo, span_hi) = self.filled_span;
        let mut i = span_hi + 1;
        // Walk from the field side (last sample) to the gauge side.
        while i > span_lo {
            i -= 1;
            if s[i].gap >= dz {
                continue;
            }
            let end = i;
            let mut deepest = i;
            loop {
                if s[i].gap < s[deepest].gap {
                    deepest = i;
                }
                if i == 0 || s[i - 1].gap >= dz {
                    break;
                }
                i -= 1;
            }
            let start = i;
            // The contact patch lies inside the virtual interpenetration region at ε × the
            // depth (Kik–Piotrowski's ε): its force centroid is the reference point.
            let depth = dz - s[deepest].gap;
            let cut = dz - VIRTUAL_FRACTION * depth;
            let (mut weight, mut moment) = (0.0, 0.0);
            for (k, sample) in s.iter().enumerate().take(end + 1).skip(start) {
                let virtual_depth = cut - sample.gap;
                if virtual_depth > 0.0 {
                    weight += virtual_depth;
                    moment += virtual_depth * k as f64;
                }
            }
            let centroid = if weight > 0.0 {
                moment / weight
            } else {
                deepest as f64
            };
            let region = Region {
                first: start,
                last: end,
                centroid_index: centroid,
                deepest,
                depth: dz - s[deepest].gap,
            };
            if count < out.len() {
                out[count] = region;
                count += 1;
            } else if let Some(shallowest) =
                (0..count).min_by(|&a, &b| out[a].depth.total_cmp(&out[b].depth))
            {
                if region.depth > out[shallowest].depth {
                    out.copy_within(shallowest + 1..count, shallowest);
                    out[count - 1] = region;
                }
            }
        }
        count
    }

    /// Describes the point at fractional sample index `at` (linear interpolation between the
    /// samples of the last search): lateral position, rail coordinate and the rail's contact
    /// angle and profile coordinates there.
    pub fn point_at(&self, at: f64) -> ContactPoint {
        let s = &self.samples;
        // `as usize` floors a non-negative value (and saturates below 0) without a call to
        // libm's floor, which baseline x86-64 (no SSE4.1 rounding) would need.
        let i = (at as usize).min(s.len().saturating_sub(2));
        let t = at - i as f64;
        let lerp = |a: f64, b: f64| a + (b - a) * t;
        let sample = GapSample {
            gap: lerp(s[i].gap, s[i + 1].gap),
            slope: lerp(s[i].slope, s[i + 1].slope),
            x: lerp(s[i].x, s[i + 1].x),
            y_rail: lerp(s[i].y_rail, s[i + 1].y_rail),
            y_wheel: lerp(s[i].y_wheel, s[i + 1].y_wheel),
        };
        let w = self.scan_lo + self.scan_dw * at;
        self.describe(w, &sample)
    }

    /// Lateral coordinate (wheelset frame) of fractional sample index `at` of the last search [m].
    pub fn lateral_at(&self, at: f64) -> f64 {
        self.scan_lo + self.scan_dw * at
    }

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

    /// Searches the contact at `pose`: samples the gap, finds its deepest point and the contact
    /// candidates ([`WheelOnRail::candidates`]).
    ///
    /// The gap is sampled every `scan_step` over the overlap of the profiles, but lazily: every
    /// [`COARSE_STRIDE`]-th sample first, then the samples of the coarse intervals whose gap
    /// can lie (by `gap_lower_bound`) within [`INITIAL_FILL_DEPTH`] of the deepest coarse
    /// sample; [`WheelOnRail::regions`] fills further intervals when asked for a deeper level.
    /// Every sample with a gap below the filled level is the one the full scan would compute,
    /// and so are the candidates below it (the local minima; see `find_candidates`).
    pub fn search(&mut self, pose: &SidePose) -> Result<(), SearchError> {
        self.candidates.clear();
        let p = self.prepare(pose);
        self.pose = p;
        // `+ 0.0` turns −0 (a mirrored zero shift) into 0 for messages.
        let lateral = pose.lateral + 0.0;
        let (lo, hi) = self.overlap(&p).ok_or(SearchError::NoOverlap { lateral })?;
        // Samples at whole multiples of the step in the wheelset frame, whatever the overlap:
        // a sample's position does not move with the pose, so every quantity taken from the
        // samples (the candidates' brackets, the ridges, the reference points' integrals)
        // changes continuously with the pose.
        // The grid covers the overlap [lo, hi] with at most one step beyond each end (still
        // inside both profiles: `overlap` keeps a step from their ends); the overlap itself,
        // continuous in the pose, bounds what is integrated ([`WheelOnRail::scan_range`]).
        let step = self.scan_step;
        let (first_k, last_k) = ((lo / step).floor(), (hi / step).ceil());
        let n = (last_k - first_k) as usize;
        self.scan_bounds = (lo, hi);
        let lo = first_k * step;
        self.scan_lo = lo;
        self.scan_dw = step;
        let mut samples = std::mem::take(&mut self.samples);
        let mut coarse = std::mem::take(&mut self.coarse);
        samples.clear();
        samples.resize(n + 1, UNFILLED);
        coarse.clear();
        samples[0] = self.sample(lo, &p);
        let mut coarse_deepest = samples[0].gap;
        let mut first = 0;
        while first < n {
            let last = (first + self.coarse_stride).min(n);
            let (wa, wb) = (lo + step * first as f64, lo + step * last as f64);
            samples[last] = self.sample(wb, &p);
            coarse_deepest = coarse_deepest.min(samples[last].gap);
            let (ga, gb) = (samples[first].gap, samples[last].gap);
            let lower = self.gap_lower_bound((wa, ga), (wb, gb), &p).min(ga).min(gb);
            coarse.push(CoarseInterval {
                first,
                last,
                lower,
                filled: last - first <= 1,
            });
            first = last;
        }
        self.pieces.clear();
        self.pieces
            .extend(samples.windows(2).map(|w| Piece::of(&w[0], &w[1], step)));
        self.samples = samples;
        self.coarse = coarse;
        self.filled_level = f64::NEG_INFINITY;
        self.filled_span = (usize::MAX, 0);
        // Every sample below the deepest coarse one is computed: the deepest sample is exact.
        self.fill_to(coarse_deepest + INITIAL_FILL_DEPTH);

        // Deepest sample overall: at a profile end (within half a step of the overlap's
        // bounds, or beyond them) means no contact inside the profiles.
        let s = &self.samples;
        let (span_lo, span_hi) = self.filled_span;
        let deepest = (span_lo..=span_hi)
            .min_by(|&a, &b| s[a].gap.total_cmp(&s[b].gap))
            .unwrap_or(0);
        let w_deepest = lo + step * deepest as f64;
        let (bound_lo, bound_hi) = self.scan_bounds;
        if w_deepest <= bound_lo + 0.5 * step || w_deepest >= bound_hi - 0.5 * step {
            let y_rail = s[deepest].y_rail;
            return Err(SearchError::AtProfileEnd { lateral, y_rail });
        }
        let (wheel_lo, wheel_hi) = self.wheel.y_range();
        let y_wheel = s[deepest].y_wheel;
        if !(wheel_lo..=wheel_hi).contains(&y_wheel) {
            return Err(SearchError::OutsideWheel { lateral, y_wheel });
        }
        let on_flange_top = y_wheel < self.flange_steepest
            && self.wheel.dz(y_wheel).abs().atan() < FLANGE_CLIMB_ANGLE;
        if y_wheel < self.flange_tip + FLANGE_TIP_MARGIN || on_flange_top {
            return Err(SearchError::FlangeClimb { lateral, y_wheel });
        }
        self.find_candidates();
        Ok(())
    }

    /// Computes every sample (and finds every candidate and ridge) below `level` [m] (vertical
    /// gap with the wheelset at its nominal height).
    pub fn fill_to_level(&mut self, level: f64) {
        self.fill_to(level);
    }

    /// The ridges of the last search: `ridges()[k]` lies between candidates k and k + 1
    /// ([`WheelOnRail::candidates`], field side first); `None` where the gap between them rises
    /// above the filled level ([`WheelOnRail::fill_to_level`]).
    pub fn ridges(&self) -> &[Option<Ridge>] {
        &self.ridges[..self.candidates.len().saturating_sub(1)]
    }

    /// Vertical gap at lateral `w` (wheelset frame) of the last search's pose [m].
    pub fn gap_at(&self, w: f64) -> f64 {
        self.sample(w, &self.pose).gap
    }

    /// Fractional sample index of lateral `w` (wheelset frame) [-].
    fn index_of(&self, w: f64) -> f64 {
        (w - self.scan_lo) / self.scan_dw
    }

    /// [`WheelOnRail::point_at`] at lateral `w` (wheelset frame).
    pub fn point_at_lateral(&self, w: f64) -> ContactPoint {
        self.point_at(self.index_of(w).clamp(0.0, (self.samples.len() - 1) as f64))
    }

    /// Lateral range where both profiles exist at the last search's pose (wheelset frame): the
    /// bounds of every patch [m].
    pub fn scan_range(&self) -> (f64, f64) {
        self.scan_bounds
    }

    /// The first lateral between `from` and `to` (either order) where the gap rises to `level`,
    /// walking from `from` (where it lies below `level`); `to` if it stays below. Bracketed by
    /// the samples, refined on the exact gap (Illinois) to 1e−10 m, so it moves continuously with
    /// the pose and the level. `level` must not exceed the filled level.
    pub fn crossing(&self, from: f64, to: f64, level: f64) -> f64 {
        let p = &self.pose;
        let s = &self.samples;
        let last = s.len() - 1;
        let forward = to > from;
        // Samples strictly between from and to, walking outwards.
        let (i_from, i_to) = (self.index_of(from), self.index_of(to));
        let mut i = if forward {
            (i_from.floor() + 1.0).max(0.0)
        } else {
            (i_from.ceil() - 1.0).min(last as f64)
        };
        let (mut a, mut ga) = (from, self.gap_at(from) - level);
        if ga >= 0.0 {
            return from;
        }
        loop {
            let inside = if forward { i < i_to } else { i > i_to };
            if !inside || i < 0.0 || i > last as f64 {
                break;
            }
            let k = i as usize;
            let g = s[k].gap - level;
            let w = self.scan_lo + self.scan_dw * i;
            if g >= 0.0 {
                return self.level_root((a, ga), (w, self.gap_at(w) - level), level);
            }
            (a, ga) = (w, g);
            i += if forward { 1.0 } else { -1.0 };
        }
        let gt = self.gap_at(to) - level;
        if gt >= 0.0 {
            self.level_root((a, ga), (to, gt), level)
        } else {
            let _ = p;
            to
        }
    }

    /// Root of gap(w) − `level` between the lateral `below` and the lateral `at_or_above` (each
    /// with its gap − level) by Illinois to 1e−10 m.
    fn level_root(&self, below: (f64, f64), at_or_above: (f64, f64), level: f64) -> f64 {
        let mut bracket = Illinois::new(below, at_or_above);
        let mut w = at_or_above.0;
        for _ in 0..60 {
            if bracket.width() < 1e-10 || bracket.pos.1 == 0.0 {
                return bracket.pos.0;
            }
            w = bracket.inside_or_midpoint(bracket.secant());
            bracket.update(w, self.gap_at(w) - level);
        }
        w
    }

    /// Moments of the interpenetration below `level` over the laterals [lo, hi] (wheelset
    /// frame): with the depth d(w) = max(0, level − gap(w)), its integral, the d-weighted mean
    /// lateral and the d-weighted variance of the lateral ([`DepthMoments`]); `None` where nothing
    /// lies below the level. The gap between two samples is the cubic Hermite interpolant of the
    /// samples' gaps and slopes (fourth order: a narrow flange region a few samples wide is
    /// resolved, and a dip between two samples counts), integrated exactly between its crossings
    /// of the level. Continuous in the pose, the level and the ends. `level` must not exceed the
    /// filled level.
    pub fn depth_moments(&self, lo: f64, hi: f64, level: f64) -> Option<DepthMoments> {
        let s = &self.samples;
        let last = s.len() - 1;
        let (lo, hi) = (lo.min(hi), lo.max(hi));
        let (span_lo, span_hi) = self.filled_span;
        if span_lo > span_hi {
            return None;
        }
        let ia = self.index_of(lo).clamp(span_lo as f64, span_hi as f64);
        let ib = self.index_of(hi).clamp(span_lo as f64, span_hi as f64);
        let h = self.scan_dw;
        // Moments in the sample index t (w = scan_lo + h t); converted at the end.
        let mut sums = [0.0; 3];
        let mut k = (ia as usize).min(last.saturating_sub(1));
        while (k as f64) < ib && k < last {
            let piece = &self.pieces[k];
            let (t0, t1) = ((ia - k as f64).max(0.0), (ib - k as f64).min(1.0));
            if t1 > t0 && piece.lowest < level {
                let depth = [
                    level - piece.cubic[0],
                    -piece.cubic[1],
                    -piece.cubic[2],
                    -piece.cubic[3],
                ];
                let m = if piece.highest < level && t0 == 0.0 && t1 == 1.0 {
                    // Wholly below the level over the whole piece: ∫ tʲ (level − H) dt.
                    std::array::from_fn(|j| level / (j + 1) as f64 - piece.whole[j])
                } else if piece.highest < level {
                    cubic_moments(&depth, t0, t1)
                } else {
                    positive_moments(&depth, t0, t1)
                };
                // Shift from the piece's t to the sample index: t → k + t.
                let kf = k as f64;
                sums[0] += m[0];
                sums[1] += m[1] + kf * m[0];
                sums[2] += m[2] + 2.0 * kf * m[1] + kf * kf * m[0];
            }
            k += 1;
        }
        if sums[0].is_nan() || sums[0] <= 0.0 {
            return None;
        }
        let mean_t = sums[1] / sums[0];
        let variance_t = (sums[2] / sums[0] - mean_t * mean_t).max(0.0);
        Some(DepthMoments {
            integral: sums[0] * h,
            mean: self.scan_lo + h * mean_t,
            variance: variance_t * h * h,
        })
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

    /// The contact candidates of the last search, ordered from the field side to the gauge
    /// side: the refined local minima of the gap below the filled level (at least the deepest
    /// point; [`WheelOnRail::regions`] adds those of the deeper levels it is asked for).
    pub fn candidates(&self) -> &ContactCandidates {
        &self.candidates
    }

    /// The refined local minima of the gap below the filled level (see `candidates`) and the
    /// ridges between them.
    ///
    /// The extrema are found on the cubic Hermite interpolant of the samples' gaps and slopes
    /// (one per sample interval: the roots of its derivative), not by comparing samples: a
    /// minimum narrower than the sample spacing — one just born at a fold, where a shoulder of
    /// the gap turns into a minimum and a ridge — is found as soon as the interpolant shows it
    /// (near a fold the gap is locally cubic, which the interpolant reproduces), so that its
    /// ridge is still low when it appears and the patch groups take it in without a jump.
    /// Each minimum is then refined on the exact gap inside the stretch between its
    /// neighbouring critical points of the interpolant, and each ridge likewise.
    fn find_candidates(&mut self) {
        let s = std::mem::take(&mut self.samples);
        let n = s.len() - 1;
        let (lo, step, level, p) = (self.scan_lo, self.scan_dw, self.filled_level, self.pose);
        // Critical points of the interpolant, ascending in w (see [`Extremum`]). Minima below
        // the level lie in the filled span.
        let (span_lo, span_hi) = self.filled_span;
        let mut found = [Extremum::default(); MAX_CANDIDATES];
        let mut ridge_between = [Extremum::default(); MAX_CANDIDATES];
        let mut count = 0usize;
        let mut ridge = Extremum {
            value: f64::NEG_INFINITY,
            ..Extremum::default()
        };
        let mut unfilled_since_last = false;
        for k in span_lo..span_hi.min(n) {
            let (a, b) = (&s[k], &s[k + 1]);
            if !(a.gap.is_finite() && b.gap.is_finite()) {
                unfilled_since_last = true;
                continue;
            }
            // A sample is a ridge candidate too (the maximum between two minima may sit on a
            // sample where the interpolant's pieces meet with a kink).
            if a.gap > ridge.value && k > span_lo {
                ridge = Extremum {
                    at: k as f64,
                    value: a.gap,
                    bracket: ((k as f64 - 1.0).max(0.0), (k as f64 + 1.0).min(n as f64)),
                };
            }
            let cubic = hermite_depth(0.0, a.gap, b.gap, a.slope * step, b.slope * step);
            // The interpolant is −cubic: its derivative's roots in [0, 1).
            let (c1, c2, c3) = (-cubic[1], -cubic[2], -cubic[3]);
            let mut roots = [f64::NAN; 2];
            quadratic_roots(3.0 * c3, 2.0 * c2, c1, &mut roots);
            let valid = |t: f64| (0.0..1.0).contains(&t);
            let (r0, r1) = (roots[0], roots[1]);
            for (idx, t) in [r0, r1].into_iter().enumerate() {
                if !valid(t) {
                    continue;
                }
                let curvature = 2.0 * c2 + 6.0 * c3 * t;
                // cubic = 0 − H: the interpolant's value is −cubic(t).
                let value = -cubic_at(&cubic, t);
                let other = if idx == 0 { r1 } else { r0 };
                let (mut lo_t, mut hi_t) = (0.0, 1.0);
                if (0.0..=1.0).contains(&other) {
                    if other < t {
                        lo_t = other;
                    } else if other > t {
                        hi_t = other;
                    }
                }
                let kf = k as f64;
                let e = Extremum {
                    at: kf + t,
                    value,
                    bracket: (kf + lo_t, kf + hi_t),
                };
                if curvature < 0.0 {
                    if value > ridge.value {
                        ridge = e;
                    }
                    continue;
                }
                if !(curvature > 0.0 && value < level - MIN_PROMINENCE) {
                    continue;
                }
                if count > 0 {
                    let prev = found[count - 1];
                    let height = if unfilled_since_last {
                        f64::INFINITY
                    } else {
                        ridge.value - prev.value.max(value)
                    };
                    if height < MIN_PROMINENCE || count == MAX_CANDIDATES {
                        if value < prev.value {
                            found[count - 1] = e;
                        }
                        ridge = e;
                        unfilled_since_last = false;
                        continue;
                    }
                    ridge_between[count - 1] = if unfilled_since_last {
                        Extremum {
                            value: f64::INFINITY,
                            ..ridge
                        }
                    } else {
                        ridge
                    };
                }
                found[count] = e;
                count += 1;
                ridge = e;
                unfilled_since_last = false;
            }
        }
        let lateral = |t: f64| lo + step * t;
        // Refine and describe, field side first (largest w first); a minimum refined at a
        // lower level of this search is taken over (its samples are the same).
        let mut candidates = ContactCandidates::default();
        let mut minima = [0usize; MAX_CANDIDATES];
        for (k, e) in found[..count].iter().rev().enumerate() {
            let key = (e.at * 1024.0) as usize;
            minima[k] = key;
            let known = (0..self.candidates.len()).find(|&j| self.candidate_minima[j] == key);
            let point = match known {
                Some(j) => self.candidates.points[j],
                None => {
                    let (a, b) = (lateral(e.bracket.0), lateral(e.bracket.1));
                    let (sa, sb) = (self.sample(a, &p), self.sample(b, &p));
                    let mid = self.sample(lateral(e.at), &p);
                    let (w, refined) = self.refine((a, sa), (b, sb), mid, &p);
                    self.describe(w, &refined)
                }
            };
            candidates.push(point);
        }
        // Ridges between neighbouring candidates (field side first, as the candidates): the
        // highest critical point or sample between them refined to the gap's local maximum, or
        // none where an unfilled interval lies between them (the ridge is above the filled
        // level).
        let mut ridges = [None; MAX_CANDIDATES];
        for k in 0..count.saturating_sub(1) {
            // Candidate k (field side) is found[count − 1 − k]; the ridge before it is
            // ridge_between[count − 2 − k].
            let e = ridge_between[count - 2 - k];
            let (outer, inner) = (&candidates.points[k], &candidates.points[k + 1]);
            ridges[k] = e.value.is_finite().then(|| {
                let a = lateral(e.bracket.0).max(inner.lateral);
                let b = lateral(e.bracket.1).min(outer.lateral);
                let (w, top) = self.refine_ridge(a, b, &p);
                // A sample's gap is exact: the ridge is at least that high.
                let sampled = if e.at.fract() == 0.0 {
                    e.value
                } else {
                    f64::NEG_INFINITY
                };
                Ridge {
                    lateral: w,
                    gap: top.gap.max(sampled),
                }
            });
        }
        self.candidates = candidates;
        self.candidate_minima = minima;
        self.ridges = ridges;
        self.samples = s;
    }
}

/// A critical point of the gap's interpolant ([`WheelOnRail::find_candidates`]).
#[derive(Debug, Clone, Copy, Default)]
struct Extremum {
    /// Fractional sample index.
    at: f64,
    /// The interpolant's value there [m].
    value: f64,
    /// Fractional sample indices of the neighbouring critical points (or the interval's ends).
    bracket: (f64, f64),
}

/// Real roots of a t² + b t + c, ascending, into `out` (NaN where there are fewer than two).
fn quadratic_roots(a: f64, b: f64, c: f64, out: &mut [f64; 2]) {
    *out = [f64::NAN; 2];
    if a == 0.0 {
        if b != 0.0 {
            out[0] = -c / b;
        }
        return;
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return;
    }
    let r = disc.sqrt();
    // Cancellation-free roots.
    let q = -0.5 * (b + if b >= 0.0 { r } else { -r });
    let (x0, x1) = (q / a, if q != 0.0 { c / q } else { f64::NAN });
    *out = if x1 < x0 { [x1, x0] } else { [x0, x1] };
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s1002_on_uic60() -> WheelOnRail {
        let wheel = Profile::builtin("S1002").unwrap();
        let rail = Profile::builtin("UIC60").unwrap();
        WheelOnRail::new(
            wheel,
            &rail,
            &TrackSetup::default(),
            DEFAULT_SCAN_STEP,
            DEFAULT_B_MIN,
        )
        .unwrap()
    }

    /// The lazy scan computes what the full scan computes below every level asked for: the
    /// samples (bit for bit), the regions and the candidates, over shifts, yaw and roll
    /// (including a yaw large enough for two lowest points per lateral on the flange).
    #[test]
    fn lazy_scan_equals_the_full_scan_below_the_filled_level() {
        let mut lazy = s1002_on_uic60();
        let mut full = s1002_on_uic60();
        full.coarse_stride = 1;
        let mut poses = 0;
        let mut filled_fraction = 0.0;
        let mut crowded = 0;
        for lateral_mm in -8..=9 {
            for yaw in [0.0, 0.003, -0.003, 0.04] {
                for roll in [0.0, 0.002, -0.002] {
                    let pose = SidePose {
                        lateral: 1e-3 * lateral_mm as f64,
                        yaw,
                        roll,
                    };
                    let (a, b) = (lazy.search(&pose), full.search(&pose));
                    assert_eq!(a, b, "{pose:?}");
                    if a.is_err() {
                        continue;
                    }
                    poses += 1;
                    let touch = full.candidates().as_slice().iter().map(|c| c.gap);
                    let touch = touch.fold(f64::INFINITY, f64::min);
                    for depth in [0.0, 2e-5, 1e-4, 3e-4, 1e-3, 3e-3] {
                        let dz = touch + depth;
                        let mut ra = [Region::default(); 4];
                        let mut rb = [Region::default(); 4];
                        let na = lazy.regions(dz, &mut ra);
                        let nb = full.regions(dz, &mut rb);
                        assert_eq!(ra[..na], rb[..nb], "{pose:?} at {depth}");
                        let level = lazy.filled_level.max(dz);
                        for (i, (sa, sb)) in lazy.samples.iter().zip(&full.samples).enumerate() {
                            if sb.gap < level {
                                assert_eq!(sa.gap.to_bits(), sb.gap.to_bits(), "{pose:?} {i}");
                                assert_eq!(sa.y_rail.to_bits(), sb.y_rail.to_bits());
                            } else {
                                assert!(sa.gap >= level, "{pose:?} {i}");
                            }
                        }
                        let below = |c: &&ContactPoint| c.gap < level - MIN_PROMINENCE;
                        let from_full: Vec<_> =
                            full.candidates().as_slice().iter().filter(below).collect();
                        let from_lazy: Vec<_> = lazy.candidates().as_slice().iter().collect();
                        if full.candidates().len() < MAX_CANDIDATES {
                            assert_eq!(from_lazy, from_full, "{pose:?} at {depth}");
                        } else {
                            // The full scan ran out of candidate slots on minima high above
                            // and merged the later ones; the lazy scan keeps all below the
                            // level: it holds every one of the full scan's.
                            crowded += 1;
                            assert!(from_full.iter().all(|c| from_lazy.contains(c)), "{pose:?}");
                        }
                    }
                    let computed = lazy.samples.iter().filter(|s| s.gap.is_finite()).count();
                    filled_fraction += computed as f64 / lazy.samples.len() as f64;
                }
            }
        }
        assert!(poses > 150, "{poses}");
        eprintln!(
            "poses {poses}, crowded {crowded}, filled {}",
            filled_fraction / poses as f64
        );
        // Even 3 mm deep (every region of every load) the lazy scan skips samples.
        assert!(
            filled_fraction / (poses as f64) < 0.9,
            "{}",
            filled_fraction / poses as f64
        );
    }

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
