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

/// What is compared: modification time and size, or None for a missing file.
type Stamp = Option<(SystemTime, u64)>;

fn stamp(path: &PathBuf) -> Stamp {
    let meta = std::fs::metadata(path).ok()?;
    Some((meta.modified().ok()?, meta.len()))
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
}
