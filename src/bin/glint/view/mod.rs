//! `glint view SCENE.lua`: a window (winit) showing the scene traced progressively —
//! one jittered sample per pixel per frame, accumulated until the image equals `glint
//! render --aa uniform --samples n` — on the GPU device that presents it, or by the CPU
//! tracer; a camera moved with the mouse and keys; the script re-run when any file it
//! read changes. See docs/view.md.
//!
//! - [`args`]: the command line; [`config`]: it resolved, and the display check; [`load`]: the script run (one script driver) and the
//!   view's sampling; [`camera`]: the moved camera, written as `pack` writes it;
//! - [`app`]: the window, its device and events; [`session`]: the state they change;
//!   [`present`]: the surface and the present pass; [`input`]: keys and mouse;
//!   [`watch`]: live reload's file watcher; [`status`]: title and timings; [`save`]: S.

pub mod app;
pub mod args;
pub mod camera;
pub mod config;
pub mod input;
pub mod load;
pub mod present;
pub mod save;
pub mod session;
pub mod status;
pub mod watch;

pub use args::ViewArgs;
pub use config::{display_available, no_display_message, ViewConfig, NO_DISPLAY_EXIT};

/// Runs `glint view`: Ok on a clean quit, else the message and exit code.
pub fn run(args: &ViewArgs) -> Result<(), (String, u8)> {
    let config = ViewConfig::from_args(args).map_err(|e| (e, 2))?;
    if let Err(why) = display_available() {
        return Err((no_display_message(&why), NO_DISPLAY_EXIT));
    }
    app::run_app(config)
}
