//! `fmi2DoStep` through the C ABI: a Rust host loads the packed WheelRailContact FMU's
//! shared library (`libloading`), instantiates it as any FMI host does, sets the normal model and
//! 78.5 kN per wheel, and times `fmi2DoStep` of 1 ms with constant inputs (the central case) and
//! with the lateral shift following 3 mm sin 2πt (set before each step). Compare with
//! `wheelset/*_central` and `moving/*` of the `contact` bench (the model alone): the difference
//! is the FMI layer's overhead.
//!
//! Needs the packed FMU: `cargo run --release -p fmu-pack` first (`FMU_DIR` overrides
//! `target/fmu`); without it the bench says so and measures nothing.
//! `cargo bench --bench fmu_dostep`; figures in docs/performance.md.

use std::ffi::{c_char, CString};
use std::io::Read;
use std::path::{Path, PathBuf};

use criterion::{criterion_group, criterion_main, Criterion};
use fmi_sys::fmi2::{
    fmi2CallbackFunctions, fmi2Component, fmi2Integer, fmi2Real, fmi2Status, fmi2Type,
    fmi2Type_fmi2CoSimulation, fmi2ValueReference,
};
use libloading::Library;

/// Wheel load of the central case [N].
const LOAD: f64 = 78_500.0;
/// Communication step [s].
const STEP: f64 = 1e-3;

type Instantiate = unsafe extern "C" fn(
    *const c_char,
    fmi2Type,
    *const c_char,
    *const c_char,
    *const fmi2CallbackFunctions,
    i32,
    i32,
) -> fmi2Component;
type Setup = unsafe extern "C" fn(fmi2Component, i32, f64, f64, i32, f64) -> fmi2Status;
type Transition = unsafe extern "C" fn(fmi2Component) -> fmi2Status;
type SetReal = unsafe extern "C" fn(
    fmi2Component,
    *const fmi2ValueReference,
    usize,
    *const fmi2Real,
) -> fmi2Status;
type SetInteger = unsafe extern "C" fn(
    fmi2Component,
    *const fmi2ValueReference,
    usize,
    *const fmi2Integer,
) -> fmi2Status;
type DoStep = unsafe extern "C" fn(fmi2Component, f64, f64, i32) -> fmi2Status;
type FreeInstance = unsafe extern "C" fn(fmi2Component);

/// The unpacked FMU: its library, GUID and the value references the bench sets.
struct Unpacked {
    library: PathBuf,
    resources: PathBuf,
    guid: String,
    normal_model: u32,
    q_left: u32,
    q_right: u32,
    y: u32,
}

/// Extracts `fmu` into `dir` and reads what the bench needs from its modelDescription.xml.
fn unpack(fmu: &Path, dir: &Path) -> Unpacked {
    let file = std::fs::File::open(fmu).expect("open the FMU");
    let mut archive = zip::ZipArchive::new(file).expect("the FMU is a zip archive");
    archive.extract(dir).expect("extract the FMU");
    let mut xml = String::new();
    archive
        .by_name("modelDescription.xml")
        .expect("modelDescription.xml in the FMU")
        .read_to_string(&mut xml)
        .expect("read modelDescription.xml");
    let attribute = |text: &str, name: &str| -> Option<String> {
        let key = format!("{name}=\"");
        let start = text.find(&key)? + key.len();
        let end = text[start..].find('"')? + start;
        Some(text[start..end].to_string())
    };
    let reference = |variable: &str| -> u32 {
        xml.split("<ScalarVariable")
            .find(|chunk| attribute(chunk, "name").as_deref() == Some(variable))
            .and_then(|chunk| attribute(chunk, "valueReference"))
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("variable {variable} in modelDescription.xml"))
    };
    let identifier = attribute(&xml, "modelIdentifier").expect("modelIdentifier");
    Unpacked {
        library: dir.join(format!("binaries/linux64/{identifier}.so")),
        resources: dir.join("resources"),
        guid: attribute(&xml, "guid").expect("guid"),
        normal_model: reference("normalModel"),
        q_left: reference("Qleft"),
        q_right: reference("Qright"),
        y: reference("y"),
    }
}

/// One initialized instance of the FMU and the entry points the loop calls.
struct Instance {
    component: fmi2Component,
    set_real: SetReal,
    do_step: DoStep,
    free: FreeInstance,
    y: u32,
    time: f64,
    _library: Library,
}

impl Instance {
    fn new(fmu: &Unpacked, normal_model: i32) -> Self {
        // SAFETY: the library is the FMU's own, whose entry points have these FMI 2.0
        // signatures; every call below follows the FMI 2.0 calling sequence of a
        // Co-Simulation slave, and the library outlives the instance (kept in it).
        unsafe {
            let library = Library::new(&fmu.library).expect("load the FMU's library");
            let instantiate = *library.get::<Instantiate>(b"fmi2Instantiate").unwrap();
            let setup = *library.get::<Setup>(b"fmi2SetupExperiment").unwrap();
            let enter = *library
                .get::<Transition>(b"fmi2EnterInitializationMode")
                .unwrap();
            let exit = *library
                .get::<Transition>(b"fmi2ExitInitializationMode")
                .unwrap();
            let set_integer = *library.get::<SetInteger>(b"fmi2SetInteger").unwrap();
            let set_real = *library.get::<SetReal>(b"fmi2SetReal").unwrap();
            let do_step = *library.get::<DoStep>(b"fmi2DoStep").unwrap();
            let free = *library.get::<FreeInstance>(b"fmi2FreeInstance").unwrap();
            let name = CString::new("bench").unwrap();
            let guid = CString::new(fmu.guid.as_str()).unwrap();
            let uri = CString::new(format!("file://{}", fmu.resources.display())).unwrap();
            // No logger: the bench's calls succeed or it stops on their status.
            let callbacks = fmi2CallbackFunctions {
                logger: None,
                allocateMemory: None,
                freeMemory: None,
                stepFinished: None,
                componentEnvironment: std::ptr::null_mut(),
            };
            let component = instantiate(
                name.as_ptr(),
                fmi2Type_fmi2CoSimulation,
                guid.as_ptr(),
                uri.as_ptr(),
                &callbacks,
                0,
                0,
            );
            assert!(!component.is_null(), "fmi2Instantiate failed");
            let ok = |status: fmi2Status, call: &str| assert_eq!(status, 0, "{call}");
            ok(setup(component, 0, 0.0, 0.0, 0, 0.0), "fmi2SetupExperiment");
            ok(
                set_integer(component, &fmu.normal_model, 1, &normal_model),
                "fmi2SetInteger normalModel",
            );
            ok(enter(component), "fmi2EnterInitializationMode");
            ok(set_real(component, &fmu.q_left, 1, &LOAD), "Qleft");
            ok(set_real(component, &fmu.q_right, 1, &LOAD), "Qright");
            ok(exit(component), "fmi2ExitInitializationMode");
            let mut instance = Self {
                component,
                set_real,
                do_step,
                free,
                y: fmu.y,
                time: 0.0,
                _library: library,
            };
            // The first step is a cold start; the timed ones are warm.
            instance.step(None);
            instance
        }
    }

    /// One `fmi2DoStep` of [`STEP`], after setting the lateral shift `y` [m] if given.
    fn step(&mut self, y: Option<f64>) {
        // SAFETY: an initialized instance of the library kept alive in `self`.
        unsafe {
            if let Some(y) = y {
                assert_eq!((self.set_real)(self.component, &self.y, 1, &y), 0, "y");
            }
            let status = (self.do_step)(self.component, self.time, STEP, 1);
            assert_eq!(status, 0, "fmi2DoStep at t = {}", self.time);
        }
        self.time += STEP;
    }
}

impl Drop for Instance {
    fn drop(&mut self) {
        // SAFETY: the instance was created by this library and is freed once.
        unsafe { (self.free)(self.component) }
    }
}

fn bench_dostep(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let fmu_dir = std::env::var_os("FMU_DIR").map_or(root.join("target/fmu"), PathBuf::from);
    let fmu = fmu_dir.join("WheelRailContact.fmu");
    if !fmu.is_file() {
        eprintln!(
            "fmu_dostep: {} is missing — run `cargo run --release -p fmu-pack` first; nothing \
             measured",
            fmu.display()
        );
        return;
    }
    let dir = std::env::temp_dir().join(format!("railcontact-bench-{}", std::process::id()));
    let unpacked = unpack(&fmu, &dir);
    let mut group = c.benchmark_group("fmu_dostep");
    for (code, name) in [(1, "hertz"), (5, "stripes-ab"), (6, "analyn")] {
        let mut steady = Instance::new(&unpacked, code);
        group.bench_function(format!("{name}_constant"), |b| b.iter(|| steady.step(None)));
        let mut moving = Instance::new(&unpacked, code);
        group.bench_function(format!("{name}_moving"), |b| {
            b.iter(|| {
                let y = 3e-3 * (2.0 * std::f64::consts::PI * moving.time).sin();
                moving.step(Some(y))
            })
        });
    }
    group.finish();
    std::fs::remove_dir_all(&dir).ok();
}

criterion_group!(benches, bench_dostep);
criterion_main!(benches);
