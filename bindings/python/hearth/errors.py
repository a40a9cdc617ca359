"""Exceptions: every HearthResult other than HEARTH_OK becomes a HearthError.

The library decides what is an error; the binding only reports it, with the code, the
code's name (`hearth_result_name`) and the calling thread's detail message
(`hearth_last_error_message`), read right after the failing call.
"""

import ctypes

from . import _ffi
from ._lib import lib


class HearthError(Exception):
    """A Hearth call failed. `code` is the HearthResult, `name` its C name, `message` the detail."""

    def __init__(self, code, name, message, function=None):
        self.code = code
        self.name = name
        self.message = message
        self.function = function
        where = f"{function}: " if function else ""
        super().__init__(f"{where}{name}: {message}" if message else f"{where}{name}")


class NullPointer(HearthError):
    """HEARTH_ERROR_NULL_POINTER: a required pointer was NULL (e.g. a closed world)."""


class InvalidId(HearthError, LookupError):
    """HEARTH_ERROR_INVALID_ID: a destroyed, never-existing or foreign id."""


class InvalidArgument(HearthError, ValueError):
    """HEARTH_ERROR_INVALID_ARGUMENT: NaN/infinite numbers, negative sizes, unknown codes, ..."""


class WorldLocked(HearthError):
    """HEARTH_ERROR_WORLD_LOCKED: a structural change from inside a step's callback."""


class BufferTooSmall(HearthError):
    """HEARTH_ERROR_BUFFER_TOO_SMALL: a caller-owned buffer is too small; nothing was written."""


class Panic(HearthError):
    """HEARTH_ERROR_PANIC: an internal bug caught at the boundary; the world refuses further steps."""


class Io(HearthError):
    """HEARTH_ERROR_IO: writing a recording (a file, or the write callback) failed."""


class LimitReached(HearthError):
    """HEARTH_ERROR_LIMIT_REACHED: a fixed capacity is used up (4,095 worlds alive at once)."""


ERRORS = {
    _ffi.HEARTH_ERROR_NULL_POINTER: NullPointer,
    _ffi.HEARTH_ERROR_INVALID_ID: InvalidId,
    _ffi.HEARTH_ERROR_INVALID_ARGUMENT: InvalidArgument,
    _ffi.HEARTH_ERROR_WORLD_LOCKED: WorldLocked,
    _ffi.HEARTH_ERROR_BUFFER_TOO_SMALL: BufferTooSmall,
    _ffi.HEARTH_ERROR_PANIC: Panic,
    _ffi.HEARTH_ERROR_IO: Io,
    _ffi.HEARTH_ERROR_LIMIT_REACHED: LimitReached,
}


def result_name(code):
    """`hearth_result_name`: the C name of a result code (unknown codes get one too)."""
    return lib.hearth_result_name(code).decode("utf-8", "replace")


def last_error_message():
    """`hearth_last_error_message`: the calling thread's detail message of its last failure."""
    length = lib.hearth_last_error_message(None, 0)
    buf = ctypes.create_string_buffer(length + 1)
    lib.hearth_last_error_message(buf, len(buf))
    return buf.value.decode("utf-8", "replace")


def error_for(code, function=None):
    """The exception for a non-OK result, with the message of the call that just failed."""
    cls = ERRORS.get(code, HearthError)
    return cls(code, result_name(code), last_error_message(), function)


def check(code, function=None):
    """Raises the matching HearthError unless `code` is HEARTH_OK."""
    if code != _ffi.HEARTH_OK:
        raise error_for(code, function)


def _errcheck(result, function, _args):
    code = result.value
    if code != _ffi.HEARTH_OK:
        raise error_for(code, function.__name__)
    return code


# Every function that returns a HearthResult raises the matching HearthError on failure, so
# no call's result can be forgotten.
for _name, (_restype, _) in _ffi.FUNCTIONS.items():
    if _restype is _ffi.HearthResult:
        getattr(lib, _name).errcheck = _errcheck
