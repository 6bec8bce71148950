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
    /// The row with its `error` in `error_unit`, printed with `error_decimals`.
    fn error(self, error: f64, error_unit: &'static str, error_decimals: usize) -> Self {
        Self {
            error,
            error_unit,
            error_decimals,
            ..self
        }
    }

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

    /// Whether `other` is a row of the same case and model run.
    fn same_run(&self, other: &ErrorRow) -> bool {
        self.case == other.case
            && self.model == other.model
            && self.tangential == other.tangential
            && self.planar == other.planar
    }

    /// The tangential option's label ("FASTSIM on the ellipse" for the Hertz rows).
    fn option_text(&self) -> String {
        self.tangential
            .map_or("FASTSIM on the ellipse".to_string(), option_label)
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

/// What a row of the error table is about: the case and the model run.
#[derive(Debug, Clone, Copy)]
struct Subject {
    case: &'static str,
    model: NormalModel,
    tangential: Option<TangentialModel>,
    planar: Option<bool>,
}

impl Subject {
    /// A row of `quantity` [`unit`], the model's `value` against CONTACT's `reference`, both
    /// printed with `decimals`; the error is set by [`ErrorRow::error`].
    fn row(
        self,
        quantity: &'static str,
        unit: &'static str,
        decimals: usize,
        value: f64,
        reference: Option<f64>,
    ) -> ErrorRow {
        ErrorRow {
            case: self.case,
            model: self.model,
            tangential: self.tangential,
            planar: self.planar,
            quantity,
            unit,
            decimals,
            value,
            reference,
            error: 0.0,
            error_unit: "",
            error_decimals: 0,
        }
    }
}

/// Rows of the central normal case.
pub fn central_rows(runs: &[NormalRun], r: &Reference) -> Vec<ErrorRow> {
    let (area_ref, pmax_ref) = (r.normal.area_mm2, r.normal.pmax_mpa);
    let mut rows = Vec::new();
    for run in runs {
        let subject = Subject {
            case: "central",
            model: run.model,
            tangential: None,
            planar: None,
        };
        let area = run.totals.area * 1e6;
        let pmax = run.totals.pmax * 1e-6;
        let rms = strip_pmax_rms(&run.profile, &r.strips);
        let rms_share = 100.0 * rms / pmax_ref;
        for (quantity, unit, value, reference, error, error_unit) in [
            ("area", "mm2", area, area_ref, relative(area, area_ref), "%"),
            ("pmax", "MPa", pmax, pmax_ref, relative(pmax, pmax_ref), "%"),
            (
                "strip_pmax_rms",
                "MPa",
                rms,
                pmax_ref,
                rms_share,
                "% of pmax_ref",
            ),
        ] {
            let row = subject.row(quantity, unit, 2, value, Some(reference));
            rows.push(row.error(error, error_unit, 2));
        }
    }
    rows
}

/// Rows of pure spin.
pub fn spin_rows(runs: &[SpinRun], r: &Reference) -> Vec<ErrorRow> {
    let s = &r.spin;
    let mut rows = Vec::new();
    for run in runs {
        if run.model == NormalModel::Hertz && !run.planar {
            // Hertz patches are always planar: the same numbers as the planar row.
            continue;
        }
        let t = &run.normal.totals;
        let subject = Subject {
            case: "pure_spin",
            model: run.model,
            tangential: (run.model != NormalModel::Hertz).then_some(run.tangential),
            planar: (run.model != NormalModel::Hertz).then_some(run.planar),
        };
        let mz_ref = s.mz_nm();
        let slip = 100.0 * (1.0 - t.adhesion);
        let slip_ref = s.slip_share();
        for (quantity, unit, decimals, value, reference, error, error_unit) in [
            ("Fx", "N", 1, t.fx, s.fx_n, t.fx - s.fx_n, "N"),
            ("Fy", "N", 1, t.fy, s.fs_n, relative(t.fy, s.fs_n), "%"),
            ("Mz", "N.m", 3, t.mz, mz_ref, relative(t.mz, mz_ref), "%"),
            (
                "slip_share",
                "%",
                2,
                slip,
                slip_ref,
                slip - slip_ref,
                "percentage points",
            ),
        ] {
            let error_decimals = if error_unit == "%" { 2 } else { 1 };
            let row = subject.row(quantity, unit, decimals, value, Some(reference));
            rows.push(row.error(error, error_unit, error_decimals));
        }
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
        let subject = Subject {
            case: "creep_curves",
            model: c.model,
            tangential: (c.model != NormalModel::Hertz).then_some(c.tangential),
            planar: Some(true),
        };
        for (quantity, value) in [("worst_abs_error", worst), ("mean_abs_error", mean)] {
            let row = subject.row(quantity, "muN", 4, value, None);
            rows.push(row.error(value, "muN", 4));
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

/// Per model run of `case` (in the rows' order), its rows of `quantities`; runs missing one are
/// left out.
fn runs_of<'a, const N: usize>(
    rows: &'a [ErrorRow],
    case: &'a str,
    quantities: [&'a str; N],
) -> impl Iterator<Item = [&'a ErrorRow; N]> + 'a {
    rows.iter()
        .filter(move |row| row.case == case && row.quantity == quantities[0])
        .filter_map(move |first| {
            let of_run: Option<Vec<&ErrorRow>> = quantities
                .iter()
                .map(|&q| rows.iter().find(|r| r.same_run(first) && r.quantity == q))
                .collect();
            of_run?.try_into().ok()
        })
}

/// Fx [N], Fy [N], Mz [N·m] and the slip share [%] as the pure-spin tables print them.
pub fn spin_cells(fx: f64, fy: f64, mz: f64, slip_share: f64) -> [String; 4] {
    [
        format!("{fx:.1}"),
        format!("{fy:.1}"),
        format!("{mz:.3}"),
        format!("{slip_share:.2} %"),
    ]
}

/// The error tables as markdown.
pub fn markdown(rows: &[ErrorRow], r: &Reference) -> String {
    let mut out = String::new();
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
    for [a, p, s] in runs_of(rows, "central", ["area", "pmax", "strip_pmax_rms"]) {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {:.1} % |",
            model_label(a.model),
            a.value_text(),
            a.error_text(),
            p.value_text(),
            p.error_text(),
            s.value_text(),
            s.error
        );
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
    let [fx, fy, mz, slip] = spin_cells(s.fx_n, s.fs_n, s.mz_nm(), s.slip_share());
    let _ = writeln!(
        out,
        "| CONTACT (exact) | | yes | {fx} | {fy} | | {mz} | | {slip} |"
    );
    for [fx, fy, mz, slip] in runs_of(rows, "pure_spin", ["Fx", "Fy", "Mz", "slip_share"]) {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} % |",
            model_label(fx.model),
            fx.option_text(),
            fx.planar.map_or("yes", |p| if p { "yes" } else { "no" }),
            fx.value_text(),
            fy.value_text(),
            fy.error_text(),
            mz.value_text(),
            mz.error_text(),
            slip.value_text()
        );
    }

    let _ = writeln!(
        out,
        "\n### Creep curves (series c_pure_dy0, planar patches): |ΔF|/(μN)\n"
    );
    let _ = writeln!(out, "| model | tangential option | worst | mean |");
    let _ = writeln!(out, "|---|---|---|---|");
    let creep = ["worst_abs_error", "mean_abs_error"];
    for [worst, mean] in runs_of(rows, "creep_curves", creep) {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} |",
            model_label(worst.model),
            worst.option_text(),
            worst.value_text(),
            mean.value_text()
        );
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
