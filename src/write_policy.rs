//! Where a scene may write: the rule for the image names a script gives `gr.render`.
//!
//! Reads are confined to the scene's folder (`scene::files`); writes are confined the
//! same way. A script-named output must be a relative path that stays, after `..` and
//! symbolic links are resolved, under the output folder (the current folder, or
//! `--output-dir DIR`) or a folder given by `--allow-write DIR`; and it may replace only
//! a regular, writable image file (PNG or EXR by content), never a link, a device, a
//! read-only file or a file of another kind. An output given on the command line (`-o`)
//! is the user's choice and is not checked here. Names are walked from opened folder
//! handles ([`crate::folder_walk`]), never resolved to absolute paths, so an output
//! folder deeper than PATH_MAX is judged as any other.

use crate::folder_walk::{self, Root};
use std::ffi::OsStr;
use std::io::Read;
use std::os::fd::OwnedFd;
use std::path::{Component, Path, PathBuf};

/// The first bytes of the image files glint writes (PNG, OpenEXR): only such a file may
/// be replaced by a script-named output.
const IMAGE_MAGICS: [&[u8]; 2] = [b"\x89PNG\r\n\x1a\n", b"\x76\x2f\x31\x01"];

/// The folders script-named outputs may go to, each as its identity (device and inode):
/// an output is judged by walking its name from opened folder handles
/// ([`crate::folder_walk`]), never by its absolute spelling, so an output folder deeper
/// than PATH_MAX is written as any other.
#[derive(Clone, Debug)]
pub struct WritePolicy {
    /// The folder relative names are taken from (`--output-dir`, else the current one),
    /// as the user gave it (for the names printed).
    base: PathBuf,
    /// Folders an output may lie under: the base, then `--allow-write`'s.
    roots: Vec<Root>,
}

impl WritePolicy {
    /// The rule for `output_dir` (None: the current folder) and the `allow_write`
    /// folders; a folder that cannot be opened is an error naming it.
    pub fn new(output_dir: Option<&Path>, allow_write: &[PathBuf]) -> Result<WritePolicy, String> {
        let base = output_dir.map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        let mut roots = Vec::new();
        for dir in std::iter::once(&base).chain(allow_write) {
            let root = Root::open(dir).map_err(|e| {
                let why = match e.raw_os_error() {
                    Some(libc::ENOTDIR) => "not a folder".to_string(),
                    _ => e.to_string(),
                };
                format!(
                    "cannot write under '{}': {why}",
                    crate::display_path::shown(dir)
                )
            })?;
            roots.push(root);
        }
        Ok(WritePolicy { base, roots })
    }

    /// The path to write for the script-named output `name`, or why the script may not
    /// write it (the message names `name` and the flags that widen the rule).
    pub fn place(&self, name: &Path) -> Result<PathBuf, String> {
        let refuse =
            |why: &str| format!("cannot write '{}': {why}", crate::display_path::shown(name));
        if name.as_os_str().is_empty() || name.file_name().is_none() {
            return Err(refuse("not a file name"));
        }
        if name
            .components()
            .any(|c| matches!(c, Component::RootDir | Component::Prefix(_)))
        {
            return Err(refuse(
                "a scene's output name must be relative (to the current folder, or --output-dir DIR); -o FILE on the command line writes anywhere",
            ));
        }
        let path = self.base.join(name);
        // The last name is kept as written: a link there is refused, not followed.
        let walked = folder_walk::walk(&path, false).map_err(|e| refuse(&e.to_string()))?;
        // The folder the output goes in: the walk's, or, where the name is an existing
        // folder, the one above it.
        let within = match walked.rest.is_empty() {
            false => folder_walk::lies_within(&walked.folder, &Root::ids(&self.roots)),
            true => folder_walk::open_parent(&walked.folder)
                .is_ok_and(|up| folder_walk::lies_within(&up, &Root::ids(&self.roots))),
        };
        if !within {
            let roots: Vec<String> = self
                .roots
                .iter()
                .map(|r| crate::display_path::shown(&r.shown))
                .collect();
            return Err(refuse(&format!(
                "it is outside the folders this scene may write ({}); --output-dir DIR or --allow-write DIR allows another folder, -o FILE names the output",
                roots.join(", ")
            )));
        }
        if walked.rest.is_empty() {
            return Err(refuse("it exists and is not a regular file"));
        }
        if let Some(leaf) = walked.leaf() {
            check_replaceable(&walked.folder, leaf).map_err(|why| refuse(&why))?;
        }
        Ok(if self.base == Path::new(".") {
            name.to_path_buf()
        } else {
            path
        })
    }
}

/// Whether the existing entry `name` in `folder` may be replaced: a regular file (not a
/// link), writable by its mode and by this process, that holds a PNG or EXR image.
fn check_replaceable(folder: &OwnedFd, name: &OsStr) -> Result<(), String> {
    let st = folder_walk::stat_in(folder, name)
        .map_err(|e| format!("it exists and cannot be examined: {e}"))?;
    match st.st_mode & libc::S_IFMT {
        libc::S_IFLNK => {
            return Err("it is a symbolic link; a scene replaces only image files".into())
        }
        libc::S_IFREG => {}
        _ => return Err("it exists and is not a regular file".into()),
    }
    if st.st_mode & 0o222 == 0 || !folder_walk::writable_in(folder, name) {
        return Err("it exists and is read-only".into());
    }
    let mut head = [0u8; 8];
    // Opened as every reader opens (never blocking: the file may have been replaced by
    // a FIFO since it was looked at; a link swapped in is not followed).
    let (mut file, _) =
        crate::scene::files::open_checked_in(folder, name, u64::MAX).map_err(|r| match r {
            crate::scene::files::Refusal::Io(e) => format!("it exists and cannot be examined: {e}"),
            _ => "it exists and is not a regular file".to_string(),
        })?;
    let n = file
        .read(&mut head)
        .map_err(|e| format!("it exists and cannot be examined: {e}"))?;
    if !IMAGE_MAGICS.iter().any(|m| head[..n].starts_with(m)) {
        return Err(
            "it exists and is not a PNG or EXR image; a scene replaces only image files".into(),
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_must_stay_under_the_roots() {
        let dir = crate::testing::scratch::temp_dir("write-policy");
        std::fs::create_dir_all(dir.join("out/sub")).unwrap();
        std::fs::create_dir_all(dir.join("other")).unwrap();
        let policy = WritePolicy::new(Some(&dir.join("out")), &[]).unwrap();
        assert!(policy.place(Path::new("a.png")).is_ok());
        assert!(policy.place(Path::new("sub/../a.png")).is_ok());
        for bad in ["../a.png", "/tmp/a.png", "sub/../../other/a.png", ""] {
            assert!(policy.place(Path::new(bad)).is_err(), "{bad}");
        }
        std::os::unix::fs::symlink(dir.join("other"), dir.join("out/link")).unwrap();
        let e = policy.place(Path::new("link/a.png")).unwrap_err();
        assert!(e.contains("--allow-write"), "{e}");
        let wide = WritePolicy::new(Some(&dir.join("out")), &[dir.join("other")]).unwrap();
        assert!(wide.place(Path::new("link/a.png")).is_ok());
        assert!(wide.place(Path::new("../other/a.png")).is_ok());
    }

    #[test]
    fn only_writable_image_files_are_replaced() {
        use std::os::unix::fs::PermissionsExt;
        let dir = crate::testing::scratch::temp_dir("write-policy-replace");
        let policy = WritePolicy::new(Some(&dir), &[]).unwrap();
        std::fs::write(dir.join("text.png"), b"not an image").unwrap();
        std::fs::write(dir.join("old.png"), IMAGE_MAGICS[0]).unwrap();
        std::fs::write(dir.join("ro.png"), IMAGE_MAGICS[0]).unwrap();
        std::fs::set_permissions(dir.join("ro.png"), std::fs::Permissions::from_mode(0o444))
            .unwrap();
        std::os::unix::fs::symlink(dir.join("old.png"), dir.join("link.png")).unwrap();
        std::fs::create_dir(dir.join("dir.png")).unwrap();
        assert!(policy.place(Path::new("old.png")).is_ok());
        for bad in ["text.png", "ro.png", "link.png", "dir.png"] {
            assert!(policy.place(Path::new(bad)).is_err(), "{bad}");
        }
    }
}
