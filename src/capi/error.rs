//! Result codes, the thread-local error message, and the one panic boundary every export
//! runs inside.

use std::cell::RefCell;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Result of every fallible call: `HEARTH_OK` (0) or a positive error code. A failing call
/// changes nothing. `hearth_result_name` gives a printable name and
/// `hearth_last_error_message` the detail of the calling thread's last failure.
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[allow(non_camel_case_types, clippy::upper_case_acronyms)]
pub enum HearthResult {
    /// Success.
    HEARTH_OK = 0,
    /// A required pointer argument was NULL.
    HEARTH_ERROR_NULL_POINTER = 1,
    /// An id is null, was destroyed, never existed, or belongs to another world.
    HEARTH_ERROR_INVALID_ID = 2,
    /// A number or value is out of range (NaN, infinite, negative size or mass, zero
    /// quaternion, unknown type code, flag byte other than 0/1), or a def was not made by
    /// its `*_def_default()` function.
    HEARTH_ERROR_INVALID_ARGUMENT = 3,
    /// A structural change was attempted from inside a callback during a step.
    HEARTH_ERROR_WORLD_LOCKED = 4,
    /// A caller-owned buffer is too small; nothing was written.
    HEARTH_ERROR_BUFFER_TOO_SMALL = 5,
    /// An internal bug was caught at the boundary. A world that panicked mid-step refuses
    /// further steps with this code.
    HEARTH_ERROR_PANIC = 6,
    /// Reading or writing a file (or a host's write callback) failed; the message says what
    /// and why.
    HEARTH_ERROR_IO = 7,
    /// A fixed capacity is used up: `hearth_world_create` with 4,095 worlds alive at once
    /// (the most whose ids can be told apart). Destroy one and try again.
    HEARTH_ERROR_LIMIT_REACHED = 8,
}

pub use HearthResult::*;

/// An error on its way to C: a code and a detail message.
pub struct Failure {
    pub code: HearthResult,
    pub message: String,
}

impl Failure {
    pub fn new(code: HearthResult, message: impl Into<String>) -> Failure {
        Failure {
            code,
            message: message.into(),
        }
    }
    pub fn null(what: &str) -> Failure {
        Failure::new(HEARTH_ERROR_NULL_POINTER, format!("{what} must not be NULL"))
    }
    pub fn invalid(message: impl Into<String>) -> Failure {
        Failure::new(HEARTH_ERROR_INVALID_ARGUMENT, message)
    }
}

impl From<crate::error::Error> for Failure {
    fn from(e: crate::error::Error) -> Failure {
        let code = match e {
            crate::error::Error::InvalidId(_) => HEARTH_ERROR_INVALID_ID,
            crate::error::Error::InvalidArgument(_) => HEARTH_ERROR_INVALID_ARGUMENT,
            crate::error::Error::LimitReached(_) => HEARTH_ERROR_LIMIT_REACHED,
        };
        Failure::new(code, e.to_string())
    }
}

pub type FfiResult = Result<(), Failure>;

thread_local! {
    static LAST_ERROR: RefCell<String> = const { RefCell::new(String::new()) };
}

pub fn set_last_error(message: &str) {
    LAST_ERROR.with(|e| {
        let mut e = e.borrow_mut();
        e.clear();
        e.push_str(message);
    });
}

pub fn with_last_error<R>(f: impl FnOnce(&str) -> R) -> R {
    LAST_ERROR.with(|e| f(&e.borrow()))
}

fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown panic".to_string()
    }
}

/// The panic boundary: runs `f`, maps its error or a panic to a result code and records
/// the message for `hearth_last_error_message`.
pub fn guard(f: impl FnOnce() -> FfiResult) -> HearthResult {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(())) => HEARTH_OK,
        Ok(Err(failure)) => {
            set_last_error(&failure.message);
            failure.code
        }
        Err(payload) => {
            set_last_error(&format!("internal error (panic): {}", panic_message(&*payload)));
            HEARTH_ERROR_PANIC
        }
    }
}

/// The panic boundary for functions that return a value rather than a result.
pub fn guard_value<T>(fallback: T, f: impl FnOnce() -> T) -> T {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(v) => v,
        Err(payload) => {
            set_last_error(&format!("internal error (panic): {}", panic_message(&*payload)));
            fallback
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn last() -> String {
        with_last_error(|m| m.to_string())
    }

    #[test]
    fn a_panic_becomes_a_result_code_with_its_message() {
        let r = guard(|| panic!("boom at the boundary"));
        assert_eq!(r, HEARTH_ERROR_PANIC);
        assert!(last().contains("boom at the boundary"), "{}", last());
        assert_eq!(guard_value(7, || panic!("again")), 7);
        assert!(last().contains("again"));
    }

    #[test]
    fn failures_keep_their_code_and_message_and_success_keeps_the_last_message() {
        assert_eq!(guard(|| Err(Failure::null("out"))), HEARTH_ERROR_NULL_POINTER);
        assert_eq!(last(), "out must not be NULL");
        assert_eq!(guard(|| Ok(())), HEARTH_OK);
        assert_eq!(last(), "out must not be NULL");
    }

    #[test]
    fn messages_are_per_thread() {
        let _ = guard(|| Err(Failure::invalid("main thread")));
        std::thread::spawn(|| {
            assert_eq!(last(), "");
            let _ = guard(|| Err(Failure::invalid("other thread")));
            assert_eq!(last(), "other thread");
        })
        .join()
        .unwrap();
        assert_eq!(last(), "main thread");
    }
}
