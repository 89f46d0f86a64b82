//! The house rules, checked from the source text (no build of anything else needed):
//! dependencies between the top-level modules of each crate of `src/` (the library, and
//! the binary in `src/bin/glint/`) point one way, so do those between the files of every
//! module folder at any depth, no function in `src/` is longer than 100 lines, in Rust
//! or WGSL, and no file of the library (`src/` outside `src/bin/`) longer than 800; every
//! WGSL file sits beside its Rust twin (`X.wgsl` beside `X.rs`), but for
//! the few listed in [`WGSL_WITHOUT_RUST_BESIDE`].
//! Test modules (`#[cfg(test)] mod tests` and what follows it) are not counted: tests may
//! reach anywhere.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The longest function the house allows, in lines from its `fn` line to its closing brace.
const MAX_FUNCTION_LINES: usize = 100;

/// The longest library file the house allows, in lines (Rust or WGSL, test module included).
const MAX_LIBRARY_FILE_LINES: usize = 800;

/// The source roots of the package's crates, each checked on its own (`crate::` names its
/// own root): the library (`src/`, `src/bin/` left out) and the binary `glint`.
const CRATE_ROOTS: [&str; 2] = ["src", "src/bin/glint"];

/// One source file: its path relative to its crate's root (with `/` separators) and its
/// text without the test module.
struct SourceFile {
    relative: String,
    text: String,
}

/// The files of the crate whose sources lie under `root` (one of [`CRATE_ROOTS`]).
fn source_files(root: &str) -> Vec<SourceFile> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join(root);
    let mut paths = Vec::new();
    collect_rust_files(&src, &mut paths);
    paths.sort();
    paths
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).expect("read a source file");
            let relative = path
                .strip_prefix(&src)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            SourceFile {
                relative,
                text: without_test_module(&text).to_string(),
            }
        })
        .collect()
}

fn collect_rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("read src/") {
        let path = entry.unwrap().path();
        // The binaries under src/bin/ are crates of their own.
        if path.is_dir() && !path.ends_with("src/bin") {
            collect_rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The text before the file's `#[cfg(test)]` test module, if it has one.
fn without_test_module(text: &str) -> &str {
    let mut search_from = 0;
    while let Some(found) = text[search_from..].find("#[cfg(test)]") {
        let at = search_from + found;
        let rest = text[at + "#[cfg(test)]".len()..].trim_start();
        if rest.starts_with("mod tests") {
            return &text[..at];
        }
        search_from = at + 1;
    }
    text
}

/// The names that `text` uses under `prefix` (e.g. `crate::` gives the top-level modules):
/// every `prefix name` path and every name inside a `use prefix{a, b::c}` group.
fn names_used_under(text: &str, prefix: &str) -> BTreeSet<String> {
    let mut names = BTreeSet::new();
    let mut rest = text;
    while let Some(at) = rest.find(prefix) {
        let preceded_by_ident = rest[..at]
            .chars()
            .next_back()
            .is_some_and(|c| c.is_alphanumeric() || c == '_');
        let after = &rest[at + prefix.len()..];
        if !preceded_by_ident {
            if let Some(group) = after.strip_prefix('{') {
                let end = group.find("};").unwrap_or(group.len());
                names.extend(group_heads(&group[..end]));
            } else {
                let name: String = after
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if !name.is_empty() {
                    names.insert(name);
                }
            }
        }
        rest = after;
    }
    names
}

/// The first path segment of each top-level item of a `{a, b::{c, d}, e::f}` group.
fn group_heads(group: &str) -> Vec<String> {
    let mut heads = Vec::new();
    let mut depth = 0;
    let mut at_item_start = true;
    let mut current = String::new();
    for c in group.chars() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                at_item_start = true;
                continue;
            }
            _ => {}
        }
        if depth == 0 && at_item_start {
            if c.is_alphanumeric() || c == '_' {
                current.push(c);
            } else if !current.is_empty() {
                heads.push(std::mem::take(&mut current));
                at_item_start = false;
            }
        }
    }
    if !current.is_empty() {
        heads.push(current);
    }
    heads
}

/// The cycles of a dependency graph: each set of nodes that all reach one another, sorted.
fn cycles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    let reach = |from: &str| -> BTreeSet<String> {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from.to_string()];
        while let Some(node) = stack.pop() {
            for next in graph.get(&node).into_iter().flatten() {
                if graph.contains_key(next) && seen.insert(next.clone()) {
                    stack.push(next.clone());
                }
            }
        }
        seen
    };
    let reachable: BTreeMap<&String, BTreeSet<String>> =
        graph.keys().map(|k| (k, reach(k))).collect();
    let mut found: BTreeSet<Vec<String>> = BTreeSet::new();
    for (node, reached) in &reachable {
        if !reached.contains(*node) {
            continue; // not on a cycle
        }
        // A BTreeSet iterates in order, so the component comes out sorted.
        let component: Vec<String> = reached
            .iter()
            .filter(|other| reachable[other].contains(*node))
            .cloned()
            .collect();
        found.insert(component);
    }
    found.into_iter().collect()
}

fn top_module(relative: &str) -> String {
    relative
        .split('/')
        .next()
        .unwrap()
        .trim_end_matches(".rs")
        .to_string()
}

#[test]
fn top_level_modules_depend_one_way() {
    for root in CRATE_ROOTS {
        let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for file in source_files(root) {
            let module = top_module(&file.relative);
            let uses = names_used_under(&file.text, "crate::");
            graph
                .entry(module.clone())
                .or_default()
                .extend(uses.into_iter().filter(|u| *u != module));
        }
        let found = cycles(&graph);
        assert!(
            found.is_empty(),
            "import cycles between top-level modules of {root}/: {found:?}"
        );
    }
}

/// The module path of a file relative to `src/`: `scene/lua/args.rs` is
/// `[scene, lua, args]`, a folder's `mod.rs` is the folder's own module.
fn module_path(relative: &str) -> Vec<String> {
    let mut path: Vec<String> = relative
        .trim_end_matches(".rs")
        .split('/')
        .map(str::to_string)
        .collect();
    if path.last().is_some_and(|last| last == "mod") {
        path.pop();
    }
    path
}

/// `(folder, child)` for each module a file reaches by path: `crate::a::b::c` names `b`
/// in folder `a` and `c` in folder `a/b`; `super::x` names `x` in the folder of the
/// file's parent module, `super::super::x` one level up, and so on.
fn reached_children(module: &[String], text: &str) -> BTreeSet<(String, String)> {
    let mut reached = BTreeSet::new();
    for depth in 1..module.len() {
        let folder = &module[..depth];
        let prefix = format!("crate::{}::", folder.join("::"));
        for child in names_used_under(text, &prefix) {
            reached.insert((folder.join("/"), child));
        }
    }
    let mut search_from = 0;
    while let Some(found) = text[search_from..].find("super::") {
        let at = search_from + found;
        search_from = at + "super::".len();
        let before = text[..at].chars().next_back();
        if before.is_some_and(|c| c == ':' || c.is_alphanumeric() || c == '_') {
            continue; // a later `super::` of a chain, or part of a longer name
        }
        let mut levels = 0;
        let mut rest = &text[at..];
        while let Some(after) = rest.strip_prefix("super::") {
            levels += 1;
            rest = after;
        }
        if levels > module.len() {
            continue;
        }
        // The absolute path the reference names, down to its last plain segment; a
        // `{…}` group at the end contributes each of its heads.
        let mut path: Vec<String> = module[..module.len() - levels].to_vec();
        let mut tails = Vec::new();
        loop {
            if let Some(group) = rest.strip_prefix('{') {
                tails = group_heads(&group[..group.find("};").unwrap_or(group.len())]);
                break;
            }
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if name.is_empty() {
                break;
            }
            rest = &rest[name.len()..];
            path.push(name);
            match rest.strip_prefix("::") {
                Some(after) => rest = after,
                None => break,
            }
        }
        for k in 1..path.len() {
            reached.insert((path[..k].join("/"), path[k].clone()));
        }
        for tail in tails.into_iter().filter(|t| !t.is_empty()) {
            reached.insert((path.join("/"), tail));
        }
    }
    reached
}

/// The import cycles among the children of every folder of `files`, at any depth: each
/// child (a file, or a sub-folder with everything in it) is a node, and a file's
/// reference to a sibling's path an edge.
fn folder_cycles(files: &[SourceFile]) -> Vec<String> {
    let mut graphs: BTreeMap<String, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for file in files {
        let module = module_path(&file.relative);
        let own = file.relative.trim_end_matches(".rs");
        let segments: Vec<&str> = own.split('/').collect();
        // The node this file belongs to in each folder above it.
        for depth in 1..segments.len() {
            let folder = segments[..depth].join("/");
            let node = segments[depth].to_string();
            graphs.entry(folder).or_default().entry(node).or_default();
        }
        for (folder, child) in reached_children(&module, &file.text) {
            let folder_segments = folder.split('/').count();
            if !own.starts_with(&format!("{folder}/")) || segments.len() <= folder_segments {
                continue; // a reference into a folder from outside it
            }
            let node = segments[folder_segments].to_string();
            if node != child {
                graphs
                    .entry(folder)
                    .or_default()
                    .entry(node)
                    .or_default()
                    .insert(child);
            }
        }
    }
    let mut problems = Vec::new();
    for (folder, graph) in &graphs {
        for cycle in cycles(graph) {
            problems.push(format!("{folder}/: {}", cycle.join(" <-> ")));
        }
    }
    problems
}

#[test]
fn files_of_every_module_folder_depend_one_way() {
    for root in CRATE_ROOTS {
        let problems = folder_cycles(&source_files(root));
        assert!(
            problems.is_empty(),
            "import cycles between files of one folder of {root}/: {problems:#?}"
        );
    }
}

/// The folder check sees nested folders: a cycle two levels down (and one through
/// `super::` and a `crate::` path alike) is found; a parent using its children is not one.
#[test]
fn the_folder_check_finds_a_nested_cycle() {
    let file = |relative: &str, text: &str| SourceFile {
        relative: relative.to_string(),
        text: text.to_string(),
    };
    let cyclic = [
        file("scene/lua/mod.rs", "mod a; mod b; use a::x;"),
        file("scene/lua/a.rs", "use super::b::Y;"),
        file("scene/lua/b.rs", "use crate::scene::lua::{a::X, mod_item};"),
        file("scene/mod.rs", "mod lua;"),
    ];
    assert_eq!(
        folder_cycles(&cyclic),
        vec!["scene/lua/: a <-> b".to_string()]
    );
    let deeper = [
        file("scene/lua/deep/p.rs", "use super::q::Z;"),
        file("scene/lua/deep/q.rs", "use super::super::deep::p::W;"),
    ];
    assert_eq!(
        folder_cycles(&deeper),
        vec!["scene/lua/deep/: p <-> q".to_string()]
    );
    let one_way = [
        file("scene/lua/a.rs", "use super::b::Y;"),
        file("scene/lua/b.rs", "use super::with_state;"),
        file("scene/flatten.rs", "use crate::scene::lua::a;"),
        file(
            "scene/lua/mod.rs",
            "mod a; mod b; use a::x; use crate::scene::options::O;",
        ),
    ];
    assert_eq!(folder_cycles(&one_way), Vec::<String>::new());
    // A sub-folder is one node of its parent folder: lua/a -> flatten -> lua is a cycle.
    let across = [
        file("scene/lua/a.rs", "use crate::scene::flatten::F;"),
        file("scene/flatten.rs", "use crate::scene::lua::a::A;"),
    ];
    assert_eq!(
        folder_cycles(&across),
        vec!["scene/: flatten <-> lua".to_string()]
    );
}

/// `(file, line, name, length)` of every function longer than the limit.
fn long_functions(files: &[SourceFile]) -> Vec<(String, usize, String, usize)> {
    let mut long = Vec::new();
    for file in files {
        let lines: Vec<&str> = file.text.lines().collect();
        for (start, line) in lines.iter().enumerate() {
            let Some(name) = function_name(line) else {
                continue;
            };
            let mut depth: i64 = 0;
            let mut opened = false;
            let mut end = start;
            while end < lines.len() {
                depth += lines[end].matches('{').count() as i64;
                depth -= lines[end].matches('}').count() as i64;
                opened |= lines[end].contains('{');
                if opened && depth <= 0 {
                    break;
                }
                end += 1;
            }
            let length = end - start + 1;
            if length > MAX_FUNCTION_LINES {
                long.push((file.relative.clone(), start + 1, name, length));
            }
        }
    }
    long
}

/// The name of the function a line declares with a body (not a trait method's `;`).
fn function_name(line: &str) -> Option<String> {
    let trimmed = line.trim_start();
    if trimmed.starts_with("//") || trimmed.trim_end().ends_with(';') {
        return None;
    }
    let mut words = trimmed.split_whitespace().peekable();
    while let Some(word) = words.next() {
        let qualifier = word.starts_with("pub")
            || matches!(word, "const" | "async" | "unsafe" | "extern" | "\"C\"");
        if word == "fn" {
            let name: String = words
                .next()?
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            return (!name.is_empty()).then_some(name);
        }
        if !qualifier {
            return None;
        }
    }
    None
}

#[test]
fn no_function_in_src_is_longer_than_the_limit() {
    for root in CRATE_ROOTS {
        let long = long_functions(&source_files(root));
        assert!(
            long.is_empty(),
            "functions over {MAX_FUNCTION_LINES} lines in {root}/: {long:#?}"
        );
    }
}

/// `.wgsl` files of `dir` and its folders, as paths relative to `root` with `/`.
fn wgsl_files(root: &Path, dir: &Path, out: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).expect("read a source folder") {
        let path = entry.unwrap().path();
        if path.is_dir() {
            wgsl_files(root, &path, out);
        } else if path.extension().is_some_and(|e| e == "wgsl") {
            let relative = path.strip_prefix(root).unwrap().to_string_lossy();
            out.push(relative.replace('\\', "/"));
        }
    }
}

/// Every WGSL file of the repository (under `src/` and `shaders/`), sorted.
fn all_wgsl_files() -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in ["src", "shaders"] {
        wgsl_files(root, &root.join(dir), &mut files);
    }
    files.sort();
    files
}

/// The WGSL files with no `X.rs` beside them, and why (sorted by path).
const WGSL_WITHOUT_RUST_BESIDE: &[(&str, &str)] = &[
    (
        "shaders/bench/torus.wgsl",
        "the torus benchmark's kernel, twin of src/bench/ferrari.rs, outside the library's tracer",
    ),
    (
        "shaders/view_present.wgsl",
        "glint view's present pass, which has no CPU twin (src/bin/glint/view/present.rs builds it)",
    ),
];

#[test]
fn every_wgsl_file_sits_beside_its_rust_twin() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let apart: Vec<String> = all_wgsl_files()
        .into_iter()
        .filter(|f| !root.join(f.replace(".wgsl", ".rs")).is_file())
        .collect();
    let listed: Vec<String> = WGSL_WITHOUT_RUST_BESIDE
        .iter()
        .map(|(f, _)| f.to_string())
        .collect();
    assert_eq!(
        apart, listed,
        "WGSL files without an X.rs beside them (left) vs WGSL_WITHOUT_RUST_BESIDE (right)"
    );
}

#[test]
fn no_wgsl_function_is_longer_than_the_limit() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files: Vec<SourceFile> = all_wgsl_files()
        .into_iter()
        .map(|relative| SourceFile {
            text: std::fs::read_to_string(root.join(&relative)).expect("read a WGSL file"),
            relative,
        })
        .collect();
    assert!(files.len() > 20, "too few WGSL files: {}", files.len());
    let long = long_functions(&files);
    assert!(
        long.is_empty(),
        "WGSL functions over {MAX_FUNCTION_LINES} lines: {long:#?}"
    );
}

/// `(file, lines)` of every file of `files` (paths relative to the repository, with their
/// text) longer than [`MAX_LIBRARY_FILE_LINES`].
fn long_files(files: &[(String, String)]) -> Vec<(String, usize)> {
    files
        .iter()
        .map(|(relative, text)| (relative.clone(), text.lines().count()))
        .filter(|(_, lines)| *lines > MAX_LIBRARY_FILE_LINES)
        .collect()
}

/// The library's Rust and WGSL files (`src/` outside `src/bin/`), whole, with their paths
/// relative to the repository.
fn library_files() -> Vec<(String, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut paths = Vec::new();
    collect_rust_files(&root.join("src"), &mut paths);
    let mut relatives: Vec<String> = paths
        .iter()
        .map(|p| {
            p.strip_prefix(root)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/")
        })
        .collect();
    relatives.extend(
        all_wgsl_files()
            .into_iter()
            .filter(|f| f.starts_with("src/")),
    );
    relatives.retain(|f| !f.starts_with("src/bin/"));
    relatives.sort();
    relatives
        .into_iter()
        .map(|relative| {
            let text = std::fs::read_to_string(root.join(&relative)).expect("read a source file");
            (relative, text)
        })
        .collect()
}

#[test]
fn no_library_file_is_longer_than_the_limit() {
    let files = library_files();
    assert!(
        files.iter().any(|(f, _)| f.ends_with(".wgsl")) && files.len() > 100,
        "too few library files: {}",
        files.len()
    );
    let long = long_files(&files);
    assert!(
        long.is_empty(),
        "library files over {MAX_LIBRARY_FILE_LINES} lines (split them by concern): {long:#?}"
    );
}

#[test]
fn the_checks_find_what_they_look_for() {
    // A cycle, a one-way chain, a grouped import and a long function, from text.
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    graph.insert("a".into(), BTreeSet::from(["b".into()]));
    graph.insert("b".into(), BTreeSet::from(["c".into()]));
    graph.insert("c".into(), BTreeSet::from(["a".into()]));
    graph.insert("d".into(), BTreeSet::from(["a".into()]));
    assert_eq!(
        cycles(&graph),
        vec![vec!["a".to_string(), "b".into(), "c".into()]]
    );
    graph.get_mut("c").unwrap().clear();
    assert!(cycles(&graph).is_empty());

    let uses = names_used_under(
        "use crate::{cpu::x, gpu::{a, b}, pack};\nfn f() { crate::scene::g() }",
        "crate::",
    );
    assert_eq!(
        uses,
        BTreeSet::from(["cpu".into(), "gpu".into(), "pack".into(), "scene".into()])
    );
    assert!(names_used_under("my_crate::cpu", "crate::").is_empty());

    let body = "    x();\n".repeat(MAX_FUNCTION_LINES);
    let text = format!("pub(crate) fn too_long() {{\n{body}}}\nfn short() {{}}\n");
    let long = long_functions(&[SourceFile {
        relative: "x.rs".into(),
        text,
    }]);
    assert_eq!(
        long,
        vec![(
            "x.rs".to_string(),
            1,
            "too_long".to_string(),
            MAX_FUNCTION_LINES + 2
        )]
    );
    assert_eq!(
        without_test_module("a\n#[cfg(test)]\nmod tests {}\n"),
        "a\n"
    );

    let lines = |n: usize| "x\n".repeat(n);
    let files = [
        ("src/a.rs".to_string(), lines(MAX_LIBRARY_FILE_LINES)),
        ("src/b.wgsl".to_string(), lines(MAX_LIBRARY_FILE_LINES + 1)),
    ];
    assert_eq!(
        long_files(&files),
        vec![("src/b.wgsl".to_string(), MAX_LIBRARY_FILE_LINES + 1)]
    );
}
