//! The C++ bindings, built with g++ against the freshly built library (the approach of
//! `tests/c_harness.rs`: the `cc` crate finds the compiler, the libraries are the ones next to
//! this test binary in `target/<profile>/deps`).
//!
//! * `tests/cpp/test_hearth.cpp` exercises `bindings/cpp/hearth.hpp`: linked shared and
//!   static, and built once more with `-fno-exceptions` for the no-exceptions API.
//! * `tests/cpp/test_unreal_conversion.cpp` exercises the engine-independent header of the
//!   Unreal plug-in (`bindings/unreal/HearthPhysics/.../HearthConversion.h`).
//! * `examples/cpp/pyramid.cpp` must print what `examples/c/pyramid.c` prints, line by line,
//!   except the word naming the language.
//!
//! Every program is compiled with `-std=c++17 -Wall -Wextra -Wpedantic -Werror` (C11 for the
//! C example) and, with `HEARTH_VALGRIND=1`, also run under valgrind (no errors, no leaks).

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `target/<profile>/deps`, where this build put `libhearth.so` and `libhearth.a`.
fn lib_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let dir = exe.parent().unwrap().to_path_buf();
    for lib in ["libhearth.so", "libhearth.a"] {
        assert!(dir.join(lib).exists(), "{lib} missing in {}", dir.display());
    }
    dir
}

fn out_dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bindings_cpp");
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn triple() -> String {
    format!("{}-unknown-linux-gnu", std::env::consts::ARCH)
}

/// The C or C++ compiler with the project's warning flags and include paths.
fn compiler(cpp: bool) -> Command {
    let mut b = cc::Build::new();
    b.cargo_metadata(false)
        .cargo_warnings(false)
        .opt_level(1)
        .debug(true)
        .host(&triple())
        .target(&triple())
        .out_dir(out_dir())
        .cpp(cpp)
        .warnings(true)
        .extra_warnings(true)
        .warnings_into_errors(true);
    let mut cmd = b.get_compiler().to_command();
    cmd.arg(if cpp { "-std=c++17" } else { "-std=c11" });
    cmd.arg("-Wpedantic");
    cmd.arg("-I").arg(root().join("include"));
    cmd.arg("-I").arg(root().join("bindings").join("cpp"));
    cmd
}

/// A command for a built program. Cargo's LD_LIBRARY_PATH lists `target/<profile>` first,
/// where an older `cargo build` may have left a stale libhearth.so; it would win over the
/// program's RUNPATH, so it is removed and the program loads the library it was linked for.
fn program(exe: &Path) -> Command {
    let mut cmd = Command::new(exe);
    cmd.env_remove("LD_LIBRARY_PATH");
    cmd
}

fn run(cmd: &mut Command) -> String {
    let out = cmd.output().unwrap_or_else(|e| panic!("cannot run {cmd:?}: {e}"));
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "{cmd:?} failed:\n{text}");
    text
}

#[derive(Clone, Copy)]
enum Link {
    Shared,
    Static,
}

/// Compiles `source` (relative to the repository root) into `exe_name`.
fn build(source: &str, exe_name: &str, cpp: bool, link: Link, extra: &[&str]) -> PathBuf {
    let exe = out_dir().join(exe_name);
    let lib = lib_dir();
    let mut cmd = compiler(cpp);
    cmd.args(extra);
    cmd.arg(root().join(source)).arg("-o").arg(&exe);
    match link {
        Link::Shared => {
            cmd.arg("-L")
                .arg(&lib)
                .arg("-lhearth")
                .arg(format!("-Wl,-rpath,{}", lib.display()));
        }
        Link::Static => {
            cmd.arg(lib.join("libhearth.a")).args(["-lpthread", "-ldl"]);
        }
    }
    cmd.arg("-lm");
    run(&mut cmd);
    exe
}

/// Runs a program (and, with `HEARTH_VALGRIND=1`, runs it again under valgrind); returns
/// its output.
fn run_program(exe: &Path) -> String {
    let text = run(&mut program(exe));
    if std::env::var("HEARTH_VALGRIND").as_deref() == Ok("1") {
        let v = run(Command::new("valgrind")
            .env_remove("LD_LIBRARY_PATH")
            .args([
                "--error-exitcode=99",
                "--leak-check=full",
                "--show-leak-kinds=definite,indirect,possible",
                "--errors-for-leak-kinds=definite,indirect,possible",
                "--track-origins=yes",
                "-q",
            ])
            .arg(exe));
        assert_eq!(
            v.replace('\r', ""),
            text.replace('\r', ""),
            "different output under valgrind"
        );
        println!("valgrind clean: {}", exe.display());
    }
    text
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

#[test]
fn cpp_pyramid_prints_what_the_c_pyramid_prints() {
    let c = build("examples/c/pyramid.c", "pyramid_c", false, Link::Shared, &[]);
    let cpp = build("examples/cpp/pyramid.cpp", "pyramid_cpp", true, Link::Shared, &[]);
    let c_out = run(&mut program(&c));
    let cpp_out = run_program(&cpp);
    print!("{cpp_out}");
    let c_lines: Vec<&str> = c_out.lines().collect();
    let cpp_lines: Vec<&str> = cpp_out.lines().collect();
    assert_eq!(c_lines.len(), cpp_lines.len(), "C:\n{c_out}\nC++:\n{cpp_out}");
    assert!(c_lines.len() >= 8, "too short:\n{c_out}");
    assert!(c_lines[0].contains(" C example: "), "{}", c_lines[0]);
    assert_eq!(
        cpp_lines[0],
        c_lines[0].replace(" C example: ", " C++ example: "),
        "first line"
    );
    for (i, (a, b)) in c_lines.iter().zip(&cpp_lines).enumerate().skip(1) {
        assert_eq!(a, b, "line {} differs", i + 1);
    }
    assert_eq!(cpp_lines.last(), Some(&"done"));
}

#[test]
fn unreal_conversion_header_passes() {
    let public = root().join("bindings/unreal/HearthPhysics/Source/HearthPhysics/Public");
    let include = format!("-I{}", public.display());
    let exe = build(
        "tests/cpp/test_unreal_conversion.cpp",
        "test_unreal_conversion",
        true,
        Link::Shared,
        &[&include],
    );
    run_test_program(&exe, 3000);
}
