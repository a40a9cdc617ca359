"""Threads and the world state hash (issue 15): `worker_count` gives bit-identical results."""

import pytest
from conftest import ground

import hearth

DT = 1.0 / 60.0


def _pile_hash(**settings):
    """Hash of 200 spheres and boxes dropped in a grid onto a plane, after 30 steps."""
    with hearth.World(**settings) as w:
        ground(w)
        for i in range(200):
            body = w.create_body(
                "dynamic", position=((i % 10) * 1.05 - 5.0, 0.5 + (i // 10 % 4) * 1.1, (i // 40) * 1.05)
            )
            if i % 2:
                body.add_box(half_extents=(0.5, 0.5, 0.5))
            else:
                body.add_sphere(radius=0.5)
        before = w.state_hash
        for _ in range(30):
            w.step(DT)
        assert w.state_hash != before, "the pile moved"
        return w.state_hash


def test_worker_counts_give_the_same_hash():
    assert hearth.lib.hearth_world_def_default().worker_count == 1
    one = _pile_hash()
    assert one == _pile_hash(), "twice in a process"
    for n in (2, 3):
        assert _pile_hash(worker_count=n) == one


def test_worker_count_outside_one_to_sixty_four_is_refused():
    for bad in (0, 65):
        with pytest.raises(hearth.InvalidArgument) as e:
            hearth.World(worker_count=bad)
        assert "worker_count" in e.value.message


def test_the_hash_of_a_closed_world_is_a_null_pointer_error():
    w = hearth.World()
    w.close()
    with pytest.raises(hearth.NullPointer):
        w.state_hash
