//! The per-context cache of compiled pipelines (`PipelineCache`, held by `GpuContext`)
//! and what it stores (`CompiledPipeline`); `pipeline` compiles and fills it.

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
    /// Whether the render kernels check Mesa's loop limiter (software adapters).
    pub iteration_guard: bool,
}

/// Pipelines compiled on one device, by (features, entry); whether the iteration guard
/// is in is a property of the device.
#[derive(Default)]
pub struct PipelineCache {
    pub(super) map: Mutex<HashMap<(SceneFeatures, Entry), Arc<CompiledPipeline>>>,
}
