//! Packaging: `bindings/packaging/install.sh` installs the libraries this test build made
//! (`target/<profile>/deps`, never a stale `target/release` copy, and without running cargo)
//! into a temporary prefix; the prefix is then moved (the install must be relocatable), and
//!
//! * `examples/cmake_consumer` is configured with `cmake -DCMAKE_PREFIX_PATH=<prefix>`, built
//!   and run, linked with `hearth::hearth` (shared) and `hearth::hearth_static`;
//! * `find_package(hearth <version>)` accepts compatible versions and refuses others;
//! * `bindings/packaging/pkgconfig_check.c` is compiled with `pkg-config --cflags --libs hearth`
//!   and run, and `pkg-config --modversion` is the crate's version.
//!
//! Needs `cmake` and `pkg-config` (Debian packages `cmake` and `pkg-config`/`pkgconf`); the
//! tests fail with that message when they are missing.

mod common;

use common::{lib_dir, program, root, run};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Fails with the package to install when a tool is missing.
fn require_tool(tool: &str, debian_package: &str) {
    let found = Command::new(tool)
        .arg("--version")
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    assert!(
        found,
        "`{tool}` is needed by the packaging tests but was not found: install the Debian package `{debian_package}` (apt-get install {debian_package})"
    );
}

fn crate_version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

/// Installs into a fresh prefix and moves it elsewhere; returns the moved prefix. Each test
/// gets its own directory (tests run in parallel).
fn installed_prefix(name: &str) -> PathBuf {
    let base = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("packaging").join(name);
    let _ = std::fs::remove_dir_all(&base);
    std::fs::create_dir_all(&base).unwrap();
    let first = base.join("staging");
    let text = run(Command::new("bash")
        .arg(root().join("bindings/packaging/install.sh"))
        .arg("--prefix")
        .arg(&first)
        .arg("--lib-dir")
        .arg(lib_dir()));
    assert!(
        text.contains(&format!("installed Hearth {}", crate_version())),
        "{text}"
    );
    for f in [
        "lib/libhearth.so",
        "lib/libhearth.a",
        "include/hearth.h",
        "include/hearth.hpp",
        "lib/pkgconfig/hearth.pc",
        "lib/cmake/hearth/hearthConfig.cmake",
        "lib/cmake/hearth/hearthConfigVersion.cmake",
    ] {
        assert!(first.join(f).is_file(), "{f} not installed");
    }
    // The installed files are copies of this build's.
    for (installed, source) in [
        ("include/hearth.h", root().join("include/hearth.h")),
        ("include/hearth.hpp", root().join("bindings/cpp/hearth.hpp")),
        ("lib/libhearth.a", lib_dir().join("libhearth.a")),
    ] {
        assert!(
            std::fs::read(first.join(installed)).unwrap() == std::fs::read(&source).unwrap(),
            "{installed} differs from {}",
            source.display()
        );
    }
    let moved = base.join("moved");
    std::fs::rename(&first, &moved).unwrap();
    moved
}

fn cmake_configure(source: &Path, build: &Path, prefix: &Path) -> String {
    let _ = std::fs::remove_dir_all(build);
    run(Command::new("cmake")
        .arg("-S")
        .arg(source)
        .arg("-B")
        .arg(build)
        .arg(format!("-DCMAKE_PREFIX_PATH={}", prefix.display()))
        .arg("-DCMAKE_BUILD_TYPE=Release"))
}

#[test]
fn cmake_consumer_builds_and_runs_against_the_installed_copy() {
    require_tool("cmake", "cmake");
    let prefix = installed_prefix("cmake");
    let build = prefix.parent().unwrap().join("build");
    let text = cmake_configure(&root().join("examples/cmake_consumer"), &build, &prefix);
    assert!(text.contains(&format!("Found Hearth {}", crate_version())), "{text}");
    run(Command::new("cmake").arg("--build").arg(&build));
    for exe in ["consumer", "consumer_static"] {
        let out = run(&mut program(&build.join(exe)));
        print!("{out}");
        assert!(out.contains("consumer: OK"), "{exe}:\n{out}");
    }
    // The shared build really uses the installed (moved) library.
    let ldd = run(Command::new("ldd")
        .env_remove("LD_LIBRARY_PATH")
        .arg(build.join("consumer")));
    let line = ldd
        .lines()
        .find(|l| l.contains("libhearth.so"))
        .unwrap_or_else(|| panic!("consumer does not load libhearth.so:\n{ldd}"));
    assert!(line.contains(&prefix.join("lib").display().to_string()), "{line}");
    // The static build does not need it at all.
    let ldd = run(Command::new("ldd")
        .env_remove("LD_LIBRARY_PATH")
        .arg(build.join("consumer_static")));
    assert!(!ldd.contains("libhearth"), "{ldd}");
}

#[test]
fn find_package_checks_the_version() {
    require_tool("cmake", "cmake");
    let prefix = installed_prefix("version");
    let project = prefix.parent().unwrap().join("version_project");
    std::fs::create_dir_all(&project).unwrap();
    let (major, rest) = crate_version().split_once('.').unwrap();
    let minor = rest.split('.').next().unwrap();
    let next_major = major.parse::<u32>().unwrap() + 1;
    let next_minor = minor.parse::<u32>().unwrap() + 1;
    std::fs::write(
        project.join("CMakeLists.txt"),
        format!(
            r#"cmake_minimum_required(VERSION 3.16)
project(version_check LANGUAGES C)
find_package(hearth {next_major}.0 QUIET)
if(hearth_FOUND)
    message(FATAL_ERROR "a newer major version was accepted")
endif()
find_package(hearth {major}.{next_minor} QUIET)
if(hearth_FOUND)
    message(FATAL_ERROR "a newer minor version was accepted")
endif()
find_package(hearth {version} EXACT REQUIRED)
if(NOT TARGET hearth::hearth OR NOT TARGET hearth::hearth_static)
    message(FATAL_ERROR "imported targets missing")
endif()
message(STATUS "version check passed: ${{hearth_VERSION}}")
"#,
            version = crate_version()
        ),
    )
    .unwrap();
    let text = cmake_configure(&project, &project.join("build"), &prefix);
    assert!(
        text.contains(&format!("version check passed: {}", crate_version())),
        "{text}"
    );
}

#[test]
fn pkg_config_builds_a_c_program_against_the_installed_copy() {
    require_tool("pkg-config", "pkg-config");
    let prefix = installed_prefix("pkgconfig");
    let pc_path = prefix.join("lib/pkgconfig");
    let pkg_config = |args: &[&str]| -> String {
        run(Command::new("pkg-config")
            .env("PKG_CONFIG_PATH", &pc_path)
            .args(args)
            .arg("hearth"))
        .trim()
        .to_string()
    };
    assert_eq!(pkg_config(&["--modversion"]), crate_version());
    let static_libs = pkg_config(&["--static", "--libs"]);
    assert!(static_libs.contains("-lpthread") && static_libs.contains("-ldl"));
    let flags = pkg_config(&["--cflags", "--libs"]);
    assert!(flags.contains("-lhearth") && flags.contains("-I"), "{flags}");

    let exe = prefix.parent().unwrap().join("pkgconfig_check");
    let mut cc = Command::new("cc");
    cc.args(["-std=c11", "-Wall", "-Wextra", "-Wpedantic", "-Werror"])
        .arg(root().join("bindings/packaging/pkgconfig_check.c"))
        .args(flags.split_whitespace())
        .arg("-lm")
        .arg(format!("-Wl,-rpath,{}", prefix.join("lib").display()))
        .arg("-o")
        .arg(&exe);
    run(&mut cc);
    let out = run(&mut program(&exe));
    print!("{out}");
    assert!(out.contains("pkg-config: OK"), "{out}");
}
