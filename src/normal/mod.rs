//! Normal contact: Hertz and the non-elliptic strip models, their parameters and the model factory.
//!
//! * [`hertz`] — the elliptic (Hertz) solution, the basis of every model;
//! * [`shape`] — Hertz functions of the curvature ratio, tabulated for per-strip use;
//! * [`strips`] — the per-strip pressure every strip model writes, and its patch summary;
//! * [`linder`], [`kik_piotrowski`], [`stripes`], [`analyn`], [`coupled_strips`] — the strip
//!   models, each one [`StripModel`], built by [`NormalModel::strip_model`];
//! * [`kernel`] — the half-space kernel of a semi-elliptic strip load (KP6), shared by
//!   `kik_piotrowski` and `coupled_strips`.

pub mod analyn;
pub mod coupled_strips;
pub mod hertz;
pub mod kernel;
pub mod kik_piotrowski;
pub mod linder;
pub mod shape;
pub mod stripes;
pub mod strips;
#[cfg(test)]
pub(crate) mod test_support;

use crate::geometry::strips::StripGeometry;
use shape::HertzShapeTable;
use strips::StripSolution;

/// Default number of strips across a patch: on the central case the strip models' tangential
/// forces are as close to their 200-strip values with 24 strips as with 40 (the elements along
/// each strip set the error; docs/performance.md), at ~60 % of the cost. Not fewer: Linder's
/// force jumps as a strip enters contact (∝ 1/strips), and at 20 strips a jump near y = 2.9 mm
/// exceeds the 1 % load check.
pub const DEFAULT_STRIPS: usize = 24;

/// Parameters shared by the strip normal models.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalParams {
    /// Contact modulus E* = E/(2(1 − ν²)) [Pa].
    pub e_star: f64,
    /// Floor of the lateral curvature B [1/m] (docs/theory.md §5.9; default 0.1 1/m = CONTACT's
    /// 1e−4 1/mm): STRIPES-B and ANALYN replace B < b_min by b_min, STRIPES-A&B shifts all B by
    /// max(0, b_min − min B).
    pub b_min: f64,
    /// STRIPES-B smoothing window of B as a fraction of the strip set's width [-] (0 = none).
    pub b_smoothing: f64,
    /// Kik–Piotrowski area-preserving shape correction (KP8).
    pub kp_shape_correction: bool,
}

/// Default STRIPES-B smoothing window (fraction of the patch width).
pub const DEFAULT_B_SMOOTHING: f64 = 0.2;

impl NormalParams {
    /// The floor of B the models apply: `b_min`, or the default where it is not finite and
    /// positive (the models never fail on a bad parameter; the FMU validates it on setting).
    pub fn b_floor(&self) -> f64 {
        if self.b_min.is_finite() && self.b_min > 0.0 {
            self.b_min
        } else {
            Self::default().b_min
        }
    }
}

impl Default for NormalParams {
    fn default() -> Self {
        Self {
            e_star: hertz::contact_modulus(2.1e11, 0.28),
            b_min: 0.1,
            b_smoothing: DEFAULT_B_SMOOTHING,
            kp_shape_correction: false,
        }
    }
}

/// A strip normal model. Implementations own fixed-size scratch buffers: neither method
/// allocates, panics or produces NaN for any finite geometry (B may be ≤ 0) and any δ.
pub trait StripModel {
    /// δ-independent work for a new geometry (curvature rules, smoothing, per-strip Hertz shapes).
    fn prepare(&mut self, geom: &StripGeometry, params: &NormalParams, table: &HertzShapeTable);
    /// Pressure at the normal approach δ [m] of the patch's first-contact point (δ ≤ 0: no
    /// contact). Writes all `geom.n` strips of `out` and returns the normal force [N].
    fn solve(
        &mut self,
        geom: &StripGeometry,
        params: &NormalParams,
        table: &HertzShapeTable,
        delta: f64,
        out: &mut StripSolution,
    ) -> f64;
}

/// The normal contact models (FMU parameter `normalModel`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum NormalModel {
    /// 1: Hertz per contact patch (multi-Hertzian), no strips.
    #[default]
    Hertz,
    /// 2: Linder's virtual penetration (`linder`).
    Linder,
    /// 3: Kik–Piotrowski (`kik_piotrowski`).
    KikPiotrowski,
    /// 4: STRIPES with B correction and smoothing (`stripes::StripesB`).
    StripesB,
    /// 5: STRIPES with A-and-B correction, no smoothing (`stripes::StripesAB`).
    StripesAB,
    /// 6: ANALYN (`analyn`).
    Analyn,
    /// 7: strips coupled through the half-space, lengths by the local Hertz ratio
    /// (`coupled_strips`).
    CoupledStrips,
}

impl NormalModel {
    /// All models in FMU order (`normalModel` = index + 1).
    pub const ALL: [NormalModel; 7] = [
        NormalModel::Hertz,
        NormalModel::Linder,
        NormalModel::KikPiotrowski,
        NormalModel::StripesB,
        NormalModel::StripesAB,
        NormalModel::Analyn,
        NormalModel::CoupledStrips,
    ];

    /// The model of FMU code `code` (1…7).
    pub fn from_code(code: i32) -> Option<Self> {
        usize::try_from(code - 1)
            .ok()
            .and_then(|i| Self::ALL.get(i).copied())
    }

    /// FMU code (1…7).
    pub fn code(self) -> i32 {
        Self::ALL
            .iter()
            .position(|m| *m == self)
            .map_or(1, |i| i as i32 + 1)
    }

    /// Short name (CLI, reports).
    pub fn name(self) -> &'static str {
        match self {
            NormalModel::Hertz => "hertz",
            NormalModel::Linder => "linder",
            NormalModel::KikPiotrowski => "kik-piotrowski",
            NormalModel::StripesB => "stripes-b",
            NormalModel::StripesAB => "stripes-ab",
            NormalModel::Analyn => "analyn",
            NormalModel::CoupledStrips => "coupled-strips",
        }
    }

    /// The model named `name` (as [`NormalModel::name`]).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|m| m.name() == name)
    }

    /// Whether a strip patch of this model takes its reference point at the weighted centre of
    /// the interpenetration (CONTACT's contact reference point: ANALYN and the coupled strips,
    /// whose pressure lies near the exact one's) or at its own force centroid (Linder,
    /// Kik–Piotrowski and STRIPES, whose published pressures may sit a few millimetres away from
    /// it: their forces and creepages follow their own pressure). docs/theory.md §7.9.
    pub fn reference_at_interpenetration(self) -> bool {
        matches!(self, NormalModel::Analyn | NormalModel::CoupledStrips)
    }

    /// A solver for a strip model; `None` for Hertz (no strips).
    pub fn strip_model(self) -> Option<Box<dyn StripModel + Send>> {
        Some(match self {
            NormalModel::Hertz => return None,
            NormalModel::Linder => Box::new(linder::Linder::default()),
            NormalModel::KikPiotrowski => Box::new(kik_piotrowski::KikPiotrowski::default()),
            NormalModel::StripesB => Box::new(stripes::StripesB::default()),
            NormalModel::StripesAB => Box::new(stripes::StripesAB::default()),
            NormalModel::Analyn => Box::new(analyn::Analyn::default()),
            NormalModel::CoupledStrips => Box::new(coupled_strips::CoupledStrips::default()),
        })
    }
}
