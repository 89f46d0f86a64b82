//! The device: a context on an adapter ([`context::GpuContext`]) and what it keeps
//! between renders: its compiled pipelines in memory and on disk, the kernels it dumps
//! (`--dump-kernels`) and the frame buffers it reuses.

pub mod context;
pub mod disk_cache;
pub mod dump;
pub mod pipeline_cache;
pub mod scratch;
