//! The `gr` Lua module: runs a CS488 A4 scene script (the language is described in
//! docs/scene-language.md) into a [`SceneGraph`], handing each `gr.render` call to the
//! caller as it happens.
//!
//! Layout: `sandbox` builds the restricted Lua state (limits, `require`, `unpack`,
//! `readobj`), `gr` defines the scene calls, `handles` the node/material/light userdata
//! and their methods, `methods` the method tables scripts may extend, `args` checks
//! arguments and words the errors, `options` parses the render-options table, `preludes`
//! runs the `--prelude` files before the scene.
//! The script's state lives in Lua's app data ([`State`]) so that the `'static` callbacks
//! mlua requires can reach it; only `gr.render`, which borrows the caller's `on_render`,
//! is a scoped function.

mod advice;
mod args;
mod deep_nesting;
mod dot_call;
mod era;
mod gr;
mod handle_types;
mod handles;
mod maps;
mod methods;
mod notes;
mod options;
mod preludes;
mod sandbox;
mod unknown;
mod watchdog;
mod wrappers;

pub use gr::MAX_IMAGE_SIDE;

use super::files::{open_regular, ReadPolicy, MAX_FILE_BYTES};
use super::paths::SceneFolders;
use super::{MeshId, NodeId, RenderRequest, SceneGraph, TransformOrder};
use crate::display_path::shown_text;
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

/// How much of the budget one byte of the Lua heap takes: Lua counts the bytes it asks
/// for, the C allocator adds a header and rounds each block up (a short string of 25
/// bytes takes a 48-byte block), which for Lua's many small objects nearly doubles it.
pub const LUA_HEAP_FACTOR: u64 = 2;

/// Bytes of the budget one element of a growing vector takes: the vector's capacity may
/// be twice its length, and while it grows the old and the new buffer exist together.
pub(crate) const fn grown(bytes: usize) -> u64 {
    3 * bytes as u64
}

/// The Lua heap's own limit when `left` bytes of the budget are free for it.
pub(crate) fn lua_share(left: u64) -> u64 {
    left / LUA_HEAP_FACTOR
}

/// Longest error message kept (the rest is cut, saying how much).
pub const MAX_MESSAGE_BYTES: usize = 4096;

/// `message` cut to [`MAX_MESSAGE_BYTES`] (at a character boundary).
pub fn cap_message(message: &str) -> String {
    if message.len() <= MAX_MESSAGE_BYTES {
        return message.to_string();
    }
    let mut end = MAX_MESSAGE_BYTES;
    while !message.is_char_boundary(end) {
        end -= 1;
    }
    format!("{}… ({} more bytes)", &message[..end], message.len() - end)
}

/// Registry key of the `require` cache (also visible as `package.loaded`), which also
/// keeps preludes from running twice.
const LOADED_KEY: &str = "glint.loaded";

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

/// Runs the scene file at `path`. Meshes and modules resolve against its directory (then
/// the current one, see `scene::paths`).
pub fn run_scene_file(
    path: &Path,
    config: &ScriptConfig,
    on_render: &mut OnRender<'_>,
) -> Result<ScriptReport, SceneError> {
    let bytes = read_scene_bytes(path, config.memory_limit)?;
    let source = String::from_utf8_lossy(&bytes);
    let base_dir = path.parent().unwrap_or(Path::new(""));
    run_scene_source(
        &crate::display_path::shown(path),
        &source,
        base_dir,
        config,
        on_render,
    )
}

/// The scene file's bytes, read once: a regular file (a FIFO or a device is refused
/// without blocking), its size counted against `memory_limit` before it is read (it is
/// held while the script runs, with Lua's compiled copy), and read from the handle
/// whose size was checked (a file that grows meanwhile is refused).
pub fn read_scene_bytes(path: &Path, memory_limit: usize) -> Result<Vec<u8>, SceneError> {
    use std::io::Read;
    let read_error = |message| SceneError::Read {
        path: path.to_path_buf(),
        message,
    };
    let (file, len) = open_regular(path, "scene file", MAX_FILE_BYTES).map_err(read_error)?;
    if len.saturating_mul(SOURCE_BYTES_PER_BYTE) > memory_limit as u64 {
        return Err(read_error(format!(
            "{}: the scene file is {} MiB; running it may take {SOURCE_BYTES_PER_BYTE}× that, over the memory limit of {} MiB; --memory-limit MIB raises it",
            crate::display_path::shown(path),
            len.div_ceil(1 << 20),
            memory_limit >> 20
        )));
    }
    let cannot = |e: std::io::Error| {
        read_error(format!(
            "cannot read scene file '{}': {e}",
            crate::display_path::shown(path)
        ))
    };
    let mut bytes = Vec::new();
    bytes
        .try_reserve_exact(len as usize)
        .map_err(|e| cannot(std::io::Error::other(e)))?;
    file.take(len + 1).read_to_end(&mut bytes).map_err(cannot)?;
    if bytes.len() as u64 > len {
        return Err(read_error(format!(
            "cannot read scene file '{}': it grew while being read",
            crate::display_path::shown(path)
        )));
    }
    Ok(bytes)
}

/// Bytes of the budget one byte of scene or module text may take while it runs: the
/// text, the Lua heap's copy while it is parsed, the compiled chunk.
pub const SOURCE_BYTES_PER_BYTE: u64 = 4;

/// Scene or module text as Lua should see it: a UTF-8 byte-order mark removed, and a
/// precompiled (binary) chunk refused, naming the file.
pub(crate) fn source_text<'s>(chunk_name: &str, source: &'s str) -> Result<&'s str, String> {
    if source.starts_with('\x1b') {
        return Err(format!(
            "{chunk_name}:1: a precompiled (binary) Lua chunk; glint runs Lua source text only"
        ));
    }
    Ok(source.strip_prefix('\u{feff}').unwrap_or(source))
}

/// Gives the script `frame` and `clock` for an animation's frame: looked up through the
/// globals' `__index` (they are not stored), so that reading either is recorded in the
/// report (`--frames` on a script that never reads them makes the same image each frame).
fn set_frame_globals(lua: &Lua, frame: Option<FrameGlobals>) -> mlua::Result<()> {
    let Some(f) = frame else {
        return Ok(());
    };
    let meta = lua.create_table()?;
    meta.set(
        "__index",
        lua.create_function(move |lua, (_, key): (mlua::Value, mlua::Value)| {
            let value = match key.as_string().map(|s| s.to_string_lossy()).as_deref() {
                Some("frame") => mlua::Value::Integer(f.frame),
                Some("clock") => mlua::Value::Number(f.clock),
                _ => return Ok(mlua::Value::Nil),
            };
            with_state(lua, |s| s.report.reads_frame = true);
            Ok(value)
        })?,
    )?;
    lua.globals().set_metatable(Some(meta))?;
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
    let preludes = preludes::read_all(&config.preludes)?;
    let source =
        source_text(chunk_name, source).map_err(|message| SceneError::Syntax { message })?;
    let watchdog = watchdog::Watchdog::start(config.time_limit, config.hard_time_limit, chunk_name);
    let limits = sandbox::Limits {
        instruction_limit: config.instruction_limit,
        ..sandbox::Limits::default()
    };
    let lua =
        sandbox::new_lua(config, &limits, watchdog.clock()).map_err(|e| SceneError::Runtime {
            message: format!("{chunk_name}: cannot set up Lua: {e}"),
            traceback: None,
        })?;
    let readable_preludes = preludes::readable(config, &preludes);
    let state = initial_state(
        (chunk_name, source),
        config,
        base_dir,
        readable_preludes,
        source.len() as u64,
        &limits,
        watchdog.clock(),
    );
    lua.set_app_data(state);
    let setup = gr::install(&lua)
        .and_then(|()| methods::install(&lua, handles::node_methods(), handles::material_methods()))
        .and_then(|()| sandbox::install(&lua))
        .and_then(|()| wrappers::install(&lua))
        .and_then(|()| {
            let left = config.memory_limit.saturating_sub(source.len()) as u64;
            lua.set_memory_limit(lua_share(left) as usize).map(|_| ())
        })
        .and_then(|()| set_frame_globals(&lua, config.frame));
    if let Err(e) = setup {
        return Err(SceneError::Runtime {
            message: format!("{chunk_name}: cannot set up the gr module: {e}"),
            traceback: None,
        });
    }

    let mut memory_at = None;
    let result = lua.scope(|scope| {
        let render = scope.create_function_mut(|lua, args: mlua::MultiValue| {
            gr::render(lua, args, &mut *on_render)
        })?;
        lua.globals()
            .get::<mlua::Table>("gr")?
            .set("render", render)?;
        preludes::run_all(&lua, &preludes)?;
        let main = lua
            .load(source)
            .set_name(format!("@{chunk_name}"))
            .set_mode(ChunkMode::Text)
            .into_function()
            .map_err(|e| {
                deep_nesting::locate(e, source.as_bytes(), chunk_name, config.memory_limit)
            })?;
        run_main(&lua, main, &mut memory_at)
    });

    // The state stays installed until the Lua state is dropped, so nothing Lua might
    // still run while closing can find it missing.
    let (render_error, report) = with_state(&lua, |s| {
        notes::flush(s);
        s.report.looks_pre2015 = s.era.verdict();
        (s.render_error.take(), std::mem::take(&mut s.report))
    });
    // A render failure or a reached limit ends the script even if a `pcall` in the
    // script caught the Lua error and carried on.
    if let Some((location, error)) = render_error {
        return Err(SceneError::Render { location, error });
    }
    if let Some(message) = limits.exceeded.take() {
        return Err(SceneError::Limit {
            message: cap_message(&message),
        });
    }
    if let Some(at) = memory_at {
        limits.last_location.set(Some(at));
    }
    match result {
        Ok(()) => Ok(report),
        Err(e) => Err(convert_error(&e, chunk_name, config, &limits)),
    }
}

/// The script's state before it runs (the scene's chunk name and text): an empty graph, the read policy (the scene's
/// folders, the preludes' and `--allow-read`'s), `charged` bytes already held (the
/// script's text) and the limits' shared record.
fn initial_state(
    (chunk_name, source): (&str, &str),
    config: &ScriptConfig,
    base_dir: &Path,
    prelude_dirs: Vec<PathBuf>,
    charged: u64,
    limits: &sandbox::Limits,
    clock: watchdog::ScriptClock,
) -> State {
    let folders = SceneFolders::new(base_dir);
    State {
        scene_chunk: chunk_name.to_string(),
        scene_source: source.into(),
        era: era::EraEvidence::default(),
        graph: SceneGraph::default(),
        order: config.transform_order.unwrap_or_default(),
        order_fixed: config.transform_order.is_some(),
        read_policy: ReadPolicy::new(base_dir, &[prelude_dirs, folders.readable()].concat()),
        folders,
        report: ScriptReport::default(),
        mesh_cache: HashMap::new(),
        texture_cache: HashMap::new(),
        render_error: None,
        memory_limit: config.memory_limit as u64,
        // The text is held while the script runs.
        charged,
        parents: Vec::new(),
        cycle_search: handles::CycleSearch::default(),
        cycle_check_visits: 0,
        clock,
        module_dirs: HashMap::new(),
        notes: notes::Notes::new(config.ignore_extra_arguments),
        limits: limits.clone(),
        renders_requested: 0,
        pixels_requested: 0,
        max_renders: config.max_renders,
        max_render_pixels: config.max_render_pixels,
    }
}

/// Runs the script's main chunk as a coroutine: when it fails for memory, the dead
/// coroutine keeps its stack, so the line where the allocation failed (in `..`,
/// `string.rep`, `table.concat`, any call) can still be read into `memory_at`. A yield
/// from the main chunk is an error, as it is in plain Lua.
fn run_main(lua: &Lua, main: mlua::Function, memory_at: &mut Option<String>) -> mlua::Result<()> {
    let thread = lua.create_thread(main)?;
    let result = thread.resume::<mlua::MultiValue>(());
    if let Err(e) = &result {
        if matches!(e, mlua::Error::MemoryError(_)) {
            *memory_at = innermost_line(&thread);
        }
    }
    result?;
    if thread.status() == mlua::thread::ThreadStatus::Resumable {
        let at = innermost_line(&thread).unwrap_or_else(|| "?".into());
        return Err(mlua::Error::RuntimeError(format!(
            "{at}: attempt to yield from outside a coroutine"
        )));
    }
    Ok(())
}

/// `file:line` of the innermost Lua frame of a dead coroutine.
fn innermost_line(thread: &mlua::Thread) -> Option<String> {
    use mlua::ffi;
    let state = thread.state();
    for level in 0..64 {
        // SAFETY: `state` is the thread's, alive while `thread` is; lua_getstack and
        // lua_getinfo only read it (a zeroed lua_Debug is how the C API starts one).
        unsafe {
            let mut ar: ffi::lua_Debug = std::mem::zeroed();
            if ffi::lua_getstack(state, level, &mut ar) == 0 {
                return None;
            }
            if ffi::lua_getinfo(state, c"Sl".as_ptr(), &mut ar) == 0 || ar.currentline <= 0 {
                continue;
            }
            let src = std::ffi::CStr::from_ptr(ar.short_src.as_ptr()).to_string_lossy();
            let full = std::ffi::CStr::from_ptr(ar.source).to_bytes();
            let name = match full.strip_prefix(b"@") {
                Some(path) if path.len() < 4096 => String::from_utf8_lossy(path).into_owned(),
                _ => src.into_owned(),
            };
            if name != "glint" {
                return Some(format!("{name}:{}", ar.currentline));
            }
        }
    }
    None
}

/// Everything the callbacks share while a script runs (kept in Lua's app data).
pub(crate) struct State {
    pub graph: SceneGraph,
    /// The scene's chunk name as locations start (`scene.lua` of `scene.lua:7`).
    pub scene_chunk: String,
    /// The scene's text, for advice that quotes a line (`dot_call`).
    pub scene_source: std::sync::Arc<str>,
    /// What tells the pre-2015 course's scenes from later ones (`era`).
    pub era: era::EraEvidence,
    pub order: TransformOrder,
    /// The CLI flag fixed the order: `gr.transform_order` is recorded but has no effect.
    pub order_fixed: bool,
    /// Where the scene's relative paths resolve (`scene::paths`).
    pub folders: SceneFolders,
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
    /// Chunk names (`@path`) of the preludes and the modules they required, with the
    /// folder their own `require` calls look in (the scene's modules look beside it).
    pub module_dirs: HashMap<String, PathBuf>,
    /// Notes on arguments glint does not use, printed at each render and at the end.
    pub notes: notes::Notes,
    /// The limits' shared record: once one is reached, every `gr` call fails.
    pub limits: sandbox::Limits,
    /// `gr.render` calls so far, and the pixels they asked for.
    pub renders_requested: u64,
    pub pixels_requested: u64,
    /// [`ScriptConfig::max_renders`], [`ScriptConfig::max_render_pixels`].
    pub max_renders: u64,
    pub max_render_pixels: u64,
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
    let used = lua_heap(lua);
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
        return Err(reach_limit(a, format!(
            "{what} '{}' is {} MiB; reading it may take up to {factor}× that, over the {} MiB left of the memory limit; --memory-limit MIB raises it",
            crate::display_path::shown(path),
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
    let used = lua_heap(a.lua);
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
        Ok(left) => {
            a.lua
                .set_memory_limit(lua_share(left).try_into().unwrap_or(usize::MAX))?;
            Ok(())
        }
        Err((charged, limit)) => Err(reach_limit(a, format!(
            "{what} ({} MiB) would go over the memory limit of {} MiB (the scene holds {} MiB, Lua {} MiB); --memory-limit MIB raises it",
            bytes.div_ceil(1 << 20),
            limit >> 20,
            charged >> 20,
            used >> 20
        ))),
    }
}

/// Returns bytes charged for something the scene no longer holds (a render's lights).
pub(crate) fn release(lua: &Lua, bytes: u64) {
    let left = with_state(lua, |s| {
        s.charged = s.charged.saturating_sub(bytes);
        s.memory_limit.saturating_sub(s.charged)
    });
    let _ = lua.set_memory_limit(lua_share(left).try_into().unwrap_or(usize::MAX));
}

/// What the Lua heap takes of the budget ([`LUA_HEAP_FACTOR`] per byte Lua counts).
fn lua_heap(lua: &Lua) -> u64 {
    (lua.used_memory() as u64).saturating_mul(LUA_HEAP_FACTOR)
}

/// A limit reached at the call `a` (memory, renders): final, as the hook's limits are.
pub(crate) fn reach_limit(a: &args::Args, message: String) -> mlua::Error {
    let message = match a.error(message) {
        mlua::Error::RuntimeError(m) => m,
        other => other.to_string(),
    };
    sandbox::end_thread(a.lua);
    with_state(a.lua, |s| s.limits.clone()).reach(message)
}

/// Fails once a limit has been reached: every `gr` call checks it first.
pub(crate) fn ensure_live(lua: &Lua) -> mlua::Result<()> {
    match with_state(lua, |s| s.limits.reached()) {
        Some(message) => Err(mlua::Error::RuntimeError(message)),
        None => Ok(()),
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
        // The script's own text (a token, an `error` argument) is escaped: a message
        // stays one line and sends the terminal nothing.
        mlua::Error::SyntaxError { message, .. } => SceneError::Syntax {
            message: shown_text(message),
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
                message: shown_text(&with_location(message, traceback.as_deref())),
                traceback,
            }
        }
        other => {
            let text = other.to_string();
            let (message, tb) = split_traceback(&text);
            SceneError::Runtime {
                message: shown_text(message),
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
    // A position inside glint's own Lua wrappers says nothing to the user: the script's
    // frame in the traceback does.
    let message = match message.strip_prefix("glint:") {
        Some(rest) if leading_location(message).is_some() => {
            rest.split_once(": ").map_or(message, |(_, m)| m)
        }
        _ => message,
    };
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
        // glint's own Lua wrappers (chunk `=glint`) are not the script's place.
        (!file.starts_with('[') && file != "glint" && line.bytes().all(|b| b.is_ascii_digit()))
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
