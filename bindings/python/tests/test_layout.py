"""Every mirrored struct has the size, alignment and field offsets a C compiler gives it.

A tiny C program generated from the parsed header prints sizeof, _Alignof and offsetof of
every struct and field; it is compiled with the system C compiler (`cc`, or $CC) against
include/hearth.h and compared with ctypes.
"""

import ctypes
import os
import shutil
import subprocess

import c_header
import pytest

from hearth import _ffi

HEADER = c_header.parse()


@pytest.fixture(scope="module")
def c_layout(tmp_path_factory):
    compiler = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc")
    if not compiler:
        pytest.skip("no C compiler (cc) to measure the C layout with")
    lines = ["#include <stdio.h>", "#include <stddef.h>", '#include "hearth.h"', "int main(void) {"]
    for name, fields in HEADER.structs.items():
        lines.append(f'    printf("{name} %zu %zu\\n", sizeof({name}), _Alignof({name}));')
        for f in fields:
            lines.append(f'    printf("{name}.{f.name} %zu\\n", offsetof({name}, {f.name}));')
    lines += ["    return 0;", "}"]
    d = tmp_path_factory.mktemp("layout")
    src, exe = d / "layout.c", d / "layout"
    src.write_text("\n".join(lines) + "\n")
    subprocess.run(
        [compiler, "-std=c11", "-I", str(c_header.HEADER.parent), str(src), "-o", str(exe)],
        check=True,
        capture_output=True,
    )
    out = subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout
    layout = {}
    for line in out.splitlines():
        key, *numbers = line.split()
        layout[key] = tuple(int(n) for n in numbers)
    return layout


@pytest.mark.parametrize("name", sorted(HEADER.structs))
def test_struct_layout_matches_c(c_layout, name):
    mirror = getattr(_ffi, name)
    assert (ctypes.sizeof(mirror), ctypes.alignment(mirror)) == c_layout[name], f"sizeof/alignof {name}"
    for f in HEADER.structs[name]:
        assert getattr(mirror, f.name).offset == c_layout[f"{name}.{f.name}"][0], f"offsetof({name}, {f.name})"
