//! Device acquisition, kept apart from the work so tests (and the CLI) can make one
//! [`GpuContext`] and pass it to every render (wgpu's `execute_gpu_inner` pattern).
//! Backends: wgpu's primary ones — Vulkan, Metal, DX12 (each compiled in where its
//! platform has it) — unless `WGPU_BACKEND` names others; never GL by default: with no
//! Vulkan driver wgpu would silently pick GL llvmpipe, whose output differs.

use crate::gpu::compile::kernel::{KernelConfig, KernelVariant};
use crate::gpu::device::disk_cache::DiskCache;
use crate::gpu::device::pipeline_cache::PipelineCache;
use crate::gpu::GpuError;
use std::sync::{Arc, Mutex};

/// The environment variable that sets llvmpipe's (lavapipe's) worker threads.
pub const LLVMPIPE_THREADS_VAR: &str = "LP_NUM_THREADS";

/// Worker threads glint asks llvmpipe for where the user has not set
/// [`LLVMPIPE_THREADS_VAR`]: four per core up to 16 (Mesa 22's cap), and never fewer than
/// the cores (Mesa caps the value itself). Mesa's default is one per core, and a dispatch then ends when the thread with the slowest
/// workgroups does while the other cores idle (on this project's 2 cores, 13% between
/// the two threads' work on macho-cows); with more threads than cores the operating
/// system balances them: 5–20% less GPU time on the mesh scenes (docs/journal/2026-11-29-gpu-kernel-variant-measured.md). Only
/// llvmpipe reads the variable.
pub fn default_llvmpipe_threads(cores: usize) -> usize {
    (4 * cores).min(16).max(cores).max(1)
}

/// Sets [`LLVMPIPE_THREADS_VAR`] to [`default_llvmpipe_threads`] unless it is set.
///
/// # Safety
/// Changes the process environment: call it before any other thread runs (glibc's
/// `setenv` is not safe beside a concurrent `getenv`), and before the first GPU instance
/// is made (Mesa reads the variable when its driver starts).
pub unsafe fn set_default_llvmpipe_threads() {
    if std::env::var_os(LLVMPIPE_THREADS_VAR).is_none() {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        // SAFETY: the caller's contract above.
        unsafe {
            std::env::set_var(
                LLVMPIPE_THREADS_VAR,
                default_llvmpipe_threads(cores).to_string(),
            )
        };
    }
}

/// llvmpipe's worker threads, as `glint info` and `glint bench --gpu` say it.
pub fn llvmpipe_threads_line() -> String {
    let var = LLVMPIPE_THREADS_VAR;
    match std::env::var(var) {
        Ok(n) => format!("llvmpipe worker threads: {n} ({var})"),
        Err(_) => format!("llvmpipe worker threads: one per core ({var} unset)"),
    }
}

/// A device and queue on one adapter, plus the pipelines compiled on it so far.
pub struct GpuContext {
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub info: wgpu::AdapterInfo,
    pub limits: wgpu::Limits,
    /// The shader variant compiled on this device, chosen from the adapter
    /// ([`KernelConfig::for_adapter`]); benchmarks may change it before rendering (the
    /// pipeline cache is keyed by it).
    pub kernel: KernelConfig,
    /// Set by the device-lost callback; checked after every wait.
    pub(crate) lost: Arc<Mutex<Option<String>>>,
    pub(crate) pipelines: PipelineCache,
    /// Compiled pipelines kept across runs (`crate::gpu::device::disk_cache`).
    pub(crate) disk_cache: DiskCache,
    /// Frame buffers kept between frames (`crate::gpu::device::scratch`).
    pub(crate) scratch: crate::gpu::device::scratch::ScratchPool,
    /// `--dump-kernels`: where each pipeline compiled on it is written (`crate::gpu::device::dump`).
    pub dump: Option<crate::gpu::device::dump::KernelDump>,
}

/// One adapter, as `glint info` lists it.
#[derive(Clone, Debug)]
pub struct AdapterSummary {
    pub name: String,
    pub backend: String,
    pub device_type: String,
    pub driver: String,
    pub max_storage_buffer_binding_size: u64,
    pub max_storage_buffers_per_shader_stage: u32,
    pub max_compute_invocations_per_workgroup: u32,
    pub max_compute_workgroups_per_dimension: u32,
    pub max_buffer_size: u64,
    /// Rows (and most columns) of a 2-D texture: the scene's tables are 4 096 texels wide
    /// and at most this many rows (`gpu::upload::tables`).
    pub max_texture_dimension_2d: u32,
    /// The kernel variant glint would compile on it.
    pub kernel: KernelConfig,
}

/// Vulkan, Metal and DX12, or the backends `WGPU_BACKEND` names.
pub fn backends() -> wgpu::Backends {
    wgpu::Backends::from_env()
        .unwrap_or(wgpu::Backends::VULKAN | wgpu::Backends::METAL | wgpu::Backends::DX12)
}

/// The instance on [`backends`].
fn instance() -> wgpu::Instance {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    desc.backends = backends();
    wgpu::Instance::new(desc)
}

/// Every adapter on the enabled backends.
pub fn list_adapters() -> Vec<AdapterSummary> {
    let instance = instance();
    pollster::block_on(instance.enumerate_adapters(backends()))
        .iter()
        .map(|a| {
            let info = a.get_info();
            let l = a.limits();
            AdapterSummary {
                name: info.name,
                backend: format!("{:?}", info.backend),
                device_type: format!("{:?}", info.device_type),
                driver: format!("{} {}", info.driver, info.driver_info)
                    .trim()
                    .to_string(),
                max_storage_buffer_binding_size: l.max_storage_buffer_binding_size,
                max_storage_buffers_per_shader_stage: l.max_storage_buffers_per_shader_stage,
                max_compute_invocations_per_workgroup: l.max_compute_invocations_per_workgroup,
                max_compute_workgroups_per_dimension: l.max_compute_workgroups_per_dimension,
                max_buffer_size: l.max_buffer_size,
                max_texture_dimension_2d: l.max_texture_dimension_2d,
                kernel: KernelConfig::for_adapter(info.device_type, &l),
            }
        })
        .collect()
}

impl GpuContext {
    /// Compiles `variant`'s kernels from now on instead of the adapter's choice
    /// (`--kernel-variant`, for `render` and `view` alike), with this adapter's limits.
    pub fn force_kernel_variant(&mut self, variant: KernelVariant) {
        self.kernel = KernelConfig::for_variant(variant, &self.limits);
    }

    /// Bytes of frame buffers kept for the next frame (`crate::gpu::device::scratch`).
    pub fn kept_frame_bytes(&self) -> u64 {
        self.scratch.kept_bytes()
    }

    /// A device on the first adapter whose name contains `adapter_name` (any case), or on
    /// the default adapter when None; with the adapter's own limits (wgpu's defaults are
    /// lower than what lavapipe and real GPUs offer).
    pub fn new(adapter_name: Option<&str>) -> Result<GpuContext, GpuError> {
        let instance = instance();
        let adapters = pollster::block_on(instance.enumerate_adapters(backends()));
        let names: Vec<String> = adapters.iter().map(|a| a.get_info().name).collect();
        let adapter = match adapter_name {
            Some(wanted) => {
                let lower = wanted.to_lowercase();
                adapters
                    .into_iter()
                    .find(|a| a.get_info().name.to_lowercase().contains(&lower))
            }
            None => pollster::block_on(
                instance.request_adapter(&wgpu::RequestAdapterOptions::default()),
            )
            .ok(),
        };
        let adapter = adapter.ok_or_else(|| GpuError::NoAdapter {
            wanted: adapter_name.map(str::to_string),
            available: names,
        })?;
        Self::from_adapter(adapter)
    }

    /// The on-disk pipeline cache this context reads and writes.
    pub fn disk_cache(&self) -> &DiskCache {
        &self.disk_cache
    }

    /// Replaces the on-disk pipeline cache (the environment's by default); pipelines
    /// already compiled on this context are not compiled again.
    pub fn set_disk_cache(&mut self, cache: DiskCache) {
        self.disk_cache = cache;
    }

    /// A device on `adapter`, with timestamp queries where the adapter has them (for the
    /// frame's GPU time) and pipeline caches where it has them (`crate::gpu::device::disk_cache`).
    pub fn from_adapter(adapter: wgpu::Adapter) -> Result<GpuContext, GpuError> {
        let info = adapter.get_info();
        let limits = adapter.limits();
        let disk_cache = DiskCache::from_env(&info)?;
        let features =
            adapter.features() & (wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::PIPELINE_CACHE);
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("glint"),
            required_features: features,
            required_limits: limits.clone(),
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|e| GpuError::RequestDevice {
            adapter: info.name.clone(),
            message: e.to_string(),
        })?;
        let lost = Arc::new(Mutex::new(None));
        let lost_in_callback = Arc::clone(&lost);
        device.set_device_lost_callback(move |reason, message| {
            if let Ok(mut slot) = lost_in_callback.lock() {
                *slot = Some(format!("{reason:?}: {message}"));
            }
        });
        Ok(GpuContext {
            adapter,
            device,
            queue,
            kernel: KernelConfig::for_adapter(info.device_type, &limits),
            info,
            limits,
            lost,
            pipelines: PipelineCache::default(),
            disk_cache,
            scratch: Default::default(),
            dump: None,
        })
    }

    /// Waits for all submitted work; a device loss or poll failure becomes an error.
    pub fn wait(&self) -> Result<(), GpuError> {
        let polled = self.device.poll(wgpu::PollType::wait_indefinitely());
        if let Some(reason) = self.lost.lock().ok().and_then(|l| l.clone()) {
            return Err(GpuError::DeviceLost(reason));
        }
        polled.map(|_| ()).map_err(|e| GpuError::Wgpu {
            what: "wait",
            message: e.to_string(),
        })
    }

    /// Waits for submission `index` (and earlier ones); a device loss or poll failure
    /// becomes an error.
    pub(crate) fn wait_for(&self, index: wgpu::SubmissionIndex) -> Result<(), GpuError> {
        let polled = self.device.poll(wgpu::PollType::Wait {
            submission_index: Some(index),
            timeout: None,
        });
        if let Some(reason) = self.lost.lock().ok().and_then(|l| l.clone()) {
            return Err(GpuError::DeviceLost(reason));
        }
        polled.map(|_| ()).map_err(|e| GpuError::Wgpu {
            what: "wait",
            message: e.to_string(),
        })
    }

    /// Runs `f` inside a validation + out-of-memory error scope, returning its value or
    /// the first error wgpu reported.
    pub(crate) fn scoped<T>(
        &self,
        what: &'static str,
        f: impl FnOnce() -> T,
    ) -> Result<T, GpuError> {
        let oom = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let value = f();
        let errors = [
            pollster::block_on(validation.pop()),
            pollster::block_on(oom.pop()),
        ];
        match errors.into_iter().flatten().next() {
            Some(e) => Err(GpuError::Wgpu {
                what,
                message: e.to_string(),
            }),
            None => Ok(value),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::default_llvmpipe_threads;

    #[test]
    fn four_llvmpipe_threads_a_core_up_to_llvmpipes_cap() {
        assert_eq!(default_llvmpipe_threads(1), 4);
        assert_eq!(default_llvmpipe_threads(2), 8);
        assert_eq!(default_llvmpipe_threads(4), 16);
        assert_eq!(default_llvmpipe_threads(8), 16);
        // Never fewer than Mesa's own default, one per core.
        assert_eq!(default_llvmpipe_threads(64), 64);
        assert_eq!(default_llvmpipe_threads(0), 1);
    }
}
