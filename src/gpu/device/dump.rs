//! `glint render --dump-kernels DIR`: every pipeline a render creates, written as it is
//! compiled — `ENTRY.wgsl` (the assembled module wgpu is given) and `ENTRY.spv` (the
//! SPIR-V wgpu 30 hands a Vulkan driver for that entry, rebuilt by [`crate::gpu::compile::spirv`]).
//! A later pipeline of the same entry (another `gr.render` of the script with other
//! features) is written as `ENTRY-2.*`, `ENTRY-3.*`…; a pipeline already compiled on the
//! context is not compiled, nor written, again.

use crate::gpu::compile::shader::Entry;
use crate::gpu::compile::spirv::{spirv_bytes, wgsl_to_spirv, SpirvTarget};
use crate::gpu::GpuError;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Where a context writes the kernels it compiles, and how many of each entry so far.
#[derive(Debug)]
pub struct KernelDump {
    dir: PathBuf,
    written: Mutex<HashMap<&'static str, u32>>,
}

impl KernelDump {
    /// A dump into `dir`, created if missing.
    pub fn new(dir: &Path) -> Result<KernelDump, GpuError> {
        crate::atomic_write::create_dir_all_clearly(dir).map_err(|e| GpuError::Dump {
            path: crate::display_path::shown(dir),
            message: e.to_string(),
        })?;
        Ok(KernelDump {
            dir: dir.to_path_buf(),
            written: Mutex::new(HashMap::new()),
        })
    }

    /// The file stem of the next pipeline of `entry`: `main`, then `main-2`…
    fn next_stem(&self, entry: Entry) -> String {
        let mut written = self.written.lock().unwrap_or_else(|e| e.into_inner());
        let count = written.entry(entry.name()).or_insert(0);
        *count += 1;
        match *count {
            1 => entry.name().to_string(),
            n => format!("{}-{n}", entry.name()),
        }
    }
}

/// Writes `bytes` to `path` through a temporary file beside it
/// ([`crate::atomic_write`]), so that a failed write leaves no half-written kernel.
fn write_whole(path: &Path, bytes: &[u8]) -> Result<(), GpuError> {
    let fail = |e: std::io::Error| GpuError::Dump {
        path: crate::display_path::shown(path),
        message: e.to_string(),
    };
    use std::io::Write;
    crate::atomic_write::write_via_temp_with(path, fail, |file| file.write_all(bytes).map_err(fail))
}

/// Writes one kernel as `STEM.wgsl` and `STEM.spv` in `dir`.
pub fn write_kernel(
    dir: &Path,
    stem: &str,
    source: &str,
    entry: Entry,
    layout: &[wgpu::BindGroupLayoutEntry],
    target: SpirvTarget,
) -> Result<(), GpuError> {
    let words =
        wgsl_to_spirv(source, entry, layout, target).map_err(|message| GpuError::Shader {
            features: format!("{entry:?}"),
            message,
        })?;
    write_whole(&dir.join(format!("{stem}.wgsl")), source.as_bytes())?;
    write_whole(&dir.join(format!("{stem}.spv")), &spirv_bytes(&words))
}

/// `get_pipeline`'s hook: writes the kernel about to be compiled (`entry` of `source`,
/// bound as `layout`) when its context dumps (`dump` is set).
pub fn dump_kernel(
    dump: Option<&KernelDump>,
    entry: Entry,
    source: &str,
    layout: &[wgpu::BindGroupLayoutEntry],
) -> Result<(), GpuError> {
    let Some(dump) = dump else {
        return Ok(());
    };
    let stem = dump.next_stem(entry);
    let target = SpirvTarget::vulkan_1_3();
    write_kernel(&dump.dir, &stem, source, entry, layout, target)
}
