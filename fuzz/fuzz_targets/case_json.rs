//! The JSON reader of the `railcontact` command's case files (`railcontact::case_json`): never
//! panics; an error names a line and column inside the text; strings and numbers written by
//! `quote`/`number` read back to the same value.
#![no_main]

use libfuzzer_sys::fuzz_target;
use railcontact::case_json::{number, parse, quote, Value};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match parse(text) {
        Ok(value) => check_round_trip(&value),
        Err(e) => {
            let lines = text.split('\n').count();
            assert!(e.line >= 1 && e.line <= lines, "{e} ({lines} lines)");
            assert!(e.column >= 1, "{e}");
        }
    }
    // Any text as a JSON string literal reads back unchanged.
    assert_eq!(parse(&quote(text)), Ok(Value::String(text.to_string())));
});

/// Every string and number of a parsed document survives `quote`/`number` and `parse`.
fn check_round_trip(value: &Value) {
    match value {
        Value::Number(x, _) => {
            assert!(x.is_finite());
            let again = parse(&number(*x)).ok().and_then(|v| v.as_f64());
            assert_eq!(again.map(f64::to_bits), Some(x.to_bits()), "{x}");
        }
        Value::String(s) => {
            assert_eq!(parse(&quote(s)), Ok(Value::String(s.clone())));
        }
        Value::Array(items) => items.iter().for_each(check_round_trip),
        Value::Object(members) => members.iter().for_each(|(k, v)| {
            assert_eq!(parse(&quote(k)), Ok(Value::String(k.clone())));
            check_round_trip(v);
        }),
        Value::Null | Value::Bool(_) => {}
    }
}
