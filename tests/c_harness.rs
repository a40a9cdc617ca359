//! The C harness: compiles the C programs under `tests/c/` with the `cc` crate against the
//! freshly built library and runs them. Each program includes only `include/hearth.h`.
//!
//! Also checks that the committed header matches a fresh generation, that the header
//! compiles as C11 and C++17 with warnings as errors, that the shared library exports only
//! `hearth_*` symbols, and (with `HEARTH_VALGRIND=1`) runs every program under valgrind.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Where this build put `libhearth.so` and `libhearth.a`: `target/<profile>/deps`, next to this
/// test binary. (`cargo test` does not copy them up to `target/<profile>`; a copy there may be
/// stale from an earlier `cargo build`, so it is never used.)
fn lib_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let dir = exe.parent().unwrap().to_path_buf();
    assert!(
        dir.join(shared_lib_name()).exists(),
        "shared library missing in {}",
        dir.display()
    );
    assert!(
        dir.join("libhearth.a").exists(),
        "static library missing in {}",
        dir.display()
    );
    dir
}

fn shared_lib_name() -> &'static str {
    if cfg!(target_os = "macos") {
        "libhearth.dylib"
    } else {
        "libhearth.so"
    }
}

fn out_dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("c_harness");
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn triple() -> String {
    let arch = std::env::consts::ARCH;
    if cfg!(target_os = "macos") {
        format!("{arch}-apple-darwin")
    } else {
        format!("{arch}-unknown-linux-gnu")
    }
}

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
    cmd.arg("-I").arg(root().join("tests").join("c"));
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

/// Builds one C test program; returns the executable.
fn build(source: &str, cpp: bool, link: Link) -> PathBuf {
    let name = Path::new(source).file_stem().unwrap().to_str().unwrap();
    let suffix = match (cpp, link) {
        (false, Link::Shared) => "c",
        (true, Link::Shared) => "cpp",
        (false, Link::Static) => "c_static",
        (true, Link::Static) => "cpp_static",
    };
    let exe = out_dir().join(format!("{name}_{suffix}"));
    let lib = lib_dir();
    let mut cmd = compiler(cpp);
    if cpp {
        cmd.arg("-x").arg("c++");
    }
    cmd.arg(root().join("tests").join("c").join(source));
    if cpp {
        cmd.arg("-x").arg("none");
    }
    cmd.arg("-o").arg(&exe);
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

/// Runs a test program (and again under valgrind with `HEARTH_VALGRIND=1`). cargo puts
/// `target/<profile>` first in `LD_LIBRARY_PATH`, which would win over the programs' rpath and
/// load a possibly stale `libhearth.so` from an earlier `cargo build`: it is removed.
fn run_program(exe: &Path) -> String {
    let text = run(Command::new(exe).env_remove("LD_LIBRARY_PATH"));
    assert!(text.contains(" 0 failed"), "{}:\n{text}", exe.display());
    print!("{text}");
    if std::env::var("HEARTH_VALGRIND").as_deref() == Ok("1") {
        let v = run(Command::new("valgrind")
            .env_remove("LD_LIBRARY_PATH")
            .args([
                "--error-exitcode=99",
                "--leak-check=full",
                "--show-leak-kinds=definite,indirect,possible",
            ])
            .args([
                "--errors-for-leak-kinds=definite,indirect,possible",
                "--track-origins=yes",
                "-q",
            ])
            .arg(exe));
        assert!(v.contains(" 0 failed"), "under valgrind:\n{v}");
        println!("valgrind clean: {}", exe.display());
    }
    text
}

const PROGRAMS: &[&str] = &[
    "test_api.c",
    "test_generators.c",
    "test_particles.c",
    "test_joints.c",
    "test_soft.c",
];

#[test]
fn c_programs_pass_with_the_shared_library() {
    for p in PROGRAMS {
        run_program(&build(p, false, Link::Shared));
    }
}

#[test]
fn c_programs_pass_compiled_as_cpp17() {
    for p in PROGRAMS {
        run_program(&build(p, true, Link::Shared));
    }
}

#[test]
fn c_programs_pass_with_the_static_library() {
    for p in PROGRAMS {
        let exe = build(p, false, Link::Static);
        let text = run(&mut Command::new(&exe));
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
    run(compiler(false).arg("-fsyntax-only").arg(&src_c));
    run(compiler(true).arg("-fsyntax-only").arg(&src_cpp));
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
