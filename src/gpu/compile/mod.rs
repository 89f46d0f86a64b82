//! What a kernel is compiled from: the kernel variant chosen for an adapter, the WGSL
//! module assembled and specialised per feature set and variant (`shader`), the binding
//! numbers it declares, the per-ray lists' layout (with its WGSL, `lists.wgsl`, beside)
//! and the SPIR-V a driver is handed.

pub mod bindings;
pub mod kernel;
pub mod lists;
pub mod shader;
pub mod spirv;
