//! Reads the WGSL side of the twins through naga: every function of the assembled shader
//! modules (the render module, the probe module and the torus benchmark's), the number
//! of arguments it takes and the functions it calls, in the order its calls run.
//!
//! A module is specialised by the scene's features and the kernel variant (`// #if`
//! blocks), and each specialisation leaves out some calls. So that every call is seen,
//! the modules are assembled in a set of configurations that together keep every line
//! of every shader file (chosen greedily from feature sets × kernel variants), from the
//! texts given (so tests can feed edited copies), and parsed with naga; a function's
//! calls are kept per configuration.

use glint::gpu::compile::shader::{assemble_common_with, assemble_with, preprocess_with, Entry};
use glint::gpu::KernelConfig;
use glint::mailboxes::Mailboxes;
use glint::pack::SceneFeatures;
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::hash::{DefaultHasher, Hash, Hasher};
use std::sync::Mutex;

/// One WGSL function as naga reads it.
#[derive(Clone, Debug, Default)]
pub struct WgslFunction {
    /// The shader file that declares it (its repository path, `src/…/X.wgsl`).
    pub file: String,
    /// A `@compute` entry point (its arguments are builtins, not a call's).
    pub entry_point: bool,
    /// Arguments, an `array<T, N>` counted as N.
    pub arity: usize,
    /// The functions its body calls (naga's `Statement::Call`, through every nested
    /// block), in the order they run, each with whether it runs whenever the function
    /// does (not inside an `if`, `switch` or loop): once per distinct list over the
    /// configurations without `ITERATION_GUARD` (lavapipe's loop-limiter check, which
    /// the CPU has no twin of).
    pub calls: BTreeSet<Vec<(String, bool)>>,
}

/// Everything read from the modules.
#[derive(Clone, Default)]
pub struct WgslModules {
    /// By function name (WGSL has one namespace per module; the modules share theirs).
    pub functions: BTreeMap<String, WgslFunction>,
    /// Configurations parsed, over all modules.
    pub configurations: usize,
    /// Modules that did not parse, or lines no configuration keeps.
    pub problems: Vec<String>,
}

/// The modules the GPU tracer builds.
#[derive(Clone, Copy)]
enum ModuleKind {
    Render,
    Probe,
    Bench,
    /// `glint view`'s present pass: one file, no prelude, no specialisation
    /// (src/bin/glint/view/present.rs builds it as it is).
    Present,
}

/// The benchmark kernel, as `assemble_common_with` names it (its path under `shaders/`).
const BENCH_NAME: &str = "bench/torus.wgsl";
const BENCH_FILE: &str = "shaders/bench/torus.wgsl";
const PRESENT_FILE: &str = "shaders/view_present.wgsl";

/// Every scene feature.
fn all_features() -> SceneFeatures {
    SceneFeatures(SceneFeatures::ALL.iter().fold(0, |acc, (f, _)| acc | f.0))
}

/// The candidate configurations: feature sets (none, all, each alone, all but each) ×
/// the kernel variant's flags that select calls: the mailboxes, the tables' binding and
/// `CAMERA_RAY_IN_LOOP` with `ANY_HIT_ONE_LOOP` (trace_ray's and occlusion_walk's two
/// forms, each compared with the one CPU form), and `WAVEFRONT` (the wavefront kernels'
/// files, or the megakernel `main`, which only modules without them have).
/// Not `ITERATION_GUARD` (see [`WgslFunction::calls`]) nor `LISTS_IN_STORAGE`, whose
/// branches call no twin.
fn candidates() -> Vec<(SceneFeatures, KernelConfig)> {
    let flags: Vec<SceneFeatures> = SceneFeatures::ALL.iter().map(|(f, _)| *f).collect();
    let all = all_features();
    let mut sets = vec![SceneFeatures::empty(), all];
    for f in &flags {
        sets.push(*f);
        sets.push(SceneFeatures(all.0 & !f.0));
    }
    let mut out = Vec::new();
    for features in sets {
        for mailboxes in Mailboxes::ALL {
            for storage_tables in [false, true] {
                for camera_ray_in_loop in [true, false] {
                    for wavefront in [true, false] {
                        let kernel = KernelConfig {
                            mailboxes,
                            storage_tables,
                            camera_ray_in_loop,
                            // Tied to the other loop form (each form of each function
                            // against the one CPU form): the two are the hardware variant's.
                            any_hit_one_loop: camera_ray_in_loop,
                            wavefront,
                            ..KernelConfig::default()
                        };
                        out.push((features, kernel));
                    }
                }
            }
        }
    }
    out
}

/// The real module of `kind` in one configuration: its prelude (everything before the
/// first file) and its files' names, in order.
fn layout(
    kind: ModuleKind,
    features: SceneFeatures,
    kernel: KernelConfig,
) -> (String, Vec<String>) {
    let source = match kind {
        ModuleKind::Render => assemble_with(features, Entry::Render, kernel),
        ModuleKind::Probe => assemble_with(features, Entry::Probe, kernel),
        ModuleKind::Bench => assemble_common_with(features, (BENCH_NAME, "")),
        ModuleKind::Present => return (String::new(), vec![PRESENT_FILE.to_string()]),
    };
    let mut parts = source.split("\n// ---- ");
    let prelude = parts.next().unwrap_or_default().to_string();
    let files = parts
        .filter_map(|p| p.split_once(" ----").map(|(name, _)| name.to_string()))
        .collect();
    (prelude, files)
}

/// A file's text as the module includes it (the benchmark kernel behind its own prelude).
fn module_text(name: &str, texts: &HashMap<&str, &str>) -> Option<String> {
    let text = texts.get(name)?;
    Some(if name == BENCH_FILE {
        glint::bench::torus_gpu::bench_prelude() + text
    } else {
        text.to_string()
    })
}

/// Each file's text with every code line tagged with its number (` //@12`), so that the
/// lines a configuration keeps can be read back from the preprocessed text.
fn tagged_texts(texts: &HashMap<&str, &str>) -> HashMap<String, String> {
    texts
        .iter()
        .filter(|(f, _)| f.ends_with(".wgsl"))
        .map(|(file, text)| {
            let mut tagged = String::with_capacity(text.len() * 2);
            for (i, line) in text.lines().enumerate() {
                tagged += line;
                if !(line.trim().starts_with("// #") || line.trim().is_empty()) {
                    tagged += &format!(" //@{}", i + 1);
                }
                tagged.push('\n');
            }
            (file.to_string(), tagged)
        })
        .collect()
}

/// Which lines (file, 1-based line) of `files` a configuration keeps.
fn kept_lines(
    files: &[String],
    tagged: &HashMap<String, String>,
    features: SceneFeatures,
    kernel: KernelConfig,
) -> BTreeSet<(String, usize)> {
    let mut kept = BTreeSet::new();
    for name in files {
        let Some(text) = tagged.get(name) else {
            continue;
        };
        let Ok(out) = preprocess_with(name, text, features, kernel) else {
            continue; // reported when the configuration is assembled
        };
        for line in out.lines() {
            if let Some(n) = line
                .rfind(" //@")
                .and_then(|at| line[at + 4..].parse().ok())
            {
                kept.insert((name.clone(), n));
            }
        }
    }
    kept
}

/// The shape of the files' `#if` blocks: each directive, and each run of other lines as
/// one mark. Configurations that keep every line of one set of files keep every line of
/// any with the same shape, so the tests that edit a line inside a block reuse them.
fn block_shape(texts: &HashMap<&str, &str>) -> Vec<String> {
    let mut shape = Vec::new();
    let mut files: Vec<_> = texts.iter().filter(|(f, _)| f.ends_with(".wgsl")).collect();
    files.sort();
    for (file, text) in files {
        shape.push(file.to_string());
        for line in text.lines() {
            let line = line.trim();
            if line.starts_with("// #") {
                shape.push(line.to_string());
            } else if !line.is_empty() && shape.last().is_none_or(|s| s != "…") {
                shape.push("…".to_string());
            }
        }
    }
    shape
}

/// Configurations that together keep every line that any candidate keeps: greedily,
/// the one that adds most first.
fn covering(kind: ModuleKind, texts: &HashMap<&str, &str>) -> Vec<(SceneFeatures, KernelConfig)> {
    type Cover = Vec<(SceneFeatures, KernelConfig)>;
    static COVERS: Mutex<BTreeMap<(u8, Vec<String>), Cover>> = Mutex::new(BTreeMap::new());
    let key = (kind as u8, block_shape(texts));
    if let Some(cover) = COVERS.lock().unwrap().get(&key) {
        return cover.clone();
    }
    let tagged = tagged_texts(texts);
    let all = candidates();
    // (A module's files are the same in every configuration of one `wavefront`, which
    // appends the wavefront kernels' files. The probe module shares the render module's
    // common files, whose lines the render module's cover keeps.)
    let files_of = |kind, wavefront| {
        let kernel = KernelConfig {
            wavefront,
            ..KernelConfig::default()
        };
        layout(kind, SceneFeatures::empty(), kernel).1
    };
    let files: [Vec<String>; 2] = [false, true].map(|wavefront| {
        let mut files = files_of(kind, wavefront);
        if let ModuleKind::Probe = kind {
            let render = files_of(ModuleKind::Render, wavefront);
            files.retain(|f| !render.contains(f));
        }
        files
    });
    let kept: Vec<BTreeSet<(String, usize)>> = all
        .iter()
        .map(|&(features, kernel)| {
            let files = &files[kernel.wavefront as usize];
            kept_lines(files, &tagged, features, kernel)
        })
        .collect();
    let mut covered: BTreeSet<(String, usize)> = BTreeSet::new();
    let mut chosen = Vec::new();
    loop {
        let best = (0..all.len())
            .map(|i| (kept[i].difference(&covered).count(), i))
            .max_by_key(|&(n, i)| (n, std::cmp::Reverse(i)));
        match best {
            Some((n, i)) if n > 0 => {
                covered.extend(kept[i].iter().cloned());
                chosen.push(all[i]);
            }
            _ => break,
        }
    }
    COVERS.lock().unwrap().insert(key, chosen.clone());
    chosen
}

/// The module of `kind` in one configuration, assembled from `texts`.
fn assemble(
    kind: ModuleKind,
    texts: &HashMap<&str, &str>,
    features: SceneFeatures,
    kernel: KernelConfig,
) -> Result<(String, Vec<(usize, String)>), String> {
    let (mut source, files) = layout(kind, features, kernel);
    let mut starts = Vec::new();
    for name in files {
        let text = module_text(&name, texts).ok_or(format!("no file {name}"))?;
        source += &format!("\n// ---- {name} ----\n");
        starts.push((source.len(), name.clone()));
        source += &preprocess_with(&name, &text, features, kernel)?;
    }
    Ok((source, starts))
}

/// Arguments of `f`, an array of constant size N counted as N.
fn arity(module: &naga::Module, f: &naga::Function) -> usize {
    f.arguments
        .iter()
        .map(|a| match module.types[a.ty].inner {
            naga::TypeInner::Array {
                size: naga::ArraySize::Constant(n),
                ..
            } => n.get() as usize,
            _ => 1,
        })
        .sum()
}

/// The calls of `block` and the blocks nested in it, in the order they run; `fixed`:
/// whether `block` runs whenever its function does.
fn calls_in(
    block: &naga::Block,
    module: &naga::Module,
    fixed: bool,
    out: &mut Vec<(String, bool)>,
) {
    for statement in block.iter() {
        match statement {
            naga::Statement::Block(inner) => calls_in(inner, module, fixed, out),
            naga::Statement::If { accept, reject, .. } => {
                calls_in(accept, module, false, out);
                calls_in(reject, module, false, out);
            }
            naga::Statement::Switch { cases, .. } => {
                for case in cases {
                    calls_in(&case.body, module, false, out);
                }
            }
            naga::Statement::Loop {
                body, continuing, ..
            } => {
                calls_in(body, module, false, out);
                calls_in(continuing, module, false, out);
            }
            naga::Statement::Call { function, .. } => {
                let name = module.functions[*function].name.clone().unwrap_or_default();
                out.push((name, fixed));
            }
            _ => {}
        }
    }
}

/// The file whose part of `source` holds byte `offset` (`starts` from [`assemble`]).
fn file_at(starts: &[(usize, String)], offset: usize) -> String {
    starts
        .iter()
        .rev()
        .find(|(start, _)| *start <= offset)
        .map_or_else(|| "the prelude".to_string(), |(_, f)| f.clone())
}

/// Adds one parsed configuration's functions to `out`, and their calls where
/// `with_calls`.
fn read_module(
    module: &naga::Module,
    source: &str,
    starts: &[(usize, String)],
    with_calls: bool,
    out: &mut WgslModules,
) {
    let mut add = |name: &str, file: String, f: &naga::Function, entry_point: bool| {
        let entry = out.functions.entry(name.to_string()).or_default();
        entry.file = file;
        entry.entry_point = entry_point;
        entry.arity = arity(module, f);
        if with_calls {
            let mut calls = Vec::new();
            calls_in(&f.body, module, true, &mut calls);
            entry.calls.insert(calls);
        }
    };
    for (handle, f) in module.functions.iter() {
        let offset = module
            .functions
            .get_span(handle)
            .to_range()
            .map_or(0, |r| r.start);
        add(
            f.name.as_deref().unwrap_or_default(),
            file_at(starts, offset),
            f,
            false,
        );
    }
    for ep in &module.entry_points {
        // An entry point's function has no span of its own: find its declaration.
        let offset = source.find(&format!("fn {}(", ep.name)).unwrap_or_default();
        add(&ep.name, file_at(starts, offset), &ep.function, true);
    }
}

/// Reads the WGSL functions of `texts` (repository path, text) through naga; the tests
/// that edit the Rust side reuse the reading of the same WGSL texts (a reading takes
/// seconds in a debug build).
pub fn read(texts: &[(String, String)]) -> WgslModules {
    static READ: Mutex<BTreeMap<u64, WgslModules>> = Mutex::new(BTreeMap::new());
    let mut hasher = DefaultHasher::new();
    texts
        .iter()
        .filter(|(f, _)| f.ends_with(".wgsl"))
        .for_each(|text| text.hash(&mut hasher));
    let key = hasher.finish();
    if let Some(found) = READ.lock().unwrap().get(&key) {
        return found.clone();
    }
    let read = read_modules(texts);
    READ.lock().unwrap().insert(key, read.clone());
    read
}

fn read_modules(texts: &[(String, String)]) -> WgslModules {
    let texts: HashMap<&str, &str> = texts
        .iter()
        .map(|(f, t)| (f.as_str(), t.as_str()))
        .collect();
    let mut out = WgslModules::default();
    let kinds = [
        ModuleKind::Render,
        ModuleKind::Probe,
        ModuleKind::Bench,
        ModuleKind::Present,
    ];
    for kind in kinds {
        let mut configurations = match kind {
            // The benchmark's kernel is built for tori alone, in the default variant.
            ModuleKind::Bench => vec![(SceneFeatures::TORUS, KernelConfig::default())],
            ModuleKind::Present => vec![(SceneFeatures::empty(), KernelConfig::default())],
            _ => covering(kind, &texts),
        };
        if let ModuleKind::Render = kind {
            // The loop-limiter check's functions are listed too (their calls are not).
            let guarded = KernelConfig {
                iteration_guard: true,
                wavefront: false,
                ..KernelConfig::default()
            };
            configurations.push((all_features(), guarded));
        }
        for (features, kernel) in configurations {
            out.configurations += 1;
            let parsed = assemble(kind, &texts, features, kernel).and_then(|(source, starts)| {
                naga::front::wgsl::parse_str(&source)
                    .map(|module| (module, source.clone(), starts))
                    .map_err(|e| e.emit_to_string(&source))
            });
            match parsed {
                Ok((module, source, starts)) => {
                    let with_calls = !kernel.iteration_guard;
                    read_module(&module, &source, &starts, with_calls, &mut out)
                }
                Err(e) => out.problems.push(format!(
                    "[{features}; {kernel}] the module does not parse: {e}"
                )),
            }
        }
    }
    out
}
