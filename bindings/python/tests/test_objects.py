"""Joints, built-in generators, particles and soft bodies through the binding."""

import math

import pytest
from conftest import ground

import hearth

DT = 1.0 / 60.0


def distance(a, b):
    return math.dist(tuple(a), tuple(b))


# ----------------------------------------------------------------------------------- joints


def test_ball_joint_pendulum_keeps_its_length(world):
    bob = world.create_body("dynamic", position=(1.0, 0.0, 0.0))
    bob.add_sphere(radius=0.1)
    joint = world.create_ball_joint(bob, None, frame_a=(-1.0, 0.0, 0.0))  # anchor: the world origin
    assert joint.type is hearth.JointType.BALL
    assert joint.bodies == (bob, None)
    lowest = 0.0
    for _ in range(60):
        world.step(DT)
        assert distance(bob.position, (0.0, 0.0, 0.0)) == pytest.approx(1.0, abs=5e-3)
        lowest = min(lowest, bob.position.y)
    assert lowest < -0.9  # it swung down
    force, torque = joint.force  # on body B: here the world
    assert math.hypot(*force) > 0.0
    joint.set_cone_limit(True, 0.5)
    assert joint.cone_limit == (True, pytest.approx(0.5))
    joint.set_limits(True, -0.25, 0.25)  # twist
    assert joint.limits == (True, pytest.approx(-0.25), pytest.approx(0.25))


def test_hinge_motor_limits_and_spring(world):
    door = world.create_body("dynamic")
    door.add_box(half_extents=(0.5, 1.0, 0.05))
    world.gravity = (0.0, 0.0, 0.0)
    hinge = world.create_hinge_joint(door, enable_motor=True, motor_speed=1.0, max_motor_torque=1e4)
    assert hinge.type is hearth.JointType.HINGE
    assert hinge.motor == (True, pytest.approx(1.0), pytest.approx(1e4))
    for _ in range(30):
        world.step(DT)
    # The hinge axis is Z; the motor drives B (the world) relative to A (the door) at +1 rad/s.
    assert door.angular_velocity.z == pytest.approx(-1.0, abs=1e-2)
    hinge.set_motor(False, 0.0, 0.0)
    assert hinge.motor.enabled is False
    hinge.set_limits(True, -0.5, 0.5)
    assert hinge.limits == (True, pytest.approx(-0.5), pytest.approx(0.5))
    hinge.set_spring(True, 2.0, 0.5)
    assert hinge.spring == (True, pytest.approx(2.0), pytest.approx(0.5))
    with pytest.raises(hearth.InvalidArgument):
        hinge.set_cone_limit(True, 0.5)  # not a ball joint: the library says so
    with pytest.raises(hearth.InvalidArgument):
        hinge.set_limits(True, 0.5, -0.5)


def test_distance_fixed_and_slider_joints(world):
    a = world.create_body("dynamic", position=(0.0, 5.0, 0.0))
    a.add_sphere(radius=0.2)
    b = world.create_body("dynamic", position=(2.0, 5.0, 0.0))
    b.add_sphere(radius=0.2)
    world.create_distance_joint(a, b, length=2.0)
    world.create_fixed_joint(a, frame_b=(0.0, 5.0, 0.0))  # welds A to the world where it is
    for _ in range(60):
        world.step(DT)
    assert a.position == pytest.approx((0.0, 5.0, 0.0), abs=1e-2)
    assert distance(a.position, b.position) == pytest.approx(2.0, abs=1e-2)

    c = world.create_body("dynamic", position=(5.0, 5.0, 0.0))
    c.add_box(half_extents=(0.2, 0.2, 0.2))
    slider = world.create_slider_joint(c, None, frame_b=(5.0, 5.0, 0.0))
    assert slider.type is hearth.JointType.SLIDER
    c.linear_velocity = (1.0, 1.0, 1.0)
    for _ in range(30):
        world.step(DT)
    assert c.position.x == pytest.approx(5.0, abs=1e-2) and c.position.y == pytest.approx(5.0, abs=1e-2)
    assert c.position.z > 0.2  # free along Z only


def test_a_weak_joint_breaks_and_is_reported(world):
    heavy = world.create_body("dynamic")
    heavy.add_box(half_extents=(0.5, 0.5, 0.5))  # 1000 kg
    joint = world.create_ball_joint(heavy, break_force=10.0)
    world.step(DT)
    assert joint.is_broken
    assert world.broken_joints == [joint]
    world.step(DT)
    assert world.broken_joints == []
    joint.destroy()
    with pytest.raises(hearth.InvalidId):
        joint.is_broken


def test_joint_errors_come_from_the_library(world):
    static = world.create_body()
    with pytest.raises(hearth.InvalidArgument):
        world.create_ball_joint(static)  # both sides static
    body = world.create_body("dynamic")
    body.destroy()
    with pytest.raises(hearth.InvalidId):
        world.create_hinge_joint(body)


# ------------------------------------------------------------------------------- generators


def test_built_in_generators(world):
    world.gravity = (0.0, 0.0, 0.0)
    body = world.create_body("dynamic", position=(2.0, 0.0, 0.0))
    body.add_sphere(radius=0.1)
    spring = world.create_spring_generator(other=(0.0, 0.0, 0.0), rest_length=0.0, stiffness=10.0)
    assert spring.type is hearth.GeneratorType.SPRING
    spring.attach(body)
    world.step(DT)
    assert body.linear_velocity.x < 0.0  # pulled toward the anchor

    up = world.create_gravity_generator(acceleration=(0.0, 3.0, 0.0))
    p = world.create_particle()
    up.attach(p)
    world.step(DT)
    assert p.velocity.y == pytest.approx(3.0 * DT, rel=1e-3)

    drag = world.create_drag_generator(k1=1.0, k2=0.0)
    assert drag.attachment_count == (0, 0)
    q = world.create_particle(velocity=(10.0, 0.0, 0.0))
    drag.attach(q)
    world.step(DT)
    assert 0.0 < q.velocity.x < 10.0

    for gen in (
        world.create_bungee_generator(other=body),
        world.create_stiff_spring_generator(anchor=(body, (0.0, 0.1, 0.0))),
        world.create_buoyancy_generator(),
        world.create_explosion_generator(center=(0.0, 0.0, 0.0), affect_all=False),
    ):
        gen.attach(p)
    world.step(DT)
    with pytest.raises(hearth.InvalidArgument):
        world.create_drag_generator(k1=-1.0)


def test_rods_and_cables_link_particles(world):
    a = world.create_particle(position=(0.0, 5.0, 0.0), inverse_mass=0.0)  # pinned
    b = world.create_particle(position=(1.0, 5.0, 0.0))
    rod = world.create_rod_generator(a=a, b=b, length=1.0)
    assert rod.type is hearth.GeneratorType.ROD
    c = world.create_particle(position=(0.0, 3.0, 0.0))
    world.create_cable_generator(a=a, b=hearth.link_end(c), max_length=2.5)
    for _ in range(60):
        world.step(DT)
    assert distance(a.position, b.position) == pytest.approx(1.0, abs=1e-4)
    assert distance(a.position, c.position) <= 2.5 + 1e-3
    with pytest.raises(hearth.InvalidArgument):
        rod.attach(b)  # rods take no attachments


# -------------------------------------------------------------------------------- particles


def test_particle_falls_and_lands(world):
    ground(world)
    p = world.create_particle(position=(0.0, 2.0, 0.0), radius=0.05, user_data=7)
    assert p.user_data == 7
    world.step(DT)
    assert p.velocity.y == pytest.approx(-9.81 * DT, rel=1e-3)
    for _ in range(120):
        world.step(DT)
    assert p.position.y == pytest.approx(0.05, abs=1e-2)
    p.position = (0.0, 1.0, 0.0)
    p.velocity = (0.0, 0.0, 1.0)
    assert p.position == pytest.approx((0.0, 1.0, 0.0)) and p.velocity == pytest.approx((0.0, 0.0, 1.0))
    p.apply_impulse((0.0, 0.0, -1.0))  # 1 kg: dv = -1
    assert p.velocity == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)
    p.apply_force((0.0, 1.0, 0.0))
    p.set_awake(False)
    assert not p.is_awake
    p.destroy()
    with pytest.raises(hearth.InvalidId):
        p.position


def test_bursts_and_expiry(world):
    default_count = hearth.lib.hearth_burst_def_default().count
    sparks = world.emit_burst(position=(0.0, 1.0, 0.0), seed=3)
    assert len(sparks) == default_count == world.particle_count
    short = world.emit_burst(count=4, lifetime_min=0.01, lifetime_max=0.01, particle={"user_data": 99})
    assert len(short) == 4
    world.step(DT)
    expired = world.expired_particles
    assert sorted(e.particle.id for e in expired) == sorted(p.id for p in short)
    assert all(e.user_data == 99 for e in expired)
    assert world.particle_count == default_count
    world.step(DT)
    assert world.expired_particles == []
    with pytest.raises(hearth.InvalidArgument):
        world.emit_burst(direction=(0.0, 0.0, 0.0))


def test_attach_particles_is_all_or_nothing(world):
    gen = world.create_drag_generator()
    ps = [world.create_particle() for _ in range(3)]
    ps[1].destroy()
    with pytest.raises(hearth.InvalidId):
        gen.attach_particles(ps)
    assert gen.attachment_count == (0, 0)
    gen.attach_particles([ps[0], ps[2]])
    assert gen.attachment_count == (0, 2)
    world.set_particle_iterations(4, 2)
    with pytest.raises(hearth.InvalidArgument):
        world.set_particle_iterations(0, 2)


# ------------------------------------------------------------------------------ soft bodies


def test_pressurised_ball_rests_and_keeps_its_volume(world):
    ground(world)
    ball = world.create_soft_body_icosphere(0.5, 3, position=(0.0, 1.5, 0.0), pressure=400.0, user_data=5)
    assert world.soft_body_count == 1
    assert ball.user_data == 5 and ball.pressure == pytest.approx(400.0)
    assert ball.mass == pytest.approx(hearth.lib.hearth_soft_body_def_default().mass, rel=1e-5)
    rest = ball.rest_volume
    assert rest == pytest.approx(4.0 / 3.0 * math.pi * 0.5**3, rel=0.05)
    # At the default (inextensible) skin the gas makes a hard ball: it bounces for a few
    # seconds before the deformation damping has it rest. The skin keeps its rest area
    # against the gas, so the gas holds it at its rest volume (0.05 % under measured).
    for _ in range(480):
        world.step(DT)
    inflated = ball.volume
    assert inflated == pytest.approx(rest, rel=0.005)
    for _ in range(30):
        world.step(DT)
    assert ball.volume == pytest.approx(inflated, rel=0.02)
    assert 0.3 < ball.center.y < 0.6
    ball.pressure = 0.0
    with pytest.raises(hearth.InvalidArgument):
        ball.pressure = -1.0
    ball.destroy()
    assert world.soft_body_count == 0


def test_pinned_cloth_hangs(world):
    cloth = world.create_soft_body_cloth(1.0, 1.0, 4, 4, position=(0.0, 2.0, 0.0))
    assert cloth.vertex_count == 25
    cloth.pin_vertex(0)
    cloth.pin_vertex(4)
    assert cloth.is_vertex_pinned(0) and not cloth.is_vertex_pinned(1)
    pinned = cloth.vertex_position(0)
    for _ in range(60):
        world.step(DT)
    assert cloth.vertex_position(0) == pytest.approx(pinned)
    assert cloth.vertex_position(24).y < 1.9  # the free edge swings down
    cloth.unpin_vertex(0)
    assert not cloth.is_vertex_pinned(0)
    with pytest.raises(hearth.InvalidArgument):
        cloth.pin_vertex(25)  # out of range


def test_soft_mesh_from_python_lists(world):
    world.gravity = (0.0, 0.0, 0.0)
    vertices = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
    indices = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    tet = world.create_soft_body_mesh(vertices, indices, masses=[1.0, 2.0, 3.0, 4.0], damping=0.0)
    assert (tet.vertex_count, tet.triangle_count) == (4, 4)
    assert list(tet.get_indices()) == [i for tri in indices for i in tri]
    assert tet.mass == pytest.approx(10.0)
    assert tet.volume == pytest.approx(1.0 / 6.0, rel=1e-5)
    tet.apply_impulse_all((10.0, 0.0, 0.0))  # dv = J / total mass
    world.step(DT)
    assert tet.vertex_velocity(0).x == pytest.approx(1.0, rel=1e-3)
    tet.apply_impulse(3, (0.0, 4.0, 0.0))
    with pytest.raises(ValueError):
        world.create_soft_body_mesh(vertices, indices, masses=[1.0])
    with pytest.raises(hearth.InvalidArgument):
        world.create_soft_body_mesh(vertices, [(0, 0, 1)])  # a triangle repeating a vertex
    box = world.create_soft_body_box((0.5, 0.5, 0.5), (2, 2, 2))
    assert box.vertex_count == 27


def _def_values(**fields):
    """The settings fields of a HearthSoftBodyDef fresh from its default with `fields` applied."""
    sd = hearth.lib.hearth_soft_body_def_default()
    for name, value in fields.items():
        setattr(sd, name, value)
    values = {name: getattr(sd, name) for name in hearth.SoftBodySettings._fields}
    values["preserve_volume"] = bool(values["preserve_volume"])
    values["collide"] = bool(values["collide"])
    return hearth.SoftBodySettings(**values)


def test_soft_body_def_has_the_documented_defaults():
    sd = hearth.lib.hearth_soft_body_def_default()
    assert sd.deformation_damping == pytest.approx(2.0)
    assert (sd.substeps, sd.iterations, sd.collide) == (20, 2, 1)
    assert sd.damping == pytest.approx(0.5) and sd.bend_compliance == pytest.approx(0.01)


def test_soft_settings_are_the_def_given_at_creation(world):
    plain = world.create_soft_body_cloth(1.0, 1.0, 2, 2)
    assert plain.settings == _def_values()
    fields = dict(
        edge_compliance=1e-4,
        bend_compliance=math.inf,
        preserve_volume=1,
        volume_compliance=0.01,
        pressure=30.0,
        damping=0.25,
        deformation_damping=3.5,
        friction=0.8,
        restitution=0.1,
        vertex_radius=0.02,
        gravity_scale=0.5,
        substeps=12,
        iterations=4,
        collide=0,
    )
    ball = world.create_soft_body_icosphere(0.5, 1, **fields)
    got = ball.settings
    assert isinstance(got, hearth.SoftBodySettings)
    assert got == _def_values(**fields)
    assert got.preserve_volume is True and got.collide is False
    assert got.iterations == 4 and got.deformation_damping == pytest.approx(3.5)
    assert ball.pressure == got.pressure


def test_soft_settings_set_then_get(world):
    ball = world.create_soft_body_icosphere(0.5, 1, position=(0.0, 2.0, 0.0))
    # values a float32 holds exactly, so that what comes back compares equal
    wanted = ball.settings._replace(
        edge_compliance=2.0**-10,
        bend_compliance=0.5,
        pressure=12.0,
        damping=1.5,
        deformation_damping=0.0,
        friction=0.125,
        vertex_radius=0.0625,
        gravity_scale=-1.0,
        substeps=64,
        iterations=16,
        preserve_volume=True,
        collide=False,
    )
    ball.settings = wanted
    assert ball.settings == wanted
    assert ball.pressure == 12.0  # the same pressure as hearth_soft_body_get_pressure
    ball.set_settings(damping=0.75, iterations=1)  # on top of the current settings
    assert ball.settings == wanted._replace(damping=0.75, iterations=1)
    ball.set_settings(wanted, substeps=1)
    assert ball.settings == wanted._replace(substeps=1)
    raw = hearth.ffi.HearthSoftBodySettings()
    hearth.lib.hearth_soft_body_get_settings(world._ptr, ball._id, raw)
    raw.friction = 2.0
    ball.set_settings(raw)
    assert ball.settings.friction == 2.0
    ball.pressure = 7.0  # the single setter shows in the settings too
    assert ball.settings.pressure == 7.0
    world.step(DT)  # the new settings run
    assert ball.center.y > 2.0  # gravity_scale -1: it rises
    with pytest.raises(TypeError):
        ball.set_settings(stiffness=1.0)
    with pytest.raises(TypeError):
        ball.set_settings({"damping": 1.0})


def test_soft_set_compliance_changes_the_settings(world):
    cloth = world.create_soft_body_cloth(1.0, 1.0, 4, 4)
    before = cloth.settings
    cloth.set_compliance(0.001, math.inf, 0.25)
    after = cloth.settings
    assert (after.edge_compliance, after.bend_compliance, after.volume_compliance) == (
        pytest.approx(0.001),
        math.inf,
        0.25,
    )
    assert after._replace(edge_compliance=0.0, bend_compliance=0.0, volume_compliance=0.0) == before._replace(
        edge_compliance=0.0, bend_compliance=0.0, volume_compliance=0.0
    )


@pytest.mark.parametrize(
    "fields",
    [
        {"damping": math.nan},
        {"deformation_damping": -1.0},
        {"deformation_damping": math.nan},
        {"friction": -0.5},
        {"pressure": math.inf},
        {"edge_compliance": math.inf},
        {"bend_compliance": math.nan},
        {"gravity_scale": math.inf},
        {"iterations": 0},
        {"iterations": 17},
        {"substeps": 0},
        {"substeps": 65},
        {"preserve_volume": 2},
        {"collide": 3},
    ],
)
def test_soft_bad_settings_are_refused_and_change_nothing(world, fields):
    ball = world.create_soft_body_icosphere(0.5, 1, deformation_damping=1.0, iterations=3)
    before = ball.settings
    with pytest.raises(hearth.InvalidArgument) as err:
        ball.set_settings(**fields)
    assert err.value.code == hearth.ffi.HEARTH_ERROR_INVALID_ARGUMENT
    assert ball.settings == before


@pytest.mark.parametrize(
    "compliance",
    [
        (math.nan, 0.0, 0.0),
        (-1.0, 0.0, 0.0),
        (0.0, -1e-3, 0.0),
        (0.0, math.nan, 0.0),
        (math.inf, 0.0, 0.0),
        (0.0, 0.0, math.inf),
    ],
)
def test_soft_bad_compliance_is_refused_and_changes_nothing(world, compliance):
    ball = world.create_soft_body_icosphere(0.5, 1)
    before = ball.settings
    with pytest.raises(hearth.InvalidArgument):
        ball.set_compliance(*compliance)
    assert ball.settings == before


def test_soft_settings_of_a_destroyed_soft_body(world):
    ball = world.create_soft_body_icosphere(0.5, 1)
    settings = ball.settings
    ball.destroy()
    with pytest.raises(hearth.InvalidId):
        ball.settings
    with pytest.raises(hearth.InvalidId):
        ball.settings = settings
    with pytest.raises(hearth.InvalidId):
        ball.set_settings(settings, damping=1.0)
    with pytest.raises(hearth.InvalidId):
        ball.set_compliance(0.0, 0.01, 0.0)
    other = world.create_soft_body_icosphere(0.5, 1)  # reuses the slot with a new generation
    assert other.id[0] == ball.id[0] and other.id != ball.id
    with pytest.raises(hearth.InvalidId):
        ball.set_compliance(0.0, 0.01, 0.0)
    assert other.settings == settings


def test_soft_settings_are_locked_during_a_step(world):
    ball = world.create_soft_body_icosphere(0.5, 1)
    body = world.create_body("dynamic")
    body.add_sphere(radius=0.1)
    seen = []

    def callback(w, ctx):
        seen.append(ball.settings)  # reading is allowed
        for change in (lambda: ball.set_compliance(0.1, 0.1, 0.1), lambda: ball.set_settings(damping=3.0)):
            with pytest.raises(hearth.WorldLocked):
                change()

    world.create_force_generator(callback).attach(body)
    before = ball.settings
    world.step(DT)
    assert seen == [before] and ball.settings == before
