//! Case files of the `railcontact` command (`railcontact_cli::case`): reading any text as a case,
//! applying it to the FMU's values and solving it (`railcontact_cli::solve`, with the pressure
//! grid and the traction field) never panics; a rejected case's error names a reason, and a syntax
//! error's line lies inside the text.
#![no_main]

use libfuzzer_sys::fuzz_target;
use railcontact::fmi::variables::Values;
use railcontact::geometry::profile::BUILTIN_NAMES;
use railcontact::models::wheel_rail_contact::INFO;
use railcontact_cli::case::{self, Setting};
use railcontact_cli::solve::{self, Extras};

/// Pressure points per strip of the solved cases' grids.
const GRID: usize = 4;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let case = match case::parse(text) {
        Ok(case) => case,
        Err(e) => {
            if let Some((line, _)) = e.position {
                let lines = text.split('\n').count();
                assert!(line <= lines, "{e} ({lines} lines)");
            }
            assert!(!e.reason.is_empty(), "{e}");
            return;
        }
    };
    // Built-in profiles only: a fuzzed path could name any file of the machine.
    let files = case
        .entries
        .iter()
        .any(|e| matches!(&e.setting, Setting::Text(s) if !is_builtin(s)));
    if files {
        return;
    }
    let mut values = Values::from_start(INFO.variables, INFO.counts);
    case.apply(&mut values, None);
    let extras = Extras {
        grid: Some(GRID),
        traction: true,
    };
    // Errors (refused steps, bad profiles or values) are answers; only a panic is a failure.
    let _ = solve::solve(&mut values, extras);
});

fn is_builtin(spec: &str) -> bool {
    BUILTIN_NAMES
        .iter()
        .any(|b| b.eq_ignore_ascii_case(spec.trim()))
}
