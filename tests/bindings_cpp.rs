//! The C++ bindings, built with g++ against the freshly built library (the approach of
//! `tests/c_harness.rs`: the `cc` crate finds the compiler, the libraries are the ones next to
//! this test binary in `target/<profile>/deps`).
//!
//! * `tests/cpp/test_hearth.cpp` exercises `bindings/cpp/hearth.hpp`: linked shared and
//!   static, and built once more with `-fno-exceptions` for the no-exceptions API.
//! * `tests/cpp/test_unreal_conversion.cpp` and `tests/cpp/test_unreal_simulation.cpp` exercise
//!   the engine-independent core of the Unreal plug-in (`bindings/unreal/HearthPhysics/.../Public/`
//!   `HearthConversion.h`, `HearthSimulation.h`, `HearthShapes.h`) in a real Hearth world.
//! * `examples/cpp/pyramid.cpp` must print what `examples/c/pyramid.c` prints, line by line,
//!   except the word naming the language.
//!
//! Every program is compiled with `-std=c++17 -Wall -Wextra -Wpedantic -Werror` (C11 for the
//! C example) and, with `HEARTH_VALGRIND=1`, also run under valgrind (no errors, no leaks).

mod common;

use common::{compiler, lib_dir, link, program, root, run, run_program, Link};
use std::path::{Path, PathBuf};
use std::process::Command;

fn out_dir() -> PathBuf {
    common::out_dir("bindings_cpp")
}

/// Compiles `source` (relative to the repository root) into `exe_name`, with the C++ wrapper
/// on the include path.
fn build(source: &str, exe_name: &str, cpp: bool, linkage: Link, extra: &[&str]) -> PathBuf {
    let exe = out_dir().join(exe_name);
    let mut cmd = compiler(cpp, &out_dir());
    cmd.arg("-I").arg(root().join("bindings").join("cpp"));
    cmd.args(extra);
    cmd.arg(root().join(source)).arg("-o").arg(&exe);
    link(&mut cmd, linkage);
    run(&mut cmd);
    exe
}

/// Runs a test program; it must report " 0 failed" and at least `min_passed` checks.
fn run_test_program(exe: &Path, min_passed: u32) {
    let text = run_program(exe);
    print!("{text}");
    let line = text
        .lines()
        .find(|l| l.contains(" passed, "))
        .unwrap_or_else(|| panic!("{}: no summary line:\n{text}", exe.display()));
    assert!(line.ends_with(" 0 failed"), "{}:\n{text}", exe.display());
    let passed: u32 = line
        .split(": ")
        .last()
        .and_then(|s| s.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("cannot read the pass count in {line:?}"));
    assert!(passed >= min_passed, "{}: only {passed} checks ran", exe.display());
}

const TEST_HEARTH: &str = "tests/cpp/test_hearth.cpp";

#[test]
fn cpp_wrapper_with_the_shared_library() {
    let exe = build(TEST_HEARTH, "test_hearth_shared", true, Link::Shared, &[]);
    // It loads this build's library, not a copy elsewhere.
    let ldd = run(Command::new("ldd").env_remove("LD_LIBRARY_PATH").arg(&exe));
    let line = ldd.lines().find(|l| l.contains("libhearth.so")).unwrap_or_default();
    assert!(line.contains(&lib_dir().display().to_string()), "{ldd}");
    run_test_program(&exe, 300);
}

#[test]
fn cpp_wrapper_with_the_static_library() {
    let exe = build(TEST_HEARTH, "test_hearth_static", true, Link::Static, &[]);
    run_test_program(&exe, 300);
}

#[test]
fn cpp_wrapper_without_exceptions() {
    // `-fno-exceptions`: only the nothrow API exists, and the header must still compile.
    let exe = build(
        TEST_HEARTH,
        "test_hearth_noexcept",
        true,
        Link::Shared,
        &["-fno-exceptions"],
    );
    let text = run_program(&exe);
    print!("{text}");
    assert!(text.contains("(no exceptions): "), "{text}");
    assert!(text.trim_end().ends_with(" 0 failed"), "{text}");
    // The same with the macro instead of the compiler flag, statically linked.
    let exe = build(
        TEST_HEARTH,
        "test_hearth_nomacro_static",
        true,
        Link::Static,
        &["-DHEARTH_CPP_NO_EXCEPTIONS"],
    );
    let text = run(&mut program(&exe));
    assert!(
        text.contains("(no exceptions): ") && text.trim_end().ends_with(" 0 failed"),
        "{text}"
    );
}

/// The pyramid examples step 30 s and exit with status 1 unless every body sleeps by then.
#[test]
fn cpp_pyramid_prints_what_the_c_pyramid_prints() {
    let cpp = build("examples/cpp/pyramid.cpp", "pyramid_cpp", true, Link::Shared, &[]);
    let cpp_out = run_program(&cpp);
    print!("{cpp_out}");
    common::assert_prints_like_the_c_pyramid(&cpp_out, "C++", &out_dir());
    assert_eq!(cpp_out.lines().last(), Some("done"));
}

/// The include paths of the Unreal plug-in's engine-independent headers and the tests' stand-ins
/// for Unreal types, and `-Wshadow` (Unreal builds treat shadowed names as errors).
fn unreal_flags() -> Vec<String> {
    let public = root().join("bindings/unreal/HearthPhysics/Source/HearthPhysics/Public");
    vec![
        format!("-I{}", public.display()),
        format!("-I{}", root().join("tests/cpp").display()),
        "-Wshadow".to_string(),
    ]
}

#[test]
fn unreal_conversion_header_passes() {
    let flags = unreal_flags();
    let flags: Vec<&str> = flags.iter().map(String::as_str).collect();
    let exe = build(
        "tests/cpp/test_unreal_conversion.cpp",
        "test_unreal_conversion",
        true,
        Link::Shared,
        &flags,
    );
    run_test_program(&exe, 3000);
}

#[test]
fn unreal_simulation_core_passes() {
    // HearthSimulation.h and HearthShapes.h: frame-rate independent forces, interpolation,
    // kinematic bodies, gameplay moves, gravity, throttled errors, collision elements, convex
    // elements as hulls, complex collision as meshes (winding), landscapes as heightfields, and
    // the shared-geometry cache.
    let flags = unreal_flags();
    let flags: Vec<&str> = flags.iter().map(String::as_str).collect();
    let exe = build(
        "tests/cpp/test_unreal_simulation.cpp",
        "test_unreal_simulation",
        true,
        Link::Shared,
        &flags,
    );
    run_test_program(&exe, 50_000);
}
