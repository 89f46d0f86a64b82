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
            match c {
                '\n' => out.push_str("\\n"),
                '\t' => out.push_str("\\t"),
                '\r' => out.push_str("\\r"),
                c if c.is_control() => out.push_str(&c.escape_unicode().to_string()),
                c => out.push(c),
            }
        }
        for b in chunk.invalid() {
            out.push_str(&format!("\\x{b:02x}"));
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
}
