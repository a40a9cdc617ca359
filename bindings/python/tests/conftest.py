"""pytest setup: import the binding from this checkout.

`cargo test --release --test bindings_python` sets HEARTH_LIBRARY to the library it just
built. Run by hand (`python3 -m pytest bindings/python/tests`), the tests fall back to
target/release/libhearth.so of this checkout when HEARTH_LIBRARY is unset.
"""

import os
import sys
from pathlib import Path

import pytest

BINDING = Path(__file__).resolve().parents[1]
ROOT = BINDING.parents[1]
sys.path.insert(0, str(BINDING))

if not os.environ.get("HEARTH_LIBRARY"):
    fallback = ROOT / "target" / "release" / "libhearth.so"
    if fallback.exists():
        os.environ["HEARTH_LIBRARY"] = str(fallback)

import hearth  # noqa: E402


@pytest.fixture
def world():
    with hearth.World() as w:
        yield w


def ground(world):
    """A static plane y <= 0."""
    body = world.create_body()
    body.add_plane(normal=(0.0, 1.0, 0.0), offset=0.0)
    return body
