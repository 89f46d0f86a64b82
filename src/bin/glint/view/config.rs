//! What `glint view` was asked, resolved ([`ViewConfig`]), and whether there is a display
//! to open its window on (the one message a display-less run prints).

use super::args::{ViewArgs, ViewBackend};
use super::load::ViewSampling;
use glint::scene::OptionOverrides;
use glint::script_driver::ScriptSettings;
use std::path::PathBuf;

/// Exit code of a view that cannot open a window (as a usage error: nothing ran).
pub const NO_DISPLAY_EXIT: u8 = 2;

/// Everything the view was asked on the command line, resolved.
#[derive(Clone, Debug)]
pub struct ViewConfig {
    pub scene: PathBuf,
    pub script: ScriptSettings,
    pub overrides: OptionOverrides,
    pub sampling: ViewSampling,
    pub output: Option<PathBuf>,
    pub output_dir: Option<PathBuf>,
    pub allow_write: Vec<PathBuf>,
    pub backend: ViewBackend,
    pub adapter: Option<String>,
    pub kernel_variant: Option<glint::gpu::KernelVariant>,
    pub frames: Option<u64>,
    pub screenshot: Option<PathBuf>,
}

impl ViewConfig {
    pub fn from_args(args: &ViewArgs) -> Result<ViewConfig, String> {
        glint::write_policy::WritePolicy::new(args.output_dir.as_deref(), &args.allow_write)?;
        Ok(ViewConfig {
            scene: args.scene.clone(),
            script: args.script_settings()?,
            overrides: args.overrides(),
            sampling: ViewSampling {
                aa: args.aa,
                samples: args.samples,
            },
            output: args.output.clone(),
            output_dir: args.output_dir.clone(),
            allow_write: args.allow_write.clone(),
            backend: args.backend,
            adapter: args.adapter.clone(),
            kernel_variant: args.kernel_variant,
            frames: args.frames,
            screenshot: args.screenshot.clone(),
        })
    }
}

/// Why there is no window, as the one message a display-less run prints.
pub fn no_display_message(why: &str) -> String {
    format!(
        "glint view needs a display to open its window, and {why}; to render the scene to a file instead, use glint render SCENE.lua -o image.png"
    )
}

/// Whether the environment names a display this build can open (X11: `DISPLAY`; on a
/// Wayland desktop that is XWayland's), else why not.
pub fn display_available() -> Result<(), String> {
    let set = |v: &str| std::env::var_os(v).is_some_and(|s| !s.is_empty());
    if set("DISPLAY") {
        return Ok(());
    }
    if set("WAYLAND_DISPLAY") {
        return Err("WAYLAND_DISPLAY is set but DISPLAY is not (this build opens X11 windows: run XWayland)".into());
    }
    Err("neither DISPLAY nor WAYLAND_DISPLAY is set".into())
}
