//! The layout of the command's JSON: objects and arrays down to [`PRETTY_DEPTH`] levels one
//! member a line, indented by two spaces; deeper ones (a strip's row, a grid point, a traction
//! element) on one line with `", "` and `": "` separators. Numbers are serde_json's: the shortest
//! text that reads back to the same `f64`; a non-finite number is `null`.

use serde::Serialize;
use serde_json::ser::Formatter;
use std::io::{self, Write};

/// Nesting levels written one member a line (document, "strips", a patch's list of strips).
pub const PRETTY_DEPTH: usize = 3;

/// `value` as JSON text in this layout, with a final newline.
pub fn to_text<T: Serialize + ?Sized>(value: &T) -> Result<String, serde_json::Error> {
    let mut out = Vec::new();
    let mut ser = serde_json::Serializer::with_formatter(&mut out, Layout::default());
    value.serialize(&mut ser)?;
    out.push(b'\n');
    // serde_json writes UTF-8 only.
    Ok(String::from_utf8_lossy(&out).into_owned())
}

/// serde_json formatter: pretty to [`PRETTY_DEPTH`], compact below.
#[derive(Debug, Default)]
struct Layout {
    /// Nesting level of the innermost open array or object (1 = the document).
    depth: usize,
    /// Whether the innermost open array or object has a member yet.
    has_value: bool,
}

impl Layout {
    fn pretty(&self) -> bool {
        self.depth <= PRETTY_DEPTH
    }

    fn begin<W: ?Sized + Write>(&mut self, w: &mut W, open: &[u8]) -> io::Result<()> {
        self.depth += 1;
        self.has_value = false;
        w.write_all(open)
    }

    fn end<W: ?Sized + Write>(&mut self, w: &mut W, close: &[u8]) -> io::Result<()> {
        let pretty = self.pretty();
        self.depth -= 1;
        if pretty && self.has_value {
            w.write_all(b"\n")?;
            indent(w, self.depth)?;
        }
        w.write_all(close)
    }

    fn member<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        if self.pretty() {
            w.write_all(if first { b"\n" } else { b",\n" })?;
            indent(w, self.depth)
        } else if first {
            Ok(())
        } else {
            w.write_all(b", ")
        }
    }
}

fn indent<W: ?Sized + Write>(w: &mut W, depth: usize) -> io::Result<()> {
    for _ in 0..depth {
        w.write_all(b"  ")?;
    }
    Ok(())
}

impl Formatter for Layout {
    fn begin_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.begin(w, b"[")
    }

    fn end_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.end(w, b"]")
    }

    fn begin_array_value<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        self.member(w, first)
    }

    fn end_array_value<W: ?Sized + Write>(&mut self, _w: &mut W) -> io::Result<()> {
        self.has_value = true;
        Ok(())
    }

    fn begin_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.begin(w, b"{")
    }

    fn end_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.end(w, b"}")
    }

    fn begin_object_key<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        self.member(w, first)
    }

    fn begin_object_value<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        w.write_all(b": ")
    }

    fn end_object_value<W: ?Sized + Write>(&mut self, _w: &mut W) -> io::Result<()> {
        self.has_value = true;
        Ok(())
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
