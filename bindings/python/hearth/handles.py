"""Handles to the objects inside a world: bodies, shapes, joints, generators, particles and
soft bodies.

A handle is a world and a C id (`{index, generation}`). It holds no state of its own: every
property reads the world through the C API, so a handle to a destroyed object raises
InvalidId (with the library's message) like the C call does. Handles compare equal when
they name the same object of the same world.
"""

import ctypes
from collections import namedtuple
from ctypes import byref
from enum import IntEnum

from . import _ffi
from ._convert import (
    IDENTITY,
    c_view,
    fill,
    from_transform,
    from_vec3,
    new_buffer,
    to_quat,
    to_transform,
    to_vec3,
)
from ._lib import lib


class BodyType(IntEnum):
    """`HEARTH_BODY_*`."""

    STATIC = _ffi.HEARTH_BODY_STATIC
    KINEMATIC = _ffi.HEARTH_BODY_KINEMATIC
    DYNAMIC = _ffi.HEARTH_BODY_DYNAMIC


class GeneratorType(IntEnum):
    """`HEARTH_GENERATOR_*`."""

    GRAVITY = _ffi.HEARTH_GENERATOR_GRAVITY
    DRAG = _ffi.HEARTH_GENERATOR_DRAG
    SPRING = _ffi.HEARTH_GENERATOR_SPRING
    BUNGEE = _ffi.HEARTH_GENERATOR_BUNGEE
    STIFF_SPRING = _ffi.HEARTH_GENERATOR_STIFF_SPRING
    BUOYANCY = _ffi.HEARTH_GENERATOR_BUOYANCY
    EXPLOSION = _ffi.HEARTH_GENERATOR_EXPLOSION
    ROD = _ffi.HEARTH_GENERATOR_ROD
    CABLE = _ffi.HEARTH_GENERATOR_CABLE
    USER_FORCE = _ffi.HEARTH_GENERATOR_USER_FORCE
    USER_CONTACT = _ffi.HEARTH_GENERATOR_USER_CONTACT


class JointType(IntEnum):
    """`HEARTH_JOINT_*`."""

    BALL = _ffi.HEARTH_JOINT_BALL
    HINGE = _ffi.HEARTH_JOINT_HINGE
    FIXED = _ffi.HEARTH_JOINT_FIXED
    DISTANCE = _ffi.HEARTH_JOINT_DISTANCE
    SLIDER = _ffi.HEARTH_JOINT_SLIDER


class Integrator(IntEnum):
    """`HEARTH_INTEGRATOR_*`."""

    SEMI_IMPLICIT_EULER = _ffi.HEARTH_INTEGRATOR_SEMI_IMPLICIT_EULER
    RK4 = _ffi.HEARTH_INTEGRATOR_RK4


def _enum_or_code(enum, value):
    """An enum member for a known code; any other number unchanged (for the library to judge)."""
    try:
        return enum(value)
    except ValueError:
        return value


Motor = namedtuple("Motor", "enabled speed max")
Limits = namedtuple("Limits", "enabled lower upper")
ConeLimit = namedtuple("ConeLimit", "enabled angle")
Spring = namedtuple("Spring", "enabled hertz damping_ratio")
JointForce = namedtuple("JointForce", "force torque")
AttachmentCount = namedtuple("AttachmentCount", "bodies particles")

#: The settings of a soft body that may change after creation (`HearthSoftBodySettings`):
#: the like-named fields of `HearthSoftBodyDef`, with the flags `preserve_volume` and
#: `collide` as bools. Read with `SoftBody.settings`, change with `SoftBody.set_settings`.
SoftBodySettings = namedtuple("SoftBodySettings", [name for name, _ in _ffi.HearthSoftBodySettings._fields_])
_SOFT_FLAGS = ("preserve_volume", "collide")


class _Handle:
    """A world and an id. Subclasses set _ID_TYPE, the C id struct."""

    __slots__ = ("world", "_id")
    _ID_TYPE = None

    def __init__(self, world, c_id):
        self.world = world
        self._id = self._ID_TYPE(c_id.index, c_id.generation)  # a copy: C arrays are transient

    @classmethod
    def from_id(cls, world, index, generation):
        """A handle from raw id numbers (e.g. from a bulk ids buffer)."""
        return cls(world, cls._ID_TYPE(index, generation))

    @property
    def id(self):
        """The C id as (index, generation)."""
        return (self._id.index, self._id.generation)

    @property
    def _w(self):
        return self.world._ptr

    def __eq__(self, other):
        return type(other) is type(self) and other.world is self.world and other.id == self.id

    def __hash__(self):
        return hash((type(self), id(self.world), self.id))

    def __repr__(self):
        return f"{type(self).__name__}(index={self._id.index}, generation={self._id.generation})"


class Body(_Handle):
    """A rigid body (`HearthBodyId`). Create with `World.create_body`."""

    __slots__ = ()
    _ID_TYPE = _ffi.HearthBodyId

    # -- reads
    @property
    def transform(self):
        """Pose of the body origin: Transform(position, rotation)."""
        out = _ffi.HearthTransform()
        lib.hearth_body_get_transform(self._w, self._id, byref(out))
        return from_transform(out)

    @transform.setter
    def transform(self, value):
        self.set_transform(value)

    @property
    def position(self):
        return self.transform.position

    @position.setter
    def position(self, value):
        """Teleports the origin, keeping the rotation."""
        self.set_transform(value)

    @property
    def rotation(self):
        return self.transform.rotation

    @rotation.setter
    def rotation(self, value):
        """Turns the body about its origin, keeping the position."""
        self.set_transform((self.position, value))

    @property
    def linear_velocity(self):
        out = _ffi.HearthVec3()
        lib.hearth_body_get_linear_velocity(self._w, self._id, byref(out))
        return from_vec3(out)

    @linear_velocity.setter
    def linear_velocity(self, value):
        lib.hearth_body_set_linear_velocity(self._w, self._id, to_vec3(value))

    @property
    def angular_velocity(self):
        out = _ffi.HearthVec3()
        lib.hearth_body_get_angular_velocity(self._w, self._id, byref(out))
        return from_vec3(out)

    @angular_velocity.setter
    def angular_velocity(self, value):
        lib.hearth_body_set_angular_velocity(self._w, self._id, to_vec3(value))

    @property
    def is_awake(self):
        out = ctypes.c_bool()
        lib.hearth_body_is_awake(self._w, self._id, byref(out))
        return out.value

    @property
    def center_of_mass(self):
        out = _ffi.HearthVec3()
        lib.hearth_body_get_center_of_mass(self._w, self._id, byref(out))
        return from_vec3(out)

    @property
    def mass(self):
        out = ctypes.c_float()
        lib.hearth_body_get_mass(self._w, self._id, byref(out))
        return out.value

    @property
    def user_data(self):
        out = ctypes.c_uint64()
        lib.hearth_body_get_user_data(self._w, self._id, byref(out))
        return out.value

    @property
    def type(self):
        out = ctypes.c_uint32()
        lib.hearth_body_get_type(self._w, self._id, byref(out))
        return _enum_or_code(BodyType, out.value)

    # -- changes
    def set_transform(self, transform):
        """Teleports the body: a Transform/(position, rotation) pair, or a position alone."""
        current = _ffi.HearthTransform()
        if not isinstance(transform, _ffi.HearthTransform) and len(transform) == 3:
            lib.hearth_body_get_transform(self._w, self._id, byref(current))
        lib.hearth_body_set_transform(self._w, self._id, byref(to_transform(transform, current)))

    def set_target_transform(self, target):
        """Kinematic bodies: reach `target` by the end of the next step."""
        current = _ffi.HearthTransform()
        if not isinstance(target, _ffi.HearthTransform) and len(target) == 3:
            lib.hearth_body_get_transform(self._w, self._id, byref(current))
        lib.hearth_body_set_target_transform(self._w, self._id, byref(to_transform(target, current)))

    def set_awake(self, awake):
        lib.hearth_body_set_awake(self._w, self._id, int(awake))

    def set_damping(self, linear_damping, angular_damping):
        lib.hearth_body_set_damping(self._w, self._id, linear_damping, angular_damping)

    # -- runtime setters (each with its getter)
    @type.setter
    def type(self, value):
        """`hearth_body_set_type`: a BodyType or its name ("static", "kinematic", "dynamic")."""
        if isinstance(value, str):
            value = BodyType[value.upper()]
        lib.hearth_body_set_type(self._w, self._id, int(value))

    @property
    def gravity_scale(self):
        out = ctypes.c_float()
        lib.hearth_body_get_gravity_scale(self._w, self._id, byref(out))
        return out.value

    @gravity_scale.setter
    def gravity_scale(self, value):
        lib.hearth_body_set_gravity_scale(self._w, self._id, value)

    @property
    def locked_axes(self):
        """`hearth_body_get_locked_axes` / `hearth_body_set_locked_axes`: HEARTH_LOCK_* bits ORed
        (world axes). Setting zeroes the locked velocity components at once and wakes the body."""
        out = ctypes.c_uint32()
        lib.hearth_body_get_locked_axes(self._w, self._id, byref(out))
        return out.value

    @locked_axes.setter
    def locked_axes(self, value):
        lib.hearth_body_set_locked_axes(self._w, self._id, value)

    @property
    def mass_data(self):
        """(mass kg, centre of mass in the body frame, diagonal of the inertia kg·m²)."""
        out = _ffi.HearthMassData()
        lib.hearth_body_get_mass_data(self._w, self._id, byref(out))
        return out.mass, from_vec3(out.center), from_vec3(out.inertia)

    def set_mass_data(self, mass, center, inertia):
        """`hearth_body_set_mass_data`: overrides mass, centre and principal inertia."""
        data = _ffi.HearthMassData(mass, to_vec3(center), to_vec3(inertia))
        lib.hearth_body_set_mass_data(self._w, self._id, byref(data))

    def reset_mass_data(self):
        lib.hearth_body_reset_mass_data(self._w, self._id)

    @property
    def enabled(self):
        out = ctypes.c_bool()
        lib.hearth_body_is_enabled(self._w, self._id, byref(out))
        return out.value

    @enabled.setter
    def enabled(self, value):
        """`hearth_body_enable` (True) / `hearth_body_disable` (False)."""
        if value:
            lib.hearth_body_enable(self._w, self._id)
        else:
            lib.hearth_body_disable(self._w, self._id)

    def apply_force(self, force):
        lib.hearth_body_apply_force(self._w, self._id, to_vec3(force))

    def apply_torque(self, torque):
        lib.hearth_body_apply_torque(self._w, self._id, to_vec3(torque))

    def apply_linear_impulse(self, impulse):
        lib.hearth_body_apply_linear_impulse(self._w, self._id, to_vec3(impulse))

    def apply_angular_impulse(self, impulse):
        lib.hearth_body_apply_angular_impulse(self._w, self._id, to_vec3(impulse))

    def apply_force_at_point(self, force, point):
        lib.hearth_body_apply_force_at_point(self._w, self._id, to_vec3(force), to_vec3(point))

    def apply_impulse_at_point(self, impulse, point):
        lib.hearth_body_apply_impulse_at_point(self._w, self._id, to_vec3(impulse), to_vec3(point))

    def destroy(self):
        """Destroys the body, its shapes and joints; the handle becomes stale."""
        lib.hearth_body_destroy(self._w, self._id)

    # -- shapes (material fields: those of HearthShapeDef, defaults from hearth_shape_def_default)
    def _add(self, create, geometry, material):
        sd = fill(lib.hearth_shape_def_default(), material)
        out = _ffi.HearthShapeId()
        create(self._w, self._id, byref(sd), byref(geometry), byref(out))
        return Shape(self.world, out)

    def add_sphere(self, radius, center=(0.0, 0.0, 0.0), **material):
        """`hearth_shape_create_sphere`; `material`: density, static_friction, ... (HearthShapeDef)."""
        return self._add(lib.hearth_shape_create_sphere, _ffi.HearthSphere(to_vec3(center), radius), material)

    def add_box(self, half_extents, center=(0.0, 0.0, 0.0), rotation=IDENTITY, **material):
        """`hearth_shape_create_box`: half extents (m), centre and rotation in the body frame."""
        box = _ffi.HearthBox(to_vec3(center), to_quat(rotation), to_vec3(half_extents))
        return self._add(lib.hearth_shape_create_box, box, material)

    def add_capsule(self, a, b, radius, **material):
        """`hearth_shape_create_capsule`: segment end points in the body frame and radius."""
        return self._add(lib.hearth_shape_create_capsule, _ffi.HearthCapsule(to_vec3(a), to_vec3(b), radius), material)

    def add_plane(self, normal, offset=0.0, **material):
        """`hearth_shape_create_plane` (static bodies): points with dot(normal, p) <= offset are inside."""
        return self._add(lib.hearth_shape_create_plane, _ffi.HearthPlane(to_vec3(normal), offset), material)

    def add_hull(self, hull, scale=1.0, position=(0.0, 0.0, 0.0), rotation=IDENTITY, **material):
        """`hearth_shape_create_hull`: instances `hull` (a Hull) scaled uniformly by `scale`, placed
        at `position`/`rotation` in the body frame. Mass comes from the polyhedron and density."""
        shape = _ffi.HearthHullShape(hull._id, to_transform((position, rotation)), scale)
        return self._add(lib.hearth_shape_create_hull, shape, material)

    def add_mesh(self, mesh, scale=(1.0, 1.0, 1.0), position=(0.0, 0.0, 0.0), rotation=IDENTITY, **material):
        """`hearth_shape_create_mesh` (static and kinematic bodies): instances `mesh` (a Mesh) scaled
        per axis, placed at `position`/`rotation` in the body frame."""
        shape = _ffi.HearthMeshShape(mesh._id, to_transform((position, rotation)), to_vec3(scale))
        return self._add(lib.hearth_shape_create_mesh, shape, material)

    def add_heightfield(self, heightfield, scale=(1.0, 1.0, 1.0), position=(0.0, 0.0, 0.0), rotation=IDENTITY, **material):
        """`hearth_shape_create_heightfield` (static and kinematic bodies): `scale` x and z are the
        sample spacing (m), y multiplies the heights."""
        shape = _ffi.HearthHeightfieldShape(heightfield._id, to_transform((position, rotation)), to_vec3(scale))
        return self._add(lib.hearth_shape_create_heightfield, shape, material)


class Shape(_Handle):
    """A shape on a body (`HearthShapeId`). Create with `Body.add_sphere` and friends."""

    __slots__ = ()
    _ID_TYPE = _ffi.HearthShapeId

    @property
    def body(self):
        out = _ffi.HearthBodyId()
        lib.hearth_shape_get_body(self._w, self._id, byref(out))
        return Body(self.world, out)

    def _get_float(self, getter):
        out = ctypes.c_float()
        getter(self._w, self._id, byref(out))
        return out.value

    @property
    def friction(self):
        """(static, dynamic) friction coefficients; set with a pair or one number for both."""
        s, d = ctypes.c_float(), ctypes.c_float()
        lib.hearth_shape_get_friction(self._w, self._id, byref(s), byref(d))
        return s.value, d.value

    @friction.setter
    def friction(self, value):
        s, d = (value, value) if isinstance(value, (int, float)) else value
        lib.hearth_shape_set_friction(self._w, self._id, s, d)

    @property
    def restitution(self):
        return self._get_float(lib.hearth_shape_get_restitution)

    @restitution.setter
    def restitution(self, value):
        lib.hearth_shape_set_restitution(self._w, self._id, value)

    @property
    def rolling_resistance(self):
        return self._get_float(lib.hearth_shape_get_rolling_resistance)

    @rolling_resistance.setter
    def rolling_resistance(self, value):
        lib.hearth_shape_set_rolling_resistance(self._w, self._id, value)

    @property
    def torsional_friction(self):
        return self._get_float(lib.hearth_shape_get_torsional_friction)

    @torsional_friction.setter
    def torsional_friction(self, value):
        lib.hearth_shape_set_torsional_friction(self._w, self._id, value)

    @property
    def density(self):
        return self._get_float(lib.hearth_shape_get_density)

    @density.setter
    def density(self, value):
        lib.hearth_shape_set_density(self._w, self._id, value)

    @property
    def user_data(self):
        out = ctypes.c_uint64()
        lib.hearth_shape_get_user_data(self._w, self._id, byref(out))
        return out.value

    @user_data.setter
    def user_data(self, value):
        lib.hearth_shape_set_user_data(self._w, self._id, value)

    def destroy(self):
        lib.hearth_shape_destroy(self._w, self._id)

    @property
    def filter(self):
        """`hearth_shape_get_filter`: (category_bits, mask_bits, group_index)."""
        out = _ffi.HearthFilter()
        lib.hearth_shape_get_filter(self._w, self._id, byref(out))
        return (out.category_bits, out.mask_bits, out.group_index)

    @filter.setter
    def filter(self, value):
        """`hearth_shape_set_filter` from (category_bits, mask_bits, group_index); pairs are
        re-evaluated at the next step."""
        f = lib.hearth_filter_default()
        f.category_bits, f.mask_bits, f.group_index = value
        lib.hearth_shape_set_filter(self._w, self._id, f)


class Joint(_Handle):
    """A joint between two bodies or a body and the world (`HearthJointId`)."""

    __slots__ = ()
    _ID_TYPE = _ffi.HearthJointId

    @property
    def type(self):
        out = ctypes.c_uint32()
        lib.hearth_joint_get_type(self._w, self._id, byref(out))
        return _enum_or_code(JointType, out.value)

    @property
    def bodies(self):
        """(body_a, body_b); body_b is None for a joint to the world."""
        a, b = _ffi.HearthBodyId(), _ffi.HearthBodyId()
        lib.hearth_joint_get_bodies(self._w, self._id, byref(a), byref(b))
        return Body(self.world, a), (Body(self.world, b) if (b.index, b.generation) != (0, 0) else None)

    def set_motor(self, enable, speed, max):
        """Hinge (rad/s, N·m) or slider (m/s, N) motor."""
        lib.hearth_joint_set_motor(self._w, self._id, int(enable), speed, max)

    @property
    def motor(self):
        e, s, m = ctypes.c_bool(), ctypes.c_float(), ctypes.c_float()
        lib.hearth_joint_get_motor(self._w, self._id, byref(e), byref(s), byref(m))
        return Motor(e.value, s.value, m.value)

    def set_limits(self, enable, lower, upper):
        lib.hearth_joint_set_limits(self._w, self._id, int(enable), lower, upper)

    @property
    def limits(self):
        e, lo, hi = ctypes.c_bool(), ctypes.c_float(), ctypes.c_float()
        lib.hearth_joint_get_limits(self._w, self._id, byref(e), byref(lo), byref(hi))
        return Limits(e.value, lo.value, hi.value)

    def set_cone_limit(self, enable, angle):
        lib.hearth_joint_set_cone_limit(self._w, self._id, int(enable), angle)

    @property
    def cone_limit(self):
        e, a = ctypes.c_bool(), ctypes.c_float()
        lib.hearth_joint_get_cone_limit(self._w, self._id, byref(e), byref(a))
        return ConeLimit(e.value, a.value)

    def set_spring(self, enable, hertz, damping_ratio):
        lib.hearth_joint_set_spring(self._w, self._id, int(enable), hertz, damping_ratio)

    @property
    def spring(self):
        e, h, d = ctypes.c_bool(), ctypes.c_float(), ctypes.c_float()
        lib.hearth_joint_get_spring(self._w, self._id, byref(e), byref(h), byref(d))
        return Spring(e.value, h.value, d.value)

    @property
    def force(self):
        """JointForce(force, torque) applied to body B during the last step (world space)."""
        f, t = _ffi.HearthVec3(), _ffi.HearthVec3()
        lib.hearth_joint_get_force(self._w, self._id, byref(f), byref(t))
        return JointForce(from_vec3(f), from_vec3(t))

    @property
    def is_broken(self):
        out = ctypes.c_bool()
        lib.hearth_joint_is_broken(self._w, self._id, byref(out))
        return out.value

    def destroy(self):
        lib.hearth_joint_destroy(self._w, self._id)


class Particle(_Handle):
    """A point mass (`HearthParticleId`). Create with `World.create_particle` or `World.emit_burst`."""

    __slots__ = ()
    _ID_TYPE = _ffi.HearthParticleId

    @property
    def position(self):
        out = _ffi.HearthVec3()
        lib.hearth_particle_get_position(self._w, self._id, byref(out))
        return from_vec3(out)

    @position.setter
    def position(self, value):
        lib.hearth_particle_set_position(self._w, self._id, to_vec3(value))

    @property
    def velocity(self):
        out = _ffi.HearthVec3()
        lib.hearth_particle_get_velocity(self._w, self._id, byref(out))
        return from_vec3(out)

    @velocity.setter
    def velocity(self, value):
        lib.hearth_particle_set_velocity(self._w, self._id, to_vec3(value))

    @property
    def is_awake(self):
        out = ctypes.c_bool()
        lib.hearth_particle_is_awake(self._w, self._id, byref(out))
        return out.value

    def set_awake(self, awake):
        lib.hearth_particle_set_awake(self._w, self._id, int(awake))

    @property
    def user_data(self):
        out = ctypes.c_uint64()
        lib.hearth_particle_get_user_data(self._w, self._id, byref(out))
        return out.value

    def apply_force(self, force):
        lib.hearth_particle_apply_force(self._w, self._id, to_vec3(force))

    def apply_impulse(self, impulse):
        lib.hearth_particle_apply_impulse(self._w, self._id, to_vec3(impulse))

    def destroy(self):
        lib.hearth_particle_destroy(self._w, self._id)


class Generator(_Handle):
    """A force or contact generator (`HearthGeneratorId`). Create with `World.create_*_generator`,
    `World.create_rod` / `create_cable`, or with a Python callable via
    `World.create_force_generator` / `create_contact_generator`."""

    __slots__ = ()
    _ID_TYPE = _ffi.HearthGeneratorId

    @property
    def type(self):
        out = ctypes.c_uint32()
        lib.hearth_generator_get_type(self._w, self._id, byref(out))
        return _enum_or_code(GeneratorType, out.value)

    def attach(self, target):
        """Makes the generator act on a Body or a Particle."""
        if isinstance(target, Particle):
            lib.hearth_generator_attach_particle(self._w, self._id, target._id)
        else:
            lib.hearth_generator_attach_body(self._w, self._id, _body_id(target))

    def detach(self, target):
        if isinstance(target, Particle):
            lib.hearth_generator_detach_particle(self._w, self._id, target._id)
        else:
            lib.hearth_generator_detach_body(self._w, self._id, _body_id(target))

    def attach_particles(self, particles):
        """Attaches many particles at once, all or nothing: a sequence of Particle or a ctypes
        array from `particle_ids()`."""
        ids = particle_ids(particles)
        lib.hearth_generator_attach_particles(self._w, self._id, ids, len(ids))

    @property
    def attachment_count(self):
        """AttachmentCount(bodies, particles): the live objects attached."""
        b, p = ctypes.c_uint32(), ctypes.c_uint32()
        lib.hearth_generator_get_attachment_count(self._w, self._id, byref(b), byref(p))
        return AttachmentCount(b.value, p.value)

    def destroy(self):
        """Destroys the generator; a Python callback it ran is released."""
        lib.hearth_generator_destroy(self._w, self._id)
        self.world._release_callback(self._id)


class SoftBody(_Handle):
    """A soft body (`HearthSoftBodyId`). Create with `World.create_soft_body_mesh`,
    `create_soft_icosphere`, `create_soft_box` or `create_soft_cloth`."""

    __slots__ = ()
    _ID_TYPE = _ffi.HearthSoftBodyId

    def _count(self, fn):
        out = ctypes.c_size_t()
        fn(self._w, self._id, byref(out))
        return out.value

    @property
    def vertex_count(self):
        return self._count(lib.hearth_soft_body_get_vertex_count)

    @property
    def triangle_count(self):
        return self._count(lib.hearth_soft_body_get_triangle_count)

    def _read(self, fn, count_fn, ctype, typecode, per, out):
        if out is None:
            out = new_buffer(typecode, per * self._count(count_fn))
        view = c_view(out, ctype, typecode)
        count = ctypes.c_size_t()
        fn(self._w, self._id, view, len(view), byref(count))
        return out

    def get_positions(self, out=None):
        """Every vertex position (m, world space) into `out` (float32 buffer, 3 per vertex; a new
        array('f') when None), in one call. Returns `out`."""
        return self._read(
            lib.hearth_soft_body_get_positions,
            lib.hearth_soft_body_get_vertex_count,
            _ffi.HearthVec3,
            "f",
            3,
            out,
        )

    def get_normals(self, out=None):
        """Every vertex normal into `out` (float32, 3 per vertex), as get_positions."""
        return self._read(
            lib.hearth_soft_body_get_normals,
            lib.hearth_soft_body_get_vertex_count,
            _ffi.HearthVec3,
            "f",
            3,
            out,
        )

    def get_indices(self, out=None):
        """The triangle indices into `out` (uint32 buffer, 3 per triangle; a new array('I') when
        None). Returns `out`."""
        return self._read(
            lib.hearth_soft_body_get_indices,
            lib.hearth_soft_body_get_triangle_count,
            ctypes.c_uint32,
            "I",
            3,
            out,
        )

    def _vertex_vec(self, fn, vertex):
        out = _ffi.HearthVec3()
        fn(self._w, self._id, vertex, byref(out))
        return from_vec3(out)

    def vertex_position(self, vertex):
        return self._vertex_vec(lib.hearth_soft_body_get_vertex_position, vertex)

    def vertex_velocity(self, vertex):
        return self._vertex_vec(lib.hearth_soft_body_get_vertex_velocity, vertex)

    def _float(self, fn):
        out = ctypes.c_float()
        fn(self._w, self._id, byref(out))
        return out.value

    @property
    def center(self):
        out = _ffi.HearthVec3()
        lib.hearth_soft_body_get_center(self._w, self._id, byref(out))
        return from_vec3(out)

    @property
    def mass(self):
        return self._float(lib.hearth_soft_body_get_mass)

    @property
    def volume(self):
        return self._float(lib.hearth_soft_body_get_volume)

    @property
    def rest_volume(self):
        return self._float(lib.hearth_soft_body_get_rest_volume)

    @property
    def pressure(self):
        """Gas pressure n·R·T (J); settable."""
        return self._float(lib.hearth_soft_body_get_pressure)

    @pressure.setter
    def pressure(self, value):
        lib.hearth_soft_body_set_pressure(self._w, self._id, value)

    @property
    def user_data(self):
        out = ctypes.c_uint64()
        lib.hearth_soft_body_get_user_data(self._w, self._id, byref(out))
        return out.value

    @property
    def settings(self):
        """SoftBodySettings: what the soft body runs with now, those given at creation or set
        since (`hearth_soft_body_get_settings`). Assigning a SoftBodySettings replaces them all
        (`soft.settings = soft.settings._replace(damping=1.0)`), as `set_settings`."""
        out = _ffi.HearthSoftBodySettings()
        lib.hearth_soft_body_get_settings(self._w, self._id, byref(out))
        values = {name: getattr(out, name) for name in SoftBodySettings._fields}
        for flag in _SOFT_FLAGS:
            values[flag] = bool(values[flag])
        return SoftBodySettings(**values)

    @settings.setter
    def settings(self, value):
        self.set_settings(value)

    def set_settings(self, settings=None, **fields):
        """Replaces the settings (`hearth_soft_body_set_settings`); they take effect at the next
        step. `settings` (a SoftBodySettings or a HearthSoftBodySettings; the current settings
        when None) with the keyword `fields` applied on top, e.g.
        `soft.set_settings(damping=1.0, substeps=30)`. The library checks every field as at
        creation; on error (InvalidArgument: NaN, negative, out of range) nothing changes."""
        if settings is None:
            settings = self.settings
        if isinstance(settings, _ffi.HearthSoftBodySettings):
            struct = _ffi.HearthSoftBodySettings.from_buffer_copy(settings)
        elif isinstance(settings, SoftBodySettings):
            struct = fill(_ffi.HearthSoftBodySettings(), settings._asdict())
        else:
            raise TypeError(f"settings must be a SoftBodySettings, not {type(settings).__name__}")
        fill(struct, fields)
        lib.hearth_soft_body_set_settings(self._w, self._id, byref(struct))

    def set_compliance(self, edge, bend, volume):
        """Sets the three compliances (the inverse of stiffness, >= 0) in one call
        (`hearth_soft_body_set_compliance`): `edge` of the stretch springs (m/N, 0 inextensible),
        `bend` of the bending springs (m/N, `math.inf` disables bending), `volume` of the volume
        constraint (0 incompressible). Takes effect at the next step; nothing changes on error."""
        lib.hearth_soft_body_set_compliance(self._w, self._id, edge, bend, volume)

    def pin_vertex(self, vertex, body=None):
        """Pins a vertex where it is now: to the world (body None) or to a body."""
        lib.hearth_soft_body_pin_vertex(self._w, self._id, vertex, _body_id(body))

    def unpin_vertex(self, vertex):
        lib.hearth_soft_body_unpin_vertex(self._w, self._id, vertex)

    def is_vertex_pinned(self, vertex):
        out = ctypes.c_bool()
        lib.hearth_soft_body_is_vertex_pinned(self._w, self._id, vertex, byref(out))
        return out.value

    def apply_impulse(self, vertex, impulse):
        lib.hearth_soft_body_apply_impulse(self._w, self._id, vertex, to_vec3(impulse))

    def apply_impulse_all(self, impulse):
        lib.hearth_soft_body_apply_impulse_all(self._w, self._id, to_vec3(impulse))

    def destroy(self):
        lib.hearth_soft_body_destroy(self._w, self._id)


# ------------------------------------------------------------------------------ id helpers


def _body_id(body):
    """The C id of a Body; None is the null id (the world)."""
    return _ffi.HearthBodyId() if body is None else body._id


def _particle_id(particle):
    return _ffi.HearthParticleId() if particle is None else particle._id


def _ids(handles, id_type):
    if isinstance(handles, ctypes.Array) and handles._type_ is id_type:
        return handles
    return (id_type * len(handles))(*(h._id for h in handles))


def body_ids(bodies):
    """A ctypes array of the bodies' C ids, to build once and pass to `World.get_transforms`
    every frame (an array passed back in is used as is)."""
    return _ids(bodies, _ffi.HearthBodyId)


def particle_ids(particles):
    """A ctypes array of the particles' C ids (see `body_ids`)."""
    return _ids(particles, _ffi.HearthParticleId)


class Hull(_Handle):
    """A convex hull shared by shapes (`HearthHullId`). Create with `World.create_hull`; use with
    `Body.add_hull`. `destroy` is refused (InvalidArgument) while shapes use it."""

    __slots__ = ()
    _ID_TYPE = _ffi.HearthHullId

    @property
    def vertex_count(self):
        out = ctypes.c_uint32()
        lib.hearth_hull_get_vertex_count(self._w, self._id, byref(out))
        return out.value

    def destroy(self):
        lib.hearth_hull_destroy(self._w, self._id)


class Mesh(_Handle):
    """A triangle mesh shared by shapes (`HearthMeshId`). Create with `World.create_mesh`; use with
    `Body.add_mesh` on static or kinematic bodies."""

    __slots__ = ()
    _ID_TYPE = _ffi.HearthMeshId

    def _count(self, fn):
        out = ctypes.c_uint32()
        fn(self._w, self._id, byref(out))
        return out.value

    @property
    def triangle_count(self):
        """Triangles kept (those given minus the degenerate ones)."""
        return self._count(lib.hearth_mesh_get_triangle_count)

    @property
    def degenerate_count(self):
        """Triangles skipped at creation as degenerate."""
        return self._count(lib.hearth_mesh_get_degenerate_count)

    def destroy(self):
        lib.hearth_mesh_destroy(self._w, self._id)


class Heightfield(_Handle):
    """A heightfield shared by shapes (`HearthHeightfieldId`). Create with
    `World.create_heightfield`; use with `Body.add_heightfield` on static or kinematic bodies."""

    __slots__ = ()
    _ID_TYPE = _ffi.HearthHeightfieldId

    def destroy(self):
        lib.hearth_heightfield_destroy(self._w, self._id)
