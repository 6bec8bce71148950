//! Validity of a wheelset result: is the contact state one that elastic half-space theory can
//! describe at all?
//!
//! Every normal model of this crate (Hertz, the strip models) is elastic half-space contact: it
//! assumes small strains and a patch that is small compared with the bodies' radii of curvature
//! and dimensions. A prescribed position that pushes a wheel millimetres into the rail, or an
//! absurd wheel load, still gives finite numbers — hundreds of meganewtons and tens of
//! gigapascals — that mean nothing. [`validity`] flags such states; the FMU answers them with
//! `fmi2Warning` and the message of [`Implausible::message`], the command line with its own exit
//! code (`docs/reliability.md`, "Implausible contact states"). Outputs stay finite.
//!
//! # The criterion: the normal approach of any patch of either wheel above 1 mm
//!
//! Wheel–rail approaches (`penetration`) are 10–200 µm on the tread (Hertz at 20–300 kN) and
//! 0.49–0.65 mm in flange contact at a 300 kN wheel load (the six normal models, y = −8 mm). The approach
//! measures the patch against the radii: a Hertz semi-axis is ≈ √(δ R), so at δ = 1 mm the patch
//! on the tread (built-in S1002 on UIC60) is 39 mm long and 78 mm wide, wider than the rail head
//! (72 mm) — the half-space assumption no longer holds, whatever the material. [`MAX_PENETRATION`]
//! = 1 mm is reached at a wheel load of ≈ 4 MN on the tread and ≈ 0.6–0.9 MN in flange contact,
//! beyond any real wheel load (static 50–125 kN, dynamic peaks up to ~400 kN), and by a
//! prescribed position `z` that lowers a wheel ~1 mm below the height at which it touches.
//!
//! # Why not the maximum pressure
//!
//! Real wheel–rail pressures are 0.5–3 GPa on the tread; steel is fully plastic when the mean
//! pressure reaches its hardness (≤ 4 GPa). But the elastic models legitimately compute local
//! maxima of 7–12 GPa in heavy flange contact (300–500 kN, a 4 mrad yaw; STRIPES, ANALYN and Hertz
//! alike), and a single strip of Linder's model peaked at 28 GPa in ordinary tread contact (47 kN,
//! in a random walk of the pose) where the patch as a whole is sound. A pressure limit would flag
//! states whose loads and positions are not absurd; the approach does not.

use crate::wheelset::{SideResult, Vertical, WheelsetResult};
use std::fmt;

/// Largest plausible normal approach of a patch [m].
pub const MAX_PENETRATION: f64 = 1e-3;
/// A wheel load above this [N] is named as the likely cause of an implausible state (wheel loads
/// are 20–400 kN including dynamic peaks).
const ABSURD_LOAD: f64 = 5e5;

/// The quantity that left the plausible range.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Quantity {
    /// The patch's normal approach `penetration` [m].
    Penetration,
}

impl Quantity {
    /// The FMU output's name within a patch (`penetration`).
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Penetration => "penetration",
        }
    }

    /// SI unit.
    pub fn unit(self) -> &'static str {
        match self {
            Quantity::Penetration => "m",
        }
    }

    /// The plausibility limit [SI].
    pub fn limit(self) -> f64 {
        match self {
            Quantity::Penetration => MAX_PENETRATION,
        }
    }
}

/// A patch whose state lies beyond elastic half-space contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Implausible {
    /// The wheel, "left" or "right".
    pub wheel: &'static str,
    /// The patch, 1-based (as in the outputs `left.p1` …).
    pub patch: usize,
    /// The quantity beyond its limit.
    pub quantity: Quantity,
    /// Its value [SI].
    pub value: f64,
    /// Its limit [SI].
    pub limit: f64,
}

/// The patch of `result` furthest beyond [`MAX_PENETRATION`] (left wheel first on a tie), or
/// `None` if every patch in contact is within it. Pure; no allocation.
pub fn validity(result: &WheelsetResult) -> Option<Implausible> {
    let quantity = Quantity::Penetration;
    let limit = quantity.limit();
    let mut worst: Option<Implausible> = None;
    for (wheel, side) in [("left", &result.left), ("right", &result.right)] {
        for (k, patch) in in_contact(side).enumerate() {
            let value = patch.penetration;
            // NaN compares false: a NaN value is not taken as plausible.
            if value <= limit {
                continue;
            }
            let worse = match &worst {
                None => true,
                Some(w) => value > w.value || (value.is_nan() && !w.value.is_nan()),
            };
            if worse {
                worst = Some(Implausible {
                    wheel,
                    patch: k + 1,
                    quantity,
                    value,
                    limit,
                });
            }
        }
    }
    worst
}

/// The patches of a side that are in use.
fn in_contact(side: &SideResult) -> impl Iterator<Item = &crate::wheelset::PatchResult> {
    side.all_patches().iter()
}

impl fmt::Display for Implausible {
    /// `right wheel, patch 1: penetration = 4.9800e-2 m exceeds the limit 1e-3 m of elastic
    /// half-space contact (…)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let unit = self.quantity.unit();
        write!(
            f,
            "{} wheel, patch {}: {} = {:.4e} {unit} exceeds the limit {:e} {unit} of elastic \
             half-space contact (wheel-rail approaches are 1e-5 to 2e-4 m on the tread, below \
             7e-4 m in flange contact; at 1e-3 m a patch is as wide as the rail head)",
            self.wheel,
            self.patch,
            self.quantity.name(),
            self.value,
            self.limit
        )
    }
}

impl Implausible {
    /// The likely cause, given how the wheels' heights were set.
    pub fn cause(&self, vertical: &Vertical) -> String {
        let depth_mm = self.value * 1e3;
        match *vertical {
            Vertical::Position { z } => format!(
                "the prescribed position z = {z} m (verticalMode = 2) pushes the {} wheel \
                 {depth_mm:.3} mm into the rail; lower z to within ~0.2 mm of the height at which \
                 the wheel touches, or prescribe the wheel loads (verticalMode = 1)",
                self.wheel
            ),
            Vertical::Loads { left, right } => {
                let (name, load) = if self.wheel == "left" {
                    ("Qleft", left)
                } else {
                    ("Qright", right)
                };
                if load > ABSURD_LOAD {
                    format!(
                        "the wheel load {name} = {load} N is far beyond wheel loads of \
                         2e4 to 4e5 N"
                    )
                } else {
                    format!(
                        "the {} wheel ({name} = {load} N) sinks {depth_mm:.3} mm into the rail: \
                         check Young's modulus E and the profiles (a very soft material, or a \
                         conformal or sharp profile feature)",
                        self.wheel
                    )
                }
            }
        }
    }

    /// The full message: what, the likely cause, and that the outputs are not physical.
    pub fn message(&self, vertical: &Vertical) -> String {
        format!(
            "implausible contact state: {self}; likely cause: {}. The outputs are computed but \
             are not physical",
            self.cause(vertical)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wheelset::PatchResult;

    fn patch(penetration: f64) -> PatchResult {
        PatchResult {
            penetration,
            pmax: 1.2e9,
            fn_: 1.0,
            ..PatchResult::default()
        }
    }

    fn result(left: &[PatchResult], right: &[PatchResult]) -> WheelsetResult {
        let side = |p: &[PatchResult]| {
            let mut s = SideResult {
                n_patches: p.len(),
                n_groups: p.len(),
                n_regions: p.len(),
                ..SideResult::default()
            };
            s.patches[..p.len()].copy_from_slice(p);
            s.groups[..p.len()].copy_from_slice(p);
            s.regions[..p.len()].copy_from_slice(p);
            s
        };
        WheelsetResult {
            left: side(left),
            right: side(right),
        }
    }

    /// The central case's approach (0.1 mm), a heavy flange contact's (0.65 mm) and the limit
    /// itself are plausible; just above it is not; the deepest patch wins, across wheels.
    #[test]
    fn limit_and_the_deepest_patch() {
        let ok = patch(1e-4);
        assert_eq!(validity(&result(&[ok], &[ok, patch(6.5e-4)])), None);
        let at = patch(MAX_PENETRATION);
        assert_eq!(validity(&result(&[at], &[at, ok])), None);
        let w = validity(&result(&[ok, patch(1.5e-3)], &[patch(1.2e-3)])).unwrap();
        assert_eq!(
            (w.wheel, w.patch, w.quantity),
            ("left", 2, Quantity::Penetration)
        );
        assert_eq!((w.value, w.limit), (1.5e-3, MAX_PENETRATION));
        let w = validity(&result(&[patch(1.2e-3)], &[ok, ok, patch(2e-3)])).unwrap();
        assert_eq!((w.wheel, w.patch, w.value), ("right", 3, 2e-3));
        // Patches beyond n_regions are not looked at.
        let mut r = result(&[ok], &[ok]);
        r.right.regions[2] = patch(0.05);
        assert_eq!(validity(&r), None);
        // NaN is not plausible.
        let w = validity(&result(&[patch(f64::NAN)], &[])).unwrap();
        assert!(w.value.is_nan());
    }

    /// The message names the quantity, its value, the limit and the cause.
    #[test]
    fn message_names_quantity_value_limit_and_cause() {
        let w = validity(&result(&[], &[patch(0.0498)])).unwrap();
        let m = w.message(&Vertical::Position { z: 0.05 });
        for part in [
            "right wheel, patch 1",
            "penetration = 4.9800e-2 m",
            "limit 1e-3 m",
            "z = 0.05 m (verticalMode = 2) pushes the right wheel 49.800 mm into the rail",
            "not physical",
        ] {
            assert!(m.contains(part), "{part:?} in {m}");
        }
        let m = w.message(&Vertical::Loads {
            left: 1e3,
            right: 1e7,
        });
        assert!(m.contains("Qright = 10000000 N is far beyond"), "{m}");
        let m = w.message(&Vertical::Loads {
            left: 1e7,
            right: 8e4,
        });
        assert!(
            m.contains("sinks 49.800 mm into the rail: check Young's modulus E"),
            "{m}"
        );
    }
}
