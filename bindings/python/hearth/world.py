"""The World: owner of everything in a simulation (`HearthWorld *`)."""

import ctypes
import os
from collections import namedtuple
from ctypes import POINTER, byref

from . import _ffi
from ._convert import IDENTITY, c_view, check_format, fill, from_vec3, new_buffer, to_quat, to_record, to_transform, to_vec3
from ._lib import lib
from .callbacks import (
    contact_trampoline,
    force_trampoline,
    pair_filter_trampoline,
    pre_solve_trampoline,
    record_write_trampoline,
)
from .errors import HearthError
from .handles import (
    Body,
    BodyType,
    Generator,
    Heightfield,
    Hull,
    Joint,
    Mesh,
    Particle,
    Shape,
    SoftBody,
    _body_id,
    _particle_id,
    body_ids,
    particle_ids,
)

WorldCounters = namedtuple("WorldCounters", [name for name, _ in _ffi.HearthWorldCounters._fields_])
ExpiredParticle = namedtuple("ExpiredParticle", "particle position velocity user_data")
ParticleData = namedtuple("ParticleData", "count ids positions velocities")

# hearth_particle_emit_burst takes at most this many particles per burst (HearthBurstDef.count);
# the binding sizes its id buffer to the smaller of this and the def's count, so that an
# absurd count is refused by the library instead of allocating gigabytes first.
_MAX_BURST = 1 << 20


def link_end(target=None, point=(0.0, 0.0, 0.0)):
    """A `HearthLinkEnd`: a point on a Body (body frame), a Particle, or a world point (target
    None)."""
    end = _ffi.HearthLinkEnd()
    if isinstance(target, Particle):
        end.particle = target._id
    elif target is not None:
        end.body = target._id
    end.point = to_vec3(point)
    return end


def _to_link_end(value):
    """A link end from a HearthLinkEnd, a Body, a Particle, a (Body, point) pair or a world point."""
    if isinstance(value, _ffi.HearthLinkEnd):
        return value
    if isinstance(value, (Body, Particle)):
        return link_end(value)
    if len(value) == 2 and isinstance(value[0], Body):
        return link_end(value[0], value[1])
    return link_end(None, value)


# Field converters for defs: ids from handles (None is the null id), link ends from the forms above.
_CONVERT = {
    _ffi.HearthBodyId: _body_id,
    _ffi.HearthParticleId: _particle_id,
    _ffi.HearthLinkEnd: _to_link_end,
}


def _def(default_fn, fields, flatten=()):
    """A def fresh from its `*_def_default()` with `fields` applied."""
    return fill(default_fn(), fields, flatten=flatten, convert=_CONVERT)


class World:
    """A Hearth world. Keyword arguments are fields of `HearthWorldDef` (gravity, substeps,
    enable_sleep, worker_count, ...); the rest keep the values of `hearth_world_def_default()`.
    `worker_count=n` steps on n threads the world starts itself (results are bit for bit those
    of one thread; see `state_hash`).

    Use it as a context manager or call `close()`; a world is used by one thread at a time.
    """

    def __init__(self, **settings):
        self._ptr = None
        self._callbacks = {}  # (index, generation) of a user generator -> its ctypes trampoline
        self._record_write = None  # the recording's write trampoline, kept alive while recording
        self._pair_filter = None  # the pair-filter trampoline, kept alive while set
        self._pre_solve = None  # the pre-solve trampoline, kept alive while set
        self._stepping = False
        self._callback_error = None
        wd = _def(lib.hearth_world_def_default, settings)
        ptr = POINTER(_ffi.HearthWorld)()
        lib.hearth_world_create(byref(wd), byref(ptr))
        self._ptr = ptr

    # -- lifetime
    def close(self):
        """Destroys the world and everything in it; idempotent. Later calls through the world or
        its handles fail with NullPointer."""
        if self._stepping:
            raise RuntimeError("a world cannot be closed from inside one of its own step callbacks")
        if self._ptr is not None:
            lib.hearth_world_destroy(self._ptr)
            self._ptr = None
        self._callbacks.clear()
        self._record_write = None

    @property
    def closed(self):
        return self._ptr is None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:  # noqa: BLE001 - interpreter shutdown may have torn down modules
            pass

    def __repr__(self):
        return f"<hearth.World {'closed' if self.closed else hex(ctypes.addressof(self._ptr.contents))}>"

    # -- stepping
    def step(self, dt):
        """Advances the world by `dt` seconds. An exception raised by a Python generator callback
        during the step is re-raised here, after the step has completed."""
        if self._stepping:  # from a callback: the library refuses it (WorldLocked)
            lib.hearth_world_step(self._ptr, dt)
            return
        self._stepping = True
        failure = None
        try:
            lib.hearth_world_step(self._ptr, dt)
        except HearthError as e:
            failure = e
        finally:
            self._stepping = False
            error, self._callback_error = self._callback_error, None
        if error is not None:
            if failure is not None and hasattr(error, "add_note"):  # Python 3.11+
                error.add_note(f"hearth_world_step also failed: {failure}")
            raise error
        if failure is not None:
            raise failure

    # -- recording (for the browser viewer, viewer/index.html)
    def record(self, path=None, write=None, contacts=False):
        """Starts recording the world: into the file at `path` (`hearth_world_record_start_file`),
        or through `write(data: bytes)` (`hearth_world_record_start_callback`), called now with
        the recording's start and after every step with that step. `contacts` records every
        touching contact manifold too. Stops with `stop_recording()` or `close()`. A failed write
        stops the recording and the next `step()` raises Io (the exception `write` raised
        is re-raised by the step it happened in)."""
        if (path is None) == (write is None):
            raise ValueError("give either a path or a write callable")
        rd = _def(lib.hearth_record_def_default, {"record_contacts": int(bool(contacts))})
        if path is not None:
            lib.hearth_world_record_start_file(self._ptr, os.fsencode(path), byref(rd))
            return
        trampoline = record_write_trampoline(self, write)
        rd.write = trampoline
        try:
            lib.hearth_world_record_start_callback(self._ptr, byref(rd))
        except HearthError as failure:
            error, self._callback_error = self._callback_error, None
            raise failure from error
        self._record_write = trampoline

    def stop_recording(self):
        """`hearth_world_record_stop`: ends the recording (Io if a write had failed)."""
        try:
            lib.hearth_world_record_stop(self._ptr)
        finally:
            if not self._stepping:
                self._record_write = None

    def draw(self, drawer, shapes=True, aabbs=False, contacts=False, joints=False, centers_of_mass=False):
        """`hearth_world_draw`: describes the world to `drawer` (see `hearth.callbacks.draw`) as the
        flags ask. Colours are 0xRRGGBBAA (`HearthDebugDraw` in include/hearth.h lists them)."""
        from .callbacks import draw

        flags = dict(shapes=shapes, aabbs=aabbs, contacts=contacts, joints=joints, centers_of_mass=centers_of_mass)
        draw(self, drawer, flags)
    # -- snapshots (rollback, replays)
    def snapshot_size(self):
        """`hearth_world_snapshot_size`: bytes `save_snapshot()` returns now."""
        out = ctypes.c_size_t()
        lib.hearth_world_snapshot_size(self._ptr, byref(out))
        return out.value

    def save_snapshot(self):
        """`hearth_world_snapshot_save`: everything that affects the world's future, as bytes
        (user generator callbacks and a running recording excepted)."""
        size = self.snapshot_size()
        buf = (ctypes.c_uint8 * max(size, 1))()
        written = ctypes.c_size_t()
        lib.hearth_world_snapshot_save(self._ptr, buf, size, byref(written))
        return bytes(buf[: written.value])

    def restore_snapshot(self, data):
        """`hearth_world_snapshot_restore` from bytes of `save_snapshot()` (of this world or
        another). Raises InvalidArgument (nothing changed) for a truncated, corrupted or
        other-version snapshot. Restored into the world it came from, the Python callables of
        user generators keep running; restored elsewhere, set them again with
        `set_force_callback` / `set_contact_callback` (`generators_missing_callbacks()` lists
        which)."""
        data = bytes(data)
        buf = (ctypes.c_uint8 * max(len(data), 1)).from_buffer_copy(data.ljust(1, b"\0"))
        lib.hearth_world_snapshot_restore(self._ptr, buf, len(data))

    def generators_missing_callbacks(self):
        """`hearth_world_get_user_generators_missing_callback`: user generators restored
        without a callback (skipped by `step()` until set)."""
        count = ctypes.c_size_t()
        lib.hearth_world_get_user_generators_missing_callback(self._ptr, None, 0, byref(count))
        ids = (_ffi.HearthGeneratorId * max(count.value, 1))()
        lib.hearth_world_get_user_generators_missing_callback(self._ptr, ids, count.value, byref(count))
        return [Generator(self, ids[i]) for i in range(count.value)]

    def set_force_callback(self, generator, callback):
        """`hearth_generator_set_user_force_callback`: `callback(world, context)` for a user
        force generator (after a restore into another world, or to replace it)."""
        trampoline = force_trampoline(self, callback)
        gd = _def(lib.hearth_user_force_generator_def_default, {})
        gd.callback = trampoline
        lib.hearth_generator_set_user_force_callback(self._ptr, generator._id, byref(gd))
        self._callbacks[(generator._id.index, generator._id.generation)] = trampoline

    def set_contact_callback(self, generator, callback, **fields):
        """`hearth_generator_set_user_contact_callback`: `callback(world, context, sink)` for a
        user contact generator; keywords as for `create_contact_generator` (`capacity`)."""
        trampoline = contact_trampoline(self, callback)
        gd = _def(lib.hearth_user_contact_generator_def_default, fields)
        gd.callback = trampoline
        lib.hearth_generator_set_user_contact_callback(self._ptr, generator._id, byref(gd))
        self._callbacks[(generator._id.index, generator._id.generation)] = trampoline

    def _callback_failed(self, error):
        if self._callback_error is None:
            self._callback_error = error

    def _release_callback(self, generator_id):
        self._callbacks.pop((generator_id.index, generator_id.generation), None)

    # -- settings and counters
    @property
    def gravity(self):
        out = _ffi.HearthVec3()
        lib.hearth_world_get_gravity(self._ptr, byref(out))
        return from_vec3(out)

    @gravity.setter
    def gravity(self, value):
        lib.hearth_world_set_gravity(self._ptr, to_vec3(value))

    @property
    def counters(self):
        out = _ffi.HearthWorldCounters()
        lib.hearth_world_get_counters(self._ptr, byref(out))
        return to_record(out, WorldCounters)

    @property
    def state_hash(self):
        """`hearth_world_get_hash`: a 64-bit hash of every body's, particle's and soft-body
        vertex's motion state, equal for equal runs at any worker count."""
        out = ctypes.c_uint64()
        lib.hearth_world_get_hash(self._ptr, byref(out))
        return out.value

    def rebuild_broadphase(self):
        """`hearth_world_rebuild_broadphase`: rebuilds the broad-phase tree (after loading a
        level, so that queries and pair searches test fewer boxes); results of queries and
        ids are unchanged."""
        lib.hearth_world_rebuild_broadphase(self._ptr)

    def set_particle_iterations(self, velocity_iterations, position_iterations):
        lib.hearth_world_set_particle_iterations(self._ptr, velocity_iterations, position_iterations)

    # -- bodies
    def create_body(self, type=None, **fields):
        """`hearth_body_create`. `type`: a BodyType or its name ("dynamic"); other keywords are
        fields of HearthBodyDef, plus `position` and `rotation` for the transform's parts."""
        if isinstance(type, str):
            type = BodyType[type.upper()]
        if type is not None:
            fields["type"] = type
        bd = _def(lib.hearth_body_def_default, fields, flatten=("transform",))
        out = _ffi.HearthBodyId()
        lib.hearth_body_create(self._ptr, byref(bd), byref(out))
        return Body(self, out)

    def get_transforms(self, bodies, out=None):
        """`hearth_world_get_transforms`: the transforms of `bodies` (Body handles, or an array from
        `hearth.body_ids` to reuse every frame) in one call, into `out`: a writable float32
        buffer of 7 numbers per body (position x, y, z, rotation x, y, z, w), or a new
        array('f') when None. Returns `out`."""
        ids = body_ids(bodies)
        count = len(ids)
        if out is None:
            out = new_buffer("f", 7 * count)
        view = c_view(out, _ffi.HearthTransform, "f")
        if len(view) < count:
            raise ValueError(f"out holds {len(view)} transforms (7 float32 each) but {count} bodies were given")
        lib.hearth_world_get_transforms(self._ptr, ids, count, view)
        return out

    # -- joints
    def _joint(self, default_fn, create_fn, body_a, body_b, fields):
        fields = dict(fields, body_a=body_a, body_b=body_b)
        jd = _def(default_fn, fields, flatten=("base",))
        out = _ffi.HearthJointId()
        create_fn(self._ptr, byref(jd), byref(out))
        return Joint(self, out)

    def create_ball_joint(self, body_a, body_b=None, **fields):
        """`hearth_joint_create_ball`; body_b None joins body_a to the world. Keywords: fields of
        HearthBallJointDef and of its base (frame_a, frame_b, collide_connected, ...)."""
        return self._joint(lib.hearth_ball_joint_def_default, lib.hearth_joint_create_ball, body_a, body_b, fields)

    def create_hinge_joint(self, body_a, body_b=None, **fields):
        """`hearth_joint_create_hinge` (fields of HearthHingeJointDef and its base)."""
        return self._joint(lib.hearth_hinge_joint_def_default, lib.hearth_joint_create_hinge, body_a, body_b, fields)

    def create_fixed_joint(self, body_a, body_b=None, **fields):
        """`hearth_joint_create_fixed` (fields of HearthFixedJointDef and its base)."""
        return self._joint(lib.hearth_fixed_joint_def_default, lib.hearth_joint_create_fixed, body_a, body_b, fields)

    def create_distance_joint(self, body_a, body_b=None, **fields):
        """`hearth_joint_create_distance` (fields of HearthDistanceJointDef and its base)."""
        return self._joint(
            lib.hearth_distance_joint_def_default, lib.hearth_joint_create_distance, body_a, body_b, fields
        )

    def create_slider_joint(self, body_a, body_b=None, **fields):
        """`hearth_joint_create_slider` (fields of HearthSliderJointDef and its base)."""
        return self._joint(lib.hearth_slider_joint_def_default, lib.hearth_joint_create_slider, body_a, body_b, fields)

    # -- events and step callbacks
    @staticmethod
    def _array(pointer, count):
        # Copies: the C arrays live only until the next step.
        ctype = pointer._type_
        return [ctype.from_buffer_copy(pointer[i]) for i in range(count)]

    def contact_events(self):
        """`hearth_world_get_contact_events`: (begin, end, hit) of the last step, copies of the
        C structs (HearthContactEvent, HearthContactHitEvent)."""
        ev = _ffi.HearthContactEvents()
        lib.hearth_world_get_contact_events(self._ptr, byref(ev))
        return (
            self._array(ev.begin, ev.begin_count),
            self._array(ev.end, ev.end_count),
            self._array(ev.hit, ev.hit_count),
        )

    def sensor_events(self):
        """`hearth_world_get_sensor_events`: (begin, end) of the last step (HearthSensorEvent)."""
        ev = _ffi.HearthSensorEvents()
        lib.hearth_world_get_sensor_events(self._ptr, byref(ev))
        return self._array(ev.begin, ev.begin_count), self._array(ev.end, ev.end_count)

    def body_events(self):
        """`hearth_world_get_body_events`: the move events of the last step
        (HearthBodyMoveEvent)."""
        ev = _ffi.HearthBodyEvents()
        lib.hearth_world_get_body_events(self._ptr, byref(ev))
        return self._array(ev.moves, ev.move_count)

    def set_pair_filter(self, callback):
        """`hearth_world_set_pair_filter_callback` with `callback(world, shape_a, shape_b) -> bool`
        (False: the pair makes no contact until proposed again), or None to clear it."""
        trampoline = pair_filter_trampoline(self, callback) if callback is not None else None
        lib.hearth_world_set_pair_filter_callback(
            self._ptr, trampoline if trampoline is not None else _ffi.HearthPairFilterCallback(), None
        )
        self._pair_filter = trampoline

    def set_pre_solve(self, callback):
        """`hearth_world_set_pre_solve_callback` with `callback(world, contact) -> bool` (False:
        the contact does not push in this step; `contact` a HearthPreSolveContact), or None."""
        trampoline = pre_solve_trampoline(self, callback) if callback is not None else None
        lib.hearth_world_set_pre_solve_callback(
            self._ptr, trampoline if trampoline is not None else _ffi.HearthPreSolveCallback(), None
        )
        self._pre_solve = trampoline

    @property
    def broken_joints(self):
        """`hearth_world_get_broken_joints`: the joints that broke during the last step."""
        count = ctypes.c_size_t()
        lib.hearth_world_get_broken_joints(self._ptr, None, 0, byref(count))
        ids = (_ffi.HearthJointId * count.value)()
        if count.value:
            lib.hearth_world_get_broken_joints(self._ptr, ids, len(ids), byref(count))
        return [Joint(self, j) for j in ids[: count.value]]

    # -- generators
    def _generator(self, default_fn, create_fn, fields):
        gd = _def(default_fn, fields)
        out = _ffi.HearthGeneratorId()
        create_fn(self._ptr, byref(gd), byref(out))
        return Generator(self, out)

    def create_gravity_generator(self, **fields):
        """`hearth_generator_create_gravity` (fields of HearthGravityGeneratorDef); attach objects."""
        return self._generator(lib.hearth_gravity_generator_def_default, lib.hearth_generator_create_gravity, fields)

    def create_drag_generator(self, **fields):
        """`hearth_generator_create_drag` (k1, k2)."""
        return self._generator(lib.hearth_drag_generator_def_default, lib.hearth_generator_create_drag, fields)

    def create_spring_generator(self, **fields):
        """`hearth_generator_create_spring`. `other`: a Body, a Particle, a (Body, local point)
        pair, a world point or a `link_end(...)`."""
        return self._generator(lib.hearth_spring_generator_def_default, lib.hearth_generator_create_spring, fields)

    def create_bungee_generator(self, **fields):
        """`hearth_generator_create_bungee` (a spring that only pulls; HearthSpringGeneratorDef)."""
        return self._generator(lib.hearth_spring_generator_def_default, lib.hearth_generator_create_bungee, fields)

    def create_stiff_spring_generator(self, **fields):
        """`hearth_generator_create_stiff_spring` (anchor, local_point, stiffness, damping)."""
        return self._generator(
            lib.hearth_stiff_spring_generator_def_default, lib.hearth_generator_create_stiff_spring, fields
        )

    def create_buoyancy_generator(self, **fields):
        """`hearth_generator_create_buoyancy` (fields of HearthBuoyancyGeneratorDef)."""
        return self._generator(
            lib.hearth_buoyancy_generator_def_default, lib.hearth_generator_create_buoyancy, fields
        )

    def create_explosion_generator(self, **fields):
        """`hearth_generator_create_explosion` (fields of HearthExplosionGeneratorDef)."""
        return self._generator(
            lib.hearth_explosion_generator_def_default, lib.hearth_generator_create_explosion, fields
        )

    def create_rod_generator(self, **fields):
        """`hearth_generator_create_rod`: ends `a` and `b` (link ends as for springs), `length`."""
        return self._generator(lib.hearth_rod_generator_def_default, lib.hearth_generator_create_rod, fields)

    def create_cable_generator(self, **fields):
        """`hearth_generator_create_cable`: ends `a` and `b`, `max_length`, `restitution`."""
        return self._generator(lib.hearth_cable_generator_def_default, lib.hearth_generator_create_cable, fields)

    def create_force_generator(self, callback):
        """`hearth_generator_create_user_force` with a Python callable `callback(world, context)`,
        run once per step; it may read anything and apply forces and torques. Attach the
        bodies and particles it should be told about."""
        trampoline = force_trampoline(self, callback)
        gd = _def(lib.hearth_user_force_generator_def_default, {})
        gd.callback = trampoline
        out = _ffi.HearthGeneratorId()
        lib.hearth_generator_create_user_force(self._ptr, byref(gd), byref(out))
        self._callbacks[(out.index, out.generation)] = trampoline
        return Generator(self, out)

    def create_contact_generator(self, callback, **fields):
        """`hearth_generator_create_user_contact` with a Python callable
        `callback(world, context, sink)` that adds contacts with `sink.add(...)`. Keywords:
        fields of HearthUserContactGeneratorDef (`capacity`)."""
        trampoline = contact_trampoline(self, callback)
        gd = _def(lib.hearth_user_contact_generator_def_default, fields)
        gd.callback = trampoline
        out = _ffi.HearthGeneratorId()
        lib.hearth_generator_create_user_contact(self._ptr, byref(gd), byref(out))
        self._callbacks[(out.index, out.generation)] = trampoline
        return Generator(self, out)

    # -- particles
    def create_particle(self, **fields):
        """`hearth_particle_create` (fields of HearthParticleDef)."""
        pd = _def(lib.hearth_particle_def_default, fields)
        out = _ffi.HearthParticleId()
        lib.hearth_particle_create(self._ptr, byref(pd), byref(out))
        return Particle(self, out)

    def emit_burst(self, **fields):
        """`hearth_particle_emit_burst` (fields of HearthBurstDef; `particle` takes a dict of
        HearthParticleDef fields). Returns the new particles."""
        bd = _def(lib.hearth_burst_def_default, fields)
        ids = (_ffi.HearthParticleId * min(bd.count, _MAX_BURST))()
        count = ctypes.c_size_t()
        lib.hearth_particle_emit_burst(self._ptr, byref(bd), ids, len(ids), byref(count))
        return [Particle(self, p) for p in ids[: count.value]]

    @property
    def particle_count(self):
        out = ctypes.c_size_t()
        lib.hearth_world_get_particle_count(self._ptr, byref(out))
        return out.value

    def get_particles(self, positions=True, velocities=False, ids=False):
        """`hearth_world_get_particles`: every live particle in one call. Each argument is True
        (a new array sized to the particle count), False (skip it) or a writable buffer:
        float32, 3 per particle, for positions and velocities; uint32, 2 per particle
        (index, generation; see `Particle.from_id`), for ids. The buffers given decide the
        capacity. Returns ParticleData(count, ids, positions, velocities)."""
        count_needed = None
        buffers, views = [], []
        for arg, ctype, typecode, per in (
            (ids, _ffi.HearthParticleId, "I", 2),
            (positions, _ffi.HearthVec3, "f", 3),
            (velocities, _ffi.HearthVec3, "f", 3),
        ):
            if arg is False or arg is None:
                buffers.append(None)
                views.append(None)
                continue
            if arg is True:
                if count_needed is None:
                    count_needed = self.particle_count
                arg = new_buffer(typecode, per * count_needed)
            buffers.append(arg)
            views.append(c_view(arg, ctype, typecode))
        capacity = min((len(v) for v in views if v is not None), default=0)
        count = ctypes.c_size_t()
        lib.hearth_world_get_particles(self._ptr, *views, capacity, byref(count))
        return ParticleData(count.value, *buffers)

    def get_particle_positions(self, particles, out=None):
        """`hearth_world_get_particle_positions`: positions of the given particles (handles or a
        `hearth.particle_ids` array) into `out` (float32, 3 each; new array('f') when None)."""
        ids = particle_ids(particles)
        count = len(ids)
        if out is None:
            out = new_buffer("f", 3 * count)
        view = c_view(out, _ffi.HearthVec3, "f")
        if len(view) < count:
            raise ValueError(f"out holds {len(view)} positions (3 float32 each) but {count} particles were given")
        lib.hearth_world_get_particle_positions(self._ptr, ids, count, view)
        return out

    @property
    def expired_particles(self):
        """`hearth_world_get_expired_particles`: the particles that expired in the last step, as
        ExpiredParticle(particle, position, velocity, user_data) (the particle ids are stale)."""
        array = POINTER(_ffi.HearthExpiredParticle)()
        count = ctypes.c_size_t()
        lib.hearth_world_get_expired_particles(self._ptr, byref(array), byref(count))
        return [
            ExpiredParticle(Particle(self, e.id), from_vec3(e.position), from_vec3(e.velocity), e.user_data)
            for e in (array[: count.value] if count.value else ())
        ]

    # -- soft bodies
    def _soft(self, create, fields, *args):
        sd = _def(lib.hearth_soft_body_def_default, fields, flatten=("transform",))
        out = _ffi.HearthSoftBodyId()
        create(self._ptr, byref(sd), *args, byref(out))
        return SoftBody(self, out)

    def create_soft_body_mesh(self, vertices, indices, masses=None, **fields):
        """`hearth_soft_body_create_mesh`: `vertices` (3-sequences, or a flat float32 buffer),
        `indices` (three per triangle, flat or as triples, or a uint32 buffer), optional
        per-vertex `masses`. Keywords: fields of HearthSoftBodyDef, plus `position`/`rotation`."""
        verts = _input_array(vertices, _ffi.HearthVec3, "f", 3)
        idx = _input_array(indices, ctypes.c_uint32, "I", 1)
        mass = None
        if masses is not None:
            mass = _input_array(masses, ctypes.c_float, "f", 1)
            if len(mass) != len(verts):  # the library reads one mass per vertex
                raise ValueError(f"{len(mass)} masses for {len(verts)} vertices")
        return self._soft(lib.hearth_soft_body_create_mesh, fields, verts, len(verts), idx, len(idx), mass)

    def create_soft_body_icosphere(self, radius, subdivisions, **fields):
        """`hearth_soft_body_create_icosphere`: a ball of `radius`, `subdivisions` 0..=6."""
        return self._soft(lib.hearth_soft_body_create_icosphere, fields, radius, subdivisions)

    def create_soft_body_box(self, half_extents, cells, **fields):
        """`hearth_soft_body_create_box`: half extents (m) and `cells` = (x, y, z) lattice cells."""
        cx, cy, cz = cells
        return self._soft(lib.hearth_soft_body_create_box, fields, to_vec3(half_extents), cx, cy, cz)

    def create_soft_body_cloth(self, width, height, columns, rows, **fields):
        """`hearth_soft_body_create_cloth`: `width × height` (m) in the XZ plane, `columns × rows`."""
        return self._soft(lib.hearth_soft_body_create_cloth, fields, width, height, columns, rows)

    @property
    def soft_body_count(self):
        out = ctypes.c_size_t()
        lib.hearth_world_get_soft_body_count(self._ptr, byref(out))
        return out.value

    # -- shared geometry (the arrays are copied)
    def create_hull(self, points, **fields):
        """`hearth_hull_create`: a convex hull of `points` (3-sequences or a flat float32 buffer).
        Keywords: fields of HearthHullDef (convex_radius, weld_tolerance)."""
        hd = _def(lib.hearth_hull_def_default, fields)
        pts = _input_array(points, _ffi.HearthVec3, "f", 3)
        out = _ffi.HearthHullId()
        lib.hearth_hull_create(self._ptr, byref(hd), pts, len(pts), byref(out))
        return Hull(self, out)

    def create_mesh(self, vertices, indices):
        """`hearth_mesh_create`: `vertices` (3-sequences or a flat float32 buffer) and `indices`
        (three per triangle, counter-clockwise seen from the front; flat, triples or uint32)."""
        verts = _input_array(vertices, _ffi.HearthVec3, "f", 3)
        idx = _input_array(indices, ctypes.c_uint32, "I", 1)
        out = _ffi.HearthMeshId()
        lib.hearth_mesh_create(self._ptr, verts, len(verts), idx, len(idx), byref(out))
        return Mesh(self, out)

    def create_heightfield(self, rows, columns, heights, holes=None):
        """`hearth_heightfield_create`: `rows × columns` row-major `heights` (float32 buffer or
        numbers); `holes` None or one 0/1 flag per cell, (rows − 1) × (columns − 1) of them."""
        h = _input_array(heights, ctypes.c_float, "f", 1)
        if len(h) != rows * columns:  # the library reads rows × columns heights
            raise ValueError(f"{len(h)} heights for {rows} × {columns} samples")
        flags = None
        if holes is not None:
            flags = (ctypes.c_uint8 * len(holes))(*[int(x) for x in holes])
            if rows >= 2 and columns >= 2 and len(flags) != (rows - 1) * (columns - 1):
                raise ValueError(f"{len(flags)} hole flags for {(rows - 1) * (columns - 1)} cells")
        out = _ffi.HearthHeightfieldId()
        lib.hearth_heightfield_create(self._ptr, rows, columns, h, flags, byref(out))
        return Heightfield(self, out)

    # -- queries
    def cast_ray_closest(self, origin, translation, filter=None):
        """`hearth_world_cast_ray_closest`: the nearest hit (a RayHit) of the ray from `origin`
        along `translation`, or None. `filter`: a `query_filter(...)` (default: the default)."""
        out = _ffi.HearthRayHit()
        lib.hearth_world_cast_ray_closest(self._ptr, to_vec3(origin), to_vec3(translation), byref(_filter(filter)), byref(out))
        return _hit(self, out)

    def cast_ray(self, origin, translation, callback, filter=None):
        """`hearth_world_cast_ray`: calls `callback(hit)` (a RayHit) for the hits, going on as it
        returns (Box2D's protocol: -1 ignore, 0 stop, a fraction clips, 1 continue). An exception
        in the callback stops the cast and is re-raised here."""
        failed = []

        def trampoline(_user_data, hit):
            try:
                return float(callback(_hit(self, hit.contents)))
            except BaseException as e:  # noqa: BLE001 - nothing may cross into C
                failed.append(e)
                return 0.0

        fn = _ffi.HearthRayCallback(trampoline)
        lib.hearth_world_cast_ray(self._ptr, to_vec3(origin), to_vec3(translation), byref(_filter(filter)), fn, None)
        if failed:
            raise failed[0]

    def cast_rays(self, rays, filter=None):
        """`hearth_world_cast_rays`: the nearest hit (RayHit or None) of each (origin,
        translation) pair of `rays`, in one call."""
        inputs = (_ffi.HearthRayInput * len(rays))(*[_ffi.HearthRayInput(to_vec3(o), to_vec3(t)) for o, t in rays])
        out = (_ffi.HearthRayHit * len(rays))()
        lib.hearth_world_cast_rays(self._ptr, inputs, len(rays), byref(_filter(filter)), out)
        return [_hit(self, h) for h in out]

    def cast_shape(self, shape, transform, translation, filter=None):
        """`hearth_world_cast_shape`: moves `shape` (from `query_sphere` and friends) placed at
        `transform` (a position, or (position, rotation)) along `translation`; the first hit
        (RayHit, fraction 0 when overlapping at the start) or None."""
        out = _ffi.HearthRayHit()
        xf = to_transform(transform)
        lib.hearth_world_cast_shape(self._ptr, byref(shape), byref(xf), to_vec3(translation), byref(_filter(filter)), byref(out))
        return _hit(self, out)

    def _overlap(self, call):
        count = ctypes.c_size_t()
        call(None, 0, byref(count))
        ids = (_ffi.HearthShapeId * count.value)()
        if count.value:
            call(ids, len(ids), byref(count))
        return [Shape(self, s) for s in ids[: count.value]]

    def overlap_shape(self, shape, transform, filter=None):
        """`hearth_world_overlap_shape`: the shapes that overlap or touch `shape` at `transform`."""
        xf, f = to_transform(transform), _filter(filter)
        return self._overlap(lambda ids, cap, n: lib.hearth_world_overlap_shape(self._ptr, byref(shape), byref(xf), byref(f), ids, cap, n))

    def overlap_aabb(self, lower, upper, filter=None):
        """`hearth_world_overlap_aabb`: the shapes whose bounds overlap the box `lower`..`upper`."""
        lo, hi, f = to_vec3(lower), to_vec3(upper), _filter(filter)
        return self._overlap(lambda ids, cap, n: lib.hearth_world_overlap_aabb(self._ptr, lo, hi, byref(f), ids, cap, n))

    def overlap_point(self, point, filter=None):
        """`hearth_world_overlap_point`: the solid shapes containing `point`."""
        p, f = to_vec3(point), _filter(filter)
        return self._overlap(lambda ids, cap, n: lib.hearth_world_overlap_point(self._ptr, p, byref(f), ids, cap, n))


def _input_array(values, ctype, typecode, per):
    """A ctypes array of `ctype` copied from a buffer (float32/uint32 items or bytes) or from a
    sequence of numbers or of `per`-sequences."""
    try:
        mv = memoryview(values)
    except TypeError:
        flat = []
        for v in values:
            if isinstance(v, (int, float)):
                flat.append(v)
            else:
                flat.extend(v)
        if len(flat) % per:
            raise ValueError(f"{len(flat)} numbers do not make whole groups of {per}") from None
        data = ctypes.c_float * len(flat) if typecode == "f" else ctypes.c_uint32 * len(flat)
        return (ctype * (len(flat) // per)).from_buffer_copy(data(*flat)) if flat else (ctype * 0)()
    check_format(mv, typecode, "input")
    size = ctypes.sizeof(ctype)
    if mv.nbytes % size:
        raise ValueError(f"a buffer of {mv.nbytes} bytes does not hold whole {ctype.__name__} items")
    return (ctype * (mv.nbytes // size)).from_buffer_copy(mv.tobytes())


# -- queries (hearth_world_cast_*, hearth_world_overlap_*)
RayHit = namedtuple("RayHit", "shape body point normal fraction")

ALL_BITS = (1 << 64) - 1


def query_filter(category_bits=1, mask_bits=ALL_BITS):
    """A HearthQueryFilter: the query's categories and the shape categories it reports. The
    defaults are `hearth_query_filter_default()`; `query_filter(ALL_BITS)` sees every shape."""
    f = lib.hearth_query_filter_default()
    f.category_bits = category_bits
    f.mask_bits = mask_bits
    return f


def query_sphere(radius, center=(0.0, 0.0, 0.0)):
    """A sphere for `World.cast_shape` and `World.overlap_shape`."""
    q = _ffi.HearthQueryShape()
    q.type = _ffi.HEARTH_QUERY_SHAPE_SPHERE
    q.sphere = _ffi.HearthSphere(to_vec3(center), radius)
    return q


def query_capsule(a, b, radius):
    """A capsule (segment end points, radius) for the shape queries."""
    q = _ffi.HearthQueryShape()
    q.type = _ffi.HEARTH_QUERY_SHAPE_CAPSULE
    q.capsule = _ffi.HearthCapsule(to_vec3(a), to_vec3(b), radius)
    return q


def query_box(half_extents, center=(0.0, 0.0, 0.0), rotation=IDENTITY):
    """A box for the shape queries."""
    q = _ffi.HearthQueryShape()
    q.type = _ffi.HEARTH_QUERY_SHAPE_BOX
    q.box = _ffi.HearthBox(to_vec3(center), to_quat(rotation), to_vec3(half_extents))
    return q


def query_hull(hull, scale=1.0, position=(0.0, 0.0, 0.0), rotation=IDENTITY):
    """A convex hull (a Hull) scaled and placed, for the shape queries."""
    q = _ffi.HearthQueryShape()
    q.type = _ffi.HEARTH_QUERY_SHAPE_HULL
    q.hull = _ffi.HearthHullShape(hull._id, to_transform((position, rotation)), scale)
    return q


def _filter(value):
    return query_filter() if value is None else value


def _hit(world, h):
    if (h.shape.index, h.shape.generation) == (0, 0):
        return None
    return RayHit(Shape(world, h.shape), Body(world, h.body), from_vec3(h.point), from_vec3(h.normal), h.fraction)
