//! The documentation a user reads first, checked:
//!
//! * the C snippets of `README.md` and `docs/API.md` compile as they are (inside a `main`) against
//!   this build, run, and leave the box at the height their comments give (0.50 m);
//! * every relative link in `README.md`, `docs/API.md` and the READMEs of `examples/` and
//!   `bindings/` names a file or directory of the repository (no `../shared/...`);
//! * every folder of `examples/` has a README with a shell block of build and run commands;
//! * every item of `include/hearth.h` has a group in the API reference
//!   (`docs/doxygen_filter.py --check`; the reference itself is built with Doxygen by `.ci/docs`).

mod common;

use common::{compiler, link, root, run, Link};
use std::path::{Path, PathBuf};
use std::process::Command;

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

/// The fenced code blocks of a markdown text with the given info string.
fn code_blocks<'a>(markdown: &'a str, language: &str) -> Vec<&'a str> {
    let fence = format!("```{language}\n");
    let mut blocks = Vec::new();
    let mut rest = markdown;
    while let Some(start) = rest.find(&fence) {
        let body = &rest[start + fence.len()..];
        let end = body.find("\n```").expect("unterminated code block");
        blocks.push(&body[..end + 1]);
        rest = &body[end + 4..];
    }
    blocks
}

/// Compiles the first C block of `doc` inside a `main` that prints the box's height, runs it,
/// and returns the height.
fn run_snippet(doc: &str, name: &str) -> f64 {
    let markdown = read(&root().join(doc));
    let blocks = code_blocks(&markdown, "c");
    let snippet = blocks.first().unwrap_or_else(|| panic!("{doc} has no C block"));
    let body: String = snippet
        .lines()
        .filter(|l| !l.starts_with("#include"))
        .map(|l| format!("    {l}\n"))
        .collect();
    assert!(
        body.contains("hearth_body_get_transform(world, box, &t)"),
        "{doc}: {snippet}"
    );
    let source = format!(
        "#include \"hearth.h\"\n#include <stdio.h>\n\nint main(void) {{\n{body}    printf(\"%.4f\\n\", (double)t.position.y);\n    return 0;\n}}\n"
    );
    let dir = common::out_dir("docs");
    let file = dir.join(format!("{name}.c"));
    std::fs::write(&file, &source).unwrap();
    let exe = dir.join(name);
    // As a user compiles it, without -Werror: the snippet leaves some outputs unused.
    let mut cmd = compiler(false, &dir);
    cmd.args(["-Wno-error", "-Wno-unused-variable", "-Wno-unused-but-set-variable"]);
    cmd.arg(&file).arg("-o").arg(&exe);
    link(&mut cmd, Link::Shared);
    run(&mut cmd);
    let out = common::run_program(&exe);
    out.trim()
        .parse()
        .unwrap_or_else(|_| panic!("{doc}: snippet printed {out:?}"))
}

#[test]
fn readme_and_api_guide_snippets_leave_the_box_on_the_ground() {
    // The box (half extent 0.5 m) rests on the plane y = 0: its centre at 0.50 m, within the
    // contact solver's resting sag (measured 0.2 mm), 2 mm allowed.
    for (doc, name) in [("README.md", "readme_snippet"), ("docs/API.md", "api_guide_snippet")] {
        let y = run_snippet(doc, name);
        println!("{doc}: the box rests at y = {y} m");
        assert!((y - 0.5).abs() < 2e-3, "{doc}: the box ended at y = {y} m, not 0.50 m");
    }
}

/// The text of a markdown file without fenced code blocks and inline code spans.
fn prose(markdown: &str) -> String {
    let mut out = String::new();
    let mut in_block = false;
    for line in markdown.lines() {
        if line.trim_start().starts_with("```") {
            in_block = !in_block;
            continue;
        }
        if !in_block {
            // Drop `inline code`.
            for (i, part) in line.split('`').enumerate() {
                if i % 2 == 0 {
                    out.push_str(part);
                }
            }
            out.push('\n');
        }
    }
    out
}

/// Relative link targets of a markdown file: `](target)` outside code that is not a URL or
/// an anchor.
fn relative_links(markdown: &str) -> Vec<String> {
    let markdown = prose(markdown);
    let mut links = Vec::new();
    let mut rest = markdown.as_str();
    while let Some(i) = rest.find("](") {
        let after = &rest[i + 2..];
        let end = after.find(')').unwrap_or(after.len());
        let target = after[..end].split('#').next().unwrap_or("").trim().to_string();
        if !target.is_empty() && !target.contains("://") && !target.starts_with("mailto:") {
            links.push(target);
        }
        rest = &after[end.min(after.len())..];
    }
    links
}

fn markdown_files() -> Vec<PathBuf> {
    let mut files = vec![root().join("README.md"), root().join("docs/API.md")];
    for dir in ["examples", "bindings"] {
        let mut stack = vec![root().join(dir)];
        while let Some(d) = stack.pop() {
            for entry in std::fs::read_dir(&d).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    stack.push(path);
                } else if path.file_name().is_some_and(|n| n == "README.md") {
                    files.push(path);
                }
            }
        }
    }
    files
}

#[test]
fn documentation_links_point_into_the_repository() {
    let mut checked = 0;
    for file in markdown_files() {
        let text = read(&file);
        assert!(
            !text.contains("shared/API.md"),
            "{} points at shared/API.md",
            file.display()
        );
        for link in relative_links(&text) {
            let target = file.parent().unwrap().join(&link);
            assert!(
                target.exists(),
                "{}: the link {link} names nothing in the repository",
                file.display()
            );
            // Inside the repository, not beside it.
            let resolved = target.canonicalize().unwrap();
            assert!(
                resolved.starts_with(root().canonicalize().unwrap()),
                "{}: the link {link} leaves the repository",
                file.display()
            );
            checked += 1;
        }
    }
    assert!(checked >= 20, "only {checked} links checked");
}

#[test]
fn every_example_folder_has_a_readme_with_commands() {
    let examples = root().join("examples");
    assert!(examples.join("README.md").is_file(), "examples/README.md missing");
    for entry in std::fs::read_dir(&examples).unwrap() {
        let dir = entry.unwrap().path();
        if !dir.is_dir() {
            continue;
        }
        let readme = dir.join("README.md");
        assert!(readme.is_file(), "{} has no README.md", dir.display());
        let text = read(&readme);
        let commands = code_blocks(&text, "sh");
        assert!(
            !commands.is_empty(),
            "{} has no ```sh block with its build and run commands",
            readme.display()
        );
    }
}

#[test]
fn every_header_item_has_a_reference_group() {
    let out = Command::new("python3")
        .current_dir(root())
        .args(["docs/doxygen_filter.py", "--check", "include/hearth.h"])
        .output()
        .expect("python3");
    assert!(
        out.status.success(),
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    // Every group the filter uses is defined in docs/reference.dox.
    let groups = read(&root().join("docs/reference.dox"));
    let filter = read(&root().join("docs/doxygen_filter.py"));
    for line in filter.lines() {
        let line = line.trim();
        if let Some(rest) = line.strip_prefix("(\"") {
            let group = &rest[..rest.find('"').unwrap()];
            assert!(
                groups.contains(&format!("\\defgroup {group} ")),
                "group {group} has no \\defgroup in docs/reference.dox"
            );
        }
    }
}
