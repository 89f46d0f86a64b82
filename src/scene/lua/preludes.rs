//! Preludes (`--prelude FILE`, repeatable): Lua files run before the scene, in the same
//! state, sandbox and limits, so that a scene written for another CS488 tracer can have
//! its calls mapped onto glint's in Lua the user can read (`scenes/dialects/`).
//!
//! A prelude's folder is readable (its own modules and assets). Its `require` calls look
//! for modules beside it (a folder of preludes can share helpers), not beside the scene,
//! and what it loads is cached by identity (device and inode), so a file given twice, or given and
//! also required by another prelude, runs once. Each prelude receives its path and its
//! folder (canonical and absolute where the system can give it) as `...`. Errors inside a
//! prelude name its file and line.

use super::config::ScriptConfig;
use super::errors::SceneError;
use super::with_state;
use crate::folder_walk::{self, FileId};
use crate::scene::files::{read_regular, MAX_FILE_BYTES};
use mlua::chunk::ChunkMode;
use mlua::{Lua, Table, Value};
use std::path::{Path, PathBuf};

/// A prelude read before the script starts.
pub(super) struct Prelude {
    /// As given (messages name it so).
    path: PathBuf,
    /// Its identity: the key that keeps it from running twice (as the modules of
    /// preludes are keyed).
    key: String,
    /// Its folder (canonical where the system can give one): readable, and where its
    /// `require` looks.
    folder: PathBuf,
    source: Vec<u8>,
}

/// Reads every prelude (a missing or unreadable one fails before anything runs).
pub(super) fn read_all(paths: &[PathBuf]) -> Result<Vec<Prelude>, SceneError> {
    paths
        .iter()
        .map(|path| {
            let fail = |message: String| SceneError::Read {
                path: path.clone(),
                message,
            };
            let source = read_regular(path, "prelude", MAX_FILE_BYTES).map_err(fail)?;
            // Canonical where the system can give it; else (a folder past PATH_MAX) as
            // given, which the rules judge by the folder itself.
            let folder = match path.canonicalize() {
                Ok(canonical) if canonical.is_file() => canonical.parent().map(Path::to_path_buf),
                _ => path.parent().map(Path::to_path_buf),
            };
            let folder = folder
                .filter(|f| !f.as_os_str().is_empty())
                .unwrap_or_else(|| PathBuf::from("."));
            let key = crate::folder_walk::FileId::of_path(path)
                .map_err(|e| {
                    fail(format!(
                        "cannot read prelude '{}': {e}",
                        crate::display_path::shown(path)
                    ))
                })?
                .key();
            Ok(Prelude {
                path: path.clone(),
                key,
                folder,
                source,
            })
        })
        .collect()
}

/// The folders the scene may read besides its own: `--allow-read` and the preludes'
/// that are not too wide ([`too_wide`]: such a prelude reads its own folder, for its
/// modules, but the scene gains nothing from it).
pub(super) fn readable(config: &ScriptConfig, preludes: &[Prelude]) -> Vec<PathBuf> {
    let home = std::env::var_os("HOME").map(PathBuf::from);
    let mut folders = config.allow_read.clone();
    folders.extend(
        preludes
            .iter()
            .filter(|p| !too_wide(&p.folder, Path::new("."), home.as_deref()))
            .map(|p| p.folder.clone()),
    );
    folders
}

/// Whether a prelude's `folder` would open too much to a scene: the filesystem's root,
/// the home folder `home` or a folder above it, or a folder above the start folder
/// `start` (the rule the start folder follows: `--prelude ~/dialect.lua` must not make
/// every file of the user readable to a downloaded scene). Judged by the folders'
/// identities ([`folder_walk::lies_within`]), not their absolute paths.
fn too_wide(folder: &Path, start: &Path, home: Option<&Path>) -> bool {
    let id = |p: &Path| FileId::of_folder(p).ok();
    let Some(folder_id) = id(folder) else {
        return false; // Not a folder: nothing under it is readable anyway.
    };
    let root = id(Path::new("/"));
    let holds = |inner: &Path| {
        folder_walk::open_folder(inner).is_ok_and(|fd| folder_walk::lies_within(&fd, &[folder_id]))
    };
    let start_id = id(start);
    Some(folder_id) == root
        || home.is_some_and(holds)
        || (holds(start) && start_id != Some(folder_id))
}

/// Runs the preludes in order (each at most once), before the scene.
pub(super) fn run_all(lua: &Lua, preludes: &[Prelude]) -> mlua::Result<()> {
    let loaded: Table = lua.named_registry_value(super::LOADED_KEY)?;
    for prelude in preludes {
        let key = prelude.key.as_str();
        if !loaded.raw_get::<Value>(key)?.is_nil() {
            continue;
        }
        let shown = crate::display_path::shown(&prelude.path);
        let chunk = format!("@{shown}");
        with_state(lua, |s| {
            s.module_dirs.insert(chunk.clone(), prelude.folder.clone());
        });
        // Nesting past Lua's parser is said at the prelude's own file and line.
        let left = super::budget::memory_left(lua) as usize;
        lua.load(&prelude.source[..])
            .set_name(chunk)
            .set_mode(ChunkMode::Text)
            .into_function()
            .map_err(|e| super::deep_nesting::locate(e, &prelude.source, &shown, left))?
            .call::<()>((
                prelude.path.to_string_lossy().into_owned(),
                prelude.folder.to_string_lossy().into_owned(),
            ))?;
        loaded.raw_set(key, true)?;
    }
    Ok(())
}

/// The folder a `require` called now looks in when its caller is a prelude or one of
/// its modules (None: the scene's folder, as for the scene's own `require`).
pub(super) fn caller_module_dir(lua: &Lua) -> Option<PathBuf> {
    let source = (0..64)
        .map_while(|level| lua.inspect_stack(level, |d| d.source().source.map(|s| s.into_owned())))
        .flatten()
        .find(|s| s.starts_with('@'))?;
    with_state(lua, |s| s.module_dirs.get(&source).cloned())
}

/// Records that the module loaded as chunk `chunk` belongs to the prelude folder `dir`,
/// so that its own `require` calls look there too.
pub(super) fn adopt_module(lua: &Lua, chunk: &str, dir: &Path) {
    with_state(lua, |s| {
        s.module_dirs.insert(chunk.to_string(), dir.to_path_buf());
    });
}

#[cfg(test)]
mod tests {
    use super::too_wide;
    use crate::testing::scratch::temp_dir as glint_scratch;
    use std::path::Path;

    #[test]
    fn root_home_and_folders_above_the_start_are_too_wide_for_a_scene() {
        let dir = glint_scratch("preludes-wide");
        let (h, me) = (dir.join("h"), dir.join("h/me"));
        let (a4, srv, srv_a4) = (me.join("a4"), dir.join("srv"), dir.join("srv/a4"));
        let (dialects, inner) = (me.join("dialects"), me.join("a4/dialects"));
        for d in [&a4, &srv_a4, &dialects, &inner] {
            std::fs::create_dir_all(d).unwrap();
        }
        let home = Some(me.as_path());
        assert!(too_wide(Path::new("/"), &a4, home), "root");
        assert!(too_wide(&me, &a4, home), "home");
        assert!(too_wide(&h, &a4, home), "above home");
        assert!(too_wide(&srv, &srv_a4, home), "above start");
        assert!(!too_wide(&a4, &a4, home), "the start folder");
        assert!(!too_wide(&dialects, &a4, home));
        assert!(!too_wide(&inner, &a4, home));
    }
}
