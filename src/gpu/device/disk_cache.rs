//! The on-disk cache of compiled pipelines: what the driver returns from wgpu's
//! `PipelineCache::get_data` (on Vulkan, the `VkPipelineCache` blob) after a pipeline is
//! compiled, kept in one file per kernel and handed back to the driver on the next run,
//! so that it can skip its own compile. Not to be confused with
//! `PipelineCache` in `pipeline_cache.rs`, the in-memory map of one context.
//!
//! A file is named by a hash of its key and starts with glint's own header (magic,
//! format version, key, payload length, SHA-256 of all that and the payload); the key is
//! the adapter (name, backend, type, vendor and device ids), the driver (name and
//! info), glint's version and the kernel (a hash of the final WGSL, the kernel variant,
//! the entry point). A file that is truncated, fails its checksum or holds another key is
//! ignored — never handed to the driver — with one note on stderr per process, and
//! rewritten. Files are written whole to a temporary name and renamed, so concurrent runs
//! (processes or threads) each read either no file or a whole one, and the last writer
//! wins with a file as valid as the others. Where the device lacks
//! `Features::PIPELINE_CACHE` (every backend but Vulkan), nothing is read or written.
//!
//! Where: `GLINT_CACHE_DIR`, else `$XDG_CACHE_HOME/glint`, else `$HOME/.cache/glint`
//! (`%LOCALAPPDATA%\glint` on Windows); `GLINT_PIPELINE_CACHE=off` turns it off. Deleting
//! the folder clears it.

use crate::gpu::compile::kernel::KernelConfig;
use crate::gpu::compile::shader::Entry;
use crate::gpu::GpuError;
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

/// Overrides the cache folder (tests, or a user who wants it elsewhere).
pub const CACHE_DIR_VAR: &str = "GLINT_CACHE_DIR";
/// `off` turns the cache off; `on` (or unset) keeps it on.
pub const CACHE_SWITCH_VAR: &str = "GLINT_PIPELINE_CACHE";

/// The first bytes of every cache file.
pub const MAGIC: [u8; 8] = *b"GLINTPC\n";
/// Bumped whenever the header's layout changes; other versions are ignored.
pub const FORMAT_VERSION: u32 = 1;
/// magic, format version, key length (u32), payload length (u64), SHA-256.
pub const HEADER_LEN: usize = 8 + 4 + 4 + 8 + 32;

/// Why a cache file was ignored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rejection {
    /// Shorter than its header says (an interrupted copy, a full disk).
    Truncated,
    /// Not a glint cache file, or one of another format version.
    NotACacheFile,
    /// The checksum does not match, or bytes follow the payload.
    Corrupt,
    /// A valid file whose key is not this adapter's, driver's or kernel's.
    Foreign,
    /// It exists but could not be read.
    Unreadable,
    /// A FIFO, device, socket or folder (or a link to one): never opened for reading
    /// in a way that could block or never end.
    NotAFile,
    /// Larger than any cache file ([`MAX_FILE_BYTES`]): not read.
    TooBig,
}

impl std::fmt::Display for Rejection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Rejection::Truncated => "truncated",
            Rejection::NotACacheFile => "not a glint pipeline cache file of this format",
            Rejection::Corrupt => "corrupt (checksum mismatch)",
            Rejection::Foreign => "made for another adapter, driver or kernel",
            Rejection::Unreadable => "unreadable",
            Rejection::NotAFile => "not a regular file",
            Rejection::TooBig => "larger than any pipeline cache file",
        })
    }
}

/// What the on-disk pipeline cache did for one pipeline.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DiskOutcome {
    /// Off (`GLINT_PIPELINE_CACHE=off`, or no cache folder).
    #[default]
    Off,
    /// The device has no `PIPELINE_CACHE` feature (not Vulkan): nothing read or written.
    Unsupported,
    /// No file yet: compiled, and the driver's data written.
    Written,
    /// A valid file for this adapter, driver and kernel was handed to the driver; nothing
    /// written.
    Reused,
    /// A file was there but failed a check; ignored (never handed to the driver) and
    /// rewritten.
    Rejected(Rejection),
    /// The file could not be written (the note on stderr says why).
    WriteFailed,
}

/// One context's on-disk cache: its folder (None: off) and its adapter's part of the key.
#[derive(Clone, Debug)]
pub struct DiskCache {
    dir: Option<PathBuf>,
    adapter_key: String,
}

/// Set once a note about the cache has been printed: at most one per process.
static NOTED: AtomicBool = AtomicBool::new(false);

fn note_once(message: impl FnOnce() -> String) {
    if !NOTED.swap(true, Ordering::Relaxed) {
        eprintln!(
            "glint: note: {}",
            crate::display_path::for_terminal(&message())
        );
    }
}

/// The user's cache folder for glint, from the environment (None: no home to put it in).
pub fn default_dir() -> Option<PathBuf> {
    let var = |name: &str| std::env::var_os(name).filter(|v| !v.is_empty());
    if let Some(dir) = var(CACHE_DIR_VAR) {
        return Some(PathBuf::from(dir));
    }
    // The XDG spec: a relative XDG_CACHE_HOME is invalid and ignored.
    if let Some(xdg) = var("XDG_CACHE_HOME").map(PathBuf::from) {
        if xdg.is_absolute() {
            return Some(xdg.join("glint"));
        }
    }
    if let Some(home) = var("HOME") {
        return Some(PathBuf::from(home).join(".cache").join("glint"));
    }
    var("LOCALAPPDATA").map(|d| PathBuf::from(d).join("glint"))
}

/// The adapter's and driver's part of every key, and glint's version.
fn adapter_key(info: &wgpu::AdapterInfo) -> String {
    format!(
        "glint {}\nadapter: {}; backend {:?}; type {:?}; vendor 0x{:04x}; device 0x{:04x}\ndriver: {}; {}\n",
        env!("CARGO_PKG_VERSION"),
        info.name,
        info.backend,
        info.device_type,
        info.vendor,
        info.device,
        info.driver,
        info.driver_info,
    )
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Whether [`CACHE_SWITCH_VAR`] holds a value glint takes (unset, `on` or `off`): the
/// command line checks it before anything runs, so that a bad value is a usage error
/// (exit code 2) and not a failed render.
pub fn check_switch() -> Result<(), GpuError> {
    let switch = std::env::var_os(CACHE_SWITCH_VAR).unwrap_or_default();
    match switch.to_str() {
        Some("" | "on" | "off") => Ok(()),
        _ => Err(GpuError::Setting {
            var: CACHE_SWITCH_VAR,
            value: switch.to_string_lossy().into_owned(),
            expected: "on or off",
        }),
    }
}

impl DiskCache {
    /// No cache: nothing read or written.
    pub fn off() -> DiskCache {
        DiskCache {
            dir: None,
            adapter_key: String::new(),
        }
    }

    /// A cache in `dir` for pipelines compiled on the adapter of `info`.
    pub fn at(dir: impl Into<PathBuf>, info: &wgpu::AdapterInfo) -> DiskCache {
        DiskCache {
            dir: Some(dir.into()),
            adapter_key: adapter_key(info),
        }
    }

    /// The cache the environment asks for ([`CACHE_SWITCH_VAR`], [`default_dir`]); a
    /// value of the switch other than `on` or `off` is an error naming it.
    pub fn from_env(info: &wgpu::AdapterInfo) -> Result<DiskCache, GpuError> {
        check_switch()?;
        let switch = std::env::var_os(CACHE_SWITCH_VAR).unwrap_or_default();
        if switch == "off" {
            return Ok(DiskCache::off());
        }
        Ok(match default_dir() {
            Some(dir) => DiskCache::at(dir, info),
            None => DiskCache::off(),
        })
    }

    /// The folder, None when off.
    pub fn dir(&self) -> Option<&Path> {
        self.dir.as_deref()
    }

    /// The full key of a kernel: the adapter's part, then the kernel's.
    fn key(&self, source: &str, kernel: KernelConfig, entry: Entry) -> String {
        let wgsl = hex(&Sha256::digest(source.as_bytes()));
        format!(
            "{}kernel: {}; {kernel:?}; wgsl sha256 {wgsl}\n",
            self.adapter_key,
            entry.name()
        )
    }

    /// The cache for one pipeline about to be compiled on `device`: its file read and
    /// checked, and a `wgpu::PipelineCache` made from it (empty when the file is missing
    /// or fails a check).
    pub(crate) fn open(
        &self,
        device: &wgpu::Device,
        info: &wgpu::AdapterInfo,
        source: &str,
        kernel: KernelConfig,
        entry: Entry,
    ) -> StoredPipeline {
        let Some(dir) = &self.dir else {
            return StoredPipeline::none(DiskOutcome::Off);
        };
        let supported = device.features().contains(wgpu::Features::PIPELINE_CACHE)
            && wgpu::util::pipeline_cache_key(info).is_some();
        if !supported {
            return StoredPipeline::none(DiskOutcome::Unsupported);
        }
        let key = self.key(source, kernel, entry);
        let name = hex(&Sha256::digest(key.as_bytes())[..16]);
        let path = dir.join(format!("{}-{name}.bin", entry.name()));
        let (payload, state) = match read_file(&path, &key) {
            Ok(None) => (None, DiskOutcome::Written),
            Ok(Some(payload)) => (Some(payload), DiskOutcome::Reused),
            Err(why) => (None, DiskOutcome::Rejected(why)),
        };
        if let DiskOutcome::Rejected(why) = state {
            note_once(|| {
                format!(
                    "ignored the pipeline cache file {} ({why}); it is rewritten",
                    crate::display_path::shown(&path)
                )
            });
        }
        // SAFETY: `payload` is only ever bytes that `get_data` returned on an adapter
        // and driver of this key, checked against their checksum; `fallback` makes wgpu
        // (and the driver, which checks its own header) start empty on anything else.
        let cache = unsafe {
            device.create_pipeline_cache(&wgpu::PipelineCacheDescriptor {
                label: Some("glint pipeline cache"),
                data: payload.as_deref(),
                fallback: true,
            })
        };
        StoredPipeline {
            cache: Some(cache),
            path: Some(path),
            key,
            state,
        }
    }

    /// After the pipeline is compiled: writes the driver's data unless a valid file was
    /// used; returns what was done.
    pub(crate) fn keep(&self, stored: &StoredPipeline) -> DiskOutcome {
        let (Some(cache), Some(path)) = (&stored.cache, &stored.path) else {
            return stored.state;
        };
        if stored.state == DiskOutcome::Reused {
            return DiskOutcome::Reused;
        }
        let Some(payload) = cache.get_data() else {
            return DiskOutcome::Unsupported;
        };
        match write_file(path, &stored.key, &payload) {
            Ok(()) => stored.state,
            Err(e) => {
                note_once(|| {
                    format!(
                        "cannot write the pipeline cache file {}: {e}; compiled pipelines are not kept ({CACHE_SWITCH_VAR}=off silences this)",
                        crate::display_path::shown(path)
                    )
                });
                DiskOutcome::WriteFailed
            }
        }
    }
}

/// One pipeline's cache while it compiles: pass `cache()` in its descriptor.
pub(crate) struct StoredPipeline {
    cache: Option<wgpu::PipelineCache>,
    path: Option<PathBuf>,
    key: String,
    /// What `keep` will report if it writes nothing else.
    state: DiskOutcome,
}

impl StoredPipeline {
    fn none(state: DiskOutcome) -> StoredPipeline {
        StoredPipeline {
            cache: None,
            path: None,
            key: String::new(),
            state,
        }
    }

    /// The `cache` of the pipeline descriptor.
    pub(crate) fn cache(&self) -> Option<&wgpu::PipelineCache> {
        self.cache.as_ref()
    }
}

/// The file's bytes for `key` and `payload`: header, key, payload.
pub fn encode(key: &str, payload: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER_LEN + key.len() + payload.len());
    out.extend_from_slice(&MAGIC);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    out.extend_from_slice(&(key.len() as u32).to_le_bytes());
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    let sum = checksum(&out[8..], key.as_bytes(), payload);
    out.extend_from_slice(&sum);
    out.extend_from_slice(key.as_bytes());
    out.extend_from_slice(payload);
    out
}

/// SHA-256 of the header's fields after the magic, the key and the payload.
fn checksum(fields: &[u8], key: &[u8], payload: &[u8]) -> [u8; 32] {
    let mut hash = Sha256::new();
    hash.update(fields);
    hash.update(key);
    hash.update(payload);
    hash.finalize().into()
}

/// The payload of a file's `bytes`, if they are whole, unaltered and for `key`.
pub fn parse<'a>(bytes: &'a [u8], key: &str) -> Result<&'a [u8], Rejection> {
    if bytes.len() < HEADER_LEN {
        return Err(if MAGIC.starts_with(&bytes[..bytes.len().min(8)]) {
            Rejection::Truncated
        } else {
            Rejection::NotACacheFile
        });
    }
    let total = header_total(&bytes[..HEADER_LEN])?;
    let key_len = u64::from(u32::from_le_bytes(
        bytes[12..16].try_into().unwrap_or([0; 4]),
    ));
    let len = bytes.len() as u64;
    if len < total {
        return Err(Rejection::Truncated);
    }
    if len > total {
        return Err(Rejection::Corrupt);
    }
    let stored_key = &bytes[HEADER_LEN..HEADER_LEN + key_len as usize];
    let payload = &bytes[HEADER_LEN + key_len as usize..];
    if checksum(&bytes[8..24], stored_key, payload)[..] != bytes[24..HEADER_LEN] {
        return Err(Rejection::Corrupt);
    }
    if stored_key != key.as_bytes() {
        return Err(Rejection::Foreign);
    }
    Ok(payload)
}

/// The payload of the cache file at `path` for `key` (None: there is none), read as
/// every reader of glint reads ([`crate::scene::files::open_checked`]): a FIFO, device
/// or link to one, or a file over [`MAX_FILE_BYTES`], is refused without blocking or
/// reading it; the header is read and checked against the file's size before the rest,
/// so a large file that is not a cache file costs its first bytes only.
pub fn read_file(path: &Path, key: &str) -> Result<Option<Vec<u8>>, Rejection> {
    use crate::scene::files::{open_checked, Refusal};
    use std::io::Read;
    let (file, len) = match open_checked(path, MAX_FILE_BYTES) {
        Ok(opened) => opened,
        Err(Refusal::Io(e)) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(Refusal::Io(_)) => return Err(Rejection::Unreadable),
        Err(Refusal::NotRegular) => return Err(Rejection::NotAFile),
        Err(Refusal::TooBig(_)) => return Err(Rejection::TooBig),
    };
    let mut bytes = Vec::new();
    let mut reader = file.take(MAX_FILE_BYTES + 1);
    (&mut reader)
        .take(HEADER_LEN as u64)
        .read_to_end(&mut bytes)
        .map_err(|_| Rejection::Unreadable)?;
    if bytes.len() == HEADER_LEN {
        // The lengths the header claims against the file's: nothing more is read from
        // a file that cannot be whole.
        let claimed = header_total(&bytes)?;
        if claimed != len {
            return Err(if claimed > len {
                Rejection::Truncated
            } else {
                Rejection::Corrupt
            });
        }
        reader
            .read_to_end(&mut bytes)
            .map_err(|_| Rejection::Unreadable)?;
    }
    parse(&bytes, key).map(|payload| Some(payload.to_vec()))
}

/// Largest cache file read: a driver's data for one pipeline is kilobytes to a few
/// megabytes.
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// The whole length a file's header claims (header, key and payload), if the header is
/// a glint cache file's of this format.
fn header_total(header: &[u8]) -> Result<u64, Rejection> {
    let word = |at: usize| u32::from_le_bytes(header[at..at + 4].try_into().unwrap_or([0; 4]));
    if header[..8] != MAGIC || word(8) != FORMAT_VERSION {
        return Err(Rejection::NotACacheFile);
    }
    let key_len = u64::from(word(12));
    let payload_len = u64::from_le_bytes(header[16..24].try_into().unwrap_or([0; 8]));
    (HEADER_LEN as u64)
        .checked_add(key_len)
        .and_then(|n| n.checked_add(payload_len))
        .ok_or(Rejection::Corrupt)
}

/// Writes the file whole under a temporary name and renames it over `path`.
fn write_file(path: &Path, key: &str, payload: &[u8]) -> std::io::Result<()> {
    use std::io::Write;
    if let Some(dir) = path.parent() {
        crate::atomic_write::create_dir_all_clearly(dir)?;
    }
    let bytes = encode(key, payload);
    crate::atomic_write::write_via_temp(path, |file| file.write_all(&bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    const KEY: &str = "glint test\nkernel: main\n";

    #[test]
    fn a_whole_file_reads_back_its_payload() {
        let bytes = encode(KEY, b"driver data");
        assert_eq!(parse(&bytes, KEY), Ok(&b"driver data"[..]));
        assert_eq!(parse(&encode(KEY, b""), KEY), Ok(&b""[..]));
    }

    #[test]
    fn every_damaged_file_is_refused() {
        let bytes = encode(KEY, b"driver data");
        for cut in [0, 5, HEADER_LEN - 1, HEADER_LEN, bytes.len() - 1] {
            let want = if cut == 0 || cut >= 8 || MAGIC.starts_with(&bytes[..cut]) {
                Rejection::Truncated
            } else {
                Rejection::NotACacheFile
            };
            assert_eq!(parse(&bytes[..cut], KEY), Err(want), "cut at {cut}");
        }
        // Every single flipped bit is caught (in the magic or version as not a cache
        // file, in a length as truncated or corrupt, anywhere else by the checksum).
        for at in 0..bytes.len() {
            let mut bad = bytes.clone();
            bad[at] ^= 0x10;
            assert!(parse(&bad, KEY).is_err(), "byte {at} flipped was accepted");
        }
        let mut longer = bytes.clone();
        longer.push(0);
        assert_eq!(parse(&longer, KEY), Err(Rejection::Corrupt));
        assert_eq!(parse(b"PNG....", KEY), Err(Rejection::NotACacheFile));
    }

    /// Files that are not what they seem are refused without blocking, and without
    /// reading more than a header of a file that cannot be whole.
    #[test]
    fn cache_files_are_read_as_they_really_are() {
        let dir = crate::testing::scratch::temp_dir("cache-files");
        let path = |name: &str| dir.join(name);
        assert_eq!(read_file(&path("missing.bin"), KEY), Ok(None));
        std::fs::write(path("good.bin"), encode(KEY, b"driver data")).unwrap();
        assert_eq!(
            read_file(&path("good.bin"), KEY),
            Ok(Some(b"driver data".to_vec()))
        );
        let fifo = std::ffi::CString::new(path("fifo.bin").to_str().unwrap()).unwrap();
        // SAFETY: a valid NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o600) }, 0);
        assert_eq!(read_file(&path("fifo.bin"), KEY), Err(Rejection::NotAFile));
        std::os::unix::fs::symlink("/dev/zero", path("zero.bin")).unwrap();
        assert_eq!(read_file(&path("zero.bin"), KEY), Err(Rejection::NotAFile));
        // Sparse: 2 GiB, and 60 MiB whose header claims 40 bytes of key and payload.
        let sized = |name: &str, len: u64, head: &[u8]| {
            std::fs::write(path(name), head).unwrap();
            let file = std::fs::OpenOptions::new()
                .write(true)
                .open(path(name))
                .unwrap();
            file.set_len(len).unwrap();
        };
        sized("huge.bin", 2 << 30, b"");
        assert_eq!(read_file(&path("huge.bin"), KEY), Err(Rejection::TooBig));
        sized("long.bin", 60 << 20, &encode(KEY, b"driver data"));
        assert_eq!(read_file(&path("long.bin"), KEY), Err(Rejection::Corrupt));
        sized(
            "other.bin",
            60 << 20,
            b"not a cache file at all, just bytes, many of them",
        );
        assert_eq!(
            read_file(&path("other.bin"), KEY),
            Err(Rejection::NotACacheFile)
        );
    }

    #[test]
    fn a_valid_file_for_another_key_is_foreign() {
        let bytes = encode("glint test\nkernel: probe\n", b"driver data");
        assert_eq!(parse(&bytes, KEY), Err(Rejection::Foreign));
    }

    #[test]
    fn the_key_names_adapter_driver_and_kernel() {
        let mut info = wgpu::AdapterInfo::new(wgpu::DeviceType::Cpu, wgpu::Backend::Vulkan);
        info.name = "llvmpipe".into();
        info.vendor = 0x10005;
        info.driver = "llvmpipe".into();
        info.driver_info = "Mesa 22.3.6".into();
        let cache = DiskCache::at("/nonexistent", &info);
        let a = cache.key("fn a() {}", KernelConfig::default(), Entry::Render);
        assert!(a.contains("llvmpipe") && a.contains("Mesa 22.3.6") && a.contains("0x10005"));
        assert!(a.contains(env!("CARGO_PKG_VERSION")) && a.contains("kernel: main"));
        let b = cache.key("fn b() {}", KernelConfig::default(), Entry::Render);
        let c = cache.key("fn a() {}", KernelConfig::default(), Entry::Probe);
        let other = KernelConfig {
            workgroup_side: 4,
            ..KernelConfig::default()
        };
        let d = cache.key("fn a() {}", other, Entry::Render);
        assert!(a != b && a != c && a != d && b != c);
    }
}
