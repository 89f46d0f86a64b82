//! Scripts that nest deeper than Lua's parser can follow (about 200 levels of brackets,
//! calls or right-associative operators: `((((…))))`, `{{{{…}}}}`, `1 .. 1 .. 1 …`):
//! Lua reports a bare "C stack overflow", with neither file nor line, because its parser
//! raises the error from C. The line is found again by compiling prefixes of the
//! script (only on this error, and only compiling: nothing runs).

use mlua::chunk::ChunkMode;
use mlua::{Lua, LuaOptions, StdLib};

/// `error` as it should be said: a "C stack overflow" from compiling `source` becomes a
/// syntax error naming `chunk_name` and the line where the nesting ran out; any other
/// error is returned as it is.
pub(super) fn locate(
    error: mlua::Error,
    source: &[u8],
    chunk_name: &str,
    memory_limit: usize,
) -> mlua::Error {
    if !is_stack_overflow(&error) {
        return error;
    }
    let line =
        overflow_line(source, memory_limit).map_or_else(String::new, |line| format!("{line}:"));
    mlua::Error::SyntaxError {
        message: format!(
            "{chunk_name}:{line} the script nests too deeply for Lua's parser (C stack overflow: about 200 levels of brackets, calls or operators)"
        ),
        incomplete_input: false,
    }
}

fn is_stack_overflow(error: &mlua::Error) -> bool {
    error.to_string().contains("C stack overflow")
}

/// The first line (1-based) whose prefix of `source` already overflows the parser: a
/// prefix that does implies every longer one does, so a binary search over the lines
/// finds it in about log₂(lines) compiles.
fn overflow_line(source: &[u8], memory_limit: usize) -> Option<usize> {
    let ends: Vec<usize> = source
        .iter()
        .enumerate()
        .filter(|(_, b)| **b == b'\n')
        .map(|(i, _)| i)
        .chain([source.len()])
        .collect();
    let overflows = |line: usize| {
        let lua = Lua::new_with(StdLib::NONE, LuaOptions::default()).ok()?;
        lua.set_memory_limit(memory_limit).ok()?;
        let compiled = lua
            .load(&source[..ends[line]])
            .set_mode(ChunkMode::Text)
            .into_function();
        Some(compiled.is_err_and(|e| is_stack_overflow(&e)))
    };
    if overflows(ends.len() - 1) != Some(true) {
        return None;
    }
    let (mut low, mut high) = (0, ends.len() - 1);
    while low < high {
        let mid = (low + high) / 2;
        if overflows(mid)? {
            high = mid;
        } else {
            low = mid + 1;
        }
    }
    Some(low + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_that_nests_too_deeply_is_found() {
        let deep = format!(
            "x = 1\ny = 2\nz = {}1{}\nw = 3\n",
            "(".repeat(300),
            ")".repeat(300)
        );
        let lua = Lua::new();
        let e = lua.load(deep.as_str()).into_function().unwrap_err();
        assert!(is_stack_overflow(&e), "{e}");
        let located = locate(e, deep.as_bytes(), "scene.lua", 1 << 30).to_string();
        assert!(
            located.contains("scene.lua:3: the script nests too deeply"),
            "{located}"
        );
        let flat = mlua::Error::RuntimeError("boom".into());
        assert_eq!(
            locate(flat, b"", "scene.lua", 1 << 30).to_string(),
            "runtime error: boom"
        );
    }
}
