//! The JSON reader moved into the library as [`railcontact::case_json`] (so that it can be
//! fuzzed, `fuzz/`); the command uses it from there. This re-export remains for `tests/cli.rs`,
//! which includes this file by path; it can go once that test uses `railcontact::case_json`.

pub use railcontact::case_json::*;
