//! The `gr` Lua module: runs a CS488 A4 scene script (the language is described in the
//! README) into a [`SceneGraph`], handing each `gr.render` call to the caller as it happens.
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
mod handles;
mod maps;
mod options;
mod sandbox;

use super::{MeshId, RenderRequest, SceneGraph, TransformOrder};
use mlua::chunk::ChunkMode;
use mlua::Lua;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// How to run a script. The defaults suit the command line.
#[derive(Clone, Debug)]
pub struct ScriptConfig {
    /// Transform order forced by the CLI flag; it beats `gr.transform_order` in the script.
    pub transform_order: Option<TransformOrder>,
    /// Lua VM instructions a script may execute before it is stopped as a runaway.
    pub instruction_limit: u64,
    /// Bytes the Lua heap may grow to (meshes built in Rust do not count).
    pub memory_limit: usize,
}

impl Default for ScriptConfig {
    fn default() -> Self {
        ScriptConfig {
            transform_order: None,
            instruction_limit: 200_000_000,
            memory_limit: 1 << 30,
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
    /// The scene file itself could not be read.
    #[error("cannot read scene file '{}': {source}", path.display())]
    Read {
        path: PathBuf,
        source: std::io::Error,
    },
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
    /// The instruction or memory limit was reached.
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
    let bytes = std::fs::read(path).map_err(|source| SceneError::Read {
        path: path.to_path_buf(),
        source,
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

/// Runs scene source text named `chunk_name` (used in messages as `chunk_name:line:`),
/// resolving meshes and modules against `base_dir`.
pub fn run_scene_source(
    chunk_name: &str,
    source: &str,
    base_dir: &Path,
    config: &ScriptConfig,
    on_render: &mut OnRender<'_>,
) -> Result<ScriptReport, SceneError> {
    let limits = sandbox::Limits::default();
    let lua = sandbox::new_lua(config, &limits).map_err(|e| SceneError::Runtime {
        message: format!("{chunk_name}: cannot set up Lua: {e}"),
        traceback: None,
    })?;
    lua.set_app_data(State {
        graph: SceneGraph::default(),
        order: config.transform_order.unwrap_or_default(),
        order_fixed: config.transform_order.is_some(),
        base_dir: base_dir.to_path_buf(),
        report: ScriptReport::default(),
        mesh_cache: HashMap::new(),
        texture_cache: HashMap::new(),
        render_error: None,
    });
    let setup = gr::install(&lua).and_then(|()| sandbox::install(&lua));
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

    let mut state = lua
        .remove_app_data::<State>()
        .expect("the script state outlives the script");
    // A render failure or a reached limit ends the script even if a `pcall` in the
    // script caught the Lua error and carried on.
    if let Some((location, error)) = state.render_error.take() {
        return Err(SceneError::Render { location, error });
    }
    if let Some(message) = limits.instructions_exceeded.take() {
        return Err(SceneError::Limit { message });
    }
    match result {
        Ok(()) => Ok(state.report),
        Err(e) => Err(convert_error(&e, chunk_name, config)),
    }
}

/// Everything the callbacks share while a script runs (kept in Lua's app data).
pub(crate) struct State {
    pub graph: SceneGraph,
    pub order: TransformOrder,
    /// The CLI flag fixed the order: `gr.transform_order` is recorded but has no effect.
    pub order_fixed: bool,
    pub base_dir: PathBuf,
    pub report: ScriptReport,
    /// Mesh files already loaded, so instancing a file twice shares the triangles.
    pub mesh_cache: HashMap<PathBuf, MeshId>,
    /// Image files already loaded, so materials naming the same file share its texels.
    pub texture_cache: HashMap<PathBuf, crate::scene::TextureId>,
    /// The caller's render error, kept whole (Lua can only carry a string of it).
    pub render_error: Option<(String, anyhow::Error)>,
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
fn convert_error(e: &mlua::Error, chunk_name: &str, config: &ScriptConfig) -> SceneError {
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
        mlua::Error::MemoryError(_) => SceneError::Limit {
            message: format!(
                "{chunk_name}: the script used more than the memory limit of {} MiB",
                config.memory_limit >> 20
            ),
        },
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
fn with_location(message: &str, traceback: Option<&str>) -> String {
    let located = message.split(": ").next().is_some_and(|head| {
        head.rsplit_once(':')
            .is_some_and(|(_, line)| !line.is_empty() && line.bytes().all(|b| b.is_ascii_digit()))
    });
    if located {
        return message.to_string();
    }
    let frame = traceback.and_then(|tb| {
        tb.lines().map(str::trim).find_map(|l| {
            let (file, rest) = l.split_once(':')?;
            let (line, _) = rest.split_once(':')?;
            (!file.starts_with('[') && line.bytes().all(|b| b.is_ascii_digit()))
                .then(|| format!("{file}:{line}"))
        })
    });
    match frame {
        Some(at) => format!("{at}: {message}"),
        None => message.to_string(),
    }
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
    }

    #[test]
    fn config_defaults() {
        let c = ScriptConfig::default();
        assert_eq!(c.transform_order, None);
        assert_eq!(c.instruction_limit, 200_000_000);
        assert_eq!(c.memory_limit, 1 << 30);
    }
}
