//! What the host puts on the device for a scene: its packed arrays as tables (textures)
//! and its globals as a uniform, checked against the adapter's limits.

pub mod buffers;
pub mod tables;
