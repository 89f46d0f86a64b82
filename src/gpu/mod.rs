//! The GPU tracer: the WGSL beside [`crate::tracer`]'s Rust (`src/tracer/*/X.wgsl`),
//! specialised per scene feature set and run on wgpu (Vulkan, Metal or DX12) in
//! whole-frame passes. The host side by concern, each folder using only those before
//! it: `compile` (what a kernel is compiled from: the kernel variant, the assembled
//! WGSL, the bindings it declares, the per-ray lists' layout, its SPIR-V), `device` (the
//! context on an adapter, with its pipeline caches and frame buffers), `upload` (the
//! scene's tables and uniforms), `plan` (a frame's chunks and dispatches, a file a form),
//! and after them `pipeline` (compute pipelines), `frame` (a frame's buffers and
//! encoding), `wavefront` (which renders run the wavefront kernels), `render` (a frame's
//! submits) and `view` (`glint view`'s frames). Device acquisition ([`GpuContext`]) is
//! separate from the work ([`render_gpu`]) so tests pass their own.

pub mod compile;
pub mod device;
pub mod error;
pub mod frame;
pub mod pipeline;
pub mod plan;
pub mod render;
pub mod upload;
pub mod view;
pub mod wavefront;

pub use compile::kernel::{KernelConfig, KernelVariant};
pub use device::context::{list_adapters, AdapterSummary, GpuContext};
pub use error::GpuError;
pub use render::{render_gpu, GpuRender, GpuRenderInfo, GpuRenderOptions, PassTime};
