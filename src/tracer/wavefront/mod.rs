//! The wavefront form of `path`'s tracing: a batch of camera samples in passes over
//! queues (chains; trees where dielectrics branch; adaptive AA's lattice through them);
//! built on `sampling` and below. Each pass is a file beside its WGSL twin: the batch
//! and its queues' entries (`batch`), the camera and closest passes and the generation
//! loop (`wavefront`), the shade, shadow and gather passes, the tree's pieces
//! (`wavefront_tree`) and adaptive AA's lattice (`wavefront_lattice`); the queues'
//! specification (`queues`), with what is generated from it in `queues/`.

pub mod batch;
pub mod queues;
// The camera and closest passes keep the name of their WGSL twin, wavefront.wgsl, beside them.
#[allow(clippy::module_inception)]
pub mod wavefront;
pub mod wavefront_gather;
pub mod wavefront_lattice;
pub mod wavefront_shade;
pub mod wavefront_shadow;
pub mod wavefront_tree;
