"""Bulk read-back into caller-owned buffers equals the single reads."""

import ctypes
import math
from array import array

import pytest
from conftest import ground

import hearth

DT = 1.0 / 60.0


@pytest.fixture
def scene(world):
    ground(world)
    bodies = []
    for i in range(10):
        b = world.create_body("dynamic", position=(0.3 * i, 1.0 + 1.1 * i, 0.1 * i))
        if i % 2:
            b.add_box(half_extents=(0.5, 0.5, 0.5))
        else:
            b.add_sphere(radius=0.5)
        b.angular_velocity = (0.1 * i, 0.2, -0.3)
        bodies.append(b)
    for _ in range(30):
        world.step(DT)
    return world, bodies


def single_reads(bodies):
    flat = []
    for b in bodies:
        t = b.transform
        flat.extend(t.position)
        flat.extend(t.rotation)
    return array("f", flat)


def test_get_transforms_equals_single_reads(scene):
    world, bodies = scene
    out = world.get_transforms(bodies)
    assert isinstance(out, array) and out.typecode == "f" and len(out) == 7 * len(bodies)
    assert out == single_reads(bodies)


def test_get_transforms_into_reused_buffers(scene):
    world, bodies = scene
    ids = hearth.body_ids(bodies)
    assert hearth.body_ids(ids) is ids  # passed back in, used as is
    buf = array("f", [0.0]) * (7 * len(bodies) + 7)  # larger than needed is fine
    assert world.get_transforms(ids, out=buf) is buf
    assert buf[: 7 * len(bodies)] == single_reads(bodies)
    raw = bytearray(7 * 4 * len(bodies))
    world.get_transforms(ids, out=raw)
    assert array("f", bytes(raw)) == single_reads(bodies)
    view = memoryview(buf)
    world.step(DT)
    world.get_transforms(ids, out=view)
    assert buf[: 7 * len(bodies)] == single_reads(bodies)


def test_get_transforms_rejects_unsuitable_buffers(scene):
    world, bodies = scene
    with pytest.raises(ValueError, match="transforms"):
        world.get_transforms(bodies, out=array("f", [0.0]) * 7)
    with pytest.raises(TypeError, match="float32"):
        world.get_transforms(bodies, out=array("d", [0.0]) * (7 * len(bodies)))
    with pytest.raises(TypeError, match="writable"):
        world.get_transforms(bodies, out=bytes(7 * 4 * len(bodies)))


def test_get_transforms_with_a_stale_id_writes_nothing(scene):
    world, bodies = scene
    bodies[3].destroy()
    out = array("f", [-1.0]) * (7 * len(bodies))
    with pytest.raises(hearth.InvalidId) as e:
        world.get_transforms(bodies, out=out)
    assert "3" in e.value.message  # names the first bad index
    assert set(out) == {-1.0}


def test_get_transforms_of_nothing(world):
    assert len(world.get_transforms([])) == 0


def make_particles(world, n):
    return [
        world.create_particle(position=(0.1 * i, 1.0 + 0.2 * i, 0.0), velocity=(1.0, 0.5 * i, 0.0), user_data=i)
        for i in range(n)
    ]


def test_get_particles_equals_single_reads(world):
    ground(world)
    particles = make_particles(world, 12)
    for _ in range(20):
        world.step(DT)
    data = world.get_particles(positions=True, velocities=True, ids=True)
    assert data.count == world.particle_count == 12
    for k in range(data.count):
        p = hearth.Particle.from_id(world, data.ids[2 * k], data.ids[2 * k + 1])
        assert p in particles
        assert tuple(data.positions[3 * k : 3 * k + 3]) == p.position
        assert tuple(data.velocities[3 * k : 3 * k + 3]) == p.velocity

    positions = world.get_particle_positions(particles)
    assert positions == array("f", [c for p in particles for c in p.position])


def test_get_particles_into_caller_buffers(world):
    make_particles(world, 5)
    positions = array("f", [0.0]) * 15
    data = world.get_particles(positions=positions)
    assert data.positions is positions and data.velocities is None and data.ids is None
    assert data.count == 5
    small = array("f", [7.0]) * 6  # room for 2 particles
    with pytest.raises(hearth.BufferTooSmall):  # the library's verdict, from the capacity
        world.get_particles(positions=small)
    assert set(small) == {7.0}


def test_soft_body_vertices_equal_single_reads(world):
    ground(world)
    ball = world.create_soft_body_icosphere(radius=0.5, subdivisions=2, position=(0.0, 1.0, 0.0), pressure=50.0)
    for _ in range(10):
        world.step(DT)
    n = ball.vertex_count
    assert n == 162
    positions = ball.get_positions()
    assert len(positions) == 3 * n
    for v in (0, 17, n - 1):
        assert tuple(positions[3 * v : 3 * v + 3]) == ball.vertex_position(v)
    normals = ball.get_normals()
    for v in range(n):
        assert math.sqrt(sum(c * c for c in normals[3 * v : 3 * v + 3])) == pytest.approx(1.0, abs=1e-4)
    indices = ball.get_indices()
    assert indices.typecode == "I" and len(indices) == 3 * ball.triangle_count
    assert max(indices) == n - 1

    buf = array("f", [0.0]) * (3 * n)
    assert ball.get_positions(out=buf) is buf and buf == positions
    small = array("f", [5.0]) * (3 * n - 3)
    with pytest.raises(hearth.BufferTooSmall):
        ball.get_positions(out=small)
    assert set(small) == {5.0}
    as_uint = (ctypes.c_uint32 * len(indices))()
    ball.get_indices(out=as_uint)
    assert list(as_uint) == list(indices)
