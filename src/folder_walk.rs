//! Resolving a path one component at a time from opened folder handles, so that the rules
//! for what a scene may read and write never need a path's absolute spelling. A folder
//! whose absolute path is over PATH_MAX (4 096 bytes) can be opened by a relative path
//! but not by its absolute one: walked from the current folder (`openat` on each name,
//! `O_NOFOLLOW`, symbolic links read and followed here, at most [`MAX_LINKS`] of them),
//! it is checked and used as any other, and a file beside it opens however long the
//! whole path is.
//!
//! Whether a path lies inside an allowed folder is asked of the folders themselves
//! ([`lies_within`]): from the folder the path ends in, the walk climbs by `..` (the real
//! parent, as the kernel sees it) comparing each folder's device and inode with the
//! allowed folders'. Nothing is compared as text, so `..`, links and long paths are
//! judged as the system resolves them. (`openat2`'s `RESOLVE_BENEATH` would refuse what
//! the rules allow: a link from the scene's folder into another readable folder.)

use std::collections::VecDeque;
use std::ffi::{CString, OsStr, OsString};
use std::fs::File;
use std::io;
use std::os::fd::{AsRawFd, FromRawFd, OwnedFd, RawFd};
use std::os::unix::ffi::{OsStrExt, OsStringExt};
use std::path::{Component, Path, PathBuf};

/// Most symbolic links one walk follows (the kernel's own bound; past it, ELOOP).
const MAX_LINKS: usize = 40;

/// Most folders [`lies_within`] climbs (far deeper than any tree a path can name).
const MAX_CLIMB: usize = 1 << 16;

/// A file's identity: its device and inode (the same file under any spelling of its path).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FileId {
    dev: u64,
    ino: u64,
}

impl FileId {
    /// The identity of an opened file.
    pub fn of(file: &File) -> io::Result<FileId> {
        use std::os::unix::fs::MetadataExt;
        let meta = file.metadata()?;
        Ok(FileId {
            dev: meta.dev(),
            ino: meta.ino(),
        })
    }

    /// The identity of the file `path` names (links followed).
    pub fn of_path(path: &Path) -> io::Result<FileId> {
        use std::os::unix::fs::MetadataExt;
        let meta = std::fs::metadata(path)?;
        Ok(FileId {
            dev: meta.dev(),
            ino: meta.ino(),
        })
    }

    /// The identity of the folder behind `fd`.
    pub fn of_fd(fd: &OwnedFd) -> io::Result<FileId> {
        let st = fstat(fd.as_raw_fd())?;
        Ok(FileId {
            dev: st.st_dev,
            ino: st.st_ino,
        })
    }

    /// The identity of the folder `path` names, opened by a walk ([`open_folder`]).
    pub fn of_folder(path: &Path) -> io::Result<FileId> {
        FileId::of_fd(&open_folder(path)?)
    }

    /// A text key for the identity (a Lua table's key for a module loaded once).
    pub fn key(&self) -> String {
        format!("file:{}:{}", self.dev, self.ino)
    }
}

/// A folder a rule admits (what a scene may read, or write under): its identity, which
/// the rule compares ([`lies_within`]), and a path for messages.
#[derive(Clone, Debug)]
pub struct Root {
    pub id: FileId,
    /// Its canonical path where the system can give one (else the path as given).
    pub shown: PathBuf,
}

impl Root {
    /// The folder `dir` as a root (an error when it cannot be opened as a folder).
    pub fn open(dir: &Path) -> io::Result<Root> {
        let id = FileId::of_folder(dir)?;
        let shown = dir
            .canonicalize()
            .ok()
            .filter(|real| real.is_dir())
            .unwrap_or_else(|| dir.to_path_buf());
        Ok(Root { id, shown })
    }

    /// The identities of `roots`, as [`lies_within`] takes them.
    pub fn ids(roots: &[Root]) -> Vec<FileId> {
        roots.iter().map(|root| root.id).collect()
    }
}

/// Where a path led.
#[derive(Debug)]
pub struct Walk {
    /// The deepest existing folder the path reaches (the path's own folder when the path
    /// names a file in it).
    pub folder: OwnedFd,
    /// What follows `folder`: nothing when the path names that folder; the name of an
    /// existing entry that is not a folder (a link when the walk did not follow the last
    /// one); or, past the first name that could not be looked up, the names as written
    /// (`..` cancelling one of them), so that a path that does not exist is judged by
    /// where it would lie, as one that does.
    pub rest: Vec<OsString>,
    /// Why the path does not lead to an existing entry (None: it does).
    pub failed: Option<io::Error>,
}

impl Walk {
    /// The one name after [`Walk::folder`] when the path names an existing entry that is
    /// not a folder.
    pub fn leaf(&self) -> Option<&OsStr> {
        match (&self.failed, self.rest.as_slice()) {
            (None, [name]) => Some(name),
            _ => None,
        }
    }
}

/// One step of a walk.
enum Step {
    Root,
    Up,
    Name(OsString),
}

fn steps(path: &Path) -> impl Iterator<Item = Step> + '_ {
    path.components().filter_map(|c| match c {
        Component::Prefix(_) | Component::RootDir => Some(Step::Root),
        Component::CurDir => None,
        Component::ParentDir => Some(Step::Up),
        Component::Normal(name) => Some(Step::Name(name.to_os_string())),
    })
}

/// Walks `path` (relative to the current folder, or absolute) from opened folders,
/// following symbolic links on the way, and the last one only when `follow_last`. A
/// name that cannot be looked up (missing, no permission, a link loop) ends the real
/// walk: the rest is taken as written and the error kept in [`Walk::failed`]. Fails only
/// when the starting folder itself cannot be opened.
pub fn walk(path: &Path, follow_last: bool) -> io::Result<Walk> {
    let start = if path.has_root() { "/" } else { "." };
    let mut folder = open_folder_at(libc::AT_FDCWD, OsStr::new(start))?;
    let mut queue: VecDeque<Step> = steps(path).collect();
    let (mut rest, mut failed, mut links) = (Vec::new(), None, 0);
    while let Some(step) = queue.pop_front() {
        let last = queue.is_empty();
        let name = match step {
            Step::Root => {
                folder = open_folder_at(libc::AT_FDCWD, OsStr::new("/"))?;
                rest.clear();
                continue;
            }
            Step::Up if rest.pop().is_some() => continue,
            Step::Up => OsString::from(".."),
            Step::Name(name) if failed.is_some() || !rest.is_empty() => {
                rest.push(name);
                continue;
            }
            Step::Name(name) => name,
        };
        let looked = stat_at(folder.as_raw_fd(), &name).and_then(|st| {
            match st.st_mode & libc::S_IFMT {
                libc::S_IFLNK if !last || follow_last => {
                    links += 1;
                    if links > MAX_LINKS {
                        return Err(io::Error::from_raw_os_error(libc::ELOOP));
                    }
                    let target = read_link_at(folder.as_raw_fd(), &name)?;
                    for step in steps(Path::new(&target))
                        .collect::<Vec<_>>()
                        .into_iter()
                        .rev()
                    {
                        queue.push_front(step);
                    }
                }
                libc::S_IFDIR => folder = open_folder_at(folder.as_raw_fd(), &name)?,
                _ if last => rest.push(name.clone()),
                _ => return Err(io::Error::from_raw_os_error(libc::ENOTDIR)),
            }
            Ok(())
        });
        if let Err(e) = looked {
            failed = Some(e);
            if name != ".." {
                rest.push(name);
            }
        }
    }
    Ok(Walk {
        folder,
        rest,
        failed,
    })
}

/// The folder `path` names, opened by a walk (see [`walk`]): any depth the system can
/// reach by the path as given, however long its absolute form.
pub fn open_folder(path: &Path) -> io::Result<OwnedFd> {
    let walked = walk(path, true)?;
    if let Some(e) = walked.failed {
        return Err(e);
    }
    if !walked.rest.is_empty() {
        return Err(io::Error::from_raw_os_error(libc::ENOTDIR));
    }
    Ok(walked.folder)
}

/// The folder above `folder` (`..`: the root's is the root).
pub fn open_parent(folder: &OwnedFd) -> io::Result<OwnedFd> {
    open_folder_at(folder.as_raw_fd(), OsStr::new(".."))
}

/// Whether the folder `folder` is one of `roots` or lies below one: climbs by `..` to the
/// filesystem's root comparing identities. A folder that cannot be climbed (no
/// permission above it) counts as outside.
pub fn lies_within(folder: &OwnedFd, roots: &[FileId]) -> bool {
    let Ok(mut id) = FileId::of_fd(folder) else {
        return false;
    };
    let mut current = match open_folder_at(folder.as_raw_fd(), OsStr::new("..")) {
        Ok(up) => up,
        Err(_) => return roots.contains(&id),
    };
    for _ in 0..MAX_CLIMB {
        if roots.contains(&id) {
            return true;
        }
        let Ok(up) = FileId::of_fd(&current) else {
            return false;
        };
        if up == id {
            return false; // `..` of the root is the root.
        }
        id = up;
        current = match open_folder_at(current.as_raw_fd(), OsStr::new("..")) {
            Ok(next) => next,
            Err(_) => return roots.contains(&id),
        };
    }
    false
}

/// Opens `name` in `folder` with `flags` (and `O_NOFOLLOW`, `O_CLOEXEC`: a link swapped
/// in after the walk is refused, not followed); `mode` for a file created.
pub fn open_in(folder: &OwnedFd, name: &OsStr, flags: i32, mode: u32) -> io::Result<File> {
    let c = c_name(name)?;
    // SAFETY: a valid NUL-terminated name and an open folder descriptor.
    let fd = unsafe {
        libc::openat(
            folder.as_raw_fd(),
            c.as_ptr(),
            flags | libc::O_NOFOLLOW | libc::O_CLOEXEC,
            mode,
        )
    };
    if fd < 0 {
        return Err(io::Error::last_os_error());
    }
    // SAFETY: `fd` was just opened and is owned by nothing else.
    Ok(unsafe { File::from_raw_fd(fd) })
}

/// What `name` in `folder` is, without following a link.
pub fn stat_in(folder: &OwnedFd, name: &OsStr) -> io::Result<libc::stat> {
    stat_at(folder.as_raw_fd(), name)
}

/// Whether this process may write `name` in `folder` (`faccessat`).
pub fn writable_in(folder: &OwnedFd, name: &OsStr) -> bool {
    let Ok(c) = c_name(name) else {
        return false;
    };
    // SAFETY: a valid NUL-terminated name and an open folder descriptor.
    unsafe { libc::faccessat(folder.as_raw_fd(), c.as_ptr(), libc::W_OK, 0) == 0 }
}

/// Renames `from` to `to`, both in `folder` (`renameat`: the name `to` itself is
/// replaced, a link there too, never its target).
pub fn rename_in(folder: &OwnedFd, from: &OsStr, to: &OsStr) -> io::Result<()> {
    let (from, to) = (c_name(from)?, c_name(to)?);
    let fd = folder.as_raw_fd();
    // SAFETY: valid NUL-terminated names and an open folder descriptor.
    if unsafe { libc::renameat(fd, from.as_ptr(), fd, to.as_ptr()) } != 0 {
        return Err(io::Error::last_os_error());
    }
    Ok(())
}

/// Removes the file `name` in `folder`.
pub fn remove_in(folder: &OwnedFd, name: &OsStr) -> io::Result<()> {
    let c = c_name(name)?;
    // SAFETY: a valid NUL-terminated name and an open folder descriptor.
    if unsafe { libc::unlinkat(folder.as_raw_fd(), c.as_ptr(), 0) } != 0 {
        return Err(io::Error::last_os_error());
    }
    Ok(())
}

fn c_name(name: &OsStr) -> io::Result<CString> {
    CString::new(name.as_bytes()).map_err(|_| io::Error::from_raw_os_error(libc::EINVAL))
}

/// `name` in `at` opened as a folder handle (`O_PATH`: no read permission needed, only
/// the search permission a path needs) without following a link.
fn open_folder_at(at: RawFd, name: &OsStr) -> io::Result<OwnedFd> {
    let c = c_name(name)?;
    let flags = libc::O_PATH | libc::O_DIRECTORY | libc::O_NOFOLLOW | libc::O_CLOEXEC;
    // SAFETY: a valid NUL-terminated name; `at` is AT_FDCWD or an open descriptor.
    let fd = unsafe { libc::openat(at, c.as_ptr(), flags) };
    if fd < 0 {
        return Err(io::Error::last_os_error());
    }
    // SAFETY: `fd` was just opened and is owned by nothing else.
    Ok(unsafe { OwnedFd::from_raw_fd(fd) })
}

fn fstat(fd: RawFd) -> io::Result<libc::stat> {
    // SAFETY: stat is plain data; fstat fills it for an open descriptor.
    let mut st: libc::stat = unsafe { std::mem::zeroed() };
    if unsafe { libc::fstat(fd, &mut st) } != 0 {
        return Err(io::Error::last_os_error());
    }
    Ok(st)
}

fn stat_at(at: RawFd, name: &OsStr) -> io::Result<libc::stat> {
    let c = c_name(name)?;
    // SAFETY: stat is plain data; fstatat fills it given a valid name and descriptor.
    let mut st: libc::stat = unsafe { std::mem::zeroed() };
    if unsafe { libc::fstatat(at, c.as_ptr(), &mut st, libc::AT_SYMLINK_NOFOLLOW) } != 0 {
        return Err(io::Error::last_os_error());
    }
    Ok(st)
}

fn read_link_at(at: RawFd, name: &OsStr) -> io::Result<OsString> {
    let c = c_name(name)?;
    let mut buf = vec![0u8; libc::PATH_MAX as usize + 1];
    // SAFETY: readlinkat writes at most `buf.len()` bytes into `buf`.
    let n = unsafe { libc::readlinkat(at, c.as_ptr(), buf.as_mut_ptr().cast(), buf.len()) };
    if n < 0 {
        return Err(io::Error::last_os_error());
    }
    buf.truncate(n as usize);
    Ok(OsString::from_vec(buf))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn id(path: &Path) -> FileId {
        FileId::of_fd(&open_folder(path).unwrap()).unwrap()
    }

    #[test]
    fn walks_resolve_dots_and_links_and_judge_missing_paths_by_where_they_would_lie() {
        let dir = crate::testing::scratch::temp_dir("folder-walk");
        std::fs::create_dir_all(dir.join("a/b")).unwrap();
        std::fs::create_dir_all(dir.join("out")).unwrap();
        std::fs::write(dir.join("a/b/f.obj"), "x").unwrap();
        std::os::unix::fs::symlink("../out", dir.join("a/link")).unwrap();
        std::os::unix::fs::symlink("loop", dir.join("a/loop")).unwrap();
        let a = [id(&dir.join("a"))];
        let walked = walk(&dir.join("a/b/../b/f.obj"), true).unwrap();
        assert_eq!(walked.leaf(), Some(OsStr::new("f.obj")));
        assert!(lies_within(&walked.folder, &a));
        let out = walk(&dir.join("a/link/x.obj"), true).unwrap();
        assert!(out.failed.is_some() && !lies_within(&out.folder, &a));
        let missing = walk(&dir.join("a/none/../../out/x"), true).unwrap();
        assert_eq!(
            missing.rest,
            vec![OsString::from("out"), OsString::from("x")]
        );
        assert!(missing.failed.is_some() && !lies_within(&missing.folder, &a));
        let looped = walk(&dir.join("a/loop"), true).unwrap();
        assert_eq!(looped.failed.unwrap().raw_os_error(), Some(libc::ELOOP));
        let unfollowed = walk(&dir.join("a/link"), false).unwrap();
        assert_eq!(unfollowed.leaf(), Some(OsStr::new("link")));
        assert!(lies_within(&walk(&dir.join("a"), true).unwrap().folder, &a));
    }

    /// A folder past PATH_MAX: opened from a relative path, and climbed to its root.
    #[test]
    fn folders_past_path_max_are_walked_and_climbed() {
        let dir = crate::testing::scratch::temp_dir("folder-walk-deep");
        let name = "d".repeat(200);
        let mut deep = open_folder(&dir).unwrap();
        for _ in 0..22 {
            let c = c_name(OsStr::new(&name)).unwrap();
            // SAFETY: a valid name and an open folder descriptor.
            assert_eq!(
                unsafe { libc::mkdirat(deep.as_raw_fd(), c.as_ptr(), 0o755) },
                0
            );
            deep = open_folder_at(deep.as_raw_fd(), OsStr::new(&name)).unwrap();
        }
        let file = open_in(
            &deep,
            OsStr::new("m.obj"),
            libc::O_WRONLY | libc::O_CREAT,
            0o644,
        );
        drop(file.unwrap());
        assert!(lies_within(&deep, &[id(&dir)]));
        let root = std::env::temp_dir();
        assert!(!lies_within(&open_folder(&root).unwrap(), &[id(&dir)]));
        let mut path = dir.to_path_buf();
        for _ in 0..22 {
            path.push(&name);
        }
        assert!(path.as_os_str().len() > libc::PATH_MAX as usize);
        let walked = walk(&path.join("m.obj"), true).unwrap();
        assert_eq!(walked.leaf(), Some(OsStr::new("m.obj")));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
