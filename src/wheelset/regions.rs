//! The reported patches of a wheel: one per contact region, in output slots that follow them.
//!
//! Internally a wheel's contact is described by patch groups ([`crate::geometry::groups`]):
//! runs of gap minima with continuous weights, blended where two descriptions of one region
//! meet (a minimum alone and with its neighbour). Two of them can describe one physical region
//! (a minimum's group and the merged group holding it lie at the same place), so the outputs are
//! built from the physical regions instead (docs/conventions.md, "Output slots"):
//!
//! 1. **Basins.** The search's candidates in contact at the wheel's lowering cut the wheel into
//!    basins, one per minimum, separated at the ridge between neighbours where it is submerged,
//!    else half-way between their interpenetration regions' edges. Each internal part (a
//!    weighted group's patch) is attributed to the basins its load lies in: a Hertz patch by the
//!    share of its interpenetration at the wheel's lowering over each basin, a strip patch strip
//!    by strip (a strip straddling a bound split by its lateral extent; a piece's reference
//!    point, rolling radius and angle are the part's, moved by how its strips' means differ from
//!    the part's). A part within one basin (the common case) is attributed whole.
//! 2. **Regions.** Neighbouring basins belong to one region where their interpenetration regions
//!    at the wheel's lowering touch (the ridge between them is submerged) or their loads' centres
//!    lie within [`NEAR`] of each other; they separate continuously: the combination fraction
//!    c = max(1 − S(s/[`SEPARATION`]), 1 − S((d − [`NEAR`])/[`NEAR_BLEND`])) of the edge
//!    separation s of the two interpenetration regions and the distance d of the load centres
//!    (S the smoothstep) is 1 for one region and 0 for two.
//! 3. **Merging and splitting.** Basins joined with c = 1 form one reported patch. Across a link
//!    with 0 < c < 1 the lighter patch gives the fraction c of everything it carries to the
//!    heavier one: it fades out as the regions merge, and a part splitting off starts from
//!    nothing. Where their loads lie within [`EQUAL_LOAD_BAND`] (1 − c) of each other both give,
//!    in shares that ramp smoothly with the load difference, so nothing jumps where their loads
//!    cross; the exchange depends on the pose alone, not on the steps before it.
//! 4. **Slots.** A reported patch keeps the slot whose patch of the last step lay within
//!    [`SLOT_MATCH_DISTANCE`] of its reference point (nearest first); a new one takes the first
//!    free slot, heaviest first; beyond three, the lightest are not shown (their forces are in
//!    the totals).
//!
//! A reported patch's contact angle is the direction of its normal forces' resultant; its
//! normal and creep forces the whole force of what it carries decomposed in its contact axes
//! (the reported patches' forces sum to the wheel's); its spin moment, area and frictional power
//! the sums; its peak pressure per part the largest share × piece peak, averaged over the parts
//! by normal force; its reference point, rolling radius and other figures their means weighted
//! by normal force. One part in one basin is reported as it is. The wheel's totals (force,
//! moment) are the internal parts', unchanged.

use nalgebra::Vector3;

use super::kinematics::{contact_axes, point_position};
use super::{PatchResult, Side, SideResult, WheelsetInput, MAX_PATCHES};
use crate::geometry::groups::{smoothstep, MAX_GROUPS};
use crate::geometry::search::{ContactPoint, MAX_CANDIDATES};

/// Reported patches per wheel at most: one per basin.
pub const MAX_REGIONS: usize = MAX_CANDIDATES;

/// Edge separation of two interpenetration regions below which they combine into one reported
/// patch (fully at 0, not at all from this on) [m].
pub const SEPARATION: f64 = 1e-3;

/// Distance of two basins' load centres (`yRail`) within which they are one reported patch [m].
/// While two reported patches combine partly, the heavier one's reference point moves towards
/// the lighter one's by at most half their distance; with 2 mm, no two reported patches of a
/// wheel lie closer than 1 mm.
pub const NEAR: f64 = 2e-3;

/// Beyond [`NEAR`], the distance over which two load centres separate [m].
pub const NEAR_BLEND: f64 = 1e-3;

/// Largest move of a patch's reference point (`y_rail`) between two steps for it to keep its
/// output slot [m]: 4 mm, more than a reference point moves in one communication step of any
/// vehicle run (a wheelset hunting at 5 Hz with 10 mm amplitude moves 0.3 mm per millisecond),
/// less than the distance between a tread and a flange contact (≳ 10 mm).
pub(super) const SLOT_MATCH_DISTANCE: f64 = 4e-3;

/// A reported patch in an output slot (part of the state that decides the next step's slots).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slot {
    /// The patch's reference point on the rail, `PatchResult::y_rail` [m].
    pub y_rail: f64,
    /// The internal part carrying most of its load (its traction field and strips are the
    /// slot's): an index of the step's parts.
    pub group: usize,
}

/// Pieces a wheel's parts can be cut into: every part in every basin.
const MAX_PIECES: usize = MAX_REGIONS * MAX_GROUPS;

/// Buffers of [`report`], kept with the wheel so that a step writes only what it uses (about
/// 15 kB, which clearing on every step would cost more than the rest of the report).
#[derive(Debug, Clone)]
pub(super) struct Scratch {
    pieces: [Piece; MAX_PIECES],
    /// `amount[c][i]`: the fraction of piece i that reported patch (cluster) c carries.
    amount: [[f64; MAX_PIECES]; MAX_REGIONS],
}

impl Default for Scratch {
    fn default() -> Self {
        Self {
            pieces: [Piece::default(); MAX_PIECES],
            amount: [[0.0; MAX_PIECES]; MAX_REGIONS],
        }
    }
}

/// One part's share in one basin.
#[derive(Debug, Clone, Copy, Default)]
struct Piece {
    basin: usize,
    part: usize,
    /// The share: its normal force, area, forces, moment and power are the part's (weighted)
    /// times this fraction; its other figures are its own.
    result: PatchResult,
}

/// What the strips of one part put into one basin.
#[derive(Debug, Clone, Copy, Default)]
struct StripShare {
    /// Normal force [N] and its moments: Σ N_j (sin γ_j, cos γ_j), Σ N_j yRail_j, Σ N_j r_j,
    /// Σ N_j position_j.
    normal: f64,
    direction: (f64, f64),
    y_rail: f64,
    radius: f64,
    position: Vector3<f64>,
    /// Σ share × strip area [m²] and the largest share × strip peak [Pa].
    area: f64,
    pmax: f64,
}

/// The basins of the wheel at its lowering: one per candidate (gap minimum) in contact there,
/// separated by the ridge between neighbours where it is submerged, otherwise half-way between
/// the edges of their interpenetration regions (wheelset frame; candidates field side first, so
/// the laterals descend). Only the gap below the lowering decides them, which the search has
/// sampled exactly whatever levels the step's iterations asked for: the basins of a pose do not
/// depend on the steps before it.
struct Basins {
    /// `bounds[k]`: the lateral between basin k (field side) and k + 1.
    bounds: [f64; MAX_CANDIDATES],
    /// The minima of the basins.
    minima: [ContactPoint; MAX_CANDIDATES],
    /// `separation[k]`: the distance between the edges of the interpenetration regions of basins
    /// k and k + 1 at the lowering, 0 where the ridge between them is submerged [m].
    separation: [f64; MAX_CANDIDATES],
    count: usize,
}

impl Basins {
    /// The basins of `side`'s last search at the lowering `dz`.
    fn of(side: &Side, dz: f64) -> Self {
        let geometry = &side.geometry;
        let candidates = geometry.candidates().as_slice();
        let ridges = geometry.ridges();
        let mut b = Self {
            bounds: [f64::NEG_INFINITY; MAX_CANDIDATES],
            minima: [ContactPoint::default(); MAX_CANDIDATES],
            separation: [f64::INFINITY; MAX_CANDIDATES],
            count: 0,
        };
        // The candidates in contact (the deepest at least), with their indices.
        let deepest = (0..candidates.len())
            .min_by(|&i, &j| candidates[i].gap.total_cmp(&candidates[j].gap))
            .unwrap_or(0);
        let mut index = [0usize; MAX_CANDIDATES];
        for (i, c) in candidates.iter().enumerate().take(MAX_CANDIDATES) {
            if c.gap < dz || i == deepest {
                b.minima[b.count] = *c;
                index[b.count] = i;
                b.count += 1;
            }
        }
        for k in 0..b.count.saturating_sub(1) {
            let (m, n) = (&b.minima[k], &b.minima[k + 1]);
            // The ridge between two neighbouring candidates where the search knows it.
            let ridge = (index[k + 1] == index[k] + 1)
                .then(|| ridges.get(index[k]).copied().flatten())
                .flatten();
            match ridge {
                Some(r) if r.gap < dz => {
                    b.bounds[k] = r.lateral;
                    b.separation[k] = 0.0;
                }
                Some(r) => {
                    // Each region's edge towards the ridge (found even where the ridge rises
                    // above the lowering by less than the samples show).
                    let (edge_m, edge_n) = (
                        geometry.crossing(m.lateral, r.lateral, dz),
                        geometry.crossing(n.lateral, r.lateral, dz),
                    );
                    b.bounds[k] = r.lateral;
                    b.separation[k] = (edge_m - edge_n).abs();
                }
                None => {
                    let (edge_m, edge_n) = (
                        geometry.crossing(m.lateral, n.lateral, dz),
                        geometry.crossing(n.lateral, m.lateral, dz),
                    );
                    b.bounds[k] = 0.5 * (edge_m + edge_n);
                    b.separation[k] = (edge_m - edge_n).abs();
                }
            }
        }
        b.count = b.count.max(1);
        b
    }

    /// The lateral range (low, high) of basin `k` (wheelset frame).
    fn range(&self, k: usize) -> (f64, f64) {
        let high = if k == 0 {
            f64::INFINITY
        } else {
            self.bounds[k - 1]
        };
        let low = if k + 1 < self.count {
            self.bounds[k]
        } else {
            f64::NEG_INFINITY
        };
        (low, high)
    }

    /// Share of each basin in the lateral interval [lo, hi] (by length), into `out`.
    fn interval_shares(&self, lo: f64, hi: f64, out: &mut [f64; MAX_CANDIDATES]) {
        let width = hi - lo;
        for (k, share) in out.iter_mut().enumerate().take(self.count) {
            let (a, b) = self.range(k);
            let overlap = (hi.min(b) - lo.max(a)).max(0.0);
            *share = if width > 0.0 {
                overlap / width
            } else if lo >= a && lo < b {
                1.0
            } else {
                0.0
            };
        }
    }
}

/// The sum of `items` (each a piece of `pieces` and its factor): see the module
/// documentation. The peak pressure is, per part, the largest factor × piece peak (the part's own
/// peak where all its pieces are whole), and across parts their mean weighted by normal force.
fn aggregate(sigma: f64, pieces: &[Piece], items: &[(usize, f64)]) -> PatchResult {
    let mut out = PatchResult::default();
    // The normal forces' resultant and the whole force on the wheel (−Fn e_z + Fx e_x + Fy e_y).
    let (mut normal, mut force) = (Vector3::zeros(), Vector3::zeros());
    let (mut area_adhesion, mut position) = (0.0, Vector3::zeros());
    let mut part_peak = [0.0_f64; MAX_GROUPS];
    let mut part_load = [0.0; MAX_GROUPS];
    // The largest local fatigue index of the parts that contribute.
    let mut local = f64::NEG_INFINITY;
    for &(i, f) in items {
        let (p, part) = (pieces[i].result, pieces[i].part);
        let fn_ = f * p.fn_;
        part_peak[part] = part_peak[part].max(f * p.pmax);
        part_load[part] += fn_;
        let (e_y, e_z) = contact_axes(sigma, p.contact_angle);
        normal += e_z * fn_;
        force += Vector3::new(f * p.fx, 0.0, 0.0) + e_y * (f * p.fy) - e_z * fn_;
        out.fn_ += fn_;
        out.mz += f * p.mz;
        out.area += f * p.area;
        out.frictional_power += f * p.frictional_power;
        out.t_gamma += f * p.t_gamma;
        out.wheel_wear_rate += f * p.wheel_wear_rate;
        out.rail_wear_rate += f * p.rail_wear_rate;
        if f > 0.0 {
            local = local.max(p.fatigue_index_local);
        }
        area_adhesion += f * p.area * p.adhesion_fraction;
        position += Vector3::from(p.position) * fn_;
        for (sum, v) in [
            (&mut out.y_rail, p.y_rail),
            (&mut out.rolling_radius, p.rolling_radius),
            (&mut out.max_traction, p.max_traction),
            (&mut out.penetration, p.penetration),
            (&mut out.a, p.a),
            (&mut out.b, p.b),
            (&mut out.length, p.length),
            (&mut out.width, p.width),
            (&mut out.curv_a, p.curv_a),
            (&mut out.curv_b, p.curv_b),
            (&mut out.creepage.xi, p.creepage.xi),
            (&mut out.creepage.eta, p.creepage.eta),
            (&mut out.creepage.phi, p.creepage.phi),
        ] {
            *sum += fn_ * v;
        }
    }
    if out.fn_ > 0.0 {
        let n = out.fn_;
        for v in [
            &mut out.y_rail,
            &mut out.rolling_radius,
            &mut out.max_traction,
            &mut out.penetration,
            &mut out.a,
            &mut out.b,
            &mut out.length,
            &mut out.width,
            &mut out.curv_a,
            &mut out.curv_b,
            &mut out.creepage.xi,
            &mut out.creepage.eta,
            &mut out.creepage.phi,
        ] {
            *v /= n;
        }
        out.position = (position / n).into();
        out.pmax = part_load
            .iter()
            .zip(&part_peak)
            .map(|(load, peak)| load * peak)
            .sum::<f64>()
            / n;
    }
    if out.area > 0.0 {
        out.adhesion_fraction = area_adhesion / out.area;
    }
    if local.is_finite() {
        out.fatigue_index_local = local;
    }
    // The normal forces' resultant gives the angle (e_z = (0, σ sin γ, cos γ)); the whole force
    // is decomposed in the patch's axes, so that the reported patches' forces sum to the wheel's.
    out.contact_angle = (sigma * normal.y).atan2(normal.z);
    let (e_y, e_z) = contact_axes(sigma, out.contact_angle);
    out.fn_ = -force.dot(&e_z);
    out.fx = force.x;
    out.fy = force.dot(&e_y);
    out.weight = 1.0;
    out
}

/// The pieces of the step's parts (`out.groups`), into `pieces`; returns how many.
fn pieces(
    side: &Side,
    input: &WheelsetInput,
    planar: bool,
    basins: &Basins,
    out: &SideResult,
    pieces: &mut [Piece; MAX_PIECES],
) -> usize {
    let mut count = 0;
    let mut shares = [0.0; MAX_CANDIDATES];
    for part in 0..out.n_groups {
        let result = out.groups[part];
        let strip = side
            .strip_of_group
            .get(part)
            .copied()
            .flatten()
            .and_then(|k| side.strips.as_ref()?.patches().get(k));
        let (lo, hi) = side.part_bounds[part];
        basins.interval_shares(lo.min(hi), lo.max(hi), &mut shares);
        let whole = shares[..basins.count].iter().position(|&s| s == 1.0);
        if let Some(basin) = whole.or((basins.count == 1).then_some(0)) {
            pieces[count] = Piece {
                basin,
                part,
                result,
            };
            count += 1;
            continue;
        }
        match strip {
            Some(patch) => {
                // Strip by strip: each strip's lateral extent (half-way to its neighbours).
                let n = patch.geom.len();
                let lateral = &patch.points.lateral;
                let mut acc = [StripShare::default(); MAX_CANDIDATES];
                let mut all = StripShare::default();
                for j in 0..n.min(patch.sol.n) {
                    let force = patch.sol.force[j].max(0.0);
                    // The strip's area as the patch summary counts it.
                    let area = 2.0 * patch.sol.half_length[j] * patch.geom.ds
                        + patch.sol.area_correction[j];
                    if force <= 0.0 && area <= 0.0 {
                        continue;
                    }
                    let before = if j > 0 {
                        lateral[j - 1]
                    } else {
                        2.0 * lateral[j] - lateral[(j + 1).min(n - 1)]
                    };
                    let after = if j + 1 < n {
                        lateral[j + 1]
                    } else {
                        2.0 * lateral[j] - lateral[j.saturating_sub(1)]
                    };
                    let (a, b) = (0.5 * (before + lateral[j]), 0.5 * (lateral[j] + after));
                    basins.interval_shares(a.min(b), a.max(b), &mut shares);
                    let point = ContactPoint {
                        longitudinal: patch.geom.x_c[j],
                        lateral: lateral[j],
                        rolling_radius: patch.points.rolling_radius[j],
                        ..ContactPoint::default()
                    };
                    let position = point_position(side.sigma, &point, input.yaw, input.roll);
                    let strip = |e: &mut StripShare, w: f64| {
                        let f = w * force;
                        e.normal += f;
                        e.direction.0 += f * patch.points.sin_angle[j];
                        e.direction.1 += f * patch.points.cos_angle[j];
                        e.y_rail += f * patch.points.y_rail[j];
                        e.radius += f * patch.points.rolling_radius[j];
                        e.position += position * f;
                        e.area += w * area.max(0.0);
                        e.pmax = e.pmax.max(w * patch.sol.pmax[j]);
                    };
                    strip(&mut all, 1.0);
                    for (e, &w) in acc.iter_mut().zip(&shares).take(basins.count) {
                        if w > 0.0 {
                            strip(e, w);
                        }
                    }
                }
                if all.normal <= 0.0 {
                    continue;
                }
                // Each piece: the part's figures moved by how its strips' means differ from the
                // whole part's, so that a part whose strips all lie in one basin is reported as it
                // is, and a piece changes continuously as strips cross a basin's bound.
                let mean = |e: &StripShare| {
                    (
                        e.direction.0.atan2(e.direction.1),
                        e.y_rail / e.normal,
                        e.radius / e.normal,
                        e.position / e.normal,
                    )
                };
                let (angle_all, y_all, radius_all, position_all) = mean(&all);
                for (basin, e) in acc[..basins.count].iter().enumerate() {
                    if e.normal <= 0.0 && e.area <= 0.0 {
                        continue;
                    }
                    let mut r = scaled(&result, e.normal / all.normal);
                    if e.normal > 0.0 {
                        let (angle, y, radius, position) = mean(e);
                        if !planar {
                            r.contact_angle = result.contact_angle + (angle - angle_all);
                        }
                        r.y_rail = result.y_rail + (y - y_all);
                        r.rolling_radius = result.rolling_radius + (radius - radius_all);
                        r.position =
                            (Vector3::from(result.position) + (position - position_all)).into();
                    }
                    r.area = if all.area > 0.0 {
                        result.area * e.area / all.area
                    } else {
                        0.0
                    };
                    r.pmax = e.pmax;
                    pieces[count] = Piece {
                        basin,
                        part,
                        result: r,
                    };
                    count += 1;
                }
            }
            None => {
                // A Hertz patch: by its interpenetration at the wheel's lowering per basin.
                let geometry = &side.geometry;
                let mut total = 0.0;
                let mut integral = [0.0; MAX_CANDIDATES];
                for (k, v) in integral.iter_mut().enumerate().take(basins.count) {
                    let (a, b) = basins.range(k);
                    let (a, b) = (a.max(lo.min(hi)), b.min(lo.max(hi)));
                    if b > a {
                        *v = geometry
                            .depth_moments(a, b, out.z)
                            .map_or(0.0, |m| m.integral);
                        total += *v;
                    }
                }
                let fallback = basins.count.saturating_sub(1).min(
                    (0..basins.count)
                        .find(|&k| {
                            let (a, b) = basins.range(k);
                            let w = result_lateral(side, &result);
                            w >= a && w < b
                        })
                        .unwrap_or(0),
                );
                for (basin, v) in integral[..basins.count].iter().enumerate() {
                    let share = if total > 0.0 {
                        v / total
                    } else if basin == fallback {
                        1.0
                    } else {
                        0.0
                    };
                    if share <= 0.0 {
                        continue;
                    }
                    pieces[count] = Piece {
                        basin,
                        part,
                        result: scaled(&result, share),
                    };
                    count += 1;
                }
            }
        }
    }
    count
}

/// The wheelset-frame lateral of a part's reference point (from its track-axes position).
fn result_lateral(side: &Side, r: &PatchResult) -> f64 {
    side.sigma * r.position[1]
}

/// `r` with its extensive quantities scaled by `share`.
fn scaled(r: &PatchResult, share: f64) -> PatchResult {
    PatchResult {
        fn_: r.fn_ * share,
        fx: r.fx * share,
        fy: r.fy * share,
        mz: r.mz * share,
        area: r.area * share,
        frictional_power: r.frictional_power * share,
        t_gamma: r.t_gamma * share,
        wheel_wear_rate: r.wheel_wear_rate * share,
        rail_wear_rate: r.rail_wear_rate * share,
        ..*r
    }
}

/// Fills `out.regions` from the step's parts (`out.groups`; strip patches `planar` or not) and
/// assigns the output slots (`side.slots` updated): the module documentation.
pub(super) fn report(side: &mut Side, input: &WheelsetInput, planar: bool, out: &mut SideResult) {
    out.n_regions = 0;
    out.patches = [PatchResult::default(); MAX_PATCHES];
    out.n_patches = 0;
    if out.n_groups == 0 {
        side.slots = [None; MAX_PATCHES];
        clear_tails(out);
        return;
    }
    // The gap below the lowering sampled exactly (the iterations usually have already).
    side.geometry.fill_to_level(out.z);
    let basins = Basins::of(side, out.z);
    let Some(mut scratch) = side.scratch.take() else {
        return;
    };
    let n = pieces(side, input, planar, &basins, out, &mut scratch.pieces);
    let Scratch {
        pieces: all,
        amount,
    } = &mut *scratch;
    let all = &all[..n];
    // Each basin's own load and centre.
    let mut load = [0.0; MAX_CANDIDATES];
    let mut centre = [0.0; MAX_CANDIDATES];
    for p in all {
        load[p.basin] += p.result.fn_;
        centre[p.basin] += p.result.fn_ * p.result.y_rail;
    }
    for k in 0..basins.count {
        centre[k] = if load[k] > 0.0 {
            centre[k] / load[k]
        } else {
            basins.minima[k].y_rail
        };
    }
    // Combination fractions of neighbouring basins at the wheel's lowering.
    let mut link = [0.0; MAX_CANDIDATES];
    for (k, c) in link
        .iter_mut()
        .enumerate()
        .take(basins.count.saturating_sub(1))
    {
        let separation = basins.separation[k];
        let by_edges = 1.0 - smoothstep(separation / SEPARATION);
        let distance = (centre[k] - centre[k + 1]).abs();
        let by_centres = 1.0 - smoothstep((distance - NEAR) / NEAR_BLEND);
        *c = by_edges.max(by_centres);
    }
    // Clusters: runs of basins joined fully.
    let mut cluster_of = [0usize; MAX_CANDIDATES];
    let mut clusters = 0;
    for k in 0..basins.count {
        if k > 0 && link[k - 1] < 1.0 {
            clusters += 1;
        }
        cluster_of[k] = clusters;
    }
    let clusters = clusters + 1;
    // Amount of every piece in every cluster, before the partial links' flows.
    for row in &mut amount[..clusters] {
        row[..n].fill(0.0);
    }
    let mut own_load = [0.0; MAX_REGIONS];
    for (i, p) in all.iter().enumerate() {
        let c = cluster_of[p.basin];
        amount[c][i] = 1.0;
        own_load[c] += p.result.fn_;
    }
    // Partial links, field side first: each of the two gives part of what it holds to the
    // other, the lighter (nearly) all of the fraction c.
    for k in 0..basins.count.saturating_sub(1) {
        let c = link[k];
        if !(c > 0.0 && c < 1.0) {
            continue;
        }
        let (a, b) = (cluster_of[k], cluster_of[k + 1]);
        let gives_b = lighter_gives(own_load[a], own_load[b], c);
        let (row_a, row_b) = (amount[a], amount[b]);
        for (i, (held_a, held_b)) in row_a.iter().zip(&row_b).enumerate().take(all.len()) {
            amount[a][i] = held_a * (1.0 - c * (1.0 - gives_b)) + held_b * c * gives_b;
            amount[b][i] = held_b * (1.0 - c * gives_b) + held_a * c * (1.0 - gives_b);
        }
    }
    // The reported patches.
    let mut items = [(0usize, 0.0); MAX_PIECES];
    let mut pieces_of_part = [0usize; MAX_GROUPS];
    for p in all {
        pieces_of_part[p.part] += 1;
    }
    let mut dominant = [0usize; MAX_REGIONS];
    for held in &amount[..clusters] {
        let mut m = 0;
        let mut heaviest = (0.0, 0);
        for (i, (p, &f)) in all.iter().zip(held).enumerate() {
            if f > 0.0 {
                items[m] = (i, f);
                m += 1;
                if f * p.result.fn_ >= heaviest.0 {
                    heaviest = (f * p.result.fn_, p.part);
                }
            }
        }
        if m == 0 {
            continue;
        }
        // One part whole (all its pieces, nothing moved): reported as it is.
        let part = all[items[0].0].part;
        let whole = items[..m]
            .iter()
            .all(|&(i, f)| all[i].part == part && f == 1.0)
            && m == pieces_of_part[part];
        let region = if whole {
            PatchResult {
                weight: 1.0,
                ..out.groups[part]
            }
        } else {
            aggregate(side.sigma, all, &items[..m])
        };
        if region.fn_ <= 0.0 {
            continue;
        }
        let r = out.n_regions;
        out.regions[r] = region;
        dominant[r] = heaviest.1;
        out.n_regions += 1;
    }
    // Slots: the patches matched to the last step's keep theirs, the others take free ones,
    // heaviest first.
    let previous = side.slots;
    let slot_of = match_slots(&previous, &out.regions[..out.n_regions]);
    let mut region_of_slot: [Option<usize>; MAX_PATCHES] = [None; MAX_PATCHES];
    let mut order = [0usize; MAX_REGIONS];
    for (k, o) in order.iter_mut().enumerate() {
        *o = k;
    }
    let order = &mut order[..out.n_regions];
    order.sort_by(|&a, &b| out.regions[b].fn_.total_cmp(&out.regions[a].fn_));
    let shown = &order[..out.n_regions.min(MAX_PATCHES)];
    for &r in shown.iter() {
        if let Some(s) = slot_of[r] {
            region_of_slot[s] = Some(r);
        }
    }
    for &r in shown.iter() {
        if region_of_slot.contains(&Some(r)) {
            continue;
        }
        if let Some(free) = region_of_slot.iter().position(|s| s.is_none()) {
            region_of_slot[free] = Some(r);
        }
    }
    let mut next: [Option<Slot>; MAX_PATCHES] = [None; MAX_PATCHES];
    for (slot, r) in region_of_slot.iter().enumerate() {
        let Some(r) = *r else { continue };
        next[slot] = Some(Slot {
            y_rail: out.regions[r].y_rail,
            group: dominant[r],
        });
        out.patches[slot] = out.regions[r];
        out.n_patches += 1;
    }
    side.slots = next;
    side.scratch = Some(scratch);
    clear_tails(out);
}

/// Zeroes the internal and reported patches beyond their counts (the evaluations of a step leave
/// what they do not overwrite), so that a result depends on its step alone.
fn clear_tails(out: &mut SideResult) {
    // Every written entry has a positive weight.
    for p in out.groups[out.n_groups..]
        .iter_mut()
        .chain(&mut out.regions[out.n_regions..])
    {
        if p.weight != 0.0 {
            *p = PatchResult::default();
        }
    }
}

/// Relative load difference of two partly combined patches below which both give to each other,
/// per unit of 1 − c [-]: outside this band (|F_a − F_b|/(F_a + F_b) ≥ 0.05 (1 − c)) only the
/// lighter gives. Inside it the two move towards each other; narrow, so that two reported
/// patches come within 1 mm of each other only where their loads agree to a few per cent while
/// they are all but merged.
const EQUAL_LOAD_BAND: f64 = 0.05;

/// Of the fraction c that two partly combined patches of loads `load_a`, `load_b` [N] exchange,
/// the share that b gives to a (the rest a gives to b): 1 where b is the lighter, 0 where a is,
/// a smooth ramp where their loads lie within [`EQUAL_LOAD_BAND`] (1 − c) of each other — so
/// that the exchange is continuous where their loads cross, and one-sided as c → 1, where they
/// become one patch.
fn lighter_gives(load_a: f64, load_b: f64, c: f64) -> f64 {
    let total = load_a + load_b;
    let difference = if total > 0.0 {
        (load_a - load_b) / total
    } else {
        0.0
    };
    let band = EQUAL_LOAD_BAND * (1.0 - c);
    if band > 0.0 {
        smoothstep(0.5 + difference / (2.0 * band))
    } else if difference > 0.0 {
        1.0
    } else {
        0.0
    }
}

/// For each reported patch, the slot of `previous` it keeps: pairs of reference points
/// (`y_rail`) within [`SLOT_MATCH_DISTANCE`], nearest first, each slot and patch once.
fn match_slots(
    previous: &[Option<Slot>; MAX_PATCHES],
    regions: &[PatchResult],
) -> [Option<usize>; MAX_REGIONS] {
    let mut pairs = [(f64::INFINITY, 0usize, 0usize); MAX_PATCHES * MAX_REGIONS];
    let mut count = 0;
    for (slot, old) in previous.iter().enumerate() {
        let Some(old) = old else { continue };
        for (r, region) in regions.iter().enumerate() {
            let d = (region.y_rail - old.y_rail).abs();
            if d <= SLOT_MATCH_DISTANCE {
                pairs[count] = (d, slot, r);
                count += 1;
            }
        }
    }
    let pairs = &mut pairs[..count];
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut slot_of = [None; MAX_REGIONS];
    let mut slot_taken = [false; MAX_PATCHES];
    for &(_, slot, r) in pairs.iter() {
        if slot_of[r].is_none() && !slot_taken[slot] {
            slot_of[r] = Some(slot);
            slot_taken[slot] = true;
        }
    }
    slot_of
}
