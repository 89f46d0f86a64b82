//! The library is a library: no source file of the library crate (`src/`, `src/bin/` left
//! out) uses a crate that only the `glint` binary needs — clap (the command line),
//! indicatif (the progress bar), winit (the view's window) or ash (the kernel
//! instrument's Vulkan calls) — and Cargo.toml keeps those optional, behind the `cli`
//! feature the binary requires, so that a program embedding glint builds none of them
//! (`glint = { default-features = false }`). Read from the source text: nothing is built.

use std::path::{Path, PathBuf};

/// The crates only the binary may use.
const BINARY_ONLY: [&str; 4] = ["clap", "indicatif", "winit", "ash"];

fn repository() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The library crate's `.rs` files: everything under `src/` but the binaries in `src/bin/`.
fn library_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("read src/") {
        let path = entry.unwrap().path();
        if path.is_dir() && !path.ends_with("src/bin") {
            library_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// `(line, crate)` for each use of one of `crates` in `text`: a path through it
/// (`clap::Args`, in a `use`, a derive or an expression), or `use`/`extern crate` of it.
/// Comments do not count; a longer name that ends the same (`hash::`) does not either.
fn uses_of(text: &str, crates: &[&str]) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let code = line.split("//").next().unwrap_or("");
        for name in crates {
            for (at, _) in code.match_indices(name) {
                let before = code[..at].chars().next_back();
                let after = &code[at + name.len()..];
                let bounded = !before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':');
                let named = after.starts_with("::")
                    || (after.trim_start().starts_with(';')
                        && (code[..at].trim_end().ends_with("use")
                            || code[..at].trim_end().ends_with("extern crate")));
                if bounded && named {
                    found.push((number + 1, name.to_string()));
                }
            }
        }
    }
    found
}

#[test]
fn no_library_file_uses_a_binary_only_crate() {
    let root = repository();
    let mut files = Vec::new();
    library_files(&root.join("src"), &mut files);
    assert!(files.len() > 50, "only {} library files found", files.len());
    let mut problems = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for (line, name) in uses_of(&text, &BINARY_ONLY) {
            let relative = file.strip_prefix(&root).unwrap().display().to_string();
            problems.push(format!("{relative}:{line}: {name}"));
        }
    }
    assert!(
        problems.is_empty(),
        "the library crate uses the binary's crates (move the code to src/bin/glint/):\n{}",
        problems.join("\n")
    );
}

/// The `[section]` of Cargo.toml's text that `header` opens, up to the next section.
fn section<'a>(toml: &'a str, header: &str) -> &'a str {
    let start = toml
        .find(&format!("\n{header}\n"))
        .unwrap_or_else(|| panic!("Cargo.toml has no {header}"));
    let body = &toml[start + header.len() + 2..];
    &body[..body.find("\n[").unwrap_or(body.len())]
}

#[test]
fn cargo_toml_builds_them_for_the_binary_only() {
    let toml = std::fs::read_to_string(repository().join("Cargo.toml")).unwrap();
    let dependencies = section(&toml, "[dependencies]");
    let features = section(&toml, "[features]");
    let cli = features
        .lines()
        .find(|l| l.starts_with("cli ="))
        .expect("a `cli` feature");
    for name in BINARY_ONLY {
        let line = dependencies
            .lines()
            .find(|l| l.starts_with(&format!("{name} =")))
            .unwrap_or_else(|| panic!("{name} is not a dependency"));
        assert!(
            line.contains("optional = true"),
            "{name} is not optional: {line}"
        );
        assert!(
            cli.contains(&format!("\"dep:{name}\"")),
            "cli lacks {name}: {cli}"
        );
    }
    let bin = section(&toml, "[[bin]]");
    assert!(
        bin.contains("name = \"glint\"") && bin.contains("required-features = [\"cli\"]"),
        "the glint binary must require the cli feature:\n{bin}"
    );
}

#[test]
fn the_check_finds_what_it_looks_for() {
    let text = "use clap::Args;\n\
                #[derive(Debug, clap::ValueEnum)]\n\
                // clap::Args in a comment\n\
                let h = std::hash::Hash; let p = ash_tray::x;\n\
                extern crate winit;\n\
                fn f() { let _ = indicatif::ProgressBar::new(1); } // winit::x\n";
    assert_eq!(
        uses_of(text, &BINARY_ONLY),
        vec![
            (1, "clap".to_string()),
            (2, "clap".to_string()),
            (5, "winit".to_string()),
            (6, "indicatif".to_string()),
        ]
    );
}
