#!/usr/bin/env python3
"""pyramid.py - the scene of examples/c/pyramid.c through the Python binding.

Builds a pyramid of unit boxes on a ground plane, drops a "pile" of 60 alternating spheres
and boxes onto it from a grid above, and steps 30 s at 60 Hz. Every three seconds it prints the
time, the height of the pyramid's top box and how many bodies are awake (all asleep by the
end, or it exits with status 1): the same text as
the C example, number for number (Hearth is deterministic), but for the word "Python".

Run from the repository root, after `cargo build --release`:
    HEARTH_LIBRARY=target/release/libhearth.so python3 examples/python/pyramid.py
"""

import struct
import sys
from pathlib import Path

# The binding in this repository (an installed `hearth` package needs no path).
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bindings" / "python"))

import hearth  # noqa: E402

BASE = 5  # boxes per side in the bottom layer: 25+16+9+4+1 = 55 boxes
PYRAMID_BOXES = 55
PILE_BODIES = 60  # alternating spheres (r = 0.5) and unit boxes
PILE_ROW = 8  # the pile starts as an 8 x 8 grid (60 of its 64 cells used)


def f32(x):
    """x rounded to a C float, so that the arithmetic matches the C example's exactly."""
    return struct.unpack("f", struct.pack("f", x))[0]


DT = f32(1.0 / 60.0)
STEPS = 1800  # 30 s
REPORT_EVERY = 180


def hash_state(h, bodies, transforms):
    """FNV-1a over the bits of every body's position, rotation, linear and angular velocity
    (13 floats), folded into h: the "state hash" column, as in pyramid.c."""
    for b, body in enumerate(bodies):
        state = list(transforms[7 * b : 7 * b + 7]) + list(body.linear_velocity) + list(body.angular_velocity)
        for bits in struct.unpack("<13I", struct.pack("<13f", *state)):
            h = ((h ^ bits) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return h


def main():
    with hearth.World() as world:  # gravity -9.81 y, defaults of hearth_world_def_default()
        ground = world.create_body()  # static by default
        ground.add_plane(normal=(0.0, 1.0, 0.0), offset=0.0)  # the half-space y <= 0

        def add_box(p):
            body = world.create_body(hearth.BodyType.DYNAMIC, position=p)
            body.add_box(half_extents=(0.5, 0.5, 0.5))
            return body

        def add_sphere(p):
            body = world.create_body(hearth.BodyType.DYNAMIC, position=p)
            body.add_sphere(radius=0.5)
            return body

        bodies = []
        # Pyramid: layer L has (BASE - L)^2 boxes, centred on the y axis; the last is the top.
        for layer in range(BASE):
            n = BASE - layer
            offset = f32(-0.5 * (n - 1))
            for i in range(n):
                for k in range(n):
                    bodies.append(add_box((f32(offset + i), f32(0.5 + layer), f32(offset + k))))
        top = len(bodies) - 1

        # Pile: a grid 1.5 m apart, 10 m up, centred over the pyramid.
        for j in range(PILE_BODIES):
            x = f32(-5.25 + f32(1.5 * (j % PILE_ROW)))
            z = f32(-5.25 + f32(1.5 * (j // PILE_ROW)))
            p = (x, 10.0, z)
            bodies.append(add_sphere(p) if j % 2 == 0 else add_box(p))

        print(
            f"Hearth {hearth.VERSION_MAJOR}.{hearth.VERSION_MINOR}.{hearth.VERSION_PATCH} Python example: "
            f"pyramid of {PYRAMID_BOXES} boxes (base {BASE}) + pile of {PILE_BODIES} spheres/boxes"
        )
        print("%8s %14s %16s %8s" % ("t [s]", "top box y [m]", "state hash", "awake"))
        state_hash = 0xCBF29CE484222325

        ids = hearth.body_ids(bodies)  # built once, reused every report
        transforms = None  # caller-owned, filled in one call per report
        awake = len(bodies)
        for step in range(1, STEPS + 1):
            world.step(DT)
            transforms = world.get_transforms(ids, out=transforms)
            state_hash = hash_state(state_hash, bodies, transforms)  # after every step
            if step % REPORT_EVERY != 0:
                continue
            transforms = world.get_transforms(ids, out=transforms)
            awake = sum(1 for body in bodies if body.is_awake)
            t = f32(step * DT)
            top_y = transforms[7 * top + 1]  # 7 floats per transform: position x, y, z, rotation
            print("%8.2f %14.3f %016x %4d/%d" % (t, top_y, state_hash, awake, len(bodies)))

    if awake != 0:
        print(f"error: {awake} bodies still awake after {STEPS} steps", file=sys.stderr)
        return 1
    print("done")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except hearth.HearthError as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
