#!/usr/bin/env bash
# install.sh - installs Hearth for C and C++ consumers.
#
# Linux:
#   PREFIX/lib/libhearth.so.X.Y.Z                      the shared library (SONAME libhearth.so.ABI)
#   PREFIX/lib/libhearth.so.ABI -> libhearth.so.X.Y.Z  what programs load
#   PREFIX/lib/libhearth.so -> libhearth.so.ABI        what -lhearth finds when linking
#   PREFIX/lib/libhearth.a                             the static library
#   PREFIX/lib/.debug/libhearth.so.X.Y.Z.debug         debug info, split off (only when the
#                                                      build had any: --profile release-with-debug)
# Windows (a library directory holding hearth.dll):
#   PREFIX/bin/hearth.dll
#   PREFIX/lib/hearth.dll.lib, PREFIX/lib/hearth.lib   MSVC build (`cargo build --release` on Windows)
#   PREFIX/lib/libhearth.dll.a, PREFIX/lib/libhearth.a MinGW build (--target x86_64-pc-windows-gnu)
# Both:
#   PREFIX/include/hearth.h, PREFIX/include/hearth.hpp
#   PREFIX/lib/pkgconfig/hearth.pc, hearth-static.pc   (pkg-config hearth / hearth-static; not MSVC)
#   PREFIX/lib/cmake/hearth/hearthConfig.cmake         (find_package(hearth X.Y): hearth::hearth,
#   PREFIX/lib/cmake/hearth/hearthConfigVersion.cmake   hearth::hearth_static)
#
# ABI = the major version, or 0.MINOR while the major is 0 (every 0.x minor may break the ABI,
# as Cargo treats it): version 0.2.0 installs libhearth.so.0.2.0 with SONAME libhearth.so.0.2.
#
# Usage: bindings/packaging/install.sh --prefix DIR [--lib-dir DIR | --target TRIPLE] [--keep-debug]
#   --prefix DIR      where to install (created if missing).
#   --lib-dir DIR     take the built libraries from DIR (target/release, target/<triple>/release,
#                     or a copy of them) instead of running cargo.
#   --target TRIPLE   run `cargo build --release --target TRIPLE` first and install its output
#                     (x86_64-pc-windows-gnu needs mingw-w64).
#   --keep-debug      install the libraries as built: no debug-info split, no stripping of the
#                     static library (it otherwise loses its debug info and LLVM bitcode).
#
# Without --lib-dir or --target it runs `cargo build --release` and installs target/release.
# The installed tree is relocatable: hearthConfig.cmake and the .pc files find the prefix from
# their own location, so the directory may be moved or packaged after installing.
set -euo pipefail

usage() {
    sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'
    exit "${1:-0}"
}

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
prefix=""
lib_dir=""
target=""
keep_debug=0
while [ $# -gt 0 ]; do
    case "$1" in
        --prefix) prefix=${2:?--prefix needs a directory}; shift 2 ;;
        --prefix=*) prefix=${1#--prefix=}; shift ;;
        --lib-dir) lib_dir=${2:?--lib-dir needs a directory}; shift 2 ;;
        --lib-dir=*) lib_dir=${1#--lib-dir=}; shift ;;
        --target) target=${2:?--target needs a target triple}; shift 2 ;;
        --target=*) target=${1#--target=}; shift ;;
        --keep-debug) keep_debug=1; shift ;;
        -h|--help) usage 0 ;;
        *) echo "install.sh: unknown argument: $1" >&2; usage 2 >&2 ;;
    esac
done
[ -n "$prefix" ] || { echo "install.sh: --prefix is required" >&2; usage 2 >&2; }
if [ -n "$lib_dir" ] && [ -n "$target" ]; then
    echo "install.sh: --lib-dir and --target exclude each other" >&2
    exit 2
fi

if [ -z "$lib_dir" ]; then
    if [ -n "$target" ]; then
        (cd "$root" && cargo build --release --target "$target")
        lib_dir="$root/target/$target/release"
    else
        (cd "$root" && cargo build --release)
        lib_dir="$root/target/release"
    fi
fi

# What was built decides the layout.
if [ -f "$lib_dir/hearth.dll" ] && [ -f "$lib_dir/hearth.dll.lib" ]; then
    platform=msvc
    needed=(hearth.dll hearth.dll.lib hearth.lib)
elif [ -f "$lib_dir/hearth.dll" ]; then
    platform=mingw
    needed=(hearth.dll libhearth.dll.a libhearth.a)
else
    platform=linux
    needed=(libhearth.so libhearth.a)
fi
for f in "${needed[@]}"; do
    [ -f "$lib_dir/$f" ] || { echo "install.sh: $lib_dir/$f not found (build first, or pass --lib-dir)" >&2; exit 1; }
done

# The version of the crate, which build.rs also writes into the header.
version=$(sed -n 's/^version *= *"\([^"]*\)".*/\1/p' "$root/Cargo.toml" | head -n 1)
[ -n "$version" ] || { echo "install.sh: no version in $root/Cargo.toml" >&2; exit 1; }
major=${version%%.*}
minor=$(echo "$version" | cut -d. -f2)
if [ "$major" = "0" ]; then abi="0.$minor"; else abi="$major"; fi

mkdir -p "$prefix"
prefix=$(cd "$prefix" && pwd)
install -d "$prefix/lib/cmake/hearth" "$prefix/include"
install -m 644 "$root/include/hearth.h" "$prefix/include/hearth.h"
install -m 644 "$root/bindings/cpp/hearth.hpp" "$prefix/include/hearth.hpp"

# strip_static ARCHIVE OBJCOPY: drops debug info and the LLVM bitcode Rust's standard library
# carries for link-time optimisation (C linkers never read it): 30 MB -> 12 MB on Linux.
# Rust's MinGW archives also hold split-DWARF members (*.dwo) with no sections, which objcopy
# refuses: they are removed first. On failure the archive is installed as built, with a warning.
strip_static() {
    [ "$keep_debug" = 1 ] && return 0
    if ! command -v "$2" >/dev/null 2>&1; then
        echo "install.sh: $2 not found; $1 keeps its debug info" >&2
        return 0
    fi
    local work="$1.stripping" log
    cp "$1" "$work"
    # (binutils' LLVM plugin complains about Rust's newer bitcode on stderr: harmless.)
    local dwo
    dwo=$(ar t "$work" 2>/dev/null | grep '\.dwo$' || true)
    if [ -n "$dwo" ]; then
        # shellcheck disable=SC2086 # one member name per word
        ar d "$work" $dwo >/dev/null 2>&1
    fi
    if log=$("$2" --strip-debug --remove-section=.llvmbc --remove-section=.llvmcmd "$work" 2>&1); then
        mv "$work" "$1"
    else
        rm -f "$work"
        echo "install.sh: could not strip $1 ($(printf '%s\n' "$log" | grep -v 'bfd plugin' | tail -n 1)); installed as built" >&2
    fi
}

case "$platform" in
linux)
    real="libhearth.so.$version"
    install -m 755 "$lib_dir/libhearth.so" "$prefix/lib/$real"
    soname=$(objdump -p "$prefix/lib/$real" 2>/dev/null | sed -n 's/^ *SONAME *//p')
    if [ "$soname" != "libhearth.so.$abi" ]; then
        echo "install.sh: $lib_dir/libhearth.so has SONAME '$soname', expected libhearth.so.$abi (built by an older build.rs?)" >&2
        exit 1
    fi
    ln -sfn "$real" "$prefix/lib/libhearth.so.$abi"
    ln -sfn "libhearth.so.$abi" "$prefix/lib/libhearth.so"
    if [ "$keep_debug" = 0 ] && objdump -h "$prefix/lib/$real" | grep -q ' \.debug_info '; then
        # Split the debug info off (GDB finds it through the debug link in .debug/).
        install -d "$prefix/lib/.debug"
        objcopy --only-keep-debug "$prefix/lib/$real" "$prefix/lib/.debug/$real.debug"
        objcopy --strip-debug --add-gnu-debuglink="$prefix/lib/.debug/$real.debug" "$prefix/lib/$real"
        echo "split debug info into lib/.debug/$real.debug"
    fi
    install -m 644 "$lib_dir/libhearth.a" "$prefix/lib/libhearth.a"
    strip_static "$prefix/lib/libhearth.a" objcopy
    static_libs="-lpthread -ldl -lm"
    cmake_static_libs='Threads::Threads;${CMAKE_DL_LIBS};m'
    cmake_shared="IMPORTED_LOCATION \"\${_hearth_prefix}/lib/$real\"
        IMPORTED_SONAME \"libhearth.so.$abi\""
    cmake_static_file=libhearth.a
    ;;
mingw|msvc)
    install -d "$prefix/bin"
    install -m 755 "$lib_dir/hearth.dll" "$prefix/bin/hearth.dll"
    if [ "$platform" = mingw ]; then
        implib=libhearth.dll.a
        cmake_static_file=libhearth.a
    else
        implib=hearth.dll.lib
        cmake_static_file=hearth.lib
    fi
    install -m 644 "$lib_dir/$implib" "$prefix/lib/$implib"
    install -m 644 "$lib_dir/$cmake_static_file" "$prefix/lib/$cmake_static_file"
    [ "$platform" = mingw ] && strip_static "$prefix/lib/libhearth.a" x86_64-w64-mingw32-objcopy
    # What Rust's standard library needs from Windows (rustc --print native-static-libs).
    static_libs="-lkernel32 -lntdll -luserenv -lws2_32 -ldbghelp"
    cmake_static_libs="kernel32;ntdll;userenv;ws2_32;dbghelp"
    cmake_shared="IMPORTED_LOCATION \"\${_hearth_prefix}/bin/hearth.dll\"
        IMPORTED_IMPLIB \"\${_hearth_prefix}/lib/$implib\""
    ;;
esac

# pkg-config (not for MSVC, which has no pkg-config convention): ${pcfiledir} keeps it
# relocatable. hearth.pc links the shared library; its Libs.private are what the static
# library needs in a fully static program (`cc -static ... $(pkg-config --static --libs hearth)`).
# hearth-static.pc links the static library into an otherwise dynamic program.
if [ "$platform" != msvc ]; then
    install -d "$prefix/lib/pkgconfig"
    cat > "$prefix/lib/pkgconfig/hearth.pc" <<PC
prefix=\${pcfiledir}/../..
libdir=\${prefix}/lib
includedir=\${prefix}/include

Name: hearth
Description: Hearth, a real-time 3D physics engine with a C ABI (C header hearth.h, C++17 wrapper hearth.hpp)
Version: $version
Libs: -L\${libdir} -lhearth
Libs.private: $static_libs
Cflags: -I\${includedir}
PC
    cat > "$prefix/lib/pkgconfig/hearth-static.pc" <<PC
prefix=\${pcfiledir}/../..
libdir=\${prefix}/lib
includedir=\${prefix}/include

Name: hearth-static
Description: Hearth linked statically (libhearth.a and what it needs from the system)
Version: $version
Libs: \${libdir}/libhearth.a $static_libs
Cflags: -I\${includedir}
PC
fi

cat > "$prefix/lib/cmake/hearth/hearthConfig.cmake" <<CMAKE
# hearthConfig.cmake - written by bindings/packaging/install.sh for Hearth $version ($platform).
#
#   find_package(hearth $abi REQUIRED)
#   target_link_libraries(app PRIVATE hearth::hearth)         # the shared library
#   target_link_libraries(app PRIVATE hearth::hearth_static)  # the static library (+ system libraries)
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
        $cmake_shared
        INTERFACE_INCLUDE_DIRECTORIES "\${_hearth_prefix}/include")
endif()

if(NOT TARGET hearth::hearth_static)
    add_library(hearth::hearth_static STATIC IMPORTED)
    set_target_properties(hearth::hearth_static PROPERTIES
        IMPORTED_LOCATION "\${_hearth_prefix}/lib/$cmake_static_file"
        IMPORTED_LINK_INTERFACE_LANGUAGES "C"
        INTERFACE_INCLUDE_DIRECTORIES "\${_hearth_prefix}/include"
        INTERFACE_LINK_LIBRARIES "$cmake_static_libs")
endif()

set(hearth_LIBRARIES hearth::hearth)
set(hearth_FOUND TRUE)
unset(_hearth_prefix)
CMAKE

# CMake's SameMajorVersion, with the ABI as the major: find_package(hearth X.Y) accepts this
# copy when the ABI is the same and the request is not newer. Before 1.0 the ABI is 0.MINOR:
# 0.2 and 0.2.0 are accepted by 0.2.x; 0.1, 0.3 and 1.0 are not; a bare "0" accepts any 0.x.
cat > "$prefix/lib/cmake/hearth/hearthConfigVersion.cmake" <<CMAKE
# hearthConfigVersion.cmake - written by bindings/packaging/install.sh.
set(PACKAGE_VERSION "$version")
if(PACKAGE_FIND_VERSION VERSION_GREATER PACKAGE_VERSION)
    set(PACKAGE_VERSION_COMPATIBLE FALSE)
elseif(NOT PACKAGE_FIND_VERSION_MAJOR STREQUAL "$major")
    set(PACKAGE_VERSION_COMPATIBLE FALSE)
elseif("$major" STREQUAL "0" AND PACKAGE_FIND_VERSION_COUNT GREATER 1
       AND NOT PACKAGE_FIND_VERSION_MINOR STREQUAL "$minor")
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

echo "installed Hearth $version ($platform, ABI $abi) into $prefix"
