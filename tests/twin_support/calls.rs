//! The twin functions each twin calls, on both sides, for `tests/gpu/twins.rs`'s call
//! check. Only calls to twins count; the rules that set the others aside:
//! - a call to a function with no twin of its own (a Rust helper, a WGSL function on the
//!   test's `WGSL_WITHOUT_TWIN` list, such as the table readers that stand for the
//!   CPU's slice indexing) counts as the twin calls that function makes, transitively:
//!   a helper is a way to write steps, not a step;
//! - a call to something outside `src/` (glam's `Vec3::dot`, `f32::max`, `Some`, WGSL's
//!   builtins, which naga does not see as calls) is no step of either tracer;
//! - a call to a Rust function whose twin comment is about part or a form of a WGSL
//!   function (`triangle4.rs`'s four-lane triangle test: "Mirror of
//!   src/tracer/geometry/intersect.wgsl::intersect_triangle on four triangles, one per lane") counts
//!   as a call of that WGSL function: the CPU-only form of a step is that step;
//! - WGSL calls under `ITERATION_GUARD` (lavapipe's loop-limiter check) are not read
//!   (`wgsl_calls`): the CPU has no loop limiter.
//!
//! A Rust method call `x.f()` is resolved by the receiver's type where the body says it
//! (`self`, a typed parameter or `let`, a `let` of `Type::f(…)`, `Type { … }` or of a
//! function of `src/` that returns a named type); else it is the method `T::f` of `src/`
//! when exactly one type there has a method `f`; a name that several types share is set
//! aside, unless one of them is a twin, which is reported as a call that cannot be
//! resolved. A path call `f()` is resolved through the caller's file: a function of that
//! file, else the one its `use` names (or a glob `use`'s module has), else the only one
//! of that name in `src/` if the file imports the name; `m::f()` is `f` of module `m`;
//! `Type::f()` and `Self::f()` the method of that type.

use super::rust_calls::{Call, Receiver, RustCall, RustFile, RustFunction};
use super::wgsl_calls::WgslModules;
use super::Item;
use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};

/// A Rust function: (file, key).
pub type RustFn = (String, String);

/// The file stem of a module path segment list's module (`super::ray::offset_ray` → `ray`).
fn module_of(path: &[String]) -> Option<&str> {
    (path.len() >= 2).then(|| path[path.len() - 2].as_str())
}

fn stem(file: &str) -> &str {
    let name = file.rsplit('/').next().unwrap_or(file);
    let name = name.strip_suffix(".rs").unwrap_or(name);
    if name == "mod" {
        file.rsplit('/').nth(1).unwrap_or(name)
    } else {
        name
    }
}

/// The Rust side's functions and how calls resolve to them.
pub struct RustIndex<'a> {
    files: &'a BTreeMap<String, RustFile>,
    /// Free functions and methods by name: key → files.
    by_key: HashMap<String, Vec<String>>,
    /// Methods by their own name → (file, key).
    methods: HashMap<String, Vec<RustFn>>,
}

impl<'a> RustIndex<'a> {
    pub fn new(files: &'a BTreeMap<String, RustFile>) -> RustIndex<'a> {
        let mut by_key: HashMap<String, Vec<String>> = HashMap::new();
        let mut methods: HashMap<String, Vec<RustFn>> = HashMap::new();
        for (file, f) in files {
            for function in &f.functions {
                by_key
                    .entry(function.key.clone())
                    .or_default()
                    .push(file.clone());
                if let Some((_, name)) = function.key.split_once("::") {
                    methods
                        .entry(name.to_string())
                        .or_default()
                        .push((file.clone(), function.key.clone()));
                }
            }
        }
        RustIndex {
            files,
            by_key,
            methods,
        }
    }

    fn in_module(&self, key: &str, module: &str) -> Option<RustFn> {
        let files = self.by_key.get(key)?;
        let matching: Vec<&String> = files.iter().filter(|f| stem(f) == module).collect();
        (matching.len() == 1).then(|| (matching[0].clone(), key.to_string()))
    }

    /// The function of `src/` that `call` in `caller` calls, if any; Err for a method
    /// name that several types share.
    fn resolve(&self, caller: &RustFn, call: &Call) -> Result<Option<RustFn>, Vec<RustFn>> {
        let (file, key) = caller;
        match call {
            Call::Method(name, Some(Receiver::Type(ty))) => {
                Ok(self.in_file_or_any(&format!("{ty}::{name}"), file))
            }
            Call::Method(name, Some(Receiver::ReturnOf(path))) => {
                let returned = self
                    .resolve(caller, &Call::Path(path.clone()))?
                    .and_then(|f| self.function(&f).and_then(|g| g.returns.clone()));
                match returned {
                    Some(ty) => self.resolve(
                        caller,
                        &Call::Method(name.clone(), Some(Receiver::Type(ty))),
                    ),
                    None => self.resolve(caller, &Call::Method(name.clone(), None)),
                }
            }
            Call::Method(name, None) => match self.methods.get(name).map(Vec::as_slice) {
                None => Ok(None),
                Some([one]) => Ok(Some(one.clone())),
                Some(several) => Err(several.to_vec()),
            },
            Call::Path(path) => {
                let name = path.last().map(String::as_str).unwrap_or_default();
                if path.len() >= 2 {
                    let qualifier = path[path.len() - 2].as_str();
                    if qualifier == "Self" {
                        let ty = key.split_once("::").map_or("", |(t, _)| t);
                        return Ok(self.in_file_or_any(&format!("{ty}::{name}"), file));
                    }
                    if qualifier.starts_with(|c: char| c.is_uppercase()) {
                        return Ok(self.in_file_or_any(&format!("{qualifier}::{name}"), file));
                    }
                    return Ok(self.in_module(name, qualifier));
                }
                let files = self.by_key.get(name);
                if files.is_some_and(|f| f.contains(file)) {
                    return Ok(Some((file.clone(), name.to_string())));
                }
                let uses = &self.files[file].uses;
                let imported = uses.get(name).and_then(|paths| {
                    paths
                        .iter()
                        .find_map(|p| module_of(p).and_then(|m| self.in_module(name, m)))
                });
                let globs = uses.get("*").map(Vec::as_slice).unwrap_or_default();
                let globbed = || {
                    globs
                        .iter()
                        .find_map(|p| p.last().and_then(|m| self.in_module(name, m)))
                };
                // A name declared once in src/ (re-exported, say) is that function.
                let unique = || match files.map(Vec::as_slice) {
                    Some([one]) if uses.contains_key(name) => Some((one.clone(), name.to_string())),
                    _ => None,
                };
                Ok(imported.or_else(globbed).or_else(unique))
            }
        }
    }

    /// `Type::f` in `file`, else wherever it is declared once.
    fn in_file_or_any(&self, key: &str, file: &str) -> Option<RustFn> {
        let files = self.by_key.get(key)?;
        if files.iter().any(|f| f == file) {
            return Some((file.to_string(), key.to_string()));
        }
        (files.len() == 1).then(|| (files[0].clone(), key.to_string()))
    }

    fn function(&self, f: &RustFn) -> Option<&RustFunction> {
        self.files
            .get(&f.0)
            .and_then(|file| file.functions.iter().find(|g| g.key == f.1))
    }

    fn calls(&self, f: &RustFn) -> &[RustCall] {
        self.function(f).map_or(&[], |g| g.calls.as_slice())
    }
}

/// The twins a Rust function calls (as their WGSL names: `twin_of` maps each twin, and
/// each partial twin, to the WGSL function it stands for), helpers followed through,
/// each with whether it runs whenever the function does; and the calls that may be a
/// twin's but cannot be resolved.
pub fn rust_twin_calls(
    index: &RustIndex,
    twin_of: &HashMap<RustFn, String>,
    f: &RustFn,
) -> (Vec<(String, bool)>, Vec<String>) {
    let mut out = Vec::new();
    let mut unresolved = Vec::new();
    let mut visiting = HashSet::from([f.clone()]);
    rust_walk(
        index,
        twin_of,
        f,
        true,
        &mut visiting,
        &mut out,
        &mut unresolved,
    );
    (out, unresolved)
}

#[allow(clippy::too_many_arguments)]
fn rust_walk(
    index: &RustIndex,
    twin_of: &HashMap<RustFn, String>,
    f: &RustFn,
    fixed: bool,
    visiting: &mut HashSet<RustFn>,
    out: &mut Vec<(String, bool)>,
    unresolved: &mut Vec<String>,
) {
    for RustCall { call, fixed: here } in index.calls(f) {
        let fixed = fixed && *here;
        match index.resolve(f, call) {
            Ok(Some(callee)) => {
                if let Some(wgsl) = twin_of.get(&callee) {
                    out.push((wgsl.clone(), fixed));
                } else if visiting.insert(callee.clone()) {
                    rust_walk(index, twin_of, &callee, fixed, visiting, out, unresolved);
                    visiting.remove(&callee);
                }
            }
            Ok(None) => {}
            Err(several) => {
                if several.iter().any(|c| twin_of.contains_key(c)) {
                    unresolved.push(format!("{call:?} (one of {several:?})"));
                }
            }
        }
    }
}

/// The twins a WGSL function calls in each configuration, untwinned helpers followed
/// through, each with whether it runs whenever the function does.
pub fn wgsl_twin_calls(
    modules: &WgslModules,
    twinned: &HashSet<String>,
    name: &str,
) -> BTreeSet<Vec<(String, bool)>> {
    let Some(f) = modules.functions.get(name) else {
        return BTreeSet::new();
    };
    f.calls
        .iter()
        .map(|calls| {
            let mut out = Vec::new();
            let mut visiting = HashSet::from([name.to_string()]);
            for (callee, fixed) in calls {
                wgsl_walk(modules, twinned, callee, *fixed, &mut visiting, &mut out);
            }
            out
        })
        .collect()
}

fn wgsl_walk(
    modules: &WgslModules,
    twinned: &HashSet<String>,
    callee: &str,
    fixed: bool,
    visiting: &mut HashSet<String>,
    out: &mut Vec<(String, bool)>,
) {
    if twinned.contains(callee) {
        out.push((callee.to_string(), fixed));
        return;
    }
    if !visiting.insert(callee.to_string()) {
        return;
    }
    // A helper's calls in every configuration it was compiled in.
    if let Some(f) = modules.functions.get(callee) {
        let several = f.calls.len() > 1;
        for calls in &f.calls {
            for (inner, here) in calls {
                // (Calls that differ between configurations are not fixed.)
                let fixed = fixed && *here && !several;
                wgsl_walk(modules, twinned, inner, fixed, visiting, out);
            }
        }
    }
    visiting.remove(callee);
}

/// The names of `calls` (where `fixed_only`, of the fixed ones), each once, where it
/// first appears.
pub fn first_calls(calls: &[(String, bool)], fixed_only: bool) -> Vec<String> {
    let mut seen = HashSet::new();
    calls
        .iter()
        .filter(|(_, fixed)| *fixed || !fixed_only)
        .filter(|(c, _)| seen.insert(c.clone()))
        .map(|(c, _)| c.clone())
        .collect()
}

/// Rust functions whose twin comment names a WGSL function but is about part of it, or
/// a form of it ("Mirror of src/tracer/geometry/intersect.wgsl::intersect_triangle on four
/// triangles, one per lane — change both."): a call of one counts as a call of the WGSL
/// function it names (a lane-wise form of a step is that step).
pub fn partial_function_twins(items: &[Item]) -> Vec<(RustFn, String)> {
    let wgsl_fns: HashSet<(&str, &str)> = items
        .iter()
        .filter(|i| i.is_fn && i.file.ends_with(".wgsl"))
        .map(|i| (i.file.as_str(), i.key.as_str()))
        .collect();
    items
        .iter()
        .filter(|i| i.is_fn && i.file.ends_with(".rs"))
        .filter_map(|i| {
            let twin = i.twin.as_ref().filter(|t| !t.exact)?;
            let key = twin.key.as_deref()?;
            wgsl_fns
                .contains(&(twin.path.as_str(), key))
                .then(|| ((i.file.clone(), i.key.clone()), key.to_string()))
        })
        .collect()
}

/// Exact one-to-one function twins: (Rust (file, key), WGSL name).
pub fn function_pairs(items: &[Item]) -> Vec<(RustFn, String)> {
    let index: HashMap<(&str, &str), &Item> = items
        .iter()
        .map(|i| ((i.file.as_str(), i.key.as_str()), i))
        .collect();
    let mut pairs = Vec::new();
    for item in items.iter().filter(|i| i.is_fn && i.file.ends_with(".rs")) {
        let Some(twin) = item.twin.as_ref().filter(|t| t.exact) else {
            continue;
        };
        let Some(other) = index.get(&(twin.path.as_str(), twin.key.as_deref().unwrap_or("")))
        else {
            continue;
        };
        if other.is_fn {
            pairs.push(((item.file.clone(), item.key.clone()), other.key.clone()));
        }
    }
    pairs
}
