//! The kernels a scene's renders would compile: each `gr.render` of the script flattened
//! and packed as `glint render` does, its feature set specialising every render-module
//! entry point in the chosen kernel variant, and each entry's SPIR-V built as wgpu 30
//! hands it to Vulkan ([`glint::gpu::compile::spirv`]). Identical SPIR-V (the same entry of
//! scenes with the same features) is kept once, with every scene that uses it.

use glint::gpu::compile::kernel::{KernelConfig, KernelVariant};
use glint::gpu::compile::shader::{assemble_with, wavefront_kernels, Entry};
use glint::gpu::compile::spirv::{entry_spirv, spirv_bytes, SpirvTarget};
use glint::gpu::plan::Mode;
use glint::pack::SceneFeatures;
use glint::pipeline::prepare_request;
use glint::scene::OptionOverrides;
use glint::script_driver::{run_script, ScriptSettings};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};

/// Functions whose presence makes a kernel a traversal kernel (it walks the scene's
/// grids for closest or any hits), held to the tighter register budget.
const TRAVERSAL_FUNCTIONS: &[&str] = &["closest_hit", "any_hit"];

/// One distinct kernel: an entry point's SPIR-V.
#[derive(Clone, Debug)]
pub struct Kernel {
    pub entry: Entry,
    pub features: SceneFeatures,
    pub kernel: KernelConfig,
    pub wgsl: String,
    pub spirv: Vec<u32>,
    /// SHA-256 of the `.spv` file's bytes, hex.
    pub digest: String,
    /// It walks the scene for hits (reaches [`TRAVERSAL_FUNCTIONS`]).
    pub traversal: bool,
    /// (scene, whether the scene's own AA mode dispatches this entry) for every scene
    /// that compiles it.
    pub scenes: Vec<(String, bool)>,
}

/// The kernels of some scenes.
#[derive(Debug, Default)]
pub struct KernelSet {
    pub kernels: Vec<Kernel>,
}

/// The (features, AA mode) of each `gr.render` of `scene`.
pub fn scene_renders(scene: &Path) -> Result<Vec<(SceneFeatures, Mode)>, String> {
    let mut renders = Vec::new();
    let mut on_render = |graph: &glint::scene::SceneGraph,
                         request: &glint::scene::RenderRequest|
     -> anyhow::Result<()> {
        let (_, packed) = prepare_request(graph, request, &OptionOverrides::default())?;
        renders.push((packed.features, Mode::of(&packed.globals)));
        Ok(())
    };
    run_script(scene, &ScriptSettings::default(), &mut on_render)
        .map_err(|e| format!("{}: {e}", glint::display_path::shown(scene)))?;
    Ok(renders)
}

/// The kernel variant the instrument compiles: as glint chooses it for a hardware or a
/// software adapter (software: as on lavapipe, which binds every table as a storage
/// texture).
pub fn variant_config(variant: KernelVariant) -> KernelConfig {
    let limits = wgpu::Limits {
        max_storage_textures_per_shader_stage: u32::MAX,
        ..Default::default()
    };
    KernelConfig::for_variant(variant, &limits)
}

/// The SHA-256 of SPIR-V words as a `.spv` file, hex.
pub fn spirv_digest(words: &[u32]) -> String {
    Sha256::digest(spirv_bytes(words))
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

impl KernelSet {
    /// Adds `scene`'s kernels: `entries` (None: every render-module entry) of each of its
    /// renders' feature sets.
    pub fn add_scene(
        &mut self,
        scene: &Path,
        entries: Option<&[Entry]>,
        kernel: KernelConfig,
        target: SpirvTarget,
    ) -> Result<(), String> {
        let name = scene_name(scene);
        let all: Vec<Entry> = Entry::ALL.into_iter().filter(|e| e.is_render()).collect();
        let wanted = entries.unwrap_or(&all);
        for (features, mode) in scene_renders(scene)? {
            for &entry in wanted {
                if !entry.exists_in(kernel, features) {
                    continue;
                }
                // Where the wavefront kernels exist, AA none runs them instead of `main`,
                // uniform AA instead of its passes, adaptive AA instead of its tracing
                // passes (a tree: with its rounds and fold).
                let wavefront = wavefront_kernels(kernel, features);
                let tree = features.contains(SceneFeatures::REFRACTION);
                let dispatched = match mode {
                    Mode::None if wavefront && tree => Entry::WAVEFRONT_TREE[..10].contains(&entry),
                    Mode::Uniform { .. } if wavefront && tree => {
                        Entry::WAVEFRONT_TREE.contains(&entry)
                    }
                    Mode::None if wavefront => Entry::WAVEFRONT[..6].contains(&entry),
                    Mode::Uniform { .. } if wavefront => Entry::WAVEFRONT.contains(&entry),
                    Mode::Adaptive { .. } if wavefront && tree => {
                        Entry::ADAPTIVE_WAVEFRONT_TREE.contains(&entry)
                    }
                    Mode::Adaptive { .. } if wavefront => {
                        Entry::ADAPTIVE_WAVEFRONT.contains(&entry)
                    }
                    _ => mode.entries().contains(&entry),
                };
                self.add(&name, features, entry, dispatched, kernel, target)?;
            }
        }
        Ok(())
    }

    /// Adds the kernels of a scene with exactly `features`, named `name` (no script: the
    /// feature combinations of `glint kernels --features`): `entries` (None: every
    /// render-module entry) that its render module has. No AA mode is its own, so none
    /// is marked as dispatched.
    pub fn add_features(
        &mut self,
        name: &str,
        features: SceneFeatures,
        entries: Option<&[Entry]>,
        kernel: KernelConfig,
        target: SpirvTarget,
    ) -> Result<(), String> {
        let all: Vec<Entry> = Entry::ALL.into_iter().filter(|e| e.is_render()).collect();
        for &entry in entries.unwrap_or(&all) {
            if entry.exists_in(kernel, features) {
                self.add(name, features, entry, false, kernel, target)?;
            }
        }
        Ok(())
    }

    /// Adds a WGSL module of one's own (`--wgsl`): `entries` (None: `main`) of it, laid
    /// out as the render module's entries are.
    pub fn add_wgsl(
        &mut self,
        file: &Path,
        entries: Option<&[Entry]>,
        kernel: KernelConfig,
        target: SpirvTarget,
    ) -> Result<(), String> {
        let wgsl = read_wgsl(file)?;
        let name = scene_name(file);
        for &entry in entries.unwrap_or(&[Entry::Render]) {
            self.push(
                &name,
                &wgsl,
                SceneFeatures::empty(),
                entry,
                false,
                kernel,
                target,
            )?;
        }
        Ok(())
    }

    fn add(
        &mut self,
        scene: &str,
        features: SceneFeatures,
        entry: Entry,
        dispatched: bool,
        kernel: KernelConfig,
        target: SpirvTarget,
    ) -> Result<(), String> {
        let known = self
            .kernels
            .iter_mut()
            .find(|k| k.entry == entry && k.features == features && k.kernel == kernel);
        if let Some(k) = known {
            if !k.scenes.iter().any(|(s, _)| s == scene) {
                k.scenes.push((scene.to_string(), dispatched));
            }
            return Ok(());
        }
        let wgsl = assemble_with(features, entry, kernel);
        self.push(scene, &wgsl, features, entry, dispatched, kernel, target)
    }

    /// Compiles `entry` of `wgsl` to SPIR-V and keeps it.
    #[allow(clippy::too_many_arguments)]
    fn push(
        &mut self,
        scene: &str,
        wgsl: &str,
        features: SceneFeatures,
        entry: Entry,
        dispatched: bool,
        kernel: KernelConfig,
        target: SpirvTarget,
    ) -> Result<(), String> {
        let layout = glint::gpu::pipeline::layout_entries(entry, kernel);
        let (spirv, functions) = entry_spirv(wgsl, entry, &layout, target)
            .map_err(|e| format!("{scene}: {}: {e}", entry.name()))?;
        let traversal = functions
            .iter()
            .any(|f| TRAVERSAL_FUNCTIONS.contains(&f.as_str()));
        self.kernels.push(Kernel {
            entry,
            features,
            kernel,
            digest: spirv_digest(&spirv),
            wgsl: wgsl.to_string(),
            spirv,
            traversal,
            scenes: vec![(scene.to_string(), dispatched)],
        });
        Ok(())
    }
}

/// A WGSL module of one's own, read as every file glint reads (regular files only, at
/// most [`super::wgsl_bounds::MAX_WGSL_BYTES`]) and held to
/// [`super::wgsl_bounds::check_bounds`] before naga sees it.
pub fn read_wgsl(file: &Path) -> Result<String, String> {
    use super::wgsl_bounds::{check_bounds, MAX_WGSL_BYTES};
    let shown = glint::display_path::shown(file);
    let bytes = glint::scene::files::read_regular(file, "WGSL module", MAX_WGSL_BYTES)?;
    let wgsl = String::from_utf8(bytes).map_err(|_| format!("{shown}: not UTF-8 text"))?;
    check_bounds(&wgsl).map_err(|e| format!("{shown}:{e}"))?;
    Ok(wgsl)
}

/// A scene as the tables name it: its path as given.
fn scene_name(scene: &Path) -> String {
    glint::display_path::shown(scene)
}

/// Every scene script under `dir` (recursively, `.lua` files that call `gr.render`
/// somewhere in their text), sorted. Symbolic links to folders are not followed (a link
/// loop would never end); a `.lua` entry is read as a scene is
/// ([`glint::scene::files::read_regular`]: a FIFO, a device or a link to one is
/// skipped without blocking, and at most [`glint::scene::files::MAX_FILE_BYTES`]).
pub fn scenes_under(dir: &Path) -> Vec<PathBuf> {
    use glint::scene::files::{read_regular, MAX_FILE_BYTES};
    let mut found = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(read) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in read.flatten() {
            let p = e.path();
            // The entry itself, not what a link points at.
            if e.file_type().is_ok_and(|t| t.is_dir()) {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "lua")
                && read_regular(&p, "scene", MAX_FILE_BYTES)
                    .is_ok_and(|t| t.windows(9).any(|w| w == b"gr.render"))
            {
                found.push(p);
            }
        }
    }
    found.sort();
    found
}
