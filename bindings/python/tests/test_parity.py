"""Parity: every function, type and constant of include/hearth.h is mirrored by the binding
with the same signature, and every function is used by the Pythonic layer (or listed, with a
reason, in hearth._ffi.NOT_WRAPPED). A new export fails here until someone wraps it."""

import ctypes
import re
from pathlib import Path

import c_header
import pytest

import hearth
from hearth import _ffi

HEADER = c_header.parse()
PACKAGE = Path(hearth.__file__).resolve().parent
# The Pythonic layer: every module of the package but the raw mirror itself.
LAYER_SOURCE = "".join(p.read_text() for p in sorted(PACKAGE.glob("*.py")) if p.name != "_ffi.py")

SCALARS = {
    "uint8_t": ctypes.c_uint8,
    "uint32_t": ctypes.c_uint32,
    "int32_t": ctypes.c_int32,
    "uint64_t": ctypes.c_uint64,
    "size_t": ctypes.c_size_t,
    "float": ctypes.c_float,
    "bool": ctypes.c_bool,
    "char": ctypes.c_char,
    "HearthResult": _ffi.HearthResult,
}


def expected_ctype(ctype):
    """The ctypes type a C type from the header must be declared as."""
    if ctype == "void":
        return None
    if ctype == "const char *":
        return ctypes.c_char_p  # a returned static string
    if ctype == "void *":
        return ctypes.c_void_p
    bare = ctype.replace("const ", "").replace("struct ", "")
    stars = bare.count("*")
    base = bare.replace("*", "").strip()
    if base in SCALARS:
        result = SCALARS[base]
    else:
        result = getattr(_ffi, base)  # a mirrored struct or callback type
    for _ in range(stars):
        result = ctypes.POINTER(result)
    return result


def test_binding_version_constants_match_the_header():
    assert hearth.VERSION_MAJOR == HEADER.defines["HEARTH_VERSION_MAJOR"]
    assert hearth.VERSION_MINOR == HEADER.defines["HEARTH_VERSION_MINOR"]
    assert hearth.VERSION_PATCH == HEADER.defines["HEARTH_VERSION_PATCH"]
    assert _ffi.HEARTH_VERSION == HEADER.defines["HEARTH_VERSION"]


def test_loaded_library_has_the_binding_major_version():
    assert hearth.lib.hearth_version() >> 16 == hearth.VERSION_MAJOR


def test_every_constant_is_mirrored_with_its_value():
    constants = dict(HEADER.defines)
    for enum in HEADER.enums.values():
        constants.update(enum)
    for name, value in constants.items():
        assert getattr(_ffi, name, None) == value, f"{name} = {value} in the header"


@pytest.mark.parametrize("name", sorted(HEADER.functions))
def test_function_is_declared_with_the_header_signature(name):
    fn = HEADER.functions[name]
    assert name in _ffi.FUNCTIONS, f"{name} is exported but not declared in hearth/_ffi.py"
    restype, argtypes = _ffi.FUNCTIONS[name]
    assert restype is expected_ctype(fn.restype), f"{name}: return type {fn.restype}"
    assert argtypes == [expected_ctype(p.ctype) for p in fn.params], f"{name}: parameters"
    # and the loaded library's function object carries exactly these declarations
    loaded = getattr(hearth.lib, name)
    assert loaded.restype is restype and loaded.argtypes == argtypes


@pytest.mark.parametrize("name", sorted(HEADER.functions))
def test_function_is_wrapped_or_listed(name):
    wrapped = re.search(rf"\blib\.{name}\b", LAYER_SOURCE) is not None
    if name in _ffi.NOT_WRAPPED:
        assert not wrapped, f"{name} is wrapped; remove it from NOT_WRAPPED"
        assert _ffi.NOT_WRAPPED[name].strip(), f"{name}: NOT_WRAPPED needs a reason"
    else:
        assert wrapped, f"{name} is exported by include/hearth.h but no Python class wraps it"


def test_no_stale_declarations_or_exemptions():
    assert set(_ffi.FUNCTIONS) == set(HEADER.functions)
    stale = set(_ffi.NOT_WRAPPED) - set(HEADER.functions) - HEADER.type_names()
    assert not stale, f"NOT_WRAPPED lists names the header no longer has: {sorted(stale)}"


@pytest.mark.parametrize("name", sorted(HEADER.structs))
def test_struct_is_mirrored_field_by_field(name):
    mirror = getattr(_ffi, name, None)
    assert mirror is not None and issubclass(mirror, ctypes.Structure), f"{name} is not mirrored"
    declared = [(f, t) for f, t in mirror._fields_]
    expected = [(p.name, expected_ctype(p.ctype)) for p in HEADER.structs[name]]
    assert declared == expected


@pytest.mark.parametrize("name", sorted(HEADER.opaque))
def test_opaque_type_is_mirrored_and_has_a_class(name):
    mirror = getattr(_ffi, name, None)
    assert mirror is not None and issubclass(mirror, ctypes.Structure), f"{name} is not mirrored"
    # HearthWorld -> hearth.World, HearthContactSink -> hearth.ContactSink
    assert hasattr(hearth, name.removeprefix("Hearth")) or name in _ffi.NOT_WRAPPED


@pytest.mark.parametrize("name", sorted(HEADER.callbacks))
def test_callback_type_is_mirrored_and_wrapped(name):
    cb = HEADER.callbacks[name]
    mirror = getattr(_ffi, name, None)
    assert mirror is not None, f"{name} is not mirrored"
    assert mirror._restype_ is expected_ctype(cb.restype)
    assert list(mirror._argtypes_) == [expected_ctype(p.ctype) for p in cb.params]
    wrapped = re.search(rf"_ffi\.{name}\(", LAYER_SOURCE) is not None
    assert wrapped or name in _ffi.NOT_WRAPPED, f"no Python callable can be used as a {name}"


def test_result_enum_is_mirrored():
    assert set(HEADER.enums) == {"HearthResult"}, "a new enum in the header: mirror it"
    for code, cls in hearth.errors.ERRORS.items():
        assert cls.__name__.upper() == hearth.result_name(code).removeprefix("HEARTH_ERROR_").replace("_", "")
    assert set(hearth.errors.ERRORS) == {v for k, v in HEADER.enums["HearthResult"].items() if k != "HEARTH_OK"}


def unwrapped(header):
    """Names of the header's functions and types that the binding neither wraps nor lists."""
    names = []
    for name in header.functions:
        if name not in _ffi.NOT_WRAPPED and not re.search(rf"\blib\.{name}\b", LAYER_SOURCE):
            names.append(name)
    for name in header.type_names():
        if name not in _ffi.NOT_WRAPPED and not hasattr(_ffi, name):
            names.append(name)
    return names


def test_everything_in_the_header_is_wrapped():
    assert unwrapped(HEADER) == []


def test_a_new_export_fails_the_parity_check(tmp_path):
    extra = """
typedef struct HearthBeam { struct HearthVec3 origin; struct HearthVec3 direction; } HearthBeam;
HearthResult hearth_world_cast_beam(const struct HearthWorld *world, const struct HearthBeam *beam);
#endif  /* HEARTH_H */
"""
    text = c_header.HEADER.read_text().replace("#endif  /* HEARTH_H */", extra)
    path = tmp_path / "hearth.h"
    path.write_text(text)
    assert sorted(unwrapped(c_header.parse(path))) == ["HearthBeam", "hearth_world_cast_beam"]


def test_package_metadata_version_is_the_binding_version():
    pyproject = (PACKAGE.parent / "pyproject.toml").read_text()
    assert re.search(r'^version = "([^"]+)"', pyproject, flags=re.M).group(1) == hearth.__version__
