//! The per-context cache of compiled pipelines (`PipelineCache`, held by `GpuContext`)
//! and what it stores (`CompiledPipeline`); `pipeline` compiles and fills it.

use crate::gpu::compile::kernel::KernelConfig;
use crate::gpu::compile::shader::Entry;
pub use crate::gpu::device::disk_cache::DiskOutcome;
use crate::pack::SceneFeatures;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// A compiled pipeline and what it cost.
pub struct CompiledPipeline {
    pub pipeline: wgpu::ComputePipeline,
    pub layout: wgpu::BindGroupLayout,
    /// WGSL assembly, naga validation, shader module and pipeline creation.
    pub compile_time: Duration,
    /// `compile_time` step by step, and what the on-disk cache did.
    pub steps: CompileSteps,
    pub features: SceneFeatures,
    /// The kernel variant (workgroup size, mailboxes, loop-limiter guard).
    pub kernel: KernelConfig,
}

/// Where compile time went, step by step: one pipeline's ([`CompileSteps`]) or the sum
/// over several ([`CompileSummary`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CompileTimes {
    /// Assembling the specialised WGSL.
    pub assemble: Duration,
    /// glint's own naga parse and validation (for errors that point into the source).
    pub validate: Duration,
    /// Reading and checking the cache file, and `create_pipeline_cache`.
    pub cache_load: Duration,
    /// `create_shader_module`: wgpu parses and validates the WGSL again.
    pub shader_module: Duration,
    /// `create_compute_pipeline`: naga writes the backend's code (SPIR-V) and the
    /// driver compiles it.
    pub pipeline: Duration,
    /// `get_data` and writing the cache file.
    pub cache_store: Duration,
}

impl std::ops::AddAssign for CompileTimes {
    fn add_assign(&mut self, other: CompileTimes) {
        self.assemble += other.assemble;
        self.validate += other.validate;
        self.cache_load += other.cache_load;
        self.shader_module += other.shader_module;
        self.pipeline += other.pipeline;
        self.cache_store += other.cache_store;
    }
}

/// Where a pipeline's compile time went (`--stats` prints the sums), and what the
/// on-disk cache of [`crate::gpu::device::disk_cache`] did for it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CompileSteps {
    pub times: CompileTimes,
    pub disk: DiskOutcome,
}

/// The steps of several pipelines' compiles summed, and what the on-disk cache did for
/// them (for `--stats`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CompileSummary {
    pub times: CompileTimes,
    /// Pipelines whose driver data came from a cache file.
    pub reused: u32,
    /// Pipelines whose data was written to a new file.
    pub written: u32,
    /// Pipelines whose file failed a check (ignored and rewritten).
    pub rejected: u32,
    /// Pipelines with no cache: off, unsupported, or not writable.
    pub uncached: u32,
}

impl CompileSummary {
    pub fn of<'a>(steps: impl IntoIterator<Item = &'a CompileSteps>) -> CompileSummary {
        let mut sum = CompileSummary::default();
        for s in steps {
            sum.times += s.times;
            match s.disk {
                DiskOutcome::Reused => sum.reused += 1,
                DiskOutcome::Written => sum.written += 1,
                DiskOutcome::Rejected(_) => sum.rejected += 1,
                DiskOutcome::Off | DiskOutcome::Unsupported | DiskOutcome::WriteFailed => {
                    sum.uncached += 1
                }
            }
        }
        sum
    }
}

/// Times the steps of a compile one after another.
pub(crate) struct Lap(Instant);

impl Lap {
    pub(crate) fn start() -> Lap {
        Lap(Instant::now())
    }

    /// Time since the start or the last `next`.
    pub(crate) fn next(&mut self) -> Duration {
        let now = Instant::now();
        std::mem::replace(&mut self.0, now).elapsed()
    }
}

/// Pipelines compiled on one device, by (features, kernel variant, entry), and their
/// shader modules by WGSL source (several entries share one module).
#[derive(Default)]
pub struct PipelineCache {
    pub(crate) map: Mutex<HashMap<PipelineKey, Arc<CompiledPipeline>>>,
    pub(crate) modules: Mutex<HashMap<String, wgpu::ShaderModule>>,
}

/// What a compiled pipeline is specialised for.
pub type PipelineKey = (SceneFeatures, KernelConfig, Entry);
