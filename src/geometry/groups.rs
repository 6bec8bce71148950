//! Which minima of a wheel's gap share a contact patch: patch groups with continuous weights.
//!
//! The vertical gap between a wheel and its rail has one or more local minima (contact
//! candidates: tread, flange root, flange), separated by ridges. At a lowering (interpenetration
//! level) L a minimum below L is in contact. Two neighbouring basins either form two patches
//! (the ridge between them stands above L) or one patch with two pressure lobes (the ridge is
//! submerged). Switching between the two descriptions makes the forces jump where the exact
//! theory's pressure moves continuously. So the choice is blended:
//!
//! * **Merge fraction of a ridge.** A ridge R joins the basin on its left, of deepest gap g_l,
//!   and the one on its right, g_r. The shallower basin lies d = L − max(g_l, g_r) below the
//!   level and the ridge e = R − max(g_l, g_r) above that basin's bottom. The ridge is submerged
//!   by the fraction u = 1 − e/d of the shallower basin's depth; t = S(u/0.8) with S the
//!   smoothstep 3v² − 2v³ on [0, 1] (t = 0 for u ≤ 0: the ridge stands above the level, two
//!   patches; t = 1 for u ≥ 0.8: the ridge is a shallow saddle inside one patch). t = 0 when the
//!   shallower basin is not below the level at all.
//! * **Basins.** The basin a ridge bounds on one side holds the minima reachable from it
//!   through lower ridges (the merge tree of the gap's sublevel sets). To stay continuous where
//!   two ridges pass each other in height, a minimum i behind higher ridges counts with its gap
//!   raised by the excess, g_i + max(0, M_i − R) (M_i the highest ridge between i and R):
//!   g_l = min over the minima on the left of that, likewise g_r. At a fold, where a minimum
//!   and its ridge merge and vanish, the neighbouring ridges' basins already hold the
//!   neighbour's minimum, and the merge fraction of the vanishing ridge is 1: nothing jumps.
//! * **Groups.** Every run of consecutive minima [first, last] is a possible patch. With the
//!   ridges merged independently with probabilities t, its weight is
//!   w = Π_inner t × (1 − t_before) × (1 − t_after): the runs of a partition all carry weight 1
//!   when every t is 0 or 1 (the common case: one group per separate patch), and in a transition
//!   the two descriptions are blended linearly. Σ over the groups that contain a minimum of
//!   their weights is 1 for every minimum.
//!
//! Every weight is a continuous function of the gaps, the ridges and the level, so a quantity
//! blended with them is continuous in the wheelset's pose wherever the per-group quantities are
//! — which the callers obtain from integrals of the interpenetration over a group's laterals,
//! never from the position of one minimum (in a conformal contact the gap is flat to a fraction
//! of a micrometre over millimetres, and its minima are round-off). Groups whose weight is below
//! [`GROUP_WEIGHT_MIN`] are dropped (their force is below that fraction of their own force).
//!
//! Known limits: the blend is a model of the transition, not a solution of it: in a transition
//! region the forces are a weighted mean of two descriptions that each hold only at its ends.

use crate::geometry::search::{ContactPoint, Ridge, WheelOnRail, MAX_CANDIDATES};

/// Most groups kept per wheel (three separate patches with one transition, or a chain of three
/// minima in transition: at most six runs carry weight).
pub const MAX_GROUPS: usize = 6;

/// Groups lighter than this are left out [-].
pub const GROUP_WEIGHT_MIN: f64 = 1e-6;

/// The smoothstep 3u² − 2u³ of u clamped to [0, 1].
pub fn smoothstep(u: f64) -> f64 {
    let u = u.clamp(0.0, 1.0);
    u * u * (3.0 - 2.0 * u)
}

/// Submerged fraction of the shallower basin's depth from which a ridge no longer separates two
/// patches (t = 1): a ridge rising less than a fifth of that depth above the basin's bottom is a
/// shallow saddle inside one patch (the exact theory's pressure passes over it), so that poses
/// near such a saddle — the benchmark's central case has one 1.8 µm high in a 75 µm deep
/// patch — are one patch, not a blend.
pub const MERGED_SUBMERGENCE: f64 = 0.8;

/// Smallest depth scale of a merge fraction where shoulders merge, as a fraction of the level's
/// depth below the deepest minimum: a ridge less than this high above a basin merges it with
/// its neighbour also where the basin lies above the level (a shoulder of the neighbour's patch
/// at the level where the merging is decided, possibly in contact at the wheel's actual
/// lowering), so that a minimum always vanishes at a fold (its ridge height → 0) as part of its
/// neighbour's group. For the multi-Hertzian patches, whose merge level is an estimate of the
/// wheel's approach; not for the strip layout, whose level lies beyond the approach (a basin
/// entering there merged at once would widen its group's strips abruptly).
pub const SHOULDER_FRACTION: f64 = 0.1;

/// Merge fraction t of a ridge at gap `ridge` (`None`: above every level considered) between
/// basins whose deepest gaps are `gap_a` and `gap_b`, at interpenetration level `level`, with
/// the deepest minimum of the wheel at `deepest` (all vertical gaps, [m]). The shallower basin's
/// depth below the level counts as at least `shoulder` (0 or [`SHOULDER_FRACTION`]) of the
/// level's depth. See the module documentation.
pub fn merge_fraction(
    level: f64,
    deepest: f64,
    gap_a: f64,
    gap_b: f64,
    ridge: Option<f64>,
    shoulder: f64,
) -> f64 {
    let Some(ridge) = ridge else {
        return 0.0;
    };
    let shallower = gap_a.max(gap_b);
    let depth = (level - shallower).max(shoulder * (level - deepest));
    if depth.is_nan() || depth <= 0.0 {
        return 0.0;
    }
    let height = (ridge - shallower).max(0.0);
    smoothstep((1.0 - height / depth) / MERGED_SUBMERGENCE)
}

/// The deepest gap of the basin on one side of ridge `r` (module documentation): the minima
/// `gaps[i]` for i in `side` (walked away from the ridge), each raised by the excess of the
/// highest ridge between it and ridge r over ridge r.
fn basin_bottom(
    gaps: &[f64],
    ridges: &[Option<f64>],
    r: usize,
    side: impl Iterator<Item = usize>,
    ridge_before: impl Fn(usize) -> Option<usize>,
) -> f64 {
    let height = |k: usize| ridges.get(k).copied().flatten().unwrap_or(f64::INFINITY);
    let own = height(r);
    let mut highest = f64::NEG_INFINITY;
    let mut bottom = f64::INFINITY;
    for i in side {
        if let Some(k) = ridge_before(i) {
            highest = highest.max(height(k));
        }
        let excess = (highest - own).max(0.0);
        if !excess.is_finite() {
            break;
        }
        bottom = bottom.min(gaps[i] + excess);
    }
    bottom
}

/// One patch group: the run of candidates `first..=last` (indices in the wheel's candidate
/// order) and its weight.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Group {
    pub first: usize,
    pub last: usize,
    /// Weight of the group's patch in the wheel's forces [-].
    pub weight: f64,
}

/// The groups of one wheel at one level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroupLayout {
    groups: [Group; MAX_GROUPS],
    len: usize,
}

impl Default for GroupLayout {
    fn default() -> Self {
        Self {
            groups: [Group::default(); MAX_GROUPS],
            len: 0,
        }
    }
}

impl GroupLayout {
    /// The groups of the candidates with vertical gaps `gaps` (in order along the wheel) and the
    /// ridges `ridges[k]` between candidates k and k + 1, merged at level `level` [m]. Only
    /// groups whose deepest member lies below `contact_level` [m] (the lowering: the others
    /// touch nothing) and whose weight reaches [`GROUP_WEIGHT_MIN`] are kept; if more than
    /// [`MAX_GROUPS`] remain, the heaviest.
    pub fn new(
        gaps: &[f64],
        ridges: &[Option<f64>],
        level: f64,
        contact_level: f64,
        shoulder: f64,
    ) -> Self {
        let m = gaps.len().min(MAX_CANDIDATES);
        let mut merge = [0.0; MAX_CANDIDATES];
        let deepest = gaps[..m].iter().copied().fold(f64::INFINITY, f64::min);
        for (r, merge_r) in merge.iter_mut().enumerate().take(m.saturating_sub(1)) {
            // Ridge r lies between minima r and r + 1; the ridge before minimum i, walking away
            // from ridge r, is i − 1 on the low side (i < r) and i on the high side (i > r + 1).
            let low = basin_bottom(gaps, ridges, r, (0..=r).rev(), |i| (i < r).then_some(i));
            let high = basin_bottom(gaps, ridges, r, r + 1..m, |i| (i > r + 1).then(|| i - 1));
            *merge_r = merge_fraction(
                level,
                deepest,
                low,
                high,
                ridges.get(r).copied().flatten(),
                shoulder,
            );
        }
        let mut layout = Self::default();
        for first in 0..m {
            let before = if first > 0 { merge[first - 1] } else { 0.0 };
            let mut inner = 1.0 - before;
            for last in first..m {
                if last > first {
                    inner *= merge[last - 1];
                }
                if inner < GROUP_WEIGHT_MIN {
                    break;
                }
                let after = if last + 1 < m { merge[last] } else { 0.0 };
                let weight = inner * (1.0 - after);
                let deepest = gaps[first..=last]
                    .iter()
                    .copied()
                    .fold(f64::INFINITY, f64::min);
                if weight < GROUP_WEIGHT_MIN || deepest.is_nan() || deepest >= contact_level {
                    continue;
                }
                layout.push(Group {
                    first,
                    last,
                    weight,
                });
            }
        }
        layout
    }

    fn push(&mut self, group: Group) {
        if self.len < MAX_GROUPS {
            self.groups[self.len] = group;
            self.len += 1;
        } else if let Some(lightest) =
            (0..self.len).min_by(|&a, &b| self.groups[a].weight.total_cmp(&self.groups[b].weight))
        {
            if group.weight > self.groups[lightest].weight {
                self.groups[lightest] = group;
            }
        }
    }

    pub fn groups(&self) -> &[Group] {
        &self.groups[..self.len]
    }
}

/// The lateral bounds (gauge side, field side; wheelset frame) of `group` among the candidates
/// `candidates` (field side first) with `ridges` between them: the ridges to the neighbouring
/// candidates outside the group (the neighbour itself where the ridge is above the filled
/// level), or the ends of the scan `scan`.
pub fn group_bounds(
    candidates: &[ContactPoint],
    ridges: &[Option<Ridge>],
    group: &Group,
    scan: (f64, f64),
) -> (f64, f64) {
    let m = candidates.len();
    let field = if group.first > 0 {
        ridges[group.first - 1].map_or(candidates[group.first - 1].lateral, |r| r.lateral)
    } else {
        scan.1
    };
    let gauge = if group.last + 1 < m {
        ridges[group.last].map_or(candidates[group.last + 1].lateral, |r| r.lateral)
    } else {
        scan.0
    };
    (gauge, field)
}

/// The patch groups of the wheel's current search merged at the level `level` and in contact
/// at the lowering `contact_level` [m], shoulders merging with `shoulder` (see
/// [`crate::geometry::groups`]), with the candidates they refer to.
pub fn groups_at(
    geometry: &mut WheelOnRail,
    level: f64,
    contact_level: f64,
    shoulder: f64,
) -> (GroupLayout, [ContactPoint; MAX_CANDIDATES], usize) {
    geometry.fill_to_level(level.max(contact_level));
    let candidates = geometry.candidates().as_slice();
    let m = candidates.len();
    let mut points = [ContactPoint::default(); MAX_CANDIDATES];
    points[..m].copy_from_slice(candidates);
    let mut gaps = [0.0; MAX_CANDIDATES];
    let mut ridge_gaps = [None; MAX_CANDIDATES];
    for k in 0..m {
        gaps[k] = points[k].gap;
    }
    for (k, r) in geometry.ridges().iter().enumerate() {
        ridge_gaps[k] = r.map(|r| r.gap);
    }
    (
        GroupLayout::new(
            &gaps[..m],
            &ridge_gaps[..m.saturating_sub(1)],
            level,
            contact_level,
            shoulder,
        ),
        points,
        m,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Weight carried by candidate `k` over all groups that contain it.
    fn coverage(layout: &GroupLayout, k: usize) -> f64 {
        layout
            .groups()
            .iter()
            .filter(|g| (g.first..=g.last).contains(&k))
            .map(|g| g.weight)
            .sum()
    }

    /// The weight of group `first..=last` (0 if absent).
    fn weight(layout: &GroupLayout, first: usize, last: usize) -> f64 {
        layout
            .groups()
            .iter()
            .find(|g| g.first == first && g.last == last)
            .map_or(0.0, |g| g.weight)
    }

    #[test]
    fn separate_and_merged_minima() {
        // Two minima 10 µm apart in depth; level 100 µm above the deeper.
        let gaps = [0.0, 10e-6];
        // Ridge above the level: two groups of weight 1.
        let split = GroupLayout::new(&gaps, &[Some(150e-6)], 100e-6, 100e-6, SHOULDER_FRACTION);
        assert_eq!(split.groups().len(), 2);
        assert!(split.groups().iter().all(|g| g.weight == 1.0));
        // No ridge left above the shallower minimum: one group.
        let merged = GroupLayout::new(&gaps, &[Some(10e-6)], 100e-6, 100e-6, SHOULDER_FRACTION);
        assert_eq!(merged.groups().len(), 1);
        let g = merged.groups()[0];
        assert_eq!((g.first, g.last, g.weight), (0, 1, 1.0));
        // Half submerged: the transition, every candidate fully covered.
        let half = GroupLayout::new(&gaps, &[Some(55e-6)], 100e-6, 100e-6, SHOULDER_FRACTION);
        assert_eq!(half.groups().len(), 3);
        for k in 0..2 {
            assert!((coverage(&half, k) - 1.0).abs() < 1e-12);
        }
        // A minimum above the level behind a high ridge merges with nothing ...
        let above = GroupLayout::new(
            &[0.0, 150e-6],
            &[Some(200e-6)],
            100e-6,
            100e-6,
            SHOULDER_FRACTION,
        );
        assert_eq!(above.groups().len(), 1);
        assert_eq!(
            merge_fraction(100e-6, 0.0, 0.0, 150e-6, Some(200e-6), SHOULDER_FRACTION),
            0.0
        );
        // ... but a shoulder (its ridge less than a tenth of the level's depth above it) belongs
        // to its neighbour: a fold leaves no separate group behind.
        assert_eq!(
            merge_fraction(
                100e-6,
                0.0,
                0.0,
                150e-6,
                Some(150e-6 + 1e-9),
                SHOULDER_FRACTION
            ),
            1.0
        );
    }

    #[test]
    fn weights_are_continuous_as_a_ridge_sinks_and_depths_cross() {
        // Sweep the ridge through the level and the depths through each other: no step in any
        // group's weight larger than the sweep's resolution allows (the smoothstep's slope is
        // at most 1.5 per unit u; 4000 steps move u by well under 1e−3 each).
        let level = 100e-6;
        let mut previous: Option<[f64; 3]> = None;
        for k in 0..=4000 {
            let x = k as f64 / 4000.0;
            let gap_b = 20e-6 * (1.0 - 2.0 * x);
            let ridge = 130e-6 * (1.0 - x) + gap_b.max(0.0) * x;
            let layout = GroupLayout::new(
                &[0.0, gap_b],
                &[Some(ridge)],
                level,
                level,
                SHOULDER_FRACTION,
            );
            let now = [
                weight(&layout, 0, 0),
                weight(&layout, 1, 1),
                weight(&layout, 0, 1),
            ];
            if let Some(p) = previous {
                for (a, b) in p.iter().zip(&now) {
                    assert!((a - b).abs() < 2e-3, "weight step at {x}: {p:?} {now:?}");
                }
            }
            previous = Some(now);
        }
    }

    #[test]
    fn a_fold_and_a_ridge_crossing_change_no_weight_abruptly() {
        let level = 100e-6;
        // Fold: minimum 1 (between 0 and 2) rises onto its ridge with minimum 0 and vanishes;
        // minimum 2 is deeper than 1. Just before the fold the three-minimum layout must give
        // the two-minimum layout's weights (groups with 0 and 1 ↔ groups with 0).
        let (g0, g1, g2, r12) = (0.0, 30e-6, 5e-6, 60e-6);
        let before = GroupLayout::new(
            &[g0, g1, g2],
            &[Some(g1 + 1e-12), Some(r12)],
            level,
            level,
            SHOULDER_FRACTION,
        );
        let after = GroupLayout::new(&[g0, g2], &[Some(r12)], level, level, SHOULDER_FRACTION);
        assert!((weight(&before, 0, 1) - weight(&after, 0, 0)).abs() < 1e-9);
        assert!((weight(&before, 0, 2) - weight(&after, 0, 1)).abs() < 1e-9);
        assert!((weight(&before, 2, 2) - weight(&after, 1, 1)).abs() < 1e-9);
        assert!(weight(&before, 1, 1) < 1e-9 && weight(&before, 1, 2) < 1e-9);
        // Ridge crossing: the two ridges of three minima pass each other in height.
        let mut previous: Option<Vec<f64>> = None;
        for k in 0..=2000 {
            let r0 = 40e-6 + 20e-6 * (k as f64 / 2000.0);
            let layout = GroupLayout::new(
                &[0.0, 20e-6, 10e-6],
                &[Some(r0), Some(50e-6)],
                level,
                level,
                SHOULDER_FRACTION,
            );
            let now: Vec<f64> = (0..3)
                .flat_map(|a| (a..3).map(move |b| (a, b)))
                .map(|(a, b)| weight(&layout, a, b))
                .collect();
            if let Some(p) = &previous {
                for (a, b) in p.iter().zip(&now) {
                    assert!((a - b).abs() < 2e-3, "step at {k}: {p:?} {now:?}");
                }
            }
            previous = Some(now);
        }
    }
}
