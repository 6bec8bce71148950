//! A small FMI 2.0 CS host run on every packed FMU, through the `fmi_host` harness: unzips it,
//! loads its shared library from the platform folder the packer wrote (checking that all 34
//! `fmi2*` functions resolve), reads value references, the GUID and the default experiment from
//! the packed `modelDescription.xml` (not from the Rust table, as a real host would) and checks
//! the value references against the table, then runs the model's default experiment with the
//! unpacked `resources/` as `resourceLocation`, printing a table and what the FMU logged.

use crate::platform::Platform;
use fmi_host::{DefaultExperiment, Fmu, Instance, Status};
use railcontact::fmi::model::ModelInfo;
use std::path::Path;

/// What the default experiment sweeps and prints, per model.
struct Demo {
    /// Input swept linearly over the experiment's steps.
    sweep: &'static str,
    from: f64,
    to: f64,
    /// Outputs printed per step.
    columns: &'static [&'static str],
}

fn demo(model_identifier: &str) -> Option<Demo> {
    match model_identifier {
        "HertzContact" => Some(Demo {
            sweep: "eta",
            from: 0.0,
            to: -0.004,
            columns: &["a", "b", "pmax", "Fy", "Mz", "adhesionFraction"],
        }),
        "WheelRailContact" => Some(Demo {
            sweep: "y",
            from: 0.0,
            to: 0.008,
            columns: &[
                "right.p1.Fn",
                "right.p1.yRail",
                "right.p2.Fn",
                "right.p2.yRail",
                "right.p3.Fn",
                "right.p3.yRail",
                "right.Fy",
                "left.Fy",
            ],
        }),
        _ => None,
    }
}

/// Refuses an archive with an entry that is not deflated (how the packer writes every entry).
fn check_deflated(fmu: &Path) -> Result<(), String> {
    let file = std::fs::File::open(fmu).map_err(|e| format!("{}: {e}", fmu.display()))?;
    let mut archive = zip::ZipArchive::new(file).map_err(|e| format!("{}: {e}", fmu.display()))?;
    for i in 0..archive.len() {
        let entry = archive.by_index(i).map_err(|e| e.to_string())?;
        if entry.compression() != zip::CompressionMethod::Deflated {
            return Err(format!(
                "{}: entry {} is not deflated",
                fmu.display(),
                entry.name()
            ));
        }
    }
    Ok(())
}

/// Checks that the packed model description gives every variable of the table its value
/// reference.
fn check_value_references(info: &ModelInfo, fmu: &Fmu) -> Result<(), String> {
    for v in info.variables {
        let packed = fmu
            .description()
            .variable(v.name)
            .map_err(|e| e.to_string())?;
        if packed.vr != v.vr {
            return Err(format!(
                "{}: {} has value reference {} in the XML, {} in the table",
                info.model_identifier, v.name, packed.vr, v.vr
            ));
        }
    }
    Ok(())
}

/// Start, stop and step of the packed `<DefaultExperiment>`.
fn experiment(fmu: &Fmu) -> Result<(f64, f64, f64), String> {
    let id = &fmu.description().model_identifier;
    let de: DefaultExperiment = fmu
        .description()
        .default_experiment
        .ok_or_else(|| format!("{id}: no <DefaultExperiment> in the model description"))?;
    let (Some(stop), Some(step)) = (de.stop_time, de.step_size) else {
        return Err(format!(
            "{id}: <DefaultExperiment> needs stopTime and stepSize (it has {de:?})"
        ));
    };
    Ok((de.start_time.unwrap_or(0.0), stop, step))
}

fn check(status: Status, call: &str) -> Result<(), String> {
    if status == Status::Ok {
        Ok(())
    } else {
        Err(format!("{call} returned {status}"))
    }
}

/// Prints what the FMU logged (warnings and worse: it logs nothing else unless asked to).
fn print_log(instance: &Instance) {
    for m in instance.messages() {
        eprintln!("  [{} {}] {}", m.status, instance.name(), m.text);
    }
}

pub fn run_default_experiment(
    info: &ModelInfo,
    fmu_path: &Path,
    platform: &Platform,
    run_root: &Path,
) -> Result<(), String> {
    let id = info.model_identifier;
    let dir = run_root.join(id);
    let _ = std::fs::remove_dir_all(&dir);
    check_deflated(fmu_path)?;
    fmi_host::unzip(fmu_path, &dir).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(dir.join("resources")).map_err(|e| e.to_string())?;
    let fmu = Fmu::load(&dir, platform.folder).map_err(|e| format!("{id}: {e}"))?;
    check_value_references(info, &fmu)?;
    let Some(demo) = demo(id) else {
        println!("{id}: no default experiment defined in fmu-pack");
        return Ok(());
    };
    for name in std::iter::once(&demo.sweep).chain(demo.columns) {
        fmu.description()
            .variable(name)
            .map_err(|e| e.to_string())?;
    }
    let (start, stop, step) = experiment(&fmu)?;
    let steps = ((stop - start) / step).round().max(1.0) as usize;
    println!(
        "{id}: types platform {:?}, FMI version {}, {steps} steps of {step} s",
        fmu.types_platform(),
        fmu.version()
    );
    let instance = fmu.instantiate(id).map_err(|e| e.to_string())?;
    let result = sweep(&instance, &demo, (start, stop, step), steps);
    print_log(&instance);
    result.map_err(|e| format!("{id}: {e}"))
}

/// Initializes `f` at the sweep's first value, steps `steps` times with the swept input moving
/// linearly to its last value, prints a row of the demo's columns per step, terminates.
fn sweep(
    f: &Instance,
    demo: &Demo,
    (start, stop, step): (f64, f64, f64),
    steps: usize,
) -> Result<(), String> {
    check(f.setup_experiment(start, Some(stop)), "fmi2SetupExperiment")?;
    check(f.enter_initialization(), "fmi2EnterInitializationMode")?;
    check(f.set_real(demo.sweep, demo.from), "fmi2SetReal")?;
    check(f.exit_initialization(), "fmi2ExitInitializationMode")?;
    print!("{:>10} {:>12}", "t [s]", demo.sweep);
    for col in demo.columns {
        print!(" {col:>16}");
    }
    println!();
    let columns: Vec<u32> = demo.columns.iter().map(|c| f.vr(c)).collect();
    // A patch slot's column ("side.pK.…") prints "-" while the slot is empty (its Fn is zero).
    let slot_fn: Vec<Option<usize>> = demo
        .columns
        .iter()
        .map(|c| {
            let slot = c.rsplit_once('.').map(|(prefix, _)| prefix)?;
            slot.rsplit_once('.')
                .filter(|(_, p)| p.starts_with('p') && p[1..].parse::<u32>().is_ok())?;
            let fn_column = format!("{slot}.Fn");
            demo.columns.iter().position(|d| *d == fn_column)
        })
        .collect();
    let mut row = vec![0.0; columns.len()];
    for k in 0..steps {
        let t = start + k as f64 * step;
        let value = demo.from + (demo.to - demo.from) * (k + 1) as f64 / steps as f64;
        check(f.set_real(demo.sweep, value), "fmi2SetReal")?;
        check(f.step(t, step), "fmi2DoStep")?;
        check(f.get_reals(&columns, &mut row), "fmi2GetReal")?;
        print!("{:>10.4} {value:>12.4e}", t + step);
        for (x, fn_column) in row.iter().zip(&slot_fn) {
            if !x.is_finite() {
                return Err(format!("non-finite output {x}"));
            }
            if fn_column.is_some_and(|k| row[k] == 0.0) {
                print!(" {:>16}", "-");
            } else {
                print!(" {x:>16.6e}");
            }
        }
        println!();
    }
    check(f.terminate(), "fmi2Terminate")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pack::{write_fmu, Resources};
    use railcontact::models::wheel_rail_contact::INFO;

    /// `right.Fy` after one step of an instance of the unpacked FMU in `dir` (its functions
    /// linked into this test, its resources from `dir`), with wheelProfile = `wheel`; Err(log)
    /// when initialization fails.
    fn right_fy(dir: &Path, name: &str, wheel: &str) -> Result<f64, Vec<String>> {
        let functions = fmi_host::linked_functions!(railcontact::models::export);
        let resources = fmi_host::file_uri(&dir.join("resources"));
        let fmu = Fmu::linked(functions, INFO.model_description_xml, Some(resources)).unwrap();
        let f = fmu.instantiate(name).unwrap();
        assert_eq!(f.setup_experiment(0.0, None), Status::Ok);
        assert_eq!(f.set_string("wheelProfile", wheel), Status::Ok);
        assert_eq!(f.set_real("y", 0.003), Status::Ok);
        let ok = f.enter_initialization() == Status::Ok
            && f.exit_initialization() == Status::Ok
            && f.step(0.0, 1e-3) == Status::Ok;
        let fy = if ok {
            f.get_real("right.Fy").ok()
        } else {
            None
        };
        fy.ok_or_else(|| f.messages().into_iter().map(|m| m.text).collect())
    }

    #[test]
    fn a_bundled_profile_loads_by_its_bare_name() {
        let benchmark = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../tests/data/profiles/MBench_S1002_v3.prw")
            .canonicalize()
            .expect("the benchmark profiles are required");
        let dir = std::env::temp_dir().join(format!("fmu-pack-bundled-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        // The library is not loaded here (the test calls the model's exports linked into this
        // binary), so any bytes stand in for it.
        let library = dir.join("library");
        std::fs::write(&library, b"-").unwrap();
        let resources = Resources::new(std::slice::from_ref(&benchmark)).unwrap();
        let platform = Platform::of_target("x86_64-unknown-linux-gnu").unwrap();
        let fmu = dir.join("WheelRailContact.fmu");
        write_fmu(&INFO, &library, &platform, &resources, &fmu).unwrap();
        let unpacked = dir.join("unpacked");
        check_deflated(&fmu).unwrap();
        fmi_host::unzip(&fmu, &unpacked).unwrap();
        assert!(unpacked.join("resources/MBench_S1002_v3.prw").is_file());

        let bundled = right_fy(&unpacked, "bundled", "MBench_S1002_v3.prw").unwrap();
        let by_path = right_fy(&unpacked, "byPath", benchmark.to_str().unwrap()).unwrap();
        let builtin = right_fy(&unpacked, "builtin", "S1002").unwrap();
        assert_eq!(bundled.to_bits(), by_path.to_bits());
        assert_ne!(bundled, builtin);

        let log = right_fy(&unpacked, "missing", "MBench_S1002_v4.prw").unwrap_err();
        let resources_dir = std::path::absolute(unpacked.join("resources")).unwrap();
        let expected = format!(
            "looked in the FMU's resources folder ({})",
            resources_dir.join("MBench_S1002_v4.prw").display()
        );
        assert!(
            log.iter()
                .any(|m| m.contains("wheelProfile = \"MBench_S1002_v4.prw\"")
                    && m.contains(&expected)
                    && m.contains("the working directory")),
            "{expected:?} not in {log:#?}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
