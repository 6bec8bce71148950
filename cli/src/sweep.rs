//! `railcontact sweep`: the model over the lateral shift `y`, as a text table per wheel — number
//! of patches, then per patch yRail [mm], contact angle [rad], normal force Fn [kN], rolling
//! radius [mm], and the wheel's total lateral force Fy [kN]. Shifts where the wheel leaves the
//! profiles get a note instead of numbers; implausible states get their numbers and a warning.

use crate::{model, output_integer, output_real, unit_suffix, Failure};
use railcontact::fmi::model::{Evaluation, ModelError};
use railcontact::fmi::variables::Values;
use railcontact::models::wheel_rail_contact::{generated::var, INFO};
use railcontact::wheelset::MAX_PATCHES;
use std::fmt::Write as _;

/// Most rows a sweep may have.
pub const MAX_ROWS: usize = 100_000;

/// The shifts of a sweep [m]: from `from` to `to` (either way) in steps of `step`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepRange {
    pub from: f64,
    pub to: f64,
    pub step: f64,
}

/// One wheel in one row.
struct SideRow {
    /// The number of patches in the output slots.
    count: usize,
    /// Per output slot: yRail [m], contact angle [rad], Fn [N], rolling radius [m]; `None`
    /// where the slot is empty.
    patches: [Option<[f64; 4]>; MAX_PATCHES],
    fy: f64,
}

enum Row {
    /// The outputs, and the warning of an implausible state.
    Values(Box<[SideRow; 2]>, Option<String>),
    Note(String),
}

/// What went wrong in a sweep's rows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepOutcome {
    /// A row failed with an error (other than leaving the profiles).
    pub errors: bool,
    /// Rows with an implausible contact state.
    pub warnings: usize,
}

/// The table of the case `values` over `range`, and what went wrong in its rows.
pub fn sweep(mut values: Values, range: SweepRange) -> Result<(String, SweepOutcome), Failure> {
    let y_info = INFO
        .variable("y")
        .ok_or_else(|| Failure::Error("internal error: no input y".into()))?;
    for (name, x) in [("--from", range.from), ("--to", range.to)] {
        if !y_info.accepts_real(x) {
            return Err(Failure::Error(format!(
                "{name} {x}: y = {x} is outside the allowed range {}{}",
                y_info.allowed,
                unit_suffix(y_info)
            )));
        }
    }
    if !(range.step.is_finite() && range.step > 0.0) {
        return Err(Failure::Error(format!(
            "--step {}: the step must be a number > 0 [m]",
            range.step
        )));
    }
    let span = (range.to - range.from).abs();
    let intervals = (span / range.step * (1.0 + 1e-9)).floor();
    if intervals >= MAX_ROWS as f64 {
        return Err(Failure::Error(format!(
            "--step {}: {} rows, at most {MAX_ROWS} are allowed",
            range.step,
            intervals + 1.0
        )));
    }
    let direction = if range.to >= range.from { 1.0 } else { -1.0 };

    let mut model = model(&values)?;
    let mut rows = Vec::new();
    let mut errors = false;
    let mut warnings = 0;
    for k in 0..=intervals as usize {
        // Rounded to 1e-12 m so that the printed shifts are exact (no "-0.000").
        let y = (range.from + direction * k as f64 * range.step) * 1e12;
        let y = y.round() / 1e12 + 0.0;
        values.set_real(var::y, y);
        let row = match model.evaluate(&mut values, 0.0) {
            Ok(outcome) => {
                let warning = match outcome {
                    Evaluation::Ok => None,
                    Evaluation::Warning(m) => {
                        warnings += 1;
                        Some(m)
                    }
                };
                Row::Values(
                    Box::new([side_row(&values, "left")?, side_row(&values, "right")?]),
                    warning,
                )
            }
            Err(ModelError::Discard(m)) => Row::Note(m),
            Err(ModelError::Error(m)) => {
                errors = true;
                Row::Note(format!("error: {m}"))
            }
        };
        rows.push((y, row));
    }
    Ok((
        table(&values, range, &rows),
        SweepOutcome { errors, warnings },
    ))
}

fn side_row(values: &Values, side: &str) -> Result<SideRow, Failure> {
    let count = usize::try_from(output_integer(values, &format!("{side}.nPatches"))?)
        .unwrap_or(0)
        .min(MAX_PATCHES);
    let mut patches = [None; MAX_PATCHES];
    for (k, slot) in patches.iter_mut().enumerate() {
        let mut patch = [0.0; 4];
        for (x, q) in patch
            .iter_mut()
            .zip(["yRail", "contactAngle", "Fn", "rollingRadius"])
        {
            *x = output_real(values, &format!("{side}.p{}.{q}", k + 1))?;
        }
        // An empty slot has every output zero.
        *slot = (patch[2] > 0.0).then_some(patch);
    }
    Ok(SideRow {
        count,
        patches,
        fy: output_real(values, &format!("{side}.Fy"))?,
    })
}

fn table(values: &Values, range: SweepRange, rows: &[(f64, Row)]) -> String {
    // Slot column groups per wheel: up to the last slot the sweep uses (at least one).
    let groups: [usize; 2] = [0, 1].map(|s| {
        rows.iter()
            .filter_map(|(_, r)| match r {
                Row::Values(sides, _) => sides[s].patches.iter().rposition(Option::is_some),
                Row::Note(_) => None,
            })
            .max()
            .map_or(1, |k| k + 1)
    });
    let mut header = vec!["y[mm]".to_string()];
    for (s, letter) in ["L", "R"].iter().enumerate() {
        header.push(format!("{letter}.n"));
        for k in 1..=groups[s] {
            for q in ["yRail[mm]", "gamma[rad]", "Fn[kN]", "r[mm]"] {
                header.push(format!("{letter}.p{k}.{q}"));
            }
        }
        header.push(format!("{letter}.Fy[kN]"));
    }
    let widths: Vec<usize> = header.iter().map(|h| h.len().max(9)).collect();

    let mut out = String::new();
    let mode = if values.integer(var::verticalMode) == 2 {
        "vertical position z prescribed".to_string()
    } else {
        format!(
            "Qleft = {} kN, Qright = {} kN",
            values.real(var::Qleft) / 1e3,
            values.real(var::Qright) / 1e3
        )
    };
    let _ = writeln!(
        out,
        "# railcontact sweep: WheelRailContact, wheel {}, rail {}, {mode}; y from {} to {} mm, \
         step {} mm",
        values.string(var::wheelProfile),
        values.string(var::railProfile),
        range.from * 1e3,
        range.to * 1e3,
        range.step * 1e3
    );
    let _ = writeln!(
        out,
        "# y = lateral shift of the wheelset; L/R = left/right wheel: n = number of patches; pK = \
         output slot K (a patch keeps its slot while it exists; slots are not ordered in space): \
         yRail, gamma = contact angle, Fn = normal force, r = rolling radius ('-': empty slot); \
         Fy = total lateral force of the rail on the wheel"
    );
    let cells: Vec<String> = header
        .iter()
        .zip(&widths)
        .map(|(h, w)| format!("{h:>w$}"))
        .collect();
    let _ = writeln!(out, "{}", cells.join(" "));

    for (y, row) in rows {
        let mut cells = vec![format!("{:.3}", y * 1e3)];
        let warning = match row {
            Row::Note(note) => {
                let _ = writeln!(out, "{:>w$} -- {note}", cells[0], w = widths[0]);
                continue;
            }
            Row::Values(sides, warning) => {
                for (s, side) in sides.iter().enumerate() {
                    cells.push(side.count.to_string());
                    for k in 0..groups[s] {
                        match side.patches[k] {
                            Some([y_rail, gamma, fn_, r]) => cells.extend([
                                format!("{:.3}", y_rail * 1e3),
                                format!("{gamma:.5}"),
                                format!("{:.3}", fn_ / 1e3),
                                format!("{:.3}", r * 1e3),
                            ]),
                            None => cells.extend(std::iter::repeat_n("-".to_string(), 4)),
                        }
                    }
                    cells.push(format!("{:.3}", side.fy / 1e3));
                }
                warning.as_deref()
            }
        };
        let cells: Vec<String> = cells
            .iter()
            .zip(&widths)
            .map(|(c, w)| format!("{c:>w$}"))
            .collect();
        match warning {
            None => {
                let _ = writeln!(out, "{}", cells.join(" "));
            }
            Some(m) => {
                let _ = writeln!(out, "{} -- warning: {m}", cells.join(" "));
            }
        }
    }
    out
}
