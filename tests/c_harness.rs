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
    "test_record.c",
    "test_ranges.c",
    "test_geometry.c",
    "test_query.c",
    "test_events.c",
    "test_setters.c",
    "test_draw.c",
    "test_snapshot.c",
    "test_threads.c",
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
        // Under valgrind too with HEARTH_VALGRIND=1: the static link is its own binary.
        run_test_program(&build(p, false, Link::Static));
    }
}

/// The seeded fuzzer of the whole C API (`tests/c/fuzz_api.c`; its header says what it checks):
/// C11 and C++17 against the shared library and C11 against the static one (each also under
/// valgrind with `HEARTH_VALGRIND=1`). Its default run is four seeds of 1,500 calls;
/// `HEARTH_FUZZ_ITERATIONS` and `HEARTH_FUZZ_SEED` make it longer (README). A failure prints
/// the seed and the call, and `fuzz_api SEED CALLS` replays it.
#[test]
fn c_api_fuzzer_finds_no_broken_promise() {
    let mut called = String::new();
    for (cpp, linkage) in [(false, Link::Shared), (true, Link::Shared), (false, Link::Static)] {
        let exe = build("fuzz_api.c", cpp, linkage);
        let text = run_program(&exe); // every linkage under valgrind with HEARTH_VALGRIND=1
        assert!(text.contains(" 0 failed"), "{}:\n{text}", exe.display());
        called = text
            .lines()
            .find(|l| l.starts_with("fuzz_api: called"))
            .unwrap_or_default()
            .to_string();
    }
    // The run reached every function of the header.
    let called: std::collections::BTreeSet<&str> = called.split(':').nth(2).unwrap_or("").split_whitespace().collect();
    let missing: Vec<String> = header_functions()
        .into_iter()
        .filter(|f| !called.contains(f.as_str()))
        .collect();
    assert!(missing.is_empty(), "the fuzzer's default run never called {missing:?}");
}

/// Every function of the header appears in the fuzzer: a new export must be added to
/// `tests/c/fuzz_api.c`.
#[test]
fn c_api_fuzzer_covers_every_export() {
    let source = std::fs::read_to_string(root().join("tests/c/fuzz_api.c")).unwrap();
    let missing: Vec<String> = header_functions()
        .into_iter()
        .filter(|f| !source.contains(&format!("{f}(")) && !source.contains(&format!("\"{f}\"")))
        .collect();
    assert!(missing.is_empty(), "tests/c/fuzz_api.c never calls {missing:?}");
}

/// The names of the functions `include/hearth.h` declares (comments left out).
fn header_functions() -> Vec<String> {
    let text = std::fs::read_to_string(root().join("include/hearth.h")).unwrap();
    let mut code = String::new();
    let mut rest = text.as_str();
    while let Some(start) = rest.find("/*") {
        code.push_str(&rest[..start]);
        rest = rest[start..].find("*/").map_or("", |end| &rest[start + end + 2..]);
    }
    code.push_str(rest);
    let mut names = Vec::new();
    for (i, _) in code.match_indices("hearth_") {
        let name: String = code[i..]
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect();
        let after = code[i + name.len()..].trim_start();
        let before = code[..i].chars().next_back().unwrap_or(' ');
        if after.starts_with('(') && (before == ' ' || before == '*') && !names.contains(&name) {
            names.push(name);
        }
    }
    assert!(names.len() >= 100, "only {} functions found in the header", names.len());
    names
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

/// `build.rs` generates the header into `OUT_DIR` only (a build leaves the source tree as it
/// was); the committed `include/hearth.h` must equal it byte for byte. This compares file
/// contents, so it works in a git checkout, a tarball or a vendored copy alike. With
/// `HEARTH_UPDATE_HEADER=1` it writes the fresh header over the committed one instead.
#[test]
fn committed_header_matches_a_fresh_generation() {
    let fresh = std::fs::read(Path::new(env!("OUT_DIR")).join("hearth.h")).unwrap();
    let path = root().join("include").join("hearth.h");
    if std::env::var_os("HEARTH_UPDATE_HEADER").is_some_and(|v| v == "1") {
        if std::fs::read(&path).ok().as_deref() != Some(fresh.as_slice()) {
            std::fs::write(&path, &fresh).unwrap();
            println!("include/hearth.h regenerated");
        }
        return;
    }
    let committed = std::fs::read(&path).unwrap();
    assert!(
        fresh == committed,
        "include/hearth.h is stale: the header build.rs generated from src/capi differs. \
         Regenerate it with `HEARTH_UPDATE_HEADER=1 cargo test --release --test c_harness \
         committed_header` and commit it."
    );
}

/// A build must not write into the source tree: build.rs only writes below OUT_DIR (and the
/// SONAME links in the target directory). Checked on its source, as any write it made to the
/// committed header would be invisible to the comparison above.
#[test]
fn build_script_writes_only_into_out_dir() {
    let build = std::fs::read_to_string(root().join("build.rs")).unwrap();
    let writes: Vec<&str> = build.lines().filter(|l| l.contains("fs::write(")).collect();
    assert_eq!(writes.len(), 1, "{writes:?}");
    let body = &build[build.find("fn main()").unwrap()..];
    let write_at = body.find("fs::write(").unwrap();
    assert!(
        body[..write_at].contains("env::var(\"OUT_DIR\")") && !body.contains("join(\"include\")"),
        "build.rs writes somewhere else than OUT_DIR"
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

/// `examples/c/pyramid.c` (55 boxes, then 60 spheres and boxes dropped on them, 30 s at
/// 60 Hz) ends with every one of its 115 bodies asleep: the rolling spheres stop by their
/// rolling resistance. It exits 1 otherwise; its last line reports `0/115` awake.
/// `examples/c/one_way_platform.c` checks its own outcome (the box rests on the slab at
/// 3.35 m within 5 mm) and exits 1 otherwise.
#[test]
fn c_one_way_platform_example_rests_on_top() {
    let exe = out_dir().join("one_way_platform_c");
    let mut cmd = common::compiler(false, &out_dir());
    cmd.arg(root().join("examples/c/one_way_platform.c"))
        .arg("-o")
        .arg(&exe);
    common::link(&mut cmd, Link::Shared);
    run(&mut cmd);
    let text = run(&mut common::program(&exe));
    print!("{text}");
    assert!(text.contains("rests at 3.3") && text.contains(": OK"), "{text}");
}

#[test]
fn c_pyramid_example_ends_with_every_body_asleep() {
    let text = run(&mut common::program(&common::build_c_pyramid(&out_dir())));
    print!("{text}");
    let last = text
        .lines()
        .rev()
        .filter_map(|l| l.split_whitespace().next_back())
        .find(|w| w.contains('/'))
        .unwrap_or_else(|| panic!("no awake count printed:\n{text}"));
    assert_eq!(last, "0/115", "bodies still awake at the end:\n{text}");
}
