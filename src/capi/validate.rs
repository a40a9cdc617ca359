//! One validation helper per input kind: pointers, flag bytes, type codes, def cookies.
//! Number ranges are checked by the core, which returns the same errors to Rust users.

use super::error::Failure;

/// Set by every `*_def_default()` in a def's `internal_value`; a def without it (stack
/// garbage, zeroed memory) is rejected.
pub(crate) const DEF_COOKIE: u32 = 0x4845_4152; // "HEAR"

pub fn cookie(value: u32, what: &str) -> Result<(), Failure> {
    if value == DEF_COOKIE {
        Ok(())
    } else {
        Err(Failure::invalid(format!(
            "{what} was not initialised by {what}_default() (internal_value mismatch)"
        )))
    }
}

/// A `uint8_t` flag: 0 or 1, anything else rejected.
pub fn flag(value: u8, what: &str) -> Result<bool, Failure> {
    match value {
        0 => Ok(false),
        1 => Ok(true),
        v => Err(Failure::invalid(format!("{what} must be 0 or 1, got {v}"))),
    }
}

/// Reads a `const T *` input, rejecting NULL.
///
/// # Safety
/// `ptr` must be NULL or point to a readable, initialised `T`.
pub unsafe fn input<'a, T>(ptr: *const T, what: &str) -> Result<&'a T, Failure> {
    ptr.as_ref().ok_or_else(|| Failure::null(what))
}

/// Checks an output pointer is not NULL. Outputs are written only on success.
pub fn output<T>(ptr: *mut T, what: &str) -> Result<*mut T, Failure> {
    if ptr.is_null() {
        Err(Failure::null(what))
    } else {
        Ok(ptr)
    }
}

/// Fails with `HEARTH_ERROR_BUFFER_TOO_SMALL` (nothing written) when a caller-owned array of
/// `capacity` elements cannot hold `needed`.
pub fn capacity(capacity: usize, needed: usize, what: &str) -> Result<(), Failure> {
    if capacity < needed {
        return Err(Failure::new(
            super::error::HEARTH_ERROR_BUFFER_TOO_SMALL,
            format!("{what}: room for {capacity} elements, {needed} needed"),
        ));
    }
    Ok(())
}

/// The count-then-fill protocol of bulk reads into a caller-owned array: `capacity == 0` only
/// asks for the count (`None`); otherwise `out` must be non-NULL and hold `needed` elements,
/// and the slice to fill is returned. Nothing is written on failure.
///
/// # Safety
/// `out` must be NULL or writable for `capacity` elements.
pub unsafe fn counted_output<'a, T>(
    out: *mut T,
    capacity: usize,
    needed: usize,
    what: &str,
) -> Result<Option<&'a mut [T]>, Failure> {
    if capacity == 0 {
        return Ok(None);
    }
    let out = output(out, what)?;
    self::capacity(capacity, needed, what)?;
    Ok(Some(std::slice::from_raw_parts_mut(out, needed)))
}
