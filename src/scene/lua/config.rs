//! How a script runs ([`ScriptConfig`]: its limits, folders, preludes and frame) and what
//! it did ([`ScriptReport`]), with the defaults the command line starts from.

use crate::scene::TransformOrder;
use std::path::PathBuf;
use std::time::Duration;

/// How to run a script. The defaults suit the command line.
#[derive(Clone, Debug)]
pub struct ScriptConfig {
    /// Transform order forced by the CLI flag; it beats `gr.transform_order` in the script.
    pub transform_order: Option<TransformOrder>,
    /// Lua VM instructions a script may execute before it is stopped as a runaway.
    pub instruction_limit: u64,
    /// The memory budget in bytes: the Lua heap plus what the scene holds in Rust (nodes
    /// and their names, meshes, textures) plus what each render will build (counted
    /// before it is built).
    pub memory_limit: usize,
    /// Wall-clock time the script may run, renders not counted.
    pub time_limit: Duration,
    /// End the process (exit code 3) when the script overruns `time_limit` where the
    /// instruction hook cannot stop it (inside a C function). For the command line; a
    /// library caller gets the error only when the hook can raise it.
    pub hard_time_limit: bool,
    /// Folders the scene may read besides its own (`--allow-read`).
    pub allow_read: Vec<PathBuf>,
    /// Lua files run before the scene, in order, in the same state and under the same
    /// limits (`--prelude`): a dialect of another CS488 tracer mapped onto glint's calls.
    /// Each one's folder is readable too.
    pub preludes: Vec<PathBuf>,
    /// No notes about arguments glint does not use (`--ignore-extra-arguments`; a scene
    /// can say the same with `gr.ignore_extra_arguments()`).
    pub ignore_extra_arguments: bool,
    /// Most `gr.render` calls the script may make (`--max-renders`).
    pub max_renders: u64,
    /// Most pixels all of the script's `gr.render` calls may ask for together
    /// (`--max-render-pixels`).
    pub max_render_pixels: u64,
    /// An animation's frame (`--frames`, `--frame`): the globals `frame` and `clock` the
    /// script sees; `None` leaves them unset.
    pub frame: Option<FrameGlobals>,
}

/// The globals of one frame of an animation (POV-Ray's `frame_number` and `clock`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameGlobals {
    /// The frame number (a Lua integer).
    pub frame: i64,
    /// 0 at the range's first frame, 1 at its last (0 for a single frame).
    pub clock: f64,
}

/// Default bound on the renders of one script.
pub const DEFAULT_MAX_RENDERS: u64 = 1024;

/// Default bound on the pixels of all the renders of one script (2³²: 32 images of the
/// largest size, 2 000 frames of 1920×1080).
pub const DEFAULT_MAX_RENDER_PIXELS: u64 = 1 << 32;

/// Default memory budget (2 GiB).
pub const DEFAULT_MEMORY_LIMIT: usize = 2 << 30;

/// Default script time limit: the slowest script of `scenes/` and the CS488 corpus runs
/// in well under a second (scrabble.lua's whole 4×4 render takes 0.3 s), so 15 s leaves
/// a margin of 50 and still ends a runaway within half a minute, start-up included.
pub const DEFAULT_TIME_LIMIT: Duration = Duration::from_secs(15);

impl Default for ScriptConfig {
    fn default() -> Self {
        ScriptConfig {
            transform_order: None,
            instruction_limit: 200_000_000,
            memory_limit: DEFAULT_MEMORY_LIMIT,
            time_limit: DEFAULT_TIME_LIMIT,
            hard_time_limit: false,
            allow_read: Vec::new(),
            preludes: Vec::new(),
            ignore_extra_arguments: false,
            max_renders: DEFAULT_MAX_RENDERS,
            max_render_pixels: DEFAULT_MAX_RENDER_PIXELS,
            frame: None,
        }
    }
}

/// What a finished script did, for the caller's summary and hints.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ScriptReport {
    /// Number of `gr.render` calls.
    pub renders: usize,
    /// The script called `gr.transform_order`.
    pub order_set_by_script: bool,
    /// What makes the script look written for the pre-2015 course, which needs
    /// `--transform-order post` unless it says so itself (`readobj at scene.lua:8`;
    /// see `era`), or None.
    pub looks_pre2015: Option<String>,
    /// The script read the global `frame` or `clock` (set for `--frames`).
    pub reads_frame: bool,
    /// The notes printed on stderr (arguments glint does not use), one per call site.
    pub notes: Vec<String>,
    /// The advice printed on stderr (likely mistakes: a field of view in radians, a root
    /// with nothing under it), one per call site.
    pub advice: Vec<String>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn config_defaults() {
        let c = ScriptConfig::default();
        assert_eq!(c.transform_order, None);
        assert_eq!(c.instruction_limit, 200_000_000);
        assert_eq!(c.memory_limit, 2 << 30);
        assert_eq!(c.time_limit, Duration::from_secs(15));
    }
}
