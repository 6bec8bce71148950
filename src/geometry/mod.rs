//! Contact geometry: profiles, the mounted track, the contact search and the patch layout.
//!
//! * [`profile`] — built-in and measured wheel and rail profiles;
//! * [`track`] — rails mounted at gauge and inclination, the wheelset's wheels;
//! * [`search`] — the gap between wheel and rail over the lateral coordinate, its minima and
//!   ridges, contact planes;
//! * [`groups`] — contact patches as weighted groups of the gap's minima;
//! * [`strips`] — a patch's undeformed geometry on lateral strips.

pub mod groups;
pub mod profile;
pub mod search;
pub mod strips;
pub mod track;
