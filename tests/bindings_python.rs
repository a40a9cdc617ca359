//! The Python binding (`bindings/python`): runs its pytest suite against the freshly built
//! shared library, and checks that `examples/python/pyramid.py` prints the same text as
//! `examples/c/pyramid.c` (but for the language's name): Hearth is deterministic, so the
//! numbers must be identical.
//!
//! Needs `python3` with pytest (`pip install pytest`) and a C compiler.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn shared_lib_name() -> &'static str {
    if cfg!(target_os = "macos") {
        "libhearth.dylib"
    } else {
        "libhearth.so"
    }
}

/// The shared library this build made: `target/<profile>/deps`, next to this test binary
/// (as in `tests/c_harness.rs`; a copy in `target/<profile>` may be stale).
fn library() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let lib = exe.parent().unwrap().join(shared_lib_name());
    assert!(lib.exists(), "shared library missing: {}", lib.display());
    lib
}

fn out_dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bindings_python");
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `python3` with the library named by `HEARTH_LIBRARY`, writing no bytecode or pytest cache
/// into the source tree.
fn python() -> Command {
    let mut cmd = Command::new("python3");
    cmd.current_dir(root())
        .env("HEARTH_LIBRARY", library())
        .env("PYTHONDONTWRITEBYTECODE", "1");
    cmd
}

fn output(cmd: &mut Command) -> Output {
    cmd.output()
        .unwrap_or_else(|e| panic!("cannot run {cmd:?}: {e} (is python3 installed?)"))
}

fn text(out: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}

#[test]
fn python_binding_pytest_suite_passes() {
    let probe = output(python().args(["-c", "import pytest"]));
    assert!(
        probe.status.success(),
        "pytest is not installed for python3: pip install pytest\n{}",
        text(&probe)
    );
    let out = output(python().args(["-m", "pytest", "bindings/python/tests", "-q", "-p", "no:cacheprovider"]));
    let report = text(&out);
    assert!(
        out.status.success(),
        "python3 -m pytest bindings/python/tests failed:\n{report}"
    );
    print!("{report}");
}

/// Builds `examples/c/pyramid.c` against the same library, as `tests/c_harness.rs` does.
fn build_c_pyramid() -> PathBuf {
    let triple = format!(
        "{}-{}",
        std::env::consts::ARCH,
        if cfg!(target_os = "macos") {
            "apple-darwin"
        } else {
            "unknown-linux-gnu"
        }
    );
    let compiler = cc::Build::new()
        .cargo_metadata(false)
        .cargo_warnings(false)
        .opt_level(2)
        .host(&triple)
        .target(&triple)
        .out_dir(out_dir())
        .get_compiler();
    let exe = out_dir().join("pyramid_c");
    let lib_dir = library().parent().unwrap().to_path_buf();
    let mut cmd = compiler.to_command();
    cmd.arg("-std=c11")
        .arg("-I")
        .arg(root().join("include"))
        .arg(root().join("examples/c/pyramid.c"))
        .arg("-o")
        .arg(&exe)
        .arg("-L")
        .arg(&lib_dir)
        .arg("-lhearth")
        .arg(format!("-Wl,-rpath,{}", lib_dir.display()))
        .arg("-lm");
    let out = output(&mut cmd);
    assert!(out.status.success(), "{cmd:?} failed:\n{}", text(&out));
    exe
}

fn run_example(cmd: &mut Command, what: &str) -> String {
    let out = output(cmd);
    assert!(out.status.success(), "{what} failed:\n{}", text(&out));
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn python_pyramid_prints_what_the_c_pyramid_prints() {
    let c = run_example(&mut Command::new(build_c_pyramid()), "examples/c/pyramid.c");
    let py = run_example(
        python().arg(Path::new("examples").join("python").join("pyramid.py")),
        "examples/python/pyramid.py",
    );
    println!("{py}");
    let c_lines: Vec<&str> = c.lines().collect();
    let py_lines: Vec<&str> = py.lines().collect();
    assert!(c_lines.len() > 3, "the C example printed too little:\n{c}");
    assert_eq!(
        c_lines.len(),
        py_lines.len(),
        "line counts differ\nC:\n{c}\nPython:\n{py}"
    );
    for (i, (c_line, py_line)) in c_lines.iter().zip(&py_lines).enumerate() {
        let expected = if i == 0 {
            assert!(c_line.contains(" C example"), "unexpected first line: {c_line}");
            c_line.replacen(" C example", " Python example", 1)
        } else {
            c_line.to_string()
        };
        assert_eq!(*py_line, expected, "line {} differs", i + 1);
    }
}
