"""Debug draw through the binding (issue 14): exact primitive counts per shape and flag, the
colours of awake and sleeping bodies, missing methods skipped, exceptions re-raised, errors."""

import pytest
from conftest import ground

import hearth

DT = 1.0 / 60.0


class Counter:
    def __init__(self):
        self.counts = {}
        self.colors = []

    def _add(self, kind, color=None):
        self.counts[kind] = self.counts.get(kind, 0) + 1
        if color is not None:
            self.colors.append(color)

    def segment(self, a, b, color):
        self._add("segment", color)

    def polygon(self, vertices, color):
        assert len(vertices) >= 3
        self._add("polygon", color)
        self.counts["polygon_vertices"] = self.counts.get("polygon_vertices", 0) + len(vertices)

    def sphere(self, center, radius, color):
        self._add("sphere", color)

    def capsule(self, a, b, radius, color):
        self._add("capsule", color)

    def transform(self, position, rotation):
        self._add("transform")

    def point(self, p, size, color):
        self._add("point", color)


def test_shapes_and_flags_draw_exact_counts(world):
    ground(world)
    box = world.create_body("dynamic", position=(0.0, 0.5, 0.0), allow_sleep=0)
    box.add_box(half_extents=(0.5, 0.5, 0.5))
    ball = world.create_body("dynamic", position=(3.0, 0.5, 0.0), allow_sleep=0)
    ball.add_sphere(0.5)
    ball.add_capsule((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), 0.2)
    c = Counter()
    world.draw(c)
    assert c.counts == {"polygon": 7, "polygon_vertices": 28, "sphere": 1, "capsule": 1}
    for _ in range(30):
        world.step(DT)
    c = Counter()
    world.draw(c, shapes=False, aabbs=True)
    assert c.counts == {"segment": 36}
    c = Counter()
    world.draw(c, shapes=False, centers_of_mass=True)
    assert c.counts == {"transform": 2}
    c = Counter()
    world.draw(c, shapes=False, contacts=True)
    assert c.counts["point"] >= 5  # four under the box, one or two under the ball and capsule


def test_colours_follow_sleep_and_missing_methods_are_skipped(world):
    body = world.create_body("dynamic", position=(0.0, 5.0, 0.0))
    body.add_sphere(0.5)

    class Spheres:
        def __init__(self):
            self.colors = []

        def sphere(self, center, radius, color):
            self.colors.append(color)

    s = Spheres()
    world.draw(s)
    body.set_awake(False)
    world.draw(s)
    assert s.colors == [0xE68C33FF, 0x8C7359FF]


def test_an_exception_in_a_drawer_is_reraised_and_errors_raise(world):
    body = world.create_body("dynamic")
    body.add_sphere(0.5)

    class Boom:
        def sphere(self, center, radius, color):
            raise RuntimeError("boom")

    with pytest.raises(RuntimeError, match="boom"):
        world.draw(Boom())
    with pytest.raises(hearth.errors.InvalidArgument):
        world.draw(Counter(), shapes=2)
    # The world is not left locked.
    world.step(DT)
