"""Recording a world for the browser viewer: into a file and through a Python callable, and the
errors of both."""

import pytest
from conftest import ground

import hearth

DT = 1.0 / 60.0


def falling_ball(world):
    body = world.create_body("dynamic", position=(0.0, 3.0, 0.0), user_data=7)
    body.add_sphere(radius=0.5)
    return body


def test_a_file_recording_grows_with_every_step_and_stops(world, tmp_path):
    ground(world)
    falling_ball(world)
    path = tmp_path / "ball.hrec"
    world.record(path, contacts=True)
    start = path.stat().st_size
    assert start > 16
    with open(path, "rb") as f:
        head = f.read(16)
    assert head[:8] == b"HEARTHRC" and head[8] == 1 and head[12] == 1  # version 1, contacts
    with pytest.raises(hearth.InvalidArgument, match="already recording"):
        world.record(path)
    for _ in range(30):
        world.step(DT)
    size = path.stat().st_size
    assert size > start + 30 * 31  # at least the falling ball's 31-byte record per step
    world.stop_recording()
    world.step(DT)
    assert path.stat().st_size == size
    with pytest.raises(hearth.InvalidArgument, match="not recording"):
        world.stop_recording()


def test_a_callable_receives_the_same_kind_of_stream(world):
    falling_ball(world)
    chunks = []
    world.record(write=chunks.append)
    assert len(chunks) == 1 and chunks[0][:8] == b"HEARTHRC"
    for _ in range(5):
        world.step(DT)
    assert len(chunks) == 6 and all(isinstance(c, bytes) for c in chunks)
    world.stop_recording()
    world.step(DT)
    assert len(chunks) == 6


def test_a_failing_callable_stops_the_recording_and_the_next_step_says_so(world):
    ball = falling_ball(world)
    calls = []

    def write(data):
        calls.append(len(data))
        if len(calls) == 3:
            raise OSError("disk full")

    world.record(write=write)
    world.step(DT)
    with pytest.raises(OSError, match="disk full"):  # re-raised by the step it happened in
        world.step(DT)
    y = ball.position.y
    with pytest.raises(hearth.Io, match="write callback returned 1"):
        world.step(DT)  # reports the failure and does not step
    assert ball.position.y == y
    world.step(DT)  # then steps again, not recording
    assert len(calls) == 3 and ball.position.y < y


def test_recording_errors_name_the_problem(world, tmp_path):
    with pytest.raises(ValueError):
        world.record()
    with pytest.raises(ValueError):
        world.record(tmp_path / "x.hrec", write=print)
    with pytest.raises(hearth.Io, match="nonexistent-dir"):
        world.record(tmp_path / "nonexistent-dir" / "x.hrec")
    with pytest.raises(hearth.InvalidArgument, match="empty"):
        world.record("")
    with pytest.raises(hearth.Io):
        world.record(write=lambda data: 1 / 0)  # the very first write fails
    with pytest.raises(hearth.InvalidArgument, match="not recording"):
        world.stop_recording()
    world.close()
    with pytest.raises(hearth.NullPointer):
        world.record(tmp_path / "y.hrec")
