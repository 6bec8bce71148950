//! Equivalent conicity of the wheelset on its track (EN 15302): the rolling-radius difference
//! Δr(y) from the rigid contact search, and the equivalent conicity λ(A) by harmonic
//! linearisation and by integration of Klingel's equation.
//!
//! # Rolling-radius difference
//!
//! The rigid wheelset (both wheels of the configured profile, mounted at the flange-back
//! distance) is shifted laterally by y towards the right rail (track axes, `docs/conventions.md`)
//! on the rails of the configured profile, inclination and gauge, without yaw. At each shift the
//! roll angle θ is found at which both wheels touch their rails (their smallest vertical gaps
//! are equal: the wheelset rests on both rails; EN 15302 takes the roll into account), then
//! Δr(y) = r_right − r_left, the rolling radii at the deepest point of each wheel's gap
//! ([`crate::geometry::search`]). Positive Δr for y > 0 is restoring: the right wheel, shifted
//! towards its flange, rolls on the larger radius. Without roll (`roll = false`) each wheel
//! touches independently at θ = 0.
//!
//! A coned wheelset with cone slope tan γ on knife-edge rails gives Δr = 2 tan γ y without roll;
//! with roll, θ ≈ −Δr/(2e) moves the wheels' bottoms by r0 |θ| across the rails, as a further
//! shift, and Δr = 2 tan γ y · e/(e − r0 tan γ) to first order: 3 % more at tan γ = 0.05.
//!
//! # Equivalent conicity
//!
//! **Harmonic linearisation** (EN 15302 Annex C, the linear regression of Δr over a harmonic
//! motion y = A sin ωt; the describing function of Δr):
//!
//! λ(A) = 1/(2πA) ∫₀^{2π} Δr(A sin τ) sin τ dτ = 1/(πA²) ∫_{−A}^{A} Δr(y) y / √(A² − y²) dy,
//!
//! exact for Δr = 2λy. Δr is interpolated linearly between the computed shifts, and the
//! integral is evaluated exactly on each linear piece (antiderivatives −√(A² − y²) and
//! A²/2 asin(y/A) − y/2 √(A² − y²)), so jumps of Δr (a contact point jumping to the flange root)
//! are integrated without quadrature error.
//!
//! **Klingel integration** (EN 15302 Annex B, integration of the nonlinear differential
//! equation): the kinematic motion of the free wheelset along the track distance x,
//!
//! y′ = ψ,  ψ′ = −Δr(y)/(2 e0 r0),
//!
//! from y = A, ψ = 0, integrated (classical Runge–Kutta, 4000 steps per estimated wavelength)
//! over one full cycle; its wavelength L gives λ(A) = e0 r0 (2π/L)² (Klingel's formula
//! L = 2π √(e0 r0/λ) inverted). r0 is the mean rolling radius and e0 half the lateral distance
//! between the contact points of the centred wheelset. For a linear Δr both methods give the same
//! λ; for a nonlinear one they differ by a few per cent.
//!
//! Known limits: straight track, no yaw (EN 15302's definition), rigid contact points (no
//! elastic spreading of the contact), one amplitude measured from the start y = A (an asymmetric
//! Δr swings to a different negative amplitude).

use crate::error::{require_positive, InputError};
use crate::geometry::profile::Profile;
use crate::geometry::search::{ContactPoint, SearchError, SidePose, WheelOnRail};
use crate::geometry::track::{GeometryError, TrackSetup};
use crate::numeric::roots::Illinois;

/// Roll iteration: largest |gap difference| accepted [m] (far below any radius difference).
const ROLL_GAP_TOLERANCE: f64 = 1e-13;
/// Roll iteration: iteration limit (Illinois, [`crate::numeric::roots`], converges in ~6–10
/// steps).
const ROLL_ITERATIONS: usize = 100;
/// Runge–Kutta steps per estimated wavelength of the Klingel integration: the phase error of a
/// linear oscillator is O((ωh)⁴) ≈ 6e−12 per cycle, the error of the kinks of the interpolated
/// Δr (its slope changes once per shift step) ~1e−6 relative.
const KLINGEL_STEPS_PER_WAVELENGTH: f64 = 4000.0;
/// The Klingel integration gives up after this many estimated wavelengths without a cycle.
const KLINGEL_MAX_WAVELENGTHS: f64 = 20.0;
/// Most shifts of one Δr table.
pub const MAX_SHIFTS: usize = 100_001;

/// Default largest lateral shift of the Δr table [m].
pub const DEFAULT_Y_MAX: f64 = 0.007;
/// Default step of the Δr table [m].
pub const DEFAULT_Y_STEP: f64 = 5e-5;
/// The amplitudes EN 15302 reports by default [m].
pub const DEFAULT_AMPLITUDES: [f64; 6] = [0.001, 0.002, 0.003, 0.004, 0.005, 0.006];

/// Why a conicity calculation failed.
#[derive(Debug, Clone, PartialEq)]
pub enum ConicityError {
    /// A setting is out of range.
    Input(InputError),
    /// The profiles or the set-up are unusable.
    Geometry(GeometryError),
    /// At shift `y` one wheel has no usable rigid contact.
    NoContact {
        y: f64,
        side: &'static str,
        reason: SearchError,
    },
    /// At shift `y` no roll angle rests the wheelset on both rails.
    Roll { y: f64 },
    /// The amplitude lies outside the computed shifts.
    Amplitude { amplitude: f64, y_max: f64 },
    /// The Klingel motion at this amplitude does not oscillate (Δr not restoring).
    NoOscillation { amplitude: f64 },
    /// At shift `y` the loaded wheelset has no solution ([`RollingRadiusDifference::loaded`]).
    Loaded { y: f64, reason: String },
}

impl std::fmt::Display for ConicityError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ConicityError::Input(e) => e.fmt(f),
            ConicityError::Geometry(e) => e.fmt(f),
            ConicityError::NoContact { y, side, reason } => {
                write!(
                    f,
                    "shift y = {y} m: no contact on the {side} wheel: {reason}"
                )
            }
            ConicityError::Roll { y } => write!(
                f,
                "shift y = {y} m: no roll angle rests the wheelset on both rails"
            ),
            ConicityError::Amplitude { amplitude, y_max } => write!(
                f,
                "amplitude = {amplitude} m is outside the allowed range (0, {y_max}] m (the \
                 largest shift of the rolling-radius difference table)"
            ),
            ConicityError::Loaded { y, reason } => {
                write!(
                    f,
                    "shift y = {y} m: the loaded wheelset has no solution: {reason}"
                )
            }
            ConicityError::NoOscillation { amplitude } => write!(
                f,
                "amplitude = {amplitude} m: the kinematic motion does not oscillate (the \
                 rolling-radius difference is not restoring), so the Klingel conicity is \
                 undefined"
            ),
        }
    }
}

impl std::error::Error for ConicityError {}

impl From<InputError> for ConicityError {
    fn from(e: InputError) -> Self {
        ConicityError::Input(e)
    }
}

impl From<GeometryError> for ConicityError {
    fn from(e: GeometryError) -> Self {
        ConicityError::Geometry(e)
    }
}

/// The shifts of the Δr table and how the roll is treated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShiftGrid {
    /// Largest lateral shift [m]; the table covers [−y_max, y_max].
    pub y_max: f64,
    /// Step between shifts [m].
    pub y_step: f64,
    /// Whether the wheelset rolls to rest on both rails (EN 15302); `false`: θ = 0.
    pub roll: bool,
}

impl Default for ShiftGrid {
    fn default() -> Self {
        Self {
            y_max: DEFAULT_Y_MAX,
            y_step: DEFAULT_Y_STEP,
            roll: true,
        }
    }
}

/// The rigid contact at one lateral shift.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShiftPoint {
    /// Lateral shift towards the right rail [m].
    pub y: f64,
    /// Rolling-radius difference r_right − r_left [m].
    pub delta_r: f64,
    /// Roll angle at which both wheels touch, positive lowering the right wheel [rad].
    pub roll: f64,
    /// The contact points (each in its side frame: lateral towards its field side).
    pub right: ContactPoint,
    pub left: ContactPoint,
}

/// The rolling-radius difference Δr(y) of a wheelset on its track.
#[derive(Debug, Clone, PartialEq)]
pub struct RollingRadiusDifference {
    points: Vec<ShiftPoint>,
    grid: ShiftGrid,
    /// Mean rolling radius of the centred wheelset [m].
    r0: f64,
    /// Half the lateral distance between the contact points of the centred wheelset [m].
    e0: f64,
}

/// The equivalent conicity at one amplitude.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conicity {
    /// Amplitude of the lateral motion [m].
    pub amplitude: f64,
    /// Harmonic linearisation (EN 15302 Annex C) [-].
    pub harmonic: f64,
    /// Klingel integration (EN 15302 Annex B) [-]; `None` where the motion does not oscillate.
    pub klingel: Option<f64>,
    /// The Klingel wavelength [m]; `None` as `klingel`.
    pub wavelength: Option<f64>,
}

/// Both wheels' geometry.
struct Pair {
    right: WheelOnRail,
    left: WheelOnRail,
}

impl Pair {
    /// The deepest rigid contact of each wheel at shift `y` and roll `roll`.
    fn touch(&mut self, y: f64, roll: f64) -> Result<(ContactPoint, ContactPoint), ConicityError> {
        let right = deepest(
            &mut self.right,
            SidePose {
                lateral: y,
                yaw: 0.0,
                roll,
            },
        )
        .map_err(|reason| ConicityError::NoContact {
            y,
            side: "right",
            reason,
        })?;
        let left = deepest(
            &mut self.left,
            SidePose {
                lateral: -y,
                yaw: 0.0,
                roll: -roll,
            },
        )
        .map_err(|reason| ConicityError::NoContact {
            y,
            side: "left",
            reason,
        })?;
        Ok((right, left))
    }

    /// The roll angle at which both wheels touch at shift `y`, starting from `guess`, with the
    /// contact points: the gap difference g(θ) = gap_right − gap_left falls with θ (rolling
    /// lowers the right wheel); bracketed by steps that double, then Illinois
    /// ([`crate::numeric::roots`]).
    fn rest(
        &mut self,
        y: f64,
        guess: f64,
        half_spacing: f64,
    ) -> Result<(f64, ContactPoint, ContactPoint), ConicityError> {
        let mut eval = |theta: f64| -> Result<(f64, ContactPoint, ContactPoint), ConicityError> {
            let (r, l) = self.touch(y, theta)?;
            Ok((r.gap - l.gap, r, l))
        };
        let (g0, r0, l0) = eval(guess)?;
        if g0.abs() <= ROLL_GAP_TOLERANCE {
            return Ok((guess, r0, l0));
        }
        // dg/dθ ≈ −2e: the first step aims at the root, later ones double until g changes sign.
        let direction = g0.signum();
        let mut step = g0.abs() / (2.0 * half_spacing) + 1e-9;
        let (mut a, mut ga) = (guess, g0);
        let (b, gb) = loop {
            let theta = guess + direction * step;
            let (g, r, l) = eval(theta)?;
            if g.abs() <= ROLL_GAP_TOLERANCE {
                return Ok((theta, r, l));
            }
            if g.signum() != direction {
                break (theta, g);
            }
            (a, ga) = (theta, g);
            step *= 2.0;
            if step > 0.5 {
                return Err(ConicityError::Roll { y });
            }
        };
        // The bracket holds −g (g falls with θ): its negative end is the one with g > 0.
        let (positive, negative) = if ga > 0.0 {
            ((a, ga), (b, gb))
        } else {
            ((b, gb), (a, ga))
        };
        let mut bracket = Illinois::new((positive.0, -positive.1), (negative.0, -negative.1));
        for _ in 0..ROLL_ITERATIONS {
            let theta = bracket.inside_or_midpoint(bracket.secant());
            let (g, r, l) = eval(theta)?;
            if g.abs() <= ROLL_GAP_TOLERANCE || bracket.width() <= 1e-15 {
                return Ok((theta, r, l));
            }
            bracket.update(theta, -g);
        }
        Err(ConicityError::Roll { y })
    }
}

/// The deepest of the rigid contact candidates at `pose`.
fn deepest(geometry: &mut WheelOnRail, pose: SidePose) -> Result<ContactPoint, SearchError> {
    geometry.search(&pose)?;
    Ok(geometry
        .candidates()
        .as_slice()
        .iter()
        .copied()
        .min_by(|a, b| a.gap.total_cmp(&b.gap))
        .unwrap_or_default())
}

impl RollingRadiusDifference {
    /// Δr over `grid` for `wheel` (on both ends of the axle) on `rail` mounted per `setup`;
    /// `scan_step` [m] is the contact search's sampling step
    /// ([`crate::geometry::search::DEFAULT_SCAN_STEP`]).
    pub fn compute(
        wheel: &Profile,
        rail: &Profile,
        setup: &TrackSetup,
        scan_step: f64,
        grid: ShiftGrid,
    ) -> Result<Self, ConicityError> {
        require_positive("yMax", grid.y_max)?;
        require_positive("yStep", grid.y_step)?;
        if grid.y_max > 0.05 {
            return Err(InputError::new("yMax", grid.y_max, "(0, 0.05] m").into());
        }
        let half_count = (grid.y_max / grid.y_step * (1.0 + 1e-12)).floor();
        if 2.0 * half_count + 1.0 > MAX_SHIFTS as f64 {
            return Err(InputError::new("yStep", grid.y_step, "at most 100001 shifts").into());
        }
        let half_count = half_count as usize;
        let b_min = crate::geometry::search::DEFAULT_B_MIN;
        let mount = || WheelOnRail::new(wheel.clone(), rail, setup, scan_step, b_min);
        let mut pair = Pair {
            right: mount()?,
            left: mount()?,
        };
        let estimate = setup.taping_line_offset();
        let shift = |pair: &mut Pair, y: f64, guess: f64| -> Result<ShiftPoint, ConicityError> {
            let (roll, right, left) = if grid.roll {
                pair.rest(y, guess, estimate)?
            } else {
                let (r, l) = pair.touch(y, 0.0)?;
                (0.0, r, l)
            };
            Ok(ShiftPoint {
                y,
                delta_r: right.rolling_radius - left.rolling_radius,
                roll,
                right,
                left,
            })
        };
        // From the centre outwards, each shift starting its roll iteration at its neighbour's.
        let centre = shift(&mut pair, 0.0, 0.0)?;
        let mut points = vec![centre; 2 * half_count + 1];
        for sign in [1.0, -1.0] {
            let mut guess = centre.roll;
            for k in 1..=half_count {
                // Rounded to 1e−12 m so that the shifts print as the multiples they are.
                let y = (sign * grid.y_step * k as f64 * 1e12).round() / 1e12;
                let p = shift(&mut pair, y, guess)?;
                guess = p.roll;
                let index = if sign > 0.0 {
                    half_count + k
                } else {
                    half_count - k
                };
                points[index] = p;
            }
        }
        Ok(Self {
            points,
            grid: ShiftGrid {
                y_max: grid.y_step * half_count as f64,
                ..grid
            },
            r0: 0.5 * (centre.right.rolling_radius + centre.left.rolling_radius),
            e0: 0.5 * (centre.right.lateral + centre.left.lateral),
        })
    }

    /// Δr over `grid` of the loaded element `wheelset` (its profiles, track, normal model and
    /// settings) under the vertical load `load` [N] on each wheel at zero creepage, without roll
    /// (`grid.roll` is ignored): each wheel's rolling radius, contact angle, lateral position
    /// and rail coordinate are the normal-force-weighted means over its patches' — the rolling
    /// radius where the load is (docs/conventions.md), the radius a loaded wheel rolls on. The
    /// elastic patches smooth the rigid contact's jumps (S1002 on UIC60 1:40: 0.45 mm at
    /// y = ±0.25 mm, where the loaded wheelset runs on two patches).
    pub fn loaded(
        wheelset: &mut crate::wheelset::Wheelset,
        load: f64,
        grid: ShiftGrid,
    ) -> Result<Self, ConicityError> {
        use crate::tangential::fastsim::Creepage;
        use crate::wheelset::{Creepages, SideResult, Vertical, WheelsetInput, WheelsetResult};
        require_positive("yMax", grid.y_max)?;
        require_positive("yStep", grid.y_step)?;
        require_positive("load", load)?;
        let half_count = (grid.y_max / grid.y_step * (1.0 + 1e-12)).floor();
        if grid.y_max > 0.05 || 2.0 * half_count + 1.0 > MAX_SHIFTS as f64 {
            return Err(
                InputError::new("yMax", grid.y_max, "(0, 0.05] m, at most 100001 shifts").into(),
            );
        }
        let half_count = half_count as usize;
        let point = |side: &SideResult| {
            let patches = side.all_patches();
            let normal: f64 = patches.iter().map(|p| p.fn_).sum();
            let mean = |f: &dyn Fn(&crate::wheelset::PatchResult) -> f64| {
                patches.iter().map(|p| p.fn_ * f(p)).sum::<f64>() / normal
            };
            ContactPoint {
                lateral: mean(&|p| p.position[1].abs()),
                y_rail: mean(&|p| p.y_rail),
                contact_angle: mean(&|p| p.contact_angle),
                rolling_radius: mean(&|p| p.rolling_radius),
                ..ContactPoint::default()
            }
        };
        let mut points = Vec::with_capacity(2 * half_count + 1);
        for k in 0..=2 * half_count {
            let y = (grid.y_step * (k as f64 - half_count as f64) * 1e12).round() / 1e12;
            let input = WheelsetInput {
                y,
                yaw: 0.0,
                roll: 0.0,
                vertical: Vertical::Loads {
                    left: load,
                    right: load,
                },
                creepages: Creepages::Prescribed {
                    creepage: Creepage::default(),
                    vx: 1.0,
                },
                track: Default::default(),
            };
            let mut out = WheelsetResult::default();
            wheelset
                .solve(&input, &mut out)
                .map_err(|e| ConicityError::Loaded {
                    y,
                    reason: e.to_string(),
                })?;
            let (right, left) = (point(&out.right), point(&out.left));
            points.push(ShiftPoint {
                y,
                delta_r: right.rolling_radius - left.rolling_radius,
                roll: 0.0,
                right,
                left,
            });
        }
        let centre = points[half_count];
        Ok(Self {
            points,
            grid: ShiftGrid {
                y_max: grid.y_step * half_count as f64,
                roll: false,
                ..grid
            },
            r0: 0.5 * (centre.right.rolling_radius + centre.left.rolling_radius),
            e0: 0.5 * (centre.right.lateral + centre.left.lateral),
        })
    }

    /// The shifts, ascending in y.
    pub fn points(&self) -> &[ShiftPoint] {
        &self.points
    }

    /// The grid actually used (`y_max` a whole number of steps).
    pub fn grid(&self) -> ShiftGrid {
        self.grid
    }

    /// Mean rolling radius of the centred wheelset [m].
    pub fn r0(&self) -> f64 {
        self.r0
    }

    /// Half the lateral distance between the contact points of the centred wheelset [m].
    pub fn e0(&self) -> f64 {
        self.e0
    }

    /// Δr at shift `y`, interpolated linearly; `None` outside the table.
    pub fn at(&self, y: f64) -> Option<f64> {
        let (lo, step) = (-self.grid.y_max, self.grid.y_step);
        let u = (y - lo) / step;
        let last = self.points.len() - 1;
        if !(u >= -1e-9 && u <= last as f64 + 1e-9) {
            return None;
        }
        let i = (u.max(0.0) as usize).min(last.saturating_sub(1));
        let t = (u - i as f64).clamp(0.0, 1.0);
        let (a, b) = (
            self.points[i].delta_r,
            self.points[(i + 1).min(last)].delta_r,
        );
        Some(a + (b - a) * t)
    }

    fn check_amplitude(&self, amplitude: f64) -> Result<(), ConicityError> {
        if amplitude.is_finite() && amplitude > 0.0 && amplitude <= self.grid.y_max * (1.0 + 1e-12)
        {
            Ok(())
        } else {
            Err(ConicityError::Amplitude {
                amplitude,
                y_max: self.grid.y_max,
            })
        }
    }

    /// Equivalent conicity at `amplitude` by harmonic linearisation (module header) [-].
    pub fn harmonic(&self, amplitude: f64) -> Result<f64, ConicityError> {
        self.check_amplitude(amplitude)?;
        let a = amplitude.min(self.grid.y_max);
        let a2 = a * a;
        let root = |y: f64| (a2 - y * y).max(0.0).sqrt();
        // ∫ y/√(A²−y²) and ∫ y²/√(A²−y²).
        let first = |y: f64| -root(y);
        let second = |y: f64| 0.5 * a2 * (y / a).clamp(-1.0, 1.0).asin() - 0.5 * y * root(y);
        let mut integral = 0.0;
        for w in self.points.windows(2) {
            let (y1, y2) = (w[0].y.max(-a), w[1].y.min(a));
            if y2 <= y1 {
                continue;
            }
            let slope = (w[1].delta_r - w[0].delta_r) / (w[1].y - w[0].y);
            let offset = w[0].delta_r - slope * w[0].y;
            integral += offset * (first(y2) - first(y1)) + slope * (second(y2) - second(y1));
        }
        Ok(integral / (std::f64::consts::PI * a2))
    }

    /// Equivalent conicity at `amplitude` by integration of Klingel's equation (module header)
    /// and its wavelength [-, m].
    pub fn klingel(&self, amplitude: f64) -> Result<(f64, f64), ConicityError> {
        self.check_amplitude(amplitude)?;
        let no_oscillation = ConicityError::NoOscillation { amplitude };
        let estimate = self.harmonic(amplitude)?;
        if estimate.is_nan() || estimate <= 0.0 {
            return Err(no_oscillation);
        }
        let k = 1.0 / (2.0 * self.e0 * self.r0);
        let length = 2.0 * std::f64::consts::PI * (self.e0 * self.r0 / estimate).sqrt();
        let h = length / KLINGEL_STEPS_PER_WAVELENGTH;
        let out_of_table = ConicityError::Amplitude {
            amplitude,
            y_max: self.grid.y_max,
        };
        let accel = |y: f64| self.at(y).map(|d| -k * d).ok_or(out_of_table.clone());
        let (mut x, mut y, mut psi) = (0.0, amplitude.min(self.grid.y_max), 0.0);
        let mut lower_turn = false;
        let steps = (KLINGEL_MAX_WAVELENGTHS * KLINGEL_STEPS_PER_WAVELENGTH) as usize;
        for _ in 0..steps {
            let (k1y, k1p) = (psi, accel(y)?);
            let (k2y, k2p) = (psi + 0.5 * h * k1p, accel(y + 0.5 * h * k1y)?);
            let (k3y, k3p) = (psi + 0.5 * h * k2p, accel(y + 0.5 * h * k2y)?);
            let (k4y, k4p) = (psi + h * k3p, accel(y + h * k3y)?);
            let y_next = y + h / 6.0 * (k1y + 2.0 * k2y + 2.0 * k3y + k4y);
            let psi_next = psi + h / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p);
            // The lower turning point (ψ from − to +), then back at the top (ψ from + to −).
            if !lower_turn && psi < 0.0 && psi_next >= 0.0 {
                lower_turn = true;
            } else if lower_turn && psi > 0.0 && psi_next <= 0.0 {
                let wavelength = x + h * psi / (psi - psi_next);
                let lambda = self.e0 * self.r0 * (2.0 * std::f64::consts::PI / wavelength).powi(2);
                return Ok((lambda, wavelength));
            }
            (x, y, psi) = (x + h, y_next, psi_next);
        }
        Err(no_oscillation)
    }

    /// Both conicities at `amplitude`.
    pub fn conicity(&self, amplitude: f64) -> Result<Conicity, ConicityError> {
        let harmonic = self.harmonic(amplitude)?;
        let klingel = match self.klingel(amplitude) {
            Ok(k) => Some(k),
            Err(ConicityError::NoOscillation { .. }) => None,
            Err(e) => return Err(e),
        };
        Ok(Conicity {
            amplitude,
            harmonic,
            klingel: klingel.map(|k| k.0),
            wavelength: klingel.map(|k| k.1),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::profile::ProfileKind;

    /// Cone slope tan γ of the test wheel [-], crown radius of the test rail [m].
    const K: f64 = 0.05;
    const R: f64 = 0.05;

    /// A coned wheel, radius r0 − K·y over the running surface, with a flange (a steep
    /// parabola) beyond 30 mm on the gauge side so that the contact search sees a wheel.
    /// Interpolated exactly (no smoothing): the spline's ripple from the flange's curvature jump
    /// decays by 0.27 per 0.5 mm knot, to < 1e−10 of it 10 mm from the jump, far from the
    /// contact points (|y| < 10 mm).
    fn cone() -> Profile {
        let ys: Vec<f64> = (-120..=120).map(|i| f64::from(i) * 5e-4).collect();
        let zs: Vec<f64> = ys
            .iter()
            .map(|&y| -K * y + 20.0 * (-0.03 - y).max(0.0).powi(2))
            .collect();
        Profile::from_points("cone", ProfileKind::Wheel, &ys, &zs, 0.0).unwrap()
    }

    /// A rail head that is a circle of radius R (crown at y = 0), sampled every 0.1 mm.
    fn circular_rail() -> Profile {
        let ys: Vec<f64> = (-400..=400).map(|i| f64::from(i) * 1e-4).collect();
        let zs: Vec<f64> = ys.iter().map(|&y| R - (R * R - y * y).sqrt()).collect();
        Profile::from_points("circle", ProfileKind::Rail, &ys, &zs, 0.0).unwrap()
    }

    fn setup() -> TrackSetup {
        TrackSetup {
            rail_inclination: 0.0,
            ..TrackSetup::default()
        }
    }

    fn table(roll: bool) -> RollingRadiusDifference {
        let grid = ShiftGrid {
            y_max: 0.006,
            y_step: 1e-4,
            roll,
        };
        RollingRadiusDifference::compute(&cone(), &circular_rail(), &setup(), 5e-4, grid).unwrap()
    }

    /// Without roll a cone gives Δr = 2 K y exactly (each contact lies where the rail's slope
    /// equals the cone's, fixed on the rail, so the wheels' contact coordinates move by ∓y), and
    /// both conicities equal K. Tolerances: the mounted rail is a resampled spline
    /// ([`crate::geometry::track`]) whose slope is exact to ~1e−7, which moves a contact on the
    /// 50 mm crown by ~5e−9 m and Δr by 2 K × that = 5e−10 m (1e−9 allowed); that is 1e−5 of Δr
    /// at 1 mm (2e−5 allowed on λ, whose integration is exact for a linear Δr and, for Klingel,
    /// within 1e−8 at 4000 Runge–Kutta steps per wavelength).
    #[test]
    fn a_cone_without_roll_has_its_slope_as_conicity() {
        let t = table(false);
        for p in t.points() {
            assert!((p.delta_r - 2.0 * K * p.y).abs() < 1e-9, "{p:?}");
            assert_eq!(p.roll, 0.0);
        }
        for a in DEFAULT_AMPLITUDES {
            let c = t.conicity(a).unwrap();
            assert!((c.harmonic - K).abs() < 2e-5 * K, "{c:?}");
            let klingel = c.klingel.unwrap();
            assert!((klingel - K).abs() < 2e-5 * K, "{c:?}");
            let wavelength = 2.0 * std::f64::consts::PI * (t.e0() * t.r0() / K).sqrt();
            assert!((c.wavelength.unwrap() / wavelength - 1.0).abs() < 1e-5);
        }
        // The centred contact: the rail's slope equals the cone's at y_rail = −R K/√(1 + K²).
        let c = t.points()[t.points().len() / 2];
        let y_rail = -R * K / (1.0 + K * K).sqrt();
        assert!((c.right.y_rail - y_rail).abs() < 1e-9, "{c:?}");
        assert!((t.e0() - (setup().taping_line_offset() + (c.right.y_wheel))).abs() < 1e-12);
    }

    /// With roll, a cone on circular rails: the wheelset rests on both rails at
    /// θ = −K y/(Y − K(R + r0)), which shifts both contact points across the wheels by
    /// (R + r0) θ, so Δr = 2 K y · Y/(Y − K(R + r0)), with Y the lateral position of the crown
    /// centres. Neglected terms are O(θ²) ≈ 2e−7 relative at 6 mm (θ ≈ 4e−4 rad); the rail's
    /// representation adds 1e−9 m to Δr (previous test), 1e−5 of λ at 1 mm.
    #[test]
    fn a_cone_with_roll_follows_the_linear_roll_theory() {
        let t = table(true);
        let s = setup();
        let gauge_point = -(R * R - (R - s.gauge_depth).powi(2)).sqrt();
        let crown = 0.5 * s.track_gauge - gauge_point;
        let lever = R + s.wheel_radius;
        let lambda = K * crown / (crown - K * lever);
        for p in t.points() {
            let theta = -K * p.y / (crown - K * lever);
            assert!((p.roll - theta).abs() < 1e-5 * theta.abs() + 1e-12, "{p:?}");
            let expected = 2.0 * lambda * p.y;
            let tolerance = 1e-6 * expected.abs() + 1e-9;
            assert!((p.delta_r - expected).abs() < tolerance, "{p:?} {expected}");
        }
        for a in DEFAULT_AMPLITUDES {
            let c = t.conicity(a).unwrap();
            assert!(
                (c.harmonic / lambda - 1.0).abs() < 2e-5,
                "{c:?} vs {lambda}"
            );
            assert!((c.klingel.unwrap() / lambda - 1.0).abs() < 2e-5, "{c:?}");
        }
    }

    /// A Δr with a jump (a contact point jumping to the flange root) is integrated exactly: a
    /// step Δr = D sign(y) gives λ(A) = 2D/(πA) (the first Fourier coefficient of a square
    /// wave), up to the one step the interpolation spreads the jump over (relative error
    /// O((step/A)²)).
    #[test]
    fn harmonic_linearisation_of_a_step() {
        let step = 1e-5;
        let d = 1e-3;
        let n = 600;
        let points = (0..=2 * n)
            .map(|i| {
                let y = step * (i as f64 - n as f64);
                let mut p = ShiftPoint {
                    y,
                    delta_r: d * y.signum() * f64::from(u8::from(y != 0.0)),
                    roll: 0.0,
                    right: ContactPoint::default(),
                    left: ContactPoint::default(),
                };
                p.right.rolling_radius = 0.46;
                p
            })
            .collect();
        let t = RollingRadiusDifference {
            points,
            grid: ShiftGrid {
                y_max: step * n as f64,
                y_step: step,
                roll: false,
            },
            r0: 0.46,
            e0: 0.75,
        };
        for a in [0.001, 0.003, 0.006] {
            let exact = 2.0 * d / (std::f64::consts::PI * a);
            let lambda = t.harmonic(a).unwrap();
            assert!(
                (lambda / exact - 1.0).abs() < 1e-4,
                "{a}: {lambda} vs {exact}"
            );
        }
    }

    #[test]
    fn bad_settings_and_amplitudes_are_named() {
        let e = RollingRadiusDifference::compute(
            &cone(),
            &circular_rail(),
            &setup(),
            5e-4,
            ShiftGrid {
                y_step: -1.0,
                ..ShiftGrid::default()
            },
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "yStep = -1 is outside the allowed range > 0 (finite)"
        );
        let t = table(false);
        let e = t.harmonic(0.0065).unwrap_err();
        assert!(
            e.to_string().starts_with("amplitude = 0.0065 m is outside"),
            "{e}"
        );
        assert!(t.klingel(f64::NAN).is_err());
        assert!(t.at(0.0061).is_none() && t.at(0.006).is_some());
    }
}
