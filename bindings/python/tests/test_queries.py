"""Queries and collision filters through the binding: ray casts (closest, callback, batch),
shape casts and overlaps against analytic answers, shape filters at creation and at run time,
and their errors."""

import pytest

import hearth

DT = 1.0 / 60.0


def test_rays_hit_a_sphere_at_d_minus_r(world):
    ball = world.create_body("static", position=(0.0, 2.0, 0.0))
    shape = ball.add_sphere(0.5)
    hit = world.cast_ray_closest((-4.0, 2.0, 0.0), (10.0, 0.0, 0.0))
    assert hit.shape == shape and hit.body == ball
    assert hit.fraction == pytest.approx(0.35, abs=1e-5)  # (d - r) / |v| = 3.5 / 10
    assert hit.normal.x == pytest.approx(-1.0, abs=1e-5)
    assert world.cast_ray_closest((-4.0, 9.0, 0.0), (10.0, 0.0, 0.0)) is None
    # A rebuilt broad-phase tree answers the same.
    world.rebuild_broadphase()
    again = world.cast_ray_closest((-4.0, 2.0, 0.0), (10.0, 0.0, 0.0))
    assert again.shape == shape and again.fraction == hit.fraction
    hits = world.cast_rays([((-4.0, 2.0, 0.0), (10.0, 0.0, 0.0)), ((0.0, 9.0, 0.0), (1.0, 0.0, 0.0))])
    assert hits[0].shape == shape and hits[1] is None
    seen = []
    world.cast_ray((-4.0, 2.0, 0.0), (10.0, 0.0, 0.0), lambda h: seen.append(h.fraction) or 1.0)
    assert seen == [pytest.approx(0.35, abs=1e-5)]
    # An exception in the callback stops the cast and comes back here.
    with pytest.raises(ZeroDivisionError):
        world.cast_ray((-4.0, 2.0, 0.0), (10.0, 0.0, 0.0), lambda h: 1 / 0)
    with pytest.raises(hearth.InvalidArgument, match="translation"):
        world.cast_ray_closest((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    with pytest.raises(hearth.InvalidArgument, match="origin"):
        world.cast_ray_closest((float("nan"), 0.0, 0.0), (1.0, 0.0, 0.0))


def test_shape_casts_and_overlaps(world):
    ground = world.create_body()
    plane = ground.add_plane(normal=(0.0, 1.0, 0.0))
    hit = world.cast_shape(hearth.query_sphere(0.5), (0.0, 5.0, 0.0), (0.0, -10.0, 0.0))
    assert hit.shape == plane and hit.fraction == pytest.approx(0.45, abs=1e-6)  # (5 - 0.5) / 10
    ball = world.create_body("static", position=(3.0, 1.0, 0.0))
    s = ball.add_sphere(0.5)
    assert world.overlap_shape(hearth.query_box((0.3, 0.3, 0.3)), (3.5, 1.5, 0.0)) == [s]
    assert set(world.overlap_aabb((2.0, -1.0, -1.0), (4.0, 2.0, 1.0))) == {plane, s}
    assert world.overlap_point((3.0, 1.2, 0.0)) == [s]
    assert world.overlap_point((3.0, 5.0, 0.0)) == []
    cap = hearth.query_capsule((0.0, -0.5, 0.0), (0.0, 0.5, 0.0), 0.25)
    assert world.cast_shape(cap, (0.0, 5.0, 0.0), (0.0, -10.0, 0.0)).fraction == pytest.approx(0.425, abs=1e-6)
    hull = world.create_hull([(x, y, z) for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)])
    assert world.cast_shape(hearth.query_hull(hull), (0.0, 5.0, 0.0), (0.0, -10.0, 0.0)).fraction == pytest.approx(
        0.45, abs=1e-5
    )
    with pytest.raises(hearth.InvalidArgument, match="radius"):
        world.overlap_shape(hearth.query_sphere(-1.0), (0.0, 0.0, 0.0))
    with pytest.raises(hearth.InvalidArgument, match="aabb"):
        world.overlap_aabb((1.0, 1.0, 1.0), (0.0, 0.0, 0.0))


def test_filters_at_creation_and_at_run_time(world):
    ground = world.create_body()
    ground.add_plane(normal=(0.0, 1.0, 0.0))
    box = world.create_body("dynamic", position=(0.0, 0.5, 0.0))
    shape = box.add_box((0.5, 0.5, 0.5), filter=hearth.ffi.HearthFilter(2, hearth.ALL_BITS, 0))
    assert shape.filter == (2, hearth.ALL_BITS, 0)
    for _ in range(30):
        world.step(DT)
    assert box.position.y == pytest.approx(0.5, abs=5e-3)
    # A query that leaves out category 2 does not see it.
    assert world.cast_ray_closest((0.0, 5.0, 0.0), (0.0, -4.0, 0.0), hearth.query_filter(1, ~2 & hearth.ALL_BITS)) is None
    shape.filter = (2, 0, 0)  # collides with nothing now
    for _ in range(30):
        world.step(DT)
    assert box.position.y < 0.0
    with pytest.raises(hearth.InvalidId):
        shape.destroy()
        shape.filter = (1, 1, 0)
