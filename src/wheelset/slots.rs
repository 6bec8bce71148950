//! Output slots: each patch keeps the slot it had in the last step.

use super::{PatchResult, SideResult, MAX_PATCHES};
use crate::geometry::groups::MAX_GROUPS;

/// A patch in an output slot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slot {
    /// The patch's reference point on the rail, `PatchResult::y_rail` [m].
    pub y_rail: f64,
    /// Index of the patch in `SideResult::groups`.
    pub group: usize,
}

/// Largest move of a patch's reference point (`y_rail`) between two steps for it to keep its
/// output slot [m]: 4 mm, more than a reference point moves in one communication step of any
/// vehicle run (a wheelset hunting at 5 Hz with 10 mm amplitude moves 0.3 mm per millisecond),
/// less than the distance between a tread and a flange contact (≳ 10 mm).
pub(super) const SLOT_MATCH_DISTANCE: f64 = 4e-3;

/// Fills the output slots of `out` from its patch groups, keeping each patch in the slot it had
/// in the last step (`slots`, matched by the reference point's `y_rail` within
/// [`SLOT_MATCH_DISTANCE`], nearest first); new patches take the first free slots, heaviest
/// first; where more patches carry load than there are slots, the lightest are not shown (their
/// forces are in the totals). Updates `slots`.
pub(super) fn assign_slots(slots: &mut [Option<Slot>; MAX_PATCHES], out: &mut SideResult) {
    let n = out.n_groups;
    // The heaviest patches, at most one per slot.
    let mut order = [0usize; MAX_GROUPS];
    for (k, o) in order.iter_mut().enumerate() {
        *o = k;
    }
    let order = &mut order[..n];
    order.sort_by(|&a, &b| out.groups[b].fn_.total_cmp(&out.groups[a].fn_));
    let shown = &order[..n.min(MAX_PATCHES)];
    let mut taken = [false; MAX_GROUPS];
    let mut next: [Option<Slot>; MAX_PATCHES] = [None; MAX_PATCHES];
    // Matches nearest first.
    let mut pairs = [(f64::INFINITY, 0usize, 0usize); MAX_PATCHES * MAX_PATCHES];
    let mut count = 0;
    for (slot, old) in slots.iter().enumerate() {
        let Some(old) = old else { continue };
        for &g in shown {
            let d = (out.groups[g].y_rail - old.y_rail).abs();
            if d <= SLOT_MATCH_DISTANCE {
                pairs[count] = (d, slot, g);
                count += 1;
            }
        }
    }
    let pairs = &mut pairs[..count];
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    for &(_, slot, g) in pairs.iter() {
        if next[slot].is_none() && !taken[g] {
            next[slot] = Some(Slot {
                y_rail: out.groups[g].y_rail,
                group: g,
            });
            taken[g] = true;
        }
    }
    for &g in shown {
        if taken[g] {
            continue;
        }
        if let Some(free) = next.iter().position(|s| s.is_none()) {
            next[free] = Some(Slot {
                y_rail: out.groups[g].y_rail,
                group: g,
            });
            taken[g] = true;
        }
    }
    out.patches = [PatchResult::default(); MAX_PATCHES];
    out.n_patches = 0;
    for (slot, s) in next.iter().enumerate() {
        if let Some(s) = s {
            out.patches[slot] = out.groups[s.group];
            out.n_patches += 1;
        }
    }
    *slots = next;
}
