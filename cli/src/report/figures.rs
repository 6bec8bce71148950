//! The report's figures, each a [`ReportFigure`] drawn from the model runs of [`super::study`]
//! and the CONTACT data of [`super::reference`] (optional: without it the models are drawn
//! alone):
//!
//! * [`Outlines`] — patch outlines (leading and trailing edge per strip, x against yRail) of every
//!   normal model over CONTACT's (as Sichani et al. 2014, Fig. 2);
//! * [`Pressure`] — the maximum pressure per strip along yRail (as Sichani et al. 2014, Fig. 3);
//! * [`Spin`] — |tangential traction| and slip elements in pure spin, one panel per model, planar
//!   or non-planar patches (as Sichani et al. 2014, Fig. 4);
//! * [`Shifts`] — outline, strip pressure and lateral curvature B of both STRIPES variants at
//!   several lateral shifts (as Sichani et al. 2014, Fig. 5);
//! * [`Creep`] — creep-force curves Fx(ξ), Fy(η) over μN per normal model and tangential option;
//! * [`Dissipation`] — frictional power density across the patch against the exact rolling
//!   solution ([`super::dissipation`]).
//!
//! Lateral axis: the right rail's `yRail` in mm, positive towards the field side (CONTACT's
//! right-rail coordinate is the same axis, docs/conventions.md); x along the rolling direction,
//! leading edge at positive x. Pressures and tractions in MPa.

use super::dissipation::Panel;
use super::plot::{
    banded_colour, colour_bar, curve, fail, filled, legend, legend_height, model_colour,
    model_label, outline, padded_range, panel, title, with_legend, Axes, Chart, Figure,
    LegendEntry, LineKind, Look, Marker, AUX_COLOUR, COLOUR_LEVELS, FONT, REFERENCE_COLOUR,
};
use super::reference::{RefStrip, Reference};
use super::study::{Cell, CreepCurve, NormalRun, SpinRun, StripRow};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use railcontact::normal::NormalModel;
use railcontact::tangential::patch::TangentialModel;

/// Metres → millimetres.
const TO_MM: f64 = 1e3;
/// Pascal → megapascal.
const TO_MPA: f64 = 1e-6;
/// Height of a figure's title strip [px].
const TITLE_H: u32 = 44;
/// Height of a row heading [px].
const HEADING_H: u32 = 28;

const Y_RAIL_LABEL: &str = "yRail [mm]  (right rail, + towards the field side)";
const X_LABEL: &str = "x [mm]  (rolling direction)";

/// The label of CONTACT's solution.
const CONTACT: &str = "CONTACT (exact half-space)";

fn reference_look() -> Look {
    Look::solid(REFERENCE_COLOUR, 2)
}

fn model_look(model: NormalModel) -> Look {
    Look::solid(model_colour(model), 2)
}

/// A model variant's look: its colour, dashed.
fn unsmoothed_look(model: NormalModel) -> Look {
    model_look(model).with(LineKind::Dashed, Marker::None)
}

/// A patch's outline as a polygon in (yRail, x) [mm]: leading edges in increasing yRail, then the
/// trailing edges back.
pub fn outline_points(strips: &[StripRow]) -> Vec<(f64, f64)> {
    let lead = strips.iter().map(|s| (s.y_rail * TO_MM, s.x_lead * TO_MM));
    let trail = strips
        .iter()
        .rev()
        .map(|s| (s.y_rail * TO_MM, s.x_trail * TO_MM));
    lead.chain(trail).collect()
}

/// CONTACT's outline in (yRail, x) [mm].
pub fn reference_outline(strips: &[RefStrip]) -> Vec<(f64, f64)> {
    let lead = strips.iter().map(|s| (s.y_rail_mm, s.x_max_mm));
    let trail = strips.iter().rev().map(|s| (s.y_rail_mm, s.x_min_mm));
    lead.chain(trail).collect()
}

/// Strip maxima of a patch in (yRail [mm], pmax [MPa]).
fn pressure_points(strips: &[StripRow]) -> Vec<(f64, f64)> {
    strips
        .iter()
        .map(|s| (s.y_rail * TO_MM, s.pmax * TO_MPA))
        .collect()
}

fn reference_pressure(strips: &[RefStrip]) -> Vec<(f64, f64)> {
    strips.iter().map(|s| (s.y_rail_mm, s.pmax_mpa)).collect()
}

/// A signed percentage for captions, e.g. "+3.1 %".
fn percent(value: f64, reference: f64) -> String {
    format!("{:+.1} %", 100.0 * (value / reference - 1.0))
}

/// Axes in (yRail, x) [mm] that hold every outline of `runs` and the reference's.
fn outline_axes(runs: &[&NormalRun], reference: Option<&[RefStrip]>) -> Axes {
    let mut ys = Vec::new();
    let mut xs = Vec::new();
    for run in runs {
        for strips in &run.patches {
            for (y, x) in outline_points(strips) {
                ys.push(y);
                xs.push(x.abs());
            }
        }
    }
    for (y, x) in reference.map(reference_outline).unwrap_or_default() {
        ys.push(y);
        xs.push(x.abs());
    }
    let x_max = xs.iter().copied().fold(1.0, f64::max) * 1.15;
    Axes {
        x: padded_range(ys, 0.04),
        y: (-x_max, x_max),
        x_label: Y_RAIL_LABEL.to_string(),
        y_label: X_LABEL.to_string(),
    }
}

/// Draws CONTACT's outline filled light grey with a black edge.
fn draw_reference_outline<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    strips: &[RefStrip],
) -> Result<(), String> {
    let points = reference_outline(strips);
    filled(chart, &points, REFERENCE_COLOUR.mix(0.12))?;
    outline(chart, &points, reference_look())
}

fn model_entries(models: impl IntoIterator<Item = NormalModel>) -> Vec<LegendEntry> {
    models
        .into_iter()
        .map(|m| LegendEntry::line(model_label(m), model_look(m)))
        .collect()
}

/// Legend: CONTACT's line (where the reference is drawn), then the model of each of `runs`.
fn runs_legend(reference: Option<&Reference>, runs: &[NormalRun]) -> Vec<LegendEntry> {
    let contact = reference.map(|_| LegendEntry::line(CONTACT, reference_look()));
    let models = model_entries(runs.iter().map(|r| r.model));
    contact.into_iter().chain(models).collect()
}

/// Draws the outline of every patch of `run` in its model's look.
fn draw_outlines<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    run: &NormalRun,
) -> Result<(), String> {
    for strips in &run.patches {
        outline(chart, &outline_points(strips), model_look(run.model))?;
    }
    Ok(())
}

/// Draws the strip maxima of every patch of `run` in `look`.
fn draw_pressures<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    run: &NormalRun,
    look: Look,
) -> Result<(), String> {
    for strips in &run.patches {
        curve(chart, &pressure_points(strips), look)?;
    }
    Ok(())
}

/// Draws CONTACT's outline as a thin edge (over traction cells).
fn draw_reference_edge<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    r: &Reference,
) -> Result<(), String> {
    outline(
        chart,
        &reference_outline(&r.strips),
        Look::solid(REFERENCE_COLOUR, 1),
    )
}

// ---------------------------------------------------------------------------------------------
// The figures

/// The report's figures: each one's file name, size and title, and its drawing below the title.
pub enum ReportFigure<'a> {
    Outlines(Outlines<'a>),
    Pressure(Pressure<'a>),
    Spin(Spin<'a>),
    Shifts(Shifts<'a>),
    Creep(Creep<'a>),
    Dissipation(Dissipation<'a>),
}

impl ReportFigure<'_> {
    fn title(&self) -> String {
        match self {
            Self::Outlines(f) => format!("Contact patch outlines, {}", f.setup),
            Self::Pressure(f) => format!("Maximum pressure per strip, {}", f.setup),
            Self::Spin(f) => f.title(),
            Self::Shifts(f) => format!(
                "STRIPES-B and STRIPES-A&B over the lateral shift y of the wheelset, {}",
                f.setup
            ),
            Self::Creep(f) => format!(
                "Creep-force curves, planar patches, creepages prescribed, {}",
                f.setup
            ),
            Self::Dissipation(f) => format!(
                "Frictional power density across the patch, creepages prescribed, {}",
                f.setup
            ),
        }
    }
}

impl Figure for ReportFigure<'_> {
    fn name(&self) -> &str {
        match self {
            Self::Outlines(_) => "patch_outlines",
            Self::Pressure(_) => "pressure_per_strip",
            Self::Spin(f) if f.planar => "pure_spin_planar",
            Self::Spin(_) => "pure_spin_nonplanar",
            Self::Shifts(_) => "lateral_shifts",
            Self::Creep(_) => "creep_curves",
            Self::Dissipation(_) => "power_density",
        }
    }

    fn size(&self) -> (u32, u32) {
        match self {
            Self::Outlines(_) => (1350, 800),
            Self::Pressure(_) => (1100, 680),
            Self::Spin(_) => (1300, 1200),
            Self::Shifts(_) => (1600, 1050),
            Self::Creep(f) => (1300, 560 * f.rows.len().max(1) as u32 + TITLE_H),
            Self::Dissipation(_) => (1500, 700),
        }
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let area = title(root, &self.title(), TITLE_H)?;
        match self {
            Self::Outlines(f) => f.draw(&area),
            Self::Pressure(f) => f.draw(&area),
            Self::Spin(f) => f.draw(&area),
            Self::Shifts(f) => f.draw(&area),
            Self::Creep(f) => f.draw(&area),
            Self::Dissipation(f) => f.draw(&area),
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Patch outlines

/// Patch outlines of every normal model (one panel each) over CONTACT's.
pub struct Outlines<'a> {
    pub runs: &'a [NormalRun],
    pub reference: Option<&'a Reference>,
    pub setup: String,
}

impl Outlines<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let panels = with_legend(area, &runs_legend(self.reference, self.runs))?;
        let strips = self.reference.map(|r| r.strips.as_slice());
        let runs: Vec<&NormalRun> = self.runs.iter().collect();
        let axes = outline_axes(&runs, strips);
        let cols = 3;
        let rows = self.runs.len().div_ceil(cols).max(1);
        for (run, area) in self.runs.iter().zip(panels.split_evenly((rows, cols))) {
            let t = &run.totals;
            let mut caption = format!(
                "{}: {:.1} mm², pmax {:.0} MPa",
                model_label(run.model),
                t.area * TO_MM * TO_MM,
                t.pmax * TO_MPA
            );
            if let Some(r) = self.reference {
                caption = format!(
                    "{} — area {}, pmax {}",
                    model_label(run.model),
                    percent(t.area * TO_MM * TO_MM, r.normal.area_mm2),
                    percent(t.pmax * TO_MPA, r.normal.pmax_mpa)
                );
            }
            let mut chart = panel(&area, &caption, &axes)?;
            if let Some(s) = strips {
                draw_reference_outline(&mut chart, s)?;
            }
            draw_outlines(&mut chart, run)?;
        }
        Ok(())
    }
}

// ---------------------------------------------------------------------------------------------
// Pressure per strip

/// Maximum pressure per strip along yRail, every model and CONTACT in one panel.
pub struct Pressure<'a> {
    pub runs: &'a [NormalRun],
    /// STRIPES-B without smoothing of B (drawn dashed in its colour), if the case smooths.
    pub unsmoothed: Option<&'a NormalRun>,
    pub reference: Option<&'a Reference>,
    pub setup: String,
}

impl Pressure<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let mut entries = runs_legend(self.reference, self.runs);
        if let Some(run) = self.unsmoothed {
            entries.push(LegendEntry::line(
                format!(
                    "{} without smoothing of B (bSmoothing = 0)",
                    model_label(run.model)
                ),
                unsmoothed_look(run.model),
            ));
        }
        let area = with_legend(area, &entries)?;
        let strips = self.reference.map(|r| r.strips.as_slice());
        let mut ys = Vec::new();
        let mut ps = vec![0.0];
        for run in self.runs.iter().chain(self.unsmoothed) {
            for patch in &run.patches {
                for (y, p) in pressure_points(patch) {
                    ys.push(y);
                    ps.push(p);
                }
            }
        }
        for (y, p) in strips.map(reference_pressure).unwrap_or_default() {
            ys.push(y);
            ps.push(p);
        }
        let p_max = ps.iter().copied().fold(0.0, f64::max);
        let axes = Axes {
            x: padded_range(ys, 0.04),
            y: (0.0, 1.08 * p_max.max(1.0)),
            x_label: Y_RAIL_LABEL.to_string(),
            y_label: "strip maximum pressure [MPa]".to_string(),
        };
        let mut chart = panel(&area, "", &axes)?;
        if let Some(s) = strips {
            curve(
                &mut chart,
                &reference_pressure(s),
                Look::solid(REFERENCE_COLOUR, 3),
            )?;
        }
        for run in self.runs {
            draw_pressures(&mut chart, run, model_look(run.model))?;
        }
        if let Some(run) = self.unsmoothed {
            draw_pressures(&mut chart, run, unsmoothed_look(run.model))?;
        }
        Ok(())
    }
}

// ---------------------------------------------------------------------------------------------
// Pure spin

/// Tangential traction of pure spin: CONTACT's and one panel per model.
pub struct Spin<'a> {
    pub runs: &'a [SpinRun],
    pub reference: Option<&'a Reference>,
    /// Planar (`planarPatch` = true) or non-planar patches: names the file and the title.
    pub planar: bool,
    /// Upper end of the colour scale [MPa] (shared by both spin figures).
    pub scale_mpa: f64,
    pub axes: Axes,
}

/// Axes in (yRail, x) [mm] holding every traction field of `runs` and CONTACT's.
pub fn spin_axes(runs: &[SpinRun], reference: Option<&Reference>) -> Axes {
    let normal: Vec<&NormalRun> = runs.iter().map(|r| &r.normal).collect();
    let mut axes = outline_axes(&normal, reference.map(|r| r.strips.as_slice()));
    let (mut lo, mut hi) = axes.x;
    for c in runs.iter().flat_map(|r| &r.cells) {
        lo = lo.min(c.y0 * TO_MM);
        hi = hi.max(c.y1 * TO_MM);
    }
    axes.x = (lo, hi);
    axes
}

/// The largest |traction| of the spin runs and CONTACT's [MPa].
pub fn spin_scale(runs: &[SpinRun], reference: Option<&Reference>) -> f64 {
    let models = runs
        .iter()
        .flat_map(|r| &r.cells)
        .map(|c| c.traction * TO_MPA);
    let contact = reference
        .into_iter()
        .flat_map(|r| &r.traction)
        .map(|e| e.px_mpa.hypot(e.ps_mpa));
    models.chain(contact).fold(1.0, f64::max)
}

/// A run of cells of one strip with the same colour level: (y0, y1, x0, x1) [mm] and level.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Band {
    y: (f64, f64),
    x: (f64, f64),
    level: usize,
}

/// The colour level of a traction [Pa] on a scale up to `scale_mpa`.
fn level(traction: f64, scale_mpa: f64) -> usize {
    let t = (traction * TO_MPA / scale_mpa).clamp(0.0, 1.0);
    ((t * COLOUR_LEVELS as f64).floor() as usize).min(COLOUR_LEVELS - 1)
}

/// Cells merged into bands: consecutive cells of a strip (same lateral extent, sorted along x,
/// touching) with the same colour level become one rectangle (fewer SVG elements, the same
/// picture).
fn bands(cells: &[Cell], scale_mpa: f64) -> Vec<Band> {
    let mut sorted: Vec<&Cell> = cells.iter().collect();
    sorted.sort_by(|a, b| {
        a.y0.total_cmp(&b.y0)
            .then(a.y1.total_cmp(&b.y1))
            .then(a.x0.total_cmp(&b.x0))
    });
    let mut out: Vec<Band> = Vec::new();
    for c in sorted {
        let band = Band {
            y: (c.y0 * TO_MM, c.y1 * TO_MM),
            x: (c.x0 * TO_MM, c.x1 * TO_MM),
            level: level(c.traction, scale_mpa),
        };
        match out.last_mut() {
            Some(last)
                if last.y == band.y
                    && last.level == band.level
                    && (band.x.0 - last.x.1).abs() <= 1e-6 * (1.0 + band.x.0.abs()) =>
            {
                last.x.1 = band.x.1;
            }
            _ => out.push(band),
        }
    }
    out
}

/// Filled traction cells (yRail, x in mm). Each band is drawn larger by 5 % of
/// its width on every side so that rounding to pixels leaves no gaps between neighbours.
fn draw_cells<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    cells: &[Cell],
    scale_mpa: f64,
) -> Result<(), String> {
    chart
        .draw_series(bands(cells, scale_mpa).into_iter().map(|b| {
            let pad = 0.05 * (b.y.1 - b.y.0);
            let (dy, dx) = (pad, pad);
            let t = (b.level as f64 + 0.5) / COLOUR_LEVELS as f64;
            Rectangle::new(
                [(b.y.0 - dy, b.x.0 - dx), (b.y.1 + dy, b.x.1 + dx)],
                banded_colour(t).filled(),
            )
        }))
        .map_err(fail)?;
    Ok(())
}

/// Marks the slipping cells with dots (drawn last, over the outlines).
fn draw_slip<DB: DrawingBackend>(chart: &mut Chart<'_, DB>, cells: &[Cell]) -> Result<(), String> {
    chart
        .draw_series(cells.iter().filter(|c| c.slip).map(|c| {
            let centre = (0.5 * (c.y0 + c.y1) * TO_MM, 0.5 * (c.x0 + c.x1) * TO_MM);
            EmptyElement::at(centre)
                + Circle::new((0, 0), 2, WHITE.filled())
                + Circle::new((0, 0), 2, BLACK.stroke_width(1))
        }))
        .map_err(fail)?;
    Ok(())
}

/// CONTACT's traction grid as cells (0.2 mm elements; lateral extent through the s → yRail map).
fn reference_cells(r: &Reference) -> Vec<Cell> {
    let half_s = 0.1;
    r.traction
        .iter()
        .map(|e| {
            let y0 = super::reference::y_rail_of_s(&r.strips, e.s_mm - half_s);
            let y1 = super::reference::y_rail_of_s(&r.strips, e.s_mm + half_s);
            Cell {
                y0: y0 / TO_MM,
                y1: y1 / TO_MM,
                x0: (e.x_mm - half_s) / TO_MM,
                x1: (e.x_mm + half_s) / TO_MM,
                px: e.px_mpa / TO_MPA,
                py: e.ps_mpa / TO_MPA,
                traction: e.px_mpa.hypot(e.ps_mpa) / TO_MPA,
                slip: e.slip,
            }
        })
        .collect()
}

/// Lateral and longitudinal size of the bins the traction arrows average over [mm].
const ARROW_BIN_MM: f64 = 1.5;
/// Length of the arrow of the colour scale's largest traction [px].
const ARROW_MAX_PX: f64 = 32.0;

/// Traction arrows: the cells' mean traction per [`ARROW_BIN_MM`] bin, drawn from the bin's
/// mean cell centre in pixels (the panel's axes have different scales), x (rolling direction)
/// up and the lateral traction (towards the field side) to the right.
fn draw_arrows<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    cells: &[Cell],
    scale_mpa: f64,
) -> Result<(), String> {
    use std::collections::BTreeMap;
    // Bin → (Σ area, Σ area·y, Σ area·x, Σ area·px, Σ area·py) in mm and MPa.
    let mut bins: BTreeMap<(i64, i64), [f64; 5]> = BTreeMap::new();
    for c in cells {
        let (y, x) = (0.5 * (c.y0 + c.y1) * TO_MM, 0.5 * (c.x0 + c.x1) * TO_MM);
        let area = ((c.y1 - c.y0) * (c.x1 - c.x0)).abs() * TO_MM * TO_MM;
        let key = (
            (y / ARROW_BIN_MM).floor() as i64,
            (x / ARROW_BIN_MM).floor() as i64,
        );
        let b = bins.entry(key).or_default();
        for (k, v) in [1.0, y, x, c.px * TO_MPA, c.py * TO_MPA].iter().enumerate() {
            b[k] += area * v;
        }
    }
    let style = WHITE.stroke_width(1);
    chart
        .draw_series(bins.values().filter(|b| b[0] > 0.0).map(|b| {
            let (y, x, px, py) = (b[1] / b[0], b[2] / b[0], b[3] / b[0], b[4] / b[0]);
            let t = px.hypot(py);
            let length = ARROW_MAX_PX * (t / scale_mpa).min(1.0);
            let (ux, uy) = if t > 0.0 {
                (py / t, -px / t)
            } else {
                (0.0, 0.0)
            };
            let tip = ((length * ux).round() as i32, (length * uy).round() as i32);
            let head = |angle: f64| {
                let (sin, cos) = angle.sin_cos();
                let h = 5.0_f64.min(0.5 * length);
                (
                    tip.0 - (h * (cos * ux - sin * uy)).round() as i32,
                    tip.1 - (h * (sin * ux + cos * uy)).round() as i32,
                )
            };
            EmptyElement::at((y, x))
                + PathElement::new(vec![(0, 0), tip], style)
                + PathElement::new(vec![head(0.5), tip, head(-0.5)], style)
        }))
        .map_err(fail)?;
    Ok(())
}

impl Spin<'_> {
    fn title(&self) -> String {
        let mode = if self.planar {
            "planar patches (planarPatch = true)"
        } else {
            "non-planar patches (planarPatch = false)"
        };
        let option = self
            .runs
            .iter()
            .find(|r| r.model != NormalModel::Hertz)
            .map_or_else(String::new, |r| format!(", {}", option_label(r.tangential)));
        format!("Pure spin φ = 0.052 rad/m (ξ = η = 0 prescribed), {mode}{option}")
    }

    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let mut entries = vec![
            LegendEntry::line(
                "slip element",
                Look::solid(BLACK, 1).with(LineKind::None, Marker::Circle),
            ),
            LegendEntry::line(
                "mean traction per 1.5 mm bin (white arrows)",
                Look::solid(AUX_COLOUR, 1),
            ),
        ];
        if self.reference.is_some() {
            entries.push(LegendEntry::line(
                "CONTACT patch outline",
                Look::solid(REFERENCE_COLOUR, 1),
            ));
        }
        entries.extend(model_entries(self.runs.iter().map(|r| r.model)));
        let panels = with_legend(area, &entries)?;
        let areas = panels.split_evenly((4, 2));
        let mut slots = areas.iter();
        let caption = |name: &str, fx: f64, fy: f64, mz: f64, slip: f64| {
            format!(
                "{name}: Fx {fx:.0} N, Fy {fy:.0} N, Mz {mz:.1} N·m, slip {:.1} %",
                100.0 * slip
            )
        };
        if let Some(r) = self.reference {
            let area = slots.next().ok_or("no panel for the reference")?;
            let s = &r.spin;
            let text = caption(
                "CONTACT",
                s.fx_n,
                s.fs_n,
                s.mn_nmm * 1e-3,
                1.0 - s.adhesion_fraction,
            );
            let mut chart = panel(area, &text, &self.axes)?;
            let cells = reference_cells(r);
            draw_cells(&mut chart, &cells, self.scale_mpa)?;
            draw_arrows(&mut chart, &cells, self.scale_mpa)?;
            draw_reference_edge(&mut chart, r)?;
            draw_slip(&mut chart, &cells)?;
        }
        for run in self.runs {
            let Some(area) = slots.next() else {
                break;
            };
            let t = &run.normal.totals;
            let name = if run.model == NormalModel::Hertz {
                "1 Hertz (ellipse, planar)".to_string()
            } else {
                model_label(run.model)
            };
            let text = caption(&name, t.fx, t.fy, t.mz, 1.0 - t.adhesion);
            let mut chart = panel(area, &text, &self.axes)?;
            draw_cells(&mut chart, &run.cells, self.scale_mpa)?;
            draw_arrows(&mut chart, &run.cells, self.scale_mpa)?;
            if let Some(r) = self.reference {
                draw_reference_edge(&mut chart, r)?;
            }
            draw_outlines(&mut chart, &run.normal)?;
            draw_slip(&mut chart, &run.cells)?;
        }
        if let Some(area) = slots.next() {
            let (w, _) = area.dim_in_pixel();
            let (bar, _) = area.split_horizontally(w.min(200));
            colour_bar(&bar, self.scale_mpa, "|traction| [MPa]")?;
        }
        Ok(())
    }
}

/// Short name of a tangential option with its code.
pub fn option_label(t: TangentialModel) -> String {
    let name = match t {
        TangentialModel::ModelDefault => "model's own FASTSIM",
        TangentialModel::EquivalentEllipse => "FASTSIM, equivalent ellipse",
        TangentialModel::Fastrip => "FaStrip",
        TangentialModel::LocalEllipses => "FASTSIM, local ellipses",
        TangentialModel::FastripCoupled => "FaStrip, coupled coefficients",
    };
    format!(
        "tangentialModel {}: {name}",
        super::study::tangential_code(t)
    )
}

// ---------------------------------------------------------------------------------------------
// Lateral shifts

/// Both STRIPES variants at one lateral shift.
pub struct ShiftRuns {
    /// Lateral shift of the wheelset [m].
    pub y: f64,
    pub runs: Vec<NormalRun>,
}

/// "y = +1 mm", "y = 0 mm" for a shift [m].
fn shift_label(y: f64) -> String {
    format!("y = {} mm", signed_mm(y))
}

/// A length [m] in mm with its sign ("+1", "-1.5", "0").
pub fn signed_mm(y: f64) -> String {
    let mm = (y * TO_MM * 1e6).round() / 1e6 + 0.0;
    if mm == 0.0 {
        "0".to_string()
    } else {
        format!("{mm:+}")
    }
}

/// Outline, strip pressure and curvature B of the STRIPES variants over lateral shifts.
pub struct Shifts<'a> {
    pub shifts: &'a [ShiftRuns],
    /// CONTACT's strips (drawn in the y = 0 column).
    pub reference: Option<&'a Reference>,
    pub setup: String,
}

impl Shifts<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let mut models: Vec<NormalModel> = Vec::new();
        for run in self.shifts.iter().flat_map(|s| &s.runs) {
            if !models.contains(&run.model) {
                models.push(run.model);
            }
        }
        let mut entries = Vec::new();
        if self.reference.is_some() {
            entries.push(LegendEntry::line(
                format!("{CONTACT} (y = 0 only)"),
                reference_look(),
            ));
        }
        entries.extend(model_entries(models.iter().copied()));
        entries.push(LegendEntry::line(
            "B of the geometry (before the models' rules)",
            Look::solid(AUX_COLOUR, 2).with(LineKind::Dashed, Marker::None),
        ));
        let panels = with_legend(area, &entries)?;
        let cols = self.shifts.len().max(1);
        let areas = panels.split_evenly((3, cols));
        for (c, shift) in self.shifts.iter().enumerate() {
            let reference = self
                .reference
                .filter(|_| shift.y.abs() < 1e-9)
                .map(|r| r.strips.as_slice());
            let runs: Vec<&NormalRun> = shift.runs.iter().collect();
            let mut axes = outline_axes(&runs, reference);
            let label = shift_label(shift.y);
            // Row 1: outlines.
            let mut chart = panel(&areas[c], &format!("{label}: patch outline"), &axes)?;
            if let Some(s) = reference {
                draw_reference_outline(&mut chart, s)?;
            }
            for run in &shift.runs {
                draw_outlines(&mut chart, run)?;
            }
            // Row 2: strip maxima.
            let p_max = shift
                .runs
                .iter()
                .flat_map(|r| r.patches.iter().flatten())
                .map(|s| s.pmax * TO_MPA)
                .chain(reference.into_iter().flatten().map(|s| s.pmax_mpa))
                .fold(1.0, f64::max);
            axes.y = (0.0, 1.08 * p_max);
            axes.y_label = "strip max. pressure [MPa]".to_string();
            let mut chart = panel(&areas[cols + c], &format!("{label}: pressure"), &axes)?;
            if let Some(s) = reference {
                curve(&mut chart, &reference_pressure(s), reference_look())?;
            }
            for run in &shift.runs {
                draw_pressures(&mut chart, run, model_look(run.model))?;
            }
            // Row 3: lateral curvature.
            let b_values = shift
                .runs
                .iter()
                .flat_map(|r| r.patches.iter().flatten())
                .flat_map(|s| [Some(s.b_raw), s.b_model])
                .flatten();
            let (lo, hi) = padded_range(b_values.chain([0.0]), 0.08);
            axes.y = (lo, hi);
            axes.y_label = "B [1/m]".to_string();
            let mut chart = panel(
                &areas[2 * cols + c],
                &format!("{label}: lateral curvature B"),
                &axes,
            )?;
            for run in &shift.runs {
                for strips in &run.patches {
                    let raw: Vec<(f64, f64)> =
                        strips.iter().map(|s| (s.y_rail * TO_MM, s.b_raw)).collect();
                    curve(
                        &mut chart,
                        &raw,
                        Look::solid(AUX_COLOUR, 2).with(LineKind::Dashed, Marker::None),
                    )?;
                    let used: Vec<(f64, f64)> = strips
                        .iter()
                        .filter_map(|s| s.b_model.map(|b| (s.y_rail * TO_MM, b)))
                        .collect();
                    curve(&mut chart, &used, model_look(run.model))?;
                }
            }
        }
        Ok(())
    }
}

// ---------------------------------------------------------------------------------------------
// Creep curves

/// Creep-force curves: one row per group of curves, Fx(ξ) and Fy(η) side by side.
pub struct Creep<'a> {
    /// Rows: (title, curves).
    pub rows: Vec<(String, Vec<&'a CreepCurve>)>,
    pub reference: Option<&'a Reference>,
    pub setup: String,
}

/// The look of a creep curve: its normal model's colour; in rows that compare tangential
/// options, the option's line and marker.
fn creep_look(c: &CreepCurve, by_option: bool) -> Look {
    let base = model_look(c.model);
    if !by_option || c.model == NormalModel::Hertz {
        return base;
    }
    match c.tangential {
        TangentialModel::ModelDefault => base.with(LineKind::Solid, Marker::Circle),
        TangentialModel::EquivalentEllipse => base.with(LineKind::Dashed, Marker::Triangle),
        TangentialModel::Fastrip => Look { width: 3, ..base }.with(LineKind::Solid, Marker::Square),
        TangentialModel::LocalEllipses => base.with(LineKind::Dotted, Marker::Cross),
        TangentialModel::FastripCoupled => {
            Look { width: 3, ..base }.with(LineKind::Dashed, Marker::Circle)
        }
    }
}

/// Whether a row's curves differ in tangential option (a normal model with several options).
fn compares_options(curves: &[&CreepCurve]) -> bool {
    curves.iter().enumerate().any(|(i, a)| {
        a.model != NormalModel::Hertz
            && curves[i + 1..]
                .iter()
                .any(|b| b.model == a.model && b.tangential != a.tangential)
    })
}

fn creep_label(c: &CreepCurve, by_option: bool) -> String {
    if c.model == NormalModel::Hertz {
        "1 Hertz (FASTSIM on the ellipse)".to_string()
    } else if by_option {
        format!("{}, {}", model_label(c.model), option_label(c.tangential))
    } else {
        model_label(c.model)
    }
}

impl Creep<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let n = self.rows.len().max(1);
        for ((name, curves), row) in self.rows.iter().zip(area.split_evenly((n, 1))) {
            let by_option = compares_options(curves);
            let mut entries = Vec::new();
            if self.reference.is_some() {
                entries.push(LegendEntry::line(
                    CONTACT,
                    reference_look().with(LineKind::Solid, Marker::Circle),
                ));
            }
            entries.extend(
                curves.iter().map(|c| {
                    LegendEntry::line(creep_label(c, by_option), creep_look(c, by_option))
                }),
            );
            let (w, _) = row.dim_in_pixel();
            let (head, body) = row.split_vertically(HEADING_H + legend_height(w, &entries));
            head.draw(&Text::new(
                name.clone(),
                (w as i32 / 2, 6),
                TextStyle::from((FONT, 17).into_font().style(FontStyle::Bold))
                    .pos(Pos::new(HPos::Center, VPos::Top)),
            ))
            .map_err(fail)?;
            let (_, legend_strip) = head.split_vertically(HEADING_H);
            legend(&legend_strip, &entries)?;
            let sides = body.split_evenly((1, 2));
            for (k, area) in sides.iter().enumerate() {
                let longitudinal = k == 0;
                let (symbol, force) = if longitudinal {
                    ("ξ", "Fx / μN")
                } else {
                    ("η", "Fy / μN")
                };
                let c_max = curves
                    .iter()
                    .flat_map(|c| if longitudinal { &c.fx } else { &c.fy })
                    .map(|p| p.0)
                    .fold(1e-3, f64::max);
                let axes = Axes {
                    x: (0.0, c_max * 1.02),
                    y: (-1.1, 0.1),
                    x_label: format!("creepage {symbol} [-]"),
                    y_label: format!("{force} [-]"),
                };
                let caption = if longitudinal {
                    "pure longitudinal creepage ξ (η = φ = 0)"
                } else {
                    "pure lateral creepage η (ξ = φ = 0)"
                };
                let mut chart = panel(area, caption, &axes)?;
                if let Some(r) = self.reference {
                    let points: Vec<(f64, f64)> = r
                        .creep
                        .iter()
                        .filter(|p| {
                            if longitudinal {
                                p.eta == 0.0
                            } else {
                                p.xi.abs() < 1e-6
                            }
                        })
                        .map(|p| {
                            if longitudinal {
                                (p.xi, p.fx_over_mufn)
                            } else {
                                (p.eta, p.fs_over_mufn)
                            }
                        })
                        .collect();
                    curve(
                        &mut chart,
                        &points,
                        reference_look().with(LineKind::Solid, Marker::Circle),
                    )?;
                }
                for c in curves {
                    let points = if longitudinal { &c.fx } else { &c.fy };
                    curve(&mut chart, points, creep_look(c, by_option))?;
                }
            }
        }
        Ok(())
    }
}

// ---------------------------------------------------------------------------------------------
// Frictional power density

/// Frictional power density along yRail at each shift of [`super::dissipation::SHIFTS_MM`]
/// (one panel each): the exact rolling solution and every normal model.
pub struct Dissipation<'a> {
    pub panels: &'a [Panel],
    pub setup: String,
}

/// The exact rolling solution's label.
const EXACT_ROLLING: &str = "exact half-space, steady rolling (0.4 mm elements)";

impl Dissipation<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let mut entries = vec![LegendEntry::line(
            EXACT_ROLLING,
            Look::solid(REFERENCE_COLOUR, 3),
        )];
        if let Some(p) = self.panels.first() {
            entries.extend(model_entries(p.models.iter().map(|m| m.model)));
        }
        let area = with_legend(area, &entries)?;
        let n = self.panels.len().max(1);
        for (p, area) in self.panels.iter().zip(area.split_evenly((1, n))) {
            let profiles = std::iter::once(&p.exact).chain(p.models.iter().map(|m| &m.profile));
            let points: Vec<(f64, f64)> = profiles.flat_map(|q| q.points.clone()).collect();
            let top = points.iter().map(|q| q.1).fold(0.0, f64::max);
            let axes = Axes {
                x: padded_range(points.iter().map(|q| q.0), 0.04),
                y: (0.0, 1.08 * top.max(1e-9)),
                x_label: Y_RAIL_LABEL.to_string(),
                y_label: "Tγ per unit width [N/mm]".to_string(),
            };
            let caption = format!(
                "y = {} mm: ξ = {}, η = 0, φ = {:.4} 1/m (rolling spin)",
                p.shift_mm, p.creepage.xi, p.creepage.phi
            );
            let mut chart = panel(&area, &caption, &axes)?;
            curve(
                &mut chart,
                &p.exact.points,
                Look::solid(REFERENCE_COLOUR, 3),
            )?;
            for m in &p.models {
                curve(&mut chart, &m.profile.points, model_look(m.model))?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn strip(y: f64, lead: f64) -> StripRow {
        StripRow {
            y_rail: y,
            x_lead: lead,
            x_trail: -lead,
            pmax: 1e6,
            b_raw: 1.0,
            b_model: None,
        }
    }

    #[test]
    fn outline_runs_along_the_leading_edge_and_back() {
        let p = outline_points(&[strip(0.001, 0.002), strip(0.002, 0.003)]);
        assert_eq!(p, vec![(1.0, 2.0), (2.0, 3.0), (2.0, -3.0), (1.0, -2.0)]);
    }

    #[test]
    fn touching_cells_of_one_level_merge() {
        let cell = |x0: f64, traction| Cell {
            y0: 0.0,
            y1: 1e-3,
            x0,
            x1: x0 + 1e-3,
            px: traction,
            py: 0.0,
            traction,
            slip: false,
        };
        let b = bands(&[cell(0.0, 1e6), cell(1e-3, 1e6), cell(2e-3, 100e6)], 100.0);
        assert_eq!(b.len(), 2);
        assert_eq!((b[0].x, b[0].level), ((0.0, 2.0), 0));
        assert_eq!(b[1].level, COLOUR_LEVELS - 1);
        assert_eq!(shift_label(0.0), "y = 0 mm");
        assert_eq!(shift_label(-1e-3), "y = -1 mm");
        assert_eq!(shift_label(2e-3), "y = +2 mm");
    }

    #[test]
    fn percent_is_signed() {
        assert_eq!(percent(110.0, 100.0), "+10.0 %");
        assert_eq!(percent(90.0, 100.0), "-10.0 %");
    }
}
