//! Rigid contact search between one wheel and its rail for a wheelset pose.
//!
//! Method (docs/theory.md §7.6): in the side frame (see [`crate::geometry::track`]) the wheelset
//! pose is a lateral shift, a yaw angle ψ and a roll angle θ. For each lateral coordinate W across
//! the rail (measured from the wheelset centre along the wheelset's own lateral axis):
//!
//! * **roll** is applied by rotating the rail curve by −θ about the wheelset centre into the
//!   wheelset frame (a rail is a 2-D curve extruded along x, so the rotated rail is again a curve);
//! * **yaw**: a wheel of revolution seen from below has, at lateral W, its lowest point ahead of
//!   or behind the axle plane (the yaw lead/lag of the contact point; `lowest_point.rs`);
//! * the **vertical gap** g(W) = z_rail(W) − z_wheel(W) (z down) is sampled on a uniform grid and
//!   its local minima are refined by regula falsi on its slope: each separate local minimum is a
//!   potential contact point (tread, flange root, flange). Minima whose gap rises between them by
//!   less than [`MIN_PROMINENCE`] are one point.
//! * the grid is sampled **lazily**: every `COARSE_STRIDE`-th sample first, the fine samples only
//!   where a lower bound of the gap lies below the level asked for (`sampling.rs`).
//!
//! Per contact point: contact angle γ (from the rail slope; positive when the contact plane rises
//! towards the gauge side, i.e. towards the flange — the same sign on both wheels), rolling radius,
//! rail and wheel profile coordinates, and the relative curvatures
//! A = cos γ/(2r) (Meusnier, straight rail) and B = (κ_rail − κ_wheel)/2 with
//! κ = z''/(1 + z'²)^{3/2}, floored at `b_min` (CONTACT's floor 1e−4 1/mm, docs/theory.md §5.9).
//!
//! Known limits: the gap is measured vertically in the wheelset frame (δ_normal = δ_vertical·cos γ);
//! B ignores the small change of lateral curvature by yaw; straight track.
//!
//! One file per concept, each adding its `impl WheelOnRail` block:
//!
//! * `mod.rs` (this index) — the pose ([`SidePose`]), the contact point ([`ContactPoint`]), why a
//!   pose has none ([`SearchError`]), [`WheelOnRail`] with its construction, the rail point and
//!   the gap sample at a lateral, and the points of the last search;
//! * `sampling.rs` — the search itself: the lazy coarse/fine scan of the gap, its lower bounds
//!   from the profiles' heights and slopes, the filling of the fine samples below a level;
//! * `lowest_point.rs` — the yawed wheel's lowest point at a lateral;
//! * `candidates.rs` — contact candidates ([`ContactCandidates`]) and the ridges between them
//!   ([`Ridge`]): the extrema of the samples' Hermite interpolant, refined on the exact gap;
//! * `regions.rs` — interpenetration regions ([`Region`]), their edges and depth moments
//!   ([`DepthMoments`]) on the Hermite pieces;
//! * `plane.rs` — contact planes ([`ContactPlane`]), the projection of the surfaces on them and
//!   the strips' geometry ([`StripPoints`]).

mod candidates;
mod lowest_point;
mod plane;
mod regions;
mod sampling;

pub use candidates::{ContactCandidates, Ridge, MAX_CANDIDATES, MIN_PROMINENCE};
pub use plane::{ContactPlane, StripPoints, UNREACHED_GAP};
pub use regions::{DepthMoments, Region};

use crate::geometry::profile::bounds::HeightBounds;
use crate::geometry::profile::Profile;
use crate::geometry::track::{GeometryError, MountedRail, TrackSetup};
use lowest_point::{wheel_convexity, wheel_lead_bound, UNIMODAL_MARGIN};
use regions::Piece;
use sampling::{CoarseInterval, COARSE_STRIDE};

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

/// Height-bound bins per scan step (see [`HeightBounds`]): half a step, so that an interval's
/// bound is widened by at most a quarter of its width at each end.
const BOUND_BINS_PER_STEP: f64 = 2.0;

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

/// A fine sample not computed: its gap lies above the search's filled level.
const UNFILLED: GapSample = GapSample {
    gap: f64::INFINITY,
    slope: 0.0,
    x: 0.0,
    y_rail: 0.0,
    y_wheel: 0.0,
};

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
}

/// The S1002 wheel on the UIC60 rail at the default set-up (the tests' wheel).
#[cfg(test)]
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
