//! The `gr` Lua module: runs a CS488 A4 scene script (the language is described in
//! docs/scene-language.md) into a [`SceneGraph`], handing each `gr.render` call to the
//! caller as it happens.
//!
//! Layout: `sandbox` builds the restricted Lua state (limits, `require`, `unpack`,
//! `readobj`), `gr` defines the scene calls, `handles` the node/material/light userdata
//! and their methods, `args` checks arguments and words the errors, `options` parses the
//! render-options table.
//! The script's state lives in Lua's app data ([`State`]) so that the `'static` callbacks
//! mlua requires can reach it; only `gr.render`, which borrows the caller's `on_render`,
//! is a scoped function.

mod args;
mod gr;
mod handle_types;
mod handles;
mod maps;
mod options;
mod sandbox;
mod watchdog;

pub use gr::MAX_IMAGE_SIDE;

use super::files::{read_regular, ReadPolicy, MAX_FILE_BYTES};
use super::{MeshId, NodeId, RenderRequest, SceneGraph, TransformOrder};
use mlua::chunk::ChunkMode;
use mlua::Lua;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
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
    /// The script used inline meshes, `require` or bare `unpack`: the pre-2015 family,
    /// which needs `--transform-order post` unless it says so itself.
    pub looks_pre2015: bool,
}

/// A scene script failed. `Display` is the whole message, starting with `file:line:`
/// wherever Lua can tell the line.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The scene file itself could not be read; the message names the path.
    #[error("{message}")]
    Read { path: PathBuf, message: String },
    /// Lua could not parse the scene (or a module it requires).
    #[error("{message}")]
    Syntax { message: String },
    /// A runtime error: a bad argument to a `gr` call, a Lua error, a missing file.
    #[error("{message}")]
    Runtime {
        message: String,
        /// Lua's stack traceback, when there is one.
        traceback: Option<String>,
    },
    /// The instruction, time or memory limit was reached.
    #[error("{message}")]
    Limit { message: String },
    /// The caller's render callback failed; `location` is the `gr.render` call's `file:line`.
    #[error("{location}: gr.render: {error:#}")]
    Render {
        location: String,
        error: anyhow::Error,
    },
}

/// The callback `gr.render` invokes with the graph built so far and the request.
pub type OnRender<'a> = dyn FnMut(&SceneGraph, &RenderRequest) -> anyhow::Result<()> + 'a;

/// Runs the scene file at `path`. Meshes and modules resolve against its directory.
pub fn run_scene_file(
    path: &Path,
    config: &ScriptConfig,
    on_render: &mut OnRender<'_>,
) -> Result<ScriptReport, SceneError> {
    let bytes =
        read_regular(path, "scene file", MAX_FILE_BYTES).map_err(|message| SceneError::Read {
            path: path.to_path_buf(),
            message,
        })?;
    let source = String::from_utf8_lossy(&bytes);
    let base_dir = path.parent().unwrap_or(Path::new(""));
    run_scene_source(
        &path.display().to_string(),
        &source,
        base_dir,
        config,
        on_render,
    )
}

/// Sets `frame` and `clock` for an animation's frame.
fn set_frame_globals(lua: &Lua, frame: Option<FrameGlobals>) -> mlua::Result<()> {
    if let Some(f) = frame {
        lua.globals().set("frame", f.frame)?;
        lua.globals().set("clock", f.clock)?;
    }
    Ok(())
}

/// Runs scene source text named `chunk_name` (used in messages as `chunk_name:line:`),
/// resolving meshes and modules against `base_dir`.
pub fn run_scene_source(
    chunk_name: &str,
    source: &str,
    base_dir: &Path,
    config: &ScriptConfig,
    on_render: &mut OnRender<'_>,
) -> Result<ScriptReport, SceneError> {
    let watchdog = watchdog::Watchdog::start(config.time_limit, config.hard_time_limit, chunk_name);
    let limits = sandbox::Limits::default();
    let lua =
        sandbox::new_lua(config, &limits, watchdog.clock()).map_err(|e| SceneError::Runtime {
            message: format!("{chunk_name}: cannot set up Lua: {e}"),
            traceback: None,
        })?;
    lua.set_app_data(State {
        graph: SceneGraph::default(),
        order: config.transform_order.unwrap_or_default(),
        order_fixed: config.transform_order.is_some(),
        base_dir: base_dir.to_path_buf(),
        read_policy: ReadPolicy::new(base_dir, &config.allow_read),
        report: ScriptReport::default(),
        mesh_cache: HashMap::new(),
        texture_cache: HashMap::new(),
        render_error: None,
        memory_limit: config.memory_limit as u64,
        charged: 0,
        parents: Vec::new(),
        cycle_search: handles::CycleSearch::default(),
        cycle_check_visits: 0,
        clock: watchdog.clock(),
    });
    let setup = gr::install(&lua)
        .and_then(|()| sandbox::install(&lua))
        .and_then(|()| set_frame_globals(&lua, config.frame));
    if let Err(e) = setup {
        return Err(SceneError::Runtime {
            message: format!("{chunk_name}: cannot set up the gr module: {e}"),
            traceback: None,
        });
    }

    let result = lua.scope(|scope| {
        let render = scope.create_function_mut(|lua, args: mlua::MultiValue| {
            gr::render(lua, args, &mut *on_render)
        })?;
        lua.globals()
            .get::<mlua::Table>("gr")?
            .set("render", render)?;
        lua.load(source)
            .set_name(format!("@{chunk_name}"))
            .set_mode(ChunkMode::Text)
            .exec()
    });

    // The state stays installed until the Lua state is dropped, so nothing Lua might
    // still run while closing can find it missing.
    let (render_error, report) = with_state(&lua, |s| {
        (s.render_error.take(), std::mem::take(&mut s.report))
    });
    // A render failure or a reached limit ends the script even if a `pcall` in the
    // script caught the Lua error and carried on.
    if let Some((location, error)) = render_error {
        return Err(SceneError::Render { location, error });
    }
    if let Some(message) = limits.exceeded.take() {
        return Err(SceneError::Limit { message });
    }
    match result {
        Ok(()) => Ok(report),
        Err(e) => Err(convert_error(&e, chunk_name, config, &limits)),
    }
}

/// Everything the callbacks share while a script runs (kept in Lua's app data).
pub(crate) struct State {
    pub graph: SceneGraph,
    pub order: TransformOrder,
    /// The CLI flag fixed the order: `gr.transform_order` is recorded but has no effect.
    pub order_fixed: bool,
    pub base_dir: PathBuf,
    /// The folders the scene may read.
    pub read_policy: ReadPolicy,
    pub report: ScriptReport,
    /// Mesh files already loaded (by canonical path), so instancing a file twice, under
    /// any spelling of its path, shares the triangles.
    pub mesh_cache: HashMap<PathBuf, MeshId>,
    /// Image files already loaded (by canonical path), so materials naming the same
    /// file share its texels.
    pub texture_cache: HashMap<PathBuf, crate::scene::TextureId>,
    /// The caller's render error, kept whole (Lua can only carry a string of it).
    pub render_error: Option<(String, anyhow::Error)>,
    /// The memory budget ([`ScriptConfig::memory_limit`]).
    pub memory_limit: u64,
    /// Bytes of the budget the scene holds in Rust (see [`charge`]).
    pub charged: u64,
    /// Per node: the nodes holding it as a child or CSG operand (the cycle check
    /// searches upwards through them).
    pub parents: Vec<Vec<NodeId>>,
    /// The cycle check's visited marks.
    pub cycle_search: handles::CycleSearch,
    /// Nodes the cycle checks of `add_child` have visited, against a limit.
    pub cycle_check_visits: u64,
    /// The wall-clock limit's clock, paused while `gr.render` renders.
    pub clock: watchdog::ScriptClock,
}

impl State {
    /// Records that `parent` holds `child` (an `add_child` or a CSG operand).
    pub fn add_parent(&mut self, child: NodeId, parent: NodeId) {
        if self.parents.len() <= child.max(parent) {
            let n = self.graph.nodes.len().max(child.max(parent) + 1);
            self.parents.resize(n, Vec::new());
        }
        self.parents[child].push(parent);
    }
}

/// Bytes of the budget left for a render: the limit less the scene and the Lua heap.
pub(crate) fn memory_left(lua: &Lua) -> u64 {
    let used = lua.used_memory() as u64;
    with_state(lua, |s| {
        s.memory_limit
            .saturating_sub(s.charged)
            .saturating_sub(used)
    })
}

/// Refuses to read the file at `path` when holding it while it is parsed or decoded
/// (`factor` bytes per byte of file) would not fit the memory budget left. A file that
/// cannot be examined passes here: reading it then reports why.
pub(crate) fn check_file_cost(
    a: &args::Args,
    path: &Path,
    factor: u64,
    what: &str,
) -> mlua::Result<()> {
    let Ok(meta) = std::fs::metadata(path) else {
        return Ok(());
    };
    let left = memory_left(a.lua);
    if meta.is_file() && meta.len().saturating_mul(factor) > left {
        return Err(a.error(format!(
            "{what} '{}' is {} MiB; reading it may take up to {factor}× that, over the {} MiB left of the memory limit; --memory-limit MIB raises it",
            path.display(),
            meta.len().div_ceil(1 << 20),
            left >> 20
        )));
    }
    Ok(())
}

/// Counts `bytes` the scene is about to hold in Rust against the memory budget (with
/// what the Lua heap holds now), or fails with a message naming the call's line. The Lua
/// heap's own limit shrinks by the same amount, so both draw on one budget.
pub(crate) fn charge(a: &args::Args, bytes: u64, what: &str) -> mlua::Result<()> {
    let used = a.lua.used_memory() as u64;
    let outcome = with_state(a.lua, |s| {
        let total = s.charged.saturating_add(bytes).saturating_add(used);
        if total > s.memory_limit {
            Err((s.charged, s.memory_limit))
        } else {
            s.charged += bytes;
            Ok(s.memory_limit - s.charged)
        }
    });
    match outcome {
        Ok(lua_limit) => {
            a.lua
                .set_memory_limit(lua_limit.try_into().unwrap_or(usize::MAX))?;
            Ok(())
        }
        Err((charged, limit)) => Err(a.error(format!(
            "{what} ({} MiB) would go over the memory limit of {} MiB (the scene holds {} MiB, Lua {} MiB); --memory-limit MIB raises it",
            bytes.div_ceil(1 << 20),
            limit >> 20,
            charged >> 20,
            used >> 20
        ))),
    }
}

/// Runs `f` on the script state. Never call Lua inside `f`: the state is borrowed.
pub(crate) fn with_state<R>(lua: &Lua, f: impl FnOnce(&mut State) -> R) -> R {
    let mut state = lua
        .app_data_mut::<State>()
        .expect("script state is installed before the script runs");
    f(&mut state)
}

/// Turns an mlua error into a [`SceneError`], unwrapping the callback layers mlua adds so
/// that the message is the one written where the error arose.
fn convert_error(
    e: &mlua::Error,
    chunk_name: &str,
    config: &ScriptConfig,
    limits: &sandbox::Limits,
) -> SceneError {
    let mut traceback = None;
    let mut e = e;
    loop {
        match e {
            mlua::Error::CallbackError {
                traceback: t,
                cause,
            } => {
                traceback.get_or_insert_with(|| t.clone());
                e = cause;
            }
            mlua::Error::WithContext { cause, .. } => e = cause,
            _ => break,
        }
    }
    match e {
        mlua::Error::SyntaxError { message, .. } => SceneError::Syntax {
            message: message.clone(),
        },
        mlua::Error::MemoryError(_) => {
            // Lua's memory errors carry no position: take the traceback's innermost
            // frame, else the last line the instruction hook saw.
            let at = traceback
                .as_deref()
                .and_then(traceback_frame)
                .or_else(|| limits.last_location.take())
                .unwrap_or_else(|| chunk_name.to_string());
            SceneError::Limit {
                message: format!(
                    "{at}: the script went over the memory limit of {} MiB; --memory-limit MIB raises it",
                    config.memory_limit >> 20
                ),
            }
        }
        mlua::Error::RuntimeError(message) => {
            let (message, tb) = split_traceback(message);
            let traceback = traceback.or(tb);
            SceneError::Runtime {
                message: with_location(message, traceback.as_deref()),
                traceback,
            }
        }
        other => {
            let text = other.to_string();
            let (message, tb) = split_traceback(&text);
            SceneError::Runtime {
                message: message.to_string(),
                traceback: traceback.or(tb),
            }
        }
    }
}

/// `error({})` and the like carry no position: borrow the innermost Lua frame of the
/// traceback (`\tscene.lua:3: in main chunk`) so the message still says where.
/// An error passed up through `coroutine.wrap` (or re-raised) gets the outer position
/// prepended to its own (`a.lua:2: a.lua:1: boom`): only the innermost, where it arose,
/// is kept.
fn with_location(message: &str, traceback: Option<&str>) -> String {
    if let Some(mut n) = leading_location(message) {
        let mut message = message;
        while let Some(inner) = leading_location(&message[n..]) {
            message = &message[n..];
            n = inner;
        }
        return message.to_string();
    }
    match traceback.and_then(traceback_frame) {
        Some(at) => format!("{at}: {message}"),
        None => message.to_string(),
    }
}

/// The length of a leading `file:line: ` in `message`, if it has one.
fn leading_location(message: &str) -> Option<usize> {
    let (head, _) = message.split_once(": ")?;
    let (_, line) = head.rsplit_once(':')?;
    (!line.is_empty() && line.bytes().all(|b| b.is_ascii_digit())).then_some(head.len() + 2)
}

/// The innermost Lua frame (`file:line`) of a traceback.
fn traceback_frame(tb: &str) -> Option<String> {
    tb.lines().map(str::trim).find_map(|l| {
        let (file, rest) = l.split_once(':')?;
        let (line, _) = rest.split_once(':')?;
        (!file.starts_with('[') && line.bytes().all(|b| b.is_ascii_digit()))
            .then(|| format!("{file}:{line}"))
    })
}

/// Separates the message from a `stack traceback:` that Lua may have appended.
fn split_traceback(s: &str) -> (&str, Option<String>) {
    match s.find("\nstack traceback:") {
        Some(i) => (s[..i].trim_end(), Some(s[i + 1..].to_string())),
        None => (s.trim_end(), None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn traceback_is_split_off() {
        let (m, tb) = split_traceback("a.lua:3: boom\nstack traceback:\n\ta.lua:3: in main chunk");
        assert_eq!(m, "a.lua:3: boom");
        assert_eq!(tb.unwrap(), "stack traceback:\n\ta.lua:3: in main chunk");
        assert_eq!(split_traceback("plain\n"), ("plain", None));
    }

    #[test]
    fn positionless_messages_borrow_the_traceback_frame() {
        let tb = "stack traceback:\n\t[C]: in function 'error'\n\tdir/a.lua:7: in main chunk";
        assert_eq!(
            with_location("table: 0x1", Some(tb)),
            "dir/a.lua:7: table: 0x1"
        );
        assert_eq!(with_location("a.lua:2: x", Some(tb)), "a.lua:2: x");
        assert_eq!(with_location("boom", None), "boom");
        assert_eq!(
            with_location("a.lua:2: a.lua:1: boom", None),
            "a.lua:1: boom"
        );
        assert_eq!(
            with_location("a.lua:3: b.lua:2: a.lua:1: x: y", Some(tb)),
            "a.lua:1: x: y"
        );
    }

    #[test]
    fn config_defaults() {
        let c = ScriptConfig::default();
        assert_eq!(c.transform_order, None);
        assert_eq!(c.instruction_limit, 200_000_000);
        assert_eq!(c.memory_limit, 2 << 30);
        assert_eq!(c.time_limit, Duration::from_secs(15));
    }
}
