"""Runtime setters through the binding (issue 14): each against its getter and its physics,
and the errors a bad value raises with nothing changed."""

import pytest
from conftest import ground

import hearth

DT = 1.0 / 60.0


def test_shape_material_setters_round_trip_and_density_doubles_the_mass(world):
    body = world.create_body("dynamic", position=(0.0, 5.0, 0.0))
    shape = body.add_box(half_extents=(0.5, 0.25, 1.0))
    m0 = body.mass
    shape.density = 2000.0
    assert shape.density == 2000.0
    assert body.mass == 2.0 * m0
    shape.friction = (0.8, 0.25)
    assert shape.friction == pytest.approx((0.8, 0.25))
    shape.restitution = 0.5
    shape.rolling_resistance = 0.25
    shape.torsional_friction = 0.125
    assert (shape.restitution, shape.rolling_resistance, shape.torsional_friction) == (0.5, 0.25, 0.125)
    shape.user_data = 1234567890123
    assert shape.user_data == 1234567890123
    with pytest.raises(hearth.errors.InvalidArgument):
        shape.density = -1.0
    with pytest.raises(hearth.errors.InvalidArgument):
        shape.friction = float("nan")
    with pytest.raises(hearth.errors.InvalidArgument):
        shape.restitution = 2.0
    assert shape.density == 2000.0 and shape.restitution == 0.5


def test_gravity_scale_zero_floats_and_mass_override_gives_dv_j_over_m(world):
    body = world.create_body("dynamic", position=(0.0, 5.0, 0.0))
    body.add_box(half_extents=(0.5, 0.5, 0.5))
    assert body.gravity_scale == 1.0
    body.gravity_scale = 0.0
    for _ in range(30):
        world.step(DT)
    assert body.position.y == 5.0
    with pytest.raises(hearth.errors.InvalidArgument):
        body.gravity_scale = float("inf")
    body.set_mass_data(4.0, (0.0, 0.0, 0.0), (2.0, 4.0, 8.0))
    mass, center, inertia = body.mass_data
    assert mass == 4.0 and tuple(inertia) == (2.0, 4.0, 8.0)
    body.apply_linear_impulse((2.0, 0.0, 0.0))
    assert body.linear_velocity.x == 0.5
    with pytest.raises(hearth.errors.InvalidArgument):
        body.set_mass_data(0.0, (0.0, 0.0, 0.0), (1.0, 1.0, 1.0))
    body.reset_mass_data()
    assert body.mass == pytest.approx(1000.0)


def test_type_change_and_disable(world):
    ground(world)
    shelf = world.create_body("static", position=(0.0, 3.0, 0.0))
    shelf.add_box(half_extents=(2.0, 0.25, 2.0))
    box = world.create_body("dynamic", position=(0.0, 3.75, 0.0), allow_sleep=0)
    box.add_box(half_extents=(0.5, 0.5, 0.5))
    for _ in range(60):
        world.step(DT)
    assert box.position.y == pytest.approx(3.75, abs=0.01)
    assert shelf.enabled
    shelf.enabled = False
    assert not shelf.enabled
    for _ in range(120):
        world.step(DT)
    assert box.position.y == pytest.approx(0.5, abs=0.01)
    shelf.enabled = True
    box.type = "static"
    assert box.type == hearth.BodyType.STATIC and box.mass == 0.0
    box.type = hearth.BodyType.DYNAMIC
    assert box.mass == pytest.approx(1000.0)
    with pytest.raises(hearth.errors.InvalidArgument):
        box.type = 7
    assert box.type == hearth.BodyType.DYNAMIC


def test_locked_axes_keep_a_body_in_its_plane(world):
    ffi = hearth.ffi
    body = world.create_body("dynamic", position=(0.0, 5.0, 0.0), locked_axes=ffi.HEARTH_LOCK_LINEAR_Z)
    body.add_box(half_extents=(0.5, 0.5, 0.5))
    assert body.locked_axes == ffi.HEARTH_LOCK_LINEAR_Z
    body.linear_velocity = (1.0, 2.0, 3.0)
    assert tuple(body.linear_velocity) == (1.0, 2.0, 0.0)
    body.locked_axes = ffi.HEARTH_LOCK_LINEAR_Y | ffi.HEARTH_LOCK_ANGULAR
    assert body.linear_velocity.y == 0.0
    for _ in range(30):
        world.step(DT)
    assert body.position.y == 5.0  # locked in y: it floats
    assert tuple(body.angular_velocity) == (0.0, 0.0, 0.0)
    with pytest.raises(hearth.errors.InvalidArgument):
        body.locked_axes = 64
    assert body.locked_axes == ffi.HEARTH_LOCK_LINEAR_Y | ffi.HEARTH_LOCK_ANGULAR
    with pytest.raises(hearth.errors.InvalidArgument):
        world.create_body("dynamic", locked_axes=128)
