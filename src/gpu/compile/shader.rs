//! Specialised WGSL: the module source is the constants prelude plus the tracer's `.wgsl`
//! files (each beside its Rust twin), with every `// #if FEATURE` … `// #else` … `// #endif` block resolved for
//! exactly the scene's [`SceneFeatures`], so code for absent features never reaches naga
//! (naga does not remove dead branches, gfx-rs/wgpu#5608). A condition is one feature name
//! in upper case (`-` as `_`: `AREA_LIGHT`), or several joined by `|` (any of them),
//! optionally negated by a leading `!`.
//! Besides the scene's features, the adapter's [`KernelConfig`]: the workgroup size (the
//! `WORKGROUP_SIZE` and `LINEAR_WORKGROUP_SIZE` constants, emitted after the prelude with
//! the per-ray lists' layout, `src/gpu/compile/lists.rs`) and
//! its flags: `ITERATION_GUARD` (software adapters, whose loop limiter the render kernels
//! check, see `src/tracer/sampling/render.wgsl`), `MAILBOXES` or `LAST_ITEM_MAILBOX` (the
//! traversal's per-ray mailboxes, all of them or one item slot: see
//! `src/tracer/traversal/traverse.wgsl`), `STORAGE_TABLES` (the scene's tables bound as read-only
//! storage textures: see `src/pack/layout.wgsl`), `LISTS_IN_STORAGE` (per-ray lists in
//! a storage buffer: see `src/gpu/compile/lists.wgsl`) and `CAMERA_RAY_IN_LOOP` (`trace_ray`'s
//! camera ray is the first entry of its loop over rays: see `src/tracer/path/trace.wgsl`), the one
//! flag that also depends on the features, since which form traces the camera ray once
//! depends on whether the scene has secondary rays at all.

use crate::constants::{
    depth_of_field_wgsl_prelude, wavefront_tree_wgsl_prelude, wavefront_wgsl_prelude, wgsl_prelude,
};
use crate::gpu::compile::kernel::KernelConfig;
use crate::gpu::compile::lists::LaneLists;
use crate::mailboxes::Mailboxes;
use crate::pack::SceneFeatures;
use crate::tracer::wavefront::queues::counters::counters_wgsl;
use crate::tracer::wavefront::queues::layout::Form;
use crate::tracer::wavefront::queues::wgsl::queue_wgsl;
use crate::tracer::wavefront::queues::{COUNTERS, REGIONS};

/// Which compute entry point a pipeline is for. Every entry but `Probe` is in the render
/// module (one source, one bind group layout).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Entry {
    /// `main`: AA none, one tile into the output buffer (the megakernel: not in modules
    /// with [`wavefront_kernels`], which trace AA none through them, glass too).
    Render,
    /// `uniform_samples`, `uniform_resolve`: uniform AA's two passes (not in modules with
    /// [`wavefront_kernels`], which trace uniform AA through them).
    UniformSamples,
    UniformResolve,
    /// `adaptive_corners`, `adaptive_decide`, `adaptive_midpoints`, `adaptive_integrate`,
    /// `adaptive_work_args`: adaptive AA's passes (`src/tracer/sampling/adaptive.wgsl`).
    AdaptiveCorners,
    AdaptiveDecide,
    AdaptiveMidpoints,
    AdaptiveIntegrate,
    AdaptiveWorkArgs,
    /// `wavefront_camera`, `wavefront_closest`, `wavefront_shade`, `wavefront_args`,
    /// `wavefront_shadow`, `wavefront_gather`, `wavefront_resolve`: AA none's and uniform
    /// AA's kernels in the wavefront form (`src/tracer/wavefront/wavefront.wgsl`; only in modules with
    /// [`wavefront_kernels`]).
    WavefrontCamera,
    WavefrontClosest,
    WavefrontShade,
    WavefrontArgs,
    WavefrontShadow,
    WavefrontGather,
    WavefrontResolve,
    /// `wavefront_lattice_camera`, `wavefront_lattice_store`: adaptive AA's corner and
    /// midpoint passes through the wavefront kernels, their camera pass and the pass that
    /// stores their samples into the lattice (`src/tracer/wavefront/wavefront_lattice.wgsl`; only in
    /// modules with [`wavefront_kernels`], which have no `AdaptiveCorners` nor
    /// `AdaptiveMidpoints`).
    WavefrontLatticeCamera,
    WavefrontLatticeStore,
    /// `wavefront_view_store`: `glint view`'s frame through the wavefront kernels, each
    /// sample added to its pixel's sum (`src/tracer/sampling/progressive.wgsl`; only in modules with
    /// [`wavefront_kernels`]).
    WavefrontViewStore,
    /// `wavefront_leg_closest`, `wavefront_crossing`, `wavefront_leg_args`,
    /// `wavefront_fold`: the glass shadow rounds and the fold of scenes with refraction
    /// (`src/tracer/wavefront/wavefront_tree.wgsl`; only in modules with [`wavefront_kernels`] and
    /// REFRACTION).
    WavefrontLegClosest,
    WavefrontCrossing,
    WavefrontLegArgs,
    WavefrontFold,
    /// `view_sample`: `glint view`'s progressive refinement, one sample a pixel
    /// (`src/tracer/sampling/progressive.wgsl`, dispatched by `gpu/view/progressive.rs`; not in modules
    /// with [`wavefront_kernels`]).
    ViewSample,
    /// `probe`: test-only, traces rays from a buffer and reports hits.
    Probe,
}

impl Entry {
    /// The wavefront kernels: the camera pass, a generation's five in the order it
    /// dispatches them, then uniform AA's resolve (AA none has no resolve): the plan's
    /// `Mode::Wavefront` pipelines.
    pub const WAVEFRONT: [Entry; 7] = banded(Entry::CHAIN_GENERATION, Entry::WavefrontResolve);

    /// `glint view`'s frame through the wavefront kernels: the camera pass, a
    /// generation's five, then the store into the sums (`gpu/view/progressive.rs`'s pipelines).
    pub const WAVEFRONT_VIEW: [Entry; 7] =
        banded(Entry::CHAIN_GENERATION, Entry::WavefrontViewStore);

    /// `glint view`'s frame through the wavefront kernels in scenes with refraction: the
    /// camera pass, a tree's generation's passes and its fold ([`Entry::WAVEFRONT_TREE`]'s
    /// before its resolve), then the store into the sums.
    pub const WAVEFRONT_VIEW_TREE: [Entry; 11] =
        banded(Entry::TREE_GENERATION, Entry::WavefrontViewStore);

    /// The megakernel entries the wavefront kernels replace: not in modules with
    /// [`wavefront_kernels`].
    pub const REPLACED_BY_WAVEFRONT: [Entry; 6] = [
        Entry::Render,
        Entry::UniformSamples,
        Entry::UniformResolve,
        Entry::AdaptiveCorners,
        Entry::AdaptiveMidpoints,
        Entry::ViewSample,
    ];

    /// Adaptive AA's passes through the wavefront kernels, in the plan's order of the
    /// `Mode::AdaptiveWavefront` pipelines: adaptive AA's small kernels, the lattice
    /// passes' camera pass, the generations' passes ([`Entry::WAVEFRONT`]'s after its
    /// camera pass) and the store pass.
    pub const ADAPTIVE_WAVEFRONT: [Entry; 10] = lattice(Entry::CHAIN_GENERATION);

    /// The wavefront kernels in scenes with refraction (paths that branch), in the order
    /// a generation dispatches them after the camera pass (the shadow pass starting each
    /// request's first leg, then rounds of leg closest, crossing and leg args), then the
    /// fold after the last generation, then uniform AA's resolve (AA none has none): the
    /// plan's `Mode::Wavefront` pipelines for a tree.
    pub const WAVEFRONT_TREE: [Entry; 11] = banded(Entry::TREE_GENERATION, Entry::WavefrontResolve);

    /// Adaptive AA's passes through the wavefront kernels in scenes with refraction, in
    /// the plan's order of the `Mode::AdaptiveWavefront` pipelines for a tree: adaptive
    /// AA's small kernels, the lattice camera pass, a tree's generation's passes and its
    /// fold ([`Entry::WAVEFRONT_TREE`]'s between its camera pass and its resolve), the
    /// store pass.
    pub const ADAPTIVE_WAVEFRONT_TREE: [Entry; 14] = lattice(Entry::TREE_GENERATION);

    /// A chain's generation, in the order it dispatches its passes: what every chain
    /// mode runs between its camera pass and its own last pass (uniform AA's resolve, the
    /// view's store, the lattice's store).
    const CHAIN_GENERATION: [Entry; 5] = [
        Entry::WavefrontClosest,
        Entry::WavefrontShade,
        Entry::WavefrontArgs,
        Entry::WavefrontShadow,
        Entry::WavefrontGather,
    ];

    /// A tree's generation's passes and its fold, in the order they are dispatched: what
    /// every tree mode runs between its camera pass and its own last pass.
    const TREE_GENERATION: [Entry; 9] = [
        Entry::WavefrontClosest,
        Entry::WavefrontShade,
        Entry::WavefrontArgs,
        Entry::WavefrontShadow,
        Entry::WavefrontLegClosest,
        Entry::WavefrontCrossing,
        Entry::WavefrontLegArgs,
        Entry::WavefrontGather,
        Entry::WavefrontFold,
    ];

    /// Adaptive AA's small kernels, which start both adaptive wavefront modes' lists.
    const ADAPTIVE_STEPS: [Entry; 3] = [
        Entry::AdaptiveDecide,
        Entry::AdaptiveWorkArgs,
        Entry::AdaptiveIntegrate,
    ];

    /// Every entry point.
    pub const ALL: [Entry; 24] = [
        Entry::Render,
        Entry::UniformSamples,
        Entry::UniformResolve,
        Entry::AdaptiveCorners,
        Entry::AdaptiveDecide,
        Entry::AdaptiveMidpoints,
        Entry::AdaptiveIntegrate,
        Entry::AdaptiveWorkArgs,
        Entry::WavefrontCamera,
        Entry::WavefrontClosest,
        Entry::WavefrontShade,
        Entry::WavefrontArgs,
        Entry::WavefrontShadow,
        Entry::WavefrontGather,
        Entry::WavefrontLatticeCamera,
        Entry::WavefrontLatticeStore,
        Entry::WavefrontResolve,
        Entry::WavefrontViewStore,
        Entry::WavefrontLegClosest,
        Entry::WavefrontCrossing,
        Entry::WavefrontLegArgs,
        Entry::WavefrontFold,
        Entry::ViewSample,
        Entry::Probe,
    ];

    /// The WGSL function name of the entry point.
    pub fn name(self) -> &'static str {
        match self {
            Entry::Render => "main",
            Entry::UniformSamples => "uniform_samples",
            Entry::UniformResolve => "uniform_resolve",
            Entry::AdaptiveCorners => "adaptive_corners",
            Entry::AdaptiveDecide => "adaptive_decide",
            Entry::AdaptiveMidpoints => "adaptive_midpoints",
            Entry::AdaptiveIntegrate => "adaptive_integrate",
            Entry::AdaptiveWorkArgs => "adaptive_work_args",
            Entry::WavefrontCamera => "wavefront_camera",
            Entry::WavefrontClosest => "wavefront_closest",
            Entry::WavefrontShade => "wavefront_shade",
            Entry::WavefrontArgs => "wavefront_args",
            Entry::WavefrontShadow => "wavefront_shadow",
            Entry::WavefrontGather => "wavefront_gather",
            Entry::WavefrontLatticeCamera => "wavefront_lattice_camera",
            Entry::WavefrontLatticeStore => "wavefront_lattice_store",
            Entry::WavefrontResolve => "wavefront_resolve",
            Entry::WavefrontViewStore => "wavefront_view_store",
            Entry::WavefrontLegClosest => "wavefront_leg_closest",
            Entry::WavefrontCrossing => "wavefront_crossing",
            Entry::WavefrontLegArgs => "wavefront_leg_args",
            Entry::WavefrontFold => "wavefront_fold",
            Entry::ViewSample => "view_sample",
            Entry::Probe => "probe",
        }
    }

    /// Whether the entry is in the render module.
    pub fn is_render(self) -> bool {
        self != Entry::Probe
    }

    /// Whether the entry is one of the wavefront kernels (in the render module only with
    /// [`wavefront_kernels`]).
    pub fn is_wavefront(self) -> bool {
        Entry::WAVEFRONT.contains(&self)
            || Entry::WAVEFRONT_VIEW.contains(&self)
            || Entry::ADAPTIVE_WAVEFRONT[3..].contains(&self)
            || self.is_wavefront_tree()
    }

    /// Whether the entry is one of the kernels only trees have (in the render module only
    /// with [`wavefront_kernels`] and REFRACTION).
    pub fn is_wavefront_tree(self) -> bool {
        matches!(
            self,
            Entry::WavefrontLegClosest
                | Entry::WavefrontCrossing
                | Entry::WavefrontLegArgs
                | Entry::WavefrontFold
        )
    }

    /// Whether the render module of `kernel` for `features` has this entry: the
    /// wavefront kernels only with [`wavefront_kernels`] (a tree's only with
    /// refraction), the megakernel entries they replace (`main` among them) only without
    /// them.
    pub fn exists_in(self, kernel: KernelConfig, features: SceneFeatures) -> bool {
        let wavefront = wavefront_kernels(kernel, features);
        let replaced = Entry::REPLACED_BY_WAVEFRONT.contains(&self);
        if self.is_wavefront_tree() {
            wavefront && features.contains(SceneFeatures::REFRACTION)
        } else if self.is_wavefront() {
            wavefront
        } else {
            !(wavefront && replaced)
        }
    }
}

/// A band's pipelines through the wavefront kernels: the camera pass, the `generation`'s
/// passes, then the mode's own `last` (uniform AA's resolve, the view's store).
const fn banded<const N: usize, const M: usize>(generation: [Entry; N], last: Entry) -> [Entry; M] {
    joined(&[&[Entry::WavefrontCamera], &generation, &[last]])
}

/// Adaptive AA's pipelines through the wavefront kernels: adaptive AA's small kernels,
/// the lattice camera pass, the `generation`'s passes, the lattice store pass.
const fn lattice<const N: usize, const M: usize>(generation: [Entry; N]) -> [Entry; M] {
    joined(&[
        &Entry::ADAPTIVE_STEPS,
        &[Entry::WavefrontLatticeCamera],
        &generation,
        &[Entry::WavefrontLatticeStore],
    ])
}

/// `parts` one after another, as one array (a mode's pipeline list, built from the
/// passes it shares with other modes and its own); `M` must be their total length.
const fn joined<const M: usize>(parts: &[&[Entry]]) -> [Entry; M] {
    let mut out = [Entry::Probe; M];
    let mut at = 0;
    let mut p = 0;
    while p < parts.len() {
        let mut i = 0;
        while i < parts[p].len() {
            out[at] = parts[p][i];
            at += 1;
            i += 1;
        }
        p += 1;
    }
    assert!(at == M);
    out
}

/// A shader file as (repository path, text), from its path under `src/`.
macro_rules! wgsl {
    ($path:literal) => {
        (
            concat!("src/", $path),
            include_str!(concat!("../../", $path)),
        )
    };
}

/// The shader files, in module order (WGSL does not care about order; readers do).
const COMMON: &[(&str, &str)] = &[
    wgsl!("pack/layout.wgsl"),
    wgsl!("gpu/compile/lists.wgsl"),
    wgsl!("tracer/base/rng.wgsl"),
    wgsl!("tracer/base/ray.wgsl"),
    wgsl!("tracer/base/math.wgsl"),
    wgsl!("tracer/geometry/intersect.wgsl"),
    wgsl!("tracer/geometry/cylinder_cone.wgsl"),
    wgsl!("tracer/geometry/torus.wgsl"),
    wgsl!("tracer/geometry/uv.wgsl"),
    wgsl!("tracer/geometry/csg.wgsl"),
    wgsl!("tracer/traversal/hit.wgsl"),
    wgsl!("tracer/traversal/dda.wgsl"),
    wgsl!("tracer/traversal/traverse_mesh.wgsl"),
    wgsl!("tracer/traversal/traverse.wgsl"),
    wgsl!("tracer/shading/surface.wgsl"),
    wgsl!("tracer/shading/shade.wgsl"),
    wgsl!("tracer/shading/smooth.wgsl"),
    wgsl!("tracer/shading/dielectric.wgsl"),
    wgsl!("tracer/shading/texture.wgsl"),
    wgsl!("tracer/shading/procedural.wgsl"),
    wgsl!("tracer/shading/environment.wgsl"),
];
const RENDER: &[(&str, &str)] = &[
    wgsl!("tracer/path/trace.wgsl"),
    wgsl!("tracer/sampling/sample_source.wgsl"),
    wgsl!("tracer/sampling/pixel_sample.wgsl"),
    wgsl!("tracer/sampling/render.wgsl"),
    wgsl!("tracer/sampling/adaptive.wgsl"),
    wgsl!("tracer/sampling/progressive.wgsl"),
];
/// Appended to the render module only where the kernel runs the wavefront kernels (so
/// that the other modules are byte for byte what they were without them).
const WAVEFRONT: &[(&str, &str)] = &[
    wgsl!("tracer/wavefront/batch.wgsl"),
    wgsl!("tracer/wavefront/wavefront.wgsl"),
    wgsl!("tracer/wavefront/wavefront_shade.wgsl"),
    wgsl!("tracer/wavefront/wavefront_shadow.wgsl"),
    wgsl!("tracer/wavefront/wavefront_gather.wgsl"),
    wgsl!("tracer/wavefront/wavefront_lattice.wgsl"),
];
/// Appended after `WAVEFRONT` where the scene has refraction (paths that branch).
const WAVEFRONT_TREE: &[(&str, &str)] = &[wgsl!("tracer/wavefront/wavefront_tree.wgsl")];
const PROBE: &[(&str, &str)] = &[wgsl!("testing/probe.wgsl")];

/// The common modules (scene layout, intersection, traversal, shading) specialised to
/// `features`, with `extra` (its path under `shaders/`, text) appended: for kernels
/// outside the tracer, such as the torus benchmark's.
pub fn assemble_common_with(features: SceneFeatures, extra: (&str, &str)) -> String {
    let kernel = KernelConfig::default();
    let mut out = wgsl_prelude() + &kernel_prelude(kernel) + &feature_prelude(features);
    let extra_path = format!("shaders/{}", extra.0);
    for (path, text) in COMMON.iter().chain([&(extra_path.as_str(), extra.1)]) {
        out += &format!("\n// ---- {path} ----\n");
        out += &preprocess_with(path, text, features, kernel)
            .unwrap_or_else(|e| panic!("{path}: {e} (a bug in the shader source)"));
    }
    out
}

/// The full WGSL source for `entry` specialised to `features`, for the default (hardware)
/// kernel variant.
pub fn assemble(features: SceneFeatures, entry: Entry) -> String {
    assemble_with(features, entry, KernelConfig::default())
}

/// The WGSL constants of `kernel`'s workgroup size.
fn kernel_prelude(kernel: KernelConfig) -> String {
    format!(
        "const WORKGROUP_SIZE: u32 = {}u;\nconst LINEAR_WORKGROUP_SIZE: u32 = {}u;\n",
        kernel.workgroup_side,
        kernel.linear_workgroup_size()
    )
}

/// The WGSL constants only `features`' code reads (none without them).
fn feature_prelude(features: SceneFeatures) -> String {
    if features.contains(SceneFeatures::DEPTH_OF_FIELD) {
        depth_of_field_wgsl_prelude()
    } else {
        String::new()
    }
}

/// The full WGSL source for `entry` specialised to `features` and `kernel`.
pub fn assemble_with(features: SceneFeatures, entry: Entry, kernel: KernelConfig) -> String {
    let mut out = wgsl_prelude() + &kernel_prelude(kernel) + &feature_prelude(features);
    out += &LaneLists::of(features, kernel).wgsl_prelude();
    let wavefront = entry.is_render() && wavefront_kernels(kernel, features);
    let tree = wavefront && features.contains(SceneFeatures::REFRACTION);
    if wavefront {
        out += &wavefront_wgsl_prelude();
    }
    if tree {
        out += &wavefront_tree_wgsl_prelude();
    }
    if wavefront {
        out += &queue_accessors(features, kernel);
    }
    out += &format!("// Specialised for features: {features}; kernel: {kernel}\n");
    let files = COMMON
        .iter()
        .chain(if entry.is_render() { RENDER } else { PROBE })
        .chain(if wavefront { WAVEFRONT } else { &[] })
        .chain(if tree { WAVEFRONT_TREE } else { &[] });
    for (path, text) in files {
        out += &format!("\n// ---- {path} ----\n");
        out += &preprocess_with(path, text, features, kernel)
            .unwrap_or_else(|e| panic!("{path}: {e} (a bug in the shader source)"));
    }
    out
}

/// The wavefront queues' accessors and counters of a render module with the wavefront
/// kernels for a scene with `features`: generated from their specification
/// (`tracer::wavefront::queues`; a tree's layout with refraction), with the fields whose `#if`
/// condition the module has.
pub fn queue_accessors(features: SceneFeatures, kernel: KernelConfig) -> String {
    let form = if features.contains(SceneFeatures::REFRACTION) {
        Form::Tree
    } else {
        Form::Chain
    };
    let present = |text: &str| {
        condition(text, features, kernel).unwrap_or_else(|e| {
            panic!("src/tracer/wavefront/queues.rs: {e} (a bug in the specification)")
        })
    };
    queue_wgsl(REGIONS, form, &present) + &counters_wgsl(COUNTERS, form)
}

/// Resolves the `// #if` blocks of one file (default kernel variant). Errors name the line
/// (unbalanced or unknown directives are bugs in the shader files, caught by the
/// validation tests).
pub fn preprocess(name: &str, text: &str, features: SceneFeatures) -> Result<String, String> {
    preprocess_with(name, text, features, KernelConfig::default())
}

/// [`preprocess`], with `ITERATION_GUARD` and `MAILBOXES` taken from `kernel`.
pub fn preprocess_with(
    name: &str,
    text: &str,
    features: SceneFeatures,
    kernel: KernelConfig,
) -> Result<String, String> {
    // Each open block: (this branch active, parent active, seen #else).
    let mut stack: Vec<(bool, bool, bool)> = Vec::new();
    let mut out = String::with_capacity(text.len());
    for (number, line) in text.lines().enumerate() {
        let at = || format!("{name}:{}", number + 1);
        let active = stack.last().is_none_or(|&(on, parent, _)| on && parent);
        let directive = line.trim().strip_prefix("// #");
        match directive {
            Some(rest) if rest.starts_with("if ") => {
                let on = condition(rest[3..].trim(), features, kernel)
                    .map_err(|e| format!("{}: {e}", at()))?;
                stack.push((on, active, false));
            }
            Some("else") => match stack.last_mut() {
                Some((on, _, seen_else)) if !*seen_else => {
                    *on = !*on;
                    *seen_else = true;
                }
                _ => return Err(format!("{}: #else without #if", at())),
            },
            Some("endif") => {
                stack
                    .pop()
                    .ok_or_else(|| format!("{}: #endif without #if", at()))?;
            }
            Some(other) => return Err(format!("{}: unknown directive #{other}", at())),
            None => {
                if active {
                    out += line;
                    out.push('\n');
                }
            }
        }
    }
    if !stack.is_empty() {
        return Err(format!("{name}: {} unclosed #if", stack.len()));
    }
    Ok(out)
}

/// Whether the render module of `kernel` for a scene with `features` has the wavefront
/// kernels (`WAVEFRONT`): where the variant asks for them; with refraction (paths that
/// branch) also the tree's (`src/tracer/wavefront/wavefront_tree.wgsl`).
pub fn wavefront_kernels(kernel: KernelConfig, _features: SceneFeatures) -> bool {
    kernel.wavefront
}

/// Whether a kernel variant sets one of its flags for a scene with these features.
type KernelFlag = fn(KernelConfig, SceneFeatures) -> bool;

/// The kernel variant's flags a shader may test with `#if`, and whether `kernel` sets each.
const KERNEL_FLAGS: [(&str, KernelFlag); 8] = [
    ("ITERATION_GUARD", |k, _| k.iteration_guard),
    ("MAILBOXES", |k, _| k.mailboxes == Mailboxes::Full),
    ("LAST_ITEM_MAILBOX", |k, _| {
        k.mailboxes == Mailboxes::LastItem
    }),
    ("STORAGE_TABLES", |k, _| k.storage_tables),
    ("LISTS_IN_STORAGE", |k, _| k.lists_in_storage),
    // With dielectrics in every variant (a second inlined copy of the first hit cost
    // llvmpipe more than the loop saves); with mirrors only where the variant asks
    // (`KernelConfig::camera_ray_in_loop`); never without secondary rays, which need
    // no loop at all. `#if` has no "and", hence the features here.
    ("CAMERA_RAY_IN_LOOP", |k, f| {
        f.contains(SceneFeatures::REFRACTION)
            || (k.camera_ray_in_loop && f.contains(SceneFeatures::REFLECTION))
    }),
    ("ANY_HIT_ONE_LOOP", |k, _| k.any_hit_one_loop),
    ("WAVEFRONT", wavefront_kernels),
];

/// Evaluates `NAME`, `A|B` or `!A|B` against `features` and `kernel`'s flags.
fn condition(text: &str, features: SceneFeatures, kernel: KernelConfig) -> Result<bool, String> {
    let (negate, names) = match text.strip_prefix('!') {
        Some(rest) => (true, rest),
        None => (false, text),
    };
    let mut any = false;
    for name in names.split('|').map(str::trim) {
        if let Some((_, set)) = KERNEL_FLAGS.iter().find(|(flag, _)| *flag == name) {
            any |= set(kernel, features);
            continue;
        }
        let flag = SceneFeatures::ALL
            .iter()
            .find(|(_, n)| n.replace('-', "_").eq_ignore_ascii_case(name))
            .map(|(f, _)| *f)
            .ok_or_else(|| {
                let valid: Vec<String> = SceneFeatures::ALL
                    .iter()
                    .map(|(_, n)| n.to_uppercase().replace('-', "_"))
                    .chain(KERNEL_FLAGS.iter().map(|(flag, _)| flag.to_string()))
                    .collect();
                format!("unknown feature '{name}' (valid: {})", valid.join(", "))
            })?;
        any |= features.contains(flag);
    }
    Ok(any != negate)
}

/// Parses and validates `source` with naga (no GPU needed); errors come formatted
/// against the source, with the features named.
pub fn validate(
    source: &str,
    features: SceneFeatures,
) -> Result<naga::Module, crate::gpu::GpuError> {
    let fail = |message: String| crate::gpu::GpuError::Shader {
        features: features.to_string(),
        message,
    };
    let module =
        naga::front::wgsl::parse_str(source).map_err(|e| fail(e.emit_to_string(source)))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .map_err(|e| fail(e.emit_to_string(source)))?;
    Ok(module)
}

/// Feature sets that exercise every feature and every pair of features (for validation
/// tests): none, all, each alone, all but each, and each pair. Every feature's code, and
/// each feature's interplay with every other, is then compiled in at least once both with
/// and without the other — all 2^n combinations would be thousands of sets.
pub fn all_feature_sets() -> Vec<SceneFeatures> {
    let flags: Vec<SceneFeatures> = SceneFeatures::ALL.iter().map(|(f, _)| *f).collect();
    let all = flags.iter().fold(SceneFeatures::empty(), |mut set, f| {
        set.insert(*f);
        set
    });
    let mut sets = vec![SceneFeatures::empty(), all];
    for (i, a) in flags.iter().enumerate() {
        sets.push(*a);
        sets.push(SceneFeatures(all.0 & !a.0));
        for b in &flags[i + 1..] {
            sets.push(SceneFeatures(a.0 | b.0));
        }
    }
    sets.sort_by_key(|s| s.0);
    sets.dedup();
    sets
}
