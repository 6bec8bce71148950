//! Validity of a wheelset result: is the contact state one that elastic half-space theory can
//! describe at all?
//!
//! Every normal model of this crate (Hertz, the strip models) is elastic half-space contact: it
//! assumes small strains, a patch that is small compared with the bodies' radii of curvature, and
//! pressures the steel carries elastically. A prescribed position that pushes a wheel millimetres
//! into the rail, or an absurd wheel load, still gives finite numbers — hundreds of meganewtons
//! and tens of gigapascals — that mean nothing. [`validity`] flags such states; the FMU answers
//! them with `fmi2Warning` and the message of [`Implausible::message`], the command line with its
//! own exit code (`docs/reliability.md`, "Implausible contact states"). Outputs stay finite.
//!
//! # Limits (any patch of either wheel)
//!
//! * **Normal approach** (`penetration`) above [`MAX_PENETRATION`] = 1 mm. Wheel–rail approaches
//!   are 10–200 µm (Hertz at 20–300 kN); at 1 mm the Hertz patch on the tread (built-in S1002
//!   on UIC60) is 39 mm long and 78 mm wide, wider than the rail head (72 mm): the half-space
//!   assumption (patch ≪ radii and body dimensions) no longer holds.
//! * **Maximum pressure** (`pmax`) above [`MAX_PRESSURE`] = 10 GPa. Wheel–rail contact pressures
//!   are 0.5–3 GPa on the tread and up to ≈ 5 GPa at a loaded flange; rail and wheel steels yield
//!   in shear at pmax ≈ 1–2 GPa (first yield at ≈ 3.2 k, k the shear yield stress of 0.3–0.5 GPa)
//!   and are fully plastic when the mean pressure reaches their hardness, ≤ 4 GPa (HB 400). An
//!   elastic pressure of 10 GPa is 2.5 × the hardest rail steel's hardness: no real contact has
//!   it.
//!
//! Both limits lie a factor 3–5 above the largest values of realistic simulations, so a warning
//! means the state itself is wrong (a position or load far out of range, a profile defect), not
//! that the contact is merely severe.

use crate::wheelset::{PatchResult, SideResult, Vertical, WheelsetResult};
use std::fmt;

/// Largest plausible normal approach of a patch [m].
pub const MAX_PENETRATION: f64 = 1e-3;
/// Largest plausible maximum pressure of a patch [Pa].
pub const MAX_PRESSURE: f64 = 10e9;
/// A wheel load above this [N] is named as the likely cause of an implausible state (wheel loads
/// are 20–200 kN, dynamic peaks up to ~400 kN); below, a profile feature is the likelier cause.
const ABSURD_LOAD: f64 = 1e6;

/// The quantity that left the plausible range.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// The patch's normal approach `penetration` [m].
    Penetration,
    /// The patch's maximum pressure `pmax` [Pa].
    MaxPressure,
}

impl Quantity {
    /// The FMU output's name within a patch (`penetration`, `pmax`).
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Penetration => "penetration",
            Quantity::MaxPressure => "pmax",
        }
    }

    /// SI unit.
    pub fn unit(self) -> &'static str {
        match self {
            Quantity::Penetration => "m",
            Quantity::MaxPressure => "Pa",
        }
    }

    /// The plausibility limit [SI].
    pub fn limit(self) -> f64 {
        match self {
            Quantity::Penetration => MAX_PENETRATION,
            Quantity::MaxPressure => MAX_PRESSURE,
        }
    }

    /// The quantity of `patch` [SI].
    fn of(self, patch: &PatchResult) -> f64 {
        match self {
            Quantity::Penetration => patch.penetration,
            Quantity::MaxPressure => patch.pmax,
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
    /// The patch's normal approach [m] (for the cause).
    pub penetration: f64,
}

/// The most implausible patch of `result` (largest ratio of a quantity to its limit), or `None`
/// if every patch is within [`MAX_PENETRATION`] and [`MAX_PRESSURE`]. Pure; no allocation.
pub fn validity(result: &WheelsetResult) -> Option<Implausible> {
    let mut worst: Option<(f64, Implausible)> = None;
    for (wheel, side) in [("left", &result.left), ("right", &result.right)] {
        for (k, patch) in in_contact(side).enumerate() {
            for quantity in [Quantity::Penetration, Quantity::MaxPressure] {
                let value = quantity.of(patch);
                let limit = quantity.limit();
                // NaN compares false: a NaN value is not silently accepted as plausible.
                if value <= limit {
                    continue;
                }
                let ratio = if value.is_nan() {
                    f64::INFINITY
                } else {
                    value / limit
                };
                if worst.as_ref().is_none_or(|(r, _)| ratio > *r) {
                    worst = Some((
                        ratio,
                        Implausible {
                            wheel,
                            patch: k + 1,
                            quantity,
                            value,
                            limit,
                            penetration: patch.penetration,
                        },
                    ));
                }
            }
        }
    }
    worst.map(|(_, w)| w)
}

/// The patches of a side that are in use.
fn in_contact(side: &SideResult) -> impl Iterator<Item = &PatchResult> {
    side.patches.iter().take(side.n_patches)
}

impl fmt::Display for Implausible {
    /// `right wheel, patch 1: penetration = 0.0498 m exceeds the limit 0.001 m of elastic
    /// half-space contact`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let unit = self.quantity.unit();
        write!(
            f,
            "{} wheel, patch {}: {} = {:.4e} {unit} exceeds the limit {:e} {unit} of elastic \
             half-space contact (wheel-rail contact has approaches of 1e-5 to 2e-4 m and \
             pressures of 0.5e9 to 3e9 Pa; steel is fully plastic beyond ~4e9 Pa)",
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
        let depth_mm = self.penetration * 1e3;
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
                        "the {} wheel ({name} = {load} N) presses {depth_mm:.3} mm into the rail \
                         on a profile feature sharper than any real wheel or rail (check the \
                         profiles, or smooth them with profileSmoothing)",
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

    fn patch(penetration: f64, pmax: f64) -> PatchResult {
        PatchResult {
            penetration,
            pmax,
            fn_: 1.0,
            ..PatchResult::default()
        }
    }

    fn result(left: &[PatchResult], right: &[PatchResult]) -> WheelsetResult {
        let side = |p: &[PatchResult]| {
            let mut s = SideResult {
                n_patches: p.len(),
                ..SideResult::default()
            };
            s.patches[..p.len()].copy_from_slice(p);
            s
        };
        WheelsetResult {
            left: side(left),
            right: side(right),
        }
    }

    /// The central case's values (approach 0.1 mm, pmax 1.2 GPa) and values just at the limits
    /// are plausible; just above either limit is not; the worst ratio wins, across wheels.
    #[test]
    fn limits_and_the_worst_patch() {
        let ok = patch(1e-4, 1.2e9);
        assert_eq!(validity(&result(&[ok], &[ok])), None);
        let at = patch(MAX_PENETRATION, MAX_PRESSURE);
        assert_eq!(validity(&result(&[at], &[at, ok])), None);
        let deep = patch(1.5e-3, 2e9);
        let hard = patch(2e-4, 3e10);
        let w = validity(&result(&[ok, deep], &[hard])).unwrap();
        assert_eq!(
            (w.wheel, w.patch, w.quantity),
            ("right", 1, Quantity::MaxPressure)
        );
        assert_eq!((w.value, w.limit), (3e10, MAX_PRESSURE));
        let w = validity(&result(&[ok, deep], &[ok])).unwrap();
        assert_eq!(
            (w.wheel, w.patch, w.quantity),
            ("left", 2, Quantity::Penetration)
        );
        // Patches beyond n_patches are not looked at.
        let mut r = result(&[ok], &[ok]);
        r.right.patches[2] = deep;
        assert_eq!(validity(&r), None);
        // NaN is not plausible.
        let w = validity(&result(&[patch(f64::NAN, 1e9)], &[])).unwrap();
        assert_eq!(w.quantity, Quantity::Penetration);
    }

    /// The message names the quantity, its value, the limit and the cause.
    #[test]
    fn message_names_quantity_value_limit_and_cause() {
        let w = validity(&result(&[], &[patch(0.0498, 1.9e10)])).unwrap();
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
        assert!(m.contains("profile feature"), "{m}");
    }
}
