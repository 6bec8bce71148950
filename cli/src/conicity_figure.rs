//! The figure of `railcontact conicity --out DIR`: the rolling-radius difference Δr(y) and the
//! equivalent conicity λ(A) by both methods, side by side (`conicity.svg`, `conicity.png`).

use crate::report::plot::{
    curve, padded_range, panel, title, with_legend, Axes, Figure, LegendEntry, LineKind, Look,
    Marker,
};
use plotters::coord::Shift;
use plotters::prelude::*;
use railcontact::wheelset::conicity::Conicity;
use railcontact_cli::conicity::ConicityRun;

/// Millimetres per metre.
const TO_MM: f64 = 1000.0;
/// Colours (Okabe–Ito): Δr and harmonic linearisation; Klingel integration; the linear slope.
const MAIN: RGBColor = RGBColor(0, 114, 178);
const KLINGEL: RGBColor = RGBColor(213, 94, 0);
const GUIDE: RGBColor = RGBColor(140, 140, 140);

/// Points of a curve.
type Points = Vec<(f64, f64)>;

/// λ(A) of `rows` as (A [mm], λ) points: by harmonic linearisation, and by Klingel integration
/// where it exists.
fn conicity_points(rows: &[Conicity]) -> (Points, Points) {
    let harmonic = rows
        .iter()
        .map(|c| (c.amplitude * TO_MM, c.harmonic))
        .collect();
    let klingel = rows
        .iter()
        .filter_map(|c| c.klingel.map(|k| (c.amplitude * TO_MM, k)))
        .collect();
    (harmonic, klingel)
}

/// Δr(y) and λ(A) of one run; `setup` describes the profiles and track for the title.
pub struct ConicityFigure<'a> {
    pub run: &'a ConicityRun,
    pub setup: String,
}

impl Figure for ConicityFigure<'_> {
    fn name(&self) -> &str {
        "conicity"
    }

    fn size(&self) -> (u32, u32) {
        (1300, 560)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let rest = title(
            root,
            &format!("Equivalent conicity (EN 15302), {}", self.setup),
            40,
        )?;
        let harmonic = Look::solid(MAIN, 2);
        let klingel = Look::solid(KLINGEL, 2).with(LineKind::Dashed, Marker::None);
        let entries = [
            LegendEntry::line("Δr(y) / harmonic linearisation", harmonic),
            LegendEntry::line("Klingel integration", klingel),
            LegendEntry::line(
                "λ(A) at the listed amplitudes",
                Look::solid(MAIN, 2).with(LineKind::None, Marker::Circle),
            ),
            LegendEntry::line(
                "2 λ(3 mm) y",
                Look::solid(GUIDE, 1).with(LineKind::Dotted, Marker::None),
            ),
        ];
        let panels = with_legend(&rest, &entries)?;
        let areas = panels.split_evenly((1, 2));
        let d = &self.run.delta_r;

        let points: Vec<(f64, f64)> = d
            .points()
            .iter()
            .map(|p| (p.y * TO_MM, p.delta_r * TO_MM))
            .collect();
        let y_max = d.grid().y_max * TO_MM;
        let axes = Axes {
            x: (-y_max, y_max),
            y: padded_range(points.iter().map(|p| p.1), 0.05),
            x_label: "lateral shift y [mm]".into(),
            y_label: "Δr = r_right − r_left [mm]".into(),
        };
        let mut chart = panel(&areas[0], "rolling-radius difference", &axes)?;
        if let Ok(c) = self.run.delta_r.conicity(0.003) {
            let line = [
                (-y_max, -2.0 * c.harmonic * y_max),
                (y_max, 2.0 * c.harmonic * y_max),
            ];
            curve(
                &mut chart,
                &line,
                Look::solid(GUIDE, 1).with(LineKind::Dotted, Marker::None),
            )?;
        }
        curve(&mut chart, &points, harmonic)?;

        let (fine_h, fine_k) = conicity_points(&self.run.curve);
        let (listed_h, listed_k) = conicity_points(&self.run.table);
        let a_max = listed_h
            .iter()
            .chain(&fine_h)
            .map(|p| p.0)
            .fold(1.0, f64::max);
        let (_, top) = padded_range(
            fine_h.iter().chain(&fine_k).chain(&listed_h).map(|p| p.1),
            0.05,
        );
        let axes = Axes {
            x: (0.0, a_max * 1.02),
            y: (0.0, top.max(0.05)),
            x_label: "amplitude A [mm]".into(),
            y_label: "equivalent conicity λ [-]".into(),
        };
        let mut chart = panel(&areas[1], "equivalent conicity", &axes)?;
        curve(&mut chart, &fine_h, harmonic)?;
        curve(&mut chart, &fine_k, klingel)?;
        curve(
            &mut chart,
            &listed_h,
            harmonic.with(LineKind::None, Marker::Circle),
        )?;
        curve(
            &mut chart,
            &listed_k,
            Look::solid(KLINGEL, 2).with(LineKind::None, Marker::Triangle),
        )?;
        Ok(())
    }
}
