//! Profile readers against the Manchester benchmark files and malformed input.
//!
//! The benchmark files are vendored in `tests/data/profiles/` (see `tests/data/README.md`). Malformed inputs are written to a
//! temporary directory; every error message must name the file, the line (where one is to blame)
//! and the reason, and nothing may panic.

#[path = "common/lcg.rs"]
mod lcg;

use lcg::Lcg;
use std::path::{Path, PathBuf};

use railcontact::geometry::profile::{
    smoothing_length_for_noise, ErrorReason, Profile, ProfileKind,
};

const MM: f64 = 1000.0;

fn bench_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/profiles")
}

fn bench(name: &str) -> PathBuf {
    let p = bench_dir().join(name);
    assert!(p.is_file(), "benchmark profile {} not found", p.display());
    p
}

/// A fresh file in a per-process temporary directory.
fn temp_file(name: &str, bytes: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("railcontact-profiles-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// The benchmark wheel comes out in the canonical frame (y ascending from −69.6 to +60 mm after
/// mirror.y and inversion) and matches the built-in S1002. The file's points lie on the analytic
/// F to 1.6e−6 mm; the difference is the interpolation of the file's 0.03–0.45 mm spacing: largest
/// (measured ≈ 0.03 mm) next to s = −69.6, where the flange back turns vertical; ≈ 1e−3 mm over the
/// flange and tread. Tolerances: 0.05 mm over −69.6…60 mm, 2e−3 mm over −65…60 mm.
#[test]
fn benchmark_wheel_matches_builtin_s1002() {
    let file = Profile::from_file(&bench("MBench_S1002_v3.prw"), None, 0.0).unwrap();
    assert_eq!(file.kind(), ProfileKind::Wheel);
    let (a, b) = file.y_range();
    assert!((a * MM + 69.612628).abs() < 1e-9 && (b * MM - 60.0).abs() < 1e-9);
    let builtin = Profile::builtin("S1002").unwrap();
    let (mut worst, mut worst_tread_flange) = (0.0f64, 0.0f64);
    let n = 12_961;
    for i in 0..n {
        let y = a + (b - a) * i as f64 / (n - 1) as f64;
        let d = (file.z(y) - builtin.z(y)).abs() * MM;
        worst = worst.max(d);
        if y * MM >= -65.0 {
            worst_tread_flange = worst_tread_flange.max(d);
        }
    }
    eprintln!(
        "S1002 file vs built-in: max {worst:.2e} mm, over -65..60 mm {worst_tread_flange:.2e} mm"
    );
    assert!(worst < 0.05, "{worst} mm");
    assert!(worst_tread_flange < 2e-3, "{worst_tread_flange} mm");
    // Flange height and taping line through the file.
    assert!((file.z(-0.055) * MM - 28.0).abs() < 1e-3);
    assert!(file.z(0.0).abs() * MM < 1e-3);
    // Loading by spec.
    let spec = bench("MBench_S1002_v3.prw");
    let p = Profile::load(spec.to_str().unwrap(), ProfileKind::Wheel, 0.0).unwrap();
    assert_eq!(p.points(), file.points());
    let e = Profile::load(spec.to_str().unwrap(), ProfileKind::Rail, 0.0).unwrap_err();
    assert!(matches!(e.reason, ErrorReason::KindMismatch { .. }), "{e}");
}

/// docs/theory.md §7.3: the benchmark rail's head is 71.95 mm wide at z = 14 mm (±0.05 mm); the
/// origin is its highest point.
#[test]
fn benchmark_rail_head_width() {
    let rail = Profile::from_file(&bench("MBench_UIC60_v3.prr"), None, 0.0).unwrap();
    assert_eq!(rail.kind(), ProfileKind::Rail);
    let w = rail.width_at_depth(0.014).unwrap() * MM;
    eprintln!("benchmark rail head width at 14 mm: {w:.4} mm");
    assert!((w - 71.95).abs() < 0.05, "{w}");
    let (z0, d0, _) = rail.eval(0.0);
    assert!(z0.abs() * MM < 1e-3 && d0.abs() < 1e-3, "{z0} {d0}");
}

/// The `.ban` file is the same rail as the `.prr` (mirrored X, same points): z within 0.01 mm
/// over the head (|y| where z ≤ 20 mm); measured ≈ 0 (identical points, rounding only).
#[test]
fn ban_and_prr_describe_the_same_rail() {
    let prr = Profile::from_file(&bench("MBench_UIC60_v3.prr"), None, 0.0).unwrap();
    let ban = Profile::from_file(&bench("MBench_UIC60_v3.ban"), None, 0.0).unwrap();
    assert_eq!(ban.kind(), ProfileKind::Rail);
    assert_eq!(ban.points().0.len(), prr.points().0.len());
    let (a, b) = prr.y_range();
    let mut worst = 0.0f64;
    let mut compared = 0;
    for i in 0..=20_000 {
        let y = a + (b - a) * i as f64 / 20_000.0;
        if prr.z(y) <= 0.020 {
            worst = worst.max((prr.z(y) - ban.z(y)).abs() * MM);
            compared += 1;
        }
    }
    assert!(compared > 10_000);
    assert!(worst < 0.01, "{worst} mm");
}

/// The built-in 60E1 against the de-canted benchmark rail: the crown and R80 agree within 2 µm
/// (the built-in junction y₁ = 10.5 mm was fitted to them), the gauge corner within 0.05 mm (the
/// benchmark's head is 71.95, not 72.00 mm wide).
#[test]
fn builtin_uic60_against_the_decanted_benchmark() {
    let rail = Profile::from_file(&bench("MBench_UIC60_v3.prr"), None, 0.0).unwrap();
    let builtin = Profile::builtin("60E1").unwrap();
    let theta = (1.0f64 / 40.0).atan();
    let (c, s) = (theta.cos(), theta.sin());
    let r = 0.3;
    let (ty, tz) = (-r * s, -r * (1.0 - c));
    let (ys, zs) = rail.points();
    let (mut crown, mut corner) = (0.0f64, 0.0f64);
    for (&y, &z) in ys.iter().zip(zs) {
        let (ym, zm) = (c * y - s * z - ty, s * y + c * z - tz);
        let d = (zm - builtin.z(ym)).abs() * MM;
        if ym.abs() < 0.025 {
            crown = crown.max(d);
        } else if ym.abs() < 0.034 {
            corner = corner.max(d);
        }
    }
    eprintln!("60E1 vs de-canted benchmark: crown+R80 {crown:.2e} mm, corner {corner:.2e} mm");
    assert!(crown < 2e-3, "{crown}");
    assert!(corner < 0.05, "{corner}");
}

/// Asserts an error whose text names the file, the line (if given) and contains `reason`.
fn expect_error(
    name: &str,
    content: &[u8],
    kind: Option<ProfileKind>,
    line: Option<usize>,
    reason: &str,
) {
    let path = temp_file(name, content);
    let e = Profile::from_file(&path, kind, 0.0).unwrap_err();
    let text = e.to_string();
    assert!(text.contains(&path.display().to_string()), "{name}: {text}");
    if let Some(k) = line {
        assert!(text.contains(&format!("line {k}:")), "{name}: {text}");
        assert_eq!(e.line(), Some(k), "{name}: {text}");
    }
    assert!(text.contains(reason), "{name}: {text}");
}

const PRR_HEAD: &str =
    "header.begin\n  type = 0\nheader.end\nspline.begin\n  units.len.f = 1000\n  point.begin\n";
const PRR_TAIL: &str = "  point.end\nspline.end\n";

#[test]
fn malformed_inputs_give_located_errors() {
    let rail = Some(ProfileKind::Rail);
    // Non-numeric value on line 9 (6 header lines, points on lines 7, 8, 9, …).
    let prr = format!("{PRR_HEAD}-10 1\n-5 0.5\n0 abc\n5 0.5\n10 1\n{PRR_TAIL}");
    expect_error(
        "nonnum.prr",
        prr.as_bytes(),
        None,
        Some(9),
        "non-numeric value \"abc\"",
    );
    expect_error(
        "nonnum.csv",
        b"y,z\n1,2\n2,3\n3,x4\n4,5\n",
        rail,
        Some(4),
        "non-numeric value \"x4\"",
    );
    // Non-monotonic lateral coordinate on line 10.
    let prr = format!("{PRR_HEAD}-10 1\n-5 0.5\n0 0\n-1 0.5\n10 1\n{PRR_TAIL}");
    expect_error(
        "nonmono.prr",
        prr.as_bytes(),
        None,
        Some(10),
        "non-monotonic lateral coordinate",
    );
    expect_error(
        "nonmono.txt",
        b"1 2\n2 3\n2 3\n4 5\n",
        rail,
        Some(3),
        "non-monotonic",
    );
    // Three points.
    let prr = format!("{PRR_HEAD}-10 1\n0 0\n10 1\n{PRR_TAIL}");
    expect_error("three.prr", prr.as_bytes(), None, None, "too few points (3");
    expect_error(
        "three.csv",
        b"1;2\n2;3\n3;4\n",
        rail,
        None,
        "too few points (3",
    );
    // NaN and infinities, also by overflow.
    let prr = format!("{PRR_HEAD}-10 1\n-5 NaN\n0 0\n10 1\n{PRR_TAIL}");
    expect_error(
        "nan.prr",
        prr.as_bytes(),
        None,
        Some(8),
        "not a finite number",
    );
    expect_error(
        "inf.csv",
        b"1 2\n2 3\n3 1e999\n4 5\n",
        rail,
        Some(3),
        "not a finite number",
    );
    expect_error(
        "huge.csv",
        b"1 2\n2 3\n3 1e300\n4 5\n",
        rail,
        Some(3),
        "out of range",
    );
    // Empty files.
    expect_error("empty.prr", b"", None, None, "missing point block");
    expect_error("empty.csv", b"", rail, None, "too few points (0");
    expect_error("empty.ban", b"", None, None, "too few points (0");
    // Missing point.end: the error points at point.begin (line 6).
    let prr = format!("{PRR_HEAD}-10 1\n-5 0.5\n0 0\n10 1\nspline.end\n");
    expect_error(
        "noend.prr",
        prr.as_bytes(),
        None,
        Some(6),
        "no matching 'point.end'",
    );
    // Binary garbage.
    expect_error(
        "garbage.prr",
        b"\x7fELF\x02\x01\x01\0\0\0",
        None,
        Some(1),
        "binary data",
    );
    expect_error(
        "garbage.ban",
        b"Filename=x\n\x00\x01",
        None,
        Some(2),
        "binary data",
    );
    // Kind needed for plain text; unknown built-in names.
    expect_error(
        "nokind.csv",
        b"1 2\n2 3\n3 4\n4 5\n",
        None,
        None,
        "pass the profile kind",
    );
    let e = Profile::load("S1003", ProfileKind::Wheel, 0.0).unwrap_err();
    assert!(
        e.to_string().contains("unknown built-in profile \"S1003\""),
        "{e}"
    );
    // Wrong kind in the header.
    let prw = "header.begin\n type = 1\nheader.end\npoint.begin\n0 0\n1 1\n2 0\n3 1\npoint.end\n";
    let path = temp_file("wheel_as_rail.prr", prw.as_bytes());
    let e = Profile::load(path.to_str().unwrap(), ProfileKind::Rail, 0.0).unwrap_err();
    assert!(
        e.to_string()
            .contains("this is a wheel profile but a rail profile is required"),
        "{e}"
    );
}

/// Random bytes, random text and mutated benchmark files through every reader: never a panic.
#[test]
fn no_panic_on_arbitrary_input() {
    let mut rng = Lcg(7);
    let base = std::fs::read(bench("MBench_UIC60_v3.prr")).unwrap();
    let alphabet = b"0123456789.-+eE \t,;\n!'=\"abnNiI";
    for case in 0..300 {
        let bytes: Vec<u8> = match case % 3 {
            0 => (0..(rng.next_u31() % 2000))
                .map(|_| rng.next_u31() as u8)
                .collect(),
            1 => (0..(rng.next_u31() % 2000))
                .map(|_| alphabet[(rng.next_u31() as usize) % alphabet.len()])
                .collect(),
            _ => {
                let mut b = base.clone();
                for _ in 0..(1 + rng.next_u31() % 20) {
                    let i = (rng.next_u31() as usize) % b.len();
                    b[i] = alphabet[(rng.next_u31() as usize) % alphabet.len()];
                }
                b.truncate((rng.next_u31() as usize) % (b.len() + 1));
                b
            }
        };
        for ext in ["prr", "prw", "ban", "csv"] {
            let path = temp_file(&format!("fuzz.{ext}"), &bytes);
            for smoothing in [0.0, 1e-3] {
                if let Ok(p) = Profile::from_file(&path, Some(ProfileKind::Rail), smoothing) {
                    let (a, b) = p.y_range();
                    let _ = p.eval(0.5 * (a + b));
                } else if let Err(e) =
                    Profile::from_file(&path, Some(ProfileKind::Wheel), smoothing)
                {
                    assert!(!e.to_string().is_empty());
                }
            }
        }
    }
}

/// A noisy measured-like rail: the benchmark points (0.46 mm apart on the crown) plus σ = 1 µm
/// noise, smoothed with ℓ = 1.5 mm. Over ±2 mm around the crown centre (y ≈ −7.5 mm, the rail is
/// canted 1:40):
/// * the smoothing bias (noise-free points) stays below 2 % of the crown curvature 1/0.3 m:
///   the R80 junctions 8.5–12.5 mm away leak ½Δκ e^(−d/√2ℓ) cos(d/√2ℓ) (spline.rs), measured
///   ≤ 1.3 %;
/// * the noise adds at most 0.3 1/m ≈ 4 predicted standard deviations
///   (σ √(h/(8√2 ℓ⁵)) = 0.073 1/m);
/// * interpolated (ℓ = 0) the curvature is off by more than 50 %.
#[test]
fn smoothing_a_noisy_rail_restores_the_crown_curvature() {
    let rail = Profile::from_file(&bench("MBench_UIC60_v3.prr"), None, 0.0).unwrap();
    let (y, z) = rail.points();
    let sigma = 1e-6;
    let ell: f64 = 1.5e-3;
    let mut rng = Lcg(99);
    let noisy: Vec<f64> = z
        .iter()
        .map(|v| {
            // Sum of 12 uniforms − 6: approximately standard normal.
            let g: f64 = (0..12)
                .map(|_| (rng.next_u31() as f64) / (1u64 << 31) as f64)
                .sum::<f64>()
                - 6.0;
            v + sigma * g
        })
        .collect();
    let kappa = 1.0 / 0.3;
    let predicted = sigma * (0.46e-3 / (8.0 * 2f64.sqrt() * ell.powi(5))).sqrt();
    assert!((smoothing_length_for_noise(sigma, 0.46e-3, predicted) - ell).abs() < 1e-12);
    let clean = Profile::from_points("clean", ProfileKind::Rail, y, z, ell).unwrap();
    let smooth = Profile::from_points("noisy", ProfileKind::Rail, y, &noisy, ell).unwrap();
    let raw = Profile::from_points("noisy", ProfileKind::Rail, y, &noisy, 0.0).unwrap();
    let (mut bias, mut noise, mut worst_r) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..=40 {
        let v = -0.0095 + 1e-4 * i as f64;
        bias = bias.max((clean.curvature(v) / kappa - 1.0).abs());
        noise = noise.max((smooth.curvature(v) - clean.curvature(v)).abs());
        worst_r = worst_r.max((raw.curvature(v) / kappa - 1.0).abs());
    }
    eprintln!(
        "noisy rail crown curvature: bias {bias:.4}, noise {noise:.3} 1/m (predicted std \
         {predicted:.3}), interpolated error {worst_r:.1}"
    );
    assert!(bias < 0.02, "{bias}");
    assert!(noise < 0.3, "{noise}");
    assert!(worst_r > 0.5, "{worst_r}");
}

// ---------------------------------------------------------------------------------------------
// Plausibility checks (railcontact::geometry::profile::checks): files that parse but cannot be right.

/// Two-column CSV text (mm) of `p`'s points, each mapped by `f` (y, z in mm → y, z in mm).
fn csv_of(p: &Profile, mut f: impl FnMut(usize, f64, f64) -> (f64, f64)) -> String {
    let (y, z) = p.points();
    let mut text = String::from("y [mm],z [mm]\n");
    for (i, (&a, &b)) in y.iter().zip(z).enumerate() {
        let (a, b) = f(i, a * MM, b * MM);
        text += &format!("{a},{b}\n");
    }
    text
}

/// Asserts that `path` is refused with a message that names the file and contains every part.
#[track_caller]
fn expect_refused(path: &Path, kind: Option<ProfileKind>, smoothing: f64, parts: &[&str]) {
    let e = Profile::from_file(path, kind, smoothing)
        .map(|_| ())
        .expect_err(&format!("{} must be refused", path.display()));
    let text = e.to_string();
    assert!(
        text.starts_with(&format!("profile file '{}'", path.display())),
        "{text}"
    );
    for part in parts {
        assert!(text.contains(part), "{part:?} in {text}");
    }
}

/// The benchmark wheel and rail (file points, ascending y).
fn bench_pair() -> (Profile, Profile) {
    (
        Profile::from_file(&bench("MBench_S1002_v3.prw"), None, 0.0).unwrap(),
        Profile::from_file(&bench("MBench_UIC60_v3.prr"), None, 0.0).unwrap(),
    )
}

/// Clean profiles still load and pass every check: the built-ins, the three benchmark files at
/// smoothing lengths 0 … 10 mm (the parameter's range), and MiniProf-style measurements — the
/// built-in UIC60 head and the benchmark wheel with σ = 2 µm Gaussian scatter, written with four
/// decimals (0.1 µm) as a MiniProf text `.ban` and a CSV, and the wheel with a sharp-cornered
/// field-side face — interpolated and smoothed. The scatter gives point offsets of ~3 µm, ten
/// times below the 0.03 mm defect threshold (checks.rs).
#[test]
fn clean_profiles_pass_the_plausibility_checks() {
    for name in ["S1002", "UIC60", "60E1"] {
        Profile::builtin(name)
            .unwrap()
            .check_plausibility()
            .unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    for file in [
        "MBench_S1002_v3.prw",
        "MBench_UIC60_v3.prr",
        "MBench_UIC60_v3.ban",
    ] {
        for smoothing in [0.0, 1e-3, 2e-3, 1e-2] {
            Profile::from_file(&bench(file), None, smoothing)
                .unwrap_or_else(|e| panic!("{file}, smoothing {smoothing}: {e}"));
        }
    }
    let mut rng = Lcg(2024);
    let mut scatter = move || {
        let g: f64 = (0..12)
            .map(|_| (rng.next_u31() as f64) / (1u64 << 31) as f64)
            .sum::<f64>()
            - 6.0;
        2e-3 * g // mm
    };
    let rail = Profile::builtin("UIC60").unwrap();
    let (y, z) = rail.points();
    let mut ban = format!(
        "Filename=measured.ban\nProgramName=MiniProf\nXYPoints={}\nXOffset=0.0000\n\
         YOffset=0.0000\nColumnDef=X,Y\n",
        y.len()
    );
    for (&a, &b) in y.iter().zip(z) {
        ban += &format!("{:.4}\t{:.4}\n", -a * MM, b * MM + scatter());
    }
    let ban = temp_file("measured.ban", ban.as_bytes());
    let (wheel, _) = bench_pair();
    let wheel_csv = csv_of(&wheel, |_, a, b| {
        (
            (a * 1e4).round() / 1e4,
            ((b + scatter()) * 1e4).round() / 1e4,
        )
    });
    let wheel_csv = temp_file("measured_wheel.csv", wheel_csv.as_bytes());
    // A measured wheel often ends with a chamfer and its field-side face, with sharp corners
    // (here a 45° chamfer from +60 to +65 mm, then 15 mm straight down): outside the contact
    // region, so they pass (an interpolating spline bends at the corners with radii < 1 mm).
    let mut with_face = csv_of(&wheel, |_, a, b| (a, b));
    let (wy, wz) = wheel.points();
    let (y_end, z_end) = (wy[wy.len() - 1] * MM, wz[wz.len() - 1] * MM);
    for k in 1..=20 {
        let d = 0.25 * f64::from(k);
        with_face += &format!("{},{}\n", y_end + d, z_end - d);
    }
    for k in 1..=30 {
        let (y, z) = (
            y_end + 5.0 + 1e-4 * f64::from(k),
            z_end - 5.0 - 0.5 * f64::from(k),
        );
        with_face += &format!("{y},{z}\n");
    }
    let with_face = temp_file("wheel_with_face.csv", with_face.as_bytes());
    for smoothing in [0.0, 1e-3] {
        Profile::from_file(&ban, None, smoothing).unwrap_or_else(|e| panic!("{e}"));
        Profile::from_file(&wheel_csv, Some(ProfileKind::Wheel), smoothing)
            .unwrap_or_else(|e| panic!("{e}"));
        Profile::from_file(&with_face, Some(ProfileKind::Wheel), smoothing)
            .unwrap_or_else(|e| panic!("{e}"));
    }
}

/// A wheel profile with its flange on the field side (not mirrored into the wheel frame, where
/// the flange lies at negative y) is refused naming the flange tip's line, with the fix: as a
/// CSV with y → −y, and as the benchmark Simpack file with its `mirror.y` switched off. The same
/// points built in memory fail `check_plausibility`, naming the point.
#[test]
fn a_wheel_with_its_flange_on_the_field_side_is_refused() {
    let (wheel, _) = bench_pair();
    let mirrored = temp_file(
        "mirrored_wheel.csv",
        csv_of(&wheel, |_, a, b| (-a, b)).as_bytes(),
    );
    // The tip (28 mm above the taping line, 30.6 mm above the lowest point) at y = −54.9 mm
    // in the benchmark frame, so +54.9 mm mirrored.
    expect_refused(
        &mirrored,
        Some(ProfileKind::Wheel),
        0.0,
        &[
            "the flange (its tip 30.6 mm high at y = +54.9 mm) lies on the field side",
            "the profile is not mirrored",
            "mirror it (y -> -y",
        ],
    );
    let text = std::fs::read_to_string(bench("MBench_S1002_v3.prw")).unwrap();
    let unmirrored = text.replacen("mirror.y       =  1", "mirror.y       =  0", 1);
    assert_ne!(unmirrored, text, "the benchmark file sets mirror.y = 1");
    let unmirrored = temp_file("unmirrored.prw", unmirrored.as_bytes());
    expect_refused(
        &unmirrored,
        None,
        1e-3,
        &["line ", "lies on the field side", "toggle mirror.y"],
    );
    let (y, z) = wheel.points();
    let flipped: Vec<f64> = y.iter().map(|v| -v).collect();
    let p = Profile::from_points("flipped", ProfileKind::Wheel, &flipped, z, 0.0).unwrap();
    let e = p.check_plausibility().unwrap_err();
    assert!(e.to_string().contains("lies on the field side"), "{e}");
    assert!(matches!(
        e.location,
        railcontact::geometry::profile::Location::Point(_)
    ));
}

/// Coordinates in metres read as mm: the wheel spans 0.13 mm, the rail 0.074 mm (limit 1 mm).
#[test]
fn profiles_in_metres_are_refused() {
    let (wheel, rail) = bench_pair();
    for (name, p, kind) in [
        ("wheel_m.csv", &wheel, ProfileKind::Wheel),
        ("rail_m.txt", &rail, ProfileKind::Rail),
    ] {
        let path = temp_file(name, csv_of(p, |_, a, b| (a / MM, b / MM)).as_bytes());
        expect_refused(
            &path,
            Some(kind),
            0.0,
            &[
                "laterally, where a wheel profile spans ~130 mm",
                "the values look like metres",
                "multiply by 1000",
            ],
        );
    }
}

/// A truncated point block: a Simpack file cut in the middle of its points (no `point.end`), the
/// first or last half of the wheel's rows (the running surface
/// around the taping line, −20 … +20 mm, is cut), the first half of the rail's rows (the field
/// side of the head is missing), and the rail with ten crown rows deleted (a 3.7 mm hole) or
/// only every tenth row kept (decimated: gaps of 4–5 mm). The three quarters of the wheel that
/// keep its running surface still load.
#[test]
fn truncated_and_gappy_point_blocks_are_refused() {
    let (wheel, rail) = bench_pair();
    let n = wheel.points().0.len();
    let keep = |p: &Profile, name: &str, rows: &dyn Fn(usize) -> bool| -> PathBuf {
        let (y, z) = p.points();
        let mut text = String::new();
        for i in (0..y.len()).filter(|&i| rows(i)) {
            text += &format!("{} {}\n", y[i] * MM, z[i] * MM);
        }
        temp_file(name, text.as_bytes())
    };
    let wheel_kind = Some(ProfileKind::Wheel);
    // The benchmark wheel file cut after a line in the middle of its point block.
    let text = std::fs::read_to_string(bench("MBench_S1002_v3.prw")).unwrap();
    let end = text[..text.len() / 2].rfind('\n').unwrap() + 1;
    let cut = temp_file("cut.prw", &text.as_bytes()[..end]);
    expect_refused(
        &cut,
        None,
        0.0,
        &["'point.begin' has no matching 'point.end': the file looks truncated"],
    );
    for (name, rows) in [
        ("wheel_head.txt", &(|i| i < n / 2) as &dyn Fn(usize) -> bool),
        ("wheel_tail.txt", &|i| i >= n / 2),
    ] {
        expect_refused(
            &keep(&wheel, name, rows),
            wheel_kind,
            0.0,
            &[
                "the wheel profile covers only y = ",
                "not the running surface around the taping line",
                "looks truncated",
            ],
        );
    }
    Profile::from_file(
        &keep(&wheel, "wheel_3q.txt", &|i| i < 3 * n / 4),
        wheel_kind,
        0.0,
    )
    .unwrap();
    let m = rail.points().0.len();
    let rail_kind = Some(ProfileKind::Rail);
    expect_refused(
        &keep(&rail, "rail_half.txt", &|i| i < m / 2),
        rail_kind,
        0.0,
        &[
            "descends only 0.0 mm below its highest point on the field (+y) side",
            "looks truncated",
        ],
    );
    // Rows 200..210 lie on the gauge-side R80/R13 (y ≈ −26 … −23 mm, 0.3–0.5 mm apart); the
    // error names the first row after the hole (index 210, on line 201).
    expect_refused(
        &keep(&rail, "rail_hole.txt", &|i| !(200..210).contains(&i)),
        rail_kind,
        0.0,
        &[
            "line 201: no points between y = -26.",
            "a gap of 3.",
            "points are missing",
        ],
    );
    expect_refused(
        &keep(&rail, "rail_decimated.txt", &|i| i % 10 == 0),
        rail_kind,
        0.0,
        &["no points between", "at most 3 mm are allowed", "decimated"],
    );
}

/// Steps and spikes: a 0.5 mm step across the benchmark rail's crown (all points beyond
/// y = 3 mm lowered), a 0.1 mm spike on one crown point and on one wheel tread point. An
/// interpolating spline bends there with radii of 0.3–0.5 mm: refused, naming the point (the
/// spike itself, the middle of the step) and suggesting a smoothing length; with that length,
/// and with the usual 1 mm, the files load.
#[test]
fn steps_and_spikes_are_refused_unless_the_smoothing_absorbs_them() {
    let (wheel, rail) = bench_pair();
    let (ry, _) = rail.points();
    let (wy, _) = wheel.points();
    let crown = ry.iter().position(|&v| v > 2e-3).unwrap();
    let tread = wy.iter().position(|&v| v > 5e-3).unwrap();
    let cases = [
        (
            "stepped_rail.csv",
            ProfileKind::Rail,
            csv_of(&rail, |_, a, b| (a, if a > 3.0 { b + 0.5 } else { b })),
            0.15,
        ),
        (
            "spiked_rail.csv",
            ProfileKind::Rail,
            csv_of(&rail, |i, a, b| (a, if i == crown { b + 0.1 } else { b })),
            0.1,
        ),
        (
            "spiked_wheel.csv",
            ProfileKind::Wheel,
            csv_of(&wheel, |i, a, b| (a, if i == tread { b - 0.1 } else { b })),
            0.1,
        ),
    ];
    for (name, kind, text, offset_mm) in cases {
        let path = temp_file(name, text.as_bytes());
        let e = Profile::from_file(&path, Some(kind), 0.0).unwrap_err();
        let m = e.to_string();
        for part in [
            "a step or spike at y = ",
            "off the curve through its neighbours",
            "(profileSmoothing = 0 m) bends there with a radius of 0.",
            "set profileSmoothing = ",
        ] {
            assert!(m.contains(part), "{name}: {part:?} in {m}");
        }
        let ErrorReason::StepOrSpike {
            offset_mm: found,
            suggestion_m: Some(suggested),
            radius_mm,
            ..
        } = e.reason
        else {
            panic!("{name}: {m}");
        };
        // The spike's own offset is its height (the curve through its neighbours is the clean
        // profile); a step's middle point lies ~40 % of the step off (the neighbours' cubic).
        assert!(found >= offset_mm * 0.95, "{name}: {found} mm");
        assert!(radius_mm < 2.0, "{name}: {radius_mm} mm");
        assert!(e.line().is_some(), "{name}: {m}");
        for smoothing in [suggested, 1e-3] {
            Profile::from_file(&path, Some(kind), smoothing)
                .unwrap_or_else(|e| panic!("{name}, smoothing {smoothing}: {e}"));
        }
    }
}
