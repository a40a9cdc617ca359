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

/// `git status` of `bindings/python`, ignored files included (None outside a git checkout).
fn tree_status() -> Option<String> {
    let out = Command::new("git")
        .current_dir(root())
        .args([
            "status",
            "--porcelain",
            "--ignored",
            "--untracked-files=all",
            "--",
            "bindings/python",
        ])
        .output()
        .ok()
        .filter(|o| o.status.success())?;
    Some(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// setuptools' leftovers in the source tree.
fn leftovers() -> Vec<PathBuf> {
    let dir = root().join("bindings/python");
    let mut found: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "egg-info"))
        .collect();
    for d in ["build", "dist"] {
        if dir.join(d).exists() {
            found.push(dir.join(d));
        }
    }
    found
}

fn pip(args: &[&str], extra: &[&Path]) -> String {
    let out = output(python().args(["-m", "pip"]).args(args).args(extra));
    assert!(out.status.success(), "pip {args:?} failed:\n{}", text(&out));
    text(&out)
}

fn wheels_in(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".whl"))
        .collect()
}

/// `pip wheel` and `pip install ./bindings/python` leave nothing in the source tree; the wheel
/// is `py3-none-any` without a library inside and `py3-none-<platform>` with one, which then
/// loads from the installed package. Needs setuptools, and wheel for setuptools < 70.1
/// (`.ci/setup` installs it); builds without isolation, so no network is used.
#[test]
fn wheels_are_tagged_by_platform_and_leave_no_build_files() {
    let probe = output(python().args([
        "-c",
        "import setuptools\ntry:\n    import setuptools.command.bdist_wheel\nexcept ImportError:\n    import wheel",
    ]));
    assert!(
        probe.status.success(),
        "setuptools and wheel are needed for python3 (pip install setuptools wheel):\n{}",
        text(&probe)
    );
    let before = tree_status();
    assert!(leftovers().is_empty(), "leftovers before the test: {:?}", leftovers());
    let scratch = common::out_dir("bindings_python/wheels");
    let _ = std::fs::remove_dir_all(&scratch);
    std::fs::create_dir_all(&scratch).unwrap();
    let source = root().join("bindings/python");
    let build_flags = ["--no-deps", "--no-build-isolation", "--quiet"];

    // A pure wheel, then an install straight from the source tree.
    let pure_dir = scratch.join("pure");
    pip(&[&["wheel"], &build_flags[..], &["-w"]].concat(), &[&pure_dir, &source]);
    assert_eq!(
        wheels_in(&pure_dir),
        vec![format!("hearth-{}-py3-none-any.whl", env!("CARGO_PKG_VERSION"))]
    );
    let site = scratch.join("site");
    pip(
        &[&["install"], &build_flags[..], &["--target"]].concat(),
        &[&site, &source],
    );
    assert!(site.join("hearth/__init__.py").is_file());
    assert!(leftovers().is_empty(), "pip left {:?} in the source tree", leftovers());
    assert_eq!(tree_status(), before, "pip changed bindings/python");

    // With the library inside: a platform wheel that carries it and loads it.
    let copy = scratch.join("package");
    let status = Command::new("cp").arg("-r").arg(&source).arg(&copy).status().unwrap();
    assert!(status.success());
    std::fs::copy(library(), copy.join("hearth").join(common::shared_lib_name())).unwrap();
    let platform_dir = scratch.join("platform");
    pip(
        &[&["wheel"], &build_flags[..], &["-w"]].concat(),
        &[&platform_dir, &copy],
    );
    let platform = String::from_utf8(
        output(python().args([
            "-c",
            "import sysconfig; print(sysconfig.get_platform().replace('-', '_').replace('.', '_'))",
        ]))
        .stdout,
    )
    .unwrap();
    let expected = format!("hearth-{}-py3-none-{}.whl", env!("CARGO_PKG_VERSION"), platform.trim());
    assert_eq!(wheels_in(&platform_dir), vec![expected.clone()]);
    let listing = run_example(
        python().args(["-m", "zipfile", "-l"]).arg(platform_dir.join(&expected)),
        "python3 -m zipfile -l",
    );
    assert!(
        listing.contains(&format!("hearth/{}", common::shared_lib_name())),
        "{listing}"
    );
    let installed = scratch.join("installed");
    pip(
        &["install", "--no-deps", "--quiet", "--target"],
        &[&installed, &platform_dir.join(&expected)],
    );
    let loaded = run_example(
        python()
            .env_remove("HEARTH_LIBRARY")
            .env("PYTHONPATH", &installed)
            .current_dir(&scratch)
            .args(["-c", "import hearth; print(hearth.library_path)"]),
        "import hearth from the installed wheel",
    );
    assert!(
        Path::new(loaded.trim()).starts_with(&installed),
        "loaded {loaded} instead of the wheel's library"
    );
}
