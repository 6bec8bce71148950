//! Non-elliptic patches of one wheel: strips on each patch's contact plane, a strip normal model
//! per patch, and the wheel's vertical position for a prescribed load (physics.md §5.1–§5.2).
//!
//! For a wheel lowered by dz from its nominal height:
//! 1. every interpenetration region of the rigid gap (at a generous trial lowering, so that each
//!    model's patch lies inside) becomes a patch: its contact plane is the tangent plane at the
//!    deepest contact candidate inside the region (the first-contact point, s = 0), and its
//!    strips cover the region ([`crate::contact_search::WheelOnRail::strip_geometry`]);
//! 2. the patch's normal approach is δ_p = dz cos γ_p − g_p (g_p its normal gap at nominal
//!    height) and the strip model gives its pressure; the wheel's vertical force is
//!    Σ N_p cos γ_p, γ_p the rail's angle at the patch's force centroid (its reference point,
//!    along whose normal the planar patch's force acts), plus the creep forces' vertical
//!    components (held fixed during the iteration);
//! 3. prescribed load: dz by a bracketed Illinois iteration (N(dz) is monotone and continuous; its
//!    slope jumps where strips or patches enter, which a bracketing method tolerates);
//! 4. **re-striping**: the strips of step 1 cover the rigid interpenetration region, wider than a
//!    model's patch. After the first solve every contiguous run of strips in contact becomes a
//!    patch of its own (separate interpenetration regions → separate patches) with the same
//!    number of strips over the run plus one old strip at each end, and dz is solved again. So
//!    the strip count is the resolution across the patch itself.
//!
//! Known limits: planar patches (one contact plane per patch; the strips' own angles are kept in
//! [`StripPoints`] for the tangential problem); the vertical gap's regions decide which minima
//! share a patch at the trial lowering.

use crate::contact_search::{ContactCandidates, ContactPlane, Region, StripPoints, WheelOnRail};
use crate::load_balance::balance;
use crate::strips::{
    HertzShapeTable, NormalModel, NormalParams, PatchSummary, StripGeometry, StripModel,
    StripSolution,
};
use crate::wheelset::MAX_PATCHES;

/// One non-elliptic patch: its plane, strips, model state and solution.
pub struct StripPatch {
    pub plane: ContactPlane,
    pub geom: StripGeometry,
    pub points: StripPoints,
    pub sol: StripSolution,
    model: Box<dyn StripModel + Send>,
}

impl StripPatch {
    fn new(model: NormalModel) -> Option<Self> {
        Some(Self {
            plane: ContactPlane::default(),
            geom: StripGeometry::default(),
            points: StripPoints::default(),
            sol: StripSolution::default(),
            model: model.strip_model()?,
        })
    }

    /// Sets the patch up on the contact plane at `origin` = (lateral w0, lift) (see
    /// [`WheelOnRail::contact_plane`]) with strips between the rail points at the laterals
    /// `ends` (either order), and prepares its model.
    fn set_up(
        &mut self,
        geometry: &WheelOnRail,
        (w0, lift): (f64, f64),
        ends: (f64, f64),
        strips: usize,
        settings: &StripSettings,
        table: &HertzShapeTable,
    ) {
        let plane = geometry.contact_plane(w0, lift);
        let s_a = geometry.plane_coordinate_of(&plane, ends.0);
        let s_b = geometry.plane_coordinate_of(&plane, ends.1);
        self.plane = plane;
        geometry.strip_geometry(
            &plane,
            s_a.min(s_b),
            s_a.max(s_b),
            strips,
            &mut self.geom,
            &mut self.points,
        );
        self.model.prepare(&self.geom, &settings.params, table);
    }

    /// Normal force at wheel lowering `dz` [N] (writes the solution).
    fn solve(&mut self, dz: f64, params: &NormalParams, table: &HertzShapeTable) -> f64 {
        let delta = self.plane.approach(dz);
        self.model
            .solve(&self.geom, params, table, delta, &mut self.sol)
    }

    pub fn summary(&self) -> PatchSummary {
        PatchSummary::of(&self.geom, &self.sol)
    }

    /// Contact angle of the patch: the rail's angle at the force centroid of the strips (the
    /// patch's reference point; planar patch, so the whole normal force acts along it) [rad].
    pub fn reference_angle(&self) -> f64 {
        let centroid = self.summary().s_centroid;
        self.interpolate(&self.points.contact_angle, centroid)
    }

    /// Linear interpolation of a per-strip quantity at in-plane coordinate `s`.
    pub fn interpolate(&self, values: &[f64], s: f64) -> f64 {
        let g = &self.geom;
        if g.n == 1 {
            return values[0];
        }
        let t = ((s - g.s[0]) / g.ds).clamp(0.0, (g.n - 1) as f64);
        let i = (t.floor() as usize).min(g.n - 2);
        let u = t - i as f64;
        values[i] + (values[i + 1] - values[i]) * u
    }
}

/// The strip patches of one wheel (two buffers: the current patches and the re-striped ones).
pub struct StripSide {
    patches: Vec<StripPatch>,
    spare: Vec<StripPatch>,
    count: usize,
}

/// Settings of the strip solve.
#[derive(Debug, Clone, Copy)]
pub struct StripSettings {
    pub model: NormalModel,
    pub strips: usize,
    pub params: NormalParams,
}

/// Iteration limit of the load balance.
const LOAD_ITERATIONS: usize = 80;
/// Trial lowering for the strip range, as a multiple of the Hertz approach: the models' patches
/// lie inside {f < δ} for ε < 1, and their approaches at a given load stay within ~1.5× Hertz's;
/// a patch touching the range's end triggers a wider range.
const RANGE_FACTOR: f64 = 2.0;
/// Range widenings before giving up on containing a patch (each doubles the trial approach).
const RANGE_RETRIES: usize = 4;

/// Strips of the first layout (step 1) for `strips` on the final patches: half as many. The
/// first layout only has to find where each model's patch lies (its runs of strips in
/// contact); the final strips cover a run plus one first-layout strip at each end, so halving
/// the first layout widens that margin by a few per cent of the patch while sparing half of the
/// first layout's geometry and load iteration. Never fewer than 5 (or `strips` if smaller): a run
/// must stay resolved. Runs one strip apart are one run (see `restrip`).
fn first_layout_strips(strips: usize) -> usize {
    strips.div_ceil(2).max(strips.min(5))
}

/// The deepest contact candidate with its lateral in [w_min, w_max]: (lateral, vertical gap).
fn deepest_candidate(candidates: &ContactCandidates, w_min: f64, w_max: f64) -> Option<(f64, f64)> {
    candidates
        .as_slice()
        .iter()
        .filter(|c| (w_min..=w_max).contains(&c.lateral))
        .min_by(|a, b| a.gap.total_cmp(&b.gap))
        .map(|c| (c.lateral, c.gap))
}

impl StripSide {
    /// Buffers for `model`; `None` for Hertz.
    pub fn new(model: NormalModel) -> Option<Self> {
        let make = || -> Option<Vec<StripPatch>> {
            (0..MAX_PATCHES).map(|_| StripPatch::new(model)).collect()
        };
        Some(Self {
            patches: make()?,
            spare: make()?,
            count: 0,
        })
    }

    pub fn patches(&self) -> &[StripPatch] {
        &self.patches[..self.count]
    }

    /// Vertical force of the rail on the wheel lowered by `dz` (upwards positive) [N].
    fn vertical_force(&mut self, dz: f64, params: &NormalParams, table: &HertzShapeTable) -> f64 {
        self.patches[..self.count]
            .iter_mut()
            .map(|p| {
                let n = p.solve(dz, params, table);
                if n > 0.0 {
                    n * p.reference_angle().cos()
                } else {
                    0.0
                }
            })
            .sum()
    }

    /// Step 1: one patch per interpenetration region at lowering `dz_range`.
    fn build_from_regions(
        &mut self,
        geometry: &mut WheelOnRail,
        dz_range: f64,
        settings: &StripSettings,
        table: &HertzShapeTable,
    ) {
        let mut regions = [Region::default(); MAX_PATCHES];
        let n = geometry.regions(dz_range, &mut regions);
        self.count = 0;
        for region in &regions[..n] {
            let w_first = geometry.lateral_at(region.first as f64);
            let w_last = geometry.lateral_at(region.last as f64);
            // The deepest candidate inside the region is its first-contact point.
            let origin =
                deepest_candidate(geometry.candidates(), w_first, w_last).unwrap_or_else(|| {
                    let p = geometry.point_at(region.deepest as f64);
                    (p.lateral, p.gap)
                });
            // Strips over the region and one sample beyond each end.
            let ends = (
                geometry.lateral_at(region.first as f64 - 1.0),
                geometry.lateral_at(region.last as f64 + 1.0),
            );
            let strips = first_layout_strips(settings.strips);
            self.patches[self.count].set_up(geometry, origin, ends, strips, settings, table);
            self.count += 1;
        }
    }

    /// Step 4: every contiguous run of strips in contact becomes a patch with its own strips.
    /// Returns false when a run touches the end of its strip range (the range was too narrow).
    fn restrip(
        &mut self,
        geometry: &WheelOnRail,
        settings: &StripSettings,
        table: &HertzShapeTable,
    ) -> bool {
        let mut count = 0usize;
        let mut contained = true;
        for k in 0..self.count {
            let old = &self.patches[k];
            let n = old.geom.len();
            // Runs from the field side (largest s) to the gauge side, as the regions come.
            let mut i = n;
            while i > 0 && count < MAX_PATCHES {
                i -= 1;
                if old.sol.half_length[i] <= 0.0 {
                    continue;
                }
                let last = i;
                // A run continues across a single strip out of contact: the new ranges reach one
                // old strip beyond each run, so two runs one strip apart would get overlapping
                // ranges — two patches over the same contact, whose forces add up (a coarse first
                // layout can put one strip centre in a notch of a patch).
                let in_contact = |j: usize| old.sol.half_length[j] > 0.0;
                while i > 0 && (in_contact(i - 1) || (i > 1 && in_contact(i - 2))) {
                    i -= 1;
                }
                let first = i;
                // A run at the end of the range needs a wider range only where the gap still
                // rises outwards there; where it falls, the run leans on a neighbouring contact
                // (two-point contact seen from this patch's plane, which has its own region),
                // and widening would only merge the two.
                let open_low = first == 0 && (n < 2 || old.geom.f[0] >= old.geom.f[1]);
                let open_high = last == n - 1 && (n < 2 || old.geom.f[n - 1] >= old.geom.f[n - 2]);
                if open_low || open_high {
                    contained = false;
                }
                // Rail points one old strip beyond the run (or the run's own end strips).
                let w_lo = old.points.lateral[first.saturating_sub(1)];
                let w_hi = old.points.lateral[(last + 1).min(n - 1)];
                let (w_min, w_max) = (w_lo.min(w_hi), w_lo.max(w_hi));
                let origin = (first..=last)
                    .min_by(|&a, &b| old.geom.f[a].total_cmp(&old.geom.f[b]))
                    .unwrap_or(first);
                // The candidate inside the run, else the run's lowest strip (its gap relative
                // to the old origin gives the lift).
                let origin = deepest_candidate(geometry.candidates(), w_min, w_max).unwrap_or((
                    old.points.lateral[origin],
                    old.plane.lift + old.geom.f[origin] / old.plane.cos_gamma,
                ));
                let ends = (w_lo, w_hi);
                self.spare[count].set_up(geometry, origin, ends, settings.strips, settings, table);
                count += 1;
            }
        }
        std::mem::swap(&mut self.patches, &mut self.spare);
        self.count = count;
        contained
    }

    /// Solves the wheel: prescribed vertical force `target` [N] (`Some`, > 0) or prescribed
    /// lowering `dz` (`None`). `touch` is the lowering at first contact, `dz_hint` a lowering
    /// that carries the load approximately (Hertz) or the prescribed one. The strips are laid out
    /// for `target`; the final patches are then balanced against `final_target` if given (the
    /// load less the creep forces' vertical component: one iteration instead of balancing to
    /// `target` and re-balancing). Returns the lowering.
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        geometry: &mut WheelOnRail,
        settings: &StripSettings,
        table: &HertzShapeTable,
        target: Option<f64>,
        final_target: Option<f64>,
        touch: f64,
        dz_hint: f64,
    ) -> f64 {
        let params = settings.params;
        let mut approach = (dz_hint - touch).max(0.0);
        let mut dz = dz_hint;
        for _ in 0..=RANGE_RETRIES {
            let dz_range = match target {
                Some(_) => touch + RANGE_FACTOR * approach,
                None => dz_hint,
            };
            self.build_from_regions(geometry, dz_range, settings, table);
            dz = match target {
                Some(q) => self.iterate(q, touch, approach, &params, table),
                None => {
                    self.vertical_force(dz_hint, &params, table);
                    dz_hint
                }
            };
            let contained = self.restrip(geometry, settings, table);
            if contained || target.is_none() {
                break;
            }
            approach *= 2.0;
        }
        // The re-striped patches are solved afresh.
        match final_target.or(target) {
            Some(q) => self.iterate(q, touch, dz - touch, &params, table),
            None => {
                self.vertical_force(dz, &params, table);
                dz
            }
        }
    }

    /// Re-solves the lowering for a new vertical force `target` [N] > 0 on the current patches
    /// (no new strips: the creep-force update of the load balance must not move strip edges),
    /// starting from the lowering `dz`. Returns the new lowering.
    pub fn rebalance(
        &mut self,
        settings: &StripSettings,
        table: &HertzShapeTable,
        target: f64,
        touch: f64,
        dz: f64,
    ) -> f64 {
        self.iterate(target, touch, dz - touch, &settings.params, table)
    }

    /// The lowering at which the vertical force equals `q` > 0 ([`balance`], first trial at the
    /// approach `approach` beyond `touch`); the patches' solutions are left at that lowering.
    fn iterate(
        &mut self,
        q: f64,
        touch: f64,
        approach: f64,
        params: &NormalParams,
        table: &HertzShapeTable,
    ) -> f64 {
        let first = approach.max(1e-9);
        let Ok(balanced) = balance(touch, first, q, LOAD_ITERATIONS, |dz| {
            Ok::<_, std::convert::Infallible>(self.vertical_force(dz, params, table) - q)
        });
        if !balanced.evaluated {
            self.vertical_force(balanced.lowering, params, table);
        }
        balanced.lowering
    }
}
