//! What every profile target checks: reading never panics (libFuzzer reports a panic as a crash),
//! and a profile that is accepted is usable — ascending finite knots and finite z, dz/dy, d²z/dy²
//! across and beyond its range.

use railcontact::geometry::profile::{Profile, ProfileKind};

/// Smoothing lengths the first input byte selects from [m] (0 = interpolate).
const SMOOTHING: [f64; 4] = [0.0, 1e-4, 1e-3, 1e-2];

/// Reads `data` (first byte: smoothing selector; the rest: the file's bytes) as the file
/// `file_name` and checks the profile if it is accepted.
pub fn check(data: &[u8], file_name: &str, kind: Option<ProfileKind>) {
    let Some((&selector, bytes)) = data.split_first() else {
        return;
    };
    let smoothing = SMOOTHING[usize::from(selector) % SMOOTHING.len()];
    match Profile::from_bytes(bytes, file_name, kind, smoothing) {
        Ok(profile) => check_profile(&profile),
        Err(e) => {
            // The message is what the FMU logs: it must name the file.
            let text = e.to_string();
            assert!(text.contains(file_name), "{text}");
        }
    }
}

fn check_profile(profile: &Profile) {
    let (y, z) = profile.points();
    assert!(y.len() >= railcontact::geometry::profile::MIN_POINTS);
    assert!(y.windows(2).all(|w| w[0] < w[1]), "knots not ascending");
    assert!(y.iter().chain(z).all(|v| v.is_finite()));
    let (y0, y1) = profile.y_range();
    let span = y1 - y0;
    for k in -4..=24 {
        let yk = y0 + span * f64::from(k) / 20.0;
        let (zk, dz, d2z) = profile.eval(yk);
        assert!(
            zk.is_finite() && dz.is_finite() && d2z.is_finite(),
            "eval({yk}) = ({zk}, {dz}, {d2z}) on [{y0}, {y1}]"
        );
    }
}
