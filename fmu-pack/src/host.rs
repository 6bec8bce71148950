//! A small FMI 2.0 CS host: unzips a packed FMU, loads its shared library (from the platform
//! folder the packer wrote) with fmi-sys's loader, checks that all 34 `fmi2*` functions resolve,
//! reads value references and the GUID from the packed `modelDescription.xml` (not from the Rust
//! table, as a real host would) and runs the model's default experiment with the unpacked
//! `resources/` as `resourceLocation`, printing a table.

use crate::platform::Platform;
use fmi_sys::fmi2::*;
use railcontact::fmi::model::ModelInfo;
use std::collections::HashMap;
use std::ffi::{CStr, CString};
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
                "right.p2.Fn",
                "right.p1.yRail",
                "right.p1.contactAngle",
                "right.p1.Fn",
                "right.Fy",
                "left.Fy",
            ],
        }),
        _ => None,
    }
}

/// Prints the FMU's log messages (routed by fmi-sys's variadic C logger through `log`).
struct StderrLog;
impl log::Log for StderrLog {
    fn enabled(&self, _: &log::Metadata<'_>) -> bool {
        true
    }
    fn log(&self, record: &log::Record<'_>) {
        eprintln!(
            "  [{} {}] {}",
            record.level(),
            record.target(),
            record.args()
        );
    }
    fn flush(&self) {}
}
static LOGGER: StderrLog = StderrLog;

pub fn unzip(fmu: &Path, dir: &Path) -> Result<(), String> {
    let file = std::fs::File::open(fmu).map_err(|e| format!("{}: {e}", fmu.display()))?;
    let mut archive = zip::ZipArchive::new(file).map_err(|e| format!("{}: {e}", fmu.display()))?;
    for i in 0..archive.len() {
        let mut entry = archive.by_index(i).map_err(|e| e.to_string())?;
        if entry.compression() != zip::CompressionMethod::Deflated {
            return Err(format!(
                "{}: entry {} is not deflated",
                fmu.display(),
                entry.name()
            ));
        }
        let Some(rel) = entry.enclosed_name() else {
            return Err(format!(
                "{}: unsafe entry name {}",
                fmu.display(),
                entry.name()
            ));
        };
        let path = dir.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|e| e.to_string())?;
        }
        let mut out = std::fs::File::create(&path).map_err(|e| e.to_string())?;
        std::io::copy(&mut entry, &mut out).map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// `attr="value"` inside one XML tag.
fn attribute<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    let len = tag[start..].find('"')?;
    Some(&tag[start..start + len])
}

/// GUID and name → value reference from a model description.
fn parse_model_description(xml: &str) -> Result<(String, HashMap<String, u32>), String> {
    let root = xml
        .find("<fmiModelDescription")
        .map(|i| &xml[i..])
        .ok_or("no <fmiModelDescription>")?;
    let guid = attribute(&root[..root.find('>').unwrap_or(root.len())], "guid")
        .ok_or("no guid attribute")?
        .to_string();
    let mut vrs = HashMap::new();
    for tag in xml.split("<ScalarVariable").skip(1) {
        let tag = &tag[..tag.find('>').unwrap_or(tag.len())];
        let name = attribute(tag, "name").ok_or("ScalarVariable without name")?;
        let vr = attribute(tag, "valueReference")
            .and_then(|v| v.parse().ok())
            .ok_or_else(|| format!("{name}: bad valueReference"))?;
        vrs.insert(name.replace("&quot;", "\""), vr);
    }
    Ok((guid, vrs))
}

fn check(status: fmi2Status, call: &str) -> Result<(), String> {
    if status == fmi2Status_fmi2OK {
        Ok(())
    } else {
        Err(format!("{call} returned status {status}"))
    }
}

/// Checks every one of the 34 FMI 2.0 CS functions resolves in the loaded library.
fn check_exports(b: &Fmi2Binding) -> Result<(), String> {
    let missing: Vec<&str> = [
        ("fmi2GetTypesPlatform", b.fmi2GetTypesPlatform.is_ok()),
        ("fmi2GetVersion", b.fmi2GetVersion.is_ok()),
        ("fmi2SetDebugLogging", b.fmi2SetDebugLogging.is_ok()),
        ("fmi2Instantiate", b.fmi2Instantiate.is_ok()),
        ("fmi2FreeInstance", b.fmi2FreeInstance.is_ok()),
        ("fmi2SetupExperiment", b.fmi2SetupExperiment.is_ok()),
        (
            "fmi2EnterInitializationMode",
            b.fmi2EnterInitializationMode.is_ok(),
        ),
        (
            "fmi2ExitInitializationMode",
            b.fmi2ExitInitializationMode.is_ok(),
        ),
        ("fmi2Terminate", b.fmi2Terminate.is_ok()),
        ("fmi2Reset", b.fmi2Reset.is_ok()),
        ("fmi2GetReal", b.fmi2GetReal.is_ok()),
        ("fmi2GetInteger", b.fmi2GetInteger.is_ok()),
        ("fmi2GetBoolean", b.fmi2GetBoolean.is_ok()),
        ("fmi2GetString", b.fmi2GetString.is_ok()),
        ("fmi2SetReal", b.fmi2SetReal.is_ok()),
        ("fmi2SetInteger", b.fmi2SetInteger.is_ok()),
        ("fmi2SetBoolean", b.fmi2SetBoolean.is_ok()),
        ("fmi2SetString", b.fmi2SetString.is_ok()),
        ("fmi2GetFMUstate", b.fmi2GetFMUstate.is_ok()),
        ("fmi2SetFMUstate", b.fmi2SetFMUstate.is_ok()),
        ("fmi2FreeFMUstate", b.fmi2FreeFMUstate.is_ok()),
        (
            "fmi2SerializedFMUstateSize",
            b.fmi2SerializedFMUstateSize.is_ok(),
        ),
        ("fmi2SerializeFMUstate", b.fmi2SerializeFMUstate.is_ok()),
        ("fmi2DeSerializeFMUstate", b.fmi2DeSerializeFMUstate.is_ok()),
        (
            "fmi2GetDirectionalDerivative",
            b.fmi2GetDirectionalDerivative.is_ok(),
        ),
        (
            "fmi2SetRealInputDerivatives",
            b.fmi2SetRealInputDerivatives.is_ok(),
        ),
        (
            "fmi2GetRealOutputDerivatives",
            b.fmi2GetRealOutputDerivatives.is_ok(),
        ),
        ("fmi2DoStep", b.fmi2DoStep.is_ok()),
        ("fmi2CancelStep", b.fmi2CancelStep.is_ok()),
        ("fmi2GetStatus", b.fmi2GetStatus.is_ok()),
        ("fmi2GetRealStatus", b.fmi2GetRealStatus.is_ok()),
        ("fmi2GetIntegerStatus", b.fmi2GetIntegerStatus.is_ok()),
        ("fmi2GetBooleanStatus", b.fmi2GetBooleanStatus.is_ok()),
        ("fmi2GetStringStatus", b.fmi2GetStringStatus.is_ok()),
    ]
    .into_iter()
    .filter(|(_, ok)| !ok)
    .map(|(name, _)| name)
    .collect();
    if missing.is_empty() {
        Ok(())
    } else {
        Err(format!("missing exports: {}", missing.join(", ")))
    }
}

/// A `file:` URI of an absolute path as hosts give `resourceLocation`: `file:///abs/path` with
/// forward slashes (`file:///C:/dir` on Windows) and bytes other than unreserved characters,
/// `/` and `:` percent-encoded.
pub fn file_uri(path: &Path) -> String {
    let mut text = path.to_string_lossy().into_owned();
    if cfg!(windows) {
        text = text.replace('\\', "/");
    }
    let mut uri = String::from("file://");
    if !text.starts_with('/') {
        uri.push('/');
    }
    for b in text.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~/:".contains(&b) {
            uri.push(b as char);
        } else {
            uri.push_str(&format!("%{b:02X}"));
        }
    }
    uri
}

pub fn run_default_experiment(
    info: &ModelInfo,
    fmu: &Path,
    platform: &Platform,
    run_root: &Path,
) -> Result<(), String> {
    let _ = log::set_logger(&LOGGER).map(|()| log::set_max_level(log::LevelFilter::Warn));
    let id = info.model_identifier;
    let dir = run_root.join(id);
    let _ = std::fs::remove_dir_all(&dir);
    unzip(fmu, &dir)?;
    let xml =
        std::fs::read_to_string(dir.join("modelDescription.xml")).map_err(|e| e.to_string())?;
    let (guid, vrs) = parse_model_description(&xml)?;
    for v in info.variables {
        if vrs.get(v.name) != Some(&v.vr) {
            return Err(format!(
                "{id}: {} has a different value reference in the XML",
                v.name
            ));
        }
    }
    let library = dir.join(platform.fmu_library(id));
    // SAFETY: loading our own freshly built library.
    let b =
        unsafe { Fmi2Binding::new(&library) }.map_err(|e| format!("{}: {e}", library.display()))?;
    check_exports(&b)?;
    let Some(demo) = demo(id) else {
        println!("{id}: no default experiment defined in fmu-pack");
        return Ok(());
    };
    let vr = |name: &str| {
        vrs.get(name)
            .copied()
            .ok_or_else(|| format!("{id}: no variable {name}"))
    };
    let sweep_vr = vr(demo.sweep)?;
    let column_vrs: Vec<u32> = demo
        .columns
        .iter()
        .map(|c| vr(c))
        .collect::<Result<_, _>>()?;

    let resources = dir.join("resources");
    std::fs::create_dir_all(&resources).map_err(|e| e.to_string())?;
    let c_name = CString::new(id).expect("identifier");
    let c_guid = CString::new(guid).map_err(|e| e.to_string())?;
    let resources = std::path::absolute(&resources).map_err(|e| e.to_string())?;
    let c_uri = CString::new(file_uri(&resources)).map_err(|e| e.to_string())?;
    let callbacks = fmi2CallbackFunctions {
        logger: Some(fmi_sys::fmi2::logger::callback_logger_handler),
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: std::ptr::null_mut(),
    };
    let de = info.default_experiment;
    let steps = ((de.stop_time - de.start_time) / de.step_size)
        .round()
        .max(1.0) as usize;
    // SAFETY: FMI calls with valid pointers on a library whose exports were checked above.
    unsafe {
        let platform = CStr::from_ptr(b.fmi2GetTypesPlatform()).to_string_lossy();
        let version = CStr::from_ptr(b.fmi2GetVersion()).to_string_lossy();
        println!(
            "{id}: types platform {platform:?}, FMI version {version}, {steps} steps of {} s",
            de.step_size
        );
        let c = b.fmi2Instantiate(
            c_name.as_ptr(),
            fmi2Type_fmi2CoSimulation,
            c_guid.as_ptr(),
            c_uri.as_ptr(),
            &callbacks,
            0,
            0,
        );
        if c.is_null() {
            return Err(format!("{id}: fmi2Instantiate returned NULL"));
        }
        let result = (|| {
            check(
                b.fmi2SetupExperiment(c, 0, 0.0, de.start_time, 1, de.stop_time),
                "fmi2SetupExperiment",
            )?;
            check(
                b.fmi2EnterInitializationMode(c),
                "fmi2EnterInitializationMode",
            )?;
            check(b.fmi2SetReal(c, &sweep_vr, 1, &demo.from), "fmi2SetReal")?;
            check(
                b.fmi2ExitInitializationMode(c),
                "fmi2ExitInitializationMode",
            )?;
            print!("{:>10} {:>12}", "t [s]", demo.sweep);
            for col in demo.columns {
                print!(" {col:>16}");
            }
            println!();
            let mut row = vec![0.0; column_vrs.len()];
            for k in 0..steps {
                let t = de.start_time + k as f64 * de.step_size;
                let value = demo.from + (demo.to - demo.from) * (k + 1) as f64 / steps as f64;
                check(b.fmi2SetReal(c, &sweep_vr, 1, &value), "fmi2SetReal")?;
                check(b.fmi2DoStep(c, t, de.step_size, 1), "fmi2DoStep")?;
                check(
                    b.fmi2GetReal(c, column_vrs.as_ptr(), column_vrs.len(), row.as_mut_ptr()),
                    "fmi2GetReal",
                )?;
                print!("{:>10.4} {value:>12.4e}", t + de.step_size);
                for x in &row {
                    if !x.is_finite() {
                        return Err(format!("{id}: non-finite output {x}"));
                    }
                    print!(" {x:>16.6e}");
                }
                println!();
            }
            check(b.fmi2Terminate(c), "fmi2Terminate")
        })();
        b.fmi2FreeInstance(c);
        result.map_err(|e| format!("{id}: {e}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pack::{write_fmu, Resources};
    use railcontact::fmi::export::*;
    use railcontact::models::wheel_rail_contact::INFO;
    use std::sync::Mutex;

    /// The FMU's log messages, by instance name.
    struct Capture(Mutex<Vec<(String, String)>>);
    impl log::Log for Capture {
        fn enabled(&self, _: &log::Metadata<'_>) -> bool {
            true
        }
        fn log(&self, r: &log::Record<'_>) {
            let mut v = self.0.lock().unwrap();
            v.push((r.target().to_string(), r.args().to_string()));
        }
        fn flush(&self) {}
    }
    static CAPTURE: Capture = Capture(Mutex::new(Vec::new()));

    #[test]
    fn file_uris_of_paths() {
        assert_eq!(
            file_uri(Path::new("/tmp/a b/résources")),
            "file:///tmp/a%20b/r%C3%A9sources"
        );
        assert_eq!(
            file_uri(Path::new(r"C:\x\resources")),
            if cfg!(windows) {
                "file:///C:/x/resources"
            } else {
                "file:///C:%5Cx%5Cresources"
            }
        );
    }

    /// `right.Fy` after one step of an instance of the unpacked FMU in `dir`, with wheelProfile
    /// = `wheel`; Err(log) when initialization fails.
    fn right_fy(dir: &Path, name: &str, wheel: &str) -> Result<f64, Vec<String>> {
        let _ = log::set_logger(&CAPTURE).map(|()| log::set_max_level(log::LevelFilter::Trace));
        let vr = |n: &str| INFO.variable(n).unwrap().vr;
        let callbacks = fmi2CallbackFunctions {
            logger: Some(fmi_sys::fmi2::logger::callback_logger_handler),
            allocateMemory: None,
            freeMemory: None,
            stepFinished: None,
            componentEnvironment: std::ptr::null_mut(),
        };
        let uri = CString::new(file_uri(&dir.join("resources"))).unwrap();
        let (c_name, guid) = (
            CString::new(name).unwrap(),
            CString::new(INFO.guid).unwrap(),
        );
        let wheel = CString::new(wheel).unwrap();
        // SAFETY: valid strings, callbacks and value references for the calls' duration.
        unsafe {
            let c = fmi2Instantiate(
                c_name.as_ptr(),
                fmi2Type_fmi2CoSimulation,
                guid.as_ptr(),
                uri.as_ptr(),
                &callbacks,
                0,
                0,
            );
            assert!(!c.is_null());
            assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), 0);
            assert_eq!(fmi2SetString(c, &vr("wheelProfile"), 1, &wheel.as_ptr()), 0);
            let y = 0.003;
            assert_eq!(fmi2SetReal(c, &vr("y"), 1, &y), 0);
            let ok = fmi2EnterInitializationMode(c) == 0 && fmi2ExitInitializationMode(c) == 0;
            let mut fy = f64::NAN;
            let ok = ok
                && fmi2DoStep(c, 0.0, 1e-3, 1) == 0
                && fmi2GetReal(c, &vr("right.Fy"), 1, &mut fy) == 0;
            fmi2FreeInstance(c);
            if ok {
                Ok(fy)
            } else {
                let log = CAPTURE.0.lock().unwrap();
                Err(log
                    .iter()
                    .filter(|(t, _)| t == name)
                    .map(|(_, m)| m.clone())
                    .collect())
            }
        }
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
        unzip(&fmu, &unpacked).unwrap();
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
