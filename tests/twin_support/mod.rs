//! Reads glint's two tracers as text for `tests/gpu/twins.rs`: each declaration (function,
//! struct, constant, variable) of the Rust sources under `src/` and the WGSL under
//! `shaders/`, the "Mirror of … — change both." comment above it, and a function's
//! parameters. Line-based, relying on rustfmt's layout (top-level items at column 0,
//! members of an `impl` indented once), which `cargo fmt --check` enforces; WGSL has no
//! nesting of declarations. What the functions do is read by parsers: the WGSL's by naga
//! ([`wgsl_calls`]), the Rust's by syn ([`rust_calls`]), compared in [`calls`].

use std::path::Path;

pub mod calls;
pub mod rust_calls;
pub mod wgsl_calls;

/// A "Mirror of … — change both." comment.
#[derive(Clone, Debug)]
pub struct TwinRef {
    /// 1-based line of the comment.
    pub line: usize,
    /// What follows "Mirror of ".
    pub text: String,
    /// The file named (`src/…rs` or `shaders/…wgsl`).
    pub path: String,
    /// The declaration named: `name`, or `Type::member` for a member of `impl Type`.
    pub key: Option<String>,
    /// Nothing but `PATH::KEY` (no "the … of" before it, no "'s …" after it): a
    /// one-to-one twin, which must name this declaration back.
    pub exact: bool,
}

/// A declaration of either side.
#[derive(Clone, Debug)]
pub struct Item {
    pub file: String,
    pub line: usize,
    /// `name`, or `Type::name` for a member of `impl Type`.
    pub key: String,
    pub is_fn: bool,
    /// Parameters as written (`name: Type`), receivers (`&self`) included.
    pub params: Vec<String>,
    pub twin: Option<TwinRef>,
}

/// Everything read from one side's files.
#[derive(Default)]
pub struct Sources {
    pub items: Vec<Item>,
    /// Twin comments above no declaration (about a file or a block), with their file.
    pub loose: Vec<(String, TwinRef)>,
    /// "Mirror of" comments that name no `src/…rs` or `shaders/…wgsl` file.
    pub malformed: Vec<String>,
}

const MIRROR: &str = "Mirror of ";
const CHANGE_BOTH: &str = " — change both.";

/// Parses the text after "//" of a twin comment; None when it names no file.
pub fn parse_twin_ref(comment: &str, line: usize) -> Option<TwinRef> {
    let text = comment.split_once(MIRROR)?.1.trim();
    let text = text.strip_suffix(CHANGE_BOTH)?.to_string();
    let start = ["shaders/", "src/"]
        .iter()
        .filter_map(|p| text.find(p))
        .min()?;
    let rest = &text[start..];
    let ext_end = [".wgsl", ".rs"]
        .iter()
        .filter_map(|e| rest.find(e).map(|i| i + e.len()))
        .min()?;
    let path = rest[..ext_end].to_string();
    let after = &rest[ext_end..];
    let (key, suffix) = match after.strip_prefix("::") {
        Some(k) => {
            let end = k
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .unwrap_or(k.len());
            (Some(k[..end].trim_end_matches(':').to_string()), &k[end..])
        }
        None => (None, after),
    };
    let exact = start == 0 && suffix.is_empty() && key.is_some();
    Some(TwinRef {
        line,
        text,
        path,
        key,
        exact,
    })
}

/// Every `.rs` and `.wgsl` under `src/` and every `.wgsl` under `shaders/` of `root`, as
/// (repository path, text), sorted by path.
pub fn source_texts(root: &Path) -> Vec<(String, String)> {
    let mut files = Vec::new();
    for (dir, ext) in [("src", "rs"), ("src", "wgsl"), ("shaders", "wgsl")] {
        collect(&root.join(dir), ext, &mut files);
    }
    files.sort();
    files
        .into_iter()
        .map(|path| {
            let name = path.strip_prefix(root).unwrap().to_string_lossy();
            (
                name.replace('\\', "/"),
                std::fs::read_to_string(&path).unwrap(),
            )
        })
        .collect()
}

fn collect(dir: &Path, ext: &str, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            collect(&path, ext, out);
        } else if path.extension().is_some_and(|e| e == ext) {
            out.push(path);
        }
    }
}

/// Declarations and twin comments of `texts` (as [`source_texts`] gives them).
pub fn parse(texts: &[(String, String)]) -> Sources {
    let mut sources = Sources::default();
    for (file, text) in texts {
        read_file(file, text, &mut sources);
    }
    sources
}

/// Where a line is: at the top level, inside `impl Type`, or inside something else (a
/// `mod`, a `trait`) whose members are not twins.
enum Scope {
    Top,
    Impl(String),
    Other,
}

/// Reads one file's declarations and twin comments into `sources`.
pub fn read_file(file: &str, text: &str, sources: &mut Sources) {
    let wgsl = file.ends_with(".wgsl");
    let lines: Vec<&str> = text.lines().collect();
    let mut scope = Scope::Top;
    let mut pending: Option<TwinRef> = None;
    for (index, raw) in lines.iter().enumerate() {
        let line = raw.trim();
        let indent = raw.len() - raw.trim_start().len();
        if let Some(comment) = line.strip_prefix("//") {
            if comment.contains(MIRROR) {
                match parse_twin_ref(comment, index + 1) {
                    Some(twin) => {
                        if let Some(old) = pending.replace(twin) {
                            sources.loose.push((file.to_string(), old));
                        }
                    }
                    None => sources
                        .malformed
                        .push(format!("{file}:{}: {line}", index + 1)),
                }
            }
            continue;
        }
        let code = if wgsl {
            strip_wgsl_attributes(line)
        } else {
            line
        };
        if code.starts_with("#[") || (wgsl && code.is_empty() && !line.is_empty()) {
            continue;
        }
        if !wgsl && indent == 0 {
            scope = top_level_scope(code, scope);
        }
        let declared = declaration(code, wgsl).filter(|_| wgsl || indent <= 4);
        let key = declared.and_then(|(name, is_fn)| match (&scope, indent) {
            (_, 0) => Some((name.to_string(), is_fn)),
            (Scope::Impl(ty), 4) => Some((format!("{ty}::{name}"), is_fn)),
            _ => None,
        });
        match key {
            Some((key, is_fn)) => {
                let params = if is_fn {
                    parameters(&lines[index..])
                } else {
                    Vec::new()
                };
                sources.items.push(Item {
                    file: file.to_string(),
                    line: index + 1,
                    key,
                    is_fn,
                    params,
                    twin: pending.take(),
                });
            }
            None => {
                if let Some(old) = pending.take() {
                    sources.loose.push((file.to_string(), old));
                }
            }
        }
    }
    if let Some(old) = pending {
        sources.loose.push((file.to_string(), old));
    }
}

/// The scope after a column-0 Rust line: `impl … Type {` opens an impl, `mod`/`trait`
/// something else, `}` closes back to the top level.
fn top_level_scope(code: &str, scope: Scope) -> Scope {
    if code == "}" {
        return Scope::Top;
    }
    if let Some(rest) = code.strip_prefix("impl") {
        let rest = skip_generics(rest.trim_end_matches('{').trim());
        let ty = rest.rsplit(" for ").next().unwrap_or(rest).trim();
        let path: String = ty
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
            .collect();
        return Scope::Impl(path.rsplit("::").next().unwrap_or("").to_string());
    }
    let visible = strip_visibility(code);
    if (visible.starts_with("mod ") || visible.starts_with("trait ")) && code.ends_with('{') {
        return Scope::Other;
    }
    scope
}

/// `text` without a leading `<…>` (an impl's generic parameters).
fn skip_generics(text: &str) -> &str {
    if !text.starts_with('<') {
        return text;
    }
    let mut depth = 0;
    for (i, c) in text.char_indices() {
        depth += i32::from(c == '<') - i32::from(c == '>');
        if depth == 0 {
            return text[i + 1..].trim_start();
        }
    }
    text
}

/// `line` without its leading WGSL attributes (`@compute`, `@workgroup_size(…)`,
/// `@group(0) @binding(1)`).
fn strip_wgsl_attributes(mut line: &str) -> &str {
    while let Some(rest) = line.strip_prefix('@') {
        let name_end = rest
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(rest.len());
        let mut after = &rest[name_end..];
        if after.starts_with('(') {
            let mut depth = 0;
            let close = after
                .char_indices()
                .find(|&(_, c)| {
                    depth += i32::from(c == '(') - i32::from(c == ')');
                    depth == 0
                })
                .map_or(after.len(), |(i, _)| i + 1);
            after = &after[close..];
        }
        line = after.trim_start();
    }
    line
}

fn strip_visibility(code: &str) -> &str {
    if let Some(rest) = code.strip_prefix("pub(") {
        return rest.split_once(')').map_or(rest, |(_, r)| r).trim_start();
    }
    code.strip_prefix("pub ").unwrap_or(code)
}

/// The declared name of a code line and whether it is a function.
fn declaration(code: &str, wgsl: bool) -> Option<(&str, bool)> {
    let code = if wgsl { code } else { strip_visibility(code) };
    let keywords: &[&str] = if wgsl {
        &["fn ", "struct ", "const ", "alias ", "override "]
    } else {
        &[
            "const fn ",
            "fn ",
            "struct ",
            "enum ",
            "const ",
            "static ",
            "type ",
        ]
    };
    let (rest, is_fn) = keywords
        .iter()
        .find_map(|k| code.strip_prefix(k).map(|r| (r, k.ends_with("fn "))))
        .or_else(|| {
            let var = code.strip_prefix("var<").filter(|_| wgsl)?;
            Some((var.split_once('>')?.1.trim_start(), false))
        })?;
    let end = rest
        .find(|c: char| !(c.is_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    (end > 0).then_some((&rest[..end], is_fn))
}

/// The parameters of the function declared on `lines[0]`, split at top-level commas.
fn parameters(lines: &[&str]) -> Vec<String> {
    let text = lines[..lines.len().min(40)].join("\n");
    // The first `(` after `fn ` (not `pub(crate)`'s).
    let Some(open) = text
        .find("fn ")
        .and_then(|f| text[f..].find('(').map(|o| f + o))
    else {
        return Vec::new();
    };
    let mut depth = 0i32;
    let mut params = Vec::new();
    let mut current = String::new();
    let mut previous = ' ';
    for c in text[open..].chars() {
        match c {
            '(' | '[' | '<' => depth += 1,
            // `->` in a closure type is no closing bracket.
            '>' if previous == '-' => {}
            ')' | ']' | '>' => depth -= 1,
            _ => {}
        }
        previous = c;
        if depth == 0 {
            break;
        }
        if c == ',' && depth == 1 {
            params.push(std::mem::take(&mut current));
        } else if !(depth == 1 && c == '(') {
            current.push(c);
        }
    }
    params.push(current);
    params
        .into_iter()
        .map(|p| p.split_whitespace().collect::<Vec<_>>().join(" "))
        .filter(|p| !p.is_empty())
        .collect()
}
