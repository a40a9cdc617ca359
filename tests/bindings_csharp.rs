//! The C# binding (`bindings/csharp/`): compiled with Mono's `mcs` and run with `mono` against
//! the freshly built library.
//!
//! - `csharp_binding_covers_the_header`: every `hearth_*` function and every `Hearth*` type of
//!   `include/hearth.h` is wrapped by the binding or listed in `bindings/csharp/not_wrapped.txt`
//!   (and the binding declares no function the header lacks). Needs no tools.
//! - `csharp_tests_pass`: a C program generated from the header prints the size and every
//!   field offset of every struct and the value of every constant; the C# test program
//!   (`bindings/csharp/tests/HearthTests.cs`) compares them with its own marshalling layout,
//!   then tests the binding's behaviour.
//! - `csharp_pyramid_prints_what_the_c_pyramid_prints`: `examples/csharp/Pyramid.cs` and
//!   `examples/c/pyramid.c` print the same lines (the language's name aside).

mod common;

use common::{lib_dir, root, run};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

fn out_dir(name: &str) -> PathBuf {
    common::out_dir(&format!("bindings_csharp/{name}"))
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

// ---------------------------------------------------------------------------------------
// Reading the header and the binding

/// The header without its comments (`/* */` and `//`).
fn strip_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    loop {
        let block = rest.find("/*");
        let line = rest.find("//");
        match (block, line) {
            (Some(b), l) if l.map_or(true, |l| b < l) => {
                out.push_str(&rest[..b]);
                let end = rest[b + 2..].find("*/").expect("unterminated comment") + b + 4;
                out.push(' ');
                rest = &rest[end..];
            }
            (_, Some(l)) => {
                out.push_str(&rest[..l]);
                rest = &rest[l..];
                rest = &rest[rest.find('\n').unwrap_or(rest.len())..];
            }
            (None, None) => {
                out.push_str(rest);
                return out;
            }
            (Some(_), None) => unreachable!(),
        }
    }
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// The identifier that starts `text` (after leading blanks), if any.
fn ident_at(text: &str) -> &str {
    let text = text.trim_start();
    &text[..text.find(|c| !is_ident(c)).unwrap_or(text.len())]
}

/// The identifier that ends `text` (before trailing blanks).
fn ident_before(text: &str) -> &str {
    let text = text.trim_end();
    &text[text.rfind(|c| !is_ident(c)).map_or(0, |i| i + 1)..]
}

/// Every identifier that follows `keyword` (as a whole word) in `text`.
fn idents_after<'a>(text: &'a str, keyword: &str) -> Vec<&'a str> {
    let mut found = Vec::new();
    let mut from = 0;
    while let Some(i) = text[from..].find(keyword) {
        let at = from + i;
        from = at + keyword.len();
        let before_ok = text[..at].chars().next_back().map_or(true, |c| !is_ident(c));
        if before_ok {
            let name = ident_at(&text[from..]);
            if !name.is_empty() {
                found.push(name);
            }
        }
    }
    found
}

/// What the header declares.
#[derive(Default)]
struct Header {
    functions: BTreeSet<String>,
    types: BTreeSet<String>,
    /// Every `typedef struct X { ... } X;` with its field names, in order.
    structs: Vec<(String, Vec<String>)>,
    /// Every `HEARTH_*` integer constant: `#define`s and `HearthResult` members.
    constants: Vec<String>,
}

fn parse_header(text: &str) -> Header {
    let mut h = Header::default();
    for line in text.lines() {
        let Some(rest) = line.trim().strip_prefix("#define ") else {
            continue;
        };
        let name = ident_at(rest);
        let value = rest[name.len()..].trim();
        if name.starts_with("HEARTH_") && !value.is_empty() && value.parse::<i64>().is_ok() {
            h.constants.push(name.to_string());
        }
    }
    let code = strip_comments(text);
    // Functions: declarations start at column 0, `<return type> hearth_name(`.
    for line in code.lines() {
        if line.starts_with(|c: char| c.is_ascii_alphabetic()) && !line.starts_with("typedef") {
            if let Some(paren) = line.find('(') {
                let name = ident_before(&line[..paren]);
                if name.starts_with("hearth_") {
                    h.functions.insert(name.to_string());
                }
            }
        }
    }
    for keyword in ["typedef struct ", "enum "] {
        for name in idents_after(&code, keyword) {
            if name.starts_with("Hearth") {
                h.types.insert(name.to_string());
            }
        }
    }
    for name in idents_after(&code, "(*") {
        if name.starts_with("Hearth") {
            h.types.insert(name.to_string());
        }
    }
    // Struct bodies: `typedef struct X {` ... `} X;`.
    let mut from = 0;
    while let Some(i) = code[from..].find("typedef struct ") {
        let start = from + i + "typedef struct ".len();
        let name = ident_at(&code[start..]);
        let after_name = &code[start + name.len()..];
        from = start;
        if !after_name.trim_start().starts_with('{') {
            continue; // opaque
        }
        let open = start + name.len() + after_name.find('{').unwrap();
        let close = open + code[open..].find('}').expect("unterminated struct");
        let fields = code[open + 1..close]
            .split(';')
            .map(ident_before)
            .filter(|f| !f.is_empty())
            .map(str::to_string)
            .collect();
        h.structs.push((name.to_string(), fields));
        from = close;
    }
    // Enum members (HearthResult).
    for name in idents_after(&code, "enum ") {
        let at = code.find(&format!("enum {name}")).unwrap();
        let open = at + code[at..].find('{').unwrap();
        let close = open + code[open..].find('}').unwrap();
        for member in code[open + 1..close].split(',') {
            let member = ident_at(member);
            if member.starts_with("HEARTH_") {
                h.constants.push(member.to_string());
            }
        }
    }
    h
}

/// What the C# sources declare: extern function names and type names.
fn parse_csharp(text: &str) -> (BTreeSet<String>, BTreeSet<String>) {
    let mut functions = BTreeSet::new();
    let mut types = BTreeSet::new();
    let mut from = 0;
    while let Some(i) = text[from..].find("static extern ") {
        let start = from + i;
        let paren = start + text[start..].find('(').unwrap();
        functions.insert(ident_before(&text[start..paren]).to_string());
        from = paren;
    }
    for keyword in ["struct ", "enum ", "class "] {
        for name in idents_after(text, keyword) {
            types.insert(name.to_string());
        }
    }
    // `delegate <return type> Name(`: the identifier before the next parenthesis.
    let mut from = 0;
    while let Some(i) = text[from..].find("delegate ") {
        let start = from + i;
        let paren = start + text[start..].find('(').unwrap();
        types.insert(ident_before(&text[start..paren]).to_string());
        from = paren;
    }
    (functions, types)
}

/// `name reason...` lines of not_wrapped.txt (blank lines and `#` comments skipped).
fn parse_not_wrapped(text: &str) -> BTreeSet<String> {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .map(|l| {
            let name = ident_at(l);
            assert!(
                l[name.len()..].trim().len() >= 10,
                "not_wrapped.txt: `{l}` needs a reason after the name"
            );
            name.to_string()
        })
        .collect()
}

/// Every problem between the header and the binding; empty when they agree. The C# name
/// of a type `HearthX` is `X`; functions keep their C names.
fn parity_problems(header: &Header, csharp: &str, not_wrapped: &str) -> Vec<String> {
    let (cs_functions, cs_types) = parse_csharp(csharp);
    let skipped = parse_not_wrapped(not_wrapped);
    let mut problems = Vec::new();
    for f in &header.functions {
        match (cs_functions.contains(f), skipped.contains(f)) {
            (false, false) => problems.push(format!(
                "function {f} is not wrapped (add a DllImport or a line to not_wrapped.txt)"
            )),
            (true, true) => problems.push(format!("function {f} is wrapped but also listed in not_wrapped.txt")),
            _ => {}
        }
    }
    for t in &header.types {
        let cs = t.strip_prefix("Hearth").unwrap();
        match (cs_types.contains(cs), skipped.contains(t)) {
            (false, false) => problems.push(format!(
                "type {t} has no C# type {cs} (add one or a line to not_wrapped.txt)"
            )),
            (true, true) => problems.push(format!("type {t} is wrapped but also listed in not_wrapped.txt")),
            _ => {}
        }
    }
    for f in &cs_functions {
        if !header.functions.contains(f) {
            problems.push(format!("the binding imports {f}, which the header does not declare"));
        }
    }
    for s in &skipped {
        if !header.functions.contains(s) && !header.types.contains(s) {
            problems.push(format!("not_wrapped.txt lists {s}, which the header does not declare"));
        }
    }
    problems
}

fn binding_sources() -> Vec<PathBuf> {
    let dir = root().join("bindings").join("csharp");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "cs"))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no .cs files in {}", dir.display());
    files
}

fn header() -> Header {
    parse_header(&read(&root().join("include").join("hearth.h")))
}

#[test]
fn csharp_binding_covers_the_header() {
    let h = header();
    assert!(h.functions.len() >= 100, "only {} functions parsed", h.functions.len());
    assert!(h.types.len() >= 30, "only {} types parsed", h.types.len());
    let csharp: String = binding_sources().iter().map(|p| read(p)).collect();
    let not_wrapped = read(&root().join("bindings/csharp/not_wrapped.txt"));
    let problems = parity_problems(&h, &csharp, &not_wrapped);
    assert!(
        problems.is_empty(),
        "the C# binding and include/hearth.h disagree:\n  {}",
        problems.join("\n  ")
    );
    println!(
        "C# binding covers {} functions and {} types of the header",
        h.functions.len(),
        h.types.len()
    );
}

#[test]
fn parity_check_reports_a_new_export_and_a_new_type() {
    let mut text = read(&root().join("include").join("hearth.h"));
    let end = text.rfind("#ifdef __cplusplus").unwrap();
    text.insert_str(
        end,
        "HearthResult hearth_body_new_thing(struct HearthWorld *world, float x);\n\
         typedef struct HearthNewDef { float x; } HearthNewDef;\n\
         typedef void (*HearthNewCallback)(void *user_data);\n",
    );
    let csharp: String = binding_sources().iter().map(|p| read(p)).collect();
    let problems = parity_problems(&parse_header(&text), &csharp, "");
    let all = problems.join("\n");
    assert!(all.contains("hearth_body_new_thing"), "{all}");
    assert!(all.contains("HearthNewDef"), "{all}");
    assert!(all.contains("HearthNewCallback"), "{all}");
    assert_eq!(problems.len(), 3, "{all}");
    // Listing them as deliberately not wrapped satisfies the check.
    let skipped = "hearth_body_new_thing  a test entry\nHearthNewDef  a test entry\nHearthNewCallback  a test entry\n";
    assert!(parity_problems(&parse_header(&text), &csharp, skipped).is_empty());
}

// ---------------------------------------------------------------------------------------
// Building and running the C# programs

/// Fails with the install hint when Mono's compiler or runtime is missing.
fn require_mono() {
    for tool in ["mcs", "mono"] {
        let ok = Command::new(tool)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success());
        assert!(
            ok,
            "`{tool}` not found: the C# binding tests need Mono. Install it with\n    \
             apt-get install mono-mcs mono-runtime"
        );
    }
}

/// Compiles the binding and `program` (more .cs files) into `dir/<name>.exe` with warnings as errors.
fn mcs(dir: &Path, name: &str, program: &[PathBuf]) -> PathBuf {
    let exe = dir.join(format!("{name}.exe"));
    let mut cmd = Command::new("mcs");
    cmd.args(["-nologo", "-debug", "-warn:4", "-warnaserror+", "-target:exe"])
        .arg(format!("-out:{}", exe.display()))
        .args(binding_sources())
        .args(program);
    run(&mut cmd);
    exe
}

/// `mono exe args`, finding `libhearth.so` through LD_LIBRARY_PATH.
fn mono(exe: &Path) -> Command {
    let lib = lib_dir();
    let mut cmd = Command::new("mono");
    cmd.arg("--debug").arg(exe);
    let var = if cfg!(target_os = "macos") {
        "DYLD_LIBRARY_PATH"
    } else {
        "LD_LIBRARY_PATH"
    };
    let mut path = lib.into_os_string();
    if let Some(old) = std::env::var_os(var) {
        path.push(":");
        path.push(old);
    }
    cmd.env(var, path);
    cmd
}

/// Builds a C program linked against the fresh shared library.
fn build_c(dir: &Path, source: &Path, name: &str) -> PathBuf {
    let exe = dir.join(name);
    let mut cmd = common::compiler(false, dir);
    cmd.arg(source).arg("-o").arg(&exe);
    common::link(&mut cmd, common::Link::Shared);
    run(&mut cmd);
    exe
}

/// A C program printing `size <Type> <bytes>`, `offset <Type> <field> <bytes>` and
/// `const <NAME> <value>` for everything the header declares.
fn layout_program(h: &Header) -> String {
    let mut c = String::from("#include \"hearth.h\"\n#include <stddef.h>\n#include <stdio.h>\n\nint main(void) {\n");
    for (name, fields) in &h.structs {
        c.push_str(&format!("    printf(\"size {name} %zu\\n\", sizeof({name}));\n"));
        for f in fields {
            c.push_str(&format!(
                "    printf(\"offset {name} {f} %zu\\n\", offsetof({name}, {f}));\n"
            ));
        }
    }
    for k in &h.constants {
        c.push_str(&format!("    printf(\"const {k} %lld\\n\", (long long)({k}));\n"));
    }
    c.push_str("    return 0;\n}\n");
    c
}

#[test]
fn csharp_tests_pass() {
    require_mono();
    let dir = out_dir("tests");
    let h = header();
    assert!(h.structs.len() >= 30 && h.constants.len() >= 20);
    let source = dir.join("layout.c");
    std::fs::write(&source, layout_program(&h)).unwrap();
    let layout_exe = build_c(&dir, &source, "layout");
    let layout = dir.join("layout.txt");
    std::fs::write(&layout, run(&mut common::program(&layout_exe))).unwrap();

    let exe = mcs(
        &dir,
        "HearthTests",
        &[root().join("bindings/csharp/tests/HearthTests.cs")],
    );
    let text = run(mono(&exe).arg(&layout));
    print!("{text}");
    assert!(text.contains(" 0 failed"), "{text}");
}

#[test]
fn csharp_pyramid_prints_what_the_c_pyramid_prints() {
    require_mono();
    let dir = out_dir("pyramid");
    let cs_exe = mcs(&dir, "Pyramid", &[root().join("examples/csharp/Pyramid.cs")]);
    let cs_out = run(&mut mono(&cs_exe));
    print!("{cs_out}");
    common::assert_prints_like_the_c_pyramid(&cs_out, "C#", &dir);
}
