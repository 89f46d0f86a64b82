//! The tracer, both sides of it: each `X.rs` here is the CPU reference and the `X.wgsl`
//! beside it its WGSL mirror on the GPU (see each function's twin comment); the two
//! follow the same steps with the same constants, in f32. The folders are the tracer's
//! layers, each using only those before it: `base` (numbers, rays, random numbers),
//! `geometry` (intersection and surface parameterisation), `traversal` (grids and
//! nearest hits), `shading` (surfaces, lights, dielectrics, textures), `path` (a camera
//! sample's rays), `sampling` (pixels, tiles and anti-aliasing) and `wavefront` (the
//! same paths in passes over queues).

pub mod base;
pub mod geometry;
pub mod path;
pub mod sampling;
pub mod shading;
pub mod traversal;
pub mod wavefront;

pub use sampling::render::{render, RenderProgress};
