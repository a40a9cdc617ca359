"""Finding the library (HEARTH_LIBRARY, next to the package, the system path) and refusing a
library of another major version."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import hearth
from hearth import _lib

LIBRARY = Path(hearth.library_path).resolve()


def run_import(package_parent, env_library=None):
    """Imports `hearth` from `package_parent` in a fresh interpreter; returns (ok, output)."""
    env = {k: v for k, v in os.environ.items() if k not in ("HEARTH_LIBRARY", "PYTHONPATH")}
    if env_library is not None:
        env["HEARTH_LIBRARY"] = str(env_library)
    code = "import hearth; print(hearth.library_path)"
    proc = subprocess.run(
        [sys.executable, "-c", code], cwd=package_parent, env=env, capture_output=True, text=True
    )
    return proc.returncode == 0, proc.stdout.strip() + proc.stderr


@pytest.fixture
def package_copy(tmp_path):
    """A copy of the package with no library next to it."""
    shutil.copytree(Path(hearth.__file__).parent, tmp_path / "hearth", ignore=shutil.ignore_patterns("*.so"))
    return tmp_path


def test_environment_variable_names_the_library(package_copy):
    ok, out = run_import(package_copy, env_library=LIBRARY)
    assert ok, out
    assert Path(out.splitlines()[0]).resolve() == LIBRARY


def test_environment_variable_is_not_silently_ignored(package_copy):
    (package_copy / "hearth" / _lib.LIBRARY_FILE).symlink_to(LIBRARY)  # a valid copy next to it
    ok, out = run_import(package_copy, env_library=package_copy / "missing" / _lib.LIBRARY_FILE)
    assert not ok
    assert "ImportError" in out and "HEARTH_LIBRARY" in out and "missing" in out


def test_library_next_to_the_package(package_copy):
    (package_copy / "hearth" / _lib.LIBRARY_FILE).symlink_to(LIBRARY)
    ok, out = run_import(package_copy)
    assert ok, out
    assert out.splitlines()[0] == str(package_copy / "hearth" / _lib.LIBRARY_FILE)


def test_library_beside_the_package_directory(package_copy):
    (package_copy / _lib.LIBRARY_FILE).symlink_to(LIBRARY)
    ok, out = run_import(package_copy)
    assert ok, out
    assert out.splitlines()[0] == str(package_copy / _lib.LIBRARY_FILE)


def test_missing_library_names_all_three_places(package_copy):
    import ctypes.util

    if ctypes.util.find_library("hearth"):
        pytest.skip("a libhearth is installed on the system library path")
    ok, out = run_import(package_copy)
    assert not ok
    assert "ImportError" in out
    for place in ("HEARTH_LIBRARY", "next to the package", 'find_library("hearth")'):
        assert place in out, out


def test_a_different_abi_is_refused():
    ours = hearth.ffi.HEARTH_VERSION
    _lib.check_version(ours)  # same version: fine
    _lib.check_version(ours + 1)  # another patch: fine
    other_major = ((hearth.VERSION_MAJOR + 1) << 16) | (3 << 8) | 4
    with pytest.raises(ImportError) as e:
        _lib.check_version(other_major)
    message = str(e.value)
    assert f"{hearth.VERSION_MAJOR + 1}.3.4" in message and hearth.__version__ in message
    # Before 1.0 the minor is part of the ABI; from 1.0 on it is not.
    v = lambda major, minor, patch: (major << 16) | (minor << 8) | patch  # noqa: E731
    with pytest.raises(ImportError):
        _lib.check_version(v(0, 2, 0), binding_version=v(0, 1, 0))
    _lib.check_version(v(0, 1, 9), binding_version=v(0, 1, 0))
    _lib.check_version(v(1, 4, 0), binding_version=v(1, 2, 0))
    with pytest.raises(ImportError):
        _lib.check_version(v(2, 0, 0), binding_version=v(1, 2, 0))


def test_library_version_is_reported():
    assert hearth.library_version().split(".")[0] == str(hearth.VERSION_MAJOR)
