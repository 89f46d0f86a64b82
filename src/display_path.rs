//! Paths as glint prints them: a file name may hold any byte but `/` and NUL, so a name
//! printed as it is could end a line and forge a status line of its own, or carry a
//! terminal's escape sequences (colours, a moved cursor, a retitled window). Printed
//! paths escape control characters and bytes that are not UTF-8 instead; and a path
//! longer than [`MAX_SHOWN_CHARS`] keeps its start and its end (the file's name) with
//! what was left out said in between, so that a message naming it still has room, under
//! the message cap, for the reason that follows it.

use std::os::unix::ffi::OsStrExt;
use std::path::Path;

/// Longest path, in characters, that a message shows whole.
pub const MAX_SHOWN_CHARS: usize = 1024;

/// `path` for a message: printable characters as they are; control characters (C0, DEL,
/// C1) as `\n`, `\t`, `\r` or `\u{1b}`; each byte that is not UTF-8 as `\xNN`; over
/// [`MAX_SHOWN_CHARS`], its first 256 and last 512 characters.
pub fn shown(path: &Path) -> String {
    let escaped = escaped(path);
    let count = escaped.chars().count();
    if count <= MAX_SHOWN_CHARS {
        return escaped;
    }
    let head: String = escaped.chars().take(256).collect();
    let tail: String = escaped.chars().skip(count - 512).collect();
    format!("{head}…({} characters left out)…{tail}", count - 768)
}

fn escaped(path: &Path) -> String {
    let mut out = String::new();
    for chunk in path.as_os_str().as_bytes().utf8_chunks() {
        for c in chunk.valid().chars() {
            push_escaped(&mut out, c);
        }
        for b in chunk.invalid() {
            out.push_str(&format!("\\x{b:02x}"));
        }
    }
    out
}

/// `c` as a message shows it: a control character (C0, DEL, C1) escaped.
fn push_escaped(out: &mut String, c: char) {
    match c {
        '\n' => out.push_str("\\n"),
        '\t' => out.push_str("\\t"),
        '\r' => out.push_str("\\r"),
        c if c.is_control() => out.push_str(&c.escape_unicode().to_string()),
        c => out.push(c),
    }
}

/// A string a script or a user gave (a node's name, an axis, a module's name, a Lua
/// error's text) for a message: control characters escaped as [`shown`] escapes them,
/// so that it stays on its line and sends the terminal nothing.
pub fn shown_text(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        push_escaped(&mut out, c);
    }
    out
}

/// A whole message as glint prints it (`glint: error: …`, notes, the view's lines): the
/// last guard before the terminal. Every control character is escaped but the line
/// breaks and tabs of glint's own multi-line messages (a shader compiler's diagnostic, a table);
/// paths and user strings inside it were escaped whole, line breaks too, by [`shown`]
/// and [`shown_text`] where the message was made.
pub fn for_terminal(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    for c in message.chars() {
        match c {
            '\n' | '\t' => out.push(c),
            c => push_escaped(&mut out, c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::OsStr;

    #[test]
    fn control_characters_and_stray_bytes_are_escaped() {
        let name = OsStr::from_bytes(b"a\nglint: wrote x.png\x1b[31m\xff\xc3\xa9.png");
        assert_eq!(
            shown(Path::new(name)),
            "a\\nglint: wrote x.png\\u{1b}[31m\\xffé.png"
        );
        assert_eq!(shown(Path::new("plain/ok.png")), "plain/ok.png");
        let long = format!("{}scene.lua", "d/".repeat(3000));
        let short = shown(Path::new(&long));
        assert!(
            short.len() < MAX_SHOWN_CHARS && short.ends_with("d/d/scene.lua"),
            "{short}"
        );
        assert!(short.contains("(5241 characters left out)"), "{short}");
    }

    #[test]
    fn user_strings_and_whole_messages_are_escaped_for_the_terminal() {
        assert_eq!(
            shown_text("n\nglint: x\u{1b}[31m"),
            "n\\nglint: x\\u{1b}[31m"
        );
        assert_eq!(shown_text("plain name"), "plain name");
        // A message keeps its own line breaks; every other control character goes.
        assert_eq!(
            for_terminal("a\u{1b}]0;title\u{7}\r\n  next\tline"),
            "a\\u{1b}]0;title\\u{7}\\r\n  next\tline"
        );
    }
}
