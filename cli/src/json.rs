//! The layout of the command's JSON: objects and arrays down to [`PRETTY_DEPTH`] levels one
//! member a line, indented by two spaces; deeper ones (a strip's row, a grid point, a traction
//! element) on one line with `", "` and `": "` separators. Numbers, strings and keys are
//! serde_json's: the shortest text that reads back to the same `f64`; a non-finite number is
//! `null`.

use serde_json::Value;

/// Nesting levels written one member a line (document, "strips", a patch's list of strips).
pub const PRETTY_DEPTH: usize = 3;

/// `value` as JSON text in this layout, with a final newline.
pub fn to_text(value: &Value) -> Result<String, serde_json::Error> {
    let mut out = String::new();
    write_value(&mut out, value, 1)?;
    out.push('\n');
    Ok(out)
}

/// Appends `value`, an array or object at nesting level `depth` (1 = the document).
fn write_value(out: &mut String, value: &Value, depth: usize) -> Result<(), serde_json::Error> {
    match value {
        Value::Array(items) => {
            let members = items.iter().map(|item| (None, item));
            write_members(out, ('[', ']'), members, depth)
        }
        Value::Object(map) => {
            let members = map.iter().map(|(key, item)| (Some(key), item));
            write_members(out, ('{', '}'), members, depth)
        }
        scalar => {
            out.push_str(&serde_json::to_string(scalar)?);
            Ok(())
        }
    }
}

/// Appends an array's items (no keys) or an object's members between `delimiters`: one a line,
/// indented, down to [`PRETTY_DEPTH`]; below it on one line.
fn write_members<'a>(
    out: &mut String,
    (open, close): (char, char),
    members: impl Iterator<Item = (Option<&'a String>, &'a Value)>,
    depth: usize,
) -> Result<(), serde_json::Error> {
    let pretty = depth <= PRETTY_DEPTH;
    let separator = if pretty { ",\n" } else { ", " };
    out.push(open);
    let mut empty = true;
    for (k, (key, item)) in members.enumerate() {
        if k > 0 {
            out.push_str(separator);
        } else if pretty {
            out.push('\n');
        }
        if pretty {
            indent(out, depth);
        }
        if let Some(key) = key {
            out.push_str(&serde_json::to_string(key)?);
            out.push_str(": ");
        }
        write_value(out, item, depth + 1)?;
        empty = false;
    }
    if pretty && !empty {
        out.push('\n');
        indent(out, depth - 1);
    }
    out.push(close);
    Ok(())
}

fn indent(out: &mut String, depth: usize) {
    for _ in 0..depth {
        out.push_str("  ");
    }
}
#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn pretty_outside_compact_inside() {
        let doc = json!({
            "a": 1.5,
            "strips": {"left.p1": [{"s": -0.001, "pmax": 1e9}, {"s": 0.0, "pmax": 2.0}]},
            "empty": {},
            "grid": {"left.p1": [[1, 2e-7, f64::NAN]]}
        });
        let text = to_text(&doc).unwrap();
        assert_eq!(
            text,
            "{\n  \"a\": 1.5,\n  \"strips\": {\n    \"left.p1\": [\n      \
             {\"s\": -0.001, \"pmax\": 1000000000.0},\n      {\"s\": 0.0, \"pmax\": 2.0}\n    \
             ]\n  },\n  \"empty\": {},\n  \"grid\": {\n    \"left.p1\": [\n      \
             [1, 2e-7, null]\n    ]\n  }\n}\n"
        );
        let back: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(back, doc);
    }
}
