"""Conversions between Python values and the mirrored C structs, and caller-owned buffers.

Vectors come in as any 3-sequence (tuple, list, Vec3, a HearthVec3) and go out as Vec3
namedtuples. Numbers are passed through unchanged: whether NaN, a negative size or an
unknown code is acceptable is for the library to decide.
"""

import ctypes
from array import array
from collections import namedtuple

from . import _ffi

Vec3 = namedtuple("Vec3", "x y z")
Quat = namedtuple("Quat", "x y z w")
Transform = namedtuple("Transform", "position rotation")

IDENTITY = Quat(0.0, 0.0, 0.0, 1.0)  # the identity rotation (for shapes; defs bring their own)


def to_vec3(value):
    if isinstance(value, _ffi.HearthVec3):
        return value
    x, y, z = value
    return _ffi.HearthVec3(x, y, z)


def to_quat(value):
    if isinstance(value, _ffi.HearthQuat):
        return value
    x, y, z, w = value
    return _ffi.HearthQuat(x, y, z, w)


def to_transform(value, base=None):
    """A HearthTransform from a HearthTransform, a (position, rotation) pair, or a position alone
    (3 numbers), which keeps the rotation of `base` (a HearthTransform)."""
    if isinstance(value, _ffi.HearthTransform):
        return value
    if len(value) == 3:
        rotation = base.rotation if base is not None else to_quat(IDENTITY)
        return _ffi.HearthTransform(to_vec3(value), rotation)
    position, rotation = value
    return _ffi.HearthTransform(to_vec3(position), to_quat(rotation))


def from_vec3(v):
    return Vec3(v.x, v.y, v.z)


def from_quat(q):
    return Quat(q.x, q.y, q.z, q.w)


def from_transform(t):
    return Transform(from_vec3(t.position), from_quat(t.rotation))


def fill(struct, values, flatten=(), convert=None):
    """Sets the fields of a def (fresh from its `*_def_default()`) from keyword arguments.

    `flatten` names nested struct fields whose own fields may be given directly (the
    `base` of a joint def); `convert` maps a field type to a converter for types this
    module does not know (ids, link ends). Nested defs accept a dict of their fields.
    """
    convert = convert or {}
    for name, value in values.items():
        target = struct
        types = dict(struct._fields_)
        if name not in types:
            for outer in flatten:
                inner = getattr(struct, outer)
                if name in dict(inner._fields_):
                    target, types = inner, dict(inner._fields_)
                    break
            else:
                known = sorted(set(types) - {"internal_value"})
                raise TypeError(f"{type(struct).__name__} has no field {name!r}; fields: {', '.join(known)}")
        if name == "internal_value":
            raise TypeError("internal_value is set by the *_def_default() function and must not be changed")
        ftype = types[name]
        if ftype is _ffi.HearthVec3:
            value = to_vec3(value)
        elif ftype is _ffi.HearthQuat:
            value = to_quat(value)
        elif ftype is _ffi.HearthTransform:
            value = to_transform(value, getattr(target, name))
        elif ftype in convert:
            value = convert[ftype](value)
        elif isinstance(value, dict) and issubclass(ftype, ctypes.Structure):
            fill(getattr(target, name), value, convert=convert)
            continue
        elif ftype is ctypes.c_uint8 and isinstance(value, bool):
            value = int(value)
        setattr(target, name, value)
    return struct


def to_record(struct, cls):
    """A namedtuple `cls` from the like-named fields of a struct."""
    return cls(*(getattr(struct, name) for name in cls._fields))


# ----------------------------------------------------------------------- caller-owned buffers

# The buffer formats accepted for each element kind: float32 or uint32 items, or raw bytes.
_FORMATS = {"f": ("f",), "I": ("I", "L", "=I", "<I", "@I")}
_BYTES = ("B", "b", "c")


def new_buffer(typecode, count):
    """A zero-filled array.array of `count` items."""
    return array(typecode, bytes(count * array(typecode).itemsize))


def check_format(mv, typecode, name):
    """Raises TypeError unless the memoryview holds float32 ("f") / uint32 ("I") items or bytes."""
    fmt = mv.format
    if fmt not in _BYTES and not (fmt in _FORMATS[typecode] and mv.itemsize == 4):
        kind = "float32" if typecode == "f" else "uint32"
        raise TypeError(f"{name} must hold {kind} items (array('{typecode}')), not format {fmt!r}")


def c_view(out, ctype, typecode, name="out"):
    """A ctypes array of `ctype` over the writable buffer `out` (as many whole elements as it
    holds): the library writes straight into the caller's memory, no copy.

    `out` may be an array.array, bytearray, memoryview, numpy array or any other writable,
    C-contiguous buffer of float32 (`typecode` "f") or uint32 ("I") items, or of bytes.
    """
    mv = memoryview(out)
    if mv.readonly:
        raise TypeError(f"{name} must be writable")
    if not mv.c_contiguous:
        raise TypeError(f"{name} must be C-contiguous")
    check_format(mv, typecode, name)
    count = mv.nbytes // ctypes.sizeof(ctype)
    raw = mv.cast("B")
    if count == 0:
        return (ctype * 0)()
    return (ctype * count).from_buffer(raw)
