"""Worlds, bodies and shapes through the binding: physics, properties and every kind of error."""

import math

import pytest
from conftest import ground

import hearth

DT = 1.0 / 60.0


def test_a_falling_box_comes_to_rest_on_the_plane(world):
    ground(world)
    box = world.create_body("dynamic", position=(0.0, 3.0, 0.0))
    box.add_box(half_extents=(0.5, 0.5, 0.5))
    g = -world.gravity.y

    # Free fall first: y = y0 - g t^2 / 2, to the first-order error of the time step.
    for _ in range(30):
        world.step(DT)
    t = 30 * DT
    assert box.position.y == pytest.approx(3.0 - 0.5 * g * t * t, abs=g * t * DT)
    assert box.linear_velocity.y == pytest.approx(-g * t, abs=1e-3)

    # Landed (at 0.71 s) and still awake: its contact with the plane touches.
    for _ in range(30):
        world.step(DT)
    assert world.counters.touching_contact_count == 1
    for _ in range(150):
        world.step(DT)
    # At rest with its bottom face on y = 0: the centre at the half extent; asleep (at
    # about 1.5 s) with its contact kept.
    assert box.position.y == pytest.approx(0.5, abs=5e-3)
    assert abs(box.position.x) < 1e-3 and abs(box.position.z) < 1e-3
    assert math.hypot(*box.linear_velocity) < 1e-2
    assert not box.is_awake
    assert world.counters.contact_count == 1


def test_sleep_and_wake(world):
    ground(world)
    box = world.create_body("dynamic", position=(0.0, 0.5, 0.0))
    box.add_box(half_extents=(0.5, 0.5, 0.5))
    for _ in range(120):
        world.step(DT)
    assert not box.is_awake
    box.set_awake(True)
    assert box.is_awake
    never = world.create_body("dynamic", position=(3.0, 0.5, 0.0), allow_sleep=False)
    never.add_sphere(radius=0.5)
    for _ in range(120):
        world.step(DT)
    assert never.is_awake


def test_defaults_come_from_the_library(world):
    body = world.create_body()
    defaults = hearth.lib.hearth_body_def_default()
    assert body.type == defaults.type == hearth.BodyType.STATIC
    assert body.transform == hearth.Transform(
        hearth.Vec3(0.0, 0.0, 0.0), hearth.Quat(*(getattr(defaults.transform.rotation, c) for c in "xyzw"))
    )
    assert world.gravity == hearth.Vec3(
        *(getattr(hearth.lib.hearth_world_def_default().gravity, c) for c in "xyz")
    )


def test_body_properties_round_trip(world):
    body = world.create_body(hearth.BodyType.DYNAMIC, position=(1.0, 2.0, 3.0), user_data=42)
    body.add_box(half_extents=(0.5, 1.0, 1.5), density=10.0)
    assert body.mass == pytest.approx(10.0 * 1.0 * 2.0 * 3.0)
    assert body.user_data == 42
    assert body.type is hearth.BodyType.DYNAMIC
    assert body.center_of_mass == pytest.approx((1.0, 2.0, 3.0))

    body.linear_velocity = (1.0, -2.0, 0.5)
    assert body.linear_velocity == pytest.approx((1.0, -2.0, 0.5))
    body.angular_velocity = [0.0, 3.0, 0.0]
    assert body.angular_velocity == pytest.approx((0.0, 3.0, 0.0))

    s = math.sqrt(0.5)
    body.rotation = (0.0, s, 0.0, s)
    assert body.position == pytest.approx((1.0, 2.0, 3.0))  # rotating kept the position
    body.position = (4.0, 5.0, 6.0)
    assert body.rotation == pytest.approx((0.0, s, 0.0, s), abs=1e-6)  # moving kept the rotation
    body.transform = hearth.Transform((0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0))
    assert body.transform.position == pytest.approx((0.0, 1.0, 0.0))

    body.linear_velocity = (0.0, 0.0, 0.0)
    body.apply_linear_impulse((60.0, 0.0, 0.0))  # dv = J / m
    assert body.linear_velocity.x == pytest.approx(60.0 / body.mass)


def test_forces_act_over_a_step(world):
    world.gravity = (0.0, 0.0, 0.0)
    assert world.gravity == (0.0, 0.0, 0.0)
    body = world.create_body("dynamic")
    body.add_sphere(radius=0.5)
    m = body.mass
    body.apply_force((m * 2.0, 0.0, 0.0))  # 2 m/s^2 for one step
    world.step(DT)
    assert body.linear_velocity.x == pytest.approx(2.0 * DT, rel=1e-4)


def test_shapes_belong_to_their_body(world):
    body = world.create_body("dynamic")
    sphere = body.add_sphere(radius=0.25, center=(0.0, 1.0, 0.0))
    capsule = body.add_capsule(a=(0.0, 0.0, -1.0), b=(0.0, 0.0, 1.0), radius=0.1)
    assert sphere.body == body and capsule.body == body
    mass = body.mass
    capsule.destroy()
    assert body.mass < mass
    with pytest.raises(hearth.InvalidId):
        capsule.body


def test_kinematic_target_transform(world):
    k = world.create_body("kinematic")
    k.add_box(half_extents=(1.0, 0.1, 1.0))
    k.set_target_transform((0.0, 1.0, 0.0))
    world.step(DT)
    assert k.position.y == pytest.approx(1.0, abs=1e-4)
    # reached: its velocity reads as the move's (1 m in one step) ...
    assert k.linear_velocity[1] == pytest.approx(1.0 / DT, rel=1e-4)
    world.step(DT)
    # ... and it stops there in the next step
    assert k.position.y == pytest.approx(1.0, abs=1e-4)
    assert k.linear_velocity == (0.0, 0.0, 0.0)


def test_max_angular_speed_is_a_world_setting():
    assert hearth.lib.hearth_world_def_default().max_angular_speed == pytest.approx(math.pi * 100.0)
    with hearth.World(max_angular_speed=10.0, gravity=(0.0, 0.0, 0.0)) as w:
        body = w.create_body("dynamic")
        body.add_sphere(radius=0.5)
        with pytest.raises(hearth.InvalidArgument) as e:
            body.angular_velocity = (0.0, 11.0, 0.0)  # above the limit: refused
        assert "max_angular_speed" in e.value.message
        body.apply_angular_impulse((0.0, 1.0e6, 0.0))  # an impulse is capped at the limit
        assert body.angular_velocity == pytest.approx((0.0, 10.0, 0.0))
    for bad in (0.0, -1.0, float("nan")):
        with pytest.raises(hearth.InvalidArgument) as e:
            hearth.World(max_angular_speed=bad)
        assert "max_angular_speed" in e.value.message


# ----------------------------------------------------------------------------------- errors


def test_stale_id_after_destroy_is_invalid_id_with_the_message(world):
    body = world.create_body("dynamic")
    body.destroy()
    with pytest.raises(hearth.InvalidId) as e:
        body.position
    err = e.value
    assert err.code == hearth.ffi.HEARTH_ERROR_INVALID_ID
    assert err.name == "HEARTH_ERROR_INVALID_ID"
    assert err.message == hearth.last_error_message() and "body" in err.message
    assert err.function == "hearth_body_get_transform"
    assert isinstance(err, hearth.HearthError) and isinstance(err, LookupError)
    with pytest.raises(hearth.InvalidId):
        body.destroy()
    # a new body does not revive the old id
    again = world.create_body("dynamic")
    assert again != body
    with pytest.raises(hearth.InvalidId):
        body.linear_velocity


def test_nan_is_invalid_argument_and_changes_nothing(world):
    body = world.create_body("dynamic", position=(1.0, 2.0, 3.0))
    body.add_sphere(radius=0.5)
    before = body.transform
    with pytest.raises(hearth.InvalidArgument) as e:
        body.position = (float("nan"), 0.0, 0.0)
    assert "NaN" in e.value.message or "finite" in e.value.message
    assert isinstance(e.value, ValueError)
    assert body.transform == before
    with pytest.raises(hearth.InvalidArgument):
        body.linear_velocity = (0.0, float("inf"), 0.0)
    assert body.linear_velocity == (0.0, 0.0, 0.0)
    with pytest.raises(hearth.InvalidArgument):
        world.step(float("nan"))
    count = world.counters.body_count
    with pytest.raises(hearth.InvalidArgument):
        world.create_body("dynamic", position=(0.0, float("nan"), 0.0))
    assert world.counters.body_count == count


def test_the_library_validates_not_the_binding(world):
    body = world.create_body("dynamic")
    mass = body.mass
    with pytest.raises(hearth.InvalidArgument):
        body.add_box(half_extents=(-1.0, 1.0, 1.0))
    with pytest.raises(hearth.InvalidArgument):
        body.add_sphere(radius=1.0, density=-5.0)
    assert body.mass == mass
    with pytest.raises(hearth.InvalidArgument):
        world.create_body(type=7)  # unknown code: the library's verdict
    with pytest.raises(hearth.InvalidArgument):
        world.create_body("dynamic", allow_sleep=2)  # flag byte other than 0/1
    with pytest.raises(hearth.InvalidArgument):
        body.add_plane(normal=(0.0, 1.0, 0.0))  # planes only on static bodies
    with pytest.raises(hearth.InvalidArgument):
        hearth.World(substeps=0)
    with pytest.raises(TypeError):
        world.create_body(colour="red")  # not a field of HearthBodyDef: a Python error
    with pytest.raises(TypeError):
        world.create_body(internal_value=0)


def test_ids_of_another_world_are_invalid(world):
    with hearth.World() as other:
        theirs = other.create_body("dynamic")
        impostor = hearth.Body(world, theirs._id)
        with pytest.raises(hearth.InvalidId):
            impostor.position


def test_world_context_manager_closes():
    with hearth.World() as w:
        body = w.create_body("dynamic")
        w.step(DT)
        assert not w.closed
    assert w.closed
    w.close()  # idempotent
    with pytest.raises(hearth.NullPointer) as e:
        w.step(DT)
    assert e.value.code == hearth.ffi.HEARTH_ERROR_NULL_POINTER
    with pytest.raises(hearth.NullPointer):
        body.position
    with pytest.raises(hearth.NullPointer):
        w.create_body()


def test_result_names_and_unknown_codes():
    assert hearth.result_name(0) == "HEARTH_OK"
    assert hearth.result_name(3) == "HEARTH_ERROR_INVALID_ARGUMENT"
    assert hearth.result_name(999) == "HEARTH_ERROR_UNKNOWN"
    assert hearth.result_name(8) == "HEARTH_ERROR_LIMIT_REACHED"
    assert issubclass(hearth.LimitReached, hearth.HearthError)
    err = hearth.errors.error_for(999)
    assert type(err) is hearth.HearthError and err.code == 999


def test_separate_worlds_step_on_separate_threads():
    import threading

    def simulate(results, key):
        with hearth.World() as w:
            ground(w)
            boxes = []
            for i in range(20):
                b = w.create_body("dynamic", position=(0.0, 0.5 + 1.01 * i, 0.0))
                b.add_box(half_extents=(0.5, 0.5, 0.5))
                boxes.append(b)
            for _ in range(120):
                w.step(DT)
            results[key] = w.get_transforms(boxes)

    results = {}
    threads = [threading.Thread(target=simulate, args=(results, k)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    simulate(results, "alone")
    assert results[0] == results[1] == results["alone"]  # deterministic, independent worlds


def test_rolling_resistance_and_torsional_friction(world):
    """The shape def's last two fields: defaults, range errors, and a ball that rolls and one
    that spins to rest on the analytic answers (7v²/10cg and 2rω/5tg)."""
    defaults = hearth.lib.hearth_shape_def_default()
    assert defaults.rolling_resistance == pytest.approx(0.05)
    assert defaults.torsional_friction == pytest.approx(0.05)
    body = world.create_body("dynamic", position=(0.0, 5.0, 0.0))
    for bad in (-0.1, 1.5, math.nan, math.inf):
        with pytest.raises(hearth.InvalidArgument, match="rolling_resistance"):
            body.add_sphere(radius=0.3, rolling_resistance=bad)
        with pytest.raises(hearth.InvalidArgument, match="torsional_friction"):
            body.add_sphere(radius=0.3, torsional_friction=bad)
    body.destroy()

    ground(world)  # default material: the balls' larger values win
    r, v, c, t, spin, g = 0.3, 2.0, 0.2, 0.3, 6.0, -world.gravity.y
    rolling = world.create_body("dynamic", position=(0.0, r, 0.0))
    rolling.add_sphere(radius=r, rolling_resistance=c, torsional_friction=t)
    rolling.linear_velocity = (v, 0.0, 0.0)
    rolling.angular_velocity = (0.0, 0.0, -v / r)
    spinning = world.create_body("dynamic", position=(5.0, r, 0.0))
    spinning.add_sphere(radius=r, rolling_resistance=c, torsional_friction=t)
    spinning.angular_velocity = (0.0, spin, 0.0)
    stopped = None
    for step in range(1, 601):
        world.step(DT)
        if stopped is None and spinning.angular_velocity.y <= 1e-3:
            stopped = step * DT
    distance = 7.0 * v * v / (10.0 * c * g)
    assert rolling.position.x == pytest.approx(distance, rel=0.05)
    assert stopped == pytest.approx(2.0 * r * spin / (5.0 * t * g), rel=0.05, abs=DT)
    assert not rolling.is_awake and not spinning.is_awake
