//! The `gr` Lua module: runs a CS488 A4 scene script (the language is described in
//! docs/scene-language.md) into a [`SceneGraph`], handing each `gr.render` call to the
//! caller as it happens.
//!
//! Layout: `run` runs a script (`source` reads and checks its text first) under the
//! `config` it is given, in the restricted Lua state `sandbox` builds (`require`,
//! `unpack`, `readobj`), whose `limits` end it once reached and whose memory `budget` the
//! script and its renders share; `errors` turns Lua's errors into [`SceneError`]s. `gr`
//! installs the scene calls: `nodes` and `meshes` make nodes, `render_call` is
//! `gr.render`; `handles` holds the node/material/light userdata and their methods,
//! `methods` the method tables scripts may extend, `args` checks arguments and words the
//! errors, `options` parses the render-options table, `preludes` runs the `--prelude`
//! files before the scene.
//! The script's state lives in Lua's app data ([`State`]) so that the `'static` callbacks
//! mlua requires can reach it; only `gr.render`, which borrows the caller's `on_render`,
//! is a scoped function.

mod advice;
mod args;
mod budget;
mod config;
mod deep_nesting;
mod dot_call;
mod era;
mod errors;
mod gr;
mod handle_types;
mod handles;
mod limits;
mod maps;
mod meshes;
mod methods;
mod nodes;
mod notes;
mod options;
mod preludes;
mod procedural;
mod render_call;
mod run;
mod sandbox;
mod source;
mod unknown;
mod watchdog;
mod wrappers;

pub use budget::LUA_HEAP_FACTOR;
pub use config::{
    FrameGlobals, ScriptConfig, ScriptReport, DEFAULT_MAX_RENDERS, DEFAULT_MAX_RENDER_PIXELS,
    DEFAULT_MEMORY_LIMIT, DEFAULT_TIME_LIMIT,
};
pub use errors::{cap_message, SceneError, MAX_MESSAGE_BYTES};
pub use render_call::{OnRender, MAX_IMAGE_SIDE};
pub use run::{run_scene_file, run_scene_source};
pub use source::{read_scene_bytes, SOURCE_BYTES_PER_BYTE};

use super::files::ReadPolicy;
use super::paths::SceneFolders;
use super::{MeshId, NodeId, SceneGraph, TransformOrder};
use mlua::Lua;
use std::collections::HashMap;
use std::path::PathBuf;

/// Registry key of the `require` cache (also visible as `package.loaded`), which also
/// keeps preludes from running twice.
const LOADED_KEY: &str = "glint.loaded";

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
    /// Mesh files already loaded (by identity: device and inode), so instancing a file
    /// twice, under any spelling of its path, shares the triangles.
    pub mesh_cache: HashMap<crate::folder_walk::FileId, MeshId>,
    /// Image files already loaded (by identity), so materials naming the same file share
    /// its texels.
    pub texture_cache: HashMap<crate::folder_walk::FileId, crate::scene::TextureId>,
    /// The caller's render error, kept whole (Lua can only carry a string of it).
    pub render_error: Option<(String, anyhow::Error)>,
    /// The memory budget ([`ScriptConfig::memory_limit`]).
    pub memory_limit: u64,
    /// Bytes of the budget the scene holds in Rust (see [`budget::charge`]).
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
    pub limits: limits::Limits,
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

/// Runs `f` on the script state. Never call Lua inside `f`: the state is borrowed.
pub(crate) fn with_state<R>(lua: &Lua, f: impl FnOnce(&mut State) -> R) -> R {
    let mut state = lua
        .app_data_mut::<State>()
        .expect("script state is installed before the script runs");
    f(&mut state)
}
