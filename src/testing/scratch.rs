//! Scratch folders for tests: a fresh, empty folder under the system temp dir that is
//! removed when its guard drops, so test runs do not pile folders up in /tmp. A test that
//! panics keeps its folder, so a failure's files can still be looked at.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// A fresh, empty folder `glint-{tag}-{process}-{n}` under the system temp dir.
pub fn temp_dir(tag: &str) -> TempDir {
    static N: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "glint-{tag}-{}-{}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("cannot create a scratch folder under the temp dir");
    TempDir(dir)
}

/// A fresh scratch folder ([`temp_dir`]) and the path of a file `name` in it (not yet
/// created): the start of most tests of a reader or a writer.
pub fn temp_file(tag: &str, name: &str) -> (TempDir, PathBuf) {
    let dir = temp_dir(tag);
    let path = dir.join(name);
    (dir, path)
}

/// A test's scratch folder ([`temp_dir`]); derefs to its path, removed on drop unless the
/// thread is panicking.
pub struct TempDir(PathBuf);

impl std::ops::Deref for TempDir {
    type Target = PathBuf;
    fn deref(&self) -> &PathBuf {
        &self.0
    }
}

impl AsRef<Path> for TempDir {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

/// The names of the entries of `dir`, sorted: what a test expects a folder to hold
/// (no temporary file left behind, no image half written).
pub fn file_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("read a scratch folder")
        .map(|e| {
            e.expect("read a folder entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    names.sort();
    names
}

#[cfg(test)]
mod tests {
    use super::temp_dir;

    #[test]
    fn the_folder_is_fresh_and_goes_with_its_guard() {
        let dir = temp_dir("scratch");
        assert!(dir.is_dir() && std::fs::read_dir(&*dir).unwrap().next().is_none());
        std::fs::write(dir.join("file"), b"x").unwrap();
        let path = dir.to_path_buf();
        drop(dir);
        assert!(!path.exists());
    }
}
