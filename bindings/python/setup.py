"""Build configuration beyond pyproject.toml: the wheel's tag and a clean source tree.

* A wheel that carries the shared library (copied into hearth/ before building) holds
  platform code, so it is tagged for the platform: py3-none-<platform> (any Python 3 and no
  Python ABI, since the binding is ctypes). Without a library the wheel is pure: py3-none-any.
* setuptools writes build/ and hearth.egg-info/ into the source tree by default; here they go
  to a temporary directory removed when the build ends, so `pip install ./bindings/python`
  and `pip wheel` leave the tree as it was.
"""

import atexit
import shutil
import tempfile
from pathlib import Path

from setuptools import Distribution, setup

try:  # setuptools >= 70.1 has its own; older ones use the wheel package's
    from setuptools.command.bdist_wheel import bdist_wheel
except ImportError:  # pragma: no cover - depends on the installed setuptools
    from wheel.bdist_wheel import bdist_wheel

HERE = Path(__file__).resolve().parent
LIBRARY_FILES = ("libhearth.so", "libhearth.dylib", "hearth.dll")


def bundles_library():
    return any((HERE / "hearth" / name).is_file() for name in LIBRARY_FILES)


class LibraryDistribution(Distribution):
    """With the library inside, the package holds platform code: it is built and installed
    like a package with extension modules (platlib), not as pure Python."""

    def has_ext_modules(self):
        return bundles_library()


class PlatformWheel(bdist_wheel):
    """py3-none-<platform> when the library is inside, py3-none-any otherwise."""

    def get_tag(self):
        python, abi, platform = super().get_tag()
        if bundles_library():
            return "py3", "none", platform
        return python, abi, platform


SCRATCH = Path(tempfile.mkdtemp(prefix="hearth-python-build-"))
atexit.register(shutil.rmtree, SCRATCH, ignore_errors=True)

setup(
    distclass=LibraryDistribution,
    cmdclass={"bdist_wheel": PlatformWheel},
    options={
        "build": {"build_base": str(SCRATCH / "build")},
        "egg_info": {"egg_base": str(SCRATCH)},
    },
)
