//! The one way a scene script is run, in every mode of the command line (`render` on
//! either tracer, `--backend both`, `bench`, `view`) and by a library caller: the binary's
//! sandbox flags (its `script_args`) become [`ScriptSettings`], and
//! [`ScriptSettings::config`] is the only place a [`ScriptConfig`] is built from them, so
//! no mode can run a script under weaker limits than another.

use crate::scene::lua::{
    run_scene_file, run_scene_source, FrameGlobals, OnRender, SceneError, ScriptConfig,
    ScriptReport,
};
use crate::scene::TransformOrder;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// What the caller says about running a script: each `None` keeps [`ScriptConfig`]'s
/// default.
#[derive(Clone, Debug, Default)]
pub struct ScriptSettings {
    /// `--transform-order` (beats the script).
    pub transform_order: Option<TransformOrder>,
    /// `--instruction-limit`: Lua instructions before the script is stopped.
    pub instruction_limit: Option<u64>,
    /// `--script-timeout`: the script's wall-clock limit.
    pub script_timeout: Option<Duration>,
    /// `--memory-limit`: the memory budget in bytes.
    pub memory_limit: Option<usize>,
    /// `--allow-read`: folders the scene may read besides its own.
    pub allow_read: Vec<PathBuf>,
    /// `--prelude`: Lua files run before the scene, in order (a dialect's calls).
    pub preludes: Vec<PathBuf>,
    /// End the process (exit code 3) when the script overruns its time where it cannot
    /// be interrupted (the command line sets it; a library caller gets an error instead).
    pub hard_time_limit: bool,
    /// `--ignore-extra-arguments`: no notes on arguments the scene passes that glint does
    /// not use.
    pub ignore_extra_arguments: bool,
    /// `--max-renders`: most `gr.render` calls one script may make.
    pub max_renders: Option<u64>,
    /// `--max-render-pixels`: most pixels all of a script's renders may ask for.
    pub max_render_pixels: Option<u64>,
    /// An animation's frame: the script's globals `frame` and `clock` (`--frames`).
    pub frame: Option<FrameGlobals>,
}

impl ScriptSettings {
    /// The script's configuration: the defaults with these settings applied.
    pub fn config(&self) -> ScriptConfig {
        let defaults = ScriptConfig::default();
        ScriptConfig {
            transform_order: self.transform_order,
            instruction_limit: self.instruction_limit.unwrap_or(defaults.instruction_limit),
            memory_limit: self.memory_limit.unwrap_or(defaults.memory_limit),
            time_limit: self.script_timeout.unwrap_or(defaults.time_limit),
            hard_time_limit: self.hard_time_limit,
            allow_read: self.allow_read.clone(),
            preludes: self.preludes.clone(),
            ignore_extra_arguments: self.ignore_extra_arguments,
            max_renders: self.max_renders.unwrap_or(defaults.max_renders),
            max_render_pixels: self.max_render_pixels.unwrap_or(defaults.max_render_pixels),
            frame: self.frame,
        }
    }
}

/// Runs the scene file at `path` under `settings`; `on_render` gets each `gr.render`.
pub fn run_script(
    path: &Path,
    settings: &ScriptSettings,
    on_render: &mut OnRender<'_>,
) -> Result<ScriptReport, SceneError> {
    run_scene_file(path, &settings.config(), on_render)
}

/// [`run_script`] on the scene's bytes, read already by the caller (the farm digests the
/// bytes it runs, so it reads them once: [`crate::scene::lua::read_scene_bytes`]).
pub fn run_script_bytes(
    path: &Path,
    bytes: &[u8],
    settings: &ScriptSettings,
    on_render: &mut OnRender<'_>,
) -> Result<ScriptReport, SceneError> {
    let source = String::from_utf8_lossy(bytes);
    let base_dir = path.parent().unwrap_or(Path::new(""));
    let name = crate::display_path::shown(path);
    run_scene_source(&name, &source, base_dir, &settings.config(), on_render)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_setting_reaches_the_config() {
        let settings = ScriptSettings {
            transform_order: Some(TransformOrder::Post),
            instruction_limit: Some(7),
            script_timeout: Some(Duration::from_secs(3)),
            memory_limit: Some(1 << 24),
            allow_read: vec![PathBuf::from("/x")],
            preludes: vec![PathBuf::from("/d/a.lua"), PathBuf::from("b.lua")],
            hard_time_limit: true,
            ignore_extra_arguments: true,
            max_renders: Some(5),
            max_render_pixels: Some(1 << 20),
            frame: Some(FrameGlobals {
                frame: 12,
                clock: 0.5,
            }),
        };
        let c = settings.config();
        assert_eq!(c.transform_order, Some(TransformOrder::Post));
        assert_eq!(c.instruction_limit, 7);
        assert_eq!(c.time_limit, Duration::from_secs(3));
        assert_eq!(c.memory_limit, 1 << 24);
        assert_eq!(c.allow_read, vec![PathBuf::from("/x")]);
        assert_eq!(
            c.preludes,
            vec![PathBuf::from("/d/a.lua"), PathBuf::from("b.lua")]
        );
        assert!(c.hard_time_limit);
        assert!(c.ignore_extra_arguments);
        assert_eq!(c.max_renders, 5);
        assert_eq!(c.max_render_pixels, 1 << 20);
        assert_eq!(
            c.frame,
            Some(FrameGlobals {
                frame: 12,
                clock: 0.5
            })
        );
    }

    #[test]
    fn unset_settings_keep_the_defaults() {
        let c = ScriptSettings::default().config();
        let d = ScriptConfig::default();
        assert_eq!(c.instruction_limit, d.instruction_limit);
        assert_eq!(c.time_limit, d.time_limit);
        assert_eq!(c.memory_limit, d.memory_limit);
        assert!(!c.hard_time_limit);
    }
}
