//! MiniProf-style text `.ban` rail profiles: `parse_ban`, then validation and the spline fit
//! (`Profile::from_bytes`).
#![no_main]

use libfuzzer_sys::fuzz_target;
use railcontact::geometry::profile::ProfileKind;

#[path = "common.rs"]
mod common;

fuzz_target!(|data: &[u8]| {
    common::check(data, "fuzz.ban", Some(ProfileKind::Rail));
});
