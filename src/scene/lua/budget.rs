//! The memory budget a script and its renders share: the Lua heap plus what the scene
//! holds in Rust plus what a render will build, each counted before it is made. Charging
//! shrinks the Lua heap's own limit by the same amount, so both draw on one budget.

use super::args::Args;
use super::limits::reach_limit;
use super::with_state;
use crate::scene::files::Opened;
use mlua::Lua;

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
    a: &Args,
    file: &Opened,
    factor: u64,
    what: &str,
) -> mlua::Result<()> {
    let left = memory_left(a.lua);
    if file.len.saturating_mul(factor) > left {
        return Err(reach_limit(a, format!(
            "{what} '{}' is {} MiB; reading it may take up to {factor}× that, over the {} MiB left of the memory limit; --memory-limit MIB raises it",
            crate::display_path::shown(&file.path),
            file.len.div_ceil(1 << 20),
            left >> 20
        )));
    }
    Ok(())
}

/// Counts `bytes` the scene is about to hold in Rust against the memory budget (with
/// what the Lua heap holds now), or fails with a message naming the call's line. The Lua
/// heap's own limit shrinks by the same amount, so both draw on one budget.
pub(crate) fn charge(a: &Args, bytes: u64, what: &str) -> mlua::Result<()> {
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
