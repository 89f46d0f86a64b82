//! Live reload's watcher: a thread that looks at every file the last script run read
//! (the script, preludes, required modules, meshes, textures; ones it looked for and did
//! not find too) every [`POLL_INTERVAL`], and wakes the event loop when one's
//! modification time, size or existence changes.
//!
//! Polling rather than the `notify` crate: a scene reads a handful of files, so a stat
//! of each five times a second costs nothing; it sees the rename-over-the-original
//! saves of most editors (an inotify watch stays on the replaced inode), works on
//! every file system (network mounts, containers' bind mounts), and adds no dependency.
//! The event loop still sleeps (`ControlFlow::Wait`) until something changed.

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::{Duration, SystemTime};

/// How often the watched files are looked at.
pub const POLL_INTERVAL: Duration = Duration::from_millis(200);

/// What is compared: modification time, size and which file it is (device and inode:
/// a symbolic link re-pointed at another file of the same time and size is a change),
/// or None for a missing file.
type Stamp = Option<(SystemTime, u64, u64, u64)>;

fn stamp(path: &PathBuf) -> Stamp {
    use std::os::unix::fs::MetadataExt;
    let meta = std::fs::metadata(path).ok()?;
    Some((meta.modified().ok()?, meta.len(), meta.dev(), meta.ino()))
}

/// The watched files, shared with the watcher thread.
#[derive(Clone, Default)]
pub struct WatchList {
    files: Arc<Mutex<Vec<(PathBuf, Stamp)>>>,
}

impl WatchList {
    /// Watches `files` from their state now on (called after each script run).
    pub fn set(&self, files: &[PathBuf]) {
        let stamped = files.iter().map(|f| (f.clone(), stamp(f))).collect();
        if let Ok(mut list) = self.files.lock() {
            *list = stamped;
        }
    }

    /// Adds `files` to those watched (a failed run keeps watching the last good run's
    /// files and adds what it read).
    pub fn add(&self, files: &[PathBuf]) {
        if let Ok(mut list) = self.files.lock() {
            for f in files {
                if !list.iter().any(|(p, _)| p == f) {
                    list.push((f.clone(), stamp(f)));
                }
            }
        }
    }

    /// Whether any watched file changed since it was stamped (restamping those).
    pub fn changed(&self) -> bool {
        let Ok(mut list) = self.files.lock() else {
            return false;
        };
        let mut any = false;
        for (path, old) in list.iter_mut() {
            let now = stamp(path);
            if now != *old {
                *old = now;
                any = true;
            }
        }
        any
    }

    /// Starts the thread that calls `wake` when a file changed; it ends when `wake`
    /// returns false (the event loop is gone).
    pub fn spawn(&self, wake: impl Fn() -> bool + Send + 'static) {
        let list = self.clone();
        std::thread::Builder::new()
            .name("glint view watcher".into())
            .spawn(move || loop {
                std::thread::sleep(POLL_INTERVAL);
                if list.changed() && !wake() {
                    return;
                }
            })
            .expect("spawning the file watcher thread");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rewrite_a_new_file_and_a_removal_are_changes() {
        let dir = glint::testing::scratch::temp_dir("watch");
        let (a, b) = (dir.join("a.lua"), dir.join("b.obj"));
        std::fs::write(&a, "x").unwrap();
        let list = WatchList::default();
        list.set(&[a.clone(), b.clone()]);
        assert!(!list.changed());
        std::fs::write(&a, "xy").unwrap();
        assert!(list.changed());
        assert!(!list.changed(), "restamped");
        std::fs::write(&b, "v 0 0 0").unwrap();
        assert!(list.changed(), "a file the run looked for appeared");
        std::fs::remove_file(&a).unwrap();
        assert!(list.changed());
    }

    /// A scene opened through a symbolic link, the link then pointed at another file of
    /// the same size and time: the view reloads.
    #[test]
    fn a_symbolic_link_re_pointed_is_a_change() {
        let dir = glint::testing::scratch::temp_dir("watch-link");
        let (one, two, link) = (
            dir.join("one.lua"),
            dir.join("two.lua"),
            dir.join("scene.lua"),
        );
        std::fs::write(&one, "x = 1").unwrap();
        std::fs::write(&two, "x = 2").unwrap();
        let time = std::fs::metadata(&one).unwrap().modified().unwrap();
        std::fs::File::options()
            .write(true)
            .open(&two)
            .unwrap()
            .set_modified(time)
            .unwrap();
        std::os::unix::fs::symlink(&one, &link).unwrap();
        let ((), reads) = glint::scene::files::record_reads(|| {
            glint::scene::files::read_regular(&link, "scene", 100).unwrap();
        });
        let list = WatchList::default();
        list.set(&reads);
        assert!(!list.changed());
        let new_link = dir.join("new-link");
        std::os::unix::fs::symlink(&two, &new_link).unwrap();
        std::fs::rename(&new_link, &link).unwrap();
        assert!(list.changed(), "watching {reads:?}");
    }
}
