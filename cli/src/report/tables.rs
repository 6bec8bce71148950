//! The report's error table against CONTACT: per normal model (and tangential option) and case,
//! the model's value, CONTACT's and the error — central normal contact (area, pmax, strip-pmax
//! RMS), pure spin (Fx, Fy, Mz, slip share) and the creep curves (worst and mean error in units
//! of μN). Written as markdown tables (in report.md) and as `errors.csv`, both from the same rows
//! and with the same printed precision.

use super::figures::option_label;
use super::plot::model_label;
use super::reference::{RefCreep, RefStrip, Reference};
use super::study::{CreepCurve, NormalRun, Options, SpinRun, Study};
use crate::Failure;
use railcontact::normal::NormalModel;
use railcontact::tangential::fastsim::Creepage;
use railcontact::tangential::patch::TangentialModel;
use std::fmt::Write as _;

/// Reference creep points with max(|ξ|, |η|) below this are skipped (the zero point: both forces
/// vanish, no information).
const CREEP_POINT_MIN: f64 = 4e-4;

/// The header of `errors.csv`.
pub const CSV_HEADER: &str =
    "case,normal_model,tangential_model,planar_patch,quantity,unit,model,reference,error,error_unit";

/// One row of the error table.
#[derive(Debug, Clone, PartialEq)]
pub struct ErrorRow {
    /// "central", "pure_spin" or "creep_curves".
    pub case: &'static str,
    pub model: NormalModel,
    /// `None` where the tangential problem plays no part.
    pub tangential: Option<TangentialModel>,
    pub planar: Option<bool>,
    pub quantity: &'static str,
    pub unit: &'static str,
    /// Decimals printed for the value and the reference.
    pub decimals: usize,
    pub value: f64,
    pub reference: Option<f64>,
    pub error: f64,
    pub error_unit: &'static str,
    pub error_decimals: usize,
}

impl ErrorRow {
    fn csv(&self) -> String {
        format!(
            "{},{},{},{},{},{},{:.*},{},{:.*},{}",
            self.case,
            model_label(self.model),
            self.tangential
                .map_or("-".to_string(), |t| super::study::tangential_code(t)
                    .to_string()),
            self.planar.map_or("-".to_string(), |p| p.to_string()),
            self.quantity,
            self.unit,
            self.decimals,
            self.value,
            self.reference
                .map_or("-".to_string(), |r| format!("{r:.*}", self.decimals)),
            self.error_decimals,
            self.error,
            self.error_unit
        )
    }

    fn value_text(&self) -> String {
        format!("{:.*}", self.decimals, self.value)
    }

    fn error_text(&self) -> String {
        let unit = if self.error_unit == "%" { " %" } else { "" };
        format!("{:+.*}{unit}", self.error_decimals, self.error)
    }
}

/// Relative error in percent.
fn relative(value: f64, reference: f64) -> f64 {
    100.0 * (value / reference - 1.0)
}

/// RMS difference [MPa] of a model's strip maxima against CONTACT's along yRail: the model's
/// `profile` ((yRail [m], pmax [Pa]) sorted, see [`NormalRun::profile`]) interpolated linearly at
/// each reference strip, zero outside it — the measure of `tests/central.rs`.
pub fn strip_pmax_rms(profile: &[(f64, f64)], reference: &[RefStrip]) -> f64 {
    let at = |y: f64| -> f64 {
        let k = profile.partition_point(|p| p.0 < y);
        if k == 0 || k == profile.len() {
            return 0.0;
        }
        let (a, b) = (profile[k - 1], profile[k]);
        if b.0 > a.0 {
            a.1 + (b.1 - a.1) * (y - a.0) / (b.0 - a.0)
        } else {
            a.1
        }
    };
    if reference.is_empty() {
        return 0.0;
    }
    let sum: f64 = reference
        .iter()
        .map(|r| (at(r.y_rail_mm * 1e-3) * 1e-6 - r.pmax_mpa).powi(2))
        .sum();
    (sum / reference.len() as f64).sqrt()
}

/// Rows of the central normal case.
pub fn central_rows(runs: &[NormalRun], r: &Reference) -> Vec<ErrorRow> {
    let mut rows = Vec::new();
    for run in runs {
        let area = run.totals.area * 1e6;
        let pmax = run.totals.pmax * 1e-6;
        let rms = strip_pmax_rms(&run.profile, &r.strips);
        let row = |quantity, unit, decimals, value, reference: f64, error, error_unit| ErrorRow {
            case: "central",
            model: run.model,
            tangential: None,
            planar: None,
            quantity,
            unit,
            decimals,
            value,
            reference: Some(reference),
            error,
            error_unit,
            error_decimals: 2,
        };
        rows.push(row(
            "area",
            "mm2",
            2,
            area,
            r.normal.area_mm2,
            relative(area, r.normal.area_mm2),
            "%",
        ));
        rows.push(row(
            "pmax",
            "MPa",
            2,
            pmax,
            r.normal.pmax_mpa,
            relative(pmax, r.normal.pmax_mpa),
            "%",
        ));
        rows.push(row(
            "strip_pmax_rms",
            "MPa",
            2,
            rms,
            r.normal.pmax_mpa,
            100.0 * rms / r.normal.pmax_mpa,
            "% of pmax_ref",
        ));
    }
    rows
}

/// Rows of pure spin.
pub fn spin_rows(runs: &[SpinRun], r: &Reference) -> Vec<ErrorRow> {
    let s = &r.spin;
    let mut rows = Vec::new();
    for run in runs {
        let t = &run.normal.totals;
        let (tangential, planar) = if run.model == NormalModel::Hertz {
            (None, None)
        } else {
            (Some(run.tangential), Some(run.planar))
        };
        if run.model == NormalModel::Hertz && !run.planar {
            // Hertz patches are always planar: the same numbers as the planar row.
            continue;
        }
        let row = |quantity, unit, decimals, value, reference, error, error_unit| ErrorRow {
            case: "pure_spin",
            model: run.model,
            tangential,
            planar,
            quantity,
            unit,
            decimals,
            value,
            reference: Some(reference),
            error,
            error_unit,
            error_decimals: if error_unit == "%" { 2 } else { 1 },
        };
        rows.push(row("Fx", "N", 1, t.fx, s.fx_n, t.fx - s.fx_n, "N"));
        rows.push(row("Fy", "N", 1, t.fy, s.fs_n, relative(t.fy, s.fs_n), "%"));
        let mz_ref = s.mn_nmm * 1e-3;
        rows.push(row(
            "Mz",
            "N.m",
            3,
            t.mz,
            mz_ref,
            relative(t.mz, mz_ref),
            "%",
        ));
        let slip = 100.0 * (1.0 - t.adhesion);
        let slip_ref = 100.0 * (1.0 - s.adhesion_fraction);
        rows.push(row(
            "slip_share",
            "%",
            2,
            slip,
            slip_ref,
            slip - slip_ref,
            "percentage points",
        ));
    }
    rows
}

/// Worst and mean |ΔF/μN| of `options` at CONTACT's creep points (Fx and Fy both counted).
pub fn creep_errors(
    study: &Study,
    options: Options,
    points: &[RefCreep],
) -> Result<(f64, f64), Failure> {
    let mut runner = study.runner(options)?;
    let mu = study.mu();
    let (mut worst, mut sum, mut count) = (0.0f64, 0.0, 0usize);
    for p in points {
        if p.xi.abs().max(p.eta.abs()) < CREEP_POINT_MIN {
            continue;
        }
        let t = runner.totals_at(Creepage {
            xi: p.xi,
            eta: p.eta,
            phi: p.phi_per_mm * 1e3,
        })?;
        let dx = (t.fx / (mu * t.fn_) - p.fx_over_mufn).abs();
        let dy = (t.fy / (mu * t.fn_) - p.fs_over_mufn).abs();
        worst = worst.max(dx).max(dy);
        sum += dx + dy;
        count += 2;
    }
    Ok((worst, if count > 0 { sum / count as f64 } else { 0.0 }))
}

/// Rows of the creep curves, one pair per curve.
pub fn creep_rows(
    study: &Study,
    curves: &[&CreepCurve],
    r: &Reference,
) -> Result<Vec<ErrorRow>, Failure> {
    let mut rows = Vec::new();
    for c in curves {
        let options = Options {
            tangential: Some(c.tangential),
            planar: Some(true),
            ..Options::normal(c.model)
        };
        let (worst, mean) = creep_errors(study, options, &r.creep)?;
        let tangential = (c.model != NormalModel::Hertz).then_some(c.tangential);
        for (quantity, value) in [("worst_abs_error", worst), ("mean_abs_error", mean)] {
            rows.push(ErrorRow {
                case: "creep_curves",
                model: c.model,
                tangential,
                planar: Some(true),
                quantity,
                unit: "muN",
                decimals: 4,
                value,
                reference: None,
                error: value,
                error_unit: "muN",
                error_decimals: 4,
            });
        }
    }
    Ok(rows)
}

/// `errors.csv`.
pub fn csv(rows: &[ErrorRow]) -> String {
    let mut out = String::from(CSV_HEADER);
    out.push('\n');
    for row in rows {
        out.push_str(&row.csv());
        out.push('\n');
    }
    out
}

fn find<'a>(
    rows: &'a [ErrorRow],
    case: &str,
    model: NormalModel,
    tangential: Option<TangentialModel>,
    planar: Option<bool>,
    quantity: &str,
) -> Option<&'a ErrorRow> {
    rows.iter().find(|r| {
        r.case == case
            && r.model == model
            && r.tangential == tangential
            && r.planar == planar
            && r.quantity == quantity
    })
}

/// The error tables as markdown.
pub fn markdown(rows: &[ErrorRow], r: &Reference) -> String {
    let mut out = String::new();
    let mut models: Vec<NormalModel> = Vec::new();
    for row in rows.iter().filter(|row| row.case == "central") {
        if !models.contains(&row.model) {
            models.push(row.model);
        }
    }
    let _ = writeln!(out, "### Central case, normal contact\n");
    let _ = writeln!(
        out,
        "| model | area mm² | error | pmax MPa | error | strip-pmax RMS MPa | RMS / pmax_ref |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|");
    let _ = writeln!(
        out,
        "| CONTACT (exact) | {:.2} | | {:.2} | | | |",
        r.normal.area_mm2, r.normal.pmax_mpa
    );
    for &m in &models {
        let get = |q| find(rows, "central", m, None, None, q);
        if let (Some(a), Some(p), Some(s)) = (get("area"), get("pmax"), get("strip_pmax_rms")) {
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} | {} | {} | {:.1} % |",
                model_label(m),
                a.value_text(),
                a.error_text(),
                p.value_text(),
                p.error_text(),
                s.value_text(),
                s.error
            );
        }
    }

    let _ = writeln!(
        out,
        "\n### Pure spin φ = 0.052 rad/m (ξ = η = 0 prescribed)\n"
    );
    let _ = writeln!(
        out,
        "| model | tangential option | planar | Fx N | Fy N | error | Mz N·m | error | slip share |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|---|");
    let s = &r.spin;
    let _ = writeln!(
        out,
        "| CONTACT (exact) | | yes | {:.1} | {:.1} | | {:.3} | | {:.2} % |",
        s.fx_n,
        s.fs_n,
        s.mn_nmm * 1e-3,
        100.0 * (1.0 - s.adhesion_fraction)
    );
    for row in rows
        .iter()
        .filter(|row| row.case == "pure_spin" && row.quantity == "Fx")
    {
        let get = |q| find(rows, "pure_spin", row.model, row.tangential, row.planar, q);
        if let (Some(fy), Some(mz), Some(slip)) = (get("Fy"), get("Mz"), get("slip_share")) {
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} % |",
                model_label(row.model),
                row.tangential
                    .map_or("FASTSIM on the ellipse".to_string(), option_label),
                row.planar.map_or("yes", |p| if p { "yes" } else { "no" }),
                row.value_text(),
                fy.value_text(),
                fy.error_text(),
                mz.value_text(),
                mz.error_text(),
                slip.value_text()
            );
        }
    }

    let _ = writeln!(
        out,
        "\n### Creep curves (series c_pure_dy0, planar patches): |ΔF|/(μN)\n"
    );
    let _ = writeln!(out, "| model | tangential option | worst | mean |");
    let _ = writeln!(out, "|---|---|---|---|");
    for row in rows
        .iter()
        .filter(|row| row.case == "creep_curves" && row.quantity == "worst_abs_error")
    {
        if let Some(mean) = find(
            rows,
            "creep_curves",
            row.model,
            row.tangential,
            row.planar,
            "mean_abs_error",
        ) {
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} |",
                model_label(row.model),
                row.tangential
                    .map_or("FASTSIM on the ellipse".to_string(), option_label),
                row.value_text(),
                mean.value_text()
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reference(y_rail_mm: f64, pmax_mpa: f64) -> RefStrip {
        RefStrip {
            s_mm: y_rail_mm,
            y_rail_mm,
            x_min_mm: -1.0,
            x_max_mm: 1.0,
            pmax_mpa,
        }
    }

    #[test]
    fn rms_interpolates_and_is_zero_outside() {
        let model = [(0.0, 100e6), (2e-3, 300e6)];
        let same = [reference(1.0, 200.0)];
        assert!(strip_pmax_rms(&model, &same).abs() < 1e-9);
        // Outside the model's patch the model's pressure is zero.
        let outside = [reference(5.0, 30.0)];
        assert!((strip_pmax_rms(&model, &outside) - 30.0).abs() < 1e-9);
    }

    #[test]
    fn csv_rows_print_the_stated_precision() {
        let row = ErrorRow {
            case: "central",
            model: NormalModel::Analyn,
            tangential: None,
            planar: None,
            quantity: "area",
            unit: "mm2",
            decimals: 2,
            value: 164.6251,
            reference: Some(168.4),
            error: -2.241,
            error_unit: "%",
            error_decimals: 2,
        };
        assert_eq!(
            row.csv(),
            "central,6 ANALYN,-,-,area,mm2,164.63,168.40,-2.24,%"
        );
        assert_eq!(CSV_HEADER.split(',').count(), row.csv().split(',').count());
    }
}
