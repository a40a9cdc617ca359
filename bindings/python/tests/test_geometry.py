"""Shared geometry through the binding: convex hulls, triangle meshes and heightfields, instanced
by shapes, with their errors; a box resting on a mesh floor and a hull cube on a heightfield at
their analytic heights."""

import pytest

import hearth

DT = 1.0 / 60.0
CUBE = [(x, y, z) for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)]


def grid(n):
    """A flat n × n grid of unit cells centred on the origin at y = 0, facing +y."""
    vertices = [(c - n / 2, 0.0, r - n / 2) for r in range(n + 1) for c in range(n + 1)]
    indices = []
    for r in range(n):
        for c in range(n):
            a = r * (n + 1) + c
            b, cc = a + 1, a + n + 1
            indices += [a, cc, cc + 1, a, cc + 1, b]
    return vertices, indices


def test_box_rests_on_a_mesh_floor(world):
    vertices, indices = grid(4)
    mesh = world.create_mesh(vertices, indices + [0, 0, 1])  # one degenerate triangle
    assert mesh.triangle_count == 32
    assert mesh.degenerate_count == 1
    ground = world.create_body("static")
    ground.add_mesh(mesh, scale=(2.0, 1.0, 2.0))
    box = world.create_body("dynamic", position=(0.3, 1.5, -0.2))
    box.add_box((0.5, 0.5, 0.5))
    for _ in range(240):
        world.step(DT)
    assert box.position.y == pytest.approx(0.5, abs=5e-3)  # analytic: half the box's height
    with pytest.raises(hearth.InvalidArgument, match="static or kinematic"):
        box.add_mesh(mesh)
    with pytest.raises(hearth.InvalidArgument, match="1 shape"):
        mesh.destroy()
    ground.destroy()
    mesh.destroy()
    with pytest.raises(hearth.InvalidId):
        _ = mesh.triangle_count


def test_hull_cube_rests_on_a_heightfield(world):
    hull = world.create_hull(CUBE + [(0.0, 0.0, 0.0)])
    assert hull.vertex_count == 8
    rows, columns = 6, 5
    field = world.create_heightfield(rows, columns, [0.25] * (rows * columns))
    terrain = world.create_body("static")
    terrain.add_heightfield(field, scale=(2.0, 2.0, 2.0))  # ground at y = 0.5
    cube = world.create_body("dynamic", position=(5.1, 2.0, 5.1))
    cube.add_hull(hull)
    assert cube.mass == pytest.approx(1000.0, rel=1e-5)  # 1 m³ of density 1000
    for _ in range(240):
        world.step(DT)
    assert cube.position.y == pytest.approx(1.0, abs=5e-3)
    with pytest.raises(hearth.InvalidArgument, match="1 shape"):
        hull.destroy()
    cube.destroy()
    hull.destroy()
    with pytest.raises(hearth.InvalidId):
        hull.destroy()
    with pytest.raises(hearth.InvalidArgument, match="heightfield can only be attached"):
        world.create_body("dynamic").add_heightfield(field)
    terrain.destroy()
    field.destroy()


def test_geometry_errors(world):
    with pytest.raises(hearth.InvalidArgument, match="at least 4 points"):
        world.create_hull(CUBE[:3])
    with pytest.raises(hearth.InvalidArgument, match="convex_radius"):
        world.create_hull(CUBE, convex_radius=-1.0)
    rounded = world.create_hull(CUBE, convex_radius=0.1)
    body = world.create_body("dynamic")
    with pytest.raises(hearth.InvalidArgument, match="scale"):
        body.add_hull(rounded, scale=0.0)
    with pytest.raises(hearth.InvalidArgument, match="index_count"):
        world.create_mesh(CUBE, [0, 1])
    with pytest.raises(hearth.InvalidArgument, match="index 2 is 9"):
        world.create_mesh(CUBE, [0, 1, 9])
    with pytest.raises(hearth.InvalidArgument, match="holes\\[0\\]"):
        world.create_heightfield(2, 2, [0.0] * 4, holes=[2])
    with pytest.raises(ValueError):
        world.create_heightfield(2, 2, [0.0] * 3)
    with pytest.raises(hearth.InvalidArgument, match="rows"):
        world.create_heightfield(1, 4, [0.0] * 4)
    holed = world.create_heightfield(2, 2, [0.0] * 4, holes=[1])
    holed.destroy()
    with hearth.World() as other:
        foreign = other.create_hull(CUBE)
        with pytest.raises(hearth.InvalidId):
            body.add_hull(hearth.Hull(world, foreign._id))
