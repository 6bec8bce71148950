//! The report's frictional power density across the patch — where on the profiles the energy
//! that wears them is dissipated — of every normal model (its own tangential pairing) against
//! the exact steady rolling solution, at lateral shifts [`SHIFTS_MM`].
//!
//! * **Creepages**: ξ = [`XI`] with the rolling spin sin γ / r0 of the exact plane (r0 = 0.46 m),
//!   prescribed at the patch (as CONTACT prescribes them at its reference point): partial slip,
//!   where the distribution of the slip matters.
//! * **Exact**: Kalker's planar problem on the exact pressure (0.2 mm normal solution) solved on
//!   0.4 mm elements (the finest of `ExactWheel::planar_t_gamma`); per element row the
//!   dissipation −Σ q·s ΔA over the row's width, at the row's rail point. Its total is low by a
//!   first-order discretisation term (docs/theory.md §4.5): the figure shows the shape, the
//!   table the totals.
//! * **Models**: the patch's elements with the slip the damage outputs use
//!   (`Wheelset::friction_field`), Σ |q| |s| ΔA per strip over the strip's width, at the strip's
//!   rail point.
//!
//! Density in N/mm: dissipation per metre rolled and per millimetre of the profile (Tγ per unit
//! width).

use super::plot::model_label;
use super::study::{Options, Study};
use crate::Failure;
use railcontact::models::wheel_rail_contact::generated::var;
use railcontact::normal::NormalModel;
use railcontact::tangential::fastsim::Creepage;
use railcontact::tangential::patch::TangentialModel;
use railcontact_halfspace::wheel_rail::ExactWheel;
use railcontact_halfspace::{Grid, RollingSolution};
use std::fmt::Write as _;

/// Lateral shifts of the comparison [mm].
pub const SHIFTS_MM: [f64; 2] = [0.0, 2.0];
/// Longitudinal creepage of the comparison [-].
pub const XI: f64 = 0.002;
/// Nominal rolling radius of the rolling spin [m].
const R0: f64 = 0.46;
/// Element size of the exact normal solution [m].
const NORMAL_ELEMENT: f64 = 0.2e-3;

/// A dissipation profile across a patch: (yRail [mm], density [N/mm]) and its total Tγ [N].
#[derive(Debug, Clone, Default)]
pub struct Profile {
    pub points: Vec<(f64, f64)>,
    pub t_gamma: f64,
}

/// One model's profile.
#[derive(Debug, Clone)]
pub struct ModelProfile {
    pub model: NormalModel,
    pub profile: Profile,
}

/// One shift: the creepages, the exact profile and the models'.
#[derive(Debug, Clone)]
pub struct Panel {
    pub shift_mm: f64,
    pub creepage: Creepage,
    /// The exact profile on 0.4 mm elements and the exact Tγ on CONTACT's
    /// (`ExactWheel::planar_t_gamma`) [N].
    pub exact: Profile,
    pub exact_t_gamma: f64,
    pub models: Vec<ModelProfile>,
}

/// Every panel of the figure (one per shift of [`SHIFTS_MM`]).
pub fn panels(study: &Study) -> Result<Vec<Panel>, Failure> {
    SHIFTS_MM.iter().map(|&s| panel(study, s)).collect()
}

fn panel(study: &Study, shift_mm: f64) -> Result<Panel, Failure> {
    let v = study.values();
    let (e, nu, load) = (v.real(var::E), v.real(var::nu), v.real(var::Qright));
    let g = e / (2.0 * (1.0 + nu));
    let y = shift_mm * 1e-3;
    // The exact wheel from the coupled strips' lowering at zero creepage.
    let mut runner = study.runner(Options {
        tangential: Some(TangentialModel::ModelDefault),
        planar: Some(true),
        ..Options::normal(NormalModel::CoupledStrips)
    })?;
    runner.values_mut().set_real(var::y, y);
    runner.prescribe(Creepage::default());
    let out = runner.solve()?;
    let exact = ExactWheel::solve(
        runner.wheelset().geometry(true),
        out.right.z,
        load,
        NORMAL_ELEMENT,
        (e, nu),
    )
    .map_err(|e| Failure::Error(format!("exact solution of the wheel: {e:?}")))?;
    let creepage = Creepage {
        xi: XI,
        eta: 0.0,
        phi: exact.reference.angle.sin() / R0,
    };
    let estimate = exact
        .planar_t_gamma(
            (creepage.xi, creepage.eta, creepage.phi),
            (g, nu, study.mu()),
        )
        .map_err(|e| Failure::Error(format!("exact rolling solution: {e:?}")))?;
    let exact_t_gamma = estimate.t_gamma;
    let (grid, solution) = &estimate.finest;
    let exact_profile = exact_profile(&exact, grid, solution);
    let models = NormalModel::ALL
        .iter()
        .map(|&model| {
            let mut runner = study.runner(Options {
                tangential: Some(TangentialModel::ModelDefault),
                ..Options::normal(model)
            })?;
            runner.values_mut().set_real(var::y, y);
            runner.prescribe(creepage);
            let out = runner.solve()?;
            let ws = runner.wheelset();
            let mut profile = Profile::default();
            for slot in 0..out.right.patches.len() {
                if let Some(field) = ws.friction_field(true, slot) {
                    add_field(&mut profile, &field);
                }
            }
            profile.points.sort_by(|a, b| a.0.total_cmp(&b.0));
            Ok(ModelProfile { model, profile })
        })
        .collect::<Result<_, Failure>>()?;
    Ok(Panel {
        shift_mm,
        creepage,
        exact: exact_profile,
        exact_t_gamma,
        models,
    })
}

/// The exact dissipation per row of the rolling solution `sol` on `grid`.
fn exact_profile(exact: &ExactWheel, grid: &Grid, sol: &RollingSolution) -> Profile {
    let fine = &exact.grid;
    let mut profile = Profile {
        t_gamma: sol.t_gamma,
        points: Vec::new(),
    };
    for j in 0..grid.ny {
        let row = j * grid.nx..(j + 1) * grid.nx;
        let dissipated: f64 = row
            .map(|k| -(sol.traction_x[k] * sol.slip_x[k] + sol.traction_y[k] * sol.slip_y[k]))
            .sum::<f64>()
            * grid.element_area();
        // The row's rail point: the fine row at its centre.
        let fine_row = (((grid.y(j) - fine.y0) / fine.dy) as usize).min(fine.ny - 1);
        let y_rail = exact.rows.y_rail[fine_row];
        profile
            .points
            .push((y_rail * 1e3, dissipated / (grid.dy * 1e3)));
    }
    profile
}

/// Adds a model field's strips (consecutive elements of one rail point) to `profile`: each
/// strip's Σ |q| |s| ΔA over its width, the spacing of the strips' lateral coordinates.
fn add_field(
    profile: &mut Profile,
    field: &[(f64, railcontact::tangential::fastsim::FrictionElement)],
) {
    // (yRail, lateral, dissipated) per strip.
    let mut strips: Vec<(f64, f64, f64)> = Vec::new();
    for (y_rail, e) in field {
        let dissipated = e.traction_sq.sqrt() * e.slip * e.area;
        match strips.last_mut() {
            Some(s) if s.0 == *y_rail && s.1 == e.lateral => s.2 += dissipated,
            _ => strips.push((*y_rail, e.lateral, dissipated)),
        }
    }
    for (j, s) in strips.iter().enumerate() {
        let before = j.checked_sub(1).map(|i| strips[i].1);
        let after = strips.get(j + 1).map(|t| t.1);
        let width = match (before, after) {
            (Some(b), Some(a)) => 0.5 * (a - b).abs(),
            (Some(b), None) => (s.1 - b).abs(),
            (None, Some(a)) => (a - s.1).abs(),
            (None, None) => continue,
        };
        if width > 0.0 {
            profile.t_gamma += s.2;
            profile.points.push((s.0 * 1e3, s.2 / (width * 1e3)));
        }
    }
}

/// The document's section: what the figure shows and each model's Tγ against the exact one.
pub fn section(panels: &[Panel]) -> String {
    let mut md = String::from("\n## Frictional power across the patch\n\n");
    md.push_str(
        "Where the energy that wears the profiles is dissipated: each normal model with its own \
         tangential pairing (`tangentialModel` 1; the slip field the damage outputs use) against \
         the exact steady rolling solution on the exact pressure (Kalker's planar problem, \
         creepages prescribed at the patch), at ξ = 0.002 with the rolling spin sin γ / r0. The \
         figure (last below) shows the density across the profile; the exact field on 0.4 mm \
         elements is low by the first-order term of docs/theory.md §4.5, so its total is taken \
         from 0.4, 0.6 and 0.8 mm extrapolated to CONTACT's 0.2 mm. Tγ = −(ξFx + ηFy + φMz) \
         per metre rolled [N]:\n\n",
    );
    md.push_str("| model |");
    for p in panels {
        let _ = write!(md, " y = {} mm: Tγ [N] | error |", p.shift_mm);
    }
    md.push_str("\n|---|");
    for _ in panels {
        md.push_str("---:|---:|");
    }
    md.push_str("\n| exact half-space |");
    for p in panels {
        let _ = write!(md, " {:.2} | |", p.exact_t_gamma);
    }
    md.push('\n');
    let models = panels.first().map_or(&[][..], |p| &p.models[..]);
    for (k, m) in models.iter().enumerate() {
        let _ = write!(md, "| {} |", model_label(m.model));
        for p in panels {
            let t = p.models[k].profile.t_gamma;
            let _ = write!(
                md,
                " {t:.2} | {:+.1} % |",
                100.0 * (t / p.exact_t_gamma - 1.0)
            );
        }
        md.push('\n');
    }
    md.push('\n');
    md
}
