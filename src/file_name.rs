//! Names glint derives from a name it was given (`out-tile-3-of-8.png`, `out-2.png`,
//! `out-cpu.png`, `demo-view-0001.png`): built from the given name's bytes, so that a
//! name that is not UTF-8 keeps its bytes (`f\xff.png` → `f\xff-2.png`) instead of being
//! mangled into another name (`f\u{FFFD}-2.png`, a file nobody asked for).

use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// `path` with `suffix` put before its extension (`out.png` + `-0001` → `out-0001.png`;
/// no extension: at the end).
pub fn with_suffix(path: &Path, suffix: &str) -> PathBuf {
    let mut name = OsString::from(path.file_stem().unwrap_or_default());
    name.push(suffix);
    if let Some(ext) = path.extension() {
        name.push(".");
        name.push(ext);
    }
    path.with_file_name(name)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::OsStr;
    use std::os::unix::ffi::OsStrExt;

    #[test]
    fn the_suffix_goes_before_the_extension_and_bytes_are_kept() {
        assert_eq!(
            with_suffix(Path::new("dir/out.png"), "-0007"),
            PathBuf::from("dir/out-0007.png")
        );
        assert_eq!(with_suffix(Path::new("x"), "-1"), PathBuf::from("x-1"));
        let raw = Path::new(OsStr::from_bytes(b"d/f\xffx.\xfeexr"));
        assert_eq!(
            with_suffix(raw, "-tile-0-of-2").as_os_str().as_bytes(),
            b"d/f\xffx-tile-0-of-2.\xfeexr"
        );
    }
}
