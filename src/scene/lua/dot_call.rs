//! A method called with `.` instead of `:` (`root.add_child(s)`): Lua then passes the
//! arguments one place early, so the object is missing and the first argument stands in
//! for it. Lua's debug information tells the two calls apart (a `:` call is named a
//! "method", a `.` call a "field"); the scene's own line gives the call to write instead.

use super::with_state;

/// `; called with '.'? write 'root:add_child(s)' …` when the running method (`func`,
/// `node:add_child`, at `at`: `scene.lua:3`) was called with `.`, else None.
pub(crate) fn hint(lua: &mlua::Lua, func: &str, at: &str) -> Option<String> {
    let called_as = lua.inspect_stack(0, |d| d.names().name_what)?;
    if called_as != Some("field") {
        return None;
    }
    let method = func.rsplit(':').next()?;
    let instead = suggestion(lua, at, method).unwrap_or_else(|| format!("object:{method}(…)"));
    Some(format!(
        "; called with `.`? write `{instead}` (with `:`, Lua passes the object itself as the first argument)"
    ))
}

/// The call at `at` (`scene.lua:7`) rewritten with `:`, read from the scene's line.
fn suggestion(lua: &mlua::Lua, at: &str, method: &str) -> Option<String> {
    let (chunk, line) = at.rsplit_once(':')?;
    let line: usize = line.parse().ok()?;
    let text = with_state(lua, |s| {
        (s.scene_chunk == chunk)
            .then(|| {
                s.scene_source
                    .lines()
                    .nth(line.checked_sub(1)?)
                    .map(str::to_string)
            })
            .flatten()
    })?;
    rewrite(&text, method)
}

/// `object:method(args)` for the first `object.method(args)` on `line`.
fn rewrite(line: &str, method: &str) -> Option<String> {
    let pattern = format!(".{method}(");
    let dot = line.find(&pattern)?;
    let object_start = line[..dot]
        .char_indices()
        .rev()
        .take_while(|&(_, c)| c.is_alphanumeric() || "_.[]'\"".contains(c))
        .last()
        .map(|(i, _)| i)?;
    let object = &line[object_start..dot];
    let open = dot + pattern.len();
    let mut depth = 1;
    let close = line[open..].char_indices().find_map(|(i, c)| {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            _ => {}
        }
        (depth == 0).then_some(open + i)
    });
    let arguments = match close {
        Some(end) => &line[open..end],
        None => "…",
    };
    Some(format!("{object}:{method}({arguments})"))
}

#[cfg(test)]
mod tests {
    use super::rewrite;

    #[test]
    fn a_dot_call_is_rewritten_with_a_colon() {
        assert_eq!(
            rewrite("root.add_child(s)", "add_child").as_deref(),
            Some("root:add_child(s)")
        );
        assert_eq!(
            rewrite("  parts[1].add_child(f(x, y)) -- x", "add_child").as_deref(),
            Some("parts[1]:add_child(f(x, y))")
        );
        assert_eq!(rewrite("root:add_child(s)", "add_child"), None);
    }
}
