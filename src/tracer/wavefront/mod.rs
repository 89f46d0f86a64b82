//! The wavefront form of `path`'s tracing: a batch of camera samples in passes over
//! queues (chains; trees where dielectrics branch; adaptive AA's lattice through them);
//! built on `sampling` and below.

pub mod queues;
// The chain's passes keep the name of their WGSL twin, wavefront.wgsl, beside them.
#[allow(clippy::module_inception)]
pub mod wavefront;
pub mod wavefront_lattice;
pub mod wavefront_tree;
