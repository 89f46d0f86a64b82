//! Running the scene for the view: the script through the one script driver (the same
//! sandbox and limits as `glint render`), its first `gr.render` flattened and packed as
//! `render` packs it, and every file the run read (for live reload).

use glint::constants::{AA_NONE, AA_UNIFORM};
use glint::pack::PackedScene;
use glint::pipeline::prepare_request;
use glint::scene::files::record_reads;
use glint::scene::{AaMode, AaSamples, Camera, OptionOverrides, RenderRequest};
use glint::script_driver::{run_script, ScriptSettings};
use std::path::{Path, PathBuf};

/// What the view shows of a script run.
pub struct LoadedScene {
    /// The first `gr.render` call, with the command line's overrides applied.
    pub request: RenderRequest,
    /// It packed, with the view's sampling in its globals ([`view_sampling`]).
    pub packed: PackedScene,
    /// The script's own camera (R returns to it; a reload that changes it moves the view).
    pub camera: Camera,
}

/// The outcome of one run: the scene or the error message (starting `file:line:` where
/// Lua can tell), and the files the run tried to read either way.
pub struct LoadOutcome {
    pub scene: Result<LoadedScene, String>,
    pub files: Vec<PathBuf>,
}

/// The sampling the view converges to: `aa` and `samples` from the command line, else
/// the scene's own `aa` when it is none or uniform (adaptive becomes uniform), and the
/// scene's `samples`.
#[derive(Clone, Copy, Debug, Default)]
pub struct ViewSampling {
    pub aa: Option<AaMode>,
    pub samples: Option<AaSamples>,
}

/// Writes the view's sampling into `packed`'s globals: uniform n×n or AA none. The
/// progressive kernels read these two fields exactly as `render_pixel` does.
pub fn view_sampling(packed: &mut PackedScene, scene_aa: AaMode, sampling: ViewSampling) {
    let g = &mut packed.globals;
    let aa = sampling.aa.unwrap_or(match scene_aa {
        AaMode::None => AaMode::None,
        AaMode::Uniform | AaMode::Adaptive => AaMode::Uniform,
    });
    g.aa_mode = if aa == AaMode::None {
        AA_NONE
    } else {
        AA_UNIFORM
    };
    if let Some(n) = sampling.samples {
        g.aa_samples = n.get();
    }
}

/// Frames until the view has every sample: n² for uniform AA, 1 for AA none.
pub fn frames_to_converge(packed: &PackedScene) -> u32 {
    match packed.globals.aa_mode {
        AA_UNIFORM => packed.globals.aa_samples * packed.globals.aa_samples,
        _ => 1,
    }
}

/// Runs `path` under `settings` and keeps its first `gr.render` (later calls are
/// ignored: the view shows one image).
pub fn load_scene(
    path: &Path,
    settings: &ScriptSettings,
    overrides: &OptionOverrides,
    sampling: ViewSampling,
) -> LoadOutcome {
    let mut first: Option<LoadedScene> = None;
    let mut on_render =
        |graph: &glint::scene::SceneGraph, request: &RenderRequest| -> anyhow::Result<()> {
            if first.is_some() {
                return Ok(());
            }
            let (request, mut packed) = prepare_request(graph, request, overrides)?;
            view_sampling(&mut packed, request.options.aa, sampling);
            first = Some(LoadedScene {
                camera: request.camera.clone(),
                request,
                packed,
            });
            Ok(())
        };
    let (result, files) = record_reads(|| run_script(path, settings, &mut on_render));
    let scene = match result {
        Err(e) => Err(glint::scene::lua::cap_message(&e.to_string())),
        Ok(_) => first.ok_or_else(|| {
            format!(
                "{}: the script never called gr.render: nothing to show",
                glint::display_path::shown(path)
            )
        }),
    };
    LoadOutcome { scene, files }
}
