//! What the tests that build and run programs against the freshly built library share: the C
//! harness, the C++, Python and C# bindings, and packaging. Each includes it with `mod common;`.
//!
//! The library is the one this build made, in `target/<profile>/deps` next to the test binary;
//! a copy in `target/<profile>` may be stale from an earlier `cargo build`, so it is never
//! used — and programs run without cargo's `LD_LIBRARY_PATH`, which lists that directory first
//! and would win over the programs' rpath.

#![allow(dead_code)] // each test binary uses its own part

use std::path::{Path, PathBuf};
use std::process::Command;

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

pub fn shared_lib_name() -> &'static str {
    if cfg!(target_os = "macos") {
        "libhearth.dylib"
    } else {
        "libhearth.so"
    }
}

/// `target/<profile>/deps`, where this build put the shared and static libraries.
pub fn lib_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let dir = exe.parent().unwrap().to_path_buf();
    for lib in [shared_lib_name(), "libhearth.a"] {
        assert!(dir.join(lib).exists(), "{lib} missing in {}", dir.display());
    }
    dir
}

/// A scratch directory of this test binary under `CARGO_TARGET_TMPDIR`.
pub fn out_dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
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

/// Runs a command; panics with its whole output unless it exits with 0. Returns stdout and
/// stderr.
pub fn run(cmd: &mut Command) -> String {
    let out = cmd.output().unwrap_or_else(|e| panic!("cannot run {cmd:?}: {e}"));
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "{cmd:?} failed ({}):\n{text}", out.status);
    text
}

/// A command for a built program, without cargo's `LD_LIBRARY_PATH` (see the module docs).
pub fn program(exe: &Path) -> Command {
    let mut cmd = Command::new(exe);
    cmd.env_remove("LD_LIBRARY_PATH");
    cmd
}

/// Runs a program, and with `HEARTH_VALGRIND=1` once more under valgrind, which must report
/// no error and no leak and print the same. Returns the output.
pub fn run_program(exe: &Path) -> String {
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
            without_thread_ids(&v),
            without_thread_ids(&text),
            "{}: different output under valgrind",
            exe.display()
        );
        println!("valgrind clean: {}", exe.display());
    }
    text
}

/// `text` with the thread ids of panic messages (`thread '<unnamed>' (2888) panicked`) taken
/// out: they differ from run to run (a program may report a host's broken task contract).
fn without_thread_ids(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find("' (") {
        let (head, tail) = rest.split_at(at + 1);
        out.push_str(head);
        let digits = tail[2..].bytes().take_while(u8::is_ascii_digit).count();
        if digits > 0 && tail[2 + digits..].starts_with(") panicked") {
            rest = &tail[3 + digits..];
        } else {
            rest = tail;
            out.push_str(&rest[..1]);
            rest = &rest[1..];
        }
    }
    out.push_str(rest);
    out
}

#[derive(Clone, Copy)]
pub enum Link {
    Shared,
    Static,
}

/// The C11 or C++17 compiler with warnings as errors (`-Wall -Wextra -Wpedantic`), writing
/// into `out`, with `include/` on the include path.
pub fn compiler(cpp: bool, out: &Path) -> Command {
    let mut b = cc::Build::new();
    b.cargo_metadata(false)
        .cargo_warnings(false)
        .opt_level(1)
        .debug(true)
        .host(&triple())
        .target(&triple())
        .out_dir(out)
        .cpp(cpp)
        .warnings(true)
        .extra_warnings(true)
        .warnings_into_errors(true);
    let mut cmd = b.get_compiler().to_command();
    cmd.arg(if cpp { "-std=c++17" } else { "-std=c11" });
    cmd.arg("-Wpedantic");
    cmd.arg("-I").arg(root().join("include"));
    cmd
}

/// Links `cmd`'s program with this build's library (shared with an rpath, or static with its
/// system libraries), then the maths library.
pub fn link(cmd: &mut Command, link: Link) {
    let lib = lib_dir();
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
}

/// Builds `examples/c/pyramid.c` into `out` against the shared library.
pub fn build_c_pyramid(out: &Path) -> PathBuf {
    let exe = out.join("pyramid_c");
    let mut cmd = compiler(false, out);
    cmd.arg(root().join("examples/c/pyramid.c")).arg("-o").arg(&exe);
    link(&mut cmd, Link::Shared);
    run(&mut cmd);
    exe
}

/// The pyramid example in `language` printed `output`: it must be what the C example prints,
/// line by line, but for the language's name in the first line. (Hearth is deterministic, so
/// the numbers are identical.)
pub fn assert_prints_like_the_c_pyramid(output: &str, language: &str, out: &Path) {
    let c_out = run(&mut program(&build_c_pyramid(out)));
    let c_lines: Vec<&str> = c_out.lines().collect();
    let lines: Vec<&str> = output.lines().collect();
    assert!(c_lines.len() >= 8, "the C example printed too little:\n{c_out}");
    assert_eq!(c_lines.len(), lines.len(), "C:\n{c_out}\n{language}:\n{output}");
    assert!(c_lines[0].contains(" C example: "), "{}", c_lines[0]);
    let first = c_lines[0].replacen(" C example: ", &format!(" {language} example: "), 1);
    assert_eq!(lines[0], first, "first line");
    // Every report carries the running hash of every body's full state (transform and
    // velocities, bit for bit, after every step): equal lines mean equal runs.
    assert!(c_lines[1].contains("state hash"), "{}", c_lines[1]);
    let reports = c_lines
        .iter()
        .filter(|l| l.trim_start().starts_with(|c: char| c.is_ascii_digit()));
    for l in reports {
        let hash = l.split_whitespace().nth(2).unwrap_or_default(); // t, top y, hash, awake
        assert!(
            hash.len() == 16 && hash.chars().all(|c| c.is_ascii_hexdigit()),
            "no state hash in {l:?}"
        );
    }
    for (i, (c, other)) in c_lines.iter().zip(&lines).enumerate().skip(1) {
        assert_eq!(c, other, "line {} differs\nC:\n{c_out}\n{language}:\n{output}", i + 1);
    }
}
