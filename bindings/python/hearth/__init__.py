"""Hearth, a real-time 3D physics engine: the Python binding (ctypes over libhearth).

    import hearth

    with hearth.World(gravity=(0, -9.81, 0)) as world:
        ground = world.create_body()                      # static by default
        ground.add_plane(normal=(0, 1, 0))
        box = world.create_body("dynamic", position=(0, 3, 0))
        box.add_box(half_extents=(0.5, 0.5, 0.5))
        for _ in range(120):
            world.step(1 / 60)
        print(box.position)

The library is found through $HEARTH_LIBRARY, next to the package, or on the system library
path (see `_lib.py`); its ABI version (the major, and the minor before 1.0) must equal
the binding's. Every failing call raises
a HearthError subclass carrying the library's code, name and message. The raw C layer (every
struct and function of include/hearth.h under its C name) is `hearth.ffi` and `hearth.lib`.
"""

from . import _ffi as ffi
from ._convert import Quat, Transform, Vec3
from ._lib import LIBRARY_FILE, library_path, lib
from ._lib import version_string as _version_string
from .callbacks import ContactSink, GeneratorContext
from .errors import (
    BufferTooSmall,
    HearthError,
    InvalidArgument,
    InvalidId,
    Io,
    LimitReached,
    NullPointer,
    Panic,
    WorldLocked,
    last_error_message,
    result_name,
)
from .handles import (
    AttachmentCount,
    Body,
    BodyType,
    ConeLimit,
    Generator,
    GeneratorType,
    Heightfield,
    Hull,
    Integrator,
    Joint,
    JointForce,
    JointType,
    Limits,
    Mesh,
    Motor,
    Particle,
    Shape,
    SoftBody,
    SoftBodySettings,
    Spring,
    body_ids,
    particle_ids,
)
from .world import (
    ALL_BITS,
    ExpiredParticle,
    ParticleData,
    RayHit,
    World,
    WorldCounters,
    link_end,
    query_box,
    query_capsule,
    query_filter,
    query_hull,
    query_sphere,
)

#: The version of the C API this binding was written for (include/hearth.h's HEARTH_VERSION_*).
VERSION_MAJOR = ffi.HEARTH_VERSION_MAJOR
VERSION_MINOR = ffi.HEARTH_VERSION_MINOR
VERSION_PATCH = ffi.HEARTH_VERSION_PATCH
__version__ = f"{VERSION_MAJOR}.{VERSION_MINOR}.{VERSION_PATCH}"


def library_version():
    """`hearth_version()` of the loaded library as "major.minor.patch"."""
    return _version_string(lib.hearth_version())


__all__ = [
    "ALL_BITS",
    "AttachmentCount",
    "Body",
    "BodyType",
    "BufferTooSmall",
    "ConeLimit",
    "ContactSink",
    "ExpiredParticle",
    "Generator",
    "GeneratorContext",
    "GeneratorType",
    "HearthError",
    "Integrator",
    "InvalidArgument",
    "InvalidId",
    "Io",
    "Joint",
    "JointForce",
    "JointType",
    "Heightfield",
    "Hull",
    "LIBRARY_FILE",
    "LimitReached",
    "Limits",
    "Mesh",
    "Motor",
    "NullPointer",
    "Panic",
    "Particle",
    "ParticleData",
    "Quat",
    "RayHit",
    "Shape",
    "SoftBody",
    "SoftBodySettings",
    "Spring",
    "Transform",
    "VERSION_MAJOR",
    "VERSION_MINOR",
    "VERSION_PATCH",
    "Vec3",
    "World",
    "WorldCounters",
    "WorldLocked",
    "body_ids",
    "ffi",
    "last_error_message",
    "lib",
    "library_path",
    "library_version",
    "link_end",
    "particle_ids",
    "query_box",
    "query_capsule",
    "query_filter",
    "query_hull",
    "query_sphere",
    "result_name",
]
