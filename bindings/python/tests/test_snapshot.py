"""Snapshots from Python: bytes out, bytes in, the same future bit for bit; ids kept; bad
bytes refused with the world unchanged; user callbacks kept or set again."""

import pytest
from conftest import ground

import hearth

DT = 1.0 / 60.0


def scene(world):
    ground(world)
    balls = []
    for i in range(5):
        b = world.create_body("dynamic", position=(0.3 * i, 1.0 + 1.1 * i, 0.0))
        b.add_sphere(radius=0.5)
        balls.append(b)
    return balls


def test_restore_then_step_replays_bit_for_bit(world):
    balls = scene(world)
    for _ in range(20):
        world.step(DT)
    snap = world.save_snapshot()
    assert isinstance(snap, bytes) and len(snap) == world.snapshot_size()
    assert snap[:8] == b"HEARTHSS"
    for _ in range(30):
        world.step(DT)
    first = [b.transform for b in balls]
    after = world.save_snapshot()
    world.restore_snapshot(snap)
    assert world.save_snapshot() == snap
    for _ in range(30):
        world.step(DT)
    assert [b.transform for b in balls] == first  # the same handles, the same poses
    assert world.save_snapshot() == after
    with hearth.World() as fresh:
        fresh.restore_snapshot(snap)
        for _ in range(30):
            fresh.step(DT)
        assert fresh.save_snapshot() == after


def test_bad_snapshots_are_refused_and_change_nothing(world):
    scene(world)
    world.step(DT)
    snap = world.save_snapshot()
    for bad in (b"", snap[:-1], snap[:40], snap + b"\0", snap[:30] + bytes([snap[30] ^ 4]) + snap[31:]):
        with pytest.raises(hearth.InvalidArgument):
            world.restore_snapshot(bad)
        assert world.save_snapshot() == snap
    other_version = snap[:8] + bytes([snap[8] + 1]) + snap[9:]
    with pytest.raises(hearth.InvalidArgument, match="version"):
        world.restore_snapshot(other_version)


def test_user_callbacks_are_kept_or_set_again(world):
    body = world.create_body("dynamic", position=(0.0, 5.0, 0.0))
    body.add_sphere(radius=0.5)
    calls = []
    gen = world.create_force_generator(lambda w, ctx: calls.append(1))
    gen.attach(body)
    snap = world.save_snapshot()
    world.restore_snapshot(snap)
    world.step(DT)
    assert len(calls) == 1 and world.generators_missing_callbacks() == []
    with hearth.World() as fresh:
        fresh.restore_snapshot(snap)
        fresh.step(DT)
        assert len(calls) == 1  # no callback: skipped
        (missing,) = fresh.generators_missing_callbacks()
        assert missing.type is hearth.GeneratorType.USER_FORCE
        fresh.set_force_callback(missing, lambda w, ctx: calls.append(2))
        fresh.step(DT)
        assert calls == [1, 2] and fresh.generators_missing_callbacks() == []
        with pytest.raises(hearth.InvalidArgument, match="generator"):
            fresh.set_contact_callback(missing, lambda w, ctx, sink: None)
