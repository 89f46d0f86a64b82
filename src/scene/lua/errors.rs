//! How a script fails ([`SceneError`]): mlua's errors unwrapped to the message written
//! where the error arose, with the `file:line` Lua knows or the traceback's innermost
//! frame, and messages cut to a bounded length.

use super::config::ScriptConfig;
use super::limits::Limits;
use std::path::PathBuf;

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

/// Turns an mlua error into a [`SceneError`], unwrapping the callback layers mlua adds so
/// that the message is the one written where the error arose.
pub(super) fn convert_error(
    e: &mlua::Error,
    chunk_name: &str,
    config: &ScriptConfig,
    limits: &Limits,
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
            message: crate::display_path::shown_text(message),
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
                message: crate::display_path::shown_text(&with_location(
                    message,
                    traceback.as_deref(),
                )),
                traceback,
            }
        }
        other => {
            let text = other.to_string();
            let (message, tb) = split_traceback(&text);
            SceneError::Runtime {
                message: crate::display_path::shown_text(message),
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
}
