//! The GPU tracer: a WGSL mirror of [`crate::cpu`] (`shaders/*.wgsl`), specialised per
//! scene feature set and run on wgpu (Vulkan, Metal or DX12) in whole-frame passes. Device acquisition
//! ([`GpuContext`]) is separate from the work ([`render_gpu`]) so tests pass their own.

pub mod bindings;
pub mod buffers;
pub mod context;
pub mod error;
pub mod frame;
pub mod pipeline;
pub mod pipeline_cache;
pub mod plan;
// Crate-visible so `testing` can re-export its test hook `render_gpu_detailed`.
pub(crate) mod render;
pub mod shader;

pub use context::{list_adapters, AdapterSummary, GpuContext};
pub use error::GpuError;
pub use render::{adaptive_leaf_counts_gpu, render_gpu, render_gpu_with_info, GpuRenderInfo};
