//! The GPU tracer: a WGSL mirror of [`crate::tracer`] (`shaders/*.wgsl`), specialised per
//! scene feature set and run on wgpu (Vulkan, Metal or DX12) in whole-frame passes. Device acquisition
//! ([`GpuContext`]) is separate from the work ([`render_gpu`]) so tests pass their own.

pub mod bindings;
pub mod buffers;
pub mod context;
pub mod disk_cache;
pub mod dump;
pub mod error;
pub mod frame;
pub mod kernel;
pub mod lists;
pub mod pipeline;
pub mod pipeline_cache;
pub mod plan;
pub mod progressive;
pub mod render;
pub mod scratch;
pub mod shader;
pub mod spirv;
pub mod tables;
pub mod view_wavefront;
pub mod wavefront;

pub use context::{list_adapters, AdapterSummary, GpuContext};
pub use error::GpuError;
pub use kernel::{KernelConfig, KernelVariant};
pub use render::{render_gpu, GpuRender, GpuRenderInfo, GpuRenderOptions, PassTime};
