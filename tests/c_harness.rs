//! The C harness: compiles the C programs under `tests/c/` with the `cc` crate against the
//! freshly built library and runs them. Each program includes only `include/hearth.h`.
//!
//! Also checks that the committed header matches a fresh generation, that the header
//! compiles as C11 and C++17 with warnings as errors, that the shared library exports only
//! `hearth_*` symbols, and (with `HEARTH_VALGRIND=1`) runs every program under valgrind.

mod common;

use common::{compiler, lib_dir, link, root, run, run_program, shared_lib_name, Link};
use std::path::{Path, PathBuf};
use std::process::Command;

fn out_dir() -> PathBuf {
    common::out_dir("c_harness")
}

/// Builds one C test program (as C, or as C++ with `cpp`); returns the executable.
fn build(source: &str, cpp: bool, linkage: Link) -> PathBuf {
    let name = Path::new(source).file_stem().unwrap().to_str().unwrap();
    let suffix = match (cpp, linkage) {
        (false, Link::Shared) => "c",
        (true, Link::Shared) => "cpp",
        (false, Link::Static) => "c_static",
        (true, Link::Static) => "cpp_static",
    };
    let exe = out_dir().join(format!("{name}_{suffix}"));
    let mut cmd = compiler(cpp, &out_dir());
    cmd.arg("-I").arg(root().join("tests").join("c"));
    if cpp {
        cmd.arg("-x").arg("c++");
    }
    cmd.arg(root().join("tests").join("c").join(source));
    if cpp {
        cmd.arg("-x").arg("none");
    }
    cmd.arg("-o").arg(&exe);
    link(&mut cmd, linkage);
    run(&mut cmd);
    exe
}

/// Runs a test program (see `common::run_program`); it must report no failed check.
fn run_test_program(exe: &Path) {
    let text = run_program(exe);
    assert!(text.contains(" 0 failed"), "{}:\n{text}", exe.display());
    print!("{text}");
}

const PROGRAMS: &[&str] = &[
    "test_api.c",
    "test_generators.c",
    "test_particles.c",
    "test_joints.c",
    "test_soft.c",
    "test_geometry.c",
];

#[test]
fn c_programs_pass_with_the_shared_library() {
    for p in PROGRAMS {
        run_test_program(&build(p, false, Link::Shared));
    }
}

#[test]
fn c_programs_pass_compiled_as_cpp17() {
    for p in PROGRAMS {
        run_test_program(&build(p, true, Link::Shared));
    }
}

#[test]
fn c_programs_pass_with_the_static_library() {
    for p in PROGRAMS {
        let exe = build(p, false, Link::Static);
        let text = run(&mut common::program(&exe));
        assert!(text.contains(" 0 failed"), "{text}");
    }
}

#[test]
fn header_compiles_as_c11_and_cpp17_with_warnings_as_errors() {
    let src_c = out_dir().join("header_only.c");
    std::fs::write(
        &src_c,
        "#include \"hearth.h\"\nint main(void) { return hearth_version() == HEARTH_VERSION ? 0 : 1; }\n",
    )
    .unwrap();
    let src_cpp = out_dir().join("header_only.cpp");
    std::fs::write(
        &src_cpp,
        "#include \"hearth.h\"\nint main() { HearthResult r = HEARTH_OK; return static_cast<int>(r); }\n",
    )
    .unwrap();
    run(compiler(false, &out_dir()).arg("-fsyntax-only").arg(&src_c));
    run(compiler(true, &out_dir()).arg("-fsyntax-only").arg(&src_cpp));
}

#[test]
fn committed_header_matches_a_fresh_generation() {
    let fresh = std::fs::read_to_string(Path::new(env!("OUT_DIR")).join("hearth.h")).unwrap();
    // Compare with what git has staged/committed when we are in a checkout, else the file.
    let committed = Command::new("git")
        .current_dir(root())
        .args(["show", ":include/hearth.h"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8(o.stdout).unwrap())
        .unwrap_or_else(|| std::fs::read_to_string(root().join("include/hearth.h")).unwrap());
    assert!(
        fresh == committed,
        "include/hearth.h is stale: build.rs generated a different header. Commit the regenerated include/hearth.h."
    );
}

#[test]
fn shared_library_exports_only_hearth_symbols() {
    let lib = lib_dir().join(shared_lib_name());
    let out = Command::new("nm")
        .args(["-D", "--defined-only"])
        .arg(&lib)
        .output()
        .expect("nm");
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    let mut exported = 0;
    for line in text.lines() {
        let mut parts = line.split_whitespace();
        let (Some(_addr), Some(kind), Some(name)) = (parts.next(), parts.next(), parts.next()) else {
            continue;
        };
        if !matches!(kind, "T" | "D" | "B" | "R" | "W" | "V" | "i") {
            continue;
        }
        assert!(
            name.starts_with("hearth_"),
            "unexpected exported symbol {name} ({kind})"
        );
        exported += 1;
    }
    assert!(exported >= 30, "only {exported} hearth_ symbols exported");
}
