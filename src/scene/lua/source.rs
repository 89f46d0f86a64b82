//! Scene and module text before Lua sees it: the scene file read once, within the memory
//! budget, and precompiled chunks refused.

use super::errors::SceneError;
use crate::scene::files::{open_regular, MAX_FILE_BYTES};
use std::path::Path;

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
