"""Python callables as force and contact generators, and what happens when they fail."""

import gc
from array import array

import pytest
from conftest import ground

import hearth

DT = 1.0 / 60.0


def hover(world, context):
    """A force generator cancelling gravity on every attached body."""
    g = world.gravity
    for body in context.bodies:
        m = body.mass
        body.apply_force((-m * g.x, -m * g.y, -m * g.z))


def test_a_python_force_generator_makes_a_body_hover(world):
    body = world.create_body("dynamic", position=(0.0, 5.0, 0.0))
    body.add_box(half_extents=(0.5, 0.5, 0.5))
    falling = world.create_body("dynamic", position=(3.0, 5.0, 0.0))
    falling.add_box(half_extents=(0.5, 0.5, 0.5))
    gen = world.create_force_generator(hover)
    gen.attach(body)
    assert gen.type is hearth.GeneratorType.USER_FORCE
    assert gen.attachment_count == (1, 0)
    for _ in range(120):
        world.step(DT)
    assert body.position.y == pytest.approx(5.0, abs=1e-4)
    assert falling.position.y < 0.0  # nothing under it, not attached


def test_the_callback_is_told_its_context(world):
    body = world.create_body("dynamic")
    particle = world.create_particle()
    seen = []
    gen = world.create_force_generator(
        lambda w, ctx: seen.append((w, ctx.generator, ctx.dt, ctx.bodies, ctx.particles))
    )
    gen.attach(body)
    gen.attach(particle)
    world.step(0.02)
    assert len(seen) == 1
    w, generator, dt, bodies, particles = seen[0]
    assert w is world and generator == gen
    assert dt == pytest.approx(0.02)
    assert bodies == [body] and particles == [particle]
    gen.detach(particle)
    world.step(0.02)
    assert seen[1][4] == []


def test_an_exception_in_a_callback_surfaces_from_step(world):
    body = world.create_body("dynamic")
    body.add_sphere(radius=0.5)
    calls = []

    def flaky(w, ctx):
        calls.append(ctx.dt)
        if len(calls) == 2:
            raise ValueError("boom in the force generator")

    world.create_force_generator(flaky).attach(body)
    world.step(DT)
    y = body.position.y
    with pytest.raises(ValueError, match="boom in the force generator") as e:
        world.step(DT)
    # the traceback reaches into the callback
    assert any(frame.name == "flaky" for frame in e.traceback)
    assert body.position.y < y  # the step itself completed
    world.step(DT)  # and the world goes on
    assert len(calls) == 3


def test_world_locked_inside_a_callback_surfaces_from_step(world):
    def structural(w, ctx):
        w.create_body("dynamic")

    world.create_force_generator(structural)
    count = world.counters.body_count
    with pytest.raises(hearth.WorldLocked) as e:
        world.step(DT)
    assert e.value.code == hearth.ffi.HEARTH_ERROR_WORLD_LOCKED and e.value.message
    assert world.counters.body_count == count

    def nested_step(w, ctx):
        w.step(DT)

    with hearth.World() as other:
        other.create_force_generator(nested_step)
        with pytest.raises(hearth.WorldLocked):
            other.step(DT)


def test_closing_the_world_from_a_callback_is_refused(world):
    world.create_force_generator(lambda w, ctx: w.close())
    with pytest.raises(RuntimeError, match="cannot be closed"):
        world.step(DT)
    assert not world.closed
    world.step(0.0)


def test_trampolines_live_while_registered(world):
    body = world.create_body("dynamic", position=(0.0, 5.0, 0.0))
    body.add_sphere(radius=0.5)
    gen = world.create_force_generator(lambda w, ctx: hover(w, ctx))  # no other reference
    gen.attach(body)
    gc.collect()
    for _ in range(10):
        world.step(DT)
    assert body.position.y == pytest.approx(5.0, abs=1e-4)
    assert len(world._callbacks) == 1
    gen.destroy()
    assert world._callbacks == {}
    with pytest.raises(hearth.InvalidId):
        gen.destroy()
    world.step(DT)
    assert body.position.y < 5.0


def test_close_releases_trampolines():
    w = hearth.World()
    w.create_force_generator(hover)
    w.create_contact_generator(lambda w, ctx, sink: None)
    assert len(w._callbacks) == 2
    w.close()
    assert w._callbacks == {}


def test_destroying_a_generator_from_its_callback_is_refused(world):
    gens = []

    def self_destruct(w, ctx):
        gens[0].destroy()

    gens.append(world.create_force_generator(self_destruct))
    with pytest.raises(hearth.WorldLocked):
        world.step(DT)
    assert len(world._callbacks) == 1  # still registered: C may call it again
    with pytest.raises(hearth.WorldLocked):
        world.step(DT)


def test_a_python_contact_generator_holds_a_particle_up(world):
    floor = 1.0
    particle = world.create_particle(position=(0.0, 2.0, 0.0), radius=0.0)

    def shelf(w, ctx, sink):
        assert sink.count == 0 and sink.capacity == 4
        for p in ctx.particles:
            y = p.position.y
            # world (A) below, particle (B) pushed along +y
            sink.add(None, p, point=(0.0, floor, 0.0), normal=(0.0, 1.0, 0.0), penetration=floor - y)
        assert sink.count == len(ctx.particles)

    gen = world.create_contact_generator(shelf, capacity=4)
    assert gen.type is hearth.GeneratorType.USER_CONTACT
    gen.attach(particle)
    for _ in range(120):
        world.step(DT)
    assert particle.position.y == pytest.approx(floor, abs=1e-2)
    assert abs(particle.velocity.y) < 0.05


def test_a_python_contact_generator_between_bodies(world):
    ground(world)
    box = world.create_body("dynamic", position=(0.0, 3.0, 0.0))
    box.add_box(half_extents=(0.5, 0.5, 0.5))
    shelf_y = 2.0

    def shelf(w, ctx, sink):
        for b in ctx.bodies:
            bottom = b.position.y - 0.5
            for x in (-0.5, 0.5):
                for z in (-0.5, 0.5):
                    p = b.position
                    sink.add(None, b, (p.x + x, bottom, p.z + z), (0.0, 1.0, 0.0), shelf_y - bottom, friction=0.5)

    world.create_contact_generator(shelf).attach(box)
    for _ in range(180):
        world.step(DT)
    assert box.position.y == pytest.approx(shelf_y + 0.5, abs=1e-2)


def test_contact_sink_errors_surface_from_step(world):
    particle = world.create_particle()
    kept = []

    def too_many(w, ctx, sink):
        kept.append(sink)
        for _ in range(3):
            sink.add(None, ctx.particles[0], (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 0.0)

    world.create_contact_generator(too_many, capacity=2).attach(particle)
    with pytest.raises(hearth.BufferTooSmall):
        world.step(DT)
    # a sink kept past its callback cannot reach C's freed memory
    with pytest.raises(hearth.NullPointer):
        kept[0].add(None, particle, (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 0.0)


def test_contact_sink_validates_in_the_library(world):
    particle = world.create_particle()

    def zero_normal(w, ctx, sink):
        sink.add(None, ctx.particles[0], (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), 0.0)

    world.create_contact_generator(zero_normal).attach(particle)
    with pytest.raises(hearth.InvalidArgument):
        world.step(DT)


def test_context_ids_feed_bulk_reads(world):
    particles = [world.create_particle(position=(float(i), 1.0, 0.0)) for i in range(5)]
    read = []

    def bulk(w, ctx):
        read.append(w.get_particle_positions(ctx.particle_ids))

    gen = world.create_force_generator(bulk)
    gen.attach_particles(particles)
    world.step(DT)
    assert len(read[0]) == 15
    assert read[0][0::3] == array("f", [0.0, 1.0, 2.0, 3.0, 4.0])
