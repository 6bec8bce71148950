//! `documentation/index.html` of an FMU: the variable table (from the same generated table as
//! `modelDescription.xml`) and the frames and sign conventions (`docs/conventions.md`).

use railcontact::fmi::model::ModelInfo;
use railcontact::fmi::variables::{Start, VarInfo};
use std::fmt::Write;

const CONVENTIONS: &str = include_str!("../../docs/conventions.md");

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn start_text(v: &VarInfo) -> String {
    match v.start {
        Start::None => String::new(),
        Start::Real(x) => format!("{x}"),
        Start::Integer(k) => k.to_string(),
        Start::Boolean(b) => b.to_string(),
        Start::String(s) => format!("{s:?}"),
    }
}

pub fn index_html(info: &ModelInfo) -> String {
    let mut h = String::new();
    let id = escape(info.model_identifier);
    write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{id}</title>\n\
<style>body{{font-family:sans-serif;max-width:70em;margin:auto}}table{{border-collapse:collapse}}\
td,th{{border:1px solid #bbb;padding:2px 6px;text-align:left}}pre{{white-space:pre-wrap}}</style>\
</head><body>\n<h1>{id}</h1>\n<p>railcontact {} — GUID <code>{}</code>. FMI 2.0 Co-Simulation. \
All quantities in SI units.</p>\n<h2>Variables</h2>\n<table><tr><th>name</th><th>causality</th>\
<th>type</th><th>unit</th><th>start</th><th>allowed</th><th>description</th></tr>\n",
        env!("CARGO_PKG_VERSION"),
        escape(info.guid)
    )
    .unwrap();
    for v in info.variables {
        writeln!(
            h,
            "<tr><td><code>{}</code></td><td>{:?}</td><td>{:?}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            escape(v.name),
            v.causality,
            v.ty,
            escape(v.unit),
            escape(&start_text(v)),
            escape(v.allowed),
            escape(v.description)
        )
        .unwrap();
    }
    write!(
        h,
        "</table>\n<h2>Frames and sign conventions</h2>\n<pre>{}</pre>\n</body></html>\n",
        escape(CONVENTIONS)
    )
    .unwrap();
    h
}
