//! The crate's models as FMUs linked into the test binary: `fmi_host` drives them through the
//! exported `fmi2*` functions, the same C ABI a host resolves from the packed library; and the
//! [`Checked`] reads and log checks of the tests, which assert and name the instance and what it
//! logged.

#![allow(dead_code)] // each test crate uses a different part

use fmi_host::{Fmu, Instance, Status};
use railcontact::fmi::model::ModelInfo;
use std::sync::Arc;

#[allow(unused_imports)] // each test crate asserts a different set of statuses
pub use fmi_host::Status::{Discard as DISCARD, Error as ERROR, Ok as OK, Warning as WARNING};

/// The resource location of linked instances: the `file:` URI of a directory that does not
/// exist (the tests use built-in profiles or absolute paths).
pub const NO_RESOURCES: &str = "file:///nonexistent/resources";

/// The FMU of `info`, linked, described by its generated model description.
pub fn fmu(info: &ModelInfo) -> Arc<Fmu> {
    let functions = fmi_host::linked_functions!(railcontact::models::export);
    Fmu::linked(
        functions,
        info.model_description_xml,
        Some(NO_RESOURCES.to_string()),
    )
    .unwrap_or_else(|e| panic!("{}: {e}", info.model_identifier))
}

/// An instance `name` of `info`; panics with the FMU's messages if it is refused.
#[track_caller]
pub fn instantiate(info: &ModelInfo, name: &str) -> Instance {
    fmu(info)
        .instantiate(name)
        .unwrap_or_else(|e| panic!("{e}"))
}

/// Reads and log checks that assert, naming the instance and what it logged.
pub trait Checked {
    /// The value of a Real variable; asserts that `fmi2GetReal` returns OK.
    fn real(&self, name: &str) -> f64;
    /// The value of an Integer variable; asserts that `fmi2GetInteger` returns OK.
    fn integer(&self, name: &str) -> i32;
    /// All outputs ([`Instance::read_outputs`]); asserts OK and that every value is finite.
    fn outputs(&self) -> Vec<f64>;
    /// Asserts that every output value is finite, naming the first that is not.
    fn assert_finite(&self, out: &[f64]);
    /// Set-up, enter and exit initialization mode; asserts OK.
    fn init(&self);
    /// The texts of the messages logged with `fmi2Error` (or worse).
    fn errors(&self) -> Vec<String>;
    /// The texts of the messages logged with `fmi2Warning`.
    fn warnings(&self) -> Vec<String>;
    /// Asserts that some warning contains every one of `parts`.
    fn assert_warning_logged(&self, parts: &[&str]);
    /// Asserts that some error message contains every one of `parts`.
    fn assert_error_logged(&self, parts: &[&str]);
}

impl Checked for Instance {
    #[track_caller]
    fn real(&self, name: &str) -> f64 {
        self.get_real(name).unwrap_or_else(|e| panic!("{e}"))
    }

    #[track_caller]
    fn integer(&self, name: &str) -> i32 {
        self.get_integer(name).unwrap_or_else(|e| panic!("{e}"))
    }

    #[track_caller]
    fn outputs(&self) -> Vec<f64> {
        let (s, out) = self.read_outputs();
        assert_eq!(
            s,
            OK,
            "{}: reading the outputs: {:?}",
            self.name(),
            self.errors()
        );
        self.assert_finite(&out);
        out
    }

    #[track_caller]
    fn assert_finite(&self, out: &[f64]) {
        if let Some(i) = out.iter().position(|x| !x.is_finite()) {
            let names = self.output_names();
            panic!("{}: output {} = {}", self.name(), names[i], out[i]);
        }
    }

    #[track_caller]
    fn init(&self) {
        let s = self.initialize();
        assert_eq!(
            s,
            OK,
            "{}: initialization: {:?}",
            self.name(),
            self.errors()
        );
    }

    fn errors(&self) -> Vec<String> {
        logged(self, |s| s >= ERROR)
    }

    fn warnings(&self) -> Vec<String> {
        logged(self, |s| s == WARNING)
    }

    #[track_caller]
    fn assert_warning_logged(&self, parts: &[&str]) {
        assert_logged(self, "warning", &self.warnings(), parts);
    }

    #[track_caller]
    fn assert_error_logged(&self, parts: &[&str]) {
        assert_logged(self, "error message", &self.errors(), parts);
    }
}

/// Asserts that one of `messages` (the `kind`s `f` logged) contains every one of `parts`.
#[track_caller]
fn assert_logged(f: &Instance, kind: &str, messages: &[String], parts: &[&str]) {
    assert!(
        messages.iter().any(|m| parts.iter().all(|p| m.contains(p))),
        "{}: no {kind} containing all of {parts:?}; {kind}s: {messages:#?}",
        f.name()
    );
}

/// The texts of the messages of `f` whose status passes `keep`.
fn logged(f: &Instance, keep: impl Fn(Status) -> bool) -> Vec<String> {
    f.messages()
        .into_iter()
        .filter(|m| keep(m.status))
        .map(|m| m.text)
        .collect()
}
