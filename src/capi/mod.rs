//! The C ABI: the only place with `extern "C"`. Converts, validates, guards against panics
//! and maps errors; the engine core knows nothing of C. See `include/hearth.h`.

pub mod body;
pub mod callback;
pub mod draw;
pub mod error;
pub mod events;
pub mod generator;
pub mod geometry;
pub mod hash;
pub mod joint;
pub mod particle;
pub mod query;
pub mod record;
pub mod setters;
pub mod shape;
pub mod snapshot;
pub mod soft;
pub mod tasks;
pub mod types;
pub mod validate;
pub mod world;

use libc::c_char;

use error::*;

const fn parse_u32(s: &str) -> u32 {
    let b = s.as_bytes();
    let mut i = 0;
    let mut v = 0;
    while i < b.len() {
        v = v * 10 + (b[i] - b'0') as u32;
        i += 1;
    }
    v
}

const VERSION_MAJOR: u32 = parse_u32(env!("CARGO_PKG_VERSION_MAJOR"));
const VERSION_MINOR: u32 = parse_u32(env!("CARGO_PKG_VERSION_MINOR"));
const VERSION_PATCH: u32 = parse_u32(env!("CARGO_PKG_VERSION_PATCH"));

/// The library version, `(major << 16) | (minor << 8) | patch`; compare with
/// `HEARTH_VERSION` from the header to detect a mismatched library.
#[no_mangle]
pub extern "C" fn hearth_version() -> u32 {
    (VERSION_MAJOR << 16) | (VERSION_MINOR << 8) | VERSION_PATCH
}

/// A static, NUL-terminated name for a result code, e.g. "HEARTH_ERROR_INVALID_ID".
/// Unknown codes give "HEARTH_ERROR_UNKNOWN". Never NULL; never free it.
#[no_mangle]
pub extern "C" fn hearth_result_name(result: i32) -> *const c_char {
    let s: &'static [u8] = match result {
        0 => b"HEARTH_OK\0",
        1 => b"HEARTH_ERROR_NULL_POINTER\0",
        2 => b"HEARTH_ERROR_INVALID_ID\0",
        3 => b"HEARTH_ERROR_INVALID_ARGUMENT\0",
        4 => b"HEARTH_ERROR_WORLD_LOCKED\0",
        5 => b"HEARTH_ERROR_BUFFER_TOO_SMALL\0",
        6 => b"HEARTH_ERROR_PANIC\0",
        7 => b"HEARTH_ERROR_IO\0",
        8 => b"HEARTH_ERROR_LIMIT_REACHED\0",
        _ => b"HEARTH_ERROR_UNKNOWN\0",
    };
    s.as_ptr() as *const c_char
}

/// Copies the calling thread's message for its last failed call into `buf` (caller-owned,
/// `len` bytes), truncated if needed and always NUL-terminated when `len > 0`. Returns the
/// full message length in bytes, without the NUL (0 if no call has failed yet). `buf` may
/// be NULL when `len` is 0, to ask for the length.
///
/// # Safety
/// `buf` must be NULL or writable for `len` bytes.
#[no_mangle]
pub unsafe extern "C" fn hearth_last_error_message(buf: *mut c_char, len: usize) -> usize {
    guard_value(0, || {
        with_last_error(|msg| {
            if !buf.is_null() && len > 0 {
                let n = msg.len().min(len - 1);
                std::ptr::copy_nonoverlapping(msg.as_ptr(), buf as *mut u8, n);
                *buf.add(n) = 0;
            }
            msg.len()
        })
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn version_matches_cargo() {
        assert_eq!(
            super::hearth_version() >> 16,
            env!("CARGO_PKG_VERSION_MAJOR").parse::<u32>().unwrap()
        );
    }
}
