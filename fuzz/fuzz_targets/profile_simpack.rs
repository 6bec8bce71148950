//! Simpack `.prr` (rail) and `.prw` (wheel) profiles: `parse_simpack`, then validation and the
//! spline fit (`Profile::from_bytes`).
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "common.rs"]
mod common;

fuzz_target!(|data: &[u8]| {
    common::check(data, "fuzz.prr", None);
    common::check(data, "fuzz.prw", None);
});
