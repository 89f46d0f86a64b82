//! The docs' links hold: every relative link of README.md and docs/ (journal included)
//! points at a file that exists, and at a heading of it where it names an anchor (GitHub's
//! slug rules); every `docs/….md` or `docs/….md#anchor` that a comment in src/, shaders/,
//! tests/ or tools/ cites does too. External http(s) links are not checked. Also: the
//! README is a front page of at most 150 lines, and every reference page in docs/ (the
//! journal apart) at most 400. Plain std, read from the source text: nothing is built.

use std::collections::{HashMap, HashSet};
use std::path::{Component, Path, PathBuf};

const README_MAX_LINES: usize = 150;
const REFERENCE_PAGE_MAX_LINES: usize = 400;

/// GitHub's anchor for a heading: the rendered text (link targets, HTML tags and inline
/// markup left out) lower-cased, every character but letters, digits, `_`, `-` and spaces
/// dropped, and each space turned into a `-`.
fn slug(heading: &str) -> String {
    let mut rendered = String::new();
    let mut rest = heading;
    while let Some(open) = rest.find("](") {
        let close = rest[open..].find(')').map_or(rest.len(), |c| open + c + 1);
        rendered.push_str(&rest[..open]);
        rest = &rest[close..];
    }
    rendered.push_str(rest);
    let mut out = String::new();
    let mut in_tag = false;
    for ch in rendered.trim().chars() {
        match ch {
            '<' => in_tag = true,
            '>' if in_tag => in_tag = false,
            _ if in_tag => {}
            ' ' => out.push('-'),
            '-' | '_' => out.push(ch),
            _ if ch.is_alphanumeric() => out.extend(ch.to_lowercase()),
            _ => {}
        }
    }
    out
}

/// The lines of a markdown text outside fenced code blocks, with their 1-based numbers.
fn prose_lines(markdown: &str) -> Vec<(usize, &str)> {
    let mut in_fence = false;
    let mut lines = Vec::new();
    for (index, line) in markdown.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            in_fence = !in_fence;
        } else if !in_fence {
            lines.push((index + 1, line));
        }
    }
    lines
}

/// The heading text of an ATX heading line (`## Text ##`), if it is one.
fn heading_text(line: &str) -> Option<&str> {
    let hashes = line.len() - line.trim_start_matches('#').len();
    let rest = &line[hashes..];
    if !(1..=6).contains(&hashes) || !rest.starts_with(' ') {
        return None;
    }
    Some(rest.trim().trim_end_matches('#').trim_end())
}

/// Every anchor a markdown text has: its headings' slugs, a repeated slug numbered
/// `-1`, `-2`… in order, as GitHub numbers them.
fn anchors(markdown: &str) -> HashSet<String> {
    let mut seen: HashMap<String, usize> = HashMap::new();
    let mut anchors = HashSet::new();
    for (_, line) in prose_lines(markdown) {
        let Some(text) = heading_text(line) else {
            continue;
        };
        let base = slug(text);
        let count = seen.entry(base.clone()).or_insert(0);
        anchors.insert(if *count == 0 {
            base.clone()
        } else {
            format!("{base}-{count}")
        });
        *count += 1;
    }
    anchors
}

/// The targets of a line's inline links and images, `[text](target)`, code spans left out.
fn link_targets(line: &str) -> Vec<&str> {
    let prose: Vec<&str> = line.split('`').step_by(2).collect();
    let mut targets = Vec::new();
    for part in prose {
        let mut rest = part;
        while let Some(open) = rest.find("](") {
            let after = &rest[open + 2..];
            let end = after.find([')', ' ']).unwrap_or(after.len());
            targets.push(&after[..end]);
            rest = &after[end..];
        }
    }
    targets
}

/// The `docs/….md` paths, with their `#anchor` where one follows, that a source line cites.
fn doc_citations(line: &str) -> Vec<&str> {
    let is_path_char = |c: char| c.is_ascii_alphanumeric() || "/._-".contains(c);
    let mut citations = Vec::new();
    for (start, _) in line.match_indices("docs/") {
        if line[..start].chars().next_back().is_some_and(is_path_char) {
            continue;
        }
        let path_len = line[start..]
            .find(|c: char| !is_path_char(c))
            .unwrap_or(line.len() - start);
        let path = line[start..start + path_len].trim_end_matches('.');
        if !path.ends_with(".md") {
            continue;
        }
        let after = &line[start + path.len()..];
        let anchor_len = match after.strip_prefix('#') {
            Some(anchor) => {
                1 + anchor
                    .find(|c: char| !(c.is_alphanumeric() || c == '-' || c == '_'))
                    .unwrap_or(anchor.len())
            }
            None => 0,
        };
        citations.push(&line[start..start + path.len() + anchor_len]);
    }
    citations
}

/// `a/b/../c` as `a/c`, without touching the file system.
fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for component in path.components() {
        match component {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// Resolves link targets against files and their headings, reading each file once.
struct Checker<'a> {
    /// A markdown file's text, `None` where there is none.
    read: &'a dyn Fn(&Path) -> Option<String>,
    /// Whether any other file (an image, a folder, a scene) exists.
    exists: &'a dyn Fn(&Path) -> bool,
    anchors: HashMap<PathBuf, Option<HashSet<String>>>,
}

impl<'a> Checker<'a> {
    fn new(read: &'a dyn Fn(&Path) -> Option<String>, exists: &'a dyn Fn(&Path) -> bool) -> Self {
        Checker {
            read,
            exists,
            anchors: HashMap::new(),
        }
    }

    /// `Ok` when `target` (a path relative to `from_file`'s folder, with an optional
    /// `#anchor`, or an anchor alone in `from_file`) exists; otherwise why not.
    fn check(&mut self, from_file: &Path, target: &str) -> Result<(), String> {
        if target.contains("://") || target.starts_with("mailto:") {
            return Ok(());
        }
        let (path, anchor) = target
            .split_once('#')
            .map_or((target, None), |(p, a)| (p, Some(a)));
        let file = if path.is_empty() {
            from_file.to_path_buf()
        } else {
            normalise(&from_file.parent().unwrap_or(Path::new("")).join(path))
        };
        let is_markdown = file.extension().is_some_and(|e| e == "md");
        let read = self.read;
        let anchors = self.anchors.entry(file.clone()).or_insert_with(|| {
            if is_markdown {
                read(&file).map(|text| anchors(&text))
            } else {
                None
            }
        });
        match (anchors, anchor) {
            (None, _) if !is_markdown && (self.exists)(&file) => Ok(()),
            (None, _) => Err(format!("{} does not exist", file.display())),
            (Some(_), None) => Ok(()),
            (Some(found), Some(anchor)) if found.contains(anchor) => Ok(()),
            (Some(_), Some(anchor)) => Err(format!(
                "{} has no heading with the anchor #{anchor}",
                file.display()
            )),
        }
    }

    /// The broken targets among `lines` (line number, targets on it) of `file`, each as
    /// `file:line: target: why`; `from_file` is what relative targets start from.
    fn broken<'t>(
        &mut self,
        file: &Path,
        from_file: &Path,
        lines: impl IntoIterator<Item = (usize, Vec<&'t str>)>,
    ) -> Vec<String> {
        let mut broken = Vec::new();
        for (number, targets) in lines {
            for target in targets {
                if let Err(why) = self.check(from_file, target) {
                    broken.push(format!("{}:{number}: {target}: {why}", file.display()));
                }
            }
        }
        broken
    }
}

/// The broken links of one markdown file.
fn broken_links_of_markdown(checker: &mut Checker, file: &Path, text: &str) -> Vec<String> {
    let lines = prose_lines(text)
        .into_iter()
        .map(|(number, line)| (number, link_targets(line)));
    checker.broken(file, file, lines)
}

/// The broken `docs/…` citations of one source file: paths from the repository's root.
fn broken_citations_of_source(checker: &mut Checker, file: &Path, text: &str) -> Vec<String> {
    let lines = text
        .lines()
        .enumerate()
        .map(|(index, line)| (index + 1, doc_citations(line)));
    checker.broken(file, Path::new("a-file-at-the-root"), lines)
}

fn repository() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every file under `folder` (relative to the repository), recursively, sorted.
fn files_under(folder: &str) -> Vec<PathBuf> {
    let root = repository();
    let mut pending = vec![root.join(folder)];
    let mut files = Vec::new();
    while let Some(dir) = pending.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                pending.push(path);
            } else {
                files.push(
                    path.strip_prefix(&root)
                        .expect("under the repository")
                        .to_path_buf(),
                );
            }
        }
    }
    files.sort();
    files
}

fn read_in_repository(path: &Path) -> Option<String> {
    std::fs::read_to_string(repository().join(path)).ok()
}

fn exists_in_repository(path: &Path) -> bool {
    repository().join(path).exists()
}

fn markdown_pages() -> Vec<PathBuf> {
    let docs = files_under("docs")
        .into_iter()
        .filter(|p| p.extension().is_some_and(|e| e == "md"));
    std::iter::once(PathBuf::from("README.md"))
        .chain(docs)
        .collect()
}

#[test]
fn every_relative_link_of_readme_and_docs_exists() {
    let mut checker = Checker::new(&read_in_repository, &exists_in_repository);
    let mut broken = Vec::new();
    for page in markdown_pages() {
        let text = read_in_repository(&page).expect("read a markdown page");
        broken.extend(broken_links_of_markdown(&mut checker, &page, &text));
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn every_docs_page_cited_by_the_code_exists_with_its_anchor() {
    let this_file = Path::new(file!()); // its unit tests cite broken pages on purpose
    let mut checker = Checker::new(&read_in_repository, &exists_in_repository);
    let mut broken = Vec::new();
    let mut cited = 0;
    for file in ["src", "shaders", "tests", "tools"]
        .into_iter()
        .flat_map(files_under)
    {
        let Some(text) = read_in_repository(&file).filter(|_| file != this_file) else {
            continue;
        };
        cited += text
            .lines()
            .map(|line| doc_citations(line).len())
            .sum::<usize>();
        broken.extend(broken_citations_of_source(&mut checker, &file, &text));
    }
    assert!(
        cited >= 20,
        "only {cited} citations of docs/ found: the scan is broken"
    );
    assert!(
        broken.is_empty(),
        "broken citations of docs/:\n{}",
        broken.join("\n")
    );
}

#[test]
fn readme_and_reference_pages_stay_short() {
    let mut too_long = Vec::new();
    for page in markdown_pages() {
        let lines = read_in_repository(&page)
            .expect("read a markdown page")
            .lines()
            .count();
        let limit = if page == Path::new("README.md") {
            README_MAX_LINES
        } else {
            REFERENCE_PAGE_MAX_LINES
        };
        if !page.starts_with("docs/journal") && lines > limit {
            too_long.push(format!(
                "{}: {lines} lines (at most {limit})",
                page.display()
            ));
        }
    }
    assert!(
        too_long.is_empty(),
        "dated material belongs in docs/journal/:\n{}",
        too_long.join("\n")
    );
}

#[cfg(test)]
mod checker {
    use super::*;

    /// A tiny repository in memory: `docs/page.md` with three headings, one repeated.
    fn synthetic(path: &Path) -> Option<String> {
        match path.to_str()? {
            "docs/page.md" => Some("# Page\n\n## Mesh walks (2026-11-30, evening)\n\n```\n## not a heading\n```\n## Notes\n## Notes\n".into()),
            "docs/other.md" => Some("# Other\n".into()),
            _ => None,
        }
    }

    fn image_exists(path: &Path) -> bool {
        path == Path::new("docs/plot.svg")
    }

    fn broken(text: &str) -> Vec<String> {
        let mut checker = Checker::new(&synthetic, &image_exists);
        broken_links_of_markdown(&mut checker, Path::new("docs/other.md"), text)
    }

    #[test]
    fn slugs_follow_githubs_rules() {
        assert_eq!(slug("Lavapipe's loop limit"), "lavapipes-loop-limit");
        assert_eq!(
            slug("Results: strides, empty cells and transposed loads (1 December 2026, morning)"),
            "results-strides-empty-cells-and-transposed-loads-1-december-2026-morning"
        );
        assert_eq!(
            slug("Sampling settings: error against time (`glint bench --sweep`)"),
            "sampling-settings-error-against-time-glint-bench---sweep"
        );
        assert_eq!(
            slug("Exact triangle–cell overlap (30 November)"),
            "exact-trianglecell-overlap-30-november"
        );
        assert_eq!(
            slug("The 10⁶ case, **bold**, [linked](x.md) <b>tag</b>"),
            "the-10⁶-case-bold-linked-tag"
        );
    }

    #[test]
    fn repeated_headings_are_numbered_and_fenced_ones_do_not_count() {
        let found = anchors(&synthetic(Path::new("docs/page.md")).unwrap());
        let expected: HashSet<String> =
            ["page", "mesh-walks-2026-11-30-evening", "notes", "notes-1"]
                .map(String::from)
                .into();
        assert_eq!(found, expected);
    }

    #[test]
    fn good_links_pass() {
        let text = "[a](page.md) [b](page.md#notes-1) ![c](plot.svg) [d](#other) [e](https://example.com/x#y) `[f](gone.md)`\n```\n[g](gone.md)\n```\n";
        assert_eq!(broken(text), Vec::<String>::new());
    }

    #[test]
    fn a_broken_anchor_a_missing_page_and_a_missing_image_fail() {
        let found = broken(
            "[a](page.md#mesh-walks) and [b](../docs/gone.md)\n![c](missing.svg) [d](#nowhere)\n",
        );
        assert_eq!(found.len(), 4, "{found:?}");
        assert!(
            found[0]
                .starts_with("docs/other.md:1: page.md#mesh-walks: docs/page.md has no heading"),
            "{}",
            found[0]
        );
        assert!(
            found[1].contains("docs/gone.md does not exist"),
            "{}",
            found[1]
        );
        assert!(
            found[2].starts_with("docs/other.md:2: missing.svg"),
            "{}",
            found[2]
        );
        assert!(found[3].contains("#nowhere"), "{}", found[3]);
    }

    #[test]
    fn citations_in_code_are_found_and_checked() {
        let line = "// measured (docs/page.md#notes, docs/page.md#gone). See docs/gone.md. Not mydocs/page.md";
        assert_eq!(
            doc_citations(line),
            ["docs/page.md#notes", "docs/page.md#gone", "docs/gone.md"]
        );
        let mut checker = Checker::new(&synthetic, &image_exists);
        let found = broken_citations_of_source(&mut checker, Path::new("src/x.rs"), line);
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(
            found[0].starts_with(
                "src/x.rs:1: docs/page.md#gone: docs/page.md has no heading with the anchor #gone"
            ),
            "{}",
            found[0]
        );
    }
}
