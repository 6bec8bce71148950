//! What can go wrong before or around an FMU call.

use crate::log::Message;
use crate::Status;
use std::path::PathBuf;

/// A failure of the host (files, library, model description) or of an FMU call.
#[derive(Debug, Clone, PartialEq)]
pub enum Error {
    /// Reading or writing a file or directory.
    Io { path: PathBuf, reason: String },
    /// An FMU archive that cannot be read or holds an entry that would leave the target folder.
    Archive { path: PathBuf, reason: String },
    /// A shared library that cannot be loaded.
    Library { path: PathBuf, reason: String },
    /// A shared library without some of the 34 FMI 2.0 Co-Simulation functions.
    MissingExports {
        path: PathBuf,
        names: Vec<&'static str>,
    },
    /// A model description that lacks something a host needs, with the reason.
    ModelDescription(String),
    /// A variable name the model description does not declare.
    UnknownVariable { model: String, name: String },
    /// A string argument with an interior NUL byte (C cannot pass it).
    Nul { what: String, value: String },
    /// `fmi2Instantiate` returned NULL; the messages the FMU logged meanwhile.
    Instantiate {
        name: String,
        messages: Vec<Message>,
    },
    /// A call returned `status` where the host needed success.
    Call(CallError),
}

/// An FMU call that failed: which instance, which call (with the variable it was about), the
/// status, and the errors and warnings the instance had logged.
#[derive(Clone, PartialEq)]
pub struct CallError {
    pub instance: String,
    pub call: String,
    pub status: Status,
    pub log: Vec<Message>,
}

impl std::fmt::Display for CallError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: {} returned {}",
            self.instance, self.call, self.status
        )?;
        let logged: Vec<&Message> = self.log.iter().filter(|m| m.status != Status::Ok).collect();
        if !logged.is_empty() {
            write!(f, "; the FMU logged:")?;
            for m in logged {
                write!(f, "\n  [{}] {}", m.status, m.text)?;
            }
        }
        Ok(())
    }
}

/// As [`Display`](std::fmt::Display): `unwrap` in a test shows the call and the FMU's log.
impl std::fmt::Debug for CallError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        std::fmt::Display::fmt(self, f)
    }
}

impl std::error::Error for CallError {}

impl From<CallError> for Error {
    fn from(e: CallError) -> Self {
        Error::Call(e)
    }
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Error::Io { path, reason } => write!(f, "{}: {reason}", path.display()),
            Error::Archive { path, reason } => write!(f, "FMU {}: {reason}", path.display()),
            Error::Library { path, reason } => {
                write!(f, "cannot load {}: {reason}", path.display())
            }
            Error::MissingExports { path, names } => write!(
                f,
                "{} does not export {} of the FMI 2.0 Co-Simulation functions: {}",
                path.display(),
                names.len(),
                names.join(", ")
            ),
            Error::ModelDescription(reason) => write!(f, "modelDescription.xml: {reason}"),
            Error::UnknownVariable { model, name } => {
                write!(f, "{model} has no variable {name:?}")
            }
            Error::Nul { what, value } => {
                write!(
                    f,
                    "{what} = {value:?} contains a NUL byte, which C strings cannot hold"
                )
            }
            Error::Instantiate { name, messages } => {
                write!(f, "fmi2Instantiate({name:?}) returned NULL")?;
                for m in messages {
                    write!(f, "\n  [{}] {}", m.status, m.text)?;
                }
                Ok(())
            }
            Error::Call(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for Error {}
