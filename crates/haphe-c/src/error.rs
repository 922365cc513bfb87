//! Status codes, the thread-local last error and the panic guard of every entry point.

use std::cell::RefCell;
use std::ffi::{CString, c_char};
use std::panic::{AssertUnwindSafe, catch_unwind};

use haphe_lib::scene::ParamError;

/// What a call did. `HAPHE_STATUS_OK` is 0; on any other status `haphe_last_error()` says why.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HapheStatus {
    /// Done.
    Ok = 0,
    /// An argument is null, out of range or not finite (a parameter outside its domain in
    /// the library's table: the message names it, its value and its domain).
    InvalidArgument = 1,
    /// A file could not be read or written.
    Io = 2,
    /// A file's content (mesh or map) is unusable; the message names the file and the place.
    Format = 3,
    /// The scene is full (its capacity was reached).
    Full = 4,
    /// A device could not be opened or faulted.
    Device = 5,
    /// An internal error (a Rust panic, caught): a bug in haphe, please report it.
    Panic = 6,
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

/// An error: a status and its message.
pub struct Failure(pub HapheStatus, pub String);

impl Failure {
    /// An [`HapheStatus::InvalidArgument`] failure.
    pub fn argument(message: impl Into<String>) -> Failure {
        Failure(HapheStatus::InvalidArgument, message.into())
    }
}

/// A value refused by the library's table of domains: [`HapheStatus::InvalidArgument`],
/// the message naming the parameter, the value and its domain.
impl From<ParamError> for Failure {
    fn from(e: ParamError) -> Failure {
        Failure::argument(e.to_string())
    }
}

/// A cut volume whose shape cannot be made (no material left, or its surface cannot be
/// mapped): [`HapheStatus::Format`], the message naming the volume.
impl From<haphe_lib::volume::CutError> for Failure {
    fn from(e: haphe_lib::volume::CutError) -> Failure {
        Failure(HapheStatus::Format, e.to_string())
    }
}

/// Records `message` as this thread's last error.
fn set_last_error(message: &str) {
    let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
    LAST_ERROR.with(|e| *e.borrow_mut() = text);
}

/// Runs `f` as an entry point: its failure becomes this thread's last error and its status;
/// a panic becomes [`HapheStatus::Panic`]. Allocates only on failure.
pub fn guard(f: impl FnOnce() -> Result<(), Failure>) -> HapheStatus {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(())) => HapheStatus::Ok,
        Ok(Err(Failure(status, message))) => {
            set_last_error(&message);
            status
        }
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_owned())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            set_last_error(&format!("internal error (please report it): {what}"));
            HapheStatus::Panic
        }
    }
}

/// The message of the last failed call on this thread (empty when none failed yet).
///
/// Ownership: the string belongs to the library and stays valid until the next failing
/// call on this thread; copy it to keep it. Never null.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_last_error() -> *const c_char {
    LAST_ERROR.with(|e| e.borrow().as_ptr())
}
