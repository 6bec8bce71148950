//! The model runs behind `railcontact report`: the case's wheelset solved through the FMU's own
//! mapping from values to settings and inputs (`wheel_rail_contact::settings`/`input`), with the
//! normal model, tangential option, patch treatment, creepages and lateral shift set per figure;
//! and the per-strip, per-element and total results the figures and tables need.
//!
//! Everything here is in SI units (m, Pa, N, N·m, 1/m); the figures convert to mm and MPa.
//! Results are those of the **right wheel** (the reference's wheel); lateral positions are its
//! `yRail` (mounted rail frame, positive towards the field side, docs/conventions.md).

use crate::Failure;
use railcontact::fmi::variables::Values;
use railcontact::geometry::profile::{Profile, ProfileKind};
use railcontact::models::wheel_rail_contact::{self as wrc, generated::var};
use railcontact::normal::hertz::contact_modulus;
use railcontact::normal::shape::HertzShapeTable;
use railcontact::normal::stripes::{StripesAB, StripesB};
use railcontact::normal::{NormalModel, NormalParams, StripModel};
use railcontact::tangential::fastsim::Creepage;
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::strip_side::StripPatch;
use railcontact::wheelset::{
    PatchResult, SideResult, TractionElement, Wheelset, WheelsetError, WheelsetResult,
};

/// Points along a Hertz ellipse's lateral axis in its strip table (ends included).
const ELLIPSE_POINTS: usize = 41;

/// The case the figures vary: its values (parameters and inputs) and its loaded profiles.
pub struct Study {
    base: Values,
    wheel: Profile,
    rail: Profile,
}

/// A wheelset set up for one figure's settings, solved for one input after another.
pub struct Runner {
    wheelset: Wheelset,
    values: Values,
}

/// One strip of a patch as the figures draw it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StripRow {
    /// Rail lateral coordinate of the strip [m].
    pub y_rail: f64,
    /// Leading and trailing edge along x [m].
    pub x_lead: f64,
    pub x_trail: f64,
    /// The strip's maximum pressure [Pa].
    pub pmax: f64,
    /// Relative lateral curvature B as the geometry gives it [1/m].
    pub b_raw: f64,
    /// B as the STRIPES model uses it (smoothed and floored, or shifted) [1/m]; `None` for the
    /// other models.
    pub b_model: Option<f64>,
}

/// Totals of the right wheel's patches (contact axes, summed over its patches).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Totals {
    pub fn_: f64,
    pub fx: f64,
    pub fy: f64,
    pub mz: f64,
    pub area: f64,
    pub pmax: f64,
    /// Area-weighted adhesion share [-].
    pub adhesion: f64,
}

/// The normal solution of one model: its patches' strips and totals.
#[derive(Debug, Clone)]
pub struct NormalRun {
    pub model: NormalModel,
    /// Per patch, strips in contact sorted by `y_rail`.
    pub patches: Vec<Vec<StripRow>>,
    /// The strip maxima along the rail, (yRail [m], pmax [Pa]) sorted by yRail: every strip of
    /// every strip patch, also those out of contact (pmax 0), as `tests/central.rs` compares
    /// them; a Hertz patch's ellipse points.
    pub profile: Vec<(f64, f64)>,
    pub totals: Totals,
}

/// One element of a traction field as a rectangle in (yRail, x) [m] with its traction [Pa].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell {
    pub y0: f64,
    pub y1: f64,
    pub x0: f64,
    pub x1: f64,
    /// Traction along x and along the element's lateral axis (towards the field side on the
    /// right wheel) [Pa].
    pub px: f64,
    pub py: f64,
    /// |traction| [Pa].
    pub traction: f64,
    pub slip: bool,
}

/// A pure-spin solution: the traction field and the patch outline.
#[derive(Debug, Clone)]
pub struct SpinRun {
    pub model: NormalModel,
    pub tangential: TangentialModel,
    pub planar: bool,
    pub cells: Vec<Cell>,
    pub normal: NormalRun,
}

/// A creep-force curve pair, forces normalised by μ N.
#[derive(Debug, Clone)]
pub struct CreepCurve {
    pub model: NormalModel,
    pub tangential: TangentialModel,
    /// (ξ, Fx/μN) at η = φ = 0.
    pub fx: Vec<(f64, f64)>,
    /// (η, Fy/μN) at ξ = φ = 0.
    pub fy: Vec<(f64, f64)>,
}

/// Settings a figure changes on the case: normal model, tangential option, planar patch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    pub model: NormalModel,
    /// `None`: the case's own `tangentialModel`.
    pub tangential: Option<TangentialModel>,
    /// `None`: the case's own `planarPatch`.
    pub planar: Option<bool>,
    /// `None`: the case's own `bSmoothing` (STRIPES-B's smoothing window).
    pub b_smoothing: Option<f64>,
}

impl Options {
    /// `model` with the case's other settings.
    pub fn normal(model: NormalModel) -> Self {
        Self {
            model,
            tangential: None,
            planar: None,
            b_smoothing: None,
        }
    }
}

fn solve_error(e: WheelsetError) -> Failure {
    match e {
        WheelsetError::NoContact { .. } | WheelsetError::Unbalanced { .. } => {
            Failure::Discard(e.to_string())
        }
        WheelsetError::Input(e) => Failure::Error(e.to_string()),
    }
}

impl Study {
    /// Loads the profiles `base` names.
    pub fn new(base: Values) -> Result<Self, Failure> {
        let smoothing = base.real(var::profileSmoothing);
        let load = |spec: &str, kind| {
            Profile::load(spec, kind, smoothing).map_err(|e| Failure::Error(e.to_string()))
        };
        let wheel = load(base.string(var::wheelProfile), ProfileKind::Wheel)?;
        let rail = load(base.string(var::railProfile), ProfileKind::Rail)?;
        Ok(Self { base, wheel, rail })
    }

    /// STRIPES-B's smoothing window of the case (fraction of the patch width).
    pub fn b_smoothing(&self) -> f64 {
        self.base.real(var::bSmoothing)
    }

    pub fn values(&self) -> &Values {
        &self.base
    }

    /// Coefficient of friction of the case.
    pub fn mu(&self) -> f64 {
        self.base.real(var::mu)
    }

    /// A wheelset with the case's settings changed by `options`.
    pub fn runner(&self, options: Options) -> Result<Runner, Failure> {
        let mut values = self.base.clone();
        values.set_integer(var::normalModel, options.model.code());
        if let Some(t) = options.tangential {
            values.set_integer(var::tangentialModel, tangential_code(t));
        }
        if let Some(planar) = options.planar {
            values.booleans[var::planarPatch.0] = planar;
        }
        if let Some(w) = options.b_smoothing {
            values.set_real(var::bSmoothing, w);
        }
        let settings = wrc::settings(&values)?;
        let wheelset = Wheelset::new(&self.wheel, &self.rail, settings)
            .map_err(|e| Failure::Error(e.to_string()))?;
        Ok(Runner { wheelset, values })
    }

    /// The normal solution with `options` and the case's inputs, the lateral shift set to `y`
    /// [m].
    pub fn normal(&self, options: Options, y: f64) -> Result<NormalRun, Failure> {
        let mut runner = self.runner(options)?;
        runner.values.set_real(var::y, y);
        let result = runner.solve()?;
        Ok(runner.normal_run(&result.right))
    }

    /// The normal solution of `model` at the case's own lateral shift.
    pub fn central(&self, model: NormalModel) -> Result<NormalRun, Failure> {
        self.normal(Options::normal(model), self.base.real(var::y))
    }

    /// Pure spin `phi` [1/m] (ξ = η = 0, prescribed at the patch) with `options`.
    pub fn spin(&self, options: Options, phi: f64) -> Result<SpinRun, Failure> {
        let mut runner = self.runner(options)?;
        runner.prescribe(Creepage {
            xi: 0.0,
            eta: 0.0,
            phi,
        });
        let result = runner.solve()?;
        let normal = runner.normal_run(&result.right);
        let cells = (0..result.right.patches.len())
            .filter_map(|k| runner.wheelset.traction_field(true, k))
            .flat_map(|field| cells(&field))
            .collect();
        Ok(SpinRun {
            model: options.model,
            tangential: runner.tangential(),
            planar: runner.planar(),
            cells,
            normal,
        })
    }

    /// Creep curves of `options` over `creepages` (pure ξ, then pure η).
    pub fn creep_curve(&self, options: Options, creepages: &[f64]) -> Result<CreepCurve, Failure> {
        let mut runner = self.runner(options)?;
        let mu = self.mu();
        let mut fx = Vec::with_capacity(creepages.len());
        let mut fy = Vec::with_capacity(creepages.len());
        for &c in creepages {
            let t = runner.totals_at(Creepage {
                xi: c,
                eta: 0.0,
                phi: 0.0,
            })?;
            fx.push((c, t.fx / (mu * t.fn_)));
            let t = runner.totals_at(Creepage {
                xi: 0.0,
                eta: c,
                phi: 0.0,
            })?;
            fy.push((c, t.fy / (mu * t.fn_)));
        }
        Ok(CreepCurve {
            model: options.model,
            tangential: runner.tangential(),
            fx,
            fy,
        })
    }
}

impl Runner {
    /// The values the next solve reads (its inputs: pose, loads, creepages).
    pub fn values_mut(&mut self) -> &mut Values {
        &mut self.values
    }

    /// The wheelset (its geometry and strip patches after the last solve).
    pub fn wheelset(&self) -> &Wheelset {
        &self.wheelset
    }

    pub fn solve(&mut self) -> Result<WheelsetResult, Failure> {
        let input = wrc::input(
            &self.values,
            self.values.integer(var::verticalMode) == 2,
            self.values.integer(var::creepageMode) == 2,
        );
        let mut result = WheelsetResult::default();
        self.wheelset
            .solve(&input, &mut result)
            .map_err(solve_error)?;
        Ok(result)
    }

    /// Switches to prescribed creepages `c` at the patch (`creepageMode` = 2).
    pub fn prescribe(&mut self, c: Creepage) {
        self.values.set_integer(var::creepageMode, 2);
        self.values.set_real(var::xi, c.xi);
        self.values.set_real(var::eta, c.eta);
        self.values.set_real(var::phi, c.phi);
    }

    /// The right wheel's totals at prescribed creepages `c`.
    pub fn totals_at(&mut self, c: Creepage) -> Result<Totals, Failure> {
        self.prescribe(c);
        Ok(totals(&self.solve()?.right))
    }

    pub fn tangential(&self) -> TangentialModel {
        self.wheelset.settings().tangential
    }

    pub fn planar(&self) -> bool {
        self.wheelset.settings().planar_patch
    }

    /// The right wheel's strips after the last solve.
    fn normal_run(&self, side: &SideResult) -> NormalRun {
        let settings = self.wheelset.settings();
        let model = settings.normal_model;
        let strip_patches: Vec<&StripPatch> = self
            .wheelset
            .strip_patches(true)
            .iter()
            .filter(|p| p.summary().in_contact())
            .collect();
        let patches: Vec<Vec<StripRow>> = if model == NormalModel::Hertz {
            side.shown_patches().map(ellipse_strips).collect()
        } else {
            let params = NormalParams {
                e_star: contact_modulus(
                    settings.material.youngs_modulus,
                    settings.material.poisson_ratio,
                ),
                b_min: settings.b_min,
                b_smoothing: settings.b_smoothing,
                kp_shape_correction: settings.kp_shape_correction,
            };
            strip_patches
                .iter()
                .map(|p| patch_strips(p, model_curvature(model, p, &params)))
                .collect()
        };
        let mut profile: Vec<(f64, f64)> = if model == NormalModel::Hertz {
            patches
                .iter()
                .flatten()
                .map(|s: &StripRow| (s.y_rail, s.pmax))
                .collect()
        } else {
            self.wheelset
                .strip_patches(true)
                .iter()
                .flat_map(|p| (0..p.geom.len()).map(move |i| (p.points.y_rail[i], p.sol.pmax[i])))
                .collect()
        };
        profile.sort_by(|a, b| a.0.total_cmp(&b.0));
        NormalRun {
            model,
            patches,
            profile,
            totals: totals(side),
        }
    }
}

/// The FMU code of a tangential option.
pub fn tangential_code(t: TangentialModel) -> i32 {
    TangentialModel::ALL
        .iter()
        .position(|&m| m == t)
        .map_or(1, |i| i as i32 + 1)
}

/// Totals of a wheel's patches.
pub fn totals(side: &SideResult) -> Totals {
    let patches = side.all_patches();
    let area: f64 = patches.iter().map(|p| p.area).sum();
    Totals {
        fn_: patches.iter().map(|p| p.fn_).sum(),
        fx: patches.iter().map(|p| p.fx).sum(),
        fy: patches.iter().map(|p| p.fy).sum(),
        mz: patches.iter().map(|p| p.mz).sum(),
        area,
        pmax: patches.iter().map(|p| p.pmax).fold(0.0, f64::max),
        adhesion: if area > 0.0 {
            patches
                .iter()
                .map(|p| p.adhesion_fraction * p.area)
                .sum::<f64>()
                / area
        } else {
            0.0
        },
    }
}

/// B per strip as a STRIPES model uses it (the model prepared on the patch's final strips),
/// `None` for the other models.
fn model_curvature(model: NormalModel, p: &StripPatch, params: &NormalParams) -> Option<Vec<f64>> {
    let table = || HertzShapeTable::new();
    match model {
        NormalModel::StripesB => {
            let mut m = StripesB::default();
            m.prepare(&p.geom, params, &table());
            Some(m.curv_b().to_vec())
        }
        NormalModel::StripesAB => {
            let mut m = StripesAB::default();
            m.prepare(&p.geom, params, &table());
            Some(m.curv_b().to_vec())
        }
        _ => None,
    }
}

/// The strips in contact of a strip patch.
fn patch_strips(p: &StripPatch, b_model: Option<Vec<f64>>) -> Vec<StripRow> {
    let n = p.geom.len();
    let mut rows: Vec<StripRow> = (0..n)
        .filter(|&i| p.sol.half_length[i] > 0.0)
        .map(|i| StripRow {
            y_rail: p.points.y_rail[i],
            x_lead: p.geom.x_c[i] + p.sol.half_length[i],
            x_trail: p.geom.x_c[i] - p.sol.half_length[i],
            pmax: p.sol.pmax[i],
            b_raw: p.geom.curv_b[i],
            b_model: b_model.as_ref().and_then(|b| b.get(i).copied()),
        })
        .collect();
    rows.sort_by(|a, b| a.y_rail.total_cmp(&b.y_rail));
    rows
}

/// A Hertz patch's ellipse as a strip table of [`ELLIPSE_POINTS`] points across it, ends
/// included (lateral position y_rail + s cos γ, as `railcontact solve` tabulates it).
fn ellipse_strips(p: &PatchResult) -> Vec<StripRow> {
    let cos_g = p.contact_angle.cos();
    (0..ELLIPSE_POINTS)
        .map(|k| {
            let u = 2.0 * k as f64 / (ELLIPSE_POINTS - 1) as f64 - 1.0;
            let root = (1.0 - u * u).max(0.0).sqrt();
            StripRow {
                y_rail: p.y_rail + p.b * u * cos_g,
                x_lead: p.a * root,
                x_trail: -p.a * root,
                pmax: p.pmax * root,
                b_raw: p.curv_b,
                b_model: None,
            }
        })
        .collect()
}

/// The elements of a traction field as rectangles: each strip (elements sharing `s`) spans half
/// the distance to its neighbours in `y_rail`, each element half the spacing to its neighbours
/// along x (uniform within a strip).
pub fn cells(field: &[TractionElement]) -> Vec<Cell> {
    let mut strips: Vec<Vec<&TractionElement>> = Vec::new();
    let mut sorted: Vec<&TractionElement> = field.iter().collect();
    sorted.sort_by(|a, b| a.s.total_cmp(&b.s).then(a.x.total_cmp(&b.x)));
    for e in sorted {
        match strips.last_mut() {
            Some(strip) if strip[0].s == e.s => strip.push(e),
            _ => strips.push(vec![e]),
        }
    }
    let ys: Vec<f64> = strips.iter().map(|s| s[0].y_rail).collect();
    let half_widths = half_spacings(&ys);
    let mut out = Vec::with_capacity(field.len());
    for (strip, (&y, &hw)) in strips.iter().zip(ys.iter().zip(&half_widths)) {
        let xs: Vec<f64> = strip.iter().map(|e| e.x).collect();
        let hx = half_spacings(&xs);
        for (e, &h) in strip.iter().zip(&hx) {
            // A single element: as long as it is wide.
            let h = if xs.len() == 1 { hw } else { h };
            out.push(Cell {
                y0: y - hw,
                y1: y + hw,
                x0: e.x - h,
                x1: e.x + h,
                px: e.px,
                py: e.py,
                traction: e.px.hypot(e.py),
                slip: e.slipping,
            });
        }
    }
    out
}

/// Area-weighted centroid (yRail, x) [m] of the slipping cells, `None` if none slips.
pub fn slip_centroid(cells: &[Cell]) -> Option<(f64, f64)> {
    let (mut a, mut y, mut x) = (0.0, 0.0, 0.0);
    for c in cells.iter().filter(|c| c.slip) {
        let area = ((c.y1 - c.y0) * (c.x1 - c.x0)).abs();
        a += area;
        y += area * 0.5 * (c.y0 + c.y1);
        x += area * 0.5 * (c.x0 + c.x1);
    }
    (a > 0.0).then(|| (y / a, x / a))
}

/// Half the spacing around each of the sorted `values`: the mean of the half-distances to both
/// neighbours (one neighbour at the ends; 0 for a single value).
pub fn half_spacings(values: &[f64]) -> Vec<f64> {
    let n = values.len();
    (0..n)
        .map(|i| {
            let left = (i > 0).then(|| values[i] - values[i - 1]);
            let right = (i + 1 < n).then(|| values[i + 1] - values[i]);
            match (left, right) {
                (Some(l), Some(r)) => 0.25 * (l + r),
                (Some(d), None) | (None, Some(d)) => 0.5 * d,
                (None, None) => 0.0,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spacings_of_a_uniform_grid() {
        assert_eq!(half_spacings(&[0.0, 1.0, 2.0]), vec![0.5, 0.5, 0.5]);
        assert_eq!(half_spacings(&[3.0]), vec![0.0]);
        assert!(half_spacings(&[]).is_empty());
    }

    #[test]
    fn ellipse_strips_close_at_the_ends() {
        let p = PatchResult {
            a: 0.006,
            b: 0.004,
            pmax: 1e9,
            y_rail: -0.01,
            ..PatchResult::default()
        };
        let s = ellipse_strips(&p);
        assert_eq!(s.len(), ELLIPSE_POINTS);
        assert!(s[0].x_lead.abs() < 1e-12 && s[ELLIPSE_POINTS - 1].pmax.abs() < 1e-3);
        let mid = s[ELLIPSE_POINTS / 2];
        assert!((mid.x_lead - 0.006).abs() < 1e-15 && (mid.y_rail + 0.01).abs() < 1e-15);
        assert!((s[0].y_rail - (-0.014)).abs() < 1e-15);
    }

    #[test]
    fn cells_cover_each_strip() {
        let e = |s: f64, x: f64, slipping| TractionElement {
            x,
            s,
            y_rail: s,
            px: 3.0,
            py: 4.0,
            pn: 1.0,
            slipping,
        };
        let field = [e(0.0, -1.0, true), e(0.0, 1.0, false), e(2.0, 0.0, false)];
        let c = cells(&field);
        assert_eq!(c.len(), 3);
        assert_eq!((c[0].y0, c[0].y1, c[0].x0, c[0].x1), (-1.0, 1.0, -2.0, 0.0));
        assert_eq!(c[0].traction, 5.0);
        assert!(c[0].slip && !c[1].slip);
        // The single element of the second strip is as long as its strip is wide.
        assert_eq!((c[2].x0, c[2].x1), (-1.0, 1.0));
        assert_eq!(slip_centroid(&c), Some((0.0, -1.0)));
        assert_eq!(slip_centroid(&c[1..]), None);
    }
}
