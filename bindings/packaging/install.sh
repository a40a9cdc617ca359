#!/usr/bin/env bash
# install.sh - installs Hearth for C and C++ consumers:
#
#   PREFIX/lib/libhearth.so, PREFIX/lib/libhearth.a
#   PREFIX/include/hearth.h, PREFIX/include/hearth.hpp
#   PREFIX/lib/pkgconfig/hearth.pc                      (pkg-config hearth)
#   PREFIX/lib/cmake/hearth/hearthConfig.cmake          (find_package(hearth): hearth::hearth,
#   PREFIX/lib/cmake/hearth/hearthConfigVersion.cmake    hearth::hearth_static)
#
# Usage: bindings/packaging/install.sh --prefix DIR [--lib-dir DIR]
#   --prefix DIR   where to install (created if missing).
#   --lib-dir DIR  take libhearth.so and libhearth.a from DIR instead of running
#                  `cargo build --release` and using target/release.
#
# The installed tree is relocatable: hearthConfig.cmake and hearth.pc find the prefix from
# their own location, so the directory may be moved or packaged after installing.
set -euo pipefail

usage() {
    sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'
    exit "${1:-0}"
}

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
prefix=""
lib_dir=""
while [ $# -gt 0 ]; do
    case "$1" in
        --prefix) prefix=${2:?--prefix needs a directory}; shift 2 ;;
        --prefix=*) prefix=${1#--prefix=}; shift ;;
        --lib-dir) lib_dir=${2:?--lib-dir needs a directory}; shift 2 ;;
        --lib-dir=*) lib_dir=${1#--lib-dir=}; shift ;;
        -h|--help) usage 0 ;;
        *) echo "install.sh: unknown argument: $1" >&2; usage 2 >&2 ;;
    esac
done
[ -n "$prefix" ] || { echo "install.sh: --prefix is required" >&2; usage 2 >&2; }

if [ -z "$lib_dir" ]; then
    (cd "$root" && cargo build --release)
    lib_dir="$root/target/release"
fi
for f in libhearth.so libhearth.a; do
    [ -f "$lib_dir/$f" ] || { echo "install.sh: $lib_dir/$f not found (build first, or pass --lib-dir)" >&2; exit 1; }
done

# The version of the crate, which build.rs also writes into the header.
version=$(sed -n 's/^version *= *"\([^"]*\)".*/\1/p' "$root/Cargo.toml" | head -n 1)
[ -n "$version" ] || { echo "install.sh: no version in $root/Cargo.toml" >&2; exit 1; }
major=${version%%.*}

mkdir -p "$prefix"
prefix=$(cd "$prefix" && pwd)
install -d "$prefix/lib/pkgconfig" "$prefix/lib/cmake/hearth" "$prefix/include"
install -m 755 "$lib_dir/libhearth.so" "$prefix/lib/libhearth.so"
install -m 644 "$lib_dir/libhearth.a" "$prefix/lib/libhearth.a"
install -m 644 "$root/include/hearth.h" "$prefix/include/hearth.h"
install -m 644 "$root/bindings/cpp/hearth.hpp" "$prefix/include/hearth.hpp"

# pkg-config: ${pcfiledir} keeps it relocatable. Libs.private are what the static library
# (the Rust standard library inside it) needs: `pkg-config --static --libs hearth`.
cat > "$prefix/lib/pkgconfig/hearth.pc" <<PC
prefix=\${pcfiledir}/../..
libdir=\${prefix}/lib
includedir=\${prefix}/include

Name: hearth
Description: Hearth, a real-time 3D physics engine with a C ABI (C header hearth.h, C++17 wrapper hearth.hpp)
Version: $version
Libs: -L\${libdir} -lhearth
Libs.private: -lpthread -ldl -lm
Cflags: -I\${includedir}
PC

cat > "$prefix/lib/cmake/hearth/hearthConfig.cmake" <<CMAKE
# hearthConfig.cmake - written by bindings/packaging/install.sh for Hearth $version.
#
#   find_package(hearth $major.0 REQUIRED)
#   target_link_libraries(app PRIVATE hearth::hearth)         # libhearth.so
#   target_link_libraries(app PRIVATE hearth::hearth_static)  # libhearth.a (+ threads, dl, m)
#
# Both targets carry the include directory (hearth.h and the C++17 wrapper hearth.hpp).
# The prefix is found from this file's location, so the installed tree may be moved.
get_filename_component(_hearth_prefix "\${CMAKE_CURRENT_LIST_DIR}/../../.." ABSOLUTE)

set(hearth_VERSION "$version")
set(hearth_INCLUDE_DIRS "\${_hearth_prefix}/include")

include(CMakeFindDependencyMacro)
find_dependency(Threads)

if(NOT TARGET hearth::hearth)
    add_library(hearth::hearth SHARED IMPORTED)
    set_target_properties(hearth::hearth PROPERTIES
        IMPORTED_LOCATION "\${_hearth_prefix}/lib/libhearth.so"
        # The library has no SONAME: link it as -lhearth, not by its absolute path.
        IMPORTED_NO_SONAME TRUE
        INTERFACE_INCLUDE_DIRECTORIES "\${_hearth_prefix}/include")
endif()

if(NOT TARGET hearth::hearth_static)
    add_library(hearth::hearth_static STATIC IMPORTED)
    set_target_properties(hearth::hearth_static PROPERTIES
        IMPORTED_LOCATION "\${_hearth_prefix}/lib/libhearth.a"
        IMPORTED_LINK_INTERFACE_LANGUAGES "C"
        INTERFACE_INCLUDE_DIRECTORIES "\${_hearth_prefix}/include"
        INTERFACE_LINK_LIBRARIES "Threads::Threads;\${CMAKE_DL_LIBS};m")
endif()

set(hearth_LIBRARIES hearth::hearth)
set(hearth_FOUND TRUE)
unset(_hearth_prefix)
CMAKE

# Compatible when the major versions match and the installed version is not older (the
# ABI only breaks with a new major; see API.md rule 11). Before 1.0 the minor must match too.
cat > "$prefix/lib/cmake/hearth/hearthConfigVersion.cmake" <<CMAKE
# hearthConfigVersion.cmake - written by bindings/packaging/install.sh.
set(PACKAGE_VERSION "$version")
if(PACKAGE_FIND_VERSION VERSION_GREATER PACKAGE_VERSION)
    set(PACKAGE_VERSION_COMPATIBLE FALSE)
elseif(NOT PACKAGE_FIND_VERSION_MAJOR STREQUAL "$major")
    set(PACKAGE_VERSION_COMPATIBLE FALSE)
elseif("$major" STREQUAL "0" AND PACKAGE_FIND_VERSION_COUNT GREATER 1
       AND NOT PACKAGE_FIND_VERSION_MINOR STREQUAL "$(echo "$version" | cut -d. -f2)")
    set(PACKAGE_VERSION_COMPATIBLE FALSE)
else()
    set(PACKAGE_VERSION_COMPATIBLE TRUE)
    if(PACKAGE_FIND_VERSION STREQUAL PACKAGE_VERSION)
        set(PACKAGE_VERSION_EXACT TRUE)
    endif()
endif()
# A 64-bit library: refuse 32-bit consumers.
if(NOT CMAKE_SIZEOF_VOID_P STREQUAL "8")
    set(PACKAGE_VERSION "\${PACKAGE_VERSION} (64bit)")
    set(PACKAGE_VERSION_UNSUITABLE TRUE)
endif()
CMAKE

echo "installed Hearth $version into $prefix"
