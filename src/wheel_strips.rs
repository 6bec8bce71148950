//! Non-elliptic patches of one wheel: strips on each patch's contact plane, a strip normal model
//! per patch, and the wheel's vertical position for a prescribed load (physics.md §5.1–§5.2).
//!
//! For a wheel lowered by dz from its nominal height:
//! 1. every interpenetration region of the rigid gap at a trial lowering (0.7 × the Hertz
//!    approach beyond first contact: there the models' patches fill 75–85 % of the region on a
//!    tread) becomes a patch: its contact plane is the tangent plane at the deepest contact
//!    candidate inside the region (the first-contact point, s = 0), and its strips cover the
//!    region ([`crate::contact_search::WheelOnRail::strip_geometry`]);
//! 2. the patch's normal approach is δ_p = dz cos γ_p − g_p (g_p its normal gap at nominal
//!    height) and the strip model gives its pressure; the wheel's vertical force is
//!    Σ N_p cos γ_p, γ_p the rail's angle at the patch's force centroid (its reference point,
//!    along whose normal the planar patch's force acts), plus the creep forces' vertical
//!    components (held fixed during the iteration);
//! 3. prescribed load: dz by a bracketed Illinois iteration (N(dz) is monotone and continuous; its
//!    slope jumps where strips or patches enter, which a bracketing method tolerates);
//! 4. **the verdict on the layout** ([`Verdict`]): where every patch holds one run of strips in
//!    contact, closed at both ends and over at least 60 % of its strips, the layout is final (the
//!    common case: one layout per solve). Otherwise, **re-striping**: every contiguous run of
//!    strips in contact becomes a patch of its own (separate interpenetration regions → separate
//!    patches) with the same number of strips over the run plus one old strip at each end, and
//!    dz is solved again; where a run is open (the patch may reach beyond the range) or shorter
//!    than three strips, the runs are first found anew on coarse strips over the region at 2 ×
//!    the approach (widened until closed). So the strip count sets the resolution across the
//!    patch itself: at least 60 % of the strips lie on it.
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
        self.interpolate_by(centroid, |j| self.points.contact_angle(j))
    }

    /// Linear interpolation of a per-strip quantity at in-plane coordinate `s`.
    pub fn interpolate(&self, values: &[f64], s: f64) -> f64 {
        self.interpolate_by(s, |j| values[j])
    }

    /// [`StripPatch::interpolate`] of the per-strip quantity `value(j)`, evaluated at the (at
    /// most two) strips the interpolation uses.
    pub fn interpolate_by(&self, s: f64, value: impl Fn(usize) -> f64) -> f64 {
        let g = &self.geom;
        if g.n == 1 {
            return value(0);
        }
        let t = ((s - g.s[0]) / g.ds).clamp(0.0, (g.n - 1) as f64);
        // `as usize` floors a non-negative value (and saturates below 0) without a call to
        // libm's floor, which baseline x86-64 (no SSE4.1 rounding) would need.
        let i = (t as usize).min(g.n - 2);
        let u = t - i as f64;
        let (lo, hi) = (value(i), value(i + 1));
        lo + (hi - lo) * u
    }
}

/// The strip patches of one wheel (two buffers: the current patches and the re-striped ones).
pub struct StripSide {
    patches: Vec<StripPatch>,
    spare: Vec<StripPatch>,
    count: usize,
    /// The approach beyond first touch at which the first layout carried the load in the last
    /// [`StripSide::solve`] [m] (0 without a load).
    layout_approach: f64,
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
/// Trial lowering of the first layout's strip range, as a multiple of the Hertz approach (the
/// strips then cover the interpenetration region at that lowering). The range is meant to be
/// final: on the built-in S1002/UIC60 tread the models' patches cover 75–85 % of it (18–20 of
/// 24 strips; 0.5 would put Linder's and Kik–Piotrowski's at the range's ends, 1.0 leaves 15 of
/// 24 strips to STRIPES). Where a patch does not fit (an open run) or is too small in it, the
/// layout is redone ([`Verdict`]).
const RANGE_FACTOR: f64 = 0.7;
/// Smallest share of a patch's strips that its run of strips in contact must cover for the
/// first layout to stand as the final one (else each run is re-striped: see [`Verdict`]). At
/// 0.6 of 24 strips a patch keeps at least 15 strips across it (accuracy: docs/performance.md).
const ACCEPTED_RUN_SHARE: f64 = 0.6;
/// Fewest strips of a run that the re-striping may start from: a run of one or two strips
/// locates a patch only to within a strip, too coarsely to lay the final strips over it (at a
/// 1 N load the patch of a single first-layout strip was wider than the three strips around
/// it); such layouts are redone over the wide range.
const MIN_RESTRIP_RUN: usize = 3;
/// Trial lowering of the wide fallback range (as a multiple of the Hertz approach): the models'
/// patches lie inside {f < δ} for ε < 1, and their approaches at a given load stay within ~1.5×
/// Hertz's; a patch touching the range's end triggers a wider range.
const WIDE_RANGE_FACTOR: f64 = 2.0;
/// Range widenings before giving up on containing a patch (each doubles the trial approach).
const RANGE_RETRIES: usize = 4;

/// A contiguous run of strips in contact on a patch (see [`StripPatch::runs`]).
#[derive(Debug, Clone, Copy, Default)]
struct Run {
    /// First and last strip of the run (indices into the patch's strips).
    first: usize,
    last: usize,
    /// The run reaches an end of the strip range where the gap still rises outwards: the
    /// patch may extend beyond the range.
    open: bool,
}

impl StripPatch {
    /// The runs of strips in contact, from the field side (largest s) to the gauge side, as
    /// the regions come; at most `out.len()`. A run continues across a single strip out of
    /// contact: [`StripSide::restrip`] gives each run a range one strip beyond its ends, so two
    /// runs one strip apart would get overlapping ranges — two patches over the same contact,
    /// whose forces add up (a coarse layout can put one strip centre in a notch of a patch).
    fn runs(&self, out: &mut [Run]) -> usize {
        let sol = &self.sol;
        let f = &self.geom.f;
        let n = self.geom.len();
        let in_contact = |j: usize| sol.half_length[j] > 0.0;
        let mut count = 0;
        let mut i = n;
        while i > 0 && count < out.len() {
            i -= 1;
            if !in_contact(i) {
                continue;
            }
            let last = i;
            while i > 0 && (in_contact(i - 1) || (i > 1 && in_contact(i - 2))) {
                i -= 1;
            }
            let first = i;
            // A run at the end of the range needs a wider range only where the gap still rises
            // outwards there; where it falls, the run leans on a neighbouring contact
            // (two-point contact seen from this patch's plane, which has its own region), and
            // widening would only merge the two.
            let open_low = first == 0 && (n < 2 || f[0] >= f[1]);
            let open_high = last == n - 1 && (n < 2 || f[n - 1] >= f[n - 2]);
            out[count] = Run {
                first,
                last,
                open: open_low || open_high,
            };
            count += 1;
        }
        count
    }
}

/// What becomes of a strip layout after its first solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Verdict {
    /// Every patch holds one closed run of strips in contact over at least
    /// [`ACCEPTED_RUN_SHARE`] of its strips: the layout is final.
    Accept,
    /// The runs are closed and of at least [`MIN_RESTRIP_RUN`] strips, but a patch holds
    /// several or a small one: each run gets its own strips ([`StripSide::restrip`]).
    Restrip,
    /// A run is open (the patch may reach beyond its range) or too short to re-stripe from, or
    /// nothing is in contact: redo the layout over the wide range.
    Widen,
}

/// Strips of the wide fallback layout for `strips` on the final patches: half as many. That
/// layout only has to find where each model's patch lies (its runs of strips in contact); the
/// final strips cover a run plus one of its strips at each end, so halving it widens that
/// margin by a few per cent of the patch while sparing half of its geometry and load
/// iteration. Never fewer than 5 (or `strips` if smaller): a run must stay resolved.
fn wide_layout_strips(strips: usize) -> usize {
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
            layout_approach: 0.0,
        })
    }

    /// See the field: the warm start of the next step's first trial (`ratio_hint` of
    /// [`StripSide::solve`]).
    pub fn layout_approach(&self) -> f64 {
        self.layout_approach
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

    /// Step 1: one patch of `strips` strips per interpenetration region at lowering `dz_range`.
    fn build_from_regions(
        &mut self,
        geometry: &mut WheelOnRail,
        dz_range: f64,
        strips: usize,
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
            self.patches[self.count].set_up(geometry, origin, ends, strips, settings, table);
            self.count += 1;
        }
    }

    /// What to do with the current layout after its first solve.
    fn verdict(&self) -> Verdict {
        let mut restrip = false;
        let mut any_run = false;
        for patch in self.patches() {
            let mut runs = [Run::default(); MAX_PATCHES];
            let n = patch.geom.len();
            let found = patch.runs(&mut runs);
            for run in &runs[..found] {
                if run.open || run.last + 1 - run.first < MIN_RESTRIP_RUN.min(n) {
                    return Verdict::Widen;
                }
            }
            any_run |= found > 0;
            let share = |run: &Run| (run.last + 1 - run.first) as f64 / n as f64;
            restrip |= found != 1 || share(&runs[0]) < ACCEPTED_RUN_SHARE;
        }
        match (any_run, restrip) {
            (false, _) => Verdict::Widen,
            (true, true) => Verdict::Restrip,
            (true, false) => Verdict::Accept,
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
            let mut runs = [Run::default(); MAX_PATCHES];
            let found = old.runs(&mut runs[..MAX_PATCHES - count]);
            for &Run { first, last, open } in &runs[..found] {
                if open {
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
    /// `target` and re-balancing). The first layout's load iteration starts at `ratio_hints[0]`
    /// (within [½, 2]) × the Hertz approach: the previous step's [`StripSide::layout_approach`]
    /// over its Hertz approach, a warm start that changes the balanced lowering only within the
    /// iteration's tolerance (the layout itself follows from the Hertz approach alone); the
    /// final patches' iteration likewise at `ratio_hints[1]` × the Hertz approach (the previous
    /// step's final approach over its Hertz approach). Returns the lowering.
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
        ratio_hints: [f64; 2],
    ) -> f64 {
        let params = settings.params;
        let approach = (dz_hint - touch).max(0.0);
        let [first_trial, final_trial] = ratio_hints.map(|r| approach * r.clamp(0.5, 2.0));
        // The lowering whose interpenetration regions a layout covers: `factor` × `approach`
        // beyond first touch, or the prescribed lowering.
        let range_at = |factor: f64, approach: f64| match target {
            Some(_) => touch + factor * approach,
            None => dz_hint,
        };
        // The first layout, meant to be final: `settings.strips` over each region at
        // RANGE_FACTOR × the Hertz approach.
        let mut dz = self.layout_and_solve(
            geometry,
            range_at(RANGE_FACTOR, approach),
            settings.strips,
            settings,
            table,
            target,
            touch,
            first_trial,
            dz_hint,
        );
        self.layout_approach = if target.is_some() { dz - touch } else { 0.0 };
        match self.verdict() {
            Verdict::Accept => {
                // Solved already, unless the final target differs from the layout's.
                if target.is_none() || final_target.is_none_or(|q| Some(q) == target) {
                    return dz;
                }
            }
            Verdict::Restrip => {
                self.restrip(geometry, settings, table);
            }
            Verdict::Widen => {
                // The wide fallback: coarse strips over the region at WIDE_RANGE_FACTOR × the
                // approach, each run re-striped; widened while a run is open.
                let mut approach = approach;
                for _ in 0..=RANGE_RETRIES {
                    let dz_range = range_at(WIDE_RANGE_FACTOR, approach);
                    let strips = wide_layout_strips(settings.strips);
                    dz = self.layout_and_solve(
                        geometry, dz_range, strips, settings, table, target, touch, approach,
                        dz_hint,
                    );
                    let contained = self.restrip(geometry, settings, table);
                    if contained || target.is_none() {
                        break;
                    }
                    approach *= 2.0;
                }
            }
        }
        // The final patches (re-striped, or the first ones for a different target) solved
        // afresh: a final target from its own warm start (the first layout's target, which
        // only a re-striping gets here, from the first layout's lowering).
        let trial = if final_target.is_some() {
            final_trial
        } else {
            dz - touch
        };
        self.solve_at(final_target.or(target), touch, trial, dz, &params, table)
    }

    /// Lays out `strips` strips per region at `dz_range` and solves them for `target` (first
    /// trial at `approach` beyond `touch`) or at the lowering `dz_hint`. Returns the lowering.
    #[allow(clippy::too_many_arguments)]
    fn layout_and_solve(
        &mut self,
        geometry: &mut WheelOnRail,
        dz_range: f64,
        strips: usize,
        settings: &StripSettings,
        table: &HertzShapeTable,
        target: Option<f64>,
        touch: f64,
        approach: f64,
        dz_hint: f64,
    ) -> f64 {
        self.build_from_regions(geometry, dz_range, strips, settings, table);
        self.solve_at(target, touch, approach, dz_hint, &settings.params, table)
    }

    /// The current patches balanced to the vertical force `target` (first trial at `approach`
    /// beyond `touch`) or, without one, solved at the lowering `dz`. Returns the lowering.
    fn solve_at(
        &mut self,
        target: Option<f64>,
        touch: f64,
        approach: f64,
        dz: f64,
        params: &NormalParams,
        table: &HertzShapeTable,
    ) -> f64 {
        match target {
            Some(q) => self.iterate(q, touch, approach, params, table),
            None => {
                self.vertical_force(dz, params, table);
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
