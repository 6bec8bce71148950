//! The status an FMI 2.0 function returns.

use fmi_sys::fmi2::{
    fmi2Status, fmi2Status_fmi2Discard, fmi2Status_fmi2Error, fmi2Status_fmi2Fatal,
    fmi2Status_fmi2OK, fmi2Status_fmi2Pending, fmi2Status_fmi2Warning,
};

/// `fmi2Status`, ordered from best to worst as FMI 2.0 numbers them, so `status >= Error`
/// reads as "failed".
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Status {
    Ok,
    Warning,
    Discard,
    Error,
    Fatal,
    Pending,
    /// A value outside the standard's enumeration (a broken FMU).
    Unknown(fmi2Status),
}

impl From<fmi2Status> for Status {
    #[allow(non_upper_case_globals)] // fmi-sys's names of the C enumerators
    fn from(raw: fmi2Status) -> Self {
        match raw {
            fmi2Status_fmi2OK => Status::Ok,
            fmi2Status_fmi2Warning => Status::Warning,
            fmi2Status_fmi2Discard => Status::Discard,
            fmi2Status_fmi2Error => Status::Error,
            fmi2Status_fmi2Fatal => Status::Fatal,
            fmi2Status_fmi2Pending => Status::Pending,
            other => Status::Unknown(other),
        }
    }
}

impl Status {
    /// Whether the call succeeded (`fmi2OK` or `fmi2Warning`).
    pub fn is_success(self) -> bool {
        matches!(self, Status::Ok | Status::Warning)
    }
}

impl std::fmt::Display for Status {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let name = match self {
            Status::Ok => "fmi2OK",
            Status::Warning => "fmi2Warning",
            Status::Discard => "fmi2Discard",
            Status::Error => "fmi2Error",
            Status::Fatal => "fmi2Fatal",
            Status::Pending => "fmi2Pending",
            Status::Unknown(raw) => return write!(f, "status {raw} (not an fmi2Status)"),
        };
        f.write_str(name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn raw_values_map_in_order() {
        let all: Vec<Status> = (0..7).map(Status::from).collect();
        assert_eq!(
            all,
            [
                Status::Ok,
                Status::Warning,
                Status::Discard,
                Status::Error,
                Status::Fatal,
                Status::Pending,
                Status::Unknown(6)
            ]
        );
        assert!(all.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(Status::Ok.to_string(), "fmi2OK");
    }
}
