//! Reading the files a scene names (its script, modules, meshes, textures) as a hostile
//! scene cannot abuse them: regular files only (a FIFO would block, `/dev/zero` would
//! never end), at most a size cap, and only under the folders the scene may read — its
//! own folder, glint's own assets ([`GLINT_ASSETS`]) and those given by `--allow-read` —
//! after resolving `..` and symbolic links, in the spirit of POV-Ray's I/O restrictions.
//! Paths are walked from opened folder handles ([`crate::folder_walk`]) and the file is
//! opened from its folder's handle, so a scene in a folder deeper than PATH_MAX reads
//! beside it as any other. A refusal names the path and the flag that widens the rule.

use std::fs::{File, OpenOptions};
use std::io::Read;
use std::os::unix::fs::OpenOptionsExt;
use std::path::{Path, PathBuf};

use crate::display_path::shown;
use crate::folder_walk::{self, FileId, Root};

/// Largest file a scene may read (a mesh, texture or module), in bytes.
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// How many characters of a file that is not the scene's own an error may quote.
pub const MAX_EXCERPT_CHARS: usize = 24;

/// glint's own assets: the `textures/` folder of the source tree the binary was built
/// from (the generated textures and fonts that `scenes/` use), readable by every scene
/// as POV-Ray's library path is.
pub const GLINT_ASSETS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/textures");

/// The folders a scene may read from, each as its identity (device and inode): a path is
/// judged by walking it from opened folder handles ([`crate::folder_walk`]), never by
/// its absolute spelling, so a scene in a folder deeper than PATH_MAX reads its
/// siblings as any other scene does.
#[derive(Clone, Debug, Default)]
pub struct ReadPolicy {
    roots: Vec<Root>,
    /// The flag's wording for messages (`--allow-read DIR`).
    flag: &'static str,
}

/// A file a scene may read, opened: checked to be a regular file; its size is checked
/// against the cap when it is read ([`Opened::read`]), so that a caller can first weigh
/// it against a memory budget.
#[derive(Debug)]
pub struct Opened {
    /// The path as tried (for messages).
    pub path: PathBuf,
    pub file: File,
    pub len: u64,
    /// The file under any spelling of its path.
    pub id: FileId,
}

impl Opened {
    /// The whole file, refused (saying `what` it is) when over `cap` bytes or when it
    /// grows past `cap` while read.
    pub fn read(self, what: &str, cap: u64) -> Result<Vec<u8>, String> {
        if self.len > cap {
            return Err(format!(
                "cannot read {what} '{}': it is {} bytes, over the limit of {cap} bytes",
                shown(&self.path),
                self.len
            ));
        }
        read_capped(self.file, self.len, &self.path, what, cap)
    }
}

impl ReadPolicy {
    /// The scene's own folder, [`GLINT_ASSETS`] and `extra` folders. Folders that do not
    /// exist are left out (nothing under them can be read anyway).
    pub fn new(scene_dir: &Path, extra: &[PathBuf]) -> ReadPolicy {
        let scene_dir = if scene_dir.as_os_str().is_empty() {
            Path::new(".")
        } else {
            scene_dir
        };
        let roots = [scene_dir, Path::new(GLINT_ASSETS)]
            .into_iter()
            .chain(extra.iter().map(PathBuf::as_path))
            .filter_map(|dir| Root::open(dir).ok())
            .collect();
        ReadPolicy {
            roots,
            flag: "--allow-read DIR",
        }
    }

    /// This policy and the folder `dir` (a prelude reading its own folder's modules).
    pub fn with_root(&self, dir: &Path) -> ReadPolicy {
        let mut wider = self.clone();
        wider.roots.extend(Root::open(dir).ok());
        wider
    }

    /// Whether `path` lies inside a folder the scene may read (whether or not it exists).
    pub fn allows(&self, path: &Path) -> bool {
        folder_walk::walk(path, true)
            .is_ok_and(|w| folder_walk::lies_within(&w.folder, &Root::ids(&self.roots)))
    }

    /// Whether `path` lies inside a folder the scene may read and names something there
    /// (a file, or anything that stops the walk other than a missing name).
    pub fn present(&self, path: &Path) -> bool {
        folder_walk::walk(path, true).is_ok_and(|w| {
            folder_walk::lies_within(&w.folder, &Root::ids(&self.roots))
                && w.failed
                    .is_none_or(|e| e.kind() != std::io::ErrorKind::NotFound)
        })
    }

    /// Opens `path` (relative to the current folder, or absolute) if the scene may read
    /// it: walked from opened folders, judged by where it lies, and the file opened from
    /// its own folder's handle (`O_NOFOLLOW`: nothing swapped in after the walk is
    /// followed) as every reader opens ([`open_checked`]: regular files only, never
    /// blocking). The size is not capped here: [`Opened::read`] caps it. A path inside
    /// is recorded for `glint view`'s reload, found or not.
    pub fn open(&self, path: &Path, what: &str) -> Result<Opened, String> {
        let cannot =
            |e: &dyn std::fmt::Display| format!("cannot read {what} '{}': {e}", shown(path));
        let walked = folder_walk::walk(path, true).map_err(|e| cannot(&e))?;
        if !folder_walk::lies_within(&walked.folder, &Root::ids(&self.roots)) {
            return Err(self.outside(path, what));
        }
        // Inside: watched by `glint view` whether or not it exists (creating it reloads).
        note_read(path);
        if let Some(e) = &walked.failed {
            return Err(cannot(e));
        }
        let Some(leaf) = walked.leaf() else {
            return Err(cannot(&"not a regular file"));
        };
        let opened = open_checked_in(&walked.folder, leaf, u64::MAX);
        let (file, len) = opened.map_err(|r| match r {
            Refusal::Io(e) => cannot(&e),
            _ => cannot(&"not a regular file"),
        })?;
        let id = FileId::of(&file).map_err(|e| cannot(&e))?;
        Ok(Opened {
            path: path.to_path_buf(),
            file,
            len,
            id,
        })
    }

    /// The refusal of `path`, outside every folder the scene may read.
    fn outside(&self, path: &Path, what: &str) -> String {
        let roots: Vec<String> = self.roots.iter().map(|r| shown(&r.shown)).collect();
        format!(
            "cannot read {what} '{}': it is outside the folders this scene may read ({}); {} allows another folder",
            shown(path),
            roots.join(", "),
            self.flag
        )
    }
}

/// Why [`open_checked`] refused a file.
#[derive(Debug)]
pub enum Refusal {
    /// Opening or looking at it failed (missing, no permission, a symbolic link loop…).
    Io(std::io::Error),
    /// A FIFO, device, socket or folder.
    NotRegular,
    /// Larger than the cap (its size in bytes).
    TooBig(u64),
}

/// Opens `path` for reading the way every reader of glint does: without blocking (a FIFO
/// would otherwise wait for a writer forever; `O_NONBLOCK`, and `O_NOCTTY` so that a
/// terminal never becomes glint's), then looks at what the opened handle is (`fstat`,
/// so that nothing can be swapped in between): a regular file of at most `cap` bytes.
/// Returns the file and its size. Reads through it should stop at `cap` bytes too (a
/// file may grow): [`read_regular`] does.
pub fn open_checked(path: &Path, cap: u64) -> Result<(File, u64), Refusal> {
    let file = OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY)
        .open(path)
        .map_err(Refusal::Io)?;
    regular(file, cap)
}

/// [`open_checked`] for the entry `name` of an opened folder (a walk's,
/// [`crate::folder_walk`]), with `O_NOFOLLOW`: a link swapped in after the walk is
/// refused, not followed.
pub fn open_checked_in(
    folder: &std::os::fd::OwnedFd,
    name: &std::ffi::OsStr,
    cap: u64,
) -> Result<(File, u64), Refusal> {
    let flags = libc::O_RDONLY | libc::O_NONBLOCK | libc::O_NOCTTY;
    let file = folder_walk::open_in(folder, name, flags, 0).map_err(Refusal::Io)?;
    regular(file, cap)
}

/// `file` and its size if the opened handle is a regular file of at most `cap` bytes
/// (`fstat`: what was opened, not what the name holds now).
fn regular(file: File, cap: u64) -> Result<(File, u64), Refusal> {
    let meta = file.metadata().map_err(Refusal::Io)?;
    if !meta.is_file() {
        return Err(Refusal::NotRegular);
    }
    if meta.len() > cap {
        return Err(Refusal::TooBig(meta.len()));
    }
    Ok((file, meta.len()))
}

/// [`open_checked`] for a scene's reads (recorded for `glint view`'s reload), with the
/// refusal said as a message naming `what` and the path.
pub fn open_regular(path: &Path, what: &str, cap: u64) -> Result<(File, u64), String> {
    open_regular_within(path, what, cap, &|len| {
        format!("it is {len} bytes, over the limit of {cap} bytes")
    })
}

/// [`open_regular`] with a file over `cap` said by `over` (given its size in bytes): the
/// cap's own reason (what is left of a memory budget, and the flag that raises it).
pub fn open_regular_within(
    path: &Path,
    what: &str,
    cap: u64,
    over: &dyn Fn(u64) -> String,
) -> Result<(File, u64), String> {
    note_read(path);
    let shown = shown(path);
    open_checked(path, cap).map_err(|refusal| match refusal {
        Refusal::Io(e) => format!("cannot read {what} '{shown}': {e}"),
        Refusal::NotRegular => format!("cannot read {what} '{shown}': not a regular file"),
        Refusal::TooBig(len) => format!("cannot read {what} '{shown}': {}", over(len)),
    })
}

thread_local! {
    /// The files opened on this thread while [`record_reads`] runs (None: not recording).
    static READ_LOG: std::cell::RefCell<Option<Vec<PathBuf>>> = const { std::cell::RefCell::new(None) };
}

/// Adds `path` to the read log when one is recording (every file a scene reads, found
/// or not, goes through [`open_regular`] or [`ReadPolicy::open`]).
fn note_read(path: &Path) {
    READ_LOG.with(|log| {
        if let Some(paths) = log.borrow_mut().as_mut() {
            let canonical = path.canonicalize().unwrap_or_else(|_| path.to_path_buf());
            // The path as given too where it differs (a symbolic link on the way): a
            // link re-pointed at another file is a change to watch for.
            let given = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
            for path in [canonical, given] {
                if !paths.contains(&path) {
                    paths.push(path);
                }
            }
        }
    });
}

/// Runs `f` and returns its value with every file it tried to read through
/// [`open_regular`] or [`ReadPolicy::open`] on this thread (the script, preludes,
/// modules, meshes, textures; missing ones too, so that creating one can be noticed),
/// in first-read order: what `glint view` watches for live reload. The scene's reads all
/// happen on the thread that runs its script.
pub fn record_reads<T>(f: impl FnOnce() -> T) -> (T, Vec<PathBuf>) {
    let outer = READ_LOG.with(|log| log.replace(Some(Vec::new())));
    let value = f();
    let paths = READ_LOG.with(|log| log.replace(outer)).unwrap_or_default();
    (value, paths)
}

/// Reads a whole regular file of at most `cap` bytes (see [`open_regular`]). A file that
/// grows while being read is cut at `cap + 1` bytes and refused.
pub fn read_regular(path: &Path, what: &str, cap: u64) -> Result<Vec<u8>, String> {
    read_regular_within(path, what, cap, &|len| {
        format!("it is {len} bytes, over the limit of {cap} bytes")
    })
}

/// [`read_regular`] with a file over `cap` said by `over` (see [`open_regular_within`]).
pub fn read_regular_within(
    path: &Path,
    what: &str,
    cap: u64,
    over: &dyn Fn(u64) -> String,
) -> Result<Vec<u8>, String> {
    let (file, len) = open_regular_within(path, what, cap, over)?;
    read_capped(file, len, path, what, cap)
}

/// Reads the opened regular `file` of `len` bytes (`path` and `what` for messages), cut
/// at `cap + 1` bytes and refused if it grew past `cap` while being read.
fn read_capped(file: File, len: u64, path: &Path, what: &str, cap: u64) -> Result<Vec<u8>, String> {
    let mut bytes = Vec::new();
    bytes
        .try_reserve_exact(len as usize)
        .map_err(|e| format!("cannot read {what} '{}': {e}", shown(path)))?;
    file.take(cap + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read {what} '{}': {e}", shown(path)))?;
    if bytes.len() as u64 > cap {
        return Err(format!(
            "cannot read {what} '{}': it grew past the limit of {cap} bytes while being read",
            shown(path)
        ));
    }
    Ok(bytes)
}

/// At most [`MAX_EXCERPT_CHARS`] characters of `text`, for quoting a file's content.
pub fn excerpt(text: &str) -> String {
    if text.chars().count() <= MAX_EXCERPT_CHARS {
        return text.to_string();
    }
    let head: String = text.chars().take(MAX_EXCERPT_CHARS).collect();
    format!("{head}…")
}

#[cfg(test)]
mod tests {
    #[test]
    fn record_reads_lists_each_file_tried_once_found_or_not() {
        let dir = crate::testing::scratch::temp_dir("reads");
        let (a, missing) = (dir.join("a.lua"), dir.join("missing.obj"));
        std::fs::write(&a, "x").unwrap();
        let ((), reads) = record_reads(|| {
            read_regular(&a, "module", 10).unwrap();
            read_regular(&a, "module", 10).unwrap();
            assert!(read_regular(&missing, "mesh file", 10).is_err());
        });
        assert_eq!(reads, vec![a.canonicalize().unwrap(), missing.clone()]);
        // Nothing is recorded outside a recording.
        let ((), none) = record_reads(|| ());
        assert!(none.is_empty());
    }

    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("glint-files-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn paths_outside_the_roots_are_refused_after_resolving_dots() {
        let dir = scratch("policy");
        std::fs::create_dir_all(dir.join("scene/tex")).unwrap();
        std::fs::write(dir.join("scene/tex/a.png"), b"x").unwrap();
        std::fs::write(dir.join("secret.txt"), b"x").unwrap();
        let policy = ReadPolicy::new(&dir.join("scene"), &[]);
        assert!(policy
            .open(&dir.join("scene/tex/../tex/a.png"), "texture")
            .is_ok());
        let e = policy
            .open(&dir.join("scene/../secret.txt"), "mesh")
            .unwrap_err();
        assert!(
            e.contains("outside the folders") && e.contains("--allow-read"),
            "{e}"
        );
        let wide = ReadPolicy::new(&dir.join("scene"), std::slice::from_ref(&dir));
        assert!(wide.open(&dir.join("secret.txt"), "mesh").is_ok());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn special_and_oversized_files_are_refused() {
        let e = read_regular(Path::new("/dev/zero"), "mesh", 100).unwrap_err();
        assert!(e.contains("not a regular file"), "{e}");
        let dir = scratch("size");
        let p = dir.join("big.obj");
        std::fs::write(&p, vec![b'#'; 101]).unwrap();
        let e = read_regular(&p, "mesh", 100).unwrap_err();
        assert!(e.contains("over the limit of 100 bytes"), "{e}");
        assert_eq!(read_regular(&p, "mesh", 101).unwrap().len(), 101);
        let fifo = dir.join("fifo");
        let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: a valid NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        let e = read_regular(&fifo, "texture", 100).unwrap_err();
        assert!(e.contains("not a regular file"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn excerpts_are_short() {
        assert_eq!(excerpt("short"), "short");
        let long = "x".repeat(100);
        assert_eq!(excerpt(&long).chars().count(), MAX_EXCERPT_CHARS + 1);
    }
}
