"""Python callables as user force and contact generators.

A callable is wrapped in a ctypes trampoline (`HearthForceCallback` /
`HearthContactCallback`) that the world keeps alive while the generator exists. The
trampoline never lets a Python exception reach C (the callbacks return void, so C has no
failure value to receive): it catches it, hands it to the world, and `World.step` re-raises
it once `hearth_world_step` has returned. The step itself completes, and the other
callbacks of that step still run; only the first exception of a step is re-raised.
"""

import ctypes
from collections import namedtuple
from ctypes import byref

from . import _ffi
from ._convert import to_vec3
from ._lib import lib
from .handles import Body, Generator, Particle, _body_id, _particle_id


class GeneratorContext:
    """What a generator callback is told (`HearthGeneratorContext`): the generator, the step's
    dt and the live bodies and particles attached to it, in attachment order.

    The C arrays are copied (one memmove each) into `body_ids` and `particle_ids`, ctypes
    arrays that bulk reads such as `World.get_particle_positions` take as they are; `bodies`
    and `particles` make handles of them on first use.
    """

    __slots__ = ("world", "generator", "dt", "body_ids", "particle_ids", "_bodies", "_particles")

    def __init__(self, world, context):
        self.world = world
        self.generator = Generator(world, context.generator)
        self.dt = context.dt
        self.body_ids = _copy(context.bodies, context.body_count, _ffi.HearthBodyId)
        self.particle_ids = _copy(context.particles, context.particle_count, _ffi.HearthParticleId)
        self._bodies = self._particles = None

    @property
    def bodies(self):
        if self._bodies is None:
            self._bodies = [Body(self.world, i) for i in self.body_ids]
        return self._bodies

    @property
    def particles(self):
        if self._particles is None:
            self._particles = [Particle(self.world, i) for i in self.particle_ids]
        return self._particles

    def __repr__(self):
        return (
            f"GeneratorContext(generator={self.generator!r}, dt={self.dt}, "
            f"bodies={len(self.body_ids)}, particles={len(self.particle_ids)})"
        )


def _copy(pointer, count, ctype):
    """A ctypes array holding a copy of `count` items at a C pointer valid only for now."""
    array = (ctype * count)()
    if count:
        ctypes.memmove(array, pointer, count * ctypes.sizeof(ctype))
    return array


def _side(target):
    """(body id, particle id) of one side of a generated contact: a Body, a Particle, or None for
    the world."""
    if isinstance(target, Particle):
        return _body_id(None), _particle_id(target)
    return _body_id(target), _particle_id(None)


class ContactSink:
    """Where a contact generator callback writes its contacts (`HearthContactSink`). Valid only
    during the callback; afterwards every call fails in the library (NULL sink)."""

    __slots__ = ("_ptr",)

    def __init__(self, ptr):
        self._ptr = ptr

    def add(self, a, b, point, normal, penetration, restitution=0.0, friction=0.0):
        """`hearth_contact_sink_add`: a contact between `a` and `b` (each a Body, a Particle, or
        None for the world) at world `point`, `normal` from A to B, `penetration` (m, > 0
        overlapping). Restitution and friction start at zero like a zero-initialised C struct."""
        body_a, particle_a = _side(a)
        body_b, particle_b = _side(b)
        contact = _ffi.HearthGeneratedContact(
            body_a, particle_a, body_b, particle_b, to_vec3(point), to_vec3(normal), penetration, restitution, friction
        )
        lib.hearth_contact_sink_add(self._ptr, byref(contact))

    def _counts(self):
        count, capacity = ctypes.c_uint32(), ctypes.c_uint32()
        lib.hearth_contact_sink_get_count(self._ptr, byref(count), byref(capacity))
        return count.value, capacity.value

    @property
    def count(self):
        """Contacts added so far in this call."""
        return self._counts()[0]

    @property
    def capacity(self):
        """Most contacts this call may add."""
        return self._counts()[1]


def force_trampoline(world, callback):
    """A HearthForceCallback that runs `callback(world, context)`."""

    def trampoline(_user_data, _world, context):
        try:
            callback(world, GeneratorContext(world, context.contents))
        except BaseException as e:  # noqa: BLE001 - nothing may cross into C
            world._callback_failed(e)

    return _ffi.HearthForceCallback(trampoline)


def contact_trampoline(world, callback):
    """A HearthContactCallback that runs `callback(world, context, sink)`."""

    def trampoline(_user_data, _world, context, sink_ptr):
        sink = ContactSink(sink_ptr)
        try:
            callback(world, GeneratorContext(world, context.contents), sink)
        except BaseException as e:  # noqa: BLE001 - nothing may cross into C
            world._callback_failed(e)
        finally:
            sink._ptr = None  # a sink kept past its callback must not reach a dangling pointer

    return _ffi.HearthContactCallback(trampoline)


def record_write_trampoline(world, write):
    """A HearthRecordWriteFn that passes each piece of a recording to `write(data)` as `bytes`.
    An exception stops the recording (the callback returns 1): it is re-raised by the step
    it happened in, and the next step (or `stop_recording`) raises Io."""

    def trampoline(_user_data, data, length):
        try:
            write(ctypes.string_at(data, length))
            return 0
        except BaseException as e:  # noqa: BLE001 - nothing may cross into C
            world._callback_failed(e)
            return 1

    return _ffi.HearthRecordWriteFn(trampoline)


PreSolveContact = namedtuple("PreSolveContact", "shape_a shape_b body_a body_b normal points")
PreSolveContact.__doc__ = """A touching contact as the pre-solve callback sees it: ids, the normal from A to B, and
`points`, a list of (point, separation) (negative separation: overlap)."""


def pair_filter_trampoline(world, callback):
    """A HearthPairFilterCallback that runs `callback(world, shape_a, shape_b) -> bool`. An
    exception keeps the pair (returns 1) and is re-raised by the step."""
    from .handles import Shape

    def trampoline(_user_data, _world, a, b):
        try:
            return 1 if callback(world, Shape(world, a), Shape(world, b)) else 0
        except BaseException as e:  # noqa: BLE001 - nothing may cross into C
            world._callback_failed(e)
            return 1

    return _ffi.HearthPairFilterCallback(trampoline)


def pre_solve_trampoline(world, callback):
    """A HearthPreSolveCallback that runs `callback(world, contact) -> bool` with `contact` a
    PreSolveContact (copies of the shapes, bodies, normal and points). An exception keeps the
    contact and is re-raised by the step."""

    def trampoline(_user_data, _world, contact):
        try:
            c = contact.contents
            copy = PreSolveContact(
                c.shape_a, c.shape_b, c.body_a, c.body_b, c.normal,
                [(c.points[i].point, c.points[i].separation) for i in range(c.point_count)],
            )
            return 1 if callback(world, copy) else 0
        except BaseException as e:  # noqa: BLE001 - nothing may cross into C
            world._callback_failed(e)
            return 1

    return _ffi.HearthPreSolveCallback(trampoline)
def draw(world, drawer, flags):
    """`hearth_world_draw` through the methods of `drawer` (any of `segment(a, b, color)`,
    `polygon(vertices, color)`, `sphere(center, radius, color)`, `capsule(a, b, radius,
    color)`, `transform(position, rotation)`, `point(p, size, color)`; points as Vec3
    tuples, colours as 0xRRGGBBAA). A missing method is a NULL callback. The first exception
    a method raises is re-raised after the draw (later primitives are skipped)."""
    from ._convert import from_quat, from_vec3

    failure = []
    d = lib.hearth_debug_draw_default()

    def guarded(fn):
        def call(*args):
            if failure:
                return
            try:
                fn(*args)
            except BaseException as e:  # noqa: BLE001 - nothing may cross into C
                failure.append(e)

        return call

    keep = []

    def bind(field, method, make):
        fn = getattr(drawer, method, None)
        if fn is not None:
            cb = make(fn)
            keep.append(cb)
            setattr(d, field, cb)

    bind("draw_segment", "segment", lambda f: _ffi.HearthDrawSegment(
        guarded(lambda _u, a, b, c: f(from_vec3(a.contents), from_vec3(b.contents), c))))
    bind("draw_polygon", "polygon", lambda f: _ffi.HearthDrawPolygon(
        guarded(lambda _u, v, n, c: f([from_vec3(v[i]) for i in range(n)], c))))
    bind("draw_sphere", "sphere", lambda f: _ffi.HearthDrawSphere(
        guarded(lambda _u, p, r, c: f(from_vec3(p.contents), r, c))))
    bind("draw_capsule", "capsule", lambda f: _ffi.HearthDrawCapsule(
        guarded(lambda _u, a, b, r, c: f(from_vec3(a.contents), from_vec3(b.contents), r, c))))
    bind("draw_transform", "transform", lambda f: _ffi.HearthDrawTransform(
        guarded(lambda _u, t: f(from_vec3(t.contents.position), from_quat(t.contents.rotation)))))
    bind("draw_point", "point", lambda f: _ffi.HearthDrawPoint(
        guarded(lambda _u, p, s, c: f(from_vec3(p.contents), s, c))))
    for name, value in flags.items():
        setattr(d, "draw_" + name, int(value))
    lib.hearth_world_draw(world._ptr, byref(d))
    if failure:
        raise failure[0]
