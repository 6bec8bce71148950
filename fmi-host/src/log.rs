//! The callbacks a host hands to `fmi2Instantiate`, and the log each instance keeps.
//!
//! The logger is C (`src/logger.c`): it formats the FMU's printf-style message and passes the
//! text to [`record`] through the component environment, a [`Sink`] owned by the instance, so
//! the messages of every instance land in its own list without a process-wide logger.

use crate::Status;
use fmi_sys::fmi2::{fmi2CallbackFunctions, fmi2Status, fmi2String};
use std::ffi::{c_char, c_void, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// One message the FMU logged.
#[derive(Debug, Clone, PartialEq)]
pub struct Message {
    pub status: Status,
    pub category: String,
    pub text: String,
}

type Record = unsafe extern "C" fn(*const Sink, fmi2String, fmi2Status, fmi2String, fmi2String);

/// The component environment of one instance: the C logger calls `record` with it (it must stay
/// the first field: `struct fmi_host_sink` in logger.c reads only that one).
#[repr(C)]
pub(crate) struct Sink {
    record: Record,
    messages: Mutex<Vec<Message>>,
}

extern "C" {
    fn fmi_host_logger(
        environment: *mut c_void,
        instance: fmi2String,
        status: fmi2Status,
        category: fmi2String,
        message: fmi2String,
        ...
    );
    fn fmi_host_allocate(count: usize, size: usize) -> *mut c_void;
    fn fmi_host_free(p: *mut c_void);
}

impl Sink {
    pub(crate) fn new() -> Box<Self> {
        Box::new(Self {
            record,
            messages: Mutex::new(Vec::new()),
        })
    }

    /// The callbacks of an instance that logs into this sink (which must outlive it).
    pub(crate) fn callbacks(&self) -> fmi2CallbackFunctions {
        fmi2CallbackFunctions {
            logger: Some(fmi_host_logger),
            allocateMemory: Some(fmi_host_allocate),
            freeMemory: Some(fmi_host_free),
            stepFinished: None,
            componentEnvironment: std::ptr::from_ref(self).cast_mut().cast(),
        }
    }

    pub(crate) fn messages(&self) -> MutexGuard<'_, Vec<Message>> {
        self.messages.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

/// Reads a C string the FMU passed; NULL reads as "".
///
/// # Safety
/// `s` is NULL or a NUL-terminated string alive for the call.
unsafe fn text(s: *const c_char) -> String {
    if s.is_null() {
        String::new()
    } else {
        // SAFETY: the caller's contract.
        unsafe { CStr::from_ptr(s) }.to_string_lossy().into_owned()
    }
}

/// Appends one message to the sink; never unwinds into the C caller.
unsafe extern "C" fn record(
    sink: *const Sink,
    _instance: fmi2String,
    status: fmi2Status,
    category: fmi2String,
    message: fmi2String,
) {
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: `sink` is the environment this crate gave `fmi2Instantiate`, alive until the
        // instance is freed; the strings are the logger's arguments, alive for the call.
        let Some(sink) = (unsafe { sink.as_ref() }) else {
            return;
        };
        let entry = Message {
            status: Status::from(status),
            // SAFETY: as above.
            category: unsafe { text(category) },
            // SAFETY: as above.
            text: unsafe { text(message) },
        };
        sink.messages().push(entry);
    }));
}
