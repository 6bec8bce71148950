//! Plain two-column text/CSV profiles in mm: `parse_columns`, then validation and the spline fit
//! (`Profile::from_bytes`), as a wheel (`.csv`) and as a rail (`.txt`).
#![no_main]

use libfuzzer_sys::fuzz_target;
use railcontact::geometry::profile::ProfileKind;

#[path = "common.rs"]
mod common;

fuzz_target!(|data: &[u8]| {
    common::check(data, "fuzz.csv", Some(ProfileKind::Wheel));
    common::check(data, "fuzz.txt", Some(ProfileKind::Rail));
});
