//! Packaging: `bindings/packaging/install.sh` installs the libraries this test build made
//! (`target/<profile>/deps`, never a stale `target/release` copy, and without running cargo)
//! into a temporary prefix; the prefix is then moved (the install must be relocatable), and
//!
//! * the shared library carries the SONAME `libhearth.so.<ABI>` (ABI `0.<minor>` while the
//!   major is 0) and is laid out as `libhearth.so -> libhearth.so.<ABI> -> libhearth.so.<version>`;
//!   neither library carries debug info (nor the static one LLVM bitcode);
//! * `examples/cmake_consumer` is configured with `cmake -DCMAKE_PREFIX_PATH=<prefix>`, built
//!   and run, linked with `hearth::hearth` (shared) and `hearth::hearth_static`;
//! * `find_package(hearth <version>)` accepts what the ABI accepts and refuses the rest, and the
//!   line the installed config suggests works;
//! * `bindings/packaging/pkgconfig_check.c` is compiled with `pkg-config --cflags --libs hearth`
//!   (shared), `hearth-static` (static library in a dynamic program) and
//!   `-static ... --static hearth` (a fully static program), and run;
//! * debug info of a library built with it is split into `lib/.debug/`; Windows build
//!   directories (MSVC, MinGW) give the Windows layout and CMake config.
//!
//! Needs `cmake`, `pkg-config` and binutils (Debian packages `cmake`, `pkg-config`/`pkgconf`,
//! `binutils`); the tests fail with that message when they are missing. The Windows libraries
//! themselves are built and run under Wine by `.ci/windows`.

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

/// The ABI version: the major, or `0.<minor>` while the major is 0.
fn abi() -> String {
    let (major, rest) = crate_version().split_once('.').unwrap();
    let minor = rest.split('.').next().unwrap();
    if major == "0" {
        format!("0.{minor}")
    } else {
        major.to_string()
    }
}

fn scratch(name: &str) -> PathBuf {
    let base = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("packaging").join(name);
    let _ = std::fs::remove_dir_all(&base);
    std::fs::create_dir_all(&base).unwrap();
    base
}

fn install(lib: &Path, prefix: &Path, extra: &[&str]) -> String {
    run(Command::new("bash")
        .arg(root().join("bindings/packaging/install.sh"))
        .arg("--prefix")
        .arg(prefix)
        .arg("--lib-dir")
        .arg(lib)
        .args(extra))
}

/// Installs into a fresh prefix and moves it elsewhere; returns the moved prefix. Each test
/// gets its own directory (tests run in parallel).
fn installed_prefix(name: &str) -> PathBuf {
    let base = scratch(name);
    let first = base.join("staging");
    let text = install(&lib_dir(), &first, &[]);
    assert!(
        text.contains(&format!("installed Hearth {} (linux, ABI {})", crate_version(), abi())),
        "{text}"
    );
    let real = format!("lib/libhearth.so.{}", crate_version());
    for f in [
        real.as_str(),
        "lib/libhearth.a",
        "include/hearth.h",
        "include/hearth.hpp",
        "lib/pkgconfig/hearth.pc",
        "lib/pkgconfig/hearth-static.pc",
        "lib/cmake/hearth/hearthConfig.cmake",
        "lib/cmake/hearth/hearthConfigVersion.cmake",
    ] {
        assert!(first.join(f).is_file(), "{f} not installed");
    }
    // The headers are copies of the repository's.
    for (installed, source) in [
        ("include/hearth.h", root().join("include/hearth.h")),
        ("include/hearth.hpp", root().join("bindings/cpp/hearth.hpp")),
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

/// Section names of an object file or of every member of an archive.
fn sections(file: &Path) -> String {
    run(Command::new("objdump").arg("-h").arg(file))
}

#[test]
fn shared_library_has_a_soname_and_versioned_links() {
    require_tool("objdump", "binutils");
    let prefix = installed_prefix("soname");
    let lib = prefix.join("lib");
    let soname = format!("libhearth.so.{}", abi());
    let real = format!("libhearth.so.{}", crate_version());
    let dynamic = run(Command::new("objdump").arg("-p").arg(lib.join(&real)));
    assert!(
        dynamic
            .lines()
            .any(|l| l.split_whitespace().eq(["SONAME", soname.as_str()])),
        "SONAME is not {soname}:\n{dynamic}"
    );
    assert_eq!(
        std::fs::read_link(lib.join("libhearth.so")).unwrap(),
        Path::new(&soname)
    );
    assert_eq!(std::fs::read_link(lib.join(&soname)).unwrap(), Path::new(&real));
    // The build tree has the SONAME too, so `-Ltarget/release -lhearth` programs run.
    assert!(lib_dir().join(&soname).exists(), "{soname} missing in the build tree");
    // Release libraries ship without debug info; the static one also without the LLVM
    // bitcode of Rust's standard library.
    assert!(
        !sections(&lib.join(&real)).contains(".debug_info"),
        "{real} has debug info"
    );
    let archive = sections(&lib.join("libhearth.a"));
    assert!(
        !archive.contains(".debug_info") && !archive.contains(".llvmbc"),
        "libhearth.a is not stripped"
    );
    // Sizes (bindings/packaging/README.md): about 4 and 12 MB today, under 5 and 14 MB.
    for (f, limit) in [(real.as_str(), 5e6), ("libhearth.a", 14e6)] {
        let size = std::fs::metadata(lib.join(f)).unwrap().len() as f64;
        println!("installed {f}: {:.2} MB", size / 1e6);
        assert!(size < limit, "{f} is {:.1} MB, over {:.0} MB", size / 1e6, limit / 1e6);
    }
}

#[test]
fn debug_info_is_split_off() {
    // A stand-in library built with -g (a real release-with-debug build takes minutes): the
    // installed library loses its debug info, which lands in lib/.debug/ behind a debug link.
    require_tool("objdump", "binutils");
    let base = scratch("debug");
    let built = base.join("built");
    std::fs::create_dir_all(&built).unwrap();
    let source = base.join("stand_in.c");
    std::fs::write(&source, "int hearth_stand_in(int x) { return 2 * x; }\n").unwrap();
    run(Command::new("cc")
        .args(["-g", "-shared", "-fPIC"])
        .arg(format!("-Wl,-soname,libhearth.so.{}", abi()))
        .arg(&source)
        .arg("-o")
        .arg(built.join("libhearth.so")));
    run(Command::new("ar").arg("rc").arg(built.join("libhearth.a")));
    let prefix = base.join("prefix");
    let text = install(&built, &prefix, &[]);
    let real = format!("libhearth.so.{}", crate_version());
    assert!(
        text.contains(&format!("split debug info into lib/.debug/{real}.debug")),
        "{text}"
    );
    let installed = sections(&prefix.join("lib").join(&real));
    assert!(!installed.contains(".debug_info"), "{installed}");
    assert!(installed.contains(".gnu_debuglink"), "{installed}");
    assert!(sections(&prefix.join(format!("lib/.debug/{real}.debug"))).contains(".debug_info"));
    // --keep-debug installs it as built.
    let kept = base.join("kept");
    install(&built, &kept, &["--keep-debug"]);
    assert!(sections(&kept.join("lib").join(&real)).contains(".debug_info"));
}

#[test]
fn windows_build_directories_give_the_windows_layout() {
    // File names only (the libraries are empty stand-ins); .ci/windows links and runs a real
    // MinGW install under Wine.
    let base = scratch("windows");
    for (platform, files, implib, static_lib) in [
        (
            "msvc",
            ["hearth.dll", "hearth.dll.lib", "hearth.lib"],
            "hearth.dll.lib",
            "hearth.lib",
        ),
        (
            "mingw",
            ["hearth.dll", "libhearth.dll.a", "libhearth.a"],
            "libhearth.dll.a",
            "libhearth.a",
        ),
    ] {
        let built = base.join(platform).join("built");
        std::fs::create_dir_all(&built).unwrap();
        for f in files {
            std::fs::write(built.join(f), b"").unwrap();
        }
        let prefix = base.join(platform).join("prefix");
        let text = install(&built, &prefix, &["--keep-debug"]);
        assert!(text.contains(&format!("({platform}, ABI {})", abi())), "{text}");
        assert!(prefix.join("bin/hearth.dll").is_file());
        assert!(prefix.join("lib").join(implib).is_file());
        assert!(prefix.join("lib").join(static_lib).is_file());
        let config = std::fs::read_to_string(prefix.join("lib/cmake/hearth/hearthConfig.cmake")).unwrap();
        assert!(
            config.contains("IMPORTED_LOCATION \"${_hearth_prefix}/bin/hearth.dll\""),
            "{config}"
        );
        assert!(
            config.contains(&format!("IMPORTED_IMPLIB \"${{_hearth_prefix}}/lib/{implib}\"")),
            "{config}"
        );
        assert!(
            config.contains(&format!("\"${{_hearth_prefix}}/lib/{static_lib}\"")),
            "{config}"
        );
        assert!(config.contains("kernel32;ntdll;userenv;ws2_32;dbghelp"), "{config}");
        // pkg-config for MinGW only.
        assert_eq!(prefix.join("lib/pkgconfig/hearth.pc").exists(), platform == "mingw");
    }
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
    // The shared build asks for the SONAME and loads the installed (moved) library.
    let ldd = run(Command::new("ldd")
        .env_remove("LD_LIBRARY_PATH")
        .arg(build.join("consumer")));
    let soname = format!("libhearth.so.{}", abi());
    let line = ldd
        .lines()
        .find(|l| l.contains("libhearth.so"))
        .unwrap_or_else(|| panic!("consumer does not load libhearth.so:\n{ldd}"));
    assert!(line.trim_start().starts_with(&soname), "{line}");
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
    let minor: u32 = rest.split('.').next().unwrap().parse().unwrap();
    let major: u32 = major.parse().unwrap();
    // The request the installed config suggests, word for word.
    let config = std::fs::read_to_string(prefix.join("lib/cmake/hearth/hearthConfig.cmake")).unwrap();
    let suggested = config
        .lines()
        .find_map(|l| l.trim_start_matches('#').trim().strip_prefix("find_package(hearth "))
        .and_then(|rest| rest.split_whitespace().next())
        .expect("the config suggests a find_package line")
        .to_string();
    assert_eq!(suggested, abi());
    let mut accepted = vec![suggested.clone(), crate_version().to_string(), major.to_string()];
    let mut refused = vec![format!("{}.0", major + 1), format!("{major}.{}", minor + 1)];
    if major == 0 {
        // Before 1.0 a minor is an ABI: an older minor is refused too.
        if minor > 0 {
            refused.push(format!("0.{}", minor - 1));
        }
    } else {
        accepted.push(format!("{major}.0"));
    }
    let mut cmake = String::from("cmake_minimum_required(VERSION 3.16)\nproject(version_check LANGUAGES C)\n");
    for (i, v) in accepted.iter().enumerate() {
        cmake += &format!(
            "find_package(hearth {v} QUIET)\nif(NOT hearth_FOUND)\n    message(FATAL_ERROR \"{v} was refused\")\nendif()\nunset(hearth_FOUND)\nunset(hearth_DIR CACHE)\n# {i}\n"
        );
    }
    for v in &refused {
        cmake += &format!(
            "find_package(hearth {v} QUIET)\nif(hearth_FOUND)\n    message(FATAL_ERROR \"{v} was accepted\")\nendif()\nunset(hearth_DIR CACHE)\n"
        );
    }
    cmake += &format!(
        "find_package(hearth {} EXACT REQUIRED)\nif(NOT TARGET hearth::hearth OR NOT TARGET hearth::hearth_static)\n    message(FATAL_ERROR \"imported targets missing\")\nendif()\nmessage(STATUS \"version check passed: ${{hearth_VERSION}}\")\n",
        crate_version()
    );
    std::fs::write(project.join("CMakeLists.txt"), cmake).unwrap();
    let text = cmake_configure(&project, &project.join("build"), &prefix);
    assert!(
        text.contains(&format!("version check passed: {}", crate_version())),
        "{text}"
    );
    println!("accepted {accepted:?}, refused {refused:?}");
}

#[test]
fn pkg_config_builds_c_programs_against_the_installed_copy() {
    require_tool("pkg-config", "pkg-config");
    let prefix = installed_prefix("pkgconfig");
    let pc_path = prefix.join("lib/pkgconfig");
    let pkg_config = |args: &[&str], package: &str| -> String {
        run(Command::new("pkg-config")
            .env("PKG_CONFIG_PATH", &pc_path)
            .args(args)
            .arg(package))
        .trim()
        .to_string()
    };
    assert_eq!(pkg_config(&["--modversion"], "hearth"), crate_version());
    assert_eq!(pkg_config(&["--modversion"], "hearth-static"), crate_version());
    let shared = pkg_config(&["--cflags", "--libs"], "hearth");
    assert!(shared.contains("-lhearth") && shared.contains("-I"), "{shared}");
    let static_libs = pkg_config(&["--static", "--libs"], "hearth");
    assert!(
        static_libs.contains("-lpthread") && static_libs.contains("-ldl"),
        "{static_libs}"
    );
    let archive = pkg_config(&["--cflags", "--libs"], "hearth-static");
    assert!(
        archive.contains("libhearth.a") && archive.contains("-lpthread"),
        "{archive}"
    );

    let compile = |flags: &str, pre: &[&str], exe: &Path| {
        let mut cc = Command::new("cc");
        cc.args(pre)
            .args(["-std=c11", "-Wall", "-Wextra", "-Wpedantic", "-Werror"])
            .arg(root().join("bindings/packaging/pkgconfig_check.c"))
            .args(flags.split_whitespace())
            .arg("-lm")
            .arg(format!("-Wl,-rpath,{}", prefix.join("lib").display()))
            .arg("-o")
            .arg(exe);
        run(&mut cc);
        let out = run(&mut program(exe));
        assert!(out.contains("pkg-config: OK"), "{out}");
        // ldd fails on a fully static program ("not a dynamic executable"): keep its text.
        let ldd = Command::new("ldd")
            .env_remove("LD_LIBRARY_PATH")
            .arg(exe)
            .output()
            .unwrap();
        format!(
            "{}{}",
            String::from_utf8_lossy(&ldd.stdout),
            String::from_utf8_lossy(&ldd.stderr)
        )
    };
    let dir = prefix.parent().unwrap();
    // Shared: the program loads the library by its SONAME.
    let ldd = compile(&shared, &[], &dir.join("check_shared"));
    assert!(ldd.contains(&format!("libhearth.so.{}", abi())), "{ldd}");
    // hearth-static: libhearth.a inside an otherwise dynamic program.
    let ldd = compile(&archive, &[], &dir.join("check_static_lib"));
    assert!(!ldd.contains("libhearth"), "{ldd}");
    // --static: a fully static program (cc -static prefers libhearth.a).
    let flags = pkg_config(&["--static", "--cflags", "--libs"], "hearth");
    let ldd = compile(&flags, &["-static"], &dir.join("check_fully_static"));
    assert!(!ldd.contains("libhearth") && !ldd.contains("libc.so"), "{ldd}");
}
