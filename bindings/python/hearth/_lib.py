"""Finds and loads the Hearth shared library, checks its version and declares every function.

Lookup order:

1. the environment variable ``HEARTH_LIBRARY`` (the full path of the library file);
2. the library file next to the package: inside the ``hearth`` package directory, then in
   the directory that holds it;
3. ``ctypes.util.find_library("hearth")`` (the system's library path).

The first place that names a library decides: when ``HEARTH_LIBRARY`` is set but cannot be
loaded, that is an error, not a reason to pick up some other copy.
"""

import ctypes
import ctypes.util
import os
import sys
from pathlib import Path

from . import _ffi

ENV_VAR = "HEARTH_LIBRARY"

if sys.platform == "darwin":
    LIBRARY_FILE = "libhearth.dylib"
elif sys.platform == "win32":
    LIBRARY_FILE = "hearth.dll"
else:
    LIBRARY_FILE = "libhearth.so"

_PACKAGE_DIR = Path(__file__).resolve().parent


def version_string(version):
    """`(major << 16) | (minor << 8) | patch` as "major.minor.patch"."""
    return f"{version >> 16}.{(version >> 8) & 0xFF}.{version & 0xFF}"


def abi_version(version):
    """The ABI a version belongs to: its major, or (0, minor) while the major is 0 (every 0.x
    minor may break the ABI, as Cargo treats it; the library's SONAME is libhearth.so.0.<minor>)."""
    major, minor = version >> 16, (version >> 8) & 0xFF
    return (0, minor) if major == 0 else (major,)


def check_version(library_version, binding_version=_ffi.HEARTH_VERSION):
    """Raises ImportError when the library's ABI is not the binding's: another major version,
    or another minor version while the major is 0. Patch versions may always differ."""
    if abi_version(library_version) != abi_version(binding_version):
        abi = ".".join(str(n) for n in abi_version(binding_version))
        raise ImportError(
            f"the Hearth library is version {version_string(library_version)} but this Python binding "
            f"was written for version {version_string(binding_version)} (ABI {abi}); "
            "the ABI versions must match (the major version, and the minor before 1.0): "
            "use the binding that came with the library"
        )


def _candidates():
    """Yields (description, path or name) in lookup order."""
    env = os.environ.get(ENV_VAR)
    if env:
        yield f"${ENV_VAR}={env}", env
        return  # an explicit choice: never fall back to another copy
    for directory in (_PACKAGE_DIR, _PACKAGE_DIR.parent):
        path = directory / LIBRARY_FILE
        if path.exists():
            yield f"next to the package ({path})", str(path)
            return
    found = ctypes.util.find_library("hearth")
    if found:
        yield f'ctypes.util.find_library("hearth") -> {found}', found


def load():
    """Loads the library, checks its version and declares every function; returns (CDLL, path)."""
    for description, target in _candidates():
        try:
            library = ctypes.CDLL(target)
        except OSError as e:
            raise ImportError(f"cannot load the Hearth library from {description}: {e}") from e
        break
    else:
        tried = [
            f"the environment variable {ENV_VAR} (unset)",
            f"{LIBRARY_FILE} next to the package (not in {_PACKAGE_DIR} nor {_PACKAGE_DIR.parent})",
            'ctypes.util.find_library("hearth") (nothing on the system library path)',
        ]
        raise ImportError(
            "cannot find the Hearth shared library; looked at: "
            + "; ".join(tried)
            + f". Build it (cargo build --release) and set {ENV_VAR} to the path of {LIBRARY_FILE}."
        )

    try:
        version_fn = library.hearth_version
    except AttributeError as e:
        raise ImportError(f"{target} is not a Hearth library (no hearth_version)") from e
    version_fn.restype, version_fn.argtypes = _ffi.FUNCTIONS["hearth_version"]
    check_version(version_fn())

    for name, (restype, argtypes) in _ffi.FUNCTIONS.items():
        try:
            fn = getattr(library, name)
        except AttributeError as e:
            raise ImportError(
                f"the Hearth library {target} (version {version_string(version_fn())}) lacks {name}, "
                f"which this binding (version {version_string(_ffi.HEARTH_VERSION)}) needs"
            ) from e
        fn.restype = restype
        fn.argtypes = argtypes
    return library, getattr(library, "_name", target)


lib, library_path = load()
