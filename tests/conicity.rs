//! Equivalent conicity (EN 15302) of the built-in S1002/UIC60 pair against the benchmark
//! profiles of `tests/data/profiles` (the same wheel and rail as measured files, the rail already
//! inclined 1:40), at the standard set-up (gauge 1435 mm, flange backs 1360 mm).

mod common;

use railcontact::geometry::profile::Profile;
use railcontact::geometry::search::DEFAULT_SCAN_STEP;
use railcontact::geometry::track::TrackSetup;
use railcontact::wheelset::conicity::{RollingRadiusDifference, ShiftGrid, DEFAULT_AMPLITUDES};

fn built_in() -> RollingRadiusDifference {
    let wheel = Profile::builtin("S1002").unwrap();
    let rail = Profile::builtin("UIC60").unwrap();
    RollingRadiusDifference::compute(
        &wheel,
        &rail,
        &TrackSetup::default(),
        DEFAULT_SCAN_STEP,
        ShiftGrid::default(),
    )
    .unwrap()
}

fn benchmark() -> RollingRadiusDifference {
    let file = |name: &str| common::data_file(&format!("profiles/{name}"));
    let wheel = Profile::from_file(&file("MBench_S1002_v3.prw"), None, 0.0).unwrap();
    let rail = Profile::from_file(&file("MBench_UIC60_v3.prr"), None, 0.0).unwrap();
    let setup = TrackSetup {
        rail_inclination: 0.0,
        ..TrackSetup::default()
    };
    RollingRadiusDifference::compute(
        &wheel,
        &rail,
        &setup,
        DEFAULT_SCAN_STEP,
        ShiftGrid::default(),
    )
    .unwrap()
}

/// The built-in pair and the benchmark files describe the same nominal geometry: their
/// conicities at 3 mm agree within 0.015 (both methods), and lie in the range known for new
/// S1002 on 1:40 UIC60 at 1435 mm gauge and 1360 mm flange backs (0.1–0.25 at 3 mm; measured
/// here: 0.185). Δr is restoring and odd within 5 % (the pair is symmetric; the files are
/// measured-like point sets), and the centred wheelset rolls at r0 ≈ 460 mm with its contact
/// points near the taping lines (e0 ≈ 750 mm).
#[test]
fn built_in_pair_matches_the_benchmark_profiles() {
    let (a, b) = (built_in(), benchmark());
    let mut rows = Vec::new();
    for amplitude in DEFAULT_AMPLITUDES {
        let (ca, cb) = (
            a.conicity(amplitude).unwrap(),
            b.conicity(amplitude).unwrap(),
        );
        rows.push((amplitude, ca, cb));
        println!(
            "A = {:.0} mm: harmonic {:.4} / {:.4}, Klingel {:.4} / {:.4} (built-in / benchmark)",
            amplitude * 1e3,
            ca.harmonic,
            cb.harmonic,
            ca.klingel.unwrap_or(f64::NAN),
            cb.klingel.unwrap_or(f64::NAN)
        );
    }
    let (_, ca, cb) = rows[2];
    assert!((ca.harmonic - cb.harmonic).abs() < 0.015, "{ca:?} {cb:?}");
    let (ka, kb) = (ca.klingel.unwrap(), cb.klingel.unwrap());
    assert!((ka - kb).abs() < 0.015, "{ka} {kb}");
    for lambda in [ca.harmonic, cb.harmonic, ka, kb] {
        assert!((0.1..0.25).contains(&lambda), "{lambda}");
    }
    for t in [&a, &b] {
        let n = t.points().len();
        for (p, q) in t.points().iter().zip(t.points().iter().rev()).take(n / 2) {
            assert!(p.delta_r < 0.0 && q.delta_r > 0.0, "{p:?}");
            assert!((p.delta_r + q.delta_r).abs() < 0.05 * q.delta_r.abs() + 2e-6);
        }
        // r0 ≈ 460 mm, e0 ≈ 750 mm (contact near the taping lines).
        assert!((t.r0() - 0.46).abs() < 1e-3 && (t.e0() - 0.75).abs() < 5e-3);
    }
}
