//! The Python binding (`bindings/python`): runs its pytest suite against the freshly built
//! shared library, and checks that `examples/python/pyramid.py` prints the same text as
//! `examples/c/pyramid.c` (but for the language's name): Hearth is deterministic, so the
//! numbers must be identical.
//!
//! Needs `python3` with pytest (`pip install pytest`) and a C compiler.

mod common;

use common::root;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The shared library this build made (see `common`).
fn library() -> PathBuf {
    common::lib_dir().join(common::shared_lib_name())
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

fn run_example(cmd: &mut Command, what: &str) -> String {
    let out = output(cmd);
    assert!(out.status.success(), "{what} failed:\n{}", text(&out));
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn python_pyramid_prints_what_the_c_pyramid_prints() {
    let py = run_example(
        python().arg(Path::new("examples").join("python").join("pyramid.py")),
        "examples/python/pyramid.py",
    );
    println!("{py}");
    common::assert_prints_like_the_c_pyramid(&py, "Python", &common::out_dir("bindings_python"));
}
