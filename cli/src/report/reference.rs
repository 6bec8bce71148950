//! The CONTACT reference solutions of the central case (tests/data/README.md), read from
//! `<reference>/central/*.csv` (described in the reference directory's README.md).
//!
//! Units stay CONTACT's (mm, N, N·mm, MPa, 1/mm) in the file-level structs; the names say which.
//! Sign conventions (reference/README.md, docs/conventions.md): CONTACT reports forces and
//! tractions on the rail and creepages of the rail, railcontact those on and of the wheel — the
//! same numbers for the same numeric creepages; CONTACT's right-rail lateral coordinate
//! (`y_rail_approx_mm`) is negative towards the gauge side, i.e. it is railcontact's `yRail` of the
//! right wheel (positive towards the field side), and its in-plane `s_mm` increases with it.
//!
//! Every error names the file and, for a bad value, its line and column.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// A CSV file: a header line of column names and rows of comma-separated fields.
struct Table {
    path: PathBuf,
    columns: HashMap<String, usize>,
    /// (1-based line number, fields).
    rows: Vec<(usize, Vec<String>)>,
}

impl Table {
    fn read(path: &Path) -> Result<Self, String> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("{}: cannot read the reference file: {e}", path.display()))?;
        Self::parse(path, &text)
    }

    /// The table in `text`, read from `path` (named in the messages).
    fn parse(path: &Path, text: &str) -> Result<Self, String> {
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty());
        let (_, header) = lines
            .next()
            .ok_or_else(|| format!("{}: empty file (expected a header line)", path.display()))?;
        let columns = header
            .split(',')
            .enumerate()
            .map(|(i, name)| (name.trim().to_string(), i))
            .collect();
        let rows = lines
            .map(|(i, l)| (i + 1, l.split(',').map(|f| f.trim().to_string()).collect()))
            .collect();
        Ok(Self {
            path: path.to_path_buf(),
            columns,
            rows,
        })
    }

    fn column(&self, name: &str) -> Result<usize, String> {
        self.columns.get(name).copied().ok_or_else(|| {
            format!(
                "{}: line 1: no column '{name}' in the header",
                self.path.display()
            )
        })
    }

    /// The text of column `col` in row `row`.
    fn text(&self, row: usize, col: usize, name: &str) -> Result<&str, String> {
        let (line, fields) = &self.rows[row];
        fields.get(col).map(String::as_str).ok_or_else(|| {
            format!(
                "{}: line {line}: missing field '{name}' (column {})",
                self.path.display(),
                col + 1
            )
        })
    }

    /// Column `name` of row `row` as a finite number.
    fn number(&self, row: usize, name: &str) -> Result<f64, String> {
        let col = self.column(name)?;
        let text = self.text(row, col, name)?;
        text.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| {
                format!(
                    "{}: line {}, column {} ('{name}'): '{text}' is not a finite number",
                    self.path.display(),
                    self.rows[row].0,
                    col + 1
                )
            })
    }

    fn len(&self) -> usize {
        self.rows.len()
    }

    fn require_rows(&self) -> Result<(), String> {
        if self.rows.is_empty() {
            Err(format!("{}: no data rows", self.path.display()))
        } else {
            Ok(())
        }
    }
}

/// `normal_dy0_summary.csv`: the normal solution's figures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalSummary {
    pub area_mm2: f64,
    pub pmax_mpa: f64,
    pub fn_n: f64,
}

/// One lateral strip of `normal_dy0_strips.csv`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefStrip {
    /// Lateral coordinate in CONTACT's contact plane [mm].
    pub s_mm: f64,
    /// Rail lateral coordinate = railcontact's `yRail` of the right wheel [mm].
    pub y_rail_mm: f64,
    /// Trailing and leading edge [mm].
    pub x_min_mm: f64,
    pub x_max_mm: f64,
    pub pmax_mpa: f64,
}

/// The φ = +5.2e−5 1/mm row of `pure_spin_summary.csv`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpinSummary {
    /// Spin creepage [1/mm].
    pub phi_per_mm: f64,
    pub fx_n: f64,
    pub fs_n: f64,
    pub mn_nmm: f64,
    pub adhesion_fraction: f64,
}

impl SpinSummary {
    /// The spin moment [N·m].
    pub fn mz_nm(&self) -> f64 {
        self.mn_nmm * 1e-3
    }

    /// The slipping share of the patch [%].
    pub fn slip_share(&self) -> f64 {
        100.0 * (1.0 - self.adhesion_fraction)
    }
}

/// One element of `pure_spin_traction_grid.csv`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefTraction {
    pub x_mm: f64,
    pub s_mm: f64,
    /// `s_mm` mapped to the rail coordinate through the strip table [mm].
    pub y_rail_mm: f64,
    pub slip: bool,
    pub px_mpa: f64,
    pub ps_mpa: f64,
}

/// One point of series `c_pure_dy0` of `creep_curves_dy0.csv` (achieved creepages).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefCreep {
    pub xi: f64,
    pub eta: f64,
    /// Spin [1/mm].
    pub phi_per_mm: f64,
    pub fx_over_mufn: f64,
    pub fs_over_mufn: f64,
}

/// All reference data the report uses.
#[derive(Debug, Clone)]
pub struct Reference {
    pub dir: PathBuf,
    pub normal: NormalSummary,
    /// Sorted by `s_mm`.
    pub strips: Vec<RefStrip>,
    pub spin: SpinSummary,
    pub traction: Vec<RefTraction>,
    pub creep: Vec<RefCreep>,
}

impl Reference {
    /// Reads `<dir>/central/*.csv`.
    pub fn load(dir: &Path) -> Result<Self, String> {
        let central = dir.join("central");
        let table = |name: &str| Table::read(&central.join(name));
        let strips = read_strips(&table("normal_dy0_strips.csv")?)?;
        Ok(Self {
            dir: dir.to_path_buf(),
            normal: read_normal(&table("normal_dy0_summary.csv")?)?,
            spin: read_spin(&table("pure_spin_summary.csv")?)?,
            traction: read_traction(&table("pure_spin_traction_grid.csv")?, &strips)?,
            creep: read_creep(&table("creep_curves_dy0.csv")?)?,
            strips,
        })
    }
}

fn read_normal(t: &Table) -> Result<NormalSummary, String> {
    t.require_rows()?;
    Ok(NormalSummary {
        area_mm2: t.number(0, "area_mm2")?,
        pmax_mpa: t.number(0, "pmax_MPa")?,
        fn_n: t.number(0, "fn_N")?,
    })
}

fn read_strips(t: &Table) -> Result<Vec<RefStrip>, String> {
    t.require_rows()?;
    let mut strips = (0..t.len())
        .map(|i| {
            Ok(RefStrip {
                s_mm: t.number(i, "s_mm")?,
                y_rail_mm: t.number(i, "y_rail_approx_mm")?,
                x_min_mm: t.number(i, "x_min_mm")?,
                x_max_mm: t.number(i, "x_max_mm")?,
                pmax_mpa: t.number(i, "pmax_MPa")?,
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    strips.sort_by(|a, b| a.s_mm.total_cmp(&b.s_mm));
    if strips.len() < 2 {
        return Err(format!(
            "{}: at least two strips are needed to map s to yRail",
            t.path.display()
        ));
    }
    Ok(strips)
}

fn read_spin(t: &Table) -> Result<SpinSummary, String> {
    t.require_rows()?;
    for i in 0..t.len() {
        let phi = t.number(i, "cphi_per_mm")?;
        if phi > 0.0 {
            return Ok(SpinSummary {
                phi_per_mm: phi,
                fx_n: t.number(i, "fx_N")?,
                fs_n: t.number(i, "fs_N")?,
                mn_nmm: t.number(i, "mn_Nmm")?,
                adhesion_fraction: t.number(i, "adh_fraction")?,
            });
        }
    }
    Err(format!(
        "{}: no row with a positive spin cphi_per_mm (the report compares φ = +0.052 rad/m)",
        t.path.display()
    ))
}

/// CONTACT's in-plane s [mm] → rail coordinate [mm], linear through the strip table (extended
/// linearly beyond its ends).
pub fn y_rail_of_s(strips: &[RefStrip], s_mm: f64) -> f64 {
    let k = strips
        .partition_point(|r| r.s_mm < s_mm)
        .clamp(1, strips.len() - 1);
    let (a, b) = (&strips[k - 1], &strips[k]);
    a.y_rail_mm + (b.y_rail_mm - a.y_rail_mm) * (s_mm - a.s_mm) / (b.s_mm - a.s_mm)
}

fn read_traction(t: &Table, strips: &[RefStrip]) -> Result<Vec<RefTraction>, String> {
    t.require_rows()?;
    (0..t.len())
        .map(|i| {
            let s_mm = t.number(i, "s_mm")?;
            let state = t.number(i, "state")?;
            if state != 1.0 && state != 2.0 {
                return Err(format!(
                    "{}: line {}: state = {state}, expected 1 (adhesion) or 2 (slip)",
                    t.path.display(),
                    t.rows[i].0
                ));
            }
            Ok(RefTraction {
                x_mm: t.number(i, "x_mm")?,
                s_mm,
                y_rail_mm: y_rail_of_s(strips, s_mm),
                slip: state == 2.0,
                px_mpa: t.number(i, "px_MPa")?,
                ps_mpa: t.number(i, "ps_MPa")?,
            })
        })
        .collect()
}

fn read_creep(t: &Table) -> Result<Vec<RefCreep>, String> {
    let series = t.column("series")?;
    let mut out = Vec::new();
    for i in 0..t.len() {
        if t.text(i, series, "series")? != "c_pure_dy0" {
            continue;
        }
        out.push(RefCreep {
            xi: t.number(i, "cksi")?,
            eta: t.number(i, "ceta")?,
            phi_per_mm: t.number(i, "cphi_per_mm")?,
            fx_over_mufn: t.number(i, "fx_over_mufn")?,
            fs_over_mufn: t.number(i, "fs_over_mufn")?,
        });
    }
    if out.is_empty() {
        return Err(format!(
            "{}: no rows of series 'c_pure_dy0'",
            t.path.display()
        ));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_values_name_file_line_and_column() {
        let t = Table::parse(Path::new("bad.csv"), "a,b\n1,2\n3,x\n").unwrap();
        assert_eq!(t.number(0, "b").unwrap(), 2.0);
        let e = t.number(1, "b").unwrap_err();
        assert!(
            e.contains("bad.csv") && e.contains("line 3") && e.contains("column 2"),
            "{e}"
        );
        let e = t.number(0, "c").unwrap_err();
        assert!(e.contains("no column 'c'"), "{e}");
        let short = Table::parse(Path::new("short.csv"), "a,b\n1\n").unwrap();
        let e = short.number(0, "b").unwrap_err();
        assert!(e.contains("line 2") && e.contains("missing field"), "{e}");
    }

    #[test]
    fn s_maps_linearly_to_y_rail() {
        let strip = |s_mm, y_rail_mm| RefStrip {
            s_mm,
            y_rail_mm,
            x_min_mm: 0.0,
            x_max_mm: 0.0,
            pmax_mpa: 0.0,
        };
        let strips = [strip(-1.0, -11.0), strip(1.0, -9.0)];
        assert_eq!(y_rail_of_s(&strips, 0.0), -10.0);
        assert_eq!(y_rail_of_s(&strips, 3.0), -7.0);
    }
}
