//! Writing a file whole or not at all, in a folder others may write too: every file glint
//! writes (images, farm tiles, pipeline-cache files, plots, dumps) goes to a temporary
//! file beside its destination, renamed over it once complete and removed on an error or
//! on a signal that ends the process.
//!
//! The temporary file is created exclusively (`O_CREAT|O_EXCL`, which never follows a
//! symbolic link, even a dangling one) under an unpredictable name,
//! `.NAME.tmp-PID-RANDOM` (64 random bits), so that anyone who can write the folder (a
//! shared farm folder, `/tmp`) cannot plant a link there and have glint write through it
//! into another file; the rename replaces a link at the destination itself, never its
//! target. Creating, renaming and removing happen in the destination's folder opened once
//! as a handle (`openat`, `renameat`, `unlinkat`), whatever the length of its path.

use crate::folder_walk;
use std::ffi::{CString, OsStr, OsString};
use std::fs::{self, File};
use std::os::fd::{AsRawFd, OwnedFd, RawFd};
use std::path::Path;
use std::sync::atomic::{AtomicPtr, Ordering};

/// Most bytes the temporary name adds to the output's: `.` before it and
/// `.tmp-PID-RANDOM` after it (a u32 in decimal, 16 hex digits; 20 bytes kept for it).
pub const TEMP_SUFFIX_MAX: usize = 1 + ".tmp-".len() + 10 + 1 + 20;

/// How many names [`create_temp`] tries before giving up (each is 64 random bits: a
/// second try is already a sign of someone planting names).
const CREATE_ATTEMPTS: usize = 8;

/// Writes `path` atomically with `write`, which fills the file it is given: a temporary
/// file beside `path` (same file system, so the rename cannot degrade to a copy),
/// created exclusively under an unpredictable name, synced and renamed over `path` once
/// `write` succeeds, removed when anything fails or a signal ends the process meanwhile
/// (see [`remove_temp_files_on_signals`]).
pub fn write_via_temp<E: From<std::io::Error>>(
    path: &Path,
    write: impl FnOnce(&mut File) -> Result<(), E>,
) -> Result<(), E> {
    write_via_temp_with(path, E::from, write)
}

/// [`write_via_temp`] with `io_error` turning the I/O errors of creating, syncing and
/// renaming into the caller's error (one naming `path`, not the temporary file).
pub fn write_via_temp_with<E>(
    path: &Path,
    io_error: impl Fn(std::io::Error) -> E,
    write: impl FnOnce(&mut File) -> Result<(), E>,
) -> Result<(), E> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path.file_name().unwrap_or_default();
    // Everything below happens in the opened folder (`openat`, `renameat`, `unlinkat`),
    // so the path's length beyond the folder never matters (a folder past PATH_MAX).
    let folder = folder_walk::open_folder(dir).map_err(&io_error)?;
    let (mut file, temp, armed) = create_temp(&folder, name).map_err(&io_error)?;
    let result = write(&mut file)
        .and_then(|()| file.sync_all().map_err(&io_error))
        .and_then(|()| {
            drop(file);
            folder_walk::rename_in(&folder, &temp, name).map_err(&io_error)
        });
    if result.is_err() {
        let _ = folder_walk::remove_in(&folder, &temp);
    }
    disarm_signal_cleanup(armed);
    result
}

/// A new file in `folder` named `.NAME.tmp-PID-RANDOM`, created exclusively, with the
/// signal clean-up armed for it; returns the file and its name.
fn create_temp(folder: &OwnedFd, name: &OsStr) -> std::io::Result<(File, OsString, Armed)> {
    let mut last = std::io::Error::from(std::io::ErrorKind::AlreadyExists);
    for _ in 0..CREATE_ATTEMPTS {
        let mut temp = OsString::from(".");
        temp.push(name);
        temp.push(format!(
            ".tmp-{}-{:016x}",
            std::process::id(),
            random_u64()?
        ));
        // Armed before the file exists, so that no signal can strand it; a name that
        // turns out taken is disarmed before anything else happens.
        let armed = arm_signal_cleanup(folder, &temp);
        let flags = libc::O_WRONLY | libc::O_CREAT | libc::O_EXCL;
        match folder_walk::open_in(folder, &temp, flags, 0o666) {
            Ok(file) => return Ok((file, temp, armed)),
            Err(e) => {
                disarm_signal_cleanup(armed);
                if e.kind() != std::io::ErrorKind::AlreadyExists {
                    return Err(e);
                }
                last = e;
            }
        }
    }
    Err(last)
}

/// 64 bits from the kernel's random source.
fn random_u64() -> std::io::Result<u64> {
    let mut bytes = [0u8; 8];
    // SAFETY: getrandom writes at most `len` bytes into the buffer it is given.
    let n = unsafe { libc::getrandom(bytes.as_mut_ptr().cast(), bytes.len(), 0) };
    if n != bytes.len() as isize {
        return Err(std::io::Error::last_os_error());
    }
    Ok(u64::from_ne_bytes(bytes))
}

/// Creates `dir` and its parents; a name that exists as something else than a folder (a
/// file, or a symbolic link to nothing) is said as such rather than as "File exists".
pub fn create_dir_all_clearly(dir: &Path) -> std::io::Result<()> {
    match fs::create_dir_all(dir) {
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
            // The folder or one above it: the first that exists but is no folder.
            let blocker = dir
                .ancestors()
                .find(|a| fs::symlink_metadata(a).is_ok() && !a.is_dir())
                .unwrap_or(dir);
            let what = match fs::symlink_metadata(blocker) {
                Ok(m) if m.file_type().is_symlink() => {
                    "is a symbolic link to nothing, or to something that is not a folder"
                }
                _ => "exists and is not a folder",
            };
            let shown = crate::display_path::shown(blocker);
            Err(std::io::Error::new(e.kind(), format!("{shown} {what}")))
        }
        other => other,
    }
}

/// How many temporary files the signal handler can know at once (concurrent writers:
/// `--backend both`, cache files written from several threads); a writer past them
/// still removes its file on errors, only not on signals.
const SIGNAL_SLOTS: usize = 32;

/// A temporary file being written, for the signal handler: its name in an open folder.
struct TempEntry {
    folder: RawFd,
    name: CString,
}

/// The temporary files being written, for the signal handler (null: a free slot). Each
/// entry is leaked (a few bytes per file written) so that a handler running on another
/// thread can never read freed memory.
static SIGNAL_TEMPS: [AtomicPtr<TempEntry>; SIGNAL_SLOTS] =
    [const { AtomicPtr::new(std::ptr::null_mut()) }; SIGNAL_SLOTS];

/// A slot holding a temporary file's entry (None: none was free).
type Armed = Option<(usize, *mut TempEntry)>;

/// Makes every signal that ends a process by default while a file is written (SIGINT,
/// SIGTERM, SIGHUP, SIGQUIT, SIGABRT (also raised when an allocation fails), SIGUSR1,
/// SIGUSR2, SIGALRM, SIGVTALRM, SIGPROF, SIGXCPU, SIGXFSZ (a file-size limit), SIGTRAP,
/// SIGSYS, SIGIO, SIGPWR, SIGSTKFLT, the real-time signals and SIGPIPE; not the faults
/// SIGSEGV and SIGBUS, whose handlers Rust uses to report a stack overflow) remove the
/// temporary files being written, if any, then end the process as the signal would
/// have. Signals the caller ignored stay ignored. For the command line. (Rust ignores
/// SIGPIPE in every program, so a report printed into a closed pipe, as in
/// `glint diff a b | head -0`, would panic; a command-line tool ends quietly instead.)
pub fn remove_temp_files_on_signals() {
    let realtime = libc::SIGRTMIN()..=libc::SIGRTMAX();
    let signals = [
        libc::SIGINT,
        libc::SIGTERM,
        libc::SIGHUP,
        libc::SIGQUIT,
        libc::SIGABRT,
        libc::SIGUSR1,
        libc::SIGUSR2,
        libc::SIGALRM,
        libc::SIGVTALRM,
        libc::SIGPROF,
        libc::SIGXCPU,
        libc::SIGXFSZ,
        libc::SIGTRAP,
        libc::SIGSYS,
        libc::SIGIO,
        libc::SIGPWR,
        libc::SIGSTKFLT,
        libc::SIGPIPE,
    ];
    for sig in signals.into_iter().chain(realtime) {
        // SAFETY: installs an async-signal-safe handler (atomic loads, unlink, signal,
        // raise); `signal` is called before any thread writes a file.
        unsafe {
            let old = libc::signal(
                sig,
                on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t,
            );
            // (The Rust runtime, not the caller, set SIGPIPE to ignored before main.)
            if old == libc::SIG_IGN && sig != libc::SIGPIPE {
                libc::signal(sig, libc::SIG_IGN);
            }
        }
    }
}

extern "C" fn on_signal(sig: libc::c_int) {
    for slot in &SIGNAL_TEMPS {
        let temp = slot.load(Ordering::SeqCst);
        // SAFETY: `temp` is null or a leaked entry, never freed; unlinkat is
        // async-signal-safe. (The folder is open while its entry is armed.)
        if let Some(entry) = unsafe { temp.as_ref() } {
            unsafe { libc::unlinkat(entry.folder, entry.name.as_ptr(), 0) };
        }
    }
    // SAFETY: signal and raise are async-signal-safe.
    unsafe {
        libc::signal(sig, libc::SIG_DFL);
        libc::raise(sig);
    }
}

/// Puts `temp` in `folder` in a free slot of the signal handler's list.
fn arm_signal_cleanup(folder: &OwnedFd, temp: &OsStr) -> Armed {
    use std::os::unix::ffi::OsStrExt;
    let name = CString::new(temp.as_bytes()).ok()?;
    let ptr = Box::into_raw(Box::new(TempEntry {
        folder: folder.as_raw_fd(),
        name,
    }));
    SIGNAL_TEMPS.iter().enumerate().find_map(|(i, slot)| {
        slot.compare_exchange(
            std::ptr::null_mut(),
            ptr,
            Ordering::SeqCst,
            Ordering::SeqCst,
        )
        .ok()
        .map(|_| (i, ptr))
    })
}

fn disarm_signal_cleanup(armed: Armed) {
    if let Some((i, ptr)) = armed {
        let _ = SIGNAL_TEMPS[i].compare_exchange(
            ptr,
            std::ptr::null_mut(),
            Ordering::SeqCst,
            Ordering::SeqCst,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::scratch::file_names as names;

    /// Files other than images: the whole new file or the old one, never a partial one.
    #[test]
    fn write_via_temp_renames_on_success_and_cleans_up_on_failure() {
        use std::io::Write;
        let (dir, target) = crate::testing::scratch::temp_file("atomic-write", "dump.bin");
        write_via_temp(&target, |file| file.write_all(b"old")).unwrap();
        let failed: std::io::Result<()> = write_via_temp(&target, |file| {
            file.write_all(b"half")?;
            Err(std::io::Error::other("disk full"))
        });
        assert!(failed.is_err());
        assert_eq!(fs::read(&target).unwrap(), b"old");
        assert_eq!(names(&dir), vec!["dump.bin".to_string()]);
    }

    /// Temporary names cannot be guessed: two writes of one file use different ones.
    #[test]
    fn temporary_names_are_unpredictable_and_fresh() {
        let dir = crate::testing::scratch::temp_dir("atomic-names");
        let mut seen = Vec::new();
        for _ in 0..2 {
            let folder = folder_walk::open_folder(&dir).unwrap();
            let (file, temp, armed) = create_temp(&folder, "a.png".as_ref()).unwrap();
            drop(file);
            disarm_signal_cleanup(armed);
            let name = temp.to_string_lossy().into_owned();
            assert!(name.starts_with(".a.png.tmp-"), "{name}");
            assert!(name.len() <= "a.png".len() + TEMP_SUFFIX_MAX, "{name}");
            seen.push(name);
        }
        assert_ne!(seen[0], seen[1]);
    }

    #[test]
    fn a_dangling_link_in_the_way_of_a_folder_is_named() {
        let dir = crate::testing::scratch::temp_dir("atomic-dangling");
        let link = dir.join("cache");
        std::os::unix::fs::symlink(dir.join("nowhere"), &link).unwrap();
        for wanted in [link.clone(), link.join("sub")] {
            let e = create_dir_all_clearly(&wanted).unwrap_err().to_string();
            assert!(e.contains("cache is a symbolic link to nothing"), "{e}");
        }
    }
}
