"""Events, sensors and the step callbacks through the Python binding: a dropped box's begin,
hit (sqrt(2gh) within 1 %) and end; a kinematic box through a sensor; move events; the
one-way platform with a pre-solve callback; a pair filter; errors surface as exceptions."""

import math

import pytest
from conftest import ground

import hearth

DT = 1.0 / 60.0


def test_a_dropped_box_reports_begin_hit_moves_and_end(world):
    plane = ground(world)
    h = 2.0
    body = world.create_body("dynamic", position=(0.0, 0.5 + h, 0.0), user_data=11)
    shape = body.add_box(half_extents=(0.5, 0.5, 0.5), enable_hit_events=1)
    begins, hits, ends, moves = [], [], [], 0
    for _ in range(120):
        world.step(DT)
        b, e, hit = world.contact_events()
        begins += b
        ends += e
        hits += hit
        for m in world.body_events():
            assert m.body.index == shape.body._id.index and m.user_data == 11
            moves += 1
    assert len(begins) == 1 and len(hits) == 1 and not ends
    assert hits[0].approach_speed == pytest.approx(math.sqrt(2 * 9.81 * h), rel=0.01)
    assert moves > 30
    assert plane is not None
    shape.destroy()
    world.step(DT)
    assert len(world.contact_events()[1]) == 1


def test_a_kinematic_box_through_a_sensor(world):
    zone = world.create_body(position=(0.0, 3.0, 0.0))
    sensor = zone.add_box(half_extents=(1.0, 1.0, 1.0), is_sensor=1)
    mover = world.create_body("kinematic", position=(-5.0, 3.0, 0.0), linear_velocity=(2.0, 0.0, 0.0))
    visitor = mover.add_box(half_extents=(0.25, 0.25, 0.25))
    begins, ends = [], []
    for _ in range(300):
        world.step(DT)
        b, e = world.sensor_events()
        begins += b
        ends += e
    assert len(begins) == 1 and len(ends) == 1
    assert begins[0].sensor_shape.index == sensor._id.index
    assert begins[0].visitor_shape.index == visitor._id.index
    with pytest.raises(hearth.HearthError):
        zone.add_plane(normal=(0.0, 1.0, 0.0), offset=0.0, is_sensor=1)
    with pytest.raises(hearth.HearthError):
        zone.add_box(half_extents=(1.0, 1.0, 1.0), is_sensor=2)


def test_a_one_way_platform_and_a_pair_filter(world):
    ground(world)
    slab = world.create_body(position=(0.0, 3.0, 0.0))
    platform = slab.add_box(half_extents=(2.0, 0.1, 2.0))
    box = world.create_body("dynamic", position=(0.0, 0.5, 0.0), linear_velocity=(0.0, 10.0, 0.0))
    box.add_box(half_extents=(0.25, 0.25, 0.25))

    def one_way(w, c):
        if c.shape_a.index == platform._id.index:
            up = c.normal.y
        elif c.shape_b.index == platform._id.index:
            up = -c.normal.y
        else:
            return True
        deepest = min(sep for _, sep in c.points)
        return up > 0.7 and deepest > -0.05

    asked = []
    world.set_pre_solve(one_way)
    world.set_pair_filter(lambda w, a, b: asked.append((a, b)) or True)
    for _ in range(180):
        world.step(DT)
    assert box.position.y == pytest.approx(3.35, abs=0.005)
    assert asked
    world.set_pre_solve(None)
    world.set_pair_filter(None)
    world.step(DT)


def test_an_exception_in_a_pre_solve_callback_surfaces_from_step(world):
    ground(world)
    box = world.create_body("dynamic", position=(0.0, 0.5, 0.0))
    box.add_box(half_extents=(0.5, 0.5, 0.5))

    def boom(w, c):
        raise RuntimeError("boom")

    world.set_pre_solve(boom)
    with pytest.raises(RuntimeError):
        world.step(DT)
    world.set_pre_solve(None)
    world.step(DT)


def test_event_reads_on_a_closed_world_fail():
    w = hearth.World()
    w.close()
    with pytest.raises(Exception):
        w.contact_events()
