//! The per-context cache of compiled pipelines (`PipelineCache`, held by `GpuContext`)
//! and what it stores (`CompiledPipeline`); `pipeline` compiles and fills it.

use super::kernel::KernelConfig;
use super::shader::Entry;
use crate::pack::SceneFeatures;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// A compiled pipeline and what it cost.
pub struct CompiledPipeline {
    pub pipeline: wgpu::ComputePipeline,
    pub layout: wgpu::BindGroupLayout,
    /// WGSL assembly, naga validation, shader module and pipeline creation.
    pub compile_time: Duration,
    pub features: SceneFeatures,
    /// The kernel variant (workgroup size, mailboxes, loop-limiter guard).
    pub kernel: KernelConfig,
}

/// Pipelines compiled on one device, by (features, kernel variant, entry).
#[derive(Default)]
pub struct PipelineCache {
    pub(super) map: Mutex<HashMap<PipelineKey, Arc<CompiledPipeline>>>,
}

/// What a compiled pipeline is specialised for.
pub type PipelineKey = (SceneFeatures, KernelConfig, Entry);
