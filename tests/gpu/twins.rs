//! The CPU tracer and its WGSL mirror are tied function by function with comments
//! (`// Mirror of src/tracer/geometry/uv.wgsl::triangle_frame — change both.`); this test reads both
//! sides (no GPU: the comments as text, the WGSL through naga, the Rust through syn) and
//! checks that the ties hold:
//! - every twin comment names a file of the other side that exists, and a declaration in
//!   it that exists (so renaming one twin without the other fails here);
//! - pairing is symmetric: a one-to-one twin comment (`PATH::NAME` and nothing else) on
//!   A naming B has a twin comment on B naming A (comments such as "the sample loop of
//!   src/tracer/sampling/render.rs::render_pixel", for a part of a function, need only exist);
//! - twins are paired file by file: a twin of `X.rs` is in `X.wgsl` beside it (every
//!   tracer file, `src/tracer/LAYER/X.rs`, and every other with such a `.wgsl`);
//! - the WGSL functions the line reader sees are those naga sees in the modules (and the
//!   queues' accessors, generated: `queue_twins`);
//! - paired functions take the same number of arguments, once the Rust side's module
//!   state is set aside ([`MODULE_SCOPE`]: what WGSL reads from bindings or private
//!   variables instead of parameters);
//! - paired functions call corresponding twins, in the same order where both call them
//!   unconditionally (what is set aside, by rule, is in `twin_support::calls`);
//! - every WGSL function has a twin, or is on [`WGSL_WITHOUT_TWIN`] with the reason;
//! - twins have the same name: every WGSL function has a Rust function of its name (or
//!   a member `Type::name` that it stands for as `type_name`), or is on
//!   [`WGSL_WITHOUT_TWIN`] or [`WGSL_NAMED_APART`] with the reason, and a one-to-one pair
//!   of function twins is named alike unless it is on [`WGSL_NAMED_APART`].

use crate::queue_twins;
use crate::twin_support;

use std::collections::{BTreeMap, BTreeSet};
use std::collections::{HashMap, HashSet};
use std::path::Path;
use twin_support::calls::{
    first_calls, function_pairs, partial_function_twins, rust_twin_calls, wgsl_twin_calls,
    RustIndex,
};
use twin_support::rust_calls::RustFile;
use twin_support::wgsl_calls::{self, WgslModules};
use twin_support::{parse, rust_calls, Item, Sources, TwinRef};

/// WGSL functions with no Rust twin, and why.
const WGSL_WITHOUT_TWIN: &[(&str, &str, &str)] = &[
    (
        "shaders/view_present.wgsl",
        "present_vertex",
        "glint view's present pass: one triangle over the window; the CPU tracer has no window",
    ),
    (
        "shaders/view_present.wgsl",
        "present_fragment",
        "glint view's present pass: shows the progressive sums (sum / count, clamped) in the \
         window; the CPU's image of the same sums is tracer::sampling::progressive::film_of_sums, which \
         tests/gpu/view.rs compares with the window",
    ),
    (
        "src/tracer/base/ray.wgsl",
        "max_element",
        "glam's Vec3::max_element on the CPU",
    ),
    (
        "src/tracer/base/ray.wgsl",
        "min_element",
        "glam's Vec3::min_element on the CPU",
    ),
    (
        "src/tracer/base/ray.wgsl",
        "copysign",
        "Rust's f32::copysign on the CPU",
    ),
    (
        "src/tracer/sampling/render.wgsl",
        "block_pixel",
        "chooses which invocation of a workgroup traces which pixel of its square (the \
         order of llvmpipe's SIMD lanes); the CPU's pixels have no lanes, and the pixel's \
         value does not depend on it",
    ),
    (
        "src/pack/layout.wgsl",
        "table_at",
        "reads the texel of a table element (src/gpu/upload/tables.rs): the CPU indexes its slices",
    ),
    (
        "src/pack/layout.wgsl",
        "table_texel",
        "where a table element lies in its texture (src/gpu/upload/tables.rs); the CPU has slices",
    ),
    (
        "src/tracer/sampling/render.wgsl",
        "loop_limiter_tripped",
        "detects lavapipe's loop limiter, which the CPU does not have",
    ),
    (
        "src/tracer/sampling/adaptive.wgsl",
        "indirect_workgroups",
        "workgroup counts of an indirect pass (adaptive_work_args' helper); the CPU has no \
         dispatches",
    ),
    (
        "src/tracer/sampling/adaptive.wgsl",
        "store_indirect_pair",
        "writes two indirect passes' workgroup counts (adaptive_work_args' and \
         wavefront_args' helper); the CPU has no dispatches",
    ),
    (
        "src/tracer/sampling/render.wgsl",
        "linear_index",
        "an invocation's index in a dispatch continued in y past the adapter's per-dimension \
         limit (src/gpu/plan/mod.rs plans it on the host); the CPU has no dispatches",
    ),
    (
        "shaders/bench/torus.wgsl",
        "bench_torus",
        "the torus benchmark's kernel; on the CPU, src/bin/glint/bench/torus.rs loops over the \
         rays calling the same solvers",
    ),
    (
        "src/gpu/compile/lists.wgsl",
        "begin_lane",
        "claims the invocation's slot of the per-ray lists' storage buffer (src/gpu/compile/lists.rs); the CPU's lists are arrays of its own",
    ),
    (
        "src/gpu/compile/lists.wgsl",
        "lane_word",
        "where a word of the invocation's list slot lies in the storage buffer (src/gpu/compile/lists.rs); the CPU indexes its arrays",
    ),
    (
        "src/gpu/compile/lists.wgsl",
        "lane_f32",
        "reads a float of the invocation's list slot; the CPU indexes its arrays",
    ),
    (
        "src/gpu/compile/lists.wgsl",
        "set_lane_f32",
        "writes a float of the invocation's list slot; the CPU indexes its arrays",
    ),
    (
        "src/gpu/compile/lists.wgsl",
        "lane_vec3",
        "reads three floats of the invocation's list slot; the CPU indexes its arrays",
    ),
    (
        "src/gpu/compile/lists.wgsl",
        "set_lane_vec3",
        "writes three floats of the invocation's list slot; the CPU indexes its arrays",
    ),
    (
        "src/tracer/path/trace.wgsl",
        "store_pending",
        "stores a ray stack entry in a private array or the list slot (src/gpu/compile/lists.rs); the CPU writes `stack[size]` \
         (a Rust twin would not be one: trace_ray's loop form stores the camera entry, a step the CPU's form has not)",
    ),
    (
        "src/tracer/path/trace.wgsl",
        "load_pending",
        "reads a ray stack entry from a private array or the list slot (src/gpu/compile/lists.rs); the CPU reads `stack[size]` \
         (the wavefront's push_next_paths and push_tree_children read through it too, and their CPU twins index the stack)",
    ),
    (
        "src/tracer/wavefront/batch.wgsl",
        "load_path",
        "path entry i of a queue as trace_ray's stack holds it, from the generated accessors of its fields (path_origin, …); the CPU's is PathQueue::load_path, a method of one queue (the WGSL names the queue by its parity)",
    ),
    (
        "src/tracer/wavefront/batch.wgsl",
        "store_path",
        "writes path entry i of a queue through the generated write_path; the CPU's is PathQueue::store_path, a method of one queue (the WGSL names the queue by its parity)",
    ),
    (
        "src/tracer/wavefront/wavefront_tree.wgsl",
        "store_leg_args",
        "writes a round's indirect workgroups (the CPU's round loop runs over its Vec)",
    ),
    (
        "src/tracer/wavefront/wavefront_tree.wgsl",
        "next_generation_room",
        "the paths a tree's next generation has room for in the `samples` buffer; the CPU's Vecs grow (a child without room sends its pixel to the CPU: src/gpu/render.rs::scatter)",
    ),
    (
        "src/tracer/wavefront/wavefront_tree.wgsl",
        "sample_without_room",
        "GPU queues only: a child without room hands the sample's pixels to the CPU tracer (the CPU's queues are Vecs that grow)",
    ),
    (
        "src/tracer/wavefront/wavefront_tree.wgsl",
        "tree_points",
        "reads the scene's light points from the `work_counts` word the camera pass wrote (the CPU's Batch::light_points)",
    ),
    (
        "src/tracer/wavefront/wavefront_tree.wgsl",
        "note_tree_points",
        "writes the scene's light points into a `work_counts` word for the later passes (the CPU's camera_pass keeps them in Batch::light_points)",
    ),
    (
        "src/tracer/sampling/adaptive.wgsl",
        "guard_lattice_point",
        "flags the pixels around a lattice point whose sample the GPU could not trace \
         (lavapipe's loop limiter, or a wavefront tree without room for a child) for the \
         CPU tracer to re-render; the CPU traces every sample",
    ),
    (
        "src/tracer/wavefront/wavefront_tree.wgsl",
        "load_leg",
        "reads leg l of a round's queue (the CPU's LegQueue::load_leg)",
    ),
];

/// WGSL functions whose Rust twin, or the Rust code they mirror part of, has another
/// name, and why: no Rust function has the WGSL function's name (or, for a one-to-one
/// pair, its twin is named otherwise).
const WGSL_NAMED_APART: &[(&str, &str, &str)] = &[(
    "src/tracer/wavefront/wavefront_tree.wgsl",
    "tree_generation_args_entry",
    "src/tracer/wavefront/wavefront.rs::wavefront_args with refraction (the CPU's queues need no \
         room cut or vertex base counter)",
)];

/// Types of Rust parameters that a WGSL twin reads from module scope instead (unless the
/// twin takes a parameter of that type too), and where.
const MODULE_SCOPE: &[(&str, &str)] = &[
    (
        "PackedScene",
        "the scene's tables (textures, src/gpu/upload/tables.rs)",
    ),
    ("PackedGlobals", "the `globals` uniform"),
    ("AdaptiveTile", "the `tile` uniform"),
    ("Lattice", "the `samples` and `split` storage buffers"),
    (
        "Batch",
        "the wavefront queues in the `samples` storage buffer and their `work_counts`",
    ),
    ("SampleSource", "the `tile` uniform (a chunk's pixels)"),
    (
        "CsgStack",
        "the csg_* private variables or the list slot (src/gpu/compile/lists.rs)",
    ),
    ("MediumStack", "the `shading_media` private variable"),
    (
        "VertexTree",
        "a tree's vertex tree in the `samples` storage buffer (src/tracer/wavefront/wavefront_tree.wgsl)",
    ),
    (
        "LegQueue",
        "a glass round's leg queues in the `samples` storage buffer and their `work_counts`",
    ),
    ("[u32]", "the `texel_table` texture"),
    (
        "impl TraversalCounters",
        "nothing: `--stats` counters are CPU-only",
    ),
];

/// This repository's sources.
pub(super) fn source_texts() -> Vec<(String, String)> {
    twin_support::source_texts(Path::new(env!("CARGO_MANIFEST_DIR")))
}

/// What the checks found.
#[derive(Default)]
pub(super) struct Findings {
    pub(super) problems: Vec<String>,
    /// One-to-one pairs (each counted once).
    pairs: usize,
    /// Of those, function pairs whose argument counts were compared.
    compared_functions: usize,
    /// Twin comments about part of a declaration, or a file.
    partial: usize,
    /// Function pairs whose calls were compared, and of those, pairs whose calls were
    /// also compared in order.
    compared_calls: usize,
    ordered_calls: usize,
    /// Module configurations naga parsed.
    configurations: usize,
    /// WGSL functions (outside shaders/bench) without a Rust function of their name, and
    /// of those, how many a Rust member `Type::name` stands for (as `type_name`); with
    /// the WGSL functions counted.
    pub(super) named_apart: NameCount,
}

/// How many WGSL functions have no Rust function of their name.
#[derive(Default)]
pub(super) struct NameCount {
    pub(super) functions: usize,
    pub(super) without_same_name: usize,
    pub(super) members: usize,
}

fn is_wgsl(file: &str) -> bool {
    file.ends_with(".wgsl")
}

pub(super) fn check(texts: &[(String, String)]) -> Findings {
    let sources = &parse(texts);
    let wgsl = wgsl_calls::read(texts);
    let (rust, rust_problems) = rust_calls::read(texts);
    let mut found = Findings {
        problems: [wgsl.problems.clone(), rust_problems].concat(),
        configurations: wgsl.configurations,
        ..Findings::default()
    };
    check_wgsl_functions(sources, &wgsl, &mut found.problems);
    found.problems.extend(
        sources
            .malformed
            .iter()
            .map(|m| format!("{m}: names no src/…rs or shaders/…wgsl file")),
    );
    let files: HashSet<&str> = sources.items.iter().map(|i| i.file.as_str()).collect();
    let index: HashMap<(&str, &str), &Item> = sources
        .items
        .iter()
        .map(|i| ((i.file.as_str(), i.key.as_str()), i))
        .collect();
    let refs = sources
        .items
        .iter()
        .filter_map(|i| i.twin.as_ref().map(|t| (i.file.as_str(), t)))
        .chain(sources.loose.iter().map(|(f, t)| (f.as_str(), t)));
    for (file, twin) in refs {
        check_reference(file, twin, &files, &index, &mut found.problems);
        found.partial += usize::from(!twin.exact);
    }
    let wgsl_fns = &wgsl;
    let mut seen = HashSet::new();
    for item in &sources.items {
        let Some(twin) = item.twin.as_ref().filter(|t| t.exact) else {
            continue;
        };
        let Some(other) = index.get(&(twin.path.as_str(), twin.key.as_deref().unwrap())) else {
            continue; // reported by check_reference
        };
        check_symmetry(item, other, &mut found.problems);
        let pair = if is_wgsl(&item.file) {
            (other.line, &other.file, item.line)
        } else {
            (item.line, &item.file, other.line)
        };
        if !seen.insert(pair) {
            continue;
        }
        found.pairs += 1;
        let (rust, wgsl) = if is_wgsl(&item.file) {
            (*other, item)
        } else {
            (item, *other)
        };
        check_file_pairing(rust, wgsl, &files, &mut found.problems);
        let naga_fn = wgsl_fns.functions.get(&wgsl.key);
        if let (true, Some(f)) = (rust.is_fn && wgsl.is_fn, naga_fn) {
            if !f.entry_point {
                found.compared_functions += 1;
                check_arguments(rust, wgsl, f.arity, &mut found.problems);
            }
        }
    }
    check_untwinned(sources, &mut found.problems);
    found.named_apart = check_names(sources, &mut found.problems);
    check_calls(sources, &rust, &wgsl, &mut found);
    found
}

/// A twin of `DIR/X.rs` is in `DIR/X.wgsl` beside it, for every tracer file (under
/// `src/tracer/`) and every other Rust file with a `.wgsl` of its stem beside it (host-side
/// data and helpers without one are mirrored in the shader file that reads them).
fn check_file_pairing(
    rust: &Item,
    wgsl: &Item,
    wgsl_files: &HashSet<&str>,
    problems: &mut Vec<String>,
) {
    let Some(stem) = rust.file.strip_suffix(".rs") else {
        return;
    };
    let expected = format!("{stem}.wgsl");
    let paired = rust.file.starts_with("src/tracer/") || wgsl_files.contains(expected.as_str());
    if paired && wgsl.file != expected {
        problems.push(format!(
            "{}:{} {} has its twin in {}, not in {expected}: twins are paired file by file",
            rust.file, rust.line, rust.key, wgsl.file
        ));
    }
}

/// The named file is on the other side and exists, and so does the named declaration.
fn check_reference(
    file: &str,
    twin: &TwinRef,
    files: &HashSet<&str>,
    index: &HashMap<(&str, &str), &Item>,
    problems: &mut Vec<String>,
) {
    let at = format!("{file}:{}: \"Mirror of {}\"", twin.line, twin.text);
    if is_wgsl(file) == is_wgsl(&twin.path) {
        problems.push(format!("{at}: a twin is on the other side (Rust ↔ WGSL)"));
    } else if !files.contains(twin.path.as_str()) {
        problems.push(format!("{at}: no file {}", twin.path));
    } else if let Some(key) = &twin.key {
        if !index.contains_key(&(twin.path.as_str(), key.as_str())) {
            problems.push(format!("{at}: {} declares no {key}", twin.path));
        }
    }
}

/// `item`'s one-to-one twin `other` names `item` back.
fn check_symmetry(item: &Item, other: &Item, problems: &mut Vec<String>) {
    let names_back = other
        .twin
        .as_ref()
        .is_some_and(|t| t.path == item.file && t.key.as_ref().is_none_or(|k| *k == item.key));
    if !names_back {
        let says = match &other.twin {
            Some(t) => format!("names \"{}\"", t.text),
            None => "has no twin comment".to_string(),
        };
        problems.push(format!(
            "{}:{}: {} names {}::{} as its twin, but {}:{} {says} (expected \"// Mirror of {}::{} — change both.\")",
            item.file, item.line, item.key, other.file, other.key, other.file, other.line, item.file, item.key
        ));
    }
}

/// How many arguments a call of the Rust function passes that its WGSL twin takes as
/// parameters: module state ([`MODULE_SCOPE`], a method's receiver included) set aside,
/// an array `[T; N]` counted as N (WGSL may pass the elements one by one), an
/// `impl Iterator` as 2 (WGSL passes the range's first and last).
fn rust_argument_count(rust: &Item, wgsl: &Item) -> usize {
    let wgsl_types: Vec<&str> = wgsl
        .params
        .iter()
        .filter_map(|p| p.split_once(':').map(|(_, t)| t))
        .collect();
    let receiver = rust.key.split_once("::").map_or("", |(ty, _)| ty);
    rust.params
        .iter()
        .map(|p| {
            // `self`, `&self`, `&mut self` stand for a parameter of the impl's type.
            let ty = p.split_once(':').map_or(receiver, |(_, t)| t);
            let ty = ty.trim().trim_start_matches('&');
            // A reference's lifetime (`&'a T`) is no part of the type's name.
            let ty = match ty.strip_prefix('\'') {
                Some(rest) => rest.split_once(' ').map_or(rest, |(_, t)| t),
                None => ty,
            };
            let ty = ty.trim_start_matches("mut ").trim();
            let base = ty.rsplit("::").next().unwrap_or(ty);
            let module_scope = MODULE_SCOPE.iter().any(|(t, _)| *t == base || *t == ty);
            if module_scope && !wgsl_types.iter().any(|w| w.contains(base)) {
                0
            } else if ty.starts_with("impl Iterator") {
                2
            } else {
                array_length(ty, ';')
            }
        })
        .sum()
}

/// N for an array type `[T<sep> N]` with a literal N, else 1.
fn array_length(ty: &str, separator: char) -> usize {
    ty.strip_prefix('[')
        .and_then(|t| t.strip_suffix(']'))
        .and_then(|t| t.rsplit_once(separator))
        .and_then(|(_, n)| n.trim().parse().ok())
        .unwrap_or(1)
}

/// The Rust function passes as many arguments as naga says its WGSL twin takes (`w`).
fn check_arguments(rust: &Item, wgsl: &Item, w: usize, problems: &mut Vec<String>) {
    let r = rust_argument_count(rust, wgsl);
    if r != w {
        problems.push(format!(
            "{}:{} {} passes {r} arguments but its twin {}:{} {} takes {w}\n  Rust: ({})\n  WGSL: ({})",
            rust.file, rust.line, rust.key, wgsl.file, wgsl.line, wgsl.key,
            rust.params.join(", "), wgsl.params.join(", ")
        ));
    }
}

/// Every WGSL function has a twin comment or an allow-list entry; every entry is needed.
fn check_untwinned(sources: &Sources, problems: &mut Vec<String>) {
    let untwinned: HashSet<(&str, &str)> = sources
        .items
        .iter()
        .filter(|i| is_wgsl(&i.file) && i.is_fn && i.twin.is_none())
        .map(|i| (i.file.as_str(), i.key.as_str()))
        .collect();
    let allowed: HashSet<(&str, &str)> =
        WGSL_WITHOUT_TWIN.iter().map(|(f, n, _)| (*f, *n)).collect();
    let mut missing: Vec<_> = untwinned.difference(&allowed).collect();
    missing.sort();
    for (file, name) in missing {
        problems.push(format!(
            "{file}: fn {name} has no twin comment and is not on WGSL_WITHOUT_TWIN (tests/gpu/twins.rs)"
        ));
    }
    let mut stale: Vec<_> = allowed.difference(&untwinned).collect();
    stale.sort();
    for (file, name) in stale {
        problems.push(format!(
            "WGSL_WITHOUT_TWIN lists {file}::{name}, which is not a WGSL function without a twin"
        ));
    }
}

/// `Type::name` as WGSL spells it: `type_name` (snake case, lower case).
fn member_name(key: &str) -> Option<String> {
    let (ty, member) = key.rsplit_once("::")?;
    let ty = ty.rsplit("::").next().unwrap_or(ty);
    let mut snake = String::new();
    for (i, c) in ty.chars().enumerate() {
        if c.is_uppercase() && i > 0 {
            snake.push('_');
        }
        snake.extend(c.to_lowercase());
    }
    Some(format!("{snake}_{}", member.to_lowercase()))
}

/// Twins have the same name: each WGSL function has a Rust function of its name (or a
/// member it stands for), or a listed reason; a one-to-one pair of function twins is
/// named alike (a member as `type_name`) unless listed; every [`WGSL_NAMED_APART`] entry
/// is needed. Returns the count of WGSL functions without a same-named Rust function.
fn check_names(sources: &Sources, problems: &mut Vec<String>) -> NameCount {
    let rust = sources.items.iter().filter(|i| !is_wgsl(&i.file));
    let plain: HashSet<&str> = rust
        .clone()
        .filter(|i| i.is_fn)
        .map(|i| i.key.rsplit("::").next().unwrap_or(&i.key))
        .collect();
    let members: HashSet<String> = rust.filter_map(|i| member_name(&i.key)).collect();
    let apart: HashSet<(&str, &str)> = WGSL_NAMED_APART.iter().map(|(f, n, _)| (*f, *n)).collect();
    let without: HashSet<(&str, &str)> =
        WGSL_WITHOUT_TWIN.iter().map(|(f, n, _)| (*f, *n)).collect();
    let mut count = NameCount::default();
    let mut needed = HashSet::new();
    let wgsl = sources
        .items
        .iter()
        .filter(|i| is_wgsl(&i.file) && i.is_fn && !i.file.starts_with("shaders/bench/"));
    for item in wgsl {
        let at = (item.file.as_str(), item.key.as_str());
        count.functions += 1;
        let same_name = plain.contains(item.key.as_str());
        let member = members.contains(&item.key);
        count.without_same_name += usize::from(!same_name);
        count.members += usize::from(!same_name && member);
        let twin_named_otherwise = item.twin.as_ref().is_some_and(|t| {
            let key = t.key.as_deref().unwrap_or("");
            t.exact
                && key.rsplit("::").next() != Some(item.key.as_str())
                && member_name(key).as_deref() != Some(item.key.as_str())
        });
        if apart.contains(&at) {
            needed.insert(at);
        } else if twin_named_otherwise {
            problems.push(format!(
                "{}:{} fn {} is named otherwise than its twin {}: name them alike (a member \
                 Type::name as type_name), or list it on WGSL_NAMED_APART (tests/gpu/twins.rs) \
                 with the reason",
                item.file,
                item.line,
                item.key,
                item.twin.as_ref().unwrap().text
            ));
        } else if !(same_name || member || without.contains(&at)) {
            problems.push(format!(
                "{}:{} fn {} has no Rust function of its name (nor a member Type::name that \
                 it stands for): name its twin alike, or list it on WGSL_NAMED_APART or \
                 WGSL_WITHOUT_TWIN (tests/gpu/twins.rs) with the reason",
                item.file, item.line, item.key
            ));
        }
    }
    for (file, name, _) in WGSL_NAMED_APART {
        if !needed.contains(&(*file, *name)) {
            problems.push(format!(
                "WGSL_NAMED_APART lists {file}::{name}, which is not a WGSL function"
            ));
        } else if plain.contains(name) {
            problems.push(format!(
                "WGSL_NAMED_APART lists {file}::{name}, but a Rust function has its name"
            ));
        }
    }
    count
}

/// The functions the line reader found in `shaders/` are the functions naga found in the
/// assembled modules, file for file (so neither reader misses one).
fn check_wgsl_functions(sources: &Sources, wgsl: &WgslModules, problems: &mut Vec<String>) {
    let by_text: BTreeSet<(&str, &str)> = sources
        .items
        .iter()
        .filter(|i| is_wgsl(&i.file) && i.is_fn)
        .map(|i| (i.file.as_str(), i.key.as_str()))
        .collect();
    let by_naga: BTreeSet<(&str, &str)> = wgsl
        .functions
        .iter()
        .map(|(name, f)| (f.file.as_str(), name.as_str()))
        .collect();
    for (file, name) in by_text.difference(&by_naga) {
        problems.push(format!(
            "{file}: fn {name} is in no module naga parsed (is the file in src/gpu/compile/shader.rs's lists?)"
        ));
    }
    let generated = queue_twins::generated_functions();
    for (file, name) in by_naga.difference(&by_text) {
        // The queues' accessors are generated into the prelude (tests/gpu/queue_twins.rs).
        if *file == "the prelude" && generated.contains(*name) {
            continue;
        }
        problems.push(format!(
            "{file}: naga sees fn {name}, which the line reader does not"
        ));
    }
}

/// Each pair of function twins calls corresponding twins (see `twin_support::calls` for
/// what is set aside, and why), and where both call them in an order, the same order.
fn check_calls(
    sources: &Sources,
    rust: &BTreeMap<String, RustFile>,
    wgsl: &WgslModules,
    found: &mut Findings,
) {
    let pairs = function_pairs(&sources.items);
    let twin_of: HashMap<(String, String), String> = pairs.iter().cloned().collect();
    let rust_of: HashMap<&str, &(String, String)> =
        pairs.iter().map(|(r, w)| (w.as_str(), r)).collect();
    let twinned: HashSet<String> = pairs.iter().map(|(_, w)| w.clone()).collect();
    // What a call of a Rust function stands for on the WGSL side.
    let mut stands_for = twin_of.clone();
    stands_for.extend(
        partial_function_twins(&sources.items)
            .into_iter()
            .filter(|(_, w)| twinned.contains(w)),
    );
    let line_of = |file: &str, key: &str| {
        sources
            .items
            .iter()
            .find(|i| i.file == file && i.key == key)
            .map_or(0, |i| i.line)
    };
    let index = RustIndex::new(rust);
    for (r, w) in &pairs {
        let Some(wf) = wgsl.functions.get(w) else {
            continue; // reported by check_wgsl_functions
        };
        let (rust_calls, unresolved) = rust_twin_calls(&index, &stands_for, r);
        let wgsl_calls = wgsl_twin_calls(wgsl, &twinned, w);
        let at_rust = format!("{}:{} {}", r.0, line_of(&r.0, &r.1), r.1);
        let at_wgsl = format!("{}:{} {w}", wf.file, line_of(&wf.file, w));
        for u in unresolved {
            found
                .problems
                .push(format!("{at_rust}: cannot tell which function {u} calls"));
        }
        found.compared_calls += 1;
        let rust_set: BTreeSet<String> = first_calls(&rust_calls, false).into_iter().collect();
        let wgsl_set: BTreeSet<String> = wgsl_calls
            .iter()
            .flat_map(|calls| first_calls(calls, false))
            .collect();
        let name = |w: &str| {
            rust_of
                .get(w)
                .map_or(w.to_string(), |(f, k)| format!("{f}::{k}"))
        };
        for extra in wgsl_set.difference(&rust_set) {
            found.problems.push(format!(
                "{at_wgsl} calls {extra} (twin of {}), but its twin {at_rust} does not",
                name(extra)
            ));
        }
        for extra in rust_set.difference(&wgsl_set) {
            found.problems.push(format!(
                "{at_rust} calls {} (twin of shaders' {extra}), but its twin {at_wgsl} does not",
                name(extra)
            ));
        }
        let rust_fixed = first_calls(&rust_calls, true);
        let wgsl_fixed: Vec<Vec<String>> =
            wgsl_calls.iter().map(|c| first_calls(c, true)).collect();
        if let Some(problem) = order_problem(&rust_fixed, &wgsl_fixed) {
            found
                .problems
                .push(format!("{at_rust} and its twin {at_wgsl}: {problem}"));
        }
        found.ordered_calls += usize::from(
            wgsl_fixed
                .iter()
                .any(|w| w.iter().filter(|c| rust_fixed.contains(c)).count() > 1),
        );
    }
}

/// Where the twins both sides call whenever they run come first in different orders, in
/// some configuration: each side's fixed calls restricted to the other's.
fn order_problem(rust: &[String], wgsl: &[Vec<String>]) -> Option<String> {
    wgsl.iter().find_map(|calls| {
        let w: Vec<&String> = calls.iter().filter(|c| rust.contains(c)).collect();
        let r: Vec<&String> = rust.iter().filter(|c| calls.contains(c)).collect();
        (w != r).then(|| format!("twins called in another order: Rust {r:?}, WGSL {w:?}"))
    })
}

#[test]
fn rust_and_wgsl_twins_name_each_other() {
    let found = check(&source_texts());
    println!(
        "{} one-to-one twin pairs ({} function pairs with argument counts compared, {} with \
         their calls compared, {} of them in order), {} partial twin comments, {} WGSL \
         functions on the allow-list; naga parsed {} module configurations",
        found.pairs,
        found.compared_functions,
        found.compared_calls,
        found.ordered_calls,
        found.partial,
        WGSL_WITHOUT_TWIN.len(),
        found.configurations
    );
    let names = &found.named_apart;
    println!(
        "by name, {} of {} WGSL functions outside shaders/bench have no Rust function of \
         their name ({} of them a Rust member Type::name's, as type_name); {} on \
         WGSL_NAMED_APART",
        names.without_same_name,
        names.functions,
        names.members,
        WGSL_NAMED_APART.len()
    );
    assert!(
        found.problems.is_empty(),
        "{} twin problems:\n{}",
        found.problems.len(),
        found.problems.join("\n")
    );
    // A floor, so a parser that stopped seeing the comments cannot pass vacuously.
    assert!(
        found.pairs >= 100 && found.compared_functions >= 80,
        "too few twins found"
    );
}
