//! `glint view SCENE.lua`: a window (winit) showing the scene traced progressively —
//! one jittered sample per pixel per frame, accumulated until the image equals `glint
//! render --aa uniform --samples n` — on the GPU device that presents it, or by the CPU
//! tracer; a camera moved with the mouse and keys; the script re-run when any file it
//! read changes. See docs/view.md.
//!
//! - [`args`]: the command line; [`load`]: the script run (one script driver) and the
//!   view's sampling; [`camera`]: the moved camera, written as `pack` writes it;
//! - [`app`]: the window, its device and events; [`session`]: the state they change;
//!   [`present`]: the surface and the present pass; [`input`]: keys and mouse;
//!   [`watch`]: live reload's file watcher; [`status`]: title and timings; [`save`]: S.

pub mod app;
pub mod args;
pub mod camera;
pub mod input;
pub mod load;
pub mod present;
pub mod save;
pub mod session;
pub mod status;
pub mod watch;

pub use args::{ViewArgs, ViewBackend};

use crate::scene::OptionOverrides;
use crate::script_driver::ScriptSettings;
use load::ViewSampling;
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
    pub frames: Option<u64>,
    pub screenshot: Option<PathBuf>,
}

impl ViewConfig {
    pub fn from_args(args: &ViewArgs) -> Result<ViewConfig, String> {
        crate::write_policy::WritePolicy::new(args.output_dir.as_deref(), &args.allow_write)?;
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

/// Runs `glint view`: Ok on a clean quit, else the message and exit code.
pub fn run(args: &ViewArgs) -> Result<(), (String, u8)> {
    let config = ViewConfig::from_args(args).map_err(|e| (e, 2))?;
    if let Err(why) = display_available() {
        return Err((no_display_message(&why), NO_DISPLAY_EXIT));
    }
    app::run_app(config)
}
