//! The house rules, checked from the source text (no build of anything else needed):
//! dependencies between the top-level modules of `src/` point one way, so do those between
//! the files of one module folder, and no function in `src/` is longer than 100 lines.
//! Test modules (`#[cfg(test)] mod tests` and what follows it) are not counted: tests may
//! reach anywhere.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The longest function the house allows, in lines from its `fn` line to its closing brace.
const MAX_FUNCTION_LINES: usize = 100;

/// One source file: its path relative to `src/` (with `/` separators) and its text
/// without the test module.
struct SourceFile {
    relative: String,
    text: String,
}

fn source_files() -> Vec<SourceFile> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
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
        if path.is_dir() {
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
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for file in source_files() {
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
        "import cycles between top-level modules of src/: {found:?}"
    );
}

#[test]
fn files_of_one_module_folder_depend_one_way() {
    let files = source_files();
    let folders: BTreeSet<String> = files
        .iter()
        .filter(|f| f.relative.contains('/'))
        .map(|f| top_module(&f.relative))
        .collect();
    let mut problems = Vec::new();
    for folder in folders {
        let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for file in files.iter().filter(|f| top_module(&f.relative) == folder) {
            let Some(inside) = file.relative.split_once('/').map(|(_, rest)| rest) else {
                continue;
            };
            let me = inside
                .split('/')
                .next()
                .unwrap()
                .trim_end_matches(".rs")
                .to_string();
            let mut uses = names_used_under(&file.text, &format!("crate::{folder}::"));
            uses.extend(names_used_under(&file.text, "super::"));
            graph
                .entry(me.clone())
                .or_default()
                .extend(uses.into_iter().filter(|u| *u != me));
        }
        for cycle in cycles(&graph) {
            problems.push(format!("{folder}/: {}", cycle.join(" <-> ")));
        }
    }
    assert!(
        problems.is_empty(),
        "import cycles between files of one folder: {problems:#?}"
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
    let long = long_functions(&source_files());
    assert!(
        long.is_empty(),
        "functions over {MAX_FUNCTION_LINES} lines: {long:#?}"
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
}
