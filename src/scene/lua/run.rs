//! Runs a scene script: sets up the sandboxed state and the `gr` module, runs the
//! preludes and then the scene as a coroutine (so that a memory error's line can still be
//! read), and turns what happened into a [`ScriptReport`] or a [`SceneError`].

use super::config::{FrameGlobals, ScriptConfig, ScriptReport};
use super::errors::{cap_message, convert_error, SceneError};
use super::render_call::OnRender;
use super::source::{read_scene_bytes, source_text};
use super::{budget, deep_nesting, era, gr, handles, limits, methods, notes, preludes};
use super::{render_call, sandbox, watchdog, with_state, wrappers, State};
use crate::scene::files::ReadPolicy;
use crate::scene::paths::SceneFolders;
use crate::scene::SceneGraph;
use mlua::chunk::ChunkMode;
use mlua::Lua;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

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
    let limits = limits::Limits {
        instruction_limit: config.instruction_limit,
        ..limits::Limits::default()
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
            lua.set_memory_limit(budget::lua_share(left) as usize)
                .map(|_| ())
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
            render_call::render(lua, args, &mut *on_render)
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
    limits: &limits::Limits,
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
