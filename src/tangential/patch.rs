//! The tangential problem of one non-elliptic (strip) patch: which flexibilities each strip gets
//! and which solver runs (docs/theory.md §4.7, §5.8, §6).
//!
//! Options (`tangentialModel` of the WheelRailContact FMU):
//!
//! 1. **the normal model's own** — the pairing of each paper: Kik–Piotrowski and ANALYN with the
//!    equivalent ellipse (Piotrowski & Kik 2008; CONTACT after KPEC and ANALYN), Linder with its
//!    local ellipses (a_j, b_L) sharing one lateral semi-axis, both STRIPES variants with the local
//!    Hertz ellipse of each strip (Ayasse & Chollet 2005);
//! 2. **equivalent ellipse** — one ellipse of the patch's area and length/width ratio,
//!    a_e = √(S/π)·√(L/W), b_e = √(S/π)·√(W/L), and its three flexibilities (F1) on every strip,
//!    used individually (Kik–Piotrowski's choice);
//! 3. **FaStrip** (Sichani et al. 2016) on the equivalent ellipse (`crate::tangential::fastrip`);
//! 4. **local Hertz ellipses** — STRIPES's strip-wise ellipses for any strip model: strip j gets
//!    a_j = x_l,j and b_j = a_j/(a/b)_H, the Hertz axis ratio of its curvatures (A_j, max(B_j,
//!    B_min));
//! 5. **FaStrip with coupled coefficients** — FaStrip as in 3, each strip's creepages scaled by
//!    its own creep coefficients from the strips coupled through the half-space in full
//!    adhesion (`crate::tangential::strip_coefficients`, docs/theory.md §6.6).
//!
//! FASTSIM's flexibility option (`flexibility`: three, single F2, blended F4) applies per strip to
//! that strip's ellipse and creepages; the blending weight F4 uses the equivalent ellipse's
//! characteristic creepages (the patch's μN), the same for all strips. In every option the
//! traction bound is μ × the normal model's own pressure on the strips (§4.3).

use crate::error::InputError;
use crate::geometry::strips::StripGeometry;
use crate::normal::shape::HertzShapeTable;
use crate::normal::strips::{PatchSummary, StripSolution};
use crate::normal::NormalModel;
use crate::tangential::fastsim::{
    blend_flexibilities, blending_weight, single_flexibility, three_flexibilities, Creepage,
    EllipticContact, Flexibility,
};
use crate::tangential::kalker::{creep_coefficients, CreepCoefficients};

/// Tangential model on strip patches (`tangentialModel`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TangentialModel {
    /// 1: the normal model's own flexibilities (see the module docs).
    #[default]
    ModelDefault,
    /// 2: one equivalent ellipse for the whole patch.
    EquivalentEllipse,
    /// 3: FaStrip on the equivalent ellipse.
    Fastrip,
    /// 4: strip-wise local ellipses: each strip's own half-length with the patch's lateral
    /// semi-axis (its equivalent ellipse's).
    LocalEllipses,
    /// 5: FaStrip with strip-wise creep coefficients from the half-space.
    FastripCoupled,
}

impl TangentialModel {
    pub const ALL: [TangentialModel; 5] = [
        TangentialModel::ModelDefault,
        TangentialModel::EquivalentEllipse,
        TangentialModel::Fastrip,
        TangentialModel::LocalEllipses,
        TangentialModel::FastripCoupled,
    ];

    /// From the FMU code 1–5.
    pub fn from_code(code: i32) -> Option<Self> {
        Self::ALL.get(usize::try_from(code - 1).ok()?).copied()
    }

    /// Whether the option runs FaStrip (3, 5) rather than FASTSIM.
    pub fn is_fastrip(self) -> bool {
        matches!(
            self,
            TangentialModel::Fastrip | TangentialModel::FastripCoupled
        )
    }

    /// Short name (CLI, docs).
    pub fn name(self) -> &'static str {
        match self {
            TangentialModel::ModelDefault => "model-default",
            TangentialModel::EquivalentEllipse => "equivalent-ellipse",
            TangentialModel::Fastrip => "fastrip",
            TangentialModel::LocalEllipses => "local-ellipses",
            TangentialModel::FastripCoupled => "fastrip-coupled",
        }
    }

    /// Where the strips' flexibilities come from for normal model `normal`.
    pub fn flexibility_source(self, normal: NormalModel) -> FlexibilitySource {
        match self {
            TangentialModel::EquivalentEllipse
            | TangentialModel::Fastrip
            | TangentialModel::FastripCoupled => FlexibilitySource::EquivalentEllipse,
            TangentialModel::LocalEllipses => FlexibilitySource::StripLength,
            TangentialModel::ModelDefault => match normal {
                NormalModel::Linder => FlexibilitySource::ModelLocal,
                NormalModel::StripesB | NormalModel::StripesAB => FlexibilitySource::LocalHertz,
                NormalModel::Hertz
                | NormalModel::KikPiotrowski
                | NormalModel::Analyn
                | NormalModel::CoupledStrips => FlexibilitySource::EquivalentEllipse,
            },
        }
    }
}

/// Which ellipse gives a strip its flexibilities.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FlexibilitySource {
    /// The patch's equivalent ellipse (same for every strip).
    EquivalentEllipse,
    /// The normal model's local ellipse (`StripSolution::local_axes`; Linder), falling back to
    /// the local Hertz ellipse where the model set none.
    ModelLocal,
    /// The strip's local Hertz ellipse.
    LocalHertz,
    /// The strip's own half-length x_l,j with the lateral semi-axis of the patch's equivalent
    /// ellipse (as Linder's local ellipses share one lateral semi-axis).
    StripLength,
}

/// The equivalent ellipse of a patch (docs/theory.md §4.7): semi-axes with the patch's area S and
/// length/width ratio L/W (W the area-weighted spread width, `PatchSummary::spread_width`,
/// which is continuous in the wheel height where the whole-strip extent jumps),
/// a_e = √(S/π)·√(L/W), b_e = √(S/π)·√(W/L), carrying the patch's normal
/// force, with its Kalker coefficients (computed once per patch).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EquivalentEllipse {
    /// Semi-axes, normal force, G, ν and μ of the ellipse.
    pub contact: EllipticContact,
    /// Kalker's C11, C22, C23 for a_e/b_e and ν.
    pub coefficients: CreepCoefficients,
}

impl EquivalentEllipse {
    /// The equivalent ellipse of `summary` with shear modulus `shear_modulus` [Pa], Poisson ratio
    /// `nu` and friction `mu`. Errors as `crate::tangential::kalker::creep_coefficients`.
    pub fn of(
        summary: &PatchSummary,
        shear_modulus: f64,
        nu: f64,
        mu: f64,
    ) -> Result<Self, InputError> {
        // The continuous spread width, not the whole-strip extent (see `PatchSummary`).
        let aspect = (summary.length / summary.spread_width).sqrt();
        let radius = (summary.area / std::f64::consts::PI).sqrt();
        let (a, b) = (radius * aspect, radius / aspect);
        Ok(Self {
            contact: EllipticContact {
                a,
                b,
                normal_force: summary.normal_force,
                shear_modulus,
                nu,
                mu,
            },
            coefficients: creep_coefficients(a, b, nu)?,
        })
    }

    /// Hertzian peak pressure of the ellipse, 3N/(2π a_e b_e) [Pa].
    pub fn peak_pressure(&self) -> f64 {
        let c = &self.contact;
        1.5 * c.normal_force / (std::f64::consts::PI * c.a * c.b)
    }
}

/// Flexibilities [L1, L2, L3] [m/Pa] of strip `j` for `source`, with the flexibility option
/// `option` applied to the strip's `creepage` (F2 single, F4 blended with the weight of the
/// patch's equivalent ellipse `equivalent`).
#[allow(clippy::too_many_arguments)]
pub fn strip_flexibilities(
    source: FlexibilitySource,
    option: Flexibility,
    geom: &StripGeometry,
    sol: &StripSolution,
    j: usize,
    b_floor: f64,
    table: &HertzShapeTable,
    equivalent: &EquivalentEllipse,
    creepage: &Creepage,
) -> Result<[f64; 3], InputError> {
    let e = &equivalent.contact;
    let (a, b, c) = match source {
        FlexibilitySource::EquivalentEllipse => (e.a, e.b, equivalent.coefficients),
        FlexibilitySource::ModelLocal if sol.local_axes[j].0 > 0.0 => {
            let (a, b) = sol.local_axes[j];
            (a, b, creep_coefficients(a, b, e.nu)?)
        }
        FlexibilitySource::StripLength => {
            let a = sol.half_length[j];
            (a, e.b, creep_coefficients(a, e.b, e.nu)?)
        }
        FlexibilitySource::ModelLocal | FlexibilitySource::LocalHertz => {
            let shape = table.lookup(geom.curv_a[j], geom.curv_b[j].max(b_floor))?;
            let a = sol.half_length[j];
            let b = a / shape.a_over_b;
            (a, b, creep_coefficients(a, b, e.nu)?)
        }
    };
    let three = three_flexibilities(a, b, e.shear_modulus, &c);
    Ok(match option {
        Flexibility::Three => three,
        Flexibility::Single => [single_flexibility(three, creepage, (a * b).sqrt()); 3],
        Flexibility::Blended => {
            // F4's weight from the patch (equivalent ellipse, total N), L× from the strip's own.
            let w = blending_weight(e, &equivalent.coefficients, creepage);
            blend_flexibilities(three, a, creepage, w)
        }
    })
}
